// What the process holds and what the machine can give: resident set sizes for the reports, and the
// up-front estimate that refuses a scene the machine cannot hold.
#ifndef scenevis_tool_Memory_h
#define scenevis_tool_Memory_h

#include <cstdint>
#include <string>

namespace scenevis
{
namespace tool
{

/// Resident set size now and at its peak (VmRSS, VmHWM of /proc/self/status), in bytes; 0 where
/// the system does not say.
struct ResidentMemory
{
  std::uint64_t current = 0;
  std::uint64_t peak = 0;
};
ResidentMemory ReadResidentMemory();

/// Bytes a new allocation can get without swapping or the OOM killer: MemAvailable of
/// /proc/meminfo, lowered to the cgroup's memory.max minus its usage when a limit is set; 0 when
/// unknown. SCENEVIS_MEMORY_LIMIT (bytes, or with a K/M/G suffix) replaces it, for tests and for
/// users who share the machine.
std::uint64_t AvailableMemory();

/// The element counts a .vtp file's header declares (summed over its pieces), read without
/// loading the file; all 0 when @p path is not a readable XML PolyData file.
struct VtpHeader
{
  std::uint64_t points = 0;
  std::uint64_t polys = 0;
  bool valid = false;
};
VtpHeader ReadVtpHeader(const std::string& path);

/// "3.1 GB", "850 MB", "12 kB": decimal units, 2-3 significant digits.
std::string FormatBytes(std::uint64_t bytes);

} // namespace tool
} // namespace scenevis

#endif

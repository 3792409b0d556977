// Transparent huge pages for the tool's heap: big models fault in memory 2 MB at a time.
#ifndef scenevis_tool_HugePages_h
#define scenevis_tool_HugePages_h

#include <cstdint>

namespace scenevis
{
namespace tool
{

/// Scene files from this size on (and demo scenes from kBigDemoTriangles on) run in huge pages.
constexpr std::uint64_t kBigSceneBytes = 64ull << 20;
constexpr long kBigDemoTriangles = 4000000;

/**
 * Whether this run should use huge pages: always with SCENEVIS_HUGE_PAGES=1, never with
 * SCENEVIS_HUGE_PAGES=0, else (auto) when the command line's --scene names a file of at least
 * kBigSceneBytes or its --triangles asks for at least kBigDemoTriangles. Running again costs
 * about 0.35 s here (VTK's libraries are loaded twice), which only big scenes win back.
 */
bool WantsHugePages(int argc, char* argv[]);

/**
 * When WantsHugePages(), runs the tool again, once, with glibc's malloc asking for transparent
 * huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1, glibc 2.35 and later; an existing
 * GLIBC_TUNABLES keeps its other settings), unless the environment already asks for them.
 * Returns only when it does not run again (not wanted, /proc/self/exe cannot be run, ...).
 *
 * Why: a tunable is read when the process starts, and a big model's setup is dominated by first
 * touches of fresh memory. On the 48.6M-triangle engine grid (BENCHMARKS.md, "Memory and page
 * faults") 4 KB pages cost 2.1M page faults and 30 s of system time before the first frame;
 * 2 MB pages 22,000 faults: first frame 93 s -> 28 s as parts, 97 s -> 47 s as one mesh, the
 * same peak memory. Where the kernel has transparent huge pages off ("never"), glibc's request
 * changes nothing. The report's first_frame_ms counts from the second start.
 */
void RerunWithHugePages(int argc, char* argv[]);

/// Whether this process's malloc asks for transparent huge pages (its GLIBC_TUNABLES sets
/// glibc.malloc.hugetlb to 1 or 2), as the render report states it.
bool HugePageMalloc();

} // namespace tool
} // namespace scenevis

#endif

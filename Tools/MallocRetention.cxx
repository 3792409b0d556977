#include "MallocRetention.h"

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace scenevis
{
namespace tool
{
namespace
{
bool gKept = false;
} // namespace

bool KeepFreedMemory()
{
#if defined(__GLIBC__)
  const char* on = std::getenv("SCENEVIS_KEEP_FREED_MEMORY");
  if (!on || std::strcmp(on, "1") != 0)
  {
    return false; // opt-in: see the header on the planner's rule
  }
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables &&
    (std::strstr(tunables, "glibc.malloc.trim_threshold") ||
      std::strstr(tunables, "glibc.malloc.mmap_threshold")))
  {
    return false;
  }
  gKept = mallopt(M_TRIM_THRESHOLD, 1 << 30) == 1 && mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1;
#endif
  return gKept;
}

bool KeepsFreedMemory()
{
  return gKept;
}

} // namespace tool
} // namespace scenevis

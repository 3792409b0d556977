#include "HugePages.h"

#include <cstdlib>
#include <cstring>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace scenevis
{
namespace tool
{

bool WantsHugePages(int argc, char* argv[])
{
  if (const char* choice = std::getenv("SCENEVIS_HUGE_PAGES"))
  {
    if (std::strcmp(choice, "0") == 0)
      return false;
    if (std::strcmp(choice, "1") == 0)
      return true;
  }
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--scene") == 0)
    {
      struct stat info;
      if (::stat(argv[i + 1], &info) == 0 &&
        static_cast<std::uint64_t>(info.st_size) >= kBigSceneBytes)
        return true;
    }
    else if (std::strcmp(argv[i], "--triangles") == 0 &&
      std::strtol(argv[i + 1], nullptr, 10) >= kBigDemoTriangles)
    {
      return true;
    }
  }
  return false;
}

void RerunWithHugePages(int argc, char* argv[])
{
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::string value = tunables ? tunables : "";
  if (value.find("glibc.malloc.hugetlb") != std::string::npos || !WantsHugePages(argc, argv))
    return; // asked for already (by us, or by the user either way), or not worth a second start
  value += (value.empty() ? "" : ":") + std::string("glibc.malloc.hugetlb=1");
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0)
    return;
  execv("/proc/self/exe", argv);
  // Not run again (no /proc, a sandbox that forbids exec): go on with normal pages, and leave
  // the environment as it was for the programs this one starts.
  if (tunables)
    setenv("GLIBC_TUNABLES", tunables, 1);
  else
    unsetenv("GLIBC_TUNABLES");
}

bool HugePageMalloc()
{
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (!tunables)
    return false;
  const std::string value = tunables;
  return value.find("glibc.malloc.hugetlb=1") != std::string::npos ||
    value.find("glibc.malloc.hugetlb=2") != std::string::npos;
}

} // namespace tool
} // namespace scenevis

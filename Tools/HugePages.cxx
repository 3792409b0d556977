#include "HugePages.h"

#include <cstdlib>
#include <cstring>
#include <string>

#include <unistd.h>

namespace scenevis
{
namespace tool
{

void RerunWithHugePages(char* argv[])
{
  const char* optOut = std::getenv("SCENEVIS_HUGE_PAGES");
  if (optOut && std::strcmp(optOut, "0") == 0)
    return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::string value = tunables ? tunables : "";
  if (value.find("glibc.malloc.hugetlb") != std::string::npos)
    return; // asked for already (by us, or by the user either way)
  value += (value.empty() ? "" : ":") + std::string("glibc.malloc.hugetlb=1");
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0)
    return;
  execv("/proc/self/exe", argv);
  // Not re-run (no /proc, a sandbox that forbids exec): go on with normal pages, and leave the
  // environment as it was for the programs this one starts.
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

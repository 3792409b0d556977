// Transparent huge pages for the tool's heap: big models fault in memory 2 MB at a time.
#ifndef scenevis_tool_HugePages_h
#define scenevis_tool_HugePages_h

namespace scenevis
{
namespace tool
{

/**
 * Runs the tool again, once, with glibc's malloc asking for transparent huge pages
 * (GLIBC_TUNABLES=glibc.malloc.hugetlb=1, glibc 2.35 and later; an existing GLIBC_TUNABLES keeps
 * its other settings), unless the environment already asks for it or SCENEVIS_HUGE_PAGES=0.
 * Returns only when it does not re-run (the variable is set, /proc/self/exe cannot be run, ...).
 *
 * Why: a tunable is read when the process starts, and a big model's setup is dominated by first
 * touches of fresh memory. On the 48.6M-triangle engine grid (BENCHMARKS.md, "48.6M triangles
 * from file to frames") 4 KB pages cost 2.1M page faults and 30 s of system time before the first
 * frame; 2 MB pages 22,000 faults: first frame 93 s -> 28 s as parts, 97 s -> 47 s as one mesh,
 * the same peak memory. Where the kernel has transparent huge pages off ("never"), glibc's request
 * changes nothing.
 */
void RerunWithHugePages(char* argv[]);

/// Whether this process's malloc asks for transparent huge pages (its GLIBC_TUNABLES sets
/// glibc.malloc.hugetlb to 1 or 2), as the render report states it.
bool HugePageMalloc();

} // namespace tool
} // namespace scenevis

#endif

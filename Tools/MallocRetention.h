// Freed heap memory kept for reuse: per-frame allocations stop faulting in fresh pages.
#ifndef scenevis_tool_MallocRetention_h
#define scenevis_tool_MallocRetention_h

namespace scenevis
{
namespace tool
{

/**
 * Sets glibc's malloc to keep freed memory for reuse instead of giving it back to the kernel:
 * trim threshold 1 GiB (the heap's top is not returned after each big free) and a fixed mmap
 * threshold of 32 MiB (blocks up to that size come from the heap, not from a fresh mapping each
 * time). Not applied with SCENEVIS_KEEP_FREED_MEMORY=0, nor when GLIBC_TUNABLES already sets
 * either threshold (the user's choice stands). Returns whether it applied them.
 *
 * Why: Mesa's llvmpipe allocates and frees its vertex and bin buffers at every draw. With glibc's
 * defaults a big free at the top of the heap is trimmed (or a big block unmapped) and the next
 * frame faults the same memory in again, 4 KB at a time. On the 2CylinderEngine as 115 translucent
 * parts in one batch (multi-actor pass, 640x480, BENCHMARKS.md "Freed memory kept") that made the
 * frames 2-3.5x slower than with the memory kept; the one-mesh mapper was not affected. The cost:
 * memory freed stays in the process (rss_end), the peak is the same.
 */
bool KeepFreedMemory();

/// Whether KeepFreedMemory() applied the thresholds in this process (for the report).
bool KeepsFreedMemory();

} // namespace tool
} // namespace scenevis

#endif

// Freed heap memory kept for reuse (opt-in): per-frame allocations stop faulting in fresh pages.
#ifndef scenevis_tool_MallocRetention_h
#define scenevis_tool_MallocRetention_h

namespace scenevis
{
namespace tool
{

/**
 * With SCENEVIS_KEEP_FREED_MEMORY=1, sets glibc's malloc to keep freed memory for reuse instead of
 * giving it back to the kernel: trim threshold 1 GiB (the heap's top is not returned after each
 * big free) and a fixed mmap threshold of 32 MiB (blocks up to that size come from the heap, not
 * from a fresh mapping each time). Not applied otherwise, nor when GLIBC_TUNABLES already sets
 * either threshold (the user's choice stands). Returns whether it applied them.
 *
 * Why: Mesa's llvmpipe allocates and frees its vertex buffers in every draw call. With glibc's
 * defaults a big free at the top of the heap is trimmed and the next frame faults the same memory
 * in again, 4 KB at a time. On the 2CylinderEngine (640x480, BENCHMARKS.md "Freed memory kept")
 * `render` frames were 1.4-3.3x faster with the memory kept; the one-mesh BSP mapper on the cad
 * demo 3.4x (78 -> 23 ms). The cost: memory freed stays in the process, the peak grows by up to
 * 18 %.
 *
 * Why opt-in: the big draws of one mesh suffer most from the churn, so keeping memory changes
 * which method is fastest. The planner's rule (vtkScenePlanRule) was measured with glibc's
 * defaults, which is what a VTK program runs with; with memory kept, auto's split of the cad demo
 * into parts is 2.2x the one-mesh mapper. On by default it needs the rule measured again.
 */
bool KeepFreedMemory();

/// Whether KeepFreedMemory() applied the thresholds in this process (for the report).
bool KeepsFreedMemory();

} // namespace tool
} // namespace scenevis

#endif

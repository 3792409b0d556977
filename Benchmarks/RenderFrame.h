// One timed frame of a benchmark: Render() and then WaitForCompletion() (glFinish).
//
// Render() returns while llvmpipe's rasterizer thread may still be drawing (4 ms a frame on
// average on the soak's 2 x 2 engine grid): without the wait, that work is counted in the next
// frame, and a frame can overlap the previous one's rasterization, which mixes the costs of
// methods measured one after the other. The soak and the planner path bench wait so; the other
// benchmarks use this.
#ifndef scenevis_bench_RenderFrame_h
#define scenevis_bench_RenderFrame_h

#include <vtkRenderWindow.h>

namespace scenevis
{
namespace bench
{

/// Renders @p window and waits until the frame is drawn.
inline void RenderFrame(vtkRenderWindow* window)
{
  window->Render();
  window->WaitForCompletion();
}

} // namespace bench
} // namespace scenevis

#endif

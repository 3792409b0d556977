/**
 * @file RenderWindow.h
 * @brief Headless render windows for SceneVis tests, benchmarks and examples.
 *
 * The window factory and its self-check are SceneVis::RenderingHeadless's
 * (vtkSceneVisHeadlessWindows.h, what users link); this header brings them into
 * scenevis::testing and adds what only tests need.
 */
#ifndef scenevis_testing_RenderWindow_h
#define scenevis_testing_RenderWindow_h

#include <vtkSceneVisHeadlessWindows.h>

class vtkRenderer;

namespace scenevis
{
namespace testing
{

using headless::Backend;
using headless::BackendAvailable;
using headless::BackendName;
using headless::CaptureImage;
using headless::CheckRenderingWorks;
using headless::DefaultBackend;
using headless::DescribeContext;
using headless::MakeRenderWindow;
using headless::MakeUncheckedRenderWindow;

/// Exit code of a test that cannot run here (e.g. the X11 back-end without $DISPLAY). Register it
/// with the CTest property SKIP_RETURN_CODE.
constexpr int kSkipReturnCode = 77;

/**
 * Make translucent geometry of @p renderer blend in primitive order ("ordered alpha blending"):
 * installs a vtkRenderStepsPass, whose translucent step is the plain vtkTranslucentPass. Without
 * it VTK 9.1 uses weighted-average OIT (when depth peeling is off), which ignores primitive order.
 * Depth peeling must stay off (it would also ignore the order).
 */
void EnableOrderedAlphaBlending(vtkRenderer* renderer);

} // namespace testing
} // namespace scenevis

#endif

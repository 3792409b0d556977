/**
 * @file RenderWindow.h
 * @brief Headless render windows for SceneVis tests, tools and examples.
 *
 * Two back-ends render the same images on this platform (Mesa llvmpipe):
 *  - Backend::OSMesa (default): an OSMesa context owned by the window; needs no X server.
 *  - Backend::X11: VTK's ordinary vtkXOpenGLRenderWindow, offscreen; needs $DISPLAY (e.g. Xvfb).
 *
 * The back-end of MakeRenderWindow(width, height) is chosen by the environment variable
 * SCENEVIS_BACKEND=osmesa|x11 (default osmesa).
 *
 * Every window returned by the factory has MSAA off (with depth peeling on llvmpipe, MSAA silently
 * drops all translucent geometry) and has passed CheckRenderingWorks(), so a broken setup (link
 * order, missing context) fails at creation with a message instead of producing black images.
 *
 * This library is for tests/tools/examples only; never link it into the plugin modules.
 * Link requirement: libOSMesa must precede libGL/libOpenGL on the link line; linking the CMake
 * target SceneVis::Testing arranges that (see Testing/Harness/CMakeLists.txt).
 */
#ifndef scenevis_testing_RenderWindow_h
#define scenevis_testing_RenderWindow_h

#include <vtkSmartPointer.h>

#include <string>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;

namespace scenevis
{
namespace testing
{

/// Exit code of a test that cannot run here (e.g. the X11 back-end without $DISPLAY). Register it
/// with the CTest property SKIP_RETURN_CODE.
constexpr int kSkipReturnCode = 77;

enum class Backend
{
  OSMesa, ///< Off-screen Mesa context owned by the window; no X server needed.
  X11     ///< VTK's GLX window rendering offscreen; needs $DISPLAY.
};

/// "osmesa" or "x11".
const char* BackendName(Backend backend);

/// The back-end named by $SCENEVIS_BACKEND (osmesa|x11, case-insensitive); OSMesa when unset.
/// Throws std::runtime_error for an unknown name (a typo must not silently pick another back-end).
Backend DefaultBackend();

/// Whether @p backend can run in this process; when not, @p why (if given) says why.
/// X11 needs $DISPLAY; OSMesa is always available.
bool BackendAvailable(Backend backend, std::string* why = nullptr);

/**
 * Create an offscreen render window of @p width x @p height pixels with MSAA off, alpha bit planes
 * on and no renderer, then run CheckRenderingWorks() on it.
 * @throws std::runtime_error when the back-end is unavailable or the self-check fails; the
 *         message names the likely cause.
 * The OSMesa context lives exactly as long as the returned window; windows may be created and
 * destroyed sequentially in one process. Do not interleave rendering of OSMesa and X11 windows
 * that are alive at the same time (GLEW's function pointers are process-global and re-initialised
 * per context).
 */
vtkSmartPointer<vtkRenderWindow> MakeRenderWindow(Backend backend, int width, int height);

/// MakeRenderWindow(DefaultBackend(), width, height).
vtkSmartPointer<vtkRenderWindow> MakeRenderWindow(int width, int height);

/// Like MakeRenderWindow() but without the self-check (for the test of the self-check itself).
vtkSmartPointer<vtkRenderWindow> MakeUncheckedRenderWindow(Backend backend, int width, int height);

/**
 * Self-check against silently black renders: renders a red opaque quad that fills the view in a
 * temporary renderer, reads the pixels back and compares them with the expected red.
 * The window's renderers are left as they were.
 * @return an empty string when rendering works, else a message naming the likely cause (libGL or
 *         libOpenGL before libOSMesa in the link order, MSAA on, no current context, ...).
 */
std::string CheckRenderingWorks(vtkRenderWindow* window);

/**
 * Make translucent geometry of @p renderer blend in primitive order ("ordered alpha blending"):
 * installs a vtkRenderStepsPass, whose translucent step is the plain vtkTranslucentPass. Without
 * it VTK 9.1 uses weighted-average OIT (when depth peeling is off), which ignores primitive order.
 * Depth peeling must stay off (it would also ignore the order).
 */
void EnableOrderedAlphaBlending(vtkRenderer* renderer);

/**
 * Render the window and read its colour buffer back as an RGB (or RGBA) unsigned-char image of
 * the window size, origin at the bottom-left like VTK.
 */
vtkSmartPointer<vtkImageData> CaptureImage(vtkRenderWindow* window, bool withAlpha = false);

/// The OpenGL vendor/renderer/version text of a window that has rendered once (for reports).
std::string DescribeContext(vtkRenderWindow* window);

} // namespace testing
} // namespace scenevis

#endif

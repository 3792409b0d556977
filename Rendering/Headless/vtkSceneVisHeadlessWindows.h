/**
 * @file    vtkSceneVisHeadlessWindows.h
 * @brief   Offscreen render windows that are checked to render: the factory behind the scenevis
 *          tool, the tests and users' own offscreen regression renders.
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
 * @code
 * // CMake: target_link_libraries(app PRIVATE SceneVis::RenderingHeadless)
 * vtkSmartPointer<vtkRenderWindow> window = scenevis::headless::MakeRenderWindow(640, 480);
 * window->AddRenderer(renderer);
 * vtkSmartPointer<vtkImageData> image = scenevis::headless::CaptureImage(window);
 * scenevis::headless::WritePng(image, "frame.png"); // vtkSceneVisImageCompare.h
 * @endcode
 *
 * Link requirement: libOSMesa must precede libGL/libOpenGL among an executable's libraries, or
 * renders come out black. Linking the CMake target SceneVis::RenderingHeadless (from the build or
 * an install) arranges that through its link options (see Rendering/Headless/CMakeLists.txt);
 * MakeRenderWindow()'s self-check catches it if something else undoes it. Link the module into
 * executables only, never into a shared library (the GLX shim must be in the executable).
 *
 * Plain functions in namespace scenevis::headless (not wrapped for Python).
 *
 * @sa vtkSceneVisOSMesaRenderWindow vtkSceneVisImageCompare.h
 */
#ifndef vtkSceneVisHeadlessWindows_h
#define vtkSceneVisHeadlessWindows_h

#include "SceneVisRenderingHeadlessModule.h" // For export macro

#include <vtkSmartPointer.h> // For vtkSmartPointer

#include <string> // For std::string

class vtkImageData;
class vtkRenderWindow;

namespace scenevis
{
namespace headless
{

enum class Backend
{
  OSMesa, ///< Off-screen Mesa context owned by the window; no X server needed.
  X11     ///< VTK's GLX window rendering offscreen; needs $DISPLAY.
};

/// "osmesa" or "x11".
SCENEVISRENDERINGHEADLESS_EXPORT const char* BackendName(Backend backend);

/// The back-end named by $SCENEVIS_BACKEND (osmesa|x11, case-insensitive); OSMesa when unset.
/// Throws std::runtime_error for an unknown name (a typo must not silently pick another back-end).
SCENEVISRENDERINGHEADLESS_EXPORT Backend DefaultBackend();

/// Whether @p backend can run in this process; when not, @p why (if given) says why.
/// X11 needs $DISPLAY; OSMesa is always available.
SCENEVISRENDERINGHEADLESS_EXPORT bool BackendAvailable(Backend backend, std::string* why = nullptr);

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
SCENEVISRENDERINGHEADLESS_EXPORT vtkSmartPointer<vtkRenderWindow> MakeRenderWindow(
  Backend backend, int width, int height);

/// MakeRenderWindow(DefaultBackend(), width, height).
SCENEVISRENDERINGHEADLESS_EXPORT vtkSmartPointer<vtkRenderWindow> MakeRenderWindow(
  int width, int height);

/// Like MakeRenderWindow() but without the self-check (for the test of the self-check itself).
SCENEVISRENDERINGHEADLESS_EXPORT vtkSmartPointer<vtkRenderWindow> MakeUncheckedRenderWindow(
  Backend backend, int width, int height);

/**
 * Self-check against silently black renders: renders a red opaque quad that fills the view in a
 * temporary renderer, reads the pixels back and compares them with the expected red.
 * The window's renderers are left as they were.
 * @return an empty string when rendering works, else a message naming the likely cause (libGL or
 *         libOpenGL before libOSMesa in the link order, MSAA on, no current context, ...).
 */
SCENEVISRENDERINGHEADLESS_EXPORT std::string CheckRenderingWorks(vtkRenderWindow* window);

/**
 * Render the window and read its colour buffer back as an RGB (or RGBA) unsigned-char image of
 * the window size, origin at the bottom-left like VTK.
 */
SCENEVISRENDERINGHEADLESS_EXPORT vtkSmartPointer<vtkImageData> CaptureImage(
  vtkRenderWindow* window, bool withAlpha = false);

/// The OpenGL vendor/renderer/version text of a window that has rendered once (for reports).
SCENEVISRENDERINGHEADLESS_EXPORT std::string DescribeContext(vtkRenderWindow* window);

} // namespace headless
} // namespace scenevis

#endif

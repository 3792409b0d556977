/**
 * @class vtkSceneVisOSMesaRenderWindow
 * @brief A vtkGenericOpenGLRenderWindow that owns an OSMesa context and its colour buffer.
 *
 * Renders without any X server or GPU (Mesa's llvmpipe), for offscreen regression renders in CI:
 * @code
 * vtkNew<vtkSceneVisOSMesaRenderWindow> window;
 * window->SetSize(400, 300);
 * std::string error;
 * if (!window->CreateContext(&error)) { std::cerr << error; return 1; }
 * window->AddRenderer(renderer);
 * window->Render(); // then vtkWindowToImageFilter, GetPixelData, ...
 * @endcode
 * MSAA is off (with depth peeling on llvmpipe, MSAA silently drops translucent geometry).
 *
 * Linking: this module is a static library; link the CMake target SceneVis::RenderingHeadless
 * into the EXECUTABLE. Its usage requirements put libOSMesa first among the executable's
 * libraries (otherwise VTK's direct OpenGL 1.1 calls go to glvnd and every frame is silently
 * black) and export the GLX shim of OSMesaContext.cxx from the executable (VTK 9.1's GLEW asks
 * GLX for every entry point). CheckLinkOrder() says whether that worked.
 *
 * The context is created by CreateContext() and destroyed with the window (after VTK released its
 * graphics resources with the context current), so windows can be created and destroyed one after
 * another in a process without leaking contexts. MakeCurrent() binds the context to the window's
 * own RGBA8 buffer, whose size always equals the window size (SetSize reallocates it).
 */
#ifndef vtkSceneVisOSMesaRenderWindow_h
#define vtkSceneVisOSMesaRenderWindow_h

#include "SceneVisRenderingHeadlessModule.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"

#include <string> // For std::string
#include <vector> // For std::vector

class SCENEVISRENDERINGHEADLESS_EXPORT vtkSceneVisOSMesaRenderWindow
  : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkSceneVisOSMesaRenderWindow* New();
  vtkTypeMacro(vtkSceneVisOSMesaRenderWindow, vtkGenericOpenGLRenderWindow);

  /// Create the OSMesa context (once). Returns false and fills @p error on failure.
  bool CreateContext(std::string* error);

  /// Bind the context to this window's buffer (no-op when there is no context).
  void MakeCurrent() override;
  bool IsCurrent() override;
  void ReleaseCurrent() override;
  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;

  /**
   * Diagnoses the link order of the running process: "" when the process-wide glClear (which VTK
   * calls directly, without GLEW) resolves to libOSMesa, else an explanation of why renders will
   * be black and how to link.
   */
  static std::string CheckLinkOrder();

  /// Resizes the OSMesa buffer along with the window.
  void SetSize(int width, int height) override;
  using Superclass::SetSize;

protected:
  vtkSceneVisOSMesaRenderWindow();
  ~vtkSceneVisOSMesaRenderWindow() override;

private:
  vtkSceneVisOSMesaRenderWindow(const vtkSceneVisOSMesaRenderWindow&) = delete;
  void operator=(const vtkSceneVisOSMesaRenderWindow&) = delete;

  void* Context = nullptr;
  std::vector<unsigned char> Buffer; // RGBA8, Size[0] x Size[1]
};

#endif

/**
 * @class vtkSceneVisOSMesaRenderWindow
 * @brief A vtkGenericOpenGLRenderWindow that owns an OSMesa context and its colour buffer.
 *
 * Use scenevis::testing::MakeRenderWindow(Backend::OSMesa, w, h) rather than this class directly:
 * the factory also turns MSAA off and runs the rendering self-check.
 *
 * The context is created by CreateContext() and destroyed with the window (after VTK released its
 * graphics resources with the context current), so windows can be created and destroyed one after
 * another in a process without leaking contexts. MakeCurrent() binds the context to the window's
 * own RGBA8 buffer, whose size always equals the window size (SetSize reallocates it).
 */
#ifndef vtkSceneVisOSMesaRenderWindow_h
#define vtkSceneVisOSMesaRenderWindow_h

#include <vtkGenericOpenGLRenderWindow.h>

#include <string>
#include <vector>

class vtkSceneVisOSMesaRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkSceneVisOSMesaRenderWindow* New();
  vtkTypeMacro(vtkSceneVisOSMesaRenderWindow, vtkGenericOpenGLRenderWindow)

    /// Create the OSMesa context (once). Returns false and fills @p error on failure.
    bool CreateContext(std::string* error);

  /// Bind the context to this window's buffer (no-op when there is no context).
  void MakeCurrent() override;
  bool IsCurrent() override;
  void ReleaseCurrent() override;
  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;

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

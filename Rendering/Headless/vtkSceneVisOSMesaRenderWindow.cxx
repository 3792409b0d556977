#include "vtkSceneVisOSMesaRenderWindow.h"

#include "OSMesaContext.h"

#include "vtkAutoInit.h"
#include "vtkObjectFactory.h"

#include <algorithm>

// The window is drawn into by vtkRenderer, vtkPolyDataMapper, ... made through VTK's object
// factories: an executable that links this window gets the OpenGL2 overrides without its own
// vtk_module_autoinit().
VTK_MODULE_INIT(vtkRenderingOpenGL2);

vtkStandardNewMacro(vtkSceneVisOSMesaRenderWindow);

vtkSceneVisOSMesaRenderWindow::vtkSceneVisOSMesaRenderWindow()
{
  // The generic window asks observers whether it is current/ready; this subclass answers itself.
  this->SetReadyForRendering(true);
  this->SetIsDirect(1);
  this->SetSupportsOpenGL(1);
  this->SetScreenSize(4096, 4096);
  this->SetMultiSamples(0);
}

vtkSceneVisOSMesaRenderWindow::~vtkSceneVisOSMesaRenderWindow()
{
  if (this->Context)
  {
    // VTK's buffers, shaders and textures must be freed while our context is current; the base
    // destructor's Finalize() cannot do it because it runs after this class is gone (its virtual
    // MakeCurrent() no longer reaches ours).
    this->MakeCurrent();
    this->ReleaseGraphicsResources(this);
    scenevis::headless::DestroyOSMesaContext(this->Context);
    this->Context = nullptr;
  }
  this->SetReadyForRendering(false);
}

bool vtkSceneVisOSMesaRenderWindow::CreateContext(std::string* error)
{
  if (!this->Context)
  {
    this->Context = scenevis::headless::CreateOSMesaContext(error);
  }
  if (this->Context)
  {
    this->MakeCurrent();
    this->SetIsCurrent(this->IsCurrent());
  }
  return this->Context != nullptr;
}

void vtkSceneVisOSMesaRenderWindow::MakeCurrent()
{
  if (!this->Context)
  {
    return;
  }
  const int width = std::max(1, this->Size[0]);
  const int height = std::max(1, this->Size[1]);
  const size_t bytes = static_cast<size_t>(width) * static_cast<size_t>(height) * 4;
  if (this->Buffer.size() != bytes)
  {
    this->Buffer.assign(bytes, 0);
  }
  else if (this->IsCurrent())
  {
    return;
  }
  scenevis::headless::MakeOSMesaCurrent(this->Context, this->Buffer.data(), width, height);
}

bool vtkSceneVisOSMesaRenderWindow::IsCurrent()
{
  return scenevis::headless::IsOSMesaCurrent(this->Context);
}

void vtkSceneVisOSMesaRenderWindow::ReleaseCurrent()
{
  if (this->IsCurrent())
  {
    scenevis::headless::ReleaseOSMesaCurrent();
  }
}

int vtkSceneVisOSMesaRenderWindow::SupportsOpenGL()
{
  return this->Context ? 1 : 0;
}

vtkTypeBool vtkSceneVisOSMesaRenderWindow::IsDirect()
{
  return this->Context ? 1 : 0;
}

std::string vtkSceneVisOSMesaRenderWindow::CheckLinkOrder()
{
  return scenevis::headless::CheckOSMesaSymbolOrder();
}

void vtkSceneVisOSMesaRenderWindow::SetSize(int width, int height)
{
  this->Superclass::SetSize(width, height);
  if (this->Context)
  {
    // Re-bind so that the OSMesa buffer (the default framebuffer) matches the window size.
    this->MakeCurrent();
  }
}

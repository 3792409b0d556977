#include "scenevis/testing/vtkSceneVisOSMesaRenderWindow.h"

#include "OSMesaContext.h"

#include <vtkObjectFactory.h>

#include <algorithm>

vtkStandardNewMacro(vtkSceneVisOSMesaRenderWindow)

  vtkSceneVisOSMesaRenderWindow::vtkSceneVisOSMesaRenderWindow()
{
  // The generic window asks observers whether it is current/ready; this subclass answers itself.
  this->SetReadyForRendering(true);
  this->SetIsDirect(1);
  this->SetSupportsOpenGL(1);
  this->SetScreenSize(4096, 4096);
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
    scenevis::testing::detail::DestroyOSMesaContext(this->Context);
    this->Context = nullptr;
  }
  this->SetReadyForRendering(false);
}

bool vtkSceneVisOSMesaRenderWindow::CreateContext(std::string* error)
{
  if (!this->Context)
  {
    this->Context = scenevis::testing::detail::CreateOSMesaContext(error);
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
  scenevis::testing::detail::MakeOSMesaCurrent(this->Context, this->Buffer.data(), width, height);
}

bool vtkSceneVisOSMesaRenderWindow::IsCurrent()
{
  return scenevis::testing::detail::IsOSMesaCurrent(this->Context);
}

void vtkSceneVisOSMesaRenderWindow::ReleaseCurrent()
{
  if (this->IsCurrent())
  {
    scenevis::testing::detail::ReleaseOSMesaCurrent();
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

void vtkSceneVisOSMesaRenderWindow::SetSize(int width, int height)
{
  this->Superclass::SetSize(width, height);
  if (this->Context)
  {
    // Re-bind so that the OSMesa buffer (the default framebuffer) matches the window size.
    this->MakeCurrent();
  }
}

#include "vtkOrderedTranslucentPass.h"

#include "vtkFXAAOptions.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFXAAFilter.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRenderState.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTranslucentPass.h"

/// Runs the translucent step, then FXAA on the renderer's viewport, as vtkOpenGLRenderer's own
/// geometry step does (vtkOpenGLRenderer::UpdateGeometry: "Apply FXAA before volumes and
/// overlays").
class vtkOrderedTranslucentPass::FXAAStep : public vtkRenderPass
{
public:
  static FXAAStep* New();
  vtkTypeMacro(FXAAStep, vtkRenderPass);

  vtkRenderPass* Translucent = nullptr; // not owned: the steps pass's TranslucentPass

  void Render(const vtkRenderState* s) override
  {
    this->NumberOfRenderedProps = 0;
    if (this->Translucent)
    {
      this->Translucent->Render(s);
      this->NumberOfRenderedProps = this->Translucent->GetNumberOfRenderedProps();
    }
    auto* renderer = vtkOpenGLRenderer::SafeDownCast(s->GetRenderer());
    if (!renderer)
    {
      return;
    }
    if (!this->Filter)
    {
      this->Filter = vtkSmartPointer<vtkOpenGLFXAAFilter>::New();
    }
    if (vtkFXAAOptions* options = renderer->GetFXAAOptions())
    {
      this->Filter->UpdateConfiguration(options);
    }
    this->Filter->Execute(renderer);
  }

  void ReleaseGraphicsResources(vtkWindow*) override
  {
    if (this->Filter)
    {
      this->Filter->ReleaseGraphicsResources();
    }
  }

protected:
  FXAAStep() = default;
  ~FXAAStep() override = default;

private:
  vtkSmartPointer<vtkOpenGLFXAAFilter> Filter;
};
vtkStandardNewMacro(vtkOrderedTranslucentPass::FXAAStep);

vtkStandardNewMacro(vtkOrderedTranslucentPass);

//------------------------------------------------------------------------------
vtkOrderedTranslucentPass::vtkOrderedTranslucentPass()
  : TranslucentThenFXAA(FXAAStep::New())
{
  // vtkRenderStepsPass already defaults to vtkTranslucentPass; set it explicitly so the
  // guarantee this class makes does not depend on that default.
  vtkNew<vtkTranslucentPass> translucent;
  this->SetTranslucentPass(translucent);
}

vtkOrderedTranslucentPass::~vtkOrderedTranslucentPass()
{
  this->TranslucentThenFXAA->Delete();
}

//------------------------------------------------------------------------------
void vtkOrderedTranslucentPass::Render(const vtkRenderState* s)
{
  vtkRenderer* renderer = s->GetRenderer();
  // Hardware selection draws ids, which FXAA would blend (vtkOpenGLRenderer skips it too).
  if (!renderer->GetUseFXAA() || renderer->GetSelector())
  {
    this->Superclass::Render(s);
    return;
  }
  // The steps are put in sequence from the members at every render: the translucent member is
  // the wrapper for this render only (no reference taken, no Modified()).
  vtkRenderPass* translucent = this->TranslucentPass;
  this->TranslucentThenFXAA->Translucent = translucent;
  this->TranslucentPass = this->TranslucentThenFXAA;
  this->Superclass::Render(s);
  this->TranslucentPass = translucent;
  this->TranslucentThenFXAA->Translucent = nullptr;
}

void vtkOrderedTranslucentPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Superclass::ReleaseGraphicsResources(w);
  this->TranslucentThenFXAA->ReleaseGraphicsResources(w);
}

//------------------------------------------------------------------------------
void vtkOrderedTranslucentPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}

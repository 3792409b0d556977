#include "vtkSceneVisRenderView.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPVSynchronizedRenderer.h"

vtkStandardNewMacro(vtkSceneVisRenderView);

vtkSceneVisRenderView::vtkSceneVisRenderView()
{
  vtkNew<vtkOrderedTranslucentPass> pass;
  this->SynchronizedRenderers->SetRenderPass(pass);
}

void vtkSceneVisRenderView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RenderPass: vtkOrderedTranslucentPass\n";
}

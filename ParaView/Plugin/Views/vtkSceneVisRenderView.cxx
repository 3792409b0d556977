#include "vtkSceneVisRenderView.h"

#include "vtkBSPTranslucentPass.h"
#include "vtkObjectFactory.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkTranslucentPass.h"

vtkStandardNewMacro(vtkSceneVisRenderView);

vtkSceneVisRenderView::vtkSceneVisRenderView()
  : Steps(vtkOrderedTranslucentPass::New())
  , SortingPass(vtkBSPTranslucentPass::New())
  , DrawingOrderPass(vtkTranslucentPass::New())
{
  this->Steps->SetTranslucentPass(this->SortingPass);
  this->SynchronizedRenderers->SetRenderPass(this->Steps);
}

vtkSceneVisRenderView::~vtkSceneVisRenderView()
{
  this->Steps->Delete();
  this->SortingPass->Delete();
  this->DrawingOrderPass->Delete();
}

void vtkSceneVisRenderView::SetSortTranslucentGeometry(bool sort)
{
  if (sort == this->SortTranslucentGeometry)
  {
    return;
  }
  this->SortTranslucentGeometry = sort;
  if (sort)
  {
    this->Steps->SetTranslucentPass(this->SortingPass);
  }
  else
  {
    this->Steps->SetTranslucentPass(this->DrawingOrderPass);
  }
  this->Modified();
}

void vtkSceneVisRenderView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SortTranslucentGeometry: " << this->SortTranslucentGeometry << "\n";
}

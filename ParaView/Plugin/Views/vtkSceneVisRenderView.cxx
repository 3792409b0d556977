#include "vtkSceneVisRenderView.h"

#include "vtkBSPTranslucentPass.h"
#include "vtkCullerCollection.h"
#include "vtkFrustumCoverageCuller.h"
#include "vtkObjectFactory.h"
#include "vtkOcclusionCuller.h"
#include "vtkOctreeCuller.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkRenderer.h"
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

//------------------------------------------------------------------------------
void vtkSceneVisRenderView::SetCulling(int mode)
{
  if (mode < CULLING_VTK || mode > CULLING_OCCLUSION)
  {
    vtkErrorMacro("Culling " << mode << " is not one of 0 (VTK), 1 (octree), 2 (occlusion).");
    return;
  }
  if (mode == this->Culling)
  {
    return;
  }
  vtkRenderer* renderer = this->GetRenderer();
  vtkCullerCollection* cullers = renderer->GetCullers();
  if (this->Culling == CULLING_VTK && !this->VTKCuller)
  {
    // Keep the renderer's own (a vtkFrustumCoverageCuller) to put it back.
    cullers->InitTraversal();
    this->VTKCuller = cullers->GetNextItem();
  }
  cullers->RemoveAllItems();
  vtkCuller* culler = this->VTKCuller;
  if (mode == CULLING_OCTREE)
  {
    if (!this->OctreeCuller)
    {
      this->OctreeCuller = vtkSmartPointer<vtkOctreeCuller>::New();
    }
    culler = this->OctreeCuller;
  }
  else if (mode == CULLING_OCCLUSION)
  {
    if (!this->OcclusionCuller)
    {
      this->OcclusionCuller = vtkSmartPointer<vtkOcclusionCuller>::New();
    }
    culler = this->OcclusionCuller;
  }
  if (!culler)
  {
    this->VTKCuller = vtkSmartPointer<vtkFrustumCoverageCuller>::New();
    culler = this->VTKCuller;
  }
  renderer->AddCuller(culler);
  this->Culling = mode;
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkSceneVisRenderView::Render(bool interactive, bool skip_rendering)
{
  if (auto* occlusion = vtkOcclusionCuller::SafeDownCast(this->OcclusionCuller))
  {
    // vtkPVLODActor then draws its decimated geometry, but the occluders rasterized are what the
    // actors' mappers hold at full resolution: a prop seen through a gap of the decimated
    // surface would be culled. Frustum culling stays.
    occlusion->SetOcclusionCulling(!(interactive && this->GetUseLODForInteractiveRender()));
  }
  this->Superclass::Render(interactive, skip_rendering);
}

//------------------------------------------------------------------------------
vtkOctreeCuller* vtkSceneVisRenderView::GetSceneVisCuller() const
{
  switch (this->Culling)
  {
    case CULLING_OCTREE:
      return this->OctreeCuller;
    case CULLING_OCCLUSION:
      return this->OcclusionCuller;
    default:
      return nullptr;
  }
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
  os << indent << "Culling: " << this->Culling << "\n";
}

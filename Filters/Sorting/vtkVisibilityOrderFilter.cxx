#include "vtkVisibilityOrderFilter.h"

#include "vtkBSPSortUtilities.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkProp3D.h"

#include <algorithm>
#include <numeric>

vtkCxxSetObjectMacro(vtkVisibilityOrderFilter, Camera, vtkCamera);

//------------------------------------------------------------------------------
vtkVisibilityOrderFilter::~vtkVisibilityOrderFilter()
{
  this->SetCamera(nullptr);
}

//------------------------------------------------------------------------------
void vtkVisibilityOrderFilter::SetProp3D(vtkProp3D* prop)
{
  if (this->Prop3D != prop)
  {
    this->Prop3D = prop;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkProp3D* vtkVisibilityOrderFilter::GetProp3D()
{
  return this->Prop3D;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkVisibilityOrderFilter::GetMTime()
{
  vtkMTimeType mTime = this->Superclass::GetMTime();
  if (this->Camera)
  {
    mTime = std::max(mTime, this->Camera->GetMTime());
  }
  if (vtkProp3D* prop = this->Prop3D)
  {
    mTime = std::max(mTime, prop->GetMTime());
  }
  return mTime;
}

//------------------------------------------------------------------------------
bool vtkVisibilityOrderFilter::ViewForInput(
  vtkPolyData* input, vtkPolyData* output, scenevis::View& view)
{
  if (!this->Camera)
  {
    vtkErrorMacro("No camera set: passing the input through unsorted.");
    output->ShallowCopy(input);
    return false;
  }
  vtkProp3D* prop = this->Prop3D;
  if (!vtkBSPSortUtilities::ViewFromCamera(this->Camera, prop ? prop->GetMatrix() : nullptr, view))
  {
    vtkErrorMacro("The camera has a non-finite position or no view direction: passing the input "
                  "through unsorted.");
    output->ShallowCopy(input);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkVisibilityOrderFilter::PolygonsForInput(vtkPolyData* input, vtkPolyData* output,
  scenevis::PolygonMesh& mesh, std::vector<vtkIdType>& cellOf)
{
  vtkBSPSortUtilities::AppendPolygons(input, nullptr, mesh, cellOf);
  if (mesh.polygonCount() == 0)
  {
    vtkWarningMacro("The input has no polygons to sort: passing it through.");
    output->ShallowCopy(input);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkIdType vtkVisibilityOrderFilter::ReportRemovedPolygons(
  std::size_t invalid, std::size_t degenerate)
{
  if (invalid > 0)
  {
    vtkWarningMacro("Removed " << invalid
                               << " polygon(s) with non-finite (NaN/Inf) points or invalid "
                                  "point ids; they cannot be drawn.");
  }
  if (degenerate > 0)
  {
    vtkWarningMacro("Removed " << degenerate
                               << " degenerate polygon(s) (fewer than 3 distinct points or "
                                  "zero area).");
  }
  return static_cast<vtkIdType>(invalid + degenerate);
}

//------------------------------------------------------------------------------
void vtkVisibilityOrderFilter::EmitCellData(vtkCellData* input, vtkIdType passThrough,
  vtkCellData* source, const std::uint32_t* sourceIndex, const std::uint32_t* cellOfRank,
  std::size_t count, vtkCellData* output)
{
  const vtkIdType total = passThrough + static_cast<vtkIdType>(count);
  output->CopyAllocate(input, total);
  for (int a = 0; a < source->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* from = source->GetAbstractArray(a);
    const char* name = from->GetName();
    vtkAbstractArray* to = name ? output->GetAbstractArray(name) : nullptr;
    vtkAbstractArray* inputArray = name ? input->GetAbstractArray(name) : nullptr;
    if (!to || !inputArray || to->GetDataType() != from->GetDataType() ||
      to->GetNumberOfComponents() != from->GetNumberOfComponents())
    {
      continue;
    }
    to->SetNumberOfTuples(total);
    for (vtkIdType c = 0; c < passThrough; ++c)
    {
      to->SetTuple(c, c, inputArray);
    }
    vtkBSPSortUtilities::PermuteTuples(from, sourceIndex, count, to, passThrough);
  }
  if (!this->GenerateOrderArrays)
  {
    return;
  }
  vtkNew<vtkIdTypeArray> originalIds;
  originalIds->SetName(OriginalCellIdArrayName());
  originalIds->SetNumberOfTuples(total);
  vtkNew<vtkIdTypeArray> ranks;
  ranks->SetName(SortRankArrayName());
  ranks->SetNumberOfTuples(total);
  vtkIdType* idPtr = originalIds->GetPointer(0);
  vtkIdType* rankPtr = ranks->GetPointer(0);
  std::iota(idPtr, idPtr + passThrough, vtkIdType(0));
  std::fill(rankPtr, rankPtr + passThrough, vtkIdType(-1));
  std::copy(cellOfRank, cellOfRank + count, idPtr + passThrough);
  std::iota(rankPtr + passThrough, rankPtr + total, vtkIdType(0));
  output->AddArray(originalIds);
  output->AddArray(ranks);
}

//------------------------------------------------------------------------------
void vtkVisibilityOrderFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "Prop3D: " << this->Prop3D.GetPointer() << "\n";
  os << indent << "Direction: "
     << (this->Direction == VTK_DIRECTION_BACK_TO_FRONT ? "BackToFront" : "FrontToBack") << "\n";
  os << indent << "GenerateOrderArrays: " << (this->GenerateOrderArrays ? "On" : "Off") << "\n";
}

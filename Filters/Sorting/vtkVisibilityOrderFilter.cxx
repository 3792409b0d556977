#include "vtkVisibilityOrderFilter.h"

#include "vtkBSPSortUtilities.h"

#include "vtkCamera.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkProp3D.h"

#include <algorithm>

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
void vtkVisibilityOrderFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "Prop3D: " << this->Prop3D.GetPointer() << "\n";
  os << indent << "Direction: "
     << (this->Direction == VTK_DIRECTION_BACK_TO_FRONT ? "BackToFront" : "FrontToBack") << "\n";
  os << indent << "GenerateOrderArrays: " << (this->GenerateOrderArrays ? "On" : "Off") << "\n";
}

#include "vtkCullerSlot.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkDataObject.h"
#include "vtkInstancedActor.h"
#include "vtkLinearTransform.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObject.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"

#include <algorithm>
#include <cmath>

namespace sc = scenevis::culling;

namespace vtkCullerSlots
{
const double* CurrentBounds(const Slot& slot, double scratch[6])
{
  if (slot.Placement < 0)
  {
    return slot.Prop->GetBounds();
  }
  static_cast<vtkInstancedActor*>(slot.Prop.GetPointer())
    ->GetPlacementBounds(slot.Placement, scratch);
  return scratch;
}

bool FiniteBounds(const double* b)
{
  for (int i = 0; i < 6; ++i)
  {
    if (!std::isfinite(b[i]))
    {
      return false;
    }
  }
  return b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5];
}

scenevis::Box ToBox(const double* b)
{
  scenevis::Box box;
  box.lo = { b[0], b[2], b[4] };
  box.hi = { b[1], b[3], b[5] };
  return box;
}

//------------------------------------------------------------------------------
bool RefreshSlot(Slot& slot, bool& warnedInvalid, vtkObject* self)
{
  vtkProp* prop = slot.Prop;
  const SlotKind oldKind = slot.Kind;
  double old[6];
  std::copy(slot.Bounds, slot.Bounds + 6, old);
  double placementBounds[6];
  const double* b = CurrentBounds(slot, placementBounds);
  if (!b)
  {
    slot.Kind = SlotKind::Flat;
  }
  else if (!vtkMath::AreBoundsInitialized(b) || !FiniteBounds(b))
  {
    slot.Kind = SlotKind::Invalid;
    if (!warnedInvalid)
    {
      warnedInvalid = true;
      vtkWarningWithObjectMacro(self,
        "A " << prop->GetClassName()
             << " has uninitialized, empty or non-finite bounds; such props are never culled "
                "(warned once).");
    }
  }
  else
  {
    slot.Kind = SlotKind::Tree;
    std::copy(b, b + 6, slot.Bounds);
  }
  vtkActor* asActor = vtkActor::SafeDownCast(prop);
  slot.IsActor = asActor != nullptr;
  // Actors: their own MTime (SetPosition, SetUserMatrix, SetMapper, ... call Modified()) plus
  // the user transform's; not vtkActor::GetMTime(), which adds the property (colour changes do
  // not move anything) and costs several virtual calls per prop and frame.
  slot.PropTime = slot.IsActor ? prop->vtkObject::GetMTime() : prop->GetMTime();
  slot.UserTransform = nullptr;
  if (asActor)
  {
    slot.UserTransform = asActor->GetUserTransform();
    if (!slot.UserTransform)
    {
      slot.UserTransform = asActor->GetUserMatrix();
    }
    slot.UserTransformTime = slot.UserTransform ? slot.UserTransform->GetMTime() : 0;
  }
  slot.Mapper = nullptr;
  slot.Data = nullptr;
  slot.Triangles = 0;
  if (vtkActor* actor = vtkActor::SafeDownCast(prop))
  {
    if (vtkMapper* mapper = actor->GetMapper())
    {
      slot.Mapper = mapper;
      slot.MapperTime = mapper->vtkObject::GetMTime();
      if (mapper->GetNumberOfInputPorts() > 0 && mapper->GetNumberOfInputConnections(0) > 0)
      {
        vtkDataObject* data = mapper->GetInputDataObject(0, 0);
        slot.Data = data;
        slot.DataTime = data ? data->GetMTime() : 0;
        if (vtkPolyData* pd = vtkPolyData::SafeDownCast(data))
        {
          // Triangles OpenGL draws: n - 2 per polygon or strip of n points (read from the cell
          // arrays' sizes, constant time).
          const auto triangles = [](vtkCellArray* cells)
          {
            return std::max<vtkIdType>(
              0, cells->GetNumberOfConnectivityIds() - 2 * cells->GetNumberOfCells());
          };
          slot.Triangles = static_cast<std::uint32_t>(std::min<vtkIdType>(
            UINT32_MAX, triangles(pd->GetPolys()) + triangles(pd->GetStrips())));
        }
      }
    }
  }
  return slot.Kind != oldKind || !std::equal(old, old + 6, slot.Bounds);
}

//------------------------------------------------------------------------------
sc::NormalCone ActorNormalCone(vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  if (!actor || !actor->GetMapper())
  {
    return sc::NormalCone::none();
  }
  vtkProperty* property = actor->GetProperty();
  if (!property->GetBackfaceCulling() || property->GetFrontfaceCulling() ||
    property->GetRepresentation() != VTK_SURFACE || property->GetEdgeVisibility())
  {
    return sc::NormalCone::none();
  }
  vtkPolyData* pd = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
  if (!pd || !pd->GetPoints() || pd->GetNumberOfVerts() || pd->GetNumberOfLines() ||
    pd->GetNumberOfStrips() || pd->GetNumberOfPolys() == 0)
  {
    return sc::NormalCone::none();
  }
  vtkMatrix4x4* m = actor->GetMatrix();
  vtkPoints* points = pd->GetPoints();
  auto world = [m, points](vtkIdType id)
  {
    double p[4] = { 0, 0, 0, 1 };
    points->GetPoint(id, p);
    double q[4];
    m->MultiplyPoint(p, q);
    return glm::dvec3(q[0], q[1], q[2]) / q[3];
  };
  std::vector<glm::dvec3> normals;
  normals.reserve(static_cast<std::size_t>(pd->GetNumberOfPolys()));
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts < 3)
    {
      continue;
    }
    const glm::dvec3 a = world(ids[0]);
    for (vtkIdType k = 1; k + 1 < npts; ++k)
    {
      normals.push_back(glm::cross(world(ids[k]) - a, world(ids[k + 1]) - a));
    }
  }
  return sc::normalConeOf(normals);
}
} // namespace vtkCullerSlots

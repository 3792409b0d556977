#include "vtkOctreeCuller.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCullerCollection.h"
#include "vtkDataObject.h"
#include "vtkLinearTransform.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProp.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "scenevis/Bvh.h"
#include "scenevis/NormalCone.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace sc = scenevis::culling;

vtkStandardNewMacro(vtkOctreeCuller);

namespace
{
enum class SlotKind : unsigned char
{
  Tree,    ///< 3D prop with valid bounds: in the hierarchy
  Flat,    ///< 2D prop (no bounds): always drawn
  Invalid  ///< uninitialized / empty / NaN bounds: always drawn
};

struct Slot
{
  vtkSmartPointer<vtkProp> Prop; // held so that a deleted prop's address is never mistaken
  SlotKind Kind = SlotKind::Flat;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  vtkMTimeType PropTime = 0;
  vtkMTimeType MapperTime = 0;
  vtkMTimeType DataTime = 0;
  vtkWeakPointer<vtkMapper> Mapper;
  vtkWeakPointer<vtkDataObject> Data;
  std::uint32_t Triangles = 0;
  bool IsActor = false;
  vtkObject* UserTransform = nullptr; // held by the prop; followed only while PropTime holds
  vtkMTimeType UserTransformTime = 0;
};

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
} // namespace

class vtkOctreeCuller::vtkInternals
{
public:
  std::vector<Slot> Slots;
  std::unordered_map<vtkProp*, std::uint32_t> SlotOf;
  // The list of the previous Cull() (compared pointer by pointer: the fast path) and the slot
  // of each of its entries.
  std::vector<vtkProp*> LastList;
  std::vector<std::uint32_t> ListSlots;
  std::vector<unsigned char> Present, Drawn;
  // Per slot: we set its multiplier to 1 while being the only culler (kept apart from Slots so
  // the per-frame loop touches one byte per prop, not a slot's cache line).
  std::vector<unsigned char> MultiplierIsOne;
  std::unordered_set<vtkProp*> Invalidated;
  bool RebuildRequested = true;
  bool NormalConesBuilt = false;
  sc::Bvh Bvh;
  std::vector<std::uint32_t> Visible;
  std::vector<vtkProp*> Culled;
  std::vector<std::uint32_t> KeptSlots;
  std::size_t RefitsSinceCheck = 0;
  std::vector<std::pair<double, std::uint32_t>> Keyed;
  std::vector<std::uint32_t> SortedSlots;
  bool WarnedInvalidBounds = false;
  bool WarnedCamera = false;
  bool WarnedViewport = false;
};

//------------------------------------------------------------------------------
vtkOctreeCuller::vtkOctreeCuller()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkOctreeCuller::~vtkOctreeCuller() = default;

//------------------------------------------------------------------------------
void vtkOctreeCuller::InvalidateProp(vtkProp* prop)
{
  if (prop)
  {
    this->Internals->Invalidated.insert(prop);
  }
}

//------------------------------------------------------------------------------
void vtkOctreeCuller::InvalidateAllProps()
{
  this->Internals->RebuildRequested = true;
}

namespace
{
/// World-space normal cone of an actor that is drawn with back-face culling; none() when the
/// actor does not qualify (see the class documentation) or its data is not polygons only.
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
} // namespace

//------------------------------------------------------------------------------
// Re-read what the hierarchy needs to know about one prop; returns whether its box changed.
static bool RefreshSlot(Slot& slot, bool& warnedInvalid, vtkOctreeCuller* self)
{
  vtkProp* prop = slot.Prop;
  const SlotKind oldKind = slot.Kind;
  double old[6];
  std::copy(slot.Bounds, slot.Bounds + 6, old);
  const double* b = prop->GetBounds();
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
          slot.Triangles = static_cast<std::uint32_t>(pd->GetNumberOfPolys() + pd->GetNumberOfStrips());
        }
      }
    }
  }
  return slot.Kind != oldKind || !std::equal(old, old + 6, slot.Bounds);
}

//------------------------------------------------------------------------------
double vtkOctreeCuller::Cull(
  vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized)
{
  vtkInternals& in = *this->Internals;
  this->CullingSkipped = false;
  this->NumberOfNodesVisited = this->NumberOfPropsTested = this->NumberOfPropsCulled = 0;
  this->NumberOfPropsCulledByFrustum = this->NumberOfPropsCulledBySize = 0;
  this->NumberOfPropsCulledByDistance = this->NumberOfPropsCulledByNormalCone = 0;
  this->NumberOfPropsDrawn = this->NumberOfTrianglesDrawn = 0;
  if (!propList || listLength <= 0)
  {
    listLength = std::max(listLength, 0);
    initialized = 1;
    return 0.0;
  }
  const auto n = static_cast<std::size_t>(listLength);

  // --- 1. Map the list onto the hierarchy's slots; rebuild only for props never seen. ----------
  const bool sameList =
    !in.RebuildRequested && n == in.LastList.size() && std::equal(propList, propList + n, in.LastList.begin());
  bool rebuild = in.RebuildRequested || in.NormalConesBuilt != this->NormalConeCulling;
  if (!sameList && !rebuild)
  {
    in.ListSlots.resize(n);
    std::fill(in.Present.begin(), in.Present.end(), 0);
    std::size_t present = 0;
    for (std::size_t i = 0; i < n && !rebuild; ++i)
    {
      const auto it = in.SlotOf.find(propList[i]);
      if (it == in.SlotOf.end())
      {
        rebuild = true;
      }
      else
      {
        in.ListSlots[i] = it->second;
        present += in.Present[it->second] ? 0 : 1;
        in.Present[it->second] = 1;
      }
    }
    // Forget props that are gone once they are the majority (they are held by reference).
    rebuild = rebuild || (in.Slots.size() > 64 && 2 * present < in.Slots.size());
  }
  if (!sameList)
  {
    in.LastList.assign(propList, propList + n);
  }
  if (rebuild)
  {
    in.Slots.clear();
    in.SlotOf.clear();
    in.Invalidated.clear();
    sc::BoxArrays boxes;
    std::vector<std::uint32_t> triangles;
    in.ListSlots.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const auto found = in.SlotOf.find(propList[i]);
      if (found != in.SlotOf.end())
      {
        in.ListSlots[i] = found->second; // the same prop twice in the list
        continue;
      }
      const auto s = static_cast<std::uint32_t>(in.Slots.size());
      in.Slots.emplace_back();
      Slot& slot = in.Slots.back();
      slot.Prop = propList[i];
      RefreshSlot(slot, in.WarnedInvalidBounds, this);
      in.SlotOf.emplace(propList[i], s);
      in.ListSlots[i] = s;
      boxes.push_back(slot.Kind == SlotKind::Tree ? ToBox(slot.Bounds) : scenevis::Box());
      triangles.push_back(slot.Triangles);
    }
    in.Bvh.build(boxes, sc::BuildMethod::BinnedSah, 4, &triangles);
    if (this->NormalConeCulling)
    {
      for (std::uint32_t s = 0; s < in.Slots.size(); ++s)
      {
        if (in.Slots[s].Kind == SlotKind::Tree)
        {
          in.Bvh.setNormalCone(s, ActorNormalCone(in.Slots[s].Prop));
        }
      }
      in.Bvh.refit();
    }
    in.NormalConesBuilt = this->NormalConeCulling;
    in.Present.assign(in.Slots.size(), 1);
    in.MultiplierIsOne.assign(in.Slots.size(), 0);
    in.RebuildRequested = false;
    ++this->NumberOfRebuilds;
  }
  else
  {
    // --- 2. Find moved props (UpdateMode) and refit their paths. ------------------------------
    std::size_t refits = 0;
    auto refresh = [&](std::uint32_t s)
    {
      Slot& slot = in.Slots[s];
      const bool changed = RefreshSlot(slot, in.WarnedInvalidBounds, this);
      if (changed)
      {
        in.Bvh.update(s, slot.Kind == SlotKind::Tree ? ToBox(slot.Bounds) : scenevis::Box());
      }
      if (this->NormalConeCulling && slot.Kind == SlotKind::Tree)
      {
        in.Bvh.setNormalCone(s, ActorNormalCone(slot.Prop)); // rotation keeps bounds sometimes
      }
      in.Bvh.setTriangleCount(s, slot.Triangles);
      refits += changed ? 1 : 0;
    };
    const std::size_t slots = in.Slots.size();
    if (this->UpdateMode == UPDATE_BOUNDS_EVERY_FRAME)
    {
      for (std::uint32_t s = 0; s < slots; ++s)
      {
        Slot& slot = in.Slots[s];
        if (!in.Present[s])
        {
          continue;
        }
        const double* b = slot.Prop->GetBounds();
        const bool same = slot.Kind == SlotKind::Tree && b && std::equal(b, b + 6, slot.Bounds);
        if (!same || (slot.Kind == SlotKind::Tree && this->NormalConeCulling &&
                       slot.Prop->vtkObject::GetMTime() != slot.PropTime))
        {
          refresh(s);
        }
      }
    }
    else if (this->UpdateMode == UPDATE_ON_MODIFIED)
    {
      for (std::uint32_t s = 0; s < slots; ++s)
      {
        Slot& slot = in.Slots[s];
        if (!in.Present[s])
        {
          continue;
        }
        // Check the prop first: a new mapper or input bumps its / the mapper's MTime, so the
        // (weak) mapper and data pointers are only followed while they are the current ones.
        vtkProp* prop = slot.Prop.GetPointer();
        bool changed = slot.IsActor ? prop->vtkObject::GetMTime() != slot.PropTime
                                    : prop->GetMTime() != slot.PropTime;
        if (!changed && slot.UserTransform)
        {
          changed = slot.UserTransform->GetMTime() != slot.UserTransformTime;
        }
        if (!changed && slot.Mapper)
        {
          changed = slot.Mapper->vtkObject::GetMTime() != slot.MapperTime ||
            (slot.Data ? slot.Data->GetMTime() != slot.DataTime : slot.DataTime != 0);
        }
        if (changed)
        {
          refresh(s);
        }
      }
    }
    for (vtkProp* prop : in.Invalidated)
    {
      const auto it = in.SlotOf.find(prop);
      if (it != in.SlotOf.end())
      {
        refresh(it->second);
      }
    }
    in.Invalidated.clear();
    if (refits > 0)
    {
      in.Bvh.refit();
      this->NumberOfRefits += static_cast<vtkIdType>(refits);
      // Many moves loosen the tree; rebuild from the current boxes when it got much worse
      // (checked now and then: degradation() is O(nodes)).
      in.RefitsSinceCheck += refits;
      if (in.RefitsSinceCheck > std::max<std::size_t>(64, slots / 16))
      {
        in.RefitsSinceCheck = 0;
        in.RebuildRequested = in.Bvh.degradation() > 2.0;
      }
    }
  }

  // --- 3. The view. ----------------------------------------------------------------------------
  sc::CullParams params;
  bool usable = true;
  vtkCamera* cam = ren ? ren->GetActiveCamera() : nullptr;
  int* size = ren ? ren->GetSize() : nullptr;
  if (!size || size[0] <= 0 || size[1] <= 0)
  {
    usable = false;
    if (!in.WarnedViewport)
    {
      in.WarnedViewport = true;
      vtkWarningMacro("The renderer's viewport has zero size: nothing is culled (warned once).");
    }
  }
  else if (cam)
  {
    const double aspect = ren->GetTiledAspectRatio();
    double eye[3], focal[3], dop[3];
    cam->GetPosition(eye);
    cam->GetFocalPoint(focal);
    cam->GetDirectionOfProjection(dop);
    const double* range = cam->GetClippingRange();
    bool finite = std::isfinite(aspect) && aspect > 0.0 && std::isfinite(range[0]) &&
      std::isfinite(range[1]) && range[1] > range[0] &&
      std::isfinite(cam->GetViewAngle()) && std::isfinite(cam->GetParallelScale());
    for (int k = 0; k < 3; ++k)
    {
      finite = finite && std::isfinite(eye[k]) && std::isfinite(focal[k]) && std::isfinite(dop[k]);
    }
    if (finite)
    {
      vtkMatrix4x4* m = cam->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
      params.frustum = sc::Frustum::fromRowMajor(&m->GetData()[0]);
      finite = params.frustum.valid();
    }
    if (!finite)
    {
      usable = false;
      if (!in.WarnedCamera)
      {
        in.WarnedCamera = true;
        vtkWarningMacro("The active camera is not usable (non-finite position, focal point, "
                        "clipping range or projection): nothing is culled (warned once).");
      }
    }
    else
    {
      params.frustumCulling = this->FrustumCulling;
      params.eye = glm::dvec3(eye[0], eye[1], eye[2]);
      params.viewDirection = glm::normalize(glm::dvec3(dop[0], dop[1], dop[2]));
      params.parallel = cam->GetParallelProjection() != 0;
      params.normalConeCulling = this->NormalConeCulling;
      params.maxDistance = this->MaximumDistance >= VTK_DOUBLE_MAX
        ? std::numeric_limits<double>::infinity()
        : this->MaximumDistance;
      if (this->MinimumPixelSize > 0.0)
      {
        const double pixels = cam->GetUseHorizontalViewAngle() ? size[0] : size[1];
        params.minPixels = this->MinimumPixelSize;
        params.pixelsPerUnit = params.parallel
          ? pixels / (2.0 * cam->GetParallelScale())
          : pixels / (2.0 * std::tan(vtkMath::RadiansFromDegrees(cam->GetViewAngle()) / 2.0));
      }
    }
  }
  else
  {
    usable = false;
  }

  // --- 4. Cull. ----------------------------------------------------------------------------------
  in.Drawn.assign(in.Slots.size(), 0);
  if (usable)
  {
    sc::CullStats stats;
    in.Bvh.cull(params, in.Visible, &stats);
    for (const std::uint32_t s : in.Visible)
    {
      in.Drawn[s] = 1;
    }
    this->NumberOfNodesVisited = static_cast<vtkIdType>(stats.nodesVisited);
    this->NumberOfPropsTested = static_cast<vtkIdType>(stats.objectsTested);
    this->NumberOfTrianglesDrawn = static_cast<vtkIdType>(stats.trianglesDrawn);
    // By reason, over all props the hierarchy knows (equal to this list's unless another
    // culler ran first and passed a subset).
    this->NumberOfPropsCulledByFrustum = static_cast<vtkIdType>(stats.culledFrustum);
    this->NumberOfPropsCulledBySize = static_cast<vtkIdType>(stats.culledContribution);
    this->NumberOfPropsCulledByDistance = static_cast<vtkIdType>(stats.culledDistance);
    this->NumberOfPropsCulledByNormalCone = static_cast<vtkIdType>(stats.culledNormalCone);
  }
  else
  {
    this->CullingSkipped = true;
    std::fill(in.Drawn.begin(), in.Drawn.end(), 1);
  }

  // --- 5. Drawn props first (relative order kept), culled ones after. --------------------------
  in.Culled.clear();
  in.KeptSlots.clear();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t s = in.ListSlots[i];
    if (in.Drawn[s])
    {
      propList[kept++] = propList[i];
      in.KeptSlots.push_back(s);
    }
    else
    {
      in.Culled.push_back(propList[i]);
    }
  }
  std::copy(in.Culled.begin(), in.Culled.end(), propList + kept);
  this->NumberOfPropsCulled = static_cast<vtkIdType>(in.Culled.size());
  this->NumberOfPropsDrawn = static_cast<vtkIdType>(kept);
  listLength = static_cast<int>(kept);

  // --- 6. Optional depth sort of the drawn props (2D / unbounded props first, as VTK does). -----
  if (this->SortingStyle != 0 && usable && kept > 1)
  {
    in.Keyed.clear();
    for (std::size_t i = 0; i < kept; ++i)
    {
      const Slot& slot = in.Slots[in.KeptSlots[i]];
      double key = -VTK_DOUBLE_MAX;
      if (slot.Kind == SlotKind::Tree)
      {
        const glm::dvec3 c = ToBox(slot.Bounds).center();
        key = glm::dot(c - params.eye, params.viewDirection);
      }
      in.Keyed.emplace_back(key, static_cast<std::uint32_t>(i));
    }
    if (this->SortingStyle == 1)
    {
      std::stable_sort(in.Keyed.begin(), in.Keyed.end(),
        [](const auto& a, const auto& b) { return a.first < b.first; });
    }
    else
    {
      std::stable_sort(in.Keyed.begin(), in.Keyed.end(),
        [](const auto& a, const auto& b) { return a.first > b.first; });
    }
    in.Culled.assign(propList, propList + kept); // reused as scratch
    in.SortedSlots.resize(kept);
    for (std::size_t i = 0; i < kept; ++i)
    {
      propList[i] = in.Culled[in.Keyed[i].second];
      in.SortedSlots[i] = in.KeptSlots[in.Keyed[i].second];
    }
    in.KeptSlots.swap(in.SortedSlots);
  }

  // --- 7. Render-time multipliers (vtkCuller contract). ---------------------------------------
  // Only cullers change the multipliers; when this is the renderer's only culler, a multiplier
  // set to 1 last frame is still 1, and not touching 50k props saves a cache miss each.
  const bool alone = ren && ren->GetCullers()->GetNumberOfItems() == 1 &&
    ren->GetCullers()->GetItemAsObject(0) == this;
  double total = 0.0;
  for (std::size_t i = 0; i < kept; ++i)
  {
    if (!initialized)
    {
      unsigned char& one = in.MultiplierIsOne[in.KeptSlots[i]];
      if (!alone || !one)
      {
        propList[i]->SetRenderTimeMultiplier(1.0);
      }
      one = alone ? 1 : 0;
      total += 1.0;
    }
    else
    {
      total += propList[i]->GetRenderTimeMultiplier();
    }
  }
  initialized = 1;
  // The renderer divides by the total: never 0 (or NaN) while props remain.
  if (kept > 0 && !(total > 0.0 && std::isfinite(total)))
  {
    total = static_cast<double>(kept);
  }
  return total;
}

//------------------------------------------------------------------------------
void vtkOctreeCuller::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FrustumCulling: " << this->FrustumCulling << "\n";
  os << indent << "MinimumPixelSize: " << this->MinimumPixelSize << " (approximate)\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance << "\n";
  os << indent << "NormalConeCulling: " << this->NormalConeCulling << "\n";
  os << indent << "SortingStyle: " << this->SortingStyle << "\n";
  os << indent << "UpdateMode: " << this->UpdateMode << "\n";
  os << indent << "Props known: " << this->Internals->Slots.size() << "\n";
  os << indent << "NumberOfNodesVisited: " << this->NumberOfNodesVisited << "\n";
  os << indent << "NumberOfPropsTested: " << this->NumberOfPropsTested << "\n";
  os << indent << "NumberOfPropsCulled: " << this->NumberOfPropsCulled << "\n";
  os << indent << "NumberOfPropsDrawn: " << this->NumberOfPropsDrawn << "\n";
  os << indent << "NumberOfTrianglesDrawn: " << this->NumberOfTrianglesDrawn << "\n";
  os << indent << "NumberOfRebuilds: " << this->NumberOfRebuilds << "\n";
  os << indent << "NumberOfRefits: " << this->NumberOfRefits << "\n";
}

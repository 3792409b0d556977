#include "vtkOctreeCuller.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCullerCollection.h"
#include "vtkDataObject.h"
#include "vtkInstancedActor.h"
#include "vtkLinearTransform.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMatrixToLinearTransform.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "vtkOccluderRasterizer.h"

#include "scenevis/Bvh.h"
#include "scenevis/NormalCone.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
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
  Tree,   ///< 3D prop with valid bounds: in the hierarchy
  Flat,   ///< 2D prop (no bounds): always drawn
  Invalid ///< uninitialized / empty / NaN bounds: always drawn
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
  // UPDATE_ON_EVENTS: the objects whose ModifiedEvent marks this slot dirty, and whether the
  // slot must be polled every frame instead (props / mappers whose bounds events cannot cover).
  std::vector<vtkObject*> Watched;
  bool Polled = false;
  bool Registered = false;
  /// A placement of a vtkInstancedActor: its index (-1: the slot is the whole prop). The
  /// placements of one actor are consecutive slots; the first (the actor's slot in SlotOf and
  /// ListSlots) holds their number in Count.
  vtkIdType Placement = -1;
  std::uint32_t Count = 1;
};

/// The bounds slot @p slot stands for now: the prop's, or its placement's (into @p scratch).
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
  // Occlusion culling: the rasterizer (made on first use) and last frame's visible slots, which
  // are this frame's first occluders.
  std::unique_ptr<vtkOccluderRasterizer> Occlusion;
  std::vector<std::uint32_t> LastVisible;
  std::vector<vtkProp*> Culled;
  std::vector<std::uint32_t> KeptSlots;
  std::vector<vtkIdType> Placements; // scratch: the visible placements of an instanced actor
  std::vector<std::uint32_t> InstancedHeads; // first slot of each vtkInstancedActor
  std::size_t RefitsSinceCheck = 0;
  std::vector<std::pair<double, std::uint32_t>> Keyed;
  std::vector<std::uint32_t> SortedSlots;
  bool WarnedInvalidBounds = false;
  bool WarnedCamera = false;
  bool WarnedViewport = false;

  // --- UPDATE_ON_EVENTS ---------------------------------------------------------------------
  struct Watch
  {
    unsigned long ModifiedTag = 0, DeleteTag = 0;
    std::vector<std::uint32_t> Slots;
  };
  // Every object observed, with the slots that depend on it (one observer pair per object, so a
  // source shared by 100k actors costs one callback that marks 100k slots).
  std::unordered_map<vtkObject*, Watch> Watches;
  vtkNew<vtkCallbackCommand> Callback;
  std::vector<std::uint32_t> DirtyList, DirtyWork;
  std::vector<unsigned char> Dirty, PrevPresent;
  std::vector<std::uint32_t> PolledSlots;
  bool EventsActive = false;
  vtkIdType Events = 0;

  /// Front-to-back cull with occlusion (vtkOcclusionCuller): props found visible are rasterized
  /// as occluders before farther nodes are tested; last frame's visible props occlude first.
  void CullOccluded(vtkRenderer* ren, const sc::CullParams& params, std::size_t cacheBudget,
    double minimumPixelsPerTriangle, sc::CullStats& stats)
  {
    if (!this->Occlusion)
    {
      this->Occlusion.reset(new vtkOccluderRasterizer);
    }
    vtkOccluderRasterizer& raster = *this->Occlusion;
    raster.CacheBudget = cacheBudget;
    raster.MinimumPixelsPerTriangle = minimumPixelsPerTriangle;
    vtkCamera* cam = ren->GetActiveCamera();
    const int* size = ren->GetSize();
    vtkMatrix4x4* m = cam->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1);
    raster.BeginFrame(size[0], size[1], &m->GetData()[0]);
    sc::OcclusionCull occlusion;
    occlusion.buffer = &raster.Buffer();
    // Only props the renderer draws this frame occlude (a prop another culler removed, or one
    // that left the renderer, stays in the hierarchy until the next rebuild).
    occlusion.drawOccluder = [this, &raster](std::uint32_t s)
    {
      if (s < this->Present.size() && this->Present[s])
      {
        const Slot& slot = this->Slots[s];
        double model[16];
        const bool placed = slot.Placement >= 0 &&
          static_cast<vtkInstancedActor*>(slot.Prop.GetPointer())
            ->GetPlacementModelMatrix(slot.Placement, model);
        raster.Draw(slot.Prop, slot.Bounds, placed ? model : nullptr);
      }
    };
    occlusion.worthDrawing = [&raster](const glm::dvec3& lo, const glm::dvec3& hi,
                               std::uint32_t triangles) {
      return raster.WorthDrawing(&lo.x, &hi.x, static_cast<vtkIdType>(triangles));
    };
    occlusion.seeds = &this->LastVisible;
    this->Bvh.cullOccluded(params, occlusion, this->Visible, &stats);
    this->LastVisible = this->Visible;
  }

  vtkInternals()
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(&vtkInternals::OnEvent);
  }
  ~vtkInternals() { this->UnwatchAll(); }

  static void OnEvent(vtkObject* caller, unsigned long event, void* clientData, void*)
  {
    auto* self = static_cast<vtkInternals*>(clientData);
    const auto it = self->Watches.find(caller);
    if (it == self->Watches.end())
    {
      return;
    }
    ++self->Events;
    for (const std::uint32_t s : it->second.Slots)
    {
      self->MarkDirty(s);
    }
    if (event == vtkCommand::DeleteEvent)
    {
      self->Watches.erase(it); // its observers die with it
    }
  }

  void MarkDirty(std::uint32_t s)
  {
    if (s < this->Dirty.size() && !this->Dirty[s])
    {
      this->Dirty[s] = 1;
      this->DirtyList.push_back(s);
    }
  }

  void WatchObject(vtkObject* object, std::uint32_t s)
  {
    auto inserted = this->Watches.try_emplace(object);
    Watch& w = inserted.first->second;
    if (inserted.second)
    {
      w.ModifiedTag = object->AddObserver(vtkCommand::ModifiedEvent, this->Callback);
      w.DeleteTag = object->AddObserver(vtkCommand::DeleteEvent, this->Callback);
    }
    w.Slots.push_back(s);
  }

  void Unregister(std::uint32_t s)
  {
    Slot& slot = this->Slots[s];
    for (vtkObject* object : slot.Watched)
    {
      const auto it = this->Watches.find(object);
      if (it == this->Watches.end())
      {
        continue; // deleted meanwhile
      }
      auto& list = it->second.Slots;
      const auto pos = std::find(list.begin(), list.end(), s);
      if (pos != list.end())
      {
        *pos = list.back();
        list.pop_back();
      }
      if (list.empty())
      {
        object->RemoveObserver(it->second.ModifiedTag);
        object->RemoveObserver(it->second.DeleteTag);
        this->Watches.erase(it);
      }
    }
    slot.Watched.clear();
    slot.Registered = false;
  }

  void UnwatchAll()
  {
    for (auto& entry : this->Watches)
    {
      entry.first->RemoveObserver(entry.second.ModifiedTag);
      entry.first->RemoveObserver(entry.second.DeleteTag);
    }
    this->Watches.clear();
    for (Slot& slot : this->Slots)
    {
      slot.Watched.clear();
      slot.Registered = false;
    }
    this->PolledSlots.clear();
  }

  /// The objects whose modification can change slot @p s's bounds (see the class documentation).
  /// Returns false when events cannot cover the prop: it is then polled every frame.
  static bool Dependencies(const Slot& slot, bool withProperty, std::vector<vtkObject*>& deps)
  {
    deps.clear();
    vtkProp* prop = slot.Prop;
    deps.push_back(prop);
    const char* name = prop->GetClassName();
    // Only plain actors: subclasses such as vtkFollower / vtkLODActor / vtkAxesActor compute
    // their matrix or bounds from other state (the camera, their parts).
    if (std::strcmp(name, "vtkOpenGLActor") != 0 && std::strcmp(name, "vtkActor") != 0 &&
      std::strcmp(name, "vtkInstancedActor") != 0)
    {
      return false;
    }
    auto* actor = static_cast<vtkActor*>(prop);
    if (vtkLinearTransform* transform = actor->GetUserTransform())
    {
      // SetUserMatrix() wraps the matrix in a vtkMatrixToLinearTransform of it: the matrix's
      // events (and the wrapper's, for SetInput) cover that one. Any other transform's inputs /
      // concatenations change it without an event on it.
      auto* wrapper = vtkMatrixToLinearTransform::SafeDownCast(transform);
      if (!wrapper || !actor->GetUserMatrix() || wrapper->GetInput() != actor->GetUserMatrix())
      {
        return false;
      }
      deps.push_back(wrapper);
    }
    if (vtkMatrix4x4* m = actor->GetUserMatrix())
    {
      deps.push_back(m);
    }
    if (withProperty)
    {
      deps.push_back(actor->GetProperty());
    }
    vtkMapper* mapper = actor->GetMapper();
    if (!mapper)
    {
      return true; // SetMapper() modifies the actor
    }
    if (!mapper->IsA("vtkPolyDataMapper"))
    {
      return false;
    }
    deps.push_back(mapper);
    if (mapper->GetNumberOfInputConnections(0) == 0)
    {
      return true; // SetInputConnection / SetInputData modify the mapper
    }
    vtkDataObject* data = mapper->GetInputDataObject(0, 0);
    if (data)
    {
      if (!data->IsA("vtkPolyData"))
      {
        return false;
      }
      deps.push_back(data);
      // A polydata's bounds come from its points; editing them fires events on the points or
      // their array, not on the polydata.
      if (vtkPoints* points = static_cast<vtkPolyData*>(data)->GetPoints())
      {
        deps.push_back(points);
        if (points->GetData())
        {
          deps.push_back(points->GetData());
        }
      }
    }
    // The upstream pipeline: a modified algorithm re-executes at the next GetBounds() (for a
    // culled prop nothing else would notice).
    std::vector<vtkAlgorithm*> stack;
    if (vtkAlgorithmOutput* out = mapper->GetInputConnection(0, 0))
    {
      stack.push_back(out->GetProducer());
    }
    std::size_t algorithms = 0;
    while (!stack.empty())
    {
      vtkAlgorithm* algorithm = stack.back();
      stack.pop_back();
      if (!algorithm || std::find(deps.begin(), deps.end(), algorithm) != deps.end())
      {
        continue;
      }
      if (++algorithms > 64)
      {
        return false; // a huge pipeline: poll instead
      }
      deps.push_back(algorithm);
      for (int port = 0; port < algorithm->GetNumberOfInputPorts(); ++port)
      {
        for (int c = 0; c < algorithm->GetNumberOfInputConnections(port); ++c)
        {
          if (vtkAlgorithmOutput* in = algorithm->GetInputConnection(port, c))
          {
            stack.push_back(in->GetProducer());
          }
        }
      }
    }
    return true;
  }

  /// (Re)register slot @p s; returns whether it is polled.
  void Register(std::uint32_t s, bool withProperty, std::vector<vtkObject*>& scratch)
  {
    Slot& slot = this->Slots[s];
    const bool events = Dependencies(slot, withProperty, scratch);
    if (slot.Registered && scratch == slot.Watched && slot.Polled == !events)
    {
      return;
    }
    this->Unregister(s);
    for (vtkObject* object : scratch)
    {
      this->WatchObject(object, s);
    }
    slot.Watched = scratch;
    slot.Registered = true;
    if (slot.Polled != !events)
    {
      slot.Polled = !events;
      this->PolledSetChanged = true;
    }
  }

  bool PolledSetChanged = true;
  void UpdatePolledList()
  {
    if (!this->PolledSetChanged)
    {
      return;
    }
    this->PolledSlots.clear();
    for (std::uint32_t s = 0; s < this->Slots.size(); ++s)
    {
      if (this->Slots[s].Registered && this->Slots[s].Polled)
      {
        this->PolledSlots.push_back(s);
      }
    }
    this->PolledSetChanged = false;
  }
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
vtkIdType vtkOctreeCuller::GetNumberOfObservedObjects() const
{
  return static_cast<vtkIdType>(this->Internals->Watches.size());
}

vtkIdType vtkOctreeCuller::GetNumberOfPolledProps() const
{
  return this->Internals->EventsActive ? static_cast<vtkIdType>(this->Internals->PolledSlots.size())
                                       : 0;
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
double vtkOctreeCuller::Cull(
  vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized)
{
  vtkInternals& in = *this->Internals;
  const auto cullStart = std::chrono::steady_clock::now();
  this->CullingSkipped = false;
  this->NumberOfPropsCulledByOcclusion = this->NumberOfOcclusionTests = 0;
  this->NumberOfOccludersDrawn = this->NumberOfOccluderTriangles = 0;
  this->NumberOfOccludersSkipped = 0;
  this->OccluderRasterTime = this->CullTime = 0.0;
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
  // A vtkInstancedActor that gained or lost placements needs other slots: rebuild.
  for (const std::uint32_t head : in.InstancedHeads)
  {
    const Slot& slot = in.Slots[head];
    const vtkIdType placements =
      static_cast<vtkInstancedActor*>(slot.Prop.GetPointer())->GetNumberOfPlacements();
    if ((slot.Placement < 0) != (placements == 0) ||
      (placements > 0 && static_cast<vtkIdType>(slot.Count) != placements))
    {
      in.RebuildRequested = true;
      break;
    }
  }
  const bool sameList = !in.RebuildRequested && n == in.LastList.size() &&
    std::equal(propList, propList + n, in.LastList.begin());
  bool rebuild = in.RebuildRequested || in.NormalConesBuilt != this->NormalConeCulling;
  if (!sameList && !rebuild)
  {
    in.ListSlots.resize(n);
    if (in.EventsActive)
    {
      in.PrevPresent = in.Present;
    }
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
        const std::uint32_t count = in.Slots[it->second].Count;
        present += in.Present[it->second] ? 0 : count;
        std::fill_n(in.Present.begin() + it->second, count, 1);
      }
    }
    // Forget props that are gone once they are the majority (they are held by reference).
    rebuild = rebuild || (in.Slots.size() > 64 && 2 * present < in.Slots.size());
    if (in.EventsActive && !rebuild)
    {
      // Props that left stop being observed; props that came back are re-read.
      std::vector<vtkObject*> scratch;
      for (std::uint32_t s = 0; s < in.Slots.size(); ++s)
      {
        if (in.PrevPresent[s] && !in.Present[s])
        {
          in.Unregister(s);
          in.PolledSetChanged = true;
        }
        else if (!in.PrevPresent[s] && in.Present[s])
        {
          in.Register(s, this->NormalConeCulling, scratch);
          in.PolledSetChanged = true;
          in.MarkDirty(s);
        }
      }
    }
  }
  if (!sameList)
  {
    in.LastList.assign(propList, propList + n);
  }
  if (rebuild)
  {
    in.UnwatchAll();
    in.EventsActive = false;
    in.Slots.clear();
    in.SlotOf.clear();
    in.InstancedHeads.clear();
    in.Invalidated.clear();
    sc::BoxArrays boxes;
    std::vector<std::uint32_t> triangles;
    in.ListSlots.resize(n);
    // One slot per prop, per placement of a vtkInstancedActor: sized once (a slot is ~180
    // bytes; growing by doubling would hold up to twice that for 46,000 placements).
    std::size_t slots = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      auto* instanced = vtkInstancedActor::SafeDownCast(propList[i]);
      slots += instanced ? std::max<std::size_t>(1, instanced->GetNumberOfPlacements()) : 1;
    }
    if (in.Slots.capacity() > slots)
    {
      std::vector<Slot>().swap(in.Slots); // cleared above
    }
    in.Slots.reserve(slots);
    for (std::size_t i = 0; i < n; ++i)
    {
      const auto found = in.SlotOf.find(propList[i]);
      if (found != in.SlotOf.end())
      {
        in.ListSlots[i] = found->second; // the same prop twice in the list
        continue;
      }
      const auto s = static_cast<std::uint32_t>(in.Slots.size());
      auto* instanced = vtkInstancedActor::SafeDownCast(propList[i]);
      const vtkIdType placements = instanced ? instanced->GetNumberOfPlacements() : 0;
      // A vtkInstancedActor is one slot per placement (none: one slot, drawing nothing).
      for (vtkIdType k = 0; k < std::max<vtkIdType>(1, placements); ++k)
      {
        in.Slots.emplace_back();
        Slot& slot = in.Slots.back();
        slot.Prop = propList[i];
        slot.Placement = placements > 0 ? k : -1;
        slot.Count = k == 0 ? static_cast<std::uint32_t>(std::max<vtkIdType>(1, placements)) : 0;
        RefreshSlot(slot, in.WarnedInvalidBounds, this);
        boxes.push_back(slot.Kind == SlotKind::Tree ? ToBox(slot.Bounds) : scenevis::Box());
        triangles.push_back(slot.Triangles);
      }
      in.SlotOf.emplace(propList[i], s);
      in.ListSlots[i] = s;
      if (instanced)
      {
        in.InstancedHeads.push_back(s);
      }
    }
    in.Bvh.build(boxes, sc::BuildMethod::BinnedSah, 4, &triangles);
    in.LastVisible.clear(); // slot numbers changed
    if (this->NormalConeCulling)
    {
      for (std::uint32_t s = 0; s < in.Slots.size(); ++s)
      {
        if (in.Slots[s].Kind == SlotKind::Tree && in.Slots[s].Placement < 0)
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
    in.Dirty.assign(in.Slots.size(), 0);
    in.DirtyList.clear();
    if (this->UpdateMode == UPDATE_ON_EVENTS)
    {
      std::vector<vtkObject*> scratch;
      for (std::uint32_t s = 0; s < in.Slots.size(); ++s)
      {
        in.Register(s, this->NormalConeCulling, scratch);
      }
      in.PolledSetChanged = true;
      in.EventsActive = true;
      // Events fired while the bounds were read above (pipeline updates) are already seen.
      std::fill(in.Dirty.begin(), in.Dirty.end(), 0);
      in.DirtyList.clear();
    }
  }
  else
  {
    // --- 2. Find moved props (UpdateMode) and refit their paths. ------------------------------
    if (in.EventsActive && this->UpdateMode != UPDATE_ON_EVENTS)
    {
      in.UnwatchAll();
      in.EventsActive = false;
    }
    std::size_t refits = 0;
    auto refresh = [&](std::uint32_t s)
    {
      Slot& slot = in.Slots[s];
      const bool changed = RefreshSlot(slot, in.WarnedInvalidBounds, this);
      if (changed)
      {
        in.Bvh.update(s, slot.Kind == SlotKind::Tree ? ToBox(slot.Bounds) : scenevis::Box());
      }
      if (this->NormalConeCulling && slot.Kind == SlotKind::Tree && slot.Placement < 0)
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
        double scratchBounds[6];
        const double* b = CurrentBounds(slot, scratchBounds);
        const bool same = slot.Kind == SlotKind::Tree && b && std::equal(b, b + 6, slot.Bounds);
        if (!same ||
          (slot.Kind == SlotKind::Tree && this->NormalConeCulling &&
            slot.Prop->vtkObject::GetMTime() != slot.PropTime))
        {
          refresh(s);
        }
      }
    }
    else if (this->UpdateMode == UPDATE_ON_EVENTS)
    {
      if (!in.EventsActive)
      {
        // Switched to events: observe everything, and re-read every prop once (changes made
        // before were not observed).
        std::vector<vtkObject*> scratch;
        in.Dirty.assign(slots, 0);
        in.DirtyList.clear();
        for (std::uint32_t s = 0; s < slots; ++s)
        {
          if (in.Present[s])
          {
            in.Register(s, this->NormalConeCulling, scratch);
            in.MarkDirty(s);
          }
        }
        in.PolledSetChanged = true;
        in.EventsActive = true;
      }
      // O(dirty props): re-read the props whose dependencies fired ModifiedEvent. A slot's own
      // events while its bounds are read (its pipeline updating) are absorbed (it is still
      // marked); events for other slots raised meanwhile are handled in the next round.
      std::vector<vtkObject*> scratch;
      for (int round = 0; round < 4 && !in.DirtyList.empty(); ++round)
      {
        in.DirtyWork.swap(in.DirtyList);
        for (const std::uint32_t s : in.DirtyWork)
        {
          if (in.Present[s])
          {
            refresh(s);
            in.Register(s, this->NormalConeCulling, scratch);
          }
          in.Dirty[s] = 0;
        }
        in.DirtyWork.clear();
      }
      // Props events cannot cover (see the class documentation): polled like
      // UPDATE_BOUNDS_EVERY_FRAME.
      in.UpdatePolledList();
      for (const std::uint32_t s : in.PolledSlots)
      {
        Slot& slot = in.Slots[s];
        if (!in.Present[s])
        {
          continue;
        }
        double scratchBounds[6];
        const double* b = CurrentBounds(slot, scratchBounds);
        const bool same = slot.Kind == SlotKind::Tree && b && std::equal(b, b + 6, slot.Bounds);
        if (!same ||
          (slot.Kind == SlotKind::Tree && this->NormalConeCulling &&
            slot.Prop->vtkObject::GetMTime() != slot.PropTime))
        {
          refresh(s);
          in.Register(s, this->NormalConeCulling, scratch);
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
      std::isfinite(range[1]) && range[1] > range[0] && std::isfinite(cam->GetViewAngle()) &&
      std::isfinite(cam->GetParallelScale());
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
    if (this->OcclusionCulling)
    {
      in.CullOccluded(
        ren, params, this->OccluderCacheBudget, this->OccluderMinimumPixelsPerTriangle, stats);
      const vtkOccluderRasterizer& raster = *in.Occlusion;
      this->NumberOfPropsCulledByOcclusion = static_cast<vtkIdType>(stats.culledOcclusion);
      this->NumberOfOcclusionTests = static_cast<vtkIdType>(stats.occlusionTests);
      this->NumberOfOccludersDrawn = raster.OccludersDrawn;
      this->NumberOfOccludersSkipped = raster.OccludersSkipped;
      this->NumberOfOccluderTriangles = raster.OccluderTriangles;
      this->OccluderRasterTime = 1e3 * raster.DrawSeconds;
      this->DepthBufferBytes = in.Occlusion->Buffer().memoryBytes();
      this->OccluderCacheBytes = raster.CacheBytes;
    }
    else
    {
      in.Bvh.cull(params, in.Visible, &stats);
    }
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
    bool drawn = in.Drawn[s] != 0;
    if (in.Slots[s].Placement >= 0)
    {
      // A vtkInstancedActor: drawn while any placement is, and told which.
      in.Placements.clear();
      for (std::uint32_t k = 0; k < in.Slots[s].Count; ++k)
      {
        if (in.Drawn[s + k])
        {
          in.Placements.push_back(static_cast<vtkIdType>(k));
        }
      }
      static_cast<vtkInstancedActor*>(propList[i])
        ->SetVisiblePlacements(in.Placements.data(), static_cast<vtkIdType>(in.Placements.size()));
      drawn = !in.Placements.empty();
    }
    if (drawn)
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
  this->CullTime =
    1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - cullStart).count();
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
  os << indent << "Objects observed: " << this->Internals->Watches.size() << "\n";
  os << indent << "NumberOfNodesVisited: " << this->NumberOfNodesVisited << "\n";
  os << indent << "NumberOfPropsTested: " << this->NumberOfPropsTested << "\n";
  os << indent << "NumberOfPropsCulled: " << this->NumberOfPropsCulled << "\n";
  os << indent << "NumberOfPropsDrawn: " << this->NumberOfPropsDrawn << "\n";
  os << indent << "NumberOfTrianglesDrawn: " << this->NumberOfTrianglesDrawn << "\n";
  os << indent << "NumberOfRebuilds: " << this->NumberOfRebuilds << "\n";
  os << indent << "NumberOfRefits: " << this->NumberOfRefits << "\n";
}

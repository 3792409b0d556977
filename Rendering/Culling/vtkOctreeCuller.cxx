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
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "vtkCullerSlot.h"
#include "vtkCullerSlotWatcher.h"
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

using namespace vtkCullerSlots;

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
  std::vector<unsigned char> Keep; // per list entry: drawn
  std::vector<std::uint32_t> KeptSlots;
  std::vector<vtkIdType> Placements; // scratch: the visible placements of an instanced actor
  std::vector<std::uint32_t> InstancedHeads; // first slot of each vtkInstancedActor
  std::size_t RefitsSinceCheck = 0;
  std::vector<std::pair<double, std::uint32_t>> Keyed;
  std::vector<std::uint32_t> SortedSlots;
  std::vector<vtkProp*> Unsorted; // scratch of SortKept
  bool WarnedInvalidBounds = false;
  bool WarnedCamera = false;
  bool WarnedViewport = false;

  // UPDATE_ON_EVENTS: what may have moved; and the slots present in the list before this one.
  vtkCullerSlotWatcher Watcher{ this->Slots };
  std::vector<unsigned char> PrevPresent;
  std::size_t PresentSlots = 0; ///< slots whose prop is in the list (Present)

  // The renderer's props as last counted (CountRendererProps): its collection's MTime, how many
  // slots belong to props in it, and which.
  vtkMTimeType ViewPropsTime = 0;
  std::size_t SlotsInRendererCount = 0;
  std::vector<unsigned char> InRenderer;

  /// Maps the list onto the slots (Present, ListSlots; observers of props that came or left);
  /// returns whether the hierarchy must be rebuilt (props never seen, or most gone from the
  /// renderer).
  bool MapList(vtkRenderer* ren, vtkProp** propList, std::size_t n, vtkOctreeCuller* self);
  /// One slot per prop (per placement of a vtkInstancedActor), the hierarchy over them, and
  /// their observers in UPDATE_ON_EVENTS. The props: the list's, and the renderer's other
  /// visible props (those a culler before this one removed: they come back without a rebuild).
  void Rebuild(vtkRenderer* ren, vtkProp** propList, std::size_t n, vtkOctreeCuller* self);
  /// Counts the slots whose prop is in the renderer again if its props changed since the last
  /// count (InRenderer, SlotsInRendererCount); returns whether they changed.
  bool CountRendererProps(vtkRenderer* ren);
  /// Re-reads the props that may have moved (how: the UpdateMode) and refits their paths.
  void FindMoved(vtkOctreeCuller* self);
  /// The camera as the core's cull parameters; false (warned once) if it or the viewport is
  /// unusable, and nothing is culled.
  bool ViewOf(vtkRenderer* ren, vtkOctreeCuller* self, scenevis::culling::CullParams& params);
  /// Sorts Placements (visible placements of the instanced actor whose first slot is @p head) by
  /// depth as SortKept sorts props: they are drawn in that order.
  void SortPlacements(std::uint32_t head, const sc::CullParams& params, int style);
  /// Sorts the @p kept props at the head of the list by depth (SortingStyle @p style, 2D /
  /// unbounded props first as VTK does), KeptSlots with them.
  void SortKept(
    vtkProp** propList, std::size_t kept, const scenevis::culling::CullParams& params, int style);

  /// Front-to-back cull with occlusion (vtkOcclusionCuller): props found visible are rasterized
  /// as occluders before farther nodes are tested; last frame's visible props occlude first.
  /// Occlusion must have been made.
  void CullOccluded(vtkRenderer* ren, const sc::CullParams& params, std::size_t cacheBudget,
    double minimumPixelsPerTriangle, sc::CullStats& stats)
  {
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
    // Props a culler before this one removed are left out: not tested against the buffer (and
    // nodes stand for the props left in; not needed when the list has them all).
    occlusion.active = this->PresentSlots < this->Slots.size() ? this->Present.data() : nullptr;
    this->Bvh.cullOccluded(params, occlusion, this->Visible, &stats);
    this->LastVisible = this->Visible;
  }
};

//------------------------------------------------------------------------------
bool vtkOctreeCuller::vtkInternals::MapList(
  vtkRenderer* ren, vtkProp** propList, std::size_t n, vtkOctreeCuller* self)
{
  // A vtkInstancedActor that gained or lost placements needs other slots: rebuild.
  for (const std::uint32_t head : this->InstancedHeads)
  {
    const Slot& slot = this->Slots[head];
    const vtkIdType placements =
      static_cast<vtkInstancedActor*>(slot.Prop.GetPointer())->GetNumberOfPlacements();
    if ((slot.Placement < 0) != (placements == 0) ||
      (placements > 0 && static_cast<vtkIdType>(slot.Count) != placements))
    {
      this->RebuildRequested = true;
      break;
    }
  }
  const bool sameList = !this->RebuildRequested && n == this->LastList.size() &&
    std::equal(propList, propList + n, this->LastList.begin());
  bool rebuild = this->RebuildRequested || this->NormalConesBuilt != self->NormalConeCulling;
  if (!sameList && !rebuild)
  {
    this->ListSlots.resize(n);
    if (this->Watcher.EventsActive)
    {
      this->PrevPresent = this->Present;
    }
    std::fill(this->Present.begin(), this->Present.end(), 0);
    std::size_t present = 0;
    for (std::size_t i = 0; i < n && !rebuild; ++i)
    {
      const auto it = this->SlotOf.find(propList[i]);
      if (it == this->SlotOf.end())
      {
        rebuild = true;
      }
      else
      {
        this->ListSlots[i] = it->second;
        const std::uint32_t count = this->Slots[it->second].Count;
        present += this->Present[it->second] ? 0 : count;
        std::fill_n(this->Present.begin() + it->second, count, 1);
      }
    }
    this->PresentSlots = present;
    // Forget props that are gone once they are the majority (they are held by reference). Gone
    // from the renderer, not only from the list: a culler that runs before this one
    // (vtkPortalCuller) often hands over less than half of the props, which must not cost a
    // rebuild every frame.
    const bool rendererChanged = this->CountRendererProps(ren);
    rebuild = rebuild ||
      (this->Slots.size() > 64 && 2 * present < this->Slots.size() &&
        2 * this->SlotsInRendererCount < this->Slots.size());
    if (this->Watcher.EventsActive && !rebuild)
    {
      // A prop that leaves the list stays observed while it is in the renderer: a culler before
      // this one drops and restores hundreds of props every frame, and observing them anew and
      // re-reading their bounds each time cost more than the occlusion traversal (Freedoom MAP12
      // in 16,800 parts after vtkPortalCuller). Its events while it is out wait in DirtyAbsent.
      // A prop in the list for the first time is observed and re-read (changes made before were
      // not observed); one gone from the renderer stops being observed.
      std::vector<vtkObject*> scratch;
      for (std::uint32_t s = 0; s < this->Slots.size(); ++s)
      {
        if (!this->PrevPresent[s] && this->Present[s] && !this->Slots[s].Registered)
        {
          this->Watcher.Register(s, self->NormalConeCulling, scratch);
          this->Watcher.PolledSetChanged = true;
          this->Watcher.MarkDirty(s);
        }
        else if (rendererChanged && !this->Present[s] && !this->InRenderer[s] &&
          this->Slots[s].Registered)
        {
          this->Watcher.Unregister(s);
          this->Watcher.PolledSetChanged = true;
        }
      }
    }
  }
  if (!sameList)
  {
    this->LastList.assign(propList, propList + n);
  }
  return rebuild;
}

//------------------------------------------------------------------------------
bool vtkOctreeCuller::vtkInternals::CountRendererProps(vtkRenderer* ren)
{
  vtkPropCollection* props = ren ? ren->GetViewProps() : nullptr;
  const vtkMTimeType time = props ? props->GetMTime() : 0;
  if (time == this->ViewPropsTime && this->InRenderer.size() == this->Slots.size())
  {
    return false;
  }
  this->ViewPropsTime = time;
  this->SlotsInRendererCount = 0;
  this->InRenderer.assign(this->Slots.size(), 0);
  if (props)
  {
    vtkCollectionSimpleIterator it;
    props->InitTraversal(it);
    while (vtkProp* prop = props->GetNextProp(it))
    {
      const auto found = this->SlotOf.find(prop);
      if (found != this->SlotOf.end())
      {
        const std::uint32_t count = this->Slots[found->second].Count;
        this->SlotsInRendererCount += count;
        std::fill_n(this->InRenderer.begin() + found->second, count, 1);
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkOctreeCuller::vtkInternals::Rebuild(
  vtkRenderer* ren, vtkProp** list, std::size_t n, vtkOctreeCuller* self)
{
  // The list first (its entries' slots are ListSlots), then the renderer's other visible props.
  std::vector<vtkProp*> props(list, list + n);
  if (vtkPropCollection* viewProps = ren ? ren->GetViewProps() : nullptr)
  {
    const std::unordered_set<vtkProp*> listed(list, list + n);
    vtkCollectionSimpleIterator it;
    viewProps->InitTraversal(it);
    while (vtkProp* prop = viewProps->GetNextProp(it))
    {
      if (prop->GetVisibility() && !listed.count(prop))
      {
        props.push_back(prop);
      }
    }
  }
  vtkProp** propList = props.data();
  const std::size_t all = props.size();
  this->Watcher.UnwatchAll();
  this->Watcher.EventsActive = false;
  this->Slots.clear();
  this->SlotOf.clear();
  this->InstancedHeads.clear();
  this->Invalidated.clear();
  sc::BoxArrays boxes;
  std::vector<std::uint32_t> triangles;
  this->ListSlots.resize(n);
  // One slot per prop, per placement of a vtkInstancedActor: sized once (a slot is ~180
  // bytes; growing by doubling would hold up to twice that for 46,000 placements).
  std::size_t slots = 0;
  for (std::size_t i = 0; i < all; ++i)
  {
    auto* instanced = vtkInstancedActor::SafeDownCast(propList[i]);
    slots += instanced ? std::max<std::size_t>(1, instanced->GetNumberOfPlacements()) : 1;
  }
  if (this->Slots.capacity() > slots)
  {
    std::vector<Slot>().swap(this->Slots); // cleared above
  }
  this->Slots.reserve(slots);
  for (std::size_t i = 0; i < all; ++i)
  {
    const auto found = this->SlotOf.find(propList[i]);
    if (found != this->SlotOf.end())
    {
      if (i < n)
      {
        this->ListSlots[i] = found->second; // the same prop twice in the list
      }
      continue;
    }
    const auto s = static_cast<std::uint32_t>(this->Slots.size());
    auto* instanced = vtkInstancedActor::SafeDownCast(propList[i]);
    const vtkIdType placements = instanced ? instanced->GetNumberOfPlacements() : 0;
    // A vtkInstancedActor is one slot per placement (none: one slot, drawing nothing).
    for (vtkIdType k = 0; k < std::max<vtkIdType>(1, placements); ++k)
    {
      this->Slots.emplace_back();
      Slot& slot = this->Slots.back();
      slot.Prop = propList[i];
      slot.Placement = placements > 0 ? k : -1;
      slot.Count = k == 0 ? static_cast<std::uint32_t>(std::max<vtkIdType>(1, placements)) : 0;
      RefreshSlot(slot, this->WarnedInvalidBounds, self);
      boxes.push_back(slot.Kind == SlotKind::Tree ? ToBox(slot.Bounds) : scenevis::Box());
      triangles.push_back(slot.Triangles);
    }
    this->SlotOf.emplace(propList[i], s);
    if (i < n)
    {
      this->ListSlots[i] = s;
    }
    if (instanced)
    {
      this->InstancedHeads.push_back(s);
    }
  }
  this->Bvh.build(boxes, sc::BuildMethod::BinnedSah, 4, &triangles);
  this->LastVisible.clear(); // slot numbers changed
  if (self->NormalConeCulling)
  {
    for (std::uint32_t s = 0; s < this->Slots.size(); ++s)
    {
      if (this->Slots[s].Kind == SlotKind::Tree && this->Slots[s].Placement < 0)
      {
        this->Bvh.setNormalCone(s, ActorNormalCone(this->Slots[s].Prop));
      }
    }
    this->Bvh.refit();
  }
  this->NormalConesBuilt = self->NormalConeCulling;
  // Present: in the list (a prop only the renderer has is neither drawn nor an occluder).
  this->Present.assign(this->Slots.size(), 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t s = this->ListSlots[i];
    std::fill_n(this->Present.begin() + s, this->Slots[s].Count, 1);
  }
  this->PresentSlots = static_cast<std::size_t>(
    std::count(this->Present.begin(), this->Present.end(), static_cast<unsigned char>(1)));
  this->ViewPropsTime = 0; // the slots changed: count again
  this->MultiplierIsOne.assign(this->Slots.size(), 0);
  this->RebuildRequested = false;
  ++self->NumberOfRebuilds;
  this->Watcher.Dirty.assign(this->Slots.size(), 0);
  this->Watcher.DirtyList.clear();
  this->Watcher.DirtyAbsent.clear();
  if (self->UpdateMode == UPDATE_ON_EVENTS)
  {
    std::vector<vtkObject*> scratch;
    for (std::uint32_t s = 0; s < this->Slots.size(); ++s)
    {
      if (this->Present[s])
      {
        this->Watcher.Register(s, self->NormalConeCulling, scratch);
      }
    }
    this->Watcher.PolledSetChanged = true;
    this->Watcher.EventsActive = true;
    // Events fired while the bounds were read above (pipeline updates) are already seen.
    std::fill(this->Watcher.Dirty.begin(), this->Watcher.Dirty.end(), 0);
    this->Watcher.DirtyList.clear();
  }
}

//------------------------------------------------------------------------------
void vtkOctreeCuller::vtkInternals::FindMoved(vtkOctreeCuller* self)
{
  if (this->Watcher.EventsActive && self->UpdateMode != UPDATE_ON_EVENTS)
  {
    this->Watcher.UnwatchAll();
    this->Watcher.EventsActive = false;
  }
  std::size_t refits = 0;
  auto refresh = [&](std::uint32_t s)
  {
    Slot& slot = this->Slots[s];
    const bool changed = RefreshSlot(slot, this->WarnedInvalidBounds, self);
    if (changed)
    {
      this->Bvh.update(s, slot.Kind == SlotKind::Tree ? ToBox(slot.Bounds) : scenevis::Box());
    }
    if (self->NormalConeCulling && slot.Kind == SlotKind::Tree && slot.Placement < 0)
    {
      this->Bvh.setNormalCone(s, ActorNormalCone(slot.Prop)); // rotation keeps bounds sometimes
    }
    this->Bvh.setTriangleCount(s, slot.Triangles);
    refits += changed ? 1 : 0;
  };
  // A polled prop may have moved when its bounds differ from its slot's, or, with normal cones,
  // when it was modified (a rotation can keep the bounds).
  auto polledMoved = [this, self](std::uint32_t s)
  {
    const Slot& slot = this->Slots[s];
    double scratchBounds[6];
    const double* b = CurrentBounds(slot, scratchBounds);
    const bool same = slot.Kind == SlotKind::Tree && b && std::equal(b, b + 6, slot.Bounds);
    return !same ||
      (slot.Kind == SlotKind::Tree && self->NormalConeCulling &&
        slot.Prop->vtkObject::GetMTime() != slot.PropTime);
  };
  const std::size_t slots = this->Slots.size();
  if (self->UpdateMode == UPDATE_BOUNDS_EVERY_FRAME)
  {
    for (std::uint32_t s = 0; s < slots; ++s)
    {
      if (this->Present[s] && polledMoved(s))
      {
        refresh(s);
      }
    }
  }
  else if (self->UpdateMode == UPDATE_ON_EVENTS)
  {
    if (!this->Watcher.EventsActive)
    {
      // Switched to events: observe everything, and re-read every prop once (changes made
      // before were not observed).
      std::vector<vtkObject*> scratch;
      this->Watcher.Dirty.assign(slots, 0);
      this->Watcher.DirtyList.clear();
      this->Watcher.DirtyAbsent.clear();
      for (std::uint32_t s = 0; s < slots; ++s)
      {
        if (this->Present[s])
        {
          this->Watcher.Register(s, self->NormalConeCulling, scratch);
          this->Watcher.MarkDirty(s);
        }
      }
      this->Watcher.PolledSetChanged = true;
      this->Watcher.EventsActive = true;
    }
    // O(dirty props): re-read the props whose dependencies fired ModifiedEvent. A slot's own
    // events while its bounds are read (its pipeline updating) are absorbed (it is still
    // marked); events for other slots raised meanwhile are handled in the next round.
    // Slots out of the list are re-read when they are back (they stay marked meanwhile).
    std::vector<vtkObject*> scratch;
    auto& absent = this->Watcher.DirtyAbsent;
    std::size_t waiting = 0;
    for (const std::uint32_t s : absent)
    {
      if (this->Present[s])
      {
        this->Watcher.DirtyList.push_back(s);
      }
      else
      {
        absent[waiting++] = s;
      }
    }
    absent.resize(waiting);
    for (int round = 0; round < 4 && !this->Watcher.DirtyList.empty(); ++round)
    {
      this->Watcher.DirtyWork.swap(this->Watcher.DirtyList);
      for (const std::uint32_t s : this->Watcher.DirtyWork)
      {
        if (!this->Present[s])
        {
          absent.push_back(s);
          continue;
        }
        refresh(s);
        this->Watcher.Register(s, self->NormalConeCulling, scratch);
        this->Watcher.Dirty[s] = 0;
      }
      this->Watcher.DirtyWork.clear();
    }
    // Props events cannot cover (see the class documentation): polled like
    // UPDATE_BOUNDS_EVERY_FRAME.
    this->Watcher.UpdatePolledList();
    for (const std::uint32_t s : this->Watcher.PolledSlots)
    {
      if (this->Present[s] && polledMoved(s))
      {
        refresh(s);
        this->Watcher.Register(s, self->NormalConeCulling, scratch);
      }
    }
  }
  else if (self->UpdateMode == UPDATE_ON_MODIFIED)
  {
    for (std::uint32_t s = 0; s < slots; ++s)
    {
      Slot& slot = this->Slots[s];
      if (!this->Present[s])
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
  for (vtkProp* prop : this->Invalidated)
  {
    const auto it = this->SlotOf.find(prop);
    if (it != this->SlotOf.end())
    {
      refresh(it->second);
    }
  }
  this->Invalidated.clear();
  if (refits > 0)
  {
    this->Bvh.refit();
    self->NumberOfRefits += static_cast<vtkIdType>(refits);
    // Many moves loosen the tree; rebuild from the current boxes when it got much worse
    // (checked now and then: degradation() is O(nodes)).
    this->RefitsSinceCheck += refits;
    if (this->RefitsSinceCheck > std::max<std::size_t>(64, slots / 16))
    {
      this->RefitsSinceCheck = 0;
      this->RebuildRequested = this->Bvh.degradation() > 2.0;
    }
  }
}

//------------------------------------------------------------------------------
bool vtkOctreeCuller::vtkInternals::ViewOf(
  vtkRenderer* ren, vtkOctreeCuller* self, sc::CullParams& params)
{
  bool usable = true;
  vtkCamera* cam = ren ? ren->GetActiveCamera() : nullptr;
  int* size = ren ? ren->GetSize() : nullptr;
  if (!size || size[0] <= 0 || size[1] <= 0)
  {
    usable = false;
    if (!this->WarnedViewport)
    {
      this->WarnedViewport = true;
      vtkWarningWithObjectMacro(self, "The renderer's viewport has zero size: nothing is culled (warned once).");
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
      if (!this->WarnedCamera)
      {
        this->WarnedCamera = true;
        vtkWarningWithObjectMacro(self, "The active camera is not usable (non-finite position, focal point, "
                        "clipping range or projection): nothing is culled (warned once).");
      }
    }
    else
    {
      params.frustumCulling = self->FrustumCulling;
      params.eye = glm::dvec3(eye[0], eye[1], eye[2]);
      params.viewDirection = glm::normalize(glm::dvec3(dop[0], dop[1], dop[2]));
      params.parallel = cam->GetParallelProjection() != 0;
      params.normalConeCulling = self->NormalConeCulling;
      params.maxDistance = self->MaximumDistance >= VTK_DOUBLE_MAX
        ? std::numeric_limits<double>::infinity()
        : self->MaximumDistance;
      if (self->MinimumPixelSize > 0.0)
      {
        const double pixels = cam->GetUseHorizontalViewAngle() ? size[0] : size[1];
        params.minPixels = self->MinimumPixelSize;
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
  return usable;
}

//------------------------------------------------------------------------------
void vtkOctreeCuller::vtkInternals::SortKept(
  vtkProp** propList, std::size_t kept, const sc::CullParams& params, int style)
{
  this->Keyed.clear();
  for (std::size_t i = 0; i < kept; ++i)
  {
    const Slot& slot = this->Slots[this->KeptSlots[i]];
    double key = -VTK_DOUBLE_MAX;
    if (slot.Kind == SlotKind::Tree)
    {
      const glm::dvec3 c = ToBox(slot.Bounds).center();
      key = glm::dot(c - params.eye, params.viewDirection);
    }
    this->Keyed.emplace_back(key, static_cast<std::uint32_t>(i));
  }
  if (style == 1)
  {
    std::stable_sort(this->Keyed.begin(), this->Keyed.end(),
      [](const auto& a, const auto& b) { return a.first < b.first; });
  }
  else
  {
    std::stable_sort(this->Keyed.begin(), this->Keyed.end(),
      [](const auto& a, const auto& b) { return a.first > b.first; });
  }
  this->Unsorted.assign(propList, propList + kept);
  this->SortedSlots.resize(kept);
  for (std::size_t i = 0; i < kept; ++i)
  {
    propList[i] = this->Unsorted[this->Keyed[i].second];
    this->SortedSlots[i] = this->KeptSlots[this->Keyed[i].second];
  }
  this->KeptSlots.swap(this->SortedSlots);
}


//------------------------------------------------------------------------------
void vtkOctreeCuller::vtkInternals::SortPlacements(
  std::uint32_t head, const sc::CullParams& params, int style)
{
  this->Keyed.clear();
  for (const vtkIdType k : this->Placements)
  {
    const Slot& slot = this->Slots[head + static_cast<std::uint32_t>(k)];
    double key = -VTK_DOUBLE_MAX;
    if (slot.Kind == SlotKind::Tree)
    {
      key = glm::dot(ToBox(slot.Bounds).center() - params.eye, params.viewDirection);
    }
    this->Keyed.emplace_back(style == 1 ? key : -key, static_cast<std::uint32_t>(k));
  }
  std::stable_sort(this->Keyed.begin(), this->Keyed.end(),
    [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < this->Keyed.size(); ++i)
  {
    this->Placements[i] = static_cast<vtkIdType>(this->Keyed[i].second);
  }
}

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
  return static_cast<vtkIdType>(this->Internals->Watcher.Watches.size());
}

vtkIdType vtkOctreeCuller::GetNumberOfPolledProps() const
{
  return this->Internals->Watcher.EventsActive ? static_cast<vtkIdType>(this->Internals->Watcher.PolledSlots.size())
                                       : 0;
}

//------------------------------------------------------------------------------
void vtkOctreeCuller::InvalidateAllProps()
{
  this->Internals->RebuildRequested = true;
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
  if (in.MapList(ren, propList, n, this))
  {
    in.Rebuild(ren, propList, n, this);
  }
  else
  {
    // --- 2. Find moved props (UpdateMode) and refit their paths. ------------------------------
    in.FindMoved(this);
  }

  // --- 3. The view. ----------------------------------------------------------------------------
  sc::CullParams params;
  const bool usable = in.ViewOf(ren, this, params);

  // --- 4. Cull. ----------------------------------------------------------------------------------
  in.Drawn.assign(in.Slots.size(), 0);
  if (usable)
  {
    sc::CullStats stats;
    if (this->OcclusionCulling)
    {
      if (!in.Occlusion)
      {
        in.Occlusion.reset(new vtkOccluderRasterizer);
      }
      vtkOccluderRasterizer& raster = *in.Occlusion;
      raster.Recording().BeforeCull(this->OcclusionRecordFile, raster.Buffer(), this);
      in.CullOccluded(
        ren, params, this->OccluderCacheBudget, this->OccluderMinimumPixelsPerTriangle, stats);
      raster.Recording().AfterCull(this->OcclusionRecordFile, this);
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
    // By reason: over all props the hierarchy knows (the renderer's: equal to this list's unless
    // another culler ran first and passed a subset), over this list's with occlusion (its
    // traversal leaves the others out). Triangles drawn: this list's (below).
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
  in.Keep.resize(n);
  in.KeptSlots.clear();
  vtkIdType trianglesDrawn = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t s = in.ListSlots[i];
    bool drawn = in.Drawn[s] != 0;
    trianglesDrawn += drawn && in.Slots[s].Placement < 0 ? in.Slots[s].Triangles : 0;
    if (in.Slots[s].Placement >= 0)
    {
      // A vtkInstancedActor: drawn while any placement is, and told which.
      in.Placements.clear();
      for (std::uint32_t k = 0; k < in.Slots[s].Count; ++k)
      {
        if (in.Drawn[s + k])
        {
          in.Placements.push_back(static_cast<vtkIdType>(k));
          trianglesDrawn += in.Slots[s + k].Triangles;
        }
      }
      if (this->SortingStyle != 0 && usable)
      {
        in.SortPlacements(s, params, this->SortingStyle);
      }
      static_cast<vtkInstancedActor*>(propList[i])
        ->SetVisiblePlacements(in.Placements.data(), static_cast<vtkIdType>(in.Placements.size()));
      drawn = !in.Placements.empty();
    }
    in.Keep[i] = drawn ? 1 : 0;
    if (drawn)
    {
      in.KeptSlots.push_back(s);
    }
  }
  const auto kept = static_cast<std::size_t>(this->CompactPropList(propList, listLength, in.Keep.data()));
  this->NumberOfPropsCulled = static_cast<vtkIdType>(n - kept);
  this->NumberOfPropsDrawn = static_cast<vtkIdType>(kept);
  if (usable)
  {
    this->NumberOfTrianglesDrawn = trianglesDrawn;
  }
  listLength = static_cast<int>(kept);

  // --- 6. Optional depth sort of the drawn props (2D / unbounded props first, as VTK does). -----
  if (this->SortingStyle != 0 && usable && kept > 1)
  {
    in.SortKept(propList, kept, params, this->SortingStyle);
  }

  // --- 7. Render-time multipliers (vtkCuller contract). ---------------------------------------
  const double total = this->SumRenderTimeMultipliers(ren, propList, listLength, initialized,
    in.MultiplierIsOne.data(), in.KeptSlots.data());
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
  os << indent << "Objects observed: " << this->Internals->Watcher.Watches.size() << "\n";
  os << indent << "NumberOfNodesVisited: " << this->NumberOfNodesVisited << "\n";
  os << indent << "NumberOfPropsTested: " << this->NumberOfPropsTested << "\n";
  os << indent << "NumberOfPropsCulled: " << this->NumberOfPropsCulled << "\n";
  os << indent << "NumberOfPropsDrawn: " << this->NumberOfPropsDrawn << "\n";
  os << indent << "NumberOfTrianglesDrawn: " << this->NumberOfTrianglesDrawn << "\n";
  os << indent << "NumberOfRebuilds: " << this->NumberOfRebuilds << "\n";
  os << indent << "NumberOfRefits: " << this->NumberOfRefits << "\n";
}

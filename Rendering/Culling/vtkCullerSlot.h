/**
 * @file vtkCullerSlot.h
 * @brief What vtkOctreeCuller knows about one prop (or one placement of a vtkInstancedActor),
 * and how it is read from VTK.
 *
 * Private to SceneVis::RenderingCulling: the hierarchy's objects are slots; a slot holds the
 * prop by reference, its box as last read, and the modification times and pointers that tell
 * the update modes whether the box may have changed (see vtkOctreeCuller.h, "Updates").
 */

#ifndef vtkCullerSlot_h
#define vtkCullerSlot_h

#include "vtkMapper.h"
#include "vtkProp.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "scenevis/Bvh.h"
#include "scenevis/NormalCone.h"

#include <cstdint>
#include <vector>

class vtkDataObject;
class vtkObject;

namespace vtkCullerSlots
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
const double* CurrentBounds(const Slot& slot, double scratch[6]);

/// Whether @p b (VTK's xmin, xmax, ymin, ...) is finite and not empty.
bool FiniteBounds(const double* b);

/// @p b as the core's box.
scenevis::Box ToBox(const double* b);

/// Re-read what the hierarchy needs to know about @p slot's prop; returns whether its box (or
/// kind) changed. Props with unusable bounds warn once, through @p warnedInvalid and @p self.
bool RefreshSlot(Slot& slot, bool& warnedInvalid, vtkObject* self);

/// World-space normal cone of an actor that is drawn with back-face culling; none() when the
/// actor does not qualify (see vtkOctreeCuller.h) or its data is not polygons only.
scenevis::culling::NormalCone ActorNormalCone(vtkProp* prop);
} // namespace vtkCullerSlots

#endif

#include "vtkPortalCuller.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "scenevis/PortalGraph.h"
#include "scenevis/PortalPvs.h"
#include "scenevis/PortalTraversal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace sp = scenevis::portals;

vtkStandardNewMacro(vtkPortalCuller);

namespace
{
struct Slot
{
  vtkProp* Prop = nullptr;
  /// Room ids of the prop's cells (empty: no room, frustum test only).
  std::vector<int> Rooms;
  /// 2D prop or bounds that cannot be tested: never culled.
  bool Never = false;
  scenevis::Box Bounds;
  vtkIdType Triangles = 0;
};

const char* FallbackText(sp::Fallback f)
{
  switch (f)
  {
    case sp::Fallback::EyeInNoRoom:
      return "eye in no room";
    case sp::Fallback::LeakyRoom:
      return "leaky room (a portal names a missing room)";
    case sp::Fallback::ParallelProjection:
      return "parallel projection with the near plane in the building";
    case sp::Fallback::InvalidView:
      return "unusable camera";
    case sp::Fallback::None:
    default:
      return "";
  }
}
} // namespace

class vtkPortalCuller::vtkInternals
{
public:
  vtkSmartPointer<vtkPolyData> Portals;
  std::unordered_map<vtkProp*, int> ExplicitRooms;
  std::unordered_map<vtkProp*, vtkSmartPointer<vtkDataArray>> ExplicitCellRooms;
  bool Dirty = true;
  vtkMTimeType PropsTime = 0;
  vtkMTimeType PortalsTime = 0;
  vtkWeakPointer<vtkRenderer> Renderer;

  std::vector<Slot> Slots;
  std::unordered_map<vtkProp*, std::size_t> SlotOf;
  // The last list handed to Cull() (before compaction) and each entry's slot (kNoSlot: none):
  // the renderer hands the same list frame after frame, so its props are looked up only when it
  // changes or the slots are rebuilt.
  static constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);
  std::vector<vtkProp*> LastList;
  std::vector<std::size_t> ListSlots;
  /// Per entry of LastList: drawn whatever the traversal finds (no slot, or a prop that cannot
  /// be tested), and its triangles.
  std::vector<unsigned char> ListAlways;
  std::vector<vtkIdType> ListTriangles;
  vtkIdType ListTrianglesTotal = 0;

  // The props of each room: per node of the graph the slots with a cell in that room (CSR), and
  // the slots that the frustum alone tests (no room, or a room id the graph does not know).
  // A frame tests the props of the rooms the traversal reached, not every prop of the list;
  // built at the first cull after the slots.
  bool RoomSlotsReady = false;
  std::vector<std::size_t> NodeSlotStart, NodeSlots, FrustumSlots;
  std::vector<std::uint32_t> SlotVisibleFrame; // per slot: the last frame it was found visible
  std::uint32_t Frame = 0;

  void BuildRoomSlots();
  /// Marks the slots the traversal finds visible this frame (SlotVisibleFrame == Frame).
  void MarkVisibleSlots();
  scenevis::PolygonMesh Mesh;
  std::vector<std::int32_t> MeshRooms;
  sp::PortalGraph Graph;
  bool HaveGraph = false;
  std::string Report;
  sp::PortalPvs Pvs;
  sp::PortalTraversal Traversal;
  std::vector<unsigned char> Keep; // per list entry: drawn
  std::string Fallback;
  bool WarnedNoPortals = false;
  bool WarnedArrays = false;
  bool WarnedCamera = false;
  bool WarnedParallel = false;
};

//------------------------------------------------------------------------------
void vtkPortalCuller::vtkInternals::BuildRoomSlots()
{
  const auto nodes = static_cast<std::size_t>(this->Graph.nodeCount());
  this->NodeSlotStart.assign(nodes + 1, 0);
  this->NodeSlots.clear();
  this->FrustumSlots.clear();
  // Two passes: count per node, then place (slots in ascending order within a node).
  for (int pass = 0; pass < 2; ++pass)
  {
    std::vector<std::size_t> next;
    if (pass == 1)
    {
      for (std::size_t k = 0; k < nodes; ++k)
      {
        this->NodeSlotStart[k + 1] += this->NodeSlotStart[k];
      }
      next.assign(this->NodeSlotStart.begin(), this->NodeSlotStart.end() - 1);
      this->NodeSlots.resize(this->NodeSlotStart[nodes]);
    }
    for (std::size_t i = 0; i < this->Slots.size(); ++i)
    {
      const Slot& slot = this->Slots[i];
      if (slot.Never)
      {
        continue; // drawn every frame (ListAlways)
      }
      bool frustum = slot.Rooms.empty();
      for (const int room : slot.Rooms)
      {
        const std::int32_t node = this->Graph.nodeOf(room);
        if (node < 0)
        {
          frustum = true; // boxVisible(-1, ...): the frustum test
        }
        else if (pass == 0)
        {
          ++this->NodeSlotStart[static_cast<std::size_t>(node) + 1];
        }
        else
        {
          this->NodeSlots[next[static_cast<std::size_t>(node)]++] = i;
        }
      }
      if (frustum && pass == 1)
      {
        this->FrustumSlots.push_back(i);
      }
    }
  }
  this->SlotVisibleFrame.assign(this->Slots.size(), 0);
  this->Frame = 0;
  this->RoomSlotsReady = true;
}

//------------------------------------------------------------------------------
void vtkPortalCuller::vtkInternals::MarkVisibleSlots()
{
  if (++this->Frame == 0) // wrapped: stamps of 2^32 frames ago would read as this frame's
  {
    std::fill(this->SlotVisibleFrame.begin(), this->SlotVisibleFrame.end(), 0);
    this->Frame = 1;
  }
  const std::uint32_t frame = this->Frame;
  for (const std::int32_t node : this->Traversal.visibleNodes())
  {
    const auto k = static_cast<std::size_t>(node);
    if (node < 0 || k + 1 >= this->NodeSlotStart.size())
    {
      continue;
    }
    for (std::size_t j = this->NodeSlotStart[k]; j < this->NodeSlotStart[k + 1]; ++j)
    {
      const std::size_t i = this->NodeSlots[j];
      if (this->SlotVisibleFrame[i] != frame &&
        this->Traversal.boxVisible(node, this->Slots[i].Bounds))
      {
        this->SlotVisibleFrame[i] = frame;
      }
    }
  }
  for (const std::size_t i : this->FrustumSlots)
  {
    if (this->SlotVisibleFrame[i] != frame && this->Traversal.boxVisible(-1, this->Slots[i].Bounds))
    {
      this->SlotVisibleFrame[i] = frame;
    }
  }
}

//------------------------------------------------------------------------------
vtkPortalCuller::vtkPortalCuller()
  : Internals(new vtkInternals)
{
  this->SetRoomIdArrayName("RoomId");
}

//------------------------------------------------------------------------------
vtkPortalCuller::~vtkPortalCuller()
{
  this->SetRoomIdArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkPortalCuller::SetPortals(vtkPolyData* portals)
{
  if (this->Internals->Portals.Get() != portals)
  {
    this->Internals->Portals = portals;
    this->Internals->Dirty = true;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkPolyData* vtkPortalCuller::GetPortals()
{
  return this->Internals->Portals;
}

//------------------------------------------------------------------------------
void vtkPortalCuller::SetPropRoom(vtkProp* prop, int room)
{
  if (prop)
  {
    this->Internals->ExplicitRooms[prop] = room;
    this->Internals->Dirty = true;
  }
}

//------------------------------------------------------------------------------
void vtkPortalCuller::SetPropCellRooms(vtkProp* prop, vtkDataArray* rooms)
{
  if (!prop)
  {
    return;
  }
  if (rooms)
  {
    this->Internals->ExplicitCellRooms[prop] = rooms;
  }
  else
  {
    this->Internals->ExplicitCellRooms.erase(prop);
  }
  this->Internals->Dirty = true;
}

//------------------------------------------------------------------------------
void vtkPortalCuller::RemovePropRoom(vtkProp* prop)
{
  const bool removed =
    this->Internals->ExplicitRooms.erase(prop) + this->Internals->ExplicitCellRooms.erase(prop) > 0;
  this->Internals->Dirty = removed || this->Internals->Dirty;
}

//------------------------------------------------------------------------------
void vtkPortalCuller::RemoveAllPropRooms()
{
  this->Internals->ExplicitRooms.clear();
  this->Internals->ExplicitCellRooms.clear();
  this->Internals->Dirty = true;
}

//------------------------------------------------------------------------------
void vtkPortalCuller::InvalidateScene()
{
  this->Internals->Dirty = true;
}

//------------------------------------------------------------------------------
const char* vtkPortalCuller::GetFallbackReason() const
{
  return this->Internals->Fallback.c_str();
}

//------------------------------------------------------------------------------
const char* vtkPortalCuller::GetGraphReport() const
{
  return this->Internals->Report.c_str();
}

namespace
{
/// Adds the polygons of @p pd (world coordinates through @p m) to @p mesh with their rooms:
/// @p fixedRoom, or the cell values of @p cellRooms (cell ids in vtkPolyData order).
void AddPolygons(vtkPolyData* pd, vtkMatrix4x4* m, int fixedRoom, vtkDataArray* cellRooms,
  scenevis::PolygonMesh& mesh, std::vector<std::int32_t>& rooms, vtkIdType& triangles)
{
  vtkPoints* points = pd->GetPoints();
  if (!points)
  {
    return;
  }
  const vtkIdType firstPoly = pd->GetNumberOfVerts() + pd->GetNumberOfLines();
  const auto base = static_cast<std::uint32_t>(mesh.points.size());
  const vtkIdType n = points->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[4] = { 0, 0, 0, 1 };
    points->GetPoint(i, p);
    double q[4];
    m->MultiplyPoint(p, q);
    mesh.addPoint(glm::dvec3(q[0], q[1], q[2]) / q[3]);
  }
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  std::vector<std::uint32_t> local;
  vtkIdType cell = firstPoly;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++cell)
  {
    if (npts < 3)
    {
      continue;
    }
    triangles += npts - 2;
    local.clear();
    for (vtkIdType k = 0; k < npts; ++k)
    {
      local.push_back(base + static_cast<std::uint32_t>(ids[k]));
    }
    mesh.addPolygon(local.data(), local.size());
    rooms.push_back(cellRooms ? static_cast<std::int32_t>(cellRooms->GetTuple1(cell)) : fixedRoom);
  }
  vtkCellArray* strips = pd->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, ids);)
  {
    triangles += std::max<vtkIdType>(npts - 2, 0);
  }
}

bool FiniteBounds(const double* b)
{
  return b && std::all_of(b, b + 6, [](double v) { return std::isfinite(v); }) &&
    vtkMath::AreBoundsInitialized(b);
}
} // namespace


//------------------------------------------------------------------------------
double vtkPortalCuller::Cull(
  vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized)
{
  const auto start = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  this->NumberOfRoomsVisited = this->NumberOfPortalsTraversed = 0;
  this->NumberOfPropsDrawn = this->NumberOfPropsCulled = 0;
  this->NumberOfTrianglesDrawn = this->NumberOfTrianglesTotal = 0;
  this->FrustumOnly = true;
  in.Fallback.clear();
  if (!propList || listLength <= 0)
  {
    listLength = std::max(listLength, 0);
    initialized = 1;
    return 0.0;
  }
  const auto n = static_cast<std::size_t>(listLength);

  // --- 1. Scene and view. --------------------------------------------------------------------
  bool usable = this->Mode != MODE_OFF && ren && this->EnsureScene(ren);
  if (this->Mode == MODE_OFF)
  {
    in.Fallback = "mode off";
  }
  else if (!usable)
  {
    in.Fallback = "no usable portals";
  }
  sp::PortalView view;
  if (usable)
  {
    vtkCamera* cam = ren->GetActiveCamera();
    const int* size = ren->GetSize();
    const double aspect = ren->GetTiledAspectRatio();
    bool ok = cam && size && size[0] > 0 && size[1] > 0 && std::isfinite(aspect) && aspect > 0.0;
    if (ok)
    {
      double eye[3];
      cam->GetPosition(eye);
      const double* range = cam->GetClippingRange();
      ok = std::isfinite(eye[0]) && std::isfinite(eye[1]) && std::isfinite(eye[2]) &&
        std::isfinite(range[0]) && std::isfinite(range[1]) && range[1] > range[0];
      if (ok)
      {
        vtkMatrix4x4* m = cam->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
        view = sp::PortalView::fromRowMajor(
          &m->GetData()[0], glm::dvec3(eye[0], eye[1], eye[2]), cam->GetParallelProjection() != 0);
      }
    }
    if (!ok)
    {
      usable = false;
      in.Fallback = "unusable camera or viewport";
      if (!in.WarnedCamera)
      {
        in.WarnedCamera = true;
        vtkWarningMacro("The active camera or the viewport is not usable (non-finite position or "
                        "clipping range, zero size): nothing is culled (warned once).");
      }
    }
  }

  // --- 2. Traverse. --------------------------------------------------------------------------
  if (usable)
  {
    sp::TraversalOptions options;
    options.mode = this->Mode == MODE_SCREEN_RECTANGLES ? sp::NarrowingMode::ScreenRectangles
                                                        : sp::NarrowingMode::ExactFrustum;
    options.outside = this->OutsidePolicy == OUTSIDE_FRUSTUM_ONLY ? sp::OutsidePolicy::FrustumOnly
                                                                  : sp::OutsidePolicy::ExteriorPortals;
    if (this->Mode == MODE_PVS)
    {
      if (in.Pvs.empty() || in.Pvs.fingerprint() != in.Graph.fingerprint())
      {
        this->ComputePVSOfScene(false);
      }
      in.Traversal.runPvs(in.Graph, in.Pvs, view, options);
    }
    else
    {
      in.Traversal.run(in.Graph, view, options);
    }
    const sp::FrameStats& s = in.Traversal.stats();
    this->FrustumOnly = s.fallback != sp::Fallback::None;
    in.Fallback = FallbackText(s.fallback);
    this->NumberOfRoomsVisited = static_cast<int>(s.roomsVisited);
    this->NumberOfPortalsTraversed = static_cast<int>(s.portalsTraversed);
    if (s.fallback == sp::Fallback::ParallelProjection && !in.WarnedParallel)
    {
      in.WarnedParallel = true;
      vtkWarningMacro("Parallel projection whose near plane touches the building's bounds (or "
                      "the frustum-only outside policy): its rays may start in several rooms or "
                      "inside walls, so portals are not used and only the view frustum culls "
                      "(warned once). Parallel views from outside the building are culled "
                      "through its exterior portals.");
    }
  }

  // --- 3. Drawn props first (relative order kept), culled ones after. ------------------------
  if (n != in.LastList.size() || !std::equal(propList, propList + n, in.LastList.begin()))
  {
    in.LastList.assign(propList, propList + n);
    in.ListSlots.resize(n);
    in.ListAlways.resize(n);
    in.ListTriangles.resize(n);
    in.ListTrianglesTotal = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const auto found = in.SlotOf.find(propList[i]);
      const bool known = found != in.SlotOf.end();
      in.ListSlots[i] = known ? found->second : vtkInternals::kNoSlot;
      in.ListAlways[i] = !known || in.Slots[found->second].Never ? 1 : 0;
      in.ListTriangles[i] = known ? in.Slots[found->second].Triangles : 0;
      in.ListTrianglesTotal += in.ListTriangles[i];
    }
  }
  this->NumberOfTrianglesTotal = in.ListTrianglesTotal;
  in.Keep.resize(n);
  if (usable && !this->FrustumOnly)
  {
    // The props of the rooms reached, then one stamp comparison per entry of the list.
    if (!in.RoomSlotsReady)
    {
      in.BuildRoomSlots();
    }
    in.MarkVisibleSlots();
    for (std::size_t i = 0; i < n; ++i)
    {
      in.Keep[i] = in.ListAlways[i] || in.SlotVisibleFrame[in.ListSlots[i]] == in.Frame ? 1 : 0;
    }
  }
  else
  {
    // Everything through the frustum (a fallback: every room counts as reached), or nothing
    // culled.
    for (std::size_t i = 0; i < n; ++i)
    {
      in.Keep[i] =
        in.ListAlways[i] || !usable || in.Traversal.boxVisible(-1, in.Slots[in.ListSlots[i]].Bounds)
        ? 1
        : 0;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    this->NumberOfTrianglesDrawn += in.Keep[i] ? in.ListTriangles[i] : 0;
  }
  const int kept = this->CompactPropList(propList, listLength, in.Keep.data());
  this->NumberOfPropsCulled = listLength - kept;
  this->NumberOfPropsDrawn = kept;
  listLength = kept;

  // --- 4. Render-time multipliers (vtkCuller contract). ------------------------------------
  const double total = this->SumRenderTimeMultipliers(ren, propList, kept, initialized);
  this->LastCullTime =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return total;
}

//------------------------------------------------------------------------------
// (Re)build the slots, the room geometry and the portal graph when the renderer's props, the
// portals or the explicit rooms changed.
bool vtkPortalCuller::EnsureScene(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  const char* arrayName = this->RoomIdArrayName ? this->RoomIdArrayName : "";
  vtkPropCollection* props = ren->GetViewProps();
  const vtkMTimeType propsTime = props->GetMTime();
  const vtkMTimeType portalsTime = in.Portals ? in.Portals->GetMTime() : 0;
  if (!in.Dirty && in.Renderer.Get() == ren && propsTime == in.PropsTime &&
    portalsTime == in.PortalsTime)
  {
    return in.HaveGraph;
  }
  in.Dirty = false;
  in.Renderer = ren;
  in.PropsTime = propsTime;
  in.PortalsTime = portalsTime;
  in.Slots.clear();
  in.SlotOf.clear();
  in.LastList.clear(); // its slots are gone
  in.RoomSlotsReady = false;
  in.Mesh = scenevis::PolygonMesh();
  in.MeshRooms.clear();
  in.HaveGraph = false;
  in.Report.clear();

  // Props: room ids, bounds, room polygons.
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (in.SlotOf.count(prop))
    {
      continue;
    }
    Slot slot;
    slot.Prop = prop;
    const double* b = prop->GetBounds(); // also brings the mapper's input up to date
    if (!FiniteBounds(b))
    {
      slot.Never = true;
    }
    else
    {
      slot.Bounds.extend(glm::dvec3(b[0], b[2], b[4]));
      slot.Bounds.extend(glm::dvec3(b[1], b[3], b[5]));
    }
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    vtkPolyData* pd = actor && actor->GetMapper()
      ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0))
      : nullptr;
    const auto explicitRoom = in.ExplicitRooms.find(prop);
    int fixedRoom = 0;
    bool haveFixed = false;
    vtkDataArray* cellRooms = nullptr;
    const auto explicitCells = in.ExplicitCellRooms.find(prop);
    if (explicitRoom != in.ExplicitRooms.end())
    {
      fixedRoom = explicitRoom->second;
      haveFixed = true;
    }
    else if (explicitCells != in.ExplicitCellRooms.end())
    {
      vtkDataArray* cells = explicitCells->second;
      if (pd && cells->GetNumberOfComponents() == 1 &&
        cells->GetNumberOfTuples() == pd->GetNumberOfCells())
      {
        cellRooms = cells;
      }
      else
      {
        in.Report += "warning: a prop's cell rooms (SetPropCellRooms) have " +
          std::to_string(cells->GetNumberOfTuples()) + " values for " +
          std::to_string(pd ? pd->GetNumberOfCells() : 0) +
          " cells: ignored, the prop is only frustum-culled\n";
      }
    }
    else if (pd && *arrayName)
    {
      vtkDataArray* field = pd->GetFieldData()->GetArray(arrayName);
      vtkDataArray* cells = pd->GetCellData()->GetArray(arrayName);
      if (field && field->GetNumberOfTuples() >= 1 && field->GetNumberOfComponents() == 1)
      {
        fixedRoom = static_cast<int>(field->GetTuple1(0));
        haveFixed = true;
      }
      else if (cells && cells->GetNumberOfComponents() == 1 &&
        cells->GetNumberOfTuples() == pd->GetNumberOfCells())
      {
        cellRooms = cells;
      }
    }
    if (haveFixed)
    {
      slot.Rooms.push_back(fixedRoom);
    }
    else if (cellRooms)
    {
      std::set<int> distinct;
      for (vtkIdType c = 0; c < cellRooms->GetNumberOfTuples(); ++c)
      {
        distinct.insert(static_cast<int>(cellRooms->GetTuple1(c)));
      }
      slot.Rooms.assign(distinct.begin(), distinct.end());
    }
    if (pd && actor)
    {
      if (haveFixed || cellRooms)
      {
        AddPolygons(pd, actor->GetMatrix(), fixedRoom, cellRooms, in.Mesh, in.MeshRooms,
          slot.Triangles);
      }
      else
      {
        scenevis::PolygonMesh unused;
        std::vector<std::int32_t> unusedRooms;
        AddPolygons(pd, actor->GetMatrix(), -1, nullptr, unused, unusedRooms, slot.Triangles);
      }
    }
    in.SlotOf.emplace(prop, in.Slots.size());
    in.Slots.push_back(std::move(slot));
  }

  // Portals.
  vtkPolyData* portals = in.Portals;
  if (!portals || portals->GetNumberOfPolys() == 0)
  {
    if (!in.WarnedNoPortals)
    {
      in.WarnedNoPortals = true;
      vtkWarningMacro("No portals (SetPortals() with polygons): nothing is culled (warned once).");
    }
    return false;
  }
  vtkDataArray* roomA = portals->GetCellData()->GetArray("RoomA");
  vtkDataArray* roomB = portals->GetCellData()->GetArray("RoomB");
  if (!roomA || !roomB || roomA->GetNumberOfTuples() != portals->GetNumberOfCells() ||
    roomB->GetNumberOfTuples() != portals->GetNumberOfCells())
  {
    if (!in.WarnedArrays)
    {
      in.WarnedArrays = true;
      vtkWarningMacro("The portals need integer cell-data arrays \"RoomA\" and \"RoomB\" with one value per "
        "cell: nothing is culled (warned once).");
    }
    return false;
  }
  sp::CellSceneInput input;
  input.mesh = &in.Mesh;
  input.roomOfPolygon = in.MeshRooms;
  const vtkIdType firstPoly = portals->GetNumberOfVerts() + portals->GetNumberOfLines();
  if (firstPoly > 0 || portals->GetNumberOfStrips() > 0)
  {
    in.Report += "warning: the portals' vertices, lines and strips are ignored (polygons only)\n";
  }
  vtkCellArray* polys = portals->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType cell = firstPoly;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++cell)
  {
    sp::PortalDesc d;
    for (vtkIdType k = 0; k < npts; ++k)
    {
      double p[3];
      portals->GetPoint(ids[k], p);
      d.polygon.emplace_back(p[0], p[1], p[2]);
    }
    d.roomA = static_cast<std::int32_t>(roomA->GetTuple1(cell));
    d.roomB = static_cast<std::int32_t>(roomB->GetTuple1(cell));
    input.portals.push_back(std::move(d));
  }
  sp::PortalGraphReport report;
  in.Graph = sp::PortalGraph::build(input, &report);
  in.Report += report.summary();
  if (report.errors() + report.warnings() > 0)
  {
    vtkWarningMacro("Portal graph: " << report.errors() << " errors, " << report.warnings()
                       << " warnings (culling stays conservative):\n"
                       << report.summary());
  }
  if (!in.Pvs.empty() && in.Pvs.fingerprint() != in.Graph.fingerprint())
  {
    in.Pvs = sp::PortalPvs();
  }
  in.HaveGraph = true;
  this->NumberOfRooms = in.Graph.roomCount();
  return true;
}

//------------------------------------------------------------------------------
bool vtkPortalCuller::ComputePVS(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  if (!ren || !this->EnsureScene(ren))
  {
    vtkWarningMacro("ComputePVS: no usable scene (renderer and portals needed).");
    return false;
  }
  this->NumberOfRooms = in.Graph.roomCount();
  return this->ComputePVSOfScene(true);
}

//------------------------------------------------------------------------------
bool vtkPortalCuller::ComputePVSOfScene(bool progressEvents)
{
  vtkInternals& in = *this->Internals;
  sp::PvsOptions options;
  options.method = this->PVSMethod == PVS_SEPARATING_PLANES ? sp::PvsMethod::SeparatingPlanes
                                                            : sp::PvsMethod::PortalFlow;
  options.budgetSeconds = this->PVSBudgetSeconds;
  if (progressEvents)
  {
    options.progress = [this](double fraction)
    {
      this->InvokeEvent(vtkCommand::ProgressEvent, &fraction);
      return true;
    };
  }
  sp::PvsStats stats;
  const auto start = std::chrono::steady_clock::now();
  in.Pvs = sp::PortalPvs::compute(in.Graph, options, &stats);
  this->PVSComputeTime =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  this->PVSAverageSetSize = stats.averageSetSize;
  this->PVSDegradedPortals = static_cast<vtkIdType>(stats.degradedPortals);
  this->PVSBudgetExceeded = stats.budgetExceeded;
  return !in.Pvs.empty();
}

//------------------------------------------------------------------------------
bool vtkPortalCuller::SavePVS(const char* fileName)
{
  vtkInternals& in = *this->Internals;
  if (!fileName || in.Pvs.empty())
  {
    vtkWarningMacro("SavePVS: no PVS computed yet, or no file name.");
    return false;
  }
  std::string error;
  if (!in.Pvs.save(fileName, &error))
  {
    vtkWarningMacro("SavePVS: " << error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkPortalCuller::LoadPVS(vtkRenderer* ren, const char* fileName)
{
  vtkInternals& in = *this->Internals;
  if (!fileName || !ren || !this->EnsureScene(ren))
  {
    vtkWarningMacro("LoadPVS: no usable scene (renderer and portals needed) or no file name.");
    return false;
  }
  std::string error;
  if (!sp::PortalPvs::load(fileName, in.Graph, in.Pvs, &error))
  {
    vtkWarningMacro("LoadPVS: " << error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkPortalCuller::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const char* modes[] = { "off", "screen rectangles", "exact frustum", "pvs" };
  os << indent << "Mode: " << modes[this->Mode] << "\n";
  os << indent << "PVSMethod: "
     << (this->PVSMethod == PVS_SEPARATING_PLANES ? "separating planes" : "portal flow") << "\n";
  os << indent << "PVSBudgetSeconds: " << this->PVSBudgetSeconds << "\n";
  os << indent << "PVSComputeTime: " << this->PVSComputeTime << " ms\n";
  os << indent << "PVSAverageSetSize: " << this->PVSAverageSetSize << "\n";
  os << indent << "PVSDegradedPortals: " << this->PVSDegradedPortals
     << (this->PVSBudgetExceeded ? " (budget exceeded)" : "") << "\n";
  os << indent << "OutsidePolicy: "
     << (this->OutsidePolicy == OUTSIDE_FRUSTUM_ONLY ? "frustum only" : "exterior portals") << "\n";
  os << indent << "RoomIdArrayName: " << (this->RoomIdArrayName ? this->RoomIdArrayName : "(none)")
     << "\n";
  os << indent << "Portals: " << this->Internals->Portals.Get() << "\n";
  os << indent << "NumberOfRooms: " << this->NumberOfRooms << "\n";
  os << indent << "NumberOfRoomsVisited: " << this->NumberOfRoomsVisited << "\n";
  os << indent << "NumberOfPortalsTraversed: " << this->NumberOfPortalsTraversed << "\n";
  os << indent << "NumberOfPropsDrawn: " << this->NumberOfPropsDrawn << "\n";
  os << indent << "NumberOfPropsCulled: " << this->NumberOfPropsCulled << "\n";
  os << indent << "NumberOfTrianglesDrawn: " << this->NumberOfTrianglesDrawn << "\n";
  os << indent << "LastCullTime: " << this->LastCullTime << " ms\n";
  os << indent << "FrustumOnly: " << this->FrustumOnly << " (" << this->Internals->Fallback
     << ")\n";
}

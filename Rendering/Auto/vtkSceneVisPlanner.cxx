#include "vtkSceneVisPlanner.h"

#include "vtkActor.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkChunkedPolyDataMapper.h"
#include "vtkCommand.h"
#include "vtkCullerCollection.h"
#include "vtkFrustumCoverageCuller.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOcclusionCuller.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

vtkStandardNewMacro(vtkSceneVisPlanner);

namespace
{
/// What the planner knows of one actor, and the modification times it was read at.
struct ActorEntry
{
  vtkActor* Actor = nullptr;
  vtkMapper* Mapper = nullptr; ///< the application's mapper (not a swapped-in one)
  vtkDataObject* Input = nullptr;
  vtkMTimeType ActorTime = 0;
  vtkMTimeType MapperTime = 0;
  vtkMTimeType InputTime = 0;
  bool Counted = false; ///< a polydata mapper with input: part of the facts
  vtkIdType Polygons = 0;
  vtkIdType Triangles = 0;
  vtkIdType TranslucentPolygons = 0;
  vtkScenePlanPartBox Box;
};

/// A mapper the planner put on an application's actor, and the actor's own.
struct MapperSwap
{
  vtkWeakPointer<vtkActor> Actor;
  vtkSmartPointer<vtkMapper> Original;
  vtkSmartPointer<vtkBSPSortedPolyDataMapper> Sorted;  ///< kept for re-use (its tree)
  vtkSmartPointer<vtkChunkedPolyDataMapper> Chunked;   ///< kept for re-use (its chunks)
  vtkMapper* Installed = nullptr;                      ///< Sorted, Chunked or nullptr
  vtkMTimeType CopiedTime = 0;                         ///< Original's MTime when copied
};

vtkIdType TrianglesOf(vtkCellArray* cells)
{
  // Fan triangulation: n - 2 triangles per polygon or strip of n points.
  return cells ? std::max<vtkIdType>(
                   0, cells->GetNumberOfConnectivityIds() - 2 * cells->GetNumberOfCells())
               : 0;
}

/// Cells of @p pd drawn translucent by @p mapper through directly coloured RGBA scalars.
vtkIdType TranslucentByScalars(vtkMapper* mapper, vtkPolyData* pd, vtkIdType polygons)
{
  if (!mapper->GetScalarVisibility() || polygons == 0)
    return 0;
  int cellFlag = 0;
  vtkAbstractArray* scalars = vtkAbstractMapper::GetAbstractScalars(pd, mapper->GetScalarMode(),
    mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
  if (!scalars)
    return 0;
  auto* colors = vtkUnsignedCharArray::SafeDownCast(scalars);
  if (colors && colors->GetNumberOfComponents() == 4 &&
    mapper->GetColorMode() != VTK_COLOR_MODE_MAP_SCALARS)
  {
    vtkIdType translucent = 0;
    const vtkIdType n = colors->GetNumberOfTuples();
    for (vtkIdType t = 0; t < n; ++t)
      translucent += colors->GetTypedComponent(t, 3) < 255 ? 1 : 0;
    if (cellFlag == 1)
      return std::min(translucent, polygons); // cell scalars: verts and lines come first, rare
    return n > 0 ? static_cast<vtkIdType>(std::ceil(
                     static_cast<double>(polygons) * static_cast<double>(translucent) /
                     static_cast<double>(n)))
                 : 0;
  }
  vtkScalarsToColors* lut = mapper->GetLookupTable();
  if (lut && !lut->IsOpaque())
    return polygons;
  return 0;
}

bool IsPlainPolyDataMapper(vtkMapper* mapper)
{
  return mapper && std::strcmp(mapper->GetClassName(), "vtkOpenGLPolyDataMapper") == 0;
}

/// The viewport's aspect ratio (1 without a window or with an empty viewport).
double AspectOf(vtkRenderer* ren)
{
  if (!ren->GetVTKWindow())
    return 1.0;
  int width = 0, height = 0;
  ren->GetTiledSize(&width, &height);
  return width > 0 && height > 0 ? static_cast<double>(width) / static_cast<double>(height) : 1.0;
}

/// Everything the visible set depends on apart from the props: camera and viewport.
void ViewKey(vtkRenderer* ren, std::vector<double>& key)
{
  key.clear();
  vtkCamera* camera = ren->GetActiveCamera();
  auto add = [&key](const double* v, int n) { key.insert(key.end(), v, v + n); };
  add(camera->GetPosition(), 3);
  add(camera->GetFocalPoint(), 3);
  add(camera->GetViewUp(), 3);
  add(camera->GetWindowCenter(), 2);
  key.push_back(camera->GetViewAngle());
  key.push_back(camera->GetParallelScale());
  key.push_back(camera->GetParallelProjection());
  key.push_back(AspectOf(ren));
  const int* size = ren->GetSize();
  key.push_back(size[0]);
  key.push_back(size[1]);
}
} // namespace

/// The renderer's StartEvent and DeleteEvent observer; owns the planner when it was made by
/// Attach().
class vtkSceneVisPlannerStart : public vtkCommand
{
public:
  static vtkSceneVisPlannerStart* New() { return new vtkSceneVisPlannerStart; }
  vtkTypeMacro(vtkSceneVisPlannerStart, vtkCommand);
  void Execute(vtkObject*, unsigned long event, void*) override
  {
    if (!this->Planner)
      return;
    if (event == vtkCommand::DeleteEvent)
      this->Planner->RendererDeleted();
    else
      this->Planner->Plan();
  }
  vtkSceneVisPlanner* Planner = nullptr;
  vtkSmartPointer<vtkSceneVisPlanner> Owned;
};

class vtkSceneVisPlanner::vtkInternals
{
public:
  vtkSceneVisPlanner* Self = nullptr;
  vtkWeakPointer<vtkRenderer> Renderer;
  unsigned long StartTag = 0;
  unsigned long DeleteTag = 0;
  /// Weak: the renderer owns it (and through it, after Attach(), this planner).
  vtkWeakPointer<vtkSceneVisPlannerStart> StartCommand;

  // --- change detection ---
  vtkNew<vtkCallbackCommand> DirtyCommand;
  std::unordered_map<vtkObject*, std::pair<vtkWeakPointer<vtkObject>, unsigned long>> Observed;
  bool SceneDirty = true;
  /// Objects that fired ModifiedEvent since the last reading, and the actors depending on each
  /// observed object (addresses only looked up, never followed: an actor may be gone).
  std::unordered_set<vtkObject*> DirtyObjects;
  std::unordered_map<vtkObject*, std::unordered_set<vtkActor*>> Dependents;
  /// Sums over the counted entries.
  vtkIdType SumPolygons = 0, SumTriangles = 0, SumTranslucent = 0;
  std::size_t SumParts = 0;
  bool Busy = false; ///< inside Plan(): our own changes are not the application's
  vtkMTimeType PropsTime = 0;
  vtkMTimeType CameraTime = 0;
  vtkCamera* Camera = nullptr;
  int Size[2] = { -1, -1 };
  std::vector<double> View, NewView;
  std::vector<ActorEntry> Entries;
  std::unordered_map<vtkProp*, std::size_t> EntryOf;

  // --- the plan ---
  vtkScenePlanFacts Facts;
  bool Planned = false;
  vtkScenePlanChoice Cull{ "none", "not planned yet" };
  vtkScenePlanChoice Translucency{ "none", "not planned yet" };
  std::string CullReasonText = "not planned yet";
  std::string ReasonText = "not planned yet";
  std::string Pending; ///< a view-driven culling method waiting for SwitchFrames renders
  /// The facts of the scene itself (not of the view) at the last decision: when they change the
  /// plan follows at once, otherwise (the view, or props moved) only with hysteresis.
  std::vector<double> SceneKey;
  int PendingFrames = 0;
  int TranslucentActors = 0;

  // --- what is installed ---
  vtkSmartPointer<vtkOcclusionCuller> Culler;
  bool CullerInstalled = false;
  std::vector<vtkSmartPointer<vtkCuller>> RemovedCullers;
  vtkNew<vtkOrderedTranslucentPass> OrderedPass; ///< with vtkBSPTranslucentPass
  vtkNew<vtkBSPTranslucentPass> SortedPass;
  vtkNew<vtkOrderedTranslucentPass> PlainPass; ///< for the BSP mapper
  vtkRenderPass* InstalledPass = nullptr;
  std::unordered_map<vtkActor*, MapperSwap> Swaps;

  // --- warnings given once ---
  bool WarnedEmpty = false;
  bool WarnedPass = false;
  std::unordered_set<vtkProp*> WarnedNoInput, WarnedNaN;

  vtkInternals() { this->OrderedPass->SetTranslucentPass(this->SortedPass); }

  static void OnModified(vtkObject* caller, unsigned long, void* clientData, void*)
  {
    auto* self = static_cast<vtkInternals*>(clientData);
    if (!self->Busy)
    {
      self->SceneDirty = true;
      self->DirtyObjects.insert(caller);
    }
  }

  /// Observes @p object for the actor @p dependent (its numbers are read again when it changes).
  void Observe(vtkObject* object, vtkActor* dependent)
  {
    if (!object)
      return;
    auto found = this->Observed.find(object);
    if (found != this->Observed.end() && !found->second.first)
    {
      // A new object where a dead one was: observe it, and forget the dead one's dependents.
      this->Observed.erase(found);
      this->Dependents.erase(object);
      found = this->Observed.end();
    }
    this->Dependents[object].insert(dependent);
    if (found != this->Observed.end())
      return;
    const unsigned long tag = object->AddObserver(vtkCommand::ModifiedEvent, this->DirtyCommand);
    this->Observed.emplace(object, std::make_pair(vtkWeakPointer<vtkObject>(object), tag));
  }

  void ForgetObservers()
  {
    for (auto& entry : this->Observed)
      if (vtkObject* object = entry.second.first)
        object->RemoveObserver(entry.second.second);
    this->Observed.clear();
    this->Dependents.clear();
    this->DirtyObjects.clear();
  }

  vtkMapper* ApplicationMapper(vtkActor* actor)
  {
    vtkMapper* current = actor->GetMapper();
    auto found = this->Swaps.find(actor);
    if (found == this->Swaps.end())
      return current;
    MapperSwap& swap = found->second;
    if (swap.Installed && current == swap.Installed)
      return swap.Original;
    if (current != swap.Original)
      this->Swaps.erase(found); // the application set a mapper of its own: it wins
    return current;
  }

  /// Reads the actors again; only those whose times changed are measured again. O(actors).
  void Inspect(vtkRenderer* ren);
  /// Reads again only the actors that depend on objects that changed, if the props are the same
  /// and stayed visible; false when a full Inspect() is needed. O(changed actors).
  bool Refresh();
  /// Measures one actor (its mapper's pipeline brought up to date, as the cullers do).
  void Read(ActorEntry& entry);
  void Add(const ActorEntry& entry, int sign);
  void UpdateFacts();
  /// Measures the view facts (ManyProps+ actors only).
  void MeasureView(vtkRenderer* ren);
  void Install(vtkRenderer* ren, const std::string& cull, const std::string& translucency);
  void InstallCuller(vtkRenderer* ren, const std::string& cull);
  void InstallPass(vtkRenderer* ren, vtkRenderPass* pass);
  void SwapMapper(vtkActor* actor, bool sorted, bool chunked);
  void UndoAll(vtkRenderer* ren);
  void Adopt(const vtkScenePlanChoice& cull, const vtkScenePlanChoice& translucency);
};

void vtkSceneVisPlanner::vtkInternals::Read(ActorEntry& entry)
{
  vtkActor* actor = entry.Actor;
  entry.Mapper = this->ApplicationMapper(actor);
  entry.Input = nullptr;
  entry.Counted = false;
  entry.Polygons = entry.Triangles = entry.TranslucentPolygons = 0;
  entry.Box = vtkScenePlanPartBox();
  this->Observe(actor, actor);
  this->Observe(entry.Mapper, actor);
  if (!entry.Mapper || entry.Mapper->GetNumberOfInputConnections(0) == 0)
  {
    if (this->WarnedNoInput.insert(actor).second)
      vtkWarningWithObjectMacro(this->Self, << "actor " << actor << " has "
                                            << (entry.Mapper ? "a mapper without input"
                                                             : "no mapper")
                                            << ": left out of the plan");
    entry.ActorTime = actor->GetMTime();
    entry.MapperTime = entry.Mapper ? entry.Mapper->GetMTime() : 0;
    return;
  }
  // GetBounds() brings the mapper's pipeline up to date (as the cullers do).
  const double* bounds = actor->GetBounds();
  entry.Input = entry.Mapper->GetInputDataObject(0, 0);
  entry.ActorTime = actor->GetMTime();
  entry.MapperTime = entry.Mapper->GetMTime();
  entry.InputTime = entry.Input ? entry.Input->GetMTime() : 0;
  this->Observe(actor->GetProperty(), actor);
  this->Observe(actor->GetUserMatrix(), actor);
  this->Observe(entry.Input, actor);
  auto* pd = vtkPolyData::SafeDownCast(entry.Input);
  if (!pd || !vtkPolyDataMapper::SafeDownCast(entry.Mapper))
    return; // not a polydata mapper: not the planner's business
  entry.Counted = true;
  entry.Polygons = pd->GetNumberOfPolys() + pd->GetNumberOfStrips();
  entry.Triangles = TrianglesOf(pd->GetPolys()) + TrianglesOf(pd->GetStrips());
  entry.TranslucentPolygons = actor->GetProperty()->GetOpacity() < 1.0
    ? entry.Polygons
    : TranslucentByScalars(entry.Mapper, pd, entry.Polygons);
  if (bounds)
    std::copy(bounds, bounds + 6, entry.Box.Box);
  if (bounds && std::any_of(bounds, bounds + 6, [](double v) { return std::isnan(v); }) &&
    this->WarnedNaN.insert(actor).second)
    vtkWarningWithObjectMacro(this->Self, << "actor " << actor
                                          << " has NaN bounds: counted in view, covering "
                                             "nothing");
  entry.Box.Triangles = entry.Triangles;
}

void vtkSceneVisPlanner::vtkInternals::Add(const ActorEntry& entry, int sign)
{
  if (!entry.Counted)
    return;
  this->SumParts = sign > 0 ? this->SumParts + 1 : this->SumParts - 1;
  this->SumPolygons += sign * entry.Polygons;
  this->SumTriangles += sign * entry.Triangles;
  this->SumTranslucent += sign * entry.TranslucentPolygons;
  this->TranslucentActors += sign * (entry.TranslucentPolygons > 0 ? 1 : 0);
}

void vtkSceneVisPlanner::vtkInternals::UpdateFacts()
{
  vtkScenePlanFacts facts;
  facts.parts = this->SumParts;
  facts.polygons = this->SumPolygons;
  facts.triangles = this->SumTriangles;
  facts.translucentFraction = facts.polygons > 0
    ? static_cast<double>(this->SumTranslucent) / static_cast<double>(facts.polygons)
    : 0.0;
  this->Facts = facts;
  ++this->Self->InspectionCount;
}

void vtkSceneVisPlanner::vtkInternals::Inspect(vtkRenderer* ren)
{
  std::vector<ActorEntry> entries;
  std::unordered_map<vtkProp*, std::size_t> entryOf;
  vtkPropCollection* props = ren->GetViewProps();
  entries.reserve(static_cast<std::size_t>(props->GetNumberOfItems()));
  this->SumParts = 0;
  this->SumPolygons = this->SumTriangles = this->SumTranslucent = 0;
  this->TranslucentActors = 0;
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    auto* actor = vtkActor::SafeDownCast(prop);
    if (!actor)
      continue;
    this->Observe(actor, actor); // hidden ones too: showing one is a change
    if (!actor->GetVisibility())
      continue;
    ActorEntry entry;
    entry.Actor = actor;
    const auto old = this->EntryOf.find(prop);
    const ActorEntry* previous = old == this->EntryOf.end() ? nullptr : &this->Entries[old->second];
    vtkMapper* mapper = this->ApplicationMapper(actor);
    vtkDataObject* input =
      mapper && mapper->GetNumberOfInputConnections(0) > 0 ? mapper->GetInputDataObject(0, 0) : nullptr;
    if (previous && previous->Counted && previous->Mapper == mapper && previous->Input == input &&
      previous->ActorTime == actor->GetMTime() && previous->MapperTime == mapper->GetMTime() &&
      previous->InputTime == (input ? input->GetMTime() : 0))
      entry = *previous;
    else
      this->Read(entry);
    entryOf[prop] = entries.size();
    entries.push_back(entry);
    this->Add(entry, +1);
  }
  // Objects of actors that left stay observed (harmless: one more reading when they change)
  // until the planner leaves the renderer.
  this->Entries.swap(entries);
  this->EntryOf.swap(entryOf);
  this->DirtyObjects.clear();
  this->UpdateFacts();
}

bool vtkSceneVisPlanner::vtkInternals::Refresh()
{
  std::unordered_set<vtkActor*> dirty;
  for (vtkObject* object : this->DirtyObjects)
  {
    auto found = this->Dependents.find(object);
    if (found != this->Dependents.end())
      dirty.insert(found->second.begin(), found->second.end());
  }
  this->DirtyObjects.clear();
  std::vector<std::size_t> changed;
  for (vtkActor* actor : dirty)
  {
    auto found = this->EntryOf.find(actor);
    if (found == this->EntryOf.end())
    {
      // Not counted: hidden (perhaps shown now) or gone. Only a hidden actor of the renderer
      // matters, and only the full reading can tell.
      if (this->Self->GetRenderer() &&
        this->Self->GetRenderer()->GetViewProps()->IsItemPresent(actor))
        return false;
      continue;
    }
    if (!actor->GetVisibility())
      return false;
    changed.push_back(found->second);
  }
  for (const std::size_t index : changed)
  {
    ActorEntry& entry = this->Entries[index];
    this->Add(entry, -1);
    this->Read(entry);
    this->Add(entry, +1);
  }
  this->UpdateFacts();
  return true;
}

void vtkSceneVisPlanner::vtkInternals::MeasureView(vtkRenderer* ren)
{
  this->Facts.inView = -1.0;
  this->Facts.depthComplexity = -1.0;
  if (this->Facts.parts < vtkScenePlanRule::ManyProps)
    return;
  std::vector<vtkScenePlanPartBox> boxes;
  boxes.reserve(this->Entries.size());
  for (const ActorEntry& entry : this->Entries)
    if (entry.Counted)
      boxes.push_back(entry.Box);
  this->Facts.inView = vtkScenePlanRule::MeasureView(
    boxes, ren->GetActiveCamera(), AspectOf(ren), &this->Facts.depthComplexity);
  ++this->Self->ViewMeasurementCount;
}

void vtkSceneVisPlanner::vtkInternals::InstallCuller(vtkRenderer* ren, const std::string& cull)
{
  vtkCullerCollection* cullers = ren->GetCullers();
  const bool wanted = cull == "octree" || cull == "occlusion";
  if (wanted)
  {
    if (!this->Culler)
      this->Culler = vtkSmartPointer<vtkOcclusionCuller>::New();
    // One culler for both: switching keeps its hierarchy.
    this->Culler->SetOcclusionCulling(cull == "occlusion");
    if (!this->CullerInstalled || !cullers->IsItemPresent(this->Culler))
    {
      // Our culler does what vtkFrustumCoverageCuller does, for a fraction of the cost.
      vtkCollectionSimpleIterator it;
      cullers->InitTraversal(it);
      std::vector<vtkCuller*> coverage;
      while (vtkCuller* culler = cullers->GetNextCuller(it))
        if (vtkFrustumCoverageCuller::SafeDownCast(culler))
          coverage.push_back(culler);
      for (vtkCuller* culler : coverage)
      {
        this->RemovedCullers.emplace_back(culler);
        cullers->RemoveItem(culler);
      }
      ren->AddCuller(this->Culler);
      this->CullerInstalled = true;
    }
  }
  else if (this->CullerInstalled)
  {
    ren->RemoveCuller(this->Culler);
    for (const auto& culler : this->RemovedCullers)
      ren->AddCuller(culler);
    this->RemovedCullers.clear();
    this->CullerInstalled = false;
  }
}

void vtkSceneVisPlanner::vtkInternals::InstallPass(vtkRenderer* ren, vtkRenderPass* pass)
{
  vtkRenderPass* current = ren->GetPass();
  if (current && current != this->InstalledPass)
  {
    if (pass && !this->WarnedPass)
    {
      this->WarnedPass = true;
      vtkWarningWithObjectMacro(this->Self, << "the renderer has its own render pass ("
                                            << current->GetClassName()
                                            << "): translucency is left to it");
    }
    this->InstalledPass = nullptr;
    return;
  }
  if (current != pass)
    ren->SetPass(pass);
  this->InstalledPass = pass;
}

void vtkSceneVisPlanner::vtkInternals::SwapMapper(vtkActor* actor, bool sorted, bool chunked)
{
  vtkMapper* own = this->ApplicationMapper(actor);
  auto found = this->Swaps.find(actor);
  if (!sorted && !chunked)
  {
    if (found != this->Swaps.end() && found->second.Installed)
    {
      actor->SetMapper(found->second.Original);
      found->second.Installed = nullptr;
    }
    return;
  }
  if (found == this->Swaps.end())
  {
    if (!IsPlainPolyDataMapper(own))
      return; // an application's own mapper class: leave it
    MapperSwap swap;
    swap.Actor = actor;
    swap.Original = own;
    found = this->Swaps.emplace(actor, swap).first;
  }
  MapperSwap& swap = found->second;
  vtkMapper* wanted = nullptr;
  if (sorted)
  {
    if (!swap.Sorted)
      swap.Sorted = vtkSmartPointer<vtkBSPSortedPolyDataMapper>::New();
    wanted = swap.Sorted;
  }
  else
  {
    if (!swap.Chunked)
      swap.Chunked = vtkSmartPointer<vtkChunkedPolyDataMapper>::New();
    wanted = swap.Chunked;
  }
  if (swap.Installed != wanted || swap.CopiedTime != swap.Original->GetMTime())
  {
    // Same input, colouring, lookup table and clipping planes as the application's mapper.
    // vtkPolyDataMapper's copy, not vtkOpenGLPolyDataMapper's: that one goes through VTK 9.1's
    // deprecated shader-code accessors (a warning each) for shader code we do not carry over.
    static_cast<vtkPolyDataMapper*>(wanted)->vtkPolyDataMapper::ShallowCopy(swap.Original);
    swap.CopiedTime = swap.Original->GetMTime();
  }
  if (actor->GetMapper() != wanted)
    actor->SetMapper(wanted);
  swap.Installed = wanted;
}

void vtkSceneVisPlanner::vtkInternals::Install(
  vtkRenderer* ren, const std::string& cull, const std::string& translucency)
{
  this->InstallCuller(ren, cull);
  if (translucency == "multi-actor")
    this->InstallPass(ren, this->OrderedPass);
  else if (translucency == "bsp-mapper")
    this->InstallPass(ren, this->PlainPass);
  else
    this->InstallPass(ren, nullptr);

  // Mappers: the BSP mapper on the one translucent actor, chunks in the big opaque ones.
  const bool passInstalled = this->InstalledPass != nullptr;
  for (ActorEntry& entry : this->Entries)
  {
    if (!entry.Counted)
      continue;
    const bool sorted =
      translucency == "bsp-mapper" && passInstalled && entry.TranslucentPolygons > 0;
    const bool chunked = cull == "chunked" && entry.TranslucentPolygons == 0 &&
      entry.Triangles >= this->Self->ChunkedMinimumTriangles;
    const vtkMapper* before = entry.Actor->GetMapper();
    this->SwapMapper(entry.Actor, sorted, chunked);
    if (entry.Actor->GetMapper() != before)
      entry.ActorTime = entry.Actor->GetMTime(); // our own change, not the application's
  }
  // Swapped actors that left the plan (hidden, removed) get their own mapper back.
  for (auto it = this->Swaps.begin(); it != this->Swaps.end();)
  {
    vtkActor* actor = it->second.Actor;
    if (!actor)
    {
      it = this->Swaps.erase(it);
      continue;
    }
    if (!this->EntryOf.count(actor) && it->second.Installed)
    {
      if (actor->GetMapper() == it->second.Installed)
        actor->SetMapper(it->second.Original);
      it->second.Installed = nullptr;
    }
    ++it;
  }
}

void vtkSceneVisPlanner::vtkInternals::UndoAll(vtkRenderer* ren)
{
  if (ren)
  {
    this->InstallCuller(ren, "none");
    if (this->InstalledPass && ren->GetPass() == this->InstalledPass)
      ren->SetPass(nullptr);
  }
  // The culler's hierarchy is of this renderer's props: a next renderer gets a new one.
  this->Culler = nullptr;
  this->CullerInstalled = false;
  this->RemovedCullers.clear();
  this->InstalledPass = nullptr;
  this->Cull = { "none", "not planned yet" };
  this->Translucency = { "none", "not planned yet" };
  this->CullReasonText = this->ReasonText = "not planned yet";
  for (auto& entry : this->Swaps)
  {
    vtkActor* actor = entry.second.Actor;
    if (actor && entry.second.Installed && actor->GetMapper() == entry.second.Installed)
      actor->SetMapper(entry.second.Original);
  }
  this->Swaps.clear();
  this->ForgetObservers();
  this->Entries.clear();
  this->EntryOf.clear();
  this->SceneDirty = true;
  this->Planned = false;
  this->Pending.clear();
  this->PendingFrames = 0;
  this->SceneKey.clear();
  this->View.clear();
  this->Camera = nullptr;
}

void vtkSceneVisPlanner::vtkInternals::Adopt(
  const vtkScenePlanChoice& cull, const vtkScenePlanChoice& translucency)
{
  this->Cull = cull;
  this->Translucency = translucency;
  this->CullReasonText = cull.Reason + " (" + this->Facts.Summary() + ")";
  this->ReasonText = "culling " + cull.Method + ": " + this->CullReasonText + "; translucency " +
    translucency.Method + ": " + translucency.Reason;
  this->Planned = true;
  this->Pending.clear();
  this->PendingFrames = 0;
  ++this->Self->PlanCount;
}

//------------------------------------------------------------------------------
vtkSceneVisPlanner::vtkSceneVisPlanner()
  : Internals(new vtkInternals)
{
  this->Internals->Self = this;
  this->Internals->DirtyCommand->SetClientData(this->Internals.get());
  this->Internals->DirtyCommand->SetCallback(&vtkInternals::OnModified);
}

vtkSceneVisPlanner::~vtkSceneVisPlanner()
{
  this->SetRenderer(nullptr);
  // A renderer that went first took its cullers and pass along; actors may outlive it.
  this->Internals->UndoAll(nullptr);
}

vtkSceneVisPlanner* vtkSceneVisPlanner::Attach(vtkRenderer* renderer)
{
  if (!renderer)
  {
    vtkGenericWarningMacro(<< "vtkSceneVisPlanner::Attach: no renderer: nothing to plan for");
    return nullptr;
  }
  vtkNew<vtkSceneVisPlanner> planner;
  planner->SetRenderer(renderer);
  planner->Internals->StartCommand->Owned = planner;
  return planner;
}

void vtkSceneVisPlanner::SetRenderer(vtkRenderer* renderer)
{
  vtkInternals& in = *this->Internals;
  vtkRenderer* current = in.Renderer;
  if (current == renderer && (renderer || !in.StartCommand))
    return;
  // An Attach() ownership is released when this function ends: it may be what keeps this
  // planner alive.
  vtkSmartPointer<vtkSceneVisPlanner> keep;
  if (vtkSceneVisPlannerStart* start = in.StartCommand)
  {
    start->Planner = nullptr;
    keep = start->Owned;
    start->Owned = nullptr;
    if (current)
    {
      current->RemoveObserver(in.StartTag);
      current->RemoveObserver(in.DeleteTag);
    }
    in.StartCommand = nullptr;
  }
  in.UndoAll(current);
  in.Renderer = renderer;
  this->PlanCount = 0;
  this->InspectionCount = 0;
  this->ViewMeasurementCount = 0;
  if (renderer)
  {
    auto start = vtkSmartPointer<vtkSceneVisPlannerStart>::New();
    start->Planner = this;
    in.StartCommand = start;
    in.StartTag = renderer->AddObserver(vtkCommand::StartEvent, start);
    in.DeleteTag = renderer->AddObserver(vtkCommand::DeleteEvent, start);
  }
  this->Modified();
}

void vtkSceneVisPlanner::RendererDeleted()
{
  // The renderer is about to remove its observers (this one among them, which may own this
  // planner) and to die with its cullers and pass: it must not be touched, not even modified.
  this->Internals->Renderer = nullptr;
  this->Internals->UndoAll(nullptr);
}

vtkRenderer* vtkSceneVisPlanner::GetRenderer()
{
  return this->Internals->Renderer;
}

void vtkSceneVisPlanner::Plan()
{
  const auto start = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  vtkRenderer* ren = in.Renderer;
  if (!ren)
  {
    vtkWarningMacro(<< "Plan(): no renderer (SetRenderer): nothing planned");
    return;
  }
  in.Busy = true;
  // The scene: the prop collection and what the observed objects said.
  vtkPropCollection* props = ren->GetViewProps();
  const bool structure = props->GetMTime() != in.PropsTime || !in.Planned;
  bool sceneChanged = structure || in.SceneDirty;
  if (sceneChanged)
  {
    if (structure || !in.Refresh())
      in.Inspect(ren);
    in.SceneDirty = false;
    in.PropsTime = props->GetMTime();
    if (in.Facts.parts == 0)
    {
      if (!in.WarnedEmpty)
        vtkWarningMacro(<< "the renderer has no visible actors with polydata: nothing installed");
      in.WarnedEmpty = true;
    }
    else
    {
      in.WarnedEmpty = false;
    }
  }
  // The view: only the camera's and viewport's parameters that change what is seen.
  vtkCamera* camera = ren->GetActiveCamera();
  bool viewChanged = sceneChanged || camera != in.Camera || camera->GetMTime() != in.CameraTime;
  if (viewChanged)
  {
    ViewKey(ren, in.NewView);
    viewChanged = sceneChanged || in.NewView != in.View;
    in.View.swap(in.NewView);
    in.Camera = camera;
    in.CameraTime = camera->GetMTime();
  }
  else
  {
    const int* size = ren->GetSize();
    if (size[0] != in.Size[0] || size[1] != in.Size[1])
    {
      ViewKey(ren, in.NewView);
      viewChanged = in.NewView != in.View;
      in.View.swap(in.NewView);
    }
  }
  {
    const int* size = ren->GetSize();
    in.Size[0] = size[0];
    in.Size[1] = size[1];
  }
  if (viewChanged && in.Facts.parts >= vtkScenePlanRule::ManyProps)
    in.MeasureView(ren);

  if (sceneChanged || viewChanged || !in.Pending.empty())
  {
    const vtkScenePlanChoice cull = vtkScenePlanRule::ChooseCulling(in.Facts);
    const auto translucency = [&in](const vtkScenePlanChoice& c)
    {
      vtkScenePlanChoice sort = vtkScenePlanRule::ChooseTranslucency(
        in.Facts.translucentFraction > 0.0, c.Method == "chunked", in.TranslucentActors > 1,
        static_cast<std::size_t>(in.TranslucentActors));
      if (sort.Method == "bsp-mapper")
      {
        // The BSP mapper replaces a plain mapper only; any other is ordered by the pass.
        for (const ActorEntry& entry : in.Entries)
        {
          if (entry.Counted && entry.TranslucentPolygons > 0 &&
            !IsPlainPolyDataMapper(entry.Mapper) &&
            !vtkBSPSortedPolyDataMapper::SafeDownCast(entry.Mapper))
          {
            sort = { "multi-actor",
              std::string("one translucent actor, drawn by a ") + entry.Mapper->GetClassName() +
                " the planner does not replace: exact order with vtkBSPTranslucentPass" };
          }
        }
      }
      return sort;
    };
    const std::vector<double> sceneKey{ static_cast<double>(in.Facts.parts),
      static_cast<double>(in.Facts.polygons), static_cast<double>(in.Facts.triangles),
      in.Facts.translucentFraction, static_cast<double>(in.TranslucentActors) };
    const bool immediate = !in.Planned || sceneKey != in.SceneKey ||
      translucency(in.Cull).Method != in.Translucency.Method;
    if (immediate)
    {
      // Props added, removed, shown, hidden or made translucent: the plan follows at once
      // (translucency is a matter of correctness).
      in.SceneKey = sceneKey;
      const vtkScenePlanChoice sort = translucency(cull);
      if (!in.Planned || cull.Method != in.Cull.Method || sort.Method != in.Translucency.Method)
        in.Adopt(cull, sort);
      else
      {
        in.Pending.clear();
        in.PendingFrames = 0;
      }
      in.Install(ren, in.Cull.Method, in.Translucency.Method);
    }
    else
    {
      if (sceneChanged) // props moved: keep the mappers in step (an input or a mapper changed)
        in.Install(ren, in.Cull.Method, in.Translucency.Method);
      if (cull.Method == in.Cull.Method)
      {
        in.Pending.clear();
        in.PendingFrames = 0;
      }
      else
      {
        // A view-driven change: clear of the thresholds by the margin, for SwitchFrames renders.
        bool clear = true;
        if (viewChanged || sceneChanged)
        {
          // The fraction in view is near 1 where it matters: its complement (the fraction out of
          // view) is what is scaled, so that a full view stays clear of the threshold.
          for (const double scale : { 1.0 - this->ViewMargin, 1.0 + this->ViewMargin })
          {
            vtkScenePlanFacts nudged = in.Facts;
            nudged.inView = 1.0 - (1.0 - nudged.inView) * scale;
            nudged.depthComplexity *= scale;
            clear &= vtkScenePlanRule::ChooseCulling(nudged).Method == cull.Method;
          }
        }
        if (!clear || cull.Method != in.Pending)
        {
          in.Pending = clear ? cull.Method : std::string();
          in.PendingFrames = clear ? 1 : 0;
        }
        else
        {
          ++in.PendingFrames;
        }
        if (!in.Pending.empty() && in.PendingFrames >= this->SwitchFrames)
        {
          in.Adopt(cull, translucency(cull));
          in.Install(ren, in.Cull.Method, in.Translucency.Method);
        }
      }
    }
  }
  in.Busy = false;
  this->LastPlanTime =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

const char* vtkSceneVisPlanner::GetCullMethod() const
{
  return this->Internals->Cull.Method.c_str();
}

const char* vtkSceneVisPlanner::GetTranslucencyMethod() const
{
  return this->Internals->Translucency.Method.c_str();
}

const char* vtkSceneVisPlanner::GetCullReason() const
{
  return this->Internals->CullReasonText.c_str();
}

const char* vtkSceneVisPlanner::GetTranslucencyReason() const
{
  return this->Internals->Translucency.Reason.c_str();
}

const char* vtkSceneVisPlanner::GetReason() const
{
  return this->Internals->ReasonText.c_str();
}

const vtkScenePlanFacts& vtkSceneVisPlanner::GetFacts() const
{
  return this->Internals->Facts;
}

vtkCuller* vtkSceneVisPlanner::GetCuller() const
{
  return this->Internals->CullerInstalled ? this->Internals->Culler.Get() : nullptr;
}

void vtkSceneVisPlanner::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& in = *this->Internals;
  os << indent << "Renderer: " << static_cast<void*>(in.Renderer.Get()) << "\n";
  os << indent << "CullMethod: " << in.Cull.Method << "\n";
  os << indent << "TranslucencyMethod: " << in.Translucency.Method << "\n";
  os << indent << "Reason: " << in.ReasonText << "\n";
  os << indent << "Facts: " << in.Facts.Summary() << "\n";
  os << indent << "PlanCount: " << this->PlanCount << "\n";
  os << indent << "InspectionCount: " << this->InspectionCount << "\n";
  os << indent << "ViewMeasurementCount: " << this->ViewMeasurementCount << "\n";
  os << indent << "Pending: " << (in.Pending.empty() ? "(none)" : in.Pending) << " for "
     << in.PendingFrames << " renders\n";
  os << indent << "SwitchFrames: " << this->SwitchFrames << "\n";
  os << indent << "ViewMargin: " << this->ViewMargin << "\n";
  os << indent << "ChunkedMinimumTriangles: " << this->ChunkedMinimumTriangles << "\n";
  os << indent << "Culler: " << (in.CullerInstalled ? "vtkOcclusionCuller" : "(none)") << "\n";
  os << indent << "Pass: " << (in.InstalledPass ? in.InstalledPass->GetClassName() : "(none)")
     << "\n";
  int swapped = 0;
  for (const auto& swap : in.Swaps)
    swapped += swap.second.Installed ? 1 : 0;
  os << indent << "SwappedMappers: " << swapped << "\n";
  os << indent << "ObservedObjects: " << in.Observed.size() << "\n";
  os << indent << "LastPlanTime: " << this->LastPlanTime << " ms\n";
}

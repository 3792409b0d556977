#include "vtkScenePlanInventory.h"

#include "vtkAbstractMapper.h"
#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

namespace
{
vtkIdType TrianglesOf(vtkCellArray* cells)
{
  // Fan triangulation: n - 2 triangles per polygon or strip of n points.
  return cells
    ? std::max<vtkIdType>(0, cells->GetNumberOfConnectivityIds() - 2 * cells->GetNumberOfCells())
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
    return n > 0 ? static_cast<vtkIdType>(std::ceil(static_cast<double>(polygons) *
                     static_cast<double>(translucent) / static_cast<double>(n)))
                 : 0;
  }
  vtkScalarsToColors* lut = mapper->GetLookupTable();
  if (lut && !lut->IsOpaque())
    return polygons;
  return 0;
}
} // namespace

vtkScenePlanInventory::vtkScenePlanInventory(
  vtkObject* owner, std::function<vtkMapper*(vtkActor*)> mapperOf)
  : Owner(owner)
  , MapperOf(std::move(mapperOf))
{
  this->DirtyCommand->SetClientData(this);
  this->DirtyCommand->SetCallback(&vtkScenePlanInventory::OnModified);
}

vtkScenePlanInventory::~vtkScenePlanInventory()
{
  this->ForgetObservers();
}

double vtkScenePlanInventory::AspectOf(vtkRenderer* ren)
{
  if (!ren->GetVTKWindow())
    return 1.0;
  int width = 0, height = 0;
  ren->GetTiledSize(&width, &height);
  return width > 0 && height > 0 ? static_cast<double>(width) / static_cast<double>(height) : 1.0;
}

void vtkScenePlanInventory::OnModified(vtkObject* caller, unsigned long, void* clientData, void*)
{
  auto* self = static_cast<vtkScenePlanInventory*>(clientData);
  if (!self->Ignoring)
  {
    self->Dirty = true;
    self->DirtyObjects.insert(caller);
  }
}

void vtkScenePlanInventory::Observe(vtkObject* object, vtkActor* dependent)
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

void vtkScenePlanInventory::ForgetObservers()
{
  for (auto& entry : this->Observed)
    if (vtkObject* object = entry.second.first)
      object->RemoveObserver(entry.second.second);
  this->Observed.clear();
  this->Dependents.clear();
  this->DirtyObjects.clear();
}

void vtkScenePlanInventory::Clear()
{
  this->ForgetObservers();
  this->Entries.clear();
  this->EntryOf.clear();
  this->SumParts = 0;
  this->SumPolygons = this->SumTriangles = this->SumTranslucent = 0;
  this->TranslucentActors = 0;
  this->Facts = vtkScenePlanFacts();
  this->Dirty = true;
  this->Inspections = 0;
  this->ViewMeasurements = 0;
}

void vtkScenePlanInventory::SetPortals(vtkPolyData* portals)
{
  this->Rooms = 0;
  this->Portals = 0;
  vtkDataArray* a = portals ? portals->GetCellData()->GetArray("RoomA") : nullptr;
  vtkDataArray* b = portals ? portals->GetCellData()->GetArray("RoomB") : nullptr;
  if (a && b && a->GetNumberOfComponents() == 1 && b->GetNumberOfComponents() == 1)
  {
    std::unordered_set<long long> rooms;
    const vtkIdType n = std::min(a->GetNumberOfTuples(), b->GetNumberOfTuples());
    for (vtkIdType c = 0; c < n; ++c)
      for (const double room : { a->GetTuple1(c), b->GetTuple1(c) })
        if (room >= 0 && room < 2147483647.0)
          rooms.insert(static_cast<long long>(room));
    this->Rooms = static_cast<int>(rooms.size());
    this->Portals = n;
  }
  this->Facts.rooms = this->Rooms;
  this->Facts.portals = this->Portals;
}

void vtkScenePlanInventory::Read(vtkScenePlanActorEntry& entry)
{
  vtkActor* actor = entry.Actor;
  entry.Mapper = this->MapperOf(actor);
  entry.Input = nullptr;
  entry.Counted = false;
  entry.Polygons = entry.Triangles = entry.TranslucentPolygons = 0;
  entry.Box = vtkScenePlanPartBox();
  this->Observe(actor, actor);
  this->Observe(entry.Mapper, actor);
  if (!entry.Mapper || entry.Mapper->GetNumberOfInputConnections(0) == 0)
  {
    if (this->WarnedNoInput.insert(actor).second)
      vtkWarningWithObjectMacro(this->Owner,
        << "actor " << actor << " has " << (entry.Mapper ? "a mapper without input" : "no mapper")
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
    vtkWarningWithObjectMacro(this->Owner, << "actor " << actor
                                           << " has NaN bounds: counted in view, covering "
                                              "nothing");
  entry.Box.Triangles = entry.Triangles;
}

void vtkScenePlanInventory::Add(const vtkScenePlanActorEntry& entry, int sign)
{
  if (!entry.Counted)
    return;
  this->SumParts = sign > 0 ? this->SumParts + 1 : this->SumParts - 1;
  this->SumPolygons += sign * entry.Polygons;
  this->SumTriangles += sign * entry.Triangles;
  this->SumTranslucent += sign * entry.TranslucentPolygons;
  this->TranslucentActors += sign * (entry.TranslucentPolygons > 0 ? 1 : 0);
}

void vtkScenePlanInventory::UpdateFacts()
{
  vtkScenePlanFacts facts;
  facts.parts = this->SumParts;
  facts.polygons = this->SumPolygons;
  facts.triangles = this->SumTriangles;
  facts.fixedActors = true; // the application's actors are drawn as they are
  facts.rooms = this->Rooms;
  facts.portals = this->Portals;
  facts.translucentFraction = facts.polygons > 0
    ? static_cast<double>(this->SumTranslucent) / static_cast<double>(facts.polygons)
    : 0.0;
  this->Facts = facts;
  ++this->Inspections;
}

void vtkScenePlanInventory::Inspect(vtkRenderer* ren)
{
  std::vector<vtkScenePlanActorEntry> entries;
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
    vtkScenePlanActorEntry entry;
    entry.Actor = actor;
    const auto old = this->EntryOf.find(prop);
    const vtkScenePlanActorEntry* previous =
      old == this->EntryOf.end() ? nullptr : &this->Entries[old->second];
    vtkMapper* mapper = this->MapperOf(actor);
    vtkDataObject* input = mapper && mapper->GetNumberOfInputConnections(0) > 0
      ? mapper->GetInputDataObject(0, 0)
      : nullptr;
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

bool vtkScenePlanInventory::Refresh(vtkRenderer* ren)
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
      if (ren && ren->GetViewProps()->IsItemPresent(actor))
        return false;
      continue;
    }
    if (!actor->GetVisibility())
      return false;
    changed.push_back(found->second);
  }
  for (const std::size_t index : changed)
  {
    vtkScenePlanActorEntry& entry = this->Entries[index];
    this->Add(entry, -1);
    this->Read(entry);
    this->Add(entry, +1);
  }
  this->UpdateFacts();
  return true;
}

void vtkScenePlanInventory::MeasureView(vtkRenderer* ren)
{
  this->Facts.inView = -1.0;
  this->Facts.depthComplexity = -1.0;
  if (this->Facts.parts < vtkScenePlanRule::ManyProps)
    return;
  std::vector<vtkScenePlanPartBox> boxes;
  boxes.reserve(this->Entries.size());
  for (const vtkScenePlanActorEntry& entry : this->Entries)
    if (entry.Counted)
      boxes.push_back(entry.Box);
  this->Facts.inView = vtkScenePlanRule::MeasureView(
    boxes, ren->GetActiveCamera(), AspectOf(ren), &this->Facts.depthComplexity);
  ++this->ViewMeasurements;
}

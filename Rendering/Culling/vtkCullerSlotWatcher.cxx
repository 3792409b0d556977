#include "vtkCullerSlotWatcher.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkLinearTransform.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkMatrixToLinearTransform.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"

#include <algorithm>
#include <cstring>

using vtkCullerSlots::Slot;

//------------------------------------------------------------------------------
vtkCullerSlotWatcher::vtkCullerSlotWatcher(std::vector<Slot>& slots)
  : Slots(slots)
{
  this->Callback->SetClientData(this);
  this->Callback->SetCallback(&vtkCullerSlotWatcher::OnEvent);
}

//------------------------------------------------------------------------------
vtkCullerSlotWatcher::~vtkCullerSlotWatcher()
{
  this->UnwatchAll();
}

//------------------------------------------------------------------------------
void vtkCullerSlotWatcher::OnEvent(
  vtkObject* caller, unsigned long event, void* clientData, void*)
{
  auto* self = static_cast<vtkCullerSlotWatcher*>(clientData);
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

//------------------------------------------------------------------------------
void vtkCullerSlotWatcher::MarkDirty(std::uint32_t s)
{
  if (s < this->Dirty.size() && !this->Dirty[s])
  {
    this->Dirty[s] = 1;
    this->DirtyList.push_back(s);
  }
}

//------------------------------------------------------------------------------
void vtkCullerSlotWatcher::WatchObject(vtkObject* object, std::uint32_t s)
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

//------------------------------------------------------------------------------
void vtkCullerSlotWatcher::Unregister(std::uint32_t s)
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

//------------------------------------------------------------------------------
void vtkCullerSlotWatcher::UnwatchAll()
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

//------------------------------------------------------------------------------
bool vtkCullerSlotWatcher::Dependencies(
  const Slot& slot, bool withProperty, std::vector<vtkObject*>& deps)
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

//------------------------------------------------------------------------------
void vtkCullerSlotWatcher::Register(
  std::uint32_t s, bool withProperty, std::vector<vtkObject*>& scratch)
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

//------------------------------------------------------------------------------
void vtkCullerSlotWatcher::UpdatePolledList()
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

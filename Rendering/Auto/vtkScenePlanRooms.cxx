#include "vtkScenePlanRooms.h"

#include "vtkScenePlanInventory.h"
#include "vtkScenePlanRoomsModel.h"
#include "vtkScenePlanRoomsWorker.h"

#include "vtkActor.h"
#include "vtkAutoRooms.h"
#include "vtkMatrix4x4.h"

#include <cstdint>
#include <sstream>

/// What a generation in the background was started for.
struct vtkScenePlanRooms::Job
{
  vtkScenePlanRoomsModel Model; ///< without its polydata: the worker has it
  std::vector<double> Signature;
  /// False once its actors are no longer the planner's (a new set, or Clear()).
  bool Wanted = true;
};

vtkScenePlanRooms::vtkScenePlanRooms()
  : Worker(new vtkScenePlanRoomsWorker)
{
}

vtkScenePlanRooms::~vtkScenePlanRooms() = default;

void vtkScenePlanRooms::Clear()
{
  this->Portals = nullptr;
  this->Rooms.clear();
  this->GeneratedFrom.clear();
  this->Reason.clear();
  if (this->Running)
  {
    this->Running->Wanted = false;
  }
  this->Restart = false;
}

bool vtkScenePlanRooms::IsPending() const
{
  return this->Restart || (this->Running && this->Running->Wanted);
}

void vtkScenePlanRooms::Wait() const
{
  this->Worker->Wait();
}

std::vector<double> vtkScenePlanRooms::Signature(vtkScenePlanInventory& inventory)
{
  std::vector<double> signature;
  for (const vtkScenePlanActorEntry& entry : inventory.GetEntries())
  {
    if (!entry.Counted)
    {
      continue;
    }
    // Pointers below 2^53 (x86-64 user space: 2^47) and MTimes are exact as doubles.
    signature.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(entry.Actor)));
    signature.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(entry.Input)));
    signature.push_back(static_cast<double>(entry.InputTime));
    vtkMatrix4x4* m = entry.Actor->GetMatrix();
    signature.insert(signature.end(), m->GetData(), m->GetData() + 16);
  }
  return signature;
}

bool vtkScenePlanRooms::Update(
  vtkScenePlanInventory& inventory, bool newActors, double budgetSeconds, bool background)
{
  const bool inUse = this->Portals != nullptr;
  if (!newActors)
  {
    // The same actors: keep what was generated for them while they stay as they were (a
    // generation in the background is checked when it ends).
    if (inUse && vtkScenePlanRooms::Signature(inventory) != this->GeneratedFrom)
    {
      this->Portals = nullptr;
      this->Rooms.clear();
      this->Reason = "generated rooms and portals dropped: an actor moved or changed since (they "
                     "are generated again when the actors change)";
      return true;
    }
    return false;
  }
  this->Clear();
  const vtkScenePlanFacts& facts = inventory.GetFacts();
  if (facts.parts < 2 ||
    facts.polygons > static_cast<vtkIdType>(vtkArchitecturalLook::MaximumPolygons))
  {
    // Nothing to gain (one actor is drawn whenever its room may be seen) or too big to try.
    return inUse;
  }
  if (background && this->Worker->IsBusy())
  {
    // One generation at a time: this set of actors is generated for when the running one ends.
    this->Restart = true;
    this->RestartBudget = budgetSeconds;
    this->Reason = "generating rooms in the background (for these actors once the generation "
                   "for the previous ones has ended)";
    return inUse;
  }

  vtkScenePlanRoomsModel model = vtkScenePlanRoomsModel::Gather(inventory);
  if (!background)
  {
    const vtkAutoRooms generated = vtkAutoRooms::Generate(model.Model, "RoomId", budgetSeconds);
    return this->Use(generated, model, vtkScenePlanRooms::Signature(inventory)) || inUse;
  }
  // The worker tests the look too (a few milliseconds): this render pays for the copy alone.
  std::ostringstream why;
  why << "generating rooms in the background (" << model.ModelPolys + model.ModelStrips
      << " polygons of " << model.Pieces.size()
      << " actors, if they look architectural; until then culling as without rooms)";
  this->Reason = why.str();
  this->Running.reset(new Job{ vtkScenePlanRoomsModel(), vtkScenePlanRooms::Signature(inventory) });
  this->Worker->Start(std::move(model.Model), budgetSeconds);
  model.Model = nullptr;
  this->Running->Model = std::move(model);
  return inUse;
}

bool vtkScenePlanRooms::Poll(vtkScenePlanInventory& inventory)
{
  if (!this->Running || !this->Worker->IsDone())
  {
    return false;
  }
  const vtkAutoRooms generated = this->Worker->Take();
  const std::unique_ptr<Job> job = std::move(this->Running);
  bool changed = false;
  if (job->Wanted && vtkScenePlanRooms::Signature(inventory) == job->Signature)
  {
    changed = this->Use(generated, job->Model, job->Signature);
  }
  else
  {
    this->Generations += generated.Tried ? 1 : 0;
    if (job->Wanted)
    {
      this->Reason = "the generation in the background discarded: an actor moved or changed "
                     "while it ran (rooms are generated again when the actors change)";
    }
  }
  if (this->Restart)
  {
    // The set of actors that came while the worker was busy.
    this->Restart = false;
    changed |= this->Update(inventory, true, this->RestartBudget, true);
  }
  return changed;
}

bool vtkScenePlanRooms::Use(
  const vtkAutoRooms& generated, const vtkScenePlanRoomsModel& model, std::vector<double> signature)
{
  this->Generations += generated.Tried ? 1 : 0;
  this->Reason = generated.Reason;
  if (!generated.Used)
  {
    return false;
  }
  this->Rooms = model.CellRoomsOf(generated.Rooms);
  this->Portals = generated.Portals;
  this->GeneratedFrom = std::move(signature);
  return true;
}

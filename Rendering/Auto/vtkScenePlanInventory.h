/**
 * @class   vtkScenePlanInventory
 * @brief   What vtkSceneVisPlanner knows of a renderer's actors: the scene's facts, kept up to
 *          date by observing the actors, their mappers, properties, matrices and inputs.
 *
 * Private to the RenderingAuto module (not a vtkObject, not wrapped). The first Inspect() reads
 * every visible actor; later, Refresh() reads again only the actors that depend on an object
 * that fired ModifiedEvent, and Inspect() re-uses the entries whose modification times did not
 * change. The facts (parts, polygons, triangles, translucent fraction) are sums kept per entry,
 * so a change costs what changed, not what the scene holds. The view facts (in view, depth
 * complexity) are measured on demand by MeasureView() from the entries' world boxes.
 *
 * The application's mapper of an actor is asked through MapperOf: the planner may have put a
 * mapper of its own on the actor, and the facts are those of the application's.
 *
 * @sa vtkSceneVisPlanner vtkScenePlanRule
 */

#ifndef vtkScenePlanInventory_h
#define vtkScenePlanInventory_h

#include "vtkCallbackCommand.h"
#include "vtkNew.h"
#include "vtkScenePlanRule.h"
#include "vtkType.h"
#include "vtkWeakPointer.h"

#include <cstddef>
#include <functional>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

class vtkActor;
class vtkDataObject;
class vtkMapper;
class vtkObject;
class vtkPolyData;
class vtkProp;
class vtkRenderer;

/// What the planner knows of one actor, and the modification times it was read at.
struct vtkScenePlanActorEntry
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

class vtkScenePlanInventory
{
public:
  /// @p owner: the object warnings are given for; @p mapperOf: the application's mapper of an
  /// actor.
  vtkScenePlanInventory(vtkObject* owner, std::function<vtkMapper*(vtkActor*)> mapperOf);
  ~vtkScenePlanInventory();
  vtkScenePlanInventory(const vtkScenePlanInventory&) = delete;
  vtkScenePlanInventory& operator=(const vtkScenePlanInventory&) = delete;

  /// Reads the renderer's visible actors; only those whose times changed are measured again.
  /// O(actors).
  void Inspect(vtkRenderer* ren);
  /// Reads again only the actors that depend on objects that changed, if the props are the same
  /// and stayed visible; false when a full Inspect() is needed. O(changed actors).
  bool Refresh(vtkRenderer* ren);
  /// Measures the view facts (ManyProps+ actors only; otherwise they are set to -1).
  void MeasureView(vtkRenderer* ren);
  /// Forgets everything and stops observing.
  void Clear();
  /// Counts the rooms (distinct RoomA and RoomB values >= 0) and the portals (cells with both
  /// arrays) of @p portals (may be null) into the facts.
  void SetPortals(vtkPolyData* portals);

  /// Whether an observed object changed since the last reading.
  bool IsDirty() const { return this->Dirty; }
  void ClearDirty() { this->Dirty = false; }
  /// While set, modifications are the planner's own and do not make the scene dirty.
  void SetIgnoringModifications(bool ignoring) { this->Ignoring = ignoring; }

  const vtkScenePlanFacts& GetFacts() const { return this->Facts; }
  /// Actors with translucent polygons among the counted ones.
  int GetTranslucentActors() const { return this->TranslucentActors; }
  std::vector<vtkScenePlanActorEntry>& GetEntries() { return this->Entries; }
  bool Contains(vtkProp* prop) const { return this->EntryOf.count(prop) != 0; }
  std::size_t GetNumberOfObservedObjects() const { return this->Observed.size(); }
  /// The viewport's aspect ratio (1 without a window or with an empty viewport).
  static double AspectOf(vtkRenderer* ren);

  /// Readings of the scene and measurements of the view since Clear().
  int GetNumberOfInspections() const { return this->Inspections; }
  int GetNumberOfViewMeasurements() const { return this->ViewMeasurements; }

private:
  static void OnModified(vtkObject* caller, unsigned long, void* clientData, void*);
  /// Observes @p object for the actor @p dependent (its numbers are read again when it changes).
  void Observe(vtkObject* object, vtkActor* dependent);
  void ForgetObservers();
  /// Measures one actor (its mapper's pipeline brought up to date, as the cullers do).
  void Read(vtkScenePlanActorEntry& entry);
  void Add(const vtkScenePlanActorEntry& entry, int sign);
  void UpdateFacts();

  vtkObject* Owner;
  std::function<vtkMapper*(vtkActor*)> MapperOf;
  vtkNew<vtkCallbackCommand> DirtyCommand;
  std::unordered_map<vtkObject*, std::pair<vtkWeakPointer<vtkObject>, unsigned long>> Observed;
  bool Dirty = true;
  bool Ignoring = false;
  /// Objects that fired ModifiedEvent since the last reading, and the actors depending on each
  /// observed object (addresses only looked up, never followed: an actor may be gone).
  std::unordered_set<vtkObject*> DirtyObjects;
  std::unordered_map<vtkObject*, std::unordered_set<vtkActor*>> Dependents;
  /// Sums over the counted entries.
  vtkIdType SumPolygons = 0, SumTriangles = 0, SumTranslucent = 0;
  std::size_t SumParts = 0;
  int TranslucentActors = 0;
  std::vector<vtkScenePlanActorEntry> Entries;
  std::unordered_map<vtkProp*, std::size_t> EntryOf;
  vtkScenePlanFacts Facts;
  int Rooms = 0;
  vtkIdType Portals = 0;
  int Inspections = 0;
  int ViewMeasurements = 0;
  std::unordered_set<vtkProp*> WarnedNoInput, WarnedNaN;
};

#endif
// VTK-HeaderTest-Exclude: vtkScenePlanInventory.h

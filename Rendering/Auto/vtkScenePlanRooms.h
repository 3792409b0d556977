/**
 * @class   vtkScenePlanRooms
 * @brief   Rooms and portals vtkSceneVisPlanner generates for a scene of actors that has none
 *          (vtkAutoRooms: the same test and rule as `scenevis --cull auto`), in the render or in
 *          the background.
 *
 * Private to the RenderingAuto module (not a vtkObject, not wrapped). Update() is called when the
 * scene changed. With a new set of actors (the renderer's prop collection changed) it tries once:
 * the counted actors' polygons and strips in world coordinates (each actor's matrix) become one
 * model (vtkScenePlanRoomsModel); when vtkAutoRooms uses the rooms it finds (at least 2 rooms, 1
 * portal, no leak), every actor gets the room of each of its cells (-1 for vertices and lines),
 * which the installer hands to the vtkPortalCuller (SetPropCellRooms) without touching the
 * application's data. Only scenes of at least 2 actors and at most
 * vtkArchitecturalLook::MaximumPolygons polygons that pass vtkArchitecturalLook's test (a few
 * milliseconds at most) are generated for, so that a scene that is no building costs nothing
 * measurable.
 *
 * Synchronously, the test and the generation run inside Update(). In the background, Update()
 * only gathers the model and starts both on a worker thread (vtkScenePlanRoomsWorker), and the
 * reason says "generating rooms in the background" until Poll(), called at every render, finds
 * it done (a scene that is no building then says so, without a plan change); its
 * rooms are then used only if the actors are still those it was generated for (Signature() at
 * the start equals Signature() now): otherwise they are discarded, as synchronous rooms are
 * dropped. A new set of actors while a generation runs: its result is discarded and, one worker
 * at a time, the new set is generated for when it ends.
 *
 * Generated rooms hold for the actors as they were: when an actor moves or its data changes
 * afterwards (same set of actors), the rooms are dropped (the plan falls back to the rule without
 * rooms) and not generated again until the set of actors changes: a changing scene does not pay
 * for generation on every frame.
 *
 * @sa vtkSceneVisPlanner vtkAutoRooms vtkGenerateRooms
 */

#ifndef vtkScenePlanRooms_h
#define vtkScenePlanRooms_h

#include "vtkDataArray.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkActor;
class vtkScenePlanInventory;
class vtkScenePlanRoomsWorker;
struct vtkAutoRooms;
struct vtkScenePlanRoomsModel;

class vtkScenePlanRooms
{
public:
  /// Rooms of one actor's cells.
  using CellRooms = std::vector<std::pair<vtkActor*, vtkSmartPointer<vtkDataArray>>>;

  vtkScenePlanRooms();
  ~vtkScenePlanRooms(); ///< waits for a generation running in the background (see Wait)
  vtkScenePlanRooms(const vtkScenePlanRooms&) = delete;
  vtkScenePlanRooms& operator=(const vtkScenePlanRooms&) = delete;

  /**
   * Bring the generated rooms up to date with @p inventory's counted actors; @p newActors: the
   * set of actors changed since the last call; @p budgetSeconds: processor seconds a generation
   * may take (vtkAutoRooms::Generate); @p background: generate on a worker thread (see the class
   * comment). Returns true when what is in use (GetPortals, GetCellRooms) changed.
   */
  bool Update(
    vtkScenePlanInventory& inventory, bool newActors, double budgetSeconds, bool background);

  /**
   * When the generation in the background has ended: its rooms put in use if they are still
   * those of @p inventory's actors (brought up to date before the call), discarded otherwise,
   * and the generation for a newer set of actors started. Returns true when what is in use
   * changed (the reason may change without it). Costs one look at the worker otherwise.
   */
  bool Poll(vtkScenePlanInventory& inventory);

  /// Rooms are being generated in the background for the current actors, or have been and wait
  /// for Poll().
  bool IsPending() const;

  /// Waits until the generation running in the background (if any) has ended; Poll() takes it.
  void Wait() const;

  /// Forget everything (a new renderer, or generation turned off): a generation running in the
  /// background goes on (it cannot be stopped) but its result will be discarded.
  void Clear();

  /// The generated portals in use, or null.
  vtkPolyData* GetPortals() const { return this->Portals; }
  const CellRooms& GetCellRooms() const { return this->Rooms; }
  /// What the last attempt found and why it is (not) used, for the culling reason; "" when
  /// nothing was tried.
  const std::string& GetReason() const { return this->Reason; }
  /// Generations run, in the render or in the background, used or not (a test that failed is
  /// not one).
  int GetNumberOfGenerations() const { return this->Generations; }

  /// What rooms are generated from: per counted actor, the actor, its input, the input's MTime
  /// and its matrix. Rooms are used only for the actors of the signature they were made for.
  static std::vector<double> Signature(vtkScenePlanInventory& inventory);

private:
  /// Puts @p generated in use for the actors of @p model, whose signature was @p signature.
  bool Use(const vtkAutoRooms& generated, const vtkScenePlanRoomsModel& model,
    std::vector<double> signature);

  vtkSmartPointer<vtkPolyData> Portals;
  CellRooms Rooms;
  std::vector<double> GeneratedFrom;
  std::string Reason;
  int Generations = 0;

  /// The generation in the background: what it was started for.
  struct Job;
  std::unique_ptr<Job> Running;
  /// The set of actors changed while a generation ran: generate for it when that one ends.
  bool Restart = false;
  double RestartBudget = 0.0;
  /// Touches none of the members above: it owns what its thread uses.
  std::unique_ptr<vtkScenePlanRoomsWorker> Worker;
};

#endif

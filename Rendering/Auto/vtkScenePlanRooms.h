/**
 * @class   vtkScenePlanRooms
 * @brief   Rooms and portals vtkSceneVisPlanner generates for a scene of actors that has none
 *          (vtkAutoRooms: the same test and rule as `scenevis --cull auto`).
 *
 * Private to the RenderingAuto module (not a vtkObject, not wrapped). Update() is called when the
 * scene changed. With a new set of actors (the renderer's prop collection changed) it tries once:
 * the counted actors' polygons and strips in world coordinates (each actor's matrix) become one
 * model; when vtkAutoRooms uses the rooms it finds (at least 2 rooms, 1 portal, no leak), every
 * actor gets the room of each of its cells (-1 for vertices and lines), which the installer hands
 * to the vtkPortalCuller (SetPropCellRooms) without touching the application's data. Only scenes
 * of at least 2 actors and at most vtkArchitecturalLook::MaximumPolygons polygons are tried, so
 * that a scene that is no building costs nothing measurable.
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

#include <string>
#include <utility>
#include <vector>

class vtkActor;
class vtkScenePlanInventory;

class vtkScenePlanRooms
{
public:
  /// Rooms of one actor's cells.
  using CellRooms = std::vector<std::pair<vtkActor*, vtkSmartPointer<vtkDataArray>>>;

  /**
   * Bring the generated rooms up to date with @p inventory's counted actors; @p newActors: the
   * set of actors changed since the last call; @p budgetSeconds: processor seconds a generation
   * may take (vtkAutoRooms::Generate). Returns true when what is in use (GetPortals,
   * GetCellRooms) changed.
   */
  bool Update(vtkScenePlanInventory& inventory, bool newActors, double budgetSeconds);

  /// Forget everything (a new renderer, or generation turned off).
  void Clear();

  /// The generated portals in use, or null.
  vtkPolyData* GetPortals() const { return this->Portals; }
  const CellRooms& GetCellRooms() const { return this->Rooms; }
  /// What the last attempt found and why it is (not) used, for the culling reason; "" when
  /// nothing was tried.
  const std::string& GetReason() const { return this->Reason; }
  /// Generations run (a test that failed is not one).
  int GetNumberOfGenerations() const { return this->Generations; }

private:
  /// What the rooms were generated from: per counted actor, the actor, its input, the input's
  /// MTime and its matrix.
  std::vector<double> Signature(vtkScenePlanInventory& inventory) const;

  vtkSmartPointer<vtkPolyData> Portals;
  CellRooms Rooms;
  std::vector<double> GeneratedFrom;
  std::string Reason;
  int Generations = 0;
};

#endif

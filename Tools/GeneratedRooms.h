// Rooms and portals found from a scene's geometry (scenevis/PortalGeneration.h) as VTK data: the
// room of every cell and the portal polygons. `scenevis portals` writes them; --cull auto
// generates them in memory for a scene that looks architectural and has none (LooksArchitectural).
#ifndef scenevis_tool_GeneratedRooms_h
#define scenevis_tool_GeneratedRooms_h

#include "scenevis/PortalGeneration.h"

#include <vtkIntArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>

namespace scenevis
{
namespace tool
{

struct GeneratedRooms
{
  portals::GeneratedPortals result;
  /// The room of every cell of the model (named @p roomArray): its polygon's (a strip's first
  /// triangle's), kOutsideRoom (-1) for other cells. Null unless result.status is Ok.
  vtkSmartPointer<vtkIntArray> rooms;
  /// One polygon per portal with RoomA and RoomB cell arrays. Null unless result.status is Ok.
  vtkSmartPointer<vtkPolyData> portals;
  std::size_t seeThroughPolygons = 0; ///< translucent cells (alpha < 255): glass
};

/// Rooms and portals of @p model. Translucent cells (alpha below 255 in RGBA cell scalars) are
/// see-through: they do not close an opening. Never throws for bad geometry (see result.status).
/// @p budgetSeconds: processor-time limit of the generation (0: none; past it, result.status is
/// OverBudget and there are no rooms). @p stopAtFirstLeak: GenerationConfig::stopAtFirstLeak
/// (a leaking scene then gives no rooms and one leak cell, sooner).
GeneratedRooms GenerateRooms(vtkPolyData* model, const std::string& roomArray,
  double budgetSeconds = 0.0, bool stopAtFirstLeak = false);

/// Whether --cull auto tries GenerateRooms on a scene without rooms and portals, and why.
struct ArchitecturalLook
{
  bool looksArchitectural = false;
  std::size_t polygons = 0;
  /// Share of the polygon area lying in axis planes of the best axis: facing along it (floors,
  /// ceilings) or perpendicular to it (walls). 1.0 for the demo building and Freedoom MAP01, 0.95
  /// for the ctf_gate1 level, but also 0.96 for the cad demo (boxes); 0.04 for the bunny.
  double alignedArea = 0.0;
  /// Of the area facing along an axis, the share facing a polygon turned towards it further
  /// along (a floor under a ceiling, walls across a room).
  double enclosedArea = 0.0;
  double ms = 0.0;
  std::string reason; ///< the numbers, and which limit failed
};

/// The limits of LooksArchitectural (the report quotes them).
constexpr double kMinAlignedArea = 0.7;
/// Measured: the demo building 0.74, MAP01 0.98, ctf_gate1 0.72; the cad demo 0.01-0.02 (a box's
/// face looks at the next part only where one happens to stand), spheres and the bunny 0.
constexpr double kMinEnclosedArea = 0.5;
/// Generation is not linear: the demo building's 3,484 polygons take 1.0 s, MAP01's 6,857 2.3 s,
/// the oa_koth2 level's 7,668 11 s (it leaks: not used), the 200-part cad demo's 9,776 8.5 s,
/// MAP12's 67,170 25 s. Above this many polygons --cull auto does not try it (`scenevis portals`
/// once, then --portals).
constexpr std::size_t kMaxGenerationPolygons = 10000;
/// And it stops after this many processor seconds (GenerationConfig::budgetSeconds): what a
/// scene that looks architectural but leaks (every real level tried) costs --cull auto before its
/// first frame on a quiet machine. Three times the building's 1.0 s; processor time, so the
/// building is not stopped on a loaded machine (at load 5-9 its wall time reached 3.1 s).
constexpr double kAutoGenerationBudgetSeconds = 3.0;

/// A cheap test, linear in the polygons (0.2-10 ms on the scenes above): at most
/// kMaxGenerationPolygons polygons, at least kMinAlignedArea of their area in axis-aligned planes
/// (walls, floors) and at least kMinEnclosedArea of the area facing along an axis looking at a
/// polygon turned back towards it (rooms are closed; parts standing in space are not). Scenes that
/// pass are then generated; the result is used only with >= 2 rooms, >= 1 portal and no leak.
ArchitecturalLook LooksArchitectural(vtkPolyData* model);

} // namespace tool
} // namespace scenevis

#endif

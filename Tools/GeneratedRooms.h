// Rooms and portals found from a scene's geometry (vtkGenerateRooms) as the tool reports them: the
// room of every cell and the portal polygons. `scenevis portals` writes them; --cull auto
// generates them in memory for a scene that looks architectural and has none (vtkAutoRooms.h).
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
/// (a leaking scene then gives no rooms and one leak cell, sooner). @p keepRoomsWithLeaks:
/// GenerationConfig::keepRoomsWithLeaks (the rooms of a leaking scene, not conservative).
GeneratedRooms GenerateRooms(vtkPolyData* model, const std::string& roomArray,
  double budgetSeconds = 0.0, bool stopAtFirstLeak = false, bool keepRoomsWithLeaks = false);

} // namespace tool
} // namespace scenevis

#endif

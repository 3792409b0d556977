/**
 * @file    vtkDemoScenePortals.h
 * @brief   The portals of a demo building (scenevis/Scenes.h) as vtkPortalCuller reads them.
 *
 * vtkDemoSceneSource's SCENE_BUILDING outputs the building's polygons with a "RoomId" per cell;
 * its doors and windows, the portals between rooms, are not polygons of the scene. For
 * portal culling (vtkPortalCuller::SetPortals) make them from the same generator call:
 *
 * @code
 * source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
 * culler->SetPortals(scenevis::MakePortalPolyData(scenevis::scenes::building(
 *   source->GetFloors(), source->GetRoomsX(), source->GetRoomsY(), source->GetSeed())));
 * @endcode
 *
 * A plain function in namespace scenevis (not wrapped for Python). The building is
 * SceneVis::Core's (scenevis/Scenes.h): a caller that makes one links SceneVis::Core.
 *
 * @sa vtkDemoSceneSource vtkPortalCuller
 */
#ifndef vtkDemoScenePortals_h
#define vtkDemoScenePortals_h

#include "SceneVisFiltersSourcesModule.h" // For export macro

#include <vtkSmartPointer.h> // For vtkSmartPointer

class vtkPolyData;

namespace scenevis
{
namespace scenes
{
struct BuildingScene;
}

/// The portals of @p building: one polygon per portal, integer cell arrays "RoomA" and "RoomB"
/// (the rooms it joins; -1 is the outside).
SCENEVISFILTERSSOURCES_EXPORT vtkSmartPointer<vtkPolyData> MakePortalPolyData(
  const scenes::BuildingScene& building);

} // namespace scenevis

#endif

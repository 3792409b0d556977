// Specification: vtkDemoSceneSource with bad parameters (issue 8).
// - Zero or negative counts are clamped to the documented minimum (64 triangles, 1 part, 1 floor
//   and 1 room per row), with a warning from the setter, and give an ordinary, non-empty scene.
// - Scene ids out of range are clamped; unknown scene names are refused and change nothing.
// - Scenes larger than MaximumTriangleCount (default 10^8, about 10 GB at the peak) are refused
//   up front: ONE clear error naming the scene and the reason, an empty output, no time spent;
//   the next update with sane counts gives the ordinary scene again. Below that limit, the
//   generator's own limits (32-bit point ids, rooms) give the same kind of error.
#include "vtkDemoSceneSource.h"

#include "scenevis/testing/Expect.h"

#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
struct Observed
{
  vtkNew<vtkDemoSceneSource> source;
  vtkNew<vtkTest::ErrorObserver> observer;
  Observed()
  {
    this->source->AddObserver(vtkCommand::ErrorEvent, this->observer);
    this->source->AddObserver(vtkCommand::WarningEvent, this->observer);
  }
  vtkIdType Update()
  {
    this->observer->Clear();
    this->source->Update();
    return this->source->GetOutput()->GetNumberOfPolys();
  }
  bool Quiet() { return !this->observer->GetError() && !this->observer->GetWarning(); }
  /// Errors reported since the last Update() (the observer concatenates their messages).
  int ErrorCount()
  {
    const std::string all = this->observer->GetErrorMessage();
    int count = 0;
    for (auto at = all.find("Cannot generate"); at != std::string::npos;
         at = all.find("Cannot generate", at + 1))
    {
      ++count;
    }
    return count;
  }
  bool ErrorSays(const std::string& text)
  {
    return this->observer->GetError() &&
      this->observer->GetErrorMessage().find(text) != std::string::npos;
  }
};
} // namespace

int TestDemoSceneSourceBadInput(int, char*[])
{
  // Zero and negative counts: clamped to the minimum, an ordinary scene.
  for (vtkIdType bad : { vtkIdType(0), vtkIdType(-5) })
  {
    Observed spheres;
    spheres.source->SetScene(vtkDemoSceneSource::SCENE_SPHERE_GRID);
    spheres.source->SetTriangleCount(bad);
    SCENEVIS_EXPECT(spheres.observer->GetWarning());
    SCENEVIS_EXPECT(spheres.source->GetTriangleCount() == 64);
    SCENEVIS_EXPECT(spheres.Update() > 0);
    SCENEVIS_EXPECT(spheres.Quiet());

    Observed cad;
    cad.source->SetScene(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY);
    cad.source->SetPartCount(bad);
    SCENEVIS_EXPECT(cad.observer->GetWarning());
    SCENEVIS_EXPECT(cad.source->GetPartCount() == 1);
    SCENEVIS_EXPECT(cad.Update() > 0);
    SCENEVIS_EXPECT(cad.Quiet());

    Observed building;
    building.source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
    building.source->SetFloors(static_cast<int>(bad));
    building.source->SetRoomsX(static_cast<int>(bad));
    building.source->SetRoomsY(static_cast<int>(bad));
    SCENEVIS_EXPECT(building.observer->GetWarning());
    SCENEVIS_EXPECT(building.source->GetFloors() == 1 && building.source->GetRoomsX() == 1 &&
      building.source->GetRoomsY() == 1);
    SCENEVIS_EXPECT(building.Update() > 0);
    SCENEVIS_EXPECT(building.Quiet());
  }

  // Scene ids out of range are clamped; unknown names are refused.
  {
    vtkNew<vtkDemoSceneSource> source;
    source->SetScene(-1);
    SCENEVIS_EXPECT(source->GetScene() == vtkDemoSceneSource::SCENE_SPHERE_GRID);
    source->SetScene(99);
    SCENEVIS_EXPECT(source->GetScene() == vtkDemoSceneSource::SCENE_BUILDING);
    SCENEVIS_EXPECT(!source->SetSceneByName("no-such-scene"));
    SCENEVIS_EXPECT(!source->SetSceneByName(nullptr));
    SCENEVIS_EXPECT(source->GetScene() == vtkDemoSceneSource::SCENE_BUILDING);
    SCENEVIS_EXPECT(std::string(vtkDemoSceneSource::GetSceneName(42)) == "unknown");
  }

  // 1e11 triangles: over MaximumTriangleCount, refused up front; then recovery.
  {
    Observed spheres;
    spheres.source->SetScene(vtkDemoSceneSource::SCENE_SPHERE_GRID);
    spheres.source->SetTriangleCount(100000000000); // 1e11
    SCENEVIS_EXPECT(spheres.Update() == 0);
    SCENEVIS_EXPECT(spheres.source->GetOutput()->GetNumberOfPoints() == 0);
    SCENEVIS_EXPECT(spheres.ErrorSays("Cannot generate the spheres scene"));
    SCENEVIS_EXPECT(spheres.ErrorSays("MaximumTriangleCount"));
    SCENEVIS_EXPECT(spheres.ErrorCount() == 1);
    // With the limit lifted, the generator's own limit (32-bit point ids) speaks, up front too.
    spheres.source->SetMaximumTriangleCount(VTK_ID_MAX);
    SCENEVIS_EXPECT(spheres.Update() == 0);
    SCENEVIS_EXPECT(spheres.ErrorSays("32-bit"));
    SCENEVIS_EXPECT(spheres.ErrorCount() == 1);
    spheres.source->SetTriangleCount(1000);
    SCENEVIS_EXPECT(spheres.Update() > 900);
    SCENEVIS_EXPECT(spheres.Quiet());
  }
  // A billion rooms: refused up front, one clear error, an empty output; then recovery.
  {
    Observed building;
    building.source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
    building.source->SetFloors(1000);
    building.source->SetRoomsX(1000);
    building.source->SetRoomsY(1000);
    SCENEVIS_EXPECT(building.Update() == 0);
    SCENEVIS_EXPECT(building.ErrorSays("Cannot generate the building scene"));
    SCENEVIS_EXPECT(building.ErrorSays("MaximumTriangleCount"));
    SCENEVIS_EXPECT(building.ErrorCount() == 1);
    building.source->SetMaximumTriangleCount(VTK_ID_MAX);
    SCENEVIS_EXPECT(building.Update() == 0);
    SCENEVIS_EXPECT(building.ErrorSays("too many rooms"));
    SCENEVIS_EXPECT(building.ErrorCount() == 1);
    building.source->SetFloors(2);
    building.source->SetRoomsX(2);
    building.source->SetRoomsY(2);
    SCENEVIS_EXPECT(building.Update() > 0);
    SCENEVIS_EXPECT(building.Quiet());
  }
  // Sizes the generators would accept but that exhaust memory: refused up front, at once.
  {
    Observed cad;
    cad.source->SetScene(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY);
    cad.source->SetPartCount(10000000);
    SCENEVIS_EXPECT(cad.Update() == 0);
    SCENEVIS_EXPECT(cad.ErrorSays("MaximumTriangleCount"));
    Observed building;
    building.source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
    building.source->SetFloors(100);
    building.source->SetRoomsX(100);
    building.source->SetRoomsY(100);
    SCENEVIS_EXPECT(building.Update() == 0);
    SCENEVIS_EXPECT(building.ErrorSays("MaximumTriangleCount"));
  }
  return scenevis::testing::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// Specification: vtkDemoSceneSource with bad parameters (issue 8).
// - Zero or negative counts are clamped to the documented minimum (64 triangles, 1 part, 1 floor
//   and 1 room per row) and give an ordinary, non-empty scene. (Silently: the setters are
//   vtkSetClampMacro; see the note in the report of issue 8.)
// - Scene ids out of range are clamped; unknown scene names are refused and change nothing.
// - Counts too large to generate (more than 32-bit point ids, or more rooms than the generator
//   accepts) give ONE clear error naming the scene and the reason, and an empty output; the next
//   update with sane counts gives the ordinary scene again.
// Only counts that the generator refuses up front are used here: counts that are accepted but
// exhaust memory (e.g. 10^7 CAD parts) take tens of seconds and gigabytes before failing with
// std::bad_alloc, which is no test for a shared machine.
#include "vtkDemoSceneSource.h"

#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
int failures = 0;
#define EXPECT(cond)                                                                               \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": expected " #cond << std::endl;                \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (false)

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
    EXPECT(spheres.source->GetTriangleCount() == 64);
    EXPECT(spheres.Update() > 0);
    EXPECT(spheres.Quiet());

    Observed cad;
    cad.source->SetScene(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY);
    cad.source->SetPartCount(bad);
    EXPECT(cad.source->GetPartCount() == 1);
    EXPECT(cad.Update() > 0);
    EXPECT(cad.Quiet());

    Observed building;
    building.source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
    building.source->SetFloors(static_cast<int>(bad));
    building.source->SetRoomsX(static_cast<int>(bad));
    building.source->SetRoomsY(static_cast<int>(bad));
    EXPECT(building.source->GetFloors() == 1 && building.source->GetRoomsX() == 1 &&
      building.source->GetRoomsY() == 1);
    EXPECT(building.Update() > 0);
    EXPECT(building.Quiet());
  }

  // Scene ids out of range are clamped; unknown names are refused.
  {
    vtkNew<vtkDemoSceneSource> source;
    source->SetScene(-1);
    EXPECT(source->GetScene() == vtkDemoSceneSource::SCENE_SPHERE_GRID);
    source->SetScene(99);
    EXPECT(source->GetScene() == vtkDemoSceneSource::SCENE_BUILDING);
    EXPECT(!source->SetSceneByName("no-such-scene"));
    EXPECT(!source->SetSceneByName(nullptr));
    EXPECT(source->GetScene() == vtkDemoSceneSource::SCENE_BUILDING);
    EXPECT(std::string(vtkDemoSceneSource::GetSceneName(42)) == "unknown");
  }

  // Too many triangles for 32-bit ids: one clear error, an empty output; then recovery.
  {
    Observed spheres;
    spheres.source->SetScene(vtkDemoSceneSource::SCENE_SPHERE_GRID);
    spheres.source->SetTriangleCount(100000000000); // 1e11
    EXPECT(spheres.Update() == 0);
    EXPECT(spheres.source->GetOutput()->GetNumberOfPoints() == 0);
    EXPECT(spheres.ErrorSays("Cannot generate the spheres scene"));
    EXPECT(spheres.ErrorSays("32-bit"));
    EXPECT(spheres.ErrorCount() == 1);
    spheres.source->SetTriangleCount(1000);
    EXPECT(spheres.Update() > 900);
    EXPECT(spheres.Quiet());
  }
  // A billion rooms: refused up front, one clear error, an empty output; then recovery.
  {
    Observed building;
    building.source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
    building.source->SetFloors(1000);
    building.source->SetRoomsX(1000);
    building.source->SetRoomsY(1000);
    EXPECT(building.Update() == 0);
    EXPECT(building.ErrorSays("Cannot generate the building scene"));
    EXPECT(building.ErrorSays("too many rooms"));
    EXPECT(building.ErrorCount() == 1);
    building.source->SetFloors(2);
    building.source->SetRoomsX(2);
    building.source->SetRoomsY(2);
    EXPECT(building.Update() > 0);
    EXPECT(building.Quiet());
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

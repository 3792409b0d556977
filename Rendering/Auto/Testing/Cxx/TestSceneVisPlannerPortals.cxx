// vtkSceneVisPlanner with the portals of a building (2 floors x 4 x 4 rooms, one actor per room
// plus one for the outside, each actor's room as "RoomId" field data):
//  (a) without portals (and without generating them): 33 actors, fewer than 100: nothing
//      installed;
//  (b) SetPortals(): planned at the next render as "portals": a vtkPortalCuller with those
//      portals in place of vtkFrustumCoverageCuller; from an eye in the middle of every room,
//      what it kept has 0 false negatives against the ID buffer's visible set of rooms, and over
//      the 32 eyes it culled rooms;
//  (c) the reason quotes the rooms and portals; a portals' modification is planned for;
//  (d) SetPortals(nullptr): VTK's culler back, the portal culler gone.
#include "vtkSceneVisPlanner.h"

#include "PlannerTesting.h"

#include "vtkPortalCuller.h"

#include "scenevis/Scenes.h"
#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkFieldData.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;
using plannertesting::Check;

bool OnlyCuller(vtkRenderer* renderer, const char* className)
{
  vtkCullerCollection* cullers = renderer->GetCullers();
  return cullers->GetNumberOfItems() >= 1 &&
    std::string(cullers->GetItemAsObject(0)->GetClassName()) == className;
}
} // namespace

int TestSceneVisPlannerPortals(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  const scenevis::scenes::BuildingScene b = scenevis::scenes::building(2, 4, 4, 5);
  const int rooms = static_cast<int>(b.rooms.size());
  const int outsideNode = rooms;

  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(200, 150);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  // actors[r + 1]: room r (-1: outside), its room as "RoomId" field data.
  std::vector<vtkSmartPointer<vtkActor>> actors = plannertesting::BuildingActors(renderer, b, true);
  const auto all = st::MakeRoomPolyData(b, -2, outsideNode);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(60.0);
  camera->SetPosition(1, -2, 1);
  camera->SetViewUp(0, 0, 1);

  // --- (a) no portals ---------------------------------------------------------------------------
  vtkSceneVisPlanner* planner = vtkSceneVisPlanner::Attach(renderer);
  planner->GenerateRoomsOff(); // the application's portals only (generated ones: see
                               // TestSceneVisPlannerGeneratedRooms)
  renderer->ResetCamera();
  window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) == "none" && !planner->GetCuller() &&
      OnlyCuller(renderer, "vtkFrustumCoverageCuller"),
    "no portals, 33 actors: nothing installed (" + std::string(planner->GetCullReason()) + ")");

  // --- (b) portals
  // ---------------------------------------------------------------------------------
  vtkSmartPointer<vtkPolyData> portals = st::MakePortalPolyData(b);
  planner->SetPortals(portals);
  vtkNew<plannertesting::RecordingCuller> recorder;
  std::size_t culledViews = 0, drawnTotal = 0, visibleTotal = 0;
  bool conservative = true;
  for (const auto& room : b.rooms)
  {
    const auto& box = room.bounds;
    const double eye[3] = { (box.lo.x + box.hi.x) / 2, (box.lo.y + box.hi.y) / 2,
      box.lo.z + 0.6 * (box.hi.z - box.lo.z) };
    // Along the room's longer axis, towards its far wall.
    camera->SetPosition(eye);
    camera->SetFocalPoint(eye[0] + 1.0, eye[1] + 0.3 * (room.ix % 2 ? 1 : -1), eye[2] - 0.1);
    camera->SetViewUp(0, 0, 1);
    renderer->ResetCameraClippingRange();
    planner->Plan(); // so that the recorder goes after the planner's culler
    renderer->RemoveCuller(recorder);
    renderer->AddCuller(recorder);
    window->Render();
    std::vector<std::uint32_t> drawn;
    for (vtkProp* prop : recorder->Kept)
      for (std::size_t a = 0; a < actors.size(); ++a)
        if (actors[a].Get() == prop)
          drawn.push_back(static_cast<std::uint32_t>(a == 0 ? outsideNode : a - 1));
    st::IdRenderOptions options;
    options.originalIdArray = "RoomNode";
    options.cameraClippingRange = true;
    const std::vector<std::uint32_t> visible =
      st::VisibleSet(st::RenderIdBuffer(window, all, camera, options));
    const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
    if (!check.conservative)
      std::cout << "room " << room.id << ": " << check.Summary() << "\n";
    conservative &= check.conservative;
    culledViews += drawn.size() < actors.size() ? 1 : 0;
    drawnTotal += drawn.size();
    visibleTotal += visible.size();
  }
  ok &= Check(std::string(planner->GetCullMethod()) == "portals" &&
      vtkPortalCuller::SafeDownCast(planner->GetCuller()) &&
      OnlyCuller(renderer, "vtkPortalCuller") &&
      vtkPortalCuller::SafeDownCast(planner->GetCuller())->GetPortals() == portals.Get(),
    "portals set: vtkPortalCuller with them in place of VTK's culler (" +
      std::string(planner->GetCullReason()) + ")");
  ok &= Check(conservative && visibleTotal > 0,
    "an eye in each of the " + std::to_string(rooms) +
      " rooms: every visible room drawn (0 false negatives)");
  ok &= Check(culledViews > b.rooms.size() / 2,
    "rooms culled in " + std::to_string(culledViews) + " of " + std::to_string(rooms) + " views; " +
      std::to_string(drawnTotal) + " rooms drawn for " + std::to_string(visibleTotal) + " visible");

  // --- (c) the reason, and a modification of the portals ---------------------------------------
  const vtkScenePlanFacts& facts = planner->GetFacts();
  ok &= Check(facts.rooms == rooms && facts.portals == portals->GetNumberOfCells() &&
      std::string(planner->GetCullReason()).find("portals") != std::string::npos,
    "facts: " + std::to_string(facts.rooms) + " rooms, " + std::to_string(facts.portals) +
      " portals");
  const int plans = planner->GetPlanCount();
  portals->GetCellData()->GetArray("RoomB")->Fill(-1.0); // every portal now leads outside
  portals->Modified();
  window->Render();
  ok &= Check(planner->GetFacts().rooms < rooms && planner->GetPlanCount() == plans &&
      std::string(planner->GetCullMethod()) == "portals",
    "modified portals read again at the next render: " + std::to_string(planner->GetFacts().rooms) +
      " rooms named");

  // --- (d) no portals again ----------------------------------------------------------------------
  renderer->RemoveCuller(recorder);
  planner->SetPortals(nullptr);
  window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) == "none" && !planner->GetCuller() &&
      OnlyCuller(renderer, "vtkFrustumCoverageCuller") &&
      renderer->GetCullers()->GetNumberOfItems() == 1,
    "portals removed: VTK's culler back, the portal culler gone");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

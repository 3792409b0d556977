// vtkSceneVisPlanner on a building whose actors say nothing of rooms or portals (2 floors x 3 x 3
// rooms, one actor per room plus one for the outside, no RoomId anywhere, no SetPortals()),
// generating in the render (GenerateRoomsInBackgroundOff; in the background:
// TestSceneVisPlannerBackgroundRooms):
//  (a) at the first render it generates rooms and portals (once) and plans "portals": a
//      vtkPortalCuller in place of VTK's culler, the reason saying what was generated;
//  (b) from an eye in the middle of every room, what the culler kept has 0 false negatives
//      against the ID buffer's visible set, rooms are culled in most views, and moving the camera
//      generates nothing again;
//  (c) an actor moved: the generated rooms are dropped (the plan falls back, the reason says
//      why) and not generated again while the set of actors stays;
//  (d) an actor added (a box standing in a room): generated again, "portals" again, still
//      conservative;
//  (e) GenerateRoomsOff(): VTK's culler back;
//  (f) a scene that is no building (a grid of boxes) is not generated for, and the reason says why.
#include "vtkSceneVisPlanner.h"

#include "PlannerTesting.h"
#include "RoomWalk.h"

#include "vtkPortalCuller.h"

#include "scenevis/Scenes.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;
using plannertesting::Check;
using plannertesting::Walk;
using plannertesting::WalkRooms;

bool Has(const char* text, const char* part)
{
  return std::string(text).find(part) != std::string::npos;
}
} // namespace

int TestSceneVisPlannerGeneratedRooms(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  const scenevis::scenes::BuildingScene b = scenevis::scenes::building(2, 3, 3, 5);
  const int rooms = static_cast<int>(b.rooms.size());
  const int outsideNode = rooms;

  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(200, 150);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  // actors[r + 1]: room r (-1: outside); no RoomId anywhere ("RoomNode" for the ID buffer only).
  std::vector<vtkSmartPointer<vtkActor>> actors =
    plannertesting::BuildingActors(renderer, b, false);
  const auto all = st::MakeRoomPolyData(b, -2, outsideNode);
  renderer->GetActiveCamera()->SetViewAngle(60.0);

  // --- (a) generated at the first render ---------------------------------------------------------
  vtkSceneVisPlanner* planner = vtkSceneVisPlanner::Attach(renderer);
  // No time limit: under AddressSanitizer the 0.65 s generation takes more than the default 3 s
  // of processor time (the budget's own test is Core.PortalGeneration.PastItsBudget...).
  planner->SetRoomGenerationBudget(0.0);
  // In the render that needs them (the background: TestSceneVisPlannerBackgroundRooms).
  planner->GenerateRoomsInBackgroundOff();
  renderer->ResetCamera();
  window->Render();
  const std::string reason = planner->GetCullReason();
  ok &= Check(std::string(planner->GetCullMethod()) == "portals" &&
      vtkPortalCuller::SafeDownCast(planner->GetCuller()) &&
      renderer->GetCullers()->GetNumberOfItems() == 1 &&
      planner->GetNumberOfRoomGenerations() == 1 && Has(reason.c_str(), "generated ") &&
      planner->GetFacts().rooms >= 2,
    "no portals given: rooms generated once, culling \"portals\" (" + reason + ")");

  // --- (b) conservative from every room; no generation on camera moves -----------------------
  const Walk walk = WalkRooms(window, renderer, planner, b, actors, all, b.rooms.size());
  ok &= Check(walk.conservative && walk.visible > 0,
    "an eye in each of the " + std::to_string(rooms) +
      " rooms: every visible room drawn (0 false negatives)");
  // (An eye over a stair or in furniture is in no room: frustum-only there, conservatively.)
  ok &= Check(walk.traversed * 4 >= b.rooms.size() * 3,
    "the eye located in a generated room and the portals traversed in " +
      std::to_string(walk.traversed) + " of " + std::to_string(rooms) + " views");
  ok &= Check(walk.culledViews > b.rooms.size() / 2,
    "rooms culled in " + std::to_string(walk.culledViews) + " of " + std::to_string(rooms) +
      " views; " + std::to_string(walk.drawn) + " rooms drawn for " + std::to_string(walk.visible) +
      " visible");
  ok &= Check(planner->GetNumberOfRoomGenerations() == 1 &&
      std::string(planner->GetCullMethod()) == "portals",
    "camera moves: nothing generated again");

  // --- (c) an actor moved: dropped ------------------------------------------------------------
  actors[1]->SetPosition(0.0, 0.0, 0.5);
  window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) != "portals" &&
      Has(planner->GetCullReason(), "dropped") && planner->GetNumberOfRoomGenerations() == 1,
    "an actor moved: generated rooms dropped (" + std::string(planner->GetCullReason()) + ")");
  actors[1]->SetPosition(0.0, 0.0, 0.0);
  window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) != "portals" &&
      planner->GetNumberOfRoomGenerations() == 1,
    "moved back, same actors: not generated again");

  // --- (d) an actor added: generated again -----------------------------------------------------
  const auto& first = b.rooms[0].bounds;
  const double lo[3] = { first.lo.x + 0.5, first.lo.y + 0.5, first.lo.z + 0.3 };
  const double hi[3] = { lo[0] + 0.4, lo[1] + 0.4, lo[2] + 0.4 };
  vtkNew<vtkPolyDataMapper> boxMapper;
  boxMapper->SetInputData(plannertesting::MakeBox(lo, hi, 0));
  vtkNew<vtkActor> box;
  box->SetMapper(boxMapper);
  renderer->AddActor(box);
  actors.push_back(box.Get());
  window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) == "portals" &&
      planner->GetNumberOfRoomGenerations() == 2,
    "an actor added: generated again, culling \"portals\" (" +
      std::string(planner->GetCullReason()) + ")");
  const Walk again = WalkRooms(window, renderer, planner, b, actors, all, 4);
  ok &= Check(again.conservative, "with the box: every visible room drawn from 4 rooms");

  // --- (e) off ----------------------------------------------------------------------------------
  planner->GenerateRoomsOff();
  window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) == "none" && !planner->GetCuller() &&
      renderer->GetCullers()->GetNumberOfItems() == 1 &&
      std::string(renderer->GetCullers()->GetItemAsObject(0)->GetClassName()) ==
        "vtkFrustumCoverageCuller",
    "GenerateRoomsOff(): VTK's culler back");

  // --- (f) not a building ------------------------------------------------------------------------
  vtkNew<vtkRenderer> boxes;
  window->RemoveRenderer(renderer);
  window->AddRenderer(boxes);
  plannertesting::BoxGrid grid(boxes, 4, 4, 1, 0.5);
  vtkSceneVisPlanner* other = vtkSceneVisPlanner::Attach(boxes);
  other->GenerateRoomsInBackgroundOff();
  boxes->ResetCamera();
  window->Render();
  ok &= Check(other->GetNumberOfRoomGenerations() == 0 &&
      Has(other->GetCullReason(), "rooms and portals not generated"),
    "a grid of boxes: not generated (" + std::string(other->GetCullReason()) + ")");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

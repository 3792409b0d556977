// vtkSceneVisPlanner generating rooms in the background (GenerateRoomsInBackground, the default) on
// the building of TestSceneVisPlannerGeneratedRooms (2 floors x 3 x 3 rooms, one actor per room
// plus one for the outside, no RoomId anywhere, no SetPortals()):
//  (a) the first render does not generate: the generation is pending, the plan is not "portals"
//      and the reason says "generating rooms in the background";
//  (b) after WaitForRoomGeneration() the next render adopts the rooms: "portals", with the rooms
//      and portals the synchronous path finds for the same actors, 0 false negatives against the
//      ID buffer from every room, nothing generated again on camera moves;
//  (c) an actor moved while the generation runs: its result is discarded (no rooms in use, the
//      reason says why) and not generated again while the set of actors stays; moved and moved
//      back before it ends: adopted (the rooms fit the actors as they are);
//  (d) an actor added while it runs: that result is discarded, the new set generated for, then
//      "portals" again, still conservative;
//  (e) a planner deleted, and a renderer (owning its attached planner) deleted, while a
//      generation runs: no crash, the renderer's own culler back;
//  (f) a scene that is no building (a grid of boxes): tested in the background too, then not
//      generated for, and the reason says why.
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
#include <vtkRendererCollection.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;
using plannertesting::Check;

bool Has(const char* text, const char* part)
{
  return std::string(text).find(part) != std::string::npos;
}

bool IsPortals(vtkSceneVisPlanner* planner)
{
  return std::string(planner->GetCullMethod()) == "portals" &&
    vtkPortalCuller::SafeDownCast(planner->GetCuller()) != nullptr;
}

/// A renderer of @p window (the only one) with the building's actors and a planner of its own,
/// generating without a time limit: under AddressSanitizer the 0.65 s generation takes more than
/// the default 3 s of processor time.
struct BuildingView
{
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  vtkSceneVisPlanner* planner = nullptr;

  BuildingView(vtkRenderWindow* window, const scenevis::scenes::BuildingScene& b, bool background)
  {
    window->GetRenderers()->RemoveAllItems();
    window->AddRenderer(this->renderer);
    this->actors = plannertesting::BuildingActors(this->renderer, b, false);
    this->renderer->GetActiveCamera()->SetViewAngle(60.0);
    this->renderer->ResetCamera();
    this->planner = vtkSceneVisPlanner::Attach(this->renderer);
    this->planner->SetRoomGenerationBudget(0.0);
    this->planner->SetGenerateRoomsInBackground(background);
  }
};

/// Waits and renders until no generation is pending (at most @p renders times); returns false
/// when one still is.
bool RenderUntilAdopted(vtkRenderWindow* window, vtkSceneVisPlanner* planner, int renders)
{
  for (int i = 0; i < renders && planner->IsRoomGenerationPending(); ++i)
  {
    planner->WaitForRoomGeneration();
    window->Render();
  }
  return !planner->IsRoomGenerationPending();
}
} // namespace

int TestSceneVisPlannerBackgroundRooms(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  const scenevis::scenes::BuildingScene b = scenevis::scenes::building(2, 3, 3, 5);
  const int rooms = static_cast<int>(b.rooms.size());
  const auto all = st::MakeRoomPolyData(b, -2, rooms);
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(200, 150);

  // The synchronous path's rooms and portals for these actors: what the background must match.
  int syncRooms = 0;
  vtkIdType syncPortals = 0;
  {
    BuildingView sync(window, b, false);
    window->Render();
    syncRooms = sync.planner->GetFacts().rooms;
    syncPortals = sync.planner->GetFacts().portals;
    ok &= Check(IsPortals(sync.planner) && syncRooms >= 2 && syncPortals >= 1,
      "synchronous: " + std::to_string(syncRooms) + " rooms, " + std::to_string(syncPortals) +
        " portals at the first render");
  }

  // --- (a) the first render starts the generation and does not wait for it ---------------------
  BuildingView view(window, b, true);
  vtkSceneVisPlanner* planner = view.planner;
  {
    vtkNew<vtkSceneVisPlanner> fresh;
    ok &= Check(fresh->GetGenerateRoomsInBackground(), "in the background by default");
  }
  window->Render();
  ok &= Check(planner->IsRoomGenerationPending() && !IsPortals(planner) &&
      planner->GetFacts().rooms == 0 && planner->GetNumberOfRoomGenerations() == 0 &&
      Has(planner->GetCullReason(), "generating rooms in the background"),
    "first render: pending, culling \"" + std::string(planner->GetCullMethod()) + "\" (" +
      planner->GetCullReason() + ")");

  // --- (b) adopted at the render after it ended --------------------------------------------------
  planner->WaitForRoomGeneration();
  ok &= Check(planner->IsRoomGenerationPending() && !IsPortals(planner),
    "ended but not adopted before a render");
  window->Render();
  ok &= Check(!planner->IsRoomGenerationPending() && IsPortals(planner) &&
      planner->GetNumberOfRoomGenerations() == 1 && planner->GetFacts().rooms == syncRooms &&
      planner->GetFacts().portals == syncPortals && Has(planner->GetCullReason(), "generated ") &&
      !Has(planner->GetCullReason(), "background"),
    "next render: culling \"portals\" with " + std::to_string(planner->GetFacts().rooms) +
      " rooms and " + std::to_string(planner->GetFacts().portals) + " portals, as synchronously (" +
      planner->GetCullReason() + ")");
  const plannertesting::Walk walk =
    plannertesting::WalkRooms(window, view.renderer, planner, b, view.actors, all, b.rooms.size());
  ok &= Check(walk.conservative && walk.visible > 0 && walk.culledViews > b.rooms.size() / 2,
    "an eye in each of the " + std::to_string(rooms) +
      " rooms: every visible room drawn (0 false negatives), rooms culled in " +
      std::to_string(walk.culledViews) + " views");
  ok &= Check(planner->GetNumberOfRoomGenerations() == 1 && IsPortals(planner) &&
      !planner->IsRoomGenerationPending(),
    "camera moves: nothing generated again");

  // --- (c) an actor moved while it runs: discarded ---------------------------------------------
  {
    BuildingView moved(window, b, true);
    window->Render();
    const bool started = moved.planner->IsRoomGenerationPending();
    moved.actors[1]->SetPosition(0.0, 0.0, 0.5);
    window->Render(); // the move seen while the worker may still run
    moved.planner->WaitForRoomGeneration();
    window->Render();
    ok &= Check(started && !moved.planner->IsRoomGenerationPending() && !IsPortals(moved.planner) &&
        moved.planner->GetFacts().rooms == 0 && Has(moved.planner->GetCullReason(), "discarded") &&
        moved.planner->GetNumberOfRoomGenerations() == 1,
      "an actor moved while generating: the result discarded, no rooms in use (" +
        std::string(moved.planner->GetCullReason()) + ")");
    moved.actors[1]->SetPosition(0.0, 0.0, 0.0);
    window->Render();
    ok &= Check(!IsPortals(moved.planner) && !moved.planner->IsRoomGenerationPending() &&
        moved.planner->GetNumberOfRoomGenerations() == 1,
      "moved back, same actors: not generated again");
  }
  {
    BuildingView back(window, b, true);
    window->Render();
    back.actors[1]->SetPosition(0.0, 0.0, 0.5);
    window->Render();
    back.actors[1]->SetPosition(0.0, 0.0, 0.0);
    back.planner->WaitForRoomGeneration();
    window->Render();
    ok &= Check(IsPortals(back.planner) && back.planner->GetFacts().rooms == syncRooms,
      "moved and moved back before it ended: adopted (" +
        std::string(back.planner->GetCullReason()) + ")");
  }

  // --- (d) an actor added while it runs: generated again for the new set ------------------------
  {
    BuildingView added(window, b, true);
    window->Render();
    const auto& first = b.rooms[0].bounds;
    const double lo[3] = { first.lo.x + 0.5, first.lo.y + 0.5, first.lo.z + 0.3 };
    const double hi[3] = { lo[0] + 0.4, lo[1] + 0.4, lo[2] + 0.4 };
    vtkNew<vtkPolyDataMapper> boxMapper;
    boxMapper->SetInputData(plannertesting::MakeBox(lo, hi, 0));
    vtkNew<vtkActor> box;
    box->SetMapper(boxMapper);
    added.renderer->AddActor(box);
    added.actors.push_back(box.Get());
    window->Render();
    ok &= Check(added.planner->IsRoomGenerationPending() && !IsPortals(added.planner) &&
        Has(added.planner->GetCullReason(), "generating rooms in the background"),
      "an actor added while generating: still generating (" +
        std::string(added.planner->GetCullReason()) + ")");
    const bool adopted = RenderUntilAdopted(window, added.planner, 3);
    ok &=
      Check(adopted && IsPortals(added.planner) && added.planner->GetNumberOfRoomGenerations() == 2,
        "then generated for the new set: culling \"portals\", " +
          std::to_string(added.planner->GetNumberOfRoomGenerations()) +
          " generations (the first discarded)");
    const plannertesting::Walk again =
      plannertesting::WalkRooms(window, added.renderer, added.planner, b, added.actors, all, 4);
    ok &= Check(again.conservative, "with the box: every visible room drawn from 4 rooms");
  }

  // --- (e) deleted while it runs ---------------------------------------------------------------
  {
    vtkNew<vtkRenderer> renderer;
    window->GetRenderers()->RemoveAllItems();
    window->AddRenderer(renderer);
    const auto actors = plannertesting::BuildingActors(renderer, b, false);
    renderer->ResetCamera();
    bool pending = false;
    {
      vtkNew<vtkSceneVisPlanner> owned;
      owned->SetRenderer(renderer);
      owned->SetRoomGenerationBudget(0.0);
      window->Render();
      pending = owned->IsRoomGenerationPending();
    } // deleted here, its worker still running
    window->Render();
    ok &= Check(pending && renderer->GetCullers()->GetNumberOfItems() == 1 &&
        std::string(renderer->GetCullers()->GetItemAsObject(0)->GetClassName()) ==
          "vtkFrustumCoverageCuller",
      "a planner deleted while generating: clean, VTK's culler back");
  }
  {
    auto renderer = vtkSmartPointer<vtkRenderer>::New();
    window->GetRenderers()->RemoveAllItems();
    window->AddRenderer(renderer);
    const auto actors = plannertesting::BuildingActors(renderer, b, false);
    renderer->ResetCamera();
    vtkSceneVisPlanner* attached = vtkSceneVisPlanner::Attach(renderer);
    attached->SetRoomGenerationBudget(0.0);
    window->Render();
    const bool pending = attached->IsRoomGenerationPending();
    window->RemoveRenderer(renderer);
    renderer = nullptr; // and its planner with it, while the worker runs
    ok &= Check(pending, "a renderer (owning its planner) deleted while generating: clean");
  }

  // --- (f) not a building ------------------------------------------------------------------------
  {
    vtkNew<vtkRenderer> boxes;
    window->GetRenderers()->RemoveAllItems();
    window->AddRenderer(boxes);
    plannertesting::BoxGrid grid(boxes, 4, 4, 1, 0.5);
    vtkSceneVisPlanner* other = vtkSceneVisPlanner::Attach(boxes);
    boxes->ResetCamera();
    window->Render();
    const bool adopted = RenderUntilAdopted(window, other, 2);
    ok &= Check(adopted && other->GetNumberOfRoomGenerations() == 0 && !IsPortals(other) &&
        Has(other->GetCullReason(), "rooms and portals not generated"),
      "a grid of boxes: not generated (" + std::string(other->GetCullReason()) + ")");
  }
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

// The building of scenes::building walked room by room under a vtkSceneVisPlanner: from an eye in
// the middle of each room, what the cullers kept against the ID buffer's visible set (the
// generated-rooms tests, in the render and in the background, share it).
#ifndef RoomWalk_h
#define RoomWalk_h

#include "PlannerTesting.h"

#include "vtkPortalCuller.h"
#include "vtkSceneVisPlanner.h"

#include "scenevis/Scenes.h"
#include "scenevis/testing/IdBuffer.h"

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

namespace plannertesting
{

/// The building's rooms from eyes in the middle of each room: whether every visible room was
/// drawn, and in how many views some actor was culled.
struct Walk
{
  bool conservative = true;
  std::size_t culledViews = 0;
  std::size_t drawn = 0;
  std::size_t visible = 0;
  std::size_t traversed = 0; ///< views the portal culler traversed (no frustum-only fallback)
};

inline Walk WalkRooms(vtkRenderWindow* window, vtkRenderer* renderer, vtkSceneVisPlanner* planner,
  const scenevis::scenes::BuildingScene& b, const std::vector<vtkSmartPointer<vtkActor>>& actors,
  vtkPolyData* all, std::size_t rooms)
{
  const int outsideNode = static_cast<int>(b.rooms.size());
  vtkNew<RecordingCuller> recorder;
  vtkCamera* camera = renderer->GetActiveCamera();
  Walk walk;
  for (std::size_t r = 0; r < rooms; ++r)
  {
    const auto& room = b.rooms[r];
    const auto& box = room.bounds;
    const double eye[3] = { (box.lo.x + box.hi.x) / 2, (box.lo.y + box.hi.y) / 2,
      box.lo.z + 0.6 * (box.hi.z - box.lo.z) };
    camera->SetPosition(eye);
    camera->SetFocalPoint(eye[0] + 1.0, eye[1] + 0.3 * (room.ix % 2 ? 1 : -1), eye[2] - 0.1);
    camera->SetViewUp(0, 0, 1);
    camera->SetClippingRange(0.05, 200.0);
    planner->Plan(); // so that the recorder goes after the planner's culler
    renderer->RemoveCuller(recorder);
    renderer->AddCuller(recorder);
    window->Render();
    std::vector<std::uint32_t> drawn;
    for (vtkProp* prop : recorder->Kept)
      for (std::size_t a = 0; a < actors.size(); ++a)
        if (actors[a].Get() == prop && a <= b.rooms.size())
          drawn.push_back(static_cast<std::uint32_t>(a == 0 ? outsideNode : a - 1));
    namespace st = scenevis::testing;
    st::IdRenderOptions options;
    options.originalIdArray = "RoomNode";
    options.cameraClippingRange = true;
    const std::vector<std::uint32_t> visible =
      st::VisibleSet(st::RenderIdBuffer(window, all, camera, options));
    const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
    if (!check.conservative)
      std::cout << "room " << room.id << ": " << check.Summary() << "\n";
    walk.conservative &= check.conservative;
    walk.culledViews += recorder->Kept.size() < actors.size() ? 1 : 0;
    auto* portals = vtkPortalCuller::SafeDownCast(planner->GetCuller());
    walk.traversed += portals && std::string(portals->GetFallbackReason()).empty() &&
        std::string(portals->GetGraphReport()).find("error") == std::string::npos
      ? 1
      : 0;
    if (portals && !std::string(portals->GetFallbackReason()).empty())
      std::cout << "room " << room.id << ": frustum only, " << portals->GetFallbackReason() << "\n";
    walk.drawn += drawn.size();
    walk.visible += visible.size();
  }
  renderer->RemoveCuller(recorder);
  return walk;
}
} // namespace plannertesting

#endif

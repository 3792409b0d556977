// Walks a camera through the generated building (2 floors x 4 x 4 rooms) along a path of doors,
// rendering offscreen with vtkPortalCuller (exact frustum mode): one actor per room, the portals
// as polydata with RoomA/RoomB. Writes a few PNG frames and prints per-frame statistics (rooms
// visited, props and triangles drawn, cull time).
//
//   BuildingWalkthrough [output-dir]
#include "vtkDemoScenePortals.h"
#include "vtkPortalCuller.h"
#include "vtkSceneVisHeadlessWindows.h"

#include "scenevis/Scenes.h"

#include <glm/geometric.hpp>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <queue>
#include <string>
#include <vector>

namespace scenes = scenevis::scenes;

namespace
{
/// The polygons of room @p room (scenes::kOutside for the outside), with a "RoomId" field array.
vtkSmartPointer<vtkPolyData> RoomPolyData(const scenes::BuildingScene& b, int room)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  for (std::size_t i = 0; i < b.mesh.polygonCount(); ++i)
  {
    if (b.room[i] != room || b.parts[b.part[i]].opacity < 1.0)
    {
      continue; // glass is left out: this example shows opaque culling
    }
    polys->InsertNextCell(static_cast<vtkIdType>(b.mesh.polygonSize(i)));
    for (std::uint32_t k = 0; k < b.mesh.polygonSize(i); ++k)
    {
      const glm::dvec3& p = b.mesh.points[b.mesh.polygon(i)[k]];
      polys->InsertCellPoint(points->InsertNextPoint(p.x, p.y, p.z));
    }
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetPolys(polys);
  vtkNew<vtkIntArray> id;
  id->SetName("RoomId");
  id->InsertNextValue(room);
  pd->GetFieldData()->AddArray(id);
  return pd;
}

glm::dvec3 Centre(const std::vector<glm::dvec3>& polygon)
{
  glm::dvec3 c(0.0);
  for (const auto& p : polygon)
  {
    c += p;
  }
  return c / static_cast<double>(polygon.size());
}

/// Waypoints at eye height: room centres and door centres from room @p from to room @p to
/// (breadth-first over the doors of the ground floor).
std::vector<glm::dvec3> DoorPath(const scenes::BuildingScene& b, int from, int to, double eyeZ)
{
  std::map<int, std::pair<int, int>> came; // room -> (previous room, portal)
  std::queue<int> queue;
  queue.push(from);
  came[from] = { -1, -1 };
  while (!queue.empty() && !came.count(to))
  {
    const int r = queue.front();
    queue.pop();
    for (std::size_t i = 0; i < b.portals.size(); ++i)
    {
      const auto& p = b.portals[i];
      if (p.kind != scenes::PortalKind::Door || (p.roomA != r && p.roomB != r))
      {
        continue;
      }
      const int next = p.roomA == r ? p.roomB : p.roomA;
      if (!came.count(next))
      {
        came[next] = { r, static_cast<int>(i) };
        queue.push(next);
      }
    }
  }
  std::vector<glm::dvec3> path;
  auto at = [eyeZ](glm::dvec3 p)
  {
    p.z = eyeZ;
    return p;
  };
  for (int r = to; r >= 0; r = came[r].first)
  {
    path.push_back(at(b.rooms[static_cast<std::size_t>(r)].bounds.center()));
    if (came[r].second >= 0)
    {
      path.push_back(at(Centre(b.portals[static_cast<std::size_t>(came[r].second)].polygon)));
    }
  }
  std::reverse(path.begin(), path.end());
  return path;
}
} // namespace

int main(int argc, char* argv[])
{
  const std::filesystem::path out = argc > 1 ? argv[1] : "building-walkthrough";
  std::filesystem::create_directories(out);
  const scenes::BuildingScene b = scenes::building(2, 4, 4, 1);

  auto window = scenevis::headless::MakeRenderWindow(480, 360);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.55, 0.7, 0.9); // sky, seen through windows
  window->AddRenderer(renderer);
  const glm::dvec3 palette[] = { { 0.85, 0.8, 0.7 }, { 0.7, 0.8, 0.85 }, { 0.8, 0.75, 0.85 },
    { 0.75, 0.85, 0.7 } };
  for (int r = scenes::kOutside; r < static_cast<int>(b.rooms.size()); ++r)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(RoomPolyData(b, r));
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    const glm::dvec3 c = r < 0 ? glm::dvec3(0.6) : palette[r % 4];
    actor->GetProperty()->SetColor(c.x, c.y, c.z);
    renderer->AddActor(actor);
  }
  vtkNew<vtkLight> headlight; // follows the camera: rooms are lit from the eye
  headlight->SetLightTypeToHeadlight();
  renderer->AddLight(headlight);

  vtkNew<vtkPortalCuller> culler;
  culler->SetPortals(scenevis::MakePortalPolyData(b));
  culler->SetMode(vtkPortalCuller::MODE_EXACT_FRUSTUM);
  renderer->AddCuller(culler);

  const int perFloor = 16;
  const std::vector<glm::dvec3> path = DoorPath(b, 0, perFloor - 1, 1.6);
  // Resample the polyline into frames; look ahead along the path.
  std::vector<double> length{ 0.0 };
  for (std::size_t i = 1; i < path.size(); ++i)
  {
    length.push_back(length.back() + glm::length(path[i] - path[i - 1]));
  }
  auto pointAt = [&](double s)
  {
    s = std::clamp(s, 0.0, length.back());
    std::size_t i = 1;
    while (i + 1 < path.size() && length[i] < s)
    {
      ++i;
    }
    const double t = (s - length[i - 1]) / std::max(length[i] - length[i - 1], 1e-9);
    return path[i - 1] + t * (path[i] - path[i - 1]);
  };
  const int frames = 24;
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(70.0);
  std::printf("walking %zu waypoints (%.1f m) from room 0 to room %d, %d frames, %d rooms\n",
    path.size(), length.back(), perFloor - 1, frames, static_cast<int>(b.rooms.size()));
  std::printf("frame  room-visits  portals  props drawn/total  triangles drawn/total  cull ms\n");
  double cullTotal = 0.0;
  long long drawnTotal = 0, allTotal = 0;
  for (int f = 0; f < frames; ++f)
  {
    const double s = length.back() * f / (frames - 1);
    const glm::dvec3 eye = pointAt(s);
    glm::dvec3 ahead = pointAt(s + 1.5);
    if (glm::length(ahead - eye) < 1e-3)
    {
      ahead = eye + (path.back() - path[path.size() - 2]);
    }
    camera->SetPosition(eye.x, eye.y, eye.z);
    camera->SetFocalPoint(ahead.x, ahead.y, ahead.z);
    camera->SetViewUp(0, 0, 1);
    camera->SetClippingRange(0.05, 200.0);
    window->Render();
    // The renderer passes the culler what vtkFrustumCoverageCuller kept: totals are over those.
    std::printf("%5d  %11d  %7d  %6d/%-10d  %9lld/%-11lld  %.3f%s\n", f,
      culler->GetNumberOfRoomsVisited(), culler->GetNumberOfPortalsTraversed(),
      culler->GetNumberOfPropsDrawn(),
      culler->GetNumberOfPropsDrawn() + culler->GetNumberOfPropsCulled(),
      static_cast<long long>(culler->GetNumberOfTrianglesDrawn()),
      static_cast<long long>(culler->GetNumberOfTrianglesTotal()), culler->GetLastCullTime(),
      culler->GetFrustumOnly() ? (std::string(" fallback: ") + culler->GetFallbackReason()).c_str()
                               : "");
    cullTotal += culler->GetLastCullTime();
    drawnTotal += culler->GetNumberOfTrianglesDrawn();
    allTotal += culler->GetNumberOfTrianglesTotal();
    if (f % 8 == 0 || f == frames - 1)
    {
      vtkNew<vtkWindowToImageFilter> grab;
      grab->SetInput(window);
      grab->ReadFrontBufferOff();
      vtkNew<vtkPNGWriter> writer;
      writer->SetInputConnection(grab->GetOutputPort());
      char name[64];
      std::snprintf(name, sizeof(name), "frame-%02d.png", f);
      writer->SetFileName((out / name).string().c_str());
      writer->Write();
    }
  }
  std::printf("walked %d frames: mean cull %.3f ms, %.1f %% of the frustum-kept triangles culled "
              "by portals; frames in %s\n",
    frames, cullTotal / frames,
    allTotal ? 100.0 * (1.0 - static_cast<double>(drawnTotal) / allTotal) : 0.0,
    out.string().c_str());
  return EXIT_SUCCESS;
}

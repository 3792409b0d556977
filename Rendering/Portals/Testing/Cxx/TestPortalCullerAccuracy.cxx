// Accuracy of vtkPortalCuller against the exact visible set (ID buffer) in the generated building
// (2 floors x 4 x 4 rooms, one actor per room plus one for the outside): over 200 random eyes --
// anywhere in the rooms, near doors, windows and stair holes, and exactly on portal planes --
// every conservative mode must draw every room that covers any pixel (0 false negatives, edge
// pixels included: the generated room and outside shells are watertight, see
// Scenes.BuildingRoomShellsAreWatertight); likewise for 30 parallel projections from outside the
// building. Prints over-draw (rooms drawn / rooms visible) and the cost per frame (cull and
// render) for screen rectangles, exact frustum, PVS and no culling. The portals go through a
// .vtp file.
#include "vtkPortalCuller.h"

#include "scenevis/PortalGraph.h"
#include "scenevis/Scenes.h"
#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <glm/geometric.hpp>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;
namespace scenes = scenevis::scenes;

struct ModeResult
{
  const char* name;
  int mode;
  std::size_t falseNegatives = 0; ///< rooms covering a pixel (any pixel) that were not drawn
  std::size_t drawn = 0;
  std::uint64_t triangles = 0;
  double cullMs = 0.0;
  double frameMs = 0.0;
};

/// The exact visible set of @p pd's rooms ("RoomNode" as the id) for @p camera, with the
/// camera's own clipping range: the frames this test checks are drawn with it.
st::IdImage RenderRoomIds(vtkRenderWindow* window, vtkPolyData* pd, vtkCamera* camera)
{
  st::IdRenderOptions options;
  options.originalIdArray = "RoomNode";
  options.cameraClippingRange = true;
  return st::RenderIdBuffer(window, pd, camera, options);
}

/// Where the eyes of the test are.
enum EyeKind
{
  kInRoom,       ///< uniformly in a room, at least 0.15 from its walls, floor and ceiling
  kNearPortal,   ///< within 0.3 of a portal's plane, over the opening
  kOnPortalPlane ///< exactly on a portal's plane, over the opening
};
} // namespace

int TestPortalCullerAccuracy(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  const scenes::BuildingScene b = scenes::building(2, 4, 4, 5);
  const int rooms = static_cast<int>(b.rooms.size());
  const int outsideNode = rooms;

  // Portals through a VTK XML file, as any tool would provide them. In this build tree's
  // Testing/Temporary, not the system's temporary directory: the files' names are fixed, and
  // another checkout's run of this test must not write them while this one reads them.
  const std::filesystem::path tempDir = st::TemporaryDirectory();
  std::error_code ignored;
  std::filesystem::create_directories(tempDir, ignored);
  const std::string portalFile = (tempDir / "scenevis-test-building-portals.vtp").string();
  const std::string pvsFile = (tempDir / "scenevis-test-building.pvs").string();
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(st::MakePortalPolyData(b));
    writer->SetFileName(portalFile.c_str());
    if (!writer->Write())
    {
      std::cerr << "cannot write " << portalFile << "\n";
      return EXIT_FAILURE;
    }
  }
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(portalFile.c_str());
  reader->Update();

  auto window = st::MakeRenderWindow(200, 150);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<vtkProp*> props;
  for (int r = -1; r < rooms; ++r)
  {
    auto pd = st::MakeRoomPolyData(b, r, outsideNode);
    vtkNew<vtkIntArray> id; // the actor's room, as field data
    id->SetName("RoomId");
    id->InsertNextValue(r);
    pd->GetFieldData()->AddArray(id);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(pd);
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.4 + 0.6 * ((r * 37 + 50) % 100) / 100.0, 0.7, 0.5);
    renderer->AddActor(actor);
    actors.push_back(actor);
    props.push_back(actor);
  }
  auto all = st::MakeRoomPolyData(b, -2, outsideNode);

  vtkNew<vtkPortalCuller> culler;
  culler->SetPortals(reader->GetOutput());
  renderer->AddCuller(culler);
  // Progress: the portal flow (the default method) reports about every 50 ms and at the end.
  double lastProgress = -1.0;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&lastProgress);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* last, void* fraction)
    { *static_cast<double*>(last) = *static_cast<double*>(fraction); });
  culler->AddObserver(vtkCommand::ProgressEvent, onProgress);
  bool ok = culler->GetPVSMethod() == vtkPortalCuller::PVS_PORTAL_FLOW &&
    culler->ComputePVS(renderer) && culler->SavePVS(pvsFile.c_str()) &&
    culler->LoadPVS(renderer, pvsFile.c_str());
  if (!ok || lastProgress != 1.0 || culler->GetPVSDegradedPortals() != 0 ||
    culler->GetPVSBudgetExceeded() || !(culler->GetPVSAverageSetSize() > 1.0))
  {
    std::cerr << "FAIL PVS compute/save/load (last progress " << lastProgress << ", degraded "
              << culler->GetPVSDegradedPortals() << ")\n";
    return EXIT_FAILURE;
  }
  if (std::string(culler->GetGraphReport()).find("error") != std::string::npos)
  {
    std::cerr << "FAIL graph report: " << culler->GetGraphReport() << "\n";
    return EXIT_FAILURE;
  }

  // Eyes must be in a room (not in furniture or stair steps) to be meaningful.
  scenevis::portals::CellSceneInput input = scenevis::portals::cellSceneOf(b);
  const auto graph = scenevis::portals::PortalGraph::build(input);
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ModeResult modes[] = { { "screen rectangles", vtkPortalCuller::MODE_SCREEN_RECTANGLES },
    { "exact frustum", vtkPortalCuller::MODE_EXACT_FRUSTUM }, { "pvs", vtkPortalCuller::MODE_PVS },
    { "no culling", vtkPortalCuller::MODE_OFF } };
  std::size_t visibleTotal = 0;
  long long trianglesTotal = 0;
  int views = 0;
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(60.0);
  window->Render(); // warm-up: shaders, buffers
  const int kViews = 200;
  int viewsOf[3] = { 0, 0, 0 };
  std::vector<std::uint64_t> roomTriangles(static_cast<std::size_t>(rooms) + 1, 0);
  for (std::size_t i = 0; i < b.mesh.polygonCount(); ++i)
  {
    roomTriangles[static_cast<std::size_t>(b.room[i] < 0 ? outsideNode : b.room[i])] +=
      b.mesh.polygonSize(i) - 2;
  }
  std::uint64_t visibleTriangles = 0;
  while (views < kViews)
  {
    // Half the eyes anywhere in a room; a quarter near a portal, a quarter on its plane. Eyes
    // keep 0.12 from every wall, so that no near plane (the culler's 0.05, the ID render's
    // reset range) reaches through one: the assumption of every guarantee.
    const auto kind = static_cast<EyeKind>(views < kViews / 2 ? kInRoom
        : views < 3 * kViews / 4                              ? kNearPortal
                                                              : kOnPortalPlane);
    glm::dvec3 eye;
    if (kind == kInRoom)
    {
      const auto& cell = b.rooms[rng() % b.rooms.size()].bounds;
      const double m = 0.5 * scenes::kWallThickness + 0.15;
      const double mz = 0.5 * scenes::kSlabThickness + 0.15;
      eye = glm::dvec3(cell.lo.x + m + u(rng) * (cell.hi.x - cell.lo.x - 2 * m),
        cell.lo.y + m + u(rng) * (cell.hi.y - cell.lo.y - 2 * m),
        cell.lo.z + mz + u(rng) * (cell.hi.z - cell.lo.z - 2 * mz));
    }
    else
    {
      const scenes::Portal& portal = b.portals[rng() % b.portals.size()];
      // A point of the opening at least 0.12 from its edges (portals are rectangles p0..p3).
      const glm::dvec3 e1 = portal.polygon[1] - portal.polygon[0];
      const glm::dvec3 e3 = portal.polygon[3] - portal.polygon[0];
      const double l1 = glm::length(e1), l3 = glm::length(e3);
      eye = portal.polygon[0] + (0.12 + u(rng) * (l1 - 0.24)) / l1 * e1 +
        (0.12 + u(rng) * (l3 - 0.24)) / l3 * e3;
      if (kind == kNearPortal)
      {
        eye += (u(rng) - 0.5) * 0.6 * portal.normal;
      }
    }
    if (graph.locate(eye, 0.0).nodes.empty())
    {
      continue; // inside furniture or a stair step, or beyond a window
    }
    ++views;
    ++viewsOf[kind];
    const double yaw = u(rng) * 6.283185307, pitch = (u(rng) - 0.5) * 0.8;
    camera->SetPosition(eye.x, eye.y, eye.z);
    camera->SetFocalPoint(eye.x + std::cos(yaw) * std::cos(pitch),
      eye.y + std::sin(yaw) * std::cos(pitch), eye.z + std::sin(pitch));
    camera->SetViewUp(0, 0, 1);
    camera->SetClippingRange(0.05, 200.0);

    const st::IdImage ids = RenderRoomIds(window, all, camera);
    const std::vector<std::uint32_t> visible = st::VisibleSet(ids);
    visibleTotal += visible.size();
    for (const std::uint32_t v : visible)
    {
      visibleTriangles += roomTriangles[v];
    }
    for (ModeResult& m : modes)
    {
      culler->SetMode(m.mode);
      std::vector<vtkProp*> list = props;
      int length = static_cast<int>(list.size());
      int initialized = 0;
      culler->Cull(renderer, list.data(), length, initialized);
      m.cullMs += culler->GetLastCullTime();
      std::vector<std::uint32_t> drawn;
      for (int i = 0; i < length; ++i)
      {
        const auto it = std::find(props.begin(), props.end(), list[static_cast<std::size_t>(i)]);
        const int room = static_cast<int>(it - props.begin()) - 1;
        drawn.push_back(static_cast<std::uint32_t>(room < 0 ? outsideNode : room));
      }
      const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
      for (const std::uint32_t missing : check.missing)
      {
        const auto pixels = std::count(ids.ids.begin(), ids.ids.end(), missing);
        const auto at = std::find(ids.ids.begin(), ids.ids.end(), missing) - ids.ids.begin();
        ++m.falseNegatives;
        std::cerr << "FAIL " << m.name << " view " << views << " (eye kind " << kind << ") eye ("
                  << eye.x << ", " << eye.y << ", " << eye.z << ") focal ("
                  << camera->GetFocalPoint()[0] << ", " << camera->GetFocalPoint()[1] << ", "
                  << camera->GetFocalPoint()[2] << "): room " << missing << " not drawn, " << pixels
                  << " pixel(s), first at (" << at % ids.width << ", " << at / ids.width << ")\n";
      }
      m.drawn += drawn.size();
      m.triangles += static_cast<std::uint64_t>(culler->GetNumberOfTrianglesDrawn());
      trianglesTotal = static_cast<long long>(culler->GetNumberOfTrianglesTotal());
      // The cost of a frame with this mode installed (the renderer's frustum culler runs first).
      const auto t0 = std::chrono::steady_clock::now();
      window->Render();
      m.frameMs +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
  }
  std::printf("\nPortal culling accuracy, building 2 x 4 x 4 (%d rooms + outside, %lld "
              "triangles), %d views (%d in rooms, %d near portals, %d on portal planes), %zu "
              "rooms visible in all (ID buffer, every pixel), %.0f triangles per frame in the "
              "visible rooms:\n",
    rooms, trianglesTotal, views, viewsOf[kInRoom], viewsOf[kNearPortal], viewsOf[kOnPortalPlane],
    visibleTotal, static_cast<double>(visibleTriangles) / views);
  std::printf("| mode | false negatives | rooms drawn / visible | triangles drawn per frame "
              "(/ in visible rooms) | cull ms/frame | frame ms (cull + render %dx%d) |\n"
              "|---|---|---|---|---|---|\n",
    window->GetSize()[0], window->GetSize()[1]);
  bool pass = true;
  for (const ModeResult& m : modes)
  {
    std::printf("| %s | %zu | %.2f | %.0f (%.2f) | %.4f | %.2f |\n", m.name, m.falseNegatives,
      static_cast<double>(m.drawn) / static_cast<double>(visibleTotal),
      static_cast<double>(m.triangles) / views,
      static_cast<double>(m.triangles) / static_cast<double>(visibleTriangles), m.cullMs / views,
      m.frameMs / views);
    pass = pass && m.falseNegatives == 0;
  }
  // Exact is at least as tight as rectangles, and both cull most of the building.
  pass = pass && modes[1].drawn <= modes[0].drawn &&
    modes[0].drawn < static_cast<std::size_t>(views) * static_cast<std::size_t>(rooms) / 4;

  // Parallel projections from outside: rays start on a near rectangle outside the building and
  // enter rooms only through windows. Same oracle, every pixel.
  camera->ParallelProjectionOn();
  std::size_t parallelMisses = 0, parallelDrawn = 0, parallelVisible = 0;
  const int kParallelViews = 30;
  for (int i = 0; i < kParallelViews; ++i)
  {
    const double yaw = u(rng) * 6.283185307, pitch = (u(rng) - 0.4) * 0.6;
    const glm::dvec3 target((u(rng) - 0.5) * 14.0, (u(rng) - 0.5) * 10.0, 0.5 + u(rng) * 5.0);
    const glm::dvec3 eye = target +
      40.0 *
        glm::dvec3(
          std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
    camera->SetPosition(eye.x, eye.y, eye.z);
    camera->SetFocalPoint(target.x, target.y, target.z);
    camera->SetViewUp(0, 0, 1);
    camera->SetParallelScale(2.0 + u(rng) * 8.0);
    camera->SetClippingRange(1.0, 200.0);
    const st::IdImage ids = RenderRoomIds(window, all, camera);
    const std::vector<std::uint32_t> visible = st::VisibleSet(ids);
    parallelVisible += visible.size();
    for (int m = 0; m < 3; ++m)
    {
      culler->SetMode(modes[m].mode);
      std::vector<vtkProp*> list = props;
      int length = static_cast<int>(list.size());
      int initialized = 0;
      culler->Cull(renderer, list.data(), length, initialized);
      std::vector<std::uint32_t> drawn;
      for (int k = 0; k < length; ++k)
      {
        const auto it = std::find(props.begin(), props.end(), list[static_cast<std::size_t>(k)]);
        const int room = static_cast<int>(it - props.begin()) - 1;
        drawn.push_back(static_cast<std::uint32_t>(room < 0 ? outsideNode : room));
      }
      parallelDrawn += drawn.size();
      for (const std::uint32_t missing : st::CullingIsConservative(visible, drawn).missing)
      {
        ++parallelMisses;
        std::cerr << "FAIL parallel " << modes[m].name << " view " << i << " eye (" << eye.x << ", "
                  << eye.y << ", " << eye.z << "): room " << missing << " not drawn, "
                  << std::count(ids.ids.begin(), ids.ids.end(), missing) << " pixel(s), first at "
                  << (std::find(ids.ids.begin(), ids.ids.end(), missing) - ids.ids.begin()) %
            ids.width
                  << ", "
                  << (std::find(ids.ids.begin(), ids.ids.end(), missing) - ids.ids.begin()) /
            ids.width
                  << "\n";
      }
      if (culler->GetFrustumOnly())
      {
        ++parallelMisses; // from outside the building a parallel view must not fall back
        std::cerr << "FAIL parallel view " << i << " fell back: " << culler->GetFallbackReason()
                  << "\n";
      }
    }
  }
  camera->ParallelProjectionOff();
  std::printf("\nParallel projections from outside, %d views: false negatives %zu, rooms drawn / "
              "visible %.2f (three modes together)\n",
    kParallelViews, parallelMisses,
    static_cast<double>(parallelDrawn) / (3.0 * static_cast<double>(parallelVisible)));
  pass = pass && parallelMisses == 0;
  if (!pass)
  {
    std::cerr << "FAIL: false negatives or no culling\n";
  }
  return vtkOutput.ExitCode(pass ? EXIT_SUCCESS : EXIT_FAILURE);
}

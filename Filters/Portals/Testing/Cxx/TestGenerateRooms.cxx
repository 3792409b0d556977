// Specification: vtkGenerateRooms on the demo building (2 floors x 3 x 3 rooms, doors, windows
// with glass, stairs, furniture) as a user gets it from vtkDemoSceneSource, its hand-made rooms and
// portals ignored:
// - the model comes out whole (same cells and points) with a RoomId cell array that replaces the
//   source's, every cell in a room or -1; no leak, no dropped polygon, the glass counted as
//   see-through;
// - portals in the portal scene format (RoomA < RoomB, or RoomB -1 for the windows: at least one
//   per window of the building), each a planar polygon;
// - used as a user would (one actor per generated room, split with vtkThreshold, and
//   vtkPortalCuller given the portals output), the culler never misses a room that covers a pixel
//   (ID buffer of the whole model, every pixel) from 40 eyes in the rooms and 10 outside, and culls
//   most rooms: fewer than half the rooms drawn per inside view on average;
// - a second update with nothing changed does not generate again.
#include "vtkGenerateRooms.h"

#include "vtkDemoSceneSource.h"
#include "vtkPortalCuller.h"

#include "scenevis/Scenes.h"
#include "scenevis/testing/Expect.h"
#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSetAttributes.h>
#include <vtkGeometryFilter.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkThreshold.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

namespace
{
namespace st = scenevis::testing;
namespace scenes = scenevis::scenes;

/// Whether all points of polygon @p cell of @p pd lie within @p tolerance of the plane through its
/// first point with its Newell normal (false for a degenerate polygon).
bool IsPlanar(vtkPolyData* pd, vtkIdType cell, double tolerance)
{
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  pd->GetPolys()->GetCellAtId(cell, npts, pts);
  double n[3] = { 0, 0, 0 }, p0[3];
  pd->GetPoint(pts[0], p0);
  for (vtkIdType k = 0; k < npts; ++k)
  {
    double a[3], b[3];
    pd->GetPoint(pts[k], a);
    pd->GetPoint(pts[(k + 1) % npts], b);
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(length > 0.0))
  {
    return false;
  }
  for (vtkIdType k = 0; k < npts; ++k)
  {
    double a[3];
    pd->GetPoint(pts[k], a);
    const double d = ((a[0] - p0[0]) * n[0] + (a[1] - p0[1]) * n[1] + (a[2] - p0[2]) * n[2]);
    if (std::abs(d) / length > tolerance)
    {
      return false;
    }
  }
  return true;
}

/// The cells of @p model whose @p array value is @p room, as polydata (what a user would do).
vtkSmartPointer<vtkPolyData> RoomPart(vtkPolyData* model, const char* array, int room)
{
  vtkNew<vtkThreshold> threshold;
  threshold->SetInputData(model);
  threshold->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, array);
  threshold->SetLowerThreshold(room - 0.5);
  threshold->SetUpperThreshold(room + 0.5);
  threshold->SetThresholdFunction(vtkThreshold::THRESHOLD_BETWEEN);
  vtkNew<vtkGeometryFilter> surface;
  surface->SetInputConnection(threshold->GetOutputPort());
  surface->Update();
  return surface->GetOutput();
}
} // namespace

int TestGenerateRooms(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  const int floors = 2, roomsX = 3, roomsY = 3;
  const unsigned int seed = 5;
  vtkNew<vtkDemoSceneSource> source;
  source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
  source->SetFloors(floors);
  source->SetRoomsX(roomsX);
  source->SetRoomsY(roomsY);
  source->SetSeed(seed);
  const scenes::BuildingScene b = scenes::building(floors, roomsX, roomsY, seed);

  vtkNew<vtkGenerateRooms> rooms;
  SCENEVIS_EXPECT(rooms->GetStatus() == vtkGenerateRooms::STATUS_NOT_RUN);
  rooms->SetInputConnection(source->GetOutputPort());
  rooms->Update();
  vtkPolyData* model = rooms->GetOutput();
  vtkPolyData* portals = rooms->GetPortalsOutput();
  vtkPolyData* input = source->GetOutput();
  const int roomCount = rooms->GetNumberOfRooms();
  std::cout << "generated " << roomCount << " rooms (" << b.rooms.size() << " hand-made), "
            << rooms->GetNumberOfPortals() << " portals (" << rooms->GetNumberOfExteriorPortals()
            << " to the outside; " << b.portals.size() << " hand-made), "
            << rooms->GetNumberOfSeeThroughPolygons() << " see-through polygons, in "
            << rooms->GetGenerationTime() << " s\n";

  // 1. The model whole, every cell with a room.
  SCENEVIS_EXPECT(rooms->GetStatus() == vtkGenerateRooms::STATUS_OK);
  SCENEVIS_EXPECT(std::string(rooms->GetStatusMessage()).empty());
  SCENEVIS_EXPECT(rooms->GetNumberOfLeakCells() == 0);
  SCENEVIS_EXPECT(rooms->GetLeaksOutput()->GetNumberOfPoints() == 0);
  SCENEVIS_EXPECT(rooms->GetNumberOfDroppedPolygons() == 0);
  SCENEVIS_EXPECT(rooms->GetNumberOfSeeThroughPolygons() > 0);
  SCENEVIS_EXPECT(model->GetNumberOfCells() == input->GetNumberOfCells());
  SCENEVIS_EXPECT(model->GetNumberOfPoints() == input->GetNumberOfPoints());
  SCENEVIS_EXPECT(roomCount >= static_cast<int>(b.rooms.size()) / 2);
  SCENEVIS_EXPECT(roomCount <= static_cast<int>(b.rooms.size()) * 2);
  auto* roomIds = vtkIntArray::SafeDownCast(model->GetCellData()->GetArray("RoomId"));
  SCENEVIS_EXPECT(roomIds && roomIds->GetNumberOfTuples() == model->GetNumberOfCells());
  SCENEVIS_EXPECT(
    roomIds != input->GetCellData()->GetArray("RoomId")); // replaced, not the source's
  if (!roomIds)
  {
    return EXIT_FAILURE;
  }
  std::vector<int> cellsOfRoom(static_cast<std::size_t>(roomCount) + 1, 0);
  for (vtkIdType c = 0; c < roomIds->GetNumberOfTuples(); ++c)
  {
    const int r = roomIds->GetValue(c);
    SCENEVIS_EXPECT(r >= -1 && r < roomCount);
    if (r >= -1 && r < roomCount)
    {
      ++cellsOfRoom[static_cast<std::size_t>(r < 0 ? roomCount : r)];
    }
  }
  SCENEVIS_EXPECT(std::count(cellsOfRoom.begin(), cellsOfRoom.end() - 1, 0) == 0); // no empty room

  // 2. Portals in the portal scene format.
  auto* roomA = vtkIntArray::SafeDownCast(portals->GetCellData()->GetArray("RoomA"));
  auto* roomB = vtkIntArray::SafeDownCast(portals->GetCellData()->GetArray("RoomB"));
  SCENEVIS_EXPECT(roomA && roomB);
  SCENEVIS_EXPECT(portals->GetNumberOfPolys() == rooms->GetNumberOfPortals());
  std::size_t windows = 0;
  for (const scenes::Portal& p : b.portals)
  {
    windows += p.kind == scenes::PortalKind::Window ? 1 : 0;
  }
  SCENEVIS_EXPECT(static_cast<std::size_t>(rooms->GetNumberOfExteriorPortals()) >= windows);
  for (vtkIdType i = 0; roomA && roomB && i < portals->GetNumberOfPolys(); ++i)
  {
    const int a = roomA->GetValue(i), c = roomB->GetValue(i);
    SCENEVIS_EXPECT(a >= 0 && a < roomCount && (c == -1 || (c > a && c < roomCount)));
    SCENEVIS_EXPECT(IsPlanar(portals, i, 1e-6));
  }

  // 3. Used as a user would: one actor per generated room (and one for the outside's cells).
  auto window = st::MakeRenderWindow(160, 120);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  std::vector<vtkProp*> props;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  for (int r = -1; r < roomCount; ++r)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(RoomPart(model, "RoomId", r));
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    actors.push_back(actor);
    props.push_back(actor);
  }
  vtkNew<vtkPortalCuller> culler;
  culler->SetPortals(portals);
  renderer->AddCuller(culler);
  // The exact visible set: the whole model, each cell named by its room's actor.
  vtkNew<vtkPolyData> all;
  all->ShallowCopy(model);
  vtkNew<vtkIntArray> node;
  node->SetName("RoomNode");
  node->SetNumberOfTuples(model->GetNumberOfCells());
  for (vtkIdType c = 0; c < model->GetNumberOfCells(); ++c)
  {
    node->SetValue(c, roomIds->GetValue(c) + 1); // the index of its actor in props
  }
  all->GetCellData()->AddArray(node);
  st::IdRenderOptions options;
  options.originalIdArray = "RoomNode";
  options.cameraClippingRange = true;

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(60.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t missed = 0, drawnInside = 0, visibleInside = 0;
  const int kInside = 40, kOutside = 10;
  for (int view = 0; view < kInside + kOutside; ++view)
  {
    glm::dvec3 eye, focal;
    if (view < kInside)
    {
      // In a hand-made room, away from its walls (the near plane must not reach through one).
      const auto& cell = b.rooms[rng() % b.rooms.size()].bounds;
      const double m = 0.5 * scenes::kWallThickness + 0.15;
      const double mz = 0.5 * scenes::kSlabThickness + 0.15;
      eye = glm::dvec3(cell.lo.x + m + u(rng) * (cell.hi.x - cell.lo.x - 2 * m),
        cell.lo.y + m + u(rng) * (cell.hi.y - cell.lo.y - 2 * m),
        cell.lo.z + mz + u(rng) * (cell.hi.z - cell.lo.z - 2 * mz));
      const double yaw = u(rng) * 6.283185307, pitch = (u(rng) - 0.5) * 0.8;
      focal = eye +
        glm::dvec3(
          std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
    }
    else
    {
      // Outside, looking at the building through its windows.
      const double yaw = u(rng) * 6.283185307;
      double box[6];
      model->GetBounds(box);
      focal = glm::dvec3(box[0] + u(rng) * (box[1] - box[0]), box[2] + u(rng) * (box[3] - box[2]),
        box[4] + u(rng) * (box[5] - box[4]));
      eye = focal + glm::dvec3(25.0 * std::cos(yaw), 25.0 * std::sin(yaw), 2.0);
    }
    camera->SetPosition(eye.x, eye.y, eye.z);
    camera->SetFocalPoint(focal.x, focal.y, focal.z);
    camera->SetViewUp(0, 0, 1);
    camera->SetClippingRange(0.05, 200.0);
    const std::vector<std::uint32_t> visible =
      st::VisibleSet(st::RenderIdBuffer(window, all, camera, options));
    std::vector<vtkProp*> list = props;
    int length = static_cast<int>(list.size());
    int initialized = 0;
    culler->Cull(renderer, list.data(), length, initialized);
    std::vector<std::uint32_t> drawn;
    for (int i = 0; i < length; ++i)
    {
      drawn.push_back(static_cast<std::uint32_t>(
        std::find(props.begin(), props.end(), list[static_cast<std::size_t>(i)]) - props.begin()));
    }
    const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
    for (const std::uint32_t m : check.missing)
    {
      ++missed;
      std::cerr << "FAIL view " << view << " eye (" << eye.x << ", " << eye.y << ", " << eye.z
                << "): generated room " << static_cast<int>(m) - 1 << " covers pixels, not drawn\n";
    }
    if (view < kInside)
    {
      drawnInside += drawn.size();
      visibleInside += visible.size();
    }
  }
  std::cout << "inside views: " << static_cast<double>(drawnInside) / kInside << " rooms drawn, "
            << static_cast<double>(visibleInside) / kInside << " visible per view, of "
            << roomCount + 1 << "; " << missed << " missed\n";
  SCENEVIS_EXPECT(missed == 0);
  SCENEVIS_EXPECT(
    drawnInside * 2 < static_cast<std::size_t>(kInside) * static_cast<std::size_t>(roomCount));

  // 4. Nothing changed: the pipeline does not run again.
  const vtkMTimeType before = model->GetMTime();
  rooms->Update();
  SCENEVIS_EXPECT(model->GetMTime() == before);
  SCENEVIS_EXPECT(
    rooms->GetOutput() == model && model->GetCellData()->GetArray("RoomId") == roomIds);

  return vtkOutput.ExitCode(scenevis::testing::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE);
}

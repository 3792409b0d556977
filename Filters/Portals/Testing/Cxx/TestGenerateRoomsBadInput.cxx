// Specification: vtkGenerateRooms on input it cannot make rooms of. Every case gives a status, a
// model with a RoomId cell array on every cell (-1 where there is no room), and says in one VTK
// warning what a user would otherwise not see; never a crash, never a cell without a room value.
// - no input cells, or only lines: STATUS_EMPTY_INPUT, no warning (nothing to say), lines in -1;
// - only NaN and degenerate polygons: STATUS_NO_VALID_POLYGONS, a warning, every cell -1;
// - NaN polygons among good ones: the good ones' rooms as without them, the bad ones -1, counted
//   and named in a warning;
// - a closed box: one room, no portal, no leak, no warning;
// - the same box with a wall missing: the leak named in a warning with a point in the leaks
//   output, the room merged into the outside; with StopAtFirstLeak exactly one leak point, no
//   rooms;
// - a closed box beside a leaking one: no rooms at all, said in the status message and a
//   warning; with KeepRoomsWithLeaks the closed box's room, and a warning that it is not
//   conservative;
// - a time budget too small: STATUS_OVER_BUDGET, a warning, no portals, every cell -1;
// - an input RoomId array of another type is replaced by the int one, and a RoomId field array
//   (one room for everything, which vtkPortalCuller would read first) removed; an empty
//   RoomArrayName means "RoomId".
#include "vtkGenerateRooms.h"

#include "vtkDemoSceneSource.h"

#include "scenevis/testing/Expect.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <array>
#include <cstdlib>
#include <iostream>
#include <vector>

namespace
{
namespace st = scenevis::testing;

using Quad = std::array<std::array<double, 3>, 4>;

/// A 4 x 4 x 3 box room, every face turned inwards; @p missing faces left out (0..5: floor,
/// ceiling, x = 0, x = 4, y = 0, y = 4).
/// The faces of a 4 x 4 x 3 box moved by @p dx along x, facing in, face @p missing left out.
void AddBox(vtkPoints* points, vtkCellArray* polys, int missing, double dx)
{
  const double X = 4, Y = 4, Z = 3;
  const std::vector<Quad> faces = {
    Quad{ { { 0, 0, 0 }, { X, 0, 0 }, { X, Y, 0 }, { 0, Y, 0 } } }, // floor, +z
    Quad{ { { 0, 0, Z }, { 0, Y, Z }, { X, Y, Z }, { X, 0, Z } } }, // ceiling, -z
    Quad{ { { 0, 0, 0 }, { 0, Y, 0 }, { 0, Y, Z }, { 0, 0, Z } } }, // x = 0, +x
    Quad{ { { X, 0, 0 }, { X, 0, Z }, { X, Y, Z }, { X, Y, 0 } } }, // x = X, -x
    Quad{ { { 0, 0, 0 }, { 0, 0, Z }, { X, 0, Z }, { X, 0, 0 } } }, // y = 0, +y
    Quad{ { { 0, Y, 0 }, { X, Y, 0 }, { X, Y, Z }, { 0, Y, Z } } }, // y = Y, -y
  };
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    if (static_cast<int>(f) == missing)
    {
      continue;
    }
    polys->InsertNextCell(4);
    for (const auto& p : faces[f])
    {
      polys->InsertCellPoint(points->InsertNextPoint(p[0] + dx, p[1], p[2]));
    }
  }
}

/// A box (see AddBox); with @p leakingBeside, a second one 10 along x with its floor missing.
vtkSmartPointer<vtkPolyData> Box(int missing = -1, bool leakingBeside = false)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddBox(points, polys, missing, 0.0);
  if (leakingBeside)
  {
    AddBox(points, polys, 0, 10.0);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  return pd;
}

/// @p pd with @p count triangles appended whose first point is NaN, and one degenerate triangle.
void AppendBadTriangles(vtkPolyData* pd, int count)
{
  vtkPoints* points = pd->GetPoints();
  vtkCellArray* polys = pd->GetPolys();
  const double nan = vtkMath::Nan();
  for (int i = 0; i < count; ++i)
  {
    const vtkIdType a = points->InsertNextPoint(nan, 0, 0);
    const vtkIdType b = points->InsertNextPoint(1, 1, 1);
    const vtkIdType c = points->InsertNextPoint(1, 2, 1);
    const vtkIdType ids[3] = { a, b, c };
    polys->InsertNextCell(3, ids);
  }
  const vtkIdType p = points->InsertNextPoint(1, 1, 1);
  const vtkIdType ids[3] = { p, p, p };
  polys->InsertNextCell(3, ids);
  pd->Modified();
}

/// The room array of @p filter's model output; checks it names every cell.
vtkIntArray* RoomsOf(vtkGenerateRooms* filter)
{
  vtkPolyData* model = filter->GetOutput();
  auto* rooms = vtkIntArray::SafeDownCast(model->GetCellData()->GetArray("RoomId"));
  SCENEVIS_EXPECT(rooms && rooms->GetNumberOfTuples() == model->GetNumberOfCells());
  return rooms;
}

bool AllOutside(vtkIntArray* rooms)
{
  for (vtkIdType c = 0; rooms && c < rooms->GetNumberOfTuples(); ++c)
  {
    if (rooms->GetValue(c) != -1)
    {
      return false;
    }
  }
  return rooms != nullptr;
}
} // namespace

int TestGenerateRoomsBadInput(int, char*[])
{
  {
    st::StrictVtkOutput strict; // no warning at all
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkGenerateRooms> filter;
    filter->SetInputData(empty);
    filter->Update();
    SCENEVIS_EXPECT(filter->GetStatus() == vtkGenerateRooms::STATUS_EMPTY_INPUT);
    SCENEVIS_EXPECT(filter->GetNumberOfRooms() == 0 && filter->GetNumberOfPortals() == 0);
    SCENEVIS_EXPECT(RoomsOf(filter) != nullptr);
    SCENEVIS_EXPECT(filter->GetPortalsOutput()->GetNumberOfCells() == 0);

    // Only lines.
    vtkNew<vtkPolyData> lines;
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    points->InsertNextPoint(1, 0, 0);
    vtkNew<vtkCellArray> cells;
    const vtkIdType ids[2] = { 0, 1 };
    cells->InsertNextCell(2, ids);
    lines->SetPoints(points);
    lines->SetLines(cells);
    filter->SetInputData(lines);
    filter->SetRoomArrayName(""); // means "RoomId"
    filter->Update();
    SCENEVIS_EXPECT(filter->GetStatus() == vtkGenerateRooms::STATUS_EMPTY_INPUT);
    SCENEVIS_EXPECT(AllOutside(RoomsOf(filter)) && filter->GetOutput()->GetNumberOfLines() == 1);
    scenevis::testing::ExpectFailures() += strict.Check().empty() ? 0 : 1;
  }
  {
    st::StrictVtkOutput strict;
    strict.ExpectWarning("no rooms generated (no valid polygons)");
    strict.ExpectWarning("NaN/Inf polygon(s) took no part");
    vtkNew<vtkPolyData> bad;
    bad->SetPoints(vtkNew<vtkPoints>());
    bad->SetPolys(vtkNew<vtkCellArray>());
    AppendBadTriangles(bad, 3);
    vtkNew<vtkGenerateRooms> filter;
    filter->SetInputData(bad);
    filter->Update();
    SCENEVIS_EXPECT(filter->GetStatus() == vtkGenerateRooms::STATUS_NO_VALID_POLYGONS);
    SCENEVIS_EXPECT(std::string(filter->GetStatusMessage()).size() > 0);
    SCENEVIS_EXPECT(AllOutside(RoomsOf(filter)));
    SCENEVIS_EXPECT(filter->GetOutput()->GetNumberOfCells() == 4);
    const std::string report = strict.Check();
    scenevis::testing::ExpectFailures() += report.empty() ? 0 : 1;
    std::cerr << report;
  }
  {
    // A closed box: one room; with a wall gone, a leak.
    st::StrictVtkOutput strict;
    vtkNew<vtkGenerateRooms> filter;
    filter->SetInputData(Box());
    filter->Update();
    SCENEVIS_EXPECT(filter->GetStatus() == vtkGenerateRooms::STATUS_OK);
    SCENEVIS_EXPECT(filter->GetNumberOfRooms() == 1 && filter->GetNumberOfPortals() == 0);
    SCENEVIS_EXPECT(filter->GetNumberOfLeakCells() == 0);
    vtkIntArray* rooms = RoomsOf(filter);
    for (vtkIdType c = 0; rooms && c < rooms->GetNumberOfTuples(); ++c)
    {
      SCENEVIS_EXPECT(rooms->GetValue(c) == 0);
    }
    scenevis::testing::ExpectFailures() += strict.Check().empty() ? 0 : 1;

    strict.ExpectWarning("where the outside leaks in");
    filter->SetInputData(Box(3));
    filter->Update();
    SCENEVIS_EXPECT(filter->GetStatus() == vtkGenerateRooms::STATUS_OK);
    SCENEVIS_EXPECT(filter->GetNumberOfLeakCells() >= 1);
    SCENEVIS_EXPECT(filter->GetLeaksOutput()->GetNumberOfVerts() >= 1);
    SCENEVIS_EXPECT(filter->GetNumberOfRooms() == 0 && AllOutside(RoomsOf(filter)));
    filter->StopAtFirstLeakOn();
    filter->Update();
    SCENEVIS_EXPECT(filter->GetNumberOfLeakCells() == 1);
    SCENEVIS_EXPECT(filter->GetLeaksOutput()->GetNumberOfVerts() == 1);
    SCENEVIS_EXPECT(filter->GetNumberOfRooms() == 0 && AllOutside(RoomsOf(filter)));
    const std::string report = strict.Check();
    scenevis::testing::ExpectFailures() += report.empty() ? 0 : 1;
    std::cerr << report;
  }
  {
    // A closed box beside one that leaks: no rooms (not even the closed box's: with a leak no
    // room labelling is conservative), the status message and the warning saying so; kept on
    // request, with a warning that they are not conservative.
    vtkNew<vtkGenerateRooms> filter;
    filter->SetInputData(Box(-1, true));
    {
      st::StrictVtkOutput strict;
      strict.ExpectWarning("no rooms: every cell in room -1");
      filter->Update();
      SCENEVIS_EXPECT(filter->GetStatus() == vtkGenerateRooms::STATUS_OK);
      SCENEVIS_EXPECT(filter->GetNumberOfLeakCells() >= 1);
      SCENEVIS_EXPECT(filter->GetNumberOfRooms() == 0 && filter->GetNumberOfPortals() == 0);
      SCENEVIS_EXPECT(AllOutside(RoomsOf(filter)));
      SCENEVIS_EXPECT(std::string(filter->GetStatusMessage()).find("leaks") != std::string::npos);
      const std::string report = strict.Check();
      scenevis::testing::ExpectFailures() += report.empty() ? 0 : 1;
      std::cerr << report;
    }
    {
      st::StrictVtkOutput strict;
      strict.ExpectWarning("NOT conservative");
      filter->KeepRoomsWithLeaksOn();
      filter->Update();
      SCENEVIS_EXPECT(filter->GetNumberOfRooms() == 1 && !AllOutside(RoomsOf(filter)));
      const std::string report = strict.Check();
      scenevis::testing::ExpectFailures() += report.empty() ? 0 : 1;
      std::cerr << report;
    }
  }
  {
    // NaN polygons among the demo building's: the same rooms, the bad cells -1.
    st::StrictVtkOutput strict;
    strict.ExpectWarning("4 degenerate or NaN/Inf polygon(s) took no part");
    vtkNew<vtkDemoSceneSource> source;
    source->SetScene(vtkDemoSceneSource::SCENE_BUILDING);
    source->SetFloors(1);
    source->SetRoomsX(2);
    source->SetRoomsY(2);
    source->Update();
    vtkNew<vtkGenerateRooms> clean;
    clean->SetInputConnection(source->GetOutputPort());
    clean->Update();
    SCENEVIS_EXPECT(
      clean->GetStatus() == vtkGenerateRooms::STATUS_OK && clean->GetNumberOfRooms() > 1);

    vtkNew<vtkPolyData> dirty;
    dirty->DeepCopy(source->GetOutput());
    const vtkIdType goodCells = dirty->GetNumberOfCells();
    AppendBadTriangles(dirty, 3);
    // The cell arrays (the glass's RGBA colours among them) cover the new cells too; the
    // source's int RoomId becomes a double one, and a stale one-room RoomId field array is added.
    vtkCellData* cellData = dirty->GetCellData();
    for (int a = 0; a < cellData->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = cellData->GetAbstractArray(a);
      while (array->GetNumberOfTuples() < dirty->GetNumberOfCells())
      {
        array->InsertNextTuple(0, array);
      }
    }
    cellData->RemoveArray("RoomId");
    vtkNew<vtkDoubleArray> oldRooms;
    oldRooms->SetName("RoomId");
    oldRooms->SetNumberOfTuples(dirty->GetNumberOfCells());
    oldRooms->FillValue(7.0);
    cellData->AddArray(oldRooms);
    vtkNew<vtkIntArray> wholeRoom;
    wholeRoom->SetName("RoomId");
    wholeRoom->InsertNextValue(7);
    dirty->GetFieldData()->AddArray(wholeRoom);
    vtkNew<vtkGenerateRooms> filter;
    filter->SetInputData(dirty);
    filter->Update();
    SCENEVIS_EXPECT(filter->GetStatus() == vtkGenerateRooms::STATUS_OK);
    SCENEVIS_EXPECT(filter->GetNumberOfDroppedPolygons() == 4);
    SCENEVIS_EXPECT(filter->GetNumberOfRooms() == clean->GetNumberOfRooms());
    SCENEVIS_EXPECT(filter->GetNumberOfPortals() == clean->GetNumberOfPortals());
    vtkIntArray* rooms = RoomsOf(filter); // the int array, not the input's double one
    SCENEVIS_EXPECT(filter->GetOutput()->GetFieldData()->GetArray("RoomId") == nullptr);
    vtkIntArray* cleanRooms = RoomsOf(clean);
    for (vtkIdType c = 0; rooms && cleanRooms && c < dirty->GetNumberOfCells(); ++c)
    {
      SCENEVIS_EXPECT(rooms->GetValue(c) == (c < goodCells ? cleanRooms->GetValue(c) : -1));
    }
    const std::string report = strict.Check();
    scenevis::testing::ExpectFailures() += report.empty() ? 0 : 1;
    std::cerr << report;

    // Over budget: no rooms, no portals, said so.
    strict.ExpectWarning("no rooms generated (over budget)");
    clean->SetBudgetSeconds(1e-9);
    clean->Update();
    SCENEVIS_EXPECT(clean->GetStatus() == vtkGenerateRooms::STATUS_OVER_BUDGET);
    SCENEVIS_EXPECT(
      clean->GetNumberOfRooms() == 0 && clean->GetPortalsOutput()->GetNumberOfCells() == 0);
    SCENEVIS_EXPECT(AllOutside(RoomsOf(clean)));
    const std::string budget = strict.Check();
    scenevis::testing::ExpectFailures() += budget.empty() ? 0 : 1;
    std::cerr << budget;
  }
  return scenevis::testing::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

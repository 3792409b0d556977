// Specification: vtkPortalCuller decides each prop by its rooms, whichever way a frame reaches
// them (it tests the props of the rooms the traversal reached, not every prop of the list):
// - a prop with cells in two rooms is drawn exactly when a twin of it in either room alone is;
// - a prop whose room id no room can have is drawn exactly when a twin with no room is (the
//   frustum decides both);
// - a prop with no usable bounds is always drawn;
// - a list that lacks some of the renderer's props (another culler ran first) keeps exactly the
//   props the full list keeps, in its own order;
// at 300 random eyes in a corridor of 8 box rooms joined by doors, looking anywhere.
#include "vtkPortalCuller.h"

#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkMinimalStandardRandomSequence.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;

constexpr int kRooms = 8;
constexpr double kRoomLength = 5.0; // room r: x in [5 r, 5 r + 5], y in [0, 4], z in [0, 3]

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}

vtkSmartPointer<vtkPolyData> Box(const double bounds[6])
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5]);
  cube->Update();
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->DeepCopy(cube->GetOutput());
  return pd;
}

void SetFieldRoom(vtkPolyData* pd, int room)
{
  vtkNew<vtkIntArray> id;
  id->SetName("RoomId");
  id->InsertNextValue(room);
  pd->GetFieldData()->AddArray(id);
}

vtkSmartPointer<vtkActor> ActorOf(vtkPolyData* pd)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(pd);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// Doors in the planes x = 5 r (rooms r - 1 and r), each at a different height along y.
vtkSmartPointer<vtkPolyData> Doors()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> a, b;
  a->SetName("RoomA");
  b->SetName("RoomB");
  for (int r = 1; r < kRooms; ++r)
  {
    const double x = kRoomLength * r, y0 = 0.3 + 0.35 * (r % 5), y1 = y0 + 1.0;
    polys->InsertNextCell(4);
    polys->InsertCellPoint(points->InsertNextPoint(x, y0, 0.0));
    polys->InsertCellPoint(points->InsertNextPoint(x, y1, 0.0));
    polys->InsertCellPoint(points->InsertNextPoint(x, y1, 2.1));
    polys->InsertCellPoint(points->InsertNextPoint(x, y0, 2.1));
    a->InsertNextValue(r - 1);
    b->InsertNextValue(r);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(a);
  pd->GetCellData()->AddArray(b);
  return pd;
}

/// The props left in @p list by one cull, in order.
std::vector<vtkProp*> Kept(vtkPortalCuller* culler, vtkRenderer* ren, std::vector<vtkProp*> list)
{
  int length = static_cast<int>(list.size());
  int initialized = 0;
  culler->Cull(ren, list.data(), length, initialized);
  list.resize(static_cast<std::size_t>(std::max(length, 0)));
  return list;
}

bool Has(const std::vector<vtkProp*>& v, vtkProp* p)
{
  return std::find(v.begin(), v.end(), p) != v.end();
}
} // namespace

int TestPortalCullerPropsByRoom(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  vtkOutput.ExpectWarning("have a room id below -1"); // the crates of no room
  vtkOutput.ExpectWarning("non-finite points");       // the NaN prop
  bool ok = true;
  auto window = st::MakeRenderWindow(96, 72);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  std::vector<vtkProp*> all;
  std::vector<vtkSmartPointer<vtkActor>> keepAlive;
  auto add = [&](vtkPolyData* pd) -> vtkActor*
  {
    keepAlive.push_back(ActorOf(pd));
    ren->AddActor(keepAlive.back());
    all.push_back(keepAlive.back());
    return keepAlive.back();
  };
  // Rooms: one actor each, the room's walls.
  for (int r = 0; r < kRooms; ++r)
  {
    const double b[6] = { kRoomLength * r, kRoomLength * (r + 1), 0, 4, 0, 3 };
    auto pd = Box(b);
    SetFieldRoom(pd, r);
    add(pd);
  }
  // Props with cells in rooms r and r + 1 (a table through the door's wall), each with its twin
  // in either room alone (same geometry).
  struct Spanning
  {
    vtkActor *both, *first, *second;
  };
  std::vector<Spanning> spanning;
  for (int r = 0; r + 1 < kRooms; ++r)
  {
    const double x = kRoomLength * (r + 1);
    const double left[6] = { x - 1.0, x, 3.2, 3.6, 0.0, 0.8 };
    const double right[6] = { x, x + 1.0, 3.2, 3.6, 0.0, 0.8 };
    vtkNew<vtkAppendPolyData> append;
    append->AddInputData(Box(left));
    append->AddInputData(Box(right));
    append->Update();
    auto both = vtkSmartPointer<vtkPolyData>::New();
    both->DeepCopy(append->GetOutput());
    vtkNew<vtkIntArray> cellRooms;
    cellRooms->SetName("RoomId");
    for (vtkIdType c = 0; c < both->GetNumberOfCells(); ++c)
    {
      cellRooms->InsertNextValue(c < both->GetNumberOfCells() / 2 ? r : r + 1);
    }
    both->GetCellData()->AddArray(cellRooms);
    auto first = vtkSmartPointer<vtkPolyData>::New();
    first->DeepCopy(append->GetOutput());
    SetFieldRoom(first, r);
    auto second = vtkSmartPointer<vtkPolyData>::New();
    second->DeepCopy(append->GetOutput());
    SetFieldRoom(second, r + 1);
    spanning.push_back({ add(both), add(first), add(second) });
  }
  // A crate per room with a room id that no room can have (negative, not the outside's), and
  // its twin with no room.
  std::vector<std::pair<vtkActor*, vtkActor*>> unknown;
  for (int r = 0; r < kRooms; ++r)
  {
    const double b[6] = { kRoomLength * r + 2.0, kRoomLength * r + 2.5, 0.5, 1.0, 0.0, 0.5 };
    auto withId = Box(b);
    SetFieldRoom(withId, -10 - r);
    unknown.emplace_back(add(withId), add(Box(b)));
  }
  // A prop whose points are all NaN: no usable bounds, never culled.
  vtkNew<vtkPoints> nanPoints;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 3; ++k)
  {
    nanPoints->InsertNextPoint(nan, nan, nan);
  }
  vtkNew<vtkCellArray> nanTriangle;
  nanTriangle->InsertNextCell({ 0, 1, 2 });
  vtkNew<vtkPolyData> nanPd;
  nanPd->SetPoints(nanPoints);
  nanPd->SetPolys(nanTriangle);
  SetFieldRoom(nanPd, 0);
  vtkActor* nanActor = add(nanPd);

  vtkNew<vtkPortalCuller> culler;
  culler->SetPortals(Doors());
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetViewUp(0, 0, 1);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(1234);
  auto uniform = [&](double lo, double hi)
  {
    random->Next();
    return lo + (hi - lo) * random->GetValue();
  };
  int twinsWrong = 0, unknownWrong = 0, nanCulled = 0, subsetWrong = 0;
  int spanningKept = 0, spanningCulled = 0, unknownKept = 0, unknownCulled = 0, narrowed = 0;
  for (int view = 0; view < 300; ++view)
  {
    const double eye[3] = { uniform(0.2, kRoomLength * kRooms - 0.2), uniform(0.2, 3.8),
      uniform(0.3, 2.7) };
    const double angle = uniform(0.0, 2.0 * 3.14159265358979);
    cam->SetPosition(eye);
    cam->SetFocalPoint(
      eye[0] + std::cos(angle), eye[1] + std::sin(angle), eye[2] + uniform(-0.3, 0.3));
    cam->SetViewAngle(uniform(30.0, 100.0));
    cam->SetClippingRange(0.05, 100.0);
    const std::vector<vtkProp*> kept = Kept(culler, ren, all);
    narrowed += culler->GetFrustumOnly() ? 0 : 1;
    for (const Spanning& s : spanning)
    {
      const bool both = Has(kept, s.both);
      twinsWrong += both != (Has(kept, s.first) || Has(kept, s.second)) ? 1 : 0;
      (both ? spanningKept : spanningCulled)++;
    }
    for (const auto& u : unknown)
    {
      const bool withId = Has(kept, u.first);
      unknownWrong += withId != Has(kept, u.second) ? 1 : 0;
      (withId ? unknownKept : unknownCulled)++;
    }
    nanCulled += Has(kept, nanActor) ? 0 : 1;
    // Every third prop, from a rotating start: what another culler might leave.
    std::vector<vtkProp*> subset;
    for (std::size_t i = static_cast<std::size_t>(view % 3); i < all.size(); i += 3)
    {
      subset.push_back(all[i]);
    }
    std::vector<vtkProp*> expected;
    std::copy_if(subset.begin(), subset.end(), std::back_inserter(expected),
      [&](vtkProp* p) { return Has(kept, p); });
    subsetWrong += Kept(culler, ren, subset) != expected ? 1 : 0;
    // And the full list again after the subset: nothing of the subset's frame is left over.
    subsetWrong += Kept(culler, ren, all) != kept ? 1 : 0;
  }
  std::printf(
    "300 views (%d narrowed by portals): spanning props kept %d / culled %d, unknown-room "
    "props kept %d / culled %d\n",
    narrowed, spanningKept, spanningCulled, unknownKept, unknownCulled);
  ok &= Check(narrowed > 250, "the portals narrow the views (not a frustum-only fallback)");
  ok &=
    Check(spanningKept > 100 && spanningCulled > 100 && unknownKept > 100 && unknownCulled > 100,
      "the views keep and cull props of each kind");
  ok &= Check(twinsWrong == 0,
    "a prop in two rooms is drawn exactly when its twin in one of them is (" +
      std::to_string(twinsWrong) + " wrong)");
  ok &= Check(unknownWrong == 0,
    "a prop of an unknown room is drawn exactly when its twin with no room is (" +
      std::to_string(unknownWrong) + " wrong)");
  ok &= Check(nanCulled == 0, "a prop without usable bounds is always drawn");
  ok &= Check(subsetWrong == 0,
    "a partial list keeps what the full list keeps, in its order (" + std::to_string(subsetWrong) +
      " wrong)");
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}

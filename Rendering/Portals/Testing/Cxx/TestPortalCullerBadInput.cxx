// Specification: vtkPortalCuller honours the vtkCuller contract and turns bad input into clear
// warnings and conservative output (never an empty frame): no portals, portals without room
// arrays, invalid portals (< 3 points, non-planar, duplicate), a dangling room id, a room with no
// portals (disconnected), an eye exactly on a portal plane, parallel projections, an unusable
// camera, mode off, props without rooms.
#include "vtkPortalCuller.h"

#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}

/// A closed box room [x0, x0 + 5] x [0, 4] x [0, 3] as one actor with field data RoomId.
vtkSmartPointer<vtkActor> Room(double x0, int room)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(x0, x0 + 5, 0, 4, 0, 3);
  cube->Update();
  vtkNew<vtkPolyData> pd;
  pd->DeepCopy(cube->GetOutput());
  vtkNew<vtkIntArray> id;
  id->SetName("RoomId");
  id->InsertNextValue(room);
  pd->GetFieldData()->AddArray(id);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(pd);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// Portal polydata: door quads in the planes x = 5 (rooms 0-1) and x = 10 (rooms 1-2), plus
/// @p extra polygons (point lists) with their rooms.
vtkSmartPointer<vtkPolyData> Portals(bool withArrays,
  const std::vector<std::pair<std::vector<double>, std::pair<int, int>>>& extra = {})
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> a, b;
  a->SetName("RoomA");
  b->SetName("RoomB");
  auto add = [&](const std::vector<double>& xyz, int ra, int rb)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(xyz.size() / 3));
    for (std::size_t k = 0; k + 2 < xyz.size(); k += 3)
    {
      polys->InsertCellPoint(points->InsertNextPoint(xyz[k], xyz[k + 1], xyz[k + 2]));
    }
    a->InsertNextValue(ra);
    b->InsertNextValue(rb);
  };
  add({ 5, 1.5, 0, 5, 2.5, 0, 5, 2.5, 2.1, 5, 1.5, 2.1 }, 0, 1);
  add({ 10, 1.5, 0, 10, 2.5, 0, 10, 2.5, 2.1, 10, 1.5, 2.1 }, 1, 2);
  for (const auto& e : extra)
  {
    add(e.first, e.second.first, e.second.second);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetPolys(polys);
  if (withArrays)
  {
    pd->GetCellData()->AddArray(a);
    pd->GetCellData()->AddArray(b);
  }
  return pd;
}

std::vector<vtkProp*> Run(vtkPortalCuller* culler, vtkRenderer* ren, std::vector<vtkProp*> props,
  int initialized = 0, double* total = nullptr)
{
  int length = static_cast<int>(props.size());
  const double t = culler->Cull(ren, props.data(), length, initialized);
  if (total)
  {
    *total = t;
  }
  if (initialized != 1 || length < 0 || length > static_cast<int>(props.size()))
  {
    std::cout << "FAIL contract: initialized " << initialized << ", length " << length << "\n";
    return {};
  }
  return std::vector<vtkProp*>(props.begin(), props.begin() + length);
}

bool Has(const std::vector<vtkProp*>& v, vtkProp* p)
{
  return std::find(v.begin(), v.end(), p) != v.end();
}
} // namespace

int TestPortalCullerBadInput(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  vtkOutput.ExpectWarning("No portals");
  vtkOutput.ExpectWarning("\"RoomA\" and \"RoomB\"");
  vtkOutput.ExpectWarning("dangling room id 9");
  vtkOutput.ExpectWarning("has 2 points");
  vtkOutput.ExpectWarning("camera or the viewport is not usable");
  vtkOutput.ExpectWarning("SavePVS: no PVS");
  vtkOutput.ExpectWarning("LoadPVS:");
  vtkOutput.ExpectWarning("is not planar");
  vtkOutput.ExpectWarning("duplicates portal 0");
  vtkOutput.ExpectWarning("Parallel projection whose near plane");
  bool ok = true;

  auto window = st::MakeRenderWindow(64, 48);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  auto r0 = Room(0, 0), r1 = Room(5, 1), r2 = Room(10, 2), r3 = Room(30, 3);
  vtkNew<vtkActor> free; // no room: frustum only
  {
    vtkNew<vtkCubeSource> cube;
    cube->SetCenter(4, 2, 1);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(cube->GetOutputPort());
    free->SetMapper(mapper);
  }
  for (vtkActor* a : { r0.Get(), r1.Get(), r2.Get(), r3.Get(), free.Get() })
  {
    ren->AddActor(a);
  }
  const std::vector<vtkProp*> props = { r0.Get(), r1.Get(), r2.Get(), r3.Get(), free.Get() };
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(2.5, 2, 1.5);
  cam->SetFocalPoint(30, 2, 1.5);
  cam->SetViewUp(0, 0, 1);
  cam->SetClippingRange(0.05, 100);

  vtkNew<vtkPortalCuller> culler;
  // No portals: warned, nothing culled.
  auto drawn = Run(culler, ren, props);
  ok &= Check(drawn.size() == props.size() && culler->GetFrustumOnly(), "no portals: all drawn");
  // Portals without RoomA/RoomB.
  culler->SetPortals(Portals(false));
  drawn = Run(culler, ren, props);
  ok &= Check(drawn.size() == props.size(), "portals without room arrays: all drawn");

  // Good portals: room 3 (no portal to it) is culled, and looking down the corridor 0-2 are kept.
  culler->SetPortals(Portals(true));
  double total = 0.0;
  std::vector<vtkProp*> list = props;
  int length = static_cast<int>(list.size());
  int initialized = 0;
  total = culler->Cull(ren, list.data(), length, initialized);
  drawn.assign(list.begin(), list.begin() + length);
  ok &= Check(length == 4 && list[4] == r3.Get() && initialized == 1,
    "contract: culled prop moved to the end, list shortened, initialized set");
  ok &= Check(list[0] == r0.Get() && list[1] == r1.Get() && list[2] == r2.Get() &&
      list[3] == free.Get(),
    "contract: drawn props keep their order");
  ok &= Check(total == 4.0, "contract: multipliers set to 1 when not initialized");
  ok &= Check(culler->GetNumberOfRoomsVisited() == 3 && culler->GetNumberOfPropsCulled() == 1 &&
      culler->GetNumberOfTrianglesDrawn() > 0 && !culler->GetFrustumOnly(),
    "statistics");
  std::printf("statistics: rooms visited %d, props culled %d, triangles drawn %lld, frustum only %d\n",
    culler->GetNumberOfRoomsVisited(), culler->GetNumberOfPropsCulled(),
    static_cast<long long>(culler->GetNumberOfTrianglesDrawn()), culler->GetFrustumOnly() ? 1 : 0);
  // initialized: existing multipliers are kept (multiplied by 1).
  r0->SetRenderTimeMultiplier(0.25);
  drawn = Run(culler, ren, props, 1, &total);
  ok &= Check(std::abs(total - 3.25) < 1e-12 && r0->GetRenderTimeMultiplier() == 0.25,
    "contract: multipliers kept when initialized");
  // Looking back from room 0: only room 0 and the free actor (in the frustum? it is at x = 2).
  cam->SetFocalPoint(-30, 2, 1.5);
  drawn = Run(culler, ren, props);
  ok &= Check(Has(drawn, r0.Get()) && !Has(drawn, r1.Get()) && !Has(drawn, r2.Get()), "looking away: rooms 1, 2 culled");
  // Everything culled is possible only with nothing visible; the total is 0 only then.
  cam->SetFocalPoint(30, 2, 1.5);

  // Mode off: nothing culled.
  culler->SetMode(vtkPortalCuller::MODE_OFF);
  drawn = Run(culler, ren, props);
  ok &= Check(drawn.size() == props.size(), "mode off: all drawn");
  culler->SetMode(vtkPortalCuller::MODE_SCREEN_RECTANGLES);
  drawn = Run(culler, ren, props);
  ok &= Check(drawn.size() == 4 && !Has(drawn, r3.Get()), "screen rectangles");
  culler->SetMode(vtkPortalCuller::MODE_PVS);
  ok &= Check(!culler->SavePVS("/nonexistent-dir/x.pvs"), "SavePVS before any PVS: warned");
  drawn = Run(culler, ren, props);
  ok &= Check(!Has(drawn, r3.Get()) && Has(drawn, r2.Get()), "pvs computed on first use");
  ok &= Check(!culler->LoadPVS(ren, "/nonexistent-dir/x.pvs"), "LoadPVS of a missing file: warned");
  culler->SetMode(vtkPortalCuller::MODE_EXACT_FRUSTUM);

  // Invalid portals: 2 points, a dangling room id (9) -> warned; room 1 leaky -> conservative.
  culler->SetPortals(Portals(true,
    { { { 20, 0, 0, 20, 1, 0 }, { 2, 3 } },
      { { 15, 1.5, 0, 15, 2.5, 0, 15, 2.5, 2.1, 15, 1.5, 2.1 }, { 1, 9 } } }));
  drawn = Run(culler, ren, props);
  ok &= Check(drawn.size() == props.size() && culler->GetFrustumOnly(),
    std::string("leaky room reached: frustum only (") + culler->GetFallbackReason() + ")");
  ok &= Check(std::string(culler->GetGraphReport()).find("has 2 points") != std::string::npos,
    "graph report lists the problems");
  culler->SetPortals(Portals(true));

  // A non-planar portal (3-4, x = 20.5 at one corner) and a duplicate of portal 0: warned; the
  // non-planar one passes the view un-narrowed, the duplicate changes nothing.
  culler->SetPortals(Portals(true,
    { { { 15, 1.5, 0, 15, 2.5, 0, 15.5, 2.5, 2.1, 15, 1.5, 2.1 }, { 2, 3 } },
      { { 5, 1.5, 0, 5, 2.5, 0, 5, 2.5, 2.1, 5, 1.5, 2.1 }, { 1, 0 } } }));
  drawn = Run(culler, ren, props);
  ok &= Check(std::string(culler->GetGraphReport()).find("not planar") != std::string::npos &&
      std::string(culler->GetGraphReport()).find("duplicates portal 0") != std::string::npos,
    "non-planar and duplicate portals reported");
  ok &= Check(Has(drawn, r0.Get()) && Has(drawn, r1.Get()) && Has(drawn, r2.Get()) &&
      !culler->GetFrustumOnly(),
    "non-planar and duplicate portals: the corridor is still drawn");
  culler->SetPortals(Portals(true));

  // Eye exactly on the plane of door 0-1 (x = 5, in the doorway): both rooms start; looking
  // down the corridor rooms 1-2 are drawn, looking back room 0 is.
  cam->SetPosition(5, 2, 1.5);
  cam->SetFocalPoint(30, 2, 1.5);
  drawn = Run(culler, ren, props);
  // (Room 0 lies wholly behind the near plane.)
  ok &= Check(Has(drawn, r1.Get()) && Has(drawn, r2.Get()) && !Has(drawn, r3.Get()) &&
      !culler->GetFrustumOnly(),
    "eye on a portal plane, looking along the corridor");
  cam->SetFocalPoint(-30, 2, 1.5);
  drawn = Run(culler, ren, props);
  ok &=
    Check(Has(drawn, r0.Get()) && !culler->GetFrustumOnly(), "eye on a portal plane, looking back");

  // Room 3 has no portals (disconnected from the others): an eye in it sees only room 3, never
  // an empty frame.
  cam->SetPosition(32.5, 2, 1.5);
  cam->SetFocalPoint(0, 2, 1.5);
  drawn = Run(culler, ren, props);
  ok &= Check(Has(drawn, r3.Get()) && !Has(drawn, r0.Get()) && !Has(drawn, r1.Get()) &&
      !Has(drawn, r2.Get()) && !culler->GetFrustumOnly(),
    "eye in a room without portals: that room only");

  // Parallel projection from outside (no exterior portals here): the closed rooms are culled,
  // the free cube is not. With the near plane inside the building: warned, frustum only.
  cam->ParallelProjectionOn();
  cam->SetParallelScale(10);
  cam->SetPosition(7.5, -40, 1.5);
  cam->SetFocalPoint(7.5, 2, 1.5);
  drawn = Run(culler, ren, props);
  ok &= Check(!Has(drawn, r0.Get()) && !Has(drawn, r1.Get()) && Has(drawn, free.Get()) &&
      !culler->GetFrustumOnly(),
    "parallel projection from outside: closed rooms culled");
  cam->SetPosition(2.5, 2, 1.5);
  cam->SetFocalPoint(30, 2, 1.5);
  drawn = Run(culler, ren, props);
  ok &= Check(drawn.size() == props.size() && culler->GetFrustumOnly() &&
      std::string(culler->GetFallbackReason()).find("parallel") != std::string::npos,
    std::string("parallel projection inside: frustum only (") + culler->GetFallbackReason() + ")");
  cam->ParallelProjectionOff();
  cam->SetPosition(2.5, 2, 1.5);
  cam->SetFocalPoint(30, 2, 1.5);

  // Eye outside every room, inside the building's bounds? Here: outside all bounds -> enter
  // through exterior portals; there are none, so only the outside (no prop) and free props.
  cam->SetPosition(2.5, -20, 1.5);
  cam->SetFocalPoint(2.5, 2, 1.5);
  drawn = Run(culler, ren, props);
  ok &= Check(!Has(drawn, r0.Get()) && Has(drawn, free.Get()), "outside: rooms without windows culled");
  culler->SetOutsidePolicy(vtkPortalCuller::OUTSIDE_FRUSTUM_ONLY);
  drawn = Run(culler, ren, props);
  ok &= Check(Has(drawn, r0.Get()) && culler->GetFrustumOnly(), "outside, frustum-only policy");
  culler->SetOutsidePolicy(vtkPortalCuller::OUTSIDE_EXTERIOR_PORTALS);

  // Unusable camera: warned once, nothing culled.
  cam->SetPosition(2.5, 2, 1.5);
  cam->SetFocalPoint(30, 2, 1.5);
  cam->SetClippingRange(std::numeric_limits<double>::quiet_NaN(), 100);
  drawn = Run(culler, ren, props);
  ok &= Check(drawn.size() == props.size(), "unusable camera: all drawn");
  cam->SetClippingRange(0.05, 100);

  // Explicit prop rooms override the data: put the free cube into room 3 (never visible here).
  culler->SetPropRoom(free.Get(), 3);
  drawn = Run(culler, ren, props);
  ok &= Check(!Has(drawn, free.Get()), "explicit prop room");
  culler->RemoveAllPropRooms();
  // Explicit rooms per cell (SetPropCellRooms): all six faces of the free cube in room 3, then
  // an array of the wrong length (reported, the cube only frustum-culled), then forgotten.
  vtkNew<vtkIntArray> cellRooms;
  cellRooms->SetNumberOfTuples(6);
  cellRooms->FillValue(3);
  culler->SetPropCellRooms(free.Get(), cellRooms);
  drawn = Run(culler, ren, props);
  ok &= Check(!Has(drawn, free.Get()), "explicit cell rooms: the cube in room 3, culled");
  vtkNew<vtkIntArray> tooShort;
  tooShort->SetNumberOfTuples(2);
  tooShort->FillValue(3);
  culler->SetPropCellRooms(free.Get(), tooShort);
  drawn = Run(culler, ren, props);
  ok &= Check(Has(drawn, free.Get()) &&
      std::string(culler->GetGraphReport()).find("2 values for 6 cells") != std::string::npos,
    "cell rooms of the wrong length: reported, the cube frustum-culled only");
  culler->SetPropCellRooms(free.Get(), nullptr);
  drawn = Run(culler, ren, props);
  ok &= Check(Has(drawn, free.Get()), "cell rooms forgotten");

  // Empty list and a real render with the culler installed.
  int zero = 0, init = 0;
  ok &= Check(culler->Cull(ren, nullptr, zero, init) == 0.0 && init == 1, "empty list");
  ren->AddCuller(culler);
  window->Render();
  ok &= Check(culler->GetNumberOfPropsDrawn() > 0, "renders with the culler installed");

  std::ostringstream print;
  culler->Print(print);
  ok &= Check(print.str().find("Mode: exact frustum") != std::string::npos, "PrintSelf");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

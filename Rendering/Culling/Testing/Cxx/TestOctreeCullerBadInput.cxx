// Specification: bad input to vtkOctreeCuller gives correct output or a clear VTK warning, never
// a crash: props with empty / NaN bounds, 2D props, unusable cameras, a zero-size viewport, and
// props added, removed and moved between frames (all four update modes, event-driven included),
// in every culling mode: frustum, distance, small-feature and normal-cone culling, alone and
// together, and occlusion (vtkOcclusionCuller), which also meets bad occluders: NaN points,
// zero-area triangles, an eye inside an occluder, its near plane cutting one, a viewport of one
// pixel, coordinates at 1e7.
#include "vtkOcclusionCuller.h"
#include "vtkOctreeCuller.h"

#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkCamera.h>
#include <vtkCubeSource.h>
#include <vtkCellArray.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>
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

vtkSmartPointer<vtkActor> Cube(double x, double y, double z)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(x, y, z);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  return actor;
}

/// Cull a copy of @p props; returns the drawn ones (the list's first listLength entries).
std::vector<vtkProp*> Run(
  vtkOctreeCuller* culler, vtkRenderer* ren, std::vector<vtkProp*> props, double* total = nullptr)
{
  int length = static_cast<int>(props.size());
  int initialized = 0;
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

/// An actor of one polydata of triangles (points 3 per triangle) at @p offset.
vtkSmartPointer<vtkActor> Triangles(const std::vector<double>& xyz, double offset = 0.0)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> cells;
  for (std::size_t i = 0; i + 8 < xyz.size(); i += 9)
  {
    vtkIdType ids[3];
    for (int k = 0; k < 3; ++k)
    {
      ids[k] = points->InsertNextPoint(
        xyz[i + 3 * k] + offset, xyz[i + 3 * k + 1] + offset, xyz[i + 3 * k + 2]);
    }
    cells->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetPolys(cells);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(pd);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  return actor;
}

/// A square wall at z = @p z, half-size @p h, two triangles (plus @p extra coordinates).
std::vector<double> Wall(double z, double h)
{
  return { -h, -h, z, h, -h, z, h, h, z, -h, -h, z, h, h, z, -h, h, z };
}

bool TestBadOccluders(vtkRenderWindow* window)
{
  bool ok = true;
  for (const double offset : { 0.0, 1e7 })
  {
    const std::string at = offset == 0.0 ? "" : " (at 1e7)";
    vtkNew<vtkRenderer> ren;
    window->AddRenderer(ren);
    vtkCamera* cam = ren->GetActiveCamera();
    cam->SetPosition(offset, offset, 10);
    cam->SetFocalPoint(offset, offset, 0);
    cam->SetClippingRange(0.5, 100);
    vtkNew<vtkOcclusionCuller> culler;
    vtkSmartPointer<vtkActor> wall = Triangles(Wall(5, 20), offset);
    vtkSmartPointer<vtkActor> hidden = Cube(offset, offset, 0);
    std::vector<vtkProp*> drawn = Run(culler, ren, { wall, hidden });
    ok &= Check(drawn.size() == 1 && Has(drawn, wall) &&
        culler->GetNumberOfPropsCulledByOcclusion() == 1,
      "occlusion" + at + ": the cube behind the wall is culled");
    // The same wall with a NaN point in one triangle and zero-area triangles: the NaN makes the
    // bounds unusable (always drawn, never an occluder), the cube is kept.
    std::vector<double> bad = Wall(5, 20);
    bad[0] = std::nan("");
    vtkSmartPointer<vtkActor> nanWall = Triangles(bad, offset);
    drawn = Run(culler, ren, { nanWall, hidden });
    ok &= Check(drawn.size() == 2, "occlusion" + at + ": a wall with a NaN point occludes nothing");
    vtkSmartPointer<vtkActor> flatWall =
      Triangles({ -20, -20, 5, 20, 20, 5, 0, 0, 5, -20, 20, 5, -20, 20, 5, 20, -20, 5 }, offset);
    drawn = Run(culler, ren, { flatWall, hidden });
    ok &= Check(drawn.size() == 2, "occlusion" + at + ": zero-area triangles occlude nothing");
    // Translucent and wireframe walls do not occlude.
    wall->GetProperty()->SetOpacity(0.5);
    drawn = Run(culler, ren, { wall, hidden });
    ok &= Check(drawn.size() == 2, "occlusion" + at + ": a translucent wall occludes nothing");
    wall->GetProperty()->SetOpacity(1.0);
    wall->GetProperty()->SetRepresentationToWireframe();
    drawn = Run(culler, ren, { wall, hidden });
    ok &= Check(drawn.size() == 2, "occlusion" + at + ": a wireframe wall occludes nothing");
    wall->GetProperty()->SetRepresentationToSurface();
    // Back-face culled wall seen from its back: not drawn, does not occlude.
    wall->GetProperty()->BackfaceCullingOn();
    cam->SetPosition(offset, offset, -10);
    cam->SetFocalPoint(offset, offset, 20);
    vtkSmartPointer<vtkActor> beyond = Cube(offset, offset, 10);
    drawn = Run(culler, ren, { wall, beyond });
    ok &= Check(Has(drawn, beyond), "occlusion" + at + ": a culled face does not occlude");
    wall->GetProperty()->BackfaceCullingOff();
    // The eye inside a closed occluder (a big cube): what is inside with it stays visible.
    vtkSmartPointer<vtkActor> room = Cube(offset, offset, 0);
    room->SetOrigin(offset, offset, 0);
    room->SetScale(40, 40, 40);
    vtkSmartPointer<vtkActor> inside = Cube(offset, offset, 5);
    cam->SetPosition(offset, offset, 10);
    cam->SetFocalPoint(offset, offset, 0);
    drawn = Run(culler, ren, { room, inside });
    ok &= Check(drawn.size() == 2, "occlusion" + at + ": eye inside an occluder");
    // The near plane cutting the wall (the eye 0.1 before it, near plane 0.5): the wall is cut
    // away where the eye is; the cube behind it stays drawn (it is seen through the cut).
    cam->SetPosition(offset, offset, 5.1);
    cam->SetClippingRange(0.5, 100);
    drawn = Run(culler, ren, { wall, hidden });
    ok &= Check(Has(drawn, hidden), "occlusion" + at + ": near plane cutting the occluder");
    // One-pixel viewport.
    cam->SetPosition(offset, offset, 10);
    ren->SetViewport(0, 0, 1.0 / 200, 1.0 / 150);
    drawn = Run(culler, ren, { wall, hidden });
    ok &= Check(Has(drawn, wall), "occlusion" + at + ": one-pixel viewport, no crash");
    ren->SetViewport(0, 0, 1, 1);
    window->RemoveRenderer(ren);
  }
  return ok;
}
} // namespace

int TestOctreeCullerBadInput(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  vtkOutput.ExpectWarning("non-finite bounds");
  vtkOutput.ExpectWarning("camera is not usable");
  vtkOutput.ExpectWarning("viewport has zero size");
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(200, 150);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  ren->GetCullers()->RemoveAllItems();
  vtkNew<vtkOctreeCuller> culler;
  ren->AddCuller(culler);

  vtkSmartPointer<vtkActor> visible = Cube(0, 0, 0);
  vtkSmartPointer<vtkActor> behind = Cube(0, 0, 50); // behind the camera
  // Empty polydata: uninitialized bounds.
  vtkNew<vtkPolyDataMapper> emptyMapper;
  vtkNew<vtkPolyData> emptyData;
  emptyMapper->SetInputData(emptyData);
  vtkNew<vtkActor> empty;
  empty->SetMapper(emptyMapper);
  // NaN bounds through a NaN position.
  vtkSmartPointer<vtkActor> nanActor = Cube(0, 0, 0);
  nanActor->SetPosition(std::nan(""), 0, 0);
  // A 2D prop (no bounds) and an actor without mapper.
  vtkNew<vtkActor2D> flat;
  vtkNew<vtkPolyDataMapper2D> flatMapper;
  flatMapper->SetInputData(emptyData);
  flat->SetMapper(flatMapper);
  vtkNew<vtkActor> noMapper;
  for (vtkProp* p : std::vector<vtkProp*>{ visible, behind, empty, nanActor, flat, noMapper })
  {
    ren->AddViewProp(p);
  }
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(0, 0, 10);
  cam->SetFocalPoint(0, 0, 0);
  cam->SetClippingRange(1, 100);

  std::vector<vtkProp*> all{ visible, behind, empty, nanActor, flat, noMapper };
  double total = 0;
  std::vector<vtkProp*> drawn = Run(culler, ren, all, &total);
  ok &= Check(drawn.size() == 5 && !Has(drawn, behind),
    "props with empty/NaN/no bounds and 2D props are kept; the one behind is culled");
  ok &= Check(total > 0, "total render time > 0 while props remain");

  // Rendering with it installed works.
  window->Render();
  ok &= Check(culler->GetNumberOfPropsDrawn() == 5, "render: 5 drawn");

  // Camera with a NaN position: warning, nothing culled.
  cam->SetPosition(std::nan(""), 0, 10);
  drawn = Run(culler, ren, all);
  ok &= Check(drawn.size() == all.size() && culler->GetCullingSkipped(), "NaN camera: all kept");
  cam->SetPosition(0, 0, 10);
  // Zero view angle (VTK clamps it to a tiny angle): no crash, the far cube is culled.
  cam->SetViewAngle(0.0);
  drawn = Run(culler, ren, all);
  ok &= Check(!Has(drawn, behind), "zero view angle: no crash");
  cam->SetViewAngle(30.0);
  // Parallel projection with zero scale: no crash.
  cam->ParallelProjectionOn();
  cam->SetParallelScale(0.0);
  drawn = Run(culler, ren, all);
  ok &= Check(drawn.size() >= 4, "zero parallel scale: no crash, unbounded props kept");
  cam->ParallelProjectionOff();

  // Zero-size viewport: warning, nothing culled.
  ren->SetViewport(0.5, 0.5, 0.5, 0.5);
  drawn = Run(culler, ren, all);
  ok &= Check(drawn.size() == all.size(), "zero-size viewport: all kept");
  ren->SetViewport(0, 0, 1, 1);

  // Empty list and null list.
  int zero = 0, init = 0;
  ok &= Check(culler->Cull(ren, nullptr, zero, init) == 0.0 && zero == 0, "empty list");

  // Every culling mode, alone and all together, on the same bad props and bad cameras: the
  // unbounded (empty, NaN, 2D, no mapper) props are always kept, unusable cameras and viewports
  // cull nothing, and the contract holds. Normal cones see back-face-culled actors, including
  // the NaN one (its cone test must not cull on NaN arithmetic).
  {
    struct Mode
    {
      const char* name;
      bool normalCones;
      double minimumPixels;
      double maximumDistance;
      bool occlusion = false;
    };
    const Mode modes[] = { { "normal cones", true, 0.0, VTK_DOUBLE_MAX },
      { "small features 4 px", false, 4.0, VTK_DOUBLE_MAX }, { "distance 100", false, 0.0, 100.0 },
      { "all modes", true, 4.0, 100.0 }, { "occlusion", false, 0.0, VTK_DOUBLE_MAX, true },
      { "occlusion and all modes", true, 4.0, 100.0, true } };
    for (vtkActor* a : { visible.GetPointer(), behind.GetPointer(), empty.GetPointer(),
           nanActor.GetPointer(), noMapper.GetPointer() })
    {
      a->GetProperty()->BackfaceCullingOn();
    }
    for (const Mode& m : modes)
    {
      const std::string name = m.name;
      vtkSmartPointer<vtkOctreeCuller> c = m.occlusion
        ? vtkSmartPointer<vtkOctreeCuller>(vtkSmartPointer<vtkOcclusionCuller>::New())
        : vtkSmartPointer<vtkOctreeCuller>::New();
      c->SetNormalConeCulling(m.normalCones);
      c->SetMinimumPixelSize(m.minimumPixels);
      c->SetMaximumDistance(m.maximumDistance);
      drawn = Run(c, ren, all);
      ok &= Check(drawn.size() == 5 && !Has(drawn, behind) && Has(drawn, visible) &&
          Has(drawn, empty) && Has(drawn, nanActor) && Has(drawn, flat) && Has(drawn, noMapper),
        name + ": unbounded props kept, the one behind culled, the visible one drawn");
      cam->SetPosition(std::nan(""), 0, 10);
      drawn = Run(c, ren, all);
      ok &= Check(drawn.size() == all.size() && c->GetCullingSkipped(), name + ": NaN camera");
      cam->SetPosition(0, 0, 10);
      cam->SetViewAngle(0.0);
      drawn = Run(c, ren, all);
      ok &= Check(!Has(drawn, behind) && Has(drawn, flat), name + ": zero view angle");
      cam->SetViewAngle(30.0);
      cam->ParallelProjectionOn();
      cam->SetParallelScale(0.0);
      drawn = Run(c, ren, all);
      ok &= Check(drawn.size() >= 4 && Has(drawn, flat), name + ": zero parallel scale");
      cam->ParallelProjectionOff();
      ren->SetViewport(0.5, 0.5, 0.5, 0.5);
      drawn = Run(c, ren, all);
      ok &= Check(drawn.size() == all.size(), name + ": zero-size viewport");
      ren->SetViewport(0, 0, 1, 1);
      ren->GetCullers()->RemoveAllItems();
      ren->AddCuller(c);
      window->Render();
      ok &= Check(c->GetNumberOfPropsDrawn() == 5, name + ": render: 5 drawn");
      ren->GetCullers()->RemoveAllItems();
      ren->AddCuller(culler);
    }
    for (vtkActor* a : { visible.GetPointer(), behind.GetPointer(), empty.GetPointer(),
           nanActor.GetPointer(), noMapper.GetPointer() })
    {
      a->GetProperty()->BackfaceCullingOff();
    }
  }

  ok &= TestBadOccluders(window);

  // Moves between frames, per update mode (UPDATE_ON_EVENTS last: it is the default).
  for (int mode = vtkOctreeCuller::UPDATE_BOUNDS_EVERY_FRAME;
       mode <= vtkOctreeCuller::UPDATE_ON_EVENTS; ++mode)
  {
    culler->SetUpdateMode(mode);
    std::vector<vtkProp*> two{ visible, behind };
    drawn = Run(culler, ren, two);
    ok &= Check(!Has(drawn, behind), "mode " + std::to_string(mode) + ": behind culled");
    behind->SetPosition(0, 0, -50); // now in front (cube centre at z = 0)
    if (mode == vtkOctreeCuller::UPDATE_MANUAL)
    {
      drawn = Run(culler, ren, two);
      ok &= Check(!Has(drawn, behind), "manual mode: not seen before InvalidateProp()");
      culler->InvalidateProp(behind);
    }
    drawn = Run(culler, ren, two);
    ok &= Check(Has(drawn, behind), "mode " + std::to_string(mode) + ": moved prop is drawn");
    behind->SetPosition(0, 0, 0);
    culler->InvalidateProp(behind);
    Run(culler, ren, two);
  }
  culler->SetUpdateMode(vtkOctreeCuller::UPDATE_BOUNDS_EVERY_FRAME);

  // Added and removed props between frames; the same prop twice.
  const vtkIdType rebuilds = culler->GetNumberOfRebuilds();
  vtkSmartPointer<vtkActor> added = Cube(1, 1, 0);
  drawn = Run(culler, ren, { visible, added, behind, visible });
  ok &= Check(Has(drawn, added) && culler->GetNumberOfRebuilds() == rebuilds + 1,
    "added prop: rebuilt once and drawn");
  drawn = Run(culler, ren, { added });
  ok &= Check(drawn.size() == 1 && culler->GetNumberOfRebuilds() == rebuilds + 1,
    "removed props: subset mapped without a rebuild");
  added = nullptr; // deleted while the culler may still know it
  drawn = Run(culler, ren, { visible, Cube(2, 0, 0) });
  ok &= Check(drawn.size() == 2, "a deleted prop and a new one: no crash");

  // Front-to-back sorting of the drawn props; 2D props first.
  {
    vtkSmartPointer<vtkActor> nearCube = Cube(0, 0, 5), midCube = Cube(0, 0, 0),
                              farCube = Cube(0, 0, -5);
    culler->SetSortingStyle(VTK_CULLER_SORT_FRONT_TO_BACK);
    drawn = Run(culler, ren, { farCube, flat, nearCube, midCube });
    ok &= Check(drawn.size() == 4 && drawn[0] == flat.GetPointer() && drawn[1] == nearCube &&
        drawn[2] == midCube && drawn[3] == farCube,
      "front-to-back: 2D prop first, then near, mid, far");
    culler->SetSortingStyle(VTK_CULLER_SORT_BACK_TO_FRONT);
    drawn = Run(culler, ren, { farCube, flat, nearCube, midCube });
    ok &= Check(
      drawn.size() == 4 && drawn[0] == farCube && drawn[2] == nearCube, "back-to-front: far first");
    culler->SetSortingStyle(VTK_CULLER_SORT_NONE);
  }

  // After vtkFrustumCoverageCuller (default install + ours): still correct.
  vtkNew<vtkRenderer> both;
  window->AddRenderer(both);
  both->AddCuller(culler);
  both->AddActor(visible);
  both->AddActor(Cube(0, 0, 50));
  both->GetActiveCamera()->SetPosition(0, 0, 10);
  both->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  window->Render();
  ok &= Check(culler->GetNumberOfPropsDrawn() == 1, "after vtkFrustumCoverageCuller: 1 drawn");
  std::ostringstream os;
  culler->Print(os);
  ok &= Check(os.str().find("NumberOfRebuilds") != std::string::npos, "PrintSelf");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

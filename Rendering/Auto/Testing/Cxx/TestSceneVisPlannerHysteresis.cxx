// When vtkSceneVisPlanner plans, and that it installs nothing a scene does not call for:
//  (a) a small opaque scene: nothing installed (VTK's culler, no pass, the application's mappers);
//  (b) nothing changed for 20 renders: no reading of the scene, no view measurement, no plan;
//  (c) a camera that flies from an overview of 576 box actors down to a view along their rows: the
//      culling plan changes once (octree -> occlusion, as the depth complexity passes 4),
//      SwitchFrames renders after the view is clear of the threshold, not every frame;
//  (d) a camera held just past the threshold (within the margin): no change;
//  (e) a camera that jumps between overview and the view along the rows every render, with an
//      actor moving every render (props that only move go through the same hysteresis): no
//      change;
//  (f) an actor added, moved, hidden or shown: the scene is read again at the next render (a moved
//      actor alone), without a new plan when the decision stays.
#include "vtkSceneVisPlanner.h"

#include "PlannerTesting.h"

#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
using plannertesting::Check;

void Place(vtkCamera* camera, const double eye[3], const double focal[3])
{
  camera->SetPosition(eye[0], eye[1], eye[2]);
  camera->SetFocalPoint(focal[0], focal[1], focal[2]);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  camera->OrthogonalizeViewUp();
}

/// The camera at @p t of the flight from the overview (t = 0) down to a view along the rows
/// (t = 1).
void Fly(vtkRenderer* renderer, double t)
{
  const double from[3] = { 12, -30, 40 }, to[3] = { -3, 12, 1.2 };
  const double focalFrom[3] = { 12, 12, 0 }, focalTo[3] = { 30, 12.3, 0.4 };
  double eye[3], focal[3];
  for (int a = 0; a < 3; ++a)
  {
    eye[a] = from[a] + t * (to[a] - from[a]);
    focal[a] = focalFrom[a] + t * (focalTo[a] - focalFrom[a]);
  }
  Place(renderer->GetActiveCamera(), eye, focal);
  renderer->ResetCameraClippingRange();
}
} // namespace

int TestSceneVisPlannerHysteresis(int, char*[])
{
  scenevis::testing::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(200, 200);

  // --- (a) a small scene -----------------------------------------------------------------------
  {
    vtkNew<vtkRenderer> small;
    window->AddRenderer(small);
    vtkNew<vtkSphereSource> sphere;
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    for (int i = 0; i < 3; ++i)
    {
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->SetPosition(1.5 * i, 0, 0);
      small->AddActor(actor);
    }
    vtkSceneVisPlanner* planner = vtkSceneVisPlanner::Attach(small);
    small->ResetCamera();
    window->Render();
    std::cout << planner->GetReason() << "\n";
    vtkCuller* first = vtkCuller::SafeDownCast(small->GetCullers()->GetItemAsObject(0));
    ok &= Check(std::string(planner->GetCullMethod()) == "none" &&
        std::string(planner->GetTranslucencyMethod()) == "none" && !planner->GetCuller() &&
        small->GetPass() == nullptr && small->GetCullers()->GetNumberOfItems() == 1 &&
        vtkFrustumCoverageCuller::SafeDownCast(first) &&
        mapper.Get() == vtkActor::SafeDownCast(small->GetActors()->GetItemAsObject(0))->GetMapper(),
      "small opaque scene: nothing installed (" + std::string(planner->GetCullReason()) + ")");
    window->RemoveRenderer(small);
  }

  // --- (b) nothing changed -----------------------------------------------------------------------
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  plannertesting::BoxGrid grid(renderer, 24, 24, 1, 0.8);
  vtkNew<vtkSceneVisPlanner> planner;
  planner->SetRenderer(renderer);
  Fly(renderer, 0.0);
  window->Render();
  std::cout << "overview: " << planner->GetReason() << "\n";
  ok &= Check(std::string(planner->GetCullMethod()) == "octree",
    "overview: everything in view, low depth complexity: the octree (the application's actors)");
  const int inspections = planner->GetInspectionCount();
  const int measurements = planner->GetViewMeasurementCount();
  for (int i = 0; i < 20; ++i)
  {
    renderer->ResetCameraClippingRange(); // modifies the camera, not the view
    window->Render();
  }
  ok &= Check(planner->GetInspectionCount() == inspections &&
      planner->GetViewMeasurementCount() == measurements && planner->GetPlanCount() == 1,
    "nothing changed for 20 renders: " + std::to_string(planner->GetInspectionCount()) +
      " reading(s), " + std::to_string(planner->GetViewMeasurementCount()) + " measurement(s), " +
      std::to_string(planner->GetPlanCount()) + " plan(s); last Plan() " +
      std::to_string(planner->GetLastPlanTime()) + " ms");

  // --- (c) the flight
  // ------------------------------------------------------------------------------
  const int frames = 120;
  int changes = 0, changedAt = -1, clearAt = -1;
  double heldT = -1.0; // a point of the flight just past the threshold, within the margin
  double lastDepth = 0.0;
  bool rising = true;
  std::string method = planner->GetCullMethod();
  for (int f = 0; f <= frames + 10; ++f) // the camera arrives, then stays for 10 renders
  {
    const double t = std::min(1.0, static_cast<double>(f) / frames);
    Fly(renderer, t);
    window->Render();
    const double depth = planner->GetFacts().depthComplexity;
    rising &= depth >= lastDepth - 0.05; // the flight is built so (the checks below rely on it)
    lastDepth = depth;
    // Clear of the threshold 4: the depth complexity less the margin still reaches it.
    const double lowered = depth * (1.0 - planner->GetViewMargin());
    if (clearAt < 0 && lowered >= 4.0)
      clearAt = f;
    if (heldT < 0.0 && depth >= 4.0 && lowered < 4.0)
      heldT = t;
    if (planner->GetCullMethod() != method)
    {
      ++changes;
      changedAt = f;
      method = planner->GetCullMethod();
      std::cout << "frame " << f << ": " << planner->GetReason() << "\n";
    }
  }
  ok &= Check(
    rising, "the depth complexity rises along the flight (to " + std::to_string(lastDepth) + ")");
  ok &= Check(changes == 1 && method == "occlusion" && planner->GetPlanCount() == 2,
    "flight: the culling plan changed " + std::to_string(changes) + " time(s), to " + method);
  ok &= Check(clearAt >= 0 && changedAt == clearAt + planner->GetSwitchFrames() - 1,
    "it changed at frame " + std::to_string(changedAt) + ", " +
      std::to_string(planner->GetSwitchFrames()) + " renders from frame " +
      std::to_string(clearAt) + " (the first clear of the threshold by the margin)");

  // --- (d) held within the margin
  // ------------------------------------------------------------------
  Fly(renderer, 0.0);
  for (int i = 0; i < 10; ++i)
    window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) == "octree", "back to the overview: octree");
  const int plans = planner->GetPlanCount();
  ok &=
    Check(heldT > 0.0, "the flight passes the margin's band (t = " + std::to_string(heldT) + ")");
  if (heldT > 0.0)
  {
    for (int i = 0; i < 20; ++i)
    {
      Fly(renderer, heldT + (i % 2) * 1e-4); // a camera that still moves a little
      window->Render();
    }
    ok &= Check(
      planner->GetPlanCount() == plans && std::string(planner->GetCullMethod()) == "octree",
      "20 renders at a depth complexity of " + std::to_string(planner->GetFacts().depthComplexity) +
        " (past 4, within the margin): no change");
  }

  // --- (e) jumping between the views
  // ---------------------------------------------------------------
  for (int i = 0; i < 30; ++i)
  {
    Fly(renderer, (i % 2) ? 1.0 : 0.0);
    grid.actors[0]->SetPosition(0, 0, (i % 2) * 0.01); // an animated actor: no bypass
    window->Render();
  }
  ok &= Check(planner->GetPlanCount() == plans,
    "30 renders jumping between overview and the view along the rows, an actor moving: no change");

  // --- (f) scene changes -----------------------------------------------------------------------
  for (int i = 0; i < 10; ++i)
    window->Render();
  const int before = planner->GetInspectionCount();
  const int plansBefore = planner->GetPlanCount();
  const double lo[3] = { 30, 30, 0 }, hi[3] = { 31, 31, 1 };
  vtkNew<vtkPolyDataMapper> extraMapper;
  extraMapper->SetInputData(plannertesting::MakeBox(lo, hi, 576));
  vtkNew<vtkActor> extra;
  extra->SetMapper(extraMapper);
  renderer->AddActor(extra);
  window->Render();
  ok &= Check(planner->GetInspectionCount() == before + 1 && planner->GetFacts().parts == 577,
    "an actor added: read at the next render (" + std::to_string(planner->GetFacts().parts) +
      " parts)");
  grid.actors[3]->SetPosition(0, 0, 0.5);
  window->Render();
  window->Render();
  ok &= Check(planner->GetInspectionCount() == before + 2 && planner->GetPlanCount() == plansBefore,
    "an actor moved: read once, the plan stays (" + std::string(planner->GetCullMethod()) + ")");
  grid.actors[5]->VisibilityOff();
  window->Render();
  const std::size_t hidden = planner->GetFacts().parts;
  grid.actors[5]->VisibilityOn();
  window->Render();
  ok &= Check(hidden == 576 && planner->GetFacts().parts == 577,
    "an actor hidden, then shown: " + std::to_string(hidden) + ", then " +
      std::to_string(planner->GetFacts().parts) + " parts");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

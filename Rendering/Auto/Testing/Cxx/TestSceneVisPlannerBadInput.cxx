// vtkSceneVisPlanner on bad input: a clear warning and a sane plan, never a crash.
//  - Plan() without a renderer; Attach(nullptr);
//  - a renderer without props (warned once, nothing installed), then with props;
//  - an actor without a mapper and one whose mapper has no input (left out, warned once each);
//  - 150 actors, one of them with a NaN point, and one with NaN bounds (warned, the view still
//    measured);
//  - a renderer with its own render pass (kept, warned once);
//  - a renderer destroyed before its attached planner's actors, and a planner destroyed before
//    its renderer (everything it installed undone).
#include "vtkSceneVisPlanner.h"

#include "PlannerTesting.h"

#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkLightsPass.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>

namespace
{
using plannertesting::Check;

/// An actor whose bounds are NaN (what a broken transform or a custom prop can give).
class NaNBoundsActor : public vtkActor
{
public:
  static NaNBoundsActor* New() { return new NaNBoundsActor; }
  vtkTypeMacro(NaNBoundsActor, vtkActor);
  double* GetBounds() override
  {
    for (double& b : this->NaNBounds)
      b = std::numeric_limits<double>::quiet_NaN();
    return this->NaNBounds;
  }
  double NaNBounds[6];
};
} // namespace

int TestSceneVisPlannerBadInput(int, char*[])
{
  scenevis::testing::StrictVtkOutput vtkOutput;
  vtkOutput.ExpectWarning("no renderer");
  vtkOutput.ExpectWarning("has no visible actors with polydata");
  vtkOutput.ExpectWarning("has no mapper");
  vtkOutput.ExpectWarning("has a mapper without input");
  vtkOutput.ExpectWarning("has NaN bounds");
  vtkOutput.ExpectWarning("has its own render pass");
  bool ok = true;

  // Nothing to plan for.
  {
    vtkNew<vtkSceneVisPlanner> planner;
    planner->Plan();
    ok &= Check(planner->GetPlanCount() == 0 && std::string(planner->GetCullMethod()) == "none",
      "Plan() without a renderer: nothing");
    ok &= Check(vtkSceneVisPlanner::Attach(nullptr) == nullptr, "Attach(nullptr): nullptr");
  }

  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(160, 160);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkSceneVisPlanner* planner = vtkSceneVisPlanner::Attach(renderer);
  window->Render();
  window->Render();
  ok &= Check(std::string(planner->GetCullMethod()) == "none" && !planner->GetCuller() &&
      renderer->GetPass() == nullptr && planner->GetFacts().parts == 0,
    "no props: nothing installed (" + std::string(planner->GetCullReason()) + ")");

  // Actors the planner cannot read: left out, the renderer not rendered (VTK itself complains
  // about a mapper without input; the planner is asked directly).
  vtkNew<vtkActor> noMapper;
  vtkNew<vtkPolyDataMapper> emptyMapper;
  vtkNew<vtkActor> noInput;
  noInput->SetMapper(emptyMapper);
  renderer->AddActor(noMapper);
  renderer->AddActor(noInput);
  planner->Plan();
  planner->Plan();
  ok &= Check(planner->GetFacts().parts == 0 && std::string(planner->GetCullMethod()) == "none",
    "actors without mapper or input: left out");
  renderer->RemoveActor(noMapper);
  renderer->RemoveActor(noInput);

  // 150 actors, one with a NaN point, and one more with NaN bounds.
  plannertesting::BoxGrid grid(renderer, 15, 10, 1, 0.8);
  auto* points = grid.boxes[7]->GetPoints();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  points->SetPoint(0, nan, nan, nan);
  points->Modified();
  vtkNew<NaNBoundsActor> nanActor;
  nanActor->SetMapper(grid.actors[9]->GetMapper());
  renderer->AddActor(nanActor);
  renderer->GetActiveCamera()->SetPosition(3, 3, 6);
  renderer->GetActiveCamera()->SetFocalPoint(3, 3, 0);
  renderer->GetActiveCamera()->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();
  planner->Plan(); // not rendered: NaN points are not for the GPU
  const vtkScenePlanFacts& facts = planner->GetFacts();
  ok &= Check(facts.parts == 151 && facts.inView >= 0.0 && facts.inView <= 1.0 &&
      std::isfinite(facts.depthComplexity),
    "NaN bounds: " + facts.Summary() + "; culling " + planner->GetCullMethod());
  points->SetPoint(0, 7, 0, 0);
  points->Modified();
  renderer->RemoveActor(nanActor);

  // Detaching: VTK's culler back.
  planner->SetRenderer(nullptr); // the renderer owned it: gone
  ok &= Check(renderer->GetCullers()->GetNumberOfItems() == 1, "detached: one culler (VTK's)");

  // A renderer with its own pass keeps it; translucency is then its business.
  {
    vtkNew<vtkRenderer> passRenderer;
    window->AddRenderer(passRenderer);
    vtkNew<vtkLightsPass> own;
    passRenderer->SetPass(own);
    plannertesting::BoxGrid translucent(passRenderer, 2, 1, 1, 0.8, 0.5);
    vtkNew<vtkSceneVisPlanner> keeper;
    keeper->SetRenderer(passRenderer);
    keeper->Plan();
    keeper->Plan();
    ok &= Check(passRenderer->GetPass() == own.Get(),
      "a renderer with its own pass keeps it (planned: " +
        std::string(keeper->GetTranslucencyMethod()) + ")");
    window->RemoveRenderer(passRenderer);
  }

  // Lifetimes: an attached planner dies with its renderer (and gives the actors their mappers
  // back); a planner that dies first undoes its work.
  {
    vtkNew<vtkActor> survivor;
    vtkNew<vtkPolyDataMapper> own;
    {
      auto shortLived = vtkSmartPointer<vtkRenderer>::New();
      window->AddRenderer(shortLived);
      vtkNew<vtkSphereSource> sphere;
      own->SetInputConnection(sphere->GetOutputPort());
      survivor->SetMapper(own);
      survivor->GetProperty()->SetOpacity(0.5);
      shortLived->AddActor(survivor);
      vtkSceneVisPlanner::Attach(shortLived);
      window->Render();
      ok &= Check(survivor->GetMapper() != own.Get(), "one translucent mesh: mapper swapped");
      window->RemoveRenderer(shortLived);
    }
    ok &= Check(survivor->GetMapper() == own.Get(),
      "renderer gone: the actor has its own mapper back");
    vtkNew<vtkRenderer> longLived;
    longLived->AddActor(survivor);
    window->AddRenderer(longLived);
    {
      vtkNew<vtkSceneVisPlanner> brief;
      brief->SetRenderer(longLived);
      window->Render();
    }
    ok &= Check(survivor->GetMapper() == own.Get() && longLived->GetPass() == nullptr,
      "planner gone: mapper and pass restored");
    window->Render();
  }
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

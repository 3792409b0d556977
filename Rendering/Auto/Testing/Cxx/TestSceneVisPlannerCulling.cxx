// vtkSceneVisPlanner on an opaque scene of 1,728 box actors (24 x 24 x 3):
//  (a) seen from far away, everything in view, depth complexity below 4: vtkOcclusionCuller with
//      occlusion off ("octree") installed in place of vtkFrustumCoverageCuller (the application's
//      actors cannot be merged, and the octree costs less per frame than VTK's culler);
//  (b) seen from above a corner, close: a few % in view, low depth complexity: the same, with
//      the same plan (no new one);
//  (c) seen along the rows from the side: depth complexity >= 4: occlusion culling on, the same
//      culler and the same hierarchy (no rebuild);
//  (a, b, c) what the cullers kept has 0 false negatives against the ID buffer's visible set, and
//      something was culled;
//  (d) the decision as data: the reason quotes the facts line; PrintSelf works.
#include "vtkSceneVisPlanner.h"

#include "PlannerTesting.h"

#include "vtkOcclusionCuller.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
namespace st = scenevis::testing;
using plannertesting::Check;

int CountCoverageCullers(vtkRenderer* renderer)
{
  int n = 0;
  vtkCollectionSimpleIterator it;
  renderer->GetCullers()->InitTraversal(it);
  while (vtkCuller* culler = renderer->GetCullers()->GetNextCuller(it))
    n += vtkFrustumCoverageCuller::SafeDownCast(culler) ? 1 : 0;
  return n;
}
} // namespace

int TestSceneVisPlannerCulling(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(300, 300);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  plannertesting::BoxGrid grid(renderer, 24, 24, 3, 0.8);
  vtkNew<vtkAppendPolyData> append; // every box, cells tagged with their actor's index
  for (const auto& box : grid.boxes)
    append->AddInputData(box);
  append->Update();

  vtkSceneVisPlanner* planner = vtkSceneVisPlanner::Attach(renderer);
  planner->SetSwitchFrames(1); // this test is about what is installed, not when
  planner->SetViewMargin(0.0);
  vtkNew<plannertesting::RecordingCuller> recorder;
  vtkCamera* camera = renderer->GetActiveCamera();

  struct View
  {
    const char* name;
    double eye[3], focal[3], angle;
    const char* expected;
  };
  const View views[] = {
    { "overview", { 12, -60, 60 }, { 12, 12, 1 }, 30, "octree" },
    { "close, above a corner", { 0.5, 0.5, 10 }, { 0.6, 0.6, 0 }, 30, "octree" },
    { "along the rows", { -3, 12, 1.2 }, { 30, 12.3, 1.2 }, 40, "occlusion" },
    { "close, above another corner", { 23.4, 23.4, 10 }, { 23.3, 23.3, 0 }, 30, "octree" },
  };
  vtkIdType rebuilds = -1;
  for (const View& view : views)
  {
    camera->SetPosition(view.eye);
    camera->SetFocalPoint(view.focal);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(view.angle);
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
    // Plan before rendering so that the recorder can be put after the planner's culler.
    planner->Plan();
    renderer->RemoveCuller(recorder);
    renderer->AddCuller(recorder);
    window->Render();
    const std::string tag = std::string(view.name) + ": ";
    std::cout << tag << planner->GetReason() << "\n";
    ok &= Check(std::string(planner->GetCullMethod()) == view.expected,
      tag + "culling " + planner->GetCullMethod() + " (expected " + view.expected + ")");
    ok &=
      Check(std::string(planner->GetTranslucencyMethod()) == "none", tag + "opaque: no sorting");
    ok &= Check(renderer->GetPass() == nullptr, tag + "no render pass");
    auto* culler = vtkOcclusionCuller::SafeDownCast(planner->GetCuller());
    ok &= Check(culler && renderer->GetCullers()->IsItemPresent(culler) &&
        CountCoverageCullers(renderer) == 0,
      tag + "vtkOcclusionCuller installed instead of vtkFrustumCoverageCuller");
    if (!culler)
      continue;
    ok &= Check(culler->GetOcclusionCulling() == (std::string(view.expected) == "occlusion"),
      tag + "occlusion culling " + (culler->GetOcclusionCulling() ? "on" : "off"));
    if (rebuilds < 0)
      rebuilds = culler->GetNumberOfRebuilds();
    ok &= Check(culler->GetNumberOfRebuilds() == rebuilds,
      tag + "hierarchy kept: " + std::to_string(culler->GetNumberOfRebuilds()) + " build(s)");

    // 0 false negatives against the exact visible set of the ID buffer.
    std::vector<std::uint32_t> drawn;
    for (vtkProp* prop : recorder->Kept)
    {
      const int index = grid.IndexOf(prop);
      if (index >= 0)
        drawn.push_back(static_cast<std::uint32_t>(index));
    }
    const st::IdImage ids = st::RenderVisibleIds(window, append->GetOutput(), camera, "PartId");
    const std::vector<std::uint32_t> visible = st::VisibleSet(ids);
    const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
    ok &= Check(check.conservative && !visible.empty(),
      tag + std::to_string(visible.size()) + " actors visible, " + std::to_string(drawn.size()) +
        " of " + std::to_string(grid.actors.size()) + " drawn: " + check.Summary());
    if (std::string(view.name) != "overview")
      ok &= Check(drawn.size() < grid.actors.size(), tag + "something was culled");
  }
  ok &= Check(planner->GetPlanCount() == 3,
    "one plan per change of method (octree, occlusion, octree): " +
      std::to_string(planner->GetPlanCount()));
  const std::string reason = planner->GetCullReason();
  ok &= Check(reason.find("1728 parts") != std::string::npos &&
      reason.find("% of the triangles in view") != std::string::npos &&
      reason.find("estimated depth complexity") != std::string::npos,
    "the reason quotes the facts: " + reason);
  std::ostringstream printed;
  planner->Print(printed);
  ok &= Check(printed.str().find("CullMethod: octree") != std::string::npos, "PrintSelf");

  // Detaching gives the renderer its own culler back.
  planner->SetRenderer(nullptr); // the renderer owned it: gone now
  ok &=
    Check(CountCoverageCullers(renderer) == 1 && renderer->GetCullers()->GetNumberOfItems() == 2,
      "detached: vtkFrustumCoverageCuller back, the planner's culler gone (and the recorder)");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

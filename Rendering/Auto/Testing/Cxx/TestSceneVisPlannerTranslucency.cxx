// vtkSceneVisPlanner on translucent scenes:
//  (a) three interpenetrating translucent actors (two spheres and a slab): vtkBSPTranslucentPass
//      under a vtkOrderedTranslucentPass installed; the ordering oracle (the painter's ID image
//      of the pass's fragments in drawing order == the z-buffer ID image) holds from several
//      views, and the image is that of 100-peel dual depth peeling;
//  (b) the actors made opaque: the pass is removed; translucent again: back;
//  (c) one translucent mesh (the 64-sphere grid, RGBA cell colours): its mapper is replaced by a
//      vtkBSPSortedPolyDataMapper (a shallow copy: same input, same colouring) under a plain
//      vtkOrderedTranslucentPass; the image is that of 100-peel depth peeling;
//  (d) detaching gives the actor its own mapper and the renderer no pass.
#include "vtkSceneVisPlanner.h"

#include "PlannerTesting.h"

#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
namespace st = scenevis::testing;
using plannertesting::Check;

vtkSmartPointer<vtkImageData> RenderWith(vtkRenderWindow* window, vtkRenderer* renderer)
{
  window->GetRenderers()->RemoveAllItems();
  window->AddRenderer(renderer);
  renderer->ResetCameraClippingRange();
  return st::CaptureImage(window);
}

void SetView(vtkRenderer* renderer, double azimuth, double elevation)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0, 1);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCamera();
  camera->Azimuth(azimuth);
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
}

vtkSmartPointer<vtkRenderer> PeelingRenderer(vtkCamera* camera)
{
  auto peel = vtkSmartPointer<vtkRenderer>::New();
  peel->SetUseDepthPeeling(1);
  peel->SetMaximumNumberOfPeels(100);
  peel->SetOcclusionRatio(0.0);
  peel->SetActiveCamera(camera);
  return peel;
}

bool LooksLikePeeling(vtkImageData* planned, vtkImageData* peeled, const std::string& tag)
{
  st::ImageThresholds peel;
  peel.maxMeanAbsError = 0.5;
  peel.maxCoveredBadFraction = 0.01;
  std::string why;
  const auto difference = st::CompareImages(planned, peeled);
  return Check(st::WithinThresholds(difference, peel, &why),
    tag + "planned vs 100-peel DDP: " + difference.Summary() + " " + why);
}
} // namespace

int TestSceneVisPlannerTranslucency(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(300, 300);

  // --- (a) several translucent actors -------------------------------------------------------
  const st::InterpenetratingActors scene = st::MakeInterpenetratingActors();
  vtkActor* red = scene.red;
  vtkActor* blue = scene.blue;
  vtkActor* green = scene.green;

  vtkNew<vtkRenderer> renderer;
  vtkSmartPointer<vtkRenderer> peelRenderer = PeelingRenderer(renderer->GetActiveCamera());
  for (vtkActor* actor : { red, blue, green })
  {
    renderer->AddActor(actor);
    peelRenderer->AddActor(actor);
  }
  vtkNew<vtkSceneVisPlanner> planner;
  planner->SetRenderer(renderer);
  const double views[][2] = { { 0, 0 }, { 40, 25 }, { 150, -30 }, { 250, 70 } };
  int v = 0;
  for (const auto& view : views)
  {
    SetView(renderer, view[0], view[1]);
    const std::string tag = "three actors, view " + std::to_string(v++) + ": ";
    auto planned = RenderWith(window, renderer);
    if (v == 1)
      std::cout << planner->GetReason() << "\n";
    ok &= Check(std::string(planner->GetTranslucencyMethod()) == "multi-actor" &&
        std::string(planner->GetCullMethod()) == "none",
      tag + "translucency " + planner->GetTranslucencyMethod() + ", culling " +
        planner->GetCullMethod());
    auto* steps = vtkOrderedTranslucentPass::SafeDownCast(renderer->GetPass());
    auto* sorted = steps ? vtkBSPTranslucentPass::SafeDownCast(steps->GetTranslucentPass()) : nullptr;
    ok &= Check(sorted != nullptr, tag + "vtkBSPTranslucentPass under vtkOrderedTranslucentPass");
    if (!sorted)
      break;
    ok &= Check(sorted->GetNumberOfSortedActors() == 3, tag + "3 actors sorted");
    vtkNew<vtkPolyData> fragments;
    sorted->GetOrderedFragments(fragments);
    vtkCamera* camera = renderer->GetActiveCamera();
    const st::IdImage painter = st::RenderPainterIds(window, fragments, camera);
    const st::IdImage zbuffer = st::RenderVisibleIds(window, fragments, camera);
    const st::OrderComparison order = st::OrderMatchesDepth(painter, zbuffer);
    ok &= Check(order.matches && order.comparedPixels > 1000,
      tag + "painter == z-buffer over " + std::to_string(fragments->GetNumberOfCells()) +
        " fragments: " + order.Summary());
    ok &= LooksLikePeeling(planned, RenderWith(window, peelRenderer), tag);
  }
  ok &= Check(planner->GetPlanCount() == 1,
    "camera moves do not re-plan a small scene: " + std::to_string(planner->GetPlanCount()));

  // --- (b) opaque, then translucent again ------------------------------------------------------
  for (vtkActor* actor : { red, blue, green })
    actor->GetProperty()->SetOpacity(1.0);
  RenderWith(window, renderer);
  ok &= Check(std::string(planner->GetTranslucencyMethod()) == "none" &&
      renderer->GetPass() == nullptr,
    "all opaque: no pass (" + std::string(planner->GetTranslucencyReason()) + ")");
  red->GetProperty()->SetOpacity(0.4);
  blue->GetProperty()->SetOpacity(0.4);
  RenderWith(window, renderer);
  ok &= Check(std::string(planner->GetTranslucencyMethod()) == "multi-actor" &&
      vtkOrderedTranslucentPass::SafeDownCast(renderer->GetPass()),
    "two translucent again: the pass is back at once");
  ok &= Check(planner->GetPlanCount() == 3, "three plans: " + std::to_string(planner->GetPlanCount()));
  planner->SetRenderer(nullptr);
  ok &= Check(renderer->GetPass() == nullptr, "detached: no pass");

  // --- (c) one translucent mesh ---------------------------------------------------------------
  vtkNew<vtkDemoSceneSource> source;
  source->SetScene(vtkDemoSceneSource::SCENE_SPHERE_GRID);
  source->SetTriangleCount(20000);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> mesh;
  mesh->SetMapper(mapper);
  vtkNew<vtkRenderer> meshRenderer;
  meshRenderer->AddActor(mesh);
  vtkSmartPointer<vtkRenderer> meshPeel = PeelingRenderer(meshRenderer->GetActiveCamera());
  vtkNew<vtkPolyDataMapper> peelMapper;
  peelMapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> peelMesh;
  peelMesh->SetMapper(peelMapper);
  meshPeel->AddActor(peelMesh);
  planner->SetRenderer(meshRenderer);
  const double meshViews[][2] = { { 30, 20 }, { 125, -35 }, { 200, 60 } };
  v = 0;
  for (const auto& view : meshViews)
  {
    SetView(meshRenderer, view[0], view[1]);
    const std::string tag = "one mesh, view " + std::to_string(v++) + ": ";
    auto planned = RenderWith(window, meshRenderer);
    if (v == 1)
      std::cout << planner->GetReason() << "\n";
    auto* bsp = vtkBSPSortedPolyDataMapper::SafeDownCast(mesh->GetMapper());
    ok &= Check(std::string(planner->GetTranslucencyMethod()) == "bsp-mapper" && bsp &&
        bsp->GetInputConnection(0, 0) == mapper->GetInputConnection(0, 0) &&
        vtkOrderedTranslucentPass::SafeDownCast(meshRenderer->GetPass()) &&
        !vtkOrderedTranslucentPass::SafeDownCast(meshRenderer->GetPass())->GetTranslucentPass()->IsA(
          "vtkBSPTranslucentPass"),
      tag + "vtkBSPSortedPolyDataMapper on the application's input, plain ordered pass");
    ok &= LooksLikePeeling(planned, RenderWith(window, meshPeel), tag);
  }
  auto* bsp = vtkBSPSortedPolyDataMapper::SafeDownCast(mesh->GetMapper());
  ok &= Check(bsp && bsp->GetNumberOfTreeBuilds() == 1, "one BSP tree for all views");

  // --- (d) detaching --------------------------------------------------------------------------
  planner->SetRenderer(nullptr);
  ok &= Check(mesh->GetMapper() == mapper.Get() && meshRenderer->GetPass() == nullptr,
    "detached: the application's mapper back, no pass");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

// vtkBSPTranslucentPass: exact order across actors.
//  1. Two interpenetrating translucent actors of different colours (plus a slab cutting both),
//     several viewpoints incl. parallel projection: image vs dual depth peeling with 100 peels,
//     and the ordering oracle (painter's ID image of the pass's fragments in drawing order ==
//     z-buffer ID image).
//  2. The 64-actor sphere grid (one colour per actor) vs 100-peel depth peeling.
//  3. Work: camera unchanged -> no re-sort/upload; camera moved -> no rebuild; actor moved ->
//     one rebuild; opacity 1 -> the actor drops out; nothing translucent -> nothing sorted.
#include "vtkBSPTranslucentPass.h"
#include "vtkOrderedTranslucentPass.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkCamera.h>
#include <vtkCubeSource.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkSphereSource.h>
#include <vtkTriangleFilter.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
namespace st = scenevis::testing;

vtkSmartPointer<vtkImageData> RenderWith(vtkRenderWindow* window, vtkRenderer* renderer)
{
  window->GetRenderers()->RemoveAllItems();
  window->AddRenderer(renderer);
  renderer->ResetCameraClippingRange();
  return st::CaptureImage(window);
}

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}

void SetView(vtkRenderer* renderer, double azimuth, double elevation, bool parallel)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0, 1);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetParallelProjection(parallel);
  renderer->ResetCamera();
  camera->Azimuth(azimuth);
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
}

vtkSmartPointer<vtkActor> MakeActor(vtkAlgorithm* source, double r, double g, double b,
  double opacity)
{
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetOpacity(opacity);
  actor->GetProperty()->SetSpecular(0.0);
  return actor;
}
} // namespace

int TestBSPTranslucentPass(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(320, 320);

  // --- 1. Interpenetrating actors ---------------------------------------------------------
  vtkNew<vtkSphereSource> sphereA;
  sphereA->SetCenter(-0.3, 0, 0);
  sphereA->SetRadius(0.8);
  sphereA->SetThetaResolution(24);
  sphereA->SetPhiResolution(24);
  vtkNew<vtkSphereSource> sphereB;
  sphereB->SetCenter(0.35, 0.1, 0.1);
  sphereB->SetRadius(0.7);
  sphereB->SetThetaResolution(24);
  sphereB->SetPhiResolution(24);
  vtkNew<vtkCubeSource> slab;
  slab->SetXLength(2.6);
  slab->SetYLength(0.15);
  slab->SetZLength(1.6);
  vtkNew<vtkTriangleFilter> slabTriangles;
  slabTriangles->SetInputConnection(slab->GetOutputPort());

  auto red = MakeActor(sphereA, 1.0, 0.2, 0.1, 0.45);
  auto blue = MakeActor(sphereB, 0.1, 0.4, 1.0, 0.35);
  auto green = MakeActor(slab, 0.2, 1.0, 0.3, 0.5);
  green->SetOrientation(0, 0, 20);

  vtkNew<vtkRenderer> sortedRenderer;
  vtkNew<vtkRenderer> peelRenderer;
  for (vtkActor* actor : { red.Get(), blue.Get(), green.Get() })
  {
    sortedRenderer->AddActor(actor);
    peelRenderer->AddActor(actor);
  }
  vtkNew<vtkOrderedTranslucentPass> steps;
  vtkNew<vtkBSPTranslucentPass> bspPass;
  steps->SetTranslucentPass(bspPass);
  sortedRenderer->SetPass(steps);
  peelRenderer->SetUseDepthPeeling(1);
  peelRenderer->SetMaximumNumberOfPeels(100);
  peelRenderer->SetOcclusionRatio(0.0);
  peelRenderer->SetActiveCamera(sortedRenderer->GetActiveCamera());

  struct ViewSpec
  {
    double azimuth, elevation;
    bool parallel;
  };
  const ViewSpec views[] = { { 0, 0, false }, { 40, 25, false }, { 150, -30, false },
    { 250, 70, false }, { 100, 15, true } };
  int v = 0;
  for (const ViewSpec& spec : views)
  {
    SetView(sortedRenderer, spec.azimuth, spec.elevation, spec.parallel);
    const std::string tag = "two actors, view " + std::to_string(v) +
      (spec.parallel ? " (parallel)" : "");
    auto sorted = RenderWith(window, sortedRenderer);
    auto peeled = RenderWith(window, peelRenderer);
    st::WritePng(sorted, st::TemporaryDirectory() + "/TestBSPTranslucentPass_actors_" +
        std::to_string(v) + "_bsp.png");
    st::WritePng(peeled, st::TemporaryDirectory() + "/TestBSPTranslucentPass_actors_" +
        std::to_string(v) + "_peel100.png");
    st::ImageThresholds peel;
    peel.maxMeanAbsError = 0.5;
    peel.maxCoveredBadFraction = 0.01;
    std::string why;
    const auto difference = st::CompareImages(sorted, peeled);
    ok &= Check(st::WithinThresholds(difference, peel, &why),
      tag + ": pass vs 100-peel DDP: " + difference.Summary() + " " + why);
    ok &= Check(bspPass->GetNumberOfSortedActors() == 3, tag + ": 3 actors sorted");

    // Ordering oracle on the merged fragments, in the pass's drawing order.
    vtkNew<vtkPolyData> fragments;
    bspPass->GetOrderedFragments(fragments);
    vtkCamera* camera = sortedRenderer->GetActiveCamera();
    const st::IdImage painter = st::RenderPainterIds(window, fragments, camera);
    const st::IdImage zbuffer = st::RenderVisibleIds(window, fragments, camera);
    const st::OrderComparison order = st::OrderMatchesDepth(painter, zbuffer);
    ok &= Check(order.matches && order.comparedPixels > 1000,
      tag + ": painter == z-buffer over " + std::to_string(fragments->GetNumberOfCells()) +
        " fragments: " + order.Summary());
    ++v;
  }
  ok &= Check(bspPass->GetNumberOfTreeBuilds() == 1, "one tree for all views");
  ok &= Check(bspPass->GetNumberOfSplits() > 0, "actors split each other: " +
      std::to_string(bspPass->GetNumberOfSplits()) + " splits, " +
      std::to_string(bspPass->GetNumberOfDrawCalls()) + " draw calls");

  // --- 3. Only the work the scene calls for ------------------------------------------------
  RenderWith(window, sortedRenderer);
  const vtkIdType updates = bspPass->GetNumberOfOrderUpdates();
  const vtkIdType uploads = bspPass->GetNumberOfIndexUploads();
  window->Render();
  window->Render();
  ok &= Check(bspPass->GetNumberOfOrderUpdates() == updates &&
      bspPass->GetNumberOfIndexUploads() == uploads,
    "camera unchanged: no re-sort, no upload");
  sortedRenderer->GetActiveCamera()->Azimuth(60);
  window->Render();
  ok &= Check(bspPass->GetNumberOfOrderUpdates() == updates + 1 &&
      bspPass->GetNumberOfTreeBuilds() == 1,
    "camera moved: one order update, no rebuild");
  blue->SetPosition(0.1, 0, 0);
  window->Render();
  ok &= Check(bspPass->GetNumberOfTreeBuilds() == 2, "actor moved: tree rebuilt (" +
      std::to_string(bspPass->GetLastBuildTime() * 1e3) + " ms)");
  {
    // Still exact after the move.
    vtkNew<vtkPolyData> fragments;
    bspPass->GetOrderedFragments(fragments);
    vtkCamera* camera = sortedRenderer->GetActiveCamera();
    const st::OrderComparison order = st::OrderMatchesDepth(
      st::RenderPainterIds(window, fragments, camera), st::RenderVisibleIds(window, fragments, camera));
    ok &= Check(order.matches, "after the move: painter == z-buffer: " + order.Summary());
  }
  RenderWith(window, sortedRenderer);
  green->GetProperty()->SetOpacity(1.0);
  window->Render();
  ok &= Check(bspPass->GetNumberOfSortedActors() == 2 && bspPass->GetNumberOfTreeBuilds() == 3,
    "opacity 1: actor dropped out of the tree");
  red->GetProperty()->SetOpacity(1.0);
  blue->GetProperty()->SetOpacity(1.0);
  window->Render();
  ok &= Check(bspPass->GetNumberOfSortedActors() == 0 && bspPass->GetNumberOfFragments() == 0 &&
      bspPass->GetNumberOfTreeBuilds() == 3,
    "nothing translucent: nothing sorted");

  // --- 2. The 64-actor sphere grid ---------------------------------------------------------
  st::SphereGridOptions options;
  options.translucency = st::Translucency::OrderedAlpha;
  vtkSmartPointer<vtkRenderer> gridSorted = st::MakeSphereGridRenderer(options);
  vtkNew<vtkOrderedTranslucentPass> gridSteps;
  vtkNew<vtkBSPTranslucentPass> gridPass;
  gridSteps->SetTranslucentPass(gridPass);
  gridSorted->SetPass(gridSteps);
  options.translucency = st::Translucency::DepthPeeling;
  options.maximumPeels = 100;
  vtkSmartPointer<vtkRenderer> gridPeeled = st::MakeSphereGridRenderer(options);
  gridPeeled->SetActiveCamera(gridSorted->GetActiveCamera());
  const ViewSpec gridViews[] = { { 30, 20, false }, { 160, -40, false }, { 80, 10, true } };
  v = 0;
  for (const ViewSpec& spec : gridViews)
  {
    SetView(gridSorted, spec.azimuth, spec.elevation, spec.parallel);
    const std::string tag = "sphere grid, view " + std::to_string(v) +
      (spec.parallel ? " (parallel)" : "");
    auto sorted = RenderWith(window, gridSorted);
    auto peeled = RenderWith(window, gridPeeled);
    st::WritePng(sorted, st::TemporaryDirectory() + "/TestBSPTranslucentPass_grid_" +
        std::to_string(v) + "_bsp.png");
    st::WritePng(peeled, st::TemporaryDirectory() + "/TestBSPTranslucentPass_grid_" +
        std::to_string(v) + "_peel100.png");
    st::ImageThresholds peel;
    peel.maxMeanAbsError = 0.5;
    peel.maxCoveredBadFraction = 0.01;
    std::string why;
    const auto difference = st::CompareImages(sorted, peeled);
    ok &= Check(st::WithinThresholds(difference, peel, &why),
      tag + ": pass vs 100-peel DDP: " + difference.Summary() + " " + why + " (" +
        std::to_string(gridPass->GetNumberOfSortedActors()) + " actors, " +
        std::to_string(gridPass->GetNumberOfFragments()) + " fragments, " +
        std::to_string(gridPass->GetNumberOfDrawCalls()) + " draw calls)");
    ++v;
  }

  window->GetRenderers()->RemoveAllItems();
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

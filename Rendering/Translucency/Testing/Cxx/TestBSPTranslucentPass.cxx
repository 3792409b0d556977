// vtkBSPTranslucentPass: exact order across actors.
//  1. Two interpenetrating translucent actors of different colours (plus a slab cutting both),
//     several viewpoints incl. parallel projection: image vs dual depth peeling with 100 peels,
//     and the ordering oracle (painter's ID image of the pass's fragments in drawing order ==
//     z-buffer ID image).
//  2. The 64-actor sphere grid (one colour per actor) vs 100-peel depth peeling.
//  3. Work: camera unchanged -> no re-sort/upload; camera moved -> no rebuild; actor moved ->
//     one rebuild; opacity 1 -> the actor drops out; nothing translucent -> nothing sorted.
//  4. Batching: actors that differ only in colour/opacity (one of them coloured by point scalars
//     through a lookup table) are drawn by one helper (1 draw call) and look as when every
//     actor is drawn with its own property (batching off) and as 100-peel peeling; a colour or
//     opacity change re-bakes colours without a tree rebuild; actors with different specular
//     or lighting settings are not batched together and keep their own look.
//  4b. Parts coloured by cell scalars (as model readers and the tool's part splitting colour
//     them): actors whose cells all have one colour are batched (1 draw call) and look as per
//     actor and as peeling; an actor whose cell colours vary stays on its own.
//  5. Two-level order: instances of one input far apart and an interpenetrating trio, images vs
//     peeling and vs one tree, the order oracle, eyes outside, inside and parallel; trees built
//     when an instance moves (none), a trio member moves (one), an instance is added (none);
//     a flattened instance (scale 0) ordered in world coordinates.
//  6. Composite inputs (how ParaView's representations draw a surface): actors drawing a
//     one-block multiblock through vtkCompositePolyDataMapper2 are sorted like their polydata
//     (image vs 100-peel peeling); two visible blocks, or per-block opacities, leave an actor
//     unsorted; block visibilities that leave one block are followed.
//  7. Actor classes that draw a mapper of their own choosing (vtkLODActor, like ParaView's
//     vtkPVLODActor, ignores the mapper handed to Render): still drawn in the exact order.
//  8. A renderer with FXAA on: the pass anti-aliases as VTK's own geometry step does (image vs
//     peeling with FXAA; the pass without FXAA differs at the edges).
#include "vtkBSPTranslucentPass.h"
#include "vtkOrderedTranslucentPass.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCompositeDataDisplayAttributes.h>
#include <vtkCompositePolyDataMapper2.h>
#include <vtkCubeSource.h>
#include <vtkElevationFilter.h>
#include <vtkImageData.h>
#include <vtkLODActor.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkSphereSource.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>

#include <cstdlib>
#include <initializer_list>
#include <iostream>
#include <string>
#include <vector>

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

/// The same actors and camera in three renderers: the pass with batching, the pass without, and
/// 100-peel dual depth peeling (the reference).
struct BatchingRenderers
{
  vtkNew<vtkRenderer> batched, unbatched, peeled;
  vtkNew<vtkOrderedTranslucentPass> batchedSteps, unbatchedSteps;
  vtkNew<vtkBSPTranslucentPass> batchedPass, unbatchedPass;

  explicit BatchingRenderers(std::initializer_list<vtkActor*> actors)
  {
    for (vtkActor* actor : actors)
    {
      this->batched->AddActor(actor);
      this->unbatched->AddActor(actor);
      this->peeled->AddActor(actor);
    }
    this->unbatchedPass->BatchingOff();
    this->batchedSteps->SetTranslucentPass(this->batchedPass);
    this->unbatchedSteps->SetTranslucentPass(this->unbatchedPass);
    this->batched->SetPass(this->batchedSteps);
    this->unbatched->SetPass(this->unbatchedSteps);
    this->peeled->SetUseDepthPeeling(1);
    this->peeled->SetMaximumNumberOfPeels(100);
    this->peeled->SetOcclusionRatio(0.0);
    this->unbatched->SetActiveCamera(this->batched->GetActiveCamera());
    this->peeled->SetActiveCamera(this->batched->GetActiveCamera());
  }
};

} // namespace

int TestBSPTranslucentPass(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(320, 320);

  // --- 1. Interpenetrating actors ---------------------------------------------------------
  const st::InterpenetratingActors scene = st::MakeInterpenetratingActors();
  vtkSphereSource* sphereA = scene.sphereA;
  vtkSphereSource* sphereB = scene.sphereB;
  vtkTriangleFilter* slabTriangles = scene.slabTriangles;
  vtkActor* red = scene.red;
  vtkActor* blue = scene.blue;
  vtkActor* green = scene.green;

  vtkNew<vtkRenderer> sortedRenderer;
  vtkNew<vtkRenderer> peelRenderer;
  for (vtkActor* actor : { red, blue, green })
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
    const std::string tag =
      "two actors, view " + std::to_string(v) + (spec.parallel ? " (parallel)" : "");
    auto sorted = RenderWith(window, sortedRenderer);
    auto peeled = RenderWith(window, peelRenderer);
    st::WritePng(sorted,
      st::TemporaryDirectory() + "/TestBSPTranslucentPass_actors_" + std::to_string(v) +
        "_bsp.png");
    st::WritePng(peeled,
      st::TemporaryDirectory() + "/TestBSPTranslucentPass_actors_" + std::to_string(v) +
        "_peel100.png");
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
  ok &= Check(bspPass->GetNumberOfSplits() > 0,
    "actors split each other: " + std::to_string(bspPass->GetNumberOfSplits()) + " splits, " +
      std::to_string(bspPass->GetNumberOfDrawCalls()) + " draw calls");

  // --- 3. Only the work the scene calls for ------------------------------------------------
  RenderWith(window, sortedRenderer);
  const vtkIdType updates = bspPass->GetNumberOfOrderUpdates();
  const vtkIdType uploads = bspPass->GetNumberOfIndexUploads();
  window->Render();
  window->Render();
  ok &= Check(
    bspPass->GetNumberOfOrderUpdates() == updates && bspPass->GetNumberOfIndexUploads() == uploads,
    "camera unchanged: no re-sort, no upload");
  sortedRenderer->GetActiveCamera()->Azimuth(60);
  window->Render();
  ok &= Check(
    bspPass->GetNumberOfOrderUpdates() == updates + 1 && bspPass->GetNumberOfTreeBuilds() == 1,
    "camera moved: one order update, no rebuild");
  blue->SetPosition(0.1, 0, 0);
  window->Render();
  ok &= Check(bspPass->GetNumberOfTreeBuilds() == 2,
    "actor moved: tree rebuilt (" + std::to_string(bspPass->GetLastBuildTime() * 1e3) + " ms)");
  {
    // Still exact after the move.
    vtkNew<vtkPolyData> fragments;
    bspPass->GetOrderedFragments(fragments);
    vtkCamera* camera = sortedRenderer->GetActiveCamera();
    const st::OrderComparison order =
      st::OrderMatchesDepth(st::RenderPainterIds(window, fragments, camera),
        st::RenderVisibleIds(window, fragments, camera));
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
    const std::string tag =
      "sphere grid, view " + std::to_string(v) + (spec.parallel ? " (parallel)" : "");
    auto sorted = RenderWith(window, gridSorted);
    auto peeled = RenderWith(window, gridPeeled);
    st::WritePng(sorted,
      st::TemporaryDirectory() + "/TestBSPTranslucentPass_grid_" + std::to_string(v) + "_bsp.png");
    st::WritePng(peeled,
      st::TemporaryDirectory() + "/TestBSPTranslucentPass_grid_" + std::to_string(v) +
        "_peel100.png");
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

  // --- 4. Batching ------------------------------------------------------------------------
  {
    vtkNew<vtkElevationFilter> elevation;
    elevation->SetInputConnection(sphereB->GetOutputPort());
    elevation->SetLowPoint(0, -0.6, 0);
    elevation->SetHighPoint(0, 0.8, 0);
    auto plain = st::MakeTranslucentActor(sphereA, 1.0, 0.2, 0.1, 0.45);
    auto scalars = st::MakeTranslucentActor(elevation, 1.0, 1.0, 1.0, 0.4);
    scalars->GetMapper()->ScalarVisibilityOn();
    scalars->GetMapper()->SetScalarRange(0.0, 1.0);
    auto slabActor = st::MakeTranslucentActor(slabTriangles, 0.2, 1.0, 0.3, 0.5);
    slabActor->SetOrientation(0, 0, -25);
    slabActor->SetPosition(0, 0.2, 0);

    BatchingRenderers renderers({ plain.Get(), scalars.Get(), slabActor.Get() });
    vtkRenderer* batched = renderers.batched;
    vtkRenderer* unbatched = renderers.unbatched;
    vtkRenderer* peeled = renderers.peeled;
    vtkBSPTranslucentPass* batchedPass = renderers.batchedPass;
    vtkBSPTranslucentPass* unbatchedPass = renderers.unbatchedPass;

    // Batched image == per-actor image (== peeling reference while nothing is specular: VTK's
    // peeling blends specular highlights differently from alpha blending, measured here at
    // 0.3-0.8/255 mean and 4-7% of pixels off for the per-actor path itself). Same tolerances
    // as above.
    auto compareAll = [&](const std::string& tag, bool withPeel)
    {
      auto withBatches = RenderWith(window, batched);
      auto perActor = RenderWith(window, unbatched);
      auto reference = withPeel ? RenderWith(window, peeled) : nullptr;
      st::WritePng(withBatches,
        st::TemporaryDirectory() + "/TestBSPTranslucentPass_batch_" + tag + "_batched.png");
      st::WritePng(perActor,
        st::TemporaryDirectory() + "/TestBSPTranslucentPass_batch_" + tag + "_per_actor.png");
      st::ImageThresholds thresholds;
      thresholds.maxMeanAbsError = 0.5;
      thresholds.maxCoveredBadFraction = 0.01;
      std::string why;
      const auto vsPerActor = st::CompareImages(withBatches, perActor);
      bool same = Check(st::WithinThresholds(vsPerActor, thresholds, &why),
        tag + ": batched vs per-actor: " + vsPerActor.Summary() + " " + why);
      if (!withPeel)
      {
        return same;
      }
      const auto vsPeel = st::CompareImages(withBatches, reference);
      same &= Check(st::WithinThresholds(vsPeel, thresholds, &why),
        tag + ": batched vs 100-peel DDP: " + vsPeel.Summary() + " " + why);
      return same;
    };
    auto describe = [](vtkBSPTranslucentPass* pass)
    {
      return std::to_string(pass->GetNumberOfBatchGroups()) + " batch group(s) of " +
        std::to_string(pass->GetNumberOfBatchedActors()) + " actors, " +
        std::to_string(pass->GetNumberOfDrawCalls()) + " draw calls";
    };

    const ViewSpec batchViews[] = { { 20, 15, false }, { 200, -35, false }, { 70, 40, true } };
    v = 0;
    for (const ViewSpec& spec : batchViews)
    {
      SetView(batched, spec.azimuth, spec.elevation, spec.parallel);
      const std::string tag = "compatible_" + std::to_string(v++);
      ok &= compareAll(tag, true);
      ok &= Check(batchedPass->GetNumberOfBatchGroups() == 1 &&
          batchedPass->GetNumberOfBatchedActors() == 3 && batchedPass->GetNumberOfDrawCalls() == 1,
        tag + ": one batch, one draw call: " + describe(batchedPass) +
          " (per actor: " + std::to_string(unbatchedPass->GetNumberOfDrawCalls()) + " draw calls)");
      ok &= Check(
        unbatchedPass->GetNumberOfBatchGroups() == 0 && unbatchedPass->GetNumberOfDrawCalls() > 3,
        tag + ": batching off: every actor on its own");
    }

    // Colour and opacity changes are baked again; the tree stays.
    const vtkIdType builds = batchedPass->GetNumberOfTreeBuilds();
    const vtkIdType bakes = batchedPass->GetNumberOfColorBakes();
    plain->GetProperty()->SetColor(0.9, 0.8, 0.1);
    scalars->GetProperty()->SetOpacity(0.6);
    ok &= compareAll("recoloured", true);
    ok &= Check(batchedPass->GetNumberOfTreeBuilds() == builds &&
        batchedPass->GetNumberOfColorBakes() == bakes + 1,
      "colour/opacity changed: colours baked again, no tree rebuild");
    window->Render();
    ok &= Check(batchedPass->GetNumberOfColorBakes() == bakes + 1, "unchanged: no bake");

    // Different specular or lighting settings: not batched together, each keeps its own look
    // (a wrongly shared property would lose the highlight or the shading and fail the images).
    plain->GetProperty()->SetSpecular(0.8);
    plain->GetProperty()->SetSpecularPower(20);
    slabActor->GetProperty()->LightingOff();
    for (const ViewSpec& spec : { batchViews[0], batchViews[1] })
    {
      SetView(batched, spec.azimuth, spec.elevation, spec.parallel);
      const std::string tag = "incompatible_" + std::to_string(v++);
      ok &= compareAll(tag, false);
      ok &= Check(batchedPass->GetNumberOfBatchGroups() == 0 &&
          batchedPass->GetNumberOfDrawCalls() == unbatchedPass->GetNumberOfDrawCalls(),
        tag + ": nothing batched: " + describe(batchedPass));
    }
    // Two of three compatible again: a batch of two plus one actor on its own.
    slabActor->GetProperty()->LightingOn();
    slabActor->GetProperty()->SetSpecular(0.8);
    slabActor->GetProperty()->SetSpecularPower(20);
    plain->GetProperty()->SetSpecularColor(1, 1, 1);
    slabActor->GetProperty()->SetSpecularColor(1, 1, 1);
    ok &= compareAll("mixed", false);
    ok &= Check(
      batchedPass->GetNumberOfBatchGroups() == 1 && batchedPass->GetNumberOfBatchedActors() == 2,
      "mixed: one batch of two, one actor alone: " + describe(batchedPass));

    // Opacity 1: drops out of its batch and of the tree.
    slabActor->GetProperty()->SetOpacity(1.0);
    ok &= compareAll("opaque_slab", false);
    ok &= Check(
      batchedPass->GetNumberOfSortedActors() == 2 && batchedPass->GetNumberOfBatchGroups() == 0,
      "opacity 1: dropped out: " + describe(batchedPass));
  }

  // --- 4b. Uniform cell colours ---------------------------------------------------------------
  {
    // A copy of @p source's output with an RGBA cell array "Colors"; with @p vary, half of the
    // cells get another colour.
    auto cellColoured = [](vtkAlgorithm* source, const unsigned char rgba[4], bool vary)
    {
      source->Update();
      auto pd = vtkSmartPointer<vtkPolyData>::New();
      pd->DeepCopy(vtkPolyData::SafeDownCast(source->GetOutputDataObject(0)));
      vtkNew<vtkUnsignedCharArray> colors;
      colors->SetName("Colors");
      colors->SetNumberOfComponents(4);
      colors->SetNumberOfTuples(pd->GetNumberOfCells());
      for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
      {
        const unsigned char other[4] = { 40, 40, 230, rgba[3] };
        colors->SetTypedTuple(c, vary && c % 2 == 1 ? other : rgba);
      }
      pd->GetCellData()->SetScalars(colors);
      return pd;
    };
    auto cellActor = [](vtkPolyData* pd)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(pd);
      mapper->SetScalarModeToUseCellData();
      mapper->SetColorModeToDirectScalars();
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->GetProperty()->SetSpecular(0.0);
      return actor;
    };
    const unsigned char red[4] = { 230, 50, 25, 115 };
    const unsigned char green[4] = { 50, 230, 80, 100 };
    const unsigned char yellow[4] = { 230, 220, 40, 128 };
    auto a = cellActor(cellColoured(sphereA, red, false));
    auto b = cellActor(cellColoured(sphereB, green, false));
    vtkSmartPointer<vtkPolyData> slabUniform = cellColoured(slabTriangles, yellow, false);
    vtkSmartPointer<vtkPolyData> slabVarying = cellColoured(slabTriangles, yellow, true);
    auto c = cellActor(slabUniform);
    c->SetOrientation(0, 0, -25);
    c->SetPosition(0, 0.2, 0);

    BatchingRenderers renderers({ a.Get(), b.Get(), c.Get() });
    const st::ImageThresholds thresholds = st::Thresholds(0.5, 0.01);
    auto check = [&](const std::string& tag, int groups, int batchedActors)
    {
      auto withBatches = RenderWith(window, renderers.batched);
      auto perActor = RenderWith(window, renderers.unbatched);
      auto reference = RenderWith(window, renderers.peeled);
      st::WritePng(withBatches,
        st::TemporaryDirectory() + "/TestBSPTranslucentPass_cells_" + tag + "_batched.png");
      std::string why;
      const auto vsPerActor = st::CompareImages(withBatches, perActor);
      const auto vsPeel = st::CompareImages(withBatches, reference);
      bool good = Check(st::WithinThresholds(vsPerActor, thresholds, &why),
        tag + ": batched vs per-actor: " + vsPerActor.Summary() + " " + why);
      good &= Check(st::WithinThresholds(vsPeel, thresholds, &why),
        tag + ": batched vs 100-peel DDP: " + vsPeel.Summary() + " " + why);
      good &= Check(st::CoveredFraction(withBatches) > 0.1 &&
          renderers.batchedPass->GetNumberOfBatchGroups() == groups &&
          renderers.batchedPass->GetNumberOfBatchedActors() == batchedActors,
        tag + ": " + std::to_string(renderers.batchedPass->GetNumberOfBatchGroups()) +
          " batch group(s) of " +
          std::to_string(renderers.batchedPass->GetNumberOfBatchedActors()) + " actors, " +
          std::to_string(renderers.batchedPass->GetNumberOfDrawCalls()) +
          " draw calls (per actor: " +
          std::to_string(renderers.unbatchedPass->GetNumberOfDrawCalls()) + ")");
      return good;
    };
    const ViewSpec cellViews[] = { { 30, 20, false }, { 160, -30, true } };
    v = 0;
    for (const ViewSpec& spec : cellViews)
    {
      SetView(renderers.batched, spec.azimuth, spec.elevation, spec.parallel);
      const std::string tag = "uniform_" + std::to_string(v++);
      ok &= check(tag, 1, 3);
      ok &= Check(renderers.batchedPass->GetNumberOfDrawCalls() == 1, tag + ": one draw call");
    }
    // The slab's cells in two colours: it leaves the batch, which keeps the two spheres.
    vtkPolyDataMapper::SafeDownCast(c->GetMapper())->SetInputData(slabVarying);
    ok &= check("varying", 1, 2);
  }

  // --- 5. Two-level order -----------------------------------------------------------------
  {
    // Four instances of one sphere input (turned, one mirrored, one scaled unevenly), far from
    // each other and from the interpenetrating trio of section 1: the instances are ordered as
    // wholes through one tree of their shared input; the trio shares one tree.
    red->GetProperty()->SetOpacity(0.45);
    blue->GetProperty()->SetOpacity(0.45);
    green->GetProperty()->SetOpacity(0.5);
    blue->SetPosition(0, 0, 0);
    // The instanced input is not convex (a ball with a smaller one inside, off centre), so a
    // wrong order inside an instance shows in the images and the oracle.
    vtkNew<vtkSphereSource> outer;
    outer->SetThetaResolution(24);
    outer->SetPhiResolution(16);
    outer->SetRadius(0.8);
    vtkNew<vtkSphereSource> inner;
    inner->SetThetaResolution(16);
    inner->SetPhiResolution(12);
    inner->SetRadius(0.35);
    inner->SetCenter(0.2, 0.1, 0.0);
    vtkNew<vtkAppendPolyData> ball;
    ball->AddInputConnection(outer->GetOutputPort());
    ball->AddInputConnection(inner->GetOutputPort());
    std::vector<vtkSmartPointer<vtkActor>> instances;
    const double places[4][3] = { { 3, 0, 0 }, { -3, 0.5, 0 }, { 0, 3, -1 }, { 0, -3, 1 } };
    for (int i = 0; i < 4; ++i)
    {
      instances.push_back(st::MakeTranslucentActor(ball, 0.2 + 0.2 * i, 0.9 - 0.2 * i, 0.5, 0.4));
      instances.back()->SetPosition(places[i][0], places[i][1], places[i][2]);
      instances.back()->SetOrientation(20.0 * i, 35.0 * i, 0);
    }
    instances[1]->SetScale(-1, 1, 1);
    instances[2]->SetScale(1.4, 0.6, 1);

    vtkNew<vtkRenderer> twoLevels;
    vtkNew<vtkRenderer> oneLevel;
    vtkNew<vtkRenderer> peeled;
    std::vector<vtkActor*> all{ red, blue, green };
    for (auto& instance : instances)
    {
      all.push_back(instance);
    }
    for (vtkActor* actor : all)
    {
      twoLevels->AddActor(actor);
      oneLevel->AddActor(actor);
      peeled->AddActor(actor);
    }
    vtkNew<vtkOrderedTranslucentPass> twoSteps;
    vtkNew<vtkBSPTranslucentPass> twoPass; // two levels: the default
    twoSteps->SetTranslucentPass(twoPass);
    twoLevels->SetPass(twoSteps);
    vtkNew<vtkOrderedTranslucentPass> oneSteps;
    vtkNew<vtkBSPTranslucentPass> onePass;
    onePass->TwoLevelOrderOff();
    oneSteps->SetTranslucentPass(onePass);
    oneLevel->SetPass(oneSteps);
    peeled->SetUseDepthPeeling(1);
    peeled->SetMaximumNumberOfPeels(100);
    peeled->SetOcclusionRatio(0.0);
    oneLevel->SetActiveCamera(twoLevels->GetActiveCamera());
    peeled->SetActiveCamera(twoLevels->GetActiveCamera());

    // The image against peeling and against one tree over everything, and the order oracle.
    // (withPeel false: coplanar overlapping polygons, whose order no method fixes.)
    auto checkView = [&](const std::string& tag, bool withPeel = true)
    {
      auto two = RenderWith(window, twoLevels);
      auto one = RenderWith(window, oneLevel);
      auto reference = RenderWith(window, peeled);
      st::WritePng(
        two, st::TemporaryDirectory() + "/TestBSPTranslucentPass_two_levels_" + tag + ".png");
      st::ImageThresholds thresholds;
      thresholds.maxMeanAbsError = 0.5;
      thresholds.maxCoveredBadFraction = 0.01;
      std::string why;
      bool good = true;
      const auto vsPeel = st::CompareImages(two, reference);
      good &= Check(!withPeel || st::WithinThresholds(vsPeel, thresholds, &why),
        tag + ": two levels vs 100-peel DDP: " + vsPeel.Summary() + " " + why);
      const auto vsOne = st::CompareImages(two, one);
      good &= Check(st::WithinThresholds(vsOne, thresholds, &why),
        tag + ": two levels vs one tree: " + vsOne.Summary() + " " + why);
      RenderWith(window, twoLevels);
      vtkNew<vtkPolyData> fragments;
      twoPass->GetOrderedFragments(fragments);
      vtkCamera* camera = twoLevels->GetActiveCamera();
      const st::OrderComparison order =
        st::OrderMatchesDepth(st::RenderPainterIds(window, fragments, camera),
          st::RenderVisibleIds(window, fragments, camera));
      good &= Check(order.matches && order.comparedPixels > 1000,
        tag + ": painter == z-buffer over " + std::to_string(fragments->GetNumberOfCells()) +
          " fragments: " + order.Summary());
      return good;
    };
    const ViewSpec twoViews[] = { { 10, 20, false }, { 130, -40, false }, { 260, 60, false },
      { 60, 10, true } };
    v = 0;
    for (const ViewSpec& spec : twoViews)
    {
      SetView(twoLevels, spec.azimuth, spec.elevation, spec.parallel);
      ok &= checkView("view_" + std::to_string(v++));
    }
    ok &= Check(twoPass->GetNumberOfPartGroups() == 5,
      "4 instances alone, the trio together: " + std::to_string(twoPass->GetNumberOfPartGroups()) +
        " groups");
    ok &= Check(twoPass->GetNumberOfTreeBuilds() == 1 && twoPass->GetLastBuildTreeCount() == 2,
      "one tree for the four instances' input, one for the trio: " +
        std::to_string(twoPass->GetLastBuildTreeCount()) + " trees");
    ok &= Check(twoPass->GetNumberOfSplits() <= onePass->GetNumberOfSplits(),
      "no more splits than one tree: " + std::to_string(twoPass->GetNumberOfSplits()) + " vs " +
        std::to_string(onePass->GetNumberOfSplits()));

    // An eye between the instances, inside the scene (VTK's culler drops the actors behind it,
    // so the pass sees fewer of them), then the first view again for the counts below.
    vtkCamera* camera = twoLevels->GetActiveCamera();
    camera->SetParallelProjection(false);
    camera->SetPosition(1.6, 1.7, 0.4);
    camera->SetFocalPoint(-3, -2, 0);
    camera->SetViewUp(0, 0, 1);
    ok &= checkView("inside");
    SetView(twoLevels, twoViews[0].azimuth, twoViews[0].elevation, twoViews[0].parallel);
    ok &= checkView("view_0_again");

    const vtkIdType buildsBefore = twoPass->GetNumberOfTreeBuilds();
    // An instance moves: the top level is built again, no BSP tree.
    instances[0]->SetPosition(3.5, 0.5, 0.2);
    ok &= checkView("instance_moved");
    ok &= Check(
      twoPass->GetNumberOfTreeBuilds() == buildsBefore + 1 && twoPass->GetLastBuildTreeCount() == 0,
      "an instance moved: no BSP tree built (" + std::to_string(twoPass->GetLastBuildTime() * 1e3) +
        " ms; one tree over everything: " + std::to_string(onePass->GetLastBuildTime() * 1e3) +
        " ms)");
    // A member of the trio moves: only the trio's tree.
    blue->SetPosition(0.05, 0, 0);
    ok &= checkView("trio_moved");
    ok &= Check(twoPass->GetLastBuildTreeCount() == 1, "a trio member moved: one tree built");
    // A fifth instance, and the instances drawn each with its own helper (batching off).
    instances.push_back(st::MakeTranslucentActor(ball, 0.9, 0.9, 0.2, 0.5));
    instances.back()->SetPosition(0, 0, 3);
    twoLevels->AddActor(instances.back());
    oneLevel->AddActor(instances.back());
    peeled->AddActor(instances.back());
    twoPass->BatchingOff();
    ok &= checkView("fifth_instance_unbatched");
    ok &= Check(twoPass->GetNumberOfPartGroups() == 6 && twoPass->GetLastBuildTreeCount() == 0,
      "a new instance of a known input: no tree built");
    // A flattened instance (scale 0 along y: no model frame) is ordered in world coordinates.
    instances.push_back(st::MakeTranslucentActor(ball, 0.3, 0.9, 0.9, 0.5));
    instances.back()->SetPosition(-3, -3, 0);
    instances.back()->SetScale(1, 0, 1);
    instances.back()->SetOrientation(30, 0, 0);
    twoLevels->AddActor(instances.back());
    oneLevel->AddActor(instances.back());
    peeled->AddActor(instances.back());
    ok &= checkView("flattened_instance", false); // a flat sphere: coplanar overlapping faces
    ok &= Check(twoPass->GetNumberOfPartGroups() == 7 && twoPass->GetLastBuildTreeCount() == 1,
      "a flattened instance: one tree of its own, in world coordinates");
    // Back to one level: the same pass builds one tree again.
    twoPass->TwoLevelOrderOff();
    ok &= checkView("back_to_one_level", false);
    ok &= Check(twoPass->GetNumberOfPartGroups() == 0 && twoPass->GetLastBuildTreeCount() == 1,
      "two levels off: one tree");
  }

  // --- 6. Composite inputs ----------------------------------------------------------------
  {
    // The two spheres and the slab of section 1, each as a one-block multiblock.
    std::vector<vtkSmartPointer<vtkActor>> actors;
    std::vector<vtkSmartPointer<vtkCompositePolyDataMapper2>> mappers;
    vtkNew<vtkRenderer> composite;
    vtkNew<vtkRenderer> peeled;
    for (vtkActor* original : { red, blue, green })
    {
      original->GetMapper()->Update();
      auto* input = vtkPolyData::SafeDownCast(original->GetMapper()->GetInputDataObject(0, 0));
      vtkNew<vtkMultiBlockDataSet> blocks;
      blocks->SetNumberOfBlocks(1);
      blocks->SetBlock(0, input);
      auto mapper = vtkSmartPointer<vtkCompositePolyDataMapper2>::New();
      mapper->SetInputDataObject(blocks);
      mapper->ScalarVisibilityOff();
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->SetProperty(original->GetProperty());
      composite->AddActor(actor);
      peeled->AddActor(actor);
      actors.push_back(actor);
      mappers.push_back(mapper);
    }
    vtkNew<vtkOrderedTranslucentPass> compositeSteps;
    vtkNew<vtkBSPTranslucentPass> compositePass;
    compositeSteps->SetTranslucentPass(compositePass);
    composite->SetPass(compositeSteps);
    peeled->SetUseDepthPeeling(1);
    peeled->SetMaximumNumberOfPeels(100);
    peeled->SetOcclusionRatio(0.0);
    peeled->SetActiveCamera(composite->GetActiveCamera());
    SetView(composite, 40, 25, false);
    auto sorted = RenderWith(window, composite);
    auto reference = RenderWith(window, peeled);
    st::ImageThresholds peel;
    peel.maxMeanAbsError = 0.5;
    peel.maxCoveredBadFraction = 0.01;
    std::string why;
    ok &= Check(compositePass->GetNumberOfSortedActors() == 3,
      "composite: three one-block actors sorted (" +
        std::to_string(compositePass->GetNumberOfSortedActors()) + ")");
    ok &= Check(st::WithinThresholds(st::CompareImages(sorted, reference), peel, &why),
      "composite: image vs 100-peel peeling " + why);
    // A second block, and per-block opacity: those actors are drawn unsorted.
    vtkNew<vtkMultiBlockDataSet> twoBlocks;
    twoBlocks->SetNumberOfBlocks(2);
    twoBlocks->SetBlock(0, sphereA->GetOutput());
    twoBlocks->SetBlock(1, sphereB->GetOutput());
    mappers[0]->SetInputDataObject(twoBlocks);
    vtkNew<vtkCompositeDataDisplayAttributes> attributes;
    attributes->SetBlockOpacity(sphereB->GetOutput(), 0.5);
    mappers[1]->SetCompositeDataDisplayAttributes(attributes);
    RenderWith(window, composite);
    ok &= Check(compositePass->GetNumberOfSortedActors() == 1,
      "composite: two blocks, or a block opacity, leave the actor unsorted (" +
        std::to_string(compositePass->GetNumberOfSortedActors()) + " sorted)");
    // Block visibilities, as ParaView sets them: the one visible block is sorted.
    vtkNew<vtkCompositeDataDisplayAttributes> visibilities;
    visibilities->SetBlockVisibility(twoBlocks, true);
    visibilities->SetBlockVisibility(sphereB->GetOutput(), false);
    mappers[0]->SetCompositeDataDisplayAttributes(visibilities);
    mappers[1]->SetCompositeDataDisplayAttributes(nullptr);
    sorted = RenderWith(window, composite);
    ok &= Check(compositePass->GetNumberOfSortedActors() == 3,
      "composite: two blocks of which one is visible, sorted (" +
        std::to_string(compositePass->GetNumberOfSortedActors()) + " sorted)");
  }

  // --- 7. An actor that picks its own mapper -----------------------------------------------
  {
    // vtkLODActor copies its mapper into its own LOD mappers with vtkOpenGLPolyDataMapper's
    // ShallowCopy, which warns about the deprecated shader-code accessors it copies.
    vtkOutput.AllowWarning("was deprecated for VTK 9.0");
    vtkNew<vtkRenderer> lod;
    vtkNew<vtkRenderer> peeled;
    std::vector<vtkSmartPointer<vtkLODActor>> actors;
    for (vtkActor* original : { red, blue, green })
    {
      auto actor = vtkSmartPointer<vtkLODActor>::New();
      actor->SetMapper(original->GetMapper());
      actor->SetProperty(original->GetProperty());
      lod->AddActor(actor);
      peeled->AddActor(actor);
      actors.push_back(actor);
    }
    vtkNew<vtkOrderedTranslucentPass> lodSteps;
    vtkNew<vtkBSPTranslucentPass> lodPass;
    lodPass->BatchingOff(); // a batch is drawn by the pass's own actor: each by its own here
    lodSteps->SetTranslucentPass(lodPass);
    lod->SetPass(lodSteps);
    vtkNew<vtkRenderer> unsorted; // actor order, no sorting: what the LOD actors draw alone
    for (auto& actor : actors)
    {
      unsorted->AddActor(actor);
    }
    vtkNew<vtkOrderedTranslucentPass> plainSteps;
    unsorted->SetPass(plainSteps);
    unsorted->SetActiveCamera(lod->GetActiveCamera());
    peeled->SetUseDepthPeeling(1);
    peeled->SetMaximumNumberOfPeels(100);
    peeled->SetOcclusionRatio(0.0);
    peeled->SetActiveCamera(lod->GetActiveCamera());
    st::ImageThresholds peel;
    peel.maxMeanAbsError = 0.5;
    peel.maxCoveredBadFraction = 0.01;
    int discriminating = 0;
    for (double azimuth : { 0.0, 40.0, 150.0, 250.0 })
    {
      SetView(lod, azimuth, 25, false);
      auto sorted = RenderWith(window, lod);
      auto reference = RenderWith(window, peeled);
      auto plain = RenderWith(window, unsorted);
      std::string why;
      ok &= Check(lodPass->GetNumberOfSortedActors() == 3 &&
          st::WithinThresholds(st::CompareImages(sorted, reference), peel, &why),
        "vtkLODActor, azimuth " + std::to_string(int(azimuth)) +
          ": sorted, image vs 100-peel peeling " + why);
      discriminating += st::WithinThresholds(st::CompareImages(plain, reference), peel) ? 0 : 1;
    }
    ok &= Check(discriminating > 0,
      "vtkLODActor: the same actors unsorted differ from peeling in " +
        std::to_string(discriminating) + " of 4 views (the check can fail)");
  }

  // --- 8. The renderer's FXAA -----------------------------------------------------------------
  // A renderer with FXAA on (ParaView's views have it) anti-aliases after its translucent
  // geometry, before volumes and overlays; a render pass replaces that step, so the ordered pass
  // applies it itself. Reference: 100-peel peeling with FXAA, by VTK's own geometry step.
  {
    vtkNew<vtkRenderer> withFxaa, withoutFxaa, peeled;
    vtkNew<vtkOrderedTranslucentPass> stepsOn, stepsOff;
    vtkNew<vtkBSPTranslucentPass> passOn, passOff;
    stepsOn->SetTranslucentPass(passOn);
    stepsOff->SetTranslucentPass(passOff);
    withFxaa->SetPass(stepsOn);
    withoutFxaa->SetPass(stepsOff);
    for (vtkRenderer* r : { withFxaa.Get(), withoutFxaa.Get(), peeled.Get() })
    {
      for (vtkActor* actor : { red, blue, green })
      {
        r->AddActor(actor);
      }
    }
    withFxaa->UseFXAAOn();
    peeled->UseFXAAOn();
    peeled->SetUseDepthPeeling(1);
    peeled->SetMaximumNumberOfPeels(100);
    peeled->SetOcclusionRatio(0.0);
    withoutFxaa->SetActiveCamera(withFxaa->GetActiveCamera());
    peeled->SetActiveCamera(withFxaa->GetActiveCamera());
    SetView(withFxaa, 40, 25, false);
    auto on = RenderWith(window, withFxaa);
    auto off = RenderWith(window, withoutFxaa);
    auto reference = RenderWith(window, peeled);
    const auto onDifference = st::CompareImages(on, reference);
    const auto offDifference = st::CompareImages(off, reference);
    std::string why;
    ok &= Check(st::WithinThresholds(onDifference, st::Thresholds(0.5, 0.0002), &why),
      "FXAA on: pass vs 100-peel peeling with FXAA: " + onDifference.Summary() + " " + why);
    ok &= Check(offDifference.badCoveredPixels > 10 * (onDifference.badCoveredPixels + 1),
      "FXAA off in the pass: its edges differ (the check can fail): " + offDifference.Summary());
  }

  window->GetRenderers()->RemoveAllItems();
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

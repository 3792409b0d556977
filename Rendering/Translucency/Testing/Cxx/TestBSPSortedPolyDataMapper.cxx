// vtkBSPSortedPolyDataMapper on the 4x4x4 translucent sphere grid (one merged mesh, RGBA cell
// colours), from several cameras incl. parallel projection:
//  (a) same image as vtkBSPSortFilter + vtkPolyDataMapper (same exact order, near-identical);
//  (b) within 0.5/255 mean error of dual depth peeling with 100 peels;
//  (c) camera unchanged -> no re-sort, no index upload; camera moved -> no vertex buffer rebuild;
//      fragments whose cells have the same colour share vertices;
//  (e) small camera steps send only the changed index ranges, and draw what a full upload draws;
//  (d) an opaque actor builds no tree at all; one that turned translucent and then opaque again
//      draws its input (not the split fragments) and keeps its tree;
//  (g) cell normals without point normals: the filter's image, vertices shared within a cell;
//  (f) with ordered leaves (a bumpy sphere): the order of vtkBSPSortFilter with the same leaf size,
//  fewer
//      fragments drawn than the tree without leaves has, and the 100-peel image.
#include "vtkBSPSortFilter.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"

#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkSphereSource.h>

#include <algorithm>
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

/// A renderer drawing @p mapper in one orange at opacity 0.4 with @p camera: ordered alpha
/// blending (vtkOrderedTranslucentPass), or 100-peel dual depth peeling if @p peel.
vtkSmartPointer<vtkRenderer> TranslucentRenderer(vtkMapper* mapper, vtkCamera* camera, bool peel)
{
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetOpacity(0.4);
  actor->GetProperty()->SetColor(0.9, 0.5, 0.2);
  vtkSmartPointer<vtkRenderer> renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->AddActor(actor);
  if (peel)
  {
    renderer->SetUseDepthPeeling(1);
    renderer->SetMaximumNumberOfPeels(100);
    renderer->SetOcclusionRatio(0.0);
  }
  else
  {
    vtkNew<vtkOrderedTranslucentPass> pass;
    renderer->SetPass(pass);
  }
  renderer->SetActiveCamera(camera);
  renderer->ResetCameraClippingRange();
  return renderer;
}

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}
} // namespace

int TestBSPSortedPolyDataMapper(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(320, 320);

  vtkNew<vtkDemoSceneSource> source;
  source->SetScene(vtkDemoSceneSource::SCENE_SPHERE_GRID);
  source->SetTriangleCount(20000);
  source->Update();

  vtkNew<vtkCamera> camera;

  // (A) the new mapper.
  vtkNew<vtkBSPSortedPolyDataMapper> sortedMapper;
  sortedMapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> sortedActor;
  sortedActor->SetMapper(sortedMapper);
  vtkNew<vtkRenderer> sortedRenderer;
  sortedRenderer->AddActor(sortedActor);
  vtkNew<vtkOrderedTranslucentPass> sortedPass;
  sortedRenderer->SetPass(sortedPass);
  sortedRenderer->SetActiveCamera(camera);

  // (B) vtkBSPSortFilter + plain mapper, ordered alpha blending.
  vtkNew<vtkBSPSortFilter> filter;
  filter->SetInputConnection(source->GetOutputPort());
  filter->SetCamera(camera);
  vtkNew<vtkPolyDataMapper> filterMapper;
  filterMapper->SetInputConnection(filter->GetOutputPort());
  vtkNew<vtkActor> filterActor;
  filterActor->SetMapper(filterMapper);
  vtkNew<vtkRenderer> filterRenderer;
  filterRenderer->AddActor(filterActor);
  vtkNew<vtkOrderedTranslucentPass> filterPass;
  filterRenderer->SetPass(filterPass);
  filterRenderer->SetActiveCamera(camera);

  // (C) dual depth peeling with 100 peels on the unsorted input.
  vtkNew<vtkPolyDataMapper> peelMapper;
  peelMapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> peelActor;
  peelActor->SetMapper(peelMapper);
  vtkNew<vtkRenderer> peelRenderer;
  peelRenderer->AddActor(peelActor);
  peelRenderer->SetUseDepthPeeling(1);
  peelRenderer->SetMaximumNumberOfPeels(100);
  peelRenderer->SetOcclusionRatio(0.0);
  peelRenderer->SetActiveCamera(camera);

  sortedRenderer->ResetCamera();
  struct ViewSpec
  {
    double azimuth, elevation;
    bool parallel;
  };
  const ViewSpec views[] = { { 30, 20, false }, { 125, -35, false }, { 200, 60, false },
    { 75, 10, true } };
  int v = 0;
  for (const ViewSpec& spec : views)
  {
    camera->SetPosition(0, 0, 1);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetParallelProjection(spec.parallel);
    sortedRenderer->ResetCamera();
    camera->Azimuth(spec.azimuth);
    camera->Elevation(spec.elevation);
    camera->OrthogonalizeViewUp();
    sortedRenderer->ResetCamera();

    auto sorted = RenderWith(window, sortedRenderer);
    auto filtered = RenderWith(window, filterRenderer);
    auto peeled = RenderWith(window, peelRenderer);
    const std::string tag = "view " + std::to_string(v) + (spec.parallel ? " (parallel)" : "");
    st::WritePng(sorted,
      st::TemporaryDirectory() + "/TestBSPSortedPolyDataMapper_" + std::to_string(v) +
        "_mapper.png");
    st::WritePng(filtered,
      st::TemporaryDirectory() + "/TestBSPSortedPolyDataMapper_" + std::to_string(v) +
        "_filter.png");
    st::WritePng(peeled,
      st::TemporaryDirectory() + "/TestBSPSortedPolyDataMapper_" + std::to_string(v) +
        "_peel100.png");

    st::ImageThresholds same; // same order: near-identical
    same.maxMeanAbsError = 0.1;
    same.maxCoveredBadFraction = 0.001;
    std::string why;
    const auto vsFilter = st::CompareImages(sorted, filtered);
    ok &= Check(st::WithinThresholds(vsFilter, same, &why),
      tag + " mapper vs BSP filter: " + vsFilter.Summary() + " " + why);
    st::ImageThresholds peel;
    peel.maxMeanAbsError = 0.5;
    peel.maxCoveredBadFraction = 0.01;
    const auto vsPeel = st::CompareImages(sorted, peeled);
    ok &= Check(st::WithinThresholds(vsPeel, peel, &why),
      tag + " mapper vs 100-peel DDP: " + vsPeel.Summary() + " " + why);
    ++v;
  }
  ok &= Check(sortedMapper->GetNumberOfTreeBuilds() == 1, "one tree build for all views");
  ok &= Check(sortedMapper->GetNumberOfVertexBufferBuilds() == 1,
    "vertex buffers built once for all views (builds: " +
      std::to_string(sortedMapper->GetNumberOfVertexBufferBuilds()) + ")");
  ok &= Check(sortedMapper->GetNumberOfFragments() > 0,
    "fragments: " + std::to_string(sortedMapper->GetNumberOfFragments()));
  // RGBA cell colours give fragments vertices carrying their cell's colour; the fragments of one
  // sphere (one colour) share them, so there are fewer vertices than fragment triangles (a
  // vertex per fragment corner would be more: every fragment has 2 more corners than triangles).
  // The images above are those of vtkBSPSortFilter's output either way.
  ok &= Check(sortedMapper->GetNumberOfFragmentVertices() > 0 &&
      sortedMapper->GetNumberOfFragmentVertices() < sortedMapper->GetNumberOfFragmentTriangles(),
    "fragments of one colour share vertices: " +
      std::to_string(sortedMapper->GetNumberOfFragmentVertices()) + " vertices for " +
      std::to_string(sortedMapper->GetNumberOfFragmentTriangles()) + " triangles");

  // (c) Camera unchanged: nothing re-sorted, nothing uploaded.
  RenderWith(window, sortedRenderer);
  const vtkIdType uploads = sortedMapper->GetNumberOfIndexUploads();
  const vtkIdType updates = sortedMapper->GetNumberOfOrderUpdates();
  RenderWith(window, sortedRenderer);
  window->Render();
  ok &= Check(sortedMapper->GetNumberOfIndexUploads() == uploads, "no upload, camera unchanged");
  ok &= Check(sortedMapper->GetNumberOfOrderUpdates() == updates, "no re-sort, camera unchanged");
  // Camera moved a lot: re-sorted and re-uploaded, vertex buffers untouched.
  camera->Azimuth(90);
  window->Render();
  ok &= Check(sortedMapper->GetNumberOfOrderUpdates() == updates + 1, "re-sort after a move");
  ok &= Check(sortedMapper->GetNumberOfIndexUploads() == uploads + 1, "one upload after a move");
  ok &= Check(sortedMapper->GetNumberOfVertexBufferBuilds() == 1, "still one vertex buffer build");
  // A new input rebuilds the tree.
  source->SetTriangleCount(10000);
  window->Render();
  ok &= Check(sortedMapper->GetNumberOfTreeBuilds() == 2, "tree rebuilt for a new input");

  // (e) Small camera steps move few fragments: only the changed index ranges are sent, and the
  // image is the one a new mapper (one full upload at that camera) draws, pixel for pixel.
  vtkNew<vtkSphereSource> ball;
  ball->SetThetaResolution(96);
  ball->SetPhiResolution(64);
  sortedMapper->SetInputConnection(ball->GetOutputPort());
  sortedActor->GetProperty()->SetOpacity(0.5);
  sortedRenderer->ResetCamera();
  RenderWith(window, sortedRenderer);
  const vtkIdType partials = sortedMapper->GetNumberOfPartialIndexUploads();
  const vtkIdType allIndices = sortedMapper->GetLastUploadIndexCount();
  vtkIdType largestSent = 0;
  for (int step = 0; step < 6; ++step)
  {
    camera->Azimuth(0.5);
    camera->Elevation(0.25);
    camera->OrthogonalizeViewUp();
    RenderWith(window, sortedRenderer);
    largestSent = std::max(largestSent, sortedMapper->GetLastUploadIndexCount());
  }
  const vtkIdType partialSteps = sortedMapper->GetNumberOfPartialIndexUploads() - partials;
  ok &= Check(partialSteps >= 3 && largestSent < allIndices,
    "small steps: " + std::to_string(partialSteps) + " of 6 uploads partial, at most " +
      std::to_string(largestSent) + " of " + std::to_string(allIndices) + " indices sent");
  auto stepped = RenderWith(window, sortedRenderer);
  vtkNew<vtkBSPSortedPolyDataMapper> freshMapper;
  freshMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> freshActor;
  freshActor->SetMapper(freshMapper);
  freshActor->GetProperty()->SetOpacity(0.5);
  vtkNew<vtkRenderer> freshRenderer;
  freshRenderer->AddActor(freshActor);
  vtkNew<vtkOrderedTranslucentPass> freshPass;
  freshRenderer->SetPass(freshPass);
  freshRenderer->SetActiveCamera(camera);
  auto fresh = RenderWith(window, freshRenderer);
  const auto vsFresh = st::CompareImages(stepped, fresh);
  ok &= Check(freshMapper->GetNumberOfPartialIndexUploads() == 0 && vsFresh.meanAbsError == 0.0,
    "after partial uploads: the image of one full upload: " + vsFresh.Summary());

  // (d) An opaque actor is never sorted and builds no tree.
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkBSPSortedPolyDataMapper> opaqueMapper;
  opaqueMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> opaqueActor;
  opaqueActor->SetMapper(opaqueMapper);
  vtkNew<vtkRenderer> opaqueRenderer;
  opaqueRenderer->AddActor(opaqueActor);
  opaqueRenderer->SetPass(sortedPass);
  auto opaqueImage = RenderWith(window, opaqueRenderer);
  ok &= Check(st::CoveredFraction(opaqueImage) > 0.05, "opaque actor drawn");
  ok &= Check(
    opaqueMapper->GetNumberOfTreeBuilds() == 0 && opaqueMapper->GetNumberOfIndexUploads() == 0,
    "opaque actor: no tree, no sorting");
  // ... until it becomes translucent.
  opaqueActor->GetProperty()->SetOpacity(0.5);
  RenderWith(window, opaqueRenderer);
  ok &= Check(
    opaqueMapper->GetNumberOfTreeBuilds() == 1 && opaqueMapper->GetNumberOfIndexUploads() == 1,
    "translucent actor: tree built, order uploaded");
  ok &= Check(opaqueMapper->GetLastRenderDrewFragments(), "translucent actor: fragments drawn");
  // Opaque again: it draws its own triangles, not the split fragments, and keeps its tree.
  const vtkIdType buffers = opaqueMapper->GetNumberOfVertexBufferBuilds();
  opaqueActor->GetProperty()->SetOpacity(1.0);
  auto opaqueAgain = RenderWith(window, opaqueRenderer);
  ok &= Check(!opaqueMapper->GetLastRenderDrewFragments() &&
      opaqueMapper->GetNumberOfVertexBufferBuilds() == buffers + 1,
    "opaque again: input drawn (one vertex buffer build)");
  const auto vsFirstOpaque = st::CompareImages(opaqueAgain, opaqueImage);
  ok &= Check(vsFirstOpaque.meanAbsError == 0.0,
    "opaque again: same image as before: " + vsFirstOpaque.Summary());
  RenderWith(window, opaqueRenderer);
  ok &= Check(opaqueMapper->GetNumberOfVertexBufferBuilds() == buffers + 1,
    "opaque, next frame: no vertex buffer build");
  opaqueActor->GetProperty()->SetOpacity(0.5);
  RenderWith(window, opaqueRenderer);
  ok &=
    Check(opaqueMapper->GetLastRenderDrewFragments() && opaqueMapper->GetNumberOfTreeBuilds() == 1,
      "translucent again: fragments drawn, tree kept");

  // (f) Ordered leaves.
  vtkSmartPointer<vtkPolyData> bumpy = st::MakeBumpySphere();
  vtkNew<vtkCamera> leafCamera;
  leafCamera->SetPosition(2.8, 5.6, 4.9);
  leafCamera->SetFocalPoint(0, 0, 0);
  leafCamera->SetViewUp(0, 0, 1);
  auto translucentRenderer = [&](vtkMapper* mapper, bool peel)
  { return TranslucentRenderer(mapper, leafCamera, peel); };
  vtkNew<vtkBSPSortedPolyDataMapper> leafMapper;
  leafMapper->SetInputData(bumpy);
  leafMapper->SetOrderedLeafSize(64);
  vtkNew<vtkBSPSortFilter> leafFilter;
  leafFilter->SetInputData(bumpy);
  leafFilter->SetOrderedLeafSize(64);
  leafFilter->SetCamera(leafCamera);
  vtkNew<vtkPolyDataMapper> leafFilterMapper;
  leafFilterMapper->SetInputConnection(leafFilter->GetOutputPort());
  vtkNew<vtkPolyDataMapper> leafPeelMapper;
  leafPeelMapper->SetInputData(bumpy);
  vtkNew<vtkBSPSortFilter> noLeaves;
  noLeaves->SetInputData(bumpy);
  noLeaves->SetCamera(leafCamera);
  noLeaves->Update();
  vtkSmartPointer<vtkRenderer> leafRenderers[3] = { translucentRenderer(leafMapper, false),
    translucentRenderer(leafFilterMapper, false), translucentRenderer(leafPeelMapper, true) };
  for (int step = 0; step < 3; ++step)
  {
    leafCamera->Azimuth(step * 50.0);
    leafCamera->Elevation(step * 15.0);
    leafCamera->OrthogonalizeViewUp();
    for (vtkRenderer* renderer : leafRenderers)
    {
      renderer->ResetCameraClippingRange();
    }
    auto mapperImage = RenderWith(window, leafRenderers[0]);
    auto filterImage = RenderWith(window, leafRenderers[1]);
    auto peelImage = RenderWith(window, leafRenderers[2]);
    const std::string tag = "ordered leaves, view " + std::to_string(step);
    std::vector<vtkIdType> mapperOrder;
    leafMapper->GetFragmentOrder(mapperOrder);
    vtkIdTypeArray* filterCells =
      vtkIdTypeArray::SafeDownCast(leafFilter->GetOutput()->GetCellData()->GetArray(
        vtkBSPSortFilter::OriginalCellIdArrayName()));
    const bool sameOrder = filterCells &&
      static_cast<vtkIdType>(mapperOrder.size()) == filterCells->GetNumberOfTuples() &&
      std::equal(mapperOrder.begin(), mapperOrder.end(), filterCells->GetPointer(0));
    ok &= Check(sameOrder && leafFilter->GetLastLeavesSorted() > 0,
      tag + ": the mapper draws the filter's order (" + std::to_string(mapperOrder.size()) +
        " fragments drawn, " + std::to_string(leafFilter->GetLastLeavesSorted()) +
        " leaves sorted)");
    ok &= Check(static_cast<vtkIdType>(mapperOrder.size()) < noLeaves->GetNumberOfFragments(),
      tag + ": fewer fragments drawn than without leaves (" +
        std::to_string(noLeaves->GetNumberOfFragments()) + ")");
    const st::ImageThresholds same = st::Thresholds(0.1, 0.001);
    const st::ImageThresholds peel = st::Thresholds(0.5, 0.01);
    std::string why;
    const auto vsFilter = st::CompareImages(mapperImage, filterImage);
    ok &= Check(st::WithinThresholds(vsFilter, same, &why),
      tag + " mapper vs filter: " + vsFilter.Summary() + " " + why);
    const auto vsPeel = st::CompareImages(mapperImage, peelImage);
    ok &= Check(st::WithinThresholds(vsPeel, peel, &why) && st::CoveredFraction(mapperImage) > 0.05,
      tag + " mapper vs 100-peel DDP: " + vsPeel.Summary() + " " + why);
    st::WritePng(mapperImage,
      st::TemporaryDirectory() + "/TestBSPSortedPolyDataMapper_leaves_" + std::to_string(step) +
        ".png");
  }
  ok &= Check(
    leafMapper->GetNumberOfTreeBuilds() == 1 && leafMapper->GetNumberOfVertexBufferBuilds() == 1,
    "ordered leaves: one tree and one vertex buffer for every view");

  // (g) Cell normals and no point normals (flat shading): every fragment carries its cell's
  // normal, and vertices are shared only between fragments of cells with the same normal, so the
  // image is vtkBSPSortFilter's (a vertex shared across cells would shade with a neighbour's
  // normal). Two overlapping spheres: fragments of one cell meet at split points.
  {
    vtkNew<vtkAppendPolyData> spheres;
    for (int k = 0; k < 2; ++k)
    {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetCenter(0.6 * k, 0.1 * k, 0.0);
      sphere->SetThetaResolution(18);
      sphere->SetPhiResolution(12);
      spheres->AddInputConnection(sphere->GetOutputPort());
    }
    vtkNew<vtkPolyDataNormals> flat;
    flat->SetInputConnection(spheres->GetOutputPort());
    flat->ComputeCellNormalsOn();
    flat->ComputePointNormalsOff();
    flat->SplittingOff();
    vtkNew<vtkCamera> flatCamera;
    vtkNew<vtkBSPSortedPolyDataMapper> flatMapper;
    flatMapper->SetInputConnection(flat->GetOutputPort());
    vtkSmartPointer<vtkRenderer> flatRenderer = TranslucentRenderer(flatMapper, flatCamera, false);
    vtkNew<vtkBSPSortFilter> flatFilter;
    flatFilter->SetInputConnection(flat->GetOutputPort());
    flatFilter->SetCamera(flatCamera);
    vtkNew<vtkPolyDataMapper> flatFilterMapper;
    flatFilterMapper->SetInputConnection(flatFilter->GetOutputPort());
    vtkSmartPointer<vtkRenderer> flatFilterRenderer =
      TranslucentRenderer(flatFilterMapper, flatCamera, false);
    flatRenderer->ResetCamera();
    flatCamera->Azimuth(35);
    flatCamera->Elevation(25);
    flatCamera->OrthogonalizeViewUp();
    flatRenderer->ResetCamera();
    auto mapperImage = RenderWith(window, flatRenderer);
    auto filterImage = RenderWith(window, flatFilterRenderer);
    std::string why;
    const auto vsFilter = st::CompareImages(mapperImage, filterImage);
    ok &= Check(st::WithinThresholds(vsFilter, st::Thresholds(0.1, 0.001), &why) &&
        st::CoveredFraction(mapperImage) > 0.05,
      "cell normals: mapper vs filter: " + vsFilter.Summary() + " " + why);
    const vtkIdType corners =
      flatMapper->GetNumberOfFragmentTriangles() + 2 * flatMapper->GetNumberOfFragments();
    ok &= Check(flatMapper->GetNumberOfFragments() > flat->GetOutput()->GetNumberOfCells() &&
        flatMapper->GetNumberOfFragmentVertices() < corners,
      "cell normals: " + std::to_string(flatMapper->GetNumberOfFragments()) + " fragments of " +
        std::to_string(flat->GetOutput()->GetNumberOfCells()) + " cells, " +
        std::to_string(flatMapper->GetNumberOfFragmentVertices()) + " vertices for " +
        std::to_string(corners) + " fragment corners");
    st::WritePng(mapperImage, st::TemporaryDirectory() + "/TestBSPSortedPolyDataMapper_flat.png");
  }

  window->GetRenderers()->RemoveAllItems();
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}

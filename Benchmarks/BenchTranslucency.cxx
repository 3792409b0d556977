// Frame time of translucent rendering of the 64-sphere scene, side by side in one run, headless
// (OSMesa, llvmpipe). A frame = 1 degree camera azimuth + Render() of a 512x512 window.
//
//   Unsorted alpha         plain mapper, plain alpha blending (vtkOrderedTranslucentPass): wrong
//   VtkDefaultOIT          plain mapper, VTK 9.1's default weighted OIT: approximate
//   DepthSortPolyData      vtkDepthSortPolyData + alpha blending: approximate
//   DualDepthPeeling4/100  VTK's dual depth peeling, 4 / 100 peels (100: reference quality)
//   BSPSortFilter          vtkBSPSortFilter + plain mapper + alpha blending: exact
//   BSPSortedMapper        vtkBSPSortedPolyDataMapper + alpha blending: exact
//   BSPTranslucentPass     64 actors (one per sphere) with vtkBSPTranslucentPass: exact
//
// The first six and the mapper draw ONE merged mesh (vtkDemoSceneSource, RGBA cell colours).
// Reproduce: LP_NUM_THREADS=1 build/bin/scenevis_translucency_bench --benchmark_filter=Frame
#include "vtkBSPSortFilter.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"

#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDepthSortPolyData.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

namespace
{
enum class Mode
{
  UnsortedAlpha,
  VtkDefaultOIT,
  DepthSortPolyData,
  DualDepthPeeling4,
  DualDepthPeeling100,
  BSPSortFilter,
  BSPSortedMapper,
  BSPTranslucentPass
};

void Frame(benchmark::State& state, Mode mode)
{
  const vtkIdType triangles = static_cast<vtkIdType>(state.range(0));
  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(512, 512);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();

  vtkNew<vtkDemoSceneSource> source;
  source->SetScene(vtkDemoSceneSource::SCENE_SPHERE_GRID);
  source->SetTriangleCount(triangles);
  vtkSmartPointer<vtkPolyDataMapper> mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkNew<vtkDepthSortPolyData> depthSort;
  vtkNew<vtkBSPSortFilter> bspFilter;
  vtkNew<vtkBSPSortedPolyDataMapper> bspMapper;
  vtkNew<vtkActor> actor;
  vtkNew<vtkOrderedTranslucentPass> steps;
  vtkNew<vtkBSPTranslucentPass> bspPass;
  switch (mode)
  {
    case Mode::BSPTranslucentPass:
    {
      // One actor per sphere, about triangles/64 triangles each.
      const int resolution =
        std::max(8, static_cast<int>(std::sqrt(static_cast<double>(triangles) / 64.0 / 2.0)) + 1);
      for (int k = 0; k < 4; ++k)
      {
        for (int j = 0; j < 4; ++j)
        {
          for (int i = 0; i < 4; ++i)
          {
            vtkNew<vtkSphereSource> sphere;
            sphere->SetCenter(i, j, k);
            sphere->SetRadius(0.8);
            sphere->SetThetaResolution(resolution);
            sphere->SetPhiResolution(resolution);
            vtkNew<vtkPolyDataMapper> sphereMapper;
            sphereMapper->SetInputConnection(sphere->GetOutputPort());
            vtkNew<vtkActor> sphereActor;
            sphereActor->SetMapper(sphereMapper);
            sphereActor->GetProperty()->SetColor(0.2 + 0.8 * i / 3, 0.2 + 0.8 * j / 3,
              0.2 + 0.8 * k / 3);
            sphereActor->GetProperty()->SetOpacity(0.3);
            renderer->AddActor(sphereActor);
          }
        }
      }
      steps->SetTranslucentPass(bspPass);
      renderer->SetPass(steps);
      break;
    }
    case Mode::BSPSortedMapper:
      bspMapper->SetInputConnection(source->GetOutputPort());
      actor->SetMapper(bspMapper);
      renderer->SetPass(steps);
      break;
    case Mode::DepthSortPolyData:
      depthSort->SetInputConnection(source->GetOutputPort());
      depthSort->SetCamera(camera);
      depthSort->SetDirectionToBackToFront();
      depthSort->SetDepthSortModeToParametricCenter();
      mapper->SetInputConnection(depthSort->GetOutputPort());
      actor->SetMapper(mapper);
      renderer->SetPass(steps);
      break;
    case Mode::BSPSortFilter:
      bspFilter->SetInputConnection(source->GetOutputPort());
      bspFilter->SetCamera(camera);
      bspFilter->SetGenerateOrderArrays(false);
      mapper->SetInputConnection(bspFilter->GetOutputPort());
      actor->SetMapper(mapper);
      renderer->SetPass(steps);
      break;
    default:
      mapper->SetInputConnection(source->GetOutputPort());
      actor->SetMapper(mapper);
      if (mode == Mode::UnsortedAlpha)
      {
        renderer->SetPass(steps);
      }
      else if (mode == Mode::DualDepthPeeling4 || mode == Mode::DualDepthPeeling100)
      {
        renderer->SetUseDepthPeeling(1);
        renderer->SetMaximumNumberOfPeels(mode == Mode::DualDepthPeeling4 ? 4 : 100);
        renderer->SetOcclusionRatio(0.0);
      }
      break;
  }
  if (mode != Mode::BSPTranslucentPass)
  {
    renderer->AddActor(actor);
  }
  renderer->ResetCamera();
  camera->Azimuth(30);
  camera->Elevation(20);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
  window->Render(); // builds trees and buffers: not timed
  window->Render();

  for (auto _ : state)
  {
    camera->Azimuth(1.0);
    window->Render();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  if (mode == Mode::BSPSortedMapper)
  {
    state.counters["fragments"] = static_cast<double>(bspMapper->GetNumberOfFragments());
    state.counters["vbo_builds"] = static_cast<double>(bspMapper->GetNumberOfVertexBufferBuilds());
    state.counters["ibo_uploads"] = static_cast<double>(bspMapper->GetNumberOfIndexUploads());
    state.counters["build_s"] = bspMapper->GetLastBuildTime();
  }
  if (mode == Mode::BSPTranslucentPass)
  {
    state.counters["fragments"] = static_cast<double>(bspPass->GetNumberOfFragments());
    state.counters["draw_calls"] = static_cast<double>(bspPass->GetNumberOfDrawCalls());
    state.counters["build_s"] = bspPass->GetLastBuildTime();
  }
  window->RemoveRenderer(renderer);
}
} // namespace

#define SCENEVIS_FRAME(name, mode)                                                                 \
  BENCHMARK_CAPTURE(Frame, name, mode)                                                             \
    ->Name("Frame/" #name)                                                                         \
    ->Arg(100000)                                                                                  \
    ->Arg(1000000)                                                                                 \
    ->Iterations(10)                                                                               \
    ->Unit(benchmark::kMillisecond)
SCENEVIS_FRAME(UnsortedAlpha, Mode::UnsortedAlpha);
SCENEVIS_FRAME(VtkDefaultOIT, Mode::VtkDefaultOIT);
SCENEVIS_FRAME(DepthSortPolyData, Mode::DepthSortPolyData);
SCENEVIS_FRAME(DualDepthPeeling4, Mode::DualDepthPeeling4);
SCENEVIS_FRAME(DualDepthPeeling100, Mode::DualDepthPeeling100);
SCENEVIS_FRAME(BSPSortFilter, Mode::BSPSortFilter);
SCENEVIS_FRAME(BSPSortedMapper, Mode::BSPSortedMapper);
SCENEVIS_FRAME(BSPTranslucentPass, Mode::BSPTranslucentPass);
BENCHMARK_CAPTURE(Frame, Smoke, Mode::BSPSortedMapper)
  ->Name("Smoke/BSPSortedMapper")
  ->Arg(5000)
  ->Iterations(3)
  ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

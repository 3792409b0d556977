// Per-frame cost of translucency sorting in a VTK pipeline, side by side in one run:
// vtkDepthSortPolyData (one depth per cell, approximate) against vtkBSPSortFilter (exact).
// A "frame" is a 1-degree camera orbit step followed by the filter's update, as an interactive
// application would do it. Reproduce: build/bin/scenevis_vtk_bench --benchmark_filter=Frame
#include "vtkBSPSortFilter.h"

#include "vtkCamera.h"
#include "vtkDepthSortPolyData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include <algorithm>

#include <benchmark/benchmark.h>

#include <cmath>

namespace
{
/// A UV sphere with about `triangles` triangles (vtkSphereSource makes 2*t*(p-2) of them).
vtkSmartPointer<vtkPolyData> Sphere(int triangles)
{
  const int resolution = std::max(8, static_cast<int>(std::sqrt(triangles / 2.0)) + 1);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution + 2);
  sphere->Update();
  return sphere->GetOutput();
}

void OrbitCamera(vtkCamera* camera)
{
  camera->SetPosition(0, 0.3, 4);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
}

void DepthSortFrame(benchmark::State& state)
{
  vtkSmartPointer<vtkPolyData> input = Sphere(static_cast<int>(state.range(0)));
  vtkNew<vtkCamera> camera;
  OrbitCamera(camera);
  vtkNew<vtkDepthSortPolyData> sorter;
  sorter->SetInputData(input);
  sorter->SetCamera(camera);
  sorter->SetDirectionToBackToFront();
  sorter->SetDepthSortModeToParametricCenter();
  sorter->Update();
  for (auto _ : state)
  {
    camera->Azimuth(1.0);
    sorter->Update();
    benchmark::DoNotOptimize(sorter->GetOutput()->GetNumberOfCells());
  }
  state.counters["triangles"] = static_cast<double>(input->GetNumberOfPolys());
}

void BSPSortFrame(benchmark::State& state)
{
  vtkSmartPointer<vtkPolyData> input = Sphere(static_cast<int>(state.range(0)));
  vtkNew<vtkCamera> camera;
  OrbitCamera(camera);
  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputData(input);
  sorter->SetCamera(camera);
  sorter->SetGenerateOrderArrays(false);
  sorter->Update();
  double orderSeconds = 0.0;
  for (auto _ : state)
  {
    camera->Azimuth(1.0);
    sorter->Update();
    orderSeconds += sorter->GetLastOrderTime();
    benchmark::DoNotOptimize(sorter->GetOutput()->GetNumberOfCells());
  }
  state.counters["triangles"] = static_cast<double>(input->GetNumberOfPolys());
  state.counters["fragments/input"] =
    static_cast<double>(sorter->GetNumberOfFragments()) / input->GetNumberOfPolys();
  state.counters["build_s"] = sorter->GetLastBuildTime();
  state.counters["order_ms"] =
    benchmark::Counter(orderSeconds * 1e3, benchmark::Counter::kAvgIterations);
}

void BSPSortBuild(benchmark::State& state)
{
  vtkSmartPointer<vtkPolyData> input = Sphere(static_cast<int>(state.range(0)));
  vtkNew<vtkCamera> camera;
  OrbitCamera(camera);
  for (auto _ : state)
  {
    vtkNew<vtkBSPSortFilter> sorter;
    sorter->SetInputData(input);
    sorter->SetCamera(camera);
    sorter->Update();
    benchmark::DoNotOptimize(sorter->GetOutput()->GetNumberOfCells());
  }
  state.counters["triangles"] = static_cast<double>(input->GetNumberOfPolys());
}
} // namespace

BENCHMARK(DepthSortFrame)->Name("Frame/DepthSortPolyData")->Arg(10000)->Arg(100000)->Arg(1000000)
  ->Unit(benchmark::kMillisecond);
BENCHMARK(BSPSortFrame)->Name("Frame/BSPSortFilter")->Arg(10000)->Arg(100000)->Arg(1000000)
  ->Unit(benchmark::kMillisecond);
BENCHMARK(BSPSortBuild)->Name("Build/BSPSortFilter")->Arg(10000)->Arg(100000)->Arg(1000000)
  ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(DepthSortFrame)->Name("Smoke/DepthSortPolyData")->Arg(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BSPSortFrame)->Name("Smoke/BSPSortFilter")->Arg(2000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

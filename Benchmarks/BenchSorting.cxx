// Per-frame cost of translucency sorting in a VTK pipeline, side by side in one run:
// vtkDepthSortPolyData (one depth per cell: approximate) against vtkBSPSortFilter (exact).
// A "frame" is a 1-degree camera orbit step followed by the filter's update, as an interactive
// application does it; the BSP tree is built before the timed loop (BuildBSP times the build).
//
// Scenes: a UV sphere and the 64-sphere grid at 10k / 100k / 1M triangles, and the real models
// fetched by scripts/fetch-data.sh (Stanford bunny, 2CylinderEngine; skipped when absent).
// Reproduce: build/bin/scenevis_vtk_bench --benchmark_filter='Frame|Build'
#include "vtkBSPSortFilter.h"
#include "vtkDemoSceneSource.h"

#include "scenevis/testing/Models.h"

#include "vtkCamera.h"
#include "vtkDepthSortPolyData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace
{
using SceneFactory = std::function<vtkSmartPointer<vtkPolyData>()>;

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

vtkSmartPointer<vtkPolyData> SphereGrid(int triangles)
{
  vtkNew<vtkDemoSceneSource> grid;
  grid->SetTriangleCount(triangles);
  grid->Update();
  return grid->GetOutput();
}

vtkSmartPointer<vtkPolyData> Model(const std::string& key)
{
  const std::string path = scenevis::testing::DataFile(key);
  return path.empty() ? nullptr : scenevis::testing::LoadModel(path);
}

/// An orbit camera three bounding radii from the centre, slightly above.
void AimCamera(vtkCamera* camera, vtkPolyData* pd)
{
  double b[6];
  pd->GetBounds(b);
  const double c[3] = { (b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2 };
  const double r =
    0.5 * std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
            (b[5] - b[4]) * (b[5] - b[4]));
  camera->SetFocalPoint(c);
  camera->SetPosition(c[0], c[1] + 0.3 * r, c[2] + 3 * r);
  camera->SetViewUp(0, 1, 0);
}

void DepthSortFrame(benchmark::State& state, const SceneFactory& scene)
{
  vtkSmartPointer<vtkPolyData> input = scene();
  if (!input)
  {
    state.SkipWithError("model not fetched (scripts/fetch-data.sh)");
    return;
  }
  vtkNew<vtkCamera> camera;
  AimCamera(camera, input);
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

void BSPSortFrame(benchmark::State& state, const SceneFactory& scene)
{
  vtkSmartPointer<vtkPolyData> input = scene();
  if (!input)
  {
    state.SkipWithError("model not fetched (scripts/fetch-data.sh)");
    return;
  }
  vtkNew<vtkCamera> camera;
  AimCamera(camera, input);
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
  state.counters["order_ms"] =
    benchmark::Counter(orderSeconds * 1e3, benchmark::Counter::kAvgIterations);
}

void BSPBuild(benchmark::State& state, const SceneFactory& scene)
{
  vtkSmartPointer<vtkPolyData> input = scene();
  if (!input)
  {
    state.SkipWithError("model not fetched (scripts/fetch-data.sh)");
    return;
  }
  vtkNew<vtkCamera> camera;
  AimCamera(camera, input);
  double fragments = 0;
  for (auto _ : state)
  {
    vtkNew<vtkBSPSortFilter> sorter;
    sorter->SetInputData(input);
    sorter->SetCamera(camera);
    sorter->Update();
    fragments = static_cast<double>(sorter->GetNumberOfFragments());
  }
  state.counters["triangles"] = static_cast<double>(input->GetNumberOfPolys());
  state.counters["fragments/input"] = fragments / input->GetNumberOfPolys();
}

void Register(const std::string& name, const SceneFactory& scene, bool smoke = false)
{
  const std::string prefix = smoke ? "Smoke/" : "";
  benchmark::RegisterBenchmark((prefix + "Frame/DepthSortPolyData/" + name).c_str(),
    DepthSortFrame, scene)
    ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark((prefix + "Frame/BSPSortFilter/" + name).c_str(), BSPSortFrame,
    scene)
    ->Unit(benchmark::kMillisecond);
  if (!smoke)
  {
    benchmark::RegisterBenchmark(("Build/BSPSortFilter/" + name).c_str(), BSPBuild, scene)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  }
}
} // namespace

int main(int argc, char** argv)
{
  Register("sphere2k", [] { return Sphere(2000); }, true);
  for (int n : { 10000, 100000, 1000000 })
  {
    const std::string k = std::to_string(n / 1000) + "k";
    Register("sphere" + k, [n] { return Sphere(n); });
    Register("spheres64x" + k, [n] { return SphereGrid(n); });
  }
  Register("bunny", [] { return Model("bunny-stl"); });
  Register("2CylinderEngine", [] { return Model("engine-glb"); });

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
  {
    return 1;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

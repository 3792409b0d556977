// Per-frame cull time of vtkOctreeCuller (three update modes) against VTK 9.1's
// vtkFrustumCoverageCuller on 100k props (the part boxes of the CAD assembly as scaled cube
// actors sharing one mapper), calling Cull() directly with a prop array: no rendering. The core
// culling benchmarks (Core/Benchmarks/BenchCulling.cpp) are linked into the same executable so
// one run shows everything side by side. `--benchmark_filter=Smoke` runs 1k-prop variants.
#include "vtkOctreeCuller.h"

#include "scenevis/Scenes.h"

#include <glm/common.hpp>
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCubeSource.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <vector>

namespace
{
struct PropScene
{
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<vtkProp*> props;
  double center[3];
  double radius;
};

// Released by main() before exit: the OSMesa window must go before static destruction.
std::map<std::size_t, std::unique_ptr<PropScene>> cache;

PropScene& scene(std::size_t n)
{
  auto& s = cache[n];
  if (!s)
  {
    s = std::make_unique<PropScene>();
    s->window = scenevis::testing::MakeRenderWindow(800, 600);
    s->window->AddRenderer(s->renderer);
    const auto cad = scenevis::scenes::cadAssembly(n, 16, 1);
    vtkNew<vtkCubeSource> cube; // unit cube centred at the origin
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(cube->GetOutputPort());
    scenevis::Box all;
    for (const auto& part : cad.parts)
    {
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      const glm::dvec3 c = part.bounds.center();
      const glm::dvec3 d = glm::max(part.bounds.hi - part.bounds.lo, glm::dvec3(1e-3));
      actor->SetPosition(c.x, c.y, c.z);
      actor->SetScale(d.x, d.y, d.z);
      s->actors.push_back(actor);
      s->props.push_back(actor);
      all.extend(part.bounds);
    }
    const glm::dvec3 c = all.center();
    s->center[0] = c.x;
    s->center[1] = c.y;
    s->center[2] = c.z;
    s->radius = 0.5 * all.diagonal();
  }
  return *s;
}

/// 16 views on a slow orbit, overviews and close-ups alternating (as in the core benchmark).
void SetView(PropScene& s, std::size_t frame)
{
  vtkCamera* cam = s.renderer->GetActiveCamera();
  const double t = 0.1 * static_cast<double>(frame % 16);
  const double d = (frame % 2 ? 0.3 : 1.2) * s.radius;
  cam->SetFocalPoint(s.center[0] + 0.1 * s.radius * std::sin(3 * t), s.center[1], s.center[2]);
  cam->SetPosition(
    s.center[0] + std::cos(t) * d, s.center[1] + std::sin(t) * d, s.center[2] + 0.5 * d);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(40);
  cam->SetClippingRange(0.01 * s.radius, 4 * s.radius);
}

void RunCuller(benchmark::State& state, vtkCuller* culler, std::size_t n, vtkOctreeCuller* stats)
{
  PropScene& s = scene(n);
  std::vector<vtkProp*> list(s.props.size());
  std::size_t frame = 0, drawn = 0;
  // Installed as recommended: the culler under test is the renderer's only culler.
  s.renderer->GetCullers()->RemoveAllItems();
  s.renderer->AddCuller(culler);
  // One untimed frame: the octree culler builds its hierarchy (and VTK warms its bounds).
  for (int warm = 0; warm < 2; ++warm)
  {
    list = s.props;
    int length = static_cast<int>(list.size()), initialized = 0;
    SetView(s, 0);
    culler->Cull(s.renderer, list.data(), length, initialized);
  }
  for (auto _ : state)
  {
    state.PauseTiming();
    SetView(s, frame++);
    std::copy(s.props.begin(), s.props.end(), list.begin()); // the renderer's fresh list
    state.ResumeTiming();
    int length = static_cast<int>(list.size()), initialized = 0;
    benchmark::DoNotOptimize(culler->Cull(s.renderer, list.data(), length, initialized));
    drawn += static_cast<std::size_t>(length);
  }
  state.counters["drawn/frame"] = static_cast<double>(drawn) / static_cast<double>(frame);
  if (stats)
  {
    state.counters["rebuilds"] = static_cast<double>(stats->GetNumberOfRebuilds());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

void VtkFrustumCoverage(benchmark::State& state, std::size_t n)
{
  vtkNew<vtkFrustumCoverageCuller> culler;
  RunCuller(state, culler, n, nullptr);
}

void Octree(benchmark::State& state, std::size_t n, int mode)
{
  vtkNew<vtkOctreeCuller> culler;
  culler->SetUpdateMode(mode);
  RunCuller(state, culler, n, culler);
}

void BM_VtkFrustumCoverageCuller_100k(benchmark::State& s) { VtkFrustumCoverage(s, 100000); }
void BM_OctreeCuller_BoundsEveryFrame_100k(benchmark::State& s)
{
  Octree(s, 100000, vtkOctreeCuller::UPDATE_BOUNDS_EVERY_FRAME);
}
void BM_OctreeCuller_OnModified_100k(benchmark::State& s)
{
  Octree(s, 100000, vtkOctreeCuller::UPDATE_ON_MODIFIED);
}
void BM_OctreeCuller_Manual_100k(benchmark::State& s)
{
  Octree(s, 100000, vtkOctreeCuller::UPDATE_MANUAL);
}
void BM_Smoke_VtkFrustumCoverageCuller_1k(benchmark::State& s) { VtkFrustumCoverage(s, 1000); }
void BM_Smoke_OctreeCuller_1k(benchmark::State& s)
{
  Octree(s, 1000, vtkOctreeCuller::UPDATE_BOUNDS_EVERY_FRAME);
}
} // namespace

BENCHMARK(BM_VtkFrustumCoverageCuller_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeCuller_BoundsEveryFrame_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeCuller_OnModified_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeCuller_Manual_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Smoke_VtkFrustumCoverageCuller_1k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Smoke_OctreeCuller_1k)->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv)
{
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
  {
    return 1;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  cache.clear();
  return 0;
}

#include "scenevis/PolygonMesh.h"

#include <benchmark/benchmark.h>

static void BM_Smoke_MeshArea(benchmark::State& state)
{
  scenevis::PolygonMesh mesh;
  for (int i = 0; i < 1000; ++i)
  {
    const auto a = mesh.addPoint({ double(i), 0, 0 });
    const auto b = mesh.addPoint({ double(i) + 1, 0, 0 });
    const auto c = mesh.addPoint({ double(i), 1, 0 });
    mesh.addPolygon({ a, b, c });
  }
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(mesh.area());
  }
  state.SetItemsProcessed(state.iterations() * 1000);
}
BENCHMARK(BM_Smoke_MeshArea);

BENCHMARK_MAIN();

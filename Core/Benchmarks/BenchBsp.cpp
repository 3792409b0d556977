// BSP core benchmarks: build, full order and incremental order of a UV sphere (the convex worst
// case of a polygon-aligned BSP) at 10k / 100k / 1M triangles. `--benchmark_filter=Smoke` runs a
// small subset in well under a second.
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>

namespace
{

using namespace scenevis;

/// Closed UV sphere of about `triangles` triangles (slices = 2 * stacks, single pole points).
PolygonMesh uvSphere(std::size_t triangles)
{
  const int stacks = std::max(2, static_cast<int>(std::lround(std::sqrt(triangles / 4.0))));
  const int slices = 2 * stacks;
  const double pi = 3.14159265358979323846;
  PolygonMesh mesh;
  const std::uint32_t north = mesh.addPoint({ 0, 0, 1 });
  for (int i = 1; i < stacks; ++i)
  {
    const double theta = pi * i / stacks;
    for (int j = 0; j < slices; ++j)
    {
      const double phi = 2 * pi * j / slices;
      mesh.addPoint({ std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
        std::cos(theta) });
    }
  }
  const std::uint32_t south = mesh.addPoint({ 0, 0, -1 });
  auto ring = [&](int i, int j)
  { return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices)); };
  for (int j = 0; j < slices; ++j)
  {
    mesh.addPolygon({ north, ring(1, j), ring(1, j + 1) });
    mesh.addPolygon({ south, ring(stacks - 1, j + 1), ring(stacks - 1, j) });
  }
  for (int i = 1; i + 1 < stacks; ++i)
  {
    for (int j = 0; j < slices; ++j)
    {
      mesh.addPolygon({ ring(i, j), ring(i + 1, j), ring(i + 1, j + 1) });
      mesh.addPolygon({ ring(i, j), ring(i + 1, j + 1), ring(i, j + 1) });
    }
  }
  return mesh;
}

struct Fixture
{
  PolygonMesh mesh;
  bsp::Tree tree;
};

/// Built once per size and shared by the order benchmarks (building 1M takes about a second).
const Fixture& fixture(std::size_t triangles)
{
  static std::map<std::size_t, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[triangles];
  if (!slot)
  {
    slot = std::make_unique<Fixture>();
    slot->mesh = uvSphere(triangles);
    slot->tree = bsp::build(slot->mesh);
  }
  return *slot;
}

/// Eye on a 20-degree-elevated orbit at 3 radii around the sphere.
View orbitView(double degrees)
{
  const double a = degrees * 3.14159265358979323846 / 180.0;
  const double e = 20.0 * 3.14159265358979323846 / 180.0;
  return View::perspective(
    glm::dvec3(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)) * 3.0);
}

void buildBenchmark(benchmark::State& state)
{
  const PolygonMesh mesh = uvSphere(static_cast<std::size_t>(state.range(0)));
  bsp::Tree tree;
  for (auto _ : state)
  {
    tree = bsp::build(mesh);
    benchmark::DoNotOptimize(tree.root);
  }
  bsp::IncrementalOrder incremental(tree, bsp::Direction::BackToFront);
  incremental.update(orbitView(0.0));
  const double input = static_cast<double>(mesh.polygonCount());
  state.counters["triangles"] = input;
  state.counters["fragments/input"] = static_cast<double>(tree.fragments.size()) / input;
  state.counters["bytes/triangle"] =
    static_cast<double>(tree.statistics.memoryBytes + incremental.memoryBytes()) / input;
  state.counters["depth"] = static_cast<double>(tree.statistics.depth);
  state.counters["nodes"] = static_cast<double>(tree.statistics.nodes);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.polygonCount()));
}

void orderBenchmark(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
  std::vector<std::uint32_t> result;
  double angle = 0.0;
  for (auto _ : state)
  {
    bsp::order(f.tree, orbitView(angle), bsp::Direction::BackToFront, result);
    benchmark::DoNotOptimize(result.data());
    angle += 1.0;
  }
  state.counters["fragments"] = static_cast<double>(f.tree.fragments.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.tree.fragments.size()));
}

void incrementalBenchmark(benchmark::State& state)
{
  const Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
  bsp::IncrementalOrder incremental(f.tree, bsp::Direction::BackToFront);
  double angle = 0.0;
  incremental.update(orbitView(angle));
  double visited = 0;
  double flipped = 0;
  double moved = 0;
  for (auto _ : state)
  {
    angle += 1.0;
    const auto& s = incremental.update(orbitView(angle));
    visited += static_cast<double>(s.nodesVisited);
    flipped += static_cast<double>(s.nodesFlipped);
    moved += static_cast<double>(s.fragmentsMoved);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["nodes"] = static_cast<double>(f.tree.nodes.size());
  state.counters["visited/update"] = visited / n;
  state.counters["flipped/update"] = flipped / n;
  state.counters["moved/update"] = moved / n;
}

} // namespace

BENCHMARK(buildBenchmark)
  ->Name("BM_Smoke_BspBuild")
  ->Arg(2000)
  ->Unit(benchmark::kMillisecond);
BENCHMARK(orderBenchmark)->Name("BM_Smoke_BspOrder")->Arg(2000)->Unit(benchmark::kMicrosecond);
BENCHMARK(incrementalBenchmark)
  ->Name("BM_Smoke_BspIncremental")
  ->Arg(2000)
  ->Unit(benchmark::kMicrosecond);

BENCHMARK(buildBenchmark)
  ->Name("BM_BspBuild")
  ->Arg(10000)
  ->Arg(100000)
  ->Arg(1000000)
  ->Unit(benchmark::kMillisecond);
BENCHMARK(orderBenchmark)
  ->Name("BM_BspOrder")
  ->Arg(10000)
  ->Arg(100000)
  ->Arg(1000000)
  ->Unit(benchmark::kMillisecond);
BENCHMARK(incrementalBenchmark)
  ->Name("BM_BspIncrementalOrbit1Deg")
  ->Arg(10000)
  ->Arg(100000)
  ->Arg(1000000)
  ->Unit(benchmark::kMillisecond);

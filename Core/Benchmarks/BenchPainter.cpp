// The painter's algorithm (PainterSort.h) per frame, side by side with the BSP on the same scenes
// and the same camera path (an orbit of radius 3x the bounding radius, 20 degrees up, 1 degree per
// frame, as BenchBsp.cpp):
// - BM_Painter/<scene>/<n>: one painter sort per frame (normalisation, done once per mesh by
//   painter::Sorter, is not timed; the Sorter's one-off cost is reported as `prepareMs`),
// - BM_PainterRef_BspOrder/<scene>/<n>: bsp::order (full walk) per frame on a prebuilt tree
//   (the one-off build is reported as `buildMs`),
// - BM_PainterRef_BspIncremental/<scene>/<n>: bsp::IncrementalOrder::update per 1-degree step.
// Scenes: "grid" = scenes::sphereGrid(4) with trianglesPerSphereFor(n) (64 overlapping spheres),
// "sphere" = scenes::sphere (a convex UV sphere, 10k only). The painter's worst case is quadratic:
// the whole filter `Painter` takes ~20 s of CPU (grid/100000: ~4 s per frame, one iteration). Counters: splits/frame, fragments/frame, pairs/frame (Newell comparisons), moves.
// `--benchmark_filter=Smoke` runs a tiny subset in well under a second.
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/PainterSort.h"
#include "scenevis/Scenes.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace
{

using namespace scenevis;

enum class Kind
{
  Grid,
  Sphere
};

const char* kindName(Kind kind)
{
  return kind == Kind::Grid ? "grid" : "sphere";
}

PolygonMesh makeMesh(Kind kind, std::size_t triangles)
{
  if (kind == Kind::Sphere)
  {
    return scenes::sphere(glm::dvec3(0.0), 1.0, triangles);
  }
  return scenes::sphereGrid(4, 0.8, 1.0, scenes::trianglesPerSphereFor(triangles)).mesh;
}

double seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

struct Fixture
{
  PolygonMesh mesh;
  double radius = 3.0;
  std::unique_ptr<painter::Sorter> sorter;
  double prepareSeconds = 0.0;
  bsp::Tree tree;
  double buildSeconds = 0.0;
};

/// Built once per scene and size; the BSP tree only when a BSP benchmark asks for it.
Fixture& fixture(Kind kind, std::size_t triangles, bool needTree)
{
  static std::map<std::pair<int, std::size_t>, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[{ static_cast<int>(kind), triangles }];
  if (!slot)
  {
    slot = std::make_unique<Fixture>();
    slot->mesh = makeMesh(kind, triangles);
    slot->radius = 1.5 * slot->mesh.bounds().diagonal() / std::sqrt(3.0);
    const auto start = std::chrono::steady_clock::now();
    slot->sorter = std::make_unique<painter::Sorter>(slot->mesh);
    slot->prepareSeconds = seconds(start);
  }
  if (needTree && slot->tree.empty())
  {
    const auto start = std::chrono::steady_clock::now();
    slot->tree = bsp::build(slot->mesh);
    slot->buildSeconds = seconds(start);
  }
  return *slot;
}

View orbitView(double degrees, double radius)
{
  const double a = degrees * 3.14159265358979323846 / 180.0;
  const double e = 20.0 * 3.14159265358979323846 / 180.0;
  return View::perspective(
    glm::dvec3(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)) * radius);
}

void painterBenchmark(benchmark::State& state, Kind kind, std::size_t triangles)
{
  Fixture& f = fixture(kind, triangles, false);
  painter::Result result;
  double angle = 0.0;
  double splits = 0;
  double fragments = 0;
  double pairs = 0;
  double moves = 0;
  double cycles = 0;
  double forced = 0;
  for (auto _ : state)
  {
    f.sorter->sort(orbitView(angle, f.radius), result);
    benchmark::DoNotOptimize(result.fragments.data());
    angle += 1.0;
    const painter::Statistics& s = result.statistics;
    splits += static_cast<double>(s.splits);
    fragments += static_cast<double>(s.fragments);
    pairs += static_cast<double>(s.pairs);
    moves += static_cast<double>(s.moves);
    cycles += static_cast<double>(s.cyclesResolved);
    forced += static_cast<double>(s.forcedEmissions);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(f.mesh.polygonCount());
  state.counters["splits/frame"] = splits / n;
  state.counters["fragments"] = fragments / n;
  state.counters["pairs/frame"] = pairs / n;
  state.counters["moves/frame"] = moves / n;
  state.counters["cycles/frame"] = cycles / n;
  state.counters["forced"] = forced / n;
  state.counters["prepareMs"] = f.prepareSeconds * 1e3;
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.mesh.polygonCount()));
}

void bspOrderBenchmark(benchmark::State& state, Kind kind, std::size_t triangles)
{
  const Fixture& f = fixture(kind, triangles, true);
  std::vector<std::uint32_t> order;
  double angle = 0.0;
  for (auto _ : state)
  {
    bsp::order(f.tree, orbitView(angle, f.radius), bsp::Direction::BackToFront, order);
    benchmark::DoNotOptimize(order.data());
    angle += 1.0;
  }
  state.counters["triangles"] = static_cast<double>(f.mesh.polygonCount());
  state.counters["splits/frame"] = 0.0; // view-independent: all made in the build
  state.counters["fragments"] = static_cast<double>(f.tree.fragments.size());
  state.counters["buildMs"] = f.buildSeconds * 1e3;
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.mesh.polygonCount()));
}

void bspIncrementalBenchmark(benchmark::State& state, Kind kind, std::size_t triangles)
{
  const Fixture& f = fixture(kind, triangles, true);
  bsp::IncrementalOrder incremental(f.tree, bsp::Direction::BackToFront);
  double angle = 0.0;
  incremental.update(orbitView(angle, f.radius));
  for (auto _ : state)
  {
    angle += 1.0;
    benchmark::DoNotOptimize(incremental.update(orbitView(angle, f.radius)).nodesVisited);
  }
  state.counters["triangles"] = static_cast<double>(f.mesh.polygonCount());
  state.counters["splits/frame"] = 0.0;
  state.counters["fragments"] = static_cast<double>(f.tree.fragments.size());
  state.counters["buildMs"] = f.buildSeconds * 1e3;
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.mesh.polygonCount()));
}

void registerTriple(const std::string& prefix, Kind kind, std::size_t n)
{
  const std::string suffix = std::string("/") + kindName(kind) + "/" + std::to_string(n);
  benchmark::RegisterBenchmark(("BM_" + prefix + "Painter" + suffix).c_str(), painterBenchmark,
    kind, n)
    ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(("BM_" + prefix + "PainterRef_BspOrder" + suffix).c_str(),
    bspOrderBenchmark, kind, n)
    ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(("BM_" + prefix + "PainterRef_BspIncremental" + suffix).c_str(),
    bspIncrementalBenchmark, kind, n)
    ->Unit(benchmark::kMillisecond);
}

int registerAll()
{
  // Smoke: tiny, runs in ctest.
  registerTriple("Smoke_", Kind::Grid, 2000);
  registerTriple("Smoke_", Kind::Sphere, 2000);
  registerTriple("", Kind::Grid, 10000);
  registerTriple("", Kind::Grid, 100000);
  registerTriple("", Kind::Sphere, 10000);
  return 0;
}

const int registered = registerAll();

} // namespace

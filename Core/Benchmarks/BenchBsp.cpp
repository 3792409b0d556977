// BSP core benchmarks: build, full order and incremental order at 10k / 100k / 1M triangles of
// three scenes:
// - "sphere": an axis-aligned UV sphere (the convex worst case of a polygon-aligned BSP; its
//   latitude rings line up with axis-aligned free planes),
// - "rotated": the same sphere turned by a generic rotation, so no axis plane runs along a ring,
// - "grid": scenes::sphereGrid(4) with trianglesPerSphereFor(n), 64 overlapping spheres (the
//   standard hard translucency scene).
// Names are BM_<What>/<scene>/<triangles>[/threads:<t>]. `--benchmark_filter=Smoke` runs a small
// subset in well under a second.
// BM_BspBuild/bunny/threads:<t> builds the Stanford bunny (69,451 triangles) from the binary STL
// that scripts/fetch-data.sh puts in ${SCENEVIS_DATA_DIR:-~/.cache/scenevis-data} (key
// bunny-stl of its manifest.txt); it is skipped when the file is absent.
// BM_BspLeafOrder/<model>/leaf:<n> (issue 15 item 2): full order per view of a tree built with
// BuildConfig::orderedLeafSize = n (0: no leaves), 24 views around the model (15-degree steps,
// 20 degrees up, at 1.5 bounding diagonals); counters give fragments stored and drawn (mean over
// the 24 views) per input polygon and the leaves that fell back per view. Models: the bunny, and
// the 2CylinderEngine as a binary STL named by SCENEVIS_ENGINE_STL (BENCHMARKS.md says how it is
// made from the glb).
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/Scenes.h"

#include "../Testing/PolygonSoups.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace
{

using namespace scenevis;

using testsupport::uvSphere;

/// Path of manifest key `key` in the data cache, or "" when the manifest lacks it.
std::string dataFile(const std::string& key)
{
  const char* dir = std::getenv("SCENEVIS_DATA_DIR");
  const char* home = std::getenv("HOME");
  const std::string root =
    dir ? std::string(dir) : std::string(home ? home : ".") + "/.cache/scenevis-data";
  std::ifstream manifest(root + "/manifest.txt");
  std::string line;
  while (std::getline(manifest, line))
  {
    if (line.rfind(key + "=", 0) == 0)
    {
      return root + "/" + line.substr(key.size() + 1);
    }
  }
  return {};
}

/// Binary STL: 80-byte header, uint32 count, then per triangle 12 floats + uint16. Points with
/// bit-identical coordinates are merged. Empty mesh when the file is absent or malformed.
PolygonMesh loadBinaryStl(const std::string& path)
{
  PolygonMesh mesh;
  std::ifstream in(path, std::ios::binary);
  char header[80];
  std::uint32_t count = 0;
  if (!in.read(header, 80) || !in.read(reinterpret_cast<char*>(&count), 4))
  {
    return mesh;
  }
  std::map<std::array<float, 3>, std::uint32_t> ids;
  for (std::uint32_t t = 0; t < count; ++t)
  {
    char record[50];
    if (!in.read(record, 50))
    {
      return PolygonMesh{};
    }
    std::uint32_t tri[3];
    for (int k = 0; k < 3; ++k)
    {
      std::array<float, 3> p;
      std::memcpy(p.data(), record + 12 + 12 * k, 12);
      auto it = ids.find(p);
      if (it == ids.end())
      {
        it = ids.emplace(p, mesh.addPoint({ p[0], p[1], p[2] })).first;
      }
      tri[k] = it->second;
    }
    mesh.addPolygon(tri, 3);
  }
  return mesh;
}

/// The binary STL of a model: a manifest key, or "env:<VARIABLE>" holding a path.
PolygonMesh loadModel(const std::string& key)
{
  std::string path;
  if (key.rfind("env:", 0) == 0)
  {
    const char* value = std::getenv(key.substr(4).c_str());
    path = value ? value : "";
  }
  else
  {
    path = dataFile(key);
  }
  return path.empty() ? PolygonMesh{} : loadBinaryStl(path);
}

struct LeafFixture
{
  PolygonMesh mesh;
  bsp::Tree tree;
  std::vector<View> views;
};

/// Built once per (model, leaf size); empty mesh when the model is absent.
const LeafFixture& leafFixture(const std::string& key, std::uint32_t leafSize)
{
  static std::map<std::pair<std::string, std::uint32_t>, std::unique_ptr<LeafFixture>> cache;
  auto& slot = cache[{ key, leafSize }];
  if (!slot)
  {
    slot = std::make_unique<LeafFixture>();
    slot->mesh = loadModel(key);
    if (slot->mesh.polygonCount() > 0)
    {
      bsp::BuildConfig config;
      config.orderedLeafSize = leafSize;
      slot->tree = bsp::build(slot->mesh, config);
      const Box bounds = slot->mesh.bounds();
      const double radius = 1.5 * bounds.diagonal();
      const double e = 20.0 * 3.14159265358979323846 / 180.0;
      for (int k = 0; k < 24; ++k)
      {
        const double a = k * 15.0 * 3.14159265358979323846 / 180.0;
        slot->views.push_back(View::perspective(bounds.center() +
          glm::dvec3(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)) * radius));
      }
    }
  }
  return *slot;
}

void leafOrderBenchmark(benchmark::State& state, const std::string& key, std::uint32_t leafSize)
{
  const LeafFixture& f = leafFixture(key, leafSize);
  if (f.mesh.polygonCount() == 0)
  {
    state.SkipWithError("model not available (see the file comment)");
    return;
  }
  std::vector<std::uint32_t> result;
  std::size_t view = 0;
  for (auto _ : state)
  {
    bsp::order(f.tree, f.views[view], bsp::Direction::BackToFront, result);
    benchmark::DoNotOptimize(result.data());
    view = view + 1 == f.views.size() ? 0 : view + 1;
  }
  double drawn = 0.0;
  double fallbacks = 0.0;
  for (const View& v : f.views)
  {
    bsp::OrderStatistics statistics;
    bsp::order(f.tree, v, bsp::Direction::BackToFront, result, &statistics);
    drawn += static_cast<double>(result.size());
    fallbacks += static_cast<double>(statistics.leavesFallenBack);
  }
  const double input = static_cast<double>(f.mesh.polygonCount());
  const double views = static_cast<double>(f.views.size());
  const bsp::BuildStatistics& st = f.tree.statistics;
  state.counters["stored/input"] = static_cast<double>(st.fragments) / input;
  state.counters["drawn/input"] = drawn / views / input;
  state.counters["noCycle/input"] = static_cast<double>(st.fragmentsWithoutFallbacks) / input;
  state.counters["leaves"] = static_cast<double>(st.orderedLeaves);
  state.counters["fallbacks/view"] = fallbacks / views;
  state.counters["treeBytes/tri"] = static_cast<double>(st.memoryBytes) / input;
  state.counters["build_s"] = st.buildSeconds;
}

void modelBuildBenchmark(benchmark::State& state, const std::string& key, int threads)
{
  const std::string path = dataFile(key);
  const PolygonMesh mesh = path.empty() ? PolygonMesh{} : loadBinaryStl(path);
  if (mesh.polygonCount() == 0)
  {
    state.SkipWithError("model not fetched (scripts/fetch-data.sh)");
    return;
  }
  bsp::BuildConfig config;
  config.threads = threads;
  bsp::Tree tree;
  for (auto _ : state)
  {
    tree = bsp::build(mesh, config);
    benchmark::DoNotOptimize(tree.root);
  }
  const double input = static_cast<double>(mesh.polygonCount());
  state.counters["triangles"] = input;
  state.counters["fragments/input"] = static_cast<double>(tree.fragments.size()) / input;
  state.counters["splits"] = static_cast<double>(tree.statistics.splits);
  state.counters["treeBytes/tri"] = static_cast<double>(tree.statistics.memoryBytes) / input;
  state.counters["depth"] = static_cast<double>(tree.statistics.depth);
}

enum class SceneKind
{
  Sphere,
  Rotated,
  Grid
};

const char* sceneName(SceneKind kind)
{
  return kind == SceneKind::Sphere ? "sphere" : (kind == SceneKind::Rotated ? "rotated" : "grid");
}

/// Turns every point by a fixed generic rotation (axis (1, 2, 3), 0.7 rad; Rodrigues' formula).
void rotate(PolygonMesh& mesh)
{
  const glm::dvec3 k = glm::normalize(glm::dvec3(1.0, 2.0, 3.0));
  const double c = std::cos(0.7);
  const double s = std::sin(0.7);
  for (glm::dvec3& p : mesh.points)
  {
    p = p * c + glm::cross(k, p) * s + k * glm::dot(k, p) * (1.0 - c);
  }
}

PolygonMesh makeScene(SceneKind kind, std::size_t triangles)
{
  switch (kind)
  {
    case SceneKind::Sphere:
      return uvSphere(triangles);
    case SceneKind::Rotated:
    {
      PolygonMesh mesh = uvSphere(triangles);
      rotate(mesh);
      return mesh;
    }
    default:
      return scenes::sphereGrid(4, 0.8, 1.0, scenes::trianglesPerSphereFor(triangles)).mesh;
  }
}

/// Orbit radius: three times the scene's bounding radius (3 for the unit sphere).
double orbitRadius(const PolygonMesh& mesh)
{
  return 1.5 * mesh.bounds().diagonal() / std::sqrt(3.0);
}

struct Fixture
{
  PolygonMesh mesh;
  bsp::Tree tree;
  double radius = 3.0;
};

/// Built once per scene and size and shared by the order benchmarks.
const Fixture& fixture(SceneKind kind, std::size_t triangles)
{
  static std::map<std::pair<int, std::size_t>, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[{ static_cast<int>(kind), triangles }];
  if (!slot)
  {
    slot = std::make_unique<Fixture>();
    slot->mesh = makeScene(kind, triangles);
    slot->radius = orbitRadius(slot->mesh);
    slot->tree = bsp::build(slot->mesh);
  }
  return *slot;
}

/// Eye on a 20-degree-elevated orbit of radius `radius` around the origin.
View orbitView(double degrees, double radius)
{
  const double a = degrees * 3.14159265358979323846 / 180.0;
  const double e = 20.0 * 3.14159265358979323846 / 180.0;
  return View::perspective(
    glm::dvec3(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)) * radius);
}

void buildBenchmark(benchmark::State& state, SceneKind kind, std::size_t triangles, int threads)
{
  const PolygonMesh mesh = makeScene(kind, triangles);
  bsp::BuildConfig config;
  config.threads = threads;
  bsp::Tree tree;
  for (auto _ : state)
  {
    tree = bsp::build(mesh, config);
    benchmark::DoNotOptimize(tree.root);
  }
  bsp::IncrementalOrder incremental(tree, bsp::Direction::BackToFront);
  incremental.update(orbitView(0.0, orbitRadius(mesh)));
  const double input = static_cast<double>(mesh.polygonCount());
  state.counters["triangles"] = input;
  state.counters["fragments/input"] = static_cast<double>(tree.fragments.size()) / input;
  state.counters["bytes/triangle"] =
    static_cast<double>(tree.statistics.memoryBytes + incremental.memoryBytes()) / input;
  state.counters["treeBytes/tri"] = static_cast<double>(tree.statistics.memoryBytes) / input;
  state.counters["incrBytes/tri"] = static_cast<double>(incremental.memoryBytes()) / input;
  state.counters["depth"] = static_cast<double>(tree.statistics.depth);
  state.counters["nodes"] = static_cast<double>(tree.statistics.nodes);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.polygonCount()));
}

void orderBenchmark(benchmark::State& state, SceneKind kind, std::size_t triangles)
{
  const Fixture& f = fixture(kind, triangles);
  std::vector<std::uint32_t> result;
  double angle = 0.0;
  for (auto _ : state)
  {
    bsp::order(f.tree, orbitView(angle, f.radius), bsp::Direction::BackToFront, result);
    benchmark::DoNotOptimize(result.data());
    angle += 1.0;
  }
  state.counters["fragments"] = static_cast<double>(f.tree.fragments.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.tree.fragments.size()));
}

/// One update per 1-degree orbit step (the first, full, update happens before timing).
void incrementalBenchmark(benchmark::State& state, SceneKind kind, std::size_t triangles)
{
  const Fixture& f = fixture(kind, triangles);
  bsp::IncrementalOrder incremental(f.tree, bsp::Direction::BackToFront);
  double angle = 0.0;
  incremental.update(orbitView(angle, f.radius));
  double visited = 0;
  double flipped = 0;
  double moved = 0;
  for (auto _ : state)
  {
    angle += 1.0;
    const auto& s = incremental.update(orbitView(angle, f.radius));
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

/// Registers BM_<what>/<scene>/<triangles>[/threads:<t>] for every combination.
int registerAll()
{
  const SceneKind all[] = { SceneKind::Sphere, SceneKind::Rotated, SceneKind::Grid };
  // Smoke: tiny, runs in ctest.
  for (SceneKind kind : { SceneKind::Sphere, SceneKind::Grid })
  {
    const std::string suffix = std::string("/") + sceneName(kind) + "/2000";
    benchmark::RegisterBenchmark(
      ("BM_Smoke_BspBuild" + suffix).c_str(), buildBenchmark, kind, std::size_t{ 2000 }, 1)
      ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(
      ("BM_Smoke_BspOrder" + suffix).c_str(), orderBenchmark, kind, std::size_t{ 2000 })
      ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("BM_Smoke_BspIncremental" + suffix).c_str(),
      incrementalBenchmark, kind, std::size_t{ 2000 })
      ->Unit(benchmark::kMicrosecond);
  }
  const std::size_t sizes[] = { 10000, 100000, 1000000 };
  for (SceneKind kind : all)
  {
    for (std::size_t n : sizes)
    {
      for (int threads : { 1, 2 })
      {
        benchmark::RegisterBenchmark((std::string("BM_BspBuild/") + sceneName(kind) + "/" +
                                       std::to_string(n) + "/threads:" + std::to_string(threads))
                                       .c_str(),
          buildBenchmark, kind, n, threads)
          ->Unit(benchmark::kMillisecond)
          ->MeasureProcessCPUTime();
      }
    }
  }
  for (int threads : { 1, 2 })
  {
    benchmark::RegisterBenchmark(
      ("BM_BspBuild/bunny/threads:" + std::to_string(threads)).c_str(), modelBuildBenchmark,
      std::string("bunny-stl"), threads)
      ->Unit(benchmark::kMillisecond)
      ->MeasureProcessCPUTime();
  }
  for (const char* model : { "bunny", "engine" })
  {
    const std::string key = model == std::string("bunny") ? "bunny-stl" : "env:SCENEVIS_ENGINE_STL";
    for (std::uint32_t leafSize : { 0u, 8u, 16u, 32u, 64u, 128u, 256u })
    {
      benchmark::RegisterBenchmark(
        (std::string("BM_BspLeafOrder/") + model + "/leaf:" + std::to_string(leafSize)).c_str(),
        leafOrderBenchmark, key, leafSize)
        ->Unit(benchmark::kMillisecond);
    }
  }
  for (SceneKind kind : all)
  {
    for (std::size_t n : sizes)
    {
      const std::string suffix = std::string("/") + sceneName(kind) + "/" + std::to_string(n);
      benchmark::RegisterBenchmark(("BM_BspOrder" + suffix).c_str(), orderBenchmark, kind, n)
        ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(
        ("BM_BspIncrementalOrbit1Deg" + suffix).c_str(), incrementalBenchmark, kind, n)
        ->Unit(benchmark::kMillisecond);
    }
  }
  return 0;
}

const int registered = registerAll();

} // namespace

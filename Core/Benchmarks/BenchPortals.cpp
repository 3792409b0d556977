// Portal culling benchmarks: per-frame cull time and the fraction of triangles culled for eyes
// inside the generated building, for each mode (screen rectangles, exact frustum, PVS lookup,
// frustum only), plus graph and PVS build times, and the eye's room lookup (grid vs. the linear
// scan over rooms and portals it replaced). One object per room (its geometry's bounds and
// triangle count). `--benchmark_filter=Smoke` runs a tiny building quickly.
//
//   build-portal/bin/scenevis_core_bench --benchmark_filter='Portal'
#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalGraph.h"
#include "scenevis/PortalPvs.h"
#include "scenevis/PortalTraversal.h"
#include "scenevis/Scenes.h"

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <tuple>

namespace
{
using namespace scenevis;
using namespace scenevis::portals;

struct PortalFixture
{
  scenes::BuildingScene building;
  PortalGraph graph;
  PortalPvs pvs;
  double pvsSeconds = 0.0;
  std::vector<PortalObject> objects;
  std::vector<PortalView> views;
};

/// Building, graph, PVS, one object per node and 64 indoor views, cached per size.
const PortalFixture& fixture(int floors, int rx, int ry)
{
  static std::map<std::tuple<int, int, int>, std::unique_ptr<PortalFixture>> cache;
  auto& slot = cache[std::make_tuple(floors, rx, ry)];
  if (slot)
  {
    return *slot;
  }
  slot = std::make_unique<PortalFixture>();
  PortalFixture& f = *slot;
  f.building = scenes::building(floors, rx, ry, 1);
  f.graph = PortalGraph::build(cellSceneOf(f.building));
  const auto t0 = std::chrono::steady_clock::now();
  f.pvs = PortalPvs::compute(f.graph);
  f.pvsSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  f.objects.resize(static_cast<std::size_t>(f.graph.nodeCount()));
  const PolygonMesh& mesh = f.building.mesh;
  for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
  {
    PortalObject& o = f.objects[static_cast<std::size_t>(f.graph.nodeOf(f.building.room[i]))];
    for (std::uint32_t k = 0; k < mesh.polygonSize(i); ++k)
    {
      o.bounds.extend(mesh.points[mesh.polygon(i)[k]]);
    }
    o.triangles += mesh.polygonSize(i) - 2;
  }
  for (std::int32_t n = 0; n < f.graph.nodeCount(); ++n)
  {
    f.objects[static_cast<std::size_t>(n)].node = n;
  }
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  while (f.views.size() < 64)
  {
    const Box& cell = f.building.rooms[rng() % f.building.rooms.size()].bounds;
    const glm::dvec3 eye(cell.lo.x + 0.5 + u(rng) * (scenes::kRoomSizeX - 1.0),
      cell.lo.y + 0.5 + u(rng) * 3.0, cell.lo.z + 1.6);
    if (f.graph.locate(eye, 0.0).nodes.empty())
    {
      continue; // in furniture
    }
    const double yaw = u(rng) * 6.283185307;
    PortalView v;
    v.eye = eye;
    v.clipFromWorld = glm::perspective(glm::radians(60.0), 4.0 / 3.0, 0.05, 500.0) *
      glm::lookAt(eye, eye + glm::dvec3(std::cos(yaw), std::sin(yaw), -0.1), glm::dvec3(0, 0, 1));
    f.views.push_back(v);
  }
  return f;
}

enum Mode
{
  kRectangles = 0,
  kExact,
  kPvs,
  kFrustumOnly
};

void runFrames(benchmark::State& state, int floors, int rx, int ry)
{
  const PortalFixture& f = fixture(floors, rx, ry);
  const auto mode = static_cast<Mode>(state.range(0));
  PortalTraversal t;
  TraversalOptions options;
  options.mode = mode == kRectangles ? NarrowingMode::ScreenRectangles : NarrowingMode::ExactFrustum;
  std::vector<std::uint8_t> visible;
  std::size_t frame = 0;
  double culled = 0.0, rooms = 0.0, portals = 0.0;
  for (auto _ : state)
  {
    const PortalView& view = f.views[frame++ % f.views.size()];
    switch (mode)
    {
      case kRectangles:
      case kExact:
        t.run(f.graph, view, options);
        break;
      case kPvs:
        t.runPvs(f.graph, f.pvs, view, options);
        break;
      case kFrustumOnly:
        t.runFrustumOnly(f.graph, view);
        break;
    }
    t.cullObjects(f.objects, visible);
    benchmark::DoNotOptimize(visible.data());
    const FrameStats& s = t.stats();
    culled += 1.0 - static_cast<double>(s.trianglesDrawn) / static_cast<double>(s.trianglesTotal);
    rooms += static_cast<double>(s.objectsDrawn);
    portals += static_cast<double>(s.portalsTraversed);
  }
  const double frames = static_cast<double>(state.iterations());
  state.counters["tri_culled_pct"] = 100.0 * culled / frames;
  state.counters["rooms_drawn"] = rooms / frames;
  state.counters["portals_traversed"] = portals / frames;
  state.counters["rooms"] = f.graph.roomCount();
  state.counters["pvs_build_s"] = f.pvsSeconds;
  state.SetLabel(mode == kRectangles ? "rectangles"
      : mode == kExact               ? "exact"
      : mode == kPvs                 ? "pvs"
                                     : "frustum-only");
}

void BM_PortalFrame1000Rooms(benchmark::State& state)
{
  runFrames(state, 10, 10, 10);
}
BENCHMARK(BM_PortalFrame1000Rooms)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

void BM_Smoke_PortalFrame(benchmark::State& state)
{
  runFrames(state, 1, 3, 3);
}
BENCHMARK(BM_Smoke_PortalFrame)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

/// The eye's rooms for the views' eyes: PortalGraph::locate() (grid) or the linear scan it
/// replaced (every room's inside() test, every portal's distance), same answers.
void locateEyes(benchmark::State& state, bool linear)
{
  const PortalFixture& f = fixture(10, 10, 10);
  const PortalGraph& g = f.graph;
  const double reach = 0.07; // the near-plane corners of the views (0.05, 60 degrees, 4:3)
  std::size_t frame = 0, found = 0;
  std::vector<std::int32_t> nodes;
  for (auto _ : state)
  {
    const glm::dvec3& eye = f.views[frame++ % f.views.size()].eye;
    nodes.clear();
    if (linear)
    {
      for (std::int32_t r = 0; r < g.roomCount(); ++r)
      {
        if (g.inside(r, eye))
        {
          nodes.push_back(r);
        }
      }
      for (const GraphPortal& p : g.portals())
      {
        const Box& b = p.bounds;
        if (eye.x < b.lo.x - reach || eye.y < b.lo.y - reach || eye.z < b.lo.z - reach ||
          eye.x > b.hi.x + reach || eye.y > b.hi.y + reach || eye.z > b.hi.z + reach)
        {
          continue;
        }
        if (geometry::distanceToConvex(p.hull, glm::dvec3(p.plane), eye) <= reach)
        {
          nodes.push_back(p.nodeA);
          nodes.push_back(p.nodeB);
        }
      }
    }
    else
    {
      nodes = g.locate(eye, reach).nodes;
    }
    found += nodes.size();
    benchmark::DoNotOptimize(nodes.data());
  }
  state.counters["nodes_per_eye"] =
    static_cast<double>(found) / static_cast<double>(state.iterations());
  state.counters["rooms"] = g.roomCount();
  state.SetLabel(linear ? "linear scan" : "grid");
}

void BM_PortalLocate1000Rooms(benchmark::State& state)
{
  locateEyes(state, false);
}
BENCHMARK(BM_PortalLocate1000Rooms)->Unit(benchmark::kMicrosecond);

void BM_PortalLocateLinearScan1000Rooms(benchmark::State& state)
{
  locateEyes(state, true);
}
BENCHMARK(BM_PortalLocateLinearScan1000Rooms)->Unit(benchmark::kMicrosecond);

void BM_PortalGraphBuild1000Rooms(benchmark::State& state)
{
  const PortalFixture& f = fixture(10, 10, 10);
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(PortalGraph::build(cellSceneOf(f.building)).portals().size());
  }
}
BENCHMARK(BM_PortalGraphBuild1000Rooms)->Unit(benchmark::kMillisecond);

void BM_Smoke_PortalPvs(benchmark::State& state)
{
  const PortalFixture& f = fixture(1, 3, 3);
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(PortalPvs::compute(f.graph).nodeCount());
  }
}
BENCHMARK(BM_Smoke_PortalPvs)->Unit(benchmark::kMillisecond);

} // namespace

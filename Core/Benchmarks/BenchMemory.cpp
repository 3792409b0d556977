// Memory of the core's spatial structures, measured rather than estimated: this executable
// replaces the global operator new/delete with counting versions (which is why it is its own
// binary, scenevis_core_memory_bench: the counters would slow down every timed benchmark of
// scenevis_core_bench). Each benchmark builds one structure once and reports
// - peakBytes: the most heap held at any moment of the build (scratch included), above what was
//   held before it started (the input is not counted),
// - retainedBytes: what is still held once the build returned, i.e. the structure itself,
// per input triangle (and per object / room where that is the natural unit). The estimate the
// BSP keeps of itself (Tree::statistics.memoryBytes) is printed beside the measured figure.
// Bytes are malloc_usable_size, i.e. what the allocator really handed out (allocator headers
// of ~8 bytes per block are not included).
//
// Scenes: BSP tree + incremental order of a UV sphere, the same sphere rotated, and 64
// overlapping spheres, at 100k and 1M triangles, built on 1 and 2 threads (target <= 200 bytes
// per input triangle at 1M); BVH (with normal cones) over 100k CAD parts; portal graph and PVS
// of the 1000-room building. `--benchmark_filter=Smoke` runs small sizes in well under a second.
//
//   build/bin/scenevis_core_memory_bench --benchmark_filter='1000000|Bvh/cad/100000|1000rooms'
//
// Timings printed beside the counters are those of a single build with counting on: use
// scenevis_core_bench for times.
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/Bvh.h"
#include "scenevis/NormalCone.h"
#include "scenevis/PortalGraph.h"
#include "scenevis/PortalPvs.h"
#include "scenevis/Scenes.h"

#include "../Testing/PolygonSoups.h"

#include <benchmark/benchmark.h>

#include <malloc.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>

// ---------------------------------------------------------------------------------------------
// Counting allocator. Relaxed atomics: the BSP builder allocates from several threads; the peak
// is a compare-exchange maximum, so it is exact for any interleaving.
namespace
{
std::atomic<std::int64_t> liveBytes{ 0 };
std::atomic<std::int64_t> peakBytes{ 0 };
std::atomic<std::int64_t> allocations{ 0 };

void* counted(void* p)
{
  if (!p)
  {
    throw std::bad_alloc();
  }
  const auto size = static_cast<std::int64_t>(malloc_usable_size(p));
  const std::int64_t now = liveBytes.fetch_add(size, std::memory_order_relaxed) + size;
  std::int64_t peak = peakBytes.load(std::memory_order_relaxed);
  while (now > peak && !peakBytes.compare_exchange_weak(peak, now, std::memory_order_relaxed))
  {
  }
  allocations.fetch_add(1, std::memory_order_relaxed);
  return p;
}

void release(void* p) noexcept
{
  if (p)
  {
    liveBytes.fetch_sub(
      static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
    std::free(p);
  }
}

void* alignedAllocation(std::size_t size, std::align_val_t align)
{
  const auto a = std::max<std::size_t>(static_cast<std::size_t>(align), sizeof(void*));
  void* p = nullptr;
  if (posix_memalign(&p, a, size == 0 ? 1 : size) != 0)
  {
    p = nullptr;
  }
  return counted(p);
}
} // namespace

void* operator new(std::size_t size)
{
  return counted(std::malloc(size == 0 ? 1 : size));
}
void* operator new[](std::size_t size)
{
  return counted(std::malloc(size == 0 ? 1 : size));
}
void* operator new(std::size_t size, std::align_val_t align)
{
  return alignedAllocation(size, align);
}
void* operator new[](std::size_t size, std::align_val_t align)
{
  return alignedAllocation(size, align);
}
void operator delete(void* p) noexcept
{
  release(p);
}
void operator delete[](void* p) noexcept
{
  release(p);
}
void operator delete(void* p, std::size_t) noexcept
{
  release(p);
}
void operator delete[](void* p, std::size_t) noexcept
{
  release(p);
}
void operator delete(void* p, std::align_val_t) noexcept
{
  release(p);
}
void operator delete[](void* p, std::align_val_t) noexcept
{
  release(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept
{
  release(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept
{
  release(p);
}

namespace
{
using namespace scenevis;

/// Heap held above a baseline: construct before the build, read after it.
class HeapProbe
{
public:
  HeapProbe()
    : base_(liveBytes.load())
    , allocationsBefore_(allocations.load())
  {
    peakBytes.store(base_);
  }
  double peak() const { return static_cast<double>(peakBytes.load() - base_); }
  double retained() const { return static_cast<double>(liveBytes.load() - base_); }
  double allocationCount() const
  {
    return static_cast<double>(allocations.load() - allocationsBefore_);
  }

private:
  std::int64_t base_;
  std::int64_t allocationsBefore_;
};

/// The UV sphere of BenchBsp.cpp and the tests, so the figures match.
using testsupport::uvSphere;

enum class SceneKind
{
  Sphere,
  Rotated,
  Grid
};

PolygonMesh makeScene(SceneKind kind, std::size_t triangles)
{
  if (kind == SceneKind::Grid)
  {
    return scenes::sphereGrid(4, 0.8, 1.0, scenes::trianglesPerSphereFor(triangles)).mesh;
  }
  PolygonMesh mesh = uvSphere(triangles);
  if (kind == SceneKind::Rotated)
  {
    // A generic rotation (axis (1, 2, 3), 0.7 rad), so no axis plane runs along a ring.
    const glm::dvec3 k = glm::normalize(glm::dvec3(1.0, 2.0, 3.0));
    const double c = std::cos(0.7);
    const double s = std::sin(0.7);
    for (glm::dvec3& p : mesh.points)
    {
      p = p * c + glm::cross(k, p) * s + k * glm::dot(k, p) * (1.0 - c);
    }
  }
  return mesh;
}

/// BSP tree plus the incremental order after its first update: what vtkBSPSortFilter keeps.
/// @p threads as in bsp::BuildConfig (vtkBSPSortFilter builds on every core): the tree is the
/// same for any count, the scratch held at the peak is not.
void bspMemory(benchmark::State& state, SceneKind kind, std::size_t triangles, int threads)
{
  const PolygonMesh mesh = makeScene(kind, triangles);
  const double input = static_cast<double>(mesh.polygonCount());
  bsp::BuildConfig config;
  config.threads = threads;
  for (auto _ : state)
  {
    HeapProbe probe;
    bsp::Tree tree = bsp::build(mesh, config);
    const double builtPeak = probe.peak();
    const double treeRetained = probe.retained();
    bsp::IncrementalOrder incremental(tree, bsp::Direction::BackToFront);
    incremental.update(View::perspective({ 2.5, 1.0, 1.2 }));
    benchmark::DoNotOptimize(incremental.order().data());
    state.counters["peakBytes/tri"] = probe.peak() / input;
    state.counters["buildPeakBytes/tri"] = builtPeak / input;
    state.counters["retainedBytes/tri"] = probe.retained() / input;
    state.counters["treeBytes/tri"] = treeRetained / input;
    state.counters["treeEstimate/tri"] = static_cast<double>(tree.statistics.memoryBytes) / input;
    state.counters["fragments/input"] = static_cast<double>(tree.fragments.size()) / input;
    state.counters["allocs"] = probe.allocationCount();
  }
  state.counters["triangles"] = input;
}

/// BVH over the parts of a CAD assembly, with a normal cone and a triangle count per part.
void bvhMemory(benchmark::State& state, std::size_t parts)
{
  const scenes::Scene scene = scenes::cadAssembly(parts, 16, 1);
  culling::BoxArrays boxes;
  for (const auto& part : scene.parts)
  {
    boxes.push_back(part.bounds);
  }
  std::vector<std::uint32_t> trianglesOf(scene.parts.size(), 0);
  std::vector<std::size_t> first(scene.parts.size(), 0);
  for (std::size_t c = scene.part.size(); c-- > 0;)
  {
    ++trianglesOf[scene.part[c]];
    first[scene.part[c]] = c; // parts are contiguous runs of polygons
  }
  std::vector<culling::NormalCone> cones(scene.parts.size());
  for (std::size_t p = 0; p < cones.size(); ++p)
  {
    cones[p] = culling::normalConeOf(scene.mesh, first[p], trianglesOf[p]);
  }
  const double triangles = static_cast<double>(scene.mesh.polygonCount());
  const double objects = static_cast<double>(boxes.size());
  for (auto _ : state)
  {
    HeapProbe probe;
    culling::Bvh bvh;
    bvh.build(boxes, culling::BuildMethod::BinnedSah, 4, &trianglesOf);
    for (std::uint32_t p = 0; p < cones.size(); ++p)
    {
      bvh.setNormalCone(p, cones[p]);
    }
    bvh.refit();
    benchmark::DoNotOptimize(bvh.nodes().data());
    state.counters["peakBytes/tri"] = probe.peak() / triangles;
    state.counters["retainedBytes/tri"] = probe.retained() / triangles;
    state.counters["retainedBytes/object"] = probe.retained() / objects;
    state.counters["peakBytes/object"] = probe.peak() / objects;
  }
  state.counters["triangles"] = triangles;
  state.counters["objects"] = objects;
}

/// Portal graph of a building, then its PVS; each measured on its own.
void portalMemory(benchmark::State& state, int floors, int roomsX, int roomsY)
{
  const scenes::BuildingScene building = scenes::building(floors, roomsX, roomsY, 1);
  const portals::CellSceneInput input = portals::cellSceneOf(building);
  const double triangles = static_cast<double>(scenes::triangleCount(building.mesh));
  const double rooms = static_cast<double>(building.rooms.size());
  for (auto _ : state)
  {
    HeapProbe graphProbe;
    portals::PortalGraph graph = portals::PortalGraph::build(input);
    state.counters["graphPeakBytes/room"] = graphProbe.peak() / rooms;
    state.counters["graphBytes/room"] = graphProbe.retained() / rooms;
    HeapProbe pvsProbe;
    portals::PortalPvs pvs = portals::PortalPvs::compute(graph);
    benchmark::DoNotOptimize(pvs.nodeCount());
    state.counters["pvsPeakBytes/room"] = pvsProbe.peak() / rooms;
    state.counters["pvsBytes/room"] = pvsProbe.retained() / rooms;
    state.counters["graph+pvsBytes/tri"] = graphProbe.retained() / triangles;
    state.counters["portals"] = static_cast<double>(graph.portals().size());
  }
  state.counters["rooms"] = rooms;
  state.counters["triangles"] = triangles;
}

int registerAll()
{
  struct Named
  {
    const char* name;
    SceneKind kind;
  };
  const Named kinds[] = { { "sphere", SceneKind::Sphere }, { "rotated", SceneKind::Rotated },
    { "grid", SceneKind::Grid } };
  for (const Named& k : kinds)
  {
    for (std::size_t n : { std::size_t{ 100000 }, std::size_t{ 1000000 } })
    {
      for (int threads : { 1, 2 })
      {
        benchmark::RegisterBenchmark((std::string("BM_MemoryBsp/") + k.name + "/" +
                                       std::to_string(n) + "/threads:" + std::to_string(threads))
                                       .c_str(),
          bspMemory, k.kind, n, threads)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
      }
    }
  }
  benchmark::RegisterBenchmark(
    "BM_Smoke_MemoryBsp/grid/2000", bspMemory, SceneKind::Grid, std::size_t{ 2000 }, 1)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_MemoryBvh/cad/100000", bvhMemory, std::size_t{ 100000 })
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_Smoke_MemoryBvh/cad/200", bvhMemory, std::size_t{ 200 })
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_MemoryPortals/1000rooms", portalMemory, 10, 10, 10)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_Smoke_MemoryPortals/9rooms", portalMemory, 1, 3, 3)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
  return 0;
}
const int registered = registerAll();
} // namespace

BENCHMARK_MAIN();

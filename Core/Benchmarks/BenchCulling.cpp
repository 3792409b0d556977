// Culling core benchmarks: BVH frustum cull of 100k CAD part boxes (binned SAH vs median build,
// nodes visited as a counter: the measurement behind choosing the BVH build) against the flat
// stateless cull of the same boxes; normal-cone cull fraction on clusters of closed CAD parts.
// `--benchmark_filter=Smoke` runs a small subset quickly.
#include "scenevis/Bvh.h"
#include "scenevis/NormalCone.h"
#include "scenevis/Scenes.h"

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <map>
#include <memory>

namespace
{
using namespace scenevis;
using namespace scenevis::culling;

/// Boxes of the parts of a CAD assembly (the real size mix), cached per size.
const BoxArrays& cadBoxes(std::size_t parts)
{
  static std::map<std::size_t, std::unique_ptr<BoxArrays>> cache;
  auto& slot = cache[parts];
  if (!slot)
  {
    const scenes::Scene scene = scenes::cadAssembly(parts, 16, 1);
    slot = std::make_unique<BoxArrays>();
    for (const auto& part : scene.parts)
    {
      slot->push_back(part.bounds);
    }
  }
  return *slot;
}

/// 16 views on a slow orbit: overviews and close-ups alternate.
std::vector<CullParams> views(const BoxArrays& boxes)
{
  Box all;
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    all.extend(boxes.get(i));
  }
  const glm::dvec3 c = all.center();
  const double r = 0.5 * all.diagonal();
  std::vector<CullParams> out;
  for (int i = 0; i < 16; ++i)
  {
    const double t = i * 0.1;
    const double d = (i % 2 ? 0.3 : 1.2) * r;
    const glm::dvec3 eye = c + glm::dvec3(std::cos(t) * d, std::sin(t) * d, 0.5 * d);
    const glm::dvec3 target = c + glm::dvec3(0.1 * r * std::sin(3 * t), 0, 0);
    CullParams p;
    p.frustum = Frustum::fromViewProjection(
      glm::perspective(glm::radians(40.0), 1.5, 0.01 * r, 4 * r) *
      glm::lookAt(eye, target, glm::dvec3(0, 0, 1)));
    p.eye = eye;
    p.viewDirection = glm::normalize(target - eye);
    out.push_back(p);
  }
  return out;
}

void bvhCull(benchmark::State& state, std::size_t n, BuildMethod method)
{
  const BoxArrays& boxes = cadBoxes(n);
  Bvh bvh;
  bvh.build(boxes, method, 4);
  const auto params = views(boxes);
  std::vector<std::uint32_t> visible;
  CullStats stats;
  std::size_t frame = 0, nodes = 0, drawn = 0;
  for (auto _ : state)
  {
    bvh.cull(params[frame++ % params.size()], visible, &stats);
    nodes += stats.nodesVisited;
    drawn += stats.objectsDrawn;
    benchmark::DoNotOptimize(visible.data());
  }
  state.counters["nodes/frame"] = static_cast<double>(nodes) / static_cast<double>(frame);
  state.counters["drawn/frame"] = static_cast<double>(drawn) / static_cast<double>(frame);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

void flatCull(benchmark::State& state, std::size_t n)
{
  const BoxArrays& boxes = cadBoxes(n);
  const auto params = views(boxes);
  std::vector<std::uint8_t> visible(boxes.size());
  std::size_t frame = 0;
  for (auto _ : state)
  {
    cullBoxesFlat(params[frame++ % params.size()].frustum, boxes, visible.data());
    benchmark::DoNotOptimize(visible.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

void BM_CoreBvhFrustumCull_Sah_100k(benchmark::State& s) { bvhCull(s, 100000, BuildMethod::BinnedSah); }
void BM_CoreBvhFrustumCull_Median_100k(benchmark::State& s) { bvhCull(s, 100000, BuildMethod::Median); }
void BM_CoreFlatFrustumCull_100k(benchmark::State& s) { flatCull(s, 100000); }
void BM_Smoke_CoreBvhFrustumCull_1k(benchmark::State& s) { bvhCull(s, 1000, BuildMethod::BinnedSah); }

void BM_CoreBvhBuild_100k(benchmark::State& state)
{
  const BoxArrays& boxes = cadBoxes(100000);
  for (auto _ : state)
  {
    Bvh bvh;
    bvh.build(boxes);
    benchmark::DoNotOptimize(bvh.nodes().data());
  }
}

void BM_CoreBvhRefit_1pctMoved_100k(benchmark::State& state)
{
  BoxArrays boxes = cadBoxes(100000);
  Bvh bvh;
  bvh.build(boxes);
  std::uint32_t next = 0;
  for (auto _ : state)
  {
    for (int k = 0; k < 1000; ++k)
    {
      const std::uint32_t id = (next += 7919) % 100000;
      Box b = boxes.get(id);
      b.lo.x += 0.5;
      b.hi.x += 0.5;
      bvh.update(id, b);
    }
    benchmark::DoNotOptimize(bvh.refit());
  }
}

/// Fraction of 24-triangle clusters of closed CAD parts culled by their normal cones, over eyes
/// around the model (about half the triangles of a closed part face away; a cone culls a cluster
/// only when all of its triangles do).
void normalCones(benchmark::State& state, std::size_t parts)
{
  const scenes::Scene scene = scenes::cadAssembly(parts, 100, 3);
  std::vector<NormalCone> cones;
  std::vector<Box> boxes;
  for (const auto& part : scene.parts)
  {
    for (std::size_t f = part.firstPolygon; f < part.firstPolygon + part.polygonCount; f += 24)
    {
      const std::size_t count = std::min<std::size_t>(24, part.firstPolygon + part.polygonCount - f);
      cones.push_back(normalConeOf(scene.mesh, f, count));
      Box b;
      for (std::size_t i = f; i < f + count; ++i)
      {
        for (std::uint32_t k = 0; k < scene.mesh.polygonSize(i); ++k)
        {
          b.extend(scene.mesh.points[scene.mesh.polygon(i)[k]]);
        }
      }
      boxes.push_back(b);
    }
  }
  const Box all = scene.mesh.bounds();
  std::size_t culled = 0, tested = 0, frame = 0;
  for (auto _ : state)
  {
    const double t = 0.37 * static_cast<double>(frame++);
    const glm::dvec3 eye = all.center() +
      glm::dvec3(std::cos(t), std::sin(t), 0.6) * all.diagonal();
    for (std::size_t i = 0; i < cones.size(); ++i)
    {
      culled += backFacingFromEye(cones[i], boxes[i].center(), 0.5 * boxes[i].diagonal(), eye);
    }
    tested += cones.size();
  }
  state.counters["culled fraction"] = static_cast<double>(culled) / static_cast<double>(tested);
  state.counters["clusters"] = static_cast<double>(cones.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(tested));
}

void BM_CoreNormalConeCullFraction_CadClusters(benchmark::State& s) { normalCones(s, 2000); }
void BM_Smoke_CoreNormalCone(benchmark::State& s) { normalCones(s, 50); }
} // namespace

BENCHMARK(BM_CoreBvhFrustumCull_Sah_100k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CoreBvhFrustumCull_Median_100k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CoreFlatFrustumCull_100k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CoreBvhBuild_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CoreBvhRefit_1pctMoved_100k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CoreNormalConeCullFraction_CadClusters)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Smoke_CoreBvhFrustumCull_1k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Smoke_CoreNormalCone)->Unit(benchmark::kMicrosecond);

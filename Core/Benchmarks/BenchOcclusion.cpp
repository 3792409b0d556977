// The occlusion buffer's two costs, per item: rasterizing occluder triangles and testing occludee
// boxes, at 800x600 (OcclusionBuffer.h).
//  - Raster: closed spheres (outward faces only, with edge neighbours, as vtkOcclusionCuller
//    draws closed meshes) on a 10 x 10 grid facing the camera; triangles per sphere from 80
//    (big triangles: many tiles each) to 20k (sub-pixel triangles: set-up cost only).
//  - Walls: two big triangles covering the screen, the best case per pixel.
//  - Boxes: small boxes behind a full-screen wall (hidden) and in front of it (visible).
// Counters: triangles (or boxes) per second; ns per item is 1e9 / that.
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/Scenes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace
{
using namespace scenevis;
using namespace scenevis::occlusion;

constexpr int kWidth = 800, kHeight = 600;

glm::dmat4 Camera()
{
  return glm::perspective(glm::radians(60.0), double(kWidth) / kHeight, 0.1, 200.0) *
    glm::lookAt(glm::dvec3(0, -30, 0), glm::dvec3(0, 0, 0), glm::dvec3(0, 0, 1));
}

struct Mesh
{
  std::vector<glm::dvec4> clip;
  std::vector<std::uint32_t> indices, neighbors;
  std::size_t triangles = 0;
};

Mesh Spheres(std::size_t trianglesPerSphere)
{
  Mesh m;
  std::vector<double> xyz;
  const glm::dmat4 camera = Camera();
  for (int i = 0; i < 10; ++i)
  {
    for (int k = 0; k < 10; ++k)
    {
      const PolygonMesh s = scenes::sphere(
        glm::dvec3(-13.5 + 3 * i, 2.0 * ((i + k) % 3), -10 + 2.2 * k), 1.4, trianglesPerSphere);
      const auto base = static_cast<std::uint32_t>(m.clip.size());
      for (const glm::dvec3& p : s.points)
      {
        m.clip.push_back(camera * glm::dvec4(p, 1.0));
        xyz.insert(xyz.end(), { p.x, p.y, p.z });
      }
      for (std::size_t t = 0; t < s.polygonCount(); ++t)
      {
        for (std::uint32_t v = 0; v < 3; ++v)
        {
          m.indices.push_back(base + s.polygon(t)[v]);
        }
      }
    }
  }
  m.triangles = m.indices.size() / 3;
  m.neighbors = buildTriangleNeighbors(xyz.data(), m.clip.size(), m.indices.data(), m.triangles);
  return m;
}

void Raster(benchmark::State& state, std::size_t trianglesPerSphere)
{
  const Mesh m = Spheres(trianglesPerSphere);
  MaskedDepthBuffer buffer;
  buffer.resize(kWidth, kHeight);
  buffer.setClipFromWorld(Camera());
  for (auto _ : state)
  {
    buffer.clear();
    buffer.drawTriangles(m.clip.data(), m.clip.size(), m.indices.data(), m.triangles,
      FaceCulling::Back, m.neighbors.data());
    benchmark::DoNotOptimize(buffer.tiles().data());
  }
  state.counters["triangles"] =
    benchmark::Counter(double(m.triangles) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["tiles_updated"] = double(buffer.stats().tilesUpdated);
}

void BM_OcclusionRaster_Spheres_80(benchmark::State& s) { Raster(s, 80); }
void BM_OcclusionRaster_Spheres_1k(benchmark::State& s) { Raster(s, 1000); }
void BM_OcclusionRaster_Spheres_20k(benchmark::State& s) { Raster(s, 20000); }
void BM_Smoke_OcclusionRaster_Spheres(benchmark::State& s) { Raster(s, 200); }
BENCHMARK(BM_OcclusionRaster_Spheres_80)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OcclusionRaster_Spheres_1k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OcclusionRaster_Spheres_20k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Smoke_OcclusionRaster_Spheres)->Unit(benchmark::kMicrosecond);

void BM_OcclusionRaster_FullScreenWall(benchmark::State& state)
{
  const glm::dmat4 camera = Camera();
  const std::vector<glm::dvec4> clip = { camera * glm::dvec4(-100, 5, -100, 1),
    camera * glm::dvec4(100, 5, -100, 1), camera * glm::dvec4(100, 5, 100, 1),
    camera * glm::dvec4(-100, 5, 100, 1) };
  const std::vector<std::uint32_t> indices = { 0, 1, 2, 0, 2, 3 };
  const std::vector<std::uint32_t> neighbors = { kNoNeighbor, kNoNeighbor, 1, 0, kNoNeighbor,
    kNoNeighbor };
  MaskedDepthBuffer buffer;
  buffer.resize(kWidth, kHeight);
  buffer.setClipFromWorld(camera);
  for (auto _ : state)
  {
    buffer.clear();
    buffer.drawTriangles(clip.data(), clip.size(), indices.data(), 2, FaceCulling::None,
      neighbors.data());
    benchmark::DoNotOptimize(buffer.tiles().data());
  }
  state.counters["pixels"] =
    benchmark::Counter(double(kWidth) * kHeight * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_OcclusionRaster_FullScreenWall)->Unit(benchmark::kMicrosecond);

void Boxes(benchmark::State& state, double y)
{
  const glm::dmat4 camera = Camera();
  const std::vector<glm::dvec4> clip = { camera * glm::dvec4(-100, 0, -100, 1),
    camera * glm::dvec4(100, 0, -100, 1), camera * glm::dvec4(100, 0, 100, 1),
    camera * glm::dvec4(-100, 0, 100, 1) };
  const std::vector<std::uint32_t> indices = { 0, 1, 2, 0, 2, 3 };
  MaskedDepthBuffer buffer;
  buffer.resize(kWidth, kHeight);
  buffer.setClipFromWorld(camera);
  buffer.drawTriangles(clip.data(), clip.size(), indices.data(), 2);
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> u(-12, 12);
  std::vector<glm::dvec3> lo(1024);
  for (glm::dvec3& p : lo)
  {
    p = glm::dvec3(u(gen), y + 0.1 * u(gen) * 0.1, u(gen) * 0.7);
  }
  std::size_t i = 0, occluded = 0;
  for (auto _ : state)
  {
    const glm::dvec3& p = lo[i++ & 1023];
    occluded += buffer.boxOccluded(p, p + glm::dvec3(0.5)) ? 1 : 0;
  }
  benchmark::DoNotOptimize(occluded);
  state.counters["boxes"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["occluded_fraction"] = double(occluded) / double(state.iterations());
}
void BM_OcclusionBoxTest_Hidden(benchmark::State& s) { Boxes(s, 5.0); }
void BM_OcclusionBoxTest_Visible(benchmark::State& s) { Boxes(s, -5.0); }
BENCHMARK(BM_OcclusionBoxTest_Hidden);
BENCHMARK(BM_OcclusionBoxTest_Visible);
} // namespace

// scenevis_occlusion_replay: replays recorded occluder rasterizations of MaskedDepthBuffer
// (OcclusionBuffer.h) and measures them where the machine's load does not enter: the best of N
// replays in this thread's CPU time, and a hash of every buffer and its statistics so that two
// builds (or two rasterizers) can be compared on the same input.
//
// Usage: scenevis_occlusion_replay FILE [repeats (default 20)] [exact|float|both (default)]
// With both, the two rasterizers (MaskedDepthBuffer::Rasterizer) replay each cull alternately,
// so that both see the same load.
//
// FILE holds, in the machine's byte order, a sequence of records, each led by an int32 tag:
//   tag 1, a cull: int32 width, int32 height, glm::dmat4 clipFromWorld (16 doubles);
//   any other tag, one drawTriangles() call of the current cull: double coverageMargin,
//     depthMargin, polygonOffsetFactor, polygonOffsetDepth; uint64 vertexCount, triangleCount;
//     int32 culling (FaceCulling), hasNeighbors, hasClusters; vertexCount glm::dvec4 clip
//     vertices; 3 triangleCount uint32 indices; if hasNeighbors 3 triangleCount uint32
//     neighbours; if hasClusters a glm::dmat4 clipFromModel, uint64 trianglesPerCluster and 6
//     doubles per run of triangles.
// Recordings of the engine-row and inside-the-grid culls of scenevis_occlusion_bench are made by
// a temporary hook in drawTriangles() (not in the library); see BENCHMARKS.md.
#include "scenevis/OcclusionBuffer.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

namespace
{
using namespace scenevis::occlusion;

struct Draw
{
  double coverageMargin = 0.0, depthMargin = 0.0, offsetFactor = 0.0, offsetDepth = 0.0;
  std::uint64_t vertexCount = 0, triangleCount = 0;
  std::int32_t culling = 0, hasNeighbors = 0, hasClusters = 0;
  std::vector<glm::dvec4> clip;
  std::vector<std::uint32_t> indices, neighbors;
  glm::dmat4 clipFromModel{ 1.0 };
  std::uint64_t trianglesPerCluster = 0;
  std::vector<double> boxes;
};

struct Cull
{
  std::int32_t width = 800, height = 600;
  glm::dmat4 clipFromWorld{ 1.0 };
  std::vector<Draw> draws;
};

double threadSeconds()
{
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::uint64_t fnv(std::uint64_t h, const void* p, std::size_t n)
{
  const unsigned char* c = static_cast<const unsigned char*>(p);
  for (std::size_t i = 0; i < n; ++i)
  {
    h ^= c[i];
    h *= 1099511628211ull;
  }
  return h;
}

bool readCulls(const char* path, std::vector<Cull>& culls)
{
  FILE* f = std::fopen(path, "rb");
  if (!f)
  {
    return false;
  }
  bool ok = true;
  auto get = [&](void* p, std::size_t n)
  {
    ok = ok && std::fread(p, 1, n, f) == n;
    return ok;
  };
  std::int32_t tag;
  while (ok && std::fread(&tag, 4, 1, f) == 1)
  {
    if (tag == 1)
    {
      Cull c;
      get(&c.width, 4);
      get(&c.height, 4);
      get(&c.clipFromWorld, sizeof c.clipFromWorld);
      culls.push_back(std::move(c));
      continue;
    }
    if (culls.empty())
    {
      culls.emplace_back();
    }
    Draw d;
    get(&d.coverageMargin, 8);
    get(&d.depthMargin, 8);
    get(&d.offsetFactor, 8);
    get(&d.offsetDepth, 8);
    get(&d.vertexCount, 8);
    get(&d.triangleCount, 8);
    get(&d.culling, 4);
    get(&d.hasNeighbors, 4);
    get(&d.hasClusters, 4);
    if (!ok || d.vertexCount > (1u << 28) || d.triangleCount > (1u << 28))
    {
      ok = false;
      break;
    }
    d.clip.resize(d.vertexCount);
    get(d.clip.data(), sizeof(glm::dvec4) * d.vertexCount);
    d.indices.resize(3 * d.triangleCount);
    get(d.indices.data(), 12 * d.triangleCount);
    if (d.hasNeighbors)
    {
      d.neighbors.resize(3 * d.triangleCount);
      get(d.neighbors.data(), 12 * d.triangleCount);
    }
    if (d.hasClusters)
    {
      get(&d.clipFromModel, sizeof d.clipFromModel);
      get(&d.trianglesPerCluster, 8);
      if (d.trianglesPerCluster == 0)
      {
        ok = false;
        break;
      }
      d.boxes.resize(6 * ((d.triangleCount + d.trianglesPerCluster - 1) / d.trianglesPerCluster));
      get(d.boxes.data(), 8 * d.boxes.size());
    }
    culls.back().draws.push_back(std::move(d));
  }
  std::fclose(f);
  return ok;
}

/// One replay of a cull into @p buffer (cleared first).
void replay(MaskedDepthBuffer& buffer, const Cull& cull)
{
  buffer.clear();
  for (const Draw& d : cull.draws)
  {
    buffer.coverageMargin = d.coverageMargin;
    buffer.depthMargin = d.depthMargin;
    buffer.polygonOffsetFactor = d.offsetFactor;
    buffer.polygonOffsetDepth = d.offsetDepth;
    TriangleClusters clusters;
    if (d.hasClusters)
    {
      clusters.clipFromModel = d.clipFromModel;
      clusters.boxes = d.boxes.data();
      clusters.trianglesPerCluster = d.trianglesPerCluster;
    }
    buffer.drawTriangles(d.clip.data(), d.vertexCount, d.indices.data(), d.triangleCount,
      static_cast<FaceCulling>(d.culling), d.hasNeighbors ? d.neighbors.data() : nullptr,
      d.hasClusters ? &clusters : nullptr);
  }
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s FILE [repeats]\n", argv[0]);
    return 2;
  }
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 20;
  const std::string which = argc > 3 ? argv[3] : "both";
  std::vector<MaskedDepthBuffer::Rasterizer> rasterizers;
  if (which != "float")
  {
    rasterizers.push_back(MaskedDepthBuffer::Rasterizer::Exact);
  }
  if (which != "exact")
  {
    rasterizers.push_back(MaskedDepthBuffer::Rasterizer::Float);
  }
  std::vector<Cull> culls;
  if (!readCulls(argv[1], culls))
  {
    std::fprintf(stderr, "%s: cannot read %s\n", argv[0], argv[1]);
    return 1;
  }
  for (std::size_t ci = 0; ci < culls.size(); ++ci)
  {
    const Cull& cull = culls[ci];
    std::vector<MaskedDepthBuffer> buffers(rasterizers.size());
    std::vector<std::vector<double>> seconds(rasterizers.size());
    for (std::size_t k = 0; k < buffers.size(); ++k)
    {
      buffers[k].resize(cull.width, cull.height);
      buffers[k].setClipFromWorld(cull.clipFromWorld);
      buffers[k].rasterizer = rasterizers[k];
    }
    for (int r = 0; r < repeats; ++r)
    {
      for (std::size_t k = 0; k < buffers.size(); ++k)
      {
        const double start = threadSeconds();
        replay(buffers[k], cull);
        seconds[k].push_back(threadSeconds() - start);
      }
    }
    for (std::size_t k = 0; k < buffers.size(); ++k)
    {
      std::sort(seconds[k].begin(), seconds[k].end());
      std::uint64_t hash = 1469598103934665603ull;
      std::size_t fullTiles = 0, maskedPixels = 0;
      for (const MaskedDepthBuffer::Tile& t : buffers[k].tiles())
      {
        hash = fnv(hash, &t.z0, 4);
        hash = fnv(hash, &t.mask, 4);
        if (t.mask)
        {
          hash = fnv(hash, &t.z1, 4);
        }
        fullTiles += t.z0 < 2.0f ? 1 : 0;
        for (std::uint32_t m = t.mask; m; m &= m - 1)
        {
          ++maskedPixels;
        }
      }
      const BufferStats& st = buffers[k].stats();
      std::printf("cull %zu %s: %zu draws, hash %016llx, full tiles %zu, working-layer pixels %zu, "
                  "in %zu drawn %zu rejected %zu tile updates %zu clusters hidden %zu/%zu; CPU "
                  "ms best %.3f median %.3f\n",
        ci, rasterizers[k] == MaskedDepthBuffer::Rasterizer::Exact ? "exact" : "float",
        cull.draws.size(), static_cast<unsigned long long>(hash), fullTiles, maskedPixels,
        st.trianglesIn, st.trianglesDrawn, st.trianglesRejected, st.tilesUpdated, st.clustersHidden,
        st.clustersTested, 1e3 * seconds[k].front(), 1e3 * seconds[k][seconds[k].size() / 2]);
    }
  }
  return 0;
}

// scenevis_occlusion_replay: replays recorded occluder rasterizations of MaskedDepthBuffer
// (OcclusionBuffer.h) and measures them where the machine's load does not enter: the best of N
// replays in this thread's CPU time, and a hash of every buffer and its statistics so that two
// builds (or two rasterizers) can be compared on the same input.
//
// Usage: scenevis_occlusion_replay FILE [repeats (default 20)] [exact|float|both (default)]
// With both, the two rasterizers (MaskedDepthBuffer::Rasterizer) replay each cull alternately,
// so that both see the same load.
//
// FILE is a recording (scenevis/OcclusionRecording.h), e.g. of the engine-row culls of
// `scenevis_occlusion_bench --record FILE` (BENCHMARKS.md).
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionRecording.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

namespace
{
using namespace scenevis::occlusion;

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

} // namespace

int main(int argc, char** argv)
{
  const char* usage = "usage: %s FILE [repeats (1..100000, default 20)] [exact|float|both]\n";
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 20;
  const std::string which = argc > 3 ? argv[3] : "both";
  if (argc < 2 || argc > 4 || repeats < 1 || repeats > 100000 ||
    (which != "exact" && which != "float" && which != "both"))
  {
    std::fprintf(stderr, usage, argv[0]);
    return 2;
  }
  std::vector<MaskedDepthBuffer::Rasterizer> rasterizers;
  if (which != "float")
  {
    rasterizers.push_back(MaskedDepthBuffer::Rasterizer::Exact);
  }
  if (which != "exact")
  {
    rasterizers.push_back(MaskedDepthBuffer::Rasterizer::Float);
  }
  std::vector<RecordedCull> culls;
  std::ifstream file(argv[1], std::ios::binary);
  std::string error;
  if (!file)
  {
    std::fprintf(stderr, "%s: cannot open %s\n", argv[0], argv[1]);
    return 1;
  }
  if (!readOcclusionRecording(file, culls, error))
  {
    std::fprintf(stderr, "%s: %s: %s\n", argv[0], argv[1], error.c_str());
    return 1;
  }
  for (std::size_t ci = 0; ci < culls.size(); ++ci)
  {
    const RecordedCull& cull = culls[ci];
    std::vector<MaskedDepthBuffer> buffers(rasterizers.size());
    std::vector<std::vector<double>> seconds(rasterizers.size());
    for (std::size_t k = 0; k < buffers.size(); ++k)
    {
      prepareReplay(buffers[k], cull);
      buffers[k].rasterizer = rasterizers[k];
    }
    for (int r = 0; r < repeats; ++r)
    {
      for (std::size_t k = 0; k < buffers.size(); ++k)
      {
        const double start = threadSeconds();
        replayDraws(buffers[k], cull);
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

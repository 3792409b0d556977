// libFuzzer target for occlusion recordings (OcclusionRecording.h): arbitrary bytes are read as a
// recording. Checked against the format itself, not just "no crash": whatever reads without an
// error must write back to exactly the bytes read (every field kept, nothing invented), and its
// culls replay into a buffer (both rasterizers) that counts every recorded triangle once. What
// does not read must say why. Culls of more than 256 x 256 pixels are read but not replayed (a
// replay's time is the rasterizer's, not the reader's).
//
// Seeds: scenevis_fuzz_make_recording_corpus DIR (MakeRecordingCorpus.cpp) writes small real
// recordings; nothing is committed.
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionRecording.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace scenevis::occlusion;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::istringstream in(bytes, std::ios::binary);
  std::vector<RecordedCull> culls;
  std::string error;
  if (!readOcclusionRecording(in, culls, error))
  {
    if (error.empty())
    {
      std::fprintf(stderr, "a recording that does not read gave no reason\n");
      std::abort();
    }
    return 0;
  }
  std::ostringstream out(std::ios::binary);
  writeOcclusionRecording(out, culls);
  if (out.str() != bytes)
  {
    std::fprintf(
      stderr, "read %zu bytes, wrote back %zu different ones\n", bytes.size(), out.str().size());
    std::abort();
  }
  for (const RecordedCull& cull : culls)
  {
    if (static_cast<long long>(cull.width) * cull.height > 256 * 256)
    {
      continue;
    }
    std::size_t triangles = 0;
    for (const RecordedDraw& d : cull.draws)
    {
      triangles += d.indices.size() / 3;
    }
    for (const auto rasterizer :
      { MaskedDepthBuffer::Rasterizer::Exact, MaskedDepthBuffer::Rasterizer::Float })
    {
      MaskedDepthBuffer buffer;
      buffer.rasterizer = rasterizer;
      prepareReplay(buffer, cull);
      replayDraws(buffer, cull);
      if (buffer.stats().trianglesIn != triangles)
      {
        std::fprintf(
          stderr, "replayed %zu triangles of %zu\n", buffer.stats().trianglesIn, triangles);
        std::abort();
      }
    }
  }
  return 0;
}

// Specification of occlusion recordings (OcclusionRecording.h): a buffer's draws, written while
// it draws them, replay into another buffer as the same buffer bit for bit (tiles and drawing
// statistics), whichever drawTriangles() overload and options were used; a recording reads back
// to the same bytes; and whatever is wrong with a file is reported, never read past or
// allocated for.
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionRecording.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace scenevis::occlusion;

namespace
{

/// Random triangles of a model: runs of triangle strips (consecutive triangles share an edge, so
/// edge neighbours matter), a few points not finite.
struct Model
{
  std::vector<double> xyz;
  std::vector<float> xyzFloat;
  std::vector<std::uint32_t> indices, neighbors;
  std::vector<double> boxes;
  std::size_t perRun = 1;

  std::size_t points() const { return xyz.size() / 3; }
  std::size_t triangles() const { return indices.size() / 3; }
  std::vector<glm::dvec4> clip(const glm::dmat4& clipFromModel) const
  {
    std::vector<glm::dvec4> out;
    for (std::size_t i = 0; i < points(); ++i)
    {
      out.push_back(clipFromModel * glm::dvec4(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], 1.0));
    }
    return out;
  }
};

Model randomModel(std::mt19937_64& rng, int runs, std::size_t perRun)
{
  auto uniform = [&](double a, double b)
  { return std::uniform_real_distribution<double>(a, b)(rng); };
  Model m;
  m.perRun = perRun;
  for (int r = 0; r < runs; ++r)
  {
    const glm::dvec3 c(uniform(-5, 5), uniform(-5, 5), uniform(-5, 5));
    const double size = uniform(0.2, 4.0);
    const auto first = static_cast<std::uint32_t>(m.points());
    for (std::size_t k = 0; k < perRun + 2; ++k)
    {
      glm::dvec3 p =
        c + glm::dvec3(uniform(-size, size), uniform(-size, size), uniform(-size, size));
      if (uniform(0, 1) < 0.01)
      {
        p.x = std::numeric_limits<double>::quiet_NaN();
      }
      m.xyz.insert(m.xyz.end(), { p.x, p.y, p.z });
    }
    for (std::uint32_t t = 0; t < perRun; ++t)
    {
      const std::uint32_t v = first + t;
      if (t % 2 == 0)
      {
        m.indices.insert(m.indices.end(), { v, v + 1, v + 2 });
      }
      else
      {
        m.indices.insert(m.indices.end(), { v + 1, v, v + 2 });
      }
    }
  }
  m.xyzFloat.assign(m.xyz.begin(), m.xyz.end());
  m.neighbors = buildTriangleNeighbors(m.xyz.data(), m.points(), m.indices.data(), m.triangles());
  m.boxes =
    buildTriangleClusters(m.xyz.data(), m.points(), m.indices.data(), m.triangles(), perRun);
  return m;
}

glm::dmat4 camera(std::mt19937_64& rng, int width, int height)
{
  auto uniform = [&](double a, double b)
  { return std::uniform_real_distribution<double>(a, b)(rng); };
  const glm::dvec3 eye(uniform(-3, 3), uniform(-16, -9), uniform(-3, 3));
  return glm::perspective(glm::radians(uniform(40, 90)), double(width) / height, 0.5, 80.0) *
    glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
}

void expectSameBuffer(
  const MaskedDepthBuffer& a, const MaskedDepthBuffer& b, const std::string& what)
{
  ASSERT_EQ(a.width(), b.width()) << what;
  ASSERT_EQ(a.height(), b.height()) << what;
  ASSERT_EQ(a.tiles().size(), b.tiles().size()) << what;
  for (std::size_t i = 0; i < a.tiles().size(); ++i)
  {
    const MaskedDepthBuffer::Tile& s = a.tiles()[i];
    const MaskedDepthBuffer::Tile& t = b.tiles()[i];
    ASSERT_TRUE(
      std::memcmp(&s.z0, &t.z0, 4) == 0 && s.mask == t.mask && std::memcmp(&s.z1, &t.z1, 4) == 0)
      << what << ", tile " << i;
  }
  const BufferStats &x = a.stats(), &y = b.stats();
  EXPECT_EQ(x.trianglesIn, y.trianglesIn) << what;
  EXPECT_EQ(x.trianglesDrawn, y.trianglesDrawn) << what;
  EXPECT_EQ(x.trianglesRejected, y.trianglesRejected) << what;
  EXPECT_EQ(x.clustersTested, y.clustersTested) << what;
  EXPECT_EQ(x.clustersHidden, y.clustersHidden) << what;
  EXPECT_EQ(x.tilesUpdated, y.tilesUpdated) << what;
}

/// Records three culls of random models into @p bytes; @p live gets each cull's buffer as drawn.
void recordCulls(std::mt19937_64& rng, MaskedDepthBuffer::Rasterizer rasterizer, std::string& bytes,
  std::vector<MaskedDepthBuffer>& live)
{
  std::ostringstream out(std::ios::binary);
  OcclusionRecorder recorder(out);
  MaskedDepthBuffer buffer;
  buffer.rasterizer = rasterizer;
  buffer.recorder = &recorder;
  const int sizes[3][2] = { { 96, 64 }, { 96, 64 }, { 37, 101 } };
  for (const auto& size : sizes)
  {
    buffer.resize(size[0], size[1]);
    const glm::dmat4 clipFromWorld = camera(rng, size[0], size[1]);
    buffer.setClipFromWorld(clipFromWorld);
    for (int draw = 0; draw < 6; ++draw)
    {
      const Model m = randomModel(rng, 3 + draw * 5, 1 + static_cast<std::size_t>(draw) * 3);
      const glm::dmat4 clipFromModel =
        clipFromWorld * glm::rotate(glm::dmat4(1.0), 0.3 * draw, glm::dvec3(0.2, 1.0, 0.4));
      // Every way of drawing, with settings that change between draws.
      buffer.coverageMargin = draw == 3 ? 1.0 / 32.0 : 1.0 / 64.0;
      buffer.polygonOffsetFactor = draw == 4 ? 2.0 : 0.0;
      buffer.polygonOffsetDepth = draw == 4 ? 1e-5 : 0.0;
      const FaceCulling culling = static_cast<FaceCulling>(draw % 3);
      TriangleClusters clusters;
      clusters.clipFromModel = clipFromModel;
      clusters.boxes = m.boxes.data();
      clusters.trianglesPerCluster = m.perRun;
      const std::uint32_t* neighbors = draw % 2 ? m.neighbors.data() : nullptr;
      const TriangleClusters* runs = draw >= 2 ? &clusters : nullptr;
      if (draw < 2)
      {
        const std::vector<glm::dvec4> clip = m.clip(clipFromModel);
        buffer.drawTriangles(
          clip.data(), clip.size(), m.indices.data(), m.triangles(), culling, neighbors, runs);
      }
      else
      {
        ModelVertices model;
        model.clipFromModel = clipFromModel;
        if (draw % 2)
        {
          model.xyzFloat = m.xyzFloat.data();
        }
        else
        {
          model.xyzDouble = m.xyz.data();
        }
        buffer.drawTriangles(
          model, m.points(), m.indices.data(), m.triangles(), culling, neighbors, runs);
      }
    }
    // A model without points: drawn as nothing, all its triangles rejected.
    const std::uint32_t three[3] = { 0, 1, 2 };
    buffer.drawTriangles(ModelVertices(), 3, three, 1);
    live.push_back(buffer);
    buffer.clear();
  }
  EXPECT_TRUE(recorder.good());
  EXPECT_EQ(recorder.culls(), 3u);
  EXPECT_EQ(recorder.draws(), 21u);
  bytes = out.str();
}

bool read(const std::string& bytes, std::vector<RecordedCull>& culls, std::string& error)
{
  std::istringstream in(bytes, std::ios::binary);
  return readOcclusionRecording(in, culls, error);
}

std::string recording()
{
  std::mt19937_64 rng(5);
  std::vector<MaskedDepthBuffer> live;
  std::string bytes;
  recordCulls(rng, MaskedDepthBuffer::Rasterizer::Exact, bytes, live);
  return bytes;
}

/// The byte offset of the first draw record's fields after its tag (the recording() layout:
/// header 8, cull record 4 + 8 + 128).
constexpr std::size_t kFirstDraw = 8 + 140 + 4;

std::string withBytes(std::string bytes, std::size_t at, const void* value, std::size_t n)
{
  std::memcpy(&bytes[at], value, n);
  return bytes;
}

} // namespace

TEST(OcclusionRecording, ReplayedCullsAreTheRecordedBuffersBitForBit)
{
  for (const auto rasterizer :
    { MaskedDepthBuffer::Rasterizer::Exact, MaskedDepthBuffer::Rasterizer::Float })
  {
    std::mt19937_64 rng(11);
    std::vector<MaskedDepthBuffer> live;
    std::string bytes;
    recordCulls(rng, rasterizer, bytes, live);
    std::vector<RecordedCull> culls;
    std::string error;
    ASSERT_TRUE(read(bytes, culls, error)) << error;
    ASSERT_EQ(culls.size(), live.size());
    std::size_t drawn = 0;
    for (std::size_t c = 0; c < culls.size(); ++c)
    {
      EXPECT_EQ(culls[c].draws.size(), 7u);
      MaskedDepthBuffer replayed;
      replayed.rasterizer = rasterizer;
      prepareReplay(replayed, culls[c]);
      replayDraws(replayed, culls[c]);
      expectSameBuffer(live[c], replayed, "cull " + std::to_string(c));
      // Twice: a replay starts from a clear buffer.
      replayDraws(replayed, culls[c]);
      expectSameBuffer(live[c], replayed, "cull " + std::to_string(c) + " again");
      drawn += live[c].stats().trianglesDrawn;
    }
    // Not the same by drawing nothing: the scenes cover pixels and skip runs.
    EXPECT_GT(drawn, 100u);
  }
}

TEST(OcclusionRecording, ARecordingReadsBackToTheSameBytes)
{
  const std::string bytes = recording();
  std::vector<RecordedCull> culls;
  std::string error;
  ASSERT_TRUE(read(bytes, culls, error)) << error;
  std::ostringstream out(std::ios::binary);
  writeOcclusionRecording(out, culls);
  EXPECT_TRUE(out.str() == bytes);
  // An empty recording is a header alone, and reads as no culls.
  std::ostringstream empty(std::ios::binary);
  writeOcclusionRecording(empty, {});
  ASSERT_TRUE(read(empty.str(), culls, error)) << error;
  EXPECT_TRUE(culls.empty());
}

TEST(OcclusionRecording, ARecordingCutShortAnywhereIsAnError)
{
  const std::string bytes = recording();
  std::vector<RecordedCull> culls;
  std::string error;
  std::size_t cut = 0;
  // Every cut inside the header and the first records, then every 97th byte.
  for (std::size_t n = 0; n < bytes.size(); n += n < 4096 ? 1 : 97)
  {
    const bool ok = read(bytes.substr(0, n), culls, error);
    // A cut between two records is a shorter recording; anywhere else it is an error.
    if (!ok)
    {
      ++cut;
      EXPECT_NE(error.find("byte "), std::string::npos) << error;
    }
  }
  EXPECT_GT(cut, 4000u);
  EXPECT_FALSE(read(bytes.substr(0, 20), culls, error));
  EXPECT_NE(error.find("cut short"), std::string::npos) << error;
}

TEST(OcclusionRecording, MalformedRecordsAreNamed)
{
  const std::string bytes = recording();
  std::vector<RecordedCull> culls;
  std::string error;
  auto rejects = [&](const std::string& file, const char* message)
  {
    EXPECT_FALSE(read(file, culls, error)) << message;
    EXPECT_NE(error.find(message), std::string::npos)
      << "expected \"" << message << "\", got \"" << error << "\"";
  };
  rejects("SVOREC02" + bytes.substr(8), "not an occlusion recording");
  rejects("", "header cut short");
  const std::int32_t seven = 7, twoTag = 2, tooWide = 16385;
  rejects(withBytes(bytes, 8, &seven, 4), "unknown record tag 7");
  rejects(withBytes(bytes, 8, &twoTag, 4), "a draw before the first cull");
  rejects(withBytes(bytes, 12, &tooWide, 4), "outside 0..16384");
  const double nan = std::numeric_limits<double>::quiet_NaN(), negative = -1.0;
  rejects(withBytes(bytes, kFirstDraw, &nan, 8), "not finite");
  // Errors name the record at fault: the first draw starts after the header and the cull.
  EXPECT_EQ(error.rfind("byte 148: ", 0), 0u) << error;
  rejects(withBytes(bytes, kFirstDraw + 8, &negative, 8), "margin outside 0..1");
  const double two = 2.0, hugeFactor = 1e5;
  rejects(withBytes(bytes, kFirstDraw, &two, 8), "margin outside 0..1");
  rejects(withBytes(bytes, kFirstDraw + 16, &hugeFactor, 8), "polygon offset beyond");
  // Counts that the file cannot hold: no allocation of their size, an error.
  const std::uint64_t huge = std::uint64_t(1) << 27, tooMany = (std::uint64_t(1) << 28) + 1;
  rejects(withBytes(bytes, kFirstDraw + 32, &huge, 8), "bytes left");
  rejects(withBytes(bytes, kFirstDraw + 40, &tooMany, 8), "more than 2^28");
  rejects(withBytes(bytes, kFirstDraw + 48, &seven, 4), "face culling 7");
  rejects(withBytes(bytes, kFirstDraw + 52, &twoTag, 4), "flag other than 0 or 1");
}

TEST(OcclusionRecording, RunsOfNoTrianglesAreAnError)
{
  RecordedCull cull;
  cull.width = 8;
  cull.height = 8;
  RecordedDraw draw;
  draw.clip.assign(3, glm::dvec4(0, 0, 0, 1));
  draw.indices = { 0, 1, 2 };
  draw.hasClusters = true;
  draw.trianglesPerCluster = 1;
  draw.boxes.assign(6, 0.0);
  cull.draws.push_back(draw);
  std::ostringstream out(std::ios::binary);
  writeOcclusionRecording(out, { cull });
  std::string bytes = out.str();
  // The count of triangles per run follows the run boxes' matrix (after the 3 indices).
  const std::size_t at = kFirstDraw + 60 + 3 * 32 + 12 + 128;
  const std::uint64_t zero = 0;
  std::vector<RecordedCull> culls;
  std::string error;
  ASSERT_TRUE(read(bytes, culls, error)) << error;
  EXPECT_FALSE(read(withBytes(bytes, at, &zero, 8), culls, error));
  EXPECT_NE(error.find("runs of 0 triangles"), std::string::npos) << error;
}

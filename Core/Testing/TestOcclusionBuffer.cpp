// Specification of the conservative occlusion buffer (OcclusionBuffer.h) and of the BVH's
// front-to-back occlusion cull, against an independent oracle (OcclusionOracle.h): a ray cast
// through the centre of every pixel (the sample OpenGL uses), exact to double precision, with no
// margins.
//
// "Conservative" means: a box (or object) reported hidden has no pixel where a point of it lies
// nearer than the nearest occluder. Efficiency checks make sure the buffer is not conservative by
// doing nothing: walls occlude, walls of many small triangles occlude, peeking boxes do not.
#include "scenevis/Bvh.h"
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionOracle.h"

#include "../src/OcclusionFront.h"    // module-private: drawTriangles' batch front end
#include "../src/OcclusionScanline.h" // module-private: the exact rasterizer's intervals

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <tuple>

using namespace scenevis;
using namespace scenevis::occlusion;

namespace
{

struct Camera
{
  glm::dmat4 clipFromWorld{ 1.0 };
  int width = 0, height = 0;
};

Camera perspectiveCamera(const glm::dvec3& eye, const glm::dvec3& target, double fovyDeg,
  int width, int height, double znear, double zfar)
{
  const glm::dvec3 dir = glm::normalize(target - eye);
  const glm::dvec3 up = std::abs(dir.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  Camera c;
  c.clipFromWorld = glm::perspective(glm::radians(fovyDeg), double(width) / height, znear, zfar) *
    glm::lookAt(eye, target, up);
  c.width = width;
  c.height = height;
  return c;
}

Camera parallelCamera(const glm::dvec3& eye, const glm::dvec3& target, double halfHeight,
  int width, int height, double znear, double zfar)
{
  const glm::dvec3 dir = glm::normalize(target - eye);
  const glm::dvec3 up = std::abs(dir.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  const double halfWidth = halfHeight * width / height;
  Camera c;
  c.clipFromWorld = glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, znear, zfar) *
    glm::lookAt(eye, target, up);
  c.width = width;
  c.height = height;
  return c;
}

using Triangle = OracleTriangle;

int visiblePixels(const Camera& cam, const std::vector<Triangle>& occluders, const glm::dvec3& lo,
  const glm::dvec3& hi)
{
  return occlusion::visiblePixels(cam.clipFromWorld, cam.width, cam.height, occluders, lo, hi);
}

/// Draws a soup (every triangle with its own three points, as many CAD files store them); with
/// @p withNeighbors the edges shared by position are found first (buildTriangleNeighbors).
void draw(MaskedDepthBuffer& buffer, const Camera& cam, const std::vector<Triangle>& triangles,
  FaceCulling culling = FaceCulling::None, bool withNeighbors = true)
{
  std::vector<glm::dvec4> clip;
  std::vector<double> xyz;
  std::vector<std::uint32_t> indices;
  for (const Triangle& t : triangles)
  {
    for (const glm::dvec3& p : { t.a, t.b, t.c })
    {
      indices.push_back(static_cast<std::uint32_t>(clip.size()));
      clip.push_back(cam.clipFromWorld * glm::dvec4(p, 1.0));
      xyz.insert(xyz.end(), { p.x, p.y, p.z });
    }
  }
  const std::vector<std::uint32_t> neighbors =
    buildTriangleNeighbors(xyz.data(), clip.size(), indices.data(), triangles.size());
  buffer.drawTriangles(clip.data(), clip.size(), indices.data(), triangles.size(), culling,
    withNeighbors ? neighbors.data() : nullptr);
}

/// A square wall in the plane y = @p y, x and z in [-h, h], split into n x n cells of two
/// counter-clockwise triangles seen from -y.
std::vector<Triangle> wall(double y, double h, int n)
{
  std::vector<Triangle> out;
  const double step = 2.0 * h / n;
  auto at = [&](int i, int k) { return glm::dvec3(-h + i * step, y, -h + k * step); };
  for (int i = 0; i < n; ++i)
  {
    for (int k = 0; k < n; ++k)
    {
      const glm::dvec3 p00 = at(i, k), p10 = at(i + 1, k), p01 = at(i, k + 1),
                       p11 = at(i + 1, k + 1);
      out.push_back({ p00, p10, p11 });
      out.push_back({ p00, p11, p01 });
    }
  }
  return out;
}

/// The rasterizer of the running test (every test runs with each, see RasterizerTest).
MaskedDepthBuffer::Rasterizer gRasterizer = MaskedDepthBuffer::Rasterizer::Float;

/// Every test of this file runs once per rasterizer (OcclusionBuffer.h, "Two rasterizers"): both
/// must be conservative, and both must occlude.
class RasterizerTest : public ::testing::TestWithParam<MaskedDepthBuffer::Rasterizer>
{
protected:
  void SetUp() override { gRasterizer = GetParam(); }
};

std::string rasterizerName(const ::testing::TestParamInfo<MaskedDepthBuffer::Rasterizer>& info)
{
  return info.param == MaskedDepthBuffer::Rasterizer::Exact ? "Exact" : "Float";
}

MaskedDepthBuffer bufferFor(const Camera& cam)
{
  MaskedDepthBuffer buffer;
  buffer.rasterizer = gRasterizer;
  buffer.resize(cam.width, cam.height);
  buffer.setClipFromWorld(cam.clipFromWorld);
  return buffer;
}

const Camera kFront = perspectiveCamera({ 0, -10, 0 }, { 0, 0, 0 }, 60.0, 83, 61, 0.1, 100.0);

/// A triangle of window coordinates set up for the exact rasterizer as drawFrontTriangle sets it
/// up (the scanline tests' common part): its edge tests (outline bit k on edge k), the columns
/// [x0, x1] and rows [y0, y1] of the viewport's pixel centres it may cover, and the coverage of
/// its scanlines. Not copied: the coverage refers to the edges.
struct ScanlineTriangle
{
  /// Nothing for a triangle of no area or one that covers no centre of a @p width x @p height
  /// viewport.
  static std::unique_ptr<const ScanlineTriangle> setUp(
    const glm::dvec3 (&v)[3], unsigned outline, double margin, int width, int height)
  {
    const double area2 =
      (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
    if (!(std::abs(area2) > 0.0))
    {
      return nullptr;
    }
    // Clamped in double before the cast: vertices far off screen lie beyond int's range.
    auto columnSpan = [](double a, double b, double c, int pixels, int& lo, int& hi)
    {
      const double low = std::ceil(std::min({ a, b, c }) - 0.5);
      const double high = std::floor(std::max({ a, b, c }) - 0.5);
      lo = static_cast<int>(std::max(0.0, low));
      hi = static_cast<int>(std::min(pixels - 1.0, high));
    };
    int x0, x1, y0, y1;
    columnSpan(v[0].x, v[1].x, v[2].x, width, x0, x1);
    columnSpan(v[0].y, v[1].y, v[2].y, height, y0, y1);
    if (x0 > x1 || y0 > y1)
    {
      return nullptr;
    }
    double extent = width + height;
    for (const glm::dvec3& p : v)
    {
      extent = std::max({ extent, std::abs(p.x), std::abs(p.y) });
    }
    return std::unique_ptr<const ScanlineTriangle>(
      new ScanlineTriangle(v, area2 > 0.0 ? 1.0 : -1.0, outline, margin, extent, x0, x1, y0, y1));
  }

  ScanlineTriangle(const ScanlineTriangle&) = delete;
  ScanlineTriangle& operator=(const ScanlineTriangle&) = delete;

  /// Whether the centre of pixel (@p i, @p y) passes all three edge tests.
  bool inside(int i, int y) const
  {
    return edges[0].inside(i + 0.5, y + 0.5) && edges[1].inside(i + 0.5, y + 0.5) &&
      edges[2].inside(i + 0.5, y + 0.5);
  }

  const int x0, x1, y0, y1;
  const EdgeTest edges[3];
  const ScanlineCoverage coverage;

private:
  ScanlineTriangle(const glm::dvec3 (&v)[3], double orientation, unsigned outline, double margin,
    double extent, int columnFrom, int columnTo, int rowFrom, int rowTo)
    : x0(columnFrom)
    , x1(columnTo)
    , y0(rowFrom)
    , y1(rowTo)
    , edges{ EdgeTest(v[0], v[1], orientation, outline & 1u, margin),
      EdgeTest(v[1], v[2], orientation, outline & 2u, margin),
      EdgeTest(v[2], v[0], orientation, outline & 4u, margin) }
    , coverage(edges, extent, columnFrom, columnTo)
  {
  }
};
} // namespace

using OcclusionBuffer = RasterizerTest;
using OcclusionCull = RasterizerTest;
INSTANTIATE_TEST_SUITE_P(Rasterizer, OcclusionBuffer,
  ::testing::Values(MaskedDepthBuffer::Rasterizer::Exact, MaskedDepthBuffer::Rasterizer::Float),
  rasterizerName);
INSTANTIATE_TEST_SUITE_P(Rasterizer, OcclusionCull,
  ::testing::Values(MaskedDepthBuffer::Rasterizer::Exact, MaskedDepthBuffer::Rasterizer::Float),
  rasterizerName);

TEST_P(OcclusionBuffer, AnEmptyBufferOccludesNothing)
{
  MaskedDepthBuffer buffer = bufferFor(kFront);
  EXPECT_FALSE(buffer.boxOccluded({ -1, 5, -1 }, { 1, 6, 1 }));
  EXPECT_EQ(buffer.tileDepth(10, 10), std::numeric_limits<float>::infinity());
}

TEST_P(OcclusionBuffer, AWallHidesWhatIsBehindItAndNotWhatIsBeforeIt)
{
  const std::vector<Triangle> w = wall(0.0, 5.0, 1);
  MaskedDepthBuffer buffer = bufferFor(kFront);
  draw(buffer, kFront, w);
  EXPECT_TRUE(buffer.boxOccluded({ -1, 1, -1 }, { 1, 2, 1 }));
  EXPECT_EQ(visiblePixels(kFront, w, { -1, 1, -1 }, { 1, 2, 1 }), 0);
  EXPECT_FALSE(buffer.boxOccluded({ -1, -2, -1 }, { 1, -1, 1 })); // in front of the wall
  EXPECT_FALSE(buffer.boxOccluded({ -1, -0.5, -1 }, { 1, 1, 1 })); // through the wall
}

TEST_P(OcclusionBuffer, AWallOfManySmallTrianglesOccludesAsOne)
{
  // 20,000 triangles, each much smaller than a tile: no single triangle covers a tile, the
  // working layer merges them.
  const std::vector<Triangle> w = wall(0.0, 5.0, 100);
  MaskedDepthBuffer buffer = bufferFor(kFront);
  draw(buffer, kFront, w);
  EXPECT_TRUE(buffer.boxOccluded({ -1, 1, -1 }, { 1, 2, 1 }));
  EXPECT_TRUE(buffer.boxOccluded({ -3, 0.5, -3 }, { 3, 9, 3 }));
}

TEST_P(OcclusionBuffer, AnOccluderSmallerThanATileHidesWhatIsBehindIt)
{
  // A wall of about 5 x 5 pixels covers no whole 8 x 4 tile: only the working layer (its mask
  // and depth) knows it; a box behind it covering fewer pixels is hidden by it.
  const std::vector<Triangle> w = wall(0.0, 0.5, 2);
  MaskedDepthBuffer buffer = bufferFor(kFront);
  draw(buffer, kFront, w);
  const glm::dvec3 lo(-0.06, 1.0, -0.06), hi(0.06, 1.1, 0.06);
  ASSERT_EQ(visiblePixels(kFront, w, lo, hi), 0);
  EXPECT_TRUE(buffer.boxOccluded(lo, hi));
  // Wider than the wall: seen beside it.
  EXPECT_FALSE(buffer.boxOccluded({ -0.8, 1.0, -0.06 }, { 0.8, 1.1, 0.06 }));
}

TEST_P(OcclusionBuffer, ABoxPeekingOutByOnePixelIsVisible)
{
  const std::vector<Triangle> w = wall(0.0, 2.0, 1);
  MaskedDepthBuffer buffer = bufferFor(kFront);
  draw(buffer, kFront, w);
  // The box behind the wall reaches just past its right edge.
  const glm::dvec3 lo(-1, 1, -1), hi(2.6, 2, 1);
  ASSERT_GT(visiblePixels(kFront, w, lo, hi), 0);
  EXPECT_FALSE(buffer.boxOccluded(lo, hi));
}

TEST_P(OcclusionBuffer, CulledFacesDoNotOcclude)
{
  const std::vector<Triangle> w = wall(0.0, 5.0, 4); // counter-clockwise seen from the eye
  {
    MaskedDepthBuffer buffer = bufferFor(kFront);
    draw(buffer, kFront, w, FaceCulling::Back);
    EXPECT_TRUE(buffer.boxOccluded({ -1, 1, -1 }, { 1, 2, 1 }));
  }
  {
    MaskedDepthBuffer buffer = bufferFor(kFront);
    draw(buffer, kFront, w, FaceCulling::Front);
    EXPECT_FALSE(buffer.boxOccluded({ -1, 1, -1 }, { 1, 2, 1 }));
    EXPECT_EQ(buffer.stats().trianglesDrawn, 0u);
  }
}

TEST_P(OcclusionBuffer, AnOccluderCutByTheNearPlaneStillOccludes)
{
  // The eye 0.15 in front of a big tilted wall that reaches behind the eye: its triangles are cut
  // by the near plane (0.1).
  const Camera cam = perspectiveCamera({ 0, -0.15, 0 }, { 0.3, 1, 0 }, 90.0, 64, 48, 0.1, 100.0);
  std::vector<Triangle> w = wall(0.0, 50.0, 3);
  for (Triangle& t : w)
  {
    for (glm::dvec3* p : { &t.a, &t.b, &t.c })
    {
      p->y += 0.1 * p->x; // tilted: part of it is nearer than the near plane
    }
  }
  MaskedDepthBuffer buffer = bufferFor(cam);
  draw(buffer, cam, w);
  const glm::dvec3 lo(-2, 3, -2), hi(2, 4, 2);
  EXPECT_EQ(visiblePixels(cam, w, lo, hi), 0);
  EXPECT_TRUE(buffer.boxOccluded(lo, hi));
  // A box reaching from the eye to behind the wall is not occluded (its part in front of the
  // wall is seen), even where the near plane cuts it.
  EXPECT_FALSE(buffer.boxOccluded({ -0.2, -0.1, -0.2 }, { 0.2, 0.5, 0.2 }));
}

TEST_P(OcclusionBuffer, OnlyThePartOfABoxInTheFrustumIsTested)
{
  // Eye at the origin looking along +y (90 degrees): a wall at y = 1. A box beside the viewer
  // reaches behind the eye, but what of it is in the frustum lies behind the wall.
  const Camera cam = perspectiveCamera({ 0, 0, 0 }, { 0, 1, 0 }, 90.0, 64, 64, 0.1, 100.0);
  const std::vector<Triangle> w = wall(1.0, 50.0, 2);
  MaskedDepthBuffer buffer = bufferFor(cam);
  draw(buffer, cam, w);
  const glm::dvec3 lo(-10, -2, -1), hi(-5, 8, 1);
  EXPECT_EQ(visiblePixels(cam, w, lo, hi), 0);
  EXPECT_TRUE(buffer.boxOccluded(lo, hi));
  // Reaching into the frustum in front of the wall: seen.
  EXPECT_FALSE(buffer.boxOccluded({ -10, -2, -1 }, { -0.5, 5, 1 }));
  // Around the eye (a room the viewer stands in): its faces are all behind the wall, but the
  // box holds the whole near plane: seen.
  ASSERT_GT(visiblePixels(cam, w, { -5, -5, -5 }, { 5, 5, 5 }), 0);
  EXPECT_FALSE(buffer.boxOccluded({ -5, -5, -5 }, { 5, 5, 5 }));
}

TEST_P(OcclusionBuffer, ParallelProjectionOccludes)
{
  const Camera cam = parallelCamera({ 0, -10, 0 }, { 0, 0, 0 }, 6.0, 70, 50, 0.1, 100.0);
  const std::vector<Triangle> w = wall(0.0, 5.0, 10);
  MaskedDepthBuffer buffer = bufferFor(cam);
  draw(buffer, cam, w);
  EXPECT_TRUE(buffer.boxOccluded({ -4, 1, -4 }, { 4, 2, 4 }));
  EXPECT_FALSE(buffer.boxOccluded({ -6, 1, -1 }, { -4, 2, 1 })); // beside the wall's edge
}

TEST_P(OcclusionBuffer, BadInputIsRejectedNotDrawn)
{
  MaskedDepthBuffer buffer = bufferFor(kFront);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  // Vertices 5-7 are not finite in w, z or w only: taken as finite, each would make a drawable
  // triangle with vertices 1 and 2 (w = inf projects to the centre; z = inf is in front).
  // Vertex 8 is finite and in front of the near plane, but its w is so small that 1 / w
  // overflows: its window point would be 0 x inf = NaN.
  std::vector<glm::dvec4> clip = { { 0, 0, 0.5, 1 }, { 1, 0, 0.5, 1 }, { 0, 1, 0.5, 1 },
    { nan, 0, 0, 1 }, { 0, 0, -5, -1 }, { 0, 0, 0.5, inf }, { 0, 0, inf, 1 }, { 0, 0, 0.5, nan },
    { 0, 0, 1e-310, 1e-310 } };
  std::vector<std::uint32_t> indices = { 0, 1, 1, /*degenerate*/ 0, 1, 3, /*NaN*/ 0, 1, 9,
    /*out of range*/ 4, 4, 4 /*behind*/, 1, 2, 5, /*w = inf*/ 1, 2, 6, /*z = inf*/ 1, 2,
    7 /*w = NaN*/, 1, 2, 8 /*w = 1e-310*/ };
  buffer.drawTriangles(clip.data(), clip.size(), indices.data(), 8);
  EXPECT_EQ(buffer.stats().trianglesRejected, 8u);
  EXPECT_EQ(buffer.stats().tilesUpdated, 0u);
  EXPECT_FALSE(buffer.boxOccluded({ nan, 0, 0 }, { 1, 1, 1 }));
  EXPECT_FALSE(buffer.boxOccluded({ 1, 1, 1 }, { 0, 0, 0 })); // empty
  MaskedDepthBuffer empty;
  empty.rasterizer = gRasterizer;
  empty.resize(0, 0);
  empty.drawTriangles(clip.data(), 3, indices.data(), 1);
  EXPECT_FALSE(empty.boxOccluded({ -1, 1, -1 }, { 1, 2, 1 }));
}

TEST_P(OcclusionBuffer, HugeCoordinateOffsetsStayConservative)
{
  const glm::dvec3 o(1e7, -2e7, 3e7);
  const Camera cam = perspectiveCamera(o + glm::dvec3(0, -10, 0), o, 60.0, 64, 48, 0.1, 100.0);
  std::vector<Triangle> w = wall(0.0, 5.0, 8);
  for (Triangle& t : w)
  {
    t.a += o;
    t.b += o;
    t.c += o;
  }
  MaskedDepthBuffer buffer = bufferFor(cam);
  draw(buffer, cam, w);
  EXPECT_TRUE(buffer.boxOccluded(o + glm::dvec3(-1, 1, -1), o + glm::dvec3(1, 2, 1)));
  EXPECT_FALSE(buffer.boxOccluded(o + glm::dvec3(-1, -2, -1), o + glm::dvec3(1, -1, 1)));
}

// The fuzz: random triangle soups and boxes seen by random perspective and parallel cameras at
// viewport sizes that are not multiples of the tile; every box reported hidden is checked at
// every pixel by the ray-casting oracle.
TEST_P(OcclusionBuffer, RandomScenesAreConservativeAtEveryPixel)
{
  std::mt19937_64 rng(12345);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::size_t tested = 0, occluded = 0, hiddenByOracle = 0;
  for (int scene = 0; scene < 60; ++scene)
  {
    const int width = 24 + static_cast<int>(uniform(0, 50));
    const int height = 16 + static_cast<int>(uniform(0, 40));
    const glm::dvec3 eye(uniform(-8, 8), uniform(-12, -6), uniform(-8, 8));
    const glm::dvec3 target(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    const Camera cam = scene % 3 == 2
      ? parallelCamera(eye, target, uniform(3, 8), width, height, 0.1, 60.0)
      : perspectiveCamera(eye, target, uniform(30, 100), width, height, 0.05, 60.0);
    std::vector<Triangle> soup;
    const int kind = scene % 4;
    if (kind == 0)
    {
      soup = wall(uniform(-3, 0), uniform(2, 6), 1 + static_cast<int>(uniform(0, 30)));
    }
    const int count = 10 + static_cast<int>(uniform(0, 80));
    for (int i = 0; i < count; ++i)
    {
      const glm::dvec3 c(uniform(-6, 6), uniform(-6, 6), uniform(-6, 6));
      const double size = kind == 1 ? uniform(0.05, 0.5) : uniform(0.5, 6);
      soup.push_back({ c + glm::dvec3(uniform(-size, size), uniform(-size, size), uniform(-size, size)),
        c + glm::dvec3(uniform(-size, size), uniform(-size, size), uniform(-size, size)),
        c + glm::dvec3(uniform(-size, size), uniform(-size, size), uniform(-size, size)) });
    }
    MaskedDepthBuffer buffer = bufferFor(cam);
    draw(buffer, cam, soup, FaceCulling::None, scene % 5 != 4);
    for (int b = 0; b < 25; ++b)
    {
      // Every fifth box is around the eye or next to it (rooms the viewer is in or beside).
      const glm::dvec3 c = b % 5 == 4 ? eye + glm::dvec3(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2))
                                      : glm::dvec3(uniform(-6, 6), uniform(-6, 6), uniform(-6, 6));
      const double s = b % 5 == 4 ? 3.0 : 1.5;
      const glm::dvec3 half(uniform(0.01, s), uniform(0.01, s), uniform(0.01, s));
      const bool reported = buffer.boxOccluded(c - half, c + half);
      const int visible = visiblePixels(cam, soup, c - half, c + half);
      ++tested;
      occluded += reported ? 1 : 0;
      hiddenByOracle += visible == 0 ? 1 : 0;
      ASSERT_FALSE(reported && visible > 0)
        << "scene " << scene << " box " << b << ": reported hidden, visible at " << visible
        << " pixels";
    }
  }
  // Not conservative by culling nothing (random soups at 24-74 pixels wide are the hard case
  // for one depth per tile: about 7% of the truly hidden boxes are found).
  EXPECT_GT(occluded, hiddenByOracle / 20) << tested << " boxes, " << hiddenByOracle
                                          << " truly hidden, " << occluded << " reported";
}

// The BVH's front-to-back cull with occlusion: opaque boxes occlude each other; every object the
// oracle sees at some pixel is in the visible list, with and without last frame's seeds, and
// with a random 30 % of the objects left out (OcclusionCull::active: as if another culler had
// removed them; the oracle then sees through them, and none is listed or drawn).
TEST_P(OcclusionCull, EveryObjectSeenAtSomePixelIsKept)
{
  std::mt19937_64 rng(777);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  culling::BoxArrays boxes;
  std::vector<Triangle> all;
  std::vector<std::vector<Triangle>> faces;
  for (int i = 0; i < 300; ++i)
  {
    // A grid of blocks with random sizes: rows hide rows.
    const glm::dvec3 c(-9 + 2.0 * (i % 10), -9 + 2.0 * ((i / 10) % 10), -3 + 2.0 * (i / 100));
    const glm::dvec3 half(uniform(0.3, 1.0), uniform(0.3, 1.0), uniform(0.3, 1.0));
    Box box;
    box.lo = c - half;
    box.hi = c + half;
    boxes.push_back(box);
    std::vector<Triangle> f;
    const glm::dvec3 l = box.lo, h = box.hi;
    const glm::dvec3 v[8] = { { l.x, l.y, l.z }, { h.x, l.y, l.z }, { l.x, h.y, l.z },
      { h.x, h.y, l.z }, { l.x, l.y, h.z }, { h.x, l.y, h.z }, { l.x, h.y, h.z },
      { h.x, h.y, h.z } };
    const int quads[6][4] = { { 0, 1, 3, 2 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 3, 7, 6 },
      { 0, 2, 6, 4 }, { 1, 3, 7, 5 } };
    for (const auto& q : quads)
    {
      f.push_back({ v[q[0]], v[q[1]], v[q[2]] });
      f.push_back({ v[q[0]], v[q[2]], v[q[3]] });
    }
    all.insert(all.end(), f.begin(), f.end());
    faces.push_back(f);
  }
  culling::Bvh bvh;
  bvh.build(boxes);
  std::vector<std::uint32_t> last;
  std::size_t culledTotal = 0, hiddenInFrustum = 0;
  std::mt19937_64 maskRng(31); // apart from the cameras' numbers
  for (int view = 0; view < 12; ++view)
  {
    std::vector<std::uint8_t> active(300, 1);
    const bool masked = view % 3 == 1;
    for (std::uint8_t& a : active)
    {
      a = !masked || std::uniform_real_distribution<double>(0, 1)(maskRng) < 0.7 ? 1 : 0;
    }
    const glm::dvec3 eye(uniform(-12, 12), -25 + uniform(-3, 3), uniform(-4, 4));
    const Camera cam = view % 4 == 3
      ? parallelCamera(eye, { 0, 0, 0 }, 8.0, 160, 120, 0.1, 80.0)
      : perspectiveCamera(eye, { uniform(-3, 3), 0, 0 }, 60.0, 160, 120, 0.1, 80.0);
    MaskedDepthBuffer buffer = bufferFor(cam);
    std::vector<glm::dvec4> clip;
    std::vector<std::uint32_t> indices;
    culling::OcclusionCull occlusion;
    occlusion.buffer = &buffer;
    occlusion.seeds = view % 2 == 1 ? &last : nullptr;
    occlusion.active = masked ? active.data() : nullptr;
    occlusion.drawOccluder = [&](std::uint32_t id) {
      ASSERT_TRUE(active[id]) << "view " << view << ": object " << id << " left out but drawn";
      // Occluder selection (views 2, 5, 8, 11): blocks thinner than 1.2 along x are never
      // drawn; leaving them out must not lose a visible object.
      const Box b = boxes.get(id);
      ASSERT_FALSE(view % 3 == 2 && b.hi.x - b.lo.x < 1.2) << "unselected occluder drawn";
      draw(buffer, cam, faces[id]);
    };
    if (view % 3 == 2)
    {
      occlusion.worthDrawing = [](const glm::dvec3& lo, const glm::dvec3& hi, std::uint32_t) {
        return hi.x - lo.x >= 1.2;
      };
    }
    culling::CullParams params;
    params.frustum = culling::Frustum::fromViewProjection(cam.clipFromWorld);
    const glm::dvec4 e = glm::inverse(cam.clipFromWorld) * glm::dvec4(0, 0, -1, 1);
    params.eye = glm::dvec3(e) / e.w;
    params.parallel = view % 4 == 3;
    params.viewDirection = glm::normalize(glm::dvec3(0, 0, 0) - eye);
    std::vector<std::uint32_t> visible;
    culling::CullStats stats;
    bvh.cullOccluded(params, occlusion, visible, &stats);
    std::vector<char> kept(300, 0);
    for (const std::uint32_t id : visible)
    {
      ASSERT_TRUE(active[id]) << "view " << view << ": object " << id << " left out but listed";
      kept[id] = 1;
    }
    // The oracle: the nearest box that takes part along each pixel's ray.
    std::vector<std::pair<glm::dvec3, glm::dvec3>> solid;
    std::vector<int> idOf;
    for (std::size_t id = 0; id < 300; ++id)
    {
      const Box b = boxes.get(id);
      if (active[id])
      {
        solid.emplace_back(b.lo, b.hi);
        idOf.push_back(static_cast<int>(id));
      }
    }
    const std::vector<int> nearest =
      nearestBoxPerPixel(cam.clipFromWorld, cam.width, cam.height, solid);
    std::vector<char> seen(300, 0);
    for (std::size_t pixel = 0; pixel < nearest.size(); ++pixel)
    {
      const int who = nearest[pixel] < 0 ? -1 : idOf[static_cast<std::size_t>(nearest[pixel])];
      if (who >= 0)
      {
        seen[static_cast<std::size_t>(who)] = 1;
        ASSERT_TRUE(kept[static_cast<std::size_t>(who)])
          << "view " << view << ": object " << who << " is seen at pixel " << pixel
          << " but was culled";
      }
    }
    culledTotal += stats.culledOcclusion;
    for (int id = 0; id < 300; ++id)
    {
      // In the frustum (kept by the frustum test alone) but seen at no pixel.
      const Box b = boxes.get(static_cast<std::size_t>(id));
      hiddenInFrustum +=
        active[id] && !seen[id] && !culling::boxOutside(params.frustum, b.lo, b.hi) ? 1 : 0;
    }
    last = visible;
  }
  // Rows behind rows are hidden: a good share of what the oracle finds hidden is culled (at
  // 160x120 about a third: a box is culled only when whole tiles are covered in front of it).
  EXPECT_GT(culledTotal, hiddenInFrustum / 4) << culledTotal << " culled by occlusion of "
                                             << hiddenInFrustum << " hidden in the frustum";
}

/// Objects for OcclusionCull tests: a box and the triangles drawn as its occluder each.
struct QuadScene
{
  culling::BoxArrays boxes;
  std::vector<std::vector<Triangle>> faces;

  void add(const glm::dvec3& lo, const glm::dvec3& hi, std::vector<Triangle> f)
  {
    Box box;
    box.lo = lo;
    box.hi = hi;
    boxes.push_back(box);
    faces.push_back(std::move(f));
  }

  /// The rectangle [x0, x1] x [z0, z1] in the plane at @p y (two triangles).
  void addRectangleAtY(double x0, double x1, double y, double z0, double z1)
  {
    const glm::dvec3 a(x0, y, z0), b(x1, y, z0), c(x1, y, z1), d(x0, y, z1);
    add(a, c, { { a, b, c }, { a, c, d } });
  }

  /// Bvh::cullOccluded() of @p bvh (built over these boxes) from @p cam, whose eye is at the
  /// origin, with OcclusionCull::active @p active; an object handed over as an occluder is drawn
  /// when @p occludes says so. The visible ids.
  std::set<std::uint32_t> cull(culling::Bvh& bvh, const Camera& cam, const std::uint8_t* active,
    const std::function<bool(std::uint32_t)>& occludes, culling::CullStats& stats) const
  {
    MaskedDepthBuffer buffer = bufferFor(cam);
    culling::OcclusionCull occlusion;
    occlusion.buffer = &buffer;
    occlusion.drawOccluder = [&](std::uint32_t id)
    {
      if (occludes(id))
      {
        draw(buffer, cam, faces[id]);
      }
    };
    occlusion.active = active;
    culling::CullParams params;
    params.frustum = culling::Frustum::fromViewProjection(cam.clipFromWorld);
    params.eye = glm::dvec3(0, 0, 0);
    std::vector<std::uint32_t> visible;
    bvh.cullOccluded(params, occlusion, visible, &stats);
    return std::set<std::uint32_t>(visible.begin(), visible.end());
  }
};

TEST_P(OcclusionCull, AWallBesideTheEyeIsDrawnBeforeWhatItHidesWhateverTheTree)
{
  // A wall of four panels two units in front of the eye, a long thin rail passing beside the eye
  // (its box comes nearer than the wall), and 200 blocks behind the wall near the rail. A
  // depth-first traversal that enters the rail's subtree first tests the blocks before the wall
  // is drawn and keeps them all; front to back over the whole tree, every block is hidden.
  QuadScene scene;
  for (int i = 0; i < 4; ++i)
  {
    // Panels of the wall y = 2 over x in [-8, 8], z in [-6, 6], abutting along x = -4, 0, 4.
    scene.addRectangleAtY(-8 + 4 * i, -4 + 4 * i, 2, -6, 6);
  }
  {
    const glm::dvec3 a(-0.2, -1, -0.45), b(0.2, -1, -0.45), c(0.2, 60, -0.45), d(-0.2, 60, -0.45);
    scene.add({ -0.2, -1, -0.45 }, { 0.2, 60, -0.45 }, { { a, b, c }, { a, c, d } });
  }
  const std::size_t firstBlock = scene.boxes.size();
  for (int i = 0; i < 200; ++i)
  {
    const double x = -2 + 0.2 * (i % 20);
    scene.addRectangleAtY(x - 0.05, x + 0.05, 10 + 4.0 * (i / 20), -0.55, -0.45);
  }
  for (const culling::BuildMethod method :
    { culling::BuildMethod::BinnedSah, culling::BuildMethod::Median })
  {
    culling::Bvh bvh;
    bvh.build(scene.boxes, method);
    const Camera cam = perspectiveCamera({ 0, 0, 0 }, { 0, 1, 0 }, 60.0, 160, 120, 0.1, 100.0);
    MaskedDepthBuffer buffer = bufferFor(cam);
    culling::OcclusionCull occlusion;
    occlusion.buffer = &buffer;
    occlusion.drawOccluder = [&](std::uint32_t id) { draw(buffer, cam, scene.faces[id]); };
    culling::CullParams params;
    params.frustum = culling::Frustum::fromViewProjection(cam.clipFromWorld);
    params.eye = glm::dvec3(0, 0, 0);
    std::vector<std::uint32_t> visible;
    bvh.cullOccluded(params, occlusion, visible, nullptr);
    for (const std::uint32_t id : visible)
    {
      EXPECT_LT(id, firstBlock) << "block " << id << " behind the wall was kept";
    }
    EXPECT_EQ(visible.size(), 3u); // the rail and the two middle panels (the outer ones are out of view)
  }
}

TEST_P(OcclusionCull, ObjectsLeftOutNeitherOccludeNorShow)
{
  // A wall (two panels) two units in front of the eye and 20 blocks behind it. Left out
  // (OcclusionCull::active 0, as when another culler removed them this frame), the panels hide
  // nothing and are not listed; a left-out block is neither listed nor tested.
  QuadScene scene;
  for (int i = 0; i < 2; ++i)
  {
    scene.addRectangleAtY(-8 + 8 * i, 8 * i, 2, -6, 6);
  }
  for (int i = 0; i < 20; ++i)
  {
    scene.addRectangleAtY(-1.04 + 0.1 * i, -0.96 + 0.1 * i, 10, -0.05, 0.05);
  }
  culling::Bvh bvh;
  bvh.build(scene.boxes);
  const Camera cam = perspectiveCamera({ 0, 0, 0 }, { 0, 1, 0 }, 60.0, 160, 120, 0.1, 100.0);
  auto cull = [&](const std::vector<std::uint8_t>& active, culling::CullStats& stats)
  {
    const auto occludes = [&](std::uint32_t id)
    {
      EXPECT_TRUE(active[id]) << "object " << id << " was left out but drawn as an occluder";
      return true;
    };
    return scene.cull(bvh, cam, active.data(), occludes, stats);
  };
  std::vector<std::uint8_t> all(scene.boxes.size(), 1);
  culling::CullStats stats;
  EXPECT_EQ(cull(all, stats), (std::set<std::uint32_t>{ 0, 1 })) << "the wall hides the blocks";
  EXPECT_EQ(stats.culledOcclusion, 20u);

  std::vector<std::uint8_t> noWall = all;
  noWall[0] = noWall[1] = 0;
  const std::set<std::uint32_t> seen = cull(noWall, stats);
  EXPECT_EQ(seen.size(), 20u) << "without the wall every block is seen";
  EXPECT_EQ(seen.count(0) + seen.count(1), 0u) << "left-out panels are listed";
  EXPECT_EQ(stats.objectsTested, 20u) << "left-out panels were tested";

  std::vector<std::uint8_t> noBlock = noWall;
  noBlock[7] = 0;
  const std::set<std::uint32_t> fewer = cull(noBlock, stats);
  EXPECT_EQ(fewer.size(), 19u);
  EXPECT_EQ(fewer.count(7), 0u) << "a left-out block is listed";
  EXPECT_EQ(stats.objectsTested, 19u);
}

TEST_P(OcclusionCull, NodesStandForTheirActiveObjects)
{
  // A wall two units in front of the eye and 400 blocks behind it, spread across the view.
  // Another culler kept the wall and 5 blocks: the traversal visits the nodes above those alone
  // (a node is the box around its active objects; one without any is not entered) and its
  // statistics count them alone.
  QuadScene scene;
  scene.addRectangleAtY(-8, 8, 2, -6, 6);
  for (int i = 0; i < 400; ++i)
  {
    const double x = -12.0 + 0.06 * i;
    scene.addRectangleAtY(x, x + 0.04, 10.0 + (i % 5), -0.05, 0.05);
  }
  culling::Bvh bvh;
  bvh.build(scene.boxes);
  const Camera cam = perspectiveCamera({ 0, 0, 0 }, { 0, 1, 0 }, 60.0, 160, 120, 0.1, 100.0);
  auto cull = [&](const std::uint8_t* active, bool withWall, culling::CullStats& stats)
  {
    return scene.cull(
      bvh, cam, active, [&](std::uint32_t id) { return id != 0 || withWall; }, stats);
  };
  const std::set<std::uint32_t> kept = { 0, 3, 101, 102, 250, 399 };
  std::vector<std::uint8_t> active(scene.boxes.size(), 0);
  for (const std::uint32_t id : kept)
  {
    active[id] = 1;
  }
  culling::CullStats all, few;
  // Without the wall drawn every block in the frustum is seen: the blocks kept, those of the
  // others in view.
  const std::set<std::uint32_t> seenAll = cull(nullptr, false, all);
  const std::set<std::uint32_t> seenFew = cull(active.data(), false, few);
  std::set<std::uint32_t> expected;
  for (const std::uint32_t id : kept)
  {
    if (seenAll.count(id))
    {
      expected.insert(id);
    }
  }
  EXPECT_GT(seenAll.size(), 100u);
  EXPECT_EQ(seenFew, expected);
  EXPECT_GE(expected.size(), 3u) << "the kept blocks are in view";
  const std::size_t depth = 2 * static_cast<std::size_t>(std::ceil(std::log2(401.0 / 4))) + 2;
  EXPECT_LE(few.nodesVisited, kept.size() * depth)
    << "nodes without an active object were entered (all active: " << all.nodesVisited << ")";
  EXPECT_LE(few.objectsTested, kept.size());
  EXPECT_EQ(few.culledFrustum, kept.size() - expected.size())
    << "culled by the frustum counts the active objects, not the subtrees";
  // With the wall: the 5 blocks are hidden, and culled by occlusion counts them, not the
  // subtrees they are in.
  culling::CullStats walled;
  EXPECT_EQ(cull(active.data(), true, walled), (std::set<std::uint32_t>{ 0 }));
  EXPECT_EQ(walled.culledOcclusion + walled.culledFrustum, kept.size() - 1);
}

TEST_P(OcclusionBuffer, TheRevisionChangesWhenATestsAnswerMay)
{
  const Camera cam = perspectiveCamera({ 0, 0, 10 }, { 0, 0, 0 }, 60.0, 64, 48, 0.1, 100.0);
  MaskedDepthBuffer buffer = bufferFor(cam);
  const glm::dvec3 lo(-1, -1, -6), hi(1, 1, -4);
  std::uint64_t revision = buffer.revision();
  EXPECT_FALSE(buffer.boxOccluded(lo, hi));
  EXPECT_EQ(revision, buffer.revision()) << "a test is not a change";
  draw(buffer, cam, { { { -50, -50, 5 }, { 50, -50, 5 }, { 0, 80, 5 } } });
  EXPECT_NE(revision, buffer.revision()) << "a wall was drawn";
  EXPECT_TRUE(buffer.boxOccluded(lo, hi));
  revision = buffer.revision();
  buffer.clear();
  EXPECT_NE(revision, buffer.revision()) << "cleared";
  EXPECT_FALSE(buffer.boxOccluded(lo, hi));
  revision = buffer.revision();
  buffer.setClipFromWorld(cam.clipFromWorld);
  EXPECT_NE(revision, buffer.revision()) << "a camera was given";
}

TEST_P(OcclusionBuffer, TwoPartsSharingAnEdgeHideABoxBehindTheSeam)
{
  // Two triangles of different parts (two draw calls, no neighbour table between them) share
  // the diagonal of a square wall; a thin box right behind the diagonal is hidden: the tiles the
  // seam crosses are completed by the union of the two masks. The diagonal is placed off the
  // pixel centres (an outline edge keeps a 1/64-pixel margin on both sides, so a seam through a
  // row of centres would leave them uncovered: conservative, and not what this test is about).
  const Camera cam = perspectiveCamera({ 0.013, -10, 0.007 }, { 0.013, 0, 0.007 }, 60.0, 83, 61,
    0.1, 100.0);
  MaskedDepthBuffer buffer = bufferFor(cam);
  const glm::dvec3 a(-8, 0, -8), b(8, 0, -8), c(8, 0, 8), d(-8, 0, 8);
  draw(buffer, cam, { { a, b, c } });
  draw(buffer, cam, { { a, c, d } });
  for (double t = -0.8; t <= 0.8; t += 0.4)
  {
    const glm::dvec3 lo(t - 0.05, 1.0, t - 0.05), hi(t + 0.05, 1.5, t + 0.05);
    EXPECT_EQ(visiblePixels(cam, { { a, b, c }, { a, c, d } }, lo, hi), 0);
    EXPECT_TRUE(buffer.boxOccluded(lo, hi)) << "a box behind the seam at " << t;
  }
}

// An edge is inside an occluder only if the neighbour across it faces the same way: across a
// degenerate neighbour (zero area: no facing) it stays an outline edge and keeps the coverage
// margin, whether the neighbour's facing is computed or read from what the front end found.
// Triangle A's edge x = 4.5 runs through the centres of pixel column 4: covered only if the edge
// is inside the occluder (A takes the tie there), never with the margin.
TEST_P(OcclusionBuffer, ADegenerateNeighbourLeavesTheSharedEdgeAnOutline)
{
  const int width = 16, height = 8;
  // Window coordinates (exact in clip space and back); w = 1, window depth 0.5.
  auto clipOf = [&](double x, double y)
  { return glm::dvec4(x / width * 2.0 - 1.0, y / height * 2.0 - 1.0, 0.0, 1.0); };
  auto column4 = [&](const glm::dvec2& third)
  {
    // A = 0 1 2 (counter-clockwise), B = 1 0 3 across A's edge 0 -> 1.
    const glm::dvec2 window[4] = { { 4.5, 0.0 }, { 4.5, 8.0 }, { -4.0, 4.0 }, third };
    std::vector<glm::dvec4> clip;
    std::vector<double> xyz;
    for (const glm::dvec2& p : window)
    {
      clip.push_back(clipOf(p.x, p.y));
      xyz.insert(xyz.end(), { p.x, p.y, 0.0 });
    }
    const std::vector<std::uint32_t> indices = { 0, 1, 2, 1, 0, 3 };
    const std::vector<std::uint32_t> neighbors =
      buildTriangleNeighbors(xyz.data(), 4, indices.data(), 2);
    EXPECT_EQ(neighbors[0], 1u);
    EXPECT_EQ(neighbors[3], 0u);
    MaskedDepthBuffer buffer;
    buffer.rasterizer = gRasterizer;
    buffer.resize(width, height);
    buffer.drawTriangles(
      clip.data(), clip.size(), indices.data(), 2, FaceCulling::None, neighbors.data());
    const MaskedDepthBuffer::Tile& tile = buffer.tiles()[0]; // pixels x 0-7, y 0-3
    const std::uint32_t covered = tile.z0 <= 1.0f ? 0xFFFFFFFFu : tile.mask;
    return covered & 0x10101010u; // pixel column 4 of the four scanlines
  };
  // A neighbour facing A's way: the edge is inside, every centre on it goes to A.
  EXPECT_EQ(column4({ 12.0, 4.0 }), 0x10101010u);
  // A degenerate neighbour (its third vertex on the edge): outline, the margin keeps column 4.
  EXPECT_EQ(column4({ 4.5, 4.0 }), 0u);
  EXPECT_EQ(column4({ 4.5, 20.0 }), 0u);
}

// Runs of triangles whose model-space box is behind what the buffer has are skipped before their
// vertices are projected (TriangleClusters): the buffer must come out bit for bit as when every
// triangle is drawn (each skipped triangle would have been rejected by its own test), with a
// model matrix, both projections, eyes close to the triangles and the near plane cutting some.
TEST_P(OcclusionBuffer, HiddenTriangleClustersAreSkippedWithTheSameBuffer)
{
  std::mt19937_64 rng(777);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::size_t skipped = 0, tested = 0;
  for (int scene = 0; scene < 80; ++scene)
  {
    const int width = 24 + static_cast<int>(uniform(0, 90));
    const int height = 16 + static_cast<int>(uniform(0, 70));
    const glm::dvec3 eye(uniform(-8, 8), uniform(-12, -4), uniform(-8, 8));
    const glm::dvec3 target(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    const Camera cam = scene % 3 == 2
      ? parallelCamera(eye, target, uniform(3, 8), width, height, 0.1, 60.0)
      : perspectiveCamera(eye, target, uniform(30, 100), width, height,
          scene % 4 == 1 ? 2.0 : 0.05, 60.0);
    const glm::dmat4 worldFromModel =
      glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(uniform(-1, 1), uniform(-1, 1),
                                                  uniform(-1, 1))),
        uniform(0, 6.28), glm::normalize(glm::dvec3(uniform(-1, 1), uniform(-1, 1), 1.0)));
    const glm::dmat4 clipFromModel = cam.clipFromWorld * worldFromModel;
    // A wall in front (world space), then runs of nearby triangles (model space).
    const std::vector<Triangle> front = wall(uniform(-4, 0), uniform(2, 8), 1 + scene % 7);
    const std::size_t perRun = 1 + static_cast<std::size_t>(scene % 9);
    const int runs = 5 + static_cast<int>(uniform(0, 40));
    std::vector<glm::dvec4> clip;
    std::vector<double> xyz;
    std::vector<std::uint32_t> indices;
    for (int r = 0; r < runs; ++r)
    {
      const glm::dvec3 c(uniform(-6, 6), uniform(-6, 8), uniform(-6, 6));
      const double size = uniform(0.05, 3.0);
      for (std::size_t t = 0; t < perRun; ++t)
      {
        for (int k = 0; k < 3; ++k)
        {
          // Some triangles share the previous triangle's last point.
          if (k == 0 && t > 0 && (t % 2) == 1)
          {
            indices.push_back(indices.back());
            continue;
          }
          const glm::dvec3 p =
            c + glm::dvec3(uniform(-size, size), uniform(-size, size), uniform(-size, size));
          indices.push_back(static_cast<std::uint32_t>(clip.size()));
          clip.push_back(clipFromModel * glm::dvec4(p, 1.0));
          xyz.insert(xyz.end(), { p.x, p.y, p.z });
        }
      }
    }
    const std::size_t triangles = indices.size() / 3;
    const std::vector<std::uint32_t> neighbors =
      buildTriangleNeighbors(xyz.data(), clip.size(), indices.data(), triangles);
    const std::vector<double> boxes =
      buildTriangleClusters(xyz.data(), clip.size(), indices.data(), triangles, perRun);
    ASSERT_EQ(boxes.size(), 6 * ((triangles + perRun - 1) / perRun));
    TriangleClusters clusters;
    clusters.clipFromModel = clipFromModel;
    clusters.boxes = boxes.data();
    clusters.trianglesPerCluster = perRun;
    const FaceCulling culling = scene % 2 ? FaceCulling::None : FaceCulling::Back;

    MaskedDepthBuffer all = bufferFor(cam), runsSkipped = bufferFor(cam);
    draw(all, cam, front);
    draw(runsSkipped, cam, front);
    all.drawTriangles(
      clip.data(), clip.size(), indices.data(), triangles, culling, neighbors.data());
    runsSkipped.drawTriangles(clip.data(), clip.size(), indices.data(), triangles, culling,
      neighbors.data(), &clusters);
    ASSERT_EQ(all.tiles().size(), runsSkipped.tiles().size());
    for (std::size_t i = 0; i < all.tiles().size(); ++i)
    {
      const MaskedDepthBuffer::Tile& a = all.tiles()[i];
      const MaskedDepthBuffer::Tile& b = runsSkipped.tiles()[i];
      ASSERT_TRUE(a.z0 == b.z0 && a.mask == b.mask && (a.mask == 0 || a.z1 == b.z1))
        << "scene " << scene << " tile " << i;
    }
    EXPECT_EQ(all.stats().trianglesDrawn, runsSkipped.stats().trianglesDrawn) << "scene " << scene;
    tested += runsSkipped.stats().clustersTested;
    skipped += runsSkipped.stats().clustersHidden;

    // The same model points handed over untransformed (ModelVertices, double and float): the
    // buffer transforms the points it needs and must come out bit for bit as from clip space.
    std::vector<float> xyzFloat(xyz.begin(), xyz.end());
    std::vector<glm::dvec4> clipOfFloat(clip.size());
    for (std::size_t i = 0; i < clip.size(); ++i)
    {
      clipOfFloat[i] =
        clipFromModel * glm::dvec4(xyzFloat[3 * i], xyzFloat[3 * i + 1], xyzFloat[3 * i + 2], 1.0);
    }
    for (int precision = 0; precision < 2; ++precision)
    {
      ModelVertices model;
      model.clipFromModel = clipFromModel;
      if (precision)
      {
        model.xyzFloat = xyzFloat.data();
      }
      else
      {
        model.xyzDouble = xyz.data();
      }
      MaskedDepthBuffer fromClip = bufferFor(cam), fromModel = bufferFor(cam);
      draw(fromClip, cam, front);
      draw(fromModel, cam, front);
      fromClip.drawTriangles(precision ? clipOfFloat.data() : clip.data(), clip.size(),
        indices.data(), triangles, culling, neighbors.data(), &clusters);
      fromModel.drawTriangles(
        model, clip.size(), indices.data(), triangles, culling, neighbors.data(), &clusters);
      for (std::size_t i = 0; i < fromClip.tiles().size(); ++i)
      {
        const MaskedDepthBuffer::Tile& a = fromClip.tiles()[i];
        const MaskedDepthBuffer::Tile& b = fromModel.tiles()[i];
        ASSERT_TRUE(a.z0 == b.z0 && a.mask == b.mask && a.z1 == b.z1)
          << "scene " << scene << " tile " << i << (precision ? " float" : " double");
      }
      EXPECT_EQ(fromClip.stats().trianglesDrawn, fromModel.stats().trianglesDrawn);
      EXPECT_EQ(fromClip.stats().trianglesRejected, fromModel.stats().trianglesRejected);
      EXPECT_EQ(fromClip.stats().tilesUpdated, fromModel.stats().tilesUpdated);
    }
  }
  // Not the same by skipping nothing.
  EXPECT_GT(skipped, tested / 10) << skipped << " of " << tested << " runs skipped";
}

TEST_P(OcclusionBuffer, ModelVerticesWithoutPointsDrawNothing)
{
  const Camera cam = perspectiveCamera({ 0, 0, 10 }, { 0, 0, 0 }, 60.0, 64, 48, 0.1, 100.0);
  MaskedDepthBuffer buffer = bufferFor(cam);
  const std::uint32_t indices[3] = { 0, 1, 2 };
  buffer.drawTriangles(ModelVertices(), 3, indices, 1);
  EXPECT_EQ(buffer.stats().trianglesRejected, 1u);
  EXPECT_FALSE(buffer.boxOccluded({ -1, -1, -6 }, { 1, 1, -4 }));
}

namespace
{
/// Window point (pixels, window depth in clip z) of a camera whose clip space is world space.
glm::dvec3 windowPoint(const Camera& cam, double x, double y, double z)
{
  return { 2.0 * x / cam.width - 1.0, 2.0 * y / cam.height - 1.0, z };
}

/// A pixel centre that a buffer claims covered: at the whole tile's z0, or at the working
/// layer's z1 where its mask has the pixel.
struct ClaimedPixel
{
  int i, j;
  double depth;
  bool whole;
};

/// Every pixel of the viewport that @p buffer claims covered at a depth below 1.
std::vector<ClaimedPixel> claimedPixels(const MaskedDepthBuffer& buffer, int width, int height)
{
  std::vector<ClaimedPixel> claimed;
  for (int ty = 0; ty < buffer.tilesY(); ++ty)
  {
    for (int tx = 0; tx < buffer.tilesX(); ++tx)
    {
      const MaskedDepthBuffer::Tile& tile = buffer.tiles()[ty * buffer.tilesX() + tx];
      for (int bit = 0; bit < 32; ++bit)
      {
        const int i = tx * 8 + bit % 8, j = ty * 4 + bit / 8;
        const bool whole = tile.z0 < 1.0f, layer = tile.mask & (1u << bit);
        const double depth = whole ? tile.z0 : tile.z1;
        if (i < width && j < height && (whole || layer) && depth < 1.0)
        {
          claimed.push_back({ i, j, depth, whole });
        }
      }
    }
  }
  return claimed;
}

/// A box of 1/50 pixel around @p p's centre, just behind the depth it is claimed at: hidden when
/// the claim holds.
std::pair<glm::dvec3, glm::dvec3> justBehind(const Camera& cam, const ClaimedPixel& p)
{
  const double z = 2.0 * p.depth - 1.0;
  return { windowPoint(cam, p.i + 0.49, p.j + 0.49, z + 1e-6),
    windowPoint(cam, p.i + 0.51, p.j + 0.51, z + 2e-6) };
}

/// What OpenGL draws of @p soup with @p culling (facing: the sign of det[x y w] in clip space).
std::vector<Triangle> drawnFaces(
  const Camera& cam, const std::vector<Triangle>& soup, FaceCulling culling)
{
  std::vector<Triangle> out;
  for (const Triangle& t : soup)
  {
    const glm::dvec4 a = cam.clipFromWorld * glm::dvec4(t.a, 1.0);
    const glm::dvec4 b = cam.clipFromWorld * glm::dvec4(t.b, 1.0);
    const glm::dvec4 c = cam.clipFromWorld * glm::dvec4(t.c, 1.0);
    const double det =
      a.x * (b.y * c.w - b.w * c.y) - a.y * (b.x * c.w - b.w * c.x) + a.w * (b.x * c.y - b.y * c.x);
    if (culling == FaceCulling::None || (culling == FaceCulling::Back && det > 0.0) ||
      (culling == FaceCulling::Front && det < 0.0))
    {
      out.push_back(t);
    }
  }
  return out;
}
} // namespace

// What float arithmetic makes hazardous (OcclusionBuffer.h, "Two rasterizers"), for both
// rasterizers, every box reported hidden checked at every pixel by the oracle: meshes whose
// vertices lie on tile and pixel-centre boundaries (and within 1e-7 pixel of them), slivers
// thinner than a pixel at every slope (exactly and nearly horizontal ones included), vertices
// far beyond the float rasterizer's range, triangles cut by the near plane, both windings with
// either face culled.
TEST_P(OcclusionBuffer, FloatHazardsAreConservativeAtEveryPixel)
{
  std::mt19937_64 rng(2026);
  auto uniform = [&](double a, double b)
  { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::size_t reported = 0, hiddenByOracle = 0, pixelsClaimed = 0;
  for (int scene = 0; scene < 100; ++scene)
  {
    const int kind = scene % 5;
    Camera cam;
    cam.width = 67;
    cam.height = 45;
    if (kind == 3)
    {
      cam = perspectiveCamera({ 0, -3, 0 }, { 0, 0, 0 }, 70.0, 67, 45, 0.5, 20.0);
    }
    auto snap = [&](double v, int step)
    {
      static const double nudge[] = { 0.0, 1e-7, -1e-7, 0.5, -0.5, 1e-3, 0.25 };
      return step * std::round(v / step) + nudge[rng() % 7];
    };
    std::vector<Triangle> soup;
    FaceCulling culling = FaceCulling::None;
    if (kind == 0 || kind == 4)
    {
      // A jittered grid mesh; kind 4: random windings, one face culled.
      const int nx = 2 + static_cast<int>(rng() % 6), ny = 2 + static_cast<int>(rng() % 5);
      const double x0 = uniform(-10, 40), y0 = uniform(-6, 25), sx = uniform(2, 14),
                   sy = uniform(1, 10), z0 = uniform(-0.5, 0.3), zx = uniform(-0.01, 0.01);
      const int step = scene % 2 == 0 ? 8 : 1;
      std::vector<glm::dvec3> p;
      for (int j = 0; j <= ny; ++j)
      {
        for (int i = 0; i <= nx; ++i)
        {
          const double x = snap(x0 + i * sx, step), y = snap(y0 + j * sy, step == 8 ? 4 : 1);
          p.push_back(windowPoint(cam, x, y, z0 + zx * x));
        }
      }
      for (int j = 0; j < ny; ++j)
      {
        for (int i = 0; i < nx; ++i)
        {
          const glm::dvec3& a = p[j * (nx + 1) + i];
          const glm::dvec3& b = p[j * (nx + 1) + i + 1];
          const glm::dvec3& c = p[(j + 1) * (nx + 1) + i + 1];
          const glm::dvec3& d = p[(j + 1) * (nx + 1) + i];
          const bool flip = kind == 4 && rng() % 2 == 0;
          soup.push_back(flip ? Triangle{ a, c, b } : Triangle{ a, b, c });
          soup.push_back(flip ? Triangle{ a, d, c } : Triangle{ a, c, d });
        }
      }
      culling =
        kind == 4 ? (scene % 2 == 0 ? FaceCulling::Back : FaceCulling::Front) : FaceCulling::None;
    }
    else if (kind == 1)
    {
      // Slivers in pairs sharing their long edge.
      for (int i = 0; i < 20; ++i)
      {
        static const double slopes[] = { 0.0, 1e-6, -3e-5, 1e-3, 0.7, 40.0, 1e5 };
        const double slope = i % 3 == 0 ? slopes[rng() % 7] : uniform(-2, 2);
        const glm::dvec2 dir = glm::normalize(glm::dvec2(1.0, slope));
        const glm::dvec2 normal(-dir.y, dir.x);
        const glm::dvec2 c(uniform(0, 67), uniform(0, 45));
        const double length = uniform(2, 60), width = uniform(1e-4, 0.8), z = uniform(-0.5, 0.5);
        const glm::dvec2 a = c - dir * length * 0.5, b = c + dir * length * 0.5;
        const glm::dvec2 up = c + normal * width, down = c - normal * uniform(1e-4, 0.8);
        const glm::dvec3 pa = windowPoint(cam, a.x, a.y, z), pb = windowPoint(cam, b.x, b.y, z);
        soup.push_back({ pa, pb, windowPoint(cam, up.x, up.y, z) });
        soup.push_back({ pb, pa, windowPoint(cam, down.x, down.y, z) });
      }
    }
    else if (kind == 2)
    {
      // Fans whose outer vertices are far outside the viewport (beyond 2^14 pixels or not).
      static const double far[] = { 1e3, 1.6e4, 1.7e4, 1e6 };
      const glm::dvec2 c(uniform(0, 67), uniform(0, 45));
      const double z = uniform(-0.5, 0.5);
      const int n = 3 + static_cast<int>(rng() % 5);
      std::vector<glm::dvec3> rim;
      for (int i = 0; i < n; ++i)
      {
        const double angle = 6.283185307179586 * (i + uniform(0, 0.5)) / n;
        const double r = i % 2 == 0 ? far[rng() % 4] : uniform(3, 40);
        rim.push_back(windowPoint(cam, c.x + r * std::cos(angle), c.y + r * std::sin(angle), z));
      }
      for (int i = 0; i < n; ++i)
      {
        soup.push_back({ windowPoint(cam, c.x, c.y, z), rim[i], rim[(i + 1) % n] });
      }
    }
    else
    {
      // Near plane (y = -2.5): a tilted grid reaching from behind the eye to the far side.
      const int n = 3 + static_cast<int>(rng() % 5);
      const double tilt = uniform(0.2, 3);
      for (int i = 0; i < n; ++i)
      {
        for (int k = 0; k < n; ++k)
        {
          auto at = [&](int a, int b)
          {
            const double x = -2.0 + 4.0 * a / n, z = -2.0 + 4.0 * b / n;
            return glm::dvec3(x, -2.5 + tilt * (z + 1.0), z);
          };
          soup.push_back({ at(i, k), at(i + 1, k), at(i + 1, k + 1) });
          soup.push_back({ at(i, k), at(i + 1, k + 1), at(i, k + 1) });
        }
      }
    }
    MaskedDepthBuffer buffer = bufferFor(cam);
    draw(buffer, cam, soup, culling, scene % 3 != 2);
    const std::vector<Triangle> drawn = drawnFaces(cam, soup, culling);
    if (kind != 3)
    {
      // The buffer itself, below the box test's one-pixel safety ring: every pixel centre it
      // claims (the whole tile at z0, the working layer's mask at z1) has a drawn triangle at
      // least as near (a box of 1/50 pixel just behind the claimed depth is hidden there).
      for (const ClaimedPixel& p : claimedPixels(buffer, cam.width, cam.height))
      {
        ++pixelsClaimed;
        const auto box = justBehind(cam, p);
        ASSERT_EQ(visiblePixels(cam, drawn, box.first, box.second), 0)
          << "scene " << scene << " (kind " << kind << "): pixel " << p.i << ", " << p.j
          << " claimed at depth " << p.depth << (p.whole ? " (whole tile)" : " (working layer)");
      }
    }
    for (int b = 0; b < 80; ++b)
    {
      glm::dvec3 lo, hi;
      if (kind == 3)
      {
        const glm::dvec3 c(uniform(-2, 2), uniform(-1, 4), uniform(-2, 2));
        const glm::dvec3 half(uniform(0.01, 0.3), uniform(0.01, 0.3), uniform(0.01, 0.3));
        lo = c - half;
        hi = c + half;
      }
      else
      {
        double x = uniform(-2, 69), y = uniform(-2, 47), z = uniform(-0.6, 0.95);
        double w = uniform(0.05, 3), h = uniform(0.05, 3), d = uniform(0.001, 0.04);
        if (b % 2 == 0 && !soup.empty())
        {
          // A box smaller than a pixel just outside or inside an edge, behind it: the coverage
          // of pixel centres near edges is what rounding can get wrong.
          const Triangle& t = soup[rng() % soup.size()];
          const glm::dvec3 v[3] = { t.a, t.b, t.c };
          const int e = static_cast<int>(rng() % 3);
          const glm::dvec2 p0((v[e].x + 1) * 0.5 * cam.width, (v[e].y + 1) * 0.5 * cam.height);
          const glm::dvec3& q = v[(e + 1) % 3];
          const glm::dvec2 p1((q.x + 1) * 0.5 * cam.width, (q.y + 1) * 0.5 * cam.height);
          const glm::dvec2 along = p0 + (p1 - p0) * uniform(0, 1);
          const glm::dvec2 n = glm::length(p1 - p0) > 0.0
            ? glm::dvec2(p0.y - p1.y, p1.x - p0.x) / glm::length(p1 - p0)
            : glm::dvec2(0.0);
          const glm::dvec2 at = along + n * uniform(-1.0, 1.0);
          x = at.x;
          y = at.y;
          w = uniform(0.01, 0.4);
          h = uniform(0.01, 0.4);
          z = std::min(0.95, std::max({ v[0].z, v[1].z, v[2].z }) + uniform(0.01, 0.1));
          d = 0.001;
        }
        lo = windowPoint(cam, x - w, y - h, z - d);
        hi = windowPoint(cam, x + w, y + h, z + d);
      }
      const bool occluded = buffer.boxOccluded(lo, hi);
      const int visible = visiblePixels(cam, drawn, lo, hi);
      reported += occluded ? 1 : 0;
      hiddenByOracle += visible == 0 ? 1 : 0;
      ASSERT_FALSE(occluded && visible > 0)
        << "scene " << scene << " (kind " << kind << ") box " << b
        << ": reported hidden, visible at " << visible << " pixels";
    }
  }
  // Not conservative by doing nothing.
  EXPECT_GT(pixelsClaimed, 10000u);
  EXPECT_GT(reported, hiddenByOracle / 5)
    << hiddenByOracle << " truly hidden, " << reported << " reported";
}

// glPolygonOffset pushes the occluders back: what lies between the surface and its offset depth
// is drawn in front of it by OpenGL, so it must not be reported hidden.
TEST_P(OcclusionBuffer, PolygonOffsetPushesOccludersBack)
{
  Camera cam;
  cam.width = 67;
  cam.height = 45;
  // A wall over the whole viewport, clip z = 0.05 x (window depth slope 0.05 / 67 per pixel,
  // 0.012 in clip z over a tile).
  const std::vector<Triangle> wall = { { { -1.5, -1.5, -0.075 }, { 1.5, -1.5, 0.075 },
                                         { 1.5, 1.5, 0.075 } },
    { { -1.5, -1.5, -0.075 }, { 1.5, 1.5, 0.075 }, { -1.5, 1.5, -0.075 } } };
  // A small box at the centre (wall at clip z 0 there), its nearest clip z at @p z.
  auto hidden = [&](double factor, double units, double z)
  {
    MaskedDepthBuffer buffer = bufferFor(cam);
    buffer.polygonOffsetFactor = factor;
    buffer.polygonOffsetDepth = units;
    draw(buffer, cam, wall);
    return buffer.boxOccluded({ -0.01, -0.01, z }, { 0.01, 0.01, z + 0.1 });
  };
  EXPECT_TRUE(hidden(0.0, 0.0, 0.05));
  EXPECT_FALSE(hidden(0.0, 0.05, 0.05)); // window depth offset 0.05 = clip 0.1
  EXPECT_TRUE(hidden(0.0, 0.05, 0.15));
  EXPECT_FALSE(hidden(40.0, 0.0, 0.05)); // 40 x 0.05 / 67 = 0.03 window depth
  EXPECT_TRUE(hidden(40.0, 0.0, 0.15));
}

namespace
{
/// A mesh in window coordinates of @p cam (clip space = world space): the grid of points
/// (x0 + i sx, y0 + j sy), i <= nx, j <= ny, each cell split along a diagonal (alternating), at
/// clip depth @p z, counter-clockwise.
std::vector<Triangle> windowGrid(
  const Camera& cam, double x0, double y0, double sx, double sy, int nx, int ny, double z)
{
  std::vector<Triangle> out;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const glm::dvec3 a = windowPoint(cam, x0 + i * sx, y0 + j * sy, z);
      const glm::dvec3 b = windowPoint(cam, x0 + (i + 1) * sx, y0 + j * sy, z);
      const glm::dvec3 c = windowPoint(cam, x0 + (i + 1) * sx, y0 + (j + 1) * sy, z);
      const glm::dvec3 d = windowPoint(cam, x0 + i * sx, y0 + (j + 1) * sy, z);
      if ((i + j) % 2 == 0)
      {
        out.push_back({ a, b, c });
        out.push_back({ a, c, d });
      }
      else
      {
        out.push_back({ a, b, d });
        out.push_back({ b, c, d });
      }
    }
  }
  return out;
}
} // namespace

// Interior edges (shared by two triangles of the same facing) give every pixel centre on them
// to exactly one of the two (OcclusionBuffer.h): meshes whose vertices, and so whose horizontal,
// vertical and diagonal edges, lie on pixel centres (exact in window coordinates: a 64 x 32
// viewport) fill every tile inside their outline, which only the outline's margin leaves open,
// and hide a box behind them.
TEST_P(OcclusionBuffer, InteriorEdgesThroughPixelCentresAreWatertight)
{
  Camera cam;
  cam.width = 64;
  cam.height = 32;
  struct Mesh
  {
    double sx, sy;
    int nx, ny;
  };
  // Cells of 4 x 4 (diagonals through every centre they cross), 6 x 3 (slope 1/2), 10 x 1 and
  // 2 x 9 (long slivers), 60 x 28 (two big triangles).
  const Mesh meshes[] = { { 4, 4, 15, 7 }, { 6, 3, 10, 9 }, { 10, 1, 6, 28 }, { 2, 9, 30, 3 },
    { 60, 28, 1, 1 } };
  for (const Mesh& m : meshes)
  {
    const std::vector<Triangle> mesh = windowGrid(cam, 1.5, 1.5, m.sx, m.sy, m.nx, m.ny, 0.2);
    // A fan around a centre, its rim on centres 14 to 20 pixels away (edges of many slopes
    // through centres).
    std::vector<Triangle> fan;
    const int rim[][2] = { { 10, 0 }, { 7, 5 }, { 3, 9 }, { 0, 10 }, { -4, 7 }, { -9, 2 },
      { -10, 0 }, { -6, -7 }, { -1, -10 }, { 5, -8 }, { 9, -3 } };
    const int n = static_cast<int>(sizeof rim / sizeof rim[0]);
    for (int k = 0; k < n; ++k)
    {
      const int* p = rim[k];
      const int* q = rim[(k + 1) % n];
      fan.push_back({ windowPoint(cam, 32.5, 16.5, 0.1),
        windowPoint(cam, 32.5 + 2 * p[0], 16.5 + 2 * p[1], 0.1),
        windowPoint(cam, 32.5 + 2 * q[0], 16.5 + 2 * q[1], 0.1) });
    }
    const std::vector<Triangle>* soups[] = { &mesh, &fan };
    for (const std::vector<Triangle>* soup : soups)
    {
      MaskedDepthBuffer buffer = bufferFor(cam);
      draw(buffer, cam, *soup);
      if (soup == &mesh)
      {
        // The mesh covers the centres x in (1.5, 61.5), y in (1.5, 29.5): tiles 1..6 x 1..6.
        for (int ty = 1; ty <= 6; ++ty)
        {
          for (int tx = 1; tx <= 6; ++tx)
          {
            const MaskedDepthBuffer::Tile& tile = buffer.tiles()[ty * buffer.tilesX() + tx];
            EXPECT_LT(tile.z0, 1.0f) << "cells " << m.sx << " x " << m.sy << ": tile " << tx << ", "
                                     << ty << " not full (mask " << std::hex << tile.mask << ")";
          }
        }
        // A box over those tiles (the test looks one pixel further).
        EXPECT_TRUE(
          buffer.boxOccluded(windowPoint(cam, 9.5, 5.5, 0.5), windowPoint(cam, 54, 26, 0.6)));
      }
      else
      {
        // Tiles 3 and 4 of rows 3 and 4 (x 24..39, y 12..19) are well inside the fan.
        for (int ty = 3; ty <= 4; ++ty)
        {
          for (int tx = 3; tx <= 4; ++tx)
          {
            const MaskedDepthBuffer::Tile& tile = buffer.tiles()[ty * buffer.tilesX() + tx];
            EXPECT_LT(tile.z0, 1.0f) << "fan: tile " << tx << ", " << ty << " not full (mask "
                                     << std::hex << tile.mask << ")";
          }
        }
        EXPECT_TRUE(
          buffer.boxOccluded(windowPoint(cam, 25.5, 13.5, 0.5), windowPoint(cam, 38, 18, 0.6)));
      }
    }
  }
}

// Outline edges keep every claimed pixel centre at least `coverageMargin` inside
// (OcclusionBuffer.h): triangles whose edges pass at 0, 1/2, 0.999 and 1.001 margins and two
// margins from rows of pixel centres, at many slopes, drawn without neighbours; every pixel the
// buffer claims (whole tiles and working layers) must be covered, by the ray oracle, by the
// triangles shrunk by the margin (less a millionth of it against the shrinking's own rounding).
TEST_P(OcclusionBuffer, OutlineEdgesKeepTheCoverageMarginAtEveryPixel)
{
  Camera cam;
  cam.width = 64;
  cam.height = 32;
  std::mt19937_64 rng(64);
  auto uniform = [&](double a, double b)
  { return std::uniform_real_distribution<double>(a, b)(rng); };
  const double margin = MaskedDepthBuffer().coverageMargin;
  std::size_t claimed = 0;
  for (int scene = 0; scene < 60; ++scene)
  {
    std::vector<Triangle> soup, shrunk;
    for (int t = 0; t < 6; ++t)
    {
      // One edge through (or just beside) a pixel centre, at a slope from a list or random.
      static const double angles[] = { 0.0, 90.0, 45.0, 135.0, 26.56505117707799, 180.0, 270.0 };
      const double angle = glm::radians(t % 2 == 0 ? angles[rng() % 7] : uniform(0.0, 360.0));
      const glm::dvec2 dir(std::cos(angle), std::sin(angle)), normal(-dir.y, dir.x);
      static const double offsets[] = { 0.0, 0.5, 0.999, 1.001, 2.0, -0.5 };
      const glm::dvec2 centre(std::floor(uniform(4, 60)) + 0.5, std::floor(uniform(4, 28)) + 0.5);
      const glm::dvec2 on = centre - normal * (offsets[rng() % 6] * margin);
      const glm::dvec2 a = on - dir * uniform(3, 40), b = on + dir * uniform(3, 40);
      const glm::dvec2 c = on + normal * uniform(2, 20) + dir * uniform(-10, 10); // inner side
      const double z = uniform(-0.5, 0.5);
      // The triangle shrunk by the margin: its vertices moved along the bisectors so that each
      // edge moves inward by (1 - 1e-6) margin.
      const glm::dvec2 v[3] = { a, b, c };
      glm::dvec2 w[3];
      const double area2 = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      for (int k = 0; k < 3; ++k)
      {
        const glm::dvec2 p = v[k], prev = v[(k + 2) % 3], next = v[(k + 1) % 3];
        auto inward = [&](const glm::dvec2& from, const glm::dvec2& to)
        {
          const glm::dvec2 d = glm::normalize(to - from);
          return area2 > 0.0 ? glm::dvec2(-d.y, d.x) : glm::dvec2(d.y, -d.x);
        };
        const glm::dvec2 n1 = inward(prev, p), n2 = inward(p, next);
        // p + s: s . n1 = s . n2 = d.
        const double d = margin * (1.0 - 1e-6);
        const double det = n1.x * n2.y - n1.y * n2.x;
        w[k] = p + glm::dvec2(d * (n2.y - n1.y), d * (n1.x - n2.x)) / det;
      }
      const bool flip = rng() % 2 == 0; // both windings
      const glm::dvec3 pa = windowPoint(cam, a.x, a.y, z), pb = windowPoint(cam, b.x, b.y, z),
                       pc = windowPoint(cam, c.x, c.y, z);
      soup.push_back(flip ? Triangle{ pa, pc, pb } : Triangle{ pa, pb, pc });
      shrunk.push_back({ windowPoint(cam, w[0].x, w[0].y, z), windowPoint(cam, w[1].x, w[1].y, z),
        windowPoint(cam, w[2].x, w[2].y, z) });
    }
    MaskedDepthBuffer buffer = bufferFor(cam);
    draw(buffer, cam, soup, FaceCulling::None, false);
    for (const ClaimedPixel& p : claimedPixels(buffer, cam.width, cam.height))
    {
      ++claimed;
      const auto box = justBehind(cam, p);
      ASSERT_EQ(visiblePixels(cam, shrunk, box.first, box.second), 0)
        << "scene " << scene << ": pixel " << p.i << ", " << p.j << " claimed"
        << (p.whole ? " (whole tile)" : " (working layer)") << " within the margin";
    }
  }
  EXPECT_GT(claimed, 5000u); // not kept by claiming nothing
}

// The exact rasterizer's per-scanline intervals (src/OcclusionScanline.h: four scanlines at a
// time, SSE2 where available, each edge's side applied by masks) are exactly the centres that
// pass all three canonical edge tests, over any narrowed range of columns of a row of tiles:
// random triangles of every kind the set-up meets (centre-aligned and integer vertices,
// horizontal and vertical edges, slivers, outline and interior edges, both windings).
TEST(OcclusionNeighbours, TrianglesWithTwoPointsInOnePlaceLeaveTheSurfaceClosed)
{
  // A unit cube, 12 outward triangles, its corners duplicated per face (as glTF meshes split
  // them at creases): welded by position, every edge joins two triangles.
  std::vector<double> xyz;
  std::vector<std::uint32_t> indices;
  const int faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  for (const auto& f : faces)
  {
    const auto base = static_cast<std::uint32_t>(xyz.size() / 3);
    for (const int corner : f)
    {
      xyz.insert(xyz.end(), { double(corner & 1), double((corner >> 1) & 1), double(corner >> 2) });
    }
    indices.insert(indices.end(), { base, base + 1, base + 2, base, base + 2, base + 3 });
  }
  const std::size_t cube = indices.size() / 3;
  auto closed = [&](const std::vector<std::uint32_t>& tris)
  {
    const std::vector<std::uint32_t> n =
      buildTriangleNeighbors(xyz.data(), xyz.size() / 3, tris.data(), tris.size() / 3);
    return std::make_pair(
      closedSurface(xyz.data(), xyz.size() / 3, tris.data(), tris.size() / 3, n), n);
  };
  auto [isClosed, neighbors] = closed(indices);
  EXPECT_TRUE(isClosed);
  EXPECT_EQ(std::count(neighbors.begin(), neighbors.end(), kNoNeighbor), 0);

  // Two degenerate triangles on the edge from corner 0 to corner 1 (a repeated point; and a
  // triangle of that edge with one end twice): the edge still joins its two faces.
  std::vector<std::uint32_t> withDegenerates = indices;
  withDegenerates.insert(withDegenerates.end(), { 0, 3, 3, 3, 0, 0 });
  std::tie(isClosed, neighbors) = closed(withDegenerates);
  EXPECT_TRUE(isClosed) << "degenerate triangles opened the surface";
  EXPECT_EQ(std::count(neighbors.begin(), neighbors.begin() + 3 * cube, kNoNeighbor), 0)
    << "a degenerate triangle on an edge hid the edge's two triangles from each other";
  EXPECT_EQ(neighbors[3 * cube], kNoNeighbor) << "a degenerate triangle has no neighbours";

  // A hole (the last triangle removed) and a flipped triangle are not closed.
  const std::vector<std::uint32_t> holed(indices.begin(), indices.end() - 3);
  EXPECT_FALSE(closed(holed).first);
  std::vector<std::uint32_t> flipped = indices;
  std::swap(flipped[1], flipped[2]);
  EXPECT_FALSE(closed(flipped).first);
  // Collinear points, three of them distinct, are a triangle of the surface: a needle on an edge
  // with no partner is an open edge.
  std::vector<std::uint32_t> needle = indices;
  xyz.insert(xyz.end(), { 0.5, 0.0, 0.0 });
  const auto middle = static_cast<std::uint32_t>(xyz.size() / 3 - 1);
  needle.insert(needle.end(), { 0, middle, 3 });
  EXPECT_FALSE(closed(needle).first);
  EXPECT_FALSE(closedSurface(xyz.data(), xyz.size() / 3, indices.data(), 0, {}));
}

TEST(OcclusionScanline, RowIntervalsAreTheCentresInsideAllThreeEdges)
{
  constexpr int width = 96, height = 48;
  std::mt19937_64 rng(12);
  auto uniform = [&](double a, double b)
  { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto coordinate = [&](double lo, double hi)
  {
    switch (rng() % 4)
    {
      case 0:
        return std::floor(uniform(lo, hi)) + 0.5; // on a pixel centre
      case 1:
        return std::floor(uniform(lo, hi)); // between centres
      default:
        return uniform(lo, hi);
    }
  };
  const double margin = MaskedDepthBuffer().coverageMargin;
  std::size_t intervals = 0, nonEmpty = 0;
  for (int t = 0; t < 200000; ++t)
  {
    // Small triangles (most of the engine row's) and large ones, around and beyond the viewport.
    const double size = t % 3 == 0 ? uniform(1.0, 120.0) : uniform(0.5, 12.0);
    const double cx = uniform(-10.0, width + 10.0), cy = uniform(-10.0, height + 10.0);
    glm::dvec3 v[3];
    for (glm::dvec3& p : v)
    {
      p = glm::dvec3(coordinate(cx - size, cx + size), coordinate(cy - size, cy + size), 0.5);
    }
    unsigned outline = static_cast<unsigned>(rng() % 8);
    switch (rng() % 7)
    {
      case 6:
      {
        // Edge 0 through a pixel centre (interior) or at the coverage margin from it (outline),
        // at a random slope: its crossings lie within rounding of a column.
        const double angle = uniform(0.0, 6.283185307179586);
        const glm::dvec3 d(std::cos(angle), std::sin(angle), 0.0), n(-d.y, d.x, 0.0);
        const glm::dvec3 c(std::floor(cx) + 0.5, std::floor(cy) + 0.5, 0.5);
        const glm::dvec3 on = c + n * ((outline & 1u) ? margin : 0.0) * (rng() % 2 ? 1.0 : -1.0);
        v[0] = on - d * uniform(0.5, size);
        v[1] = on + d * uniform(0.5, size);
        v[2] = on + n * uniform(-size, size) + d * uniform(-size, size);
        break;
      }
      case 0:
        v[1].y = v[0].y; // a horizontal edge
        break;
      case 1:
        v[2].x = v[1].x; // a vertical edge
        break;
      case 2:
        v[2] = v[0] + (v[1] - v[0]) * uniform(-0.5, 1.5) + glm::dvec3(uniform(-0.1, 0.1), 0, 0);
        break; // a sliver
      default:
        break;
    }
    const auto triangle = ScanlineTriangle::setUp(v, outline, margin, width, height);
    if (!triangle)
    {
      continue;
    }
    const int x0 = triangle->x0, x1 = triangle->x1, y0 = triangle->y0, y1 = triangle->y1;
    const ScanlineCoverage& coverage = triangle->coverage;
    for (int ty = y0 / 4; ty <= y1 / 4; ++ty)
    {
      // The columns of a run of the span's tiles (drawFrontTriangle narrows to the live ones).
      const int tx0 = x0 / 8, tx1 = x1 / 8;
      const int txFirst = tx0 + static_cast<int>(rng() % (tx1 - tx0 + 1));
      const int txLast = txFirst + static_cast<int>(rng() % (tx1 - txFirst + 1));
      const int rx0 = std::max(x0, txFirst * 8), rx1 = std::min(x1, txLast * 8 + 7);
      int first[4], last[4];
      coverage.rowIntervals(ty * 4, y0, y1, rx0, rx1, first, last);
      for (int j = 0; j < 4; ++j)
      {
        const int y = ty * 4 + j;
        int expectFirst = ScanlineCoverage::kEmpty, expectLast = -ScanlineCoverage::kEmpty;
        if (y >= y0 && y <= y1)
        {
          for (int i = rx0; i <= rx1; ++i)
          {
            if (triangle->inside(i, y))
            {
              ASSERT_TRUE(expectLast == -ScanlineCoverage::kEmpty || expectLast == i - 1)
                << "the centres inside are not one interval: triangle " << t;
              expectFirst = std::min(expectFirst, i);
              expectLast = i;
            }
          }
        }
        ++intervals;
        nonEmpty += expectLast >= expectFirst ? 1 : 0;
        ASSERT_EQ(first[j], expectFirst) << "triangle " << t << " scanline " << y;
        ASSERT_EQ(last[j], expectLast) << "triangle " << t << " scanline " << y;
      }
    }
  }
  EXPECT_GT(nonEmpty, intervals / 4); // not kept by testing empty scanlines only
}

// rowIntervals() takes most edges' crossings in 32.32 fixed point (src/OcclusionScanline.h),
// decided where the fraction is farther from a column than the rounding of the double crossing
// plus the fixed point's truncation; elsewhere, and where the crossing could overflow, the
// double crossings or the test itself. On a full-HD viewport: edges through a pixel centre (or
// at the margin from it) at every slope, integer and centre-aligned vertices, nearly horizontal
// edges around the fixed point's slope limit, vertices far off screen (around its |a| < 2^28
// limit) and tiny triangles; the intervals of random runs of tiles against the edge tests.
TEST(OcclusionScanline, FixedPointCrossingsGiveTheEdgeTestsIntervals)
{
  constexpr int width = 1920, height = 1200;
  std::mt19937_64 rng(21);
  auto uniform = [&](double a, double b)
  { return std::uniform_real_distribution<double>(a, b)(rng); };
  const double margin = MaskedDepthBuffer().coverageMargin;
  std::size_t edgesFixed = 0, edgesOther = 0, checked = 0, nonEmpty = 0;
  for (int t = 0; t < 60000; ++t)
  {
    const double cx = std::floor(uniform(0.0, width)) + 0.5;
    const double cy = std::floor(uniform(0.0, height)) + 0.5;
    const double size = t % 5 == 0 ? uniform(20.0, 400.0) : uniform(0.3, 12.0);
    unsigned outline = static_cast<unsigned>(rng() % 8);
    glm::dvec3 v[3];
    const int kind = static_cast<int>(rng() % 6);
    if (kind <= 1)
    {
      // Edge 0 through the centre (cx, cy), or at the coverage margin from it.
      const double angle = uniform(0.0, 6.283185307179586);
      const glm::dvec3 d(std::cos(angle), std::sin(angle), 0.0), n(-d.y, d.x, 0.0);
      const glm::dvec3 on =
        glm::dvec3(cx, cy, 0.5) + n * ((outline & 1u) ? margin : 0.0) * (rng() % 2 ? 1.0 : -1.0);
      v[0] = on - d * uniform(0.5, size);
      v[1] = on + d * uniform(0.5, size);
      v[2] = on + n * uniform(-size, size) + d * uniform(-size, size);
    }
    else if (kind == 2)
    {
      // Integer or centre-aligned vertices: crossings exactly on columns.
      const double half = rng() % 2 ? 0.5 : 0.0;
      for (glm::dvec3& p : v)
      {
        p = glm::dvec3(std::floor(cx + uniform(-size, size)) + half,
          std::floor(cy + uniform(-size, size)) + half, 0.5);
      }
    }
    else if (kind == 3)
    {
      // A nearly horizontal edge: slope |dx / dy| below and above the fixed point's limit,
      // 2^29 over about twice the extent (some 2^16.4 here).
      const double slope = std::exp2(uniform(10.0, 36.0)) * (rng() % 2 ? 1.0 : -1.0);
      const double dx = uniform(0.5, 2.0 * size);
      v[0] = glm::dvec3(cx - 0.5 * dx, cy - 0.5 * dx / slope, 0.5);
      v[1] = glm::dvec3(cx + 0.5 * dx, cy + 0.5 * dx / slope, 0.5);
      v[2] = glm::dvec3(cx + uniform(-size, size), cy + uniform(-size, size), 0.5);
    }
    else if (kind == 4)
    {
      // A vertex far off screen: the crossings' offset a around 2^28.
      const double far = std::exp2(uniform(20.0, 31.0));
      v[0] = glm::dvec3(cx + uniform(-size, size), cy + uniform(-size, size), 0.5);
      v[1] = glm::dvec3(cx + uniform(-size, size), cy + uniform(-size, size), 0.5);
      v[2] = glm::dvec3(cx + far * uniform(-1.0, 1.0), cy + far * uniform(-1.0, 1.0), 0.5);
    }
    else
    {
      for (glm::dvec3& p : v)
      {
        p = glm::dvec3(cx + uniform(-size, size), cy + uniform(-size, size), 0.5);
      }
    }
    const auto triangle = ScanlineTriangle::setUp(v, outline, margin, width, height);
    if (!triangle)
    {
      continue;
    }
    const int x0 = triangle->x0, x1 = triangle->x1, y0 = triangle->y0, y1 = triangle->y1;
    const ScanlineCoverage& coverage = triangle->coverage;
    const unsigned fixedEdges = coverage.fixedPointEdges();
    for (int k = 0; k < 3; ++k)
    {
      ++((fixedEdges >> k) & 1u ? edgesFixed : edgesOther);
    }
    // A few rows of tiles around the centre (all of them for small triangles), each over a
    // random run of at most 8 of the span's tiles.
    const int tyCentre = std::min(std::max(static_cast<int>(cy) / 4, y0 / 4), y1 / 4);
    const int tyFrom = std::max(y0 / 4, tyCentre - 2), tyTo = std::min(y1 / 4, tyCentre + 2);
    for (int ty = tyFrom; ty <= tyTo; ++ty)
    {
      const int tx0 = x0 / 8, tx1 = x1 / 8;
      const int txFirst = tx0 + static_cast<int>(rng() % (tx1 - tx0 + 1));
      const int txLast = std::min(tx1, txFirst + static_cast<int>(rng() % 8));
      const int rx0 = std::max(x0, txFirst * 8), rx1 = std::min(x1, txLast * 8 + 7);
      int first[4], last[4];
      coverage.rowIntervals(ty * 4, y0, y1, rx0, rx1, first, last);
      for (int j = 0; j < 4; ++j)
      {
        const int y = ty * 4 + j;
        int expectFirst = ScanlineCoverage::kEmpty, expectLast = -ScanlineCoverage::kEmpty;
        if (y >= y0 && y <= y1)
        {
          for (int i = rx0; i <= rx1; ++i)
          {
            if (triangle->inside(i, y))
            {
              expectFirst = std::min(expectFirst, i);
              expectLast = i;
            }
          }
        }
        ++checked;
        nonEmpty += expectLast >= expectFirst ? 1 : 0;
        ASSERT_EQ(first[j], expectFirst) << "triangle " << t << " kind " << kind << " y " << y;
        ASSERT_EQ(last[j], expectLast) << "triangle " << t << " kind " << kind << " y " << y;
      }
    }
  }
  EXPECT_GT(nonEmpty, checked / 4);
#ifdef SCENEVIS_OCCLUSION_SSE2
  // Both paths taken: most edges in fixed point, the steep and far ones not.
  EXPECT_GT(edgesFixed, 3 * edgesOther);
  EXPECT_GT(edgesOther, 5000u);
#endif
}

// roundUp (src/OcclusionEdge.h: every tile depth bound goes through it) is the smallest float not
// below its argument, as std::nextafter gives it, for every kind of double.
TEST(OcclusionScanline, RoundUpIsTheSmallestFloatNotBelow)
{
  auto reference = [](double value)
  {
    float f = static_cast<float>(value);
    if (static_cast<double>(f) < value)
    {
      f = std::nextafter(f, std::numeric_limits<float>::infinity());
    }
    return f;
  };
  auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  const double inf = std::numeric_limits<double>::infinity();
  const double special[] = { 0.0, -0.0, 1e-320, -1e-320, 1e-46, -1e-46, 1.4e-45, -1.4e-45, 0.1,
    -0.1, 0.5, 1.0, -1.0, 1.0 + 1e-12, -1.0 - 1e-12, 3.4028235e38, 3.4028236e38, -3.4028236e38,
    1e300, -1e300, inf, -inf };
  for (double v : special)
  {
    EXPECT_TRUE(same(roundUp(v), reference(v))) << v;
  }
  EXPECT_TRUE(std::isnan(roundUp(std::numeric_limits<double>::quiet_NaN())));
  std::mt19937_64 rng(7);
  for (int i = 0; i < 1000000; ++i)
  {
    // Depth-like values of both signs, and any bits.
    double v = std::ldexp(static_cast<double>(rng() >> 11) / 9007199254740992.0 - 0.5,
      static_cast<int>(rng() % 64) - 40);
    if (i % 4 == 0)
    {
      const std::uint64_t bits = rng();
      std::memcpy(&v, &bits, sizeof v);
      if (std::isnan(v))
      {
        continue;
      }
    }
    ASSERT_TRUE(same(roundUp(v), reference(v))) << v;
  }
}

// drawTriangles' batch front end (src/OcclusionFront.h: keepDrawable, SSE2 where available)
// keeps exactly the triangles that the scalar front end keeps (keepDrawableScalar: triangleSpan,
// doubleArea and culled, one triangle at a time), in the same order, with the same spans and
// the same doubled areas bit for bit: random batches of triangles over vertices of every kind
// (inside and far beyond the viewport, on pixel centres and between them, huge and infinite
// window coordinates, repeated and collinear vertices), every face culling, several viewports.
TEST(OcclusionFront, BatchKeepsWhatTheScalarFrontEndKeeps)
{
  std::mt19937_64 rng(2026);
  auto uniform = [&](double a, double b)
  { return std::uniform_real_distribution<double>(a, b)(rng); };
  const int sizes[][2] = { { 800, 600 }, { 1, 1 }, { 37, 5 }, { 8, 4 }, { 1920, 1200 } };
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::size_t batches = 0, kept = 0, dropped = 0, areaZero = 0, spanEmpty = 0;
  std::size_t facings[4] = {}; // Back, None, Front, Unknown
  for (const auto& size : sizes)
  {
    const int width = size[0], height = size[1];
    auto coordinate = [&](int pixels)
    {
      switch (rng() % 10)
      {
        case 0:
          return std::floor(uniform(-2.0, pixels + 2.0)) + 0.5; // on a pixel centre
        case 1:
          return std::floor(uniform(-2.0, pixels + 2.0)); // between centres
        case 2:
          return uniform(-1e7, 1e7); // far off screen
        case 3:
          return (rng() % 2 ? 1.0 : -1.0) * (rng() % 2 ? 1e300 : inf); // a vertex near w = 0
        case 4:
          return uniform(0.4, 0.6); // around the first centre
        default:
          return uniform(-3.0, pixels + 3.0);
      }
    };
    std::vector<glm::dvec3> window(512);
    std::vector<CentreSpan> centres(window.size());
    for (std::size_t i = 0; i < window.size(); ++i)
    {
      window[i] = glm::dvec3(coordinate(width), coordinate(height), uniform(0.0, 1.0));
      if (i % 7 == 3)
      {
        // On the line through the two previous vertices: zero or nearly zero area.
        window[i] = window[i - 1] + (window[i - 1] - window[i - 2]) * uniform(-2.0, 2.0);
      }
      centres[i] = centreSpan(window[i].x, window[i].y, width, height);
    }
    std::vector<std::uint32_t> indices(3 * 4096);
    for (std::size_t k = 0; k < indices.size(); ++k)
    {
      // Some triangles repeat a vertex (zero area); most use nearby vertices (small ones).
      indices[k] = k % 3 != 0 && rng() % 16 == 0
        ? indices[k - 1]
        : static_cast<std::uint32_t>((k / 3 + rng() % 8) % window.size());
    }
    // The facing both record for every front triangle, kept or not (drawTriangles' neighbour
    // test reads it instead of computing the sign of the same area again).
    std::vector<TriangleFacing> batchFacing(indices.size() / 3, TriangleFacing::Unknown);
    std::vector<TriangleFacing> scalarFacing(batchFacing);
    for (FaceCulling culling :
      { FaceCulling::None, FaceCulling::Back, FaceCulling::Front, FaceCulling::Both })
    {
      const FrontVertices vertices{ indices.data(), window.data(), centres.data(), width, height,
        culling, batchFacing.data() };
      FrontVertices scalarVertices = vertices;
      scalarVertices.facing = scalarFacing.data();
      for (std::size_t first = 0; first < indices.size() / 3; first += kFrontBatch)
      {
        FrontEntry batch[kFrontBatch], reference[kFrontBatch];
        bool front[kFrontBatch];
        const std::size_t count = 1 + rng() % kFrontBatch;
        for (std::size_t i = 0; i < count; ++i)
        {
          batch[i] = FrontEntry{ first + i, rng() % 10 != 0, CentreSpan{ 0, 0, 0, 0 }, 0.0 };
          reference[i] = batch[i];
          front[i] = batch[i].front;
          batchFacing[first + i] = scalarFacing[first + i] = TriangleFacing::Unknown;
          const std::uint32_t* tri = indices.data() + 3 * (first + i);
          areaZero += doubleArea(window[tri[0]], window[tri[1]], window[tri[2]]) == 0.0;
          const CentreSpan s =
            triangleSpan(centres[tri[0]], centres[tri[1]], centres[tri[2]], width, height);
          spanEmpty += s.x0 > s.x1 || s.y0 > s.y1;
        }
        const std::size_t n = keepDrawable(batch, count, vertices);
        const std::size_t expected = keepDrawableScalar(reference, count, scalarVertices);
        ASSERT_EQ(n, expected) << width << "x" << height << " batch at " << first;
        for (std::size_t i = 0; i < count; ++i)
        {
          const std::uint32_t* tri = indices.data() + 3 * (first + i);
          const double area2 = doubleArea(window[tri[0]], window[tri[1]], window[tri[2]]);
          const TriangleFacing facing = front[i]
            ? (area2 > 0.0 ? TriangleFacing::Front
                           : (area2 < 0.0 ? TriangleFacing::Back : TriangleFacing::None))
            : TriangleFacing::Unknown;
          ASSERT_EQ(batchFacing[first + i], facing) << "triangle " << first + i;
          ASSERT_EQ(scalarFacing[first + i], facing) << "triangle " << first + i;
          facings[static_cast<int>(facing) + 1] += 1;
        }
        for (std::size_t i = 0; i < n; ++i)
        {
          ASSERT_EQ(batch[i].triangle, reference[i].triangle);
          ASSERT_EQ(batch[i].front, reference[i].front);
          if (!batch[i].front)
          {
            continue; // clipped: decided later, from its clip coordinates
          }
          const CentreSpan& a = batch[i].span;
          const CentreSpan& b = reference[i].span;
          ASSERT_TRUE(a.x0 == b.x0 && a.x1 == b.x1 && a.y0 == b.y0 && a.y1 == b.y1)
            << "triangle " << batch[i].triangle << ": span " << a.x0 << " " << a.x1 << " " << a.y0
            << " " << a.y1 << ", scalar " << b.x0 << " " << b.x1 << " " << b.y0 << " " << b.y1;
          ASSERT_EQ(std::memcmp(&batch[i].area2, &reference[i].area2, sizeof(double)), 0)
            << "triangle " << batch[i].triangle << ": area " << batch[i].area2 << ", scalar "
            << reference[i].area2;
        }
        ++batches;
        kept += n;
        dropped += count - n;
      }
    }
  }
  // Not passed by keeping (or dropping) everything: every reason to drop occurs.
  EXPECT_GT(kept, 5000u);
  EXPECT_GT(dropped, 5000u);
  EXPECT_GT(areaZero, 500u);
  EXPECT_GT(spanEmpty, 5000u);
  EXPECT_GT(batches, 1000u);
  for (std::size_t n : facings)
  {
    EXPECT_GT(n, 500u); // every facing recorded (Unknown: the clipped ones)
  }
}

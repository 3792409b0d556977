#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionRecording.h"

#include "OcclusionEdge.h"
#include "OcclusionFront.h"
#include "OcclusionScanline.h"
#include "OcclusionTileUpdate.h"

#include <glm/common.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace scenevis
{
namespace occlusion
{

namespace
{
constexpr float kNoOccluder = std::numeric_limits<float>::infinity();
/// The smallest clip w a vertex in front of the near plane is projected with: below it 1 / w
/// overflows (a point in the eye's plane, seen through no real camera), and the vertex counts as
/// not finite (its triangles are rejected: always conservative).
constexpr double kSmallestW = 1.0 / std::numeric_limits<double>::max();

bool finite(const glm::dvec4& v)
{
#ifdef SCENEVIS_OCCLUSION_SSE2
  // x - x is 0 for every finite x and NaN for infinities and NaN: four tests in two compares.
  const __m128d xy = _mm_loadu_pd(&v.x), zw = _mm_loadu_pd(&v.z);
  const __m128d zero = _mm_setzero_pd();
  return _mm_movemask_pd(_mm_and_pd(
           _mm_cmpeq_pd(_mm_sub_pd(xy, xy), zero), _mm_cmpeq_pd(_mm_sub_pd(zw, zw), zero))) == 3;
#else
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
#endif
}

/// Whether a triangle's three vertex indices are below @p vertexCount (one compare, no branch
/// per index).
bool indicesInRange(const std::uint32_t* tri, std::size_t vertexCount)
{
  return std::max(std::max(tri[0], tri[1]), tri[2]) < vertexCount;
}

/// The tile column of pixel column @p x and the tile row of pixel row @p y, for x, y >= 0 (or
/// multiples of the tile size, as an empty row's -ScanlineCoverage::kEmpty): there a shift is
/// the division, which for an int the compiler must also round towards 0 for negatives.
static_assert(MaskedDepthBuffer::kTileWidth == 8 && MaskedDepthBuffer::kTileHeight == 4,
  "tiles of 8 x 4 pixels");
constexpr int tileColumn(int x)
{
  return x >> 3;
}
constexpr int tileRow(int y)
{
  return y >> 2;
}

} // namespace

// Not inline: inlined, GCC 12 turns these min / max into branches (measured: 280,000 more
// mispredicted branches on the four engine-row culls); out of line they are conditional moves.
// Only clipped triangles use it: the others go through keepDrawable().
CentreSpan MaskedDepthBuffer::triangleSpan(
  const CentreSpan& a, const CentreSpan& b, const CentreSpan& c) const
{
  return occlusion::triangleSpan(a, b, c, width_, height_);
}

void MaskedDepthBuffer::resize(int width, int height)
{
  width_ = std::max(0, width);
  height_ = std::max(0, height);
  tilesX_ = (width_ + kTileWidth - 1) / kTileWidth;
  tilesY_ = (height_ + kTileHeight - 1) / kTileHeight;
  tiles_.assign(static_cast<std::size_t>(tilesX_) * static_cast<std::size_t>(tilesY_),
    Tile{ kNoOccluder, 0.0f, 0u });
  blocksX_ = (tilesX_ + kBlockTiles - 1) / kBlockTiles;
  blockZ0_.assign(
    static_cast<std::size_t>(blocksX_) * ((tilesY_ + kBlockTiles - 1) / kBlockTiles), kNoOccluder);
  outsideX_.assign(static_cast<std::size_t>(tilesX_), 0u);
  outsideY_.assign(static_cast<std::size_t>(tilesY_), 0u);
  for (int tx = 0; tx < tilesX_; ++tx)
  {
    for (int i = 0; i < kTileWidth; ++i)
    {
      if (tx * kTileWidth + i >= width_)
      {
        for (int j = 0; j < kTileHeight; ++j)
        {
          outsideX_[tx] |= 1u << (j * kTileWidth + i);
        }
      }
    }
  }
  for (int ty = 0; ty < tilesY_; ++ty)
  {
    for (int j = 0; j < kTileHeight; ++j)
    {
      if (ty * kTileHeight + j >= height_)
      {
        outsideY_[ty] |= 0xFFu << (j * kTileWidth);
      }
    }
  }
  stats_ = BufferStats();
  ++revision_;
}

void MaskedDepthBuffer::setClipFromWorld(const glm::dmat4& clipFromWorld)
{
  if (recorder)
  {
    recorder->beginCull(width_, height_, clipFromWorld);
  }
  ++revision_;
  clipFromWorld_ = clipFromWorld;
  const glm::dmat4 worldFromClip = glm::inverse(clipFromWorld);
  nearCornersValid_ = true;
  for (int k = 0; k < 4; ++k)
  {
    const glm::dvec4 p = worldFromClip * glm::dvec4((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, -1.0, 1.0);
    nearCorners_[k] = glm::dvec3(p) / p.w;
    nearCornersValid_ = nearCornersValid_ && p.w != 0.0 && std::isfinite(nearCorners_[k].x) &&
      std::isfinite(nearCorners_[k].y) && std::isfinite(nearCorners_[k].z);
  }
}

void MaskedDepthBuffer::clear()
{
  std::fill(tiles_.begin(), tiles_.end(), Tile{ kNoOccluder, 0.0f, 0u });
  std::fill(blockZ0_.begin(), blockZ0_.end(), kNoOccluder);
  stats_ = BufferStats();
  ++revision_;
}

float MaskedDepthBuffer::tileDepth(int x, int y) const
{
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
  {
    return kNoOccluder;
  }
  return tiles_[static_cast<std::size_t>(y / kTileHeight) * tilesX_ + x / kTileWidth].z0;
}

void MaskedDepthBuffer::drawTriangles(const glm::dvec4* clip,
  std::size_t vertexCount,
  const std::uint32_t* indices,
  std::size_t triangleCount,
  FaceCulling culling,
  const std::uint32_t* neighbors,
  const TriangleClusters* clusters)
{
  if (recorder)
  {
    recorder->draw(
      *this, clip, nullptr, vertexCount, indices, triangleCount, culling, neighbors, clusters);
  }
  drawTrianglesFrom(
    clip, nullptr, vertexCount, indices, triangleCount, culling, neighbors, clusters);
}

void MaskedDepthBuffer::drawTriangles(const ModelVertices& model, std::size_t vertexCount,
  const std::uint32_t* indices, std::size_t triangleCount, FaceCulling culling,
  const std::uint32_t* neighbors, const TriangleClusters* clusters)
{
  if (recorder)
  {
    recorder->draw(
      *this, nullptr, &model, vertexCount, indices, triangleCount, culling, neighbors, clusters);
  }
  if (!model.xyzFloat && !model.xyzDouble)
  {
    stats_.trianglesIn += triangleCount;
    stats_.trianglesRejected += triangleCount;
    return;
  }
  drawTrianglesFrom(
    nullptr, &model, vertexCount, indices, triangleCount, culling, neighbors, clusters);
}

void MaskedDepthBuffer::drawTrianglesFrom(const glm::dvec4* clip, const ModelVertices* model,
  std::size_t vertexCount, const std::uint32_t* indices, std::size_t triangleCount,
  FaceCulling culling, const std::uint32_t* neighbors, const TriangleClusters* clusters)
{
  stats_.trianglesIn += triangleCount;
  if (tiles_.empty() || culling == FaceCulling::Both)
  {
    stats_.trianglesRejected += triangleCount;
    return;
  }
  // Each vertex is projected once, when a triangle first asks for it (shared vertices get
  // bit-identical window coordinates in every triangle, which the watertight edge rule relies
  // on; the vertices of skipped clusters are never projected). State: 0 not finite, 1 in front
  // of the near plane (window coordinates valid), 2 finite but behind it (its triangles are
  // clipped), 3 not projected yet.
  // The scratch only grows: a draw after a bigger one neither reallocates nor fills it again
  // (resize() to a larger size value-initializes the new elements: a cull's draws alternate
  // between sizes, and that filling was about 1 % of the engine row's cull). Only the entries
  // below vertexCount are read, each after it is written.
  const auto grow = [vertexCount](auto& scratch)
  {
    if (scratch.size() < vertexCount)
    {
      scratch.resize(vertexCount);
    }
  };
  grow(window_);
  grow(centres_);
  vertexState_.assign(vertexCount, kVertexUnseen);
  if (neighbors)
  {
    facing_.assign(triangleCount, TriangleFacing::Unknown);
  }
  if (model)
  {
    grow(clip_);
    clip = clip_.data();
  }
  auto state = [&](std::uint32_t i) -> unsigned
  {
    VertexState& s = vertexState_[i];
    if (s == kVertexUnseen)
    {
      if (model)
      {
        clip_[i] = model->clip(i);
      }
      const glm::dvec4& v = clip[i];
      if (!finite(v))
      {
        s = kVertexNotFinite;
      }
      else if (v.z + v.w >= 0.0 && v.w >= kSmallestW)
      {
        s = kVertexFront;
        const double inverseW = 1.0 / v.w;
#ifdef SCENEVIS_OCCLUSION_SSE2
        // x and y in one register: the same operations in the same order as below.
        const __m128d xy = _mm_mul_pd(
          _mm_add_pd(
            _mm_mul_pd(_mm_mul_pd(_mm_loadu_pd(&v.x), _mm_set1_pd(inverseW)), _mm_set1_pd(0.5)),
            _mm_set1_pd(0.5)),
          _mm_set_pd(height_, width_));
        glm::dvec3& w = window_[i];
        _mm_storeu_pd(&w.x, xy);
        w.z = v.z * inverseW * 0.5 + 0.5;
#else
        window_[i] = glm::dvec3((v.x * inverseW * 0.5 + 0.5) * width_,
          (v.y * inverseW * 0.5 + 0.5) * height_, v.z * inverseW * 0.5 + 0.5);
#endif
        centres_[i] = centreSpan(window_[i].x, window_[i].y, width_, height_);
      }
      else if (v.w > 0.0 && v.z + v.w >= 0.0)
      {
        s = kVertexNotFinite; // 0 < w < kSmallestW: 1 / w overflows, no window point
      }
      else
      {
        s = kVertexBehind;
      }
    }
    return s;
  };
  // Facing: an edge is inside the occluder only if the neighbour across it faces the same way.
  // In front of the near plane it is the sign of the window-space area; otherwise the sign of
  // det[x y w] (the same orientation, homogeneous). Where the two disagree (near-degenerate
  // triangles) an edge merely becomes an outline edge. Asked only of the neighbours of
  // triangles that are drawn (most are rejected first).
  auto facing = [&](std::size_t t) -> int
  {
    // Most neighbours went through keepDrawable() already (in this batch or an earlier one),
    // which recorded the sign of the same doubled area, bit for bit doubleArea() below: one
    // byte read instead of the neighbour's indices, states and window coordinates, which lie
    // at random places in memory.
    const TriangleFacing known = facing_[t];
    if (known != TriangleFacing::Unknown)
    {
      return static_cast<int>(known);
    }
    const std::uint32_t* tri = indices + 3 * t;
    if (!indicesInRange(tri, vertexCount))
    {
      return 0;
    }
    // Each state once (projecting a vertex not seen yet; the same states in any order).
    const unsigned s0 = state(tri[0]), s1 = state(tri[1]), s2 = state(tri[2]);
    if (s0 == kVertexNotFinite || s1 == kVertexNotFinite || s2 == kVertexNotFinite)
    {
      return 0;
    }
    double det;
    // The states are 1 (front) or 2 (behind) here: their bitwise and is 1 only if all are 1.
    if ((s0 & s1 & s2) == kVertexFront)
    {
      det = doubleArea(window_[tri[0]], window_[tri[1]], window_[tri[2]]);
    }
    else
    {
      const glm::dvec4& a = clip[tri[0]];
      const glm::dvec4& b = clip[tri[1]];
      const glm::dvec4& c = clip[tri[2]];
      det = a.x * (b.y * c.w - b.w * c.y) - a.y * (b.x * c.w - b.w * c.x) +
        a.w * (b.x * c.y - b.y * c.x);
    }
    return static_cast<int>(facingOf(det));
  };
  // A triangle kept by keepDrawable(): in front of the near plane, it is dropped if behind
  // every tile of its span, else set up; a clipped one is clipped. Either way its outline edges
  // are those whose neighbour does not face its way.
  auto drawKept = [&](const FrontEntry& e)
  {
    const std::uint32_t* tri = indices + 3 * e.triangle;
    if (e.front && hidden(window_[tri[0]], window_[tri[1]], window_[tri[2]], e.span))
    {
      ++stats_.trianglesRejected;
      return;
    }
    unsigned outline = 7u;
    const int faces =
      neighbors ? (e.front ? (e.area2 > 0.0) - (e.area2 < 0.0) : facing(e.triangle)) : 0;
    if (faces != 0)
    {
      outline = 0u;
      for (int k = 0; k < 3; ++k)
      {
        const std::uint32_t n = neighbors[3 * e.triangle + k];
        if (n >= triangleCount || facing(n) != faces)
        {
          outline |= 1u << k;
        }
      }
    }
    if (e.front)
    {
      drawFrontTriangle(
        window_[tri[0]], window_[tri[1]], window_[tri[2]], e.area2, e.span, outline);
    }
    else
    {
      const glm::dvec4 v[3] = { clip[tri[0]], clip[tri[1]], clip[tri[2]] };
      drawClippedTriangle(v, culling, outline);
    }
  };
  const bool clustered = clusters && clusters->boxes && clusters->trianglesPerCluster > 0;
  const std::size_t run = clustered ? clusters->trianglesPerCluster : triangleCount;
  for (std::size_t begin = 0; begin < triangleCount; begin += run)
  {
    const std::size_t end = std::min(triangleCount, begin + run);
    if (clustered)
    {
      ++stats_.clustersTested;
      if (boxBehindTiles(clusters->clipFromModel, clusters->boxes + 6 * (begin / run)))
      {
        ++stats_.clustersHidden;
        stats_.trianglesRejected += end - begin;
        continue;
      }
    }
    for (std::size_t first = begin; first < end; first += kFrontBatch)
    {
      // A batch of triangles: their vertices' states (each vertex projected at its first use),
      // then the span and face tests of all of them at once (keepDrawable), then, in order,
      // the depth test, the neighbours' facing and the set-up of the few that are left.
      FrontEntry batch[kFrontBatch];
      const std::size_t count = std::min(end - first, kFrontBatch);
      std::size_t usable = 0;
      for (std::size_t t = first; t < first + count; ++t)
      {
        const std::uint32_t* tri = indices + 3 * t;
        unsigned s0 = 0, s1 = 0, s2 = 0;
        if (indicesInRange(tri, vertexCount))
        {
          s0 = state(tri[0]), s1 = state(tri[1]), s2 = state(tri[2]);
        }
        batch[usable].triangle = t;
        batch[usable].front = (s0 & s1 & s2) == 1;
        usable += (s0 != 0 && s1 != 0 && s2 != 0) ? 1 : 0;
      }
      const FrontVertices vertices{ indices, window_.data(), centres_.data(), width_, height_,
        culling, neighbors ? facing_.data() : nullptr };
      const std::size_t kept = keepDrawable(batch, usable, vertices);
      stats_.trianglesRejected += count - kept;
      for (std::size_t i = 0; i < kept; ++i)
      {
        drawKept(batch[i]);
      }
    }
  }
}

bool MaskedDepthBuffer::boxBehindTiles(const glm::dmat4& clipFromModel, const double* box)
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  double x0 = inf, y0 = inf, zNear = inf, x1 = -inf, y1 = -inf;
  // The corners as the lowest one plus the matrix's columns scaled by the box's extents (three
  // additions per corner instead of a matrix product; the rounding differs from the product's
  // by a few ulps of the clip coordinates, far inside the pixel and depth margins below). Formed
  // before the loop: no branch per corner.
  glm::dvec4 corners[8];
  corners[0] = clipFromModel * glm::dvec4(box[0], box[2], box[4], 1.0);
  const glm::dvec4 ex = clipFromModel[0] * (box[1] - box[0]);
  const glm::dvec4 ey = clipFromModel[1] * (box[3] - box[2]);
  const glm::dvec4 ez = clipFromModel[2] * (box[5] - box[4]);
  corners[1] = corners[0] + ex;
  corners[2] = corners[0] + ey;
  corners[3] = corners[1] + ey;
  corners[4] = corners[0] + ez;
  corners[5] = corners[1] + ez;
  corners[6] = corners[2] + ez;
  corners[7] = corners[3] + ez;
  for (const glm::dvec4& c : corners)
  {
    // Every corner in front of the near plane: then the box's projection is inside its corners'
    // (a point of the box projects into their convex hull) and its nearest window depth is at a
    // corner (depth is a ratio of affine functions with a positive denominator).
    if (!finite(c) || !(c.w > 0.0) || !(c.z + c.w >= 0.0))
    {
      return false;
    }
    const double inverseW = 1.0 / c.w;
    const double x = (c.x * inverseW * 0.5 + 0.5) * width_;
    const double y = (c.y * inverseW * 0.5 + 0.5) * height_;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
    zNear = std::min(zNear, c.z * inverseW * 0.5 + 0.5);
  }
  // The centres a triangle of the box may cover (triangleSpan of its vertices), one pixel more
  // on each side against the rounding of the two projections; its nearest depth without the
  // depth margin hidden() adds (the margin covers their rounding).
  const CentreSpan lo = centreSpan(x0, y0, width_, height_);
  const CentreSpan hi = centreSpan(x1, y1, width_, height_);
  const int sx0 = std::max(0, lo.x0 - 1), sx1 = std::min(width_ - 1, hi.x1 + 1);
  const int sy0 = std::max(0, lo.y0 - 1), sy1 = std::min(height_ - 1, hi.y1 + 1);
  if (sx0 > sx1 || sy0 > sy1)
  {
    return true; // no centre on screen: every triangle of the box has an empty span
  }
  return behindTiles(tileColumn(sx0), tileRow(sy0), tileColumn(sx1), tileRow(sy1), zNear);
}

std::vector<double> buildTriangleClusters(const double* xyz, std::size_t pointCount,
  const std::uint32_t* indices, std::size_t triangleCount, std::size_t trianglesPerCluster)
{
  std::vector<double> boxes;
  if (trianglesPerCluster == 0)
  {
    return boxes;
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::size_t count = (triangleCount + trianglesPerCluster - 1) / trianglesPerCluster;
  boxes.reserve(6 * count);
  for (std::size_t r = 0; r < count; ++r)
  {
    double b[6] = { inf, -inf, inf, -inf, inf, -inf };
    const std::size_t end = std::min(triangleCount, (r + 1) * trianglesPerCluster);
    for (std::size_t i = 3 * r * trianglesPerCluster; i < 3 * end; ++i)
    {
      if (indices[i] >= pointCount)
      {
        continue;
      }
      const double* p = xyz + 3 * std::size_t(indices[i]);
      for (int a = 0; a < 3; ++a)
      {
        // A NaN coordinate makes the box NaN: its run is never skipped (the test needs finite
        // corners).
        b[2 * a] = std::isnan(p[a]) ? p[a] : std::min(b[2 * a], p[a]);
        b[2 * a + 1] = std::isnan(p[a]) ? p[a] : std::max(b[2 * a + 1], p[a]);
      }
    }
    boxes.insert(boxes.end(), b, b + 6);
  }
  return boxes;
}

namespace
{
/// Lexicographic order of clip-space points: a shared edge is cut by the near plane at the
/// same point in both of its triangles.
bool lessClip(const glm::dvec4& a, const glm::dvec4& b)
{
  if (a.x != b.x)
    return a.x < b.x;
  if (a.y != b.y)
    return a.y < b.y;
  if (a.z != b.z)
    return a.z < b.z;
  return a.w < b.w;
}

glm::dvec4 nearPlaneCut(const glm::dvec4& p, const glm::dvec4& q)
{
  const glm::dvec4& a = lessClip(p, q) ? p : q;
  const glm::dvec4& b = lessClip(p, q) ? q : p;
  const double da = a.z + a.w, db = b.z + b.w;
  return a + (b - a) * (da / (da - db));
}
} // namespace

void MaskedDepthBuffer::drawClippedTriangle(const glm::dvec4* in, FaceCulling culling, unsigned outline)
{
  // Near plane in clip space: z + w >= 0 (OpenGL). What lies in front of it is not drawn.
  double d[3];
  int inside = 0;
  for (int i = 0; i < 3; ++i)
  {
    d[i] = in[i].z + in[i].w;
    inside += d[i] >= 0.0 ? 1 : 0;
  }
  if (inside == 0)
  {
    ++stats_.trianglesRejected;
    return;
  }
  glm::dvec4 poly[4]{};
  unsigned edgeOutline[4]{}; // of the edge from poly[i] to poly[i + 1]
  int n = 0;
  // Sutherland-Hodgman against the near plane: at most 4 vertices, order (and so facing) kept;
  // the new edge along the near plane is an outline edge.
  for (int i = 0; i < 3; ++i)
  {
    const int j = (i + 1) % 3;
    const unsigned own = (outline >> i) & 1u;
    if (d[i] >= 0.0)
    {
      edgeOutline[n] = own;
      poly[n++] = in[i];
    }
    if ((d[i] >= 0.0) != (d[j] >= 0.0))
    {
      edgeOutline[n] = d[i] >= 0.0 ? 1u : own;
      poly[n++] = nearPlaneCut(in[i], in[j]);
    }
  }
  glm::dvec3 window[4]{};
  for (int i = 0; i < n; ++i)
  {
    const glm::dvec4& v = poly[i];
    if (!(v.w > 0.0))
    {
      // Not a projection OpenGL draws sensibly (a point at or behind the eye after clipping):
      // dropping an occluder is always conservative.
      ++stats_.trianglesRejected;
      return;
    }
    window[i] = glm::dvec3((v.x / v.w * 0.5 + 0.5) * width_, (v.y / v.w * 0.5 + 0.5) * height_,
      v.z / v.w * 0.5 + 0.5);
  }
  if (n == 3)
  {
    drawWindowTriangle(window[0], window[1], window[2], culling,
      edgeOutline[0] | (edgeOutline[1] << 1) | (edgeOutline[2] << 2));
  }
  else
  {
    // The fan's diagonal is inside the polygon: not an outline edge.
    drawWindowTriangle(window[0], window[1], window[2], culling,
      edgeOutline[0] | (edgeOutline[1] << 1));
    drawWindowTriangle(window[0], window[2], window[3], culling,
      (edgeOutline[2] << 1) | (edgeOutline[3] << 2));
  }
}

void MaskedDepthBuffer::drawWindowTriangle(const glm::dvec3& a, const glm::dvec3& b,
  const glm::dvec3& c, FaceCulling culling, unsigned outline)
{
  const double area2 = doubleArea(a, b, c);
  const CentreSpan span = triangleSpan(centreSpan(a.x, a.y, width_, height_),
    centreSpan(b.x, b.y, width_, height_), centreSpan(c.x, c.y, width_, height_));
  if (culled(area2, culling) || span.x0 > span.x1 || span.y0 > span.y1 || hidden(a, b, c, span))
  {
    ++stats_.trianglesRejected;
    return;
  }
  drawFrontTriangle(a, b, c, area2, span, outline);
}

void MaskedDepthBuffer::drawFrontTriangle(const glm::dvec3& a, const glm::dvec3& b,
  const glm::dvec3& c, double area2, const CentreSpan& span, unsigned outline)
{
  if (rasterizer == Rasterizer::Float && drawFrontTriangleFloat(a, b, c, area2, span, outline))
  {
    return;
  }
  const double orientation = area2 > 0.0 ? 1.0 : -1.0;
  const int tx0 = tileColumn(span.x0), tx1 = tileColumn(span.x1);
  const int ty0 = tileRow(span.y0), ty1 = tileRow(span.y1);
  const double zNearVertex = std::min({ a.z, b.z, c.z }) + depthMargin;
  const double extent = std::max({ std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y),
    std::abs(c.x), std::abs(c.y), static_cast<double>(width_ + height_) });
  const EdgeTest edges[3] = { EdgeTest(a, b, orientation, outline & 1u, coverageMargin),
    EdgeTest(b, c, orientation, outline & 2u, coverageMargin),
    EdgeTest(c, a, orientation, outline & 4u, coverageMargin) };
  const ScanlineCoverage coverage(edges, extent, span.x0, span.x1);
  const DepthPlane plane(a, b, c, area2, polygonOffsetFactor, polygonOffsetDepth, width_, height_);

  bool touched = false;
  for (int ty = ty0; ty <= ty1; ++ty)
  {
    Tile* row = tiles_.data() + static_cast<std::size_t>(ty) * tilesX_;
    // Tiles entirely behind what they already have get nothing (updateTile would return at
    // once): the scanlines are needed only between the first and the last other one.
    int txFirst = tx0, txLast = tx1;
    while (txFirst <= txLast && zNearVertex >= static_cast<double>(row[txFirst].z0))
    {
      ++txFirst;
    }
    while (txLast > txFirst && zNearVertex >= static_cast<double>(row[txLast].z0))
    {
      --txLast;
    }
    if (txFirst > txLast)
    {
      continue;
    }
    const int x0 = std::max(span.x0, txFirst * kTileWidth);
    const int x1 = std::min(span.x1, txLast * kTileWidth + kTileWidth - 1);
    int first[kTileHeight], last[kTileHeight];
    coverage.rowIntervals(ty * kTileHeight, span.y0, span.y1, x0, x1, first, last);
    const int rowFirst = std::min({ first[0], first[1], first[2], first[3] });
    const int rowLast = std::max({ last[0], last[1], last[2], last[3] });
    const double y0 = ty * kTileHeight + 0.5;
    const int txEnd = tileColumn(rowLast);
    for (int tx = tileColumn(rowFirst); tx <= txEnd; ++tx)
    {
      Tile& tile = row[tx];
      if (zNearVertex >= static_cast<double>(tile.z0))
      {
        continue;
      }
      const std::uint32_t mask = ScanlineCoverage::tileMask(first, last, tx * kTileWidth);
      if (mask == 0)
      {
        continue; // between the scanlines' intervals of a slanted sliver
      }
      const double xc = tx * kTileWidth + 0.5;
      const float oldZ0 = tile.z0;
      updateTile(
        tile, mask, roundUp(plane.tileBound(xc, y0) + depthMargin), outsideX_[tx] | outsideY_[ty]);
      ++revision_;
      if (tile.z0 != oldZ0)
      {
        lowerBlock(tx, ty, oldZ0);
      }
      ++stats_.tilesUpdated;
      touched = true;
    }
  }
  if (touched)
  {
    ++stats_.trianglesDrawn;
  }
  else
  {
    ++stats_.trianglesRejected;
  }
}

// hidden() and behindTiles() are used in this file only: inline, so that the test each front
// triangle gets before its set-up (and each cluster before its triangles) is not a call.
inline bool MaskedDepthBuffer::hidden(
  const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const CentreSpan& span)
{
  return behindTiles(tileColumn(span.x0), tileRow(span.y0), tileColumn(span.x1), tileRow(span.y1),
    std::min({ a.z, b.z, c.z }) + depthMargin);
}

inline bool MaskedDepthBuffer::behindTiles(int tx0, int ty0, int tx1, int ty1, double depth)
{
  // Tile indices are never negative: the block bounds once, by shifts.
  static_assert(kBlockTiles == 4, "blocks of 4 x 4 tiles");
  const int bx0 = tx0 >> 2, bx1 = tx1 >> 2, by0 = ty0 >> 2, by1 = ty1 >> 2;
  for (int by = by0; by <= by1; ++by)
  {
    for (int bx = bx0; bx <= bx1; ++bx)
    {
      float& bound = blockZ0_[static_cast<std::size_t>(by) * blocksX_ + bx];
      if (std::isnan(bound))
      {
        bound = largestZ0(bx, by);
      }
      if (depth >= static_cast<double>(bound))
      {
        continue;
      }
      const int yEnd = std::min(ty1, by * kBlockTiles + kBlockTiles - 1);
      const int xEnd = std::min(tx1, bx * kBlockTiles + kBlockTiles - 1);
      for (int ty = std::max(ty0, by * kBlockTiles); ty <= yEnd; ++ty)
      {
        const Tile* row = tiles_.data() + static_cast<std::size_t>(ty) * tilesX_;
        for (int tx = std::max(tx0, bx * kBlockTiles); tx <= xEnd; ++tx)
        {
          if (depth < static_cast<double>(row[tx].z0))
          {
            return false;
          }
        }
      }
    }
  }
  return true;
}

float MaskedDepthBuffer::largestZ0(int bx, int by) const
{
  float largest = -kNoOccluder;
  const int yEnd = std::min(tilesY_, (by + 1) * kBlockTiles);
  const int xEnd = std::min(tilesX_, (bx + 1) * kBlockTiles);
  for (int y = by * kBlockTiles; y < yEnd; ++y)
  {
    for (int x = bx * kBlockTiles; x < xEnd; ++x)
    {
      largest = std::max(largest, tiles_[static_cast<std::size_t>(y) * tilesX_ + x].z0);
    }
  }
  return largest;
}

bool MaskedDepthBuffer::rectOccluded(
  double x0, double y0, double x1, double y1, double nearestDepth) const
{
  if (tiles_.empty() || !(x0 <= x1) || !(y0 <= y1) || !std::isfinite(nearestDepth))
  {
    return false;
  }
  // Pixels whose centres can be in the rectangle, one more on each side against rounding.
  const double px0 = std::max(0.0, std::ceil(x0 - 0.5) - 1.0);
  const double px1 = std::min(static_cast<double>(width_ - 1), std::floor(x1 - 0.5) + 1.0);
  const double py0 = std::max(0.0, std::ceil(y0 - 0.5) - 1.0);
  const double py1 = std::min(static_cast<double>(height_ - 1), std::floor(y1 - 0.5) + 1.0);
  if (!(px0 <= px1 && py0 <= py1))
  {
    return false; // off screen: for the frustum test to decide, not for occlusion
  }
  const double z = nearestDepth - depthMargin;
  const int ix0 = static_cast<int>(px0), ix1 = static_cast<int>(px1);
  const int iy0 = static_cast<int>(py0), iy1 = static_cast<int>(py1);
  const int tx0 = ix0 / kTileWidth, tx1 = ix1 / kTileWidth;
  const int ty0 = iy0 / kTileHeight, ty1 = iy1 / kTileHeight;
  for (int ty = ty0; ty <= ty1; ++ty)
  {
    const Tile* row = tiles_.data() + static_cast<std::size_t>(ty) * tilesX_;
    for (int tx = tx0; tx <= tx1; ++tx)
    {
      const Tile& tile = row[tx];
      if (z > static_cast<double>(tile.z0))
      {
        continue;
      }
      // Not hidden by the whole-tile depth; the working layer may still cover exactly the
      // rectangle's pixels of this tile (a box at the edge of a tile behind a nearer occluder
      // that does not fill the tile): hidden there if all of them are in its mask and behind z1.
      if (tile.mask == 0 || !(z > static_cast<double>(tile.z1)))
      {
        return false;
      }
      const int i0 = std::max(ix0 - tx * kTileWidth, 0);
      const int i1 = std::min(ix1 - tx * kTileWidth, kTileWidth - 1);
      const int j0 = std::max(iy0 - ty * kTileHeight, 0);
      const int j1 = std::min(iy1 - ty * kTileHeight, kTileHeight - 1);
      const std::uint32_t rowBits = ((2u << i1) - 1u) & ~((1u << i0) - 1u);
      std::uint32_t covered = 0;
      for (int j = j0; j <= j1; ++j)
      {
        covered |= rowBits << (j * kTileWidth);
      }
      if ((covered & ~tile.mask) != 0)
      {
        return false;
      }
    }
  }
  return true;
}

namespace
{
/// Clip-space plane functions of the frustum sides and the near plane (inside: >= 0). The far
/// plane is not clipped: what is beyond it is hidden anyway.
inline double planeValue(int plane, const glm::dvec4& v)
{
  switch (plane)
  {
    case 0:
      return v.w + v.x;
    case 1:
      return v.w - v.x;
    case 2:
      return v.w + v.y;
    case 3:
      return v.w - v.y;
    default:
      return v.w + v.z;
  }
}
} // namespace

bool MaskedDepthBuffer::boxOccluded(const glm::dvec3& lo, const glm::dvec3& hi)
{
  ++stats_.boxesTested;
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z) || !std::isfinite(lo.x) ||
    !std::isfinite(lo.y) || !std::isfinite(lo.z) || !std::isfinite(hi.x) ||
    !std::isfinite(hi.y) || !std::isfinite(hi.z))
  {
    return false;
  }
  glm::dvec4 corner[8];
  unsigned outside = 0; // planes some corner is outside of
  for (int k = 0; k < 8; ++k)
  {
    corner[k] = clipFromWorld_ *
      glm::dvec4((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z, 1.0);
    if (!finite(corner[k]))
    {
      return false;
    }
    for (int p = 0; p < 5; ++p)
    {
      outside |= planeValue(p, corner[k]) < 0.0 ? 1u << p : 0u;
    }
  }
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, zNear = x0;
  double x1 = -x0, y1 = -x0;
  bool any = false;
  auto add = [&](const glm::dvec4& c) {
    if (!(c.w > 0.0))
    {
      return false;
    }
    const double x = (c.x / c.w * 0.5 + 0.5) * width_;
    const double y = (c.y / c.w * 0.5 + 0.5) * height_;
    const double z = c.z / c.w * 0.5 + 0.5;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
    zNear = std::min(zNear, z);
    any = true;
    return true;
  };
  if (outside == 0)
  {
    for (const glm::dvec4& c : corner)
    {
      if (!add(c))
      {
        return false;
      }
    }
  }
  else
  {
    // The near plane's rectangle inside the box: the box reaches the near plane on screen (the
    // clipped faces below would miss that face of box-and-frustum). Tested on a slightly grown
    // box so that rounding cannot miss it.
    const glm::dvec3 grow = (hi - lo) * 1e-9 + (glm::abs(lo) + glm::abs(hi)) * 1e-12;
    for (int k = 0; k < 4; ++k)
    {
      const glm::dvec3& p = nearCorners_[k];
      if (!nearCornersValid_ ||
        (p.x >= lo.x - grow.x && p.x <= hi.x + grow.x && p.y >= lo.y - grow.y &&
          p.y <= hi.y + grow.y && p.z >= lo.z - grow.z && p.z <= hi.z + grow.z))
      {
        return false;
      }
    }
    // Only the part of the box inside the frustum can be seen: clip its six faces against the
    // planes it crosses; the clipped faces bound box-and-frustum, whose vertices give the screen
    // rectangle and the nearest depth. (A box reaching the near plane thus keeps only what is
    // on screen: a room beside the viewer is tested by the part of it in view.)
    static const int faces[6][4] = { { 0, 1, 3, 2 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
      { 2, 3, 7, 6 }, { 0, 2, 6, 4 }, { 1, 3, 7, 5 } };
    glm::dvec4 bufferA[16], bufferB[16];
    for (const auto& face : faces)
    {
      int n = 4;
      glm::dvec4* in = bufferA;
      glm::dvec4* out = bufferB;
      for (int i = 0; i < 4; ++i)
      {
        in[i] = corner[face[i]];
      }
      for (int p = 0; p < 5 && n > 0; ++p)
      {
        if (!(outside & (1u << p)))
        {
          continue;
        }
        int m = 0;
        for (int i = 0; i < n; ++i)
        {
          const glm::dvec4& a = in[i];
          const glm::dvec4& b = in[(i + 1) % n];
          const double da = planeValue(p, a), db = planeValue(p, b);
          if (da >= 0.0)
          {
            out[m++] = a;
          }
          if ((da >= 0.0) != (db >= 0.0))
          {
            out[m++] = a + (b - a) * (da / (da - db));
          }
        }
        n = m;
        std::swap(in, out);
      }
      for (int i = 0; i < n; ++i)
      {
        if (!add(in[i]))
        {
          return false;
        }
      }
    }
    if (!any)
    {
      return false; // outside the frustum: for the frustum test to count, not occlusion
    }
  }
  const bool occluded = rectOccluded(x0, y0, x1, y1, zNear);
  stats_.boxesOccluded += occluded ? 1 : 0;
  return occluded;
}

std::vector<std::uint32_t> buildTriangleNeighbors(
  const double* xyz, std::size_t pointCount, const std::uint32_t* indices, std::size_t triangleCount)
{
  std::vector<std::uint32_t> neighbors(3 * triangleCount, kNoNeighbor);
  // Weld by exact coordinates: sort the points (by value; -0.0 == 0.0) and number the runs.
  std::vector<std::uint32_t> order(pointCount);
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    order[i] = static_cast<std::uint32_t>(i);
  }
  auto less = [xyz](std::uint32_t a, std::uint32_t b) {
    const double* p = xyz + 3 * std::size_t(a);
    const double* q = xyz + 3 * std::size_t(b);
    if (p[0] != q[0])
      return p[0] < q[0];
    if (p[1] != q[1])
      return p[1] < q[1];
    return p[2] < q[2];
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> weld(pointCount);
  std::uint32_t id = 0;
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    if (i > 0 && less(order[i - 1], order[i]))
    {
      ++id;
    }
    weld[order[i]] = id; // NaN coordinates compare unequal to all: they may not weld (fine)
  }
  // Every edge as (smaller welded id, larger, half-edge index, direction); sorted, an edge used
  // by exactly two half-edges of opposite directions joins their triangles.
  struct HalfEdge
  {
    std::uint64_t key;
    std::uint32_t index;
    bool forward;
    bool operator<(const HalfEdge& o) const { return key < o.key; }
  };
  std::vector<HalfEdge> edges;
  edges.reserve(3 * triangleCount);
  for (std::size_t t = 0; t < triangleCount; ++t)
  {
    const std::uint32_t* tri = indices + 3 * t;
    if (tri[0] < pointCount && tri[1] < pointCount && tri[2] < pointCount &&
      (weld[tri[0]] == weld[tri[1]] || weld[tri[1]] == weld[tri[2]] ||
        weld[tri[2]] == weld[tri[0]]))
    {
      continue; // two points in one place: no area, and its edges would hide its neighbours'
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t i0 = indices[3 * t + k], i1 = indices[3 * t + (k + 1) % 3];
      if (i0 >= pointCount || i1 >= pointCount || weld[i0] == weld[i1])
      {
        continue;
      }
      const std::uint32_t a = weld[i0], b = weld[i1];
      edges.push_back({ (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b),
        static_cast<std::uint32_t>(3 * t + k), a < b });
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key)
    {
      ++j;
    }
    if (j - i == 2 && edges[i].forward != edges[i + 1].forward)
    {
      neighbors[edges[i].index] = edges[i + 1].index / 3;
      neighbors[edges[i + 1].index] = edges[i].index / 3;
    }
    i = j;
  }
  return neighbors;
}

bool closedSurface(const double* xyz, std::size_t pointCount, const std::uint32_t* indices,
  std::size_t triangleCount, const std::vector<std::uint32_t>& neighbors)
{
  if (triangleCount == 0 || neighbors.size() != 3 * triangleCount)
  {
    return false;
  }
  const auto same = [xyz](std::uint32_t a, std::uint32_t b)
  {
    const double* p = xyz + 3 * std::size_t(a);
    const double* q = xyz + 3 * std::size_t(b);
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  };
  for (std::size_t t = 0; t < triangleCount; ++t)
  {
    const std::uint32_t* tri = indices + 3 * t;
    if (tri[0] >= pointCount || tri[1] >= pointCount || tri[2] >= pointCount)
    {
      return false;
    }
    const bool degenerate = same(tri[0], tri[1]) || same(tri[1], tri[2]) || same(tri[2], tri[0]);
    if (!degenerate &&
      (neighbors[3 * t] == kNoNeighbor || neighbors[3 * t + 1] == kNoNeighbor ||
        neighbors[3 * t + 2] == kNoNeighbor))
    {
      return false;
    }
  }
  return true;
}

} // namespace occlusion
} // namespace scenevis

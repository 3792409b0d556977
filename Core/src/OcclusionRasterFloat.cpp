// MaskedDepthBuffer's float rasterizer (OcclusionBuffer.h, "Two rasterizers"): the coverage of a
// triangle over a row of tiles from each edge's crossings of the row's four scanlines, four
// scanlines in one SSE2 register, and each tile's 32-bit mask from those crossings in a few
// integer operations. The idea of Intel's Masked Software Occlusion Culling (Hasselgren et al.
// 2016: per-scanline edge events shifted into tile masks), our own code and error bounds.
#include "scenevis/OcclusionBuffer.h"

#include "OcclusionEdge.h"
#include "OcclusionTileUpdate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scenevis
{
namespace occlusion
{

#ifdef SCENEVIS_OCCLUSION_SSE2
namespace
{
/// Window coordinates (pixels) beyond which a triangle goes to the exact rasterizer: inside, a
/// float keeps them to 2^-10 pixel, and the crossings below stay far from int overflow.
constexpr double kFloatExtent = 16384.0;
/// Edges with |dx| > kSteepest |dy| (dy != 0) go to the exact rasterizer: their crossings move
/// by more than kSteepest pixels per scanline.
constexpr double kSteepest = 65536.0;
/// Crossings are clamped to +-kClamp pixels (far beyond any viewport; the int conversion is then
/// exact).
constexpr float kClamp = 1048576.0f;
/// Eight float roundings (2^-24 each): the rounding bounds below are this times the magnitudes
/// involved, at least four times what the analysis needs.
constexpr double kRounding = 1.0 / 2097152.0; // 2^-21

/// One non-horizontal edge, as its crossing of scanline centre y: x = px + (y - py) k + shift,
/// shift = -1/2 (pixel centres are at i + 1/2) plus, on the outline, the margin and the error
/// bound towards the inside.
struct ScanEdge
{
  __m128 px, py, k, shift;
  /// All bits: the pixel at an exact crossing is inside (tie rule), else none.
  __m128 tie;
  bool left; ///< inside for x greater than the crossing
};

inline __m128 floorPs(__m128 v, __m128 one)
{
  const __m128 t = _mm_cvtepi32_ps(_mm_cvttps_epi32(v));
  return _mm_sub_ps(t, _mm_and_ps(_mm_cmplt_ps(v, t), one));
}
} // namespace
#endif

bool MaskedDepthBuffer::drawFrontTriangleFloat(const glm::dvec3& a, const glm::dvec3& b,
  const glm::dvec3& c, double area2, const CentreSpan& span, unsigned outline)
{
#ifndef SCENEVIS_OCCLUSION_SSE2
  (void)a, (void)b, (void)c, (void)area2, (void)span, (void)outline;
  return false; // the exact rasterizer draws it
#else
  const glm::dvec3* vertex[3] = { &a, &b, &c };
  double extent = static_cast<double>(width_ + height_);
  for (const glm::dvec3* v : vertex)
  {
    extent = std::max({ extent, std::abs(v->x), std::abs(v->y) });
  }
  if (!(extent <= kFloatExtent))
  {
    return false;
  }
  // Float window coordinates: a shared vertex rounds to the same floats in both of its
  // triangles, which is what makes shared edges watertight below.
  float fx[3], fy[3];
  for (int i = 0; i < 3; ++i)
  {
    fx[i] = static_cast<float>(vertex[i]->x);
    fy[i] = static_cast<float>(vertex[i]->y);
  }
  const double orientation = area2 > 0.0 ? 1.0 : -1.0;
  const double xmin = std::min({ a.x, b.x, c.x }), xmax = std::max({ a.x, b.x, c.x });
  const double ymin = std::min({ a.y, b.y, c.y }), ymax = std::max({ a.y, b.y, c.y });
  // |y - py| over the scanlines tested (within the triangle's rows), |x - px| likewise.
  const double rows = ymax - ymin + 8.0, columns = xmax - xmin + 8.0;

  ScanEdge scan[3];
  int scanCount = 0;
  int rowFirst = span.y0, rowLast = span.y1;
  double crossingError = 0.0; // the largest, for the depth bound of interior edges
  const __m128 half = _mm_set1_ps(0.5f);
  for (int e = 0; e < 3; ++e)
  {
    const int i = e, j = (e + 1) % 3;
    // Canonical direction (lexicographic on the floats): the two triangles of a shared edge
    // compute the same crossings bit for bit.
    const bool forward = fx[i] < fx[j] || (fx[i] == fx[j] && fy[i] < fy[j]);
    const int p = forward ? i : j, q = forward ? j : i;
    const float dx = fx[q] - fx[p], dy = fy[q] - fy[p];
    const double sign = (forward ? 1.0 : -1.0) * orientation;
    const bool isOutline = (outline >> e) & 1u;
    const bool includeTie = isOutline || sign > 0.0;
    if (dx == 0.0f && dy == 0.0f)
    {
      return false; // collapsed in float: not this rasterizer's business
    }
    if (dy == 0.0f)
    {
      // Horizontal: inside where g (y - py) > threshold, g = sign dx. A range of pixel rows j
      // (centre j + 1/2), found in double from float py (py - 1/2 is exact).
      const double g = sign * dx, py = fy[p];
      if (isOutline)
      {
        const double lever = 1.0 + 2.0 * columns / std::abs(static_cast<double>(dx));
        const double margin = coverageMargin + kRounding * extent * (1.0 + 2.0 * lever);
        if (g > 0.0)
          rowFirst = std::max(rowFirst, static_cast<int>(std::floor(py + margin - 0.5)) + 1);
        else
          rowLast = std::min(rowLast, static_cast<int>(std::ceil(py - margin - 0.5)) - 1);
      }
      else if (g > 0.0)
      {
        rowFirst = std::max(rowFirst,
          includeTie ? static_cast<int>(std::ceil(py - 0.5))
                     : static_cast<int>(std::floor(py - 0.5)) + 1);
      }
      else
      {
        rowLast = std::min(rowLast,
          includeTie ? static_cast<int>(std::floor(py - 0.5))
                     : static_cast<int>(std::ceil(py - 0.5)) - 1);
      }
      continue;
    }
    if (std::abs(static_cast<double>(dx)) > kSteepest * std::abs(static_cast<double>(dy)))
    {
      return false;
    }
    const float k = dx / dy;
    const double ak = std::abs(static_cast<double>(k));
    // Where the float crossing may be, against the crossing of the double edge: the vertices'
    // rounding (2^-24 extent each) moves the line by up to (1 + 2 lever) of that at the scanlines
    // tested, which moves the crossing by (1 + |k|) times as much; the crossing's own rounding
    // (y - py, k, the product, the sums) is a few 2^-24 of |px| + |y - py| |k|.
    const double lever = rows / std::abs(static_cast<double>(dy));
    const double error =
      kRounding * (extent * (1.0 + 2.0 * lever) * (1.0 + ak) + extent + rows * ak + 1.0);
    // As a distance from the edge (for the depth bound): |dy| / len of it, <= sqrt 2 / (1 + |k|).
    crossingError = std::max(crossingError, error * 1.5 / (1.0 + ak));
    ScanEdge& s = scan[scanCount++];
    s.left = -sign * dy > 0.0; // d value / dx > 0
    double shift = -0.5;
    if (isOutline)
    {
      // Inside by coverageMargin (perpendicular) is margin len / |dy| along the scanline; the
      // error bound on top, rounded so that the float shift is no smaller.
      const double len = std::sqrt(double(dx) * dx + double(dy) * dy);
      const double inward = coverageMargin * len / std::abs(static_cast<double>(dy)) + error;
      const double inflated = inward * (1.0 + 4.0 * kRounding) + kRounding;
      shift = s.left ? -0.5 + inflated : -0.5 - inflated;
    }
    s.px = _mm_set1_ps(fx[p]);
    s.py = _mm_set1_ps(fy[p]);
    s.k = _mm_set1_ps(k);
    s.shift = _mm_set1_ps(static_cast<float>(shift));
    // The outline takes no tie (its shift is strictly inward already).
    s.tie = _mm_castsi128_ps(_mm_set1_epi32(!isOutline && includeTie ? -1 : 0));
  }
  if (rowFirst > rowLast)
  {
    ++stats_.trianglesRejected;
    return true;
  }

  const DepthPlane plane(a, b, c, area2, polygonOffsetFactor, polygonOffsetDepth, width_, height_);
  // A pixel an interior edge gives to this triangle may lie up to crossingError pixels inside
  // its twin (which OpenGL draws there): the plane's value there is bounded by the tile's
  // corners, the twin's differs by at most the gradient times that distance.
  const double interiorSlack =
    (outline == 7u ? 0.0 : crossingError * (std::abs(plane.zx) + std::abs(plane.zy))) + depthMargin;
  const double zNearVertex = std::min({ a.z, b.z, c.z }) + depthMargin;

  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 lo = _mm_set1_ps(-kClamp), hi = _mm_set1_ps(kClamp);
  const __m128 leftStart = _mm_set1_ps(static_cast<float>(span.x0));
  const __m128 rightStart = _mm_set1_ps(static_cast<float>(span.x1));
  const __m128 empty = _mm_set1_ps(kClamp), minusEmpty = _mm_set1_ps(-kClamp);
  const __m128 firstRow = _mm_set1_ps(static_cast<float>(rowFirst));
  const __m128 lastRow = _mm_set1_ps(static_cast<float>(rowLast));
  const __m128 rowStep = _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f);
  const __m128i column = _mm_set_epi8(7, 6, 5, 4, 3, 2, 1, 0, 7, 6, 5, 4, 3, 2, 1, 0);
  const int ty0 = rowFirst / kTileHeight, ty1 = rowLast / kTileHeight;
  bool touched = false;
  for (int ty = ty0; ty <= ty1; ++ty)
  {
    const __m128 row = _mm_add_ps(_mm_set1_ps(static_cast<float>(ty * kTileHeight)), rowStep);
    const __m128 centre = _mm_add_ps(row, half);
    __m128 first = leftStart, last = rightStart;
    for (int e = 0; e < scanCount; ++e)
    {
      const ScanEdge& s = scan[e];
      __m128 v = _mm_add_ps(_mm_add_ps(s.px, _mm_mul_ps(_mm_sub_ps(centre, s.py), s.k)), s.shift);
      v = _mm_min_ps(_mm_max_ps(v, lo), hi);
      const __m128 down = floorPs(v, one);
      const __m128 exact = _mm_and_ps(_mm_cmpeq_ps(v, down), s.tie);
      if (s.left)
      {
        // First pixel i with i > v (i >= v with the tie): floor(v) + 1, or v itself.
        first = _mm_max_ps(first, _mm_sub_ps(_mm_add_ps(down, one), _mm_and_ps(exact, one)));
      }
      else
      {
        // Last pixel i with i < v (i <= v with the tie): ceil(v) - 1, or v itself.
        const __m128 up = _mm_add_ps(down, _mm_and_ps(_mm_cmplt_ps(down, v), one));
        last = _mm_min_ps(last, _mm_add_ps(_mm_sub_ps(up, one), _mm_and_ps(exact, one)));
      }
    }
    const __m128 valid = _mm_and_ps(_mm_cmpge_ps(row, firstRow), _mm_cmple_ps(row, lastRow));
    first = _mm_or_ps(_mm_and_ps(valid, first), _mm_andnot_ps(valid, empty));
    // The row's pixel range: the smallest first and largest last of the scanlines not empty.
    const __m128 filled = _mm_cmple_ps(first, last);
    __m128 from = _mm_or_ps(_mm_and_ps(filled, first), _mm_andnot_ps(filled, empty));
    __m128 to = _mm_or_ps(_mm_and_ps(filled, last), _mm_andnot_ps(filled, minusEmpty));
    from = _mm_min_ps(from, _mm_shuffle_ps(from, from, _MM_SHUFFLE(1, 0, 3, 2)));
    from = _mm_min_ps(from, _mm_shuffle_ps(from, from, _MM_SHUFFLE(2, 3, 0, 1)));
    to = _mm_max_ps(to, _mm_shuffle_ps(to, to, _MM_SHUFFLE(1, 0, 3, 2)));
    to = _mm_max_ps(to, _mm_shuffle_ps(to, to, _MM_SHUFFLE(2, 3, 0, 1)));
    const int xFirst = _mm_cvttss_si32(from), xLast = _mm_cvttss_si32(to);
    if (xFirst > xLast)
    {
      continue;
    }
    const __m128i firstI = _mm_cvttps_epi32(first), lastI = _mm_cvttps_epi32(last);
    // Per tile: pixel i of scanline j is covered when first_j <= 8 tx + i <= last_j; the bounds
    // relative to the tile, saturated to bytes, repeated over their scanline's 8 bytes.
    const __m128i below = _mm_sub_epi32(firstI, _mm_set1_epi32(1));
    const __m128i above = _mm_add_epi32(lastI, _mm_set1_epi32(1));
    const double y0 = ty * kTileHeight + 0.5;
    const int txEnd = xLast / kTileWidth;
    for (int tx = xFirst / kTileWidth; tx <= txEnd; ++tx)
    {
      Tile& tile = tiles_[static_cast<std::size_t>(ty) * tilesX_ + tx];
      if (zNearVertex >= static_cast<double>(tile.z0))
      {
        continue; // behind what the whole tile has: nothing to add
      }
      const __m128i base = _mm_set1_epi32(tx * kTileWidth);
      const __m128i bounds =
        _mm_packs_epi32(_mm_sub_epi32(below, base), _mm_sub_epi32(above, base));
      __m128i bytes = _mm_packs_epi16(bounds, bounds); // b0..b3 a0..a3 (twice)
      bytes = _mm_unpacklo_epi8(bytes, bytes);
      const __m128i belowRows = _mm_unpacklo_epi16(bytes, bytes); // each b_j four times
      const __m128i aboveRows = _mm_unpackhi_epi16(bytes, bytes);
      const __m128i b01 = _mm_unpacklo_epi32(belowRows, belowRows);
      const __m128i b23 = _mm_unpackhi_epi32(belowRows, belowRows);
      const __m128i a01 = _mm_unpacklo_epi32(aboveRows, aboveRows);
      const __m128i a23 = _mm_unpackhi_epi32(aboveRows, aboveRows);
      const int low =
        _mm_movemask_epi8(_mm_and_si128(_mm_cmpgt_epi8(column, b01), _mm_cmpgt_epi8(a01, column)));
      const int high =
        _mm_movemask_epi8(_mm_and_si128(_mm_cmpgt_epi8(column, b23), _mm_cmpgt_epi8(a23, column)));
      const std::uint32_t mask =
        static_cast<std::uint32_t>(low) | (static_cast<std::uint32_t>(high) << 16);
      if (mask == 0)
      {
        continue;
      }
      const double x0 = tx * kTileWidth + 0.5;
      const float oldZ0 = tile.z0;
      updateTile(tile, mask, roundUp(plane.tileBound(x0, y0) + interiorSlack),
        outsideX_[tx] | outsideY_[ty]);
      ++revision_;
      if (tile.z0 != oldZ0)
      {
        lowerBlock(tx, ty, oldZ0);
      }
      ++stats_.tilesUpdated;
      touched = true;
    }
  }
  ++(touched ? stats_.trianglesDrawn : stats_.trianglesRejected);
  return true;
#endif
}

} // namespace occlusion
} // namespace scenevis

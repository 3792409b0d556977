#pragma once
// Module-private: the edge test of MaskedDepthBuffer's exact rasterizer (OcclusionBuffer.cpp),
// with the coverage mask of a whole 8 x 4 tile computed four rows at once (SSE2, the x86-64
// baseline; the same arithmetic row by row elsewhere). Both give the same bits: only IEEE double
// operations in the same order, and integer steps that are exact. Also the depth bound of a
// triangle over a tile and the upward float rounding that both rasterizers share.

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define SCENEVIS_OCCLUSION_SSE2 1
#endif

namespace scenevis
{
namespace occlusion
{
/// The smallest float not below @p value (float(value) may round down).
inline float roundUp(double value)
{
  float f = static_cast<float>(value);
  if (static_cast<double>(f) < value)
  {
    // std::nextafter(f, +inf) without the library call (one per tile update): f is below value,
    // so neither +inf nor NaN; the next float up is one step of its bits away from zero when
    // positive, towards zero when negative (-inf gives the lowest finite float, as nextafter
    // does), the smallest positive one from +-0.
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits = f == 0.0f ? 1u : ((bits >> 31) == 0u ? bits + 1u : bits - 1u);
    std::memcpy(&f, &bits, sizeof f);
  }
  return f;
}

/**
 * Window depth of a triangle as a plane z = zx x + zy y + z00 (depth is affine in window x, y),
 * and a bound on it over the 8 x 4 pixel centres of a tile: the plane's largest value over the
 * tile's corner centres (plus a generous bound on its rounding and the OpenGL polygon offset),
 * never farther than the triangle's farthest vertex (plus offset). The depth margin comes on top.
 */
struct DepthPlane
{
  double zx, zy, z00, offset, zFarVertex, planeError, zOffset;

  DepthPlane(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double area2,
    double offsetFactor, double offsetDepth, int width, int height)
  {
    // Counter-clockwise vertex order for the solve.
    const double det = std::abs(area2);
    const glm::dvec3& q1 = area2 > 0.0 ? b : c;
    const glm::dvec3& q2 = area2 > 0.0 ? c : b;
    const double bx = q1.x - a.x, by = q1.y - a.y, bz = q1.z - a.z;
    const double cx = q2.x - a.x, cy = q2.y - a.y, cz = q2.z - a.z;
    zx = (bz * cy - by * cz) / det;
    zy = (bx * cz - bz * cx) / det;
    z00 = a.z - zx * a.x - zy * a.y;
    offset = std::max(0.0, offsetFactor) * std::max(std::abs(zx), std::abs(zy)) +
      std::max(0.0, offsetDepth);
    zFarVertex = std::max({ a.z, b.z, c.z }) + offset;
    planeError =
      1e-12 * ((std::abs(zx) + 1.0) * width + (std::abs(zy) + 1.0) * height + std::abs(z00));
    zOffset = std::max(0.0, 7 * zx) + std::max(0.0, 3 * zy);
  }

  /// The bound over the tile whose first pixel centre is (x0, y0).
  double tileBound(double x0, double y0) const
  {
    const double zCorners = zx * x0 + zy * y0 + z00 + zOffset;
    return std::min(zCorners + offset + planeError, zFarVertex);
  }
};

/**
 * Inside test of one triangle edge at pixel centres. The edge function is evaluated with the
 * edge's end points in a canonical order (lexicographic), so the two triangles sharing an edge
 * compute the same value bit for bit and differ only in `sign`; a centre exactly on the edge
 * goes to the triangle whose sign is positive (the tie rule), so shared edges leave no holes.
 */
struct EdgeTest
{
  double px, py, dx, dy; ///< canonical start point and direction
  double sign;           ///< +1 / -1: makes the triangle's inside positive
  double threshold;      ///< 0 inside an occluder, margin * length on its outline
  bool includeTie;
  double slack; ///< bound on the rounding of value() between corners and pixel centres

  EdgeTest(const glm::dvec3& from, const glm::dvec3& to, double orientation, bool outline,
    double margin, double extent)
  {
    const bool forward = from.x < to.x || (from.x == to.x && from.y < to.y);
    const glm::dvec3& p = forward ? from : to;
    const glm::dvec3& q = forward ? to : from;
    px = p.x;
    py = p.y;
    dx = q.x - p.x;
    dy = q.y - p.y;
    sign = (forward ? 1.0 : -1.0) * orientation;
    threshold = outline ? margin * std::sqrt(dx * dx + dy * dy) : 0.0;
    includeTie = outline || sign > 0.0;
    slack = 1e-9 * (std::abs(dx) + std::abs(dy)) * extent;
    gx = -sign * dy;
    gy = sign * dx;
    inverseGx = gx != 0.0 ? 1.0 / gx : 0.0; // 1 / -g == -(1 / g): symmetric between twins
  }
  double inverseGx;
  double gx, gy; ///< d value / dx, d value / dy
  double value(double x, double y) const { return sign * (dx * (y - py) - dy * (x - px)); }

  /**
   * Bits i = 0..7 of the centres (x + i, y) inside this edge. Along the row the value is affine
   * in i and crosses the threshold at t = (threshold - value(x, y)) / gx, computed from the
   * canonical value: the two triangles of a shared edge (threshold 0, opposite signs) get the
   * same t bit for bit, and the tie rule gives a centre exactly at t to one of them, so the rule
   * "inside when i is on the inner side of t" leaves no hole and covers nothing twice.
   */
  std::uint32_t rowMask(double x, double y) const
  {
    const double rowValue = value(x, y);
    if (gx == 0.0)
    {
      return (rowValue > threshold || (rowValue == threshold && includeTie)) ? 0xFFu : 0u;
    }
    const double t = std::max(-16.0, std::min(24.0, (threshold - rowValue) * inverseGx));
    // floor and ceil by truncating positive numbers (t is clamped): both twins of a shared edge
    // evaluate the same expressions of the same t, which is all that watertightness needs, and
    // an off-by-one only where t is within rounding of an integer moves a centre that lies on
    // the edge itself (inside an occluder) or within rounding of a 1/64-pixel margin.
    const int below = static_cast<int>(t + 32.0) - 32; // floor(t)
    const int above = 32 - static_cast<int>(32.0 - t); // ceil(t)
    if (gx > 0.0)
    {
      // Inside for i > t (i >= t with the tie).
      const int first = includeTie ? above : below + 1;
      return first <= 0 ? 0xFFu : (first >= 8 ? 0u : (0xFFu << first) & 0xFFu);
    }
    // Inside for i < t (i <= t with the tie).
    const int end = includeTie ? below + 1 : above;
    return end <= 0 ? 0u : (end >= 8 ? 0xFFu : (1u << end) - 1u);
  }

  /// Bits (j * 8 + i) of the centres (x + i, y + j), i < 8, j < 4, inside this edge: rowMask()
  /// of the four rows.
  std::uint32_t tileMask(double x, double y) const
  {
#ifdef SCENEVIS_OCCLUSION_SSE2
    if (gx != 0.0)
    {
      return tileMaskSse2(x, y);
    }
#endif
    std::uint32_t mask = 0;
    for (int j = 0; j < 4; ++j)
    {
      mask |= rowMask(x, y + j) << (j * 8);
    }
    return mask;
  }

#ifdef SCENEVIS_OCCLUSION_SSE2
  /// tileMask() for gx != 0: the rows' crossings t two at a time, then the pixels of all four
  /// rows compared with them as 32 bytes (i on the inner side of t), whose signs are the mask.
  std::uint32_t tileMaskSse2(double x, double y) const
  {
    const __m128d across = _mm_set1_pd(dy * (x - px));
    const __m128d lo = _mm_set1_pd(-16.0), hi = _mm_set1_pd(24.0), shift = _mm_set1_pd(32.0);
    __m128i below[2], above[2];
    for (int h = 0; h < 2; ++h)
    {
      const __m128d rows = _mm_set_pd(y + (2 * h + 1), y + 2 * h);
      const __m128d rowValue = _mm_mul_pd(_mm_set1_pd(sign),
        _mm_sub_pd(_mm_mul_pd(_mm_set1_pd(dx), _mm_sub_pd(rows, _mm_set1_pd(py))), across));
      const __m128d t = _mm_max_pd(
        _mm_min_pd(
          _mm_mul_pd(_mm_sub_pd(_mm_set1_pd(threshold), rowValue), _mm_set1_pd(inverseGx)), hi),
        lo);
      below[h] = _mm_sub_epi32(_mm_cvttpd_epi32(_mm_add_pd(t, shift)), _mm_set1_epi32(32));
      above[h] = _mm_sub_epi32(_mm_set1_epi32(32), _mm_cvttpd_epi32(_mm_sub_pd(shift, t)));
    }
    // Per row, inside for i > bound: gx > 0: i >= first, so bound = first - 1; gx < 0: i < end,
    // compared the other way round.
    const __m128i floors = _mm_unpacklo_epi64(below[0], below[1]);
    const __m128i ceils = _mm_unpacklo_epi64(above[0], above[1]);
    const __m128i one = _mm_set1_epi32(1);
    __m128i bound;
    if (gx > 0.0)
    {
      bound = includeTie ? _mm_sub_epi32(ceils, one) : floors; // first - 1
    }
    else
    {
      bound = includeTie ? _mm_add_epi32(floors, one) : ceils; // end
    }
    // Each row's bound repeated over its 8 bytes: rows 0-1 in the low register, 2-3 in the high.
    __m128i bytes = _mm_packs_epi16(_mm_packs_epi32(bound, bound), _mm_setzero_si128());
    bytes = _mm_unpacklo_epi8(bytes, bytes);
    bytes = _mm_unpacklo_epi16(bytes, bytes);
    const __m128i rows01 = _mm_unpacklo_epi32(bytes, bytes);
    const __m128i rows23 = _mm_unpackhi_epi32(bytes, bytes);
    const __m128i column = _mm_set_epi8(7, 6, 5, 4, 3, 2, 1, 0, 7, 6, 5, 4, 3, 2, 1, 0);
    int low, high;
    if (gx > 0.0)
    {
      low = _mm_movemask_epi8(_mm_cmpgt_epi8(column, rows01));
      high = _mm_movemask_epi8(_mm_cmpgt_epi8(column, rows23));
    }
    else
    {
      low = _mm_movemask_epi8(_mm_cmpgt_epi8(rows01, column));
      high = _mm_movemask_epi8(_mm_cmpgt_epi8(rows23, column));
    }
    return static_cast<std::uint32_t>(low) | (static_cast<std::uint32_t>(high) << 16);
  }
#endif
};

} // namespace occlusion
} // namespace scenevis

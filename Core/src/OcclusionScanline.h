#pragma once
// Module-private: the coverage of MaskedDepthBuffer's exact rasterizer (OcclusionBuffer.cpp), a
// scanline at a time. Per pixel row, the pixel centres inside a triangle's three edges form one
// interval of columns [first, last]; a tile's 32-bit mask is then a few byte compares of its
// four scanlines' intervals against the tile's columns (SSE2, the x86-64 baseline; the same bits
// by a loop elsewhere).
//
// Why the intervals are exact: a centre (i + 1/2, y + 1/2) is inside an edge when EdgeTest's
// canonical value v = sign (dx (y + 1/2 - py) - dy (i + 1/2 - px)), evaluated in IEEE double in
// exactly this order, is > threshold (or = threshold with the tie). Along a scanline v is
// monotone in i: x -> x - px rounds monotonically, so does the product with the fixed dy
// (increasing or decreasing by dy's sign) and the difference from the fixed row term, and the
// sign flips it exactly. So each edge's inside centres on a scanline form a half-line of columns
// (all or none where dy = 0), and the centres inside all three edges an interval. Its ends are
// that test's: from the edge's crossing of the scanline (v = threshold, computed in double),
// where it lies farther from a column than a bound on the rounding of both the crossing and v
// (delta_, 1e-9 of the coordinates: about a million times the true bound), the columns on
// either side have |v - threshold| above v's rounding, so the test's outcome is known without
// evaluating it (almost always); nearer, or for nearly horizontal edges, the test is evaluated
// at the column and its neighbour, and if the boundary is not there, a bisection over the
// columns left finds it with the same test. Either way the interval is exactly the centres that
// pass the test of all three edges. Hence, as for the per-tile edge evaluation it replaces:
// - outline edges: every centre claimed has v >= margin * length, i.e. it is at least the
//   coverage margin inside the double triangle (up to the rounding of one evaluation, about
//   1e-16 of the coordinates, far below the 1/64-pixel margin);
// - interior edges (threshold 0): the two triangles sharing the edge hold the same canonical
//   start point and direction, so they compute the same rounded dx (y - py) - dy (x - px) at
//   every centre and differ only in the sign; where it is 0 the tie rule gives the centre to
//   exactly one of them. Every centre goes to exactly one side of the edge: no hole, none
//   claimed twice.

#include "OcclusionEdge.h"

#include <algorithm>
#include <cstdint>

namespace scenevis
{
namespace occlusion
{

/// The pixel centres of one triangle, scanline by scanline (see the file comment).
class ScanlineCoverage
{
public:
  /// first of an empty scanline (and -kEmpty its last): beyond any column.
  static constexpr int kEmpty = 1 << 20;

  /// @p extent: at least every coordinate of the triangle's vertices and the viewport's width
  /// plus height; [@p x0, @p x1]: the columns that will be asked for (the triangle's span).
  ScanlineCoverage(const EdgeTest (&edges)[3], double extent, int x0, int x1)
    : edges_(edges)
  {
    for (int k = 0; k < 3; ++k)
    {
      const EdgeTest& e = edges[k];
      // Inside for larger i (gx > 0), for smaller i (gx < 0), or alike on the whole scanline.
      side_[k] = e.gx > 0.0 ? 1 : (e.gx < 0.0 ? -1 : 0);
      inverseDy_[k] = e.dy != 0.0 ? 1.0 / e.dy : 0.0;
      signedThreshold_[k] = e.sign * e.threshold;
      // How far (in columns) a crossing computed below may lie from the boundary of the
      // evaluated test. At the centres |x - px|, |y - py| <= 2 extent: the value's rounding is
      // below 4 u (|dx| + |dy|) 2 extent (u = 2^-53), that over |dy| in columns; a crossing's
      // own rounding (either formula below) below 8 u ((|dx| 2 extent + threshold) / |dy| +
      // extent + 1). Taken here with 1e-9 for those 12 u, plus 2^-32 for the rounding of the
      // crossing's fraction in rowIntervals(). Columns farther than this from the crossing are
      // decided without evaluating; a bound of 1/4 or more (nearly horizontal edges) decides
      // none.
      const double delta = 1e-9 *
          (((std::abs(e.dx) + std::abs(e.dy)) * 2.0 * extent + e.threshold) *
              std::abs(inverseDy_[k]) +
            extent + 1.0) +
        1.0 / 4294967296.0;
      delta_[k] = delta < 0.25 ? delta : 1.0;
#ifdef SCENEVIS_OCCLUSION_SSE2
      // The crossing of scanline centre y as a + b y, negated for edges inside below it (whose
      // columns are then negated too: [lo, hi] = [-x1, -x0]).
      const double mirror = side_[k] < 0 ? -1.0 : 1.0;
      above_[k] = _mm_set1_epi32(side_[k] >= 0 ? -1 : 0);
      const double slope = e.dx * inverseDy_[k];
      const double a = (e.px - 0.5) - (e.dx * e.py + signedThreshold_[k]) * inverseDy_[k];
      // The crossing in fixed point (32.32, in 64-bit integers) where it fits: at twice the
      // scanline centre yy = 2 y + 1 it is fixA + yy fixB, fixA and fixB truncated from a 2^32
      // and b 2^31. Against a + b y in real arithmetic that errs by less than 1 + |yy| units of
      // 2^-32, and a + b y (a, b the doubles above) lies as close to the test's boundary as
      // delta says: delta bounds the rounding of a and b and of the product and sum that the
      // fixed point does not round. So columns more than delta + (1 + |yy|) 2^-32 from it are
      // decided as in firstInside(), the others by the test. Used where |a| < 2^28 and
      // |b| (2 extent + 9) < 2^29 (every scanline asked has |y| <= extent + 4): no overflow,
      // whole columns in 32 bits (delta < 1/4 already keeps |b| extent below 2^27), and where
      // near < 2^29 fits the 32-bit compare.
      const double yyMax = 2.0 * extent + 9.0;
      const double nearUnits = delta_[k] * 4294967296.0 + yyMax + 3.0;
      if (side_[k] != 0 && delta_[k] < 1.0 && std::abs(a) < 268435456.0 &&
        std::abs(slope) * yyMax < 536870912.0 && nearUnits < 536870912.0)
      {
        const std::int64_t fixA = static_cast<std::int64_t>(mirror * a * 4294967296.0);
        const std::int64_t fixB = static_cast<std::int64_t>(mirror * slope * 2147483648.0);
        const int fixNear = static_cast<int>(nearUnits);
        fixed_[k] = { fixA, fixB, _mm_set_epi64x(2 * fixB, 0), _mm_set_epi64x(6 * fixB, 4 * fixB),
          _mm_set1_epi32(fixNear + 1), _mm_set1_epi32(2147483647 - 2 * fixNear) };
        fixedEdges_ |= 1u << k;
      }
      else
      {
        const double lo = side_[k] < 0 ? -x1 : x0, hi = side_[k] < 0 ? -x0 : x1;
        scan_[k] = { _mm_set1_pd(mirror * a), _mm_set1_pd(mirror * slope), _mm_set1_pd(lo - 1.5),
          _mm_set1_pd(hi + 1.5 + kShift), _mm_set1_pd(delta_[k]), _mm_set1_pd(1.0 - delta_[k]) };
      }
#else
      (void)x0, (void)x1;
#endif
    }
  }

  /// The columns i in [x0, x1] whose centres (i + 1/2, y + 1/2) are inside all three edges:
  /// [first, last], first > last when there is none.
  void interval(int y, int x0, int x1, int& first, int& last) const
  {
    first = x0;
    last = x1;
    for (int k = 0; k < 3; ++k)
    {
      const int bound = edgeBound(k, y, x0, x1);
      if (side_[k] >= 0)
      {
        first = std::max(first, bound);
      }
      else
      {
        last = std::min(last, bound);
      }
    }
  }

  /// interval() of the four scanlines y0 .. y0 + 3 (those outside [yFirst, yLast], and the
  /// empty ones, as [kEmpty, -kEmpty]): the same intervals, four at a time with SSE2.
  void rowIntervals(
    int y0, int yFirst, int yLast, int x0, int x1, int (&first)[4], int (&last)[4]) const
  {
#ifdef SCENEVIS_OCCLUSION_SSE2
    const __m128i y = _mm_add_epi32(_mm_set1_epi32(y0), _mm_set_epi32(3, 2, 1, 0));
    const __m128i valid = _mm_andnot_si128(_mm_or_si128(_mm_cmplt_epi32(y, _mm_set1_epi32(yFirst)),
                                             _mm_cmpgt_epi32(y, _mm_set1_epi32(yLast))),
      _mm_set1_epi32(-1));
    const unsigned rows = static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(valid)));
    if (rows == 0)
    {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(first), _mm_set1_epi32(kEmpty));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(last), _mm_set1_epi32(-kEmpty));
      return;
    }
    __m128i from = _mm_set1_epi32(x0), to = _mm_set1_epi32(x1);
    // Unrolled: the loop's exit depends on the edges' branches and was mispredicted.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 3
#endif
    for (int k = 0; k < 3; ++k)
    {
      alignas(16) int bound[4];
      __m128i b;
      if ((fixedEdges_ >> k) & 1u)
      {
        // The four crossings in fixed point: whole columns in the high halves, fractions in
        // the low ones; decided where the fraction f is in (near, 2^32 - near), i.e.
        // f - near - 1 < 2^32 - 2 near - 1 unsigned (signed after flipping the top bit).
        const Fixed& fixed = fixed_[k];
        const __m128i base =
          _mm_set1_epi64x(fixed.a + (2 * static_cast<std::int64_t>(y0) + 1) * fixed.b);
        const __m128 c01 = _mm_castsi128_ps(_mm_add_epi64(base, fixed.step01));
        const __m128 c23 = _mm_castsi128_ps(_mm_add_epi64(base, fixed.step23));
        const __m128i whole = _mm_castps_si128(_mm_shuffle_ps(c01, c23, 0xDD));
        const __m128i fraction = _mm_castps_si128(_mm_shuffle_ps(c01, c23, 0x88));
        const __m128i flipped = _mm_xor_si128(
          _mm_sub_epi32(fraction, fixed.nearUnits), _mm_set1_epi32(static_cast<int>(0x80000000u)));
        const int decided =
          _mm_movemask_ps(_mm_castsi128_ps(_mm_cmplt_epi32(flipped, fixed.farUnits)));
        // floor + 1: the first column above the crossing.
        b = _mm_add_epi32(whole, _mm_set1_epi32(1));
        const unsigned undecided = rows & ~static_cast<unsigned>(decided);
        if (undecided != 0)
        {
          _mm_store_si128(reinterpret_cast<__m128i*>(bound), b);
          for (unsigned left = undecided; left != 0; left &= left - 1)
          {
            const int j = lowestBit(left);
            bound[j] = side_[k] * edgeBound(k, y0 + j, x0, x1);
          }
          b = _mm_load_si128(reinterpret_cast<const __m128i*>(bound));
        }
      }
      else if (side_[k] == 0 || delta_[k] >= 1.0)
      {
        // Horizontal or nearly so: each scanline by the test itself.
        for (int j = 0; j < 4; ++j)
        {
          bound[j] = (rows >> j) & 1u ? edgeBound(k, y0 + j, x0, x1) : 0;
          bound[j] = side_[k] < 0 ? -bound[j] : bound[j];
        }
        b = _mm_load_si128(reinterpret_cast<const __m128i*>(bound));
      }
      else
      {
        // The crossings of the four scanlines (mirrored for edges inside below them), clamped
        // and shifted by 2^20 to convert by truncation; decided where their fraction is more
        // than delta from a column (as firstInside()).
        const Scan& scan = scan_[k];
        const __m128d y01 = _mm_set_pd(y0 + 1.5, y0 + 0.5), y23 = _mm_set_pd(y0 + 3.5, y0 + 2.5);
        __m128i below[2];
        int decided = 0;
        for (int h = 0; h < 2; ++h)
        {
          const __m128d t = _mm_add_pd(scan.a, _mm_mul_pd(scan.b, h ? y23 : y01));
          const __m128d shifted =
            _mm_min_pd(_mm_add_pd(_mm_max_pd(t, scan.low), _mm_set1_pd(kShift)), scan.high);
          below[h] = _mm_cvttpd_epi32(shifted);
          const __m128d frac = _mm_sub_pd(shifted, _mm_cvtepi32_pd(below[h]));
          decided |= _mm_movemask_pd(
                       _mm_and_pd(_mm_cmpgt_pd(frac, scan.delta), _mm_cmplt_pd(frac, scan.upper)))
            << (2 * h);
        }
        // floor + 1: the first column above the crossing.
        _mm_store_si128(reinterpret_cast<__m128i*>(bound),
          _mm_sub_epi32(
            _mm_unpacklo_epi64(below[0], below[1]), _mm_set1_epi32(static_cast<int>(kShift) - 1)));
        for (unsigned undecided = rows & ~static_cast<unsigned>(decided); undecided != 0;
             undecided &= undecided - 1)
        {
          const int j = lowestBit(undecided);
          bound[j] = side_[k] * edgeBound(k, y0 + j, x0, x1);
        }
        b = _mm_load_si128(reinterpret_cast<const __m128i*>(bound));
      }
      // Inside from bound on (mirrored: up to -bound); beyond the columns it empties them.
      // Both, masked by the side (a branch on it alternates between a triangle's edges and was
      // mispredicted about once per row).
      const __m128i above = above_[k];
      const __m128i greater = _mm_and_si128(_mm_cmpgt_epi32(b, from), above);
      from = _mm_or_si128(_mm_and_si128(greater, b), _mm_andnot_si128(greater, from));
      const __m128i minus = _mm_sub_epi32(_mm_setzero_si128(), b);
      const __m128i less = _mm_andnot_si128(above, _mm_cmplt_epi32(minus, to));
      to = _mm_or_si128(_mm_and_si128(less, minus), _mm_andnot_si128(less, to));
    }
    const __m128i empty = _mm_andnot_si128(_mm_cmpgt_epi32(from, to), valid); // not empty
    from =
      _mm_or_si128(_mm_and_si128(empty, from), _mm_andnot_si128(empty, _mm_set1_epi32(kEmpty)));
    to = _mm_or_si128(_mm_and_si128(empty, to), _mm_andnot_si128(empty, _mm_set1_epi32(-kEmpty)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(first), from);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(last), to);
#else
    for (int j = 0; j < 4; ++j)
    {
      first[j] = kEmpty;
      last[j] = -kEmpty;
      if (y0 + j >= yFirst && y0 + j <= yLast)
      {
        interval(y0 + j, x0, x1, first[j], last[j]);
        if (first[j] > last[j])
        {
          first[j] = kEmpty;
          last[j] = -kEmpty;
        }
      }
    }
#endif
  }

  /// Bits (j * 8 + i), i < 8, j < 4, of the columns base + i in [first[j], last[j]]: the mask of
  /// the tile whose first column is @p base.
  static std::uint32_t tileMask(const int (&first)[4], const int (&last)[4], int base)
  {
#ifdef SCENEVIS_OCCLUSION_SSE2
    // Per scanline j: covered when below_j < i < above_j, the bounds relative to the tile,
    // saturated to bytes and repeated over their scanline's 8 bytes.
    const __m128i below = _mm_sub_epi32(
      _mm_loadu_si128(reinterpret_cast<const __m128i*>(first)), _mm_set1_epi32(base + 1));
    const __m128i above = _mm_sub_epi32(
      _mm_loadu_si128(reinterpret_cast<const __m128i*>(last)), _mm_set1_epi32(base - 1));
    __m128i bytes = _mm_packs_epi16(_mm_packs_epi32(below, above), _mm_setzero_si128());
    bytes = _mm_unpacklo_epi8(bytes, bytes);                    // b0 b0 .. b3 b3 a0 a0 .. a3 a3
    const __m128i belowRows = _mm_unpacklo_epi16(bytes, bytes); // each b_j four times
    const __m128i aboveRows = _mm_unpackhi_epi16(bytes, bytes);
    const __m128i column = _mm_set_epi8(7, 6, 5, 4, 3, 2, 1, 0, 7, 6, 5, 4, 3, 2, 1, 0);
    const __m128i in01 =
      _mm_and_si128(_mm_cmpgt_epi8(column, _mm_unpacklo_epi32(belowRows, belowRows)),
        _mm_cmpgt_epi8(_mm_unpacklo_epi32(aboveRows, aboveRows), column));
    const __m128i in23 =
      _mm_and_si128(_mm_cmpgt_epi8(column, _mm_unpackhi_epi32(belowRows, belowRows)),
        _mm_cmpgt_epi8(_mm_unpackhi_epi32(aboveRows, aboveRows), column));
    return static_cast<std::uint32_t>(_mm_movemask_epi8(in01)) |
      (static_cast<std::uint32_t>(_mm_movemask_epi8(in23)) << 16);
#else
    return tileMaskScalar(first, last, base);
#endif
  }

  /// tileMask() without SSE2: the same bits.
  static std::uint32_t tileMaskScalar(const int (&first)[4], const int (&last)[4], int base)
  {
    std::uint32_t mask = 0;
    for (int j = 0; j < 4; ++j)
    {
      const int i0 = std::max(first[j] - base, 0), i1 = std::min(last[j] - base, 7);
      if (i0 <= i1)
      {
        mask |= (((2u << i1) - 1u) & ~((1u << i0) - 1u)) << (j * 8);
      }
    }
    return mask;
  }

  /// Bit k: edge k's crossings in fixed point in rowIntervals() (0 without SSE2).
  unsigned fixedPointEdges() const
  {
#ifdef SCENEVIS_OCCLUSION_SSE2
    return fixedEdges_;
#else
    return 0u;
#endif
  }

private:
  static int lowestBit(unsigned bits)
  {
    int j = 0;
    while (!((bits >> j) & 1u))
    {
      ++j;
    }
    return j;
  }

  /// Edge k on scanline y, over the columns [x0, x1]: the first column inside (x1 + 1: none)
  /// for an edge inside above its crossing or a horizontal one, the last (x0 - 1: none) for one
  /// inside below it.
  int edgeBound(int k, int y, int x0, int x1) const
  {
    const EdgeTest& e = edges_[k];
    const double yc = y + 0.5;
    auto inside = [&e, yc](int i) { return e.inside(i + 0.5, yc); };
    if (side_[k] == 0)
    {
      return inside(x0) ? x0 : x1 + 1;
    }
    // The crossing, in columns: v = threshold at x = px + (dx (y - py) - sign threshold) / dy,
    // the centre of column x - 1/2.
    const double crossing =
      (e.px - 0.5) + (e.dx * (yc - e.py) - signedThreshold_[k]) * inverseDy_[k];
    if (side_[k] > 0)
    {
      return firstInside(inside, x0, x1, crossing, delta_[k]);
    }
    // Inside below the crossing: with the columns negated, above it.
    auto mirrored = [&inside](int j) { return inside(-j); };
    return -firstInside(mirrored, -x1, -x0, -crossing, delta_[k]);
  }

  /// The smallest f in [lo, hi + 1] with inside(i) for every i in [f, hi], for a test that is
  /// monotone (false, then true) over [lo, hi] and true for columns more than @p delta above
  /// @p crossing, false for those more than @p delta below.
  template <class Inside>
  static int firstInside(const Inside& inside, int lo, int hi, double crossing, double delta)
  {
    // Clamped first (a crossing beyond the columns by more than 1 decides them all; NaN comes
    // with delta = 1: evaluated); floor by truncation, or one off, which the test of frac
    // (then outside [0, 1)) sends to the evaluation.
    const double t = std::min(hi + 1.5, std::max(lo - 1.5, crossing));
    const int below = static_cast<int>(t + 1048576.0) - 1048576;
    const double frac = t - below;
    const int c = std::min(hi + 1, std::max(lo, below + 1));
    if (frac > delta && frac < 1.0 - delta)
    {
      return c; // columns below + 1 and below are farther than delta from the crossing
    }
    int a, b; // f in [a, b]; b = hi + 1 or inside(b)
    if (c > hi || inside(c))
    {
      if (c == lo || !inside(c - 1))
      {
        return c;
      }
      a = lo;
      b = c - 1;
    }
    else
    {
      if (c == hi || inside(c + 1))
      {
        return c + 1;
      }
      a = c + 2;
      b = hi + 1;
    }
    while (a < b)
    {
      const int m = a + (b - a) / 2;
      if (inside(m))
      {
        b = m;
      }
      else
      {
        a = m + 1;
      }
    }
    return a;
  }

  const EdgeTest (&edges_)[3];
  int side_[3];
  double inverseDy_[3];
  double signedThreshold_[3];
  double delta_[3];
#ifdef SCENEVIS_OCCLUSION_SSE2
  /// Per edge, for rowIntervals(): the crossing a + b y (both lanes alike), the clamp (high
  /// with the shift), delta and 1 - delta.
  struct Scan
  {
    __m128d a, b, low, high, delta, upper;
  };
  Scan scan_[3];
  /// Per edge where it fits, the crossing in fixed point (see the constructor): a, b, the
  /// offsets of scanlines 0 .. 3 from the first, near + 1 and 2^31 - 2 near - 1.
  struct Fixed
  {
    std::int64_t a, b;
    __m128i step01, step23, nearUnits, farUnits;
  };
  Fixed fixed_[3];
  __m128i above_[3]; ///< all ones where the edge bounds the first column (side >= 0)
  unsigned fixedEdges_ = 0;                   ///< bit k: edge k in fixed point
  static constexpr double kShift = 1048576.0; // 2^20
#endif
};

} // namespace occlusion
} // namespace scenevis

#pragma once
// Module-private: the first decisions of MaskedDepthBuffer::drawTriangles about a triangle whose
// three vertices are in front of the near plane (OcclusionBuffer.cpp), before its depth test
// against the tiles and its set-up: does it cover any pixel centre of the viewport, and does
// OpenGL draw its face.
//
// keepDrawable() takes these decisions for a batch of triangles at once and compacts the batch
// to the triangles that go on, in their order, without a branch that depends on a triangle
// (most triangles of a detailed mesh stop here: no centre, or zero area). With SSE2 a
// triangle's four span bounds are reduced in one integer register and its doubled area in one
// double register; elsewhere keepDrawableScalar() runs.
//
// Why the batch decides exactly as the scalar code (keepDrawableScalar(), the code it
// replaces; OcclusionFront tests compare both on random and degenerate triangles):
// - The span is integer min / max of the vertices' spans and a clamp to the viewport: the same
//   integers whatever instructions compute them. The lower bounds are negated on the way (the
//   spans lie in [-1, size], no overflow) so that one max serves all four lanes.
// - The doubled area is the same IEEE operations on the same operands in the same order
//   ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)), two products in one register:
//   bit for bit doubleArea() (the core and its tests are built with -ffp-contract=off: no FMA
//   fuses the products, whatever the target CPU; Core/CMakeLists.txt).
// - culled() itself then decides the face, from that area.
// - The facing recorded for drawTriangles' neighbour test (FrontVertices::facing) is facingOf()
//   that area, in both versions.

#include "scenevis/OcclusionBuffer.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define SCENEVIS_OCCLUSION_FRONT_SSE2 1
#endif

namespace scenevis
{
namespace occlusion
{

/// Twice the signed area of window-space triangle abc (positive: counter-clockwise).
inline double doubleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Whether OpenGL draws nothing of a window-space triangle of doubled signed area @p area2:
/// zero or non-finite area, or a culled face.
inline bool culled(double area2, FaceCulling culling)
{
  return !(std::abs(area2) > 0.0) || !std::isfinite(area2) ||
    (culling == FaceCulling::Back && area2 < 0.0) || (culling == FaceCulling::Front && area2 > 0.0);
}

/**
 * The pixel centres (i + 1/2, j + 1/2) on either side of window point (x, y): x0 = ceil(x - 1/2)
 * and x1 = floor(x - 1/2) (likewise y), clamped to [-1, size] (enough to clip a triangle's
 * span to the viewport). The span of a triangle's centres is then min x0 ... max x1 of its
 * vertices, in integers, with no rounding per triangle.
 */
inline CentreSpan centreSpan(double x, double y, int width, int height)
{
  // Clamped, the values fit an int: floor and ceil from the truncation (cheaper than std::floor
  // and std::ceil without SSE4.1).
  const double sx = std::min(std::max(x - 0.5, -2.0), width + 1.0);
  const double sy = std::min(std::max(y - 0.5, -2.0), height + 1.0);
  const int ix = static_cast<int>(sx), iy = static_cast<int>(sy);
  return { std::max(-1, ix + (sx > ix ? 1 : 0)), std::min(width, ix - (sx < ix ? 1 : 0)),
    std::max(-1, iy + (sy > iy ? 1 : 0)), std::min(height, iy - (sy < iy ? 1 : 0)) };
}

/// The centres of a width x height viewport that a triangle with vertices' spans @p a, @p b,
/// @p c may cover (empty: x0 > x1 or y0 > y1).
inline CentreSpan triangleSpan(
  const CentreSpan& a, const CentreSpan& b, const CentreSpan& c, int width, int height)
{
  // Pairwise: the initializer-list overloads cost four times the instructions here.
  return { std::max(0, std::min(std::min(a.x0, b.x0), c.x0)),
    std::min(width - 1, std::max(std::max(a.x1, b.x1), c.x1)),
    std::max(0, std::min(std::min(a.y0, b.y0), c.y0)),
    std::min(height - 1, std::max(std::max(a.y1, b.y1), c.y1)) };
}

/// Triangles per batch of drawTriangles' front end (TriangleClusters' runs are 32 long too).
constexpr std::size_t kFrontBatch = 32;

/// A triangle on its way through the front end (see keepDrawable()).
struct FrontEntry
{
  std::size_t triangle; ///< index of the triangle (its vertices: indices[3 triangle ...])
  bool front;           ///< all three vertices in front of the near plane (else it is clipped)
  CentreSpan span;      ///< front: the centres it may cover (set by keepDrawable)
  double area2;         ///< front: its doubled signed window area (set by keepDrawable)
};

/// What keepDrawable() reads per vertex (valid for the vertices of front triangles).
struct FrontVertices
{
  const std::uint32_t* indices; ///< 3 per triangle
  const glm::dvec3* window;     ///< window coordinates per vertex
  const CentreSpan* centres;    ///< centreSpan() of each vertex
  int width, height;            ///< viewport
  FaceCulling culling;
  /// If set, facing[triangle] of every front triangle of the batch, kept or not, is set to
  /// facingOf() its doubled area (what drawTriangles' neighbour test would compute for it).
  TriangleFacing* facing = nullptr;
};

/// The facing of a triangle of doubled signed area @p area2 (NaN: None).
inline TriangleFacing facingOf(double area2)
{
  return static_cast<TriangleFacing>((area2 > 0.0 ? 1 : 0) - (area2 < 0.0 ? 1 : 0));
}

/// keepDrawable() one triangle at a time with triangleSpan(), doubleArea() and culled(): the
/// reference (and the path without SSE2).
inline std::size_t keepDrawableScalar(
  FrontEntry* entries, std::size_t count, const FrontVertices& v)
{
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    FrontEntry e = entries[i];
    bool keep = true;
    if (e.front)
    {
      const std::uint32_t* tri = v.indices + 3 * e.triangle;
      e.span =
        triangleSpan(v.centres[tri[0]], v.centres[tri[1]], v.centres[tri[2]], v.width, v.height);
      e.area2 = doubleArea(v.window[tri[0]], v.window[tri[1]], v.window[tri[2]]);
      keep = e.span.x0 <= e.span.x1 && e.span.y0 <= e.span.y1 && !culled(e.area2, v.culling);
      if (v.facing)
      {
        v.facing[e.triangle] = facingOf(e.area2);
      }
    }
    entries[kept] = e;
    kept += keep ? 1 : 0;
  }
  return kept;
}

#ifdef SCENEVIS_OCCLUSION_FRONT_SSE2
namespace detail
{
/// Lane-wise max of signed 32-bit integers (SSE2 has no pmaxsd).
inline __m128i max32(__m128i a, __m128i b)
{
  const __m128i greater = _mm_cmpgt_epi32(a, b);
  return _mm_or_si128(_mm_and_si128(greater, a), _mm_andnot_si128(greater, b));
}

/// Lane-wise min of signed 32-bit integers.
inline __m128i min32(__m128i a, __m128i b)
{
  const __m128i greater = _mm_cmpgt_epi32(a, b);
  return _mm_or_si128(_mm_and_si128(greater, b), _mm_andnot_si128(greater, a));
}

/// The lanes of @p negate (all ones) negated: (v ^ m) - m.
inline __m128i negateLanes(__m128i v, __m128i negate)
{
  return _mm_sub_epi32(_mm_xor_si128(v, negate), negate);
}

inline __m128i loadSpan(const CentreSpan& s)
{
  static_assert(sizeof(CentreSpan) == 16, "four ints");
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(&s));
}

/// Window x and y of a vertex in one register.
inline __m128d loadXY(const glm::dvec3& p)
{
  return _mm_loadu_pd(&p.x);
}
} // namespace detail
#endif

/**
 * The front-end decisions for @p count triangles (see the file comment): keeps, in their
 * order, the triangles that are not front (clipped ones: decided later) and the front ones
 * whose span is not empty and whose face OpenGL draws, with their span and doubled area; the
 * others are dropped. Returns how many are kept (entries[0, kept)).
 */
inline std::size_t keepDrawable(FrontEntry* entries, std::size_t count, const FrontVertices& v)
{
#ifdef SCENEVIS_OCCLUSION_FRONT_SSE2
  using namespace detail;
  // Lanes x0 x1 y0 y1; the lower bounds negated so that the triangle's span is a max of three.
  const __m128i lower = _mm_set_epi32(0, -1, 0, -1);
  const __m128i limit = _mm_set_epi32(v.height - 1, 0, v.width - 1, 0); // negated for x0, y0
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    FrontEntry e = entries[i];
    // For a clipped triangle the vertices' window data are stale: computed, then not used.
    const std::uint32_t* tri = v.indices + 3 * e.triangle;
    const __m128i a = negateLanes(loadSpan(v.centres[tri[0]]), lower);
    const __m128i b = negateLanes(loadSpan(v.centres[tri[1]]), lower);
    const __m128i c = negateLanes(loadSpan(v.centres[tri[2]]), lower);
    const __m128i span = negateLanes(min32(max32(max32(a, b), c), limit), lower);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&e.span), span);
    // x0 > x1 or y0 > y1 (lanes 0 and 2 against lanes 1 and 3).
    const __m128i empty = _mm_cmpgt_epi32(span, _mm_shuffle_epi32(span, _MM_SHUFFLE(2, 3, 0, 1)));
    const int emptyBits = _mm_movemask_ps(_mm_castsi128_ps(empty)) & 5;

    const __m128d pa = loadXY(v.window[tri[0]]);
    const __m128d ab = _mm_sub_pd(loadXY(v.window[tri[1]]), pa); // (b.x - a.x, b.y - a.y)
    const __m128d ac = _mm_sub_pd(loadXY(v.window[tri[2]]), pa); // (c.x - a.x, c.y - a.y)
    const __m128d products = _mm_mul_pd(ab, _mm_shuffle_pd(ac, ac, 1));
    e.area2 = _mm_cvtsd_f64(_mm_sub_sd(products, _mm_unpackhi_pd(products, products)));

    if (v.facing && e.front)
    {
      v.facing[e.triangle] = facingOf(e.area2);
    }
    const bool keep = !e.front || (emptyBits == 0 && !culled(e.area2, v.culling));
    entries[kept] = e;
    kept += keep ? 1 : 0;
  }
  return kept;
#else
  return keepDrawableScalar(entries, count, v);
#endif
}

} // namespace occlusion
} // namespace scenevis

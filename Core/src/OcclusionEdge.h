#pragma once
// Module-private: the edge test of MaskedDepthBuffer's exact rasterizer (OcclusionBuffer.cpp;
// its scanline intervals are in OcclusionScanline.h), the depth bound of a triangle over a tile
// and the upward float rounding that both rasterizers share.

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
  // std::nextafter(f, +inf) where f is below value, without the library call or a branch (one
  // per tile update; rounding down or up is a coin toss): then f is neither +inf nor NaN, and
  // the next float up is one step of its bits away from zero when positive, towards zero when
  // negative (-inf gives the lowest finite float, as nextafter does), the smallest positive one
  // from +0 (-0 is never below value: a value that rounds to -0 is not positive).
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  const std::uint32_t below = static_cast<double>(f) < value ? 1u : 0u;
  bits += (bits >> 31) == 0u ? below : 0u - below;
  std::memcpy(&f, &bits, sizeof f);
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
  double gx; ///< d value / dx

  EdgeTest(
    const glm::dvec3& from, const glm::dvec3& to, double orientation, bool outline, double margin)
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
    gx = -sign * dy;
  }
  double value(double x, double y) const { return sign * (dx * (y - py) - dy * (x - px)); }
  /// Whether the centre (x, y) is inside: value > threshold, or = threshold with the tie.
  bool inside(double x, double y) const
  {
    const double v = value(x, y);
    return v > threshold || (v == threshold && includeTie);
  }
};

} // namespace occlusion
} // namespace scenevis

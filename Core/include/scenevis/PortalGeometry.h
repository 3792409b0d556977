#pragma once
/**
 * @file PortalGeometry.h
 * @brief Small polygon helpers shared by the portal graph, traversal and PVS (header-only).
 *
 * Planes are glm::dvec4 (n, d) with p on the inner side when dot(n, p) + d >= 0 (the convention
 * of Frustum.h).
 */

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace scenevis
{
namespace portals
{
namespace geometry
{

/// Newell's normal of a closed polygon: length = 2 * area for planar polygons.
inline glm::dvec3 newellOf(const glm::dvec3* pts, std::size_t count)
{
  glm::dvec3 n(0.0);
  for (std::size_t k = 0; k < count; ++k)
  {
    const glm::dvec3& a = pts[k];
    const glm::dvec3& b = pts[(k + 1) % count];
    n += glm::dvec3(
      (a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  return n;
}

inline glm::dvec3 newellOf(const std::vector<glm::dvec3>& polygon)
{
  return newellOf(polygon.data(), polygon.size());
}

/// An orthonormal basis (u, v) of the plane with unit normal @p n, with cross(u, v) = n.
inline void planeBasis(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v)
{
  const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  u = glm::normalize(glm::cross(a, n));
  v = glm::cross(n, u);
}

inline double planeDistance(const glm::dvec4& plane, const glm::dvec3& p)
{
  return glm::dot(glm::dvec3(plane), p) + plane.w;
}

/**
 * Whether @p p (assumed in the plane) lies in the convex polygon @p hull, counter-clockwise
 * around @p normal, or within @p tol of it.
 */
inline bool insideConvex(const std::vector<glm::dvec3>& hull, const glm::dvec3& normal,
  const glm::dvec3& p, double tol)
{
  for (std::size_t k = 0; k < hull.size(); ++k)
  {
    const glm::dvec3& a = hull[k];
    const glm::dvec3& b = hull[(k + 1) % hull.size()];
    const glm::dvec3 edge = b - a;
    const double len = glm::length(edge);
    if (len == 0.0)
    {
      continue;
    }
    // Inward edge normal in the plane: normal x edge.
    if (glm::dot(glm::cross(normal, edge) / len, p - a) < -tol)
    {
      return false;
    }
  }
  return true;
}

/// Distance from @p p to the segment [a, b].
inline double distanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b)
{
  const glm::dvec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

/// Euclidean distance from @p p to the convex planar polygon @p hull (ccw around unit @p normal).
inline double distanceToConvex(const std::vector<glm::dvec3>& hull, const glm::dvec3& normal,
  const glm::dvec3& p)
{
  if (hull.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  const double h = glm::dot(normal, p - hull[0]);
  const glm::dvec3 q = p - h * normal;
  if (insideConvex(hull, normal, q, 0.0))
  {
    return std::abs(h);
  }
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < hull.size(); ++k)
  {
    d = std::min(d, distanceToSegment(p, hull[k], hull[(k + 1) % hull.size()]));
  }
  return d;
}

/**
 * Sutherland-Hodgman: clip the polygon @p in against the half-space dot(n, p) + d >= -slack,
 * writing the result to @p out (which must not alias @p in). A convex input stays convex.
 */
inline void clipPolygon(const glm::dvec3* in, std::size_t n, const glm::dvec4& plane, double slack,
  std::vector<glm::dvec3>& out)
{
  out.clear();
  if (n == 0)
  {
    return;
  }
  const glm::dvec3* prev = &in[n - 1];
  double dPrev = planeDistance(plane, *prev) + slack;
  for (std::size_t k = 0; k < n; ++k)
  {
    const glm::dvec3& cur = in[k];
    const double dCur = planeDistance(plane, cur) + slack;
    if ((dCur >= 0.0) != (dPrev >= 0.0))
    {
      const double t = dPrev / (dPrev - dCur);
      out.push_back(*prev + t * (cur - *prev));
    }
    if (dCur >= 0.0)
    {
      out.push_back(cur);
    }
    prev = &cur;
    dPrev = dCur;
  }
}

inline void clipPolygon(const std::vector<glm::dvec3>& in, const glm::dvec4& plane, double slack,
  std::vector<glm::dvec3>& out)
{
  clipPolygon(in.data(), in.size(), plane, slack, out);
}

/// Whether clipPolygon() would return the polygon unchanged: every vertex kept by @p plane.
inline bool allKept(const glm::dvec3* in, std::size_t n, const glm::dvec4& plane, double slack)
{
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!(planeDistance(plane, in[k]) + slack >= 0.0))
    {
      return false;
    }
  }
  return true;
}

} // namespace geometry
} // namespace portals
} // namespace scenevis

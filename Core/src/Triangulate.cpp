#include "Triangulate.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scenevis
{
namespace detail
{

/// Orthonormal in-plane basis (u, v) with u x v = n, so a polygon wound counter-clockwise around
/// its Newell normal stays counter-clockwise in (u, v).
void planeBasis(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v)
{
  const glm::dvec3 a = glm::abs(n);
  const glm::dvec3 axis = (a.x <= a.y && a.x <= a.z) ? glm::dvec3(1, 0, 0)
    : (a.y <= a.z)                                   ? glm::dvec3(0, 1, 0)
                                                     : glm::dvec3(0, 0, 1);
  u = glm::normalize(glm::cross(n, axis));
  v = glm::cross(n, u);
}

/**
 * Ear clipping of a simple polygon given counter-clockwise in 2D; appends triangles as triples of
 * indices into `p`. Degenerate or self-intersecting input does not stall it: when no proper ear
 * exists it drops a flat vertex, or as a last resort clips the most convex one.
 */
void earClip(const std::vector<glm::dvec2>& p, std::vector<std::uint32_t>& ring,
  std::vector<std::uint32_t>& triangles)
{
  const std::size_t m0 = p.size();
  ring.resize(m0);
  for (std::size_t i = 0; i < m0; ++i)
  {
    ring[i] = static_cast<std::uint32_t>(i);
  }
  auto orient = [&p](std::uint32_t a, std::uint32_t b, std::uint32_t c)
  { return cross2(p[b] - p[a], p[c] - p[a]); };
  // A vertex within rounding of an ear's edge blocks the ear: clipping it would leave that vertex
  // as a T-junction on the ear's long edge.
  double extent = 0.0;
  for (const glm::dvec2& q : p)
  {
    extent = std::max({ extent, std::abs(q.x - p[0].x), std::abs(q.y - p[0].y) });
  }
  const double onEdge = -1e-12 * extent * extent;
  std::size_t start = 0;
  while (ring.size() > 3)
  {
    const std::size_t m = ring.size();
    std::size_t clip = m;
    for (std::size_t k = 0; k < m && clip == m; ++k)
    {
      const std::size_t j = (start + k) % m;
      const std::uint32_t a = ring[(j + m - 1) % m];
      const std::uint32_t b = ring[j];
      const std::uint32_t c = ring[(j + 1) % m];
      if (orient(a, b, c) <= 0.0)
      {
        continue;
      }
      bool empty = true;
      for (std::uint32_t q : ring)
      {
        if (q == a || q == b || q == c || p[q] == p[a] || p[q] == p[b] || p[q] == p[c])
        {
          continue;
        }
        if (orient(a, b, q) >= onEdge && orient(b, c, q) >= onEdge && orient(c, a, q) >= onEdge)
        {
          empty = false;
          break;
        }
      }
      if (empty)
      {
        clip = j;
      }
    }
    bool emit = true;
    if (clip == m)
    {
      // No proper ear: numerically flat or self-intersecting input.
      double best = -std::numeric_limits<double>::infinity();
      double flattest = std::numeric_limits<double>::infinity();
      std::size_t flatIndex = 0;
      for (std::size_t j = 0; j < m; ++j)
      {
        const double o = orient(ring[(j + m - 1) % m], ring[j], ring[(j + 1) % m]);
        if (o > best)
        {
          best = o;
          clip = j;
        }
        if (std::abs(o) < flattest)
        {
          flattest = std::abs(o);
          flatIndex = j;
        }
      }
      if (best <= 0.0)
      {
        clip = flatIndex;
        emit = false;
      }
    }
    if (emit)
    {
      triangles.push_back(ring[(clip + m - 1) % m]);
      triangles.push_back(ring[clip]);
      triangles.push_back(ring[(clip + 1) % m]);
    }
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(clip));
    start = clip == 0 ? 0 : clip - 1;
  }
  if (orient(ring[0], ring[1], ring[2]) > 0.0)
  {
    triangles.insert(triangles.end(), ring.begin(), ring.end());
  }
}

} // namespace detail
} // namespace scenevis

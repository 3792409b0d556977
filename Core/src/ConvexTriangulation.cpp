// Triangles of convex polygons with collinear vertices on their sides (ConvexTriangulation.h).
#include "scenevis/ConvexTriangulation.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace scenevis
{
namespace
{
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
} // namespace

bool collinear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
  const glm::dvec3 u = b - a, v = c - a;
  const double w = glm::length(glm::cross(u, v));
  const double lu = glm::length(u), lv = glm::length(v);
  // Coordinates of magnitude m are off by up to m 2^-53 each (a point interpolated on an edge,
  // far from the origin): the cross product then by about that times |u| + |v|.
  double m = 0.0;
  for (int i = 0; i < 3; ++i)
  {
    m = std::max({ m, std::abs(a[i]), std::abs(b[i]), std::abs(c[i]) });
  }
  return w <= kCollinearTolerance * lu * lv + 16.0 * kEpsilon * m * (lu + lv);
}

std::size_t flatFanTriangles(const glm::dvec3* vertices, std::size_t n, std::size_t apex)
{
  std::size_t flat = 0;
  for (std::size_t k = 1; k + 1 < n; ++k)
  {
    flat += collinear(vertices[apex], vertices[(apex + k) % n], vertices[(apex + k + 1) % n]);
  }
  return flat;
}

std::size_t cleanestFanApex(const glm::dvec3* vertices, std::size_t n)
{
  std::size_t best = 0, fewest = flatFanTriangles(vertices, n, 0);
  for (std::size_t apex = 1; apex < n && fewest > 0; ++apex)
  {
    const std::size_t flat = flatFanTriangles(vertices, n, apex);
    if (flat < fewest)
    {
      best = apex;
      fewest = flat;
    }
  }
  return best;
}

namespace
{
/// Fan of ring[0..) from ring[0].
void fan(const std::vector<std::uint32_t>& ring, std::vector<std::uint32_t>& triangles)
{
  for (std::size_t k = 1; k + 1 < ring.size(); ++k)
  {
    triangles.insert(triangles.end(), { ring[0], ring[k], ring[k + 1] });
  }
}
} // namespace

void triangulateConvex(
  const glm::dvec3* vertices, std::size_t n, std::vector<std::uint32_t>& triangles)
{
  if (n < 3)
  {
    return;
  }
  if (flatFanTriangles(vertices, n, 0) == 0)
  {
    for (std::uint32_t k = 1; k + 1 < n; ++k)
    {
      triangles.insert(triangles.end(), { 0u, k, k + 1 });
    }
    return;
  }
  std::vector<std::uint32_t> ring(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    ring[k] = static_cast<std::uint32_t>(k);
  }
  // Ear clipping at corners. A corner b between a and c gives the triangle (a, b, c) area; after
  // it is clipped, a and c are neighbours, and only their own corner status can change. An ear is
  // taken only if three corners remain, so the last triangle has area too.
  const auto corner = [&](std::size_t i)
  {
    const std::size_t m = ring.size();
    return !collinear(
      vertices[ring[(i + m - 1) % m]], vertices[ring[i]], vertices[ring[(i + 1) % m]]);
  };
  std::vector<char> isCorner(n);
  std::size_t corners = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    isCorner[i] = corner(i);
    corners += static_cast<std::size_t>(isCorner[i]);
  }
  while (ring.size() > 3)
  {
    const std::size_t m = ring.size();
    std::size_t ear = m;
    for (std::size_t i = 0; i < m && ear == m; ++i)
    {
      if (!isCorner[i])
      {
        continue;
      }
      const std::size_t ia = (i + m - 1) % m, ic = (i + 1) % m;
      const glm::dvec3& a = vertices[ring[ia]];
      const glm::dvec3& c = vertices[ring[ic]];
      const bool aCorner = !collinear(vertices[ring[(ia + m - 1) % m]], a, c);
      const bool cCorner = !collinear(a, c, vertices[ring[(ic + 1) % m]]);
      const std::size_t left = corners - 1 - static_cast<std::size_t>(isCorner[ia]) -
        static_cast<std::size_t>(isCorner[ic]) + static_cast<std::size_t>(aCorner) +
        static_cast<std::size_t>(cCorner);
      if (left >= 3)
      {
        ear = i;
        triangles.insert(triangles.end(), { ring[ia], ring[i], ring[ic] });
        isCorner[ia] = aCorner;
        isCorner[ic] = cCorner;
        corners = left;
      }
    }
    if (ear == m)
    {
      break; // fewer than three corners: no area to keep
    }
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(ear));
    isCorner.erase(isCorner.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  fan(ring, triangles);
}

} // namespace scenevis

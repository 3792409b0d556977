#pragma once
// The geometric oracle of the generated-rooms tests: whether a straight segment meets an opaque
// polygon. Two points with nothing opaque between them see each other.
#include "scenevis/PolygonMesh.h"
#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalGraph.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace testing_support
{

/// Vertices of polygon @p i of @p mesh.
inline std::vector<glm::dvec3> polygonPoints(const PolygonMesh& mesh, std::size_t i)
{
  std::vector<glm::dvec3> polygon;
  for (std::uint32_t k = 0; k < mesh.polygonSize(i); ++k)
  {
    polygon.push_back(mesh.points[mesh.polygon(i)[k]]);
  }
  return polygon;
}

/// Whether the segment from @p a to @p b meets a polygon of @p mesh that is not see-through
/// (touching an edge or a vertex counts: an oracle then skips the segment). Polygon @p skip
/// (the one @p b lies on, if any) does not count.
inline bool blocked(const PolygonMesh& mesh, const std::vector<std::uint8_t>& seeThrough,
  const glm::dvec3& a, const glm::dvec3& b, std::size_t skip = static_cast<std::size_t>(-1))
{
  for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
  {
    if (i == skip || (i < seeThrough.size() && seeThrough[i]))
    {
      continue;
    }
    const std::vector<glm::dvec3> polygon = polygonPoints(mesh, i);
    const glm::dvec3 n = portals::geometry::newellOf(polygon);
    if (glm::length(n) == 0.0)
    {
      continue;
    }
    const glm::dvec3 unit = glm::normalize(n);
    const double da = glm::dot(unit, a - polygon[0]);
    const double db = glm::dot(unit, b - polygon[0]);
    if ((da > 1e-9 && db > 1e-9) || (da < -1e-9 && db < -1e-9))
    {
      continue;
    }
    const double t = std::abs(da - db) > 0.0 ? da / (da - db) : 0.0;
    const glm::dvec3 q = a + glm::clamp(t, 0.0, 1.0) * (b - a);
    if (portals::geometry::insideConvex(portals::planarConvexHull(polygon, unit), unit, q, 1e-6))
    {
      return true;
    }
  }
  return false;
}

} // namespace testing_support
} // namespace scenevis

#pragma once
// Test-only: an axis-aligned quad added to a PolygonMesh, the building block of the portal tests'
// boxes, rooms and walls.

#include "scenevis/PolygonMesh.h"

#include <glm/vec3.hpp>

#include <cstdint>

namespace scenevis
{
namespace portaltest
{

/// Adds the quad [u0, u1] x [v0, v1] in the plane coordinate[axis] == at (u, v: the next two
/// axes, cyclically), its normal along +axis (@p positive) or -axis.
inline void addAxisQuad(
  PolygonMesh& mesh, int axis, double at, bool positive, double u0, double u1, double v0, double v1)
{
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  std::uint32_t ids[4];
  for (int k = 0; k < 4; ++k)
  {
    glm::dvec3 p(0.0);
    p[axis] = at;
    p[u] = (k == 1 || k == 2) ? u1 : u0;
    p[v] = (k >= 2) ? v1 : v0;
    ids[positive ? k : 3 - k] = mesh.addPoint(p);
  }
  mesh.addPolygon(ids, 4);
}

} // namespace portaltest
} // namespace scenevis

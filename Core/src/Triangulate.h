#pragma once
// Internal to the core (not installed): planar-polygon triangulation shared by the BSP builder
// and the painter's sort, so both treat concave and non-planar input identically.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace scenevis
{
namespace detail
{

/// z component of the 2D cross product.
inline double cross2(const glm::dvec2& a, const glm::dvec2& b)
{
  return a.x * b.y - a.y * b.x;
}

/// Orthonormal in-plane basis (u, v) with u x v = n, so a polygon wound counter-clockwise around
/// its Newell normal stays counter-clockwise in (u, v).
void planeBasis(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v);

/**
 * Ear clipping of a simple polygon given counter-clockwise in 2D; appends triangles as triples of
 * indices into `p`. Degenerate or self-intersecting input does not stall it: when no proper ear
 * exists it drops a flat vertex, or as a last resort clips the most convex one.
 */
void earClip(const std::vector<glm::dvec2>& p, std::vector<std::uint32_t>& ring,
  std::vector<std::uint32_t>& triangles);

} // namespace detail
} // namespace scenevis

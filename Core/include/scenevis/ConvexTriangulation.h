#pragma once
/**
 * @file ConvexTriangulation.h
 * @brief Triangles of a convex polygon whose sides carry collinear vertices, none of them flat.
 *
 * Conforming BSP fragments (BuildConfig::conformingFragments) have their neighbours' split
 * points on their edges, so that no fragment edge passes through another fragment's vertex (a
 * T-junction, which OpenGL covers twice or not at all along the edge). A fan from a vertex that
 * lies on one of those straight runs makes flat triangles (three collinear vertices): they cover
 * nothing, and the next triangle of the fan spans the whole run with one edge, which brings the
 * T-junction back for the rasterizer. A fan from another vertex, or when none will do an ear
 * clipping that clips only corners, gives n - 2 triangles with area that share every one of the
 * polygon's edges (the sub-edges between the collinear vertices included).
 *
 * Collinear: |(b - a) x (c - a)| <= kCollinearTolerance |b - a| |c - a| (the sine of the angle
 * at a) plus the rounding of the coordinates (16 epsilon times their largest magnitude times
 * |b - a| + |c - a|), so a split point interpolated on its edge in double counts as on it, near
 * the origin or far from it.
 */

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{

/// Sine below which three points count as collinear.
constexpr double kCollinearTolerance = 1e-9;

/// Whether @p a, @p b and @p c are collinear (or two of them coincide).
bool collinear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

/**
 * The flat triangles of the fan from vertex @p apex (0 <= apex < n) of the polygon with vertex
 * positions @p vertices[0..n): triangles (apex, apex + k, apex + k + 1), k = 1 .. n - 2 (indices
 * modulo n), with three collinear vertices.
 */
std::size_t flatFanTriangles(const glm::dvec3* vertices, std::size_t n, std::size_t apex);

/**
 * The vertex whose fan has the fewest flat triangles; the first of them, so 0 when the fan from
 * vertex 0 has none.
 */
std::size_t cleanestFanApex(const glm::dvec3* vertices, std::size_t n);

/**
 * Appends n - 2 triangles of the convex polygon with vertex positions @p vertices[0..n) to
 * @p triangles, as triples of vertex indices (0 .. n - 1) in the polygon's winding: the fan from
 * vertex 0 when it has no flat triangle, else ears clipped at corners (vertices not collinear
 * with their neighbours) while three corners remain, which leaves no flat triangle. Only a
 * polygon with fewer than three corners (no area) can still get flat ones. Nothing is appended
 * for n < 3.
 */
void triangulateConvex(
  const glm::dvec3* vertices, std::size_t n, std::vector<std::uint32_t>& triangles);

} // namespace scenevis

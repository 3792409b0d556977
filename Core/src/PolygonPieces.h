#pragma once
// Internal to the core (not installed): the clean-up every sorter applies to its input polygon
// soup, shared by the BSP builder and the painter's sort so both drop, keep and split exactly the
// same polygons.

#include "scenevis/PolygonMesh.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace detail
{

/// Planar convex pieces of a polygon soup, structure of arrays, one entry per piece.
struct PolygonPieces
{
  std::vector<glm::dvec4> plane;     ///< (unit normal, offset) in the caller's local coordinates.
  std::vector<std::uint32_t> source; ///< Input polygon the piece comes from.
  std::vector<std::uint32_t> count;  ///< Vertices of the piece.
  std::vector<std::uint32_t> verts;  ///< Point ids of all pieces, consecutive, in piece order.
};

/// What PolygonPieces dropped or changed, per input polygon.
struct PieceCounts
{
  std::size_t invalid = 0;      ///< Dropped: a NaN/Inf point or an out-of-range point id.
  std::size_t degenerate = 0;   ///< Dropped: < 3 distinct points, or thinner than the tolerance.
  std::size_t triangulated = 0; ///< Concave, non-planar or star-shaped: ear-clipped.
};

/**
 * Splits every polygon of @p mesh into planar convex pieces, appended to @p out:
 * - a polygon with an out-of-range point id or a non-finite point is dropped (invalid);
 * - repeated consecutive vertices (and a closing repeat of the first) are removed; fewer than 3
 *   left, or a polygon whose twice-area |Newell normal| is at most @p tolerance times its longest
 *   edge (a sliver with no meaningful plane), is dropped (degenerate);
 * - a polygon that is planar within @p tolerance and convex (left turns everywhere and one full
 *   turn, so star shapes are not) is kept whole; any other is ear-clipped into triangles, and
 *   each triangle is kept unless it is itself a sliver.
 * @p local holds the mesh's points moved near the origin (the caller's local frame; planes are
 * in it), @p tolerance is an absolute distance in that frame.
 */
void splitIntoPieces(const PolygonMesh& mesh, const std::vector<glm::dvec3>& local,
  double tolerance, PolygonPieces& out, PieceCounts& counts);

} // namespace detail
} // namespace scenevis

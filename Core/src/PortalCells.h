#pragma once
// Internal to the core (not installed): the cells of a BSP and the faces between them (the
// portalization of Quake-style level compilers), for the portal generator (PortalGeneration.h).
// All coordinates are local: relative to bsp::Tree::origin, like the tree's planes.

#include "scenevis/BspTree.h"
#include "scenevis/PolygonMesh.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace scenevis
{
namespace detail
{

/// Cell id of the empty child slot `side` (0 front, 1 back) of node `node`.
inline std::uint32_t cellOf(std::uint32_t node, int side)
{
  return 2 * node + static_cast<std::uint32_t>(side);
}

/// A uniform grid over boxes (about one box per grid cell, at most 256 per axis): the boxes near
/// a box or point without looking at all of them.
class BoxGrid
{
public:
  BoxGrid(const std::vector<Box>& boxes, double tolerance);
  /// Ids of the boxes whose grid cells @p box touches, each once, ascending (a superset of the
  /// boxes that overlap it).
  const std::vector<std::uint32_t>& near(const Box& box);

private:
  void range(const Box& b, int lo[3], int hi[3]) const;
  Box All;
  double Tolerance;
  int Dims[3] = { 1, 1, 1 };
  std::vector<std::vector<std::uint32_t>> Cells;
  std::vector<std::uint32_t> Seen, Near;
  std::uint32_t Query = 0;
};

/// A convex piece of a node's plane between one cell in front and one behind.
struct CellFace
{
  std::uint32_t node = bsp::kNone;
  std::uint32_t front = bsp::kNone;
  std::uint32_t back = bsp::kNone;
  std::vector<glm::dvec3> polygon; ///< Counter-clockwise around the node's normal.
};

/// What remains of a face once the node's fragments are subtracted (convex).
struct OpenPiece
{
  std::uint32_t face = 0;
  std::vector<glm::dvec3> polygon; ///< Counter-clockwise around the node's normal.
};

struct CellComplex
{
  std::size_t cellCount = 0; ///< 2 * nodes; slots with a child are not cells.
  std::vector<CellFace> faces;
  std::vector<OpenPiece> open;
  std::vector<std::uint8_t> isCell; ///< Per cell id: an empty child slot.
  /// Per cell: area of fragments on its faces that face into it, and that turn their back on it.
  std::vector<double> facedArea, backedArea;
  /// Which cell each covered part of a fragment faces into (the rooms of the input polygons).
  struct Coverage
  {
    std::uint32_t source; ///< bsp::Fragment::source
    std::uint32_t cell;   ///< The cell it faces into.
    std::uint32_t behind; ///< The cell on its back.
    double area;
  };
  std::vector<Coverage> coverage;
  std::vector<std::uint8_t> touchesBox;
  std::vector<double> volume;
  std::vector<glm::dvec3> centroid; ///< Area-weighted mean of its faces' centroids (inside it).
  std::vector<double> boundaryArea;
  std::vector<std::vector<glm::dvec3>> vertices; ///< Per cell: the vertices of its faces.
};

/**
 * Cells, faces and open pieces of @p tree inside the box @p box (local coordinates, which must
 * contain every fragment with room to spare). Pieces thinner than the tree's tolerance are
 * dropped (a crack that thin is closed).
 */
CellComplex buildCellComplex(const bsp::Tree& tree, const Box& box);

/**
 * Splits cells that straddle an opening. A BSP cuts along a wall's plane only inside the region
 * of the node that holds the wall, so a cell may reach from a room through a doorway into the
 * next room when the wall's node lies elsewhere. Each cell that a polygon touches (within
 * tolerance, e.g. along the lintel of a door) and whose interior that polygon's plane crosses is
 * split by that plane (a new node without fragments). Returns the number of splits; call again
 * on the new complex until it returns 0.
 */
std::size_t splitCellsAtOpenings(bsp::Tree& tree, const CellComplex& cx);

/// The cell containing local point @p p (on a plane: the front side).
std::uint32_t locateCell(const bsp::Tree& tree, const glm::dvec3& p);

/// Whether the local segment [a, b] crosses a fragment of @p tree.
bool segmentHitsFragment(const bsp::Tree& tree, const glm::dvec3& a, const glm::dvec3& b);

/// Vertices of fragment @p f in local coordinates.
std::vector<glm::dvec3> fragmentPolygon(const bsp::Tree& tree, const bsp::Fragment& f);

/// Whether local point @p p, in the plane of the convex polygon @p poly (either winding), lies
/// inside it (strictly: more than @p tol from every edge line).
bool insideConvexPolygon(const std::vector<glm::dvec3>& poly, const glm::dvec3& p, double tol);

/// Area of a planar polygon.
double polygonArea(const std::vector<glm::dvec3>& poly);

} // namespace detail
} // namespace scenevis

#pragma once
/**
 * @file BspTree.h
 * @brief Polygon-aligned BSP tree (Fuchs, Kedem, Naylor 1980) for exact visibility order.
 *
 * Data only: the tree a builder (BspBuilder.h) makes and traversals (BspTraversal.h) walk.
 *
 * The tree is built once in world space, independent of the viewer. Every node holds a partition
 * plane and the fragments lying on it (coplanar, either facing); fragments that straddle a plane
 * are split, so for any eye the order "far subtree, own fragments, near subtree" is exact.
 *
 * Precision: all geometry is double. Planes are stored relative to `Tree::origin` (the centre of the
 * input bounds), so a model placed at 1e7 with 1e-2 features classifies as well as one at the
 * origin. A point is "on" a plane when its distance is within `Tree::tolerance`
 * (BuildConfig::relativeTolerance times the bounds diagonal); classification is a pure function of
 * (point, plane), so a vertex shared by neighbouring polygons always gets the same verdict, and a
 * split edge shared by two polygons yields one shared split point (no cracks, no T-junctions).
 *
 * Point ids: ids below `inputPointCount` are the input mesh's own points (unchanged); split points
 * follow in creation order and are described by `splitPoints`, so a caller can interpolate any
 * per-point attribute: attribute(id) = lerp(attribute(a), attribute(b), t), where a and b are
 * always smaller than id.
 */

#include "scenevis/PolygonMesh.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace bsp
{

/// No node / no child.
constexpr std::uint32_t kNone = 0xffffffffu;

/// A convex planar polygon: the piece of input polygon `source` that ended up in one node.
struct Fragment
{
  std::uint32_t source; ///< Input polygon id.
  std::uint32_t first;  ///< First entry in Tree::fragmentVertices.
  std::uint32_t count;  ///< Number of vertices (>= 3).
};

/// A point created by a split: position = lerp(point(a), point(b), t), with a, b < this point's id.
struct SplitPoint
{
  std::uint32_t a;
  std::uint32_t b;
  double t;
};

/**
 * One partition. `plane` = (n, d) with |n| = 1, relative to Tree::origin: a point p is in front
 * when dot(n, p - origin) + d > tolerance. Fragments [firstFragment, firstFragment+fragmentCount)
 * lie on the plane. A node made by a "free" plane (not a polygon's, used by the scored heuristic to
 * keep convex meshes from turning into chains) owns no fragments.
 */
struct Node
{
  glm::dvec4 plane;
  std::uint32_t front = kNone;
  std::uint32_t back = kNone;
  std::uint32_t firstFragment = 0;
  std::uint32_t fragmentCount = 0;
};

/// Numbers a test can assert on (no timing needed) plus the build time for reports.
struct BuildStatistics
{
  std::size_t inputPolygons = 0;
  std::size_t degeneratePolygons = 0; ///< Removed: < 3 distinct points or zero area.
  std::size_t invalidPolygons = 0;    ///< Removed: a NaN/Inf point or an out-of-range point id.
  std::size_t triangulatedPolygons = 0; ///< Concave or non-planar inputs split into triangles.
  std::size_t nodes = 0;
  std::size_t freePlaneNodes = 0;
  std::size_t depth = 0;      ///< Longest root-to-leaf path, in nodes.
  std::size_t fragments = 0;  ///< Output fragments (== Tree::fragments.size()).
  std::size_t splits = 0;     ///< Polygon splits performed (each adds one fragment).
  double tolerance = 0.0;     ///< Absolute plane tolerance used.
  double buildSeconds = 0.0;
  std::size_t memoryBytes = 0; ///< Heap bytes held by the Tree.
};

/// The built tree. Plain data: copyable, movable, no back-references to the input mesh.
struct Tree
{
  glm::dvec3 origin{ 0.0 };
  double tolerance = 0.0;
  std::uint32_t root = kNone;
  std::vector<Node> nodes;
  std::vector<Fragment> fragments;      ///< Grouped by node (see Node::firstFragment).
  std::vector<std::uint32_t> fragmentVertices;
  std::vector<glm::dvec3> points;       ///< Input points (same ids), then split points.
  std::size_t inputPointCount = 0;
  std::vector<SplitPoint> splitPoints;  ///< splitPoints[i] describes point inputPointCount + i.
  BuildStatistics statistics;

  bool empty() const { return root == kNone; }
};

} // namespace bsp
} // namespace scenevis

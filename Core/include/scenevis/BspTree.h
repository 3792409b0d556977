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
 * Precision: all geometry is double. Planes are stored relative to `Tree::origin` (the centre of
 * the input bounds), so a model placed at 1e7 with 1e-2 features classifies as well as one at the
 * origin. A point is "on" a plane when its distance is within `Tree::tolerance`
 * (BuildConfig::relativeTolerance times the bounds diagonal); classification is a pure function of
 * (point, plane), so a vertex shared by neighbouring polygons always gets the same verdict, and a
 * split edge shared by two polygons yields one shared split point (no cracks, no T-junctions).
 *
 * Ordered leaves (optional, BuildConfig::orderedLeafSize): a short list that none of the planes
 * the builder tries partitions without a split can be kept unsplit in an OrderedLeaf instead of a
 * subtree. A child reference
 * (Node::front / back, Tree::root) with kLeafBit set names `leaves[ref & ~kLeafBit]`, not a node.
 * The leaf stores, for every pair of its polygons that are not coplanar, one or two separating
 * planes; a traversal evaluates them for the eye and sorts the leaf's polygons topologically
 * (BspTraversal.h). Polygons of 3 or more can overlap cyclically for some eyes: the leaf then falls
 * back, for that eye only, to `fallback`, the ordinary split subtree of the same polygons (stored
 * too). So a tree with leaves stores more fragments than it draws: an order lists each leaf's
 * unsplit fragments or its fallback's, never both, and is not a permutation of all fragment ids.
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

/// Child references with this bit set name an OrderedLeaf (see the file comment).
constexpr std::uint32_t kLeafBit = 0x40000000u;

inline bool isLeaf(std::uint32_t reference)
{
  return reference != kNone && (reference & kLeafBit) != 0;
}

/// Separating planes stored per LeafPair, at most.
constexpr std::uint32_t kPairPlanes = 2;

/**
 * One pair of an OrderedLeaf's polygons with a view-dependent order, and up to kPairPlanes planes
 * that separate them (unused entries kNoPlane). Each plane index refers to the leaf's planes; its
 * top bit (kFlipPlane) flips the verdict. A plane's verdict is "first is drawn before second
 * (back to front)" when the eye is in front of the plane (side value >= 0, as in the tree's
 * nodes), flipped when kFlipPlane is set: `first` lies behind the plane and `second` in front of
 * it (each within Tree::tolerance), so from the front `second` can only be nearer. When two
 * planes' verdicts differ for an eye, a plane through the eye separates the pair (the separating
 * planes form a convex set), no ray from it passes through both polygons, and the pair imposes
 * no order. The builder picks the polygons' own planes, then planes through an edge of one and a
 * vertex of the other, as different in direction as it finds, so that this happens often.
 */
struct LeafPair
{
  std::uint8_t first;
  std::uint8_t second;
  std::uint16_t planes[kPairPlanes];
};

constexpr std::uint16_t kFlipPlane = 0x8000u;
constexpr std::uint16_t kNoPlane = 0xffffu;

/// At most this many polygons in an OrderedLeaf (LeafPair's indices are 8 bits; a traversal
/// sorts a leaf on precedence rows of 1, 2 or 4 64-bit words, as few as its size needs).
constexpr std::uint32_t kMaxLeafPolygons = 256;

/// At most this many planes in an OrderedLeaf (plane indices are 15 bits, and 0x7fff with
/// kFlipPlane would read as kNoPlane). A leaf of more than 181 polygons can have more pairs than
/// that allows for; its pairs beyond it keep their own planes only, or if they have none usable,
/// the list is split.
constexpr std::uint32_t kMaxLeafPlanes = 0x7fff;

/**
 * Unsplit convex polygons ordered per view (see the file comment). Fragments [firstFragment,
 * firstFragment + fragmentCount) are its polygons (leaf index k = fragment firstFragment + k);
 * planes [firstPlane, firstPlane + planeCount) of Tree::leafPlanes: the polygons' own planes
 * first (plane k is fragment k's), then the other separating planes of the pairs (see LeafPair);
 * pairs [firstPair, firstPair + pairCount) of Tree::leafPairs. Coplanar pairs are not stored.
 */
struct OrderedLeaf
{
  std::uint32_t firstFragment = 0;
  std::uint32_t fragmentCount = 0;
  std::uint32_t firstPlane = 0;
  std::uint32_t planeCount = 0;
  std::uint32_t firstPair = 0;
  std::uint32_t pairCount = 0;
  /// Root node of the split subtree of the same polygons, for eyes that see a cycle; kNone when
  /// no cycle is possible (the stored pairs form a forest).
  std::uint32_t fallback = kNone;
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
  /// Split points added to the edges of fragments beside a split
  /// (BuildConfig::conformingFragments).
  std::size_t conformingVertices = 0;
  std::size_t orderedLeaves = 0; ///< Tree::leaves.size().
  std::size_t leafFragments = 0; ///< Unsplit fragments held by ordered leaves.
  std::size_t leafPairs = 0;     ///< Tree::leafPairs.size().
  /// Fragments an order emits when every leaf is drawn unsplit (no view sees a cycle): fragments
  /// minus those of the leaves' fallback subtrees.
  std::size_t fragmentsWithoutFallbacks = 0;
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
  std::vector<OrderedLeaf> leaves;      ///< Empty unless built with BuildConfig::orderedLeafSize.
  std::vector<glm::dvec4> leafPlanes;   ///< Relative to origin, like Node::plane.
  std::vector<LeafPair> leafPairs;
  BuildStatistics statistics;

  bool empty() const { return root == kNone; }
};

} // namespace bsp
} // namespace scenevis

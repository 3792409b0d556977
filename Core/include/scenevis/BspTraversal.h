#pragma once
/**
 * @file BspTraversal.h
 * @brief Visibility order of a bsp::Tree's fragments for a view: full walk and incremental update.
 *
 * At every node the viewer's side is the sign of dot(plane, eye) (View.h). Back-to-front emits the
 * subtree on the far side, then the node's own fragments, then the near subtree; front-to-back is
 * the reverse. An eye exactly on a plane (dot == 0) counts as in front: any order of the two sides
 * is valid there, since they project to disjoint parts of the image. Own fragments of one node are
 * coplanar and emitted in ascending fragment id (deterministic). Walks are iterative.
 *
 * Ordered leaves (BspTree.h): each stored pair's planes are evaluated for the eye (the same side
 * rule) and give a precedence unless two planes disagree (then no ray passes through both); the
 * leaf's polygons are emitted in layers of a topological sort (Kahn's, on bit-set rows of 64, 128
 * or 256 bits, the fewest the leaf fits), each layer in ascending leaf index. When the sort
 * stalls, it walks back to a cycle and checks each of its precedences exactly (is there a plane
 * through the eye that separates the pair? the pair's separating planes through an edge of one
 * and a vertex of the other decide it), drops those no ray realises and goes on; a cycle of
 * realised precedences makes the leaf's fallback subtree walked instead, for this eye. So an
 * order of a tree with leaves lists the fragments drawn for that view: fewer than
 * Tree::fragments.size().
 */

#include "scenevis/BspTree.h"
#include "scenevis/View.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace bsp
{

enum class Direction
{
  BackToFront,
  FrontToBack
};

/// What one order() call did with the tree's ordered leaves.
struct OrderStatistics
{
  std::size_t leavesSorted = 0;     ///< Leaves emitted unsplit.
  std::size_t leavesFallenBack = 0; ///< Leaves whose pairs formed a cycle for this eye.
};

/**
 * Writes the fragment ids to draw, in order, into `order`: a permutation of all fragment ids for a
 * tree without ordered leaves; with leaves, each leaf's unsplit fragments or its fallback's (see
 * the file comment). `statistics`, when given, receives the leaves' counts.
 */
void order(const Tree& tree, const View& view, Direction direction,
  std::vector<std::uint32_t>& order, OrderStatistics* statistics = nullptr);

/**
 * Back-to-front order of one ordered leaf for `eye` (relative to the tree's origin) as leaf
 * indices 0 .. fragmentCount-1, written to `out` (fragmentCount entries). Returns false, with
 * `out` unspecified, when the leaf's precedences form a cycle for this eye.
 */
bool orderLeaf(
  const Tree& tree, const OrderedLeaf& leaf, const glm::dvec4& eye, std::uint32_t* out);

/**
 * Keeps an order up to date as the viewer moves, touching only what changed.
 *
 * Each subtree owns a contiguous range of the order; a node's range is laid out as
 * [first child][own fragments][second child]. When the viewer crosses a node's plane only that
 * node's two child blocks swap places (inner order unchanged). To find crossed planes without
 * visiting every node, each subtree keeps a safe ball in normalised homogeneous eye space: the eye
 * it was last checked at and the distance to the nearest plane within it. A new eye inside the ball
 * cannot have crossed any plane of that subtree, which is skipped whole. Small camera steps
 * therefore visit only the few subtrees whose planes pass close to the eye. Runs of single-child
 * nodes (the leaf chains on convex patches) share one ball and are re-checked as one block.
 *
 * The result after update(view) is identical to order(tree, view, direction, ...).
 */
class IncrementalOrder
{
public:
  struct UpdateStatistics
  {
    std::size_t nodesVisited = 0;
    std::size_t nodesFlipped = 0;
    std::size_t fragmentsMoved = 0;
  };

  /// `tree` must outlive this object and must not change. Throws std::invalid_argument for a
  /// tree with ordered leaves (not supported yet).
  IncrementalOrder(const Tree& tree, Direction direction);

  /// Brings order() up to date for `view`. The first call does a full walk.
  const UpdateStatistics& update(const View& view);

  const std::vector<std::uint32_t>& order() const { return Order; }
  const UpdateStatistics& lastUpdate() const { return Last; }
  /// Heap bytes held (excluding the tree).
  std::size_t memoryBytes() const;

private:
  // Implementation detail; see BspTraversal.cpp. The tree is regrouped into "units": a unit is a
  // run of nodes n1..nk where n1..n(k-1) each have exactly one child, the next node (the leaf
  // chains a polygon-aligned BSP grows on convex patches), and the tail nk has any children, each
  // the first node of another unit. A unit is tested as a block: one safe ball for its subtree,
  // and when that fails its k planes are evaluated in one tight loop over the SoA arrays below.
  struct Unit
  {
    std::uint32_t firstNode;  // into the per-node arrays; a unit's nodes are consecutive
    std::uint32_t nodeCount;  // >= 1; the last one is the tail
    std::uint32_t size;       // fragments in the unit's subtree
    std::uint32_t tailStart;  // start of the tail's range, relative to the unit's range start
    std::uint32_t front;      // unit of the tail's front child, or kNone
    std::uint32_t back;       // unit of the tail's back child, or kNone
    std::uint32_t anchor;     // Anchors index of the eye the safe ball is centred on
    float radius;             // safe distance around the anchor (rounded down)
  };
  struct Frame
  {
    std::uint32_t unit;
    std::uint32_t start;
    std::uint32_t parentFrame;
    bool expanded;
    double radius;
  };
  void walk(const View& view, bool full);
  void layout(Unit& unit, std::uint32_t start, bool full, bool tailFlipped,
    std::uint32_t oldTailStart);

  const Tree* TreePtr;
  Direction Dir;
  std::vector<std::uint32_t> Order;
  UpdateStatistics Last;
  std::vector<Unit> Units;
  // Per node, in unit order (structure of arrays: the plane loop streams through them).
  std::vector<double> PlaneX, PlaneY, PlaneZ, PlaneW; // the tree's planes, bit for bit
  std::vector<double> InvNorm;  // distance in normalised eye space = |side value| * InvNorm / |E|
  std::vector<std::uint32_t> OwnFirst;
  std::vector<std::uint32_t> OwnCount;
  std::vector<std::uint8_t> Side;      // 1: viewer in front at the last evaluation
  std::vector<std::uint8_t> ChildMask; // non-tail nodes: child goes first iff (Side ^ ChildMask)
  std::vector<std::uint32_t> MoveScratch; // children's ranges while a unit is re-laid out
  std::vector<glm::dvec4> Anchors; // normalised eyes referred to by Unit::anchor
  std::vector<Frame> Stack;
  double Scale = 1.0; // eye coordinates are divided by this (the bounds diagonal)
  bool Initialized = false;
};

} // namespace bsp
} // namespace scenevis

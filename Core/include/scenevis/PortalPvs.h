#pragma once
/**
 * @file PortalPvs.h
 * @brief Per-room potentially visible sets (PVS), precomputed from the portal graph.
 *
 * For every node (room, and the outside) the set of nodes that may be seen from anywhere in it,
 * in any direction. At run time, PVS lookup of the eye's rooms plus frustum culling replaces the
 * per-frame traversal (PortalTraversal::runPvs()).
 *
 * What is guaranteed: node Y is in PVS(X) whenever some straight line segment starts in X and
 * reaches Y crossing portals p1, p2, ..., pk (in that order, each transversally) -- the cells-and-
 * portals assumption of PortalGraph.h makes this every way to see Y from X. The computation walks
 * all portal sequences from X depth-first (explicit stack) and drops a sequence only when one of
 * these necessary conditions for such a line fails (so the PVS is a superset of the exact one):
 *  1. every later portal has a point strictly on the far side (beyond the tolerance) of the plane
 *     of every earlier one (a line crosses a plane once; lines that graze a portal plane within
 *     the graph tolerance are ignored);
 *  2. for every earlier pair (p1, pm) and (p(m-1), pm), every later portal has a point on pm's
 *     side of each plane through an edge of one and a vertex of the other that separates them
 *     (Teller's separating planes; no anti-penumbra clipping, hence looser than the exact PVS).
 * Portals whose sides cannot be told (non-planar, or neither room found on a side) impose no
 * condition. A leaky room anywhere on a sequence, or a source whose sequence count exceeds
 * PvsOptions::maxSequencesPerNode, makes the PVS every node reachable in the graph.
 */

#include "scenevis/PortalGraph.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace scenevis
{
namespace portals
{

struct PvsOptions
{
  /// Budget per source node; beyond it the source sees everything reachable (conservative).
  std::size_t maxSequencesPerNode = 2'000'000;
  /// Called after each source node with the fraction done in [0, 1]; return false to cancel.
  std::function<bool(double)> progress;
};

struct PvsStats
{
  std::size_t sequences = 0;        ///< Portal sequences accepted (walked).
  std::size_t pruned = 0;           ///< Sequences dropped by condition 1 or 2.
  std::size_t overBudget = 0;       ///< Sources that hit the budget.
  std::size_t leakySources = 0;     ///< Sources that reached a leaky room.
  double averageSetSize = 0.0;      ///< Mean PVS size over the nodes.
  bool cancelled = false;
};

class PortalPvs
{
public:
  /// Compute the PVS of every node. Returns an empty PVS (empty() true) when cancelled.
  static PortalPvs compute(const PortalGraph& graph,
    const PvsOptions& options = PvsOptions(),
    PvsStats* stats = nullptr);

  bool empty() const { return this->Sets.empty(); }
  std::int32_t nodeCount() const { return static_cast<std::int32_t>(this->Sets.size()); }
  /// The graph fingerprint the PVS was computed for.
  std::uint64_t fingerprint() const { return this->Fingerprint; }
  /// Sorted node ids visible from @p node (including itself); empty for an invalid node.
  const std::vector<std::int32_t>& visibleFrom(std::int32_t node) const;
  bool visible(std::int32_t from, std::int32_t to) const;

  /**
   * Save as a small text file: "scenevis-pvs 1", the fingerprint, the node count, then one line
   * per node "<node> <count> <ids...>". Returns false (and @p error) on I/O failure.
   */
  bool save(const std::string& path, std::string* error = nullptr) const;
  /// Load a file written by save() for @p graph; fails on a fingerprint or size mismatch.
  static bool load(const std::string& path,
    const PortalGraph& graph,
    PortalPvs& out,
    std::string* error = nullptr);

private:
  std::vector<std::vector<std::int32_t>> Sets;
  std::uint64_t Fingerprint = 0;
};

} // namespace portals
} // namespace scenevis

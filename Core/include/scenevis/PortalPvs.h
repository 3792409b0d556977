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
 * portals assumption of PortalGraph.h makes this every way to see Y from X. Lines that graze a
 * portal plane or a portal edge within the graph tolerance are ignored. Three methods
 * (PvsOptions::method), each a superset of the exact PVS:
 *
 * PortalFlow (default; the portal flow of level compilers, e.g. Quake's vis):
 *  1. Every portal is split into two directed portals (one per way through it, its plane facing
 *     the node it leads into). Might-see flood: from each directed portal s, a flood over directed
 *     portals that only follows a portal q when q has a point strictly in front of s and s a
 *     point strictly behind q (a line crosses s forward, then q forward), and the same between q
 *     and the portal passed just before it. One bit set (std::vector<uint64_t>) per portal.
 *  2. Flow: a depth-first walk from s through its might-see portals keeping, per level, the
 *     source polygon and the pass polygon clipped so far. Each step clips the next portal to the
 *     front of s and of the previous pass, the source to the back of the next portal, then the
 *     next portal by the separating planes of (source, previous pass) and of (previous pass,
 *     source) -- planes through an edge of one and a vertex of the other with the two on
 *     opposite sides; a line through both can only continue on the pass's side (anti-penumbra
 *     clipping); optionally the source by those of the next portal and the previous pass
 *     (clipSourceBySeparators). An empty polygon ends the branch. The bits the walk may still
 *     reach are the intersection of the might-see sets (or, once computed, the final sets) of
 *     the portals passed, so work done for one portal bounds the others: portals are processed
 *     in order of increasing might-see count, on PvsOptions::threads threads. With
 *     PvsOptions::passages (off by default), each step from the portal q passed into a node through
 *     its portal r also keeps only the passage of (q, r): the portals a line crossing q then r
 *     may still cross (see PvsOptions::passages), computed once per pair before the flows.
 *  3. PVS(X) = X, its neighbours, and the node behind every portal the flows of X's portals
 *     reached. Coordinates are taken relative to the centre of the portals; clipping keeps a
 *     slack of 1e3 graph tolerances (conservative: polygons only grow).
 *  After mergeAfterSteps steps the walk over paths of one source gives way to the merged flow
 *  (PvsOptions::mergeAfterSteps): one merged polygon and bit set per portal reached, a worklist
 *  that ends whatever the number of paths. After maxFlowStepsPerPortal steps for one portal, or
 * once PvsOptions::budgetSeconds has run out, a flow closes instead of descending: each portal
 * still passing the clipping is taken with everything its branch might see (the intersection of the
 * might-see or final sets along the path: conservative, and tighter than the source's might-see
 * set). With a budget, every flow gets an even share of the time left (in steps, at the rate
 * measured so far), so the budget narrows all portals rather than leaving the last, most expensive
 * ones un-narrowed. PvsStats::degradedPortals counts the flows that closed. With several threads a
 * portal may be bounded by another's final set or by its might-see set depending on timing, so two
 * runs may differ in a few extra nodes (both supersets of the exact PVS); threads = 1 is
 * deterministic.
 *
 * MightSee: step 1 alone (the loosest a closed flow can be).
 *
 * SeparatingPlanes (the first method, kept to compare): walks all portal sequences from X
 * depth-first (explicit stack) and drops a sequence only when one of these necessary conditions
 * for such a line fails:
 *  1. every later portal has a point strictly on the far side (beyond the tolerance) of the plane
 *     of every earlier one;
 *  2. for every earlier pair (p1, pm) and (p(m-1), pm), every later portal has a point on pm's
 *     side of each plane through an edge of one and a vertex of the other that separates them
 *     (Teller's separating planes; no anti-penumbra clipping, hence looser than the exact PVS).
 *  Its cost grows with the number of portal sequences: minutes to hours beyond a few hundred
 *  rooms with many openings.
 *
 * Portals whose sides cannot be told (non-planar, or neither room found on a side) impose no
 * condition: the flow passes everything reachable behind them. A leaky room anywhere in a PVS,
 * or (SeparatingPlanes) a source whose sequence count exceeds PvsOptions::maxSequencesPerNode,
 * makes the PVS every node reachable in the graph.
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

enum class PvsMethod
{
  PortalFlow,       ///< Might-see flood, then clipped flow within it (see the file comment).
  MightSee,         ///< The might-see flood alone: cheap and looser.
  SeparatingPlanes, ///< The sequence walk with separating planes; exponential on big levels.
};

struct PvsOptions
{
  PvsMethod method = PvsMethod::PortalFlow;
  /// SeparatingPlanes: budget per source node; beyond it the source sees everything reachable.
  std::size_t maxSequencesPerNode = 2'000'000;
  /// PortalFlow: worker threads; 0 = std::thread::hardware_concurrency().
  int threads = 0;
  /// PortalFlow: wall-clock budget of the flow step in seconds (0 = none): flows get even shares
  /// of it and close when theirs is used (conservative, see the file comment).
  double budgetSeconds = 0.0;
  /// PortalFlow: flow steps (portals passed) for one source portal before its flow closes
  /// (0 = no limit).
  std::size_t maxFlowStepsPerPortal = 50'000'000;
  /// PortalFlow: also clip the source by the separating planes of (next portal, previous pass).
  /// Off as in Quake's vis: on a 588-room maze it made the flow 1.6x slower for sets 0.4 %
  /// smaller.
  bool clipSourceBySeparators = false;
  /// PortalFlow: passage might-see (the idea of q3map2's passage vis). Before the flows, for
  /// every pair of consecutive directed portals (q, r) -- r leaving the node q leads into -- the
  /// portals a line crossing q then r may cross later: the might-see flood from r within the
  /// might-see sets of q and r, passing only portals with a point in front of every separating
  /// plane of q and r. A flow stepping from q through r then keeps only those bits beyond r, so
  /// every consecutive pair of its path bounds what lies beyond it (not only the source and the
  /// last pass, as the clipping does). Memory: one bit set of the directed portals per pair
  /// (Freedoom MAP12: 130,262 pairs, 189 MB, freed after the flows). Off by default: with the
  /// merged flow (mergeAfterSteps) finishing long flows, their 3-5 s and memory do not pay
  /// (MAP12: 27.6 s CPU with them, 24.3 s without; BENCHMARKS.md); without the merged flow
  /// they halve the flows a step cap closes.
  bool passages = false;
  /// PortalFlow: flow steps for one source portal after which its walk over paths stops and
  /// the merged flow finishes it instead (0 = never): one polygon per portal reached (the
  /// convex hull of what every path let through) and one set of bits, processed again while
  /// they grow. Complete and conservative, looser than the walk where paths meet, and its cost
  /// does not grow with the number of paths (long chains of small rooms). The step cap and the
  /// budget still close flows (merged ones too) when they run out. Freedoom MAP12 (1,692
  /// rooms): half of its flows pass 2,000 steps and none of them would finish otherwise. Once
  /// 24 of the last 32 walks gave way, sources skip the walk (every 8th still walks): sources
  /// come in order of might-see count, and the walks that would be thrown away cost half the
  /// time.
  std::size_t mergeAfterSteps = 2000;
  /// Called with the fraction done in [0, 1], on the calling thread only (after each source node;
  /// PortalFlow: about every 50 ms and once at the end); return false to cancel.
  std::function<bool(double)> progress;
};

struct PvsStats
{
  PvsMethod method = PvsMethod::PortalFlow;
  std::size_t sequences = 0;        ///< SeparatingPlanes: sequences accepted (walked).
  std::size_t pruned = 0;           ///< SeparatingPlanes: sequences dropped by condition 1 or 2.
  std::size_t overBudget = 0;       ///< SeparatingPlanes: sources that hit the budget.
  std::size_t leakySources = 0;     ///< Sources that reached a leaky room.
  double averageSetSize = 0.0;      ///< Mean PVS size over the nodes.
  bool cancelled = false;

  std::size_t directedPortals = 0;  ///< PortalFlow / MightSee: two per graph portal.
  double averageMightSee = 0.0;     ///< Mean might-see count per directed portal.
  double averagePortalVis = 0.0;    ///< Mean final count per directed portal.
  std::size_t flowSteps = 0;        ///< Portals passed by all flows.
  std::size_t unknownPortals = 0;   ///< Graph portals without a usable side (no narrowing).
  /// Directed portals whose flow closed early (time or step budget): conservative, looser.
  std::size_t degradedPortals = 0;
  std::size_t mergedPortals = 0;    ///< Directed portals finished by the merged flow.
  std::size_t mergedSteps = 0;      ///< Portals processed by merged flows (one per edge try).
  bool budgetExceeded = false;      ///< budgetSeconds ran out before every flow finished.
  int threads = 1;                  ///< Threads the flow ran on.
  std::size_t passages = 0;         ///< PortalFlow with passages: portal pairs with a passage.
  double averagePassage = 0.0;      ///< Mean portals per passage.
  std::size_t passageBytes = 0;     ///< Memory of the passages' bit sets (freed after the flow).
  double mightSeeSeconds = 0.0;
  double passageSeconds = 0.0; ///< Time of the passages (between might-see and flow).
  double flowSeconds = 0.0;
};

class PortalPvs
{
public:
  /// Node sets from per-node sorted lists (tests, tools); the fingerprint is taken from @p graph.
  static PortalPvs fromSets(const PortalGraph& graph, std::vector<std::vector<std::int32_t>> sets);

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

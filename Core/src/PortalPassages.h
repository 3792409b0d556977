#pragma once
// Passage might-see of the portal flow (PortalPvsFlow.cpp; the idea of q3map2's "passage vis"):
// for every pair of directed portals (q, r) where r leaves the node q leads into, the portals a
// straight line crossing q and then r may cross afterwards. Not installed.
#include "PortalFlowClip.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace portals
{
namespace flow
{

/// The directed-portal graph the passages are computed on (owned by the caller).
struct PassageGraph
{
  const std::vector<DirectedPortal>* portals = nullptr;
  const std::vector<std::uint32_t>* outStart = nullptr; ///< Per node: into outList (CSR).
  const std::vector<std::uint32_t>* outList = nullptr;  ///< Directed portals leaving each node.
  /// Per directed portal q: the first edge (q, r) of the r leaving q.to, in outList order.
  const std::vector<std::uint32_t>* succStart = nullptr;
  const std::vector<char>* edgeOk = nullptr;            ///< Per edge: a line may cross q then r.
  const std::vector<std::uint64_t>* mightSee = nullptr; ///< words per directed portal.
  std::size_t words = 0;
  double on = 0.0;    ///< Plane tolerance of the separating planes.
  double slack = 0.0; ///< A portal within slack behind a plane still counts as in front.
};

/**
 * Per edge (q, r) of PassageGraph: a bit set of the directed portals that a line crossing q
 * forward, then r forward, may cross forward after r (in any number of further steps). It is
 * the might-see flood from r restricted to might-see(q) and might-see(r) that only passes portals
 * with a point in front (within the slack) of every separating plane of q and r
 * (flow::separators): a line through q and r continues in front of each of them, and so does
 * every portal it crosses later. An edge without a passage (none(), of() is null) is one no line
 * can take (edgeOk false), or one with an unusable q or r: no narrowing.
 */
class Passages
{
public:
  /// Computes every passage on @p threads threads; stops early (leaving passages empty) when
  /// @p stop becomes true.
  static Passages compute(const PassageGraph& graph, int threads, const std::atomic<bool>& stop);

  /// The bits of edge @p e, or null when the edge has no passage.
  const std::uint64_t* of(std::size_t e) const
  {
    const std::uint32_t slot = this->Slot.empty() ? 0 : this->Slot[e];
    return slot ? &this->Bits[(slot - 1) * this->Words] : nullptr;
  }
  std::size_t count() const { return this->Count; }
  std::size_t bytes() const { return this->Bits.size() * sizeof(std::uint64_t); }
  /// Mean number of portals per passage.
  double averageSize() const;

private:
  std::vector<std::uint32_t> Slot; ///< Per edge: 1 + index into Bits' rows, 0 = no passage.
  std::vector<std::uint64_t> Bits;
  std::size_t Words = 0;
  std::size_t Count = 0;
};

} // namespace flow
} // namespace portals
} // namespace scenevis

// Passage might-see (PortalPassages.h): one separating-plane-clipped flood per portal pair.
#include "PortalPassages.h"

#include "scenevis/PortalGeometry.h"

#include <algorithm>

namespace scenevis
{
namespace portals
{
namespace flow
{

namespace
{

/// Whether @p t has a point within @p slack in front of every plane (its bounding sphere
/// first, its vertices only when the sphere straddles a plane).
bool inFrontOfAll(const DirectedPortal& t, const std::vector<glm::dvec4>& planes, double slack)
{
  if (!t.usable)
  {
    return true; // its surface is not its hull's plane: no narrowing through it
  }
  for (const glm::dvec4& plane : planes)
  {
    const double d = geometry::planeDistance(plane, t.centre);
    if (d - t.radius >= -slack)
    {
      continue;
    }
    if (d + t.radius < -slack || !(maxDistance(t.winding, plane) >= -slack))
    {
      return false;
    }
  }
  return true;
}

/// The passage of edge (q, r) into @p seen (words, zero on entry); @p rejected (words, zero on
/// entry and on return) remembers the portals tested and found behind a plane.
void passageFlood(const PassageGraph& g, std::uint32_t q, std::uint32_t r,
  const std::vector<glm::dvec4>& planes, std::uint64_t* seen, std::vector<std::uint64_t>& rejected,
  std::vector<std::uint32_t>& queue)
{
  const std::uint64_t* mq = &(*g.mightSee)[q * g.words];
  const std::uint64_t* mr = &(*g.mightSee)[r * g.words];
  std::uint64_t* no = rejected.data();
  const auto& portals = *g.portals;
  queue.clear();
  auto visit = [&](std::uint32_t t)
  {
    if (bit(seen, t) || bit(no, t) || !bit(mq, t) || !bit(mr, t))
    {
      return;
    }
    if (inFrontOfAll(portals[t], planes, g.slack))
    {
      setBit(seen, t);
      queue.push_back(t);
    }
    else
    {
      setBit(no, t);
    }
  };
  auto successors = [&](std::uint32_t a)
  {
    const auto to = static_cast<std::size_t>(portals[a].to);
    std::uint32_t e = (*g.succStart)[a];
    for (std::uint32_t k = (*g.outStart)[to]; k < (*g.outStart)[to + 1]; ++k, ++e)
    {
      if ((*g.edgeOk)[e])
      {
        visit((*g.outList)[k]);
      }
    }
  };
  successors(r);
  for (std::size_t head = 0; head < queue.size(); ++head)
  {
    successors(queue[head]);
  }
  std::fill(rejected.begin(), rejected.end(), 0);
}

} // namespace

Passages Passages::compute(const PassageGraph& g, int threads, const std::atomic<bool>& stop)
{
  Passages out;
  const auto& portals = *g.portals;
  const std::size_t D = portals.size();
  const std::size_t edges = g.edgeOk->size();
  // Slots first (one row per edge a line may take between usable portals), then the floods.
  out.Slot.assign(edges, 0);
  for (std::size_t q = 0; q < D; ++q)
  {
    const auto to = static_cast<std::size_t>(portals[q].to);
    std::uint32_t e = (*g.succStart)[q];
    for (std::uint32_t k = (*g.outStart)[to]; k < (*g.outStart)[to + 1]; ++k, ++e)
    {
      const std::uint32_t r = (*g.outList)[k];
      if ((*g.edgeOk)[e] && portals[q].usable && portals[r].usable)
      {
        out.Slot[e] = static_cast<std::uint32_t>(++out.Count);
      }
    }
  }
  out.Words = g.words;
  out.Bits.assign(out.Count * g.words, 0);
  runParallel(
    D, threads,
    [&](std::size_t q)
    {
      thread_local std::vector<std::uint64_t> rejected;
      thread_local std::vector<std::uint32_t> queue;
      thread_local std::vector<glm::dvec4> planes;
      rejected.resize(g.words);
      if (stop.load(std::memory_order_relaxed))
      {
        return;
      }
      const auto to = static_cast<std::size_t>(portals[q].to);
      std::uint32_t e = (*g.succStart)[q];
      for (std::uint32_t k = (*g.outStart)[to]; k < (*g.outStart)[to + 1]; ++k, ++e)
      {
        const std::uint32_t slot = out.Slot[e];
        if (slot == 0)
        {
          continue;
        }
        const std::uint32_t r = (*g.outList)[k];
        separators(portals[q].winding, portals[r].winding, g.on, planes);
        passageFlood(g, static_cast<std::uint32_t>(q), r, planes, &out.Bits[(slot - 1) * g.words],
          rejected, queue);
      }
    },
    [](std::size_t) {});
  return out;
}

double Passages::averageSize() const
{
  return this->Count ? double(popcount(this->Bits.data(), this->Bits.size())) / double(this->Count)
                     : 0.0;
}

} // namespace flow
} // namespace portals
} // namespace scenevis

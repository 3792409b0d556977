// PortalFlow and MightSee PVS methods (PortalPvs.h): might-see floods over directed portals, then
// the clipped flow within them, multi-threaded, with bit sets and shared bounds.
#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalPvs.h"

#include "PortalFlowClip.h"
#include "PortalPassages.h"
#include "PortalPvsInternal.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>

namespace scenevis
{
namespace portals
{

namespace
{
using flow::bit;
using flow::chop;
using flow::chopAll;
using flow::chopAllWithin;
using flow::chopWithin;
using flow::DirectedPortal;
using flow::maxDistance;
using flow::mergeHull;
using flow::minDistance;
using flow::Passages;
using flow::popcount;
using flow::runParallel;
using flow::separators;
using flow::setBit;
using flow::Winding;
using Clock = std::chrono::steady_clock;

/// One level of a flow: the node reached, the portal passed into it and the clipped polygons.
struct Level
{
  std::int32_t node = 0;
  std::uint32_t entry = 0; ///< The directed portal passed into node (the source at the root).
  std::uint32_t next = 0;  ///< Position in the node's out-portal list.
  glm::dvec4 plane{ 0.0 };
  Winding pass;   ///< The portal passed, clipped (empty at the root: no pass yet).
  Winding source; ///< The source portal, clipped.
  std::vector<std::uint64_t> might;
  /// Separating planes of (source, pass), computed once per level on first use: most next
  /// portals leave the source unclipped, so the planes are the same for all of them.
  std::vector<glm::dvec4> separators;
  bool separatorsReady = false;
};

/// The merged flow's state per portal reached (Shared::mergedFlow), reused by every source of
/// a thread.
struct MergedScratch
{
  std::vector<std::int32_t> slot;     ///< Per directed portal: its row, or -1 when not reached.
  std::vector<std::uint32_t> touched; ///< Portals with a row (to reset slot).
  std::vector<Winding> pass;          ///< Per row: the merged polygon of the portal.
  std::vector<std::vector<glm::dvec4>> separators; ///< Per row: of (source, pass), on demand.
  std::vector<double> area;                        ///< Per row: the pass polygon's area.
  std::vector<int> growth;                         ///< Per row: times the polygon grew.
  std::vector<unsigned char> state;                ///< Per row: queued, separators ready.
  std::vector<std::uint64_t> might;                ///< Per row: words of bits.
  std::vector<std::uint32_t> queue;
  Winding clip, hull;
  const Winding none{};
  std::vector<glm::dvec3> work;
};

struct Shared
{
  std::vector<DirectedPortal> portals;
  std::vector<std::uint32_t> outStart, outList; ///< Directed portals leaving each node (CSR).
  std::vector<std::uint32_t> succStart;         ///< Per directed portal: into edgeOk.
  std::vector<char> edgeOk; ///< Per (q, r in out(q.to)): a line may cross q then r.
  std::size_t words = 0;
  std::vector<std::uint64_t> mightSee, vis; ///< words per directed portal.
  Passages passages; ///< Per edge (q, r): what a line through q then r may see (when used).
  bool usePassages = false;
  std::vector<std::atomic<unsigned char>> done;
  double on = 0.0, slack = 0.0;
  std::size_t maxSteps = 0;
  bool clipSource = false;
  /// stop: cancelled (flows abort); closing: the budget ran out (flows close their branches).
  std::atomic<bool> stop{ false }, closing{ false }, budgetHit{ false };
  std::atomic<std::size_t> totalSteps{ 0 }, degraded{ 0 };
  std::atomic<std::size_t> mergedSteps{ 0 }, merged{ 0 };
  std::size_t mergeAfter = 0;
  std::atomic<std::uint32_t> recentAborts{ 0 }; ///< The last 32 walks: 1 = gave way to merging.

  const std::uint64_t* mightOf(std::size_t p) const { return &this->mightSee[p * this->words]; }
  std::uint64_t* visOf(std::size_t p) { return &this->vis[p * this->words]; }

  /// Whether a line crossing @p s forward may then cross @p r forward: r has a point in front
  /// of s and s a point behind r (bounding spheres first, the vertices when they straddle).
  bool frontOk(const DirectedPortal& s, const DirectedPortal& r) const
  {
    if (!s.usable || !r.usable)
    {
      return true;
    }
    const double rc = geometry::planeDistance(s.plane, r.centre);
    if (rc + r.radius <= this->on)
    {
      return false;
    }
    if (rc - r.radius <= this->on && !(maxDistance(r.winding, s.plane) > this->on))
    {
      return false;
    }
    const double sc = geometry::planeDistance(r.plane, s.centre);
    if (sc - s.radius >= -this->on)
    {
      return false;
    }
    return sc + s.radius < -this->on || minDistance(s.winding, r.plane) < -this->on;
  }

  /// The might-see set of @p s; @p rejected (words, zero on entry and on return) remembers the
  /// portals s cannot see at all, so each is tested once.
  void flood(std::size_t s, std::vector<std::uint32_t>& queue, std::vector<std::uint64_t>& rejected)
  {
    std::uint64_t* seen = &this->mightSee[s * this->words];
    std::uint64_t* no = rejected.data();
    const DirectedPortal& src = this->portals[s];
    queue.clear();
    const auto to = static_cast<std::size_t>(src.to);
    for (std::uint32_t k = this->outStart[to]; k < this->outStart[to + 1]; ++k)
    {
      const std::uint32_t q = this->outList[k];
      if ((q ^ 1u) != s && this->frontOk(src, this->portals[q]))
      {
        setBit(seen, q);
        queue.push_back(q);
      }
    }
    for (std::size_t head = 0; head < queue.size(); ++head)
    {
      const std::uint32_t q = queue[head];
      const auto qto = static_cast<std::size_t>(this->portals[q].to);
      std::uint32_t e = this->succStart[q];
      for (std::uint32_t k = this->outStart[qto]; k < this->outStart[qto + 1]; ++k, ++e)
      {
        const std::uint32_t r = this->outList[k];
        if (!this->edgeOk[e] || bit(seen, r) || bit(no, r))
        {
          continue;
        }
        if (this->frontOk(src, this->portals[r]))
        {
          setBit(seen, r);
          queue.push_back(r);
        }
        else
        {
          setBit(no, r);
        }
      }
    }
    std::fill(rejected.begin(), rejected.end(), 0);
  }

  /**
   * The flow from directed portal @p s; false when cancelled. After @p limit steps, or once
   * the budget has run out, the flow closes instead of descending: a portal that passes the
   * clipping is marked seen together with everything its branch might still see (the might
   * bits of its level: the intersection of the might-see or final sets of the portals on the
   * path), which bounds whatever lies beyond it. @p closed says whether that happened.
   */
  bool flow(std::size_t s, std::vector<Level>& levels, Winding& scratch, std::size_t limit,
    bool& closed, std::size_t abortAfter, bool& aborted)
  {
    aborted = false;
    const DirectedPortal& src = this->portals[s];
    std::uint64_t* visS = this->visOf(s);
    const std::size_t W = this->words;
    if (levels.empty())
    {
      levels.emplace_back();
    }
    Level& root = levels[0];
    root.node = src.to;
    root.entry = static_cast<std::uint32_t>(s);
    root.next = 0;
    root.plane = src.plane;
    root.pass.clear();
    root.source = src.winding;
    root.might.assign(this->mightOf(s), this->mightOf(s) + W);
    root.separatorsReady = false;
    std::size_t depth = 0, steps = 0;
    bool ok = true;
    bool closeNow = this->closing.load(std::memory_order_relaxed);
    for (;;)
    {
      Level& L = levels[depth];
      const auto node = static_cast<std::size_t>(L.node);
      if (this->outStart[node] + L.next >= this->outStart[node + 1])
      {
        if (depth == 0)
        {
          break;
        }
        --depth;
        continue;
      }
      const std::uint32_t p = this->outList[this->outStart[node] + L.next++];
      if (!bit(L.might.data(), p))
      {
        continue;
      }
      // The passage (portal passed into this node, p): what a line crossing both may see next.
      const std::size_t edge = this->succStart[L.entry] + L.next - 1;
      const std::uint64_t* passage = nullptr;
      if (this->usePassages)
      {
        if (!this->edgeOk[edge])
        {
          continue; // no line crosses the entry and then p
        }
        passage = this->passages.of(edge);
      }
      if (depth + 1 == levels.size())
      {
        levels.emplace_back(); // grows to the deepest flow once per thread, then reused
      }
      Level& L2 = levels[depth];
      Level& N = levels[depth + 1];
      const std::uint64_t* test = this->done[p].load(std::memory_order_acquire)
        ? &this->vis[static_cast<std::size_t>(p) * W]
        : this->mightOf(p);
      N.might.resize(W);
      // The bits beyond p: needed first only when p is already seen (nothing new: skip it);
      // otherwise only for a p that survives the clipping.
      const bool seenP = bit(visS, p);
      auto intersect = [&]()
      {
        std::uint64_t more = 0;
        if (passage)
        {
          for (std::size_t w = 0; w < W; ++w)
          {
            N.might[w] = L2.might[w] & test[w] & passage[w];
            more |= N.might[w] & ~visS[w];
          }
        }
        else
        {
          for (std::size_t w = 0; w < W; ++w)
          {
            N.might[w] = L2.might[w] & test[w];
            more |= N.might[w] & ~visS[w];
          }
        }
        return more != 0;
      };
      if (seenP && !intersect())
      {
        continue; // nothing new behind p
      }
      const DirectedPortal& dp = this->portals[p];
      if (!dp.usable)
      {
        if (!seenP)
        {
          intersect();
        }
        setBit(visS, p); // no narrowing through it: everything it may lead to
        for (std::size_t w = 0; w < W; ++w)
        {
          visS[w] |= N.might[w];
        }
        continue;
      }
      N.pass = dp.winding;
      if (!chopWithin(N.pass, src.plane, dp.centre, dp.radius, this->slack, scratch))
      {
        continue;
      }
      N.source = L2.source;
      bool sourceClipped = false;
      if (!chop(N.source, -dp.plane, this->slack, scratch, &sourceClipped))
      {
        continue;
      }
      if (depth > 0)
      {
        if (!chopWithin(N.pass, L2.plane, dp.centre, dp.radius, this->slack, scratch))
        {
          continue;
        }
        const std::vector<glm::dvec4>* planes = &L2.separators;
        if (sourceClipped)
        {
          separators(N.source, L2.pass, this->on, N.separators); // N's own are made on entry
          planes = &N.separators;
        }
        else if (!L2.separatorsReady)
        {
          separators(L2.source, L2.pass, this->on, L2.separators);
          L2.separatorsReady = true;
        }
        if (!chopAllWithin(N.pass, *planes, dp.centre, dp.radius, this->slack, scratch))
        {
          continue;
        }
        if (this->clipSource)
        {
          separators(N.pass, L2.pass, this->on, N.separators);
          if (!chopAll(N.source, N.separators, this->slack, scratch))
          {
            continue;
          }
        }
      }
      if (!seenP)
      {
        intersect();
      }
      setBit(visS, p);
      if (closeNow)
      {
        for (std::size_t w = 0; w < W; ++w)
        {
          visS[w] |= N.might[w];
        }
        continue;
      }
      N.node = dp.to;
      N.entry = p;
      N.next = 0;
      N.plane = dp.plane;
      N.separatorsReady = false;
      ++depth;
      if ((++steps & 1023u) == 0)
      {
        if (this->stop.load(std::memory_order_relaxed))
        {
          ok = false;
          break;
        }
        closeNow = closeNow || this->closing.load(std::memory_order_relaxed);
      }
      closeNow = closeNow || (limit && steps >= limit);
      if (abortAfter && steps >= abortAfter && !closeNow)
      {
        aborted = true; // the caller finishes this source with the merged flow
        break;
      }
    }
    this->totalSteps.fetch_add(steps, std::memory_order_relaxed);
    closed = closeNow;
    return ok;
  }

  /**
   * The merged flow from directed portal @p s (PvsOptions::mergeAfterSteps): a worklist over
   * portals instead of a walk over paths. Each portal r reached keeps one pass polygon, the
   * convex hull of the parts of r that every path reaching it let through, and one set of bits
   * (the union of the might bits of those paths); a portal whose polygon or bits grow is
   * processed again. A line through the source and portals p1 .. pk crosses each pi inside its
   * merged polygon (the clipping by the separating planes of the source and a larger pass keeps
   * more), so the result holds everything the flow would find: conservative, looser where paths
   * meet, and polynomial. The source is not clipped. After PvsOptions-independent kMaxGrowth
   * growths a polygon becomes its whole portal (in front of the source), so the worklist ends.
   * False when cancelled; once the budget runs out the queued portals are closed as in flow().
   */
  bool mergedFlow(std::size_t s, MergedScratch& m, Winding& scratch, bool& closed)
  {
    constexpr int kMaxGrowth = 8;
    const DirectedPortal& src = this->portals[s];
    std::uint64_t* visS = this->visOf(s);
    const std::size_t W = this->words;
    m.slot.resize(this->portals.size(), -1);
    std::size_t used = 0, steps = 0;
    auto slotOf = [&](std::uint32_t r)
    {
      if (m.slot[r] < 0)
      {
        m.slot[r] = static_cast<std::int32_t>(used++);
        m.touched.push_back(r);
        if (m.pass.size() < used)
        {
          m.pass.resize(used);
          m.separators.resize(used);
        }
        m.area.resize(std::max(m.area.size(), used));
        m.growth.resize(std::max(m.growth.size(), used));
        m.state.resize(std::max(m.state.size(), used));
        m.might.resize(std::max(m.might.size(), used * W));
        const std::size_t k = used - 1;
        m.pass[k].clear();
        m.area[k] = 0.0;
        m.growth[k] = 0;
        m.state[k] = 0;
        std::fill(m.might.begin() + static_cast<std::ptrdiff_t>(k * W),
          m.might.begin() + static_cast<std::ptrdiff_t>((k + 1) * W), 0);
      }
      return static_cast<std::size_t>(m.slot[r]);
    };
    constexpr unsigned char kQueued = 1, kSeparatorsReady = 2;
    m.queue.clear();
    bool ok = true;
    bool closeNow = this->closing.load(std::memory_order_relaxed);
    // The root (p == s) passes nothing yet: its bits are the source's might-see set.
    for (std::size_t head = 0; head <= m.queue.size(); ++head)
    {
      const bool root = head == 0;
      const std::uint32_t p = root ? static_cast<std::uint32_t>(s) : m.queue[head - 1];
      const std::size_t sp = root ? 0 : static_cast<std::size_t>(m.slot[p]);
      if (!root)
      {
        m.state[sp] &= static_cast<unsigned char>(~kQueued);
      }
      const std::uint64_t* mp = root ? this->mightOf(s) : &m.might[sp * W];
      if (closeNow && !root)
      {
        for (std::size_t w = 0; w < W; ++w)
        {
          visS[w] |= mp[w]; // as flow() closes a branch
        }
        continue;
      }
      const DirectedPortal& dp = this->portals[p];
      const auto node = static_cast<std::size_t>(dp.to);
      std::uint32_t e = this->succStart[p];
      for (std::uint32_t k = this->outStart[node]; k < this->outStart[node + 1]; ++k, ++e)
      {
        const std::uint32_t r = this->outList[k];
        if (!bit(mp, r))
        {
          continue;
        }
        const std::uint64_t* passage = nullptr;
        if (this->usePassages)
        {
          if (!this->edgeOk[e])
          {
            continue;
          }
          passage = this->passages.of(e);
        }
        const std::uint64_t* test = this->done[r].load(std::memory_order_acquire)
          ? &this->vis[static_cast<std::size_t>(r) * W]
          : this->mightOf(r);
        const DirectedPortal& dr = this->portals[r];
        ++steps;
        if (!dr.usable)
        {
          setBit(visS, r); // no narrowing through it: everything it may lead to
          for (std::size_t w = 0; w < W; ++w)
          {
            visS[w] |= mp[w] & test[w] & (passage ? passage[w] : ~std::uint64_t(0));
          }
          continue;
        }
        m.clip = dr.winding;
        if (!chopWithin(m.clip, src.plane, dr.centre, dr.radius, this->slack, scratch))
        {
          continue;
        }
        if (!root)
        {
          if (!chopWithin(m.clip, dp.plane, dr.centre, dr.radius, this->slack, scratch))
          {
            continue;
          }
          if (!(m.state[sp] & kSeparatorsReady))
          {
            separators(src.winding, m.pass[sp], this->on, m.separators[sp]);
            m.state[sp] |= kSeparatorsReady;
          }
          if (!chopAllWithin(m.clip, m.separators[sp], dr.centre, dr.radius, this->slack, scratch))
          {
            continue;
          }
        }
        setBit(visS, r);
        const std::size_t sr = slotOf(r);
        mp = root ? this->mightOf(s) : &m.might[sp * W]; // slotOf may have moved the bits
        std::uint64_t* mr = &m.might[sr * W];
        std::uint64_t more = 0;
        for (std::size_t w = 0; w < W; ++w)
        {
          const std::uint64_t b = mp[w] & test[w] & (passage ? passage[w] : ~std::uint64_t(0));
          more |= b & ~mr[w];
          mr[w] |= b;
        }
        bool grew = more != 0;
        if (m.growth[sr] <= kMaxGrowth)
        {
          if (m.pass[sr].empty())
          {
            m.area[sr] = mergeHull(m.clip, m.none, glm::dvec3(dr.plane), m.pass[sr], m.work);
            grew = true;
          }
          else
          {
            const double a = mergeHull(m.pass[sr], m.clip, glm::dvec3(dr.plane), m.hull, m.work);
            if (a > m.area[sr] * (1.0 + 1e-12))
            {
              m.pass[sr].swap(m.hull);
              m.area[sr] = a;
              m.state[sr] &= static_cast<unsigned char>(~kSeparatorsReady);
              grew = true;
              if (++m.growth[sr] > kMaxGrowth)
              {
                // Saturated: the whole portal in front of the source; it cannot grow again.
                m.pass[sr] = dr.winding;
                chop(m.pass[sr], src.plane, this->slack, scratch);
              }
            }
          }
        }
        if (grew && !(m.state[sr] & kQueued))
        {
          m.state[sr] |= kQueued;
          m.queue.push_back(r);
        }
      }
      if ((steps & 255u) == 0 || root)
      {
        if (this->stop.load(std::memory_order_relaxed))
        {
          ok = false;
          break;
        }
        closeNow = closeNow || this->closing.load(std::memory_order_relaxed);
      }
    }
    for (const std::uint32_t r : m.touched)
    {
      m.slot[r] = -1;
    }
    m.touched.clear();
    this->mergedSteps.fetch_add(steps, std::memory_order_relaxed);
    closed = closeNow;
    return ok;
  }
};

} // namespace

PortalPvs computePortalFlow(const PortalGraph& g, const PvsOptions& options, PvsStats& stats)
{
  const auto start = Clock::now();
  stats = PvsStats();
  stats.method = options.method;
  const auto nodes = static_cast<std::size_t>(g.nodeCount());
  const auto& gp = g.portals();
  Shared sh;
  sh.on = 10.0 * g.tolerance();
  sh.slack = 1000.0 * g.tolerance();
  sh.maxSteps = options.maxFlowStepsPerPortal;
  sh.clipSource = options.clipSourceBySeparators;
  sh.mergeAfter = options.method == PvsMethod::PortalFlow ? options.mergeAfterSteps : 0;
  Box all;
  for (const auto& p : gp)
  {
    all.extend(p.bounds);
  }
  const glm::dvec3 origin = all.empty() ? glm::dvec3(0.0) : all.center();

  // Directed portals: 2i leads from nodeA to nodeB, 2i + 1 back.
  const std::size_t D = 2 * gp.size();
  sh.portals.resize(D);
  for (std::size_t i = 0; i < gp.size(); ++i)
  {
    const GraphPortal& p = gp[i];
    const int side = portalOrientation(g, p);
    stats.unknownPortals += side == 0 ? 1 : 0;
    Winding w;
    for (const auto& q : p.hull)
    {
      w.push_back(q - origin);
    }
    const glm::dvec4 plane(glm::dvec3(p.plane), p.plane.w + glm::dot(glm::dvec3(p.plane), origin));
    for (int k = 0; k < 2; ++k)
    {
      DirectedPortal& d = sh.portals[2 * i + static_cast<std::size_t>(k)];
      d.from = k == 0 ? p.nodeA : p.nodeB;
      d.to = k == 0 ? p.nodeB : p.nodeA;
      d.usable = side != 0 && p.planar;
      d.plane = (k == 0 ? 1.0 : -1.0) * static_cast<double>(side) * plane;
      d.winding = w;
      glm::dvec3 c(0.0);
      for (const auto& q : w)
      {
        c += q;
      }
      d.centre = w.empty() ? c : c / static_cast<double>(w.size());
      for (const auto& q : w)
      {
        d.radius = std::max(d.radius, glm::length(q - d.centre));
      }
      d.radius *= 1.0 + 1e-12;
    }
  }
  sh.outStart.assign(nodes + 1, 0);
  for (const auto& d : sh.portals)
  {
    ++sh.outStart[static_cast<std::size_t>(d.from) + 1];
  }
  std::partial_sum(sh.outStart.begin(), sh.outStart.end(), sh.outStart.begin());
  sh.outList.resize(D);
  {
    std::vector<std::uint32_t> fill(sh.outStart.begin(), sh.outStart.end() - 1);
    for (std::uint32_t d = 0; d < D; ++d)
    {
      sh.outList[fill[static_cast<std::size_t>(sh.portals[d].from)]++] = d;
    }
  }
  sh.succStart.resize(D + 1, 0);
  for (std::size_t q = 0; q < D; ++q)
  {
    const auto to = static_cast<std::size_t>(sh.portals[q].to);
    sh.succStart[q + 1] = sh.succStart[q] + (sh.outStart[to + 1] - sh.outStart[to]);
  }
  sh.edgeOk.resize(sh.succStart[D]);
  for (std::size_t q = 0; q < D; ++q)
  {
    const auto to = static_cast<std::size_t>(sh.portals[q].to);
    std::uint32_t e = sh.succStart[q];
    for (std::uint32_t k = sh.outStart[to]; k < sh.outStart[to + 1]; ++k, ++e)
    {
      const std::uint32_t r = sh.outList[k];
      sh.edgeOk[e] = (r ^ 1u) != q && sh.frontOk(sh.portals[q], sh.portals[r]) ? 1 : 0;
    }
  }
  sh.words = (D + 63) / 64;
  sh.mightSee.assign(D * sh.words, 0);
  sh.vis.assign(D * sh.words, 0);
  sh.done = std::vector<std::atomic<unsigned char>>(D);
  stats.directedPortals = D;
  const int threads = options.threads > 0
    ? options.threads
    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  stats.threads = threads;

  bool cancelled = false;
  double reported = 0.0;
  auto report = [&](double fraction)
  {
    reported = std::min(1.0, std::max(reported, fraction)); // never backwards
    if (!cancelled && options.progress && !options.progress(reported))
    {
      cancelled = true;
      sh.stop = true;
    }
    return !cancelled;
  };
  const bool flow = options.method == PvsMethod::PortalFlow;
  const double floodShare = flow ? 0.1 : 1.0;

  // 1. Might-see floods.
  runParallel(
    D, threads,
    [&](std::size_t i)
    {
      thread_local std::vector<std::uint32_t> queue; // reused by every flood of this thread
      thread_local std::vector<std::uint64_t> rejected;
      rejected.resize(sh.words);
      if (!sh.stop.load(std::memory_order_relaxed))
      {
        sh.flood(i, queue, rejected);
      }
    },
    [&](std::size_t finished)
    { report(floodShare * double(finished) / double(std::max<std::size_t>(D, 1))); });
  stats.mightSeeSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::size_t mightTotal = 0;
  std::vector<std::size_t> mightCount(D);
  for (std::size_t p = 0; p < D; ++p)
  {
    mightCount[p] = popcount(sh.mightOf(p), sh.words);
    mightTotal += mightCount[p];
  }
  stats.averageMightSee = D ? double(mightTotal) / double(D) : 0.0;

  // 1b. Passages: what a line through each pair of consecutive portals may see next.
  if (flow && options.passages && !cancelled)
  {
    const auto passageStart = Clock::now();
    flow::PassageGraph pg;
    pg.portals = &sh.portals;
    pg.outStart = &sh.outStart;
    pg.outList = &sh.outList;
    pg.succStart = &sh.succStart;
    pg.edgeOk = &sh.edgeOk;
    pg.mightSee = &sh.mightSee;
    pg.words = sh.words;
    pg.on = sh.on;
    pg.slack = sh.slack;
    sh.passages = Passages::compute(pg, threads, sh.stop);
    sh.usePassages = true;
    stats.passages = sh.passages.count();
    stats.averagePassage = sh.passages.averageSize();
    stats.passageBytes = sh.passages.bytes();
    stats.passageSeconds = std::chrono::duration<double>(Clock::now() - passageStart).count();
    cancelled = cancelled || !report(floodShare);
  }

  // 2. Flows, fewest might-see first; unusable sources keep their might-see set.
  const auto flowStart = Clock::now();
  if (flow && !cancelled)
  {
    std::vector<std::uint32_t> order;
    for (std::uint32_t p = 0; p < D; ++p)
    {
      if (sh.portals[p].usable)
      {
        order.push_back(p);
      }
      else
      {
        std::copy(sh.mightOf(p), sh.mightOf(p) + sh.words, sh.visOf(p));
        sh.done[p].store(1, std::memory_order_release);
      }
    }
    std::stable_sort(order.begin(), order.end(),
      [&](std::uint32_t a, std::uint32_t b) { return mightCount[a] < mightCount[b]; });
    const double total = std::max<double>(1.0, double(mightTotal));
    std::atomic<std::size_t> weight{ 0 };
    const double budget = options.budgetSeconds;
    auto overBudget = [&]()
    {
      if (budget > 0.0 && std::chrono::duration<double>(Clock::now() - flowStart).count() > budget)
      {
        sh.budgetHit = true;
        sh.closing = true;
      }
    };
    // With a budget, each flow gets an even share of the time left, in steps at the rate
    // measured so far, so that the budget narrows every portal a little rather than leaving
    // the last ones (the most expensive: most might-see) with nothing.
    auto stepLimit = [&](std::size_t left) -> std::size_t
    {
      const double elapsed = std::chrono::duration<double>(Clock::now() - flowStart).count();
      const std::size_t done = sh.totalSteps.load(std::memory_order_relaxed);
      if (!(budget > 0.0) || elapsed < 0.25 || done == 0)
      {
        return sh.maxSteps;
      }
      const double share = (budget - elapsed) * (double(done) / elapsed) / double(left);
      const auto steps = static_cast<std::size_t>(std::max(256.0, share));
      return sh.maxSteps ? std::min(sh.maxSteps, steps) : steps;
    };
    runParallel(
      order.size(), threads,
      [&](std::size_t i)
      {
        thread_local std::vector<Level> levels; // grown once per thread, reused by every flow
        thread_local Winding scratch;
        const std::uint32_t s = order[i];
        overBudget();
        bool closed = false;
        const std::size_t limit = stepLimit(order.size() - i);
        thread_local MergedScratch merged;
        bool aborted = false;
        // Sources come in order of might-see count, and past some count nearly every walk
        // gives way to the merged flow: once 24 of the last 32 walks did, the walk is skipped
        // (every 8th source still walks, to notice when that stops).
        const bool skipWalk = sh.mergeAfter && i % 8 != 0 &&
          __builtin_popcount(sh.recentAborts.load(std::memory_order_relaxed)) >= 24;
        bool ok = !sh.stop.load(std::memory_order_relaxed);
        if (ok && skipWalk)
        {
          aborted = true;
        }
        else if (ok)
        {
          ok = sh.flow(s, levels, scratch, limit, closed, sh.mergeAfter, aborted);
          std::uint32_t h = sh.recentAborts.load(std::memory_order_relaxed);
          while (!sh.recentAborts.compare_exchange_weak(
            h, (h << 1) | (aborted ? 1u : 0u), std::memory_order_relaxed))
          {
          }
        }
        if (ok && aborted)
        {
          // Too many paths: the merged flow finishes the source (the walk's finds are kept).
          sh.merged.fetch_add(1, std::memory_order_relaxed);
          ok = sh.mergedFlow(s, merged, scratch, closed);
        }
        if (!ok)
        {
          std::copy(sh.mightOf(s), sh.mightOf(s) + sh.words, sh.visOf(s));
          closed = true;
        }
        sh.degraded.fetch_add(closed ? 1 : 0);
        sh.done[s].store(1, std::memory_order_release);
        weight.fetch_add(mightCount[s], std::memory_order_relaxed);
      },
      [&](std::size_t)
      {
        overBudget();
        report(floodShare + (1.0 - floodShare) * double(weight.load()) / total);
      });
    stats.budgetExceeded = sh.budgetHit.load();
    sh.passages = Passages(); // free them before the node sets
  }
  else if (!cancelled)
  {
    sh.vis = sh.mightSee;
  }
  stats.flowSeconds = std::chrono::duration<double>(Clock::now() - flowStart).count();
  if (cancelled || (options.progress && !report(1.0)))
  {
    stats.cancelled = true;
    return PortalPvs();
  }
  stats.flowSteps = sh.totalSteps.load();
  stats.degradedPortals = sh.degraded.load();
  stats.mergedPortals = sh.merged.load();
  stats.mergedSteps = sh.mergedSteps.load();
  std::size_t visTotal = 0;
  for (std::size_t p = 0; p < D; ++p)
  {
    visTotal += popcount(sh.visOf(p), sh.words);
  }
  stats.averagePortalVis = D ? double(visTotal) / double(D) : 0.0;

  // 3. Node sets: the node, its neighbours and the nodes behind every portal its portals see;
  // then only pairs seen both ways (a line from X to Y, reversed, goes from Y to X).
  const std::size_t NW = (nodes + 63) / 64;
  std::vector<std::uint64_t> raw(nodes * NW, 0);
  for (std::size_t x = 0; x < nodes; ++x)
  {
    std::uint64_t* set = &raw[x * NW];
    setBit(set, x);
    for (std::uint32_t k = sh.outStart[x]; k < sh.outStart[x + 1]; ++k)
    {
      const std::uint32_t s = sh.outList[k];
      setBit(set, static_cast<std::size_t>(sh.portals[s].to));
      const std::uint64_t* v = sh.visOf(s);
      for (std::size_t w = 0; w < sh.words; ++w)
      {
        for (std::uint64_t bits = v[w]; bits; bits &= bits - 1)
        {
          const std::size_t p = w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits));
          setBit(set, static_cast<std::size_t>(sh.portals[p].to));
        }
      }
    }
  }
  std::vector<std::vector<std::int32_t>> sets(nodes);
  std::vector<char> seen;
  std::size_t totalSize = 0;
  const auto& rooms = g.rooms();
  for (std::size_t x = 0; x < nodes; ++x)
  {
    const std::uint64_t* set = &raw[x * NW];
    bool leaky = false;
    for (std::size_t y = 0; y < nodes && !leaky; ++y)
    {
      leaky = bit(set, y) && rooms[y].leaky;
    }
    if (leaky)
    {
      ++stats.leakySources;
      seen.assign(nodes, 0);
      reachableNodes(g, static_cast<std::int32_t>(x), seen);
      for (std::size_t y = 0; y < nodes; ++y)
      {
        if (seen[y])
        {
          sets[x].push_back(static_cast<std::int32_t>(y));
        }
      }
    }
    else
    {
      for (std::size_t y = 0; y < nodes; ++y)
      {
        if (bit(set, y) && bit(&raw[y * NW], x))
        {
          sets[x].push_back(static_cast<std::int32_t>(y));
        }
      }
    }
    totalSize += sets[x].size();
  }
  stats.averageSetSize = nodes ? double(totalSize) / double(nodes) : 0.0;
  return PortalPvs::fromSets(g, std::move(sets));
}

} // namespace portals
} // namespace scenevis

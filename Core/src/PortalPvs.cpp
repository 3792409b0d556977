#include "scenevis/PortalPvs.h"

#include "scenevis/PortalGeometry.h"

#include "PortalPvsInternal.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <fstream>
#include <sstream>

namespace scenevis
{
namespace portals
{

namespace
{
/// A condition on every later portal: some point with distance > threshold to the plane.
struct Constraint
{
  glm::dvec4 plane;
  double threshold;
};

double maxDistance(const std::vector<glm::dvec3>& polygon, const glm::dvec4& plane)
{
  double d = -std::numeric_limits<double>::infinity();
  for (const auto& p : polygon)
  {
    d = std::max(d, geometry::planeDistance(plane, p));
  }
  return d;
}

} // namespace

int portalOrientation(const PortalGraph& g, const GraphPortal& p)
{
  if (!p.planar)
  {
    return 0;
  }
  const glm::dvec3 n(p.plane);
  const double delta = std::max(1e-4 * p.bounds.diagonal(), 100.0 * g.tolerance());
  const glm::dvec3 plus = p.centroid + delta * n, minus = p.centroid - delta * n;
  int vote = 0;
  bool conflict = false;
  auto add = [&](int v)
  {
    if (v == 0)
    {
      return;
    }
    conflict = conflict || (vote != 0 && vote != v);
    vote = v;
  };
  if (p.nodeA < g.roomCount())
  {
    const bool ap = g.inside(p.nodeA, plus), am = g.inside(p.nodeA, minus);
    add(am && !ap ? 1 : (ap && !am ? -1 : 0));
  }
  if (p.nodeB < g.roomCount())
  {
    const bool bp = g.inside(p.nodeB, plus), bm = g.inside(p.nodeB, minus);
    add(bp && !bm ? 1 : (bm && !bp ? -1 : 0));
  }
  if (conflict)
  {
    return 0;
  }
  if (vote == 0 && p.nodeA < g.roomCount() && p.nodeB < g.roomCount())
  {
    // No parity evidence (rooms without polygons): the rooms' box centres, if they disagree.
    const Box& a = g.rooms()[static_cast<std::size_t>(p.nodeA)].bounds;
    const Box& b = g.rooms()[static_cast<std::size_t>(p.nodeB)].bounds;
    if (!a.empty() && !b.empty())
    {
      const double da = geometry::planeDistance(p.plane, a.center());
      const double db = geometry::planeDistance(p.plane, b.center());
      const double tol = 10.0 * g.tolerance();
      vote = da < -tol && db > tol ? 1 : (da > tol && db < -tol ? -1 : 0);
    }
  }
  return vote;
}

namespace
{
/**
 * Planes through an edge of one polygon and a vertex of the other that have @p from on their
 * negative side and @p to on their positive side (both weakly).
 */
void separatingPlanes(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to,
  double tol, std::vector<Constraint>& out)
{
  auto consider = [&](const std::vector<glm::dvec3>& edgeOwner,
                    const std::vector<glm::dvec3>& vertexOwner)
  {
    for (std::size_t e = 0; e < edgeOwner.size(); ++e)
    {
      const glm::dvec3& e0 = edgeOwner[e];
      const glm::dvec3& e1 = edgeOwner[(e + 1) % edgeOwner.size()];
      for (const glm::dvec3& v : vertexOwner)
      {
        glm::dvec3 n = glm::cross(e1 - e0, v - e0);
        const double len = glm::length(n);
        if (!(len > 1e-12 * glm::length(e1 - e0) * glm::length(v - e0)))
        {
          continue;
        }
        n /= len;
        glm::dvec4 plane(n, -glm::dot(n, e0));
        auto range = [&](const std::vector<glm::dvec3>& poly, double& lo, double& hi)
        {
          lo = std::numeric_limits<double>::infinity();
          hi = -lo;
          for (const auto& q : poly)
          {
            const double d = geometry::planeDistance(plane, q);
            lo = std::min(lo, d);
            hi = std::max(hi, d);
          }
        };
        double fLo, fHi, tLo, tHi;
        range(from, fLo, fHi);
        range(to, tLo, tHi);
        if (fHi <= tol && tLo >= -tol && (fLo < -tol || tHi > tol))
        {
          out.push_back({ plane, -tol });
        }
        else if (fLo >= -tol && tHi <= tol && (fHi > tol || tLo < -tol))
        {
          out.push_back({ -plane, -tol });
        }
      }
    }
  };
  consider(from, to);
  consider(to, from);
}

} // namespace

void reachableNodes(const PortalGraph& g, std::int32_t source, std::vector<char>& seen)
{
  std::vector<std::int32_t> queue{ source };
  seen[static_cast<std::size_t>(source)] = 1;
  while (!queue.empty())
  {
    const std::int32_t n = queue.back();
    queue.pop_back();
    for (const std::uint32_t pi : g.rooms()[static_cast<std::size_t>(n)].portals)
    {
      const std::int32_t m = g.portals()[pi].other(n);
      if (!seen[static_cast<std::size_t>(m)])
      {
        seen[static_cast<std::size_t>(m)] = 1;
        queue.push_back(m);
      }
    }
  }
}

namespace
{
PortalPvs computeSeparatingPlanes(const PortalGraph& g, const PvsOptions& options, PvsStats* statsOut)
{
  PvsStats stats;
  stats.method = PvsMethod::SeparatingPlanes;
  std::vector<std::vector<std::int32_t>> sets;
  const auto nodes = static_cast<std::size_t>(g.nodeCount());
  const double tol = 10.0 * g.tolerance();
  const auto& portals = g.portals();
  std::vector<int> side(portals.size());
  for (std::size_t i = 0; i < portals.size(); ++i)
  {
    side[i] = portalOrientation(g, portals[i]);
  }

  struct Frame
  {
    std::int32_t node;
    std::size_t next; ///< Position in the node's portal list.
  };
  std::vector<Frame> stack;
  std::vector<std::uint32_t> path;                 // portal per depth (depth 1 = path[0])
  std::vector<std::vector<Constraint>> levels;     // constraints added at each depth
  std::vector<char> seen(nodes);
  std::size_t totalSize = 0;
  sets.resize(nodes);
  for (std::size_t s = 0; s < nodes; ++s)
  {
    std::fill(seen.begin(), seen.end(), 0);
    seen[s] = 1;
    stack.assign(1, Frame{ static_cast<std::int32_t>(s), 0 });
    path.clear();
    levels.clear();
    std::size_t sequences = 0;
    bool everything = g.rooms()[s].leaky;
    stats.leakySources += everything ? 1 : 0;
    while (!stack.empty() && !everything)
    {
      Frame& top = stack.back();
      const auto& list = g.rooms()[static_cast<std::size_t>(top.node)].portals;
      if (top.next == list.size())
      {
        stack.pop_back();
        if (!path.empty())
        {
          path.pop_back();
          levels.pop_back();
        }
        continue;
      }
      const std::uint32_t pi = list[top.next++];
      const std::int32_t from = top.node;
      if (std::find(path.begin(), path.end(), pi) != path.end())
      {
        continue;
      }
      const GraphPortal& p = portals[pi];
      bool ok = true;
      if (p.planar)
      {
        for (std::size_t l = 0; l < levels.size() && ok; ++l)
        {
          for (const Constraint& c : levels[l])
          {
            if (!(maxDistance(p.hull, c.plane) > c.threshold))
            {
              ok = false;
              break;
            }
          }
        }
      }
      if (!ok)
      {
        ++stats.pruned;
        continue;
      }
      ++stats.sequences;
      const std::int32_t to = p.other(from);
      seen[static_cast<std::size_t>(to)] = 1;
      if (g.rooms()[static_cast<std::size_t>(to)].leaky)
      {
        everything = true;
        ++stats.leakySources;
        break;
      }
      if (++sequences > options.maxSequencesPerNode)
      {
        everything = true;
        ++stats.overBudget;
        break;
      }
      // Conditions this portal imposes on every later one.
      std::vector<Constraint> level;
      if (side[pi] != 0)
      {
        const double sign = (to == p.nodeB ? 1.0 : -1.0) * side[pi];
        level.push_back({ sign * p.plane, tol });
      }
      if (p.planar && !path.empty())
      {
        const GraphPortal& first = portals[path.front()];
        if (first.planar)
        {
          separatingPlanes(first.hull, p.hull, tol, level);
        }
        const GraphPortal& prev = portals[path.back()];
        if (path.size() >= 2 && prev.planar)
        {
          separatingPlanes(prev.hull, p.hull, tol, level);
        }
      }
      path.push_back(pi);
      levels.push_back(std::move(level));
      stack.push_back(Frame{ to, 0 });
    }
    if (everything)
    {
      std::fill(seen.begin(), seen.end(), 0);
      reachableNodes(g, static_cast<std::int32_t>(s), seen);
    }
    auto& set = sets[s];
    for (std::size_t n = 0; n < nodes; ++n)
    {
      if (seen[n])
      {
        set.push_back(static_cast<std::int32_t>(n));
      }
    }
    totalSize += set.size();
    if (options.progress && !options.progress(static_cast<double>(s + 1) / double(nodes)))
    {
      stats.cancelled = true;
      if (statsOut)
      {
        *statsOut = stats;
      }
      return PortalPvs();
    }
  }
  stats.averageSetSize = nodes ? static_cast<double>(totalSize) / double(nodes) : 0.0;
  if (statsOut)
  {
    *statsOut = stats;
  }
  return PortalPvs::fromSets(g, std::move(sets));
}
} // namespace

PortalPvs PortalPvs::fromSets(const PortalGraph& graph, std::vector<std::vector<std::int32_t>> sets)
{
  PortalPvs pvs;
  pvs.Sets = std::move(sets);
  pvs.Fingerprint = graph.fingerprint();
  return pvs;
}

PortalPvs PortalPvs::compute(const PortalGraph& g, const PvsOptions& options, PvsStats* statsOut)
{
  if (options.method == PvsMethod::SeparatingPlanes)
  {
    return computeSeparatingPlanes(g, options, statsOut);
  }
  PvsStats stats;
  PortalPvs pvs = computePortalFlow(g, options, stats);
  if (statsOut)
  {
    *statsOut = stats;
  }
  return pvs;
}

const std::vector<std::int32_t>& PortalPvs::visibleFrom(std::int32_t node) const
{
  static const std::vector<std::int32_t> none;
  if (node < 0 || node >= this->nodeCount())
  {
    return none;
  }
  return this->Sets[static_cast<std::size_t>(node)];
}

bool PortalPvs::visible(std::int32_t from, std::int32_t to) const
{
  const auto& set = this->visibleFrom(from);
  return std::binary_search(set.begin(), set.end(), to);
}

bool PortalPvs::save(const std::string& path, std::string* error) const
{
  std::ofstream out(path);
  if (!out)
  {
    if (error)
    {
      *error = "cannot open '" + path + "' for writing";
    }
    return false;
  }
  char hex[32];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(this->Fingerprint));
  out << "scenevis-pvs 1\nfingerprint " << hex << "\nnodes " << this->Sets.size() << "\n";
  for (std::size_t n = 0; n < this->Sets.size(); ++n)
  {
    out << n << ' ' << this->Sets[n].size();
    for (const std::int32_t v : this->Sets[n])
    {
      out << ' ' << v;
    }
    out << '\n';
  }
  out.flush();
  if (!out)
  {
    if (error)
    {
      *error = "write error on '" + path + "'";
    }
    return false;
  }
  return true;
}

bool PortalPvs::load(const std::string& path, const PortalGraph& graph, PortalPvs& result,
  std::string* error)
{
  auto fail = [error](const std::string& why)
  {
    if (error)
    {
      *error = why;
    }
    return false;
  };
  std::ifstream in(path);
  if (!in)
  {
    return fail("cannot open '" + path + "'");
  }
  std::string magic, key, hex;
  int version = 0;
  std::size_t nodes = 0;
  if (!(in >> magic >> version) || magic != "scenevis-pvs" || version != 1)
  {
    return fail("'" + path + "' is not a scenevis PVS file (version 1)");
  }
  if (!(in >> key >> hex) || key != "fingerprint" || !(in >> key >> nodes) || key != "nodes")
  {
    return fail("'" + path + "': malformed header");
  }
  const std::uint64_t fingerprint = std::strtoull(hex.c_str(), nullptr, 16);
  if (fingerprint != graph.fingerprint() || nodes != static_cast<std::size_t>(graph.nodeCount()))
  {
    return fail("'" + path + "' was computed for another portal graph (fingerprint or size)");
  }
  PortalPvs pvs;
  pvs.Fingerprint = fingerprint;
  pvs.Sets.resize(nodes);
  for (std::size_t n = 0; n < nodes; ++n)
  {
    std::size_t id = 0, count = 0;
    if (!(in >> id >> count) || id != n || count > nodes)
    {
      return fail("'" + path + "': malformed line for node " + std::to_string(n));
    }
    auto& set = pvs.Sets[n];
    set.resize(count);
    for (std::size_t k = 0; k < count; ++k)
    {
      if (!(in >> set[k]) || set[k] < 0 || static_cast<std::size_t>(set[k]) >= nodes)
      {
        return fail("'" + path + "': bad node id for node " + std::to_string(n));
      }
    }
    std::sort(set.begin(), set.end());
  }
  result = std::move(pvs);
  return true;
}

} // namespace portals
} // namespace scenevis

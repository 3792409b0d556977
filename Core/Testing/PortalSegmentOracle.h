#pragma once
// A sampling oracle of room-to-room visibility for tests: straight segments walked through the
// cells of a generated level. A segment proves that every two nodes it passes through see each
// other (the part of it between them is a line crossing only portals); one that meets a wall
// stops there. Valid for scenes whose rooms' cells (rooms[r].bounds) tile the level and whose
// portals lie in the faces they open (scenes::building(), scenes::maze()).
#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalGraph.h"
#include "scenevis/Scenes.h"

#include <glm/geometric.hpp>

#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace scenevis
{
namespace testing_support
{

class PortalSegmentOracle
{
public:
  PortalSegmentOracle(const scenes::BuildingScene& level, const portals::PortalGraph& graph)
    : Level(level)
    , Graph(graph)
    , Nodes(static_cast<std::size_t>(graph.nodeCount()))
    , Proven(Nodes * Nodes, 0)
  {
    this->Scale = std::max(graph.buildingBounds().diagonal(), 1.0);
  }

  /**
   * Walks from @p a in room @p room towards @p b and appends the nodes it enters to @p chain
   * (which starts with @p room). Stops at the end of the segment, at a wall, at the outside, and
   * where it would cross a cell's edge or a portal's rim (within 1e-6 of the level's size):
   * only clear crossings prove anything.
   */
  void walk(std::int32_t room, const glm::dvec3& a, const glm::dvec3& b,
    std::vector<std::int32_t>& chain) const
  {
    chain.assign(1, room);
    const glm::dvec3 dir = b - a;
    const double eps = 1e-6 * this->Scale;
    std::int32_t cur = room;
    for (int guard = 0; guard < 100000; ++guard)
    {
      const Box& box = this->Level.rooms[static_cast<std::size_t>(cur)].bounds;
      double first = std::numeric_limits<double>::infinity(), second = first;
      int axis = -1;
      for (int k = 0; k < 3; ++k)
      {
        if (dir[k] == 0.0)
        {
          continue;
        }
        const double t = ((dir[k] > 0.0 ? box.hi[k] : box.lo[k]) - a[k]) / dir[k];
        if (t < first)
        {
          second = first;
          first = t;
          axis = k;
        }
        else if (t < second)
        {
          second = t;
        }
      }
      if (axis < 0 || first >= 1.0)
      {
        return; // the segment ends in this room
      }
      if ((second - first) * glm::length(dir) < eps)
      {
        return; // through an edge or a corner of the cell
      }
      const glm::dvec3 q = a + first * dir;
      std::int32_t next = -1;
      for (const std::uint32_t pi : this->Graph.rooms()[static_cast<std::size_t>(cur)].portals)
      {
        const portals::GraphPortal& p = this->Graph.portals()[pi];
        const glm::dvec3 n(p.plane);
        if (std::abs(n[axis]) < 0.999 || std::abs(portals::geometry::planeDistance(p.plane, q)) > eps)
        {
          continue;
        }
        if (portals::geometry::insideConvex(p.hull, n, q, -eps))
        {
          next = p.other(cur);
          break;
        }
      }
      if (next < 0)
      {
        return; // a wall
      }
      chain.push_back(next);
      if (next >= this->Graph.roomCount())
      {
        return; // the outside: the level is a box, nothing is entered again
      }
      cur = next;
    }
  }

  /// Samples @p count segments (see the .cpp of the tests) and records the pairs they prove.
  void sample(std::size_t count, std::uint64_t seed)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto rooms = static_cast<std::uint64_t>(this->Level.rooms.size());
    std::vector<std::int32_t> chain;
    auto pointIn = [&](const Box& box)
    {
      glm::dvec3 p;
      for (int k = 0; k < 3; ++k)
      {
        p[k] = box.lo[k] + (0.02 + 0.96 * u(rng)) * (box.hi[k] - box.lo[k]);
      }
      return p;
    };
    for (std::size_t i = 0; i < count; ++i)
    {
      const auto room = static_cast<std::int32_t>(rng() % rooms);
      const glm::dvec3 a = pointIn(this->Level.rooms[static_cast<std::size_t>(room)].bounds);
      glm::dvec3 b;
      const auto& own = this->Graph.rooms()[static_cast<std::size_t>(room)].portals;
      if (i % 3 != 0 && !own.empty())
      {
        // Through a random point of one of the room's portals, and far beyond: long sight lines.
        const auto& hull = this->Graph.portals()[own[rng() % own.size()]].hull;
        const std::size_t k = 1 + rng() % (hull.size() - 2);
        double s = u(rng), t = u(rng);
        if (s + t > 1.0)
        {
          s = 1.0 - s;
          t = 1.0 - t;
        }
        const glm::dvec3 on = hull[0] + s * (hull[k] - hull[0]) + t * (hull[k + 1] - hull[0]);
        b = a + (on - a) * (1.0 + 200.0 * u(rng) * u(rng));
      }
      else
      {
        b = pointIn(this->Level.rooms[rng() % rooms].bounds);
      }
      this->walk(room, a, b, chain);
      this->Segments += chain.size() > 1 ? 1 : 0;
      for (std::size_t x = 0; x < chain.size(); ++x)
      {
        for (std::size_t y = x + 1; y < chain.size(); ++y)
        {
          this->prove(chain[x], chain[y]);
        }
      }
    }
  }

  bool proven(std::int32_t from, std::int32_t to) const
  {
    return this->Proven[static_cast<std::size_t>(from) * this->Nodes + static_cast<std::size_t>(to)] != 0;
  }
  std::size_t provenPairs() const
  {
    std::size_t n = 0;
    for (const char c : this->Proven)
    {
      n += c ? 1 : 0;
    }
    return n;
  }
  /// Segments that crossed at least one portal.
  std::size_t crossingSegments() const { return this->Segments; }

private:
  void prove(std::int32_t x, std::int32_t y)
  {
    this->Proven[static_cast<std::size_t>(x) * this->Nodes + static_cast<std::size_t>(y)] = 1;
    this->Proven[static_cast<std::size_t>(y) * this->Nodes + static_cast<std::size_t>(x)] = 1;
  }

  const scenes::BuildingScene& Level;
  const portals::PortalGraph& Graph;
  std::size_t Nodes = 0;
  std::vector<char> Proven;
  double Scale = 1.0;
  std::size_t Segments = 0;
};

} // namespace testing_support
} // namespace scenevis

// Specification of cells-and-portals visibility: graph validation, eye location, the traversal in
// both narrowing modes (corridor, corner, cycles, eye on a portal, portal behind the eye,
// outside), the PVS and its file, and conservativeness against a ray-cast oracle.
#include "AxisQuad.h"
#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalGraph.h"
#include "scenevis/PortalPvs.h"
#include "scenevis/PortalTraversal.h"
#include "scenevis/Scenes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace scenevis;
using namespace scenevis::portals;

namespace
{

const NarrowingMode kModes[] = { NarrowingMode::ScreenRectangles, NarrowingMode::ExactFrustum };

/// A scene of axis-aligned box rooms with zero-thickness walls and rectangular holes.
struct BoxRooms
{
  PolygonMesh mesh;
  std::vector<std::int32_t> room;
  std::vector<PortalDesc> portals;
  std::vector<Box> rooms;
  struct Hole
  {
    int axis;
    double at;
    glm::dvec3 lo, hi;
  };
  std::vector<std::vector<Hole>> holes;

  int addRoom(const glm::dvec3& lo, const glm::dvec3& hi)
  {
    Box b;
    b.extend(lo);
    b.extend(hi);
    rooms.push_back(b);
    holes.emplace_back();
    return static_cast<int>(rooms.size()) - 1;
  }
  /// An axis-aligned rectangular portal in the plane coordinate[axis] == at.
  void addPortal(int a, int b, int axis, double at, glm::dvec3 lo, glm::dvec3 hi)
  {
    lo[axis] = hi[axis] = at;
    std::vector<glm::dvec3> quad;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int k = 0; k < 4; ++k)
    {
      glm::dvec3 p = lo;
      p[u] = (k == 1 || k == 2) ? hi[u] : lo[u];
      p[v] = (k >= 2) ? hi[v] : lo[v];
      quad.push_back(p);
    }
    portals.push_back(PortalDesc{ quad, a, b });
    for (const int r : { a, b })
    {
      if (r >= 0)
      {
        holes[static_cast<std::size_t>(r)].push_back(Hole{ axis, at, lo, hi });
      }
    }
  }
  void quad(int r, int axis, double at, double u0, double u1, double v0, double v1)
  {
    if (u1 - u0 <= 0 || v1 - v0 <= 0)
    {
      return;
    }
    scenevis::portaltest::addAxisQuad(mesh, axis, at, true, u0, u1, v0, v1);
    room.push_back(r);
  }
  /// Emit the faces of every room, each split around its (at most one) hole.
  CellSceneInput finish()
  {
    for (std::size_t r = 0; r < rooms.size(); ++r)
    {
      const Box& b = rooms[r];
      for (int axis = 0; axis < 3; ++axis)
      {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (const double at : { b.lo[axis], b.hi[axis] })
        {
          const Hole* hole = nullptr;
          for (const Hole& h : holes[r])
          {
            if (h.axis == axis && h.at == at)
            {
              hole = &h;
            }
          }
          const auto ri = static_cast<int>(r);
          if (!hole)
          {
            quad(ri, axis, at, b.lo[u], b.hi[u], b.lo[v], b.hi[v]);
            continue;
          }
          quad(ri, axis, at, b.lo[u], b.hi[u], b.lo[v], hole->lo[v]);
          quad(ri, axis, at, b.lo[u], b.hi[u], hole->hi[v], b.hi[v]);
          quad(ri, axis, at, b.lo[u], hole->lo[u], hole->lo[v], hole->hi[v]);
          quad(ri, axis, at, hole->hi[u], b.hi[u], hole->lo[v], hole->hi[v]);
        }
      }
    }
    CellSceneInput in;
    in.mesh = &mesh;
    in.roomOfPolygon = room;
    in.portals = portals;
    return in;
  }
};

/// Corridor rooms 0-3 along x (5 x 4 x 3 each) with aligned doors at x = 5, 10, 15; room 4 north
/// of room 3 (door in y = 4), room 5 east of room 4 (door in x = 20): around two corners.
BoxRooms corridor()
{
  BoxRooms s;
  for (int i = 0; i < 4; ++i)
  {
    s.addRoom({ 5.0 * i, 0, 0 }, { 5.0 * (i + 1), 4, 3 });
  }
  s.addRoom({ 15, 4, 0 }, { 20, 8, 3 });
  s.addRoom({ 20, 4, 0 }, { 25, 8, 3 });
  for (int i = 0; i < 3; ++i)
  {
    s.addPortal(i, i + 1, 0, 5.0 * (i + 1), { 0, 1.5, 0 }, { 0, 2.5, 2.1 });
  }
  s.addPortal(3, 4, 1, 4.0, { 17, 0, 0 }, { 18, 0, 2.1 });
  s.addPortal(4, 5, 0, 20.0, { 0, 5.5, 0 }, { 0, 6.5, 2.1 });
  return s;
}

/// A 2 x 2 ring of rooms (a cycle 0-1-3-2-0) with wide doors.
BoxRooms ring()
{
  BoxRooms s;
  s.addRoom({ 0, 0, 0 }, { 5, 5, 3 });
  s.addRoom({ 5, 0, 0 }, { 10, 5, 3 });
  s.addRoom({ 0, 5, 0 }, { 5, 10, 3 });
  s.addRoom({ 5, 5, 0 }, { 10, 10, 3 });
  s.addPortal(0, 1, 0, 5.0, { 0, 1, 0 }, { 0, 4, 2.1 });
  s.addPortal(0, 2, 1, 5.0, { 1, 0, 0 }, { 4, 0, 2.1 });
  s.addPortal(1, 3, 1, 5.0, { 5.5, 0, 0 }, { 9.5, 0, 2.1 });
  s.addPortal(2, 3, 0, 5.0, { 0, 5.5, 0 }, { 0, 9.5, 2.1 });
  return s;
}

PortalView lookAt(const glm::dvec3& eye, const glm::dvec3& target, double fovy = 60.0,
  double znear = 0.05, double zfar = 200.0)
{
  const glm::dvec3 dir = glm::normalize(target - eye);
  const glm::dvec3 up = std::abs(dir.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  PortalView v;
  v.clipFromWorld =
    glm::perspective(glm::radians(fovy), 1.0, znear, zfar) * glm::lookAt(eye, target, up);
  v.eye = eye;
  return v;
}

Box box(const glm::dvec3& lo, const glm::dvec3& hi)
{
  Box b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

std::set<std::int32_t> visibleSet(const PortalTraversal& t)
{
  return std::set<std::int32_t>(t.visibleNodes().begin(), t.visibleNodes().end());
}

TraversalOptions withMode(NarrowingMode mode)
{
  TraversalOptions o;
  o.mode = mode;
  return o;
}

/// Brute-force ray caster: the room of the first polygon hit by each pixel ray (depth >= near).
struct RayOracle
{
  const PolygonMesh& mesh;
  const std::vector<std::int32_t>& room;
  std::vector<glm::dvec4> planes;

  RayOracle(const PolygonMesh& m, const std::vector<std::int32_t>& r)
    : mesh(m)
    , room(r)
  {
    for (std::size_t i = 0; i < m.polygonCount(); ++i)
    {
      glm::dvec3 n = newellNormal(m.points.data(), m.polygon(i), m.polygonSize(i));
      n = glm::normalize(n);
      planes.emplace_back(n, -glm::dot(n, m.points[m.polygon(i)[0]]));
    }
  }
  bool inPolygon(std::size_t i, const glm::dvec3& q) const
  {
    const glm::dvec3 n(planes[i]);
    const std::uint32_t* ids = mesh.polygon(i);
    const std::uint32_t count = mesh.polygonSize(i);
    for (std::uint32_t k = 0; k < count; ++k)
    {
      const glm::dvec3& a = mesh.points[ids[k]];
      const glm::dvec3& b = mesh.points[ids[(k + 1) % count]];
      if (glm::dot(glm::cross(b - a, q - a), n) < 0.0)
      {
        return false;
      }
    }
    return true;
  }
  /// Visible polygons for @p view on a res x res pixel grid.
  std::set<std::size_t> visiblePolygons(const PortalView& view, double znear, int res) const
  {
    std::set<std::size_t> out;
    const glm::dmat4 inv = glm::inverse(view.clipFromWorld);
    const glm::dvec4 c0 = inv * glm::dvec4(0, 0, -1, 1);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(c0) / c0.w - view.eye);
    for (int j = 0; j < res; ++j)
    {
      for (int i = 0; i < res; ++i)
      {
        const double x = -1.0 + (2.0 * i + 1.0) / res, y = -1.0 + (2.0 * j + 1.0) / res;
        const glm::dvec4 f = inv * glm::dvec4(x, y, 1.0, 1.0);
        // Parallel projection: each ray starts on the near rectangle (no near test needed).
        const glm::dvec4 n = inv * glm::dvec4(x, y, -1.0, 1.0);
        const glm::dvec3 origin = view.parallel ? glm::dvec3(n) / n.w : view.eye;
        const glm::dvec3 dir = glm::normalize(glm::dvec3(f) / f.w - origin);
        double best = std::numeric_limits<double>::infinity();
        std::size_t hit = SIZE_MAX;
        for (std::size_t p = 0; p < planes.size(); ++p)
        {
          const double denom = glm::dot(glm::dvec3(planes[p]), dir);
          if (denom == 0.0)
          {
            continue;
          }
          const double t = -(glm::dot(glm::dvec3(planes[p]), origin) + planes[p].w) / denom;
          if (!(t > 0.0) || t >= best || (!view.parallel && t * glm::dot(dir, forward) < znear))
          {
            continue;
          }
          const glm::dvec3 q = origin + t * dir;
          if (inPolygon(p, q))
          {
            best = t;
            hit = p;
          }
        }
        if (hit != SIZE_MAX)
        {
          out.insert(hit);
        }
      }
    }
    return out;
  }
};

} // namespace

// --- Graph and validation ------------------------------------------------------------------------

TEST(PortalGraph, BuildingHasOneGraphPortalPerPortalAndNoIssues)
{
  const auto b = scenes::building(2, 3, 3, 7);
  PortalGraphReport report;
  const PortalGraph g = PortalGraph::build(cellSceneOf(b), &report);
  EXPECT_EQ(report.errors(), 0u) << report.summary();
  EXPECT_EQ(report.warnings(), 0u) << report.summary();
  EXPECT_EQ(g.roomCount(), 18);
  EXPECT_EQ(g.portals().size(), b.portals.size());
  EXPECT_FALSE(g.anyLeaky());
}

TEST(PortalGraph, InvalidPortalsAreReportedAndHandledConservatively)
{
  BoxRooms s = corridor();
  CellSceneInput in = s.finish();
  const std::size_t good = in.portals.size();
  in.portals.push_back(PortalDesc{ { { 1, 1, 1 }, { 2, 1, 1 } }, 0, 1 });             // 2 points
  in.portals.push_back(PortalDesc{ in.portals[0].polygon, 1, 57 });                  // dangling
  in.portals.push_back(PortalDesc{ in.portals[1].polygon, 2, 2 });                   // self
  in.portals.push_back(PortalDesc{ in.portals[0].polygon, 1, 0 });                   // duplicate
  in.portals.push_back(PortalDesc{ { { 10, 1.5, 0 }, { 10, 2.5, 0 }, { 10.5, 2.5, 2.1 },
                                     { 10, 1.5, 2.1 } },
    1, 2 }); // non-planar (x = 10.5)
  in.portals.push_back(PortalDesc{ { { 15, 1.0, 0 }, { 15, 3.0, 0 }, { 15, 3.0, 2.1 },
                                     { 15, 2.0, 1.0 }, { 15, 1.0, 2.1 } },
    2, 3 }); // concave (a notch)
  in.portals.push_back(PortalDesc{ { { 1, 1, 1 }, { 2, 2, 2 }, { 3, 3, 3 } }, 0, 1 }); // collinear
  in.portals.push_back(
    PortalDesc{ { { 1, 1, 1 }, { 2, 1, 1 }, { 1, std::nan(""), 1 } }, 0, 1 }); // non-finite
  PortalGraphReport report;
  const PortalGraph g = PortalGraph::build(in, &report);
  const std::string summary = report.summary();
  EXPECT_EQ(report.errors(), 4u) << summary;   // 2 points, dangling, collinear, non-finite
  EXPECT_EQ(report.warnings(), 3u) << summary; // self, duplicate, non-planar
  EXPECT_EQ(report.count(PortalIssue::Severity::Info), 1u) << summary; // concave
  EXPECT_NE(summary.find("dangling room id 57"), std::string::npos) << summary;
  EXPECT_NE(summary.find("not planar"), std::string::npos) << summary;
  EXPECT_NE(summary.find("duplicates portal 0"), std::string::npos) << summary;
  EXPECT_EQ(g.portals().size(), good + 2); // + non-planar + concave
  EXPECT_TRUE(g.rooms()[1].leaky);
  EXPECT_TRUE(g.rooms()[0].leaky); // the non-finite portal joined 0 and 1
  EXPECT_FALSE(g.rooms()[5].leaky);

  // Reaching a leaky room gives up narrowing: everything is potentially visible.
  PortalTraversal t;
  t.run(g, lookAt({ 2.5, 2, 1.5 }, { 30, 2, 1.5 }), TraversalOptions());
  EXPECT_EQ(t.stats().fallback, Fallback::LeakyRoom);
  EXPECT_TRUE(t.nodeVisible(5));
  // The PVS of a leaky room is everything reachable.
  const PortalPvs pvs = PortalPvs::compute(g);
  EXPECT_TRUE(pvs.visible(0, 5));
}

TEST(PortalGraph, RoomCountGivenMakesLargerIdsDangling)
{
  BoxRooms s = corridor();
  CellSceneInput in = s.finish();
  in.roomCount = 5; // room 5 exists in the geometry but not in the declared count
  PortalGraphReport report;
  const PortalGraph g = PortalGraph::build(in, &report);
  EXPECT_EQ(report.errors(), 1u) << report.summary();
  EXPECT_TRUE(g.rooms()[4].leaky);
}

TEST(PortalGraph, LocatesEyesInNonConvexAndOverlappingRooms)
{
  // An L-shaped room 0 (two boxes glued, one polygon set) and room 1 filling the L's notch.
  PolygonMesh mesh;
  std::vector<std::int32_t> rooms;
  auto poly = [&](std::initializer_list<glm::dvec3> pts, int r)
  {
    std::vector<std::uint32_t> ids;
    for (const auto& p : pts)
    {
      ids.push_back(mesh.addPoint(p));
    }
    mesh.addPolygon(ids.data(), ids.size());
    rooms.push_back(r);
  };
  // L: (0,0)-(10,0)-(10,4)-(4,4)-(4,10)-(0,10), height 3: floor, ceiling, 6 walls.
  const std::vector<glm::dvec2> l = { { 0, 0 }, { 10, 0 }, { 10, 4 }, { 4, 4 }, { 4, 10 },
    { 0, 10 } };
  auto prism = [&](const std::vector<glm::dvec2>& outline, int r)
  {
    std::vector<std::uint32_t> floorIds, ceilIds;
    for (const auto& p : outline)
    {
      floorIds.push_back(mesh.addPoint({ p.x, p.y, 0 }));
    }
    for (auto it = outline.rbegin(); it != outline.rend(); ++it)
    {
      ceilIds.push_back(mesh.addPoint({ it->x, it->y, 3 }));
    }
    mesh.addPolygon(floorIds.data(), floorIds.size());
    rooms.push_back(r);
    mesh.addPolygon(ceilIds.data(), ceilIds.size());
    rooms.push_back(r);
    for (std::size_t k = 0; k < outline.size(); ++k)
    {
      const auto& a = outline[k];
      const auto& b = outline[(k + 1) % outline.size()];
      poly({ { a.x, a.y, 0 }, { b.x, b.y, 0 }, { b.x, b.y, 3 }, { a.x, a.y, 3 } }, r);
    }
  };
  prism(l, 0);
  prism({ { 4, 4 }, { 10, 4 }, { 10, 10 }, { 4, 10 } }, 1);
  prism({ { 1, 1 }, { 3, 1 }, { 3, 3 }, { 1, 3 } }, 2); // overlaps room 0
  CellSceneInput in;
  in.mesh = &mesh;
  in.roomOfPolygon = rooms;
  const PortalGraph g = PortalGraph::build(in);
  EXPECT_TRUE(g.inside(0, { 2, 8, 1.5 }));
  EXPECT_TRUE(g.inside(0, { 8, 2, 1.5 }));
  EXPECT_FALSE(g.inside(0, { 7, 7, 1.5 })) << "the notch is inside the L's bounds only";
  EXPECT_TRUE(g.inside(1, { 7, 7, 1.5 }));
  EXPECT_FALSE(g.inside(1, { 2, 8, 1.5 }));
  const EyeLocation both = g.locate({ 2, 2, 1.5 }, 0.01);
  EXPECT_EQ(std::set<std::int32_t>(both.nodes.begin(), both.nodes.end()),
    (std::set<std::int32_t>{ 0, 2 }));
  // Outside the building's bounds: the outside node; inside the bounds but in no room: unknown.
  EXPECT_EQ(g.locate({ 20, 20, 1.5 }, 0.01).nodes, std::vector<std::int32_t>{ g.outsideNode() });
  EXPECT_FALSE(g.locate({ 5, 5, 5 }, 0.01).unknown); // above the roof: outside the bounds
  EXPECT_TRUE(g.locate({ 20, 20, 1.5 }, 0.01, OutsidePolicy::FrustumOnly).unknown);
}

TEST(PortalGraph, LocatesRandomEyesInTheGeneratedBuilding)
{
  const auto b = scenes::building(2, 4, 4, 3);
  const PortalGraph g = PortalGraph::build(cellSceneOf(b));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int correct = 0, wrong = 0;
  for (int i = 0; i < 400; ++i)
  {
    const auto r = static_cast<std::int32_t>(rng() % b.rooms.size());
    const Box& cell = b.rooms[static_cast<std::size_t>(r)].bounds;
    const glm::dvec3 p(cell.lo.x + 0.4 + u(rng) * (cell.hi.x - cell.lo.x - 0.8),
      cell.lo.y + 0.4 + u(rng) * (cell.hi.y - cell.lo.y - 0.8),
      cell.lo.z + 0.4 + u(rng) * (cell.hi.z - cell.lo.z - 0.8));
    const EyeLocation loc = g.locate(p, 0.0);
    correct += std::count(loc.nodes.begin(), loc.nodes.end(), r) ? 1 : 0;
    wrong += static_cast<int>(std::count_if(loc.nodes.begin(), loc.nodes.end(),
      [r](std::int32_t n) { return n != r; }));
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(correct, 360) << "misses only inside furniture and stair steps";
}

TEST(PortalGraph, GridLocateFindsWhatALinearScanFinds)
{
  // locate() tests only the rooms and portals its grid lists near the eye; a brute-force scan
  // over every room (inside()) and every portal (distance) must find the same nodes.
  const auto b = scenes::building(3, 6, 5, 8);
  const PortalGraph g = PortalGraph::build(cellSceneOf(b));
  const glm::ivec3 dims = g.gridDimensions();
  const int cells = dims.x * dims.y * dims.z;
  EXPECT_GE(cells, g.roomCount() / 4);
  EXPECT_LE(cells, g.roomCount() * 4);
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box& bb = g.buildingBounds();
  int inRooms = 0, nearPortals = 0;
  for (int i = 0; i < 3000; ++i)
  {
    glm::dvec3 eye = bb.lo - glm::dvec3(1.0) +
      glm::dvec3(u(rng), u(rng), u(rng)) * (bb.hi - bb.lo + glm::dvec3(2.0));
    if (i % 3 == 0)
    {
      // On or next to a portal: the near-portal rule matters there.
      const GraphPortal& p = g.portals()[rng() % g.portals().size()];
      eye = p.centroid + (u(rng) - 0.5) * 0.2 * glm::dvec3(p.plane);
    }
    const double reach = i % 2 ? 0.07 : 0.0;
    std::set<std::int32_t> expected;
    for (std::int32_t r = 0; r < g.roomCount(); ++r)
    {
      if (g.inside(r, eye))
      {
        expected.insert(r);
        ++inRooms;
      }
    }
    for (const GraphPortal& p : g.portals())
    {
      if (geometry::distanceToConvex(p.hull, glm::dvec3(p.plane), eye) <=
        std::max(reach, g.tolerance()))
      {
        expected.insert(p.nodeA);
        expected.insert(p.nodeB);
        ++nearPortals;
      }
    }
    const EyeLocation loc = g.locate(eye, reach, OutsidePolicy::FrustumOnly);
    EXPECT_EQ(std::set<std::int32_t>(loc.nodes.begin(), loc.nodes.end()), expected)
      << "eye (" << eye.x << ", " << eye.y << ", " << eye.z << ")";
    EXPECT_EQ(loc.nodes.size(), expected.size()) << "no duplicates";
  }
  EXPECT_GT(inRooms, 1000);
  EXPECT_GT(nearPortals, 300);
}

// --- Traversal ----------------------------------------------------------------------------------

TEST(PortalTraversal, StraightCorridorVisibleThroughAlignedDoorsNotAroundTheCorner)
{
  BoxRooms s = corridor();
  const PortalGraph g = PortalGraph::build(s.finish());
  for (const NarrowingMode mode : kModes)
  {
    SCOPED_TRACE(mode == NarrowingMode::ExactFrustum ? "exact" : "rectangles");
    PortalTraversal t;
    t.run(g, lookAt({ 2.5, 2, 1.5 }, { 30, 2, 1.5 }), withMode(mode));
    EXPECT_EQ(t.stats().fallback, Fallback::None);
    EXPECT_EQ(visibleSet(t), (std::set<std::int32_t>{ 0, 1, 2, 3 }));
    EXPECT_TRUE(t.boxVisible(3, box({ 17, 1.8, 1 }, { 18, 2.2, 1.4 })));
    EXPECT_FALSE(t.boxVisible(3, box({ 17, 3.5, 1 }, { 18, 3.9, 1.4 }))) << "off the line of doors";
    // Looking the other way: only the room itself.
    t.run(g, lookAt({ 2.5, 2, 1.5 }, { -30, 2, 1.5 }), withMode(mode));
    EXPECT_EQ(visibleSet(t), (std::set<std::int32_t>{ 0 }));
    // From room 3 looking north through the side door: room 4, but room 5 is around a corner.
    t.run(g, lookAt({ 17.5, 2, 1.5 }, { 17.5, 30, 1.5 }, 90.0), withMode(mode));
    EXPECT_TRUE(t.nodeVisible(4));
    EXPECT_FALSE(t.nodeVisible(5));
    EXPECT_FALSE(t.nodeVisible(0));
  }
}

TEST(PortalTraversal, EntryPlanesSkipTheWayBackAndAReusedTraversalMatchesAFreshOne)
{
  BoxRooms s = corridor();
  const PortalGraph g = PortalGraph::build(s.finish());
  for (const NarrowingMode mode : kModes)
  {
    SCOPED_TRACE(mode == NarrowingMode::ExactFrustum ? "exact" : "rectangles");
    PortalTraversal t;
    t.run(g, lookAt({ 2.5, 2, 1.5 }, { 30, 2, 1.5 }), withMode(mode));
    EXPECT_EQ(visibleSet(t), (std::set<std::int32_t>{ 0, 1, 2, 3 }));
    // From rooms 1..3 the door each came through is not tried again.
    EXPECT_GE(t.stats().portalsBehind, 3u);
  }
  // One traversal run frame after frame (it resets only the rooms the previous frame reached,
  // and clips each portal by the eye and far planes once per frame) answers as a fresh one.
  const auto b = scenes::building(3, 6, 6, 11);
  const PortalGraph big = PortalGraph::build(cellSceneOf(b));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const NarrowingMode mode : kModes)
  {
    PortalTraversal reused;
    for (int i = 0; i < 40; ++i)
    {
      const Box& cell = b.rooms[rng() % b.rooms.size()].bounds;
      const glm::dvec3 eye(cell.lo.x + 0.5 + u(rng) * 4.0, cell.lo.y + 0.5 + u(rng) * 3.0,
        cell.lo.z + 1.6);
      const double yaw = u(rng) * 6.283;
      const PortalView view =
        lookAt(eye, eye + glm::dvec3(std::cos(yaw), std::sin(yaw), 0.0), 70.0);
      PortalTraversal fresh;
      fresh.run(big, view, withMode(mode));
      reused.run(big, view, withMode(mode));
      ASSERT_EQ(visibleSet(reused), visibleSet(fresh)) << "view " << i;
      for (const std::int32_t node : fresh.visibleNodes())
      {
        ASSERT_EQ(reused.regionRectangles(node), fresh.regionRectangles(node));
      }
      if (i % 10 == 9)
      {
        reused.runFrustumOnly(big, view); // every node visible: the next frame resets them all
      }
    }
  }
}

TEST(PortalTraversal, AGraphRebuiltInPlaceWithMorePortalsIsNotReadThroughTheOldOnesCache)
{
  // vtkPortalCuller keeps its graph and its traversal side by side and rebuilds the graph in
  // place: the same address and node count, but here four more portals than the traversal's
  // per-portal cache was sized for.
  BoxRooms fewer = corridor();
  fewer.portals.resize(1);
  PortalGraph g = PortalGraph::build(fewer.finish());
  const PortalView view = lookAt({ 2.5, 2, 1.5 }, { 30, 2, 1.5 });
  PortalTraversal reused;
  reused.run(g, view, TraversalOptions());
  EXPECT_EQ(visibleSet(reused), (std::set<std::int32_t>{ 0, 1 }));
  BoxRooms more = corridor();
  const PortalGraph other = PortalGraph::build(more.finish());
  ASSERT_EQ(other.nodeCount(), g.nodeCount());
  ASSERT_GT(other.portals().size(), g.portals().size());
  g = other;
  reused.run(g, view, TraversalOptions());
  PortalTraversal fresh;
  fresh.run(g, view, TraversalOptions());
  EXPECT_EQ(visibleSet(reused), visibleSet(fresh));
  EXPECT_EQ(visibleSet(fresh).count(3), 1u); // down the corridor, through the new portals
}

TEST(PortalTraversal, CyclesTerminateAndARoomReachedTwiceGetsBothRegions)
{
  BoxRooms s = ring();
  const PortalGraph g = PortalGraph::build(s.finish());
  for (const NarrowingMode mode : kModes)
  {
    SCOPED_TRACE(mode == NarrowingMode::ExactFrustum ? "exact" : "rectangles");
    PortalTraversal t;
    t.run(g, lookAt({ 1, 1, 1.5 }, { 10, 10, 1.5 }, 100.0), withMode(mode));
    EXPECT_EQ(visibleSet(t), (std::set<std::int32_t>{ 0, 1, 2, 3 }));
    EXPECT_LT(t.stats().regionsExpanded, 40u);
    EXPECT_GE(t.regionRectangles(3).size(), 2u) << "reached through 1 and through 2";
    // Seen only via room 1, only via room 2; the far corner is hidden by the walls.
    EXPECT_TRUE(t.boxVisible(3, box({ 9.3, 5.9, 1.4 }, { 9.7, 6.3, 1.6 })));
    EXPECT_TRUE(t.boxVisible(3, box({ 5.9, 9.3, 1.4 }, { 6.3, 9.7, 1.6 })));
    if (mode == NarrowingMode::ExactFrustum)
    {
      EXPECT_FALSE(t.boxVisible(3, box({ 8.6, 8.6, 1.4 }, { 9.4, 9.4, 1.6 })));
    }
  }
  // Bigger graphs with many cycles: bounded work for every eye.
  const auto b = scenes::building(3, 6, 6, 11);
  const PortalGraph big = PortalGraph::build(cellSceneOf(b));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 50; ++i)
  {
    const Box& cell = b.rooms[rng() % b.rooms.size()].bounds;
    const glm::dvec3 eye(cell.lo.x + 0.5 + u(rng) * 4.0, cell.lo.y + 0.5 + u(rng) * 3.0,
      cell.lo.z + 1.6);
    const double yaw = u(rng) * 6.283;
    for (const NarrowingMode mode : kModes)
    {
      PortalTraversal t;
      t.run(big, lookAt(eye, eye + glm::dvec3(std::cos(yaw), std::sin(yaw), 0.0), 70.0),
        withMode(mode));
      EXPECT_LT(t.stats().regionsExpanded, 2000u);
    }
  }
}

TEST(PortalTraversal, EyeOnAPortalPlanePassesTheWholeFrustum)
{
  BoxRooms s = corridor();
  const PortalGraph g = PortalGraph::build(s.finish());
  for (const NarrowingMode mode : kModes)
  {
    PortalTraversal t;
    // Standing in the doorway between rooms 0 and 1, looking along the corridor and back.
    t.run(g, lookAt({ 5, 2, 1.5 }, { 30, 2, 1.5 }), withMode(mode));
    EXPECT_EQ(t.stats().fallback, Fallback::None);
    EXPECT_TRUE(t.nodeVisible(0));
    EXPECT_TRUE(t.nodeVisible(1));
    EXPECT_TRUE(t.nodeVisible(3));
    t.run(g, lookAt({ 5, 2, 1.5 }, { -30, 2, 1.5 }), withMode(mode));
    EXPECT_TRUE(t.nodeVisible(0));
    // Just in front of the doorway (closer than the near plane reaches): both rooms start.
    t.run(g, lookAt({ 4.97, 2, 1.5 }, { 4.97, 30, 1.5 }), withMode(mode));
    EXPECT_TRUE(t.nodeVisible(1));
  }
  // Edge-on: in the ring, an eye in room 0 at y = 5 - 1e-12 lies (within tolerance) in the
  // plane y = 5 of door 1-3, which it sees edge-on through door 0-1: passed on un-narrowed.
  const PortalGraph r = PortalGraph::build(ring().finish());
  for (const NarrowingMode mode : kModes)
  {
    PortalTraversal t;
    t.run(r, lookAt({ 0.5, 5.0 - 1e-12, 1.0 }, { 9, 5.0 - 1e-12, 1.0 }, 60.0, 0.001),
      withMode(mode));
    EXPECT_EQ(t.stats().startRooms, 1u);
    EXPECT_TRUE(t.nodeVisible(1));
    EXPECT_TRUE(t.nodeVisible(3));
  }
}

TEST(PortalTraversal, AnEdgeOnPortalIsCrossedOnlyWithinTheFrustum)
{
  // Rooms 0 | 1 side by side through a door as high as the wall's top (x = 5, y up to 5), room 2
  // beyond room 1's top (door at y = 5, x 5.5 to 9.5). The eye in room 0 lies in the plane
  // y = 5: door 1-2 is edge-on, attached without clipping, so only the box tests before it decide
  // whether it is crossed; the far plane at 4.9 from the eye (x = 5.4) leaves all of it out.
  BoxRooms s;
  s.addRoom({ 0, 0, 0 }, { 5, 5, 3 });
  s.addRoom({ 5, 0, 0 }, { 10, 5, 3 });
  s.addRoom({ 5, 5, 0 }, { 10, 10, 3 });
  s.addPortal(0, 1, 0, 5.0, { 0, 1, 0 }, { 0, 5, 2.5 });
  s.addPortal(1, 2, 1, 5.0, { 5.5, 0, 0 }, { 9.5, 0, 2.1 });
  const PortalGraph g = PortalGraph::build(s.finish());
  const glm::dvec3 eye(0.5, 5.0 - 1e-12, 1.0), ahead(9.0, 5.0 - 1e-12, 1.0);
  for (const NarrowingMode mode : kModes)
  {
    SCOPED_TRACE(mode == NarrowingMode::ExactFrustum ? "exact" : "rectangles");
    PortalTraversal t;
    t.run(g, lookAt(eye, ahead, 60.0, 0.001, 200.0), withMode(mode));
    EXPECT_EQ(t.stats().fallback, Fallback::None);
    EXPECT_EQ(visibleSet(t), (std::set<std::int32_t>{ 0, 1, 2 })) << "far plane at 200";
    t.run(g, lookAt(eye, ahead, 60.0, 0.001, 4.9), withMode(mode));
    EXPECT_EQ(visibleSet(t), (std::set<std::int32_t>{ 0, 1 })) << "far plane at 4.9";
  }
}

TEST(PortalTraversal, PortalPartlyBehindTheEyeIsClippedAtTheEyePlane)
{
  BoxRooms s = corridor();
  const PortalGraph g = PortalGraph::build(s.finish());
  for (const NarrowingMode mode : kModes)
  {
    SCOPED_TRACE(mode == NarrowingMode::ExactFrustum ? "exact" : "rectangles");
    PortalTraversal t;
    // In room 1, 0.3 from door 0-1 (x = 5), looking +y: half the door is behind the eye plane.
    t.run(g, lookAt({ 5.3, 2, 1.5 }, { 5.3, 30, 1.5 }, 90.0), withMode(mode));
    EXPECT_TRUE(t.nodeVisible(0));
    // A box in room 0 along a ray through the front half of the door.
    EXPECT_TRUE(t.boxVisible(0, box({ 3.9, 3.7, 1.4 }, { 4.1, 3.95, 1.6 })));
    // Entirely behind: looking +x from room 1, room 0 is not visible.
    t.run(g, lookAt({ 7.5, 2, 1.5 }, { 30, 2, 1.5 }), withMode(mode));
    EXPECT_FALSE(t.nodeVisible(0));
    EXPECT_TRUE(t.nodeVisible(3));
  }
}

TEST(PortalTraversal, OutsideTheBuildingEntersThroughWindowsOrFallsBack)
{
  const auto b = scenes::building(1, 3, 3, 2);
  const PortalGraph g = PortalGraph::build(cellSceneOf(b));
  PortalTraversal t;
  const glm::dvec3 eye(40, 1, 1.5);
  t.run(g, lookAt(eye, { 0, 0, 1.5 }), TraversalOptions());
  EXPECT_EQ(t.stats().fallback, Fallback::None);
  EXPECT_TRUE(t.nodeVisible(g.outsideNode()));
  // Rooms on the far (-x) side without a line of windows are hidden; some on the +x side seen.
  std::size_t rooms = 0;
  for (const std::int32_t n : t.visibleNodes())
  {
    rooms += n < g.roomCount() ? 1 : 0;
  }
  EXPECT_GT(rooms, 0u);
  // Looking away from the building: only the outside.
  t.run(g, lookAt(eye, { 80, 1, 1.5 }), TraversalOptions());
  EXPECT_EQ(visibleSet(t), (std::set<std::int32_t>{ g.outsideNode() }));
  TraversalOptions frustumOnly;
  frustumOnly.outside = OutsidePolicy::FrustumOnly;
  t.run(g, lookAt(eye, { 0, 0, 1.5 }), frustumOnly);
  EXPECT_EQ(t.stats().fallback, Fallback::EyeInNoRoom);
  EXPECT_TRUE(t.nodeVisible(4));
  // Inside a wall (within the building's bounds, in no room): frustum only.
  const Box& cell = b.rooms[0].bounds;
  t.run(g, lookAt({ cell.hi.x, cell.center().y + 1.2, 1.5 }, { 0, 30, 1.5 }), TraversalOptions());
  EXPECT_EQ(t.stats().fallback, Fallback::EyeInNoRoom);
}

TEST(PortalTraversal, ParallelProjectionFromOutsideEntersThroughWindows)
{
  // Orthographic views of the building from outside: rays start on the near rectangle, outside
  // the building, and enter rooms only through windows. Checked against parallel ray casting;
  // the near rectangle inside the building falls back to frustum-only culling.
  const auto b = scenes::building(2, 4, 3, 6);
  const PortalGraph g = PortalGraph::build(cellSceneOf(b));
  const PortalPvs pvs = PortalPvs::compute(g);
  const RayOracle oracle(b.mesh, b.room);
  std::vector<Box> roomGeometry(static_cast<std::size_t>(g.nodeCount()));
  for (std::size_t i = 0; i < b.mesh.polygonCount(); ++i)
  {
    for (std::uint32_t k = 0; k < b.mesh.polygonSize(i); ++k)
    {
      roomGeometry[static_cast<std::size_t>(g.nodeOf(b.room[i]))].extend(
        b.mesh.points[b.mesh.polygon(i)[k]]);
    }
  }
  auto orthoView = [](const glm::dvec3& eye, const glm::dvec3& target, double half, double znear)
  {
    PortalView v;
    v.clipFromWorld = glm::ortho(-half, half, -half, half, znear, 200.0) *
      glm::lookAt(eye, target, glm::dvec3(0, 0, 1));
    v.eye = eye;
    v.parallel = true;
    return v;
  };
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t seen = 0, drawn[3] = { 0, 0, 0 };
  for (int i = 0; i < 12; ++i)
  {
    // Around the building, slightly above or below the storeys, looking at a random point in it.
    const double yaw = u(rng) * 6.283185307, pitch = (u(rng) - 0.5) * 0.5;
    const glm::dvec3 eye = glm::dvec3(40.0 * std::cos(yaw) * std::cos(pitch),
      40.0 * std::sin(yaw) * std::cos(pitch), 3.0 + 40.0 * std::sin(pitch));
    const glm::dvec3 target((u(rng) - 0.5) * 8.0, (u(rng) - 0.5) * 6.0, 1.0 + u(rng) * 4.0);
    const PortalView view = orthoView(eye, target, 3.0 + u(rng) * 9.0, 1.0);
    std::set<std::int32_t> visibleNodes;
    for (const std::size_t p : oracle.visiblePolygons(view, 0.0, 64))
    {
      visibleNodes.insert(g.nodeOf(b.room[p]));
    }
    seen += visibleNodes.size();
    PortalTraversal t;
    for (int m = 0; m < 3; ++m)
    {
      if (m < 2)
      {
        t.run(g, view, withMode(kModes[m]));
      }
      else
      {
        t.runPvs(g, pvs, view, TraversalOptions());
      }
      ASSERT_EQ(t.stats().fallback, Fallback::None);
      EXPECT_EQ(t.stats().startRooms, 1u);
      for (const std::int32_t n : visibleNodes)
      {
        EXPECT_TRUE(t.boxVisible(n, roomGeometry[static_cast<std::size_t>(n)]))
          << "mode " << m << " view " << i << " misses node " << n;
      }
      for (std::int32_t n = 0; n < g.roomCount(); ++n)
      {
        drawn[m] += t.boxVisible(n, roomGeometry[static_cast<std::size_t>(n)]) ? 1 : 0;
      }
    }
  }
  EXPECT_GT(seen, 12u) << "the views see rooms through windows";
  EXPECT_LE(drawn[1], drawn[0]);
  EXPECT_LT(drawn[1], 12u * 24u * 3u / 4u) << "rooms behind walls are culled";
  std::printf("parallel views: rooms seen %zu, drawn: rectangles %zu, exact %zu, pvs %zu\n", seen,
    drawn[0], drawn[1], drawn[2]);

  // The near rectangle inside the building's bounds (an orthographic camera in a room): it may
  // cut through walls, so frustum only; likewise with the frustum-only outside policy.
  PortalTraversal t;
  t.run(g, orthoView({ 1.0, 1.0, 1.5 }, { 30, 1, 1.5 }, 2.0, 0.05), TraversalOptions());
  EXPECT_EQ(t.stats().fallback, Fallback::ParallelProjection);
  EXPECT_TRUE(t.nodeVisible(0));
  TraversalOptions frustumOnly;
  frustumOnly.outside = OutsidePolicy::FrustumOnly;
  t.run(g, orthoView({ 40, 1, 1.5 }, { 0, 1, 1.5 }, 5.0, 1.0), frustumOnly);
  EXPECT_EQ(t.stats().fallback, Fallback::ParallelProjection);
  // A parallel view along a wall sees its windows edge-on: passed on un-narrowed, still right.
  t.run(g,
    orthoView(
      { 40, b.portals[0].polygon[0].y, 1.5 }, { 0, b.portals[0].polygon[0].y, 1.5 }, 6.0, 1.0),
    withMode(NarrowingMode::ExactFrustum));
  EXPECT_EQ(t.stats().fallback, Fallback::None);
}

TEST(PortalTraversal, ConservativeAgainstRayCastingInTheGeneratedBuilding)
{
  const auto b = scenes::building(2, 3, 3, 4);
  const PortalGraph g = PortalGraph::build(cellSceneOf(b));
  const PortalPvs pvs = PortalPvs::compute(g);
  const RayOracle oracle(b.mesh, b.room);
  std::vector<Box> roomGeometry(static_cast<std::size_t>(g.nodeCount()));
  for (std::size_t i = 0; i < b.mesh.polygonCount(); ++i)
  {
    const std::int32_t node = g.nodeOf(b.room[i]);
    for (std::uint32_t k = 0; k < b.mesh.polygonSize(i); ++k)
    {
      roomGeometry[static_cast<std::size_t>(node)].extend(b.mesh.points[b.mesh.polygon(i)[k]]);
    }
  }
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t drawn[3] = { 0, 0, 0 }, seen = 0;
  int views = 0;
  for (int i = 0; i < 40; ++i)
  {
    const Box& cell = b.rooms[rng() % b.rooms.size()].bounds;
    const glm::dvec3 eye(cell.lo.x + 0.5 + u(rng) * 4.0, cell.lo.y + 0.5 + u(rng) * 3.0,
      cell.lo.z + 0.6 + u(rng) * 2.0);
    if (g.locate(eye, 0.0).nodes.empty())
    {
      continue; // inside furniture
    }
    ++views;
    const double yaw = u(rng) * 6.283, pitch = (u(rng) - 0.5) * 0.6;
    const glm::dvec3 dir(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch),
      std::sin(pitch));
    const PortalView view = lookAt(eye, eye + dir, 75.0, 0.05, 200.0);
    std::set<std::int32_t> visibleNodes;
    for (const std::size_t p : oracle.visiblePolygons(view, 0.05, 48))
    {
      visibleNodes.insert(g.nodeOf(b.room[p]));
    }
    seen += visibleNodes.size();
    PortalTraversal t;
    for (int m = 0; m < 3; ++m)
    {
      if (m < 2)
      {
        t.run(g, view, withMode(kModes[m]));
      }
      else
      {
        t.runPvs(g, pvs, view, TraversalOptions());
      }
      for (const std::int32_t n : visibleNodes)
      {
        EXPECT_TRUE(t.boxVisible(n, roomGeometry[static_cast<std::size_t>(n)]))
          << "mode " << m << " view " << i << " misses node " << n;
      }
      for (std::int32_t n = 0; n < g.nodeCount(); ++n)
      {
        drawn[m] += t.boxVisible(n, roomGeometry[static_cast<std::size_t>(n)]) ? 1 : 0;
      }
    }
  }
  ASSERT_GT(views, 20);
  // Tighter to looser: exact <= rectangles; all cull most rooms of the building.
  EXPECT_LE(drawn[1], drawn[0]);
  EXPECT_LT(drawn[0], static_cast<std::size_t>(views) * 19u / 2u);
  std::printf("rooms seen %zu, drawn: rectangles %zu, exact %zu, pvs %zu (over %d views)\n", seen,
    drawn[0], drawn[1], drawn[2], views);
}

// --- PVS ----------------------------------------------------------------------------------------

TEST(PortalPvs, CorridorAndCornerAndFileRoundTrip)
{
  BoxRooms s = corridor();
  const PortalGraph g = PortalGraph::build(s.finish());
  std::vector<double> progress;
  PvsOptions options;
  options.method = PvsMethod::SeparatingPlanes;
  options.progress = [&progress](double f)
  {
    progress.push_back(f);
    return true;
  };
  PvsStats stats;
  const PortalPvs pvs = PortalPvs::compute(g, options, &stats);
  ASSERT_FALSE(pvs.empty());
  EXPECT_EQ(progress.size(), static_cast<std::size_t>(g.nodeCount()));
  EXPECT_DOUBLE_EQ(progress.back(), 1.0);
  EXPECT_EQ(pvs.visibleFrom(0), (std::vector<std::int32_t>{ 0, 1, 2, 3 }))
    << "room 4 is behind a corner: no line passes the three doors and its door";
  EXPECT_TRUE(pvs.visible(3, 4));
  EXPECT_TRUE(pvs.visible(5, 4));
  EXPECT_FALSE(pvs.visible(5, 0));
  EXPECT_GT(stats.pruned, 0u);

  const std::string path = testing::TempDir() + "corridor.pvs";
  std::string error;
  ASSERT_TRUE(pvs.save(path, &error)) << error;
  PortalPvs loaded;
  ASSERT_TRUE(PortalPvs::load(path, g, loaded, &error)) << error;
  for (std::int32_t n = 0; n < g.nodeCount(); ++n)
  {
    EXPECT_EQ(loaded.visibleFrom(n), pvs.visibleFrom(n));
  }
  // Another graph: refused.
  const PortalGraph other = PortalGraph::build(ring().finish());
  EXPECT_FALSE(PortalPvs::load(path, other, loaded, &error));
  EXPECT_NE(error.find("another portal graph"), std::string::npos) << error;
  EXPECT_FALSE(PortalPvs::load(path + ".missing", g, loaded, &error));
  // Cancelled: empty.
  options.progress = [](double) { return false; };
  EXPECT_TRUE(PortalPvs::compute(g, options).empty());
}

TEST(PortalPvs, CorridorAndCornerWithPortalFlow)
{
  BoxRooms s = corridor();
  const PortalGraph g = PortalGraph::build(s.finish());
  for (const PvsMethod method : { PvsMethod::PortalFlow, PvsMethod::MightSee })
  {
    PvsOptions options;
    options.method = method;
    PvsStats stats;
    const PortalPvs pvs = PortalPvs::compute(g, options, &stats);
    ASSERT_FALSE(pvs.empty());
    EXPECT_EQ(stats.directedPortals, 2 * g.portals().size());
    EXPECT_TRUE(pvs.visible(0, 3));
    EXPECT_TRUE(pvs.visible(3, 4));
    EXPECT_TRUE(pvs.visible(5, 4));
    if (method == PvsMethod::PortalFlow)
    {
      EXPECT_FALSE(pvs.visible(5, 0)) << "two corners";
      EXPECT_EQ(pvs.visibleFrom(0), (std::vector<std::int32_t>{ 0, 1, 2, 3 }))
        << "room 4 is behind a corner: no line passes the three doors and its door";
    }
  }
}

// Specification of automatic rooms and portals (PortalGeneration.h): rooms found from walls with
// holes, one portal per doorway that covers the doorway, furniture and corridor corners inside a
// room, leaks reported, bad input answered with a status. Oracles: the rooms each test scene was
// built from (every polygon of a room must get one generated room, different rooms different
// ones) and the openings cut into its walls (every opening inside a portal joining its rooms).
#include "AxisQuad.h"
#include "scenevis/PortalGeneration.h"
#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalGraph.h"

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace scenevis;
using namespace scenevis::portals;

namespace
{

/// An axis-aligned rectangle in the plane coordinate[axis] == at: an opening in a wall.
struct Opening
{
  int axis = 0;
  double at = 0.0;
  glm::dvec3 lo{ 0.0 }, hi{ 0.0 }; ///< Corners (coordinate[axis] ignored).
  int roomA = 0, roomB = 0;        ///< Authored rooms; -1: the outside.
};

/**
 * Box rooms with zero-thickness walls: each room's six faces face into it (furniture faces out),
 * each face split around at most one rectangular hole; a hole as large as the face leaves no
 * polygon (rooms joined over a whole face make one room).
 */
struct ArchitectureSoup
{
  PolygonMesh mesh;
  std::vector<int> authoredRoom; ///< Per polygon.
  std::vector<Box> rooms;
  std::vector<Opening> openings;

  int room(const glm::dvec3& lo, const glm::dvec3& hi)
  {
    Box b;
    b.extend(lo);
    b.extend(hi);
    rooms.push_back(b);
    return static_cast<int>(rooms.size()) - 1;
  }
  void opening(int a, int b, int axis, double at, glm::dvec3 lo, glm::dvec3 hi)
  {
    lo[axis] = hi[axis] = at;
    openings.push_back(Opening{ axis, at, lo, hi, a, b });
  }
  void quad(int r, int axis, double at, bool positive, double u0, double u1, double v0, double v1)
  {
    if (u1 - u0 <= 0 || v1 - v0 <= 0)
    {
      return;
    }
    scenevis::portaltest::addAxisQuad(mesh, axis, at, positive, u0, u1, v0, v1);
    authoredRoom.push_back(r);
  }
  /// The six faces of @p b, normals into it (@p inward) or out of it, split around openings.
  void faces(int r, const Box& b, bool inward)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (const bool atLo : { true, false })
      {
        const double at = atLo ? b.lo[axis] : b.hi[axis];
        const bool positive = atLo == inward;
        const Opening* hole = nullptr;
        for (const Opening& o : openings)
        {
          if ((o.roomA == r || o.roomB == r) && o.axis == axis && o.at == at)
          {
            hole = &o;
          }
        }
        if (!hole)
        {
          quad(r, axis, at, positive, b.lo[u], b.hi[u], b.lo[v], b.hi[v]);
          continue;
        }
        const double hu0 = std::max(hole->lo[u], b.lo[u]), hu1 = std::min(hole->hi[u], b.hi[u]);
        const double hv0 = std::max(hole->lo[v], b.lo[v]), hv1 = std::min(hole->hi[v], b.hi[v]);
        quad(r, axis, at, positive, b.lo[u], b.hi[u], b.lo[v], hv0);
        quad(r, axis, at, positive, b.lo[u], b.hi[u], hv1, b.hi[v]);
        quad(r, axis, at, positive, b.lo[u], hu0, hv0, hv1);
        quad(r, axis, at, positive, hu1, b.hi[u], hv0, hv1);
      }
    }
  }
  void finish()
  {
    for (std::size_t r = 0; r < rooms.size(); ++r)
    {
      faces(static_cast<int>(r), rooms[r], true);
    }
  }
  /// A closed box standing in room @p r, facing out. Its faces lying on the room's walls or
  /// floor are hidden there: the oracle expects no particular room for them (authored room -2).
  void furniture(int r, const glm::dvec3& lo, const glm::dvec3& hi)
  {
    Box b;
    b.extend(lo);
    b.extend(hi);
    const std::size_t first = mesh.polygonCount();
    faces(r, b, false);
    const Box& walls = rooms[static_cast<std::size_t>(r)];
    for (std::size_t i = first; i < mesh.polygonCount(); ++i)
    {
      const glm::dvec3 n = newellNormal(mesh.points.data(), mesh.polygon(i), 4);
      const glm::dvec3& p = mesh.points[mesh.polygon(i)[0]];
      for (int axis = 0; axis < 3; ++axis)
      {
        if (n[axis] != 0.0 && (p[axis] == walls.lo[axis] || p[axis] == walls.hi[axis]))
        {
          authoredRoom[i] = -2;
        }
      }
    }
  }
};

GeneratedPortals generate(const PolygonMesh& mesh)
{
  GenerationInput in;
  in.mesh = &mesh;
  return generatePortals(in);
}

/// Generated room of each authored room: every polygon of one authored room must get the same
/// generated room, and different authored rooms different ones (else the test fails).
std::map<int, std::int32_t> roomMap(const ArchitectureSoup& s, const GeneratedPortals& g)
{
  std::map<int, std::set<std::int32_t>> seen;
  for (std::size_t i = 0; i < s.authoredRoom.size(); ++i)
  {
    if (s.authoredRoom[i] >= 0)
    {
      seen[s.authoredRoom[i]].insert(g.roomOfPolygon[i]);
    }
  }
  std::map<int, std::int32_t> map;
  std::set<std::int32_t> used;
  for (const auto& [authored, generated] : seen)
  {
    EXPECT_EQ(generated.size(), 1u) << "authored room " << authored << " split or mixed";
    map[authored] = *generated.begin();
    EXPECT_GE(map[authored], 0) << "authored room " << authored << " taken for the outside";
    EXPECT_TRUE(used.insert(map[authored]).second)
      << "authored room " << authored << " merged with another";
  }
  return map;
}

/// Whether @p point lies in the portal's plane (within @p tol) and inside its convex polygon.
bool portalCovers(const PortalDesc& portal, const glm::dvec3& point, double tol)
{
  const glm::dvec3 n = glm::normalize(geometry::newellOf(portal.polygon));
  if (std::abs(glm::dot(n, point - portal.polygon[0])) > tol)
  {
    return false;
  }
  std::vector<glm::dvec3> ccw = planarConvexHull(portal.polygon, n);
  return geometry::insideConvex(ccw, n, point, tol);
}

/// Every authored opening lies inside one generated portal joining the generated rooms of its
/// two authored rooms (conservativeness: a portal is never smaller than its opening).
void expectOpeningsCovered(const ArchitectureSoup& s, const GeneratedPortals& g, double tol = 1e-6)
{
  const auto rooms = roomMap(s, g);
  for (std::size_t k = 0; k < s.openings.size(); ++k)
  {
    const Opening& o = s.openings[k];
    const std::int32_t a = o.roomA < 0 ? kOutsideRoom : rooms.at(o.roomA);
    const std::int32_t b = o.roomB < 0 ? kOutsideRoom : rooms.at(o.roomB);
    std::vector<glm::dvec3> corners;
    const int u = (o.axis + 1) % 3, v = (o.axis + 2) % 3;
    for (int c = 0; c < 4; ++c)
    {
      glm::dvec3 p = o.lo;
      p[u] = (c & 1) ? o.hi[u] : o.lo[u];
      p[v] = (c & 2) ? o.hi[v] : o.lo[v];
      corners.push_back(p);
    }
    bool covered = false;
    for (const PortalDesc& p : g.portals)
    {
      const bool joins = (p.roomA == a && p.roomB == b) || (p.roomA == b && p.roomB == a);
      bool all = joins;
      for (const glm::dvec3& c : corners)
      {
        all = all && portalCovers(p, c, tol);
      }
      covered = covered || all;
    }
    EXPECT_TRUE(covered) << "opening " << k << " (rooms " << o.roomA << ", " << o.roomB
                         << ") not inside a portal joining them";
  }
}

double area(const std::vector<glm::dvec3>& polygon)
{
  return 0.5 * glm::length(geometry::newellOf(polygon));
}

/// Rooms 5 x 4 x 3 along x, doors 1 x 2.1 in the walls between them.
ArchitectureSoup rowOfRooms(int n)
{
  ArchitectureSoup s;
  for (int i = 0; i < n; ++i)
  {
    s.room({ 5.0 * i, 0, 0 }, { 5.0 * (i + 1), 4, 3 });
  }
  for (int i = 0; i + 1 < n; ++i)
  {
    s.opening(i, i + 1, 0, 5.0 * (i + 1), { 0, 1.5, 0 }, { 0, 2.5, 2.1 });
  }
  return s;
}

/// Checks of a scene whose only leaks would be its exterior openings: status Ok, no leak, @p rooms
/// rooms, each authored room one generated room of its own (never the outside), @p exterior
/// exterior portals, and every opening inside a portal joining its rooms.
void expectClosedRoomsWithExteriorPortals(
  const ArchitectureSoup& s, const GeneratedPortals& g, int rooms, std::size_t exterior)
{
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.statistics.leakCells, 0u);
  EXPECT_TRUE(g.leakPoints.empty());
  EXPECT_EQ(g.roomCount, rooms);
  EXPECT_EQ(g.statistics.exteriorPortals, exterior);
  expectOpeningsCovered(s, g);
}

/// @p s turned about the z axis by @p quarterTurns quarter turns ((x, y) -> (-y, x) each): the
/// same scene with its walls in other BSP nodes.
ArchitectureSoup turned(ArchitectureSoup s, int quarterTurns)
{
  auto turn = [quarterTurns](glm::dvec3 p)
  {
    for (int k = 0; k < quarterTurns; ++k)
    {
      p = glm::dvec3(-p.y, p.x, p.z);
    }
    return p;
  };
  for (glm::dvec3& p : s.mesh.points)
  {
    p = turn(p);
  }
  for (Box& b : s.rooms)
  {
    Box t;
    t.extend(turn(b.lo));
    t.extend(turn(b.hi));
    b = t;
  }
  for (Opening& o : s.openings)
  {
    const glm::dvec3 a = turn(o.lo), b = turn(o.hi);
    o.lo = glm::min(a, b);
    o.hi = glm::max(a, b);
    o.axis = quarterTurns % 2 == 0 || o.axis == 2 ? o.axis : 1 - o.axis;
    o.at = o.lo[o.axis];
  }
  return s;
}

/// A 10 x 4 x 3 room with a 1 x 2.1 door from the floor in its end wall x = 10, the wall
/// @p thickness thick: a second face at x = 10 + thickness facing out, the door's jambs, lintel
/// and threshold between the two faces and the wall's four end caps (all authored room -2: the
/// oracle expects no particular room for them). The opening is the door in the room's own face.
/// (Long and narrow on purpose: in a smaller room's wall plane, the open ring around the
/// building, if grouped with the door, has enough of its outline against the wall to pass.)
ArchitectureSoup roomWithAnExteriorDoor(double thickness)
{
  ArchitectureSoup s;
  s.room({ 0, 0, 0 }, { 10, 4, 3 });
  s.opening(0, -1, 0, 10.0, { 0, 1.5, 0 }, { 0, 2.5, 2.1 });
  s.finish();
  if (thickness > 0.0)
  {
    const double x0 = 10.0, x1 = 10.0 + thickness;
    s.quad(-2, 0, x1, true, 0, 4, 2.1, 3); // outer face, above the door
    s.quad(-2, 0, x1, true, 0, 1.5, 0, 2.1);
    s.quad(-2, 0, x1, true, 2.5, 4, 0, 2.1);
    s.quad(-2, 1, 1.5, true, 0, 2.1, x0, x1); // jambs, facing into the doorway
    s.quad(-2, 1, 2.5, false, 0, 2.1, x0, x1);
    s.quad(-2, 2, 2.1, false, x0, x1, 1.5, 2.5); // lintel
    s.quad(-2, 2, 0.0, true, x0, x1, 1.5, 2.5);  // threshold
    s.quad(-2, 1, 0.0, false, 0, 3, x0, x1);     // end caps, facing out
    s.quad(-2, 1, 4.0, true, 0, 3, x0, x1);
    s.quad(-2, 2, 3.0, true, x0, x1, 0, 4);
    s.quad(-2, 2, 0.0, false, x0, x1, 0, 1.5);
    s.quad(-2, 2, 0.0, false, x0, x1, 2.5, 4);
  }
  return s;
}

} // namespace

TEST(PortalGeneration, TwoRoomsJoinedByADoorGiveTwoRoomsAndOnePortalCoveringTheDoor)
{
  ArchitectureSoup s = rowOfRooms(2);
  s.finish();
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.roomCount, 2);
  ASSERT_EQ(g.portals.size(), 1u);
  EXPECT_EQ(g.statistics.leakCells, 0u);
  EXPECT_EQ(g.statistics.exteriorPortals, 0u);
  expectOpeningsCovered(s, g);
  // Not the whole wall either: the portal is the door (the wall is 4 x 3, the door 1 x 2.1).
  EXPECT_GE(area(g.portals[0].polygon), 2.1 - 1e-9);
  EXPECT_LT(area(g.portals[0].polygon), 0.5 * 12.0);
}

TEST(PortalGeneration, ARowOfRoomsGivesOneRoomEachAndAPortalPerDoor)
{
  for (const int n : { 3, 6 })
  {
    ArchitectureSoup s = rowOfRooms(n);
    s.finish();
    const GeneratedPortals g = generate(s.mesh);
    ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
    EXPECT_EQ(g.roomCount, n);
    EXPECT_EQ(g.portals.size(), static_cast<std::size_t>(n - 1));
    expectOpeningsCovered(s, g);
    // The graph built from the generated scene is valid.
    PortalGraphReport report;
    PortalGraph::build(g.cellScene(s.mesh), &report);
    EXPECT_EQ(report.errors(), 0u) << report.summary();
  }
}

TEST(PortalGeneration, AnLShapedCorridorIsOneRoomBetweenItsDoors)
{
  ArchitectureSoup s;
  const int west = s.room({ -4, -1, 0 }, { 0, 3, 3 });
  const int leg1 = s.room({ 0, 0, 0 }, { 10, 2, 3 });
  const int leg2 = s.room({ 8, 2, 0 }, { 10, 10, 3 });
  const int north = s.room({ 7, 10, 0 }, { 11, 14, 3 });
  s.opening(west, leg1, 0, 0.0, { 0, 0.5, 0 }, { 0, 1.5, 2.1 });
  s.opening(leg2, north, 1, 10.0, { 8.5, 0, 0 }, { 9.5, 0, 2.1 });
  // The legs share a whole face: no wall between them.
  s.opening(leg1, leg2, 1, 2.0, { 8, 0, 0 }, { 10, 0, 3 });
  s.finish();
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.roomCount, 3);
  EXPECT_EQ(g.portals.size(), 2u);
  std::set<std::int32_t> corridor;
  for (std::size_t i = 0; i < s.authoredRoom.size(); ++i)
  {
    if (s.authoredRoom[i] == leg1 || s.authoredRoom[i] == leg2)
    {
      corridor.insert(g.roomOfPolygon[i]);
    }
  }
  EXPECT_EQ(corridor.size(), 1u) << "the corridor's legs must be one room";
  EXPECT_GE(*corridor.begin(), 0);
  // The doors: the corridor's legs count as one authored room for the oracle.
  ArchitectureSoup doors = s;
  for (int& r : doors.authoredRoom)
  {
    r = r == leg2 ? leg1 : r;
  }
  doors.openings = { s.openings[0], s.openings[1] };
  doors.openings[1].roomA = leg1;
  expectOpeningsCovered(doors, g);
}

TEST(PortalGeneration, FurnitureStaysInItsRoom)
{
  ArchitectureSoup s = rowOfRooms(2);
  s.finish();
  const std::size_t roomPolygons = s.mesh.polygonCount();
  s.furniture(0, { 0.5, 0.5, 0 }, { 2.5, 1.5, 0.8 });   // a table-sized box on the floor
  s.furniture(0, { 3.5, 3.0, 0 }, { 5.0, 4.0, 2.0 });   // a cabinet in the corner at the door wall
  s.furniture(1, { 6.0, 0.5, 0.5 }, { 8.0, 3.5, 1.0 }); // a raised platform, free-standing
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.roomCount, 2);
  EXPECT_EQ(g.portals.size(), 1u);
  expectOpeningsCovered(s, g);
  roomMap(s, g);
  EXPECT_EQ(s.mesh.polygonCount() - roomPolygons, 18u);
}

TEST(PortalGeneration, AWindowToTheOutsideIsAnExteriorPortal)
{
  ArchitectureSoup s = rowOfRooms(2);
  s.opening(1, -1, 0, 10.0, { 0, 1, 1 }, { 0, 3, 2 });
  s.finish();
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.roomCount, 2);
  EXPECT_EQ(g.portals.size(), 2u);
  EXPECT_EQ(g.statistics.exteriorPortals, 1u);
  EXPECT_EQ(g.statistics.leakCells, 0u);
  expectOpeningsCovered(s, g);
}

// A door from the floor in an exterior wall (issue 14): box rooms float in the scene box with
// air below them, so the wall's plane is open below the floor outside the building too. Each
// scene turned four ways: which wall's BSP node reaches below the floor depends on the order.
TEST(PortalGeneration, ADoorFromTheFloorToTheOutsideIsAnExteriorPortal)
{
  for (int turns = 0; turns < 4; ++turns)
  {
    SCOPED_TRACE("turned " + std::to_string(turns) + " quarter turns");
    const ArchitectureSoup s = turned(roomWithAnExteriorDoor(0.0), turns);
    const GeneratedPortals g = generate(s.mesh);
    expectClosedRoomsWithExteriorPortals(s, g, 1, 1);
    // The door, not the wall: 1 x 2.1 in a 4 x 3 wall.
    ASSERT_EQ(g.portals.size(), 1u);
    EXPECT_LT(area(g.portals[0].polygon), 0.5 * 12.0);
  }
}

TEST(PortalGeneration, DoorsFromTheFloorToTheOutsideOfTwoRoomsAreExteriorPortals)
{
  ArchitectureSoup two = rowOfRooms(2);
  two.opening(1, -1, 0, 10.0, { 0, 1, 0 }, { 0, 2, 2.1 });  // in room 1's far wall
  two.opening(0, -1, 1, 0.0, { 1, 0, 0 }, { 2.5, 0, 2.4 }); // in room 0's side wall
  two.finish();
  for (int turns = 0; turns < 4; ++turns)
  {
    SCOPED_TRACE("turned " + std::to_string(turns) + " quarter turns");
    const ArchitectureSoup s = turned(two, turns);
    const GeneratedPortals g = generate(s.mesh);
    expectClosedRoomsWithExteriorPortals(s, g, 2, 2);
    EXPECT_EQ(g.portals.size(), 3u);
  }
}

TEST(PortalGeneration, ADoorToTheOutsideOfABuildingOnTheGroundIsAnExteriorPortal)
{
  // The ground: one polygon larger than the building, in the floor's plane, facing up.
  ArchitectureSoup ground = roomWithAnExteriorDoor(0.0);
  ground.quad(-2, 2, 0.0, true, -10, 15, -10, 14);
  for (int turns = 0; turns < 4; ++turns)
  {
    SCOPED_TRACE("turned " + std::to_string(turns) + " quarter turns");
    const ArchitectureSoup s = turned(ground, turns);
    const GeneratedPortals g = generate(s.mesh);
    expectClosedRoomsWithExteriorPortals(s, g, 1, 1);
    EXPECT_EQ(g.portals.size(), 1u);
  }
}

TEST(PortalGeneration, ADoorToTheOutsideThroughAThickWallIsAnExteriorPortal)
{
  const double thickness = 0.3;
  for (int turns = 0; turns < 4; ++turns)
  {
    SCOPED_TRACE("turned " + std::to_string(turns) + " quarter turns");
    const ArchitectureSoup s = turned(roomWithAnExteriorDoor(thickness), turns);
    const GeneratedPortals g = generate(s.mesh);
    ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
    EXPECT_EQ(g.statistics.leakCells, 0u);
    EXPECT_EQ(g.roomCount, 1);
    roomMap(s, g);
    // The doorway through the wall is a passage: joined to the room or to the outside, so the
    // portal stands on one face of the wall or the other and must cover the whole door there.
    ASSERT_EQ(g.portals.size(), 1u);
    const PortalDesc& portal = g.portals[0];
    EXPECT_EQ(portal.roomA, 0);
    EXPECT_EQ(portal.roomB, kOutsideRoom);
    const Opening& door = s.openings[0];
    const int u = (door.axis + 1) % 3, v = (door.axis + 2) % 3;
    // The wall's outer face lies `thickness` beyond the room's face, away from the room.
    const double out = door.at > s.rooms[0].center()[door.axis] ? thickness : -thickness;
    bool coveredOnAFace = false;
    for (const double at : { door.at, door.at + out })
    {
      bool all = true;
      for (int c = 0; c < 4; ++c)
      {
        glm::dvec3 corner = door.lo;
        corner[door.axis] = at;
        corner[u] = (c & 1) ? door.hi[u] : door.lo[u];
        corner[v] = (c & 2) ? door.hi[v] : door.lo[v];
        all = all && portalCovers(portal, corner, 1e-6);
      }
      coveredOnAFace = coveredOnAFace || all;
    }
    EXPECT_TRUE(coveredOnAFace) << "the portal does not cover the door on either face of the wall";
  }
}

// Converted levels (Freedoom MAP01) have floors that stop a fraction of a unit short of a wall
// on a slant: a node builder's split vertex, rounded, pulls the floor's corner off the wall's line.
// The sliver of open floor plane left between floor and wall is a hole into the void under the
// floor; the plane of another wall cuts it into pieces whose shared edge is shorter than the
// sampling step. A sample taken past that short edge lands across the slanted wall, in the open
// plane of the lower room beyond; grouping the sliver with it made the sliver no opening, so the
// room above leaked into the void (the outside). The sliver must be a portal to the outside.
TEST(PortalGeneration, ASliverBetweenAFloorAndASlantedStepIsAnExteriorPortalNotALeak)
{
  // Rooms A (floor 0) and B (floor -0.5) under one ceiling (3), parted by a step along the slanted
  // line from (0, 4.2) to (4, 3.8). A's floor is two polygons whose shared corner lies `gap` short
  // of the line (at x = 2, where the line is at y = 4); B is split at x = 2 by a wall with a door
  // (its plane cuts the sliver) and has a table whose top lies in A's floor plane (so that plane
  // is open over B beside the step too).
  const double gap = 2e-4, top = 3.0, low = -0.5;
  PolygonMesh mesh;
  // Adds @p points as one polygon whose normal points towards @p towards.
  auto add = [&mesh](std::vector<glm::dvec3> points, const glm::dvec3& towards)
  {
    if (glm::dot(geometry::newellOf(points), towards - points[0]) < 0.0)
    {
      std::reverse(points.begin(), points.end());
    }
    std::vector<std::uint32_t> ids;
    for (const glm::dvec3& p : points)
    {
      ids.push_back(mesh.addPoint(p));
    }
    mesh.addPolygon(ids.data(), ids.size());
  };
  // A vertical wall from (a.x, a.y) to (b.x, b.y) between heights z0 and z1, facing @p towards.
  auto wall = [&add](glm::dvec2 a, glm::dvec2 b, double z0, double z1, const glm::dvec3& towards) {
    add({ { a, z0 }, { b, z0 }, { b, z1 }, { a, z1 } }, towards);
  };
  const glm::dvec3 inA(2, 2, 1), inB(1, 6, 1), inB2(3, 6, 1);
  add({ { 0, 0, 0 }, { 2, 0, 0 }, { 2, 4 - gap, 0 }, { 0, 4.2, 0 } }, inA); // A's floor
  add({ { 2, 0, 0 }, { 4, 0, 0 }, { 4, 3.8, 0 }, { 2, 4 - gap, 0 } }, inA);
  add({ { 0, 4.2, low }, { 4, 3.8, low }, { 4, 8, low }, { 0, 8, low } }, inB); // B's floor
  add({ { 0, 0, top }, { 4, 0, top }, { 4, 8, top }, { 0, 8, top } }, inB);     // the ceiling
  wall({ 0, 4.2 }, { 4, 3.8 }, low, 0.0, inB);                                  // the step
  wall({ 0, 0 }, { 0, 4.2 }, 0.0, top, inA);
  wall({ 0, 0 }, { 4, 0 }, 0.0, top, inA);
  wall({ 4, 0 }, { 4, 3.8 }, 0.0, top, inA);
  wall({ 0, 4.2 }, { 0, 8 }, low, top, inB);
  wall({ 4, 3.8 }, { 4, 8 }, low, top, inB2);
  wall({ 0, 8 }, { 2, 8 }, low, top, inB);
  wall({ 2, 8 }, { 4, 8 }, low, top, inB2);
  for (const glm::dvec3& side : { inB, inB2 }) // the wall x = 2 in B, a door from y 5 to 6
  {
    wall({ 2, 4 }, { 2, 5 }, low, top, side);
    wall({ 2, 6 }, { 2, 8 }, low, top, side);
    wall({ 2, 5 }, { 2, 6 }, 2.1, top, side);
  }
  add({ { 0.5, 6.5, 0 }, { 3.5, 6.5, 0 }, { 3.5, 7.5, 0 }, { 0.5, 7.5, 0 } }, { 2, 7, 1 });
  add({ { 0.5, 6.5, 0 }, { 3.5, 6.5, 0 }, { 3.5, 7.5, 0 }, { 0.5, 7.5, 0 } }, { 2, 7, -1 });
  for (int turns = 0; turns < 4; ++turns)
  {
    SCOPED_TRACE("turned " + std::to_string(turns) + " quarter turns");
    PolygonMesh turned = mesh;
    for (glm::dvec3& p : turned.points)
    {
      for (int k = 0; k < turns; ++k)
      {
        p = glm::dvec3(-p.y, p.x, p.z);
      }
    }
    const GeneratedPortals g = generate(turned);
    ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
    EXPECT_EQ(g.statistics.leakCells, 0u);
    for (const glm::dvec3& p : g.leakPoints)
    {
      ADD_FAILURE() << "leak near " << p.x << ", " << p.y << ", " << p.z;
    }
    EXPECT_GE(g.statistics.exteriorPortals, 1u); // the sliver, a hole into the void below A
    for (std::size_t i = 0; i < turned.polygonCount(); ++i)
    {
      EXPECT_NE(g.roomOfPolygon[i], kOutsideRoom) << "polygon " << i;
    }
  }
}

TEST(PortalGeneration, AMissingWallIsReportedAsALeak)
{
  ArchitectureSoup s = rowOfRooms(2);
  // Room 1's far wall (x = 10) is gone: its inside is open to the outside with no opening.
  s.opening(1, -1, 0, 10.0, { 0, 0, 0 }, { 0, 4, 3 });
  s.finish();
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_GT(g.statistics.leakCells, 0u);
  ASSERT_FALSE(g.leakPoints.empty());
  for (const glm::dvec3& p : g.leakPoints)
  {
    EXPECT_TRUE(p.x > 5.0 && p.x < 10.0 && p.y > 0.0 && p.y < 4.0 && p.z > 0.0 && p.z < 3.0)
      << "leak point outside the open room: " << p.x << ", " << p.y << ", " << p.z;
  }
  // No rooms for a model that leaks (TestPortalGenerationLeaks.cpp says why).
  EXPECT_EQ(g.roomCount, 0);
  EXPECT_TRUE(g.portals.empty());
  EXPECT_EQ(g.statistics.roomsWithheld, 1u);
  // Kept anyway, the room with the door to the leaking one keeps its portal: what is behind it
  // is outside.
  GenerationInput in;
  in.mesh = &s.mesh;
  GenerationConfig keep;
  keep.keepRoomsWithLeaks = true;
  const GeneratedPortals kept = generatePortals(in, keep);
  EXPECT_EQ(kept.statistics.leakCells, g.statistics.leakCells);
  EXPECT_EQ(kept.roomCount, 1);
  ASSERT_EQ(kept.portals.size(), 1u);
  EXPECT_EQ(kept.portals[0].roomB, kOutsideRoom);
}

TEST(PortalGeneration, StoppingAtTheFirstLeakReportsOneLeakInTheOpenRoomAndNoRooms)
{
  ArchitectureSoup s = rowOfRooms(3);
  s.opening(2, -1, 0, 15.0, { 0, 0, 0 }, { 0, 4, 3 }); // room 2's far wall is gone
  s.finish();
  GenerationInput in;
  in.mesh = &s.mesh;
  GenerationConfig config;
  config.stopAtFirstLeak = true;
  const GeneratedPortals g = generatePortals(in, config);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.statistics.leakCells, 1u);
  ASSERT_EQ(g.leakPoints.size(), 1u);
  const glm::dvec3 p = g.leakPoints[0];
  EXPECT_TRUE(p.x > 10.0 && p.x < 15.0 && p.y > 0.0 && p.y < 4.0 && p.z > 0.0 && p.z < 3.0)
    << "leak point outside the open room: " << p.x << ", " << p.y << ", " << p.z;
  EXPECT_EQ(g.roomCount, 0);
  EXPECT_TRUE(g.portals.empty());
  EXPECT_NE(g.message.find("first leak"), std::string::npos) << g.message;
  for (const std::int32_t r : g.roomOfPolygon)
  {
    EXPECT_EQ(r, kOutsideRoom);
  }
  // Without it, every leak cell is counted and the closed rooms are found (`scenevis portals`),
  // and withheld unless kept.
  const GeneratedPortals all = generatePortals(in);
  EXPECT_GE(all.statistics.leakCells, 1u);
  EXPECT_EQ(all.roomCount, 0);
  EXPECT_EQ(all.statistics.roomsWithheld, 2u);
  GenerationConfig keep;
  keep.keepRoomsWithLeaks = true;
  EXPECT_EQ(generatePortals(in, keep).roomCount, 2);
}

TEST(PortalGeneration, AWallWoundTheWrongWayStillBelongsToItsRoom)
{
  // Room 1's far wall (x = 10) faces the outside instead of the room, as the back side's wall
  // parts of a converted Doom level do: seen only from room 1, it must be drawn with room 1.
  ArchitectureSoup s = rowOfRooms(2);
  s.finish();
  std::size_t flipped = 0;
  for (std::size_t i = 0; i < s.mesh.polygonCount(); ++i)
  {
    const std::uint32_t* ids = s.mesh.polygon(i);
    bool atFarWall = true;
    for (std::uint32_t k = 0; k < s.mesh.polygonSize(i); ++k)
    {
      atFarWall = atFarWall && s.mesh.points[ids[k]].x == 10.0;
    }
    if (atFarWall)
    {
      std::reverse(
        s.mesh.indices.begin() + s.mesh.offsets[i], s.mesh.indices.begin() + s.mesh.offsets[i + 1]);
      ++flipped;
    }
  }
  ASSERT_EQ(flipped, 1u);
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.roomCount, 2);
  roomMap(s, g); // every polygon of room 1, the flipped wall too, in one room
  expectOpeningsCovered(s, g);
}

TEST(PortalGeneration, GlassMarkedSeeThroughKeepsItsWindowOpen)
{
  ArchitectureSoup s = rowOfRooms(2);
  s.finish();
  // A pane filling the door: opaque it closes the door, see-through it does not.
  const std::uint32_t ids[4] = { s.mesh.addPoint({ 5, 1.5, 0 }), s.mesh.addPoint({ 5, 2.5, 0 }),
    s.mesh.addPoint({ 5, 2.5, 2.1 }), s.mesh.addPoint({ 5, 1.5, 2.1 }) };
  s.mesh.addPolygon(ids, 4);
  GenerationInput in;
  in.mesh = &s.mesh;
  const GeneratedPortals closed = generatePortals(in);
  EXPECT_EQ(closed.portals.size(), 0u);
  in.seeThrough.assign(s.mesh.polygonCount(), 0);
  in.seeThrough.back() = 1;
  const GeneratedPortals open = generatePortals(in);
  EXPECT_EQ(open.roomCount, 2);
  EXPECT_EQ(open.portals.size(), 1u);
  EXPECT_GE(open.roomOfPolygon.back(), 0);
}

TEST(PortalGeneration, FarFromTheOriginTheSameRoomsAndPortals)
{
  ArchitectureSoup s = rowOfRooms(3);
  const glm::dvec3 offset(1e7, -1e7, 1e7);
  for (Box& b : s.rooms)
  {
    b.lo += offset;
    b.hi += offset;
  }
  for (Opening& o : s.openings)
  {
    o.lo += offset;
    o.hi += offset;
    o.at += offset[o.axis];
  }
  s.finish();
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.roomCount, 3);
  EXPECT_EQ(g.portals.size(), 2u);
  expectOpeningsCovered(s, g, 1e-6 * 1e7);
}

TEST(PortalGeneration, PastItsBudgetGenerationStopsWithNoRooms)
{
  ArchitectureSoup s = rowOfRooms(6);
  s.finish();
  GenerationInput in;
  in.mesh = &s.mesh;
  GenerationConfig config;
  config.budgetSeconds = 1e-9; // over after the first step
  const GeneratedPortals stopped = generatePortals(in, config);
  EXPECT_EQ(stopped.status, GenerationStatus::OverBudget);
  EXPECT_NE(stopped.message.find("over the budget"), std::string::npos) << stopped.message;
  EXPECT_EQ(stopped.roomCount, 0);
  EXPECT_TRUE(stopped.portals.empty());
  ASSERT_EQ(stopped.roomOfPolygon.size(), s.mesh.polygonCount());
  for (const std::int32_t r : stopped.roomOfPolygon)
  {
    EXPECT_EQ(r, kOutsideRoom);
  }
  // A budget it fits in gives the same answer as none.
  config.budgetSeconds = 600.0;
  const GeneratedPortals within = generatePortals(in, config);
  ASSERT_EQ(within.status, GenerationStatus::Ok) << within.message;
  EXPECT_EQ(within.roomCount, 6);
  EXPECT_EQ(within.portals.size(), 5u);
}

TEST(PortalGenerationBadInput, EmptyInputGivesAStatus)
{
  GenerationInput none;
  EXPECT_EQ(generatePortals(none).status, GenerationStatus::EmptyInput);
  PolygonMesh empty;
  const GeneratedPortals g = generate(empty);
  EXPECT_EQ(g.status, GenerationStatus::EmptyInput);
  EXPECT_FALSE(g.message.empty());
  EXPECT_TRUE(g.portals.empty());
}

TEST(PortalGenerationBadInput, OnlyDegenerateOrNaNPolygonsGiveAStatus)
{
  PolygonMesh mesh;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto a = mesh.addPoint({ 0, 0, 0 }), b = mesh.addPoint({ 1, 0, 0 }),
             c = mesh.addPoint({ 2, 0, 0 }), d = mesh.addPoint({ nan, 0, 1 });
  mesh.addPolygon({ a, b, c }); // collinear
  mesh.addPolygon({ a, b, d }); // NaN
  mesh.addPolygon({ a, a, b }); // repeated point
  const GeneratedPortals g = generate(mesh);
  EXPECT_EQ(g.status, GenerationStatus::NoValidPolygons);
  EXPECT_FALSE(g.message.empty());
  ASSERT_EQ(g.roomOfPolygon.size(), 3u);
  for (const std::int32_t r : g.roomOfPolygon)
  {
    EXPECT_EQ(r, kOutsideRoom);
  }
}

TEST(PortalGenerationBadInput, BadPolygonsAmongGoodOnesAreDroppedAndCounted)
{
  ArchitectureSoup s = rowOfRooms(2);
  s.finish();
  const std::size_t good = s.mesh.polygonCount();
  const double inf = std::numeric_limits<double>::infinity();
  const auto p = s.mesh.addPoint({ 2, 2, 1 }), q = s.mesh.addPoint({ inf, 2, 1 });
  s.mesh.addPolygon({ p, q, p });
  s.mesh.addPolygon({ p, p, p });
  s.mesh.indices.push_back(123456); // out-of-range point id
  s.mesh.indices.push_back(p);
  s.mesh.indices.push_back(q);
  s.mesh.offsets.push_back(static_cast<std::uint32_t>(s.mesh.indices.size()));
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.statistics.droppedPolygons, 3u);
  EXPECT_EQ(g.roomCount, 2);
  EXPECT_EQ(g.portals.size(), 1u);
  for (std::size_t i = good; i < s.mesh.polygonCount(); ++i)
  {
    EXPECT_EQ(g.roomOfPolygon[i], kOutsideRoom);
  }
}

TEST(PortalGenerationBadInput, AnOpenSoupStillGivesAnAnswer)
{
  // A single wall and a floor: no room is closed, everything is outside, nothing crashes.
  ArchitectureSoup s;
  s.quad(0, 0, 0.0, true, 0, 4, 0, 3);
  s.quad(0, 2, 0.0, true, 0, 5, 0, 4);
  const GeneratedPortals g = generate(s.mesh);
  ASSERT_EQ(g.status, GenerationStatus::Ok) << g.message;
  EXPECT_EQ(g.roomCount, 0);
  EXPECT_TRUE(g.portals.empty());
}

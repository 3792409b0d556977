// Specification of the demo scene generators (Scenes.h): determinism, documented counts and the
// geometric properties later algorithms rely on (closed outward surfaces, a real painter's
// cycle, valid building portals).
#include "scenevis/Scenes.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <queue>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace scenes = scenevis::scenes;
using scenevis::Box;
using scenevis::PolygonMesh;

namespace
{

constexpr double kPi = 3.14159265358979323846;

/// Empty when polygons [first, first+count) form a closed, consistently oriented 2-manifold:
/// every directed edge appears once and its reverse once. Otherwise a description of the
/// first offending edge.
std::string closedSurfaceDefect(const PolygonMesh& mesh, std::size_t first, std::size_t count)
{
  std::unordered_map<std::uint64_t, int> directed;
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
  for (std::size_t i = first; i < first + count; ++i)
  {
    const std::uint32_t* ids = mesh.polygon(i);
    const std::uint32_t n = mesh.polygonSize(i);
    for (std::uint32_t k = 0; k < n; ++k)
    {
      ++directed[key(ids[k], ids[(k + 1) % n])];
    }
  }
  for (const auto& [edge, uses] : directed)
  {
    const auto a = static_cast<std::uint32_t>(edge >> 32);
    const auto b = static_cast<std::uint32_t>(edge & 0xffffffffu);
    const auto reverse = directed.find(key(b, a));
    if (uses != 1 || reverse == directed.end() || reverse->second != 1)
    {
      return "edge " + std::to_string(a) + "->" + std::to_string(b) + " used " +
             std::to_string(uses) + " times, reverse " +
             std::to_string(reverse == directed.end() ? 0 : reverse->second);
    }
  }
  return {};
}

/// Signed volume enclosed by polygons [first, first+count) (fan triangulation), measured from
/// `ref` so that far-from-origin models keep their precision. Positive for outward normals.
double signedVolume(const PolygonMesh& mesh,
                    std::size_t first,
                    std::size_t count,
                    const glm::dvec3& ref)
{
  double volume = 0.0;
  for (std::size_t i = first; i < first + count; ++i)
  {
    const std::uint32_t* ids = mesh.polygon(i);
    const glm::dvec3 p0 = mesh.points[ids[0]] - ref;
    for (std::uint32_t k = 1; k + 1 < mesh.polygonSize(i); ++k)
    {
      volume += glm::dot(p0, glm::cross(mesh.points[ids[k]] - ref, mesh.points[ids[k + 1]] - ref));
    }
  }
  return volume / 6.0;
}

glm::dvec3 polygonNormal(const PolygonMesh& mesh, std::size_t i)
{
  return scenevis::newellNormal(mesh.points.data(), mesh.polygon(i), mesh.polygonSize(i));
}

/// Largest distance of a polygon's points from the plane through its first point.
double planarityError(const std::vector<glm::dvec3>& points)
{
  glm::dvec3 n(0.0);
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    const glm::dvec3& a = points[k];
    const glm::dvec3& b = points[(k + 1) % points.size()];
    n +=
      glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  n = glm::normalize(n);
  double error = 0.0;
  for (const glm::dvec3& p : points)
  {
    error = std::max(error, std::abs(glm::dot(p - points[0], n)));
  }
  return error;
}

std::vector<glm::dvec3> polygonPoints(const PolygonMesh& mesh, std::size_t i)
{
  std::vector<glm::dvec3> points;
  for (std::uint32_t k = 0; k < mesh.polygonSize(i); ++k)
  {
    points.push_back(mesh.points[mesh.polygon(i)[k]]);
  }
  return points;
}

bool contains(const Box& box, const glm::dvec3& p, double eps)
{
  return p.x >= box.lo.x - eps && p.y >= box.lo.y - eps && p.z >= box.lo.z - eps &&
         p.x <= box.hi.x + eps && p.y <= box.hi.y + eps && p.z <= box.hi.z + eps;
}

/// Checks the Scene-wide contracts: part ranges are contiguous, cover every polygon, agree with
/// the per-polygon ids, and their bounds contain their polygons.
void expectConsistentParts(const scenes::Scene& scene)
{
  ASSERT_EQ(scene.part.size(), scene.mesh.polygonCount());
  std::uint32_t next = 0;
  for (std::size_t k = 0; k < scene.parts.size(); ++k)
  {
    const scenes::Part& part = scene.parts[k];
    ASSERT_EQ(part.firstPolygon, next) << part.name;
    next += part.polygonCount;
    EXPECT_GT(part.opacity, 0.0);
    EXPECT_LE(part.opacity, 1.0);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_GE(part.colour[c], 0.0);
      EXPECT_LE(part.colour[c], 1.0);
    }
    for (std::uint32_t i = part.firstPolygon; i < part.firstPolygon + part.polygonCount; ++i)
    {
      ASSERT_EQ(scene.part[i], k);
      for (const glm::dvec3& p : polygonPoints(scene.mesh, i))
      {
        ASSERT_TRUE(contains(part.bounds, p, 0.0)) << part.name;
      }
    }
  }
  EXPECT_EQ(next, scene.mesh.polygonCount());
}

bool sameMesh(const PolygonMesh& a, const PolygonMesh& b)
{
  return a.points == b.points && a.indices == b.indices && a.offsets == b.offsets;
}

} // namespace

// ---------------------------------------------------------------------------------------------

TEST(Scenes, ClosedSurfaceCheckDetectsHolesAndFlips)
{
  // The checker must be able to fail, or the closed-surface tests below prove nothing.
  const PolygonMesh good = scenes::sphere({ 0, 0, 0 }, 1.0, 200);
  EXPECT_EQ(closedSurfaceDefect(good, 0, good.polygonCount()), "");
  EXPECT_NE(closedSurfaceDefect(good, 0, good.polygonCount() - 1), "");
  PolygonMesh flipped = good;
  std::swap(flipped.indices[0], flipped.indices[1]);
  EXPECT_NE(closedSurfaceDefect(flipped, 0, flipped.polygonCount()), "");
}

TEST(Scenes, SphereIsClosedConvexAndOutward)
{
  const glm::dvec3 c(1.0, -2.0, 3.0);
  const double r = 0.5;
  const PolygonMesh mesh = scenes::sphere(c, r, 2000);
  EXPECT_EQ(closedSurfaceDefect(mesh, 0, mesh.polygonCount()), "");
  for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
  {
    ASSERT_EQ(mesh.polygonSize(i), 3u);
    const std::vector<glm::dvec3> p = polygonPoints(mesh, i);
    const glm::dvec3 centroid = (p[0] + p[1] + p[2]) / 3.0;
    // Outward and non-degenerate: the normal points away from the centre.
    ASSERT_GT(glm::dot(polygonNormal(mesh, i), centroid - c), 0.0) << "triangle " << i;
  }
  for (const glm::dvec3& p : mesh.points)
  {
    ASSERT_NEAR(glm::length(p - c), r, 1e-12);
  }
  const double volume = signedVolume(mesh, 0, mesh.polygonCount(), c);
  EXPECT_NEAR(volume, 4.0 / 3.0 * kPi * r * r * r, 0.02 * volume);
}

TEST(Scenes, SphereTriangleCountFollowsRequest)
{
  for (std::size_t request : { 6u, 50u, 320u, 1000u, 1562u, 15625u, 100000u })
  {
    const std::size_t got = scenes::sphere({ 0, 0, 0 }, 1.0, request).polygonCount();
    if (request >= 1000)
    {
      EXPECT_NEAR(double(got), double(request), 0.02 * double(request)) << request;
    }
    else
    {
      EXPECT_NEAR(double(got), double(request), 0.25 * double(request) + 6) << request;
    }
  }
}

TEST(Scenes, SphereGridCountsAndTotals)
{
  for (std::size_t total : { 10000u, 100000u, 1000000u })
  {
    const scenes::Scene scene =
      scenes::sphereGrid(4, 0.8, 1.0, scenes::trianglesPerSphereFor(total));
    ASSERT_EQ(scene.parts.size(), 64u);
    EXPECT_NEAR(double(scene.mesh.polygonCount()), double(total), 0.02 * double(total));
    EXPECT_EQ(scenes::triangleCount(scene.mesh), scene.mesh.polygonCount());
  }
  const scenes::Scene scene = scenes::sphereGrid(3, 0.8, 1.0, 100);
  expectConsistentParts(scene);
  ASSERT_EQ(scene.parts.size(), 27u);
  EXPECT_TRUE(scene.hasTranslucency());
  std::set<std::vector<double>> colours;
  for (const scenes::Part& part : scene.parts)
  {
    EXPECT_DOUBLE_EQ(part.opacity, 0.3);
    colours.insert({ part.colour.x, part.colour.y, part.colour.z });
    EXPECT_EQ(closedSurfaceDefect(scene.mesh, part.firstPolygon, part.polygonCount), "")
      << part.name;
    EXPECT_GT(signedVolume(scene.mesh, part.firstPolygon, part.polygonCount, part.bounds.center()),
              0.0);
  }
  EXPECT_EQ(colours.size(), 27u) << "sphere colours must be distinct";
  // Neighbours overlap (that is the point of the scene), and the grid is centred.
  const glm::dvec3 c0 = scene.parts[0].bounds.center();
  const glm::dvec3 c1 = scene.parts[1].bounds.center();
  EXPECT_LT(glm::length(c1 - c0), 2 * 0.8);
  EXPECT_NEAR(glm::length(scene.mesh.bounds().center()), 0.0, 1e-12);
}

TEST(Scenes, SphereGridIsDeterministic)
{
  const scenes::Scene a = scenes::sphereGrid(2, 0.8, 1.0, 500);
  const scenes::Scene b = scenes::sphereGrid(2, 0.8, 1.0, 500);
  EXPECT_TRUE(sameMesh(a.mesh, b.mesh));
  EXPECT_FALSE(sameMesh(a.mesh, scenes::sphereGrid(2, 0.8, 1.1, 500).mesh));
}

// ---------------------------------------------------------------------------------------------

namespace
{

/// Point-in-convex-polygon test in the xy projection (counter-clockwise polygon).
bool insideXY(const std::vector<glm::dvec3>& poly, double x, double y)
{
  for (std::size_t k = 0; k < poly.size(); ++k)
  {
    const glm::dvec3& a = poly[k];
    const glm::dvec3& b = poly[(k + 1) % poly.size()];
    if ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x) <= 0.0)
    {
      return false;
    }
  }
  return true;
}

/// z of the polygon's plane above (x, y).
double planeZ(const std::vector<glm::dvec3>& poly, double x, double y)
{
  const glm::dvec3 n = glm::cross(poly[1] - poly[0], poly[2] - poly[0]);
  return poly[0].z - (n.x * (x - poly[0].x) + n.y * (y - poly[0].y)) / n.z;
}

/// Whether segment pq crosses the interior of triangle t (Moller-Trumbore, strict).
bool segmentPiercesTriangle(const glm::dvec3& p,
                            const glm::dvec3& q,
                            const std::vector<glm::dvec3>& t)
{
  const glm::dvec3 d = q - p;
  const glm::dvec3 e1 = t[1] - t[0];
  const glm::dvec3 e2 = t[2] - t[0];
  const glm::dvec3 h = glm::cross(d, e2);
  const double det = glm::dot(e1, h);
  if (std::abs(det) < 1e-12)
  {
    return false;
  }
  const glm::dvec3 s = p - t[0];
  const double u = glm::dot(s, h) / det;
  const glm::dvec3 qv = glm::cross(s, e1);
  const double v = glm::dot(d, qv) / det;
  const double along = glm::dot(e2, qv) / det;
  return u > 1e-9 && v > 1e-9 && u + v < 1 - 1e-9 && along > 1e-9 && along < 1 - 1e-9;
}

} // namespace

TEST(Scenes, CyclicQuadsFormADepthCycle)
{
  const scenes::Scene scene = scenes::cyclicQuads();
  expectConsistentParts(scene);
  ASSERT_EQ(scene.mesh.polygonCount(), 3u);
  ASSERT_EQ(scene.parts.size(), 3u);
  std::vector<std::vector<glm::dvec3>> quads;
  for (std::size_t i = 0; i < 3; ++i)
  {
    ASSERT_EQ(scene.mesh.polygonSize(i), 4u);
    quads.push_back(polygonPoints(scene.mesh, i));
    EXPECT_LT(planarityError(quads.back()), 1e-12);
    EXPECT_GT(polygonNormal(scene.mesh, i).z, 0.0) << "quad " << i << " must face +z";
    EXPECT_DOUBLE_EQ(scene.parts[i].opacity, 0.5);
  }
  // Sample the xy plane: every pair overlaps, and wherever quads i and i+1 overlap, i is
  // strictly above (nearer a +z viewer). Together: a cycle, and no 3D intersection.
  for (std::size_t i = 0; i < 3; ++i)
  {
    const std::vector<glm::dvec3>& upper = quads[i];
    const std::vector<glm::dvec3>& lower = quads[(i + 1) % 3];
    int overlapping = 0;
    double minGap = 1e300;
    for (double x = -1.5; x <= 1.5; x += 0.01)
    {
      for (double y = -1.5; y <= 1.5; y += 0.01)
      {
        if (insideXY(upper, x, y) && insideXY(lower, x, y))
        {
          ++overlapping;
          minGap = std::min(minGap, planeZ(upper, x, y) - planeZ(lower, x, y));
        }
      }
    }
    EXPECT_GT(overlapping, 100) << "quads " << i << " and " << (i + 1) % 3 << " must overlap";
    EXPECT_GT(minGap, 0.05) << "quad " << i << " must be above quad " << (i + 1) % 3;
  }
}

TEST(Scenes, InterpenetratingTrianglesPierceEachOther)
{
  const scenes::Scene scene = scenes::interpenetratingTriangles();
  expectConsistentParts(scene);
  ASSERT_EQ(scene.mesh.polygonCount(), 2u);
  const std::vector<glm::dvec3> a = polygonPoints(scene.mesh, 0);
  const std::vector<glm::dvec3> b = polygonPoints(scene.mesh, 1);
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  auto edgePierces = [](const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& into)
  {
    int count = 0;
    for (std::size_t k = 0; k < 3; ++k)
    {
      count += segmentPiercesTriangle(from[k], from[(k + 1) % 3], into) ? 1 : 0;
    }
    return count;
  };
  EXPECT_GE(edgePierces(a, b), 1) << "an edge of A must pass through B";
  EXPECT_GE(edgePierces(b, a), 1) << "an edge of B must pass through A";
  EXPECT_GT(polygonNormal(scene.mesh, 0).z, 0.0);
  EXPECT_GT(polygonNormal(scene.mesh, 1).z, 0.0);
}

// ---------------------------------------------------------------------------------------------

TEST(Scenes, CadPartsAreClosedAndOutward)
{
  const scenes::Scene scene = scenes::cadAssembly(400, 80, 7);
  expectConsistentParts(scene);
  ASSERT_EQ(scene.parts.size(), 400u);
  std::set<std::string> kinds;
  for (const scenes::Part& part : scene.parts)
  {
    kinds.insert(part.name.substr(0, part.name.find('#')));
    ASSERT_EQ(closedSurfaceDefect(scene.mesh, part.firstPolygon, part.polygonCount), "")
      << part.name;
    ASSERT_GT(signedVolume(scene.mesh, part.firstPolygon, part.polygonCount, part.bounds.center()),
              0.0)
      << part.name;
  }
  for (std::size_t i = 0; i < scene.mesh.polygonCount(); ++i)
  {
    ASSERT_EQ(scene.mesh.polygonSize(i), 3u);
    ASSERT_GT(glm::length(polygonNormal(scene.mesh, i)), 0.0) << "degenerate triangle " << i;
  }
  for (const char* kind :
       { "baseplate", "housing", "screw", "washer", "nut", "cylinder", "block", "ball", "ring" })
  {
    EXPECT_EQ(kinds.count(kind), 1u) << kind;
  }
  EXPECT_TRUE(scene.hasTranslucency());
  EXPECT_EQ(scene.parts[0].name, "baseplate");
}

TEST(Scenes, CadAssemblyMeetsTheTriangleBudget)
{
  struct Case
  {
    std::size_t parts, perPart;
  };
  for (const Case c : { Case{ 2000, 100 }, Case{ 500, 1000 }, Case{ 10000, 50 } })
  {
    const scenes::Scene scene = scenes::cadAssembly(c.parts, c.perPart, 3);
    const double target = double(c.parts * c.perPart);
    EXPECT_EQ(scene.parts.size(), c.parts);
    EXPECT_NEAR(double(scene.mesh.polygonCount()), target, 0.1 * target)
      << c.parts << " x " << c.perPart;
    // Sizes vary a lot: the biggest part dwarfs the median one.
    std::vector<double> sizes;
    for (const scenes::Part& part : scene.parts)
    {
      sizes.push_back(part.bounds.diagonal());
    }
    std::sort(sizes.begin(), sizes.end());
    EXPECT_GT(sizes.back(), 20 * sizes[sizes.size() / 2]);
  }
}

TEST(Scenes, CadAssemblyIsDeterministicAndSeeded)
{
  const scenes::Scene a = scenes::cadAssembly(300, 100, 11);
  const scenes::Scene b = scenes::cadAssembly(300, 100, 11);
  EXPECT_TRUE(sameMesh(a.mesh, b.mesh));
  EXPECT_EQ(a.part, b.part);
  const scenes::Scene c = scenes::cadAssembly(300, 100, 12);
  EXPECT_FALSE(sameMesh(a.mesh, c.mesh));
}

TEST(Scenes, CadAssemblyOriginOnlyTranslates)
{
  const glm::dvec3 origin(1e7, -2e7, 5e6);
  const scenes::Scene a = scenes::cadAssembly(200, 60, 5);
  const scenes::Scene b = scenes::cadAssembly(200, 60, 5, origin);
  ASSERT_EQ(a.mesh.points.size(), b.mesh.points.size());
  EXPECT_EQ(a.mesh.indices, b.mesh.indices);
  for (std::size_t i = 0; i < a.mesh.points.size(); ++i)
  {
    // Far from the origin a double resolves ~4e-9; the parts are >= 0.1 mm.
    ASSERT_LT(glm::length(b.mesh.points[i] - origin - a.mesh.points[i]), 1e-7) << i;
  }
}

// ---------------------------------------------------------------------------------------------

namespace
{

/// Whether all points lie on one face of `box` (within eps).
bool onBoxFace(const Box& box, const std::vector<glm::dvec3>& points, double eps)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    for (double plane : { box.lo[axis], box.hi[axis] })
    {
      const bool all =
        std::all_of(points.begin(),
                    points.end(),
                    [&](const glm::dvec3& p) { return std::abs(p[axis] - plane) < eps; });
      if (all && std::all_of(points.begin(),
                             points.end(),
                             [&](const glm::dvec3& p) { return contains(box, p, eps); }))
      {
        return true;
      }
    }
  }
  return false;
}

} // namespace

TEST(Scenes, BuildingRoomsAndPortalsAreValid)
{
  const int floors = 3, rx = 6, ry = 7;
  const scenes::BuildingScene scene = scenes::building(floors, rx, ry, 4);
  expectConsistentParts(scene);
  ASSERT_EQ(scene.rooms.size(), std::size_t(floors * rx * ry));
  ASSERT_EQ(scene.room.size(), scene.mesh.polygonCount());
  for (std::size_t r = 0; r < scene.rooms.size(); ++r)
  {
    const scenes::Room& room = scene.rooms[r];
    EXPECT_EQ(room.id, int(r));
    EXPECT_EQ(room.id, room.floor * rx * ry + room.iy * rx + room.ix);
  }
  const std::vector<std::string> names{ "walls", "floors", "ceilings",  "facade",
                                        "roof",  "stairs", "furniture", "glass" };
  ASSERT_EQ(scene.parts.size(), names.size());
  for (std::size_t k = 0; k < names.size(); ++k)
  {
    EXPECT_EQ(scene.parts[k].name, names[k]);
    EXPECT_GT(scene.parts[k].polygonCount, 0u) << names[k];
  }

  const int roomCount = int(scene.rooms.size());
  int stairs = 0, windows = 0, doors = 0;
  for (const scenes::Portal& portal : scene.portals)
  {
    ASSERT_GE(portal.roomA, 0);
    ASSERT_LT(portal.roomA, roomCount);
    ASSERT_GE(portal.polygon.size(), 3u);
    EXPECT_LT(planarityError(portal.polygon), 1e-9);
    // Counter-clockwise around `normal`, which is a unit vector.
    const glm::dvec3 newell =
      scenevis::newellNormal(portal.polygon.data(),
                             std::vector<std::uint32_t>{ 0, 1, 2, 3 }.data(),
                             portal.polygon.size());
    EXPECT_GT(glm::dot(glm::normalize(newell), portal.normal), 1 - 1e-12);
    const scenes::Room& a = scene.rooms[std::size_t(portal.roomA)];
    EXPECT_TRUE(onBoxFace(a.bounds, portal.polygon, 1e-9));
    // The normal leaves room A.
    EXPECT_GT(glm::dot(portal.polygon[0] - a.bounds.center(), portal.normal), 0.0);
    if (portal.kind == scenes::PortalKind::Window)
    {
      ++windows;
      EXPECT_EQ(portal.roomB, scenes::kOutside);
      continue;
    }
    ASSERT_GE(portal.roomB, 0);
    ASSERT_LT(portal.roomB, roomCount);
    const scenes::Room& b = scene.rooms[std::size_t(portal.roomB)];
    EXPECT_TRUE(onBoxFace(b.bounds, portal.polygon, 1e-9));
    if (portal.kind == scenes::PortalKind::Stair)
    {
      ++stairs;
      EXPECT_EQ(b.floor, a.floor + 1);
      EXPECT_TRUE(a.stairwell && b.stairwell);
    }
    else
    {
      ++doors;
      EXPECT_EQ(a.floor, b.floor);
      EXPECT_EQ(std::abs(a.ix - b.ix) + std::abs(a.iy - b.iy), 1);
      EXPECT_LT(portal.roomA, portal.roomB);
    }
  }
  // 6 x 7 rooms: 2 x 2 blocks of 5 x 5, so 4 stairwells, each linking 3 floors by 2 portals.
  EXPECT_EQ(stairs, 4 * (floors - 1));
  EXPECT_GE(doors, floors * (rx * ry - 1)); // at least a spanning tree per floor
  EXPECT_GT(windows, 0);
}

TEST(Scenes, BuildingPolygonsLieInTheirRooms)
{
  const scenes::BuildingScene scene = scenes::building(2, 5, 4, 9);
  int outside = 0;
  for (std::size_t i = 0; i < scene.mesh.polygonCount(); ++i)
  {
    const std::vector<glm::dvec3> points = polygonPoints(scene.mesh, i);
    // Quads, and triangle fans where a face takes its neighbour's vertices (no T-junctions).
    ASSERT_TRUE(points.size() == 4u || points.size() == 3u) << points.size();
    ASSERT_LT(planarityError(points), 1e-9);
    ASSERT_GT(glm::length(polygonNormal(scene.mesh, i)), 1e-6) << "degenerate quad " << i;
    const std::int32_t r = scene.room[i];
    if (r == scenes::kOutside)
    {
      ++outside;
      continue;
    }
    ASSERT_GE(r, 0);
    ASSERT_LT(r, int(scene.rooms.size()));
    for (const glm::dvec3& p : points)
    {
      ASSERT_TRUE(contains(scene.rooms[std::size_t(r)].bounds, p, 1e-9))
        << "polygon " << i << " of part " << scene.parts[scene.part[i]].name << " leaves room "
        << r;
    }
  }
  EXPECT_GT(outside, 0);
  // Furniture and stairs are closed boxes facing out, six quads each.
  for (const char* name : { "furniture", "stairs" })
  {
    const auto part = std::find_if(scene.parts.begin(),
                                   scene.parts.end(),
                                   [&](const scenes::Part& p) { return p.name == name; });
    ASSERT_NE(part, scene.parts.end());
    ASSERT_EQ(part->polygonCount % 6, 0u);
    for (std::uint32_t first = part->firstPolygon; first < part->firstPolygon + part->polygonCount;
         first += 6)
    {
      EXPECT_GT(signedVolume(scene.mesh, first, 6, scene.mesh.points[scene.mesh.polygon(first)[0]]),
                0.0)
        << name << " box at polygon " << first;
    }
  }
}

TEST(Scenes, BuildingRoomsFaceInward)
{
  // Each room's floor faces up and its ceiling down; wall faces point into their room.
  const scenes::BuildingScene scene = scenes::building(1, 2, 2, 1);
  const scenes::Part& walls = scene.parts[0];
  int faces = 0;
  for (std::uint32_t i = walls.firstPolygon; i < walls.firstPolygon + walls.polygonCount; ++i)
  {
    const glm::dvec3 n = glm::normalize(polygonNormal(scene.mesh, i));
    const std::vector<glm::dvec3> p = polygonPoints(scene.mesh, i);
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& q : p)
    {
      centre += q / static_cast<double>(p.size());
    }
    const Box& room = scene.rooms[std::size_t(scene.room[i])].bounds;
    // Room faces sit half a wall inside the cell; the reveals (jambs) face across openings.
    const int axis = std::abs(n.x) > 0.5 ? 0 : (std::abs(n.y) > 0.5 ? 1 : 2);
    const double toCell = std::min(centre[axis] - room.lo[axis], room.hi[axis] - centre[axis]);
    if (axis == 2 || std::abs(toCell - 0.5 * scenes::kWallThickness) > 1e-9)
    {
      continue;
    }
    ++faces;
    EXPECT_GT(glm::dot(n, room.center() - centre), 0.0) << "wall polygon " << i;
  }
  EXPECT_GE(faces, 16); // 4 rooms x 4 sides, some split around openings
  for (std::uint32_t i = scene.parts[1].firstPolygon;
       i < scene.parts[1].firstPolygon + scene.parts[1].polygonCount;
       ++i)
  {
    EXPECT_GT(polygonNormal(scene.mesh, i).z, 0.0);
  }
  for (std::uint32_t i = scene.parts[2].firstPolygon;
       i < scene.parts[2].firstPolygon + scene.parts[2].polygonCount;
       ++i)
  {
    EXPECT_LT(polygonNormal(scene.mesh, i).z, 0.0);
  }
}

namespace
{
/// Distance from @p p to the segment [a, b].
double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b)
{
  const glm::dvec3 ab = b - a;
  const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(p - (a + t * ab));
}

/// Whether the segment [p, q] lies on the boundary of @p polygon (within @p eps).
bool onPolygonBoundary(
  const std::vector<glm::dvec3>& polygon, const glm::dvec3& p, const glm::dvec3& q, double eps)
{
  for (std::size_t k = 0; k < polygon.size(); ++k)
  {
    const glm::dvec3& a = polygon[k];
    const glm::dvec3& b = polygon[(k + 1) % polygon.size()];
    if (segmentDistance(p, a, b) <= eps && segmentDistance(q, a, b) <= eps)
    {
      return true;
    }
  }
  return false;
}

using Edge = std::pair<std::array<double, 3>, std::array<double, 3>>;
std::array<double, 3> key(const glm::dvec3& p)
{
  return { p.x, p.y, p.z };
}

/// The room shells of @p scene (parts walls, floors, ceilings) and the outside's (facade, roof),
/// checked as in the test below. Returns the problems found (empty: watertight); fills
/// @p portalEdges with, per portal and side (room id, -1 for the outside), the edges of that
/// side's shell lying on the portal's boundary.
std::vector<std::string> shellDefects(const scenes::BuildingScene& scene,
  std::map<std::pair<std::size_t, int>, std::set<Edge>>& portalEdges)
{
  std::vector<std::string> problems;
  // Shell s = room s - 1; shell 0 is the outside.
  const std::size_t shells = scene.rooms.size() + 1;
  std::vector<std::map<Edge, int>> directed(shells);
  for (std::size_t i = 0; i < scene.mesh.polygonCount(); ++i)
  {
    const std::string& part = scene.parts[scene.part[i]].name;
    const std::int32_t r = scene.room[i];
    const bool roomShell = r >= 0 && (part == "walls" || part == "floors" || part == "ceilings");
    const bool outsideShell = r == scenes::kOutside && (part == "facade" || part == "roof");
    if (!roomShell && !outsideShell)
    {
      continue;
    }
    const std::vector<glm::dvec3> pts = polygonPoints(scene.mesh, i);
    for (std::size_t k = 0; k < pts.size(); ++k)
    {
      ++directed[std::size_t(r + 1)][Edge{ key(pts[k]), key(pts[(k + 1) % pts.size()]) }];
    }
  }
  std::vector<std::vector<std::size_t>> portalsOf(shells);
  for (std::size_t p = 0; p < scene.portals.size(); ++p)
  {
    for (const std::int32_t r : { scene.portals[p].roomA, scene.portals[p].roomB })
    {
      portalsOf[std::size_t(r + 1)].push_back(p);
    }
  }
  auto point = [](const std::array<double, 3>& a) { return glm::dvec3(a[0], a[1], a[2]); };
  for (std::size_t s = 0; s < shells; ++s)
  {
    const int r = int(s) - 1;
    for (const auto& [edge, count] : directed[s])
    {
      const Edge reverse{ edge.second, edge.first };
      const auto back = directed[s].find(reverse);
      const int backCount = back == directed[s].end() ? 0 : back->second;
      if (count == 1 && backCount == 1)
      {
        continue; // shared by exactly two polygons, consistently oriented
      }
      bool onPortal = false;
      if (count == 1 && backCount == 0)
      {
        for (const std::size_t p : portalsOf[s])
        {
          if (onPolygonBoundary(
                scene.portals[p].polygon, point(edge.first), point(edge.second), 1e-9))
          {
            onPortal = true;
            portalEdges[{ p, r }].insert(
              std::min(edge, reverse)); // undirected, comparable across the two sides
            break;
          }
        }
      }
      if (!onPortal && problems.size() < 10)
      {
        const glm::dvec3 a = point(edge.first), b = point(edge.second);
        problems.push_back((r < 0 ? std::string("outside") : "room " + std::to_string(r)) +
          ": edge (" + std::to_string(a.x) + ", " + std::to_string(a.y) + ", " +
          std::to_string(a.z) + ") - (" + std::to_string(b.x) + ", " + std::to_string(b.y) + ", " +
          std::to_string(b.z) + ") used " + std::to_string(count) + " + " +
          std::to_string(backCount) + " times and not on a portal");
      }
    }
  }
  return problems;
}
} // namespace

TEST(Scenes, BuildingRoomShellsAreWatertight)
{
  // Every edge of a room's walls, floor and ceiling (reveals and stair shafts included), and of
  // the outside's facade and roof, is shared by exactly two of its polygons with opposite
  // directions (same end points: no T-junction, so rasterisation leaves no crack), or lies on
  // the boundary of one of its portals. Across a portal the two sides' edges on it are the
  // same, and they go all the way round the opening.
  for (const auto& size : { std::array<int, 4>{ 3, 6, 7, 4 }, std::array<int, 4>{ 2, 4, 4, 5 },
         std::array<int, 4>{ 4, 3, 2, 9 } })
  {
    const scenes::BuildingScene scene = scenes::building(size[0], size[1], size[2], size[3]);
    std::map<std::pair<std::size_t, int>, std::set<Edge>> portalEdges;
    const std::vector<std::string> problems = shellDefects(scene, portalEdges);
    EXPECT_TRUE(problems.empty()) << problems.size() << " problem(s), first: " << problems[0];
    for (std::size_t p = 0; p < scene.portals.size(); ++p)
    {
      const scenes::Portal& portal = scene.portals[p];
      const std::set<Edge>& a = portalEdges[{ p, portal.roomA }];
      double perimeter = 0.0, covered = 0.0;
      for (std::size_t k = 0; k < portal.polygon.size(); ++k)
      {
        perimeter +=
          glm::length(portal.polygon[(k + 1) % portal.polygon.size()] - portal.polygon[k]);
      }
      for (const Edge& e : a)
      {
        covered += glm::length(glm::dvec3(e.second[0], e.second[1], e.second[2]) -
          glm::dvec3(e.first[0], e.first[1], e.first[2]));
      }
      EXPECT_NEAR(covered, perimeter, 1e-9)
        << "portal " << p << ": room " << portal.roomA << "'s shell does not close around it";
      EXPECT_EQ(a, (portalEdges[{ p, portal.roomB }]))
        << "portal " << p << ": the two sides' edges on it differ (T-junction)";
    }
  }
  // The check can fail: a wall face split around a hole the old way (a full-width band below a
  // side piece) leaves a T-junction.
  scenes::BuildingScene broken = scenes::building(1, 2, 1, 1);
  const std::size_t wall = broken.parts[0].firstPolygon;
  const std::uint32_t* ids = broken.mesh.polygon(wall);
  const glm::dvec3 a = broken.mesh.points[ids[0]], b = broken.mesh.points[ids[1]];
  broken.mesh.points[ids[1]] = a + 0.5 * (b - a); // a vertex moved along the edge: a T-junction
  std::map<std::pair<std::size_t, int>, std::set<Edge>> unused;
  EXPECT_FALSE(shellDefects(broken, unused).empty());
}

TEST(Scenes, BuildingEveryRoomIsReachableThroughPortals)
{
  const scenes::BuildingScene scene = scenes::building(4, 7, 6, 2);
  std::vector<std::vector<int>> adjacent(scene.rooms.size());
  for (const scenes::Portal& portal : scene.portals)
  {
    if (portal.roomB != scenes::kOutside)
    {
      adjacent[std::size_t(portal.roomA)].push_back(portal.roomB);
      adjacent[std::size_t(portal.roomB)].push_back(portal.roomA);
    }
  }
  std::vector<char> seen(scene.rooms.size(), 0);
  std::queue<int> todo;
  todo.push(0);
  seen[0] = 1;
  std::size_t reached = 1;
  while (!todo.empty())
  {
    const int r = todo.front();
    todo.pop();
    for (int next : adjacent[std::size_t(r)])
    {
      if (!seen[std::size_t(next)])
      {
        seen[std::size_t(next)] = 1;
        ++reached;
        todo.push(next);
      }
    }
  }
  EXPECT_EQ(reached, scene.rooms.size());
}

TEST(Scenes, BuildingIsDeterministicAndScales)
{
  const scenes::BuildingScene a = scenes::building(2, 3, 3, 5);
  const scenes::BuildingScene b = scenes::building(2, 3, 3, 5);
  EXPECT_TRUE(sameMesh(a.mesh, b.mesh));
  EXPECT_EQ(a.room, b.room);
  ASSERT_EQ(a.portals.size(), b.portals.size());
  const scenes::BuildingScene c = scenes::building(2, 3, 3, 6);
  EXPECT_FALSE(sameMesh(a.mesh, c.mesh));

  const scenes::BuildingScene big = scenes::building(10, 10, 10, 1);
  EXPECT_EQ(big.rooms.size(), 1000u);
  EXPECT_GT(big.portals.size(), 1000u);
}

TEST(Scenes, GeneratorsRejectBadSizes)
{
  EXPECT_THROW(scenes::sphereGrid(0), std::invalid_argument);
  EXPECT_THROW(scenes::sphere({ 0, 0, 0 }, 0.0, 100), std::invalid_argument);
  EXPECT_THROW(scenes::cadAssembly(0), std::invalid_argument);
  EXPECT_THROW(scenes::building(0, 1, 1), std::invalid_argument);
}

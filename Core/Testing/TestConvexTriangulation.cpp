// Triangles of convex polygons with collinear vertices on their sides (ConvexTriangulation.h),
// checked against what a rasterizer needs of them: n - 2 triangles, none flat while the polygon
// has three corners, every edge of the polygon (each piece between collinear vertices) an edge
// of exactly one triangle in the polygon's direction (so a neighbour that shares those pieces
// meets it edge to edge), and together the polygon's area. Polygons: hand-made cases and random
// convex polygons in random planes with points put on their sides as a BSP split puts them
// (interpolated in double).
#include "scenevis/ConvexTriangulation.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

using scenevis::collinear;

namespace
{
/// A named polygon: its vertices in order.
struct Polygon
{
  std::string name;
  std::vector<glm::dvec3> vertices;
};

glm::dvec3 doubledAreaVector(const std::vector<glm::dvec3>& v)
{
  glm::dvec3 sum(0.0);
  for (std::size_t k = 1; k + 1 < v.size(); ++k)
  {
    sum += glm::cross(v[k] - v[0], v[k + 1] - v[0]);
  }
  return sum;
}

std::size_t cornerCount(const std::vector<glm::dvec3>& v)
{
  std::size_t corners = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    corners += !collinear(v[(i + v.size() - 1) % v.size()], v[i], v[(i + 1) % v.size()]);
  }
  return corners;
}

/// @p corners with @p onSide[k] points put on side k (corner k to corner k + 1) at random
/// parameters, then the list started at vertex @p start.
std::vector<glm::dvec3> withPointsOnSides(const std::vector<glm::dvec3>& corners,
  const std::vector<int>& onSide, std::size_t start, std::mt19937& random)
{
  std::uniform_real_distribution<double> parameter(0.05, 0.95);
  std::vector<glm::dvec3> out;
  for (std::size_t k = 0; k < corners.size(); ++k)
  {
    const glm::dvec3 a = corners[k], b = corners[(k + 1) % corners.size()];
    out.push_back(a);
    std::vector<double> ts;
    for (int i = 0; i < onSide[k]; ++i)
    {
      ts.push_back(parameter(random));
    }
    std::sort(ts.begin(), ts.end());
    for (double t : ts)
    {
      out.push_back(a + (b - a) * t);
    }
  }
  std::rotate(
    out.begin(), out.begin() + static_cast<std::ptrdiff_t>(start % out.size()), out.end());
  return out;
}

/// Random convex polygons (3-7 corners on an ellipse in a random plane, some far from the
/// origin) with 0-4 points on each side, started at a random vertex.
std::vector<Polygon> randomPolygons(unsigned seed, int count)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Polygon> all;
  for (int p = 0; p < count; ++p)
  {
    const int n = 3 + static_cast<int>(random() % 5);
    std::vector<double> angles;
    for (int k = 0; k < n; ++k)
    {
      angles.push_back(3.14159265358979 * (unit(random) + 1.0));
    }
    std::sort(angles.begin(), angles.end());
    glm::dvec3 normal(unit(random), unit(random), unit(random));
    if (glm::dot(normal, normal) < 1e-6)
    {
      normal = glm::dvec3(0.0, 0.0, 1.0);
    }
    normal = glm::normalize(normal);
    const glm::dvec3 u = glm::normalize(glm::cross(
      normal, std::abs(normal.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0)));
    const glm::dvec3 v = glm::cross(normal, u);
    const glm::dvec3 centre = (p % 4 == 3 ? 1e6 : 1.0) * glm::dvec3(unit(random), unit(random), 0);
    const double a = 1.0 + 3.0 * (unit(random) + 1.0), b = 0.2 + (unit(random) + 1.0);
    std::vector<glm::dvec3> corners;
    for (double t : angles)
    {
      corners.push_back(centre + a * std::cos(t) * u + b * std::sin(t) * v);
    }
    if (cornerCount(corners) != corners.size())
    {
      continue; // two angles too close: not the corners asked for
    }
    std::vector<int> onSide;
    for (int k = 0; k < n; ++k)
    {
      onSide.push_back(static_cast<int>(random() % 5));
    }
    const std::size_t total = static_cast<std::size_t>(n) +
      static_cast<std::size_t>(std::accumulate(onSide.begin(), onSide.end(), 0));
    all.push_back({ "random " + std::to_string(p),
      withPointsOnSides(corners, onSide, random() % total, random) });
  }
  return all;
}

std::vector<Polygon> handMade()
{
  std::mt19937 random(7);
  const std::vector<glm::dvec3> triangle{ { 0, 0, 0 }, { 4, 0, 0 }, { 1, 3, 0 } };
  const std::vector<glm::dvec3> square{ { 0, 0, 0 }, { 2, 0, 0 }, { 2, 2, 0 }, { 0, 2, 0 } };
  std::vector<Polygon> all;
  all.push_back({ "triangle", triangle });
  // A fan from vertex 0 spans side 0 (0 to 1) with its points: flat triangles.
  all.push_back(
    { "triangle, 1 point on side 0", withPointsOnSides(triangle, { 1, 0, 0 }, 0, random) });
  all.push_back({ "triangle, 2 on side 0", withPointsOnSides(triangle, { 2, 0, 0 }, 0, random) });
  all.push_back(
    { "triangle, 1 on every side", withPointsOnSides(triangle, { 1, 1, 1 }, 0, random) });
  // No vertex has a clean fan: every corner touches a side with points, every point shares its
  // side with another.
  all.push_back(
    { "triangle, 2 on every side", withPointsOnSides(triangle, { 2, 2, 2 }, 0, random) });
  all.push_back({ "triangle, 3 0 3", withPointsOnSides(triangle, { 3, 0, 3 }, 2, random) });
  all.push_back(
    { "square, 2 on every side", withPointsOnSides(square, { 2, 2, 2, 2 }, 1, random) });
  all.push_back({ "square, 5 on one side", withPointsOnSides(square, { 0, 0, 5, 0 }, 3, random) });
  return all;
}

/// The hand-made cases, then @p count random ones.
std::vector<Polygon> handMadeAndRandom(unsigned seed, int count)
{
  std::vector<Polygon> all = handMade();
  for (Polygon& p : randomPolygons(seed, count))
  {
    all.push_back(std::move(p));
  }
  return all;
}

/// Checks the triangles of @p polygon (local indices) as the file's comment says.
void checkTriangulation(const Polygon& polygon, const std::vector<std::uint32_t>& triangles)
{
  const std::vector<glm::dvec3>& v = polygon.vertices;
  const std::size_t n = v.size();
  ASSERT_EQ(triangles.size(), 3 * (n - 2)) << polygon.name;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  glm::dvec3 area(0.0);
  const glm::dvec3 normal = glm::normalize(doubledAreaVector(v));
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    const std::uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    ASSERT_LT(std::max({ a, b, c }), n) << polygon.name;
    EXPECT_FALSE(collinear(v[a], v[b], v[c]))
      << polygon.name << ": flat triangle " << a << " " << b << " " << c;
    const glm::dvec3 twice = glm::cross(v[b] - v[a], v[c] - v[a]);
    EXPECT_GT(glm::dot(twice, normal), 0.0) << polygon.name << ": not in the polygon's winding";
    area += twice;
    ++edges[{ a, b }];
    ++edges[{ b, c }];
    ++edges[{ c, a }];
  }
  for (std::uint32_t k = 0; k < n; ++k)
  {
    const std::uint32_t next = static_cast<std::uint32_t>((k + 1) % n);
    EXPECT_EQ(edges[std::make_pair(k, next)], 1) << polygon.name << ": edge " << k << "-" << next;
  }
  const double expected = glm::length(doubledAreaVector(v));
  EXPECT_NEAR(glm::dot(area, normal), expected, 1e-9 * expected) << polygon.name;
}
} // namespace

TEST(ConvexTriangulation, EveryEdgeOfThePolygonIsAnEdgeOfOneTriangleWithArea)
{
  const std::vector<Polygon> all = handMadeAndRandom(11, 3000);
  std::size_t fannedFromZero = 0;
  for (const Polygon& polygon : all)
  {
    std::vector<std::uint32_t> triangles;
    scenevis::triangulateConvex(polygon.vertices.data(), polygon.vertices.size(), triangles);
    checkTriangulation(polygon, triangles);
    fannedFromZero +=
      scenevis::flatFanTriangles(polygon.vertices.data(), polygon.vertices.size(), 0) == 0;
  }
  // The cases reach both ways: plain fans and clipped ears.
  EXPECT_GT(fannedFromZero, 100u);
  EXPECT_LT(fannedFromZero, all.size() - 100);
}

TEST(ConvexTriangulation, TheCleanestApexHasTheFewestFlatFanTrianglesAndComesFirst)
{
  const std::vector<Polygon> all = handMadeAndRandom(12, 2000);
  std::size_t moved = 0;
  for (const Polygon& polygon : all)
  {
    const glm::dvec3* v = polygon.vertices.data();
    const std::size_t n = polygon.vertices.size();
    std::vector<std::size_t> flat(n);
    for (std::size_t apex = 0; apex < n; ++apex)
    {
      // Brute force: the triangles of the fan, each tested.
      for (std::size_t k = 1; k + 1 < n; ++k)
      {
        flat[apex] += collinear(v[apex], v[(apex + k) % n], v[(apex + k + 1) % n]);
      }
    }
    const std::size_t best =
      static_cast<std::size_t>(std::min_element(flat.begin(), flat.end()) - flat.begin());
    EXPECT_EQ(scenevis::cleanestFanApex(v, n), best) << polygon.name;
    moved += best != 0;
  }
  EXPECT_GT(moved, 100u);
}

TEST(ConvexTriangulation, NoAreaNoFlatnessToAvoid)
{
  // Two coincident points, or all on a line: n - 2 triangles all the same, and no hang.
  const std::vector<glm::dvec3> line{ { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 3, 0, 0 } };
  std::vector<std::uint32_t> triangles;
  scenevis::triangulateConvex(line.data(), line.size(), triangles);
  EXPECT_EQ(triangles.size(), 6u);
  triangles.clear();
  scenevis::triangulateConvex(line.data(), 2, triangles);
  EXPECT_TRUE(triangles.empty());
  EXPECT_TRUE(collinear(line[0], line[0], line[3]));
}

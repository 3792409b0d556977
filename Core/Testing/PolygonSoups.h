#pragma once
// Test geometry shared by the core tests and benchmarks (TestBspOrder, TestPainterSort,
// TestOrderOracle, TestBspBuilder, TestBspTraversal, BenchBsp): small hand-made polygon sets, the
// UV sphere, random soups and random viewers. Header-only; every function is deterministic (for
// its seed), so a failing case can be replayed.

#include "scenevis/OrderOracle.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/View.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace scenevis
{
namespace testsupport
{

using oracle::Polygon;

constexpr double kPi = 3.14159265358979323846;

/// The polygons as one mesh (no shared points), polygon i = input i.
inline PolygonMesh meshOf(const std::vector<Polygon>& polygons)
{
  PolygonMesh mesh;
  for (const Polygon& poly : polygons)
  {
    std::vector<std::uint32_t> ids;
    for (const glm::dvec3& p : poly)
    {
      ids.push_back(mesh.addPoint(p));
    }
    mesh.addPolygon(ids.data(), ids.size());
  }
  return mesh;
}

/**
 * Closed unit UV sphere of about `triangles` triangles: stacks = round(sqrt(triangles / 4)),
 * slices = 2 * stacks, single pole points. (scenes::sphere() picks its resolution differently;
 * the BSP figures in BENCHMARKS.md were measured on this one.)
 */
inline PolygonMesh uvSphere(std::size_t triangles)
{
  const int stacks = std::max(2, static_cast<int>(std::lround(std::sqrt(triangles / 4.0))));
  const int slices = 2 * stacks;
  PolygonMesh mesh;
  const std::uint32_t north = mesh.addPoint({ 0, 0, 1 });
  for (int i = 1; i < stacks; ++i)
  {
    const double theta = kPi * i / stacks;
    for (int j = 0; j < slices; ++j)
    {
      const double phi = 2 * kPi * j / slices;
      mesh.addPoint({ std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
        std::cos(theta) });
    }
  }
  const std::uint32_t south = mesh.addPoint({ 0, 0, -1 });
  auto ring = [&](int i, int j)
  { return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices)); };
  for (int j = 0; j < slices; ++j)
  {
    mesh.addPolygon({ north, ring(1, j), ring(1, j + 1) });
    mesh.addPolygon({ south, ring(stacks - 1, j + 1), ring(stacks - 1, j) });
  }
  for (int i = 1; i + 1 < stacks; ++i)
  {
    for (int j = 0; j < slices; ++j)
    {
      mesh.addPolygon({ ring(i, j), ring(i + 1, j), ring(i + 1, j + 1) });
      mesh.addPolygon({ ring(i, j), ring(i + 1, j + 1), ring(i, j + 1) });
    }
  }
  return mesh;
}

/// Axis-aligned rectangle [x0, x1] x [y0, y1] at height z, counter-clockwise seen from +z.
inline Polygon rectZ(double z, double x0, double x1, double y0, double y1)
{
  return { { x0, y0, z }, { x1, y0, z }, { x1, y1, z }, { x0, y1, z } };
}

/**
 * Three sticks in a cycle: stick k lies above stick k+1 where they cross, so no order of the
 * whole sticks is correct seen from above; a correct order must split one of them.
 */
inline std::vector<Polygon> cyclicSticks()
{
  std::vector<glm::dvec3> corner;
  for (int k = 0; k < 3; ++k)
  {
    const double angle = kPi / 2 + k * 2 * kPi / 3;
    corner.emplace_back(std::cos(angle), std::sin(angle), 0.0);
  }
  std::vector<Polygon> sticks;
  const double extension = 0.2;
  const double halfWidth = 0.1;
  for (int k = 0; k < 3; ++k)
  {
    const glm::dvec3 a = corner[k];
    const glm::dvec3 b = corner[(k + 1) % 3];
    const double length = glm::length(b - a);
    const glm::dvec3 d = (b - a) / length;
    const glm::dvec3 m(-d.y, d.x, 0.0);
    auto at = [&](double s, double side)
    {
      glm::dvec3 p = a + d * s + m * (side * halfWidth);
      p.z = 0.1 + 0.8 * (s + extension) / (length + 2 * extension);
      return p;
    };
    const double s0 = -extension;
    const double s1 = length + extension;
    sticks.push_back({ at(s0, -1), at(s1, -1), at(s1, 1), at(s0, 1) });
  }
  return sticks;
}

/// "perspective(x, y, z)" or "parallel(x, y, z)" with full precision, for failure messages.
inline std::string describe(const View& view)
{
  std::ostringstream out;
  out.precision(17);
  out << (view.isParallel() ? "parallel(" : "perspective(") << view.eye.x << ", " << view.eye.y
      << ", " << view.eye.z << ")";
  return out.str();
}

/// Perspective eyes around (and some inside) the bounds at random directions and distances, then
/// parallel views along random directions.
inline std::vector<View> randomViews(
  const Box& bounds, std::uint64_t seed, int perspective, int parallel)
{
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double diagonal = bounds.diagonal();
  std::vector<View> views;
  auto direction = [&]
  {
    glm::dvec3 d(gauss(rng), gauss(rng), gauss(rng));
    return glm::normalize(d);
  };
  for (int i = 0; i < perspective; ++i)
  {
    // Distances from deep inside to well outside, uniform in log scale.
    const double distance = diagonal * 0.02 * std::pow(150.0, unit(rng));
    views.push_back(View::perspective(bounds.center() + direction() * distance));
  }
  for (int i = 0; i < parallel; ++i)
  {
    views.push_back(View::parallel(direction()));
  }
  return views;
}

/// Bounds of a list of polygons.
inline Box boundsOf(const std::vector<Polygon>& polygons)
{
  Box box;
  for (const Polygon& poly : polygons)
  {
    for (const glm::dvec3& p : poly)
    {
      box.extend(p);
    }
  }
  return box;
}

/// A random convex polygon (triangle or planar quad) of size about `size` centred at `c`.
inline Polygon randomPolygon(std::mt19937_64& rng, const glm::dvec3& c, double size)
{
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  if (unit(rng) < 0.5)
  {
    Polygon tri;
    for (int k = 0; k < 3; ++k)
    {
      tri.push_back(c + glm::dvec3(gauss(rng), gauss(rng), gauss(rng)) * (0.5 * size));
    }
    return tri;
  }
  // A convex quad: four points on an ellipse in a random plane, angles a quarter turn apart.
  const glm::dvec3 normal = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
  const glm::dvec3 helper = std::abs(normal.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, normal));
  const glm::dvec3 v = glm::cross(normal, u);
  const double ru = size * (0.3 + 0.7 * unit(rng));
  const double rv = size * (0.3 + 0.7 * unit(rng));
  const double start = unit(rng) * 2 * kPi;
  Polygon quad;
  for (int k = 0; k < 4; ++k)
  {
    const double angle = start + k * kPi / 2 + (unit(rng) - 0.5) * 0.8;
    quad.push_back(c + u * (ru * std::cos(angle)) + v * (rv * std::sin(angle)));
  }
  return quad;
}

/// `count` random triangles and quads inside the unit cube.
inline std::vector<Polygon> randomSoup(std::uint64_t seed, int count, double size = 0.35)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Polygon> soup;
  for (int i = 0; i < count; ++i)
  {
    const glm::dvec3 c(unit(rng), unit(rng), unit(rng));
    soup.push_back(randomPolygon(rng, c, size * (0.3 + unit(rng))));
  }
  return soup;
}

} // namespace testsupport
} // namespace scenevis

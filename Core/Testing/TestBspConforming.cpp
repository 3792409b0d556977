// Conforming fragments (BuildConfig::conformingFragments, makeConforming): the fragments of a BSP
// tree, and of the painter's algorithm, meet edge to edge. No fragment vertex may lie strictly
// inside another fragment's edge (a T-junction, where OpenGL covers pixels twice or not at all),
// checked by brute force over every vertex and every edge. The fragments keep covering exactly what
// they covered: the same fragments, sources and (doubled) areas, only collinear vertices added.
// Without the option the same check finds T-junctions on every scene, so it can fail.
#include "scenevis/BspBuilder.h"
#include "scenevis/ConvexTriangulation.h"
#include "scenevis/PainterSort.h"
#include "scenevis/Scenes.h"

#include "PolygonSoups.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

using scenevis::PolygonMesh;
using scenevis::bsp::BuildConfig;
using scenevis::bsp::Tree;

namespace
{
/**
 * T-junctions between fragments of one surface: a vertex of fragment G lying strictly inside an
 * edge of fragment F (within 1e-9 of the edge's length, away from its ends), when G is a piece of
 * the same input polygon as F or of one sharing an input edge with it. (Fragments of two
 * surfaces that pass through each other meet along their intersection line with vertices on
 * each other's edges; OpenGL needs no common edge between them, so those are not counted.)
 */
template <typename Fragments> // bsp::Tree or painter::Result
std::size_t countTJunctions(const PolygonMesh& mesh, const Fragments& tree)
{
  // Input polygons sharing an input edge.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> byEdge;
  for (std::uint32_t p = 0; p < mesh.polygonCount(); ++p)
  {
    const std::uint32_t* ids = mesh.polygon(p);
    const std::size_t n = mesh.offsets[p + 1] - mesh.offsets[p];
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::uint32_t a = ids[k], b = ids[(k + 1) % n];
      byEdge[{ std::min(a, b), std::max(a, b) }].push_back(p);
    }
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> neighbours;
  for (const auto& edge : byEdge)
  {
    for (std::uint32_t p : edge.second)
    {
      for (std::uint32_t q : edge.second)
      {
        neighbours.insert({ p, q });
      }
    }
  }
  std::size_t count = 0;
  for (const auto& f : tree.fragments)
  {
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const std::uint32_t u = tree.fragmentVertices[f.first + k];
      const std::uint32_t v = tree.fragmentVertices[f.first + (k + 1) % f.count];
      const glm::dvec3 a = tree.points[u], b = tree.points[v];
      const glm::dvec3 ab = b - a;
      const double length2 = glm::dot(ab, ab);
      if (length2 == 0.0)
      {
        continue;
      }
      for (const auto& g : tree.fragments)
      {
        if (g.source != f.source && !neighbours.count({ f.source, g.source }))
        {
          continue;
        }
        for (std::uint32_t j = 0; j < g.count; ++j)
        {
          const std::uint32_t w = tree.fragmentVertices[g.first + j];
          if (w == u || w == v)
          {
            continue;
          }
          const double t = glm::dot(tree.points[w] - a, ab) / length2;
          const glm::dvec3 off = tree.points[w] - (a + t * ab);
          if (t > 1e-6 && t < 1.0 - 1e-6 && glm::dot(off, off) <= 1e-18 * length2)
          {
            ++count;
          }
        }
      }
    }
  }
  return count;
}

/// Twice the area of fragment @p f (a convex planar polygon).
double doubledArea(const Tree& tree, const scenevis::bsp::Fragment& f)
{
  glm::dvec3 sum(0.0);
  const glm::dvec3 p0 = tree.points[tree.fragmentVertices[f.first]];
  for (std::uint32_t k = 1; k + 1 < f.count; ++k)
  {
    sum += glm::cross(tree.points[tree.fragmentVertices[f.first + k]] - p0,
      tree.points[tree.fragmentVertices[f.first + k + 1]] - p0);
  }
  return glm::length(sum);
}

struct Case
{
  std::string name;
  PolygonMesh mesh;
};

/// Meshes whose polygons share edges (closed surfaces passing through each other): splits
/// leave T-junctions unless the fragments are made conforming.
std::vector<Case> surfaces()
{
  using namespace scenevis;
  std::vector<Case> all;
  all.push_back({ "sphere grid 2x2x2", scenes::sphereGrid(2, 0.8, 1.0, 120).mesh });
  all.push_back({ "sphere grid 3x3x3", scenes::sphereGrid(3, 0.6, 1.0, 80).mesh });
  all.push_back({ "cad assembly", scenes::cadAssembly(12, 40, 5).mesh });
  return all;
}

/// The surfaces, and polygon soups with no shared edge (nothing to make conforming).
std::vector<Case> cases()
{
  using namespace scenevis;
  std::vector<Case> all = surfaces();
  all.push_back({ "interpenetrating triangles", scenes::interpenetratingTriangles().mesh });
  all.push_back({ "cyclic quads", scenes::cyclicQuads().mesh });
  all.push_back({ "random soup", testsupport::meshOf(testsupport::randomSoup(7, 60)) });
  return all;
}
} // namespace

TEST(BspConforming, FragmentsMeetEdgeToEdge)
{
  for (const Case& c : cases())
  {
    const Tree tree = scenevis::bsp::build(c.mesh);
    ASSERT_FALSE(tree.empty()) << c.name;
    EXPECT_GT(tree.statistics.splits, 0u) << c.name << ": the scene must split something";
    EXPECT_EQ(countTJunctions(c.mesh, tree), 0u) << c.name;
  }
}

TEST(BspConforming, WithoutTheOptionSplitsLeaveTJunctions)
{
  BuildConfig off;
  off.conformingFragments = false;
  for (const Case& c : surfaces())
  {
    const Tree tree = scenevis::bsp::build(c.mesh, off);
    EXPECT_EQ(tree.statistics.conformingVertices, 0u) << c.name;
    EXPECT_GT(countTJunctions(c.mesh, tree), 0u)
      << c.name << ": the check must see the T-junctions";
  }
}

TEST(BspConforming, SameFragmentsSameAreasOnlyCollinearVerticesAdded)
{
  BuildConfig off;
  off.conformingFragments = false;
  for (const Case& c : cases())
  {
    const Tree plain = scenevis::bsp::build(c.mesh, off);
    const Tree conforming = scenevis::bsp::build(c.mesh);
    ASSERT_EQ(plain.fragments.size(), conforming.fragments.size()) << c.name;
    EXPECT_EQ(plain.nodes.size(), conforming.nodes.size()) << c.name;
    EXPECT_EQ(plain.points.size(), conforming.points.size()) << c.name << ": no new points";
    std::size_t added = 0;
    for (std::size_t i = 0; i < plain.fragments.size(); ++i)
    {
      const auto& p = plain.fragments[i];
      const auto& q = conforming.fragments[i];
      EXPECT_EQ(p.source, q.source) << c.name;
      ASSERT_GE(q.count, p.count) << c.name;
      added += q.count - p.count;
      const double area = doubledArea(plain, p);
      EXPECT_NEAR(doubledArea(conforming, q), area, 1e-9 * (1.0 + area)) << c.name;
      // The plain fragment's vertices, in the same cyclic order, are a subsequence (from
      // wherever the conforming fragment starts: makeConforming picks its fan apex).
      std::uint32_t start = 0;
      while (start < q.count &&
        conforming.fragmentVertices[q.first + start] != plain.fragmentVertices[p.first])
      {
        ++start;
      }
      std::uint32_t next = 0;
      for (std::uint32_t k = 0; k < q.count && next < p.count; ++k)
      {
        if (conforming.fragmentVertices[q.first + (start + k) % q.count] ==
          plain.fragmentVertices[p.first + next])
        {
          ++next;
        }
      }
      EXPECT_EQ(next, p.count) << c.name << ": fragment " << i;
    }
    EXPECT_EQ(added, conforming.statistics.conformingVertices) << c.name;
  }
}

/// What an OpenGL mapper draws of a fragment is the fan from its first vertex. Conforming
/// fragments have points on their sides; a fan from a vertex on such a side makes flat
/// triangles and spans the side with one edge, a T-junction again. Each fragment must start at
/// a vertex whose fan has the fewest flat triangles (brute force over every vertex).
TEST(BspConforming, FragmentsStartAtTheirCleanestFanApex)
{
  for (const Case& c : surfaces())
  {
    const Tree tree = scenevis::bsp::build(c.mesh);
    std::size_t withPoints = 0, flatFromZero = 0;
    std::vector<glm::dvec3> v;
    for (const auto& f : tree.fragments)
    {
      v.clear();
      for (std::uint32_t k = 0; k < f.count; ++k)
      {
        v.push_back(tree.points[tree.fragmentVertices[f.first + k]]);
      }
      std::size_t fewest = f.count;
      for (std::size_t apex = 0; apex < f.count; ++apex)
      {
        fewest = std::min(fewest, scenevis::flatFanTriangles(v.data(), f.count, apex));
      }
      const std::size_t fromZero = scenevis::flatFanTriangles(v.data(), f.count, 0);
      EXPECT_EQ(fromZero, fewest) << c.name;
      bool onSide = false;
      for (std::size_t k = 0; k < f.count; ++k)
      {
        onSide =
          onSide || scenevis::collinear(v[(k + f.count - 1) % f.count], v[k], v[(k + 1) % f.count]);
      }
      withPoints += onSide;
      flatFromZero += fromZero;
    }
    EXPECT_GT(withPoints, 10u) << c.name << ": the scene must put points on fragment sides";
    RecordProperty(c.name + " flat fan triangles", static_cast<int>(flatFromZero));
  }
}

/// The painter's algorithm (PainterSort.h) splits per view, with the BSP's point conventions: its
/// fragments meet edge to edge too, and without the option they do not.
TEST(BspConforming, PainterFragmentsMeetEdgeToEdge)
{
  scenevis::painter::Config off;
  off.conformingFragments = false;
  for (const Case& c : surfaces())
  {
    const auto view = scenevis::View::perspective({ 3.1, 2.2, 4.3 });
    const scenevis::painter::Result plain = scenevis::painter::sort(c.mesh, view, off);
    const scenevis::painter::Result conforming = scenevis::painter::sort(c.mesh, view);
    EXPECT_GT(conforming.statistics.splits, 0u) << c.name << ": the view must split something";
    EXPECT_GT(conforming.statistics.conformingVertices, 0u) << c.name;
    EXPECT_EQ(plain.fragments.size(), conforming.fragments.size()) << c.name;
    EXPECT_GT(countTJunctions(c.mesh, plain), 0u) << c.name;
    EXPECT_EQ(countTJunctions(c.mesh, conforming), 0u) << c.name;
  }
}

TEST(BspConforming, ParallelBuildGivesTheSameTree)
{
  const PolygonMesh mesh = scenevis::scenes::sphereGrid(3, 0.8, 1.0, 80).mesh;
  BuildConfig serial, parallel;
  parallel.threads = 2;
  const Tree a = scenevis::bsp::build(mesh, serial);
  const Tree b = scenevis::bsp::build(mesh, parallel);
  EXPECT_EQ(a.fragmentVertices, b.fragmentVertices);
  EXPECT_GT(b.statistics.conformingVertices, 0u);
  EXPECT_EQ(countTJunctions(mesh, b), 0u);
}

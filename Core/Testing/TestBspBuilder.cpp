// Specification of bsp::build: normalisation of the input, splitting without cracks, statistics,
// precision far from the origin, depth on convex meshes, determinism and cancellation.
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/Scenes.h"

#include "PolygonSoups.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <vector>

namespace
{

using namespace scenevis;
using bsp::BuildConfig;

BuildConfig firstInList()
{
  BuildConfig config;
  config.partition = BuildConfig::Partition::FirstInList;
  return config;
}

std::uint32_t addQuad(PolygonMesh& mesh, const glm::dvec3& a, const glm::dvec3& b,
  const glm::dvec3& c, const glm::dvec3& d)
{
  const std::uint32_t i = mesh.addPoint(a);
  mesh.addPoint(b);
  mesh.addPoint(c);
  mesh.addPoint(d);
  return mesh.addPolygon({ i, i + 1, i + 2, i + 3 });
}

std::uint32_t addTriangle(
  PolygonMesh& mesh, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
  const std::uint32_t i = mesh.addPoint(a);
  mesh.addPoint(b);
  mesh.addPoint(c);
  return mesh.addPolygon({ i, i + 1, i + 2 });
}

/// Closed UV sphere (slices = 2 * stacks); `rotate` turns it off the axes so that no free plane
/// can run along its latitude rings.
PolygonMesh uvSphere(std::size_t triangles, bool rotate = false)
{
  PolygonMesh mesh = scenevis::testsupport::uvSphere(triangles);
  if (rotate)
  {
    const double a = 0.7;
    const double b = 0.4;
    for (glm::dvec3& p : mesh.points)
    {
      const glm::dvec3 q(
        std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z);
      p = glm::dvec3(
        q.x, std::cos(b) * q.y - std::sin(b) * q.z, std::sin(b) * q.y + std::cos(b) * q.z);
    }
  }
  return mesh;
}

/// Deterministic soup of random, mostly intersecting triangles in [-1, 1]^3. Coordinates are
/// multiples of 2^-20, so adding 1e7 to them is exact.
PolygonMesh randomSoup(int triangles, std::uint64_t seed, const glm::dvec3& offset = glm::dvec3(0))
{
  std::uint64_t state = seed * 0x9e3779b97f4a7c15ull + 1;
  auto next = [&state]()
  {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    const auto q = static_cast<std::int64_t>(state >> 43) - (std::int64_t(1) << 20);
    return std::ldexp(static_cast<double>(q), -20);
  };
  PolygonMesh mesh;
  for (int t = 0; t < triangles; ++t)
  {
    const glm::dvec3 c(next(), next(), next());
    glm::dvec3 p[3];
    for (glm::dvec3& q : p)
    {
      q = offset + c + glm::dvec3(next(), next(), next()) * 0.5;
    }
    addTriangle(mesh, p[0], p[1], p[2]);
  }
  return mesh;
}

double fragmentArea(const bsp::Tree& tree, const bsp::Fragment& f)
{
  return 0.5 *
    glm::length(newellNormal(tree.points.data(), tree.fragmentVertices.data() + f.first, f.count));
}

double totalFragmentArea(const bsp::Tree& tree)
{
  double sum = 0.0;
  for (const bsp::Fragment& f : tree.fragments)
  {
    sum += fragmentArea(tree, f);
  }
  return sum;
}

double distanceToPlane(const bsp::Tree& tree, const glm::dvec4& plane, std::uint32_t id)
{
  return glm::dot(glm::dvec3(plane), tree.points[id] - tree.origin) + plane.w;
}

/// Parent of every node (kNone for the root).
std::vector<std::uint32_t> parents(const bsp::Tree& tree)
{
  std::vector<std::uint32_t> parent(tree.nodes.size(), bsp::kNone);
  for (std::uint32_t i = 0; i < tree.nodes.size(); ++i)
  {
    for (std::uint32_t child : { tree.nodes[i].front, tree.nodes[i].back })
    {
      if (child != bsp::kNone)
      {
        parent[child] = i;
      }
    }
  }
  return parent;
}

/// Node owning each fragment.
std::vector<std::uint32_t> fragmentNodes(const bsp::Tree& tree)
{
  std::vector<std::uint32_t> node(tree.fragments.size(), bsp::kNone);
  for (std::uint32_t i = 0; i < tree.nodes.size(); ++i)
  {
    for (std::uint32_t k = 0; k < tree.nodes[i].fragmentCount; ++k)
    {
      node[tree.nodes[i].firstFragment + k] = i;
    }
  }
  return node;
}

void expectSameTree(const bsp::Tree& a, const bsp::Tree& b)
{
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
  {
    ASSERT_EQ(a.nodes[i].plane, b.nodes[i].plane) << "node " << i;
    ASSERT_EQ(a.nodes[i].front, b.nodes[i].front);
    ASSERT_EQ(a.nodes[i].back, b.nodes[i].back);
    ASSERT_EQ(a.nodes[i].firstFragment, b.nodes[i].firstFragment);
    ASSERT_EQ(a.nodes[i].fragmentCount, b.nodes[i].fragmentCount);
  }
  ASSERT_EQ(a.fragments.size(), b.fragments.size());
  for (std::size_t i = 0; i < a.fragments.size(); ++i)
  {
    ASSERT_EQ(a.fragments[i].source, b.fragments[i].source);
    ASSERT_EQ(a.fragments[i].first, b.fragments[i].first);
    ASSERT_EQ(a.fragments[i].count, b.fragments[i].count);
  }
  EXPECT_EQ(a.fragmentVertices, b.fragmentVertices);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.root, b.root);
}

TEST(BspBuilder, EmptyMeshGivesEmptyTree)
{
  const bsp::Tree tree = bsp::build(PolygonMesh{});
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(tree.statistics.nodes, 0u);
  std::vector<std::uint32_t> order{ 7 };
  bsp::order(tree, View::perspective({ 0, 0, 5 }), bsp::Direction::BackToFront, order);
  EXPECT_TRUE(order.empty());
}

TEST(BspBuilder, TwoCrossingQuadsNeedExactlyOneSplit)
{
  PolygonMesh mesh;
  addQuad(mesh, { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 });
  addQuad(mesh, { 0, -1, -1 }, { 0, 1, -1 }, { 0, 1, 1 }, { 0, -1, 1 });
  for (const BuildConfig& config : { BuildConfig{}, firstInList() })
  {
    const bsp::Tree tree = bsp::build(mesh, config);
    EXPECT_EQ(tree.statistics.splits, 1u);
    EXPECT_EQ(tree.statistics.fragments, 3u);
    EXPECT_EQ(tree.fragments.size(), 3u);
    EXPECT_EQ(tree.statistics.nodes, 3u);
    EXPECT_EQ(tree.splitPoints.size(), 2u) << "one new point on each of the two cut edges";
    EXPECT_NEAR(totalFragmentArea(tree), 8.0, 1e-12);
  }
}

TEST(BspBuilder, CubeNeedsNoSplits)
{
  PolygonMesh mesh;
  for (int i = 0; i < 8; ++i)
  {
    mesh.addPoint({ (i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0 });
  }
  // Outward-facing faces.
  mesh.addPolygon({ 0, 2, 3, 1 });
  mesh.addPolygon({ 4, 5, 7, 6 });
  mesh.addPolygon({ 0, 1, 5, 4 });
  mesh.addPolygon({ 2, 6, 7, 3 });
  mesh.addPolygon({ 0, 4, 6, 2 });
  mesh.addPolygon({ 1, 3, 7, 5 });
  for (const BuildConfig& config : { BuildConfig{}, firstInList() })
  {
    const bsp::Tree tree = bsp::build(mesh, config);
    EXPECT_EQ(tree.statistics.fragments, 6u);
    EXPECT_EQ(tree.statistics.splits, 0u);
    EXPECT_EQ(tree.statistics.nodes, 6u);
    EXPECT_EQ(tree.statistics.depth, 6u) << "a convex solid is a chain";
    EXPECT_EQ(tree.statistics.triangulatedPolygons, 0u) << "convex planar quads are kept";
    for (const bsp::Fragment& f : tree.fragments)
    {
      EXPECT_EQ(f.count, 4u);
    }
    EXPECT_TRUE(tree.splitPoints.empty());
    EXPECT_EQ(tree.points.size(), 8u);
  }
}

TEST(BspBuilder, CoplanarPolygonsShareANode)
{
  PolygonMesh mesh;
  // Two disjoint triangles in z = 0, one of them facing down, and one triangle above them.
  addTriangle(mesh, { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 });
  addTriangle(mesh, { 0, 0, 2 }, { 1, 0, 2 }, { 0, 1, 2 });
  addTriangle(mesh, { 3, 0, 0 }, { 3, 1, 0 }, { 4, 0, 0 });
  for (const BuildConfig& config : { BuildConfig{}, firstInList() })
  {
    const bsp::Tree tree = bsp::build(mesh, config);
    EXPECT_EQ(tree.statistics.nodes, 2u);
    EXPECT_EQ(tree.statistics.fragments, 3u);
    bool found = false;
    for (const bsp::Node& node : tree.nodes)
    {
      if (node.fragmentCount == 2)
      {
        found = true;
        // Own fragments in ascending input order.
        EXPECT_EQ(tree.fragments[node.firstFragment].source, 0u);
        EXPECT_EQ(tree.fragments[node.firstFragment + 1].source, 2u);
      }
    }
    EXPECT_TRUE(found);
  }
}

TEST(BspBuilder, DegenerateAndInvalidPolygonsAreRemovedAndCounted)
{
  PolygonMesh mesh;
  const std::uint32_t a = mesh.addPoint({ 0, 0, 0 });
  const std::uint32_t b = mesh.addPoint({ 1, 0, 0 });
  const std::uint32_t c = mesh.addPoint({ 0, 1, 0 });
  const std::uint32_t mid = mesh.addPoint({ 0.5, 0, 0 });
  const std::uint32_t nan = mesh.addPoint({ std::numeric_limits<double>::quiet_NaN(), 0, 0 });
  const std::uint32_t inf = mesh.addPoint({ 0, std::numeric_limits<double>::infinity(), 0 });
  mesh.addPolygon({ a, b, c });          // valid
  mesh.addPolygon({ a, a, b, b });       // two distinct points after removing repeats
  mesh.addPolygon({ a, b, b, c, a });    // repeats (also cyclic) removed: a valid triangle
  mesh.addPolygon({ a, mid, b });        // collinear: zero area
  mesh.addPolygon({ a, b });             // too few points
  mesh.addPolygon({ a, b, nan });        // NaN point
  mesh.addPolygon({ a, inf, c });        // Inf point
  mesh.addPolygon({ a, b, 1000 });       // out-of-range id
  const bsp::Tree tree = bsp::build(mesh);
  const bsp::BuildStatistics& s = tree.statistics;
  EXPECT_EQ(s.inputPolygons, 8u);
  EXPECT_EQ(s.degeneratePolygons, 3u);
  EXPECT_EQ(s.invalidPolygons, 3u);
  ASSERT_EQ(s.fragments, 2u);
  EXPECT_EQ(tree.fragments[0].source, 0u);
  EXPECT_EQ(tree.fragments[1].source, 2u);
  EXPECT_EQ(tree.fragments[1].count, 3u) << "repeated ids are dropped, not kept as edges";
  // Finite bounds only: the NaN/Inf points do not move the origin or the tolerance.
  EXPECT_EQ(tree.origin, glm::dvec3(0.5, 0.5, 0.0));
  EXPECT_NEAR(s.tolerance, 1e-10 * std::sqrt(2.0), 1e-20);
}

TEST(BspBuilder, ConcavePolygonIsTriangulatedConservingArea)
{
  // An L: the unit square [0,2]x[0,2] minus [1,2]x[1,2], area 3, counter-clockwise, tilted out of
  // the axis planes so that the projection is exercised too.
  const glm::dvec3 u = glm::normalize(glm::dvec3(1, 1, 0));
  const glm::dvec3 v = glm::normalize(glm::dvec3(-1, 1, 1));
  const glm::dvec2 l[6] = { { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
  const glm::dvec3 w = glm::normalize(v - u * glm::dot(u, v));
  PolygonMesh mesh;
  std::vector<std::uint32_t> ids;
  for (const glm::dvec2& p : l)
  {
    ids.push_back(mesh.addPoint(glm::dvec3(5, 5, 5) + u * p.x + w * p.y));
  }
  mesh.addPolygon(ids.data(), ids.size());
  const bsp::Tree tree = bsp::build(mesh);
  EXPECT_EQ(tree.statistics.triangulatedPolygons, 1u);
  EXPECT_EQ(tree.statistics.splits, 0u) << "all triangles are coplanar";
  ASSERT_EQ(tree.fragments.size(), 4u) << "a simple hexagon gives n - 2 triangles";
  for (const bsp::Fragment& f : tree.fragments)
  {
    EXPECT_EQ(f.source, 0u);
    EXPECT_EQ(f.count, 3u);
  }
  EXPECT_NEAR(totalFragmentArea(tree), 3.0, 1e-12);
  EXPECT_EQ(tree.points.size(), 6u) << "ear clipping adds no points";
  // Same winding as the input: every triangle's normal agrees with the polygon's.
  const glm::dvec3 n = newellNormal(mesh.points.data(), ids.data(), ids.size());
  for (const bsp::Fragment& f : tree.fragments)
  {
    const glm::dvec3 fn =
      newellNormal(tree.points.data(), tree.fragmentVertices.data() + f.first, f.count);
    EXPECT_GT(glm::dot(fn, n), 0.0);
  }
}

TEST(BspBuilder, NonPlanarQuadIsTriangulatedAndPlanarConvexQuadIsKept)
{
  PolygonMesh mesh;
  addQuad(mesh, { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0.3 }, { 0, 1, 0 }); // warped
  addQuad(mesh, { 0, 0, 5 }, { 1, 0, 5 }, { 1, 1, 5 }, { 0, 1, 5 });   // flat
  const bsp::Tree tree = bsp::build(mesh);
  EXPECT_EQ(tree.statistics.triangulatedPolygons, 1u);
  std::map<std::uint32_t, int> piecesBySource;
  for (const bsp::Fragment& f : tree.fragments)
  {
    ++piecesBySource[f.source];
    EXPECT_EQ(f.count, f.source == 0 ? 3u : 4u);
  }
  EXPECT_EQ(piecesBySource[0], 2);
  EXPECT_EQ(piecesBySource[1], 1);
}

TEST(BspBuilder, FragmentAreaIsConservedOnRandomSoups)
{
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
  {
    const PolygonMesh mesh = randomSoup(300, seed);
    for (const BuildConfig& config : { BuildConfig{}, firstInList() })
    {
      const bsp::Tree tree = bsp::build(mesh, config);
      EXPECT_GT(tree.statistics.splits, 100u) << "a soup of crossing triangles must split";
      EXPECT_EQ(tree.statistics.fragments, 300u + tree.statistics.splits);
      EXPECT_NEAR(totalFragmentArea(tree), mesh.area(), 1e-9 * mesh.area()) << "seed " << seed;
      // Per source polygon too: pieces add up to their polygon.
      std::vector<double> perSource(mesh.polygonCount(), 0.0);
      for (const bsp::Fragment& f : tree.fragments)
      {
        perSource[f.source] += fragmentArea(tree, f);
      }
      for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
      {
        const double area =
          0.5 * glm::length(newellNormal(mesh.points.data(), mesh.polygon(i), 3));
        ASSERT_NEAR(perSource[i], area, 1e-9 * area) << "polygon " << i;
      }
    }
  }
}

TEST(BspBuilder, SharedEdgeGetsOneSharedSplitPoint)
{
  PolygonMesh mesh;
  // First polygon: the partition plane x = 0 (FirstInList takes it as the root).
  addQuad(mesh, { 0, -5, -5 }, { 0, 5, -5 }, { 0, 5, 5 }, { 0, -5, 5 });
  // Two triangles sharing the edge (a, b), which crosses x = 0.
  const std::uint32_t a = mesh.addPoint({ -1, 0, 1 });
  const std::uint32_t b = mesh.addPoint({ 1, 0.5, 1 });
  const std::uint32_t c = mesh.addPoint({ 0.5, 2, 1.5 });
  const std::uint32_t d = mesh.addPoint({ 0.5, -2, 0.5 });
  mesh.addPolygon({ a, b, c });
  mesh.addPolygon({ b, a, d });
  const bsp::Tree tree = bsp::build(mesh, firstInList());
  EXPECT_EQ(tree.statistics.splits, 2u);
  ASSERT_EQ(tree.splitPoints.size(), 3u) << "edge (a, b) is cut once for both triangles";
  std::uint32_t shared = bsp::kNone;
  for (std::size_t i = 0; i < tree.splitPoints.size(); ++i)
  {
    if (tree.splitPoints[i].a == a && tree.splitPoints[i].b == b)
    {
      shared = static_cast<std::uint32_t>(tree.inputPointCount + i);
    }
  }
  ASSERT_NE(shared, bsp::kNone);
  std::set<std::uint32_t> sourcesUsingShared;
  for (const bsp::Fragment& f : tree.fragments)
  {
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      if (tree.fragmentVertices[f.first + k] == shared)
      {
        sourcesUsingShared.insert(f.source);
      }
    }
  }
  EXPECT_EQ(sourcesUsingShared, (std::set<std::uint32_t>{ 1, 2 }));
}

TEST(BspBuilder, SplitPointsLieOnTheirEdgeAndOnAPlaneAbove)
{
  const PolygonMesh mesh = randomSoup(200, 11);
  const bsp::Tree tree = bsp::build(mesh);
  ASSERT_FALSE(tree.splitPoints.empty());
  ASSERT_EQ(tree.points.size(), tree.inputPointCount + tree.splitPoints.size());
  for (std::size_t i = 0; i < tree.splitPoints.size(); ++i)
  {
    const bsp::SplitPoint& s = tree.splitPoints[i];
    const std::size_t id = tree.inputPointCount + i;
    ASSERT_LT(s.a, s.b);
    ASSERT_LT(s.b, id);
    ASSERT_GT(s.t, 0.0);
    ASSERT_LT(s.t, 1.0);
    const glm::dvec3 expected = tree.points[s.a] + (tree.points[s.b] - tree.points[s.a]) * s.t;
    ASSERT_LT(glm::length(tree.points[id] - expected), 1e-14);
  }
  // Every vertex of a fragment lies on its node's plane; every split vertex also lies on the
  // plane of some ancestor (the one that cut it).
  const std::vector<std::uint32_t> parent = parents(tree);
  const std::vector<std::uint32_t> owner = fragmentNodes(tree);
  const double tol = tree.tolerance * (1 + 1e-6);
  for (std::size_t fi = 0; fi < tree.fragments.size(); ++fi)
  {
    const bsp::Fragment& f = tree.fragments[fi];
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const std::uint32_t id = tree.fragmentVertices[f.first + k];
      ASSERT_LE(std::abs(distanceToPlane(tree, tree.nodes[owner[fi]].plane, id)), tol);
      if (id < tree.inputPointCount)
      {
        continue;
      }
      bool onAncestor = false;
      for (std::uint32_t n = parent[owner[fi]]; n != bsp::kNone && !onAncestor; n = parent[n])
      {
        onAncestor = std::abs(distanceToPlane(tree, tree.nodes[n].plane, id)) <= tol;
      }
      ASSERT_TRUE(onAncestor) << "split point " << id;
    }
  }
}

TEST(BspBuilder, FarFromTheOriginGivesTheSameTopology)
{
  const PolygonMesh near = randomSoup(400, 5);
  const PolygonMesh far = randomSoup(400, 5, glm::dvec3(1e7, -1e7, 1e7));
  for (const BuildConfig& config : { BuildConfig{}, firstInList() })
  {
    const bsp::Tree a = bsp::build(near, config);
    const bsp::Tree b = bsp::build(far, config);
    EXPECT_GT(a.statistics.splits, 0u);
    EXPECT_EQ(a.statistics.splits, b.statistics.splits);
    EXPECT_EQ(a.statistics.fragments, b.statistics.fragments);
    EXPECT_EQ(a.statistics.nodes, b.statistics.nodes);
    EXPECT_EQ(a.statistics.depth, b.statistics.depth);
    EXPECT_EQ(a.fragmentVertices, b.fragmentVertices);
    // At 1e7 the coordinate resolution (16 * DBL_EPSILON * 1e7 ~ 3.6e-8) exceeds the relative
    // tolerance of this small soup, so the tolerance grows to it; the topology does not change.
    EXPECT_GE(b.tolerance, a.tolerance);
    EXPECT_LE(b.tolerance, 16.0 * std::numeric_limits<double>::epsilon() * 1.1e7);
  }
}

TEST(BspBuilder, PlanarQuadFarFromTheOriginIsNotTriangulated)
{
  // A planar convex quad whose coordinates were rounded at 1e7: off its plane by ~1e-9, far more
  // than 1e-10 times this small scene's diagonal, but within the coordinate resolution.
  const glm::dvec3 points[] = { { 10000000.064927921, -9999999.9190032296, 30000000.033482913 },
    { 10000000.073561197, -9999999.9096492641, 30000000.046199989 },
    { 10000000.07458611, -9999999.9214021601, 30000000.055429883 },
    { 10000000.064789204, -9999999.9314880706, 30000000.040681362 }, { 1e7, -1e7, 3e7 },
    { 1e7 + 0.1, -1e7, 3e7 }, { 1e7 + 0.1, -1e7 + 0.1, 3e7 + 0.1 } };
  PolygonMesh mesh;
  for (const glm::dvec3& p : points)
  {
    mesh.addPoint(p);
  }
  mesh.addPolygon({ 0, 1, 2, 3 });
  mesh.addPolygon({ 4, 5, 6 });
  const bsp::Tree tree = bsp::build(mesh);
  EXPECT_EQ(tree.statistics.triangulatedPolygons, 0u);
  EXPECT_EQ(tree.statistics.degeneratePolygons, 0u);
  EXPECT_GE(tree.tolerance, 16.0 * std::numeric_limits<double>::epsilon() * 3e7);
  std::set<std::uint32_t> sources;
  for (const bsp::Fragment& f : tree.fragments)
  {
    sources.insert(f.source);
  }
  EXPECT_EQ(sources.size(), 2u);
}

TEST(BspBuilder, SplitPointsFarFromTheOriginLieOnTheirPlane)
{
  // Split points are stored in world coordinates, rounded to ~2e-9 at 1e7: the tolerance (at
  // least the coordinate resolution) must cover that, so every split vertex still classifies as
  // on the plane of the ancestor that made it.
  const PolygonMesh mesh = randomSoup(300, 17, glm::dvec3(1e7, -1e7, 3e7));
  for (const BuildConfig& config : { BuildConfig{}, firstInList() })
  {
    const bsp::Tree tree = bsp::build(mesh, config);
    ASSERT_FALSE(tree.splitPoints.empty());
    EXPECT_GE(tree.tolerance, 16.0 * std::numeric_limits<double>::epsilon() * 3e7);
    const std::vector<std::uint32_t> parent = parents(tree);
    const std::vector<std::uint32_t> owner = fragmentNodes(tree);
    for (std::size_t fi = 0; fi < tree.fragments.size(); ++fi)
    {
      const bsp::Fragment& f = tree.fragments[fi];
      for (std::uint32_t k = 0; k < f.count; ++k)
      {
        const std::uint32_t id = tree.fragmentVertices[f.first + k];
        ASSERT_LE(std::abs(distanceToPlane(tree, tree.nodes[owner[fi]].plane, id)),
          tree.tolerance);
        if (id < tree.inputPointCount)
        {
          continue;
        }
        bool onAncestor = false;
        for (std::uint32_t n = parent[owner[fi]]; n != bsp::kNone && !onAncestor; n = parent[n])
        {
          onAncestor = std::abs(distanceToPlane(tree, tree.nodes[n].plane, id)) <= tree.tolerance;
        }
        ASSERT_TRUE(onAncestor) << "split point " << id;
      }
    }
  }
}

TEST(BspBuilder, AllScoresAndEffortsBuildValidTrees)
{
  const scenes::Scene scene = scenes::sphereGrid(2, 0.8, 1.0, 2000);
  BuildConfig classic;
  classic.score = BuildConfig::Score::SplitsAndBalance;
  BuildConfig thorough;
  thorough.effort = BuildConfig::Effort::Thorough;
  for (const BuildConfig& config : { BuildConfig{}, classic, thorough })
  {
    const bsp::Tree tree = bsp::build(scene.mesh, config);
    EXPECT_GT(tree.statistics.splits, 0u);
    EXPECT_NEAR(totalFragmentArea(tree), scene.mesh.area(), 1e-9 * scene.mesh.area());
    EXPECT_LT(tree.statistics.depth, 200u);
  }
}

TEST(BspBuilder, FirstInListChainOnASphereIsBuiltAndWalkedWithoutRecursion)
{
  const PolygonMesh mesh = uvSphere(30000, true);
  const bsp::Tree tree = bsp::build(mesh, firstInList());
  // A convex mesh with polygon planes only: every plane has all others behind it, a chain.
  EXPECT_EQ(tree.statistics.splits, 0u);
  EXPECT_EQ(tree.statistics.depth, tree.statistics.nodes);
  EXPECT_GT(tree.statistics.depth, 14000u) << "one node per planar quad of the UV sphere";
  std::vector<std::uint32_t> order;
  bsp::order(tree, View::perspective({ 0.3, 0.2, 4 }), bsp::Direction::BackToFront, order);
  EXPECT_EQ(order.size(), tree.fragments.size());
  bsp::IncrementalOrder incremental(tree, bsp::Direction::BackToFront);
  incremental.update(View::perspective({ 0.3, 0.2, 4 }));
  EXPECT_EQ(incremental.order(), order);
}

TEST(BspBuilder, ScoredKeepsASphereShallowWithFewSplits)
{
  const PolygonMesh mesh = uvSphere(200000, true);
  const bsp::Tree tree = bsp::build(mesh);
  const double input = static_cast<double>(mesh.polygonCount());
  EXPECT_LT(tree.statistics.depth, 200u);
  EXPECT_GT(tree.statistics.freePlaneNodes, 0u);
  EXPECT_LE(static_cast<double>(tree.statistics.fragments), 1.5 * input);
  EXPECT_LE(static_cast<double>(tree.statistics.memoryBytes), 200.0 * input);
  EXPECT_NEAR(totalFragmentArea(tree), mesh.area(), 1e-9 * mesh.area());
  EXPECT_GT(tree.statistics.buildSeconds, 0.0);
}

TEST(BspBuilder, IsDeterministic)
{
  const PolygonMesh mesh = randomSoup(500, 3);
  const bsp::Tree a = bsp::build(mesh);
  const bsp::Tree b = bsp::build(mesh);
  expectSameTree(a, b);
  BuildConfig other;
  other.seed = 12345;
  const bsp::Tree c = bsp::build(mesh, other);
  const bsp::Tree d = bsp::build(mesh, other);
  expectSameTree(c, d);
  other.effort = BuildConfig::Effort::Thorough;
  expectSameTree(bsp::build(mesh, other), bsp::build(mesh, other));
  EXPECT_NEAR(totalFragmentArea(c), mesh.area(), 1e-9 * mesh.area());
}

TEST(BspBuilder, ThreadsGiveTheIdenticalTree)
{
  // Large enough that both sides of some node get built concurrently: the worker's subtree is
  // renumbered on merge, which must reproduce the serial node, fragment and point ids exactly.
  const PolygonMesh sphere = uvSphere(100000, true);
  const PolygonMesh grid =
    scenes::sphereGrid(4, 0.8, 1.0, scenes::trianglesPerSphereFor(60000)).mesh;
  for (const PolygonMesh* mesh : { &sphere, &grid })
  {
    BuildConfig serial;
    serial.threads = 1;
    const bsp::Tree a = bsp::build(*mesh, serial);
    ASSERT_GT(a.splitPoints.size(), 0u) << "the case must exercise split point renumbering";
    for (int threads : { 2, 3, 0 })
    {
      BuildConfig config;
      config.threads = threads;
      const bsp::Tree b = bsp::build(*mesh, config);
      expectSameTree(a, b);
      ASSERT_EQ(a.splitPoints.size(), b.splitPoints.size());
      for (std::size_t i = 0; i < a.splitPoints.size(); ++i)
      {
        ASSERT_EQ(a.splitPoints[i].a, b.splitPoints[i].a) << "split point " << i;
        ASSERT_EQ(a.splitPoints[i].b, b.splitPoints[i].b) << "split point " << i;
        ASSERT_EQ(a.splitPoints[i].t, b.splitPoints[i].t) << "split point " << i;
      }
      EXPECT_EQ(a.inputPointCount, b.inputPointCount);
      EXPECT_EQ(a.statistics.splits, b.statistics.splits);
      EXPECT_EQ(a.statistics.depth, b.statistics.depth);
      EXPECT_EQ(a.statistics.freePlaneNodes, b.statistics.freePlaneNodes);
      EXPECT_EQ(a.statistics.nodes, b.statistics.nodes);
      EXPECT_EQ(a.statistics.fragments, b.statistics.fragments);
      EXPECT_EQ(a.statistics.memoryBytes, b.statistics.memoryBytes);
    }
  }
}

TEST(BspBuilder, ParallelBuildCanBeCancelled)
{
  const PolygonMesh mesh = uvSphere(100000, true);
  BuildConfig config;
  config.threads = 2;
  int calls = 0;
  const bsp::Tree cancelled = bsp::build(mesh, config,
    [&calls](double f)
    {
      ++calls;
      return f < 0.2;
    });
  EXPECT_TRUE(cancelled.empty());
  EXPECT_TRUE(cancelled.nodes.empty());
  EXPECT_LT(calls, 50);
}

TEST(BspBuilder, ProgressIsReportedAndCanCancel)
{
  const PolygonMesh mesh = uvSphere(20000);
  std::vector<double> fractions;
  const bsp::Tree full = bsp::build(mesh, {},
    [&fractions](double f)
    {
      fractions.push_back(f);
      return true;
    });
  EXPECT_FALSE(full.empty());
  ASSERT_GE(fractions.size(), 50u);
  EXPECT_LE(fractions.size(), 200u);
  for (std::size_t i = 1; i < fractions.size(); ++i)
  {
    EXPECT_GE(fractions[i], fractions[i - 1]);
  }
  EXPECT_LE(fractions.back(), 1.0);

  int calls = 0;
  const bsp::Tree cancelled = bsp::build(mesh, {},
    [&calls](double f)
    {
      ++calls;
      return f < 0.3;
    });
  EXPECT_TRUE(cancelled.empty());
  EXPECT_TRUE(cancelled.fragments.empty());
  EXPECT_TRUE(cancelled.nodes.empty());
  EXPECT_LT(calls, 50);
}

} // namespace

// Unused points and points of dropped polygons do not set the tolerance: one stray point 1e7
// away must not merge two real quads 2e-6 apart into one node (fuzzer finding).
TEST(BspBuilder, StrayPointsDoNotInflateTheTolerance)
{
  PolygonMesh mesh;
  for (double z : { 0.0, 2e-6 })
  {
    const auto a = mesh.addPoint({ 0, 0, z });
    const auto b = mesh.addPoint({ 1, 0, z });
    const auto c = mesh.addPoint({ 1, 1, z });
    const auto d = mesh.addPoint({ 0, 1, z });
    mesh.addPolygon({ a, b, c, d });
  }
  const bsp::Tree clean = bsp::build(mesh);
  const auto stray = mesh.addPoint({ 1e7, 1e7, 1e7 });
  mesh.addPolygon({ stray, stray, stray }); // degenerate: dropped
  mesh.addPoint({ -1e7, 0, 0 });           // unused
  const bsp::Tree withStrays = bsp::build(mesh);
  EXPECT_EQ(withStrays.tolerance, clean.tolerance);
  EXPECT_EQ(withStrays.nodes.size(), 2u); // the two quads stay in separate nodes
  EXPECT_EQ(withStrays.statistics.degeneratePolygons, 1u);
}

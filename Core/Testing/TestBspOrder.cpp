// Hard cases for the BSP visibility order. Each test builds a tree (both partition strategies),
// orders its fragments for many viewers and lets the brute-force oracle (OrderOracle.h) judge:
// zero violations are required. The last tests show the oracle does fail on wrong orders, so a
// pass here means something.
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/OrderOracle.h"
#include "scenevis/Scenes.h"

#include "PolygonSoups.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using scenevis::Box;
using scenevis::PolygonMesh;
using scenevis::View;
using scenevis::bsp::BuildConfig;
using scenevis::bsp::Direction;
using scenevis::bsp::Tree;
using scenevis::oracle::OracleConfig;
using scenevis::oracle::OracleReport;
using scenevis::oracle::Polygon;

using scenevis::testsupport::boundsOf;
using scenevis::testsupport::cyclicSticks;
using scenevis::testsupport::describe;
using scenevis::testsupport::kPi;
using scenevis::testsupport::meshOf;
using scenevis::testsupport::randomPolygon;
using scenevis::testsupport::randomSoup;
using scenevis::testsupport::randomViews;
using scenevis::testsupport::rectZ;
using scenevis::testsupport::uvSphere;

namespace
{

struct NamedConfig
{
  const char* name;
  BuildConfig config;
};

std::vector<NamedConfig> partitions()
{
  NamedConfig first{ "FirstInList", BuildConfig() };
  first.config.partition = BuildConfig::Partition::FirstInList;
  NamedConfig scored{ "Scored", BuildConfig() };
  scored.config.partition = BuildConfig::Partition::Scored;
  NamedConfig scoredNoFree{ "ScoredNoFreePlanes", BuildConfig() };
  scoredNoFree.config.partition = BuildConfig::Partition::Scored;
  scoredNoFree.config.allowFreePlanes = false;
  return { first, scored, scoredNoFree };
}

/**
 * Checks one order of `tree` for `view`: a permutation; every node's own fragments form one
 * ascending block (BspTraversal.h); the oracle finds no violation; and front-to-back is a correct
 * order when reversed (when checkFrontToBack).
 */
::testing::AssertionResult orderIsCorrect(const Tree& tree, const std::vector<Polygon>& fragments,
  const View& view, const OracleConfig& oracleConfig = {}, bool checkFrontToBack = true)
{
  std::vector<std::uint32_t> order;
  scenevis::bsp::order(tree, view, Direction::BackToFront, order);
  if (order.size() != tree.fragments.size())
  {
    return ::testing::AssertionFailure() << "order has " << order.size() << " entries for "
                                         << tree.fragments.size() << " fragments";
  }
  std::vector<std::size_t> position(order.size(), order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    if (order[i] >= order.size() || position[order[i]] != order.size())
    {
      return ::testing::AssertionFailure() << "order is not a permutation at " << i;
    }
    position[order[i]] = i;
  }
  for (std::size_t n = 0; n < tree.nodes.size(); ++n)
  {
    const auto& node = tree.nodes[n];
    for (std::uint32_t k = 1; k < node.fragmentCount; ++k)
    {
      const std::uint32_t f = node.firstFragment + k;
      if (position[f] != position[f - 1] + 1)
      {
        return ::testing::AssertionFailure()
               << "own fragments of node " << n << " are not one ascending block";
      }
    }
  }

  const OracleReport report = scenevis::oracle::checkOrder(fragments, order, view, oracleConfig);
  if (!report.ok())
  {
    const auto& v = report.violations.front();
    const auto relation =
      scenevis::oracle::relate(fragments[v.farther], fragments[v.nearer], view, oracleConfig);
    return ::testing::AssertionFailure()
           << report.violations.size() << " violation(s) for " << describe(view)
           << "; first: fragment " << v.farther << " (source " << tree.fragments[v.farther].source
           << ", position " << position[v.farther] << ") is farther than fragment " << v.nearer
           << " (source " << tree.fragments[v.nearer].source << ", position " << position[v.nearer]
           << "), separation " << relation.separation << " at (" << relation.witness.x << ", "
           << relation.witness.y << ", " << relation.witness.z << ")"
           << (report.conflictingPairs ? "; fragments interpenetrate" : "");
  }

  if (!checkFrontToBack)
  {
    return ::testing::AssertionSuccess();
  }
  std::vector<std::uint32_t> frontToBack;
  scenevis::bsp::order(tree, view, Direction::FrontToBack, frontToBack);
  std::reverse(frontToBack.begin(), frontToBack.end());
  const OracleReport reversed =
    scenevis::oracle::checkOrder(fragments, frontToBack, view, oracleConfig);
  if (!reversed.ok())
  {
    return ::testing::AssertionFailure()
           << reversed.violations.size() << " violation(s) of reversed front-to-back for "
           << describe(view);
  }
  return ::testing::AssertionSuccess();
}

/// Every fragment vertex lies on its node's plane (within a few plane tolerances).
::testing::AssertionResult fragmentsLieOnTheirPlanes(const Tree& tree)
{
  double maxAbs = 0.0;
  for (const glm::dvec3& p : tree.points)
  {
    maxAbs = std::max({ maxAbs, std::abs(p.x), std::abs(p.y), std::abs(p.z) });
  }
  const double slack = 4.0 * tree.tolerance + 64.0 * DBL_EPSILON * maxAbs;
  for (std::size_t n = 0; n < tree.nodes.size(); ++n)
  {
    const auto& node = tree.nodes[n];
    const glm::dvec3 normal(node.plane);
    for (std::uint32_t f = node.firstFragment; f < node.firstFragment + node.fragmentCount; ++f)
    {
      const auto& fragment = tree.fragments[f];
      for (std::uint32_t k = 0; k < fragment.count; ++k)
      {
        const glm::dvec3 p = tree.points[tree.fragmentVertices[fragment.first + k]];
        const double distance = glm::dot(normal, p - tree.origin) + node.plane.w;
        if (std::abs(distance) > slack)
        {
          return ::testing::AssertionFailure()
                 << "fragment " << f << " vertex " << k << " is " << distance << " off node " << n;
        }
      }
    }
  }
  return ::testing::AssertionSuccess();
}

/// Builds `polygons` with every partition strategy and checks the order for every view.
void expectCorrectOrders(const std::vector<Polygon>& polygons, const std::vector<View>& views,
  const OracleConfig& oracleConfig = {}, std::size_t minSplits = 0)
{
  const PolygonMesh mesh = meshOf(polygons);
  for (const NamedConfig& partition : partitions())
  {
    SCOPED_TRACE(partition.name);
    const Tree tree = scenevis::bsp::build(mesh, partition.config);
    ASSERT_FALSE(tree.empty());
    EXPECT_EQ(tree.statistics.fragments, tree.fragments.size());
    EXPECT_GE(tree.statistics.splits, minSplits);
    EXPECT_TRUE(fragmentsLieOnTheirPlanes(tree));
    const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
    for (std::size_t i = 0; i < views.size(); ++i)
    {
      // Front-to-back (reversed) on every third view: it is the same walk, and this keeps the
      // suite fast.
      ASSERT_TRUE(orderIsCorrect(tree, fragments, views[i], oracleConfig, i % 3 == 0));
    }
  }
}

} // namespace

TEST(BspOrder, CyclicOverlapIsSplitAndOrdered)
{
  const std::vector<Polygon> sticks = cyclicSticks();
  std::vector<View> views = randomViews(boundsOf(sticks), 7, 24, 8);
  views.push_back(View::parallel({ 0, 0, -1 }));
  views.push_back(View::parallel({ 0, 0, 1 }));
  views.push_back(View::perspective({ 0.1, 0.05, 6 }));
  // A cycle has no order without a split.
  expectCorrectOrders(sticks, views, {}, 1);
}

TEST(BspOrder, InterpenetratingPolygonsAreSplit)
{
  // Two triangles piercing each other.
  const std::vector<Polygon> triangles = { { { -1, -1, 0 }, { 1, -1, 0 }, { 0, 1, 0 } },
    { { -0.2, 0, -1 }, { 0.3, 0.1, 1 }, { 0.1, -0.8, 0.4 } } };
  expectCorrectOrders(triangles, randomViews(boundsOf(triangles), 11, 24, 8), {}, 1);

  // A triangle piercing a quad.
  const std::vector<Polygon> pierced = { rectZ(0, -1, 1, -1, 1),
    { { -0.5, 0.1, -1 }, { 0.5, -0.1, -1 }, { 0.05, 0.0, 1.5 } } };
  expectCorrectOrders(pierced, randomViews(boundsOf(pierced), 12, 24, 8), {}, 1);
}

TEST(BspOrder, CoplanarOverlappingPolygonsAreOrderedDeterministically)
{
  Polygon flipped = rectZ(0, 0, 2, 0, 2);
  std::reverse(flipped.begin(), flipped.end());
  const std::vector<Polygon> polys = { rectZ(0, -1, 1, -1, 1), rectZ(0, -0.5, 1.5, -0.5, 0.5),
    flipped, rectZ(0.5, -1, 2, -1, 2), { { -1, 0.2, -1 }, { 2, 0.2, -1 }, { 2, 0.3, 1 } } };
  const std::vector<View> views = randomViews(boundsOf(polys), 13, 24, 8);
  expectCorrectOrders(polys, views);

  const PolygonMesh mesh = meshOf(polys);
  for (const NamedConfig& partition : partitions())
  {
    SCOPED_TRACE(partition.name);
    const Tree a = scenevis::bsp::build(mesh, partition.config);
    const Tree b = scenevis::bsp::build(mesh, partition.config);
    ASSERT_EQ(a.fragments.size(), b.fragments.size());
    for (const View& view : views)
    {
      std::vector<std::uint32_t> orderA;
      std::vector<std::uint32_t> orderB;
      scenevis::bsp::order(a, view, Direction::BackToFront, orderA);
      scenevis::bsp::order(b, view, Direction::BackToFront, orderB);
      ASSERT_EQ(orderA, orderB);
    }
  }

  // The textbook build puts the three coplanar quads on the root node (quad 0's plane).
  BuildConfig first;
  first.partition = BuildConfig::Partition::FirstInList;
  const Tree tree = scenevis::bsp::build(meshOf({ polys[0], polys[1], polys[2] }), first);
  ASSERT_FALSE(tree.empty());
  EXPECT_EQ(tree.nodes[tree.root].fragmentCount, 3u);
  EXPECT_EQ(tree.fragments.size(), 3u);
}

TEST(BspOrder, NearCoplanarPolygonsAreSeparated)
{
  // Pairs of overlapping quads 1e-9 * diagonal apart, the gap larger than the BSP tolerance
  // (1e-10): they are distinct planes and must be ordered. The oracle resolves them with a
  // tolerance below the gap (and above the BSP's).
  const double diagonal = std::sqrt(3.0 * 2.0 * 2.0);
  const double gap = 1e-9 * diagonal;
  std::vector<Polygon> polys = { rectZ(0, -1, 1, -1, 1), rectZ(gap, -0.5, 1, -0.5, 1),
    { { -1, -1, -1 }, { -1, 1, -1 }, { 1, 1, 1 }, { 1, -1, 1 } } };
  // The same pair tilted: planes x + z = c and x + z = c + gap * sqrt(2).
  polys.push_back({ { -1, -1, 0.5 }, { 0, -1, -0.5 }, { 0, 1, -0.5 }, { -1, 1, 0.5 } });
  polys.push_back(
    { { -0.8, -0.5, 0.3 + gap * std::sqrt(2.0) }, { 0.2, -0.5, -0.7 + gap * std::sqrt(2.0) },
      { 0.2, 0.5, -0.7 + gap * std::sqrt(2.0) }, { -0.8, 0.5, 0.3 + gap * std::sqrt(2.0) } });
  OracleConfig tight;
  tight.relativeDepthTolerance = 3e-10;
  std::vector<View> views = randomViews(boundsOf(polys), 17, 24, 8);
  views.push_back(View::perspective({ 0.1, 0.2, 3 }));
  views.push_back(View::perspective({ 0.1, 0.2, -3 }));
  views.push_back(View::perspective({ -4, 0.1, 0.02 })); // grazing
  expectCorrectOrders(polys, views, tight);

  // The oracle does see those gaps: the order flips with the side of the viewer.
  EXPECT_EQ(scenevis::oracle::relate(polys[0], polys[1], View::perspective({ 0.1, 0.2, 3 }), tight)
              .relation,
    scenevis::oracle::Relation::FirstFarther);

  // Closer than the BSP tolerance: treated as coplanar by both.
  polys[1] = rectZ(1e-12, -0.5, 1, -0.5, 1);
  expectCorrectOrders(polys, views);
}

TEST(BspOrder, LongThinTrianglesCrossingTheScene)
{
  std::vector<Polygon> polys = randomSoup(21, 25, 0.3);
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 8; ++i)
  {
    // From one side of the cube to the other, 1e-3 wide.
    const glm::dvec3 a(-0.1, unit(rng), unit(rng));
    const glm::dvec3 b(1.1, unit(rng), unit(rng));
    const glm::dvec3 side = glm::normalize(glm::cross(b - a, glm::dvec3(unit(rng), 1, unit(rng))));
    polys.push_back({ a, b, a + side * 1e-3 });
  }
  expectCorrectOrders(polys, randomViews(boundsOf(polys), 23, 24, 8));
}

TEST(BspOrder, SliversFromRepeatedSplits)
{
  // A shallow cone of 96 thin triangles, cut by many vertical quads: repeated splits leave slivers.
  std::vector<Polygon> polys;
  const int spokes = 96;
  for (int k = 0; k < spokes; ++k)
  {
    const double a0 = 2 * kPi * k / spokes;
    const double a1 = 2 * kPi * (k + 1) / spokes;
    polys.push_back(
      { { 0, 0, 0.05 }, { std::cos(a0), std::sin(a0), 0 }, { std::cos(a1), std::sin(a1), 0 } });
  }
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 16; ++i)
  {
    const glm::dvec3 a(unit(rng), unit(rng), -0.3);
    const glm::dvec3 b(unit(rng), unit(rng), -0.3);
    polys.push_back({ a, b, b + glm::dvec3(0, 0, 0.6), a + glm::dvec3(0, 0, 0.6) });
  }
  const std::vector<View> views = randomViews(boundsOf(polys), 32, 8, 2);
  expectCorrectOrders(polys, views, {}, 16);
}

TEST(BspOrder, DegeneratePolygonsAreRemovedAndCounted)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PolygonMesh mesh = meshOf(cyclicSticks());
  const std::uint32_t a = mesh.addPoint({ 0, 0, 0.5 });
  const std::uint32_t b = mesh.addPoint({ 1, 0, 0.5 });
  const std::uint32_t c = mesh.addPoint({ 2, 0, 0.5 });
  const std::uint32_t d = mesh.addPoint({ 0, 1, 0.5 });
  const std::uint32_t bad = mesh.addPoint({ nan, 0, 0 });
  mesh.addPolygon({ a, a, a });    // repeated point
  mesh.addPolygon({ a, b, a, b }); // two distinct points
  mesh.addPolygon({ a, b, c });    // collinear: zero area
  mesh.addPolygon({ a, b, bad });  // non-finite point
  mesh.addPolygon({ a, b, 9999 }); // point id out of range
  mesh.addPolygon({ a, b, b, d }); // a repeated point but a real triangle: kept
  const std::vector<std::uint32_t> kept = { 0, 1, 2, 8 };

  std::vector<Polygon> visible;
  for (std::uint32_t id : kept)
  {
    Polygon poly;
    for (std::uint32_t k = 0; k < mesh.polygonSize(id); ++k)
    {
      poly.push_back(mesh.points[mesh.polygon(id)[k]]);
    }
    visible.push_back(poly);
  }
  const std::vector<View> views = randomViews(boundsOf(visible), 41, 16, 4);
  for (const NamedConfig& partition : partitions())
  {
    SCOPED_TRACE(partition.name);
    const Tree tree = scenevis::bsp::build(mesh, partition.config);
    EXPECT_EQ(tree.statistics.inputPolygons, 9u);
    EXPECT_EQ(tree.statistics.degeneratePolygons, 3u);
    EXPECT_EQ(tree.statistics.invalidPolygons, 2u);
    std::vector<bool> seen(mesh.polygonCount(), false);
    for (const auto& fragment : tree.fragments)
    {
      ASSERT_LT(fragment.source, mesh.polygonCount());
      seen[fragment.source] = true;
    }
    for (std::uint32_t id = 0; id < mesh.polygonCount(); ++id)
    {
      const bool isKept = std::find(kept.begin(), kept.end(), id) != kept.end();
      EXPECT_EQ(seen[id], isKept) << "polygon " << id;
    }
    const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
    for (const View& view : views)
    {
      ASSERT_TRUE(orderIsCorrect(tree, fragments, view));
    }
  }
}

TEST(BspOrder, FarFromOriginMatchesOrigin)
{
  // 1e-2 features in a 0.1 box, on a 2^-24 grid, so that the scene moved by 1e7 is exactly the same
  // geometry (every coordinate stays representable). Triangles and parallelograms only: exactly
  // planar on the grid.
  const double grid = std::ldexp(1.0, -24);
  auto snap = [grid](const glm::dvec3& p) { return glm::round(p / grid) * grid; };
  std::mt19937_64 rng(51);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  std::vector<Polygon> scene;
  for (int i = 0; i < 40; ++i)
  {
    const glm::dvec3 c = snap(glm::dvec3(unit(rng), unit(rng), unit(rng)) * 0.1);
    const glm::dvec3 e1 = snap(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)) * 0.015);
    const glm::dvec3 e2 = snap(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)) * 0.015);
    if (i % 2 == 0)
    {
      scene.push_back({ c, c + e1, c + e2 });
    }
    else
    {
      scene.push_back({ c, c + e1, c + e1 + e2, c + e2 });
    }
  }
  const glm::dvec3 offset(1e7, -1e7, 1e7);
  std::vector<Polygon> moved = scene;
  for (Polygon& poly : moved)
  {
    for (glm::dvec3& p : poly)
    {
      p += offset;
    }
  }
  const std::vector<View> views = randomViews(boundsOf(scene), 52, 16, 4);
  std::vector<View> movedViews;
  for (const View& view : views)
  {
    movedViews.push_back(
      view.isParallel() ? view : View::perspective(glm::dvec3(view.eye) + offset));
  }
  expectCorrectOrders(scene, views);
  expectCorrectOrders(moved, movedViews);
  for (const NamedConfig& partition : partitions())
  {
    SCOPED_TRACE(partition.name);
    const Tree atOrigin = scenevis::bsp::build(meshOf(scene), partition.config);
    const Tree far = scenevis::bsp::build(meshOf(moved), partition.config);
    EXPECT_EQ(atOrigin.fragments.size(), far.fragments.size());
    EXPECT_EQ(atOrigin.statistics.splits, far.statistics.splits);
    EXPECT_EQ(atOrigin.statistics.triangulatedPolygons, 0u);
    EXPECT_EQ(far.statistics.triangulatedPolygons, 0u);
  }
}

TEST(BspOrder, EyeExactlyOnPartitionPlanes)
{
  // Axis-aligned quads among random polygons; the eye is put exactly on each quad's plane (inside
  // the quad, on its edge line, and outside it), so it lies on a partition plane of every build.
  std::vector<Polygon> polys = randomSoup(61, 12);
  polys.insert(polys.begin(), rectZ(0.5, 0.1, 0.9, 0.1, 0.9));
  polys.push_back({ { 0.25, 0, 0 }, { 0.25, 1, 0 }, { 0.25, 1, 1 }, { 0.25, 0, 1 } });
  polys.push_back({ { 0, 0.75, 0 }, { 1, 0.75, 0 }, { 1, 0.75, 1 }, { 0, 0.75, 1 } });
  std::vector<View> views;
  for (double s : { 0.5, 0.9, 1.7, -0.6 })
  {
    views.push_back(View::perspective({ s, 0.3, 0.5 }));
    views.push_back(View::perspective({ 0.25, s, 0.4 }));
    views.push_back(View::perspective({ 0.6, 0.75, s }));
  }
  // On the plane of a random (tilted) polygon: on it up to rounding.
  for (std::size_t i = 1; i < 6; ++i)
  {
    const Polygon& p = polys[i];
    views.push_back(View::perspective(p[0] + (p[1] - p[0]) * 0.3 + (p[2] - p[0]) * 0.3));
    views.push_back(View::perspective(p[0] + (p[1] - p[0]) * 2.5 - (p[2] - p[0]) * 1.5));
  }
  // Parallel views edge-on to the axis-aligned planes.
  views.push_back(View::parallel({ 1, 0, 0 }));
  views.push_back(View::parallel({ 0, 1, 0 }));
  views.push_back(View::parallel({ 1, 1, 0 }));
  expectCorrectOrders(polys, views);
}

TEST(BspOrder, ParallelProjection)
{
  std::vector<View> views;
  std::mt19937_64 rng(71);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 12; ++i)
  {
    views.push_back(View::parallel({ gauss(rng), gauss(rng), gauss(rng) }));
  }
  for (const glm::dvec3& axis : { glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1) })
  {
    views.push_back(View::parallel(axis));
  }
  expectCorrectOrders(cyclicSticks(), views, {}, 1);
  for (std::uint64_t seed = 72; seed < 76; ++seed)
  {
    SCOPED_TRACE(seed);
    expectCorrectOrders(randomSoup(seed, 30), views);
  }
}

TEST(BspOrder, EyeInsideTheGeometry)
{
  // A closed cube of 2x2 quads per face, with random polygons inside it; eyes inside the cube.
  std::vector<Polygon> polys;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (double side : { 0.0, 1.0 })
    {
      for (int cell = 0; cell < 4; ++cell)
      {
        const double u0 = 0.5 * (cell % 2);
        const double v0 = 0.5 * (cell / 2);
        Polygon quad;
        for (auto uv : { glm::dvec2(u0, v0), glm::dvec2(u0 + 0.5, v0),
               glm::dvec2(u0 + 0.5, v0 + 0.5), glm::dvec2(u0, v0 + 0.5) })
        {
          glm::dvec3 p;
          p[axis] = side;
          p[(axis + 1) % 3] = uv.x;
          p[(axis + 2) % 3] = uv.y;
          quad.push_back(p);
        }
        polys.push_back(quad);
      }
    }
  }
  std::mt19937_64 rng(81);
  std::uniform_real_distribution<double> unit(0.2, 0.8);
  for (int i = 0; i < 16; ++i)
  {
    polys.push_back(randomPolygon(rng, glm::dvec3(unit(rng), unit(rng), unit(rng)), 0.15));
  }
  std::vector<View> views;
  std::uniform_real_distribution<double> inside(0.02, 0.98);
  for (int i = 0; i < 16; ++i)
  {
    views.push_back(View::perspective({ inside(rng), inside(rng), inside(rng) }));
  }
  views.push_back(View::perspective({ 0.5, 0.5, 0.5 }));
  expectCorrectOrders(polys, views);
}

TEST(BspOrder, RandomSoups)
{
  // 50 seeds x 30 polygons x 8 viewers (6 perspective, 2 parallel) x every partition strategy.
  for (std::uint64_t seed = 1000; seed < 1050; ++seed)
  {
    SCOPED_TRACE(seed);
    const std::vector<Polygon> soup = randomSoup(seed, 30);
    expectCorrectOrders(soup, randomViews(boundsOf(soup), seed * 7, 6, 2));
    if (HasFatalFailure())
    {
      return;
    }
  }
}

TEST(BspOrder, GridSnappedSoupsWithEyesOnPlanes)
{
  // Coordinates on a 1/8 grid: many coplanar polygons (either facing), shared vertices and edges,
  // T-junctions, vertices exactly on other polygons' planes, collinear (degenerate) triangles. The
  // eyes are on a 1/16 grid, so many lie exactly on partition planes, some on edges.
  for (std::uint64_t seed = 0; seed < 40; ++seed)
  {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> cell(0, 8);
    auto gridPoint = [&] { return glm::dvec3(cell(rng), cell(rng), cell(rng)) * 0.125; };
    std::vector<Polygon> polys;
    const int count = 10 + static_cast<int>(seed % 30);
    while (static_cast<int>(polys.size()) < count)
    {
      if (rng() % 2 == 0)
      {
        polys.push_back({ gridPoint(), gridPoint(), gridPoint() });
        continue;
      }
      // An axis-aligned rectangle, either facing.
      const int axis = static_cast<int>(rng() % 3);
      const double level = cell(rng) * 0.125;
      int u0 = cell(rng);
      int u1 = cell(rng);
      int v0 = cell(rng);
      int v1 = cell(rng);
      if (u0 == u1 || v0 == v1)
      {
        continue;
      }
      Polygon rect;
      for (auto uv :
        { glm::dvec2(u0, v0), glm::dvec2(u1, v0), glm::dvec2(u1, v1), glm::dvec2(u0, v1) })
      {
        glm::dvec3 p;
        p[axis] = level;
        p[(axis + 1) % 3] = uv.x * 0.125;
        p[(axis + 2) % 3] = uv.y * 0.125;
        rect.push_back(p);
      }
      polys.push_back(rect);
    }
    std::vector<View> views;
    for (int k = 0; k < 6; ++k)
    {
      views.push_back(View::perspective(gridPoint() * 1.5 - glm::dvec3(0.25)));
    }
    views.push_back(View::parallel({ 1, 0, 0 }));
    views.push_back(View::parallel({ 1, -1, 1 }));
    expectCorrectOrders(polys, views);
    if (HasFatalFailure())
    {
      return;
    }
  }
}

TEST(BspOrder, IncrementalOrderFollowsACameraPath)
{
  const std::vector<Polygon> soup = randomSoup(91, 40);
  const PolygonMesh mesh = meshOf(soup);
  const Box bounds = boundsOf(soup);
  for (const NamedConfig& partition : partitions())
  {
    SCOPED_TRACE(partition.name);
    const Tree tree = scenevis::bsp::build(mesh, partition.config);
    const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
    for (Direction direction : { Direction::BackToFront, Direction::FrontToBack })
    {
      scenevis::bsp::IncrementalOrder incremental(tree, direction);
      std::vector<View> path;
      // An orbit that dips through the soup, then a straight line through its centre.
      for (int step = 0; step < 240; ++step)
      {
        const double a = 2 * kPi * step / 240.0;
        const double radius = 0.3 + 1.2 * (0.5 + 0.5 * std::cos(3 * a));
        path.push_back(View::perspective(
          bounds.center() + glm::dvec3(std::cos(a), std::sin(a), 0.3 * std::sin(2 * a)) * radius));
      }
      for (int step = 0; step <= 60; ++step)
      {
        path.push_back(
          View::perspective(glm::dvec3(-1, -0.5, 0.2) + glm::dvec3(3, 2, 0.6) * (step / 60.0)));
      }
      for (int step = 0; step < 30; ++step)
      {
        const double a = 2 * kPi * step / 30.0;
        path.push_back(View::parallel({ std::cos(a), std::sin(a), 0.4 }));
      }
      std::vector<std::uint32_t> expected;
      for (std::size_t i = 0; i < path.size(); ++i)
      {
        incremental.update(path[i]);
        scenevis::bsp::order(tree, path[i], direction, expected);
        ASSERT_EQ(incremental.order(), expected) << "step " << i << " " << describe(path[i]);
        if (direction == Direction::BackToFront && i % 4 == 0)
        {
          const OracleReport report =
            scenevis::oracle::checkOrder(fragments, incremental.order(), path[i]);
          ASSERT_TRUE(report.ok()) << report.violations.size() << " violation(s) at step " << i;
        }
      }
    }
  }
}

TEST(BspOrder, OracleRejectsAReversedBspOrder)
{
  // The suite can fail: the BSP's own order reversed is wrong for the cyclic sticks and for a soup.
  const View view = View::perspective({ 0.1, 0.05, 6 });
  for (const std::vector<Polygon>& polys : { cyclicSticks(), randomSoup(5, 30) })
  {
    for (const NamedConfig& partition : partitions())
    {
      SCOPED_TRACE(partition.name);
      const Tree tree = scenevis::bsp::build(meshOf(polys), partition.config);
      const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
      std::vector<std::uint32_t> order;
      scenevis::bsp::order(tree, view, Direction::BackToFront, order);
      EXPECT_TRUE(scenevis::oracle::checkOrder(fragments, order, view).ok());
      std::reverse(order.begin(), order.end());
      EXPECT_GT(scenevis::oracle::checkOrder(fragments, order, view).violations.size(), 0u);
      // So is front-to-back used as back-to-front.
      scenevis::bsp::order(tree, view, Direction::FrontToBack, order);
      EXPECT_GT(scenevis::oracle::checkOrder(fragments, order, view).violations.size(), 0u);
    }
  }
}

// The hard case "a 1M-triangle sphere": the textbook partition makes it a chain of depth n (every
// polygon behind every other plane); the scored heuristic must keep it shallow, conserve area,
// and walk it fully and incrementally (too big for the O(n^2) oracle, which checks the same code
// on the smaller cases above).
TEST(BspOrder, MillionTriangleSphereBuildsShallowAndWalks)
{
  namespace bsp = scenevis::bsp;
  const PolygonMesh sphere = scenevis::scenes::sphere({ 0.3, -0.2, 0.1 }, 1.0, 1'000'000);
  ASSERT_GT(sphere.polygonCount(), 990'000u);
  const bsp::Tree tree = bsp::build(sphere);
  EXPECT_LT(tree.statistics.depth, 1000u);
  EXPECT_LE(tree.fragments.size(), sphere.polygonCount() * 3 / 2);

  double fragmentArea = 0.0;
  for (const bsp::Fragment& f : tree.fragments)
  {
    fragmentArea += 0.5 *
      glm::length(scenevis::newellNormal(tree.points.data(), &tree.fragmentVertices[f.first], f.count));
  }
  EXPECT_NEAR(fragmentArea, sphere.area(), 1e-9 * sphere.area());

  bsp::IncrementalOrder incremental(tree, bsp::Direction::BackToFront);
  std::vector<std::uint32_t> full;
  for (int step = 0; step < 3; ++step)
  {
    const double angle = step * kPi / 180.0; // 1-degree orbit steps
    const View view = View::perspective({ 4.0 * std::cos(angle), 1.0, 4.0 * std::sin(angle) });
    bsp::order(tree, view, bsp::Direction::BackToFront, full);
    incremental.update(view);
    ASSERT_EQ(incremental.order(), full) << "step " << step;
    std::vector<std::uint32_t> sorted = full;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i)
    {
      ASSERT_EQ(sorted[i], i);
    }
  }
  // A small step re-emits only a small part of the tree.
  EXPECT_LT(incremental.lastUpdate().nodesVisited, tree.nodes.size() / 4);
}

// Issue 15 item 2, "convex-patch leaves": a set in which every polygon lies behind (or on) every
// other polygon's plane needs no splitting, because from any eye drawing its back-facing polygons
// first, then its front-facing ones, is a correct back-to-front order (back-facing ones never
// overlap each other, nor do front-facing ones, and every front-facing polygon has all others
// behind its plane). For the mirror case (every polygon in front of every other plane, a concave
// patch) the front-facing ones go first. These tests check that rule with the oracle, so that a
// tree whose leaves hold such sets can rely on it; the builder does not use it yet (BENCHMARKS.md,
// "Fewer fragments": it saves nothing on the bunny or the 2CylinderEngine).
namespace
{

/// Facing order of `polygons` for `view`: polygons the eye is behind first when `convex` (in
/// front of, when not), each group in input order. The side test is the traversals' (an eye on
/// the plane counts as in front), with the plane of each polygon fitted by Newell's method.
std::vector<std::uint32_t> facingOrder(
  const std::vector<Polygon>& polygons, const View& view, bool convex)
{
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> second;
  for (std::uint32_t i = 0; i < polygons.size(); ++i)
  {
    const Polygon& p = polygons[i];
    glm::dvec3 normal(0.0);
    glm::dvec3 centre(0.0);
    for (std::size_t k = 0; k < p.size(); ++k)
    {
      const glm::dvec3& a = p[k];
      const glm::dvec3& b = p[(k + 1) % p.size()];
      normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
        (a.x - b.x) * (a.y + b.y));
      centre += a;
    }
    centre /= static_cast<double>(p.size());
    const glm::dvec4 plane(normal, -glm::dot(normal, centre));
    const bool inFront = glm::dot(plane, view.eye) >= 0.0;
    (inFront == convex ? second : first).push_back(i);
  }
  first.insert(first.end(), second.begin(), second.end());
  return first;
}

std::vector<Polygon> reversedWinding(std::vector<Polygon> polygons)
{
  for (Polygon& p : polygons)
  {
    std::reverse(p.begin(), p.end());
  }
  return polygons;
}

/// Eyes exactly (up to rounding) on the planes of some of the polygons, outside them.
std::vector<View> eyesOnPlanes(const std::vector<Polygon>& polygons, int count)
{
  std::vector<View> views;
  for (int i = 0; i < count; ++i)
  {
    const Polygon& p = polygons[(static_cast<std::size_t>(i) * 7919u) % polygons.size()];
    views.push_back(View::perspective(p[0] + 2.5 * (p[1] - p[0]) + 1.5 * (p[2] - p[0])));
  }
  return views;
}

} // namespace

TEST(BspOrder, ConvexPatchFacingOrderIsExactFromAnyEye)
{
  // A closed convex polyhedron, an open cap of it, and a convex patch whose vertices are moved by
  // up to 1e-11 of the diagonal (straddling each other's planes by less than the BSP tolerance).
  const std::vector<Polygon> sphere = scenevis::oracle::polygonsOf(uvSphere(600));
  std::vector<Polygon> cap;
  for (const Polygon& p : sphere)
  {
    if (p[0].z > 0.2 && p[1].z > 0.2 && p[2].z > 0.2)
    {
      cap.push_back(p);
    }
  }
  std::vector<Polygon> jittered = sphere;
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> noise(-1e-11, 1e-11);
  for (Polygon& p : jittered)
  {
    for (glm::dvec3& v : p)
    {
      v += glm::dvec3(noise(rng), noise(rng), noise(rng));
    }
  }
  ASSERT_GT(cap.size(), 100u);
  struct Case
  {
    const char* name;
    std::vector<Polygon> polygons;
  };
  for (const Case& c : { Case{ "closed", sphere }, Case{ "cap", cap }, Case{ "jittered", jittered } })
  {
    std::vector<View> views = randomViews(boundsOf(c.polygons), 15, 24, 6);
    const std::vector<View> onPlanes = eyesOnPlanes(c.polygons, 8);
    views.insert(views.end(), onPlanes.begin(), onPlanes.end());
    for (bool convex : { true, false })
    {
      // Reversed winding turns the convex patch into a concave one (every polygon in front of
      // every other plane): the same rule with the groups swapped.
      const std::vector<Polygon> polygons = convex ? c.polygons : reversedWinding(c.polygons);
      for (const View& view : views)
      {
        const OracleReport report =
          scenevis::oracle::checkOrder(polygons, facingOrder(polygons, view, convex), view);
        EXPECT_TRUE(report.ok()) << c.name << (convex ? " convex" : " concave") << ": "
                                 << report.violations.size() << " violation(s) for "
                                 << describe(view);
      }
    }
  }
}

TEST(BspOrder, FacingOrderFailsOffConvexPatches)
{
  // The rule needs the patch property: on two spheres, one behind the other, some eye sees a
  // back-facing polygon of the near sphere in front of a front-facing one of the far sphere;
  // and the swapped groups are wrong on a convex patch.
  std::vector<Polygon> two = scenevis::oracle::polygonsOf(uvSphere(200));
  const std::vector<Polygon> one = two;
  for (Polygon p : one)
  {
    for (glm::dvec3& v : p)
    {
      v.z += 3.0;
    }
    two.push_back(p);
  }
  const View view = View::perspective({ 0.1, 0.2, 8.0 });
  EXPECT_GT(scenevis::oracle::checkOrder(two, facingOrder(two, view, true), view).violations.size(),
    0u);
  EXPECT_GT(scenevis::oracle::checkOrder(one, facingOrder(one, view, false), view).violations.size(),
    0u);
}

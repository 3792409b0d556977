// Ordered leaves (BspTree.h, BuildConfig::orderedLeafSize): short lists kept unsplit and sorted per
// view by their pairs' separating planes, with the split subtree as fallback for eyes that see a
// cycle. What is drawn for a view must cover every input polygon exactly once and be a correct
// back-to-front order by the brute-force oracle (OrderOracle.h), from eyes outside, inside, on
// polygon planes and at infinity.
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/OrderOracle.h"

#include "PolygonSoups.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using scenevis::PolygonMesh;
using scenevis::View;
using scenevis::bsp::BuildConfig;
using scenevis::bsp::Direction;
using scenevis::bsp::OrderStatistics;
using scenevis::bsp::Tree;
using scenevis::oracle::Polygon;

using scenevis::testsupport::boundsOf;
using scenevis::testsupport::cyclicSticks;
using scenevis::testsupport::describe;
using scenevis::testsupport::meshOf;
using scenevis::testsupport::randomSoup;
using scenevis::testsupport::randomViews;
using scenevis::testsupport::rectZ;
using scenevis::testsupport::uvSphere;

namespace
{

BuildConfig withLeaves(
  std::uint32_t size, BuildConfig::Partition partition = BuildConfig::Partition::Scored)
{
  BuildConfig config;
  config.orderedLeafSize = size;
  config.partition = partition;
  return config;
}

double area(const Polygon& polygon)
{
  glm::dvec3 sum(0.0);
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
  {
    sum += glm::cross(polygon[k] - polygon[0], polygon[k + 1] - polygon[0]);
  }
  return 0.5 * glm::length(sum);
}

/**
 * The order drawn for `view`, checked: no fragment twice, every input polygon covered by its
 * drawn fragments' area (so no leaf is drawn both unsplit and split, or neither), no oracle
 * violation, and the front-to-back order is the reverse of back-to-front.
 */
::testing::AssertionResult drawnOrderIsCorrect(const Tree& tree,
  const std::vector<Polygon>& fragments, const std::vector<double>& inputArea, const View& view,
  OrderStatistics* statistics = nullptr)
{
  std::vector<std::uint32_t> order;
  scenevis::bsp::order(tree, view, Direction::BackToFront, order, statistics);
  std::vector<bool> seen(tree.fragments.size(), false);
  std::vector<double> covered(inputArea.size(), 0.0);
  std::vector<Polygon> drawn;
  for (std::uint32_t id : order)
  {
    if (id >= seen.size() || seen[id])
    {
      return ::testing::AssertionFailure() << "fragment " << id << " drawn twice or unknown";
    }
    seen[id] = true;
    covered[tree.fragments[id].source] += area(fragments[id]);
    drawn.push_back(fragments[id]);
  }
  for (std::size_t s = 0; s < inputArea.size(); ++s)
  {
    if (std::abs(covered[s] - inputArea[s]) > 1e-9 * std::max(1.0, inputArea[s]))
    {
      return ::testing::AssertionFailure()
        << "input polygon " << s << " covered " << covered[s] << " of " << inputArea[s];
    }
  }
  std::vector<std::uint32_t> identity(drawn.size());
  for (std::uint32_t i = 0; i < identity.size(); ++i)
  {
    identity[i] = i;
  }
  scenevis::oracle::OracleConfig oracleConfig;
  oracleConfig.samplesPerOverlap = 1; // drawn polygons never intersect (see OrderOracle.h)
  const auto report = scenevis::oracle::checkOrder(drawn, identity, view, oracleConfig);
  if (!report.ok())
  {
    const auto& v = report.violations.front();
    return ::testing::AssertionFailure()
      << report.violations.size() << " violation(s) for " << describe(view) << "; first: fragment "
      << order[v.farther] << " drawn after fragment " << order[v.nearer] << " but farther";
  }
  std::vector<std::uint32_t> frontToBack;
  scenevis::bsp::order(tree, view, Direction::FrontToBack, frontToBack);
  std::reverse(frontToBack.begin(), frontToBack.end());
  if (frontToBack != order)
  {
    return ::testing::AssertionFailure()
      << "front-to-back is not back-to-front reversed for " << describe(view);
  }
  return ::testing::AssertionSuccess();
}

/// Eyes on the planes of some polygons (inside them and outside them), as in TestBspOrder.
std::vector<View> eyesOnPlanes(const std::vector<Polygon>& polygons, int count)
{
  std::vector<View> views;
  for (int i = 0; i < count && i < static_cast<int>(polygons.size()); ++i)
  {
    const Polygon& p = polygons[static_cast<std::size_t>(i) * polygons.size() / count];
    views.push_back(View::perspective(p[0] + (p[1] - p[0]) * 0.3 + (p[2] - p[0]) * 0.3));
    views.push_back(View::perspective(p[0] + (p[1] - p[0]) * 2.5 - (p[2] - p[0]) * 1.5));
  }
  return views;
}

/// Statistics summed over `views`, with every order checked.
struct Totals
{
  std::size_t drawn = 0;
  std::size_t sorted = 0;
  std::size_t fallenBack = 0;
};

Totals expectCorrectOrders(const std::vector<Polygon>& polygons, const std::vector<View>& views,
  std::uint32_t leafSize, BuildConfig::Partition partition = BuildConfig::Partition::Scored)
{
  Totals totals;
  const PolygonMesh mesh = meshOf(polygons);
  const Tree tree = scenevis::bsp::build(mesh, withLeaves(leafSize, partition));
  EXPECT_FALSE(tree.empty());
  EXPECT_EQ(tree.statistics.orderedLeaves, tree.leaves.size());
  const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
  std::vector<double> inputArea;
  for (const Polygon& p : polygons)
  {
    inputArea.push_back(area(p));
  }
  for (const View& view : views)
  {
    OrderStatistics statistics;
    EXPECT_TRUE(drawnOrderIsCorrect(tree, fragments, inputArea, view, &statistics));
    std::vector<std::uint32_t> order;
    scenevis::bsp::order(tree, view, Direction::BackToFront, order);
    totals.drawn += order.size();
    totals.sorted += statistics.leavesSorted;
    totals.fallenBack += statistics.leavesFallenBack;
  }
  return totals;
}

/// A unit sphere whose vertices are moved radially by up to +-`amplitude` (seeded): a closed
/// surface with convex, concave and saddle patches, like a scanned model.
std::vector<Polygon> bumpySphere(std::size_t triangles, double amplitude, std::uint64_t seed)
{
  PolygonMesh mesh = uvSphere(triangles);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (glm::dvec3& p : mesh.points)
  {
    p *= 1.0 + amplitude * unit(rng);
  }
  return scenevis::oracle::polygonsOf(mesh);
}

/**
 * Polygons in the cells of a lattice (spacing 1, `nx` x `ny` x `nz` cells), each inside the ball
 * of radius 0.4 around its cell's centre, so no two intersect and one list of all of them can be
 * a leaf: in every `tripleEvery`-th cell a turned copy of the cyclic sticks (a true cycle from
 * some eyes), elsewhere a random triangle.
 */
std::vector<Polygon> latticeOfSeparatedPolygons(
  int nx, int ny, int nz, int tripleEvery, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto inBall = [&]
  {
    glm::dvec3 p;
    do
    {
      p = glm::dvec3(unit(rng), unit(rng), unit(rng));
    } while (glm::dot(p, p) > 1.0);
    return p * 0.4;
  };
  std::vector<Polygon> polygons;
  int cell = 0;
  for (int x = 0; x < nx; ++x)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int z = 0; z < nz; ++z, ++cell)
      {
        const glm::dvec3 centre(x + 0.5, y + 0.5, z + 0.5);
        if (cell % tripleEvery != 0)
        {
          polygons.push_back({ centre + inBall(), centre + inBall(), centre + inBall() });
          continue;
        }
        const glm::dvec3 axis = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        const double angle = 3.0 * unit(rng);
        for (Polygon stick : cyclicSticks())
        {
          for (glm::dvec3& p : stick)
          {
            // Centred, scaled into the ball (the sticks reach 1.2 from their axis), turned.
            p = (p - glm::dvec3(0.0, 0.0, 0.5)) * 0.3;
            p = p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
              axis * glm::dot(axis, p) * (1.0 - std::cos(angle)) + centre;
          }
          polygons.push_back(stick);
        }
      }
    }
  }
  return polygons;
}

/**
 * `count` long thin vertical rectangles (20 x 0.06) stacked 0.08 apart, each along a random
 * horizontal direction and moved up to 1 sideways: no two touch, but every one's plane cuts
 * nearly all the others, so nearly every pair needs two planes besides their own.
 */
std::vector<Polygon> verticalStrips(int count, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Polygon> strips;
  for (int k = 0; k < count; ++k)
  {
    const double direction = 3.14159265358979 * unit(rng);
    const glm::dvec3 along(std::cos(direction), std::sin(direction), 0.0);
    const glm::dvec3 up(0.0, 0.0, 0.03);
    const glm::dvec3 centre(unit(rng), unit(rng), 0.08 * k);
    strips.push_back({ centre - along * 10.0 - up, centre + along * 10.0 - up,
      centre + along * 10.0 + up, centre - along * 10.0 + up });
  }
  return strips;
}

/// `polygons` turned by a generic rotation, so that no gap between them is axis-aligned.
std::vector<Polygon> turned(std::vector<Polygon> polygons)
{
  const glm::dvec3 axis = glm::normalize(glm::dvec3(1.0, 2.0, 3.0));
  const double angle = 0.7;
  for (Polygon& polygon : polygons)
  {
    for (glm::dvec3& p : polygon)
    {
      p = p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
        axis * glm::dot(axis, p) * (1.0 - std::cos(angle));
    }
  }
  return polygons;
}

} // namespace

TEST(BspOrderedLeaves, OffByDefaultAndTheTreeIsUnchanged)
{
  const PolygonMesh mesh = meshOf(randomSoup(5, 40, 0.15));
  const Tree plain = scenevis::bsp::build(mesh);
  EXPECT_TRUE(plain.leaves.empty());
  EXPECT_EQ(plain.statistics.orderedLeaves, 0u);
  EXPECT_EQ(plain.statistics.fragmentsWithoutFallbacks, plain.fragments.size());
  const Tree leaves = scenevis::bsp::build(mesh, withLeaves(16));
  EXPECT_FALSE(leaves.leaves.empty());
}

TEST(BspOrderedLeaves, SeparatedPolygonsStayWholeAndAreSortedForEveryEye)
{
  // Parallel and tilted rectangles stacked over each other: every pair is separated by an own
  // plane, the leaf holds them unsplit, and from above and below the order must reverse.
  std::vector<Polygon> stack;
  for (int k = 0; k < 6; ++k)
  {
    stack.push_back(rectZ(0.2 * k, 0.1 * k, 1.0 + 0.1 * k, 0.0, 1.0));
  }
  stack.push_back({ { -0.5, 0.5, 1.1 }, { 2.0, 0.5, 1.6 }, { 2.0, 0.6, 1.6 }, { -0.5, 0.6, 1.1 } });
  std::vector<View> views = randomViews(boundsOf(stack), 3, 24, 8);
  views.push_back(View::perspective({ 0.5, 0.5, 10.0 }));
  views.push_back(View::perspective({ 0.5, 0.5, -10.0 }));
  views.push_back(View::perspective({ 0.5, 0.5, 0.4 })); // on a rectangle's plane
  views.push_back(View::parallel({ 0.0, 0.0, 1.0 }));
  views.push_back(View::parallel({ 1.0, 0.0, 0.0 })); // edge-on to all rectangles
  for (const View& v : eyesOnPlanes(stack, 7))
  {
    views.push_back(v);
  }
  const Totals totals = expectCorrectOrders(stack, views, 8);
  EXPECT_EQ(totals.fallenBack, 0u);
  EXPECT_EQ(totals.drawn, views.size() * stack.size()); // nothing split
}

TEST(BspOrderedLeaves, TheOracleRejectsAReversedLeafOrder)
{
  // The check above has teeth: a leaf's order reversed is caught. Two long strips crossing one
  // above the other, each tilted about its length so that its plane cuts the other: no polygon
  // plane partitions them, so they form a leaf.
  const std::vector<Polygon> stack = { { { -5.0, -0.2, -0.06 }, { 5.0, -0.2, -0.06 },
                                         { 5.0, 0.2, 0.06 }, { -5.0, 0.2, 0.06 } },
    { { -0.2, -5.0, 1.06 }, { 0.2, -5.0, 0.94 }, { 0.2, 5.0, 0.94 }, { -0.2, 5.0, 1.06 } } };
  const Tree tree = scenevis::bsp::build(meshOf(stack), withLeaves(8));
  ASSERT_EQ(tree.leaves.size(), 1u);
  const View view = View::perspective({ 0.5, 0.5, 10.0 });
  std::vector<std::uint32_t> order;
  scenevis::bsp::order(tree, view, Direction::BackToFront, order);
  ASSERT_EQ(order.size(), stack.size());
  const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
  std::vector<Polygon> drawn;
  for (std::uint32_t id : order)
  {
    drawn.push_back(fragments[id]);
  }
  std::vector<std::uint32_t> reversed(drawn.size());
  for (std::uint32_t i = 0; i < reversed.size(); ++i)
  {
    reversed[i] = static_cast<std::uint32_t>(reversed.size() - 1 - i);
  }
  EXPECT_FALSE(scenevis::oracle::checkOrder(drawn, reversed, view).ok());
}

TEST(BspOrderedLeaves, CyclicOverlapFallsBackToTheSplitSubtree)
{
  // Seen from above, the three sticks overlap cyclically: no order of the whole sticks is right,
  // so the leaf must draw its split fallback. Seen from the side there is no cycle.
  const std::vector<Polygon> sticks = cyclicSticks();
  const Tree tree = scenevis::bsp::build(meshOf(sticks), withLeaves(8));
  ASSERT_EQ(tree.leaves.size(), 1u);
  ASSERT_NE(tree.leaves[0].fallback, scenevis::bsp::kNone);
  EXPECT_GT(tree.statistics.fragments, tree.statistics.fragmentsWithoutFallbacks);
  const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
  std::vector<double> inputArea;
  for (const Polygon& p : sticks)
  {
    inputArea.push_back(area(p));
  }
  OrderStatistics statistics;
  EXPECT_TRUE(drawnOrderIsCorrect(
    tree, fragments, inputArea, View::perspective({ 0.0, 0.0, 5.0 }), &statistics));
  EXPECT_EQ(statistics.leavesFallenBack, 1u);
  EXPECT_TRUE(drawnOrderIsCorrect(
    tree, fragments, inputArea, View::parallel({ 0.0, 0.0, -1.0 }), &statistics));
  EXPECT_EQ(statistics.leavesFallenBack, 1u);
  EXPECT_TRUE(drawnOrderIsCorrect(
    tree, fragments, inputArea, View::parallel({ 1.0, 0.0, 0.0 }), &statistics));
  EXPECT_EQ(statistics.leavesSorted, 1u);

  std::vector<View> views = randomViews(boundsOf(sticks), 11, 32, 16);
  const Totals totals = expectCorrectOrders(sticks, views, 8);
  EXPECT_GT(totals.fallenBack, 0u);
  EXPECT_GT(totals.sorted, 0u);
}

TEST(BspOrderedLeaves, ListsThatPartitionWithoutSplitsAreNotLeaves)
{
  // A leaf needs a sort per view and, when its pairs could form a cycle, a stored fallback; a
  // list that a plane partitions without splitting anything needs neither. Stacked rectangles:
  // their own planes do it (no leaf at all). Four copies of the cyclic sticks side by side: no
  // own plane does, but gaps along x do, so each copy is its own leaf with its own fallback
  // instead of one leaf of 12 with a fallback of all 12.
  std::vector<Polygon> stack;
  for (int k = 0; k < 6; ++k)
  {
    stack.push_back(rectZ(0.2 * k, 0.1 * k, 1.0 + 0.1 * k, 0.0, 1.0));
  }
  const Tree stacked = scenevis::bsp::build(meshOf(stack), withLeaves(8));
  EXPECT_TRUE(stacked.leaves.empty());
  EXPECT_EQ(stacked.fragments.size(), stack.size());

  std::vector<Polygon> copies;
  for (int c = 0; c < 4; ++c)
  {
    for (Polygon stick : cyclicSticks())
    {
      for (glm::dvec3& p : stick)
      {
        p += glm::dvec3(3.0 * c, 0.7 * c, 0.0);
      }
      copies.push_back(stick);
    }
  }
  const Tree tree = scenevis::bsp::build(meshOf(copies), withLeaves(16));
  ASSERT_EQ(tree.leaves.size(), 4u);
  for (const auto& leaf : tree.leaves)
  {
    EXPECT_EQ(leaf.fragmentCount, 3u);
    EXPECT_NE(leaf.fallback, scenevis::bsp::kNone); // each copy is a true cycle from above
  }
  std::vector<View> views = randomViews(boundsOf(copies), 21, 16, 6);
  views.push_back(View::perspective({ 4.5, 1.0, 6.0 }));
  const Totals totals = expectCorrectOrders(copies, views, 16);
  EXPECT_GT(totals.fallenBack, 0u);
  EXPECT_GT(totals.sorted, 0u);
}

TEST(BspOrderedLeaves, RandomSoupsFromManyEyes)
{
  // Small polygons (few intersect, so most short lists become leaves) and the usual size (many
  // intersect, so lists split until their pairs separate), at every leaf size; every third seed
  // with the textbook partition (lists shrink one polygon at a time, so leaves form early).
  Totals all;
  for (std::uint32_t leafSize : { 8u, 16u, 32u, 64u })
  {
    for (std::uint64_t seed = 2000; seed < 2012; ++seed)
    {
      SCOPED_TRACE(::testing::Message() << "leaf size " << leafSize << ", seed " << seed);
      const double size = seed % 2 ? 0.35 : 0.12;
      const std::vector<Polygon> soup = randomSoup(seed, 40, size);
      std::vector<View> views = randomViews(boundsOf(soup), seed * 13, 8, 3);
      for (const View& v : eyesOnPlanes(soup, 3))
      {
        views.push_back(v);
      }
      const Totals totals = expectCorrectOrders(soup, views, leafSize,
        seed % 3 == 0 ? BuildConfig::Partition::FirstInList : BuildConfig::Partition::Scored);
      all.sorted += totals.sorted;
      all.fallenBack += totals.fallenBack;
      if (HasFailure())
      {
        return;
      }
    }
  }
  EXPECT_GT(all.sorted, 0u);
}

TEST(BspOrderedLeaves, ScatteredCyclicTriplesFromManyEyes)
{
  // Copies of the three cyclic sticks, turned and moved at random so that copies overlap each
  // other too: leaves whose eyes see true cycles (the fallback is drawn) next to spurious ones
  // (precedences between polygons no ray from the eye meets both of, which the sort drops).
  Totals all;
  for (std::uint64_t seed = 3000; seed < 3008; ++seed)
  {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Polygon> soup;
    for (int copy = 0; copy < 5; ++copy)
    {
      const glm::dvec3 axis = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
      const double angle = 0.6 * gauss(rng);
      const glm::dvec3 offset(2.0 * unit(rng), 2.0 * unit(rng), 1.5 * unit(rng));
      for (Polygon stick : cyclicSticks())
      {
        for (glm::dvec3& p : stick)
        {
          // Rodrigues' rotation, then the offset.
          p = p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
            axis * glm::dot(axis, p) * (1.0 - std::cos(angle)) + offset;
        }
        soup.push_back(stick);
      }
    }
    std::vector<View> views = randomViews(boundsOf(soup), seed, 12, 6);
    for (const View& v : eyesOnPlanes(soup, 4))
    {
      views.push_back(v);
    }
    for (std::uint32_t leafSize : { 8u, 32u })
    {
      const Totals totals = expectCorrectOrders(soup, views, leafSize);
      all.sorted += totals.sorted;
      all.fallenBack += totals.fallenBack;
    }
    if (HasFailure())
    {
      return;
    }
  }
  EXPECT_GT(all.sorted, 0u);
  EXPECT_GT(all.fallenBack, 0u); // the fallback is exercised, not only the sort
}

TEST(BspOrderedLeaves, LeavesOfMoreThan64PolygonsFromManyEyes)
{
  // Up to 256 polygons per leaf: precedence rows of 2 and 4 words, cycles through polygons past
  // the first word, and (above 181 polygons) more pairs than 15-bit plane indices can give two
  // planes each. Lattices of separated polygons keep whole lists of 65-220 unsplit.
  Totals all;
  struct Case
  {
    int nx, ny, nz;
    std::uint32_t leafSize;
  };
  for (const Case c : { Case{ 4, 4, 6, 128 }, Case{ 5, 6, 6, 256 }, Case{ 4, 5, 6, 256 } })
  {
    for (std::uint64_t seed = 4000; seed < 4003; ++seed)
    {
      SCOPED_TRACE(::testing::Message() << "leaf size " << c.leafSize << ", seed " << seed);
      const std::vector<Polygon> soup =
        turned(latticeOfSeparatedPolygons(c.nx, c.ny, c.nz, 7, seed));
      const Tree tree = scenevis::bsp::build(meshOf(soup), withLeaves(c.leafSize));
      std::uint32_t largest = 0;
      for (const auto& leaf : tree.leaves)
      {
        largest = std::max(largest, leaf.fragmentCount);
        EXPECT_LE(leaf.planeCount, scenevis::bsp::kMaxLeafPlanes);
      }
      EXPECT_GT(largest, c.leafSize / 2); // the wide rows are used
      std::vector<View> views = randomViews(boundsOf(soup), seed, 10, 4);
      for (const View& v : eyesOnPlanes(soup, 4))
      {
        views.push_back(v);
      }
      const Totals totals = expectCorrectOrders(soup, views, c.leafSize);
      all.sorted += totals.sorted;
      all.fallenBack += totals.fallenBack;
      if (HasFailure())
      {
        return;
      }
    }
  }
  EXPECT_GT(all.sorted, 0u);
  EXPECT_GT(all.fallenBack, 0u); // cycles inside the wide leaves are seen and fall back
}

TEST(BspOrderedLeaves, AListWhosePairsNeedMorePlanesThanIndicesIsSplit)
{
  // 190 vertical strips (turned, so no axis gap separates them) would need about 2 planes per
  // pair besides their own: 36k, more than 15-bit plane indices name (kMaxLeafPlanes; without
  // that cap this list becomes one leaf of 33k planes). It is split instead, and what is drawn
  // stays exact.
  const std::vector<Polygon> strips = turned(verticalStrips(190, 5));
  const Tree tree = scenevis::bsp::build(meshOf(strips), withLeaves(256));
  EXPECT_GT(tree.leaves.size(), 1u);
  for (const auto& leaf : tree.leaves)
  {
    EXPECT_LE(leaf.planeCount, scenevis::bsp::kMaxLeafPlanes);
  }
  std::vector<View> views = randomViews(boundsOf(strips), 6, 12, 4);
  for (const View& v : eyesOnPlanes(strips, 4))
  {
    views.push_back(v);
  }
  expectCorrectOrders(strips, views, 256);
}

TEST(BspOrderedLeaves, FragmentsWithManyVerticesNeedNoFallbackWithoutACycle)
{
  // Long strips stacked 0.08 apart: from above a ray meets the higher strip first, so no cycle
  // exists there and no leaf may fall back. Their fragments carry the split points of their
  // neighbours (conforming fragments), more than 64 vertices on some, which the exact check of a
  // stalled sort must still handle.
  const std::vector<Polygon> strips = turned(verticalStrips(60, 5));
  const Tree tree = scenevis::bsp::build(meshOf(strips), withLeaves(256));
  ASSERT_FALSE(tree.leaves.empty());
  std::uint32_t mostVertices = 0;
  for (const auto& fragment : tree.fragments)
  {
    mostVertices = std::max(mostVertices, fragment.count);
  }
  EXPECT_GT(mostVertices, 64u);
  const std::vector<Polygon> fragments = scenevis::oracle::fragmentPolygons(tree);
  std::vector<double> inputArea;
  for (const Polygon& p : strips)
  {
    inputArea.push_back(area(p));
  }
  const glm::dvec3 above = turned({ { glm::dvec3(0.0, 0.0, 40.0) } })[0][0];
  OrderStatistics statistics;
  EXPECT_TRUE(
    drawnOrderIsCorrect(tree, fragments, inputArea, View::perspective(above), &statistics));
  EXPECT_EQ(statistics.leavesFallenBack, 0u);
  EXPECT_GT(statistics.leavesSorted, 0u);
}

TEST(BspOrderedLeaves, BumpySurfaceFromOutsideInsideAndOnPlanes)
{
  // A closed scanned-like surface: its leaves are patches of neighbours, the case the option is
  // for. Eyes outside, inside (the sphere's centre region), on triangle planes, and parallel.
  const std::vector<Polygon> surface = bumpySphere(600, 0.15, 9);
  std::vector<View> views = randomViews(boundsOf(surface), 17, 20, 6);
  for (const View& v : eyesOnPlanes(surface, 6))
  {
    views.push_back(v);
  }
  views.push_back(View::perspective({ 0.0, 0.0, 0.0 }));
  views.push_back(View::perspective({ 0.3, -0.2, 0.1 }));
  for (std::uint32_t leafSize : { 16u, 64u, 256u })
  {
    SCOPED_TRACE(leafSize);
    const Totals totals = expectCorrectOrders(surface, views, leafSize);
    EXPECT_GT(totals.sorted, 0u);
  }
}

TEST(BspOrderedLeaves, FewerFragmentsDrawnThanTheSplitTree)
{
  const std::vector<Polygon> surface = bumpySphere(2000, 0.05, 4);
  const PolygonMesh mesh = meshOf(surface);
  const Tree plain = scenevis::bsp::build(mesh);
  const Tree leaves = scenevis::bsp::build(mesh, withLeaves(32));
  ASSERT_GT(plain.statistics.splits, 0u);
  std::size_t drawn = 0;
  const std::vector<View> views = randomViews(boundsOf(surface), 5, 8, 2);
  for (const View& view : views)
  {
    std::vector<std::uint32_t> order;
    scenevis::bsp::order(leaves, view, Direction::BackToFront, order);
    drawn += order.size();
  }
  EXPECT_LT(drawn, views.size() * plain.fragments.size());
  EXPECT_LE(leaves.statistics.fragmentsWithoutFallbacks * views.size(), drawn);
}

TEST(BspOrderedLeaves, ThreadsGiveTheIdenticalTree)
{
  // Both sides of the top nodes are large, so a worker builds one of them, leaves included; its
  // leaves, planes, pairs and fallback nodes are renumbered on merge to the serial ids.
  const PolygonMesh grid = meshOf(bumpySphere(60000, 0.05, 3));
  BuildConfig serial = withLeaves(32);
  serial.threads = 1;
  BuildConfig parallel = withLeaves(32);
  parallel.threads = 2;
  const Tree a = scenevis::bsp::build(grid, serial);
  const Tree b = scenevis::bsp::build(grid, parallel);
  ASSERT_GT(a.leaves.size(), 0u);
  ASSERT_EQ(a.root, b.root);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
  {
    ASSERT_EQ(a.nodes[i].plane, b.nodes[i].plane) << "node " << i;
    ASSERT_EQ(a.nodes[i].front, b.nodes[i].front) << "node " << i;
    ASSERT_EQ(a.nodes[i].back, b.nodes[i].back) << "node " << i;
    ASSERT_EQ(a.nodes[i].firstFragment, b.nodes[i].firstFragment) << "node " << i;
    ASSERT_EQ(a.nodes[i].fragmentCount, b.nodes[i].fragmentCount) << "node " << i;
  }
  ASSERT_EQ(a.leaves.size(), b.leaves.size());
  for (std::size_t i = 0; i < a.leaves.size(); ++i)
  {
    const auto& x = a.leaves[i];
    const auto& y = b.leaves[i];
    ASSERT_EQ(std::vector<std::uint32_t>({ x.firstFragment, x.fragmentCount, x.firstPlane,
                x.planeCount, x.firstPair, x.pairCount, x.fallback }),
      std::vector<std::uint32_t>({ y.firstFragment, y.fragmentCount, y.firstPlane, y.planeCount,
        y.firstPair, y.pairCount, y.fallback }))
      << "leaf " << i;
  }
  EXPECT_EQ(a.leafPlanes, b.leafPlanes);
  ASSERT_EQ(a.leafPairs.size(), b.leafPairs.size());
  for (std::size_t i = 0; i < a.leafPairs.size(); ++i)
  {
    ASSERT_EQ(a.leafPairs[i].first, b.leafPairs[i].first);
    ASSERT_EQ(a.leafPairs[i].second, b.leafPairs[i].second);
    ASSERT_EQ(a.leafPairs[i].planes[0], b.leafPairs[i].planes[0]);
    ASSERT_EQ(a.leafPairs[i].planes[1], b.leafPairs[i].planes[1]);
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
  EXPECT_EQ(a.statistics.leafFragments, b.statistics.leafFragments);
  EXPECT_EQ(a.statistics.fragmentsWithoutFallbacks, b.statistics.fragmentsWithoutFallbacks);
  EXPECT_EQ(a.statistics.memoryBytes, b.statistics.memoryBytes);
  std::vector<std::uint32_t> orderA;
  std::vector<std::uint32_t> orderB;
  const View view = View::perspective({ 0.3, 0.2, 6.0 });
  scenevis::bsp::order(a, view, Direction::BackToFront, orderA);
  scenevis::bsp::order(b, view, Direction::BackToFront, orderB);
  EXPECT_EQ(orderA, orderB);
}

TEST(BspOrderedLeaves, IncrementalOrderRejectsLeaves)
{
  const Tree tree = scenevis::bsp::build(meshOf(cyclicSticks()), withLeaves(8));
  EXPECT_THROW(
    scenevis::bsp::IncrementalOrder(tree, Direction::BackToFront), std::invalid_argument);
}

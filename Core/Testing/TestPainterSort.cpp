// The painter's algorithm (PainterSort.h) judged by the brute-force oracle (OrderOracle.h): every
// order it produces must have zero violations, for cycles, interpenetration, random soups,
// coplanar polygons, parallel views and eyes inside the geometry. The plain depth sort (no Newell
// tests) is shown to fail the oracle on the cyclic quads, so a pass here means something.
#include "scenevis/OrderOracle.h"
#include "scenevis/PainterSort.h"
#include "scenevis/Scenes.h"

#include "PolygonSoups.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using scenevis::Box;
using scenevis::PolygonMesh;
using scenevis::View;
using scenevis::oracle::OracleConfig;
using scenevis::oracle::OracleReport;
using scenevis::oracle::Polygon;
namespace painter = scenevis::painter;
namespace scenes = scenevis::scenes;

using scenevis::testsupport::describe;
using scenevis::testsupport::kPi;
using scenevis::testsupport::meshOf;
using scenevis::testsupport::randomSoup;
using scenevis::testsupport::randomViews;
using scenevis::testsupport::rectZ;

namespace
{

/// The fragments of a result as point loops, in the result's (back-to-front) order.
std::vector<Polygon> fragmentPolygons(const painter::Result& result)
{
  std::vector<Polygon> polys;
  polys.reserve(result.fragments.size());
  for (const auto& f : result.fragments)
  {
    Polygon poly;
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      poly.push_back(result.points[result.fragmentVertices[f.first + k]]);
    }
    polys.push_back(std::move(poly));
  }
  return polys;
}

std::vector<std::uint32_t> identity(std::size_t n)
{
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  return order;
}

/// Structural checks: split points are what they claim and every fragment has >= 3 vertices.
::testing::AssertionResult wellFormed(const painter::Result& result)
{
  if (result.points.size() != result.inputPointCount + result.splitPoints.size())
  {
    return ::testing::AssertionFailure() << "point count mismatch";
  }
  for (std::size_t i = 0; i < result.splitPoints.size(); ++i)
  {
    const auto& sp = result.splitPoints[i];
    const std::size_t id = result.inputPointCount + i;
    if (sp.a >= id || sp.b >= id || !(sp.t >= 0.0 && sp.t <= 1.0))
    {
      return ::testing::AssertionFailure() << "split point " << id << " badly described";
    }
    const glm::dvec3 expected = result.points[sp.a] + (result.points[sp.b] - result.points[sp.a]) * sp.t;
    if (glm::length(expected - result.points[id]) > 1e-12 * (1.0 + glm::length(expected)))
    {
      return ::testing::AssertionFailure() << "split point " << id << " is not lerp(a, b, t)";
    }
  }
  for (const auto& f : result.fragments)
  {
    if (f.count < 3 || f.first + f.count > result.fragmentVertices.size())
    {
      return ::testing::AssertionFailure() << "bad fragment";
    }
  }
  if (result.statistics.fragments != result.fragments.size())
  {
    return ::testing::AssertionFailure() << "statistics.fragments mismatch";
  }
  return ::testing::AssertionSuccess();
}

/// Sorts `mesh` for `view` and lets the oracle judge the order.
::testing::AssertionResult sortIsCorrect(painter::Sorter& sorter, const View& view,
  const OracleConfig& oracleConfig = {}, painter::Result* out = nullptr)
{
  painter::Result result;
  sorter.sort(view, result);
  const ::testing::AssertionResult formed = wellFormed(result);
  if (!formed)
  {
    return formed;
  }
  if (result.statistics.forcedEmissions != 0)
  {
    return ::testing::AssertionFailure() << "forced emissions for " << describe(view);
  }
  const std::vector<Polygon> fragments = fragmentPolygons(result);
  const OracleReport report = scenevis::oracle::checkOrder(
    fragments, identity(fragments.size()), view, oracleConfig);
  if (out)
  {
    *out = result;
  }
  if (!report.ok())
  {
    const auto& v = report.violations.front();
    const auto relation =
      scenevis::oracle::relate(fragments[v.farther], fragments[v.nearer], view, oracleConfig);
    return ::testing::AssertionFailure()
           << report.violations.size() << " violation(s) for " << describe(view)
           << "; first: fragment at position " << v.farther << " (source "
           << result.fragments[v.farther].source << ") is farther than position " << v.nearer
           << " (source " << result.fragments[v.nearer].source << "), separation "
           << relation.separation << (report.conflictingPairs ? "; fragments interpenetrate" : "")
           << "; splits " << result.statistics.splits;
  }
  return ::testing::AssertionSuccess();
}

void expectCorrectOrders(const PolygonMesh& mesh, const std::vector<View>& views,
  const OracleConfig& oracleConfig = {})
{
  painter::Sorter sorter(mesh);
  for (const View& view : views)
  {
    ASSERT_TRUE(sortIsCorrect(sorter, view, oracleConfig));
  }
}

const View kTopView = View::perspective({ 0.1, 0.05, 6 });

} // namespace

TEST(PainterSort, CyclicQuadsAreSplitAndOrdered)
{
  const PolygonMesh mesh = scenes::cyclicQuads().mesh;
  painter::Sorter sorter(mesh);
  painter::Result result;
  ASSERT_TRUE(sortIsCorrect(sorter, kTopView, {}, &result));
  // No order of the three whole quads is correct: the cycle must have been split.
  EXPECT_GE(result.statistics.splits, 1u);
  EXPECT_GE(result.statistics.cyclesResolved + result.statistics.intersectionSplits, 1u);
  EXPECT_GT(result.fragments.size(), 3u);
  EXPECT_TRUE(sortIsCorrect(sorter, View::parallel({ 0, 0, -1 })));
  std::vector<View> views = randomViews(mesh.bounds(), 7, 40, 16);
  views.push_back(View::parallel({ 0, 0, 1 }));
  views.push_back(View::perspective({ 0, 0, -6 }));
  views.push_back(View::perspective({ 0, 0, 0.01 })); // between the quads' extremes
  expectCorrectOrders(mesh, views);
}

TEST(PainterSort, PlainDepthSortFailsTheOracleOnCyclicQuads)
{
  // The suite can fail: sorting whole polygons by farthest depth (no Newell tests, no splits) is
  // wrong on the cycle, and the oracle says so; the full algorithm is right on the same view.
  const PolygonMesh mesh = scenes::cyclicQuads().mesh;
  painter::Config plain;
  plain.newellTests = false;
  for (const View& view : { kTopView, View::parallel({ 0, 0, -1 }) })
  {
    SCOPED_TRACE(describe(view));
    const painter::Result bad = painter::sort(mesh, view, plain);
    ASSERT_EQ(bad.fragments.size(), 3u);
    EXPECT_EQ(bad.statistics.splits, 0u);
    const std::vector<Polygon> polys = fragmentPolygons(bad);
    const OracleReport report = scenevis::oracle::checkOrder(polys, identity(3), view);
    EXPECT_GT(report.violations.size(), 0u);

    const painter::Result good = painter::sort(mesh, view);
    const std::vector<Polygon> fragments = fragmentPolygons(good);
    EXPECT_TRUE(
      scenevis::oracle::checkOrder(fragments, identity(fragments.size()), view).ok());
    // And the good order reversed is wrong (the oracle sees the order, not just the fragments).
    std::vector<std::uint32_t> reversed = identity(fragments.size());
    std::reverse(reversed.begin(), reversed.end());
    EXPECT_FALSE(scenevis::oracle::checkOrder(fragments, reversed, view).ok());
  }
}

TEST(PainterSort, InterpenetratingPolygonsAreSplit)
{
  const PolygonMesh triangles = scenes::interpenetratingTriangles().mesh;
  {
    const painter::Result result = painter::sort(triangles, kTopView);
    EXPECT_GE(result.statistics.splits, 1u);
    EXPECT_GE(result.statistics.intersectionSplits, 1u);
  }
  expectCorrectOrders(triangles, randomViews(triangles.bounds(), 11, 32, 12));

  // A triangle piercing a quad, and two triangles piercing each other.
  const std::vector<Polygon> pierced = { rectZ(0, -1, 1, -1, 1),
    { { -0.5, 0.1, -1 }, { 0.5, -0.1, -1 }, { 0.05, 0.0, 1.5 } } };
  expectCorrectOrders(meshOf(pierced), randomViews(meshOf(pierced).bounds(), 12, 32, 12));
  const std::vector<Polygon> pair = { { { -1, -1, 0 }, { 1, -1, 0 }, { 0, 1, 0 } },
    { { -0.2, 0, -1 }, { 0.3, 0.1, 1 }, { 0.1, -0.8, 0.4 } } };
  expectCorrectOrders(meshOf(pair), randomViews(meshOf(pair).bounds(), 13, 32, 12));
}

TEST(PainterSort, RandomSoupsManySeedsAndCameras)
{
  for (std::uint64_t seed = 0; seed < 40; ++seed)
  {
    SCOPED_TRACE(seed);
    const PolygonMesh mesh = meshOf(randomSoup(seed, 12 + static_cast<int>(seed % 5) * 8));
    expectCorrectOrders(mesh, randomViews(mesh.bounds(), 1000 + seed, 6, 3));
    if (HasFatalFailure())
    {
      return;
    }
  }
}

TEST(PainterSort, CoplanarPolygons)
{
  Polygon flipped = rectZ(0, 0, 2, 0, 2);
  std::reverse(flipped.begin(), flipped.end());
  const std::vector<Polygon> polys = { rectZ(0, -1, 1, -1, 1), rectZ(0, -0.5, 1.5, -0.5, 0.5),
    flipped, rectZ(0.5, -1, 2, -1, 2), { { -1, 0.2, -1 }, { 2, 0.2, -1 }, { 2, 0.3, 1 } } };
  const PolygonMesh mesh = meshOf(polys);
  std::vector<View> views = randomViews(mesh.bounds(), 13, 24, 8);
  views.push_back(View::perspective({ 0.3, 0.2, 0.0 })); // in the common plane
  views.push_back(View::parallel({ 1, 0, 0 }));         // along the common plane
  expectCorrectOrders(mesh, views);
  // Coplanar quads alone never need a split.
  const painter::Result result = painter::sort(meshOf({ polys[0], polys[1], polys[2] }), kTopView);
  EXPECT_EQ(result.statistics.splits, 0u);
  EXPECT_EQ(result.fragments.size(), 3u);
}

TEST(PainterSort, ParallelViews)
{
  // Axis-aligned grid geometry seen along the axes and diagonals: many vertices exactly on other
  // polygons' planes, edge-on polygons, equal depth extents.
  for (std::uint64_t seed = 0; seed < 20; ++seed)
  {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> cell(0, 8);
    auto gridPoint = [&] { return glm::dvec3(cell(rng), cell(rng), cell(rng)) * 0.125; };
    std::vector<Polygon> polys;
    const int count = 10 + static_cast<int>(seed % 20);
    while (static_cast<int>(polys.size()) < count)
    {
      if (rng() % 2 == 0)
      {
        polys.push_back({ gridPoint(), gridPoint(), gridPoint() });
        continue;
      }
      const int axis = static_cast<int>(rng() % 3);
      const double level = cell(rng) * 0.125;
      const int u0 = cell(rng);
      const int u1 = cell(rng);
      const int v0 = cell(rng);
      const int v1 = cell(rng);
      if (u0 == u1 || v0 == v1)
      {
        continue;
      }
      Polygon rect;
      for (auto uv : { glm::dvec2(u0, v0), glm::dvec2(u1, v0), glm::dvec2(u1, v1),
             glm::dvec2(u0, v1) })
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
    for (const glm::dvec3& d : { glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1),
           glm::dvec3(1, -1, 1), glm::dvec3(0.3, 0.5, -0.8) })
    {
      views.push_back(View::parallel(d));
    }
    expectCorrectOrders(meshOf(polys), views);
    if (HasFatalFailure())
    {
      return;
    }
  }
}

TEST(PainterSort, EyeInsideGeometry)
{
  // Supported: depth is the distance from the eye, and the extent and projection tests are
  // conservative for fragments beside or behind the eye. A closed box around a soup, seen from
  // inside the soup.
  std::vector<Polygon> polys = randomSoup(77, 30);
  const double lo = -0.3;
  const double hi = 1.3;
  polys.push_back(rectZ(lo, lo, hi, lo, hi));
  polys.push_back(rectZ(hi, lo, hi, lo, hi));
  polys.push_back({ { lo, lo, lo }, { lo, hi, lo }, { lo, hi, hi }, { lo, lo, hi } });
  polys.push_back({ { hi, lo, lo }, { hi, hi, lo }, { hi, hi, hi }, { hi, lo, hi } });
  polys.push_back({ { lo, lo, lo }, { hi, lo, lo }, { hi, lo, hi }, { lo, lo, hi } });
  polys.push_back({ { lo, hi, lo }, { hi, hi, lo }, { hi, hi, hi }, { lo, hi, hi } });
  const PolygonMesh mesh = meshOf(polys);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<View> views;
  for (int i = 0; i < 16; ++i)
  {
    views.push_back(View::perspective({ unit(rng), unit(rng), unit(rng) }));
  }
  painter::Sorter sorter(mesh);
  std::size_t undecided = 0;
  for (const View& view : views)
  {
    painter::Result result;
    ASSERT_TRUE(sortIsCorrect(sorter, view, {}, &result));
    undecided += result.statistics.undecidedProjections;
  }
  // The conservative path was exercised.
  EXPECT_GT(undecided, 0u);

  // Inside the overlapping spheres of a small sphere grid.
  const PolygonMesh grid = scenes::sphereGrid(2, 0.8, 1.0, 60).mesh;
  expectCorrectOrders(grid,
    { View::perspective({ 0.01, 0.02, 0.03 }), View::perspective({ 0.5, 0.45, 0.4 }),
      View::perspective({ -0.2, 0.7, 0.1 }) });
}

TEST(PainterSort, SphereGridOrbit)
{
  const PolygonMesh grid = scenes::sphereGrid(4, 0.8, 1.0, 20).mesh;
  std::vector<View> views;
  for (int step = 0; step < 6; ++step)
  {
    const double a = 2 * kPi * step / 6.0;
    views.push_back(View::perspective(glm::dvec3(std::cos(a), std::sin(a), 0.35) * 7.0));
  }
  views.push_back(View::parallel({ 1, 2, -3 }));
  painter::Sorter sorter(grid);
  for (const View& view : views)
  {
    painter::Result result;
    OracleConfig fast;
    fast.samplesPerOverlap = 3;
    ASSERT_TRUE(sortIsCorrect(sorter, view, fast, &result));
    EXPECT_GT(result.statistics.splits, 0u); // the spheres intersect
  }
}

TEST(PainterSort, Deterministic)
{
  const PolygonMesh mesh = meshOf(randomSoup(3, 40));
  const View view = View::perspective({ 2.5, -1.0, 1.5 });
  const painter::Result a = painter::sort(mesh, view);
  painter::Sorter sorter(mesh);
  painter::Result b;
  sorter.sort(View::perspective({ -3, 2, 1 }), b); // reused scratch must not leak into the next
  sorter.sort(view, b);
  ASSERT_EQ(a.fragments.size(), b.fragments.size());
  for (std::size_t i = 0; i < a.fragments.size(); ++i)
  {
    EXPECT_EQ(a.fragments[i].source, b.fragments[i].source);
    EXPECT_EQ(a.fragments[i].first, b.fragments[i].first);
    EXPECT_EQ(a.fragments[i].count, b.fragments[i].count);
  }
  EXPECT_EQ(a.fragmentVertices, b.fragmentVertices);
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(0, std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(glm::dvec3)));
  EXPECT_EQ(a.statistics.splits, b.statistics.splits);
  EXPECT_EQ(a.statistics.pairs, b.statistics.pairs);
}

TEST(PainterSort, AreaIsConserved)
{
  for (const PolygonMesh& mesh :
    { meshOf(randomSoup(21, 40, 0.6)), scenes::sphereGrid(3, 0.8, 1.0, 40).mesh,
      scenes::cyclicQuads().mesh })
  {
    const double expected = mesh.area();
    for (const View& view :
      { View::perspective({ 0.4, 0.3, 4.0 }), View::parallel({ 1, 1, 1 }) })
    {
      const painter::Result result = painter::sort(mesh, view);
      double area = 0.0;
      for (const auto& f : result.fragments)
      {
        area += 0.5 * glm::length(scenevis::newellNormal(
                        result.points.data(), result.fragmentVertices.data() + f.first, f.count));
      }
      EXPECT_NEAR(area, expected, 1e-9 * expected);
      EXPECT_GT(result.statistics.splits, 0u);
    }
  }
}

TEST(PainterSort, InvalidAndNonConvexInputs)
{
  PolygonMesh mesh;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto a = mesh.addPoint({ 0, 0, 0 });
  const auto b = mesh.addPoint({ 1, 0, 0 });
  const auto c = mesh.addPoint({ 0, 1, 0 });
  const auto d = mesh.addPoint({ 2, 0, 0 });
  const auto n = mesh.addPoint({ nan, 0, 0 });
  mesh.addPolygon({ a, b, c });    // fine
  mesh.addPolygon({ a, b, n });    // NaN point: invalid
  mesh.addPolygon({ a, b, 999 });  // out-of-range id: invalid
  mesh.addPolygon({ a, b, d });    // collinear: degenerate
  mesh.addPolygon({ a, a, b, b }); // < 3 distinct: degenerate
  // A concave "L" above, and a non-planar quad crossing the triangle.
  std::vector<std::uint32_t> l;
  for (const glm::dvec3& p : { glm::dvec3(-0.5, -0.5, 0.3), glm::dvec3(1.5, -0.5, 0.3),
         glm::dvec3(1.5, 0.2, 0.3), glm::dvec3(0.2, 0.2, 0.3), glm::dvec3(0.2, 1.5, 0.3),
         glm::dvec3(-0.5, 1.5, 0.3) })
  {
    l.push_back(mesh.addPoint(p));
  }
  mesh.addPolygon(l.data(), l.size());
  std::vector<std::uint32_t> bent;
  for (const glm::dvec3& p : { glm::dvec3(0.1, 0.1, -0.5), glm::dvec3(0.8, 0.1, 0.5),
         glm::dvec3(0.8, 0.6, -0.4), glm::dvec3(0.1, 0.6, 0.6) })
  {
    bent.push_back(mesh.addPoint(p));
  }
  mesh.addPolygon(bent.data(), bent.size());

  painter::Sorter sorter(mesh);
  const painter::Statistics& st = sorter.normalisation();
  EXPECT_EQ(st.inputPolygons, 7u);
  EXPECT_EQ(st.invalidPolygons, 2u);
  EXPECT_EQ(st.degeneratePolygons, 2u);
  EXPECT_EQ(st.triangulatedPolygons, 2u);
  EXPECT_EQ(st.pieces, 1u + 4u + 2u);
  for (const View& view : randomViews(mesh.bounds(), 3, 16, 6))
  {
    painter::Result result;
    ASSERT_TRUE(sortIsCorrect(sorter, view, {}, &result));
    for (const auto& f : result.fragments)
    {
      EXPECT_TRUE(f.source == 0 || f.source == 5 || f.source == 6);
    }
  }
  // Empty and all-invalid meshes give empty results.
  EXPECT_TRUE(painter::sort(PolygonMesh(), kTopView).fragments.empty());
}

TEST(PainterSort, SplitCapTerminatesWithForcedEmissions)
{
  // With no splits allowed the cycle cannot be resolved: the sort still terminates, emits every
  // quad once and reports the forced emissions (the order is then wrong, and the oracle says so).
  const PolygonMesh mesh = scenes::cyclicQuads().mesh;
  painter::Config noSplits;
  noSplits.maxSplitsPerPolygon = 0.0;
  const painter::Result result = painter::sort(mesh, kTopView, noSplits);
  ASSERT_EQ(result.fragments.size(), 3u);
  EXPECT_EQ(result.statistics.splits, 0u);
  EXPECT_GT(result.statistics.forcedEmissions, 0u);
  std::vector<std::uint32_t> sources;
  for (const auto& f : result.fragments)
  {
    sources.push_back(f.source);
  }
  std::sort(sources.begin(), sources.end());
  EXPECT_EQ(sources, (std::vector<std::uint32_t>{ 0, 1, 2 }));
  EXPECT_FALSE(scenevis::oracle::checkOrder(fragmentPolygons(result), identity(3), kTopView).ok());

  // A dense soup of big intersecting polygons terminates within the default cap.
  const PolygonMesh dense = meshOf(randomSoup(8, 80, 1.0));
  const painter::Result heavy = painter::sort(dense, View::perspective({ 0.5, 0.5, 3 }));
  EXPECT_EQ(heavy.statistics.forcedEmissions, 0u);
  EXPECT_GT(heavy.statistics.splits, 0u);
}

TEST(PainterSort, StatisticsCountTheTestLevels)
{
  const PolygonMesh grid = scenes::sphereGrid(3, 0.8, 1.0, 80).mesh;
  const painter::Result result = painter::sort(grid, View::perspective({ 5, 4, 3 }));
  const painter::Statistics& st = result.statistics;
  EXPECT_EQ(st.inputPolygons, grid.polygonCount());
  EXPECT_EQ(st.fragments, st.pieces + st.splits);
  EXPECT_GT(st.pairs, 0u);
  EXPECT_GT(st.screenExtent.passed, 0u);
  EXPECT_GT(st.behindPlane.passed + st.inFrontOfPlane.passed, 0u);
  EXPECT_LE(st.screenExtent.evaluated, st.pairs);
  EXPECT_LE(st.projection.evaluated, st.inFrontOfPlane.evaluated);
  EXPECT_EQ(st.splits, st.intersectionSplits + st.cyclesResolved);
  EXPECT_GE(st.sortSeconds, 0.0);
  EXPECT_GT(st.tolerance, 0.0);
}

// The brute-force visibility-order oracle must itself be shown to fail on wrong orders, to pass
// on right ones, and to impose no constraint where no ray sees both polygons.
#include "scenevis/OrderOracle.h"

#include "PolygonSoups.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

using scenevis::View;
using scenevis::oracle::checkOrder;
using scenevis::oracle::OracleConfig;
using scenevis::oracle::OracleReport;
using scenevis::oracle::Polygon;
using scenevis::oracle::Relation;
using scenevis::oracle::Violation;

using scenevis::testsupport::cyclicSticks;
using scenevis::testsupport::kPi;
using scenevis::testsupport::rectZ;

namespace
{

Polygon translated(Polygon poly, const glm::dvec3& offset)
{
  for (glm::dvec3& p : poly)
  {
    p += offset;
  }
  return poly;
}

/// The six faces of the box [-1, 1]^3.
std::vector<Polygon> boxFaces()
{
  std::vector<Polygon> faces;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (double side : { -1.0, 1.0 })
    {
      Polygon face;
      for (auto uv : { glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1) })
      {
        glm::dvec3 p;
        p[axis] = side;
        p[(axis + 1) % 3] = uv.x;
        p[(axis + 2) % 3] = uv.y;
        face.push_back(p);
      }
      faces.push_back(face);
    }
  }
  return faces;
}

std::vector<std::vector<std::uint32_t>> allPermutations(std::uint32_t n)
{
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<std::vector<std::uint32_t>> result;
  do
  {
    result.push_back(order);
  } while (std::next_permutation(order.begin(), order.end()));
  return result;
}

} // namespace

TEST(OrderOracle, TwoStackedQuadsWrongOrderIsOneViolation)
{
  // Quad 0 at z = 0 is behind quad 1 at z = 1 for an eye above both.
  const std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1), rectZ(1, -1, 1, -1, 1) };
  const View view = View::perspective({ 0.2, 0.1, 5.0 });
  const OracleReport right = checkOrder(quads, { 0, 1 }, view);
  EXPECT_TRUE(right.ok());
  EXPECT_EQ(right.constrainedPairs, 1u);
  const OracleReport wrong = checkOrder(quads, { 1, 0 }, view);
  ASSERT_EQ(wrong.violations.size(), 1u);
  EXPECT_EQ(wrong.violations[0].farther, 0u);
  EXPECT_EQ(wrong.violations[0].nearer, 1u);
  EXPECT_EQ(wrong.conflictingPairs, 0u);

  // From below the relation flips.
  const View below = View::perspective({ 0.2, 0.1, -5.0 });
  EXPECT_TRUE(checkOrder(quads, { 1, 0 }, below).ok());
  EXPECT_EQ(checkOrder(quads, { 0, 1 }, below).violations.size(), 1u);
}

TEST(OrderOracle, DisjointProjectionsImposeNothing)
{
  const std::vector<Polygon> quads = { rectZ(0, -2, -1, -1, 1), rectZ(1, 1, 2, -1, 1) };
  for (const View& view : { View::perspective({ 0, 0, 20 }), View::parallel({ 0, 0, -1 }) })
  {
    for (const auto& order : allPermutations(2))
    {
      const OracleReport report = checkOrder(quads, order, view);
      EXPECT_TRUE(report.ok());
      EXPECT_EQ(report.constrainedPairs, 0u);
    }
  }
}

TEST(OrderOracle, EyeBetweenQuadsSeesNoCommonRay)
{
  // One quad below the eye, one above: every ray meets at most one of them.
  const std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1), rectZ(1, -1, 1, -1, 1) };
  const View view = View::perspective({ 0.1, -0.2, 0.5 });
  for (const auto& order : allPermutations(2))
  {
    const OracleReport report = checkOrder(quads, order, view);
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(report.constrainedPairs, 0u);
  }
}

TEST(OrderOracle, EyeInsideClosedBoxHasNoConstraint)
{
  // From inside a closed box every ray leaves through exactly one face: all 720 orders are right.
  const std::vector<Polygon> faces = boxFaces();
  for (const glm::dvec3& eye :
    { glm::dvec3(0.1, 0.2, -0.3), glm::dvec3(0, 0, 0), glm::dvec3(0.99, -0.99, 0.5) })
  {
    const View view = View::perspective(eye);
    for (const auto& order : allPermutations(6))
    {
      const OracleReport report = checkOrder(faces, order, view);
      ASSERT_TRUE(report.ok());
      ASSERT_EQ(report.constrainedPairs, 0u);
    }
  }
}

TEST(OrderOracle, EyeInsideBoxWithInteriorPolygon)
{
  // A quad inside the box hides part of the faces behind it, seen across cube-map face borders.
  std::vector<Polygon> polys = boxFaces();
  polys.push_back(rectZ(0.5, -0.4, 0.4, -0.4, 0.4)); // id 6: hides part of the top face only
  const View view = View::perspective({ 0.05, -0.1, 0.0 });
  // The top face is z = +1: axis 2, side +1 -> id 5.
  std::vector<std::uint32_t> order = { 0, 1, 2, 3, 4, 5, 6 };
  const OracleReport right = checkOrder(polys, order, view);
  EXPECT_TRUE(right.ok());
  EXPECT_EQ(right.constrainedPairs, 1u);
  std::swap(order[5], order[6]);
  const OracleReport wrong = checkOrder(polys, order, view);
  ASSERT_EQ(wrong.violations.size(), 1u);
  EXPECT_EQ(wrong.violations[0].farther, 5u);
  EXPECT_EQ(wrong.violations[0].nearer, 6u);
}

TEST(OrderOracle, OverlapAcrossCubeMapFaces)
{
  // A wide floor under the eye and a small quad farther down, seen at 68 degrees off the -z axis
  // (through the +x face of the cube map). Only that ray direction sees both.
  const std::vector<Polygon> polys = { rectZ(-2, 4.5, 5.5, -0.5, 0.5),
    rectZ(-1, -10, 10, -10, 10) };
  const View view = View::perspective({ 0, 0, 0 });
  EXPECT_TRUE(checkOrder(polys, { 0, 1 }, view).ok());
  EXPECT_EQ(checkOrder(polys, { 1, 0 }, view).violations.size(), 1u);
}

TEST(OrderOracle, ParallelViews)
{
  const std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1), rectZ(1, 0, 2, 0, 2) };
  // Looking down (-z): quad 0 is farther.
  const View down = View::parallel({ 0, 0, -1 });
  EXPECT_TRUE(checkOrder(quads, { 0, 1 }, down).ok());
  EXPECT_EQ(checkOrder(quads, { 1, 0 }, down).violations.size(), 1u);
  // Looking up: reversed.
  const View up = View::parallel({ 0.1, 0.2, 1 });
  EXPECT_TRUE(checkOrder(quads, { 1, 0 }, up).ok());
  EXPECT_EQ(checkOrder(quads, { 0, 1 }, up).violations.size(), 1u);
  // Looking sideways the quads are edge-on: no ray passes through both interiors.
  const View side = View::parallel({ 1, 0, 0 });
  EXPECT_EQ(checkOrder(quads, { 0, 1 }, side).constrainedPairs, 0u);
  // A parallel view has no "behind the eye": a slanted view still sees both.
  const View slanted = View::parallel({ 0.3, 0.3, -1 });
  EXPECT_EQ(checkOrder(quads, { 1, 0 }, slanted).violations.size(), 1u);
}

TEST(OrderOracle, CyclicOverlapViolatesEveryOrder)
{
  const std::vector<Polygon> sticks = cyclicSticks();
  for (const View& view : { View::parallel({ 0, 0, -1 }), View::perspective({ 0.1, 0.05, 6 }),
         View::parallel({ 0.05, -0.1, -1 }) })
  {
    for (const auto& order : allPermutations(3))
    {
      const OracleReport report = checkOrder(sticks, order, view);
      EXPECT_GE(report.violations.size(), 1u);
      EXPECT_EQ(report.constrainedPairs, 3u);
      EXPECT_EQ(report.conflictingPairs, 0u);
    }
  }
  // Each crossing on its own has a definite relation: stick k lies above stick k+1.
  const View down = View::parallel({ 0, 0, -1 });
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_EQ(scenevis::oracle::relate(sticks[k], sticks[(k + 1) % 3], down).relation,
      Relation::SecondFarther);
  }
}

TEST(OrderOracle, InterpenetratingPairViolatesEveryOrder)
{
  // Quad 1 tilts through quad 0 along x = 0: above it for x > 0, below for x < 0.
  const std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1),
    { { -1, -1, -0.5 }, { 1, -1, 0.5 }, { 1, 1, 0.5 }, { -1, 1, -0.5 } } };
  for (const View& view : { View::parallel({ 0, 0, -1 }), View::perspective({ 0.1, 0.2, 4 }) })
  {
    for (const auto& order : allPermutations(2))
    {
      const OracleReport report = checkOrder(quads, order, view);
      EXPECT_EQ(report.violations.size(), 1u);
      EXPECT_EQ(report.conflictingPairs, 1u);
    }
    EXPECT_EQ(scenevis::oracle::relate(quads[0], quads[1], view).relation, Relation::Conflicting);
  }
  // With only the centroid sampled, the penetration is not seen (centroid lies on the crossing).
  OracleConfig centroidOnly;
  centroidOnly.samplesPerOverlap = 1;
  EXPECT_EQ(
    checkOrder(quads, { 0, 1 }, View::parallel({ 0, 0, -1 }), centroidOnly).conflictingPairs, 0u);
}

TEST(OrderOracle, CoplanarAndTouchingPolygonsImposeNothing)
{
  const View view = View::perspective({ 0.3, 0.2, 3 });
  // Overlapping coplanar quads, either facing.
  Polygon flipped = rectZ(0, 0, 2, 0, 2);
  std::reverse(flipped.begin(), flipped.end());
  const std::vector<Polygon> coplanar = { rectZ(0, -1, 1, -1, 1), flipped };
  for (const auto& order : allPermutations(2))
  {
    EXPECT_EQ(checkOrder(coplanar, order, view).constrainedPairs, 0u);
  }
  // Neighbours sharing an edge, flat and folded: their images only touch.
  const std::vector<Polygon> neighbours = { rectZ(0, -1, 0, -1, 1), rectZ(0, 0, 1, -1, 1),
    { { 1, -1, 0 }, { 2, -1, 1 }, { 2, 1, 1 }, { 1, 1, 0 } } };
  for (const auto& order : allPermutations(3))
  {
    EXPECT_EQ(checkOrder(neighbours, order, view).constrainedPairs, 0u);
  }
}

TEST(OrderOracle, NearCoplanarSeparationIsMeasuredPerpendicular)
{
  // Two quads 1e-9 apart (scene diagonal ~3): within the default tolerance, but resolved by a
  // tolerance below it; a grazing eye does not change the verdict.
  const std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1), rectZ(1e-9, -0.5, 1.5, -1, 1) };
  OracleConfig tight;
  tight.relativeDepthTolerance = 1e-11;
  for (const glm::dvec3& eye : { glm::dvec3(0, 0, 2), glm::dvec3(-30, 0.1, 0.5) })
  {
    const View view = View::perspective(eye);
    EXPECT_EQ(checkOrder(quads, { 1, 0 }, view).constrainedPairs, 0u);
    EXPECT_TRUE(checkOrder(quads, { 0, 1 }, view, tight).ok());
    EXPECT_EQ(checkOrder(quads, { 1, 0 }, view, tight).violations.size(), 1u);
  }
}

TEST(OrderOracle, PolygonSeenEdgeOnConstrainsNothing)
{
  // Regression: a BSP fragment whose plane passes through the eye (up to rounding, 6e-18 here)
  // has a sliver image of rounding-noise width; it must not produce a violation.
  const std::vector<Polygon> polys = {
    { { 0.79749457893763931, 0.36278711109890105, 0.58781892473144404 },
      { 0.72283805834755344, 0.25960607539366704, 0.73502503683691534 },
      { 0.65846341704494871, 0.17833486458501585, 0.44125412545151244 } },
    { { 0.69735304512758989, 0.10000000000000001, 0.5 }, { 0.9, 0.10000000000000001, 0.5 },
      { 0.9, 0.25307123757280842, 0.5 }, { 0.81409305113953567, 0.38673570639765681, 0.5 },
      { 0.62392156259402121, 0.13076672977614251, 0.5 } }
  };
  const View view =
    View::perspective({ 0.73338827419280639, 0.27649712643316532, 0.58801131857910593 });
  for (const auto& order : allPermutations(2))
  {
    EXPECT_EQ(checkOrder(polys, order, view).constrainedPairs, 0u);
  }
  // Exactly edge-on in a parallel view: the same.
  const std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1),
    { { 0, -1, -1 }, { 0, 1, -1 }, { 0, 1, 1 }, { 0, -1, 1 } } };
  EXPECT_EQ(checkOrder(quads, { 0, 1 }, View::parallel({ 0, 1, 0.3 })).constrainedPairs, 0u);
  EXPECT_EQ(checkOrder(quads, { 0, 1 }, View::parallel({ 0.2, 1, 0.3 })).constrainedPairs, 1u);
}

TEST(OrderOracle, PolygonsTouchingAlongAPlaneThroughTheEyeConstrainNothing)
{
  // Regression: two BSP fragments on either side of the plane x + y = 1, each with an edge on it,
  // and the eye on it too. No ray meets both, but on a cube-map face border one image is a
  // rounding sliver that "overlaps" the other; the width test must reject it.
  const std::vector<Polygon> polys = {
    { { 0.50735294117647056, 0.73529411764705888, 0.3970588235294118 }, { 0.375, 1, 0 },
      { 0.29999999999999999, 0.69999999999999996, 0.037499999999999999 },
      { 0.41326530612244894, 0.58673469387755106, 0.31122448979591838 } },
    { { 0.30373831775700932, 0.56775700934579443, 0.12149532710280374 },
      { 0.45000000000000007, 0.47999999999999998, 0.18000000000000002 },
      { 0.4705882352941177, 0.52941176470588236, 0.21568627450980393 },
      { 0.36392405063291139, 0.63607594936708867, 0.19198312236286921 } }
  };
  const View view = View::perspective({ 1.0625, -0.0625, -0.25 });
  for (const auto& order : allPermutations(2))
  {
    EXPECT_EQ(checkOrder(polys, order, view).constrainedPairs, 0u);
  }
  EXPECT_EQ(scenevis::oracle::relate(polys[0], polys[1], view).relation, Relation::Unconstrained);
}

TEST(OrderOracle, FarFromOriginGivesSameVerdicts)
{
  // 1e-2 features at 1e7: the input resolution is ~2e-9, far below the features.
  const glm::dvec3 offset(1e7, -1e7, 1e7);
  std::vector<Polygon> sticks = cyclicSticks();
  std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1), rectZ(0.5, -1, 1, -1, 1) };
  for (Polygon& p : sticks)
  {
    for (glm::dvec3& v : p)
    {
      v *= 1e-2;
    }
    p = translated(p, offset);
  }
  for (Polygon& p : quads)
  {
    for (glm::dvec3& v : p)
    {
      v *= 1e-2;
    }
    p = translated(p, offset);
  }
  const View view = View::perspective(offset + glm::dvec3(0.001, 0.002, 0.05));
  for (const auto& order : allPermutations(3))
  {
    EXPECT_GE(checkOrder(sticks, order, view).violations.size(), 1u);
  }
  EXPECT_TRUE(checkOrder(quads, { 0, 1 }, view).ok());
  EXPECT_EQ(checkOrder(quads, { 1, 0 }, view).violations.size(), 1u);
  // Their planes are resolved well enough at 1e7: none is set aside as untrusted.
  EXPECT_EQ(checkOrder(sticks, { 0, 1, 2 }, view).untrustedPolygons, 0u);
  EXPECT_EQ(checkOrder(quads, { 0, 1 }, view).untrustedPolygons, 0u);
  const View parallel = View::parallel({ 0.01, 0.02, -1 });
  EXPECT_TRUE(checkOrder(quads, { 0, 1 }, parallel).ok());
  EXPECT_EQ(checkOrder(quads, { 1, 0 }, parallel).violations.size(), 1u);
}

// Regressions from Core/Fuzz (fragments of the BSP built from the reproducer, printed with
// SCENEVIS_FUZZ_DUMP=1; %.17g round-trips every double). Each gave a false violation before the
// witness re-check (rule 1) and the untrusted-plane rule (rule 2) of OrderOracle.h.

TEST(OrderOracle, FuzzEyeOnSeparatingPlaneIsNotAViolation)
{
  // crashes/oracle-eye-on-separating-plane: the eye (-2, -2, -2) lies exactly on the root plane;
  // fragment 0 (fuzz fragment 23) touches it from one side, the others from the other side. The
  // double-precision witness ray (separation 0.1) misses fragment 0 in exact arithmetic.
  const std::vector<Polygon> polys = {
    { { 0.17102348249889232, -0.25, 0.21577315019937965 },
      { 0.240566037735849, -0.25, 0.25471698113207542 }, { 0, -1, 0 },
      { -0.20000000000000007, -1.1333333333333333, -0.13333333333333336 } },
    { { -0.31034443296686809, -0.88362012238987253, -0.34482778351656596 },
      { -0.33333333333333337, -0.91666666666666674, -0.33333333333333331 },
      { -0.32424216698688729, -1.2734949457646756, -0.32424216698688718 } },
    { { -0.63636363636363646, -1.1931818181818183, -0.63636363636363624 },
      { -0.61206873875995149, -1.147628885174909, -0.67887970717008495 },
      { -0.40151128264844799, -1.4280341718970067, -0.40151128264844782 } },
    { { -0.31818181818181823, -1.5113636363636365, -0.31818181818181812 },
      { 0.85185236143448828, -0.8873454072349396, -0.86419776866942788 },
      { 0.81944558355651997, -0.67130047304057339, -0.67130047304057339 },
      { 0.50228656220989643, 0.49161593856371316, 0.49161593856371316 },
      { 0.22726506613656949, -0.17047337908093341, 0.22726506613656955 } }
  };
  const View view = View::perspective({ -2, -2, -2 });
  const OracleReport bsp = checkOrder(polys, { 3, 1, 2, 0 }, view); // the BSP's order
  EXPECT_TRUE(bsp.ok());
  EXPECT_GT(bsp.unconfirmedRays, 0u); // the grazing rays were cast and dropped
  EXPECT_EQ(bsp.untrustedPolygons, 0u);
  for (const Violation& v : bsp.violations)
  {
    ADD_FAILURE() << "false violation " << v.farther << " > " << v.nearer;
  }
  // The real constraints among fragments 1-3 are still enforced.
  const OracleReport reversed = checkOrder(polys, { 0, 2, 1, 3 }, view);
  EXPECT_EQ(reversed.violations.size(), 3u);
  for (const Violation& v : reversed.violations)
  {
    EXPECT_NE(v.farther, 0u);
    EXPECT_NE(v.nearer, 0u);
  }
}

TEST(OrderOracle, FuzzSpeckAt1e7ConstrainsNothing)
{
  // crashes/oracle-speck-at-1e7 (with SCENEVIS_FUZZ_STRICT=1): fragment 2 is a 1e-6 speck among
  // coordinates at 1e7 (rounding ~1e-9), so its vertices do not determine its plane (tilted
  // ~1e-2 rad). It was reported farther than both others, by up to 0.64.
  const std::vector<Polygon> polys = {
    { { 10000000.25, 10000000.25, -19999999.75 }, { 10000000.375, 9999999.5, -19999998.75 },
      { 10000000.925179189, 9999999.6311699506, -20000000.368830048 } },
    { { 10000001.000001892, 10000001, -19999999 }, { 10000000.25, 10000000.25, -19999999.75 },
      { 10000001.000000928, 10000001.000000486, -19999998.999998637 },
      { 10000001.000001129, 10000001.000000436, -19999998.999998838 } },
    { { 10000001.000000158, 10000000.999999035, -19999999.000001647 },
      { 10000001.000000225, 10000000.999998622, -19999999.000002351 },
      { 10000000.999999918, 10000000.999998519, -19999999.000001479 } }
  };
  const View view = View::perspective({ 9999998, 9999998, -20000002 });
  for (const auto& order : allPermutations(3))
  {
    const OracleReport report = checkOrder(polys, order, view);
    EXPECT_TRUE(report.ok());
    EXPECT_GE(report.untrustedPolygons, 1u);
  }
}

TEST(OrderOracle, FuzzSliverFalsePositive)
{
  // corpus/oracle-sliver-false-positive: a tetrahedron-like soup and its copy shifted by ~1e-9,
  // split by the BSP into 9 fragments; fragment 4 is a 1.65 x 1.5e-10 sliver whose plane (from
  // its vertices) is 6e-8 rad off, which made fragment 5 look 1.7e-8 farther than it.
  const std::vector<Polygon> polys = {
    { { -1.625, -2, 1.625 }, { -0.625, -1.375, -0.875 }, { -1.75, -0.875, -2 } },
    { { -0.625, -1.375, -0.875 }, { -1.75, -0.875, -2 }, { -2, -1.625, -1.75 } },
    { { -1.6250000009313226, -2.0000000009313226, 1.6249999990686774 },
      { -0.62500000120263222, -1.3750000011008912, -0.87500000025304825 },
      { -1.7500000008974088, -0.87500000123654598, -1.9999999999478253 } },
    { { -0.625, -1.375, -0.875 }, { -2, -1.625, -1.75 }, { -2, -2, -2 } },
    { { -0.62500000120263222, -1.3750000011008912, -0.87500000025304825 },
      { -0.62500000093132257, -1.3750000009313226, -0.87500000093132257 },
      { -0.62500000114809628, -1.3750000008349788, -0.87500000114809628 },
      { -0.62500000261135591, -1.3750000004747918, -0.87500000166177194 } },
    { { -0.62500000093132257, -1.3750000009313226, -0.87500000093132257 },
      { -0.62500000114809628, -1.3750000008349788, -0.87500000114809628 },
      { -2.0000000008831509, -1.6250000007868071, -1.7500000009794945 },
      { -2.0000000009313226, -1.6250000009313226, -1.7500000009313226 } },
    { { -2.0000000009313226, -1.6250000009313226, -1.7500000009313226 },
      { -2.0000000009313226, -2.0000000009313226, -2.0000000009313226 },
      { -0.62500000093132257, -1.3750000009313226, -0.87500000093132257 } },
    { { -0.62500000114809628, -1.3750000008349788, -0.87500000114809628 },
      { -1.7500000009313226, -0.87500000093132257, -2.0000000009313226 },
      { -1.7500000008974088, -0.87500000123654598, -1.9999999999478253 },
      { -0.62500000261135591, -1.3750000004747918, -0.87500000166177194 } },
    { { -0.62500000114809628, -1.3750000008349788, -0.87500000114809628 },
      { -1.7500000009313226, -0.87500000093132257, -2.0000000009313226 },
      { -2.0000000008831509, -1.6250000007868071, -1.7500000009794945 } }
  };
  const View view = View::perspective({ -2, -2, -2 });
  const std::vector<std::uint32_t> bspOrder = { 0, 2, 1, 7, 8, 3, 4, 5, 6 };
  const OracleReport report = checkOrder(polys, bspOrder, view);
  EXPECT_TRUE(report.ok());
  EXPECT_GE(report.untrustedPolygons, 1u);
  EXPECT_EQ(scenevis::oracle::relate(polys[5], polys[4], view).relation, Relation::Unconstrained);
  // The well-conditioned fragments still constrain: the reversed order breaks all 4 relations.
  const std::vector<std::uint32_t> reversed(bspOrder.rbegin(), bspOrder.rend());
  const OracleReport wrong = checkOrder(polys, reversed, view);
  EXPECT_EQ(wrong.constrainedPairs, report.constrainedPairs);
  EXPECT_EQ(wrong.violations.size(), report.constrainedPairs);
  EXPECT_GE(wrong.violations.size(), 4u);
}

TEST(OrderOracle, DegeneratePolygonsAreIgnored)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Polygon> polys = { rectZ(0, -1, 1, -1, 1),
    { { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 } },      // repeated point
    { { -1, -1, 1 }, { 0, 0, 1 }, { 1, 1, 1 } },    // collinear
    { { -1, -1, 1 }, { 1, -1, 1 }, { nan, 0, 1 } }, // non-finite
    { { -1, -1, 1 }, { 1, -1, 1 } } };              // two points
  const View view = View::perspective({ 0, 0, 5 });
  for (const auto& order :
    { std::vector<std::uint32_t>{ 4, 3, 2, 1, 0 }, std::vector<std::uint32_t>{ 0, 1, 2, 3, 4 } })
  {
    const OracleReport report = checkOrder(polys, order, view);
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(report.constrainedPairs, 0u);
  }
}

TEST(OrderOracle, MeshInputAndRelateWitness)
{
  scenevis::PolygonMesh mesh;
  for (const Polygon& poly : { rectZ(0, -1, 1, -1, 1), rectZ(1, -1, 1, -1, 1) })
  {
    std::vector<std::uint32_t> ids;
    for (const glm::dvec3& p : poly)
    {
      ids.push_back(mesh.addPoint(p));
    }
    mesh.addPolygon(ids.data(), ids.size());
  }
  const View view = View::perspective({ 0, 0, 5 });
  EXPECT_TRUE(checkOrder(mesh, { 0, 1 }, view).ok());
  EXPECT_FALSE(checkOrder(mesh, { 1, 0 }, view).ok());

  const auto polys = scenevis::oracle::polygonsOf(mesh);
  const auto relation = scenevis::oracle::relate(polys[0], polys[1], view);
  EXPECT_EQ(relation.relation, Relation::FirstFarther);
  EXPECT_NEAR(relation.witness.z, 0.0, 1e-12); // on the first polygon
  EXPECT_NEAR(relation.separation, 1.0, 1e-9);
  EXPECT_EQ(scenevis::oracle::relate(polys[1], polys[0], view).relation, Relation::SecondFarther);
}

TEST(OrderOracle, RejectsNonPermutations)
{
  const std::vector<Polygon> quads = { rectZ(0, -1, 1, -1, 1), rectZ(1, -1, 1, -1, 1) };
  const View view = View::perspective({ 0, 0, 5 });
  EXPECT_THROW(checkOrder(quads, { 0 }, view), std::invalid_argument);
  EXPECT_THROW(checkOrder(quads, { 0, 0 }, view), std::invalid_argument);
  EXPECT_THROW(checkOrder(quads, { 0, 2 }, view), std::invalid_argument);
}

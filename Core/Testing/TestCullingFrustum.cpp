// Specification of the frustum, the p-/n-vertex box test with plane masking and temporal
// coherence, and the BVH frustum cull against brute force.
#include "scenevis/Bvh.h"
#include "scenevis/Frustum.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace scenevis;
using namespace scenevis::culling;

namespace
{
glm::dmat4 perspectiveView(const glm::dvec3& eye,
  const glm::dvec3& target,
  double fovyDeg,
  double aspect,
  double znear,
  double zfar)
{
  const glm::dvec3 dir = glm::normalize(target - eye);
  const glm::dvec3 up = std::abs(dir.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  return glm::perspective(glm::radians(fovyDeg), aspect, znear, zfar) *
    glm::lookAt(eye, target, up);
}

struct Rng
{
  std::mt19937_64 gen;
  explicit Rng(std::uint64_t seed)
    : gen(seed)
  {
  }
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(gen); }
  glm::dvec3 vec(double a, double b) { return { uniform(a, b), uniform(a, b), uniform(a, b) }; }
};

Frustum randomFrustum(Rng& rng)
{
  const glm::dvec3 eye = rng.vec(-40, 40);
  glm::dvec3 target = rng.vec(-20, 20);
  if (glm::length(target - eye) < 1.0)
  {
    target += glm::dvec3(5, 0, 0);
  }
  const double znear = rng.uniform(0.05, 5);
  if (rng.uniform(0, 1) < 0.2)
  {
    // Parallel projection.
    const double s = rng.uniform(2, 30);
    const glm::dvec3 dir = glm::normalize(target - eye);
    const glm::dvec3 up = std::abs(dir.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
    return Frustum::fromViewProjection(
      glm::ortho(-s, s, -s * 0.7, s * 0.7, znear, znear + rng.uniform(5, 120)) *
      glm::lookAt(eye, target, up));
  }
  return Frustum::fromViewProjection(perspectiveView(eye, target, rng.uniform(10, 100),
    rng.uniform(0.4, 2.5), znear, znear + rng.uniform(5, 120)));
}

/// CAD-like size mix: log-uniform sizes from 0.01 to 20, some flat.
BoxArrays randomBoxes(Rng& rng, std::size_t n)
{
  BoxArrays boxes;
  for (std::size_t i = 0; i < n; ++i)
  {
    const glm::dvec3 c = rng.vec(-50, 50);
    glm::dvec3 h(std::exp(rng.uniform(std::log(0.005), std::log(10.0))),
      std::exp(rng.uniform(std::log(0.005), std::log(10.0))),
      std::exp(rng.uniform(std::log(0.005), std::log(10.0))));
    if (i % 17 == 0)
    {
      h.z = 0.0; // flat box (a single face)
    }
    Box b;
    b.lo = c - h;
    b.hi = c + h;
    boxes.push_back(b);
  }
  return boxes;
}

std::vector<std::uint32_t> bruteForce(const Frustum& f, const BoxArrays& boxes)
{
  std::vector<std::uint8_t> visible(boxes.size());
  cullBoxesFlat(f, boxes, visible.data());
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
  {
    if (visible[i])
    {
      ids.push_back(i);
    }
  }
  return ids;
}

std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v)
{
  std::sort(v.begin(), v.end());
  return v;
}
} // namespace

TEST(CullingFrustum, PlanesOfAPerspectiveMatrixAreNormalisedAndPointInward)
{
  const Frustum f = Frustum::fromViewProjection(
    perspectiveView({ 0, 0, 10 }, { 0, 0, 0 }, 60.0, 1.0, 1.0, 100.0));
  ASSERT_TRUE(f.valid());
  auto inside = [&f](const glm::dvec3& p)
  {
    for (const auto& pl : f.planes)
    {
      if (glm::dot(glm::dvec3(pl), p) + pl.w < 0)
      {
        return false;
      }
    }
    return true;
  };
  EXPECT_TRUE(inside({ 0, 0, 0 }));
  EXPECT_FALSE(inside({ 0, 0, 11 }));  // behind the eye
  EXPECT_FALSE(inside({ 0, 0, 9.5 })); // before the near plane
  EXPECT_FALSE(inside({ 0, 0, -95 })); // beyond the far plane
  EXPECT_FALSE(inside({ 20, 0, 0 }));  // right of the 60 deg cone
  EXPECT_TRUE(inside({ 5, 0, 0 }));
  // Near plane distance is Euclidean: the eye is 1 behind it.
  EXPECT_NEAR(glm::dot(glm::dvec3(f.planes[kNear]), glm::dvec3(0, 0, 10)) + f.planes[kNear].w, -1.0,
    1e-9);
}

TEST(CullingFrustum, RowMajorInputMatchesGlm)
{
  const glm::dmat4 m = perspectiveView({ 3, 4, 5 }, { 0, 0, 0 }, 45.0, 1.5, 0.5, 50.0);
  double rowMajor[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      rowMajor[r * 4 + c] = m[c][r];
    }
  }
  const Frustum a = Frustum::fromViewProjection(m);
  const Frustum b = Frustum::fromRowMajor(rowMajor);
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_EQ(a.planes[i], b.planes[i]);
  }
}

TEST(CullingFrustum, DegenerateMatrixIsInvalidAndCullsNothing)
{
  const Frustum f = Frustum::fromViewProjection(glm::dmat4(0.0));
  EXPECT_FALSE(f.valid());
  EXPECT_FALSE(boxOutside(f, { 0, 0, 0 }, { 1, 1, 1 }));
  glm::dmat4 nanMatrix(1.0);
  nanMatrix[0][0] = std::nan("");
  EXPECT_FALSE(Frustum::fromViewProjection(nanMatrix).valid());
}

TEST(CullingFrustum, BoxCases)
{
  const Frustum f = Frustum::fromViewProjection(
    perspectiveView({ 0, 0, 10 }, { 0, 0, 0 }, 60.0, 1.0, 1.0, 100.0));
  std::uint8_t mask = kAllPlanes, hint = 0;
  // Fully inside: passes and every plane bit is cleared.
  EXPECT_TRUE(testBoxMasked(f, { -1, -1, -1 }, { 1, 1, 1 }, mask, hint));
  EXPECT_EQ(mask, 0);
  // (Looking down -z, the view-up of perspectiveView() is +x: +x is the top of the image.)
  // Straddling the top plane: passes, the top plane stays in the mask.
  mask = kAllPlanes;
  EXPECT_TRUE(testBoxMasked(f, { 5, -1, -1 }, { 30, 1, 1 }, mask, hint));
  EXPECT_TRUE(mask & (1u << kTop));
  EXPECT_FALSE(mask & (1u << kBottom));
  // Outside the top plane: culled and the hint remembers the plane.
  mask = kAllPlanes;
  hint = kNear;
  EXPECT_FALSE(testBoxMasked(f, { 40, -1, -1 }, { 50, 1, 1 }, mask, hint));
  EXPECT_EQ(hint, kTop);
  // A box containing the whole frustum is not culled.
  EXPECT_FALSE(boxOutside(f, glm::dvec3(-1e3), glm::dvec3(1e3)));
  // A point box (zero size) behind the eye is culled; one on the axis is not.
  EXPECT_TRUE(boxOutside(f, { 0, 0, 20 }, { 0, 0, 20 }));
  EXPECT_FALSE(boxOutside(f, { 0, 0, 0 }, { 0, 0, 0 }));
}

TEST(CullingFrustum, MaskedTestOfChildrenEqualsFullTest)
{
  // Plane masking: testing a child only against the planes its parent straddles gives exactly
  // the full test's answer, over many random frusta and nested boxes.
  Rng rng(7);
  std::size_t culled = 0, total = 0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    const Frustum f = randomFrustum(rng);
    const glm::dvec3 c = rng.vec(-40, 40);
    const glm::dvec3 h = rng.vec(0.01, 20);
    const glm::dvec3 plo = c - h, phi = c + h;
    std::uint8_t parentMask = kAllPlanes, hint = 0;
    if (!testBoxMasked(f, plo, phi, parentMask, hint))
    {
      continue;
    }
    for (int k = 0; k < 20; ++k)
    {
      glm::dvec3 a(rng.uniform(plo.x, phi.x), rng.uniform(plo.y, phi.y), rng.uniform(plo.z, phi.z));
      glm::dvec3 b(rng.uniform(plo.x, phi.x), rng.uniform(plo.y, phi.y), rng.uniform(plo.z, phi.z));
      std::uint8_t mask = parentMask, childHint = static_cast<std::uint8_t>(k % 6);
      const bool kept = testBoxMasked(f, glm::min(a, b), glm::max(a, b), mask, childHint);
      EXPECT_EQ(kept, !boxOutside(f, glm::min(a, b), glm::max(a, b)));
      culled += kept ? 0 : 1;
      ++total;
    }
  }
  EXPECT_GT(culled, total / 20); // the cases are not all trivial
}

TEST(CullingBvh, FrustumCullEqualsBruteForceOverRandomFrusta)
{
  Rng rng(11);
  const BoxArrays boxes = randomBoxes(rng, 5000);
  for (const BuildMethod method : { BuildMethod::BinnedSah, BuildMethod::Median })
  {
    Bvh bvh;
    bvh.build(boxes, method, 4);
    std::vector<std::uint32_t> visible;
    std::size_t visibleTotal = 0;
    for (int frame = 0; frame < 300; ++frame)
    {
      CullParams params;
      params.frustum = randomFrustum(rng);
      CullStats stats;
      bvh.cull(params, visible, &stats);
      const auto expected = bruteForce(params.frustum, boxes);
      ASSERT_EQ(sorted(visible), expected) << "frame " << frame;
      EXPECT_EQ(stats.objectsDrawn + stats.objectsCulled(), boxes.size());
      EXPECT_EQ(stats.culledFrustum, boxes.size() - expected.size());
      visibleTotal += expected.size();
    }
    EXPECT_GT(visibleTotal, 0u);
    EXPECT_LT(visibleTotal, 300u * boxes.size());
  }
}

TEST(CullingBvh, TemporalCoherenceAcrossSmoothCameraPathDoesNotChangeResults)
{
  Rng rng(3);
  const BoxArrays boxes = randomBoxes(rng, 3000);
  Bvh bvh;
  bvh.build(boxes);
  std::vector<std::uint32_t> visible;
  for (int frame = 0; frame < 200; ++frame)
  {
    const double t = frame * 0.03;
    CullParams params;
    params.frustum = Frustum::fromViewProjection(perspectiveView(
      { 60 * std::cos(t), 60 * std::sin(t), 10 }, { 0, 0, 0 }, 40.0, 1.3, 1.0, 150.0));
    bvh.cull(params, visible, nullptr);
    ASSERT_EQ(sorted(visible), bruteForce(params.frustum, boxes)) << "frame " << frame;
  }
}

TEST(CullingBvh, RefitAfterMovesEqualsBruteForceOnTheNewBoxes)
{
  Rng rng(5);
  BoxArrays boxes = randomBoxes(rng, 4000);
  Bvh bvh;
  bvh.build(boxes);
  std::vector<std::uint32_t> visible;
  for (int round = 0; round < 20; ++round)
  {
    // Move 5 % of the objects, some far.
    for (int k = 0; k < 200; ++k)
    {
      const auto id = static_cast<std::uint32_t>(rng.uniform(0, boxes.size() - 0.5));
      Box b = boxes.get(id);
      const glm::dvec3 d = rng.vec(-1, 1) * (k % 10 == 0 ? 80.0 : 3.0);
      b.lo += d;
      b.hi += d;
      boxes.set(id, b);
      bvh.update(id, b);
    }
    EXPECT_GT(bvh.refit(), 0u);
    // Invariant: every node contains its objects / children.
    const auto& nodes = bvh.nodes();
    for (std::uint32_t ni = 0; ni < nodes.size(); ++ni)
    {
      if (!nodes[ni].isLeaf())
      {
        for (const std::uint32_t c : { ni + 1, nodes[ni].first })
        {
          ASSERT_TRUE(glm::all(glm::lessThanEqual(nodes[ni].lo, nodes[c].lo)));
          ASSERT_TRUE(glm::all(glm::greaterThanEqual(nodes[ni].hi, nodes[c].hi)));
        }
      }
    }
    for (int frame = 0; frame < 20; ++frame)
    {
      CullParams params;
      params.frustum = randomFrustum(rng);
      bvh.cull(params, visible, nullptr);
      ASSERT_EQ(sorted(visible), bruteForce(params.frustum, boxes))
        << "round " << round << " frame " << frame;
    }
  }
  EXPECT_GE(bvh.degradation(), 1.0);
}

TEST(CullingBvh, InvalidBoxesAreAlwaysVisible)
{
  Rng rng(9);
  BoxArrays boxes = randomBoxes(rng, 100);
  boxes.set(3, Box()); // empty
  Box nanBox;
  nanBox.lo = glm::dvec3(std::nan(""), 0, 0);
  nanBox.hi = glm::dvec3(1, 1, 1);
  boxes.set(7, nanBox);
  Bvh bvh;
  bvh.build(boxes);
  EXPECT_TRUE(bvh.alwaysVisible(3));
  EXPECT_TRUE(bvh.alwaysVisible(7));
  CullParams params;
  // A frustum far away from everything.
  params.frustum = Frustum::fromViewProjection(
    perspectiveView({ 1000, 1000, 1000 }, { 2000, 2000, 2000 }, 30, 1, 1, 10));
  std::vector<std::uint32_t> visible;
  bvh.cull(params, visible, nullptr);
  EXPECT_EQ(sorted(visible), (std::vector<std::uint32_t>{ 3, 7 }));
  // Moving an object to a NaN box makes it always visible too.
  Box infBox;
  infBox.lo = glm::dvec3(-INFINITY);
  infBox.hi = glm::dvec3(INFINITY);
  bvh.update(10, infBox);
  bvh.refit();
  bvh.cull(params, visible, nullptr);
  EXPECT_EQ(sorted(visible), (std::vector<std::uint32_t>{ 3, 7, 10 }));
  // An empty tree culls without crashing.
  Bvh empty;
  empty.build(BoxArrays());
  empty.cull(params, visible, nullptr);
  EXPECT_TRUE(visible.empty());
}

TEST(CullingBvh, DistanceCullingEqualsBruteForce)
{
  Rng rng(13);
  const BoxArrays boxes = randomBoxes(rng, 3000);
  Bvh bvh;
  bvh.build(boxes);
  std::vector<std::uint32_t> visible;
  for (int frame = 0; frame < 50; ++frame)
  {
    CullParams params;
    params.frustumCulling = false;
    params.eye = rng.vec(-60, 60);
    params.maxDistance = rng.uniform(5, 80);
    bvh.cull(params, visible, nullptr);
    std::vector<std::uint32_t> expected;
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
    {
      const Box b = boxes.get(i);
      const glm::dvec3 d = glm::max(glm::max(b.lo - params.eye, params.eye - b.hi), glm::dvec3(0));
      if (glm::dot(d, d) <= params.maxDistance * params.maxDistance)
      {
        expected.push_back(i);
      }
    }
    ASSERT_EQ(sorted(visible), expected);
  }
}

TEST(CullingBvh, ContributionCullingDropsOnlySmallFarObjects)
{
  BoxArrays boxes;
  Box big, small, nearSmall;
  big.lo = glm::dvec3(-5, -5, -105);
  big.hi = glm::dvec3(5, 5, -95);
  small.lo = glm::dvec3(-0.01, -0.01, -100.01);
  small.hi = glm::dvec3(0.01, 0.01, -99.99);
  nearSmall.lo = glm::dvec3(-0.01, -0.01, -1.01);
  nearSmall.hi = glm::dvec3(0.01, 0.01, -0.99);
  boxes.push_back(big);
  boxes.push_back(small);
  boxes.push_back(nearSmall);
  Bvh bvh;
  bvh.build(boxes, BuildMethod::BinnedSah, 1);
  CullParams params;
  params.frustumCulling = false;
  params.eye = glm::dvec3(0);
  params.viewDirection = glm::dvec3(0, 0, -1);
  params.pixelsPerUnit = 500.0; // 1000 px viewport, 90 deg
  params.minPixels = 2.0;
  std::vector<std::uint32_t> visible;
  CullStats stats;
  bvh.cull(params, visible, &stats);
  // small: 0.035 diagonal at depth 100 -> 0.17 px: culled; the others are far above 2 px.
  EXPECT_EQ(sorted(visible), (std::vector<std::uint32_t>{ 0, 2 }));
  EXPECT_EQ(stats.culledContribution, 1u);
}

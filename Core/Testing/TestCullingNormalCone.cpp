// Specification of normal cones: conservative (never cull a front-facing triangle) against the
// brute-force per-triangle back-face test, over many random eyes, and useful (they do cull).
#include "scenevis/Bvh.h"
#include "scenevis/NormalCone.h"
#include "scenevis/Scenes.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace scenevis;
using namespace scenevis::culling;

namespace
{
struct Cluster
{
  std::vector<glm::dvec3> a, b, c; // triangles
  Box box;
  NormalCone cone;
  glm::dvec3 center() const { return box.center(); }
  double radius() const { return 0.5 * glm::length(box.hi - box.lo); }
};

/// Clusters of up to `size` consecutive triangles of every part of `scene`.
std::vector<Cluster> clustersOf(const scenes::Scene& scene, std::size_t size)
{
  std::vector<Cluster> clusters;
  const PolygonMesh& mesh = scene.mesh;
  for (const auto& part : scene.parts)
  {
    for (std::size_t first = part.firstPolygon; first < part.firstPolygon + part.polygonCount;
         first += size)
    {
      const std::size_t count =
        std::min<std::size_t>(size, part.firstPolygon + part.polygonCount - first);
      Cluster cl;
      std::vector<glm::dvec3> normals;
      for (std::size_t i = first; i < first + count; ++i)
      {
        const std::uint32_t* ids = mesh.polygon(i);
        for (std::uint32_t k = 1; k + 1 < mesh.polygonSize(i); ++k)
        {
          cl.a.push_back(mesh.points[ids[0]]);
          cl.b.push_back(mesh.points[ids[k]]);
          cl.c.push_back(mesh.points[ids[k + 1]]);
          for (const auto* p : { &cl.a.back(), &cl.b.back(), &cl.c.back() })
          {
            cl.box.extend(*p);
          }
        }
      }
      cl.cone = normalConeOf(mesh, first, count);
      clusters.push_back(std::move(cl));
    }
  }
  return clusters;
}

bool anyFrontFacing(const Cluster& cl, const glm::dvec3& eye)
{
  for (std::size_t t = 0; t < cl.a.size(); ++t)
  {
    if (triangleFrontFacing(cl.a[t], cl.b[t], cl.c[t], eye))
    {
      return true;
    }
  }
  return false;
}

bool anyFrontFacingAlong(const Cluster& cl, const glm::dvec3& dop)
{
  for (std::size_t t = 0; t < cl.a.size(); ++t)
  {
    if (glm::dot(glm::cross(cl.b[t] - cl.a[t], cl.c[t] - cl.a[t]), -dop) > 0.0)
    {
      return true;
    }
  }
  return false;
}
} // namespace

TEST(CullingNormalCone, ConeOfAClosedSurfaceNeverCulls)
{
  const PolygonMesh sphere = scenes::sphere({ 0, 0, 0 }, 1.0, 200);
  EXPECT_FALSE(normalConeOf(sphere, 0, sphere.polygonCount()).canCull());
}

TEST(CullingNormalCone, DegenerateInput)
{
  EXPECT_FALSE(normalConeOf(std::vector<glm::dvec3>{}).canCull());
  EXPECT_FALSE(normalConeOf(std::vector<glm::dvec3>{ glm::dvec3(0) }).canCull());
  EXPECT_FALSE(
    normalConeOf(std::vector<glm::dvec3>{ { 0, 0, 1 }, { std::nan(""), 0, 1 } }).canCull());
  const NormalCone flat = normalConeOf(std::vector<glm::dvec3>{ { 0, 0, 2 }, { 0, 0, 0 } });
  ASSERT_TRUE(flat.canCull());
  EXPECT_NEAR(flat.sinHalfAngle, 0.0, 1e-6);
  // Opposite normals: hemisphere or more.
  EXPECT_FALSE(normalConeOf(std::vector<glm::dvec3>{ { 0, 0, 1 }, { 0, 0, -1 } }).canCull());
  // Eye inside the bounding sphere: never culled.
  EXPECT_FALSE(backFacingFromEye(flat, { 0, 0, 0 }, 1.0, { 0, 0, -0.5 }));
  EXPECT_TRUE(backFacingFromEye(flat, { 0, 0, 0 }, 1.0, { 0, 0, -5 }));
  EXPECT_FALSE(backFacingFromEye(flat, { 0, 0, 0 }, 1.0, { 0, 0, 5 }));
  EXPECT_FALSE(backFacingAlong(flat, { 0, 0, 0 }));
}

TEST(CullingNormalCone, NeverCullsAFrontFacingTriangleFromRandomEyes)
{
  const scenes::Scene cad = scenes::cadAssembly(300, 80, 17);
  const auto clusters = clustersOf(cad, 24);
  const Box bounds = cad.mesh.bounds();
  std::mt19937_64 gen(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::size_t culls = 0, tests = 0;
  for (int e = 0; e < 300; ++e)
  {
    // Eyes near and far, inside the model's box and around it.
    const double spread = e % 3 == 0 ? 0.6 : (e % 3 == 1 ? 1.5 : 5.0);
    const glm::dvec3 eye = bounds.center() +
      glm::dvec3(u(gen), u(gen), u(gen)) * (bounds.hi - bounds.lo) * spread;
    for (const Cluster& cl : clusters)
    {
      ++tests;
      if (backFacingFromEye(cl.cone, cl.center(), cl.radius(), eye))
      {
        ++culls;
        ASSERT_FALSE(anyFrontFacing(cl, eye)) << "false cull, eye " << eye.x << " " << eye.y
                                              << " " << eye.z;
      }
    }
  }
  // Useful: a good share of the clusters of closed parts is culled (about half are back-facing).
  EXPECT_GT(culls, tests / 20) << culls << " of " << tests;
}

TEST(CullingNormalCone, NeverCullsAFrontFacingTriangleAlongRandomDirections)
{
  const scenes::Scene cad = scenes::cadAssembly(200, 80, 23);
  const auto clusters = clustersOf(cad, 24);
  std::mt19937_64 gen(43);
  std::normal_distribution<double> n(0.0, 1.0);
  std::size_t culls = 0, tests = 0;
  for (int e = 0; e < 200; ++e)
  {
    const glm::dvec3 dop = glm::normalize(glm::dvec3(n(gen), n(gen), n(gen)));
    for (const Cluster& cl : clusters)
    {
      ++tests;
      if (backFacingAlong(cl.cone, dop))
      {
        ++culls;
        ASSERT_FALSE(anyFrontFacingAlong(cl, dop));
      }
    }
  }
  EXPECT_GT(culls, tests / 10);
}

TEST(CullingNormalCone, MergedConesAreConservativeToo)
{
  // The BVH culls whole nodes with merged cones and the node's bounding sphere.
  const scenes::Scene cad = scenes::cadAssembly(100, 100, 5);
  const auto clusters = clustersOf(cad, 16);
  std::mt19937_64 gen(44);
  std::uniform_int_distribution<std::size_t> pick(0, clusters.size() - 1);
  std::uniform_real_distribution<double> u(-300.0, 300.0);
  std::size_t culls = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    const Cluster& x = clusters[pick(gen)];
    const Cluster& y = clusters[pick(gen)];
    const NormalCone m = merge(x.cone, y.cone);
    if (!m.canCull())
    {
      continue;
    }
    // Every normal of both clusters is within the merged cone.
    for (const Cluster* cl : { &x, &y })
    {
      for (std::size_t t = 0; t < cl->a.size(); ++t)
      {
        const glm::dvec3 nrm = glm::cross(cl->b[t] - cl->a[t], cl->c[t] - cl->a[t]);
        if (glm::length(nrm) > 0)
        {
          const double s = glm::length(glm::cross(glm::normalize(nrm), m.axis));
          ASSERT_TRUE(glm::dot(nrm, m.axis) > 0 && s <= m.sinHalfAngle)
            << s << " " << m.sinHalfAngle << " x " << x.cone.sinHalfAngle << " y "
            << y.cone.sinHalfAngle << " axes " << glm::dot(x.cone.axis, y.cone.axis);
        }
      }
    }
    Box box = x.box;
    box.extend(y.box);
    const glm::dvec3 eye(u(gen), u(gen), u(gen) * 0.3 + 50);
    if (backFacingFromEye(m, box.center(), 0.5 * glm::length(box.hi - box.lo), eye))
    {
      ++culls;
      ASSERT_FALSE(anyFrontFacing(x, eye) || anyFrontFacing(y, eye));
    }
  }
  EXPECT_GT(culls, 0u);
}

TEST(CullingNormalCone, BvhConeCullingIsConservative)
{
  const scenes::Scene cad = scenes::cadAssembly(200, 80, 31);
  const auto clusters = clustersOf(cad, 24);
  BoxArrays boxes;
  for (const Cluster& cl : clusters)
  {
    boxes.push_back(cl.box);
  }
  Bvh bvh;
  bvh.build(boxes);
  for (std::uint32_t i = 0; i < clusters.size(); ++i)
  {
    bvh.setNormalCone(i, clusters[i].cone);
  }
  bvh.refit();
  const Box bounds = cad.mesh.bounds();
  std::mt19937_64 gen(45);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::uint32_t> visible;
  std::size_t culled = 0;
  for (int e = 0; e < 100; ++e)
  {
    CullParams params;
    params.frustumCulling = false;
    params.normalConeCulling = true;
    params.eye = bounds.center() + glm::dvec3(u(gen), u(gen), u(gen)) * (bounds.hi - bounds.lo);
    CullStats stats;
    bvh.cull(params, visible, &stats);
    std::vector<std::uint8_t> drawn(clusters.size(), 0);
    for (std::uint32_t id : visible)
    {
      drawn[id] = 1;
    }
    for (std::uint32_t i = 0; i < clusters.size(); ++i)
    {
      if (!drawn[i])
      {
        ASSERT_FALSE(anyFrontFacing(clusters[i], params.eye)) << "cluster " << i;
      }
    }
    culled += stats.culledNormalCone;
  }
  EXPECT_GT(culled, 0u);
}

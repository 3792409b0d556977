// Specification of bsp::order and bsp::IncrementalOrder: permutations, direction symmetry, a
// hand-checked case, eyes on planes, and incremental == full walk along many camera paths.
#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/OrderOracle.h"
#include "scenevis/Scenes.h"

#include "PolygonSoups.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace
{

using namespace scenevis;
using bsp::Direction;
using testsupport::uvSphere;

constexpr double kPi = 3.14159265358979323846;

struct Random
{
  std::uint64_t state;
  double uniform() // [0, 1)
  {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  }
  double symmetric() { return 2.0 * uniform() - 1.0; }
  glm::dvec3 vector() { return glm::dvec3(symmetric(), symmetric(), symmetric()); }
};

PolygonMesh randomSoup(int triangles, std::uint64_t seed)
{
  Random random{ seed * 0x9e3779b97f4a7c15ull + 7 };
  PolygonMesh mesh;
  for (int t = 0; t < triangles; ++t)
  {
    const glm::dvec3 c = random.vector();
    const std::uint32_t i = mesh.addPoint(c + random.vector() * 0.4);
    mesh.addPoint(c + random.vector() * 0.4);
    mesh.addPoint(c + random.vector() * 0.4);
    mesh.addPolygon({ i, i + 1, i + 2 });
  }
  return mesh;
}

std::vector<std::uint32_t> fullOrder(const bsp::Tree& tree, const View& view, Direction d)
{
  std::vector<std::uint32_t> result;
  bsp::order(tree, view, d, result);
  return result;
}

bool isPermutation(std::vector<std::uint32_t> order, std::size_t n)
{
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> identity(n);
  std::iota(identity.begin(), identity.end(), 0u);
  return order == identity;
}

/// Eye on the orbit of radius `r` at `degrees` around z, 25 degrees up.
glm::dvec3 orbit(double degrees, double r)
{
  const double a = degrees * kPi / 180.0;
  const double e = 25.0 * kPi / 180.0;
  return glm::dvec3(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)) * r;
}

/// A point exactly on the plane of a fragment of the tree (one of its vertices), so that the eye
/// sits on a partition plane up to rounding.
glm::dvec3 pointOnSomePlane(const bsp::Tree& tree, Random& random)
{
  const auto f = static_cast<std::size_t>(random.uniform() * tree.fragments.size());
  return tree.points[tree.fragmentVertices[tree.fragments[f].first]];
}

void expectIncrementalMatchesFull(const bsp::Tree& tree, const std::vector<View>& path)
{
  for (Direction d : { Direction::BackToFront, Direction::FrontToBack })
  {
    bsp::IncrementalOrder incremental(tree, d);
    for (std::size_t i = 0; i < path.size(); ++i)
    {
      incremental.update(path[i]);
      ASSERT_EQ(incremental.order(), fullOrder(tree, path[i], d))
        << "step " << i << (d == Direction::BackToFront ? " back-to-front" : " front-to-back");
    }
  }
}

TEST(BspTraversal, OrderIsAPermutationAndFrontToBackIsItsReverse)
{
  const PolygonMesh mesh = randomSoup(300, 1);
  const bsp::Tree tree = bsp::build(mesh);
  Random random{ 99 };
  for (int i = 0; i < 20; ++i)
  {
    const View view = i % 2 ? View::perspective(random.vector() * 3.0)
                            : View::parallel(random.vector() + glm::dvec3(0, 0, 1e-3));
    std::vector<std::uint32_t> backToFront = fullOrder(tree, view, Direction::BackToFront);
    const std::vector<std::uint32_t> frontToBack = fullOrder(tree, view, Direction::FrontToBack);
    ASSERT_TRUE(isPermutation(backToFront, tree.fragments.size()));
    std::reverse(backToFront.begin(), backToFront.end());
    ASSERT_EQ(backToFront, frontToBack);
  }
}

TEST(BspTraversal, TwoParallelQuadsFarOneFirstFromEitherSide)
{
  PolygonMesh mesh;
  for (double z : { 0.0, 1.0 })
  {
    const std::uint32_t i = mesh.addPoint({ -1, -1, z });
    mesh.addPoint({ 1, -1, z });
    mesh.addPoint({ 1, 1, z });
    mesh.addPoint({ -1, 1, z });
    mesh.addPolygon({ i, i + 1, i + 2, i + 3 });
  }
  const bsp::Tree tree = bsp::build(mesh);
  ASSERT_EQ(tree.fragments.size(), 2u);
  auto sources = [&tree](const std::vector<std::uint32_t>& order)
  {
    std::vector<std::uint32_t> s;
    for (std::uint32_t f : order)
    {
      s.push_back(tree.fragments[f].source);
    }
    return s;
  };
  using V = std::vector<std::uint32_t>;
  EXPECT_EQ(sources(fullOrder(tree, View::perspective({ 0.2, 0.1, 5 }), Direction::BackToFront)),
    (V{ 0, 1 }));
  EXPECT_EQ(sources(fullOrder(tree, View::perspective({ 0.2, 0.1, -5 }), Direction::BackToFront)),
    (V{ 1, 0 }));
  EXPECT_EQ(sources(fullOrder(tree, View::perspective({ 0.2, 0.1, 0.5 }), Direction::FrontToBack)),
    (V{ 1, 0 })) << "between the quads: either is fine geometrically, the tree decides";
  // Looking down -z from above: quad 0 is farther.
  EXPECT_EQ(sources(fullOrder(tree, View::parallel({ 0, 0, -1 }), Direction::BackToFront)),
    (V{ 0, 1 }));
  EXPECT_EQ(sources(fullOrder(tree, View::parallel({ 0.1, 0, 1 }), Direction::BackToFront)),
    (V{ 1, 0 }));
  // Far from the origin the planes are relative to Tree::origin: same answer.
  EXPECT_EQ(sources(fullOrder(tree, View::perspective({ 1e7, 1e7, 5e7 }), Direction::BackToFront)),
    (V{ 0, 1 }));
}

TEST(BspTraversal, EyeExactlyOnAPlaneStillGivesAPermutation)
{
  const PolygonMesh mesh = randomSoup(200, 2);
  const bsp::Tree tree = bsp::build(mesh);
  Random random{ 5 };
  for (int i = 0; i < 30; ++i)
  {
    const View view = View::perspective(pointOnSomePlane(tree, random));
    for (Direction d : { Direction::BackToFront, Direction::FrontToBack })
    {
      ASSERT_TRUE(isPermutation(fullOrder(tree, view, d), tree.fragments.size()));
    }
  }
  // Parallel views along a partition plane (w = 0 and n . v = 0).
  const glm::dvec3 n(tree.nodes[tree.root].plane);
  const glm::dvec3 along = glm::normalize(glm::cross(n, glm::dvec3(0.3, 0.5, 0.7)));
  ASSERT_TRUE(isPermutation(
    fullOrder(tree, View::parallel(along), Direction::BackToFront), tree.fragments.size()));
}

TEST(BspTraversal, OrderIsCorrectAccordingToTheOracle)
{
  const PolygonMesh mesh = randomSoup(60, 3);
  const bsp::Tree tree = bsp::build(mesh);
  const std::vector<oracle::Polygon> fragments = oracle::fragmentPolygons(tree);
  oracle::OracleConfig config;
  config.samplesPerOverlap = 1;
  Random random{ 17 };
  for (int i = 0; i < 6; ++i)
  {
    const View view = i % 2 ? View::perspective(random.vector() * 4.0)
                            : View::parallel(random.vector() + glm::dvec3(0, 0, 1e-3));
    const oracle::OracleReport report =
      oracle::checkOrder(fragments, fullOrder(tree, view, Direction::BackToFront), view, config);
    EXPECT_TRUE(report.violations.empty()) << report.violations.size() << " violations, view " << i;
  }
}

TEST(BspTraversal, IncrementalMatchesFullOrderOnRandomPaths)
{
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
  {
    const PolygonMesh mesh = randomSoup(250, seed);
    const bsp::Tree tree = bsp::build(mesh);
    Random random{ seed + 1000 };
    std::vector<View> path;
    glm::dvec3 eye = random.vector() * 2.0;
    for (int i = 0; i < 150; ++i)
    {
      const double kind = random.uniform();
      if (kind < 0.6)
      {
        eye += random.vector() * 0.05; // small step, often inside the soup
        path.push_back(View::perspective(eye));
      }
      else if (kind < 0.75)
      {
        eye = random.vector() * 4.0; // jump
        path.push_back(View::perspective(eye));
      }
      else if (kind < 0.9)
      {
        path.push_back(View::parallel(random.vector() + glm::dvec3(1e-3, 0, 0)));
      }
      else
      {
        eye = pointOnSomePlane(tree, random); // exactly on a plane
        path.push_back(View::perspective(eye));
      }
    }
    expectIncrementalMatchesFull(tree, path);
  }
}

TEST(BspTraversal, IncrementalMatchesFullOrderOnOrbits)
{
  const PolygonMesh mesh = uvSphere(5000);
  for (bool scored : { true, false })
  {
    bsp::BuildConfig config;
    if (!scored)
    {
      config.partition = bsp::BuildConfig::Partition::FirstInList;
    }
    const bsp::Tree tree = bsp::build(mesh, config);
    std::vector<View> path;
    for (int step = 0; step < 400; ++step)
    {
      path.push_back(View::perspective(orbit(step, 3.0)));
    }
    for (int step = 0; step < 100; ++step)
    {
      path.push_back(View::perspective(orbit(3.0 * step, 0.5))); // inside the sphere
    }
    for (int step = 0; step < 100; ++step)
    {
      path.push_back(View::parallel(-orbit(step, 1.0)));
    }
    path.push_back(View::perspective(glm::dvec3(0.0))); // on every free plane through the centre
    path.push_back(View::perspective(mesh.points[5]));  // on the planes of the triangles at a vertex
    path.push_back(View::perspective(orbit(0, 3.0)));
    expectIncrementalMatchesFull(tree, path);
  }
}

TEST(BspTraversal, IncrementalMatchesFullOrderOnTheSphereGrid)
{
  // Overlapping spheres: many splits, so chains are short and most units have two children whose
  // ranges move when a chain node above them flips.
  const PolygonMesh mesh = scenes::sphereGrid(3, 0.8, 1.0, 200).mesh;
  const bsp::Tree tree = bsp::build(mesh);
  Random random{ 4242 };
  std::vector<View> path;
  for (int step = 0; step < 200; ++step)
  {
    path.push_back(View::perspective(orbit(step * 1.5, 4.0)));
  }
  for (int step = 0; step < 100; ++step)
  {
    path.push_back(View::perspective(orbit(step * 3.0, 0.9 + 0.3 * std::sin(step * 0.2))));
  }
  for (int step = 0; step < 60; ++step)
  {
    const double kind = random.uniform();
    if (kind < 0.4)
    {
      path.push_back(View::perspective(random.vector() * 3.0));
    }
    else if (kind < 0.7)
    {
      path.push_back(View::parallel(random.vector() + glm::dvec3(0, 1e-3, 0)));
    }
    else
    {
      path.push_back(View::perspective(pointOnSomePlane(tree, random)));
    }
  }
  expectIncrementalMatchesFull(tree, path);
}

TEST(BspTraversal, IncrementalCompactsAnchorsOnLongPaths)
{
  const PolygonMesh mesh = randomSoup(100, 8);
  const bsp::Tree tree = bsp::build(mesh);
  bsp::IncrementalOrder incremental(tree, Direction::BackToFront);
  const std::size_t before = incremental.memoryBytes();
  for (int step = 0; step < 3000; ++step)
  {
    const View view = View::perspective(orbit(step * 0.7, 2.0 + 0.5 * std::sin(step * 0.01)));
    incremental.update(view);
    if (step % 97 == 0)
    {
      ASSERT_EQ(incremental.order(), fullOrder(tree, view, Direction::BackToFront));
    }
  }
  EXPECT_LT(incremental.memoryBytes(), before + 64 * 1024) << "eye anchors must not pile up";
}

TEST(BspTraversal, SmallOrbitStepVisitsFewNodes)
{
  const PolygonMesh mesh = uvSphere(100000);
  const bsp::Tree tree = bsp::build(mesh);
  bsp::IncrementalOrder incremental(tree, Direction::BackToFront);
  const bsp::IncrementalOrder::UpdateStatistics first = incremental.update(View::perspective(orbit(0, 3)));
  EXPECT_EQ(first.nodesVisited, tree.nodes.size()) << "the first update is a full walk";
  std::size_t visited = 0;
  std::size_t flipped = 0;
  const int steps = 20;
  for (int step = 1; step <= steps; ++step)
  {
    const auto& s = incremental.update(View::perspective(orbit(step, 3)));
    visited += s.nodesVisited;
    flipped += s.nodesFlipped;
    EXPECT_LE(s.nodesFlipped, s.nodesVisited);
  }
  EXPECT_LT(visited / steps, tree.nodes.size() / 5) << "a 1 degree step must skip most subtrees";
  EXPECT_GT(flipped, 0u) << "the silhouette moves, so some planes are crossed";
  EXPECT_EQ(incremental.order(), fullOrder(tree, View::perspective(orbit(steps, 3)),
                                   Direction::BackToFront));
  // Standing still costs (almost) nothing.
  const auto& still = incremental.update(View::perspective(orbit(steps, 3)));
  EXPECT_EQ(still.nodesFlipped, 0u);
  EXPECT_LT(still.nodesVisited, tree.nodes.size() / 20);
}

TEST(BspTraversal, EmptyTree)
{
  const bsp::Tree tree;
  bsp::IncrementalOrder incremental(tree, Direction::BackToFront);
  incremental.update(View::perspective({ 1, 2, 3 }));
  EXPECT_TRUE(incremental.order().empty());
  EXPECT_EQ(incremental.lastUpdate().nodesVisited, 0u);
}

} // namespace

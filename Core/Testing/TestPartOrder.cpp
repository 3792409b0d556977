// The two-level order (PartTree.h, PartOrder.h): placed parts ordered as wholes, each by its own
// mesh's tree, and parts that no plane separates by one world-space tree. Every order is judged by
// the brute-force oracle (OrderOracle.h) over all drawn fragments in world coordinates, from eyes
// around, inside and between the parts, on the separating planes, and parallel views.
#include "scenevis/BspBuilder.h"
#include "scenevis/OrderOracle.h"
#include "scenevis/PartOrder.h"
#include "scenevis/PartTree.h"

#include "PolygonSoups.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

using scenevis::Box;
using scenevis::PolygonMesh;
using scenevis::View;
using scenevis::bsp::Direction;
using scenevis::oracle::Polygon;
using scenevis::parts::Part;
using scenevis::parts::Piece;
using scenevis::testsupport::describe;
using scenevis::testsupport::meshOf;
using scenevis::testsupport::randomSoup;
using scenevis::testsupport::randomViews;
using scenevis::testsupport::uvSphere;

namespace parts = scenevis::parts;
namespace bsp = scenevis::bsp;

namespace
{

/// Meshes, their own trees (built once per mesh, in model coordinates) and the placed parts.
struct PartScene
{
  std::vector<PolygonMesh> meshes;
  std::vector<Part> parts;

  std::vector<bsp::Tree> meshTrees;
  std::vector<std::vector<Polygon>> meshFragments; ///< Each mesh tree's fragments (model).
  parts::Tree tree;

  void build()
  {
    meshTrees.clear();
    meshFragments.clear();
    std::vector<const PolygonMesh*> pointers;
    for (const PolygonMesh& m : meshes)
    {
      meshTrees.push_back(bsp::build(m));
      meshFragments.push_back(scenevis::oracle::fragmentPolygons(meshTrees.back()));
      pointers.push_back(&m);
    }
    tree = parts::build(pointers, parts);
  }

  std::vector<const bsp::Tree*> treePointers() const
  {
    std::vector<const bsp::Tree*> t;
    for (const bsp::Tree& m : meshTrees)
    {
      t.push_back(&m);
    }
    return t;
  }

  /// A drawn piece as a world-space polygon.
  Polygon world(const Piece& piece) const
  {
    const parts::Group& group = tree.groups[piece.group];
    if (!group.single())
    {
      Polygon polygon =
        scenevis::oracle::fragmentPolygons(tree.shapes[group.shape].tree)[piece.fragment];
      for (glm::dvec3& p : polygon)
      {
        p = glm::dvec3(group.worldFromShape * glm::dvec4(p, 1.0));
      }
      return polygon;
    }
    const Part& part = parts[piece.part];
    Polygon polygon = meshFragments[part.mesh][piece.fragment];
    for (glm::dvec3& p : polygon)
    {
      p = glm::dvec3(part.worldFromModel * glm::dvec4(p, 1.0));
    }
    return polygon;
  }

  /// The oracle's verdict on @p pieces drawn in that order (first drawn first).
  scenevis::oracle::OracleReport judge(const std::vector<Piece>& pieces, const View& view) const
  {
    std::vector<Polygon> polygons;
    std::vector<std::uint32_t> drawn;
    for (const Piece& p : pieces)
    {
      drawn.push_back(static_cast<std::uint32_t>(polygons.size()));
      polygons.push_back(this->world(p));
    }
    return scenevis::oracle::checkOrder(polygons, drawn, view);
  }

  Box bounds() const
  {
    Box box;
    for (const Part& part : parts)
    {
      for (const glm::dvec3& p : meshes[part.mesh].points)
      {
        const glm::dvec3 w(part.worldFromModel * glm::dvec4(p, 1.0));
        if (std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z))
        {
          box.extend(w);
        }
      }
    }
    return box;
  }

  /// Fragments every order must draw: each single part's mesh tree, each merged tree.
  std::size_t expectedPieces() const
  {
    std::size_t n = 0;
    for (const parts::Group& g : tree.groups)
    {
      n += g.single() ? meshTrees[parts[g.parts.front()].mesh].fragments.size()
                      : tree.shapes[g.shape].tree.fragments.size();
    }
    return n;
  }
};

glm::dmat4 placement(
  const glm::dvec3& at, double angle, const glm::dvec3& axis, const glm::dvec3& scale)
{
  return glm::scale(glm::rotate(glm::translate(glm::dmat4(1.0), at), angle, axis), scale);
}

/// The complete order for `view` drawn through the oracle, back to front and (reversed) front to
/// back; every fragment drawn exactly once.
::testing::AssertionResult orderIsCorrect(const PartScene& scene, const View& view)
{
  for (const Direction direction : { Direction::BackToFront, Direction::FrontToBack })
  {
    std::vector<Piece> pieces;
    parts::order(scene.tree, scene.treePointers(), view, direction, pieces);
    if (pieces.size() != scene.expectedPieces())
    {
      return ::testing::AssertionFailure()
        << pieces.size() << " pieces drawn for " << scene.expectedPieces() << " fragments";
    }
    std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> seen;
    for (const Piece& p : pieces)
    {
      if (!seen.insert({ p.group, p.part, p.fragment }).second)
      {
        return ::testing::AssertionFailure()
          << "fragment " << p.fragment << " of part " << p.part << " drawn twice";
      }
    }
    if (direction == Direction::FrontToBack)
    {
      std::reverse(pieces.begin(), pieces.end());
    }
    const auto report = scene.judge(pieces, view);
    if (!report.ok())
    {
      const auto& v = report.violations.front();
      return ::testing::AssertionFailure()
        << report.violations.size() << " violation(s) "
        << (direction == Direction::BackToFront ? "back to front" : "front to back") << " for "
        << describe(view) << "; first: part " << pieces[v.farther].part << " (group "
        << pieces[v.farther].group << ") is farther than part " << pieces[v.nearer].part
        << " (group " << pieces[v.nearer].group << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Random views around the scene, an eye at every part's centre, and eyes on every separating
/// plane of the top level (the projection of the scene's centre onto it).
std::vector<View> viewsOf(const PartScene& scene, std::uint64_t seed, int perspective, int parallel)
{
  const Box box = scene.bounds();
  std::vector<View> views = randomViews(box, seed, perspective, parallel);
  for (const Part& part : scene.parts)
  {
    views.push_back(View::perspective(glm::dvec3(part.worldFromModel * glm::dvec4(0, 0, 0, 1))));
  }
  for (const parts::Node& node : scene.tree.nodes)
  {
    if (node.group == bsp::kNone)
    {
      const glm::dvec3 n(node.plane);
      const glm::dvec3 c = box.center();
      views.push_back(View::perspective(c - n * (glm::dot(n, c) + node.plane.w)));
    }
  }
  return views;
}

} // namespace

TEST(PartOrder, SeparatePartsAreOrderedAsWholesWithoutSplittingEachOther)
{
  // A 3 x 3 x 2 grid of two meshes, rotated, scaled unevenly and some mirrored: instances that
  // share their mesh's tree.
  PartScene scene;
  scene.meshes.push_back(uvSphere(200));
  scene.meshes.push_back(meshOf(randomSoup(7, 30)));
  for (int i = 0; i < 18; ++i)
  {
    const glm::dvec3 at(3.0 * (i % 3), 3.0 * ((i / 3) % 3), 3.0 * (i / 9));
    const double mirror = i % 4 == 3 ? -1.0 : 1.0;
    scene.parts.push_back(Part{ static_cast<std::uint32_t>(i % 2),
      placement(at, 0.4 * i, glm::normalize(glm::dvec3(1, 2, 3 + i)),
        glm::dvec3(mirror * 1.2, 0.7, 1.0)) });
  }
  scene.build();
  const parts::Statistics& s = scene.tree.statistics;
  EXPECT_EQ(s.groups, 18u);
  EXPECT_EQ(s.singlePartGroups, 18u);
  EXPECT_EQ(s.mergedFragments, 0u);
  EXPECT_EQ(s.separatingPlanes, 17u);
  EXPECT_LE(s.depth, 6u); // balanced: ceil(log2 18) + 1
  for (const View& view : viewsOf(scene, 11, 24, 6))
  {
    EXPECT_TRUE(orderIsCorrect(scene, view));
  }
}

TEST(PartOrder, PartsThatInterpenetrateShareOneTree)
{
  PartScene scene;
  scene.meshes.push_back(uvSphere(120));
  scene.parts.push_back(Part{ 0, placement({ 0, 0, 0 }, 0.0, { 0, 0, 1 }, glm::dvec3(1.0)) });
  scene.parts.push_back(Part{ 0, placement({ 1.2, 0.3, 0 }, 0.5, { 1, 0, 0 }, glm::dvec3(1.0)) });
  scene.parts.push_back(Part{ 0, placement({ 6, 0, 0 }, 0.0, { 0, 0, 1 }, glm::dvec3(1.0)) });
  // Nested: a small part inside a big one is not separable either.
  scene.parts.push_back(Part{ 0, placement({ 0, 6, 0 }, 0.0, { 0, 0, 1 }, glm::dvec3(2.0)) });
  scene.parts.push_back(Part{ 0, placement({ 0.2, 6, 0.1 }, 1.0, { 0, 1, 0 }, glm::dvec3(0.5)) });
  scene.build();
  const parts::Statistics& s = scene.tree.statistics;
  EXPECT_EQ(s.groups, 3u);
  EXPECT_EQ(s.singlePartGroups, 1u);
  EXPECT_EQ(s.largestGroup, 2u);
  EXPECT_EQ(s.mergedPolygons, 4 * scene.meshes[0].polygonCount());
  for (const View& view : viewsOf(scene, 12, 24, 6))
  {
    EXPECT_TRUE(orderIsCorrect(scene, view));
  }
}

TEST(PartOrder, TouchingPartsAreSeparatedAtTheirCommonPlane)
{
  // Unit cubes side by side sharing faces (a bolt on a plate): separable, no polygon split.
  std::vector<Polygon> cube;
  const double o = 0.0, l = 1.0;
  cube.push_back({ { o, o, o }, { o, l, o }, { l, l, o }, { l, o, o } });
  cube.push_back({ { o, o, l }, { l, o, l }, { l, l, l }, { o, l, l } });
  cube.push_back({ { o, o, o }, { l, o, o }, { l, o, l }, { o, o, l } });
  cube.push_back({ { o, l, o }, { o, l, l }, { l, l, l }, { l, l, o } });
  cube.push_back({ { o, o, o }, { o, o, l }, { o, l, l }, { o, l, o } });
  cube.push_back({ { l, o, o }, { l, l, o }, { l, l, l }, { l, o, l } });
  PartScene scene;
  scene.meshes.push_back(meshOf(cube));
  for (int i = 0; i < 4; ++i)
  {
    scene.parts.push_back(
      Part{ 0, glm::translate(glm::dmat4(1.0), glm::dvec3(i % 2, i / 2, 0.0)) });
  }
  scene.parts.push_back(Part{ 0, glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 1.0)) });
  scene.build();
  EXPECT_EQ(scene.tree.statistics.singlePartGroups, 5u);
  std::vector<View> views = viewsOf(scene, 13, 24, 6);
  // Eyes on the common faces and edges.
  for (const glm::dvec3& eye : { glm::dvec3(1.0, 0.5, 0.5), glm::dvec3(1.0, 1.0, 0.5),
         glm::dvec3(1.0, 1.0, 1.0), glm::dvec3(3.0, 1.0, 1.0), glm::dvec3(1.0, -2.0, 0.5) })
  {
    views.push_back(View::perspective(eye));
  }
  for (const View& view : views)
  {
    EXPECT_TRUE(orderIsCorrect(scene, view));
  }
}

TEST(PartOrder, RandomPlacementsOfRandomSoupsAreOrderedExactly)
{
  // Fuzz against the oracle: parts of random polygons (which intersect inside a part), placed
  // by random affine maps, mirrors included; some overlap, some touch, some stand apart.
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  for (int round = 0; round < 12; ++round)
  {
    PartScene scene;
    for (int m = 0; m < 3; ++m)
    {
      scene.meshes.push_back(meshOf(randomSoup(100 * round + m, 8 + 4 * m)));
    }
    const int count = 4 + round % 6;
    for (int i = 0; i < count; ++i)
    {
      glm::dmat4 linear(1.0);
      for (int c = 0; c < 3; ++c)
      {
        for (int r = 0; r < 3; ++r)
        {
          linear[c][r] = (c == r ? 1.0 : 0.0) + 0.4 * gauss(rng);
        }
      }
      const glm::dvec3 at(4.0 * unit(rng), 4.0 * unit(rng), 2.0 * unit(rng));
      scene.parts.push_back(
        Part{ static_cast<std::uint32_t>(i % 3), glm::translate(glm::dmat4(1.0), at) * linear });
    }
    scene.build();
    EXPECT_EQ(scene.tree.statistics.isolatedParts, 0u);
    for (const View& view : viewsOf(scene, 1000 + round, 10, 3))
    {
      EXPECT_TRUE(orderIsCorrect(scene, view)) << "round " << round;
    }
  }
}

TEST(PartOrder, APartMovedIntoAnotherJoinsItsGroup)
{
  PartScene scene;
  scene.meshes.push_back(uvSphere(120));
  scene.parts.push_back(Part{ 0, glm::dmat4(1.0) });
  scene.parts.push_back(Part{ 0, glm::translate(glm::dmat4(1.0), glm::dvec3(5, 0, 0)) });
  scene.build();
  EXPECT_EQ(scene.tree.statistics.singlePartGroups, 2u);
  const std::size_t meshFragments = scene.meshTrees[0].fragments.size();

  scene.parts[1].worldFromModel = glm::translate(glm::dmat4(1.0), glm::dvec3(1.5, 0, 0));
  std::vector<const PolygonMesh*> meshes{ &scene.meshes[0] };
  scene.tree = parts::build(meshes, scene.parts); // the mesh's own tree is kept
  EXPECT_EQ(scene.tree.statistics.groups, 1u);
  EXPECT_EQ(scene.tree.statistics.largestGroup, 2u);
  EXPECT_EQ(scene.meshTrees[0].fragments.size(), meshFragments);
  for (const View& view : viewsOf(scene, 14, 16, 4))
  {
    EXPECT_TRUE(orderIsCorrect(scene, view));
  }
}

TEST(PartOrder, GroupsDrawnInTheWrongOrderAreCaughtByTheOracle)
{
  // The test above could pass with any group order if the oracle saw nothing: swapping the two
  // groups of parts one behind the other must be reported.
  PartScene scene;
  scene.meshes.push_back(uvSphere(120));
  scene.parts.push_back(Part{ 0, glm::dmat4(1.0) });
  scene.parts.push_back(Part{ 0, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 3)) });
  scene.build();
  const View view = View::perspective({ 0.1, 0.2, 10.0 });
  std::vector<Piece> pieces;
  parts::order(scene.tree, scene.treePointers(), view, Direction::BackToFront, pieces);
  ASSERT_FALSE(pieces.empty());
  EXPECT_EQ(pieces.front().part, 0u) << "the part farther from the eye comes first";
  std::stable_partition(pieces.begin(), pieces.end(), [](const Piece& p) { return p.part == 1; });
  EXPECT_FALSE(scene.judge(pieces, view).ok());
}

TEST(PartOrder, BadPartsAreDrawnApartAndCountedNotLost)
{
  PartScene scene;
  scene.meshes.push_back(uvSphere(60));
  scene.meshes.push_back(PolygonMesh()); // no polygons
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scene.parts.push_back(Part{ 0, glm::dmat4(1.0) });
  scene.parts.push_back(Part{ 0, glm::translate(glm::dmat4(1.0), glm::dvec3(4, 0, 0)) });
  glm::dmat4 notFinite(1.0);
  notFinite[3][0] = nan;
  scene.parts.push_back(Part{ 0, notFinite });
  scene.parts.push_back(Part{ 0, glm::scale(glm::dmat4(1.0), glm::dvec3(0, 0, 1)) }); // a line
  scene.parts.push_back(Part{ 1, glm::dmat4(1.0) });
  glm::dmat4 projective(1.0);
  projective[0][3] = 0.5;
  scene.parts.push_back(Part{ 0, projective });

  // The mesh id out of range is built apart: the scene's helpers index meshes by it.
  std::vector<const PolygonMesh*> meshes{ &scene.meshes[0], &scene.meshes[1] };
  std::vector<Part> withBadMesh = scene.parts;
  withBadMesh.push_back(Part{ 7, glm::dmat4(1.0) });
  const parts::Tree bad = parts::build(meshes, withBadMesh);
  // Not finite, no vertex, no mesh: isolated. The line and the projective part are placed in
  // world coordinates and ordered with the sphere they overlap.
  EXPECT_EQ(bad.statistics.isolatedParts, 3u);
  EXPECT_EQ(bad.isolatedGroups, 3u);
  EXPECT_EQ(bad.statistics.worldFrameParts, 2u);
  EXPECT_EQ(bad.statistics.singlePartGroups, 1u);
  EXPECT_EQ(bad.statistics.largestGroup, 3u);
  EXPECT_TRUE(bad.shapes[bad.groups[2].shape].tree.empty()); // the missing mesh: nothing to draw

  scene.build();
  EXPECT_EQ(scene.tree.statistics.isolatedParts, 2u);
  const auto shapeOf = [&](std::uint32_t g) -> const bsp::Tree&
  { return scene.tree.shapes[scene.tree.groups[g].shape].tree; };
  // The not-finite part's polygons are refused by the builder; the line's are degenerate: both
  // counted there, none drawn.
  EXPECT_EQ(shapeOf(0).statistics.invalidPolygons, scene.meshes[0].polygonCount());
  EXPECT_TRUE(shapeOf(1).empty());
  std::size_t degenerate = 0;
  for (const parts::Shape& shape : scene.tree.shapes)
  {
    degenerate += shape.tree.statistics.degeneratePolygons;
  }
  EXPECT_GE(degenerate, scene.meshes[0].polygonCount());
  for (const View& view : viewsOf(scene, 15, 8, 2))
  {
    std::vector<std::uint32_t> groups;
    parts::groupOrder(scene.tree, view, Direction::BackToFront, groups);
    ASSERT_EQ(groups.size(), scene.tree.groups.size());
    EXPECT_EQ(groups[0], 0u);
    EXPECT_EQ(groups[1], 1u);
    if (std::isfinite(view.eye.x))
    {
      EXPECT_TRUE(orderIsCorrect(scene, view)); // what is drawn is still in order
    }
  }

  // No parts at all.
  const parts::Tree none = parts::build(meshes, {});
  EXPECT_TRUE(none.empty());
  std::vector<Piece> pieces{ Piece{ 1, 2, 3 } };
  parts::order(none, {}, View::perspective({ 0, 0, 1 }), Direction::BackToFront, pieces);
  EXPECT_TRUE(pieces.empty());
}

TEST(PartOrder, MovingOnePartRebuildsOnlyTheShapesOfTheGroupsItLeavesOrJoins)
{
  // Three pairs of interpenetrating spheres, far apart, each pair overlapping differently: three
  // groups of their own shapes.
  PartScene scene;
  scene.meshes.push_back(uvSphere(120));
  for (int pair = 0; pair < 3; ++pair)
  {
    scene.parts.push_back(Part{ 0, glm::translate(glm::dmat4(1.0), glm::dvec3(6.0 * pair, 0, 0)) });
    scene.parts.push_back(Part{
      0, glm::translate(glm::dmat4(1.0), glm::dvec3(6.0 * pair + 1.0 + 0.1 * pair, 0.2, 0)) });
  }
  scene.build();
  ASSERT_EQ(scene.tree.statistics.groups, 3u);
  ASSERT_EQ(scene.tree.statistics.shapes, 3u);

  // The second sphere of the last pair moves out of its partner: that group splits in two, the
  // other two shapes are taken as they were.
  scene.parts[5].worldFromModel = glm::translate(glm::dmat4(1.0), glm::dvec3(12.0, 5.0, 0.0));
  std::vector<const PolygonMesh*> meshes{ &scene.meshes[0] };
  const parts::Tree moved = parts::build(meshes, scene.parts, {}, &scene.tree);
  EXPECT_EQ(moved.statistics.groups, 4u);
  EXPECT_EQ(moved.statistics.shapes, 2u);
  EXPECT_EQ(moved.statistics.reusedShapes, 2u);
  EXPECT_EQ(moved.statistics.singlePartGroups, 2u);
  scene.tree = moved;
  for (const View& view : viewsOf(scene, 16, 12, 3))
  {
    EXPECT_TRUE(orderIsCorrect(scene, view));
  }

  // Nothing moved: every shape is reused.
  const parts::Tree same = parts::build(meshes, scene.parts, {}, &scene.tree);
  EXPECT_EQ(same.statistics.reusedShapes, 2u);
  EXPECT_EQ(same.statistics.mergedFragments, moved.statistics.mergedFragments);
}

TEST(PartOrder, CopiesOfASubAssemblyShareOneShape)
{
  // A sub-assembly of three interpenetrating parts (two meshes), placed four times: turned,
  // mirrored and moved far from the origin. One shape is built; every copy is ordered exactly
  // through it.
  PartScene scene;
  scene.meshes.push_back(uvSphere(120));
  scene.meshes.push_back(meshOf(randomSoup(5, 12)));
  const std::vector<Part> unit{ Part{ 0, glm::dmat4(1.0) },
    Part{ 1, placement({ 0.5, 0.0, 0.0 }, 0.3, { 0, 0, 1 }, glm::dvec3(1.5)) },
    Part{ 0, placement({ 0.0, 0.8, 0.3 }, 0.0, { 0, 0, 1 }, glm::dvec3(0.6)) } };
  const std::vector<glm::dmat4> copies{ glm::dmat4(1.0),
    placement({ 5, 0, 0 }, 1.0, { 0, 0, 1 }, glm::dvec3(1.0)),
    placement({ 0, 5, 1 }, 2.0, glm::normalize(glm::dvec3(1, 1, 0)), glm::dvec3(-1, 1, 1)),
    placement({ 1e4, 1e4, 0 }, 0.5, { 0, 1, 0 }, glm::dvec3(1.0)) };
  for (const glm::dmat4& copy : copies)
  {
    for (const Part& part : unit)
    {
      scene.parts.push_back(Part{ part.mesh, copy * part.worldFromModel });
    }
  }
  scene.build();
  EXPECT_EQ(scene.tree.statistics.groups, 4u);
  EXPECT_EQ(scene.tree.statistics.largestGroup, 3u);
  EXPECT_EQ(scene.tree.statistics.shapes, 1u);
  // Far from the origin the oracle's tolerances follow the coordinates; the near copies are
  // judged on their own.
  scene.parts.pop_back();
  scene.parts.pop_back();
  scene.parts.pop_back();
  scene.build();
  EXPECT_EQ(scene.tree.statistics.shapes, 1u);
  for (const View& view : viewsOf(scene, 17, 16, 4))
  {
    EXPECT_TRUE(orderIsCorrect(scene, view));
  }
}

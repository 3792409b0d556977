// libFuzzer target for the two-level order (PartTree.h, PartOrder.h): arbitrary bytes -> one to
// three small meshes (coordinates on a coarse grid, near-coincident values, now and then NaN or
// 1e30), two to eight parts placing them (grid translations, turns by multiples of 45 degrees,
// uneven scales, mirrors, a scale of 0, now and then a projective or non-finite matrix) and an
// eye (perspective, sometimes on a grid plane, or parallel). Checked, not just "no crash":
// - every fragment of every group's tree is drawn exactly once;
// - on conditioned input (every world coordinate finite and within 1e6) the brute-force order
//   oracle (OrderOracle.h) finds no violation in the world-space fragments, back to front, and
//   in front to back reversed.
// SCENEVIS_FUZZ_SELFTEST=1 reverses the group order, which the oracle must catch on some input
// (abort); SCENEVIS_FUZZ_VERBOSE=1 prints groups, shapes and fragments per input.
#include "scenevis/BspBuilder.h"
#include "scenevis/OrderOracle.h"
#include "scenevis/PartOrder.h"
#include "scenevis/PartTree.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <set>
#include <tuple>
#include <vector>

namespace
{
namespace bsp = scenevis::bsp;
namespace parts = scenevis::parts;

/// Reads bytes as small numbers; past the end, zeros.
struct Reader
{
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint8_t byte() { return at < size ? data[at++] : 0; }
  double coordinate()
  {
    const std::uint8_t kind = byte();
    const double grid = (static_cast<int>(byte()) - 128) / 32.0;
    switch (kind % 32)
    {
      case 0:
        return grid + (static_cast<int>(byte()) - 128) * 1e-9; // near-coincident
      case 1:
        return kind == 1 ? std::numeric_limits<double>::quiet_NaN() : grid;
      case 2:
        return kind == 2 ? 1e30 : grid;
      default:
        return grid;
    }
  }
};

glm::dmat4 placement(Reader& in)
{
  const std::uint8_t kind = in.byte();
  const glm::dvec3 at((static_cast<int>(in.byte()) - 128) / 16.0,
    (static_cast<int>(in.byte()) - 128) / 16.0, (static_cast<int>(in.byte()) - 128) / 32.0);
  const double angle = (in.byte() % 8) * 0.7853981633974483;
  static const glm::dvec3 axes[4] = { { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 1 } };
  glm::dvec3 scale(0.5 + in.byte() / 128.0, 0.5 + in.byte() / 128.0, 0.5 + in.byte() / 128.0);
  if (kind % 7 == 1)
  {
    scale.x = -scale.x; // mirror
  }
  if (kind % 31 == 2)
  {
    scale.y = 0.0; // flat: no model frame
  }
  glm::dmat4 m = glm::scale(
    glm::rotate(glm::translate(glm::dmat4(1.0), at), angle, glm::normalize(axes[kind % 4])), scale);
  if (kind == 3)
  {
    m[0][3] = 0.01; // projective
  }
  if (kind == 4)
  {
    m[3][1] = std::numeric_limits<double>::quiet_NaN();
  }
  return m;
}

bool conditioned(const scenevis::oracle::Polygon& polygon)
{
  for (const glm::dvec3& p : polygon)
  {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || std::abs(p.x) > 1e6 ||
      std::abs(p.y) > 1e6 || std::abs(p.z) > 1e6)
    {
      return false;
    }
  }
  return true;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Reader in{ data, size };
  std::vector<scenevis::PolygonMesh> meshes(1 + in.byte() % 3);
  for (scenevis::PolygonMesh& mesh : meshes)
  {
    const int points = 3 + in.byte() % 10;
    for (int i = 0; i < points; ++i)
    {
      mesh.addPoint({ in.coordinate(), in.coordinate(), in.coordinate() });
    }
    const int polygons = 1 + in.byte() % 8;
    for (int k = 0; k < polygons; ++k)
    {
      std::vector<std::uint32_t> ids(3 + in.byte() % 2);
      for (std::uint32_t& id : ids)
      {
        id = in.byte() % points;
      }
      mesh.addPolygon(ids.data(), ids.size());
    }
  }
  std::vector<parts::Part> placed(2 + in.byte() % 7);
  for (parts::Part& part : placed)
  {
    part.mesh = in.byte() % meshes.size();
    part.worldFromModel = placement(in);
  }
  const std::uint8_t viewKind = in.byte();
  glm::dvec3 eye(in.coordinate() * 4.0, in.coordinate() * 4.0, in.coordinate() * 4.0);
  if (viewKind % 4 == 1)
  {
    eye.z = 0.0; // on a grid plane: where separating planes and polygons lie
  }
  const scenevis::View view = viewKind % 4 == 2
    ? scenevis::View::parallel(glm::normalize(glm::dvec3(1.0, 0.3, -0.2) + eye * 0.01))
    : scenevis::View::perspective(eye);

  std::vector<const scenevis::PolygonMesh*> meshPointers;
  std::vector<bsp::Tree> trees;
  for (const scenevis::PolygonMesh& mesh : meshes)
  {
    meshPointers.push_back(&mesh);
    trees.push_back(bsp::build(mesh));
  }
  std::vector<const bsp::Tree*> treePointers;
  for (const bsp::Tree& tree : trees)
  {
    treePointers.push_back(&tree);
  }
  const parts::Tree tree = parts::build(meshPointers, placed);

  // Every fragment of every group's tree, exactly once.
  std::vector<parts::Piece> pieces;
  parts::order(tree, treePointers, view, bsp::Direction::BackToFront, pieces);
  std::size_t expected = 0;
  for (const parts::Group& g : tree.groups)
  {
    expected += g.single() ? trees[placed[g.parts.front()].mesh].fragments.size()
                           : tree.shapes[g.shape].tree.fragments.size();
  }
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> seen;
  for (const parts::Piece& p : pieces)
  {
    seen.insert({ p.group, p.part, p.fragment });
  }
  if (pieces.size() != expected || seen.size() != expected)
  {
    std::fprintf(stderr, "part order fuzz: %zu pieces (%zu distinct) for %zu fragments\n",
      pieces.size(), seen.size(), expected);
    std::abort();
  }
  if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z))
  {
    return 0;
  }

  // The oracle on the world-space fragments.
  std::vector<std::vector<scenevis::oracle::Polygon>> meshFragments;
  for (const bsp::Tree& t : trees)
  {
    meshFragments.push_back(scenevis::oracle::fragmentPolygons(t));
  }
  std::vector<std::vector<scenevis::oracle::Polygon>> shapeFragments;
  for (const parts::Shape& shape : tree.shapes)
  {
    shapeFragments.push_back(scenevis::oracle::fragmentPolygons(shape.tree));
  }
  const bool selftest = std::getenv("SCENEVIS_FUZZ_SELFTEST") != nullptr;
  for (const bsp::Direction direction :
    { bsp::Direction::BackToFront, bsp::Direction::FrontToBack })
  {
    parts::order(tree, treePointers, view, direction, pieces);
    if (direction == bsp::Direction::FrontToBack)
    {
      std::reverse(pieces.begin(), pieces.end());
    }
    if (selftest)
    {
      // Groups in reverse order, each group's own order kept.
      std::stable_sort(pieces.begin(), pieces.end(),
        [&](const parts::Piece& a, const parts::Piece& b) { return a.group > b.group; });
    }
    std::vector<scenevis::oracle::Polygon> polygons;
    for (const parts::Piece& p : pieces)
    {
      const parts::Group& g = tree.groups[p.group];
      scenevis::oracle::Polygon polygon = g.single()
        ? meshFragments[placed[p.part].mesh][p.fragment]
        : shapeFragments[g.shape][p.fragment];
      const glm::dmat4& m = g.single() ? placed[p.part].worldFromModel : g.worldFromShape;
      for (glm::dvec3& q : polygon)
      {
        q = glm::dvec3(m * glm::dvec4(q, 1.0));
      }
      if (!conditioned(polygon))
      {
        return 0; // outside the oracle's range: the sanitizers judge
      }
      polygons.push_back(std::move(polygon));
    }
    std::vector<std::uint32_t> identity(polygons.size());
    for (std::uint32_t i = 0; i < identity.size(); ++i)
    {
      identity[i] = i;
    }
    const auto report = scenevis::oracle::checkOrder(polygons, identity, view);
    if (!report.ok() && report.conflictingPairs == 0)
    {
      const auto& v = report.violations.front();
      std::fprintf(stderr,
        "part order fuzz: %zu violation(s) %s; first: part %u (group %u) farther than part %u "
        "(group %u); %zu groups, %zu shapes\n",
        report.violations.size(),
        direction == bsp::Direction::BackToFront ? "back to front" : "front to back",
        pieces[v.farther].part, pieces[v.farther].group, pieces[v.nearer].part,
        pieces[v.nearer].group, tree.groups.size(), tree.shapes.size());
      std::abort();
    }
  }
  if (std::getenv("SCENEVIS_FUZZ_VERBOSE"))
  {
    std::fprintf(stderr, "part order fuzz: %zu parts, %zu groups, %zu shapes, %zu fragments\n",
      placed.size(), tree.groups.size(), tree.shapes.size(), expected);
  }
  return 0;
}

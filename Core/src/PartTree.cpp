// The top level of the two-level order: separating planes between placed parts (PartTree.h).
#include "scenevis/PartTree.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

namespace scenevis
{
namespace parts
{
namespace
{

/// The axes, the face diagonals and the body diagonals (unit length): the k-DOP of each part.
constexpr int kDirections = 13;

const std::array<glm::dvec3, kDirections>& directions()
{
  static const std::array<glm::dvec3, kDirections> d = []
  {
    const std::array<glm::dvec3, kDirections> raw{ { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 },
      { 1, 1, 0 }, { 1, -1, 0 }, { 1, 0, 1 }, { 1, 0, -1 }, { 0, 1, 1 }, { 0, 1, -1 }, { 1, 1, 1 },
      { 1, 1, -1 }, { 1, -1, 1 }, { -1, 1, 1 } } };
    std::array<glm::dvec3, kDirections> unit{};
    for (int i = 0; i < kDirections; ++i)
    {
      unit[i] = glm::normalize(raw[i]);
    }
    return unit;
  }();
  return d;
}

struct Extent
{
  std::array<double, kDirections> lo;
  std::array<double, kDirections> hi;
};

bool finite(const glm::dmat4& m)
{
  for (int c = 0; c < 4; ++c)
  {
    for (int r = 0; r < 4; ++r)
    {
      if (!std::isfinite(m[c][r]))
      {
        return false;
      }
    }
  }
  return true;
}

/// @p p placed by @p m, divided by w when @p m is projective (not finite when w is 0).
glm::dvec3 toWorld(const glm::dmat4& m, const glm::dvec3& p)
{
  const glm::dvec4 w = m * glm::dvec4(p, 1.0);
  return w.w == 1.0 ? glm::dvec3(w) : glm::dvec3(w) / w.w;
}

/// An affine matrix (bottom row 0 0 0 1) whose linear part is far from singular, and its inverse.
bool invertibleAffine(const glm::dmat4& m, glm::dmat4& inverse)
{
  if (!finite(m) || m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
  {
    return false;
  }
  const glm::dmat3 linear(m);
  const double scale =
    std::max({ glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2]) });
  if (!(scale > 0.0) || std::abs(glm::determinant(linear)) <= 1e-12 * scale * scale * scale)
  {
    return false;
  }
  inverse = glm::inverse(m);
  return finite(inverse);
}

/// The ids of the finite points a mesh's polygons use, each once.
std::vector<std::uint32_t> usedPoints(const PolygonMesh& mesh)
{
  std::vector<char> used(mesh.points.size(), 0);
  for (const std::uint32_t id : mesh.indices)
  {
    if (id < used.size())
    {
      used[id] = 1;
    }
  }
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < used.size(); ++i)
  {
    const glm::dvec3& p = mesh.points[i];
    if (used[i] && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
    {
      ids.push_back(i);
    }
  }
  return ids;
}

/// A plane with parts [0, split) of `set` (sorted by `direction`'s lo) behind and the rest in
/// front, or split == 0 when there is none.
struct Separation
{
  int direction = 0;
  std::size_t split = 0;
  double offset = 0.0;
};

Separation separate(
  std::vector<std::uint32_t>& set, const std::vector<Extent>& extents, std::vector<std::uint32_t>& scratch)
{
  Separation best;
  std::size_t bestImbalance = std::numeric_limits<std::size_t>::max();
  const std::size_t m = set.size();
  scratch = set;
  for (int d = 0; d < kDirections; ++d)
  {
    std::sort(scratch.begin(), scratch.end(),
      [&](std::uint32_t a, std::uint32_t b) {
        return extents[a].lo[d] < extents[b].lo[d] ||
          (extents[a].lo[d] == extents[b].lo[d] && a < b);
      });
    double farthest = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k + 1 < m; ++k)
    {
      farthest = std::max(farthest, extents[scratch[k]].hi[d]);
      const double next = extents[scratch[k + 1]].lo[d];
      // Parts at the gap may overlap by the rounding of the compared values (file comment).
      const double tolerance = 64.0 * DBL_EPSILON * std::max(std::abs(farthest), std::abs(next));
      const std::size_t imbalance = 2 * (k + 1) > m ? 2 * (k + 1) - m : m - 2 * (k + 1);
      if (farthest <= next + tolerance && imbalance < bestImbalance)
      {
        bestImbalance = imbalance;
        best.direction = d;
        best.split = k + 1;
        best.offset = 0.5 * (farthest + next);
      }
    }
    if (best.split && best.direction == d)
    {
      set = scratch; // keep this direction's sort: the split refers to it
    }
    if (bestImbalance <= 1)
    {
      break; // as balanced as it gets
    }
  }
  return best;
}

/// Relative matrices equal up to rounding (see PartTree.h).
bool sameMatrix(const glm::dmat4& a, const glm::dmat4& b)
{
  for (int c = 0; c < 4; ++c)
  {
    for (int r = 0; r < 4; ++r)
    {
      if (std::abs(a[c][r] - b[c][r]) > 1e-12 * (1.0 + std::abs(a[c][r]) + std::abs(b[c][r])))
      {
        return false;
      }
    }
  }
  return true;
}

/// The members' meshes and relative matrices of a group of valid parts.
void shapeKey(const Group& group, const std::vector<Part>& parts, Shape& key)
{
  key.memberMeshes.clear();
  key.memberMatrices.clear();
  for (const std::uint32_t p : group.parts)
  {
    key.memberMeshes.push_back(parts[p].mesh);
    key.memberMatrices.push_back(group.shapeFromWorld * parts[p].worldFromModel);
  }
}

/// The shape among `candidates` (indices into `shapes`) made of the same members as `key`.
std::uint32_t findShape(
  const std::vector<Shape>& shapes, const std::vector<std::uint32_t>& candidates, const Shape& key)
{
  for (const std::uint32_t s : candidates)
  {
    const Shape& shape = shapes[s];
    bool same = shape.memberMeshes == key.memberMeshes;
    for (std::size_t i = 0; same && i < key.memberMatrices.size(); ++i)
    {
      same = sameMatrix(shape.memberMatrices[i], key.memberMatrices[i]);
    }
    if (same)
    {
      return s;
    }
  }
  return bsp::kNone;
}

/// Builds the tree of `shape` over `group`'s polygons placed by `shapeFrom` (per member).
void buildShape(Shape& shape, const Group& group, const std::vector<Part>& parts,
  const std::vector<const PolygonMesh*>& meshes, const std::vector<glm::dmat4>& shapeFrom,
  const bsp::BuildConfig& config)
{
  PolygonMesh mesh;
  std::vector<std::uint32_t> ids;
  for (std::uint32_t member = 0; member < group.parts.size(); ++member)
  {
    const Part& part = parts[group.parts[member]];
    if (part.mesh >= meshes.size() || !meshes[part.mesh])
    {
      continue;
    }
    const PolygonMesh& source = *meshes[part.mesh];
    const auto base = static_cast<std::uint32_t>(mesh.points.size());
    for (const glm::dvec3& q : source.points)
    {
      mesh.points.push_back(toWorld(shapeFrom[member], q)); // the matrix may be projective
    }
    for (std::uint32_t i = 0; i < source.polygonCount(); ++i)
    {
      ids.assign(source.polygon(i), source.polygon(i) + source.polygonSize(i));
      for (std::uint32_t& id : ids)
      {
        // An out-of-range id stays out of range, for the builder to drop and count.
        id = id < source.points.size() ? id + base : std::numeric_limits<std::uint32_t>::max();
      }
      mesh.addPolygon(ids.data(), ids.size());
      shape.polygonMember.push_back(member);
      shape.polygonSource.push_back(i);
    }
  }
  shape.tree = bsp::build(mesh, config);
}

} // namespace

Tree build(const std::vector<const PolygonMesh*>& meshes, const std::vector<Part>& parts,
  const BuildConfig& config, const Tree* previous)
{
  const auto start = std::chrono::steady_clock::now();
  Tree tree;
  tree.parts = parts;
  const std::size_t n = parts.size();
  tree.modelFromWorld.assign(n, glm::dmat4(1.0));
  tree.statistics.parts = n;

  // Each part's k-DOP in world coordinates.
  std::vector<std::vector<std::uint32_t>> used(meshes.size());
  std::vector<char> usedKnown(meshes.size(), 0);
  std::vector<Extent> extents(n);
  std::vector<char> valid(n, 0);
  std::vector<char> affine(n, 0); // has a model frame: an invertible affine matrix
  for (std::size_t i = 0; i < n; ++i)
  {
    const Part& part = parts[i];
    if (part.mesh >= meshes.size() || !meshes[part.mesh] || !finite(part.worldFromModel))
    {
      continue;
    }
    affine[i] = invertibleAffine(part.worldFromModel, tree.modelFromWorld[i]) ? 1 : 0;
    if (!affine[i])
    {
      tree.modelFromWorld[i] = glm::dmat4(1.0);
    }
    if (!usedKnown[part.mesh])
    {
      used[part.mesh] = usedPoints(*meshes[part.mesh]);
      usedKnown[part.mesh] = 1;
    }
    Extent& e = extents[i];
    e.lo.fill(std::numeric_limits<double>::infinity());
    e.hi.fill(-std::numeric_limits<double>::infinity());
    bool any = false;
    for (const std::uint32_t id : used[part.mesh])
    {
      const glm::dvec3 w = toWorld(part.worldFromModel, meshes[part.mesh]->points[id]);
      if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
      {
        continue;
      }
      any = true;
      for (int d = 0; d < kDirections; ++d)
      {
        const double s = glm::dot(directions()[d], w);
        e.lo[d] = std::min(e.lo[d], s);
        e.hi[d] = std::max(e.hi[d], s);
      }
    }
    valid[i] = any ? 1 : 0;
    if (!any)
    {
      tree.modelFromWorld[i] = glm::dmat4(1.0);
      affine[i] = 0;
    }
    tree.statistics.worldFrameParts += valid[i] && !affine[i] ? 1 : 0;
  }

  // Isolated parts first: a group each (see the file comment).
  for (std::uint32_t i = 0; i < n; ++i)
  {
    if (!valid[i])
    {
      Group g;
      g.parts.push_back(i);
      tree.groups.push_back(std::move(g));
      ++tree.statistics.isolatedParts;
    }
  }
  tree.isolatedGroups = static_cast<std::uint32_t>(tree.groups.size());

  // The top level, built with an explicit stack of part sets.
  struct Work
  {
    std::vector<std::uint32_t> set;
    std::uint32_t node;
    std::size_t depth;
  };
  std::vector<Work> stack;
  std::vector<std::uint32_t> all;
  for (std::uint32_t i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      all.push_back(i);
    }
  }
  if (!all.empty())
  {
    tree.root = 0;
    tree.nodes.emplace_back();
    stack.push_back(Work{ std::move(all), 0, 1 });
  }
  std::vector<std::uint32_t> scratch;
  while (!stack.empty())
  {
    Work w = std::move(stack.back());
    stack.pop_back();
    tree.statistics.depth = std::max(tree.statistics.depth, w.depth);
    const Separation s =
      w.set.size() > 1 ? separate(w.set, extents, scratch) : Separation{};
    if (s.split == 0)
    {
      std::sort(w.set.begin(), w.set.end());
      tree.nodes[w.node].group = static_cast<std::uint32_t>(tree.groups.size());
      Group g;
      g.parts = std::move(w.set);
      tree.groups.push_back(std::move(g));
      continue;
    }
    const auto back = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.nodes.emplace_back();
    Node& node = tree.nodes[w.node];
    node.plane = glm::dvec4(directions()[s.direction], -s.offset);
    node.back = back;
    node.front = back + 1;
    ++tree.statistics.separatingPlanes;
    std::vector<std::uint32_t> behind(w.set.begin(), w.set.begin() + s.split);
    w.set.erase(w.set.begin(), w.set.begin() + s.split);
    stack.push_back(Work{ std::move(w.set), back + 1, w.depth + 1 });
    stack.push_back(Work{ std::move(behind), back, w.depth + 1 });
  }

  // Shapes: one tree over the polygons of each group of several parts (and of each isolated
  // part), shared by the groups made of the same meshes in the same relative placement, and
  // taken from `previous` when it has one.
  std::map<std::vector<std::uint32_t>, std::vector<std::uint32_t>> built, before;
  if (previous)
  {
    for (std::uint32_t s = 0; s < previous->shapes.size(); ++s)
    {
      if (!previous->shapes[s].memberMeshes.empty())
      {
        before[previous->shapes[s].memberMeshes].push_back(s);
      }
    }
  }
  Shape key;
  for (std::uint32_t g = 0; g < tree.groups.size(); ++g)
  {
    Group& group = tree.groups[g];
    const bool isolated = g < tree.isolatedGroups;
    if (group.parts.size() == 1 && !isolated && affine[group.parts.front()])
    {
      ++tree.statistics.singlePartGroups;
      continue;
    }
    std::vector<glm::dmat4> shapeFrom;
    if (isolated)
    {
      shapeFrom.push_back(parts[group.parts.front()].worldFromModel);
    }
    else
    {
      // The frame: the first member's model coordinates, or the world's when no member has an
      // invertible affine matrix.
      const auto framed = std::find_if(
        group.parts.begin(), group.parts.end(), [&](std::uint32_t p) { return affine[p] != 0; });
      if (framed != group.parts.end())
      {
        group.worldFromShape = parts[*framed].worldFromModel;
        group.shapeFromWorld = tree.modelFromWorld[*framed];
      }
      shapeKey(group, parts, key);
      shapeFrom = key.memberMatrices;
      std::uint32_t found = findShape(tree.shapes, built[key.memberMeshes], key);
      if (found == bsp::kNone && previous)
      {
        const std::uint32_t old = findShape(previous->shapes, before[key.memberMeshes], key);
        if (old != bsp::kNone)
        {
          found = static_cast<std::uint32_t>(tree.shapes.size());
          tree.shapes.push_back(previous->shapes[old]);
          built[key.memberMeshes].push_back(found);
          ++tree.statistics.reusedShapes;
        }
      }
      if (found != bsp::kNone)
      {
        group.shape = found;
        tree.statistics.mergedPolygons += tree.shapes[found].polygonMember.size();
        tree.statistics.mergedFragments += tree.shapes[found].tree.fragments.size();
        continue;
      }
    }
    group.shape = static_cast<std::uint32_t>(tree.shapes.size());
    tree.shapes.emplace_back();
    Shape& shape = tree.shapes.back();
    buildShape(shape, group, parts, meshes, shapeFrom, config.shapeConfig);
    if (!isolated)
    {
      shape.memberMeshes = key.memberMeshes;
      shape.memberMatrices = key.memberMatrices;
      built[key.memberMeshes].push_back(group.shape);
    }
    tree.statistics.mergedPolygons += shape.polygonMember.size();
    tree.statistics.mergedFragments += shape.tree.fragments.size();
  }
  tree.statistics.shapes = tree.shapes.size();
  tree.statistics.groups = tree.groups.size();
  for (const Group& g : tree.groups)
  {
    tree.statistics.largestGroup = std::max(tree.statistics.largestGroup, g.parts.size());
  }
  tree.statistics.buildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tree;
}

} // namespace parts
} // namespace scenevis

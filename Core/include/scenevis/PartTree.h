#pragma once
/**
 * @file PartTree.h
 * @brief Two-level visibility order: placed parts ordered as wholes, polygons split only where
 *        parts cannot be separated.
 *
 * A scene of many parts (CAD assemblies, instanced models) ordered by one BSP over all its
 * polygons splits polygons of one part by the planes of others, although most parts never
 * overlap. Here the order has two levels:
 * - Top: a tree over the parts whose every plane has each part entirely on one side of it (a
 *   part never straddles a top-level plane, so no polygon is split there). For any eye the far
 *   side's parts come before the near side's: a ray from the eye that meets both sides meets the
 *   far side last (the two sides are convex half-spaces), so nothing on the far side can cover
 *   anything on the near side.
 * - Leaves ("groups"): parts that no plane separates. A group of one part is ordered by that
 *   part's own BSP (bsp::Tree of its mesh, in the mesh's own coordinates: built once per
 *   distinct mesh, shared by its instances and kept when the part moves). A group of several
 *   parts gets one BSP over their polygons (a Shape), split only among themselves, in the first
 *   part's model coordinates; groups that are copies of one sub-assembly (the same meshes in the
 *   same relative placement, up to a relative 1e-12 per matrix entry) share it.
 *
 * Separating planes. Each part is summarised by the interval [lo, hi] of dot(direction, p) over
 * its polygons' world vertices for a fixed set of directions (the 3 axes, the 6 face diagonals
 * and the 4 body diagonals: a 26-sided discrete-orientation polytope around the part). For each
 * direction the parts are swept in increasing lo; wherever the largest hi so far does not pass
 * the next lo (by more than the tolerance), the plane halfway between separates the parts seen so
 * far from the rest. The most balanced such plane over all directions splits the set; a set that
 * has none becomes a group. Touching parts (a bolt on a plate) are separable: a polygon of each
 * on the common plane is coplanar, which constrains no order.
 *
 * The top level does not depend on the leaves' trees, so moving a part rebuilds the top level
 * (13 sorts of the parts per level) and the shapes of the groups it leaves or joins (see
 * `previous` below); the parts' own trees never.
 *
 * Tolerance: two parts at a gap count as touching when they overlap along the direction by no
 * more than the rounding of the compared values, 64 * DBL_EPSILON * (the larger magnitude of the
 * two interval ends). Not more: a tolerance relative to the parts' or the scene's size let one
 * huge part (1e30) close gaps between ordinary parts (found by the fuzzer). Parts that touch
 * only up to a coarser noise stay together, in one group: slower, never wrong.
 *
 * Matrices that are finite but not an invertible affine map (a scale of 0 flattens a part, a
 * projective matrix divides by w) give a part no model frame: it is separated like any other,
 * but ordered by a shape in world coordinates (Statistics::worldFrameParts). Bad input: a part
 * whose mesh id is out of range, whose matrix is not finite, or that has no finite vertex is not
 * separated from anything: it is drawn through a group of its own whose shape is in world
 * coordinates (the BSP builder drops and counts degenerate or non-finite polygons), placed
 * before every other group, and counted in Statistics::isolatedParts.
 */

#include "scenevis/BspBuilder.h"
#include "scenevis/BspTree.h"
#include "scenevis/PolygonMesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace parts
{

/// A placed part: mesh `mesh` (an index into the caller's meshes) drawn with `worldFromModel`
/// (an affine matrix; mirrors allowed).
struct Part
{
  std::uint32_t mesh = 0;
  glm::dmat4 worldFromModel{ 1.0 };
};

/// One top-level partition, or a leaf (`group != bsp::kNone`). For inner nodes `plane` = (n, d):
/// every part of the `front` subtree has dot(n, p) + d >= -tolerance at all its vertices, every
/// part of `back` <= +tolerance (the tolerance of the two parts at the gap, see the file comment).
struct Node
{
  glm::dvec4 plane{ 0.0 };
  std::uint32_t front = bsp::kNone;
  std::uint32_t back = bsp::kNone;
  std::uint32_t group = bsp::kNone;
};

/**
 * A BSP over the polygons of several parts, in the model coordinates of the first of them. Groups
 * of the same meshes in the same relative placement (copies of one sub-assembly) share one shape.
 */
struct Shape
{
  bsp::Tree tree;
  /// Per input polygon of `tree`: the position in Group::parts of its part, and its polygon id
  /// in that part's mesh (fragment `source` indexes these).
  std::vector<std::uint32_t> polygonMember;
  std::vector<std::uint32_t> polygonSource;
  /// What the shape is made of: per member, its mesh and its matrix relative to the first
  /// member (shapeFromWorld * worldFromModel). Empty for an isolated part's shape (never shared).
  std::vector<std::uint32_t> memberMeshes;
  std::vector<glm::dmat4> memberMatrices;
};

/// Parts that no plane separates.
struct Group
{
  std::vector<std::uint32_t> parts; ///< Ascending part ids.
  /// bsp::kNone: the group's one part is ordered by its mesh's own tree. Otherwise (two or more
  /// parts, or one without a model frame or isolated) the index of its Shape in Tree::shapes.
  std::uint32_t shape = bsp::kNone;
  /// The shape's coordinates: those of the first part's model that has a frame (the identity
  /// when none has, and for an isolated part: then the shape is in world coordinates).
  glm::dmat4 worldFromShape{ 1.0 };
  glm::dmat4 shapeFromWorld{ 1.0 };

  bool single() const { return shape == bsp::kNone; }
};

struct Statistics
{
  std::size_t parts = 0;
  std::size_t groups = 0;
  std::size_t singlePartGroups = 0;
  std::size_t largestGroup = 0;     ///< Parts in the largest group.
  std::size_t isolatedParts = 0;    ///< Bad input parts (see the file comment).
  std::size_t worldFrameParts = 0;  ///< Valid parts without a model frame (file comment).
  std::size_t separatingPlanes = 0; ///< Inner nodes.
  std::size_t depth = 0;            ///< Longest root-to-leaf path, in nodes.
  std::size_t shapes = 0;           ///< Distinct shapes of the groups of several parts.
  std::size_t mergedPolygons = 0;   ///< Input polygons of the shapes.
  std::size_t mergedFragments = 0;  ///< Fragments drawn for the groups with a shape (a shared
                                    ///< shape counts once per group).
  std::size_t reusedShapes = 0;     ///< Shapes taken from the previous tree, not built.
  double buildSeconds = 0.0;
};

struct Tree
{
  std::vector<Part> parts;
  std::vector<glm::dmat4> modelFromWorld; ///< Per part (identity for parts without a frame).
  std::vector<Node> nodes;
  std::vector<Group> groups; ///< The isolated parts' groups first, then the leaves'.
  std::vector<Shape> shapes;
  std::uint32_t isolatedGroups = 0; ///< How many groups come first, before every view's order.
  std::uint32_t root = bsp::kNone;  ///< kNone when no part is valid.
  Statistics statistics;

  bool empty() const { return groups.empty(); }
};

struct BuildConfig
{
  /// For the shapes' trees.
  bsp::BuildConfig shapeConfig;
};

/**
 * The top level and the shapes for `parts` placed from `meshes` (model coordinates; only
 * the vertices of their polygons count). The meshes' own trees are the caller's (bsp::build once
 * per mesh); they are needed only to order single-part groups (PartOrder.h).
 *
 * `previous`: the tree of the same meshes and config before some parts moved. A shape of the
 * same meshes in the same relative placement is taken from there instead of being built again
 * (Statistics::reusedShapes), so moving a part costs the top level plus the shapes of the
 * groups it leaves or joins.
 */
Tree build(const std::vector<const PolygonMesh*>& meshes, const std::vector<Part>& parts,
  const BuildConfig& config = {}, const Tree* previous = nullptr);

} // namespace parts
} // namespace scenevis

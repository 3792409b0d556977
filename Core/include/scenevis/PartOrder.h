#pragma once
/**
 * @file PartOrder.h
 * @brief Visibility order of a parts::Tree (PartTree.h) for a view.
 *
 * The top level is walked like a BSP (far side, then near side; an eye on a plane counts as in
 * front, where either order is valid because no ray from it meets both sides' interiors). Each
 * group is then ordered by its own tree with the view in that tree's coordinates (an invertible
 * affine map keeps every point on the same side of every plane, mirrors included): a
 * single-part group by its mesh's tree in the part's model coordinates, a group of several by
 * its shape's tree. A renderer draws the groups one after the other in groupOrder() and keeps
 * one bsp::IncrementalOrder per group; a part's fragments are never interleaved with another's
 * except inside a group of several.
 */

#include "scenevis/BspTraversal.h"
#include "scenevis/PartTree.h"
#include "scenevis/View.h"

#include <cstdint>
#include <vector>

namespace scenevis
{
namespace parts
{

/// The groups in drawing order (each once).
void groupOrder(
  const Tree& tree, const View& view, bsp::Direction direction, std::vector<std::uint32_t>& groups);

/// `view` in the model coordinates of part `part` (what its mesh's tree is ordered with).
View modelView(const Tree& tree, std::uint32_t part, const View& view);

/// One drawn fragment: `fragment` of the part's mesh tree when its group is single(), else of
/// the group's shape (drawn with Group::worldFromShape; Shape::polygonSource names the polygon).
struct Piece
{
  std::uint32_t group;
  std::uint32_t part;
  std::uint32_t fragment;
};

/**
 * The complete order as one list: the groups in groupOrder(), each expanded by its own tree (for
 * tests and callers that want one list; a renderer orders each group into its own buffer and
 * saves the expansion, about a third of the time on a million fragments). `meshTrees[m]`
 * is the tree of mesh m (in its model coordinates) and must exist for every mesh a single-part
 * group uses.
 */
void order(const Tree& tree, const std::vector<const bsp::Tree*>& meshTrees, const View& view,
  bsp::Direction direction, std::vector<Piece>& pieces);

} // namespace parts
} // namespace scenevis

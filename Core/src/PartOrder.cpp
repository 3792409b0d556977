// Walks the two-level order of PartTree.h (see PartOrder.h).
#include "scenevis/PartOrder.h"

#include <glm/geometric.hpp>

namespace scenevis
{
namespace parts
{

void groupOrder(
  const Tree& tree, const View& view, bsp::Direction direction, std::vector<std::uint32_t>& groups)
{
  groups.clear();
  groups.reserve(tree.groups.size());
  const bool backToFront = direction == bsp::Direction::BackToFront;
  // The isolated parts' groups come before everything else in drawing order.
  if (backToFront)
  {
    for (std::uint32_t g = 0; g < tree.isolatedGroups; ++g)
    {
      groups.push_back(g);
    }
  }
  if (tree.root != bsp::kNone)
  {
    std::vector<std::uint32_t> stack{ tree.root };
    while (!stack.empty())
    {
      const Node& node = tree.nodes[stack.back()];
      stack.pop_back();
      if (node.group != bsp::kNone)
      {
        groups.push_back(node.group);
        continue;
      }
      // The eye in front (or on the plane): the back side is the far one.
      const bool eyeInFront = glm::dot(node.plane, view.eye) >= 0.0;
      const std::uint32_t farSide = eyeInFront ? node.back : node.front;
      const std::uint32_t nearSide = eyeInFront ? node.front : node.back;
      // The side to emit first is pushed last.
      stack.push_back(backToFront ? nearSide : farSide);
      stack.push_back(backToFront ? farSide : nearSide);
    }
  }
  if (!backToFront)
  {
    for (std::uint32_t g = tree.isolatedGroups; g-- > 0;)
    {
      groups.push_back(g);
    }
  }
}

View modelView(const Tree& tree, std::uint32_t part, const View& view)
{
  return View{ tree.modelFromWorld[part] * view.eye };
}

void order(const Tree& tree, const std::vector<const bsp::Tree*>& meshTrees, const View& view,
  bsp::Direction direction, std::vector<Piece>& pieces)
{
  pieces.clear();
  std::vector<std::uint32_t> groups;
  groupOrder(tree, view, direction, groups);
  std::vector<std::uint32_t> fragments;
  for (const std::uint32_t g : groups)
  {
    const Group& group = tree.groups[g];
    if (group.single())
    {
      const std::uint32_t part = group.parts.front();
      bsp::order(
        *meshTrees[tree.parts[part].mesh], modelView(tree, part, view), direction, fragments);
      for (const std::uint32_t f : fragments)
      {
        pieces.push_back(Piece{ g, part, f });
      }
      continue;
    }
    const Shape& shape = tree.shapes[group.shape];
    bsp::order(shape.tree, View{ group.shapeFromWorld * view.eye }, direction, fragments);
    for (const std::uint32_t f : fragments)
    {
      const std::uint32_t member = shape.polygonMember[shape.tree.fragments[f].source];
      pieces.push_back(Piece{ g, group.parts[member], f });
    }
  }
}

} // namespace parts
} // namespace scenevis

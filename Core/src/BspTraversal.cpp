#include "scenevis/BspTraversal.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scenevis
{
namespace bsp
{
namespace
{

/// Both traversals decide sides with this one expression, so update() can never disagree with
/// order() on an eye that lies (numerically) on a plane.
bool viewerInFront(const glm::dvec4& plane, const glm::dvec4& eye)
{
  return plane.x * eye.x + plane.y * eye.y + plane.z * eye.z + plane.w * eye.w >= 0.0;
}

constexpr std::uint32_t kEmitOwn = 0x80000000u;
constexpr std::uint32_t kFrontBit = 0x80000000u;
constexpr std::uint32_t kAnchorMask = 0x7fffffffu;

/// After this many distinct eyes the anchors are compacted by a full walk (amortised over as many
/// updates, so negligible), keeping Anchors small.
constexpr std::size_t kMaxAnchors = 1024;

/// The safe radius is |dot(P, E)| for unit P, E; this margin absorbs the rounding of that dot
/// product and of the normalisations, so a skipped plane's exact side test cannot have changed.
constexpr double kRadiusMargin = 1e-9;

float roundDown(double r)
{
  if (!(r > 0.0))
  {
    return 0.0f;
  }
  float f = static_cast<float>(r);
  if (static_cast<double>(f) > r)
  {
    f = std::nextafter(f, 0.0f);
  }
  return f;
}

} // namespace

void order(const Tree& tree, const View& view, Direction direction, std::vector<std::uint32_t>& out)
{
  out.resize(tree.fragments.size());
  if (tree.empty())
  {
    return;
  }
  const glm::dvec4 eye = view.relativeTo(tree.origin).eye;
  const bool backToFront = direction == Direction::BackToFront;
  std::vector<std::uint32_t> stack;
  stack.reserve(64);
  stack.push_back(tree.root);
  std::uint32_t* write = out.data();
  while (!stack.empty())
  {
    const std::uint32_t item = stack.back();
    stack.pop_back();
    if (item & kEmitOwn)
    {
      const Node& node = tree.nodes[item & ~kEmitOwn];
      if (backToFront)
      {
        for (std::uint32_t k = 0; k < node.fragmentCount; ++k)
        {
          *write++ = node.firstFragment + k;
        }
      }
      else
      {
        for (std::uint32_t k = node.fragmentCount; k > 0; --k)
        {
          *write++ = node.firstFragment + k - 1;
        }
      }
      continue;
    }
    const Node& node = tree.nodes[item];
    const bool inFront = viewerInFront(node.plane, eye);
    const std::uint32_t nearChild = inFront ? node.front : node.back;
    const std::uint32_t farChild = inFront ? node.back : node.front;
    const std::uint32_t first = backToFront ? farChild : nearChild;
    const std::uint32_t second = backToFront ? nearChild : farChild;
    // Pushed in reverse: the stack pops `first` next.
    if (second != kNone)
    {
      stack.push_back(second);
    }
    if (node.fragmentCount > 0)
    {
      stack.push_back(item | kEmitOwn);
    }
    if (first != kNone)
    {
      stack.push_back(first);
    }
  }
}

IncrementalOrder::IncrementalOrder(const Tree& tree, Direction direction)
  : TreePtr(&tree)
  , Dir(direction)
{
  Box box;
  for (const glm::dvec3& p : tree.points)
  {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
    {
      box.extend(p);
    }
  }
  Scale = box.diagonal() > 0.0 ? box.diagonal() : 1.0;
  States.assign(tree.nodes.size(), NodeState{ 0, 0, 0, 0.0f });
  Order.resize(tree.fragments.size());
  if (tree.empty())
  {
    return;
  }
  // Subtree sizes, children before parents: reverse of an iterative pre-order.
  std::vector<std::uint32_t> preorder;
  preorder.reserve(tree.nodes.size());
  std::vector<std::uint32_t> stack{ tree.root };
  while (!stack.empty())
  {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    preorder.push_back(n);
    const Node& node = tree.nodes[n];
    if (node.front != kNone)
    {
      stack.push_back(node.front);
    }
    if (node.back != kNone)
    {
      stack.push_back(node.back);
    }
  }
  for (auto it = preorder.rbegin(); it != preorder.rend(); ++it)
  {
    const Node& node = tree.nodes[*it];
    std::uint32_t size = node.fragmentCount;
    size += node.front != kNone ? States[node.front].size : 0;
    size += node.back != kNone ? States[node.back].size : 0;
    States[*it].size = size;
  }
}

const IncrementalOrder::UpdateStatistics& IncrementalOrder::update(const View& view)
{
  Last = UpdateStatistics{};
  const bool full = !Initialized || Anchors.size() >= kMaxAnchors;
  if (full)
  {
    Anchors.clear();
  }
  if (!TreePtr->empty())
  {
    walk(view, full);
  }
  Initialized = true;
  return Last;
}

void IncrementalOrder::walk(const View& view, bool full)
{
  const Tree& tree = *TreePtr;
  const glm::dvec4 eyeRaw = view.relativeTo(tree.origin).eye;
  glm::dvec4 eye(glm::dvec3(eyeRaw) / Scale, eyeRaw.w);
  const double eyeLength = glm::length(eye);
  eye = eyeLength > 0.0 ? eye / eyeLength : glm::dvec4(0.0);
  const auto anchorIndex = static_cast<std::uint32_t>(Anchors.size());
  Anchors.push_back(eye);
  const bool backToFront = Dir == Direction::BackToFront;

  Stack.clear();
  Stack.push_back(Frame{ tree.root, 0, kNone, false, 0.0 });
  while (!Stack.empty())
  {
    const auto frameIndex = static_cast<std::uint32_t>(Stack.size() - 1);
    const Frame frame = Stack.back();
    NodeState& state = States[frame.node];
    if (frame.expanded)
    {
      // Post-order: every child has lowered frame.radius to what it can guarantee around `eye`.
      state.radius = roundDown(frame.radius);
      state.anchor = (state.anchor & kFrontBit) | anchorIndex;
      Stack.pop_back();
      if (frame.parentFrame != kNone)
      {
        double& r = Stack[frame.parentFrame].radius;
        r = std::min(r, frame.radius);
      }
      continue;
    }
    if (!full)
    {
      const double distance = glm::length(eye - Anchors[state.anchor & kAnchorMask]);
      if (distance < static_cast<double>(state.radius))
      {
        // No plane of this subtree can have changed side; its ball, shrunk by the distance
        // moved, is still a safe ball around the new eye.
        Stack.pop_back();
        if (frame.parentFrame != kNone)
        {
          double& r = Stack[frame.parentFrame].radius;
          r = std::min(r, static_cast<double>(state.radius) - distance);
        }
        continue;
      }
    }

    ++Last.nodesVisited;
    const Node& node = tree.nodes[frame.node];
    const bool inFront = viewerInFront(node.plane, eyeRaw);
    const std::uint32_t nearChild = inFront ? node.front : node.back;
    const std::uint32_t farChild = inFront ? node.back : node.front;
    const std::uint32_t first = backToFront ? farChild : nearChild;
    const std::uint32_t second = backToFront ? nearChild : farChild;
    const std::uint32_t firstSize = first != kNone ? States[first].size : 0;
    const std::uint32_t own = node.fragmentCount;
    if (full)
    {
      std::uint32_t* write = Order.data() + frame.start + firstSize;
      for (std::uint32_t k = 0; k < own; ++k)
      {
        write[k] = backToFront ? node.firstFragment + k : node.firstFragment + own - 1 - k;
      }
    }
    else if (((state.anchor & kFrontBit) != 0) != inFront)
    {
      // Range is [second][own][first] from the last layout; make it [first][own][second].
      const std::uint32_t secondSize = second != kNone ? States[second].size : 0;
      const auto begin = Order.begin() + frame.start;
      std::rotate(begin, begin + secondSize, begin + state.size);
      std::rotate(begin, begin + own, begin + own + firstSize);
      ++Last.nodesFlipped;
      Last.fragmentsMoved += state.size;
    }
    if (first != kNone)
    {
      States[first].offset = 0;
    }
    if (second != kNone)
    {
      States[second].offset = firstSize + own;
    }
    state.anchor = (inFront ? kFrontBit : 0u) | (state.anchor & kAnchorMask);

    // Distance from the eye to this plane in the normalised homogeneous space.
    const glm::dvec4 p(glm::dvec3(node.plane), node.plane.w / Scale);
    const double radius = std::abs(glm::dot(p, eye)) / glm::length(p) - kRadiusMargin;
    Stack[frameIndex].expanded = true;
    Stack[frameIndex].radius = radius;
    if (second != kNone)
    {
      Stack.push_back(Frame{ second, frame.start + States[second].offset, frameIndex, false, 0.0 });
    }
    if (first != kNone)
    {
      Stack.push_back(Frame{ first, frame.start, frameIndex, false, 0.0 });
    }
  }
}

std::size_t IncrementalOrder::memoryBytes() const
{
  return Order.capacity() * sizeof(std::uint32_t) + States.capacity() * sizeof(NodeState) +
    Anchors.capacity() * sizeof(glm::dvec4) + Stack.capacity() * sizeof(Frame);
}

} // namespace bsp
} // namespace scenevis

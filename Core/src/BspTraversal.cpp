#include "scenevis/BspTraversal.h"

#include "BspSide.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace scenevis
{
namespace bsp
{
namespace
{

using detail::sideValue;

bool viewerInFront(const glm::dvec4& plane, const glm::dvec4& eye)
{
  return sideValue(plane.x, plane.y, plane.z, plane.w, eye.x, eye.y, eye.z, eye.w) >= 0.0;
}

constexpr std::uint32_t kEmitOwn = 0x80000000u;
static_assert((kEmitOwn & kLeafBit) == 0, "stack tags must differ");

/// Longest run of single-child nodes grouped into one unit of IncrementalOrder: long enough to
/// cover the leaf chains of the scored builder (<= 128) whole, short enough that a unit's safe
/// ball still localises the planes near the eye on a FirstInList chain.
constexpr std::uint32_t kMaxUnitNodes = 256;

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

void order(const Tree& tree, const View& view, Direction direction, std::vector<std::uint32_t>& out,
  OrderStatistics* statistics)
{
  out.resize(tree.fragments.size());
  OrderStatistics counts;
  if (tree.empty())
  {
    if (statistics)
    {
      *statistics = counts;
    }
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
    if (isLeaf(item))
    {
      const OrderedLeaf& leaf = tree.leaves[item & ~kLeafBit];
      if (orderLeaf(tree, leaf, eye, write))
      {
        for (std::uint32_t k = 0; k < leaf.fragmentCount; ++k)
        {
          write[k] += leaf.firstFragment;
        }
        if (!backToFront)
        {
          std::reverse(write, write + leaf.fragmentCount);
        }
        write += leaf.fragmentCount;
        ++counts.leavesSorted;
      }
      else if (leaf.fallback != kNone)
      {
        stack.push_back(leaf.fallback);
        ++counts.leavesFallenBack;
      }
      // else unreachable: a leaf without fallback has a forest of pairs, which cannot stall.
      continue;
    }
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
  out.resize(static_cast<std::size_t>(write - out.data()));
  if (statistics)
  {
    *statistics = counts;
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
  if (!tree.leaves.empty())
  {
    throw std::invalid_argument("IncrementalOrder: trees with ordered leaves are not supported");
  }
  Order.resize(tree.fragments.size());
  if (tree.empty())
  {
    return;
  }
  const std::size_t nodeCount = tree.nodes.size();
  PlaneX.reserve(nodeCount);
  PlaneY.reserve(nodeCount);
  PlaneZ.reserve(nodeCount);
  PlaneW.reserve(nodeCount);
  InvNorm.reserve(nodeCount);
  OwnFirst.reserve(nodeCount);
  OwnCount.reserve(nodeCount);
  ChildMask.reserve(nodeCount);
  Side.assign(nodeCount, 0);
  const bool backToFront = direction == Direction::BackToFront;

  // Units in pre-order (parents before children), each unit's nodes consecutive in chain order.
  struct Pending
  {
    std::uint32_t node;
    std::uint32_t parentUnit;
    bool isFront;
  };
  std::vector<Pending> stack{ Pending{ tree.root, kNone, false } };
  while (!stack.empty())
  {
    const Pending item = stack.back();
    stack.pop_back();
    const auto unitIndex = static_cast<std::uint32_t>(Units.size());
    Unit unit{};
    unit.firstNode = static_cast<std::uint32_t>(PlaneX.size());
    unit.front = unit.back = kNone;
    if (item.parentUnit != kNone)
    {
      (item.isFront ? Units[item.parentUnit].front : Units[item.parentUnit].back) = unitIndex;
    }
    std::uint32_t n = item.node;
    for (;;)
    {
      const Node& node = tree.nodes[n];
      const glm::dvec4 p(glm::dvec3(node.plane), node.plane.w / Scale);
      const double length = glm::length(p);
      PlaneX.push_back(node.plane.x);
      PlaneY.push_back(node.plane.y);
      PlaneZ.push_back(node.plane.z);
      PlaneW.push_back(node.plane.w);
      InvNorm.push_back(length > 0.0 ? 1.0 / (Scale * length) : 0.0);
      OwnFirst.push_back(node.firstFragment);
      OwnCount.push_back(node.fragmentCount);
      ++unit.nodeCount;
      const bool single = (node.front == kNone) != (node.back == kNone);
      // Back-to-front puts the far child first: the front child when the viewer is behind.
      ChildMask.push_back(static_cast<std::uint8_t>((node.front != kNone) == backToFront));
      if (!single || unit.nodeCount >= kMaxUnitNodes)
      {
        // Tail: its children start units of their own (back pushed first: front is done first).
        if (node.back != kNone)
        {
          stack.push_back(Pending{ node.back, unitIndex, false });
        }
        if (node.front != kNone)
        {
          stack.push_back(Pending{ node.front, unitIndex, true });
        }
        break;
      }
      n = node.front != kNone ? node.front : node.back;
    }
    Units.push_back(unit);
  }
  // Subtree sizes: children come after their parents.
  for (auto it = Units.rbegin(); it != Units.rend(); ++it)
  {
    std::uint32_t size = 0;
    for (std::uint32_t i = it->firstNode; i < it->firstNode + it->nodeCount; ++i)
    {
      size += OwnCount[i];
    }
    size += it->front != kNone ? Units[it->front].size : 0;
    size += it->back != kNone ? Units[it->back].size : 0;
    it->size = size;
  }
  Units.shrink_to_fit();
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

void IncrementalOrder::layout(Unit& unit, std::uint32_t start, bool full,
  bool tailFlipped, std::uint32_t oldTailStart)
{
  const bool backToFront = Dir == Direction::BackToFront;
  const std::uint32_t b = unit.firstNode;
  const std::uint32_t tail = b + unit.nodeCount - 1;
  std::uint32_t* out = Order.data();
  auto emitOwn = [&](std::uint32_t i, std::uint32_t at)
  {
    const std::uint32_t first = OwnFirst[i];
    const std::uint32_t count = OwnCount[i];
    std::uint32_t* write = out + at;
    if (backToFront)
    {
      for (std::uint32_t k = 0; k < count; ++k)
      {
        write[k] = first + k;
      }
    }
    else
    {
      for (std::uint32_t k = 0; k < count; ++k)
      {
        write[k] = first + count - 1 - k;
      }
    }
  };
  // Chain nodes whose child goes second are emitted before the tail in chain order; those whose
  // child goes first come after it, innermost first.
  std::uint32_t tailStart = 0;
  for (std::uint32_t i = b; i < tail; ++i)
  {
    tailStart += (Side[i] ^ ChildMask[i]) ? 0u : OwnCount[i];
  }
  const bool inFront = Side[tail] != 0;
  const std::uint32_t nearChild = inFront ? unit.front : unit.back;
  const std::uint32_t farChild = inFront ? unit.back : unit.front;
  const std::uint32_t first = backToFront ? farChild : nearChild;
  const std::uint32_t second = backToFront ? nearChild : farChild;
  const std::uint32_t firstSize = first != kNone ? Units[first].size : 0;
  const std::uint32_t secondSize = second != kNone ? Units[second].size : 0;
  const std::uint32_t tailOwn = OwnCount[tail];
  const std::uint32_t tailAt = start + tailStart;
  if (!full && firstSize + secondSize > 0 && (tailFlipped || tailStart != oldTailStart))
  {
    // The children's ranges keep their contents but move: park them, then put them back.
    // Before this update the tail range was [second][own][first] if the tail flipped, else
    // [first][own][second].
    const std::uint32_t oldBase = start + oldTailStart;
    const std::uint32_t oldFirstAt = tailFlipped ? oldBase + secondSize + tailOwn : oldBase;
    const std::uint32_t oldSecondAt = tailFlipped ? oldBase : oldBase + firstSize + tailOwn;
    MoveScratch.resize(firstSize + secondSize);
    std::copy(out + oldFirstAt, out + oldFirstAt + firstSize, MoveScratch.data());
    std::copy(out + oldSecondAt, out + oldSecondAt + secondSize, MoveScratch.data() + firstSize);
    std::copy(MoveScratch.data(), MoveScratch.data() + firstSize, out + tailAt);
    std::copy(MoveScratch.data() + firstSize, MoveScratch.data() + firstSize + secondSize,
      out + tailAt + firstSize + tailOwn);
    Last.fragmentsMoved += firstSize + secondSize;
  }
  std::uint32_t pos = start;
  for (std::uint32_t i = b; i < tail; ++i)
  {
    if (!(Side[i] ^ ChildMask[i]))
    {
      emitOwn(i, pos);
      pos += OwnCount[i];
    }
  }
  emitOwn(tail, pos + firstSize);
  pos += firstSize + tailOwn + secondSize;
  for (std::uint32_t i = tail; i-- > b;)
  {
    if (Side[i] ^ ChildMask[i])
    {
      emitOwn(i, pos);
      pos += OwnCount[i];
    }
  }
  Last.fragmentsMoved += unit.size - firstSize - secondSize;
  unit.tailStart = tailStart;
}

void IncrementalOrder::walk(const View& view, bool full)
{
  const glm::dvec4 eyeRaw = view.relativeTo(TreePtr->origin).eye;
  glm::dvec4 eye(glm::dvec3(eyeRaw) / Scale, eyeRaw.w);
  const double eyeLength = glm::length(eye);
  eye = eyeLength > 0.0 ? eye / eyeLength : glm::dvec4(0.0);
  // Distance to a plane in normalised eye space = |side value| * InvNorm * eyeScale.
  const double eyeScale = eyeLength > 0.0 ? 1.0 / eyeLength : 0.0;
  const auto anchorIndex = static_cast<std::uint32_t>(Anchors.size());
  Anchors.push_back(eye);
  const bool backToFront = Dir == Direction::BackToFront;
  const double ex = eyeRaw.x;
  const double ey = eyeRaw.y;
  const double ez = eyeRaw.z;
  const double ew = eyeRaw.w;

  Stack.clear();
  Stack.push_back(Frame{ 0, 0, kNone, false, 0.0 });
  while (!Stack.empty())
  {
    const auto frameIndex = static_cast<std::uint32_t>(Stack.size() - 1);
    const Frame frame = Stack.back();
    Unit& unit = Units[frame.unit];
    if (frame.expanded)
    {
      // Post-order: every child has lowered frame.radius to what it can guarantee around `eye`.
      unit.radius = roundDown(frame.radius);
      unit.anchor = anchorIndex;
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
      const double distance = glm::length(eye - Anchors[unit.anchor]);
      if (distance < static_cast<double>(unit.radius))
      {
        // No plane of this subtree can have changed side; its ball, shrunk by the distance
        // moved, is still a safe ball around the new eye.
        Stack.pop_back();
        if (frame.parentFrame != kNone)
        {
          double& r = Stack[frame.parentFrame].radius;
          r = std::min(r, static_cast<double>(unit.radius) - distance);
        }
        continue;
      }
    }

    // Evaluate every plane of the unit: new sides, crossings, nearest plane.
    const std::uint32_t b = unit.firstNode;
    const std::uint32_t e = b + unit.nodeCount;
    const std::uint32_t tail = e - 1;
    const std::uint8_t oldTailSide = Side[tail];
    double nearest = std::numeric_limits<double>::infinity();
    std::uint32_t flips = 0;
    {
      const double* px = PlaneX.data();
      const double* py = PlaneY.data();
      const double* pz = PlaneZ.data();
      const double* pw = PlaneW.data();
      const double* inv = InvNorm.data();
      std::uint8_t* side = Side.data();
      for (std::uint32_t i = b; i < e; ++i)
      {
        const double s = sideValue(px[i], py[i], pz[i], pw[i], ex, ey, ez, ew);
        const std::uint8_t f = s >= 0.0 ? 1 : 0;
        flips += f ^ side[i];
        side[i] = f;
        nearest = std::min(nearest, std::abs(s) * inv[i]);
      }
    }
    Last.nodesVisited += unit.nodeCount;
    Last.nodesFlipped += flips;
    if (full || flips > 0)
    {
      layout(unit, frame.start, full, Side[tail] != oldTailSide, unit.tailStart);
    }

    const bool inFront = Side[tail] != 0;
    const std::uint32_t nearChild = inFront ? unit.front : unit.back;
    const std::uint32_t farChild = inFront ? unit.back : unit.front;
    const std::uint32_t first = backToFront ? farChild : nearChild;
    const std::uint32_t second = backToFront ? nearChild : farChild;
    const std::uint32_t firstSize = first != kNone ? Units[first].size : 0;
    const std::uint32_t tailStart = frame.start + unit.tailStart;

    Stack[frameIndex].expanded = true;
    Stack[frameIndex].radius = nearest * eyeScale - kRadiusMargin;
    if (second != kNone)
    {
      Stack.push_back(
        Frame{ second, tailStart + firstSize + OwnCount[tail], frameIndex, false, 0.0 });
    }
    if (first != kNone)
    {
      Stack.push_back(Frame{ first, tailStart, frameIndex, false, 0.0 });
    }
  }
}

std::size_t IncrementalOrder::memoryBytes() const
{
  return Order.capacity() * sizeof(std::uint32_t) + Units.capacity() * sizeof(Unit) +
    (PlaneX.capacity() + PlaneY.capacity() + PlaneZ.capacity() + PlaneW.capacity() +
      InvNorm.capacity()) * sizeof(double) +
    (OwnFirst.capacity() + OwnCount.capacity()) * sizeof(std::uint32_t) + Side.capacity() +
    ChildMask.capacity() + MoveScratch.capacity() * sizeof(std::uint32_t) +
    Anchors.capacity() * sizeof(glm::dvec4) + Stack.capacity() * sizeof(Frame);
}

} // namespace bsp
} // namespace scenevis

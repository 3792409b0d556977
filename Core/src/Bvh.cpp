#include "scenevis/Bvh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace scenevis
{
namespace culling
{

namespace
{
bool finiteBox(const Box& b)
{
  for (int k = 0; k < 3; ++k)
  {
    if (!std::isfinite(b.lo[k]) || !std::isfinite(b.hi[k]))
    {
      return false;
    }
  }
  return !b.empty();
}

constexpr int kBins = 16;
} // namespace

double halfArea(const glm::dvec3& lo, const glm::dvec3& hi)
{
  const glm::dvec3 d = glm::max(hi - lo, glm::dvec3(0.0));
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

// ----------------------------------------------------------------------------------------------
// Build
// ----------------------------------------------------------------------------------------------

void Bvh::build(const BoxArrays& boxes,
  BuildMethod method,
  unsigned leafSize,
  const std::vector<std::uint32_t>* triangles)
{
  const std::size_t n = boxes.size();
  method_ = method;
  leafSize_ = std::max(1u, leafSize);
  nodes_.clear();
  nodeCones_.clear();
  dirtyLeaves_.clear();

  // Valid boxes first (they go into the tree), always-visible ones after them; a stable order so
  // the build is deterministic.
  std::vector<std::uint32_t> ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  std::vector<std::uint8_t> valid(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    valid[i] = finiteBox(boxes.get(i)) ? 1 : 0;
  }
  const auto split = std::stable_partition(
    ids.begin(), ids.end(), [&valid](std::uint32_t i) { return valid[i] != 0; });
  const auto treeCount = static_cast<std::uint32_t>(split - ids.begin());

  centroid_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    centroid_[i] = boxes.get(i).center();
  }
  id_ = ids;
  treeCount_ = treeCount;
  buildBoxes_ = &boxes;
  if (treeCount > 0)
  {
    nodes_.reserve(2 * static_cast<std::size_t>(treeCount));
    buildRange(0, treeCount, 0);
  }
  buildBoxes_ = nullptr;

  position_.assign(n, 0);
  leafOf_.assign(n, 0);
  boxes_.resize(n);
  always_.assign(n, 0);
  cones_.assign(n, NormalCone::none());
  triangles_.assign(n, 0);
  for (std::uint32_t p = 0; p < n; ++p)
  {
    const std::uint32_t id = id_[p];
    position_[id] = p;
    boxes_.set(p, boxes.get(id));
    always_[p] = p >= treeCount ? 1 : 0;
    if (triangles && id < triangles->size())
    {
      triangles_[p] = (*triangles)[id];
    }
  }
  for (std::uint32_t ni = 0; ni < nodes_.size(); ++ni)
  {
    const Node& node = nodes_[ni];
    if (node.isLeaf())
    {
      for (std::uint32_t p = node.first; p < node.first + node.count; ++p)
      {
        leafOf_[p] = ni;
      }
    }
  }
  nodeCones_.assign(nodes_.size(), NormalCone::none());
  nodeHint_.assign(nodes_.size(), 0);
  objectHint_.assign(n, 0);
  leafDirty_.assign(nodes_.size(), 0);
  // Children have larger indices than their parent: one reverse sweep fits every node.
  for (std::size_t ni = nodes_.size(); ni-- > 0;)
  {
    computeNodeBounds(static_cast<std::uint32_t>(ni));
  }
  builtArea_ = totalArea();
  centroid_.clear();
  centroid_.shrink_to_fit();
}

std::uint32_t Bvh::buildRange(std::uint32_t begin, std::uint32_t end, std::uint32_t parent)
{
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  // Node boxes are computed bottom-up after the build (computeNodeBounds); here only the
  // centroid bounds, which choose the split axis.
  Box centroids;
  for (std::uint32_t p = begin; p < end; ++p)
  {
    centroids.extend(centroid_[id_[p]]);
  }
  Node node;
  node.parent = parent;
  node.objects = end - begin;
  node.begin = begin;
  const std::uint32_t count = end - begin;
  if (count <= leafSize_)
  {
    node.first = begin;
    node.count = count;
    nodes_[index] = node;
    return index;
  }
  const glm::dvec3 extent = centroids.hi - centroids.lo;
  int axis = 0;
  if (extent.y > extent[axis])
  {
    axis = 1;
  }
  if (extent.z > extent[axis])
  {
    axis = 2;
  }
  std::uint32_t mid = begin + count / 2;
  auto key = [this, axis](std::uint32_t id) { return centroid_[id][axis]; };
  bool done = false;
  if (method_ == BuildMethod::BinnedSah && extent[axis] > 0.0)
  {
    // SAH over kBins bins of the centroid range: cost = sum over both sides of
    // (half area of the side's box) x (objects on that side).
    std::array<Box, kBins> binBox;
    std::array<std::uint32_t, kBins> binCount{};
    const double scale = kBins / extent[axis];
    auto binOf = [&](std::uint32_t id)
    {
      const int b = static_cast<int>((key(id) - centroids.lo[axis]) * scale);
      return std::clamp(b, 0, kBins - 1);
    };
    for (std::uint32_t p = begin; p < end; ++p)
    {
      const std::uint32_t id = id_[p];
      const int b = binOf(id);
      binBox[b].extend(buildBoxes_->get(id));
      ++binCount[b];
    }
    std::array<double, kBins> rightCost{};
    Box acc;
    std::uint32_t accCount = 0;
    for (int b = kBins - 1; b > 0; --b)
    {
      acc.extend(binBox[b]);
      accCount += binCount[b];
      rightCost[b] = accCount ? halfArea(acc.lo, acc.hi) * accCount : 0.0;
    }
    acc = Box();
    accCount = 0;
    double best = std::numeric_limits<double>::infinity();
    int bestSplit = -1;
    for (int b = 0; b < kBins - 1; ++b)
    {
      acc.extend(binBox[b]);
      accCount += binCount[b];
      if (accCount == 0 || accCount == count)
      {
        continue;
      }
      const double cost = halfArea(acc.lo, acc.hi) * accCount + rightCost[b + 1];
      if (cost < best)
      {
        best = cost;
        bestSplit = b;
      }
    }
    if (bestSplit >= 0)
    {
      const auto it = std::partition(id_.begin() + begin, id_.begin() + end,
        [&](std::uint32_t id) { return binOf(id) <= bestSplit; });
      mid = static_cast<std::uint32_t>(it - id_.begin());
      done = mid > begin && mid < end;
    }
  }
  if (!done)
  {
    mid = begin + count / 2;
    std::nth_element(id_.begin() + begin, id_.begin() + mid, id_.begin() + end,
      [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  }
  nodes_[index] = node;
  buildRange(begin, mid, index);
  const std::uint32_t right = buildRange(mid, end, index);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

void Bvh::computeNodeBounds(std::uint32_t ni)
{
  Node& node = nodes_[ni];
  if (node.isLeaf())
  {
    glm::dvec3 lo(std::numeric_limits<double>::infinity());
    glm::dvec3 hi(-std::numeric_limits<double>::infinity());
    NormalCone cone = cones_[node.first];
    for (std::uint32_t p = node.first; p < node.first + node.count; ++p)
    {
      lo = glm::min(lo, glm::dvec3(boxes_.minX[p], boxes_.minY[p], boxes_.minZ[p]));
      hi = glm::max(hi, glm::dvec3(boxes_.maxX[p], boxes_.maxY[p], boxes_.maxZ[p]));
      if (p != node.first)
      {
        cone = merge(cone, cones_[p]);
      }
    }
    node.lo = lo;
    node.hi = hi;
    nodeCones_[ni] = cone;
  }
  else
  {
    const Node& a = nodes_[ni + 1];
    const Node& b = nodes_[node.first];
    node.lo = glm::min(a.lo, b.lo);
    node.hi = glm::max(a.hi, b.hi);
    nodeCones_[ni] = merge(nodeCones_[ni + 1], nodeCones_[node.first]);
  }
}

double Bvh::totalArea() const
{
  double sum = 0.0;
  for (const Node& node : nodes_)
  {
    sum += halfArea(node.lo, node.hi);
  }
  return sum;
}

double Bvh::degradation() const
{
  return builtArea_ > 0.0 ? totalArea() / builtArea_ : 1.0;
}

// ----------------------------------------------------------------------------------------------
// Incremental update
// ----------------------------------------------------------------------------------------------

Box Bvh::objectBox(std::uint32_t id) const
{
  return boxes_.get(position_[id]);
}

void Bvh::update(std::uint32_t id, const Box& box)
{
  const std::uint32_t p = position_[id];
  if (!finiteBox(box))
  {
    always_[p] = 1;
    return;
  }
  if (p >= treeCount_)
  {
    // Not in the tree (it had no valid box at build time): stays always visible until rebuilt.
    return;
  }
  always_[p] = 0;
  boxes_.set(p, box);
  const std::uint32_t leaf = leafOf_[p];
  if (!leafDirty_[leaf])
  {
    leafDirty_[leaf] = 1;
    dirtyLeaves_.push_back(leaf);
  }
}

void Bvh::setNormalCone(std::uint32_t id, const NormalCone& cone)
{
  const std::uint32_t p = position_[id];
  cones_[p] = cone;
  if (p < treeCount_)
  {
    const std::uint32_t leaf = leafOf_[p];
    if (!leafDirty_[leaf])
    {
      leafDirty_[leaf] = 1;
      dirtyLeaves_.push_back(leaf);
    }
  }
}

void Bvh::setTriangleCount(std::uint32_t id, std::uint32_t triangles)
{
  triangles_[position_[id]] = triangles;
}

std::size_t Bvh::refit()
{
  std::size_t recomputed = 0;
  for (const std::uint32_t leaf : dirtyLeaves_)
  {
    leafDirty_[leaf] = 0;
    std::uint32_t ni = leaf;
    while (true)
    {
      const Node before = nodes_[ni];
      const NormalCone coneBefore = nodeCones_[ni];
      computeNodeBounds(ni);
      ++recomputed;
      const Node& after = nodes_[ni];
      const bool same = before.lo == after.lo && before.hi == after.hi &&
        coneBefore.axis == nodeCones_[ni].axis &&
        coneBefore.sinHalfAngle == nodeCones_[ni].sinHalfAngle;
      // Ancestors only depend on this node through its box and cone.
      if ((same && ni != leaf) || ni == 0)
      {
        break;
      }
      ni = nodes_[ni].parent;
    }
  }
  dirtyLeaves_.clear();
  return recomputed;
}

// ----------------------------------------------------------------------------------------------
// Cull
// ----------------------------------------------------------------------------------------------

struct Bvh::Frame
{
  const CullParams& params;
  std::vector<std::uint32_t>& visible;
  CullStats& stats;
  bool contribution;
  bool nodeContribution;
  bool distance;
  double maxDistance2;
  bool cones;
};

namespace
{
inline double nearestDistance2(const glm::dvec3& eye, const glm::dvec3& lo, const glm::dvec3& hi)
{
  const glm::dvec3 d = glm::max(glm::max(lo - eye, eye - hi), glm::dvec3(0.0));
  return glm::dot(d, d);
}

/// Whether a sphere (c, r) projects to less than minPixels (approximate; see CullParams).
inline bool tooSmall(const CullParams& p, const glm::dvec3& c, double r, double slack)
{
  if (p.parallel)
  {
    return 2.0 * r * p.pixelsPerUnit < p.minPixels;
  }
  // slack = r for a node: its objects' centres can be up to r nearer than its own centre.
  const double depth = glm::dot(c - p.eye, p.viewDirection) - slack;
  return depth > r && 2.0 * r * p.pixelsPerUnit < p.minPixels * depth;
}
} // namespace

Bvh::Frame Bvh::makeFrame(
  const CullParams& params, std::vector<std::uint32_t>& visible, CullStats& stats) const
{
  Frame frame{ params, visible, stats, false, false, false, 0.0, false };
  frame.contribution = params.minPixels > 0.0 && params.pixelsPerUnit > 0.0 &&
    std::isfinite(params.pixelsPerUnit);
  // A node is culled for size only if every object below it would be: an object's radius is at
  // most the node's and its centre at most the node's radius nearer (tooSmall's slack).
  frame.nodeContribution = frame.contribution;
  frame.distance = params.maxDistance < std::numeric_limits<double>::infinity();
  frame.maxDistance2 = params.maxDistance * params.maxDistance;
  frame.cones = params.normalConeCulling;
  return frame;
}

void Bvh::appendAlwaysVisible(std::vector<std::uint32_t>& visible, CullStats& stats) const
{
  // Objects without a valid box are always drawn.
  for (std::uint32_t p = 0; p < id_.size(); ++p)
  {
    if (always_[p])
    {
      visible.push_back(id_[p]);
      ++stats.objectsDrawn;
      stats.trianglesDrawn += triangles_[p];
    }
  }
}

void Bvh::cull(const CullParams& params, std::vector<std::uint32_t>& visible, CullStats* stats)
{
  visible.clear();
  CullStats local;
  Frame frame = makeFrame(params, visible, local);
  if (!nodes_.empty())
  {
    cullNode(frame, 0, params.frustumCulling ? kAllPlanes : 0);
  }
  appendAlwaysVisible(visible, local);
  if (stats)
  {
    *stats = local;
  }
}

bool Bvh::nodePasses(Frame& f, std::uint32_t ni, std::uint8_t& mask) const
{
  const Node& node = nodes_[ni];
  return boxPasses(f, ni, node.lo, node.hi, node.objects, mask);
}

bool Bvh::boxPasses(Frame& f, std::uint32_t ni, const glm::dvec3& lo, const glm::dvec3& hi,
  std::uint32_t objects, std::uint8_t& mask) const
{
  const CullParams& params = f.params;
  ++f.stats.nodesVisited;
  if (mask && !testBoxMasked(params.frustum, lo, hi, mask, nodeHint_[ni]))
  {
    f.stats.culledFrustum += objects;
    return false;
  }
  if (f.distance && nearestDistance2(params.eye, lo, hi) > f.maxDistance2)
  {
    f.stats.culledDistance += objects;
    return false;
  }
  const glm::dvec3 center = (lo + hi) * 0.5;
  const double radius = 0.5 * glm::length(hi - lo);
  if (f.nodeContribution && tooSmall(params, center, radius, radius))
  {
    f.stats.culledContribution += objects;
    return false;
  }
  // The node's cone holds the normals of all its objects, so of any of them inside [lo, hi].
  if (f.cones && nodeCones_[ni].canCull() &&
    (params.parallel ? backFacingAlong(nodeCones_[ni], params.viewDirection)
                     : backFacingFromEye(nodeCones_[ni], center, radius, params.eye)))
  {
    f.stats.culledNormalCone += objects;
    return false;
  }
  return true;
}

bool Bvh::objectPasses(Frame& f, std::uint32_t p, std::uint8_t mask) const
{
  const CullParams& params = f.params;
  ++f.stats.objectsTested;
  const glm::dvec3 lo(boxes_.minX[p], boxes_.minY[p], boxes_.minZ[p]);
  const glm::dvec3 hi(boxes_.maxX[p], boxes_.maxY[p], boxes_.maxZ[p]);
  if (mask && !testBoxMasked(params.frustum, lo, hi, mask, objectHint_[p]))
  {
    ++f.stats.culledFrustum;
    return false;
  }
  if (f.distance && nearestDistance2(params.eye, lo, hi) > f.maxDistance2)
  {
    ++f.stats.culledDistance;
    return false;
  }
  const glm::dvec3 c = (lo + hi) * 0.5;
  const double r = 0.5 * glm::length(hi - lo);
  if (f.contribution && tooSmall(params, c, r, 0.0))
  {
    ++f.stats.culledContribution;
    return false;
  }
  if (f.cones && cones_[p].canCull() &&
    (params.parallel ? backFacingAlong(cones_[p], params.viewDirection)
                     : backFacingFromEye(cones_[p], c, r, params.eye)))
  {
    ++f.stats.culledNormalCone;
    return false;
  }
  return true;
}

void Bvh::cullNode(Frame& f, std::uint32_t ni, std::uint8_t mask) const
{
  if (!nodePasses(f, ni, mask))
  {
    return;
  }
  const Node& node = nodes_[ni];
  if (mask == 0 && !f.distance && !f.contribution && !f.cones)
  {
    // Fully inside the frustum and nothing else to test: the whole subtree is visible, and its
    // objects are contiguous in tree order.
    for (std::uint32_t p = node.begin; p < node.begin + node.objects; ++p)
    {
      if (!always_[p])
      {
        f.visible.push_back(id_[p]);
        ++f.stats.objectsDrawn;
        f.stats.trianglesDrawn += triangles_[p];
      }
    }
    return;
  }
  if (!node.isLeaf())
  {
    cullNode(f, ni + 1, mask);
    cullNode(f, node.first, mask);
    return;
  }
  for (std::uint32_t p = node.first; p < node.first + node.count; ++p)
  {
    if (always_[p])
    {
      continue; // reported after the traversal
    }
    if (objectPasses(f, p, mask))
    {
      f.visible.push_back(id_[p]);
      ++f.stats.objectsDrawn;
      f.stats.trianglesDrawn += triangles_[p];
    }
  }
}

// ----------------------------------------------------------------------------------------------
// Cull with occlusion
// ----------------------------------------------------------------------------------------------

namespace
{
/// A node or an object position waiting in cullOccluded()'s heap.
struct HeapEntry
{
  double nearness;
  std::uint32_t index;
  std::uint8_t mask;
  bool object;
  /// An object's second test: the buffer's revision at its first test (the same revision
  /// answers the same, so the test is not repeated when nothing was drawn in between).
  std::uint64_t revision = 0;
};
/// HeapEntry::mask of an object's second test (frustum masks use the low six bits).
constexpr std::uint8_t kSecondTest = 0xFF;
} // namespace

struct Bvh::OcclusionFrame
{
  Frame base;
  OcclusionCull& occlusion;
  std::vector<HeapEntry> heap;
};

namespace
{
/// How near a box comes to the viewer: squared distance from the eye (perspective) or the
/// smallest coordinate along the view direction (parallel). Only the order matters.
inline double nearness(const CullParams& p, const glm::dvec3& lo, const glm::dvec3& hi)
{
  if (p.parallel)
  {
    const glm::dvec3& d = p.viewDirection;
    return std::min(lo.x * d.x, hi.x * d.x) + std::min(lo.y * d.y, hi.y * d.y) +
      std::min(lo.z * d.z, hi.z * d.z);
  }
  return nearestDistance2(p.eye, lo, hi);
}
} // namespace

bool Bvh::worthDrawing(const OcclusionCull& occlusion, std::uint32_t p) const
{
  return !occlusion.worthDrawing ||
    occlusion.worthDrawing(glm::dvec3(boxes_.minX[p], boxes_.minY[p], boxes_.minZ[p]),
      glm::dvec3(boxes_.maxX[p], boxes_.maxY[p], boxes_.maxZ[p]), triangles_[p]);
}

void Bvh::drawOnce(OcclusionFrame& of, std::uint32_t p)
{
  if (!of.occlusion.drawOccluder || occluderStamp_[p] == occlusionFrame_)
  {
    return;
  }
  occluderStamp_[p] = occlusionFrame_;
  if (worthDrawing(of.occlusion, p))
  {
    of.occlusion.drawOccluder(id_[p]);
    ++of.base.stats.occludersDrawn;
  }
}

void Bvh::cullOccluded(const CullParams& params,
  OcclusionCull& occlusion,
  std::vector<std::uint32_t>& visible,
  CullStats* stats)
{
  if (!occlusion.buffer)
  {
    cull(params, visible, stats);
    return;
  }
  visible.clear();
  CullStats local;
  OcclusionFrame frame{ makeFrame(params, visible, local), occlusion, {} };
  if (occluderStamp_.size() != id_.size() || ++occlusionFrame_ == 0)
  {
    occluderStamp_.assign(id_.size(), 0);
    occlusionFrame_ = 1;
  }
  const std::uint8_t allPlanes = params.frustumCulling ? kAllPlanes : 0;
  // Temporal coherence: last frame's visible objects occlude first, if they still pass this
  // frame's tests (counted apart, so the statistics describe the traversal alone).
  if (occlusion.seeds && occlusion.drawOccluder)
  {
    CullStats scratch;
    std::vector<std::uint32_t> none;
    Frame probe = makeFrame(params, none, scratch);
    for (const std::uint32_t id : *occlusion.seeds)
    {
      if (id >= position_.size())
      {
        continue;
      }
      const std::uint32_t p = position_[id];
      if (p >= treeCount_ || always_[p] || occluderStamp_[p] == occlusionFrame_ ||
        (occlusion.active && !occlusion.active[id]) || !objectPasses(probe, p, allPlanes))
      {
        continue;
      }
      occluderStamp_[p] = occlusionFrame_;
      if (worthDrawing(occlusion, p))
      {
        occlusion.drawOccluder(id);
        ++local.occludersDrawn;
      }
    }
  }
  if (!nodes_.empty())
  {
    if (occlusion.active)
    {
      boundActive(occlusion.active);
    }
    cullNodeOccluded(frame, 0, allPlanes);
  }
  appendAlwaysVisible(visible, local);
  if (stats)
  {
    *stats = local;
  }
}

void Bvh::boundActive(const std::uint8_t* active)
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  activeBounds_.resize(nodes_.size());
  // Children have larger indices than their parent: one reverse sweep.
  for (std::size_t ni = nodes_.size(); ni-- > 0;)
  {
    const Node& node = nodes_[ni];
    NodeBound& b = activeBounds_[ni];
    if (node.isLeaf())
    {
      b.lo = glm::dvec3(inf);
      b.hi = glm::dvec3(-inf);
      b.objects = 0;
      for (std::uint32_t p = node.first; p < node.first + node.count; ++p)
      {
        if (!always_[p] && active[id_[p]])
        {
          b.lo = glm::min(b.lo, glm::dvec3(boxes_.minX[p], boxes_.minY[p], boxes_.minZ[p]));
          b.hi = glm::max(b.hi, glm::dvec3(boxes_.maxX[p], boxes_.maxY[p], boxes_.maxZ[p]));
          ++b.objects;
        }
      }
    }
    else
    {
      const NodeBound& l = activeBounds_[ni + 1];
      const NodeBound& r = activeBounds_[node.first];
      b.lo = glm::min(l.lo, r.lo);
      b.hi = glm::max(l.hi, r.hi);
      b.objects = l.objects + r.objects;
    }
  }
}

void Bvh::cullNodeOccluded(OcclusionFrame& of, std::uint32_t root, std::uint8_t rootMask)
{
  // Best-first, not depth-first: nodes and objects come off one heap, nearest first, so that
  // every object is tested after all nearer ones were drawn as occluders. Depth-first (nearer
  // child first) finishes a whole subtree before its sibling: with the eye between the two, the
  // far contents of the first are tested before the wall a few units away in the second is
  // drawn (a Quake-3 spawn facing a wall kept 324 parts of which 4 are visible). The order does
  // not change what a test may conclude, only how much has been drawn when it runs.
  Frame& f = of.base;
  auto& heap = of.heap;
  heap.clear();
  const auto later = [](const HeapEntry& a, const HeapEntry& b) {
    return a.nearness > b.nearness || (a.nearness == b.nearness && a.index > b.index);
  };
  // With objects left out (OcclusionCull::active), a node is the box around its active objects,
  // and a node without any is not visited.
  const bool pruned = of.occlusion.active != nullptr;
  const auto bound = [&](std::uint32_t ni)
  {
    const Node& node = nodes_[ni];
    return pruned ? activeBounds_[ni] : NodeBound{ node.lo, node.hi, node.objects };
  };
  const NodeBound rootBound = bound(root);
  if (rootBound.objects == 0)
  {
    return;
  }
  heap.push_back({ nearness(f.params, rootBound.lo, rootBound.hi), root, rootMask, false });
  while (!heap.empty())
  {
    std::pop_heap(heap.begin(), heap.end(), later);
    const HeapEntry entry = heap.back();
    heap.pop_back();
    std::uint8_t mask = entry.mask;
    if (entry.object)
    {
      const std::uint32_t p = entry.index;
      const glm::dvec3 lo(boxes_.minX[p], boxes_.minY[p], boxes_.minZ[p]);
      const glm::dvec3 hi(boxes_.maxX[p], boxes_.maxY[p], boxes_.maxZ[p]);
      const bool unchanged =
        entry.mask == kSecondTest && entry.revision == of.occlusion.buffer->revision();
      if (!unchanged)
      {
        ++f.stats.occlusionTests;
        if (of.occlusion.buffer->boxOccluded(lo, hi))
        {
          ++f.stats.culledOcclusion;
          continue;
        }
      }
      if (entry.mask != kSecondTest)
      {
        // Not hidden by what is nearer than its box's nearest point: drawn as an occluder now
        // (what it hides is hidden from here on), but kept only if it is still not hidden when
        // the traversal reaches its centre: a long part that comes near the eye (a crankshaft
        // along a row of engines) is mostly behind parts whose boxes come less near. Drawing it
        // only at its centre delayed the occluders of a whole row (the CLI's engine-row view of
        // the 10 x 10 grid kept 67 parts for 15 visible, 37 now). A part drawn and then culled is
        // hidden behind occluders drawn before it, so what it hides is hidden by them too.
        const glm::dvec3 c = (lo + hi) * 0.5;
        const double key = f.params.parallel ? glm::dot(c, f.params.viewDirection)
                                             : glm::dot(c - f.params.eye, c - f.params.eye);
        if (key > entry.nearness)
        {
          drawOnce(of, p);
          heap.push_back({ key, p, kSecondTest, true, of.occlusion.buffer->revision() });
          std::push_heap(heap.begin(), heap.end(), later);
          continue;
        }
      }
      f.visible.push_back(id_[p]);
      ++f.stats.objectsDrawn;
      f.stats.trianglesDrawn += triangles_[p];
      drawOnce(of, p);
      continue;
    }
    const std::uint32_t ni = entry.index;
    const NodeBound b = bound(ni);
    if (!boxPasses(f, ni, b.lo, b.hi, b.objects, mask))
    {
      continue;
    }
    const Node& node = nodes_[ni];
    ++f.stats.occlusionTests;
    if (of.occlusion.buffer->boxOccluded(b.lo, b.hi))
    {
      f.stats.culledOcclusion += b.objects;
      continue;
    }
    if (!node.isLeaf())
    {
      for (const std::uint32_t child : { ni + 1, node.first })
      {
        const NodeBound c = bound(child);
        if (c.objects == 0)
        {
          continue;
        }
        heap.push_back({ nearness(f.params, c.lo, c.hi), child, mask, false });
        std::push_heap(heap.begin(), heap.end(), later);
      }
      continue;
    }
    for (std::uint32_t p = node.first; p < node.first + node.count; ++p)
    {
      if (always_[p] || (of.occlusion.active && !of.occlusion.active[id_[p]]) ||
        !objectPasses(f, p, mask))
      {
        continue;
      }
      const glm::dvec3 lo(boxes_.minX[p], boxes_.minY[p], boxes_.minZ[p]);
      const glm::dvec3 hi(boxes_.maxX[p], boxes_.maxY[p], boxes_.maxZ[p]);
      heap.push_back({ nearness(f.params, lo, hi), p, mask, true });
      std::push_heap(heap.begin(), heap.end(), later);
    }
  }
}

} // namespace culling
} // namespace scenevis

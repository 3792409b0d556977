#pragma once
/**
 * @file Bvh.h
 * @brief Bounding volume hierarchy over axis-aligned boxes for hierarchical view culling.
 *
 * Why a BVH and not a (loose) octree: CAD assemblies mix part sizes over 2-3 orders of magnitude
 * (a baseplate the size of the model, screws of 1 mm), are spatially very uneven (clusters inside
 * housings, empty space above the board) and parts move (exploded views, kinematics). A BVH
 * adapts to all three: every node is the tight union of its objects (a loose octree's cells are
 * fixed and up to 2x looser, and the baseplate-sized object sits at the root and is tested every
 * frame either way), its size is bounded (2n - 1 nodes for n objects, never empty cells), and a
 * moved object is handled by a refit of its leaf-to-root path in O(log n) with no reinsertion.
 * Measured (Core/Benchmarks/BenchCulling.cpp, 100k boxes of the CAD size mix): the binned-SAH
 * BVH visits fewer nodes than the median-split one for the same frusta; see the numbers printed
 * by the benchmark (nodes visited per frame as a counter). A loose octree was not implemented.
 *
 * Layout: nodes in depth-first order (left child = node + 1, right child stored), object boxes
 * kept in tree order as structure-of-arrays for linear access in leaves; per-node and per-object
 * "last culling plane" bytes for temporal coherence. Boxes that are empty or not finite are not
 * put in the tree: they are always reported visible (the caller cannot be sure where they are).
 *
 * Per-frame state (coherence hints) lives in the tree, so cull() is not const; everything else
 * about a frame is passed in CullParams, so one tree serves any number of views in turn.
 */

#include "scenevis/Frustum.h"
#include "scenevis/NormalCone.h"
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/PolygonMesh.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace scenevis
{
namespace culling
{

/// What to test this frame; each test can be switched off independently.
struct CullParams
{
  Frustum frustum;
  bool frustumCulling = true;

  /// The eye (camera position) and, for perspective, the view direction (unit, into the scene);
  /// for a parallel projection the direction of projection. Needed by contribution, distance
  /// and normal-cone culling.
  glm::dvec3 eye{ 0.0 };
  glm::dvec3 viewDirection{ 0.0, 0.0, -1.0 };
  bool parallel = false;

  /**
   * Small-feature (contribution) culling, APPROXIMATE: an object whose bounding sphere projects
   * to a diameter below minPixels pixels is culled, even though it may cover a few pixels.
   * pixelsPerUnit: for perspective the projected size in pixels of a unit length at unit view
   * depth (viewport height / (2 tan(fovy / 2))); for parallel, pixels per world unit
   * (viewport height / (2 * parallel scale)). 0 = off.
   */
  double minPixels = 0.0;
  double pixelsPerUnit = 0.0;

  /// Distance culling: objects whose nearest point is farther than this from the eye are culled.
  double maxDistance = std::numeric_limits<double>::infinity();

  /// Clustered back-face culling with the objects' normal cones (see NormalCone.h).
  bool normalConeCulling = false;
};

/// Per-frame statistics (reset by every cull()).
struct CullStats
{
  std::size_t nodesVisited = 0;
  std::size_t objectsTested = 0; ///< objects tested individually (in visited leaves)
  std::size_t culledFrustum = 0; ///< objects culled, by reason (whole subtrees included)
  std::size_t culledContribution = 0;
  std::size_t culledDistance = 0;
  std::size_t culledNormalCone = 0;
  std::size_t culledOcclusion = 0;    ///< hidden behind occluders (cullOccluded() only)
  std::size_t occlusionTests = 0;     ///< node and object boxes tested against the buffer
  std::size_t occludersDrawn = 0;     ///< objects handed to OcclusionCull::drawOccluder
  std::size_t objectsDrawn = 0;
  std::size_t trianglesDrawn = 0; ///< sum of the drawn objects' triangle counts (if given)

  std::size_t objectsCulled() const
  {
    return culledFrustum + culledContribution + culledDistance + culledNormalCone +
      culledOcclusion;
  }
};

/**
 * Occlusion culling on top of CullParams (see OcclusionBuffer.h for the buffer's contract).
 * The tree is traversed front to back; a node or object whose box is hidden behind the buffer's
 * occluders is culled with its subtree, and every object found visible is handed to drawOccluder
 * (which rasterizes it into the buffer if it is an opaque occluder) before anything farther is
 * tested, so what is drawn occludes what is behind it.
 *
 * Conservative: an object is culled only if its box is hidden behind occluders; each occluder is
 * an object this traversal reports visible, or one it drew when its box's nearest point was not
 * hidden and culled later (when the traversal reached the box's centre, with more drawn) because
 * it was then hidden behind occluders drawn before it, or a seed that passes this frame's other
 * tests. An occluder that is not reported visible is hidden at each of its pixels behind earlier
 * occluders, so what it hides is hidden by them too (transitively by visible ones). So whatever
 * the caller draws opaque where drawOccluder said, the culled objects are hidden in the final
 * image.
 */
struct OcclusionCull
{
  /// Sized to the viewport and cleared by the caller; setClipFromWorld() of this frame's camera.
  occlusion::MaskedDepthBuffer* buffer = nullptr;
  /// Rasterize object @p id into the buffer if it is an occluder (at most once per cull).
  std::function<void(std::uint32_t id)> drawOccluder;
  /// Occluder selection, optional: whether an object with world box [lo, hi] and @p triangles
  /// (its build-time triangle count) is worth rasterizing; when it says no, drawOccluder is not
  /// called for it (leaving an occluder out is always conservative). Asked from the hierarchy's
  /// own arrays, so that a wide view whose objects are nearly all visible and nearly all too small
  /// to occlude does not touch the caller's per-object records.
  std::function<bool(const glm::dvec3& lo, const glm::dvec3& hi, std::uint32_t triangles)>
    worthDrawing;
  /// Objects drawn as occluders before the traversal (temporal coherence: last frame's visible
  /// set). Seeds that fail this frame's frustum / distance / size / cone tests are skipped.
  const std::vector<std::uint32_t>* seeds = nullptr;
  /// Optional, one byte per object id: 0 leaves the object out of this cull (another culler
  /// removed it this frame): it is not tested, counted, drawn as an occluder or visible (objects
  /// without a box, never culled, are listed as always). A node then stands for its active
  /// objects: it is tested with the box around them (bottom-up, O(nodes) per cull) and skipped
  /// when it has none, and its statistics count them.
  const std::uint8_t* active = nullptr;
};

enum class BuildMethod
{
  BinnedSah, ///< surface area heuristic over 16 centroid bins (default)
  Median     ///< object median along the largest centroid extent
};

class Bvh
{
public:
  struct Node
  {
    glm::dvec3 lo{ 0.0 }, hi{ 0.0 };
    std::uint32_t first = 0;   ///< leaf: first object position; internal: right child index
    std::uint32_t count = 0;   ///< leaf: object count (> 0); internal: 0
    std::uint32_t parent = 0;  ///< root: itself
    std::uint32_t objects = 0; ///< objects in the subtree: positions [begin, begin + objects)
    std::uint32_t begin = 0;
    bool isLeaf() const { return count != 0; }
  };

  /**
   * Build over @p boxes (object i = box i). @p triangles (optional, size boxes.size()): triangle
   * count per object for the statistics. @p leafSize: at most this many objects per leaf.
   */
  void build(const BoxArrays& boxes,
    BuildMethod method = BuildMethod::BinnedSah,
    unsigned leafSize = 4,
    const std::vector<std::uint32_t>* triangles = nullptr);

  std::size_t objectCount() const { return position_.size(); }
  const std::vector<Node>& nodes() const { return nodes_; }

  /// Move object @p id to @p box (its ancestors are refit by refit()). A box that is empty or
  /// not finite makes the object always visible (it keeps its last valid box in the tree).
  void update(std::uint32_t id, const Box& box);
  /// Set object @p id's normal cone (also applied by refit()).
  void setNormalCone(std::uint32_t id, const NormalCone& cone);
  void setTriangleCount(std::uint32_t id, std::uint32_t triangles);
  /// Refit the boxes and cones of the ancestors of objects changed since the last refit.
  /// @return the number of nodes recomputed.
  std::size_t refit();

  /// Box of object @p id as the tree holds it.
  Box objectBox(std::uint32_t id) const;
  /// Whether object @p id is kept visible because its box is empty or not finite.
  bool alwaysVisible(std::uint32_t id) const { return always_[position_[id]] != 0; }

  /**
   * Cull: append the ids of the objects that pass every enabled test to @p visible (cleared
   * first; tree order, not id order) and fill @p stats if given.
   */
  void cull(const CullParams& params, std::vector<std::uint32_t>& visible, CullStats* stats);

  /**
   * Cull with the tests of @p params and occlusion (see OcclusionCull): front to back over the
   * whole tree (one heap of nodes and objects by their boxes' nearness, so every object is
   * tested after all objects whose boxes come nearer were drawn). @p visible lists the objects
   * drawn, nearest box first.
   */
  void cullOccluded(const CullParams& params,
    OcclusionCull& occlusion,
    std::vector<std::uint32_t>& visible,
    CullStats* stats);

  /// Sum of the half surface areas of all nodes relative to that right after build(): grows as
  /// refits loosen the tree; rebuild when it gets large (e.g. > 1.5).
  double degradation() const;

private:
  struct Frame;
  Frame makeFrame(const CullParams& params, std::vector<std::uint32_t>& visible,
    CullStats& stats) const;
  void appendAlwaysVisible(std::vector<std::uint32_t>& visible, CullStats& stats) const;
  std::uint32_t buildRange(std::uint32_t begin, std::uint32_t end, std::uint32_t parent);
  void cullNode(Frame& frame, std::uint32_t node, std::uint8_t mask) const;
  struct OcclusionFrame;
  void cullNodeOccluded(OcclusionFrame& frame, std::uint32_t node, std::uint8_t mask);
  /// OcclusionCull::worthDrawing of the object at position @p p (true without one).
  bool worthDrawing(const OcclusionCull& occlusion, std::uint32_t p) const;
  /// Hands the object at position @p p to drawOccluder once per cull (if worthDrawing).
  void drawOnce(OcclusionFrame& frame, std::uint32_t p);
  bool nodePasses(Frame& frame, std::uint32_t node, std::uint8_t& mask) const;
  /// nodePasses() for the @p objects of node @p node inside [lo, hi].
  bool boxPasses(Frame& frame, std::uint32_t node, const glm::dvec3& lo, const glm::dvec3& hi,
    std::uint32_t objects, std::uint8_t& mask) const;
  /// What a node stands for in cullOccluded(): its box and objects, or with OcclusionCull::active
  /// its active objects' (boundActive()).
  struct NodeBound
  {
    glm::dvec3 lo, hi;
    std::uint32_t objects = 0;
  };
  /// activeBounds_ for @p active, children before parents.
  void boundActive(const std::uint8_t* active);
  bool objectPasses(Frame& frame, std::uint32_t position, std::uint8_t mask) const;
  void computeNodeBounds(std::uint32_t node);
  double totalArea() const;

  // Objects in tree order (position p); id_[p] is the object id, position_[id] its position.
  std::vector<std::uint32_t> id_, position_, leafOf_;
  BoxArrays boxes_;
  std::vector<NormalCone> cones_;
  std::vector<std::uint32_t> triangles_;
  std::vector<std::uint8_t> always_;
  std::vector<Node> nodes_;
  std::vector<NormalCone> nodeCones_;
  // Temporal coherence: the plane that culled the node / object last time. Mutable so that
  // cull() can be called on a tree whose structure is otherwise shared read-only.
  mutable std::vector<std::uint8_t> nodeHint_, objectHint_;
  std::vector<std::uint32_t> dirtyLeaves_;
  // cullOccluded(): frame stamp per object position when it was drawn as an occluder.
  std::vector<std::uint32_t> occluderStamp_;
  std::uint32_t occlusionFrame_ = 0;
  std::vector<NodeBound> activeBounds_;
  std::vector<std::uint8_t> leafDirty_;
  // Build scratch.
  std::vector<glm::dvec3> centroid_;
  const BoxArrays* buildBoxes_ = nullptr;
  std::uint32_t treeCount_ = 0; ///< positions [0, treeCount_) are in the tree
  unsigned leafSize_ = 4;
  BuildMethod method_ = BuildMethod::BinnedSah;
  double builtArea_ = 0.0;
};

/// Half surface area of a box (the SAH cost weight).
double halfArea(const glm::dvec3& lo, const glm::dvec3& hi);

} // namespace culling
} // namespace scenevis

#pragma once
/**
 * @file BspBuilder.h
 * @brief Builds a bsp::Tree from a PolygonMesh.
 *
 * Input: any polygons. Convex planar polygons are used as they are; concave or non-planar ones
 * are first triangulated (ear clipping in the polygon's best-fit plane, no new points); polygons
 * with < 3 distinct points or zero area, and polygons touching a NaN/Inf point, are removed and
 * counted in BuildStatistics. Every fragment of the result is convex.
 *
 * Partition choice (Config::partition):
 * - FirstInList: the textbook choice, the first polygon of the node's list. A convex mesh then
 *   becomes a chain as deep as it has polygons; build and traversal are iterative and survive it.
 * - Scored: sample `candidates` polygon planes (seeded, deterministic; twice as many on short
 *   lists, which are scored exactly anyway: at most 32 fragments, 128 with Effort::Thorough) and,
 *   when allowFreePlanes and the list has more than 128 fragments, axis-aligned free planes:
 *   through the median of the polygon centroids (and through the median polygon's nearest
 *   vertex), and per axis the best position found by a sweep over the sorted extents of up to 64
 *   fragments (256 with Effort::Thorough; finds gaps between parts and planes along aligned
 *   faces). Each is scored against up to `samplePolygons` polygons (see Score) and the lowest wins.
 *
 * Scores (Config::score), with front / back / splits counted on the sample:
 * - SubtreeCost (default): on lists of at most 128 fragments (where most splits happen),
 *   C(front + splits) + C(back + splits) with C(m) = m log2 m: the estimated cost of building both
 *   children (a split fragment goes to both; fragments coplanar with a polygon plane leave the
 *   list). It weighs a split by the work still to come below it and favours balance only as much
 *   as that saves; splitWeight is not used there. Longer lists use SplitsAndBalance, whose strong
 *   preference for balance keeps the tree shallow (C alone lets peeled chains deepen it and makes
 *   incremental traversal visit more nodes). Bunny: 2.08 (Effort::Thorough: 2.02) instead of 2.28
 *   fragments per triangle.
 * - SplitsAndBalance: splits * splitWeight + |front - back| on every list (the classic heuristic).
 *
 * Effort (Config::effort), measured side by side in one run (single thread, CPU seconds, best of
 * 2, g++ 12 -O3 on 2 shared cores, so +-15 %; fragments per input polygon):
 *
 *   scene               | before score/sweep | Default        | Thorough
 *   --------------------+--------------------+----------------+---------------
 *   bunny (69k)         | 2.280   0.32 s     | 2.083  0.40 s  | 2.024  0.62 s
 *   engine (121k)       | 2.491   0.77 s     | 2.401  0.78 s  | 2.377  0.87 s
 *   64 spheres (1M)     | 1.626   3.28 s     | 1.584  3.48 s  | 1.581  5.89 s
 *   rotated sphere (1M) | 1.473   2.13 s     | 1.438  2.50 s  | 1.448  3.15 s
 *   aligned sphere (1M) | 1.093   1.26 s     | 1.079  1.53 s  | 1.081  2.41 s
 *
 * Default: sweeps over 64 fragments, twice the candidates on lists of at most 32 fragments, the
 * score's early-out bound checked every 4th fragment: 1.0-1.25x the build time of the plain
 * SplitsAndBalance builder for 77-100 % of Thorough's fragment savings. Thorough (256-fragment
 * sweeps, twice the candidates up to 128 fragments, bound checked every fragment) saves another
 * 1-3 % of fragments on organic meshes (bunny, engine) for 1.1-1.7x Default's build time. Default
 * deepens the tree of a generic (rotated) sphere: 1M depth 471 instead of 277.
 *
 * Measured and not adopted (issue 15 item 2; BENCHMARKS.md, "Fewer fragments"): stopping at sets
 * in which every polygon has all others on one side of its plane (convex patches: below 128
 * fragments the scores already chain them without splits), scoring short lists by such patches,
 * diagonal sweeps, two-level lookahead, a per-split weight in SubtreeCost, more candidates: none
 * gets the bunny below 1.98 fragments per triangle. Ordered leaves (Config::orderedLeafSize, off
 * by default) draw fewer: bunny 1.59 / 1.26, engine 2.01 / 1.82 per input polygon at 64 / 256,
 * for several times the order time and tree memory (BENCHMARKS.md, "ordered leaves" and
 * "longer ordered leaves").
 *
 * Tolerance: Tree::tolerance = max(relativeTolerance * bounds diagonal,
 * 16 * DBL_EPSILON * max |coordinate|): the second term is the coordinate resolution, which far
 * from the origin (1e7) exceeds the relative tolerance of a small scene.
 *
 * The build is iterative (explicit work stack), deterministic for a given seed and input, and does
 * not depend on thread timing.
 */

#include "scenevis/BspTree.h"

#include <cstdint>
#include <functional>

namespace scenevis
{
namespace bsp
{

struct BuildConfig
{
  enum class Partition
  {
    FirstInList,
    Scored
  };
  /// How Scored rates a candidate plane (see the file comment).
  enum class Score
  {
    SubtreeCost,
    SplitsAndBalance
  };
  /// Build time vs. fragment count of Scored (see the table in the file comment).
  enum class Effort
  {
    Default,
    Thorough
  };
  Partition partition = Partition::Scored;
  Score score = Score::SubtreeCost;
  Effort effort = Effort::Default;
  int candidates = 16;
  int samplePolygons = 128;
  /// Weight of a split in Score::SplitsAndBalance (unused by SubtreeCost).
  double splitWeight = 4.0;
  bool allowFreePlanes = true;
  std::uint64_t seed = 1;
  /// Plane tolerance relative to the diagonal of the input bounds (never below the coordinate
  /// resolution, see the file comment).
  double relativeTolerance = 1e-10;
  /**
   * Ordered leaves (BspTree.h): a list of at most this many fragments (capped at
   * kMaxLeafPolygons = 256) is first partitioned by a plane that splits none of it, when there
   * is one: a polygon's own plane, else (when the list would make a leaf that needs a fallback)
   * an axis-aligned plane through a gap between the fragments' extents or one of 64 sampled
   * separating planes of its pairs. What no such plane separates is kept unsplit when every pair
   * of its polygons is either coplanar or separated by a plane (the polygons' own planes, else an
   * axis between their edges and normals): an order then sorts the leaf per view instead of
   * drawing a split subtree. A list with an intersecting pair is split as usual (its shorter
   * children try again). When the pairs of a leaf could form a cycle (its pair graph is not a
   * forest), the split subtree is built as well, as the leaf's fallback for the eyes that see
   * one. 0 (default) builds no leaves; the tree is then exactly the one built without this
   * option. Larger leaves draw fewer fragments and cost more order time and memory (bunny: 1.59
   * per input polygon at 64, 1.26 at 256; BENCHMARKS.md, "ordered leaves").
   * IncrementalOrder does not take trees with leaves (yet).
   */
  std::uint32_t orderedLeafSize = 0;
  /**
   * Fragments that meet edge to edge (makeConforming()): a split adds its point to the fragments
   * on the other side of the split edge too, so that no fragment edge passes through another's
   * vertex. OpenGL fills the pixels along an edge shared by two triangles exactly once only when
   * both have the same end points; at a T-junction (one side split, the other not) the rounding of
   * the split point to float leaves pixels covered twice or not at all, which blending shows as
   * a wrong translucent layer. Default on; off: the fragments of the split alone.
   */
  bool conformingFragments = true;
  /// Worker threads for the build: once a node's two sides are both large, they are built
  /// concurrently. The result (every array of the Tree) is identical for any value; 1 builds on
  /// the calling thread only, 0 means std::thread::hardware_concurrency().
  int threads = 1;
};

/// Called now and then with the fraction of polygons placed; return false to cancel the build
/// (the result is then an empty tree).
using ProgressCallback = std::function<bool(double fraction)>;

Tree build(const PolygonMesh& mesh, const BuildConfig& config = {},
  const ProgressCallback& progress = {});

/**
 * Makes @p tree's fragments meet edge to edge: every split point that lies strictly inside a
 * fragment's edge (made by splitting a polygon on the other side of that edge, or the same line
 * further along) is inserted into it, in order. The fragments keep their shape and convexity (the
 * inserted points are on their edges: collinear vertices). A fragment that gets points starts at
 * the vertex a fan triangulation (the one OpenGL mappers use: vertex 0 with each edge) from which
 * has the fewest flat triangles (ConvexTriangulation.h), so that the fan keeps the inserted
 * points as triangle corners. Returns the number of vertices inserted. build() calls it unless
 * BuildConfig::conformingFragments is off.
 */
std::size_t makeConforming(Tree& tree);

/**
 * makeConforming() on the fragments of anything with a bsp::Tree's point and split-point
 * conventions (a painter::Result: PainterSort.h): @p points holds the input points, then the
 * split points that @p splitPoints describes.
 */
std::size_t makeConforming(std::vector<Fragment>& fragments,
  std::vector<std::uint32_t>& fragmentVertices, const std::vector<glm::dvec3>& points,
  std::size_t inputPointCount, const std::vector<SplitPoint>& splitPoints);

} // namespace bsp
} // namespace scenevis

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
 * - Scored: sample `candidates` polygon planes (seeded, deterministic; twice as many on lists of at
 *   most 128 fragments, which are scored exactly anyway) and, when allowFreePlanes and the list has
 *   more than 128 fragments, axis-aligned free planes: through the median of the polygon centroids
 *   (and through the median polygon's nearest vertex), and per axis the best position found by a
 *   sweep over the sorted extents of up to 256 fragments (finds gaps between parts and planes
 *   along aligned faces). Each is scored against up to `samplePolygons` polygons (see Score) and
 *   the lowest wins.
 *
 * Scores (Config::score), with front / back / splits counted on the sample:
 * - SubtreeCost (default): on lists of at most 128 fragments (where most splits happen),
 *   C(front + splits) + C(back + splits) with C(m) = m log2 m: the estimated cost of building both
 *   children (a split fragment goes to both; fragments coplanar with a polygon plane leave the
 *   list). It weighs a split by the work still to come below it and favours balance only as much
 *   as that saves; splitWeight is not used there. Longer lists use SplitsAndBalance, whose strong
 *   preference for balance keeps the tree shallow (C alone lets peeled chains deepen it and makes
 *   incremental traversal visit more nodes). Bunny: 2.02 instead of 2.28 fragments per triangle.
 * - SplitsAndBalance: splits * splitWeight + |front - back| on every list (the classic heuristic).
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
  Partition partition = Partition::Scored;
  Score score = Score::SubtreeCost;
  int candidates = 16;
  int samplePolygons = 128;
  /// Weight of a split in Score::SplitsAndBalance (unused by SubtreeCost).
  double splitWeight = 4.0;
  bool allowFreePlanes = true;
  std::uint64_t seed = 1;
  /// Plane tolerance relative to the diagonal of the input bounds (never below the coordinate
  /// resolution, see the file comment).
  double relativeTolerance = 1e-10;
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

} // namespace bsp
} // namespace scenevis

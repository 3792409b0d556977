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
 * - Scored: sample `candidates` polygon planes (seeded, deterministic) and, when allowFreePlanes,
 *   three axis-aligned planes through the median of the polygon centroids; score each against up to
 *   `samplePolygons` polygons as splits * splitWeight + |front - back| and take the lowest.
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
  Partition partition = Partition::Scored;
  int candidates = 16;
  int samplePolygons = 128;
  double splitWeight = 4.0;
  bool allowFreePlanes = true;
  std::uint64_t seed = 1;
  /// Plane tolerance relative to the diagonal of the input bounds.
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

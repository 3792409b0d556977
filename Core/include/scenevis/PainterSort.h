#pragma once
/**
 * @file PainterSort.h
 * @brief The painter's algorithm of Newell, Newell & Sancha (1972): a per-frame, view-dependent
 *        back-to-front order that splits polygons where no order of whole polygons exists.
 *
 * The comparison mode of SceneVis's accuracy-versus-time story: exact like the BSP (BspBuilder.h,
 * BspTraversal.h) on cycles and interpenetrating polygons, because it splits them too, but all the
 * work is redone for every view, and its worst case is quadratic in the polygon count.
 *
 * Input (as BspBuilder.h): any polygons. Convex planar polygons are used as they are; concave or
 * non-planar ones are triangulated first (ear clipping in the best-fit plane, no new points);
 * polygons with < 3 distinct points or zero area, and polygons touching a NaN/Inf point or an
 * out-of-range point id, are removed and counted in Statistics. This happens once, in the Sorter's
 * constructor; Sorter::sort() then does only the view-dependent work.
 *
 * Depth. Perspective: the Euclidean distance from the eye (the distance along the ray through the
 * point). A fragment's depth extent is [exact distance from the eye to the convex polygon,
 * largest vertex distance]. Distance orders hits along every ray in every direction, so the eye may
 * be anywhere, inside the geometry too. Parallel: the coordinate along the view direction.
 *
 * Algorithm, per view. The fragments are sorted by farthest depth (farthest first). The head P of
 * the list (the farthest, or the polygon most recently moved there) is compared with every other
 * remaining fragment Q whose depth extent overlaps P's, by the tests below, cheapest first; P may
 * be drawn before Q as soon as one passes:
 *   (1) depth extents: P is entirely at least as far as Q (this is also what ends the scan);
 *   (2) screen extents do not overlap. Parallel: x/y boxes in the image plane. Perspective: the
 *       eye may be anywhere, so there is no single image plane; the "screen" is the sphere of
 *       directions and each fragment's extent is a bounding cone (axis, half-angle < 90 degrees;
 *       a fragment seen across a half-space or more gets an unbounded cone);
 *   (3) P lies entirely on the far side of Q's plane (the side away from the eye);
 *   (4) Q lies entirely on the near side of P's plane (the eye's side);
 *   (5) the projections do not overlap: exact convex-polygon separation (separating axis test).
 *       Perspective: central projection onto a plane perpendicular to the mean of the two cone
 *       axes; when the two cones do not fit together in an open half-space around it (a fragment
 *       passes beside or behind the eye) the test is not decided and counts as overlap, so the
 *       exact plane tests decide (conservative, counted in Statistics::undecidedProjections).
 * When P passes against all of them it is emitted. When P fails against Q, the swapped tests ask
 * whether Q may be drawn before P ((1') Q entirely farther, (3') Q on the far side of P's plane,
 * (4') P on the near side of Q's plane): if so Q moves to the head of the list and is marked. A
 * marked fragment that would have to move again closes a cycle (some fragments on the chain of
 * moves each need another before them): one fragment of the cycle that straddles another's plane is
 * split by that plane (there always is one when the cycle is real; otherwise the marked fragment
 * is bisected, counted as a fallback split). When neither may go first, both straddle the other's
 * plane (interpenetration, or a pair the tests cannot separate): P is split by Q's plane.
 *
 * An edge-on fragment (its plane within the tolerance of the eye; parallel views: its radius times
 * |cos(normal, direction)| within the tolerance) covers no image area and is ordered freely.
 *
 * Splits (as in the BSP). A point is on a plane when its distance is within the tolerance
 * (Config::relativeTolerance times the diagonal of the input bounds); classification is a pure
 * function of (point, plane), and a split edge yields one split point per (edge, plane), shared by
 * every fragment that has that edge, so neighbours split by the same plane stay crack-free; and
 * after the sort each split point is inserted into the other fragments' edges it lies on
 * (Config::conformingFragments), so no fragment edge passes through another's vertex.
 * Geometry is evaluated relative to the centre of the input bounds.
 *
 * Termination: every step emits a fragment, moves an unmarked one (at most as many as remain) or
 * splits one. Splits are capped at Config::maxSplitsPerPolygon times the polygon count (plus 64);
 * beyond the cap, a conflict that needs a split emits the head as it is (the order may then be
 * wrong; counted in Statistics::forcedEmissions). The cap is far above what real scenes need.
 *
 * Point ids: ids below `inputPointCount` are the input mesh's own points; split points follow in
 * creation order and are described by `splitPoints` (attribute(id) = lerp(attribute(a),
 * attribute(b), t), with a and b smaller than id), exactly as in bsp::Tree.
 *
 * Determinism: the result is a pure function of (mesh, view, config).
 */

#include "scenevis/BspTree.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/View.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace scenevis
{
namespace painter
{

struct Config
{
  /// Plane tolerance relative to the diagonal of the input bounds.
  double relativeTolerance = 1e-10;
  /// Safety cap: at most maxSplitsPerPolygon * polygons + 64 splits per sort (see file comment);
  /// 0 allows no split at all (every conflict that needs one is a forced emission).
  double maxSplitsPerPolygon = 16.0;
  /// false: the plain depth sort (by farthest depth, no Newell tests, no splits). Wrong on cycles
  /// and overlapping depth ranges; kept for comparison and to show the oracle can fail.
  bool newellTests = true;
  /**
   * Fragments that meet edge to edge, as bsp::BuildConfig::conformingFragments: after the sort,
   * every split point is inserted into the fragment edges it lies on (bsp::makeConforming), so
   * no fragment edge passes through a neighbour's vertex (a T-junction, where OpenGL covers
   * pixels twice or not at all). Default on; off: the fragments of the splits alone.
   */
  bool conformingFragments = true;
};

/// How often a test was evaluated on a (head, other) pair and how often it decided the pair.
struct TestCount
{
  std::size_t evaluated = 0;
  std::size_t passed = 0;
};

struct Statistics
{
  // Normalisation (once per mesh; copied into every sort's statistics).
  std::size_t inputPolygons = 0;
  std::size_t degeneratePolygons = 0;   ///< Removed: < 3 distinct points or zero area.
  std::size_t invalidPolygons = 0;      ///< Removed: a NaN/Inf point or an out-of-range point id.
  std::size_t triangulatedPolygons = 0; ///< Concave or non-planar inputs split into triangles.
  std::size_t pieces = 0;               ///< Convex planar polygons after normalisation.

  // Per sort.
  std::size_t fragments = 0; ///< Output fragments (== Result::fragments.size()).
  std::size_t pairs = 0;     ///< (head, other) pairs compared.
  TestCount depthExtent;     ///< (1); `passed` counts the scans it ended.
  TestCount screenExtent;    ///< (2)
  TestCount behindPlane;     ///< (3) P on the far side of Q's plane.
  TestCount inFrontOfPlane;  ///< (4) Q on the near side of P's plane.
  TestCount projection;      ///< (5)
  TestCount swapped;         ///< (1') (3') (4') after all of (1)-(5) failed.
  std::size_t edgeOnPairs = 0;          ///< Pairs decided because one of them is edge-on.
  std::size_t undecidedProjections = 0; ///< (5) not decidable (perspective), taken as overlap.
  std::size_t moves = 0;                ///< Fragments moved to the head of the list.
  std::size_t splits = 0;               ///< Each adds one fragment.
  std::size_t conformingVertices = 0;   ///< Split points inserted into fragment edges.
  std::size_t intersectionSplits = 0;   ///< Neither of the pair may go first.
  std::size_t cyclesResolved = 0;       ///< Splits made because a marked fragment had to move.
  std::size_t fallbackSplits = 0;       ///< Cycle without a straddling pair: bisected.
  std::size_t forcedEmissions = 0;      ///< Split cap reached: emitted unresolved.
  double tolerance = 0.0;               ///< Absolute plane tolerance used.
  double sortSeconds = 0.0;             ///< Wall time of the sort (excluding normalisation).
};

/// One view's order. Plain data, like bsp::Tree.
struct Result
{
  /// Back to front: fragments[0] is drawn first. Convex planar polygons, `source` = input id.
  std::vector<bsp::Fragment> fragments;
  std::vector<std::uint32_t> fragmentVertices;
  std::vector<glm::dvec3> points;         ///< Input points (same ids), then split points.
  std::size_t inputPointCount = 0;
  std::vector<bsp::SplitPoint> splitPoints; ///< splitPoints[i] describes inputPointCount + i.
  Statistics statistics;
};

/**
 * Normalises a mesh once and sorts it for any number of views. Not thread-safe (sort() reuses
 * scratch memory); use one Sorter per thread. The mesh is copied (points only), so it need not
 * outlive the Sorter.
 */
class Sorter
{
public:
  explicit Sorter(const PolygonMesh& mesh, const Config& config = {});
  ~Sorter();
  Sorter(Sorter&&) noexcept;
  Sorter& operator=(Sorter&&) noexcept;
  Sorter(const Sorter&) = delete;
  Sorter& operator=(const Sorter&) = delete;

  /// Sorts for `view` into `result` (its memory is reused across calls).
  void sort(const View& view, Result& result);
  Result sort(const View& view);

  /// Normalisation statistics (the per-sort fields are zero).
  const Statistics& normalisation() const;

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};

/// One-shot convenience: Sorter(mesh, config).sort(view).
Result sort(const PolygonMesh& mesh, const View& view, const Config& config = {});

} // namespace painter
} // namespace scenevis

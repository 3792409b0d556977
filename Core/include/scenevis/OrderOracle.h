#pragma once
/**
 * @file OrderOracle.h
 * @brief Brute-force judge of a back-to-front visibility order, for tests and debugging.
 *
 * Definition. An order of polygons is a correct back-to-front order for a View when, for every pair
 * A, B such that some ray from the viewer passes through the interiors of both, the polygon hit
 * farther along that ray comes first. Pairs that are coplanar over their common rays (within the
 * depth tolerance below) impose no constraint, and neither do pairs that only touch (an overlap
 * of projected area or width below the tolerances, e.g. neighbours sharing an edge).
 *
 * Method. Rays are found by projection:
 * - Perspective: the eye may be inside the geometry, so rays go in every direction. The sphere of
 *   directions is covered by the six faces of a cube map around the eye; every polygon is
 *   clipped to each face's 90-degree frustum (and to a near plane at a tiny distance in front of
 *   the eye) and projected centrally onto the face. A polygon that passes behind the eye is
 *   thereby split among the faces it is seen through, and a polygon entirely behind one face's
 *   frustum is not seen there: two polygons on opposite sides of the eye share no ray and get no
 *   constraint.
 * - Parallel: one orthographic projection along the view direction; every polygon is seen (the
 *   viewer is at infinity behind the scene).
 * In each projection the two projected convex polygons are intersected (Sutherland-Hodgman). When
 * the intersection has area, sample rays are cast through its vertex mean (an interior point that,
 * unlike the area centroid, stays accurate for thin overlaps) and through the points halfway from
 * there to its vertices, and the hit distances on the two polygons' planes are compared. The pair
 * is violated when at least one sample sees the polygon that comes later in the order strictly
 * farther. For non-intersecting polygons the depth relation is the same over the whole overlap, so
 * every sample agrees and one would suffice (BSP fragments: set samplesPerOverlap = 1 for speed).
 * For polygons that interpenetrate (an unsplit soup) the samples can disagree; such a pair admits
 * no correct order and is reported as violated whatever the order (and counted in
 * OracleReport::conflictingPairs). Samples are finitely many, so a penetration confined to a thin
 * rim of the overlap can be missed.
 *
 * Trust. The search above runs in double precision and can be fooled by its own rounding (found by
 * Core/Fuzz: an eye on, or within 1e-12 of, a plane that two fragments touch from either side; an
 * eye thousands of scene diagonals away; slivers and specks whose plane, fitted through rounded
 * vertices, is tilted). Two rules make every reported relation rest on a real ray:
 * 1. Witness re-check. Every sample ray that would constrain a pair is re-cast in long double
 *    against both polygons' actual vertices (taken relative to the local origin in long double,
 *    planes refitted in long double). It counts only when it hits both polygons' interiors at
 *    least depthTolerance away from every edge (point-in-convex-polygon test in each polygon's
 *    plane), in front of the eye (perspective), and the perpendicular separation recomputed from
 *    those hits exceeds depthTolerance plus tilt(A) * (gap + extent(A)) + tilt(B) * (gap +
 *    extent(B)), gap being the distance between the two hits (see rule 2 for tilt). Dropped rays
 *    are counted in OracleReport::unconfirmedRays; the witness reported by relate() is always a
 *    confirmed ray.
 * 2. Untrusted planes. A polygon's fitted plane is uncertain by the angle
 *      tilt = (8 eps extent + 2 max(u |c|, r)) / w,
 *    where extent is the diagonal of its bounding box, w = 2 area / extent its width, u = eps / 2
 *    the unit roundoff, |c| its largest absolute coordinate (its vertices are only known to
 *    u |c|), and r the plane-fit residual (largest distance of a vertex from the fitted plane).
 *    When tilt * (scene diagonal) exceeds 64 depth tolerances (the sliver 1.65 x 1.5e-10 and the
 *    1e-6 speck at 1e7 of the fuzzer are far beyond; a 2e-3-wide polygon at 1e7 in a 0.03 scene is
 *    well within), the polygon imposes no constraint at all and is counted in
 *    OracleReport::untrustedPolygons. Below that, rule 1's tilt slack covers it.
 * So a reported violation is always witnessed by a ray that, in long double, clearly passes
 * through both polygons as given; the price is that relations closer than these margins (rays
 * grazing an edge, thin or ill-conditioned polygons) go unreported.
 *
 * Candidate pairs come from a sweep over the projected bounding boxes, so the cost is about
 * O(n log n + overlapping pairs) per projection; a few thousand polygons take well under a second.
 *
 * Tolerances (all in OracleConfig):
 * - Depth: a sample constrains the pair only when each hit point is farther than `depthTolerance`
 *   from the other polygon's plane: |tA - tB| * min(|cos A|, |cos B|) > depthTolerance, with t
 *   the distance along the ray and cos the cosine between the ray and a polygon's normal. This is
 *   a distance perpendicular to the planes, the kind of distance a BSP classifies points with, so
 *   it does not blow up for grazing rays. depthTolerance = relativeDepthTolerance * (the diagonal
 *   of the bounds of all polygons) + 16 * DBL_EPSILON * (largest absolute coordinate): the second
 *   term is the resolution of the input coordinates themselves, so a scene placed at 1e7 is judged
 *   as strictly as its coordinates allow and no stricter. Keep relativeDepthTolerance above the
 *   BSP's own relative tolerance (1e-10 by default), which is free to treat points that close to
 *   a plane as lying on it.
 * - Edge-on: a polygon whose plane passes within depthTolerance of the eye (perspective), or
 *   whose extent along the view direction is within depthTolerance (parallel), is seen edge-on
 *   and constrains nothing: its image is thinner than its own positional uncertainty. This is
 *   what makes an eye placed exactly on a partition plane judgeable.
 * - Area and width: an overlap counts when its projected area exceeds relativeAreaTolerance times
 *   the smaller of the two projected areas (and a tiny absolute floor), and when its width (area /
 *   diameter), carried into the scene at the nearer hit distance, exceeds depthTolerance. So
 *   polygons that only touch up to rounding (a shared edge, a common line through the eye, a
 *   cube-map face border) get no constraint, even when one image is itself a rounding sliver.
 *
 * Input polygons must be planar and convex (every BSP fragment is); non-convex polygons must be
 * triangulated by the caller. Polygons with fewer than 3 points, zero area or non-finite points
 * cover no ray and are ignored (they may still appear in the order).
 *
 * Coordinates are taken relative to the eye (perspective) or the centre of the bounds (parallel)
 * before any arithmetic; subtracting nearby doubles is exact, so a model at 1e7 loses nothing.
 */

#include "scenevis/BspTree.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/View.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace oracle
{

/// A polygon as a loop of points (planar, convex; the closing edge is implicit).
using Polygon = std::vector<glm::dvec3>;

struct OracleConfig
{
  /// Depth tolerance relative to the diagonal of the scene bounds (see the file comment).
  double relativeDepthTolerance = 1e-9;
  /// Minimum overlap area relative to the smaller projected area of the pair.
  double relativeAreaTolerance = 1e-9;
  /// Rays cast per overlap region: the centroid, then up to samplesPerOverlap - 1 points halfway
  /// to the overlap's vertices (spread evenly over them). 1 is enough for non-intersecting inputs.
  int samplesPerOverlap = 9;
};

/// A pair in the wrong order: `farther` was hit farther along some ray but comes later.
struct Violation
{
  std::uint32_t farther;
  std::uint32_t nearer;
};

struct OracleReport
{
  /// At most one entry per unordered pair, sorted by (farther, nearer).
  std::vector<Violation> violations;
  /// Pairs with at least one sample ray that constrains their order.
  std::size_t constrainedPairs = 0;
  /// Pairs seen in both depth orders (interpenetrating): violated by every order.
  std::size_t conflictingPairs = 0;
  /// The absolute depth tolerance that was used.
  double depthTolerance = 0.0;
  /// Polygons whose fitted plane is too uncertain to judge (rule 2): they constrain nothing.
  std::size_t untrustedPolygons = 0;
  /// Sample rays that constrained a pair in double precision but failed the long double re-cast
  /// (rule 1) and were dropped. Diagnostic: such rays graze an edge or ride on rounding.
  std::size_t unconfirmedRays = 0;

  bool ok() const { return violations.empty(); }
};

/**
 * Judges `order` (a permutation of 0 .. polygons.size()-1, back to front: first drawn first) for
 * `view`. Throws std::invalid_argument when `order` is not such a permutation.
 */
OracleReport checkOrder(const std::vector<Polygon>& polygons,
  const std::vector<std::uint32_t>& order, const View& view, const OracleConfig& config = {});

/// The same for the polygons of a mesh (see polygonsOf).
OracleReport checkOrder(const PolygonMesh& mesh, const std::vector<std::uint32_t>& order,
  const View& view, const OracleConfig& config = {});

/// The depth relation of one pair, for debugging a reported violation.
enum class Relation
{
  Unconstrained, ///< No common ray with area, or coplanar within the tolerance.
  FirstFarther,  ///< The first polygon must be drawn before the second.
  SecondFarther, ///< The second polygon must be drawn before the first.
  Conflicting    ///< Both seen (interpenetrating): no order is correct.
};

struct PairRelation
{
  Relation relation = Relation::Unconstrained;
  /// A point of the first polygon where the (first found) constraining ray hits it.
  glm::dvec3 witness{ 0.0 };
  /// Perpendicular separation of the hit points at the witness ray (see depth tolerance).
  double separation = 0.0;
};

/**
 * Relation of `a` and `b` for `view`. The depth tolerance is derived from these two polygons only,
 * so near the tolerance it can differ from the verdict of checkOrder on a larger scene.
 */
PairRelation relate(
  const Polygon& a, const Polygon& b, const View& view, const OracleConfig& config = {});

/// Every polygon of `mesh` as a point loop, in polygon id order.
std::vector<Polygon> polygonsOf(const PolygonMesh& mesh);

/// Every fragment of `tree` as a point loop, in fragment id order (the ids bsp::order emits).
std::vector<Polygon> fragmentPolygons(const bsp::Tree& tree);

} // namespace oracle
} // namespace scenevis

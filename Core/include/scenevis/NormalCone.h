#pragma once
/**
 * @file NormalCone.h
 * @brief Normal cones for clustered back-face culling (Shirman & Abi-Ezzi 1993).
 *
 * A cluster of triangles whose unit normals all lie within half-angle alpha of an axis a is
 * entirely back-facing from eye e when every point p of the cluster satisfies
 * angle(a, p - e) < 90 deg - alpha: then angle(n, p - e) < 90 deg for every normal n, i.e.
 * dot(n, e - p) < 0. With the cluster inside a sphere (c, r) at distance D = |c - e| > r,
 * angle(a, p - e) <= theta + asin(r / D) with theta = angle(a, c - e), and since
 * sin(alpha + beta) <= sin(alpha) + sin(beta), the trig-free sufficient condition is
 *
 *     dot(a, c - e) > D * sin(alpha) + r            (strict; cf. meshoptimizer's
 *                                                    meshopt_computeClusterBounds cone test)
 *
 * which holds for perspective projection without any approximation: no front-facing triangle is
 * ever culled. For a parallel projection with direction of projection v (into the scene) the
 * cluster is back-facing when dot(a, v) > sin(alpha).
 *
 * The cone is only meaningful for geometry drawn with back-face culling (GL_CULL_FACE, back
 * faces), with counter-clockwise front faces, and it must be computed from the points as they
 * are drawn (world space, after the actor's transform: a mirroring transform flips the winding,
 * which a cone computed from transformed points takes into account). Closed surfaces have normals
 * in all directions, so a cone over a whole closed part never culls; cones pay off on clusters
 * (patches of some tens to hundreds of triangles) and on open surfaces.
 *
 * Conservativeness margins: sin(alpha) is rounded up by a relative 1e-9 and the test requires a
 * margin of 1e-9 * (D + r), which covers the rounding of the double-precision arithmetic here.
 */

#include "scenevis/PolygonMesh.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace culling
{

struct NormalCone
{
  glm::dvec3 axis{ 0.0, 0.0, 1.0 }; ///< unit axis
  /// sin of the half-angle; > 1 means "at least a hemisphere": the cone never culls.
  double sinHalfAngle = 2.0;

  bool canCull() const { return sinHalfAngle < 1.0; }
  /// The cone that never culls (empty input, hemisphere or more, non-finite normals).
  static NormalCone none() { return NormalCone{}; }
};

/**
 * Cone of the given normals (any length > 0; zero-length ones are ignored: a triangle with
 * exactly zero area draws no pixels). Non-finite normals give NormalCone::none().
 * The axis is the normalised sum of the unit normals; alpha the largest angle to it.
 */
NormalCone normalConeOf(const std::vector<glm::dvec3>& normals);

/// Cone of the triangles of a fan triangulation of polygons [first, first + count) of @p mesh.
NormalCone normalConeOf(const PolygonMesh& mesh, std::size_t first, std::size_t count);

/// A cone containing both cones (none() if either is none() or they span a hemisphere).
NormalCone merge(const NormalCone& a, const NormalCone& b);

/// Whether every triangle of a cluster with cone @p cone inside sphere (@p center, @p radius)
/// faces away from the perspective eye @p eye (conservative: false when in doubt).
bool backFacingFromEye(const NormalCone& cone,
  const glm::dvec3& center,
  double radius,
  const glm::dvec3& eye);

/// Same for a parallel projection along @p directionOfProjection (unit, into the scene).
bool backFacingAlong(const NormalCone& cone, const glm::dvec3& directionOfProjection);

/// Reference per-triangle test: whether triangle (a, b, c) (counter-clockwise = front) faces
/// the eye, i.e. dot(cross(b - a, c - a), eye - a) > 0.
bool triangleFrontFacing(const glm::dvec3& a,
  const glm::dvec3& b,
  const glm::dvec3& c,
  const glm::dvec3& eye);

} // namespace culling
} // namespace scenevis

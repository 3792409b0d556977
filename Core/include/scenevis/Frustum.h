#pragma once
/**
 * @file Frustum.h
 * @brief View frustum planes from a view-projection matrix and the p-/n-vertex box test.
 *
 * Planes are extracted from the clip-from-world matrix (Gribb & Hartmann) in double precision and
 * normalised, so plane values are signed Euclidean distances. A point p is on the inner side of
 * plane (n, d) when dot(n, p) + d >= 0. OpenGL clip conventions: -w <= x, y, z <= w (VTK's
 * vtkCamera::GetCompositeProjectionTransformMatrix(aspect, -1, 1) produces such a matrix; VTK
 * stores it row-major, glm column-major, so transpose when converting).
 *
 * Box test (the "n-vertex / p-vertex" method): for plane (n, d) the p-vertex is the box corner
 * farthest along n, the n-vertex the nearest one. p-vertex outside -> the whole box is outside;
 * n-vertex inside -> the whole box is inside that plane and a child box (contained in this one)
 * need not test it again ("plane masking"). Both values are computed with the same expression
 * `((n.x * x + n.y * y) + n.z * z) + d`, whose floating-point result is monotone in each corner
 * coordinate (rounding is monotone), so masking and hierarchical culling give results that are
 * bit-for-bit identical to testing every box against all six planes. Tests rely on that.
 */

#include "scenevis/PolygonMesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace culling
{

/// Plane order in Frustum::planes.
enum FrustumPlane : int
{
  kLeft = 0,
  kRight,
  kBottom,
  kTop,
  kNear,
  kFar,
  kPlaneCount
};

/// Bit mask with all six plane bits set: nothing known yet about a box.
constexpr std::uint8_t kAllPlanes = 0x3F;

struct Frustum
{
  /// (n, d) with |n| = 1; inside when dot(n, p) + d >= 0. Order: FrustumPlane.
  std::array<glm::dvec4, 6> planes{};

  /// Planes of the clip-from-world matrix @p clipFromWorld (glm convention: clip = M * p).
  /// A degenerate matrix gives a frustum for which valid() is false.
  static Frustum fromViewProjection(const glm::dmat4& clipFromWorld);

  /// Same, from VTK's row-major 16 doubles (vtkMatrix4x4::GetData()).
  static Frustum fromRowMajor(const double m[16]);

  /// All plane coefficients finite and every normal of unit length (not a degenerate matrix).
  bool valid() const;
};

/// Signed distance of the p-vertex (corner farthest along the normal); < 0: box outside.
inline double pVertexDistance(const glm::dvec4& p, const glm::dvec3& lo, const glm::dvec3& hi)
{
  const double x = p.x >= 0.0 ? hi.x : lo.x;
  const double y = p.y >= 0.0 ? hi.y : lo.y;
  const double z = p.z >= 0.0 ? hi.z : lo.z;
  return ((p.x * x + p.y * y) + p.z * z) + p.w;
}

/// Signed distance of the n-vertex (corner nearest along the normal); >= 0: box fully inside.
inline double nVertexDistance(const glm::dvec4& p, const glm::dvec3& lo, const glm::dvec3& hi)
{
  const double x = p.x >= 0.0 ? lo.x : hi.x;
  const double y = p.y >= 0.0 ? lo.y : hi.y;
  const double z = p.z >= 0.0 ? lo.z : hi.z;
  return ((p.x * x + p.y * y) + p.z * z) + p.w;
}

/// Reference test without masking: whether the box is outside any of the six planes.
bool boxOutside(const Frustum& frustum, const glm::dvec3& lo, const glm::dvec3& hi);

/**
 * Masked test with temporal coherence. Only planes whose bit is set in @p mask are tested;
 * the plane @p hint (the one that culled this box last time) is tested first.
 * @return false when the box is outside a tested plane (then @p hint is set to that plane);
 *         true otherwise, with the bits of planes the box is fully inside cleared from @p mask.
 */
inline bool testBoxMasked(const Frustum& frustum,
  const glm::dvec3& lo,
  const glm::dvec3& hi,
  std::uint8_t& mask,
  std::uint8_t& hint)
{
  // Coherence: a box culled last frame is most likely culled by the same plane this frame.
  const int first = hint < kPlaneCount ? hint : 0;
  if ((mask >> first) & 1u)
  {
    if (pVertexDistance(frustum.planes[first], lo, hi) < 0.0)
    {
      return false;
    }
  }
  for (int i = 0; i < kPlaneCount; ++i)
  {
    const auto bit = static_cast<std::uint8_t>(1u << i);
    if (!(mask & bit))
    {
      continue;
    }
    const glm::dvec4& plane = frustum.planes[i];
    if (i != first && pVertexDistance(plane, lo, hi) < 0.0)
    {
      hint = static_cast<std::uint8_t>(i);
      return false;
    }
    if (nVertexDistance(plane, lo, hi) >= 0.0)
    {
      mask = static_cast<std::uint8_t>(mask & ~bit);
    }
  }
  return true;
}

/**
 * Structure-of-arrays axis-aligned boxes (the input of the cullers; cf. filament's Culler).
 * Box i is [minX[i], maxX[i]] x [minY[i], maxY[i]] x [minZ[i], maxZ[i]].
 */
struct BoxArrays
{
  std::vector<double> minX, minY, minZ, maxX, maxY, maxZ;

  std::size_t size() const { return minX.size(); }
  void resize(std::size_t n);
  void set(std::size_t i, const Box& box);
  Box get(std::size_t i) const;
  void push_back(const Box& box);
};

/**
 * Flat, stateless frustum cull of @p count boxes (the brute-force reference and the baseline the
 * hierarchy is measured against): visible[i] = 1 unless box i is outside a plane.
 * Boxes with NaN coordinates are kept (comparisons with NaN are false).
 */
void cullBoxesFlat(const Frustum& frustum, const BoxArrays& boxes, std::uint8_t* visible);

} // namespace culling
} // namespace scenevis

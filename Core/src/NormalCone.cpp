#include "scenevis/NormalCone.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace scenevis
{
namespace culling
{

namespace
{
constexpr double kRelativeMargin = 1e-9;

bool finite(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// A sine rounded up so the cone never shrinks by rounding.
double roundUp(double s)
{
  return s * (1.0 + kRelativeMargin) + kRelativeMargin;
}

/// Angle between two unit vectors; atan2 of |cross| and dot is accurate near 0 (acos is not:
/// one ulp of a cosine near 1 is 1.5e-8 rad).
double angleBetween(const glm::dvec3& a, const glm::dvec3& b)
{
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}
} // namespace

NormalCone normalConeOf(const std::vector<glm::dvec3>& normals)
{
  glm::dvec3 sum(0.0);
  std::size_t used = 0;
  for (const glm::dvec3& n : normals)
  {
    if (!finite(n))
    {
      return NormalCone::none();
    }
    const double len = glm::length(n);
    if (len == 0.0)
    {
      continue; // zero area: rasterises nothing
    }
    sum += n / len;
    ++used;
  }
  const double sumLength = glm::length(sum);
  if (used == 0 || !(sumLength > 1e-12 * static_cast<double>(used)))
  {
    return NormalCone::none();
  }
  NormalCone cone;
  cone.axis = sum / sumLength;
  double maxSin = 0.0;
  for (const glm::dvec3& n : normals)
  {
    const double len = glm::length(n);
    if (len == 0.0)
    {
      continue;
    }
    const glm::dvec3 unit = n / len;
    // Half-angle >= 90 deg (or so close that rounding could matter): never cull.
    if (!(glm::dot(unit, cone.axis) > 1e-6))
    {
      return NormalCone::none();
    }
    // |cross| is the sine, accurate for small angles (sqrt(1 - cos^2) is not).
    maxSin = std::max(maxSin, glm::length(glm::cross(unit, cone.axis)));
  }
  cone.sinHalfAngle = roundUp(maxSin);
  if (!(cone.sinHalfAngle < 1.0))
  {
    return NormalCone::none();
  }
  return cone;
}

NormalCone normalConeOf(const PolygonMesh& mesh, std::size_t first, std::size_t count)
{
  std::vector<glm::dvec3> normals;
  normals.reserve(count);
  for (std::size_t i = first; i < first + count && i < mesh.polygonCount(); ++i)
  {
    const std::uint32_t* ids = mesh.polygon(i);
    const std::uint32_t size = mesh.polygonSize(i);
    for (std::uint32_t k = 1; k + 1 < size; ++k)
    {
      const glm::dvec3& a = mesh.points[ids[0]];
      normals.push_back(glm::cross(mesh.points[ids[k]] - a, mesh.points[ids[k + 1]] - a));
    }
  }
  return normalConeOf(normals);
}

NormalCone merge(const NormalCone& a, const NormalCone& b)
{
  if (!a.canCull() || !b.canCull())
  {
    return NormalCone::none();
  }
  const glm::dvec3 sum = a.axis + b.axis;
  const double len = glm::length(sum);
  if (!(len > 1e-9))
  {
    return NormalCone::none();
  }
  NormalCone cone;
  cone.axis = sum / len;
  // Half-angle: the farther of the two cones' rims from the new axis. Computed with angles
  // (build time only) and rounded outwards.
  auto rim = [&cone](const NormalCone& c)
  {
    return angleBetween(cone.axis, c.axis) + std::asin(std::min(1.0, c.sinHalfAngle));
  };
  const double angle = std::max(rim(a), rim(b)) * (1.0 + kRelativeMargin) + kRelativeMargin;
  const double halfPi = 1.57079632679489661923;
  if (!(angle < halfPi - 1e-6))
  {
    return NormalCone::none();
  }
  cone.sinHalfAngle = roundUp(std::sin(angle));
  return cone;
}

bool backFacingFromEye(const NormalCone& cone,
  const glm::dvec3& center,
  double radius,
  const glm::dvec3& eye)
{
  if (!cone.canCull() || !(radius >= 0.0))
  {
    return false;
  }
  const glm::dvec3 v = center - eye;
  const double distance = glm::length(v);
  if (!(distance > radius))
  {
    return false; // the eye may be inside the cluster's sphere
  }
  const double lhs = glm::dot(v, cone.axis);
  const double rhs = distance * cone.sinHalfAngle + radius;
  return lhs > rhs + kRelativeMargin * (distance + radius);
}

bool backFacingAlong(const NormalCone& cone, const glm::dvec3& directionOfProjection)
{
  if (!cone.canCull())
  {
    return false;
  }
  const double len = glm::length(directionOfProjection);
  if (!(len > 0.0) || !std::isfinite(len))
  {
    return false;
  }
  return glm::dot(cone.axis, directionOfProjection) / len > cone.sinHalfAngle + kRelativeMargin;
}

bool triangleFrontFacing(const glm::dvec3& a,
  const glm::dvec3& b,
  const glm::dvec3& c,
  const glm::dvec3& eye)
{
  return glm::dot(glm::cross(b - a, c - a), eye - a) > 0.0;
}

} // namespace culling
} // namespace scenevis

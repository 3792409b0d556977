#pragma once
/**
 * @file View.h
 * @brief A viewpoint for visibility ordering: an eye point (perspective) or a direction (parallel).
 *
 * Both are one homogeneous point: a perspective eye e is (e, 1); a parallel view looking along
 * direction v is the point at infinity behind the scene, (-v, 0). The side of a plane (n, d) the
 * viewer is on is then the sign of dot((n, d), eye) for both kinds alike.
 */

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace scenevis
{

struct View
{
  glm::dvec4 eye{ 0.0, 0.0, 0.0, 1.0 };

  static View perspective(const glm::dvec3& eyePoint) { return View{ glm::dvec4(eyePoint, 1.0) }; }
  /// `direction`: the direction of projection, from the viewer into the scene.
  static View parallel(const glm::dvec3& direction)
  {
    return View{ glm::dvec4(-glm::normalize(direction), 0.0) };
  }
  bool isParallel() const { return eye.w == 0.0; }
  /// The same view with the eye expressed relative to `origin` (planes stored relative to it).
  View relativeTo(const glm::dvec3& origin) const
  {
    return View{ glm::dvec4(glm::dvec3(eye) - origin * eye.w, eye.w) };
  }
};

} // namespace scenevis

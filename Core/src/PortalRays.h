// The rays of PortalGraph::inside() (module-private): three fixed directions in general
// position, and for each a basis of the plane perpendicular to it, in which a polygon's
// projection along the ray decides whether the ray's line can meet it.
#ifndef scenevis_PortalRays_h
#define scenevis_PortalRays_h

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace scenevis
{
namespace portals
{
namespace rays
{
constexpr int kCount = 3;

/// Direction @p k (0 to 2) of the inside test's rays.
inline const glm::dvec3& direction(int k)
{
  static const glm::dvec3 dirs[kCount] = { glm::normalize(glm::dvec3(0.5377, 0.8191, 0.2003)),
    glm::normalize(glm::dvec3(-0.7071, 0.3156, 0.6321)),
    glm::normalize(glm::dvec3(0.1234, -0.5871, -0.8001)) };
  return dirs[k];
}

/// Two unit vectors spanning the plane perpendicular to direction(@p k): a point x projects to
/// (dot(u, x), dot(v, x)), and every point of a ray from p projects where p does.
inline void basis(int k, glm::dvec3& u, glm::dvec3& v)
{
  const glm::dvec3& d = direction(k);
  u = glm::normalize(glm::cross(d, glm::dvec3(0.0, 0.0, 1.0)));
  v = glm::cross(d, u);
}
} // namespace rays
} // namespace portals
} // namespace scenevis

#endif

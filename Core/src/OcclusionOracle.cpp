#include "scenevis/OcclusionOracle.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace scenevis
{
namespace occlusion
{

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The ray through a pixel centre from the near plane (t = 0) to the far plane (t = 1).
struct Ray
{
  glm::dvec3 origin, direction;
};

/// Nearest t in [0, 1] where the ray meets the triangle (Moller-Trumbore, both faces), or +inf.
double hitTriangle(const Ray& r, const OracleTriangle& t)
{
  const glm::dvec3 e1 = t.b - t.a, e2 = t.c - t.a;
  const glm::dvec3 p = glm::cross(r.direction, e2);
  const double det = glm::dot(e1, p);
  if (!(std::abs(det) > 1e-300))
  {
    return kInf;
  }
  const glm::dvec3 s = r.origin - t.a;
  const double u = glm::dot(s, p) / det;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(r.direction, q) / det;
  const double hit = glm::dot(e2, q) / det;
  if (!(u >= 0.0 && v >= 0.0 && u + v <= 1.0 && hit >= 0.0 && hit <= 1.0))
  {
    return kInf;
  }
  return hit;
}

/// Nearest t in [0, 1] of the ray inside the box, or +inf.
double hitBox(const Ray& r, const glm::dvec3& lo, const glm::dvec3& hi)
{
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k)
  {
    if (r.direction[k] == 0.0)
    {
      if (r.origin[k] < lo[k] || r.origin[k] > hi[k])
      {
        return kInf;
      }
      continue;
    }
    double a = (lo[k] - r.origin[k]) / r.direction[k];
    double b = (hi[k] - r.origin[k]) / r.direction[k];
    if (a > b)
    {
      std::swap(a, b);
    }
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1 ? t0 : kInf;
}
} // namespace

namespace
{
Ray pixelRay(const glm::dmat4& worldFromClip, int width, int height, int i, int j)
{
  const double x = (i + 0.5) / width * 2.0 - 1.0;
  const double y = (j + 0.5) / height * 2.0 - 1.0;
  const glm::dvec4 n = worldFromClip * glm::dvec4(x, y, -1.0, 1.0);
  const glm::dvec4 f = worldFromClip * glm::dvec4(x, y, 1.0, 1.0);
  const glm::dvec3 p0 = glm::dvec3(n) / n.w, p1 = glm::dvec3(f) / f.w;
  return Ray{ p0, p1 - p0 };
}
} // namespace

std::vector<int> nearestBoxPerPixel(const glm::dmat4& clipFromWorld, int width, int height,
  const std::vector<std::pair<glm::dvec3, glm::dvec3>>& boxes)
{
  const glm::dmat4 worldFromClip = glm::inverse(clipFromWorld);
  std::vector<int> nearest(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), -1);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const Ray r = pixelRay(worldFromClip, width, height, i, j);
      double best = kInf;
      for (std::size_t b = 0; b < boxes.size(); ++b)
      {
        const double t = hitBox(r, boxes[b].first, boxes[b].second);
        if (t < best)
        {
          best = t;
          nearest[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + i] =
            static_cast<int>(b);
        }
      }
    }
  }
  return nearest;
}

int visiblePixels(const glm::dmat4& clipFromWorld, int width, int height,
  const std::vector<OracleTriangle>& occluders, const glm::dvec3& lo, const glm::dvec3& hi)
{
  const glm::dmat4 worldFromClip = glm::inverse(clipFromWorld);
  int visible = 0;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const Ray r = pixelRay(worldFromClip, width, height, i, j);
      const double box = hitBox(r, lo, hi);
      if (box == kInf)
      {
        continue;
      }
      double nearest = kInf;
      for (const OracleTriangle& t : occluders)
      {
        nearest = std::min(nearest, hitTriangle(r, t));
      }
      visible += box < nearest ? 1 : 0;
    }
  }
  return visible;
}

} // namespace occlusion
} // namespace scenevis

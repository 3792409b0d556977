#include "PolygonPieces.h"

#include "Triangulate.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>

namespace scenevis
{
namespace detail
{
namespace
{
constexpr double kTwoPi = 6.28318530717958647692;

/// Appends the piece unless it is a sliver; see splitIntoPieces().
bool addIfValid(const std::vector<glm::dvec3>& local, double tolerance, std::uint32_t source,
  const std::uint32_t* ids, std::size_t count, PolygonPieces& out)
{
  const glm::dvec3 n = newellNormal(local.data(), ids, count);
  const double len = glm::length(n);
  double maxEdge = 0.0;
  glm::dvec3 centroid(0.0);
  for (std::size_t k = 0; k < count; ++k)
  {
    maxEdge = std::max(maxEdge, glm::length(local[ids[(k + 1) % count]] - local[ids[k]]));
    centroid += local[ids[k]];
  }
  // |n| = 2 * area, so this asks whether the polygon is thinner than the tolerance: such a sliver
  // has no meaningful plane and cannot be classified consistently.
  if (!(len > tolerance * maxEdge) || len == 0.0)
  {
    return false;
  }
  const glm::dvec3 unit = n / len;
  centroid /= static_cast<double>(count);
  out.plane.emplace_back(unit, -glm::dot(unit, centroid));
  out.source.push_back(source);
  out.count.push_back(static_cast<std::uint32_t>(count));
  out.verts.insert(out.verts.end(), ids, ids + count);
  return true;
}

/// Whether the polygon (2D, in its plane) turns left at every vertex and once in total.
bool isConvex(const std::vector<glm::dvec2>& p, double tolerance)
{
  const std::size_t m = p.size();
  double turning = 0.0;
  for (std::size_t k = 0; k < m; ++k)
  {
    const glm::dvec2 e1 = p[k] - p[(k + m - 1) % m];
    const glm::dvec2 e2 = p[(k + 1) % m] - p[k];
    const double c = cross2(e1, e2);
    if (c < -tolerance * std::max(glm::length(e1), glm::length(e2)))
    {
      return false;
    }
    turning += std::atan2(c, glm::dot(e1, e2));
  }
  // Star polygons turn left everywhere too, but more than once.
  return std::abs(turning - kTwoPi) < 1e-6;
}
} // namespace

void splitIntoPieces(const PolygonMesh& mesh, const std::vector<glm::dvec3>& local,
  double tolerance, PolygonPieces& out, PieceCounts& counts)
{
  const std::size_t pointCount = mesh.points.size();
  const std::size_t polygons = mesh.polygonCount();
  out.plane.reserve(out.plane.size() + polygons);
  out.source.reserve(out.source.size() + polygons);
  out.count.reserve(out.count.size() + polygons);
  out.verts.reserve(out.verts.size() + mesh.indices.size());
  std::vector<std::uint32_t> ids;
  std::vector<glm::dvec2> poly2d;
  std::vector<std::uint32_t> ring;
  std::vector<std::uint32_t> triangles;
  for (std::size_t i = 0; i < polygons; ++i)
  {
    const std::uint32_t* polygon = mesh.polygon(i);
    const std::uint32_t size = mesh.polygonSize(i);
    const auto source = static_cast<std::uint32_t>(i);
    bool valid = true;
    ids.clear();
    for (std::uint32_t k = 0; k < size && valid; ++k)
    {
      const std::uint32_t id = polygon[k];
      valid = id < pointCount;
      if (valid)
      {
        const glm::dvec3& p = mesh.points[id];
        valid = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      }
      if (valid && (ids.empty() || ids.back() != id))
      {
        ids.push_back(id);
      }
    }
    if (!valid)
    {
      ++counts.invalid;
      continue;
    }
    while (ids.size() > 1 && ids.back() == ids.front())
    {
      ids.pop_back();
    }
    const std::size_t m = ids.size();
    if (m < 3)
    {
      ++counts.degenerate;
      continue;
    }
    if (m == 3)
    {
      if (!addIfValid(local, tolerance, source, ids.data(), 3, out))
      {
        ++counts.degenerate;
      }
      continue;
    }
    const glm::dvec3 n = newellNormal(local.data(), ids.data(), m);
    const double len = glm::length(n);
    double maxEdge = 0.0;
    glm::dvec3 centroid(0.0);
    for (std::size_t k = 0; k < m; ++k)
    {
      maxEdge = std::max(maxEdge, glm::length(local[ids[(k + 1) % m]] - local[ids[k]]));
      centroid += local[ids[k]];
    }
    if (!(len > tolerance * maxEdge) || len == 0.0)
    {
      ++counts.degenerate;
      continue;
    }
    centroid /= static_cast<double>(m);
    const glm::dvec3 unit = n / len;
    const double d = -glm::dot(unit, centroid);
    bool planar = true;
    for (std::size_t k = 0; k < m && planar; ++k)
    {
      planar = std::abs(glm::dot(unit, local[ids[k]]) + d) <= tolerance;
    }
    glm::dvec3 u;
    glm::dvec3 v;
    planeBasis(unit, u, v);
    poly2d.resize(m);
    for (std::size_t k = 0; k < m; ++k)
    {
      const glm::dvec3 q = local[ids[k]] - centroid;
      poly2d[k] = glm::dvec2(glm::dot(q, u), glm::dot(q, v));
    }
    if (planar && isConvex(poly2d, tolerance))
    {
      addIfValid(local, tolerance, source, ids.data(), m, out);
      continue;
    }
    ++counts.triangulated;
    triangles.clear();
    earClip(poly2d, ring, triangles);
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
    {
      const std::uint32_t tri[3] = { ids[triangles[t]], ids[triangles[t + 1]],
        ids[triangles[t + 2]] };
      addIfValid(local, tolerance, source, tri, 3, out);
    }
  }
}

} // namespace detail
} // namespace scenevis

#include "scenevis/PolygonMesh.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace scenevis
{

void Box::extend(const glm::dvec3& p)
{
  lo = glm::min(lo, p);
  hi = glm::max(hi, p);
}

void Box::extend(const Box& b)
{
  if (!b.empty())
  {
    extend(b.lo);
    extend(b.hi);
  }
}

double Box::diagonal() const
{
  return empty() ? 0.0 : glm::length(hi - lo);
}

std::uint32_t PolygonMesh::addPoint(const glm::dvec3& p)
{
  points.push_back(p);
  return static_cast<std::uint32_t>(points.size() - 1);
}

std::uint32_t PolygonMesh::addPolygon(std::initializer_list<std::uint32_t> ids)
{
  return addPolygon(ids.begin(), ids.size());
}

std::uint32_t PolygonMesh::addPolygon(const std::uint32_t* ids, std::size_t count)
{
  indices.insert(indices.end(), ids, ids + count);
  offsets.push_back(static_cast<std::uint32_t>(indices.size()));
  return static_cast<std::uint32_t>(polygonCount() - 1);
}

std::uint32_t PolygonMesh::append(const PolygonMesh& other)
{
  const auto first = static_cast<std::uint32_t>(polygonCount());
  const auto base = static_cast<std::uint32_t>(points.size());
  points.insert(points.end(), other.points.begin(), other.points.end());
  indices.reserve(indices.size() + other.indices.size());
  for (std::uint32_t id : other.indices)
  {
    indices.push_back(id + base);
  }
  const std::uint32_t shift = offsets.back();
  for (std::size_t i = 1; i < other.offsets.size(); ++i)
  {
    offsets.push_back(other.offsets[i] + shift);
  }
  return first;
}

Box PolygonMesh::bounds() const
{
  Box box;
  for (const glm::dvec3& p : points)
  {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
    {
      box.extend(p);
    }
  }
  return box;
}

double PolygonMesh::area() const
{
  double sum = 0.0;
  for (std::size_t i = 0; i < polygonCount(); ++i)
  {
    sum += 0.5 * glm::length(newellNormal(points.data(), polygon(i), polygonSize(i)));
  }
  return sum;
}

glm::dvec3 newellNormal(const glm::dvec3* points, const std::uint32_t* ids, std::size_t count)
{
  glm::dvec3 n(0.0);
  if (count < 3)
  {
    return n;
  }
  // Relative to the first vertex: keeps the cross products small far from the origin.
  const glm::dvec3 origin = points[ids[0]];
  for (std::size_t i = 0; i < count; ++i)
  {
    const glm::dvec3 a = points[ids[i]] - origin;
    const glm::dvec3 b = points[ids[(i + 1) % count]] - origin;
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

} // namespace scenevis

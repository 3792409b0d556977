#pragma once
/**
 * @file PolygonMesh.h
 * @brief The VTK-free polygon soup every SceneVis algorithm consumes.
 *
 * Points are stored in double precision in the model's own coordinates; algorithms that need
 * precision far from the origin (CAD at 1e7) subtract a local origin themselves. Polygons are
 * stored CSR-style: polygon i uses `indices[offsets[i] .. offsets[i+1])`. This maps one-to-one onto
 * a vtkPoints + vtkCellArray pair, so the VTK layer converts without reordering.
 */

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace scenevis
{

/// Axis-aligned box; empty when `lo > hi` on any axis (the default).
struct Box
{
  glm::dvec3 lo{ 1e300, 1e300, 1e300 };
  glm::dvec3 hi{ -1e300, -1e300, -1e300 };

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const glm::dvec3& p);
  void extend(const Box& b);
  glm::dvec3 center() const { return (lo + hi) * 0.5; }
  /// Length of the diagonal; 0 for an empty box.
  double diagonal() const;
};

class PolygonMesh
{
public:
  std::vector<glm::dvec3> points;
  /// Size polygonCount()+1; offsets.front() == 0.
  std::vector<std::uint32_t> offsets{ 0 };
  std::vector<std::uint32_t> indices;

  std::size_t polygonCount() const { return offsets.size() - 1; }
  std::uint32_t polygonSize(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
  const std::uint32_t* polygon(std::size_t i) const { return indices.data() + offsets[i]; }

  std::uint32_t addPoint(const glm::dvec3& p);
  /// Appends a polygon over existing point ids; returns its id.
  std::uint32_t addPolygon(std::initializer_list<std::uint32_t> ids);
  std::uint32_t addPolygon(const std::uint32_t* ids, std::size_t count);
  /// Appends every polygon of `other`, offsetting point ids; returns the id of the first one.
  std::uint32_t append(const PolygonMesh& other);

  /// Bounds of the points that are finite (NaN/Inf points are ignored).
  Box bounds() const;
  /// Total area of all polygons (Newell's formula; exact for planar polygons).
  double area() const;
};

/// Newell's normal of a polygon given by point ids: length = 2 * area for planar polygons.
glm::dvec3 newellNormal(const glm::dvec3* points, const std::uint32_t* ids, std::size_t count);

} // namespace scenevis

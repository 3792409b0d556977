#include "scenevis/Frustum.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace scenevis
{
namespace culling
{

Frustum Frustum::fromViewProjection(const glm::dmat4& m)
{
  // Row i of M (glm stores columns): clip_i = dot(row_i, p). Inside: -w <= x, y, z <= w, i.e.
  // row3 + rowk >= 0 and row3 - rowk >= 0.
  auto row = [&m](int i) { return glm::dvec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
  const glm::dvec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
  Frustum f;
  f.planes[kLeft] = r3 + r0;
  f.planes[kRight] = r3 - r0;
  f.planes[kBottom] = r3 + r1;
  f.planes[kTop] = r3 - r1;
  f.planes[kNear] = r3 + r2;
  f.planes[kFar] = r3 - r2;
  for (glm::dvec4& p : f.planes)
  {
    const double len = glm::length(glm::dvec3(p));
    if (len > 0.0 && std::isfinite(len))
    {
      p /= len;
    }
    else
    {
      // Degenerate: make valid() false and never cull through this plane (NaN compares false).
      p = glm::dvec4(std::nan(""));
    }
  }
  return f;
}

Frustum Frustum::fromRowMajor(const double m[16])
{
  glm::dmat4 g(1.0);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      g[c][r] = m[r * 4 + c];
    }
  }
  return fromViewProjection(g);
}

bool Frustum::valid() const
{
  for (const glm::dvec4& p : planes)
  {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w))
    {
      return false;
    }
    if (std::abs(glm::length(glm::dvec3(p)) - 1.0) > 1e-9)
    {
      return false;
    }
  }
  return true;
}

bool boxOutside(const Frustum& frustum, const glm::dvec3& lo, const glm::dvec3& hi)
{
  for (const glm::dvec4& p : frustum.planes)
  {
    if (pVertexDistance(p, lo, hi) < 0.0)
    {
      return true;
    }
  }
  return false;
}

void BoxArrays::resize(std::size_t n)
{
  for (auto* v : { &minX, &minY, &minZ, &maxX, &maxY, &maxZ })
  {
    v->resize(n);
  }
}

void BoxArrays::set(std::size_t i, const Box& box)
{
  minX[i] = box.lo.x;
  minY[i] = box.lo.y;
  minZ[i] = box.lo.z;
  maxX[i] = box.hi.x;
  maxY[i] = box.hi.y;
  maxZ[i] = box.hi.z;
}

Box BoxArrays::get(std::size_t i) const
{
  Box b;
  b.lo = { minX[i], minY[i], minZ[i] };
  b.hi = { maxX[i], maxY[i], maxZ[i] };
  return b;
}

void BoxArrays::push_back(const Box& box)
{
  resize(size() + 1);
  set(size() - 1, box);
}

void cullBoxesFlat(const Frustum& frustum, const BoxArrays& boxes, std::uint8_t* visible)
{
  const std::size_t n = boxes.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const glm::dvec3 lo(boxes.minX[i], boxes.minY[i], boxes.minZ[i]);
    const glm::dvec3 hi(boxes.maxX[i], boxes.maxY[i], boxes.maxZ[i]);
    visible[i] = boxOutside(frustum, lo, hi) ? 0 : 1;
  }
}

} // namespace culling
} // namespace scenevis

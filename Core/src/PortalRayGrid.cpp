// PortalGraph::buildRayGrids(): the inside test's polygons bucketed per room and ray direction
// (see PortalGraph::RayGrid).
#include "scenevis/PortalGraph.h"

#include "PortalRays.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scenevis
{
namespace portals
{

void PortalGraph::buildRayGrids()
{
  this->RayGrids.assign(static_cast<std::size_t>(this->RoomCount) * rays::kCount, RayGrid());
  std::vector<double> lo, hi; // per polygon of the room: u0 v0 and u1 v1 of its projection
  for (std::int32_t room = 0; room < this->RoomCount; ++room)
  {
    const GraphRoom& r = this->Rooms[static_cast<std::size_t>(room)];
    if (r.polygonCount < kRayGridMinPolygons)
    {
      continue;
    }
    for (int d = 0; d < rays::kCount; ++d)
    {
      glm::dvec3 u, v;
      rays::basis(d, u, v);
      lo.assign(2 * std::size_t(r.polygonCount), std::numeric_limits<double>::infinity());
      hi.assign(2 * std::size_t(r.polygonCount), -std::numeric_limits<double>::infinity());
      double largest = 0.0; // of the coordinates, for the margin
      for (std::uint32_t i = 0; i < r.polygonCount; ++i)
      {
        const BoundaryPolygon& bp = this->Polygons[r.firstPolygon + i];
        const glm::dvec3* pts = this->PolygonPoints.data() + bp.first;
        const glm::dvec3 n(bp.plane);
        for (std::uint32_t k = 0; k < bp.count; ++k)
        {
          // The point, and the point moved along the dominant axis onto the polygon's plane:
          // parity() finds a crossing where the ray meets that plane inside the polygon's
          // outline in the other two axes, which the moved points' hull holds even where a
          // polygon is not quite planar.
          glm::dvec3 onPlane = pts[k];
          onPlane[bp.axis] -= (glm::dot(n, pts[k]) + bp.plane.w) / n[bp.axis];
          for (const glm::dvec3& x : { pts[k], onPlane })
          {
            const double pu = glm::dot(u, x), pv = glm::dot(v, x);
            lo[2 * i] = std::min(lo[2 * i], pu);
            lo[2 * i + 1] = std::min(lo[2 * i + 1], pv);
            hi[2 * i] = std::max(hi[2 * i], pu);
            hi[2 * i + 1] = std::max(hi[2 * i + 1], pv);
            largest = std::max({ largest, std::abs(x.x), std::abs(x.y), std::abs(x.z) });
          }
        }
      }
      // The margin: a crossing's point is computed with rounding of a few units of 1e-16 of the
      // coordinates and of the ray's length (within the room's bounds); 1e-6 is far above it.
      const double margin = 1e-6 * (largest + r.bounds.diagonal()) + this->Tolerance;
      double u0 = std::numeric_limits<double>::infinity(), v0 = u0, u1 = -u0, v1 = -u0;
      bool finiteBounds = true;
      for (std::uint32_t i = 0; i < r.polygonCount; ++i)
      {
        lo[2 * i] -= margin, lo[2 * i + 1] -= margin;
        hi[2 * i] += margin, hi[2 * i + 1] += margin;
        finiteBounds = finiteBounds && std::isfinite(lo[2 * i]) && std::isfinite(lo[2 * i + 1]) &&
          std::isfinite(hi[2 * i]) && std::isfinite(hi[2 * i + 1]);
        u0 = std::min(u0, lo[2 * i]), v0 = std::min(v0, lo[2 * i + 1]);
        u1 = std::max(u1, hi[2 * i]), v1 = std::max(v1, hi[2 * i + 1]);
      }
      if (!finiteBounds || !(u1 > u0 && v1 > v0))
      {
        continue; // no grid: every polygon is read
      }
      // About two polygons per cell, square cells, at most 256 per axis.
      const double side = std::max(u1 - u0, v1 - v0);
      const int cells = std::clamp(
        static_cast<int>(std::ceil(std::sqrt(0.5 * static_cast<double>(r.polygonCount)))), 1, 256);
      RayGrid& grid = this->RayGrids[static_cast<std::size_t>(room) * rays::kCount + d];
      grid.u0 = u0;
      grid.v0 = v0;
      grid.inverseCell = static_cast<double>(cells) / side;
      // A coordinate's cell is floor((c - origin) * inverseCell), as parity() computes it: that
      // is monotone in c, so a polygon listed in the cells of its bounds' ends is listed in the
      // cell of every point between them.
      auto cellOf = [&](double c, double origin, int count) {
        return std::clamp(
          static_cast<int>(std::floor((c - origin) * grid.inverseCell)), 0, count - 1);
      };
      grid.nu = std::clamp(static_cast<int>(std::floor((u1 - u0) * grid.inverseCell)) + 1, 1, 257);
      grid.nv = std::clamp(static_cast<int>(std::floor((v1 - v0) * grid.inverseCell)) + 1, 1, 257);
      const std::size_t cellCount = std::size_t(grid.nu) * std::size_t(grid.nv);
      grid.start.assign(cellCount + 1, 0);
      // Polygons whose projected bounds span many cells (long slanted slivers) could make the
      // lists quadratic in the polygons: past 64 entries per polygon, no grid.
      std::size_t entries = 0;
      for (std::uint32_t i = 0; i < r.polygonCount; ++i)
      {
        entries +=
          std::size_t(cellOf(hi[2 * i], u0, grid.nu) - cellOf(lo[2 * i], u0, grid.nu) + 1) *
          std::size_t(cellOf(hi[2 * i + 1], v0, grid.nv) - cellOf(lo[2 * i + 1], v0, grid.nv) + 1);
      }
      if (entries > 64u * std::size_t(r.polygonCount))
      {
        grid = RayGrid();
        continue;
      }
      for (int pass = 0; pass < 2; ++pass)
      {
        std::vector<std::uint32_t> next;
        if (pass == 1)
        {
          for (std::size_t c = 0; c < cellCount; ++c)
          {
            grid.start[c + 1] += grid.start[c];
          }
          next.assign(grid.start.begin(), grid.start.end() - 1);
          grid.polygons.resize(grid.start[cellCount]);
        }
        for (std::uint32_t i = 0; i < r.polygonCount; ++i)
        {
          const int a0 = cellOf(lo[2 * i], u0, grid.nu), a1 = cellOf(hi[2 * i], u0, grid.nu);
          const int b0 = cellOf(lo[2 * i + 1], v0, grid.nv),
                    b1 = cellOf(hi[2 * i + 1], v0, grid.nv);
          for (int b = b0; b <= b1; ++b)
          {
            for (int a = a0; a <= a1; ++a)
            {
              const std::size_t c = std::size_t(b) * std::size_t(grid.nu) + std::size_t(a);
              if (pass == 0)
              {
                ++grid.start[c + 1];
              }
              else
              {
                grid.polygons[next[c]++] = r.firstPolygon + i;
              }
            }
          }
        }
      }
    }
  }
}

} // namespace portals
} // namespace scenevis

#pragma once
// Test-only: an open floor of box rooms joined by portals, the scene of the exact traversal's
// sight-line test (TestPortalSightLines.cpp) and of its fuzz target (FuzzPortalTraversal.cpp).

#include "AxisQuad.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/PortalGraph.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <random>
#include <vector>

namespace scenevis
{
namespace portaltest
{

/// Variations of an open floor. The defaults make the floors the sight-line test always had.
struct OpenFloorOptions
{
  /// Chance that the face between two neighbouring cells is a portal (else a wall on each side).
  double portalProbability = 0.8;
  double storeyHeight = 3.0;
  /// Added to every coordinate once the floor is made (1e7: coordinates far from the origin, where
  /// the rounding is 2e-9 and the rooms a few units wide).
  glm::dvec3 offset{ 0.0 };
  /// Portals as openings inside their face (each side's margin 0 or 5..35 % of the face, drawn
  /// from a second generator), the rest of the face a wall on each side, instead of the whole
  /// face. Which faces are portals does not change: the same seed makes the same rooms.
  bool openings = false;
};

/**
 * An open floor as game levels have it: nx x ny cells of jittered widths (0.3 to 2.3), one
 * storey, every face between two cells either a portal (80 % by default: the whole face) or a
 * wall; exterior walls all round, a floor and a ceiling per cell. A room is reached along many
 * chains of portals whose cones nest, so the traversal's regions are often contained in others
 * (and merged), unlike in the mazes, whose openings sit inside walls.
 */
struct OpenFloor
{
  PolygonMesh mesh;
  std::vector<std::int32_t> roomOfPolygon;
  std::vector<portals::PortalDesc> portals;
  /// Per room (id j * nx + i): its box.
  std::vector<Box> cells;

  OpenFloor(int nx, int ny, std::uint64_t seed, const OpenFloorOptions& options = {})
  {
    std::mt19937_64 rng(seed);
    std::mt19937_64 openingRng(seed ^ 0x9e3779b97f4a7c15ull);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> xs{ 0.0 }, ys{ 0.0 };
    for (int i = 0; i < nx; ++i)
    {
      xs.push_back(xs.back() + 0.3 + 2.0 * u(rng));
    }
    for (int j = 0; j < ny; ++j)
    {
      ys.push_back(ys.back() + 0.3 + 2.0 * u(rng));
    }
    const auto x = [&xs](int i) { return xs[static_cast<std::size_t>(i)]; };
    const auto y = [&ys](int j) { return ys[static_cast<std::size_t>(j)]; };
    const double h = options.storeyHeight;
    const auto id = [nx](int i, int j) { return j * nx + i; };
    const auto face = [this](std::int32_t room, int axis, double at, bool positive, double u0,
                        double u1, double v0, double v1)
    {
      addAxisQuad(this->mesh, axis, at, positive, u0, u1, v0, v1);
      this->roomOfPolygon.push_back(room);
    };
    // An opening's margin on one side, as a fraction of the face: none (a door's sill) or 5..35 %.
    const auto margin = [&openingRng, &u]()
    { return u(openingRng) < 0.25 ? 0.0 : 0.05 + 0.3 * u(openingRng); };
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        Box cell;
        cell.extend(glm::dvec3(x(i), y(j), 0.0));
        cell.extend(glm::dvec3(x(i + 1), y(j + 1), h));
        this->cells.push_back(cell);
        face(id(i, j), 2, 0.0, true, x(i), x(i + 1), y(j), y(j + 1));
        face(id(i, j), 2, h, false, x(i), x(i + 1), y(j), y(j + 1));
        // The face to +x (axis 0: u = y, v = z) and to +y (axis 1: u = z, v = x).
        for (const int axis : { 0, 1 })
        {
          const bool last = axis == 0 ? i + 1 == nx : j + 1 == ny;
          const double at = axis == 0 ? x(i + 1) : y(j + 1);
          const double u0 = axis == 0 ? y(j) : 0.0, u1 = axis == 0 ? y(j + 1) : h;
          const double v0 = axis == 0 ? 0.0 : x(i), v1 = axis == 0 ? h : x(i + 1);
          const std::int32_t next =
            axis == 0 ? (last ? -1 : id(i + 1, j)) : (last ? -1 : id(i, j + 1));
          if (!last && u(rng) < options.portalProbability)
          {
            // The portal's extent in the face: all of it, or an opening with a wall round it.
            double a0 = u0, a1 = u1, b0 = v0, b1 = v1;
            if (options.openings)
            {
              a0 = u0 + margin() * (u1 - u0);
              a1 = u1 - margin() * (u1 - u0);
              b0 = v0 + margin() * (v1 - v0);
              b1 = v1 - margin() * (v1 - v0);
              const double pieces[4][4] = { { u0, a0, v0, v1 }, { a1, u1, v0, v1 },
                { a0, a1, v0, b0 }, { a0, a1, b1, v1 } };
              for (const auto& w : pieces)
              {
                if (w[1] > w[0] && w[3] > w[2])
                {
                  face(id(i, j), axis, at, false, w[0], w[1], w[2], w[3]);
                  face(next, axis, at, true, w[0], w[1], w[2], w[3]);
                }
              }
            }
            std::vector<glm::dvec3> quad;
            for (int k = 0; k < 4; ++k)
            {
              glm::dvec3 p(0.0);
              p[axis] = at;
              p[(axis + 1) % 3] = (k == 1 || k == 2) ? a1 : a0;
              p[(axis + 2) % 3] = k >= 2 ? b1 : b0;
              quad.push_back(p);
            }
            this->portals.push_back(portals::PortalDesc{ quad, id(i, j), next });
            continue;
          }
          face(id(i, j), axis, at, false, u0, u1, v0, v1);
          if (next >= 0)
          {
            face(next, axis, at, true, u0, u1, v0, v1);
          }
        }
        // Exterior walls to -x and -y.
        if (i == 0)
        {
          face(id(i, j), 0, 0.0, true, y(j), y(j + 1), 0.0, h);
        }
        if (j == 0)
        {
          face(id(i, j), 1, 0.0, true, 0.0, h, x(i), x(i + 1));
        }
      }
    }
    if (options.offset != glm::dvec3(0.0))
    {
      for (glm::dvec3& p : this->mesh.points)
      {
        p += options.offset;
      }
      for (portals::PortalDesc& portal : this->portals)
      {
        for (glm::dvec3& p : portal.polygon)
        {
          p += options.offset;
        }
      }
      for (Box& cell : this->cells)
      {
        cell.lo += options.offset;
        cell.hi += options.offset;
      }
    }
  }

  portals::CellSceneInput input() const
  {
    portals::CellSceneInput in;
    in.mesh = &this->mesh;
    in.roomOfPolygon = this->roomOfPolygon;
    in.portals = this->portals;
    in.roomCount = static_cast<std::int32_t>(this->cells.size());
    return in;
  }
};

} // namespace portaltest
} // namespace scenevis

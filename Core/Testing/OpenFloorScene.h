#pragma once
// Test-only: an open floor of box rooms joined by portals, the scene of the exact traversal's
// sight-line test (TestPortalSightLines.cpp) and of its fuzz target (FuzzPortalTraversal.cpp).

#include "AxisQuad.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/PortalGraph.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstdint>
#include <numeric>
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
  /// Chance that the face between two neighbouring cells is open: the two cells are one room
  /// (an L, a U, a room round a pillar of wall; at most maxCellsPerRoom cells). Between cells of
  /// one room that are not joined directly the face is a wall (never a portal). Drawn from a third
  /// generator: 0 (default) makes the floors above.
  double joinProbability = 0.0;
  int maxCellsPerRoom = 4;
};

/**
 * An open floor as game levels have it: nx x ny cells of jittered widths (0.3 to 2.3), one
 * storey, every face between two cells either a portal (80 % by default: the whole face) or a
 * wall; exterior walls all round, a floor and a ceiling per cell. A room is reached along many
 * chains of portals whose cones nest, so the traversal's regions are often contained in others
 * (and merged), unlike in the mazes, whose openings sit inside walls. A room is one cell, or
 * several joined ones (OpenFloorOptions::joinProbability): then it is not convex.
 */
struct OpenFloor
{
  PolygonMesh mesh;
  std::vector<std::int32_t> roomOfPolygon;
  std::vector<portals::PortalDesc> portals;
  /// Per cell (j * nx + i): its box, and the room it is part of (the cell's index when no cells
  /// are joined).
  std::vector<Box> cells;
  std::vector<std::int32_t> roomOfCell;
  std::int32_t roomCount = 0;
  /// The cells' edges along x and y, before the offset.
  std::vector<double> xs{ 0.0 }, ys{ 0.0 };
  glm::dvec3 offset{ 0.0 };
  double height = 0.0;

  OpenFloor(int nx, int ny, std::uint64_t seed, const OpenFloorOptions& options = {})
  {
    std::mt19937_64 rng(seed);
    std::mt19937_64 openingRng(seed ^ 0x9e3779b97f4a7c15ull);
    std::mt19937_64 joinRng(seed ^ 0x5bd1e9955bd1e995ull);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    this->offset = options.offset;
    this->height = options.storeyHeight;
    std::vector<double>& xEdges = this->xs;
    std::vector<double>& yEdges = this->ys;
    for (int i = 0; i < nx; ++i)
    {
      xEdges.push_back(xEdges.back() + 0.3 + 2.0 * u(rng));
    }
    for (int j = 0; j < ny; ++j)
    {
      yEdges.push_back(yEdges.back() + 0.3 + 2.0 * u(rng));
    }
    const auto x = [&xEdges](int i) { return xEdges[static_cast<std::size_t>(i)]; };
    const auto y = [&yEdges](int j) { return yEdges[static_cast<std::size_t>(j)]; };
    const double h = options.storeyHeight;
    const auto cellId = [nx](int i, int j) { return j * nx + i; };
    joinCells(nx, ny, options, joinRng);
    const auto id = [this, &cellId](int i, int j)
    { return this->roomOfCell[static_cast<std::size_t>(cellId(i, j))]; };
    const auto joined = [this, &cellId](int i, int j, int axis)
    {
      return this->joinedFace[2 * static_cast<std::size_t>(cellId(i, j)) +
               static_cast<std::size_t>(axis)] != 0;
    };
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
          if (!last && next == id(i, j) && joined(i, j, axis))
          {
            continue; // open: one room on both sides
          }
          if (!last && next != id(i, j) && u(rng) < options.portalProbability)
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
    in.roomCount = this->roomCount;
    return in;
  }

  /**
   * Whether the segment from @p a to @p b (world points between floor and ceiling) stays inside
   * room @p room: every stretch between its crossings of the cells' edges has its middle in a
   * cell of the room. A line of sight crossing a room of several cells must not pass through a
   * wall between two portals (bench::RayWalk's `clear`).
   */
  bool segmentInRoom(std::int32_t room, const glm::dvec3& a, const glm::dvec3& b) const
  {
    const glm::dvec3 p = a - this->offset, q = b - this->offset;
    std::vector<double> ts{ 0.0, 1.0 };
    for (int axis = 0; axis < 2; ++axis)
    {
      const std::vector<double>& edges = axis == 0 ? this->xs : this->ys;
      const double d = q[axis] - p[axis];
      for (std::size_t k = 1; d != 0.0 && k + 1 < edges.size(); ++k)
      {
        const double t = (edges[k] - p[axis]) / d;
        if (t > 0.0 && t < 1.0)
        {
          ts.push_back(t);
        }
      }
    }
    std::sort(ts.begin(), ts.end());
    for (std::size_t k = 0; k + 1 < ts.size(); ++k)
    {
      const glm::dvec3 m = p + (0.5 * (ts[k] + ts[k + 1])) * (q - p);
      const auto cell = [](const std::vector<double>& edges, double v) {
        return static_cast<int>(std::upper_bound(edges.begin(), edges.end(), v) - edges.begin()) -
          1;
      };
      const int i = cell(this->xs, m.x), j = cell(this->ys, m.y);
      const int nx = static_cast<int>(this->xs.size()) - 1,
                ny = static_cast<int>(this->ys.size()) - 1;
      if (i < 0 || j < 0 || i >= nx || j >= ny ||
        this->roomOfCell[static_cast<std::size_t>(j * nx + i)] != room)
      {
        return false;
      }
    }
    return true;
  }

private:
  /// Per cell and axis (2 c + axis): the face to +x / +y of cell c joins it to its neighbour.
  std::vector<std::uint8_t> joinedFace;

  /// Joins neighbouring cells into rooms (union-find, at most maxCellsPerRoom cells a room) and
  /// numbers the rooms in the order of their first cell: roomOfCell, roomCount, joinedFace.
  void joinCells(int nx, int ny, const OpenFloorOptions& options, std::mt19937_64& rng)
  {
    const std::size_t count = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
    std::vector<std::size_t> parent(count), size(count, 1);
    std::iota(parent.begin(), parent.end(), std::size_t{ 0 });
    const auto find = [&parent](std::size_t c)
    {
      while (parent[c] != c)
      {
        c = parent[c] = parent[parent[c]];
      }
      return c;
    };
    this->joinedFace.assign(2 * count, 0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int j = 0; options.joinProbability > 0.0 && j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        for (const int axis : { 0, 1 })
        {
          if (axis == 0 ? i + 1 == nx : j + 1 == ny)
          {
            continue;
          }
          const std::size_t c = static_cast<std::size_t>(j * nx + i);
          const std::size_t n = axis == 0 ? c + 1 : c + static_cast<std::size_t>(nx);
          const std::size_t rc = find(c), rn = find(n);
          if (u(rng) < options.joinProbability && rc != rn &&
            size[rc] + size[rn] <= static_cast<std::size_t>(options.maxCellsPerRoom))
          {
            parent[rn] = rc;
            size[rc] += size[rn];
            this->joinedFace[2 * c + static_cast<std::size_t>(axis)] = 1;
          }
        }
      }
    }
    std::vector<std::int32_t> number(count, -1);
    this->roomOfCell.assign(count, -1);
    this->roomCount = 0;
    for (std::size_t c = 0; c < count; ++c)
    {
      std::int32_t& r = number[find(c)];
      if (r < 0)
      {
        r = this->roomCount++;
      }
      this->roomOfCell[c] = r;
    }
  }
};

} // namespace portaltest
} // namespace scenevis

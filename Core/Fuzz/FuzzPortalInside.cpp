// libFuzzer target for PortalGraph::inside() on rooms of many polygons (its per-direction ray
// grids, PortalGraph::RayGrid): arbitrary bytes -> one box room whose faces are cut into a grid
// of quads (up to 16 x 16 per face, so from 6 to 1,536 polygons: with and without ray grids),
// of random size, now and then 1e7 from the origin, with its grid points moved along their
// face's normal (quads that are not planar; shared points move together, so the room stays
// closed), some faces' order reversed, and a NaN and a degenerate polygon mixed in; then points
// anywhere around it.
//
// Oracle (the room is known; not just "no crash"): a point farther from every face's plane than
// 1e-3 of the room's size plus the largest move is inside() exactly when it is inside the box.
//
// SCENEVIS_FUZZ_SELFTEST=1 flips the expected answer of the first point checked (must abort on
// any input with a point).
#include "FuzzBytes.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/PortalGraph.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

namespace
{
using scenevis::PolygonMesh;
using namespace scenevis::portals;

using scenevis::fuzz::Bytes;

[[noreturn]] void fail(const char* what, const glm::dvec3& q)
{
  std::fprintf(stderr, "FuzzPortalInside: %s at (%.17g, %.17g, %.17g)\n", what, q.x, q.y, q.z);
  std::abort();
}

/// A move along the face normal for the grid point (a, b) of face @p face: the same for every
/// quad that shares the point (edges of two faces keep 0, so faces still meet).
double moveOf(int face, int a, int b, int na, int nb, double amplitude)
{
  if (a == 0 || b == 0 || a == na || b == nb)
  {
    return 0.0;
  }
  const unsigned h = static_cast<unsigned>(face * 7919 + a * 104729 + b * 1299709);
  return amplitude * (static_cast<double>(h % 2001u) / 1000.0 - 1.0);
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Bytes in{ data, size };
  const int n[3] = { 1 + static_cast<int>(in.next() % 16), 1 + static_cast<int>(in.next() % 16),
    1 + static_cast<int>(in.next() % 16) };
  const glm::dvec3 extent(0.5 + in.next(), 0.5 + in.next(), 0.5 + in.next());
  const unsigned flags = in.next();
  const glm::dvec3 offset = (flags & 1u) ? glm::dvec3(1e7, -3e6, 2.5e6) : glm::dvec3(0.0);
  const double largest = std::max({ extent.x, extent.y, extent.z });
  const double amplitude = (flags & 2u) ? 1e-4 * largest * (1 + in.next() % 8) : 0.0;
  PolygonMesh mesh;
  std::vector<std::int32_t> rooms;
  // Faces: axis k, at 0 or extent[k]; the grid over the other two axes (i, j).
  int face = 0;
  for (int k = 0; k < 3; ++k)
  {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    for (int side = 0; side < 2; ++side, ++face)
    {
      const bool reversed = ((flags >> 2) & 1u) && face % 2 == 1;
      const double normalSign = side == 0 ? -1.0 : 1.0;
      for (int a = 0; a < n[i]; ++a)
      {
        for (int b = 0; b < n[j]; ++b)
        {
          std::uint32_t ids[4];
          const int corners[4][2] = { { a, b }, { a + 1, b }, { a + 1, b + 1 }, { a, b + 1 } };
          for (int c = 0; c < 4; ++c)
          {
            glm::dvec3 p(0.0);
            p[i] = extent[i] * corners[c][0] / n[i];
            p[j] = extent[j] * corners[c][1] / n[j];
            p[k] = side * extent[k] +
              normalSign * moveOf(face, corners[c][0], corners[c][1], n[i], n[j], amplitude);
            ids[reversed ? 3 - c : c] = mesh.addPoint(offset + p);
          }
          mesh.addPolygon(ids, 4);
          rooms.push_back(0);
        }
      }
    }
  }
  if (flags & 8u)
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    mesh.addPolygon({ mesh.addPoint({ nan, 0, 0 }), mesh.addPoint(offset + glm::dvec3(1, 0, 0)),
      mesh.addPoint(offset + glm::dvec3(0, 1, 0)) });
    rooms.push_back(0);
    const std::uint32_t p = mesh.addPoint(offset + 0.5 * extent);
    mesh.addPolygon({ p, p, p });
    rooms.push_back(0);
  }
  CellSceneInput scene;
  scene.mesh = &mesh;
  scene.roomOfPolygon = rooms;
  const PortalGraph graph = PortalGraph::build(scene);
  if (graph.roomCount() != 1)
  {
    fail("not one room", offset);
  }
  static const bool selftest = std::getenv("SCENEVIS_FUZZ_SELFTEST") != nullptr;
  bool flipped = false;
  const double keepOut = 1e-3 * largest + 1.01 * amplitude;
  while (in.more())
  {
    // A point in [-0.25, 1.25] of the box along each axis.
    glm::dvec3 local;
    for (int k = 0; k < 3; ++k)
    {
      local[k] = extent[k] * (-0.25 + 1.5 * in.next() / 255.0);
    }
    double nearest = std::numeric_limits<double>::infinity();
    bool truth = true;
    for (int k = 0; k < 3; ++k)
    {
      nearest = std::min({ nearest, std::abs(local[k]), std::abs(local[k] - extent[k]) });
      truth = truth && local[k] > 0.0 && local[k] < extent[k];
    }
    if (nearest <= keepOut)
    {
      continue;
    }
    if (selftest && !flipped)
    {
      truth = !truth;
      flipped = true;
    }
    if (graph.inside(0, offset + local) != truth)
    {
      fail(truth ? "a point inside the room is not inside()" : "a point outside is inside()",
        offset + local);
    }
  }
  return 0;
}

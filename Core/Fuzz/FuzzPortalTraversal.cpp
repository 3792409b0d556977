// libFuzzer target for the exact portal traversal (PortalTraversal) against sight lines: arbitrary
// bytes -> an open floor (Core/Testing/OpenFloorScene.h: 1..12 x 1..10 box cells of one storey
// 1..6 high, each face between two rooms a portal with a drawn probability, the whole face or an
// opening inside a wall, now and then 1e7 from the origin; with flag 8 half the faces between
// cells open, joining cells into rooms of 2..6 cells that are not convex), traversal options
// (either narrowing mode, 1..16 regions per room), then up to 6 views: the eye anywhere in a room
// or within 1e-6 of the room's size of one of its faces (a portal's plane or a wall), any yaw,
// pitch within
// +-81 degrees, a view angle of 20..150 degrees, a near plane 1e-7..0.1 of the building's size.
// One PortalTraversal runs every view, as a culler reuses it frame after frame.
//
// Oracle (as TestPortalSightLines.cpp): 12 x 12 rays per view are walked through the portals by
// bench::RayWalk (Core/Testing/PortalRayWalk.h), which shares none of the traversal's clipping,
// containment or merging (in rooms of several cells a ray that passes through a wall between two
// crossings ends there: OpenFloor::segmentInRoom); beyond each portal a ray crosses, the room it
// enters must hold the ray's point in a region (boxVisible() of a tiny box around it). A frame that
// fell back (stats().fallback) makes every room visible and tests boxes against the view frustum
// only (PortalTraversal.h), so the same check holds for it.
//
// SCENEVIS_FUZZ_SELFTEST=1 expects the first crossing checked to be outside every region of its
// room (must abort on any input whose rays cross a portal).
#include "FuzzBytes.h"
#include "OpenFloorScene.h"
#include "PortalRayWalk.h"
#include "scenevis/PortalGraph.h"
#include "scenevis/PortalTraversal.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

namespace
{
using scenevis::Box;
using namespace scenevis::portals;

using scenevis::fuzz::Bytes;

constexpr int kRays = 12; // per side of the view
constexpr int kViews = 6; // at most, per input
constexpr double kPi = 3.14159265358979323846;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Bytes in{ data, size };
  const int nx = 1 + static_cast<int>(in.next() % 12);
  const int ny = 1 + static_cast<int>(in.next() % 10);
  const unsigned seedLow = in.next();
  const std::uint64_t seed = seedLow | (static_cast<std::uint64_t>(in.next()) << 8);
  scenevis::portaltest::OpenFloorOptions floorOptions;
  floorOptions.portalProbability = in.unit();
  const unsigned flags = in.next();
  floorOptions.offset = (flags & 1u) ? glm::dvec3(1e7, -3e6, 2.5e6) : glm::dvec3(0.0);
  floorOptions.openings = (flags & 2u) != 0;
  floorOptions.joinProbability = (flags & 8u) ? 0.5 : 0.0;
  floorOptions.maxCellsPerRoom = 2 + static_cast<int>((flags >> 4) % 5);
  TraversalOptions options;
  options.mode = (flags & 4u) ? NarrowingMode::ScreenRectangles : NarrowingMode::ExactFrustum;
  options.maxRegionsPerRoom = 1 + in.next() % 16;
  floorOptions.storeyHeight = 1.0 + 5.0 * in.unit();
  const scenevis::portaltest::OpenFloor floor(nx, ny, seed, floorOptions);
  const PortalGraph graph = PortalGraph::build(floor.input());
  const auto portalsOf = scenevis::bench::PortalsOfNodes(graph);
  const double sceneSize = graph.buildingBounds().diagonal();

  static const bool selftest = std::getenv("SCENEVIS_FUZZ_SELFTEST") != nullptr;
  bool flipped = false;
  PortalTraversal traversal; // reused across views, as a culler does
  for (int v = 0; v < kViews && in.more(); ++v)
  {
    // The eye: fractions of a room's box, or one coordinate 1e-6 .. 3e-11 of the box's extent
    // from one of its faces (a wall, or a portal's plane: the eye nearly stands in the doorway).
    // 1e7 from the origin the smallest distances round onto the face: an eye then in no room
    // makes the frame fall back.
    const Box& cell = floor.cells[in.next() % floor.cells.size()];
    const glm::dvec3 extent = cell.hi - cell.lo;
    glm::dvec3 eye;
    for (int k = 0; k < 3; ++k)
    {
      eye[k] = cell.lo[k] + extent[k] * ((in.next() + 0.5) / 256.0);
    }
    const unsigned nearFace = in.next();
    if (nearFace < 96)
    {
      const int axis = static_cast<int>(nearFace % 3);
      const double distance = extent[axis] * std::ldexp(1e-6, -static_cast<int>(nearFace / 6));
      eye[axis] = (nearFace / 3) % 2 ? cell.hi[axis] - distance : cell.lo[axis] + distance;
    }
    const double yaw = 2.0 * kPi * in.next() / 256.0;
    const double pitch = 0.9 * kPi * (in.unit() - 0.5);
    const double fov = 20.0 + 130.0 * in.unit();
    const double nearPlane = sceneSize * std::pow(10.0, -7.0 + 6.0 * in.unit());
    const double farPlane = 2.0 * sceneSize;
    const glm::dvec3 forward(
      std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
    PortalView view;
    view.eye = eye;
    view.clipFromWorld = glm::perspective(glm::radians(fov), 1.0, nearPlane, farPlane) *
      glm::lookAt(eye, eye + forward, glm::dvec3(0, 0, 1));
    traversal.run(graph, view, options);
    const Fallback fallback = traversal.stats().fallback;

    // 12 x 12 rays over the view: 1/24 of it inside the frustum's side planes.
    const EyeLocation start = graph.locate(eye, 0.0, OutsidePolicy::ExteriorPortals);
    scenevis::bench::WalkViewRays(
      graph, portalsOf, start.nodes, eye, forward, fov, kRays,
      [&](int ray, std::int32_t node, double t, const glm::dvec3& d)
      {
        // A point on the ray just beyond the portal (as the test). Where that is nearer than the
        // near plane (an eye close to the portal), the point where the ray is as far beyond the
        // near plane: regions are cones from the eye (the traversal clips portals at the eye
        // plane, not the near plane), so any point of the ray in the view's depth range asks the
        // same, and boxVisible() drops boxes before the near plane.
        const double beyond = 1e-4 * sceneSize;
        const double s = std::max(t + beyond, (nearPlane + beyond) / glm::dot(d, forward));
        const glm::dvec3 p = eye + s * d;
        // The box: 1e-9 of the building's size as the test, plus 4 units of rounding of p's
        // coordinates. 1e7 from the origin a double resolves 1.9e-9 and p (and the ray's
        // crossing) is rounded by as much: 1e-9 of a building 3 to 36 across is 1.6 to 19 units
        // of rounding only. At the origin the second term is below 1e-13.
        const double coordinate = std::max({ std::abs(p.x), std::abs(p.y), std::abs(p.z) });
        const double half =
          1e-9 * sceneSize + 4.0 * std::numeric_limits<double>::epsilon() * coordinate;
        bool expected = true;
        if (selftest && !flipped)
        {
          expected = false;
          flipped = true;
        }
        if (traversal.boxVisible(node, scenevis::bench::TinyBox(p, half)) != expected)
        {
          std::fprintf(stderr,
            "FuzzPortalTraversal: view %d, ray %d: room %d entered at t = %.17g is %s\n  eye "
            "(%.17g, %.17g, %.17g), d (%.17g, %.17g, %.17g), point at s = %.17g\n  floor %d x %d "
            "seed %llu flags %u, %s, %zu regions per room, fallback %d, near %.17g, view angle "
            "%.17g\n",
            v, ray, node, t, expected ? "outside every region of it" : "in a region (self-test)",
            eye.x, eye.y, eye.z, d.x, d.y, d.z, s, nx, ny, static_cast<unsigned long long>(seed),
            flags, options.mode == NarrowingMode::ExactFrustum ? "exact" : "rectangles",
            options.maxRegionsPerRoom, static_cast<int>(fallback), nearPlane, fov);
          std::abort();
        }
        return true;
      },
      [&floor](std::int32_t room, const glm::dvec3& from, const glm::dvec3& to)
      { return floor.segmentInRoom(room, from, to); });
  }
  return 0;
}

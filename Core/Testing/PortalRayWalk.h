// A ray from the eye walked through the portal graph: the oracle for "a line of sight through
// portals reaches this room". If a ray from the eye crosses a chain of portals, each of the room
// the ray is in, in order, into the room, the room is visible through portals from the eye's room:
// a conservative PVS must hold it (scenevis_pvs_bench), and a region of the exact traversal must
// hold the ray beyond each crossing (TestPortalSightLines).
#ifndef scenevis_bench_PortalRayWalk_h
#define scenevis_bench_PortalRayWalk_h

#include "scenevis/PortalGraph.h"

#include <glm/geometric.hpp>
#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace scenevis
{
namespace bench
{

/// Where the ray o + t d (t > 0) crosses planar convex portal @p p, or +inf if it misses it.
inline double RayCrossesPortal(
  const portals::GraphPortal& p, const glm::dvec3& o, const glm::dvec3& d)
{
  const glm::dvec3 n(p.plane);
  const double denom = glm::dot(n, d);
  if (!p.planar || p.hull.size() < 3 || denom == 0.0)
  {
    return std::numeric_limits<double>::infinity();
  }
  const double t = -(glm::dot(n, o) + p.plane.w) / denom;
  if (!(t > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  const glm::dvec3 x = o + t * d;
  int sign = 0;
  for (std::size_t i = 0; i < p.hull.size(); ++i)
  {
    const glm::dvec3& a = p.hull[i];
    const glm::dvec3& b = p.hull[(i + 1) % p.hull.size()];
    const double s = glm::dot(glm::cross(b - a, x - a), n);
    const int si = s > 0.0 ? 1 : (s < 0.0 ? -1 : 0);
    if (si != 0 && sign != 0 && si != sign)
    {
      return std::numeric_limits<double>::infinity();
    }
    sign = si != 0 ? si : sign;
  }
  return t;
}

/// The portals of each node, the outside node included.
inline std::vector<std::vector<std::uint32_t>> PortalsOfNodes(const portals::PortalGraph& graph)
{
  std::vector<std::vector<std::uint32_t>> of(static_cast<std::size_t>(graph.nodeCount()));
  for (std::uint32_t i = 0; i < graph.portals().size(); ++i)
  {
    of[static_cast<std::size_t>(graph.portals()[i].nodeA)].push_back(i);
    of[static_cast<std::size_t>(graph.portals()[i].nodeB)].push_back(i);
  }
  return of;
}

/// RayWalk()'s default `clear`: the segment between two crossings of a room's boundary lies in the
/// room, as in a convex room (a ray that left it through a wall meets its portals from outside,
/// which the walk finds by itself).
struct ConvexRooms
{
  bool operator()(std::int32_t, const glm::dvec3&, const glm::dvec3&) const { return true; }
};

/// Walks the ray from @p eye along @p d, starting in node @p start, across the portals it meets:
/// each time the nearest portal of the node it is in (never the one it came through), crossed
/// from inside that room into the other; @p enter(node) for every node entered (return false to
/// stop). A ray from the eye may leave a room through a wall and meet one of its portals from the
/// far side; such a path is no line of sight, and the walk ends there. @p enter also gets the
/// ray parameter of the crossing (the point eye + t d on the portal). In rooms that are not
/// convex a ray can also pass through a wall and come back into the room: @p clear(room, from,
/// to) says whether the segment from where the ray entered the room (or the eye) to its next
/// crossing stays in the room; if not, the walk ends.
template <typename Enter, typename Clear = ConvexRooms>
void RayWalk(const portals::PortalGraph& graph,
  const std::vector<std::vector<std::uint32_t>>& portalsOf, std::int32_t start,
  const glm::dvec3& eye, const glm::dvec3& d, Enter&& enter, const Clear& clear = Clear())
{
  std::int32_t node = start;
  double tNow = 0.0;
  std::int64_t came = -1;
  for (int step = 0; step < 100000; ++step)
  {
    double best = std::numeric_limits<double>::infinity();
    std::int64_t next = -1;
    for (const std::uint32_t i : portalsOf[static_cast<std::size_t>(node)])
    {
      if (static_cast<std::int64_t>(i) == came)
      {
        continue;
      }
      const double t = RayCrossesPortal(graph.portals()[i], eye, d);
      if (t > tNow && t < best)
      {
        best = t;
        next = i;
      }
    }
    if (next < 0)
    {
      return;
    }
    const portals::GraphPortal& p = graph.portals()[static_cast<std::size_t>(next)];
    const glm::dvec3 x = eye + best * d;
    const double delta = 1e-3 * p.bounds.diagonal();
    const std::int32_t to = p.other(node);
    const bool outside = node == graph.outsideNode() || to == graph.outsideNode();
    if (!outside && (!graph.inside(node, x - delta * d) || !graph.inside(to, x + delta * d)))
    {
      return;
    }
    if (node != graph.outsideNode() && !clear(node, eye + tNow * d, x))
    {
      return;
    }
    node = to;
    tNow = best;
    came = next;
    if (!enter(node, best))
    {
      return;
    }
  }
}

/**
 * The sight lines of a perspective view, walked: @p raysPerSide x @p raysPerSide rays from @p eye
 * through the centres of a grid over the view (unit direction @p forward, up towards +z as
 * glm::lookAt(eye, eye + forward, (0, 0, 1)) makes it, view angle @p fovDegrees on a square
 * image), built from the camera's frame rather than an inverted matrix (no rounding of the inverse
 * far from the origin). Each ray is walked by RayWalk() from every node of @p starts;
 * @p visit(ray, node, t, d) for every node entered (return false to stop that walk); @p clear as
 * RayWalk()'s.
 */
template <typename Visit, typename Clear = ConvexRooms>
void WalkViewRays(const portals::PortalGraph& graph,
  const std::vector<std::vector<std::uint32_t>>& portalsOf, const std::vector<std::int32_t>& starts,
  const glm::dvec3& eye, const glm::dvec3& forward, double fovDegrees, int raysPerSide,
  Visit&& visit, const Clear& clear = Clear())
{
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double halfWidth = std::tan(glm::radians(fovDegrees) / 2.0);
  for (int i = 0; i < raysPerSide * raysPerSide; ++i)
  {
    const double x = -1.0 + 2.0 * ((i % raysPerSide) + 0.5) / raysPerSide;
    const double y = -1.0 + 2.0 * ((i / raysPerSide) + 0.5) / raysPerSide;
    const glm::dvec3 d = glm::normalize(forward + halfWidth * (x * right + y * up));
    for (const std::int32_t room : starts)
    {
      RayWalk(
        graph, portalsOf, room, eye, d,
        [&](std::int32_t node, double t) { return visit(i, node, t, d); }, clear);
    }
  }
}

/// A box of half size @p half around @p p: PortalTraversal::boxVisible() of it asks whether a
/// region of the room holds p (the sight-line checks).
inline Box TinyBox(const glm::dvec3& p, double half)
{
  Box b;
  b.extend(p - glm::dvec3(half));
  b.extend(p + glm::dvec3(half));
  return b;
}

/// Whether RayWalk() from @p start enters node @p target.
inline bool RayReaches(const portals::PortalGraph& graph,
  const std::vector<std::vector<std::uint32_t>>& portalsOf, std::int32_t start, std::int32_t target,
  const glm::dvec3& eye, const glm::dvec3& d)
{
  bool reached = start == target;
  RayWalk(graph, portalsOf, start, eye, d,
    [&reached, target](std::int32_t node, double)
    {
      reached = node == target;
      return !reached;
    });
  return reached;
}

} // namespace bench
} // namespace scenevis

#endif

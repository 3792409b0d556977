#include "scenevis/PortalTraversal.h"

#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalPvs.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scenevis
{
namespace portals
{

namespace
{
/// Rectangles grow by this much (NDC) whenever they are computed: float noise never shrinks them.
constexpr double kRectSlack = 1e-9;
/// Merges of one room's regions in a frame after which its region is the whole view.
constexpr std::uint32_t kMergesPerRoom = 4;

/// The part of rectangle @p a (xmin, ymin, xmax, ymax) inside @p b; empty when min > max.
glm::dvec4 intersectRects(const glm::dvec4& a, const glm::dvec4& b)
{
  return glm::dvec4(std::max(a.x, b.x), std::max(a.y, b.y), std::min(a.z, b.z), std::min(a.w, b.w));
}

glm::dvec4 normalizedPlane(const glm::dvec4& p)
{
  const double len = glm::length(glm::dvec3(p));
  return len > 0.0 ? p / len : p;
}
} // namespace

PortalView PortalView::fromRowMajor(const double m[16], const glm::dvec3& eye, bool parallel)
{
  PortalView v;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      v.clipFromWorld[c][r] = m[4 * r + c];
    }
  }
  v.eye = eye;
  v.parallel = parallel;
  return v;
}

glm::dvec4 PortalTraversal::ndcBounds(const glm::dvec3* poly, std::size_t count) const
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  glm::dvec4 rect(inf, inf, -inf, -inf);
  const glm::dmat4& m = this->View.clipFromWorld;
  for (std::size_t k = 0; k < count; ++k)
  {
    const glm::dvec4 c = m * glm::dvec4(poly[k], 1.0);
    if (!(c.w > 0.0))
    {
      // Cannot happen after the front clip, but never shrink on doubt.
      return glm::dvec4(-inf, -inf, inf, inf);
    }
    const double x = c.x / c.w, y = c.y / c.w;
    rect = glm::dvec4(
      std::min(rect.x, x), std::min(rect.y, y), std::max(rect.z, x), std::max(rect.w, y));
  }
  return glm::dvec4(
    rect.x - kRectSlack, rect.y - kRectSlack, rect.z + kRectSlack, rect.w + kRectSlack);
}

glm::dvec4 PortalTraversal::rectPlane(int side, double value) const
{
  // x_ndc >= v  <=>  row0 . P - v * row3 . P >= 0 (w > 0); likewise for the other sides.
  switch (side)
  {
    case 0:
      return normalizedPlane(this->Rows[0] - value * this->Rows[3]);
    case 1:
      return normalizedPlane(value * this->Rows[3] - this->Rows[0]);
    case 2:
      return normalizedPlane(this->Rows[1] - value * this->Rows[3]);
    default:
      return normalizedPlane(value * this->Rows[3] - this->Rows[1]);
  }
}

std::uint32_t PortalTraversal::addRegion(const glm::dvec4& rect)
{
  Region r;
  r.rect = rect;
  r.firstPlane = static_cast<std::uint32_t>(this->Planes.size());
  this->Planes.push_back(this->rectPlane(0, rect.x));
  this->Planes.push_back(this->rectPlane(1, rect.z));
  this->Planes.push_back(this->rectPlane(2, rect.y));
  this->Planes.push_back(this->rectPlane(3, rect.w));
  r.planeCount = 4;
  r.firstVertex = static_cast<std::uint32_t>(this->Vertices.size());
  this->Regions.push_back(r);
  return static_cast<std::uint32_t>(this->Regions.size() - 1);
}

void PortalTraversal::fallBack(Fallback why)
{
  this->FrustumOnly = true;
  this->Stats.fallback = why;
  this->WorkList.clear();
  this->Visible.clear();
  if (this->Graph)
  {
    for (std::int32_t n = 0; n < this->Graph->nodeCount(); ++n)
    {
      this->Visible.push_back(n);
    }
  }
  this->Stats.roomsVisited = this->Visible.size();
}

bool PortalTraversal::begin(const PortalGraph& graph, const PortalView& view,
  const TraversalOptions& options)
{
  const auto nodes = static_cast<std::size_t>(graph.nodeCount());
  // The same graph as the previous frame's: the same address is not enough, a caller may rebuild
  // its graph in place (vtkPortalCuller does), and the per-portal cache must fit its portals.
  if (this->LastGraph == &graph && this->LastFingerprint == graph.fingerprint() &&
    this->LastNodes == nodes && this->NodeRegions.size() >= nodes &&
    this->NodeGeneration.size() >= nodes && this->Clipped.size() == graph.portals().size() &&
    this->ExitStart.size() == nodes + 1)
  {
    // Only the nodes the previous frame reached have regions: reset those, not every node.
    for (const std::int32_t n : this->Visible)
    {
      this->NodeRegions[static_cast<std::size_t>(n)].clear();
      this->NodeGeneration[static_cast<std::size_t>(n)] = 0;
    }
  }
  else
  {
    if (this->NodeRegions.size() < nodes)
    {
      this->NodeRegions.resize(nodes);
    }
    for (auto& list : this->NodeRegions)
    {
      list.clear();
    }
    this->NodeGeneration.assign(nodes, 0);
    this->Clipped.assign(graph.portals().size(), ClippedPortal());
    this->buildExits(graph);
    this->Frame = 0;
  }
  this->LastGraph = &graph;
  this->LastFingerprint = graph.fingerprint();
  this->LastNodes = nodes;
  if (++this->Frame == 0)
  {
    // The stamp wrapped: no cached portal may pass for this frame's.
    this->Clipped.assign(graph.portals().size(), ClippedPortal());
    this->Frame = 1;
  }
  this->ClippedVertices.clear();
  this->Graph = &graph;
  this->Options = options;
  this->View = view;
  this->Stats = FrameStats();
  this->FrustumOnly = false;
  this->Regions.clear();
  this->Planes.clear();
  this->Vertices.clear();
  this->Visible.clear();
  this->WorkList.clear();
  this->PlaneSlack = 10.0 * graph.tolerance();

  this->ViewFrustum = culling::Frustum::fromViewProjection(view.clipFromWorld);
  const glm::dmat4& m = view.clipFromWorld;
  for (int r = 0; r < 4; ++r)
  {
    this->Rows[r] = glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]);
  }
  const bool finiteEye =
    std::isfinite(view.eye.x) && std::isfinite(view.eye.y) && std::isfinite(view.eye.z);
  if (!this->ViewFrustum.valid() || !finiteEye)
  {
    this->fallBack(Fallback::InvalidView);
    return false;
  }
  const glm::dmat4 inv = glm::inverse(m);
  if (view.parallel)
  {
    // Rays are parallel to the direction in which only the NDC depth changes (x and y rows are
    // constant along it); they start on the near rectangle, so the near plane is the front.
    glm::dvec3 d = glm::cross(glm::dvec3(this->Rows[0]), glm::dvec3(this->Rows[1]));
    const double len = glm::length(d);
    const bool affine =
      this->Rows[3] == glm::dvec4(0.0, 0.0, 0.0, this->Rows[3].w) && this->Rows[3].w > 0.0;
    if (!(len > 0.0) || !std::isfinite(len) || !affine)
    {
      this->fallBack(Fallback::InvalidView);
      return false;
    }
    d /= len;
    if (glm::dot(glm::dvec3(this->Rows[2]), d) < 0.0)
    {
      d = -d; // towards increasing depth
    }
    this->Direction = d;
    this->FrontPlane = this->ViewFrustum.planes[culling::kNear];
    this->NearBox = Box();
    for (int k = 0; k < 4; ++k)
    {
      const glm::dvec4 c = inv * glm::dvec4(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, -1.0, 1.0);
      this->NearBox.extend(glm::dvec3(c) / c.w);
    }
    this->NearDistance = 0.0;
    return true;
  }
  // How far the near plane reaches from the eye: its corners.
  double reach = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    glm::dvec4 c = inv * glm::dvec4(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, -1.0, 1.0);
    if (!(std::abs(c.w) > 0.0))
    {
      continue;
    }
    reach = std::max(reach, glm::length(glm::dvec3(c) / c.w - view.eye));
  }
  if (!std::isfinite(reach))
  {
    this->fallBack(Fallback::InvalidView);
    return false;
  }
  this->NearDistance = options.nearDistance >= 0.0 ? options.nearDistance : 1.01 * reach;
  // The eye plane (w = depth in front of the eye), moved a hair forward so that projected points
  // stay finite; portals closer than that are within NearDistance and handled by locate().
  const glm::dvec4 front = normalizedPlane(this->Rows[3]);
  const double nearDepth = geometry::planeDistance(front, glm::dvec3(inv * glm::dvec4(0, 0, -1, 1)) /
      (inv * glm::dvec4(0, 0, -1, 1)).w);
  this->FrontPlane = front - glm::dvec4(0.0, 0.0, 0.0, 1e-3 * std::max(nearDepth, 0.0));
  return true;
}

PortalTraversal::RegionShape PortalTraversal::shapeOf(const Region& r) const
{
  return RegionShape{ r.rect, r.via, this->Vertices.data() + r.firstVertex, r.vertexCount };
}

bool PortalTraversal::subsumedInNode(std::int32_t node, const RegionShape& inner) const
{
  for (const std::uint32_t other : this->NodeRegions[static_cast<std::size_t>(node)])
  {
    if (this->subsumed(inner, this->Regions[other]))
    {
      return true;
    }
  }
  return false;
}

bool PortalTraversal::subsumed(const RegionShape& inner, const Region& outer) const
{
  constexpr double e = 1e-12;
  if (inner.rect.x < outer.rect.x - e || inner.rect.y < outer.rect.y - e ||
    inner.rect.z > outer.rect.z + e || inner.rect.w > outer.rect.w + e)
  {
    return false;
  }
  if (outer.via >= 0 && inner.via != outer.via)
  {
    // The outer region passes on only what lies beyond its entry plane; the inner's rays must
    // be beyond it too: they are when the portal they crossed last is (a ray crosses it once).
    if (inner.vertexCount == 0)
    {
      return false;
    }
    for (std::uint32_t v = 0; v < inner.vertexCount; ++v)
    {
      if (geometry::planeDistance(outer.entry, inner.vertices[v]) < -10.0 * this->PlaneSlack)
      {
        return false;
      }
    }
  }
  if (outer.edgePlanes == 0)
  {
    return true;
  }
  if (inner.vertexCount == 0)
  {
    return false; // a rectangle-only region: cannot show it is inside the edge planes
  }
  const std::uint32_t firstEdge = outer.firstPlane + 4;
  for (std::uint32_t v = 0; v < inner.vertexCount; ++v)
  {
    for (std::uint32_t p = firstEdge; p < firstEdge + outer.edgePlanes; ++p)
    {
      // 10x the clipping slack: every crossing may grow a region by one slack, so a region that
      // went round a cycle of rooms sticks out of its ancestor by a few; with one slack it
      // would never be subsumed and the cycle would run until the rooms' regions are merged
      // (seen with parallel views: 50x the work and looser merged regions).
      if (geometry::planeDistance(this->Planes[p], inner.vertices[v]) < -10.0 * this->PlaneSlack)
      {
        return false;
      }
    }
  }
  return true;
}

bool PortalTraversal::attach(std::int32_t node, std::uint32_t region, bool checkSubsumed)
{
  auto& list = this->NodeRegions[static_cast<std::size_t>(node)];
  if (checkSubsumed &&
    (std::find(list.begin(), list.end(), region) != list.end() ||
      this->subsumedInNode(node, this->shapeOf(this->Regions[region]))))
  {
    ++this->Stats.regionsSubsumed;
    return false;
  }
  if (list.empty())
  {
    this->Visible.push_back(node);
    if (this->Graph->rooms()[static_cast<std::size_t>(node)].leaky)
    {
      // Something unknown is behind this room's broken portal: give up narrowing.
      this->fallBack(Fallback::LeakyRoom);
      return false;
    }
  }
  list.push_back(region);
  auto& generation = this->NodeGeneration[static_cast<std::size_t>(node)];
  if (list.size() > std::max<std::size_t>(this->Options.maxRegionsPerRoom, 1))
  {
    // Bound the work: one rectangle around all of them (bigger, hence still conservative).
    glm::dvec4 u = this->Regions[list[0]].rect;
    for (const std::uint32_t r : list)
    {
      const glm::dvec4& q = this->Regions[r].rect;
      u = glm::dvec4(std::min(u.x, q.x), std::min(u.y, q.y), std::max(u.z, q.z), std::max(u.w, q.w));
    }
    if (generation >= kMergesPerRoom)
    {
      // The room keeps merging: each merged rectangle lets through a little more, which comes
      // back round a cycle of rooms as a region not quite inside it (clipping keeps points
      // within the slack), so the rectangles can creep by rounding for millions of merges. The
      // whole view holds every region the room can get: it ends the room's merging.
      u = glm::dvec4(-1.0, -1.0, 1.0, 1.0);
    }
    const std::uint32_t merged = this->addRegion(u);
    list.assign(1, merged);
    ++generation;
    ++this->Stats.regionsMerged;
    this->push(node, merged, generation);
    return true;
  }
  this->push(node, region, generation);
  return true;
}

void PortalTraversal::push(std::int32_t node, std::uint32_t region, std::uint32_t generation)
{
  const glm::dvec4& r = this->Regions[region].rect;
  this->WorkList.push_back(Work{ (r.z - r.x) * (r.w - r.y), node, region, generation });
  std::push_heap(this->WorkList.begin(), this->WorkList.end(), narrower);
}

const PortalTraversal::ClippedPortal& PortalTraversal::clippedPortal(std::uint32_t index)
{
  ClippedPortal& c = this->Clipped[index];
  if (c.stamp == this->Frame)
  {
    return c;
  }
  c.stamp = this->Frame;
  // The hull itself until a plane cuts it (most portals lie wholly between the eye and far
  // planes), then ClipA and ClipB in turn.
  const std::vector<glm::dvec3>& hull = this->Graph->portals()[index].hull;
  const glm::dvec3* poly = hull.data();
  std::size_t count = hull.size();
  for (const glm::dvec4* plane : { &this->FrontPlane, &this->ViewFrustum.planes[culling::kFar] })
  {
    if (count >= 3 && !geometry::allKept(poly, count, *plane, this->PlaneSlack))
    {
      std::vector<glm::dvec3>& out = poly == this->ClipA.data() ? this->ClipB : this->ClipA;
      geometry::clipPolygon(poly, count, *plane, this->PlaneSlack, out);
      poly = out.data();
      count = out.size();
    }
  }
  c.first = static_cast<std::uint32_t>(this->ClippedVertices.size());
  c.count = count >= 3 ? static_cast<std::uint32_t>(count) : 0;
  this->ClippedVertices.insert(this->ClippedVertices.end(), poly, poly + c.count);
  c.rect = this->ndcBounds(poly, c.count);
  return c;
}

void PortalTraversal::buildExits(const PortalGraph& graph)
{
  this->ExitStart.assign(1, 0);
  this->Exits.clear();
  for (std::int32_t n = 0; n < graph.nodeCount(); ++n)
  {
    for (const std::uint32_t pi : graph.rooms()[static_cast<std::size_t>(n)].portals)
    {
      const GraphPortal& p = graph.portals()[pi];
      this->Exits.push_back(Exit{ p.bounds.lo, p.bounds.hi, pi, p.other(n) });
    }
    this->ExitStart.push_back(static_cast<std::uint32_t>(this->Exits.size()));
  }
}

PortalTraversal::ExitGate PortalTraversal::exitGate(const Region& parent) const
{
  ExitGate g;
  if (parent.via >= 0)
  {
    g.planes[g.count++] = parent.entry;
    g.entryFirst = true;
  }
  for (std::uint32_t p = parent.firstPlane; p < parent.firstPlane + 4; ++p)
  {
    g.planes[g.count++] = this->Planes[p];
  }
  g.slack = this->PlaneSlack;
  return g;
}

int PortalTraversal::ExitGate::firstBeyond(const glm::dvec3& lo, const glm::dvec3& hi) const
{
  for (int k = 0; k < this->count; ++k)
  {
    if (culling::pVertexDistance(this->planes[k], lo, hi) < -this->slack)
    {
      return k;
    }
  }
  return -1;
}

void PortalTraversal::expand(const Work& w)
{
  ++this->Stats.regionsExpanded;
  // A copy: crossings append to Regions.
  const Region parent = this->Regions[w.region];
  const ExitGate gate = this->exitGate(parent);
  const auto node = static_cast<std::size_t>(w.node);
  const auto via = static_cast<std::uint32_t>(parent.via); // no portal's index when -1
  const std::uint32_t end = this->ExitStart[node + 1];
  this->Stats.portalsTested += end - this->ExitStart[node];
  for (std::uint32_t e = this->ExitStart[node]; e < end; ++e)
  {
    const Exit& exit = this->Exits[e];
    // The rays of the parent crossed its entry portal's plane away from the eye, once: that
    // portal again, or one wholly on the eye's side of its plane, is out of their reach.
    if (exit.portal == via)
    {
      ++this->Stats.portalsBehind;
      continue;
    }
    const int beyond = gate.firstBeyond(exit.lo, exit.hi);
    if (beyond >= 0)
    {
      this->Stats.portalsBehind += beyond == 0 && gate.entryFirst ? 1 : 0;
      continue;
    }
    this->crossPortal(exit, w.region, parent);
    if (this->FrustumOnly)
    {
      return;
    }
  }
}

void PortalTraversal::crossPortal(const Exit& exit, std::uint32_t from, const Region& parent)
{
  const std::uint32_t index = exit.portal;
  const std::int32_t to = exit.to;
  const double slack = this->PlaneSlack;

  // Edge-on (the eye in the portal's plane; parallel rays along it) or non-planar: no narrowing
  // is possible or safe.
  const GraphPortal& portal = this->Graph->portals()[index];
  const bool edgeOn = this->View.parallel
    ? std::abs(glm::dot(glm::dvec3(portal.plane), this->Direction)) <= 1e-9
    : std::abs(geometry::planeDistance(portal.plane, this->View.eye)) <= slack;
  if (!portal.planar || edgeOn)
  {
    // The parent's region as it is, without clipping: the far, front and edge planes are the
    // last tests.
    if (culling::pVertexDistance(this->ViewFrustum.planes[culling::kFar], exit.lo, exit.hi) <
        -slack ||
      culling::pVertexDistance(this->FrontPlane, exit.lo, exit.hi) < -slack)
    {
      return;
    }
    for (std::uint32_t p = parent.firstPlane + 4; p < parent.firstPlane + parent.planeCount; ++p)
    {
      if (culling::pVertexDistance(this->Planes[p], exit.lo, exit.hi) < -slack)
      {
        return;
      }
    }
    if (this->attach(to, from, true))
    {
      ++this->Stats.portalsTraversed;
    }
    return;
  }

  const bool exact = this->Options.mode == NarrowingMode::ExactFrustum;
  const ClippedPortal& cached = this->clippedPortal(index);
  if (cached.count < 3)
  {
    return;
  }
  // The portal as clipped so far: the frame's cached polygon until a plane cuts it (most planes
  // keep all of it), then ClipA and ClipB in turn.
  const glm::dvec3* poly = this->ClippedVertices.data() + cached.first;
  std::size_t count = cached.count;
  if (exact)
  {
    // The region this crossing can make lies inside the cached portal and the parent's rectangle
    // (clipping keeps a polygon within its input's hull): when the room already has a region
    // that holds all of that, or nothing is left, the clipping is not needed.
    const glm::dvec4 most = intersectRects(cached.rect, parent.rect);
    if (!(most.x <= most.z && most.y <= most.w))
    {
      return;
    }
    if (this->subsumedInNode(to,
          RegionShape{
            most, static_cast<std::int32_t>(index), poly, static_cast<std::uint32_t>(count) }))
    {
      ++this->Stats.regionsSubsumed;
      return;
    }
  }
  auto clip = [&](const glm::dvec4& plane)
  {
    if (geometry::allKept(poly, count, plane, slack))
    {
      return true;
    }
    std::vector<glm::dvec3>& out = poly == this->ClipA.data() ? this->ClipB : this->ClipA;
    geometry::clipPolygon(poly, count, plane, slack, out);
    poly = out.data();
    count = out.size();
    return count >= 3;
  };
  if (exact)
  {
    if (parent.via >= 0 && !clip(parent.entry))
    {
      ++this->Stats.portalsBehind;
      return;
    }
    for (std::uint32_t p = parent.firstPlane; p < parent.firstPlane + parent.planeCount; ++p)
    {
      if (!clip(this->Planes[p]))
      {
        return;
      }
    }
  }

  // Screen rectangle of what is left, within the parent's.
  const glm::dvec4 rect = intersectRects(this->ndcBounds(poly, count), parent.rect);
  if (!(rect.x <= rect.z && rect.y <= rect.w))
  {
    return;
  }
  // A region the room already holds a bigger one of adds nothing: found before its planes are
  // made (most crossings of a frame on open levels end here).
  const RegionShape shape{ rect, static_cast<std::int32_t>(index), exact ? poly : nullptr,
    exact ? static_cast<std::uint32_t>(count) : 0U };
  if (this->subsumedInNode(to, shape))
  {
    ++this->Stats.regionsSubsumed;
    return;
  }

  const std::uint32_t id = this->addRegion(rect);
  {
    // The rays of the new region crossed this portal's plane away from the eye.
    glm::dvec4 entry = portal.plane;
    const double towards = this->View.parallel
      ? glm::dot(glm::dvec3(entry), this->Direction)
      : -geometry::planeDistance(entry, this->View.eye);
    Region& r = this->Regions[id];
    r.via = static_cast<std::int32_t>(index);
    r.entry = towards < 0.0 ? -entry : entry;
  }
  if (exact)
  {
    // Planes through the eye and each edge of the clipped portal, facing its centroid.
    glm::dvec3 centroid(0.0);
    for (std::size_t k = 0; k < count; ++k)
    {
      centroid += poly[k];
    }
    centroid /= static_cast<double>(count);
    // Parallel projection: planes through each edge containing the ray direction.
    const glm::dvec3& eye = this->View.eye;
    const bool parallel = this->View.parallel;
    std::uint32_t edges = 0;
    for (std::size_t k = 0; k < count; ++k)
    {
      const glm::dvec3& q0 = poly[k];
      const glm::dvec3& q1 = poly[(k + 1) % count];
      const glm::dvec3 p0 = parallel ? q1 - q0 : q0 - eye;
      const glm::dvec3 p1 = parallel ? this->Direction : q1 - eye;
      glm::dvec3 n = glm::cross(p0, p1);
      const double len = glm::length(n);
      if (!(len > 1e-12 * glm::length(p0) * glm::length(p1)))
      {
        continue; // degenerate edge: fewer planes = a bigger region
      }
      n /= len;
      glm::dvec4 plane(n, -glm::dot(n, parallel ? q0 : eye));
      if (geometry::planeDistance(plane, centroid) < 0.0)
      {
        plane = -plane;
      }
      this->Planes.push_back(plane);
      ++edges;
    }
    Region& r = this->Regions[id];
    r.edgePlanes = edges;
    r.planeCount += edges;
    r.firstVertex = static_cast<std::uint32_t>(this->Vertices.size());
    r.vertexCount = static_cast<std::uint32_t>(count);
    this->Vertices.insert(this->Vertices.end(), poly, poly + count);
  }
  if (this->attach(to, id, false))
  {
    ++this->Stats.portalsTraversed;
  }
}

void PortalTraversal::startRegion(std::int32_t node, bool expand)
{
  if (!this->NodeRegions[static_cast<std::size_t>(node)].empty())
  {
    return;
  }
  const std::uint32_t full = this->addRegion(glm::dvec4(-1.0, -1.0, 1.0, 1.0));
  if (expand)
  {
    this->attach(node, full, false);
  }
  else
  {
    this->NodeRegions[static_cast<std::size_t>(node)].push_back(full);
    this->Visible.push_back(node);
  }
}

EyeLocation PortalTraversal::startNodes(
  const PortalGraph& graph, const PortalView& view, const TraversalOptions& options)
{
  if (!view.parallel)
  {
    EyeLocation loc = graph.locate(view.eye, this->NearDistance, options.outside);
    if (loc.unknown)
    {
      this->fallBack(Fallback::EyeInNoRoom);
    }
    return loc;
  }
  // Parallel rays start anywhere on the near rectangle. Entirely outside the building's bounds
  // they start outside and enter through exterior portals; otherwise the rectangle may cut
  // through walls and voids, and which rooms rays start in is not worth finding: frustum only.
  EyeLocation loc;
  const Box& b = graph.buildingBounds();
  const Box& n = this->NearBox;
  const double t = graph.tolerance();
  const bool apart = b.empty() || n.hi.x < b.lo.x - t || n.hi.y < b.lo.y - t ||
    n.hi.z < b.lo.z - t || n.lo.x > b.hi.x + t || n.lo.y > b.hi.y + t || n.lo.z > b.hi.z + t;
  if (apart && options.outside == OutsidePolicy::ExteriorPortals)
  {
    loc.nodes.push_back(graph.outsideNode());
  }
  else
  {
    loc.unknown = true;
    this->fallBack(Fallback::ParallelProjection);
  }
  return loc;
}

void PortalTraversal::run(const PortalGraph& graph, const PortalView& view,
  const TraversalOptions& options)
{
  if (!this->begin(graph, view, options))
  {
    return;
  }
  const EyeLocation loc = this->startNodes(graph, view, options);
  if (this->FrustumOnly)
  {
    return;
  }
  this->Stats.startRooms = loc.nodes.size();
  for (const std::int32_t node : loc.nodes)
  {
    this->startRegion(node, true);
    if (this->FrustumOnly)
    {
      return;
    }
  }
  while (!this->WorkList.empty() && !this->FrustumOnly)
  {
    std::pop_heap(this->WorkList.begin(), this->WorkList.end(), narrower);
    const Work w = this->WorkList.back();
    this->WorkList.pop_back();
    if (w.generation != this->NodeGeneration[static_cast<std::size_t>(w.node)])
    {
      continue; // merged into a bigger region since it was queued
    }
    this->expand(w);
  }
  this->Stats.roomsVisited = this->Visible.size();
}

void PortalTraversal::runPvs(const PortalGraph& graph, const PortalPvs& pvs,
  const PortalView& view, const TraversalOptions& options)
{
  if (!this->begin(graph, view, options))
  {
    return;
  }
  if (pvs.nodeCount() != graph.nodeCount() || pvs.fingerprint() != graph.fingerprint())
  {
    this->fallBack(Fallback::InvalidView);
    return;
  }
  const EyeLocation loc = this->startNodes(graph, view, options);
  if (this->FrustumOnly)
  {
    return;
  }
  this->Stats.startRooms = loc.nodes.size();
  for (const std::int32_t node : loc.nodes)
  {
    for (const std::int32_t seen : pvs.visibleFrom(node))
    {
      this->startRegion(seen, false);
    }
  }
  this->Stats.roomsVisited = this->Visible.size();
}

void PortalTraversal::runFrustumOnly(const PortalGraph& graph, const PortalView& view)
{
  TraversalOptions options;
  if (this->begin(graph, view, options))
  {
    this->fallBack(Fallback::None);
  }
}

bool PortalTraversal::nodeVisible(std::int32_t node) const
{
  if (this->FrustumOnly)
  {
    return true;
  }
  return node >= 0 && static_cast<std::size_t>(node) < this->NodeRegions.size() &&
    !this->NodeRegions[static_cast<std::size_t>(node)].empty();
}

bool PortalTraversal::boxVisible(std::int32_t node, const Box& box) const
{
  if (box.empty())
  {
    return this->nodeVisible(node) || node < 0;
  }
  const culling::Frustum& f = this->ViewFrustum;
  if (this->FrustumOnly || node < 0 || !this->Graph || node >= this->Graph->nodeCount())
  {
    return !f.valid() || !culling::boxOutside(f, box.lo, box.hi);
  }
  if (!this->nodeVisible(node))
  {
    return false; // not reached (most rooms of a big building, for most props)
  }
  const double slack = this->PlaneSlack;
  if (culling::pVertexDistance(f.planes[culling::kNear], box.lo, box.hi) < -slack ||
    culling::pVertexDistance(f.planes[culling::kFar], box.lo, box.hi) < -slack)
  {
    return false;
  }
  for (const std::uint32_t r : this->NodeRegions[static_cast<std::size_t>(node)])
  {
    const Region& region = this->Regions[r];
    bool inside = true;
    for (std::uint32_t p = region.firstPlane; p < region.firstPlane + region.planeCount && inside;
         ++p)
    {
      inside = culling::pVertexDistance(this->Planes[p], box.lo, box.hi) >= -slack;
    }
    if (inside)
    {
      return true;
    }
  }
  return false;
}

void PortalTraversal::cullObjects(const std::vector<PortalObject>& objects,
  std::vector<std::uint8_t>& visible)
{
  visible.resize(objects.size());
  this->Stats.objectsDrawn = 0;
  this->Stats.objectsTotal = objects.size();
  this->Stats.trianglesDrawn = this->Stats.trianglesTotal = 0;
  for (std::size_t i = 0; i < objects.size(); ++i)
  {
    const PortalObject& o = objects[i];
    const bool v = this->boxVisible(o.node, o.bounds);
    visible[i] = v ? 1 : 0;
    this->Stats.trianglesTotal += o.triangles;
    if (v)
    {
      ++this->Stats.objectsDrawn;
      this->Stats.trianglesDrawn += o.triangles;
    }
  }
}

std::vector<glm::dvec4> PortalTraversal::regionRectangles(std::int32_t node) const
{
  std::vector<glm::dvec4> out;
  if (this->FrustumOnly)
  {
    out.emplace_back(-1.0, -1.0, 1.0, 1.0);
    return out;
  }
  if (node >= 0 && static_cast<std::size_t>(node) < this->NodeRegions.size())
  {
    for (const std::uint32_t r : this->NodeRegions[static_cast<std::size_t>(node)])
    {
      out.push_back(this->Regions[r].rect);
    }
  }
  return out;
}

} // namespace portals
} // namespace scenevis

#include "scenevis/PortalGraph.h"

#include "scenevis/PortalGeometry.h"
#include "scenevis/Scenes.h"

#include "PortalRays.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <utility>

namespace scenevis
{
namespace portals
{

std::size_t PortalGraphReport::count(PortalIssue::Severity severity) const
{
  return static_cast<std::size_t>(std::count_if(issues.begin(), issues.end(),
    [severity](const PortalIssue& issue) { return issue.severity == severity; }));
}

std::string PortalGraphReport::summary() const
{
  std::ostringstream out;
  for (const PortalIssue& issue : issues)
  {
    out << (issue.severity == PortalIssue::Severity::Error
               ? "error"
               : issue.severity == PortalIssue::Severity::Warning ? "warning" : "info");
    if (issue.portal >= 0)
    {
      out << ": portal " << issue.portal;
    }
    if (issue.room >= 0)
    {
      out << ": room " << issue.room;
    }
    out << ": " << issue.message << "\n";
  }
  return out.str();
}

std::vector<glm::dvec3> planarConvexHull(const std::vector<glm::dvec3>& points,
  const glm::dvec3& normal)
{
  if (points.size() < 3)
  {
    return points;
  }
  glm::dvec3 u, v;
  geometry::planeBasis(normal, u, v);
  struct P2
  {
    double x, y;
    std::size_t i;
  };
  std::vector<P2> p;
  p.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    p.push_back({ glm::dot(points[i], u), glm::dot(points[i], v), i });
  }
  std::sort(p.begin(), p.end(),
    [](const P2& a, const P2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  auto cross = [](const P2& o, const P2& a, const P2& b)
  { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  std::vector<P2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0.0)
    {
      --k;
    }
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i)
  {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0.0)
    {
      --k;
    }
    h[k++] = p[i - 1];
  }
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i + 1 < k; ++i)
  {
    out.push_back(points[h[i].i]);
  }
  return out;
}

namespace
{
constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;
void hashBytes(std::uint64_t& h, const void* data, std::size_t n)
{
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i)
  {
    h = (h ^ bytes[i]) * 1099511628211ull;
  }
}

bool finite(const glm::dvec3& p)
{
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

/// The two axes a boundary polygon keeps for its 2D point-in-polygon test (its normal's
/// dominant axis @p axis dropped): x the first, y the second.
struct KeptAxes
{
  int x, y;
  explicit KeptAxes(int axis)
    : x(axis == 0 ? 1 : 0)
    , y(axis == 2 ? 1 : 2)
  {
  }
};
} // namespace

std::int32_t PortalGraph::nodeOf(std::int32_t roomId) const
{
  if (roomId == kOutsideRoom)
  {
    return this->RoomCount;
  }
  return roomId >= 0 && roomId < this->RoomCount ? roomId : -1;
}

PortalGraph PortalGraph::build(const CellSceneInput& input, PortalGraphReport* reportOut)
{
  PortalGraphReport localReport;
  PortalGraphReport& report = reportOut ? *reportOut : localReport;
  report.issues.clear();
  auto issue = [&report](PortalIssue::Severity s, std::int32_t portal, std::int32_t room,
                 std::string message)
  { report.issues.push_back(PortalIssue{ s, portal, room, std::move(message) }); };
  using S = PortalIssue::Severity;

  PortalGraph g;
  const PolygonMesh* mesh = input.mesh;
  const std::size_t polygonCount = mesh ? mesh->polygonCount() : 0;
  if (mesh && input.roomOfPolygon.size() != polygonCount)
  {
    issue(S::Error, -1, -1,
      "roomOfPolygon has " + std::to_string(input.roomOfPolygon.size()) + " entries for " +
        std::to_string(polygonCount) + " polygons; the geometry is ignored for room location");
    mesh = nullptr;
  }

  // --- Room ids in use. ---------------------------------------------------------------------
  std::int32_t maxGeometryRoom = -1;
  std::size_t badPolygonRooms = 0;
  if (mesh)
  {
    for (const std::int32_t r : input.roomOfPolygon)
    {
      if (r < kOutsideRoom)
      {
        ++badPolygonRooms;
      }
      maxGeometryRoom = std::max(maxGeometryRoom, r);
    }
  }
  if (badPolygonRooms)
  {
    issue(S::Warning, -1, -1,
      std::to_string(badPolygonRooms) +
        " polygons have a room id below -1; they belong to no room (the VTK culler draws such "
        "geometry whenever it is in the frustum)");
  }
  // Portal ends per id, to find ids that only a single portal names (dangling).
  std::map<std::int32_t, int> portalEnds;
  for (const PortalDesc& p : input.portals)
  {
    ++portalEnds[p.roomA];
    ++portalEnds[p.roomB];
  }
  std::vector<char> hasGeometry(static_cast<std::size_t>(std::max(maxGeometryRoom + 1, 0)), 0);
  if (mesh)
  {
    for (const std::int32_t r : input.roomOfPolygon)
    {
      if (r >= 0)
      {
        hasGeometry[static_cast<std::size_t>(r)] = 1;
      }
    }
  }
  auto known = [&](std::int32_t id)
  {
    if (id == kOutsideRoom)
    {
      return true;
    }
    if (id < kOutsideRoom)
    {
      return false;
    }
    if (input.roomCount >= 0)
    {
      return id < input.roomCount;
    }
    // Inferred room set: a room must have geometry or (without geometry) join two portals.
    if (!mesh)
    {
      return true;
    }
    const bool geometry =
      static_cast<std::size_t>(id) < hasGeometry.size() && hasGeometry[static_cast<std::size_t>(id)];
    return geometry || portalEnds[id] >= 2;
  };
  std::int32_t roomCount = input.roomCount;
  if (roomCount < 0)
  {
    roomCount = maxGeometryRoom + 1;
    for (const PortalDesc& p : input.portals)
    {
      for (const std::int32_t id : { p.roomA, p.roomB })
      {
        if (known(id))
        {
          roomCount = std::max(roomCount, id + 1);
        }
      }
    }
  }
  g.RoomCount = std::max(roomCount, 0);
  g.Rooms.resize(static_cast<std::size_t>(g.RoomCount) + 1);

  // --- Scene size and tolerance. ------------------------------------------------------------
  Box all;
  if (mesh)
  {
    for (const auto& p : mesh->points)
    {
      if (finite(p))
      {
        all.extend(p);
      }
    }
  }
  for (const PortalDesc& p : input.portals)
  {
    for (const auto& q : p.polygon)
    {
      if (finite(q))
      {
        all.extend(q);
      }
    }
  }
  g.Tolerance = std::max(1e-9 * all.diagonal(), 1e-12);

  // --- Portals. -----------------------------------------------------------------------------
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::uint32_t>> byPair;
  std::vector<std::vector<glm::dvec3>> parityPolygon; // per graph portal, the input projected
  for (std::size_t i = 0; i < input.portals.size(); ++i)
  {
    const PortalDesc& in = input.portals[i];
    const auto pi = static_cast<std::int32_t>(i);
    const bool knownA = known(in.roomA), knownB = known(in.roomB);
    if (!knownA && !knownB)
    {
      issue(S::Error, pi, -1,
        "both room ids (" + std::to_string(in.roomA) + ", " + std::to_string(in.roomB) +
          ") are dangling; portal dropped");
      continue;
    }
    if (!knownA || !knownB)
    {
      const std::int32_t good = knownA ? in.roomA : in.roomB;
      const std::int32_t bad = knownA ? in.roomB : in.roomA;
      issue(S::Error, pi, good,
        "dangling room id " + std::to_string(bad) +
          "; portal dropped and the room marked leaky (frustum-only culling once it is seen)");
      g.Rooms[static_cast<std::size_t>(g.nodeOf(good))].leaky = true;
      continue;
    }
    if (in.roomA == in.roomB)
    {
      issue(S::Warning, pi, in.roomA, "joins a room to itself; dropped");
      continue;
    }
    if (in.polygon.size() < 3)
    {
      issue(S::Error, pi, -1,
        "has " + std::to_string(in.polygon.size()) + " points (needs >= 3); dropped");
      continue;
    }
    if (!std::all_of(in.polygon.begin(), in.polygon.end(), finite))
    {
      issue(S::Error, pi, -1,
        "has non-finite points; dropped and both rooms marked leaky");
      g.Rooms[static_cast<std::size_t>(g.nodeOf(in.roomA))].leaky = true;
      g.Rooms[static_cast<std::size_t>(g.nodeOf(in.roomB))].leaky = true;
      continue;
    }
    GraphPortal gp;
    gp.input = pi;
    gp.nodeA = g.nodeOf(in.roomA);
    gp.nodeB = g.nodeOf(in.roomB);
    glm::dvec3 n(0.0), c(0.0);
    for (std::size_t k = 0; k < in.polygon.size(); ++k)
    {
      const glm::dvec3& a = in.polygon[k];
      const glm::dvec3& b = in.polygon[(k + 1) % in.polygon.size()];
      n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
        (a.x - b.x) * (a.y + b.y));
      c += a;
      gp.bounds.extend(a);
    }
    c /= static_cast<double>(in.polygon.size());
    const double size = std::max(gp.bounds.diagonal(), g.Tolerance);
    const double len = glm::length(n);
    if (!(len > 1e-12 * size * size))
    {
      issue(S::Error, pi, -1, "has zero area; dropped");
      continue;
    }
    n /= len;
    gp.plane = glm::dvec4(n, -glm::dot(n, c));
    double deviation = 0.0;
    for (const auto& q : in.polygon)
    {
      deviation = std::max(deviation, std::abs(glm::dot(n, q) + gp.plane.w));
    }
    if (deviation > 1e-3 * size)
    {
      gp.planar = false;
      issue(S::Warning, pi, -1,
        "is not planar (a point is " + std::to_string(deviation) +
          " from its plane); the view passes through it un-narrowed");
    }
    // Points projected onto the plane, so the hull and the parity polygon lie in it exactly.
    std::vector<glm::dvec3> projected;
    projected.reserve(in.polygon.size());
    for (const auto& q : in.polygon)
    {
      projected.push_back(q - n * (glm::dot(n, q) + gp.plane.w));
    }
    gp.hull = planarConvexHull(projected, n);
    if (gp.hull.size() < 3)
    {
      issue(S::Error, pi, -1, "is degenerate (collinear points); dropped");
      continue;
    }
    const double polygonArea = 0.5 * len;
    const double hullArea = 0.5 * glm::length(geometry::newellOf(gp.hull));
    if (hullArea > polygonArea * (1.0 + 1e-9))
    {
      issue(S::Info, pi, -1, "is concave or self-intersecting; its convex hull is used");
    }
    gp.centroid = glm::dvec3(0.0);
    for (const auto& q : gp.hull)
    {
      gp.centroid += q;
    }
    gp.centroid /= static_cast<double>(gp.hull.size());
    // Duplicates: same pair of nodes, every hull point matched within tolerance.
    const auto key = std::make_pair(std::min(gp.nodeA, gp.nodeB), std::max(gp.nodeA, gp.nodeB));
    bool duplicate = false;
    const double matchTol = std::max(1e-6 * size, g.Tolerance);
    for (const std::uint32_t other : byPair[key])
    {
      const GraphPortal& o = g.Portals[other];
      if (o.hull.size() != gp.hull.size())
      {
        continue;
      }
      const bool same = std::all_of(gp.hull.begin(), gp.hull.end(),
        [&](const glm::dvec3& q)
        {
          return std::any_of(o.hull.begin(), o.hull.end(),
            [&](const glm::dvec3& r) { return glm::length(q - r) <= matchTol; });
        });
      if (same)
      {
        issue(S::Warning, pi, -1,
          "duplicates portal " + std::to_string(o.input) + "; dropped");
        duplicate = true;
        break;
      }
    }
    if (duplicate)
    {
      continue;
    }
    byPair[key].push_back(static_cast<std::uint32_t>(g.Portals.size()));
    parityPolygon.push_back(std::move(projected));
    g.Portals.push_back(std::move(gp));
  }
  for (std::uint32_t i = 0; i < g.Portals.size(); ++i)
  {
    const GraphPortal& p = g.Portals[i];
    for (const std::int32_t node : { p.nodeA, p.nodeB })
    {
      GraphRoom& room = g.Rooms[static_cast<std::size_t>(node)];
      room.portals.push_back(i);
      room.bounds.extend(p.bounds);
    }
  }

  // --- Boundary polygons per room (for the inside test), minus portal coverings. -------------
  std::vector<std::vector<std::uint32_t>> polygonsOf(g.Rooms.size());
  std::size_t nonFinitePolygons = 0;
  if (mesh)
  {
    for (std::size_t i = 0; i < polygonCount; ++i)
    {
      const std::int32_t node = g.nodeOf(input.roomOfPolygon[i]);
      if (node < 0)
      {
        continue;
      }
      const std::uint32_t* ids = mesh->polygon(i);
      const std::uint32_t count = mesh->polygonSize(i);
      bool ok = count >= 3;
      for (std::uint32_t k = 0; k < count && ok; ++k)
      {
        ok = ids[k] < mesh->points.size() && finite(mesh->points[ids[k]]);
      }
      if (!ok)
      {
        ++nonFinitePolygons;
        continue;
      }
      GraphRoom& room = g.Rooms[static_cast<std::size_t>(node)];
      for (std::uint32_t k = 0; k < count; ++k)
      {
        room.bounds.extend(mesh->points[ids[k]]);
      }
      polygonsOf[static_cast<std::size_t>(node)].push_back(static_cast<std::uint32_t>(i));
    }
  }
  if (nonFinitePolygons)
  {
    issue(S::Warning, -1, -1,
      std::to_string(nonFinitePolygons) +
        " polygons have fewer than 3 points, bad point ids or non-finite points; ignored for "
        "room location");
  }
  auto addBoundary = [&g](const glm::dvec3* pts, const std::uint32_t* ids, std::size_t count)
  {
    BoundaryPolygon bp;
    bp.first = static_cast<std::uint32_t>(g.PolygonPoints.size());
    bp.count = static_cast<std::uint32_t>(count);
    glm::dvec3 n(0.0), c(0.0);
    for (std::size_t k = 0; k < count; ++k)
    {
      const glm::dvec3& p = ids ? pts[ids[k]] : pts[k];
      g.PolygonPoints.push_back(p);
      c += p;
    }
    n = geometry::newellOf(g.PolygonPoints.data() + bp.first, count);
    const double len = glm::length(n);
    if (!(len > 0.0))
    {
      g.PolygonPoints.resize(bp.first);
      return false;
    }
    n /= len;
    c /= static_cast<double>(count);
    bp.plane = glm::dvec4(n, -glm::dot(n, c));
    const glm::dvec3 a = glm::abs(n);
    bp.axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    const KeptAxes kept(bp.axis);
    const glm::dvec3* stored = g.PolygonPoints.data() + bp.first;
    double xLo = stored[0][kept.x], xHi = xLo;
    bp.yLo = bp.yHi = stored[0][kept.y];
    for (std::size_t k = 1; k < count; ++k)
    {
      xLo = std::min(xLo, stored[k][kept.x]);
      xHi = std::max(xHi, stored[k][kept.x]);
      bp.yLo = std::min(bp.yLo, stored[k][kept.y]);
      bp.yHi = std::max(bp.yHi, stored[k][kept.y]);
    }
    bp.xBeyond = xHi + 1e-9 * (std::abs(xHi) + (xHi - xLo));
    g.Polygons.push_back(bp);
    return true;
  };
  for (std::size_t node = 0; node < g.Rooms.size(); ++node)
  {
    GraphRoom& room = g.Rooms[node];
    room.firstPolygon = static_cast<std::uint32_t>(g.Polygons.size());
    for (const std::uint32_t poly : polygonsOf[node])
    {
      const std::uint32_t* ids = mesh->polygon(poly);
      const std::uint32_t count = mesh->polygonSize(poly);
      // A polygon lying in one of the room's portal openings (glass, a door leaf) would cancel
      // the portal's crossing in the parity count: the portal is the boundary there.
      bool covering = false;
      for (const std::uint32_t pi : room.portals)
      {
        const GraphPortal& p = g.Portals[pi];
        const double tol = std::max(1e-6 * p.bounds.diagonal(), g.Tolerance);
        bool within = true;
        for (std::uint32_t k = 0; k < count && within; ++k)
        {
          const glm::dvec3& q = mesh->points[ids[k]];
          within = std::abs(glm::dot(glm::dvec3(p.plane), q) + p.plane.w) <= tol &&
            geometry::insideConvex(p.hull, glm::dvec3(p.plane), q, tol);
        }
        if (within)
        {
          covering = true;
          break;
        }
      }
      if (!covering)
      {
        addBoundary(mesh->points.data(), ids, count);
      }
    }
    if (g.Polygons.size() > room.firstPolygon)
    {
      for (const std::uint32_t pi : room.portals)
      {
        addBoundary(parityPolygon[pi].data(), nullptr, parityPolygon[pi].size());
      }
    }
    room.polygonCount = static_cast<std::uint32_t>(g.Polygons.size()) - room.firstPolygon;
  }
  for (std::int32_t r = 0; r < g.RoomCount; ++r)
  {
    g.BuildingBounds.extend(g.Rooms[static_cast<std::size_t>(r)].bounds);
    g.AnyLeaky = g.AnyLeaky || g.Rooms[static_cast<std::size_t>(r)].leaky;
  }
  g.AnyLeaky = g.AnyLeaky || g.Rooms.back().leaky;

  g.buildGrid();
  g.buildRayGrids();

  // --- Fingerprint: topology and portal geometry. --------------------------------------------
  std::uint64_t h = kFnvOffset;
  hashBytes(h, &g.RoomCount, sizeof(g.RoomCount));
  for (const GraphPortal& p : g.Portals)
  {
    hashBytes(h, &p.nodeA, sizeof(p.nodeA));
    hashBytes(h, &p.nodeB, sizeof(p.nodeB));
    for (const auto& q : p.hull)
    {
      hashBytes(h, &q, sizeof(q));
    }
  }
  g.Fingerprint = h;
  return g;
}

bool PortalGraph::BoxGrid::cellRange(
  const glm::dvec3& a, const glm::dvec3& b, glm::ivec3& lo, glm::ivec3& hi) const
{
  if (this->empty() || b.x < this->bounds.lo.x || b.y < this->bounds.lo.y ||
    b.z < this->bounds.lo.z || a.x > this->bounds.hi.x || a.y > this->bounds.hi.y ||
    a.z > this->bounds.hi.z)
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    // Clamped in double before the conversion: far-away or huge inputs stay defined.
    const double l = std::floor((a[k] - this->bounds.lo[k]) * this->inverseCell[k]);
    const double h = std::floor((b[k] - this->bounds.lo[k]) * this->inverseCell[k]);
    const double top = static_cast<double>(this->dims[k] - 1);
    lo[k] = static_cast<int>(std::clamp(l, 0.0, top));
    hi[k] = static_cast<int>(std::clamp(h, 0.0, top));
  }
  return true;
}

void PortalGraph::buildGrid()
{
  BoxGrid& grid = this->Grid;
  grid = BoxGrid();
  Box all = this->BuildingBounds;
  for (const GraphPortal& p : this->Portals)
  {
    all.extend(p.bounds);
  }
  if (all.empty() || this->RoomCount <= 0)
  {
    return;
  }
  const double t = this->Tolerance;
  grid.bounds.lo = all.lo - glm::dvec3(t);
  grid.bounds.hi = all.hi + glm::dvec3(t);
  // About one cell per room: cubic cells of the size that gives that count for the volume, so
  // a flat building gets a flat grid. At most 128 cells per axis (2M cells).
  const glm::dvec3 extent = grid.bounds.hi - grid.bounds.lo;
  const double largest = std::max({ extent.x, extent.y, extent.z });
  const glm::dvec3 clampedExtent = glm::max(extent, glm::dvec3(1e-3 * largest));
  const double volume = clampedExtent.x * clampedExtent.y * clampedExtent.z;
  const double cell = std::cbrt(volume / static_cast<double>(this->RoomCount));
  for (int k = 0; k < 3; ++k)
  {
    const double n = std::ceil(extent[k] / cell);
    grid.dims[k] = static_cast<int>(std::clamp(std::isfinite(n) ? n : 1.0, 1.0, 128.0));
    grid.inverseCell[k] = extent[k] > 0.0 ? grid.dims[k] / extent[k] : 0.0;
  }
  const auto cells = static_cast<std::size_t>(grid.dims.x) * grid.dims.y * grid.dims.z;
  auto fill = [&](std::size_t count, auto boxOf, std::vector<std::uint32_t>& start,
                std::vector<std::uint32_t>& items)
  {
    start.assign(cells + 1, 0);
    glm::ivec3 lo, hi;
    for (int pass = 0; pass < 2; ++pass)
    {
      for (std::size_t i = 0; i < count; ++i)
      {
        const Box& b = boxOf(i);
        if (b.empty() || !grid.cellRange(b.lo - glm::dvec3(t), b.hi + glm::dvec3(t), lo, hi))
        {
          continue;
        }
        for (int z = lo.z; z <= hi.z; ++z)
        {
          for (int y = lo.y; y <= hi.y; ++y)
          {
            for (int x = lo.x; x <= hi.x; ++x)
            {
              const std::size_t c =
                (static_cast<std::size_t>(z) * grid.dims.y + y) * grid.dims.x + x;
              if (pass == 0)
              {
                ++start[c + 1];
              }
              else
              {
                items[start[c]++] = static_cast<std::uint32_t>(i);
              }
            }
          }
        }
      }
      if (pass == 0)
      {
        for (std::size_t c = 0; c < cells; ++c)
        {
          start[c + 1] += start[c];
        }
        items.resize(start[cells]);
      }
    }
    // The second pass advanced each start to the next cell's: shift back.
    for (std::size_t c = cells; c > 0; --c)
    {
      start[c] = start[c - 1];
    }
    start[0] = 0;
  };
  fill(
    static_cast<std::size_t>(this->RoomCount),
    [this](std::size_t i) -> const Box& { return this->Rooms[i].bounds; }, grid.roomStart,
    grid.rooms);
  fill(
    this->Portals.size(), [this](std::size_t i) -> const Box& { return this->Portals[i].bounds; },
    grid.portalStart, grid.portals);
}

int PortalGraph::parity(std::int32_t room, const glm::dvec3& p, int direction) const
{
  const GraphRoom& r = this->Rooms[static_cast<std::size_t>(room)];
  const glm::dvec3& dir = rays::direction(direction);
  // The room's polygons, or those of the grid cell that holds p's projection (none outside the
  // grid: no polygon's projection holds it).
  const std::uint32_t* listed = nullptr;
  std::uint32_t first = r.firstPolygon, count = r.polygonCount;
  const RayGrid* grid = this->RayGrids.empty()
    ? nullptr
    : &this->RayGrids[static_cast<std::size_t>(room) * rays::kCount + direction];
  if (grid && grid->nu > 0)
  {
    glm::dvec3 u, v;
    rays::basis(direction, u, v);
    const double cu = std::floor((glm::dot(u, p) - grid->u0) * grid->inverseCell);
    const double cv = std::floor((glm::dot(v, p) - grid->v0) * grid->inverseCell);
    if (!(cu >= 0.0 && cu < grid->nu && cv >= 0.0 && cv < grid->nv))
    {
      return 0;
    }
    const std::size_t cell = static_cast<std::size_t>(cv) * grid->nu + static_cast<std::size_t>(cu);
    listed = grid->polygons.data() + grid->start[cell];
    first = 0;
    count = grid->start[cell + 1] - grid->start[cell];
  }
  int crossings = 0;
  for (std::uint32_t i = 0; i < count; ++i)
  {
    const BoundaryPolygon& bp = this->Polygons[listed ? listed[i] : first + i];
    const glm::dvec3 n(bp.plane);
    const double denom = glm::dot(n, dir);
    if (denom == 0.0)
    {
      continue;
    }
    const double t = -(glm::dot(n, p) + bp.plane.w) / denom;
    if (!(t > 0.0))
    {
      continue;
    }
    const glm::dvec3 q = p + t * dir;
    // Crossing-number test in the plane of the two non-dominant axes.
    const KeptAxes kept(bp.axis);
    const int ax = kept.x, ay = kept.y;
    if (q[ay] < bp.yLo || q[ay] >= bp.yHi || q[ax] > bp.xBeyond)
    {
      continue; // no edge the loop below would count (see BoundaryPolygon)
    }
    bool in = false;
    const glm::dvec3* pts = this->PolygonPoints.data() + bp.first;
    for (std::uint32_t k = 0, j = bp.count - 1; k < bp.count; j = k++)
    {
      const double yi = pts[k][ay], yj = pts[j][ay];
      if ((yi > q[ay]) != (yj > q[ay]))
      {
        const double x = pts[k][ax] + (q[ay] - yi) * (pts[j][ax] - pts[k][ax]) / (yj - yi);
        if (q[ax] < x)
        {
          in = !in;
        }
      }
    }
    crossings += in ? 1 : 0;
  }
  return crossings & 1;
}

bool PortalGraph::inside(std::int32_t room, const glm::dvec3& p) const
{
  if (room < 0 || room >= this->RoomCount)
  {
    return false;
  }
  const GraphRoom& r = this->Rooms[static_cast<std::size_t>(room)];
  const double t = this->Tolerance;
  if (r.bounds.empty() || p.x < r.bounds.lo.x - t || p.y < r.bounds.lo.y - t ||
    p.z < r.bounds.lo.z - t || p.x > r.bounds.hi.x + t || p.y > r.bounds.hi.y + t ||
    p.z > r.bounds.hi.z + t)
  {
    return false;
  }
  if (r.polygonCount == 0)
  {
    return true;
  }
  // Three fixed directions in general position (src/PortalRays.h); the majority vote absorbs a
  // ray that grazes an edge or a crack between polygons. Two agreeing rays decide the vote; the
  // third is cast only when they disagree.
  const int first = this->parity(room, p, 0);
  const int second = this->parity(room, p, 1);
  if (first == second)
  {
    return first == 1;
  }
  return this->parity(room, p, 2) == 1;
}

EyeLocation PortalGraph::locate(const glm::dvec3& eye, double nearDistance,
  OutsidePolicy policy) const
{
  EyeLocation loc;
  if (!finite(eye))
  {
    loc.unknown = true;
    return loc;
  }
  const BoxGrid& grid = this->Grid;
  glm::ivec3 lo, hi;
  if (grid.cellRange(eye, eye, lo, hi))
  {
    const std::size_t c =
      (static_cast<std::size_t>(lo.z) * grid.dims.y + lo.y) * grid.dims.x + lo.x;
    for (std::uint32_t k = grid.roomStart[c]; k < grid.roomStart[c + 1]; ++k)
    {
      const auto r = static_cast<std::int32_t>(grid.rooms[k]);
      if (this->inside(r, eye))
      {
        loc.nodes.push_back(r);
      }
    }
    // Ascending ids whatever the grid's order (callers and tests see a stable order).
    std::sort(loc.nodes.begin(), loc.nodes.end());
  }
  const std::size_t inRooms = loc.nodes.size();
  const double reach = std::max(nearDistance, this->Tolerance);
  std::vector<std::uint32_t> candidates;
  if (grid.cellRange(eye - glm::dvec3(reach), eye + glm::dvec3(reach), lo, hi))
  {
    for (int z = lo.z; z <= hi.z; ++z)
    {
      for (int y = lo.y; y <= hi.y; ++y)
      {
        for (int x = lo.x; x <= hi.x; ++x)
        {
          const std::size_t c = (static_cast<std::size_t>(z) * grid.dims.y + y) * grid.dims.x + x;
          candidates.insert(candidates.end(), grid.portals.begin() + grid.portalStart[c],
            grid.portals.begin() + grid.portalStart[c + 1]);
        }
      }
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  }
  for (const std::uint32_t pi : candidates)
  {
    const GraphPortal& p = this->Portals[pi];
    const Box& b = p.bounds;
    if (eye.x < b.lo.x - reach || eye.y < b.lo.y - reach || eye.z < b.lo.z - reach ||
      eye.x > b.hi.x + reach || eye.y > b.hi.y + reach || eye.z > b.hi.z + reach)
    {
      continue;
    }
    if (geometry::distanceToConvex(p.hull, glm::dvec3(p.plane), eye) <= reach)
    {
      for (const std::int32_t node : { p.nodeA, p.nodeB })
      {
        if (std::find(loc.nodes.begin(), loc.nodes.end(), node) == loc.nodes.end())
        {
          loc.nodes.push_back(node);
        }
      }
    }
  }
  loc.nearPortalNodes = loc.nodes.size() - inRooms;
  if (loc.nodes.empty())
  {
    const Box& b = this->BuildingBounds;
    const double t = this->Tolerance;
    const bool outsideBuilding = b.empty() || eye.x < b.lo.x - t || eye.y < b.lo.y - t ||
      eye.z < b.lo.z - t || eye.x > b.hi.x + t || eye.y > b.hi.y + t || eye.z > b.hi.z + t;
    if (policy == OutsidePolicy::ExteriorPortals && outsideBuilding)
    {
      loc.nodes.push_back(this->outsideNode());
    }
    else
    {
      loc.unknown = true;
    }
  }
  return loc;
}

CellSceneInput cellSceneOf(const scenes::BuildingScene& building)
{
  CellSceneInput in;
  in.mesh = &building.mesh;
  in.roomOfPolygon = building.room;
  in.roomCount = static_cast<std::int32_t>(building.rooms.size());
  in.portals.reserve(building.portals.size());
  for (const auto& p : building.portals)
  {
    in.portals.push_back(PortalDesc{ p.polygon, p.roomA, p.roomB });
  }
  return in;
}

} // namespace portals
} // namespace scenevis

// libFuzzer target for automatic rooms and portals (PortalGeneration.h): arbitrary bytes -> a grid
// of up to 3 x 3 closed box rooms (zero-thickness walls, each room's faces facing into it) with
// doors and windows of random sizes and places in the walls between them, now and then a door or a
// window to the outside (flag 8; flags 64 and 128 pick the exterior wall: x = 0, the far x wall,
// y = 0 or the far y wall), a 1e7 offset, degenerate and NaN/Inf polygons mixed in, or free
// triangles anywhere.
// Flag 32 drops one polygon of the rooms (a leak, sanity checks only). Flag 16 also runs it with
// GenerationConfig::stopAtFirstLeak, which must give the same answer without a leak and one leak
// cell with no rooms when there is one.
//
// Oracle (the scene is built from known rooms and openings; not just "no crash"):
// - always: a sane answer (a status of the enum; without Ok no rooms and no portals; a room id in
//   range for every polygon; portals with finite points and ordered room pairs);
// - for the box rooms, with or without degenerate/NaN polygons (which must be dropped, nothing
//   more): status Ok, no leak, every polygon of one authored room in the same generated room, never
//   the outside, and every opening covered: its two rooms are one generated room, or a portal
//   joining their generated rooms contains all four corners of the opening (a portal is never
//   smaller than the opening it stands for). Rooms may merge (passages do): conservative.
// Free triangles change the rooms legitimately: then only the sanity checks and the sanitizers.
//
// SCENEVIS_FUZZ_SELFTEST=1 shrinks every portal by 5 % about its centroid before the check (must
// abort on any input with a door); SCENEVIS_FUZZ_VERBOSE=1 prints the rooms, portals and openings.
// Seeds: scenevis_fuzz_make_portal_corpus writes them (CTest does, before Fuzz.PortalCorpus).
#include "scenevis/PortalGeneration.h"
#include "scenevis/PortalGeometry.h"
#include "scenevis/PortalGraph.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <vector>

namespace
{
using namespace scenevis;
using namespace scenevis::portals;

/// Reads bytes; past the end, zeros (so the empty input is one closed room).
struct Reader
{
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint8_t byte() { return at < size ? data[at++] : 0; }
  double unit() { return byte() / 255.0; }
};

/// A rectangle in the plane coordinate[axis] == at between two authored rooms (-1: outside).
struct Opening
{
  int axis = 0;
  double at = 0.0;
  glm::dvec3 lo{ 0.0 }, hi{ 0.0 };
  int roomA = 0, roomB = 0;
};

struct Scene
{
  PolygonMesh mesh;
  std::vector<int> authoredRoom; ///< Per polygon; -1 for garbage.
  std::vector<Box> rooms;
  std::vector<Opening> openings;
  glm::dvec3 origin{ 0.0 };

  void quad(int r, int axis, double at, bool positive, double u0, double u1, double v0, double v1)
  {
    if (u1 - u0 <= 0 || v1 - v0 <= 0)
    {
      return;
    }
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    std::uint32_t ids[4];
    for (int k = 0; k < 4; ++k)
    {
      glm::dvec3 p(0.0);
      p[axis] = at;
      p[u] = (k == 1 || k == 2) ? u1 : u0;
      p[v] = (k >= 2) ? v1 : v0;
      ids[positive ? k : 3 - k] = mesh.addPoint(p + origin);
    }
    mesh.addPolygon(ids, 4);
    authoredRoom.push_back(r);
  }
  /// Room @p r's six faces facing into it, each split around its (at most one) opening.
  void faces(int r)
  {
    const Box& b = rooms[static_cast<std::size_t>(r)];
    for (int axis = 0; axis < 3; ++axis)
    {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (const bool atLo : { true, false })
      {
        const double at = atLo ? b.lo[axis] : b.hi[axis];
        const Opening* hole = nullptr;
        for (const Opening& o : openings)
        {
          if ((o.roomA == r || o.roomB == r) && o.axis == axis && o.at == at)
          {
            hole = &o;
          }
        }
        if (!hole)
        {
          quad(r, axis, at, atLo, b.lo[u], b.hi[u], b.lo[v], b.hi[v]);
          continue;
        }
        quad(r, axis, at, atLo, b.lo[u], b.hi[u], b.lo[v], hole->lo[v]);
        quad(r, axis, at, atLo, b.lo[u], b.hi[u], hole->hi[v], b.hi[v]);
        quad(r, axis, at, atLo, b.lo[u], hole->lo[u], hole->lo[v], hole->hi[v]);
        quad(r, axis, at, atLo, hole->hi[u], b.hi[u], hole->lo[v], hole->hi[v]);
      }
    }
  }
  /// An opening in the wall coordinate[axis] == at, spanning [u0, u1] along the wall's other
  /// horizontal axis: a door from the floor or a window, its size and place from the bytes.
  void opening(Reader& in, int a, int b, int axis, double at, double u0, double u1, double height)
  {
    const int u = axis == 0 ? 1 : 0;
    const double length = u1 - u0, margin = 0.25;
    const double width = 0.2 + in.unit() * (length - 2 * margin - 0.2);
    const double start = u0 + margin + in.unit() * (length - 2 * margin - width);
    const bool door = in.byte() % 2 == 0;
    const double bottom = door ? 0.0 : margin + in.unit() * (height - 2 * margin - 0.3);
    const double top = bottom + 0.3 + in.unit() * (height - margin - bottom - 0.3);
    Opening o;
    o.axis = axis;
    o.at = at;
    o.lo[axis] = o.hi[axis] = at;
    o.lo[u] = start;
    o.hi[u] = start + width;
    o.lo[2] = bottom;
    o.hi[2] = top;
    o.roomA = a;
    o.roomB = b;
    openings.push_back(o);
  }
};

[[noreturn]] void fail(const char* what, long long detail)
{
  std::fprintf(stderr, "portal generation fuzz: %s (%lld)\n", what, detail);
  std::abort();
}

bool finite(const glm::dvec3& p)
{
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

/// Whether @p point lies in the portal's plane and inside its convex polygon (within @p tol).
bool portalCovers(const PortalDesc& portal, const glm::dvec3& point, double tol)
{
  const glm::dvec3 n = glm::normalize(geometry::newellOf(portal.polygon));
  if (std::abs(glm::dot(n, point - portal.polygon[0])) > tol)
  {
    return false;
  }
  return geometry::insideConvex(planarConvexHull(portal.polygon, n), n, point, tol);
}

void checkSane(const GeneratedPortals& g, std::size_t polygons)
{
  if (g.status != GenerationStatus::Ok && g.status != GenerationStatus::EmptyInput &&
    g.status != GenerationStatus::NoValidPolygons && g.status != GenerationStatus::OverBudget)
  {
    fail("status out of the enum", static_cast<long long>(g.status));
  }
  if (g.status != GenerationStatus::Ok && (g.roomCount != 0 || !g.portals.empty()))
  {
    fail("rooms or portals without status Ok", g.roomCount);
  }
  if (g.status == GenerationStatus::Ok && g.roomOfPolygon.size() != polygons)
  {
    fail("roomOfPolygon size differs from the polygon count", g.roomOfPolygon.size());
  }
  if (g.roomCount < 0)
  {
    fail("negative room count", g.roomCount);
  }
  for (const std::int32_t r : g.roomOfPolygon)
  {
    if (r < kOutsideRoom || r >= g.roomCount)
    {
      fail("polygon room id out of range", r);
    }
  }
  for (const PortalDesc& p : g.portals)
  {
    if (p.polygon.size() < 3)
    {
      fail("portal with fewer than 3 points", p.polygon.size());
    }
    if (!std::all_of(p.polygon.begin(), p.polygon.end(), finite))
    {
      fail("portal with a non-finite point", 0);
    }
    const bool exterior = p.roomB == kOutsideRoom;
    if (p.roomA < 0 || p.roomA >= g.roomCount ||
      (!exterior && (p.roomB <= p.roomA || p.roomB >= g.roomCount)))
    {
      fail("portal room pair out of range or unordered", p.roomA * 1000LL + p.roomB);
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Reader in{ data, size };
  const std::uint8_t flags = in.byte();
  const bool offset = flags & 1, badPolygons = flags & 2, freeTriangles = flags & 4,
             outsideOpening = flags & 8;
  Scene s;
  if (offset)
  {
    s.origin = glm::dvec3(1e7, -1e7, 5e6);
  }
  const int nx = 1 + in.byte() % 3, ny = 1 + in.byte() % 3;
  std::vector<double> xs{ 0.0 }, ys{ 0.0 };
  for (int i = 0; i < nx; ++i)
  {
    xs.push_back(xs.back() + 3.0 + (in.byte() % 8) * 0.5);
  }
  for (int j = 0; j < ny; ++j)
  {
    ys.push_back(ys.back() + 3.0 + (in.byte() % 8) * 0.5);
  }
  const double height = 2.5 + (in.byte() % 4) * 0.5;
  auto id = [nx](int i, int j) { return j * nx + i; };
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      Box b;
      b.extend({ xs[i], ys[j], 0.0 });
      b.extend({ xs[i + 1], ys[j + 1], height });
      s.rooms.push_back(b);
    }
  }
  // An opening in a wall between neighbours for two bytes in three.
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      if (i + 1 < nx && in.byte() % 3 != 0)
      {
        s.opening(in, id(i, j), id(i + 1, j), 0, xs[i + 1], ys[j], ys[j + 1], height);
      }
      if (j + 1 < ny && in.byte() % 3 != 0)
      {
        s.opening(in, id(i, j), id(i, j + 1), 1, ys[j + 1], xs[i], xs[i + 1], height);
      }
    }
  }
  if (outsideOpening)
  {
    // A door or a window in an exterior wall of a corner room. A door reaches down to the floor,
    // below which the wall's plane is open outside the building (the rooms float in the scene
    // box): the threshold must part the door's open region from that plane (issue 14).
    switch ((flags >> 6) & 3)
    {
      case 0:
        s.opening(in, id(0, 0), -1, 0, xs[0], ys[0], ys[1], height);
        break;
      case 1:
        s.opening(in, id(nx - 1, 0), -1, 0, xs[nx], ys[0], ys[1], height);
        break;
      case 2:
        s.opening(in, id(0, 0), -1, 1, ys[0], xs[0], xs[1], height);
        break;
      default:
        s.opening(in, id(0, ny - 1), -1, 1, ys[ny], xs[0], xs[1], height);
        break;
    }
  }
  for (int r = 0; r < nx * ny; ++r)
  {
    s.faces(r);
  }
  const bool missingWall = flags & 32;
  if (missingWall)
  {
    // One wall, floor or ceiling polygon gone: the room behind it leaks (or, a sliver beside a
    // door gone, the door grows); only the sanity checks and stopAtFirstLeak's consistency.
    const std::size_t gone = in.byte() % s.mesh.polygonCount();
    PolygonMesh kept;
    kept.points = s.mesh.points;
    for (std::size_t i = 0; i < s.mesh.polygonCount(); ++i)
    {
      if (i != gone)
      {
        kept.addPolygon(s.mesh.polygon(i), s.mesh.polygonSize(i));
      }
    }
    s.mesh = kept;
    s.authoredRoom.pop_back();
  }
  const std::size_t goodPolygons = s.mesh.polygonCount();

  if (badPolygons)
  {
    // Degenerate and non-finite polygons: dropped, the rooms unchanged.
    const double bad[] = { std::numeric_limits<double>::quiet_NaN(),
      std::numeric_limits<double>::infinity(), 1.0, 1.0 };
    const int count = 1 + in.byte() % 4;
    for (int k = 0; k < count; ++k)
    {
      const glm::dvec3 p = glm::dvec3(xs[1] * in.unit(), ys[1] * in.unit(), height * in.unit());
      const double odd = bad[in.byte() % 4];
      const std::uint32_t a = s.mesh.addPoint(p + s.origin);
      const std::uint32_t b = s.mesh.addPoint(p + s.origin + glm::dvec3(odd, 0.0, 0.0));
      const std::uint32_t c = s.mesh.addPoint(p + s.origin + glm::dvec3(2.0 * odd, 0.0, 0.0));
      s.mesh.addPolygon({ a, b, c }); // collinear, or touching NaN/Inf
      s.authoredRoom.push_back(-1);
    }
  }
  if (freeTriangles)
  {
    const int count = 1 + in.byte() % 8;
    for (int k = 0; k < count; ++k)
    {
      std::uint32_t ids[3];
      for (std::uint32_t& i : ids)
      {
        const std::uint8_t kind = in.byte();
        glm::dvec3 p(xs.back() * in.unit(), ys.back() * in.unit(), height * in.unit());
        if (kind == 1)
        {
          p.x = 1e30;
        }
        else if (kind == 2)
        {
          p.y = std::numeric_limits<double>::quiet_NaN();
        }
        i = s.mesh.addPoint(p + s.origin);
      }
      s.mesh.addPolygon(ids, 3);
      s.authoredRoom.push_back(-1);
    }
  }

  GenerationInput input;
  input.mesh = &s.mesh;
  GeneratedPortals g = generatePortals(input);
  checkSane(g, s.mesh.polygonCount());
  if (flags & 16)
  {
    // GenerationConfig::stopAtFirstLeak (--cull auto): without a leak the same answer, with one
    // a single leak cell and no rooms.
    GenerationConfig stopping;
    stopping.stopAtFirstLeak = true;
    const GeneratedPortals h = generatePortals(input, stopping);
    checkSane(h, s.mesh.polygonCount());
    if (h.status != g.status)
    {
      fail("stopAtFirstLeak changed the status", static_cast<long long>(h.status));
    }
    if (g.status == GenerationStatus::Ok && g.statistics.leakCells == 0)
    {
      bool same = h.statistics.leakCells == 0 && h.roomCount == g.roomCount &&
        h.roomOfPolygon == g.roomOfPolygon && h.portals.size() == g.portals.size();
      for (std::size_t i = 0; same && i < g.portals.size(); ++i)
      {
        same = h.portals[i].roomA == g.portals[i].roomA &&
          h.portals[i].roomB == g.portals[i].roomB && h.portals[i].polygon == g.portals[i].polygon;
      }
      if (!same)
      {
        fail("stopAtFirstLeak changed the rooms or portals of a scene without leaks", 0);
      }
    }
    else if (g.status == GenerationStatus::Ok &&
      (h.statistics.leakCells != 1 || h.roomCount != 0 || !h.portals.empty()))
    {
      fail("stopAtFirstLeak on a leaking scene: not one leak cell and no rooms",
        static_cast<long long>(h.statistics.leakCells));
    }
  }
  if (std::getenv("SCENEVIS_FUZZ_SELFTEST"))
  {
    for (PortalDesc& p : g.portals)
    {
      glm::dvec3 centroid(0.0);
      for (const glm::dvec3& q : p.polygon)
      {
        centroid += q / double(p.polygon.size());
      }
      for (glm::dvec3& q : p.polygon)
      {
        q = centroid + 0.95 * (q - centroid);
      }
    }
  }
  const bool verbose = std::getenv("SCENEVIS_FUZZ_VERBOSE") != nullptr;
  if (verbose)
  {
    std::fprintf(stderr,
      "portal generation fuzz: %d x %d rooms, %zu openings, %zu polygons (%zu bad or free): "
      "status %d, %d rooms, %zu portals, %zu leak cells\n",
      nx, ny, s.openings.size(), s.mesh.polygonCount(), s.mesh.polygonCount() - goodPolygons,
      static_cast<int>(g.status), g.roomCount, g.portals.size(), g.statistics.leakCells);
  }
  if (verbose)
  {
    for (const glm::dvec3& p : g.leakPoints)
    {
      std::fprintf(stderr, "  leak at %g %g %g\n", p.x, p.y, p.z);
    }
    for (const Opening& o : s.openings)
    {
      std::fprintf(stderr, "  opening %d-%d axis %d at %g: %g %g %g .. %g %g %g\n", o.roomA,
        o.roomB, o.axis, o.at, o.lo.x, o.lo.y, o.lo.z, o.hi.x, o.hi.y, o.hi.z);
    }
    for (const PortalDesc& p : g.portals)
    {
      std::fprintf(stderr, "  portal %d-%d:", p.roomA, p.roomB);
      for (const glm::dvec3& q : p.polygon)
      {
        std::fprintf(stderr, " (%g %g %g)", q.x, q.y, q.z);
      }
      std::fprintf(stderr, "\n");
    }
  }
  if (freeTriangles || missingWall)
  {
    return 0;
  }

  // The oracle: the authored rooms and openings.
  if (g.status != GenerationStatus::Ok)
  {
    fail("closed box rooms without status Ok", static_cast<long long>(g.status));
  }
  if (g.statistics.leakCells != 0)
  {
    fail("closed box rooms reported leaking", g.statistics.leakCells);
  }
  std::map<int, std::int32_t> generated;
  for (std::size_t i = 0; i < goodPolygons; ++i)
  {
    const int r = s.authoredRoom[i];
    const std::int32_t room = g.roomOfPolygon[i];
    if (room == kOutsideRoom)
    {
      fail("a polygon of a closed room taken for the outside", r);
    }
    const auto [it, inserted] = generated.emplace(r, room);
    if (!inserted && it->second != room)
    {
      fail("an authored room split over two generated rooms", r);
    }
  }
  const double diagonal = glm::length(glm::dvec3(xs.back(), ys.back(), height));
  const double tol = 1e-5 * diagonal + 1e-15 * glm::length(s.origin);
  for (std::size_t k = 0; k < s.openings.size(); ++k)
  {
    const Opening& o = s.openings[k];
    const std::int32_t a = generated.at(o.roomA);
    const std::int32_t b = o.roomB < 0 ? kOutsideRoom : generated.at(o.roomB);
    if (a == b)
    {
      continue; // one room on both sides: the opening is inside it
    }
    const int u = (o.axis + 1) % 3, v = (o.axis + 2) % 3;
    bool covered = false;
    for (const PortalDesc& p : g.portals)
    {
      const bool joins = (p.roomA == a && p.roomB == b) || (p.roomA == b && p.roomB == a);
      bool all = joins;
      for (int c = 0; c < 4 && all; ++c)
      {
        glm::dvec3 corner = o.lo;
        corner[u] = (c & 1) ? o.hi[u] : o.lo[u];
        corner[v] = (c & 2) ? o.hi[v] : o.lo[v];
        all = portalCovers(p, corner + s.origin, tol);
      }
      covered = covered || all;
    }
    if (verbose)
    {
      std::fprintf(stderr, "  opening %zu: rooms %d, %d -> %d, %d, covered %d\n", k, o.roomA,
        o.roomB, a, b, int(covered));
    }
    if (!covered)
    {
      fail("an opening between two rooms not inside a portal joining them", k);
    }
  }
  return 0;
}

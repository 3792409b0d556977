#include "scenevis/PortalGeneration.h"

#include "PortalCells.h"
#include "scenevis/PortalGeometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <numeric>
#include <time.h> // clock_gettime, CLOCK_THREAD_CPUTIME_ID (POSIX)
#include <tuple>
#include <utility>

namespace scenevis
{
namespace portals
{
namespace
{

using detail::CellComplex;
using detail::OpenPiece;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Processor seconds the calling thread has used: what the budget counts, so that the same scene
/// gets the same answer on a busy machine as on a quiet one, and on a worker thread (the planner
/// generates in the background) as on the render thread: the process's time (std::clock) would
/// also count the threads rendering meanwhile. Generation runs on one thread. Where there is no
/// thread clock, std::clock.
double cpuSeconds()
{
#if defined(CLOCK_THREAD_CPUTIME_ID)
  timespec now{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now) == 0)
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
#endif
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

struct UnionFind
{
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n)
    : parent(n)
  {
    std::iota(parent.begin(), parent.end(), 0u);
  }
  std::uint32_t find(std::uint32_t x)
  {
    while (parent[x] != x)
    {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  /// The smaller root survives, so the result does not depend on the order of the calls.
  void unite(std::uint32_t a, std::uint32_t b)
  {
    a = find(a);
    b = find(b);
    if (a != b)
    {
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
};

/// A plane up to orientation, quantised so that the same plane stored by different nodes (from
/// different polygons of it) gets the same key. A plane split over two keys only loses openings,
/// which merges rooms: the conservative direction.
std::array<long long, 4> planeKey(glm::dvec4 plane, double quantum)
{
  int axis = 0;
  for (int k = 1; k < 3; ++k)
  {
    if (std::abs(plane[k]) > std::abs(plane[axis]))
    {
      axis = k;
    }
  }
  if (plane[axis] < 0.0)
  {
    plane = -plane;
  }
  return { std::llround(plane.x * 1e6), std::llround(plane.y * 1e6), std::llround(plane.z * 1e6),
    std::llround(plane.w / quantum) };
}

bool contains(const Box& b, const glm::dvec3& p, double tol)
{
  for (int k = 0; k < 3; ++k)
  {
    if (p[k] < b.lo[k] - tol || p[k] > b.hi[k] + tol)
    {
      return false;
    }
  }
  return true;
}

Box boundsOf(const std::vector<glm::dvec3>& poly)
{
  Box b;
  for (const glm::dvec3& p : poly)
  {
    b.extend(p);
  }
  return b;
}

/**
 * Marks the open pieces that belong to openings (see the file comment of PortalGeneration.h):
 * pieces of one plane that touch are one region; samples just outside each piece's edges tell
 * whether the outline runs along a polygon of the plane ("wall") or not. A region lies in one
 * plane, so each plane (group) is classified on its own, all at once (classifyAll) or when a
 * piece of it is first asked about (isOpening: the flood that stops at the first leak).
 */
class OpeningClassifier
{
public:
  OpeningClassifier(const bsp::Tree& bspTree, const CellComplex& complex,
    const std::vector<std::uint32_t>& airPieces, double enclosureShare, double sampleStep,
    UnionFind& regionSets)
    : tree(bspTree)
    , cx(complex)
    , enclosure(enclosureShare)
    , step(sampleStep)
    , regions(regionSets)
    , tol(bspTree.tolerance)
    , groupOfPiece(complex.open.size(), bsp::kNone)
    , opening(complex.open.size(), 0)
    , wall(complex.open.size(), 0.0)
    , other(complex.open.size(), 0.0)
    , regionWall(complex.open.size(), 0.0)
    , regionOther(complex.open.size(), 0.0)
  {
    const double quantum = std::max(1e3 * tol, 1e-300);
    std::map<std::array<long long, 4>, std::uint32_t> groupOfKey;
    std::vector<std::uint32_t> groupOfNode(tree.nodes.size(), bsp::kNone);
    auto groupOf = [&](std::uint32_t node)
    {
      if (groupOfNode[node] == bsp::kNone)
      {
        const auto key = planeKey(tree.nodes[node].plane, quantum);
        groupOfNode[node] =
          groupOfKey.emplace(key, static_cast<std::uint32_t>(groupOfKey.size())).first->second;
      }
      return groupOfNode[node];
    };
    for (const std::uint32_t i : airPieces)
    {
      const std::uint32_t g = groupOf(cx.faces[cx.open[i].face].node);
      piecesOf.resize(std::max<std::size_t>(piecesOf.size(), g + 1));
      piecesOf[g].push_back(i);
      groupOfPiece[i] = g;
    }
    nodesOf.resize(piecesOf.size());
    done.assign(piecesOf.size(), 0);
    for (std::uint32_t n = 0; n < tree.nodes.size(); ++n)
    {
      if (tree.nodes[n].fragmentCount > 0)
      {
        const auto key = planeKey(tree.nodes[n].plane, quantum);
        const auto it = groupOfKey.find(key);
        if (it != groupOfKey.end())
        {
          nodesOf[it->second].push_back(n);
        }
      }
    }
  }

  /// Whether air piece @p i belongs to an opening (its plane classified now if not yet).
  bool isOpening(std::uint32_t i)
  {
    const std::uint32_t g = groupOfPiece[i];
    if (g == bsp::kNone)
    {
      return false;
    }
    if (!done[g])
    {
      classify(g);
    }
    return opening[i] != 0;
  }

  /// Every plane classified: per open piece, 1 when it belongs to an opening.
  const std::vector<std::uint8_t>& classifyAll()
  {
    for (std::uint32_t g = 0; g < piecesOf.size(); ++g)
    {
      if (!done[g])
      {
        classify(g);
      }
    }
    return opening;
  }

private:
  void classify(std::uint32_t g)
  {
    done[g] = 1;
    const auto& pieces = piecesOf[g];
    fragments.clear();
    fragmentBounds.clear();
    for (const std::uint32_t n : nodesOf[g])
    {
      const bsp::Node& node = tree.nodes[n];
      for (std::uint32_t k = 0; k < node.fragmentCount; ++k)
      {
        fragments.push_back(detail::fragmentPolygon(tree, tree.fragments[node.firstFragment + k]));
        fragmentBounds.push_back(boundsOf(fragments.back()));
      }
    }
    pieceBounds.clear();
    for (const std::uint32_t i : pieces)
    {
      pieceBounds.push_back(boundsOf(cx.open[i].polygon));
    }
    detail::BoxGrid pieceGrid(pieceBounds, tol), fragmentGrid(fragmentBounds, tol);
    for (std::size_t pi = 0; pi < pieces.size(); ++pi)
    {
      const std::uint32_t i = pieces[pi];
      const auto& poly = cx.open[i].polygon;
      const glm::dvec3 normal(tree.nodes[cx.faces[cx.open[i].face].node].plane);
      for (std::size_t k = 0; k < poly.size(); ++k)
      {
        const glm::dvec3 a = poly[k];
        const glm::dvec3 edge = poly[(k + 1) % poly.size()] - a;
        const double len = glm::length(edge);
        if (len <= tol)
        {
          continue;
        }
        const glm::dvec3 outward = glm::cross(edge, normal) / len;
        const glm::dvec3 lift = step * normal;
        // Whether a polygon meets the plane along this edge in front (0) or behind (1): tested
        // once, across the edge's middle, when a sample first asks (-1: not yet).
        int meetsAlong[2] = { -1, -1 };
        const double nearEdge = std::min(10.0 * tol, 0.1 * step);
        for (const double t : { 1.0 / 6.0, 0.5, 5.0 / 6.0 })
        {
          const glm::dvec3 q = a + t * edge;
          const glm::dvec3 p = q + step * outward, back = q - step * outward;
          // An edge along a wall that crosses the plane (on both sides of it) is not part of an
          // outline in the plane: whatever lies beyond is another space.
          const bool polygonInFront = detail::segmentHitsFragment(tree, back + lift, p + lift);
          if (polygonInFront && detail::segmentHitsFragment(tree, back - lift, p - lift))
          {
            other[i] += len / 3.0;
            continue;
          }
          Box at;
          at.extend(p);
          // The open piece beyond: the one holding the sample, if it reaches back to the edge.
          // A sample `step` out from an edge shorter than that (across the end of a sliver
          // between a floor and a slanted wall that the floor stops short of) can land across
          // that wall, in a piece that does not border this one: then the piece just beyond the
          // edge is the neighbour, if there is one.
          const glm::dvec3 nearP = q + nearEdge * outward;
          auto pieceAt = [&](const glm::dvec3& x, bool reachingBack)
          {
            Box around;
            around.extend(x);
            for (const std::uint32_t pj : pieceGrid.near(around))
            {
              const auto& candidate = cx.open[pieces[pj]].polygon;
              if (pj != pi && contains(pieceBounds[pj], x, tol) &&
                detail::insideConvexPolygon(candidate, x, -tol) &&
                (!reachingBack || detail::insideConvexPolygon(candidate, nearP, -tol)))
              {
                return static_cast<std::size_t>(pj);
              }
            }
            return pieces.size();
          };
          std::size_t beyond = pieceAt(p, false);
          if (beyond < pieces.size() &&
            !detail::insideConvexPolygon(cx.open[pieces[beyond]].polygon, nearP, -tol))
          {
            beyond = pieceAt(p, true);
            if (beyond == pieces.size())
            {
              beyond = pieceAt(nearP, false);
            }
          }
          if (beyond < pieces.size())
          {
            // Open beyond the edge too: the same region, unless a polygon meets the plane along
            // the edge on one side (the floor at the threshold of a door in an exterior wall,
            // with the open plane below the floor outside beyond it): then the spaces on that
            // side differ across the edge, as across a wall that crosses the plane. Along the
            // edge itself, not within `step` of it (a door's jamb a few millimetres beside a
            // cell's edge in the doorway does not part it). Cheap tests first: no polygon enters
            // a cell, so the two pieces have different cells on that side; the segment across
            // the edge lies inside the one tested above (in front: it hit, so behind not).
            const detail::CellFace& face = cx.faces[cx.open[i].face];
            const detail::CellFace& next = cx.faces[cx.open[pieces[beyond]].face];
            const bool flipped = glm::dot(glm::dvec3(tree.nodes[next.node].plane), normal) < 0.0;
            const std::uint32_t side = polygonInFront ? face.front : face.back;
            const std::uint32_t nextSide = polygonInFront == flipped ? next.back : next.front;
            int& meets = meetsAlong[polygonInFront ? 0 : 1];
            if (side != nextSide && meets < 0)
            {
              const glm::dvec3 middle = a + 0.5 * edge, across = nearEdge * outward;
              const glm::dvec3 off = polygonInFront ? lift : -lift;
              meets =
                detail::segmentHitsFragment(tree, middle - across + off, middle + across + off);
            }
            if (side != nextSide && meets > 0)
            {
              other[i] += len / 3.0;
            }
            else
            {
              regions.unite(i, pieces[beyond]);
            }
            continue;
          }
          bool found = false;
          for (const std::uint32_t f : fragmentGrid.near(at))
          {
            if (contains(fragmentBounds[f], p, tol) &&
              detail::insideConvexPolygon(fragments[f], p, -tol))
            {
              found = true;
              break;
            }
          }
          (found ? wall : other)[i] += len / 3.0;
        }
      }
    }
    // Regions never leave their plane: the group's sums are final.
    for (const std::uint32_t i : pieces)
    {
      const std::uint32_t r = regions.find(i);
      regionWall[r] += wall[i];
      regionOther[r] += other[i];
    }
    for (const std::uint32_t i : pieces)
    {
      const std::uint32_t r = regions.find(i);
      opening[i] =
        regionWall[r] > 0.0 && regionWall[r] >= enclosure * (regionWall[r] + regionOther[r]);
    }
  }

  const bsp::Tree& tree;
  const CellComplex& cx;
  const double enclosure, step;
  UnionFind& regions;
  const double tol;
  std::vector<std::vector<std::uint32_t>> piecesOf, nodesOf;
  std::vector<std::uint32_t> groupOfPiece;
  std::vector<std::uint8_t> done, opening;
  std::vector<double> wall, other, regionWall, regionOther;
  std::vector<std::vector<glm::dvec3>> fragments;
  std::vector<Box> fragmentBounds, pieceBounds;
};

/// Area-weighted centroid and Newell normal of input polygon @p i (local coordinates); false for
/// an invalid or degenerate polygon.
bool polygonFrame(const PolygonMesh& mesh, std::size_t i, const glm::dvec3& origin,
  glm::dvec3& centroid, glm::dvec3& normal)
{
  const std::uint32_t* ids = mesh.polygon(i);
  const std::size_t n = mesh.polygonSize(i);
  if (n < 3)
  {
    return false;
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    if (ids[k] >= mesh.points.size())
    {
      return false;
    }
    const glm::dvec3& p = mesh.points[ids[k]];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    {
      return false;
    }
  }
  normal = newellNormal(mesh.points.data(), ids, n);
  const double len = glm::length(normal);
  if (!(len > 0.0))
  {
    return false;
  }
  normal /= len;
  const glm::dvec3 p0 = mesh.points[ids[0]] - origin;
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (std::size_t k = 1; k + 1 < n; ++k)
  {
    const glm::dvec3 p1 = mesh.points[ids[k]] - origin, p2 = mesh.points[ids[k + 1]] - origin;
    const double a = glm::dot(glm::cross(p1 - p0, p2 - p0), normal);
    sum += a * (p0 + p1 + p2) / 3.0;
    weight += a;
  }
  centroid = weight != 0.0 ? sum / weight : p0;
  return true;
}

} // namespace

CellSceneInput GeneratedPortals::cellScene(const PolygonMesh& mesh) const
{
  CellSceneInput in;
  in.mesh = &mesh;
  in.roomOfPolygon = this->roomOfPolygon;
  in.portals = this->portals;
  in.roomCount = this->roomCount;
  return in;
}

GeneratedPortals generatePortals(const GenerationInput& input, const GenerationConfig& config)
{
  const auto start = Clock::now();
  const double cpuStart = cpuSeconds();
  GeneratedPortals out;
  GenerationStatistics& stats = out.statistics;
  if (!input.mesh || input.mesh->polygonCount() == 0)
  {
    out.status = GenerationStatus::EmptyInput;
    out.message = "no polygons";
    return out;
  }
  const PolygonMesh& mesh = *input.mesh;
  const std::size_t polygons = mesh.polygonCount();
  stats.inputPolygons = polygons;
  // Past the budget: no rooms, and the step it stopped after in the message.
  auto overBudget = [&](const char* step)
  {
    const double seconds = cpuSeconds() - cpuStart;
    if (config.budgetSeconds <= 0.0 || seconds <= config.budgetSeconds)
    {
      return false;
    }
    out.status = GenerationStatus::OverBudget;
    out.message = "stopped after " + std::to_string(seconds) + " s of processor time (" + step +
      "), over the budget of " + std::to_string(config.budgetSeconds) + " s";
    out.roomOfPolygon.assign(polygons, kOutsideRoom);
    out.portals.clear();
    out.roomCount = 0;
    stats.totalSeconds = secondsSince(start);
    return true;
  };
  out.roomOfPolygon.assign(polygons, kOutsideRoom);

  // The cells are made by the polygons that block sight only.
  PolygonMesh blocking;
  blocking.points = mesh.points;
  for (std::size_t i = 0; i < polygons; ++i)
  {
    if (i < input.seeThrough.size() && input.seeThrough[i])
    {
      continue;
    }
    blocking.addPolygon(mesh.polygon(i), mesh.polygonSize(i));
  }
  stats.blockingPolygons = blocking.polygonCount();
  const auto bspStart = Clock::now();
  // Free planes are off: a free plane through a wall's plane would leave the wall's polygons to a
  // descendant node in the same plane, and the free node's faces would look open.
  bsp::BuildConfig bspConfig = config.bsp;
  bspConfig.allowFreePlanes = false;
  bsp::Tree tree = bsp::build(blocking, bspConfig);
  stats.bspSeconds = secondsSince(bspStart);
  stats.bspNodes = tree.nodes.size();
  stats.droppedPolygons = tree.statistics.degeneratePolygons + tree.statistics.invalidPolygons;
  if (tree.empty())
  {
    out.status = blocking.polygonCount() == 0 ? GenerationStatus::EmptyInput
                                              : GenerationStatus::NoValidPolygons;
    out.message = blocking.polygonCount() == 0
      ? "every polygon is see-through: nothing makes cells"
      : "every polygon is degenerate or has a NaN/Inf point";
    stats.totalSeconds = secondsSince(start);
    return out;
  }
  if (overBudget("the BSP"))
  {
    return out;
  }

  Box inner;
  for (const std::uint32_t id : tree.fragmentVertices)
  {
    inner.extend(tree.points[id] - tree.origin);
  }
  const double diagonal = std::max(inner.diagonal(), 1e6 * tree.tolerance);
  Box box = inner;
  const glm::dvec3 grow(config.margin * diagonal + 1e3 * tree.tolerance);
  box.lo -= grow;
  box.hi += grow;
  const auto cellsStart = Clock::now();
  CellComplex cx = detail::buildCellComplex(tree, box);
  for (int round = 0; round < 64; ++round)
  {
    if (overBudget("the cells"))
    {
      return out;
    }
    const std::size_t splits = detail::splitCellsAtOpenings(tree, cx);
    stats.openingSplits += splits;
    if (splits == 0)
    {
      break;
    }
    if (overBudget("the splits at openings"))
    {
      return out;
    }
    cx = detail::buildCellComplex(tree, box);
  }
  stats.cellSeconds = secondsSince(cellsStart);
  const std::size_t cells = cx.cellCount;
  stats.faces = cx.faces.size();
  stats.openFaces = cx.open.size();
  for (std::size_t c = 0; c < cells; ++c)
  {
    stats.cells += cx.isCell[c];
  }

  // Air: everything reached through open faces from the front of a polygon or from the box.
  UnionFind air(cells);
  for (const OpenPiece& p : cx.open)
  {
    air.unite(cx.faces[p.face].front, cx.faces[p.face].back);
  }
  // A space is air when polygons face into it more than they turn their back on it: the inside
  // of a cabinet standing against a wall is faced by the wall but backed by the cabinet.
  std::vector<double> faced(cells, 0.0), backed(cells, 0.0);
  std::vector<std::uint8_t> airRoot(cells, 0), isAir(cells, 0);
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    if (cx.isCell[c])
    {
      const std::uint32_t r = air.find(c);
      faced[r] += cx.facedArea[c];
      backed[r] += cx.backedArea[c];
      airRoot[r] = airRoot[r] || cx.touchesBox[c];
    }
  }
  for (std::uint32_t r = 0; r < cells; ++r)
  {
    airRoot[r] = airRoot[r] || faced[r] > backed[r];
  }
  std::vector<std::uint32_t> airPieces;
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    isAir[c] = cx.isCell[c] && airRoot[air.find(c)];
    stats.airCells += isAir[c];
  }
  for (std::uint32_t i = 0; i < cx.open.size(); ++i)
  {
    const detail::CellFace& f = cx.faces[cx.open[i].face];
    if (isAir[f.front] && isAir[f.back])
    {
      airPieces.push_back(i);
    }
  }

  const auto openingsStart = Clock::now();
  UnionFind regions(cx.open.size());
  const double step = std::max(1e-4 * diagonal, 100.0 * tree.tolerance);
  OpeningClassifier openings(tree, cx, airPieces, config.openingEnclosure, step, regions);

  // Only space that polygons face into: the void inside a level's pillars is enclosed too, but
  // its walls turn their backs on it. @p c is an air cell joined to the outside.
  auto leaks = [&](std::uint32_t c)
  {
    if (!contains(inner, cx.centroid[c], 0.0) || cx.facedArea[c] <= cx.backedArea[c])
    {
      return false;
    }
    int hits = 0;
    for (int k = 0; k < 3; ++k)
    {
      for (const double to : { box.lo[k], box.hi[k] })
      {
        glm::dvec3 end = cx.centroid[c];
        end[k] = to;
        hits += detail::segmentHitsFragment(tree, cx.centroid[c], end);
      }
    }
    return hits >= 5;
  };

  if (config.stopAtFirstLeak)
  {
    // Flood from the box across open faces that are not openings, classifying a plane's openings
    // only when the flood reaches it: a leak usually shows in the first cells flooded, long
    // before every plane is classified. The cells reached are exactly the outside's below.
    std::vector<std::vector<std::uint32_t>> piecesOfCell(cells);
    for (const std::uint32_t i : airPieces)
    {
      piecesOfCell[cx.faces[cx.open[i].face].front].push_back(i);
      piecesOfCell[cx.faces[cx.open[i].face].back].push_back(i);
    }
    std::vector<std::uint8_t> reached(cells, 0);
    std::vector<std::uint32_t> queue;
    for (std::uint32_t c = 0; c < cells; ++c)
    {
      if (isAir[c] && cx.touchesBox[c])
      {
        reached[c] = 1;
        queue.push_back(c);
      }
    }
    for (std::size_t at = 0; at < queue.size(); ++at)
    {
      if (at % 256 == 255 && overBudget("the flood from the outside"))
      {
        return out;
      }
      const std::uint32_t c = queue[at];
      if (leaks(c))
      {
        stats.leakCells = 1;
        out.leakPoints.push_back(cx.centroid[c] + tree.origin);
        stats.openingSeconds = secondsSince(openingsStart);
        stats.totalSeconds = secondsSince(start);
        out.message = "stopped at the first leak (stopAtFirstLeak): no rooms";
        return out;
      }
      for (const std::uint32_t i : piecesOfCell[c])
      {
        const detail::CellFace& f = cx.faces[cx.open[i].face];
        const std::uint32_t next = f.front == c ? f.back : f.front;
        if (!reached[next] && !openings.isOpening(i))
        {
          reached[next] = 1;
          queue.push_back(next);
        }
      }
    }
  }
  const std::vector<std::uint8_t>& opening = openings.classifyAll();

  stats.openingSeconds = secondsSince(openingsStart);
  if (overBudget("the openings"))
  {
    return out;
  }

  // Rooms: air cells joined across everything that is not an opening.
  UnionFind rooms(cells);
  for (const std::uint32_t i : airPieces)
  {
    stats.openingFaces += opening[i];
    if (!opening[i])
    {
      rooms.unite(cx.faces[cx.open[i].face].front, cx.faces[cx.open[i].face].back);
    }
  }
  auto outsideRoots = [&]()
  {
    std::vector<std::uint8_t> outside(cells, 0);
    for (std::uint32_t c = 0; c < cells; ++c)
    {
      if (isAir[c] && cx.touchesBox[c])
      {
        outside[rooms.find(c)] = 1;
      }
    }
    return outside;
  };
  std::vector<std::uint8_t> outside = outsideRoots();

  // Leaks: cells joined to the outside without an opening, yet enclosed by geometry.
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    if (c % 256 == 255 && overBudget("the leak search"))
    {
      return out;
    }
    if (isAir[c] && outside[rooms.find(c)] && leaks(c))
    {
      ++stats.leakCells;
      if (out.leakPoints.size() < 64)
      {
        out.leakPoints.push_back(cx.centroid[c] + tree.origin);
      }
    }
  }

  // Passages: rooms thin for their largest opening join the neighbour they share most with.
  std::vector<double> volume(cells, 0.0), largest(cells, 0.0), facedBy(cells, 0.0);
  std::vector<std::vector<std::pair<std::uint32_t, double>>> neighbours(cells);
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    if (isAir[c])
    {
      volume[rooms.find(c)] += cx.volume[c];
      facedBy[rooms.find(c)] += cx.facedArea[c];
    }
  }
  for (const std::uint32_t i : airPieces)
  {
    const detail::CellFace& f = cx.faces[cx.open[i].face];
    const std::uint32_t a = rooms.find(f.front), b = rooms.find(f.back);
    if (!opening[i] || a == b)
    {
      continue;
    }
    const double area = detail::polygonArea(cx.open[i].polygon);
    for (const auto& [from, to] : { std::pair(a, b), std::pair(b, a) })
    {
      auto& list = neighbours[from];
      auto it =
        std::find_if(list.begin(), list.end(), [to = to](const auto& e) { return e.first == to; });
      if (it == list.end())
      {
        list.emplace_back(to, area);
      }
      else
      {
        it->second += area;
      }
    }
  }
  std::vector<std::uint32_t> passages;
  for (std::uint32_t r = 0; r < cells; ++r)
  {
    if (!isAir[r] || rooms.find(r) != r || outside[r])
    {
      continue;
    }
    ++stats.roomsBeforePassages;
    for (const auto& e : neighbours[r])
    {
      largest[r] = std::max(largest[r], e.second);
    }
    // A room no polygon faces into would have no geometry to find an eye in: a passage too.
    if (largest[r] > 0.0 &&
      (volume[r] < config.passageThickness * std::pow(largest[r], 1.5) || facedBy[r] <= 0.0))
    {
      passages.push_back(r);
    }
  }
  std::sort(passages.begin(), passages.end(),
    [&](std::uint32_t a, std::uint32_t b)
    { return std::tie(volume[a], a) < std::tie(volume[b], b); });
  for (const std::uint32_t r : passages)
  {
    std::uint32_t best = bsp::kNone;
    double bestArea = -1.0;
    for (const auto& e : neighbours[r])
    {
      if (e.second > bestArea || (e.second == bestArea && e.first < best))
      {
        best = e.first;
        bestArea = e.second;
      }
    }
    if (best != bsp::kNone && rooms.find(best) != rooms.find(r))
    {
      rooms.unite(best, r);
      ++stats.passagesMerged;
    }
  }
  outside = outsideRoots();

  // A polygon seen from several rooms would close only the one it is given (the portal graph
  // finds an eye by the polygons around it, so the others would lose it): the rooms a polygon
  // faces into are one room. (The steps of a stair cut its well into rooms otherwise.)
  std::vector<std::uint32_t> firstCell(blocking.polygonCount(), bsp::kNone);
  for (const auto& cover : cx.coverage)
  {
    std::uint32_t cell = cover.cell;
    if (!isAir[cell] || outside[rooms.find(cell)])
    {
      // Facing the outside with a room behind: that room's (see the polygons' rooms below).
      if (!isAir[cell] || !isAir[cover.behind] || outside[rooms.find(cover.behind)])
      {
        continue;
      }
      cell = cover.behind;
    }
    std::uint32_t& first = firstCell[cover.source];
    if (first == bsp::kNone)
    {
      first = cell;
    }
    else if (rooms.find(first) != rooms.find(cell))
    {
      rooms.unite(first, cell);
      ++stats.roomsJoinedByPolygons;
    }
  }
  outside = outsideRoots();

  // Room ids in the order of their first cell: deterministic.
  std::vector<std::int32_t> idOfRoot(cells, kOutsideRoom);
  std::vector<std::int32_t> roomOfCell(cells, kOutsideRoom - 1);
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    if (!isAir[c])
    {
      continue;
    }
    const std::uint32_t r = rooms.find(c);
    if (!outside[r] && idOfRoot[r] == kOutsideRoom)
    {
      idOfRoot[r] = out.roomCount++;
    }
    roomOfCell[c] = idOfRoot[r];
  }
  stats.rooms = static_cast<std::size_t>(out.roomCount);

  // Each polygon: the room its fragments face into over the largest area; polygons without a
  // covered part (see-through ones) the room just in front of their centroid.
  std::vector<std::uint32_t> inputOf;
  for (std::uint32_t i = 0; i < polygons; ++i)
  {
    if (i >= input.seeThrough.size() || !input.seeThrough[i])
    {
      inputOf.push_back(i);
    }
  }
  std::vector<std::vector<std::pair<std::int32_t, double>>> votes(polygons);
  for (const auto& cover : cx.coverage)
  {
    std::int32_t room = roomOfCell[cover.cell];
    // Facing the outside with a room behind: a polygon wound the wrong way, like the back
    // side's wall parts of a converted Doom level, which face the void under the other side's
    // floor. Only its room sees it. (Facing solid space, it is hidden: left without a room.)
    if (room == kOutsideRoom && roomOfCell[cover.behind] >= 0)
    {
      room = roomOfCell[cover.behind];
    }
    if (room < kOutsideRoom)
    {
      continue;
    }
    auto& list = votes[inputOf[cover.source]];
    auto it =
      std::find_if(list.begin(), list.end(), [room](const auto& e) { return e.first == room; });
    if (it == list.end())
    {
      list.emplace_back(room, cover.area);
    }
    else
    {
      it->second += cover.area;
    }
  }
  const double lift = std::max(1e-5 * diagonal, 10.0 * tree.tolerance);
  for (std::size_t i = 0; i < polygons; ++i)
  {
    if (!votes[i].empty())
    {
      const auto best = std::max_element(votes[i].begin(), votes[i].end(),
        [](const auto& a, const auto& b)
        { return std::tie(a.second, b.first) < std::tie(b.second, a.first); });
      out.roomOfPolygon[i] = best->first;
      continue;
    }
    glm::dvec3 centroid, normal;
    if (!polygonFrame(mesh, i, tree.origin, centroid, normal))
    {
      continue;
    }
    // No covered part: see-through, coincident with another polygon that took the cover
    // (zero-thickness walls), or hidden (facing solid space: the bottom of a box on the floor,
    // a box's face inside another). First the room just in front of its centroid; a hidden
    // face can peek out at its edges, where it is seen from the room around it: then the room
    // just beyond an edge on its back side (beside the box, above the floor); last the first
    // room stepping from its centroid along its normal.
    const std::uint32_t front = detail::locateCell(tree, centroid + lift * normal);
    std::int32_t room = front == bsp::kNone ? kOutsideRoom - 1 : roomOfCell[front];
    room = room >= 0 ? room : kOutsideRoom - 1;
    const std::uint32_t* ids = mesh.polygon(i);
    const std::size_t count = mesh.polygonSize(i);
    for (const double side : { -1.0, 1.0 })
    {
      for (std::size_t k = 0; k < count && room < 0; ++k)
      {
        const glm::dvec3 a = mesh.points[ids[k]] - tree.origin;
        const glm::dvec3 edge = mesh.points[ids[(k + 1) % count]] - tree.origin - a;
        const double len = glm::length(edge);
        if (!(len > 0.0))
        {
          continue;
        }
        const glm::dvec3 outward = glm::cross(edge, normal) / len;
        const glm::dvec3 p = a + 0.5 * edge + 2.0 * lift * (outward + side * normal);
        const std::uint32_t c = detail::locateCell(tree, p);
        room = c == bsp::kNone ? room : std::max(room, roomOfCell[c]);
      }
    }
    room = room >= 0 ? room : kOutsideRoom - 1;
    for (double away = lift; away < diagonal && room < 0; away *= 4.0)
    {
      for (const double sign : { 1.0, -1.0 })
      {
        const std::uint32_t c = detail::locateCell(tree, centroid + sign * away * normal);
        const std::int32_t r = c == bsp::kNone ? kOutsideRoom - 1 : roomOfCell[c];
        if (r >= 0 || (r == kOutsideRoom && room < kOutsideRoom))
        {
          room = r;
        }
        if (room >= 0)
        {
          break;
        }
      }
    }
    if (room < kOutsideRoom)
    {
      ++stats.polygonsWithoutRoom;
      continue;
    }
    out.roomOfPolygon[i] = room;
  }

  // Portals: per opening region and room pair, the hull of its pieces.
  std::map<std::tuple<std::uint32_t, std::int32_t, std::int32_t>, std::vector<glm::dvec3>> groups;
  std::map<std::tuple<std::uint32_t, std::int32_t, std::int32_t>, glm::dvec3> normals;
  for (const std::uint32_t i : airPieces)
  {
    const detail::CellFace& f = cx.faces[cx.open[i].face];
    std::int32_t a = roomOfCell[f.front], b = roomOfCell[f.back];
    if (!opening[i] || a == b)
    {
      continue;
    }
    if (a == kOutsideRoom || (b != kOutsideRoom && b < a))
    {
      std::swap(a, b);
    }
    const auto key = std::make_tuple(regions.find(i), a, b);
    auto& points = groups[key];
    points.insert(points.end(), cx.open[i].polygon.begin(), cx.open[i].polygon.end());
    normals[key] = glm::dvec3(tree.nodes[f.node].plane);
  }
  for (const auto& [key, points] : groups)
  {
    PortalDesc portal;
    portal.polygon = planarConvexHull(points, normals[key]);
    if (portal.polygon.size() < 3)
    {
      continue;
    }
    for (glm::dvec3& p : portal.polygon)
    {
      p += tree.origin;
    }
    portal.roomA = std::get<1>(key);
    portal.roomB = std::get<2>(key);
    stats.exteriorPortals += portal.roomB == kOutsideRoom;
    out.portals.push_back(std::move(portal));
  }
  stats.portals = out.portals.size();
  if (stats.leakCells > 0 && !config.keepRoomsWithLeaks)
  {
    // No labelling is conservative with leaks (see the header): none is given.
    stats.roomsWithheld = stats.rooms;
    stats.portalsWithheld = stats.portals;
    stats.rooms = stats.portals = stats.exteriorPortals = 0;
    out.roomOfPolygon.assign(polygons, kOutsideRoom);
    out.portals.clear();
    out.roomCount = 0;
    out.message = "the model leaks (" + std::to_string(stats.leakCells) +
      " leak cells): no rooms, since portals through a leak may hide what is seen (" +
      std::to_string(stats.roomsWithheld) + " rooms, " + std::to_string(stats.portalsWithheld) +
      " portals withheld; keepRoomsWithLeaks gives them)";
  }
  stats.totalSeconds = secondsSince(start);
  return out;
}

} // namespace portals
} // namespace scenevis

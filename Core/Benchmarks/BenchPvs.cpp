// PVS precompute at level scale: a maze level (scenes::maze(), ~1,700 rooms and ~5,800 portals
// by default) through the portal-flow PVS and the separating-plane PVS (stopped after a time
// limit), their set sizes, the rooms a sampling oracle proves visible that each PVS lost, and
// the per-frame traversal cost (exact frustum narrowing and PVS lookup) for eyes in rooms.
//
//   build/bin/scenevis_pvs_bench                       # 24 x 24 rooms x 3 floors
//   build/bin/scenevis_pvs_bench --rooms 6,6,2 --old-seconds 5 --segments 20000 --frames 20
//
// A portal scene file instead of the maze (e.g. a Doom map converted by scripts/wad-to-portals.py):
//
//   build/bin/scenevis_pvs_bench --scene MAP.vtp --portals MAP-portals.vtp
//     --cameras MAP-cameras.json
//
// times the portal-flow PVS of that scene (no oracle: the rooms' cells are not boxes; the PVS is
// checked against the exact traversal from every camera instead, and `scenevis cull --exact`
// checks both against the ID buffer) and the traversal from each camera of the file (perspective,
// its view angle on a square image, each camera timed --frames times, default 200).
//
// Options: --scene FILE.vtp --portals FILE.vtp --cameras FILE.json --room-array NAME (RoomId)
// --rooms X,Y,FLOORS  --halls N (open halls per floor, default 6)
// --hall-size N (largest hall side in rooms, default 12)  --seed N  --threads N (0 = all cores)
// --budget S (flow budget, 0 = none)  --max-steps N (flow steps per portal before it closes)
// --passages 0|1 (passage might-see in the flow, default 0)
// --merge-after N (flow steps before the merged flow finishes a source, 0 = never; default 2000)
// --max-regions N (regions per room before the exact traversal merges them, default 16)
// --ray-oracle N (N x N rays per camera walked through the portals: each room they enter must be
// in the PVS; exit 1 otherwise)
// --old-seconds S (limit of the separating-plane run, 0 skips it)  --segments N (oracle samples)
// --frames N (traversal views).
#include "PortalRayWalk.h"
#include "PortalSceneFile.h"
#include "PortalSegmentOracle.h"

#include "CameraFile.h"

#include "scenevis/PortalGraph.h"
#include "scenevis/PortalPvs.h"
#include "scenevis/PortalTraversal.h"
#include "scenevis/Scenes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <random>
#include <string>
#include <vector>

using namespace scenevis;
using namespace scenevis::portals;

namespace
{
/// A fingerprint of an exact traversal's result, chained onto @p h: the rooms reached and, with
/// @p regions, every region rectangle, bit for bit (to show that a faster traversal gives the same
/// answer); without, two traversals that reach the same rooms from every camera give one value.
std::uint64_t TraversalFingerprint(const PortalTraversal& t, std::uint64_t h, bool regions = true)
{
  const auto mix = [&h](std::uint64_t v) { h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2); };
  std::vector<std::int32_t> nodes = t.visibleNodes();
  std::sort(nodes.begin(), nodes.end());
  for (const std::int32_t n : nodes)
  {
    mix(static_cast<std::uint64_t>(n));
    if (!regions)
    {
      continue;
    }
    for (const glm::dvec4& r : t.regionRectangles(n))
    {
      for (int k = 0; k < 4; ++k)
      {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &r[k], sizeof bits);
        mix(bits);
      }
    }
  }
  if (!regions)
  {
    mix(0xffffffffull); // end of this camera's rooms
  }
  return h;
}
using Clock = std::chrono::steady_clock;
/// --max-steps: flow steps per source portal before its flow closes its branches.
std::size_t maxStepsPerPortal = scenevis::portals::PvsOptions().maxFlowStepsPerPortal;
/// Regions per room before the exact traversal merges them into a rectangle (--max-regions).
std::size_t maxRegionsPerRoom = scenevis::portals::TraversalOptions().maxRegionsPerRoom;
/// --ray-oracle N: N x N rays per camera checked against the PVS (0: none).
std::size_t rayOracle = 0;
/// --passages 0|1: the flow without or with passage might-see (PvsOptions::passages).
bool usePassages = scenevis::portals::PvsOptions().passages;
/// --merge-after N: flow steps before a source's walk gives way to the merged flow (0 = never).
std::size_t mergeAfter = scenevis::portals::PvsOptions().mergeAfterSteps;
double since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}
/// Processor time of the process (all threads) since @p c, in seconds: on a loaded machine the
/// wall time says more about the other processes than about this one.
double cpuSince(std::clock_t c)
{
  return static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC;
}

std::size_t entries(const PortalPvs& pvs)
{
  std::size_t n = 0;
  for (std::int32_t x = 0; x < pvs.nodeCount(); ++x)
  {
    n += pvs.visibleFrom(x).size();
  }
  return n;
}

/// The portal flow's line: its wall and CPU seconds, then what PortalPvs::compute reported.
void PrintFlow(double wallSeconds, double cpuSeconds, const PvsStats& stats, const PortalPvs& flow)
{
  std::printf(
    "portal flow: %.2f s wall, %.2f s CPU, on %d threads (might-see %.2f s, flow %.2f s); "
    "%zu directed portals, might-see %.1f and final %.1f portals each; %zu flow steps; "
    "%zu degraded portals%s; PVS %.1f nodes per node (%zu entries)\n",
    wallSeconds, cpuSeconds, stats.threads, stats.mightSeeSeconds, stats.flowSeconds,
    stats.directedPortals, stats.averageMightSee, stats.averagePortalVis, stats.flowSteps,
    stats.degradedPortals, stats.budgetExceeded ? " (budget exceeded)" : "", stats.averageSetSize,
    entries(flow));
  if (stats.mergedPortals)
  {
    std::printf("merged flow: %zu directed portals finished by it, %zu merged steps\n",
      stats.mergedPortals, stats.mergedSteps);
  }
  if (stats.passages)
  {
    std::printf("passages: %zu portal pairs, %.1f portals each, %.1f MB, %.2f s\n", stats.passages,
      stats.averagePassage, double(stats.passageBytes) / 1e6, stats.passageSeconds);
  }
}

/// Pairs (rooms) the oracle proved visible that @p pvs lacks.
std::size_t lost(const testing_support::PortalSegmentOracle& oracle, const PortalPvs& pvs)
{
  std::size_t n = 0;
  for (std::int32_t x = 0; x < pvs.nodeCount(); ++x)
  {
    for (std::int32_t y = 0; y < pvs.nodeCount(); ++y)
    {
      n += oracle.proven(x, y) && !pvs.visible(x, y) ? 1 : 0;
    }
  }
  return n;
}

double median(std::vector<double> v)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double percentile(std::vector<double> v, double q)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

/// The PVS and the traversal of a portal scene file, seen from the cameras of a camera file.
int benchSceneFile(const std::string& scene, const std::string& portalsFile,
  const std::string& camerasFile, const std::string& roomArray, int threads, double budget,
  std::size_t repeats)
{
  auto t0 = Clock::now();
  PolygonMesh mesh;
  PortalGraphReport report;
  PortalGraph graph;
  std::vector<tool::CameraSpec> cameras;
  try
  {
    const CellSceneInput input = bench::readPortalScene(scene, portalsFile, roomArray, mesh);
    graph = PortalGraph::build(input, &report);
    if (!camerasFile.empty())
    {
      cameras = tool::ReadCameraFile(camerasFile, tool::CameraSpec());
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "scenevis_pvs_bench: %s\n", e.what());
    return 1;
  }
  std::printf("level: %s: %d rooms, %zu portals, %zu polygons (read and graph built in %.2f s, "
              "%zu graph errors, %zu warnings)\n",
    scene.c_str(), graph.roomCount(), graph.portals().size(), mesh.polygonCount(), since(t0),
    report.errors(), report.warnings());

  PvsOptions options;
  options.threads = threads;
  options.budgetSeconds = budget;
  options.maxFlowStepsPerPortal = maxStepsPerPortal;
  options.passages = usePassages;
  options.mergeAfterSteps = mergeAfter;
  PvsStats stats;
  t0 = Clock::now();
  const std::clock_t c0 = std::clock();
  const PortalPvs flow = PortalPvs::compute(graph, options, &stats);
  PrintFlow(since(t0), cpuSince(c0), stats, flow);

  // Each camera: the median of its repeats; then the median and the 90th percentile over cameras.
  std::vector<double> exactMs, pvsMs;
  std::size_t exactRooms = 0, pvsRooms = 0, outsidePvs = 0, fallbacks = 0;
  std::size_t outsideRegions = 0, outsideBelowPixel = 0, outsideSeenByRay = 0;
  std::size_t rayRooms = 0, rayMisses = 0;
  std::uint64_t fingerprint = 0, roomsFingerprint = 0;
  std::size_t expanded = 0, merged = 0, crossings = 0;
  const auto portalsOf = bench::PortalsOfNodes(graph);
  double largestOutside = 0.0;
  PortalTraversal t;
  TraversalOptions topt;
  topt.maxRegionsPerRoom = maxRegionsPerRoom;
  const double diagonal = graph.buildingBounds().diagonal();
  for (const tool::CameraSpec& c : cameras)
  {
    const glm::dvec3 eye(c.eye[0], c.eye[1], c.eye[2]);
    const glm::dvec3 focal(c.focal[0], c.focal[1], c.focal[2]);
    const glm::dvec3 up = c.hasUp ? glm::dvec3(c.up[0], c.up[1], c.up[2]) : glm::dvec3(0, 0, 1);
    const double angle = c.viewAngle > 0.0 ? c.viewAngle : 90.0;
    const double zNear = c.FixedClippingRange() ? c.clippingRange[0] : 1e-3 * diagonal;
    const double zFar = c.FixedClippingRange() ? c.clippingRange[1] : 2.0 * diagonal;
    PortalView view;
    view.eye = eye;
    view.clipFromWorld =
      glm::perspective(glm::radians(angle), 1.0, zNear, zFar) * glm::lookAt(eye, focal, up);
    std::vector<double> a, b;
    for (std::size_t r = 0; r < std::max<std::size_t>(repeats, 1); ++r)
    {
      auto s = Clock::now();
      t.run(graph, view, topt);
      a.push_back(1e3 * since(s));
    }
    fallbacks += t.stats().fallback == Fallback::None ? 0 : 1;
    std::vector<std::int32_t> reached = t.visibleNodes();
    exactRooms += reached.size();
    fingerprint = TraversalFingerprint(t, fingerprint);
    roomsFingerprint = TraversalFingerprint(t, roomsFingerprint, false);
    expanded += t.stats().regionsExpanded;
    merged += t.stats().regionsMerged;
    crossings += t.stats().portalsTraversed;
    for (std::size_t r = 0; r < std::max<std::size_t>(repeats, 1); ++r)
    {
      auto s = Clock::now();
      t.runPvs(graph, flow, view, topt);
      b.push_back(1e3 * since(s));
    }
    pvsRooms += t.visibleNodes().size();
    // The traversal's start rooms: the eye's, and those of portals within the near plane's
    // corner distance; the oracles below walk rays from each of them.
    const double halfTan = std::tan(glm::radians(angle) / 2.0);
    const EyeLocation loc =
      graph.locate(eye, zNear * std::sqrt(1.0 + 2.0 * halfTan * halfTan), topt.outside);
    const glm::dmat4 worldFromClip = glm::inverse(view.clipFromWorld);
    // The unit direction from the eye through the point (x, y) of normalized device coordinates.
    const auto rayThrough = [&](double x, double y)
    {
      const glm::dvec4 far = worldFromClip * glm::dvec4(x, y, 1.0, 1.0);
      return glm::normalize(glm::dvec3(far) / far.w - eye);
    };
    if (rayOracle > 0)
    {
      // The PVS against rays: every room a ray from the eye enters through portals (RayWalk)
      // must be in the PVS of the rooms the traversal starts from.
      std::vector<char> missed(static_cast<std::size_t>(graph.nodeCount()), 0);
      for (std::size_t i = 0; i < rayOracle * rayOracle; ++i)
      {
        const double x = -1.0 + 2.0 * (static_cast<double>(i % rayOracle) + 0.5) / rayOracle;
        const double y = -1.0 + 2.0 * (static_cast<double>(i / rayOracle) + 0.5) / rayOracle;
        const glm::dvec3 d = rayThrough(x, y);
        for (const std::int32_t start : loc.nodes)
        {
          bench::RayWalk(graph, portalsOf, start, eye, d,
            [&](std::int32_t node, double)
            {
              ++rayRooms;
              if (!t.nodeVisible(node) && !missed[static_cast<std::size_t>(node)])
              {
                missed[static_cast<std::size_t>(node)] = 1;
                ++rayMisses;
              }
              return true;
            });
        }
      }
    }
    std::vector<std::int32_t> outside;
    for (const std::int32_t node : reached)
    {
      if (!t.nodeVisible(node))
      {
        outside.push_back(node);
      }
    }
    outsidePvs += outside.size();
    if (!outside.empty())
    {
      // How much of the view the exact traversal saw such a room through: its largest region
      // rectangle in pixels of a 1024-pixel square image (an upper bound of the region).
      t.run(graph, view, topt);
      for (const std::int32_t node : outside)
      {
        bool seen = false;
        for (const glm::dvec4& r : t.regionRectangles(node))
        {
          const double w = 512.0 * (r.z - r.x), h = 512.0 * (r.w - r.y);
          largestOutside = std::max(largestOutside, std::max(w, h));
          outsideBelowPixel += w < 1.0 || h < 1.0 ? 1 : 0;
          ++outsideRegions;
          // The oracle: 32 x 32 rays from the eye through the region's rectangle.
          for (int i = 0; i < 32 * 32 && !seen; ++i)
          {
            const double x = r.x + (r.z - r.x) * ((i % 32) + 0.5) / 32.0;
            const double y = r.y + (r.w - r.y) * ((i / 32) + 0.5) / 32.0;
            const glm::dvec3 d = rayThrough(x, y);
            for (const std::int32_t start : loc.nodes)
            {
              seen = seen || bench::RayReaches(graph, portalsOf, start, node, eye, d);
            }
          }
        }
        outsideSeenByRay += seen ? 1 : 0;
      }
    }
    exactMs.push_back(median(a));
    pvsMs.push_back(median(b));
  }
  if (!cameras.empty())
  {
    const double n = static_cast<double>(cameras.size());
    std::printf(
      "traversal from %zu cameras (%zu runs each; per camera the median): exact frustum "
      "narrowing median %.3f ms, 90th percentile %.3f ms, max %.3f ms, %.1f nodes "
      "reached (result fingerprint %016llx, rooms %016llx; per frame %.1f regions expanded, %.1f "
      "crossings made a region, %.2f merges); portal-flow PVS lookup median %.3f ms, %.1f nodes; "
      "%zu frustum-only "
      "fallbacks; rooms the exact traversal reaches outside the PVS: %zu (through %zu regions, "
      "%zu of them narrower than a pixel of 1024x1024; the widest %.2f pixels; %zu of these rooms "
      "reached by a ray from the eye through portals: PVS misses)\n",
      cameras.size(), std::max<std::size_t>(repeats, 1), median(exactMs), percentile(exactMs, 0.9),
      percentile(exactMs, 1.0), static_cast<double>(exactRooms) / n,
      static_cast<unsigned long long>(fingerprint),
      static_cast<unsigned long long>(roomsFingerprint), static_cast<double>(expanded) / n,
      static_cast<double>(crossings) / n, static_cast<double>(merged) / n, median(pvsMs),
      static_cast<double>(pvsRooms) / n, fallbacks, outsidePvs, outsideRegions, outsideBelowPixel,
      largestOutside, outsideSeenByRay);
  }
  // The exact traversal is conservative too (it may cross a portal the eye meets from its far
  // side, after a wall): a room it reaches outside the PVS is a PVS miss only if a ray confirms it.
  if (rayOracle > 0)
  {
    std::printf("ray oracle: %zu x %zu rays per camera entered rooms %zu times; rooms entered but "
                "not in the PVS: %zu\n",
      rayOracle, rayOracle, rayRooms, rayMisses);
  }
  return outsideSeenByRay == 0 && rayMisses == 0 ? 0 : 1;
}
} // namespace

int main(int argc, char** argv)
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0); // each result as it comes, also into a file
  scenes::MazeConfig config;
  config.roomsX = 24;
  config.roomsY = 24;
  config.floors = 3;
  config.openings[0] = 0.05;
  config.openings[1] = 0.25;
  config.openings[2] = 0.4;
  config.openings[3] = 0.3;
  config.stairHole = 0.25;
  config.hallsPerFloor = 6;
  config.hallSize = 12;
  int threads = 0;
  double budget = 0.0, oldSeconds = 120.0;
  std::size_t segments = 2'000'000, frames = 200;
  std::string scene, portalsFile, camerasFile, roomArray = "RoomId";
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string key = argv[i];
    const char* value = argv[i + 1];
    if (key == "--rooms" &&
      std::sscanf(value, "%d,%d,%d", &config.roomsX, &config.roomsY, &config.floors) == 3)
    {
    }
    else if (key == "--halls")
    {
      config.hallsPerFloor = std::atoi(value);
    }
    else if (key == "--hall-size")
    {
      config.hallSize = std::atoi(value);
    }
    else if (key == "--seed")
    {
      config.seed = std::strtoull(value, nullptr, 10);
    }
    else if (key == "--threads")
    {
      threads = std::atoi(value);
    }
    else if (key == "--budget")
    {
      budget = std::atof(value);
    }
    else if (key == "--max-steps")
    {
      maxStepsPerPortal = std::strtoull(value, nullptr, 10);
    }
    else if (key == "--merge-after")
    {
      mergeAfter = std::strtoull(value, nullptr, 10);
    }
    else if (key == "--passages")
    {
      usePassages = std::atoi(value) != 0;
    }
    else if (key == "--ray-oracle")
    {
      rayOracle = std::strtoull(value, nullptr, 10);
    }
    else if (key == "--max-regions")
    {
      maxRegionsPerRoom = std::strtoull(value, nullptr, 10);
    }
    else if (key == "--old-seconds")
    {
      oldSeconds = std::atof(value);
    }
    else if (key == "--segments")
    {
      segments = std::strtoull(value, nullptr, 10);
    }
    else if (key == "--frames")
    {
      frames = std::strtoull(value, nullptr, 10);
    }
    else if (key == "--scene")
    {
      scene = value;
    }
    else if (key == "--portals")
    {
      portalsFile = value;
    }
    else if (key == "--cameras")
    {
      camerasFile = value;
    }
    else if (key == "--room-array")
    {
      roomArray = value;
    }
    else
    {
      std::fprintf(
        stderr, "scenevis_pvs_bench: unknown option or bad value: %s %s\n", argv[i], value);
      return 2;
    }
  }

  if (!scene.empty() || !portalsFile.empty())
  {
    if (scene.empty() || portalsFile.empty())
    {
      std::fprintf(stderr, "scenevis_pvs_bench: --scene and --portals go together\n");
      return 2;
    }
    return benchSceneFile(scene, portalsFile, camerasFile, roomArray, threads, budget, frames);
  }

  auto t0 = Clock::now();
  const scenes::BuildingScene level = scenes::maze(config);
  PortalGraphReport report;
  const PortalGraph graph = PortalGraph::build(cellSceneOf(level), &report);
  std::printf("level: maze %dx%dx%d seed %llu: %d rooms, %zu portals, %zu polygons "
              "(generated and graph built in %.2f s, %zu graph errors)\n",
    config.roomsX, config.roomsY, config.floors, static_cast<unsigned long long>(config.seed),
    graph.roomCount(), graph.portals().size(), level.mesh.polygonCount(), since(t0),
    report.errors());

  PvsOptions options;
  options.threads = threads;
  options.budgetSeconds = budget;
  options.maxFlowStepsPerPortal = maxStepsPerPortal;
  options.passages = usePassages;
  options.mergeAfterSteps = mergeAfter;
  PvsStats stats;
  t0 = Clock::now();
  std::clock_t c0 = std::clock();
  const PortalPvs flow = PortalPvs::compute(graph, options, &stats);
  const double flowSeconds = since(t0);
  PrintFlow(flowSeconds, cpuSince(c0), stats, flow);
  options.method = PvsMethod::MightSee;
  t0 = Clock::now();
  const PortalPvs might = PortalPvs::compute(graph, options, &stats);
  std::printf("might-see only: %.2f s; PVS %.1f nodes per node\n", since(t0), stats.averageSetSize);

  PortalPvs old;
  if (oldSeconds > 0.0)
  {
    options = PvsOptions();
    options.method = PvsMethod::SeparatingPlanes;
    double done = 0.0;
    t0 = Clock::now();
    c0 = std::clock();
    options.progress = [&](double f)
    {
      done = f;
      return since(t0) < oldSeconds;
    };
    old = PortalPvs::compute(graph, options, &stats);
    if (old.empty())
    {
      std::printf("separating planes: stopped after %.1f s wall, %.1f s CPU, with %.1f %% of the "
                  "source rooms done (%zu sequences walked)\n",
        since(t0), cpuSince(c0), 100.0 * done, stats.sequences);
    }
    else
    {
      std::printf("separating planes: %.2f s wall, %.2f s CPU; PVS %.1f nodes per node (%zu "
                  "entries)\n",
        since(t0), cpuSince(c0), stats.averageSetSize, entries(old));
    }
  }

  t0 = Clock::now();
  testing_support::PortalSegmentOracle oracle(level, graph);
  oracle.sample(segments, 7);
  std::printf("oracle: %zu segments (%zu through portals) in %.2f s prove %zu ordered pairs; "
              "lost by portal flow %zu, by might-see %zu",
    segments, oracle.crossingSegments(), since(t0), oracle.provenPairs(), lost(oracle, flow),
    lost(oracle, might));
  if (!old.empty())
  {
    std::printf(", by separating planes %zu", lost(oracle, old));
  }
  std::printf("\n");

  // Per-frame traversal: eyes at 1.6 m in random rooms, random headings, 90 degrees.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> exactMs, pvsMs;
  double exactRooms = 0.0, pvsRooms = 0.0;
  PortalTraversal t;
  TraversalOptions topt;
  std::size_t views = 0;
  for (std::size_t f = 0; f < frames; ++f)
  {
    const Box& cell = level.rooms[rng() % level.rooms.size()].bounds;
    const glm::dvec3 eye(cell.lo.x + (0.1 + 0.8 * u(rng)) * (cell.hi.x - cell.lo.x),
      cell.lo.y + (0.1 + 0.8 * u(rng)) * (cell.hi.y - cell.lo.y), cell.lo.z + 1.6);
    const double yaw = u(rng) * 6.283185307;
    PortalView view;
    view.eye = eye;
    view.clipFromWorld = glm::perspective(glm::radians(90.0), 1.0, 0.05, 1000.0) *
      glm::lookAt(eye, eye + glm::dvec3(std::cos(yaw), std::sin(yaw), 0.0), glm::dvec3(0, 0, 1));
    auto a = Clock::now();
    t.run(graph, view, topt);
    exactMs.push_back(1e3 * since(a));
    exactRooms += static_cast<double>(t.visibleNodes().size());
    a = Clock::now();
    t.runPvs(graph, flow, view, topt);
    pvsMs.push_back(1e3 * since(a));
    pvsRooms += static_cast<double>(t.visibleNodes().size());
    ++views;
  }
  if (views)
  {
    std::printf("traversal over %zu views (90 degrees): exact frustum narrowing median %.3f ms, "
                "%.1f nodes; portal-flow PVS lookup median %.3f ms, %.1f nodes\n",
      views, median(exactMs), exactRooms / double(views), median(pvsMs), pvsRooms / double(views));
  }
  return lost(oracle, flow) == 0 ? 0 : 1;
}

// Specification of the exact traversal against sight lines: a ray from the eye that crosses a
// chain of portals lies, beyond each crossing, in a region of the room it enters. This is what
// lets the culler keep every object such a ray can meet; the oracle walks the ray through the
// portals itself (PortalRayWalk.h), so it does not share the traversal's clipping, region
// containment or merging.
#include "OpenFloorScene.h"
#include "PortalRayWalk.h"
#include "scenevis/PortalGraph.h"
#include "scenevis/PortalTraversal.h"
#include "scenevis/Scenes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace scenevis;
using namespace scenevis::portals;
using scenevis::portaltest::OpenFloor;

namespace
{
/// Mazes with open halls: rooms reached by many chains of portals, so regions are contained in
/// others, merged and clipped many times over.
std::vector<scenes::MazeConfig> openMazes()
{
  std::vector<scenes::MazeConfig> configs;
  const int shapes[][5] = { // x, y, floors, halls per floor, seed
    { 7, 6, 2, 5, 1 }, { 8, 8, 2, 1, 2 }, { 10, 9, 1, 4, 3 }, { 6, 6, 3, 2, 4 }
  };
  for (const auto& s : shapes)
  {
    scenes::MazeConfig c;
    c.roomsX = s[0];
    c.roomsY = s[1];
    c.floors = s[2];
    c.hallsPerFloor = s[3];
    c.seed = static_cast<std::uint64_t>(s[4]);
    c.aligned = 0.8; // long sight lines
    configs.push_back(c);
  }
  return configs;
}

/// What the sight-line checks went through.
struct SightLineCount
{
  std::size_t crossings = 0; ///< Ray crossings checked.
  std::size_t subsumed = 0;  ///< Regions the traversals found contained in others.
  std::size_t merged = 0;    ///< Merges of a room's regions.
};

/// Whether a ray's segment between two crossings stays in a room (RayWalk's `clear`).
using ClearSegment = std::function<bool(std::int32_t, const glm::dvec3&, const glm::dvec3&)>;

/**
 * From @p views random eyes in the cells, 90-degree views: each of 40 x 40 rays from the eye is
 * walked through the portals, and beyond each portal it crosses, the room it enters must hold
 * the ray's point in a region (boxVisible() of a tiny box around it). Rooms that are not convex
 * need @p clear (a ray through a wall is no sight line).
 */
void expectSightLinesInRegions(const PortalGraph& graph, const std::vector<Box>& cells,
  std::uint64_t seed, int views, const TraversalOptions& options, const std::string& name,
  SightLineCount& count, const ClearSegment& clear = nullptr)
{
  constexpr int kRays = 40; // per side of the view
  const auto portalsOf = bench::PortalsOfNodes(graph);
  const double size = graph.buildingBounds().diagonal();
  std::mt19937_64 rng(seed * 31 + 7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PortalTraversal traversal; // reused across views, as a culler does
  for (int v = 0; v < views && !::testing::Test::HasFailure(); ++v)
  {
    const Box& cell = cells[rng() % cells.size()];
    const glm::dvec3 eye = cell.lo +
      (cell.hi - cell.lo) * glm::dvec3(0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng), 0.3 + 0.4 * u(rng));
    const double yaw = 6.283185307 * u(rng), pitch = 0.4 * (u(rng) - 0.5);
    const glm::dvec3 dir(
      std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
    PortalView view;
    view.eye = eye;
    view.clipFromWorld = glm::perspective(glm::radians(90.0), 1.0, 1e-3 * size, 2.0 * size) *
      glm::lookAt(eye, eye + dir, glm::dvec3(0, 0, 1));
    traversal.run(graph, view, options);
    ASSERT_EQ(traversal.stats().fallback, Fallback::None) << name << ": the eye is in a room";
    count.subsumed += traversal.stats().regionsSubsumed;
    count.merged += traversal.stats().regionsMerged;
    const EyeLocation start = graph.locate(eye, 0.0, OutsidePolicy::ExteriorPortals);
    const glm::dmat4 worldFromClip = glm::inverse(view.clipFromWorld);
    for (int i = 0; i < kRays * kRays; ++i)
    {
      const double x = -1.0 + 2.0 * ((i % kRays) + 0.5) / kRays;
      const double y = -1.0 + 2.0 * ((i / kRays) + 0.5) / kRays;
      const glm::dvec4 far = worldFromClip * glm::dvec4(x, y, 1.0, 1.0);
      const glm::dvec3 d = glm::normalize(glm::dvec3(far) / far.w - eye);
      for (const std::int32_t room : start.nodes)
      {
        bench::RayWalk(
          graph, portalsOf, room, eye, d,
          [&](std::int32_t node, double t)
          {
            // A point on the ray just beyond the portal, well inside the view's depth range.
            const glm::dvec3 p = eye + (t + 1e-4 * size) * d;
            ++count.crossings;
            EXPECT_TRUE(traversal.boxVisible(node, bench::TinyBox(p, 1e-9 * size)))
              << name << ", view " << v << ", ray " << i << ": room " << node
              << " entered at t = " << t << " is outside every region of it";
            return !::testing::Test::HasFailure();
          },
          [&clear](std::int32_t node, const glm::dvec3& from, const glm::dvec3& to)
          { return !clear || clear(node, from, to); });
      }
    }
  }
}
} // namespace

TEST(PortalTraversal, SightLinesThroughMazesLieInARegionOfEachRoomTheyEnter)
{
  SightLineCount count;
  for (const scenes::MazeConfig& config : openMazes())
  {
    const scenes::BuildingScene maze = scenes::maze(config);
    std::vector<Box> cells;
    for (const auto& room : maze.rooms)
    {
      cells.push_back(room.bounds);
    }
    expectSightLinesInRegions(PortalGraph::build(cellSceneOf(maze)), cells, config.seed, 16,
      TraversalOptions(), "maze seed " + std::to_string(config.seed), count);
  }
  std::printf("mazes: %zu crossings checked; regions subsumed %zu, merged %zu\n", count.crossings,
    count.subsumed, count.merged);
  EXPECT_GT(count.crossings, 20000u) << "the views look through many portals";
}

TEST(PortalTraversal, SightLinesThroughOpenFloorsLieInARegionOfEachRoomTheyEnter)
{
  SightLineCount count;
  for (const std::uint64_t seed : { 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u })
  {
    const OpenFloor floor(20, 14, seed);
    const PortalGraph graph = PortalGraph::build(floor.input());
    // The default bound on regions per room, and a bound of 2 that merges often.
    for (const std::size_t regions : { 8u, 2u })
    {
      TraversalOptions options;
      options.maxRegionsPerRoom = regions;
      expectSightLinesInRegions(graph, floor.cells, seed, 12, options,
        "open floor seed " + std::to_string(seed) + ", " + std::to_string(regions) +
          " regions per room",
        count);
    }
  }
  std::printf("open floors: %zu crossings checked; regions subsumed %zu, merged %zu\n",
    count.crossings, count.subsumed, count.merged);
  EXPECT_GT(count.crossings, 20000u) << "the views look through many portals";
  EXPECT_GT(count.subsumed, 1000u) << "regions contained in others: the open floors' point";
  EXPECT_GT(count.merged, 100u) << "and rooms whose regions are merged";
}

TEST(PortalTraversal, SightLinesThroughRoomsOfSeveralCellsLieInARegionOfEachRoomTheyEnter)
{
  // Rooms of up to 4 cells (L, U, S shapes, rooms round a wall): not convex, so a region's rays
  // can reach a portal of the room on the eye's side of the portal they came in by, and a region
  // that came in by another portal is contained in it only if its portal lies beyond that entry
  // plane (PortalTraversal::subsumed). Box rooms never test that rule: every portal of a convex
  // room lies beyond each of its portals' planes.
  SightLineCount count;
  std::size_t rooms = 0, cells = 0;
  // Seeds 1015 and 2097 (of 6 and 98 tried): the views where a sight line is lost without the
  // entry-plane rule, in screen-rectangle mode (2 regions per room).
  for (const std::uint64_t seed : { 11u, 12u, 13u, 14u, 1015u, 2097u })
  {
    portaltest::OpenFloorOptions floorOptions;
    floorOptions.joinProbability = 0.45;
    floorOptions.openings = seed % 2 == 0;
    const OpenFloor floor(16, 12, seed, floorOptions);
    rooms += static_cast<std::size_t>(floor.roomCount);
    cells += floor.cells.size();
    const PortalGraph graph = PortalGraph::build(floor.input());
    for (const std::size_t regions : { 16u, 2u })
    {
      TraversalOptions options;
      options.maxRegionsPerRoom = regions;
      options.mode = regions == 2u ? NarrowingMode::ScreenRectangles : NarrowingMode::ExactFrustum;
      expectSightLinesInRegions(graph, floor.cells, seed, 12, options,
        "floor of joined cells, seed " + std::to_string(seed) + ", " + std::to_string(regions) +
          " regions per room",
        count,
        [&floor](std::int32_t room, const glm::dvec3& from, const glm::dvec3& to)
        { return floor.segmentInRoom(room, from, to); });
    }
  }
  std::printf("joined cells: %zu rooms of %zu cells; %zu crossings checked; regions subsumed %zu, "
              "merged %zu\n",
    rooms, cells, count.crossings, count.subsumed, count.merged);
  EXPECT_LT(rooms * 2, cells) << "most rooms have several cells";
  EXPECT_GT(count.crossings, 20000u) << "the views look through many portals";
  EXPECT_GT(count.subsumed, 1000u);
}

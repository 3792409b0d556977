// Specification of the bound on the exact traversal's work when a room's regions keep merging:
// a merged rectangle lets through a little more than its regions did (clipping keeps points
// within a slack), which can come back round a cycle of rooms as a region not quite inside it, so
// merged rectangles could creep by rounding, merge after merge. After a few merges in a frame a
// room's region is the whole view, which holds every region it can get.
//
// The floor below was found by the traversal's fuzz target (Core/Fuzz/FuzzPortalTraversal.cpp):
// an open floor whose faces are all openings, an eye looking steeply up with a 133-degree view and
// one region per room. Before the bound one frame expanded 1.36 million regions (1.7 million
// merges) to reach 26 rooms.
#include "OpenFloorScene.h"
#include "PortalRayWalk.h"
#include "scenevis/PortalGraph.h"
#include "scenevis/PortalTraversal.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace scenevis;
using namespace scenevis::portals;

TEST(PortalTraversal, RoomsThatKeepMergingEndWithTheWholeViewAndLoseNoSightLine)
{
  portaltest::OpenFloorOptions floorOptions;
  floorOptions.portalProbability = 1.0;
  floorOptions.openings = true;
  floorOptions.storeyHeight = 2.6862745098039218;
  const portaltest::OpenFloor floor(9, 6, 241, floorOptions);
  const PortalGraph graph = PortalGraph::build(floor.input());
  const double size = graph.buildingBounds().diagonal();
  const glm::dvec3 eye(5.4842564982760829, 3.620868495399292, 1.1699984681372551);
  const double yaw = 4.3442335912921362, fov = 133.1764705882353, zNear = 0.00060125496053480703;
  const auto portalsOf = bench::PortalsOfNodes(graph);
  const EyeLocation start = graph.locate(eye, 0.0, OutsidePolicy::ExteriorPortals);
  ASSERT_FALSE(start.nodes.empty()) << "the eye is in a room";

  PortalTraversal traversal;
  std::size_t views = 0, crossings = 0;
  // The pitch of the fuzzer's input (1.358), and around it.
  for (const double pitch : { 1.3582768237579399, 1.2, 1.45, 0.9 })
  {
    const glm::dvec3 forward(
      std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
    PortalView view;
    view.eye = eye;
    view.clipFromWorld = glm::perspective(glm::radians(fov), 1.0, zNear, 2.0 * size) *
      glm::lookAt(eye, eye + forward, glm::dvec3(0, 0, 1));
    for (const std::size_t regions : { 1u, 2u, 3u })
    {
      TraversalOptions options;
      options.maxRegionsPerRoom = regions;
      traversal.run(graph, view, options);
      ++views;
      const FrameStats& stats = traversal.stats();
      ASSERT_EQ(stats.fallback, Fallback::None);
      // 54 rooms, each merged at most 4 times then holding the whole view: the work is a small
      // multiple of the rooms, not millions of regions.
      EXPECT_LT(stats.regionsExpanded, 2000u)
        << "pitch " << pitch << ", " << regions << " regions per room: " << stats.regionsMerged
        << " merges";

      // The whole view is bigger than any region: still every sight line through the portals
      // lies in a region of each room it enters (as TestPortalSightLines.cpp checks).
      bench::WalkViewRays(graph, portalsOf, start.nodes, eye, forward, fov, 24,
        [&](int ray, std::int32_t node, double t, const glm::dvec3& d)
        {
          const double s = std::max(t, zNear / glm::dot(d, forward)) + 1e-4 * size;
          ++crossings;
          EXPECT_TRUE(traversal.boxVisible(node, bench::TinyBox(eye + s * d, 1e-9 * size)))
            << "pitch " << pitch << ", " << regions << " regions per room, ray " << ray
            << ": room " << node << " entered at t = " << t << " is outside every region";
          return !::testing::Test::HasFailure();
        });
    }
  }
  EXPECT_EQ(views, 12u);
  EXPECT_GT(crossings, 2000u) << "the views look through many openings";
}

// Specification of the portal-flow PVS (PortalPvs.h, PvsMethod::PortalFlow): conservative against
// a sampling oracle (segments walked through the cells of the demo building and of random maze
// levels), within its might-see sets, compared with the separating-plane method, its budget,
// progress and cancel, and fuzzed over random levels.
#include "PortalSegmentOracle.h"

#include "scenevis/PortalGraph.h"
#include "scenevis/PortalPvs.h"
#include "scenevis/Scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

using namespace scenevis;
using namespace scenevis::portals;
using scenevis::testing_support::PortalSegmentOracle;

namespace
{

PortalPvs computeWith(
  const PortalGraph& g, PvsMethod method, PvsStats* stats = nullptr, int threads = 0)
{
  PvsOptions options;
  options.method = method;
  options.threads = threads;
  return PortalPvs::compute(g, options, stats);
}

/// Pairs the oracle proved that @p pvs lacks, as "from->to" strings (the first few).
std::vector<std::string> misses(
  const PortalSegmentOracle& oracle, const PortalPvs& pvs, std::size_t* count = nullptr)
{
  std::vector<std::string> out;
  std::size_t n = 0;
  for (std::int32_t x = 0; x < pvs.nodeCount(); ++x)
  {
    for (std::int32_t y = 0; y < pvs.nodeCount(); ++y)
    {
      if (oracle.proven(x, y) && !pvs.visible(x, y))
      {
        if (++n <= 5)
        {
          out.push_back(std::to_string(x) + "->" + std::to_string(y));
        }
      }
    }
  }
  if (count)
  {
    *count = n;
  }
  return out;
}

std::size_t totalSize(const PortalPvs& pvs)
{
  std::size_t n = 0;
  for (std::int32_t x = 0; x < pvs.nodeCount(); ++x)
  {
    n += pvs.visibleFrom(x).size();
  }
  return n;
}

bool subset(const PortalPvs& a, const PortalPvs& b)
{
  for (std::int32_t x = 0; x < a.nodeCount(); ++x)
  {
    const auto& sa = a.visibleFrom(x);
    const auto& sb = b.visibleFrom(x);
    if (!std::includes(sb.begin(), sb.end(), sa.begin(), sa.end()))
    {
      return false;
    }
  }
  return true;
}

std::string joined(const std::vector<std::string>& v)
{
  std::string s;
  for (const auto& x : v)
  {
    s += x + " ";
  }
  return s;
}

/// A maze of x * y rooms on @p floors storeys (the other settings as MazeConfig's defaults).
scenes::MazeConfig mazeOf(int x, int y, int floors, std::uint64_t seed, int halls = 0)
{
  scenes::MazeConfig c;
  c.roomsX = x;
  c.roomsY = y;
  c.floors = floors;
  c.seed = seed;
  c.hallsPerFloor = halls;
  return c;
}

scenes::MazeConfig randomMaze(std::uint64_t seed)
{
  std::mt19937_64 rng(seed * 7919 + 3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  scenes::MazeConfig c;
  c.seed = seed;
  c.roomsX = 2 + static_cast<int>(rng() % 6);
  c.roomsY = 1 + static_cast<int>(rng() % 6);
  c.floors = 1 + static_cast<int>(rng() % 3);
  for (double& o : c.openings)
  {
    o = u(rng);
  }
  c.aligned = u(rng);
  c.exteriorWindow = u(rng);
  c.stairHole = 0.5 * u(rng);
  c.hallsPerFloor = static_cast<int>(rng() % 3);
  c.hallSize = 2 + static_cast<int>(rng() % 4);
  return c;
}

/// Two mazes with open halls and aligned openings (long sight lines through many portals), then
/// randomMaze(seed) for seeds firstSeed ... lastSeed.
std::vector<scenes::MazeConfig> hallsAndRandomMazes(std::uint64_t firstSeed, std::uint64_t lastSeed)
{
  std::vector<scenes::MazeConfig> configs = { mazeOf(7, 6, 2, 5, 1), mazeOf(8, 8, 2, 1, 2) };
  for (std::uint64_t seed = firstSeed; seed <= lastSeed; ++seed)
  {
    configs.push_back(randomMaze(seed));
  }
  return configs;
}
} // namespace

TEST(PortalPvsFlow, ContainsEverySampledSightLineInTheDemoBuilding)
{
  for (const std::uint64_t seed : { 1u, 4u, 9u })
  {
    const auto b = scenes::building(2, 4, 3, seed);
    const PortalGraph g = PortalGraph::build(cellSceneOf(b));
    PortalSegmentOracle oracle(b, g);
    oracle.sample(20000, seed);
    ASSERT_GT(oracle.crossingSegments(), 5000u);
    PvsStats stats;
    const PortalPvs flow = computeWith(g, PvsMethod::PortalFlow, &stats);
    const PortalPvs old = computeWith(g, PvsMethod::SeparatingPlanes);
    std::size_t missedFlow = 0, missedOld = 0;
    EXPECT_EQ(misses(oracle, flow, &missedFlow).size(), 0u)
      << "seed " << seed << ": " << joined(misses(oracle, flow));
    EXPECT_EQ(misses(oracle, old, &missedOld).size(), 0u) << "seed " << seed;
    EXPECT_EQ(stats.degradedPortals, 0u);
    EXPECT_EQ(stats.unknownPortals, 0u);
    std::printf("building seed %llu: proven %zu pairs; flow %zu, separating planes %zu\n",
      static_cast<unsigned long long>(seed), oracle.provenPairs(), totalSize(flow), totalSize(old));
  }
}

TEST(PortalPvsFlow, ContainsEverySampledSightLineInAMaze)
{
  const auto m = scenes::maze(mazeOf(7, 6, 2, 5, 1));
  PortalGraphReport report;
  const PortalGraph g = PortalGraph::build(cellSceneOf(m), &report);
  EXPECT_EQ(report.errors() + report.warnings(), 0u) << report.summary();
  PortalSegmentOracle oracle(m, g);
  oracle.sample(60000, 11);
  const PortalPvs flow = computeWith(g, PvsMethod::PortalFlow);
  std::size_t missed = 0;
  const auto first = misses(oracle, flow, &missed);
  EXPECT_EQ(missed, 0u) << joined(first);
  PvsOptions options;
  options.clipSourceBySeparators = true;
  const PortalPvs tighter = PortalPvs::compute(g, options);
  EXPECT_EQ(misses(oracle, tighter).size(), 0u) << "source clipped too";
  std::printf("maze 7x6x2: %zu portals, proven %zu pairs, flow %zu (source clipped too: %zu)\n",
    g.portals().size(), oracle.provenPairs(), totalSize(flow), totalSize(tighter));
}

TEST(PortalPvsFlow, WithinMightSeeAndComparedWithSeparatingPlanes)
{
  std::size_t flowTotal = 0, oldTotal = 0, mightTotal = 0, proven = 0;
  for (const std::uint64_t seed : { 2u, 3u, 6u })
  {
    const auto m = scenes::maze(mazeOf(5, 4, 2, seed));
    const PortalGraph g = PortalGraph::build(cellSceneOf(m));
    PvsStats flowStats, mightStats;
    const PortalPvs flow = computeWith(g, PvsMethod::PortalFlow, &flowStats);
    const PortalPvs might = computeWith(g, PvsMethod::MightSee, &mightStats);
    const PortalPvs old = computeWith(g, PvsMethod::SeparatingPlanes);
    EXPECT_TRUE(subset(flow, might)) << "seed " << seed;
    EXPECT_LE(flowStats.averagePortalVis, flowStats.averageMightSee);
    EXPECT_DOUBLE_EQ(mightStats.averagePortalVis, mightStats.averageMightSee);
    PortalSegmentOracle oracle(m, g);
    oracle.sample(20000, seed);
    EXPECT_EQ(misses(oracle, old).size(), 0u) << "separating planes, seed " << seed;
    EXPECT_EQ(misses(oracle, flow).size(), 0u) << "flow, seed " << seed;
    flowTotal += totalSize(flow);
    oldTotal += totalSize(old);
    mightTotal += totalSize(might);
    proven += oracle.provenPairs();
  }
  // Never looser than the might-see flood; against the separating planes: printed.
  EXPECT_LT(flowTotal, mightTotal);
  std::printf("3 mazes 5x4x2: PVS entries flow %zu, separating planes %zu, might-see %zu; "
              "sampled truth >= %zu pairs + diagonal\n",
    flowTotal, oldTotal, mightTotal, proven);
}

TEST(PortalPvsFlow, OneThreadIsDeterministicManyAreConservative)
{
  // One storey; the same answer from two runs on one thread, and conservative on four.
  const auto m = scenes::maze(mazeOf(6, 5, 1, 8));
  const PortalGraph g = PortalGraph::build(cellSceneOf(m));
  const PortalPvs one = computeWith(g, PvsMethod::PortalFlow, nullptr, 1);
  const PortalPvs again = computeWith(g, PvsMethod::PortalFlow, nullptr, 1);
  const PortalPvs many = computeWith(g, PvsMethod::PortalFlow, nullptr, 4);
  for (std::int32_t x = 0; x < g.nodeCount(); ++x)
  {
    EXPECT_EQ(one.visibleFrom(x), again.visibleFrom(x)) << "one thread is deterministic";
    EXPECT_TRUE(std::binary_search(one.visibleFrom(x).begin(), one.visibleFrom(x).end(), x));
    for (const std::uint32_t pi : g.rooms()[static_cast<std::size_t>(x)].portals)
    {
      EXPECT_TRUE(one.visible(x, g.portals()[pi].other(x))) << "neighbours see each other";
    }
  }
  PortalSegmentOracle oracle(m, g);
  oracle.sample(20000, 8);
  EXPECT_EQ(misses(oracle, many).size(), 0u);
  EXPECT_EQ(misses(oracle, one).size(), 0u);
}

TEST(PortalPvsFlow, BudgetClosesFlowsConservativelyAndSaysSo)
{
  // Past the budget or the step cap a flow closes: what its open branches might still see is
  // taken whole. Never tighter than the full flow (conservative: the oracle's pairs are all
  // there), never looser than the might-see flood.
  const auto m = scenes::maze(mazeOf(8, 8, 2, 1));
  const PortalGraph g = PortalGraph::build(cellSceneOf(m));
  const PortalPvs full = computeWith(g, PvsMethod::PortalFlow, nullptr, 1);
  const PortalPvs might = computeWith(g, PvsMethod::MightSee);
  PortalSegmentOracle oracle(m, g);
  oracle.sample(20000, 8);

  PvsOptions options;
  options.budgetSeconds = 1e-12; // over before the first flow starts: every flow closes at once
  PvsStats stats;
  const PortalPvs late = PortalPvs::compute(g, options, &stats);
  EXPECT_TRUE(stats.budgetExceeded);
  EXPECT_EQ(stats.degradedPortals, stats.directedPortals - 2 * stats.unknownPortals);
  EXPECT_TRUE(subset(full, late));
  EXPECT_TRUE(subset(late, might));
  EXPECT_EQ(misses(oracle, late).size(), 0u);

  options.budgetSeconds = 0.0;
  options.maxFlowStepsPerPortal = 3;
  options.threads = 1; // the same order as `full`: every bound at least as loose
  const PortalPvs capped = PortalPvs::compute(g, options, &stats);
  EXPECT_FALSE(stats.budgetExceeded);
  EXPECT_GT(stats.degradedPortals, 0u);
  EXPECT_TRUE(subset(full, capped));
  EXPECT_TRUE(subset(capped, might));
  EXPECT_EQ(misses(oracle, capped).size(), 0u);
  // Closing keeps what the capped flows found: tighter than the might-see sets they once fell
  // back to.
  EXPECT_LT(totalSize(capped), totalSize(might));
  std::printf("8x8x2 maze: PVS entries full flow %zu, capped at 3 steps %zu, budget 0 %zu, "
              "might-see %zu\n",
    totalSize(full), totalSize(capped), totalSize(late), totalSize(might));
}

TEST(PortalPvsFlow, ProgressOnTheCallingThreadAndCancel)
{
  const auto m = scenes::maze(mazeOf(6, 6, 2, 1));
  const PortalGraph g = PortalGraph::build(cellSceneOf(m));
  std::vector<double> seen;
  bool otherThread = false;
  const auto caller = std::this_thread::get_id();
  PvsOptions options;
  options.progress = [&](double f)
  {
    otherThread = otherThread || std::this_thread::get_id() != caller;
    seen.push_back(f);
    return true;
  };
  EXPECT_FALSE(PortalPvs::compute(g, options).empty());
  ASSERT_FALSE(seen.empty());
  EXPECT_FALSE(otherThread);
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  PvsStats stats;
  options.progress = [](double) { return false; };
  EXPECT_TRUE(PortalPvs::compute(g, options, &stats).empty());
  EXPECT_TRUE(stats.cancelled);
}

TEST(PortalPvsFlow, NonPlanarAndLeakyPortalsStayConservative)
{
  const auto m = scenes::maze(mazeOf(4, 3, 2, 3));
  CellSceneInput in = cellSceneOf(m);
  ASSERT_GT(in.portals.size(), 4u);
  // Bend the first portal out of its plane: it can no longer narrow anything.
  in.portals[0].polygon[2] += 0.3 * glm::dvec3(m.portals[0].normal);
  PortalGraphReport report;
  const PortalGraph bent = PortalGraph::build(in, &report);
  ASSERT_NE(report.summary().find("not planar"), std::string::npos);
  PvsStats stats;
  const PortalPvs pvs = computeWith(bent, PvsMethod::PortalFlow, &stats);
  EXPECT_GE(stats.unknownPortals, 1u);
  PortalSegmentOracle oracle(m, bent);
  oracle.sample(20000, 3);
  EXPECT_EQ(misses(oracle, pvs).size(), 0u);

  // A dangling room id makes its room leaky: whoever may see it sees everything reachable.
  in = cellSceneOf(m);
  in.portals.push_back(PortalDesc{ in.portals[0].polygon, 0, 999 });
  in.roomCount = static_cast<std::int32_t>(m.rooms.size());
  const PortalGraph leaky = PortalGraph::build(in);
  ASSERT_TRUE(leaky.rooms()[0].leaky);
  const PortalPvs fromLeaky = computeWith(leaky, PvsMethod::PortalFlow, &stats);
  EXPECT_GT(stats.leakySources, 0u);
  EXPECT_EQ(fromLeaky.visibleFrom(0).size(),
    computeWith(leaky, PvsMethod::SeparatingPlanes).visibleFrom(0).size());
}

TEST(PortalPvsFlow, FuzzRandomMazesAgainstTheSamplingOracle)
{
  // Random grids of rooms (1-3 storeys of random heights, 0-3 openings per wall of random kinds
  // and sizes, aligned or not, windows, stair holes, open halls), each checked against 8,000
  // segments.
  std::size_t levels = 0, pairs = 0, flowTotal = 0, mightTotal = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed)
  {
    const scenes::MazeConfig c = randomMaze(seed);
    const auto m = scenes::maze(c);
    const PortalGraph g = PortalGraph::build(cellSceneOf(m));
    const PortalPvs flow = computeWith(g, PvsMethod::PortalFlow, nullptr, 1 + int(seed % 2));
    const PortalPvs might = computeWith(g, PvsMethod::MightSee);
    PortalSegmentOracle oracle(m, g);
    oracle.sample(8000, seed);
    std::size_t missed = 0;
    const auto first = misses(oracle, flow, &missed);
    EXPECT_EQ(missed, 0u) << "seed " << seed << " (" << c.roomsX << "x" << c.roomsY << "x"
                          << c.floors << "): " << joined(first);
    EXPECT_TRUE(subset(flow, might)) << "seed " << seed;
    ++levels;
    pairs += oracle.provenPairs();
    flowTotal += totalSize(flow);
    mightTotal += totalSize(might);
  }
  std::printf("fuzz: %zu levels, %zu proven pairs, PVS entries flow %zu, might-see %zu\n", levels,
    pairs, flowTotal, mightTotal);
}

TEST(PortalPvsFlow, PassagesKeepEverySampledSightLineAndOnlyNarrowTheFlow)
{
  // Passage might-see (PvsOptions::passages) only removes bits the separating planes of two
  // consecutive portals rule out: on one thread the sets are within those of the flow without
  // passages, and no pair a sampled segment proves visible is lost. Mazes with open halls and
  // aligned openings (long sight lines through many portals) and random mazes.
  std::size_t with = 0, without = 0, pairs = 0, passages = 0;
  const std::vector<scenes::MazeConfig> configs = hallsAndRandomMazes(41, 52);
  for (const scenes::MazeConfig& c : configs)
  {
    const auto m = scenes::maze(c);
    const PortalGraph g = PortalGraph::build(cellSceneOf(m));
    PvsOptions options;
    options.threads = 1;
    options.passages = true;
    PvsStats stats;
    const PortalPvs narrowed = PortalPvs::compute(g, options, &stats);
    options.passages = false;
    const PortalPvs plain = PortalPvs::compute(g, options);
    const std::string name = std::to_string(c.roomsX) + "x" + std::to_string(c.roomsY) + "x" +
      std::to_string(c.floors) + " seed " + std::to_string(c.seed);
    EXPECT_GT(stats.passages, 0u) << name;
    EXPECT_TRUE(subset(narrowed, plain)) << name;
    PortalSegmentOracle oracle(m, g);
    oracle.sample(30000, c.seed + 100);
    std::size_t missed = 0;
    const auto first = misses(oracle, narrowed, &missed);
    EXPECT_EQ(missed, 0u) << name << ": " << joined(first);
    EXPECT_EQ(misses(oracle, plain).size(), 0u) << name << " (without passages)";
    with += totalSize(narrowed);
    without += totalSize(plain);
    pairs += oracle.provenPairs();
    passages += stats.passages;
  }
  std::printf("passages: %zu levels, %zu portal pairs, %zu proven pairs, PVS entries with "
              "passages %zu, without %zu\n",
    configs.size(), passages, pairs, with, without);
}

TEST(PortalPvsFlow, PassagesWithFourThreadsAndAStepCapStayConservative)
{
  // Threads change which bounds a flow meets (another portal's final set or its might-see set)
  // and a step cap closes flows: the passages must hold in every case.
  const auto m = scenes::maze(mazeOf(8, 8, 2, 1, 2));
  const PortalGraph g = PortalGraph::build(cellSceneOf(m));
  PortalSegmentOracle oracle(m, g);
  oracle.sample(30000, 17);
  PvsOptions options;
  options.threads = 4;
  options.passages = true;
  const PortalPvs many = PortalPvs::compute(g, options);
  EXPECT_EQ(misses(oracle, many).size(), 0u);
  options.maxFlowStepsPerPortal = 5;
  PvsStats stats;
  const PortalPvs capped = PortalPvs::compute(g, options, &stats);
  EXPECT_GT(stats.degradedPortals, 0u);
  EXPECT_EQ(misses(oracle, capped).size(), 0u);
}

TEST(PortalPvsFlow, MergedFlowKeepsEverySampledSightLineAndHoldsTheWalksSets)
{
  // The merged flow (PvsOptions::mergeAfterSteps) keeps one polygon per portal reached instead
  // of one per path. Forced on every source (after 1 step), on one thread: it holds everything
  // the walk over paths finds (every path's polygons lie inside the merged ones), stays within
  // the might-see sets, closes no flow, and loses no pair a sampled segment proves visible;
  // with and without passages (every other level).
  std::size_t merged = 0, walked = 0, might = 0, pairs = 0;
  const std::vector<scenes::MazeConfig> configs = hallsAndRandomMazes(61, 76);
  for (const scenes::MazeConfig& c : configs)
  {
    const auto m = scenes::maze(c);
    const PortalGraph g = PortalGraph::build(cellSceneOf(m));
    const std::string name = std::to_string(c.roomsX) + "x" + std::to_string(c.roomsY) + "x" +
      std::to_string(c.floors) + " seed " + std::to_string(c.seed);
    PvsOptions options;
    options.threads = 1;
    options.passages = c.seed % 2 == 1;
    options.mergeAfterSteps = 0;
    const PortalPvs walk = PortalPvs::compute(g, options);
    options.mergeAfterSteps = 1;
    PvsStats stats;
    const PortalPvs mergedPvs = PortalPvs::compute(g, options, &stats);
    const PortalPvs mightPvs = computeWith(g, PvsMethod::MightSee);
    EXPECT_EQ(stats.degradedPortals, 0u) << name;
    EXPECT_TRUE(subset(walk, mergedPvs)) << name;
    EXPECT_TRUE(subset(mergedPvs, mightPvs)) << name;
    PortalSegmentOracle oracle(m, g);
    oracle.sample(30000, c.seed + 200);
    std::size_t missed = 0;
    const auto first = misses(oracle, mergedPvs, &missed);
    EXPECT_EQ(missed, 0u) << name << ": " << joined(first);
    merged += totalSize(mergedPvs);
    walked += totalSize(walk);
    might += totalSize(mightPvs);
    pairs += oracle.provenPairs();
  }
  EXPECT_LT(merged, might) << "the merged flow narrows the might-see sets";
  std::printf("merged flow: %zu levels, %zu proven pairs, PVS entries walk %zu, merged %zu, "
              "might-see %zu\n",
    configs.size(), pairs, walked, merged, might);
}

TEST(PortalPvsFlow, MergedFlowOnFourThreadsAndUnderABudgetStaysConservative)
{
  const auto m = scenes::maze(mazeOf(8, 8, 2, 1, 2));
  const PortalGraph g = PortalGraph::build(cellSceneOf(m));
  PortalSegmentOracle oracle(m, g);
  oracle.sample(30000, 19);
  PvsOptions options;
  options.threads = 4;
  options.passages = true;
  options.mergeAfterSteps = 1;
  PvsStats stats;
  const PortalPvs many = PortalPvs::compute(g, options, &stats);
  EXPECT_GT(stats.mergedPortals, 0u);
  EXPECT_EQ(misses(oracle, many).size(), 0u);
  options.budgetSeconds = 1e-12; // merged flows close at once
  const PortalPvs late = PortalPvs::compute(g, options, &stats);
  EXPECT_TRUE(stats.budgetExceeded);
  EXPECT_EQ(misses(oracle, late).size(), 0u);
}

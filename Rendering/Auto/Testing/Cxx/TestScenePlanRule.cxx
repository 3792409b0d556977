// The rule's culling choice from facts alone, at the edges of its thresholds: many small opaque
// parts that may be merged are drawn as one mesh (whole, or in chunks with occlusion between
// them), while parts the application draws as they are, translucent parts and parts of many
// triangles keep a prop culler. Then the translucency choice for a mesh of parts (split into
// actors when its translucent parts' boxes overlap little) and the overlap measure itself.
#include "PlannerTesting.h"

#include "vtkScenePlanRule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace
{
using plannertesting::Check;

/// A game level as the command line sees it: @p parts opaque surfaces, @p triangles in all.
vtkScenePlanFacts Level(std::size_t parts, vtkIdType triangles, double depthComplexity = 15.0)
{
  vtkScenePlanFacts facts;
  facts.parts = parts;
  facts.triangles = triangles;
  facts.polygons = triangles;
  facts.inView = 0.5;
  facts.depthComplexity = depthComplexity;
  return facts;
}

/// A translucent mesh of @p parts parts (all translucent), @p overlap of whose boxes overlap.
vtkScenePlanFacts Translucent(std::size_t parts, double overlap, double inView = 1.0)
{
  vtkScenePlanFacts facts = Level(parts, 20 * static_cast<vtkIdType>(parts));
  facts.translucentFraction = 0.5;
  facts.translucentParts = parts;
  facts.translucentOverlap = overlap;
  facts.inView = inView;
  facts.depthComplexity = 2.0; // translucent parts hide little: no occlusion culling
  return facts;
}

bool ExpectSort(const vtkScenePlanFacts& facts, const std::string& method,
  const std::string& reasonHas, const std::string& what, bool severalActors = false)
{
  const vtkScenePlanChoice choice =
    vtkScenePlanRule::ChooseTranslucency(facts, false, severalActors, severalActors ? 2 : 1);
  return Check(choice.Method == method && choice.Reason.find(reasonHas) != std::string::npos,
    what + ": " + choice.Method + ", " + choice.Reason);
}

vtkScenePlanPartBox Box(double x0, double x1, double y0, double y1, double z0, double z1,
  bool translucent = true, vtkIdType triangles = 1)
{
  vtkScenePlanPartBox box;
  box.Triangles = triangles;
  const double b[6] = { x0, x1, y0, y1, z0, z1 };
  std::copy(b, b + 6, box.Box);
  box.Translucent = translucent;
  return box;
}

bool ExpectOverlap(
  const std::vector<vtkScenePlanPartBox>& boxes, double expected, const std::string& what)
{
  const double overlap = vtkScenePlanRule::MeasureOverlap(boxes);
  return Check(std::abs(overlap - expected) < 1e-12,
    what + ": " + std::to_string(overlap) + " (expected " + std::to_string(expected) + ")");
}

bool Expect(const vtkScenePlanFacts& facts, const std::string& method, int chunkSize,
  const std::string& reasonHas, const std::string& what)
{
  const vtkScenePlanChoice choice = vtkScenePlanRule::ChooseCulling(facts);
  return Check(choice.Method == method && choice.ChunkSize == chunkSize &&
      choice.Reason.find(reasonHas) != std::string::npos,
    what + ": " + choice.Method + " (chunks of " + std::to_string(choice.ChunkSize) + "), " +
      choice.Reason);
}
} // namespace

int TestScenePlanRule(int, char*[])
{
  bool ok = true;
  const int chunk = vtkScenePlanRule::SmallPartChunkSize;
  const vtkIdType big = vtkScenePlanRule::ChunkOcclusionTriangles;

  // ctf_gate1: 1,319 surfaces, 3,885 triangles; ctf_inyard: 4,239 surfaces, 18,332 triangles.
  ok &= Expect(Level(1319, 3885), "none", 0, "2.95 triangles on average", "small level: whole");
  ok &= Expect(Level(4239, 18332), "chunked-occlusion", chunk, "in chunks of 64",
    "big level: chunks with occlusion");
  ok &= Expect(Level(4239, 18332, 2.0), "chunked", chunk, "in chunks of 64",
    "big level seen with little depth: chunks, frustum only");
  // The thresholds themselves.
  ok &= Expect(Level(1000, big - 1), "none", 0, "< 10000", "one triangle below the chunk size");
  ok &= Expect(Level(1000, big), "chunked-occlusion", chunk, ">= 10000", "at the chunk size");
  const std::size_t parts = 1000;
  const auto perPartLimit =
    static_cast<vtkIdType>(vtkScenePlanRule::SmallPartTriangles * static_cast<double>(parts));
  ok &= Expect(Level(parts, perPartLimit - 1), "chunked-occlusion", chunk, "opaque parts",
    "just under the small-part size");
  ok &= Expect(Level(parts, perPartLimit), "occlusion", 0, "1000 parts",
    "at the small-part size: one actor per part, culled");

  // Not merged: the application's own actors, translucent parts, fewer than ManyProps parts.
  vtkScenePlanFacts fixed = Level(4239, 18332);
  fixed.fixedActors = true;
  ok &= Expect(fixed, "occlusion", 0, "4239 parts", "fixed actors stay actors");
  vtkScenePlanFacts translucent = Level(4239, 18332);
  translucent.translucentFraction = 0.1;
  ok &= Expect(translucent, "occlusion", 0, "4239 parts", "translucent parts keep their order");
  ok &= Expect(Level(vtkScenePlanRule::ManyProps - 1, 990), "none", 0, "< 100",
    "few parts: drawn whole as before");
  // The engine grid: 46,000 parts of about 1,000 triangles.
  ok &= Expect(Level(46000, 48600000), "occlusion", 0, "46000 parts", "big parts: culled as props");

  // Translucent meshes of parts: split into actors (multi-actor) below MaxOverlapToSplit of the
  // translucent parts' boxes overlapping, one mesh in BSP order (bsp-mapper) from it on.
  const double edge = vtkScenePlanRule::MaxOverlapToSplit;
  ok &= ExpectSort(Translucent(1000, 0.05), "multi-actor", "1000 translucent parts overlap little",
    "the cad demo: split");
  ok &= ExpectSort(Translucent(115, 0.77), "bsp-mapper", "BSP tree", "the engine: one mesh");
  ok &= ExpectSort(Translucent(1000, std::nextafter(edge, 0.0)), "multi-actor",
    "% of the triangles are in", "just under the overlap threshold: split");
  ok &= ExpectSort(Translucent(1000, edge), "bsp-mapper", "BSP tree", "at the threshold: one mesh");
  ok &= ExpectSort(Translucent(1000, 0.0), "multi-actor", "(0 % of the triangles", "no overlap");
  ok &= ExpectSort(Translucent(vtkScenePlanRule::MinPartsToSplit, 0.0), "multi-actor",
    "split into one actor per part", "the fewest parts split");
  ok &= ExpectSort(Translucent(vtkScenePlanRule::MinPartsToSplit - 1, 0.0), "bsp-mapper",
    "BSP tree", "one translucent part: nothing to order across");
  ok &= ExpectSort(Translucent(1000, -1.0), "bsp-mapper", "BSP tree", "overlap not measured");
  const std::size_t most = vtkScenePlanRule::MaxPartsToSplit;
  ok &= ExpectSort(Translucent(most, 0.0), "multi-actor", "split", "the most parts split");
  ok &= ExpectSort(Translucent(most + 1, 0.0), "bsp-mapper", "BSP tree",
    "one part more: the actors cost more than the mapper's sort");
  vtkScenePlanFacts tiny = Translucent(1000, 0.0);
  tiny.triangles = perPartLimit - 1;
  ok &= ExpectSort(tiny, "bsp-mapper", "BSP tree",
    "parts of just under SmallPartTriangles (a level's surfaces): one mesh");
  tiny.triangles = perPartLimit;
  ok &= ExpectSort(tiny, "multi-actor", "split", "parts of SmallPartTriangles: split");
  vtkScenePlanFacts fixedTranslucent = Translucent(1000, 0.0);
  fixedTranslucent.fixedActors = true;
  ok &= ExpectSort(fixedTranslucent, "bsp-mapper", "BSP tree", "one fixed actor is not split");
  ok &= ExpectSort(Translucent(1000, 0.9), "multi-actor", "in 2 actors",
    "several actors are ordered across actors whatever they overlap", true);
  ok &= ExpectSort(Level(1000, 20000), "none", "opaque", "opaque: no sorting");
  ok &= Check(
    vtkScenePlanRule::ChooseTranslucency(Translucent(1000, 0.0), true, false, 1).Method == "oit",
    "chunked drawing: order independent even when the parts could be split");

  // The culling of such a mesh follows: split parts may be culled as actors when not all in
  // view, while parts that overlap a lot stay one mesh ("none") above MaxTranslucentForActors.
  ok &= Expect(Translucent(1000, 0.05, 0.5), "octree", 0, "1000 parts",
    "translucent parts that overlap little, half in view: culled as actors");
  ok &= Expect(Translucent(1000, edge, 0.5), "none", 0, "translucent",
    "translucent parts that overlap a lot: one mesh");
  ok &= Expect(Translucent(1000, 0.05, 1.0), "none", 0, "of the triangles",
    "in full view: not culled, whether split or not");

  // The measure.
  ok &= ExpectOverlap({}, 0.0, "no boxes");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1) }, 0.0, "one box");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1), Box(2, 3, 0, 1, 0, 1), Box(0, 1, 2, 3, 0, 1) }, 0.0,
    "separated boxes");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1), Box(1, 2, 0, 1, 0, 1), Box(0, 1, 0, 1, -1, 0) }, 0.0,
    "boxes that touch (a bolt on a plate) do not overlap");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1), Box(1 - 1e-8, 2, 0, 1, 0, 1) }, 0.0,
    "boxes that touch up to rounding do not overlap");
  ok &= ExpectOverlap(
    { Box(0, 1, 0, 1, 0, 1), Box(0.99, 2, 0, 1, 0, 1) }, 1.0, "boxes 1 % into each other overlap");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1), Box(0.5, 1.5, 0.5, 1.5, 0.5, 1.5),
                        Box(5, 6, 0, 1, 0, 1), Box(0, 1, 5, 6, 0, 1) },
    0.5, "two of four overlap");
  ok &= ExpectOverlap(
    { Box(0, 1, 0, 1, 0, 1), Box(0.5, 1.5, 0.5, 1.5, 0.5, 1.5, false), Box(5, 6, 0, 1, 0, 1) }, 0.0,
    "opaque boxes are not counted");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1, true, 10), Box(0.5, 2, 0, 1, 0, 1, true, 10),
                        Box(5, 6, 0, 1, 0, 1, false, 80) },
    0.2, "weighted by triangles: 20 of 100 in overlapping translucent parts");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1, true, 10), Box(0.5, 2, 0, 1, 0, 1, true, 10),
                        Box(5, 6, 0, 1, 0, 1, true, 30) },
    0.4, "weighted by triangles: 20 of 50");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1), Box(0.25, 0.75, 0.25, 0.75, 0.5, 0.5) }, 1.0,
    "a flat part through a box overlaps it");
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0.5, 0.5), Box(0.5, 1.5, 0, 1, 0.5, 0.5) }, 0.0,
    "coplanar flat parts do not overlap");
  ok &= ExpectOverlap({ Box(0, 0, 0, 0, 0, 0), Box(0, 0, 0, 0, 0, 0) }, 0.0,
    "two points at the origin do not overlap");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ok &= ExpectOverlap({ Box(0, 1, 0, 1, 0, 1), Box(nan, 1, 0, 1, 0, 1), vtkScenePlanPartBox() },
    0.0, "NaN and empty boxes are left out");
  {
    // Found only along one axis: boxes spread along y, all sharing their x and z extents.
    std::vector<vtkScenePlanPartBox> row;
    for (int i = 0; i < 1000; ++i)
      row.push_back(Box(0, 1, 2 * i, 2 * i + 1 + (i % 10 == 0 ? 1.5 : 0.0), 0, 1));
    ok &= ExpectOverlap(row, 0.2, "a row along y, every tenth box reaching into the next");
    // Stacked: every box overlaps every other; the sweep stops early and says so.
    std::vector<vtkScenePlanPartBox> stack(4000, Box(0, 1, 0, 1, 0, 1));
    ok &= ExpectOverlap(stack, 1.0, "4000 boxes in one place");
  }
  return ok ? 0 : 1;
}

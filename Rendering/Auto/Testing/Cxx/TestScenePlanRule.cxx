// The rule's culling choice from facts alone, at the edges of its thresholds: many small opaque
// parts that may be merged are drawn as one mesh (whole, or in chunks with occlusion between
// them), while parts the application draws as they are, translucent parts and parts of many
// triangles keep a prop culler.
#include "PlannerTesting.h"

#include "vtkScenePlanRule.h"

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
  return ok ? 0 : 1;
}

// Auto mode: the facts of a scene and the plan made from them.
#include "AutoPlan.h"

#include "Progress.h"
#include "SplitParts.h"
#include "vtkAutoRooms.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPoints.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <chrono>
#include <unordered_map>
#include <unordered_set>

namespace scenevis
{
namespace tool
{
namespace
{
/// The rule's thresholds (vtkScenePlanRule documents why they are what they are).
constexpr std::size_t kManyProps = vtkScenePlanRule::ManyProps;

SceneFacts InspectScene(vtkPolyData* pd, vtkPolyData* portals, const Options& options)
{
  SceneFacts facts;
  facts.polygons = pd->GetNumberOfCells();
  facts.triangles = CountTriangles(pd);
  facts.parts = std::max<std::size_t>(1, DistinctValues(pd, options.partArray.c_str()).size());
  if (auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars()))
  {
    if (colors->GetNumberOfComponents() == 4 && facts.polygons > 0)
    {
      vtkIdType translucent = 0;
      for (vtkIdType c = 0; c < colors->GetNumberOfTuples(); ++c)
        translucent += colors->GetTypedComponent(c, 3) < 255 ? 1 : 0;
      facts.translucentFraction =
        static_cast<double>(translucent) / static_cast<double>(facts.polygons);
    }
  }
  for (const long long room : DistinctValues(pd, options.roomArray.c_str()))
    facts.rooms += room >= 0 ? 1 : 0;
  facts.portals = portals ? portals->GetNumberOfCells() : 0;
  return facts;
}

/// The facts of an instanced scene: every placement is a part, counted with its mesh's polygons.
SceneFacts InspectInstances(const InstancedScene& scene)
{
  SceneFacts facts;
  std::vector<vtkIdType> translucentOf(scene.meshes.size(), 0);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
  {
    auto* colors = vtkUnsignedCharArray::SafeDownCast(scene.meshes[m]->GetCellData()->GetScalars());
    if (colors && colors->GetNumberOfComponents() == 4)
    {
      for (vtkIdType c = 0; c < colors->GetNumberOfTuples(); ++c)
        translucentOf[m] += colors->GetTypedComponent(c, 3) < 255 ? 1 : 0;
    }
  }
  std::vector<vtkIdType> trianglesOf(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    trianglesOf[m] = CountTriangles(scene.meshes[m]);
  vtkIdType translucent = 0;
  for (const auto& instance : scene.instances)
  {
    facts.polygons += scene.meshes[instance.mesh]->GetNumberOfCells();
    facts.triangles += trianglesOf[instance.mesh];
    translucent += translucentOf[instance.mesh];
  }
  facts.parts = std::max<std::size_t>(1, scene.instances.size());
  facts.fixedActors = true; // one actor per placement, never merged
  if (facts.polygons > 0)
    facts.translucentFraction =
      static_cast<double>(translucent) / static_cast<double>(facts.polygons);
  return facts;
}

using PartBox = vtkScenePlanPartBox;

/// The bounding box, triangle count and translucency (RGBA cell colours) of each part (of
/// @p partArray) of @p pd.
std::vector<PartBox> PartBoxes(vtkPolyData* pd, const std::string& partArray)
{
  vtkDataArray* partIds = pd->GetCellData()->GetArray(partArray.c_str());
  auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
  if (colors && colors->GetNumberOfComponents() != 4)
    colors = nullptr;
  std::unordered_map<long long, PartBox> parts;
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkIdType c = 0;
  PartBox* part = nullptr;
  long long partId = 0;
  vtkPoints* points = pd->GetPoints();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts); ++c)
  {
    const long long id = partIds ? static_cast<long long>(partIds->GetTuple1(c)) : 0;
    if (!part || id != partId) // runs of one part's cells: one lookup
      part = &parts[id];
    partId = id;
    part->Triangles += std::max<vtkIdType>(npts - 2, 0);
    part->Translucent = part->Translucent || (colors && colors->GetTypedComponent(c, 3) < 255);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      double p[3];
      points->GetPoint(pts[k], p);
      for (int a = 0; a < 3; ++a)
      {
        part->Box[2 * a] = std::min(part->Box[2 * a], p[a]);
        part->Box[2 * a + 1] = std::max(part->Box[2 * a + 1], p[a]);
      }
    }
  }
  std::vector<PartBox> boxes;
  boxes.reserve(parts.size());
  for (const auto& entry : parts)
    boxes.push_back(entry.second);
  return boxes;
}

/// The box and triangles of each placement of @p scene (each mesh's triangles counted once).
std::vector<PartBox> InstanceBoxes(const InstancedScene& scene)
{
  std::vector<vtkIdType> trianglesOf(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    trianglesOf[m] = CountTriangles(scene.meshes[m]);
  std::vector<PartBox> boxes(scene.instances.size());
  for (std::size_t i = 0; i < scene.instances.size(); ++i)
  {
    InstanceBounds(scene, scene.instances[i], boxes[i].Box);
    boxes[i].Triangles = trianglesOf[scene.instances[i].mesh];
  }
  return boxes;
}

/**
 * --cull auto on a scene without rooms and portals: rooms and portals generated in memory when it
 * looks architectural and used when they are at least 2 rooms and 1 portal with no leak
 * (vtkAutoRooms, as the auto planner does); the room array of @p pd is then replaced and @p facts
 * count them. Returns what was found and why, for the culling reason.
 */
std::string GenerateRoomsForAuto(vtkPolyData* pd, const std::string& roomArray, SceneFacts& facts,
  vtkSmartPointer<vtkPolyData>& portals, double& ms)
{
  const vtkAutoRooms generated = vtkAutoRooms::Generate(pd, roomArray.c_str());
  ms = generated.Milliseconds;
  if (!generated.Used)
  {
    return "; " + generated.Reason;
  }
  pd->GetCellData()->RemoveArray(roomArray.c_str());
  pd->GetCellData()->AddArray(generated.Rooms);
  portals = generated.Portals;
  const auto before = facts.rooms;
  facts.rooms = generated.RoomCount;
  facts.portals = static_cast<vtkIdType>(generated.PortalCount);
  std::string why = "auto: " + generated.Reason;
  if (before > 0)
    why += "; the scene's " + std::to_string(before) + " rooms (" + roomArray +
      ") came without portals and were replaced";
  return why;
}

bool IsPropCulling(const std::string& mode)
{
  return mode == "frustum" || mode == "octree" || mode == "normal-cones" ||
    mode.rfind("small:", 0) == 0 || CullUsesPortals(mode) || CullUsesOcclusion(mode);
}

CullPlan PlanCulling(
  const std::string& requested, const SceneFacts& facts, const std::string& roomArray)
{
  CullPlan plan;
  plan.method = requested;
  plan.roomArray = roomArray;
  plan.reason = "requested with --cull (" + facts.Summary() + ")";
  const bool rooms = facts.rooms > 0 && facts.portals > 0;
  if (requested == "auto")
  {
    const vtkScenePlanChoice choice = vtkScenePlanRule::ChooseCulling(facts);
    plan.method = choice.Method;
    plan.reason = choice.Reason + " (" + facts.Summary() + ")";
    plan.chunkSize = choice.ChunkSize;
  }
  if (plan.Portals() && !rooms)
  {
    throw UsageError("--cull " + plan.method +
      " needs rooms and portals: the building demo, or a model with a " + roomArray +
      " cell array (--room-array) and --portals FILE.vtp");
  }
  plan.needsActors = IsPropCulling(plan.method);
  plan.chunked = plan.method == "chunked" || plan.method == "chunked-occlusion";
  if (plan.method.rfind("small:", 0) == 0)
  {
    plan.smallPixels = std::stod(plan.method.substr(6));
  }
  return plan;
}

/// The translucency method given the culling plan: prop culling draws one actor per group, which
/// only methods that work across actors can order; chunked drawing reorders the polygons chunk by
/// chunk, which only order-independent methods survive.
std::string ChooseSort(const std::string& requested, const SceneFacts& facts, const CullPlan& cull,
  bool split, std::size_t actors, std::string& reason)
{
  reason = "requested with --sort";
  const bool independent =
    requested == "none" || requested == "oit" || requested.rfind("peel:", 0) == 0;
  if (requested != "auto")
  {
    if (cull.chunked && !independent)
      throw UsageError("--cull chunked reorders the polygons chunk by chunk: --sort takes auto, "
                       "none, oit or peel:N with it");
    if (split && !independent && requested != "multi-actor")
      throw UsageError("--cull " + cull.method +
        " draws one actor per part: --sort takes auto, "
        "none, oit, multi-actor or peel:N with it");
    return requested;
  }
  const vtkScenePlanChoice choice =
    vtkScenePlanRule::ChooseTranslucency(facts, cull.chunked, split, actors);
  reason = choice.Reason;
  return choice.Method;
}
} // namespace

std::set<long long> DistinctValues(
  vtkPolyData* pd, const char* name, const std::vector<vtkIdType>* cells)
{
  std::set<long long> values;
  vtkDataArray* array = pd->GetCellData()->GetArray(name);
  if (!array || array->GetNumberOfComponents() != 1)
  {
    return values;
  }
  if (cells)
  {
    for (const vtkIdType c : *cells)
      values.insert(static_cast<long long>(array->GetTuple1(c)));
    return values;
  }
  // Hashed, and a run of cells with one value looked up once: exporters write parts' cells
  // together (48.6M cells in 2 s instead of 6).
  std::unordered_set<long long> seen;
  bool first = true;
  long long previous = 0;
  for (vtkIdType c = 0; c < array->GetNumberOfTuples(); ++c)
  {
    const auto value = static_cast<long long>(array->GetTuple1(c));
    if (first || value != previous)
      seen.insert(value);
    first = false;
    previous = value;
  }
  values.insert(seen.begin(), seen.end());
  return values;
}

ScenePlan PlanScene(const Options& options, const LoadedScene& scene, const std::string& sort,
  vtkRenderer* renderer, bool releaseSplitScene)
{
  ScenePlan plan;
  const auto inspectStart = std::chrono::steady_clock::now();
  plan.instanced = scene.instanced.get();
  plan.facts = plan.instanced ? InspectInstances(*plan.instanced)
                              : InspectScene(scene.polydata, scene.portals, options);
  // A translucent mesh of parts: how much its translucent parts overlap decides whether it is
  // split into them (vtkScenePlanRule::SplitsIntoParts), unless the sort orders one mesh.
  // Portal and prop culling draw one actor per room or part, which such a sort cannot follow
  // either.
  const bool sortAcrossActors = sort == "auto" || sort == "none" || sort == "oit" ||
    sort == "multi-actor" || sort.rfind("peel:", 0) == 0;
  const bool measureOverlap = !plan.instanced && sortAcrossActors &&
    plan.facts.translucentFraction > 0.0 && plan.facts.parts >= vtkScenePlanRule::MinPartsToSplit;
  if (plan.facts.parts >= kManyProps || measureOverlap)
  {
    const std::vector<PartBox> boxes = plan.instanced
      ? InstanceBoxes(*plan.instanced)
      : PartBoxes(scene.polydata, options.partArray);
    if (plan.facts.parts >= kManyProps)
      plan.facts.inView = vtkScenePlanRule::MeasureView(boxes, renderer->GetActiveCamera(),
        static_cast<double>(options.width) / static_cast<double>(options.height),
        &plan.facts.depthComplexity);
    if (measureOverlap)
    {
      plan.facts.translucentParts = static_cast<std::size_t>(std::count_if(
        boxes.begin(), boxes.end(), [](const PartBox& box) { return box.Translucent; }));
      plan.facts.translucentOverlap = vtkScenePlanRule::MeasureOverlap(boxes);
    }
  }
  plan.inspectMs = Milliseconds(inspectStart);
  plan.portals = scene.portals;
  std::string generation;
  if (options.cull == "auto" && !plan.instanced &&
    !(plan.facts.rooms > 0 && plan.facts.portals > 0))
  {
    generation = sortAcrossActors
      ? GenerateRoomsForAuto(
          scene.polydata, options.roomArray, plan.facts, plan.portals, plan.generateMs)
      : "; rooms and portals not generated: --sort " + sort + " orders one mesh";
  }
  plan.cull = PlanCulling(options.cull, plan.facts, options.roomArray);
  if (generation.rfind("auto: ", 0) == 0)
    plan.cull.reason = generation + "; " + plan.cull.reason;
  else
    plan.cull.reason += generation;
  if (plan.instanced && options.cull == "auto" && plan.cull.chunked)
  {
    // The rule's choice for one big opaque mesh; placements are drawn as they are, one actor
    // per mesh, so they are culled as props instead.
    const std::string why = plan.cull.reason;
    plan.cull = PlanCulling("octree", plan.facts, options.roomArray);
    plan.cull.reason = "placements are drawn as they are (--instances), so not chunked: the BVH "
                       "culls them one by one; the rule for one mesh said: " +
      why;
  }
  plan.cull.pvsBudget = options.pvsBudget;
  plan.cull.recordOcclusion = options.recordOcclusion;
  if (options.chunkSize > 0)
    plan.cull.chunkSize = options.chunkSize;
  if (plan.instanced)
  {
    if (plan.cull.chunked)
      throw UsageError("--cull " + plan.cull.method +
        " draws one mesh; --instances draws one actor per placement: choose a prop culling mode");
    plan.groups = plan.instanced->meshes;
  }
  else if (plan.cull.needsActors)
  {
    // Rooms first: an actor must lie in one room for the portal culler to cull it.
    const auto splitStart = std::chrono::steady_clock::now();
    plan.groups =
      SplitByKeys(scene.polydata, { options.roomArray, options.partArray }, releaseSplitScene);
    plan.splitMs = Milliseconds(splitStart);
  }
  const std::size_t actors = plan.instanced ? plan.instanced->instances.size() : plan.groups.size();
  plan.sort = ChooseSort(
    sort, plan.facts, plan.cull, plan.instanced || plan.groups.size() > 1, actors, plan.sortReason);
  const std::string& m = plan.cull.method;
  plan.instancedProps = plan.instanced && !options.instanceActors && plan.sort != "multi-actor" &&
    (m == "none" || m == "octree" || m == "occlusion");
  if (plan.sort == "multi-actor" && plan.groups.empty())
  {
    const auto splitStart = std::chrono::steady_clock::now();
    plan.groups = SplitByPart(scene.polydata, options.partArray, releaseSplitScene);
    plan.splitMs = Milliseconds(splitStart);
  }
  return plan;
}

} // namespace tool
} // namespace scenevis

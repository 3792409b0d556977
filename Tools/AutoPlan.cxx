// Auto mode: the facts of a scene and the plan made from them.
#include "AutoPlan.h"

#include "Progress.h"
#include "SplitParts.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkMatrix4x4.h>
#include <vtkPoints.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace scenevis
{
namespace tool
{
namespace
{
/// Above this many parts, culling whole props pays for its hierarchy (auto -> octree).
constexpr std::size_t kManyProps = 100;
/// Above this many triangles in one opaque mesh, culling chunks inside it pays (auto -> chunked):
/// the 64 spheres at 1M triangles seen from inside the grid draw 10x faster chunked (19k of 1M
/// triangles drawn), and a full view costs about the same either way.
constexpr vtkIdType kHugeMesh = 500000;
/// Prop culling draws one actor per part, which translucency then orders across actors
/// (vtkBSPTranslucentPass); above this fraction of translucent polygons that sort interleaves
/// the parts' fragments into thousands of draw calls (2CylinderEngine at opacity 0.4: 32k draw
/// calls, 4.3 s a frame), so auto keeps one mesh with the BSP order instead.
constexpr double kMaxTranslucentForActors = 0.25;
/// Prop culling draws one actor per part, which costs VTK per-actor work every frame; when the
/// first camera sees at least this fraction of the triangles, culling cannot pay for that (the
/// cad demo in full view: 1.2-1.5x slower than one mesh; seen from close up: 1.4-1.7x faster).
constexpr double kMinInViewForNoCulling = 0.9;

/// Estimated depth complexity (the in-view parts' screen rectangles summed, over the viewport)
/// from which auto prefers occlusion culling to frustum culling alone: most of what is in view
/// is then hidden behind nearer parts (the 2CylinderEngine grid 4 x 4 seen down a row: 86 parts
/// drawn per part seen with frustum culling, 2 with occlusion; BENCHMARKS.md). The value 4 is a
/// first estimate, not yet calibrated over many scenes: the cad demo's views score 1.3-2.7.
constexpr double kOcclusionDepthComplexity = 4.0;

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
  if (facts.polygons > 0)
    facts.translucentFraction =
      static_cast<double>(translucent) / static_cast<double>(facts.polygons);
  return facts;
}

/// A part's world box and triangles: what auto's view estimate (TrianglesInView) looks at.
struct PartBox
{
  double box[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  vtkIdType triangles = 0;
};

/// The bounding box and triangle count of each part (of @p partArray) of @p pd.
std::vector<PartBox> PartBoxes(vtkPolyData* pd, const std::string& partArray)
{
  vtkDataArray* partIds = pd->GetCellData()->GetArray(partArray.c_str());
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
    part->triangles += std::max<vtkIdType>(npts - 2, 0);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      double p[3];
      points->GetPoint(pts[k], p);
      for (int a = 0; a < 3; ++a)
      {
        part->box[2 * a] = std::min(part->box[2 * a], p[a]);
        part->box[2 * a + 1] = std::max(part->box[2 * a + 1], p[a]);
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
    InstanceBounds(scene, scene.instances[i], boxes[i].box);
    boxes[i].triangles = trianglesOf[scene.instances[i].mesh];
  }
  return boxes;
}

/// The fraction of the triangles of @p parts whose bounding box meets the side planes of
/// @p camera's frustum (near and far ignored: the clipping range follows the props);
/// @p depthComplexity: the in-view parts' screen rectangles over the viewport.
double TrianglesInView(const std::vector<PartBox>& parts, vtkCamera* camera, double aspect,
  double* depthComplexity = nullptr)
{
  vtkIdType total = 0;
  for (const PartBox& part : parts)
    total += part.triangles;
  if (total == 0)
  {
    return 1.0;
  }
  double planes[24]; // left, right, bottom, top, near, far: ax + by + cz + d >= 0 inside
  camera->GetFrustumPlanes(aspect, planes);
  vtkMatrix4x4* projection = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  double covered = 0.0;
  vtkIdType inView = 0;
  for (const PartBox& part : parts)
  {
    bool outside = false;
    for (int k = 0; k < 4 && !outside; ++k)
    {
      const double* plane = planes + 4 * k;
      double distance = plane[3];
      for (int a = 0; a < 3; ++a)
        distance += plane[a] * (plane[a] >= 0.0 ? part.box[2 * a + 1] : part.box[2 * a]);
      outside = distance < 0.0;
    }
    inView += outside ? 0 : part.triangles;
    if (!outside && depthComplexity)
    {
      // Screen rectangle in normalized device coordinates ([-1, 1]^2, area 4).
      double x0 = 1.0, x1 = -1.0, y0 = 1.0, y1 = -1.0;
      bool whole = false;
      for (int k = 0; k < 8 && !whole; ++k)
      {
        const double p[4] = { part.box[k & 1], part.box[2 + ((k >> 1) & 1)],
          part.box[4 + ((k >> 2) & 1)], 1.0 };
        double q[4];
        projection->MultiplyPoint(p, q);
        if (!(q[3] > 0.0))
        {
          whole = true;
          break;
        }
        x0 = std::min(x0, q[0] / q[3]);
        x1 = std::max(x1, q[0] / q[3]);
        y0 = std::min(y0, q[1] / q[3]);
        y1 = std::max(y1, q[1] / q[3]);
      }
      covered += whole ? 4.0
                       : std::max(0.0, std::min(x1, 1.0) - std::max(x0, -1.0)) *
          std::max(0.0, std::min(y1, 1.0) - std::max(y0, -1.0));
    }
  }
  if (depthComplexity)
  {
    *depthComplexity = covered / 4.0;
  }
  return static_cast<double>(inView) / static_cast<double>(total);
}

bool IsPropCulling(const std::string& mode)
{
  return mode == "frustum" || mode == "octree" || mode == "normal-cones" || mode == "occlusion" ||
    mode.rfind("small:", 0) == 0 || mode == "portals" || mode == "pvs";
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
    const bool opaque = facts.translucentFraction == 0.0;
    std::ostringstream why;
    if (rooms)
    {
      plan.method = "portals";
      why << facts.rooms << " rooms and " << facts.portals
          << " portals: cells and portals skip the rooms the eye cannot see through them";
    }
    else if (facts.parts >= kManyProps && facts.translucentFraction <= kMaxTranslucentForActors &&
      facts.inView < kMinInViewForNoCulling)
    {
      if (facts.depthComplexity >= kOcclusionDepthComplexity)
      {
        plan.method = "occlusion";
        why << facts.parts << " parts (>= " << kManyProps
            << ") and an estimated depth complexity of " << std::setprecision(3)
            << facts.depthComplexity << " (>= " << kOcclusionDepthComplexity
            << "): most of what is in view is hidden, so parts hidden behind nearer opaque ones "
               "are culled too";
      }
      else
      {
        plan.method = "octree";
        why << facts.parts << " parts (>= " << kManyProps
            << "): one actor per part, culled by the BVH a whole subtree at a time";
      }
    }
    else if (facts.triangles >= kHugeMesh && opaque)
    {
      plan.method = "chunked";
      why << facts.triangles << " triangles (>= " << kHugeMesh << ") in " << facts.parts
          << (facts.parts == 1 ? " part" : " parts")
          << ", opaque: chunks of the one mesh are culled inside its buffers";
    }
    else
    {
      plan.method = "none";
      if (facts.parts >= kManyProps && facts.inView >= kMinInViewForNoCulling)
        why << facts.parts << " parts, but the first camera sees " << std::setprecision(3)
            << 100.0 * facts.inView << " % of the triangles (>= " << 100.0 * kMinInViewForNoCulling
            << " %): culling would draw nearly all of them as many actors";
      else if (facts.parts >= kManyProps)
        why << facts.parts << " parts but " << std::setprecision(3)
            << 100.0 * facts.translucentFraction << " % translucent (> "
            << 100.0 * kMaxTranslucentForActors
            << " %): one mesh in BSP order draws faster than sorting that many actors' "
               "fragments across actors";
      else if (facts.triangles >= kHugeMesh)
        why << facts.triangles << " triangles but translucent (" << std::setprecision(3)
            << 100.0 * facts.translucentFraction
            << " %): chunked drawing would break the sorted order, so everything is drawn";
      else
        why << facts.parts << (facts.parts == 1 ? " part" : " parts") << " (< " << kManyProps
            << ") and " << facts.triangles << " triangles (< " << kHugeMesh << ")"
            << (opaque ? ", opaque" : "") << ": drawing everything costs less than culling";
    }
    plan.reason = why.str() + " (" + facts.Summary() + ")";
  }
  if ((plan.method == "portals" || plan.method == "pvs") && !rooms)
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
std::string ChooseSort(const std::string& requested, bool translucent, const CullPlan& cull,
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
  if (!translucent)
  {
    reason = "the scene is opaque: no sorting needed";
    return "none";
  }
  if (cull.chunked)
  {
    reason = "translucent, but chunked drawing reorders the polygons: VTK's weighted OIT "
             "(order independent, approximate)";
    return "oit";
  }
  if (split)
  {
    reason = "translucent polygons in " + std::to_string(actors) +
      " actors (prop culling): exact order across actors with vtkBSPTranslucentPass";
    return "multi-actor";
  }
  // The mapper, not the filter: the same exact order, but only the index buffer changes per
  // frame (scripts/culling-report.py, docs/auto-vs-fixed.csv: 1.1-1.3x faster frames).
  reason = "the scene has translucent polygons: exact order with the BSP tree, rewritten in the "
           "index buffer only (vtkBSPSortedPolyDataMapper)";
  return "bsp-mapper";
}
} // namespace

std::string SceneFacts::Summary() const
{
  std::ostringstream text;
  text << parts << (parts == 1 ? " part, " : " parts, ") << triangles << " triangles, "
       << std::setprecision(3) << 100.0 * translucentFraction << " % translucent, " << rooms
       << " rooms, " << portals << " portals";
  if (inView >= 0.0)
    text << ", " << 100.0 * inView << " % of the triangles in view";
  if (depthComplexity >= 0.0)
    text << ", estimated depth complexity " << depthComplexity;
  return text.str();
}

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
  if (plan.facts.parts >= kManyProps)
  {
    const std::vector<PartBox> boxes = plan.instanced
      ? InstanceBoxes(*plan.instanced)
      : PartBoxes(scene.polydata, options.partArray);
    plan.facts.inView = TrianglesInView(boxes, renderer->GetActiveCamera(),
      static_cast<double>(options.width) / static_cast<double>(options.height),
      &plan.facts.depthComplexity);
  }
  plan.inspectMs = Milliseconds(inspectStart);
  plan.cull = PlanCulling(options.cull, plan.facts, options.roomArray);
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
  plan.sort = ChooseSort(sort, plan.facts.translucentFraction > 0.0, plan.cull,
    plan.instanced || plan.groups.size() > 1, actors, plan.sortReason);
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

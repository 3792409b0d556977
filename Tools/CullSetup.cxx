// The --cull modes installed on a renderer.
#include "CullSetup.h"

#include "Progress.h"
#include "Report.h"
#include "SceneLoading.h"
#include "vtkChunkedPolyDataMapper.h"
#include "vtkInstancedActor.h"
#include "vtkOcclusionCuller.h"

#include "scenevis/OcclusionRecording.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkCuller.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkMapper.h>
#include <vtkNew.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

namespace scenevis
{
namespace tool
{

/**
 * Cullers run one after the other, as a renderer runs its own list (each gets what the ones
 * before it kept): one culler for CullStage to time and re-use.
 */
class CullerChain : public vtkCuller
{
public:
  static CullerChain* New() { return new CullerChain; }
  vtkTypeMacro(CullerChain, vtkCuller);

  static vtkSmartPointer<CullerChain> Of(vtkCuller* first, vtkCuller* second)
  {
    auto chain = vtkSmartPointer<CullerChain>::New();
    chain->Cullers = { first, second };
    return chain;
  }

  double Cull(vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized) override
  {
    double total = 0.0;
    for (const auto& culler : this->Cullers)
    {
      total = culler->Cull(ren, propList, listLength, initialized);
    }
    return total;
  }

  std::vector<vtkSmartPointer<vtkCuller>> Cullers;
};

/**
 * Wraps the culler of a mode (vtkFrustumCoverageCuller, vtkOctreeCuller, vtkPortalCuller, or
 * the portal culler and the occlusion culler in a CullerChain): times it, records what it kept,
 * and while the camera, the viewport and the props are unchanged re-uses the last visible set
 * instead of culling again (auto's "camera unchanged: no re-cull"). It honours the vtkCuller
 * contract itself on re-used frames.
 */
class CullStage : public vtkCuller
{
public:
  static CullStage* New() { return new CullStage; }
  vtkTypeMacro(CullStage, vtkCuller);

  double Cull(vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized) override
  {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<double> key = ViewKey(ren);
    const std::vector<vtkProp*> input(propList, propList + listLength);
    double total = 0.0;
    this->Reused = this->HaveLast && key == this->LastKey && input == this->LastInput;
    if (this->Reused)
    {
      std::vector<vtkProp*> culled;
      int kept = 0;
      for (vtkProp* prop : input)
      {
        if (this->VisibleSet.count(prop))
          propList[kept++] = prop;
        else
          culled.push_back(prop);
      }
      std::copy(culled.begin(), culled.end(), propList + kept);
      listLength = kept;
      for (int i = 0; i < kept; ++i)
      {
        if (!initialized)
          propList[i]->SetRenderTimeMultiplier(1.0);
        total += propList[i]->GetRenderTimeMultiplier();
      }
      initialized = 1;
    }
    else
    {
      total = this->Inner->Cull(ren, propList, listLength, initialized);
      this->LastKey = key;
      this->LastInput = input;
      this->HaveLast = true;
      this->VisibleSet = std::set<vtkProp*>(propList, propList + listLength);
    }
    this->Visible.assign(propList, propList + listLength);
    this->LastMs = Milliseconds(start);
    return total;
  }

  vtkSmartPointer<vtkCuller> Inner;
  std::vector<vtkProp*> Visible; ///< props kept by the last Cull()
  bool Reused = false;           ///< the last Cull() re-used the previous visible set
  double LastMs = 0.0;

private:
  /// Everything the visible set depends on apart from the props: camera and viewport.
  static std::vector<double> ViewKey(vtkRenderer* ren)
  {
    vtkCamera* camera = ren->GetActiveCamera();
    std::vector<double> key;
    auto add = [&key](const double* v, int n) { key.insert(key.end(), v, v + n); };
    add(camera->GetPosition(), 3);
    add(camera->GetFocalPoint(), 3);
    add(camera->GetViewUp(), 3);
    add(camera->GetClippingRange(), 2);
    add(camera->GetWindowCenter(), 2);
    key.push_back(camera->GetViewAngle());
    key.push_back(camera->GetParallelScale());
    key.push_back(camera->GetParallelProjection());
    key.push_back(ren->GetTiledAspectRatio());
    const int* size = ren->GetSize();
    key.push_back(size[0]);
    key.push_back(size[1]);
    return key;
  }

  std::vector<double> LastKey;
  std::vector<vtkProp*> LastInput;
  std::set<vtkProp*> VisibleSet;
  bool HaveLast = false;
};

CullSetup::CullSetup(const CullPlan& plan, const MethodPipeline& pipeline, vtkRenderer* renderer,
  vtkPolyData* scene, vtkPolyData* portals, bool showProgress)
  : Plan(plan)
  , Pipeline(pipeline)
{
  // "none" really draws everything: not even VTK's default frustum coverage culler.
  renderer->GetCullers()->RemoveAllItems();
  // Refused up front, as any file the tool cannot write (the culler would only warn); until a
  // cull records, the file is a recording of no culls.
  if (!plan.recordOcclusion.empty())
  {
    std::ofstream file(plan.recordOcclusion, std::ios::binary | std::ios::trunc);
    scenevis::occlusion::writeOcclusionRecording(file, {});
    if (!file.flush())
      throw std::runtime_error("cannot write '" + plan.recordOcclusion + "'");
  }
  if (vtkChunkedPolyDataMapper* chunked = pipeline.GetChunkedMapper())
  {
    chunked->SetOcclusionCulling(plan.method == "chunked-occlusion");
    if (plan.chunkSize > 0)
      chunked->SetChunkSize(plan.chunkSize);
    if (plan.method == "chunked-occlusion" && !plan.recordOcclusion.empty())
      chunked->SetOcclusionRecordFile(plan.recordOcclusion.c_str());
  }
  // Triangles per actor, of the scene's polygons before any sorting splits them (one actor:
  // the whole scene, whose mapper may read a sorter that has not run yet).
  const auto& actors = pipeline.GetActors();
  std::unordered_map<vtkPolyData*, vtkIdType> trianglesOfInput; // instances share their mesh
  for (const auto& actor : actors)
  {
    auto* input = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
    vtkIdType triangles = 0;
    if (actors.size() == 1)
      triangles = CountTriangles(scene);
    else if (input)
    {
      auto found = trianglesOfInput.find(input);
      if (found == trianglesOfInput.end())
        found = trianglesOfInput.emplace(input, CountTriangles(input)).first;
      triangles = found->second;
    }
    this->TrianglesOf[actor] = triangles; // instanced props: per placement
    if (auto* instanced = vtkInstancedActor::SafeDownCast(actor))
      triangles *= instanced->GetNumberOfPlacements();
    this->TotalTriangles += triangles;
  }
  vtkSmartPointer<vtkCuller> inner;
  const std::string& m = plan.method;
  if (m == "frustum")
  {
    inner = vtkSmartPointer<vtkFrustumCoverageCuller>::New();
  }
  if (m == "octree" || m == "normal-cones" || plan.Occlusion() || plan.smallPixels > 0.0)
  {
    this->Octree = plan.Occlusion()
      ? vtkSmartPointer<vtkOctreeCuller>(vtkSmartPointer<vtkOcclusionCuller>::New())
      : vtkSmartPointer<vtkOctreeCuller>::New();
    if (m == "normal-cones")
    {
      // Normal cones only apply to actors drawn with back-face culling.
      this->Octree->NormalConeCullingOn();
      for (const auto& actor : pipeline.GetActors())
        actor->GetProperty()->BackfaceCullingOn();
    }
    this->Octree->SetMinimumPixelSize(plan.smallPixels);
    if (plan.Occlusion() && !plan.recordOcclusion.empty())
      vtkOcclusionCuller::SafeDownCast(this->Octree)
        ->SetOcclusionRecordFile(plan.recordOcclusion.c_str());
    inner = this->Octree;
  }
  if (plan.Portals())
  {
    this->Portal = vtkSmartPointer<vtkPortalCuller>::New();
    this->Portal->SetPortals(portals);
    this->Portal->SetRoomIdArrayName(plan.roomArray.c_str());
    this->Portal->SetMode(
      plan.Pvs() ? vtkPortalCuller::MODE_PVS : vtkPortalCuller::MODE_EXACT_FRUSTUM);
    // portals+occlusion: the occlusion culler gets what the portal culler kept.
    inner = inner ? vtkSmartPointer<vtkCuller>(CullerChain::Of(this->Portal, inner))
                  : vtkSmartPointer<vtkCuller>(this->Portal);
    if (plan.Pvs())
    {
      // Past the budget, the unfinished portals keep their conservative might-see sets.
      this->Portal->SetPVSBudgetSeconds(plan.pvsBudget);
      vtkNew<ProgressBar> progress;
      progress->Label = "computing PVS";
      if (showProgress)
        this->Portal->AddObserver(vtkCommand::ProgressEvent, progress);
      const auto start = std::chrono::steady_clock::now();
      const bool computed = this->Portal->ComputePVS(renderer);
      this->PvsMs = Milliseconds(start);
      this->Portal->RemoveObservers(vtkCommand::ProgressEvent);
      if (!computed)
        throw std::runtime_error("cannot compute the PVS of the portal scene");
    }
  }
  if (inner)
  {
    this->Stage = vtkSmartPointer<CullStage>::New();
    this->Stage->Inner = inner;
    renderer->AddCuller(this->Stage);
  }
}

vtkIdType CullSetup::PropsDrawn() const
{
  if (!this->Stage)
    return this->Pipeline.Placements();
  vtkIdType props = 0;
  for (vtkProp* prop : this->Stage->Visible)
  {
    auto* instanced = vtkInstancedActor::SafeDownCast(prop);
    props += instanced ? instanced->GetNumberOfVisiblePlacements() : 1;
  }
  return props;
}

vtkIdType CullSetup::TrianglesDrawn() const
{
  if (vtkChunkedPolyDataMapper* chunked = this->Pipeline.GetChunkedMapper())
    return chunked->GetNumberOfTrianglesDrawn();
  if (!this->Stage)
    return this->TotalTriangles;
  vtkIdType triangles = 0;
  for (vtkProp* prop : this->Stage->Visible)
  {
    auto found = this->TrianglesOf.find(prop);
    auto* instanced = vtkInstancedActor::SafeDownCast(prop);
    triangles += (found == this->TrianglesOf.end() ? 0 : found->second) *
      (instanced ? instanced->GetNumberOfVisiblePlacements() : 1);
  }
  return triangles;
}

double CullSetup::CullMs() const
{
  if (vtkChunkedPolyDataMapper* chunked = this->Pipeline.GetChunkedMapper())
    return chunked->GetLastCullTime() * 1e3;
  return this->Stage ? this->Stage->LastMs : 0.0;
}

bool CullSetup::Reused() const
{
  return this->Stage && this->Stage->Reused;
}

const std::vector<vtkProp*>* CullSetup::Visible() const
{
  return this->Stage ? &this->Stage->Visible : nullptr;
}

void CullSetup::Describe(std::ostream& json) const
{
  json << ", \"approximate\": " << (this->Plan.smallPixels > 0.0 ? "true" : "false");
  if (this->Plan.smallPixels > 0.0)
    json << ", \"minimum_pixels\": " << this->Plan.smallPixels;
  json << ", \"actors\": " << this->Pipeline.Parts();
  if (this->Pipeline.InstancedProps())
    json << ", \"instanced_props\": true, \"placements\": " << this->Pipeline.Placements();
  json << ", \"triangles_total\": " << this->TotalTriangles;
  if (this->Octree)
  {
    vtkOctreeCuller* oc = this->Octree;
    json << ", \"octree\": {\"nodes_visited\": " << oc->GetNumberOfNodesVisited()
         << ", \"props_tested\": " << oc->GetNumberOfPropsTested()
         << ", \"culled_by_frustum\": " << oc->GetNumberOfPropsCulledByFrustum()
         << ", \"culled_by_size\": " << oc->GetNumberOfPropsCulledBySize()
         << ", \"culled_by_normal_cone\": " << oc->GetNumberOfPropsCulledByNormalCone()
         << ", \"rebuilds\": " << oc->GetNumberOfRebuilds() << "}";
    if (auto* occ = vtkOcclusionCuller::SafeDownCast(oc))
    {
      json << ", \"occlusion\": {\"culled_by_occlusion\": "
           << occ->GetNumberOfPropsCulledByOcclusion()
           << ", \"occlusion_tests\": " << occ->GetNumberOfOcclusionTests()
           << ", \"occluders_drawn\": " << occ->GetNumberOfOccludersDrawn()
           << ", \"occluders_skipped\": " << occ->GetNumberOfOccludersSkipped()
           << ", \"occluder_triangles\": " << occ->GetNumberOfOccluderTriangles()
           << ", \"raster_ms\": " << occ->GetOccluderRasterTime()
           << ", \"cull_ms\": " << occ->GetCullTime()
           << ", \"depth_buffer_bytes\": " << occ->GetDepthBufferBytes()
           << ", \"occluder_cache_bytes\": " << occ->GetOccluderCacheBytes() << "}";
    }
  }
  if (this->Portal)
  {
    vtkPortalCuller* p = this->Portal;
    json << ", \"portals\": {\"rooms\": " << p->GetNumberOfRooms()
         << ", \"rooms_visited\": " << p->GetNumberOfRoomsVisited()
         << ", \"portals_traversed\": " << p->GetNumberOfPortalsTraversed()
         << ", \"frustum_only\": " << (p->GetFrustumOnly() ? "true" : "false")
         << ", \"fallback\": " << JsonString(p->GetFallbackReason())
         << ", \"pvs_ms\": " << this->PvsMs;
    if (this->PvsMs > 0.0)
    {
      json << ", \"pvs\": {\"method\": "
           << (p->GetPVSMethod() == vtkPortalCuller::PVS_SEPARATING_PLANES ? "\"separating-planes\""
                                                                           : "\"portal-flow\"")
           << ", \"average_rooms\": " << p->GetPVSAverageSetSize()
           << ", \"degraded_portals\": " << p->GetPVSDegradedPortals()
           << ", \"budget_seconds\": " << p->GetPVSBudgetSeconds()
           << ", \"budget_exceeded\": " << (p->GetPVSBudgetExceeded() ? "true" : "false") << "}";
    }
    json << "}";
  }
  if (vtkChunkedPolyDataMapper* c = this->Pipeline.GetChunkedMapper())
  {
    json << ", \"chunked\": {\"chunks\": " << c->GetNumberOfChunks()
         << ", \"chunks_drawn\": " << c->GetNumberOfChunksDrawn()
         << ", \"culled_by_frustum\": " << c->GetNumberOfChunksCulledByFrustum()
         << ", \"culled_by_normal_cone\": " << c->GetNumberOfChunksCulledByNormalCone()
         << ", \"culled_by_size\": " << c->GetNumberOfChunksCulledBySize()
         << ", \"culled_by_occlusion\": " << c->GetNumberOfChunksCulledByOcclusion()
         << ", \"draw_calls\": " << c->GetNumberOfDrawCalls()
         << ", \"partition_ms\": " << c->GetLastPartitionTime() * 1e3 << "}";
  }
}
} // namespace tool
} // namespace scenevis

// The translucency methods of --sort as one pipeline on a renderer.
#include "MethodPipeline.h"

#include "vtkInstancedActor.h"

#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkMatrix4x4.h>
#include <vtkPropCollection.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>

namespace scenevis
{
namespace tool
{
namespace
{
/// Above this many actors, a command that has written everything leaves without tearing down.
constexpr int kFastExitActors = 1000;
} // namespace

MethodPipeline::MethodPipeline(const std::string& requested, vtkPolyData* pd, vtkRenderer* renderer,
  bool showProgress, const std::vector<vtkSmartPointer<vtkPolyData>>* groups, bool chunked,
  const InstancedScene* instanced, bool instancedProps)
  // bsp-leaves:N is the BSP filter with ordered leaves of up to N polygons.
  : Method(requested.rfind("bsp-leaves:", 0) == 0 ? "bsp" : requested)
  , Input(pd)
  , InputPolygons(pd ? pd->GetNumberOfPolys() : 0)
{
  const std::string& method = this->Method;
  if (requested.rfind("bsp-leaves:", 0) == 0)
  {
    this->Bsp->SetOrderedLeafSize(std::stoi(requested.substr(11)));
  }
  if (chunked)
  {
    this->Chunked = vtkSmartPointer<vtkChunkedPolyDataMapper>::New();
    this->Mapper = this->Chunked;
  }
  else
  {
    this->Mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  }
  const bool split = instanced || (groups && groups->size() > 1);
  if (!pd && groups)
  {
    for (const auto& group : *groups)
      this->InputPolygons += group->GetNumberOfPolys();
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  auto makeActor = [&](vtkPolyDataMapper* mapper)
  {
    mapper->SetScalarModeToUseCellData();
    mapper->SetColorModeToDirectScalars();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    // Not renderer->AddActor(): vtkViewport::AddViewProp first scans every prop already there
    // (HasViewProp), so adding n actors costs O(n^2): 88 s for 46,000 parts. Each actor here is
    // new, so the scan can be skipped; AddConsumer is the rest of what AddViewProp does.
    renderer->GetViewProps()->AddItem(actor);
    actor->AddConsumer(renderer);
    this->Actors.push_back(actor);
    return actor.Get();
  };
  if (method == "bsp-mapper")
  {
    this->BspMapper->SetInputData(pd);
    makeActor(this->BspMapper);
  }
  else if (instanced && instancedProps)
  {
    // One vtkInstancedActor per mesh, its placements as plain matrices (136 bytes each instead
    // of a vtkActor and its transforms); a placement-aware culler culls them one by one.
    this->PerMesh = true;
    vtkNew<vtkProperty> property;
    std::vector<vtkSmartPointer<vtkInstancedActor>> meshActors;
    for (const auto& mesh : instanced->meshes)
    {
      auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      mapper->SetInputData(mesh);
      mapper->SetScalarModeToUseCellData();
      mapper->SetColorModeToDirectScalars();
      meshActors.push_back(vtkSmartPointer<vtkInstancedActor>::New());
      meshActors.back()->SetMapper(mapper);
      meshActors.back()->SetProperty(property);
    }
    std::vector<vtkIdType> placementsOf(instanced->meshes.size(), 0);
    for (const Instance& instance : instanced->instances)
      ++placementsOf[instance.mesh];
    for (std::size_t m = 0; m < meshActors.size(); ++m)
      meshActors[m]->ReservePlacements(placementsOf[m]);
    for (std::size_t i = 0; i < instanced->instances.size(); ++i)
    {
      const Instance& instance = instanced->instances[i];
      meshActors[instance.mesh]->AddPlacement(instance.matrix.data(), static_cast<vtkIdType>(i));
      this->InstancedPolygons += instanced->meshes[instance.mesh]->GetNumberOfPolys();
    }
    this->PlacementCount = static_cast<vtkIdType>(instanced->instances.size());
    for (const auto& actor : meshActors)
    {
      if (actor->GetNumberOfPlacements() == 0)
        continue;
      renderer->GetViewProps()->AddItem(actor);
      actor->AddConsumer(renderer);
      this->Actors.push_back(actor);
    }
  }
  else if (instanced)
  {
    std::vector<vtkSmartPointer<vtkPolyDataMapper>> mappers;
    for (const auto& mesh : instanced->meshes)
    {
      mappers.push_back(vtkSmartPointer<vtkPolyDataMapper>::New());
      mappers.back()->SetInputData(mesh);
    }
    // One property for every placement: the colours are cell scalars, and a property per actor
    // would cost ~1 kB each (46 MB for 46,000 placements).
    vtkNew<vtkProperty> property;
    for (const auto& instance : instanced->instances)
    {
      vtkActor* actor = makeActor(mappers[instance.mesh]);
      vtkNew<vtkMatrix4x4> matrix;
      matrix->DeepCopy(instance.matrix.data());
      actor->SetUserMatrix(matrix);
      actor->SetProperty(property);
      this->InstancedPolygons += instanced->meshes[instance.mesh]->GetNumberOfPolys();
    }
    if (method == "multi-actor")
      this->OrderedPass->SetTranslucentPass(this->BspPass);
  }
  else if (method == "multi-actor" || split)
  {
    const std::vector<vtkSmartPointer<vtkPolyData>> whole{ pd };
    vtkNew<vtkProperty> property; // shared, as for instances (colours are cell scalars)
    for (const auto& part : groups && !groups->empty() ? *groups : whole)
    {
      auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      mapper->SetInputData(part);
      makeActor(mapper)->SetProperty(property);
    }
    if (method == "multi-actor")
      this->OrderedPass->SetTranslucentPass(this->BspPass);
  }
  else
  {
    vtkActor* actor = makeActor(this->Mapper);
    if (method == "bsp")
    {
      this->Bsp->SetInputData(pd);
      this->Bsp->SetCamera(camera);
      this->Bsp->SetProp3D(actor);
      if (showProgress)
      {
        this->Progress->Label = "building BSP tree";
        this->Bsp->AddObserver(vtkCommand::ProgressEvent, this->Progress);
      }
      this->Sorter = this->Bsp;
    }
    else if (method == "painter")
    {
      this->Painter->SetInputData(pd);
      this->Painter->SetCamera(camera);
      this->Painter->SetProp3D(actor);
      this->Sorter = this->Painter;
    }
    else if (method == "depth-sort")
    {
      this->DepthSort->SetInputData(pd);
      this->DepthSort->SetCamera(camera);
      this->DepthSort->SetProp3D(actor);
      this->DepthSort->SetDirectionToBackToFront();
      this->DepthSort->SetDepthSortModeToParametricCenter();
      this->Sorter = this->DepthSort;
    }
    if (this->Sorter)
    {
      this->Mapper->SetInputConnection(this->Sorter->GetOutputPort());
    }
    else
    {
      this->Mapper->SetInputData(pd);
    }
  }
  if (method.rfind("peel:", 0) == 0)
  {
    renderer->SetUseDepthPeeling(1);
    renderer->SetMaximumNumberOfPeels(std::stoi(method.substr(5)));
    renderer->SetOcclusionRatio(0.0);
  }
  else if (method != "oit")
  {
    // Every method with a drawing order (and "none": the input's order) needs ordered blending.
    renderer->SetPass(this->OrderedPass);
  }
}

double MethodPipeline::Update()
{
  this->OrderCountBefore = this->OrderCount();
  const auto start = std::chrono::steady_clock::now();
  if (this->Sorter)
  {
    this->Sorter->Update();
  }
  this->LastUpdateMs = Milliseconds(start);
  return this->LastUpdateMs;
}

double MethodPipeline::LastSortMs() const
{
  if (this->OrderCount() == this->OrderCountBefore)
    return 0.0;
  if (this->Method == "bsp")
    return this->Bsp->GetLastOrderTime() * 1e3;
  if (this->Method == "painter")
    return this->Painter->GetLastOrderTime() * 1e3;
  if (this->Method == "depth-sort")
    return this->LastUpdateMs;
  if (this->Method == "bsp-mapper")
    return this->BspMapper->GetLastOrderTime() * 1e3;
  if (this->Method == "multi-actor")
    return this->BspPass->GetLastOrderTime() * 1e3;
  return 0.0;
}

double MethodPipeline::BuildMs() const
{
  if (this->Method == "bsp")
    return this->Bsp->GetLastBuildTime() * 1e3;
  if (this->Method == "painter")
    return this->Painter->GetLastBuildTime() * 1e3;
  if (this->Method == "bsp-mapper")
    return this->BspMapper->GetLastBuildTime() * 1e3;
  if (this->Method == "multi-actor")
    return this->BspPass->GetLastBuildTime() * 1e3;
  return 0.0;
}

vtkIdType MethodPipeline::Fragments() const
{
  if (this->Method == "bsp") // what the last order drew (fewer than stored with ordered leaves)
    return this->Bsp->GetLastNumberOfOrderedFragments();
  if (this->Method == "painter")
    return this->Painter->GetNumberOfFragments();
  if (this->Method == "bsp-mapper")
    return this->BspMapper->GetNumberOfFragments();
  if (this->Method == "multi-actor")
    return this->BspPass->GetNumberOfFragments();
  return this->InstancedPolygons > 0 ? this->InstancedPolygons : this->InputPolygons;
}

vtkSmartPointer<vtkPolyData> MethodPipeline::DrawnOrder() const
{
  if (this->Sorter)
  {
    return this->Sorter->GetOutput();
  }
  if (this->Method == "none" && this->InstancedPolygons == 0)
  {
    return this->Input;
  }
  if (this->Method == "multi-actor")
  {
    auto fragments = vtkSmartPointer<vtkPolyData>::New();
    this->BspPass->GetOrderedFragments(fragments);
    return fragments;
  }
  return nullptr;
}

void MethodPipeline::Describe(std::ostream& json, std::ostream& text) const
{
  if (this->Method == "bsp")
  {
    json << ",\n  \"bsp\": {\"fragments\": " << this->Bsp->GetNumberOfFragments()
         << ", \"ordered_leaf_size\": " << this->Bsp->GetOrderedLeafSize()
         << ", \"fragments_drawn\": " << this->Bsp->GetLastNumberOfOrderedFragments()
         << ", \"splits\": " << this->Bsp->GetNumberOfSplits()
         << ", \"depth\": " << this->Bsp->GetTreeDepth()
         << ", \"removed_polygons\": " << this->Bsp->GetNumberOfRemovedPolygons() << "}";
    text << ", BSP build " << this->BuildMs() << " ms (" << this->Bsp->GetNumberOfFragments()
         << " fragments, " << this->Bsp->GetNumberOfSplits() << " splits, depth "
         << this->Bsp->GetTreeDepth() << ")";
  }
  else if (this->Method == "painter")
  {
    json << ",\n  \"painter\": {\"fragments\": " << this->Painter->GetNumberOfFragments()
         << ", \"splits\": " << this->Painter->GetNumberOfSplits()
         << ", \"forced_emissions\": " << this->Painter->GetNumberOfForcedEmissions()
         << ", \"removed_polygons\": " << this->Painter->GetNumberOfRemovedPolygons() << "}";
    text << ", painter's normalisation " << this->BuildMs()
         << " ms (last frame: " << this->Painter->GetNumberOfFragments() << " fragments, "
         << this->Painter->GetNumberOfSplits() << " splits)";
  }
  else if (this->Method == "bsp-mapper")
  {
    json << ",\n  \"bsp_mapper\": {\"fragments\": " << this->BspMapper->GetNumberOfFragments()
         << ", \"triangles\": " << this->BspMapper->GetNumberOfFragmentTriangles()
         << ", \"tree_builds\": " << this->BspMapper->GetNumberOfTreeBuilds()
         << ", \"index_uploads\": " << this->BspMapper->GetNumberOfIndexUploads()
         << ", \"vertex_buffer_builds\": " << this->BspMapper->GetNumberOfVertexBufferBuilds()
         << "}";
    text << ", BSP build (in the mapper) " << this->BuildMs() << " ms ("
         << this->BspMapper->GetNumberOfFragments() << " fragments)";
  }
  else if (this->Method == "multi-actor")
  {
    json << ",\n  \"multi_actor\": {\"actors\": " << this->Parts()
         << ", \"sorted_actors\": " << this->BspPass->GetNumberOfSortedActors()
         << ", \"fragments\": " << this->BspPass->GetNumberOfFragments()
         << ", \"splits\": " << this->BspPass->GetNumberOfSplits()
         << ", \"draw_calls\": " << this->BspPass->GetNumberOfDrawCalls() << "}";
    text << ", " << this->Parts() << " actors, BSP build (in the pass) " << this->BuildMs()
         << " ms (" << this->BspPass->GetNumberOfFragments() << " fragments, "
         << this->BspPass->GetNumberOfDrawCalls() << " draw calls)";
  }
}

vtkMTimeType MethodPipeline::OrderCount() const
{
  if (this->Sorter)
    return this->Sorter->GetOutput()->GetMTime();
  if (this->Method == "bsp-mapper")
    return static_cast<vtkMTimeType>(this->BspMapper->GetNumberOfOrderUpdates());
  if (this->Method == "multi-actor")
    return static_cast<vtkMTimeType>(this->BspPass->GetNumberOfOrderUpdates());
  return 0;
}

void ExitNowIfManyActors(int actors)
{
  if (actors <= kFastExitActors)
    return;
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(EXIT_SUCCESS);
}

} // namespace tool
} // namespace scenevis

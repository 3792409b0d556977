// Specification of instanced glTF loading (Tools/Instances.h) on the real 2CylinderEngine: each
// distinct mesh primitive is loaded once, every node that draws it becomes a placement, and the
// placed meshes draw the same image as LoadModel's flattened copy of the same file.
#include "../Instances.h"

#include "scenevis/testing/GTestSupport.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <set>

namespace st = scenevis::testing;
using scenevis::tool::InstancedScene;

namespace
{
vtkIdType Triangles(vtkPolyData* pd)
{
  return pd->GetNumberOfPolys(); // glTF primitives are triangles
}

/// Renders @p meshes placed by @p scene (or, without it, the one flattened polydata) with the
/// tool's colouring: direct RGBA cell scalars.
vtkSmartPointer<vtkImageData> Render(const InstancedScene* scene, vtkPolyData* flattened)
{
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(320, 240);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  std::vector<vtkSmartPointer<vtkPolyDataMapper>> mappers;
  auto mapperOf = [&](vtkPolyData* pd)
  {
    mappers.push_back(vtkSmartPointer<vtkPolyDataMapper>::New());
    mappers.back()->SetInputData(pd);
    mappers.back()->SetScalarModeToUseCellData();
    mappers.back()->SetColorModeToDirectScalars();
    return mappers.back().Get();
  };
  if (scene)
  {
    for (const auto& mesh : scene->meshes)
      mapperOf(mesh);
    for (const auto& instance : scene->instances)
    {
      vtkNew<vtkActor> actor;
      actor->SetMapper(mappers[instance.mesh]);
      actor->SetUserMatrix(instance.matrix);
      renderer->AddActor(actor);
    }
  }
  else
  {
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapperOf(flattened));
    renderer->AddActor(actor);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(300, 200, 400);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetClippingRange(10, 3000);
  return st::CaptureImage(window);
}
} // namespace

TEST(Instances, EngineMeshesLoadOnceAndPlaceEveryNode)
{
  const std::string path = st::DataFile("engine-glb");
  if (path.empty())
    GTEST_SKIP() << "engine-glb not fetched (scripts/fetch-data.sh)";
  std::string error;
  vtkSmartPointer<vtkPolyData> library = scenevis::tool::LoadGltfMeshLibrary(path, &error);
  ASSERT_TRUE(library) << error;
  vtkSmartPointer<vtkPolyData> flattened = st::LoadModel(path, &error);
  ASSERT_TRUE(flattened) << error;

  const InstancedScene scene = scenevis::tool::UnpackMeshLibrary(library);
  // The file: 29 meshes of 34 primitives, drawn by 67 nodes (115 node-primitive pairs).
  EXPECT_EQ(scene.meshes.size(), 34u);
  ASSERT_EQ(scene.instances.size(), 115u);
  std::set<vtkIdType> parts;
  vtkDataArray* partIds = flattened->GetCellData()->GetArray("PartId");
  for (vtkIdType c = 0; c < partIds->GetNumberOfTuples(); ++c)
    parts.insert(static_cast<vtkIdType>(partIds->GetTuple1(c)));
  EXPECT_EQ(parts.size(), scene.instances.size()) << "one placement per flattened part";
  vtkIdType placed = 0;
  vtkIdType loaded = 0;
  for (const auto& instance : scene.instances)
    placed += Triangles(scene.meshes[instance.mesh]);
  for (const auto& mesh : scene.meshes)
  {
    loaded += Triangles(mesh);
    EXPECT_EQ(mesh->GetFieldData()->GetNumberOfArrays(), 0) << "placements stay in the library";
  }
  EXPECT_EQ(placed, flattened->GetNumberOfPolys());
  EXPECT_LT(loaded, placed) << "shared meshes are loaded once (75,730 triangles for 121,496 drawn)";

  // The same picture: at most a few edge pixels differ (model-space float coordinates times the
  // matrix on the GPU against world-space float coordinates).
  vtkSmartPointer<vtkImageData> instanced = Render(&scene, nullptr);
  vtkSmartPointer<vtkImageData> reference = Render(nullptr, flattened);
  const st::ImageDifference difference = st::CompareImages(instanced, reference);
  st::ImageThresholds thresholds;
  thresholds.maxCoveredBadFraction = 0.0005;
  std::string why;
  EXPECT_TRUE(st::WithinThresholds(difference, thresholds, &why)) << why << difference.Summary();
  EXPECT_GT(st::CoveredFraction(instanced), 0.2);
}

TEST(Instances, ALibraryWithoutPlacementsIsAnError)
{
  vtkNew<vtkPolyData> empty;
  EXPECT_THROW(scenevis::tool::UnpackMeshLibrary(empty), std::runtime_error);
}

// Specification of instanced glTF loading (Tools/Instances.h) on the real 2CylinderEngine and on a
// small file with repeated nodes (repeated.gltf, written by Tools/CMakeLists.txt): each distinct
// mesh primitive is loaded once, every node that draws it becomes a placement, the placed meshes
// draw the same image as LoadModel's flattened copy of the same file, and flattened again they
// are that copy cell for cell (placement i is its PartId i), so the BSP orders both alike.
#include "../Instances.h"
#include "vtkBSPSortFilter.h"
#include "vtkInstancedActor.h"
#include "vtkOcclusionCuller.h"

#include "scenevis/testing/GTestSupport.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCullerCollection.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

namespace st = scenevis::testing;
using scenevis::tool::InstancedScene;

namespace
{
vtkIdType Triangles(vtkPolyData* pd)
{
  return pd->GetNumberOfPolys(); // glTF primitives are triangles
}

/// How Render draws an instanced scene: one vtkActor per placement, or one vtkInstancedActor
/// per mesh (the tool's default), alone or under vtkOcclusionCuller.
enum class Draw
{
  Actors,
  InstancedProps,
  InstancedPropsOccluded
};

/// Renders @p meshes placed by @p scene (or, without it, the one flattened polydata) with the
/// tool's colouring: direct RGBA cell scalars.
vtkSmartPointer<vtkImageData> Render(const InstancedScene* scene, vtkPolyData* flattened,
  const double eye[3] = nullptr, double farClip = 3000.0, Draw draw = Draw::Actors)
{
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(320, 240);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  if (draw == Draw::InstancedPropsOccluded)
  {
    renderer->GetCullers()->RemoveAllItems();
    renderer->AddCuller(vtkSmartPointer<vtkOcclusionCuller>::New());
  }
  std::vector<vtkSmartPointer<vtkPolyDataMapper>> mappers;
  auto mapperOf = [&](vtkPolyData* pd)
  {
    mappers.push_back(vtkSmartPointer<vtkPolyDataMapper>::New());
    mappers.back()->SetInputData(pd);
    mappers.back()->SetScalarModeToUseCellData();
    mappers.back()->SetColorModeToDirectScalars();
    return mappers.back().Get();
  };
  if (scene && draw != Draw::Actors)
  {
    std::vector<vtkSmartPointer<vtkInstancedActor>> actors;
    for (const auto& mesh : scene->meshes)
    {
      actors.push_back(vtkSmartPointer<vtkInstancedActor>::New());
      actors.back()->SetMapper(mapperOf(mesh));
      renderer->AddActor(actors.back());
    }
    for (const auto& instance : scene->instances)
      actors[instance.mesh]->AddPlacement(instance.matrix.data());
  }
  else if (scene)
  {
    for (const auto& mesh : scene->meshes)
      mapperOf(mesh);
    for (const auto& instance : scene->instances)
    {
      vtkNew<vtkActor> actor;
      actor->SetMapper(mappers[instance.mesh]);
      vtkNew<vtkMatrix4x4> matrix;
      matrix->DeepCopy(instance.matrix.data());
      actor->SetUserMatrix(matrix);
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
  const double engineEye[3] = { 300, 200, 400 };
  camera->SetPosition(eye ? eye : engineEye);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetClippingRange(farClip / 300.0, farClip);
  return st::CaptureImage(window);
}
/// The instanced scene of a glTF file (fails the test when it cannot be read).
InstancedScene LoadInstances(const std::string& path)
{
  std::string error;
  vtkSmartPointer<vtkPolyData> library = scenevis::tool::LoadGltfMeshLibrary(path, &error);
  if (!library)
    throw std::runtime_error(error);
  return scenevis::tool::UnpackMeshLibrary(library);
}

/// Cell for cell the same polygons: count, PartId, and every point within @p tolerance.
void ExpectSameCells(vtkPolyData* expected, vtkPolyData* actual, double tolerance)
{
  ASSERT_EQ(actual->GetNumberOfCells(), expected->GetNumberOfCells());
  vtkDataArray* expectedParts = expected->GetCellData()->GetArray("PartId");
  vtkDataArray* actualParts = actual->GetCellData()->GetArray("PartId");
  ASSERT_TRUE(expectedParts && actualParts);
  vtkIdType wrongParts = 0;
  vtkIdType wrongPoints = 0;
  vtkNew<vtkIdList> a;
  vtkNew<vtkIdList> b;
  for (vtkIdType c = 0; c < expected->GetNumberOfCells(); ++c)
  {
    wrongParts += expectedParts->GetTuple1(c) == actualParts->GetTuple1(c) ? 0 : 1;
    expected->GetCellPoints(c, a);
    actual->GetCellPoints(c, b);
    if (a->GetNumberOfIds() != b->GetNumberOfIds())
    {
      ++wrongPoints;
      continue;
    }
    for (vtkIdType k = 0; k < a->GetNumberOfIds(); ++k)
    {
      double p[3];
      double q[3];
      expected->GetPoint(a->GetId(k), p);
      actual->GetPoint(b->GetId(k), q);
      if (std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) > tolerance)
      {
        ++wrongPoints;
        break;
      }
    }
  }
  EXPECT_EQ(wrongParts, 0) << "cells whose PartId is not their placement";
  EXPECT_EQ(wrongPoints, 0) << "cells whose points differ";
}

/// The BSP order of @p pd for an eye: the input cell of every output fragment.
std::vector<vtkIdType> BspOrder(vtkPolyData* pd, const double eye[3])
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(eye);
  camera->SetFocalPoint(0, 0, 0);
  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputData(pd);
  sorter->SetCamera(camera);
  sorter->Update();
  vtkDataArray* original = sorter->GetOutput()->GetCellData()->GetArray("OriginalCellId");
  std::vector<vtkIdType> order;
  for (vtkIdType c = 0; original && c < original->GetNumberOfTuples(); ++c)
    order.push_back(static_cast<vtkIdType>(original->GetTuple1(c)));
  return order;
}

std::string ReadText(const std::string& path)
{
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// repeated.gltf with @p from replaced by @p to, as a file of its own; "" when @p from is absent.
std::string RepeatedVariant(const std::string& name, const std::string& from, const std::string& to)
{
  std::string text = ReadText(SCENEVIS_REPEATED_GLTF);
  const auto at = text.find(from);
  if (at == std::string::npos)
    return std::string();
  text.replace(at, from.size(), to);
  const std::string path = std::string(SCENEVIS_REPEATED_GLTF) + "." + name + ".gltf";
  std::ofstream(path) << text;
  return path;
}
} // namespace

TEST(Instances, RepeatedNodesLoadOnceAndFlattenToTheImport)
{
  const InstancedScene scene = LoadInstances(SCENEVIS_REPEATED_GLTF);
  EXPECT_EQ(scene.meshes.size(), 2u) << "a cube and a tetrahedron";
  ASSERT_EQ(scene.instances.size(), 6u) << "the cube 4 times, the tetrahedron twice";
  std::string error;
  vtkSmartPointer<vtkPolyData> imported = st::LoadModel(SCENEVIS_REPEATED_GLTF, &error);
  ASSERT_TRUE(imported) << error;
  vtkSmartPointer<vtkPolyData> flattened = scenevis::tool::FlattenInstances(scene);
  EXPECT_EQ(flattened->GetNumberOfCells(), 4 * 12 + 2 * 4);
  ExpectSameCells(imported, flattened, 1e-6);

  const double eye[3] = { 4, 6, 12 };
  vtkSmartPointer<vtkImageData> instanced = Render(&scene, nullptr, eye, 100.0);
  vtkSmartPointer<vtkImageData> reference = Render(nullptr, imported, eye, 100.0);
  const st::ImageDifference difference = st::CompareImages(instanced, reference);
  st::ImageThresholds thresholds;
  thresholds.maxCoveredBadFraction = 0.0005;
  std::string why;
  EXPECT_TRUE(st::WithinThresholds(difference, thresholds, &why)) << why << difference.Summary();
  EXPECT_GT(st::CoveredFraction(instanced), 0.05);
  for (const Draw draw : { Draw::InstancedProps, Draw::InstancedPropsOccluded })
  {
    EXPECT_TRUE(st::ImagesIdentical(Render(&scene, nullptr, eye, 100.0, draw), instanced, &why))
      << "vtkInstancedActor per mesh: " << why;
  }

  // sort --instances: the BSP over the flattened placements is the BSP over the flattened file.
  const std::vector<vtkIdType> order = BspOrder(flattened, eye);
  EXPECT_EQ(order.size(), BspOrder(imported, eye).size());
  EXPECT_EQ(order, BspOrder(imported, eye));
}

TEST(Instances, EngineFlattensToTheImportAndSortsAlike)
{
  const std::string path = st::DataFile("engine-glb");
  if (path.empty())
    GTEST_SKIP() << "engine-glb not fetched (scripts/fetch-data.sh)";
  const InstancedScene scene = LoadInstances(path);
  std::string error;
  vtkSmartPointer<vtkPolyData> imported = st::LoadModel(path, &error);
  ASSERT_TRUE(imported) << error;
  vtkSmartPointer<vtkPolyData> flattened = scenevis::tool::FlattenInstances(scene);
  ExpectSameCells(imported, flattened, 1e-4);
  const double eye[3] = { 300, 200, 400 };
  EXPECT_EQ(BspOrder(flattened, eye), BspOrder(imported, eye));
}

TEST(Instances, NodesWithSingularOrNonFiniteMatricesAreRefused)
{
  struct Case
  {
    const char* name;
    const char* from;
    const char* to;
    const char* message;
  };
  for (const Case& c : {
         Case{ "zero-scale", "\"scale\":[0.5,1.5,0.5]", "\"scale\":[0.5,0,0.5]",
           "node 3 has a singular matrix" },
         Case{ "singular-matrix", "\"matrix\":[2,0,0,0,0,2,0,0", "\"matrix\":[2,0,0,0,4,0,0,0",
           "node 4 has a singular matrix" },
         Case{ "huge-matrix", "\"matrix\":[2,", "\"matrix\":[1e308,", "node 4 has a" },
       })
  {
    const std::string path = RepeatedVariant(c.name, c.from, c.to);
    ASSERT_FALSE(path.empty()) << c.name << ": repeated.gltf changed";
    std::string error;
    EXPECT_FALSE(scenevis::tool::LoadGltfMeshLibrary(path, &error)) << c.name;
    EXPECT_NE(error.find(c.message), std::string::npos) << c.name << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << c.name << ": one line";
    std::remove(path.c_str());
  }
}

TEST(Instances, VrmlUsesBecomePlacementsOfOneMesh)
{
  std::string error;
  vtkSmartPointer<vtkPolyData> library =
    scenevis::tool::LoadVrmlMeshLibrary(SCENEVIS_REPEATED_WRL, &error);
  ASSERT_TRUE(library) << error;
  const InstancedScene scene = scenevis::tool::UnpackMeshLibrary(library);
  // The box in red (DEF BOX, used twice more), the box's faces in blue (geometry USE), and the
  // tetrahedron in red (material USE RED, inlined).
  EXPECT_EQ(scene.meshes.size(), 3u);
  ASSERT_EQ(scene.instances.size(), 5u);
  EXPECT_EQ(scene.instances[0].mesh, scene.instances[1].mesh);
  EXPECT_EQ(scene.instances[0].mesh, scene.instances[2].mesh);
  EXPECT_NE(scene.instances[0].mesh, scene.instances[3].mesh) << "another colour";
  vtkSmartPointer<vtkPolyData> imported = st::LoadModel(SCENEVIS_REPEATED_WRL, &error);
  ASSERT_TRUE(imported) << error;
  vtkSmartPointer<vtkPolyData> flattened = scenevis::tool::FlattenInstances(scene);
  ExpectSameCells(imported, flattened, 1e-6);

  const double eye[3] = { 3, 5, 12 };
  vtkSmartPointer<vtkImageData> instanced = Render(&scene, nullptr, eye, 100.0);
  vtkSmartPointer<vtkImageData> reference = Render(nullptr, imported, eye, 100.0);
  const st::ImageDifference difference = st::CompareImages(instanced, reference);
  st::ImageThresholds thresholds;
  thresholds.maxCoveredBadFraction = 0.0005;
  std::string why;
  EXPECT_TRUE(st::WithinThresholds(difference, thresholds, &why)) << why << difference.Summary();
  for (const Draw draw : { Draw::InstancedProps, Draw::InstancedPropsOccluded })
  {
    EXPECT_TRUE(st::ImagesIdentical(Render(&scene, nullptr, eye, 100.0, draw), instanced, &why))
      << "vtkInstancedActor per mesh: " << why;
  }
  EXPECT_GT(st::CoveredFraction(instanced), 0.05);
}

TEST(Instances, VrmlUsesAreCheckedBeforeImport)
{
  using scenevis::tool::CheckVrmlUses;
  EXPECT_EQ(CheckVrmlUses(ReadText(SCENEVIS_REPEATED_WRL)), "");
  EXPECT_EQ(CheckVrmlUses("DEF A Shape { } # USE B\nShape { geometry USE A } "
                          "WorldInfo { info \"USE C\" }"),
    "")
    << "comments and strings are not USEs";
  EXPECT_EQ(CheckVrmlUses("Shape {}\nTransform { children [ USE NOSUCH ] }"),
    "USE NOSUCH (line 2) names no DEF before it");
  EXPECT_EQ(CheckVrmlUses("Transform { children [ USE LATER ] }\nDEF LATER Shape { }"),
    "USE LATER (line 1) names no DEF before it");
  EXPECT_EQ(CheckVrmlUses("DEF A Transform {\n children [\n Shape { }\n USE A ] }"),
    "USE A (line 4) is inside DEF A: a node cannot contain itself");
  EXPECT_EQ(CheckVrmlUses("DEF A Group { children [ DEF B Group { children [ USE A ] } ] }"),
    "USE A (line 1) is inside DEF A: a node cannot contain itself");

  // Through the loader: one line naming the file and the USE.
  const std::string path = std::string(SCENEVIS_REPEATED_WRL) + ".undefined.wrl";
  std::ofstream(path) << ReadText(SCENEVIS_REPEATED_WRL) << "Transform { children [ USE BOXX ] }\n";
  std::string error;
  EXPECT_FALSE(scenevis::tool::LoadVrmlMeshLibrary(path, &error));
  EXPECT_NE(error.find("USE BOXX (line"), std::string::npos) << error;
  std::remove(path.c_str());
}

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

  // One vtkInstancedActor per mesh draws every placement as its own actor would: pixel for
  // pixel, with no culler and under vtkOcclusionCuller (which culls placements one by one).
  for (const Draw draw : { Draw::InstancedProps, Draw::InstancedPropsOccluded })
  {
    vtkSmartPointer<vtkImageData> props = Render(&scene, nullptr, nullptr, 3000.0, draw);
    EXPECT_TRUE(st::ImagesIdentical(props, instanced, &why)) << why;
  }
}

TEST(Instances, ALibraryWithoutPlacementsIsAnError)
{
  vtkNew<vtkPolyData> empty;
  EXPECT_THROW(scenevis::tool::UnpackMeshLibrary(empty), std::runtime_error);
}

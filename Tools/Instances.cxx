#include "Instances.h"

#include <vtkAppendPolyData.h>
#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkGLTFDocumentLoader.h>
#include <vtkIdTypeArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include "SplitParts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace scenevis
{
namespace tool
{
namespace
{

using Loader = vtkGLTFDocumentLoader;

/// The first error VTK reports while the loader works.
void KeepFirstError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* message = static_cast<std::string*>(clientData);
  if (message->empty() && callData)
    *message = static_cast<const char*>(callData);
}

/// RGBA of a primitive as LoadModel's flattened import colours it (the importer's diffuse colour:
/// the material's base colour factor; opacity 1).
void PrimitiveColour(
  const Loader::Model& model, const Loader::Primitive& primitive, unsigned char rgba[4])
{
  double rgb[3] = { 1.0, 1.0, 1.0 };
  if (primitive.Material >= 0 && primitive.Material < static_cast<int>(model.Materials.size()))
  {
    const auto& factor = model.Materials[primitive.Material].PbrMetallicRoughness.BaseColorFactor;
    for (std::size_t c = 0; c < 3 && c < factor.size(); ++c)
      rgb[c] = factor[c];
  }
  for (int c = 0; c < 3; ++c)
    rgba[c] = static_cast<unsigned char>(std::lround(255.0 * std::clamp(rgb[c], 0.0, 1.0)));
  rgba[3] = 255;
}

/// @p geometry with only a MeshId and a Colors cell array (as the flattened import keeps).
vtkSmartPointer<vtkPolyData> TaggedMesh(
  vtkPolyData* geometry, vtkIdType meshId, const unsigned char rgba[4])
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(geometry);
  mesh->GetCellData()->Initialize();
  const vtkIdType cells = mesh->GetNumberOfCells();
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("MeshId");
  ids->SetNumberOfTuples(cells);
  ids->FillValue(meshId);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(cells);
  for (int c = 0; c < 4; ++c)
    colors->FillComponent(c, rgba[c]);
  mesh->GetCellData()->AddArray(ids);
  mesh->GetCellData()->SetScalars(colors);
  return mesh;
}

} // namespace

vtkSmartPointer<vtkPolyData> LoadGltfMeshLibrary(const std::string& path, std::string* error)
{
  std::string firstError;
  auto fail = [&](const std::string& why) -> vtkSmartPointer<vtkPolyData>
  {
    if (error)
      *error = "cannot read '" + path + "': " + (firstError.empty() ? why : firstError);
    return nullptr;
  };
  vtkNew<Loader> loader;
  vtkNew<vtkCallbackCommand> errors;
  errors->SetCallback(KeepFirstError);
  errors->SetClientData(&firstError);
  loader->AddObserver(vtkCommand::ErrorEvent, errors);
  std::vector<char> glb;
  const bool binary = path.size() > 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  if ((binary && !loader->LoadFileBuffer(path, glb)) || !loader->LoadModelMetaDataFromFile(path) ||
    !loader->LoadModelData(glb) || !loader->BuildModelVTKGeometry())
  {
    return fail("not a readable glTF 2.0 file");
  }
  const Loader::Model& model = *loader->GetInternalModel();
  if (model.DefaultScene < 0 || model.DefaultScene >= static_cast<int>(model.Scenes.size()))
    return fail("no default scene");

  vtkNew<vtkAppendPolyData> append;
  std::map<std::pair<int, std::size_t>, vtkIdType> meshIdOf; // (mesh, primitive) -> MeshId
  vtkNew<vtkIdTypeArray> instanceMesh;
  instanceMesh->SetName("InstanceMesh");
  vtkNew<vtkDoubleArray> instanceMatrix;
  instanceMatrix->SetName("InstanceMatrix");
  instanceMatrix->SetNumberOfComponents(16);
  // Depth first from the scene's roots; a node reached twice (a malformed hierarchy) is skipped.
  std::vector<bool> visited(model.Nodes.size(), false);
  std::vector<int> stack(
    model.Scenes[model.DefaultScene].Nodes.rbegin(), model.Scenes[model.DefaultScene].Nodes.rend());
  while (!stack.empty())
  {
    const int index = stack.back();
    stack.pop_back();
    if (index < 0 || index >= static_cast<int>(model.Nodes.size()) || visited[index])
      continue;
    visited[index] = true;
    const Loader::Node& node = model.Nodes[index];
    if (node.Mesh >= 0 && node.Mesh < static_cast<int>(model.Meshes.size()))
    {
      const auto& primitives = model.Meshes[node.Mesh].Primitives;
      for (std::size_t p = 0; p < primitives.size(); ++p)
      {
        vtkPolyData* geometry = primitives[p].Geometry;
        if (!geometry || geometry->GetNumberOfPolys() == 0)
          continue;
        auto found = meshIdOf.find({ node.Mesh, p });
        if (found == meshIdOf.end())
        {
          const auto id = static_cast<vtkIdType>(meshIdOf.size());
          unsigned char rgba[4];
          PrimitiveColour(model, primitives[p], rgba);
          append->AddInputData(TaggedMesh(geometry, id, rgba));
          found = meshIdOf.emplace(std::make_pair(node.Mesh, p), id).first;
        }
        instanceMesh->InsertNextValue(found->second);
        double m[16];
        vtkMatrix4x4::Identity(m);
        if (node.GlobalTransform)
          vtkMatrix4x4::DeepCopy(m, node.GlobalTransform);
        instanceMatrix->InsertNextTuple(m);
      }
    }
    for (auto child = node.Children.rbegin(); child != node.Children.rend(); ++child)
      stack.push_back(*child);
  }
  if (meshIdOf.empty())
    return fail("no surface geometry");
  append->Update();
  auto library = vtkSmartPointer<vtkPolyData>::New();
  library->ShallowCopy(append->GetOutput());
  library->GetFieldData()->AddArray(instanceMesh);
  library->GetFieldData()->AddArray(instanceMatrix);
  return library;
}

InstancedScene UnpackMeshLibrary(vtkPolyData* library)
{
  auto* meshOf = vtkIdTypeArray::SafeDownCast(library->GetFieldData()->GetArray("InstanceMesh"));
  auto* matrixOf =
    vtkDoubleArray::SafeDownCast(library->GetFieldData()->GetArray("InstanceMatrix"));
  if (!meshOf || !matrixOf || matrixOf->GetNumberOfComponents() != 16 ||
    matrixOf->GetNumberOfTuples() != meshOf->GetNumberOfTuples() ||
    meshOf->GetNumberOfTuples() == 0)
  {
    throw std::runtime_error("the mesh library has no placements (InstanceMesh, InstanceMatrix)");
  }
  InstancedScene scene;
  scene.meshes = SplitByKeys(library, { "MeshId" });
  for (auto& mesh : scene.meshes)
  {
    if (mesh == library) // a single mesh: keep the library's cells, not its placements
    {
      mesh = vtkSmartPointer<vtkPolyData>::New();
      mesh->ShallowCopy(library);
    }
    mesh->GetFieldData()->Initialize();
  }
  for (vtkIdType i = 0; i < meshOf->GetNumberOfTuples(); ++i)
  {
    const vtkIdType mesh = meshOf->GetValue(i);
    if (mesh < 0 || mesh >= static_cast<vtkIdType>(scene.meshes.size()))
      throw std::runtime_error("placement " + std::to_string(i) + " names mesh " +
        std::to_string(mesh) + " of " + std::to_string(scene.meshes.size()));
    Instance instance;
    instance.mesh = static_cast<std::size_t>(mesh);
    instance.matrix = vtkSmartPointer<vtkMatrix4x4>::New();
    instance.matrix->DeepCopy(matrixOf->GetTuple(i));
    scene.instances.push_back(instance);
  }
  return scene;
}

void InstanceBounds(const InstancedScene& scene, const Instance& instance, double bounds[6])
{
  double box[6];
  scene.meshes[instance.mesh]->GetBounds(box);
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = VTK_DOUBLE_MAX;
    bounds[2 * a + 1] = -VTK_DOUBLE_MAX;
  }
  for (int k = 0; k < 8; ++k)
  {
    const double p[4] = { box[k & 1], box[2 + ((k >> 1) & 1)], box[4 + ((k >> 2) & 1)], 1.0 };
    double q[4];
    instance.matrix->MultiplyPoint(p, q);
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], q[a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], q[a]);
    }
  }
}

void InstancedBounds(const InstancedScene& scene, double bounds[6])
{
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = VTK_DOUBLE_MAX;
    bounds[2 * a + 1] = -VTK_DOUBLE_MAX;
  }
  for (const Instance& instance : scene.instances)
  {
    // Every point through the matrix (not the box's corners, which a rotation widens): the
    // same bounds, hence the same default camera, as the flattened scene.
    vtkPolyData* mesh = scene.meshes[instance.mesh];
    const double(*m)[4] = instance.matrix->Element;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      for (int a = 0; a < 3; ++a)
      {
        const double q = m[a][0] * p[0] + m[a][1] * p[1] + m[a][2] * p[2] + m[a][3];
        bounds[2 * a] = std::min(bounds[2 * a], q);
        bounds[2 * a + 1] = std::max(bounds[2 * a + 1], q);
      }
    }
  }
}

} // namespace tool
} // namespace scenevis

#include "Instances.h"

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkAppendPolyData.h>
#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkGLTFDocumentLoader.h>
#include <vtkIdTypeArray.h>
#include <vtkMapper.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVRMLImporter.h>

#include "SplitParts.h"
#include "vtkSceneVisModelReader.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
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

/// Why a placement's model-to-world matrix cannot place a mesh ("" when it can): a NaN or
/// infinite element, a scale that overflows, or a singular matrix (normals and bounds need its
/// inverse).
std::string BadPlacement(const double m[16])
{
  if (!std::all_of(m, m + 16, [](double v) { return std::isfinite(v); }))
    return "has a NaN or infinite matrix";
  const double determinant = vtkMatrix4x4::Determinant(m);
  if (!std::isfinite(determinant))
    return "has a matrix whose scale overflows";
  if (!(std::abs(determinant) > 0.0))
    return "has a singular matrix (a zero scale?)";
  return std::string();
}

/// "node 3 'Wheel'" for errors.
std::string NodeName(const Loader::Node& node, int index)
{
  return "node " + std::to_string(index) + (node.Name.empty() ? "" : " '" + node.Name + "'");
}

/// Removes the file it names when it goes.
struct TemporaryFile
{
  TemporaryFile() = default;
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile()
  {
    if (!this->Path.empty())
      std::remove(this->Path.c_str());
  }
  std::string Path;
};

/// @p text as a new file in the temporary directory; false when it cannot be written.
bool WriteTemporary(const std::string& text, TemporaryFile& file)
{
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/scenevis-XXXXXX.wrl";
  const int fd = ::mkstemps(&pattern[0], 4);
  if (fd < 0)
    return false;
  file.Path = pattern;
  const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  return written;
}

/// The extension of @p path in lower case, without the dot ("" without one).
std::string LowerExtension(const std::string& path)
{
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? std::string() : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool IsVrmlNameChar(char c)
{
  return !std::isspace(static_cast<unsigned char>(c)) && c != '{' && c != '}' && c != '[' &&
    c != ']' && c != ',' && c != '#' && c != '"';
}

} // namespace

std::string CheckVrmlUses(const std::string& text)
{
  struct Open
  {
    std::string name;
    int depth;
  };
  std::vector<Open> open;        // DEF'd nodes whose braces are not closed yet
  std::set<std::string> defined; // DEF'd nodes whose braces are closed
  std::string pendingDef;        // DEF NAME read, its node's '{' not yet
  int depth = 0;
  int line = 1;
  auto readWord = [&](std::size_t& i)
  {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
      line += text[i++] == '\n' ? 1 : 0;
    const std::size_t start = i;
    while (i < text.size() && IsVrmlNameChar(text[i]))
      ++i;
    return text.substr(start, i - start);
  };
  for (std::size_t i = 0; i < text.size();)
  {
    const char c = text[i];
    if (c == '\n')
    {
      ++line;
      ++i;
    }
    else if (c == '#') // a comment, to the end of the line
    {
      while (i < text.size() && text[i] != '\n')
        ++i;
    }
    else if (c == '"') // a string: skipped, escapes included
    {
      for (++i; i < text.size() && text[i] != '"'; ++i)
      {
        line += text[i] == '\n' ? 1 : 0;
        if (text[i] == '\\')
          ++i;
      }
      ++i;
    }
    else if (c == '{' || c == '[')
    {
      ++depth;
      if (!pendingDef.empty() && c == '{')
      {
        open.push_back({ pendingDef, depth });
        pendingDef.clear();
      }
      ++i;
    }
    else if (c == '}' || c == ']')
    {
      if (!open.empty() && open.back().depth == depth)
      {
        defined.insert(open.back().name);
        open.pop_back();
      }
      --depth;
      ++i;
    }
    else if (IsVrmlNameChar(c))
    {
      const std::string word = readWord(i);
      if (word == "DEF")
        pendingDef = readWord(i);
      else if (word == "USE")
      {
        const int at = line;
        const std::string name = readWord(i);
        const bool inside = std::any_of(
          open.begin(), open.end(), [&](const Open& node) { return node.name == name; });
        if (inside)
          return "USE " + name + " (line " + std::to_string(at) + ") is inside DEF " + name +
            ": a node cannot contain itself";
        if (!defined.count(name))
          return "USE " + name + " (line " + std::to_string(at) + ") names no DEF before it";
      }
    }
    else
    {
      ++i;
    }
  }
  return std::string();
}

vtkSmartPointer<vtkPolyData> LoadVrmlMeshLibrary(const std::string& path, std::string* error)
{
  std::string firstError;
  auto fail = [&](const std::string& why) -> vtkSmartPointer<vtkPolyData>
  {
    if (error)
      *error = "cannot read '" + path + "': " + (firstError.empty() ? why : firstError);
    return nullptr;
  };
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return fail("cannot open the file");
  std::ostringstream read;
  read << in.rdbuf();
  const std::string text = read.str();
  const std::string badUse = CheckVrmlUses(text);
  if (!badUse.empty())
    return fail(badUse);
  // VTK 9.1 ignores `material USE NAME`; the flattened import reads the same rewritten text.
  const std::string fixed = vtkSceneVisModelReader::InlineVrmlMaterialUses(text);
  TemporaryFile temporary;
  if (fixed != text && !WriteTemporary(fixed, temporary))
    return fail("cannot write a temporary copy");

  vtkNew<vtkVRMLImporter> importer;
  importer->SetFileName(temporary.Path.empty() ? path.c_str() : temporary.Path.c_str());
  vtkNew<vtkRenderWindow> window; // never rendered: the importer only needs its renderer
  importer->SetRenderWindow(window);
  vtkNew<vtkCallbackCommand> errors;
  errors->SetCallback(KeepFirstError);
  errors->SetClientData(&firstError);
  importer->AddObserver(vtkCommand::ErrorEvent, errors);
  importer->Read();
  vtkRenderer* renderer = importer->GetRenderer();
  if (!firstError.empty() || !renderer)
    return fail("not a readable VRML 2.0 file");

  // The importer gives a USE of a DEF'd Shape or geometry an actor of its own that shares the
  // DEF's mapper: one mesh per (mapper input, colour). The actors are visited as the flattened
  // import (vtkSceneVisModelReader) visits them, so placement i is its PartId i.
  vtkNew<vtkAppendPolyData> append;
  std::map<std::pair<vtkDataObject*, unsigned long>, vtkIdType> meshIdOf;
  vtkNew<vtkIdTypeArray> instanceMesh;
  instanceMesh->SetName("InstanceMesh");
  vtkNew<vtkDoubleArray> instanceMatrix;
  instanceMatrix->SetName("InstanceMatrix");
  instanceMatrix->SetNumberOfComponents(16);
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  vtkIdType shape = 0;
  while (vtkActor* actor = actors->GetNextActor(it))
  {
    vtkMapper* mapper = actor->GetMapper();
    if (!mapper)
      continue;
    if (vtkAlgorithm* source = mapper->GetInputAlgorithm())
      source->Update();
    auto* input = vtkPolyData::SafeDownCast(mapper->GetInputDataObject(0, 0));
    if (!input || input->GetNumberOfCells() == 0)
      continue;
    double rgb[3];
    actor->GetProperty()->GetDiffuseColor(rgb);
    unsigned char rgba[4];
    for (int c = 0; c < 3; ++c)
      rgba[c] = static_cast<unsigned char>(std::lround(255.0 * std::clamp(rgb[c], 0.0, 1.0)));
    rgba[3] = static_cast<unsigned char>(
      std::lround(255.0 * std::clamp(actor->GetProperty()->GetOpacity(), 0.0, 1.0)));
    const unsigned long colour = (static_cast<unsigned long>(rgba[0]) << 24) |
      (static_cast<unsigned long>(rgba[1]) << 16) | (static_cast<unsigned long>(rgba[2]) << 8) |
      rgba[3];
    auto found = meshIdOf.find({ input, colour });
    if (found == meshIdOf.end())
    {
      const auto id = static_cast<vtkIdType>(meshIdOf.size());
      append->AddInputData(TaggedMesh(input, id, rgba));
      found = meshIdOf.emplace(std::make_pair(input, colour), id).first;
    }
    double m[16];
    vtkMatrix4x4::DeepCopy(m, actor->GetMatrix());
    const std::string bad = BadPlacement(m);
    if (!bad.empty())
      return fail("shape " + std::to_string(shape) + " " + bad);
    instanceMesh->InsertNextValue(found->second);
    instanceMatrix->InsertNextTuple(m);
    ++shape;
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

bool IsInstanceable(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  return ext == "glb" || ext == "gltf" || ext == "wrl";
}

vtkSmartPointer<vtkPolyData> LoadMeshLibrary(const std::string& path, std::string* error)
{
  return LowerExtension(path) == "wrl" ? LoadVrmlMeshLibrary(path, error)
                                       : LoadGltfMeshLibrary(path, error);
}

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
  // Depth first from the scene's roots in vtkGLTFImporter's order (a stack: the last root and
  // the last child first), so placement i is the flattened import's PartId i. A node reached
  // twice (a malformed hierarchy) is skipped.
  std::vector<bool> visited(model.Nodes.size(), false);
  std::vector<int> stack(
    model.Scenes[model.DefaultScene].Nodes.begin(), model.Scenes[model.DefaultScene].Nodes.end());
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
        // Skipped as the flattened import skips it (a part of no cells), so that placement i
        // stays its PartId i; a primitive of lines or points is placed like a surface.
        vtkPolyData* geometry = primitives[p].Geometry;
        if (!geometry || geometry->GetNumberOfCells() == 0)
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
        const std::string bad = BadPlacement(m);
        if (!bad.empty())
          return fail(NodeName(node, index) + " " + bad);
        instanceMatrix->InsertNextTuple(m);
      }
    }
    stack.insert(stack.end(), node.Children.begin(), node.Children.end());
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
  scene.instances.reserve(static_cast<std::size_t>(meshOf->GetNumberOfTuples()));
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
    matrixOf->GetTypedTuple(i, instance.matrix.data());
    scene.instances.push_back(instance);
  }
  return scene;
}

vtkSmartPointer<vtkPolyData> FlattenInstances(
  const InstancedScene& scene, const std::string& partArray)
{
  vtkNew<vtkAppendPolyData> append;
  for (std::size_t i = 0; i < scene.instances.size(); ++i)
  {
    const Instance& instance = scene.instances[i];
    // The same filter and matrix as the flattened import (vtkSceneVisModelReader), so the same
    // float coordinates.
    vtkNew<vtkTransform> transform;
    transform->SetMatrix(instance.matrix.data());
    vtkNew<vtkTransformPolyDataFilter> moved;
    moved->SetTransform(transform);
    moved->SetInputData(scene.meshes[instance.mesh]);
    moved->Update();
    auto piece = vtkSmartPointer<vtkPolyData>::New();
    piece->ShallowCopy(moved->GetOutput());
    vtkNew<vtkIdTypeArray> part;
    part->SetName(partArray.c_str());
    part->SetNumberOfTuples(piece->GetNumberOfCells());
    part->FillValue(static_cast<vtkIdType>(i));
    piece->GetCellData()->RemoveArray(partArray.c_str());
    piece->GetCellData()->AddArray(part);
    append->AddInputData(piece);
  }
  if (scene.instances.empty())
    return vtkSmartPointer<vtkPolyData>::New();
  append->Update();
  auto flattened = vtkSmartPointer<vtkPolyData>::New();
  flattened->ShallowCopy(append->GetOutput());
  return flattened;
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
    vtkMatrix4x4::MultiplyPoint(instance.matrix.data(), p, q);
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
    const double* m = instance.matrix.data();
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      for (int a = 0; a < 3; ++a)
      {
        const double q = m[4 * a] * p[0] + m[4 * a + 1] * p[1] + m[4 * a + 2] * p[2] + m[4 * a + 3];
        bounds[2 * a] = std::min(bounds[2 * a], q);
        bounds[2 * a + 1] = std::max(bounds[2 * a + 1], q);
      }
    }
  }
}

} // namespace tool
} // namespace scenevis

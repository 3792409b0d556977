#include "scenevis/testing/Models.h"

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkAlgorithm.h>
#include <vtkAppendPolyData.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkGLTFImporter.h>
#include <vtkIdTypeArray.h>
#include <vtkImporter.h>
#include <vtkMapper.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSTLReader.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVRMLImporter.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace scenevis
{
namespace testing
{
namespace
{
/// Keeps the first error a reader reports (instead of letting it reach the output window).
class FirstError : public vtkCommand
{
public:
  static FirstError* New() { return new FirstError; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Message.empty() && data)
    {
      this->Message = static_cast<const char*>(data);
      this->Message.erase(this->Message.find_last_not_of("\n ") + 1);
    }
  }
  std::string Message;
};

std::string Extension(const std::string& path)
{
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool IsNameChar(char c)
{
  return !std::isspace(static_cast<unsigned char>(c)) && c != '{' && c != '}' && c != '[' &&
    c != ']' && c != ',';
}

/// Index of the first character at or after @p i that is not white space.
std::size_t SkipSpace(const std::string& text, std::size_t i)
{
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
  {
    ++i;
  }
  return i;
}

/// Reads a VRML name starting at @p i (after white space); returns its end, or npos.
std::size_t ReadName(const std::string& text, std::size_t i, std::string& name)
{
  i = SkipSpace(text, i);
  const std::size_t start = i;
  while (i < text.size() && IsNameChar(text[i]))
  {
    ++i;
  }
  name = text.substr(start, i - start);
  return name.empty() ? std::string::npos : i;
}

/// The text as a uniquely named file in the temporary directory ("" on failure).
std::string WriteTemporary(const std::string& text, const std::string& suffix)
{
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/scenevis-XXXXXX" + suffix;
  const int fd = ::mkstemps(&pattern[0], static_cast<int>(suffix.size()));
  if (fd < 0)
  {
    return std::string();
  }
  const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  if (!written)
  {
    std::remove(pattern.c_str());
    return std::string();
  }
  return pattern;
}

/**
 * Imports a scene file (glTF or VRML) and merges its actors into one polydata with "PartId" and
 * "Colors" cell arrays; see LoadModel().
 */
vtkSmartPointer<vtkPolyData> ImportScene(
  vtkImporter* importer, vtkCommand* errors, std::string& why)
{
  vtkNew<vtkRenderWindow> window; // never rendered: the importer only needs its renderer
  importer->SetRenderWindow(window);
  importer->AddObserver(vtkCommand::ErrorEvent, errors);
  importer->Read();
  vtkRenderer* renderer = importer->GetRenderer();
  if (!renderer)
  {
    why = "the importer created no renderer";
    return nullptr;
  }
  vtkNew<vtkAppendPolyData> append;
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  vtkIdType part = 0;
  while (vtkActor* actor = actors->GetNextActor(it))
  {
    vtkMapper* mapper = actor->GetMapper();
    if (!mapper)
    {
      continue;
    }
    if (vtkAlgorithm* source = mapper->GetInputAlgorithm())
    {
      source->Update();
    }
    auto* input = vtkPolyData::SafeDownCast(mapper->GetInputDataObject(0, 0));
    if (!input || input->GetNumberOfCells() == 0)
    {
      continue;
    }
    vtkNew<vtkTransform> transform;
    transform->SetMatrix(actor->GetMatrix());
    vtkNew<vtkTransformPolyDataFilter> moved;
    moved->SetTransform(transform);
    moved->SetInputData(input);
    moved->Update();
    auto piece = vtkSmartPointer<vtkPolyData>::New();
    piece->ShallowCopy(moved->GetOutput());
    // Only the part and colour arrays are kept per cell: parts rarely share other cell arrays,
    // and vtkAppendPolyData would drop them anyway.
    piece->GetCellData()->Initialize();
    const vtkIdType cells = piece->GetNumberOfCells();
    vtkNew<vtkIdTypeArray> partIds;
    partIds->SetName("PartId");
    partIds->SetNumberOfTuples(cells);
    partIds->FillValue(part);
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("Colors");
    colors->SetNumberOfComponents(4);
    colors->SetNumberOfTuples(cells);
    double rgb[3];
    actor->GetProperty()->GetDiffuseColor(rgb);
    const double opacity = actor->GetProperty()->GetOpacity();
    unsigned char rgba[4];
    for (int c = 0; c < 3; ++c)
    {
      rgba[c] = static_cast<unsigned char>(std::lround(255.0 * std::clamp(rgb[c], 0.0, 1.0)));
    }
    rgba[3] = static_cast<unsigned char>(std::lround(255.0 * std::clamp(opacity, 0.0, 1.0)));
    for (int c = 0; c < 4; ++c)
    {
      colors->FillComponent(c, rgba[c]);
    }
    piece->GetCellData()->AddArray(partIds);
    piece->GetCellData()->SetScalars(colors);
    append->AddInputData(piece);
    ++part;
  }
  if (part == 0)
  {
    why = "no surface geometry";
    return nullptr;
  }
  append->Update();
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(append->GetOutput());
  return result;
}
} // namespace

std::string InlineVrmlMaterialUses(const std::string& text)
{
  if (text.find("USE") == std::string::npos)
  {
    return text;
  }
  // Pass 1: the node text ("Material { ... }") of every `material DEF NAME Material {...}`.
  std::map<std::string, std::string> defined;
  for (std::size_t at = text.find("material"); at != std::string::npos;
       at = text.find("material", at + 1))
  {
    std::string keyword;
    std::string name;
    std::string type;
    std::size_t i = ReadName(text, at + 8, keyword);
    if (i == std::string::npos || keyword != "DEF" ||
      (i = ReadName(text, i, name)) == std::string::npos)
    {
      continue;
    }
    const std::size_t nodeStart = SkipSpace(text, i);
    if ((i = ReadName(text, i, type)) == std::string::npos || type != "Material")
    {
      continue;
    }
    i = SkipSpace(text, i);
    const std::size_t close = i < text.size() && text[i] == '{' ? text.find('}', i) : i;
    if (close == std::string::npos || close == i)
    {
      continue;
    }
    defined.emplace(name, text.substr(nodeStart, close + 1 - nodeStart));
  }
  // Pass 2: copy the text, replacing `material USE NAME` by `material <node text>`.
  std::string out;
  out.reserve(text.size() + text.size() / 4);
  std::size_t copied = 0;
  for (std::size_t at = text.find("material"); at != std::string::npos;
       at = text.find("material", at + 1))
  {
    std::string keyword;
    std::string name;
    std::size_t i = ReadName(text, at + 8, keyword);
    if (i == std::string::npos || keyword != "USE" ||
      (i = ReadName(text, i, name)) == std::string::npos)
    {
      continue;
    }
    const auto found = defined.find(name);
    if (found == defined.end())
    {
      continue;
    }
    out.append(text, copied, at - copied);
    out += "material ";
    out += found->second;
    copied = i;
  }
  out.append(text, copied, std::string::npos);
  return out;
}

std::string DataDirectory()
{
  if (const char* dir = std::getenv("SCENEVIS_DATA_DIR"))
  {
    return dir;
  }
  const char* home = std::getenv("HOME");
  return std::string(home ? home : ".") + "/.cache/scenevis-data";
}

std::string DataFile(const std::string& key)
{
  const std::string dir = DataDirectory();
  std::ifstream manifest(dir + "/manifest.txt");
  std::string line;
  while (std::getline(manifest, line))
  {
    if (line.rfind(key + "=", 0) == 0)
    {
      const std::string path = dir + "/" + line.substr(key.size() + 1);
      return std::ifstream(path).good() ? path : std::string();
    }
  }
  return std::string();
}

namespace
{
vtkSmartPointer<vtkPolyData> LoadModelUnguarded(const std::string& path, std::string* error);
}

vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error)
{
  std::string why;
  vtkSmartPointer<vtkPolyData> result;
  try
  {
    result = LoadModelUnguarded(path, &why);
  }
  catch (const std::exception& e)
  {
    // VTK's glTF loader lets jsoncpp's exceptions through on some malformed files.
    why = "cannot read '" + path + "': " + e.what();
  }
  if (!result && error)
  {
    // One line: reader messages can span several.
    std::replace(why.begin(), why.end(), '\n', ' ');
    *error = why;
  }
  return result;
}

namespace
{
vtkSmartPointer<vtkPolyData> LoadModelUnguarded(const std::string& path, std::string* error)
{
  auto fail = [&](const std::string& why) -> vtkSmartPointer<vtkPolyData> {
    if (error)
    {
      *error = why;
    }
    return nullptr;
  };
  if (!std::ifstream(path).good())
  {
    return fail("cannot open '" + path + "'");
  }
  const std::string ext = Extension(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  vtkSmartPointer<vtkAlgorithm> last;
  if (ext == "vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "vtk")
  {
    auto r = vtkSmartPointer<vtkPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "stl")
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "glb" || ext == "gltf" || ext == "wrl")
  {
    std::string file = path;
    std::string temporary;
    vtkSmartPointer<vtkImporter> importer;
    if (ext == "wrl")
    {
      std::ifstream in(path, std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      const std::string original = text.str();
      const std::string fixed = InlineVrmlMaterialUses(original);
      if (fixed != original)
      {
        temporary = WriteTemporary(fixed, ".wrl");
        if (temporary.empty())
        {
          return fail("cannot write a temporary copy of '" + path + "'");
        }
        file = temporary;
      }
      auto vrml = vtkSmartPointer<vtkVRMLImporter>::New();
      vrml->SetFileName(file.c_str());
      importer = vrml;
    }
    else
    {
      auto gltf = vtkSmartPointer<vtkGLTFImporter>::New();
      gltf->SetFileName(file.c_str());
      importer = gltf;
    }
    vtkNew<FirstError> errors;
    std::string why;
    auto scene = ImportScene(importer, errors, why);
    if (!temporary.empty())
    {
      std::remove(temporary.c_str());
    }
    if (!errors->Message.empty())
    {
      return fail("cannot read '" + path + "': " + errors->Message);
    }
    if (!scene)
    {
      return fail("cannot read '" + path + "': " + why);
    }
    return scene;
  }
  else
  {
    return fail("unsupported model format '." + ext + "' (vtp vtk ply stl obj glb gltf wrl)");
  }
  if (!last)
  {
    last = reader;
  }
  vtkNew<FirstError> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  last->AddObserver(vtkCommand::ErrorEvent, errors);
  last->Update();
  auto* output = vtkPolyData::SafeDownCast(last->GetOutputDataObject(0));
  if (!errors->Message.empty())
  {
    return fail("cannot read '" + path + "': " + errors->Message);
  }
  if (!output || output->GetNumberOfCells() == 0)
  {
    return fail("cannot read '" + path + "': no cells");
  }
  vtkSmartPointer<vtkPolyData> result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(output);
  return result;
}
} // namespace

} // namespace testing
} // namespace scenevis

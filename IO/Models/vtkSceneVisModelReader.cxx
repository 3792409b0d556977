#include "vtkSceneVisModelReader.h"

#include "vtkIsolatedRead.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkAlgorithm.h"
#include "vtkAppendPolyData.h"
#include "vtkAutoInit.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkErrorCode.h"
#include "vtkExecutive.h"
#include "vtkGLTFImporter.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImporter.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataReader.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVRMLImporter.h"
#include "vtkXMLPolyDataReader.h"

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
#include <unistd.h>
#include <vector>

// The importers make their render window, renderer, actors and mappers through VTK's object
// factories; without the OpenGL2 overrides vtkPolyDataMapper::New() is null and the glTF importer
// crashes. Nothing is rendered.
VTK_MODULE_INIT(vtkRenderingOpenGL2);

vtkStandardNewMacro(vtkSceneVisModelReader);

namespace
{
const char* const kExtensions[] = { "vtp", "vtk", "ply", "stl", "obj", "glb", "gltf", "wrl" };

std::string UnsupportedFormat(const std::string& ext)
{
  return "unsupported model format '." + ext + "' (vtp vtk ply stl obj glb gltf wrl)";
}

/// Keeps the first error and the first warning a reader (or its executive) reports, instead of
/// letting them reach the output window.
class FirstError : public vtkCommand
{
public:
  static FirstError* New() { return new FirstError; }
  void Execute(vtkObject* caller, unsigned long event, void* data) override
  {
    if (vtkExecutive::SafeDownCast(caller))
    {
      return; // "returned failure for request": the reader's own error or warning says why
    }
    std::string& kept = event == vtkCommand::ErrorEvent ? this->Message : this->Warning;
    if (kept.empty() && data)
    {
      kept = static_cast<const char*>(data);
      kept.erase(kept.find_last_not_of("\n ") + 1);
    }
  }
  /// Observes the errors and warnings of @p algorithm, and silences its executive's.
  void Watch(vtkAlgorithm* algorithm)
  {
    for (vtkObject* object :
      { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
    {
      object->AddObserver(vtkCommand::ErrorEvent, this);
      object->AddObserver(vtkCommand::WarningEvent, this);
    }
  }
  std::string Message;
  std::string Warning;
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
 * "Colors" cell arrays (the class comment).
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

/// Swallows the reader's error event: LoadFile() returns the message instead of printing it.
class IgnoreEvent : public vtkCommand
{
public:
  static IgnoreEvent* New() { return new IgnoreEvent; }
  void Execute(vtkObject*, unsigned long, void*) override {}
};
} // namespace

vtkSmartPointer<vtkPolyData> vtkSceneVisModelReader::LoadFile(
  const std::string& path, std::string* error, bool removeNonFiniteCells)
{
  vtkNew<vtkSceneVisModelReader> reader;
  vtkNew<IgnoreEvent> quiet;
  reader->AddObserver(vtkCommand::ErrorEvent, quiet);
  reader->SetFileName(path.c_str());
  reader->SetRemoveNonFiniteCells(removeNonFiniteCells);
  reader->Update();
  if (*reader->GetErrorMessage())
  {
    if (error)
    {
      *error = reader->GetErrorMessage();
    }
    return nullptr;
  }
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(reader->GetOutput());
  return result;
}

std::string vtkSceneVisModelReader::InlineVrmlMaterialUses(const std::string& text)
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

namespace
{
/// A reader of type @p Reader for @p path.
template <typename Reader>
vtkSmartPointer<vtkAlgorithm> NewFileReader(const std::string& path)
{
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(path.c_str());
  return reader;
}

/// Removes the file it names when it goes (also when an importer throws).
struct TemporaryFile
{
  TemporaryFile() = default;
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile()
  {
    if (!this->Path.empty())
    {
      std::remove(this->Path.c_str());
    }
  }
  std::string Path;
};

/// Reads @p path with the reader its extension names; nullptr and @p error on failure.
vtkSmartPointer<vtkPolyData> ReadModel(const std::string& path, std::string* error)
{
  auto fail = [&](const std::string& why) -> vtkSmartPointer<vtkPolyData>
  {
    if (error)
    {
      *error = why;
    }
    return nullptr;
  };
  const std::string ext = Extension(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == "vtp")
  {
    reader = NewFileReader<vtkXMLPolyDataReader>(path);
  }
  else if (ext == "vtk")
  {
    reader = NewFileReader<vtkPolyDataReader>(path);
  }
  else if (ext == "ply")
  {
    reader = NewFileReader<vtkPLYReader>(path);
  }
  else if (ext == "stl")
  {
    reader = NewFileReader<vtkSTLReader>(path);
  }
  else if (ext == "obj")
  {
    reader = NewFileReader<vtkOBJReader>(path);
  }
  else if (ext == "glb" || ext == "gltf" || ext == "wrl")
  {
    std::string file = path;
    TemporaryFile temporary;
    vtkSmartPointer<vtkImporter> importer;
    if (ext == "wrl")
    {
      std::ifstream in(path, std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      const std::string original = text.str();
      const std::string fixed = vtkSceneVisModelReader::InlineVrmlMaterialUses(original);
      if (fixed != original)
      {
        temporary.Path = WriteTemporary(fixed, ".wrl");
        if (temporary.Path.empty())
        {
          return fail("cannot write a temporary copy of '" + path + "'");
        }
        file = temporary.Path;
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
    return fail(UnsupportedFormat(ext));
  }
  vtkNew<FirstError> errors;
  errors->Watch(reader);
  reader->Update();
  auto* output = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!errors->Message.empty())
  {
    return fail("cannot read '" + path + "': " + errors->Message);
  }
  if (!output || output->GetNumberOfCells() == 0)
  {
    return fail("cannot read '" + path +
      "': " + (errors->Warning.empty() ? std::string("no cells") : errors->Warning));
  }
  vtkSmartPointer<vtkPolyData> result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(output);
  return result;
}


bool IsFinite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}
} // namespace

//------------------------------------------------------------------------------
vtkSceneVisModelReader::vtkSceneVisModelReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkSceneVisModelReader::~vtkSceneVisModelReader()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
bool vtkSceneVisModelReader::CanReadFile(const char* fileName)
{
  const std::string ext = Extension(fileName ? fileName : "");
  return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

//------------------------------------------------------------------------------
std::string vtkSceneVisModelReader::DescribeBadPointId(vtkPolyData* pd)
{
  const vtkIdType points = pd->GetNumberOfPoints();
  vtkIdType cell = 0;
  for (vtkCellArray* cells : { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() })
  {
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    const vtkIdType count = cells ? cells->GetNumberOfCells() : 0;
    for (vtkIdType c = 0; c < count; ++c, ++cell)
    {
      cells->GetCellAtId(c, npts, pts);
      for (vtkIdType k = 0; k < npts; ++k)
      {
        if (pts[k] < 0 || pts[k] >= points)
        {
          return "cell " + std::to_string(cell) + " uses point " + std::to_string(pts[k]) +
            " of only " + std::to_string(points);
        }
      }
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
vtkIdType vtkSceneVisModelReader::RemoveCellsWithNonFinitePoints(vtkPolyData* pd)
{
  vtkPoints* points = pd ? pd->GetPoints() : nullptr;
  const vtkIdType count = points ? points->GetNumberOfPoints() : 0;
  std::vector<vtkIdType> bad;
  for (vtkIdType i = 0; i < count; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    if (!IsFinite(p))
    {
      bad.push_back(i);
    }
  }
  if (bad.empty())
  {
    return 0;
  }
  pd->BuildLinks();
  vtkNew<vtkIdList> cells;
  std::set<vtkIdType> removed;
  for (vtkIdType point : bad)
  {
    pd->GetPointCells(point, cells);
    for (vtkIdType k = 0; k < cells->GetNumberOfIds(); ++k)
    {
      if (removed.insert(cells->GetId(k)).second)
      {
        pd->DeleteCell(cells->GetId(k));
      }
    }
  }
  pd->RemoveDeletedCells();
  // No cell uses them now, but point bounds still would: park them on a finite point.
  double parked[3] = { 0.0, 0.0, 0.0 };
  for (vtkIdType i = 0; i < count; ++i)
  {
    points->GetPoint(i, parked);
    if (IsFinite(parked))
    {
      break;
    }
  }
  for (vtkIdType point : bad)
  {
    points->SetPoint(point, parked);
  }
  points->Modified();
  return static_cast<vtkIdType>(removed.size());
}

//------------------------------------------------------------------------------
int vtkSceneVisModelReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ErrorMessage.clear();
  this->NumberOfRemovedCells = 0;
  this->SetErrorCode(vtkErrorCode::NoError);

  const std::string path = this->FileName ? this->FileName : "";
  std::string why;
  vtkSmartPointer<vtkPolyData> model;
  if (path.empty())
  {
    why = "no FileName set";
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
  }
  else if (!std::ifstream(path).good())
  {
    why = "cannot open '" + path + "'";
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
  else if (!CanReadFile(path.c_str()))
  {
    why = "cannot read '" + path + "': " + UnsupportedFormat(Extension(path));
    this->SetErrorCode(vtkErrorCode::UnrecognizedFileTypeError);
  }
  else
  {
    auto read = [&path](std::string* error)
    {
      try
      {
        return ReadModel(path, error);
      }
      catch (const std::exception& e)
      {
        // VTK's glTF loader lets jsoncpp's exceptions through on some malformed files.
        *error = "cannot read '" + path + "': " + e.what();
        return vtkSmartPointer<vtkPolyData>();
      }
    };
    const bool isolate = this->ReadInChildProcess && Extension(path) != "vtp";
    model = isolate ? vtkIsolatedRead::Run(path, read, &why) : read(&why);
    if (model)
    {
      why = DescribeBadPointId(model);
      if (!why.empty())
      {
        why = "cannot read '" + path + "': " + why;
        model = nullptr;
      }
    }
    if (model && this->RemoveNonFiniteCells)
    {
      this->NumberOfRemovedCells = RemoveCellsWithNonFinitePoints(model);
      if (model->GetNumberOfCells() == 0)
      {
        why = "cannot read '" + path + "': every cell has a NaN/Inf point";
        model = nullptr;
      }
    }
    if (!model)
    {
      this->SetErrorCode(vtkErrorCode::FileFormatError);
    }
  }
  if (!model)
  {
    // One line: VTK's readers' messages can span several.
    std::replace(why.begin(), why.end(), '\n', ' ');
    this->ErrorMessage = why;
    output->Initialize();
    vtkErrorMacro(<< why);
    return 1;
  }
  output->ShallowCopy(model);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSceneVisModelReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "RemoveNonFiniteCells: " << this->RemoveNonFiniteCells << "\n";
  os << indent << "ReadInChildProcess: " << this->ReadInChildProcess << "\n";
  os << indent << "NumberOfRemovedCells: " << this->NumberOfRemovedCells << "\n";
  os << indent << "ErrorMessage: " << this->ErrorMessage << "\n";
}

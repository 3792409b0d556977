#include "scenevis/testing/Models.h"

#include <vtkAlgorithm.h>
#include <vtkAppendPolyData.h>
#include <vtkCommand.h>
#include <vtkCompositeDataGeometryFilter.h>
#include <vtkGLTFReader.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSTLReader.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>

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
} // namespace

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

vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error)
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
  else if (ext == "glb" || ext == "gltf")
  {
    auto r = vtkSmartPointer<vtkGLTFReader>::New();
    r->SetFileName(path.c_str());
    r->SetApplyDeformationsToGeometry(true);
    reader = r;
    auto merge = vtkSmartPointer<vtkCompositeDataGeometryFilter>::New();
    merge->SetInputConnection(r->GetOutputPort());
    last = merge;
  }
  else
  {
    return fail("unsupported model format '." + ext + "' (vtp vtk ply stl obj glb gltf)");
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

} // namespace testing
} // namespace scenevis

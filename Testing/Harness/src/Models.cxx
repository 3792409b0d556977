#include "scenevis/testing/Models.h"

#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSceneVisModelReader.h>

#include <cstdlib>
#include <fstream>

namespace scenevis
{
namespace testing
{
namespace
{
/// Swallows the reader's error event: LoadModel() returns the message instead of printing it.
class IgnoreEvent : public vtkCommand
{
public:
  static IgnoreEvent* New() { return new IgnoreEvent; }
  void Execute(vtkObject*, unsigned long, void*) override {}
};
} // namespace

std::string InlineVrmlMaterialUses(const std::string& text)
{
  return vtkSceneVisModelReader::InlineVrmlMaterialUses(text);
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

vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error)
{
  vtkNew<vtkSceneVisModelReader> reader;
  vtkNew<IgnoreEvent> quiet;
  reader->AddObserver(vtkCommand::ErrorEvent, quiet);
  reader->SetFileName(path.c_str());
  // The scenevis tool removes NaN/Inf cells itself and says how many; keep them for it.
  reader->RemoveNonFiniteCellsOff();
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

} // namespace testing
} // namespace scenevis

#include "scenevis/testing/Models.h"

#include <vtkPolyData.h>
#include <vtkSceneVisModelReader.h>

namespace scenevis
{
namespace testing
{

std::string InlineVrmlMaterialUses(const std::string& text)
{
  return vtkSceneVisModelReader::InlineVrmlMaterialUses(text);
}

vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error)
{
  return vtkSceneVisModelReader::LoadFile(path, error, false);
}

} // namespace testing
} // namespace scenevis

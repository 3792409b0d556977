/**
 * @file Models.h
 * @brief Loading third-party models for tests and benchmarks.
 *
 * The reading is vtkSceneVisModelReader and the data cache (DataDirectory(), DataFile())
 * vtkSceneVisDataCache.h, both of SceneVis::IOModels (what users link); this header brings them
 * into scenevis::testing for the tests' callers.
 */
#ifndef scenevis_testing_Models_h
#define scenevis_testing_Models_h

#include <vtkSceneVisDataCache.h>
#include <vtkSmartPointer.h>

#include <string>

class vtkPolyData;

namespace scenevis
{
namespace testing
{

using scenevis::DataDirectory;
using scenevis::DataFile;

/**
 * vtkSceneVisModelReader::LoadFile() with RemoveNonFiniteCells off (tests see the cells as the
 * scenevis tool does before it removes and counts them).
 * @return nullptr when the file cannot be read; @p error then says why in one line.
 */
vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error = nullptr);

/// vtkSceneVisModelReader::InlineVrmlMaterialUses().
std::string InlineVrmlMaterialUses(const std::string& text);

} // namespace testing
} // namespace scenevis

#endif

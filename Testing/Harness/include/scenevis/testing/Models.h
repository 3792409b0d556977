/**
 * @file Models.h
 * @brief Loading third-party models for tests, benchmarks and tools.
 *
 * The reading itself is vtkSceneVisModelReader (module SceneVis::IOModels, what users link);
 * LoadModel() and InlineVrmlMaterialUses() forward to it for the existing callers. The data cache
 * (DataDirectory(), DataFile()) is test-only and lives here.
 *
 * Real models are never committed: scripts/fetch-data.sh puts them into a cache directory
 * ($SCENEVIS_DATA_DIR, default ~/.cache/scenevis-data) and writes `manifest.txt` there, one
 * `key=relative/path` per line (e.g. `bunny-stl`, `engine-glb`). DataFile() resolves a key;
 * callers skip (never fail) when the data was not fetched.
 */
#ifndef scenevis_testing_Models_h
#define scenevis_testing_Models_h

#include <vtkSmartPointer.h>

#include <string>

class vtkPolyData;

namespace scenevis
{
namespace testing
{

/// The data cache directory ($SCENEVIS_DATA_DIR or ~/.cache/scenevis-data).
std::string DataDirectory();

/// Absolute path of the manifest entry @p key, or "" when it was not fetched.
std::string DataFile(const std::string& key);

/**
 * A model read by vtkSceneVisModelReader (formats, "PartId" and "Colors" arrays: see there), with
 * RemoveNonFiniteCells off (the scenevis tool removes and counts those cells itself) and without
 * printing the reader's error.
 * @return nullptr when the file cannot be read; @p error then says why in one line.
 */
vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error = nullptr);

/// vtkSceneVisModelReader::InlineVrmlMaterialUses().
std::string InlineVrmlMaterialUses(const std::string& text);

} // namespace testing
} // namespace scenevis

#endif

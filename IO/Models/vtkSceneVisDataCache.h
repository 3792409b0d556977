/**
 * @file    vtkSceneVisDataCache.h
 * @brief   Where the models fetched by scripts/fetch-data.sh are: named models for the
 *          `scenevis` tool (`--scene engine-glb`), the tests and the benchmarks.
 *
 * Real models are never committed: scripts/fetch-data.sh puts them into a cache directory
 * ($SCENEVIS_DATA_DIR, default ~/.cache/scenevis-data) and writes `manifest.txt` there, one
 * `key=relative/path` per line (e.g. `bunny-stl`, `engine-glb`). DataFile() resolves a key; a
 * key that was not fetched resolves to "" (tests and benchmarks then skip, the tool says so).
 *
 * @code
 * const std::string path = scenevis::DataFile("engine-glb");
 * if (!path.empty())
 *   polydata = vtkSceneVisModelReader::LoadFile(path, &error);
 * @endcode
 *
 * Plain functions in namespace scenevis (not wrapped for Python).
 *
 * @sa vtkSceneVisModelReader
 */
#ifndef vtkSceneVisDataCache_h
#define vtkSceneVisDataCache_h

#include "SceneVisIOModelsModule.h" // For export macro

#include <string> // For std::string

namespace scenevis
{

/// The data cache directory ($SCENEVIS_DATA_DIR or ~/.cache/scenevis-data).
SCENEVISIOMODELS_EXPORT std::string DataDirectory();

/// Absolute path of the manifest entry @p key, or "" when it was not fetched (or its file is gone).
SCENEVISIOMODELS_EXPORT std::string DataFile(const std::string& key);

} // namespace scenevis

#endif

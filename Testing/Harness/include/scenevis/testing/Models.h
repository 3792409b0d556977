/**
 * @file Models.h
 * @brief Loading third-party models for tests, benchmarks and tools.
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
 * Read a surface model as one polydata: .vtp, .vtk (legacy polydata), .ply, .stl, .obj, and
 * .glb/.gltf (all meshes of the default scene merged, node transforms applied).
 * @return nullptr when the file cannot be read; @p error then says why in one line.
 */
vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error = nullptr);

} // namespace testing
} // namespace scenevis

#endif

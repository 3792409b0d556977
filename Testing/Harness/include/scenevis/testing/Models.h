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
 * Read a surface model as one polydata: .vtp, .vtk (legacy polydata), .ply, .stl, .obj, and the
 * scene formats .glb/.gltf and .wrl (VRML 2.0), which go through VTK's importers: every imported
 * actor becomes one part, its matrix applied, and the merged output gets two cell arrays:
 * "PartId" (vtkIdTypeArray, the actor's index in import order) and "Colors" (RGBA unsigned char
 * cell scalars from the actor's diffuse colour and opacity). VRML files are first passed through
 * InlineVrmlMaterialUses(), because VTK 9.1's importer ignores `material USE NAME`.
 * @return nullptr when the file cannot be read; @p error then says why in one line.
 */
vtkSmartPointer<vtkPolyData> LoadModel(const std::string& path, std::string* error = nullptr);

/**
 * VRML text with every `material USE NAME` replaced by a copy of the `material DEF NAME
 * Material { ... }` node defined earlier in the text (VTK 9.1's vtkVRMLImporter ignores USE for
 * materials, so KiCad parts, which define each material once and USE it for every shape, would
 * come out white and opaque). Unknown names are left as they are. Text without USE is returned
 * unchanged.
 */
std::string InlineVrmlMaterialUses(const std::string& text);

} // namespace testing
} // namespace scenevis

#endif

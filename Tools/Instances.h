// Instanced scenes: each distinct mesh loaded once, placed many times (glTF nodes that reference
// one mesh). One mapper per mesh and one actor per placement, so GPU buffers, BVHs and occluder
// caches are built once per mesh, not once per copy.
#ifndef scenevis_tool_Instances_h
#define scenevis_tool_Instances_h

#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>
#include <vector>

class vtkMatrix4x4;
class vtkPolyData;

namespace scenevis
{
namespace tool
{

struct Instance
{
  std::size_t mesh = 0;                 ///< index into InstancedScene::meshes
  vtkSmartPointer<vtkMatrix4x4> matrix; ///< model to world
};

struct InstancedScene
{
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  std::vector<Instance> instances;
};

/**
 * Reads a glTF 2.0 file (.gltf or .glb) into a "mesh library": one polydata holding every distinct
 * mesh primitive that a node of the default scene draws, once, its cells tagged by a "MeshId" cell
 * array (0, 1, ... in order of first use) and coloured like LoadModel's flattened import ("Colors":
 * RGBA of the material's base colour), plus two field-data arrays that place them:
 * "InstanceMesh" (one MeshId per drawing node) and "InstanceMatrix" (its 16-value global matrix,
 * row-major). The library survives a .vtp round trip, so it can be read in a child process.
 * @return nullptr and a one-line @p error when the file cannot be read or draws nothing.
 */
vtkSmartPointer<vtkPolyData> LoadGltfMeshLibrary(const std::string& path, std::string* error);

/**
 * The meshes and placements of a mesh library (LoadGltfMeshLibrary, after any per-cell processing
 * such as colours and normals). Throws std::runtime_error when the placements are missing or name
 * a mesh the library does not have.
 */
InstancedScene UnpackMeshLibrary(vtkPolyData* library);

/// World-space bounds of every placed mesh: of its points, as the flattened scene's (so the same
/// default camera); linear in the placed points.
void InstancedBounds(const InstancedScene& scene, double bounds[6]);

/// World-space box of one placement: the mesh's box corners through its matrix (conservative;
/// wider than the points' bounds under a rotation). Constant time.
void InstanceBounds(const InstancedScene& scene, const Instance& instance, double bounds[6]);

} // namespace tool
} // namespace scenevis

#endif

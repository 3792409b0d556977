// Instanced scenes: each distinct mesh loaded once, placed many times (glTF nodes that reference
// one mesh, VRML USEs of a DEF'd shape or geometry). One mapper per mesh and one actor per
// placement, so GPU buffers, BVHs and occluder caches are built once per mesh, not once per copy.
#ifndef scenevis_tool_Instances_h
#define scenevis_tool_Instances_h

#include <vtkSmartPointer.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

class vtkPolyData;

namespace scenevis
{
namespace tool
{

struct Instance
{
  std::size_t mesh = 0; ///< index into InstancedScene::meshes
  /// Model to world, row-major (vtkMatrix4x4's order); plain values: a vtkMatrix4x4 per
  /// placement costs 225 bytes of heap (10 MB for 46,000 placements).
  std::array<double, 16> matrix;
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
 * row-major). Placements are in vtkGLTFImporter's order, so placement i is the flattened import's
 * PartId i. The library survives a .vtp round trip, so it can be read in a child process.
 * @return nullptr and a one-line @p error when the file cannot be read, draws nothing, or a node
 * that draws has a NaN, infinite or singular global matrix (its normals and bounds would be NaN).
 */
vtkSmartPointer<vtkPolyData> LoadGltfMeshLibrary(const std::string& path, std::string* error);

/**
 * Reads a VRML 2.0 file (.wrl) into a mesh library like LoadGltfMeshLibrary's: VTK's importer
 * gives a USE of a DEF'd Shape or geometry node an actor that shares the DEF's mapper, so each
 * distinct (geometry, colour) is one mesh and each shape drawn one placement (its actor's
 * matrix), in the order of the flattened import (placement i is its PartId i). What VTK 9.1's
 * importer does not instance is not instanced either (a USE of a Transform or Group draws
 * nothing, in both forms). `material USE` is inlined as the flattened import does.
 * @return nullptr and a one-line @p error for an unreadable file, one without surfaces, a bad
 * USE (CheckVrmlUses) or a shape whose matrix cannot place it.
 */
vtkSmartPointer<vtkPolyData> LoadVrmlMeshLibrary(const std::string& path, std::string* error);

/// LoadVrmlMeshLibrary for .wrl files, else LoadGltfMeshLibrary.
vtkSmartPointer<vtkPolyData> LoadMeshLibrary(const std::string& path, std::string* error);

/// Whether --instances can read @p path: glTF (.glb, .gltf) or VRML (.wrl), any case.
bool IsInstanceable(const std::string& path);

/**
 * The first bad USE of a VRML text, as one line ("" when there is none): a USE of a name that no
 * DEF before it defines (VTK's importer silently draws nothing), or a USE inside the node its
 * name DEFs (a node containing itself, which VTK's importer turns into a copy). Comments and
 * strings are skipped. Linear in the text.
 */
std::string CheckVrmlUses(const std::string& text);

/**
 * The meshes and placements of a mesh library (LoadGltfMeshLibrary, after any per-cell processing
 * such as colours and normals). Throws std::runtime_error when the placements are missing or name
 * a mesh the library does not have.
 */
InstancedScene UnpackMeshLibrary(vtkPolyData* library);

/**
 * The placed meshes in world space as one polydata, placement after placement, each mesh's points
 * (and point normals) through its matrix, its cells tagged with a @p partArray cell array holding
 * the placement's index. Cell for cell what the flattened import of the same glTF file gives
 * (LoadModel: placement i is its PartId i), so a command can treat an instanced scene as the
 * flattened one where it needs every polygon (sort's BSP, cull --exact's ID buffer). Linear in
 * the placed polygons: this is the memory instancing saves, so the render and cull paths never
 * call it.
 */
vtkSmartPointer<vtkPolyData> FlattenInstances(
  const InstancedScene& scene, const std::string& partArray = "PartId");

/// World-space bounds of every placed mesh: of its points, as the flattened scene's (so the same
/// default camera); linear in the placed points.
void InstancedBounds(const InstancedScene& scene, double bounds[6]);

/// World-space box of one placement: the mesh's box corners through its matrix (conservative;
/// wider than the points' bounds under a rotation). Constant time.
void InstanceBounds(const InstancedScene& scene, const Instance& instance, double bounds[6]);

} // namespace tool
} // namespace scenevis

#endif

// The scene a command works on: an embedded demo, a data-cache key or a model file, loaded and
// checked, with its colours, its portals, its part and room arrays checked and smooth normals.
#ifndef scenevis_tool_SceneLoading_h
#define scenevis_tool_SceneLoading_h

#include "Instances.h"
#include "Options.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace scenevis
{
namespace tool
{

/// A scene as the commands work on it, and what loading it cost (the reports' times).
struct LoadedScene
{
  vtkSmartPointer<vtkPolyData> polydata;
  /// Portals (RoomA/RoomB cell arrays) of a building: the demo's own or --portals; else null.
  vtkSmartPointer<vtkPolyData> portals;
  std::string description;
  bool zUp = false; ///< the cad and building demos are z-up
  double loadMs = 0.0;
  double checkMs = 0.0;   ///< checking the part and room arrays, compacting the cells
  double normalsMs = 0.0; ///< computing normals (0 when the file has them)
  std::uint64_t rssAfterLoad = 0;
  /// Bytes the cells took beyond their 32-bit storage as the reader gave them (CompactCellStorage):
  /// the polydata as loaded is its size now plus these.
  std::uint64_t compactedBytes = 0;
  /// --instances: the meshes and their placements; polydata is then the mesh library (every
  /// distinct mesh once), not the scene.
  std::shared_ptr<InstancedScene> instanced;
};

/// The scene of --scene as read: an embedded demo (with the building's portals), or a data-cache
/// key or model file read as an untrusted file (UntrustedFiles.h), its colours as RGBA cell
/// scalars (--opacity applied), and the portals of --portals. Throws UsageError for a scene that
/// names nothing, std::runtime_error for one that cannot be read or used.
LoadedScene LoadScene(const Options& options);

/// The scene as loaded, its part and room arrays checked, with smooth normals when it has none.
LoadedScene LoadSceneWithNormals(const Options& options);

/// The bounds of the scene as drawn: its polydata, or its placed meshes (--instances).
void SceneBounds(const LoadedScene& scene, double bounds[6]);

/// Triangles of the polygons (a polygon of n points counts n - 2).
vtkIdType CountTriangles(vtkPolyData* pd);

/// The cells of @p pd split into one polydata per value of the cell array @p partArray; with
/// @p releaseInputPolygons, @p pd gives its polygons up as the parts get theirs (SplitByKeys).
std::vector<vtkSmartPointer<vtkPolyData>> SplitByPart(
  vtkPolyData* pd, const std::string& partArray, bool releaseInputPolygons = false);

} // namespace tool
} // namespace scenevis

#endif

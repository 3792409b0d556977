/**
 * @class   vtkBSPSortUtilities
 * @brief   Conversions between VTK data and the SceneVis BSP core, shared by the sorting classes.
 *
 * vtkBSPSortFilter, vtkBSPSortedPolyDataMapper and vtkBSPTranslucentPass all feed polydata to the
 * VTK-free BSP core (scenevis/BspBuilder.h) and turn its fragments back into drawable data; the
 * conventions live here once:
 * - polygons are taken in VTK's cell order (verts, lines, polys, strips): polys as they are,
 *   strips as their triangles with alternating winding fixed, so all face the strip's way;
 * - split points follow the core's convention (point id = input point count + index, at
 *   lerp(point(a), point(b), t)), and EVERY point-data array is interpolated the same way, with
 *   normals re-normalised;
 * - a camera becomes a scenevis::View in the data coordinates of a prop (through the inverse of
 *   its matrix): an eye point for perspective cameras, a direction for parallel ones.
 *
 * A plain class of static functions (no vtkObject): it has no state.
 */

#ifndef vtkBSPSortUtilities_h
#define vtkBSPSortUtilities_h

#include "SceneVisFiltersSortingModule.h" // For export macro
#include "vtkType.h"                      // For vtkIdType

#include "scenevis/BspTree.h"     // For scenevis::bsp::SplitPoint
#include "scenevis/PolygonMesh.h" // For scenevis::PolygonMesh
#include "scenevis/View.h"        // For scenevis::View

#include <cstddef> // For std::size_t
#include <vector>  // For std::vector

class vtkCamera;
class vtkMatrix4x4;
class vtkPointData;
class vtkPoints;
class vtkPolyData;

class SCENEVISFILTERSSORTING_EXPORT vtkBSPSortUtilities
{
public:
  /**
   * Appends the polygons of @p input (polys, then strips as their triangles) to @p mesh, with
   * points transformed by @p matrix (nullptr: unchanged), and for every appended polygon the
   * input cell id it came from to @p cellOf. Point ids are offset by the mesh's point count.
   */
  static void AppendPolygons(vtkPolyData* input, vtkMatrix4x4* matrix,
    scenevis::PolygonMesh& mesh, std::vector<vtkIdType>& cellOf);

  /**
   * Fills @p points and @p pointData with the input's points and point data followed by
   * @p count split points: positions and every point-data array interpolated, normals
   * re-normalised. @p points takes the input's precision.
   */
  static void InterpolateSplitPoints(vtkPolyData* input,
    const scenevis::bsp::SplitPoint* splits, std::size_t count, vtkPoints* points,
    vtkPointData* pointData);

  /**
   * The view of @p camera in the data coordinates of a prop with matrix @p propMatrix (nullptr:
   * world coordinates). Returns false when the camera has a non-finite position or no view
   * direction (then @p view is unchanged).
   */
  static bool ViewFromCamera(vtkCamera* camera, vtkMatrix4x4* propMatrix, scenevis::View& view);

  vtkBSPSortUtilities() = delete;
};

#endif
// VTK-HeaderTest-Exclude: vtkBSPSortUtilities.h

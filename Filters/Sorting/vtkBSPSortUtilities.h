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
 *   its matrix): an eye point for perspective cameras, a direction for parallel ones;
 * - ordered fragments (of a bsp::Tree or a painter::Result, which share the layout) become a
 *   vtkCellArray of polygons, and per-cell arrays follow the same order (EmitPolygons,
 *   PermuteTuples): both run on every camera change, so they work on raw memory, in parallel.
 *
 * A plain class of static functions (no vtkObject): it has no state.
 */

#ifndef vtkBSPSortUtilities_h
#define vtkBSPSortUtilities_h

#include "SceneVisFiltersSortingModule.h" // For export macro
#include "vtkSmartPointer.h"              // For vtkSmartPointer
#include "vtkType.h"                      // For vtkIdType

#include "scenevis/BspTree.h"     // For scenevis::bsp::SplitPoint
#include "scenevis/PolygonMesh.h" // For scenevis::PolygonMesh
#include "scenevis/View.h"        // For scenevis::View

#include <cstddef> // For std::size_t
#include <cstdint> // For std::uint32_t
#include <vector>  // For std::vector

class vtkAbstractArray;
class vtkCamera;
class vtkCellArray;
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
   * The triangles of convex fragments (fragment f: vertices[offsets[f] .. offsets[f + 1]), point
   * ids as InterpolateSplitPoints numbers them) for an index buffer: for every fragment in turn,
   * its size - 2 triangles as triples of indices into @p vertices, appended to @p corners. The
   * fan from the fragment's first vertex, unless that fan has flat triangles (conforming
   * fragments carry their neighbours' split points on their sides): then ears clipped at its
   * corners (scenevis/ConvexTriangulation.h), so that every piece of every side is a triangle
   * edge. Collinearity is judged on the points in double, split points interpolated as the BSP
   * core does.
   */
  static void TriangulateFragments(vtkPolyData* input, const scenevis::bsp::SplitPoint* splits,
    std::size_t splitCount, const std::uint32_t* offsets, std::size_t fragmentCount,
    const std::uint32_t* vertices, std::vector<std::uint32_t>& corners);

  /**
   * The view of @p camera in the data coordinates of a prop with matrix @p propMatrix (nullptr:
   * world coordinates). Returns false when the camera has a non-finite position or no view
   * direction (then @p view is unchanged).
   */
  static bool ViewFromCamera(vtkCamera* camera, vtkMatrix4x4* propMatrix, scenevis::View& view);

  /**
   * The polygons fragments[order[0]], fragments[order[1]], ... (@p count of them) as a cell array;
   * @p order nullptr: fragments[0 .. count) as they are. Each fragment lists
   * fragmentVertices[first .. first + count). The cell array uses 32-bit storage when
   * @p pointCount and @p vertexCount (the size of @p fragmentVertices) allow, else 64-bit.
   * Works for bsp::Tree (fragments in tree order + an IncrementalOrder) and painter::Result
   * (fragments already in drawing order).
   */
  static vtkSmartPointer<vtkCellArray> EmitPolygons(const scenevis::bsp::Fragment* fragments,
    const std::uint32_t* fragmentVertices, std::size_t vertexCount, std::size_t pointCount,
    const std::uint32_t* order, std::size_t count);

  /**
   * target[offset + r] = source[order[r]] for r in [0, count): every component of every tuple.
   * @p target must already hold at least offset + count tuples. Numeric arrays with the standard
   * memory layout are copied as raw bytes in parallel; other arrays (strings, variants, SOA)
   * tuple by tuple.
   */
  static void PermuteTuples(vtkAbstractArray* source, const std::uint32_t* order,
    std::size_t count, vtkAbstractArray* target, vtkIdType offset);

  vtkBSPSortUtilities() = delete;
};

#endif
// VTK-HeaderTest-Exclude: vtkBSPSortUtilities.h

/**
 * @class   vtkVisibilityOrderFilter
 * @brief   Abstract base of the filters that put polygons in visibility order for a camera.
 *
 * What vtkBSPSortFilter and vtkPainterSortFilter share: the camera (required), an optional prop
 * whose matrix takes the camera into the input's data coordinates, the direction (back to front
 * by default), and the OriginalCellId / SortRank output arrays. The filter's MTime includes the
 * camera's and the prop's, so a camera move re-executes the pipeline (as vtkDepthSortPolyData).
 *
 * @sa vtkBSPSortFilter vtkPainterSortFilter vtkDepthSortPolyData
 */

#ifndef vtkVisibilityOrderFilter_h
#define vtkVisibilityOrderFilter_h

#include "SceneVisFiltersSortingModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkWeakPointer.h" // For vtkWeakPointer

#include "scenevis/PolygonMesh.h" // For scenevis::PolygonMesh
#include "scenevis/View.h"        // For scenevis::View

#include <cstddef> // For std::size_t
#include <cstdint> // For std::uint32_t
#include <vector>  // For std::vector

class vtkCamera;
class vtkCellData;
class vtkProp3D;

class SCENEVISFILTERSSORTING_EXPORT vtkVisibilityOrderFilter : public vtkPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkVisibilityOrderFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Directions
  {
    VTK_DIRECTION_BACK_TO_FRONT = 0,
    VTK_DIRECTION_FRONT_TO_BACK = 1
  };

  ///@{
  /**
   * The camera that defines the order. Required.
   */
  virtual void SetCamera(vtkCamera*);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  ///@{
  /**
   * Optional prop whose matrix maps the input's coordinates to world coordinates; the camera is
   * then taken into data coordinates through the inverse of that matrix. Held weakly.
   */
  void SetProp3D(vtkProp3D*);
  vtkProp3D* GetProp3D();
  ///@}

  ///@{
  /**
   * Back to front (default) or front to back.
   */
  vtkSetClampMacro(Direction, int, VTK_DIRECTION_BACK_TO_FRONT, VTK_DIRECTION_FRONT_TO_BACK);
  vtkGetMacro(Direction, int);
  void SetDirectionToBackToFront() { this->SetDirection(VTK_DIRECTION_BACK_TO_FRONT); }
  void SetDirectionToFrontToBack() { this->SetDirection(VTK_DIRECTION_FRONT_TO_BACK); }
  ///@}

  ///@{
  /**
   * Whether to add the OriginalCellId and SortRank cell-data arrays (default on).
   */
  vtkSetMacro(GenerateOrderArrays, vtkTypeBool);
  vtkGetMacro(GenerateOrderArrays, vtkTypeBool);
  vtkBooleanMacro(GenerateOrderArrays, vtkTypeBool);
  ///@}

  vtkMTimeType GetMTime() override;

  /// Cell-data array: the input cell id of every output cell.
  static const char* OriginalCellIdArrayName() { return "OriginalCellId"; }
  /// Cell-data array: the position of every fragment in the order (-1 for verts and lines).
  static const char* SortRankArrayName() { return "SortRank"; }

protected:
  vtkVisibilityOrderFilter() = default;
  ~vtkVisibilityOrderFilter() override;

  /**
   * The view in the input's data coordinates. Without a camera, or with a camera that has a
   * non-finite position or no view direction, reports an error, passes @p input through to
   * @p output unsorted and returns false.
   */
  bool ViewForInput(vtkPolyData* input, vtkPolyData* output, scenevis::View& view);

  /**
   * The input's polygons and strips (as triangles) appended to @p mesh, with the input cell id of
   * each in @p cellOf. When the input has none, warns, passes @p input through to @p output and
   * returns false.
   */
  bool PolygonsForInput(vtkPolyData* input, vtkPolyData* output, scenevis::PolygonMesh& mesh,
    std::vector<vtkIdType>& cellOf);

  /**
   * Warns about the polygons the sorter removed (@p invalid: non-finite points or bad point ids;
   * @p degenerate: fewer than 3 distinct points or zero area); returns their sum.
   */
  vtkIdType ReportRemovedPolygons(std::size_t invalid, std::size_t degenerate);

  /**
   * Fills @p output's cell data for @p passThrough verts/lines (copied from @p input) followed by
   * @p count fragments, fragment r taking tuple @p sourceIndex[r] of @p source, and adds the
   * OriginalCellId / SortRank arrays when GenerateOrderArrays is on (fragment r comes from input
   * cell @p cellOfRank[r]; verts and lines keep their ids and get rank -1).
   */
  void EmitCellData(vtkCellData* input, vtkIdType passThrough, vtkCellData* source,
    const std::uint32_t* sourceIndex, const std::uint32_t* cellOfRank, std::size_t count,
    vtkCellData* output);

  vtkCamera* Camera = nullptr;
  vtkWeakPointer<vtkProp3D> Prop3D;
  int Direction = VTK_DIRECTION_BACK_TO_FRONT;
  vtkTypeBool GenerateOrderArrays = true;

private:
  vtkVisibilityOrderFilter(const vtkVisibilityOrderFilter&) = delete;
  void operator=(const vtkVisibilityOrderFilter&) = delete;
};

#endif

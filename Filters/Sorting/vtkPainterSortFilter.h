/**
 * @class   vtkPainterSortFilter
 * @brief   Back-to-front (or front-to-back) order of polygons by the painter's algorithm of
 *          Newell, Newell & Sancha, redone for every camera.
 *
 * vtkPainterSortFilter is the per-frame counterpart of vtkBSPSortFilter, with the same interface
 * and output: it orders the polygons of its input for a camera so that translucent surfaces blend
 * correctly when drawn in output order, splitting polygons where no order of whole polygons
 * exists (cyclic overlaps, interpenetration). It uses scenevis::painter::Sorter
 * (scenevis/PainterSort.h):
 *
 * - input (or settings) changed: the input's polygons are normalised once (concave/non-planar
 *   ones triangulated, degenerate ones removed with a warning);
 * - camera or prop changed: the whole order is computed again (depth sort plus Newell's tests,
 *   with splits), and the output is re-emitted; there is no incremental update, and the cost
 *   grows faster than linearly with the polygon count (quadratic in the worst case), so it is
 *   meant for small scenes and as a comparison;
 * - nothing changed: the pipeline does not execute.
 *
 * Output (as vtkBSPSortFilter): the input's points followed by the split points of THIS view,
 * with all point data interpolated (normals re-normalised); verts and lines pass through first,
 * then the polygon fragments in visibility order. Cell data are copied from each fragment's
 * input cell; the cell-data arrays OriginalCellId and SortRank (-1 for verts and lines) are added
 * unless GenerateOrderArrays is off. The fragments meet edge to edge (scenevis::painter::Config::
 * conformingFragments: every split point is also a vertex of the neighbours whose edges it lies
 * on, and each fragment starts at a vertex from which VTK's fan keeps those points as corners),
 * so blending shows no cracks or doubled pixels along split edges.
 *
 * The order is exact unless the split cap (MaxSplitsPerPolygon) is reached, in which case
 * conflicts are emitted unresolved; GetNumberOfForcedEmissions() counts them.
 *
 * As with vtkBSPSortFilter, set a vtkOrderedTranslucentPass on the renderer to see the order on
 * screen (VTK 9.1's default translucency ignores primitive order).
 *
 * @sa vtkBSPSortFilter vtkDepthSortPolyData
 */

#ifndef vtkPainterSortFilter_h
#define vtkPainterSortFilter_h

#include "SceneVisFiltersSortingModule.h" // For export macro
#include "vtkVisibilityOrderFilter.h"

#include <memory> // For std::unique_ptr

class SCENEVISFILTERSSORTING_EXPORT vtkPainterSortFilter : public vtkVisibilityOrderFilter
{
public:
  static vtkPainterSortFilter* New();
  vtkTypeMacro(vtkPainterSortFilter, vtkVisibilityOrderFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;


  ///@{
  /**
   * Sorter settings (see scenevis/PainterSort.h): plane tolerance relative to the diagonal of the
   * input bounds, and the split cap per polygon. Changing them re-normalises on the next update.
   */
  vtkSetClampMacro(RelativeTolerance, double, 0.0, 1e-3);
  vtkGetMacro(RelativeTolerance, double);
  vtkSetClampMacro(MaxSplitsPerPolygon, double, 0.0, 1e6);
  vtkGetMacro(MaxSplitsPerPolygon, double);
  ///@}

  ///@{
  /**
   * Statistics of the last update.
   */
  vtkIdType GetNumberOfFragments() const;
  vtkIdType GetNumberOfSplits() const;
  vtkIdType GetNumberOfRemovedPolygons() const;
  vtkIdType GetNumberOfForcedEmissions() const; ///< Conflicts left unresolved (split cap).
  double GetLastSortTime() const;               ///< Seconds: the painter's sort alone.
  double GetLastOrderTime() const;              ///< Seconds: sort + output emission.
  double GetLastBuildTime() const;              ///< Seconds: the last normalisation.
  vtkIdType GetNumberOfBuilds() const;          ///< Normalisations since construction.
  vtkIdType GetNumberOfSorts() const;           ///< Sorts since construction.
  ///@}

protected:
  vtkPainterSortFilter();
  ~vtkPainterSortFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double RelativeTolerance = 1e-10;
  double MaxSplitsPerPolygon = 16.0;

private:
  vtkPainterSortFilter(const vtkPainterSortFilter&) = delete;
  void operator=(const vtkPainterSortFilter&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif

/**
 * @class   vtkBSPSortFilter
 * @brief   Exact back-to-front (or front-to-back) order of polygons with a reusable BSP tree.
 *
 * vtkBSPSortFilter orders the polygons of its input for a camera so that translucent surfaces
 * blend correctly when drawn in output order. Unlike vtkDepthSortPolyData, which sorts one depth
 * per cell and is wrong for intersecting, long or cyclically overlapping polygons, it builds a
 * polygon-aligned BSP tree (Fuchs, Kedem, Naylor 1980) once, splitting polygons that straddle a
 * partition plane, and then only walks it when the camera moves. The result is exact for any
 * perspective or parallel camera.
 *
 * Work done per update:
 * - input (or partition settings) changed: the tree is rebuilt (progress events are fired);
 * - only the camera or prop changed: the order is brought up to date incrementally (only subtrees
 *   whose plane the eye crossed are touched) and the output cells are re-emitted;
 * - nothing changed: the pipeline does not execute at all.
 *
 * Output: the input's points followed by the points created by splits, with ALL point data
 * interpolated (normals re-normalised); verts and lines pass through first and unchanged, then the
 * polygon fragments in visibility order (triangle strips are handled as their triangles, concave
 * and non-planar polygons are triangulated). Cell data are copied from each fragment's input cell.
 * Two cell-data arrays are added: OriginalCellId (input cell id of each output cell) and SortRank
 * (position of the fragment in the order; -1 for verts and lines), so the order itself can be
 * shown with a lookup table, as in VTK's TestDepthSortPolyData.
 *
 * Note that VTK 9.1 draws translucent geometry with order-independent blending by default, which
 * ignores primitive order; set a vtkOrderedTranslucentPass (SceneVis::RenderingTranslucency) on
 * the renderer to see the order on screen.
 *
 * Bad input: points with NaN/Inf coordinates and polygons with fewer than three distinct points
 * or zero area are removed with a warning that counts them; without a camera the input passes
 * through unsorted with an error.
 *
 * @sa vtkDepthSortPolyData
 */

#ifndef vtkBSPSortFilter_h
#define vtkBSPSortFilter_h

#include "SceneVisFiltersSortingModule.h" // For export macro
#include "vtkVisibilityOrderFilter.h"

#include <memory> // For std::unique_ptr

class SCENEVISFILTERSSORTING_EXPORT vtkBSPSortFilter : public vtkVisibilityOrderFilter
{
public:
  static vtkBSPSortFilter* New();
  vtkTypeMacro(vtkBSPSortFilter, vtkVisibilityOrderFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;


  enum PartitionModes
  {
    PARTITION_FIRST_IN_LIST = 0, ///< The textbook choice; convex meshes become deep chains.
    PARTITION_SCORED = 1         ///< Sampled candidates scored by splits and balance (default).
  };

  ///@{
  /**
   * How partition planes are chosen (see scenevis/BspBuilder.h). Changing any of these rebuilds
   * the tree on the next update.
   */
  vtkSetClampMacro(PartitionMode, int, PARTITION_FIRST_IN_LIST, PARTITION_SCORED);
  vtkGetMacro(PartitionMode, int);
  vtkSetClampMacro(CandidateCount, int, 1, 1024);
  vtkGetMacro(CandidateCount, int);
  vtkSetClampMacro(SplitWeight, double, 0.0, 1e6);
  vtkGetMacro(SplitWeight, double);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  vtkSetClampMacro(RelativeTolerance, double, 0.0, 1e-3);
  vtkGetMacro(RelativeTolerance, double);
  ///@}

  ///@{
  /**
   * Ordered leaves (scenevis/BspTree.h): lists of at most this many polygons that no partition
   * plane separates without a split are kept whole, and sorted per view by the separating planes
   * stored for their pairs, instead of being split. 0 (the default) turns them off; values are
   * clamped to [0, 256]. Exact either way; leaves trade fewer output polygons for order time and
   * memory (the bunny: 2.08 output polygons per input without leaves, 1.59 at 64 and 1.26 at 256,
   * for about 5x and 30-40x the order time: BENCHMARKS.md, "ordered leaves"). With leaves the
   * order is a full traversal on every camera change (the incremental update does not take them),
   * and the number of output polygons depends on the view. Changing it rebuilds the tree.
   */
  vtkSetClampMacro(OrderedLeafSize, int, 0, 256);
  vtkGetMacro(OrderedLeafSize, int);
  ///@}

  ///@{
  /**
   * Statistics of the last build and update.
   */
  vtkIdType GetNumberOfFragments() const;
  vtkIdType GetNumberOfSplits() const;
  vtkIdType GetNumberOfRemovedPolygons() const;
  vtkIdType GetTreeDepth() const;
  double GetLastBuildTime() const;     ///< Seconds.
  double GetLastOrderTime() const;     ///< Seconds.
  vtkIdType GetNumberOfBuilds() const; ///< Trees built since construction.
  vtkIdType GetLastNodesVisited() const;
  /// Polygons in the last output (fragments drawn for that view; GetNumberOfFragments() with no
  /// ordered leaves, fewer with them).
  vtkIdType GetLastNumberOfOrderedFragments() const;
  /// Ordered leaves kept whole, and leaves that drew their split subtree because their pairs
  /// formed a cycle for the view, in the last update (0 without ordered leaves).
  vtkIdType GetLastLeavesSorted() const;
  vtkIdType GetLastLeavesFallenBack() const;
  ///@}

protected:
  vtkBSPSortFilter();
  ~vtkBSPSortFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int PartitionMode = PARTITION_SCORED;
  int CandidateCount = 16;
  double SplitWeight = 4.0;
  unsigned int Seed = 1;
  double RelativeTolerance = 1e-10;
  int OrderedLeafSize = 0;

private:
  vtkBSPSortFilter(const vtkBSPSortFilter&) = delete;
  void operator=(const vtkBSPSortFilter&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif

/**
 * @class   vtkBSPSortedPolyDataMapper
 * @brief   A polydata mapper that draws translucent polygons in exact back-to-front order by
 *          rewriting only its triangle index buffer when the camera moves.
 *
 * vtkBSPSortFilter + vtkPolyDataMapper re-orders polydata on the CPU: every camera move makes a
 * new polydata, and VTK then rebuilds and re-uploads every vertex buffer. This mapper instead
 *
 * 1. builds a polygon-aligned BSP tree of its input once (again only when the input's MTime
 *    changes), splitting polygons that straddle partition planes;
 * 2. builds the vertex buffers ONCE from the fragment geometry: the input's points followed by the
 *    split points, with all point data interpolated (normals re-normalised, scalars/colours,
 *    texture coordinates, ...), and the fragments triangulated (a fan from the first vertex, or
 *    ears at the corners where the fan would make flat triangles of the split points on a side:
 *    vtkBSPSortUtilities::TriangulateFragments);
 * 3. per frame, only when the camera (taken into the actor's data coordinates through the actor's
 *    matrix; perspective or parallel) has moved, brings the BSP order up to date incrementally
 *    (scenevis::bsp::IncrementalOrder) and re-uploads the triangle index buffer in that order.
 *    Camera unchanged: nothing is re-sorted and nothing is uploaded.
 *
 * Only translucent rendering needs an order: while its actor is opaque the mapper neither sorts
 * nor draws the split fragments (it draws its input, exactly like vtkOpenGLPolyDataMapper; the
 * tree is kept), and an actor that has never been rendered translucent does not even build the
 * tree.
 *
 * To see the order on screen, translucent geometry must be alpha blended in primitive order: set
 * a vtkOrderedTranslucentPass on the renderer (VTK 9.1's default weighted OIT ignores order).
 *
 * Data handled:
 * - point data: all arrays interpolated at split points (normals re-normalised);
 * - cell data: when the mapper colours by cell scalars, or the input has cell normals and no
 *   point normals, each fragment gets its own copies of its vertices and the cell's values become
 *   per-vertex values (so the order can change without gl_PrimitiveID-indexed cell textures);
 *   verts and lines are then not drawn. Otherwise cell data are not needed for drawing and dropped.
 * - verts and lines: drawn unsorted (as by the superclass); triangle strips are sorted as their
 *   triangles; concave/non-planar polygons are triangulated by the BSP builder.
 *
 * Limits: sorting applies to the surface representation without edge visibility (edges and
 * wireframe/points representations draw the input, unsorted). Hardware picking draws the input
 * (so it reports input cell ids), which costs a vertex buffer build each way on a translucent
 * actor.
 *
 * Instrumentation (for tests and benchmarks): GetNumberOfIndexUploads(),
 * GetNumberOfOrderUpdates(), GetNumberOfTreeBuilds(), GetNumberOfVertexBufferBuilds().
 *
 * @sa vtkBSPSortFilter vtkOrderedTranslucentPass vtkBSPTranslucentPass
 */

#ifndef vtkBSPSortedPolyDataMapper_h
#define vtkBSPSortedPolyDataMapper_h

#include "SceneVisRenderingTranslucencyModule.h" // For export macro
#include "vtkOpenGLPolyDataMapper.h"

#include <cstdint> // For std::uint32_t
#include <memory>  // For std::unique_ptr, std::shared_ptr
#include <vector>  // For std::vector

struct vtkBSPFragmentSet;

class SCENEVISRENDERINGTRANSLUCENCY_EXPORT vtkBSPSortedPolyDataMapper
  : public vtkOpenGLPolyDataMapper
{
public:
  static vtkBSPSortedPolyDataMapper* New();
  vtkTypeMacro(vtkBSPSortedPolyDataMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void RenderPieceStart(vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceFinish(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow*) override;

  /// Maps the scalars of the geometry drawn (the fragments) rather than those of the input.
  using vtkOpenGLPolyDataMapper::MapScalars;
  vtkUnsignedCharArray* MapScalars(double alpha) override;

  ///@{
  /**
   * Counters since construction: index buffer uploads made for a new order, incremental order
   * updates (camera moved), BSP trees built, and vertex buffer (re)builds.
   */
  vtkIdType GetNumberOfIndexUploads() const;
  vtkIdType GetNumberOfOrderUpdates() const;
  vtkIdType GetNumberOfTreeBuilds() const;
  vtkIdType GetNumberOfVertexBufferBuilds() const;
  ///@}

  ///@{
  /**
   * Of the index uploads, those that sent only the ranges of the buffer whose fragments changed
   * place (glBufferSubData; a small camera step moves few fragments), and the number of indices
   * the last upload sent (all of them for a full upload).
   */
  vtkIdType GetNumberOfPartialIndexUploads() const;
  vtkIdType GetLastUploadIndexCount() const;
  ///@}

  ///@{
  /**
   * Whether a new order sends only the changed index ranges (default on) or the whole index
   * buffer every time (for measuring what the partial uploads save).
   */
  vtkSetMacro(PartialIndexUploads, bool);
  vtkGetMacro(PartialIndexUploads, bool);
  vtkBooleanMacro(PartialIndexUploads, bool);
  ///@}

  ///@{
  /**
   * Ordered leaves (scenevis/BspTree.h, as vtkBSPSortFilter::SetOrderedLeafSize): lists of at
   * most this many polygons that no partition plane separates without a split are kept whole and
   * sorted per view, instead of being split. 0 (default): off; clamped to [0, 256]. The order
   * stays exact and fewer triangles are drawn (a non-convex closed mesh: about 1.3-1.6 fragments
   * per input polygon instead of 2.1), for more order time per camera move (a full traversal, not
   * the incremental update) and a larger vertex buffer (it holds the leaves' split fallbacks too).
   * Changing it rebuilds the tree at the next render.
   */
  vtkSetClampMacro(OrderedLeafSize, int, 0, 256);
  vtkGetMacro(OrderedLeafSize, int);
  ///@}

  ///@{
  /**
   * Size of the fragment geometry (0 before the first translucent render). With ordered leaves
   * this counts every fragment stored; GetFragmentOrder() lists those the last order drew.
   */
  vtkIdType GetNumberOfFragments() const;
  vtkIdType GetNumberOfFragmentTriangles() const;
  ///@}

  /**
   * Vertices of the fragment geometry's vertex buffer (0 before the first translucent render).
   * Cell colours or cell normals give fragments vertices of their own, carrying their cell's
   * values; fragments whose cells have the same values in every cell array share them.
   */
  vtkIdType GetNumberOfFragmentVertices() const;

  /// Whether the last render drew the split fragments (sorted) rather than the input (opaque).
  bool GetLastRenderDrewFragments() const;

  /// Seconds of the last tree build, of the last order update + index upload, and of the last
  /// index upload alone (gathering the triangles in order + glBufferData or glBufferSubData).
  double GetLastBuildTime() const;
  double GetLastOrderTime() const;
  double GetLastUploadTime() const;

  /**
   * The current drawing order as input cell ids of the fragments (one entry per fragment drawn,
   * in drawing order). Empty before the first sorted render.
   */
  void GetFragmentOrder(std::vector<vtkIdType>& cellIds) const;

protected:
  vtkBSPSortedPolyDataMapper();
  ~vtkBSPSortedPolyDataMapper() override;

  void UpdateCameraShiftScale(vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void BuildIBO(vtkRenderer* ren, vtkActor* act, vtkPolyData* poly) override;
  // Used by vtkBSPTranslucentPass: the fragments come from its world-space tree, the order of this
  // actor's fragments is given, and RenderPiece draws only index range [first, first + count).
  friend class vtkBSPTranslucentPass;
  void SetExternalFragments(std::shared_ptr<const vtkBSPFragmentSet> fragments);
  /// Local fragment ids in drawing order; uploads the index buffer if it differs from the last.
  void SetExternalOrder(const std::vector<std::uint32_t>& order);
  void SetDrawRange(vtkIdType firstIndex, vtkIdType indexCount);
  /// The point data of the external fragments' input changed (e.g. baked colours): build the
  /// vertex buffers again at the next render; the order is kept.
  void InvalidateExternalGeometry();

private:
  vtkBSPSortedPolyDataMapper(const vtkBSPSortedPolyDataMapper&) = delete;
  void operator=(const vtkBSPSortedPolyDataMapper&) = delete;

  bool PartialIndexUploads = true;
  int OrderedLeafSize = 0;
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif

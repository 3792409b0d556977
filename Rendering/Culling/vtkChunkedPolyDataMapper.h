/**
 * @class   vtkChunkedPolyDataMapper
 * @brief   A polydata mapper that culls spatial chunks of ONE big mesh per frame without
 *          touching its GPU buffers.
 *
 * vtkOctreeCuller culls whole props; a CAD model is often one merged mesh (one prop), which a prop
 * culler can only draw entirely. This mapper
 *
 * 1. partitions the polygons of its input once (again only when the input or ChunkSize changes)
 *    into spatial chunks: a binary tree of median splits over polygon centroids along the
 *    largest extent, until a node holds at most ChunkSize triangles (default 2048). Each tree
 *    node covers a contiguous range of chunks; each chunk a contiguous range of polygons.
 * 2. draws a copy of the input whose polygons are reordered chunk by chunk (points, point data,
 *    verts, lines and strips are shared with the input, cell data are permuted with the cells),
 *    so every chunk and every tree node is ONE contiguous range of the triangle index buffer.
 *    The vertex and index buffers are built once by vtkOpenGLPolyDataMapper from that copy.
 * 3. per frame (in RenderPieceStart, with the camera that draws) traverses the tree in the
 *    actor's model coordinates and draws only the index ranges of the chunks that pass, adjacent
 *    ranges merged into one glDrawRangeElements call. A node entirely inside the frustum is
 *    drawn as one range without visiting its children. Camera moves never rebuild or upload any
 *    buffer.
 *
 * Tests per chunk (each can be switched off):
 * - frustum (FrustumCulling, default on): exact, conservative p-/n-vertex box test of the chunk's
 *   bounds (inflated by 1e-5 of the mesh diagonal against GPU float rounding) with plane masking;
 * - normal cones (NormalConeCulling, default on, but only active when the actor's property has
 *   BackfaceCulling on, FrontfaceCulling off, surface representation, and the actor matrix has a
 *   positive determinant): a chunk whose triangles all face away from the eye is not drawn
 *   (conservative, see scenevis/NormalCone.h). Chunks with polygons of 7+ points never cull this
 *   way (VTK triangulates those itself);
 * - small features (MinimumPixelSize, default 0 = off): APPROXIMATE, chunks whose bounding
 *   sphere projects below that many pixels are not drawn although they may cover a few pixels.
 *
 * Drawing is exactly that of vtkOpenGLPolyDataMapper for the triangles drawn: same shaders, same
 * buffers, same primitive order among the triangles drawn (the chunk order), cell scalars / cell
 * normals through the gl_PrimitiveID offset set per range. Everything else falls back to the
 * superclass's full draw (no culling): a hardware selector (picking), representations other
 * than surface, edge visibility, an unusable camera, or a triangle index buffer whose size does
 * not match the partition (warned once): VTK 9.1 leaves out of the index buffer every triangle
 * with two points at the same coordinates (real CAD data has them, e.g. KiCad parts; remove them
 * first) and may triangulate polygons of 7+ points differently.
 *
 * Limits: picking reports cell ids of the reordered copy (GetInputCellId() maps them back);
 * memory: the reordered polygon connectivity and cell data are a second copy of the input's.
 *
 * Statistics of the last render: nodes visited, chunks tested / drawn / culled by reason,
 * triangles drawn, draw calls; counters of partition builds and vertex buffer builds.
 *
 * @sa vtkOctreeCuller vtkOpenGLPolyDataMapper
 */

#ifndef vtkChunkedPolyDataMapper_h
#define vtkChunkedPolyDataMapper_h

#include "SceneVisRenderingCullingModule.h" // For export macro
#include "vtkOpenGLPolyDataMapper.h"

#include <algorithm> // For std::min
#include <memory>    // For std::unique_ptr
#include <vector>    // For std::vector

class SCENEVISRENDERINGCULLING_EXPORT vtkChunkedPolyDataMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkChunkedPolyDataMapper* New();
  vtkTypeMacro(vtkChunkedPolyDataMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void RenderPieceStart(vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow*) override;

  /// Maps the scalars of the geometry drawn (the reordered copy) rather than those of the input.
  using vtkOpenGLPolyDataMapper::MapScalars;
  vtkUnsignedCharArray* MapScalars(double alpha) override;

  ///@{
  /// Target number of triangles per chunk (a chunk holds at most this many unless one polygon
  /// has more). Default 2048. Changing it re-partitions at the next render.
  vtkSetClampMacro(ChunkSize, int, 1, VTK_INT_MAX);
  vtkGetMacro(ChunkSize, int);
  ///@}

  // The culling switches below take effect at the next render and, unlike other mapper settings,
  // do not call Modified(): toggling them never rebuilds the vertex buffers.

  ///@{
  /// Frustum culling of chunks (exact, conservative). Default on.
  void SetFrustumCulling(bool on) { this->FrustumCulling = on; }
  vtkGetMacro(FrustumCulling, bool);
  vtkBooleanMacro(FrustumCulling, bool);
  ///@}

  ///@{
  /// Normal-cone (clustered back-face) culling of chunks, active only when the actor is drawn
  /// with back-face culling (see the class documentation). Default on.
  void SetNormalConeCulling(bool on) { this->NormalConeCulling = on; }
  vtkGetMacro(NormalConeCulling, bool);
  vtkBooleanMacro(NormalConeCulling, bool);
  ///@}

  ///@{
  /// APPROXIMATE small-feature culling in pixels (projected bounding-sphere diameter). 0 = off
  /// (default).
  void SetMinimumPixelSize(double pixels)
  {
    this->MinimumPixelSize = pixels > 0.0 ? std::min(pixels, VTK_DOUBLE_MAX) : 0.0;
  }
  vtkGetMacro(MinimumPixelSize, double);
  ///@}

  ///@{
  /// Statistics of the last render of this mapper.
  vtkIdType GetNumberOfChunks() const;
  vtkIdType GetNumberOfTriangles() const;
  vtkIdType GetNumberOfNodesVisited() const;
  vtkIdType GetNumberOfChunksTested() const;
  vtkIdType GetNumberOfChunksDrawn() const;
  vtkIdType GetNumberOfChunksCulledByFrustum() const;
  vtkIdType GetNumberOfChunksCulledByNormalCone() const;
  vtkIdType GetNumberOfChunksCulledBySize() const;
  vtkIdType GetNumberOfTrianglesDrawn() const;
  vtkIdType GetNumberOfDrawCalls() const;
  /// Whether the last render drew everything (see the class documentation for when).
  bool GetCullingSkipped() const;
  /// Seconds of the last partition build and of the last per-frame cull.
  double GetLastPartitionTime() const;
  double GetLastCullTime() const;
  ///@}

  ///@{
  /// Counters since construction: partitions built, vertex buffer (re)builds.
  vtkIdType GetNumberOfPartitionBuilds() const;
  vtkIdType GetNumberOfVertexBufferBuilds() const;
  ///@}

  /// Input cell ids of the polygons drawn by the last render (ascending chunk order).
  void GetDrawnCellIds(std::vector<vtkIdType>& cellIds) const;
  /// Input cell id of cell @p id of the reordered copy (as reported by picking); -1 if invalid.
  vtkIdType GetInputCellId(vtkIdType id) const;

protected:
  vtkChunkedPolyDataMapper();
  ~vtkChunkedPolyDataMapper() override;

  void UpdateCameraShiftScale(vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;

  int ChunkSize = 2048;
  bool FrustumCulling = true;
  bool NormalConeCulling = true;
  double MinimumPixelSize = 0.0;

private:
  vtkChunkedPolyDataMapper(const vtkChunkedPolyDataMapper&) = delete;
  void operator=(const vtkChunkedPolyDataMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif

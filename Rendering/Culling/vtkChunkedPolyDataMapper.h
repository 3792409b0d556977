/**
 * @class   vtkChunkedPolyDataMapper
 * @brief   A polydata mapper that culls spatial chunks of ONE big mesh per frame without
 *          touching its GPU buffers.
 *
 * vtkOctreeCuller culls whole props; a CAD model is often one merged mesh (one prop), which a prop
 * culler can only draw entirely. This mapper
 *
 * 1. owns the triangle list it draws: once per input (again only when the input or ChunkSize
 *    changes) it turns the polygons and triangle strips of its input into triangles exactly as
 *    vtkOpenGLIndexBufferObject does (polygons of any size fanned from their first point, strips
 *    with alternating winding), leaving out every triangle with two points at the same
 *    coordinates (they cover no pixel; VTK drops them from its index buffer too) and every
 *    triangle with a point id out of range. Each triangle remembers its input cell.
 * 2. partitions those triangles into spatial chunks: a binary tree of median splits over
 *    triangle centroids along the largest extent, until a node holds at most ChunkSize
 *    triangles (default 2048). Each tree node covers a contiguous range of chunks; each chunk a
 *    contiguous range of triangles.
 * 3. draws a copy of the input whose polygons are those triangles, chunk by chunk, and which has
 *    no strips (points, point data, verts and lines are shared with the input; cell data get one
 *    tuple per triangle, that of its input cell). Every cell of the copy is a triangle that VTK
 *    keeps, so triangle k of the index buffer that vtkOpenGLPolyDataMapper builds from the copy
 *    is our triangle k whatever VTK's rule for degenerate cells, and every chunk and every tree
 *    node is ONE contiguous range of that index buffer. The buffers are built once.
 * 4. per frame (in RenderPieceStart, with the camera that draws) traverses the tree in the
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
 *   positive determinant): a chunk whose triangles, as wound when drawn, all face away from the
 *   eye is not drawn (conservative, see scenevis/NormalCone.h);
 * - small features (MinimumPixelSize, default 0 = off): APPROXIMATE, chunks whose bounding
 *   sphere projects below that many pixels are not drawn although they may cover a few pixels.
 *
 * Drawing is exactly that of vtkOpenGLPolyDataMapper for the triangles drawn: same triangles,
 * shaders and buffers, the chunk order among the triangles drawn, cell scalars / cell normals
 * through the gl_PrimitiveID offset set per range. Degenerate triangles, polygons of any size,
 * strips and verts / lines / polygons / strips in one input are all culled. Culling is skipped
 * (the superclass draws everything; GetCullingSkipped() says so) only for what it cannot
 * express as triangle ranges: a hardware selector (picking: the copy is drawn, see below),
 * vertex visibility, an unusable camera, more than 2^31 / 3 triangles, and representations
 * other than surface or edge visibility: those show cell outlines, so the superclass draws the
 * input itself rather than the copy (switching rebuilds the buffers).
 *
 * Limits: picking a surface reports cell ids of the copy (GetInputCellId() maps them back);
 * memory: the copy's triangle connectivity (32-bit ids below 2^31 points; the occlusion raster
 * reads it in place, and it is uploaded as the index buffer in place, without VTK's temporary
 * vector of the same indices), 4 bytes per triangle naming its input cell, and one cell-data tuple per
 * triangle are a second copy of the input's (inputs of 2^32 points or cells and more are drawn
 * whole, as VTK's 32-bit index buffers cannot address them).
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
#include <string>    // For std::string
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
  /// Largest number of triangles per chunk. Default 2048. Changing it re-partitions at the next
  /// render.
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
  /// Occlusion culling between the mesh's own chunks (default off): the chunk tree is traversed
  /// front to back, chunks drawn are rasterized into a software depth buffer
  /// (scenevis/OcclusionBuffer.h) and chunks hidden behind them are not drawn. Conservative
  /// (a chunk is culled only if its box is hidden at every pixel centre); active only for an
  /// opaque surface. Costs the rasterization of the visible chunks' triangles on the CPU: it
  /// pays when much of the mesh in view is hidden (one big CAD mesh seen from close by).
  void SetOcclusionCulling(bool on) { this->OcclusionCulling = on; }
  vtkGetMacro(OcclusionCulling, bool);
  vtkBooleanMacro(OcclusionCulling, bool);
  ///@}

  ///@{
  /// Record the chunks' occluder rasterization of every render from the next one on into this
  /// file (created, or emptied), for scenevis_occlusion_replay, as
  /// vtkOcclusionCuller::SetOcclusionRecordFile() does (coordinates are the mesh's own). Null or
  /// "" (default): nothing is recorded. A file that cannot be written is an error, and
  /// recording stops.
  void SetOcclusionRecordFile(const char* fileName);
  const char* GetOcclusionRecordFile() const { return this->OcclusionRecordFile.c_str(); }
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
  /// Triangles in the list drawn (degenerate ones left out), culled or not.
  vtkIdType GetNumberOfTriangles() const;
  vtkIdType GetNumberOfNodesVisited() const;
  vtkIdType GetNumberOfChunksTested() const;
  vtkIdType GetNumberOfChunksDrawn() const;
  vtkIdType GetNumberOfChunksCulledByFrustum() const;
  vtkIdType GetNumberOfChunksCulledByNormalCone() const;
  vtkIdType GetNumberOfChunksCulledBySize() const;
  vtkIdType GetNumberOfChunksCulledByOcclusion() const;
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

  /// Kibibytes held for the copy drawn (its polygons and cell data, the map to input cells),
  /// beyond the input: 0 before the first render. The copy carries only the cell arrays the
  /// mapper can draw with (the scalars its scalar mode selects, cell normals, ghost flags, the
  /// arrays named by its selection settings); choosing another array to colour by copies it.
  unsigned long GetCopyMemorySize() const;

  /// Input cell ids of the polygons and strips with a triangle drawn by the last render, each
  /// once (in chunk order of their first triangle drawn). Verts and lines are not listed.
  void GetDrawnCellIds(std::vector<vtkIdType>& cellIds) const;
  /// Input cell id of cell @p id of the copy drawn (as reported by picking: verts and lines keep
  /// their ids, triangle k of the copy is cell number verts + lines + k); -1 if invalid.
  vtkIdType GetInputCellId(vtkIdType id) const;

protected:
  vtkChunkedPolyDataMapper();
  ~vtkChunkedPolyDataMapper() override;

  void UpdateCameraShiftScale(vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void BuildIBO(vtkRenderer* ren, vtkActor* act, vtkPolyData* poly) override;

  int ChunkSize = 2048;
  bool FrustumCulling = true;
  bool NormalConeCulling = true;
  double MinimumPixelSize = 0.0;
  bool OcclusionCulling = false;
  std::string OcclusionRecordFile;

private:
  vtkChunkedPolyDataMapper(const vtkChunkedPolyDataMapper&) = delete;
  void operator=(const vtkChunkedPolyDataMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif

/**
 * @class   vtkOccluderRasterizer
 * @brief   Module-private: draws VTK actors as occluders into SceneVis's software depth buffer.
 *
 * Used by vtkOctreeCuller when occlusion culling is on (vtkOcclusionCuller). Per frame,
 * BeginFrame() sizes and clears the buffer for the renderer's viewport and camera; Draw(prop)
 * rasterizes a prop if OpenGL will draw it as an opaque surface, and does nothing otherwise:
 *
 * - only plain actors with a vtkPolyDataMapper whose input is a vtkPolyData, or a composite
 *   mapper's visible polydata blocks when no block has a colour, opacity or material of its own
 *   (ParaView's representations, VTK's multiblock readers; vtkMapperPolyData), surface
 *   representation, opacity 1 and no translucent geometry (textures / scalars with alpha), no
 *   mapper clipping planes, no z-buffer shift (VTK_RESOLVE_SHIFT_ZBUFFER) occlude; translucent
 *   props never occlude (they can still be culled behind opaque ones);
 * - face culling as the property says (an actor matrix with a negative determinant and face
 *   culling on: not an occluder, the winding that OpenGL sees is not certain);
 * - triangles, triangle strips (OpenGL's alternating order) and polygons of 4+ points that are
 *   planar and convex (then every triangulation, VTK's included, covers the same area); other
 *   polygons are left out (leaving out an occluder is always conservative);
 * - polygon offset (VTK_RESOLVE_POLYGON_OFFSET) is added to the occluders' depth bounds;
 * - of a closed, consistently oriented mesh only the outward-facing triangles are rasterized
 *   (the others are always behind them: a subset of what OpenGL draws, so still conservative,
 *   at half the work; with the eye inside such a mesh it occludes nothing).
 *
 * Triangle lists and edge neighbours are cached per vtkPolyData (shared by all actors that draw
 * it: instances cost one entry) and rebuilt when its MTime changes; entries not used for a while
 * are dropped when the cache exceeds CacheBudget bytes.
 */
#ifndef vtkOccluderRasterizer_h
#define vtkOccluderRasterizer_h

#include "vtkType.h"
#include "vtkWeakPointer.h"

#include "vtkOcclusionRecordFile.h"

#include "scenevis/OcclusionBuffer.h"

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

class vtkPoints;
class vtkPolyData;
class vtkProp;

class vtkOccluderRasterizer
{
public:
  /// Viewport size in pixels and the camera's clip-from-world matrix (VTK's row-major, as
  /// vtkCamera::GetCompositeProjectionTransformMatrix(aspect, -1, 1) returns it).
  void BeginFrame(int width, int height, const double clipFromWorldRowMajor[16]);
  /// Rasterize @p prop if it is an opaque occluder (see the class comment); @p bounds: its world
  /// bounds as the culler knows them (for occluder selection); @p placement: the model-to-world
  /// matrix to draw it with (16 values, row-major; a vtkInstancedActor's placement), instead of
  /// the actor's own.
  void Draw(vtkProp* prop, const double bounds[6], const double* placement = nullptr);
  /// Occluder selection alone, before any question to the actor, its mapper or its data (in a
  /// wide view nearly every prop is visible and most are too small to occlude; this is what such
  /// a prop costs): false, and counted in OccludersSkipped, if a prop with world bounds [lo, hi]
  /// and @p triangles OpenGL triangles covers fewer than MinimumPixelsPerTriangle pixels per
  /// triangle.
  bool WorthDrawing(const double lo[3], const double hi[3], vtkIdType triangles);

  scenevis::occlusion::MaskedDepthBuffer& Buffer() { return this->DepthBuffer; }

  /// The file this frame's rasterization is recorded to (vtkOcclusionCuller's
  /// SetOcclusionRecordFile()).
  vtkOcclusionRecordFile& Recording() { return this->RecordFile; }

  /// Occluder selection: a prop whose screen rectangle has fewer than this many pixels per
  /// triangle is not rasterized (it costs more than it hides: small, finely tessellated parts).
  /// 0 rasterizes every visible opaque prop. Leaving occluders out is always conservative.
  double MinimumPixelsPerTriangle = 0.0;
  vtkIdType OccludersSkipped = 0; ///< this frame, by MinimumPixelsPerTriangle (WorthDrawing()
                                  ///< counts props that would not occlude anyway too)

  ///@{
  /// This frame: props rasterized, their triangles, seconds spent in Draw().
  vtkIdType OccludersDrawn = 0;
  vtkIdType OccluderTriangles = 0;
  double DrawSeconds = 0.0;
  ///@}
  /// Bytes of cached triangle lists and neighbours; budget before unused entries are dropped.
  std::size_t CacheBytes = 0;
  std::size_t CacheBudget = std::size_t(256) << 20;

private:
  struct Mesh
  {
    vtkWeakPointer<vtkPolyData> Data;
    vtkMTimeType Time = 0;
    std::vector<std::uint32_t> Triangles; // 3 point ids each
    std::vector<std::uint32_t> Neighbors; // 3 per triangle
    /// Model-space boxes of runs of kTrianglesPerCluster triangles (buildTriangleClusters).
    std::vector<double> Clusters;
    /// Closed and consistently oriented (scenevis::occlusion::closedSurface(): every edge of a
    /// triangle with three distinct points has a neighbour): only the faces of one side can be
    /// nearest, those facing out (Outward: the signed volume is positive).
    bool Closed = false;
    bool Outward = true;
    std::uint64_t LastFrame = 0;
    std::size_t Bytes() const
    {
      return (this->Triangles.size() + this->Neighbors.size()) * 4 + this->Clusters.size() * 8;
    }
  };
  Mesh* MeshOf(vtkPolyData* data);
  /// Rasterize @p mesh of @p points (its polydata's) through @p clipFromModel (row-major).
  void DrawMesh(vtkPoints* points, const Mesh& mesh, const double clipFromModel[16],
    scenevis::occlusion::FaceCulling culling);
  /// Pixels of the viewport covered by the screen rectangle of world box @p bounds (the whole
  /// viewport when a corner is behind the eye or in front of the near plane).
  double ScreenArea(const double bounds[6]) const;
  void Evict();

  scenevis::occlusion::MaskedDepthBuffer DepthBuffer;
  vtkOcclusionRecordFile RecordFile;
  double ClipFromWorld[16] = { 0 };
  std::unordered_map<vtkPolyData*, Mesh> Meshes;
  std::vector<double> Points; // an occluder's points as doubles, when its array is neither
                              // float nor double
  std::uint64_t Frame = 0;
  // Draw() scratch: the polydata a prop's mapper draws, and their meshes.
  std::vector<vtkPolyData*> Leaves;
  std::vector<std::pair<vtkPolyData*, Mesh*>> LeafMeshes;
};

#endif

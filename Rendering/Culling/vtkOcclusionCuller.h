/**
 * @class   vtkOcclusionCuller
 * @brief   Frustum + occlusion culling of many props: what is hidden behind opaque props is not
 *          drawn, so a frame costs what is visible rather than what is in the frustum.
 *
 * A vtkOctreeCuller (same hierarchy over the props' bounds, same update modes, frustum and the
 * other tests) whose traversal also culls by occlusion, on the CPU, before VTK draws anything:
 *
 * 1. The props that were visible last frame and are still in the frustum are rasterized first
 *    into a software depth buffer of the renderer's viewport size (temporal coherence: they are
 *    the best first occluders).
 * 2. The hierarchy is traversed front to back, nearest child first. Each node's box is tested
 *    against the buffer; a hidden node is culled with its whole subtree. Each prop found visible
 *    is rasterized as an occluder before anything farther is tested.
 *
 * Conservative by construction (the buffer's contract, scenevis/OcclusionBuffer.h): a prop is
 * culled only if its bounding box is hidden at every pixel centre OpenGL samples behind opaque
 * props that are drawn this frame; margins cover the GPU's vertex snapping and depth precision.
 * There is no "few pixels" threshold. Which props occlude, and how (translucent props never
 * occlude but can be culled behind opaque ones; face culling; polygons left out), is listed in
 * vtkOccluderRasterizer.h; a prop that cannot occlude is still culled when hidden.
 *
 * Use it instead of VTK's vtkFrustumCoverageCuller:
 * @code
 * vtkNew<vtkOcclusionCuller> culler;
 * renderer->GetCullers()->RemoveAllItems();
 * renderer->AddCuller(culler);
 * @endcode
 * It pays when much of what is in the frustum is hidden: interiors, rows of parts, CAD assemblies
 * seen from close by. With everything visible it costs the rasterization of the visible props
 * (OccluderRasterTime) for nothing; vtkOctreeCuller is then the better choice.
 *
 * Statistics of the last Cull(): those of vtkOctreeCuller, plus props culled by occlusion,
 * occlusion tests (node and prop boxes), occluders drawn and their triangles, the time spent
 * rasterizing occluders and in the whole Cull(), and the memory of the depth buffer (12 bytes
 * per 8x4 pixels, 4 more per 32x16) and of the occluder cache (triangle lists with edge neighbours, 24 bytes per
 * triangle of each distinct mesh rasterized, bounded by OccluderCacheBudget).
 *
 * @sa vtkOctreeCuller vtkCuller
 */
#ifndef vtkOcclusionCuller_h
#define vtkOcclusionCuller_h

#include "SceneVisRenderingCullingModule.h" // For export macro
#include "vtkOctreeCuller.h"

class SCENEVISRENDERINGCULLING_EXPORT vtkOcclusionCuller : public vtkOctreeCuller
{
public:
  static vtkOcclusionCuller* New();
  vtkTypeMacro(vtkOcclusionCuller, vtkOctreeCuller);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Occlusion culling on (default) or off (then it is a vtkOctreeCuller).
  void SetOcclusionCulling(bool on);
  bool GetOcclusionCulling() const { return this->OcclusionCulling; }
  vtkBooleanMacro(OcclusionCulling, bool);
  ///@}

  ///@{
  /// Bytes of occluder triangle lists kept between frames (default 256 MiB); meshes not used
  /// recently are dropped beyond it and rebuilt when they occlude again.
  void SetOccluderCacheBudget(vtkIdType bytes);
  vtkIdType GetOccluderCacheBudget() const;
  ///@}

  ///@{
  /// Occluder selection: a visible prop is rasterized as an occluder only if its screen
  /// rectangle has at least this many pixels per triangle (default 1): small, finely
  /// tessellated parts cost more to rasterize than they hide. 0 rasterizes every visible opaque
  /// prop. Any value is conservative (fewer occluders only cull less).
  vtkSetClampMacro(OccluderMinimumPixelsPerTriangle, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(OccluderMinimumPixelsPerTriangle, double);
  ///@}

  ///@{
  /// Record the occluder rasterization of every Cull() from the next one on into this file
  /// (created, or emptied), for scenevis_occlusion_replay: the depth buffer's size and camera,
  /// then each occluder's triangles as rasterized (scenevis/OcclusionRecording.h). The file is
  /// complete after each Cull(). Null or "" (default): nothing is recorded. A file that cannot
  /// be written is an error, and recording stops.
  void SetOcclusionRecordFile(const char* fileName);
  const char* GetOcclusionRecordFile() const { return this->OcclusionRecordFile.c_str(); }
  ///@}
  ///@{
  /// Statistics of the last Cull().
  vtkIdType GetNumberOfPropsCulledByOcclusion() const
  {
    return this->NumberOfPropsCulledByOcclusion;
  }
  vtkIdType GetNumberOfOcclusionTests() const { return this->NumberOfOcclusionTests; }
  vtkIdType GetNumberOfOccludersDrawn() const { return this->NumberOfOccludersDrawn; }
  /// Visible props not rasterized by OccluderMinimumPixelsPerTriangle (the selection comes
  /// first, so translucent props that would not occlude anyway are counted too).
  vtkIdType GetNumberOfOccludersSkipped() const { return this->NumberOfOccludersSkipped; }
  vtkIdType GetNumberOfOccluderTriangles() const { return this->NumberOfOccluderTriangles; }
  /// Milliseconds spent rasterizing occluders (part of GetCullTime()).
  double GetOccluderRasterTime() const { return this->OccluderRasterTime; }
  /// Milliseconds of the whole Cull().
  double GetCullTime() const { return this->CullTime; }
  vtkIdType GetDepthBufferBytes() const { return static_cast<vtkIdType>(this->DepthBufferBytes); }
  vtkIdType GetOccluderCacheBytes() const
  {
    return static_cast<vtkIdType>(this->OccluderCacheBytes);
  }
  ///@}

protected:
  vtkOcclusionCuller();
  ~vtkOcclusionCuller() override;

private:
  vtkOcclusionCuller(const vtkOcclusionCuller&) = delete;
  void operator=(const vtkOcclusionCuller&) = delete;
};

#endif

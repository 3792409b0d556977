/**
 * @class   vtkSceneVisRenderView
 * @brief   ParaView's render view with translucent geometry blended in the order it is drawn.
 *
 * ParaView's render view draws translucent surfaces with depth peeling (or, with peeling off,
 * VTK's weighted order-independent blending): both ignore the order of the primitives, and
 * peeling is exact only with enough peels. This view is a vtkPVRenderView whose render pass is
 * SceneVis's vtkOrderedTranslucentPass (plain "over" blending in primitive order, depth writes
 * off) with, by default, vtkBSPTranslucentPass as its translucent step: the polygons of every
 * translucent surface shown are drawn in one exact back-to-front order for the view's camera,
 * every frame (BSP trees built once per input, the order updated as the camera moves).
 * SortTranslucentGeometry off: translucent geometry is drawn in the order of its cells, for
 * data already ordered by the BSP Sort or Painter Sort filters. The view's depth peeling
 * settings are ignored.
 *
 * Culling (SetCulling): VTK's frustum coverage culler, as ParaView's render view has (default),
 * or SceneVis's vtkOctreeCuller (a BVH over the view's props: frustum culling in O(log n)) or
 * vtkOcclusionCuller (the same, and props hidden behind nearer opaque ones are not drawn; a
 * conservative software depth buffer: no visible pixel is lost). Each representation is one
 * prop, so culling pays for scenes of many representations. On MPI ranks each rank culls its
 * own props with its own occluders, which is conservative for the composited image too (a prop
 * hidden behind geometry of the same rank is hidden in the depth-composited image). In
 * interactive renders that draw ParaView's decimated level-of-detail geometry (data above the
 * view's LOD threshold) props are not culled by occlusion: the occluders are the full-resolution
 * surfaces, which the decimated ones drawn in their place may not cover.
 *
 * Its proxy is "SceneVis Ordered Translucency" (views group, SceneVisRenderView), a RenderView
 * with every RenderView property, SortTranslucentGeometry and Culling.
 *
 * @sa vtkOrderedTranslucentPass vtkBSPSortFilter
 */

#ifndef vtkSceneVisRenderView_h
#define vtkSceneVisRenderView_h

#include "SceneVisParaViewViewsModule.h" // For export macro
#include "vtkPVRenderView.h"
#include "vtkSmartPointer.h" // For the cullers

class vtkBSPTranslucentPass;
class vtkCuller;
class vtkOctreeCuller;
class vtkOrderedTranslucentPass;
class vtkTranslucentPass;

class SCENEVISPARAVIEWVIEWS_EXPORT vtkSceneVisRenderView : public vtkPVRenderView
{
public:
  static vtkSceneVisRenderView* New();
  vtkTypeMacro(vtkSceneVisRenderView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Draw translucent polygons in an exact order for the camera, every frame (default on), or in
   * the order of their cells (off).
   */
  void SetSortTranslucentGeometry(bool sort);
  vtkGetMacro(SortTranslucentGeometry, bool);
  ///@}

  /// The translucent step while sorting (its counters: sorted actors, fragments, trees built).
  vtkBSPTranslucentPass* GetSortingPass() { return this->SortingPass; }

  enum CullingModes
  {
    CULLING_VTK = 0,      ///< VTK's vtkFrustumCoverageCuller (ParaView's own)
    CULLING_OCTREE = 1,   ///< vtkOctreeCuller
    CULLING_OCCLUSION = 2 ///< vtkOcclusionCuller
  };
  ///@{
  /// How the view's renderer culls props (CullingModes; default CULLING_VTK).
  void SetCulling(int mode);
  vtkGetMacro(Culling, int);
  ///@}

  /// The SceneVis culler in use (vtkOcclusionCuller is a vtkOctreeCuller), null with VTK's.
  vtkOctreeCuller* GetSceneVisCuller() const;

protected:
  vtkSceneVisRenderView();
  ~vtkSceneVisRenderView() override;

  /// Occlusion culling off for the interactive renders that draw level-of-detail geometry.
  void Render(bool interactive, bool skip_rendering) override;

  bool SortTranslucentGeometry = true;
  int Culling = CULLING_VTK;
  vtkOrderedTranslucentPass* Steps;
  vtkBSPTranslucentPass* SortingPass;
  vtkTranslucentPass* DrawingOrderPass;
  vtkSmartPointer<vtkCuller> VTKCuller; ///< the renderer's own culler, put back for CULLING_VTK
  vtkSmartPointer<vtkOctreeCuller> OctreeCuller;    ///< made when first chosen
  vtkSmartPointer<vtkOctreeCuller> OcclusionCuller; ///< a vtkOcclusionCuller, when first chosen

private:
  vtkSceneVisRenderView(const vtkSceneVisRenderView&) = delete;
  void operator=(const vtkSceneVisRenderView&) = delete;
};

#endif

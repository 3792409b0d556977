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
 * settings are ignored. Its proxy is "SceneVis Ordered Translucency" (views group,
 * SceneVisRenderView), a RenderView with every RenderView property and SortTranslucentGeometry.
 *
 * @sa vtkOrderedTranslucentPass vtkBSPSortFilter
 */

#ifndef vtkSceneVisRenderView_h
#define vtkSceneVisRenderView_h

#include "SceneVisParaViewViewsModule.h" // For export macro
#include "vtkPVRenderView.h"

class vtkBSPTranslucentPass;
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

protected:
  vtkSceneVisRenderView();
  ~vtkSceneVisRenderView() override;

  bool SortTranslucentGeometry = true;
  vtkOrderedTranslucentPass* Steps;
  vtkBSPTranslucentPass* SortingPass;
  vtkTranslucentPass* DrawingOrderPass;

private:
  vtkSceneVisRenderView(const vtkSceneVisRenderView&) = delete;
  void operator=(const vtkSceneVisRenderView&) = delete;
};

#endif

/**
 * @class   vtkSceneVisRenderView
 * @brief   ParaView's render view with translucent geometry blended in the order it is drawn.
 *
 * ParaView's render view draws translucent surfaces with depth peeling (or, with peeling off,
 * VTK's weighted order-independent blending): both ignore the order of the primitives, so a
 * surface ordered back to front by SceneVis (the BSP Sort and Painter Sort filters) shows no
 * better than an unordered one. This view is a vtkPVRenderView whose render pass is SceneVis's
 * vtkOrderedTranslucentPass (plain "over" blending in primitive order, depth writes off): what is
 * drawn back to front composites exactly, as in the SceneVis VTK modules. The view's depth
 * peeling settings are ignored. Its proxy is "SceneVis Ordered Translucency" (views group,
 * SceneVisRenderView), a RenderView with every RenderView property.
 *
 * @sa vtkOrderedTranslucentPass vtkBSPSortFilter
 */

#ifndef vtkSceneVisRenderView_h
#define vtkSceneVisRenderView_h

#include "SceneVisParaViewViewsModule.h" // For export macro
#include "vtkPVRenderView.h"

class SCENEVISPARAVIEWVIEWS_EXPORT vtkSceneVisRenderView : public vtkPVRenderView
{
public:
  static vtkSceneVisRenderView* New();
  vtkTypeMacro(vtkSceneVisRenderView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSceneVisRenderView();
  ~vtkSceneVisRenderView() override = default;

private:
  vtkSceneVisRenderView(const vtkSceneVisRenderView&) = delete;
  void operator=(const vtkSceneVisRenderView&) = delete;
};

#endif

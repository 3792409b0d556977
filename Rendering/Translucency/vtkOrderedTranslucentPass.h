/**
 * @class   vtkOrderedTranslucentPass
 * @brief   The standard render steps, with translucent geometry blended in primitive order.
 *
 * VTK 9.1 renders translucent geometry with weighted-average order-independent translucency
 * whenever depth peeling is off, and that blending ignores the order in which primitives are
 * drawn: a back-to-front order made by vtkBSPSortFilter or vtkDepthSortPolyData does not show on
 * screen. This pass is a vtkRenderStepsPass (lights, opaque, translucent, volumes, overlay) whose
 * translucent step is a plain vtkTranslucentPass: ordinary "over" alpha blending with depth writes
 * off, so primitives drawn far-to-near composite exactly.
 *
 * Usage:
 * @code
 * vtkNew<vtkOrderedTranslucentPass> pass;
 * renderer->SetPass(pass);
 * @endcode
 * The renderer's depth-peeling settings are ignored while the pass is set. Its FXAA setting
 * (vtkRenderer::SetUseFXAA) is honoured: vtkOpenGLRenderer applies FXAA after the translucent
 * geometry only in its own geometry step, which a render pass replaces, so this pass applies it
 * itself at the same point (after the translucent step, before volumes and overlays). Without
 * that, a view with FXAA on (ParaView's default) drew this pass's images aliased while every
 * other view was anti-aliased: 0.9 % of an engine's pixels (its edges) off by more than 16.
 * Under parallel compositing (vtkSynchronizedRenderers) the renderer's FXAA is off during the
 * render and applied to the composited image instead.
 *
 * @sa vtkRenderStepsPass vtkTranslucentPass vtkOrderIndependentTranslucentPass
 */

#ifndef vtkOrderedTranslucentPass_h
#define vtkOrderedTranslucentPass_h

#include "SceneVisRenderingTranslucencyModule.h" // For export macro
#include "vtkRenderStepsPass.h"

class SCENEVISRENDERINGTRANSLUCENCY_EXPORT vtkOrderedTranslucentPass : public vtkRenderStepsPass
{
public:
  static vtkOrderedTranslucentPass* New();
  vtkTypeMacro(vtkOrderedTranslucentPass, vtkRenderStepsPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The render steps, with the renderer's FXAA (when on) after the translucent step.
  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

protected:
  vtkOrderedTranslucentPass();
  ~vtkOrderedTranslucentPass() override;

private:
  class FXAAStep;
  FXAAStep* TranslucentThenFXAA; ///< wraps TranslucentPass during Render when FXAA is on

  vtkOrderedTranslucentPass(const vtkOrderedTranslucentPass&) = delete;
  void operator=(const vtkOrderedTranslucentPass&) = delete;
};

#endif

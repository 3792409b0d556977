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
 * The renderer's depth-peeling settings are ignored while the pass is set.
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

protected:
  vtkOrderedTranslucentPass();
  ~vtkOrderedTranslucentPass() override = default;

private:
  vtkOrderedTranslucentPass(const vtkOrderedTranslucentPass&) = delete;
  void operator=(const vtkOrderedTranslucentPass&) = delete;
};

#endif

#include "scenevis/testing/RenderWindow.h"

#include <vtkNew.h>
#include <vtkRenderStepsPass.h>
#include <vtkRenderer.h>

namespace scenevis
{
namespace testing
{

void EnableOrderedAlphaBlending(vtkRenderer* renderer)
{
  if (!renderer)
  {
    return;
  }
  // vtkRenderStepsPass's translucent step is the plain vtkTranslucentPass: ordinary "over"
  // blending in primitive order. The default pipeline would use weighted-average OIT instead.
  vtkNew<vtkRenderStepsPass> steps;
  renderer->SetPass(steps);
  renderer->SetUseDepthPeeling(0);
}

} // namespace testing
} // namespace scenevis

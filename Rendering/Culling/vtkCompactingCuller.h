/**
 * @class   vtkCompactingCuller
 * @brief   The vtkCuller contract in one place, for cullers that decide prop by prop.
 *
 * vtkRenderer::UpdateCulling hands each of its cullers in turn the props still to be drawn. A
 * culler must then
 * - move the props it culls to the end of the list, the kept ones first in their relative order
 *   (a culler may reorder the kept ones on purpose, e.g. to sort them), and shorten listLength
 *   to the props kept;
 * - when @c initialized is 0 (it is the first culler this frame), set every kept prop's
 *   render-time multiplier to 1; otherwise keep what earlier cullers set (multiply by 1);
 * - set @c initialized to 1 and return the sum of the kept props' multipliers, which the
 *   renderer divides by: never 0 (or NaN) while props remain.
 * Culled props' multipliers are not touched: nothing reads them past listLength.
 *
 * Subclasses decide which props to keep, then call CompactPropList() and
 * SumRenderTimeMultipliers(). vtkOctreeCuller, vtkOcclusionCuller and vtkPortalCuller do.
 */

#ifndef vtkCompactingCuller_h
#define vtkCompactingCuller_h

#include "SceneVisRenderingCullingModule.h" // For export macro
#include "vtkCuller.h"

#include <vector> // For std::vector

class vtkProp;
class vtkRenderer;

class SCENEVISRENDERINGCULLING_EXPORT vtkCompactingCuller : public vtkCuller
{
public:
  vtkTypeMacro(vtkCompactingCuller, vtkCuller);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkCompactingCuller();
  ~vtkCompactingCuller() override;

  /// Moves the props of @p propList whose @p keep flag (one per list position) is 0 to the end
  /// of the list, the kept ones first in their relative order; returns how many are kept.
  int CompactPropList(vtkProp** propList, int listLength, const unsigned char* keep);

  /// Render-time multipliers of the @p kept props at the head of @p propList, and the total
  /// Cull() returns (see the class comment); sets @p initialized to 1.
  /// @p multiplierIsOne and @p flagOf (optional, both or neither): flags the subclass keeps for
  /// its props, the flag of the list's i-th prop at multiplierIsOne[flagOf[i]]. A set flag says
  /// this culler left the prop's multiplier at 1 while it was the renderer's only culler; while
  /// it still is, such a prop is not written again (for 50k props that saves a cache miss each).
  double SumRenderTimeMultipliers(vtkRenderer* ren, vtkProp** propList, int kept,
    int& initialized, unsigned char* multiplierIsOne = nullptr,
    const unsigned int* flagOf = nullptr);

private:
  vtkCompactingCuller(const vtkCompactingCuller&) = delete;
  void operator=(const vtkCompactingCuller&) = delete;

  std::vector<vtkProp*> Culled; // scratch of CompactPropList
};

#endif

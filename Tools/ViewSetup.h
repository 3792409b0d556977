// The view the commands render: the background, and the camera set up from the camera options
// (or one camera of --cameras) and the scene's bounds.
#ifndef scenevis_tool_ViewSetup_h
#define scenevis_tool_ViewSetup_h

#include "CameraFile.h"

#include <vtkSceneVisImageCompare.h>

class vtkPolyData;
class vtkRenderer;

namespace scenevis
{
namespace tool
{

/// The background of every render, exact in 8 bits (image comparisons tell it from the scene).
constexpr double kBackground[3] = { 26 / 255.0, 26 / 255.0, 31 / 255.0 }; // exact in 8 bits
const scenevis::headless::Rgb kBackgroundRgb = { 26, 26, 31 };

/// The camera's fixed clipping range (--clipping-range, a camera's "clipping_range"), else one
/// fitted to the visible props, as after every camera move.
void ResetClippingRange(const CameraSpec& spec, vtkRenderer* renderer);

/// Sets up the renderer's camera for a scene of @p bounds: the eye (and focal point, else the
/// scene's centre) of @p spec, else a three-quarter view that fits the scene; the default up is
/// +z when @p zUp, else +y. Throws UsageError for an eye at the default focal point or an up
/// along the view direction.
void SetUpCamera(
  const CameraSpec& spec, vtkRenderer* renderer, const double bounds[6], bool zUp = false);

/// The same for the bounds of @p pd.
void SetUpCamera(const CameraSpec& spec, vtkRenderer* renderer, vtkPolyData* pd, bool zUp = false);

} // namespace tool
} // namespace scenevis

#endif

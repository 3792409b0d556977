// The view the commands render: background and camera.
#include "ViewSetup.h"

#include "Options.h"

#include <vtkCamera.h>
#include <vtkMath.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>

namespace scenevis
{
namespace tool
{

void ResetClippingRange(const CameraSpec& spec, vtkRenderer* renderer)
{
  if (spec.FixedClippingRange())
    renderer->GetActiveCamera()->SetClippingRange(spec.clippingRange);
  else
    renderer->ResetCameraClippingRange();
}

void SetUpCamera(const CameraSpec& spec, vtkRenderer* renderer, const double bounds[6], bool zUp)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(spec.parallel);
  const double center[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const double defaultUp[3] = { 0.0, zUp ? 0.0 : 1.0, zUp ? 1.0 : 0.0 };
  const double* up = spec.hasUp ? spec.up : defaultUp;
  if (spec.hasEye)
  {
    if (!spec.hasFocal && std::equal(spec.eye, spec.eye + 3, center))
      throw UsageError("--camera: the eye is the scene's centre, the default focal point; give "
                       "a focal point too (EX,EY,EZ,FX,FY,FZ)");
    const double* focal = spec.hasFocal ? spec.focal : center;
    const double direction[3] = { focal[0] - spec.eye[0], focal[1] - spec.eye[1],
      focal[2] - spec.eye[2] };
    double side[3];
    vtkMath::Cross(direction, up, side);
    // An up along the view direction leaves VTK no view plane (a NaN view-up): an up given is
    // a usage error, the default one is swapped for the other default axis.
    const double alternativeUp[3] = { 0.0, zUp ? 1.0 : 0.0, zUp ? 0.0 : 1.0 };
    if (vtkMath::Norm(side) <= 1e-9 * vtkMath::Norm(direction) * vtkMath::Norm(up))
    {
      if (spec.hasUp)
        throw UsageError("--up is parallel to the view direction from --camera");
      up = alternativeUp;
    }
    camera->SetPosition(spec.eye);
    camera->SetFocalPoint(focal);
    camera->SetViewUp(up[0], up[1], up[2]);
    camera->OrthogonalizeViewUp();
    // Everything the camera does not give is reset: with --cameras, the renderer's camera still
    // holds the previous camera's values. Unless given, the parallel scale shows the whole scene
    // (its bounding sphere, with the default view's margin) from anywhere.
    camera->SetViewAngle(spec.viewAngle > 0.0 ? spec.viewAngle : 30.0);
    const double radius = 0.5 *
      std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
        (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
        (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    camera->SetParallelScale(
      spec.parallelScale > 0.0 ? spec.parallelScale : std::max(radius, 1e-12) / 1.1);
    ResetClippingRange(spec, renderer);
    return;
  }
  camera->SetFocalPoint(center);
  // Start looking along -up x (the horizontal axis) so that azimuth and elevation give a
  // three-quarter view from above whatever the up axis.
  if (std::abs(up[2]) > 0.9 * std::sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]))
    camera->SetPosition(center[0], center[1] - 1.0, center[2]);
  else
    camera->SetPosition(center[0], center[1], center[2] + 1.0);
  camera->SetViewUp(up[0], up[1], up[2]);
  camera->Azimuth(30.0);
  camera->Elevation(25.0);
  camera->OrthogonalizeViewUp();
  // From the scene's bounds, not the props': the sorted pipeline has not run yet. VTK fits the
  // scene's bounding sphere into its default 30-degree view angle (and resets the angle to it).
  renderer->ResetCamera(bounds);
  if (spec.viewAngle > 0.0 && !spec.parallel)
  {
    // The same fit in the angle given: the distance that keeps the sphere in view goes with
    // 1 / sin(angle / 2). Zoom(1.1) would narrow the angle, so the margin is a dolly too.
    const double halfAngle = vtkMath::RadiansFromDegrees(spec.viewAngle / 2.0);
    camera->SetViewAngle(spec.viewAngle);
    camera->Dolly(1.1 * std::sin(halfAngle) / std::sin(vtkMath::RadiansFromDegrees(15.0)));
    renderer->ResetCameraClippingRange(bounds);
  }
  else
  {
    camera->Zoom(1.1);
  }
  if (spec.parallelScale > 0.0)
    camera->SetParallelScale(spec.parallelScale);
  if (spec.FixedClippingRange())
    camera->SetClippingRange(spec.clippingRange);
}

void SetUpCamera(const CameraSpec& spec, vtkRenderer* renderer, vtkPolyData* pd, bool zUp)
{
  double bounds[6];
  pd->GetBounds(bounds); // finite: LoadScene removed cells with NaN/Inf points
  SetUpCamera(spec, renderer, bounds, zUp);
}

} // namespace tool
} // namespace scenevis

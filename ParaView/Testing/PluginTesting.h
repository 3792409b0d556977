// What the plugin's test drivers share (header-only: the main build's test harness is built
// against the system's VTK 9.1 and cannot be linked with ParaView's VTK 9.2): checks that count
// failures, render views made as paraview.simple makes them, and the image comparison the
// issue's targets are stated in (mean difference per channel, pixels off by more than 16).
#ifndef SceneVisPluginTesting_h
#define SceneVisPluginTesting_h

#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSaveScreenshotProxy.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVector.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

namespace scenevis_pvtest
{
inline int& Failures()
{
  static int failures = 0;
  return failures;
}

inline void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok:   " : "FAIL: ") << what << "\n";
  Failures() += ok ? 0 : 1;
}

/// A camera for NewView(): looking at @p focal from @p eye, y up, 30 degrees.
struct ViewCamera
{
  double eye[3];
  double focal[3];
};

/**
 * A render view proxy of @p name (views group) of @p size x @p size pixels with @p camera and no
 * orientation axes; @p peels > 0: depth peeling with that many peels, 0: peeling off, -1:
 * ParaView's defaults left as they are; @p sort: SortTranslucentGeometry of the SceneVis view.
 */
inline vtkSmartPointer<vtkSMViewProxy> NewView(vtkSMSessionProxyManager* pxm,
  vtkSMParaViewPipelineController* controller, const char* name, const ViewCamera& camera, int size,
  int peels, bool sort = false)
{
  vtkSmartPointer<vtkSMViewProxy> view;
  view.TakeReference(vtkSMViewProxy::SafeDownCast(pxm->NewProxy("views", name)));
  if (!view)
  {
    return view;
  }
  controller->InitializeProxy(view);
  const int viewSize[2] = { size, size };
  vtkSMPropertyHelper(view, "ViewSize").Set(viewSize, 2);
  vtkSMPropertyHelper(view, "OrientationAxesVisibility").Set(0);
  vtkSMPropertyHelper(view, "CameraPosition").Set(camera.eye, 3);
  vtkSMPropertyHelper(view, "CameraFocalPoint").Set(camera.focal, 3);
  const double up[3] = { 0.0, 1.0, 0.0 };
  vtkSMPropertyHelper(view, "CameraViewUp").Set(up, 3);
  vtkSMPropertyHelper(view, "CameraViewAngle").Set(30.0);
  if (peels >= 0)
  {
    vtkSMPropertyHelper(view, "DepthPeeling").Set(peels > 0 ? 1 : 0);
  }
  if (peels > 0)
  {
    vtkSMPropertyHelper(view, "MaximumNumberOfPeels").Set(peels);
  }
  if (view->GetProperty("SortTranslucentGeometry"))
  {
    vtkSMPropertyHelper(view, "SortTranslucentGeometry").Set(sort ? 1 : 0);
  }
  view->UpdateVTKObjects();
  return view;
}

/// @p source's output shown at @p opacity in @p view (of @p size x @p size), as an RGB image.
inline vtkSmartPointer<vtkImageData> Render(
  vtkSMViewProxy* view, vtkSMSourceProxy* source, int size, double opacity = 0.4)
{
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  vtkSMProxy* representation = controller->Show(source, 0, view);
  if (!representation)
  {
    return nullptr;
  }
  vtkSMPropertyHelper(representation, "Opacity").Set(opacity);
  representation->UpdateVTKObjects();
  view->StillRender();
  return vtkSMSaveScreenshotProxy::CaptureImage(view, vtkVector2i(size, size));
}

struct ImageError
{
  double mean = -1.0;      ///< mean absolute difference per channel, in 1/255 steps (-1: no images)
  double offPercent = 0.0; ///< pixels with a channel off by more than 16
};

inline ImageError Compare(vtkImageData* a, vtkImageData* b)
{
  ImageError error;
  auto* pa = a ? vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars()) : nullptr;
  auto* pb = b ? vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars()) : nullptr;
  if (!pa || !pb || pa->GetNumberOfTuples() != pb->GetNumberOfTuples() ||
    pa->GetNumberOfTuples() == 0 || pa->GetNumberOfComponents() < 3 ||
    pb->GetNumberOfComponents() < 3)
  {
    return error;
  }
  double sum = 0.0;
  vtkIdType off = 0;
  for (vtkIdType i = 0; i < pa->GetNumberOfTuples(); ++i)
  {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
    {
      const int d = std::abs(int(pa->GetTypedComponent(i, c)) - int(pb->GetTypedComponent(i, c)));
      sum += d;
      worst = std::max(worst, d);
    }
    off += worst > 16 ? 1 : 0;
  }
  error.mean = sum / (3.0 * pa->GetNumberOfTuples());
  error.offPercent = 100.0 * off / pa->GetNumberOfTuples();
  return error;
}

inline std::string Describe(const ImageError& e)
{
  return std::to_string(e.mean) + "/255 mean, " + std::to_string(e.offPercent) +
    " % of pixels off by > 16";
}
} // namespace scenevis_pvtest

#endif

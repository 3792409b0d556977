// Specification, on screen: the 64 overlapping translucent spheres sorted by vtkBSPSortFilter and
// drawn with ordered alpha blending (vtkOrderedTranslucentPass) look like the converged
// depth-peeling reference (100 peels), and like the PNG baseline a person has looked at. VTK's
// default weighted OIT, measured the same way, is far off - that is what the filter is for.
#include "vtkBSPSortFilter.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"

#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdlib>
#include <iostream>

namespace
{
namespace st = scenevis::testing;

enum class Method
{
  BSP,
  DepthPeeling100,
  DefaultOIT
};

vtkSmartPointer<vtkImageData> Render(Method method)
{
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(400, 400);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkDemoSceneSource> spheres;
  spheres->SetTriangleCount(20000);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(5.5, 3.7, 7.3);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewAngle(40);

  vtkNew<vtkBSPSortFilter> sorter;
  vtkNew<vtkOrderedTranslucentPass> ordered;
  switch (method)
  {
    case Method::BSP:
      sorter->SetInputConnection(spheres->GetOutputPort());
      sorter->SetCamera(camera);
      sorter->SetProp3D(actor);
      mapper->SetInputConnection(sorter->GetOutputPort());
      renderer->SetPass(ordered);
      break;
    case Method::DepthPeeling100:
      mapper->SetInputConnection(spheres->GetOutputPort());
      renderer->SetUseDepthPeeling(1);
      renderer->SetMaximumNumberOfPeels(100);
      renderer->SetOcclusionRatio(0.0);
      break;
    case Method::DefaultOIT:
      mapper->SetInputConnection(spheres->GetOutputPort());
      break;
  }
  renderer->ResetCameraClippingRange(-2.5, 2.5, -2.5, 2.5, -2.5, 2.5);
  return st::CaptureImage(window);
}
} // namespace

int TestBSPSortFilterSpheresImage(int, char*[])
{
  st::StrictVtkOutput strict;
  int failures = 0;
  vtkSmartPointer<vtkImageData> bsp = Render(Method::BSP);
  vtkSmartPointer<vtkImageData> peeled = Render(Method::DepthPeeling100);
  vtkSmartPointer<vtkImageData> oit = Render(Method::DefaultOIT);

  const st::ImageDifference bspError = st::CompareImages(bsp, peeled);
  const st::ImageDifference oitError = st::CompareImages(oit, peeled);
  // Artifacts for a person: the reference and where the BSP image differs from it.
  const std::string dir = st::TemporaryDirectory();
  st::WritePng(peeled, dir + "/BSPSortFilterSpheres.peel100.png");
  st::WritePng(oit, dir + "/BSPSortFilterSpheres.oit.png");
  st::WritePng(st::MakeDifferenceImage(bsp, peeled), dir + "/BSPSortFilterSpheres.peel100-diff.png");
  std::cout << "BSP + ordered alpha vs 100-peel reference: " << bspError.Summary() << "\n";
  std::cout << "VTK default OIT     vs 100-peel reference: " << oitError.Summary() << "\n";

  st::ImageThresholds exact;
  exact.maxMeanAbsError = 0.5;
  exact.maxCoveredBadFraction = 0.001;
  std::string why;
  if (!st::WithinThresholds(bspError, exact, &why))
  {
    std::cerr << "FAIL: the BSP image must match the peeling reference: " << why << "\n";
    ++failures;
  }
  if (!(oitError.meanAbsError > 4 * bspError.meanAbsError + 1.0))
  {
    std::cerr << "FAIL: the control (weighted OIT) should be clearly worse than the BSP order\n";
    ++failures;
  }
  const std::string baseline = st::CompareWithBaseline(bsp, "BSPSortFilterSpheres.png", exact);
  if (!baseline.empty())
  {
    std::cerr << "FAIL: " << baseline << "\n";
    ++failures;
  }
  return strict.ExitCode(failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE);
}

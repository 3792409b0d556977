// Example: exact translucency in an ordinary VTK pipeline.
//
//   source -> vtkPolyDataNormals -> vtkBSPSortFilter -> vtkPolyDataMapper -> vtkActor
//   renderer with vtkOrderedTranslucentPass (plain alpha blending in draw order)
//
// The BSP tree is built on the first render; each later frame only re-orders it for the new
// camera. Renders an orbit offscreen and writes one PNG per frame.
// Usage: TranslucentSorting [output-prefix] (default: translucent-sorting)
#include "vtkBSPSortFilter.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"

#include "vtkSceneVisHeadlessWindows.h"
#include "vtkSceneVisImageCompare.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  const std::string prefix = argc > 1 ? argv[1] : "translucent-sorting";

  // 64 overlapping translucent spheres, RGBA colours as cell scalars.
  vtkNew<vtkDemoSceneSource> spheres;
  spheres->SetTriangleCount(50000);

  // Smooth normals: the sorter interpolates them (and all other point data) at split points.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(spheres->GetOutputPort());

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkActor> actor;
  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputConnection(normals->GetOutputPort());
  sorter->SetCamera(renderer->GetActiveCamera());
  sorter->SetProp3D(actor);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sorter->GetOutputPort());
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  actor->SetMapper(mapper);
  renderer->AddActor(actor);

  // VTK 9.1 blends translucency order-independently by default; this pass respects our order.
  vtkNew<vtkOrderedTranslucentPass> pass;
  renderer->SetPass(pass);

  vtkSmartPointer<vtkRenderWindow> window = scenevis::headless::MakeRenderWindow(600, 600);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(5.5, 3.7, 7.3);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewAngle(40);

  for (int frame = 0; frame < 3; ++frame)
  {
    camera->Azimuth(frame == 0 ? 0.0 : 30.0);
    renderer->ResetCameraClippingRange();
    const std::string file = prefix + "-" + std::to_string(frame) + ".png";
    if (!scenevis::headless::WritePng(scenevis::headless::CaptureImage(window), file))
    {
      std::cerr << "cannot write " << file << "\n";
      return EXIT_FAILURE;
    }
    std::cout << file << ": " << sorter->GetNumberOfFragments() << " fragments, built "
              << sorter->GetNumberOfBuilds() << " time(s), order "
              << sorter->GetLastOrderTime() * 1e3 << " ms\n";
  }
  // The tree was built once; every frame after the first only re-ordered it.
  return sorter->GetNumberOfBuilds() == 1 ? EXIT_SUCCESS : EXIT_FAILURE;
}

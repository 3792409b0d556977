// Example: a headless regression render of a translucent scene, as a CI job would write it, with
// nothing but VTK and the SceneVis modules (no test harness).
//
//   vtkDemoSceneSource (64 overlapping translucent spheres)
//     -> vtkBSPSortedPolyDataMapper (exact back-to-front order, rewritten in the index buffer)
//   renderer with vtkOrderedTranslucentPass (plain alpha blending in draw order)
//   offscreen vtkRenderWindow -> vtkWindowToImageFilter -> compared with a baseline PNG
//
// Three things a regression render of translucency must get right, and how:
// - the image must not depend on the GPU's blending order: VTK 9.1's default weighted
//   order-independent translucency is an approximation, so the baseline would record its error;
//   the exact BSP order with plain blending (vtkOrderedTranslucentPass) is what the image shows;
// - the image must be reproducible: multisampling off, a fixed camera and window size (with
//   Mesa's llvmpipe also LP_NUM_THREADS=1);
// - a second render with the same camera must cost nothing: the mapper neither re-sorts nor
//   re-uploads (checked below with its counters).
//
// Usage: HeadlessRegression BASELINE.png [--write-baseline] [OUTPUT.png]
//   Compares the render with BASELINE.png (vtkImageDifference, threshold 10); exit 0 when it
//   matches, 1 when it does not (OUTPUT.png and OUTPUT-diff.png are written to look at),
//   77 (skipped) without an X display. --write-baseline writes BASELINE.png instead: look at it
//   before committing it.
// Debian's VTK renders offscreen through X: run under `xvfb-run -a -s "-screen 0 1280x1024x24"`.
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkImageDifference.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
void WritePng(vtkAlgorithmOutput* image, const std::string& file)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(image);
  writer->SetFileName(file.c_str());
  writer->Write();
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: HeadlessRegression BASELINE.png [--write-baseline] [OUTPUT.png]\n";
    return 2;
  }
  const std::string baseline = argv[1];
  bool writeBaseline = false;
  std::string output = "headless-regression.png";
  for (int i = 2; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--write-baseline")
    {
      writeBaseline = true;
    }
    else
    {
      output = arg;
    }
  }
  if (!std::getenv("DISPLAY"))
  {
    std::cout << "skipped: no X display (run under xvfb-run)\n";
    return 77;
  }

  vtkNew<vtkDemoSceneSource> spheres;
  spheres->SetTriangleCount(20000);

  vtkNew<vtkBSPSortedPolyDataMapper> mapper;
  mapper->SetInputConnection(spheres->GetOutputPort());
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.0);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.12);
  vtkNew<vtkOrderedTranslucentPass> pass;
  renderer->SetPass(pass);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(5.5, 3.7, 7.3);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  window->Render();

  // Same camera again: the order is reused, nothing is sorted or uploaded.
  const vtkIdType updates = mapper->GetNumberOfOrderUpdates();
  const vtkIdType uploads = mapper->GetNumberOfIndexUploads();
  window->Render();
  const bool idle = mapper->GetNumberOfOrderUpdates() == updates &&
    mapper->GetNumberOfIndexUploads() == uploads && mapper->GetNumberOfTreeBuilds() == 1;
  std::cout << mapper->GetNumberOfFragments() << " fragments; tree built "
            << mapper->GetNumberOfTreeBuilds() << " time(s); unchanged camera "
            << (idle ? "re-sorted nothing" : "RE-SORTED") << "\n";

  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->SetInputBufferTypeToRGB();
  capture->ReadFrontBufferOff();
  capture->Update();

  if (writeBaseline)
  {
    WritePng(capture->GetOutputPort(), baseline);
    std::cout << "wrote baseline " << baseline << " (look at it before committing it)\n";
    return idle ? EXIT_SUCCESS : EXIT_FAILURE;
  }
  if (!std::ifstream(baseline).good())
  {
    std::cerr << "no baseline " << baseline << " (run with --write-baseline)\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  vtkNew<vtkImageDifference> difference;
  difference->SetInputConnection(capture->GetOutputPort());
  difference->SetImageConnection(reader->GetOutputPort());
  difference->Update();
  const double error = difference->GetThresholdedError();
  const bool matches = error <= 10.0;
  std::cout << "thresholded error against " << baseline << ": " << error
            << (matches ? " (matches)" : " (DIFFERS)") << "\n";
  if (!matches)
  {
    WritePng(capture->GetOutputPort(), output);
    const std::string diff = output.substr(0, output.rfind('.')) + "-diff.png";
    WritePng(difference->GetOutputPort(), diff);
    std::cerr << "wrote " << output << " and " << diff << "\n";
  }
  return matches && idle ? EXIT_SUCCESS : EXIT_FAILURE;
}

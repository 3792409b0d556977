// VTK-style test: the OSMesa and X11 back-ends must render bit-identical images of the same scenes
// (64 translucent spheres with depth peeling and with ordered alpha; the opaque grid). Needs
// $DISPLAY (Xvfb); without it exits with scenevis::testing::kSkipReturnCode (CTest: skipped).
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkImageData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdlib>
#include <exception>
#include <iostream>

namespace
{
vtkSmartPointer<vtkImageData> RenderWith(scenevis::testing::Backend backend,
  const scenevis::testing::SphereGridOptions& options)
{
  // One window at a time: each back-end's window is gone before the other renders.
  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(backend, 200, 200);
  window->AddRenderer(scenevis::testing::MakeSphereGridRenderer(options));
  return scenevis::testing::CaptureImage(window);
}
} // namespace

int TestHarnessBackendIdentity(int, char*[])
{
  using namespace scenevis::testing;
  setenv("LP_NUM_THREADS", "1", 0);
  std::string why;
  if (!BackendAvailable(Backend::X11, &why))
  {
    std::cout << "SKIP: " << why << "\n";
    return kSkipReturnCode;
  }
  StrictVtkOutput strict;
  int failures = 0;
  try
  {
    struct Case
    {
      const char* name;
      Translucency translucency;
      double opacity;
    };
    for (const Case& c : { Case{ "translucent-depth-peeling", Translucency::DepthPeeling, 0.3 },
           Case{ "translucent-ordered-alpha", Translucency::OrderedAlpha, 0.3 },
           Case{ "opaque", Translucency::DepthPeeling, 1.0 } })
    {
      SphereGridOptions options;
      options.translucency = c.translucency;
      options.opacity = c.opacity;
      auto osmesa = RenderWith(Backend::OSMesa, options);
      auto x11 = RenderWith(Backend::X11, options);
      if (CoveredFraction(osmesa) < 0.05)
      {
        std::cerr << "FAIL " << c.name << ": the OSMesa image is (almost) empty\n";
        ++failures;
      }
      std::string difference;
      if (!ImagesIdentical(osmesa, x11, &difference))
      {
        std::cerr << "FAIL " << c.name << ": OSMesa and X11 images differ: " << difference << " ("
                  << CompareImages(x11, osmesa).Summary() << ")\n";
        WritePng(
          osmesa, TemporaryDirectory() + "/HarnessBackendIdentity-" + c.name + ".osmesa.png");
        WritePng(x11, TemporaryDirectory() + "/HarnessBackendIdentity-" + c.name + ".x11.png");
        ++failures;
      }
      else
      {
        std::cout << c.name << ": bit-identical\n";
      }
    }
  }
  catch (const std::exception& error)
  {
    std::cerr << "FAIL: " << error.what() << "\n";
    ++failures;
  }
  return strict.ExitCode(failures ? EXIT_FAILURE : EXIT_SUCCESS);
}

// VTK-style test (int Test...(argc, argv)): the demo scene, 64 translucent spheres (4x4x4 grid,
// radius 0.8, spacing 1, opacity 0.3) with depth peeling, 400x400, OSMesa, against the baseline
// Testing/Data/Baseline/HarnessSphereGridDepthPeeling.png. Also exercises StrictVtkOutput from a
// non-GoogleTest test.
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdlib>
#include <exception>
#include <iostream>

int TestHarnessBaseline(int, char*[])
{
  using namespace scenevis::testing;
  setenv("LP_NUM_THREADS", "1", 0); // before the first context: pixel-exact llvmpipe
  StrictVtkOutput strict;
  int failures = 0;
  try
  {
    for (Translucency mode : { Translucency::DepthPeeling, Translucency::OrderedAlpha })
    {
      SphereGridOptions options; // the standard demo scene
      options.translucency = mode;
      vtkSmartPointer<vtkRenderWindow> window = MakeRenderWindow(Backend::OSMesa, 400, 400);
      window->AddRenderer(MakeSphereGridRenderer(options));
      const char* baseline = mode == Translucency::DepthPeeling
        ? "HarnessSphereGridDepthPeeling.png"
        : "HarnessSphereGridOrderedAlpha.png";
      const std::string message = CompareWithBaseline(window, baseline);
      if (!message.empty())
      {
        // Go on: every missing baseline gets its candidate written in one run.
        std::cerr << message << "\n";
        ++failures;
      }
    }
  }
  catch (const std::exception& error)
  {
    std::cerr << "FAIL: " << error.what() << "\n";
    return strict.ExitCode(EXIT_FAILURE);
  }
  return strict.ExitCode(failures ? EXIT_FAILURE : EXIT_SUCCESS);
}

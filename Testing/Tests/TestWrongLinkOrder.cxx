// Built with libOpenGL/libGL deliberately BEFORE libOSMesa on the link line (see CMakeLists.txt).
// Demonstrates that the start-up self-check turns the otherwise silent black render into a clear
// error that names the link order. Passes when the self-check reports the link-order problem.
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkRenderWindow.h>

#include <cstdlib>
#include <iostream>
#include <stdexcept>

int main()
{
  using namespace scenevis::testing;
  // Whatever VTK says while rendering into the void is part of what we demonstrate; allow it.
  StrictVtkOutput strict;
  strict.AllowError("");
  strict.AllowWarning("");
  try
  {
    vtkSmartPointer<vtkRenderWindow> window = MakeRenderWindow(Backend::OSMesa, 32, 32);
    std::cerr << "FAIL: the self-check passed although libGL/libOpenGL precede libOSMesa; the "
                 "wrong link order no longer reproduces a black render here\n";
    return strict.ExitCode(EXIT_FAILURE);
  }
  catch (const std::runtime_error& error)
  {
    const std::string message = error.what();
    std::cout << "Self-check reported:\n" << message << "\n";
    const bool namesLinkOrder = message.find("[link order]") != std::string::npos &&
      message.find("libOSMesa") != std::string::npos;
    if (!namesLinkOrder)
    {
      std::cerr << "FAIL: the self-check failed but did not name the link order\n";
      return strict.ExitCode(EXIT_FAILURE);
    }
  }
  return strict.ExitCode(EXIT_SUCCESS);
}

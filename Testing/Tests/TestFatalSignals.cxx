// A test process that crashes the way the CI run of 2026-11-27 did, under the signal handlers
// VTK's test driver installs (vtksys' stack trace on error, then loguru's through vtkLogger::Init)
// and then a StrictVtkOutput, as every VTK-level test has. Run by FatalSignals.cmake, which
// expects the process to die by the signal within seconds and to have named it:
//   heap     the heap's metadata overwritten, then freed: glibc aborts from inside free(); under
//            loguru's handler, which allocates, the process hung until CTest's 600 s timeout;
//   segv     a plain invalid read;
//   overflow unbounded recursion: the handler runs on its own stack.
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkLogger.h>
#include <vtksys/SystemInformation.hxx>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

namespace
{
// Opaque to the optimizer: the writes below must happen as written.
volatile std::ptrdiff_t gBefore = 64;
volatile std::size_t gLength = 256;
volatile int gDepthLimit = 1 << 30;
volatile int* volatile gNull = nullptr;

int Recurse(int depth)
{
  volatile char frame[4096];
  frame[0] = static_cast<char>(depth);
  return depth < gDepthLimit ? Recurse(depth + 1) + frame[0] : frame[0];
}
} // namespace

int main(int argc, char* argv[])
{
  vtksys::SystemInformation::SetStackTraceOnError(1);
  vtkLogger::Init(argc, argv);
  scenevis::testing::StrictVtkOutput strict;
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "heap")
  {
    char* block = static_cast<char*>(std::malloc(16));
    char* const start = block - gBefore;
    std::memset(start, 0xff, gLength);
    std::free(block);
    std::free(std::malloc(16));
  }
  else if (mode == "segv")
  {
    return *gNull;
  }
  else if (mode == "overflow")
  {
    return Recurse(0);
  }
  std::cerr << "usage: " << argv[0] << " heap|segv|overflow\n";
  return strict.ExitCode(EXIT_FAILURE);
}

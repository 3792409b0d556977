// scenevis: the SceneVis command-line tool. Renders a model or an embedded demo scene offscreen
// with a chosen translucency method, writes PNG frames and a JSON report of what was done and how
// long it took; writes sorted polydata for a camera; measures accuracy against time of every
// translucency method (`bench`). `scenevis --help` documents it.
//
// The commands live in Command*.cxx (Commands.h); this file only dispatches to them and keeps
// the exit-code contract.

#include "Commands.h"
#include "HugePages.h"
#include "MallocRetention.h"
#include "Options.h"

#include <vtkAutoInit.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <regex>
#include <string>

// The chart (bench plot) needs the 2D context device and text rendering; the harness initialises
// the OpenGL2 rendering overrides itself.
VTK_MODULE_INIT(vtkRenderingContextOpenGL2);
VTK_MODULE_INIT(vtkRenderingFreeType);
VTK_MODULE_INIT(vtkInteractionStyle); // vtkContextView makes an interactor style

namespace
{
constexpr int kExitUsage = 2;
constexpr int kExitFailure = 1;

/// A message as the one line the exit-code contract promises: VTK's "ERROR: In FILE, line N"
/// headers dropped, line breaks folded.
std::string OneLine(const std::string& message)
{
  static const std::regex header(R"((ERROR|Warning): In [^\n]*, line [0-9]+\n)");
  std::string line = std::regex_replace(message, header, "");
  std::replace(line.begin(), line.end(), '\n', ' ');
  line = std::regex_replace(line, std::regex(" +"), " ");
  while (!line.empty() && line.back() == ' ')
    line.pop_back();
  return line;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h"))
  {
    std::cout << scenevis::tool::HelpText();
    return EXIT_SUCCESS;
  }
  if (argc >= 2 && std::string(argv[1]) == "--version")
  {
    std::cout << "scenevis " << SCENEVIS_VERSION << "\n";
    return EXIT_SUCCESS;
  }
  scenevis::tool::RerunWithHugePages(argc, argv);
  scenevis::tool::KeepFreedMemory();
  try
  {
    const scenevis::tool::Options options = scenevis::tool::ParseOptions(argc, argv);
    if (options.command == "bench")
    {
      return scenevis::tool::RunBench(options);
    }
    if (options.command == "cull")
    {
      return scenevis::tool::RunCull(options);
    }
    if (options.command == "portals")
    {
      return scenevis::tool::RunPortals(options);
    }
    return options.command == "render" ? scenevis::tool::RunRender(options)
                                       : scenevis::tool::RunSort(options);
  }
  catch (const scenevis::tool::UsageError& e)
  {
    std::cerr << "scenevis: " << OneLine(e.what()) << "\n";
    return kExitUsage;
  }
  catch (const std::exception& e)
  {
    std::cerr << "scenevis: " << OneLine(e.what()) << "\n";
    return kExitFailure;
  }
}

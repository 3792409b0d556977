// Time and progress as the tool reports them: milliseconds since a moment (the reports' times,
// first_frame_ms since the tool started) and the progress bar drawn on stderr on a terminal.
#ifndef scenevis_tool_Progress_h
#define scenevis_tool_Progress_h

#include <vtkCommand.h>

#include <chrono>
#include <string>

namespace scenevis
{
namespace tool
{

/// When the tool started: the reports' first_frame_ms counts from here.
extern const std::chrono::steady_clock::time_point kProgramStart;

/// Milliseconds since @p start.
double Milliseconds(std::chrono::steady_clock::time_point start);

/// Prints a progress bar on stderr, as an observer of ProgressEvent (BSP build, PVS precompute)
/// or called directly (frames). Callers attach it only when stderr is a terminal, so that logs
/// and pipes stay clean.
class ProgressBar : public vtkCommand
{
public:
  static ProgressBar* New() { return new ProgressBar; }
  static bool OnTerminal();
  void Execute(vtkObject*, unsigned long, void* data) override;
  void Show(double fraction);
  std::string Label;
  int LastPercent = -1;
};

} // namespace tool
} // namespace scenevis

#endif

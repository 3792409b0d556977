// Time and progress as the tool reports them.
#include "Progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace scenevis
{
namespace tool
{

extern const std::chrono::steady_clock::time_point kProgramStart = std::chrono::steady_clock::now();

double Milliseconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

bool ProgressBar::OnTerminal()
{
  return isatty(STDERR_FILENO) != 0;
}

void ProgressBar::Execute(vtkObject*, unsigned long, void* data)
{
  this->Show(*static_cast<double*>(data));
}

void ProgressBar::Show(double fraction)
{
  const int percent = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100.0);
  if (percent != LastPercent)
  {
    LastPercent = percent;
    std::fprintf(stderr, "\r%s [%-40s] %3d%%", Label.c_str(),
      std::string(static_cast<std::size_t>(percent * 40 / 100), '#').c_str(), percent);
    if (percent >= 100)
    {
      std::fprintf(stderr, "\n");
    }
  }
}

} // namespace tool
} // namespace scenevis

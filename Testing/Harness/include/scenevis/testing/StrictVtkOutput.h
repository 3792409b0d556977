/**
 * @file StrictVtkOutput.h
 * @brief Make VTK errors and warnings fail tests.
 *
 * VTK reports problems through vtkOutputWindow and carries on; the exit code stays 0. The classes
 * here record every error and warning so that a test can fail on any it did not declare:
 *
 * @code
 * // GoogleTest: derive from scenevis::testing::StrictVtkTest (GTestSupport.h), or
 * scenevis::testing::StrictVtkOutput strict;
 * strict.ExpectError("No input data");        // must occur (at least once)
 * strict.AllowWarning("deprecated");          // may occur
 * ... run VTK code ...
 * const std::string report = strict.Check(); // "" when clean
 * EXPECT_TRUE(report.empty()) << report;
 *
 * // vtk_add_test_cxx-style test functions:
 * int TestSomething(int, char*[]) { scenevis::testing::StrictVtkOutput strict; ...
 *   return strict.ExitCode(EXIT_SUCCESS); }
 * @endcode
 *
 * A StrictVtkOutput that is destroyed without Check()/ExitCode() having been called checks itself
 * and, on unexpected messages, prints the report and terminates the process with EXIT_FAILURE, so
 * a forgotten check still fails loudly.
 *
 * Messages sent to an object that has its own vtkCommand::ErrorEvent/WarningEvent observer never
 * reach the output window (VTK's design); such observers are the caller's own expectation.
 */
#ifndef scenevis_testing_StrictVtkOutput_h
#define scenevis_testing_StrictVtkOutput_h

#include <vtkOutputWindow.h>
#include <vtkSceneVisRecordingOutputWindow.h>
#include <vtkSmartPointer.h>

#include <mutex>
#include <string>
#include <vector>

namespace scenevis
{
namespace testing
{

// Recording is SceneVis::RenderingHeadless's (the rendering self-check records with it too).
using headless::KindName;
using headless::ScopedVtkOutputRecorder;
using headless::VtkMessage;

/**
 * RAII guard: while alive, every VTK error or warning must have been declared with ExpectError /
 * ExpectWarning (must occur) or AllowError / AllowWarning (may occur); matching is by substring.
 * Declared messages are printed marked "(expected)" and not passed on; undeclared ones are passed
 * on to the previous output window (printed, or judged by an enclosing guard).
 * Also forces vtkObject::GlobalWarningDisplay on while alive (when off, VTK prints nothing), and
 * installs InstallFatalSignalHandlers() (FatalSignals.h): a crash ends the test at once.
 */
class StrictVtkOutput
{
public:
  StrictVtkOutput();
  ~StrictVtkOutput();
  StrictVtkOutput(const StrictVtkOutput&) = delete;
  StrictVtkOutput& operator=(const StrictVtkOutput&) = delete;

  /// An error containing @p substring must occur at least once; all such errors are accepted.
  StrictVtkOutput& ExpectError(const std::string& substring);
  /// A warning (vtkWarningMacro or vtkGenericWarningMacro) containing @p substring must occur.
  StrictVtkOutput& ExpectWarning(const std::string& substring);
  /// Errors containing @p substring are accepted but not required.
  StrictVtkOutput& AllowError(const std::string& substring);
  /// Warnings containing @p substring are accepted but not required.
  StrictVtkOutput& AllowWarning(const std::string& substring);

  /// All messages recorded so far (errors, warnings and plain text).
  std::vector<VtkMessage> Messages() const;

  /**
   * Judge what was recorded so far and mark the guard as checked.
   * @return an empty string when every error/warning was declared and every Expect* occurred;
   *         otherwise a report listing the unexpected messages and the missing expected ones.
   */
  std::string Check();

  /// For test functions that return an exit code: Check(); on failure print the report to
  /// std::cerr and return EXIT_FAILURE, otherwise return @p result.
  int ExitCode(int result);

  /// Forget the recorded messages and the satisfied expectations (declarations stay).
  void Clear();

private:
  struct Rule
  {
    bool error;    // error rule (else warning rule)
    bool required; // Expect* (else Allow*)
    std::string substring;
  };
  bool Matches(const Rule& rule, const VtkMessage& message) const;
  bool IsDeclared(const VtkMessage& message) const;

  mutable std::mutex Mutex;
  std::vector<Rule> Rules;
  bool Checked = false;
  vtkSmartPointer<vtkSceneVisRecordingOutputWindow> Recorder;
  vtkSmartPointer<vtkOutputWindow> Previous;
  int PreviousGlobalWarningDisplay;
};

} // namespace testing
} // namespace scenevis

#endif

/**
 * @class   vtkSceneVisRecordingOutputWindow
 * @brief   vtkOutputWindow that records VTK's errors and warnings, then passes them on.
 *
 * VTK reports problems through vtkOutputWindow and carries on. This window records every message
 * (thread-safe: VTK may report from worker threads) and passes it on to Next (normally the output
 * window that was installed before) unless the Filter says the message is consumed.
 * scenevis::headless::ScopedVtkOutputRecorder installs one for a scope; the rendering self-check
 * (vtkSceneVisHeadlessWindows.h) uses it to name what VTK said when a render comes out wrong, and
 * the tests' StrictVtkOutput (Testing/Harness) judges the recorded messages.
 *
 * Messages sent to an object that has its own vtkCommand::ErrorEvent/WarningEvent observer never
 * reach the output window (VTK's design).
 *
 * @sa vtkOutputWindow
 */
#ifndef vtkSceneVisRecordingOutputWindow_h
#define vtkSceneVisRecordingOutputWindow_h

#include "SceneVisRenderingHeadlessModule.h" // For export macro

#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h> // For vtkSmartPointer

#include <functional> // For std::function
#include <mutex>      // For std::mutex
#include <string>     // For std::string
#include <vector>     // For std::vector

namespace scenevis
{
namespace headless
{

/// One message that VTK sent to the output window.
struct VtkMessage
{
  enum class Kind
  {
    Error,
    Warning,        ///< vtkWarningMacro
    GenericWarning, ///< vtkGenericWarningMacro
    Text            ///< plain DisplayText
  };
  Kind kind;
  std::string text;
};

/// "error", "warning", "generic warning" or "text".
SCENEVISRENDERINGHEADLESS_EXPORT const char* KindName(VtkMessage::Kind kind);

} // namespace headless
} // namespace scenevis

class SCENEVISRENDERINGHEADLESS_EXPORT vtkSceneVisRecordingOutputWindow : public vtkOutputWindow
{
public:
  static vtkSceneVisRecordingOutputWindow* New();
  // clang-format off
  // No ';': tests built with -Wpedantic include this header (through StrictVtkOutput.h).
  vtkTypeMacro(vtkSceneVisRecordingOutputWindow, vtkOutputWindow)
  // clang-format on

  void DisplayText(const char* text) override;
  void DisplayErrorText(const char* text) override;
  void DisplayWarningText(const char* text) override;
  void DisplayGenericWarningText(const char* text) override;
  void DisplayDebugText(const char* text) override;

  /// The window messages are passed on to (may be null: then they go to std::cerr).
  void SetNext(vtkOutputWindow* next) { this->Next = next; }

  /// Returns true for a message that must not be passed on (e.g. an expected error).
  void SetFilter(std::function<bool(const scenevis::headless::VtkMessage&)> filter);

  std::vector<scenevis::headless::VtkMessage> GetMessages() const;
  void ClearMessages();

protected:
  vtkSceneVisRecordingOutputWindow() = default;
  ~vtkSceneVisRecordingOutputWindow() override = default;

private:
  vtkSceneVisRecordingOutputWindow(const vtkSceneVisRecordingOutputWindow&) = delete;
  void operator=(const vtkSceneVisRecordingOutputWindow&) = delete;

  void Record(scenevis::headless::VtkMessage::Kind kind, const char* text);

  mutable std::mutex Mutex;
  std::vector<scenevis::headless::VtkMessage> Messages;
  std::function<bool(const scenevis::headless::VtkMessage&)> Filter;
  vtkSmartPointer<vtkOutputWindow> Next;
};

namespace scenevis
{
namespace headless
{

/**
 * RAII: while alive, records all VTK messages and passes all of them on to the previously
 * installed output window (so an enclosing guard still judges them); turns
 * vtkObject::GlobalWarningDisplay on meanwhile (when off, VTK reports nothing).
 */
class SCENEVISRENDERINGHEADLESS_EXPORT ScopedVtkOutputRecorder
{
public:
  ScopedVtkOutputRecorder();
  ~ScopedVtkOutputRecorder();
  ScopedVtkOutputRecorder(const ScopedVtkOutputRecorder&) = delete;
  ScopedVtkOutputRecorder& operator=(const ScopedVtkOutputRecorder&) = delete;

  std::vector<VtkMessage> Messages() const;
  /// Error and warning texts, each prefixed by its kind.
  std::vector<std::string> ErrorsAndWarnings() const;

private:
  vtkSmartPointer<vtkSceneVisRecordingOutputWindow> Recorder;
  vtkSmartPointer<vtkOutputWindow> Previous;
  int PreviousGlobalWarningDisplay;
};

} // namespace headless
} // namespace scenevis

#endif

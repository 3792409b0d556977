#include "scenevis/testing/StrictVtkOutput.h"

#include "scenevis/testing/FatalSignals.h"

#include <vtkObject.h>
#include <vtkObjectFactory.h>

#include <cstdlib>
#include <iostream>
#include <sstream>

vtkStandardNewMacro(vtkSceneVisRecordingOutputWindow)

  void vtkSceneVisRecordingOutputWindow::SetFilter(
    std::function<bool(const scenevis::testing::VtkMessage&)> filter)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Filter = std::move(filter);
}

std::vector<scenevis::testing::VtkMessage> vtkSceneVisRecordingOutputWindow::GetMessages() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Messages;
}

void vtkSceneVisRecordingOutputWindow::ClearMessages()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Messages.clear();
}

void vtkSceneVisRecordingOutputWindow::Record(scenevis::testing::VtkMessage::Kind kind,
  const char* text)
{
  using Kind = scenevis::testing::VtkMessage::Kind;
  scenevis::testing::VtkMessage message{ kind, text ? text : "" };
  std::function<bool(const scenevis::testing::VtkMessage&)> filter;
  vtkSmartPointer<vtkOutputWindow> next;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Messages.push_back(message);
    filter = this->Filter;
    next = this->Next;
  }
  if (filter && filter(message))
  {
    return;
  }
  if (!next)
  {
    std::cerr << message.text;
    return;
  }
  switch (kind)
  {
    case Kind::Error:
      next->DisplayErrorText(message.text.c_str());
      break;
    case Kind::Warning:
      next->DisplayWarningText(message.text.c_str());
      break;
    case Kind::GenericWarning:
      next->DisplayGenericWarningText(message.text.c_str());
      break;
    case Kind::Text:
      next->DisplayText(message.text.c_str());
      break;
  }
}

void vtkSceneVisRecordingOutputWindow::DisplayText(const char* text)
{
  this->Record(scenevis::testing::VtkMessage::Kind::Text, text);
}

void vtkSceneVisRecordingOutputWindow::DisplayErrorText(const char* text)
{
  this->Record(scenevis::testing::VtkMessage::Kind::Error, text);
}

void vtkSceneVisRecordingOutputWindow::DisplayWarningText(const char* text)
{
  this->Record(scenevis::testing::VtkMessage::Kind::Warning, text);
}

void vtkSceneVisRecordingOutputWindow::DisplayGenericWarningText(const char* text)
{
  this->Record(scenevis::testing::VtkMessage::Kind::GenericWarning, text);
}

void vtkSceneVisRecordingOutputWindow::DisplayDebugText(const char* text)
{
  // Debug output is neither recorded nor judged; pass it on unchanged.
  vtkSmartPointer<vtkOutputWindow> next;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    next = this->Next;
  }
  if (next)
  {
    next->DisplayDebugText(text);
  }
}

namespace scenevis
{
namespace testing
{

const char* KindName(VtkMessage::Kind kind)
{
  switch (kind)
  {
    case VtkMessage::Kind::Error:
      return "error";
    case VtkMessage::Kind::Warning:
      return "warning";
    case VtkMessage::Kind::GenericWarning:
      return "generic warning";
    case VtkMessage::Kind::Text:
      break;
  }
  return "text";
}

namespace
{
bool IsError(const VtkMessage& message)
{
  return message.kind == VtkMessage::Kind::Error;
}

bool IsWarning(const VtkMessage& message)
{
  return message.kind == VtkMessage::Kind::Warning ||
    message.kind == VtkMessage::Kind::GenericWarning;
}

std::string Trimmed(const std::string& text)
{
  const auto end = text.find_last_not_of("\r\n ");
  return end == std::string::npos ? std::string() : text.substr(0, end + 1);
}
} // namespace

ScopedVtkOutputRecorder::ScopedVtkOutputRecorder()
  : Recorder(vtkSmartPointer<vtkSceneVisRecordingOutputWindow>::New())
  , Previous(vtkOutputWindow::GetInstance())
  , PreviousGlobalWarningDisplay(vtkObject::GetGlobalWarningDisplay())
{
  this->Recorder->SetNext(this->Previous);
  vtkOutputWindow::SetInstance(this->Recorder);
  vtkObject::GlobalWarningDisplayOn();
}

ScopedVtkOutputRecorder::~ScopedVtkOutputRecorder()
{
  vtkOutputWindow::SetInstance(this->Previous);
  vtkObject::SetGlobalWarningDisplay(this->PreviousGlobalWarningDisplay);
}

std::vector<VtkMessage> ScopedVtkOutputRecorder::Messages() const
{
  return this->Recorder->GetMessages();
}

std::vector<std::string> ScopedVtkOutputRecorder::ErrorsAndWarnings() const
{
  std::vector<std::string> result;
  for (const VtkMessage& message : this->Recorder->GetMessages())
  {
    if (message.kind != VtkMessage::Kind::Text)
    {
      result.push_back(std::string(KindName(message.kind)) + ": " + Trimmed(message.text));
    }
  }
  return result;
}

StrictVtkOutput::StrictVtkOutput()
  : Recorder(vtkSmartPointer<vtkSceneVisRecordingOutputWindow>::New())
  , Previous(vtkOutputWindow::GetInstance())
  , PreviousGlobalWarningDisplay(vtkObject::GetGlobalWarningDisplay())
{
  InstallFatalSignalHandlers(); // over the test driver's, which can deadlock (FatalSignals.h)
  this->Recorder->SetNext(this->Previous);
  this->Recorder->SetFilter(
    [this](const VtkMessage& message)
    {
      if (message.kind == VtkMessage::Kind::Text || !this->IsDeclared(message))
      {
        return false; // pass on: printed, or judged by an enclosing guard
      }
      std::cerr << "(expected VTK " << KindName(message.kind) << ") " << Trimmed(message.text)
                << "\n";
      return true;
    });
  vtkOutputWindow::SetInstance(this->Recorder);
  vtkObject::GlobalWarningDisplayOn();
}

StrictVtkOutput::~StrictVtkOutput()
{
  vtkOutputWindow::SetInstance(this->Previous);
  vtkObject::SetGlobalWarningDisplay(this->PreviousGlobalWarningDisplay);
  this->Recorder->SetFilter(nullptr);
  if (!this->Checked)
  {
    const std::string report = this->Check();
    if (!report.empty())
    {
      // VTK errors do not change exit codes; a guard nobody checked must still fail the process.
      std::cerr << report << "\nStrictVtkOutput destroyed unchecked with unexpected VTK output: "
                << "terminating with EXIT_FAILURE" << std::endl;
      std::_Exit(EXIT_FAILURE);
    }
  }
}

StrictVtkOutput& StrictVtkOutput::ExpectError(const std::string& substring)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Rules.push_back(Rule{ true, true, substring });
  return *this;
}

StrictVtkOutput& StrictVtkOutput::ExpectWarning(const std::string& substring)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Rules.push_back(Rule{ false, true, substring });
  return *this;
}

StrictVtkOutput& StrictVtkOutput::AllowError(const std::string& substring)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Rules.push_back(Rule{ true, false, substring });
  return *this;
}

StrictVtkOutput& StrictVtkOutput::AllowWarning(const std::string& substring)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Rules.push_back(Rule{ false, false, substring });
  return *this;
}

bool StrictVtkOutput::Matches(const Rule& rule, const VtkMessage& message) const
{
  const bool kindMatches = rule.error ? IsError(message) : IsWarning(message);
  return kindMatches && message.text.find(rule.substring) != std::string::npos;
}

bool StrictVtkOutput::IsDeclared(const VtkMessage& message) const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  for (const Rule& rule : this->Rules)
  {
    if (this->Matches(rule, message))
    {
      return true;
    }
  }
  return false;
}

std::vector<VtkMessage> StrictVtkOutput::Messages() const
{
  return this->Recorder->GetMessages();
}

std::string StrictVtkOutput::Check()
{
  this->Checked = true;
  const std::vector<VtkMessage> messages = this->Recorder->GetMessages();
  std::vector<Rule> rules;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    rules = this->Rules;
  }
  std::ostringstream report;
  for (const VtkMessage& message : messages)
  {
    if (message.kind != VtkMessage::Kind::Text && !this->IsDeclared(message))
    {
      report << "Unexpected VTK " << KindName(message.kind) << ": " << Trimmed(message.text)
             << "\n";
    }
  }
  for (const Rule& rule : rules)
  {
    if (!rule.required)
    {
      continue;
    }
    bool seen = false;
    for (const VtkMessage& message : messages)
    {
      seen = seen || this->Matches(rule, message);
    }
    if (!seen)
    {
      report << "Expected VTK " << (rule.error ? "error" : "warning") << " containing \""
             << rule.substring << "\" did not occur\n";
    }
  }
  return report.str();
}

int StrictVtkOutput::ExitCode(int result)
{
  const std::string report = this->Check();
  if (!report.empty())
  {
    std::cerr << report;
    return EXIT_FAILURE;
  }
  return result;
}

void StrictVtkOutput::Clear()
{
  this->Recorder->ClearMessages();
}

} // namespace testing
} // namespace scenevis

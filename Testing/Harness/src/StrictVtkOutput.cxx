#include "scenevis/testing/StrictVtkOutput.h"

#include "scenevis/testing/FatalSignals.h"

#include <vtkObject.h>

#include <cstdlib>
#include <iostream>
#include <sstream>

namespace scenevis
{
namespace testing
{

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

// Recording VTK's messages; see vtkSceneVisRecordingOutputWindow.h.
#include "vtkSceneVisRecordingOutputWindow.h"

#include <vtkObject.h>
#include <vtkObjectFactory.h>

#include <iostream>

vtkStandardNewMacro(vtkSceneVisRecordingOutputWindow);

void vtkSceneVisRecordingOutputWindow::SetFilter(
  std::function<bool(const scenevis::headless::VtkMessage&)> filter)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Filter = std::move(filter);
}

std::vector<scenevis::headless::VtkMessage> vtkSceneVisRecordingOutputWindow::GetMessages() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Messages;
}

void vtkSceneVisRecordingOutputWindow::ClearMessages()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Messages.clear();
}

void vtkSceneVisRecordingOutputWindow::Record(
  scenevis::headless::VtkMessage::Kind kind, const char* text)
{
  using Kind = scenevis::headless::VtkMessage::Kind;
  scenevis::headless::VtkMessage message{ kind, text ? text : "" };
  std::function<bool(const scenevis::headless::VtkMessage&)> filter;
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
  this->Record(scenevis::headless::VtkMessage::Kind::Text, text);
}

void vtkSceneVisRecordingOutputWindow::DisplayErrorText(const char* text)
{
  this->Record(scenevis::headless::VtkMessage::Kind::Error, text);
}

void vtkSceneVisRecordingOutputWindow::DisplayWarningText(const char* text)
{
  this->Record(scenevis::headless::VtkMessage::Kind::Warning, text);
}

void vtkSceneVisRecordingOutputWindow::DisplayGenericWarningText(const char* text)
{
  this->Record(scenevis::headless::VtkMessage::Kind::GenericWarning, text);
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
namespace headless
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

} // namespace headless
} // namespace scenevis

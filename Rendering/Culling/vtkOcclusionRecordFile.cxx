#include "vtkOcclusionRecordFile.h"

#include "vtkObject.h"
#include "vtkSetGet.h"

vtkOcclusionRecordFile::~vtkOcclusionRecordFile()
{
  this->Close();
}

void vtkOcclusionRecordFile::Close()
{
  if (this->Buffer)
  {
    this->Buffer->recorder = nullptr;
  }
  this->Buffer = nullptr;
  this->Recorder.reset();
  this->Stream.reset();
  this->FileName.clear();
}

bool vtkOcclusionRecordFile::Open(
  const std::string& fileName, scenevis::occlusion::MaskedDepthBuffer& buffer)
{
  this->Close();
  if (fileName.empty())
  {
    return true;
  }
  auto stream = std::make_unique<std::ofstream>(fileName, std::ios::binary | std::ios::trunc);
  if (!*stream)
  {
    return false;
  }
  this->Stream = std::move(stream);
  this->Recorder = std::make_unique<scenevis::occlusion::OcclusionRecorder>(*this->Stream);
  this->Buffer = &buffer;
  buffer.recorder = this->Recorder.get();
  this->FileName = fileName;
  return true;
}

bool vtkOcclusionRecordFile::Flush()
{
  if (!this->Stream || (this->Stream->flush() && this->Recorder->good()))
  {
    return true;
  }
  this->Close();
  return false;
}

void vtkOcclusionRecordFile::BeforeCull(
  std::string& fileName, scenevis::occlusion::MaskedDepthBuffer& buffer, vtkObject* owner)
{
  if (this->FileName != fileName && !this->Open(fileName, buffer))
  {
    vtkErrorWithObjectMacro(
      owner, "cannot write the occlusion recording " << fileName << ": nothing is recorded");
    fileName.clear();
  }
}

void vtkOcclusionRecordFile::AfterCull(std::string& fileName, vtkObject* owner)
{
  if (!this->Flush())
  {
    vtkErrorWithObjectMacro(
      owner, "writing the occlusion recording " << fileName << " failed: recording stopped");
    fileName.clear();
  }
}

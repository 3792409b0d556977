/**
 * @class   vtkOcclusionRecordFile
 * @brief   Module-private: the file a software depth buffer's culls are recorded to, for
 *          vtkOcclusionCuller and vtkChunkedPolyDataMapper's SetOcclusionRecordFile().
 *
 * While open, the buffer's recorder (scenevis/OcclusionRecording.h) writes every cull it begins
 * and every occluder it draws to the file; Flush() after each cull makes the file complete even
 * if the process then ends without destructors (as `scenevis` does after big scenes).
 */
#ifndef vtkOcclusionRecordFile_h
#define vtkOcclusionRecordFile_h

#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionRecording.h"

class vtkObject;

#include <fstream>
#include <memory>
#include <string>

class vtkOcclusionRecordFile
{
public:
  ~vtkOcclusionRecordFile();
  /// Record @p buffer's culls into @p fileName (created or emptied) from now on; "" stops and
  /// closes the file. False, and nothing recorded, if the file cannot be opened.
  bool Open(const std::string& fileName, scenevis::occlusion::MaskedDepthBuffer& buffer);
  /// The file being written ("" when none).
  const std::string& Name() const { return this->FileName; }
  /// Writes out what was recorded so far; false, and the file closed, if a write failed.
  bool Flush();

  ///@{
  /// What the owners do around each cull: before it, follow their file name @p fileName
  /// (open it when it changed); after it, flush. A file that cannot be opened or written is a
  /// VTK error of @p owner, and @p fileName is cleared (recording stops; culling goes on).
  void BeforeCull(
    std::string& fileName, scenevis::occlusion::MaskedDepthBuffer& buffer, vtkObject* owner);
  void AfterCull(std::string& fileName, vtkObject* owner);
  ///@}

private:
  void Close();

  std::string FileName;
  std::unique_ptr<std::ofstream> Stream;
  std::unique_ptr<scenevis::occlusion::OcclusionRecorder> Recorder;
  scenevis::occlusion::MaskedDepthBuffer* Buffer = nullptr;
};

#endif

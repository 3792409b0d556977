// Reading model files the tool cannot trust: VTK's output silenced (the tool's errors are one
// line), readers run in a child process (a reader crash costs the child, not the tool), a file
// refused up front when the machine cannot hold it, bad point ids caught.
#ifndef scenevis_tool_UntrustedFiles_h
#define scenevis_tool_UntrustedFiles_h

#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

namespace scenevis
{
namespace tool
{

/// While alive, VTK's output window prints nothing: readers of bad files print multi-line
/// errors (their XML parsers' too, which LoadFile's error observer cannot see), while the
/// tool's contract is one line; LoadFile's own message says what went wrong.
class QuietVtkOutput
{
public:
  QuietVtkOutput()
    : Previous(vtkOutputWindow::GetInstance())
    , PreviousVerbosity(vtkLogger::GetCurrentVerbosityCutoff())
  {
    vtkOutputWindow::SetInstance(this->Silent);
    // VTK 9 also logs every error through vtkLogger (to stderr) before the output window.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~QuietVtkOutput()
  {
    vtkOutputWindow::SetInstance(this->Previous);
    vtkLogger::SetStderrVerbosity(this->PreviousVerbosity);
  }
  QuietVtkOutput(const QuietVtkOutput&) = delete;
  QuietVtkOutput& operator=(const QuietVtkOutput&) = delete;

private:
  class SilentWindow : public vtkOutputWindow
  {
  public:
    static SilentWindow* New() { return new SilentWindow; }
    void DisplayText(const char*) override {}
  };
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkLogger::Verbosity PreviousVerbosity;
  vtkNew<SilentWindow> Silent;
};

/// The tool's model reading: vtkSceneVisModelReader::LoadFile() with the cells on NaN/Inf points
/// kept (the tool removes and counts them itself) and the error returned, not printed.
vtkSmartPointer<vtkPolyData> LoadModelKeepingNonFinite(const std::string& path, std::string* error);

/**
 * LoadModelKeepingNonFinite() (or @p load) in a child process. VTK 9.1's PLY and glTF readers crash
 * on some malformed files (Testing/BadInput lists them); the tool reads files it cannot trust, so a
 * reader crash must cost the child, not the tool: the child writes what it read as an uncompressed
 * .vtp to a temporary file (a few ms per 100k triangles), or its one-line error to a pipe. Without
 * fork, reads in this process; so are .vtp files, whose reader does not crash on bad ones.
 */
using ModelLoader = vtkSmartPointer<vtkPolyData> (*)(const std::string&, std::string*);

vtkSmartPointer<vtkPolyData> LoadModelIsolated(
  const std::string& path, std::string& error, ModelLoader load = LoadModelKeepingNonFinite);

/// A cell that names a point the file does not have (a damaged or hand-written file) is an error:
/// every later step would read out of bounds.
void CheckPointIds(vtkPolyData* pd, const std::string& path);

/**
 * Refuses, before reading it, a model that the machine cannot hold: its polydata estimated from a
 * .vtp header's point and polygon counts (else from the file's size), times what the tool's paths
 * need on top of it, against the memory available now (AvailableMemory, Memory.h). A
 * refused scene costs a line and exit 1, not minutes of reading and a kill by the kernel.
 */
void CheckFitsInMemory(const std::string& path);

} // namespace tool
} // namespace scenevis

#endif

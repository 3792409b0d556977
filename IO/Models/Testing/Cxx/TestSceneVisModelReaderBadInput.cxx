// Specification: vtkSceneVisModelReader with bad input (issue 8's catalogue; the malformed files of
// the real data are in Testing/BadInput/TestMalformedModels.cxx).
// - No file name, a missing file, an unknown extension, a file its VTK reader rejects (garbage
//   .vtp, .stl, .glb and .wrl), a file without cells, a cell naming a point the file does not
//   have, and a file whose every cell uses a NaN point: ONE error event whose message (also in
//   GetErrorMessage()) is one line naming the file and the reason, an ErrorCode, an empty output.
// - VTK's own readers' errors and warnings do not reach the output window (they are folded into
//   the line); only objects the reader cannot observe may print (vtkGLTFDocumentLoader, inside
//   vtkGLTFImporter, logs its own error on the malformed glTF files).
// - The next update with a good file gives the ordinary model, and no error.
#include "vtkSceneVisModelReader.h"

#include "scenevis/testing/Expect.h"
#include "scenevis/testing/ImageCompare.h" // WriteTemporaryFile

#include "vtkCommand.h"
#include "vtkErrorCode.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPolyData.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// Fails the test on anything that reaches the output window, unless Allowed names its source.
class FailingOutputWindow : public vtkOutputWindow
{
public:
  static FailingOutputWindow* New() { return new FailingOutputWindow; }
  void DisplayText(const char* text) override
  {
    if (!this->Allowed.empty() && std::string(text).find(this->Allowed) != std::string::npos)
    {
      return;
    }
    std::cerr << "unexpected output window text: " << text << std::endl;
    ++scenevis::testing::ExpectFailures();
  }
  std::string Allowed;
};
FailingOutputWindow* Strict = nullptr;

/// Counts error and warning events and keeps the error messages.
class Events : public vtkCommand
{
public:
  static Events* New() { return new Events; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    if (event == vtkCommand::ErrorEvent)
    {
      ++this->Errors;
      this->ErrorMessages += data ? static_cast<const char*>(data) : "";
    }
    else
    {
      ++this->Warnings;
    }
  }
  int Errors = 0;
  int Warnings = 0;
  std::string ErrorMessages;
};

/// An ASCII PLY of the given vertex and face lines.
std::string Ply(
  int vertices, const std::string& vertexLines, int faces, const std::string& faceLines)
{
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
    std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n" + vertexLines +
    faceLines;
}

const char* const kTriangle = R"(# vtk DataFile Version 3.0
triangle
ASCII
DATASET POLYDATA
POINTS 3 float
0 0 0 1 0 0 0 1 0
POLYGONS 1 4
3 0 1 2
)";

std::string WriteText(const std::string& name, const std::string& text)
{
  return scenevis::testing::WriteTemporaryFile(name, text);
}

/// Reads @p path and checks the bad-input contract; @p reason must be in the message.
void ExpectRefused(const std::string& path, const std::string& reason, unsigned long code,
  const std::string& mayPrint = std::string())
{
  Strict->Allowed = mayPrint;
  vtkNew<vtkSceneVisModelReader> reader;
  vtkNew<Events> observer;
  reader->AddObserver(vtkCommand::ErrorEvent, observer);
  reader->AddObserver(vtkCommand::WarningEvent, observer);
  if (!path.empty())
  {
    reader->SetFileName(path.c_str());
  }
  reader->Update();
  const std::string message = reader->GetErrorMessage();
  bool ok = reader->GetOutput()->GetNumberOfCells() == 0 &&
    reader->GetOutput()->GetNumberOfPoints() == 0 && observer->Errors == 1 &&
    observer->Warnings == 0 && message.find(reason) != std::string::npos &&
    message.find('\n') == std::string::npos &&
    observer->ErrorMessages.find(message) != std::string::npos && reader->GetErrorCode() == code;
  if (!path.empty() && message.find(path) == std::string::npos)
  {
    ok = false;
  }
  if (!ok)
  {
    std::cerr << "'" << path << "': expected one error with '" << reason << "' and error code "
              << vtkErrorCode::GetStringFromErrorCode(code) << ", an empty output; got "
              << observer->Errors << " error(s), " << observer->Warnings << " warning(s), message '"
              << message << "', code "
              << vtkErrorCode::GetStringFromErrorCode(reader->GetErrorCode()) << ", "
              << reader->GetOutput()->GetNumberOfCells() << " cells" << std::endl;
    ++scenevis::testing::ExpectFailures();
  }
}
} // namespace

int TestSceneVisModelReaderBadInput(int, char*[])
{
  // The output window is the check; VTK 9.1 also logs every message to stderr through vtkLogger,
  // where the test driver's "ERR|" pattern would fail the allowed ones.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkNew<FailingOutputWindow> strict;
  vtkOutputWindow::SetInstance(strict);
  Strict = strict;

  ExpectRefused("", "no FileName", vtkErrorCode::NoFileNameError);
  ExpectRefused("/nonexistent/model.glb", "cannot open", vtkErrorCode::CannotOpenFileError);

  std::vector<std::string> written;
  auto write = [&](const std::string& name, const std::string& text)
  {
    written.push_back(WriteText(name, text));
    return written.back();
  };
  const std::string triangle = write("scenevis-reader-bad-ok.vtk", kTriangle);

  // Wrong extensions: unknown, none, and a good file under a name no reader claims.
  ExpectRefused(write("scenevis-reader-bad.xyz", kTriangle), "unsupported model format '.xyz'",
    vtkErrorCode::UnrecognizedFileTypeError);
  ExpectRefused(write("scenevis-reader-bad-noext", kTriangle), "unsupported model format",
    vtkErrorCode::UnrecognizedFileTypeError);

  // Malformed files, each in a format the reader knows.
  const unsigned long format = vtkErrorCode::FileFormatError;
  ExpectRefused(write("scenevis-reader-bad.stl",
                  "solid x\nfacet normal 0 0 1\n  outer loop\n"
                  "    vertex 0 0 0\n  endloop\nendfacet\n"),
    "cannot read", format);
  ExpectRefused(write("scenevis-reader-bad.glb", "glTF\x02 garbage, not a binary glTF"),
    "cannot read", format, "vtkGLTFDocumentLoader");
  ExpectRefused(write("scenevis-reader-bad.gltf", "{ \"asset\": 3 }"), "cannot read", format,
    "vtkGLTFDocumentLoader");
  ExpectRefused(write("scenevis-reader-bad.wrl", "#VRML V2.0 utf8\nShape { geometry [ }\n"),
    "cannot read", format);
  ExpectRefused(write("scenevis-reader-bad.obj", "# no faces\nv 0 0 0\n"), "no cells", format);
  ExpectRefused(write("scenevis-reader-empty.ply", ""), "Could not open PLY file", format);
  ExpectRefused(write("scenevis-reader-bad-ids.vtk",
                  "# vtk DataFile Version 3.0\nbad ids\nASCII\nDATASET POLYDATA\n"
                  "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 7\n"),
    "cell 0 uses point 7 of only 3", format);
  ExpectRefused(
    write("scenevis-reader-all-nan.ply", Ply(3, "nan 0 0\n1 0 0\n0 1 0\n", 1, "3 0 1 2\n")),
    "every cell has a NaN/Inf point", format);

  // Recovery: the same reader, a bad file, then a good one.
  {
    vtkNew<vtkSceneVisModelReader> reader;
    vtkNew<Events> observer;
    reader->AddObserver(vtkCommand::ErrorEvent, observer);
    reader->SetFileName("/nonexistent/model.stl");
    reader->Update();
    SCENEVIS_EXPECT(observer->Errors == 1);
    reader->SetFileName(triangle.c_str());
    reader->Update();
    SCENEVIS_EXPECT(observer->Errors == 1);
    SCENEVIS_EXPECT(reader->GetOutput()->GetNumberOfCells() == 1);
    SCENEVIS_EXPECT(std::string(reader->GetErrorMessage()).empty());
    SCENEVIS_EXPECT(reader->GetErrorCode() == vtkErrorCode::NoError);
  }
  SCENEVIS_EXPECT(vtkSceneVisModelReader::CanReadFile("a/b.GLB"));
  SCENEVIS_EXPECT(!vtkSceneVisModelReader::CanReadFile("a.b/c"));
  SCENEVIS_EXPECT(!vtkSceneVisModelReader::CanReadFile(nullptr));

  for (const std::string& path : written)
  {
    std::remove(path.c_str());
  }
  vtkOutputWindow::SetInstance(nullptr);
  if (const int failures = scenevis::testing::ExpectFailures())
  {
    std::cerr << failures << " failure(s)" << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}

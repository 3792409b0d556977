// Specification: the malformed-model catalogue (issue 8). `scenevis render` is run on every
// deliberately broken model file of the fetched real data (npm stl-models' broken/ folder, the
// broken glTF and PLY files of assimp-testmodels) and on truncated copies of good models, each in
// a child process with a timeout. The table below says what must happen to each file:
//
//   Renders      exit 0, and the PNG shows geometry (the tool read polygons and drew them);
//   Rejected     exit 1 with exactly one line on stderr, "scenevis: ...", matching the table's
//                pattern (no VTK log lines around it);
//   ReaderCrash  VTK 9.1's reader itself crashes on the file. The tool reads models in a child
//                process, so it must survive: exit 1 with one line that says the reader crashed.
//                The test also reads the file with the bare VTK reader in a forked child (no
//                SceneVis code) and requires that to crash, so "the crash is VTK's" is checked,
//                not assumed.
//
// A crash of the tool, a hang (timeout), exit 0 with an empty image, or any outcome other than the
// table's fails: a change of behaviour must update the table.
//
// Every file is also read by vtkSceneVisModelReader (SceneVis::IOModels, what users link) alone in
// a child process: Renders must give cells and no error; Rejected ONE error (matching the table's
// pattern) and an empty output. By default the reader does not guard against VTK's reader crashes:
// on ReaderCrash files it may crash too, and only a hang fails. With ReadInChildProcess on it must
// not: ReaderCrash files give ONE error saying VTK's reader crashed, and an empty output; the
// other files as without it.
//
// Usage: scenevis_bad_input_models <path of scenevis> <scratch directory>
//        scenevis_bad_input_models --bare-read FILE   (VTK's reader alone; used internally)
//        scenevis_bad_input_models --module-read FILE (vtkSceneVisModelReader; used internally)
//        scenevis_bad_input_models --module-read-isolated FILE (the same, ReadInChildProcess on)
// Exit 77 (skip) when the real data was not fetched (scripts/fetch-data.sh).
#include "ChildProcess.h"

#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/Models.h"

#include <vtkCommand.h>
#include <vtkGLTFImporter.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkSTLReader.h>
#include <vtkSceneVisModelReader.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

namespace
{
using namespace badinput;

enum class Outcome
{
  Renders,
  Rejected,
  ReaderCrash
};

const char* OutcomeName(Outcome o)
{
  return o == Outcome::Renders ? "renders" : (o == Outcome::Rejected ? "rejected" : "reader crash");
}

struct Case
{
  const char* dataKey; ///< manifest key of the folder or file
  const char* path;    ///< inside that folder ("" for a file key)
  double keepFraction; ///< < 1: a truncated copy keeping this fraction of the bytes is read
  Outcome expected;
  const char* message; ///< Rejected: regex the "scenevis:" line must match
  const char* why;     ///< what is wrong with the file, and where VTK crashes
};

// clang-format off
const Case kCatalogue[] = {
  // npm stl-models 0.12.0, broken/: what vtkSTLReader makes of each.
  { "stl-broken-dir", "empty.stl", 1, Outcome::Rejected, "cannot read .*empty\\.stl", "0 bytes" },
  { "stl-broken-dir", "fourVertices.ascii.stl", 1, Outcome::Rejected, "cannot read .*fourVertices\\.ascii\\.stl", "a facet with 4 vertices" },
  { "stl-broken-dir", "incorrectFaceCounter.bin.stl", 1, Outcome::Renders, "", "binary face count disagrees with the file size" },
  { "stl-broken-dir", "missingEndsolid.ascii.stl", 1, Outcome::Rejected, "cannot read .*missingEndsolid", "no endsolid" },
  { "stl-broken-dir", "missingFace.ascii.stl", 1, Outcome::Renders, "", "one facet fewer than declared" },
  { "stl-broken-dir", "missingNormal.ascii.stl", 1, Outcome::Renders, "", "facet without normal" },
  { "stl-broken-dir", "notANumberNormal.ascii.stl", 1, Outcome::Renders, "", "NaN normal" },
  { "stl-broken-dir", "quad.ascii.stl", 1, Outcome::Rejected, "cannot read .*quad\\.ascii\\.stl", "a quad facet" },
  { "stl-broken-dir", "singleFace.ascii.stl", 1, Outcome::Renders, "", "one facet only" },
  { "stl-broken-dir", "solidNameMismatch.ascii.stl", 1, Outcome::Renders, "", "endsolid names another solid" },
  { "stl-broken-dir", "twoVertices.ascii.stl", 1, Outcome::Rejected, "cannot read .*twoVertices\\.ascii\\.stl", "a facet with 2 vertices" },
  { "stl-broken-dir", "wrongHeader.bin.stl", 1, Outcome::Renders, "", "binary file whose header starts with 'solid'" },
  { "stl-broken-dir", "wrongNormal.ascii.stl", 1, Outcome::Renders, "", "normal disagrees with the winding" },
  { "stl-broken-dir", "wrongNormals.ascii.stl", 1, Outcome::Renders, "", "all normals disagree with the winding" },
  // assimp-testmodels: the deliberately broken files (see /work/shared/DATA.md).
  { "assimp-models-dir", "PLY/issue623.ply", 1, Outcome::ReaderCrash, "",
    "malformed ASCII PLY; VTK crashes in vtkPLY::get_ascii_item (strtol on a wild pointer)" },
  { "assimp-models-dir", "glTF2/MissingBin/BoxTextured.gltf", 1, Outcome::ReaderCrash, "",
    "buffer .bin missing; VTK logs 'Invalid buffer.uri' then crashes in "
    "vtkGLTFDocumentLoader::ExtractPrimitiveAccessorData" },
  { "assimp-models-dir", "glTF2/RecursiveNodes/RecursiveNodes.gltf", 1, Outcome::ReaderCrash, "",
    "a node is its own child; VTK recurses without end in "
    "vtkGLTFDocumentLoader::BuildGlobalTransforms (stack overflow)" },
  { "assimp-models-dir", "glTF2/wrongTypes/badArray.gltf", 1, Outcome::ReaderCrash, "",
    "an array where an object belongs; VTK crashes in "
    "vtkGLTFDocumentLoader::BuildPolyDataFromPrimitive" },
  { "assimp-models-dir", "glTF2/wrongTypes/badExtension.gltf", 1, Outcome::Renders, "", "unsupported extension (VTK warns)" },
  { "assimp-models-dir", "glTF2/wrongTypes/badNumber.gltf", 1, Outcome::Renders, "", "bad texture index (VTK logs an error, geometry is fine)" },
  { "assimp-models-dir", "glTF2/wrongTypes/badObject.gltf", 1, Outcome::Rejected, "Json::Value", "an object of the wrong type (jsoncpp throws)" },
  { "assimp-models-dir", "glTF2/wrongTypes/badString.gltf", 1, Outcome::Renders, "", "a number where a string belongs" },
  { "assimp-models-dir", "glTF2/wrongTypes/badUint.gltf", 1, Outcome::Renders, "", "bad texture index (VTK logs an error, geometry is fine)" },
  // Truncated copies of good models (written into the scratch directory).
  { "bunny-stl", "", 0.5, Outcome::Renders, "",
    "binary STL cut in the middle of the triangles: VTK reads the triangles before the cut "
    "without a word (the count in the header is ignored)" },
  { "engine-glb", "", 0.5, Outcome::Rejected, "cannot read .*truncated-engine-glb\\.glb",
    "GLB cut in the middle of its binary chunk" },
  { "wuson-ply", "", 0.5, Outcome::ReaderCrash, "",
    "ASCII PLY cut in the middle of the vertices; VTK logs 'unexpected end of file' per missing "
    "element, then corrupts the heap in vtkPLYReader::RequestData (free(): invalid size)" },
  { "wuson-obj", "", 0.5, Outcome::Rejected, "cannot read .*truncated-wuson-obj\\.obj': no cells",
    "OBJ cut before its first face" },
  { "wuson-stl", "", 0.1, Outcome::Renders, "",
    "ASCII STL cut after a tenth: VTK reads the facets before the cut without a word" },
};
// clang-format on

/// Reads @p file with VTK's own reader alone (no SceneVis code): the body of the
/// `--bare-read FILE` mode of this executable.
int BareRead(const std::string& file)
{
  const std::string extension = file.substr(file.rfind('.') + 1);
  if (extension == "ply")
  {
    vtkNew<vtkPLYReader> ply;
    ply->SetFileName(file.c_str());
    ply->Update();
  }
  else if (extension == "stl")
  {
    vtkNew<vtkSTLReader> stl;
    stl->SetFileName(file.c_str());
    stl->Update();
  }
  else if (extension == "obj")
  {
    vtkNew<vtkOBJReader> obj;
    obj->SetFileName(file.c_str());
    obj->Update();
  }
  else
  {
    vtkNew<vtkRenderWindow> window; // never rendered: the importer only needs its renderer
    vtkNew<vtkGLTFImporter> gltf;
    gltf->SetFileName(file.c_str());
    gltf->SetRenderWindow(window);
    gltf->Update();
  }
  return EXIT_SUCCESS;
}

/// Counts the error events of the object it observes (and keeps them from the output window).
class CountErrors : public vtkCommand
{
public:
  static CountErrors* New() { return new CountErrors; }
  void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
  int Count = 0;
};

/// Reads @p file with vtkSceneVisModelReader: the body of the `--module-read FILE` mode. Prints
/// the reader's error message; exit 0: cells and no error, 1: one error and an empty output,
/// 2: anything else (then the counts are printed too).
int ModuleRead(const std::string& file, bool isolated)
{
  vtkNew<vtkSceneVisModelReader> reader;
  reader->SetReadInChildProcess(isolated);
  vtkNew<CountErrors> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(file.c_str());
  reader->Update();
  const vtkIdType cells = reader->GetOutput()->GetNumberOfCells();
  const std::string message = reader->GetErrorMessage();
  std::cout << message << std::endl;
  if (cells > 0 && errors->Count == 0 && message.empty())
  {
    return 0;
  }
  if (cells == 0 && errors->Count == 1 && !message.empty() &&
    message.find('\n') == std::string::npos)
  {
    return 1;
  }
  std::cout << cells << " cells, " << errors->Count << " error events" << std::endl;
  return 2;
}

/// vtkSceneVisModelReader on @p file in a child process, against the table's outcome: what
/// happened (appended to @p seen), and the problem, if any, in @p problem (unless already set).
void CheckModuleReader(const Case& c, const std::string& file, const std::string& scratch,
  bool isolated, std::string& seen, std::string& problem)
{
  const Run run = RunChild(
    { "/proc/self/exe", isolated ? "--module-read-isolated" : "--module-read", file }, scratch);
  const std::vector<std::string> out = Lines(run.out);
  const std::string message = out.empty() ? std::string() : out.front();
  std::string wrong;
  seen +=
    isolated ? "; vtkSceneVisModelReader, ReadInChildProcess: " : "; vtkSceneVisModelReader: ";
  if (run.timedOut)
  {
    seen += "hang";
    wrong = "vtkSceneVisModelReader hangs";
  }
  else if (run.signal != 0)
  {
    seen += "killed by signal " + std::to_string(run.signal);
    if (isolated)
    {
      wrong = "vtkSceneVisModelReader crashed with ReadInChildProcess on";
    }
    else if (c.expected != Outcome::ReaderCrash)
    {
      wrong = "vtkSceneVisModelReader crashed on a file VTK's reader survives";
    }
  }
  else if (run.exitCode == 0)
  {
    seen += "cells, no error";
    if (c.expected == Outcome::Rejected)
    {
      wrong = "vtkSceneVisModelReader read a file the tool rejects";
    }
  }
  else if (run.exitCode == 1)
  {
    seen += "one error, empty output (\"" + message + "\")";
    if (c.expected == Outcome::Renders)
    {
      wrong = "vtkSceneVisModelReader rejected a file the tool renders";
    }
    else if (c.expected == Outcome::Rejected && !std::regex_search(message, std::regex(c.message)))
    {
      wrong = std::string("vtkSceneVisModelReader's error does not match '") + c.message + "'";
    }
    else if (c.expected == Outcome::ReaderCrash && isolated &&
      !std::regex_search(message, std::regex("VTK's reader crashed on it")))
    {
      wrong = "vtkSceneVisModelReader's error does not say VTK's reader crashed";
    }
  }
  else
  {
    seen += "exit " + std::to_string(run.exitCode) + " (" + run.out + ")";
    wrong = "vtkSceneVisModelReader broke its contract (cells and no error, or one error and an "
            "empty output)";
  }
  if (problem.empty())
  {
    problem = wrong;
  }
}

/// Whether VTK's own reader, alone in a fresh process (this executable in --bare-read mode),
/// crashes on @p file: the signal of the first of up to 3 runs that crashed, else 0. This makes
/// "the crash is VTK's" a checked fact rather than a comment. Fresh processes, and more than one
/// run, because some of these crashes are heap corruption, whose symptom depends on the heap.
int BareVtkReaderSignal(const std::string& file, const std::string& scratch)
{
  for (int attempt = 0; attempt < 3; ++attempt)
  {
    const Run run = RunChild({ "/proc/self/exe", "--bare-read", file }, scratch);
    if (run.signal != 0)
    {
      return run.signal;
    }
  }
  return 0;
}

/// The VTK class that reads @p file.
std::string ReaderOf(const std::string& file)
{
  const std::string extension = file.substr(file.rfind('.') + 1);
  return extension == "ply" ? "vtkPLYReader"
    : extension == "stl"    ? "vtkSTLReader"
    : extension == "obj"    ? "vtkOBJReader"
                            : "vtkGLTFImporter";
}

/// Copy of @p source keeping the first @p fraction of its bytes, same extension.
std::string TruncatedCopy(
  const std::string& source, double fraction, const std::string& scratch, const std::string& key)
{
  const std::string bytes = ReadFile(source);
  const std::string::size_type dot = source.rfind('.');
  const std::string target =
    scratch + "/truncated-" + key + (dot == std::string::npos ? "" : source.substr(dot));
  std::ofstream out(target, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() * fraction));
  return target;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc == 3 && std::string(argv[1]) == "--bare-read")
  {
    return BareRead(argv[2]);
  }
  if (argc == 3 && std::string(argv[1]) == "--module-read")
  {
    return ModuleRead(argv[2], false);
  }
  if (argc == 3 && std::string(argv[1]) == "--module-read-isolated")
  {
    return ModuleRead(argv[2], true);
  }
  if (argc != 3)
  {
    std::cerr << "usage: scenevis_bad_input_models <scenevis> <scratch directory>\n";
    return EXIT_FAILURE;
  }
  const std::string tool = argv[1];
  const std::string scratch = argv[2];
  mkdir(scratch.c_str(), 0755);

  int failures = 0;
  int ran = 0;
  for (const Case& c : kCatalogue)
  {
    const std::string base = scenevis::testing::DataFile(c.dataKey);
    if (base.empty())
    {
      continue;
    }
    std::string file = *c.path ? base + "/" + c.path : base;
    std::string label = *c.path ? c.path : c.dataKey;
    if (c.keepFraction < 1.0)
    {
      file = TruncatedCopy(file, c.keepFraction, scratch, c.dataKey);
      label = std::string(c.dataKey) + " truncated to " +
        std::to_string(static_cast<int>(c.keepFraction * 100)) + "%";
    }
    ++ran;
    const std::string png = scratch + "/frame.png";
    std::remove(png.c_str());
    const Run run =
      RunChild({ tool, "render", "--scene", file, "--size", "64x48", "--out", png }, scratch);

    // Classify what happened.
    const std::vector<std::string> errLines = Lines(run.err);
    std::vector<std::string> toolLines;
    for (const std::string& line : errLines)
    {
      if (line.rfind("scenevis: ", 0) == 0)
      {
        toolLines.push_back(line);
      }
    }
    std::string problem;
    std::string seen;
    if (run.timedOut)
    {
      seen = "hang (killed after " + std::to_string(static_cast<int>(kTimeoutSeconds)) + " s)";
      problem = "the tool hangs";
    }
    else if (run.signal != 0)
    {
      seen = std::string("killed by signal ") + std::to_string(run.signal) + " (" +
        strsignal(run.signal) + ")";
      const std::string reader = ReaderOf(file);
      const int bare = BareVtkReaderSignal(file, scratch);
      if (bare > 0)
      {
        seen += "; VTK's " + reader + " alone dies of signal " + std::to_string(bare) +
          " too: the crash is VTK's";
      }
      else
      {
        seen += "; VTK's " + reader + " alone does not crash";
      }
      problem = "the tool crashed (it must read models in a child process and report a reader "
                "crash in one line)";
    }
    else if (run.exitCode == 0)
    {
      seen = "exit 0";
      auto image = scenevis::testing::ReadPng(png);
      const double covered = image ? scenevis::testing::CoveredFraction(image, { 26, 26, 31 }) : 0;
      seen += ", " + std::to_string(static_cast<int>(covered * 100 + 0.5)) + "% of pixels covered";
      if (c.expected != Outcome::Renders)
      {
        problem = std::string("expected ") + OutcomeName(c.expected) + ", but it rendered";
      }
      else if (!(covered > 0.0))
      {
        problem = "exit 0 with an empty (or missing) image";
      }
    }
    else
    {
      seen = "exit " + std::to_string(run.exitCode);
      const bool oneLine = toolLines.size() == 1;
      if (oneLine)
      {
        seen += ": \"" + toolLines.front() + "\"";
      }
      if (errLines.size() > toolLines.size())
      {
        seen += " (+" + std::to_string(errLines.size() - toolLines.size()) + " lines of VTK log)";
      }
      if (run.exitCode != 1)
      {
        problem = "exit code other than 0 or 1";
      }
      else if (!oneLine)
      {
        problem = "exit 1 without exactly one 'scenevis: ' error line (got " +
          std::to_string(toolLines.size()) + ")";
      }
      else if (c.expected == Outcome::Renders)
      {
        problem = "expected it to render";
      }
      else if (errLines.size() != 1)
      {
        problem = "VTK's log lines around the error line (one line alone is the contract)";
      }
      else if (c.expected == Outcome::ReaderCrash &&
        !std::regex_search(toolLines.front(), std::regex("crash", std::regex::icase)))
      {
        problem = "VTK's reader crashes on this file; the error line must say so";
      }
      else if (c.expected == Outcome::ReaderCrash)
      {
        const int bare = BareVtkReaderSignal(file, scratch);
        seen += bare > 0 ? "; VTK's " + ReaderOf(file) + " alone dies of signal " +
            std::to_string(bare) + " too: the crash is VTK's"
                         : "; VTK's " + ReaderOf(file) + " alone does not crash";
        if (bare <= 0)
        {
          problem = "VTK's reader alone survives this file: the crash is SceneVis's";
        }
      }
      else if (c.expected == Outcome::Rejected &&
        !std::regex_search(toolLines.front(), std::regex(c.message)))
      {
        problem = std::string("error line does not match '") + c.message + "'";
      }
    }
    CheckModuleReader(c, file, scratch, false, seen, problem);
    CheckModuleReader(c, file, scratch, true, seen, problem);
    std::cout << (problem.empty() ? "ok   " : "FAIL ") << label << " [" << c.why << "]: expected "
              << OutcomeName(c.expected) << ", got " << seen;
    std::cout << " (" << static_cast<int>(run.seconds * 1000) << " ms)\n";
    if (!problem.empty())
    {
      std::cout << "     " << problem << "\n";
      for (std::size_t l = 0; l < errLines.size() && l < 12; ++l)
      {
        std::cout << "     | " << errLines[l] << "\n";
      }
      ++failures;
    }
  }
  if (ran == 0)
  {
    std::cout << "the real data is not fetched (scripts/fetch-data.sh): skipped\n";
    return 77;
  }
  std::cout << ran << " files, " << failures << " failed\n";
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

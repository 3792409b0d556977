// Specification: bad GEOMETRY in well-formed files, end to end through `scenevis render` with
// every translucency method that SceneVis implements (issue 8), and through `scenevis portals`
// (rooms and portals found, or one error line and no file left; issue 14). The file is valid VTK
// XML; what is in it is not: NaN/Inf points, nothing at all, only degenerate polygons, no polygons,
// mixed cell types, non-planar and self-intersecting polygons, 1e7 offsets with 1e-3 features,
// extents of 1e-12 and 1e12. Each (file, method) pair runs in a child process with a timeout:
//
//   Renders    exit 0 and the PNG shows geometry;
//   Rejected   exit 1 with exactly one "scenevis: ..." line on stderr matching the pattern.
//
// A crash, a hang, exit 0 with an empty image or any other outcome than the table's fails.
// These renders run with the default --cull auto: on the files with few polygons mostly in axis
// planes (the extreme scales, the offsets), auto generates rooms and portals in memory
// (Tools/GeneratedRooms.h), so bad geometry reaches that path too; the methods that order one
// mesh (--sort bsp and the like) skip it.
//
// A second table holds bad inputs beside the geometry, each run once and Rejected (exit 1, one
// line, no image written): part arrays that are not one integer per cell or have more than a
// million distinct values, a part array named but missing, and camera files (--cameras) that
// are not JSON, nest without end, hold NaN or bytes, or describe no camera.
// Needs no fetched data: the files are written by this test.
//
// Usage: scenevis_bad_input_geometry <path of scenevis> <scratch directory>
#include "ChildProcess.h"

#include "scenevis/testing/ImageCompare.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkXMLPolyDataWriter.h>

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace
{
using namespace badinput;

/// Two overlapping spheres (parts 0 and 1 of a PartId array, for the multi-actor method),
/// with every point mapped to offset + scale * p.
vtkSmartPointer<vtkPolyData> TwoSpheres(double scale = 1.0, double offset = 0.0)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIdTypeArray> parts;
  parts->SetName("PartId");
  for (int s = 0; s < 2; ++s)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(16);
    sphere->SetPhiResolution(8);
    sphere->SetCenter(0.6 * s, 0.2 * s, 0.0);
    sphere->Update();
    vtkPolyData* part = sphere->GetOutput();
    const vtkIdType first = points->GetNumberOfPoints();
    for (vtkIdType i = 0; i < part->GetNumberOfPoints(); ++i)
    {
      double p[3];
      part->GetPoint(i, p);
      points->InsertNextPoint(offset + scale * p[0], offset + scale * p[1], offset + scale * p[2]);
    }
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    vtkCellArray* cells = part->GetPolys();
    for (cells->InitTraversal(); cells->GetNextCell(n, ids);)
    {
      std::vector<vtkIdType> shifted(ids, ids + n);
      for (vtkIdType& id : shifted)
      {
        id += first;
      }
      polys->InsertNextCell(n, shifted.data());
      parts->InsertNextValue(s);
    }
  }
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(parts);
  return pd;
}

vtkSmartPointer<vtkPolyData> WithBadPoints(double bad)
{
  vtkSmartPointer<vtkPolyData> pd = TwoSpheres();
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); i += 17)
  {
    pd->GetPoints()->SetPoint(i, bad, 0.0, bad);
  }
  return pd;
}

vtkSmartPointer<vtkPolyData> OnlyDegenerate()
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(2, 0, 0);
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell({ 0, 0, 1 }); // two distinct points
  polys->InsertNextCell({ 0, 1, 2 }); // collinear: zero area
  pd->SetPoints(points);
  pd->SetPolys(polys);
  return pd;
}

vtkSmartPointer<vtkPolyData> VertsAndLinesOnly()
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(1, 1, 0);
  vtkNew<vtkCellArray> verts;
  verts->InsertNextCell({ 0 });
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell({ 0, 1, 2 });
  pd->SetPoints(points);
  pd->SetVerts(verts);
  pd->SetLines(lines);
  return pd;
}

/// The two spheres plus verts, a line and a triangle strip through them.
vtkSmartPointer<vtkPolyData> MixedCells()
{
  vtkSmartPointer<vtkPolyData> pd = TwoSpheres();
  pd->GetCellData()->Initialize(); // per-poly arrays would not cover the new cells
  vtkPoints* points = pd->GetPoints();
  const vtkIdType first = points->GetNumberOfPoints();
  for (int i = 0; i < 6; ++i)
  {
    points->InsertNextPoint(-1.0 + 0.5 * (i / 2), (i % 2) ? 0.8 : -0.8, (i % 2) ? 0.3 : -0.3);
  }
  vtkNew<vtkCellArray> strips;
  strips->InsertNextCell({ first, first + 1, first + 2, first + 3, first + 4, first + 5 });
  vtkNew<vtkCellArray> verts;
  verts->InsertNextCell({ 0 });
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell({ 0, 1, 2 });
  pd->SetStrips(strips);
  pd->SetVerts(verts);
  pd->SetLines(lines);
  return pd;
}

/// A non-planar quad, a concave dart and a self-intersecting pentagon over a floor.
vtkSmartPointer<vtkPolyData> AwkwardPolygons()
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  const double p[][3] = { { -2, -2, 0 }, { 2, -2, 0 }, { 2, 2, 0 }, { -2, 2, 0 }, { -1, -1, 0.5 },
    { 1, -1, 1.5 }, { 1, 1, 0.5 }, { -1, 1, 1.5 }, { -1.5, 0, 1 }, { 1.5, -1, 1 }, { 0, 0, 1 },
    { 1.5, 1, 1 }, { -1, -1.5, 2 }, { 1, 1.5, 2 }, { 1.2, -1.5, 2 }, { -1, 1.5, 2 },
    { -1.3, 0, 2 } };
  for (const auto& q : p)
  {
    points->InsertNextPoint(q);
  }
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell({ 0, 1, 2, 3 });
  polys->InsertNextCell({ 4, 5, 6, 7 });
  polys->InsertNextCell({ 8, 9, 10, 11 });
  polys->InsertNextCell({ 12, 13, 14, 15, 16 });
  pd->SetPoints(points);
  pd->SetPolys(polys);
  return pd;
}

/// The two spheres with their PartId array replaced by @p parts (same name, one tuple a cell).
vtkSmartPointer<vtkPolyData> WithPartArray(vtkSmartPointer<vtkDataArray> parts)
{
  vtkSmartPointer<vtkPolyData> pd = TwoSpheres();
  const vtkIdType cells = pd->GetNumberOfCells();
  parts->SetName("PartId");
  parts->SetNumberOfTuples(cells);
  for (vtkIdType c = 0; c < cells; ++c)
  {
    for (int k = 0; k < parts->GetNumberOfComponents(); ++k)
      parts->SetComponent(c, k, c < cells / 2 ? 0.0 : 1.0);
  }
  pd->GetCellData()->RemoveArray("PartId");
  pd->GetCellData()->AddArray(parts);
  return pd;
}

/// 1,000,001 triangles (all on the same three points) with a distinct PartId each: one actor
/// per part would be a million actors.
vtkSmartPointer<vtkPolyData> MillionParts()
{
  constexpr vtkIdType kCells = 1000001;
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(kCells + 1);
  connectivity->SetNumberOfValues(3 * kCells);
  vtkNew<vtkIdTypeArray> parts;
  parts->SetName("PartId");
  parts->SetNumberOfValues(kCells);
  for (vtkIdType c = 0; c < kCells; ++c)
  {
    offsets->SetValue(c, 3 * c);
    for (vtkIdType k = 0; k < 3; ++k)
      connectivity->SetValue(3 * c + k, k);
    parts->SetValue(c, c);
  }
  offsets->SetValue(kCells, 3 * kCells);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(parts);
  return pd;
}

enum class Outcome
{
  Renders,
  Rejected
};

struct Case
{
  const char* name;
  std::function<vtkSmartPointer<vtkPolyData>()> make;
  Outcome expected;
  const char* message; ///< Rejected: regex the "scenevis:" line must match
};

const char* const kMethods[] = { "bsp", "painter", "bsp-mapper", "multi-actor", "depth-sort" };

/// A bad input other than geometry: a scene file (@p make) or a camera file (@p text), and the
/// options that read it; always Rejected.
struct InputCase
{
  const char* name;
  std::function<vtkSmartPointer<vtkPolyData>()> make; ///< null: the two spheres
  std::optional<std::string> cameras;                 ///< camera file text; none: no --cameras
  std::vector<std::string> options;
  const char* message;
};

bool WriteText(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text;
  return static_cast<bool>(out);
}

/// One line "ok"/"FAIL" for a run expected to exit 1 with one "scenevis: " line matching
/// @p message and to write no image @p png; returns whether it failed.
bool ReportRejected(
  const std::string& label, const Run& run, const char* message, const std::string& png)
{
  std::vector<std::string> toolLines;
  const std::vector<std::string> errLines = Lines(run.err);
  for (const std::string& line : errLines)
  {
    if (line.rfind("scenevis: ", 0) == 0)
      toolLines.push_back(line);
  }
  std::string problem;
  if (run.timedOut)
    problem = "the tool hangs";
  else if (run.signal != 0)
    problem = "the tool crashes (signal " + std::to_string(run.signal) + ")";
  else if (run.exitCode != 1)
    problem = "exit " + std::to_string(run.exitCode) + ", expected 1";
  else if (toolLines.size() != 1 || errLines.size() != 1)
    problem = "not exactly one line on stderr, a 'scenevis: ' one";
  else if (!std::regex_search(toolLines.front(), std::regex(message)))
    problem = std::string("error line does not match '") + message + "'";
  else if (std::ifstream(png).good())
    problem = "an image was written although the input was rejected";
  std::cout << (problem.empty() ? "ok   " : "FAIL ") << label << ": "
            << (toolLines.empty() ? std::string("(no error line)") : toolLines.front()) << " ("
            << static_cast<int>(run.seconds * 1000) << " ms)\n";
  if (!problem.empty())
  {
    std::cout << "     " << problem << "\n";
    for (std::size_t l = 0; l < errLines.size() && l < 12; ++l)
      std::cout << "     | " << errLines[l] << "\n";
  }
  return !problem.empty();
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc != 3)
  {
    std::cerr << "usage: scenevis_bad_input_geometry <scenevis> <scratch directory>\n";
    return EXIT_FAILURE;
  }
  const std::string tool = argv[1];
  const std::string scratch = argv[2];
  mkdir(scratch.c_str(), 0755);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  const Case catalogue[] = {
    { "nan-points", [&] { return WithBadPoints(nan); }, Outcome::Renders, "" },
    // The tool removes the cells that use NaN/Inf points before anything else (and says so): VTK's
    // bounds skip NaN but not Inf points, so one Inf point would otherwise empty every image.
    { "inf-points", [&] { return WithBadPoints(inf); }, Outcome::Renders, "" },
    { "empty", [] { return vtkSmartPointer<vtkPolyData>::New(); }, Outcome::Rejected,
      "cannot read .*empty\\.vtp" },
    // Nothing drawable: rejected, though "no drawable polygons" would say it better.
    { "only-degenerate", OnlyDegenerate, Outcome::Rejected, "the rendered image is empty" },
    // No polygons to sort: the verts and the line are drawn as they are.
    { "verts-and-lines-only", VertsAndLinesOnly, Outcome::Renders, "" },
    { "mixed-cells", MixedCells, Outcome::Renders, "" },
    { "non-planar-self-intersecting", AwkwardPolygons, Outcome::Renders, "" },
    { "offset-1e7-features-1e-3", [] { return TwoSpheres(1e-3, 1e7); }, Outcome::Renders, "" },
    { "extent-1e-12", [] { return TwoSpheres(1e-12, 0.0); }, Outcome::Renders, "" },
    { "extent-1e12", [] { return TwoSpheres(1e12, 0.0); }, Outcome::Renders, "" },
  };

  int failures = 0;
  for (const Case& c : catalogue)
  {
    const std::string file = scratch + "/" + c.name + ".vtp";
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(c.make());
    writer->SetFileName(file.c_str());
    if (writer->Write() != 1)
    {
      std::cout << "FAIL cannot write " << file << "\n";
      ++failures;
      continue;
    }
    for (const char* method : kMethods)
    {
      const std::string png = scratch + "/frame.png";
      std::remove(png.c_str());
      // At opacity 0.4: a model file is opaque by default, and these methods are for translucency.
      const Run run = RunChild({ tool, "render", "--scene", file, "--opacity", "0.4", "--sort",
                                 method, "--size", "64x48", "--out", png },
        scratch);
      const std::vector<std::string> errLines = Lines(run.err);
      std::vector<std::string> toolLines;
      for (const std::string& line : errLines)
      {
        if (line.rfind("scenevis: ", 0) == 0)
        {
          toolLines.push_back(line);
        }
      }
      std::string seen, problem;
      if (run.timedOut)
      {
        seen = "hang";
        problem = "the tool hangs";
      }
      else if (run.signal != 0)
      {
        seen = "killed by signal " + std::to_string(run.signal);
        problem = "the tool crashes";
      }
      else if (run.exitCode == 0)
      {
        auto image = scenevis::testing::ReadPng(png);
        const double covered =
          image ? scenevis::testing::CoveredFraction(image, { 26, 26, 31 }) : 0.0;
        seen = "exit 0, " + std::to_string(static_cast<int>(covered * 100 + 0.5)) + "% covered";
        if (c.expected != Outcome::Renders)
        {
          problem = "expected it to be rejected";
        }
        else if (!(covered > 0.0))
        {
          problem = "exit 0 with an empty (or missing) image";
        }
      }
      else
      {
        seen = "exit " + std::to_string(run.exitCode) +
          (toolLines.size() == 1 ? ": \"" + toolLines.front() + "\"" : std::string());
        if (run.exitCode != 1)
        {
          problem = "exit code other than 0 or 1";
        }
        else if (toolLines.size() != 1)
        {
          problem = "not exactly one 'scenevis: ' error line";
        }
        else if (c.expected != Outcome::Rejected)
        {
          problem = "expected it to render";
        }
        else if (!std::regex_search(toolLines.front(), std::regex(c.message)))
        {
          problem = std::string("error line does not match '") + c.message + "'";
        }
      }
      std::cout << (problem.empty() ? "ok   " : "FAIL ") << c.name << " --sort " << method
                << ": expected " << (c.expected == Outcome::Renders ? "renders" : "rejected")
                << ", got " << seen << " (" << static_cast<int>(run.seconds * 1000) << " ms)\n";
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
  }
  // `scenevis portals` on every file: rooms and portals found (exit 0, both files written) or one
  // error line (exit 1, neither file left behind); never a crash or a hang.
  for (const Case& c : catalogue)
  {
    const std::string file = scratch + "/" + c.name + ".vtp";
    const std::string prefix = scratch + "/portals-" + c.name;
    const std::string model = prefix + ".vtp", portals = prefix + "-portals.vtp";
    std::remove(model.c_str());
    std::remove(portals.c_str());
    const Run run = RunChild({ tool, "portals", "--scene", file, "--out", prefix }, scratch);
    std::size_t toolLines = 0;
    for (const std::string& line : Lines(run.err))
    {
      toolLines += line.rfind("scenevis: ", 0) == 0 ? 1 : 0;
    }
    struct stat st;
    const bool written = stat(model.c_str(), &st) == 0 && stat(portals.c_str(), &st) == 0;
    const bool partial =
      !written && (stat(model.c_str(), &st) == 0 || stat(portals.c_str(), &st) == 0);
    std::string problem;
    if (run.timedOut || run.signal != 0)
    {
      problem = run.timedOut ? "the tool hangs" : "killed by signal " + std::to_string(run.signal);
    }
    else if (run.exitCode == 0 && !written)
    {
      problem = "exit 0 without both files";
    }
    else if (run.exitCode == 1 && (toolLines != 1 || written || partial))
    {
      problem = "exit 1 without exactly one 'scenevis: ' line, or with files left behind";
    }
    else if (run.exitCode != 0 && run.exitCode != 1)
    {
      problem = "exit code " + std::to_string(run.exitCode);
    }
    std::cout << (problem.empty() ? "ok   " : "FAIL ") << c.name << " portals: exit "
              << run.exitCode << (written ? ", files written" : ", no files") << "\n";
    if (!problem.empty())
    {
      std::cout << "     " << problem << "\n";
      ++failures;
    }
  }

  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::string bytes;
  for (int b = 0; b < 256; ++b)
    bytes += static_cast<char>(b);
  const InputCase inputs[] = {
    { "part-array-float", [] { return WithPartArray(vtkSmartPointer<vtkFloatArray>::New()); },
      std::nullopt, {}, "cell array 'PartId' .*float values, not one integer per cell" },
    { "part-array-2-components",
      []
      {
        auto parts = vtkSmartPointer<vtkIdTypeArray>::New();
        parts->SetNumberOfComponents(2);
        return WithPartArray(parts);
      },
      std::nullopt, {}, "cell array 'PartId' .*2-component" },
    { "part-array-1000001-values", MillionParts, std::nullopt, { "--sort", "none" },
      "more than 1000000 distinct values" },
    { "part-array-named-missing", nullptr, std::nullopt, { "--part-array", "Body" },
      "no cell array 'Body' .*its cell arrays: PartId" },
    { "cameras-not-json", nullptr, "eye 0 0 15", {}, "--cameras .*not valid JSON" },
    { "cameras-nested-100000-deep", nullptr, deep, {}, "nested deeper than" },
    { "cameras-bytes-0-255", nullptr, bytes, {}, "not valid JSON: .*unexpected byte 0x00$" },
    { "cameras-nan", nullptr, R"([{"eye": [NaN, 0, 15], "focal": [0, 0, 0]}])", {},
      "NaN and Infinity" },
    { "cameras-none", nullptr, "[]", {}, "has no cameras" },
    { "cameras-eye-is-focal", nullptr, R"([{"eye": [0, 0, 0], "focal": [0, 0, 0]}])", {},
      "'eye' equals 'focal'" },
  };
  for (const InputCase& c : inputs)
  {
    const std::string file = scratch + "/" + c.name + ".vtp";
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(c.make ? c.make() : TwoSpheres());
    writer->SetFileName(file.c_str());
    if (writer->Write() != 1)
    {
      std::cout << "FAIL cannot write " << file << "\n";
      ++failures;
      continue;
    }
    const std::string png = scratch + "/input.png";
    std::remove(png.c_str());
    std::remove((scratch + "/input-0.png").c_str());
    std::vector<std::string> command = { tool, "render", "--scene", file, "--size", "64x48",
      "--out", png };
    if (c.cameras)
    {
      const std::string cameras = scratch + "/" + c.name + ".json";
      if (!WriteText(cameras, *c.cameras))
      {
        std::cout << "FAIL cannot write " << cameras << "\n";
        ++failures;
        continue;
      }
      command.insert(command.end(), { "--cameras", cameras });
    }
    command.insert(command.end(), c.options.begin(), c.options.end());
    const Run run = RunChild(command, scratch);
    failures += ReportRejected(c.name, run, c.message, png) ? 1 : 0;
  }

  std::cout << failures << " failed\n";
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

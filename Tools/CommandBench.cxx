// `scenevis bench`: accuracy against time of every translucency method, as a CSV table and a
// plot of frame time against image error.
#include "Commands.h"
#include "MethodPipeline.h"
#include "Progress.h"
#include "SceneLoading.h"
#include "ViewSetup.h"

#include <vtkSceneVisDataCache.h>
#include <vtkSceneVisHeadlessWindows.h>
#include <vtkSceneVisIdBuffer.h>
#include <vtkSceneVisImageCompare.h>

#include <vtkAxis.h>
#include <vtkCamera.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenevis
{
namespace tool
{
namespace
{
/// One method on one scene in the accuracy-versus-time report.
struct BenchRow
{
  std::string method;
  std::string scene;
  vtkIdType triangles = 0;
  double fragments = 0.0;     ///< mean over the timed frames
  double frameMs = 0.0;       ///< median of (sort + render + glFinish)
  double sortMs = 0.0;        ///< median
  double setupMs = 0.0;       ///< the untimed warm-up frame (builds, shader compilation)
  double meanAbsError = 0.0;  ///< vs peel:100, mean over frames
  double badPercent = 0.0;    ///< % of covered pixels off by > 16 levels, mean over frames
  double misordered = -1.0;   ///< ID oracle, mean over frames; < 0: not applicable
  double compared = 0.0;      ///< pixels the oracle compared (outside the edge mask), mean
  double misorderedAll = 0.0; ///< the oracle without the edge mask (every pixel), mean
  bool skipped = false;
  std::string note;
};

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double Mean(const std::vector<double>& values)
{
  return values.empty()
    ? 0.0
    : std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

/// The scene's name in the report: the demo name, the data key, or the file's stem.
std::string SceneLabel(const std::string& scene)
{
  const auto slash = scene.find_last_of('/');
  std::string name = slash == std::string::npos ? scene : scene.substr(slash + 1);
  const auto dot = name.find('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

constexpr vtkIdType kPainterMaxTriangles = 20000;
const char* const kBenchMethods[] = { "none", "oit", "depth-sort", "painter", "bsp",
  "bsp-leaves:64", "bsp-mapper", "multi-actor", "peel:4", "peel:100" };
const char* const kReferenceMethod = "peel:100";

/// Runs one method on a loaded scene; `reference` holds peel:100's frames (filled when `method`
/// is the reference itself); `parts` are the scene's parts (multi-actor draws one actor each).
BenchRow BenchMethod(const Options& options, const std::string& method, const std::string& label,
  vtkPolyData* pd, const std::vector<vtkSmartPointer<vtkPolyData>>& parts, vtkRenderWindow* window,
  std::vector<vtkSmartPointer<vtkImageData>>& reference)
{
  namespace headless = scenevis::headless;
  namespace idbuffer = scenevis::idbuffer;
  BenchRow row;
  row.method = method;
  row.scene = label;
  row.triangles = CountTriangles(pd);
  const bool isReference = method == kReferenceMethod;

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  window->AddRenderer(renderer);
  {
    MethodPipeline pipeline(
      method, pd, renderer, false, method == "multi-actor" ? &parts : nullptr);
    SetUpCamera(options.camera, renderer, pd);
    vtkCamera* camera = renderer->GetActiveCamera();

    // Warm-up frame at the start camera: tree builds, shader compilation, first uploads.
    auto start = std::chrono::steady_clock::now();
    pipeline.Update();
    window->Render();
    window->WaitForCompletion();
    row.setupMs = Milliseconds(start);

    std::vector<double> frameMs, sortMs, fragments, errors, bad, misordered, compared,
      misorderedAll;
    for (int f = 0; f < options.frames; ++f)
    {
      camera->Azimuth(options.orbit);
      ResetClippingRange(options.camera, renderer);
      start = std::chrono::steady_clock::now();
      pipeline.Update();
      window->Render();
      window->WaitForCompletion();
      frameMs.push_back(Milliseconds(start));
      sortMs.push_back(pipeline.LastSortMs());
      fragments.push_back(static_cast<double>(pipeline.Fragments()));

      // Accuracy, untimed: the camera did not move, so nothing is sorted again.
      vtkSmartPointer<vtkImageData> image = headless::CaptureImage(window);
      if (isReference)
      {
        reference.push_back(image);
      }
      else
      {
        const headless::ImageDifference difference =
          headless::CompareImages(image, reference.at(static_cast<std::size_t>(f)), kBackgroundRgb);
        if (!difference.comparable)
        {
          throw std::runtime_error("cannot compare with the reference: " + difference.problem);
        }
        errors.push_back(difference.meanAbsError);
        bad.push_back(100.0 * difference.coveredBadFraction);
      }
      if (vtkSmartPointer<vtkPolyData> drawn = pipeline.DrawnOrder())
      {
        const idbuffer::IdImage painterIds = idbuffer::RenderPainterIds(window, drawn, camera);
        const idbuffer::IdImage depthIds = idbuffer::RenderVisibleIds(window, drawn, camera);
        const idbuffer::OrderComparison order = idbuffer::OrderMatchesDepth(painterIds, depthIds);
        // Without the edge mask: on fine meshes (triangles of a few pixels) nearly every pixel
        // is next to another id, so the masked comparison sees little; every pixel counts here,
        // at the price of a few legitimate differences along intersection lines.
        const idbuffer::OrderComparison unmasked = idbuffer::OrderMatchesDepth(
          painterIds, depthIds, std::vector<std::uint8_t>(depthIds.ids.size(), std::uint8_t(0)));
        if (!order.problem.empty() || !unmasked.problem.empty())
        {
          throw std::runtime_error("ID oracle: " + order.problem + unmasked.problem);
        }
        misordered.push_back(static_cast<double>(order.mismatchedPixels));
        compared.push_back(static_cast<double>(order.comparedPixels));
        misorderedAll.push_back(static_cast<double>(unmasked.mismatchedPixels));
      }
    }
    row.frameMs = Median(frameMs);
    row.sortMs = Median(sortMs);
    row.fragments = Mean(fragments);
    row.meanAbsError = Mean(errors);
    row.badPercent = Mean(bad);
    row.misordered = misordered.empty() ? -1.0 : Mean(misordered);
    row.compared = Mean(compared);
    row.misorderedAll = Mean(misorderedAll);
    if (isReference)
      row.note = "reference";
    else if (method == "bsp-mapper")
      row.note = "sort inside the render; fragments not exposed to the ID oracle";
    else if (method.rfind("bsp-leaves:", 0) == 0)
      row.note = "vtkBSPSortFilter with ordered leaves of up to " + method.substr(11) +
        " polygons; fragments drawn per view";
    else if (method == "multi-actor")
      row.note = std::to_string(pipeline.Parts()) + " actors; sort inside the render";
    else if (method == "oit" || method.rfind("peel:", 0) == 0)
      row.note = "order independent: no drawing order to check";
  }
  window->RemoveRenderer(renderer);
  return row;
}

std::string CsvField(const std::string& text)
{
  if (text.find_first_of(",\"\n") == std::string::npos)
  {
    return text;
  }
  std::string out = "\"";
  for (char c : text)
  {
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return out + "\"";
}

void WriteCsv(const std::vector<BenchRow>& rows, const std::string& path)
{
  std::ofstream csv(path);
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
  csv << "method,scene,triangles,fragments,median_frame_ms,sort_ms,mean_abs_error,"
         "bad_pixels_percent,misordered_pixels,oracle_pixels,misordered_unmasked,setup_ms,note\n";
  csv << std::fixed;
  for (const BenchRow& row : rows)
  {
    csv << CsvField(row.method) << "," << CsvField(row.scene) << "," << row.triangles << ",";
    if (row.skipped)
    {
      csv << ",,,,,,,,," << CsvField(row.note) << "\n";
      continue;
    }
    csv << std::setprecision(0) << row.fragments << "," << std::setprecision(3) << row.frameMs
        << "," << row.sortMs << "," << row.meanAbsError << "," << row.badPercent << ",";
    if (row.misordered >= 0.0)
    {
      csv << std::setprecision(1) << row.misordered << "," << std::setprecision(0) << row.compared
          << "," << std::setprecision(1) << row.misorderedAll;
    }
    else
    {
      csv << ",,";
    }
    csv << "," << std::setprecision(1) << row.setupMs << "," << CsvField(row.note) << "\n";
  }
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

/// Frame time (log x) against mean absolute error, one chart per scene, one marker per method.
void WritePlot(const std::vector<BenchRow>& rows, const std::vector<std::string>& scenes,
  const Options& options, const std::string& path)
{
  const int count = static_cast<int>(scenes.size());
  vtkSmartPointer<vtkRenderWindow> window =
    scenevis::headless::MakeRenderWindow(std::max(1, count) * 520, 900);
  vtkNew<vtkContextView> view;
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  window->AddRenderer(view->GetRenderer());
  vtkNew<vtkChartMatrix> matrix;
  matrix->SetSize(vtkVector2i(std::max(1, count), 2));
  matrix->SetGutter(vtkVector2f(70.0f, 70.0f));
  matrix->SetBorders(70, 60, 20, 40);
  view->GetScene()->AddItem(matrix);

  const unsigned char colors[][3] = { { 228, 26, 28 }, { 255, 127, 0 }, { 166, 86, 40 },
    { 152, 78, 163 }, { 55, 126, 184 }, { 77, 175, 74 }, { 0, 170, 170 }, { 247, 129, 191 },
    { 60, 60, 60 } };
  const int markers[] = { vtkPlotPoints::CROSS, vtkPlotPoints::PLUS, vtkPlotPoints::SQUARE,
    vtkPlotPoints::CIRCLE, vtkPlotPoints::DIAMOND };
  // Top row: mean absolute error; bottom row: % of covered pixels off by more than 16 levels.
  for (int cell = 0; cell < 2 * count; ++cell)
  {
    const int i = cell % count;
    const bool top = cell < count;
    auto value = [top](const BenchRow& row) { return top ? row.meanAbsError : row.badPercent; };
    auto* chart = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(i, top ? 1 : 0)));
    if (!chart)
    {
      continue;
    }
    vtkIdType triangles = 0;
    for (const BenchRow& row : rows)
    {
      if (row.scene == scenes[static_cast<std::size_t>(i)])
        triangles = row.triangles;
    }
    chart->SetTitle(scenes[static_cast<std::size_t>(i)] + " (" + std::to_string(triangles) +
      " triangles, " + std::to_string(options.width) + "x" + std::to_string(options.height) + ")" +
      (top ? "" : ": bad pixels"));
    chart->GetTitleProperties()->SetFontSize(16);
    // Log scale by hand (x = log10(ms), ticks labelled in ms): VTK 9.1's log axes misplace
    // plots of single points.
    vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
    x->SetTitle("median frame time (ms, log scale)");
    double minMs = 1e300;
    double maxMs = 0.0;
    for (const BenchRow& row : rows)
    {
      if (row.scene == scenes[static_cast<std::size_t>(i)] && !row.skipped)
      {
        minMs = std::min(minMs, std::max(row.frameMs, 1e-3));
        maxMs = std::max(maxMs, std::max(row.frameMs, 1e-3));
      }
    }
    if (maxMs <= 0.0)
    {
      minMs = maxMs = 1.0;
    }
    const double lo = std::floor(std::log10(minMs) - 0.05);
    const double hi = std::ceil(std::log10(maxMs) + 0.05);
    x->SetBehavior(vtkAxis::FIXED);
    x->SetMinimum(lo);
    x->SetMaximum(hi);
    vtkNew<vtkDoubleArray> tickPositions;
    vtkNew<vtkStringArray> tickLabels;
    for (int decade = static_cast<int>(lo); decade <= static_cast<int>(hi); ++decade)
    {
      for (const double mantissa : { 1.0, 2.0, 5.0 })
      {
        const double position = decade + std::log10(mantissa);
        if (position > hi + 1e-9)
        {
          break;
        }
        std::ostringstream label;
        label << mantissa * std::pow(10.0, decade);
        tickPositions->InsertNextValue(position);
        tickLabels->InsertNextValue(label.str());
      }
    }
    x->SetCustomTickPositions(tickPositions, tickLabels);
    vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
    y->SetTitle(top ? "mean abs. error vs peel:100 (levels)"
                    : "% covered pixels off by > 16 levels vs peel:100");
    y->SetMinimum(0.0);
    y->SetBehavior(vtkAxis::FIXED);
    double maxError = top ? 0.5 : 1.0;
    for (const BenchRow& row : rows)
    {
      if (row.scene == scenes[static_cast<std::size_t>(i)] && !row.skipped)
        maxError = std::max(maxError, value(row));
    }
    y->SetMaximum(maxError * 1.15);
    // One table per chart: a row per method that ran, the frame time, and one error column per
    // method that is NaN except in its own row (NaN points are not drawn), so that every method
    // is its own plot (own colour, marker and legend entry) on shared x values.
    std::vector<const BenchRow*> shown;
    std::vector<int> shownIndex;
    int m = 0;
    for (const char* method : kBenchMethods)
    {
      for (const BenchRow& row : rows)
      {
        if (row.scene == scenes[static_cast<std::size_t>(i)] && row.method == method &&
          !row.skipped)
        {
          shown.push_back(&row);
          shownIndex.push_back(m);
        }
      }
      ++m;
    }
    vtkNew<vtkTable> table;
    vtkNew<vtkDoubleArray> time;
    time->SetName("time");
    for (const BenchRow* row : shown)
    {
      time->InsertNextValue(std::log10(std::max(row->frameMs, 1e-3)));
    }
    table->AddColumn(time);
    for (std::size_t k = 0; k < shown.size(); ++k)
    {
      vtkNew<vtkDoubleArray> error;
      error->SetName(shown[k]->method.c_str());
      for (std::size_t r = 0; r < shown.size(); ++r)
      {
        error->InsertNextValue(r == k ? value(*shown[k]) : std::nan(""));
      }
      table->AddColumn(error);
    }
    for (std::size_t k = 0; k < shown.size(); ++k)
    {
      const int index = shownIndex[k];
      vtkPlot* plot = chart->AddPlot(vtkChart::POINTS);
      plot->SetInputData(table, 0, static_cast<vtkIdType>(k + 1));
      plot->SetColor(colors[index][0], colors[index][1], colors[index][2], 255);
      plot->SetLabel(shown[k]->method);
      plot->SetWidth(2.0f);
      if (auto* points = vtkPlotPoints::SafeDownCast(plot))
      {
        points->SetMarkerStyle(markers[index % 5]);
        points->SetMarkerSize(14.0f);
      }
    }
    chart->SetShowLegend(top);
    chart->GetLegend()->GetLabelProperties()->SetFontSize(13);
  }
  vtkSmartPointer<vtkImageData> image = scenevis::headless::CaptureImage(window);
  window->RemoveRenderer(view->GetRenderer());
  if (!scenevis::headless::WritePng(image, path))
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}
} // namespace

int RunBench(const Options& options)
{
  ApplyBackendOption(options);
  std::vector<std::string> scenes = options.scenes;
  if (scenes.empty())
  {
    scenes = { "spheres", "cyclic-quads" };
    if (!scenevis::DataFile("bunny-stl").empty())
    {
      scenes.push_back("bunny-stl");
    }
  }
  if (!options.outDir.empty())
  {
    std::string partial;
    std::stringstream dirs(options.outDir);
    std::string piece;
    if (options.outDir[0] == '/')
      partial = "/";
    while (std::getline(dirs, piece, '/'))
    {
      if (piece.empty())
        continue;
      partial += piece + "/";
      mkdir(partial.c_str(), 0755);
    }
  }
  const std::string csvPath = options.outDir + "/accuracy-vs-time.csv";
  const std::string plotPath = options.outDir + "/accuracy-vs-time.png";

  std::vector<BenchRow> rows;
  std::vector<std::string> labels;
  std::cout << std::fixed << std::setprecision(2);
  std::cout << "scenevis bench: " << scenes.size() << " scene(s), " << options.frames
            << " frames of " << options.orbit << " deg, " << options.width << "x" << options.height
            << "\n";
  {
    vtkSmartPointer<vtkRenderWindow> window =
      scenevis::headless::MakeRenderWindow(options.width, options.height);
    for (const std::string& scene : scenes)
    {
      Options sceneOptions = options;
      sceneOptions.scene = scene;
      const LoadedScene loaded = LoadSceneWithNormals(sceneOptions);
      vtkPolyData* pd = loaded.polydata;
      const std::string label = SceneLabel(scene);
      labels.push_back(label);
      const vtkIdType triangles = CountTriangles(pd);
      const std::vector<vtkSmartPointer<vtkPolyData>> groups = SplitByPart(pd, options.partArray);
      const std::size_t parts = groups.size();
      std::cout << "  " << label << ": " << loaded.description << ", " << triangles
                << " triangles, " << parts << " part(s)\n";

      std::vector<vtkSmartPointer<vtkImageData>> reference;
      std::map<std::string, BenchRow> results;
      // The reference first: every other method is compared with its frames.
      std::vector<std::string> runOrder = { kReferenceMethod };
      for (const char* method : kBenchMethods)
      {
        if (method != std::string(kReferenceMethod))
          runOrder.emplace_back(method);
      }
      for (const std::string& method : runOrder)
      {
        BenchRow row;
        if (method == "painter" && triangles > kPainterMaxTriangles)
        {
          row.note = "skipped: more than " + std::to_string(kPainterMaxTriangles) +
            " triangles (the painter's sort is quadratic in the worst case)";
        }
        else if (method == "multi-actor" && parts < 2)
        {
          row.note = "skipped: the scene has no parts (" + options.partArray + ")";
        }
        if (!row.note.empty())
        {
          row.method = method;
          row.scene = label;
          row.triangles = triangles;
          row.skipped = true;
          std::cout << "    " << std::setw(11) << std::left << method << std::right << " "
                    << row.note << "\n";
        }
        else
        {
          row = BenchMethod(sceneOptions, method, label, pd, groups, window, reference);
          std::cout << "    " << std::setw(11) << std::left << method << std::right << " frame "
                    << std::setw(9) << row.frameMs << " ms, sort " << std::setw(9) << row.sortMs
                    << " ms, error " << std::setw(6) << row.meanAbsError << " levels, "
                    << std::setw(6) << row.badPercent << " % bad";
          if (row.misordered >= 0.0)
          {
            std::cout << ", misordered " << row.misordered << " of " << row.compared
                      << " px (unmasked " << row.misorderedAll << ")";
          }
          std::cout << std::endl;
        }
        results[method] = row;
      }
      for (const char* method : kBenchMethods)
      {
        rows.push_back(results[method]);
      }
    }
  }
  WriteCsv(rows, csvPath);
  WritePlot(rows, labels, options, plotPath);
  std::cout << "  wrote " << csvPath << " and " << plotPath << "\n";
  return EXIT_SUCCESS;
}

} // namespace tool
} // namespace scenevis

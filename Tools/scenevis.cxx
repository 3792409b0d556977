// scenevis: the SceneVis command-line tool. Renders a model or an embedded demo scene offscreen
// with a chosen translucency method, writes PNG frames and a JSON report of what was done and how
// long it took; writes sorted polydata for a camera; measures accuracy against time of every
// translucency method (`bench`). `scenevis --help` documents it.
#include "vtkBSPSortFilter.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkChunkedPolyDataMapper.h"
#include "vtkDemoSceneSource.h"
#include "vtkOcclusionCuller.h"
#include "vtkMatrix4x4.h"
#include "vtkOctreeCuller.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPainterSortFilter.h"
#include "vtkPortalCuller.h"

#include "scenevis/Scenes.h"

#include "CameraFile.h"
#include "Instances.h"
#include "Memory.h"
#include "SplitParts.h"
#include "AutoPlan.h"
#include "CullSetup.h"
#include "MethodPipeline.h"
#include "Options.h"
#include "Progress.h"
#include "Report.h"
#include "SceneLoading.h"
#include "ViewSetup.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkAbstractArray.h>
#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkAxis.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkCommand.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkCuller.h>
#include <vtkCullerCollection.h>
#include <vtkDataArray.h>
#include <vtkDepthSortPolyData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkLogger.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

// The chart (bench plot) needs the 2D context device and text rendering; the harness initialises
// the OpenGL2 rendering overrides itself.
VTK_MODULE_INIT(vtkRenderingContextOpenGL2);
VTK_MODULE_INIT(vtkRenderingFreeType);
VTK_MODULE_INIT(vtkInteractionStyle); // vtkContextView makes an interactor style

namespace
{
using scenevis::tool::SplitByKeys;
constexpr int kExitUsage = 2;
constexpr int kExitFailure = 1;

using namespace scenevis::tool;

int Render(const Options& options)
{
  ApplyBackendOption(options);
  LoadedScene scene = LoadSceneWithNormals(options);
  vtkPolyData* pd = scene.polydata;
  // The polydata as loaded, with the cell storage the reader gave it (the figure peak memory is
  // compared with: BENCHMARKS.md, "48.6M triangles from file to frames").
  const double polydataBytes = 1024.0 * static_cast<double>(pd->GetActualMemorySize()) +
    static_cast<double>(scene.compactedBytes);

  const auto windowStart = std::chrono::steady_clock::now();
  const scenevis::testing::Backend backend = scenevis::testing::DefaultBackend();
  vtkSmartPointer<vtkRenderWindow> window =
    scenevis::testing::MakeRenderWindow(backend, options.width, options.height);
  const double windowMs = Milliseconds(windowStart);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  window->AddRenderer(renderer);
  // With --cameras, every camera is one frame; else the command line's camera, orbited.
  const bool perCamera = !options.cameras.empty();
  const std::vector<scenevis::tool::CameraSpec> cameras = CamerasToRun(options);
  const int frameCount = perCamera ? static_cast<int>(cameras.size()) : options.frames;
  double bounds[6];
  const auto boundsStart = std::chrono::steady_clock::now();
  SceneBounds(scene, bounds);
  const double boundsMs = Milliseconds(boundsStart);
  SetUpCamera(cameras[0], renderer, bounds, scene.zUp); // auto looks at what the first frame sees
  const ScenePlan plan =
    PlanScene(options, scene, options.sort, renderer, /*releaseSplitScene=*/true);
  if (!plan.instanced && plan.groups.size() > 1)
  {
    // The parts are drawn, not the flattened scene they were split from: its polygons went back
    // as soon as the parts had theirs, the rest goes before the parts get mappers and buffers.
    scene.polydata = nullptr;
    pd = nullptr;
  }
  const bool translucent = plan.facts.translucentFraction > 0.0;
  const std::string& method = plan.sort;
  std::string reason = plan.sortReason;
  const bool onTerminal = ProgressBar::OnTerminal();
  const auto actorsStart = std::chrono::steady_clock::now();
  MethodPipeline pipeline(
    method, pd, renderer, onTerminal, &plan.groups, plan.cull.chunked, plan.instanced);
  const double actorsMs = Milliseconds(actorsStart);
  if (method == "multi-actor" && !plan.instanced)
  {
    const std::string& part = options.partArray;
    reason += "; " + std::to_string(pipeline.Parts()) +
      (pipeline.Parts() == 1 ? " actor (the scene has no " + part + " parts)"
          : plan.cull.needsActors && plan.facts.rooms > 0
          ? " actors, one per part (" + part + ") and room (" + options.roomArray + ")"
          : " actors, one per part (" + part + ")");
  }
  SetUpCamera(cameras[0], renderer, bounds, scene.zUp); // again: the clipping range from the actors
  const auto cullersStart = std::chrono::steady_clock::now();
  const CullSetup culling(plan.cull, pipeline, renderer, pd, scene.portals, onTerminal);
  const double cullersMs = Milliseconds(cullersStart);

  struct Frame
  {
    std::string file;
    std::string camera; ///< JSON
    bool cameraUnchanged = false;
    bool sorted = false;
    bool cullReused = false;
    double sortMs = 0.0;
    double cullMs = 0.0;
    double renderMs = 0.0;
    vtkIdType propsDrawn = 0;
    vtkIdType trianglesDrawn = 0;
    vtkIdType polygonsDrawn = 0;
  };
  std::vector<Frame> frames;
  double buildMs = 0.0;
  double firstFrameMs = 0.0;      ///< since the tool started
  double firstFrameTotalMs = 0.0; ///< the first frame's update and render
  vtkNew<ProgressBar> progress;
  progress->Label = "rendering " + std::to_string(frameCount) + " frames";
  const bool showFrames = onTerminal && frameCount > 1;
  for (int f = 0; f < frameCount; ++f)
  {
    const scenevis::tool::CameraSpec& spec = cameras[perCamera ? static_cast<std::size_t>(f) : 0];
    Frame frame;
    if (perCamera)
    {
      frame.file = CameraFileName(options.out, static_cast<std::size_t>(f), ".png");
      if (f > 0)
        SetUpCamera(spec, renderer, bounds, scene.zUp);
    }
    else
    {
      frame.file = FrameFileName(options.out, f, options.frames);
      // An orbit of 0 degrees leaves the camera as it is: nothing needs sorting or culling again.
      frame.cameraUnchanged = f > 0 && options.orbit == 0.0;
      if (f > 0 && !frame.cameraUnchanged)
      {
        renderer->GetActiveCamera()->Azimuth(options.orbit);
        ResetClippingRange(spec, renderer);
      }
    }
    const auto updateStart = std::chrono::steady_clock::now();
    pipeline.Update();
    const auto renderStart = std::chrono::steady_clock::now();
    vtkSmartPointer<vtkImageData> image = scenevis::testing::CaptureImage(window);
    const double totalMs = Milliseconds(renderStart);
    if (f == 0)
    {
      firstFrameMs = Milliseconds(kProgramStart);
      firstFrameTotalMs = Milliseconds(updateStart);
    }
    frame.sortMs = pipeline.LastSortMs();
    frame.sorted = pipeline.Sorted();
    frame.cullMs = culling.CullMs();
    frame.cullReused = culling.Reused();
    // The render time without what was measured inside it: the cull, and the sort of the
    // mapper and pass methods.
    frame.renderMs =
      std::max(0.0, totalMs - frame.cullMs - (pipeline.SortsInRender() ? frame.sortMs : 0.0));
    frame.propsDrawn = culling.PropsDrawn();
    frame.trianglesDrawn = culling.TrianglesDrawn();
    frame.polygonsDrawn = pipeline.Fragments();
    frame.camera = JsonCamera(renderer->GetActiveCamera(), spec.FixedClippingRange());
    if (f == 0)
    {
      buildMs = pipeline.BuildMs();
    }
    if (!scenevis::testing::WritePng(image, frame.file))
    {
      throw std::runtime_error("cannot write '" + frame.file + "'");
    }
    if (scenevis::testing::CoveredFraction(image, kBackgroundRgb) <= 0.0)
    {
      throw std::runtime_error(
        (perCamera ? "camera " + std::to_string(f) + " of " + options.camerasFile + ": "
                   : std::string()) +
        "the rendered image is empty (nothing in view?)");
    }
    frames.push_back(frame);
    if (showFrames)
    {
      progress->Show(static_cast<double>(f + 1) / frameCount);
    }
  }

  // Report.
  const vtkIdType cells = plan.facts.polygons;
  const scenevis::tool::ResidentMemory memory = scenevis::tool::ReadResidentMemory();
  const double accountedMs = scene.loadMs + scene.checkMs + scene.normalsMs + windowMs + boundsMs +
    plan.inspectMs + plan.splitMs + actorsMs + cullersMs + firstFrameTotalMs;
  std::ostringstream json;
  std::ostringstream details;
  json << std::fixed << std::setprecision(3);
  details << std::fixed << std::setprecision(1);
  json << "{\n  \"command\": \"render\",\n  \"scene\": " << JsonString(scene.description)
       << ",\n  \"polygons\": " << cells << ",\n  \"triangles\": " << plan.facts.triangles
       << ",\n  \"parts\": " << plan.facts.parts
       << ",\n  \"translucent_fraction\": " << std::setprecision(4)
       << plan.facts.translucentFraction << std::setprecision(3)
       << ",\n  \"rooms\": " << plan.facts.rooms << ",\n  \"portals\": " << plan.facts.portals
       << ",\n  \"translucent\": " << (translucent ? "true" : "false")
       << ",\n  \"translucency\": {\"method\": " << JsonString(method)
       << ", \"reason\": " << JsonString(reason)
       << "},\n  \"culling\": {\"method\": " << JsonString(plan.cull.method)
       << ", \"reason\": " << JsonString(plan.cull.reason);
  culling.Describe(json);
  json << "},\n  \"backend\": " << JsonString(scenevis::testing::BackendName(backend))
       << ",\n  \"size\": [" << options.width << ", " << options.height
       << "],\n  \"load_ms\": " << scene.loadMs << ",\n  \"check_ms\": " << scene.checkMs
       << ",\n  \"normals_ms\": " << scene.normalsMs << ",\n  \"window_ms\": " << windowMs
       << ",\n  \"bounds_ms\": " << boundsMs
       << ",\n  \"inspect_ms\": " << plan.inspectMs << ",\n  \"split_ms\": " << plan.splitMs
       << ",\n  \"actors_ms\": " << actorsMs << ",\n  \"cullers_ms\": " << cullersMs
       << ",\n  \"build_ms\": " << buildMs << ",\n  \"cull_setup_ms\": " << culling.SetupMs()
       << ",\n  \"first_frame_ms\": " << firstFrameMs
       << ",\n  \"unaccounted_ms\": " << std::max(0.0, firstFrameMs - accountedMs)
       << ",\n  \"memory\": {\"peak_rss\": " << memory.peak
       << ", \"rss_after_load\": " << scene.rssAfterLoad << ", \"rss_end\": " << memory.current
       << ", \"polydata_bytes\": " << polydataBytes
       << ", \"cells_compacted_bytes\": " << scene.compactedBytes
       << ", \"peak_over_polydata\": " << static_cast<double>(memory.peak) / polydataBytes
       << ", \"peak_bytes_per_triangle\": "
       << static_cast<double>(memory.peak) /
      static_cast<double>(std::max<vtkIdType>(1, plan.facts.triangles))
       << "}"
       << ",\n  \"sort_in_render\": " << (pipeline.SortsInRender() ? "true" : "false");
  if (perCamera)
    json << ",\n  \"cameras_file\": " << JsonString(options.camerasFile);
  pipeline.Describe(json, details);
  json << ",\n  \"frames\": [";
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    const Frame& frame = frames[i];
    json << (i ? "," : "") << "\n    {\"file\": " << JsonString(frame.file)
         << ", \"camera_unchanged\": " << (frame.cameraUnchanged ? "true" : "false")
         << ", \"sorted\": " << (frame.sorted ? "true" : "false")
         << ", \"cull_reused\": " << (frame.cullReused ? "true" : "false")
         << ", \"sort_ms\": " << frame.sortMs << ", \"cull_ms\": " << frame.cullMs
         << ", \"render_ms\": " << frame.renderMs << ", \"props_drawn\": " << frame.propsDrawn
         << ", \"triangles_drawn\": " << frame.trianglesDrawn
         << ", \"polygons_drawn\": " << frame.polygonsDrawn
         << ",\n     \"camera\": " << frame.camera << "}";
  }
  json << "\n  ]\n}\n";
  if (!options.report.empty())
    WriteReport(json.str(), options.report);

  std::cout << std::fixed << std::setprecision(1);
  std::cout << "scenevis render: " << scene.description << ", " << cells << " polygons"
            << (translucent ? " (translucent)" : " (opaque)") << "\n";
  std::cout << "  translucency: " << method << " - " << reason << "\n";
  std::cout << "  culling: " << plan.cull.method << " - " << plan.cull.reason << "\n";
  std::cout << "  back-end: " << scenevis::testing::BackendName(backend) << ", " << options.width
            << "x" << options.height << "\n";
  std::cout << "  load " << scene.loadMs << " ms, window " << windowMs << " ms" << details.str();
  if (culling.SetupMs() > 0.0)
    std::cout << ", PVS " << culling.SetupMs() << " ms";
  std::cout << "\n  first frame after " << firstFrameMs / 1000.0 << " s (load "
            << scene.loadMs / 1000.0 << ", checks " << scene.checkMs / 1000.0 << ", normals "
            << scene.normalsMs / 1000.0 << ", facts " << plan.inspectMs / 1000.0 << ", split "
            << plan.splitMs / 1000.0 << ", actors " << actorsMs / 1000.0 << ", cullers "
            << cullersMs / 1000.0 << ", frame " << firstFrameTotalMs / 1000.0 << " s)\n";
  std::cout << "  memory: peak " << scenevis::tool::FormatBytes(memory.peak) << " = "
            << std::setprecision(2) << static_cast<double>(memory.peak) / polydataBytes
            << "x the scene's polydata ("
            << scenevis::tool::FormatBytes(static_cast<std::uint64_t>(polydataBytes)) << "), "
            << std::setprecision(0)
            << static_cast<double>(memory.peak) /
      static_cast<double>(std::max<vtkIdType>(1, plan.facts.triangles))
            << " bytes per triangle" << std::setprecision(1) << "\n";
  for (const Frame& frame : frames)
  {
    std::cout << "  " << frame.file << ": sort " << std::setprecision(2) << frame.sortMs << " ms"
              << (pipeline.SortsInRender() ? " (inside the render)" : "") << ", cull "
              << frame.cullMs << " ms" << (frame.cullReused ? " (re-used)" : "") << ", render "
              << frame.renderMs << " ms, " << frame.propsDrawn << " props, " << frame.trianglesDrawn
              << " of " << culling.TrianglesTotal() << " triangles"
              << (frame.cameraUnchanged ? ", camera unchanged" : "") << "\n";
  }
  if (!options.report.empty())
  {
    std::cout << "  report: " << options.report << "\n";
  }
  ExitNowIfManyActors(pipeline.Parts());
  return EXIT_SUCCESS;
}

/// The key of a cell: its values of the arrays the scene is split into actors by.
std::vector<long long> CellKey(const std::vector<vtkDataArray*>& arrays, vtkIdType cell)
{
  std::vector<long long> key;
  for (vtkDataArray* array : arrays)
    key.push_back(static_cast<long long>(array->GetTuple1(cell)));
  return key;
}

/// The arrays of @p names (the room and the part array) that @p pd has.
std::vector<vtkDataArray*> KeyArrays(vtkPolyData* pd, const std::vector<std::string>& names)
{
  std::vector<vtkDataArray*> arrays;
  for (const std::string& name : names)
  {
    if (vtkDataArray* array = pd->GetCellData()->GetArray(name.c_str()))
      arrays.push_back(array);
  }
  return arrays;
}

/// cull --exact: the exact visible set (cells with a pixel in a depth-tested ID render of the
/// whole scene) against what the mode drew. False negatives break the promise of a conservative
/// mode; over-draw is what it costs. Translucent surfaces are opaque in the ID render, so what
/// is seen only through glass counts as over-draw, never as a false negative.
void DescribeExact(std::ostream& json, vtkRenderWindow* window, vtkCamera* camera,
  bool fixedClippingRange, vtkPolyData* pd, const std::vector<std::string>& keys,
  const MethodPipeline& pipeline, const CullSetup& culling)
{
  namespace st = scenevis::testing;
  const auto start = std::chrono::steady_clock::now();
  st::IdRenderOptions idOptions;
  // A fixed clipping range clips what the mode draws too: the exact set must be clipped alike.
  idOptions.cameraClippingRange = fixedClippingRange;
  const st::IdImage visibleIds = st::RenderIdBuffer(window, pd, camera, idOptions);
  const std::vector<std::uint32_t> visibleCells = st::VisibleSet(visibleIds);
  const double exactMs = Milliseconds(start);

  // Which cells of the scene were drawn: the chunked mapper's cells, the cells of the actors
  // kept (matched by their room and part key), or all cells of the one actor if it was kept.
  const std::vector<vtkDataArray*> arrays = KeyArrays(pd, keys);
  const vtkIdType cells = pd->GetNumberOfCells();
  std::vector<char> drawn(static_cast<std::size_t>(cells), 0);
  std::set<std::vector<long long>> drawnKeys;
  const bool split = pipeline.Parts() > 1;
  if (vtkChunkedPolyDataMapper* chunked = pipeline.GetChunkedMapper())
  {
    std::vector<vtkIdType> ids;
    chunked->GetDrawnCellIds(ids);
    for (const vtkIdType id : ids)
      drawn[static_cast<std::size_t>(id)] = 1;
  }
  else if (split)
  {
    const std::vector<vtkProp*>* kept = culling.Visible();
    for (vtkProp* prop : kept ? *kept : std::vector<vtkProp*>())
    {
      auto* actor = vtkActor::SafeDownCast(prop);
      auto* input =
        actor ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0)) : nullptr;
      if (input && input->GetNumberOfCells() > 0)
        drawnKeys.insert(CellKey(KeyArrays(input, keys), 0));
    }
    for (vtkIdType c = 0; c < cells; ++c)
      drawn[static_cast<std::size_t>(c)] = drawnKeys.count(CellKey(arrays, c)) ? 1 : 0;
  }
  else if (culling.PropsDrawn() > 0)
  {
    std::fill(drawn.begin(), drawn.end(), 1);
  }
  vtkIdType falseNegativeCells = 0;
  std::set<std::vector<long long>> visibleKeys;
  std::set<std::vector<long long>> missedKeys;
  for (const std::uint32_t id : visibleCells)
  {
    const auto cell = static_cast<vtkIdType>(id);
    const std::vector<long long> key = CellKey(arrays, cell);
    visibleKeys.insert(key);
    if (!drawn[static_cast<std::size_t>(cell)])
    {
      ++falseNegativeCells;
      missedKeys.insert(key);
    }
  }
  // What an approximate mode costs on screen: the pixels whose visible cell it did not draw.
  std::size_t visiblePixels = 0;
  std::size_t lostPixels = 0;
  for (const std::uint32_t id : visibleIds.ids)
  {
    if (id == st::kNoId || id >= drawn.size())
      continue;
    ++visiblePixels;
    lostPixels += drawn[id] ? 0 : 1;
  }
  const auto drawnCells = std::count(drawn.begin(), drawn.end(), 1);
  json << ",\n  \"exact\": {\"visible_pixels\": " << visiblePixels
       << ", \"lost_pixels\": " << lostPixels << ", \"visible_cells\": " << visibleCells.size()
       << ", \"drawn_cells\": " << drawnCells
       << ", \"false_negative_cells\": " << falseNegativeCells << ", \"overdraw_cells\": "
       << drawnCells - static_cast<vtkIdType>(visibleCells.size()) + falseNegativeCells;
  if (split)
  {
    vtkIdType overdrawProps = 0;
    for (const auto& key : drawnKeys)
      overdrawProps += visibleKeys.count(key) ? 0 : 1;
    json << ", \"visible_props\": " << visibleKeys.size()
         << ", \"drawn_props\": " << drawnKeys.size()
         << ", \"false_negative_props\": " << missedKeys.size()
         << ", \"overdraw_props\": " << overdrawProps;
  }
  json << ", \"id_render_ms\": " << exactMs << "}";
}

/// `scenevis cull`: what a mode keeps for one camera (or each camera of --cameras: an array), as
/// JSON on stdout. The visible set is that of a real (offscreen) render, so it is exactly what
/// `render` would draw.
int Cull(const Options& options)
{
  ApplyBackendOption(options);
  LoadedScene scene = LoadSceneWithNormals(options);
  vtkPolyData* pd = scene.polydata;
  std::vector<std::string> exported;
  if (!options.exportScene.empty())
  {
    exported.push_back(options.exportScene + ".vtp");
    WritePolyData(pd, exported.back());
    if (scene.portals)
    {
      exported.push_back(options.exportScene + "-portals.vtp");
      WritePolyData(scene.portals, exported.back());
    }
  }
  const bool perCamera = !options.cameras.empty();
  const std::vector<scenevis::tool::CameraSpec> cameras = CamerasToRun(options);
  vtkSmartPointer<vtkRenderWindow> window =
    scenevis::testing::MakeRenderWindow(options.width, options.height);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  SetUpCamera(cameras[0], renderer, pd, scene.zUp);
  // Visibility does not depend on the drawing order: nothing is sorted.
  const ScenePlan plan = PlanScene(options, scene, "none", renderer);
  MethodPipeline pipeline("none", pd, renderer, false, &plan.groups, plan.cull.chunked);
  SetUpCamera(cameras[0], renderer, pd, scene.zUp); // again: the clipping range from the actors
  const CullSetup culling(
    plan.cull, pipeline, renderer, pd, scene.portals, ProgressBar::OnTerminal());
  const std::vector<std::string> keys = { options.roomArray, options.partArray };
  const char* const partArray = options.partArray.c_str();
  const char* const roomArray = options.roomArray.c_str();

  std::vector<std::string> results;
  for (std::size_t c = 0; c < cameras.size(); ++c)
  {
    const scenevis::tool::CameraSpec& spec = cameras[c];
    if (c > 0)
      SetUpCamera(spec, renderer, pd, scene.zUp);
    window->Render();

    // What was drawn: the visible actors' polygons, or the chunked mapper's drawn cells.
    std::set<long long> parts;
    std::set<long long> rooms;
    vtkIdType propsVisible = culling.PropsDrawn();
    if (vtkChunkedPolyDataMapper* chunked = pipeline.GetChunkedMapper())
    {
      std::vector<vtkIdType> cells;
      chunked->GetDrawnCellIds(cells);
      parts = DistinctValues(pd, partArray, &cells);
      rooms = DistinctValues(pd, roomArray, &cells);
      propsVisible = cells.empty() ? 0 : 1;
    }
    else
    {
      std::set<vtkProp*> visible;
      if (const std::vector<vtkProp*>* kept = culling.Visible())
        visible.insert(kept->begin(), kept->end());
      for (const auto& actor : pipeline.GetActors())
      {
        if (culling.Visible() && !visible.count(actor))
          continue;
        auto* input = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
        if (!input)
          continue;
        const std::set<long long> p = DistinctValues(input, partArray);
        const std::set<long long> r = DistinctValues(input, roomArray);
        parts.insert(p.begin(), p.end());
        rooms.insert(r.begin(), r.end());
      }
    }
    vtkCamera* camera = renderer->GetActiveCamera();
    std::ostringstream json;
    json << std::fixed << std::setprecision(3);
    json << "{\n  \"command\": \"cull\",\n  \"scene\": " << JsonString(scene.description)
         << ",\n  \"camera\": " << JsonCamera(camera, spec.FixedClippingRange())
         << ",\n  \"size\": [" << options.width << ", " << options.height
         << "],\n  \"culling\": {\"method\": " << JsonString(plan.cull.method)
         << ", \"reason\": " << JsonString(plan.cull.reason);
    culling.Describe(json);
    json << "},\n  \"cull_ms\": " << culling.CullMs()
         << ",\n  \"props\": {\"total\": " << pipeline.Parts() << ", \"visible\": " << propsVisible
         << "},\n  \"triangles\": {\"total\": " << plan.facts.triangles
         << ", \"visible\": " << culling.TrianglesDrawn()
         << "},\n  \"parts\": {\"total\": " << plan.facts.parts << ", \"visible\": " << parts.size()
         << ", \"ids\": " << JsonIds(parts) << "}";
    if (plan.facts.rooms > 0)
    {
      // -1 is the outside (facade, roof): listed when its props are drawn, not counted as a room.
      const auto insideRooms =
        std::count_if(rooms.begin(), rooms.end(), [](long long room) { return room >= 0; });
      json << ",\n  \"rooms\": {\"total\": " << plan.facts.rooms << ", \"visible\": " << insideRooms
           << ", \"ids\": " << JsonIds(rooms) << "}";
    }
    if (vtkChunkedPolyDataMapper* chunked = pipeline.GetChunkedMapper())
    {
      json << ",\n  \"chunks\": {\"total\": " << chunked->GetNumberOfChunks()
           << ", \"visible\": " << chunked->GetNumberOfChunksDrawn() << "}";
    }
    if (options.exact)
    {
      DescribeExact(json, window, camera, spec.FixedClippingRange(), pd, keys, pipeline, culling);
    }
    if (!exported.empty())
    {
      json << ",\n  \"exported\": [";
      for (std::size_t i = 0; i < exported.size(); ++i)
        json << (i ? ", " : "") << JsonString(exported[i]);
      json << "]";
    }
    json << "\n}";
    results.push_back(json.str());
  }
  std::string text;
  if (perCamera)
  {
    // One result per camera, in the file's order.
    text = "[\n";
    for (std::size_t i = 0; i < results.size(); ++i)
      text += results[i] + (i + 1 < results.size() ? ",\n" : "\n");
    text += "]\n";
  }
  else
  {
    text = results.front() + "\n";
  }
  std::cout << text;
  if (!options.report.empty())
    WriteReport(text, options.report);
  ExitNowIfManyActors(pipeline.Parts());
  return EXIT_SUCCESS;
}

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
  return values.empty() ? 0.0
                        : std::accumulate(values.begin(), values.end(), 0.0) /
      static_cast<double>(values.size());
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
const char* const kBenchMethods[] = { "none", "oit", "depth-sort", "painter", "bsp", "bsp-mapper",
  "multi-actor", "peel:4", "peel:100" };
const char* const kReferenceMethod = "peel:100";

/// Runs one method on a loaded scene; `reference` holds peel:100's frames (filled when `method`
/// is the reference itself); `parts` are the scene's parts (multi-actor draws one actor each).
BenchRow BenchMethod(const Options& options, const std::string& method, const std::string& label,
  vtkPolyData* pd, const std::vector<vtkSmartPointer<vtkPolyData>>& parts, vtkRenderWindow* window,
  std::vector<vtkSmartPointer<vtkImageData>>& reference)
{
  namespace st = scenevis::testing;
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
      vtkSmartPointer<vtkImageData> image = st::CaptureImage(window);
      if (isReference)
      {
        reference.push_back(image);
      }
      else
      {
        const st::ImageDifference difference =
          st::CompareImages(image, reference.at(static_cast<std::size_t>(f)), kBackgroundRgb);
        if (!difference.comparable)
        {
          throw std::runtime_error("cannot compare with the reference: " + difference.problem);
        }
        errors.push_back(difference.meanAbsError);
        bad.push_back(100.0 * difference.coveredBadFraction);
      }
      if (vtkSmartPointer<vtkPolyData> drawn = pipeline.DrawnOrder())
      {
        const st::IdImage painterIds = st::RenderPainterIds(window, drawn, camera);
        const st::IdImage depthIds = st::RenderVisibleIds(window, drawn, camera);
        const st::OrderComparison order = st::OrderMatchesDepth(painterIds, depthIds);
        // Without the edge mask: on fine meshes (triangles of a few pixels) nearly every pixel
        // is next to another id, so the masked comparison sees little; every pixel counts here,
        // at the price of a few legitimate differences along intersection lines.
        const st::OrderComparison unmasked = st::OrderMatchesDepth(painterIds, depthIds,
          std::vector<std::uint8_t>(depthIds.ids.size(), std::uint8_t(0)));
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
    scenevis::testing::MakeRenderWindow(std::max(1, count) * 520, 900);
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
  vtkSmartPointer<vtkImageData> image = scenevis::testing::CaptureImage(window);
  window->RemoveRenderer(view->GetRenderer());
  if (!scenevis::testing::WritePng(image, path))
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

int Bench(const Options& options)
{
  ApplyBackendOption(options);
  std::vector<std::string> scenes = options.scenes;
  if (scenes.empty())
  {
    scenes = { "spheres", "cyclic-quads" };
    if (!scenevis::testing::DataFile("bunny-stl").empty())
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
            << " frames of " << options.orbit << " deg, " << options.width << "x"
            << options.height << "\n";
  {
    vtkSmartPointer<vtkRenderWindow> window =
      scenevis::testing::MakeRenderWindow(options.width, options.height);
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
          std::cout << "    " << std::setw(11) << std::left << method << std::right
                    << " frame " << std::setw(9) << row.frameMs << " ms, sort " << std::setw(9)
                    << row.sortMs << " ms, error " << std::setw(6) << row.meanAbsError
                    << " levels, " << std::setw(6) << row.badPercent << " % bad";
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

/// `scenevis sort`: the polydata in BSP order for the camera, or for each camera of --cameras
/// (OUT-0.vtp, OUT-1.vtp, ...: the tree is built once, each camera only re-orders it).
int Sort(const Options& options)
{
  const LoadedScene scene = LoadScene(options);
  double bounds[6];
  scene.polydata->GetBounds(bounds);
  const double center[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const bool perCamera = !options.cameras.empty();
  const std::vector<scenevis::tool::CameraSpec> cameras = CamerasToRun(options);
  vtkNew<vtkCamera> camera;
  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputData(scene.polydata);
  sorter->SetCamera(camera);
  if (options.frontToBack)
  {
    sorter->SetDirectionToFrontToBack();
  }
  vtkNew<ProgressBar> progress;
  progress->Label = "building BSP tree";
  if (isatty(STDERR_FILENO))
  {
    sorter->AddObserver(vtkCommand::ProgressEvent, progress);
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(sorter->GetOutputPort());
  writer->SetDataModeToBinary();
  for (std::size_t c = 0; c < cameras.size(); ++c)
  {
    // The order depends on the eye (perspective) or the view direction (parallel) only; the rest
    // is set so that the output is what a renderer with this camera would see in this order.
    const scenevis::tool::CameraSpec& spec = cameras[c];
    camera->SetParallelProjection(spec.parallel);
    if (spec.hasEye)
    {
      camera->SetPosition(spec.eye);
      camera->SetFocalPoint(spec.hasFocal ? spec.focal : center);
    }
    else
    {
      const double size =
        std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-12 });
      camera->SetFocalPoint(center);
      camera->SetPosition(center[0] + size, center[1] + size, center[2] + 2 * size);
    }
    if (spec.hasUp)
    {
      camera->SetViewUp(spec.up);
      camera->OrthogonalizeViewUp();
    }
    if (spec.viewAngle > 0.0)
      camera->SetViewAngle(spec.viewAngle);
    if (spec.parallelScale > 0.0)
      camera->SetParallelScale(spec.parallelScale);
    if (spec.FixedClippingRange())
      camera->SetClippingRange(spec.clippingRange);
    sorter->Update();
    const std::string out = perCamera ? CameraFileName(options.out, c, ".vtp") : options.out;
    writer->SetFileName(out.c_str());
    if (writer->Write() != 1)
    {
      throw std::runtime_error("cannot write '" + out + "'");
    }
    std::cout << std::fixed << std::setprecision(2) << "scenevis sort: " << scene.description
              << ", " << scene.polydata->GetNumberOfCells() << " polygons -> "
              << sorter->GetNumberOfFragments() << " fragments (" << sorter->GetNumberOfSplits()
              << " splits), build " << sorter->GetLastBuildTime() * 1e3 << " ms, order "
              << sorter->GetLastOrderTime() * 1e3 << " ms, eye "
              << JsonVector(camera->GetPosition()) << " -> " << out << "\n";
  }
  return EXIT_SUCCESS;
}

/// A message as the one line the exit-code contract promises: VTK's "ERROR: In FILE, line N"
/// headers dropped, line breaks folded.
std::string OneLine(const std::string& message)
{
  static const std::regex header(R"((ERROR|Warning): In [^\n]*, line [0-9]+\n)");
  std::string line = std::regex_replace(message, header, "");
  std::replace(line.begin(), line.end(), '\n', ' ');
  line = std::regex_replace(line, std::regex(" +"), " ");
  while (!line.empty() && line.back() == ' ')
    line.pop_back();
  return line;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h"))
  {
    std::cout << HelpText();
    return EXIT_SUCCESS;
  }
  if (argc >= 2 && std::string(argv[1]) == "--version")
  {
    std::cout << "scenevis " << SCENEVIS_VERSION << "\n";
    return EXIT_SUCCESS;
  }
  try
  {
    const Options options = ParseOptions(argc, argv);
    if (options.command == "bench")
    {
      return Bench(options);
    }
    if (options.command == "cull")
    {
      return Cull(options);
    }
    return options.command == "render" ? Render(options) : Sort(options);
  }
  catch (const UsageError& e)
  {
    std::cerr << "scenevis: " << OneLine(e.what()) << "\n";
    return kExitUsage;
  }
  catch (const std::exception& e)
  {
    std::cerr << "scenevis: " << OneLine(e.what()) << "\n";
    return kExitFailure;
  }
}

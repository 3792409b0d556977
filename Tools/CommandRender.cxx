// `scenevis render`: draws the scene offscreen, writes the frames and the report.
#include "AutoPlan.h"
#include "Commands.h"
#include "CullSetup.h"
#include "HugePages.h"
#include "MallocRetention.h"
#include "Memory.h"
#include "MethodPipeline.h"
#include "Progress.h"
#include "Report.h"
#include "SceneLoading.h"
#include "ViewSetup.h"

#include <vtkSceneVisHeadlessWindows.h>
#include <vtkSceneVisImageCompare.h>

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenevis
{
namespace tool
{

int RunRender(const Options& options)
{
  ApplyBackendOption(options);
  LoadedScene scene = LoadSceneWithNormals(options);
  vtkPolyData* pd = scene.polydata;
  // The polydata as loaded, with the cell storage the reader gave it (the figure peak memory is
  // compared with: BENCHMARKS.md, "48.6M triangles from file to frames").
  const double polydataBytes = 1024.0 * static_cast<double>(pd->GetActualMemorySize()) +
    static_cast<double>(scene.compactedBytes);

  const auto windowStart = std::chrono::steady_clock::now();
  const scenevis::headless::Backend backend = scenevis::headless::DefaultBackend();
  vtkSmartPointer<vtkRenderWindow> window =
    scenevis::headless::MakeRenderWindow(backend, options.width, options.height);
  const double windowMs = Milliseconds(windowStart);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  window->AddRenderer(renderer);
  // With --cameras, every camera is one frame; else the command line's camera, orbited.
  const bool perCamera = !options.cameras.empty();
  const std::vector<CameraSpec> cameras = CamerasToRun(options);
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
  MethodPipeline pipeline(method, pd, renderer, onTerminal, &plan.groups, plan.cull.chunked,
    plan.instanced, plan.instancedProps);
  const double actorsMs = Milliseconds(actorsStart);
  if (pipeline.InstancedProps())
  {
    // The placements live in the instanced actors now (6 MB for 46,000 of them).
    std::vector<Instance>().swap(scene.instanced->instances);
  }
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
  const CullSetup culling(plan.cull, pipeline, renderer, pd, plan.portals, onTerminal);
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
    const CameraSpec& spec = cameras[perCamera ? static_cast<std::size_t>(f) : 0];
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
    vtkSmartPointer<vtkImageData> image = scenevis::headless::CaptureImage(window);
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
    if (!scenevis::headless::WritePng(image, frame.file))
    {
      throw std::runtime_error("cannot write '" + frame.file + "'");
    }
    if (scenevis::headless::CoveredFraction(image, kBackgroundRgb) <= 0.0)
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
  const ResidentMemory memory = ReadResidentMemory();
  const double accountedMs = scene.loadMs + scene.checkMs + scene.normalsMs + windowMs + boundsMs +
    plan.inspectMs + plan.generateMs + plan.splitMs + actorsMs + cullersMs + firstFrameTotalMs;
  std::ostringstream json;
  std::ostringstream details;
  json << std::fixed << std::setprecision(3);
  details << std::fixed << std::setprecision(1);
  json << "{\n  \"command\": \"render\",\n  \"scene\": " << JsonString(scene.description)
       << ",\n  \"polygons\": " << cells << ",\n  \"triangles\": " << plan.facts.triangles
       << ",\n  \"parts\": " << plan.facts.parts
       << ",\n  \"translucent_fraction\": " << std::setprecision(4)
       << plan.facts.translucentFraction << std::setprecision(3)
       << ",\n  \"translucent_parts\": " << plan.facts.translucentParts
       << ",\n  \"translucent_overlap\": " << plan.facts.translucentOverlap
       << ",\n  \"rooms\": " << plan.facts.rooms << ",\n  \"portals\": " << plan.facts.portals
       << ",\n  \"translucent\": " << (translucent ? "true" : "false")
       << ",\n  \"translucency\": {\"method\": " << JsonString(method)
       << ", \"reason\": " << JsonString(reason)
       << "},\n  \"culling\": {\"method\": " << JsonString(plan.cull.method)
       << ", \"reason\": " << JsonString(plan.cull.reason);
  culling.Describe(json);
  json << "},\n  \"backend\": " << JsonString(scenevis::headless::BackendName(backend))
       << ",\n  \"size\": [" << options.width << ", " << options.height
       << "],\n  \"load_ms\": " << scene.loadMs << ",\n  \"check_ms\": " << scene.checkMs
       << ",\n  \"normals_ms\": " << scene.normalsMs << ",\n  \"window_ms\": " << windowMs
       << ",\n  \"bounds_ms\": " << boundsMs << ",\n  \"inspect_ms\": " << plan.inspectMs
       << ",\n  \"rooms_ms\": " << plan.generateMs << ",\n  \"split_ms\": " << plan.splitMs
       << ",\n  \"actors_ms\": " << actorsMs << ",\n  \"cullers_ms\": " << cullersMs
       << ",\n  \"build_ms\": " << buildMs << ",\n  \"cull_setup_ms\": " << culling.SetupMs()
       << ",\n  \"first_frame_ms\": " << firstFrameMs
       << ",\n  \"unaccounted_ms\": " << std::max(0.0, firstFrameMs - accountedMs)
       << ",\n  \"memory\": {\"peak_rss\": " << memory.peak
       << ", \"rss_after_load\": " << scene.rssAfterLoad << ", \"rss_end\": " << memory.current
       << ", \"polydata_bytes\": " << polydataBytes
       << ", \"cells_compacted_bytes\": " << scene.compactedBytes
       << ", \"huge_page_malloc\": " << (HugePageMalloc() ? "true" : "false")
       << ", \"keeps_freed_memory\": " << (KeepsFreedMemory() ? "true" : "false")
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
  std::cout << "  back-end: " << scenevis::headless::BackendName(backend) << ", " << options.width
            << "x" << options.height << "\n";
  std::cout << "  load " << scene.loadMs << " ms, window " << windowMs << " ms" << details.str();
  if (culling.SetupMs() > 0.0)
    std::cout << ", PVS " << culling.SetupMs() << " ms";
  std::cout << "\n  first frame after " << firstFrameMs / 1000.0 << " s (load "
            << scene.loadMs / 1000.0 << ", checks " << scene.checkMs / 1000.0 << ", normals "
            << scene.normalsMs / 1000.0 << ", facts " << plan.inspectMs / 1000.0 << ", rooms "
            << plan.generateMs / 1000.0 << ", split "
            << plan.splitMs / 1000.0 << ", actors " << actorsMs / 1000.0 << ", cullers "
            << cullersMs / 1000.0 << ", frame " << firstFrameTotalMs / 1000.0 << " s)\n";
  std::cout << "  memory: peak " << FormatBytes(memory.peak) << " = " << std::setprecision(2)
            << static_cast<double>(memory.peak) / polydataBytes << "x the scene's polydata ("
            << FormatBytes(static_cast<std::uint64_t>(polydataBytes)) << "), "
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

} // namespace tool
} // namespace scenevis

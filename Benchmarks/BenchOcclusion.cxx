// scenevis_occlusion_bench: occlusion culling on a real CAD assembly at scale, side by side with
// frustum culling alone, in one run.
//
// Scene (EngineGrid.h): the 2CylinderEngine glTF (Debian's assimp-testmodels: 115 parts, 121,496
// triangles, real degenerate triangles) split into its parts, then instanced on an N x N grid
// (default 20 x 20 = 400 engines, 46,000 actors, 48.6M triangles): the actors of a part share its
// mapper, each engine is placed by the actors' positions. Opaque (each part gets its glTF colour
// at opacity 1).
//
// Per camera (an engine-row view looking down a row, as a CAD user inspecting one line of a
// plant; a view from inside the grid; an overview from above):
//  - the visible set: an ID render of every actor (flat colour = actor index, depth-tested);
//  - vtkOctreeCuller (frustum only) and vtkOcclusionCuller: props drawn, over-draw (drawn /
//    visible), false negatives (visible props not drawn: must be 0), cull time, time spent
//    rasterizing occluders, and whole frame time (cull + llvmpipe draw, wall clock);
//  - the memory of the occlusion buffer and of its occluder cache;
//  - OpenGL occlusion queries for comparison (OcclusionQueries.h): the visible set drawn first as
//    the occluders (the best case of CHC++-style reuse: last frame's visible set exactly), then one
//    query per remaining prop the frustum keeps, on its bounding box; drawn = the occluders + the
//    props whose query passed; "cull ms" = issuing and reading the queries, "frame ms" = the
//    occluders' frame + the queries + drawing what passed.
// Usage: scenevis_occlusion_bench [--grid N] [--size WxH] [--frames K]
//        [--pixels-per-triangle P] [--smoke] [--write-flat FILE.vtp] [--occlusion-only]
//        [--view NAME] [--cull-only K] [--record PREFIX]
// --write-flat writes the grid as ONE polydata (raw appended data, the model's point normals, a
// PartId cell array naming the 46,000 placed parts, as flattening exporters write it) and exits:
// the input of `scenevis render --scene`.
// (--smoke: 2 x 2 engines at 160x120, one frame: a seconds-long check that it runs, for CI).
// --occlusion-only measures the occlusion culler alone (no frustum-only or GL-query rows, which
// draw most of the grid): minutes less per run when tuning the culler, or profiling it with
// many --frames; --view measures only the view whose name starts with NAME ("engine", "inside",
// "overview"); --cull-only K also calls the culler K times in a row at each camera without
// drawing (warm caches) and prints its wall and thread CPU time per cull: the culler's cost alone,
// for tuning and profiling it on a loaded machine. --record PREFIX writes every cull of the
// occlusion culler at a view to PREFIX-VIEW.rec (PREFIX-engine-row.rec, ...; see
// vtkOcclusionCuller::SetOcclusionRecordFile):
// the input of scenevis_occlusion_replay, which times the rasterizer alone (BENCHMARKS.md).
// Needs the data cache (scripts/fetch-data.sh); prints "SKIPPED" and exits 77 (CTest's
// SKIP_RETURN_CODE) without it.
#include "EngineGrid.h"
#include "OcclusionQueries.h"
#include "vtkOcclusionCuller.h"
#include "vtkOctreeCuller.h"

#include "RenderFrame.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <array>
#include <iostream>
#include <set>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

using scenevis::bench::EngineGrid;
using scenevis::bench::EnginePart;

/// The actors seen at some pixel (every actor drawn, depth-tested, flat ID colours).
std::set<std::size_t> VisibleActors(EngineGrid& g, vtkRenderWindow* window)
{
  for (std::size_t a = 0; a < g.actors.size(); ++a)
  {
    g.actors[a]->SetProperty(g.idLooks[a]);
  }
  g.renderer->GetCullers()->RemoveAllItems();
  vtkSmartPointer<vtkImageData> image = st::CaptureImage(window);
  for (std::size_t a = 0; a < g.actors.size(); ++a)
  {
    g.actors[a]->SetProperty(g.looks[a]);
  }
  std::set<std::size_t> seen;
  const auto* px = static_cast<const unsigned char*>(image->GetScalarPointer());
  const int comps = image->GetNumberOfScalarComponents();
  const vtkIdType n = image->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const std::size_t id = (std::size_t(px[i * comps]) << 16) | (std::size_t(px[i * comps + 1]) << 8) |
      px[i * comps + 2];
    if (id > 0 && id <= g.actors.size())
    {
      seen.insert(id - 1);
    }
  }
  return seen;
}

struct Row
{
  std::string culler;
  std::size_t drawn = 0, missing = 0;
  double cullMs = 0, rasterMs = 0, frameMs = 0;
  vtkIdType culledByOcclusion = 0, occluders = 0, occluderTriangles = 0, trianglesDrawn = 0;
  vtkIdType bufferBytes = 0, cacheBytes = 0;
  bool queriesOk = true;     ///< gl-queries: the queries ran without a GL error
  std::size_t queries = 0;   ///< gl-queries: boxes queried
};

/// This thread's CPU time in seconds (the cull's own cost, whatever the load of other processes).
double ThreadSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// --cull-only: @p repeats direct Cull() calls at the current camera, no drawing between them
/// (warm caches: the culler's cost alone, for profiling and tuning it).
void MeasureCullOnly(EngineGrid& g, vtkOctreeCuller* culler, const char* view, int repeats)
{
  double wall = 0, cpu = 0;
  int kept = 0;
  for (int r = 0; r < repeats; ++r)
  {
    std::vector<vtkProp*> props(g.actors.begin(), g.actors.end());
    int length = static_cast<int>(props.size()), initialized = 0;
    const auto start = Clock::now();
    const double cpuStart = ThreadSeconds();
    culler->Cull(g.renderer, props.data(), length, initialized);
    cpu += ThreadSeconds() - cpuStart;
    wall += Seconds(start);
    kept = length;
  }
  std::printf("%-12s cull only: %d culls, %.3f ms wall, %.3f ms thread CPU per cull, %d props "
              "kept\n",
    view, repeats, 1e3 * wall / repeats, 1e3 * cpu / repeats, kept);
}

Row Measure(EngineGrid& g, vtkRenderWindow* window, vtkOctreeCuller* culler, const char* name,
  const std::set<std::size_t>& visible, int frames, int cullOnly, const char* view)
{
  Row row;
  row.culler = name;
  g.renderer->GetCullers()->RemoveAllItems();
  g.renderer->AddCuller(culler);
  scenevis::bench::RenderFrame(
    window); // warm-up: hierarchy, buffers, caches, last frame's visible set
  // The drawn set of this camera, by a direct Cull() on the renderer's props.
  std::vector<vtkProp*> props(g.actors.begin(), g.actors.end());
  int length = static_cast<int>(props.size()), initialized = 0;
  culler->Cull(g.renderer, props.data(), length, initialized);
  std::set<vtkProp*> drawn(props.begin(), props.begin() + length);
  row.drawn = drawn.size();
  if (cullOnly > 0)
  {
    MeasureCullOnly(g, culler, view, cullOnly);
  }
  for (const std::size_t a : visible)
  {
    row.missing += drawn.count(g.actors[a]) ? 0 : 1;
  }
  double cull = 0, raster = 0;
  const auto start = Clock::now();
  for (int f = 0; f < frames; ++f)
  {
    scenevis::bench::RenderFrame(window);
    if (auto* occlusion = vtkOcclusionCuller::SafeDownCast(culler))
    {
      cull += occlusion->GetCullTime();
      raster += occlusion->GetOccluderRasterTime();
    }
  }
  row.frameMs = 1e3 * Seconds(start) / frames;
  if (auto* occlusion = vtkOcclusionCuller::SafeDownCast(culler))
  {
    row.cullMs = cull / frames;
    row.rasterMs = raster / frames;
    row.culledByOcclusion = occlusion->GetNumberOfPropsCulledByOcclusion();
    row.occluders = occlusion->GetNumberOfOccludersDrawn();
    row.occluderTriangles = occlusion->GetNumberOfOccluderTriangles();
    row.bufferBytes = occlusion->GetDepthBufferBytes();
    row.cacheBytes = occlusion->GetOccluderCacheBytes();
  }
  else
  {
    // Cull time of the frustum culler alone, without drawing.
    const auto t = Clock::now();
    for (int f = 0; f < 5; ++f)
    {
      std::vector<vtkProp*> again(g.actors.begin(), g.actors.end());
      int len = static_cast<int>(again.size()), init = 0;
      culler->Cull(g.renderer, again.data(), len, init);
    }
    row.cullMs = 1e3 * Seconds(t) / 5;
  }
  row.trianglesDrawn = culler->GetNumberOfTrianglesDrawn();
  g.renderer->GetCullers()->RemoveAllItems();
  return row;
}
/// The GL-queries row (see the file comment).
Row MeasureQueries(EngineGrid& g, vtkRenderWindow* window, const std::set<std::size_t>& visible)
{
  Row row;
  row.culler = "gl-queries";
  // The frustum's props (octree), without the visible set: the boxes to query.
  vtkNew<vtkOctreeCuller> frustum;
  std::vector<vtkProp*> props(g.actors.begin(), g.actors.end());
  int length = static_cast<int>(props.size()), initialized = 0;
  frustum->Cull(g.renderer, props.data(), length, initialized);
  std::vector<std::size_t> candidates;
  std::vector<std::array<double, 6>> boxes;
  std::map<vtkProp*, std::size_t> index;
  for (std::size_t a = 0; a < g.actors.size(); ++a)
  {
    index[g.actors[a]] = a;
  }
  for (int i = 0; i < length; ++i)
  {
    const std::size_t a = index[props[i]];
    if (!visible.count(a))
    {
      candidates.push_back(a);
      std::array<double, 6> b;
      g.actors[a]->GetBounds(b.data());
      boxes.push_back(b);
    }
  }
  for (std::size_t a = 0; a < g.actors.size(); ++a)
  {
    g.actors[a]->SetVisibility(visible.count(a) ? 1 : 0);
  }
  g.renderer->GetCullers()->RemoveAllItems();
  scenevis::bench::RenderFrame(window); // warm-up
  auto start = Clock::now();
  scenevis::bench::RenderFrame(window);
  const double occludersMs = 1e3 * Seconds(start);
  scenevis::bench::QueryResult queries;
  vtkNew<vtkCallbackCommand> onEnd;
  struct Context
  {
    vtkRenderer* renderer;
    const std::vector<std::array<double, 6>>* boxes;
    scenevis::bench::QueryResult* result;
  } context{ g.renderer, &boxes, &queries };
  onEnd->SetClientData(&context);
  onEnd->SetCallback([](vtkObject*, unsigned long, void* data, void*) {
    auto* c = static_cast<Context*>(data);
    *c->result = scenevis::bench::QueryBoxes(c->renderer, *c->boxes);
  });
  const unsigned long tag = g.renderer->AddObserver(vtkCommand::EndEvent, onEnd);
  window->Render();
  g.renderer->RemoveObserver(tag);
  // Then the props whose query passed are drawn too.
  std::size_t passed = 0;
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    if (i < queries.visible.size() && queries.visible[i])
    {
      g.actors[candidates[i]]->SetVisibility(1);
      ++passed;
    }
  }
  start = Clock::now();
  scenevis::bench::RenderFrame(window);
  const double drawMs = 1e3 * Seconds(start);
  for (const auto& actor : g.actors)
  {
    actor->SetVisibility(1);
  }
  row.drawn = visible.size() + passed;
  row.queriesOk = queries.ok;
  row.cullMs = queries.issueMs + queries.waitMs;
  row.frameMs = occludersMs + row.cullMs + (passed > 0 ? drawMs - occludersMs : 0.0);
  row.occluders = static_cast<vtkIdType>(visible.size());
  row.queries = candidates.size();
  return row;
}
/// The grid as one polydata (FlattenEngineGrid()), written uncompressed to @p path.
bool WriteFlat(const std::vector<EnginePart>& parts, int n, const char* path)
{
  vtkSmartPointer<vtkPolyData> flat = scenevis::bench::FlattenEngineGrid(parts, n);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(flat);
  writer->SetFileName(path);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToNone();
  writer->EncodeAppendedDataOff(); // raw bytes, as big-model exporters write them (not base64)
  std::printf("writing %lld triangles of %lld parts to %s\n",
    static_cast<long long>(flat->GetNumberOfCells()), static_cast<long long>(parts.size()) * n * n,
    path);
  return writer->Write() == 1;
}
} // namespace

int main(int argc, char* argv[])
{
  int n = 20, width = 800, height = 600, frames = 3;
  double pixelsPerTriangle = -1.0; // the culler's default
  const char* flatFile = nullptr;
  bool occlusionOnly = false;
  int cullOnly = 0;
  std::string onlyView, recordPrefix;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--grid" && i + 1 < argc)
      n = std::max(1, std::atoi(argv[++i]));
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2)
      ;
    else if (a == "--write-flat" && i + 1 < argc)
      flatFile = argv[++i];
    else if (a == "--pixels-per-triangle" && i + 1 < argc)
      pixelsPerTriangle = std::atof(argv[++i]);
    else if (a == "--frames" && i + 1 < argc)
      frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--view" && i + 1 < argc)
      onlyView = argv[++i];
    else if (a == "--cull-only" && i + 1 < argc)
      cullOnly = std::max(0, std::atoi(argv[++i]));
    else if (a == "--record" && i + 1 < argc)
      recordPrefix = argv[++i];
    else if (a == "--occlusion-only")
      occlusionOnly = true;
    else if (a == "--smoke")
    {
      n = 2;
      width = 160;
      height = 120;
      frames = 1;
    }
    else
    {
      std::cerr << "usage: scenevis_occlusion_bench [--grid N] [--size WxH] [--frames K] "
                   "[--pixels-per-triangle P] [--smoke] [--occlusion-only] [--view NAME] "
                   "[--cull-only K] [--record PREFIX]\n";
      return 2;
    }
  }
  scenevis::bench::EngineModel engine;
  if (const int status = scenevis::bench::LoadEngine(engine))
  {
    return status;
  }
  const std::vector<EnginePart>& parts = engine.parts;
  if (flatFile)
  {
    return WriteFlat(parts, n, flatFile) ? 0 : 1;
  }
  auto t0 = Clock::now();
  EngineGrid g;
  scenevis::bench::BuildEngineGrid(g, parts, n);
  const double gridS = Seconds(t0);
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(width, height);
  window->AddRenderer(g.renderer);
  std::printf("scene: 2CylinderEngine (%zu parts), %d x %d engines = %zu actors, %lld triangles; "
              "read %.2f s, split %.2f s, grid %.2f s; %dx%d, %d frames per row\n",
    parts.size(), n, n, g.actors.size(), static_cast<long long>(g.triangles), engine.readSeconds,
    engine.splitSeconds, gridS, width, height, frames);

  struct View
  {
    const char* name;
    double eye[3], focal[3], angle;
  };
  const double* b = g.bounds;
  const double cy = 0.5 * (b[2] + b[3]);
  const double row = b[4] + 0.5 * g.pitch[2] * (n > 1 ? 1 : 0.5); // centre line of the first row
  const double spanX = b[1] - b[0], spanZ = b[5] - b[4];
  const View views[] = {
    { "engine row", { b[0] - 0.3 * g.pitch[0], cy, row }, { b[1], cy, row }, 60.0 },
    { "inside grid", { b[0] + 0.45 * spanX, cy, b[4] + 0.42 * spanZ },
      { b[1], cy, b[5] }, 60.0 },
    { "overview", { b[0] - 0.3 * spanX, b[3] + 0.8 * spanX, b[4] - 0.3 * spanZ },
      { 0.5 * (b[0] + b[1]), cy, 0.5 * (b[4] + b[5]) }, 40.0 },
  };
  std::printf("%-12s %-10s %8s %8s %9s %6s %9s %9s %10s %9s %10s %12s\n", "view", "culler",
    "visible", "drawn", "over-draw", "missed", "cull ms", "raster ms", "frame ms", "occluders",
    "occl. tris", "tris drawn");
  for (const View& v : views)
  {
    if (std::string(v.name).compare(0, onlyView.size(), onlyView) != 0)
    {
      continue;
    }
    vtkCamera* cam = g.renderer->GetActiveCamera();
    cam->SetPosition(v.eye);
    cam->SetFocalPoint(v.focal);
    cam->SetViewUp(0, 1, 0);
    cam->SetViewAngle(v.angle);
    g.renderer->ResetCameraClippingRange();
    const std::set<std::size_t> visible = VisibleActors(g, window);
    vtkNew<vtkOctreeCuller> frustum;
    vtkNew<vtkOcclusionCuller> occlusion;
    if (pixelsPerTriangle >= 0.0)
    {
      occlusion->SetOccluderMinimumPixelsPerTriangle(pixelsPerTriangle);
    }
    if (!recordPrefix.empty())
    {
      std::string file = recordPrefix + "-" + v.name + ".rec";
      std::replace(file.begin() + recordPrefix.size(), file.end(), ' ', '-');
      occlusion->SetOcclusionRecordFile(file.c_str());
    }
    std::vector<Row> rows;
    if (!occlusionOnly)
    {
      rows.push_back(Measure(g, window, frustum, "frustum", visible, frames, cullOnly, v.name));
    }
    rows.push_back(Measure(g, window, occlusion, "occlusion", visible, frames, cullOnly, v.name));
    if (!occlusionOnly)
    {
      const Row glRow = MeasureQueries(g, window, visible);
      std::printf("%-12s %-10s %8zu %8zu %9.2f %6s %9.3f %9s %10.1f %9lld %10s %12s  (%zu box "
                  "queries%s)\n",
        v.name, glRow.culler.c_str(), visible.size(), glRow.drawn,
        double(glRow.drawn) / std::max<std::size_t>(1, visible.size()), "0", glRow.cullMs, "-",
        glRow.frameMs, static_cast<long long>(glRow.occluders), "-", "-", glRow.queries,
        glRow.queriesOk ? "" : ", GL ERROR");
    }
    for (const Row& r : rows)
    {
      std::printf("%-12s %-10s %8zu %8zu %9.2f %6zu %9.3f %9.3f %10.1f %9lld %10lld %12lld\n",
        v.name, r.culler.c_str(), visible.size(), r.drawn,
        double(r.drawn) / std::max<std::size_t>(1, visible.size()), r.missing, r.cullMs,
        r.rasterMs, r.frameMs, static_cast<long long>(r.occluders),
        static_cast<long long>(r.occluderTriangles), static_cast<long long>(r.trianglesDrawn));
    }
    const Row& occluded = rows.back();
    char speedUp[32] = "-";
    if (!occlusionOnly)
    {
      std::snprintf(speedUp, sizeof(speedUp), "%.1fx",
        rows[0].frameMs / std::max(1e-9, occluded.frameMs));
    }
    std::printf("%-12s frame speed-up %s; occlusion buffer %lld bytes, occluder cache %lld "
                "bytes\n",
      v.name, speedUp,
      static_cast<long long>(occluded.bufferBytes), static_cast<long long>(occluded.cacheBytes));
    std::fflush(stdout);
  }
  return 0;
}

// scenevis_soak_bench: a soak run of every culling mode on a real CAD scene of 10M+ triangles:
// does memory stay flat and do frames stay as fast over thousands of frames of a moving camera?
//
// Scene (EngineGrid.h): the 2CylinderEngine glTF instanced on an N x N grid (default 10 x 10 =
// 100 engines, 11,500 actors, 12.1M triangles), opaque.
//
// Camera path: seeded and the same for every mode. Segments of 50 +- 15 frames; in each the eye
// orbits its focal point at a fixed height (0.3 to 1 degree per frame) while zooming in and out
// (the distance swings by up to a factor e^0.5 either way); each new segment is a random jump to
// one of four kinds of view, the eye at the engines' height as a person walking through a plant:
// from outside the grid (up to 30 % of an engine's height above it), the eye inside the grid
// (often inside an engine), the eye in the gaps between engines, and the eye at the end of a row
// looking down it.
// Every jump breaks the cullers' temporal coherence (last frame's visible set, plane masks) and
// brings other meshes into the occluder cache.
//
// Modes (each a separate soak, one after the other in this process, each with its own window):
//  - none:      VTK's default culler (vtkFrustumCoverageCuller) over the 11,500 actors;
//  - frustum:   vtkOctreeCuller (BVH frustum culling) over the actors;
//  - occlusion: vtkOcclusionCuller (frustum + software occlusion culling) over the actors;
//  - chunked:   the grid flattened into ONE polydata drawn by vtkChunkedPolyDataMapper with
//               OcclusionCullingOn() (frustum + occlusion culling of its spatial chunks).
//
// Measured per mode: frame time (wall clock of vtkRenderWindow::Render() and glFinish: cull +
// llvmpipe draw, the rasterizer's work included)
// median / p95 / max per window of 250 frames; resident memory (/proc/self/statm) and the heap's
// live bytes (glibc mallinfo2: what is allocated and not freed, against what malloc keeps) after
// frame 100, at the end of every window and at the end, and the process's peak (VmHWM of
// /proc/self/status, so far in the run). With --passes P (P >= 2) the path is rendered P times
// and the warm-up is the whole first pass: every camera once, so caches and buffers sized by the
// largest frame of the path (llvmpipe's, VTK's, the cullers') have reached that size; growth over
// the later passes, on the same cameras, is memory never given back. Verdicts per mode:
//  - "RSS growth < 1% after warm-up" (from frame 100, or from the end of the first pass): PASS /
//    FAIL;
//  - frame times stable: frames 100-149 are rendered again at the end with the same cameras; their
//    median must be within 1.25x of the first time. The windows' medians are printed but are no
//    verdict: each window holds another mix of views (a 10 x 10 grid seen from outside costs
//    10-30x a view from inside it), so they differ by 5x and more on a steady renderer.
//
// Usage: scenevis_soak_bench [--grid N] [--size WxH] [--frames K] [--modes LIST] [--seed S]
//        [--warm-up F] [--window W] [--passes P] [--smoke] [--abandon]
//   --abandon: _exit right after the first mode's last frame (for heaptrack, see Options).
//   --no-finish: no glFinish after each Render() (see Options::finish).
//   --frames K: the path's length; P passes render K x P frames.
//   LIST: comma-separated from none,frustum,occlusion,chunked (default all four).
//   --smoke: 2 x 2 engines at 160x120, 20 frames (warm-up 5, windows of 10): a check that it runs,
//   for CI. Default size 320x240: llvmpipe's frame is bound by geometry here (640x480 costs
//   1.5x). Run the soak of issue 13 as
//   LP_NUM_THREADS=0 scenevis_soak_bench --grid 10 --frames 400 --passes 2 --size 160x120
//   --window 100 --modes occlusion
//   LP_NUM_THREADS=0 has llvmpipe rasterize on the calling thread (the same images): its
//   rasterizer thread keeps scene storage whose size depends on timing, up to 200 MiB more on
//   this grid, which a growth check cannot tell from a leak (BENCHMARKS.md, "Where the growth
//   is").
// Needs the data cache (scripts/fetch-data.sh); prints "SKIPPED" and exits 77 (CTest's
// SKIP_RETURN_CODE) without it.
#include "EngineGrid.h"
#include "vtkChunkedPolyDataMapper.h"
#include "vtkOcclusionCuller.h"
#include "vtkOctreeCuller.h"

#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCuller.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
namespace sb = scenevis::bench;
using Clock = std::chrono::steady_clock;

constexpr double kPi = 3.14159265358979323846;
constexpr double kMiB = 1024.0 * 1024.0;

double Milliseconds(Clock::time_point since)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

/// Resident bytes of this process now (/proc/self/statm).
double ResidentBytes()
{
  std::ifstream statm("/proc/self/statm");
  double size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

/// Peak resident bytes of this process so far (VmHWM of /proc/self/status).
double PeakResidentBytes()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind("VmHWM:", 0) == 0)
    {
      return 1024.0 * std::atof(line.c_str() + 6);
    }
  }
  return 0.0;
}

/// Bytes the process's heap holds for live allocations now (glibc mallinfo2: in-use chunks plus
/// mmapped blocks). Against the resident bytes it tells retained memory (live objects: a leak or a
/// cache) from free memory malloc keeps (fragmentation).
double HeapInUseBytes()
{
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks) + static_cast<double>(info.hblkhd);
}

/// Bytes malloc holds free in its arenas (glibc mallinfo2 fordblks): RSS that no live object uses.
double HeapFreeBytes()
{
  return static_cast<double>(mallinfo2().fordblks);
}

/// The kinds of view a jump goes to.
enum ViewKind
{
  Outside,
  Inside,
  Gaps,
  Row,
  NumberOfViewKinds
};
const char* const kViewKindNames[NumberOfViewKinds] = { "outside", "inside", "gaps", "row" };

/// One camera of the path.
struct Pose
{
  double eye[3], focal[3], viewAngle;
  ViewKind kind;
  int segment; ///< index of the jump that started this segment of the path
};

/// The seeded camera path (see the file comment); the same numbers on every platform (the
/// generator's raw output is mapped to [0, 1) here, not by a standard distribution).
class CameraPath
{
public:
  CameraPath(const double bounds[6], const double pitch[3], int n, std::uint64_t seed)
    : Gen(seed)
    , N(n)
  {
    std::copy(bounds, bounds + 6, this->B);
    std::copy(pitch, pitch + 3, this->Pitch);
  }

  std::vector<Pose> Make(int frames)
  {
    std::vector<Pose> path;
    while (static_cast<int>(path.size()) < frames)
    {
      this->Jump();
      const int length = 35 + static_cast<int>(this->U() * 31.0);
      const double zoomPeriod = 40.0 + 60.0 * this->U(), zoomPhase = 2.0 * kPi * this->U();
      for (int t = 0; t < length && static_cast<int>(path.size()) < frames; ++t)
      {
        const double azimuth = this->Azimuth + this->Orbit * t;
        const double distance =
          this->Distance * std::exp(this->Zoom * std::sin(zoomPhase + 2.0 * kPi * t / zoomPeriod));
        Pose p;
        for (int k = 0; k < 3; ++k)
        {
          p.focal[k] = this->Focal[k];
        }
        p.eye[0] = this->Focal[0] + distance * std::sin(azimuth);
        p.eye[1] = this->EyeY;
        p.eye[2] = this->Focal[2] + distance * std::cos(azimuth);
        p.viewAngle = this->ViewAngle;
        p.kind = this->Kind;
        p.segment = this->Segments;
        path.push_back(p);
      }
    }
    return path;
  }

private:
  double U() { return static_cast<double>(this->Gen() >> 11) * 0x1.0p-53; }
  double Between(double a, double b) { return a + (b - a) * this->U(); }
  double Radians(double degrees) { return degrees * kPi / 180.0; }

  void Jump()
  {
    const double* b = this->B;
    const double midY = 0.5 * (b[2] + b[3]), height = b[3] - b[2];
    const double spanX = b[1] - b[0], spanZ = b[5] - b[4];
    const double diagonal =
      std::sqrt(spanX * spanX + spanZ * spanZ + (b[3] - b[2]) * (b[3] - b[2]));
    const double engineX = this->Pitch[0] / 1.15, engineZ = this->Pitch[2] / 1.15;
    this->Orbit = this->Radians(this->Between(0.3, 1.0)) * (this->U() < 0.5 ? -1.0 : 1.0);
    this->Zoom = this->Between(0.2, 0.5);
    this->Azimuth = this->Radians(this->Between(0.0, 360.0));
    ++this->Segments;
    this->Kind = static_cast<ViewKind>(static_cast<int>(this->U() * NumberOfViewKinds));
    if (this->Kind == Outside) // from outside the grid, a little above it, as around a plant
    {
      this->Focal[0] = 0.5 * (b[0] + b[1]) + this->Between(-0.25, 0.25) * spanX;
      this->Focal[1] = midY;
      this->Focal[2] = 0.5 * (b[4] + b[5]) + this->Between(-0.25, 0.25) * spanZ;
      this->Distance = this->Between(0.8, 1.4) * diagonal;
      this->EyeY = this->Between(b[2] + 0.3 * height, b[3] + 0.3 * height);
      this->ViewAngle = 30.0;
    }
    else if (this->Kind == Inside) // the eye inside the grid, often inside an engine
    {
      this->Focal[0] = this->Between(b[0], b[1]);
      this->Focal[1] = this->Between(b[2], b[3]);
      this->Focal[2] = this->Between(b[4], b[5]);
      this->Distance = this->Between(0.3, 1.0) * this->Pitch[0];
      this->EyeY = this->Between(b[2] + 0.2 * height, b[3] - 0.1 * height);
      this->ViewAngle = 60.0;
    }
    else if (this->Kind ==
      Gaps) // the eye in the gaps between engines, around a corner of four engines
    {
      const int i = static_cast<int>(this->U() * this->N),
                j = static_cast<int>(this->U() * this->N);
      this->Focal[0] = b[0] + i * this->Pitch[0] + 0.5 * (engineX + this->Pitch[0]);
      this->Focal[1] = this->Between(b[2], b[3]);
      this->Focal[2] = b[4] + j * this->Pitch[2] + 0.5 * (engineZ + this->Pitch[2]);
      this->Distance = this->Between(0.03, 0.07) * this->Pitch[0];
      this->EyeY = this->Between(b[2] + 0.2 * height, b[3] - 0.1 * height);
      this->ViewAngle = 60.0;
    }
    else // at the end of a row looking down it: the focal point half-way along the row
    {
      const bool alongX = this->U() < 0.5;
      const int row = static_cast<int>(this->U() * this->N);
      const double lateral = (alongX ? b[4] : b[0]) + row * this->Pitch[alongX ? 2 : 0] +
        0.5 * (alongX ? engineZ : engineX);
      const double span = alongX ? spanX : spanZ;
      const bool fromLow = this->U() < 0.5;
      this->Focal[1] = this->Between(b[2], b[3]);
      this->Focal[alongX ? 0 : 2] = 0.5 * (alongX ? b[0] + b[1] : b[4] + b[5]);
      this->Focal[alongX ? 2 : 0] = lateral;
      // The eye 0.55 spans from the focal point: just outside the grid, zooming in and out of it.
      this->Distance = 0.55 * span;
      this->Zoom = this->Between(0.1, 0.3);
      this->Azimuth = alongX ? (fromLow ? -0.5 * kPi : 0.5 * kPi) : (fromLow ? kPi : 0.0);
      this->Orbit = this->Radians(this->Between(0.02, 0.08)) * (this->U() < 0.5 ? -1.0 : 1.0);
      this->EyeY = this->Between(b[2] + 0.2 * height, b[3] - 0.1 * height);
      this->ViewAngle = 60.0;
    }
  }

  std::mt19937_64 Gen;
  int N;
  double B[6], Pitch[3];
  double Focal[3] = { 0, 0, 0 };
  double Azimuth = 0, EyeY = 0, Distance = 1, Orbit = 0, Zoom = 0, ViewAngle = 30;
  ViewKind Kind = Outside;
  int Segments = -1;
};

struct Options
{
  int grid = 10, width = 320, height = 240, frames = 2000, warmUp = 100, window = 250;
  int replay = 50;
  int passes = 1; ///< times the whole path is rendered; with 2+, the first pass is the warm-up
  std::uint64_t seed = 13;
  std::vector<std::string> modes{ "none", "frustum", "occlusion", "chunked" };
  /// --abandon: leave the process right after the last frame of the first mode, freeing nothing,
  /// so that a heap profiler (heaptrack) reports what is live then, by call stack, as "leaked".
  /// Two runs, --passes 1 and --passes 2, then diffed: what the second pass added.
  bool abandon = false;
  /// Each frame ends with glFinish (WaitForCompletion), inside its time; --no-finish leaves
  /// llvmpipe free to rasterize a frame while the next one is culled and binned.
  bool finish = true;
};

/// Median, p95 and max of @p ms.
struct Spread
{
  double median = 0, p95 = 0, max = 0;
};

Spread SpreadOf(std::vector<double> ms)
{
  Spread s;
  if (ms.empty())
  {
    return s;
  }
  std::sort(ms.begin(), ms.end());
  const auto at = [&ms](double q)
  { return ms[std::min(ms.size() - 1, static_cast<std::size_t>(q * (ms.size() - 1) + 0.5))]; };
  s.median = at(0.5);
  s.p95 = at(0.95);
  s.max = ms.back();
  return s;
}

struct SoakResult
{
  std::string mode;
  std::vector<double> frameMs, replayMs, windowRss, windowHeap;
  double rssWarm = 0, rssEnd = 0, peak = 0, seconds = 0;
  double heapWarm = 0, heapEnd = 0; ///< live heap bytes (HeapInUseBytes) after warm-up, at the end
  /// With 2+ passes: RSS and live heap at the end of the first pass (every camera seen once).
  double rssPass1 = 0, heapPass1 = 0, peakPass1 = 0;
  double meanDrawn = 0; ///< props (actor modes) or triangles (chunked) drawn per frame
  double finishMs = 0;  ///< time spent in WaitForCompletion() after Render() returned, summed
  std::string drawnUnit;
  double rssFrom = 0, growth = 0; ///< the verdict's reference RSS and the growth from it, in %
  bool rssPass = false, framesStable = false;
};

/// Renders @p path in @p renderer (already holding the scene) in a new window; @p drawn reports
/// what the last frame drew, @p caches (optional) the bytes the culler's own caches hold (shown
/// in the progress lines, so that their part of the heap is seen apart).
SoakResult Soak(const std::string& mode, vtkRenderer* renderer, const double bounds[6],
  const std::vector<Pose>& path, const Options& o, const std::function<double()>& drawn,
  const std::function<double()>& caches = nullptr)
{
  SoakResult r;
  r.mode = mode;
  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(o.width, o.height);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  const auto render = [&](const Pose& p)
  {
    camera->SetFocalPoint(p.focal);
    camera->SetPosition(p.eye);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(p.viewAngle);
    renderer->ResetCameraClippingRange(bounds);
    const auto start = Clock::now();
    window->Render();
    if (o.finish)
    {
      // Render() returns while llvmpipe's rasterizer thread may still draw the frame (a frame
      // shown on screen or read back waits for it); glFinish makes the time the whole frame's.
      const auto returned = Clock::now();
      window->WaitForCompletion();
      r.finishMs += Milliseconds(returned);
    }
    return Milliseconds(start);
  };
  const auto start = Clock::now();
  double drawnSum = 0;
  const std::size_t total = path.size() * static_cast<std::size_t>(o.passes);
  for (std::size_t f = 0; f < total; ++f)
  {
    r.frameMs.push_back(render(path[f % path.size()]));
    drawnSum += drawn();
    if (static_cast<int>(f) + 1 == o.warmUp)
    {
      r.rssWarm = ResidentBytes();
      r.heapWarm = HeapInUseBytes();
    }
    if (o.passes > 1 && f + 1 == path.size())
    {
      r.rssPass1 = ResidentBytes();
      r.heapPass1 = HeapInUseBytes();
      r.peakPass1 = PeakResidentBytes();
    }
    if ((f + 1) % static_cast<std::size_t>(o.window) == 0 || f + 1 == total)
    {
      r.windowRss.push_back(ResidentBytes());
      r.windowHeap.push_back(HeapInUseBytes());
      // Progress of a long run, on stderr so that stdout keeps only the figures.
      std::fprintf(stderr,
        "[%s] %zu frames in %.0f s, RSS %.1f MiB, heap in use %.1f MiB, free in malloc's arenas "
        "%.1f MiB",
        mode.c_str(), f + 1, 1e-3 * Milliseconds(start), r.windowRss.back() / kMiB,
        r.windowHeap.back() / kMiB, HeapFreeBytes() / kMiB);
      if (caches)
      {
        std::fprintf(stderr, ", of it the culler's caches %.1f MiB", caches() / kMiB);
      }
      std::fprintf(stderr, "\n");
    }
  }
  r.rssEnd = ResidentBytes();
  r.heapEnd = HeapInUseBytes();
  if (o.abandon)
  {
    std::fprintf(stderr, "[%s] abandoned after %zu frames (--abandon), RSS %.1f MiB\n",
      mode.c_str(), total, r.rssEnd / kMiB);
    std::fflush(nullptr);
    _exit(0);
  }
  r.meanDrawn = drawnSum / std::max<std::size_t>(1, total);
  // The same cameras again: frames warm-up .. warm-up + replay - 1.
  for (int f = o.warmUp; f < o.warmUp + o.replay && f < static_cast<int>(path.size()); ++f)
  {
    r.replayMs.push_back(render(path[static_cast<std::size_t>(f)]));
  }
  r.seconds = 1e-3 * Milliseconds(start);
  r.peak = PeakResidentBytes();
  window->RemoveRenderer(renderer);
  return r;
}

/// Prints the figures and verdicts of @p r; fills its verdicts.
void Report(SoakResult& r, const std::vector<Pose>& path, const Options& o)
{
  std::printf("mode %s: %zu frames (+%zu replayed) in %.1f s; %.1f %s drawn per frame on "
              "average\n",
    r.mode.c_str(), r.frameMs.size(), r.replayMs.size(), r.seconds, r.meanDrawn,
    r.drawnUnit.c_str());
  if (o.finish)
  {
    std::printf("  waiting for llvmpipe after Render() returned (glFinish): %.2f ms per frame on "
                "average\n",
      r.finishMs / std::max<std::size_t>(1, r.frameMs.size() + r.replayMs.size()));
  }
  std::printf("  %-7s %-11s %10s %10s %10s %12s %13s\n", "window", "frames", "median ms", "p95 ms",
    "max ms", "RSS MiB end", "heap MiB end");
  std::vector<double> medians;
  for (std::size_t w = 0; w * static_cast<std::size_t>(o.window) < r.frameMs.size(); ++w)
  {
    const std::size_t from = w * static_cast<std::size_t>(o.window);
    const std::size_t to = std::min(r.frameMs.size(), from + static_cast<std::size_t>(o.window));
    const Spread s =
      SpreadOf(std::vector<double>(r.frameMs.begin() + static_cast<std::ptrdiff_t>(from),
        r.frameMs.begin() + static_cast<std::ptrdiff_t>(to)));
    medians.push_back(s.median);
    const std::string frames = std::to_string(from) + "-" + std::to_string(to - 1);
    std::printf("  %-7zu %-11s %10.1f %10.1f %10.1f %12.1f %13.1f\n", w + 1, frames.c_str(),
      s.median, s.p95, s.max, w < r.windowRss.size() ? r.windowRss[w] / kMiB : 0.0,
      w < r.windowHeap.size() ? r.windowHeap[w] / kMiB : 0.0);
  }
  std::printf("  by view:");
  for (int kind = 0; kind < NumberOfViewKinds; ++kind)
  {
    std::vector<double> ms;
    for (std::size_t f = 0; f < r.frameMs.size(); ++f)
    {
      if (path[f % path.size()].kind == kind)
      {
        ms.push_back(r.frameMs[f]);
      }
    }
    if (!ms.empty())
    {
      std::printf(
        " %s %zu frames median %.1f ms;", kViewKindNames[kind], ms.size(), SpreadOf(ms).median);
    }
  }
  std::printf("\n");
  const auto percent = [](double from, double to) { return 100.0 * (to - from) / std::max(1.0, from); };
  double growth = percent(r.rssWarm, r.rssEnd);
  std::printf("  RSS: after frame %d %.1f MiB, end %.1f MiB, growth %+.2f %%; peak "
              "(VmHWM, process so far) %.1f MiB\n",
    o.warmUp, r.rssWarm / kMiB, r.rssEnd / kMiB, growth, r.peak / kMiB);
  std::printf("  heap in use (live allocations): after warm-up %.1f MiB, end %.1f MiB, growth "
              "%+.2f %%\n",
    r.heapWarm / kMiB, r.heapEnd / kMiB, percent(r.heapWarm, r.heapEnd));
  if (o.passes > 1)
  {
    // The warm-up is the whole first pass: every camera of the path once, so every cache and
    // buffer the path fills has reached the size the path needs. Growth on the next passes over
    // the same cameras is memory that is never given back.
    growth = percent(r.rssPass1, r.rssEnd);
    std::printf("  after the first pass (warm-up: the path's %zu cameras once): RSS %.1f MiB, "
                "heap in use %.1f MiB; after pass %d: RSS %+.2f %%, heap in use %+.2f %%\n",
      path.size(), r.rssPass1 / kMiB, r.heapPass1 / kMiB, o.passes, growth,
      percent(r.heapPass1, r.heapEnd));
    // Memory given back between frames and taken again (llvmpipe's per-frame scene data, malloc's
    // moving mmap threshold) shows as RSS growth on the samples; the high-water mark says whether
    // the later passes needed more than the first at any moment.
    std::printf("  peak RSS (VmHWM) at the end of the first pass %.1f MiB, at the end %.1f MiB "
                "(%+.2f %%)\n",
      r.peakPass1 / kMiB, r.peak / kMiB, percent(r.peakPass1, r.peak));
  }
  const double lowest = *std::min_element(medians.begin(), medians.end());
  const double highest = *std::max_element(medians.begin(), medians.end());
  const std::size_t replayed = r.replayMs.size();
  const Spread first = SpreadOf(std::vector<double>(r.frameMs.begin() + o.warmUp,
    r.frameMs.begin() + o.warmUp + static_cast<std::ptrdiff_t>(replayed)));
  const Spread again = SpreadOf(r.replayMs);
  const double replayRatio = again.median / std::max(1e-9, first.median);
  const double windowRatio = highest / std::max(1e-9, medians.front());
  r.framesStable = replayRatio <= 1.25;
  std::printf("  frame times: window medians %.2fx..%.2fx of the first; frames %d-%zu again at "
              "the end: median %.1f ms vs %.1f ms the first time (%.2fx) -> %s (replay within "
              "1.25x)\n",
    lowest / std::max(1e-9, medians.front()), windowRatio, o.warmUp, o.warmUp + replayed - 1,
    again.median, first.median, replayRatio, r.framesStable ? "stable" : "NOT STABLE");
  r.rssFrom = o.passes > 1 ? r.rssPass1 : r.rssWarm;
  r.growth = growth;
  r.rssPass = growth < 1.0;
  std::printf("  %s %s: RSS growth < 1%% after warm-up (%s: %+.2f %%)\n", r.mode.c_str(),
    r.rssPass ? "PASS" : "FAIL", o.passes > 1 ? "the first pass" : "the first frames", growth);
  std::fflush(stdout);
}

bool ParseOptions(int argc, char* argv[], Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool value = i + 1 < argc;
    if (a == "--grid" && value)
      o.grid = std::max(1, std::atoi(argv[++i]));
    else if (a == "--size" && value && std::sscanf(argv[++i], "%dx%d", &o.width, &o.height) == 2 &&
      o.width > 0 && o.height > 0)
      ;
    else if (a == "--frames" && value)
      o.frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--warm-up" && value)
      o.warmUp = std::max(1, std::atoi(argv[++i]));
    else if (a == "--passes" && value)
      o.passes = std::max(1, std::atoi(argv[++i]));
    else if (a == "--window" && value)
      o.window = std::max(1, std::atoi(argv[++i]));
    else if (a == "--seed" && value)
      o.seed = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--modes" && value)
    {
      o.modes.clear();
      std::stringstream list(argv[++i]);
      for (std::string m; std::getline(list, m, ',');)
      {
        if (m != "none" && m != "frustum" && m != "occlusion" && m != "chunked")
        {
          std::cerr << "unknown mode '" << m << "' (none, frustum, occlusion, chunked)\n";
          return false;
        }
        o.modes.push_back(m);
      }
    }
    else if (a == "--abandon")
      o.abandon = true;
    else if (a == "--no-finish")
      o.finish = false;
    else if (a == "--smoke")
    {
      o.grid = 2;
      o.width = 160;
      o.height = 120;
      o.frames = 20;
      o.warmUp = 5;
      o.window = 10;
      o.replay = 5;
    }
    else
    {
      std::cerr << "usage: scenevis_soak_bench [--grid N] [--size WxH] [--frames K] [--modes "
                   "none,frustum,occlusion,chunked] [--seed S] [--warm-up F] [--window W] "
                   "[--passes P] [--smoke] [--abandon] [--no-finish]\n";
      return false;
    }
  }
  if (o.warmUp >= o.frames)
  {
    std::cerr << "--warm-up must be below --frames\n";
    return false;
  }
  o.replay = std::min(o.replay, o.frames - o.warmUp);
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options o;
  if (!ParseOptions(argc, argv, o))
  {
    return 2;
  }
  sb::EngineModel engine;
  if (const int status = sb::LoadEngine(engine))
  {
    return status;
  }
  double pitch[3], bounds[6];
  sb::EnginePitch(engine.parts, pitch);
  sb::EngineGridBounds(engine.parts, o.grid, bounds);
  const std::vector<Pose> path = CameraPath(bounds, pitch, o.grid, o.seed).Make(o.frames);
  std::printf("camera path (seed %llu), first frame and kind of each segment:",
    static_cast<unsigned long long>(o.seed));
  for (std::size_t f = 0; f < path.size(); ++f)
  {
    if (f == 0 || path[f].segment != path[f - 1].segment)
    {
      std::printf(
        "%s %zu %s", path[f].segment % 10 == 0 ? "\n " : "", f, kViewKindNames[path[f].kind]);
    }
  }
  std::printf("\n");
  std::unique_ptr<sb::EngineGrid> grid;
  std::size_t actorModesLeft = static_cast<std::size_t>(std::count_if(
    o.modes.begin(), o.modes.end(), [](const std::string& m) { return m != "chunked"; }));
  std::vector<SoakResult> results;
  for (const std::string& mode : o.modes)
  {
    auto t0 = Clock::now();
    SoakResult r;
    if (mode == "chunked")
    {
      vtkSmartPointer<vtkPolyData> flat = sb::FlattenEngineGrid(engine.parts, o.grid);
      vtkNew<vtkChunkedPolyDataMapper> mapper;
      mapper->SetInputData(flat);
      mapper->ScalarVisibilityOff();
      mapper->OcclusionCullingOn();
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      vtkNew<vtkRenderer> renderer;
      renderer->AddActor(actor);
      std::printf("mode chunked: %lld triangles as one polydata, flattened in %.2f s\n",
        static_cast<long long>(flat->GetNumberOfCells()), 1e-3 * Milliseconds(t0));
      std::fflush(stdout);
      flat = nullptr; // the mapper holds it
      r = Soak(mode, renderer, bounds, path, o,
        [&mapper] { return static_cast<double>(mapper->GetNumberOfTrianglesDrawn()); });
      r.drawnUnit = "triangles";
    }
    else
    {
      if (!grid)
      {
        grid = std::make_unique<sb::EngineGrid>();
        sb::BuildEngineGrid(*grid, engine.parts, o.grid);
        std::printf("scene: 2CylinderEngine (%zu parts, read %.2f s, split %.2f s), %d x %d "
                    "engines = %zu actors, %lld triangles, built in %.2f s; %dx%d, seed %llu\n",
          engine.parts.size(), engine.readSeconds, engine.splitSeconds, o.grid, o.grid,
          grid->actors.size(), static_cast<long long>(grid->triangles), 1e-3 * Milliseconds(t0),
          o.width, o.height, static_cast<unsigned long long>(o.seed));
        std::fflush(stdout);
      }
      vtkRenderer* renderer = grid->renderer;
      renderer->GetCullers()->RemoveAllItems();
      vtkSmartPointer<vtkCuller> culler;
      vtkOctreeCuller* octree = nullptr;
      if (mode == "none")
      {
        culler = vtkSmartPointer<vtkFrustumCoverageCuller>::New();
      }
      else
      {
        auto ours = mode == "occlusion"
          ? vtkSmartPointer<vtkOctreeCuller>(vtkSmartPointer<vtkOcclusionCuller>::New())
          : vtkSmartPointer<vtkOctreeCuller>::New();
        octree = ours;
        culler = ours;
      }
      renderer->AddCuller(culler);
      auto* occlusion = vtkOcclusionCuller::SafeDownCast(octree);
      r = Soak(
        mode, renderer, bounds, path, o,
        [octree] { return octree ? static_cast<double>(octree->GetNumberOfPropsDrawn()) : 0.0; },
        occlusion ? std::function<double()>([occlusion] {
          return static_cast<double>(occlusion->GetOccluderCacheBytes());
        })
                  : nullptr);
      r.drawnUnit = octree ? "props" : "(not counted by VTK's culler)";
      renderer->GetCullers()->RemoveAllItems();
      if (--actorModesLeft == 0)
      {
        grid.reset(); // before the one-mesh mode, whose flattened copy is as big
      }
    }
    Report(r, path, o);
    results.push_back(r);
  }
  std::printf("\nsummary (%zu frames per mode: a path of %zu x %d passes, %d x %d engines, %dx%d, "
              "seed %llu; RSS from: frame %d, or the end of the first pass with 2+ passes)\n",
    path.size() * static_cast<std::size_t>(o.passes), path.size(), o.passes,
    o.grid, o.grid, o.width, o.height, static_cast<unsigned long long>(o.seed), o.warmUp);
  std::printf("%-10s %10s %10s %10s %12s %12s %9s %11s %7s %10s\n", "mode", "median ms", "p95 ms",
    "max ms", "RSS from MiB", "RSS end MiB", "growth %", "peak MiB", "RSS", "frames");
  for (const SoakResult& r : results)
  {
    const Spread s = SpreadOf(r.frameMs);
    std::printf("%-10s %10.1f %10.1f %10.1f %12.1f %12.1f %+9.2f %11.1f %7s %10s\n", r.mode.c_str(),
      s.median, s.p95, s.max, r.rssFrom / kMiB, r.rssEnd / kMiB, r.growth, r.peak / kMiB,
      r.rssPass ? "PASS" : "FAIL", r.framesStable ? "stable" : "UNSTABLE");
  }
  return 0;
}

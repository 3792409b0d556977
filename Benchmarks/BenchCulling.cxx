// Per-frame cull time of vtkOctreeCuller (four update modes) against VTK 9.1's
// vtkFrustumCoverageCuller on 100k props (the part boxes of the CAD assembly as scaled cube
// actors sharing one mapper), calling Cull() directly with a prop array: no rendering.
// Frame time of vtkChunkedPolyDataMapper against vtkPolyDataMapper on one merged CAD mesh of
// ~10M triangles (cadAssembly(100000, 100)) with ~10 % in view, OSMesa 800x600, a frame = a
// small camera move + Render() (wall time: llvmpipe renders in its own threads).
// The core culling benchmarks (Core/Benchmarks/BenchCulling.cpp) are linked into the same
// executable so one run shows everything side by side. `--benchmark_filter=Smoke` runs small
// variants. SCENEVIS_BENCH_MESH_TRIANGLES overrides the mesh size (default 10'000'000).
#include "vtkChunkedPolyDataMapper.h"
#include "vtkOctreeCuller.h"
#include "vtkDemoSceneSource.h"

#include "scenevis/Scenes.h"

#include <glm/common.hpp>
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkCullerCollection.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <vector>

namespace
{
struct PropScene
{
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<vtkProp*> props;
  double center[3];
  double radius;
};

// Released by main() before exit: the OSMesa window must go before static destruction.
std::map<std::size_t, std::unique_ptr<PropScene>> cache;

PropScene& scene(std::size_t n)
{
  auto& s = cache[n];
  if (!s)
  {
    s = std::make_unique<PropScene>();
    s->window = scenevis::testing::MakeRenderWindow(800, 600);
    s->window->AddRenderer(s->renderer);
    const auto cad = scenevis::scenes::cadAssembly(n, 16, 1);
    vtkNew<vtkCubeSource> cube; // unit cube centred at the origin
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(cube->GetOutputPort());
    scenevis::Box all;
    for (const auto& part : cad.parts)
    {
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      const glm::dvec3 c = part.bounds.center();
      const glm::dvec3 d = glm::max(part.bounds.hi - part.bounds.lo, glm::dvec3(1e-3));
      actor->SetPosition(c.x, c.y, c.z);
      actor->SetScale(d.x, d.y, d.z);
      s->actors.push_back(actor);
      s->props.push_back(actor);
      all.extend(part.bounds);
    }
    const glm::dvec3 c = all.center();
    s->center[0] = c.x;
    s->center[1] = c.y;
    s->center[2] = c.z;
    s->radius = 0.5 * all.diagonal();
  }
  return *s;
}

/// 16 views on a slow orbit, overviews and close-ups alternating (as in the core benchmark).
void SetView(PropScene& s, std::size_t frame)
{
  vtkCamera* cam = s.renderer->GetActiveCamera();
  const double t = 0.1 * static_cast<double>(frame % 16);
  const double d = (frame % 2 ? 0.3 : 1.2) * s.radius;
  cam->SetFocalPoint(s.center[0] + 0.1 * s.radius * std::sin(3 * t), s.center[1], s.center[2]);
  cam->SetPosition(
    s.center[0] + std::cos(t) * d, s.center[1] + std::sin(t) * d, s.center[2] + 0.5 * d);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(40);
  cam->SetClippingRange(0.01 * s.radius, 4 * s.radius);
}

void RunCuller(benchmark::State& state, vtkCuller* culler, std::size_t n, vtkOctreeCuller* stats)
{
  PropScene& s = scene(n);
  std::vector<vtkProp*> list(s.props.size());
  std::size_t frame = 0, drawn = 0;
  // Installed as recommended: the culler under test is the renderer's only culler.
  s.renderer->GetCullers()->RemoveAllItems();
  s.renderer->AddCuller(culler);
  // One untimed frame: the octree culler builds its hierarchy (and VTK warms its bounds).
  for (int warm = 0; warm < 2; ++warm)
  {
    list = s.props;
    int length = static_cast<int>(list.size()), initialized = 0;
    SetView(s, 0);
    culler->Cull(s.renderer, list.data(), length, initialized);
  }
  for (auto _ : state)
  {
    state.PauseTiming();
    SetView(s, frame++);
    std::copy(s.props.begin(), s.props.end(), list.begin()); // the renderer's fresh list
    state.ResumeTiming();
    int length = static_cast<int>(list.size()), initialized = 0;
    benchmark::DoNotOptimize(culler->Cull(s.renderer, list.data(), length, initialized));
    drawn += static_cast<std::size_t>(length);
  }
  state.counters["drawn/frame"] = static_cast<double>(drawn) / static_cast<double>(frame);
  if (stats)
  {
    state.counters["rebuilds"] = static_cast<double>(stats->GetNumberOfRebuilds());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

void VtkFrustumCoverage(benchmark::State& state, std::size_t n)
{
  vtkNew<vtkFrustumCoverageCuller> culler;
  RunCuller(state, culler, n, nullptr);
}

void Octree(benchmark::State& state, std::size_t n, int mode)
{
  vtkNew<vtkOctreeCuller> culler;
  culler->SetUpdateMode(mode);
  RunCuller(state, culler, n, culler);
}

void BM_VtkFrustumCoverageCuller_100k(benchmark::State& s) { VtkFrustumCoverage(s, 100000); }
void BM_OctreeCuller_BoundsEveryFrame_100k(benchmark::State& s)
{
  Octree(s, 100000, vtkOctreeCuller::UPDATE_BOUNDS_EVERY_FRAME);
}
void BM_OctreeCuller_OnModified_100k(benchmark::State& s)
{
  Octree(s, 100000, vtkOctreeCuller::UPDATE_ON_MODIFIED);
}
void BM_OctreeCuller_Manual_100k(benchmark::State& s)
{
  Octree(s, 100000, vtkOctreeCuller::UPDATE_MANUAL);
}
void BM_OctreeCuller_OnEvents_100k(benchmark::State& s)
{
  Octree(s, 100000, vtkOctreeCuller::UPDATE_ON_EVENTS);
}
void BM_Smoke_VtkFrustumCoverageCuller_1k(benchmark::State& s) { VtkFrustumCoverage(s, 1000); }
void BM_Smoke_OctreeCuller_1k(benchmark::State& s)
{
  Octree(s, 1000, vtkOctreeCuller::UPDATE_BOUNDS_EVERY_FRAME);
}
void BM_Smoke_OctreeCuller_OnEvents_1k(benchmark::State& s)
{
  Octree(s, 1000, vtkOctreeCuller::UPDATE_ON_EVENTS);
}

// ---- One big mesh: chunked vs plain mapper, whole frames. ------------------------------------
struct MeshScene
{
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkRenderer> plainRenderer, chunkedRenderer;
  vtkNew<vtkPolyDataMapper> plain;
  vtkNew<vtkChunkedPolyDataMapper> chunked;
  vtkNew<vtkActor> plainActor, chunkedActor;
  vtkNew<vtkCamera> camera;
  double bounds[6];
  vtkIdType triangles = 0;
};
std::map<std::size_t, std::unique_ptr<MeshScene>> meshCache;

MeshScene& meshScene(std::size_t parts, std::size_t trianglesPerPart)
{
  auto& s = meshCache[parts * 100000 + trianglesPerPart];
  if (!s)
  {
    s = std::make_unique<MeshScene>();
    vtkNew<vtkDemoSceneSource> source;
    source->SetScene(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY);
    source->SetPartCount(static_cast<vtkIdType>(parts));
    source->SetTriangleCount(static_cast<vtkIdType>(parts * trianglesPerPart));
    source->Update();
    vtkNew<vtkPolyData> mesh;
    mesh->ShallowCopy(source->GetOutput());
    // Opaque part colours (RGB cell scalars): both mappers draw in the opaque pass.
    auto* rgba = vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetScalars());
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetName("RGB");
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(rgba->GetNumberOfTuples());
    for (vtkIdType i = 0; i < rgba->GetNumberOfTuples(); ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        rgb->SetValue(3 * i + k, rgba->GetValue(4 * i + k));
      }
    }
    mesh->GetCellData()->RemoveArray(rgba->GetName());
    mesh->GetCellData()->SetScalars(rgb);
    mesh->GetBounds(s->bounds);
    s->triangles = mesh->GetNumberOfPolys();
    s->window = scenevis::testing::MakeRenderWindow(800, 600);
    s->plain->SetInputData(mesh);
    s->chunked->SetInputData(mesh);
    s->plainActor->SetMapper(s->plain);
    s->chunkedActor->SetMapper(s->chunked);
    s->plainRenderer->AddActor(s->plainActor);
    s->chunkedRenderer->AddActor(s->chunkedActor);
    s->plainRenderer->SetActiveCamera(s->camera);
    s->chunkedRenderer->SetActiveCamera(s->camera);
  }
  return *s;
}

/// Looking obliquely down at a corner region of the board: about 10 % of the triangles in view.
/// @p frame moves the camera a little (a slow pan).
void MeshView(MeshScene& s, std::size_t frame)
{
  const double* b = s.bounds;
  const double w = b[1] - b[0], h = b[3] - b[2];
  const double t = 0.002 * static_cast<double>(frame % 50);
  const double fx = b[0] + (0.22 + t) * w, fy = b[2] + 0.22 * h;
  s.camera->SetFocalPoint(fx, fy, b[4]);
  s.camera->SetPosition(fx - 0.12 * w, fy - 0.12 * h, b[4] + 0.18 * w);
  s.camera->SetViewUp(0, 0, 1);
  s.camera->SetViewAngle(30);
  s.camera->SetClippingRange(0.005 * w, 2.0 * w);
}

void MeshFrame(benchmark::State& state, std::size_t parts, std::size_t perPart, bool chunked)
{
  MeshScene& s = meshScene(parts, perPart);
  vtkRenderer* ren = chunked ? s.chunkedRenderer.GetPointer() : s.plainRenderer.GetPointer();
  s.window->GetRenderers()->RemoveAllItems();
  s.window->AddRenderer(ren);
  MeshView(s, 0);
  s.window->Render(); // builds the buffers (and the partition), untimed
  s.window->Render();
  std::size_t frame = 0;
  double drawn = 0.0, calls = 0.0;
  for (auto _ : state)
  {
    MeshView(s, ++frame);
    s.window->Render();
    if (chunked)
    {
      drawn += static_cast<double>(s.chunked->GetNumberOfTrianglesDrawn());
      calls += static_cast<double>(s.chunked->GetNumberOfDrawCalls());
    }
    else
    {
      drawn += static_cast<double>(s.triangles);
    }
  }
  const double frames = static_cast<double>(std::max<std::size_t>(frame, 1));
  state.counters["triangles"] = static_cast<double>(s.triangles);
  state.counters["drawn/frame"] = drawn / frames;
  state.counters["in view %"] = 100.0 * drawn / frames / static_cast<double>(s.triangles);
  if (chunked)
  {
    state.counters["draw calls"] = calls / frames;
    state.counters["chunks"] = static_cast<double>(s.chunked->GetNumberOfChunks());
    state.counters["VBO builds"] = static_cast<double>(s.chunked->GetNumberOfVertexBufferBuilds());
    state.counters["partition s"] = s.chunked->GetLastPartitionTime();
  }
}

std::size_t MeshParts()
{
  const char* env = std::getenv("SCENEVIS_BENCH_MESH_TRIANGLES");
  const std::size_t triangles = env ? std::strtoull(env, nullptr, 10) : 10000000;
  return std::max<std::size_t>(triangles / 100, 100);
}
void BM_PlainMapperFrame_CadMesh(benchmark::State& s) { MeshFrame(s, MeshParts(), 100, false); }
void BM_ChunkedMapperFrame_CadMesh(benchmark::State& s) { MeshFrame(s, MeshParts(), 100, true); }
void BM_Smoke_PlainMapperFrame_CadMesh(benchmark::State& s) { MeshFrame(s, 2000, 50, false); }
void BM_Smoke_ChunkedMapperFrame_CadMesh(benchmark::State& s) { MeshFrame(s, 2000, 50, true); }
} // namespace

BENCHMARK(BM_VtkFrustumCoverageCuller_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeCuller_BoundsEveryFrame_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeCuller_OnModified_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeCuller_Manual_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeCuller_OnEvents_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Smoke_VtkFrustumCoverageCuller_1k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Smoke_OctreeCuller_1k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Smoke_OctreeCuller_OnEvents_1k)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlainMapperFrame_CadMesh)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(6);
BENCHMARK(BM_ChunkedMapperFrame_CadMesh)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(30);
BENCHMARK(BM_Smoke_PlainMapperFrame_CadMesh)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_Smoke_ChunkedMapperFrame_CadMesh)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

int main(int argc, char** argv)
{
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
  {
    return 1;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  cache.clear();
  meshCache.clear();
  return 0;
}

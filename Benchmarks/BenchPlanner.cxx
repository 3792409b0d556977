// What vtkSceneVisPlanner costs per render, without the render (its Plan(), which the renderer's
// StartEvent calls), on grids of N box actors (shared mapper, one window):
//  - Unchanged: nothing changed since the last plan (the target: <= 0.05 ms a frame);
//  - StartEvent: the same through the renderer's StartEvent, as in a real render;
//  - CameraMoved: the camera moved a little every call (ManyProps+ actors: the view measured
//    again; hysteresis keeps the plan);
//  - ActorMoved: one actor moved every call (the scene read again: only that actor re-measured).
// Run: build/bin/scenevis_planner_bench [--benchmark_filter=Unchanged]
#include "vtkSceneVisPlanner.h"

#include "scenevis/testing/RenderWindow.h"

#include <benchmark/benchmark.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkCubeSource.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cmath>
#include <vector>

namespace
{
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(320, 240);
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkPolyDataMapper> mapper;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  vtkNew<vtkSceneVisPlanner> planner;

  explicit Scene(int n)
  {
    this->window->AddRenderer(this->renderer);
    this->cube->SetXLength(0.8);
    this->cube->SetYLength(0.8);
    this->cube->SetZLength(0.8);
    this->mapper->SetInputConnection(this->cube->GetOutputPort());
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    for (int i = 0; i < n; ++i)
    {
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(this->mapper);
      actor->SetPosition(i % side, i / side, 0);
      this->renderer->AddActor(actor);
      this->actors.push_back(actor);
    }
    vtkCamera* camera = this->renderer->GetActiveCamera();
    camera->SetFocalPoint(side / 2.0, side / 2.0, 0);
    camera->SetPosition(side / 2.0, -side / 2.0, side / 2.0);
    camera->SetViewUp(0, 0, 1);
    this->planner->SetRenderer(this->renderer);
    this->planner->Plan();
  }
};

void Unchanged(benchmark::State& state)
{
  Scene scene(static_cast<int>(state.range(0)));
  for (auto _ : state)
    scene.planner->Plan();
  state.counters["plans"] = scene.planner->GetPlanCount();
  state.counters["readings"] = scene.planner->GetInspectionCount();
}

void StartEvent(benchmark::State& state)
{
  Scene scene(static_cast<int>(state.range(0)));
  for (auto _ : state)
    scene.renderer->InvokeEvent(vtkCommand::StartEvent);
  state.counters["readings"] = scene.planner->GetInspectionCount();
}

void CameraMoved(benchmark::State& state)
{
  Scene scene(static_cast<int>(state.range(0)));
  vtkCamera* camera = scene.renderer->GetActiveCamera();
  int i = 0;
  for (auto _ : state)
  {
    camera->Azimuth((i++ % 2) ? 0.01 : -0.01);
    scene.planner->Plan();
  }
  state.counters["measurements"] = scene.planner->GetViewMeasurementCount();
}

void ActorMoved(benchmark::State& state)
{
  Scene scene(static_cast<int>(state.range(0)));
  int i = 0;
  for (auto _ : state)
  {
    scene.actors[0]->SetPosition(0, 0, (i++ % 2) ? 0.01 : 0.0);
    scene.planner->Plan();
  }
  state.counters["readings"] = scene.planner->GetInspectionCount();
}
} // namespace

BENCHMARK(Unchanged)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(StartEvent)->Arg(10)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(CameraMoved)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(ActorMoved)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();

// Example: an ordinary VTK program plus ONE line, vtkSceneVisPlanner::Attach(renderer), gets the
// visibility effects its scene calls for, re-planned as the camera moves:
//
//   800 opaque boxes (one actor each, 20 x 20 x 2) and 3 overlapping translucent spheres
//   -> the planner: exact translucency across the 3 spheres (vtkBSPTranslucentPass), and
//      vtkOcclusionCuller in place of VTK's frustum coverage culler (800 actors: its hierarchy
//      costs less per frame even with everything in view), with occlusion culling on once the
//      boxes hide one another (estimated depth complexity 4 or more)
//
// The camera flies from an overview (everything in view, little overlap: frustum culling) down
// to a view along the rows of boxes (most of them hidden: occlusion culling); the plan changes
// once on the way, not every frame. Renders offscreen without X through the OSMesa window
// (SceneVis::RenderingHeadless); with a display, a vtkRenderWindow does the same.
// Usage: AutoPlanner [frames] (default 40)
#include "vtkSceneVisOSMesaRenderWindow.h"
#include "vtkSceneVisPlanner.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCubeSource.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  const int frames = argc > 1 ? std::max(2, std::atoi(argv[1])) : 40;

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCubeSource> cube;
  cube->SetXLength(0.8);
  cube->SetYLength(0.8);
  cube->SetZLength(0.8);
  vtkNew<vtkPolyDataMapper> cubeMapper;
  cubeMapper->SetInputConnection(cube->GetOutputPort());
  for (int z = 0; z < 2; ++z)
  {
    for (int y = 0; y < 20; ++y)
    {
      for (int x = 0; x < 20; ++x)
      {
        vtkNew<vtkActor> box;
        box->SetMapper(cubeMapper);
        box->SetPosition(x, y, z);
        box->GetProperty()->SetColor(0.3 + 0.03 * x, 0.3 + 0.03 * y, 0.8 - 0.3 * z);
        renderer->AddActor(box);
      }
    }
  }
  const double centres[3][3] = { { 9.5, 9.5, 2.5 }, { 10.3, 9.8, 2.7 }, { 9.9, 10.4, 2.3 } };
  const double colours[3][3] = { { 1, 0.2, 0.1 }, { 0.1, 0.4, 1 }, { 0.2, 1, 0.3 } };
  for (int s = 0; s < 3; ++s)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(centres[s][0], centres[s][1], centres[s][2]);
    sphere->SetRadius(0.9);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(colours[s][0], colours[s][1], colours[s][2]);
    actor->GetProperty()->SetOpacity(0.4);
    renderer->AddActor(actor);
  }

  // The one line: only the effects this scene calls for, planned at every render.
  vtkSceneVisPlanner* planner = vtkSceneVisPlanner::Attach(renderer);

  vtkNew<vtkSceneVisOSMesaRenderWindow> window;
  window->SetSize(320, 240);
  std::string error;
  if (!window->CreateContext(&error))
  {
    std::cerr << "AutoPlanner: " << error << "\n";
    return EXIT_FAILURE;
  }
  window->AddRenderer(renderer);

  vtkCamera* camera = renderer->GetActiveCamera();
  std::string last;
  for (int frame = 0; frame < frames; ++frame)
  {
    const double t = static_cast<double>(frame) / (frames - 1);
    camera->SetFocalPoint(9.5 + 10.5 * t, 9.5 + 0.5 * t, 0.5);
    camera->SetPosition(9.5 - 12.5 * t, -25 + 34.8 * t, 35 - 34.5 * t);
    camera->SetViewUp(0, 0, 1);
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
    window->Render();
    const std::string plan =
      std::string(planner->GetCullMethod()) + " / " + planner->GetTranslucencyMethod();
    if (plan != last)
      std::cout << "frame " << frame << ": culling / translucency " << plan << "\n  "
                << planner->GetReason() << "\n";
    last = plan;
  }
  std::cout << "planned " << planner->GetPlanCount() << " times in " << frames
            << " frames; last plan took " << planner->GetLastPlanTime() << " ms\n";
  const bool culled = std::string(planner->GetCullMethod()) == "occlusion";
  const bool exact = std::string(planner->GetTranslucencyMethod()) == "multi-actor";
  return culled && exact ? EXIT_SUCCESS : EXIT_FAILURE;
}

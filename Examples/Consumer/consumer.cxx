// Through the installed SceneVis package: sorts a sphere for a camera (SceneVis::FiltersSorting),
// reads a VRML part whose material is USEd (SceneVis::IOModels), and renders it offscreen without X
// through the OSMesa window (SceneVis::RenderingHeadless) with the auto planner attached
// (SceneVis::RenderingAuto): the frame must show the part's green. Then the same through the
// checked window factory and image measures (SceneVis::RenderingHeadless), the part's visible
// cells by an ID render (SceneVis::RenderingIdBuffer), a demo building's portals
// (SceneVis::FiltersSources) and the data cache's directory (SceneVis::IOModels).
#include "scenevis/Scenes.h"

#include <vtkActor.h>
#include <vtkBSPSortFilter.h>
#include <vtkCamera.h>
#include <vtkDemoScenePortals.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSceneVisDataCache.h>
#include <vtkSceneVisHeadlessWindows.h>
#include <vtkSceneVisIdBuffer.h>
#include <vtkSceneVisImageCompare.h>
#include <vtkSceneVisModelReader.h>
#include <vtkSceneVisOSMesaRenderWindow.h>
#include <vtkSceneVisPlanner.h>
#include <vtkSphereSource.h>
#include <vtkUnsignedCharArray.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
// A quad in the xy plane whose material is DEF'd on one shape and USEd on the quad's.
const char* const kPart = R"(#VRML V2.0 utf8
Shape { appearance Appearance { material DEF GREEN Material { diffuseColor 0.1 0.8 0.2 } } }
Shape { geometry IndexedFaceSet { coordIndex [0,1,2,3,-1]
  coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] } }
  appearance Appearance { material USE GREEN } }
)";
}

int main()
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 4);
  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputConnection(sphere->GetOutputPort());
  sorter->SetCamera(camera);
  sorter->Update();
  const vtkIdType sorted = sorter->GetOutput()->GetNumberOfPolys();
  std::cout << "consumer: sorted " << sorted << " polygons" << std::endl;
  if (sorted < sphere->GetOutput()->GetNumberOfPolys())
  {
    return EXIT_FAILURE;
  }

  const std::string path = "consumer-part.wrl";
  std::ofstream(path) << kPart;
  vtkNew<vtkSceneVisModelReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  std::remove(path.c_str());
  const vtkIdType cells = reader->GetOutput()->GetNumberOfCells();
  std::cout << "consumer: read " << cells << " cell(s) " << reader->GetErrorMessage() << std::endl;
  if (cells != 1)
  {
    return EXIT_FAILURE;
  }

  const std::string linkOrder = vtkSceneVisOSMesaRenderWindow::CheckLinkOrder();
  if (!linkOrder.empty())
  {
    std::cerr << "consumer: " << linkOrder << std::endl;
    return EXIT_FAILURE;
  }
  vtkNew<vtkSceneVisOSMesaRenderWindow> window;
  window->SetSize(64, 48);
  std::string error;
  if (!window->CreateContext(&error))
  {
    std::cerr << "consumer: " << error << std::endl;
    return EXIT_FAILURE;
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetScalarModeToUseCellData(); // the parts' colours (VRML parts also get point scalars)
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff(); // the cell colours as they are
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0, 0, 0);
  window->AddRenderer(renderer);
  vtkSceneVisPlanner* planner = vtkSceneVisPlanner::Attach(renderer); // SceneVis::RenderingAuto
  renderer->ResetCamera();
  window->Render();
  std::cout << "consumer: planned " << planner->GetPlanCount() << " time(s): culling "
            << planner->GetCullMethod() << ", translucency " << planner->GetTranslucencyMethod()
            << std::endl;
  if (planner->GetPlanCount() != 1)
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkUnsignedCharArray> pixels;
  vtkRenderWindow* base = window; // vtkOpenGLRenderWindow hides the array overload
  base->GetPixelData(0, 0, 63, 47, /*front=*/0, pixels);
  vtkIdType green = 0;
  for (vtkIdType i = 0; i < pixels->GetNumberOfTuples(); ++i)
  {
    if (pixels->GetValue(3 * i + 1) > 150 && pixels->GetValue(3 * i) < 80)
    {
      ++green;
    }
  }
  std::cout << "consumer: rendered " << green << " of " << pixels->GetNumberOfTuples()
            << " pixels green through the installed OSMesa window" << std::endl;
  if (green <= pixels->GetNumberOfTuples() / 4)
  {
    return EXIT_FAILURE;
  }

  vtkSmartPointer<vtkRenderWindow> checked = scenevis::headless::MakeRenderWindow(64, 48);
  vtkNew<vtkPolyDataMapper> mapperAgain; // mappers keep their buffers in one window's context
  mapperAgain->SetInputConnection(reader->GetOutputPort());
  mapperAgain->SetScalarModeToUseCellData();
  vtkNew<vtkActor> actorAgain;
  actorAgain->SetMapper(mapperAgain);
  actorAgain->GetProperty()->LightingOff();
  vtkNew<vtkRenderer> again;
  again->AddActor(actorAgain);
  again->SetActiveCamera(renderer->GetActiveCamera());
  checked->AddRenderer(again);
  const double covered = scenevis::headless::CoveredFraction(
    scenevis::headless::CaptureImage(checked), scenevis::headless::Rgb{ 0, 0, 0 });
  const std::size_t visible = scenevis::idbuffer::VisibleSet(
    scenevis::idbuffer::RenderVisibleIds(checked, reader->GetOutput(), again->GetActiveCamera()))
                                .size();
  const vtkIdType portals =
    scenevis::MakePortalPolyData(scenevis::scenes::building(1, 2, 1, 1))->GetNumberOfCells();
  std::cout << "consumer: " << scenevis::headless::BackendName(scenevis::headless::DefaultBackend())
            << " window covered " << covered << ", " << visible << " cell(s) visible, " << portals
            << " portal(s), data cache " << scenevis::DataDirectory() << std::endl;
  return covered > 0.25 && visible == 1 && portals > 0 && !scenevis::DataDirectory().empty()
    ? EXIT_SUCCESS
    : EXIT_FAILURE;
}

// `scenevis sort`: the polydata in BSP order for a camera, written as VTK XML (--instances: the
// placed meshes flattened into world space first).
#include "Commands.h"
#include "Progress.h"
#include "Report.h"
#include "SceneLoading.h"
#include "vtkBSPSortFilter.h"

#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenevis
{
namespace tool
{

int RunSort(const Options& options)
{
  LoadedScene scene = LoadScene(options);
  if (options.instances)
  {
    // The BSP over every placed polygon in world space: exact (polygons of different placements
    // that cross are split), and cell for cell the order of the flattened file. Ordering the
    // placements as whole actors (the multi-actor pass) is not exact: two interpenetrating
    // placements have no right order.
    const InstancedScene instanced = UnpackMeshLibrary(scene.polydata);
    scene.polydata = FlattenInstances(instanced);
    scene.description += ", " + std::to_string(instanced.meshes.size()) + " meshes placed " +
      std::to_string(instanced.instances.size()) + " times, flattened";
  }
  double bounds[6];
  scene.polydata->GetBounds(bounds);
  const double center[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const bool perCamera = !options.cameras.empty();
  const std::vector<CameraSpec> cameras = CamerasToRun(options);
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
    const CameraSpec& spec = cameras[c];
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

} // namespace tool
} // namespace scenevis

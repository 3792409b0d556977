// `scenevis portals`: rooms and portals found from a model's geometry (scenevis/PortalGeneration.h)
// and written in the portal scene format: OUT.vtp, the model with an integer room cell array
// (--room-array, default RoomId; -1 outside), and OUT-portals.vtp, one polygon per portal with
// RoomA and RoomB, which `render`, `cull` and vtkPortalCuller read. Translucent cells (alpha below
// 255 in the scene's RGBA colours: glass) are see-through: they do not close an opening. A model
// that leaks gets no rooms (every cell -1, no portals) unless --keep-leaking-rooms: a warning says
// which.
#include "Commands.h"
#include "GeneratedRooms.h"
#include "Report.h"
#include "SceneLoading.h"

#include "scenevis/PortalGeneration.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenevis
{
namespace tool
{
namespace
{
/// Writes @p data to @p path through a temporary file, so a failed run leaves no half file.
void WriteVtp(vtkPolyData* data, const std::string& path)
{
  const std::string partial = path + ".partial";
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(partial.c_str());
  writer->SetInputData(data);
  writer->SetDataModeToAppended(); // raw appended: the core's own reader takes it too
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToNone();
  if (writer->Write() != 1 || std::rename(partial.c_str(), path.c_str()) != 0)
  {
    std::remove(partial.c_str());
    throw std::runtime_error("cannot write " + path);
  }
}

} // namespace

int RunPortals(const Options& options)
{
  const LoadedScene scene = LoadScene(options);
  vtkPolyData* model = scene.polydata;
  const GeneratedRooms generated =
    GenerateRooms(model, options.roomArray, 0.0, false, options.keepLeakingRooms);
  const portals::GeneratedPortals& result = generated.result;
  if (result.status != portals::GenerationStatus::Ok)
  {
    throw std::runtime_error("no rooms found in " + scene.description + ": " + result.message);
  }
  vtkNew<vtkPolyData> out;
  out->ShallowCopy(model);
  out->GetCellData()->RemoveArray(options.roomArray.c_str());
  out->GetCellData()->AddArray(generated.rooms);
  const std::string modelPath = options.out + ".vtp";
  const std::string portalsPath = options.out + "-portals.vtp";
  WriteVtp(generated.portals, portalsPath);
  WriteVtp(out, modelPath);

  const portals::GenerationStatistics& s = result.statistics;
  if (s.leakCells > 0 && !result.leakPoints.empty())
  {
    const glm::dvec3& at = result.leakPoints.front();
    std::cerr << "warning: " << s.leakCells << " leak cells, the first at (" << at.x << ", " << at.y
              << ", " << at.z << "): "
              << (options.keepLeakingRooms
                     ? "rooms kept (--keep-leaking-rooms): NOT conservative, the portals may hide "
                       "visible cells"
                     : "no rooms written (every cell -1, no portals): portals through a leak may "
                       "hide visible cells; " +
                       std::to_string(s.roomsWithheld) + " rooms and " +
                       std::to_string(s.portalsWithheld) +
                       " portals withheld (--keep-leaking-rooms writes them)")
              << "\n";
  }
  std::cout << "{\"scene\": " << JsonString(scene.description)
            << ", \"polygons\": " << s.inputPolygons
            << ", \"see_through_polygons\": " << generated.seeThroughPolygons
            << ", \"dropped_polygons\": " << s.droppedPolygons << ", \"cells\": " << s.cells
            << ", \"rooms\": " << result.roomCount << ", \"portals\": " << result.portals.size()
            << ", \"exterior_portals\": " << s.exteriorPortals
            << ", \"leak_cells\": " << s.leakCells << ", \"rooms_withheld\": " << s.roomsWithheld
            << ", \"portals_withheld\": " << s.portalsWithheld
            << ", \"polygons_without_room\": " << s.polygonsWithoutRoom
            << ", \"seconds\": " << s.totalSeconds << ", \"bsp_seconds\": " << s.bspSeconds
            << ", \"cell_seconds\": " << s.cellSeconds
            << ", \"opening_seconds\": " << s.openingSeconds
            << ", \"model\": " << JsonString(modelPath)
            << ", \"portals_file\": " << JsonString(portalsPath) << "}\n";
  return EXIT_SUCCESS;
}

} // namespace tool
} // namespace scenevis

// `scenevis portals`: rooms and portals found from a model's geometry (scenevis/PortalGeneration.h)
// and written in the portal scene format: OUT.vtp, the model with an integer room cell array
// (--room-array, default RoomId; -1 outside), and OUT-portals.vtp, one polygon per portal with
// RoomA and RoomB, which `render`, `cull` and vtkPortalCuller read. Translucent cells (alpha below
// 255 in the scene's RGBA colours: glass) are see-through: they do not close an opening.
#include "Commands.h"
#include "Report.h"
#include "SceneLoading.h"
#include "vtkBSPSortUtilities.h"

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

/// The portals as polygons with RoomA and RoomB.
vtkSmartPointer<vtkPolyData> PortalPolyData(const std::vector<portals::PortalDesc>& descs)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> roomA;
  roomA->SetName("RoomA");
  vtkNew<vtkIntArray> roomB;
  roomB->SetName("RoomB");
  for (const portals::PortalDesc& portal : descs)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(portal.polygon.size()));
    for (const glm::dvec3& p : portal.polygon)
    {
      polys->InsertCellPoint(points->InsertNextPoint(p.x, p.y, p.z));
    }
    roomA->InsertNextValue(portal.roomA);
    roomB->InsertNextValue(portal.roomB);
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetPolys(polys);
  data->GetCellData()->AddArray(roomA);
  data->GetCellData()->AddArray(roomB);
  return data;
}
} // namespace

int RunPortals(const Options& options)
{
  const LoadedScene scene = LoadScene(options);
  vtkPolyData* model = scene.polydata;
  PolygonMesh mesh;
  std::vector<vtkIdType> cellOf;
  vtkBSPSortUtilities::AppendPolygons(model, nullptr, mesh, cellOf);
  portals::GenerationInput input;
  input.mesh = &mesh;
  auto* colors = vtkUnsignedCharArray::SafeDownCast(model->GetCellData()->GetScalars());
  std::size_t seeThrough = 0;
  if (colors && colors->GetNumberOfComponents() == 4)
  {
    for (const vtkIdType cell : cellOf)
    {
      input.seeThrough.push_back(colors->GetTypedComponent(cell, 3) < 255 ? 1 : 0);
      seeThrough += input.seeThrough.back();
    }
  }
  const portals::GeneratedPortals result = portals::generatePortals(input);
  if (result.status != portals::GenerationStatus::Ok)
  {
    throw std::runtime_error("no rooms found in " + scene.description + ": " + result.message);
  }

  // The room of every cell: its polygon's (a strip's first triangle's), -1 for other cells.
  vtkNew<vtkIntArray> rooms;
  rooms->SetName(options.roomArray.c_str());
  rooms->SetNumberOfTuples(model->GetNumberOfCells());
  rooms->FillValue(portals::kOutsideRoom);
  std::vector<char> assigned(static_cast<std::size_t>(model->GetNumberOfCells()), 0);
  for (std::size_t i = 0; i < cellOf.size(); ++i)
  {
    if (!assigned[static_cast<std::size_t>(cellOf[i])])
    {
      rooms->SetValue(cellOf[i], result.roomOfPolygon[i]);
      assigned[static_cast<std::size_t>(cellOf[i])] = 1;
    }
  }
  vtkNew<vtkPolyData> out;
  out->ShallowCopy(model);
  out->GetCellData()->RemoveArray(options.roomArray.c_str());
  out->GetCellData()->AddArray(rooms);
  const std::string modelPath = options.out + ".vtp";
  const std::string portalsPath = options.out + "-portals.vtp";
  WriteVtp(PortalPolyData(result.portals), portalsPath);
  WriteVtp(out, modelPath);

  const portals::GenerationStatistics& s = result.statistics;
  std::cout << "{\"scene\": " << JsonString(scene.description)
            << ", \"polygons\": " << s.inputPolygons << ", \"see_through_polygons\": " << seeThrough
            << ", \"dropped_polygons\": " << s.droppedPolygons << ", \"cells\": " << s.cells
            << ", \"rooms\": " << result.roomCount << ", \"portals\": " << result.portals.size()
            << ", \"exterior_portals\": " << s.exteriorPortals
            << ", \"leak_cells\": " << s.leakCells
            << ", \"polygons_without_room\": " << s.polygonsWithoutRoom
            << ", \"seconds\": " << s.totalSeconds << ", \"model\": " << JsonString(modelPath)
            << ", \"portals_file\": " << JsonString(portalsPath) << "}\n";
  return EXIT_SUCCESS;
}

} // namespace tool
} // namespace scenevis

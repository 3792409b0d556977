#include "vtkGenerateRooms.h"

#include "vtkBSPSortUtilities.h"

#include "scenevis/PortalGeneration.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <string>
#include <vector>

namespace portals = scenevis::portals;

struct vtkGenerateRooms::Internals
{
  portals::GeneratedPortals Result;
  bool Run = false;
  vtkIdType SeeThroughPolygons = 0;
};

vtkStandardNewMacro(vtkGenerateRooms);

namespace
{
/// One polygon per portal with RoomA and RoomB.
void FillPortals(const std::vector<portals::PortalDesc>& descs, vtkPolyData* output)
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
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetCellData()->AddArray(roomA);
  output->GetCellData()->AddArray(roomB);
}

/// One vertex per leak point.
void FillLeaks(const std::vector<glm::dvec3>& leaks, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> verts;
  for (const glm::dvec3& p : leaks)
  {
    verts->InsertNextCell(1);
    verts->InsertCellPoint(points->InsertNextPoint(p.x, p.y, p.z));
  }
  output->SetPoints(points);
  output->SetVerts(verts);
}

const char* StatusName(int status)
{
  switch (status)
  {
    case vtkGenerateRooms::STATUS_OK:
      return "ok";
    case vtkGenerateRooms::STATUS_EMPTY_INPUT:
      return "empty input";
    case vtkGenerateRooms::STATUS_NO_VALID_POLYGONS:
      return "no valid polygons";
    case vtkGenerateRooms::STATUS_OVER_BUDGET:
      return "over budget";
    default:
      return "not run";
  }
}
} // namespace

vtkGenerateRooms::vtkGenerateRooms()
  : Internal(new Internals)
{
  const portals::GenerationConfig defaults;
  this->OpeningEnclosure = defaults.openingEnclosure;
  this->PassageThickness = defaults.passageThickness;
  this->Margin = defaults.margin;
  this->BudgetSeconds = defaults.budgetSeconds;
  this->StopAtFirstLeak = defaults.stopAtFirstLeak;
  this->KeepRoomsWithLeaks = defaults.keepRoomsWithLeaks;
  this->SetRoomArrayName("RoomId");
  this->SetNumberOfOutputPorts(3);
}

vtkGenerateRooms::~vtkGenerateRooms()
{
  this->SetRoomArrayName(nullptr);
}

vtkPolyData* vtkGenerateRooms::GetPortalsOutput()
{
  return this->GetOutput(1);
}

vtkPolyData* vtkGenerateRooms::GetLeaksOutput()
{
  return this->GetOutput(2);
}

int vtkGenerateRooms::GetStatus() const
{
  if (!this->Internal->Run)
  {
    return STATUS_NOT_RUN;
  }
  switch (this->Internal->Result.status)
  {
    case portals::GenerationStatus::Ok:
      return STATUS_OK;
    case portals::GenerationStatus::EmptyInput:
      return STATUS_EMPTY_INPUT;
    case portals::GenerationStatus::NoValidPolygons:
      return STATUS_NO_VALID_POLYGONS;
    case portals::GenerationStatus::OverBudget:
      return STATUS_OVER_BUDGET;
  }
  return STATUS_NOT_RUN;
}

const char* vtkGenerateRooms::GetStatusMessage() const
{
  return this->Internal->Result.message.c_str();
}

int vtkGenerateRooms::GetNumberOfRooms() const
{
  return this->Internal->Result.roomCount;
}

vtkIdType vtkGenerateRooms::GetNumberOfPortals() const
{
  return static_cast<vtkIdType>(this->Internal->Result.portals.size());
}

vtkIdType vtkGenerateRooms::GetNumberOfExteriorPortals() const
{
  return static_cast<vtkIdType>(this->Internal->Result.statistics.exteriorPortals);
}

vtkIdType vtkGenerateRooms::GetNumberOfLeakCells() const
{
  return static_cast<vtkIdType>(this->Internal->Result.statistics.leakCells);
}

vtkIdType vtkGenerateRooms::GetNumberOfDroppedPolygons() const
{
  return static_cast<vtkIdType>(this->Internal->Result.statistics.droppedPolygons);
}

vtkIdType vtkGenerateRooms::GetNumberOfSeeThroughPolygons() const
{
  return this->Internal->SeeThroughPolygons;
}

double vtkGenerateRooms::GetGenerationTime() const
{
  return this->Internal->Result.statistics.totalSeconds;
}

const portals::GeneratedPortals& vtkGenerateRooms::GetResult() const
{
  return this->Internal->Result;
}

int vtkGenerateRooms::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* portalsOutput = vtkPolyData::GetData(outputVector, 1);
  vtkPolyData* leaksOutput = vtkPolyData::GetData(outputVector, 2);
  if (!input || !output || !portalsOutput || !leaksOutput)
  {
    return 0;
  }
  const std::string roomArray =
    this->RoomArrayName && *this->RoomArrayName ? this->RoomArrayName : "RoomId";

  // The model's polygons (strips as triangles), each with the input cell it comes from.
  scenevis::PolygonMesh mesh;
  std::vector<vtkIdType> cellOf;
  vtkBSPSortUtilities::AppendPolygons(input, nullptr, mesh, cellOf);
  portals::GenerationInput generationInput;
  generationInput.mesh = &mesh;
  this->Internal->SeeThroughPolygons = 0;
  auto* colors = vtkUnsignedCharArray::SafeDownCast(input->GetCellData()->GetScalars());
  if (this->TranslucentCellsAreSeeThrough && colors && colors->GetNumberOfComponents() == 4)
  {
    generationInput.seeThrough.reserve(cellOf.size());
    for (const vtkIdType cell : cellOf)
    {
      const bool glass = colors->GetTypedComponent(cell, 3) < 255;
      generationInput.seeThrough.push_back(glass ? 1 : 0);
      this->Internal->SeeThroughPolygons += glass ? 1 : 0;
    }
  }
  portals::GenerationConfig config;
  config.openingEnclosure = this->OpeningEnclosure;
  config.passageThickness = this->PassageThickness;
  config.margin = this->Margin;
  config.budgetSeconds = this->BudgetSeconds;
  config.stopAtFirstLeak = this->StopAtFirstLeak;
  config.keepRoomsWithLeaks = this->KeepRoomsWithLeaks;
  this->UpdateProgress(0.0);
  this->Internal->Result = portals::generatePortals(generationInput, config);
  this->Internal->Run = true;
  const portals::GeneratedPortals& result = this->Internal->Result;
  this->UpdateProgress(1.0);

  // Every cell gets a room, -1 unless generation gave its polygon (a strip: its first
  // triangle's) one.
  output->ShallowCopy(input);
  vtkNew<vtkIntArray> rooms;
  rooms->SetName(roomArray.c_str());
  rooms->SetNumberOfTuples(input->GetNumberOfCells());
  rooms->FillValue(portals::kOutsideRoom);
  if (result.status == portals::GenerationStatus::Ok)
  {
    std::vector<char> assigned(static_cast<std::size_t>(input->GetNumberOfCells()), 0);
    for (std::size_t i = 0; i < cellOf.size(); ++i)
    {
      const auto cell = static_cast<std::size_t>(cellOf[i]);
      if (!assigned[cell])
      {
        rooms->SetValue(cellOf[i], result.roomOfPolygon[i]);
        assigned[cell] = 1;
      }
    }
  }
  // An input room array goes, in cell data and in field data: vtkPortalCuller reads a field
  // array of that name first (one room for a whole actor), so a stale one passed through would
  // put every cell in one room.
  output->GetCellData()->RemoveArray(roomArray.c_str());
  output->GetFieldData()->RemoveArray(roomArray.c_str());
  output->GetCellData()->AddArray(rooms);
  FillPortals(result.portals, portalsOutput);
  FillLeaks(result.leakPoints, leaksOutput);

  // Say what a user would otherwise not see: no rooms, leaks, polygons left out.
  const int status = this->GetStatus();
  if (status == STATUS_NO_VALID_POLYGONS || status == STATUS_OVER_BUDGET)
  {
    vtkWarningMacro(<< "no rooms generated (" << StatusName(status) << "): " << result.message
                    << "; every cell is in room -1 (outside)");
  }
  if (result.statistics.leakCells > 0 && !result.leakPoints.empty())
  {
    const glm::dvec3& at = result.leakPoints.front();
    const char* outcome = this->StopAtFirstLeak ? "stopped at the first: no rooms"
      : this->KeepRoomsWithLeaks
      ? "rooms kept (KeepRoomsWithLeaks): NOT conservative, portals through a leak may hide"
        " visible cells"
      : "no rooms: every cell in room -1 (KeepRoomsWithLeaks keeps the rooms, not conservatively)";
    vtkWarningMacro(<< result.statistics.leakCells
                    << " cell(s) where the outside leaks in through a gap that is not an opening"
                    << ", the first at (" << at.x << ", " << at.y << ", " << at.z
                    << "; see the leaks output): " << outcome);
  }
  if (result.statistics.droppedPolygons > 0)
  {
    vtkWarningMacro(<< result.statistics.droppedPolygons
                    << " degenerate or NaN/Inf polygon(s) took no part in the rooms: room -1");
  }
  return 1;
}

void vtkGenerateRooms::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RoomArrayName: " << (this->RoomArrayName ? this->RoomArrayName : "(none)")
     << "\n";
  os << indent << "OpeningEnclosure: " << this->OpeningEnclosure << "\n";
  os << indent << "PassageThickness: " << this->PassageThickness << "\n";
  os << indent << "Margin: " << this->Margin << "\n";
  os << indent << "BudgetSeconds: " << this->BudgetSeconds << "\n";
  os << indent << "StopAtFirstLeak: " << this->StopAtFirstLeak << "\n";
  os << indent << "KeepRoomsWithLeaks: " << this->KeepRoomsWithLeaks << "\n";
  os << indent << "TranslucentCellsAreSeeThrough: " << this->TranslucentCellsAreSeeThrough << "\n";
  os << indent << "Status: " << StatusName(this->GetStatus()) << "\n";
  os << indent << "NumberOfRooms: " << this->GetNumberOfRooms() << "\n";
  os << indent << "NumberOfPortals: " << this->GetNumberOfPortals() << "\n";
  os << indent << "NumberOfLeakCells: " << this->GetNumberOfLeakCells() << "\n";
}

// Rooms and portals found from a scene's geometry, as VTK data, for `scenevis portals`.
#include "GeneratedRooms.h"

#include "vtkGenerateRooms.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkNew.h>

namespace scenevis
{
namespace tool
{
GeneratedRooms GenerateRooms(vtkPolyData* model, const std::string& roomArray, double budgetSeconds,
  bool stopAtFirstLeak, bool keepRoomsWithLeaks)
{
  vtkNew<vtkGenerateRooms> filter;
  filter->SetInputData(model);
  filter->SetRoomArrayName(roomArray.c_str());
  filter->SetBudgetSeconds(budgetSeconds);
  filter->SetStopAtFirstLeak(stopAtFirstLeak);
  filter->SetKeepRoomsWithLeaks(keepRoomsWithLeaks);
  // The tool reports the status, leaks and dropped polygons itself (report and one line each).
  vtkNew<vtkCallbackCommand> quiet;
  filter->AddObserver(vtkCommand::WarningEvent, quiet);
  filter->Update();
  GeneratedRooms generated;
  generated.result = filter->GetResult();
  generated.seeThroughPolygons = static_cast<std::size_t>(filter->GetNumberOfSeeThroughPolygons());
  if (generated.result.status != portals::GenerationStatus::Ok)
  {
    return generated;
  }
  generated.rooms =
    vtkIntArray::SafeDownCast(filter->GetOutput()->GetCellData()->GetArray(roomArray.c_str()));
  generated.portals = filter->GetPortalsOutput();
  return generated;
}

} // namespace tool
} // namespace scenevis

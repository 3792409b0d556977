// What the vtkSceneVisPlanner tests share: a grid of box actors (one actor per box, world
// coordinates, a "PartId" per cell for the ID buffer), a culler that records what the cullers
// before it kept, and the check printer.
#ifndef PlannerTesting_h
#define PlannerTesting_h

#include "scenevis/Scenes.h"
#include "scenevis/testing/Scenes.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCuller.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProp.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <iostream>
#include <string>
#include <vector>

namespace plannertesting
{

inline bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}

/// A box [lo, hi] as six quads, every cell carrying @p partId in "PartId".
inline vtkSmartPointer<vtkPolyData> MakeBox(const double lo[3], const double hi[3], int partId)
{
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 8; ++k)
    points->InsertNextPoint((k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1],
      (k & 4) ? hi[2] : lo[2]);
  const vtkIdType faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
    { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> ids;
  ids->SetName("PartId");
  for (const auto& face : faces)
  {
    polys->InsertNextCell(4, face);
    ids->InsertNextValue(partId);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(ids);
  return pd;
}

/// nx x ny x nz boxes of size @p size at unit spacing from the origin, one actor each.
struct BoxGrid
{
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<vtkSmartPointer<vtkPolyData>> boxes;

  BoxGrid(vtkRenderer* renderer, int nx, int ny, int nz, double size, double opacity = 1.0)
  {
    for (int z = 0; z < nz; ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x)
        {
          const double lo[3] = { double(x), double(y), double(z) };
          const double hi[3] = { x + size, y + size, z + size };
          auto box = MakeBox(lo, hi, static_cast<int>(this->boxes.size()));
          auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
          mapper->SetInputData(box);
          mapper->ScalarVisibilityOff();
          auto actor = vtkSmartPointer<vtkActor>::New();
          actor->SetMapper(mapper);
          actor->GetProperty()->SetColor(0.2 + 0.6 * x / nx, 0.2 + 0.6 * y / ny, 0.8);
          actor->GetProperty()->SetOpacity(opacity);
          renderer->AddActor(actor);
          this->actors.push_back(actor);
          this->boxes.push_back(box);
        }
  }

  /// Index of @p prop in the grid, or -1.
  int IndexOf(vtkProp* prop) const
  {
    for (std::size_t i = 0; i < this->actors.size(); ++i)
      if (this->actors[i].Get() == prop)
        return static_cast<int>(i);
    return -1;
  }
};

/// The building @p b as an application with one actor per room has it: actors[r + 1] draws room r
/// (actors[0] the outside), each with "RoomNode" cell data (the ID buffer's room) and, with
/// @p roomField, its room as "RoomId" field data (what vtkPortalCuller reads).
inline std::vector<vtkSmartPointer<vtkActor>> BuildingActors(
  vtkRenderer* renderer, const scenevis::scenes::BuildingScene& b, bool roomField)
{
  const int rooms = static_cast<int>(b.rooms.size());
  std::vector<vtkSmartPointer<vtkActor>> actors;
  for (int r = -1; r < rooms; ++r)
  {
    auto pd = scenevis::testing::MakeRoomPolyData(b, r, rooms);
    if (roomField)
    {
      vtkNew<vtkIntArray> id;
      id->SetName("RoomId");
      id->InsertNextValue(r);
      pd->GetFieldData()->AddArray(id);
    }
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(pd);
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    actors.push_back(actor);
  }
  return actors;
}

/// Records the props the cullers before it kept; culls nothing.
class RecordingCuller : public vtkCuller
{
public:
  static RecordingCuller* New() { return new RecordingCuller; }
  vtkTypeMacro(RecordingCuller, vtkCuller);
  double Cull(vtkRenderer*, vtkProp** propList, int& listLength, int& initialized) override
  {
    this->Kept.assign(propList, propList + listLength);
    double total = 0.0;
    for (int i = 0; i < listLength; ++i)
    {
      if (!initialized)
        propList[i]->SetRenderTimeMultiplier(1.0);
      total += propList[i]->GetRenderTimeMultiplier();
    }
    initialized = 1;
    return total;
  }
  std::vector<vtkProp*> Kept;
};

} // namespace plannertesting

#endif

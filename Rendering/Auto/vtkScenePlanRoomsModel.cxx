#include "vtkScenePlanRoomsModel.h"

#include "vtkScenePlanInventory.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPoints.h"

namespace
{
/// Appends @p cells to @p out with their point ids shifted by @p base.
void AppendCells(vtkCellArray* cells, vtkIdType base, vtkCellArray* out)
{
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  std::vector<vtkIdType> shifted;
  for (cells->InitTraversal(); cells->GetNextCell(npts, pts);)
  {
    shifted.assign(pts, pts + npts);
    for (vtkIdType& id : shifted)
    {
      id += base;
    }
    out->InsertNextCell(npts, shifted.data());
  }
}
} // namespace

vtkScenePlanRoomsModel vtkScenePlanRoomsModel::Gather(vtkScenePlanInventory& inventory)
{
  vtkScenePlanRoomsModel gathered;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkCellArray> strips;
  for (const vtkScenePlanActorEntry& entry : inventory.GetEntries())
  {
    auto* pd = vtkPolyData::SafeDownCast(entry.Input);
    if (!entry.Counted || !pd || !pd->GetPoints())
    {
      continue;
    }
    gathered.Pieces.push_back(
      { entry.Actor, pd->GetNumberOfVerts(), pd->GetNumberOfLines(), pd->GetNumberOfPolys(),
        pd->GetNumberOfStrips(), polys->GetNumberOfCells(), strips->GetNumberOfCells() });
    vtkMatrix4x4* m = entry.Actor->GetMatrix();
    const vtkIdType base = points->GetNumberOfPoints();
    for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
    {
      double p[4] = { 0, 0, 0, 1 };
      pd->GetPoint(i, p);
      double q[4];
      m->MultiplyPoint(p, q);
      points->InsertNextPoint(q[0] / q[3], q[1] / q[3], q[2] / q[3]);
    }
    AppendCells(pd->GetPolys(), base, polys);
    AppendCells(pd->GetStrips(), base, strips);
  }
  gathered.Model = vtkSmartPointer<vtkPolyData>::New();
  gathered.Model->SetPoints(points);
  gathered.Model->SetPolys(polys);
  gathered.Model->SetStrips(strips);
  gathered.ModelPolys = polys->GetNumberOfCells();
  return gathered;
}

vtkScenePlanRooms::CellRooms vtkScenePlanRoomsModel::CellRoomsOf(vtkIntArray* rooms) const
{
  vtkScenePlanRooms::CellRooms cellRooms;
  const vtkIdType stripBase = this->ModelPolys;
  for (const Piece& piece : this->Pieces)
  {
    vtkNew<vtkIntArray> actorRooms;
    actorRooms->SetName("RoomId");
    actorRooms->SetNumberOfTuples(piece.Verts + piece.Lines + piece.Polys + piece.Strips);
    vtkIdType cell = 0;
    for (vtkIdType k = 0; k < piece.Verts + piece.Lines; ++k)
    {
      actorRooms->SetValue(cell++, -1);
    }
    for (vtkIdType k = 0; k < piece.Polys; ++k)
    {
      actorRooms->SetValue(cell++, rooms->GetValue(piece.FirstPoly + k));
    }
    for (vtkIdType k = 0; k < piece.Strips; ++k)
    {
      actorRooms->SetValue(cell++, rooms->GetValue(stripBase + piece.FirstStrip + k));
    }
    cellRooms.emplace_back(piece.Actor, actorRooms);
  }
  return cellRooms;
}

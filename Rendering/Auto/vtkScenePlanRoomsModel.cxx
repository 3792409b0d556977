#include "vtkScenePlanRoomsModel.h"

#include "vtkScenePlanInventory.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPoints.h"

vtkScenePlanRoomsModel vtkScenePlanRoomsModel::Gather(vtkScenePlanInventory& inventory)
{
  vtkScenePlanRoomsModel gathered;
  std::vector<vtkPolyData*> inputs;
  vtkIdType pointCount = 0;
  for (const vtkScenePlanActorEntry& entry : inventory.GetEntries())
  {
    auto* pd = vtkPolyData::SafeDownCast(entry.Input);
    if (entry.Counted && pd && pd->GetPoints())
    {
      inputs.push_back(pd);
      gathered.Pieces.push_back({ entry.Actor, pd->GetNumberOfVerts(), pd->GetNumberOfLines(),
        pd->GetNumberOfPolys(), pd->GetNumberOfStrips(), 0, 0 });
      pointCount += pd->GetNumberOfPoints();
    }
  }
  // In bulk (this runs in the render): the points written in place, the cells appended with
  // their point ids shifted.
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(pointCount);
  double* out = coordinates->GetPointer(0);
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkCellArray> strips;
  vtkIdType base = 0;
  for (std::size_t k = 0; k < inputs.size(); ++k)
  {
    vtkPolyData* pd = inputs[k];
    Piece& piece = gathered.Pieces[k];
    piece.FirstPoly = polys->GetNumberOfCells();
    piece.FirstStrip = strips->GetNumberOfCells();
    vtkMatrix4x4* m = piece.Actor->GetMatrix();
    vtkDataArray* in = pd->GetPoints()->GetData();
    const vtkIdType n = pd->GetNumberOfPoints();
    for (vtkIdType i = 0; i < n; ++i, out += 3)
    {
      double p[4] = { 0, 0, 0, 1 };
      in->GetTuple(i, p);
      double q[4];
      m->MultiplyPoint(p, q);
      out[0] = q[0] / q[3];
      out[1] = q[1] / q[3];
      out[2] = q[2] / q[3];
    }
    polys->Append(pd->GetPolys(), base);
    strips->Append(pd->GetStrips(), base);
    base += n;
  }
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  gathered.Model = vtkSmartPointer<vtkPolyData>::New();
  gathered.Model->SetPoints(points);
  gathered.Model->SetPolys(polys);
  gathered.Model->SetStrips(strips);
  gathered.ModelPolys = polys->GetNumberOfCells();
  gathered.ModelStrips = strips->GetNumberOfCells();
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

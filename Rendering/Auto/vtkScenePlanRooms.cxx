#include "vtkScenePlanRooms.h"

#include "vtkScenePlanInventory.h"

#include "vtkActor.h"
#include "vtkAutoRooms.h"
#include "vtkCellArray.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPoints.h"

#include <cstdint>

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

void vtkScenePlanRooms::Clear()
{
  this->Portals = nullptr;
  this->Rooms.clear();
  this->GeneratedFrom.clear();
  this->Reason.clear();
}

std::vector<double> vtkScenePlanRooms::Signature(vtkScenePlanInventory& inventory) const
{
  std::vector<double> signature;
  for (const vtkScenePlanActorEntry& entry : inventory.GetEntries())
  {
    if (!entry.Counted)
    {
      continue;
    }
    // Pointers below 2^53 (x86-64 user space: 2^47) and MTimes are exact as doubles.
    signature.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(entry.Actor)));
    signature.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(entry.Input)));
    signature.push_back(static_cast<double>(entry.InputTime));
    vtkMatrix4x4* m = entry.Actor->GetMatrix();
    signature.insert(signature.end(), m->GetData(), m->GetData() + 16);
  }
  return signature;
}

bool vtkScenePlanRooms::Update(
  vtkScenePlanInventory& inventory, bool newActors, double budgetSeconds)
{
  const bool inUse = this->Portals != nullptr;
  if (!newActors)
  {
    // The same actors: keep what was generated for them while they stay as they were.
    if (inUse && this->Signature(inventory) != this->GeneratedFrom)
    {
      this->Portals = nullptr;
      this->Rooms.clear();
      this->Reason = "generated rooms and portals dropped: an actor moved or changed since (they "
                     "are generated again when the actors change)";
      return true;
    }
    return false;
  }
  this->Clear();
  const vtkScenePlanFacts& facts = inventory.GetFacts();
  if (facts.parts < 2 ||
    facts.polygons > static_cast<vtkIdType>(vtkArchitecturalLook::MaximumPolygons))
  {
    // Nothing to gain (one actor is drawn whenever its room may be seen) or too big to try.
    return inUse;
  }

  // The counted actors' polygons and strips in world coordinates, as one model.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkCellArray> strips;
  struct Piece
  {
    vtkActor* Actor;
    vtkPolyData* Data;
    vtkIdType FirstPoly;
    vtkIdType FirstStrip;
  };
  std::vector<Piece> pieces;
  for (const vtkScenePlanActorEntry& entry : inventory.GetEntries())
  {
    auto* pd = vtkPolyData::SafeDownCast(entry.Input);
    if (!entry.Counted || !pd || !pd->GetPoints())
    {
      continue;
    }
    pieces.push_back({ entry.Actor, pd, polys->GetNumberOfCells(), strips->GetNumberOfCells() });
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
  vtkNew<vtkPolyData> model;
  model->SetPoints(points);
  model->SetPolys(polys);
  model->SetStrips(strips);
  const vtkAutoRooms generated = vtkAutoRooms::Generate(model, "RoomId", budgetSeconds);
  this->Generations += generated.Tried ? 1 : 0;
  this->Reason = generated.Reason;
  if (!generated.Used)
  {
    return inUse;
  }

  // Each actor's cells: vertices and lines -1, then its polygons, then its strips.
  const vtkIdType stripBase = polys->GetNumberOfCells();
  for (const Piece& piece : pieces)
  {
    vtkPolyData* pd = piece.Data;
    vtkNew<vtkIntArray> rooms;
    rooms->SetName("RoomId");
    rooms->SetNumberOfTuples(pd->GetNumberOfCells());
    vtkIdType cell = 0;
    for (const vtkIdType n : { pd->GetNumberOfVerts(), pd->GetNumberOfLines() })
    {
      for (vtkIdType k = 0; k < n; ++k)
      {
        rooms->SetValue(cell++, -1);
      }
    }
    for (vtkIdType k = 0; k < pd->GetNumberOfPolys(); ++k)
    {
      rooms->SetValue(cell++, generated.Rooms->GetValue(piece.FirstPoly + k));
    }
    for (vtkIdType k = 0; k < pd->GetNumberOfStrips(); ++k)
    {
      rooms->SetValue(cell++, generated.Rooms->GetValue(stripBase + piece.FirstStrip + k));
    }
    this->Rooms.emplace_back(piece.Actor, rooms);
  }
  this->Portals = generated.Portals;
  this->GeneratedFrom = this->Signature(inventory);
  return true;
}

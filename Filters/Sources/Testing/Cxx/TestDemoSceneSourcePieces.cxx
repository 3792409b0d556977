// Specification: piece i of n of a demo scene holds whole parts and only the points they use; the
// n pieces together are the whole scene (every polygon once, with its part, colour, room and
// points), balanced by polygons; more pieces than parts, or a piece number out of range, give
// empty pieces, not a crash.
#include "vtkDemoSceneSource.h"

#include "scenevis/testing/Expect.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <map>
#include <vector>

namespace
{
/// One polygon as a value: its part, colour, room and point coordinates, in order.
using Polygon = std::vector<double>;

std::vector<Polygon> Polygons(vtkPolyData* pd)
{
  std::vector<Polygon> out;
  auto* parts = vtkIdTypeArray::SafeDownCast(pd->GetCellData()->GetArray("PartId"));
  auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
  auto* rooms = vtkIntArray::SafeDownCast(pd->GetCellData()->GetArray("RoomId"));
  if (pd->GetNumberOfCells() > 0 && (!parts || !colors))
  {
    std::cerr << "a piece lost PartId or its colours\n";
    ++scenevis::testing::ExpectFailures();
    return out;
  }
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
  {
    pd->GetPolys()->GetCellAtId(c, npts, ids);
    Polygon p{ static_cast<double>(parts->GetValue(c)), rooms ? rooms->GetValue(c) : -2.0 };
    for (int k = 0; k < 4; ++k)
    {
      p.push_back(colors->GetTypedComponent(c, k));
    }
    for (vtkIdType k = 0; k < npts; ++k)
    {
      const double* x = pd->GetPoint(ids[k]);
      p.insert(p.end(), x, x + 3);
    }
    out.push_back(p);
  }
  return out;
}

void CheckPieces(vtkDemoSceneSource* source, const char* scene, int pieces)
{
  source->UpdatePiece(0, 1, 0);
  std::vector<Polygon> whole = Polygons(source->GetOutput());
  const vtkIdType parts =
    source->GetOutput()->GetFieldData()->GetAbstractArray("PartNames")->GetNumberOfTuples();
  std::vector<Polygon> together;
  std::map<double, int> pieceOfPart;
  std::size_t largest = 0;
  for (int piece = 0; piece < pieces; ++piece)
  {
    source->UpdatePiece(piece, pieces, 0);
    vtkPolyData* pd = source->GetOutput();
    // Only the points its polygons use.
    std::vector<char> used(static_cast<std::size_t>(pd->GetNumberOfPoints()), 0);
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
    {
      pd->GetPolys()->GetCellAtId(c, npts, ids);
      for (vtkIdType k = 0; k < npts; ++k)
      {
        used[static_cast<std::size_t>(ids[k])] = 1;
      }
    }
    SCENEVIS_EXPECT(std::all_of(used.begin(), used.end(), [](char u) { return u == 1; }));
    // The part names and colours stay whole on every piece.
    SCENEVIS_EXPECT(pd->GetFieldData()->GetAbstractArray("PartNames") &&
      pd->GetFieldData()->GetAbstractArray("PartNames")->GetNumberOfTuples() == parts);
    const std::vector<Polygon> mine = Polygons(pd);
    for (const Polygon& p : mine)
    {
      // Whole parts: a part is on one piece only.
      const auto at = pieceOfPart.emplace(p[0], piece).first;
      SCENEVIS_EXPECT(at->second == piece);
    }
    largest = std::max(largest, mine.size());
    together.insert(together.end(), mine.begin(), mine.end());
  }
  std::sort(whole.begin(), whole.end());
  std::sort(together.begin(), together.end());
  SCENEVIS_EXPECT(together == whole);
  std::cout << scene << ", " << pieces << " pieces: " << whole.size() << " polygons, " << parts
            << " parts, largest piece " << largest << "\n";
  if (parts >= 8 * pieces)
  {
    // Balanced by polygons: no piece holds much more than its share.
    SCENEVIS_EXPECT(
      static_cast<double>(largest) <= 1.5 * static_cast<double>(whole.size()) / pieces);
  }
}
} // namespace

int TestDemoSceneSourcePieces(int, char*[])
{
  vtkNew<vtkDemoSceneSource> source;
  source->SetTriangleCount(4000);
  source->SetPartCount(60);
  source->SetFloors(2);
  for (const char* scene : { "spheres", "cad", "building", "triangles" })
  {
    SCENEVIS_EXPECT(source->SetSceneByName(scene));
    for (const int pieces : { 1, 2, 3, 7 })
    {
      CheckPieces(source, scene, pieces);
    }
  }
  // More pieces than parts: the two triangles' scene has two parts; most pieces are empty.
  SCENEVIS_EXPECT(source->SetSceneByName("triangles"));
  source->UpdatePiece(4, 5, 0);
  SCENEVIS_EXPECT(source->GetOutput()->GetNumberOfCells() <= 1);
  // A piece number out of range is empty.
  source->UpdatePiece(5, 5, 0);
  SCENEVIS_EXPECT(source->GetOutput()->GetNumberOfCells() == 0);
  return scenevis::testing::ExpectFailures() == 0 ? 0 : 1;
}

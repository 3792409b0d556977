// Specification of SplitByKeys (Tools/SplitParts.h): a flattened mesh split into its parts keeps
// every cell exactly once, with its points, point data and cell data, in ascending key order.
#include "../SplitParts.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <array>
#include <map>
#include <random>
#include <tuple>
#include <vector>

using scenevis::tool::SplitByKeys;

namespace
{
using Corner = std::array<double, 4>;                      // x, y, z and the point's scalar
using Polygon = std::tuple<int, int, std::vector<Corner>>; // (room, part) -> its corners

/// A random polygon soup over a shared pool of points (parts share points, as flattened meshes
/// often do), with RoomId and PartId cell arrays, a point scalar and a cell scalar.
vtkSmartPointer<vtkPolyData> RandomScene(std::mt19937& random, int cells, int points)
{
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::uniform_int_distribution<int> point(0, points - 1);
  std::uniform_int_distribution<int> size(3, 8);
  std::uniform_int_distribution<int> key(-3, 6);
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> weight;
  weight->SetName("Weight");
  for (int p = 0; p < points; ++p)
  {
    pts->InsertNextPoint(coordinate(random), coordinate(random), coordinate(random));
    weight->InsertNextValue(static_cast<float>(p));
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> room;
  vtkNew<vtkIntArray> part;
  vtkNew<vtkIntArray> serial;
  room->SetName("RoomId");
  part->SetName("PartId");
  serial->SetName("Serial");
  int run = 0;
  int currentPart = 0;
  for (int c = 0; c < cells; ++c)
  {
    if (run-- <= 0) // runs of cells in one part, as exporters write them, and stray cells
    {
      run = std::uniform_int_distribution<int>(0, 5)(random);
      currentPart = key(random);
    }
    const int n = size(random);
    polys->InsertNextCell(n);
    for (int k = 0; k < n; ++k)
      polys->InsertCellPoint(point(random));
    room->InsertNextValue(currentPart % 2);
    part->InsertNextValue(currentPart);
    serial->InsertNextValue(c);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  pd->GetPointData()->SetScalars(weight);
  pd->GetCellData()->AddArray(room);
  pd->GetCellData()->AddArray(part);
  pd->GetCellData()->AddArray(serial);
  return pd;
}

/// Every polygon of @p pd with its keys and its corners (coordinates and point scalar), by the
/// value of its Serial cell array.
std::map<int, Polygon> Polygons(vtkPolyData* pd)
{
  std::map<int, Polygon> result;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
  {
    pd->GetCellPoints(c, ids);
    std::vector<Corner> corners;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double x[3];
      pd->GetPoint(ids->GetId(k), x);
      corners.push_back(
        { x[0], x[1], x[2], pd->GetPointData()->GetScalars()->GetTuple1(ids->GetId(k)) });
    }
    const auto serial = static_cast<int>(pd->GetCellData()->GetArray("Serial")->GetTuple1(c));
    result[serial] = { static_cast<int>(pd->GetCellData()->GetArray("RoomId")->GetTuple1(c)),
      static_cast<int>(pd->GetCellData()->GetArray("PartId")->GetTuple1(c)), corners };
  }
  return result;
}
} // namespace

TEST(SplitParts, EveryCellLandsOnceInItsPartWithItsPointsAndData)
{
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial)
  {
    vtkSmartPointer<vtkPolyData> scene = RandomScene(random, 400, 150);
    const std::map<int, Polygon> expected = Polygons(scene);
    const auto parts = SplitByKeys(scene, { "RoomId", "PartId" });
    ASSERT_GT(parts.size(), 1u);
    std::map<int, Polygon> seen;
    std::pair<int, int> previousKey(-1000, -1000);
    for (const auto& part : parts)
    {
      const std::map<int, Polygon> polygons = Polygons(part);
      ASSERT_FALSE(polygons.empty());
      const std::pair<int, int> key(
        std::get<0>(polygons.begin()->second), std::get<1>(polygons.begin()->second));
      EXPECT_LT(previousKey, key) << "parts come in ascending (RoomId, PartId) order";
      previousKey = key;
      for (const auto& [serial, polygon] : polygons)
      {
        EXPECT_EQ(key, std::make_pair(std::get<0>(polygon), std::get<1>(polygon)))
          << "one key per part";
        EXPECT_TRUE(seen.emplace(serial, polygon).second) << "cell " << serial << " twice";
      }
      // Compact: every point of the part is used by one of its cells.
      std::vector<bool> used(static_cast<std::size_t>(part->GetNumberOfPoints()), false);
      vtkNew<vtkIdList> ids;
      for (vtkIdType c = 0; c < part->GetNumberOfCells(); ++c)
      {
        part->GetCellPoints(c, ids);
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
          used[static_cast<std::size_t>(ids->GetId(k))] = true;
      }
      EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
      EXPECT_NE(part->GetPointData()->GetScalars(), nullptr) << "attributes keep their role";
      EXPECT_FALSE(part->GetPolys()->IsStorage64Bit()) << "a part's cells take 32-bit ids";
    }
    EXPECT_EQ(seen, expected);
  }
}

TEST(SplitParts, OnePartOrNoKeyGivesTheInputItself)
{
  std::mt19937 random(3);
  vtkSmartPointer<vtkPolyData> scene = RandomScene(random, 50, 40);
  EXPECT_EQ(SplitByKeys(scene, { "NoSuchArray" }).front(), scene);
  vtkDataArray* part = scene->GetCellData()->GetArray("PartId");
  for (vtkIdType c = 0; c < part->GetNumberOfTuples(); ++c)
    part->SetTuple1(c, 4);
  const auto parts = SplitByKeys(scene, { "PartId" });
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts.front(), scene);
  vtkNew<vtkPolyData> empty;
  EXPECT_EQ(SplitByKeys(empty, { "PartId" }).size(), 1u);
}

TEST(SplitParts, ReleasingTheInputGivesTheSamePartsAndLeavesItWithoutPolygons)
{
  std::mt19937 random(11);
  for (int trial = 0; trial < 5; ++trial)
  {
    vtkSmartPointer<vtkPolyData> scene = RandomScene(random, 300, 120);
    const auto kept = SplitByKeys(scene, { "RoomId", "PartId" });
    const vtkIdType points = scene->GetNumberOfPoints();
    const auto released = SplitByKeys(scene, { "RoomId", "PartId" }, true);
    ASSERT_EQ(kept.size(), released.size());
    for (std::size_t i = 0; i < kept.size(); ++i)
    {
      EXPECT_EQ(Polygons(kept[i]), Polygons(released[i])) << "part " << i;
      EXPECT_EQ(kept[i]->GetNumberOfPoints(), released[i]->GetNumberOfPoints()) << "part " << i;
    }
    EXPECT_EQ(scene->GetNumberOfPolys(), 0) << "the input's polygons went back";
    EXPECT_EQ(scene->GetNumberOfPoints(), points) << "its points stay";
  }
  // No split, nothing released: the caller draws the input itself.
  vtkSmartPointer<vtkPolyData> one = RandomScene(random, 50, 40);
  const vtkIdType polygons = one->GetNumberOfPolys();
  EXPECT_EQ(SplitByKeys(one, { "NoSuchArray" }, true).front(), one);
  EXPECT_EQ(one->GetNumberOfPolys(), polygons);
}

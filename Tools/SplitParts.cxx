#include "SplitParts.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace scenevis
{
namespace tool
{
namespace
{

struct KeyHash
{
  std::size_t operator()(const std::vector<long long>& key) const
  {
    std::size_t h = 0;
    for (const long long v : key)
      h = h * 0x9E3779B97F4A7C15ull + std::hash<long long>()(v);
    return h;
  }
};

/// 0, 1, ..., n - 1.
vtkSmartPointer<vtkIdList> Iota(vtkIdType n)
{
  auto ids = vtkSmartPointer<vtkIdList>::New();
  ids->SetNumberOfIds(n);
  std::iota(ids->GetPointer(0), ids->GetPointer(0) + n, vtkIdType{ 0 });
  return ids;
}

/// The part of cells @p cells of @p pd: its points compacted through @p stamp / @p local (input
/// point -> the part that last used it / its id there), which @p part marks as its own.
vtkSmartPointer<vtkPolyData> MakePart(vtkPolyData* pd, vtkIdList* cells, std::int32_t part,
  std::vector<std::int32_t>& stamp, std::vector<vtkIdType>& local)
{
  vtkCellArray* polys = pd->GetPolys();
  const vtkIdType cellCount = cells->GetNumberOfIds();
  vtkIdType connectivitySize = 0;
  for (vtkIdType i = 0; i < cellCount; ++i)
    connectivitySize += polys->GetCellSize(cells->GetId(i));

  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(cellCount + 1);
  connectivity->SetNumberOfValues(connectivitySize);
  vtkNew<vtkIdList> sourcePoints;
  sourcePoints->Allocate(connectivitySize);
  vtkIdType at = 0;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  for (vtkIdType i = 0; i < cellCount; ++i)
  {
    offsets->SetValue(i, at);
    polys->GetCellAtId(cells->GetId(i), npts, pts);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      const auto p = static_cast<std::size_t>(pts[k]);
      if (stamp[p] != part)
      {
        stamp[p] = part;
        local[p] = sourcePoints->GetNumberOfIds();
        sourcePoints->InsertNextId(pts[k]);
      }
      connectivity->SetValue(at++, local[p]);
    }
  }
  offsets->SetValue(cellCount, at);

  const vtkIdType pointCount = sourcePoints->GetNumberOfIds();
  vtkNew<vtkPoints> points;
  points->SetDataType(pd->GetPoints()->GetDataType());
  points->SetNumberOfPoints(pointCount);
  pd->GetPoints()->GetData()->GetTuples(sourcePoints, points->GetData());
  vtkNew<vtkCellArray> partPolys;
  partPolys->SetData(offsets, connectivity);

  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->SetPoints(points);
  result->SetPolys(partPolys);
  result->GetPointData()->CopyAllocate(pd->GetPointData(), pointCount);
  result->GetPointData()->CopyData(pd->GetPointData(), sourcePoints, Iota(pointCount));
  result->GetCellData()->CopyAllocate(pd->GetCellData(), cellCount);
  result->GetCellData()->CopyData(pd->GetCellData(), cells, Iota(cellCount));
  return result;
}

} // namespace

std::vector<vtkSmartPointer<vtkPolyData>> SplitByKeys(
  vtkPolyData* pd, const std::vector<std::string>& keys)
{
  std::vector<vtkDataArray*> keyArrays;
  for (const std::string& key : keys)
  {
    if (vtkDataArray* array = pd->GetCellData()->GetArray(key.c_str()))
      keyArrays.push_back(array);
  }
  const vtkIdType cells = pd->GetNumberOfCells();
  if (keyArrays.empty() || cells == 0 || cells != pd->GetNumberOfPolys())
    return { pd };

  // 1. Each cell's part, numbered in order of first appearance.
  std::unordered_map<std::vector<long long>, std::int32_t, KeyHash> partOfKey;
  std::vector<std::vector<long long>> keyOfPart;
  std::vector<std::int32_t> partOfCell(static_cast<std::size_t>(cells));
  std::vector<long long> key(keyArrays.size());
  std::int32_t previous = -1;
  for (vtkIdType c = 0; c < cells; ++c)
  {
    bool same = previous >= 0;
    for (std::size_t k = 0; k < keyArrays.size(); ++k)
    {
      const auto value = static_cast<long long>(keyArrays[k]->GetTuple1(c));
      same = same && value == key[k];
      key[k] = value;
    }
    if (!same)
    {
      auto found = partOfKey.find(key);
      if (found == partOfKey.end())
      {
        found = partOfKey.emplace(key, static_cast<std::int32_t>(keyOfPart.size())).first;
        keyOfPart.push_back(key);
      }
      previous = found->second;
    }
    partOfCell[static_cast<std::size_t>(c)] = previous;
  }
  const std::size_t partCount = keyOfPart.size();
  if (partCount < 2)
    return { pd };

  // 2. Parts in ascending key order; each part's cells by a counting sort.
  std::vector<std::int32_t> byKey(partCount);
  std::iota(byKey.begin(), byKey.end(), 0);
  std::sort(byKey.begin(), byKey.end(),
    [&](std::int32_t a, std::int32_t b) { return keyOfPart[a] < keyOfPart[b]; });
  std::vector<vtkIdType> cellCount(partCount, 0);
  for (const std::int32_t part : partOfCell)
    ++cellCount[static_cast<std::size_t>(part)];
  std::vector<vtkSmartPointer<vtkIdList>> cellsOfPart(partCount);
  for (std::size_t part = 0; part < partCount; ++part)
  {
    cellsOfPart[part] = vtkSmartPointer<vtkIdList>::New();
    cellsOfPart[part]->Allocate(cellCount[part]);
  }
  for (vtkIdType c = 0; c < cells; ++c)
    cellsOfPart[static_cast<std::size_t>(partOfCell[static_cast<std::size_t>(c)])]->InsertNextId(c);
  std::vector<std::int32_t>().swap(partOfCell);

  // 3. One pass per part over its own cells.
  const auto pointCount = static_cast<std::size_t>(pd->GetNumberOfPoints());
  std::vector<std::int32_t> stamp(pointCount, -1);
  std::vector<vtkIdType> local(pointCount, 0);
  std::vector<vtkSmartPointer<vtkPolyData>> result;
  result.reserve(partCount);
  for (const std::int32_t part : byKey)
  {
    auto& partCells = cellsOfPart[static_cast<std::size_t>(part)];
    result.push_back(MakePart(pd, partCells, part, stamp, local));
    partCells = nullptr; // its memory goes back before the next part is made
  }
  return result;
}

} // namespace tool
} // namespace scenevis

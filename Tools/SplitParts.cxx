#include "SplitParts.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cstdint>
#include <limits>
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

/// The cells @p cells of @p polys as a cell array of @p Array (vtkTypeInt32Array when the part's
/// connectivity fits 32 bits: half the memory of VTK's default 64-bit ids), their points
/// renumbered through @p stamp / @p local (input point -> the part that last used it / its id
/// there), which @p part marks as its own; @p sourcePoints receives the input ids of the part's
/// points in their new order.
template <typename Array>
vtkSmartPointer<vtkCellArray> CompactCells(vtkCellArray* polys, vtkIdList* cells,
  vtkIdType connectivitySize, std::int32_t part, std::vector<std::int32_t>& stamp,
  std::vector<std::uint32_t>& local, vtkIdList* sourcePoints)
{
  const vtkIdType cellCount = cells->GetNumberOfIds();
  vtkNew<Array> offsets;
  vtkNew<Array> connectivity;
  offsets->SetNumberOfValues(cellCount + 1);
  connectivity->SetNumberOfValues(connectivitySize);
  sourcePoints->Allocate(connectivitySize);
  vtkIdType at = 0;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  using Value = typename Array::ValueType;
  for (vtkIdType i = 0; i < cellCount; ++i)
  {
    offsets->SetValue(i, static_cast<Value>(at));
    polys->GetCellAtId(cells->GetId(i), npts, pts);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      const auto p = static_cast<std::size_t>(pts[k]);
      if (stamp[p] != part)
      {
        stamp[p] = part;
        local[p] = static_cast<std::uint32_t>(sourcePoints->GetNumberOfIds());
        sourcePoints->InsertNextId(pts[k]);
      }
      connectivity->SetValue(at++, static_cast<Value>(local[p]));
    }
  }
  offsets->SetValue(cellCount, static_cast<Value>(at));
  auto result = vtkSmartPointer<vtkCellArray>::New();
  result->SetData(offsets, connectivity);
  return result;
}

/// The cells @p cells of @p pd as a cell array of 32-bit ids when they fit (see CompactCells).
vtkSmartPointer<vtkCellArray> PartCells(vtkPolyData* pd, vtkIdList* cells, std::int32_t part,
  std::vector<std::int32_t>& stamp, std::vector<std::uint32_t>& local, vtkIdList* sourcePoints)
{
  vtkCellArray* polys = pd->GetPolys();
  const vtkIdType cellCount = cells->GetNumberOfIds();
  vtkIdType connectivitySize = 0;
  for (vtkIdType i = 0; i < cellCount; ++i)
    connectivitySize += polys->GetCellSize(cells->GetId(i));
  auto result = connectivitySize <= std::numeric_limits<std::int32_t>::max()
    ? CompactCells<vtkTypeInt32Array>(
        polys, cells, connectivitySize, part, stamp, local, sourcePoints)
    : CompactCells<vtkTypeInt64Array>(
        polys, cells, connectivitySize, part, stamp, local, sourcePoints);
  sourcePoints->Squeeze(); // kept until the points are copied: its exact size only
  return result;
}

/// The points @p sourcePoints of @p pd with their point data, and the cell data of its cells
/// @p cells, into @p part (whose polygons are already set).
void CopyPartData(
  vtkPolyData* pd, vtkIdList* cells, vtkIdList* sourcePoints, vtkPolyData* part)
{
  const vtkIdType pointCount = sourcePoints->GetNumberOfIds();
  vtkNew<vtkPoints> points;
  points->SetDataType(pd->GetPoints()->GetDataType());
  points->SetNumberOfPoints(pointCount);
  pd->GetPoints()->GetData()->GetTuples(sourcePoints, points->GetData());
  part->SetPoints(points);
  part->GetPointData()->CopyAllocate(pd->GetPointData(), pointCount);
  part->GetPointData()->CopyData(pd->GetPointData(), sourcePoints, Iota(pointCount));
  const vtkIdType cellCount = cells->GetNumberOfIds();
  part->GetCellData()->CopyAllocate(pd->GetCellData(), cellCount);
  part->GetCellData()->CopyData(pd->GetCellData(), cells, Iota(cellCount));
}

} // namespace

std::vector<vtkSmartPointer<vtkPolyData>> SplitByKeys(
  vtkPolyData* pd, const std::vector<std::string>& keys, bool releaseInputPolygons)
{
  std::vector<vtkDataArray*> keyArrays;
  for (const std::string& key : keys)
  {
    if (vtkDataArray* array = pd->GetCellData()->GetArray(key.c_str()))
      keyArrays.push_back(array);
  }
  const vtkIdType cells = pd->GetNumberOfCells();
  if (keyArrays.empty() || cells == 0 || cells != pd->GetNumberOfPolys() ||
    cells >= std::numeric_limits<std::uint32_t>::max() ||
    pd->GetNumberOfPoints() >= std::numeric_limits<std::uint32_t>::max())
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
  // cellsOfPart[firstCell[p], firstCell[p + 1]): the cells of part p, in input order (32-bit:
  // 4 bytes per cell while the input and the parts made so far are both in memory).
  std::vector<std::size_t> firstCell(partCount + 1, 0);
  for (const std::int32_t part : partOfCell)
    ++firstCell[static_cast<std::size_t>(part) + 1];
  std::partial_sum(firstCell.begin(), firstCell.end(), firstCell.begin());
  std::vector<std::uint32_t> cellsOfPart(static_cast<std::size_t>(cells));
  {
    std::vector<std::size_t> next(firstCell.begin(), firstCell.end() - 1);
    for (vtkIdType c = 0; c < cells; ++c)
      cellsOfPart[next[static_cast<std::size_t>(partOfCell[static_cast<std::size_t>(c)])]++] =
        static_cast<std::uint32_t>(c);
  }
  std::vector<std::int32_t>().swap(partOfCell);

  auto cellsOf = [&](std::int32_t part, vtkIdList* ids)
  {
    const auto p = static_cast<std::size_t>(part);
    ids->SetNumberOfIds(static_cast<vtkIdType>(firstCell[p + 1] - firstCell[p]));
    std::copy(cellsOfPart.begin() + static_cast<std::ptrdiff_t>(firstCell[p]),
      cellsOfPart.begin() + static_cast<std::ptrdiff_t>(firstCell[p + 1]), ids->GetPointer(0));
  };

  // 3. One pass per part over its own cells: its polygons, and which input points it uses.
  const auto pointCount = static_cast<std::size_t>(pd->GetNumberOfPoints());
  std::vector<std::int32_t> stamp(pointCount, -1);
  std::vector<std::uint32_t> local(pointCount, 0);
  std::vector<vtkSmartPointer<vtkPolyData>> result;
  std::vector<vtkSmartPointer<vtkIdList>> sourcePoints;
  result.reserve(partCount);
  sourcePoints.reserve(partCount);
  vtkNew<vtkIdList> partCells;
  for (const std::int32_t part : byKey)
  {
    cellsOf(part, partCells);
    sourcePoints.push_back(vtkSmartPointer<vtkIdList>::New());
    result.push_back(vtkSmartPointer<vtkPolyData>::New());
    result.back()->SetPolys(PartCells(pd, partCells, part, stamp, local, sourcePoints.back()));
  }
  std::vector<std::int32_t>().swap(stamp);
  std::vector<std::uint32_t>().swap(local);
  if (releaseInputPolygons)
    pd->SetPolys(vtkSmartPointer<vtkCellArray>::New()); // the largest array of a big input

  // 4. Each part's points, point data and cell data.
  for (std::size_t i = 0; i < partCount; ++i)
  {
    cellsOf(byKey[i], partCells);
    CopyPartData(pd, partCells, sourcePoints[i], result[i]);
    sourcePoints[i] = nullptr;
  }
  return result;
}

} // namespace tool
} // namespace scenevis

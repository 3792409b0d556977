#include "vtkBSPSortUtilities.h"

#include "vtkAbstractArray.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include "scenevis/ConvexTriangulation.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace
{
bool IsFinite(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

/// The fragments as polygons in `order` (nullptr: as they are), with ArrayT offsets/connectivity.
template <typename ArrayT>
vtkSmartPointer<vtkCellArray> EmitPolygonsAs(const scenevis::bsp::Fragment* fragments,
  const std::uint32_t* fragmentVertices, const std::uint32_t* order, std::size_t count)
{
  using ValueT = typename ArrayT::ValueType;
  auto fragmentAt = [&](std::size_t r) -> const scenevis::bsp::Fragment& {
    return fragments[order ? order[r] : r];
  };
  vtkNew<ArrayT> offsets;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(count + 1));
  ValueT* offsetPtr = offsets->GetPointer(0);
  // Prefix sum of the fragment sizes in output order (serial: it is a dependency chain).
  offsetPtr[0] = 0;
  for (std::size_t r = 0; r < count; ++r)
  {
    offsetPtr[r + 1] = offsetPtr[r] + static_cast<ValueT>(fragmentAt(r).count);
  }
  vtkNew<ArrayT> connectivity;
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(offsetPtr[count]));
  ValueT* connPtr = connectivity->GetPointer(0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType r = begin; r < end; ++r)
    {
      const scenevis::bsp::Fragment& fragment = fragmentAt(static_cast<std::size_t>(r));
      const std::uint32_t* vertices = fragmentVertices + fragment.first;
      std::copy(vertices, vertices + fragment.count, connPtr + offsetPtr[r]);
    }
  });
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  polys->SetData(offsets, connectivity);
  return polys;
}
} // namespace

//------------------------------------------------------------------------------
void vtkBSPSortUtilities::AppendPolygons(vtkPolyData* input, vtkMatrix4x4* matrix,
  scenevis::PolygonMesh& mesh, std::vector<vtkIdType>& cellOf)
{
  const auto base = static_cast<std::uint32_t>(mesh.points.size());
  const vtkIdType numPoints = input->GetNumberOfPoints();
  mesh.points.reserve(mesh.points.size() + static_cast<std::size_t>(numPoints));
  for (vtkIdType i = 0; i < numPoints; ++i)
  {
    double p[4] = { 0.0, 0.0, 0.0, 1.0 };
    input->GetPoint(i, p);
    if (matrix)
    {
      matrix->MultiplyPoint(p, p);
      if (p[3] != 0.0 && p[3] != 1.0)
      {
        p[0] /= p[3];
        p[1] /= p[3];
        p[2] /= p[3];
      }
    }
    mesh.points.emplace_back(p[0], p[1], p[2]);
  }
  // Cell ids follow VTK's order: verts, lines, polys, strips.
  vtkIdType cellId = input->GetNumberOfVerts() + input->GetNumberOfLines();
  std::vector<std::uint32_t> ids;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = input->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts); ++cellId)
  {
    ids.resize(static_cast<std::size_t>(npts));
    for (vtkIdType k = 0; k < npts; ++k)
    {
      ids[static_cast<std::size_t>(k)] = base + static_cast<std::uint32_t>(pts[k]);
    }
    mesh.addPolygon(ids.data(), ids.size());
    cellOf.push_back(cellId);
  }
  vtkCellArray* strips = input->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, pts); ++cellId)
  {
    for (vtkIdType k = 0; k + 2 < npts; ++k)
    {
      // Every other triangle of a strip is wound the other way: swap so all face the same way.
      const std::uint32_t a = base + static_cast<std::uint32_t>(pts[k]);
      const std::uint32_t b = base + static_cast<std::uint32_t>(pts[k + 1]);
      const std::uint32_t c = base + static_cast<std::uint32_t>(pts[k + 2]);
      if (k % 2 == 0)
      {
        mesh.addPolygon({ a, b, c });
      }
      else
      {
        mesh.addPolygon({ b, a, c });
      }
      cellOf.push_back(cellId);
    }
  }
}

//------------------------------------------------------------------------------
void vtkBSPSortUtilities::InterpolateSplitPoints(vtkPolyData* input,
  const scenevis::bsp::SplitPoint* splits, std::size_t count, vtkPoints* points,
  vtkPointData* pointData)
{
  const vtkIdType numIn = input->GetNumberOfPoints();
  const vtkIdType numOut = numIn + static_cast<vtkIdType>(count);
  points->SetDataType(input->GetPoints() ? input->GetPoints()->GetDataType() : VTK_FLOAT);
  points->SetNumberOfPoints(numOut);
  for (vtkIdType i = 0; i < numIn; ++i)
  {
    points->SetPoint(i, input->GetPoint(i));
  }
  // Positions go through the same interpolation as every other per-point array.
  pointData->DeepCopy(input->GetPointData());
  for (int a = -1; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = a < 0 ? points->GetData() : pointData->GetAbstractArray(a);
    array->Resize(numOut);
    array->SetNumberOfTuples(numOut);
    for (std::size_t s = 0; s < count; ++s)
    {
      array->InterpolateTuple(
        numIn + static_cast<vtkIdType>(s), splits[s].a, array, splits[s].b, array, splits[s].t);
    }
  }
  if (vtkDataArray* normals = pointData->GetNormals())
  {
    for (vtkIdType i = numIn; i < numOut; ++i)
    {
      double n[3];
      normals->GetTuple(i, n);
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (length > 0.0)
      {
        normals->SetTuple3(i, n[0] / length, n[1] / length, n[2] / length);
      }
    }
  }
}

//------------------------------------------------------------------------------
void vtkBSPSortUtilities::TriangulateFragments(vtkPolyData* input,
  const scenevis::bsp::SplitPoint* splits, std::size_t splitCount, const std::uint32_t* offsets,
  std::size_t fragmentCount, const std::uint32_t* vertices, std::vector<std::uint32_t>& corners)
{
  const vtkIdType numIn = input->GetNumberOfPoints();
  const auto inputPoint = [input](vtkIdType id)
  {
    double p[3];
    input->GetPoint(id, p);
    return glm::dvec3(p[0], p[1], p[2]);
  };
  // Split points in double, as the builder makes them (lo + (hi - lo) t, ends made first).
  std::vector<glm::dvec3> split(splitCount);
  const auto position = [&](std::uint32_t id)
  {
    return static_cast<vtkIdType>(id) < numIn ? inputPoint(static_cast<vtkIdType>(id))
                                              : split[id - static_cast<std::uint32_t>(numIn)];
  };
  for (std::size_t s = 0; s < splitCount; ++s)
  {
    const glm::dvec3 lo = position(splits[s].a), hi = position(splits[s].b);
    split[s] = lo + (hi - lo) * splits[s].t;
  }
  std::vector<glm::dvec3> polygon;
  std::vector<std::uint32_t> local;
  for (std::size_t f = 0; f < fragmentCount; ++f)
  {
    const std::uint32_t first = offsets[f], n = offsets[f + 1] - first;
    local.clear();
    if (n > 3)
    {
      polygon.resize(n);
      for (std::uint32_t k = 0; k < n; ++k)
      {
        polygon[k] = position(vertices[first + k]);
      }
      scenevis::triangulateConvex(polygon.data(), n, local);
      for (const std::uint32_t k : local)
      {
        corners.push_back(first + k);
      }
    }
    else if (n == 3)
    {
      corners.insert(corners.end(), { first, first + 1, first + 2 });
    }
  }
}

//------------------------------------------------------------------------------
bool vtkBSPSortUtilities::ViewFromCamera(
  vtkCamera* camera, vtkMatrix4x4* propMatrix, scenevis::View& view)
{
  double position[3], focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  double eye[4] = { position[0], position[1], position[2], 1.0 };
  double direction[4] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2],
    0.0 };
  if (propMatrix)
  {
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(propMatrix, inverse);
    inverse->MultiplyPoint(eye, eye);
    inverse->MultiplyPoint(direction, direction);
    if (eye[3] != 0.0)
    {
      for (int i = 0; i < 3; ++i)
      {
        eye[i] /= eye[3];
      }
    }
  }
  const double length = std::sqrt(
    direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  const bool parallel = camera->GetParallelProjection() != 0;
  if (!IsFinite(eye) || !IsFinite(direction) || (parallel && !(length > 0.0)))
  {
    return false;
  }
  view = parallel ? scenevis::View::parallel({ direction[0], direction[1], direction[2] })
                  : scenevis::View::perspective({ eye[0], eye[1], eye[2] });
  return true;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkCellArray> vtkBSPSortUtilities::EmitPolygons(
  const scenevis::bsp::Fragment* fragments, const std::uint32_t* fragmentVertices,
  std::size_t vertexCount, std::size_t pointCount, const std::uint32_t* order, std::size_t count)
{
  const bool fits32 = pointCount < 0x7fffffffu && vertexCount < 0x7fffffffu;
  return fits32 ? EmitPolygonsAs<vtkTypeInt32Array>(fragments, fragmentVertices, order, count)
                : EmitPolygonsAs<vtkTypeInt64Array>(fragments, fragmentVertices, order, count);
}

//------------------------------------------------------------------------------
void vtkBSPSortUtilities::PermuteTuples(vtkAbstractArray* source, const std::uint32_t* order,
  std::size_t count, vtkAbstractArray* target, vtkIdType offset)
{
  const int components = source->GetNumberOfComponents();
  auto* sourceData = vtkDataArray::SafeDownCast(source);
  auto* targetData = vtkDataArray::SafeDownCast(target);
  if (sourceData && targetData && sourceData->HasStandardMemoryLayout() &&
    targetData->HasStandardMemoryLayout() &&
    sourceData->GetDataType() == targetData->GetDataType())
  {
    const int size = sourceData->GetDataTypeSize() * components;
    const auto* from = static_cast<const unsigned char*>(sourceData->GetVoidPointer(0));
    auto* to = static_cast<unsigned char*>(targetData->GetVoidPointer(0)) + offset * size;
    vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType r = begin; r < end; ++r)
      {
        std::memcpy(to + r * size,
          from + static_cast<std::size_t>(order[static_cast<std::size_t>(r)]) * size,
          static_cast<std::size_t>(size));
      }
    });
    return;
  }
  for (std::size_t r = 0; r < count; ++r)
  {
    target->SetTuple(offset + static_cast<vtkIdType>(r), order[r], source);
  }
}

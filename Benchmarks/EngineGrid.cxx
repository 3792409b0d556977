#include "EngineGrid.h"

#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkPropCollection.h>

#include <algorithm>
#include <chrono>
#include <iostream>

namespace scenevis
{
namespace bench
{
namespace
{
double SecondsSince(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// Bounds of the unplaced engine (all parts).
void EngineBounds(const std::vector<EnginePart>& parts, double b[6])
{
  for (int k = 0; k < 3; ++k)
  {
    b[2 * k] = 1e300;
    b[2 * k + 1] = -1e300;
  }
  for (const EnginePart& p : parts)
  {
    const double* pb = p.data->GetBounds();
    for (int k = 0; k < 3; ++k)
    {
      b[2 * k] = std::min(b[2 * k], pb[2 * k]);
      b[2 * k + 1] = std::max(b[2 * k + 1], pb[2 * k + 1]);
    }
  }
}
} // namespace

int LoadEngine(EngineModel& model)
{
  const std::string path = scenevis::testing::DataFile("engine-glb");
  if (path.empty())
  {
    std::cout << "SKIPPED: engine-glb is not in the data cache "
              << scenevis::testing::DataDirectory() << " (run scripts/fetch-data.sh)\n";
    return scenevis::testing::kSkipReturnCode;
  }
  auto start = std::chrono::steady_clock::now();
  std::string error;
  vtkSmartPointer<vtkPolyData> mesh = scenevis::testing::LoadModel(path, &error);
  if (!mesh)
  {
    std::cerr << "cannot read " << path << ": " << error << "\n";
    return 1;
  }
  model.readSeconds = SecondsSince(start);
  start = std::chrono::steady_clock::now();
  model.parts = SplitParts(mesh);
  model.splitSeconds = SecondsSince(start);
  return 0;
}

std::vector<EnginePart> SplitParts(vtkPolyData* model)
{
  vtkDataArray* partIds = model->GetCellData()->GetArray("PartId");
  vtkDataArray* colours = model->GetCellData()->GetArray("Colors");
  const vtkIdType cells = model->GetNumberOfCells();
  vtkIdType parts = 1;
  for (vtkIdType c = 0; partIds && c < cells; ++c)
  {
    parts = std::max<vtkIdType>(parts, static_cast<vtkIdType>(partIds->GetComponent(c, 0)) + 1);
  }
  std::vector<EnginePart> out(static_cast<std::size_t>(parts));
  std::vector<vtkSmartPointer<vtkPoints>> points(out.size());
  std::vector<vtkSmartPointer<vtkCellArray>> polys(out.size());
  // The model's own normals travel with its points (the flattened file keeps them, as exporters
  // write them: a reader need not compute them).
  vtkDataArray* modelNormals = model->GetPointData()->GetNormals();
  std::vector<vtkSmartPointer<vtkFloatArray>> normals(out.size());
  std::vector<std::vector<vtkIdType>> pointMap(out.size());
  std::vector<char> coloured(out.size(), 0);
  for (std::size_t p = 0; p < out.size(); ++p)
  {
    points[p] = vtkSmartPointer<vtkPoints>::New();
    points[p]->SetDataTypeToDouble();
    polys[p] = vtkSmartPointer<vtkCellArray>::New();
    normals[p] = vtkSmartPointer<vtkFloatArray>::New();
    normals[p]->SetName("Normals");
    normals[p]->SetNumberOfComponents(3);
  }
  vtkNew<vtkIdList> ids;
  std::vector<vtkIdType> cell;
  for (vtkIdType c = 0; c < cells; ++c)
  {
    if (model->GetCellType(c) != VTK_TRIANGLE && model->GetCellType(c) != VTK_POLYGON &&
      model->GetCellType(c) != VTK_QUAD)
    {
      continue;
    }
    const auto p = static_cast<std::size_t>(partIds ? partIds->GetComponent(c, 0) : 0);
    model->GetCellPoints(c, ids);
    cell.clear();
    std::vector<vtkIdType>& map = pointMap[p];
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      const vtkIdType id = ids->GetId(k);
      if (static_cast<std::size_t>(id) >= map.size())
      {
        map.resize(static_cast<std::size_t>(id) + 1, -1);
      }
      if (map[static_cast<std::size_t>(id)] < 0)
      {
        map[static_cast<std::size_t>(id)] = points[p]->InsertNextPoint(model->GetPoint(id));
        if (modelNormals)
          normals[p]->InsertNextTuple(modelNormals->GetTuple(id));
      }
      cell.push_back(map[static_cast<std::size_t>(id)]);
    }
    polys[p]->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
    if (colours && !coloured[p])
    {
      for (int k = 0; k < 3; ++k)
      {
        out[p].colour[k] = colours->GetComponent(c, k) / 255.0;
      }
      coloured[p] = 1;
    }
  }
  std::vector<EnginePart> kept;
  for (std::size_t p = 0; p < out.size(); ++p)
  {
    if (polys[p]->GetNumberOfCells() > 0)
    {
      out[p].data = vtkSmartPointer<vtkPolyData>::New();
      out[p].data->SetPoints(points[p]);
      out[p].data->SetPolys(polys[p]);
      if (modelNormals)
        out[p].data->GetPointData()->SetNormals(normals[p]);
      kept.push_back(out[p]);
    }
  }
  return kept;
}

void EnginePitch(const std::vector<EnginePart>& parts, double pitch[3])
{
  double b[6];
  EngineBounds(parts, b);
  for (int k = 0; k < 3; ++k)
  {
    pitch[k] = 1.15 * (b[2 * k + 1] - b[2 * k]);
  }
}

void EngineGridBounds(const std::vector<EnginePart>& parts, int n, double bounds[6])
{
  double pitch[3];
  EnginePitch(parts, pitch);
  EngineBounds(parts, bounds);
  bounds[1] += (n - 1) * pitch[0];
  bounds[5] += (n - 1) * pitch[2];
}

void BuildEngineGrid(EngineGrid& g, const std::vector<EnginePart>& parts, int n)
{
  std::vector<vtkSmartPointer<vtkPolyDataMapper>> mappers;
  vtkIdType engineTriangles = 0;
  for (const EnginePart& p : parts)
  {
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputData(p.data);
    mapper->ScalarVisibilityOff();
    mappers.push_back(mapper);
    engineTriangles += p.data->GetNumberOfCells(); // polygons; the engine has triangles only
  }
  EnginePitch(parts, g.pitch);
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      for (std::size_t p = 0; p < parts.size(); ++p)
      {
        auto actor = vtkSmartPointer<vtkActor>::New();
        actor->SetMapper(mappers[p]);
        actor->SetPosition(i * g.pitch[0], 0.0, j * g.pitch[2]);
        auto look = vtkSmartPointer<vtkProperty>::New();
        look->SetColor(parts[p].colour[0], parts[p].colour[1], parts[p].colour[2]);
        actor->SetProperty(look);
        const std::size_t id = g.actors.size() + 1;
        auto idLook = vtkSmartPointer<vtkProperty>::New();
        idLook->SetColor(((id >> 16) & 255) / 255.0, ((id >> 8) & 255) / 255.0, (id & 255) / 255.0);
        idLook->LightingOff();
        idLook->SetAmbient(1.0);
        idLook->SetDiffuse(0.0);
        idLook->SetSpecular(0.0);
        // AddActor() would scan all props first (O(n^2): 88 s for 46,000 actors).
        g.renderer->GetViewProps()->AddItem(actor);
        actor->AddConsumer(g.renderer);
        g.actors.push_back(actor);
        g.looks.push_back(look);
        g.idLooks.push_back(idLook);
      }
    }
  }
  g.triangles = engineTriangles * n * n;
  g.renderer->ComputeVisiblePropBounds(g.bounds);
}

vtkSmartPointer<vtkPolyData> FlattenEngineGrid(const std::vector<EnginePart>& parts, int n)
{
  double pitch[3];
  EnginePitch(parts, pitch);
  vtkIdType points = 0, cells = 0;
  for (const EnginePart& p : parts)
  {
    points += p.data->GetNumberOfPoints();
    cells += p.data->GetNumberOfCells();
  }
  vtkNew<vtkPoints> allPoints;
  allPoints->SetDataTypeToFloat();
  allPoints->Allocate(points * n * n);
  vtkNew<vtkCellArray> polys;
  polys->AllocateEstimate(cells * n * n, 3);
  vtkNew<vtkIdTypeArray> partId;
  partId->SetName("PartId");
  partId->Allocate(cells * n * n);
  const bool withNormals = !parts.empty() && parts.front().data->GetPointData()->GetNormals();
  vtkNew<vtkFloatArray> allNormals;
  allNormals->SetName("Normals");
  allNormals->SetNumberOfComponents(3);
  allNormals->Allocate(3 * points * n * n);
  vtkIdType actor = 0;
  std::vector<vtkIdType> shifted;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      for (const EnginePart& p : parts)
      {
        const vtkIdType base = allPoints->GetNumberOfPoints();
        for (vtkIdType q = 0; q < p.data->GetNumberOfPoints(); ++q)
        {
          double x[3];
          p.data->GetPoint(q, x);
          allPoints->InsertNextPoint(x[0] + i * pitch[0], x[1], x[2] + j * pitch[2]);
          if (withNormals)
            allNormals->InsertNextTuple(p.data->GetPointData()->GetNormals()->GetTuple(q));
        }
        vtkIdType npts = 0;
        const vtkIdType* ids = nullptr;
        vtkCellArray* cellArray = p.data->GetPolys();
        for (cellArray->InitTraversal(); cellArray->GetNextCell(npts, ids);)
        {
          shifted.assign(ids, ids + npts);
          for (vtkIdType& id : shifted)
          {
            id += base;
          }
          polys->InsertNextCell(npts, shifted.data());
          partId->InsertNextValue(actor);
        }
        ++actor;
      }
    }
  }
  auto flat = vtkSmartPointer<vtkPolyData>::New();
  flat->SetPoints(allPoints);
  flat->SetPolys(polys);
  flat->GetCellData()->AddArray(partId);
  if (withNormals)
    flat->GetPointData()->SetNormals(allNormals);
  return flat;
}

} // namespace bench
} // namespace scenevis

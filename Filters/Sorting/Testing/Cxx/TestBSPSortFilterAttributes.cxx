// Specification: split fragments carry every point and cell attribute of their input, verts and
// lines pass through first and unchanged, triangle strips are sorted as their triangles.
#include "vtkBSPSortFilter.h"

#include "scenevis/testing/Expect.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

namespace
{
// Attribute fields that are linear in position, so interpolation along an edge is exact.
double Temperature(const double p[3])
{
  return 1.0 + 2.0 * p[0] - 3.0 * p[1] + 0.5 * p[2];
}

double PolysArea(vtkPolyData* pd)
{
  double area = 0.0;
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    double normal[3];
    area += vtkPolygon::ComputeArea(pd->GetPoints(), n, ids, normal);
  }
  return area;
}

// A horizontal quad (z = 0) pierced by a vertical one (x = 0.25): one of them must be split.
vtkSmartPointer<vtkPolyData> CrossingQuadsWithAttributes()
{
  vtkNew<vtkPoints> points;
  const double p[][3] = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 },
    { 0.25, -0.5, -1 }, { 0.25, 0.5, -1 }, { 0.25, 0.5, 1 }, { 0.25, -0.5, 1 },
    { 3, 3, 3 }, { 4, 4, 4 } };
  for (const auto& q : p)
  {
    points->InsertNextPoint(q);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  vtkNew<vtkCellArray> verts;
  verts->InsertNextCell({ 8 });
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell({ 8, 9 });
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell({ 0, 1, 2, 3 });
  polys->InsertNextCell({ 4, 5, 6, 7 });
  pd->SetVerts(verts);
  pd->SetLines(lines);
  pd->SetPolys(polys);

  vtkNew<vtkDoubleArray> temperature;
  temperature->SetName("Temperature");
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double x[3];
    points->GetPoint(i, x);
    temperature->InsertNextValue(Temperature(x));
    // Deliberately non-parallel normals along split edges, so interpolation shortens them.
    normals->InsertNextTuple3(i < 4 ? 0.0 : 1.0, 0.0, i < 4 ? 1.0 : (x[2] > 0 ? 1.0 : -1.0));
    tcoords->InsertNextTuple2(x[1], x[2]);
  }
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    normals->SetTuple3(i, n[0] / len, n[1] / len, n[2] / len);
  }
  pd->GetPointData()->AddArray(temperature);
  pd->GetPointData()->SetNormals(normals);
  pd->GetPointData()->SetTCoords(tcoords);

  vtkNew<vtkIntArray> part;
  part->SetName("Part");
  for (int v : { 100, 101, 10, 20 })
  {
    part->InsertNextValue(v);
  }
  pd->GetCellData()->AddArray(part);
  return pd;
}
} // namespace

int TestBSPSortFilterAttributes(int, char*[])
{
  vtkSmartPointer<vtkPolyData> input = CrossingQuadsWithAttributes();
  vtkNew<vtkCamera> camera;
  camera->SetPosition(2, -3, 5);
  camera->SetFocalPoint(0, 0, 0);

  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputData(input);
  sorter->SetCamera(camera);
  sorter->Update();
  vtkPolyData* out = sorter->GetOutput();

  // Topology: exactly one split, i.e. three fragments and two new points.
  SCENEVIS_EXPECT(sorter->GetNumberOfSplits() == 1);
  SCENEVIS_EXPECT(out->GetNumberOfPolys() == 3);
  SCENEVIS_EXPECT(out->GetNumberOfPoints() == input->GetNumberOfPoints() + 2);
  SCENEVIS_EXPECT(std::abs(PolysArea(out) - PolysArea(input)) < 1e-9);

  // Verts and lines first and unchanged.
  SCENEVIS_EXPECT(out->GetNumberOfVerts() == 1 && out->GetNumberOfLines() == 1);
  vtkIntArray* part = vtkIntArray::SafeDownCast(out->GetCellData()->GetArray("Part"));
  vtkIdTypeArray* original = vtkIdTypeArray::SafeDownCast(
    out->GetCellData()->GetArray(vtkBSPSortFilter::OriginalCellIdArrayName()));
  vtkIdTypeArray* rank = vtkIdTypeArray::SafeDownCast(
    out->GetCellData()->GetArray(vtkBSPSortFilter::SortRankArrayName()));
  SCENEVIS_EXPECT(part && original && rank);
  if (!part || !original || !rank)
  {
    return EXIT_FAILURE;
  }
  SCENEVIS_EXPECT(part->GetValue(0) == 100 && part->GetValue(1) == 101);
  SCENEVIS_EXPECT(rank->GetValue(0) == -1 && rank->GetValue(1) == -1);
  // Every fragment carries its source cell's data; ranks count up in output order.
  for (vtkIdType c = 2; c < out->GetNumberOfCells(); ++c)
  {
    const vtkIdType source = original->GetValue(c);
    SCENEVIS_EXPECT(source == 2 || source == 3);
    SCENEVIS_EXPECT(part->GetValue(c) == (source == 2 ? 10 : 20));
    SCENEVIS_EXPECT(rank->GetValue(c) == c - 2);
  }

  // Point data: linear fields interpolated exactly, normals unit length, on every point.
  vtkDataArray* temperature = out->GetPointData()->GetArray("Temperature");
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  vtkDataArray* tcoords = out->GetPointData()->GetTCoords();
  SCENEVIS_EXPECT(temperature && normals && tcoords);
  if (!temperature || !normals || !tcoords)
  {
    return EXIT_FAILURE;
  }
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3], n[3], t[2];
    out->GetPoint(i, x);
    normals->GetTuple(i, n);
    tcoords->GetTuple(i, t);
    SCENEVIS_EXPECT(std::abs(temperature->GetTuple1(i) - Temperature(x)) < 1e-5);
    SCENEVIS_EXPECT(std::abs(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0) < 1e-5);
    SCENEVIS_EXPECT(std::abs(t[0] - x[1]) < 1e-5 && std::abs(t[1] - x[2]) < 1e-5);
  }

  // Triangle strips: a 4-point strip is sorted as its two triangles, both tagged with the strip.
  vtkNew<vtkPolyData> strip;
  vtkNew<vtkPoints> stripPoints;
  stripPoints->InsertNextPoint(0, 0, 0);
  stripPoints->InsertNextPoint(1, 0, 0);
  stripPoints->InsertNextPoint(0, 1, 0.2);
  stripPoints->InsertNextPoint(1, 1, 0.2);
  strip->SetPoints(stripPoints);
  vtkNew<vtkCellArray> strips;
  strips->InsertNextCell({ 0, 1, 2, 3 });
  strip->SetStrips(strips);
  sorter->SetInputData(strip);
  sorter->Update();
  out = sorter->GetOutput();
  SCENEVIS_EXPECT(out->GetNumberOfPolys() == 2);
  SCENEVIS_EXPECT(out->GetNumberOfStrips() == 0);
  original = vtkIdTypeArray::SafeDownCast(
    out->GetCellData()->GetArray(vtkBSPSortFilter::OriginalCellIdArrayName()));
  SCENEVIS_EXPECT(original && original->GetValue(0) == 0 && original->GetValue(1) == 0);
  SCENEVIS_EXPECT(std::abs(PolysArea(out) - 1.0198039027185568) < 1e-6);

  return scenevis::testing::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

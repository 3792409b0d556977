// Specification: the bad-input catalogue of the sorting filters (issue 8). Every case runs on
// vtkBSPSortFilter (without and with ordered leaves) AND vtkPainterSortFilter (same interface,
// same contract):
// - no camera, or a camera with a NaN/Inf position: an error, the input passes through unsorted;
// - a camera with a zero view angle, or whose eye is its focal point: a correct order (the order
//   of a perspective camera depends on its eye only);
// - empty input: a warning and an empty output;
// - NaN/Inf points and polygons with fewer than three distinct points or zero area: removed,
//   counted (GetNumberOfRemovedPolygons) and reported in a warning; the rest sorted;
// - non-planar and self-intersecting polygons: triangulated, ordered correctly, area kept;
// - mixed verts, lines, polys and strips: verts and lines pass through first and unchanged (rank
//   -1), strips are sorted as their triangles;
// - 1e7 coordinate offsets with 1e-3 features, and extents of 1e-12 and 1e12: no complaint, a
//   correct order, and the fragments cover exactly the input's area.
// "Correct order" is judged by the brute-force oracle (scenevis/OrderOracle.h) on the output
// polygons in output order, on scenes that need splits (cyclic quads, interpenetrating
// triangles), and every such check also requires the oracle to have found constrained pairs, so
// it cannot pass vacuously.
#include "vtkBSPSortFilter.h"
#include "vtkPainterSortFilter.h"

#include "scenevis/testing/Expect.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDemoSceneSource.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include "scenevis/OrderOracle.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// vtkBSPSortFilter with ordered leaves of up to 64 polygons: the same contract on bad input.
class vtkBSPSortFilterWithLeaves : public vtkBSPSortFilter
{
public:
  static vtkBSPSortFilterWithLeaves* New()
  {
    auto* filter = new vtkBSPSortFilterWithLeaves;
    filter->InitializeObjectBase();
    filter->SetOrderedLeafSize(64);
    return filter;
  }
  vtkTypeMacro(vtkBSPSortFilterWithLeaves, vtkBSPSortFilter);
};

/// One filter run with its errors and warnings captured.
template <class Filter>
struct Sorted
{
  vtkNew<Filter> filter;
  vtkNew<vtkTest::ErrorObserver> observer;

  Sorted(vtkPolyData* input, vtkCamera* camera)
  {
    this->filter->AddObserver(vtkCommand::ErrorEvent, this->observer);
    this->filter->AddObserver(vtkCommand::WarningEvent, this->observer);
    this->filter->SetInputData(input);
    this->filter->SetCamera(camera);
    this->filter->Update();
  }
  vtkPolyData* Output() { return this->filter->GetOutput(); }
  bool Error() { return this->observer->GetError() != 0; }
  bool Warning() { return this->observer->GetWarning() != 0; }
  bool Quiet() { return !this->Error() && !this->Warning(); }
};

vtkSmartPointer<vtkPolyData> DemoScene(int scene)
{
  vtkNew<vtkDemoSceneSource> source;
  source->SetScene(scene);
  source->Update();
  vtkSmartPointer<vtkPolyData> pd = source->GetOutput();
  return pd;
}

/// A copy of @p input with every point p replaced by offset + scale * p (double precision).
vtkSmartPointer<vtkPolyData> Scaled(vtkPolyData* input, double scale, const double offset[3])
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(input);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(input->GetNumberOfPoints());
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    points->SetPoint(
      i, offset[0] + scale * p[0], offset[1] + scale * p[1], offset[2] + scale * p[2]);
  }
  out->SetPoints(points);
  return out;
}

/// The polygons of @p pd in cell order, as the oracle takes them.
std::vector<scenevis::oracle::Polygon> PolygonsOf(vtkPolyData* pd)
{
  std::vector<scenevis::oracle::Polygon> polygons;
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    scenevis::oracle::Polygon polygon;
    for (vtkIdType k = 0; k < n; ++k)
    {
      double p[3];
      pd->GetPoint(ids[k], p);
      polygon.emplace_back(p[0], p[1], p[2]);
    }
    polygons.push_back(polygon);
  }
  return polygons;
}

/// Area of a planar polygon (half the length of its Newell normal), in long double.
long double Area(const scenevis::oracle::Polygon& polygon)
{
  if (polygon.empty())
  {
    return 0;
  }
  const glm::dvec3 origin = polygon.front(); // relative coordinates: exact far from the origin
  long double n[3] = { 0, 0, 0 };
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::dvec3 a = polygon[i] - origin;
    const glm::dvec3 b = polygon[(i + 1) % polygon.size()] - origin;
    n[0] += static_cast<long double>(a.y) * b.z - static_cast<long double>(a.z) * b.y;
    n[1] += static_cast<long double>(a.z) * b.x - static_cast<long double>(a.x) * b.z;
    n[2] += static_cast<long double>(a.x) * b.y - static_cast<long double>(a.y) * b.x;
  }
  return 0.5L * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

long double TotalArea(vtkPolyData* pd)
{
  long double sum = 0;
  for (const auto& polygon : PolygonsOf(pd))
  {
    sum += Area(polygon);
  }
  return sum;
}

/// Whether the output's polygons, in output order, are a correct back-to-front order for @p eye
/// (and the oracle had pairs to judge).
bool OrderIsCorrect(vtkPolyData* output, const double eye[3])
{
  const auto polygons = PolygonsOf(output);
  std::vector<std::uint32_t> order(polygons.size());
  for (std::uint32_t i = 0; i < order.size(); ++i)
  {
    order[i] = i;
  }
  const scenevis::oracle::OracleReport report = scenevis::oracle::checkOrder(
    polygons, order, scenevis::View::perspective({ eye[0], eye[1], eye[2] }));
  if (!report.ok() || report.constrainedPairs == 0)
  {
    std::cerr << "[" << scenevis::testing::ExpectContext()
              << "] oracle: " << report.violations.size() << " violations, "
              << report.constrainedPairs << " constrained pairs\n";
  }
  return report.ok() && report.constrainedPairs > 0;
}

/// A camera looking at the centre of @p pd from above (+z) and a little aside.
void LookFromAbove(vtkPolyData* pd, vtkCamera* camera)
{
  double b[6];
  pd->GetBounds(b);
  const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double d = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  camera->SetFocalPoint(c);
  camera->SetPosition(c[0] + 0.1 * d, c[1] + 0.05 * d, c[2] + 2.0 * d);
}

/// Points 0..4 with a bad value in point 3, and polygons around it.
vtkSmartPointer<vtkPolyData> TrianglesWithBadPoint(double badValue)
{
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(badValue, 0, 1);
  points->InsertNextPoint(0, 0, 1);
  pd->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell({ 0, 1, 2 });    // fine
  polys->InsertNextCell({ 0, 3, 4 });    // touches the bad point
  polys->InsertNextCell({ 0, 0, 1 });    // fewer than three distinct points
  polys->InsertNextCell({ 0, 1, 1, 0 }); // zero area
  pd->SetPolys(polys);
  return pd;
}

/// A large quad at z = 0 under: a non-planar quad, a concave "dart", and a self-intersecting
/// (bow-tie) pentagon, all above it; plus a symmetric bow-tie whose signed area is zero.
vtkSmartPointer<vtkPolyData> AwkwardPolygons()
{
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const double p[][3] = {
    { -2, -2, 0 }, { 2, -2, 0 }, { 2, 2, 0 }, { -2, 2, 0 },           // 0-3 floor
    { -1, -1, 0.5 }, { 1, -1, 1.5 }, { 1, 1, 0.5 }, { -1, 1, 1.5 },   // 4-7 non-planar
    { -1.5, 0, 1 }, { 1.5, -1, 1 }, { 0, 0, 1 }, { 1.5, 1, 1 },       // 8-11 concave dart
    { -1, -1.5, 2 }, { 1, 1.5, 2 }, { 1.2, -1.5, 2 }, { -1, 1.5, 2 }, // 12-15 bow-tie
    { -1.3, 0, 2 },                                                   // 16
    { -1, -1, 3 }, { 1, 1, 3 }, { 1, -1, 3 }, { -1, 1, 3 }            // 17-20 zero bow-tie
  };
  for (const auto& q : p)
  {
    points->InsertNextPoint(q);
  }
  pd->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell({ 0, 1, 2, 3 });
  polys->InsertNextCell({ 4, 5, 6, 7 });
  polys->InsertNextCell({ 8, 9, 10, 11 });
  polys->InsertNextCell({ 12, 13, 14, 15, 16 });
  polys->InsertNextCell({ 17, 18, 19, 20 });
  pd->SetPolys(polys);
  return pd;
}

/// Two verts, a polyline, the cyclic quads as polys, and a strip of 4 triangles crossing them.
vtkSmartPointer<vtkPolyData> MixedCells()
{
  const double noOffset[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkPolyData> pd =
    Scaled(DemoScene(vtkDemoSceneSource::SCENE_CYCLIC_QUADS), 1.0, noOffset);
  pd->GetCellData()->Initialize(); // cell data of the quads only would not fit the new cells
  vtkPoints* points = pd->GetPoints();
  double b[6];
  pd->GetBounds(b);
  const double zMid = 0.5 * (b[4] + b[5]);
  const vtkIdType first = points->GetNumberOfPoints();
  for (int i = 0; i < 6; ++i)
  {
    // A strip zig-zagging across the quads at their mid height, tilted so it crosses them.
    const double x = b[0] + (b[1] - b[0]) * (i / 2) / 2.0;
    const double y = (i % 2) ? b[3] : b[2];
    points->InsertNextPoint(x, y, zMid + 0.3 * (b[5] - b[4]) * ((i % 2) ? 1 : -1));
  }
  vtkNew<vtkCellArray> strips;
  strips->InsertNextCell({ first, first + 1, first + 2, first + 3, first + 4, first + 5 });
  pd->SetStrips(strips);
  vtkNew<vtkCellArray> verts;
  verts->InsertNextCell({ 0 });
  verts->InsertNextCell({ 1 });
  pd->SetVerts(verts);
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell({ 0, 1, 2 });
  pd->SetLines(lines);
  return pd;
}

template <class Filter>
void RunCatalogue(const char* filterName)
{
  auto caseName = [&](const std::string& what)
  { scenevis::testing::ExpectContext() = std::string(filterName) + ": " + what; };
  vtkSmartPointer<vtkPolyData> quads = DemoScene(vtkDemoSceneSource::SCENE_CYCLIC_QUADS);
  vtkSmartPointer<vtkPolyData> triangles =
    DemoScene(vtkDemoSceneSource::SCENE_INTERPENETRATING_TRIANGLES);
  vtkNew<vtkCamera> camera;
  LookFromAbove(quads, camera);

  caseName("no camera");
  {
    Sorted<Filter> run(quads, nullptr);
    SCENEVIS_EXPECT(run.Error());
    SCENEVIS_EXPECT(run.observer->GetErrorMessage().find("No camera") != std::string::npos);
    SCENEVIS_EXPECT(run.Output()->GetNumberOfPolys() == quads->GetNumberOfPolys());
  }
  for (double bad : { kNaN, kInf, -kInf })
  {
    caseName("camera position " + std::to_string(bad));
    vtkNew<vtkCamera> broken;
    broken->SetPosition(bad, 0, 5);
    Sorted<Filter> run(quads, broken);
    SCENEVIS_EXPECT(run.Error());
    SCENEVIS_EXPECT(run.observer->GetErrorMessage().find("non-finite") != std::string::npos);
    SCENEVIS_EXPECT(run.Output()->GetNumberOfPolys() == quads->GetNumberOfPolys());
  }
  caseName("zero view angle");
  {
    vtkNew<vtkCamera> narrow;
    narrow->DeepCopy(camera);
    narrow->SetViewAngle(0.0); // vtkCamera clamps it to 1e-8 degrees: it never reaches 0
    SCENEVIS_EXPECT(narrow->GetViewAngle() < 1e-6);
    Sorted<Filter> run(quads, narrow);
    SCENEVIS_EXPECT(run.Quiet());
    SCENEVIS_EXPECT(OrderIsCorrect(run.Output(), narrow->GetPosition()));
  }
  caseName("eye == focal point");
  {
    vtkNew<vtkCamera> collapsed;
    collapsed->DeepCopy(camera);
    // vtkCamera keeps its direction of projection and puts the focal point 1e-20 along it; the
    // order of a perspective camera depends on the eye alone, which is still well defined.
    collapsed->SetFocalPoint(collapsed->GetPosition());
    SCENEVIS_EXPECT(collapsed->GetDistance() < 1e-10);
    Sorted<Filter> run(quads, collapsed);
    SCENEVIS_EXPECT(run.Quiet());
    SCENEVIS_EXPECT(OrderIsCorrect(run.Output(), collapsed->GetPosition()));
  }
  caseName("empty input");
  {
    vtkNew<vtkPolyData> empty;
    Sorted<Filter> run(empty, camera);
    SCENEVIS_EXPECT(run.Warning() && !run.Error());
    SCENEVIS_EXPECT(run.Output()->GetNumberOfCells() == 0);
  }
  for (double bad : { kNaN, kInf })
  {
    caseName("bad point " + std::to_string(bad) + " and degenerate polygons");
    Sorted<Filter> run(TrianglesWithBadPoint(bad), camera);
    SCENEVIS_EXPECT(run.Warning() && !run.Error());
    SCENEVIS_EXPECT(run.observer->GetWarningMessage().find("Removed") != std::string::npos);
    SCENEVIS_EXPECT(run.filter->GetNumberOfRemovedPolygons() == 3);
    SCENEVIS_EXPECT(run.Output()->GetNumberOfPolys() == 1);
  }
  caseName("non-planar, concave and self-intersecting polygons");
  {
    vtkSmartPointer<vtkPolyData> awkward = AwkwardPolygons();
    vtkNew<vtkCamera> above;
    above->SetPosition(0.3, 0.2, 8);
    Sorted<Filter> run(awkward, above);
    SCENEVIS_EXPECT(!run.Error());
    // The symmetric bow-tie has zero signed (Newell) area: removed and counted, with a warning.
    SCENEVIS_EXPECT(run.filter->GetNumberOfRemovedPolygons() == 1);
    SCENEVIS_EXPECT(run.Warning());
    SCENEVIS_EXPECT(run.Output()->GetNumberOfPolys() >= 5);
    SCENEVIS_EXPECT(OrderIsCorrect(run.Output(), above->GetPosition()));
    // Every fragment comes from a kept input cell.
    auto* original = vtkIdTypeArray::SafeDownCast(
      run.Output()->GetCellData()->GetArray(vtkVisibilityOrderFilter::OriginalCellIdArrayName()));
    SCENEVIS_EXPECT(original && original->GetRange()[0] >= 0 && original->GetRange()[1] <= 3);
    // The floor and the dart are planar: their fragments keep their area exactly.
    long double floorArea = 0, dartArea = 0;
    const auto polygons = PolygonsOf(run.Output());
    for (std::size_t c = 0; original && c < polygons.size(); ++c)
    {
      const vtkIdType from = original->GetValue(static_cast<vtkIdType>(c));
      if (from == 0)
      {
        floorArea += Area(polygons[c]);
      }
      else if (from == 2)
      {
        dartArea += Area(polygons[c]);
      }
    }
    SCENEVIS_EXPECT(std::fabs(static_cast<double>(floorArea) - 16.0) < 1e-12);
    // Dart (-1.5,0) (1.5,-1) (0,0) (1.5,1): two triangles of area 0.75 each.
    SCENEVIS_EXPECT(std::fabs(static_cast<double>(dartArea) - 1.5) < 1e-12);
  }
  caseName("mixed verts, lines, polys and strips");
  {
    vtkSmartPointer<vtkPolyData> mixed = MixedCells();
    Sorted<Filter> run(mixed, camera);
    SCENEVIS_EXPECT(run.Quiet());
    vtkPolyData* out = run.Output();
    SCENEVIS_EXPECT(out->GetNumberOfVerts() == 2);
    SCENEVIS_EXPECT(out->GetNumberOfLines() == 1);
    SCENEVIS_EXPECT(out->GetNumberOfStrips() == 0);
    SCENEVIS_EXPECT(out->GetNumberOfPolys() >= 3 + 4);
    auto* original = vtkIdTypeArray::SafeDownCast(
      out->GetCellData()->GetArray(vtkVisibilityOrderFilter::OriginalCellIdArrayName()));
    auto* rank = vtkIdTypeArray::SafeDownCast(
      out->GetCellData()->GetArray(vtkVisibilityOrderFilter::SortRankArrayName()));
    SCENEVIS_EXPECT(original && rank);
    if (original && rank)
    {
      // Verts and lines first, unchanged: input cells 0, 1 (verts) and 2 (line), rank -1.
      for (vtkIdType c = 0; c < 3; ++c)
      {
        SCENEVIS_EXPECT(original->GetValue(c) == c && rank->GetValue(c) == -1);
      }
      // Then every fragment of the quads (cells 3-5) and of the strip (cell 6), ranks 0, 1, ...
      bool fromStrip = false;
      for (vtkIdType c = 3; c < out->GetNumberOfCells(); ++c)
      {
        SCENEVIS_EXPECT(original->GetValue(c) >= 3 && original->GetValue(c) <= 6);
        SCENEVIS_EXPECT(rank->GetValue(c) == c - 3);
        fromStrip = fromStrip || original->GetValue(c) == 6;
      }
      SCENEVIS_EXPECT(fromStrip);
    }
    // The fragments cover the quads and the strip's 4 triangles exactly.
    long double inputArea = 0;
    for (const auto& quad : PolygonsOf(mixed))
    {
      inputArea += Area(quad);
    }
    vtkCellArray* strips = mixed->GetStrips();
    const vtkIdType* strip = nullptr;
    vtkIdType n = 0;
    strips->GetCellAtId(0, n, strip);
    for (vtkIdType t = 0; t + 2 < n; ++t)
    {
      scenevis::oracle::Polygon triangle;
      for (vtkIdType k = 0; k < 3; ++k)
      {
        double p[3];
        mixed->GetPoint(strip[t + k], p);
        triangle.emplace_back(p[0], p[1], p[2]);
      }
      inputArea += Area(triangle);
    }
    SCENEVIS_EXPECT(
      std::fabs(static_cast<double>((TotalArea(out) - inputArea) / inputArea)) < 1e-12);
    SCENEVIS_EXPECT(OrderIsCorrect(out, camera->GetPosition()));
  }
  // Scale and offset: the hard scenes at 1e-3 placed at 1e7, and at extents 1e-12 and 1e12.
  struct Placement
  {
    const char* name;
    double scale;
    double offset[3];
  };
  const Placement placements[] = { { "1e-3 features at 1e7", 1e-3, { 1e7, -1e7, 1e7 } },
    { "extent 1e-12", 1e-12, { 3e-12, 0, 0 } }, { "extent 1e12", 1e12, { 3e12, 0, 0 } } };
  for (const Placement& placement : placements)
  {
    for (vtkPolyData* scene : { quads.Get(), triangles.Get() })
    {
      caseName(std::string(placement.name) + (scene == quads ? ", cyclic quads" : ", triangles"));
      vtkSmartPointer<vtkPolyData> placed = Scaled(scene, placement.scale, placement.offset);
      vtkNew<vtkCamera> view;
      LookFromAbove(placed, view);
      Sorted<Filter> run(placed, view);
      SCENEVIS_EXPECT(run.Quiet());
      SCENEVIS_EXPECT(run.filter->GetNumberOfRemovedPolygons() == 0);
      SCENEVIS_EXPECT(
        run.Output()->GetNumberOfPolys() > scene->GetNumberOfPolys()); // splits needed
      SCENEVIS_EXPECT(OrderIsCorrect(run.Output(), view->GetPosition()));
      const long double in = TotalArea(placed);
      const long double out = TotalArea(run.Output());
      SCENEVIS_EXPECT(std::fabs(static_cast<double>((out - in) / in)) < 1e-6);
    }
  }
  // A sphere at 1e12, as a closed surface (the original case of this test).
  caseName("sphere at 1e12");
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(1e12);
    sphere->SetCenter(3e12, 0, 0);
    sphere->Update();
    vtkNew<vtkCamera> far;
    far->SetPosition(3e12, 0, 5e12);
    far->SetFocalPoint(3e12, 0, 0);
    Sorted<Filter> run(sphere->GetOutput(), far);
    SCENEVIS_EXPECT(run.Quiet());
    SCENEVIS_EXPECT(run.Output()->GetNumberOfPolys() >= sphere->GetOutput()->GetNumberOfPolys());
  }
}
} // namespace

int TestBSPSortFilterBadInput(int, char*[])
{
  RunCatalogue<vtkBSPSortFilter>("vtkBSPSortFilter");
  RunCatalogue<vtkBSPSortFilterWithLeaves>("vtkBSPSortFilter, ordered leaves of 64");
  RunCatalogue<vtkPainterSortFilter>("vtkPainterSortFilter");
  return scenevis::testing::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

#include "scenevis/testing/Scenes.h"

#include "scenevis/testing/RenderWindow.h"

#include "scenevis/Scenes.h"

#include <vtkActor.h>
#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <cmath>

namespace scenevis
{
namespace testing
{

vtkSmartPointer<vtkRenderer> MakeSphereGridRenderer(const SphereGridOptions& options)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(0, 0, 0);
  const int n = options.count;
  const double denominator = n > 1 ? double(n - 1) : 1.0;
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        vtkNew<vtkSphereSource> sphere;
        sphere->SetCenter(i * options.spacing, j * options.spacing, k * options.spacing);
        sphere->SetRadius(options.radius);
        sphere->SetThetaResolution(options.resolution);
        sphere->SetPhiResolution(options.resolution);
        vtkNew<vtkPolyDataMapper> mapper;
        mapper->SetInputConnection(sphere->GetOutputPort());
        mapper->ScalarVisibilityOff();
        vtkNew<vtkActor> actor;
        actor->SetMapper(mapper);
        actor->GetProperty()->SetColor(
          0.2 + 0.8 * i / denominator, 0.2 + 0.8 * j / denominator, 0.2 + 0.8 * k / denominator);
        actor->GetProperty()->SetOpacity(options.opacity);
        renderer->AddActor(actor);
      }
    }
  }
  switch (options.translucency)
  {
    case Translucency::DepthPeeling:
      renderer->SetUseDepthPeeling(1);
      renderer->SetMaximumNumberOfPeels(options.maximumPeels);
      renderer->SetOcclusionRatio(0.0);
      break;
    case Translucency::OrderedAlpha:
      EnableOrderedAlphaBlending(renderer);
      break;
    case Translucency::VtkDefault:
      break;
  }
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->GetActiveCamera()->Elevation(20);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCamera();
  return renderer;
}

vtkSmartPointer<vtkPolyData> MakeQuad(double x0, double y0, double x1, double y1, double z)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(x0, y0, z);
  points->InsertNextPoint(x1, y0, z);
  points->InsertNextPoint(x1, y1, z);
  points->InsertNextPoint(x0, y1, z);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->SetPoints(points);
  result->SetPolys(polys);
  return result;
}

vtkSmartPointer<vtkPolyData> MakeBumpySphere(double radius)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(32);
  sphere->Update();
  auto bumpy = vtkSmartPointer<vtkPolyData>::New();
  bumpy->DeepCopy(sphere->GetOutput());
  vtkPoints* points = bumpy->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    const double theta = std::atan2(p[1], p[0]);
    const double phi = std::acos(std::max(-1.0, std::min(1.0, p[2] / radius)));
    const double scale = 1.0 + 0.15 * std::sin(7.0 * theta) * std::sin(5.0 * phi);
    points->SetPoint(i, scale * p[0], scale * p[1], scale * p[2]);
  }
  return bumpy;
}

vtkSmartPointer<vtkPolyData> AppendPolygons(vtkPolyData* a, vtkPolyData* b)
{
  // vtkAppendPolyData keeps the input order of cells within each cell type; the inputs here are
  // polygons only, so the result is a's cells followed by b's.
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(a);
  append->AddInputData(b);
  append->Update();
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(append->GetOutput());
  return result;
}

vtkSmartPointer<vtkPolyData> MakeRoomPolyData(
  const scenevis::scenes::BuildingScene& building, int room, int outsideNode)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> node;
  node->SetName("RoomNode");
  for (std::size_t i = 0; i < building.mesh.polygonCount(); ++i)
  {
    if (room >= -1 && building.room[i] != room)
      continue;
    polys->InsertNextCell(static_cast<vtkIdType>(building.mesh.polygonSize(i)));
    for (std::uint32_t k = 0; k < building.mesh.polygonSize(i); ++k)
    {
      const glm::dvec3& p = building.mesh.points[building.mesh.polygon(i)[k]];
      polys->InsertCellPoint(points->InsertNextPoint(p.x, p.y, p.z));
    }
    node->InsertNextValue(building.room[i] < 0 ? outsideNode : building.room[i]);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(node);
  return pd;
}

vtkSmartPointer<vtkActor> MakeTranslucentActor(
  vtkAlgorithm* source, double r, double g, double b, double opacity)
{
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetOpacity(opacity);
  actor->GetProperty()->SetSpecular(0.0);
  return actor;
}

InterpenetratingActors MakeInterpenetratingActors()
{
  InterpenetratingActors scene;
  scene.sphereA = vtkSmartPointer<vtkSphereSource>::New();
  scene.sphereA->SetCenter(-0.3, 0, 0);
  scene.sphereA->SetRadius(0.8);
  scene.sphereA->SetThetaResolution(24);
  scene.sphereA->SetPhiResolution(24);
  scene.sphereB = vtkSmartPointer<vtkSphereSource>::New();
  scene.sphereB->SetCenter(0.35, 0.1, 0.1);
  scene.sphereB->SetRadius(0.7);
  scene.sphereB->SetThetaResolution(24);
  scene.sphereB->SetPhiResolution(24);
  scene.slab = vtkSmartPointer<vtkCubeSource>::New();
  scene.slab->SetXLength(2.6);
  scene.slab->SetYLength(0.15);
  scene.slab->SetZLength(1.6);
  scene.slabTriangles = vtkSmartPointer<vtkTriangleFilter>::New();
  scene.slabTriangles->SetInputConnection(scene.slab->GetOutputPort());
  scene.red = MakeTranslucentActor(scene.sphereA, 1.0, 0.2, 0.1, 0.45);
  scene.blue = MakeTranslucentActor(scene.sphereB, 0.1, 0.4, 1.0, 0.35);
  scene.green = MakeTranslucentActor(scene.slab, 0.2, 1.0, 0.3, 0.5);
  scene.green->SetOrientation(0, 0, 20);
  return scene;
}

} // namespace testing
} // namespace scenevis

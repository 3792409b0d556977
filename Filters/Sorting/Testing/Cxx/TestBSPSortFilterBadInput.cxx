// Specification: bad input gives a clear VTK error or warning and a sane output, never a crash.
#include "vtkBSPSortFilter.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

namespace
{
int failures = 0;
#define EXPECT(cond)                                                                               \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": expected " #cond << std::endl;                \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (false)

struct Observed
{
  vtkNew<vtkTest::ErrorObserver> observer;
  explicit Observed(vtkBSPSortFilter* filter)
  {
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->AddObserver(vtkCommand::WarningEvent, observer);
  }
};

vtkSmartPointer<vtkPolyData> Triangles(double badValue)
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
} // namespace

int TestBSPSortFilterBadInput(int, char*[])
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 5);

  // No camera: error, input passes through unsorted.
  {
    vtkNew<vtkBSPSortFilter> sorter;
    Observed observed(sorter);
    sorter->SetInputConnection(sphere->GetOutputPort());
    sorter->Update();
    EXPECT(observed.observer->GetError());
    EXPECT(observed.observer->GetErrorMessage().find("No camera") != std::string::npos);
    EXPECT(sorter->GetOutput()->GetNumberOfPolys() == sphere->GetOutput()->GetNumberOfPolys());
  }
  // Camera with a NaN position: error and pass-through.
  {
    vtkNew<vtkCamera> broken;
    broken->SetPosition(std::numeric_limits<double>::quiet_NaN(), 0, 5);
    vtkNew<vtkBSPSortFilter> sorter;
    Observed observed(sorter);
    sorter->SetInputConnection(sphere->GetOutputPort());
    sorter->SetCamera(broken);
    sorter->Update();
    EXPECT(observed.observer->GetError());
    EXPECT(sorter->GetOutput()->GetNumberOfPolys() == sphere->GetOutput()->GetNumberOfPolys());
  }
  // Empty input: a warning and an empty output.
  {
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkBSPSortFilter> sorter;
    Observed observed(sorter);
    sorter->SetInputData(empty);
    sorter->SetCamera(camera);
    sorter->Update();
    EXPECT(observed.observer->GetWarning());
    EXPECT(sorter->GetOutput()->GetNumberOfCells() == 0);
  }
  // NaN and Inf points, degenerate polygons: removed, counted and reported; the rest sorted.
  for (double bad : { std::numeric_limits<double>::quiet_NaN(),
         std::numeric_limits<double>::infinity() })
  {
    vtkNew<vtkBSPSortFilter> sorter;
    Observed observed(sorter);
    sorter->SetInputData(Triangles(bad));
    sorter->SetCamera(camera);
    sorter->Update();
    EXPECT(observed.observer->GetWarning());
    EXPECT(sorter->GetNumberOfRemovedPolygons() == 3);
    EXPECT(sorter->GetOutput()->GetNumberOfPolys() == 1);
  }
  // Huge and tiny extents sort without complaint.
  for (double scale : { 1e12, 1e-12 })
  {
    vtkNew<vtkSphereSource> scaled;
    scaled->SetRadius(scale);
    scaled->SetCenter(3 * scale, 0, 0);
    vtkNew<vtkCamera> far;
    far->SetPosition(3 * scale, 0, 5 * scale);
    far->SetFocalPoint(3 * scale, 0, 0);
    vtkNew<vtkBSPSortFilter> sorter;
    Observed observed(sorter);
    sorter->SetInputConnection(scaled->GetOutputPort());
    sorter->SetCamera(far);
    sorter->Update();
    EXPECT(!observed.observer->GetError() && !observed.observer->GetWarning());
    EXPECT(sorter->GetOutput()->GetNumberOfPolys() >= scaled->GetOutput()->GetNumberOfPolys());
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

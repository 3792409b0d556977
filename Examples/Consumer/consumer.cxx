// Sorts a sphere for a camera through the installed SceneVis package.
#include <vtkBSPSortFilter.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include <cstdlib>
#include <iostream>

int main()
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 4);
  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputConnection(sphere->GetOutputPort());
  sorter->SetCamera(camera);
  sorter->Update();
  const vtkIdType sorted = sorter->GetOutput()->GetNumberOfPolys();
  std::cout << "consumer: sorted " << sorted << " polygons" << std::endl;
  return sorted >= sphere->GetOutput()->GetNumberOfPolys() ? EXIT_SUCCESS : EXIT_FAILURE;
}

// Specification: the tree is built once per input; a camera move only re-orders (incrementally);
// front-to-back is the reverse of back-to-front; a prop's matrix maps the camera into data space;
// the ordered-leaf size is a build setting (changing it rebuilds, a camera move does not).
#include "vtkBSPSortFilter.h"

#include "scenevis/testing/Expect.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <vector>

namespace
{
/// Output polygons as (source cell, first point id) pairs, in output order.
std::vector<std::pair<vtkIdType, vtkIdType>> Sequence(vtkPolyData* pd)
{
  std::vector<std::pair<vtkIdType, vtkIdType>> sequence;
  vtkIdTypeArray* original = vtkIdTypeArray::SafeDownCast(
    pd->GetCellData()->GetArray(vtkBSPSortFilter::OriginalCellIdArrayName()));
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType c = 0;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids); ++c)
  {
    sequence.emplace_back(original ? original->GetValue(c) : -1, ids[0]);
  }
  return sequence;
}
} // namespace

int TestBSPSortFilterUpdates(int, char*[])
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(64);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 5);
  camera->SetFocalPoint(0, 0, 0);

  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputConnection(sphere->GetOutputPort());
  sorter->SetCamera(camera);
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == 1);
  const vtkIdType nodesAfterBuild = sorter->GetLastNodesVisited();
  const auto before = Sequence(sorter->GetOutput());

  // Camera moves: re-order only, and a small step visits only part of the tree.
  camera->Azimuth(1.0);
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == 1);
  SCENEVIS_EXPECT(sorter->GetLastNodesVisited() < nodesAfterBuild);
  camera->Azimuth(90.0);
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == 1);
  const auto rotated = Sequence(sorter->GetOutput());
  SCENEVIS_EXPECT(rotated != before);

  // Nothing changed: the filter does not execute again.
  const vtkMTimeType outputTime = sorter->GetOutput()->GetMTime();
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetOutput()->GetMTime() == outputTime);

  // Front to back is the exact reverse of back to front.
  sorter->SetDirectionToFrontToBack();
  sorter->Update();
  auto reversed = Sequence(sorter->GetOutput());
  std::reverse(reversed.begin(), reversed.end());
  SCENEVIS_EXPECT(reversed == rotated);
  sorter->SetDirectionToBackToFront();

  // The input changes: one rebuild.
  sphere->SetThetaResolution(32);
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == 2);

  // A prop's matrix: sorting in data space with the prop equals sorting the transformed camera.
  vtkNew<vtkActor> actor;
  actor->SetPosition(10, 0, 0);
  actor->RotateY(30);
  sorter->SetProp3D(actor);
  sorter->Update();
  const auto withProp = Sequence(sorter->GetOutput());

  vtkNew<vtkTransform> inverse;
  inverse->SetMatrix(actor->GetMatrix());
  inverse->Inverse();
  vtkNew<vtkCamera> dataCamera;
  double position[3], focal[3];
  inverse->TransformPoint(camera->GetPosition(), position);
  inverse->TransformPoint(camera->GetFocalPoint(), focal);
  dataCamera->SetPosition(position);
  dataCamera->SetFocalPoint(focal);
  vtkNew<vtkBSPSortFilter> reference;
  reference->SetInputConnection(sphere->GetOutputPort());
  reference->SetCamera(dataCamera);
  reference->Update();
  SCENEVIS_EXPECT(Sequence(reference->GetOutput()) == withProp);

  // Moving the prop re-orders without a rebuild.
  const vtkIdType builds = sorter->GetNumberOfBuilds();
  actor->RotateY(120);
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == builds);
  SCENEVIS_EXPECT(Sequence(sorter->GetOutput()) != withProp);

  // Ordered leaves: a rebuild when the size changes, none when the camera moves; the output
  // lists the fragments the view draws, and front to back is still the exact reverse.
  sorter->SetOrderedLeafSize(16);
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == builds + 1);
  SCENEVIS_EXPECT(
    sorter->GetLastNumberOfOrderedFragments() == sorter->GetOutput()->GetNumberOfPolys());
  SCENEVIS_EXPECT(sorter->GetLastNumberOfOrderedFragments() <= sorter->GetNumberOfFragments());
  const auto leafOrder = Sequence(sorter->GetOutput());
  camera->Azimuth(45.0);
  sorter->Update();
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == builds + 1);
  const auto leafMoved = Sequence(sorter->GetOutput());
  SCENEVIS_EXPECT(leafMoved != leafOrder);
  sorter->SetDirectionToFrontToBack();
  sorter->Update();
  auto leafReversed = Sequence(sorter->GetOutput());
  std::reverse(leafReversed.begin(), leafReversed.end());
  SCENEVIS_EXPECT(leafReversed == leafMoved);
  SCENEVIS_EXPECT(sorter->GetNumberOfBuilds() == builds + 1);
  sorter->SetOrderedLeafSize(1000); // clamped to 256
  SCENEVIS_EXPECT(sorter->GetOrderedLeafSize() == 256);

  return scenevis::testing::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

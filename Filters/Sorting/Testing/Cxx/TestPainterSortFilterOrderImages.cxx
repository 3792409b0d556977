// vtkPainterSortFilter, at image level: drawing its output in order with the depth test off (a
// painter's ID image) gives exactly the z-buffer ID image of the same fragments, for the cyclic
// quads and the translucent sphere grid, from perspective and parallel cameras; one filter
// follows a moving camera (normalised once, sorted per view). Controls: the reversed order and,
// on the cyclic quads, vtkDepthSortPolyData do not match. Also checks the output arrays.
#include "vtkDemoSceneSource.h"
#include "vtkPainterSortFilter.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDepthSortPolyData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"

#include <cstdlib>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;
int failures = 0;

struct View
{
  const char* name;
  double eye[3];
  bool parallel;
};

/// Mismatching pixels between the painter's image of `ordered`'s cell order and its z-buffer.
std::size_t Mismatch(vtkRenderWindow* window, vtkPolyData* ordered, vtkCamera* camera,
  std::size_t* compared = nullptr)
{
  const st::IdImage painter = st::RenderPainterIds(window, ordered, camera);
  const st::IdImage depth = st::RenderVisibleIds(window, ordered, camera);
  const st::OrderComparison result = st::OrderMatchesDepth(painter, depth);
  if (compared)
  {
    *compared = result.comparedPixels;
  }
  return result.problem.empty() ? result.mismatchedPixels : static_cast<std::size_t>(-1);
}

vtkSmartPointer<vtkPolyData> Reversed(vtkPolyData* pd)
{
  std::vector<vtkIdType> order(static_cast<std::size_t>(pd->GetNumberOfCells()));
  std::iota(order.rbegin(), order.rend(), 0);
  return st::ReorderCells(pd, order);
}

void Expect(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "  FAIL: " << what << "\n";
    ++failures;
  }
}

/// OriginalCellId / SortRank present, one per output cell, ranks 0..n-1, ids valid, and the
/// PartId cell data copied from each fragment's original cell.
void CheckArrays(vtkPolyData* input, vtkPolyData* output)
{
  auto* ids = vtkIdTypeArray::SafeDownCast(
    output->GetCellData()->GetArray(vtkPainterSortFilter::OriginalCellIdArrayName()));
  auto* ranks = vtkIdTypeArray::SafeDownCast(
    output->GetCellData()->GetArray(vtkPainterSortFilter::SortRankArrayName()));
  vtkDataArray* inParts = input->GetCellData()->GetArray("PartId");
  vtkDataArray* outParts = output->GetCellData()->GetArray("PartId");
  if (!ids || !ranks || !inParts || !outParts)
  {
    Expect(false, "OriginalCellId, SortRank and PartId arrays in the output");
    return;
  }
  const vtkIdType cells = output->GetNumberOfCells();
  bool ok = ids->GetNumberOfTuples() == cells && ranks->GetNumberOfTuples() == cells &&
    outParts->GetNumberOfTuples() == cells;
  for (vtkIdType c = 0; ok && c < cells; ++c)
  {
    const vtkIdType original = ids->GetValue(c);
    ok = ranks->GetValue(c) == c && original >= 0 && original < input->GetNumberOfCells() &&
      outParts->GetTuple1(c) == inParts->GetTuple1(original);
  }
  Expect(ok, "order arrays consistent and cell data follow the original cells");
}
} // namespace

int TestPainterSortFilterOrderImages(int, char*[])
{
  st::StrictVtkOutput strict;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(240, 240);

  const View views[] = { { "front", { 0.0, 0.0, 6.0 }, false },
    { "oblique", { 3.0, -2.0, 5.0 }, false }, { "below", { 1.0, 2.0, -6.0 }, false },
    { "parallel", { -2.0, 1.5, 5.0 }, true } };

  for (const char* sceneName : { "cyclic-quads", "spheres" })
  {
    vtkNew<vtkDemoSceneSource> source;
    source->SetSceneByName(sceneName);
    source->SetTriangleCount(3000);
    source->Update();

    // One filter and one camera for all views: the sorter is built once, sorted per view.
    vtkNew<vtkCamera> camera;
    vtkNew<vtkPainterSortFilter> sorter;
    sorter->SetInputConnection(source->GetOutputPort());
    sorter->SetCamera(camera);
    for (const View& view : views)
    {
      camera->SetPosition(view.eye);
      camera->SetFocalPoint(0, 0, 0);
      camera->SetParallelProjection(view.parallel);
      camera->SetParallelScale(2.5);
      camera->SetViewAngle(40);

      sorter->Update();
      std::size_t compared = 0;
      const std::size_t painter = Mismatch(window, sorter->GetOutput(), camera, &compared);
      const std::size_t reversed = Mismatch(window, Reversed(sorter->GetOutput()), camera);
      std::cout << sceneName << " / " << view.name << ": painter's order mismatches " << painter
                << " of " << compared << " pixels (" << sorter->GetNumberOfFragments()
                << " fragments, " << sorter->GetNumberOfSplits() << " splits, "
                << sorter->GetLastSortTime() * 1e3 << " ms), reversed order mismatches "
                << reversed << "\n";
      Expect(painter == 0 && compared >= 1000,
        "the painter's order must match the depth test on a covered image");
      Expect(reversed != 0, "the reversed order must not match (the oracle must be able to fail)");
      Expect(sorter->GetNumberOfForcedEmissions() == 0, "no forced emissions");
      CheckArrays(source->GetOutput(), sorter->GetOutput());

      if (std::string(sceneName) == "cyclic-quads" && !view.parallel &&
        std::string(view.name) != "below")
      {
        Expect(sorter->GetNumberOfSplits() > 0, "a cycle needs a split");
        vtkNew<vtkDepthSortPolyData> depthSort;
        depthSort->SetInputConnection(source->GetOutputPort());
        depthSort->SetCamera(camera);
        depthSort->SetDirectionToBackToFront();
        depthSort->SetDepthSortModeToParametricCenter();
        depthSort->Update();
        const std::size_t centroid = Mismatch(window, depthSort->GetOutput(), camera);
        std::cout << "  vtkDepthSortPolyData mismatches " << centroid << "\n";
        Expect(centroid != 0, "a whole-polygon order of a cyclic overlap cannot be correct");
      }
    }
    Expect(sorter->GetNumberOfBuilds() == 1, "normalised once per input");
    Expect(sorter->GetNumberOfSorts() == 4, "sorted once per view");
    const vtkIdType sorts = sorter->GetNumberOfSorts();
    sorter->Update();
    Expect(sorter->GetNumberOfSorts() == sorts, "camera unchanged: no re-sort");

    // Front to back is the exact reverse.
    sorter->SetDirectionToFrontToBack();
    sorter->Update();
    const std::size_t frontToBack = Mismatch(window, Reversed(sorter->GetOutput()), camera);
    Expect(frontToBack == 0, "front-to-back reversed must match the depth test");
  }
  return strict.ExitCode(failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE);
}

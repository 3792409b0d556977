/**
 * @file ChunkedMapperTesting.h
 * @brief Oracles shared by the vtkChunkedPolyDataMapper tests on meshes with every cell kind.
 *
 * The ID-buffer harness takes polygons only; these meshes also hold strips, polygons of 7+
 * points and degenerate triangles. The ID mesh is built here independently of the mapper: every
 * polygon fanned and every strip split into its triangles, degenerate ones kept (they cover no
 * pixel in the ID render either), each triangle carrying its input cell id.
 */
#ifndef ChunkedMapperTesting_h
#define ChunkedMapperTesting_h

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataObject.h>
#include <vtkHardwareSelector.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSelection.h>
#include <vtkSelectionNode.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <set>
#include <string>

namespace chunked_testing
{

/// Triangles of the polygons and strips of @p input (points shared) with the input cell id of
/// each in the cell array @p idName.
inline vtkSmartPointer<vtkPolyData> TrianglesWithInputIds(vtkPolyData* input, const char* idName)
{
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName(idName);
  const vtkIdType polyBase = input->GetNumberOfVerts() + input->GetNumberOfLines();
  const vtkIdType stripBase = polyBase + input->GetNumberOfPolys();
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = input->GetPolys();
  for (vtkIdType c = 0; c < input->GetNumberOfPolys(); ++c)
  {
    polys->GetCellAtId(c, npts, pts);
    for (vtkIdType j = 1; j + 1 < npts; ++j)
    {
      const vtkIdType tri[3] = { pts[0], pts[j], pts[j + 1] };
      triangles->InsertNextCell(3, tri);
      ids->InsertNextValue(polyBase + c);
    }
  }
  vtkCellArray* strips = input->GetStrips();
  for (vtkIdType c = 0; c < input->GetNumberOfStrips(); ++c)
  {
    strips->GetCellAtId(c, npts, pts);
    for (vtkIdType j = 0; j + 2 < npts; ++j)
    {
      const vtkIdType tri[3] = { pts[j], pts[j + 1], pts[j + 2] };
      triangles->InsertNextCell(3, tri);
      ids->InsertNextValue(stripBase + c);
    }
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(input->GetPoints());
  out->SetPolys(triangles);
  out->GetCellData()->AddArray(ids);
  return out;
}

/// Cell ids reported by a hardware selection of the whole viewport of @p renderer (which must
/// be in its window), each passed through @p map (e.g. vtkChunkedPolyDataMapper::GetInputCellId).
inline std::set<vtkIdType> SelectedCells(
  vtkRenderer* renderer, const std::function<vtkIdType(vtkIdType)>& map)
{
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(renderer);
  const int* size = renderer->GetRenderWindow()->GetSize();
  selector->SetArea(
    0, 0, static_cast<unsigned int>(size[0] - 1), static_cast<unsigned int>(size[1] - 1));
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  auto selection = vtkSmartPointer<vtkSelection>::Take(selector->Select());
  std::set<vtkIdType> cells;
  for (unsigned int n = 0; selection && n < selection->GetNumberOfNodes(); ++n)
  {
    auto* list = vtkIdTypeArray::SafeDownCast(selection->GetNode(n)->GetSelectionList());
    for (vtkIdType i = 0; list && i < list->GetNumberOfValues(); ++i)
    {
      cells.insert(map(list->GetValue(i)));
    }
  }
  return cells;
}

} // namespace chunked_testing

#endif

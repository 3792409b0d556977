"""numpy interop: the order arrays through vtk.util.numpy_support (skipped without numpy)."""
import pytest
import vtk
import scenevis

np = pytest.importorskip("numpy")
from vtk.util import numpy_support  # noqa: E402


def sorted_spheres():
    source = scenevis.vtkDemoSceneSource()
    source.SetTriangleCount(2000)
    camera = vtk.vtkCamera()
    camera.SetPosition(5.5, 3.7, 7.3)
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputConnection(source.GetOutputPort())
    sorter.SetCamera(camera)
    sorter.Update()
    source.Update()
    return source.GetOutput(), sorter, camera


def test_order_arrays_as_numpy():
    mesh, sorter, camera = sorted_spheres()
    out = sorter.GetOutput()
    rank = numpy_support.vtk_to_numpy(out.GetCellData().GetArray("SortRank"))
    original = numpy_support.vtk_to_numpy(out.GetCellData().GetArray("OriginalCellId"))
    assert rank.shape == original.shape == (out.GetNumberOfCells(),)
    assert np.array_equal(rank, np.arange(len(rank)))
    # Every input cell is drawn by at least one fragment; the extra fragments are the splits.
    per_cell = np.bincount(original, minlength=mesh.GetNumberOfCells())
    assert per_cell.min() >= 1 and per_cell.size == mesh.GetNumberOfCells()
    assert int(per_cell.sum() - mesh.GetNumberOfCells()) == sorter.GetNumberOfSplits()
    # Cell data follow their fragment: the part of each fragment is its input cell's part.
    parts_in = numpy_support.vtk_to_numpy(mesh.GetCellData().GetArray("PartId"))
    parts_out = numpy_support.vtk_to_numpy(out.GetCellData().GetArray("PartId"))
    assert np.array_equal(parts_out, parts_in[original])


def test_back_to_front_by_centroid_depth_on_average():
    """Far fragments come first: the first tenth of the order lies farther from the eye than the
    last tenth (centroid distance is a whole-polygon measure, so only this trend is asserted)."""
    _, sorter, camera = sorted_spheres()
    out = sorter.GetOutput()
    centers = vtk.vtkCellCenters()
    centers.SetInputData(out)
    centers.Update()
    xyz = numpy_support.vtk_to_numpy(centers.GetOutput().GetPoints().GetData())
    distance = np.linalg.norm(xyz - np.array(camera.GetPosition()), axis=1)
    tenth = len(distance) // 10
    assert distance[:tenth].min() > distance[-tenth:].max()


def test_numpy_input_through_the_filter():
    """A mesh made with numpy goes in; the order comes out."""
    grid = np.array([[x, y, 0.1 * x * y] for x in range(5) for y in range(5)], dtype=float)
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(grid, deep=True))
    triangles = []
    for x in range(4):
        for y in range(4):
            a = 5 * x + y
            triangles += [(a, a + 5, a + 1), (a + 1, a + 5, a + 6)]
    cells = vtk.vtkCellArray()
    cells.SetData(
        numpy_support.numpy_to_vtkIdTypeArray(np.arange(0, 3 * len(triangles) + 1, 3), deep=True),
        numpy_support.numpy_to_vtkIdTypeArray(np.array(triangles).ravel(), deep=True))
    mesh = vtk.vtkPolyData()
    mesh.SetPoints(points)
    mesh.SetPolys(cells)
    camera = vtk.vtkCamera()
    camera.SetPosition(2, 2, 10)
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputData(mesh)
    sorter.SetCamera(camera)
    sorter.Update()
    original = numpy_support.vtk_to_numpy(
        sorter.GetOutput().GetCellData().GetArray("OriginalCellId"))
    assert sorted(set(original.tolist())) == list(range(len(triangles)))

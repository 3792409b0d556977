"""The wrapped vtkBSPSortFilter's output judged by the order oracle (order_oracle.py, the
definition of Core's C++ oracle replicated in Python), and the output's own invariants."""
import math

import pytest
import vtk
import scenevis

from order_oracle import check_order, polygons_in_view, polygon_area


def camera_at(position, focal=(0, 0, 0)):
    camera = vtk.vtkCamera()
    camera.SetPosition(*position)
    camera.SetFocalPoint(*focal)
    camera.SetViewUp(0, 1, 0) if abs(position[0]) + abs(position[2]) > 1e-9 else \
        camera.SetViewUp(0, 0, 1)
    return camera


def demo(name):
    source = scenevis.vtkDemoSceneSource()
    assert source.SetSceneByName(name)
    return source


def two_spheres():
    """Two interpenetrating spheres: no order of their unsplit triangles is right."""
    append = vtk.vtkAppendPolyData()
    for centre in ((0, 0, 0), (0.6, 0.2, 0.1)):
        sphere = vtk.vtkSphereSource()
        sphere.SetCenter(*centre)
        sphere.SetThetaResolution(10)
        sphere.SetPhiResolution(8)
        append.AddInputConnection(sphere.GetOutputPort())
    return append


def sorted_output(source, camera, direction=None):
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputConnection(source.GetOutputPort())
    sorter.SetCamera(camera)
    if direction == "front-to-back":
        sorter.SetDirectionToFrontToBack()
    sorter.Update()
    return sorter


SCENES = [
    ("cyclic-quads", lambda: demo("cyclic-quads"), (0.3, 0.2, 6.0)),
    ("interpenetrating-triangles", lambda: demo("triangles"), (0.5, 0.4, 5.0)),
    ("two-spheres", two_spheres, (2.0, 1.5, 4.0)),
    ("two-spheres-other-side", two_spheres, (-3.0, -1.0, -2.5)),
]


@pytest.mark.parametrize("name,make,eye", SCENES, ids=[s[0] for s in SCENES])
def test_bsp_order_passes_the_oracle(name, make, eye):
    source = make()
    camera = camera_at(eye)
    sorter = sorted_output(source, camera)
    violated, constrained = check_order(polygons_in_view(sorter.GetOutput(), camera))
    assert constrained > 0, "the scene must constrain the order"
    assert violated == 0, f"{violated} of {constrained} pairs out of order"


@pytest.mark.parametrize("name,make,eye", SCENES, ids=[s[0] for s in SCENES])
def test_the_oracle_rejects_wrong_orders(name, make, eye):
    """The oracle is not vacuous: the unsplit input (no order of it is right for these scenes)
    and the reversed BSP order both fail."""
    source = make()
    camera = camera_at(eye)
    source.Update()
    violated, _ = check_order(polygons_in_view(source.GetOutput(), camera))
    assert violated > 0
    sorter = sorted_output(source, camera)
    reversed_order = list(reversed(polygons_in_view(sorter.GetOutput(), camera)))
    violated, _ = check_order(reversed_order)
    assert violated > 0


def test_front_to_back_is_the_reverse_order():
    camera = camera_at((2.0, 1.5, 4.0))
    sorter = sorted_output(two_spheres(), camera, "front-to-back")
    polys = polygons_in_view(sorter.GetOutput(), camera)
    violated, constrained = check_order(list(reversed(polys)))
    assert constrained > 0 and violated == 0


def test_camera_move_reorders_without_rebuilding():
    source = two_spheres()
    camera = camera_at((2.0, 1.5, 4.0))
    sorter = sorted_output(source, camera)
    assert sorter.GetNumberOfBuilds() == 1
    camera.SetPosition(-3.0, -1.0, -2.5)
    sorter.Update()
    assert sorter.GetNumberOfBuilds() == 1
    violated, constrained = check_order(polygons_in_view(sorter.GetOutput(), camera))
    assert constrained > 0 and violated == 0


def test_order_arrays_and_statistics():
    """SortRank is the output position of every fragment; OriginalCellId names the input cell
    each fragment lies in (on its plane), every input cell is covered, and the fragments of a
    cell add up to its area. Statistics are plain Python numbers."""
    source = two_spheres()
    source.Update()
    mesh = source.GetOutput()
    camera = camera_at((2.0, 1.5, 4.0))
    sorter = sorted_output(source, camera)
    out = sorter.GetOutput()
    rank = out.GetCellData().GetArray(scenevis.vtkVisibilityOrderFilter.SortRankArrayName())
    original = out.GetCellData().GetArray("OriginalCellId")
    n = out.GetNumberOfCells()
    assert rank is not None and original is not None
    assert [int(rank.GetTuple1(i)) for i in range(n)] == list(range(n))

    for value in (sorter.GetNumberOfFragments(), sorter.GetNumberOfSplits(),
                  sorter.GetTreeDepth(), sorter.GetNumberOfBuilds()):
        assert isinstance(value, int)
    assert isinstance(sorter.GetLastBuildTime(), float)
    assert sorter.GetNumberOfFragments() == n
    assert sorter.GetNumberOfSplits() > 0
    assert n == mesh.GetNumberOfCells() + sorter.GetNumberOfSplits()

    area = {}
    for i in range(n):
        cell_id = int(original.GetTuple1(i))
        assert 0 <= cell_id < mesh.GetNumberOfCells()
        fragment = out.GetCell(i)
        input_cell = mesh.GetCell(cell_id)
        normal, centre = [0.0] * 3, [0.0] * 3
        vtk.vtkPolygon.ComputeNormal(input_cell.GetPoints(), normal)
        p0 = input_cell.GetPoints().GetPoint(0)
        for k in range(fragment.GetNumberOfPoints()):
            p = fragment.GetPoints().GetPoint(k)
            assert abs(sum((p[j] - p0[j]) * normal[j] for j in range(3))) < 1e-7
        area[cell_id] = area.get(cell_id, 0.0) + polygon_area(fragment)
    assert sorted(area) == list(range(mesh.GetNumberOfCells()))
    for cell_id, total in area.items():
        assert math.isclose(total, polygon_area(mesh.GetCell(cell_id)), rel_tol=1e-6)  # float points


def test_painter_sort_filter_is_wrapped_too():
    camera = camera_at((0.3, 0.2, 6.0))
    source = demo("cyclic-quads")  # held: a VTK 9.1 connection does not keep its producer
    painter = scenevis.vtkPainterSortFilter()
    painter.SetInputConnection(source.GetOutputPort())
    painter.SetCamera(camera)
    painter.Update()
    assert painter.GetOutput().GetNumberOfPolys() >= 3
    violated, _ = check_order(polygons_in_view(painter.GetOutput(), camera))
    assert violated == 0


def bumpy_sphere():
    """A closed, non-convex surface (radial bumps on a sphere): the tree without ordered leaves
    splits it, with leaves many of its polygons stay whole."""
    sphere = vtk.vtkSphereSource()
    sphere.SetThetaResolution(24)
    sphere.SetPhiResolution(16)
    sphere.Update()
    bumpy = vtk.vtkPolyData()
    bumpy.DeepCopy(sphere.GetOutput())
    points = bumpy.GetPoints()
    for i in range(points.GetNumberOfPoints()):
        x, y, z = points.GetPoint(i)
        theta = math.atan2(y, x)
        phi = math.acos(max(-1.0, min(1.0, z / 0.5)))
        scale = 1.0 + 0.15 * math.sin(7.0 * theta) * math.sin(5.0 * phi)
        points.SetPoint(i, scale * x, scale * y, scale * z)
    producer = vtk.vtkTrivialProducer()
    producer.SetOutput(bumpy)
    return producer


@pytest.mark.parametrize("eye", [(1.5, 1.0, 2.0), (-2.0, -0.5, 1.0)])
def test_ordered_leaves_pass_the_oracle_with_fewer_polygons(eye):
    """SetOrderedLeafSize: whole polygons sorted per view inside the tree's leaves; the order
    is still exact, its reverse is not, and fewer polygons are drawn than without leaves."""
    source = bumpy_sphere()
    camera = camera_at(eye)
    plain = sorted_output(source, camera)
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputConnection(source.GetOutputPort())
    sorter.SetCamera(camera)
    sorter.SetOrderedLeafSize(64)
    sorter.Update()
    assert sorter.GetOrderedLeafSize() == 64
    assert sorter.GetLastLeavesSorted() > 0
    drawn = sorter.GetOutput().GetNumberOfPolys()
    assert drawn == sorter.GetLastNumberOfOrderedFragments()
    assert drawn < plain.GetOutput().GetNumberOfPolys()
    in_view = polygons_in_view(sorter.GetOutput(), camera)
    violated, constrained = check_order(in_view)
    assert constrained > 0
    assert violated == 0, f"{violated} of {constrained} pairs out of order"
    violated, _ = check_order(list(reversed(in_view)))
    assert violated > 0

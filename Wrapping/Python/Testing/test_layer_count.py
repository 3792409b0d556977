"""scripts/layer-count.py, the measuring tool of BENCHMARKS' "The engine's last pixels off", on a
scene whose layers are known: two parts lying face to face (two coplanar squares that overlap)
and a triangle through them, which the BSP splits."""
import importlib.util
import os

import numpy as np
import pytest
import scenevis
import vtk

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "..", "scripts", "layer-count.py")
SIZE = 120
EYE, FOCAL, UP = (0.6, -0.4, 4.0), (0.75, 0.5, 0.0), (0.0, 1.0, 0.0)


@pytest.fixture(scope="module")
def layer_count():
    spec = importlib.util.spec_from_file_location("layer_count", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def two_parts_face_to_face():
    """Squares [0, 1] x [0, 1] (part 0) and [0.5, 1.5] x [0, 1] (part 1) in z = 0, and a
    triangle (part 2) that crosses that plane."""
    points = vtk.vtkPoints()
    for p in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
              (0.5, 0, 0), (1.5, 0, 0), (1.5, 1, 0), (0.5, 1, 0),
              (0.2, 0.3, -0.5), (1.3, 0.5, 0.5), (0.3, 0.8, 0.4)]:
        points.InsertNextPoint(*p)
    cells = vtk.vtkCellArray()
    parts = vtk.vtkIntArray()
    parts.SetName("PartId")
    for triangle, part in [((0, 1, 2), 0), ((0, 2, 3), 0), ((4, 5, 6), 1), ((4, 6, 7), 1),
                           ((8, 9, 10), 2)]:
        cells.InsertNextCell(3, triangle)
        parts.InsertNextValue(part)
    polydata = vtk.vtkPolyData()
    polydata.SetPoints(points)
    polydata.SetPolys(cells)
    polydata.GetCellData().AddArray(parts)
    return polydata


def fragments_of(polydata, camera):
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputData(polydata)
    sorter.SetCamera(camera)
    sorter.Update()
    return sorter.GetOutput()


def test_counts_layers_and_finds_what_peeling_drops(layer_count, render_window):
    scene = two_parts_face_to_face()
    cam = layer_count.camera(EYE, FOCAL, UP, scene.GetBounds())
    fragments = fragments_of(scene, cam)
    assert fragments.GetNumberOfCells() > scene.GetNumberOfCells(), "the triangle is split"

    plain = layer_count.layers(scene, cam, SIZE, window=render_window)
    split = layer_count.layers(fragments, cam, SIZE, window=render_window)
    peeled = layer_count.layers(scene, cam, SIZE, peel=True, window=render_window)

    # The overlap of the squares, at a point the triangle does not reach: 2 layers.
    window = layer_count.window_points(scene, cam, SIZE)
    x, y = (int(v) for v in layer_count.to_window([0.9, 0.1, 0.0], cam, SIZE)[0])
    assert plain[y, x] == 2
    assert split[y, x] == 2
    assert peeled[y, x] == 1, "depth peeling keeps one of two layers at one depth"
    covered = int((plain > 0).sum())
    assert covered > 0.2 * SIZE * SIZE
    # The fragments tile their polygons: their layers differ at most along split edges.
    assert int((split != plain).sum()) <= 0.01 * covered
    # Peeling drops a layer across the overlap: a tenth of the squares' area at least.
    assert int((peeled < plain).sum()) >= 0.1 * covered

    # What the script reports for such a pixel: two coplanar polygons of different parts.
    at = layer_count.covering_triangles(window, layer_count.cells_of(scene))
    points = np.array([scene.GetPoint(i) for i in range(scene.GetNumberOfPoints())])
    parts = np.array([scene.GetCellData().GetArray("PartId").GetValue(c)
                      for c in range(scene.GetNumberOfCells())])
    assert layer_count.coplanar_pair(at((x + 0.5, y + 0.5)), points, parts) == "other part"
    assert layer_count.coplanar_pair(at((x + 0.5, y + 0.5)), points, np.zeros_like(parts)) == \
        "same part"

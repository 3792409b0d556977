"""Bad input from Python: None, wrong types, NaN points, bad files. Each gives a Python exception
or a VTK error message and an empty or cleaned output, never a crash."""
import math
import os

import pytest
import vtk
import scenevis


def nan_polydata():
    """Two triangles, one of them with a NaN vertex."""
    points = vtk.vtkPoints()
    for p in ((0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (math.nan, 0.5, 0.5)):
        points.InsertNextPoint(*p)
    polys = vtk.vtkCellArray()
    for cell in ((0, 1, 2), (1, 3, 4)):
        polys.InsertNextCell(3, cell)
    mesh = vtk.vtkPolyData()
    mesh.SetPoints(points)
    mesh.SetPolys(polys)
    return mesh


def test_wrong_types_raise_type_error():
    sorter = scenevis.vtkBSPSortFilter()
    with pytest.raises(TypeError):
        sorter.SetInputConnection(vtk.vtkSphereSource())   # an algorithm, not an output port
    with pytest.raises(TypeError):
        sorter.SetCamera(vtk.vtkActor())
    with pytest.raises(TypeError):
        sorter.SetCamera("camera")
    with pytest.raises(TypeError):
        sorter.SetPartitionMode("scored")
    with pytest.raises(TypeError):
        vtk.vtkRenderer().AddCuller(vtk.vtkActor())
    with pytest.raises(TypeError):
        vtk.vtkRenderer().SetPass(scenevis.vtkBSPSortFilter())
    with pytest.raises(TypeError):
        scenevis.vtkOrderedTranslucentPass().SetTranslucentPass(scenevis.vtkOctreeCuller())
    with pytest.raises(TypeError):
        scenevis.vtkPortalCuller().SetPortals(vtk.vtkImageData())
    with pytest.raises(TypeError):
        scenevis.vtkPortalCuller().SetPropRoom(None, "kitchen")
    with pytest.raises(TypeError):
        scenevis.vtkDemoSceneSource().SetTriangleCount("many")


def test_none_inputs_give_vtk_errors(vtk_messages):
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputConnection(None)   # allowed by VTK: removes the connection
    sorter.SetCamera(None)
    sorter.Update()
    assert "error" in vtk_messages.text().lower()
    assert sorter.GetOutput().GetNumberOfCells() == 0

    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputData(None)
    sorter.Update()
    assert sorter.GetOutput().GetNumberOfCells() == 0

    source = vtk.vtkSphereSource()     # input but no camera: passes through unsorted, an error
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputConnection(source.GetOutputPort())
    before = len(vtk_messages.text())
    sorter.Update()
    assert "camera" in vtk_messages.text()[before:].lower()
    assert sorter.GetOutput().GetNumberOfCells() == 96

    culler = scenevis.vtkPortalCuller()
    culler.SetPortals(None)
    assert culler.GetPortals() is None
    mapper = scenevis.vtkBSPSortedPolyDataMapper()
    mapper.SetInputData(None)
    passes = scenevis.vtkOrderedTranslucentPass()
    passes.SetTranslucentPass(None)


def test_wrong_data_type_gives_a_vtk_error(vtk_messages):
    image = vtk.vtkImageData()
    image.SetDimensions(4, 4, 4)
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputData(image)
    sorter.SetCamera(vtk.vtkCamera())
    sorter.Update()
    assert "error" in vtk_messages.text().lower()


def test_nan_points_are_removed_with_a_warning(vtk_messages):
    camera = vtk.vtkCamera()
    camera.SetPosition(0.3, 0.4, 5)
    for algorithm in (scenevis.vtkBSPSortFilter(), scenevis.vtkPainterSortFilter()):
        algorithm.SetInputData(nan_polydata())
        algorithm.SetCamera(camera)
        algorithm.Update()
        out = algorithm.GetOutput()
        assert algorithm.GetNumberOfRemovedPolygons() == 1
        assert out.GetNumberOfPolys() == 1
        used = {out.GetCell(0).GetPointId(k) for k in range(3)}
        assert all(math.isfinite(c) for i in used for c in out.GetPoint(i))
    assert "warning" in vtk_messages.text().lower()


def test_nan_points_in_culled_and_sorted_rendering(render_window, vtk_messages):
    """A mesh with NaN points drawn by the sorted and chunked mappers, under the cullers."""
    renderer = vtk.vtkRenderer()
    render_window.AddRenderer(renderer)
    for mapper in (scenevis.vtkBSPSortedPolyDataMapper(), scenevis.vtkChunkedPolyDataMapper()):
        mapper.SetInputData(nan_polydata())
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetOpacity(0.5)
        renderer.AddActor(actor)
    renderer.GetCullers().RemoveAllItems()
    renderer.AddCuller(scenevis.vtkOcclusionCuller())
    renderer.AddCuller(scenevis.vtkPortalCuller())
    steps = scenevis.vtkOrderedTranslucentPass()
    steps.SetTranslucentPass(scenevis.vtkBSPTranslucentPass())
    renderer.SetPass(steps)
    renderer.GetActiveCamera().SetPosition(0.3, 0.4, 5)
    renderer.GetActiveCamera().SetFocalPoint(0.5, 0.5, 0)
    render_window.Render()
    render_window.Render()


def test_model_reader_bad_files(tmp_path, vtk_messages):
    reader = scenevis.vtkSceneVisModelReader()
    reader.SetFileName(str(tmp_path / "missing.stl"))
    reader.Update()
    assert reader.GetOutput().GetNumberOfCells() == 0
    assert isinstance(reader.GetErrorMessage(), str) and reader.GetErrorMessage()

    garbage = tmp_path / "garbage.ply"
    garbage.write_bytes(os.urandom(2048))
    reader.SetFileName(str(garbage))
    reader.Update()
    assert reader.GetOutput().GetNumberOfCells() == 0
    assert reader.GetErrorMessage()

    reader.SetFileName(None)
    reader.Update()
    assert reader.GetOutput().GetNumberOfCells() == 0


def test_demo_source_rejects_unknown_scenes(vtk_messages):
    source = scenevis.vtkDemoSceneSource()
    assert source.SetSceneByName("no-such-scene") is False
    source.SetTriangleCount(-5)    # clamped, with a warning
    assert source.GetTriangleCount() >= 64

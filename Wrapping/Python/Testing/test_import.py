"""`import vtk, scenevis`: every public SceneVis class is there, built against the VTK python3
runs, and its objects pass freely to and from vtk's."""
import os

import vtk
import scenevis

CLASSES = [
    # SceneVis::FiltersSorting
    "vtkBSPSortFilter", "vtkPainterSortFilter", "vtkVisibilityOrderFilter", "vtkBSPSortUtilities",
    # SceneVis::FiltersSources
    "vtkDemoSceneSource",
    # SceneVis::FiltersPortals
    "vtkGenerateRooms",
    # SceneVis::RenderingTranslucency
    "vtkBSPSortedPolyDataMapper", "vtkBSPTranslucentPass", "vtkOrderedTranslucentPass",
    # SceneVis::RenderingCulling
    "vtkOctreeCuller", "vtkOcclusionCuller", "vtkChunkedPolyDataMapper",
    # SceneVis::RenderingPortals
    "vtkPortalCuller",
    # SceneVis::IOModels
    "vtkSceneVisModelReader",
    # SceneVis::RenderingAuto
    "vtkSceneVisPlanner", "vtkScenePlanRule",
]


def test_every_class_is_wrapped():
    missing = [name for name in CLASSES if not hasattr(scenevis, name)]
    assert missing == []


def test_same_vtk_libraries_as_the_c_plus_plus_build():
    """One libvtkCommonCore in the process: scenevis's extensions link the libraries of
    python3-vtk9 (the VTK 9.1 of libvtk9-dev), not a second VTK."""
    assert vtk.vtkVersion.GetVTKMajorVersion() == 9
    assert vtk.vtkVersion.GetVTKMinorVersion() == 1
    with open("/proc/self/maps") as maps:
        common_core = {line.split()[-1] for line in maps if "libvtkCommonCore" in line}
    assert len(common_core) == 1, common_core
    sorting = [m for m in os.listdir(os.path.dirname(scenevis.__file__))
               if m.startswith("SceneVisFiltersSorting")]
    assert sorting, "the extension module is next to __init__.py"


def test_objects_are_vtk_objects():
    sorter = scenevis.vtkBSPSortFilter()
    assert isinstance(sorter, vtk.vtkPolyDataAlgorithm)
    assert sorter.IsA("vtkAlgorithm") and sorter.GetClassName() == "vtkBSPSortFilter"
    assert isinstance(scenevis.vtkOctreeCuller(), vtk.vtkCuller)
    assert isinstance(scenevis.vtkOcclusionCuller(), scenevis.vtkOctreeCuller)
    assert isinstance(scenevis.vtkPortalCuller(), vtk.vtkCuller)
    assert isinstance(scenevis.vtkBSPSortedPolyDataMapper(), vtk.vtkOpenGLPolyDataMapper)
    assert isinstance(scenevis.vtkChunkedPolyDataMapper(), vtk.vtkPolyDataMapper)
    assert isinstance(scenevis.vtkOrderedTranslucentPass(), vtk.vtkRenderPass)
    assert isinstance(scenevis.vtkBSPTranslucentPass(), vtk.vtkRenderPass)
    assert isinstance(scenevis.vtkSceneVisModelReader(), vtk.vtkPolyDataAlgorithm)
    assert "vtkBSPSortFilter" in str(sorter)  # PrintSelf


def test_pipeline_between_vtk_and_scenevis():
    """vtk source -> scenevis filter -> vtk filter -> scenevis mapper -> vtk actor/renderer with
    scenevis culler and pass; everything connects and the scenevis objects come back as
    themselves."""
    sphere = vtk.vtkSphereSource()
    sorter = scenevis.vtkBSPSortFilter()
    sorter.SetInputConnection(sphere.GetOutputPort())
    camera = vtk.vtkCamera()
    camera.SetPosition(0, 0, 5)
    sorter.SetCamera(camera)
    assert sorter.GetCamera() is camera
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputConnection(sorter.GetOutputPort())
    normals.Update()
    assert normals.GetOutput().GetNumberOfCells() == sorter.GetOutput().GetNumberOfCells() > 0
    assert normals.GetInputAlgorithm() is sorter

    mapper = scenevis.vtkBSPSortedPolyDataMapper()
    mapper.SetInputConnection(normals.GetOutputPort())
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    assert actor.GetMapper() is mapper

    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    culler = scenevis.vtkOctreeCuller()
    renderer.AddCuller(culler)
    assert renderer.GetCullers().IsItemPresent(culler)
    passes = scenevis.vtkOrderedTranslucentPass()
    translucent = scenevis.vtkBSPTranslucentPass()
    passes.SetTranslucentPass(translucent)
    assert passes.GetTranslucentPass() is translucent
    renderer.SetPass(passes)
    assert renderer.GetPass() is passes


def test_demo_scene_source():
    source = scenevis.vtkDemoSceneSource()
    assert source.SetSceneByName("cyclic-quads") is True
    assert source.GetScene() == scenevis.vtkDemoSceneSource.SCENE_CYCLIC_QUADS
    assert scenevis.vtkDemoSceneSource.GetSceneName(scenevis.vtkDemoSceneSource.SCENE_BUILDING) \
        == "building"
    source.Update()
    assert source.GetOutput().GetNumberOfPolys() == 3


def test_readme_python_snippet_runs():
    """The README's Python snippet, as written (rendered offscreen)."""
    import pytest
    if not os.environ.get("DISPLAY"):
        pytest.skip("no X display (the suite runs under xvfb-run)")
    readme = os.path.join(os.path.dirname(__file__), "..", "..", "..", "README.md")
    with open(readme) as f:
        text = f.read()
    snippet = text.split("```python\n", 1)[1].split("```", 1)[0]
    snippet = snippet.replace("window.Render()", "window.SetOffScreenRendering(1)\nwindow.Render()")
    scope = {}
    exec(compile(snippet, "README.md", "exec"), scope)
    assert isinstance(scope["culler"].GetNumberOfPropsDrawn(), int)
    assert list(scope["rank"][:3]) == [0, 1, 2]

"""The cullers from Python: they plug into a vtk renderer, and their statistics are plain Python
numbers that add up."""
import os
import sys

import pytest
import vtk
import scenevis

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "Examples", "Python"))
import building_walkthrough  # noqa: E402  (the example's hand-written building)


def box_grid(renderer, n=10, spacing=2.0):
    """n x n unit cubes on the z = 0 plane, one actor each."""
    for i in range(n):
        for j in range(n):
            cube = vtk.vtkCubeSource()
            cube.SetCenter(i * spacing, j * spacing, 0)
            mapper = vtk.vtkPolyDataMapper()
            mapper.SetInputConnection(cube.GetOutputPort())
            actor = vtk.vtkActor()
            actor.SetMapper(mapper)
            renderer.AddActor(actor)
    return n * n


def test_octree_culler_statistics(render_window):
    renderer = vtk.vtkRenderer()
    render_window.AddRenderer(renderer)
    total = box_grid(renderer)
    renderer.GetCullers().RemoveAllItems()
    culler = scenevis.vtkOctreeCuller()
    renderer.AddCuller(culler)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, 0, 6)        # looking down at the corner cube only
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewAngle(30)
    renderer.ResetCameraClippingRange()
    render_window.Render()

    drawn, culled = culler.GetNumberOfPropsDrawn(), culler.GetNumberOfPropsCulled()
    assert all(isinstance(v, int) for v in (drawn, culled, culler.GetNumberOfNodesVisited(),
                                            culler.GetNumberOfTrianglesDrawn()))
    assert drawn + culled == total
    assert 1 <= drawn < 10 and culler.GetNumberOfPropsCulledByFrustum() == culled
    # Triangles as OpenGL draws them: 6 quads, 12 triangles per cube.
    assert culler.GetNumberOfTrianglesDrawn() == 12 * drawn
    assert culler.GetNumberOfRebuilds() == 1

    renderer.ResetCamera()                # the whole grid in view: nothing culled
    render_window.Render()
    assert culler.GetNumberOfPropsDrawn() == total and culler.GetNumberOfPropsCulled() == 0
    assert culler.GetNumberOfRebuilds() == 1


def test_occlusion_culler_culls_behind_a_wall(render_window):
    renderer = vtk.vtkRenderer()
    render_window.AddRenderer(renderer)
    total = box_grid(renderer, n=4)
    wall = vtk.vtkCubeSource()           # a wall between the eye and the boxes
    wall.SetBounds(-5, 12, -5, 12, 3, 3.5)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(wall.GetOutputPort())
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    renderer.GetCullers().RemoveAllItems()
    culler = scenevis.vtkOcclusionCuller()
    renderer.AddCuller(culler)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(3, 3, 20)
    camera.SetFocalPoint(3, 3, 0)
    renderer.ResetCameraClippingRange()
    render_window.Render()
    render_window.Render()  # the second frame starts from the first's visible set
    assert culler.GetNumberOfPropsCulledByOcclusion() == total
    assert culler.GetNumberOfPropsDrawn() == 1
    assert isinstance(culler.GetCullTime(), float)


def test_chunked_mapper_statistics(render_window):
    source = scenevis.vtkDemoSceneSource()
    source.SetScene(scenevis.vtkDemoSceneSource.SCENE_CAD_ASSEMBLY)
    source.SetPartCount(200)
    source.SetTriangleCount(20000)
    mapper = scenevis.vtkChunkedPolyDataMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    render_window.AddRenderer(renderer)
    renderer.ResetCamera()
    render_window.Render()
    chunks, drawn = mapper.GetNumberOfChunks(), mapper.GetNumberOfChunksDrawn()
    assert isinstance(chunks, int) and chunks > 1 and drawn == chunks
    assert mapper.GetNumberOfTrianglesDrawn() == mapper.GetNumberOfTriangles() > 0
    renderer.GetActiveCamera().Zoom(6)   # a corner of the board: chunks culled by the frustum
    renderer.ResetCameraClippingRange()
    render_window.Render()
    assert 0 < mapper.GetNumberOfChunksDrawn() < chunks
    assert mapper.GetNumberOfChunksCulledByFrustum() > 0
    assert mapper.GetNumberOfPartitionBuilds() == 1


def test_portal_culler_statistics(render_window):
    renderer = vtk.vtkRenderer()
    render_window.AddRenderer(renderer)
    culler = scenevis.vtkPortalCuller()
    building_walkthrough.build_scene(renderer, culler)
    renderer.GetCullers().RemoveAllItems()  # alone: it sees every prop, not the frustum's
    renderer.AddCuller(culler)
    rooms = building_walkthrough.ROOMS
    props = renderer.GetViewProps().GetNumberOfItems()
    camera = renderer.GetActiveCamera()
    camera.SetViewUp(0, 0, 1)
    camera.SetViewAngle(60)
    camera.SetPosition(2.0, 2.0, 1.6)        # in the first room, facing the solid end wall
    camera.SetFocalPoint(-1.0, 2.0, 1.6)
    camera.SetClippingRange(0.05, 100)
    render_window.Render()
    assert culler.GetNumberOfRooms() == rooms
    assert culler.GetNumberOfRoomsVisited() == 1
    assert culler.GetNumberOfPortalsTraversed() == 0
    assert culler.GetNumberOfPropsDrawn() + culler.GetNumberOfPropsCulled() == props
    assert culler.GetNumberOfPropsDrawn() <= 5   # the room and its 4 boxes
    assert not culler.GetFrustumOnly()

    camera.SetFocalPoint(6.0, 1.0, 1.6)       # towards the first door
    render_window.Render()
    assert culler.GetNumberOfRoomsVisited() >= 2
    assert culler.GetNumberOfPortalsTraversed() >= 1

    # Outside every room with the frustum-only policy: a fallback, said so, never an empty image.
    culler.SetOutsidePolicy(scenevis.vtkPortalCuller.OUTSIDE_FRUSTUM_ONLY)
    camera.SetPosition(10.0, -6.0, 1.6)
    camera.SetFocalPoint(10.0, 2.0, 1.6)
    render_window.Render()
    assert culler.GetFrustumOnly()
    assert isinstance(culler.GetFallbackReason(), str) and culler.GetFallbackReason()
    assert culler.GetNumberOfPropsDrawn() >= 1

    assert isinstance(culler.GetLastCullTime(), float)
    assert isinstance(culler.GetGraphReport(), str)

"""scenevis.vtkGenerateRooms from Python: the rooms and portals of the Python example's building,
found from its geometry alone (its hand-written portals left out), match the hand-written ones."""
import os
import sys

import vtk
import scenevis

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "Examples", "Python"))
import building_walkthrough as bw  # noqa: E402  (the example's hand-written building)


def generated_building():
    append = vtk.vtkAppendPolyData()
    for i in range(bw.ROOMS):
        append.AddInputData(bw.room_polydata(i))
    rooms = scenevis.vtkGenerateRooms()
    rooms.SetInputConnection(append.GetOutputPort())
    rooms.Update()
    return append, rooms


def test_one_room_per_room_and_one_portal_per_door():
    append, rooms = generated_building()
    assert rooms.GetStatus() == scenevis.vtkGenerateRooms.STATUS_OK
    assert rooms.GetNumberOfRooms() == bw.ROOMS
    assert rooms.GetNumberOfPortals() == bw.ROOMS - 1
    assert rooms.GetNumberOfExteriorPortals() == 0 and rooms.GetNumberOfLeakCells() == 0

    # Each hand-made room is one generated room of its own (named by its floor, its first
    # cell); its cells are in it, but for its half of each doorway, which may go to the room on
    # the doorway's other side (a doorway through a thick wall is a passage of either room).
    room_ids = rooms.GetOutput().GetCellData().GetArray("RoomId")
    # The example's one-room "RoomId" field array (passed on by vtkAppendPolyData) is gone: the
    # portal culler would read it before the cell array.
    assert rooms.GetOutput().GetFieldData().GetArray("RoomId") is None
    firsts = [0]
    for i in range(bw.ROOMS):
        firsts.append(firsts[-1] + bw.room_polydata(i).GetNumberOfCells())
    generated_of = [room_ids.GetValue(firsts[i]) for i in range(bw.ROOMS)]
    assert sorted(generated_of) == list(range(bw.ROOMS))
    for i in range(bw.ROOMS):
        allowed = {generated_of[j] for j in (i - 1, i, i + 1) if 0 <= j < bw.ROOMS}
        values = {room_ids.GetValue(c) for c in range(firsts[i], firsts[i + 1])}
        assert values <= allowed, (i, values, allowed)

    # Each door's portal joins the two rooms on either side and covers the doorway.
    portals = rooms.GetPortalsOutput()
    room_a = portals.GetCellData().GetArray("RoomA")
    room_b = portals.GetCellData().GetArray("RoomB")
    for i in range(bw.ROOMS - 1):
        pair = tuple(sorted((generated_of[i], generated_of[i + 1])))
        found = [p for p in range(portals.GetNumberOfCells())
                 if (room_a.GetValue(p), room_b.GetValue(p)) == pair]
        assert len(found) == 1, (i, pair)
        bounds = portals.GetCell(found[0]).GetBounds()
        y0, y1 = bw.door_y(i) - bw.DOOR_WIDTH / 2, bw.door_y(i) + bw.DOOR_WIDTH / 2
        eps = 1e-6  # the example's points are single precision
        assert bounds[2] <= y0 + eps and bounds[3] >= y1 - eps
        assert bounds[4] <= eps and bounds[5] >= bw.DOOR_HEIGHT - eps
        assert bw.SIZE * (i + 1) - bw.WALL / 2 - eps <= bounds[0] <= bw.SIZE * (i + 1) + bw.WALL / 2 + eps


def test_generated_portals_drive_the_portal_culler(render_window):
    """One actor per generated room, the generated portals: from the first room looking down the
    row, the culler draws fewer rooms than there are and every room the eye sees."""
    append, rooms = generated_building()
    renderer = vtk.vtkRenderer()
    render_window.AddRenderer(renderer)
    culler = scenevis.vtkPortalCuller()
    culler.SetPortals(rooms.GetPortalsOutput())
    renderer.AddCuller(culler)
    for r in range(rooms.GetNumberOfRooms()):
        threshold = vtk.vtkThreshold()
        threshold.SetInputConnection(rooms.GetOutputPort())
        threshold.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS,
                                         "RoomId")
        threshold.SetLowerThreshold(r - 0.5)
        threshold.SetUpperThreshold(r + 0.5)
        threshold.SetThresholdFunction(vtk.vtkThreshold.THRESHOLD_BETWEEN)
        surface = vtk.vtkGeometryFilter()
        surface.SetInputConnection(threshold.GetOutputPort())
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputConnection(surface.GetOutputPort())
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        renderer.AddActor(actor)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0.5, 1.0, bw.EYE)     # room 0, in line with its door at y = 1
    camera.SetFocalPoint(10.0, 1.0, bw.EYE)
    camera.SetViewUp(0, 0, 1)
    camera.SetClippingRange(0.05, 100)
    render_window.Render()
    drawn = culler.GetNumberOfPropsDrawn()
    assert culler.GetNumberOfRooms() == bw.ROOMS
    assert "error" not in culler.GetGraphReport()
    assert drawn == 2                # room 0 and the next through its door, not the far ones

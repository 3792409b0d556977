#!/usr/bin/env python3
"""A building walkthrough with portals from Python: the scene format of scenevis.vtkPortalCuller
written by hand, a camera walked through the doors, per-frame statistics, and a check that the
culling changed nothing on screen.

The building: a row of ROOMS rooms (4 x 4 x 3 m) along x, joined by doors that alternate between
the two sides of the row. Every room is closed but for its portals (the cells-and-portals
assumption): the walls between rooms have a thickness, each room owns its face of them and its
half of each doorway, and the portal is the doorway's middle. Each room is one actor whose polydata carries a one-tuple field-data
array "RoomId"; each room also holds furniture (boxes) given its room with SetPropRoom. The
portals are one polydata: one quad per door, with integer cell-data arrays "RoomA" and "RoomB".

With --generated the portals are not written by hand: scenevis.vtkGenerateRooms finds the rooms
and portals from the rooms' polygons, and the culler gets each room actor's cell rooms with
SetPropCellRooms (the actors' own data untouched). The walk and its checks are the same.

Usage: building_walkthrough.py [OUTPUT_DIR] [--frames N] [--generated]
"""
import math
import os
import sys
import time

import vtk
import scenevis

ROOMS = 6
SIZE = 4.0        # room size along x and y
HEIGHT = 3.0
DOOR_WIDTH = 1.0
DOOR_HEIGHT = 2.2
WALL = 0.1        # thickness of the walls between rooms
EYE = 1.6


def door_y(i):
    """The y of the door between room i and room i + 1: alternating sides."""
    return 1.0 if i % 2 == 0 else 3.0


def quad(points, polys, corners, flip=False):
    """One quad; its front (counter-clockwise corners) faces into the room it bounds, reversed
    with flip."""
    polys.InsertNextCell(4)
    for c in (reversed(corners) if flip else corners):
        polys.InsertCellPoint(points.InsertNextPoint(*c))


def x_wall(points, polys, x, door=None, facing=1):
    """The wall x = const over the row's width, with a door hole centred at y = door, facing +x
    (facing=1) or -x (facing=-1): into its room."""
    flip = facing < 0
    if door is None:
        quad(points, polys, [(x, 0, 0), (x, SIZE, 0), (x, SIZE, HEIGHT), (x, 0, HEIGHT)], flip)
        return
    y0, y1 = door - DOOR_WIDTH / 2, door + DOOR_WIDTH / 2
    quad(points, polys, [(x, 0, 0), (x, y0, 0), (x, y0, HEIGHT), (x, 0, HEIGHT)], flip)
    quad(points, polys, [(x, y1, 0), (x, SIZE, 0), (x, SIZE, HEIGHT), (x, y1, HEIGHT)], flip)
    quad(points, polys, [(x, y0, DOOR_HEIGHT), (x, y1, DOOR_HEIGHT), (x, y1, HEIGHT),
                         (x, y0, HEIGHT)], flip)


def half_doorway(points, polys, x_wall_face, x_portal, door):
    """The room's half of the doorway through a wall WALL thick: its floor, jambs and lintel
    between the wall face and the portal in the middle of the wall, facing into the doorway."""
    y0, y1 = door - DOOR_WIDTH / 2, door + DOOR_WIDTH / 2
    a, b = x_wall_face, x_portal
    flip = b < a
    quad(points, polys, [(a, y0, 0), (b, y0, 0), (b, y1, 0), (a, y1, 0)], flip)
    quad(points, polys, [(a, y0, 0), (a, y0, DOOR_HEIGHT), (b, y0, DOOR_HEIGHT), (b, y0, 0)], flip)
    quad(points, polys, [(a, y1, 0), (b, y1, 0), (b, y1, DOOR_HEIGHT), (a, y1, DOOR_HEIGHT)], flip)
    quad(points, polys, [(a, y0, DOOR_HEIGHT), (a, y1, DOOR_HEIGHT), (b, y1, DOOR_HEIGHT),
                         (b, y0, DOOR_HEIGHT)], flip)


def room_polydata(i):
    """Room i closed but for its portals (the cells-and-portals assumption): floor, ceiling, the
    two long walls, its faces of the walls it shares with its neighbours (WALL thick, door holes)
    and its halves of the doorways up to the portals in the walls' middle."""
    points, polys = vtk.vtkPoints(), vtk.vtkCellArray()
    x0, x1 = SIZE * i + WALL / 2, SIZE * (i + 1) - WALL / 2
    quad(points, polys, [(x0, 0, 0), (x1, 0, 0), (x1, SIZE, 0), (x0, SIZE, 0)])
    quad(points, polys, [(x0, 0, HEIGHT), (x0, SIZE, HEIGHT), (x1, SIZE, HEIGHT),
                         (x1, 0, HEIGHT)])
    quad(points, polys, [(x0, 0, 0), (x0, 0, HEIGHT), (x1, 0, HEIGHT), (x1, 0, 0)])
    quad(points, polys, [(x0, SIZE, 0), (x1, SIZE, 0), (x1, SIZE, HEIGHT), (x0, SIZE, HEIGHT)])
    if i == 0:
        x_wall(points, polys, x0)
    else:
        x_wall(points, polys, x0, door_y(i - 1))
        half_doorway(points, polys, x0, SIZE * i, door_y(i - 1))
    if i == ROOMS - 1:
        x_wall(points, polys, x1, facing=-1)
    else:
        x_wall(points, polys, x1, door_y(i), facing=-1)
        half_doorway(points, polys, x1, SIZE * (i + 1), door_y(i))
    room = vtk.vtkPolyData()
    room.SetPoints(points)
    room.SetPolys(polys)
    room_id = vtk.vtkIntArray()
    room_id.SetName("RoomId")
    room_id.InsertNextValue(i)
    room.GetFieldData().AddArray(room_id)
    return room


def portals_polydata():
    points, polys = vtk.vtkPoints(), vtk.vtkCellArray()
    room_a, room_b = vtk.vtkIntArray(), vtk.vtkIntArray()
    room_a.SetName("RoomA")
    room_b.SetName("RoomB")
    for i in range(ROOMS - 1):
        x, y = SIZE * (i + 1), door_y(i)
        y0, y1 = y - DOOR_WIDTH / 2, y + DOOR_WIDTH / 2
        quad(points, polys, [(x, y0, 0), (x, y1, 0), (x, y1, DOOR_HEIGHT), (x, y0, DOOR_HEIGHT)])
        room_a.InsertNextValue(i)
        room_b.InsertNextValue(i + 1)
    portals = vtk.vtkPolyData()
    portals.SetPoints(points)
    portals.SetPolys(polys)
    portals.GetCellData().AddArray(room_a)
    portals.GetCellData().AddArray(room_b)
    return portals


def generated_rooms():
    """Rooms and portals found from the rooms' geometry alone (scenevis.vtkGenerateRooms), as for
    a model that comes without portals: the portals, and per hand-made room i the generated room
    of each of its cells and of its floor."""
    append = vtk.vtkAppendPolyData()
    for i in range(ROOMS):
        append.AddInputData(room_polydata(i))
    rooms = scenevis.vtkGenerateRooms()
    rooms.SetInputConnection(append.GetOutputPort())
    rooms.Update()
    print(f"generated {rooms.GetNumberOfRooms()} rooms, {rooms.GetNumberOfPortals()} portals, "
          f"{rooms.GetNumberOfLeakCells()} leak cells in {rooms.GetGenerationTime():.2f} s")
    room_ids = rooms.GetOutput().GetCellData().GetArray("RoomId")
    cell_rooms, floor_room, first = [], [], 0
    for i in range(ROOMS):
        cells = room_polydata(i).GetNumberOfCells()
        array = vtk.vtkIntArray()
        for c in range(cells):
            array.InsertNextValue(room_ids.GetValue(first + c))
        cell_rooms.append(array)
        floor_room.append(room_ids.GetValue(first))  # the floor is each room's first cell
        first += cells
    return rooms.GetPortalsOutput(), cell_rooms, floor_room


def build_scene(renderer, culler, generated=False):
    """The rooms and their furniture, with the hand-written portals, or (generated) with rooms
    and portals found from the geometry: the room actors' cells get their generated rooms with
    SetPropCellRooms, the furniture the room of its room's floor."""
    palette = [(0.85, 0.8, 0.7), (0.7, 0.8, 0.85), (0.8, 0.75, 0.85), (0.75, 0.85, 0.7)]
    if generated:
        portals, cell_rooms, room_of = generated_rooms()
    else:
        portals, cell_rooms, room_of = portals_polydata(), None, list(range(ROOMS))
    for i in range(ROOMS):
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputData(room_polydata(i))
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(*palette[i % 4])
        renderer.AddActor(actor)
        if cell_rooms:
            culler.SetPropCellRooms(actor, cell_rooms[i])
        for k in range(4):  # furniture: boxes along the long walls
            box = vtk.vtkCubeSource()
            box.SetCenter(SIZE * i + 0.8 + k * 0.8, 0.5 if k % 2 == 0 else SIZE - 0.5, 0.41)
            box.SetXLength(0.5)
            box.SetYLength(0.6)
            box.SetZLength(0.8)
            mapper = vtk.vtkPolyDataMapper()
            mapper.SetInputConnection(box.GetOutputPort())
            actor = vtk.vtkActor()
            actor.SetMapper(mapper)
            actor.GetProperty().SetColor(0.55, 0.35, 0.2)
            renderer.AddActor(actor)
            culler.SetPropRoom(actor, room_of[i])
    culler.SetPortals(portals)


def walk_path():
    """Room centres and door centres, at eye height, from the first room to the last."""
    path = [(SIZE / 2, SIZE / 2, EYE)]
    for i in range(ROOMS - 1):
        path.append((SIZE * (i + 1), door_y(i), EYE))
        path.append((SIZE * (i + 1.5), SIZE / 2, EYE))
    return path


def sample(path, s):
    """The point at arc length s along the polyline (clamped)."""
    s = max(0.0, s)
    for a, b in zip(path, path[1:]):
        d = math.dist(a, b)
        if s <= d:
            t = s / d
            return tuple(p + t * (q - p) for p, q in zip(a, b))
        s -= d
    return path[-1]


def capture(window):
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    image = vtk.vtkImageData()
    image.DeepCopy(grab.GetOutput())
    return image


def differing_pixels(a, b):
    diff = vtk.vtkImageDifference()
    diff.SetInputData(a)
    diff.SetImageData(b)
    diff.SetThreshold(0)
    diff.AllowShiftOff()
    diff.AveragingOff()
    diff.Update()
    return diff.GetError()


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    out = args[0] if args else "building-walkthrough"
    frames = int(argv[argv.index("--frames") + 1]) if "--frames" in argv else 24
    if "--frames" in argv:
        args.remove(argv[argv.index("--frames") + 1])
    os.makedirs(out, exist_ok=True)
    if not os.environ.get("DISPLAY"):
        print("skipped: no X display (run under xvfb-run)")
        return 77

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(480, 360)
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(0.55, 0.7, 0.9)
    window.AddRenderer(renderer)
    culler = scenevis.vtkPortalCuller()
    culler.SetMode(scenevis.vtkPortalCuller.MODE_EXACT_FRUSTUM)
    build_scene(renderer, culler, generated="--generated" in argv)
    renderer.AddCuller(culler)  # after VTK's vtkFrustumCoverageCuller
    camera = renderer.GetActiveCamera()
    camera.SetViewAngle(70)
    camera.SetViewUp(0, 0, 1)
    props = renderer.GetViewProps().GetNumberOfItems()
    print(f"building: {ROOMS} rooms, {ROOMS - 1} doors, {props} props")

    path = walk_path()
    length = sum(math.dist(a, b) for a, b in zip(path, path[1:]))
    culled_frames = 0
    worst_difference = 0
    for f in range(frames):
        s = length * f / max(1, frames - 1)
        eye = sample(path, min(s, length - 0.3))
        ahead = sample(path, min(s, length - 0.3) + 0.3)
        camera.SetPosition(*eye)
        camera.SetFocalPoint(ahead[0], ahead[1], EYE)
        camera.SetClippingRange(0.05, 100)
        start = time.perf_counter()
        window.Render()
        ms = 1000 * (time.perf_counter() - start)
        drawn, culled = culler.GetNumberOfPropsDrawn(), culler.GetNumberOfPropsCulled()
        culled_frames += culled > 0
        print(f"  frame {f}: rooms visited {culler.GetNumberOfRoomsVisited()} of "
              f"{culler.GetNumberOfRooms()}, portals {culler.GetNumberOfPortalsTraversed()}, "
              f"props drawn {drawn}, culled {culled}, triangles "
              f"{culler.GetNumberOfTrianglesDrawn()} of {culler.GetNumberOfTrianglesTotal()}, "
              f"cull {culler.GetLastCullTime():.3f} ms, frame {ms:.1f} ms"
              + (f", frustum only: {culler.GetFallbackReason()}" if culler.GetFrustumOnly()
                 else ""))
        if f % 8 == 0 or f == frames - 1:
            # Conservative: the same frame without the portal culler looks exactly the same.
            culled_image = capture(window)
            renderer.GetCullers().RemoveItem(culler)
            window.Render()
            unculled_image = capture(window)
            difference = differing_pixels(culled_image, unculled_image)
            if difference:
                print(f"  frame {f}: DIFFERS from the unculled render ({difference:g})")
                writer = vtk.vtkPNGWriter()
                writer.SetInputData(unculled_image)
                writer.SetFileName(os.path.join(out, f"frame-{f:02d}-unculled.png"))
                writer.Write()
            worst_difference = max(worst_difference, difference)
            renderer.AddCuller(culler)
            writer = vtk.vtkPNGWriter()
            writer.SetInputData(culled_image)
            writer.SetFileName(os.path.join(out, f"frame-{f:02d}.png"))
            writer.Write()
    print(f"walked {frames} frames; props culled in {culled_frames} of them; "
          f"difference from the unculled render: {worst_difference:g}")
    return 0 if culled_frames > 0 and worst_difference == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/env python3
"""Culling a big CAD assembly from Python, offscreen, with the statistics as plain numbers.

1. Many actors: the demo assembly (scenevis.vtkDemoSceneSource, 2,000 parts) split by its PartId
   cell array into one actor per part (numpy), culled by scenevis.vtkOcclusionCuller (BVH frustum
   culling plus conservative occlusion culling) instead of VTK's vtkFrustumCoverageCuller.
2. One mesh: the same assembly merged, drawn by scenevis.vtkChunkedPolyDataMapper, which culls
   spatial chunks of it inside its own buffers.
The camera flies low over the board; every frame prints what was drawn and culled.

Usage: cad_culling.py [OUTPUT_DIR] [--frames N]
"""
import os
import sys
import time

import numpy as np
import vtk
import scenevis
from vtk.util import numpy_support


def assembly(parts, triangles):
    source = scenevis.vtkDemoSceneSource()
    source.SetScene(scenevis.vtkDemoSceneSource.SCENE_CAD_ASSEMBLY)
    source.SetPartCount(parts)
    source.SetTriangleCount(triangles)
    source.SetSeed(7)
    source.Update()
    return source


def split_parts(mesh):
    """One polydata per PartId (its own points), with the part's RGBA as actor colour."""
    polys = mesh.GetPolys()
    offsets = numpy_support.vtk_to_numpy(polys.GetOffsetsArray())
    connectivity = numpy_support.vtk_to_numpy(polys.GetConnectivityArray())
    part_of_cell = numpy_support.vtk_to_numpy(mesh.GetCellData().GetArray("PartId"))
    colours = numpy_support.vtk_to_numpy(mesh.GetCellData().GetArray("Colors"))
    points = numpy_support.vtk_to_numpy(mesh.GetPoints().GetData())
    order = np.argsort(part_of_cell, kind="stable")
    sizes = offsets[order + 1] - offsets[order]
    # The point ids of the cells in part order, in one gather.
    ends = np.cumsum(sizes)
    gather = np.arange(ends[-1]) + np.repeat(offsets[order] - (ends - sizes), sizes)
    all_ids = connectivity[gather]
    first_cells = np.flatnonzero(np.diff(part_of_cell[order])) + 1
    first_ids = np.concatenate(([0], ends))[first_cells]
    for cells, part_sizes, ids in zip(np.split(order, first_cells), np.split(sizes, first_cells),
                                      np.split(all_ids, first_ids)):
        used, local = np.unique(ids, return_inverse=True)
        part_points = vtk.vtkPoints()
        part_points.SetData(numpy_support.numpy_to_vtk(points[used], deep=True))
        cell_array = vtk.vtkCellArray()
        cell_array.SetData(
            numpy_support.numpy_to_vtkIdTypeArray(
                np.concatenate(([0], np.cumsum(part_sizes))).astype(np.int64), deep=True),
            numpy_support.numpy_to_vtkIdTypeArray(local.astype(np.int64), deep=True))
        part = vtk.vtkPolyData()
        part.SetPoints(part_points)
        part.SetPolys(cell_array)
        yield part, colours[cells[0]] / 255.0


def fly_over(camera, b, f, n):
    """Frame f of n looks down at a point moving diagonally over the board."""
    w, h = b[1] - b[0], b[3] - b[2]
    t = 0.15 + 0.7 * f / max(1, n - 1)
    fx, fy = b[0] + t * w, b[2] + t * h
    camera.SetFocalPoint(fx, fy, b[4])
    camera.SetPosition(fx - 0.1 * w, fy - 0.15 * h, b[4] + 0.08 * w)
    camera.SetViewUp(0, 0, 1)
    camera.SetViewAngle(35)


def write_png(window, path):
    capture = vtk.vtkWindowToImageFilter()
    capture.SetInput(window)
    capture.ReadFrontBufferOff()
    writer = vtk.vtkPNGWriter()
    writer.SetInputConnection(capture.GetOutputPort())
    writer.SetFileName(path)
    writer.Write()
    print(f"  wrote {path}")


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    out = args[0] if args else "."
    frames = int(argv[argv.index("--frames") + 1]) if "--frames" in argv else 6
    os.makedirs(out, exist_ok=True)
    if not os.environ.get("DISPLAY"):
        print("skipped: no X display (run under xvfb-run)")
        return 77

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(640, 480)

    # ---- 1. Many actors, one per part, culled by vtkOcclusionCuller. --------------------------
    start = time.perf_counter()
    source = assembly(2000, 200000)
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(0.12, 0.13, 0.16)
    window.AddRenderer(renderer)
    for part, rgba in split_parts(source.GetOutput()):
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputData(part)
        mapper.ScalarVisibilityOff()
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(*rgba[:3])
        actor.GetProperty().SetOpacity(rgba[3])
        renderer.AddActor(actor)
    renderer.GetCullers().RemoveAllItems()
    culler = scenevis.vtkOcclusionCuller()
    renderer.AddCuller(culler)
    actors = renderer.GetActors().GetNumberOfItems()
    print(f"many actors: {actors} actors, {source.GetOutput().GetNumberOfCells()} triangles "
          f"({time.perf_counter() - start:.2f} s to make)")
    b = renderer.ComputeVisiblePropBounds()
    drawn_total = 0
    for f in range(frames):
        fly_over(renderer.GetActiveCamera(), b, f, frames)
        renderer.ResetCameraClippingRange()
        start = time.perf_counter()
        window.Render()
        ms = 1000 * (time.perf_counter() - start)
        stats = {
            "drawn": culler.GetNumberOfPropsDrawn(),
            "culled": culler.GetNumberOfPropsCulled(),
            "frustum": culler.GetNumberOfPropsCulledByFrustum(),
            "occlusion": culler.GetNumberOfPropsCulledByOcclusion(),
            "nodes": culler.GetNumberOfNodesVisited(),
            "triangles": culler.GetNumberOfTrianglesDrawn(),
        }
        assert all(isinstance(v, int) for v in stats.values())
        drawn_total += stats["drawn"]
        print(f"  frame {f}: props drawn {stats['drawn']}, culled {stats['culled']} (frustum "
              f"{stats['frustum']}, occlusion {stats['occlusion']}), nodes visited "
              f"{stats['nodes']}, triangles {stats['triangles']}, frame {ms:.1f} ms")
        if f in (0, frames - 1):
            write_png(window, os.path.join(out, f"cad-actors-{f}.png"))
    print(f"  hierarchy built {culler.GetNumberOfRebuilds()} time(s); "
          f"{drawn_total / (frames * actors):.1%} of the props drawn per frame")
    window.RemoveRenderer(renderer)

    # ---- 2. One mesh, drawn by vtkChunkedPolyDataMapper. --------------------------------------
    mapper = scenevis.vtkChunkedPolyDataMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    mapper.SetScalarModeToUseCellData()
    mapper.SetColorModeToDirectScalars()
    mapper.OcclusionCullingOn()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(0.12, 0.13, 0.16)
    renderer.AddActor(actor)
    window.AddRenderer(renderer)
    print(f"one mesh: {source.GetOutput().GetNumberOfCells()} triangles")
    for f in range(frames):
        fly_over(renderer.GetActiveCamera(), b, f, frames)
        renderer.ResetCameraClippingRange()
        start = time.perf_counter()
        window.Render()
        ms = 1000 * (time.perf_counter() - start)
        print(f"  frame {f}: chunks drawn {mapper.GetNumberOfChunksDrawn()} of "
              f"{mapper.GetNumberOfChunks()} (frustum {mapper.GetNumberOfChunksCulledByFrustum()}"
              f", occlusion {mapper.GetNumberOfChunksCulledByOcclusion()}), triangles "
              f"{mapper.GetNumberOfTrianglesDrawn()} of {mapper.GetNumberOfTriangles()}, "
              f"frame {ms:.1f} ms")
        if f == frames - 1:
            write_png(window, os.path.join(out, f"cad-mesh-{f}.png"))
    print(f"  hierarchy built {mapper.GetNumberOfPartitionBuilds()} time(s), vertex buffers "
          f"built {mapper.GetNumberOfVertexBufferBuilds()} time(s)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

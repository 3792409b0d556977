#!/usr/bin/python3
"""Where BSP fragments cover other pixels than the polygons they were split from.

    PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a /usr/bin/python3 \
        scripts/split-coverage.py ORIGINAL.vtp FRAGMENTS.vtp EYE FOCAL UP [SIZE]

ORIGINAL.vtp is a scene as `scenevis cull --export-scene` writes it, FRAGMENTS.vtp the same scene
sorted by `scenevis sort --camera EYE,FOCAL --up UP` (EYE, FOCAL and UP are x,y,z; view angle 30).
Both are drawn white at opacity 0.1 over black with plain blending in draw order
(vtkOrderedTranslucentPass), so a pixel's value gives the number of layers that cover its centre,
whatever their order. The script prints the pixels whose layer counts differ and, for each, the
distance of its centre to the nearest edge of the original polygons in window coordinates, beside
the same distance for random covered pixels: a coverage difference that comes from the
rasterizer's sub-pixel vertex precision (1/256 pixel in llvmpipe) lies within a few thousandths of
a pixel of an edge the BSP split.
"""
import math
import sys

import numpy as np
import scenevis  # noqa: F401  (vtkOrderedTranslucentPass)
import vtk
from vtk.util.numpy_support import vtk_to_numpy

OPACITY = 0.1


def load(path):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetOutput().GetNumberOfCells() == 0:
        sys.exit(f"split-coverage: no cells in '{path}'")
    return reader.GetOutput()


def camera(eye, focal, up, bounds):
    cam = vtk.vtkCamera()
    cam.SetPosition(*eye)
    cam.SetFocalPoint(*focal)
    cam.SetViewUp(*up)
    cam.SetViewAngle(30)
    # One clipping range for both renders: the scene's box seen from the eye.
    corners = np.array([[bounds[i], bounds[2 + j], bounds[4 + k]]
                        for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    direction = np.subtract(focal, eye)
    direction /= np.linalg.norm(direction)
    depths = (corners - eye) @ direction
    cam.SetClippingRange(max(1e-3 * depths.max(), 0.9 * depths.min()), 1.1 * depths.max())
    return cam


def layers(polydata, cam, size):
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(polydata)
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(1, 1, 1)
    prop.SetOpacity(OPACITY)
    prop.LightingOff()
    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0, 0, 0)
    renderer.SetPass(scenevis.vtkOrderedTranslucentPass())
    renderer.SetActiveCamera(cam)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    window.SetSize(size, size)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    red = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(size, size, 3)[:, :, 0]
    covered = np.maximum(1e-9, 1.0 - red.astype(float) / 255.0)
    return np.round(np.log(covered) / math.log(1.0 - OPACITY)).astype(int)


def edges_in_window(polydata, cam, size):
    matrix = cam.GetCompositeProjectionTransformMatrix(1.0, -1.0, 1.0)
    m = np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
    points = vtk_to_numpy(polydata.GetPoints().GetData()).astype(np.float64)
    clip = np.c_[points, np.ones(len(points))] @ m.T
    window = np.c_[(clip[:, 0] / clip[:, 3] + 1) * size / 2, (clip[:, 1] / clip[:, 3] + 1) * size / 2]
    cells = polydata.GetPolys()
    offsets = vtk_to_numpy(cells.GetOffsetsArray())
    ids = vtk_to_numpy(cells.GetConnectivityArray())
    starts, ends = [], []
    for c in range(len(offsets) - 1):
        cell = ids[offsets[c]:offsets[c + 1]]
        starts.extend(cell)
        ends.extend(np.roll(cell, -1))
    a, b = window[np.array(starts)], window[np.array(ends)]
    keep = ((b - a) ** 2).sum(1) > 1e-18
    return a[keep], b[keep]


def nearest_edge(point, a, b):
    d = b - a
    t = np.clip(((point - a) * d).sum(1) / (d * d).sum(1), 0.0, 1.0)
    return float(np.sqrt((((a + t[:, None] * d) - point) ** 2).sum(1)).min())


def main(argv):
    if len(argv) not in (6, 7):
        sys.exit(__doc__)
    eye, focal, up = ([float(v) for v in arg.split(",")] for arg in argv[3:6])
    size = int(argv[6]) if len(argv) == 7 else 240
    original, fragments = load(argv[1]), load(argv[2])
    cam = camera(eye, focal, up, original.GetBounds())
    before, after = layers(original, cam, size), layers(fragments, cam, size)
    a, b = edges_in_window(original, cam, size)
    ys, xs = np.nonzero(after != before)
    print(f"{size} x {size}: {int((before > 0).sum())} pixels covered, "
          f"{int((after > before).sum())} with more layers, {int((after < before).sum())} with fewer")
    snap = 1.0 / 256.0
    near = 0
    for x, y in zip(xs, ys):
        distance = nearest_edge(np.array([x + 0.5, y + 0.5]), a, b)
        near += distance < snap
        print(f"  pixel ({x}, {y}): {before[y, x]} -> {after[y, x]} layers, "
              f"nearest original edge {distance:.5f} px")
    rows, cols = np.nonzero(before > 0)
    pick = np.random.default_rng(1).choice(len(rows), size=min(400, len(rows)), replace=False)
    sample = np.array([nearest_edge(np.array([cols[i] + 0.5, rows[i] + 0.5]), a, b) for i in pick])
    print(f"differing pixels within 1/256 px of an original edge: {near} of {len(xs)}; "
          f"random covered pixels: {(sample < snap).mean() * 100:.1f} % "
          f"(median distance {np.median(sample):.3f} px, {len(sample)} sampled)")


if __name__ == "__main__":
    main(sys.argv)

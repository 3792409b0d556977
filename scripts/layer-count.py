#!/usr/bin/python3
"""Layers per pixel, counted: BSP fragments and 100-peel depth peeling against the unsplit mesh.

    PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a /usr/bin/python3 \
        scripts/layer-count.py ORIGINAL.vtp FRAGMENTS.vtp EYE FOCAL UP [SIZE]

ORIGINAL.vtp is a scene as `scenevis cull --export-scene` writes it, FRAGMENTS.vtp the same scene
sorted by `scenevis sort --camera EYE,FOCAL --up UP` (EYE, FOCAL and UP are x,y,z; view angle 30).
Everything is drawn white at opacity 0.1 over black, so a pixel's value gives the number of layers
over its centre whatever their order. The unsplit mesh drawn with plain blending counts every
polygon that covers the centre: the count the other two are compared with.

1. The fragments (plain blending). For each pixel whose count differs: the distance of its centre
   to the nearest edge of the polygons and of the fragments in window coordinates (beside that
   distance for random covered pixels), and whether in double precision as many fragments as
   polygons cover the centre. A difference that comes from the rasterizer's sub-pixel vertex
   precision (1/256 pixel in llvmpipe) lies within a few thousandths of a pixel of an edge the
   BSP split or made, where the fragments are right in exact arithmetic.
2. The unsplit mesh through VTK's depth peeling (100 peels, occlusion ratio 0), the reference of
   the accuracy-versus-time report. For a sample of the pixels where peeling has fewer layers:
   whether two coplanar polygons of the original cover the centre (peeling keeps one of two
   layers at the same depth), and whether they belong to different parts (PartId).
3. The accuracy-versus-time report's measure at this camera: the fragments in their colours
   ('Colors' cell scalars, opacity 0.4, lit) drawn in their sorted order against the unsplit mesh
   through 100-peel peeling; of the pixels off by more than 16 levels, how many are where peeling
   has a layer too few or too many, where the fragments' count is off, and where every count is
   right (what is left is order).
"""
import math
import sys

import numpy as np
import scenevis  # noqa: F401  (vtkOrderedTranslucentPass)
import vtk
from vtk.util.numpy_support import vtk_to_numpy

OPACITY = 0.1
COLOUR_OPACITY = 0.4  # the accuracy report's


def load(path):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetOutput().GetNumberOfCells() == 0:
        sys.exit(f"layer-count: no cells in '{path}'")
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


def render(polydata, cam, size, peel=False, window=None, colours=False):
    """The RGB image (size x size x 3, row 0 at the bottom) of @p polydata drawn in @p window (an
    offscreen window, or a new one when None): plain blending in cell order, or 100-peel depth
    peeling with @p peel; white at opacity OPACITY without lighting, or with @p colours its
    'Colors' cell scalars at COLOUR_OPACITY, lit (the accuracy report's look)."""
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(polydata)
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    if colours:
        mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectColorArray("Colors")
        mapper.SetColorModeToDirectScalars()
        mapper.ScalarVisibilityOn()
        prop.SetOpacity(COLOUR_OPACITY)
    else:
        mapper.ScalarVisibilityOff()
        prop.SetColor(1, 1, 1)
        prop.SetOpacity(OPACITY)
        prop.LightingOff()
    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0, 0, 0)
    if peel:
        renderer.SetUseDepthPeeling(1)
        renderer.SetMaximumNumberOfPeels(100)
        renderer.SetOcclusionRatio(0.0)
    else:
        renderer.SetPass(scenevis.vtkOrderedTranslucentPass())
    renderer.SetActiveCamera(cam)
    if window is None:
        window = vtk.vtkRenderWindow()
        window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetAlphaBitPlanes(1)
    window.AddRenderer(renderer)
    window.SetSize(size, size)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    window.RemoveRenderer(renderer)
    return vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(size, size, 3)


def layers(polydata, cam, size, peel=False, window=None):
    """The layers over each pixel centre, a size x size array (row 0 at the bottom) (see
    render())."""
    red = render(polydata, cam, size, peel, window)[:, :, 0]
    covered = np.maximum(1e-9, 1.0 - red.astype(float) / 255.0)
    return np.round(np.log(covered) / math.log(1.0 - OPACITY)).astype(int)


def window_points(polydata, cam, size):
    """The points of @p polydata in window coordinates (pixel centres at half-integers)."""
    return to_window(vtk_to_numpy(polydata.GetPoints().GetData()), cam, size)


def to_window(points, cam, size):
    """World @p points (n x 3) in window coordinates."""
    matrix = cam.GetCompositeProjectionTransformMatrix(1.0, -1.0, 1.0)
    m = np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    clip = np.c_[points, np.ones(len(points))] @ m.T
    return np.c_[(clip[:, 0] / clip[:, 3] + 1) * size / 2, (clip[:, 1] / clip[:, 3] + 1) * size / 2]


def cells_of(polydata):
    cells = polydata.GetPolys()
    offsets = vtk_to_numpy(cells.GetOffsetsArray())
    ids = vtk_to_numpy(cells.GetConnectivityArray())
    return [ids[offsets[c]:offsets[c + 1]] for c in range(len(offsets) - 1)]


def edges_in_window(window, cells):
    starts, ends = [], []
    for cell in cells:
        starts.extend(cell)
        ends.extend(np.roll(cell, -1))
    a, b = window[np.array(starts)], window[np.array(ends)]
    keep = ((b - a) ** 2).sum(1) > 1e-18
    return a[keep], b[keep]


def nearest_edge(point, a, b):
    d = b - a
    t = np.clip(((point - a) * d).sum(1) / (d * d).sum(1), 0.0, 1.0)
    return float(np.sqrt((((a + t[:, None] * d) - point) ** 2).sum(1)).min())


def covering_triangles(window, cells):
    """A function of a window point: the (cell, fan triangle) pairs whose triangle covers it."""
    fan = np.array([(c, cell[0], cell[k], cell[k + 1])
                    for c, cell in enumerate(cells) for k in range(1, len(cell) - 1)])
    a, b, c = window[fan[:, 1]], window[fan[:, 2]], window[fan[:, 3]]

    def at(point):
        def side(p, q):
            dx, dy = q[:, 0] - p[:, 0], q[:, 1] - p[:, 1]
            return dx * (point[1] - p[:, 1]) - dy * (point[0] - p[:, 0])
        e0, e1, e2 = side(a, b), side(b, c), side(c, a)
        inside = ((e0 > 0) & (e1 > 0) & (e2 > 0)) | ((e0 < 0) & (e1 < 0) & (e2 < 0))
        return fan[inside]
    return at


def coplanar_pair(triangles, points, parts):
    """'other part', 'same part' or None: two of @p triangles in one plane (world coordinates)."""
    planes = []
    for t in triangles:
        a, b, c = points[t[1]], points[t[2]], points[t[3]]
        n = np.cross(b - a, c - a)
        n /= np.linalg.norm(n)
        planes.append((n, float(n @ a), t[0]))
    scale = max(1.0, float(np.abs(points).max()))
    found = None
    for i in range(len(planes)):
        for j in range(i + 1, len(planes)):
            (ni, di, ci), (nj, dj, cj) = planes[i], planes[j]
            sign = 1.0 if ni @ nj > 0 else -1.0
            if abs(abs(ni @ nj) - 1.0) < 1e-6 and abs(di - sign * dj) < 1e-6 * scale:
                if parts is None or parts[ci] == parts[cj]:
                    found = found or "same part"
                else:
                    return "other part"
    return found


def vector(text, name):
    """x,y,z as three finite floats, or exit with one line naming @p name."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        sys.exit(f"layer-count: {name} must be three finite numbers x,y,z, not '{text}'")
    return values


def main(argv):
    if len(argv) not in (6, 7):
        sys.exit(__doc__)
    eye, focal, up = (vector(arg, name) for arg, name in zip(argv[3:6], ("EYE", "FOCAL", "UP")))
    size_text = argv[6] if len(argv) == 7 else "240"
    size = int(size_text) if size_text.isdigit() else 0
    if not 8 <= size <= 4096:
        sys.exit(f"layer-count: SIZE must be a whole number of pixels in 8..4096, "
                 f"not '{size_text}'")
    original, fragments = load(argv[1]), load(argv[2])
    cam = camera(eye, focal, up, original.GetBounds())
    before, after = layers(original, cam, size), layers(fragments, cam, size)
    window, cells = window_points(original, cam, size), cells_of(original)
    a, b = edges_in_window(window, cells)
    ys, xs = np.nonzero(after != before)
    print(f"{size} x {size}: {int((before > 0).sum())} pixels covered")
    print(f"fragments: {int((after > before).sum())} pixels with more layers, "
          f"{int((after < before).sum())} with fewer")
    snap = 1.0 / 256.0
    fragment_window, fragment_cells = window_points(fragments, cam, size), cells_of(fragments)
    fa, fb = edges_in_window(fragment_window, fragment_cells)
    covering = covering_triangles(window, cells)
    fragments_covering = covering_triangles(fragment_window, fragment_cells)
    near = exact = 0
    for x, y in zip(xs, ys):
        centre = np.array([x + 0.5, y + 0.5])
        to_original, to_fragment = nearest_edge(centre, a, b), nearest_edge(centre, fa, fb)
        near += min(to_original, to_fragment) < snap
        # In double precision: as many fragments over the centre as polygons.
        polygons = len({int(t[0]) for t in covering(centre)})
        pieces = len({int(t[0]) for t in fragments_covering(centre)})
        exact += polygons == pieces
        print(f"  pixel ({x}, {y}): {before[y, x]} -> {after[y, x]} layers; nearest edge of "
              f"the polygons {to_original:.5f} px, of the fragments {to_fragment:.5f} px; "
              f"in double precision {polygons} polygons, {pieces} fragments over the centre")
    rows, cols = np.nonzero(before > 0)
    pick = np.random.default_rng(1).choice(len(rows), size=min(400, len(rows)), replace=False)
    sample = np.array([min(nearest_edge(c, a, b), nearest_edge(c, fa, fb))
                       for c in (np.array([cols[i] + 0.5, rows[i] + 0.5]) for i in pick)])
    print(f"differing pixels within 1/256 px of an edge (polygons' or fragments'): {near} of "
          f"{len(xs)}, against {(sample < snap).mean() * 100:.1f} % of random covered pixels "
          f"(median distance {np.median(sample):.4f} px, {len(sample)} sampled); as many "
          f"fragments as polygons over the centre in double precision: {exact} of {len(xs)}")

    peeled = layers(original, cam, size, peel=True)
    fewer_rows, fewer_cols = np.nonzero(peeled < before)
    print(f"100-peel peeling: {int((peeled > before).sum())} pixels with more layers, "
          f"{len(fewer_rows)} with fewer ({int((peeled <= before - 2).sum())} by 2 or more)")
    if len(fewer_rows):
        points = vtk_to_numpy(original.GetPoints().GetData()).astype(np.float64)
        part_array = original.GetCellData().GetArray("PartId")
        parts = vtk_to_numpy(part_array) if part_array else None
        pick = np.random.default_rng(2).choice(len(fewer_rows), size=min(40, len(fewer_rows)),
                                              replace=False)
        kinds = {"other part": 0, "same part": 0, None: 0}
        for i in pick:
            centre = (fewer_cols[i] + 0.5, fewer_rows[i] + 0.5)
            kinds[coplanar_pair(covering(centre), points, parts)] += 1
        print(f"  of {len(pick)} sampled: two coplanar polygons of different parts cover the "
              f"centre at {kinds['other part']}, of one part at {kinds['same part']}, "
              f"none at {kinds[None]}")

    # 3. The accuracy report's measure: the fragments in colour (plain blending, the sorted order)
    # against the unsplit mesh through 100-peel peeling, pixels off by more than 16 levels, and
    # which of them are where a layer count above differs.
    sorted_image = render(fragments, cam, size, colours=True).astype(int)
    peeled_image = render(original, cam, size, peel=True, colours=True).astype(int)
    off = (np.abs(sorted_image - peeled_image).max(axis=2) > 16) & (before > 0)
    short, extra, split = off & (peeled < before), off & (peeled > before), off & (after != before)
    rest = off & ~(short | extra | split)
    print(f"colour, opacity {COLOUR_OPACITY}: {int(off.sum())} of {int((before > 0).sum())} "
          f"covered pixels off by > 16 between the sorted fragments and 100-peel peeling "
          f"({100.0 * off.sum() / max(1, (before > 0).sum()):.2f} %): peeling a layer short at "
          f"{int(short.sum())}, a layer more at {int(extra.sum())}, the fragments' count off at "
          f"{int(split.sum())}, every count right at {int(rest.sum())}")


if __name__ == "__main__":
    main(sys.argv)

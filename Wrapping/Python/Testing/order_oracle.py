"""A brute-force judge of a back-to-front order, in Python: the definition of Core's C++ oracle
(scenevis/OrderOracle.h) for a perspective eye in front of which every polygon lies.

An order of convex polygons is a correct back-to-front order when, for every pair A, B that some
ray from the eye passes through (their central projections overlap with area), the polygon hit
farther along that ray comes first. Method: project every polygon onto the plane z = -1 of the
camera's view coordinates, intersect the two projections (Sutherland-Hodgman), cast a ray through
the intersection's vertex mean and compare the hit distances on the two planes.
"""
import math


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _newell(poly):
    n = [0.0, 0.0, 0.0]
    for k, p in enumerate(poly):
        q = poly[(k + 1) % len(poly)]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    return tuple(n)


def _area2(poly):
    return sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(poly, poly[1:] + poly[:1]))


def _clip(subject, clipper):
    """Sutherland-Hodgman: subject clipped by the convex, counter-clockwise clipper."""
    out = subject
    for a, b in zip(clipper, clipper[1:] + clipper[:1]):
        if not out:
            break
        inp, out = out, []

        def side(p):
            return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])

        for k, p in enumerate(inp):
            q = inp[(k + 1) % len(inp)]
            sp, sq = side(p), side(q)
            if sp >= 0:
                out.append(p)
            if (sp >= 0) != (sq >= 0):
                t = sp / (sp - sq)
                out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return out


def polygon_area(cell):
    """The area of a planar vtkCell polygon (Newell)."""
    points = [cell.GetPoints().GetPoint(k) for k in range(cell.GetNumberOfPoints())]
    return math.sqrt(_dot(_newell(points), _newell(points))) / 2


def polygons_in_view(polydata, camera):
    """The polygons of polydata in the camera's view coordinates (eye at the origin, looking down
    -z), in cell order."""
    view = camera.GetViewTransformMatrix()
    m = [[view.GetElement(r, c) for c in range(4)] for r in range(4)]
    points = polydata.GetPoints()
    polys = []
    ids = polydata.GetPolys()
    ids.InitTraversal()
    import vtk

    cell = vtk.vtkIdList()
    while ids.GetNextCell(cell):
        poly = []
        for k in range(cell.GetNumberOfIds()):
            p = points.GetPoint(cell.GetId(k))
            poly.append(tuple(m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3]
                              for r in range(3)))
        polys.append(poly)
    return polys


def _hit(poly, ray):
    """Distance factor t at which the ray from the origin meets poly (its fan triangles: the
    polygon's own vertices, not a fitted plane), or None when it misses."""
    a = poly[0]
    for b, c in zip(poly[1:], poly[2:]):
        e1, e2 = _sub(b, a), _sub(c, a)
        h = (ray[1] * e2[2] - ray[2] * e2[1], ray[2] * e2[0] - ray[0] * e2[2],
             ray[0] * e2[1] - ray[1] * e2[0])
        det = _dot(e1, h)
        if det == 0:
            continue
        s = (-a[0], -a[1], -a[2])
        u = _dot(s, h) / det
        q = (s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
             s[0] * e1[1] - s[1] * e1[0])
        v = _dot(ray, q) / det
        if u < 0 or v < 0 or u + v > 1:
            continue
        return _dot(e2, q) / det
    return None


def check_order(polys, relative_tolerance=1e-7):
    """Judges the back-to-front order of polys (convex, view coordinates). Returns
    (violated pairs, constrained pairs): pairs seen along a common ray whose hits are more than
    the depth tolerance apart, and those of them whose later polygon is hit farther.

    Tolerances, relative to the scene's diagonal D (coarser than the C++ oracle, which proves
    every witness ray in long double down to 1e-9 D; here slivers from splits are simply not
    judged): a sample constrains the pair when its two hits are more than relative_tolerance x D
    apart; an overlap counts when its width (area / diameter), carried into the scene at the
    hit distance, exceeds relative_tolerance x D. Depths are taken on the polygons' own vertices
    (fan triangles), not on fitted planes."""
    coords = [p for poly in polys for p in poly]
    if not coords:
        return 0, 0
    diagonal = math.dist([min(p[k] for p in coords) for k in range(3)],
                         [max(p[k] for p in coords) for k in range(3)])
    depth_tolerance = relative_tolerance * diagonal
    items = []
    for poly in polys:
        if any(p[2] >= -depth_tolerance for p in poly):
            raise ValueError("the oracle needs every polygon in front of the eye")
        flat = [(p[0] / -p[2], p[1] / -p[2]) for p in poly]
        area = _area2(flat)
        if area < 0:
            flat.reverse()
        if abs(area) <= 1e-300 or _dot(_newell(poly), _newell(poly)) == 0:
            items.append(None)  # degenerate or seen edge-on: constrains nothing
            continue
        xs, ys = [p[0] for p in flat], [p[1] for p in flat]
        items.append((flat, poly, abs(area), (min(xs), max(xs), min(ys), max(ys))))
    violated = constrained = 0
    for i, a in enumerate(items):
        if a is None:
            continue
        for b in items[i + 1:]:
            if b is None:
                continue
            ba, bb = a[3], b[3]
            if ba[1] <= bb[0] or bb[1] <= ba[0] or ba[3] <= bb[2] or bb[3] <= ba[2]:
                continue
            common = _clip(a[0], b[0])
            if len(common) < 3:
                continue
            diameter = max(math.dist(p, q) for p in common for q in common)
            width = abs(_area2(common)) / 2 / diameter if diameter > 0 else 0.0
            cx = sum(p[0] for p in common) / len(common)
            cy = sum(p[1] for p in common) / len(common)
            ray = (cx, cy, -1.0)
            ta, tb = _hit(a[1], ray), _hit(b[1], ray)
            if ta is None or tb is None or abs(ta - tb) <= depth_tolerance \
                    or width * min(ta, tb) <= depth_tolerance:
                continue
            constrained += 1
            if tb > ta:
                violated += 1
    return violated, constrained

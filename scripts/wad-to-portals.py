#!/usr/bin/env python3
"""Converts a map of a Doom WAD (vanilla "Doom format": the lumps THINGS, LINEDEFS, SIDEDEFS,
VERTEXES, SEGS, SSECTORS, NODES, SECTORS after the map's marker) into a SceneVis portal scene:
the model, its portals and one camera per player start.

    python3 scripts/wad-to-portals.py WAD MAP OUT.vtp OUT-portals.vtp OUT-cameras.json \
        [--all-things OUT-things-cameras.json]
    python3 scripts/wad-to-portals.py WAD --list      (the maps with their sector counts)

Rooms are the map's sectors (RoomId = sector index); Doom is 2.5D, z up, in map units.

OUT.vtp: polygons with the cell arrays
  RoomId  (Int32) the sector whose volume the polygon bounds
  Colors  (UInt8 RGBA, opaque) a colour per kind of surface shaded by the sector's light level
  Every polygon faces into its sector (counter-clockwise seen from inside it).
  - one-sided lines: a wall quad from the floor to the ceiling of their sector;
  - two-sided lines joining two sectors: per side, the part of that side's own height range
    outside the opening: the lower part (from its floor up to the other floor) and the upper
    part (from the other ceiling up to its ceiling), RoomId = that side's sector; where the
    opening is shut, the side's whole range. Middle textures (grates, fences) are left out: they
    are see-through;
  - floors and ceilings: each subsector of the map's own BSP as a convex polygon: the map's
    bounds clipped by the node partition lines down to the subsector, then by the lines of the
    linedefs its segs lie on (the linedefs' exact vertices, not the segs' rounded split points,
    so floors meet walls exactly). RoomId = the sector of the subsector's first seg.
  - closed sectors (ceiling <= floor: shut doors, raised lifts) bound no volume and get no
    polygon: their floors and ceilings would lie on the edges where the walls that close them
    meet, seen there only through depth ties.
  The room's surfaces close its volume except at its portals, the portal scene format's
  assumption: along a two-sided line a sector's height range is covered by the lower part, the
  opening and the upper part. And the model is watertight: points within 1e-3 are welded, and
  every point lying inside another polygon's edge is inserted into that edge (no T-junctions,
  whose pixel cracks would show rooms no portal leads to); a polygon that got such points is
  written as triangles from its centre (VTK's own triangulation of collinear points makes
  needle triangles with wrong depths).

OUT-portals.vtp: one vertical quad per two-sided line joining two different sectors, over the
opening between the higher of the two floors and the lower of the two ceilings (integer cell
arrays RoomA, RoomB = the front and back sectors). The quad is exactly the opening, so never
smaller than it. Closed openings (height <= 0: shut doors, lifts up) are not portals; a line
with the same sector on both sides is not one either.

OUT-cameras.json: the format of `scenevis --cameras`: one camera per player start (thing types
1-4) and deathmatch start (11), each place and direction once: eye 41 units above the floor of
the sector the thing stands in (the player's view height), looking horizontally along the
thing's angle (degrees, 0 = east, counter-clockwise), up +z, view_angle 90 (Doom's 90-degree
horizontal field of view on a square image, e.g. --size 1024x1024), clipping range
[1, 1.05 x the map's diagonal] (the default range fitted to the props could put the near plane
behind a wall 16 units away: the player's radius).

--all-things OUT-things-cameras.json: also a camera per thing of any kind (monsters, items,
decorations; hundreds of places all over the map, for benchmarks), the same way, where a player
could stand: in a sector at least 56 units high (the player's height) and at least 16 units (the
player's radius) from every line, so that the near plane never reaches through a wall (things in
wall niches, low crawl spaces or on a line are left out).

Refused with one line on stderr and exit code 1: a file that is not a WAD, a directory or lump
outside the file, a map that is missing, in Hexen format (BEHAVIOR) or without vanilla BSP
nodes (e.g. ZDoom's compressed "ZNOD"), indices out of range. Usage errors exit 2. Python 3
standard library only.
"""
import json
import math
import os
import struct
import sys

MAP_LUMPS = ("THINGS", "LINEDEFS", "SIDEDEFS", "VERTEXES", "SEGS", "SSECTORS", "NODES",
             "SECTORS")
NO_SIDE = 0xFFFF
SUBSECTOR_BIT = 0x8000
START_TYPES = (1, 2, 3, 4, 11)
VIEW_HEIGHT = 41.0
PLAYER_HEIGHT, PLAYER_RADIUS = 56, 16
COLOURS = {"wall": (0.75, 0.70, 0.62), "lower": (0.55, 0.60, 0.72), "upper": (0.72, 0.58, 0.55),
           "floor": (0.50, 0.62, 0.48), "ceiling": (0.66, 0.66, 0.70)}


class WadError(Exception):
    pass


def read_directory(data):
    if len(data) < 12:
        raise WadError(f"too short for a WAD header ({len(data)} bytes)")
    ident, count, offset = struct.unpack_from("<4sii", data, 0)
    if ident not in (b"IWAD", b"PWAD"):
        raise WadError(f"not a WAD (magic {ident!r}; expected b'IWAD' or b'PWAD')")
    if count < 0 or offset < 0 or offset + 16 * count > len(data):
        raise WadError(f"the directory ({count} lumps at {offset}) lies outside the "
                       f"{len(data)}-byte file (truncated?)")
    lumps = []
    for index in range(count):
        position, size, raw = struct.unpack_from("<ii8s", data, offset + 16 * index)
        name = raw.split(b"\0")[0].decode("latin-1").upper()
        if position < 0 or size < 0 or position + size > len(data):
            raise WadError(f"lump {index} ({name}: {size} bytes at {position}) lies outside the "
                           f"{len(data)}-byte file (truncated?)")
        lumps.append((name, data[position:position + size]))
    return lumps


def list_maps(lumps):
    """(name, sectors, linedefs) of every map: a marker followed by THINGS."""
    maps = []
    for index, (name, _) in enumerate(lumps[:-1]):
        if lumps[index + 1][0] == "THINGS":
            sizes = {n: len(d) for n, d in lumps[index + 1:index + 12]}
            maps.append((name, sizes.get("SECTORS", 0) // 26, sizes.get("LINEDEFS", 0) // 14))
    return maps


def map_lumps(lumps, map_name):
    for index, (name, _) in enumerate(lumps):
        if name == map_name.upper() and index + 1 < len(lumps) and lumps[index + 1][0] == "THINGS":
            found = {}
            for name2, data in lumps[index + 1:index + 13]:
                if name2 in found or (name2 not in MAP_LUMPS and name2 not in (
                        "REJECT", "BLOCKMAP", "BEHAVIOR", "SCRIPTS")):
                    break
                found[name2] = data
            if "BEHAVIOR" in found:
                raise WadError(f"map {map_name} is in Hexen format (BEHAVIOR lump); only the "
                               "vanilla Doom format is read")
            missing = [n for n in MAP_LUMPS if n not in found]
            if missing:
                raise WadError(f"map {map_name} lacks the lumps {', '.join(missing)}")
            return found
    known = ", ".join(m[0] for m in list_maps(lumps)) or "none"
    raise WadError(f"no map {map_name} in the WAD (maps: {known})")


def records(lump, size, fmt, what):
    if len(lump) % size:
        raise WadError(f"the {what} lump ({len(lump)} bytes) is not a multiple of {size}"
                       + (" (compressed or extended nodes?)" if what in ("NODES", "SEGS",
                                                                         "SSECTORS") else ""))
    return list(struct.iter_unpack(fmt, lump))


def clip(polygon, a, b, c):
    """Keep the part of a convex polygon where a*x + b*y + c >= 0."""
    out = []
    n = len(polygon)
    for i in range(n):
        p, q = polygon[i], polygon[(i + 1) % n]
        dp = a * p[0] + b * p[1] + c
        dq = a * q[0] + b * q[1] + c
        if dp >= 0.0:
            out.append(p)
        if (dp >= 0.0) != (dq >= 0.0):
            t = dp / (dp - dq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return out


def make_watertight(polygons, weld=1e-3):
    """Weld points closer than `weld` into one, then put every point that lies inside another
    polygon's edge (within `weld`) into that edge, in place: T-junctions (a subsector's floor
    edge spanning two of its neighbour's, a wall's foot spanning several floor edges, a lower
    part's top corner on the vertical edge of the wall beside it) leave pixel cracks that the
    rasterizer lets rays through, into rooms no portal leads to. Returns the points inserted and
    the indices of the polygons that got some."""
    cell = 64.0
    welded, grid = [], {}

    def key(p):
        return (int(math.floor(p[0] / cell)), int(math.floor(p[1] / cell)))

    def weld_point(p):
        kx, ky = key(p)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for q in grid.get((kx + dx, ky + dy), ()):
                    if max(abs(p[0] - q[0]), abs(p[1] - q[1]), abs(p[2] - q[2])) <= weld:
                        return q
        grid.setdefault((kx, ky), []).append(p)
        welded.append(p)
        return p

    for polygon in polygons:
        polygon[:] = [weld_point(tuple(float(v) for v in p)) for p in polygon]
    inserted, changed = 0, []
    for index, polygon in enumerate(polygons):
        out = []
        for i, a in enumerate(polygon):
            b = polygon[(i + 1) % len(polygon)]
            out.append(a)
            d = (b[0] - a[0], b[1] - a[1], b[2] - a[2])
            length2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
            if length2 <= weld * weld:
                continue
            cells = set()
            steps = int(math.sqrt(length2) / (cell / 2)) + 1
            for k in range(steps + 1):
                kx, ky = key((a[0] + d[0] * k / steps, a[1] + d[1] * k / steps))
                cells.update((kx + dx, ky + dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1))
            between = []
            for c in cells:
                for q in grid.get(c, ()):
                    if q is a or q is b:
                        continue
                    t = ((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1] + (q[2] - a[2]) * d[2]) \
                        / length2
                    if t <= 0.0 or t >= 1.0:
                        continue
                    e = (a[0] + t * d[0] - q[0], a[1] + t * d[1] - q[1], a[2] + t * d[2] - q[2])
                    if e[0] * e[0] + e[1] * e[1] + e[2] * e[2] <= weld * weld:
                        between.append((t, q))
            between.sort()
            out.extend(q for _, q in between)
            inserted += len(between)
        if len(out) > len(polygon):
            changed.append(index)
        polygon[:] = out
    return inserted, changed


def fan_around_centre(polygons, rooms, kinds, changed):
    """Replaces each polygon of `changed` (convex, with points on its edges) by triangles from its
    centre to each edge, in place. VTK triangulates a polygon itself, and three collinear points
    (an inserted point between two corners) become a needle triangle whose depth is wrong: MAP12
    showed a floor 570 units behind a wall through a one-pixel hole in the wall."""
    changed = set(changed)
    out_polygons, out_rooms, out_kinds = [], [], []
    for index, (polygon, room, kind) in enumerate(zip(polygons, rooms, kinds)):
        if index not in changed:
            out_polygons.append(polygon)
            out_rooms.append(room)
            out_kinds.append(kind)
            continue
        centre = tuple(sum(p[k] for p in polygon) / len(polygon) for k in range(3))
        for i, a in enumerate(polygon):
            out_polygons.append([centre, a, polygon[(i + 1) % len(polygon)]])
            out_rooms.append(room)
            out_kinds.append(kind)
    polygons[:], rooms[:], kinds[:] = out_polygons, out_rooms, out_kinds


def right_of(x0, y0, dx, dy):
    """Half-plane coefficients of the right side of the directed line (x0, y0) + t (dx, dy): the
    front of a node partition and the side of a seg's own sector in Doom."""
    # cross(d, p - p0) <= 0 on the right: -dy (x - x0) + dx (y - y0) <= 0.
    return dy, -dx, -(dy * x0 - dx * y0)


def convert(data, map_name, all_things=False):
    lumps = read_directory(data)
    m = map_lumps(lumps, map_name)
    things = records(m["THINGS"], 10, "<5h", "THINGS")
    linedefs = records(m["LINEDEFS"], 14, "<7H", "LINEDEFS")
    sidedefs = records(m["SIDEDEFS"], 30, "<2h8s8s8sh", "SIDEDEFS")
    vertexes = records(m["VERTEXES"], 4, "<2h", "VERTEXES")
    segs = records(m["SEGS"], 12, "<6H", "SEGS")
    ssectors = records(m["SSECTORS"], 4, "<2H", "SSECTORS")
    nodes = records(m["NODES"], 28, "<4h8h2H", "NODES")
    sectors = records(m["SECTORS"], 26, "<2h8s8s3h", "SECTORS")
    if not sectors or not linedefs or not vertexes:
        raise WadError(f"map {map_name} has no sectors, lines or vertices")
    if not ssectors or not segs:
        raise WadError(f"map {map_name} has no BSP (SSECTORS/SEGS empty: nodes not built?)")
    if len(m["NODES"]) >= 4 and m["NODES"][:4] in (b"XNOD", b"ZNOD", b"XGLN", b"ZGLN"):
        raise WadError(f"map {map_name} has extended nodes ({m['NODES'][:4].decode()}); only "
                       "vanilla nodes are read")

    def sector_of_side(side, what):
        if side >= len(sidedefs):
            raise WadError(f"{what} names sidedef {side} of {len(sidedefs)}")
        sector = sidedefs[side][5]
        if not 0 <= sector < len(sectors):
            raise WadError(f"sidedef {side} names sector {sector} of {len(sectors)}")
        return sector

    floor = [s[0] for s in sectors]
    ceiling = [s[1] for s in sectors]
    light = [max(0, min(255, s[4])) for s in sectors]
    polygons, rooms, kinds = [], [], []  # polygons: lists of (x, y, z)
    portals, portal_rooms = [], []
    closed = 0
    line_sides = []
    for index, (v1, v2, _flags, _special, _tag, front, back) in enumerate(linedefs):
        if v1 >= len(vertexes) or v2 >= len(vertexes):
            raise WadError(f"linedef {index} names vertex {max(v1, v2)} of {len(vertexes)}")
        if front == NO_SIDE and back != NO_SIDE:
            front, back, v1, v2 = back, NO_SIDE, v2, v1  # the left side only: face it the other way
        sa = sector_of_side(front, f"linedef {index}") if front != NO_SIDE else -1
        sb = sector_of_side(back, f"linedef {index}") if back != NO_SIDE else -1
        line_sides.append((sa, sb))
        (x1, y1), (x2, y2) = vertexes[v1], vertexes[v2]
        if sa < 0 or (x1, y1) == (x2, y2):
            continue

        def quad(z0, z1, room, kind):
            if z1 > z0:
                # Each side's parts face into its own sector (the front is on the right of v1 ->
                # v2): the back side's are wound the other way.
                a, b = ((x1, y1), (x2, y2)) if room == sa else ((x2, y2), (x1, y1))
                polygons.append([(*a, z0), (*b, z0), (*b, z1), (*a, z1)])
                rooms.append(room)
                kinds.append((kind, room))

        if sb < 0:
            quad(floor[sa], ceiling[sa], sa, "wall")
            continue
        if sb == sa:
            continue
        top_floor = max(floor[sa], floor[sb])
        low_ceiling = min(ceiling[sa], ceiling[sb])
        # Each side closes its own sector's height range only: the part below the other's floor
        # ("lower") and above its ceiling ("upper"), or all of it where the opening is shut. A
        # closed sector (ceiling <= floor: a shut door, a lift up) has no range and gets nothing.
        for room, other in ((sa, sb), (sb, sa)):
            if low_ceiling <= top_floor:
                quad(floor[room], ceiling[room], room, "upper")
                continue
            quad(floor[room], floor[other], room, "lower")
            quad(ceiling[other], ceiling[room], room, "upper")
        if low_ceiling > top_floor:
            portals.append([(x1, y1, top_floor), (x2, y2, top_floor), (x2, y2, low_ceiling),
                            (x1, y1, low_ceiling)])
            portal_rooms.append((sa, sb))
        else:
            closed += 1

    # Floors and ceilings from the BSP.
    xs = [v[0] for v in vertexes]
    ys = [v[1] for v in vertexes]
    margin = 64.0
    bounds = [(min(xs) - margin, min(ys) - margin), (max(xs) + margin, min(ys) - margin),
              (max(xs) + margin, max(ys) + margin), (min(xs) - margin, max(ys) + margin)]
    seg_sector, seg_plane = [], []
    for index, (v1, v2, _angle, line, direction, _offset) in enumerate(segs):
        if line >= len(linedefs) or v1 >= len(vertexes) or v2 >= len(vertexes):
            raise WadError(f"seg {index} names linedef {line} / vertices {v1}, {v2} out of range")
        lv1, lv2, _f, _s, _t, front, back = linedefs[line]
        side = back if direction else front
        if side == NO_SIDE:
            side = front if direction else back
        if side == NO_SIDE:
            raise WadError(f"seg {index}: linedef {line} has no sidedef")
        seg_sector.append(sector_of_side(side, f"seg {index}"))
        (ax, ay), (bx, by) = vertexes[lv1], vertexes[lv2]
        if direction:
            ax, ay, bx, by = bx, by, ax, ay
        seg_plane.append(right_of(ax, ay, bx - ax, by - ay))
    subsector_polygons = [None] * len(ssectors)
    empty_subsectors = 0
    root = len(nodes) - 1 if nodes else SUBSECTOR_BIT
    stack = [(root, bounds)] if nodes else [(SUBSECTOR_BIT, bounds)]
    visits = 0
    while stack:
        child, polygon = stack.pop()
        visits += 1
        if visits > 4 * (len(nodes) + len(ssectors)) + 8:
            raise WadError("the BSP nodes form a cycle")
        if child & SUBSECTOR_BIT:
            index = child & ~SUBSECTOR_BIT if nodes else 0
            if index >= len(ssectors):
                raise WadError(f"a node names subsector {index} of {len(ssectors)}")
            count, first = ssectors[index]
            if first + count > len(segs) or count == 0:
                raise WadError(f"subsector {index}: segs {first}..{first + count} of {len(segs)}")
            for k in range(first, first + count):
                if len(polygon) < 3:
                    break
                polygon = clip(polygon, *seg_plane[k])
            subsector_polygons[index] = polygon
            continue
        if child >= len(nodes):
            raise WadError(f"a node names node {child} of {len(nodes)}")
        x, y, dx, dy = nodes[child][0:4]
        right, left = nodes[child][12:14]
        a, b, c = right_of(x, y, dx, dy)
        stack.append((right, clip(polygon, a, b, c)))
        stack.append((left, clip(polygon, -a, -b, -c)))
    for index, polygon in enumerate(subsector_polygons):
        if polygon is None or len(polygon) < 3:
            empty_subsectors += 1
            continue
        # Drop repeated points (clips through a vertex), keep the polygon counter-clockwise.
        cleaned = []
        for p in polygon:
            if not cleaned or abs(p[0] - cleaned[-1][0]) + abs(p[1] - cleaned[-1][1]) > 1e-9:
                cleaned.append(p)
        if len(cleaned) > 1 and abs(cleaned[0][0] - cleaned[-1][0]) + abs(
                cleaned[0][1] - cleaned[-1][1]) <= 1e-9:
            cleaned.pop()
        area = sum(cleaned[i][0] * cleaned[(i + 1) % len(cleaned)][1]
                   - cleaned[(i + 1) % len(cleaned)][0] * cleaned[i][1]
                   for i in range(len(cleaned))) / 2.0
        if len(cleaned) < 3 or abs(area) < 1e-6:
            empty_subsectors += 1
            continue
        if area < 0:
            cleaned.reverse()
        sector = seg_sector[ssectors[index][1]]
        if ceiling[sector] <= floor[sector]:
            continue  # a closed sector bounds no volume: its floor and ceiling can only be seen
            # where they touch the walls that close it, through depth ties.
        polygons.append([(x, y, floor[sector]) for x, y in cleaned])  # faces up
        rooms.append(sector)
        kinds.append(("floor", sector))
        polygons.append([(x, y, ceiling[sector]) for x, y in reversed(cleaned)])  # faces down
        rooms.append(sector)
        kinds.append(("ceiling", sector))

    t_junctions, changed = make_watertight(polygons)
    fan_around_centre(polygons, rooms, kinds, changed)

    # Cameras: the sector a thing stands in, found by walking the BSP.
    def sector_at(x, y):
        child = root if nodes else SUBSECTOR_BIT
        for _ in range(len(nodes) + 1):
            if child & SUBSECTOR_BIT:
                index = child & ~SUBSECTOR_BIT if nodes else 0
                return seg_sector[ssectors[index][1]]
            nx, ny, ndx, ndy = nodes[child][0:4]
            a, b, c = right_of(nx, ny, ndx, ndy)
            child = nodes[child][12] if a * x + b * y + c >= 0 else nodes[child][13]
        raise WadError("the BSP nodes form a cycle")

    segments = [(vertexes[v1], vertexes[v2]) for v1, v2, *_ in linedefs]

    def player_fits(x, y, sector):
        # Where a player could stand: the sector at least PLAYER_HEIGHT high and every line at
        # least PLAYER_RADIUS away, so that the near plane (1 unit) never reaches through a wall.
        if ceiling[sector] - floor[sector] < PLAYER_HEIGHT:
            return False
        r = PLAYER_RADIUS
        for (ax, ay), (bx, by) in segments:
            if (x < min(ax, bx) - r or x > max(ax, bx) + r or y < min(ay, by) - r
                    or y > max(ay, by) + r):
                continue
            dx, dy = bx - ax, by - ay
            t = ((x - ax) * dx + (y - ay) * dy) / float(dx * dx + dy * dy or 1)
            t = min(1.0, max(0.0, t))
            if math.hypot(ax + t * dx - x, ay + t * dy - y) < r:
                return False
        return True

    far = 1.05 * math.hypot(max(xs) - min(xs), max(ys) - min(ys)) + max(ceiling) - min(floor)
    cameras, thing_cameras = [], []
    for x, y, angle, kind, _flags in things:
        if kind not in START_TYPES and not all_things:
            continue
        sector = sector_at(x, y)
        if kind not in START_TYPES and not player_fits(x, y, sector):
            continue
        eye = [float(x), float(y), floor[sector] + VIEW_HEIGHT]
        focal = [x + 100.0 * math.cos(math.radians(angle)),
                 y + 100.0 * math.sin(math.radians(angle)), eye[2]]
        camera = {"eye": [round(v, 3) for v in eye], "focal": [round(v, 3) for v in focal],
                  "up": [0, 0, 1], "view_angle": 90, "clipping_range": [1, round(far)]}
        if kind in START_TYPES and camera not in cameras:
            cameras.append(camera)
        if all_things and camera not in thing_cameras:
            thing_cameras.append(camera)
    colours = []
    for kind, room in kinds:
        shade = 0.35 + 0.65 * light[room] / 255.0
        colours.append([int(round(255 * v * shade)) for v in COLOURS[kind]] + [255])
    two_sided = sum(1 for a, b in line_sides if a >= 0 and b >= 0 and a != b)
    return {"polygons": polygons, "rooms": rooms, "colours": colours, "portals": portals,
            "portal_rooms": portal_rooms, "cameras": cameras, "thing_cameras": thing_cameras,
            "sectors": len(sectors),
            "lines": len(linedefs), "two_sided": two_sided, "closed": closed,
            "subsectors": len(ssectors), "empty_subsectors": empty_subsectors,
            "t_junctions": t_junctions}


def write_vtp(path, polygons, cell_arrays):
    """VTK XML PolyData of polygons, appended raw binary (UInt64 byte count, then the bytes).
    cell_arrays: (name, vtk type, struct code, components, flat values)."""
    points = [v for polygon in polygons for p in polygon for v in p]
    offsets, end = [], 0
    for polygon in polygons:
        end += len(polygon)
        offsets.append(end)
    n_points, n_cells = len(points) // 3, len(polygons)
    blocks = [("Points", "Float32", 3, "f", points)]
    blocks += [(name, vtk_type, components, code, values)
               for name, vtk_type, code, components, values in cell_arrays]
    blocks += [("connectivity", "Int32", 1, "i", range(n_points)),
               ("offsets", "Int32", 1, "i", offsets)]
    payload, where = bytearray(), {}
    for name, _type, _components, code, values in blocks:
        values = list(values)
        where[name] = len(payload)
        raw = struct.pack(f"<{len(values)}{code}", *values)
        payload += struct.pack("<Q", len(raw)) + raw

    def array(name, vtk_type, components):
        extra = f' Name="{name}"' if name != "Points" else ""
        return (f'<DataArray type="{vtk_type}"{extra} NumberOfComponents="{components}" '
                f'format="appended" offset="{where[name]}"/>')

    scalars = ' Scalars="Colors"' if any(b[0] == "Colors" for b in blocks) else ""
    header = "\n".join([
        '<?xml version="1.0"?>',
        '<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">',
        "<PolyData>",
        f'<Piece NumberOfPoints="{n_points}" NumberOfVerts="0" NumberOfLines="0" '
        f'NumberOfStrips="0" NumberOfPolys="{n_cells}">',
        f"<CellData{scalars}>"] + [array(b[0], b[1], b[2]) for b in blocks[1:-2]] + [
        "</CellData>",
        "<Points>", array("Points", "Float32", 3), "</Points>",
        "<Polys>", array("connectivity", "Int32", 1), array("offsets", "Int32", 1), "</Polys>",
        "</Piece>", "</PolyData>", '<AppendedData encoding="raw">', "_"])
    with open(path + ".tmp", "wb") as out:
        out.write(header.encode("ascii"))
        out.write(payload)
        out.write(b"\n</AppendedData>\n</VTKFile>\n")
    os.replace(path + ".tmp", path)


def main(argv):
    args = argv[1:]
    if any(a in ("-h", "--help") for a in args):
        print(__doc__)
        return 0
    if len(args) == 2 and args[1] == "--list":
        try:
            with open(args[0], "rb") as f:
                maps = list_maps(read_directory(f.read()))
        except (OSError, WadError) as error:
            print(f"wad-to-portals: {args[0]}: {error}", file=sys.stderr)
            return 1
        for name, n_sectors, n_lines in maps:
            print(f"{name} {n_sectors} sectors {n_lines} lines")
        return 0
    things_path = None
    if len(args) == 7 and args[5] == "--all-things":
        things_path = args[6]
        args = args[:5]
    if len(args) != 5:
        print("wad-to-portals: usage: wad-to-portals.py WAD MAP OUT.vtp OUT-portals.vtp "
              "OUT-cameras.json [--all-things OUT.json] (or WAD --list)", file=sys.stderr)
        return 2
    source, map_name, vtp, portals_vtp, cameras_path = args
    try:
        with open(source, "rb") as f:
            data = f.read()
        scene = convert(data, map_name, things_path is not None)
    except (OSError, WadError, struct.error) as error:
        print(f"wad-to-portals: {source}: {error}", file=sys.stderr)
        return 1
    write_vtp(vtp, scene["polygons"], [
        ("RoomId", "Int32", "i", 1, scene["rooms"]),
        ("Colors", "UInt8", "B", 4, [v for c in scene["colours"] for v in c])])
    write_vtp(portals_vtp, scene["portals"], [
        ("RoomA", "Int32", "i", 1, [a for a, _ in scene["portal_rooms"]]),
        ("RoomB", "Int32", "i", 1, [b for _, b in scene["portal_rooms"]])])
    for path, cameras in ((cameras_path, scene["cameras"]), (things_path, scene["thing_cameras"])):
        if path:
            with open(path + ".tmp", "w") as f:
                json.dump(cameras, f, indent=1)
                f.write("\n")
            os.replace(path + ".tmp", path)
    print(f"wad-to-portals: {source} {map_name.upper()}: {scene['sectors']} rooms (sectors), "
          f"{len(scene['portals'])} portals ({scene['closed']} closed openings of "
          f"{scene['two_sided']} two-sided lines left out), {len(scene['polygons'])} polygons "
          f"from {scene['lines']} lines and {scene['subsectors']} subsectors "
          f"({scene['empty_subsectors']} empty), {scene['t_junctions']} T-junctions closed, "
          f"{len(scene['cameras'])} start cameras"
          + (f", {len(scene['thing_cameras'])} thing cameras" if things_path else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

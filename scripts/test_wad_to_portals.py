#!/usr/bin/env python3
"""Tests of scripts/wad-to-portals.py on a tiny Doom map built here (standard library only):
three sectors in a row: a room (floor 0, ceiling 128), a lower-ceiling room with a raised floor
(16, 96) joined to it by an open two-sided line, and a shut door (16, 16) behind a closed one;
a BSP of two nodes and three subsectors; player and deathmatch starts. The model is watertight
(no T-junctions) and the shut door, a closed sector, has no polygon. And bad input (wrong magic,
a truncated file, a missing map, a Hexen map, extended nodes, a line naming a missing vertex)
refused with one line and exit code 1.

    python3 scripts/test_wad_to_portals.py [-v]
"""
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "wad-to-portals.py")
NONE = 0xFFFF

VERTEXES = [(0, 0), (128, 0), (256, 0), (288, 0), (288, 128), (256, 128), (128, 128), (0, 128)]
# (v1, v2, front sidedef, back sidedef): each sector on the right of its lines.
LINEDEFS = [(0, 7, 0, NONE), (7, 6, 1, NONE), (1, 0, 2, NONE), (1, 6, 3, 4), (6, 5, 5, NONE),
            (2, 1, 6, NONE), (2, 5, 7, 8), (5, 4, 9, NONE), (4, 3, 10, NONE), (3, 2, 11, NONE)]
SIDE_SECTORS = [0, 0, 0, 1, 0, 1, 1, 2, 1, 2, 2, 2]
SECTORS = [(0, 128, 160), (16, 96, 200), (16, 16, 128)]  # floor, ceiling, light
# (v1, v2, linedef, direction) per subsector.
SUBSECTORS = [[(0, 7, 0, 0), (7, 6, 1, 0), (6, 1, 3, 1), (1, 0, 2, 0)],
              [(1, 6, 3, 0), (6, 5, 4, 0), (5, 2, 6, 1), (2, 1, 5, 0)],
              [(2, 5, 6, 0), (5, 4, 7, 0), (4, 3, 8, 0), (3, 2, 9, 0)]]
# x, y, dx, dy, then right and left children: node 0 splits sector 1 from 2 at x = 256, node 1
# (the root, last) splits sector 0 from the rest at x = 128. The right side is the front.
NODES = [(256, 0, 0, 128, 0x8002, 0x8001), (128, 0, 0, 128, 0, 0x8000)]
THINGS = [(64, 64, 0, 1), (64, 64, 0, 2), (192, 64, 90, 11), (64, 32, 0, 3004)]


def lump_data():
    segs, ssectors = b"", b""
    for subsector in SUBSECTORS:
        ssectors += struct.pack("<2H", len(subsector), len(segs) // 12)
        for v1, v2, line, direction in subsector:
            segs += struct.pack("<6H", v1, v2, 0, line, direction, 0)
    nodes = b"".join(struct.pack("<4h8h2H", x, y, dx, dy, *([0] * 8), right, left)
                     for x, y, dx, dy, right, left in NODES)
    return [
        ("THINGS", b"".join(struct.pack("<5h", x, y, a, t, 7) for x, y, a, t in THINGS)),
        ("LINEDEFS", b"".join(struct.pack("<7H", v1, v2, 1 if back == NONE else 4, 0, 0,
                                          front, back) for v1, v2, front, back in LINEDEFS)),
        ("SIDEDEFS", b"".join(struct.pack("<2h8s8s8sh", 0, 0, b"-", b"-", b"-", s)
                              for s in SIDE_SECTORS)),
        ("VERTEXES", b"".join(struct.pack("<2h", x, y) for x, y in VERTEXES)),
        ("SEGS", segs),
        ("SSECTORS", ssectors),
        ("NODES", nodes),
        ("SECTORS", b"".join(struct.pack("<2h8s8s3h", f, c, b"FLAT", b"CEIL", light, 0, 0)
                             for f, c, light in SECTORS)),
        ("REJECT", b""),
        ("BLOCKMAP", b""),
    ]


def tiny_wad(lumps=None, marker="MAP01", magic=b"PWAD"):
    lumps = [(marker, b"")] + (lumps if lumps is not None else lump_data())
    body, directory = b"", b""
    for name, data in lumps:
        directory += struct.pack("<ii8s", 12 + len(body), len(data), name.encode())
        body += data
    return magic + struct.pack("<ii", len(lumps), 12 + len(body)) + body + directory


def read_vtp(path):
    """The appended raw arrays of the converter's .vtp, by name (enough to check it)."""
    with open(path, "rb") as f:
        data = f.read()
    head, _, payload = data.partition(b'<AppendedData encoding="raw">\n_')
    arrays = {}
    for match in re.finditer(rb'<DataArray type="(\w+)"(?: Name="(\w+)")? NumberOfComponents='
                             rb'"(\d)" format="appended" offset="(\d+)"/>', head):
        kind, name, offset = match.group(1), match.group(2) or b"Points", int(match.group(4))
        size = struct.unpack_from("<Q", payload, offset)[0]
        code = {b"Float32": "f", b"Int32": "i", b"UInt8": "B"}[kind]
        count = size // struct.calcsize(code)
        arrays[name.decode()] = struct.unpack_from(f"<{count}{code}", payload, offset + 8)
    return head.decode("ascii"), arrays


def polygons(arrays):
    points = arrays["Points"]
    out, start = [], 0
    for end in arrays["offsets"]:
        out.append([tuple(points[3 * i:3 * i + 3]) for i in arrays["connectivity"][start:end]])
        start = end
    return out


def area_xy(polygon):
    return sum(p[0] * q[1] - q[0] * p[1]
               for p, q in zip(polygon, polygon[1:] + polygon[:1])) / 2.0


def area_3d(polygon):
    n = [0.0, 0.0, 0.0]
    for p, q in zip(polygon, polygon[1:] + polygon[:1]):
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    return sum(v * v for v in n) ** 0.5 / 2.0


class ConverterTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)

    def path(self, name):
        return os.path.join(self.dir.name, name)

    def convert(self, data, map_name="MAP01"):
        with open(self.path("map.wad"), "wb") as f:
            f.write(data)
        return subprocess.run([sys.executable, SCRIPT, self.path("map.wad"), map_name,
                               self.path("map.vtp"), self.path("portals.vtp"),
                               self.path("cameras.json")], capture_output=True, text=True)

    def test_converts_rooms_portals_and_cameras(self):
        result = self.convert(tiny_wad())
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("3 rooms (sectors), 1 portals (1 closed openings of 2 two-sided lines",
                      result.stdout)
        head, arrays = read_vtp(self.path("map.vtp"))
        model = polygons(arrays)
        rooms = arrays["RoomId"]
        # Walls: 3 of room 0; the open line's lower (0..16) and upper (96..128) parts face room 0;
        # 2 of room 1; the shut door's line closes room 1 (16..96); the door itself, a closed
        # sector, has no walls, floor or ceiling. Then a floor and a ceiling per subsector of
        # rooms 0 and 1. The two walls of room 0 beside the open line get the corners of its
        # lower and upper parts (no T-junctions) and are written as 6 triangles each: 22 cells.
        self.assertIn('NumberOfPolys="22"', head)
        walls = [(r, p) for r, p in zip(rooms, model) if len(set(q[2] for q in p)) > 1]
        self.assertEqual(sorted(set(r for r, _ in walls)), [0, 1])
        for room, area in ((0, 3 * 128 * 128 + 128 * 16 + 128 * 32), (1, 3 * 128 * 80)):
            self.assertAlmostEqual(sum(area_3d(p) for r, p in walls if r == room), area, places=2)
        spans = sorted((r, min(q[2] for q in p), max(q[2] for q in p), p[0][0]) for r, p in walls
                       if p[0][0] == p[1][0] and p[0][0] in (128, 256))
        self.assertEqual(spans, [(0, 0, 16, 128), (0, 96, 128, 128), (1, 16, 96, 256)])
        flats = [(r, p) for r, p in zip(rooms, model) if len(set(q[2] for q in p)) == 1]
        self.assertEqual(len(flats), 4)
        for room, polygon in flats:
            floor, ceiling, _ = SECTORS[room]
            width = {0: 128, 1: 128}[room]
            up = polygon[0][2] == floor and area_xy(polygon) > 0
            down = polygon[0][2] == ceiling and area_xy(polygon) < 0
            self.assertTrue(up or down, (room, polygon))  # floors face up, ceilings down
            self.assertAlmostEqual(abs(area_xy(polygon)), width * 128, places=3)
        self.assertEqual(len(arrays["Colors"]), 4 * 22)
        head, arrays = read_vtp(self.path("portals.vtp"))
        self.assertIn('NumberOfPolys="1"', head)
        (portal,) = polygons(arrays)
        self.assertEqual(sorted(portal), [(128, 0, 16), (128, 0, 96), (128, 128, 16),
                                          (128, 128, 96)])
        self.assertEqual((arrays["RoomA"], arrays["RoomB"]), ((1,), (0,)))
        with open(self.path("cameras.json")) as f:
            cameras = json.load(f)
        self.assertEqual(len(cameras), 2)  # player 2 starts where player 1 does
        self.assertEqual(cameras[0]["eye"], [64, 64, 41])
        self.assertEqual(cameras[0]["focal"], [164, 64, 41])
        self.assertEqual(cameras[1]["eye"], [192, 64, 57])
        self.assertAlmostEqual(cameras[1]["focal"][0], 192, places=3)
        self.assertEqual(cameras[1]["focal"][1:], [164, 57])
        self.assertEqual(cameras[1]["up"], [0, 0, 1])
        self.assertEqual(cameras[1]["view_angle"], 90)
        self.assertEqual(cameras[1]["clipping_range"][0], 1)

    def test_walls_face_into_their_sector(self):
        # A portal generator tells air from solid by the side polygons face: the back side's
        # lower and upper parts of a two-sided line must face their own sector too (they used to
        # be wound like the front side's, toward the void under or over the other sector).
        self.assertEqual(self.convert(tiny_wad()).returncode, 0)
        _, arrays = read_vtp(self.path("map.vtp"))
        model = polygons(arrays)
        centre = {}
        for room, polygon in zip(arrays["RoomId"], model):
            if len(set(q[2] for q in polygon)) == 1:  # a flat: the room's middle in x and y
                xs, ys = [q[0] for q in polygon], [q[1] for q in polygon]
                centre.setdefault(room, ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2))
        walls = 0
        for room, polygon in zip(arrays["RoomId"], model):
            if len(set(q[2] for q in polygon)) == 1:
                continue
            n = [0.0, 0.0]
            for p, q in zip(polygon, polygon[1:] + polygon[:1]):  # Newell, x and y only
                n[0] += (p[1] - q[1]) * (p[2] + q[2])
                n[1] += (p[2] - q[2]) * (p[0] + q[0])
            mx = sum(q[0] for q in polygon) / len(polygon)
            my = sum(q[1] for q in polygon) / len(polygon)
            cx, cy = centre[room]
            self.assertGreater(n[0] * (cx - mx) + n[1] * (cy - my), 0.0, (room, polygon))
            walls += 1
        self.assertGreater(walls, 0)

    def test_closed_sector_bounds_nothing(self):
        # MAP12 lost 15 pixels of 8 shut doors to the ID buffer: a closed sector's floor and
        # ceiling lie on the edge where the walls that close it meet, and depth ties showed them
        # there, with no portal leading to them. A closed sector has no polygon at all.
        self.assertEqual(self.convert(tiny_wad()).returncode, 0)
        _, arrays = read_vtp(self.path("map.vtp"))
        self.assertNotIn(2, arrays["RoomId"])
        # Each room's walls stay within its own height range (nothing hangs below its floor).
        for room, polygon in zip(arrays["RoomId"], polygons(arrays)):
            floor, ceiling, _ = SECTORS[room]
            self.assertTrue(all(floor <= p[2] <= ceiling for p in polygon), (room, polygon))

    def test_watertight(self):
        # MAP12 lost 6 pixels through T-junctions (a floor edge spanning two of its neighbour's,
        # a wall's foot on a longer floor edge): no point of a polygon may lie inside another
        # polygon's edge, so that every edge is drawn from the same two points on both sides.
        result = self.convert(tiny_wad())
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(result.stdout, r" [1-9][0-9]* T-junctions closed")
        model = polygons(read_vtp(self.path("map.vtp"))[1])
        # And no three collinear points in a cell: VTK would triangulate them into a needle
        # triangle with wrong depths (a one-pixel hole in a MAP12 wall).
        for polygon in model:
            for a, b, c in zip(polygon, polygon[1:] + polygon[:1], polygon[2:] + polygon[:2]):
                self.assertGreater(area_3d([a, b, c]), 1e-6, polygon)
        points = {p for polygon in model for p in polygon}
        for polygon in model:
            for a, b in zip(polygon, polygon[1:] + polygon[:1]):
                d = [b[k] - a[k] for k in range(3)]
                length2 = sum(v * v for v in d)
                for q in points:
                    t = sum((q[k] - a[k]) * d[k] for k in range(3)) / length2
                    off = sum((a[k] + t * d[k] - q[k]) ** 2 for k in range(3))
                    self.assertFalse(1e-9 < t < 1 - 1e-9 and off < 1e-12,
                                     f"{q} lies inside the edge {a}-{b} of {polygon}")

    def test_all_things(self):
        with open(self.path("map.wad"), "wb") as f:
            f.write(tiny_wad())
        result = subprocess.run([sys.executable, SCRIPT, self.path("map.wad"), "MAP01",
                                 self.path("map.vtp"), self.path("portals.vtp"),
                                 self.path("cameras.json"), "--all-things",
                                 self.path("things.json")], capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stderr)
        # The monster at (64, 32) stands in room 0, 32 units from its wall: kept. The deathmatch
        # start stands in a room 80 high: kept (starts are always cameras).
        self.assertIn("2 start cameras, 3 thing cameras", result.stdout)
        with open(self.path("things.json")) as f:
            cameras = json.load(f)
        self.assertEqual([c["eye"] for c in cameras], [[64, 64, 41], [192, 64, 57], [64, 32, 41]])
        # Moved to 10 units from the wall, it is left out (the near plane could reach through).
        lumps = lump_data()
        things = bytearray(lumps[0][1])
        struct.pack_into("<h", things, 10 * 3 + 2, 10)
        lumps[0] = ("THINGS", bytes(things))
        with open(self.path("map.wad"), "wb") as f:
            f.write(tiny_wad(lumps))
        result = subprocess.run([sys.executable, SCRIPT, self.path("map.wad"), "MAP01",
                                 self.path("map.vtp"), self.path("portals.vtp"),
                                 self.path("cameras.json"), "--all-things",
                                 self.path("things.json")], capture_output=True, text=True)
        self.assertIn("2 start cameras, 2 thing cameras", result.stdout)

    def test_list(self):
        with open(self.path("map.wad"), "wb") as f:
            f.write(tiny_wad())
        result = subprocess.run([sys.executable, SCRIPT, self.path("map.wad"), "--list"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout, "MAP01 3 sectors 10 lines\n")

    def assertRefused(self, data, message, map_name="MAP01"):
        result = self.convert(data, map_name)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr.count("\n"), 1, result.stderr)
        self.assertIn(message, result.stderr)
        self.assertFalse(os.path.exists(self.path("map.vtp")))

    def test_wrong_magic(self):
        self.assertRefused(tiny_wad(magic=b"IBSP"), "not a WAD")

    def test_truncated(self):
        self.assertRefused(tiny_wad()[:-20], "outside the")
        self.assertRefused(tiny_wad()[:8], "too short")

    def test_missing_map(self):
        self.assertRefused(tiny_wad(), "no map E1M1 in the WAD (maps: MAP01)", "E1M1")

    def test_hexen_map(self):
        self.assertRefused(tiny_wad(lump_data() + [("BEHAVIOR", b"ACS\0")]), "Hexen format")

    def test_extended_nodes(self):
        lumps = [(n, b"XNOD" + b"\0" * 24 if n == "NODES" else d) for n, d in lump_data()]
        self.assertRefused(tiny_wad(lumps), "extended nodes (XNOD)")

    def test_line_naming_a_missing_vertex(self):
        lumps = lump_data()
        lines = bytearray(lumps[1][1])
        struct.pack_into("<H", lines, 14 * 4, 500)
        lumps[1] = ("LINEDEFS", bytes(lines))
        self.assertRefused(tiny_wad(lumps), "linedef 4 names vertex 500 of 8")

    def test_usage(self):
        result = subprocess.run([sys.executable, SCRIPT, "only-one-argument"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("usage", result.stderr)


if __name__ == "__main__":
    unittest.main()

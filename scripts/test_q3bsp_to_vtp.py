#!/usr/bin/env python3
"""Tests of scripts/q3bsp-to-vtp.py on a tiny Quake-3 BSP built here (standard library only):
one quad (polygon), one 3 x 3 Bezier patch, one sky quad, one face of a door (model 1), a
billboard and two spawn points; and bad input (wrong magic, truncated file, a lump outside the
file, a face naming a missing vertex) refused with one line and exit code 1.

    python3 scripts/test_q3bsp_to_vtp.py [-v]
"""
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "q3bsp-to-vtp.py")


def vertex(x, y, z, normal=(0.0, 0.0, 1.0)):
    return struct.pack("<3f2f2f3f4B", x, y, z, 0, 0, 0, 0, *normal, 128, 128, 128, 255)


def face(texture, kind, first, count, first_mv=0, count_mv=0, size=(0, 0), normal=(0, 0, 1)):
    return struct.pack("<12i12f2i", texture, -1, kind, first, count, first_mv, count_mv, 0,
                       0, 0, 0, 0, *([0.0] * 9), *normal, *size)


def tiny_bsp():
    entities = (b'{\n"classname" "worldspawn"\n}\n'
                b'{\n"classname" "info_player_deathmatch"\n"origin" "10 20 30"\n"angle" "90"\n}\n'
                b'{\n"classname" "team_CTF_bluespawn"\n"origin" "-5 0 0"\n}\n'
                b'{\n"classname" "team_CTF_blueplayer"\n"origin" "-5 0 0"\n}\n'
                b'{\n"classname" "item_health"\n"origin" "1 1 1"\n}\n\0')
    textures = b"".join(struct.pack("<64sii", name, flags, contents) for name, flags, contents in [
        (b"textures/base_wall/concrete", 0, 1), (b"textures/skies/sky", 0x4, 1)])
    vertexes = b"".join([
        vertex(0, 0, 0), vertex(64, 0, 0), vertex(64, 64, 0), vertex(0, 64, 0),   # quad, 0..3
        *[vertex(x * 32, 100 + y * 32, (x == 1) * 32) for y in range(3) for x in range(3)],  # 4..12
        vertex(0, 0, 500), vertex(64, 0, 500), vertex(64, 64, 500),               # sky, 13..15
        vertex(0, 0, 100), vertex(0, 64, 100), vertex(0, 64, 164),                # door, 16..18
        vertex(5, 5, 5)])                                                         # flare, 19
    # Quake 3 winds its triangles clockwise seen from the front: for a +z normal, 0 2 1.
    meshverts = struct.pack("<12i", 0, 2, 1, 0, 3, 2, 0, 2, 1, 0, 2, 1)
    faces = b"".join([
        face(0, 1, 0, 4, 0, 6),
        face(0, 2, 4, 9, size=(3, 3)),
        face(1, 1, 13, 3, 6, 3),
        face(0, 4, 19, 1),
        face(0, 1, 16, 3, 9, 3, normal=(1, 0, 0))])
    models = struct.pack("<6f4i", -1, -1, -1, 100, 200, 600, 0, 4, 0, 0) + \
        struct.pack("<6f4i", 0, 0, 100, 0, 64, 164, 4, 1, 0, 0)
    lumps = [b""] * 17
    lumps[0], lumps[1], lumps[7] = entities, textures, models
    lumps[10], lumps[11], lumps[13] = vertexes, meshverts, faces
    header = bytearray(b"IBSP" + struct.pack("<i", 46) + b"\0" * (17 * 8))
    body, offset = b"", len(header)
    for index, lump in enumerate(lumps):
        struct.pack_into("<ii", header, 8 + 8 * index, offset + len(body), len(lump))
        body += lump
    return bytes(header) + body


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


class ConverterTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)

    def path(self, name):
        return os.path.join(self.dir.name, name)

    def convert(self, data, *extra):
        with open(self.path("map.bsp"), "wb") as f:
            f.write(data)
        return subprocess.run([sys.executable, SCRIPT, self.path("map.bsp"), self.path("map.vtp"),
                               self.path("cameras.json"), *extra], capture_output=True, text=True)

    def test_converts_world_surfaces_and_spawn_cameras(self):
        result = self.convert(tiny_bsp(), "--patch-level", "2")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("10 triangles, 2 surfaces of 5", result.stdout)
        self.assertIn("1 sky (SURF_SKY)", result.stdout)
        self.assertIn("1 billboards", result.stdout)
        self.assertIn("1 brush models other than the world", result.stdout)
        head, arrays = read_vtp(self.path("map.vtp"))
        self.assertIn('NumberOfPolys="10"', head)
        # The quad's 2 triangles are part 0; the patch at level 2: 4 x 2 triangles, part 1.
        self.assertEqual(arrays["PartId"], (0, 0) + (1,) * 8)
        self.assertEqual(arrays["offsets"], tuple(range(3, 31, 3)))
        points = arrays["Points"]
        self.assertEqual(len(points), 3 * (4 + 9))  # the patch: a 3 x 3 grid
        # Counter-clockwise seen from +z (the quad's front): positive signed area.
        a, b, c = (points[3 * i:3 * i + 3] for i in arrays["connectivity"][0:3])
        self.assertGreater((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0)
        # The patch passes through its corners and rises to half its middle control row.
        self.assertEqual(max(points[2::3]), 16.0)
        self.assertEqual(len(arrays["Colors"]), 4 * 10)
        self.assertTrue(all(alpha == 255 for alpha in arrays["Colors"][3::4]))
        with open(self.path("cameras.json")) as f:
            cameras = json.load(f)
        self.assertEqual(len(cameras), 2)  # the blue player start shares the blue spawn's place
        self.assertEqual(cameras[0]["eye"], [10, 20, 56])
        self.assertAlmostEqual(cameras[0]["focal"][0], 10, places=3)
        self.assertAlmostEqual(cameras[0]["focal"][1], 120, places=3)
        self.assertEqual(cameras[0]["up"], [0, 0, 1])
        self.assertAlmostEqual(cameras[0]["view_angle"], 73.7398, places=3)
        self.assertEqual(cameras[1]["focal"], [95, 0, 26])

    def assertRefused(self, data, message):
        result = self.convert(data)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr.count("\n"), 1, result.stderr)
        self.assertIn(message, result.stderr)
        self.assertFalse(os.path.exists(self.path("map.vtp")))

    def test_wrong_magic(self):
        self.assertRefused(b"VBSP" + tiny_bsp()[4:], "not a Quake-3 BSP")

    def test_wrong_version(self):
        data = bytearray(tiny_bsp())
        struct.pack_into("<i", data, 4, 47)
        self.assertRefused(bytes(data), "version 47")

    def test_truncated(self):
        self.assertRefused(tiny_bsp()[:-100], "outside the")
        self.assertRefused(tiny_bsp()[:50], "too short")

    def test_face_naming_a_missing_vertex(self):
        data = bytearray(tiny_bsp())
        faces_offset = struct.unpack_from("<i", data, 8 + 8 * 13)[0]
        struct.pack_into("<i", data, faces_offset + 12, 1000)  # the quad's first vertex
        self.assertRefused(bytes(data), "face 0: vertices 1000")

    def test_usage(self):
        result = subprocess.run([sys.executable, SCRIPT, "only-one-argument"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("usage", result.stderr)


if __name__ == "__main__":
    unittest.main()

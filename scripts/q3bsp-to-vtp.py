#!/usr/bin/env python3
"""Converts a Quake-3 level (.bsp, "IBSP" version 46) into a SceneVis scene: a VTK XML PolyData
file with one part per drawn surface, and a camera file with one camera per spawn point.

    python3 scripts/q3bsp-to-vtp.py MAP.bsp OUT.vtp OUT-cameras.json [--patch-level N]

OUT.vtp: the world's surfaces as triangles, with the cell arrays
  PartId  (Int32) the surface's index in the BSP's faces lump: one surface = one part (actor)
  Colors  (UInt8 RGBA, opaque) a colour per texture (hashed from its name) times the surface's
          baked vertex lighting, so that pictures of the level are readable
and point normals from the BSP's vertices. Appended raw binary (header_type UInt64), which VTK 9.1's
vtkXMLPolyDataReader reads. Polygons and meshes (face types 1 and 3) are the triangles of their
mesh vertices; Bezier patches (type 2: a grid of 3 x 3 biquadratic patches) are tessellated at a
fixed level (--patch-level, default 4: 32 triangles per 3 x 3 patch; the game tessellates them
adaptively, at about that density on a typical curve). Triangles are written counter-clockwise
seen from the front (Quake 3 winds them clockwise).

Left out, with the count of each reason printed:
  - billboards (flares, type 4) and surfaces without triangles;
  - the surfaces of brush models other than model 0 (doors, lifts, platforms, moving or
    animated: the world alone is the static level, so doors are open);
  - sky (SURF_SKY 0x4; the sky box is drawn behind everything) and SURF_NODRAW (0x80: caulk,
    clip, trigger brushes);
  - fog volumes (CONTENTS_FOG 0x40), triggers (CONTENTS_TRIGGER 0x40000000), and see-through
    surfaces (CONTENTS_TRANSLUCENT 0x20000000: water, glass, beams, alpha-tested grates and
    wires): they never hide anything in the game, so keeping them as opaque surfaces would let
    occlusion culling hide what a player sees through them.

OUT-cameras.json: the format of `scenevis --cameras`. One camera per spawn point of the entities
lump (info_player_deathmatch, info_player_start, team_CTF_redspawn/bluespawn, team_CTF_redplayer/
blueplayer), in the order of the lump, each place and direction once: eye at the spawn origin + 26 (Quake 3's view height,
z up), looking horizontally along its "angle" (yaw, degrees; or the yaw of "angles"), up +z,
and the game's 90-degree horizontal field of view at 4:3 (800 x 600): view_angle = 2 atan(tan 45
* 600 / 800) = 73.74 degrees vertically.

A file that is not a version-46 IBSP, or whose lumps lie outside it, is refused with one line on
stderr and exit code 1; usage errors exit 2. Python 3 standard library only.
"""
import json
import math
import os
import struct
import sys
import zlib

SURF_SKY = 0x4
SURF_NODRAW = 0x80
CONTENTS_FOG = 0x40
CONTENTS_TRANSLUCENT = 0x20000000
CONTENTS_TRIGGER = 0x40000000

FACE_POLYGON, FACE_PATCH, FACE_MESH, FACE_BILLBOARD = 1, 2, 3, 4
LUMP_ENTITIES, LUMP_TEXTURES, LUMP_MODELS = 0, 1, 7
LUMP_VERTEXES, LUMP_MESHVERTS, LUMP_FACES = 10, 11, 13
VERTEX_SIZE, FACE_SIZE, TEXTURE_SIZE, MODEL_SIZE = 44, 104, 72, 40

SPAWN_CLASSES = ("info_player_deathmatch", "info_player_start", "team_CTF_redspawn",
                 "team_CTF_bluespawn", "team_CTF_redplayer", "team_CTF_blueplayer")
VIEW_HEIGHT = 26.0
VIEW_ANGLE = 2.0 * math.degrees(math.atan(math.tan(math.radians(45.0)) * 600.0 / 800.0))


class BspError(Exception):
    pass


def read_lumps(data):
    if len(data) < 8 + 17 * 8:
        raise BspError(f"too short for a Quake-3 BSP header ({len(data)} bytes)")
    magic, version = data[:4], struct.unpack_from("<i", data, 4)[0]
    if magic != b"IBSP" or version != 46:
        raise BspError(f"not a Quake-3 BSP (magic {magic!r}, version {version}; "
                       "expected b'IBSP', 46)")
    lumps = []
    for index in range(17):
        offset, length = struct.unpack_from("<ii", data, 8 + 8 * index)
        if offset < 0 or length < 0 or offset + length > len(data):
            raise BspError(f"lump {index} ({offset}, {length} bytes) lies outside the "
                           f"{len(data)}-byte file (truncated?)")
        lumps.append(data[offset:offset + length])
    return lumps


def records(lump, size, fmt, what):
    if len(lump) % size:
        raise BspError(f"the {what} lump ({len(lump)} bytes) is not a multiple of {size}")
    return list(struct.iter_unpack(fmt, lump))


def parse_entities(text):
    """The entities lump: { "key" "value" ... } blocks -> a list of dicts."""
    entities, current, tokens = [], None, []
    i = 0
    while i < len(text):
        c = text[i]
        if c == '"':
            end = text.find('"', i + 1)
            if end < 0:
                break
            tokens.append(text[i + 1:end])
            i = end + 1
            continue
        if c == "{":
            current, tokens = {}, []
        elif c == "}" and current is not None:
            for k in range(0, len(tokens) - 1, 2):
                current[tokens[k]] = tokens[k + 1]
            entities.append(current)
            current, tokens = None, []
        i += 1
    return entities


def spawn_cameras(entities):
    cameras = []
    for entity in entities:
        if entity.get("classname") not in SPAWN_CLASSES or "origin" not in entity:
            continue
        try:
            x, y, z = (float(v) for v in entity["origin"].split())
            yaw = float(entity["angle"]) if "angle" in entity else (
                float(entity["angles"].split()[1]) if "angles" in entity else 0.0)
        except ValueError:
            continue
        eye = [x, y, z + VIEW_HEIGHT]
        focal = [x + 100.0 * math.cos(math.radians(yaw)), y + 100.0 * math.sin(math.radians(yaw)),
                 eye[2]]
        camera = {"eye": [round(v, 3) for v in eye], "focal": [round(v, 3) for v in focal],
                  "up": [0, 0, 1], "view_angle": round(VIEW_ANGLE, 4)}
        if camera not in cameras:  # CTF maps often put a team's first spawn on a spawn point
            cameras.append(camera)
    return cameras


def bezier3(a, b, c, t):
    s = 1.0 - t
    return [s * s * a[k] + 2.0 * s * t * b[k] + t * t * c[k] for k in range(len(a))]


def tessellate_patch(control, width, height, level):
    """A width x height control grid of biquadratic patches -> (points, normals, triangles) on one
    shared grid of ((width-1)/2*level+1) x ((height-1)/2*level+1) points (no seams inside)."""
    pu, pv = (width - 1) // 2, (height - 1) // 2
    cols, rows = pu * level + 1, pv * level + 1
    points, normals = [], []
    for row in range(rows):
        patch_v = min(row // level, pv - 1)
        v = (row - patch_v * level) / level
        for col in range(cols):
            patch_u = min(col // level, pu - 1)
            u = (col - patch_u * level) / level
            curve = []
            for j in range(3):
                base = (2 * patch_v + j) * width + 2 * patch_u
                curve.append(bezier3(control[base], control[base + 1], control[base + 2], u))
            p = bezier3(curve[0], curve[1], curve[2], v)
            points.append(p[0:3])
            normals.append(p[3:6])
    triangles = []
    for row in range(rows - 1):
        for col in range(cols - 1):
            a = row * cols + col
            b, c, d = a + 1, a + cols, a + cols + 1
            triangles.append((a, c, b))
            triangles.append((b, c, d))
    return points, normals, triangles


def texture_colour(name):
    h = zlib.crc32(name.encode("latin-1"))
    # A muted, distinct colour per texture: hue from the hash, medium saturation.
    hue = (h % 360) / 60.0
    x = 1.0 - abs(hue % 2.0 - 1.0)
    r, g, b = [(1, x, 0), (x, 1, 0), (0, 1, x), (0, x, 1), (x, 0, 1), (1, 0, x)][int(hue) % 6]
    return [0.45 + 0.45 * r, 0.45 + 0.45 * g, 0.45 + 0.45 * b]


def convert(data, patch_level):
    lumps = read_lumps(data)
    textures = [(raw.split(b"\0")[0].decode("latin-1"), flags, contents)
                for raw, flags, contents in records(lumps[LUMP_TEXTURES], TEXTURE_SIZE, "<64sii",
                                                    "textures")]
    models = records(lumps[LUMP_MODELS], MODEL_SIZE, "<6f4i", "models")
    vertexes = records(lumps[LUMP_VERTEXES], VERTEX_SIZE, "<3f2f2f3f4B", "vertexes")
    meshverts = records(lumps[LUMP_MESHVERTS], 4, "<i", "meshverts")
    faces = records(lumps[LUMP_FACES], FACE_SIZE, "<12i12f2i", "faces")
    if not models:
        raise BspError("no models (the world is model 0)")
    world = range(models[0][6], models[0][6] + models[0][7])

    points, normals, connectivity, part_ids, colours = [], [], [], [], []
    skipped = {}
    winding_checked = [0, 0]  # triangles facing along / against the face normal (planar faces)

    def skip(reason):
        skipped[reason] = skipped.get(reason, 0) + 1

    for index, face in enumerate(faces):
        texture, _effect, kind, first, count, first_mv, count_mv = face[0:7]
        size = face[24:26]
        if index not in world:
            skip("brush models other than the world (doors, lifts, platforms)")
            continue
        if kind == FACE_BILLBOARD:
            skip("billboards (flares)")
            continue
        if not 0 <= texture < len(textures):
            raise BspError(f"face {index} names texture {texture} of {len(textures)}")
        name, flags, contents = textures[texture]
        if flags & SURF_SKY:
            skip("sky (SURF_SKY)")
            continue
        if flags & SURF_NODRAW:
            skip("not drawn (SURF_NODRAW)")
            continue
        if contents & CONTENTS_FOG:
            skip("fog volumes (CONTENTS_FOG)")
            continue
        if contents & CONTENTS_TRIGGER:
            skip("triggers (CONTENTS_TRIGGER)")
            continue
        if contents & CONTENTS_TRANSLUCENT:
            skip("see-through (CONTENTS_TRANSLUCENT: water, glass, beams, grates)")
            continue
        if first < 0 or count < 0 or first + count > len(vertexes):
            raise BspError(f"face {index}: vertices {first}..{first + count} of {len(vertexes)}")
        base = len(points)
        if kind in (FACE_POLYGON, FACE_MESH):
            if first_mv < 0 or count_mv < 0 or first_mv + count_mv > len(meshverts) or count_mv % 3:
                raise BspError(f"face {index}: mesh vertices {first_mv}..{first_mv + count_mv} "
                               f"of {len(meshverts)}")
            local_points = [vertexes[first + k][0:3] for k in range(count)]
            local_normals = [vertexes[first + k][7:10] for k in range(count)]
            triangles = []
            for k in range(first_mv, first_mv + count_mv, 3):
                a, b, c = meshverts[k][0], meshverts[k + 1][0], meshverts[k + 2][0]
                if not (0 <= a < count and 0 <= b < count and 0 <= c < count):
                    raise BspError(f"face {index}: mesh vertex out of its {count} vertices")
                triangles.append((a, c, b))  # clockwise in Quake 3 -> counter-clockwise
            if kind == FACE_POLYGON and triangles:
                a, b, c = (local_points[v] for v in triangles[0])
                n = [(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                     (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                     (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])]
                along = sum(n[k] * face[21 + k] for k in range(3))
                winding_checked[0 if along >= 0 else 1] += 1
        elif kind == FACE_PATCH:
            width, height = size
            if width < 3 or height < 3 or width % 2 == 0 or height % 2 == 0 or width * height != count:
                raise BspError(f"face {index}: patch of {width} x {height} control points "
                               f"({count} vertices)")
            control = [vertexes[first + k][0:3] + vertexes[first + k][7:10] for k in range(count)]
            local_points, local_normals, triangles = tessellate_patch(control, width, height,
                                                                      patch_level)
        else:
            skip(f"unknown surface type {kind}")
            continue
        if not triangles:
            skip("surfaces without triangles")
            continue
        points.extend(local_points)
        normals.extend(local_normals)
        for a, b, c in triangles:
            connectivity.extend((base + a, base + b, base + c))
        # Baked lighting: the mean vertex colour of the surface, kept away from black.
        light = [0.0, 0.0, 0.0]
        for k in range(count):
            for j in range(3):
                light[j] += vertexes[first + k][10 + j]
        light = [min(1.0, 0.35 + 0.65 * v / (255.0 * max(count, 1)) * 1.6) for v in light]
        rgb = [int(round(255 * t * l)) for t, l in zip(texture_colour(name), light)]
        part_ids.extend([index] * len(triangles))
        colours.extend([rgb + [255]] * len(triangles))
    entities = parse_entities(lumps[LUMP_ENTITIES].split(b"\0")[0].decode("latin-1"))
    return {"points": points, "normals": normals, "connectivity": connectivity,
            "part_ids": part_ids, "colours": colours, "skipped": skipped,
            "winding": winding_checked, "cameras": spawn_cameras(entities),
            "faces": len(faces), "surfaces": len(set(part_ids))}


def write_vtp(path, scene):
    """VTK XML PolyData, appended raw binary: each array is a UInt64 byte count then its bytes."""
    n_points, n_cells = len(scene["points"]), len(scene["part_ids"])
    blocks = [
        ("Points", "Float32", 3, "<%df" % (3 * n_points), [v for p in scene["points"] for v in p]),
        ("Normals", "Float32", 3, "<%df" % (3 * n_points), [v for p in scene["normals"] for v in p]),
        ("PartId", "Int32", 1, "<%di" % n_cells, scene["part_ids"]),
        ("Colors", "UInt8", 4, "<%dB" % (4 * n_cells), [v for c in scene["colours"] for v in c]),
        ("connectivity", "Int32", 1, "<%di" % (3 * n_cells), scene["connectivity"]),
        ("offsets", "Int32", 1, "<%di" % n_cells, range(3, 3 * n_cells + 1, 3)),
    ]
    payload, offsets = bytearray(), {}
    for name, _type, _components, fmt, values in blocks:
        offsets[name] = len(payload)
        raw = struct.pack(fmt, *values)
        payload += struct.pack("<Q", len(raw)) + raw

    def array(name, vtk_type, components):
        extra = f' Name="{name}"' if name != "Points" else ""
        return (f'<DataArray type="{vtk_type}"{extra} NumberOfComponents="{components}" '
                f'format="appended" offset="{offsets[name]}"/>')

    spec = {name: (t, c) for name, t, c, _f, _v in blocks}
    header = "\n".join([
        '<?xml version="1.0"?>',
        '<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">',
        "<PolyData>",
        f'<Piece NumberOfPoints="{n_points}" NumberOfVerts="0" NumberOfLines="0" '
        f'NumberOfStrips="0" NumberOfPolys="{n_cells}">',
        '<PointData Normals="Normals">', array("Normals", *spec["Normals"]), "</PointData>",
        '<CellData Scalars="Colors">', array("PartId", *spec["PartId"]),
        array("Colors", *spec["Colors"]), "</CellData>",
        "<Points>", array("Points", *spec["Points"]), "</Points>",
        "<Polys>", array("connectivity", *spec["connectivity"]), array("offsets", *spec["offsets"]),
        "</Polys>",
        "</Piece>", "</PolyData>", '<AppendedData encoding="raw">', "_"])
    with open(path + ".tmp", "wb") as out:
        out.write(header.encode("ascii"))
        out.write(payload)
        out.write(b"\n</AppendedData>\n</VTKFile>\n")
    os.replace(path + ".tmp", path)


def main(argv):
    args, patch_level = [], 4
    i = 1
    while i < len(argv):
        if argv[i] == "--patch-level":
            if i + 1 >= len(argv) or not argv[i + 1].isdigit() or not 1 <= int(argv[i + 1]) <= 64:
                print("q3bsp-to-vtp: --patch-level expects an integer in 1..64", file=sys.stderr)
                return 2
            patch_level = int(argv[i + 1])
            i += 2
            continue
        if argv[i] in ("-h", "--help"):
            print(__doc__)
            return 0
        args.append(argv[i])
        i += 1
    if len(args) != 3:
        print("q3bsp-to-vtp: usage: q3bsp-to-vtp.py MAP.bsp OUT.vtp OUT-cameras.json "
              "[--patch-level N]", file=sys.stderr)
        return 2
    source, vtp, cameras_path = args
    try:
        with open(source, "rb") as f:
            data = f.read()
        scene = convert(data, patch_level)
    except (OSError, BspError, struct.error) as error:
        print(f"q3bsp-to-vtp: {source}: {error}", file=sys.stderr)
        return 1
    if not scene["part_ids"]:
        print(f"q3bsp-to-vtp: {source}: no drawable surface in the world", file=sys.stderr)
        return 1
    write_vtp(vtp, scene)
    with open(cameras_path + ".tmp", "w") as f:
        json.dump(scene["cameras"], f, indent=1)
        f.write("\n")
    os.replace(cameras_path + ".tmp", cameras_path)
    skipped = ", ".join(f"{count} {reason}" for reason, count in sorted(scene["skipped"].items()))
    print(f"q3bsp-to-vtp: {source}: {len(scene['part_ids'])} triangles, {scene['surfaces']} "
          f"surfaces of {scene['faces']}, {len(scene['points'])} points, "
          f"{len(scene['cameras'])} spawn cameras; skipped: {skipped or 'nothing'}; "
          f"planar faces wound with/against their normal: {scene['winding'][0]}/"
          f"{scene['winding'][1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

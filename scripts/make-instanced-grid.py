#!/usr/bin/env python3
"""Writes an N x N grid of copies of a glTF binary model (.glb) as an INSTANCED glTF: one .gltf
whose nodes place the model's meshes N*N times, and one .bin holding the model's buffer once.

It is the instanced twin of `scenevis_occlusion_bench --grid N --write-flat FILE.vtp` (the same
layout: copies 15 % apart along x and z, computed from the exact world bounds of the model's
points), so the two files show the same scene, flattened and instanced:

    python3 scripts/make-instanced-grid.py ENGINE.glb 20 grid20-instanced.gltf
    scenevis render --scene grid20-instanced.gltf --instances ...

Each copy duplicates the model's node hierarchy under a root node that translates it; every node
still references the model's own meshes (glTF forbids a node with two parents, not a mesh used
by many nodes). Cameras and other non-mesh nodes are left out. Standard library only.
"""
import json
import os
import struct
import sys


def read_glb(path):
    data = open(path, "rb").read()
    magic, _version, _length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67:
        sys.exit(f"{path}: not a binary glTF (.glb)")
    offset, document, binary = 12, None, b""
    while offset < len(data):
        length, kind = struct.unpack_from("<II", data, offset)
        chunk = data[offset + 8:offset + 8 + length]
        if kind == 0x4E4F534A:
            document = json.loads(chunk)
        elif kind == 0x004E4942:
            binary = chunk
        offset += 8 + length
    return document, binary


def multiply(a, b):
    """Column-major 4x4 product a * b."""
    return [sum(a[r + 4 * k] * b[k + 4 * c] for k in range(4)) for c in range(4) for r in range(4)]


IDENTITY = [1.0 if r == c else 0.0 for c in range(4) for r in range(4)]


def local_matrix(node):
    if "matrix" in node:
        return list(node["matrix"])
    if any(key in node for key in ("translation", "rotation", "scale")):
        tx, ty, tz = node.get("translation", [0, 0, 0])
        x, y, z, w = node.get("rotation", [0, 0, 0, 1])
        sx, sy, sz = node.get("scale", [1, 1, 1])
        r = [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
             2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
             2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
             0, 0, 0, 1]
        s = [sx, 0, 0, 0, 0, sy, 0, 0, 0, 0, sz, 0, 0, 0, 0, 1]
        t = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, tx, ty, tz, 1]
        return multiply(t, multiply(r, s))
    return IDENTITY


def positions(document, binary, accessor_index):
    accessor = document["accessors"][accessor_index]
    view = document["bufferViews"][accessor["bufferView"]]
    stride = view.get("byteStride", 12)
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    for i in range(accessor["count"]):
        yield struct.unpack_from("<fff", binary, start + i * stride)


def world_bounds(document, binary):
    low, high = [float("inf")] * 3, [float("-inf")] * 3
    scene = document["scenes"][document.get("scene", 0)]
    stack = [(index, IDENTITY) for index in scene["nodes"]]
    while stack:
        index, parent = stack.pop()
        node = document["nodes"][index]
        matrix = multiply(parent, local_matrix(node))
        if "mesh" in node:
            for primitive in document["meshes"][node["mesh"]]["primitives"]:
                for x, y, z in positions(document, binary, primitive["attributes"]["POSITION"]):
                    for a in range(3):
                        q = matrix[a] * x + matrix[4 + a] * y + matrix[8 + a] * z + matrix[12 + a]
                        low[a], high[a] = min(low[a], q), max(high[a], q)
        stack.extend((child, matrix) for child in node.get("children", []))
    return low, high


def draws_meshes(document, index):
    node = document["nodes"][index]
    return "mesh" in node or any(draws_meshes(document, c) for c in node.get("children", []))


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: make-instanced-grid.py MODEL.glb N OUT.gltf")
    source, n, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    document, binary = read_glb(source)
    low, high = world_bounds(document, binary)
    pitch = [1.15 * (high[a] - low[a]) for a in range(3)]
    roots = [i for i in document["scenes"][document.get("scene", 0)]["nodes"]
             if draws_meshes(document, i)]
    nodes = []

    def copy(index):
        node = {key: value for key, value in document["nodes"][index].items()
                if key not in ("children", "camera")}
        children = [copy(c) for c in document["nodes"][index].get("children", [])
                    if draws_meshes(document, c)]
        if children:
            node["children"] = children
        nodes.append(node)
        return len(nodes) - 1

    tiles = []
    for i in range(n):
        for j in range(n):
            children = [copy(r) for r in roots]
            nodes.append({"name": f"copy {i},{j}", "children": children,
                          "translation": [i * pitch[0], 0.0, j * pitch[2]]})
            tiles.append(len(nodes) - 1)
    bin_name = os.path.splitext(os.path.basename(out))[0] + ".bin"
    document["nodes"] = nodes
    document["scenes"] = [{"nodes": tiles}]
    document["scene"] = 0
    document.pop("cameras", None)
    document["buffers"] = [{"byteLength": len(binary), "uri": bin_name}]
    with open(os.path.join(os.path.dirname(out) or ".", bin_name), "wb") as f:
        f.write(binary)
    with open(out, "w") as f:
        json.dump(document, f)
    meshes = sum(1 for node in nodes if "mesh" in node)
    print(f"{out}: {n} x {n} copies, {len(nodes)} nodes, {meshes} mesh nodes, "
          f"pitch {pitch[0]:.6g} x {pitch[2]:.6g}, buffer {len(binary)} bytes ({bin_name})")


if __name__ == "__main__":
    main()

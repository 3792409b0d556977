#!/usr/bin/env python3
"""Writes a glTF 2.0 file (.gltf + .bin) whose one mesh, an N x N grid of quads (2 N^2 triangles,
opaque), is placed twice: a model with few placements and many triangles, for the command line's
--instances --cull auto test (the rule picks "chunked" for one such mesh, which placements cannot
use). Usage: write_big_gltf.py OUT.gltf [N]"""
import json
import struct
import sys


def main():
    out = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 510
    points = [(i / n, j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
    indices = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            indices += [a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]
    blob = struct.pack(f"<{3 * len(points)}f", *[c for p in points for c in p])
    index_offset = len(blob)
    blob += struct.pack(f"<{len(indices)}I", *indices)
    bin_name = out.rsplit("/", 1)[-1].rsplit(".", 1)[0] + ".bin"
    with open(out.rsplit("/", 1)[0] + "/" + bin_name if "/" in out else bin_name, "wb") as f:
        f.write(blob)
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"mesh": 0, "translation": [0, 0, -2]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                    "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1]}}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(points), "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": index_offset},
                        {"buffer": 0, "byteOffset": index_offset,
                         "byteLength": len(blob) - index_offset}],
        "buffers": [{"byteLength": len(blob), "uri": bin_name}]}
    with open(out, "w") as f:
        json.dump(gltf, f)


if __name__ == "__main__":
    main()

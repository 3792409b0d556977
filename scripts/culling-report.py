#!/usr/bin/env python3
"""Regenerates the committed culling and auto-mode reports with the `scenevis` tool.

docs/culling-vs-time.csv -- every culling mode on the demo CAD assembly (5,000 parts, 2M
    triangles, a close camera) and on the demo building (eye inside a room): median frame time
    over an orbit (sort + cull + render), cull time, triangles drawn, and accuracy against the
    exact visible set of `scenevis cull --exact` (a depth-tested ID buffer of every cell): visible
    pixels, cells and parts the mode culled (false negatives; conservative modes must show 0) and
    cells drawn per visible cell (over-draw).
docs/auto-vs-fixed.csv -- `--sort auto --cull auto` against every fixed exact combination on the
    demo scenes: median frame time of each, what auto chose, and auto / best fixed.

    python3 scripts/culling-report.py [--build DIR] [--frames N]

Builds the tool first (in $SCENEVIS_BUILD_DIR, default build/ of the source tree). Timings depend
on the machine and its load: compare rows within one run. LP_NUM_THREADS=1 keeps llvmpipe's
images exact.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CAD = ["--scene", "cad", "--parts", "5000", "--triangles", "2000000",
       "--camera", "60,60,60,140,140,0"]
BUILDING = ["--scene", "building", "--camera", "-7.5,-4,1.6,0,-4,1.6"]
CULLING_SCENES = [
    ("cad 2M, close camera", CAD,
     ["none", "frustum", "octree", "normal-cones", "occlusion", "small:4", "small:16", "small:64",
      "chunked"]),
    ("building, inside a room", BUILDING,
     ["none", "frustum", "octree", "occlusion", "portals", "pvs", "small:16"]),
]

# Demo scenes for auto vs fixed; the fixed choices are the exact ones valid for the scene
# (prop culling needs one actor per part, so it goes with multi-actor sorting).
AUTO_SCENES = [
    ("spheres", ["--scene", "spheres"],
     [("bsp", "none"), ("bsp-mapper", "none"), ("multi-actor", "none"),
      ("multi-actor", "octree")]),
    ("cyclic-quads", ["--scene", "cyclic-quads"],
     [("bsp", "none"), ("bsp-mapper", "none"), ("painter", "none")]),
    ("cad", ["--scene", "cad"],
     [("bsp", "none"), ("bsp-mapper", "none"), ("multi-actor", "none"),
      ("multi-actor", "octree")]),
    ("cad, close camera", ["--scene", "cad", "--camera", "60,60,60,140,140,0"],
     [("bsp", "none"), ("bsp-mapper", "none"), ("multi-actor", "none"),
      ("multi-actor", "octree"), ("multi-actor", "occlusion")]),
    ("building, inside", BUILDING,
     [("bsp", "none"), ("bsp-mapper", "none"), ("multi-actor", "none"),
      ("multi-actor", "octree"), ("multi-actor", "occlusion"), ("multi-actor", "portals"),
      ("multi-actor", "pvs")]),
]


def run(tool, args):
    """Runs the tool, returns its JSON report (render) or stdout JSON (cull)."""
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "report.json")
        command = [tool] + args
        if args[0] == "render":
            command += ["--out", os.path.join(tmp, "frame.png"), "--report", report]
        result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, check=False)
        if result.returncode != 0:
            sys.exit("culling-report: %s failed (%d): %s" % (" ".join(command), result.returncode,
                                                              result.stderr.strip()))
        if args[0] == "render":
            with open(report) as f:
                return json.load(f)
        return json.loads(result.stdout)


def frame_times(report):
    """Median frame time and cull time (ms) over the frames after the first."""
    frames = report["frames"][1:] or report["frames"]
    total = [f["sort_ms"] + f["cull_ms"] + f["render_ms"] for f in frames]
    return (statistics.median(total), statistics.median(f["cull_ms"] for f in frames),
            statistics.median(f["triangles_drawn"] for f in frames))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.environ.get("SCENEVIS_BUILD_DIR",
                                                          os.path.join(ROOT, "build")))
    parser.add_argument("--frames", type=int, default=8)
    options = parser.parse_args()
    os.environ.setdefault("LP_NUM_THREADS", "1")
    if not os.path.exists(os.path.join(options.build, "CMakeCache.txt")):
        subprocess.run(["cmake", "-S", ROOT, "-B", options.build, "-DCMAKE_BUILD_TYPE=Release"],
                       check=True)
    subprocess.run(["cmake", "--build", options.build, "-j2", "--target", "scenevis"], check=True)
    tool = os.path.join(options.build, "bin", "scenevis")
    orbit = ["--frames", str(options.frames), "--orbit", "0.5", "--size", "640x480"]

    rows = []
    for name, scene, modes in CULLING_SCENES:
        for mode in modes:
            sort = "multi-actor" if mode not in ("none", "chunked") else "none"
            report = run(tool, ["render"] + scene + orbit + ["--cull", mode, "--sort", sort])
            frame, cull, drawn = frame_times(report)
            exact = run(tool, ["cull"] + scene + ["--cull", mode, "--exact", "--size", "640x480"])
            e = exact["exact"]
            rows.append({
                "scene": name, "culling": mode, "sort": sort,
                "approximate": int(bool(report["culling"].get("approximate", False))),
                "frame_ms": round(frame, 2), "cull_ms": round(cull, 3),
                "triangles_drawn": int(drawn), "triangles_total": report["triangles"],
                "visible_pixels": e["visible_pixels"], "lost_pixels": e["lost_pixels"],
                "visible_cells": e["visible_cells"],
                "false_negative_cells": e["false_negative_cells"],
                # Per part only where the mode draws one actor per part.
                "false_negative_parts": e.get("false_negative_props", ""),
                "overdraw": round(e["drawn_cells"] / max(1, e["visible_cells"]), 2),
            })
            print("%-26s %-13s %8.1f ms  cull %7.3f ms  drawn %9d  missed %6d px %5d cells"
                  % (name, mode, frame, cull, drawn, e["lost_pixels"], e["false_negative_cells"]))
    path = os.path.join(ROOT, "docs", "culling-vs-time.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    rows = []
    for name, scene, fixed in AUTO_SCENES:
        auto = run(tool, ["render"] + scene + orbit)
        auto_ms = frame_times(auto)[0]
        chose = "%s + %s" % (auto["translucency"]["method"], auto["culling"]["method"])
        timings = []
        for sort, cull in fixed:
            timings.append((frame_times(run(tool, ["render"] + scene + orbit +
                                                   ["--sort", sort, "--cull", cull]))[0],
                            "%s + %s" % (sort, cull)))
        best_ms, best = min(timings)
        rows.append({
            "scene": name, "auto_chose": chose, "auto_ms": round(auto_ms, 2),
            "best_fixed": best, "best_fixed_ms": round(best_ms, 2),
            "auto_over_best": round(auto_ms / best_ms, 2),
            "fixed": "; ".join("%s %.1f ms" % (label, ms) for ms, label in timings),
        })
        print("%-18s auto (%s) %.1f ms; best fixed %s %.1f ms; ratio %.2f"
              % (name, chose, auto_ms, best, best_ms, auto_ms / best_ms))
    path = os.path.join(ROOT, "docs", "auto-vs-fixed.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    print("culling-report: wrote docs/culling-vs-time.csv and docs/auto-vs-fixed.csv")


if __name__ == "__main__":
    main()

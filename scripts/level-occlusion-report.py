#!/usr/bin/env python3
"""Occlusion culling on real game levels (issue 12): over-draw and frame times of
`--cull octree` (frustum culling alone) against `--cull occlusion`, from every spawn point.

Needs the converted OpenArena maps (`bash scripts/fetch-data.sh --levels`). Per level:

  accuracy  `scenevis cull --scene L.vtp --cull MODE --exact --cameras C.json --size 800x600`,
            all cameras in one process: parts kept (drawn) and visible (the ID render of every
            cell, depth-tested), false-negative cells / parts and lost pixels (must be 0).
  time      `LP_NUM_THREADS=1 scenevis render --scene L.vtp --cull MODE --cameras C2.json
            --size 800x600`, where C2 is the level's cameras (at most --render-cameras of them,
            evenly spaced) twice in a row: the first pass uploads every part drawn (llvmpipe's
            first draw of a buffer costs more than the draws of a running game), the second is
            timed. Frame = cull_ms + render_ms of the report's frame. --repeat N runs each render
            N times, octree and occlusion interleaved, and keeps each camera's fastest frame.

Over-draw = parts kept / parts visible per camera; the table gives the median and the worst over
the cameras, the frame-time ratio octree / occlusion likewise (per camera, then median and worst).

    python3 scripts/level-occlusion-report.py [--tool PATH] [--levels a,b] [--exact-cameras N]
        [--render-cameras N] [--repeat N] [--with-none] [--also MODES] [--steps exact,time]
        [--out-dir DIR]

--with-none also times `--cull none` (the whole level as one actor: one draw call, no culling),
the floor a culler of many actors competes with. --also MODES times more --cull modes beside
(comma-separated, e.g. auto,chunked-occlusion); with them a second table gives each mode's median
frame, the octree / mode ratio (per camera, then median and worst) and what auto chose.

Writes DIR/levels-occlusion.json (every number) and prints the Markdown table of BENCHMARKS.md.
Times depend on the machine and its load: compare rows within one run.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODES = ("octree", "occlusion")


def data_dir():
    return os.environ.get("SCENEVIS_DATA_DIR", os.path.expanduser("~/.cache/scenevis-data"))


def manifest():
    entries = {}
    path = os.path.join(data_dir(), "manifest.txt")
    if os.path.exists(path):
        for line in open(path):
            if "=" in line and not line.startswith("#"):
                key, value = line.strip().split("=", 1)
                entries[key] = os.path.join(data_dir(), value)
    return entries


def run(command, env=None):
    result = subprocess.run(command, capture_output=True, text=True, env=env)
    if result.returncode != 0:
        sys.exit(f"level-occlusion-report: {' '.join(command)} failed ({result.returncode}):\n"
                 f"{result.stderr}")
    return result.stdout


def spread(items, count):
    if count <= 0 or len(items) <= count:
        return list(items)
    return [items[round(i * (len(items) - 1) / (count - 1))] for i in range(count)]


def accuracy(tool, scene, cameras, mode):
    out = json.loads(run([tool, "cull", "--scene", scene, "--cull", mode, "--exact",
                          "--cameras", cameras, "--size", "800x600"]))
    rows = []
    for result in out:
        exact = result["exact"]
        rows.append({"visible_props": exact["visible_props"], "drawn_props": exact["drawn_props"],
                     "false_negative_props": exact["false_negative_props"],
                     "false_negative_cells": exact["false_negative_cells"],
                     "lost_pixels": exact["lost_pixels"], "visible_cells": exact["visible_cells"],
                     "drawn_cells": exact["drawn_cells"], "cull_ms": result["cull_ms"]})
    return rows


def frames(tool, scene, cameras_file, count, mode, workdir):
    env = dict(os.environ, LP_NUM_THREADS="1")
    report = os.path.join(workdir, f"render-{mode}.json")
    run([tool, "render", "--scene", scene, "--cull", mode, "--cameras", cameras_file,
         "--size", "800x600", "--out", os.path.join(workdir, f"{mode}.png"), "--report", report],
        env)
    out = json.load(open(report))
    method = out["culling"]["method"]
    return [{"frame_ms": f["cull_ms"] + f["render_ms"], "cull_ms": f["cull_ms"],
             "render_ms": f["render_ms"], "props_drawn": f["props_drawn"],
             "triangles_drawn": f["triangles_drawn"], "method": method}
            for f in out["frames"][count:]]


def level_info(scene):
    """Triangles and surfaces from the .vtp header and the converter's log next to it."""
    log = os.path.splitext(scene)[0] + ".log"
    text = open(log).read() if os.path.exists(log) else ""
    info = {}
    for field, word in (("triangles", " triangles"), ("surfaces", " surfaces of")):
        at = text.find(word)
        if at > 0:
            info[field] = int(text[:at].split()[-1])
    return info


def median_worst(values, worst=max):
    return (statistics.median(values), worst(values)) if values else (float("nan"),) * 2


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tool", default=os.path.join(
        os.environ.get("SCENEVIS_BUILD_DIR", os.path.join(ROOT, "build")), "bin", "scenevis"))
    parser.add_argument("--levels", default="", help="comma-separated map names (default: all)")
    parser.add_argument("--render-cameras", type=int, default=12)
    parser.add_argument("--with-none", action="store_true",
                        help="also time --cull none: the whole level as one actor, one draw call")
    parser.add_argument("--also", default="",
                        help="more --cull modes to time beside octree and occlusion "
                        "(comma-separated)")
    parser.add_argument("--exact-cameras", type=int, default=0,
                        help="at most this many cameras (evenly spaced) in the exact step "
                        "(default 0: all)")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--out-dir", default=".")
    parser.add_argument("--steps", default="exact,time",
                        help="exact, time or both; a step not run keeps its numbers from an "
                        "earlier run's levels-occlusion.json in --out-dir")
    args = parser.parse_args()
    steps = set(args.steps.split(","))
    entries = manifest()
    levels = sorted(k[len("level-"):] for k in entries
                    if k.startswith("level-") and not k.endswith("-cameras"))
    if args.levels:
        levels = [name for name in args.levels.split(",") if name]
    if not levels:
        sys.exit("level-occlusion-report: no levels fetched (bash scripts/fetch-data.sh --levels)")
    results = {}
    os.makedirs(args.out_dir, exist_ok=True)
    saved = os.path.join(args.out_dir, "levels-occlusion.json")
    if os.path.exists(saved):
        with open(saved) as f:
            results = json.load(f)
    with tempfile.TemporaryDirectory() as workdir:
        for name in levels:
            scene, cameras_path = entries[f"level-{name}"], entries[f"level-{name}-cameras"]
            cameras = json.load(open(cameras_path))
            level = results.get(name, {})
            level.update({"cameras": len(cameras), **level_info(scene)})
            results[name] = level
            if "exact" in steps:
                exact_cameras = spread(cameras, args.exact_cameras)
                subset = os.path.join(workdir, f"{name}-exact-cameras.json")
                with open(subset, "w") as f:
                    json.dump(exact_cameras, f)
                level["exact_cameras"] = len(exact_cameras)
                for mode in MODES:
                    level[f"{mode}_exact"] = accuracy(args.tool, scene, subset, mode)
            if "time" not in steps:
                print(f"level-occlusion-report: {name} done", file=sys.stderr)
                with open(saved, "w") as f:
                    json.dump(results, f, indent=1)
                continue
            timed_cameras = spread(cameras, args.render_cameras)
            doubled = os.path.join(workdir, f"{name}-timed-cameras.json")
            json.dump(timed_cameras + timed_cameras, open(doubled, "w"))
            level["render_cameras"] = len(timed_cameras)
            timed_modes = MODES + (("none",) if args.with_none else ())
            timed_modes += tuple(m for m in args.also.split(",") if m and m not in timed_modes)
            runs = {mode: [] for mode in timed_modes}
            for _ in range(args.repeat):
                for mode in timed_modes:
                    runs[mode].append(frames(args.tool, scene, doubled, len(timed_cameras), mode,
                                             workdir))
            for mode in timed_modes:
                best = []
                for i in range(len(timed_cameras)):
                    best.append(min((r[i] for r in runs[mode]), key=lambda f: f["frame_ms"]))
                level[f"{mode}_frames"] = best
                level[f"{mode}_frame_runs_ms"] = [[f["frame_ms"] for f in r] for r in runs[mode]]
            results[name] = level
            print(f"level-occlusion-report: {name} done", file=sys.stderr)
            os.makedirs(args.out_dir, exist_ok=True)
            with open(saved, "w") as f:
                json.dump(results, f, indent=1)
    os.makedirs(args.out_dir, exist_ok=True)
    with open(saved, "w") as f:
        json.dump(results, f, indent=1)

    print("| level | triangles | surfaces | cameras | octree kept / visible (median, worst) | "
          "occlusion kept / visible (median, worst) | false negatives (parts, cells, pixels) | "
          "octree frame ms | occlusion frame ms | ratio (median, worst) | occlusion cull ms | one mesh ms |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, level in results.items():
        if "occlusion_exact" not in level or "occlusion_frames" not in level:
            continue
        row = [name, f"{level.get('triangles', '?'):,}", f"{level.get('surfaces', '?'):,}",
               f"{level['cameras']} ({level.get('exact_cameras', level['cameras'])} exact, "
               f"{level['render_cameras']} timed)"]
        for mode in MODES:
            exact = level[f"{mode}_exact"]
            ratios = [e["drawn_props"] / e["visible_props"] for e in exact if e["visible_props"]]
            kept = statistics.median(e["drawn_props"] for e in exact)
            seen = statistics.median(e["visible_props"] for e in exact)
            med, worst = median_worst(ratios)
            row.append(f"{kept:g} / {seen:g} (**{med:.2f}**, {worst:.2f})")
        occ = level["occlusion_exact"]
        row.append(f"{sum(e['false_negative_props'] for e in occ)}, "
                   f"{sum(e['false_negative_cells'] for e in occ)}, "
                   f"{sum(e['lost_pixels'] for e in occ)}")
        octree = [f["frame_ms"] for f in level["octree_frames"]]
        occlusion = [f["frame_ms"] for f in level["occlusion_frames"]]
        row.append(f"{statistics.median(octree):.0f}")
        row.append(f"{statistics.median(occlusion):.0f}")
        ratio = [a / b for a, b in zip(octree, occlusion)]
        med, worst = median_worst(ratio, min)
        row.append(f"**{med:.1f}×**, {worst:.1f}×")
        row.append(f"{statistics.median(f['cull_ms'] for f in level['occlusion_frames']):.1f}")
        none = [f["frame_ms"] for f in level.get("none_frames", [])]
        row.append(f"{statistics.median(none):.0f}" if none else "")
        print("| " + " | ".join(row) + " |")
    also = [m for m in args.also.split(",") if m]
    if also:
        print_modes_table(results, ("occlusion", "none") + tuple(also))


def print_modes_table(results, modes):
    """Each mode's median frame beside the octree's, and octree / mode per camera."""
    print()
    print("| level | triangles per surface | auto chose | octree frame ms | " +
          " | ".join(f"{m} frame ms (octree / {m}: median, worst)" for m in modes) + " |")
    print("|---" * (4 + len(modes)) + "|")
    ratios = {m: [] for m in modes}
    for name, level in results.items():
        if "octree_frames" not in level:
            continue
        octree = [f["frame_ms"] for f in level["octree_frames"]]
        auto = level.get("auto_frames", [{}])[0].get("method", "")
        per_surface = level.get("triangles", 0) / max(level.get("surfaces", 1), 1)
        row = [name, f"{per_surface:.1f}", auto, f"{statistics.median(octree):.1f}"]
        for mode in modes:
            frames = [f["frame_ms"] for f in level.get(f"{mode}_frames", [])]
            if not frames:
                row.append("")
                continue
            ratio = [a / b for a, b in zip(octree, frames)]
            ratios[mode].extend(ratio)
            med, worst = median_worst(ratio, min)
            row.append(f"{statistics.median(frames):.1f} (**{med:.2f}×**, {worst:.2f}×)")
        print("| " + " | ".join(row) + " |")
    print("| all cameras | | | | " + " | ".join(
        f"**{statistics.median(ratios[m]):.2f}×** median, ≥ 3× on {sum(r >= 3 for r in ratios[m])}"
        f" of {len(ratios[m])}" if ratios[m] else "" for m in modes) + " |")


if __name__ == "__main__":
    main()

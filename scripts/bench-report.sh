#!/usr/bin/env bash
# Regenerates the committed accuracy-versus-time report, docs/accuracy-vs-time.csv and
# docs/accuracy-vs-time.png, with `scenevis bench`: every translucency method on the 64-sphere
# demo (19,456 triangles, just under the 20k up to which the painter's sort is run), the cyclic
# quads and, when fetched (scripts/fetch-data.sh), the Stanford bunny and the 2CylinderEngine glTF
# (121k triangles in 115 parts: multi-actor draws one actor per part) at opacity 0.4; 10 frames
# on a 2-degree orbit at 640x480, errors against 100-peel depth peeling. Builds the tool first
# (in $SCENEVIS_BUILD_DIR, default build/ of the source tree).
#
#   bash scripts/bench-report.sh [extra scenevis bench options, e.g. --frames 20]
#
# Timings depend on the machine and on its load: the report is for comparing methods with each
# other within one run, not across machines. LP_NUM_THREADS=1 keeps llvmpipe's images exact.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SCENEVIS_BUILD_DIR:-$root/build}"
jobs="${SCENEVIS_JOBS:-2}"

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j"$jobs" --target scenevis

scenes=(--scene spheres --scene cyclic-quads)
data_dir="${SCENEVIS_DATA_DIR:-$HOME/.cache/scenevis-data}"
if grep -q '^bunny-stl=' "$data_dir/manifest.txt" 2>/dev/null; then
  scenes+=(--scene bunny-stl)
else
  echo "bench-report: the bunny is not fetched (bash scripts/fetch-data.sh); leaving it out" >&2
fi
if grep -q '^engine-glb=' "$data_dir/manifest.txt" 2>/dev/null; then
  scenes+=(--scene engine-glb)
else
  echo "bench-report: the engine is not fetched (bash scripts/fetch-data.sh); leaving it out" >&2
fi

export LP_NUM_THREADS="${LP_NUM_THREADS:-1}"
"$build/bin/scenevis" bench "${scenes[@]}" --triangles 19000 --opacity 0.4 \
  --frames 10 --orbit 2 --size 640x480 --out-dir "$root/docs" "$@"
echo "bench-report: regenerated docs/accuracy-vs-time.csv and docs/accuracy-vs-time.png"

#!/usr/bin/env bash
# The README's main-job command: installs what is missing, builds, and renders the embedded
# translucent demo (64 overlapping spheres) offscreen with the exact BSP order; prints what was
# done and how long it took. Extra arguments go to `scenevis render` (see `scenevis --help`).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SCENEVIS_BUILD_DIR:-$root/build}
start=$(date +%s)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
out=${SCENEVIS_DEMO_OUT:-$PWD/scenevis-demo.png}
"$build/bin/scenevis" render --scene spheres --triangles 100000 --size 1024x768 \
  --out "$out" --report "${out%.png}.json" "$@"
echo "demo: done in $(( $(date +%s) - start )) s; look at $out"

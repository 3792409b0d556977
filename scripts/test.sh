#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, and runs the whole test suite.
# One Xvfb display serves the whole run (xvfb-run -a races when started per test); the default
# rendering back-end (OSMesa) needs none, the X11 back-end tests use it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SCENEVIS_BUILD_DIR:-$root/build}
start=$(date +%s)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
cd "$build"
export LP_NUM_THREADS=1
xvfb-run -a -s "-screen 0 1280x1024x24" \
  ctest --output-on-failure -j"$(nproc)" --timeout 600 "$@"
echo "test: done in $(( $(date +%s) - start )) s"

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
# Real third-party models (Debian's assimp-testmodels, npm's stl-models and bunny, and the
# OpenArena levels: a 37 MB download converted once in ~10 s of CPU; ~215 MB in
# ~/.cache/scenevis-data, not the 1.2 GB KiCad library): the reader and real-model tests use them.
# Without them those tests are skipped, so a failed fetch is reported loudly, not hidden.
if ! bash "$root/scripts/fetch-data.sh" --levels > "$build.fetch-data.log" 2>&1; then
  cat "$build.fetch-data.log" >&2
  echo "test: WARNING: fetching the real models failed; tests that need them will be SKIPPED" >&2
fi
cd "$build"
export LP_NUM_THREADS=1
xvfb-run -a -s "-screen 0 1280x1024x24" \
  ctest --output-on-failure -j"$(nproc)" --timeout 600 "$@"
# The ParaView plugin: the filter modules built again against ParaView's VTK, loaded into
# ParaView's server manager by its test (scripts/build-paraview-plugin.sh).
paraview_build=${SCENEVIS_PARAVIEW_BUILD_DIR:-$root/build-paraview}
bash "$root/scripts/build-paraview-plugin.sh"
(cd "$paraview_build" && xvfb-run -a -s "-screen 0 1280x1024x24" \
  ctest --output-on-failure --timeout 600)
# Second build with ASan + UBSan + LeakSanitizer of the non-rendering tests, and a short fuzz run
# (scripts/sanitize.sh; SCENEVIS_SANITIZE=0 skips it, SCENEVIS_FUZZ_SECONDS=0 skips the fuzzing).
if [ "${SCENEVIS_SANITIZE:-1}" != "0" ]; then
  bash "$root/scripts/sanitize.sh"
fi
echo "test: done in $(( $(date +%s) - start )) s"

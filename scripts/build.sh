#!/usr/bin/env bash
# Configures and builds SceneVis into ${SCENEVIS_BUILD_DIR:-build}. Extra arguments go to CMake.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SCENEVIS_BUILD_DIR:-$root/build}
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
start=$(date +%s)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSCENEVIS_WARNINGS_AS_ERRORS=$werror "$@" \
  >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j"$(nproc)"
echo "build: done in $(( $(date +%s) - start )) s ($build)"

#!/usr/bin/env bash
# Configures and builds the SceneVis ParaView plugin (ParaView/, against Debian's paraview-dev and
# its own VTK) into ${SCENEVIS_PARAVIEW_BUILD_DIR:-build-paraview}. Extra arguments go to CMake.
# The plugin: <build>/lib/paraview-5.11/plugins/SceneVis/SceneVis.so (LoadPlugin in ParaView).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SCENEVIS_PARAVIEW_BUILD_DIR:-$root/build-paraview}
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
start=$(date +%s)
cmake -S "$root/ParaView" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DSCENEVIS_WARNINGS_AS_ERRORS=$werror "$@" \
  >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j"$(nproc)"
echo "build-paraview-plugin: done in $(( $(date +%s) - start )) s ($build)"

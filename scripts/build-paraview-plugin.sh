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
# The main build's tool (VTK 9.1), when built: ParaView.Plugin compares the view's images with its.
main_tool=${SCENEVIS_BUILD_DIR:-$root/build}/bin/scenevis
vtk91_tool=""
if [ -x "$main_tool" ]; then vtk91_tool=$main_tool; fi
cmake -S "$root/ParaView" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DSCENEVIS_WARNINGS_AS_ERRORS=$werror -DSCENEVIS_VTK91_TOOL="$vtk91_tool" "$@" \
  >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j"$(nproc)"
echo "build-paraview-plugin: done in $(( $(date +%s) - start )) s ($build)"

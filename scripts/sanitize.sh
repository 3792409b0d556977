#!/usr/bin/env bash
# Sanitizer run: a second build with AddressSanitizer + UndefinedBehaviorSanitizer (+ LeakSanitizer,
# which is part of ASan on Linux) of the core tests and of every VTK-level module test (those that
# render use OSMesa, so no X is needed), run with leak detection on, and
# a short libFuzzer run of Core/Fuzz/FuzzBsp on its seed corpus when clang + libFuzzer are there.
#
#   bash scripts/sanitize.sh            # what scripts/test.sh (and so CI) runs after the main suite
#
# Environment:
#   SCENEVIS_ASAN_BUILD_DIR   build directory (default <repo>/build-asan)
#   SCENEVIS_FUZZ_BUILD_DIR   fuzzer build directory (default <repo>/build-fuzz)
#   SCENEVIS_FUZZ_SECONDS     length of the fuzz run (default 60; 0 skips fuzzing)
#   SCENEVIS_FUZZ_OCCLUSION_SECONDS  length of the occlusion fuzz run after it (default 30)
#   SCENEVIS_FUZZ_PART_ORDER_SECONDS length of the two-level order fuzz run after that (default 20)
#   SCENEVIS_FUZZ_PORTAL_SECONDS     length of the portal generation fuzz run after that (default 30)
#   SCENEVIS_FUZZ_RECORDING_SECONDS  length of the occlusion recording fuzz run after that (default 20)
#   SCENEVIS_FUZZ_INSIDE_SECONDS     length of the rooms' inside test fuzz run after that (default 20)
#   SCENEVIS_FUZZ_TRAVERSAL_SECONDS  length of the portal traversal fuzz run after that (default 20)
#   SCENEVIS_SANITIZE_CXX     compiler for the ASan build (default: CMake's default, g++ on Debian)
#
# Only SceneVis' own code is instrumented (CMake option SCENEVIS_SANITIZE); VTK, GoogleTest and the
# system libraries are Debian's. Leaks inside VTK/Mesa/MPI libraries are suppressed by
# Testing/Sanitizers/lsan.supp (see the comments there); any leak through our code fails the run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SCENEVIS_ASAN_BUILD_DIR:-$root/build-asan}
fuzzbuild=${SCENEVIS_FUZZ_BUILD_DIR:-$root/build-fuzz}
fuzzseconds=${SCENEVIS_FUZZ_SECONDS:-60}
occlusionseconds=${SCENEVIS_FUZZ_OCCLUSION_SECONDS:-30}
partorderseconds=${SCENEVIS_FUZZ_PART_ORDER_SECONDS:-20}
portalseconds=${SCENEVIS_FUZZ_PORTAL_SECONDS:-30}
recordingseconds=${SCENEVIS_FUZZ_RECORDING_SECONDS:-20}
insideseconds=${SCENEVIS_FUZZ_INSIDE_SECONDS:-20}
traversalseconds=${SCENEVIS_FUZZ_TRAVERSAL_SECONDS:-20}
jobs=$(nproc)
start=$(date +%s)

werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
compiler=()
if [ -n "${SCENEVIS_SANITIZE_CXX:-}" ]; then compiler=(-DCMAKE_CXX_COMPILER="$SCENEVIS_SANITIZE_CXX"); fi

# --- 1. ASan + UBSan build of the non-rendering tests ----------------------------------------------
# Without the Python wrapping: an instrumented extension module cannot load into an uninstrumented
# python3 (the ASan runtime must come first); the Python tests run in the main build.
mkdir -p "$build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${compiler[@]}" \
  -DSCENEVIS_SANITIZE=address,undefined -DSCENEVIS_WARNINGS_AS_ERRORS=$werror \
  -DSCENEVIS_BUILD_BENCHMARKS=OFF -DSCENEVIS_BUILD_SOAK_BENCH=ON -DSCENEVIS_BUILD_EXAMPLES=OFF \
  -DSCENEVIS_BUILD_FUZZERS=ON -DSCENEVIS_WRAP_PYTHON=OFF \
  >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$root/Testing/Sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# gtest_discover_tests runs the test binary at build time, so the options above already apply.
cmake --build "$build" -j"$jobs" --target scenevis_core_tests scenevis_fuzz_bsp_replay \
  scenevis_fuzz_occlusion_replay scenevis_fuzz_part_order_replay scenevis_fuzz_portal_generation_replay \
  scenevis_fuzz_make_portal_corpus scenevis_fuzz_recording_replay scenevis_fuzz_make_recording_corpus \
  scenevis_fuzz_portal_inside_replay scenevis_fuzz_portal_traversal_replay \
  scenevis_split_parts_tests scenevis_instances_tests scenevis_huge_pages_tests \
  SceneVisFiltersSortingCxxTests SceneVisFiltersSortingRenderingCxxTests \
  SceneVisFiltersSourcesCxxTests SceneVisFiltersPortalsCxxTests SceneVisIOModelsCxxTests \
  SceneVisRenderingCullingCxxTests \
  SceneVisRenderingPortalsCxxTests SceneVisRenderingTranslucencyCxxTests \
  SceneVisRenderingAutoCxxTests scenevis_soak_bench
echo "sanitize: asan build done in $(( $(date +%s) - start )) s ($build)"

# The VTK-level tests are named after their module (SceneVis::FiltersSortingCxx-TestX), rendering
# ones included; those live in executables not built here (left to the main run) and are skipped:
# ctest shows an empty command for them. Fuzz.BspCorpus replays Core/Fuzz/corpus and crashes.
# Core.PortalPvsFlow.* run the multi-threaded portal-flow PVS (worker threads sharing bit sets)
# on the demo building and 40 random maze levels under ASan/UBSan, Fuzz* included.
# Every VTK-level test of the modules too (they render with OSMesa, no X needed): LeakSanitizer
# is the leak check of the filters, mappers, passes, cullers, the model reader and the auto planner
# (bad input included: SceneVis::IOModelsCxx-TestSceneVisModelReaderBadInput,
# SceneVis::RenderingAutoCxx-TestSceneVisPlannerBadInput,
# SceneVis::FiltersPortalsCxx-TestGenerateRoomsBadInput); and the tool's own code paths
# that take files and split them (Tool.SplitParts, Tool.Instances: glTF and VRML instancing, the
# VRML USE checks and refused matrices, flattening placements for sort and cull --exact) or read
# the command line to decide on huge pages (Tool.HugePages). Bench.SoakLeaks: 300 frames of
# the soak's moving camera per culling mode on a 2 x 2 engine grid (Benchmarks/BenchSoak.cxx), the
# leak check of a long run (skipped without the data cache).
tests='^(Core\.|Fuzz\.|SceneVis::|Tool\.(SplitParts|Instances|HugePages)\.|Bench\.SoakLeaks$)'
unbuilt=$(cd "$build" && ctest -N -V -R "$tests" | awk '
  /Test command:/ { cmd = $0; sub(/^[0-9]+: Test command: */, "", cmd); empty = (cmd == "" || cmd ~ /^"/) }
  /^ *Test +#[0-9]+:/ { if (empty) { sub(/^ *Test +#[0-9]+: /, ""); print } }' | paste -sd'|' -)
(cd "$build" && ctest --output-on-failure -j"$jobs" --timeout 600 -R "$tests" \
  ${unbuilt:+-E "^($unbuilt)\$"})
echo "sanitize: asan/ubsan/lsan tests passed after $(( $(date +%s) - start )) s"

# --- 2. Short fuzz run (optional: needs clang and libclang-rt-14-dev's libFuzzer) ------------------
if [ "$fuzzseconds" = "0" ]; then
  echo "sanitize: fuzzing skipped (SCENEVIS_FUZZ_SECONDS=0)"
  exit 0
fi
clangxx=$(command -v clang++ || command -v clang++-14 || true)
fuzzlib=$(ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a 2>/dev/null | head -n 1 || true)
if [ -z "$clangxx" ] || [ -z "$fuzzlib" ]; then
  echo "sanitize: fuzzing skipped (no clang++ or libFuzzer; apt-get install clang libclang-rt-14-dev)"
  exit 0
fi
fuzzstart=$(date +%s)
mkdir -p "$fuzzbuild"
clangcc=${clangxx/clang++/clang}
cmake -S "$root" -B "$fuzzbuild" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER="$clangcc" -DCMAKE_CXX_COMPILER="$clangxx" \
  -DSCENEVIS_BUILD_FUZZERS=ON -DSCENEVIS_SANITIZE=address,undefined \
  -DBUILD_TESTING=OFF -DSCENEVIS_BUILD_BENCHMARKS=OFF -DSCENEVIS_BUILD_EXAMPLES=OFF \
  -DSCENEVIS_WRAP_PYTHON=OFF >"$fuzzbuild.configure.log" 2>&1 || { cat "$fuzzbuild.configure.log"; exit 1; }
cmake --build "$fuzzbuild" -j"$jobs" --target scenevis_fuzz_bsp scenevis_fuzz_occlusion \
  scenevis_fuzz_part_order scenevis_fuzz_portal_generation scenevis_fuzz_make_portal_corpus \
  scenevis_fuzz_recording scenevis_fuzz_make_recording_corpus scenevis_fuzz_portal_inside \
  scenevis_fuzz_portal_traversal
# New inputs go to a scratch directory; the committed seed corpus is only read.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && "$fuzzbuild/bin/scenevis_fuzz_bsp" -max_total_time="$fuzzseconds" -timeout=20 \
  -rss_limit_mb=2048 -print_final_stats=1 "$work" "$root/Core/Fuzz/corpus" 2>"$work/fuzz.log") || {
  tail -n 80 "$work/fuzz.log"
  echo "sanitize: the fuzzer failed; reproducer:"; ls -l "$work"/crash-* "$work"/leak-* \
    "$work"/timeout-* "$work"/oom-* 2>/dev/null || true
  exit 1
}
grep -E '^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb)' "$work/fuzz.log" || true
# fuzz NAME TARGET SECONDS SEEDS WHAT: libFuzzer target TARGET for SECONDS (0 skips it) in
# $work/NAME from the seed directory SEEDS; on a failure the log's end and the reproducer.
fuzz() {
  local name=$1 target=$2 seconds=$3 seeds=$4 what=$5
  [ "$seconds" != "0" ] || return 0
  mkdir -p "$work/$name"
  (cd "$work/$name" && "$fuzzbuild/bin/$target" -max_total_time="$seconds" -timeout=20 \
    -rss_limit_mb=2048 -print_final_stats=1 "$work/$name" "$seeds" 2>"$work/$name.log") || {
    tail -n 40 "$work/$name.log"
    echo "sanitize: the $what fuzzer failed; reproducer:"
    ls -l "$work/$name"/crash-* 2>/dev/null || true
    exit 1
  }
  grep -E '^(#[0-9]+ +DONE|stat::number_of_executed_units)' "$work/$name.log" || true
}
# The occlusion buffer against its ray oracle (Core/Fuzz/FuzzOcclusion.cpp).
fuzz occlusion scenevis_fuzz_occlusion "$occlusionseconds" "$root/Core/Fuzz/occlusion-corpus" occlusion
# The two-level order against the order oracle (Core/Fuzz/FuzzPartOrder.cpp).
fuzz part-order scenevis_fuzz_part_order "$partorderseconds" "$root/Core/Fuzz/part-order-corpus" \
  "two-level order"
# Rooms and portals against the box rooms they were built from (Core/Fuzz/FuzzPortalGeneration.cpp)
# and occlusion recordings read back to their bytes and replayed (FuzzOcclusionRecording.cpp):
# their seeds are written by code.
mkdir -p "$work/portal-seeds" "$work/recording-seeds"
"$fuzzbuild/bin/scenevis_fuzz_make_portal_corpus" "$work/portal-seeds" >/dev/null
"$fuzzbuild/bin/scenevis_fuzz_make_recording_corpus" "$work/recording-seeds"
fuzz portal scenevis_fuzz_portal_generation "$portalseconds" "$work/portal-seeds" "portal generation"
fuzz recording scenevis_fuzz_recording "$recordingseconds" "$work/recording-seeds" \
  "occlusion recording"
# The rooms' inside test against the box rooms it is given (Core/Fuzz/FuzzPortalInside.cpp).
fuzz inside scenevis_fuzz_portal_inside "$insideseconds" "$root/Core/Fuzz/inside-corpus" \
  "rooms' inside test"
# The exact portal traversal against sight lines through the portals
# (Core/Fuzz/FuzzPortalTraversal.cpp).
fuzz traversal scenevis_fuzz_portal_traversal "$traversalseconds" \
  "$root/Core/Fuzz/traversal-corpus" "portal traversal"
echo "sanitize: fuzzing ${fuzzseconds} s + occlusion ${occlusionseconds} s + two-level order ${partorderseconds} s + portal generation ${portalseconds} s + recordings ${recordingseconds} s + inside ${insideseconds} s + traversal ${traversalseconds} s passed (build+run $(( $(date +%s) - fuzzstart )) s)"
echo "sanitize: done in $(( $(date +%s) - start )) s"

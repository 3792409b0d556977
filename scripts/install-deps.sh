#!/usr/bin/env bash
# Installs the Debian packages SceneVis needs to build, test and render headless, if missing.
# Idempotent and quick when everything is there. Needs root (or sudo) only when installing.
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  libvtk9-dev libglm-dev
  libosmesa6-dev xvfb xauth
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev  # libFuzzer for scripts/sanitize.sh (~45 MB download)
  # Python wrapping (`import vtk, scenevis`) and its tests. Never python3-paraview: it conflicts
  # with python3-vtk9 and would remove libvtk9-dev.
  python3-vtk9 python3-dev python3-pytest python3-numpy
  # The ParaView plugin (ParaView/): ParaView 5.11 with its own VTK 9.2, beside libvtk9-dev;
  # mpiexec for its tests on two MPI ranks (Open MPI, the MPI ParaView is built with).
  paraview-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
start=$(date +%s)
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done in $(( $(date +%s) - start )) s"

#!/usr/bin/env bash
# fetch-data.sh: fetch the real third-party models SceneVis tests and benchmarks use.
#
# Everything goes into a cache OUTSIDE the source tree (never commit it):
#   ${SCENEVIS_DATA_DIR:-$HOME/.cache/scenevis-data}
# Nothing is installed system-wide: Debian packages are downloaded with `apt-get download` and
# unpacked with `dpkg -x`; npm packages go into a private prefix with `npm install --prefix`.
# The script is idempotent: a second run only prints what is already there.
#
# Layout of the cache (paths in manifest.txt are relative to it, so it can be moved):
#   debs/                         the downloaded .deb files
#   debian/<package>/usr/...      unpacked Debian packages
#   npm/node_modules/<package>/   npm packages
#   derived/                      files we generate from the above (bunny.ply: the npm bunny
#                                 module is a decimated bunny, 1,839 points / 3,674 triangles;
#                                 the full 69,451-triangle scan is bunny-stl)
#   derived/levels/               with --levels: the OpenArena maps (bsp/<map>.bsp, taken from
#                                 the package's pak6-patch085.pk3) converted by
#                                 scripts/q3bsp-to-vtp.py: <map>.vtp (one PartId part per
#                                 surface) and <map>-cameras.json (one camera per spawn point)
#   derived/doom/                 with --levels: Doom maps of Freedoom (the package's WADs)
#                                 converted by scripts/wad-to-portals.py into the portal scene
#                                 format: <map>.vtp (RoomId = sector), <map>-portals.vtp
#                                 (RoomA/RoomB), <map>-cameras.json (player starts) and
#                                 <map>-things-cameras.json (a camera per thing: benchmarks)
#   manifest.txt                  key=relative/path, one per line, sorted by key
#
# Sources and licences: assimp-testmodels (Debian, assimp's test corpus, various licences, see
# usr/share/doc/assimp-testmodels/copyright), stl-models@0.12.0 and bunny@1.0.1 (npm; the Stanford
# bunny is from the Stanford 3D Scanning Repository), kicad-packages3d (Debian, CC-BY-SA 4.0 with
# exception), openarena-085-data (Debian, GPL-2+, see usr/share/doc/openarena-085-data/copyright;
# its pak6-patch085.pk3 holds the 12 maps of OpenArena 0.8.5; openarena-data's pak0.pk3 has none),
# freedoom (Debian, BSD-3-Clause-style "freedoom-license", see usr/share/doc/freedoom/copyright).
#
# Usage: scripts/fetch-data.sh [--kicad] [--levels] [--dir DIR] [--help]
#   --kicad    also fetch kicad-packages3d (379 MB download; only *.wrl files are kept)
#   --levels   also fetch openarena-085-data (37 MB download) and convert its 12 Quake-3 maps
#              (keys level-<map> and level-<map>-cameras; python3 needed), and freedoom (16 MB
#              download) and convert two Doom maps into cells and portals: freedoom2's MAP12, the
#              largest of both WADs (1,692 sectors, 5,772 open portals), and its MAP01 (198
#              sectors) for tests (keys doom-<map>, doom-<map>-portals, doom-<map>-cameras,
#              doom-<map>-things-cameras)
#   --dir DIR  cache directory (overrides SCENEVIS_DATA_DIR)
set -euo pipefail

DATA_DIR="${SCENEVIS_DATA_DIR:-$HOME/.cache/scenevis-data}"
WITH_KICAD=0
WITH_LEVELS=0

usage()
{
  sed -n '2,/^set -euo/p' "$0" | sed -e '/^set -euo/d' -e 's/^# \{0,1\}//'
}

while [ $# -gt 0 ]; do
  case "$1" in
    --kicad) WITH_KICAD=1 ;;
    --levels) WITH_LEVELS=1 ;;
    --dir)
      [ $# -ge 2 ] || { echo "fetch-data: --dir needs an argument" >&2; exit 2; }
      DATA_DIR="$2"
      shift
      ;;
    -h | --help) usage; exit 0 ;;
    *) echo "fetch-data: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done

# Pinned versions: benchmarks compare numbers across runs, so the data must not drift silently.
NPM_PACKAGES=(stl-models@0.12.0 bunny@1.0.1)

log() { printf 'fetch-data: %s\n' "$*"; }
die() { printf 'fetch-data: error: %s\n' "$*" >&2; exit 1; }

for tool in apt-get dpkg; do
  command -v "$tool" > /dev/null || die "'$tool' not found (Debian/Ubuntu host needed for the .deb models)"
done

mkdir -p "$DATA_DIR"
DATA_DIR="$(cd "$DATA_DIR" && pwd)"
case "$DATA_DIR/" in
  "$(cd "$(dirname "$0")/.." && pwd)/"*) die "the cache must be outside the source tree: $DATA_DIR" ;;
esac
mkdir -p "$DATA_DIR/debs" "$DATA_DIR/debian" "$DATA_DIR/npm" "$DATA_DIR/derived"

# fetch_deb PACKAGE KEEP_DEB [DPKG_EXTRACT_FILTER...]: download and unpack a Debian package into
# debian/PACKAGE unless the stamp says this version is already there. KEEP_DEB=0 deletes the .deb
# after unpacking (the stamp makes it unnecessary; kicad's is 379 MB). The optional filter is a
# list of glob patterns; when given, only matching files are kept (kicad's STEP files are not
# wanted, only its VRML).
fetch_deb()
{
  local pkg="$1"
  local keep="$2"
  shift 2
  local dest="$DATA_DIR/debian/$pkg"
  local stamp="$dest/.scenevis-stamp"
  if [ -f "$stamp" ]; then
    log "$pkg: present ($(cat "$stamp"))"
    return 0
  fi
  local deb
  deb="$(ls "$DATA_DIR/debs/${pkg}"_*.deb 2> /dev/null | head -n 1 || true)"
  if [ -z "$deb" ]; then
    log "$pkg: downloading"
    # apt-get download only needs the package lists; on a fresh container they are missing, so
    # refresh them once and retry rather than asking the user to do it.
    if ! (cd "$DATA_DIR/debs" && apt-get download "$pkg" 2> "$DATA_DIR/debs/apt.log"); then
      log "$pkg: apt-get download failed; running apt-get update once and retrying"
      apt-get update > /dev/null || die "apt-get update failed (need root or sudo for the lists?)"
      (cd "$DATA_DIR/debs" && apt-get download "$pkg") || die "apt-get download $pkg failed"
    fi
    deb="$(ls "$DATA_DIR/debs/${pkg}"_*.deb | head -n 1)"
  fi
  log "$pkg: unpacking $(basename "$deb")"
  rm -rf "$dest.tmp"
  mkdir -p "$dest.tmp"
  if [ $# -gt 0 ]; then
    # Stream the data tarball so only the wanted files ever hit the disk.
    dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$dest.tmp" --wildcards "$@"
  else
    dpkg -x "$deb" "$dest.tmp"
  fi
  rm -rf "$dest"
  mv "$dest.tmp" "$dest"
  basename "$deb" > "$stamp"
  if [ "$keep" = 0 ]; then
    rm -f "$deb"
  fi
}

fetch_npm()
{
  local missing=()
  local spec name version installed
  for spec in "${NPM_PACKAGES[@]}"; do
    name="${spec%@*}"
    version="${spec##*@}"
    installed=""
    if [ -f "$DATA_DIR/npm/node_modules/$name/package.json" ]; then
      installed="$(node -e 'process.stdout.write(require(process.argv[1]).version)' \
        "$DATA_DIR/npm/node_modules/$name/package.json")"
    fi
    if [ "$installed" = "$version" ]; then
      log "$name: present ($version)"
    else
      missing+=("$spec")
    fi
  done
  if [ ${#missing[@]} -gt 0 ]; then
    log "npm: installing ${missing[*]}"
    # --no-save keeps npm from growing a package.json we would then have to maintain.
    npm install --prefix "$DATA_DIR/npm" --no-save --no-audit --no-fund --loglevel=error \
      "${missing[@]}"
  fi
}

# The bunny npm package is a JS module ({positions, cells}); our readers want a file, so write it
# out once as ASCII PLY (ASCII: diffable and readable by vtkPLYReader).
derive_bunny_ply()
{
  local out="$DATA_DIR/derived/bunny.ply"
  if [ -s "$out" ]; then
    log "bunny.ply: present"
    return 0
  fi
  log "bunny.ply: writing from the bunny npm module"
  node -e '
    const b = require(process.argv[1]);
    const lines = ["ply", "format ascii 1.0", "comment Stanford bunny via npm bunny@1.0.1",
      "element vertex " + b.positions.length, "property float x", "property float y",
      "property float z", "element face " + b.cells.length,
      "property list uchar int vertex_indices", "end_header"];
    for (const p of b.positions) lines.push(p.join(" "));
    for (const c of b.cells) lines.push(c.length + " " + c.join(" "));
    require("fs").writeFileSync(process.argv[2] + ".tmp", lines.join("\n") + "\n");
    require("fs").renameSync(process.argv[2] + ".tmp", process.argv[2]);
  ' "$DATA_DIR/npm/node_modules/bunny" "$out"
}

# Quake-3 levels: the maps' .bsp files out of the .pk3 (a zip), each converted into a .vtp and
# a camera file. The stamp names the package and the converter's checksum, so a new converter
# converts again.
derive_levels()
{
  local pk3="$DATA_DIR/debian/openarena-085-data/usr/share/games/openarena/baseoa/pak6-patch085.pk3"
  local out="$DATA_DIR/derived/levels"
  local converter
  converter="$(cd "$(dirname "$0")" && pwd)/q3bsp-to-vtp.py"
  [ -f "$pk3" ] || die "openarena-085-data has no $pk3"
  local want
  want="$(cat "$DATA_DIR/debian/openarena-085-data/.scenevis-stamp") $(sha256sum "$converter" | cut -c1-16)"
  if [ -f "$out/.scenevis-stamp" ] && [ "$(cat "$out/.scenevis-stamp")" = "$want" ]; then
    log "levels: present ($(ls "$out"/*.vtp | wc -l) maps)"
    return 0
  fi
  command -v python3 > /dev/null || die "'python3' not found (needed to convert the levels)"
  log "levels: extracting the maps and converting them"
  rm -rf "$out.tmp"
  mkdir -p "$out.tmp/bsp"
  python3 -c '
import os, sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as pk3:
    for entry in pk3.infolist():
        if entry.filename.startswith("maps/") and entry.filename.endswith(".bsp"):
            with open(os.path.join(sys.argv[2], os.path.basename(entry.filename)), "wb") as f:
                f.write(pk3.read(entry))
' "$pk3" "$out.tmp/bsp"
  local bsp map
  for bsp in "$out.tmp"/bsp/*.bsp; do
    map="$(basename "$bsp" .bsp)"
    python3 "$converter" "$bsp" "$out.tmp/$map.vtp" "$out.tmp/$map-cameras.json" \
      > "$out.tmp/$map.log" || die "converting $map failed"
    log "level $map: $(sed 's/^q3bsp-to-vtp: [^:]*: //' "$out.tmp/$map.log")"
  done
  echo "$want" > "$out.tmp/.scenevis-stamp"
  rm -rf "$out"
  mv "$out.tmp" "$out"
}

# Doom maps: the WADs stay where the package puts them; each pinned map is converted into the
# portal scene format. The stamp names the package and the converter's checksum, as above.
DOOM_MAPS=(freedoom2:MAP12 freedoom2:MAP01)
derive_doom()
{
  local wads="$DATA_DIR/debian/freedoom/usr/share/games/doom"
  local out="$DATA_DIR/derived/doom"
  local converter
  converter="$(cd "$(dirname "$0")" && pwd)/wad-to-portals.py"
  local want
  want="$(cat "$DATA_DIR/debian/freedoom/.scenevis-stamp") $(sha256sum "$converter" | cut -c1-16) ${DOOM_MAPS[*]}"
  if [ -f "$out/.scenevis-stamp" ] && [ "$(cat "$out/.scenevis-stamp")" = "$want" ]; then
    log "doom: present ($(ls "$out"/*-portals.vtp | wc -l) maps)"
    return 0
  fi
  command -v python3 > /dev/null || die "'python3' not found (needed to convert the Doom maps)"
  rm -rf "$out.tmp"
  mkdir -p "$out.tmp"
  local entry wad map name
  for entry in "${DOOM_MAPS[@]}"; do
    wad="${entry%%:*}"
    map="${entry##*:}"
    name="$(echo "$map" | tr '[:upper:]' '[:lower:]')"
    [ -f "$wads/$wad.wad" ] || die "freedoom has no $wads/$wad.wad"
    python3 "$converter" "$wads/$wad.wad" "$map" "$out.tmp/$name.vtp" "$out.tmp/$name-portals.vtp" \
      "$out.tmp/$name-cameras.json" --all-things "$out.tmp/$name-things-cameras.json" \
      > "$out.tmp/$name.log" || die "converting $wad $map failed"
    log "doom $name: $(sed 's/^wad-to-portals: [^:]*: //' "$out.tmp/$name.log")"
  done
  echo "$want" > "$out.tmp/.scenevis-stamp"
  rm -rf "$out"
  mv "$out.tmp" "$out"
}

start=$(date +%s)
command -v npm > /dev/null || die "'npm' not found (needed for stl-models and bunny)"
fetch_deb assimp-testmodels 1
if [ "$WITH_KICAD" = 1 ]; then
  fetch_deb kicad-packages3d 0 '*.wrl' './usr/share/doc/*'
fi
if [ "$WITH_LEVELS" = 1 ]; then
  fetch_deb openarena-085-data 0 './usr/share/games/openarena/baseoa/pak6-patch085.pk3' \
    './usr/share/doc/*'
  derive_levels
  fetch_deb freedoom 0 './usr/share/games/doom/*.wad' './usr/share/doc/*'
  derive_doom
fi
fetch_npm
derive_bunny_ply

# Manifest: stable keys -> paths relative to DATA_DIR. Tests read this instead of hard-coding
# the package layout, so a Debian/npm version bump only touches this script.
A=debian/assimp-testmodels/usr/share/assimp/models
declare -A files=(
  [engine-glb]="$A/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
  [wuson-obj]="$A/OBJ/WusonOBJ.obj"
  [wuson-ply]="$A/PLY/Wuson.ply"
  [wuson-stl]="$A/STL/Wuson.stl"
  [wuson-wrl]="$A/WRL/Wuson.wrl"
  [ifc-house]="$A/IFC/AC14-FZK-Haus.ifc"
  [assimp-models-dir]="$A"
  [bunny-stl]="npm/node_modules/stl-models/objects/bunny.bin.stl"
  # stl-models calls its malformed files "broken" (bad headers, wrong counts, NaN normals, ...).
  [stl-broken-dir]="npm/node_modules/stl-models/broken"
  [stl-misc-dir]="npm/node_modules/stl-models/misc"
  [stl-models-dir]="npm/node_modules/stl-models/objects"
  [bunny-ply]="derived/bunny.ply"
)
if [ -d "$DATA_DIR/debian/kicad-packages3d" ]; then
  files[kicad-wrl-dir]="debian/kicad-packages3d/usr/share/kicad/3dmodels"
fi
# The levels stay listed once converted, also in runs without --levels.
if [ -f "$DATA_DIR/derived/levels/.scenevis-stamp" ]; then
  files[levels-dir]="derived/levels"
  for level in "$DATA_DIR"/derived/levels/*.vtp; do
    map="$(basename "$level" .vtp)"
    files[level-$map]="derived/levels/$map.vtp"
    files[level-$map-cameras]="derived/levels/$map-cameras.json"
  done
fi

if [ -f "$DATA_DIR/derived/doom/.scenevis-stamp" ]; then
  for level in "$DATA_DIR"/derived/doom/*-portals.vtp; do
    map="$(basename "$level" -portals.vtp)"
    files[doom-$map]="derived/doom/$map.vtp"
    files[doom-$map-portals]="derived/doom/$map-portals.vtp"
    files[doom-$map-cameras]="derived/doom/$map-cameras.json"
    files[doom-$map-things-cameras]="derived/doom/$map-things-cameras.json"
  done
fi

manifest="$DATA_DIR/manifest.txt"
{
  echo "# SceneVis data manifest: key=path relative to this file's directory"
  for key in $(printf '%s\n' "${!files[@]}" | sort); do
    path="${files[$key]}"
    if [ -e "$DATA_DIR/$path" ]; then
      echo "$key=$path"
    else
      echo "fetch-data: warning: $key missing: $path" >&2
    fi
  done
} > "$manifest.tmp"
mv "$manifest.tmp" "$manifest"

echo
echo "SceneVis data in $DATA_DIR"
printf '%-26s %12s  %s\n' KEY SIZE PATH
grep -v '^#' "$manifest" | while IFS='=' read -r key path; do
  if [ -d "$DATA_DIR/$path" ]; then
    size="$(du -sh "$DATA_DIR/$path" | cut -f1) ($(find "$DATA_DIR/$path" -type f | wc -l) files)"
  else
    size="$(stat -c %s "$DATA_DIR/$path")"
  fi
  printf '%-26s %12s  %s\n' "$key" "$size" "$path"
done
echo "manifest: $manifest ($(($(date +%s) - start)) s)"

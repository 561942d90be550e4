#!/usr/bin/env bash
# The lean bundle end to end: builds build-bundle-lean/ (PATHLET_LEAN=ON, no tests: the command,
# the plugins and the Python module), packs it with the real compression, checks it is at most
# 15 MiB, and uses it as a plain user (check_bundle.sh lean): render, validate, import pathlet,
# pictures identical to the full build's command (REFERENCE, required), and EXR, quality's
# ray-traced reference and HDF5 refused (image_io_stb.cpp, rt_ao_absent.cpp, hdf5_field_absent.cpp).
# Every build compiles through ccache when it is installed (cmake/PathletBuild.cmake), so the lean
# build reuses the full build's object files: only the sources that differ compile, and when
# REFERENCE's tree was built through ccache any other compile that misses the cache fails the
# test (a source the lean build changes must compile outside the unity batches: engine/CMakeLists.txt).
# Without ccache it is a whole lean build (minutes on two cores).
#   tests/bundle/test_lean_bundle.sh WORK REFERENCE_PATHLET [-- CMAKE_ARGS...]
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
WORK=${1:?usage: test_lean_bundle.sh WORK REFERENCE_PATHLET [-- CMAKE_ARGS...]}
REFERENCE=${2:?usage: test_lean_bundle.sh WORK REFERENCE_PATHLET [-- CMAKE_ARGS...]}
shift 2
[ "${1:-}" = "--" ] && shift
[ -x "$REFERENCE" ] || { echo "FAIL: no reference command '$REFERENCE': the lean bundle's pictures are compared with the full build's"; exit 1; }
mkdir -p "$WORK"
# ccache's record of each compile (a "# SOURCE" line, then hit or miss counters).
export CCACHE_STATSLOG=$WORK/ccache-stats.log
rm -f "$CCACHE_STATSLOG"
start=$(date +%s)
"$SRC/scripts/bundle.sh" --lean "$WORK/pathlet-lean.tar.xz" -- "$@"
echo "lean build and packing: $(($(date +%s) - start)) s"
# What the lean build may compile anew: the sources whose text differs from the full build's.
lean_only="image_io.cpp image_io_stb.cpp build_info.cpp hdf5_field_absent.cpp rt_ao_absent.cpp"
reference_tree=$(dirname "$(dirname "$REFERENCE")")
if ! command -v ccache >/dev/null; then
  echo "note: no ccache, so the lean build compiled everything (scripts/install-deps.sh installs ccache)"
elif ! grep -q '^CMAKE_BUILD_TYPE:STRING=Release$' "$reference_tree/CMakeCache.txt" 2>/dev/null ||
     ! grep -q ccache "$reference_tree/engine/CMakeFiles/pathlet.dir/build.make"; then
  echo "note: $reference_tree is not a Release build through ccache: the lean build's cache hits are not checked"
else
  missed=$(awk '/^# /{unit=$2} /^cache_miss$/{print unit}' "$CCACHE_STATSLOG" | xargs -rn1 basename | sort -u)
  hits=$(grep -c '^direct_cache_hit$\|^preprocessed_cache_hit$' "$CCACHE_STATSLOG" || true)
  echo "lean build: $hits compiles from the full build's cache; compiled anew: $(echo $missed)"
  unexpected=$(comm -23 <(echo "$missed" | sed '/^$/d') <(printf '%s\n' $lean_only | sort))
  [ -z "$unexpected" ] || { echo "FAIL: the lean build compiled $(echo $unexpected) again, which the full build had compiled"; exit 1; }
fi
size=$(stat -c %s "$WORK/pathlet-lean.tar.xz")
limit=$((15 * 1024 * 1024))
[ "$size" -le "$limit" ] || { echo "FAIL: the lean bundle is $size bytes, over 15 MiB"; exit 1; }
# Its pictures are the full build's (same shaders; PNG through stb vs OIIO): compared pixel by pixel.
"$SRC/tests/bundle/check_bundle.sh" "$WORK/pathlet-lean.tar.xz" "$SRC" "$WORK/check" lean "$REFERENCE"
rm -rf "$WORK"

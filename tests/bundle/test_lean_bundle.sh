#!/usr/bin/env bash
# The lean bundle end to end: builds build-bundle-lean/ (PATHLET_LEAN=ON, no tests: the command,
# the plugins and the Python module), packs it with the real compression, checks it is at most
# 15 MiB, and uses it as a plain user (check_bundle.sh lean): render, validate, import pathlet,
# pictures identical to the full build's command (REFERENCE, required), and EXR, quality's
# ray-traced reference and HDF5 refused (image_io_stb.cpp, rt_ao_absent.cpp, hdf5_field_absent.cpp).
# With ccache (scripts/install-deps.sh installs it; scripts/test.sh compiles a fresh build tree
# through it) the lean build reuses the full build's object files: only the few sources that
# differ compile (ccache's preprocessed mode matches across the two trees with CCACHE_BASEDIR the
# source tree). Without ccache it is a whole lean build (minutes on two cores).
#   tests/bundle/test_lean_bundle.sh WORK REFERENCE_PATHLET [-- CMAKE_ARGS...]
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
WORK=${1:?usage: test_lean_bundle.sh WORK REFERENCE_PATHLET [-- CMAKE_ARGS...]}
REFERENCE=${2:?usage: test_lean_bundle.sh WORK REFERENCE_PATHLET [-- CMAKE_ARGS...]}
shift 2
[ "${1:-}" = "--" ] && shift
[ -x "$REFERENCE" ] || { echo "FAIL: no reference command '$REFERENCE': the lean bundle's pictures are compared with the full build's"; exit 1; }
args=("$@")
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$SRC}
  args=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache "${args[@]}")
else
  echo "note: no ccache, so the lean build compiles everything (scripts/install-deps.sh installs ccache)"
fi
mkdir -p "$WORK"
start=$(date +%s)
"$SRC/scripts/bundle.sh" --lean "$WORK/pathlet-lean.tar.xz" -- "${args[@]}"
echo "lean build and packing: $(($(date +%s) - start)) s"
size=$(stat -c %s "$WORK/pathlet-lean.tar.xz")
limit=$((15 * 1024 * 1024))
[ "$size" -le "$limit" ] || { echo "FAIL: the lean bundle is $size bytes, over 15 MiB"; exit 1; }
# Its pictures are the full build's (same shaders; PNG through stb vs OIIO): compared pixel by pixel.
"$SRC/tests/bundle/check_bundle.sh" "$WORK/pathlet-lean.tar.xz" "$SRC" "$WORK/check" lean "$REFERENCE"
rm -rf "$WORK"

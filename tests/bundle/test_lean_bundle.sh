#!/usr/bin/env bash
# The lean bundle end to end: builds build-bundle-lean/ (PATHLET_LEAN=ON, no tests; minutes on
# two cores without a compiler cache, so not part of scripts/test.sh), packs it with the real
# compression, checks it is at most 15 MiB, and uses it as a plain user (check_bundle.sh lean):
# render, validate, import pathlet, and EXR, quality's ray-traced reference and HDF5 refused.
#   tests/bundle/test_lean_bundle.sh [WORK] [-- CMAKE_ARGS...]    (e.g. -- -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
WORK=${1:-$(mktemp -d)}
shift || true
[ "${1:-}" = "--" ] && shift
mkdir -p "$WORK"
"$SRC/scripts/bundle.sh" --lean "$WORK/pathlet-lean.tar.xz" -- "$@"
size=$(stat -c %s "$WORK/pathlet-lean.tar.xz")
limit=$((15 * 1024 * 1024))
[ "$size" -le "$limit" ] || { echo "FAIL: the lean bundle is $size bytes, over 15 MiB"; exit 1; }
# Its pictures are the full build's where one is there (same shaders; PNG through stb vs OIIO).
reference=()
[ -x "$SRC/build/bin/pathlet" ] && reference=("$SRC/build/bin/pathlet")
"$SRC/tests/bundle/check_bundle.sh" "$WORK/pathlet-lean.tar.xz" "$SRC" "$WORK/check" lean "${reference[@]}"

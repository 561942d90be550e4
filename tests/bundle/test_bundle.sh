#!/usr/bin/env bash
# The default bundle, made from this build tree (scripts/bundle.sh --from) as a folder (packing
# its 430 MB takes minutes; test_lean_bundle.sh tests the tarball round trip) and used as a plain
# user with a clean environment (check_bundle.sh). The lean bundle needs its own build:
# tests/bundle/test_lean_bundle.sh.
set -euo pipefail
BUILD=$1 SRC=$2 WORK=$3
rm -rf "$WORK"
mkdir -p "$WORK"
"$SRC/scripts/bundle.sh" --from "$BUILD" "$WORK/unpacked"
"$SRC/tests/bundle/check_bundle.sh" "$WORK/unpacked" "$SRC" "$WORK/check" default "$BUILD/bin/pathlet"
rm -rf "$WORK"  # a few hundred MB

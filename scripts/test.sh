#!/usr/bin/env bash
# Builds everything and runs every test (real GL through EGL on Mesa llvmpipe).
# A fresh build tree compiles through ccache (scripts/install-deps.sh installs it): the lean
# bundle's test (ctest bundle.lean, its own lean build) then reuses these object files. An
# existing tree keeps the compiler it was configured with.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
if command -v ccache >/dev/null; then
  export CMAKE_C_COMPILER_LAUNCHER=${CMAKE_C_COMPILER_LAUNCHER-ccache} CMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER-ccache}
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
fi
scripts/build.sh
cd build
ctest --output-on-failure -j2 --timeout 600 "$@"

#!/usr/bin/env bash
# Configures and builds Pathlet (Release) into build/ ($PATHLET_BUILD_DIR to build elsewhere).
#   scripts/build.sh [--runtime] [CMAKE_ARGS...]
#     --runtime   only what `pathlet` runs: the command, the pass plugins and the share folder
#                 (target pathlet_runtime); no tests, benchmarks, Python module or fuzzers.
#                 scripts/main.sh builds this; scripts/test.sh builds everything.
#     CMAKE_ARGS  go to the configure step (PATHLET_CONFIGURE=0 skips it: an existing tree).
# The build's output is also kept in BUILD/build.log (tests/main_job reads it).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${PATHLET_BUILD_DIR:-build}
targets=()
if [ "${1:-}" = "--runtime" ]; then
  targets=(--target pathlet_runtime)
  shift
fi
if [ "${PATHLET_CONFIGURE:-1}" != 0 ]; then
  cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
fi
cmake --build "$BUILD" -j"$(nproc)" "${targets[@]}" 2>&1 | tee "$BUILD/build.log"

#!/usr/bin/env bash
# Builds everything and runs every test (real GL through EGL on Mesa llvmpipe).
# Compiles through ccache, as scripts/main.sh does (cmake/PathletBuild.cmake; scripts/install-deps.sh
# installs it): after the main job only the tests, benchmarks and the Python module compile, and
# the lean bundle's test (ctest bundle.lean, its own lean build) reuses these object files.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j2 --timeout 600 "$@"

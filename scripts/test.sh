#!/usr/bin/env bash
# Builds everything and runs every test (real GL through EGL on Mesa llvmpipe).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j2 --timeout 600 "$@"

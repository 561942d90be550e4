#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build what the render
# runs (the `pathlet` command, the pass plugins and the share folder; scripts/test.sh builds the
# tests, benchmarks and the Python module), and render the built-in aortic-arch phantom
# (generated on first use, then cached) through the LineAO graph (variant 1) to
# out/variant1_lineao/*.png (+ out/variant1_lineao.mp4 when ffmpeg exists), printing the
# per-pass timing table.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh --runtime
video=()
command -v ffmpeg >/dev/null && video=(--video out/variant1_lineao.mp4)
build/bin/pathlet render variant1_lineao --time 0:18:0.25 --size 1280x720 --out out \
  --report out/variant1_lineao_timing "${video[@]}" "$@"

#!/usr/bin/env bash
# Regenerates golden images deliberately: runs the GL test binaries (optionally only the
# tests matching a gtest filter) with PATHLET_UPDATE_GOLDENS=1, then lists which goldens
# changed so you can look at each before committing. ctest never updates goldens (it clears
# the variable), so a stray environment cannot rewrite them.
#   scripts/update-goldens.sh [GTEST_FILTER]      e.g. scripts/update-goldens.sh 'Oit.*'
set -euo pipefail
cd "$(dirname "$0")/.."
FILTER=${1:-*}
# A shader cache of this run only (as ctest's, tests/PathletTest.cmake): LLVM compiles a shader once.
MESA_SHADER_CACHE_DIR=$(mktemp -d /tmp/pathlet_goldens_mesa.XXXXXX)
trap 'rm -rf "$MESA_SHADER_CACHE_DIR"' EXIT
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe MESA_SHADER_CACHE_DISABLE=false MESA_SHADER_CACHE_DIR PATHLET_PLUGIN_PATH= \
  PATHLET_UPDATE_GOLDENS=1 PATHLET_REAL_DATA_DIR="${PATHLET_REAL_DATA_DIR:-$PWD/../shared/data/real}"
for t in build/bin/test_*; do
  "$t" --gtest_filter="$FILTER" --gtest_brief=1 >/dev/null 2>&1 || true
done
# gpu_check.quick's renders of every shipped graph (tests/gpu_check/goldens), with everything.
[ "$FILTER" = "*" ] && XDG_CONFIG_HOME=$PWD/build/test-config tests/gpu_check/test_gpu_check.sh "$PWD" build/bin/pathlet >/dev/null
changed=$(git status --porcelain -- '*/goldens/*' | awk '{print $2}')
if [ -z "$changed" ]; then
  echo "update-goldens: no golden changed"
else
  echo "update-goldens: changed (look at each, e.g. with the diff images in build/**/golden_failures/):"
  echo "$changed" | sed 's/^/  /'
fi

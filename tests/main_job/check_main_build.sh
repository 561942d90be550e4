#!/usr/bin/env bash
# scripts/main.sh builds only what its render runs (issue 35): its build step, run on this built
# tree without configuring, names in its log (BUILD/build.log, "Built target X") the command,
# the plugins and the share folder, and no test, benchmark, fuzzer, test fixture or Python module.
set -euo pipefail
BUILD=$1 SRC=$2
grep -q '^CMAKE_GENERATOR:INTERNAL=Unix Makefiles$' "$BUILD/CMakeCache.txt" ||
  { echo "skipped: the log check reads the Makefiles generator's 'Built target' lines"; exit 77; }
steps=$(grep -E '^[^#]*scripts/build\.sh' "$SRC/scripts/main.sh")
[ "$(echo "$steps" | wc -l)" = 1 ] || { echo "FAIL: main.sh builds more than once: $steps"; exit 1; }
step=$(echo "$steps" | sed -E 's/^[[:space:]]*//')
case "$step" in scripts/build.sh*) ;; *) echo "FAIL: main.sh's build step is '$step'"; exit 1 ;; esac
(cd "$SRC" && PATHLET_BUILD_DIR="$BUILD" PATHLET_CONFIGURE=0 bash -c "$step" >/dev/null)
built=$(sed -n 's/.*Built target \([A-Za-z0-9_.+-]*\).*/\1/p' "$BUILD/build.log" | sort -u)
echo "main.sh builds: $(echo $built)"
bad=$(echo "$built" | grep -E '^(test_|bench_|fuzz_|fixture_|_pathlet$|pathlet_python$|pathlet_test|make_seeds$|gtest|gmock|benchmark|kit_probe$|vao_fragment_probe$)' || true)
[ -z "$bad" ] || { echo "FAIL: main.sh builds $(echo $bad)"; exit 1; }
for want in pathlet pathlet_cli pathlet_share lineao overlay gbuffer; do
  echo "$built" | grep -qx "$want" || { echo "FAIL: main.sh does not build $want"; exit 1; }
done

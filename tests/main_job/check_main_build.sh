#!/usr/bin/env bash
# scripts/main.sh builds only what its render runs: its build step, run on this built
# tree without configuring, names in its log (BUILD/build.log, "Built target X") the command,
# the plugins and the share folder, and nothing that is not on their allow-list (no test,
# benchmark, fuzzer, test fixture or Python module).
set -euo pipefail
BUILD=$1 SRC=$2
grep -q '^CMAKE_GENERATOR:INTERNAL=Unix Makefiles$' "$BUILD/CMakeCache.txt" ||
  { echo "skipped: the log check reads the Makefiles generator's 'Built target' lines"; exit 77; }
steps=$(grep -E '^[^#]*scripts/build\.sh' "$SRC/scripts/main.sh")
[ "$(echo "$steps" | wc -l)" = 1 ] || { echo "FAIL: main.sh builds more than once: $steps"; exit 1; }
step=$(echo "$steps" | sed -E 's/^[[:space:]]*//')
case "$step" in scripts/build.sh*) ;; *) echo "FAIL: main.sh's build step is '$step'"; exit 1 ;; esac
# The step rewrites BUILD/build.log: the log of the build that made this tree is put back after.
saved=$(mktemp)
if [ -f "$BUILD/build.log" ]; then
  cp -p "$BUILD/build.log" "$saved"
  trap 'mv "$saved" "$BUILD/build.log"' EXIT
else
  trap 'rm -f "$saved"' EXIT
fi
(cd "$SRC" && PATHLET_BUILD_DIR="$BUILD" PATHLET_CONFIGURE=0 bash -c "$step" >/dev/null)
built=$(sed -n 's/.*Built target \([A-Za-z0-9_.+-]*\).*/\1/p' "$BUILD/build.log" | sort -u)
echo "main.sh builds: $(echo $built)"
# An allow-list: the engine's runtime targets and each shipped pass (passes/*/CMakeLists.txt's
# pathlet_add_pass, not NO_INSTALL) with its shaders. Anything else (a test, benchmark, fuzzer,
# fixture plugin, the Python module, a target named tomorrow) is a failure.
allowed="pathlet pathlet_cli pathlet_share pathlet_runtime pathlet_base pathlet_data pathlet_sdk_fingerprint pathlet_app_support
  pathlet_bench pathlet_quality pathlet_pass_pch"  # pathlet_pass_pch: the plugins' precompiled header
passes=""
for f in "$SRC"/passes/*/CMakeLists.txt; do
  grep -q 'NO_INSTALL' "$f" && continue
  passes="$passes $(sed -n 's/^[[:space:]]*pathlet_add_pass(\([A-Za-z0-9_]*\).*/\1/p' "$f")"
done
for pass in $passes; do allowed="$allowed $pass ${pass}_shaders"; done
bad=$(comm -23 <(echo "$built") <(printf '%s\n' $allowed | sort -u))
[ -z "$bad" ] || { echo "FAIL: main.sh builds $(echo $bad), none of the command, the shipped plugins or the share folder"; exit 1; }
for want in pathlet pathlet_cli pathlet_share $passes; do
  echo "$built" | grep -qx "$want" || { echo "FAIL: main.sh does not build $want"; exit 1; }
done

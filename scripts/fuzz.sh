#!/usr/bin/env bash
# Runs every fuzz target (tests/fuzz) for SECONDS each (default 60) under ASan+UBSan, after
# replaying the checked-in regression inputs. A crash, sanitizer report, uncaught exception or a
# single allocation over 512 MB fails the run; the input is saved in build-san/fuzz-findings/.
# Targets run side by side, one a core (FUZZ_JOBS=N to change).
#   scripts/fuzz.sh [SECONDS] [TARGET...]      (builds with scripts/sanitize.sh's settings)
# FUZZ_SEED=N fixes libFuzzer's random seed (CI does, so a red run is reproducible and a finding
# does not appear by chance on an unrelated change); unset, every run explores anew.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${1:-60}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && mapfile -t TARGETS < <(grep -v '^#' tests/fuzz/targets.txt)
if [ ! -x build-san/bin/make_seeds ]; then
  CC=clang-14 CXX=clang++-14 cmake -S . -B build-san -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPATHLET_FUZZ=ON \
    -DPATHLET_BUILD_BENCHMARKS=OFF >/dev/null
fi
cmake --build build-san -j"$(nproc)" --target make_seeds $(printf 'fuzz_%s ' "${TARGETS[@]}") >/dev/null
CORPUS=build-san/fuzz-corpus FINDINGS=build-san/fuzz-findings
mkdir -p "$CORPUS" "$FINDINGS"
rm -f "$FINDINGS"/*.row
build-san/bin/make_seeds "$CORPUS" . >/dev/null
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# One target a core at a time (libFuzzer runs one thread): each writes its row to $FINDINGS/$t.row,
# printed in the list's order once all have run.
fuzz_one() {
  local t=$1 bin=build-san/bin/fuzz_$1 log="$FINDINGS/$1.log" row="$FINDINGS/$1.row" result
  mkdir -p "$CORPUS/$t"
  # Inputs that once crashed must stay fixed.
  if compgen -G "tests/fuzz/regressions/$t/*" >/dev/null; then
    if ! "$bin" -malloc_limit_mb=512 -rss_limit_mb=2048 tests/fuzz/regressions/$t/* >"$FINDINGS/$t.replay.log" 2>&1; then
      echo "fuzz: $t: a regression input fails again (see $FINDINGS/$t.replay.log)" >"$row"; return 1
    fi
  fi
  local dict=() seed=()
  [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
  [ -n "${FUZZ_SEED:-}" ] && seed=(-seed="$FUZZ_SEED")
  if "$bin" "$CORPUS/$t" "${dict[@]}" -max_total_time="$SECONDS_PER_TARGET" -malloc_limit_mb=512 -rss_limit_mb=2048 \
       -timeout=10 -artifact_prefix="$FINDINGS/$t-" -print_final_stats=1 "${seed[@]}" >"$log" 2>&1; then
    result=ok
  else
    result="FAILED: $(grep -m1 -E 'ERROR|runtime error|Test unit written|terminate called' "$log" || echo 'see log') ($log)"
  fi
  local runs
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  printf '%-12s %10s %10s %s\n' "$t" "${runs:-?}" "$SECONDS_PER_TARGET" "$result" >"$row"
  if [ "$result" != ok ]; then
    # CI keeps only this output: show what crashed and the input that did it.
    { grep -m1 -B2 -A12 -E 'terminate called|ERROR: AddressSanitizer|runtime error|ERROR: libFuzzer' "$log" | sed 's/^/    /' || true
      for a in "$FINDINGS/$t-"*; do [ -f "$a" ] && { echo "    input $a (base64):"; base64 -w 100 "$a" | head -20 | sed 's/^/    /'; }; done
    } >>"$row"
    return 1
  fi
}
export -f fuzz_one
export SECONDS_PER_TARGET CORPUS FINDINGS
JOBS=${FUZZ_JOBS:-$(nproc)}
echo "fuzz: ${#TARGETS[@]} targets, ${SECONDS_PER_TARGET} s each, $JOBS at a time"
failed=0
printf '%s\0' "${TARGETS[@]}" | xargs -0 -n1 -P"$JOBS" bash -c 'fuzz_one "$1"' _ || failed=1
printf '%-12s %10s %10s %s\n' target runs seconds result
for t in "${TARGETS[@]}"; do cat "$FINDINGS/$t.row" 2>/dev/null || { echo "fuzz: $t: no result"; failed=1; }; done
exit "$failed"

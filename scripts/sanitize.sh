#!/usr/bin/env bash
# Builds the data importers, graph code, non-GL test suites and fuzz targets with clang under
# AddressSanitizer + UndefinedBehaviorSanitizer into build-san/, and runs those test suites.
# CI runs it after scripts/test.sh; scripts/fuzz.sh reuses the same build.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t FUZZ_TARGETS < <(grep -v '^#' tests/fuzz/targets.txt)
CC=clang-14 CXX=clang++-14 cmake -S . -B build-san -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPATHLET_FUZZ=ON \
  -DPATHLET_BUILD_BENCHMARKS=OFF "$@" >/dev/null
targets=(make_seeds test_io test_trace test_graph)
for t in "${FUZZ_TARGETS[@]}"; do targets+=("fuzz_$t"); done
echo "sanitize: building ${#targets[@]} targets with ASan+UBSan (clang-14)"
cmake --build build-san -j"$(nproc)" --target "${targets[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export PATHLET_REAL_DATA_DIR="${PATHLET_REAL_DATA_DIR:-$PWD/../shared/data/real}"
failed=0
for t in test_io test_trace test_graph; do
  echo "sanitize: $t"
  "build-san/bin/$t" --gtest_brief=1 || failed=1
done
[ "$failed" -eq 0 ] && echo "sanitize: all non-GL suites clean under ASan+UBSan"
exit "$failed"

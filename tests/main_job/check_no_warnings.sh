#!/usr/bin/env bash
# The build that made this tree printed no compiler or linker warning. It reads BUILD/build.log,
# which scripts/build.sh writes (the whole build in CI; after the main job, what test.sh added).
#   check_no_warnings.sh BUILD [LOG]   (LOG: another log to check, e.g. to show the check fails)
set -euo pipefail
BUILD=$1
log=${2:-$BUILD/build.log}
[ -s "$log" ] || { echo "skipped: no $log (scripts/build.sh writes it)"; exit 77; }
found=$(grep -E '(^|[^A-Za-z])warning:' "$log" || true)
if [ -n "$found" ]; then
  echo "$found" | head -20
  echo "FAIL: $(echo "$found" | wc -l) warning(s) in $log (the first 20 above)"
  exit 1
fi
echo "no warning in $log ($(grep -c 'Building C' "$log" || true) compiles)"

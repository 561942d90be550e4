#!/usr/bin/env bash
# Where a build's compile time went, from BUILD/unit-times.tsv (one line per compile: user and
# system CPU seconds, wall seconds, object file; cmake/unit_time.sh writes it): CPU per target,
# the slowest units, the total. A compile under 0.2 s is counted as a ccache hit.
#   scripts/build-times.sh [BUILD] [--top N]       (BUILD: build/; N: 15)
# The log grows with every build of the tree: remove it first to see one build alone.
set -euo pipefail
BUILD=build TOP=15
while [ $# -gt 0 ]; do
  case "$1" in
    --top) TOP=${2:?--top needs a number}; shift ;;
    -h|--help) sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) BUILD=$1 ;;
  esac
  shift
done
LOG=$BUILD/unit-times.tsv
[ -s "$LOG" ] || { echo "build-times: no $LOG (a build configured with PATHLET_UNIT_TIMES=ON writes it)" >&2; exit 1; }
# The target is the folder before .dir in the object's path.
awk -F'\t' -v top="$TOP" '
  { cpu = $1 + $2; n = split($4, p, "/"); t = "?"
    for (i = 1; i <= n; i++) if (p[i] ~ /\.dir$/) { t = substr(p[i], 1, length(p[i]) - 4); break }
    units[t]++; time[t] += cpu; total += cpu; count++; if (cpu < 0.2) { hits[t]++; nhits++ }
    line[count] = sprintf("%8.2f  %s", cpu, $4) }
  END {
    printf "%-32s %6s %6s %9s\n", "target", "units", "hits", "CPU s"
    for (t in units) printf "%-32s %6d %6d %9.1f\n", t, units[t], hits[t], time[t] | "sort -k4 -rn"
    close("sort -k4 -rn")
    printf "%-32s %6d %6d %9.1f\n\nslowest units (CPU s):\n", "total", count, nhits, total
    for (i = 1; i <= count; i++) print line[i] | ("sort -rn | head -" top)
  }' "$LOG"

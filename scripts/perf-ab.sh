#!/usr/bin/env bash
# What a change costs: this tree against its base, on this machine, in the same minutes.
#
#   scripts/perf-ab.sh [BASE] [--rounds N] [--size WxH] [--frames N] [--threshold T] [--all-passes]
#
# BASE (default: the merge base with main) is built in its own tree, build/perf-ab/<commit>/
# (its `git archive`, the runtime only, through ccache when it is on PATH; kept, so the next run
# against it builds nothing: remove build/perf-ab/ to free the space). This tree, uncommitted
# changes included, is built in build/ (target pathlet_runtime). Then both run the same cases on
# the study phantom, interleaved, so load on a busy machine hits both alike: each round runs
# every case with both builds at once (llvmpipe, timed by CPU time: below) or one right after the
# other, which one first alternating (a GPU, timed by the clock):
#   v1, v2, v3, v4      each shipped variant (variant1_lineao, variant2_oit, variant3_geomfade,
#                       variant4_opacity) with its 1 s window, `pathlet bench` at t = 9 s
#   ... every line      the same with window=0; variant 1 also with cull=false
#   render loop         `pathlet render variant1_lineao --no-images` over 41 frames, as a whole
#   start-up            a one-frame render (no warm-up), as a whole
# On a software rasterizer (llvmpipe) everything is the process's CPU time (`bench --timing
# cpu`; a whole run's user + system time), which a busy machine's load barely moves (its wall
# clock moves by tens of per cent); on a GPU, GL timestamps and the wall clock. A BASE without
# `--timing cpu` is timed by the glFinish-bracketed wall clock, and the table says so.
# It prints one table (scripts/perf_ab_table.py): per case its frame time and the passes that
# take at least 5 % of it, base and new medians, the range of new/base over the rounds, and a
# verdict only where every round agrees (every ratio beyond 1 + T, default 0.15). Put the table
# in the closing note of every change to engine/ or passes/ (docs/performance.md).
#   --rounds N     rounds (default 3, at least 2)
#   --size WxH     output size (default 960x540)
#   --frames N     measured frames per bench case (default 5, after 2 warm-up frames)
#   --threshold T  see above; --all-passes lists every pass
#   --keep DIR     keep every run's results in DIR (runs.tsv, as the table reads it, and the logs)
# Exits 0 when the table is printed (whatever it says), 2 on bad usage, 1 when a build or run fails.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

usage() { sed -n '2,33p' "$0"; }
die() { echo "perf-ab: $*" >&2; exit 2; }
positive() { [[ $2 =~ ^[0-9]+$ ]] && (($2 >= $3)) || die "$1 '$2': expected a whole number >= $3"; }

base_arg="" rounds=3 size=960x540 frames=5 threshold=0.15 all_passes=() keep=""
while (($#)); do
  case "$1" in
    --rounds|--size|--frames|--threshold|--keep) (($# >= 2)) || die "$1 needs a value (see --help)" ;;&
    --rounds) positive --rounds "$2" 2; rounds=$2; shift 2 ;;
    --size) [[ $2 =~ ^[1-9][0-9]*x[1-9][0-9]*$ ]] || die "--size '$2': expected WxH, e.g. 960x540"; size=$2; shift 2 ;;
    --frames) positive --frames "$2" 1; frames=$2; shift 2 ;;
    --threshold) [[ $2 =~ ^[0-9]*\.?[0-9]+$ && $2 =~ [1-9] ]] || die "--threshold '$2': expected a fraction > 0, e.g. 0.15"
                 threshold=$2; shift 2 ;;
    --all-passes) all_passes=(--all-passes); shift ;;
    --keep) [[ ! -e $2 ]] || die "--keep '$2': already there (give a new folder)"; keep=$(realpath -m "$2"); shift 2 ;;
    -h|--help) usage; exit 0 ;;
    -*) die "unknown option '$1' (see --help)" ;;
    *) [[ -z $base_arg ]] || die "one BASE only (got '$base_arg' and '$1')"; base_arg=$1; shift ;;
  esac
done

if [[ -z $base_arg ]]; then
  git rev-parse --verify -q main >/dev/null || die "no branch 'main' to take the merge base with: give BASE"
  base_arg=$(git merge-base HEAD main)
fi
base=$(git rev-parse --verify -q "$base_arg^{commit}") || die "BASE '$base_arg' is not a commit of this repository"
short=$(git rev-parse --short "$base")
python=/usr/bin/python3  # Debian's (another python3 may come first on PATH)

# ---- builds -------------------------------------------------------------------------------------
base_dir=$root/build/perf-ab/$short
build_base() {
  [[ -x $base_dir/build/bin/pathlet && -f $base_dir/.built ]] && return
  echo "perf-ab: building BASE $short in $base_dir (the runtime only)" >&2
  rm -rf "$base_dir"
  mkdir -p "$base_dir.tmp"
  git archive "$base" | tar -x -C "$base_dir.tmp"
  mv "$base_dir.tmp" "$base_dir"  # a tree is whole or absent
  # ccache sees the same paths relative to the build folder as in build/ (a tree with its build/ inside).
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  (cd "$base_dir" && export CCACHE_BASEDIR=$base_dir &&
     cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >build.log 2>&1 &&
     cmake --build build --target pathlet_runtime -j"$(nproc)" >>build.log 2>&1) ||
    { tail -30 "$base_dir/build.log" >&2; echo "perf-ab: building BASE $short failed ($base_dir/build.log)" >&2; exit 1; }
  touch "$base_dir/.built"
}
build_new() {
  echo "perf-ab: building this tree in build/ (the runtime only)" >&2
  { [[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release; } >/dev/null &&
    cmake --build build --target pathlet_runtime -j"$(nproc)" >build/perf-ab-new.log 2>&1 ||
    { tail -30 build/perf-ab-new.log >&2; echo "perf-ab: building this tree failed (build/perf-ab-new.log)" >&2; exit 1; }
}
mkdir -p build/perf-ab
build_base
build_new
declare -A bin=([base]=$base_dir/build/bin/pathlet [new]=$root/build/bin/pathlet)
export PATHLET_PLUGIN_PATH=  # each build's own plugins only

# How to time: the process's CPU time on a software rasterizer where both builds have it.
renderer=$("${bin[new]}" info --gl 2>/dev/null | sed -n 's/^GL_RENDERER //p')
timing=(--timing auto) run_clock=wall timing_note="GL timestamps (medians), whole runs by the wall clock"
if [[ ${renderer,,} =~ llvmpipe|softpipe|swrast|swiftshader ]]; then
  if [[ $("${bin[base]}" bench --help 2>&1) == *'auto|gpu|finish|cpu'* ]]; then
    timing=(--timing cpu) run_clock=cpu timing_note="process CPU time (bench --timing cpu; whole runs: user + system)"
  else
    timing=(--timing finish)
    timing_note="the glFinish-bracketed WALL CLOCK: BASE $short has no --timing cpu, so a busy machine's load is in every number"
  fi
fi

# ---- the cases, interleaved -----------------------------------------------------------------------
cases=(
  "v1|bench variant1_lineao"
  "v1 every line|bench variant1_lineao --set window=0"
  "v1 every line, cull=false|bench variant1_lineao --set window=0 --set cull=false"
  "v2|bench variant2_oit"
  "v2 every line|bench variant2_oit --set window=0"
  "v3|bench variant3_geomfade"
  "v3 every line|bench variant3_geomfade --set window=0"
  "v4|bench variant4_opacity"
  "v4 every line|bench variant4_opacity --set window=0"
  "render loop, 41 frames|render variant1_lineao --time 8:12:0.1"
  "start-up, one frame|render variant1_lineao --time 9 --warmup 0"
)
work=$(mktemp -d /tmp/pathlet-perf-ab.XXXXXX)
trap 'rm -rf "$work"' EXIT
runs=$work/runs.tsv
: >"$runs"

# timed LOG CMD...: runs CMD (its output into LOG), prints its seconds ($run_clock: wall, or cpu
# for user + system time of all its threads); fails as CMD does.
timed() {
  "$python" - "$run_clock" "$@" <<'EOF'
import resource, subprocess, sys, time
clock, log, cmd = sys.argv[1], sys.argv[2], sys.argv[3:]
t0 = time.monotonic()
with open(log, "w") as out:
    rc = subprocess.call(cmd, stdout=out, stderr=subprocess.STDOUT)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(r.ru_utime + r.ru_stime if clock == "cpu" else time.monotonic() - t0)
sys.exit(rc)
EOF
}

# measure ROUND CASE_INDEX BUILD: one run of a case with one build, its line into runs.tsv
measure() {
  local r=$1 c=$2 build=$3 name=${cases[$2]%%|*} cmd=${cases[$2]#*|}
  local out=$work/$r-$c-$build
  read -ra args <<<"$cmd"
  if [[ ${args[0]} == bench ]]; then
    "${bin[$build]}" "${args[@]}" --size "$size" --time 9 --frames "$frames" --warmup 2 --quiet --no-images \
      "${timing[@]}" --out "$out" >"$out.log" 2>&1 || { cat "$out.log" >&2; echo "perf-ab: $build: '$cmd' failed" >&2; exit 1; }
    printf '%s\t%s\t%s\t%s\n' "$r" "$name" "$build" "$out/results.json" >>"$runs"
  else
    local s
    s=$(timed "$out.log" "${bin[$build]}" "${args[@]}" --size "$size" --no-images --quiet) ||
      { cat "$out.log" >&2; echo "perf-ab: $build: '$cmd' failed" >&2; exit 1; }
    printf '%s\t%s\t%s\t%s\n' "$r" "$name" "$build" "$s" >>"$runs"
  fi
}

# Once with each build, not measured: the phantom's cache and the driver's shader cache filled.
for b in base new; do
  "${bin[$b]}" render variant1_lineao --time 9 --warmup 0 --size "$size" --no-images --quiet >"$work/first-$b.log" 2>&1 ||
    { cat "$work/first-$b.log" >&2; echo "perf-ab: $b: the first render failed" >&2; exit 1; }
done
load0=$(cut -d' ' -f1 /proc/loadavg)
start=$(date +%s)
for ((r = 1; r <= rounds; ++r)); do
  for c in "${!cases[@]}"; do
    if (((r + c) % 2)); then order=(new base); else order=(base new); fi
    if [[ $run_clock == cpu ]]; then  # at once: the machine's load in the same seconds on both
      measure "$r" "$c" base & pids=($!)
      measure "$r" "$c" new & pids+=($!)
      for p in "${pids[@]}"; do wait "$p" || exit 1; done
    else
      for b in "${order[@]}"; do measure "$r" "$c" "$b"; done
    fi
  done
  echo "perf-ab: round $r of $rounds done ($(($(date +%s) - start)) s)" >&2
done

dirty=""
git diff --quiet HEAD -- 2>/dev/null || dirty=" + uncommitted changes"
echo "perf-ab: new = this tree ($(git rev-parse --short HEAD)$dirty), base = $short; $size, study phantom," \
  "$rounds rounds, $frames frames a bench case; ${renderer:-unknown renderer}, $(nproc) cores, load average $load0" \
  "at the start, $(cut -d' ' -f1 /proc/loadavg) at the end; $(($(date +%s) - start)) s"
echo "perf-ab: timed by $timing_note"
if [[ -n $keep ]]; then  # the results with runs.tsv pointing at them
  mkdir -p "$(dirname "$keep")" && cp -r "$work" "$keep.tmp" && sed -i "s#$work#$keep#" "$keep.tmp/runs.tsv" &&
    mv "$keep.tmp" "$keep" && echo "perf-ab: every run kept in $keep" >&2
fi
"$python" scripts/perf_ab_table.py "$runs" --threshold "$threshold" "${all_passes[@]}"

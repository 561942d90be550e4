#!/usr/bin/env bash
# One command for anyone with a GPU: what Pathlet does on it, returned as one tarball.
#
#   scripts/gpu-check.sh [options] OUTDIR            the check (about 3 minutes on an H200)
#   scripts/gpu-check.sh --make-reference DIR         the llvmpipe renders to compare with (here)
#
# The check writes OUTDIR/gpu-check-HOST-STAMP.tar.gz holding:
#   info-gl.txt, info-gl-minimum.txt   the renderer and the limits the engine uses (pathlet info --gl)
#   nvidia-smi.txt, clocks.csv         the GPU and its SM clock / utilisation every 100 ms (if nvidia-smi)
#   renders/GRAPH.png, compare.txt     every shipped graph at 960x540 (study phantom, t = 4.5 s; those
#                                      that need an extension the driver lacks, or EXR in a lean build:
#                                      renders/unsupported.txt), and
#                                      its distance to the llvmpipe render of the reference folder:
#                                      share of pixels more than 8/255 off (pass: <= 0.5 %)
#   bench_window/, bench_all/          pathlet bench of every shipped variant at 1920x1080 with the
#                                      1 s window and with every line (--set window=0; there also
#                                      variant 1 with cull=false): results.json, summary.csv; the
#                                      printed tables in bench_*.txt
#   compute_GRAPH.txt, compute.txt     fullscreen passes as fragment against compute:
#                                      per pass both medians and compute/fragment, interleaved
#                                      rounds (scripts/bench-compute.sh); the picture with every
#                                      port forced each way (pathlet imagediff); the overlay's cost
#                                      with and without its labels
#   transparency/                      at BENCH_SIZE: every transparency technique against the
#                                      exact reference (scripts/transparency-techniques.py --plots:
#                                      speed, bytes a pixel, SSIM/PSNR/...), and the exact reference
#                                      against depth peeling with every line (exact_vs_peel.txt)
#   loop.txt                           the render loop's wall clock: variant 1, 1 s window, 250 frames
#                                      of 1920x1080 with --no-images (and --video where ffmpeg is)
#   summary.txt                        the lines a person reads first (also printed)
# Options:
#   --pathlet CMD      the pathlet command (default: bin/pathlet of an unpacked bundle named by
#                      PATHLET_BUNDLE, else build/bin/pathlet, else pathlet on PATH)
#   --reference DIR    the llvmpipe renders (default: gpu-reference/ next to this script's repo, or
#                      share/pathlet/gpu-reference of the bundle); without one the renders are kept
#                      but not compared
#   --quick            tiny sizes, the small phantom and few frames: for testing this script
# Exit status: 0 when the check ran (whatever it measured), 1 when a step failed, 2 bad usage.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)

usage() { sed -n '2,29p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
PATHLET="" REFERENCE="" QUICK=0 MAKE_REF="" OUTDIR=""
while [ $# -gt 0 ]; do
  case "$1" in
    --pathlet) PATHLET=${2:?--pathlet needs a command}; shift 2 ;;
    --reference) REFERENCE=${2:?--reference needs a folder}; shift 2 ;;
    --make-reference) MAKE_REF=${2:?--make-reference needs a folder}; shift 2 ;;
    --quick) QUICK=1; shift ;;
    -h|--help) usage ;;
    -*) echo "gpu-check: unknown option '$1'" >&2; usage ;;
    *) [ -z "$OUTDIR" ] || { echo "gpu-check: one OUTDIR only" >&2; usage; }; OUTDIR=$1; shift ;;
  esac
done
[ -n "$MAKE_REF" ] || [ -n "$OUTDIR" ] || usage

if [ -z "$PATHLET" ]; then
  if [ -n "${PATHLET_BUNDLE:-}" ] && [ -x "$PATHLET_BUNDLE/bin/pathlet" ]; then PATHLET=$PATHLET_BUNDLE/bin/pathlet
  elif [ -x "$ROOT/build/bin/pathlet" ]; then PATHLET=$ROOT/build/bin/pathlet
  else PATHLET=$(command -v pathlet || true); fi
fi
[ -n "$PATHLET" ] || { echo "gpu-check: no pathlet command (build it, unpack a bundle and set PATHLET_BUNDLE, or --pathlet)" >&2; exit 1; }

# What the check renders and times. --quick shrinks everything (the script's own test).
if [ "$QUICK" = 1 ]; then
  PHANTOM=small RENDER_SIZE=160x90 BENCH_SIZE=160x90 FRAMES=3 TIME=2 LOOP_TIME=0:0.4:0.04 WINDOW_TIME=2 ROUNDS=1
else
  PHANTOM=study RENDER_SIZE=960x540 BENCH_SIZE=1920x1080 FRAMES=100 TIME=4.5 LOOP_TIME=0:9.96:0.04 WINDOW_TIME=9 ROUNDS=3
fi
VARIANTS=variant1_lineao,variant2_oit,variant2_oit_ao,variant3_geomfade,isl,variant1_vao,variant4_opacity

# The shipped graphs: every graphs/*.json the command can find by name.
graph_dir() {
  local d
  for d in "$(dirname "$PATHLET")/../share/pathlet/graphs" "$ROOT/graphs"; do
    [ -d "$d" ] && { (cd "$d" && pwd); return; }
  done
}
GRAPHS_DIR=$(graph_dir)
[ -n "$GRAPHS_DIR" ] || { echo "gpu-check: no graphs folder next to $PATHLET or in $ROOT" >&2; exit 1; }
graphs() { for f in "$GRAPHS_DIR"/*.json; do basename "$f" .json; done; }

# Every shipped graph, one frame at RENDER_SIZE, into $1/GRAPH.png (4 at a time: the GPU is not
# the bottleneck of one-frame runs, process start-up and shader compiles are). A graph that needs
# an extension this driver lacks (MLAB: fragment shader interlock) is listed in
# $1/unsupported.txt with it, not a failure.
render_all() {
  local dest=$1 failed=0
  mkdir -p "$dest"
  for g in $(graphs); do
    echo "$g"
  done | xargs -P 4 -I{} sh -c '
      out=$(mktemp -d) &&
      "$0" render {} --phantom "$1" --time "$2" --size "$3" --out "$out" --quiet >"$out/log" 2>&1 &&
      f=$(find "$out" -name "*.png" | sort | head -n 1) && [ -n "$f" ] && mv "$f" "$4/{}.png"; rc=$?;
      if [ $rc -ne 0 ] && grep -q "which this driver (.*) lacks" "$out/log"; then
        echo "{} $(grep -o "needs GL_[A-Za-z0-9_]*" "$out/log" | head -n 1)" >>"$4/unsupported.txt"; rc=0;
      elif [ $rc -ne 0 ] && grep -q "this build has no EXR" "$out/log"; then
        echo "{} needs EXR (the lean build writes PNG only)" >>"$4/unsupported.txt"; rc=0; fi;
      [ $rc -eq 0 ] || { echo "gpu-check: render of {} failed:" >&2; cat "$out/log" >&2; }; rm -rf "$out"; exit $rc' \
      "$PATHLET" "$PHANTOM" "$TIME" "$RENDER_SIZE" "$dest" || failed=1
  return $failed
}

if [ -n "$MAKE_REF" ]; then
  echo "gpu-check: reference renders with $("$PATHLET" info --gl | sed -n 's/^GL_RENDERER //p') into $MAKE_REF"
  render_all "$MAKE_REF" || exit 1
  "$PATHLET" info --gl >"$MAKE_REF/info-gl.txt"
  exit 0
fi

if [ -z "$REFERENCE" ]; then
  for d in "$ROOT/gpu-reference" "$(dirname "$PATHLET")/../share/pathlet/gpu-reference"; do
    [ -d "$d" ] && { REFERENCE=$d; break; }
  done
fi

STAMP=$(date -u +%Y%m%dT%H%M%SZ)
HOST=$(hostname 2>/dev/null || echo host)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/gpu-check.XXXXXX")
trap 'kill $SMI 2>/dev/null; rm -rf "$WORK"' EXIT
R=$WORK/gpu-check-$HOST-$STAMP
mkdir -p "$R" "$OUTDIR"
FAILED=0
step() { echo "gpu-check: $*" | tee -a "$R/steps.txt" >&2; }
say() { echo "$*" | tee -a "$R/summary.txt"; }
T0=$(date +%s)

step "renderer and limits"
"$PATHLET" info --gl >"$R/info-gl.txt" 2>&1 || FAILED=1
PATHLET_GL_LIMITS=minimum "$PATHLET" info --gl >"$R/info-gl-minimum.txt" 2>&1 || FAILED=1
RENDERER=$(sed -n 's/^GL_RENDERER //p' "$R/info-gl.txt")
say "renderer: ${RENDERER:-unknown}"
SMI=""
if command -v nvidia-smi >/dev/null; then
  nvidia-smi -q >"$R/nvidia-smi.txt" 2>&1
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,utilization.gpu,power.draw --format=csv -lms 100 \
    >"$R/clocks.csv" 2>/dev/null &
  SMI=$!
fi

step "data: the $PHANTOM phantom (generated once, then cached)"
t=$(date +%s.%N)
"$PATHLET" render variant1_lineao --phantom "$PHANTOM" --time "$TIME" --size 64x36 --no-images --quiet \
  >"$R/phantom.log" 2>&1 || { FAILED=1; cat "$R/phantom.log" >&2; }
say "phantom ($PHANTOM) ready in $(awk -v a="$t" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s"

step "every shipped graph at $RENDER_SIZE"
render_all "$R/renders" || FAILED=1
[ -f "$R/renders/unsupported.txt" ] && say "not rendered, this driver lacks what they need: $(sort "$R/renders/unsupported.txt" | paste -sd, -)"
if [ -n "$REFERENCE" ]; then
  over=0
  for png in "$R"/renders/*.png; do
    g=$(basename "$png" .png)
    if [ ! -f "$REFERENCE/$g.png" ]; then echo "$g no-reference" >>"$R/compare.txt"; continue; fi
    share=$("$PATHLET" imagediff "$png" "$REFERENCE/$g.png" --threshold 8 | sed -n 's/^share_over_pct //p')
    verdict=ok
    awk -v s="${share:-100}" 'BEGIN { exit !(s > 0.5) }' && { verdict=DIFFERENT; over=$((over + 1)); }
    echo "$g ${share:-?} $verdict" >>"$R/compare.txt"
  done
  say "renders vs llvmpipe: $(grep -c ' ok$' "$R/compare.txt") of $(wc -l <"$R/compare.txt") within 0.5 % of pixels > 8/255 off ($over different; compare.txt)"
else
  say "renders: no llvmpipe reference (scripts/gpu-check.sh --make-reference DIR, then --reference DIR)"
fi

bench() {  # $1: name, $2: graphs, rest: extra options
  local name=$1 graphs=$2
  shift 2
  step "bench $name ($BENCH_SIZE, $FRAMES frames a graph)"
  "$PATHLET" bench "$graphs" --phantom "$PHANTOM" --size "$BENCH_SIZE" --time "$WINDOW_TIME" --frames "$FRAMES" \
    --report "$R/bench_$name" --quiet "$@" >"$R/bench_$name.txt" 2>&1 || { FAILED=1; tail -5 "$R/bench_$name.txt" >&2; }
  say "bench $name:"
  sed -n '/^summary/,$p' "$R/bench_$name.txt" | tee -a "$R/summary.txt"
}
bench window "$VARIANTS"
# Every line, and variant 1 once more unculled: the culling must never be slower than cull=false.
bench all "$VARIANTS,variant1_lineao" --set window=0 --set "$(( $(tr -cd , <<<"$VARIANTS" | wc -c) + 2 )):cull=false"

step "transparency techniques ($BENCH_SIZE) against the exact reference"
TEXP=$ROOT/graphs/experiments/transparency_techniques.json
if [ "$QUICK" = 1 ]; then  # the small phantom, few frames: the step's own test
  TEXP=$WORK/transparency_quick.json
  sed -e 's/"phantom": "study"/"phantom": "small"/' -e 's/"time": "[^"]*"/"time": "2:2.04:0.04"/' \
    "$ROOT/graphs/experiments/transparency_techniques.json" >"$TEXP"
fi
# The first Python with matplotlib draws the plot (Debian's may not be first on PATH); else no plot.
PY="" PLOTS=""
for p in $(command -v python3) /usr/bin/python3; do
  [ -x "$p" ] || continue; [ -n "$PY" ] || PY=$p
  "$p" -c 'import matplotlib' 2>/dev/null && { PY=$p PLOTS=--plots; break; }
done
mkdir -p "$R/transparency"
"${PY:-python3}" "$ROOT/scripts/transparency-techniques.py" "$TEXP" --pathlet "$PATHLET" --size "$BENCH_SIZE" $PLOTS \
  --out "$R/transparency" >"$R/transparency.txt" 2>&1 || { FAILED=1; tail -5 "$R/transparency.txt" >&2; }
say "transparency techniques at $BENCH_SIZE (x exact = speed-up over variant2_exact):"
grep '^|' "$R/transparency.txt" | tee -a "$R/summary.txt"
"$PATHLET" quality variant2_exact --reference variant2_depth_peel --phantom "$PHANTOM" --time "$WINDOW_TIME" \
  --size "$BENCH_SIZE" --set window=0 --set overlay=false --out "$R/transparency/exact_vs_peel" \
  >"$R/transparency/exact_vs_peel.txt" 2>&1 || FAILED=1
say "exact vs depth peeling, every line: $(grep -E '^(ssim|share over)' "$R/transparency/exact_vs_peel.txt" | paste -sd, -)"
"$PATHLET" bench variant2_exact,variant2_depth_peel --phantom "$PHANTOM" --size "$BENCH_SIZE" --time "$WINDOW_TIME" \
  --frames "$FRAMES" --set window=0 --set overlay=false --quiet >"$R/transparency/bench_exact_peel.txt" 2>&1 || FAILED=1
say "every line, exact / depth peeling:"
sed -n '/^summary/,$p' "$R/transparency/bench_exact_peel.txt" | tee -a "$R/summary.txt"

step "fullscreen passes: fragment against compute ($BENCH_SIZE, $ROUNDS rounds)"
# The ports of each graph (the passes with the parameter impl), switched together.
for spec in "variant1_lineao:gauss_pyramid lineao bilateral edge_aa" "variant1_vao:volume_ao" \
            "variant1_stable:temporal_ao"; do
  g=${spec%%:*}
  PATHLET="$PATHLET" PASSES="${spec#*:}" "$ROOT/scripts/bench-compute.sh" "$ROUNDS" "$BENCH_SIZE" "$g" \
    --phantom "$PHANTOM" --time "$WINDOW_TIME" --frames "$FRAMES" >"$R/compute_$g.txt" 2>&1 ||
    { FAILED=1; tail -5 "$R/compute_$g.txt" >&2; }
  say "compute/fragment, $g:"
  grep -E '^pass | \* ' "$R/compute_$g.txt" | tee -a "$R/summary.txt"
done
ports=(gauss_pyramid lineao bilateral edge_aa)
for impl in fragment compute; do
  sets=()
  for p in "${ports[@]}"; do sets+=(--set "$p.impl=$impl"); done
  "$PATHLET" render variant1_lineao --phantom "$PHANTOM" --time "$TIME" --size "$RENDER_SIZE" --quiet \
    --out "$WORK/impl_$impl" "${sets[@]}" >>"$R/compute.txt" 2>&1 || FAILED=1
done
{ echo "variant1_lineao, every port impl=fragment against impl=compute:"
  "$PATHLET" imagediff "$WORK"/impl_fragment/variant1_lineao/*.png "$WORK"/impl_compute/variant1_lineao/*.png \
    --threshold 1; } >>"$R/compute.txt" 2>&1 || FAILED=1
say "fragment vs compute picture: $(sed -n 's/^max_levels /max levels /p' "$R/compute.txt") (0 = identical)"
"$PATHLET" bench variant1_lineao,variant1_lineao --set 2:overlay=false --phantom "$PHANTOM" --size "$BENCH_SIZE" \
  --time "$WINDOW_TIME" --frames "$FRAMES" --quiet >"$R/bench_overlay.txt" 2>&1 || FAILED=1
say "overlay with labels / without (the copy alone), ms: $(awk '$1 == "overlay" { printf "%s%s", sep, $2; sep = " / " }' "$R/bench_overlay.txt")"

step "render loop wall clock"
seconds() {  # wall seconds of a command, its output dropped
  local a b
  a=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  b=$(date +%s.%N)
  awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b - a }'
}
loop() {  # frames per second of wall clock past start-up for one render command
  local frames start full
  frames=$(awk -v r="$LOOP_TIME" 'BEGIN { split(r, a, ":"); printf "%d", (a[2] - a[1]) / a[3] + 1.5 }')
  start=$(seconds "$PATHLET" render variant1_lineao --phantom "$PHANTOM" --time 0 --size "$BENCH_SIZE" --quiet --no-images)
  full=$(seconds "$PATHLET" render variant1_lineao --phantom "$PHANTOM" --time "$LOOP_TIME" --size "$BENCH_SIZE" --quiet "$@")
  awk -v n="$frames" -v s="$start" -v f="$full" \
    'BEGIN { d = f - s; printf "%d frames, %.2f s (start-up %.2f s): %.1f fps\n", n, f, s, (d > 0 ? (n - 1) / d : 0) }'
}
say "loop --no-images: $(loop --no-images)"
if command -v ffmpeg >/dev/null; then
  say "loop --video: $(loop --no-images --video "$WORK/loop.mp4" --out "$WORK/loop")"
else
  say "loop --video: skipped (no ffmpeg on PATH)"
fi

kill $SMI 2>/dev/null
if [ -s "$R/clocks.csv" ]; then
  say "SM clock MHz (min / median / max over the check): $(awk -F', ' 'NR > 1 { gsub(/ MHz/, "", $2); print $2 }' "$R/clocks.csv" |
    sort -n | awk '{ a[NR] = $1 } END { if (NR) printf "%s / %s / %s", a[1], a[int((NR + 1) / 2)], a[NR] }')"
fi
say "check took $(( $(date +%s) - T0 )) s; step failures: $FAILED"
tar -C "$WORK" -czf "$OUTDIR/gpu-check-$HOST-$STAMP.tar.gz" "$(basename "$R")"
echo "gpu-check: wrote $OUTDIR/gpu-check-$HOST-$STAMP.tar.gz" >&2
exit $FAILED

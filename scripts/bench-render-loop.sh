#!/usr/bin/env bash
# What the frame loop costs around the frames themselves: wall clock of
# `pathlet render` against startup + the frames' own time, and of the main job's kind of run
# (PNGs and --video) against the same run with --no-images.
#
#   scripts/bench-render-loop.sh [--rounds N] [--size WxH] [--time A:B:S] [--graph G] [PATHLET ...]
#
# Every PATHLET binary (default build/bin/pathlet; give two to compare a before and an after)
# runs in every round, interleaved, so a noisy machine hits them alike:
#   startup    wall of a one-frame run (--no-images --warmup 0) minus that frame's own time
#   no-images  wall of `render --no-images`; frames = the sum of every frame's own time
#              (the trace's frame spans on the render thread, warm-up frames included)
#   video      wall of `render --video` writing the PNGs too (scripts/main.sh's run)
# and prints per binary the ranges over the rounds of
#   loop  = no-images wall / (startup + frames)      target <= 1.10
#   video = video wall / no-images wall              target <= 1.25
# and for the video run its frames' own time (encoders competing for the cores slow them) and,
# where the binary reports it, the render thread's time on the output side (read-back,
# waiting for a full ring or for the encoders, the final drain).
# Data: the built-in study phantom (cached in ~/.cache/pathlet after its first use).
set -euo pipefail
cd "$(dirname "$0")/.."

rounds=3 size=1280x720 time=0:18:0.25 graph=variant1_lineao bins=()
while (($#)); do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --time) time=$2; shift 2 ;;
    --graph) graph=$2; shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) bins+=("$1"); shift ;;
  esac
done
((${#bins[@]})) || bins=(build/bin/pathlet)
command -v ffmpeg >/dev/null || { echo "bench-render-loop: ffmpeg is not on PATH (the video run needs it)" >&2; exit 1; }
for b in "${bins[@]}"; do [[ -x $b ]] || { echo "bench-render-loop: $b is not an executable" >&2; exit 1; }; done

work=$(mktemp -d /tmp/pathlet-bench-loop.XXXXXX)
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
# frames_s TRACE: the sum of the frame spans on the CPU track, in seconds
frames_s() {
  python3 - "$1" <<'EOF'
import json, sys
ev = json.load(open(sys.argv[1]))["traceEvents"]
print(sum(e["dur"] for e in ev if e.get("cat") == "frame" and e.get("tid") == 1) / 1e6)
EOF
}
# run NAME BIN ARGS...: wall seconds of one run into $work/NAME.wall, its report under $work/NAME
run() {
  local name=$1 bin=$2; shift 2
  rm -rf "$work/$name.out"
  local t0; t0=$(now)
  "$bin" render "$graph" --size "$size" --quiet --report "$work/$name" "$@" >"$work/$name.log" 2>&1 ||
    { cat "$work/$name.log" >&2; exit 1; }
  python3 -c "print($(now) - $t0)" > "$work/$name.wall"
}

load0=$(cut -d' ' -f1 /proc/loadavg)
results="$work/results.txt"
: > "$results"
renderer=""
for ((r = 1; r <= rounds; ++r)); do
  for i in "${!bins[@]}"; do
    b=${bins[$i]}
    run "s$i" "$b" --time 0 --warmup 0 --no-images
    run "n$i" "$b" --time "$time" --no-images
    run "v$i" "$b" --time "$time" --out "$work/v$i.out" --video "$work/v$i.out/video.mp4"
    startup=$(python3 -c "print($(cat "$work/s$i.wall") - $(frames_s "$work/s$i.trace.json"))")
    frames=$(frames_s "$work/n$i.trace.json")
    nwall=$(cat "$work/n$i.wall") vwall=$(cat "$work/v$i.wall")
    pngs=$(find "$work/v$i.out" -name '*.png' | wc -l)
    out=$(python3 -c "import json;print(round(json.load(open('$work/v$i.json'))['meta'].get('output_s', -1), 2))")
    vframes=$(frames_s "$work/v$i.trace.json")
    echo "$i $startup $frames $nwall $vwall $pngs $out $vframes" >> "$results"
    [[ -n $renderer ]] || renderer=$(python3 -c "import json;print(json.load(open('$work/n$i.json'))['meta']['renderer'])" 2>/dev/null || true)
    printf 'round %d  %-28s startup %5.2f s  frames %6.2f s  no-images %6.2f s  video %6.2f s (its frames %6.2f s, %d PNGs, output side %s s)\n' \
      "$r" "$b" "$startup" "$frames" "$nwall" "$vwall" "$vframes" "$pngs" "$out" >&2
  done
done

echo "render loop, $graph, $size, --time $time, $rounds rounds (renderer: ${renderer:-unknown};" \
  "load average $load0 at the start, $(cut -d' ' -f1 /proc/loadavg) at the end, $(nproc) cores)"
python3 - "$results" "${bins[@]}" <<'EOF'
import sys
rows = [l.split() for l in open(sys.argv[1])]
print(f"{'binary':<34} {'startup s':>11} {'frames s':>13} {'no-images s':>13} {'video s':>13} {'loop':>11} {'video/no-img':>13}"
      f" {'video: frames s':>16} {'output side s':>14}")
for i, b in enumerate(sys.argv[2:]):
    rs = [[float(x) for x in r[1:]] for r in rows if r[0] == str(i)]
    def rng(vals, f="{:.2f}"):
        lo, hi = min(vals), max(vals)
        return f.format(lo) if abs(hi - lo) < 5e-3 else f"{f.format(lo)}-{f.format(hi)}"
    loop = [n / (s + f) for s, f, n, v, p, o, vf in rs]
    vid = [v / n for s, f, n, v, p, o, vf in rs]
    out = [r[5] for r in rs]
    print(f"{b:<34} {rng([r[0] for r in rs]):>11} {rng([r[1] for r in rs]):>13} {rng([r[2] for r in rs]):>13} "
          f"{rng([r[3] for r in rs]):>13} {rng(loop):>11} {rng(vid):>13} {rng([r[6] for r in rs]):>16} "
          f"{rng(out) if min(out) >= 0 else '-':>14}")
print("targets: loop <= 1.10, video/no-img <= 1.25")
EOF

#!/usr/bin/env bash
# Fragment against compute versions of the fullscreen passes, interleaved:
# every round benches GRAPH twice in one `pathlet bench` run, once with impl=fragment and once
# with impl=compute for every pass named in PASSES, alternating which goes first (a noisy,
# shared machine drifts between rounds). Prints per pass the medians of both versions and the
# compute/fragment ratio over the rounds (min..max), with the GL renderer.
#
#   scripts/bench-compute.sh [ROUNDS] [SIZE] [GRAPH] [more bench options...]
#   PASSES="lineao bilateral" scripts/bench-compute.sh 4 1280x720 variant1_lineao --time 9
#
# Defaults: 4 rounds, 1280x720, variant1_lineao (study phantom, t = 9 s, 10 frames after 3 of
# warm-up), PASSES = gauss_pyramid lineao bilateral edge_aa.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
pathlet="${PATHLET:-$here/build/bin/pathlet}"
rounds="${1:-4}"
size="${2:-1280x720}"
graph="${3:-variant1_lineao}"
shift $(( $# < 3 ? $# : 3 ))
passes=(${PASSES:-gauss_pyramid lineao bilateral edge_aa})
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

for ((r = 0; r < rounds; ++r)); do
    # Even rounds fragment first, odd rounds compute first.
    if ((r % 2 == 0)); then first=fragment second=compute; else first=compute second=fragment; fi
    sets=()
    for p in "${passes[@]}"; do sets+=(--set "1:$p.impl=$first" --set "2:$p.impl=$second"); done
    "$pathlet" bench "$graph,$graph" --size "$size" --quiet "${sets[@]}" --report "$work/round$r" "$@" \
        > "$work/round$r.txt" 2>&1 || { cat "$work/round$r.txt"; exit 1; }
    echo "$first $second" > "$work/round$r.order"
done

renderer=$("$pathlet" info --gl 2>/dev/null | sed -n 's/^GL_RENDERER //p')
python3 - "$work" "$rounds" "$renderer" "${passes[@]}" <<'EOF'
import csv, sys
work, rounds, renderer, ports = sys.argv[1], int(sys.argv[2]), sys.argv[3], set(sys.argv[4:])
times = {}  # (impl, pass) -> [median per round]
for r in range(rounds):
    order = open(f"{work}/round{r}.order").read().split()
    labels = []
    for row in csv.DictReader(open(f"{work}/round{r}.csv")):
        if row["label"] not in labels:
            labels.append(row["label"])
        impl = order[labels.index(row["label"])]
        times.setdefault((impl, row["pass"]), []).append(float(row["median_ms"]))
print(f"renderer: {renderer}; {rounds} rounds, medians per round in ms")
print(f"{'pass':<16}{'fragment':>18}{'compute':>18}{'compute/fragment':>18}{'median':>8}")
names = [p for (impl, p) in times if impl == "fragment"]
for p in names:
    f, c = times[("fragment", p)], times.get(("compute", p), [])
    if not c:
        continue
    ratios = [b / a for a, b in zip(f, c) if a > 0]
    if not ratios:
        continue
    mark = " *" if p in ports else ""
    ratios.sort()
    median = ratios[len(ratios) // 2] if len(ratios) % 2 else sum(ratios[len(ratios) // 2 - 1:][:2]) / 2
    print(f"{p + mark:<16}{min(f):>8.2f}..{max(f):<8.2f}{min(c):>8.2f}..{max(c):<8.2f}"
          f"{ratios[0]:>8.2f}..{ratios[-1]:<8.2f}{median:>8.2f}")
print("* the passes switched between fragment and compute")
EOF

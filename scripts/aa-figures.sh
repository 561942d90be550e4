#!/usr/bin/env bash
# The anti-aliasing figures of the study's-picture issue, on the built-in study phantom at
# 640x360, t = 9 s, 1 s window, overlay off: RMS (0..255, over covered pixels) against a 4x4
# supersampled render of the same graph (render --ssaa 4: LineAO radii, filter widths and the
# level of detail scaled; aa=false there, so the 16 box-filtered samples are the ground truth),
# the share of isolated dark speckles, and the frame time with and without anti-aliasing.
# "hard edges" = the same frame with aa=false and gbuffer.halo_min_px=0 (the 20 % halo alone);
# the picture before edge_aa existed (commit 24abc9b) measured 48.1 here (README).
#   scripts/aa-figures.sh [GRAPH] [RUNS]      e.g. scripts/aa-figures.sh variant1_lineao 3
set -euo pipefail
cd "$(dirname "$0")/.."
GRAPH=${1:-variant1_lineao}
RUNS=${2:-3}
P=${PATHLET:-build/bin/pathlet}
/usr/bin/python3 -c 'import numpy, PIL' 2>/dev/null ||
  { echo "aa-figures: needs Debian's python3-numpy and python3-pil (scripts/install-deps.sh)" >&2; exit 1; }
OUT=$(mktemp -d /tmp/pathlet_aa.XXXXXX)
trap 'rm -rf "$OUT"' EXIT
COMMON=(--time 9 --size 640x360 --quiet --set overlay=false)
BEFORE=(--set aa=false --set gbuffer.halo_min_px=0)
render() { local dir=$1; shift; "$P" render "$GRAPH" "${COMMON[@]}" --out "$OUT/$dir" "$@" >/dev/null; }
echo "aa-figures: rendering $GRAPH (4 frames, two of them 2560x1440) ..."
render before "${BEFORE[@]}"
render before_ref "${BEFORE[@]}" --ssaa 4
render after
render after_ref --set aa=false --ssaa 4
metric() {  # IMAGE REFERENCE -> "rms speckle"
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, numpy as np
from PIL import Image
a = np.asarray(Image.open(sys.argv[1]).convert('RGB'), dtype=np.float64)
r = np.asarray(Image.open(sys.argv[2]).convert('RGB'), dtype=np.float64)
bg = a[0, 0]
cov = np.any(np.abs(a - bg) > 8, axis=2) | np.any(np.abs(r - bg) > 8, axis=2)
rms = np.sqrt(((a - r) ** 2)[cov].mean())
L = a.mean(axis=2); c = L[1:-1, 1:-1]
nb = np.stack([L[:-2, 1:-1], L[2:, 1:-1], L[1:-1, :-2], L[1:-1, 2:]])
speck = (nb - c[None] > 60).all(axis=0) & cov[1:-1, 1:-1]
print(f"{rms:.1f} {speck.sum() / max(cov.sum(), 1):.4f}")
PY
}
read -r rb sb < <(metric "$OUT"/before/*/00000.png "$OUT"/before_ref/*/00000.png)
read -r ra sa < <(metric "$OUT"/after/*/00000.png "$OUT"/after_ref/*/00000.png)
printf '%-34s %12s %10s\n' "" "RMS vs 4x4" "speckles"
printf '%-34s %12s %10s\n' "hard edges (aa=false, 20 % halo)" "$rb" "$sb"
printf '%-34s %12s %10s\n' "after (edge_aa, halo >= 1 px)" "$ra" "$sa"
awk -v a="$ra" -v b="$rb" 'BEGIN { printf "RMS edge_aa / hard edges: %.0f %%\n", 100 * a / b }'
echo "frame time (median of 10 frames at t = 9, 640x360), $RUNS runs alternating:"
for run in $(seq "$RUNS"); do
  b=$("$P" bench "$GRAPH" --size 640x360 --time 9 --frames 10 --set overlay=false "${BEFORE[@]}" 2>&1 |
      awk '$1 == "frame" { print $2; exit }')
  a=$("$P" bench "$GRAPH" --size 640x360 --time 9 --frames 10 --set overlay=false 2>&1 | awk '$1 == "frame" { print $2; exit }')
  awk -v a="$a" -v b="$b" -v r="$run" 'BEGIN { printf "  run %d: aa=false %6.1f ms, aa=true %6.1f ms, ratio %.2f\n", r, b, a, a / b }'
done

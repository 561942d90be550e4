#!/usr/bin/env bash
# The object-space AO figures (docs/rendering.md, "Object-space AO from line density"), on the
# built-in study phantom at 960x540, t = 9 s, 1 s window, overlay off:
#   docs/vao_compare.png  the arch: variant 1 with LineAO and with volume AO (top), and their AO
#                         maps beside the ray-traced AO of `pathlet quality` (bottom)
#   docs/vao_vortex.png   the aneurysm's vortex, seen from the side (--orbit 12), both graphs
# and the quality numbers of those frames.
#   scripts/vao-figures.sh [OUT_DIR]      (default docs)
set -euo pipefail
cd "$(dirname "$0")/.."
DOCS=${1:-docs}
P=${PATHLET:-build/bin/pathlet}
/usr/bin/python3 -c 'import PIL' 2>/dev/null ||
  { echo "vao-figures: needs Debian's python3-pil (scripts/install-deps.sh)" >&2; exit 1; }
OUT=$(mktemp -d /tmp/pathlet_vao.XXXXXX)
trap 'rm -rf "$OUT"' EXIT
for g in variant1_lineao variant1_vao; do
  "$P" quality "$g" --size 960x540 --rays 128 --flicker-rays 0 --time 9:9.04:0.04 --images --out "$OUT/q" |
    grep -E "MAE"
  "$P" render "$g" --time 9 --size 960x540 --set overlay=false --quiet --out "$OUT/front" >/dev/null 2>&1
  "$P" render "$g" --time 9 --size 960x540 --set overlay=false --orbit 12 --quiet --out "$OUT/side" >/dev/null 2>&1
done
/usr/bin/python3 - "$OUT" "$DOCS" <<'PY'
import sys
sys.path.insert(0, 'scripts/figures')
from contact_sheet import row, stack, save
out, docs = sys.argv[1], sys.argv[2]
arch = (380, 10, 620, 250)
top = row([f'{out}/front/variant1_lineao/00000.png', f'{out}/front/variant1_vao/00000.png'],
          ['variant1_lineao (LineAO)', 'variant1_vao (volume AO)'], arch, scale=2)
bottom = row([f'{out}/q/variant1_lineao_ao.png', f'{out}/q/variant1_vao_ao.png', f'{out}/q/variant1_vao_reference.png'],
             ['LineAO', 'volume AO', 'ray-traced AO (reference)'], arch)
save(stack([top, bottom]), f'{docs}/vao_compare.png')
vortex = (440, 160, 580, 300)
save(row([f'{out}/side/variant1_lineao/00000.png', f'{out}/side/variant1_vao/00000.png'],
         ['variant1_lineao', 'variant1_vao'], vortex, scale=3), f'{docs}/vao_vortex.png')
PY
echo "vao-figures: wrote $DOCS/vao_compare.png, $DOCS/vao_vortex.png"

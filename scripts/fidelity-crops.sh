#!/usr/bin/env bash
# The fidelity crops of docs/quality.md: the study phantom at 1280x720, t = 9 s, every line
# whole (window=0, the densest picture), a crop of the descending aorta shown three times:
#   docs/fidelity_edges.png  variant 1 | the same graph with --ssaa 4 and aa off | |difference| x4
#   docs/fidelity_vao.png    variant1_vao's AO | the ray-traced AO of `pathlet quality` | |difference| x4
# and the figures of the whole frame (aa_metric.py's RMS and speckles; MAE and correlation).
#   scripts/fidelity-crops.sh [OUT_DIR]      (default docs)
set -euo pipefail
cd "$(dirname "$0")/.."
DOCS=${1:-docs}
P=${PATHLET:-build/bin/pathlet}
METRIC=${AA_METRIC:-../shared/tools/aa_metric.py}  # the shared tools (AA_METRIC=PATH elsewhere)
/usr/bin/python3 -c 'import numpy, PIL' 2>/dev/null ||
  { echo "fidelity-crops: needs Debian's python3-numpy and python3-pil (scripts/install-deps.sh)" >&2; exit 1; }
[ -f "$METRIC" ] || { echo "fidelity-crops: $METRIC not found (the shared tools)" >&2; exit 1; }
OUT=$(mktemp -d /tmp/pathlet_fidelity.XXXXXX)
trap 'rm -rf "$OUT"' EXIT
COMMON=(--time 9 --size 1280x720 --quiet --set window=0)
echo "fidelity-crops: rendering variant 1 plain and 4x4 supersampled, and variant1_vao's AO ..." >&2
"$P" render variant1_lineao "${COMMON[@]}" --out "$OUT/plain" >/dev/null
"$P" render variant1_lineao "${COMMON[@]}" --set aa=false --ssaa 4 --out "$OUT/ssaa" >/dev/null
echo "edges, variant 1 against --ssaa 4: $(/usr/bin/python3 "$METRIC" "$OUT"/plain/*/00000.png "$OUT"/ssaa/*/00000.png)"
"$P" quality variant1_vao --size 1280x720 --time 9:9.04:0.04 --set window=0 --flicker-rays 0 --images \
  --out "$OUT/q" | grep -E "MAE" | sed 's/^ */volume AO, /'
/usr/bin/python3 - "$OUT" "$DOCS" <<'PY'
import sys
import numpy as np
from PIL import Image
sys.path.insert(0, 'scripts/figures')
from contact_sheet import row, save
out, docs = sys.argv[1], sys.argv[2]
BOX = (690, 430, 800, 560)  # the descending aorta at 1280x720, every line whole
SCALE = 4
def load(path):
    return np.asarray(Image.open(path).convert('RGB'), dtype=np.float64)
def difference(a, b):
    return 255.0 - np.minimum(np.abs(a - b).max(axis=2, keepdims=True) * 4.0, 255.0).repeat(3, axis=2)
plain = load(f'{out}/plain/variant1_lineao/00000.png')
ssaa = load(f'{out}/ssaa/variant1_lineao/00000.png')
save(row([plain, ssaa, difference(plain, ssaa)], ['variant 1', '--ssaa 4 (reference)', '|difference| x4 (dark = off)'],
         BOX, SCALE), f'{docs}/fidelity_edges.png')
ao = load(f'{out}/q/variant1_vao_ao.png')
rt = load(f'{out}/q/variant1_vao_reference.png')
save(row([ao, rt, difference(ao, rt)], ['volume AO', 'ray-traced AO (reference)', '|difference| x4 (dark = off)'],
         BOX, SCALE), f'{docs}/fidelity_vao.png')
print(f'wrote {docs}/fidelity_edges.png and {docs}/fidelity_vao.png (crop {BOX}, {SCALE}x)', file=sys.stderr)
PY

#!/usr/bin/env bash
# The opacity optimization figures (docs/opacity-optimization.md), on the built-in
# study phantom at t = 9.3 s (systole: the fast jet is at the pathlets' heads), 1 s window, 960x540
# per picture, overlay off, variant 2 (left) and variant 4 with its defaults (right):
#   docs/variant4_aneurysm.png  the descending aorta and the aneurysm from the side
#                               (docs/aneurysm_camera.json)
#   docs/variant4_overview.png  the default framing
#   scripts/opacity-figures.sh [OUT_DIR]      (default docs)
set -euo pipefail
cd "$(dirname "$0")/.."
DOCS=${1:-docs}
P=${PATHLET:-build/bin/pathlet}
/usr/bin/python3 -c 'import PIL' 2>/dev/null ||
  { echo "opacity-figures: needs Debian's python3-pil (scripts/install-deps.sh)" >&2; exit 1; }
OUT=$(mktemp -d /tmp/pathlet_oo.XXXXXX)
trap 'rm -rf "$OUT"' EXIT
for g in variant2_oit variant4_opacity; do
  "$P" render "$g" --time 9.3 --size 960x540 --set overlay=false --camera docs/aneurysm_camera.json --quiet \
    --out "$OUT/side" >/dev/null 2>&1
  "$P" render "$g" --time 9.3 --size 960x540 --set overlay=false --quiet --out "$OUT/front" >/dev/null 2>&1
done
/usr/bin/python3 - "$OUT" "$DOCS" <<'PY'
import sys
sys.path.insert(0, "scripts/figures")
from contact_sheet import row, save
out, docs = sys.argv[1], sys.argv[2]
labels = ["variant 2 (end fade)", "variant 4 (opacity optimization)"]
for view, box, name in (("side", (200, 0, 760, 540), "variant4_aneurysm"), ("front", (300, 0, 660, 540), "variant4_overview")):
    print(save(row([f"{out}/{view}/{g}/00000.png" for g in ("variant2_oit", "variant4_opacity")], labels, box,
                   label_at=(4, 3)), f"{docs}/{name}.png"))
PY

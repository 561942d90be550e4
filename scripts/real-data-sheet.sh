#!/usr/bin/env bash
# docs/real_data.png: every shipped graph that draws lines on every real data set in
# ../shared/data/real (rows), at the default framing and defaults, one frame each — what a
# researcher sees on these data without tuning. The same data sets and options as the
# conformance suite tests/real. Needs a build (build/bin/pathlet) and Debian's python3-pil.
#
#   scripts/real-data-sheet.sh [OUT.png] [CELL_WxH]     (default docs/real_data.png 320x180)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-docs/real_data.png}
CELL=${2:-320x180}
REAL=${PATHLET_REAL_DATA_DIR:-$PWD/../shared/data/real}
PATHLET=${PATHLET:-build/bin/pathlet}
[ -d "$REAL" ] || { echo "real data not found: $REAL (set PATHLET_REAL_DATA_DIR)" >&2; exit 1; }
[ -x "$PATHLET" ] || { echo "no $PATHLET: build first (scripts/build.sh)" >&2; exit 1; }
/usr/bin/python3 -c 'import PIL' 2>/dev/null || { echo "needs python3-pil (apt-get install python3-pil)" >&2; exit 1; }

TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# The velocity volumes are traced first, as a user would (defaults, plus the carotid's
# vessel threshold from VTK's own examples).
"$PATHLET" trace "$REAL/aortic-arch-cfd-4dflownet/example_data_HR.h5" -o "$TMP/arch.vtp" --wall "$TMP/arch.glb" >/dev/null 2>&1
"$PATHLET" trace "$REAL/carotid-vtk/carotid.vtk" --mask-threshold 175 -o "$TMP/carotid.vtp" --wall "$TMP/carotid.glb" >/dev/null 2>&1

# name | label | data file | load options (for info and render) | wall
SETS=(
  "aneurysm|aneurysm pathlines (text rows)|$REAL/aneurysm-pathlines/blood_flow||"
  "arch|4DFlowNet aortic arch (traced, with wall)|$TMP/arch.vtp||$TMP/arch.glb"
  "carotid|carotid field (traced, with wall)|$TMP/carotid.vtp||$TMP/carotid.glb"
  "vmtk|vmtk abdominal aorta (centrelines, surface)|$REAL/vmtk-abdominal-aorta/aorta-centerline.vtp|--streamlines|$REAL/vmtk-abdominal-aorta/aorta-surface.stl"
  "fornix|fornix tracts (TrackVis .trk)|$REAL/fornix-tractography/tracks300.trk||"
)
# Graphs that draw lines (demo_blur draws a test pattern, no data).
GRAPHS=()
for g in graphs/*.json; do
  n=$(basename "$g" .json)
  grep -q '"type": "\(gbuffer\|isl\|geometric_fade\|fill_list\|fade_core\)"' "$g" && GRAPHS+=("$n")
done

for s in "${SETS[@]}"; do
  IFS='|' read -r name label data load wall <<<"$s"
  # One frame at the middle of the data's time span (streamlines have none: drawn whole).
  # shellcheck disable=SC2086
  span=$("$PATHLET" info "$data" $load | sed -n 's/^time: *\([-0-9.e+]*\) \.\. \([-0-9.e+]*\).*/\1 \2/p')
  t=0
  [ -n "$span" ] && t=$(awk -v a="${span% *}" -v b="${span#* }" 'BEGIN { printf "%.2f", (a + b) / 2 }')
  mesh=()
  [ -n "$wall" ] && mesh=(--mesh "$wall")
  for g in "${GRAPHS[@]}"; do
    # shellcheck disable=SC2086
    "$PATHLET" render "graphs/$g.json" --data "$data" $load "${mesh[@]}" --time "$t" --size "$CELL" --out "$TMP/$name" --quiet >/dev/null
  done
  echo "$name|$label|${span:+t = $t}" >>"$TMP/sets.txt"
done

/usr/bin/python3 - "$TMP" "$OUT" "$CELL" "${GRAPHS[@]}" <<'EOF'
import glob, os, sys
from PIL import Image, ImageDraw, ImageFont
tmp, out, cell, graphs = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
W, H = (int(v) for v in cell.split("x"))
sets = [l.strip().split("|") for l in open(os.path.join(tmp, "sets.txt"))]
font_file = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
font = ImageFont.truetype(font_file, 15) if os.path.exists(font_file) else ImageFont.load_default()
left, top = 250, 28
sheet = Image.new("RGB", (left + W * len(graphs), top + H * len(sets)), "white")
d = ImageDraw.Draw(sheet)
for c, g in enumerate(graphs):
    d.text((left + c * W + 6, 6), g, fill=(30, 30, 30), font=font)
for r, (name, label, t) in enumerate(sets):
    y = top + r * H
    title, _, detail = label.partition(" (")  # two lines: the data set, then how it was made
    d.text((8, y + H // 2 - 30), title, fill=(30, 30, 30), font=font)
    if detail:
        d.text((8, y + H // 2 - 10), "(" + detail, fill=(30, 30, 30), font=font)
    d.text((8, y + H // 2 + 12), t or "no time: whole lines", fill=(110, 110, 110), font=font)
    for c, g in enumerate(graphs):
        files = sorted(glob.glob(os.path.join(tmp, name, g, "*.png")))
        if files:
            sheet.paste(Image.open(files[-1]).convert("RGB").resize((W, H)), (left + c * W, y))
    d.line([(0, y), (sheet.width, y)], fill=(200, 200, 200))
os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
sheet.save(out + ".tmp.png")
os.replace(out + ".tmp.png", out)
print(f"{out}: {len(sets)} data sets x {len(graphs)} graphs")
EOF

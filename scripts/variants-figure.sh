#!/usr/bin/env bash
# The README's lead picture: the study's variants side by side on the built-in study phantom,
# each drawn by its shipped graph with its own defaults, at one time and camera
# (docs/variants_camera.json: the aortic arch and the aneurysm's vortex from the front left):
#   variant 1 (variant1_lineao), variant 2 (variant2_oit), variant 3 (variant3_geomfade),
#   variant 4 (variant4_opacity) and illuminated streamlines (isl)
# Each panel is a supersampled frame cropped to the vessel; the speed legend, the same for all,
# is taken from variant 1's overlay and put at the right.
#   scripts/variants-figure.sh [OUT.png]     (default docs/variants.png)
# Environment: PATHLET (build/bin/pathlet), TIME (9.3: systole, the fast jet at the heads), SSAA (2).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT_PNG=${1:-docs/variants.png}
P=${PATHLET:-build/bin/pathlet}
TIME=${TIME:-9.3}
SSAA=${SSAA:-2}
[ -x "$P" ] || { echo "variants-figure: $P not built (scripts/build.sh --runtime)" >&2; exit 2; }
/usr/bin/python3 -c 'import PIL' 2>/dev/null ||
  { echo "variants-figure: needs Debian's python3-pil (scripts/install-deps.sh)" >&2; exit 2; }
work=$(mktemp -d /tmp/pathlet_variants.XXXXXX)
trap 'rm -rf "$work"' EXIT
graphs=(variant1_lineao variant2_oit variant3_geomfade variant4_opacity isl)
render() {  # graph, overlay, output folder
  if ! "$P" render "$1" --time "$TIME" --size 800x650 --ssaa "$SSAA" --camera docs/variants_camera.json \
      --set overlay="$2" --quiet --out "$3" >"$work/log" 2>&1; then
    sed 's/^/    /' "$work/log" >&2
    echo "variants-figure: rendering $1 failed" >&2
    exit 1
  fi
}
for g in "${graphs[@]}"; do render "$g" false "$work/plain"; done
render "${graphs[0]}" true "$work/overlay"
/usr/bin/python3 - "$work" "$OUT_PNG" "${graphs[@]}" <<'PY'
import os, sys
from PIL import Image, ImageChops, ImageDraw, ImageFont
work, out, graphs = sys.argv[1], sys.argv[2], sys.argv[3:]
labels = {"variant1_lineao": ("variant 1", "LineAO"), "variant2_oit": ("variant 2", "opacity fade"),
          "variant3_geomfade": ("variant 3", "width fade"), "variant4_opacity": ("variant 4", "optimized opacity"),
          "isl": ("illuminated", "streamlines")}
ims = [Image.open(f"{work}/plain/{g}/00000.png").convert("RGB") for g in graphs]
W, H = ims[0].size
# One crop for every panel: the columns where any panel is not white (lines and wall).
white = Image.new("RGB", (W, H), "white")
boxes = [ImageChops.difference(im, white).getbbox() for im in ims]
if None in boxes:
    sys.exit("variants-figure: a panel is empty")
left, right = max(min(b[0] for b in boxes) - 16, 0), min(max(b[2] for b in boxes) + 16, W)
# The legend: what variant 1's overlay adds right of the vessel.
overlay = Image.open(f"{work}/overlay/{graphs[0]}/00000.png").convert("RGB")
legend_box = ImageChops.difference(overlay, ims[0]).crop((right, 0, W, H)).getbbox()
if legend_box is None:
    sys.exit("variants-figure: no legend beside the vessel in the overlay")
legend = overlay.crop((right + legend_box[0] - 8, 0, right + legend_box[2] + 8, H))
font = ImageFont.truetype("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", 24)
w, top, gap = right - left, 64, 8
sheet = Image.new("RGB", (len(ims) * (w + gap) + legend.width, H + top), "white")
draw = ImageDraw.Draw(sheet)
for k, (g, im) in enumerate(zip(graphs, ims)):
    x = k * (w + gap)
    sheet.paste(im.crop((left, 0, right, H)), (x, top))
    for line, text in enumerate(labels.get(g, (g, ""))):
        draw.text((x + 10, 4 + 28 * line), text, fill="black", font=font)
sheet.paste(legend, (len(ims) * (w + gap), top))
tmp = out + ".tmp.png"
sheet.save(tmp, optimize=True)
os.replace(tmp, out)
print(f"{out}: {len(ims)} panels of {w}x{H} and the legend, {sheet.width}x{sheet.height}")
PY

#!/usr/bin/env bash
# docs/data.md's figure: the real fornix tractography (../shared/data/real, 300 tracts) cut into
# eight bundles, given as eight files the way tractography arrives, drawn by the default graph
# for tracts (tracts_lineao: direction colours) and then coloured by bundle, with the legend of
# their names. The cut: halves by each tract's centroid along the file's first axis, quarters of
# each half along the second, written as TrackVis files with the original header.
#   scripts/bundles-figure.sh [OUT.png]     (default docs/tracts_bundles.png)
# Environment: PATHLET (build/bin/pathlet), REAL (../shared/data/real), SSAA (2).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT_PNG=${1:-docs/tracts_bundles.png}
P=${PATHLET:-build/bin/pathlet}
REAL=${REAL:-../shared/data/real}
SSAA=${SSAA:-2}
TRK="$REAL/fornix-tractography/tracks300.trk"
[ -x "$P" ] || { echo "bundles-figure: $P not built (scripts/build.sh --runtime)" >&2; exit 2; }
[ -f "$TRK" ] || { echo "bundles-figure: $TRK not found (set REAL to shared/data/real)" >&2; exit 2; }
/usr/bin/python3 -c 'import PIL, numpy' 2>/dev/null ||
  { echo "bundles-figure: needs Debian's python3-pil and python3-numpy (scripts/install-deps.sh)" >&2; exit 2; }
work=$(mktemp -d /tmp/pathlet_bundles.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir "$work/bundles"
/usr/bin/python3 - "$TRK" "$work/bundles" <<'PY'
import struct, sys
import numpy as np
trk, out = sys.argv[1], sys.argv[2]
data = open(trk, "rb").read()
head = data[:1000]
n_scalars, n_props = struct.unpack_from("<h", head, 36)[0], struct.unpack_from("<h", head, 238)[0]
tracks, at = [], 1000
while at < len(data):
    n = struct.unpack_from("<i", data, at)[0]
    size = 4 + 4 * (n * (3 + n_scalars) + n_props)
    pts = np.frombuffer(data, "<f4", n * (3 + n_scalars), at + 4).reshape(n, 3 + n_scalars)[:, :3]
    tracks.append((data[at:at + size], pts.mean(axis=0)))
    at += size
order = sorted(range(len(tracks)), key=lambda i: tracks[i][1][0])
half = len(order) // 2
k = 0
for side in (order[:half], order[half:]):
    side = sorted(side, key=lambda i: tracks[i][1][1])
    for q in range(4):
        part = sorted(side[q * len(side) // 4:(q + 1) * len(side) // 4])
        k += 1
        h = bytearray(head)
        struct.pack_into("<i", h, 988, len(part))  # n_count
        with open(f"{out}/fornix_part{k}.trk", "wb") as f:
            f.write(bytes(h) + b"".join(tracks[i][0] for i in part))
PY
files=("$work"/bundles/*.trk)
render() {  # output folder, --set ...
  local out=$1
  shift
  if ! "$P" render --size 640x400 --ssaa "$SSAA" --out "$out" "$@" --data "${files[@]}" >"$work/log" 2>&1; then
    sed 's/^/    /' "$work/log" >&2
    echo "bundles-figure: rendering failed" >&2
    exit 1
  fi
  grep -q "graph: tracts_lineao" "$work/log" || { echo "bundles-figure: the default graph was not tracts_lineao" >&2; exit 1; }
}
render "$work/direction"
render "$work/bundle" --set colormap=bundle
/usr/bin/python3 - "$work" "$OUT_PNG" <<'PY'
import sys
from PIL import ImageFont
sys.path.insert(0, "scripts/figures")
from contact_sheet import row, save
work, out = sys.argv[1], sys.argv[2]
font = ImageFont.truetype("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", 18)
sheet = row([f"{work}/{k}/tracts_lineao/00000.png" for k in ("direction", "bundle")],
            ("default: direction colours", "--set colormap=bundle"), top=34, font=font, label_at=(12, 8))
save(sheet, out, optimize=True)
print(f"wrote {out} ({sheet.width}x{sheet.height})")
PY

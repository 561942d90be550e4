#!/usr/bin/env bash
# Every shipped graph's frames as a table of checksums: the study phantom at two times (4.5 s
# and 9.3 s), with the graph's own pathlet window and with every line whole (window=0, where the
# graph has the variable), at 640x360. A change that must not alter a picture (a refactoring,
# a build setting) is checked against the committed table bit for bit:
#   scripts/frame-table.sh                 render, compare with tests/frame_table.tsv, exit 1 on a difference
#   scripts/frame-table.sh --update        render and rewrite the table (a deliberate change of pictures)
#   scripts/frame-table.sh --keep DIR      ... and keep the rendered files in DIR (to look at a difference)
# Checksums are of the pixels of the files the graph captures (PNG, or EXR for float outputs:
# OpenImageIO's SHA-1 of the pixel data, so an EXR header's write time does not count), rendered on this
# machine's GL (llvmpipe): another driver or LLVM version may differ by a bit, so the table is a
# tool for one machine, not a CI test; the golden-image tests compare with a tolerance.
set -euo pipefail
cd "$(dirname "$0")/.."
PATHLET=${PATHLET:-build/bin/pathlet}
TABLE=tests/frame_table.tsv
update=0 keep=""
while [ $# -gt 0 ]; do
  case "$1" in
    --update) update=1 ;;
    --keep) keep=$2; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "frame-table: unknown option '$1' (--update, --keep DIR)" >&2; exit 2 ;;
  esac
  shift
done
[ -x "$PATHLET" ] || { echo "frame-table: $PATHLET not built (scripts/build.sh --runtime)" >&2; exit 2; }
command -v iinfo >/dev/null || { echo "frame-table: iinfo (openimageio-tools) not found" >&2; exit 2; }
# The first 16 hex digits of the SHA-1 of a file's pixels.
pixel_hash() { iinfo --hash "$1" | sed -n 's/^ *SHA-1: //p' | cut -c1-16; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe PATHLET_PLUGIN_PATH=
rows=$work/rows.tsv
: >"$rows"
for file in graphs/*.json; do
  g=$(basename "$file" .json)
  windows=(default)
  "$PATHLET" graph "$g" --expanded 2>/dev/null |
    /usr/bin/python3 -c 'import json, sys; sys.exit("window" not in json.load(sys.stdin).get("variables", {}))' &&
    windows+=(0)
  for w in "${windows[@]}"; do
    sets=()
    [ "$w" = 0 ] && sets=(--set window=0)
    out=$work/$g-$w
    if ! "$PATHLET" render "$g" --time 4.5:9.4:4.8 --size 640x360 --out "$out" --quiet "${sets[@]}" \
        >"$work/log" 2>&1; then
      printf '%s\t%s\t-\t-\tFAILED\n' "$g" "$w" >>"$rows"
      sed 's/^/    /' "$work/log" >&2
      continue
    fi
    (cd "$out" && find . -type f | LC_ALL=C sort) | while read -r f; do
      printf '%s\t%s\t%s\t%s\n' "$g" "$w" "${f#./}" "$(pixel_hash "$out/$f")" >>"$rows"
    done
  done
  echo "frame-table: $g" >&2
done
[ -n "$keep" ] && { mkdir -p "$keep"; cp -r "$work"/*-default "$work"/*-0 "$keep"/ 2>/dev/null || true; }
header='# graph	window	file	pixels SHA-1 (16 hex digits): scripts/frame-table.sh'
if [ "$update" = 1 ]; then
  { echo "$header"; cat "$rows"; } >"$TABLE.tmp" && mv "$TABLE.tmp" "$TABLE"
  echo "frame-table: wrote $TABLE ($(wc -l <"$rows") frames)"
  exit 0
fi
if diff <(grep -v '^#' "$TABLE") "$rows" >"$work/diff"; then
  echo "frame-table: all $(wc -l <"$rows") frames bit-identical to $TABLE"
else
  echo "frame-table: frames differ from $TABLE (< table, > now):"
  cat "$work/diff"
  exit 1
fi

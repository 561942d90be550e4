#!/usr/bin/env bash
# scripts/transparency-techniques.py on llvmpipe: a bad --size is refused (exit 2); a technique
# that breaks in setup (not a missing extension) is left out, named, the table of the others is
# written, and the run exits 1; --size replaces the experiment's sizes.
#   test_transparency_script.sh SOURCE_DIR PATHLET PYTHON
set -uo pipefail
SRC=$1 PATHLET=$2 PY=$3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
S=$SRC/scripts/transparency-techniques.py

"$PY" "$S" --size 12 --pathlet "$PATHLET" --out "$WORK/a" >"$WORK/bad_size" 2>&1
[ $? -eq 2 ] || fail "--size 12: expected exit 2: $(cat "$WORK/bad_size")"
grep -q "expected WIDTHxHEIGHT" "$WORK/bad_size" || fail "--size 12 does not say what it expects: $(cat "$WORK/bad_size")"

cat >"$WORK/broken.json" <<'JSON'
{ "version": 1, "name": "broken", "passes": [ { "name": "x", "type": "no_such_pass" } ] }
JSON
cat >"$WORK/exp.json" <<JSON
{ "name": "tt_test", "graphs": [ { "graph": "variant2_exact", "label": "exact" },
                                 { "graph": "$WORK/broken.json", "label": "broken" } ],
  "data": [ { "phantom": "small" } ], "sizes": [ "320x180" ], "time": "2:2.04:0.04",
  "frames": 1, "warmup": 0, "set": [ "overlay=false" ] }
JSON
"$PY" "$S" "$WORK/exp.json" --size 96x54 --pathlet "$PATHLET" --out "$WORK/out" >"$WORK/printed" 2>&1
rc=$?
[ $rc -eq 1 ] || fail "a broken technique: expected exit 1, got $rc: $(cat "$WORK/printed")"
grep -q "left out: broken" "$WORK/printed" || fail "the broken technique is not named: $(cat "$WORK/printed")"
grep -q "no_such_pass" "$WORK/printed" || fail "the broken technique's error is not shown"
grep -q "left out because they failed: .*broken.json" "$WORK/printed" || fail "the failure is not summed up"
grep -Eq '^\| exact \| +\| 96x54 \| [0-9.]+ \| 1\.00 ' "$WORK/out/transparency_techniques.md" ||
  fail "no table row for exact at --size 96x54: $(cat "$WORK/out/transparency_techniques.md" 2>&1)"
! grep -q broken "$WORK/out/transparency_techniques.md" || fail "the broken technique has a row"
echo "transparency-techniques: --size checked, a broken technique left out with its error, the table written, exit 1"

#!/usr/bin/env bash
# scripts/gpu-check.sh on llvmpipe, --quick: it runs the check against the committed llvmpipe
# renders of every shipped graph (tests/gpu_check/goldens/, --quick's sizes) and leaves one
# tarball with every part a GPU run needs (limits, renders that match the goldens, both benches
# with their summaries, the render loop). What a GPU measures is not checked here; that the
# script runs through, returns its results and renders what the goldens show is.
#   test_gpu_check.sh SOURCE_DIR PATHLET
#   PATHLET_UPDATE_GOLDENS=1 test_gpu_check.sh ...   re-renders the goldens (look at each before committing)
set -euo pipefail
SRC=$1 PATHLET=$2
GOLDENS=$SRC/tests/gpu_check/goldens
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
if [ "${PATHLET_UPDATE_GOLDENS:-0}" = 1 ]; then
  rm -rf "$GOLDENS"
  "$SRC/scripts/gpu-check.sh" --quick --pathlet "$PATHLET" --make-reference "$GOLDENS"
  rm -f "$GOLDENS/info-gl.txt" "$GOLDENS/unsupported.txt"  # this machine's, not goldens
  echo "gpu_check: goldens re-rendered into $GOLDENS"; exit 0
fi
"$SRC/scripts/gpu-check.sh" --quick --pathlet "$PATHLET" --reference "$GOLDENS" "$WORK/out" >"$WORK/printed" 2>&1 ||
  { cat "$WORK/printed"; echo "FAIL: the check exited non-zero"; exit 1; }
tarballs=("$WORK"/out/gpu-check-*.tar.gz)
[ ${#tarballs[@]} -eq 1 ] && [ -f "${tarballs[0]}" ] || { echo "FAIL: expected one tarball, got: ${tarballs[*]}"; exit 1; }
tar -C "$WORK" -xzf "${tarballs[0]}"
R=$(echo "$WORK"/gpu-check-*/)
fail() { echo "FAIL: $*"; cat "$R/summary.txt"; exit 1; }
for f in info-gl.txt info-gl-minimum.txt compare.txt summary.txt bench_window.json bench_all.json bench_window.txt; do
  [ -s "$R/$f" ] || fail "$f missing or empty"
done
grep -q '^GL_MAX_IMAGE_UNITS 8$' "$R/info-gl-minimum.txt" || fail "info-gl-minimum.txt does not say 8 image units"
grep -Eq '^PATHLET_BUILD build: (full|lean)' "$R/info-gl.txt" || fail "info-gl.txt does not say which build made it"
graphs=$(ls "$SRC"/graphs/*.json | wc -l)
# A graph this driver cannot run (an extension it lacks) is named with it instead of rendered.
unsupported=0
if [ -f "$R/renders/unsupported.txt" ]; then
  unsupported=$(wc -l <"$R/renders/unsupported.txt")
  ! grep -Ev ' needs (GL_[A-Za-z0-9_]*|EXR \(the lean build writes PNG only\))$' "$R/renders/unsupported.txt" ||
    fail "an unsupported graph without what it needs"
fi
renders=$(ls "$R"/renders/*.png | wc -l)
[ $((renders + unsupported)) -eq "$graphs" ] || fail "not one render (or unsupported) per shipped graph ($graphs): $renders, $unsupported"
[ "$renders" -gt $((graphs / 2)) ] || fail "only $renders of $graphs shipped graphs rendered"
[ "$(grep -c ' ok$' "$R/compare.txt")" -eq "$renders" ] ||
  fail "renders differ from the goldens (a deliberate change or a new graph: scripts/update-goldens.sh): $(cat "$R/compare.txt")"
grep -q 'wall fps' "$R/bench_window.txt" || fail "the bench summary has no wall fps column"
grep -q 'variant4_opacity' "$R/bench_window.txt" || fail "variant 4 is not benched"
grep -q 'variant1_lineao \[cull=false\]' "$R/bench_all.txt" || fail "every line: no unculled variant 1 beside the culled one"
grep -Eq '^loop --no-images: [0-9]+ frames, .* [0-9.]+ fps$' "$R/summary.txt" || fail "no render-loop frame rate"
grep -q '^renderer: llvmpipe' "$R/summary.txt" || fail "the summary does not name the renderer"
for g in variant1_lineao variant1_vao variant1_stable; do
  grep -q ' \* ' "$R/compute_$g.txt" || fail "compute_$g.txt has no fragment/compute row"
done
# The transparency table: every technique llvmpipe runs, against the exact reference, and exact against peeling.
for t in exact WBOIT MBOIT; do
  grep -Eq "^\| $t \| window=1 " "$R/transparency.txt" || fail "transparency.txt has no $t row for the 1 s window"
done
grep -Eq '^\| WBOIT \| window=0 \| [0-9]+x[0-9]+ \| [0-9.]+ \| [0-9.]+ \| [0-9]+ \| 0\.[0-9]+ ' "$R/transparency.txt" ||
  fail "the WBOIT row with every line has no speed, bytes and SSIM"
[ -s "$R/transparency/transparency_techniques.png" ] || fail "no speed-against-SSIM plot"
grep -Eq '^ssim (0\.99[0-9]*|1(\.0*)?)$' "$R/transparency/exact_vs_peel.txt" ||
  fail "the exact reference does not match depth peeling: $(cat "$R/transparency/exact_vs_peel.txt")"
grep -q 'variant2_depth_peel' "$R/transparency/bench_exact_peel.txt" || fail "depth peeling is not benched"
grep -q '^fragment vs compute picture: max levels 0 ' "$R/summary.txt" || fail "the ports' pictures differ (compute.txt)"
echo "gpu-check --quick: every part present; $renders renders match the goldens ($unsupported need what this driver or build lacks)"

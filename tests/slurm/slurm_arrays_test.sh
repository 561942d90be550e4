#!/usr/bin/env bash
# The Slurm scripts on a real Slurm: a one-node cluster on this machine (slurm_cluster.sh) runs
# scripts/slurm/render_array.sbatch and bench_array.sbatch as 3-task arrays, then the dependent
# steps (assemble_video.sbatch when ffmpeg is there; the bench merge), and the results must be
# a single-machine run's: the same frames byte for byte, every bench run merged.
# Exit 77 (ctest: skipped) with the reason where Slurm is not installed or cannot start; in CI
# (CI set) that fails instead (tests/support/optional_tool.sh).
set -euo pipefail
SRC=${PATHLET_SOURCE_DIR:?}
PATHLET=${PATHLET_CLI:?}
source "$SRC/tests/slurm/slurm_cluster.sh"
D=$(mktemp -d "${TMPDIR:-/tmp}/pathlet_slurm.XXXXXX")
trap 'slurm_down; rm -rf "$D"' EXIT
fail() { echo "FAIL: $*" >&2; for f in "$D"/work/*.log "$D"/slurm*.log; do [ -f "$f" ] && { echo "--- $f" >&2; tail -5 "$f" >&2; }; done; exit 1; }
if ! slurm_up "$D/slurm"; then  # skipped, or failed in CI (tests/support/optional_tool.sh)
  "$SRC/tests/support/optional_tool.sh" --missing "Slurm cannot start here: $SLURM_WHY"
  exit $?
fi
echo "slurm: one node, $(sinfo -h -N -o '%N %c CPUs %t')"
mkdir -p "$D/work"
cd "$D/work"  # jobs write their logs where they were submitted
"$PATHLET" phantom --preset small -o "$D/small.pathlet" --wall "$D/small.glb" >/dev/null 2>&1
# Small: 160x90, 9 frames; the scripts ask for 4 CPUs a task, more than a 2-core node has.
common=(--cpus-per-task=1 --time=00:10:00)
render_env="ALL,PATHLET=$PATHLET,GRAPH=variant1_lineao,DATA=$D/small.pathlet,MESH=$D/small.glb,TIME=0:2:0.25,SIZE=160x90,OUT=$D/render"
rjob=$(sbatch --parsable "${common[@]}" --array=0-2 --export="$render_env" "$SRC/scripts/slurm/render_array.sbatch")
cat > "$D/exp.json" <<JSON
{ "name": "slurm_test", "graphs": ["variant1_lineao", {"graph": "isl", "label": "ISL"}],
  "data": [{"file": "small.pathlet", "mesh": "small.glb"}], "sizes": ["64x36", "96x54"], "time": 2, "frames": 2, "warmup": 0 }
JSON
bench_env="ALL,PATHLET=$PATHLET,EXPERIMENT=$D/exp.json,OUT=$D/bench"
bjob=$(sbatch --parsable "${common[@]}" --array=0-2 --export="$bench_env" "$SRC/scripts/slurm/bench_array.sbatch")
mjob=$(sbatch --parsable "${common[@]}" --dependency=afterok:"$bjob" --export="$bench_env,MERGE=1,SHARDS=3" \
  "$SRC/scripts/slurm/bench_array.sbatch")
jobs=("$rjob" "$bjob" "$mjob")
video=0
"$SRC/tests/support/optional_tool.sh" ffmpeg && video=1 || { [ $? = 77 ] || exit 1; }  # no video step without ffmpeg, except in CI
if [ "$video" = 1 ]; then
  jobs+=("$(sbatch --parsable "${common[@]}" --dependency=afterok:"$rjob" \
    --export="ALL,GRAPH_NAME=variant1_lineao,OUT=$D/render,VIDEO=$D/render.mp4" "$SRC/scripts/slurm/assemble_video.sbatch")")
fi
echo "submitted render $rjob, bench $bjob, merge $mjob${jobs[3]:+, video ${jobs[3]}}"
SLURM_WAIT=240 slurm_wait "${jobs[@]}" || fail "jobs still queued after 240 s: $(squeue -h -o '%i %T %r')"
for j in "${jobs[@]}"; do
  states=$(slurm_states "$j")
  [ -z "$(grep -v '^COMPLETED 0:0$' <<<"$states")" ] || fail "job $j: $(tr '\n' ' ' <<<"$states")"
done
[ "$(slurm_states "$rjob" | wc -l)" = 3 ] && [ "$(slurm_states "$bjob" | wc -l)" = 3 ] || fail "not 3 tasks per array"

# Frames: the same names and bytes as one machine's render.
"$PATHLET" render variant1_lineao --data "$D/small.pathlet" --mesh "$D/small.glb" --time 0:2:0.25 --size 160x90 \
  --out "$D/single" --quiet >/dev/null
( cd "$D/single/variant1_lineao" && ls ) > "$D/single.list"
( cd "$D/render/variant1_lineao" && ls ) > "$D/array.list"
[ "$(wc -l < "$D/single.list")" = 9 ] || fail "the single run wrote $(wc -l < "$D/single.list") frames, not 9"
diff "$D/single.list" "$D/array.list" >&2 || fail "the array wrote other frames than one machine"
while read -r f; do
  cmp -s "$D/single/variant1_lineao/$f" "$D/render/variant1_lineao/$f" || fail "frame $f differs from one machine's"
done < "$D/single.list"
echo "render: 3 tasks wrote the 9 frames of one machine, byte for byte"
if [ ${#jobs[@]} = 4 ]; then
  [ -s "$D/render.mp4" ] || fail "assemble_video.sbatch wrote no video"
  echo "video: $(stat -c %s "$D/render.mp4") bytes"
fi

# Bench: every run of the experiment, once, as one machine plans them.
"$PATHLET" bench --experiment "$D/exp.json" --out "$D/bench_single" --quiet --no-images >/dev/null
python3 - "$D/bench/all/results.json" "$D/bench_single/results.json" <<'PY' || fail "merged bench results"
import json, sys
merged, single = (json.load(open(p)) for p in sys.argv[1:])
key = lambda r: (r["meta"]["index"], r["meta"]["label"], r["meta"]["size"], [p["name"] for p in r["passes"]])
assert merged["complete"] and merged["planned_runs"] == single["planned_runs"] == 4, merged.get("planned_runs")
assert "shard" not in merged
assert [key(r) for r in merged["runs"]] == [key(r) for r in single["runs"]], [key(r) for r in merged["runs"]]
assert all(len([f for f in r["frames"] if not f["warmup"]]) == 2 for r in merged["runs"])
print(f"bench: {len(merged['runs'])} of {merged['planned_runs']} runs merged from 3 shards, as one machine plans them")
PY
for f in summary.csv frames.csv passes.svg; do [ -s "$D/bench/all/$f" ] || fail "merge wrote no $f"; done
echo "PASS"

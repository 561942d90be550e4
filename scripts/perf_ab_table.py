#!/usr/bin/python3
"""The table of scripts/perf-ab.sh: new/base ratios per case and pass, with a verdict only where
every round agrees.

    perf_ab_table.py RUNS.tsv [--threshold T] [--min-ms MS] [--all-passes]

RUNS.tsv has one line per measurement: ROUND, CASE, BUILD (base or new) and either a bench
results.json (its first run: the median of every pass and of the frame over the measured frames)
or the seconds of a case timed as a whole (the render loop, start-up: wall clock or CPU time).

Per case and pass, each round gives the ratio new/base of the two medians measured in the same
minute. SLOWER: in every round the ratio is above 1 + T and the new run's fastest frame is slower
than the base run's slowest (their frames apart), and the medians over the rounds are more than MS
apart; faster likewise the other way. Anything else is noise on a busy machine, however large one
round's ratio (a small pass's ratio moves by 20-30 % from run to run, and three rounds in a row
can agree on that by chance; their frames then overlap). Rows: every case's frame (or run), and its passes that
take at least 5 % of the base frame (all with --all-passes); a flagged pass is always shown.
"""
import argparse
import json
import statistics
import sys

FRAME = "(frame)"
RUN = "(run)"
SHOWN_SHARE = 0.05  # passes below this share of the frame are listed only with --all-passes


def samples_of(results_path):
    """{pass or FRAME: [ms of every measured frame]} of a bench results.json's first run."""
    with open(results_path) as f:
        report = json.load(f)
    runs = report.get("runs") or []
    if not runs:
        raise ValueError(f"{results_path}: no runs (the bench did not finish)")
    frames = [fr for fr in runs[0].get("frames", []) if not fr.get("warmup")]
    if not frames:
        raise ValueError(f"{results_path}: no measured frames")
    samples = {FRAME: [fr["gpu_ms"] for fr in frames if isinstance(fr.get("gpu_ms"), (int, float))]}
    for fr in frames:
        for name, ms in (fr.get("passes") or {}).items():
            if isinstance(ms, (int, float)):
                samples.setdefault(name, []).append(ms)
    return {name: v for name, v in samples.items() if v}


def read_runs(path):
    """{case: {round: {build: {pass: [ms]}}}} and the cases in their first order."""
    data, order = {}, []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            fields = line.split("\t")
            if len(fields) != 4 or fields[2] not in ("base", "new"):
                raise ValueError(f"{path}:{number}: expected ROUND, CASE, base|new, FILE|SECONDS separated by tabs")
            rnd, case, build, what = fields
            try:
                times = {RUN: [float(what) * 1000.0]}
            except ValueError:
                times = samples_of(what)
            if case not in data:
                order.append(case)
            data.setdefault(case, {}).setdefault(rnd, {})[build] = times
    return data, order


def verdict(pairs, base_ms, new_ms, threshold, min_ms):
    """pairs: (base frames, new frames) of every round."""
    if len(pairs) < 2 or abs(new_ms - base_ms) <= min_ms:
        return ""
    ratios = [statistics.median(n) / statistics.median(b) for b, n in pairs]
    if all(r > 1.0 + threshold for r in ratios) and all(min(n) > max(b) for b, n in pairs):
        return "SLOWER"
    if all(r < 1.0 / (1.0 + threshold) for r in ratios) and all(max(n) < min(b) for b, n in pairs):
        return "faster"
    return ""


def rows(data, order, threshold, min_ms, all_passes):
    """(case, pass, base ms, new ms, ratios, verdict) for the table, cases in order."""
    out = []
    for case in order:
        rounds = [r for r in data[case].values() if "base" in r and "new" in r]
        if not rounds:
            continue
        names = set.intersection(*(set(r["base"]) & set(r["new"]) for r in rounds))
        whole = RUN if RUN in names else FRAME
        med = lambda r, build, name: statistics.median(r[build][name])
        base_whole = statistics.median(med(r, "base", whole) for r in rounds) if whole in names else 0.0
        ordered = [whole] + sorted(n for n in names if n != whole)
        for name in ordered:
            base = statistics.median(med(r, "base", name) for r in rounds)
            new = statistics.median(med(r, "new", name) for r in rounds)
            pairs = [(r["base"][name], r["new"][name]) for r in rounds if med(r, "base", name) > 0]
            ratios = [statistics.median(n) / statistics.median(b) for b, n in pairs]
            v = verdict(pairs, base, new, threshold, min_ms) if pairs else ""
            shown = name == whole or all_passes or v or (base_whole > 0 and base >= SHOWN_SHARE * base_whole)
            if shown:
                out.append((case, name, base, new, ratios, v))
    return out


def ratio_range(ratios):
    if not ratios:
        return "-"
    lo, hi = min(ratios), max(ratios)
    return f"{lo:.2f}" if hi - lo < 0.005 else f"{lo:.2f}-{hi:.2f}"


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs")
    p.add_argument("--threshold", type=float, default=0.15)
    p.add_argument("--min-ms", type=float, default=0.5)
    p.add_argument("--all-passes", action="store_true")
    a = p.parse_args(argv)
    if not a.threshold > 0:
        p.error("--threshold must be > 0 (0.15 = 15 %)")
    try:
        data, order = read_runs(a.runs)
    except (OSError, ValueError) as e:
        print(f"perf_ab_table: {e}", file=sys.stderr)
        return 2
    table = rows(data, order, a.threshold, a.min_ms, a.all_passes)
    print(f"{'case':<34} {'pass':<22} {'base ms':>9} {'new ms':>9} {'new/base, each round':>21}  verdict")
    for case, name, base, new, ratios, v in table:
        print(f"{case:<34} {name:<22} {base:>9.1f} {new:>9.1f} {ratio_range(ratios):>21}  {v}")
    slower = sum(1 for r in table if r[5] == "SLOWER")
    faster = sum(1 for r in table if r[5] == "faster")
    print(f"{slower} slower, {faster} faster: flagged only where, in every round, the ratio is beyond "
          f"{1 + a.threshold:.2f} (or below {1 / (1 + a.threshold):.2f}) and the two runs' frames are apart, and the "
          f"medians are over {a.min_ms:g} ms apart")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

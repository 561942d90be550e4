"""Figures of ``pathlet bench`` results with Matplotlib, PNG and PDF:

    python3 -m pathlet.plot RESULTS.json [--compare BASELINE.json] [--out DIR] [--format png,pdf]

* passes: one horizontal stacked bar per run (graph x sweep value x size), the top-level passes'
  medians stacked, the whole frame's median and p5..p95 at its end; every run has its own
  labelled row, so no run hides behind another and no label overlaps;
* sweep (experiments with a sweep): frame time against the swept value with a p5..p95 band
  per graph and size, and the passes of each against the value;
* compare (with --compare): before and after per run, side by side, with the change.

A pass has the same colour in every figure (and in the SVG the command writes): shipped pass
names have fixed colours, others a colour from a hash of the name. Usable without the
compiled module (plots only need the results file).
"""

import argparse
import json
import math
import os
import sys

# The pass colours: one table and rule for these figures and the SVG `pathlet bench` writes
# (engine/apps/bench/svg_plot.cpp embeds the same file).
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "pass_colors.json")) as _f:
    _COLORS = json.load(_f)
PALETTE = _COLORS["palette"]
KNOWN = _COLORS["places"]
FRAME_COLOUR = "#222222"


def _fnv1a32(text):
    h = 0x811C9DC5
    for b in text.encode():
        h = ((h ^ b) * 0x01000193) & 0xFFFFFFFF
    return h


def pass_colors(names):
    """Name -> colour by pass_colors.json's rule: fixed for shipped passes, else hashed into the
    colours no known pass of these names uses (the next free one on a collision, in the order
    given)."""
    taken = {KNOWN[n] for n in names if n in KNOWN}
    out = {}
    for n in names:
        if n in out:
            continue
        if n in KNOWN:
            out[n] = PALETTE[KNOWN[n]]
            continue
        i = _fnv1a32(n) % len(PALETTE)
        for _ in range(len(PALETTE)):
            if i not in taken:
                break
            i = (i + 1) % len(PALETTE)
        taken.add(i)
        out[n] = PALETTE[i]
    return out


# ---- reading results ------------------------------------------------------------------------

def load(path):
    """A results.json, checked enough to plot: names the file and what is missing."""
    try:
        with open(path) as f:
            report = json.load(f)
    except OSError as e:
        raise SystemExit(f"{path}: cannot read: {e.strerror}")
    except ValueError as e:
        raise SystemExit(f"{path}: not valid JSON: {e}")
    if not isinstance(report, dict) or not isinstance(report.get("runs"), list):
        raise SystemExit(f"{path}: /runs: expected the results of pathlet bench (an object with \"runs\")")
    for i, r in enumerate(report["runs"]):
        for key in ("meta", "frame", "passes"):
            if key not in r:
                raise SystemExit(f"{path}: /runs/{i}: missing \"{key}\"")
    return report


def _run_label(report, run, with_size=True):
    m = run["meta"]
    label = m.get("label") or m.get("graph_label") or m.get("graph", "?")
    return f"{label} \u00b7 {m.get('size', '')}" if with_size else label


def _top_passes(run):
    return [(p["name"], p["gpu_ms"]["median"]) for p in run["passes"] if p.get("depth", 0) == 0]


def _pass_names(*reports):
    names = []
    for rep in reports:
        for r in rep["runs"]:
            for n, _ in _top_passes(r):
                if n not in names:
                    names.append(n)
    return names


def _renderer(report):
    return report.get("gl_renderer", "")


def _ordered_runs(report):
    """Runs grouped by size (in the experiment's order), plan order within a size."""
    sizes = list(report.get("sizes") or [])
    for r in report["runs"]:
        if r["meta"].get("size") not in sizes:
            sizes.append(r["meta"].get("size"))
    return sorted(report["runs"], key=lambda r: (sizes.index(r["meta"].get("size")), r["meta"].get("index", 0)))


# ---- figures ---------------------------------------------------------------------------------

def _figure(width, height):
    from matplotlib.figure import Figure
    return Figure(figsize=(width, height), layout="constrained")


def _bars(ax, rows, colors, hatch=None, alpha=1.0, height=0.7, offset=0.0):
    """rows: [(y, [(pass, ms), ...], frame_stats)]; stacked horizontal bars."""
    for y, parts, frame in rows:
        left = 0.0
        for name, ms in parts:
            ax.barh(y + offset, ms, left=left, height=height, color=colors[name], alpha=alpha, hatch=hatch,
                    edgecolor="white", linewidth=0.5)
            left += ms
        if frame:
            med, p5, p95 = frame["median"], frame["p5"], frame["p95"]
            ax.errorbar([med], [y + offset], xerr=[[med - p5], [p95 - med]], fmt="|", color=FRAME_COLOUR,
                        markersize=height * 14, capsize=2, linewidth=1)


def stacked_bars(report, ax=None, colors=None, title=None):
    """Per run, the top-level passes' median ms stacked; the frame's median and p5..p95 at the end."""
    runs = _ordered_runs(report)
    colors = colors or pass_colors(_pass_names(report))
    fig = None
    if ax is None:
        fig = _figure(10, 1.4 + 0.42 * max(1, len(runs)))
        ax = fig.add_subplot()
    rows, labels, y = [], [], 0.0
    last_size = None
    for r in runs:
        size = r["meta"].get("size")
        if last_size is not None and size != last_size:
            y += 0.6  # a gap between sizes
        last_size = size
        rows.append((y, _top_passes(r), r["frame"]["gpu_ms"]))
        labels.append(_run_label(report, r))
        y += 1.0
    _bars(ax, rows, colors)
    top = max([r[2]["p95"] for r in rows] + [sum(ms for _, ms in r[1]) for r in rows] + [1e-9])
    for (yy, parts, frame) in rows:
        ax.text(max(frame["p95"], sum(ms for _, ms in parts)) + top * 0.01, yy, f"{frame['median']:.1f} ms",
                va="center", fontsize=8)
    ax.set_yticks([r[0] for r in rows], labels, fontsize=9)
    ax.invert_yaxis()
    ax.set_xlim(0, top * 1.15)
    ax.set_xlabel("median ms per frame (stacked: top-level passes; | and whisker: frame median, p5\u2013p95)")
    ax.grid(axis="x", color="#dddddd")
    ax.set_axisbelow(True)
    from matplotlib.patches import Patch
    handles = [Patch(color=colors[n], label=n) for n in _pass_names(report)]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False,
              title="pass", title_fontsize=9)
    ax.set_title(title or f"{report.get('experiment', 'bench')}: time per pass ({_renderer(report)})", fontsize=10)
    return fig


def _x_of(value, index):
    try:
        return float(value), True
    except (TypeError, ValueError):
        return float(index), False


def sweep_series(report):
    """{(graph label, size): [(x, run), ...]} in sweep order; numeric True when every value is a number."""
    series, numeric = {}, True
    values = []
    for r in report["runs"]:
        v = r["meta"].get("sweep_value", "")
        if v not in values:
            values.append(v)
    for r in report["runs"]:
        m = r["meta"]
        x, isnum = _x_of(m.get("sweep_value"), values.index(m.get("sweep_value", "")))
        numeric &= isnum
        series.setdefault((m.get("graph_label", m.get("label")), m.get("size")), []).append((x, r))
    return series, numeric, values


def sweep_plot(report, colors=None):
    """Frame time against the swept value (p5..p95 bands), then each graph's passes against it."""
    param = report.get("sweep_param") or "value"
    series, numeric, values = sweep_series(report)
    colors = colors or pass_colors(_pass_names(report))
    n = len(series) + 1
    cols = min(3, n)
    rows = math.ceil(n / cols)
    fig = _figure(4.2 * cols + 1.5, 3.4 * rows)
    axes = [fig.add_subplot(rows, cols, i + 1) for i in range(n)]
    line_colors = ["#1f3b73", "#c0392b", "#2e8b57", "#8e44ad", "#d35400", "#16a085", "#7f8c8d", "#b7950b"]
    ax = axes[0]
    for k, ((graph, size), pts) in enumerate(series.items()):
        pts.sort(key=lambda p: p[0])
        xs = [p[0] for p in pts]
        f = [p[1]["frame"]["gpu_ms"] for p in pts]
        c = line_colors[k % len(line_colors)]
        ax.fill_between(xs, [s["p5"] for s in f], [s["p95"] for s in f], color=c, alpha=0.2, linewidth=0)
        ax.plot(xs, [s["median"] for s in f], "o-", color=c, label=f"{graph} \u00b7 {size}", markersize=4)
    ax.set_title("frame (median, band p5\u2013p95)", fontsize=10)
    ax.legend(fontsize=8, frameon=False)
    for ax_, ((graph, size), pts) in zip(axes[1:], series.items()):
        xs = [p[0] for p in pts]
        names = []
        for _, r in pts:
            for nme, _ in _top_passes(r):
                if nme not in names:
                    names.append(nme)
        for nme in names:
            stats = [next((p["gpu_ms"] for p in r["passes"] if p["name"] == nme), None) for _, r in pts]
            xs_, st = zip(*[(x, s) for x, s in zip(xs, stats) if s]) if any(stats) else ((), ())
            ax_.fill_between(xs_, [s["p5"] for s in st], [s["p95"] for s in st], color=colors[nme], alpha=0.25,
                             linewidth=0)
            ax_.plot(xs_, [s["median"] for s in st], "o-", color=colors[nme], label=nme, markersize=3)
        ax_.set_title(f"{graph} \u00b7 {size}: per pass", fontsize=10)
    for ax_ in axes:
        ax_.set_xlabel(param)
        ax_.set_ylabel("ms")
        ax_.set_ylim(bottom=0)
        ax_.grid(color="#dddddd")
        if not numeric:
            ax_.set_xticks(range(len(values)), values)
    if len(axes) > 1:
        from matplotlib.patches import Patch
        handles = [Patch(color=colors[n], label=n) for n in _pass_names(report)]
        axes[-1].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False,
                        title="pass", title_fontsize=9)
    fig.suptitle(f"{report.get('experiment', 'bench')}: frame time against {param} ({_renderer(report)})",
                 fontsize=11)
    return fig


def _key(run):
    m = run["meta"]
    return (m.get("label"), m.get("size"))


def compare_plot(baseline, current, colors=None, names=("before", "after")):
    """Before and after per run found in both: stacked passes, frame whiskers, the change."""
    base = {_key(r): r for r in baseline["runs"]}
    pairs = [(base[_key(r)], r) for r in _ordered_runs(current) if _key(r) in base]
    if not pairs:
        raise SystemExit("compare: no run in common (different graphs or sizes?)")
    colors = colors or pass_colors(_pass_names(baseline, current))
    fig = _figure(10, 1.6 + 0.85 * len(pairs))
    ax = fig.add_subplot()
    before, after, ticks, labels = [], [], [], []
    top = 1e-9
    for i, (b, c) in enumerate(pairs):
        y = i * 1.0
        before.append((y, _top_passes(b), b["frame"]["gpu_ms"]))
        after.append((y, _top_passes(c), c["frame"]["gpu_ms"]))
        ticks.append(y)
        labels.append(_run_label(current, c))
        top = max(top, b["frame"]["gpu_ms"]["p95"], c["frame"]["gpu_ms"]["p95"],
                  sum(ms for _, ms in _top_passes(b)), sum(ms for _, ms in _top_passes(c)))
    _bars(ax, before, colors, hatch="///", alpha=0.55, height=0.38, offset=-0.2)
    _bars(ax, after, colors, height=0.38, offset=0.2)
    for (y, _, fb), (_, _, fc) in zip(before, after):
        change = (fc["median"] / fb["median"] - 1) * 100 if fb["median"] > 0 else float("nan")
        ax.text(top * 1.02, y - 0.2, f"{names[0]} {fb['median']:.1f} ms", va="center", fontsize=8)
        ax.text(top * 1.02, y + 0.2, f"{names[1]} {fc['median']:.1f} ms ({change:+.0f} %)", va="center", fontsize=8)
    ax.set_yticks(ticks, labels, fontsize=9)
    ax.invert_yaxis()
    ax.set_xlim(0, top * 1.4)
    ax.set_xlabel(f"median ms per frame (hatched: {names[0]}, solid: {names[1]}; whisker: frame p5\u2013p95)")
    ax.grid(axis="x", color="#dddddd")
    ax.set_axisbelow(True)
    from matplotlib.patches import Patch
    handles = [Patch(color=colors[n], label=n) for n in _pass_names(baseline, current)]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False, title="pass")
    ax.set_title(f"{current.get('experiment', 'bench')}: {names[0]} ({_renderer(baseline)}) and {names[1]} "
                 f"({_renderer(current)})", fontsize=10)
    return fig


def _save(fig, path):
    """Nothing half-written: a temporary name beside the target, then rename."""
    d, base = os.path.split(path)
    tmp = os.path.join(d, f".{base}.tmp-{os.getpid()}{os.path.splitext(base)[1]}")
    try:
        fig.savefig(tmp, dpi=150)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


def write_all(report, out_dir, formats=("png", "pdf"), baseline=None, names=("before", "after")):
    """passes.*, sweep.* (with a sweep) and compare.* (with a baseline) into out_dir."""
    os.makedirs(out_dir, exist_ok=True)
    colors = pass_colors(_pass_names(*([baseline] if baseline else []), report))
    figures = {"passes": stacked_bars(report, colors=colors)}
    if report.get("sweep_param"):
        figures["sweep"] = sweep_plot(report, colors=colors)
    if baseline is not None:
        figures["compare"] = compare_plot(baseline, report, colors=colors, names=names)
    files = []
    for name, fig in figures.items():
        for fmt in formats:
            files.append(_save(fig, os.path.join(out_dir, f"{name}.{fmt}")))
    return files


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m pathlet.plot",
                                description="Figures of pathlet bench results (PNG and PDF, Matplotlib).")
    p.add_argument("results", help="results.json of pathlet bench --experiment (or pathlet.Results.save)")
    p.add_argument("--compare", metavar="BASELINE.json", help="also a before (baseline) / after (results) figure")
    p.add_argument("--out", metavar="DIR", help="where the figures go (default: the results' folder)")
    p.add_argument("--format", default="png,pdf", help="comma-separated: png, pdf, svg (default png,pdf)")
    a = p.parse_args(argv)
    formats = [f for f in a.format.split(",") if f]
    for f in formats:
        if f not in ("png", "pdf", "svg"):
            p.error(f"--format: unknown format '{f}' (png, pdf, svg)")
    report = load(a.results)
    baseline = load(a.compare) if a.compare else None
    names = ("before", "after")
    if baseline is not None:
        names = (os.path.basename(os.path.dirname(os.path.abspath(a.compare))) or "before",
                 os.path.basename(os.path.dirname(os.path.abspath(a.results))) or "after")
        if names[0] == names[1]:
            names = ("before", "after")
    import matplotlib
    matplotlib.use("Agg")
    out = a.out or os.path.dirname(os.path.abspath(a.results))
    for f in write_all(report, out, formats, baseline, names):
        print(f"wrote {f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

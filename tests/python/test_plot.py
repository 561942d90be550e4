# pathlet.plot and `pathlet bench --plots`: every run has its own labelled row, one colour per
# pass in every figure (and the same as the SVG the command writes), PNG and PDF, clear errors.
import json
import os
import re
import subprocess
import sys

import pytest

from conftest import read_png

GRAPHS = {
    "V1 LineAO": ["gbuffer", "gauss_pyramid", "lineao", "bilateral", "wall", "edge_aa", "overlay"],
    "V2 OIT": ["clear_list", "fill_list", "resolve_list", "gauss_pyramid", "lineao", "bilateral", "wall"],
    "V3 geometric fade": ["geometric_fade", "gauss_pyramid", "lineao", "bilateral", "wall", "edge_aa"],
    "ISL": ["isl", "wall", "edge_aa", "overlay"],
}


def stats(ms):
    return {"median": ms, "p5": ms * 0.95, "p95": ms * 1.1, "n": 10, "mean": ms, "min": ms, "max": ms}


def table3(sweep=None, scale=1.0, graphs=GRAPHS):
    """A results report shaped like table3_variants at two sizes (with a sweep of a value)."""
    runs, k = [], 0
    values = sweep or [""]
    for label, passes in graphs.items():
        for v in values:
            for size in ["1280x720", "1920x1080"]:
                f = (2.25 if size == "1920x1080" else 1.0) * scale * (1 + (float(v) if v else 0))
                ps = [{"name": n, "depth": 0, "gpu_ms": stats(f * (3 + i)), "share_pct": 0} for i, n in enumerate(passes)]
                full = sum(p["gpu_ms"]["median"] for p in ps)
                runs.append({"meta": {"index": k, "label": label + (f" window={v}" if v else ""), "graph_label": label,
                                      "size": size, "sweep_value": v},
                             "frame": {"gpu_ms": stats(full * 1.03)}, "passes": ps})
                k += 1
    return {"experiment": "table3_variants", "gl_renderer": "llvmpipe", "sizes": ["1280x720", "1920x1080"],
            "sweep_param": "window" if sweep else "", "planned_runs": k, "runs": runs}


def test_every_run_has_a_labelled_row_and_passes_keep_their_colour():
    from pathlet import plot
    rep = table3()
    fig = plot.stacked_bars(rep)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert labels == [f"{g} \u00b7 {s}" for s in ["1280x720", "1920x1080"] for g in GRAPHS], "grouped by size"
    ys = sorted(ax.get_yticks())
    assert min(b - a for a, b in zip(ys, ys[1:])) >= 1.0, "a row per run"
    names = [t.get_text() for t in ax.get_legend().get_texts()]
    assert sorted(names) == sorted({n for ps in GRAPHS.values() for n in ps})
    colours = plot.pass_colors(names)
    assert len(set(colours.values())) == len(names), "no two passes alike"
    # Every segment of a pass has that pass's colour: count segments per colour.
    from matplotlib.colors import to_hex
    seg = {}
    for p in ax.patches:
        seg[to_hex(p.get_facecolor())] = seg.get(to_hex(p.get_facecolor()), 0) + 1
    for n in names:
        runs_with = 2 * sum(n in ps for ps in GRAPHS.values())
        assert seg.get(colours[n]) == runs_with, n
    # The same pass has the same colour in a figure of other graphs.
    assert plot.pass_colors(["isl", "wall"])["wall"] == colours["wall"]


def test_sweep_and_compare_figures(tmp_path):
    from pathlet import plot
    two = {k: GRAPHS[k] for k in ("V1 LineAO", "ISL")}
    sweep = table3(sweep=["0.25", "0.5", "1"], graphs=two)
    files = plot.write_all(sweep, str(tmp_path / "s"), baseline=table3(sweep=["0.25", "0.5", "1"], scale=1.2, graphs=two))
    names = sorted(os.path.basename(f) for f in files)
    assert names == ["compare.pdf", "compare.png", "passes.pdf", "passes.png", "sweep.pdf", "sweep.png"]
    for f in files:
        assert os.path.getsize(f) > 2000, f
        if f.endswith(".png"):
            img = read_png(f)
            assert img.shape[0] > 300 and img[..., :3].std() > 10, f"{f} shows something"
        else:
            assert open(f, "rb").read(5) == b"%PDF-"
    assert not [f for f in os.listdir(tmp_path / "s") if f.startswith(".")], "no temporary left"
    fig = plot.sweep_plot(sweep)
    frame = fig.axes[0]
    assert len(frame.lines) == 4, "a line per graph and size"
    assert len(frame.collections) == 4, "a p5-p95 band per line"
    assert len(fig.axes) == 5, "and the passes of each against the value"
    cmp = plot.compare_plot(table3(scale=1.2), table3())
    texts = [t.get_text() for t in cmp.axes[0].texts]
    assert any("(-17 %)" in t for t in texts), texts  # 1/1.2 - 1


def test_command_line_and_bench_plots(cli, root, tmp_path):
    exp = tmp_path / "e.json"
    # A pass name no shipped graph has: its colour comes from the hash rule of pass_colors.json.
    (tmp_path / "mine.json").write_text(json.dumps({
        "version": 1, "resources": {"c": {"format": "rgba8"}},
        "passes": [{"name": "my_lines", "type": "isl", "outputs": {"color": "c"}}], "outputs": [{"resource": "c"}]}))
    exp.write_text(json.dumps({"graphs": ["variant1_lineao", "isl", str(tmp_path / "mine.json")],
                               "data": [{"phantom": "small"}], "sizes": ["64x36", "96x54"], "time": 2, "frames": 2,
                               "warmup": 0}))
    cli("bench", "--experiment", str(exp), "--out", str(tmp_path / "out"), "--quiet", "--no-images", "--plots")
    for f in ("passes.png", "passes.pdf", "passes.svg"):
        assert (tmp_path / "out" / f).stat().st_size > 1000, f
    # The SVG and the Matplotlib figure give each pass the same colour.
    from pathlet import plot
    svg = (tmp_path / "out" / "passes.svg").read_text()
    legend = dict((n, c) for c, n in re.findall(r'width="12" height="12" fill="(#[0-9a-f]{6})"/><text[^>]*>([^<]*)<', svg))
    assert "my_lines" in legend and legend == plot.pass_colors(list(legend))
    env = dict(os.environ)
    r = subprocess.run([sys.executable, "-m", "pathlet.plot", str(tmp_path / "nope.json")], capture_output=True,
                       text=True, env=env)
    assert r.returncode != 0 and "nope.json: cannot read" in r.stderr
    (tmp_path / "bad.json").write_text('{"runs": [{"meta": {}}]}')
    r = subprocess.run([sys.executable, "-m", "pathlet.plot", str(tmp_path / "bad.json")], capture_output=True,
                       text=True, env=env)
    assert r.returncode != 0 and 'bad.json: /runs/0: missing "frame"' in r.stderr
    r = subprocess.run([sys.executable, "-m", "pathlet.plot", str(tmp_path / "out" / "results.json"), "--compare",
                        str(tmp_path / "out" / "results.json"), "--out", str(tmp_path / "cmp"), "--format", "png"],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    assert sorted(os.listdir(tmp_path / "cmp")) == ["compare.png", "passes.png"]

#!/usr/bin/python3
"""Speed, memory and fidelity of the transparency techniques in one table.

  scripts/transparency-techniques.py [EXPERIMENT] [--out DIR] [--plots] [--reference GRAPH] [--size WxH]

EXPERIMENT (default graphs/experiments/transparency_techniques.json) names the techniques, the
data, sizes, times and the sweep, as for `pathlet bench --experiment`. For every data set, size
and sweep value the script
  1. times every graph the driver can run with `pathlet bench --experiment` (a graph that fails
     in setup with "needs GL_..." is left out, saying so): median frame and per-pass ms;
  2. reads the bytes per pixel from `pathlet graph GRAPH --plan`: every resource but the picture
     passes all techniques share (oit_color, composed, final), a growing buffer at the size
     the run reported (the lists' node_memory_mib);
  3. measures every technique against the reference (default: the experiment's first graph,
     variant2_exact) with `pathlet quality GRAPH --reference REF` over the same times, size and
     sets: SSIM (windowed), PSNR, RMSE, share over 8/255, flicker beyond the reference's own, FLIP;
and writes DIR/transparency_techniques.md and .csv (and prints the table), and each technique's
error images (pathlet quality --out) under DIR/errors/GRAPH-SWEEP-SIZE/. --plots adds
DIR/transparency_techniques.png and .svg: speed-up over the reference against SSIM, one panel a
sweep value, with the Pareto front (the techniques no other beats in both). --size replaces the
experiment's sizes (scripts/gpu-check.sh runs it at 1920x1080).
Exit status 2 for a bad experiment or option, 1 when a command fails (a technique that fails in
setup for another reason than a missing extension is left out, the table written, and the exit 1).
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMMON = {"oit_color", "composed", "final"}  # the picture's tail every variant2_* graph has
METRICS = [("ssim", r"^ssim ([-\d.eE+naninf]+)"), ("psnr", r"^psnr ([-\d.eE+naninf]+)"),
           ("rmse", r"^rmse ([-\d.eE+naninf]+)"), ("share_over_pct", r"^share over 8/255 ([-\d.eE+naninf]+) %"),
           ("flicker", r"^flicker vs reference ([-\d.eE+naninf]+|n/a)"), ("flip", r"^flip ([-\d.eE+naninf]+)")]
FAILED = []  # graphs that broke (not a missing extension): the table is written, the exit status is 1
MIB = {"B": 1.0 / 1048576, "KiB": 1.0 / 1024, "MiB": 1.0, "GiB": 1024.0}


def fail(msg, code=1):
    print(f"transparency-techniques: {msg}", file=sys.stderr)
    sys.exit(code)


def run(cmd):
    try:
        p = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as ex:
        fail(f"cannot run {cmd[0]}: {ex}")
    if p.returncode != 0:
        fail(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr.strip()}")
    return p.stdout


def load_experiment(path):
    try:
        with open(path, encoding="utf-8") as f:
            text = "\n".join(line for line in f.read().split("\n") if not line.lstrip().startswith("//"))
        e = json.loads(text)
    except (OSError, ValueError) as ex:
        fail(f"{path}: {ex}", 2)
    if not isinstance(e, dict) or not isinstance(e.get("graphs"), list) or not e["graphs"]:
        fail(f"{path}: /graphs: a list of at least one graph is needed", 2)
    return e


def graphs_of(e):
    return [(g, g) if isinstance(g, str) else (g["graph"], g.get("label", g["graph"])) for g in e["graphs"]]


def data_args(ds):
    if "phantom" in ds:
        return ["--phantom", ds["phantom"]]
    args = ["--data", ds["file"]]
    return args + (["--mesh", ds["mesh"]] if "mesh" in ds else [])


def runs_here(pathlet, graph, e):
    """'' when the driver runs the graph, else the one line it fails with (a missing extension)."""
    ds = (e.get("data") or [{"phantom": "small"}])[0]
    t = str(e.get("time", "")).split(":")[0]
    cmd = [pathlet, "render", graph, "--size", "64x36", "--no-images", "--quiet", "--warmup", "0"] + data_args(ds)
    try:
        p = subprocess.run(cmd + (["--time", t] if t else []), capture_output=True, text=True)
    except OSError as ex:
        fail(f"cannot run {pathlet}: {ex}")
    if p.returncode == 0:
        return ""
    line = next((l for l in p.stderr.split("\n") if "needs GL_" in l), "")
    if not line:  # a technique that breaks is left out of the table, said in full, and fails the run
        print(f"transparency-techniques: {' '.join(cmd)} failed ({p.returncode}):\n{p.stderr.strip()[:4000]}",
              file=sys.stderr)
        FAILED.append(graph)
        return "failed in setup: broken on this driver (above)"
    return line


def plan_bytes_per_pixel(pathlet, graph, size, sets):
    """Bytes a pixel of the graph's resources but the shared picture tail, from --plan."""
    w, h = (int(v) for v in size.split("x"))
    out = run([pathlet, "graph", graph, "--plan", "--size", size] + sum((["--set", s] for s in sets), []))
    total, buffers = 0.0, []
    for line in out.split("\n"):
        m = re.match(r"^\s+(\S+)\s+\|[#.]+\|\s+slot \d+\s+(\S+).*?([\d.]+) (B|KiB|MiB|GiB)\s", line)
        if not m or m.group(1) in COMMON:
            continue
        total += float(m.group(3)) * MIB[m.group(4)]
        if m.group(2) == "buffer":
            buffers.append(m.group(1))
    return total * 1048576 / (w * h), buffers


def quality(pathlet, graph, reference, ds, time, size, sets, out):
    cmd = [pathlet, "quality", graph, "--reference", reference, "--size", size, "--out", out] + data_args(ds)
    cmd += (["--time", time] if time else []) + sum((["--set", s] for s in sets), [])
    out = run(cmd)
    r = {}
    for key, pattern in METRICS:
        m = re.search(pattern, out, re.M)
        if not m:
            fail(f"{' '.join(cmd)}: no '{key}' in its output:\n{out}")
        r[key] = float("nan") if m.group(1) == "n/a" else float(m.group(1))
    return r


def pareto(points):
    """Indices of the points no other beats in both coordinates (higher is better in both)."""
    return [i for i, (x, y) in enumerate(points)
            if not any((x2 >= x and y2 >= y) and (x2 > x or y2 > y) for j, (x2, y2) in enumerate(points) if j != i)]


def plot(rows, reference, path_stem):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    groups = sorted({(r["data"], r["size"], r["sweep"]) for r in rows})
    fig, axes = plt.subplots(1, len(groups), figsize=(5.2 * len(groups), 4.2), squeeze=False)
    for ax, key in zip(axes[0], groups):
        rs = [r for r in rows if (r["data"], r["size"], r["sweep"]) == key]
        pts = [(r["speedup"], r["ssim"]) for r in rs]
        front = sorted((pts[i] for i in pareto(pts)), key=lambda p: p[0])
        ax.plot([p[0] for p in front], [p[1] for p in front], "--", color="0.6", label="Pareto front", zorder=1)
        for r, (x, y) in zip(rs, pts):
            ax.scatter([x], [y], s=40, zorder=2)
            ax.annotate(f"{r['technique']}\n{r['frame_ms']:.0f} ms, {r['bytes_per_pixel']:.0f} B/px", (x, y),
                        textcoords="offset points", xytext=(6, -4), fontsize=8)
        ax.axhline(0.95, color="0.8", lw=0.8)
        ax.set_xlabel(f"speed-up over {reference} (frame time)")
        ax.set_ylabel(f"SSIM against {reference}")
        data, size, sweep = key
        ax.set_title(f"{os.path.basename(data)} {size}" + (f", {sweep}" if sweep else ""), fontsize=9)
        ax.set_xlim(min(x for x, _ in pts) * 0.85, max(x for x, _ in pts) * 1.45)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{path_stem}.{ext}", dpi=110)
    return [f"{path_stem}.png", f"{path_stem}.svg"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("experiment", nargs="?", default=os.path.join(ROOT, "graphs/experiments/transparency_techniques.json"))
    ap.add_argument("--out", default="out/transparency_techniques")
    ap.add_argument("--plots", action="store_true")
    ap.add_argument("--reference", default="", help="reference graph (default: the experiment's first)")
    ap.add_argument("--pathlet", default=os.path.join(ROOT, "build/bin/pathlet"))
    ap.add_argument("--size", default="", help="WxH: measure at this size instead of the experiment's sizes")
    a = ap.parse_args()
    e = load_experiment(a.experiment)
    if a.size:
        if not re.fullmatch(r"[1-9]\d*x[1-9]\d*", a.size):
            fail(f"--size '{a.size}': expected WIDTHxHEIGHT, e.g. 1920x1080", 2)
        e["sizes"] = [a.size]
    for ds in e.get("data", []):  # data files are named relative to the experiment file, as bench reads them
        for k in ("file", "mesh"):
            if k in ds and not os.path.isabs(ds[k]):
                ds[k] = os.path.join(os.path.dirname(os.path.abspath(a.experiment)), ds[k])
    graphs = graphs_of(e)
    reference = a.reference or graphs[0][0]
    if reference not in [g for g, _ in graphs]:
        graphs.insert(0, (reference, reference))
    os.makedirs(a.out, exist_ok=True)

    kept = []
    for graph, label in graphs:
        why = runs_here(a.pathlet, graph, e)
        if why:
            print(f"left out: {label}: {why.split('failed in setup: ')[-1]}", file=sys.stderr)
            continue
        kept.append((graph, label))
    if not any(g == reference for g, _ in kept):
        fail(f"the reference {reference} does not run on this driver")
    bench_exp = dict(e, graphs=[{"graph": g, "label": l} for g, l in kept])
    bench_exp.pop("$schema", None)
    exp_path = os.path.join(a.out, "experiment.json")
    with open(exp_path, "w", encoding="utf-8") as f:
        json.dump(bench_exp, f, indent=2)
    print(f"timing {len(kept)} graphs: pathlet bench --experiment {exp_path}", file=sys.stderr)
    run([a.pathlet, "bench", "--experiment", exp_path, "--out", os.path.join(a.out, "bench")])
    with open(os.path.join(a.out, "bench", "results.json"), encoding="utf-8") as f:
        results = json.load(f)

    sweep = (e.get("sweep") or {}).get("param", "")
    label_of = dict(kept)
    timed = {}
    for r in results["runs"]:
        m = r["meta"]
        key = (m["data"], m["size"], m.get("sweep_value", ""))
        timed[(m["graph"], key)] = r
    rows = []
    for (graph, key), r in sorted(timed.items(), key=lambda kv: (kv[0][1], [g for g, _ in kept].index(kv[0][0]))):
        data, size, sv = key
        ref = timed.get((reference, key))
        sets = list(e.get("set", [])) + ([f"{sweep}={sv}"] if sweep else [])
        ds = next((d for d in results.get("data", []) if d.get("source") == data), {})
        ds_args = next(d for d in (e.get("data") or [{"phantom": "study"}])
                       if data.endswith(os.path.basename(d.get("file", "~none~"))) or
                       ("phantom" in d and f"phantom-{d['phantom']}" in data))
        time = ds.get("time", e.get("time", ""))
        bpp, buffers = plan_bytes_per_pixel(a.pathlet, graph, size, sets)
        w, h = (int(v) for v in size.split("x"))
        for p in r["passes"]:  # a growing buffer at what the run used
            grown = p.get("stats", {}).get("node_memory_mib")
            if grown and buffers:
                bpp += grown * 1048576 / (w * h)
        frame = r["frame"]["gpu_ms"]["median"]
        row = {"technique": label_of[graph], "graph": graph, "data": data, "size": size,
               "sweep": f"{sweep}={sv}" if sweep else "", "frame_ms": frame,
               "speedup": ref["frame"]["gpu_ms"]["median"] / frame if ref else float("nan"),
               "bytes_per_pixel": bpp,
               "passes": "; ".join(f"{p['name']} {p['gpu_ms']['median']:.1f}" for p in r["passes"])}
        if graph == reference:
            row.update(ssim=1.0, psnr=float("inf"), rmse=0.0, share_over_pct=0.0, flicker=0.0, flip=0.0)
        else:
            print(f"measuring {label_of[graph]} {row['sweep']} {size} against {reference}", file=sys.stderr)
            err_dir = os.path.join(a.out, "errors", "-".join(re.sub(r"[^\w.=-]", "_", v) for v in (graph, sv or "all", size)))
            row.update(quality(a.pathlet, graph, reference, ds_args, time, size, sets, err_dir))
        rows.append(row)

    cols = ["technique", "sweep", "size", "frame_ms", "speedup", "bytes_per_pixel", "ssim", "psnr", "rmse",
            "share_over_pct", "flicker", "flip", "passes"]
    head = ["technique", sweep or "setting", "size", "frame ms (median)", f"x {label_of.get(reference, reference)}",
            "bytes/px", "SSIM", "PSNR dB", "RMSE", "> 8/255 %", "flicker", "FLIP", "passes (median ms)"]
    fmt = {"frame_ms": "{:.1f}", "speedup": "{:.2f}", "bytes_per_pixel": "{:.0f}", "ssim": "{:.4f}", "psnr": "{:.1f}",
           "rmse": "{:.4f}", "share_over_pct": "{:.2f}", "flicker": "{:.4f}", "flip": "{:.4f}"}
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        lines.append("| " + " | ".join(fmt.get(c, "{}").format(r[c]) for c in cols) + " |")
    table = "\n".join(lines)
    renderer = results.get("gl_renderer", "")
    md = os.path.join(a.out, "transparency_techniques.md")
    with open(md + ".tmp", "w", encoding="utf-8") as f:
        f.write(f"{e.get('name', 'transparency_techniques')} on {renderer}; times {e.get('time', '')}\n\n{table}\n")
    os.replace(md + ".tmp", md)
    with open(os.path.join(a.out, "transparency_techniques.csv.tmp"), "w", newline="", encoding="utf-8") as f:
        wr = csv.DictWriter(f, fieldnames=cols + ["graph", "data"])
        wr.writeheader()
        for r in rows:
            wr.writerow({k: r[k] for k in cols + ["graph", "data"]})
    os.replace(os.path.join(a.out, "transparency_techniques.csv.tmp"), os.path.join(a.out, "transparency_techniques.csv"))
    print(table)
    written = [md, os.path.join(a.out, "transparency_techniques.csv")]
    if a.plots:
        written += plot(rows, label_of.get(reference, reference), os.path.join(a.out, "transparency_techniques"))
    print("wrote " + ", ".join(written), file=sys.stderr)
    if FAILED:
        fail(f"left out because they failed: {', '.join(FAILED)}")


if __name__ == "__main__":
    main()

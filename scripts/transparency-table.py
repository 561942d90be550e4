#!/usr/bin/env python3
"""Does opacity optimization help? The measures of `pathlet quality --transparency` for variant 2,
variant 4 at a few settings, and two baselines tuned to each variant 4's mean
pixel coverage: a uniform opacity and a speed -> opacity transfer function (both times the end
fade, on variant2_oit_ao's pipeline). Each baseline is run on a grid of its parameter and
interpolated at the coverage, then, for the first setting, tuned by bisection to confirm.
"Dominates" = higher focus visibility and higher context coverage than both baselines. Each
variant 4 setting's clearing is printed too: opacity_resolve's depth complexity D (fragments per
covered pixel of its lists) and the factor of q and r its `adapt` rule took (1 with adapt=fixed).

  PYTHONPATH=build/python scripts/transparency-table.py --phantom study --size 1280x720 --setting "" --setting adapt=fixed
  PYTHONPATH=build/python scripts/transparency-table.py --data arch.pathlet --setting q=10,r=0.5,lambda=2
  PYTHONPATH=build/python scripts/transparency-table.py --data tracks300.trk --pseudo-time --time 5:5.4:0.04
"""
import argparse
import json
import os
import shutil
import subprocess
import tempfile

import pathlet

KEYS = ["focus_visibility", "focus_unoccluded", "focus_ink_share", "context_coverage", "alpha_change_mean",
        "alpha_change_p95", "overflow", "pixel_coverage"]
UNIFORM = ("fill_list.color_hook=uniform_fade.glsl", "fill_list.opacity")
SPEED_TF = ("fill_list.color_hook=speed_opacity_fade.glsl", "fill_list.opacity_slow")


def measure(scene, args, graph, sets):
    r = pathlet.quality(pathlet.Graph(graph, sets), scene, time=args.time, size=args.size, transparency=True)
    if "not_measured" in r:
        raise SystemExit(f"{graph}: not measured: {r['not_measured']}")
    return r


def clearing(args, sets):
    """opacity_resolve's stats at the run's end (`pathlet render --report`; the Python render
    needs numpy): depth complexity and the factor of q and r; nan where the command is absent."""
    here = os.path.join(os.path.dirname(pathlet.__file__), "..", "..", "bin", "pathlet")
    exe = os.environ.get("PATHLET_BIN") or (here if os.path.exists(here) else shutil.which("pathlet"))
    if not exe:
        return float("nan"), float("nan")
    with tempfile.TemporaryDirectory() as d:
        cmd = [exe, "render", "variant4_opacity", "--size", args.size, "--time", args.time, "--no-images", "--quiet",
               "--report", os.path.join(d, "r")]
        cmd += ["--data", args.data] + (["--pseudo-time"] if args.pseudo_time else []) if args.data else ["--phantom", args.phantom]
        for x in sets:
            cmd += ["--set", x]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with open(os.path.join(d, "r.json")) as f:
            stats = next((p.get("stats", {}) for p in json.load(f)["passes"] if p["name"] == "opacity_resolve"), {})
    return stats.get("depth_complexity", float("nan")), stats.get("clearing_scale", float("nan"))


def row(label, r):
    return "| " + label + " | " + " | ".join(
        str(r[k]) if k == "overflow" else f"{r[k]:.4f}" for k in KEYS) + " |"


def interpolate(grid, coverage):
    """(focus visibility, context coverage) of a baseline at a pixel coverage, linear in its grid."""
    pts = sorted((r["pixel_coverage"], r["focus_visibility"], r["context_coverage"]) for _, r in grid)
    if coverage <= pts[0][0]:
        return pts[0][1:]
    for (c0, v0, k0), (c1, v1, k1) in zip(pts, pts[1:]):
        if c0 <= coverage <= c1:
            t = (coverage - c0) / (c1 - c0) if c1 > c0 else 0.0
            return v0 + t * (v1 - v0), k0 + t * (k1 - k0)
    return pts[-1][1:]


def tune(scene, args, baseline, coverage, lo=0.0, hi=1.0, steps=6):
    """The baseline's parameter whose pixel coverage matches `coverage` (bisection)."""
    hook, param = baseline
    best = None
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        r = measure(scene, args, "variant2_oit_ao", [hook, f"{param}={mid:.4f}"])
        best = (mid, r)
        if r["pixel_coverage"] < coverage:
            lo = mid
        else:
            hi = mid
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--phantom", default="study")
    ap.add_argument("--data", help="a pathline file instead of the phantom")
    ap.add_argument("--pseudo-time", action="store_true", help="streamlines (tracts) animated along their arc length")
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--time", default="9:9.4:0.04")
    ap.add_argument("--setting", action="append",
                    help="variant 4 overrides, comma-separated NAME=VALUE (repeatable; default: the graph's defaults)")
    ap.add_argument("--no-tune", action="store_true", help="interpolate only")
    args = ap.parse_args()
    scene = pathlet.load(args.data, pseudo_time=args.pseudo_time) if args.data else pathlet.phantom(args.phantom)
    settings = [[x for x in s.split(",") if x] for s in args.setting] if args.setting else [[]]

    print(f"{scene!r}, {args.size}, t = {args.time}, renderer {pathlet.gl_renderer()}\n")
    print("| run | " + " | ".join(k.replace("_", " ") for k in KEYS) + " |")
    print("|---" * (len(KEYS) + 1) + "|")
    print(row("variant 2 (end fade)", measure(scene, args, "variant2_oit", [])), flush=True)
    grids = {}
    for name, (hook, param), values in (("uniform", UNIFORM, [0.2, 0.35, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]),
                                        ("speed TF", SPEED_TF, [0.0, 0.1, 0.2, 0.35, 0.5, 0.7, 0.85, 1.0])):
        grids[name] = []
        for v in values:
            r = measure(scene, args, "variant2_oit_ao", [hook, f"{param}={v}"])
            grids[name].append((v, r))
            print(row(f"{name} {param.split('.')[1]}={v}", r), flush=True)
    results = []
    for s in settings:
        r = measure(scene, args, "variant4_opacity", s)
        results.append((s, r))
        print(row("variant 4 " + (" ".join(s) if s else "(defaults)"), r), flush=True)

    print("\n| variant 4 | depth complexity, q r factor | focus visibility | context coverage | uniform at its coverage "
          "| speed TF at its coverage | dominates both | alpha change mean vs variant 2's |")
    print("|---|---|---|---|---|---|---|---|")
    v2 = measure(scene, args, "variant2_oit", [])
    for s, r in results:
        u = interpolate(grids["uniform"], r["pixel_coverage"])
        t = interpolate(grids["speed TF"], r["pixel_coverage"])
        dom = r["focus_visibility"] > max(u[0], t[0]) and r["context_coverage"] > max(u[1], t[1])
        steady = r["alpha_change_mean"] <= v2["alpha_change_mean"]
        depth, scale = clearing(args, s)
        print(f"| {' '.join(s) or '(defaults)'} | {depth:.2f}, {scale:.3f} | {r['focus_visibility']:.4f} | {r['context_coverage']:.4f} | "
              f"{u[0]:.4f}, {u[1]:.4f} | {t[0]:.4f}, {t[1]:.4f} | {'yes' if dom else 'no'} | "
              f"{r['alpha_change_mean']:.4f} vs {v2['alpha_change_mean']:.4f} ({'no larger' if steady else 'LARGER'}) |",
              flush=True)
    if not args.no_tune:
        s, r = results[0]
        print(f"\ntuned to variant 4 {' '.join(s) or '(defaults)'}'s pixel coverage {r['pixel_coverage']:.4f}:")
        for name, baseline in (("uniform", UNIFORM), ("speed TF", SPEED_TF)):
            value, b = tune(scene, args, baseline, r["pixel_coverage"])
            print(row(f"{name} {baseline[1].split('.')[1]}={value:.4f}", b), flush=True)


if __name__ == "__main__":
    main()

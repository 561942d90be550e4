#!/usr/bin/python3
"""scripts/perf-ab.sh without building or rendering: its table (scripts/perf_ab_table.py) on made-up
bench results, where what every round agrees on is flagged and nothing else, and both scripts'
answers to bad input (a clear message naming the argument or the file and line, exit 2).

  test_perf_ab.py ROOT
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(sys.argv[1])
TABLE = os.path.join(ROOT, "scripts", "perf_ab_table.py")
SCRIPT = os.path.join(ROOT, "scripts", "perf-ab.sh")
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def results(path, frame_ms, passes, spread=(0.99, 1.0, 1.01)):
    """A bench results.json of one run with three measured frames (and a warm-up frame that must
    not count) of these medians: the frames are the medians times `spread`."""
    frames = [{"frame": 0, "warmup": True, "gpu_ms": 1000.0, "passes": {p: 1000.0 for p in passes}}]
    for k, f in enumerate(spread):
        frames.append({"frame": k + 1, "warmup": False, "gpu_ms": frame_ms * f,
                       "passes": {p: ms * f for p, ms in passes.items()}})
    with open(path, "w") as out:
        json.dump({"gl_renderer": "test", "runs": [{"meta": {"label": "x"}, "frames": frames}]}, out)
    return path


def table(work, rounds, *args):
    """perf_ab_table.py over `rounds`: [{case: (base, new)}] where base and new are
    (frame ms, {pass: ms}) or a wall time in seconds. Returns (exit code, {(case, pass): row text})."""
    tsv = os.path.join(work, "runs.tsv")
    with open(tsv, "w") as f:
        for r, cases in enumerate(rounds, 1):
            for case, builds in cases.items():
                for build, m in zip(("base", "new"), builds):
                    what = str(m) if isinstance(m, float) else results(
                        os.path.join(work, f"{r}-{case}-{build}.json"), *m)
                    f.write(f"{r}\t{case}\t{build}\t{what}\n")
    p = subprocess.run([TABLE, tsv, *args], capture_output=True, text=True)
    rows = {}
    for line in p.stdout.splitlines()[1:-1]:
        case, rest = line[:34].strip(), line[35:]
        rows[(case, rest[:22].strip())] = line
    return p.returncode, rows, p.stdout + p.stderr


def verdict(rows, case, name):
    line = rows.get((case, name))
    return None if line is None else line.split()[-1] if line.rstrip().endswith(("SLOWER", "faster")) else ""


with tempfile.TemporaryDirectory() as work:
    base = (100.0, {"lineao": 30.0, "gbuffer": 40.0, "tiny": 0.3, "edge": 2.0})
    slow_ao = (130.0, {"lineao": 60.0, "gbuffer": 40.0, "tiny": 0.6, "edge": 2.0})
    # LineAO twice as slow in every round, the frame 1.3x, the rest the same.
    code, rows, text = table(work, [{"v1": (base, slow_ao)}] * 3)
    check(code == 0, f"a table of three rounds exits 0:\n{text}")
    check(verdict(rows, "v1", "lineao") == "SLOWER", f"a pass 2x slower in every round is flagged:\n{text}")
    check(verdict(rows, "v1", "(frame)") == "SLOWER", f"the frame 1.3x slower in every round is flagged:\n{text}")
    check(verdict(rows, "v1", "gbuffer") == "", f"an unchanged pass is not flagged:\n{text}")
    check(verdict(rows, "v1", "tiny") is None, f"a pass of 0.3 of 100 ms is not listed (2x, but 0.3 ms):\n{text}")
    check("2.00" in rows.get(("v1", "lineao"), ""), f"the ratio of the medians is printed:\n{text}")
    # One round says 1.6x, the others 1.0: noise, not a change; likewise 1.2x (below 1.15) in one.
    noisy = [{"v1": (base, (160.0, {"lineao": 48.0, "gbuffer": 64.0, "tiny": 0.3, "edge": 2.0}))},
             {"v1": (base, base)},
             {"v1": (base, (120.0, {"lineao": 36.0, "gbuffer": 48.0, "tiny": 0.3, "edge": 2.0}))}]
    code, rows, text = table(work, noisy)
    check(all(verdict(rows, "v1", n) == "" for n in ("(frame)", "lineao", "gbuffer")),
          f"what one round alone says is not flagged:\n{text}")
    check("1.00-1.60" in rows.get(("v1", "(frame)"), ""), f"the range over the rounds is printed:\n{text}")
    # Faster in every round; a wall-clock case; --all-passes lists the small pass.
    fast = (60.0, {"lineao": 10.0, "gbuffer": 40.0, "tiny": 0.3, "edge": 2.0})
    code, rows, text = table(work, [{"v1": (base, fast), "loop": (4.0, 3.0)}] * 2, "--all-passes")
    check(verdict(rows, "v1", "lineao") == "faster", f"a pass 3x faster in every round is flagged faster:\n{text}")
    check(verdict(rows, "loop", "(run)") == "faster", f"a case timed as a whole is compared as a whole:\n{text}")
    check(("v1", "tiny") in rows, f"--all-passes lists every pass:\n{text}")
    # A single round flags nothing, however large.
    code, rows, text = table(work, [{"v1": (base, slow_ao)}])
    check(verdict(rows, "v1", "lineao") == "", f"one round flags nothing:\n{text}")
    # 1.3x in every round, but each round's frames overlap (0.5x..1.5x): noise, not flagged.
    code, rows, text = table(work, [{"v1": (base, (*slow_ao, (0.5, 1.0, 1.5)))}] * 3)
    check(verdict(rows, "v1", "(frame)") == "" and verdict(rows, "v1", "lineao") == "",
          f"runs whose frames overlap are not flagged, whatever their medians:\n{text}")
    # A higher threshold: 1.3x is no longer flagged, 2x still is.
    code, rows, text = table(work, [{"v1": (base, slow_ao)}] * 3, "--threshold", "0.5")
    check(verdict(rows, "v1", "(frame)") == "" and verdict(rows, "v1", "lineao") == "SLOWER",
          f"--threshold 0.5 flags 2x, not 1.3x:\n{text}")

    # Bad input: named, exit 2.
    bad = os.path.join(work, "bad.tsv")
    with open(bad, "w") as f:
        f.write("1\tv1\tbase\n")
    p = subprocess.run([TABLE, bad], capture_output=True, text=True)
    check(p.returncode == 2 and f"{bad}:1: expected ROUND, CASE, base|new" in p.stderr,
          f"a short line is named with its file and line: {p.returncode} {p.stderr}")
    empty = os.path.join(work, "empty.json")
    with open(empty, "w") as f:
        json.dump({"runs": []}, f)
    with open(bad, "w") as f:
        f.write(f"1\tv1\tbase\t{empty}\n")
    p = subprocess.run([TABLE, bad], capture_output=True, text=True)
    check(p.returncode == 2 and f"{empty}: no runs" in p.stderr, f"results without runs are named: {p.stderr}")

    for args, message in [
        (["--rounds", "1"], "--rounds '1': expected a whole number >= 2"),
        (["--rounds"], "--rounds needs a value"),
        (["--size", "960"], "--size '960': expected WxH"),
        (["--frames", "0"], "--frames '0': expected a whole number >= 1"),
        (["--threshold", "0"], "--threshold '0': expected a fraction > 0"),
        (["--bogus"], "unknown option '--bogus'"),
        (["no-such-commit-xyz"], "BASE 'no-such-commit-xyz' is not a commit of this repository"),
        (["HEAD", "HEAD~1"], "one BASE only"),
        (["--keep", work], f"--keep '{work}': already there"),
    ]:
        p = subprocess.run([SCRIPT, *args], capture_output=True, text=True, cwd=work)
        check(p.returncode == 2 and f"perf-ab: {message}" in p.stderr,
              f"perf-ab.sh {' '.join(args)}: exit 2 and '{message}' (got {p.returncode}: {p.stderr.strip()})")

if failures:
    print(f"{len(failures)} failed")
    sys.exit(1)
print("ok: the table flags what every round agrees on, nothing else; bad input is named")

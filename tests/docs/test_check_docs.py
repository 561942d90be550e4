#!/usr/bin/python3
"""check_docs.py can fail: on a copy of the source tree whose README.md is broken in one way at
a time (a missing file, a missing heading, a third set-up command, a misspelt command, option
and --set name, too many lines) it exits 1 and names each problem.

  test_check_docs.py ROOT PATHLET
"""
import os
import shutil
import subprocess
import sys
import tempfile

ROOT, PATHLET = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_docs.py")
README = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
failures = []


def tree(work, readme):
    """A copy of ROOT (links to everything but README.md and docs/, which are copied)."""
    if os.path.exists(work):
        shutil.rmtree(work)
    os.makedirs(work)
    for entry in os.listdir(ROOT):
        if entry not in ("README.md", "docs", "build"):
            os.symlink(os.path.join(ROOT, entry), os.path.join(work, entry))
    shutil.copytree(os.path.join(ROOT, "docs"), os.path.join(work, "docs"))
    with open(os.path.join(work, "README.md"), "w", encoding="utf-8") as f:
        f.write(readme)
    return work


def replace(old, new, count=1):
    assert old in README, f"the README no longer holds {old!r}: update this test's mutation"
    return README.replace(old, new, count)


def expect(name, readme, only, messages):
    work = tree(os.path.join(tempfile.gettempdir(), f"pathlet_check_docs_{os.getpid()}"), readme)
    try:
        r = subprocess.run([sys.executable, CHECK, work, PATHLET, "--only", only], capture_output=True, text=True)
    finally:
        shutil.rmtree(work)
    out = r.stdout + r.stderr
    if r.returncode != 1:
        failures.append(f"{name}: exit {r.returncode}, expected 1\n{out}")
    for m in messages:
        if m not in out:
            failures.append(f"{name}: no '{m}' in\n{out}")
    print(f"{name}: exit {r.returncode}")


expect("a link to a missing file", replace("](docs/performance.md)", "](docs/performanse.md)"), "links",
       ["docs/performanse.md does not exist"])
expect("a link to a missing heading", replace("#reading-gpu-numbers)", "#reading-gpu-number)"), "links",
       ["no heading '#reading-gpu-number' in docs/performance.md"])
expect("a third set-up command", replace("```sh\nscripts/test.sh\n```", "```sh\nscripts/test.sh\n```\n\n```sh\nscripts/install-deps.sh\n```"),
       "setup", ["expected exactly ['scripts/main.sh', 'scripts/test.sh']"])
expect("two commands in one set-up block", replace("```sh\nscripts/main.sh\n```", "```sh\nscripts/main.sh\nscripts/build.sh\n```"),
       "setup", ["a set-up block holds one command, this one 2"])
broken = README.replace("render variant2_oit --time 9 --size 1920x1080", "render variant2_oit --time 9 --sise 1920x1080", 1)
broken = broken.replace("--set overlay=false", "--set overlai=false", 1)
broken = broken.replace("build/bin/pathlet graph variant1_lineao --plan", "build/bin/pathlet grahp variant1_lineao --plan", 1)
broken = broken.replace("build/bin/pathlet view isl --time 9", "build/bin/pathlet view isl_v2 --time 9", 1)
assert broken.count("--sise") == 1 and "overlai" in broken and "grahp" in broken and "isl_v2" in broken
expect("a misspelt option, --set name, command and graph", broken, "commands",
       ["'pathlet render --sise': no such option", "overlai", "'pathlet grahp': no such command",
        "'pathlet view isl_v2': no shipped graph"])
expect("too many lines", README + "more\n" * 451, "length", ["more than 450"])

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)

#!/usr/bin/python3
"""check_docs.py can fail: on a copy of the source tree whose README.md is broken in one way at
a time (a missing file, a missing heading, a third set-up command, a misspelt command, option
and --set name, too many lines) it exits 1 and names each problem.

  test_check_docs.py ROOT PATHLET
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT, PATHLET = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_docs.py")
README = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
failures = []


def tree(work, readme, docs=None):
    """A copy of ROOT (links to everything but README.md and docs/, which are copied); `docs`:
    {name: text} replaces files of docs/."""
    if os.path.exists(work):
        shutil.rmtree(work)
    os.makedirs(work)
    for entry in os.listdir(ROOT):
        if entry not in ("README.md", "docs", "build"):
            os.symlink(os.path.join(ROOT, entry), os.path.join(work, entry))
    shutil.copytree(os.path.join(ROOT, "docs"), os.path.join(work, "docs"))
    with open(os.path.join(work, "README.md"), "w", encoding="utf-8") as f:
        f.write(readme)
    for name, text in (docs or {}).items():
        with open(os.path.join(work, "docs", name), "w", encoding="utf-8") as f:
            f.write(text)
    return work


def mutate(pattern, new, what, text=README):
    """`text` with the first match of `pattern` (a regex) replaced by `new` (a template)."""
    mutated, n = re.subn(pattern, new, text, count=1, flags=re.M)
    assert n == 1, f"the README has no {what} to break (pattern {pattern!r}): update this test"
    return mutated


def expect(name, readme, only, messages, docs=None):
    work = tree(os.path.join(tempfile.gettempdir(), f"pathlet_check_docs_{os.getpid()}"), readme, docs)
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


expect("a link to a missing file", mutate(r"\]\((docs/\w+)\.md\)", r"](\1_gone.md)", "link to docs/*.md"), "links",
       ["_gone.md does not exist"])
expect("a link to a missing heading", mutate(r"\]\(([\w/.-]+\.md)#([\w-]+)\)", r"](\1#\2-gone)", "link with an anchor"),
       "links", ["-gone' in "])
expect("a third set-up command", mutate(r"^```sh\nscripts/test.sh\n```$", "```sh\nscripts/test.sh\n```\n\n```sh\nscripts/install-deps.sh\n```",
                                        "set-up block"), "setup", ["expected exactly ['scripts/main.sh', 'scripts/test.sh']"])
expect("two commands in one set-up block", mutate(r"^```sh\nscripts/main.sh\n```$", "```sh\nscripts/main.sh\nscripts/build.sh\n```",
                                                  "set-up block"), "setup", ["a set-up block holds one command, this one 2"])
# The command checks run pathlet, so the command mutations go into one copy, each on its own line.
broken = mutate(r"^build/bin/pathlet ", "build/bin/pathlett ", "pathlet command line")
broken = mutate(r"^(build/bin/pathlet render .*)--size ", r"\1--sise ", "render line with --size", broken)
broken = mutate(r"^(build/bin/pathlet render .*--set )(\w+)=", r"\1\2_typo=", "render line with --set", broken)
broken = mutate(r"^build/bin/pathlet graph ", "build/bin/pathlet grahp ", "graph command line", broken)
broken = mutate(r"^(build/bin/pathlet view )(\w+)", r"\1\2_gone", "view line with a graph", broken)
expect("a misspelt pathlet, option, --set name, command and graph", broken, "commands",
       ["did you mean the pathlet command?", "'pathlet render --sise': no such option", "_typo=", "unknown",
        "'pathlet grahp': no such command", "_gone': no shipped graph or file of that name"])
# A misspelt hook file: a shipped one in docs/ and the reader's own in the README (only the
# file the README asks the reader to write, my_fade.glsl, is left unchecked).
OPACITY = open(os.path.join(ROOT, "docs", "opacity-optimization.md"), encoding="utf-8").read()
expect("a misspelt shipped hook and a misspelt reader's hook",
       mutate(r"(--set \S*color_hook=)my_fade\.glsl", r"\1my_fdae.glsl", "--set of my_fade.glsl"), "commands",
       ["hook file 'my_fdae.glsl' not found", "hook file 'importance_naer.glsl' not found"],
       docs={"opacity-optimization.md": mutate(r"(color_hook=)importance_near\.glsl", r"\1importance_naer.glsl",
                                               "--set of a shipped hook file", OPACITY)})
expect("too many lines", README + "more\n" * 451, "length", ["more than 450"])

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)

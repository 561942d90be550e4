#!/usr/bin/python3
"""The README and docs/*.md still work as written.

  check_docs.py ROOT PATHLET [--only links,setup,commands,length]

checks, under the source tree ROOT, with the built command PATHLET:
  1. every relative link in README.md, docs/*.md (and every other Markdown file of the tree)
     points to an existing file, and a '#anchor' to a heading of that file (GitHub's anchor rule);
  2. the README's set-up section holds exactly two fenced sh blocks, one command each:
     scripts/main.sh and scripts/test.sh (both executable), and .ci/run calls the second;
  3. every 'pathlet ...' command line in a fenced sh block of those files names a command that
     exists and only options that 'pathlet COMMAND --help' lists; a graph it names is a shipped
     graph or a file under ROOT, and its '--set NAME=VALUE's are checked by 'pathlet validate'
     against that graph;
  4. README.md has at most 450 lines.
Prints every problem as FILE:LINE: message and exits 1 when there is one.
"""
import os
import re
import shlex
import subprocess
import sys
import unicodedata

MAX_README_LINES = 450
SETUP_HEADING = "Set up"
SETUP_COMMANDS = ["scripts/main.sh", "scripts/test.sh"]
# Commands whose first positional argument is a graph (bench: a comma-separated list).
GRAPH_COMMANDS = {"render", "view", "quality", "graph", "bench"}
# A --set value that names a hook or shader file is checked with the graph: the file must be
# shipped (on the shader path), so a misspelt hook name is an error. Only the files the docs ask
# the reader to write are left out (their --set is not validated): this list, nothing else.
FILE_VALUE = re.compile(r"\.(glsl|frag|vert|geom|comp)$")
READER_FILES = {"my_fade.glsl"}

problems = []


def problem(path, line, message):
    problems.append(f"{path}:{line}: {message}")


def read_lines(path):
    with open(path, encoding="utf-8") as f:
        return f.read().split("\n")


def fenced_blocks(lines):
    """(info string, first line number (1-based) of the body, body lines) of each fenced block."""
    blocks, i = [], 0
    while i < len(lines):
        m = re.match(r"^(\s*)(```+|~~~+)\s*([\w+-]*)", lines[i])
        if not m:
            i += 1
            continue
        fence, info, start = m.group(2), m.group(3), i + 1
        j = start
        while j < len(lines) and not lines[j].strip().startswith(fence):
            j += 1
        blocks.append((info, start + 1, lines[start:j]))
        i = j + 1
    return blocks


def prose_lines(lines, keep_code=False):
    """(line number, text) of lines outside fenced blocks, inline code spans removed."""
    out, fence = [], None
    for n, line in enumerate(lines, 1):
        m = re.match(r"^\s*(```+|~~~+)", line)
        if fence:
            if m and line.strip().startswith(fence):
                fence = None
            continue
        if m:
            fence = m.group(1)
            continue
        out.append((n, line if keep_code else re.sub(r"(`+)(?:(?!\1).)+\1", "", line)))
    return out


def slug(heading):
    """GitHub's anchor for a heading: markup dropped, lower case, punctuation removed, spaces to '-'."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links keep their text
    text = text.replace("`", "").replace("*", "").strip().lower()
    text = "".join(c for c in text if c in " -_" or unicodedata.category(c)[0] in "LN")
    return text.replace(" ", "-")


def anchors(path, cache={}):
    """The anchors of a Markdown file's headings (a repeated heading gets -1, -2, ...)."""
    if path not in cache:
        seen, result = {}, set()
        for _, line in prose_lines(read_lines(path), keep_code=True):
            h = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
            if h:
                base = slug(h.group(1))
                k = seen.get(base, 0)
                seen[base] = k + 1
                result.add(base if k == 0 else f"{base}-{k}")
        cache[path] = result
    return cache[path]


LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def check_links(root, rel):
    path = os.path.join(root, rel)
    for n, text in prose_lines(read_lines(path)):
        for target in LINK.findall(text):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
                continue
            file_part, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            if not os.path.exists(dest):
                problem(rel, n, f"link '{target}': {os.path.relpath(dest, root)} does not exist")
                continue
            if anchor and dest.endswith(".md") and anchor not in anchors(dest):
                problem(rel, n, f"link '{target}': no heading '#{anchor}' in {os.path.relpath(dest, root)}")


def check_setup(root):
    rel = "README.md"
    lines = read_lines(os.path.join(root, rel))
    start = next((i for i, l in enumerate(lines) if re.match(r"^##\s", l) and SETUP_HEADING in l), None)
    if start is None:
        problem(rel, 1, f"no '## ...{SETUP_HEADING}...' heading")
        return
    end = next((i for i in range(start + 1, len(lines)) if re.match(r"^#{1,2}\s", lines[i])), len(lines))
    commands = []
    for info, first, body in fenced_blocks(lines[start + 1:end]):
        line_no = start + first
        if info not in ("sh", "bash", "console", "shell"):
            continue
        cmds = [l.strip() for l in body if l.strip() and not l.strip().startswith("#")]
        if len(cmds) != 1:
            problem(rel, line_no, f"a set-up block holds one command, this one {len(cmds)}: {cmds}")
        commands += cmds
    if commands != SETUP_COMMANDS:
        problem(rel, start + 1, f"the set-up section's commands are {commands}, expected exactly {SETUP_COMMANDS}")
    for c in SETUP_COMMANDS:
        if not os.access(os.path.join(root, c), os.X_OK):
            problem(rel, start + 1, f"{c} is not an executable file")
    ci = os.path.join(root, ".ci", "run")
    if not os.path.exists(ci) or not any(l.strip() == SETUP_COMMANDS[1] for l in read_lines(ci)):
        problem(".ci/run", 1, f"CI does not call {SETUP_COMMANDS[1]}")


class Cli:
    def __init__(self, exe, root):
        self.exe, self.root, self.helps = exe, root, {}
        out = self.run(["--help"])
        self.commands = set(re.findall(r"^  ([a-z]+)\s{2,}", out.split("commands:", 1)[-1], re.M))
        if not self.commands:
            sys.exit(f"check_docs: '{exe} --help' lists no commands")

    def run(self, args):
        r = subprocess.run([self.exe] + args, capture_output=True, text=True, timeout=60, cwd=self.root)
        return r.stdout + r.stderr

    def options(self, command):
        """{option: takes a value} from 'pathlet COMMAND --help'."""
        if command not in self.helps:
            opts = {}
            for line in self.run([command, "--help"]).split("\n"):
                m = re.match(r"^  (-\w, )?(--[\w-]+)( \S+)?", line)
                if m:
                    opts[m.group(2)] = bool(m.group(3))
                    if m.group(1):
                        opts[m.group(1)[:2]] = bool(m.group(3))
            opts["--help"] = False
            self.helps[command] = opts
        return self.helps[command]

    def graph_file(self, name):
        """The file a graph argument names, or None."""
        for candidate in (os.path.join(self.root, name), os.path.join(self.root, "graphs", name),
                          os.path.join(self.root, "graphs", name + ".json")):
            if os.path.isfile(candidate):
                return candidate
        return None

    def validate(self, graph, sets):
        args = ["validate", graph]
        for s in sets:
            args += ["--set", s]
        r = subprocess.run([self.exe] + args, capture_output=True, text=True, timeout=60, cwd=self.root)
        return r.returncode, (r.stdout + r.stderr).strip()


def command_lines(body, first):
    """(line number, text) of each command in a fenced sh block: continuations joined, comments cut."""
    out, pending, at = [], "", None
    for k, line in enumerate(body):
        if at is None:
            at = first + k
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        text = pending + line
        pending = ""
        try:
            tokens = shlex.split(text, comments=True)
        except ValueError as e:
            out.append((at, None, f"cannot split '{text.strip()}': {e}"))
            at = None
            continue
        if tokens:
            out.append((at, tokens, None))
        at = None
    return out


def check_command(cli, rel, n, tokens):
    i = 0
    while i < len(tokens) and re.match(r"^[A-Z_][A-Z0-9_]*=", tokens[i]):  # VAR=value prefixes
        i += 1
    if i < len(tokens) and tokens[i] == "xvfb-run":
        i += 1
        while i < len(tokens) and tokens[i].startswith("-"):
            i += 1
    if i >= len(tokens):
        return False
    if os.path.basename(tokens[i]) != "pathlet":
        if re.match(r"^pathlet[\w.-]", os.path.basename(tokens[i])):  # a misspelt command, not a script
            problem(rel, n, f"'{tokens[i]}': did you mean the pathlet command?")
        return False
    args = tokens[i + 1:]
    if not args or args[0].startswith("-"):
        for a in args:
            if a not in ("--help", "--version"):
                problem(rel, n, f"'pathlet {a}': not an option of pathlet itself")
        return True
    command, args = args[0], args[1:]
    if command not in cli.commands:
        problem(rel, n, f"'pathlet {command}': no such command (pathlet --help lists {sorted(cli.commands)})")
        return True
    opts = cli.options(command)
    positionals, sets, k = [], [], 0
    while k < len(args):
        a = args[k]
        if a.startswith("-") and a != "-":
            name, eq, value = a.partition("=")
            if name not in opts:
                problem(rel, n, f"'pathlet {command} {name}': no such option ('pathlet {command} --help')")
                k += 1
                continue
            if opts[name] and not eq:
                k += 1
                value = args[k] if k < len(args) else None
                if value is None:
                    problem(rel, n, f"'pathlet {command} {name}' needs a value")
            if name == "--set" and value is not None:
                sets.append(value)
        else:
            positionals.append(a)
        k += 1
    if command in GRAPH_COMMANDS and positionals and not positionals[0].isupper():
        graphs = positionals[0].split(",") if command == "bench" else [positionals[0]]
        for index, g in enumerate(graphs, 1):
            path = cli.graph_file(g)
            if not path:
                problem(rel, n, f"'pathlet {command} {g}': no shipped graph or file of that name")
                continue
            mine = []
            for s in sets:
                target, colon, rest = s.partition(":")
                if colon and "=" not in target:  # bench's GRAPH:NAME=VALUE
                    if target not in (str(index), g):
                        continue
                    s = rest
                mine.append(s)
            if mine:
                code, out = validate_with_hooks(cli, path, mine)
                if code != 0:
                    problem(rel, n, f"'pathlet {command} {g} --set {' --set '.join(mine)}': {out}")
    elif command in GRAPH_COMMANDS and sets and command != "bench" and not positionals:
        default = cli.graph_file("variant1_lineao")
        mine = list(sets)
        if mine:
            code, out = validate_with_hooks(cli, default, mine)
            if code != 0:
                problem(rel, n, f"'pathlet {command} --set {' --set '.join(mine)}' (variant1_lineao): {out}")
    return True


def reader_file(s):
    """Whether the --set value `s` names a file the docs ask the reader to write (READER_FILES)."""
    value = s.partition("=")[2].strip("'\"")
    return bool(FILE_VALUE.search(value)) and os.path.basename(value) in READER_FILES


def validate_with_hooks(cli, graph, sets):
    """Validates `sets` on `graph`, hook files included (the engine finds shipped ones on the
    shader path; one it does not find is an error), except the files of READER_FILES."""
    return cli.validate(graph, [s for s in sets if not reader_file(s)])


def check_commands(cli, rel):
    lines = read_lines(os.path.join(cli.root, rel))
    count = 0
    for info, first, body in fenced_blocks(lines):
        if info not in ("sh", "bash", "shell", "console"):
            continue
        for n, tokens, error in command_lines(body, first):
            if error:
                problem(rel, n, error)
            elif check_command(cli, rel, n, tokens):
                count += 1
    return count


def other_markdown(root, known):
    """Every other Markdown file of the source tree (pass, plugin and script READMEs, ...)."""
    found = []
    for d, dirs, names in os.walk(root, followlinks=True):
        dirs[:] = sorted(x for x in dirs if not x.startswith((".", "build")))
        rel = os.path.relpath(d, root)
        found += [os.path.normpath(os.path.join(rel, n)) for n in sorted(names) if n.endswith(".md")]
    return [f for f in found if f not in known]


def main():
    argv = sys.argv[1:]
    only = {"links", "setup", "commands", "length"}
    if len(argv) == 4 and argv[2] == "--only":
        only = set(argv[3].split(","))
        argv = argv[:2]
    if len(argv) != 2:
        sys.exit(__doc__)
    root, exe = os.path.abspath(argv[0]), os.path.abspath(argv[1])
    docs = sorted("docs/" + f for f in os.listdir(os.path.join(root, "docs")) if f.endswith(".md"))
    files = ["README.md"] + docs
    if "links" in only:
        for rel in files + other_markdown(root, files):
            check_links(root, rel)
    if "setup" in only:
        check_setup(root)
    commands = 0
    if "commands" in only:
        cli = Cli(exe, root)
        commands = sum(check_commands(cli, rel) for rel in files)
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        readme_lines = len(f.read().splitlines())
    if "length" in only and readme_lines > MAX_README_LINES:
        problem("README.md", readme_lines, f"{readme_lines} lines, more than {MAX_README_LINES}: move detail to docs/")
    for p in problems:
        print(p)
    print(f"check_docs: {len(files)} guides, {commands} pathlet command lines, README {readme_lines} lines: "
          + (f"{len(problems)} problem(s)" if problems else "ok"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

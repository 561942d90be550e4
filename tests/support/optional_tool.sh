#!/usr/bin/env bash
# The one decision of every test that needs an optional tool (ffmpeg, ffprobe, Xvfb, Slurm,
# jupyter-nbconvert): outside CI a missing tool skips the test with a message; in CI (the
# environment variable CI set, and not "false" or "0") it fails it, because CI installs every
# tool (scripts/install-deps.sh with CI set) and a test must never pass there by skipping.
#   optional_tool.sh TOOL...       exit 0 when every TOOL is on PATH
#   optional_tool.sh --missing WHY the decision alone, for a test that found the reason itself
# Missing: one line on stdout, then exit 77 (skip: ctest's SKIP_RETURN_CODE) or 1 (fail).
# gtest: optional_tool.hpp (PATHLET_REQUIRE_TOOLS); pytest: optional_tool.py (require_tools).
set -uo pipefail
why=""
if [ "${1:-}" = "--missing" ]; then
  why=${2:?optional_tool.sh --missing WHY}
else
  [ $# -gt 0 ] || { echo "usage: optional_tool.sh TOOL... | --missing WHY" >&2; exit 2; }
  for tool in "$@"; do
    command -v "$tool" >/dev/null 2>&1 || why="${why:+$why; }$tool is not on PATH"
  done
  [ -n "$why" ] || exit 0
  why="$why (scripts/install-deps.sh installs it)"
fi
case "${CI:-}" in
  ""|false|0) echo "SKIP: $why"; exit 77 ;;
  *) echo "FAIL: $why, and CI=$CI: in CI every optional tool is installed, so this test fails instead of skipping"; exit 1 ;;
esac

"""pytest's side of tests/support/optional_tool.sh, the one decision for a test that needs an
optional tool: require_tools("jupyter-nbconvert") skips the test (outside CI) or fails it (CI
set) with the script's message when one is not on PATH."""
import os
import subprocess

import pytest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "optional_tool.sh")


def require_tools(*tools):
    r = subprocess.run(["bash", SCRIPT, *tools], capture_output=True, text=True)
    message = (r.stdout + r.stderr).strip()
    if r.returncode == 77:
        pytest.skip(message)
    if r.returncode != 0:
        pytest.fail(message, pytrace=False)

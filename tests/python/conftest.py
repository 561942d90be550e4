# pytest fixtures for `import pathlet`: the build tree's package and command, the small phantom.
# ctest runs these (tests/python/CMakeLists.txt); by hand:
#   PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python
import atexit
import os
import shutil
import subprocess
import sys
import tempfile

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("PATHLET_BUILD_DIR", os.path.join(ROOT, "build"))
if not any(os.path.isdir(os.path.join(p, "pathlet")) for p in sys.path if p):
    sys.path.insert(0, os.path.join(BUILD, "python"))
os.environ.setdefault("LIBGL_ALWAYS_SOFTWARE", "1")
# Every render() builds its executor and compiles its shaders anew; on llvmpipe that is most of a
# small render (34 s for this suite without a cache, 6 s with one). A shader cache of this run
# only (a fresh folder: no stale entries from another build), shared with the commands it runs.
os.environ["MESA_SHADER_CACHE_DISABLE"] = "false"
os.environ["MESA_SHADER_CACHE_DIR"] = tempfile.mkdtemp(prefix="pathlet_pytest_mesa_")
atexit.register(shutil.rmtree, os.environ["MESA_SHADER_CACHE_DIR"], True)


@pytest.fixture(scope="session")
def pathlet():
    import pathlet as p
    return p


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("PATHLET_CLI", os.path.join(BUILD, "bin", "pathlet"))
    assert os.access(path, os.X_OK), f"no pathlet command at {path}"

    def run(*args, check=True):
        r = subprocess.run([path, *args], capture_output=True, text=True)
        if check:
            assert r.returncode == 0, f"pathlet {' '.join(args)}: exit {r.returncode}\n{r.stderr}"
        return r
    return run


@pytest.fixture(scope="session")
def scene(pathlet):
    return pathlet.phantom("small")  # 316 lines over 4 s: every test in seconds


@pytest.fixture(scope="session")
def root():
    return ROOT


def read_png(path):
    import numpy as np
    from PIL import Image
    return np.asarray(Image.open(path).convert("RGBA"))

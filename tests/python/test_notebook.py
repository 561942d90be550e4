# examples/compare_fades.ipynb executed end to end (jupyter nbconvert --execute) at a small size,
# so the example cannot rot: every cell runs, draws its figures and gives numbers.
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from optional_tool import require_tools  # noqa: E402  (tests/support: skip, or fail in CI)


def test_compare_fades_notebook_runs(root, tmp_path):
    require_tools("jupyter-nbconvert")
    nbconvert = shutil.which("jupyter-nbconvert")
    env = dict(os.environ, PATHLET_EXAMPLE_SIZE="160x90", PATHLET_EXAMPLE_PHANTOM="small",
               PATHLET_EXAMPLE_FRAMES="2", PATHLET_EXAMPLE_RAYS="16", MPLBACKEND="module://matplotlib_inline.backend_inline")
    r = subprocess.run([nbconvert, "--to", "notebook", "--execute", "--ExecutePreprocessor.timeout=300",
                        "--ExecutePreprocessor.kernel_name=python3", "--output-dir", str(tmp_path),
                        os.path.join(root, "examples", "compare_fades.ipynb")],
                       capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-3000:]
    nb = json.loads((tmp_path / "compare_fades.ipynb").read_text())
    code = [c for c in nb["cells"] if c["cell_type"] == "code"]
    outputs = [o for c in code for o in c.get("outputs", [])]
    assert not [o for o in outputs if o["output_type"] == "error"]
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(images) >= 6, "variants, AO map, passes, two sweeps, quality"
    text = "".join("".join(o.get("data", {}).get("text/plain", "")) + "".join(o.get("text", "")) for o in outputs)
    assert "316 lines" in text and "AO over covered pixels: mean 0." in text
    assert "'samples': 32" in text and "'mae': 0." in text, "the quality table"

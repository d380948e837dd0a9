# examples/lecture.ipynb runs from top to bottom as `jupyter nbconvert --execute` runs it
# (headless, small images), so that it never rots; and it is committed without outputs.
import json
import os
import shutil
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

NOTEBOOK = SOURCE_DIR / "examples" / "lecture.ipynb"


def test_notebook_is_committed_without_outputs():
    nb = json.loads(NOTEBOOK.read_text())
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            assert cell["outputs"] == [] and cell["execution_count"] is None


def test_notebook_runs_with_jupyter_nbconvert(tmp_path):
    """As a user runs it: `jupyter nbconvert --to notebook --execute`, Debian's python3 kernel,
    nothing patched; the sliders' cell draws its picture once (no front end answers them)."""
    if shutil.which("jupyter-nbconvert") is None:
        pytest.skip("jupyter-nbconvert is not installed (scripts/setup.sh installs it)")
    pytest.importorskip("ipykernel")
    env = dict(os.environ, LUZ_NOTEBOOK_SMALL="1",
               PYTHONPATH=os.pathsep.join(p for p in sys.path if p),
               JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"))
    out = tmp_path / "lecture.ipynb"
    r = subprocess.run(["jupyter", "nbconvert", "--to", "notebook", "--execute",
                        "--ExecutePreprocessor.timeout=300", str(NOTEBOOK),
                        "--output-dir", str(tmp_path), "--output", out.name],
                       cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    nb = json.loads(out.read_text())
    code = [c for c in nb["cells"] if c["cell_type"] == "code"]
    errors = [o for c in code for o in c["outputs"] if o.get("output_type") == "error"]
    assert not errors
    images = [o for c in code for o in c["outputs"] if "image/png" in o.get("data", {})]
    assert len(images) >= 10  # the figures, and the Frame shown as itself
    # the sliders' cell: its picture at the defaults
    assert any("image/png" in o.get("data", {}) for o in code[-1]["outputs"]), code[-1]

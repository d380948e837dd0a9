# examples/lecture.ipynb runs from top to bottom (executed with nbclient, headless, small images),
# so that it never rots; and it is committed without outputs.
import json
import os
import sys

import pytest

from conftest import SOURCE_DIR

NOTEBOOK = SOURCE_DIR / "examples" / "lecture.ipynb"


def test_notebook_is_committed_without_outputs():
    nb = json.loads(NOTEBOOK.read_text())
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            assert cell["outputs"] == [] and cell["execution_count"] is None


def test_notebook_runs(tmp_path, monkeypatch):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    nb = nbformat.read(str(NOTEBOOK), as_version=4)
    # The kernel: this very interpreter (Debian's python3), finding the module as we do.
    monkeypatch.setenv("LUZ_NOTEBOOK_SMALL", "1")
    monkeypatch.setenv("MPLBACKEND", "module://matplotlib_inline.backend_inline")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(p for p in sys.path if p))
    kernel_dir = tmp_path / "kernels" / "luz-test"
    kernel_dir.mkdir(parents=True)
    (kernel_dir / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "luz test", "language": "python"}))
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path))
    monkeypatch.setenv("JUPYTER_RUNTIME_DIR", str(tmp_path / "runtime"))
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="luz-test",
                                     resources={"metadata": {"path": str(tmp_path)}})
    # nbclient 0.7 mimics the front end of ipywidgets 7+ (it reads a `state` that Debian 12's
    # ipywidgets 6 does not send): without a front end, the sliders' cell just runs once.
    client.comm_open_handlers.pop("jupyter.widget", None)
    client.execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs
              if o.get("output_type") == "error"]
    assert not errors
    images = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs
              if "image/png" in o.get("data", {})]
    assert len(images) >= 10  # the figures, and the Frame shown as itself

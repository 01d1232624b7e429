"""Run every classroom notebook from its jupytext source on a fresh kernel.

Each ``notebooks/NN_*.py`` (jupytext percent format) is read with jupytext and
executed top to bottom with nbclient on a new ``python3`` kernel of the
interpreter running the tests, in a temporary working directory, so that a
notebook writes nothing into the repository. A cell that raises -- including
the notebooks' own ``assert`` cells, which check numkin's numbers against the
source documents and closed forms -- fails the test.

The per-cell timeout only guards against a hung kernel; it is not a speed
test (each notebook takes well under a minute on 2 cores).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import pytest

NOTEBOOK_DIR = Path(__file__).resolve().parents[1] / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("[0-9][0-9]_*.py"))
#: Seconds a single cell may run before the kernel is considered hung.
CELL_TIMEOUT = 600
INLINE_BACKEND = "module://matplotlib_inline.backend_inline"


def test_the_six_lessons_are_there():
    assert len(NOTEBOOKS) >= 6, f"expected the six lesson notebooks in {NOTEBOOK_DIR}, found {NOTEBOOKS}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_source_is_a_lesson(path):
    """Cheap structural checks on the source (no kernel): percent format, questions, checks."""
    jupytext = pytest.importorskip("jupytext")
    nb = jupytext.read(path)
    assert nb.metadata.get("kernelspec", {}).get("name") == "python3", f"{path.name}: kernelspec must be python3"
    markdown = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    assert markdown.lstrip().startswith("# Lesson"), f"{path.name}: the first cell must be the lesson title"
    assert "## Questions" in markdown, f"{path.name}: no '## Questions' section for the student"
    assert "$" in markdown, f"{path.name}: state the problem with its equations (LaTeX)"
    assert "assert " in code, f"{path.name}: check at least one number with an assert cell"


@pytest.fixture(scope="module")
def kernel_path(tmp_path_factory):
    """A JUPYTER_PATH whose ``python3`` kernel is the interpreter running the tests."""
    root = tmp_path_factory.mktemp("jupyter")
    spec_dir = root / "kernels" / "python3"
    spec_dir.mkdir(parents=True)
    spec = {
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "Python 3",
        "language": "python",
    }
    (spec_dir / "kernel.json").write_text(json.dumps(spec))
    return root


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_executes(path, tmp_path, monkeypatch, kernel_path, record_property):
    jupytext = pytest.importorskip("jupytext")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")

    monkeypatch.setenv("JUPYTER_PATH", str(kernel_path))
    monkeypatch.setenv("MPLBACKEND", INLINE_BACKEND)  # closes each cell's figures
    before = sorted(p.name for p in NOTEBOOK_DIR.iterdir())

    nb = jupytext.read(path)
    client = nbclient.NotebookClient(
        nb,
        timeout=CELL_TIMEOUT,
        kernel_name="python3",
        allow_errors=False,
        resources={"metadata": {"path": str(tmp_path)}},
    )
    start = time.perf_counter()
    client.execute()  # raises CellExecutionError, naming the cell, on any error
    seconds = time.perf_counter() - start
    record_property("seconds", round(seconds, 2))
    print(f"{path.name}: executed in {seconds:.1f} s")

    errors = [
        out
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
        if out.get("output_type") == "error"
    ]
    assert not errors
    assert sorted(p.name for p in NOTEBOOK_DIR.iterdir()) == before, "a notebook wrote into notebooks/"

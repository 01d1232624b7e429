"""The API reference reaches every public module, also one a function of the same name hides.

``numkin.newton`` is a function and a module; autosummary reaches the function by that name, so
the documentation's extension writes the module a page of its own (its docstring, its classes and
functions, its data) and lists it on its package's page.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[1] / "docs"


@pytest.fixture(scope="module")
def api():
    pytest.importorskip("sphinx")  # (the documentation's tools: pip install -e ".[docs]")
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import numkin_docs
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    return numkin_docs, numkin_docs.ApiIndex("numkin")


def test_modules_a_function_hides_get_pages_of_their_own(api, tmp_path):
    numkin_docs, index = api
    written = numkin_docs.write_shadowed_pages(tmp_path, index)
    assert {"numkin.newton", "numkin.figures.style", "numkin.linkages.four_bar"} <= set(written)
    assert index.shadowed_below("numkin") == ["numkin.newton"]
    page = (tmp_path / "numkin.newton-module.rst").read_text()
    assert page.startswith("numkin.newton (module)\n======================\n")
    assert ".. automodule:: numkin.newton\n   :no-members:\n   :no-index:" in page
    own = page.split(".. rubric:: Classes and functions")[1].split(".. rubric::")[0]
    for name in ("solve_batch", "dense_solver", "iterate", "BatchResult"):  # defined there, documented nowhere else
        assert f"\n   {name}\n" in own
    assert "~numkin.newton_rules.has_converged" in page  # re-exported: a link to its own page
    assert ".. autodata:: COMPACT_MIN" in page and ".. autodata:: JACOBIANS" not in page  # (JACOBIANS: newton_rules')
    assert "The function of the same name is :func:`numkin.newton`." in page
    spec = (tmp_path / "numkin.linkages.four_bar-module.rst").read_text()
    assert ".. autodata:: SPEC" in spec

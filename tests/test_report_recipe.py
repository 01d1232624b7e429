"""The "add a table" recipe of README: one new module in numkin/report, nothing else edited.

The test puts the module in a folder of its own, added to the package's search path,
so the package itself is left as it was.
"""

from __future__ import annotations

import math
import sys
import textwrap

import pytest

import numkin.report as report
from numkin import linkages

MODULE = '''
"""The crank-rocker's rocker angle at a few inputs: a table family in one module."""

import numpy as np
import pandas as pd

from numkin.report.captions import set_caption

__all__ = ["rocker_table"]


def rocker_table(mechanism, *, quantity="theta4", inputs_deg=(0.0, 90.0, 180.0)):
    """Positions of one unknown at a few inputs (deg in the table)."""
    sweep = mechanism.sweep(np.radians(np.asarray(inputs_deg)))
    table = pd.DataFrame({"theta2 [deg]": list(inputs_deg), f"{quantity} [deg]": np.degrees(sweep[quantity])})
    return set_caption(table, f"{quantity} at a few inputs")
'''


@pytest.fixture
def extra_report_module(tmp_path, monkeypatch):
    folder = tmp_path / "tables"
    folder.mkdir()
    (folder / "rocker.py").write_text(textwrap.dedent(MODULE))
    monkeypatch.setattr(report, "__path__", [*report.__path__, str(folder)])
    yield
    sys.modules.pop("numkin.report.rocker", None)


def test_a_table_added_as_one_module_is_found_and_written(extra_report_module, tmp_path):
    table = report.rocker_table(linkages.four_bar(4, 1, 3, 3))
    # the rocker angle of the 4/1/3/3 crank-rocker in closed form: at theta2 = 0 the
    # triangle O4-A-B has sides 3, 3, 3, so the rocker stands at 120 deg
    assert table["theta4 [deg]"].iloc[0] == pytest.approx(120.0, abs=1e-9)
    # at 180 deg: A = (-1, 0), |A O4| = 5, law of cosines for the angle at O4
    beta = math.degrees(math.acos((3**2 + 5**2 - 3**2) / (2 * 3 * 5)))
    assert table["theta4 [deg]"].iloc[2] == pytest.approx(180.0 - beta, abs=1e-9)
    written = report.write_tables({"rocker": table}, tmp_path / "out")
    assert sorted(p.name for p in written) == ["rocker.csv", "rocker.md", "rocker.tex"]
    assert "theta4 at a few inputs" in (tmp_path / "out" / "rocker.md").read_text()


def test_an_unknown_table_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="nonexistent_table"):
        report.nonexistent_table  # noqa: B018

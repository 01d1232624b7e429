"""What README.md says numkin prints is what numkin prints.

* The "Error analysis" section says that every number in it is printed by
  ``numkin report homework``. Each number of the section is read from the
  README and found in the report's text, as ``numkin report`` prints it (the
  same ``scene_report`` and ``format_text``): exactly as written, or, for the
  numbers rounding decides (optimal steps and the errors at and below them,
  which vary in their last digits between machines), within the same order
  of magnitude as the table cell the sentence names. Numbers that are
  settings of the report (grids, steps, angles, tolerances) are listed here
  with what they are; any other number added to the section must be printed.
* The change-point warning quoted in README.md is the one a sweep prints.
* The linear-convergence example of the Newton section converges after the
  40 halving steps of Newton's method on x**2 (x = 2**-40, derived by hand).
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

README = (Path(__file__).resolve().parents[1] / "README.md").read_text(encoding="utf-8")
NUMBER = r"[−-]?[0-9]+(?:\.[0-9]+)?(?:e[+−-]?[0-9]+)?"


def section(start: str, end: str) -> str:
    return README[README.index(start) : README.index(end)]


ERROR_ANALYSIS = section("## Error analysis", "Every number above is printed by `numkin report homework`")

#: Numbers of the section that are settings of the report, not its results.
SETTINGS = {
    "100": "the check angle, deg",
    "450": "the input speed, rad/min",
    "36": "the coarsest grid, points per turn",
    "3600": "the finest grid",
    "360": "a grid",
    "720": "a grid",
    "3": "repeat=3 in a call",
    "1e-1": "the largest step of the round-off scan",
    "1e-12": "the smallest step of the round-off scan",
    "8": "steps per decade of the scan",
    "6": "the 6 of the complex step's truncation term h²|β‴/(6β′)|",
    "1e-9": "a step of the scan",
    "1e-8": "a step of the scan",
    "1e-7": "a step of the scan",
    "1e-6": "a step of the scan",
    "0.1": "a step of the scan",
    "80": "the angle Newton starts from, deg",
    "1e-4": "the loose tolerances",
    "1": "the 1° grid",
    "001": "a source document's number",
    "003": "a source document's number",
    "−28.36941": "printed by homework 003 (its table of results), quoted beside numkin's −28.36942",
}

#: Numbers rounding decides: (context with the number as a group, table, scheme, column) -> same order of magnitude.
ROUNDING = [
    (r"second difference is best at\s+h ≈ (\S+) rad", "second_difference", "measured optimal h [rad]"),
    (r"\((\S+) on the fitted curve", "second_difference", "rel error at measured optimal h [-]"),
    (r"(\S+) measured at that\s+step", "second_difference", "rel error measured at that h [-]"),
    (r"relative error is (\S+) at h = 1e-8", "second_difference", "rel error at h = 1e-08 rad [-]"),
    (r"(\S+) at h = 1e-9", "second_difference", "rel error at h = 1e-09 rad [-]"),
    (r"Centred is best at (\S+) \(", "centred", "measured optimal h [rad]"),
    (r"Centred is best at \S+ \((\S+)\)", "centred", "rel error at measured optimal h [-]"),
    (r"five-point\s+at (\S+) \(", "five_point", "measured optimal h [rad]"),
    (r"five-point\s+at \S+ \((\S+)\)", "five_point", "rel error at measured optimal h [-]"),
    (r"(\S+) at 1e-6\)", "complex step", "rel error at h = 1e-06 rad [-]"),
    (r"at ~(\S+) only for h ≤ 1e-7", "complex step", "rel error at h = 1e-07 rad [-]"),
]


def as_float(text: str) -> float:
    return float(text.replace("−", "-"))


@pytest.fixture(scope="module")
def report():
    """The tables of ``numkin report homework`` and the text it prints."""
    from numkin.report import format_text, scene_report
    from numkin.scene import load_scene

    tables = scene_report(load_scene("homework"))
    text = "\n".join(f"## {name}\n{format_text(table)}\n" for name, table in tables.items())
    return tables, text


def rounding_numbers():
    """``(number as written, scheme, column)`` of every ROUNDING context, each found once in the section."""
    found = []
    for context, scheme, column in ROUNDING:
        hits = re.findall(context, ERROR_ANALYSIS)
        assert len(hits) == 1, f"README's Error analysis no longer says {context!r} once"
        assert re.fullmatch(NUMBER, hits[0]), f"{context!r} captured {hits[0]!r}, not a number"
        found.append((hits[0], scheme, column))
    return found


def test_rounding_decided_numbers_match_their_cells(report):
    tables, _ = report
    roundoff = tables["roundoff"].set_index("scheme")
    for written, scheme, column in rounding_numbers():
        printed = float(roundoff.loc[scheme, column])
        assert abs(math.log10(as_float(written) / printed)) < 1, (
            f"README says {written} for {scheme}, {column}; numkin report homework prints {printed:.3g}"
        )


def test_every_other_number_is_printed_as_written(report):
    _, text = report
    text = text.replace("−", "-")
    rounding = {written for written, _, _ in rounding_numbers()}
    numbers = re.findall(rf"(?<![\w.]){NUMBER}", ERROR_ANALYSIS)
    assert len(numbers) > 30
    missing = []
    for number in numbers:
        if number in SETTINGS or number in rounding:
            continue
        token = re.escape(number.replace("−", "-"))
        if re.search(rf"(?<![\w.-]){token}(?![\w.])", text) is None:
            missing.append(number)
    assert not missing, f"README's Error analysis quotes numbers numkin report homework does not print: {missing}"


def test_settings_are_settings():
    """Each number excused as a setting is in the section (stale excuses are removed)."""
    numbers = set(re.findall(rf"(?<![\w.]){NUMBER}", ERROR_ANALYSIS))
    assert set(SETTINGS) <= numbers, sorted(set(SETTINGS) - numbers)


def test_the_quoted_change_point_warning_is_the_printed_one():
    from numkin import SingularityWarning, linkages

    quoted = re.search(r'\("(kept the crossed branch \(its tangent\s+is continuous: [^"]*)"', README)
    assert quoted, "README no longer quotes the change-point warning"
    quoted = re.sub(r"\s+", " ", quoted.group(1))
    assert 'branch="crossed")` swept from 10° to 350°, at 180°' in re.sub(r"\s+", " ", README)
    mech = linkages.four_bar(5, 2, 5, 2, branch="crossed")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mech.sweep(np.radians(np.arange(10.0, 351.0)), on_singular="report")
    printed = [str(w.message) for w in caught if issubclass(w.category, SingularityWarning)]
    assert any(quoted in message for message in printed), printed


def test_linear_convergence_example():
    """Newton on x**2 from 1 halves x at every step: after 40 steps x = 2**-40 < tol = 1e-12 (and the step too)."""
    import numkin

    assert "converges after 40 halving steps to x = 2⁻⁴⁰ = 9.1e-13" in re.sub(r"\s+", " ", README)
    result = numkin.newton(lambda x: np.array([x[0] ** 2]), [1.0])
    assert result.converged and result.iterations == 40
    assert result.x[0] == pytest.approx(2.0**-40, rel=1e-9) and f"{2.0**-40:.2g}" == "9.1e-13"


def _table_cell(row_start: str, column: int) -> list[float]:
    """The numbers of one cell of README's table of numkin against the source documents."""
    row = next(line for line in README.splitlines() if line.startswith(row_start))
    cell = row.split("|")[column + 1].split(";")[0]
    return [float(v.replace("−", "-")) for v in re.findall(NUMBER, cell)]


def _printed(value: float, like: float) -> float:
    """``value`` rounded to as many decimals as the printed number ``like`` shows."""
    decimals = len(repr(like).split(".")[1]) if "." in repr(like) else 0
    return round(value, decimals)


def test_the_homework_rows_of_the_source_table_are_rounded_from_the_closed_form():
    """ω_β and α_β at θ = 100° (ω = 450 rad/min = 7.5 rad/s, 1° grid): exact, and by the differences the
    homework used, each quotient formed from β of two circle intersections (mpmath), then rounded as printed."""
    from test_report import hw_beta

    h, w = math.radians(1.0), 7.5
    beta = {k: hw_beta(k) for k in (99, 100, 101, 102)}
    rows = {
        "| | ω_β, α_β exact": (w * hw_beta(100, 1), w * w * hw_beta(100, 2)),
        "| | centred / second difference": (
            w * (beta[101] - beta[99]) / (2 * h), w * w * (beta[101] - 2 * beta[100] + beta[99]) / h**2),
        "| | forward / forward-of-forward": (
            w * (beta[101] - beta[100]) / h, w * w * (beta[102] - 2 * beta[101] + beta[100]) / h**2),
    }
    for row, reference in rows.items():
        printed = _table_cell(row, 2)
        assert len(printed) == 2, (row, printed)
        assert [_printed(r, p) for r, p in zip(reference, printed)] == printed, (row, reference)

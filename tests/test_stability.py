"""Tests for numkin.stability: every case ends in its expected outcome, and nothing is silently wrong.

Independent references: the reachable range of the non-Grashof four-bar
from the law of cosines, the slider-crank closed form, and the scaling
law of the condition number near an aligned position (cond ~ delta^-1/2).
"""

from __future__ import annotations

import math
import re

import mpmath as mp
import numpy as np
import pytest

from numkin import stability
from numkin.derivatives import SCHEMES

EXPECTED = {
    "near toggle (4, 2, 4.0001, 2)": "ok",
    "near toggle, 1e-6 deg from its limit": "ok, with warning",
    "nearly aligned, delta = 1e-02": "ok",
    "nearly aligned, delta = 1e-04": "ok",
    "nearly aligned, delta = 1e-06": "ok",
    "change point (5, 2, 5, 2), from 0 deg": "BranchError",
    "change point (5, 2, 5, 2), through 180 deg": "BranchError",
    "non-Grashof (7, 4, 3, 5), full turn": "AssemblyError",
    "cannot assemble (10, 6, 1, 1)": "AssemblyError",
    "slider-crank 80/200 at 6000 rpm": "ok",
    "homework": "ok",
    "homework x 1e-6": "ok",
    "homework x 1e3": "ok",
    "homework, 12 points per turn": "ok",
    "homework, 100 000 points per turn": "ok",
}
ERR = [f"{name} max rel error [-]" for name in SCHEMES]
NON_SPECTRAL = [f"{s.name} max rel error [-]" for s in SCHEMES.values() if not s.periodic_only]


@pytest.fixture(scope="module")
def suite():
    return stability.run_suite().set_index("case")


def test_every_case_has_its_expected_outcome(suite):
    assert list(suite.index) == list(EXPECTED) == list(stability.CASES)
    assert suite["outcome"].to_dict() == EXPECTED
    assert suite["as expected"].all()
    assert not suite["outcome"].str.contains("WRONG|unexpected").any()


def test_errors_are_outcomes_with_messages(suite):
    failed = suite[~suite["outcome"].str.startswith("ok")]
    assert len(failed) == 4
    for case, row in failed.iterrows():
        assert row["error or warning raised"].startswith(row["outcome"] + ": "), case
        assert np.isnan(row["Newton iterations (max)"])  # blank: nothing was solved
        assert np.isnan(row[ERR].to_numpy(dtype=float)).all(), case  # no number from a failed case


def test_non_grashof_names_its_reachable_range(suite):
    # crank angle where ground, crank and coupler + rocker (fully extended) close: law of cosines
    limit = math.degrees(math.acos((7**2 + 4**2 - (3 + 5) ** 2) / (2 * 7 * 4)))
    msg = suite.loc["non-Grashof (7, 4, 3, 5), full turn", "error or warning raised"]
    assert f"|theta2| <= {limit:.2f}°" in msg and "triple rocker" in msg
    msg = suite.loc["cannot assemble (10, 6, 1, 1)", "error or warning raised"]
    assert "cannot be assembled" in msg


def test_change_point_is_reported_never_switched(suite):
    row = suite.loc["change point (5, 2, 5, 2), through 180 deg"]
    assert "change point at input 180.000 deg" in row["what happened"]
    assert "branches meet" in row["error or warning raised"]
    row = suite.loc["change point (5, 2, 5, 2), from 0 deg"]
    assert "singular at input 0.000 deg" in row["what happened"]


def test_completed_cases_are_checked(suite):
    ok = suite[suite["outcome"] == "ok"]
    assert len(ok) == 10
    assert (ok["analytic vs complex step [-]"] < 1e-8).all()
    assert np.isfinite(ok[NON_SPECTRAL].to_numpy(dtype=float)).all()
    assert (ok["Newton iterations (max)"] >= 1).all()
    assert np.isfinite(ok["max cond [-]"]).all()


def test_nearly_aligned_condition_scales_like_inverse_sqrt_delta(suite):
    cond = [suite.loc[f"nearly aligned, delta = {d:.0e}", "max cond [-]"] for d in (1e-2, 1e-4, 1e-6)]
    # transmission angle ~ sqrt(delta): 100x smaller delta, 10x larger condition number
    assert cond[1] / cond[0] == pytest.approx(10, rel=0.2)
    assert cond[2] / cond[1] == pytest.approx(10, rel=0.2)
    sd = [suite.loc[f"nearly aligned, delta = {d:.0e}", "second_difference max rel error [-]"] for d in (1e-2, 1e-4, 1e-6)]
    assert sd[0] < sd[1] < sd[2]
    assert "does not resolve" in suite.loc["nearly aligned, delta = 1e-06", "what happened"]


def test_scale_cases_keep_relative_errors(suite):
    base = suite.loc["homework", NON_SPECTRAL].to_numpy(dtype=float)
    for case in ("homework x 1e-6", "homework x 1e3"):
        np.testing.assert_allclose(suite.loc[case, NON_SPECTRAL].to_numpy(dtype=float), base, rtol=1e-3)
        assert suite.loc[case, "max cond [-]"] == pytest.approx(suite.loc["homework", "max cond [-]"], rel=1e-9)
        assert "relative errors above round-off (1e-09) equal those of case 'homework'" in suite.loc[case, "what happened"]


def test_high_speed_slider_crank_against_closed_form(suite):
    r, l = 80.0, 200.0
    th = np.radians(np.arange(360.0))
    s, c = np.sin(th), np.cos(th)
    d = np.sqrt(l**2 - r**2 * s**2)
    x = r * c + d
    dx = -r * s - r**2 * s * c / d
    d2x = -r * c - r**2 * (c**2 - s**2) / d - r**4 * s**2 * c**2 / d**3
    h = th[1]
    cen = (np.roll(x, -1) - np.roll(x, 1)) / (2 * h)
    sec = (np.roll(x, -1) - 2 * x + np.roll(x, 1)) / h**2
    row = suite.loc["slider-crank 80/200 at 6000 rpm"]
    assert row["centred max rel error [-]"] == pytest.approx(np.abs(cen - dx).max() / np.abs(dx).max(), rel=1e-4)
    assert row["second_difference max rel error [-]"] == pytest.approx(
        np.abs(sec - d2x).max() / np.abs(d2x).max(), rel=1e-4
    )
    # 6000 rpm: peak piston acceleration R w^2 (1 + R/L) = 4.42e7 mm/s^2, stated with its unit
    peak = r * (2 * math.pi * 100) ** 2 * (1 + r / l)
    assert f"peak |d2/dt2| = {peak:.4g} mm/s^2" in row["what happened"]


def test_extreme_grids(suite):
    coarse = suite.loc["homework, 12 points per turn"]
    assert coarse["forward max rel error [-]"] > 0.1
    assert "does not resolve" in coarse["what happened"]
    fine = suite.loc["homework, 100 000 points per turn"]
    assert fine["points"] == 100_001
    assert fine["five_point max rel error [-]"] < 1e-7
    assert fine["centred max rel error [-]"] < 1e-7
    # second differences at h = 0.0036 deg meet the positions' round-off: the error is far above the
    # truncation error (order h^2) and above eps/h^2 (positions exact to one ulp), and below the floor
    # 4 delta/h^2 the row reports from the solver's position error delta
    err = fine["second_difference max rel error [-]"]
    h = 2 * np.pi / 100_000
    eps = np.finfo(float).eps
    assert err > 100 * h**2
    assert eps / h**2 < err
    assert "floor of 4 delta/h^2" in fine["what happened"]
    floor = float(re.search(r"floor of 4 delta/h\^2 = ([0-9.e+-]+)", fine["what happened"]).group(1))
    assert err < floor


def test_run_suite_selection_and_errors():
    t = stability.run_suite(["cannot assemble (10, 6, 1, 1)", "homework, 12 points per turn"],
                            schemes=["centred", "spectral"])
    assert list(t["case"]) == ["cannot assemble (10, 6, 1, 1)", "homework, 12 points per turn"]
    assert [c for c in t.columns if c.endswith("max rel error [-]")] == [
        "centred max rel error [-]", "spectral max rel error [-]"]
    assert t["as expected"].all()
    with pytest.raises(ValueError, match="unknown stability case"):
        stability.run_suite(["no such case"])


def test_non_monotone_first_derivative_errors_are_explained(suite):
    """Nearly aligned: the output turns within ~sqrt(delta); first-derivative errors peak at a turn one step wide."""
    rows = {d: suite.loc[f"nearly aligned, delta = {d:.0e}"] for d in (1e-2, 1e-4, 1e-6)}
    width = {d: r["sharpest turn [deg]"] for d, r in rows.items()}
    assert np.isnan(width[1e-2])  # wider than 3 grid steps: resolved, not measured
    assert width[1e-4] / width[1e-6] == pytest.approx(10, rel=0.2)  # 100x smaller delta, 10x narrower turn
    assert 0.5 < width[1e-4] < 3 and width[1e-6] < 0.5  # about one 1 deg step, and a corner between steps
    centred = {d: r["centred max rel error [-]"] for d, r in rows.items()}
    assert centred[1e-2] < centred[1e-6] < centred[1e-4]  # not monotone in delta ...
    for d in (1e-4, 1e-6):
        assert "first-derivative errors peak when the turn is about one step wide" in rows[d]["what happened"]
    assert "sharpest turn" in suite.attrs["caption"].lower() and "1e-4" in suite.attrs["caption"]
    assert np.isnan(suite.loc["homework", "sharpest turn [deg]"])


def test_report_tables_of_the_stability_scene():
    tables = stability.report_tables(["cannot assemble (10, 6, 1, 1)", "homework, 12 points per turn"])
    assert list(tables) == ["stability"]
    views = [title for title, _ in tables["stability"].attrs["views"]]
    assert views[0] == "outcome" and "what happened" in views


def test_homework_cases_are_the_documents_chained_four_bars_scaled():
    """The homework cases are built from the chained four-bars' spec: the homework's dimensions (the
    source document: linkage 1 fixed 7.0, input 1.94, coupler 6.86, output 2.36; linkage 2 fixed 1.25,
    input 2.39, coupler 1.87, output 1.26; offset 149 deg), lengths scaled, the offset angle not."""
    lengths = [7.0, 1.94, 6.86, 2.36, 1.25, 2.39, 1.87, 1.26]
    for name, scale in (("homework", 1.0), ("homework x 1e-6", 1e-6), ("homework x 1e3", 1e3)):
        values = stability.CASES[name].build().parameter_values
        assert np.allclose(values[:8], np.array(lengths) * scale, rtol=1e-15, atol=0), name
        assert values[8] == pytest.approx(math.radians(149.0), rel=1e-15)


def test_stability_imports_no_private_names():
    import ast
    import inspect

    tree = ast.parse(inspect.getsource(stability))
    private = [(node.module, alias.name) for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
               for alias in node.names if alias.name.startswith("_")]
    assert private == []


def test_lost_digits_on_the_toggle_are_shown():
    """1e-6 deg past the limit the condition number is ~1.6e5: the analytic derivatives lose digits."""
    import numkin

    row = stability.run_suite(["near toggle, 1e-6 deg from its limit"], schemes=["centred"]).iloc[0]
    assert row["as expected"] and row["outcome"] == "ok, with warning"
    assert bool(row["analytic lost digits"])
    assert "LostDigitsWarning" in row["error or warning raised"]
    assert "lose digits" in row["what happened"]
    # the estimate 3 eps cond^2 from the condition number the row reports
    est = 3 * np.finfo(float).eps * row["max cond [-]"] ** 2
    assert est > 1e-6
    assert f"{est:.2g}" in row["what happened"]
    assert numkin.LostDigitsWarning is numkin.conditioning.LostDigitsWarning
    assert not bool(stability.run_suite(["near toggle (4, 2, 4.0001, 2)"], schemes=["centred"]).iloc[0][
        "analytic lost digits"])


def _toggle_theta4(theta, sign):
    """Rocker angle of the 4/2/4.0001/2 four-bar by mpmath: |B - O4| = 2, |B - A| = 4.0001, A = 2 e^{i theta}."""
    a = 2 * mp.expj(theta) - 4  # from O4 to the crank pin A
    d = abs(a)
    along = (2**2 - mp.mpf("4.0001") ** 2 + d**2) / (2 * d)
    return mp.arg((along + sign * 1j * mp.sqrt(2**2 - along**2)) * a / d)


def test_open_sweep_errors_leave_the_end_stencils_apart():
    """Near toggle, swept 1..359 deg (an open sweep): the max rel error is over the interior points, where the
    second difference's own stencil (1, -2, 1)/h^2 applies; the one-sided end stencil (2, -5, 4, -1)/h^2 at
    1 and 359 deg has its own column. Reference: theta4 in closed form by mpmath, its exact second derivative
    by mp.diff, both differences of its values by hand."""
    name = "near toggle (4, 2, 4.0001, 2)"
    row = stability.run_suite([name], schemes=["second_difference", "spectral", "forward"]).iloc[0]
    deg = np.arange(1.0, 360.0)
    first = float(stability.CASES[name].build().sweep(np.radians(deg[:1]))["theta4"][0])  # the branch only
    with mp.workdps(30):
        sign = min((1, -1), key=lambda s: abs(mp.arg(mp.expj(_toggle_theta4(mp.radians(1), s) - first))))
        q = np.unwrap([float(_toggle_theta4(mp.radians(t), sign)) for t in deg])
        exact = np.array([float(mp.diff(lambda t: _toggle_theta4(t, sign), mp.radians(t), 2)) for t in deg])
        slope = np.array([float(mp.diff(lambda t: _toggle_theta4(t, sign), mp.radians(t), 1)) for t in deg])
    h = math.radians(1.0)
    peak = np.abs(exact).max()
    inner = np.abs((q[:-2] - 2 * q[1:-1] + q[2:]) / h**2 - exact[1:-1]) / peak
    start = abs((2 * q[0] - 5 * q[1] + 4 * q[2] - q[3]) / h**2 - exact[0]) / peak
    end = abs((2 * q[-1] - 5 * q[-2] + 4 * q[-3] - q[-4]) / h**2 - exact[-1]) / peak
    assert 170 < deg[1 + int(np.argmax(inner))] < 190  # the interior's largest error is at the sharp turn
    assert row["second_difference max rel error [-]"] == pytest.approx(inner.max(), rel=1e-6)
    assert row["second_difference ends rel error [-]"] == pytest.approx(max(start, end), rel=1e-6)
    assert round(inner.max(), 3) == 0.270 and round(start, 3) == 0.339  # the end stencil's is the larger
    assert np.isnan(row["spectral max rel error [-]"]) and np.isnan(row["spectral ends rel error [-]"])
    # forward: its own stencil at every point but the last (1 deg included), the mirrored one at 359 deg
    forward = np.abs(np.diff(q) / h - slope[:-1]) / np.abs(slope).max()
    last = abs((q[-1] - q[-2]) / h - slope[-1]) / np.abs(slope).max()
    assert row["forward max rel error [-]"] == pytest.approx(forward.max(), rel=1e-6)
    assert row["forward ends rel error [-]"] == pytest.approx(last, rel=1e-6)
    caption = stability.run_suite(["cannot assemble (10, 6, 1, 1)"]).attrs["caption"]
    assert "over the points where its own stencil applies" in caption
    assert "the last for forward, the first for backward" in caption
    assert "max rel error and ends rel error are divided by the largest |exact value| over the sweep" in caption


def test_a_full_turn_has_no_end_stencils(suite):
    ok = suite[suite["outcome"] == "ok"]
    ends = [f"{name} ends rel error [-]" for name in SCHEMES]
    open_sweeps = [c for c in ok.index if c.startswith("near toggle")]  # 1..359 deg: the only open sweeps
    assert np.isnan(ok.drop(index=open_sweeps)[ends].to_numpy(dtype=float)).all()
    assert np.isfinite(ok.loc[open_sweeps, ["centred ends rel error [-]", "five_point ends rel error [-]"]]
                       .to_numpy(dtype=float)).all()

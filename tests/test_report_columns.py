"""Tests for numkin.report: each error column holds what its header and caption say.

Independent references: the rocker angle of the near-toggle four-bar
(ground 4, crank 2, coupler 4.0001, rocker 2) in closed form, evaluated and
differentiated by mpmath at 40 digits; the two-line error model of the
round-off table derived by hand; sums of the table's own parts where a
column is defined as their sum.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from numkin import linkages, report
from numkin.report.roundoff import stencil
from numkin.schemes import get_scheme

EPS = np.finfo(float).eps


def _toggle_theta4(theta, sign):
    """Rocker angle of the 4/2/4.0001/2 four-bar: |B - O4| = 2, |B - A| = 4.0001, A = 2 e^{i theta}, O4 = (4, 0)."""
    a = 2 * mp.expj(theta) - 4
    d = abs(a)
    along = (2**2 - mp.mpf("4.0001") ** 2 + d**2) / (2 * d)
    return mp.arg((along + sign * 1j * mp.sqrt(2**2 - along**2)) * a / d)


# ------------------------------------------------------------------- round-off
@pytest.fixture(scope="module")
def toggle_roundoff():
    mech = linkages.four_bar(4, 2, 4.0001, 2)
    theta = math.radians(178.0)  # 2 deg before the sharp turn: truncation outweighs rounding at every textbook step
    table = report.roundoff_table(mech, quantity="theta4", check_angle=theta, start=math.radians(90),
                                  schemes=("centred", "five_point", "second_difference"))
    return mech, theta, table.set_index("scheme")


@pytest.mark.parametrize("scheme", ["five_point", "second_difference"])
def test_error_at_the_textbook_step_is_measured(toggle_roundoff, scheme):
    """The textbook step's error is the scheme's error at that step, not the estimate eps^(p/(p+n)): here the
    stencil applied to exact (40-digit) values at the textbook step, against the exact derivative."""
    mech, theta, table = toggle_roundoff
    row = table.loc[scheme]
    s = get_scheme(scheme)
    p, n = s.order, s.derivative
    assert row["textbook optimal h [rad]"] == pytest.approx(EPS ** (1 / (p + n)), rel=1e-12)
    h = (theta + EPS ** (1 / (p + n))) - theta  # the step the table takes: theta + h a float
    x = float(mech.solve(theta).x[1])
    ks, ws = stencil(s)
    with mp.workdps(40):
        sign = min((1, -1), key=lambda g: abs(mp.arg(mp.expj(_toggle_theta4(mp.mpf(theta), g) - x))))
        exact = mp.diff(lambda t: _toggle_theta4(t, sign), mp.mpf(theta), n)
        est = sum(mp.mpf(float(w)) * _toggle_theta4(mp.mpf(theta) + int(k) * mp.mpf(h), sign)
                  for k, w in zip(ks, ws)) / mp.mpf(h) ** n
        truncation = float(abs(est - exact) / abs(exact))
    assert truncation > 100 * EPS ** (p / (p + n))  # far from the textbook's estimate
    assert row["rel error measured at textbook h [-]"] == pytest.approx(truncation, rel=0.02)


def test_textbook_step_on_the_fitted_curve(toggle_roundoff):
    """On the two-line model C_t h^p + C_r eps/h^n the lines meet at h* with C_t h*^p = C_r eps/h*^n = e*/2, so
    at any step h the model is e*/2 ((h/h*)^p + (h*/h)^n)."""
    from numkin.report.roundoff import ROUNDOFF_SCHEMES

    hw = report.roundoff_table(linkages.chained_four_bars(), quantity="beta", check_angle=math.radians(100),
                               schemes=ROUNDOFF_SCHEMES[:4]).set_index("scheme")
    for table in (hw, toggle_roundoff[2]):
        for scheme, row in table.iterrows():
            s = get_scheme(scheme)
            hs, es, h = row["measured optimal h [rad]"], row["rel error at measured optimal h [-]"], \
                row["textbook optimal h [rad]"]
            model = es / 2 * ((h / hs) ** s.order + (hs / h) ** s.derivative)
            assert row["rel error on fitted curve at textbook h [-]"] == pytest.approx(model, rel=1e-9), scheme
    # the second difference: textbook step 1.22e-4 rad, a third of h* = 3.4e-4 -> (1/2.8)^2 + 2.8^2 ~ 8 halves of e*
    second = hw.loc["second_difference"]
    assert second["rel error on fitted curve at textbook h [-]"] > 3 * second["rel error at measured optimal h [-]"]
    caption = hw.attrs["caption"]
    assert "Relative errors: every error is divided by |exact value| at theta = 100 deg." in caption
    assert "error measured at that step" in caption and "textbook error" not in " ".join(hw.columns)


# ------------------------------------------------------------- work-precision
@pytest.fixture(scope="module")
def timed_wp():
    return report.work_precision_table(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x", repeat=2,
                                       grids=(36, 72), schemes=("forward", "centred", "second_difference"))


def test_total_time_is_the_sum_of_its_parts(timed_wp):
    sweep, derivative, total = (timed_wp[f"{part} time [ms] (varies)"].to_numpy(dtype=float)
                                for part in ("sweep", "derivative", "sweep + derivative"))
    np.testing.assert_allclose(total, sweep + derivative, rtol=1e-12)
    assert "the sweep + derivative time their sum" in timed_wp.attrs["caption"]


def test_time_rankings_read_the_total(timed_wp):
    """The Pareto front by time and the cheapest method by time, from the sum of the two medians, by hand."""
    t = timed_wp["sweep time [ms] (varies)"].to_numpy(float) + timed_wp["derivative time [ms] (varies)"].to_numpy(float)
    e = timed_wp["max rel error [-]"].to_numpy(float)
    q = timed_wp["quantity"].to_numpy()
    tie = 64 * EPS
    front = [not any(q[j] == q[k] and t[j] <= t[k] and e[j] <= e[k] + tie and (t[j] < t[k] or e[j] < e[k] - tie)
                     for j in range(len(t)) if j != k) for k in range(len(t))]
    assert timed_wp["Pareto front (varies)"].tolist() == front
    cheapest = report.cheapest_table(timed_wp, targets=(1e-2, 1e-4))
    for _, row in cheapest.iterrows():
        ok = (q == row["quantity"]) & (e <= row["wanted max rel error [-]"])
        assert row["time [ms] (varies)"] == pytest.approx(t[ok].min(), rel=1e-12)


# --------------------------------------------------------- relative errors
def _piston(t, r=80.0, rod=200.0):
    """Slider-crank x and dx/dtheta in closed form."""
    s, c = np.sin(t), np.cos(t)
    d = np.sqrt(rod**2 - r**2 * s**2)
    return r * c + d, -r * s - r**2 * s * c / d


def test_every_caption_names_the_denominator_of_each_relative_error():
    mech = linkages.slider_crank(80, 200)
    tables = report.full_report(mech, omega=1.0, quantity="x", check_angle=math.radians(90), grids=(36, 72),
                                schemes=("centred", "second_difference"), points_per_turn=36)
    peak = "the largest |exact value| over the sweep"
    for name, table in tables.items():
        columns = [c for c in table.columns if "rel error" in c]
        caption = table.attrs["caption"]
        if name == "roundoff":  # every column is relative to the value at the check angle
            assert "Relative errors: every error is divided by |exact value| at theta = 90 deg." in caption
            continue
        if not columns:
            assert "Relative errors" not in caption, name
            continue
        sentence = caption[caption.index(" Relative errors: "):]
        for column in columns:
            assert column in sentence, (name, column)
        assert peak in sentence, name
    tol = tables["tolerance"]
    assert ("v_x max rel error [%] and a_x max rel error [%] are divided by the largest |exact value| over the "
            "sweep; v_x rel error at theta = 90 deg [%] and a_x rel error at theta = 90 deg [%] by |exact value| at "
            "theta = 90 deg.") in tol.attrs["caption"]
    # and the numbers are those quotients: the tight sweep's centred v_x against the closed form, by hand
    row = tol[tol["rule"] == "numkin, tol = 1e-12"].iloc[0]
    t = np.radians(np.arange(36) * 10.0)
    x, dx = _piston(t)
    err = np.abs((np.roll(x, -1) - np.roll(x, 1)) / (2 * t[1]) - dx)
    assert row["v_x rel error at theta = 90 deg [%]"] == pytest.approx(100 * err[9] / abs(dx[9]), rel=1e-6)
    assert row["v_x max rel error [%]"] == pytest.approx(100 * err.max() / np.abs(dx).max(), rel=1e-6)
    assert "(the analytic rows: the largest |complex step| over the sweep" in tables["work_precision"].attrs["caption"]

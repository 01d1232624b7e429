"""Tests for numkin.report: the numbers in each error-analysis table, against independent references.

References: the closed form of the homework's two chained four-bars (source
document 003's dimensions), two circle intersections evaluated with mpmath at
30 digits and differentiated by mpmath (exact values, and the finite
differences of exact positions on the 1 deg grid); the values homework 003
printed from its own loop (centred 10.63198 rad/s, second difference
-28.36941 rad/s^2 at theta = 100 deg); and the closed form of the
slider-crank piston, x = r cos(t) + sqrt(l^2 - r^2 sin^2(t)), differentiated
by hand below.
"""

from __future__ import annotations

import dataclasses
import math
import sys

import mpmath as mp
import numpy as np
import pandas as pd
import pytest

from numkin import analytic, linkages, report
from numkin.scene import load_scene
from numkin.units import UnitError

EPS = np.finfo(float).eps
W_HW = 450.0 / 60.0  # rad/s
CHECK = math.radians(100.0)
R, L = 80.0, 200.0
W_SC = 6000.0 * 2.0 * math.pi / 60.0


# ----------------------------------------------------------------- references
def piston(t):
    """Slider-crank x, dx/dt, d2x/dt2 (per rad of crank), closed form, crank R, rod L."""
    s, c = np.sin(t), np.cos(t)
    d = np.sqrt(L**2 - R**2 * s**2)
    x = R * c + d
    dx = -R * s - R**2 * s * c / d
    d2x = -R * c - R**2 * (c**2 - s**2) / d - R**4 * s**2 * c**2 / d**3
    return x, dx, d2x


# homework 003: linkage 1 (fixed, input, coupler, output) and linkage 2, alpha = phi + 149 deg
HW1, HW2, HW_OFFSET = (7.0, 1.94, 6.86, 2.36), (1.25, 2.39, 1.87, 1.26), 149


def _circles(a, out, coupler, sign):
    """Angle of the output link: |B| = out, |a - B| = coupler, on the side `sign` of the line 0 -> a."""
    d = abs(a)
    along = (out**2 - coupler**2 + d**2) / (2 * d)
    across = mp.sqrt(out**2 - along**2)
    return mp.arg((along + sign * 1j * across) * a / d)


def _hw_angles(theta, signs):
    (f1, i1, c1, o1), (f2, i2, c2, o2) = HW1, HW2
    phi = _circles(f1 + i1 * mp.expj(theta), o1, c1, signs[0])
    beta = _circles(f2 + i2 * mp.expj(phi + mp.radians(HW_OFFSET)), o2, c2, signs[1])
    return phi, beta


def _hw_signs():
    """The assembly of each loop nearest to the homework's starting guesses at theta = 0 (phi 45, beta 30 deg)."""
    def gap(a, b):
        return abs(mp.arg(mp.expj(a - b)))

    s1 = min((1, -1), key=lambda s: gap(_hw_angles(0, (s, 1))[0], mp.radians(45)))
    s2 = min((1, -1), key=lambda s: gap(_hw_angles(0, (s1, s))[1], mp.radians(30)))
    return s1, s2


def hw_beta(theta_deg, order=0):
    """beta (rad) of the homework's branch, or its derivative d^n beta / d theta^n, at theta_deg, by mpmath."""
    with mp.workdps(30):
        signs = _hw_signs()
        return float(mp.diff(lambda t: _hw_angles(t, signs)[1], mp.radians(theta_deg), order))


def test_homework_reference_itself():
    # the branch the homework continues on: phi = 94.4375, beta = 214.7270 deg at theta = 100 deg
    with mp.workdps(30):
        phi, beta = _hw_angles(mp.radians(100), _hw_signs())
    assert math.degrees(float(phi)) == pytest.approx(94.4375, abs=1e-4)
    assert math.degrees(float(beta)) % 360 == pytest.approx(214.7270, abs=1e-4)
    # the assignment's check: omega_beta near 10 rad/s, alpha_beta close to -25 rad/s^2
    assert W_HW * hw_beta(100, 1) == pytest.approx(10, abs=1)
    assert W_HW**2 * hw_beta(100, 2) == pytest.approx(-25, abs=4)


def test_piston_reference_itself():
    # -R (1 + R/L) at t = 0, and the derivative formulas against central differences
    assert piston(0.0)[2] == pytest.approx(-R * (1 + R / L), rel=1e-15)
    t, h = 0.7, 1e-5
    assert (piston(t + h)[0] - piston(t - h)[0]) / (2 * h) == pytest.approx(piston(t)[1], rel=1e-8)
    assert (piston(t + h)[1] - piston(t - h)[1]) / (2 * h) == pytest.approx(piston(t)[2], rel=1e-8)


@pytest.fixture(scope="module")
def homework():
    return linkages.chained_four_bars()


@pytest.fixture(scope="module")
def slider():
    return linkages.slider_crank(R, L)


def _row(table, **match):
    sel = np.ones(len(table), dtype=bool)
    for key, value in match.items():
        sel &= table[key.replace("_", " ") if key == "points_per_turn" else key].to_numpy() == value
    rows = table[sel]
    assert len(rows) == 1, match
    return rows.iloc[0]


# ---------------------------------------------------------------- convergence
@pytest.fixture(scope="module")
def hw_convergence(homework):
    return report.convergence_table(
        homework, omega="450 rad/min", quantity="beta", check_angle=CHECK, grids=(180, 360, 720),
        schemes=("forward", "centred", "five_point", "second_difference", "forward_of_forward", "five_point_second"),
    )


@pytest.mark.parametrize(
    "scheme, order",
    [("forward", 1), ("centred", 2), ("five_point", 4), ("second_difference", 2), ("forward_of_forward", 1),
     ("five_point_second", 4)],
)
def test_observed_orders(hw_convergence, scheme, order):
    row = _row(hw_convergence, scheme=scheme, **{"points per turn": 720})
    assert row["observed order [-]"] == pytest.approx(order, abs=0.15)


def hw_differences(theta_deg=100):
    """Exact omega_beta, alpha_beta and the 1 deg grid's differences of exact positions, rad/s and rad/s^2."""
    b = {k: hw_beta(theta_deg + k) for k in (-1, 0, 1, 2)}
    h = math.radians(1.0)
    return {
        "omega": W_HW * hw_beta(theta_deg, 1),
        "alpha": W_HW**2 * hw_beta(theta_deg, 2),
        "forward": W_HW * (b[1] - b[0]) / h,
        "centred": W_HW * (b[1] - b[-1]) / (2 * h),
        "second_difference": W_HW**2 * (b[1] - 2 * b[0] + b[-1]) / h**2,
        "forward_of_forward": W_HW**2 * (b[2] - 2 * b[1] + b[0]) / h**2,
    }


def test_convergence_errors_at_check_angle_match_the_closed_form(hw_convergence):
    col = "abs error at theta = 100 deg [unit of quantity]"
    ref = hw_differences()
    for scheme in ("forward", "centred", "second_difference", "forward_of_forward"):
        exact = ref["omega"] if scheme in ("forward", "centred") else ref["alpha"]
        err = _row(hw_convergence, scheme=scheme, **{"points per turn": 360})[col]
        assert err == pytest.approx(abs(ref[scheme] - exact), rel=1e-6, abs=1e-9), scheme


def test_convergence_table_layout(hw_convergence):
    t = hw_convergence
    assert list(t.columns) == [
        "scheme", "formal order", "quantity", "points per turn", "h [deg]",
        "max abs error [unit of quantity]", "RMS abs error [unit of quantity]", "max rel error [-]",
        "abs error at theta = 100 deg [unit of quantity]", "observed order [-]",
    ]
    assert list(t["scheme"])[:3] == ["forward"] * 3
    assert list(t["points per turn"])[:3] == [180, 360, 720]
    assert list(t["h [deg]"])[:3] == [2.0, 1.0, 0.5]
    assert set(t[t.scheme == "centred"]["quantity"]) == {"omega_beta [rad/s]"}
    assert set(t[t.scheme == "second_difference"]["quantity"]) == {"alpha_beta [rad/s^2]"}
    assert t.groupby("scheme", sort=False)["observed order [-]"].apply(lambda s: bool(np.isnan(s.iloc[0]))).all()


def test_convergence_against_closed_form(slider):
    n = 72
    t = report.convergence_table(
        slider, omega="6000 rpm", quantity="x", check_angle=math.radians(90), grids=(n,),
        schemes=("centred", "second_difference"),
    )
    th = 2 * np.pi * np.arange(n) / n
    x, dx, d2x = piston(th)
    h = th[1]
    cen = (np.roll(x, -1) - np.roll(x, 1)) / (2 * h)
    sec = (np.roll(x, -1) - 2 * x + np.roll(x, 1)) / h**2
    e1, e2 = W_SC * np.abs(cen - dx), W_SC**2 * np.abs(sec - d2x)
    r1, r2 = t.iloc[0], t.iloc[1]
    assert r1["quantity"] == "v_x [mm/s]" and r2["quantity"] == "a_x [mm/s^2]"
    assert r1["max abs error [unit of quantity]"] == pytest.approx(e1.max(), rel=1e-6)
    assert r1["RMS abs error [unit of quantity]"] == pytest.approx(np.sqrt(np.mean(e1**2)), rel=1e-6)
    assert r2["max abs error [unit of quantity]"] == pytest.approx(e2.max(), rel=1e-6)
    assert r2["max rel error [-]"] == pytest.approx(e2.max() / (W_SC**2 * np.abs(d2x).max()), rel=1e-6)
    assert r2["abs error at theta = 90 deg [unit of quantity]"] == pytest.approx(e2[n // 4], rel=1e-5)


def test_open_grid_statistics_leave_the_end_stencils_apart(slider):
    """0-180 deg: max, RMS, relative error and observed order over the points where the second
    difference applies, the one-sided ends (2y0 - 5y1 + 4y2 - y3)/h^2 in their own column; closed form."""
    t = report.convergence_table(slider, omega="6000 rpm", quantity="x", check_angle=0.0, grids=(180, 360),
                                 span=math.pi, schemes=("second_difference",))
    for row, n in zip(t.itertuples(index=False), (180, 360)):
        th = np.linspace(0.0, math.pi, n // 2 + 1)
        x, _, d2x = piston(th)
        h = th[1]
        inner = W_SC**2 * np.abs((x[2:] - 2 * x[1:-1] + x[:-2]) / h**2 - d2x[1:-1])
        first = W_SC**2 * abs((2 * x[0] - 5 * x[1] + 4 * x[2] - x[3]) / h**2 - d2x[0])
        last = W_SC**2 * abs((2 * x[-1] - 5 * x[-2] + 4 * x[-3] - x[-4]) / h**2 - d2x[-1])
        values = dict(zip(t.columns, row))
        assert values["max abs error [unit of quantity]"] == pytest.approx(inner.max(), rel=1e-6)
        assert values["RMS abs error [unit of quantity]"] == pytest.approx(np.sqrt(np.mean(inner**2)), rel=1e-6)
        assert values["ends abs error [unit of quantity]"] == pytest.approx(max(first, last), rel=1e-6)
        assert values["abs error at theta = 0 deg [unit of quantity]"] == pytest.approx(first, rel=1e-6)
    assert t["observed order [-]"].iloc[1] == pytest.approx(2.0, abs=0.01)
    assert "own stencil applies" in t.attrs["caption"] and "check angle is an end point" in t.attrs["caption"]


def test_a_loosely_solved_full_turn_is_differenced_as_periodic():
    """The residual rule's sweep of the six-bar misses its start after a turn by its position error: its
    centred and second differences at 0 deg wrap around like every other row's (an own periodic stencil)."""
    from numkin.report.tolerance import student_sweep

    six_bar = linkages.six_bar()
    t = report.tolerance_table(six_bar, omega=-10.0, quantity="x", check_angle=0.0)
    inputs = np.linspace(0.0, 2 * math.pi, 361)
    loose = student_sweep(six_bar, inputs, rule="residual", tol=1e-4)
    exact = analytic.derivatives(six_bar.sweep(inputs))
    j = list(six_bar.unknowns).index("x")
    x, h, w = loose.values[j, :-1], inputs[1], -10.0
    v = w * (np.roll(x, -1) - np.roll(x, 1)) / (2 * h)
    a = w * w * (np.roll(x, -1) - 2 * x + np.roll(x, 1)) / h**2
    v_ex, a_ex = w * exact[0][j, :-1], w * w * exact[1][j, :-1]
    row = t[t["rule"] == "residual"].iloc[0]
    assert row["v_x at theta2 = 0 deg [cm/s]"] == pytest.approx(v[0], rel=1e-9)
    assert row["a_x at theta2 = 0 deg [cm/s^2]"] == pytest.approx(a[0], rel=1e-9)
    assert row["v_x max rel error [%]"] == pytest.approx(100 * np.abs(v - v_ex).max() / np.abs(v_ex).max(), rel=1e-6)
    assert row["a_x max rel error [%]"] == pytest.approx(100 * np.abs(a - a_ex).max() / np.abs(a_ex).max(), rel=1e-6)


def test_check_angle_off_the_grid_is_blank(slider):
    t = report.convergence_table(slider, omega=1.0, quantity="x", check_angle=math.radians(7), grids=(36, 360),
                                 schemes=("centred",))
    column = t["abs error at theta = 7 deg [unit of quantity]"]
    assert np.isnan(column.iloc[0]) and column.iloc[1] > 0  # 7 deg: not on the 10 deg grid, on the 1 deg one
    with pytest.raises(ValueError, match="check_angle 5729.58 deg is on none of the grids"):  # 100 given in degrees
        report.convergence_table(slider, omega=1.0, quantity="x", check_angle=100.0, grids=(36,), schemes=("centred",))


def test_open_grid_and_spectral_refusal(slider):
    t = report.convergence_table(slider, omega=1.0, quantity="x", grids=(180,), span=math.pi)
    assert "spectral" not in set(t["scheme"])  # default schemes on a half turn: no spectral
    with pytest.raises(ValueError, match="full turn"):
        report.convergence_table(slider, omega=1.0, quantity="x", grids=(180,), span=math.pi, schemes=("spectral",))


# ------------------------------------------------------------------- roundoff
@pytest.fixture(scope="module")
def hw_roundoff(homework):
    return report.roundoff_table(homework, quantity="beta", check_angle=CHECK)


def test_roundoff_exact_values_are_the_closed_form(hw_roundoff):
    t = hw_roundoff.set_index("scheme")
    assert t.loc["centred", "exact value [unit of quantity]"] == pytest.approx(hw_beta(100, 1), rel=1e-13)
    assert t.loc["second_difference", "exact value [unit of quantity]"] == pytest.approx(hw_beta(100, 2), rel=1e-12)


def test_homework_scene_roundoff_is_on_the_homework_branch():
    """The scene's guess is for theta = 0; the table at 100 deg must continue the sweep there, not restart."""
    scene = load_scene("homework")
    mech = scene.build_mechanism()
    opts = scene.report_options(mech)
    t = report.roundoff_table(mech, quantity="beta", check_angle=opts["check_angle"], guess=opts["guess"],
                              start=opts["start"]).set_index("scheme")
    exact1, exact2 = hw_beta(100, 1), hw_beta(100, 2)
    assert round(exact1, 6) == 1.417720 and round(exact2, 6) == -0.504444
    assert t.loc["forward", "exact value [unit of quantity]"] == pytest.approx(exact1, rel=1e-13)
    assert t.loc["second_difference", "exact value [unit of quantity]"] == pytest.approx(exact2, rel=1e-12)


def test_second_difference_at_1e_8_is_shown_wrong(hw_roundoff):
    t = hw_roundoff.set_index("scheme")
    sd = t.loc["second_difference"]
    assert sd["rel error at h = 1e-08 rad [-]"] > 1e-2
    assert sd["rel error at h = 1e-08 rad [-]"] > 1e4 * sd["rel error at measured optimal h [-]"]
    # below the optimum the error grows like eps / h^2: ~100x per decade (down to 1e-11 rad, where the
    # three samples differ by a few ulps and the estimate is noise of size 1e7)
    errs = [sd[f"rel error at h = {h:.0e} rad [-]"] for h in 10.0 ** -np.arange(6, 12)]
    assert all(b > 10 * a for a, b in zip(errs, errs[1:]))
    assert errs[-1] > 1e6 * errs[0] / 10


@pytest.mark.parametrize(
    "scheme, textbook", [("forward", EPS**0.5), ("centred", EPS ** (1 / 3)), ("five_point", EPS**0.2),
                         ("second_difference", EPS**0.25)],
)
def test_measured_optimum_near_textbook(hw_roundoff, scheme, textbook):
    row = hw_roundoff.set_index("scheme").loc[scheme]
    assert row["textbook optimal h [rad]"] == pytest.approx(textbook)
    assert textbook / 10 < row["measured optimal h [rad]"] < textbook * 10
    p, n = {"forward": (1, 1), "centred": (2, 1), "five_point": (4, 1), "second_difference": (2, 2)}[scheme]
    assert row["rel error at measured optimal h [-]"] < 100 * EPS ** (p / (p + n))  # the textbook's own estimate


def test_complex_step_has_no_floor(hw_roundoff):
    row = hw_roundoff.set_index("scheme").loc["complex step"]
    for h in 10.0 ** -np.arange(7, 13):
        assert row[f"rel error at h = {h:.0e} rad [-]"] <= 1e-14
    # above h = 1e-7 its own truncation, h^2 |d3beta / (6 dbeta)|, shows: ~3e-14 at 1e-6, ~3e-4 at 1e-1
    trunc = abs(hw_beta(100, 3) / (6 * hw_beta(100, 1)))
    assert row["rel error at h = 1e-06 rad [-]"] == pytest.approx(trunc * 1e-12, rel=0.2)
    assert row["rel error at h = 1e-01 rad [-]"] == pytest.approx(trunc * 1e-2, rel=0.2)


def test_captions_give_the_dimensions_with_their_unit(slider, hw_roundoff):
    """Every table's caption names the linkage as its figures do: each dimension with the length unit."""
    named = "slider-crank (crank 80 mm, rod 200 mm, offset 0 mm)"
    assert slider.title == named
    tables = [report.newton_table(slider, check_angle=math.radians(90)),
              report.jacobian_table(slider, check_angle=math.radians(90), points_per_turn=36),
              report.convergence_table(slider, omega=1.0, quantity="x", grids=(36, 72), schemes=("centred",)),
              report.tolerance_table(slider, omega=1.0, quantity="x", points_per_turn=36,
                                     check_angle=math.radians(90))]
    for table in tables:
        assert named in table.attrs["caption"], table.attrs["caption"]
    assert "chained four-bars" in hw_roundoff.attrs["caption"]  # (dimensions not in the name: as it is)


def test_roundoff_against_closed_form(slider):
    t = report.roundoff_table(slider, quantity="x", check_angle=math.radians(60),
                              schemes=("centred", "second_difference"))
    _, dx, d2x = piston(math.radians(60))
    assert t["exact value [unit of quantity]"].iloc[0] == pytest.approx(dx, rel=1e-12)
    assert t["exact value [unit of quantity]"].iloc[1] == pytest.approx(d2x, rel=1e-12)
    # truncation at h = 1e-2: centred h^2 x'''/6, second difference h^2 x''''/12, from the closed form
    h, d = 1e-3, 1e-2
    x3 = (piston(math.radians(60) + h)[2] - piston(math.radians(60) - h)[2]) / (2 * h)
    x4 = (piston(math.radians(60) + h)[2] - 2 * d2x + piston(math.radians(60) - h)[2]) / h**2
    assert t["rel error at h = 1e-02 rad [-]"].iloc[0] == pytest.approx(abs(d**2 * x3 / 6 / dx), rel=1e-3)
    assert t["rel error at h = 1e-02 rad [-]"].iloc[1] == pytest.approx(abs(d**2 * x4 / 12 / d2x), rel=1e-3)


# --------------------------------------------------------------------- Newton
def test_newton_quadratic(homework):
    t = report.newton_table(homework, check_angle=CHECK)
    assert list(t["iteration"]) == list(range(len(t)))
    orders = t["order estimate from errors [-]"].dropna()
    assert len(orders) >= 2
    assert orders.iloc[-1] == pytest.approx(2.0, abs=0.25)
    assert t["error norm [-]"].iloc[-1] < 1e-12
    assert np.all(np.diff(t["residual norm [-]"]) < 0)
    assert np.isnan(t["step norm [-]"].iloc[0])
    # the error after a step is about the next step (Newton): step k+1 ~ error k
    np.testing.assert_allclose(t["step norm [-]"].iloc[2:].to_numpy(), t["error norm [-]"].iloc[1:-1].to_numpy(),
                               rtol=0.1)


def test_jacobian_table(homework):
    t = report.jacobian_table(homework, check_angle=CHECK, points_per_turn=36, repeat=1)
    assert list(t["Jacobian"]) == ["symbolic", "forward", "central"]
    assert (t["final error (one solve) [-]"] < 1e-11).all()
    assert (t["max difference from symbolic sweep [-]"] < 1e-10).all()
    assert (t["iterations (one solve)"] <= 6).all()
    assert t["order estimate, last (one solve) [-]"].iloc[0] == pytest.approx(2.0, abs=0.25)
    assert [c for c in t.columns if "time" in c] == ["sweep time [ms] (varies)"]


# ------------------------------------------------------------------ tolerance
@pytest.fixture(scope="module")
def hw_tolerance(homework):
    return report.tolerance_table(homework, omega="450 rad/min", quantity="beta", check_angle=CHECK)


def _rule(table, prefix):
    rows = table[table["stopping rule"].str.startswith(prefix)]
    assert len(rows) == 1, prefix
    return rows.iloc[0]


W_COL, A_COL = "omega_beta at theta = 100 deg [rad/s]", "alpha_beta at theta = 100 deg [rad/s^2]"


def test_tolerance_reference_and_tight_rows(hw_tolerance):
    t = hw_tolerance
    ref = hw_differences()
    assert t[W_COL].iloc[0] == pytest.approx(ref["omega"], rel=1e-12)
    assert t[A_COL].iloc[0] == pytest.approx(ref["alpha"], rel=1e-11)
    tight = _rule(t, "numkin sweep, tol = 1e-12")
    assert tight[W_COL] == pytest.approx(ref["centred"], rel=1e-10)
    assert tight[A_COL] == pytest.approx(ref["second_difference"], rel=1e-7)
    assert tight["beta error estimate max|J^-1 F| [rad]"] < 1e-11
    assert [" ".join(r.split()[:2]) for r in t["stopping rule"]] == [
        "analytic (reference,", "absolute step", "relative step", "residual rule", "numkin sweep,", "numkin sweep,"]


def test_relative_rule_reproduces_the_homework_and_spoils_alpha_at_its_first_points(hw_tolerance):
    rel = _rule(hw_tolerance, "relative step rule")
    # the values homework 003 printed from its own loop (|dx|/|x| < 1e-4, loop by loop)
    assert rel[W_COL] == pytest.approx(10.63198, abs=1e-5)
    assert rel[A_COL] == pytest.approx(-28.36941, abs=2e-5)
    # about one Newton step per loop and point: the first point, from the far guess, is left loose
    assert rel["Newton iterations per point (mean)"] < 3.1
    assert rel["alpha_beta max rel error [%]"] > 50
    assert rel["alpha_beta largest error at theta [deg]"] == 0.0
    assert rel["beta error estimate max|J^-1 F| [rad]"] > 1e-4


def test_loose_residual_rule_spoils_alpha_not_position(hw_tolerance):
    t = hw_tolerance
    step, residual, tight = (_rule(t, p) for p in ("absolute step rule", "residual rule", "numkin sweep, tol = 1e-12"))
    am, wm = "alpha_beta max rel error [%]", "omega_beta max rel error [%]"
    # the position is off by ~1e-4 rad at most: invisible in beta, ~1e-4 / h^2 in alpha
    assert residual["beta error estimate max|J^-1 F| [rad]"] < 1e-3
    assert residual[wm] < 1.0
    assert residual[am] > 5.0
    assert residual[am] > 100 * tight[am]
    # Newton converges quadratically: a step rule at 1e-4 leaves ~1e-8 and spoils nothing
    assert step["beta error estimate max|J^-1 F| [rad]"] < 1e-7
    assert step[am] < 2 * tight[am]
    assert (t["note"] == "").all()


# ------------------------------------------------------------ work-precision
def _fixed(df):
    return df[[c for c in df.columns if "(varies)" not in c]]


WORK_COLS = ["sweep work [evaluations]", "derivative work [evaluations]", "work [evaluations]"]


@pytest.fixture(scope="module")
def slider_wp(slider):
    kw = dict(omega="6000 rpm", quantity="x", grids=(36, 72), schemes=("forward", "centred", "second_difference"),
              repeat=1)
    return report.work_precision_table(slider, **kw), report.work_precision_table(slider, **kw)


def test_work_precision_rows_and_determinism(slider_wp):
    a, b = slider_wp
    # everything but the timings is the same in a second run: the work counts and the front by work too
    pd.testing.assert_frame_equal(_fixed(a), _fixed(b))
    assert set(WORK_COLS + ["Pareto front by work"]) <= set(_fixed(a).columns)
    time_cols = [c for c in a.columns if "time" in c]
    assert len(time_cols) == 3 and all(c.endswith("(varies)") for c in time_cols)
    assert "Pareto front (varies)" in a.columns
    assert list(a["method"]) == ["analytic"] * 2 + ["complex step"] * 2 + ["forward"] * 2 + ["centred"] * 2 + [
        "analytic"] * 2 + ["complex step"] * 2 + ["second_difference"] * 2
    assert (a[a.method.isin(["analytic", "complex step"])]["max rel error [-]"] < 1e-10).all()
    assert (a[time_cols] > 0).all().all()
    # the finite-difference errors are those of the closed form
    th = 2 * np.pi * np.arange(72) / 72
    x, dx, _ = piston(th)
    cen = (np.roll(x, -1) - np.roll(x, 1)) / (2 * th[1])
    row = _row(a, method="centred", **{"points per turn": 72})
    assert row["max abs error [unit of quantity]"] == pytest.approx(W_SC * np.abs(cen - dx).max(), rel=1e-6)
    assert a["Pareto front (varies)"].any() and a["Pareto front by work"].any()


def test_work_precision_errors_for_an_input_turning_clockwise(slider):
    # omega < 0: the errors are magnitudes, those of the closed form at |omega| (the sign turns the
    # derivatives, not the size of their errors)
    kw = dict(quantity="x", grids=(36,), schemes=("forward",))
    neg = report.work_precision_table(slider, omega="-6000 rpm", **kw)
    th = 2 * np.pi * np.arange(36) / 36
    x, dx, _ = piston(th)
    fwd = (np.roll(x, -1) - x) / th[1]
    row = _row(neg, method="forward", **{"points per turn": 36})
    assert row["max abs error [unit of quantity]"] == pytest.approx(W_SC * np.abs(fwd - dx).max(), rel=1e-6)
    assert (neg["max abs error [unit of quantity]"] >= 0).all()


def test_work_counts_are_exact(slider, slider_wp):
    a, _ = slider_wp
    assert all(a[c].dtype.kind == "i" for c in WORK_COLS)
    assert (a["work [evaluations]"] == a["sweep work [evaluations]"] + a["derivative work [evaluations]"]).all()
    for n in (36, 72):
        rows = a[a["points per turn"] == n]
        samples = n + 1  # a full turn: the last input repeats the first
        # every row of a grid shares one sweep, and its work is what that sweep records: nfev + njev
        inputs = 2 * np.pi * np.arange(samples) / n
        with report.count_evaluations(slider) as count:
            sweep = slider.sweep(inputs)
        assert count.points == {"F": sweep.nfev, "J": sweep.njev}
        assert set(rows["sweep work [evaluations]"]) == {sweep.nfev + sweep.njev}
        # a converged point costs at least one fused residual-and-Jacobian evaluation per Newton step plus the first
        assert sweep.nfev >= int(np.sum(sweep.iterations + 1)) and sweep.njev >= int(np.sum(sweep.iterations + 1))
        work = {(r["method"], r["quantity"][0]): r["derivative work [evaluations]"] for _, r in rows.iterrows()}
        # velocity equations J q' = -dF/dtheta: J is the sweep's own (reused, not evaluated again);
        # dF/dtheta at every input
        assert work[("analytic", "v")] == samples
        # acceleration: dF/dtheta for q', then J q'' = -(G_q q' + G_theta): the right-hand side at every
        # input, on the same reused J
        assert work[("analytic", "a")] == 2 * samples
        # finite differences evaluate no compiled function: one stencil evaluation per distinct grid point
        assert work[("forward", "v")] == work[("centred", "v")] == work[("second_difference", "a")] == n
        # the complex step runs Newton at every point, at least F and J once each: dearer than analytic
        assert work[("complex step", "v")] >= 2 * samples
        assert work[("complex step", "v")] % samples == 0 and work[("complex step", "a")] % samples == 0


def test_work_of_an_open_grid_counts_every_sample(slider):
    t = report.work_precision_table(slider, omega=1.0, quantity="x", grids=(36,), span=math.pi, schemes=("centred",),
                                    repeat=1)
    # 0 .. 180 deg in 10 deg steps: 19 samples, the ends by one-sided stencils
    assert _row(t, method="centred")["derivative work [evaluations]"] == 19
    # the velocity equations on the sweep's Jacobian: dF/dtheta at each of the 19 samples
    assert _row(t, method="analytic", quantity="v_x [mm/s]")["derivative work [evaluations]"] == 19


def test_newton_result_counts_of_one_solve(slider, homework):
    for mech, angle in ((slider, 0.3), (homework, CHECK)):
        res = mech.solve(angle)
        k = res.iterations
        assert res.converged and k >= 1
        # Newton: the residual at the start and after each of the k steps; the Jacobian at the k iterates
        # it steps from
        assert (res.nfev, res.njev) == (k + 1, k)
        assert res.iterates.shape == (k + 1, len(mech.unknowns))


def test_count_evaluations_collects_what_numkin_records(slider):
    other = linkages.four_bar(4, 1, 3, 3)
    t = np.radians(np.arange(0, 91, 10))
    with report.count_evaluations(slider) as outer:
        s = slider.sweep(t)
        other.sweep(t)  # another mechanism's work is not counted
        with report.count_evaluations(slider) as inner:
            analytic.derivatives(s)  # on the sweep's Jacobian: dF/dtheta and the acceleration right-hand side
    assert inner.points == {"F_t": t.size, "second": t.size}
    assert outer.points == {"F": s.nfev, "J": s.njev, "F_t": t.size, "second": t.size}
    with report.count_evaluations(slider) as after:
        pass
    assert after.total == 0
    # a copy of the sweep has no Jacobian kept: the exact derivatives evaluate it once per point
    with report.count_evaluations(slider) as copied:
        analytic.tangent(dataclasses.replace(s))
    assert copied.points == {"J": t.size, "F_t": t.size}


def test_counting_a_sweep_does_not_compile_the_acceleration():
    mech = linkages.four_bar(4, 1, 3.5, 3)
    with report.count_evaluations(mech) as count:
        mech.sweep(np.radians(np.arange(0, 91, 10)))
    assert count.total > 0 and set(count.points) == {"F", "J"}
    assert "_second" not in vars(mech.compiled)  # position-only work never differentiates


def test_cheapest_table():
    wp = pd.DataFrame({
        "method": ["forward", "centred", "analytic", "forward"],
        "quantity": ["v [mm/s]"] * 4,
        "points per turn": [36, 36, 36, 720],
        "sweep + derivative time [ms] (varies)": [1.0, 1.1, 1.5, 3.0],
        "work [evaluations]": [300, 300, 380, 5000],
        "max rel error [-]": [1e-2, 1e-4, 1e-15, 1e-3],
    })
    t = report.cheapest_table(wp, targets=(1e-1, 1e-3, 1e-5, 1e-16))
    assert list(t["cheapest method (varies)"]) == ["forward", "centred", "analytic", "none"]
    assert np.isnan(t["time [ms] (varies)"].iloc[-1])
    # by work: equal work, the more accurate wins; nothing varies
    w = report.cheapest_table(wp, targets=(1e-1, 1e-3, 1e-5, 1e-16), by="work")
    assert list(w["cheapest method"]) == ["centred", "centred", "analytic", "none"]
    assert list(w["work [evaluations]"][:3]) == [300, 300, 380]
    assert not any("(varies)" in c for c in w.columns)
    with pytest.raises(ValueError, match="by must be"):
        report.cheapest_table(wp, by="speed")


# ------------------------------------------------------------------ writing
def test_write_tables(tmp_path):
    df = pd.DataFrame({"scheme": ["centred", "five_point"], "h [deg]": [1.0, 0.5],
                       "max abs error [rad/s^2]": [2.5e-4, np.nan], "Pareto front (varies)": [True, False]})
    df.attrs["caption"] = "Demo: 100% of errors"
    paths = report.write_tables({"demo_table": df, "second": df.iloc[:1]}, tmp_path / "out")
    assert [p.name for p in paths] == ["demo_table.md", "demo_table.csv", "demo_table.tex",
                                       "second.md", "second.csv", "second.tex"]
    md = paths[0].read_text()
    assert md.startswith("Demo: 100% of errors")
    assert "| scheme" in md and "max abs error [rad/s^2]" in md and "0.00025" in md and "yes" in md
    back = pd.read_csv(paths[1])
    assert list(back.columns) == list(df.columns)
    assert back["h [deg]"].tolist() == [1.0, 0.5] and np.isnan(back["max abs error [rad/s^2]"].iloc[1])
    tex = paths[2].read_text()
    for token in ("\\toprule", "\\midrule", "\\bottomrule", "\\begin{tabular}{lrrl}", "five\\_point",
                  "rad/s\\textsuperscript{2}", "100\\% of errors", "\\label{tab:demo-table}"):
        assert token in tex, token
    assert tex.count("\\\\") == 3  # header + 2 rows


def test_latex_tables_carry_the_markdown_digits_and_parts(tmp_path):
    # the value 10.6319826...: 7 significant figures in every format, not 6 in LaTeX (10.632 would hide
    # the digit a tolerance table is about)
    df = pd.DataFrame({"rule": ["homework", "relative stop"], "exact value [rad/s]": [10.6319826, 10.6328997],
                       "Newton iterations per point (mean)": [3.04, 5.0], "note": ["a", "b"]})
    df.attrs["views"] = [("values", ["rule", "exact value [rad/s]"]), ("cost", ["rule", "Newton iterations per point (mean)", "note"])]
    md, _, tex = (p.read_text() for p in report.write_tables({"t": df}, tmp_path))
    for text in ("10.631983", "10.632900", "3.0", "5.0"):
        assert text in md and text in tex, text
    assert tex.count("\\begin{tabular}") == 2 and "\\begin{tabular}{lr}" in tex and "\\begin{tabular}{lrl}" in tex
    assert "\\textbf{values}" in tex and "\\textbf{cost}" in tex


def test_write_tables_formats(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "tabulate", None)  # Markdown is written without tabulate
    assert report.write_tables({"t": pd.DataFrame({"a": [1]})}, tmp_path / "md")[0].read_text().startswith("| a |")
    paths = report.write_tables({"t": pd.DataFrame({"a": [1]})}, tmp_path / "other", formats=("csv", "tex"))
    assert [p.suffix for p in paths] == [".csv", ".tex"]
    with pytest.raises(ValueError, match="unknown table format"):
        report.write_tables({"t": pd.DataFrame({"a": [1]})}, tmp_path, formats=("xlsx",))


# --------------------------------------------------------- full report, input
def test_full_report_and_bad_input(slider):
    tables = report.full_report(slider, omega="6000 rpm", quantity="x", check_angle=math.radians(60),
                                grids=(36, 72), schemes=("centred", "second_difference"), points_per_turn=36,
                                repeat=1)
    assert list(tables) == ["convergence", "work_precision", "cheapest", "roundoff", "newton", "jacobian",
                            "tolerance"]
    assert all(isinstance(t, pd.DataFrame) and t.attrs.get("caption") for t in tables.values())
    with pytest.raises(ValueError, match=r"choose one of \['theta3', 'x'\]"):
        report.convergence_table(slider, omega=1.0, quantity="beta")
    with pytest.raises(UnitError):
        report.convergence_table(slider, omega="5 m", quantity="x")
    with pytest.raises(ValueError, match="not on the 36-point grid"):
        report.tolerance_table(slider, omega=1.0, quantity="x", check_angle=math.radians(7), points_per_turn=36)
    with pytest.raises(ValueError, match="points per turn"):
        report.convergence_table(slider, omega=1.0, quantity="x", grids=(2.5,))


def test_student_sweep_against_closed_form():
    mech = linkages.four_bar(4, 1, 3, 3)
    th = np.radians(np.arange(0.0, 361.0, 5.0))
    s = report.student_sweep(mech, th, rule="step", tol=1e-4)
    # closed form of the open branch: circle intersection
    ax, ay = np.cos(th), np.sin(th)
    dx, dy = 4 - ax, -ay
    d = np.hypot(dx, dy)
    t3 = np.arctan2(dy, dx) + np.arccos((9 + d**2 - 9) / (6 * d))
    t4 = np.arctan2(ay + 3 * np.sin(t3), ax + 3 * np.cos(t3) - 4)
    np.testing.assert_allclose(np.remainder(s["theta4"] - t4 + np.pi, 2 * np.pi) - np.pi, 0, atol=1e-7)
    r = report.student_sweep(mech, th, rule="residual", tol=1e-4)
    assert np.max(np.abs(mech.compiled.F(r.values, th, mech.parameter_values))) < 1e-4
    assert r.jacobian == "student residual rule"
    with pytest.raises(ValueError, match="rule must be"):
        report.student_sweep(mech, th, rule="both")


# ------------------------------------------------------- every table on the scene's branch
@pytest.mark.parametrize("name", ["homework", "quick-return", "six-bar", "slider-crank"])
def test_every_table_of_a_scene_is_on_its_sweeps_branch(name):
    """Each position a table solved lies on the branch of the scene's own sweep (continued from its guess)."""
    scene = load_scene(name)
    mech = scene.build_mechanism()
    opts = {**scene.report_options(mech), "grids": (36, 72), "points_per_turn": 72, "repeat": 1}
    opts["omega"] = opts["omega"] or 1.0  # a positions-only scene: any speed gives the same positions
    opts["check_angle"] = math.radians(round(math.degrees(opts["check_angle"]) / 5) * 5)  # on the 72-point grid
    tables = report.full_report(mech, **opts)
    angle = np.array([u in mech.angles for u in mech.unknowns])
    seen = 0
    for table_name, table in tables.items():
        for pos in table.attrs.get("positions", []):
            if "relative step rule" in pos["what"] or "residual rule" in pos["what"]:
                continue  # the loose rules' own sweeps may leave the branch; their rows say so in "note"
            a = pos["input [rad]"]
            # the scene's sweep: 1 deg steps from its start, continued to a
            start = math.radians(scene.start_deg)
            n = max(2, int(round(abs(math.degrees(a - start)))) + 1)
            inputs = np.linspace(start, a, n) if n > 2 or a != start else np.array([start])
            ref = mech.sweep(inputs, opts["guess"]).values[:, -1]
            got = np.array([pos[u] for u in mech.unknowns])
            gap = got - ref
            gap[angle] = np.remainder(gap[angle] + np.pi, 2 * np.pi) - np.pi
            assert np.max(np.abs(gap) / mech.xscale) < 1e-9, (table_name, pos["what"], math.degrees(a))
            seen += 1
    assert {"roundoff", "newton", "jacobian", "tolerance"} <= {k for k, t in tables.items() if t.attrs.get("positions")}
    assert seen >= 10


# ------------------------------------------------ round-off optimum, robust and on its curve
def test_numkin_report_homework_writes_the_branch_values(tmp_path, capsys):
    """The command's round-off table at theta = 100 deg lists the homework branch's exact derivatives (mpmath)."""
    from numkin import cli

    assert cli.main(["report", "homework", "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    text = (tmp_path / "homework-roundoff.md").read_text()
    d1, d2 = hw_beta(100, 1), hw_beta(100, 2)
    assert f"{d1:.6f}" == "1.417720" and f"{d2:.6f}" == "-0.504444"
    assert "| dbeta/dtheta [rad/rad] | 1.417720 |" in text
    assert "| d2beta/dtheta^2 [rad/rad^2] | -0.504444 |" in text
    assert "theta = 100 deg" in text


def test_roundoff_scan_has_each_step_once(hw_roundoff):
    """8 steps per decade from 1e-1 to 1e-12 (89; each made representable at theta = 100°, a relative change
    below 1e-4), none twice (1e-5 and 10**-5 from the scan's exponents differ in their last bit), and the
    caption's count the scan's."""
    h = np.array(hw_roundoff.attrs["scan"]["h [rad]"])
    assert h.size == 11 * 8 + 1
    np.testing.assert_allclose(np.diff(np.log10(h)), -0.125, atol=1e-4)
    assert "fitted to 89 steps" in hw_roundoff.attrs["caption"]


def test_roundoff_is_the_same_in_two_runs(homework, hw_roundoff):
    again = report.roundoff_table(homework, quantity="beta", check_angle=CHECK)
    pd.testing.assert_frame_equal(again, hw_roundoff)
    assert again.attrs["scan"] == hw_roundoff.attrs["scan"]


# truncation constants |e(h)| / h^p as h -> 0, relative to the exact value, from mpmath derivatives of beta
_TRUNCATION = {
    "forward": lambda d: abs(d[2] / (2 * d[1])),
    "centred": lambda d: abs(d[3] / (6 * d[1])),
    "five_point": lambda d: abs(d[5] / (30 * d[1])),
    "second_difference": lambda d: abs(d[4] / (12 * d[2])),
    "complex step": lambda d: abs(d[3] / (6 * d[1])),
}


@pytest.mark.parametrize("scheme", list(_TRUNCATION))
def test_roundoff_optimum_lies_on_its_curve(hw_roundoff, scheme):
    row = hw_roundoff.set_index("scheme").loc[scheme]
    d = [hw_beta(100, k) for k in range(6)]
    hstar, estar = row["measured optimal h [rad]"], row["rel error at measured optimal h [-]"]
    p = {"forward": 1, "centred": 2, "five_point": 4, "second_difference": 2, "complex step": 2}[scheme]
    # the fitted truncation line is the Taylor one: at the intersection the model is twice the line
    assert estar / (2 * hstar**p) == pytest.approx(_TRUNCATION[scheme](d), rel=0.1)
    # on the measured curve: the scan's errors within a quarter decade of h* have a median near the model
    scan = hw_roundoff.attrs["scan"]
    h = np.array(scan["h [rad]"])
    err = np.array(scan[scheme])
    near = np.abs(np.log10(h / hstar)) <= 0.25
    assert near.sum() >= 3
    assert 1 / 4 < np.median(err[near]) / estar < 4
    # and the error measured at h* itself is no larger (one sample of round-off: it may cancel to far less)
    assert row["rel error measured at that h [-]"] / estar < 10


def test_fitted_optimum_ignores_a_lucky_cancellation():
    h = 10.0 ** -np.linspace(1, 12, 89)
    err = 0.3 * h**4 + 2.0 * EPS / h
    lucky = err.copy()
    k = int(np.argmin(err)) + 2
    lucky[k] = err[k] * 1e-3  # one step where the rounding errors cancel
    assert report.fitted_optimum(h, lucky, 4, 1) == pytest.approx(report.fitted_optimum(h, err, 4, 1), rel=1e-12)
    hstar = report.fitted_optimum(h, err, 4, 1)[0]
    assert hstar == pytest.approx((2.0 * EPS / 0.3) ** (1 / 5), rel=0.02)
    assert all(math.isnan(v) for v in report.fitted_optimum(h[:3], err[:3], 4, 1))


@pytest.mark.parametrize("name", [n for n, s in __import__("numkin.derivatives", fromlist=["SCHEMES"]).SCHEMES.items()
                                  if not s.periodic_only])
def test_stencil_of_every_scheme_has_its_taylor_moments(name):
    """sum_k w_k k^m / m! is 1 for m = n (the derivative) and 0 for the other m < n + p (the order)."""
    from numkin.derivatives import get_scheme

    scheme = get_scheme(name)
    k, w = report.stencil(scheme)
    n, p = scheme.derivative, scheme.order
    for m in range(n + p):
        moment = float(np.sum(w * k.astype(float) ** m)) / math.factorial(m)
        assert moment == pytest.approx(1.0 if m == n else 0.0, abs=1e-12), (name, m)
    # the next moment is the truncation error's: not zero
    assert abs(float(np.sum(w * k.astype(float) ** (n + p)))) > 1e-9


def test_roundoff_works_for_every_scheme_of_the_registry(slider):
    from numkin.derivatives import SCHEMES

    names = [n for n, s in SCHEMES.items() if not s.periodic_only]
    t = report.roundoff_table(slider, quantity="x", check_angle=math.radians(60), schemes=names)
    assert list(t["scheme"]) == names
    assert np.isfinite(t["measured optimal h [rad]"]).all()
    _, dx, d2x = piston(math.radians(60))
    exact = t.set_index("scheme")["exact value [unit of quantity]"]
    assert exact["richardson"] == pytest.approx(dx, rel=1e-12)
    assert exact["five_point_second"] == pytest.approx(d2x, rel=1e-12)


def test_columns_no_view_names_are_written_after_the_views(tmp_path):
    df = pd.DataFrame({"scheme": ["centred"], "h [deg]": [1.0], "max abs error [rad/s]": [2.5e-4], "note": ["x"],
                       0: [3.0]})
    df.attrs["views"] = [("errors", ["scheme", "h [deg]", "max abs error [rad/s]"])]
    df.attrs["row_keys"] = ["scheme"]
    md, _, tex = (p.read_text() for p in report.write_tables({"t": df}, tmp_path))
    for text in (md, tex):  # "note" and the column named 0 are not lost, and the row stays named
        assert "other columns" in text and "note" in text and "x" in text and "| 3 |" in md
    assert tex.count("\\begin{tabular}") == 2 and "\\begin{tabular}{lrr}" in tex


def test_an_untimed_table_has_no_view_of_run_times(slider):
    """Without repeat there are no times: no part of the printed table is the row names alone."""
    t = report.work_precision_table(slider, omega="6000 rpm", quantity="x", grids=(36,), schemes=("centred",))
    views = dict(t.attrs["views"])
    keys = set(t.attrs["row_keys"])
    assert not any("run time" in title for title in views)
    assert all(set(cols) - keys for cols in views.values())
    assert "the analytic rows' against the complex step" in t.attrs["caption"]


def test_an_observed_order_from_errors_at_the_round_off_floor_is_left_blank(homework):
    """The spectral scheme reaches round-off (~1e-12 rad/s) by 180 points per turn, after which its error
    grows with N: 'observed orders' of -1.1 from there say nothing, so they are blank and the caption says
    why; the centred difference, far above its floor, keeps every order (2 from the Taylor series)."""
    t = report.convergence_table(homework, omega="450 rad/min", quantity="beta", grids=(36, 72, 180, 360),
                                 schemes=("centred", "spectral"))
    centred, spectral = t[t.scheme == "centred"], t[t.scheme == "spectral"]
    assert np.allclose(centred["observed order [-]"].iloc[1:], 2.0, atol=0.05)
    assert spectral["max abs error [unit of quantity]"].iloc[2] < 1e-11
    assert spectral["observed order [-]"].iloc[1] > 8  # 36 -> 72: spectral convergence, above the floor
    assert spectral["observed order [-]"].iloc[2:].isna().all()
    assert "round-off floor" in t.attrs["caption"] and "spectral" in t.attrs["caption"].split("round-off floor")[1]


def test_methods_exact_to_round_off_are_tied_on_the_pareto_front():
    """The analytic rows of every grid are exact to round-off: the cheapest of them is on the front by work,
    a finer grid's is not (its error is smaller only in the last digits), and no front row of one quantity
    is beaten by more than round-off by a cheaper one."""
    from numkin.report.workprecision import ROUNDOFF_TIE

    wp = report.work_precision_table(linkages.chained_four_bars(), omega="450 rad/min", quantity="beta",
                                     grids=(36, 360, 3600), schemes=("centred",))
    work = [c for c in wp.columns if c.startswith("work [")][0]
    for _, rows in wp.groupby("quantity"):
        analytic = rows[rows.method == "analytic"].sort_values(work)
        assert (analytic["max rel error [-]"] < 1e-14).all()
        assert list(analytic["Pareto front by work"]) == [True, False, False]
        front = rows[rows["Pareto front by work"]]
        for _, row in front.iterrows():
            cheaper = rows[rows[work] < row[work]]
            assert not (cheaper["max rel error [-]"] < row["max rel error [-]"] - ROUNDOFF_TIE).any()


def test_work_precision_and_convergence_agree_on_an_open_grid(slider):
    """0-180 deg: both tables give a scheme's error over the points where its own stencil applies (the
    closed-form piston's interior errors), so the same grid gives the same number in both."""
    kw = dict(omega="6000 rpm", quantity="x", grids=(36, 72), schemes=("five_point", "second_difference"),
              span=math.pi)
    wp = report.work_precision_table(slider, **kw)
    conv = report.convergence_table(slider, **kw)
    for scheme in ("five_point", "second_difference"):
        a = wp[wp.method == scheme]["max abs error [unit of quantity]"].to_numpy()
        b = conv[conv.scheme == scheme]["max abs error [unit of quantity]"].to_numpy()
        np.testing.assert_allclose(a, b, rtol=1e-9)  # the same sweeps and stencils; exact rates to round-off
    n = 36
    th = np.linspace(0.0, math.pi, n // 2 + 1)
    x, _, d2x = piston(th)
    h = th[1]
    inner = W_SC**2 * np.abs((x[2:] - 2 * x[1:-1] + x[:-2]) / h**2 - d2x[1:-1])
    row = wp[(wp.method == "second_difference") & (wp["points per turn"] == n)].iloc[0]
    assert row["max abs error [unit of quantity]"] == pytest.approx(inner.max(), rel=1e-6)
    assert "own stencil applies" in wp.attrs["caption"]


def test_a_check_angle_off_some_grids_is_said_in_the_caption():
    """From 45°, grids of 10° and 2° steps miss 100° (45 + 10k, 45 + 2k), those of 5° and 1° hold it: their cells
    are blank, and the caption says why."""
    t = report.convergence_table(linkages.four_bar(10, 3, 8, 6), omega=10.0, quantity="theta4", grids=(36, 72, 180, 360),
                                 span=math.radians(155), start=math.radians(45), check_angle=math.radians(100),
                                 schemes=("centred",))
    col = next(c for c in t.columns if c.startswith("abs error at theta2 = 100 deg"))
    assert t.set_index("points per turn")[col].isna().to_dict() == {36: True, 72: False, 180: True, 360: False}
    assert ("The error at theta2 = 100 deg is blank on the grid(s) of 36, 180 points per turn, which do not hold that "
            "angle.") in t.attrs["caption"]

"""Error tables of a derived quantity (numkin.report with quantity = a name of numkin.derived).

References, independent of numkin: the four-bar (4, 1, 3, 3) solved in closed
form by the law of cosines (written below, evaluated with mpmath at 30
digits and differentiated by mpmath.diff), its transmission angle
mu = theta4 - theta3 sampled from that closed form and differenced here with
the schemes' own formulas; the slider-crank's gap between the crank pin's x
and the piston, sqrt(l^2 - r^2 sin^2), differentiated by hand.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pandas as pd
import pytest

from numkin import linkages, report
from numkin.errors import InputError
from numkin.report.studied import studied_quantity

W = 10.0  # rad/s
MU = {"mu": ("theta4 - theta3", "angle")}
R, L = 80.0, 200.0
GAP = {"gap": ("x - r*cos(theta)", "length")}
MU_ESTIMATE = "mu error estimate max|mu(x + dx) - mu(x)|, dx = -J^-1 F [rad]"


# ----------------------------------------------------------------- references
def _four_bar(t, ground=4, crank=1, coupler=3, rocker=3):
    """(theta3, theta4) of the open four-bar at crank angle t, by the law of cosines in the triangle A B O4 (mpmath).

    The coupler leaves the crank pin A at the angle of A->O4 plus the triangle's angle at A.
    """
    ax, ay = crank * mp.cos(t), crank * mp.sin(t)
    d = mp.sqrt((ground - ax) ** 2 + ay**2)
    theta3 = mp.atan2(-ay, ground - ax) + mp.acos((coupler**2 + d**2 - rocker**2) / (2 * coupler * d))
    bx, by = ax + coupler * mp.cos(theta3), ay + coupler * mp.sin(theta3)
    return theta3, mp.atan2(by, bx - ground)


def mu_closed(t):
    theta3, theta4 = _four_bar(t)
    return theta4 - theta3


def mu_reference(points: int):
    """mu, dmu/dtheta, d2mu/dtheta2 on a grid of `points` per turn from 0 (mpmath, 30 digits)."""
    with mp.workdps(30):
        t = [2 * mp.pi * k / points for k in range(points)]
        values = np.array([float(mu_closed(x)) for x in t])
        d1 = np.array([float(mp.diff(mu_closed, x)) for x in t])
        d2 = np.array([float(mp.diff(mu_closed, x, 2)) for x in t])
    return values, d1, d2


@pytest.fixture(scope="module")
def four_bar():
    return linkages.four_bar(4, 1, 3, 3).add_quantities(MU)


@pytest.fixture(scope="module")
def reference():
    """The closed form on the 144-point grid (it holds the 36- and 72-point grids)."""
    return mu_reference(144)


GRIDS = (36, 72, 144)


@pytest.fixture(scope="module")
def mu_convergence(four_bar):
    return report.convergence_table(four_bar, omega=W, quantity="mu", check_angle=math.radians(90), grids=GRIDS,
                                    schemes=("centred", "second_difference", "spectral"))


# ----------------------------------------------------------------- the convergence table of mu
def test_the_exact_derivatives_of_mu_are_the_closed_forms(four_bar, reference):
    values, d1, d2 = reference
    sweep = four_bar.sweep(np.linspace(0.0, 2 * np.pi, 145))
    mu = studied_quantity(four_bar, "mu")
    exact1, exact2 = mu.exact(sweep)
    np.testing.assert_allclose(mu.values(sweep)[:-1], values, atol=1e-13, rtol=0)
    np.testing.assert_allclose(exact1[:-1], d1, atol=1e-11, rtol=0)
    np.testing.assert_allclose(exact2[:-1], d2, atol=1e-10, rtol=0)
    # and they are the difference of the unknowns' own rates, from their closed forms
    with mp.workdps(30):
        t = mp.radians(100)
        by_parts = mp.diff(lambda x: _four_bar(x)[1], t) - mp.diff(lambda x: _four_bar(x)[0], t)
    single = four_bar.sweep(np.radians(np.arange(0.0, 101.0)))
    assert mu.exact(single)[0][-1] == pytest.approx(float(by_parts), abs=1e-12)


def _periodic(values, points):
    """The closed-form samples of one turn, as the schemes see them (the table's grid, mu is 2 pi periodic)."""
    return values[:: 144 // points]


def test_centred_errors_on_mu_are_those_of_the_closed_form_samples(mu_convergence, reference):
    values, d1, d2 = reference
    centred = mu_convergence[mu_convergence["scheme"] == "centred"]
    second = mu_convergence[mu_convergence["scheme"] == "second_difference"]
    assert list(centred["quantity"]) == ["omega_mu [rad/s]"] * 3
    assert list(second["quantity"]) == ["alpha_mu [rad/s^2]"] * 3
    for n in GRIDS:
        k = 144 // n
        y, e1, e2 = _periodic(values, n), d1[::k], d2[::k]
        h = 2 * math.pi / n
        est1 = (np.roll(y, -1) - np.roll(y, 1)) / (2 * h)  # mu returns to its value after a turn
        est2 = (np.roll(y, -1) - 2 * y + np.roll(y, 1)) / h**2
        err1, err2 = W * np.abs(est1 - e1), W**2 * np.abs(est2 - e2)
        row1 = centred[centred["points per turn"] == n].iloc[0]
        row2 = second[second["points per turn"] == n].iloc[0]
        assert row1["max abs error [unit of quantity]"] == pytest.approx(err1.max(), rel=1e-8)
        assert row1["RMS abs error [unit of quantity]"] == pytest.approx(np.sqrt(np.mean(err1**2)), rel=1e-8)
        assert row1["max rel error [-]"] == pytest.approx(err1.max() / (W * np.abs(e1).max()), rel=1e-8)
        assert row1["abs error at theta2 = 90 deg [unit of quantity]"] == pytest.approx(err1[n // 4], rel=1e-8)
        assert row2["max abs error [unit of quantity]"] == pytest.approx(err2.max(), rel=1e-7)


def test_the_centred_scheme_on_mu_converges_with_order_two(mu_convergence):
    centred = mu_convergence[mu_convergence["scheme"] == "centred"]
    h = np.radians(centred["h [deg]"].to_numpy())
    slope = np.polyfit(np.log(h), np.log(centred["max abs error [unit of quantity]"].to_numpy()), 1)[0]
    assert slope == pytest.approx(2.0, abs=0.02)
    np.testing.assert_allclose(centred["observed order [-]"].iloc[1:], 2.0, atol=0.02)
    # the spectral scheme differences mu as periodic: exact to round-off on a turn, no observed order
    spectral = mu_convergence[mu_convergence["scheme"] == "spectral"]
    assert spectral["max rel error [-]"].max() < 1e-10
    assert spectral["observed order [-]"].isna().all()


def test_the_table_names_the_derived_quantity_and_its_units(mu_convergence):
    q = mu_convergence.attrs["quantities"]
    assert q["omega_mu [rad/s]"].of == "mu" and q["alpha_mu [rad/s^2]"].unit == "rad/s^2"
    assert "mu = theta4 - theta3" in mu_convergence.attrs["caption"]


def test_an_angle_that_turns_with_the_input_is_differenced_with_its_whole_turn():
    """phi = theta2 - theta3 gains a turn per turn of the input: periodic up to 2 pi, as an angle unknown."""
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"phi": ("theta2 - theta3", "angle")})
    t = report.convergence_table(mech, omega=W, quantity="phi", grids=(36, 72), schemes=("centred", "spectral"))
    with mp.workdps(30):
        dphi = np.array([float(1 - mp.diff(lambda x: _four_bar(x)[0], 2 * mp.pi * k / 72)) for k in range(72)])
        y = np.array([float(2 * mp.pi * k / 72 - _four_bar(2 * mp.pi * k / 72)[0]) for k in range(72)])
    y = np.unwrap(y)
    h = 2 * math.pi / 72
    est = (np.append(y[1:], y[0] + 2 * math.pi) - np.insert(y[:-1], 0, y[-1] - 2 * math.pi)) / (2 * h)
    row = t[(t["scheme"] == "centred") & (t["points per turn"] == 72)].iloc[0]
    assert row["max abs error [unit of quantity]"] == pytest.approx(W * np.abs(est - dphi).max(), rel=1e-8)
    assert t[t["scheme"] == "spectral"]["max rel error [-]"].max() < 1e-9


# ----------------------------------------------------------------- a length: the slider-crank's gap
def gap(t):
    """sqrt(l^2 - r^2 sin^2 t) and its first two derivatives, by hand."""
    s, c = np.sin(t), np.cos(t)
    g = np.sqrt(L**2 - (R * s) ** 2)
    g1 = -(R**2) * s * c / g
    g2 = -(R**2) * np.cos(2 * t) / g - (R**2 * s * c) ** 2 / g**3
    return g, g1, g2


@pytest.fixture(scope="module")
def slider():
    return linkages.slider_crank(R, L).add_quantities(GAP)


def test_the_roundoff_table_of_a_length_quantity(slider):
    t60 = math.radians(60)
    table = report.roundoff_table(slider, quantity="gap", check_angle=t60, schemes=("centred", "complex_step"))
    _, g1, _ = gap(t60)
    centred = table[table["scheme"] == "centred"].iloc[0]
    assert centred["quantity"] == "dgap/dtheta [mm/rad]"
    assert centred["exact value [unit of quantity]"] == pytest.approx(g1, rel=1e-13)
    h = table.attrs["steps"]["rel error at h = 1e-02 rad [-]"]
    h = (t60 + h) - t60
    by_hand = (gap(t60 + h)[0] - gap(t60 - h)[0]) / (2 * h)
    assert centred["rel error at h = 1e-02 rad [-]"] == pytest.approx(abs(by_hand - g1) / abs(g1), rel=1e-6)
    cs = table[table["scheme"] == "complex step"].iloc[0]
    assert cs["rel error at h = 1e-12 rad [-]"] < 1e-14  # no cancellation


def test_the_work_precision_and_convergence_tables_of_a_length_quantity(slider):
    wp = report.work_precision_table(slider, omega=W, quantity="gap", grids=(36,), schemes=("five_point",))
    assert list(wp["quantity"].unique()) == ["v_gap [mm/s]", "a_gap [mm/s^2]"]
    exact = wp[wp["method"].isin(["analytic", "complex step"])]
    assert (exact["max rel error [-]"] < 1e-13).all()
    # the expression is evaluated once per input by every method, on top of the unknowns' own work
    plain = report.work_precision_table(slider, omega=W, quantity="x", grids=(36,), schemes=("five_point",))
    extra = wp["derivative work [evaluations]"].to_numpy() - plain["derivative work [evaluations]"].to_numpy()
    assert (extra == 37).all()
    conv = report.convergence_table(slider, omega=W, quantity="gap", grids=(36, 72), schemes=("five_point",))
    t = np.linspace(0.0, 2 * np.pi, 73)[:-1]
    g, g1, _ = gap(t)
    h = 2 * math.pi / 72
    est = (np.roll(g, 2) - 8 * np.roll(g, 1) + 8 * np.roll(g, -1) - np.roll(g, -2)) / (12 * h)
    assert conv["max abs error [unit of quantity]"].iloc[1] == pytest.approx(W * np.abs(est - g1).max(), rel=1e-7)
    assert conv["observed order [-]"].iloc[1] == pytest.approx(4.0, abs=0.1)


def test_the_tolerance_table_of_mu_starts_from_the_closed_form(four_bar):
    table = report.tolerance_table(four_bar, omega=W, quantity="mu", check_angle=math.radians(100),
                                   points_per_turn=72)
    with mp.workdps(30):
        d1 = float(mp.diff(mu_closed, mp.radians(100)))
        d2 = float(mp.diff(mu_closed, mp.radians(100), 2))
    assert table["omega_mu at theta2 = 100 deg [rad/s]"].iloc[0] == pytest.approx(W * d1, abs=1e-11)
    assert table["alpha_mu at theta2 = 100 deg [rad/s^2]"].iloc[0] == pytest.approx(W**2 * d2, abs=1e-9)
    tight = table[table["rule"] == "numkin, tol = 1e-12"].iloc[0]
    assert tight[MU_ESTIMATE] < 1e-12
    loose = table[table["rule"] == "residual"].iloc[0]
    assert loose[MU_ESTIMATE] > 1e-9  # the loose rule leaves a visible step


# ----------------------------------------------------------------- a scene, through the command
SCENE = """
[scene]
description = "the transmission angle's error tables"

[mechanism]
linkage = "four_bar"
dimensions = { ground = 4, crank = 1, coupler = 3, rocker = 3 }
quantities = { mu = { expression = "theta4 - theta3", dimension = "angle" } }

[input]
speed = "10 rad/s"

[report]
quantity = "QUANTITY"
check_deg = 90
grids = [36, 72]
schemes = ["centred", "second_difference"]
points_per_turn = 36
"""


def test_numkin_report_of_a_scene_studying_mu(tmp_path, capsys, mu_convergence):
    from numkin import cli

    path = tmp_path / "mu.toml"
    path.write_text(SCENE.replace("QUANTITY", "mu"))
    out = tmp_path / "out"
    assert cli.main(["report", str(path), "--out", str(out)]) == 0
    capsys.readouterr()
    conv = pd.read_csv(out / "mu-convergence.csv")
    assert set(conv["quantity"]) == {"omega_mu [rad/s]", "alpha_mu [rad/s^2]"}
    # the same errors as the Python function on the same grids (checked above against the closed form)
    for _, row in conv.iterrows():
        same = mu_convergence[(mu_convergence["scheme"] == row["scheme"])
                              & (mu_convergence["points per turn"] == row["points per turn"])].iloc[0]
        assert row["max abs error [unit of quantity]"] == pytest.approx(same["max abs error [unit of quantity]"],
                                                                         rel=1e-12)
    assert "mu = theta4 - theta3" in (out / "mu-convergence.md").read_text()
    roundoff = pd.read_csv(out / "mu-roundoff.csv")
    with mp.workdps(30):
        d1 = float(mp.diff(mu_closed, mp.pi / 2))
    assert roundoff[roundoff["quantity"] == "dmu/dtheta2 [rad/rad]"]["exact value [unit of quantity]"].iloc[0] \
        == pytest.approx(d1, abs=1e-12)
    for name in ("work_precision", "tolerance", "newton", "jacobian"):
        assert (out / f"mu-{name}.csv").exists()


def test_a_scene_refuses_a_report_quantity_it_does_not_have(tmp_path, capsys):
    from numkin import cli

    path = tmp_path / "nu.toml"
    path.write_text(SCENE.replace("QUANTITY", "nu"))
    assert cli.main(["report", str(path)]) != 0
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "[report] quantity" in err and "'nu' is neither an unknown nor a derived quantity" in err
    assert "mu" in err and "theta3, theta4" in err


# ----------------------------------------------------------------- refusals
def test_the_tables_refuse_a_name_that_is_neither(four_bar):
    for table in (report.convergence_table, report.work_precision_table, report.tolerance_table):
        with pytest.raises(InputError, match=r"'nu' is neither an unknown nor a derived quantity.*\['mu'\]"):
            table(four_bar, omega=W, quantity="nu", check_angle=0.0) if table is report.tolerance_table else \
                table(four_bar, omega=W, quantity="nu")
    with pytest.raises(InputError, match="neither an unknown nor a derived quantity"):
        report.roundoff_table(four_bar, quantity="x_B", check_angle=0.0)


def test_a_quantity_undefined_on_part_of_the_sweep_is_refused_by_name():
    """sqrt(x - 250): the piston's x is below 250 mm over part of the turn; no table of NaN."""
    mech = linkages.slider_crank(R, L).add_quantities({"root": ("sqrt(x - 250)", "length")})
    with pytest.raises(InputError, match=r"the value of the quantity 'root = sqrt\(x - 250\)' is not finite at input"):
        report.convergence_table(mech, omega=W, quantity="root", grids=(36,), schemes=("centred",))


def test_the_roundoff_table_near_a_domain_edge_blanks_the_steps_that_leave_it():
    """sqrt(x - 250) at 40 deg: x = 250 mm near 45.7 deg, so the stencils at h = 0.1 rad reach where it is
    undefined; the smaller steps stand, the centred difference at h = 0.01 written out here."""
    mech = linkages.slider_crank(R, L).add_quantities({"root": ("sqrt(x - 250)", "length")})
    theta = math.radians(40)
    ro = report.roundoff_table(mech, quantity="root", check_angle=theta, schemes=("centred", "complex_step"))

    def root(t):
        return mp.sqrt(R * mp.cos(t) + mp.sqrt(L**2 - R**2 * mp.sin(t) ** 2) - 250)

    centred = ro.iloc[0]
    assert math.isnan(centred["rel error at h = 1e-01 rad [-]"])
    h = (theta + 1e-2) - theta
    with mp.workdps(30):
        exact = mp.diff(root, mp.mpf(theta))
        by_hand = (root(mp.mpf(theta) + h) - root(mp.mpf(theta) - h)) / (2 * h)
        assert centred["rel error at h = 1e-02 rad [-]"] == pytest.approx(float(abs(by_hand - exact) / abs(exact)),
                                                                          rel=1e-6)
    assert np.isfinite(ro.iloc[1]["rel error at h = 1e-01 rad [-]"])  # the complex step samples no other input
    assert "outside its domain" in ro.attrs["caption"]


def test_a_wrapped_derived_angle_warns_once_per_table():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"ang": ("atan2(r2*sin(theta2), r2*cos(theta2) - r1)",
                                                                 "angle")})
    with pytest.warns(UserWarning, match="wrapped data") as caught:
        report.convergence_table(mech, omega=W, quantity="ang", grids=(36, 72), schemes=("centred", "five_point"))
    assert sum("wrapped data" in str(w.message) for w in caught) == 1


def test_an_angle_reduced_by_atan2_is_differenced_across_its_cut():
    """The direction of the crank pin seen from the rocker pivot, atan2(sin t, cos t - 4), jumps from pi to -pi at
    t = 180 deg; its derivative (1 - 4 cos t) / (17 - 8 cos t), by hand, is smooth there."""
    ang = ("atan2(r2*sin(theta2), r2*cos(theta2) - r1)", "angle")
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"ang": ang})
    ro = report.roundoff_table(mech, quantity="ang", check_angle=math.pi, schemes=("centred",))
    h = ro.attrs["steps"]["rel error at h = 1e-02 rad [-]"]
    h = (math.pi + h) - math.pi
    closed = np.unwrap(np.arctan2(np.sin([math.pi - h, math.pi + h]), np.cos([math.pi - h, math.pi + h]) - 4))
    by_hand = (closed[1] - closed[0]) / (2 * h)
    assert ro["exact value [unit of quantity]"].iloc[0] == pytest.approx(0.2, rel=1e-13)
    assert ro["rel error at h = 1e-02 rad [-]"].iloc[0] == pytest.approx(abs(by_hand - 0.2) / 0.2, rel=1e-6)
    with pytest.warns(UserWarning, match="jump by more than 180"):
        conv = report.convergence_table(mech, omega=W, quantity="ang", grids=(72,), schemes=("centred",))
    t = np.linspace(0.0, 2 * np.pi, 73)[:-1]
    y = np.unwrap(np.arctan2(np.sin(t), np.cos(t) - 4))  # returns to its start: it does not turn
    est = (np.roll(y, -1) - np.roll(y, 1)) / (2 * (t[1] - t[0]))
    exact = (1 - 4 * np.cos(t)) / (17 - 8 * np.cos(t))
    assert conv["max abs error [unit of quantity]"].iloc[0] == pytest.approx(W * np.abs(est - exact).max(), rel=1e-8)


def test_a_derived_quantity_equal_to_an_unknown_has_that_unknowns_tables():
    """t4 = theta4 declared as a derived quantity: every error is the unknown's own (the same samples, the same
    rates), whatever path the tables take for it; only the work counts its expression's evaluations."""
    mech = linkages.slider_crank(R, L).add_quantities({"t3": ("theta3", "angle"), "xx": ("x", "length")})
    for unknown, derived in (("theta3", "t3"), ("x", "xx")):
        kwargs = dict(omega=W, grids=(36, 72), schemes=("centred", "five_point_second"))
        a = report.convergence_table(mech, quantity=unknown, **kwargs)
        b = report.convergence_table(mech, quantity=derived, **kwargs)
        errors = [c for c in a.columns if c.startswith(("max ", "RMS ", "observed "))]
        np.testing.assert_allclose(b[errors].to_numpy(), a[errors].to_numpy(), rtol=1e-12, atol=0)
        ro_a = report.roundoff_table(mech, quantity=unknown, check_angle=math.radians(50))
        ro_b = report.roundoff_table(mech, quantity=derived, check_angle=math.radians(50))
        steps = list(ro_a.attrs["steps"])
        np.testing.assert_allclose(ro_b[steps].to_numpy(), ro_a[steps].to_numpy(), rtol=1e-12, atol=0)


# ----------------------------------------------------------------- quantities that do not return to their start
NOT_CLOSING = {"half": ("theta2/2 + theta3", "angle"), "arc": ("r2*theta2", "length"), "phi2": ("theta2 - pi/2", "angle")}


@pytest.fixture(scope="module")
def gear():
    """half (a gear 1:2 on the crank, plus the coupler's angle), arc (a rack and pinion), phi2 (another convention)."""
    return linkages.four_bar(4, 1, 3, 3).add_quantities(NOT_CLOSING)


def half_closed(t):
    return t / 2 + _four_bar(t)[0]


def closed_samples(f, t):
    """f, df/dt, d2f/dt2 at the inputs `t` (rad) by mpmath at 30 digits; the values unwrapped."""
    with mp.workdps(30):
        x = [mp.mpf(float(v)) for v in t]
        values = np.unwrap(np.array([float(f(v)) for v in x]))
        d1 = np.array([float(mp.diff(f, v)) for v in x])
        d2 = np.array([float(mp.diff(f, v, 2)) for v in x])
    return values, d1, d2


def centred_open(y, h):
    """The centred difference on an open grid, written out: (y[i+1] - y[i-1]) / 2h inside, the second-order
    one-sided (-3 y0 + 4 y1 - y2) / 2h and (3 yN - 4 yN-1 + yN-2) / 2h at the ends."""
    out = np.empty_like(y)
    out[1:-1] = (y[2:] - y[:-2]) / (2 * h)
    out[0] = (-3 * y[0] + 4 * y[1] - y[2]) / (2 * h)
    out[-1] = (3 * y[-1] - 4 * y[-2] + y[-3]) / (2 * h)
    return out


def test_a_quantity_that_does_not_close_is_differenced_on_an_open_grid_over_all_its_points(gear):
    """half gains half a turn per turn of the crank: its full turn is an open grid of N + 1 points, the statistics
    over the points 1..N-1 where the centred stencil applies, the two ends in their own column."""
    table = report.convergence_table(gear, omega=W, quantity="half", grids=(36,), schemes=("centred",),
                                     check_angle=0.0)
    t = np.linspace(0.0, 2 * np.pi, 37)
    y, d1, _ = closed_samples(half_closed, t)
    err = W * np.abs(centred_open(y, t[1]) - d1)
    row = table.iloc[0]
    assert row["max abs error [unit of quantity]"] == pytest.approx(err[1:-1].max(), rel=1e-8)  # 0.037942
    assert row["RMS abs error [unit of quantity]"] == pytest.approx(np.sqrt(np.mean(err[1:-1] ** 2)), rel=1e-8)
    assert row["max rel error [-]"] == pytest.approx(err[1:-1].max() / (W * np.abs(d1).max()), rel=1e-8)
    assert row["ends abs error [unit of quantity]"] == pytest.approx(max(err[0], err[-1]), rel=1e-8)
    assert row["abs error at theta2 = 0 deg [unit of quantity]"] == pytest.approx(err[0], rel=1e-8)
    caption = table.attrs["caption"]
    assert "half does not return to its start" in caption and "open grid" in caption
    # the work-precision table takes the same points, and counts a stencil at each of the 37
    wp = report.work_precision_table(gear, omega=W, quantity="half", grids=(36,), schemes=("centred",))
    centred = wp[wp["method"] == "centred"].iloc[0]
    assert centred["max abs error [unit of quantity]"] == pytest.approx(err[1:-1].max(), rel=1e-8)
    assert centred["derivative work [evaluations]"] == 37 + 37  # stencils + the expression at every input
    with pytest.raises(InputError, match="spectral"):
        report.convergence_table(gear, omega=W, quantity="half", grids=(36,), schemes=("spectral",))


def test_the_tolerance_table_of_a_quantity_that_does_not_close(gear):
    """Every row of half differenced as an open grid: the tight row's largest errors are the closed form's
    centred and second differences inside the grid (not the jump of a turn closed by force)."""
    table = report.tolerance_table(gear, omega=W, quantity="half", check_angle=math.radians(30), points_per_turn=36)
    t = np.linspace(0.0, 2 * np.pi, 37)
    h = t[1]
    y, d1, d2 = closed_samples(half_closed, t)
    e1 = np.abs(centred_open(y, h) - d1)[1:-1]
    e2 = np.abs((y[2:] - 2 * y[1:-1] + y[:-2]) / h**2 - d2[1:-1])
    for rule in table["rule"][1:]:  # the loose rules' own position errors (<= 3e-6 rad) move them a little
        row = table[table["rule"] == rule].iloc[0]
        close = 1e-8 if rule == "numkin, tol = 1e-12" else 1e-2
        assert row["omega_half max rel error [%]"] == pytest.approx(100 * e1.max() / np.abs(d1).max(), rel=close)
        assert row["alpha_half max rel error [%]"] == pytest.approx(100 * e2.max() / np.abs(d2).max(), rel=close)
    assert "half does not return to its start" in table.attrs["caption"]


def test_a_quantity_with_a_zero_second_derivative_leaves_its_relative_error_blank(gear):
    """arc = r2*theta2 and phi2 = theta2 - pi/2 are linear in the input: every difference of them is exact, the
    exact second derivative is 0 and a relative error of it is undefined."""
    for q in ("arc", "phi2"):
        conv = report.convergence_table(gear, omega=W, quantity=q, grids=(36, 72))  # every scheme
        first = conv[conv["quantity"].str.startswith(("v_", "omega_"))]
        second = conv[conv["quantity"].str.startswith(("a_", "alpha_"))]
        assert first["max rel error [-]"].max() < 1e-12  # exact: the slope is r2 = 1 (or 1)
        assert second["max rel error [-]"].isna().all() and second["max abs error [unit of quantity]"].max() < 1e-9
        assert "is 0 over the whole sweep" in conv.attrs["caption"]
        wp = report.work_precision_table(gear, omega=W, quantity=q, grids=(36,))
        assert wp[wp["quantity"].str.startswith(("a_", "alpha_"))]["max rel error [-]"].isna().all()
        assert "is 0 over the whole sweep" in wp.attrs["caption"]
    tol = report.tolerance_table(gear, omega=W, quantity="arc", check_angle=math.radians(30), points_per_turn=36)
    loose = tol.iloc[1:]
    assert loose["v_arc max rel error [%]"].max() < 1e-9  # a centred difference of a line is exact
    assert loose["a_arc max rel error [%]"].isna().all()
    assert tol["v_arc at theta2 = 30 deg [mm/s]"].iloc[1:].to_numpy() == pytest.approx(W * 1.0, rel=1e-12)


def test_the_complex_step_row_is_the_complex_step_of_the_quantity_itself():
    """Im(gap(theta + i h)) / h of gap = sqrt(l^2 - r^2 sin^2 theta), by mpmath in complex arithmetic: the same
    for the two ways of writing gap, and not the exact value (at h = 0.1 it errs by O(h^2)); abs() is not
    analytic: no complex step through it."""
    mech = linkages.slider_crank(R, L).add_quantities({
        "gap": ("x - r*cos(theta)", "length"), "gap2": ("sqrt(l**2 - r**2*sin(theta)**2)", "length"),
        "dist": ("abs(x - 250)", "length")})
    theta = math.radians(60)

    def gap(z):
        return mp.sqrt(L**2 - R**2 * mp.sin(z) ** 2)

    for name in ("gap", "gap2"):
        ro = report.roundoff_table(mech, quantity=name, check_angle=theta, schemes=("complex_step",))
        row = ro.iloc[0]
        with mp.workdps(50):
            exact = mp.diff(gap, mp.mpf(theta))
            assert row["exact value [unit of quantity]"] == pytest.approx(float(exact), rel=1e-13)
            for column, h in ro.attrs["steps"].items():
                h = (theta + h) - theta  # the table's representable step
                step = mp.im(gap(mp.mpf(theta) + 1j * mp.mpf(h))) / h
                want = float(abs(step - exact) / abs(exact))
                assert row[column] == pytest.approx(want, rel=1e-6, abs=1e-15), column
        assert row["rel error at h = 1e-01 rad [-]"] == pytest.approx(7.108e-3, rel=1e-3)
    ro = report.roundoff_table(mech, quantity="dist", check_angle=theta, schemes=("centred", "complex_step"))
    steps = list(ro.attrs["steps"])
    assert ro[steps].iloc[1].isna().all() and ro[steps].iloc[0].notna().all()
    assert "not analytic (Abs)" in ro.attrs["caption"]


# ----------------------------------------------------------------- the tolerance table's error columns
def _mu_of(mech, sweep):
    theta3, theta4 = (sweep.values[mech.unknowns.index(u)] for u in ("theta3", "theta4"))
    return np.unwrap(theta4 - theta3)


def test_the_tolerance_table_of_mu_differences_each_loose_sweep_as_written_out(four_bar):
    """Turning backwards (omega < 0): each loosely solved sweep's mu, differenced here by the periodic centred and
    second differences, gives the row's velocity and acceleration at the check angle and its largest relative
    errors against the closed form; its error estimate is the distance of its mu from the closed form's."""
    n, k, w = 72, 20, -W  # the check angle 100 deg is point 20
    table = report.tolerance_table(four_bar, omega=w, quantity="mu", check_angle=math.radians(100),
                                   points_per_turn=n)
    t = np.linspace(0.0, 2 * np.pi, n + 1)
    h = t[1]
    exact, d1, d2 = closed_samples(mu_closed, t[:-1])
    analytic = table.iloc[0]
    assert analytic["omega_mu at theta2 = 100 deg [rad/s]"] == pytest.approx(w * d1[k], rel=1e-11)
    assert analytic["alpha_mu at theta2 = 100 deg [rad/s^2]"] == pytest.approx(w * w * d2[k], rel=1e-10)
    for rule in report.STUDENT_RULES:
        sweep = report.student_sweep(four_bar, t, rule=rule, tol=1e-4)
        y = _mu_of(four_bar, sweep)[:-1]  # mu returns to its value after the turn: periodic, the last point apart
        c1 = w * (np.roll(y, -1) - np.roll(y, 1)) / (2 * h)
        c2 = w * w * (np.roll(y, -1) - 2 * y + np.roll(y, 1)) / h**2
        row = table.iloc[1 + report.STUDENT_RULES.index(rule)]
        assert row["omega_mu at theta2 = 100 deg [rad/s]"] == pytest.approx(c1[k], rel=1e-9), rule
        assert row["alpha_mu at theta2 = 100 deg [rad/s^2]"] == pytest.approx(c2[k], rel=1e-9), rule
        assert row["omega_mu rel error at theta2 = 100 deg [%]"] == pytest.approx(
            100 * abs(c1[k] - w * d1[k]) / abs(w * d1[k]), rel=1e-6)
        assert row["omega_mu max rel error [%]"] == pytest.approx(
            100 * np.abs(c1 - w * d1).max() / np.abs(w * d1).max(), rel=1e-6), rule
        assert row["alpha_mu max rel error [%]"] == pytest.approx(
            100 * np.abs(c2 - w * w * d2).max() / np.abs(w * w * d2).max(), rel=1e-6), rule
        missed = np.abs(y - exact).max()  # Newton converges fast: one more step takes nearly all of it
        if missed > 1e-9:
            assert row[MU_ESTIMATE] == pytest.approx(missed, rel=1e-2), rule
        else:
            assert row[MU_ESTIMATE] < 1e-9


def test_open_grids_take_end_stencils_in_their_own_column(four_bar):
    """A part of a turn, 30 to 150 deg: the centred difference's statistics over the points 1..N-1, the one-sided
    second-order ends apart; in the tolerance table the check angle 30 deg is an end point, whose value is the end
    stencil's."""
    start, span = math.radians(30), math.radians(120)
    conv = report.convergence_table(four_bar, omega=-W, quantity="mu", grids=(72,), schemes=("centred",),
                                    start=start, span=span, check_angle=start)
    t = start + 2 * np.pi / 72 * np.arange(25)
    y, d1, _ = closed_samples(mu_closed, t)
    est = centred_open(y, t[1] - t[0])
    err = W * np.abs(est - d1)
    row = conv.iloc[0]
    assert row["max abs error [unit of quantity]"] == pytest.approx(err[1:-1].max(), rel=1e-8)
    assert row["ends abs error [unit of quantity]"] == pytest.approx(max(err[0], err[-1]), rel=1e-8)
    assert row["abs error at theta2 = 30 deg [unit of quantity]"] == pytest.approx(err[0], rel=1e-8)
    tol = report.tolerance_table(four_bar, omega=W, quantity="mu", check_angle=start, points_per_turn=72,
                                 start=start, span=span)
    tight = tol[tol["rule"] == "numkin, tol = 1e-12"].iloc[0]
    assert tight["omega_mu at theta2 = 30 deg [rad/s]"] == pytest.approx(W * est[0], rel=1e-9)
    assert tight["omega_mu max rel error [%]"] == pytest.approx(100 * err[1:-1].max() / (W * np.abs(d1).max()),
                                                                 rel=1e-7)
    assert "end point" in tol.attrs["caption"]


def test_a_quantity_within_the_closure_tolerance_keeps_its_own_small_gap_in_the_tolerance_table():
    """apx = theta3 + 1.5e-8 theta2 closes within 1e-7 rad (its end misses its start by 9.4e-8): its second
    difference is theta3's (the linear term has none), so the tight row's largest relative error of alpha is
    the periodic second difference of theta3 from the closed form; a period closed by force to whole turns
    puts the 9.4e-8 gap into a jump of gap / h^2 at the ends of the turn."""
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"apx": ("theta3 + 1.5e-8*theta2", "angle")})
    table = report.tolerance_table(mech, omega=W, quantity="apx", check_angle=0.0, points_per_turn=360)
    tight = table[table["rule"] == "numkin, tol = 1e-12"].iloc[0]
    with mp.workdps(30):
        t = [2 * mp.pi * k / 360 for k in range(360)]
        y = np.array([float(_four_bar(x)[0]) for x in t])
        d2 = np.array([float(mp.diff(lambda s: _four_bar(s)[0], x, 2)) for x in t])
    y = np.unwrap(y)
    h = 2 * math.pi / 360
    second = (np.roll(y, -1) - 2 * y + np.roll(y, 1)) / h**2  # periodic: theta3 closes after the turn
    expected = 100 * np.abs(second - d2).max() / np.abs(d2).max()
    assert tight["alpha_apx max rel error [%]"] == pytest.approx(expected, rel=1e-4)


def test_the_spectral_refusal_gives_a_length_gap_in_its_unit():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"arc": ("r2*theta2", "length")})
    with pytest.raises(InputError, match=r"arc misses it by 6\.28319 mm: leave the spectral schemes out"):
        report.convergence_table(mech, omega=W, quantity="arc", grids=(36,), schemes=("spectral",))


def test_a_derived_angle_turning_more_than_half_a_turn_per_step_is_studied_as_it_turns():
    """f = 20 theta2 + 0.1 sin(theta2) turns 200° per step of the 36-point grid: the report differences it as it
    turns (its tangent says so), so the centred difference's error is its truncation error alone,
    0.1 omega cos(theta2) (1 - sin(h)/h), largest at theta2 = 0 (hand derivation)."""
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"f": ("20*theta2 + 0.1*sin(theta2)", "angle")})
    with pytest.warns(UserWarning, match="too coarse"):
        table = report.convergence_table(mech, omega=2.0, quantity="f", grids=(36, 72), schemes=("centred",))
    row = table.set_index("points per turn").loc[36]
    h = 2 * math.pi / 36
    assert row["max abs error [unit of quantity]"] == pytest.approx(0.1 * 2.0 * (1 - math.sin(h) / h), rel=1e-6)

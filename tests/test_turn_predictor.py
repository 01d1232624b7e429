"""The batch's predictor round a whole turn: the trigonometric polynomial through the nodes.

References: trigonometric polynomials (with whole turns added) that the fit must
reproduce exactly, functions whose harmonics fall off slowly or that do not repeat
after a turn (the fit must refuse them), and the four-bar's closed form by circle
intersection computed here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import numkin.batch_fill as batch_fill
from numkin import linkages
from numkin.batch_fill import nodes_of
from numkin.march import Continuation
from numkin.turn_predictor import TURN_TRUST, turn_predict

THIRTY = math.radians(30.0)


def _four_bar_closed_form(t2, r1, r2, r3, r4):
    """Open-branch (theta3, theta4) by circle intersection in complex numbers, continuous in t2."""
    a = r2 * np.exp(1j * t2)
    to_o4 = r1 - a
    d = np.abs(to_o4)
    t3 = np.angle(to_o4) + np.arccos((r3 * r3 + d * d - r4 * r4) / (2.0 * r3 * d))
    t4 = np.angle(a + r3 * np.exp(1j * t3) - r1)
    return np.unwrap(t3), np.unwrap(t4)


def _trig(t, turns=0):
    """Harmonics up to 5 (values, tangents), plus `turns` whole turns per turn of t."""
    x = 0.3 + 0.5 * np.cos(t) - 0.2 * np.sin(2 * t) + 0.05 * np.cos(5 * t + 0.4) + turns * t
    d = -0.5 * np.sin(t) - 0.4 * np.cos(2 * t) - 0.25 * np.sin(5 * t + 0.4) + turns
    return x, d


@pytest.mark.parametrize("t", [
    np.radians(np.arange(0.0, 361.0)),  # a whole turn: the node one turn on gives the gain
    np.radians(np.arange(0.0, 360.0)),  # one step short: the gain from the last nodes' tangents
    np.radians(np.arange(360.0, -1.0, -1.0)),  # backwards
    1.0 + np.radians(np.arange(0.0, 361.0, 0.5)),  # from 1 rad, in half degrees
    np.radians(np.arange(0.0, 721.0)),  # two turns
    np.radians(np.arange(0.0, 365.0)),  # a turn and 4 steps
    np.linspace(0.0, 2 * math.pi, 36001),  # 0.01°
])
def test_trigonometric_polynomials_and_whole_turns_are_reproduced(t):
    (a, da), (b, db), (c, dc) = _trig(t), _trig(t, 1), _trig(t, -2)
    X, D = np.vstack([a, b, 40.0 * c - 40.0 * (-2) * t]), np.vstack([da, db, 40.0 * dc + 80.0])  # a length: no turns
    nodes = nodes_of(t, THIRTY)
    got = turn_predict(t, X, D, nodes, angle_rows=[0, 1], inv_xs=[1.0, 1.0, 1 / 40.0])
    assert got is not None
    np.testing.assert_allclose(got, X, rtol=0, atol=1e-12)


def test_not_applied_where_the_grid_does_not_go_round_evenly():
    def pred(t, step=THIRTY, even=True, f=_trig):
        x, d = f(t)
        return turn_predict(t, x[None, :], d[None, :], nodes_of(t, step), angle_rows=[0], inv_xs=[1.0], even=even)

    full = np.radians(np.arange(0.0, 361.0))
    assert pred(full) is not None
    assert pred(full, even=False) is None  # the caller found the steps uneven
    assert pred(np.radians(np.arange(0.0, 181.0))) is None  # half a turn
    assert pred(np.radians(np.arange(0.0, 361.0, 7.0))) is None  # 7° steps: no whole number of them to a turn
    assert pred(full, step=math.radians(7.5)) is None  # nodes every 7 steps: 7 does not divide 360
    assert pred(full, step=math.radians(90.0)) is None  # 4 nodes round the turn: too few to judge the fit by
    assert pred(full, step=math.radians(10.0)) is None  # 36 nodes: more than the fit's matrices are built for
    assert pred(full, step=math.radians(15.0)) is not None  # 24


def test_refused_where_its_highest_harmonics_are_large_or_the_function_does_not_repeat():
    t = np.radians(np.arange(0.0, 361.0))
    nodes = nodes_of(t, THIRTY)

    def pred(x, d, angle=True):
        return turn_predict(t, x[None, :], d[None, :], nodes, angle_rows=[0] if angle else [], inv_xs=[1.0])

    # 1 / (1.2 - cos t): harmonics fall off as 0.54^k, 1.6e-3 at k = 11
    assert pred(1 / (1.2 - np.cos(t)), -np.sin(t) / (1.2 - np.cos(t)) ** 2) is None
    # |sin t|^3: a jump in the third derivative, harmonics as k^-4
    assert pred(np.abs(np.sin(t)) ** 3, 3 * np.sin(t) * np.abs(np.sin(t)) * np.cos(t)) is None
    # half a turn per turn, and a length that grows: smooth on the nodes, but wrong one turn on
    assert pred(t / 2, np.full_like(t, 0.5)) is None
    assert pred(t, np.ones_like(t), angle=False) is None
    # a tangent unknown at a node (a singular one): no fit, on a grid with the node one turn on or without
    for grid in (t, t[:-1]):
        x, d = _trig(grid, 1)
        d[nodes_of(grid, THIRTY)[-2]] = np.nan
        assert turn_predict(grid, x[None, :], d[None, :], nodes_of(grid, THIRTY), angle_rows=[0], inv_xs=[1.0]) is None
    # the same half turn on a grid that stops a step short (no node one turn on): the last node refuses it
    s = t[:-1]
    assert turn_predict(s, (s / 2)[None, :], np.full((1, s.size), 0.5), nodes_of(s, THIRTY), angle_rows=[0],
                        inv_xs=[1.0]) is None
    # each of the three highest harmonics at 12 nodes (9, 10, 11; represented exactly, but as large as 1e-3)
    for k in (9, 10, 11):
        assert pred(np.cos(t) + 1e-3 * np.cos(k * t), -np.sin(t) - 1e-3 * k * np.sin(k * t)) is None
        assert pred(np.cos(t) + 1e-7 * np.cos(k * t), -np.sin(t) - 1e-7 * k * np.sin(k * t)) is not None
    # harmonics 4, 8, 12 and 16 only (a crank geared 4 to 1): 9 to 11 are zero, but 12 shows in sin 12t
    x = 0.3 * np.sin(4 * t) + 0.05 * np.cos(8 * t) + 0.01 * np.sin(12 * t) + 0.002 * np.cos(16 * t)
    d = 1.2 * np.cos(4 * t) - 0.4 * np.sin(8 * t) + 0.12 * np.cos(12 * t) - 0.032 * np.sin(16 * t)
    assert pred(x, d) is None
    # a fast harmonic the nodes cannot see (cos 12t at 30° nodes is 1 at every one): the tangents are zero
    # there too, so nothing can tell it; such a linkage is caught by Newton (one step falls short)
    assert pred(np.cos(12 * t), -12 * np.sin(12 * t)) is not None


def _four_bar_fit(r1, r2, r3, r4):
    """A four-bar on a 1° grid round a turn: the grid, its closed-form angles (2, N), the nodes, the
    fit through the closed form's values and the tangents numkin's continuation finds there, and the
    mechanism."""
    t = np.radians(np.arange(0.0, 361.0))
    X = np.vstack(_four_bar_closed_form(t, r1, r2, r3, r4))
    mech = linkages.four_bar(r1, r2, r3, r4)
    ctx = Continuation(mech, "symbolic", 1e-12, THIRTY, "raise")
    nodes = nodes_of(t, THIRTY)
    D = np.full_like(X, np.nan)
    for j in nodes:
        D[:, j] = ctx.local1(ctx.eval1(X[:, j].tolist(), float(t[j])))[0]
    return t, X, nodes, turn_predict(t, X, D, nodes, angle_rows=ctx.angle_idx, inv_xs=ctx.inv_xs), mech


def test_the_four_bar_is_predicted_to_1e_8_and_takes_one_newton_step():
    t, X, nodes, pred, mech = _four_bar_fit(4, 1, 3, 3)
    assert pred is not None and np.abs(pred - X).max() < 1e-8  # (the quintic: 4.3e-5)
    sweep = mech.sweep(t)
    fine = np.setdiff1d(np.arange(t.size), nodes)
    assert np.abs(sweep.values - X).max() < 1e-13
    assert sweep.iterations[fine].max() == 1


def test_a_four_bar_near_its_change_point_keeps_the_hermite_predictors():
    # 1 + 4 = 5 against 3 + 2.05: a crank-rocker close to the change point; its harmonics fall off slowly
    t, X, _, pred, mech = _four_bar_fit(4, 1, 3, 2.05)
    assert pred is None
    assert np.abs(mech.sweep(t).values - X).max() < 1e-12


@pytest.mark.parametrize("build", [
    lambda: linkages.four_bar(4, 1, 3, 3), lambda: linkages.four_bar(4, 1, 3, 3, branch="crossed"),
    lambda: linkages.slider_crank(80, 200, 20), linkages.six_bar, linkages.quick_return, linkages.chained_four_bars,
    lambda: linkages.four_bar(2, 4, 3.5, 4.5),  # a double crank: the coupler and rocker gain a turn per turn
])
@pytest.mark.parametrize("degrees", [np.arange(0.0, 361.0), np.arange(0.0, 360.0), np.arange(360.0, -1.0, -1.0)])
def test_sweeps_with_and_without_the_fit_agree(build, degrees, monkeypatch):
    t = np.radians(degrees)
    with_fit = build().sweep(t)
    monkeypatch.setattr(batch_fill, "TURN", False)
    hermite = build().sweep(t)
    mech = build()
    scale = np.where([u in mech.angles for u in mech.unknowns], 1.0, float(mech.length_scale))[:, None]
    assert np.abs((with_fit.values - hermite.values) / scale).max() < 1e-13
    assert np.abs(with_fit.cond - hermite.cond).max() <= 1e-11 * hermite.cond.max()
    assert with_fit.iterations.max() <= hermite.iterations.max()
    assert [e.kind for e in with_fit.events] == [e.kind for e in hermite.events]


@settings(max_examples=60, deadline=None)
@given(r2=st.floats(0.5, 1.5), r3=st.floats(2.0, 5.0), r4=st.floats(2.0, 5.0), r1=st.floats(2.0, 5.0))
def test_wherever_the_fit_is_trusted_it_is_within_its_bound_and_the_sweep_is_the_closed_form(r1, r2, r3, r4):
    # crank-rockers with the crank shortest and at least 0.05 from the change point (s + l < p + q)
    lengths = sorted([r1, r2, r3, r4])
    assume(r2 == lengths[0] and lengths[0] + lengths[3] <= lengths[1] + lengths[2] - 0.05)
    t, X, _, pred, mech = _four_bar_fit(r1, r2, r3, r4)
    if pred is not None:
        assert np.abs(pred - X).max() <= TURN_TRUST  # (its highest harmonics overestimate its error)
    sweep = mech.sweep(t)
    assert np.abs(sweep.values - X).max() < 1e-11

"""The continuation's predictors and its written-out scalar Newton.

References: polynomials the predictors must reproduce exactly (a cubic from
two points and their tangents, a quintic from two points with tangents and
curvatures), the four-bar's closed form by circle intersection computed
here, and the count of Newton iterations that quadratic convergence allows.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from numkin import batch_fill, linkages
from numkin.batch_fill import nodes_of
from numkin.march import Continuation
from numkin.predictors import QUINTIC_MIN_POINTS, hermite, node_curvatures, predict


def _cubic(t):
    return 0.1 * t**3 - 0.2 * t**2 + 0.05 * t, 0.3 * t**2 - 0.4 * t + 0.05


def test_march_predictor_is_exact_for_a_cubic_through_the_previous_tangent():
    (x0, d0), (x1, d1) = _cubic(0.0), _cubic(1.0)
    x2, _ = _cubic(1.5)
    rate = abs(d1)
    got = predict(1.0, [x1], [d1], 0.0, [x0], 1.5, None, rate, [d0])
    assert got[0] == pytest.approx(x2, abs=1e-15)
    # without the previous tangent: the quadratic through the previous point, wrong by the cubic term
    quad = predict(1.0, [x1], [d1], 0.0, [x0], 1.5, None, rate)
    assert abs(quad[0] - x2) > 1e-3


def test_march_predictor_falls_back_when_the_cubic_term_is_too_large():
    # a previous tangent far off: the cubic term exceeds the step times (1 + rate), so the quadratic is used
    got = predict(1.0, [0.0], [0.0], 0.0, [0.0], 1.5, None, 0.0, [50.0])
    assert got == [0.0]


def _quintic(t):
    c = [0.3, -0.2, 0.1, 0.05, -0.02, 0.004]
    x = sum(ck * t**k for k, ck in enumerate(c))
    d = sum(k * ck * t ** (k - 1) for k, ck in enumerate(c) if k)
    d2 = sum(k * (k - 1) * ck * t ** (k - 2) for k, ck in enumerate(c) if k > 1)
    return x, d, d2


def test_batch_predictor_is_exact_for_a_quintic_and_for_a_cubic():
    t = np.linspace(0.0, 2.0, 21)
    nodes = np.array([0, 10, 20])
    x, d, d2 = _quintic(t)
    X, D = x[None, :].copy(), d[None, :].copy()
    k = np.searchsorted(nodes, np.arange(t.size), side="right") - 1
    got = hermite(t, t, X, D, d2[None, nodes], nodes, k)
    np.testing.assert_allclose(got[0], x, rtol=0, atol=1e-14)
    # with the curvatures unknown: the cubic Hermite, exact for a cubic
    xc, dc = _cubic(t)
    got = hermite(t, t, xc[None, :].copy(), dc[None, :].copy(), np.full((1, 3), np.nan), nodes, k)
    np.testing.assert_allclose(got[0], xc, rtol=0, atol=1e-15)
    # one node without a curvature: its segments are cubic, the others quintic
    mixed = d2[None, nodes].copy()
    mixed[0, 2] = np.nan
    got = hermite(t, t, X, D, mixed, nodes, k)
    np.testing.assert_allclose(got[0, :11], x[:11], rtol=0, atol=1e-14)
    assert np.abs(got[0, 11:20] - x[11:20]).max() > 1e-6


def _four_bar_closed_form(t2, r1, r2, r3, r4):
    """Open-branch (theta3, theta4) of the four-bar, by intersecting the circles about A and O4."""
    ax, ay = r2 * np.cos(t2), r2 * np.sin(t2)
    dx, dy = r1 - ax, -ay
    d = np.hypot(dx, dy)
    gamma = np.arccos((r3**2 + d**2 - r4**2) / (2 * r3 * d))
    t3 = np.arctan2(dy, dx) + gamma
    t4 = np.arctan2(ay + r3 * np.sin(t3), ax + r3 * np.cos(t3) - r1)
    return t3, t4


def test_node_curvatures_match_a_finite_difference_of_the_closed_form():
    mech = linkages.four_bar(4, 1, 3, 3)
    t = np.radians(np.arange(0.0, 361.0, 1.0))
    sweep = mech.sweep(t)
    ctx = Continuation(mech, "symbolic", 1e-12, math.radians(30.0), "raise")
    nodes = nodes_of(t, math.radians(30.0))
    X = sweep.values.copy()
    h = 1e-4
    tn = t[nodes]
    closed = [np.unwrap(np.array(_four_bar_closed_form(tn + s * h, 4, 1, 3, 3))) for s in (-1, 0, 1)]
    D = np.full_like(X, np.nan)
    D[:, nodes] = (closed[2] - closed[0]) / (2 * h)
    d2_fd = (closed[2] - 2 * closed[1] + closed[0]) / h**2
    np.testing.assert_allclose(node_curvatures(ctx, t, X, D, nodes), d2_fd, rtol=0, atol=1e-5)


@pytest.mark.parametrize("n_points", [361, 36001])
def test_sweeps_with_either_predictor_agree_with_the_closed_form(n_points):
    # 361 points: cubic prediction (fewer than QUINTIC_MIN_POINTS per node); 36001: quintic
    assert (n_points >= QUINTIC_MIN_POINTS * 13) == (n_points == 36001)
    mech = linkages.four_bar(4, 1, 3, 3)
    t = np.linspace(0.0, 2 * math.pi, n_points)
    sweep = mech.sweep(t)
    t3, t4 = _four_bar_closed_form(t, 4, 1, 3, 3)
    for got, ref in ((sweep["theta3"], t3), (sweep["theta4"], t4)):
        assert np.abs(np.angle(np.exp(1j * (got - ref)))).max() < 1e-13
    assert sweep.iterations.max() <= 4


def test_written_out_newton_converges_quadratically_to_the_closed_form():
    mech = linkages.four_bar(4, 1, 3, 3)
    ctx = Continuation(mech, "symbolic", 1e-12, math.radians(30.0), "raise")
    assert mech.block_structure.newton1 is not None
    t2 = math.radians(40.0)
    t3, t4 = (float(v) for v in _four_bar_closed_form(np.array(t2), 4, 1, 3, 3))
    x, status, it, res, v = ctx.newton1([t3 + 0.01, t4 - 0.01], t2, 12)
    assert status == "converged"
    assert abs(x[0] - t3) < 1e-14 and abs(x[1] - t4) < 1e-14
    # from an error of 1e-2: about 1e-4, 1e-8, 1e-16 -- and a last step to see it
    assert 3 <= it <= 4
    assert res < 1e-14
    # det J = r3 r4 sin(theta3 - theta4): zero where theta3 = theta4, refused there and never divided by
    x, status, it, res, v = ctx.newton1([0.5, 0.5], t2, 12)
    assert (status, it, x) == ("singular", 0, [0.5, 0.5])


@pytest.mark.parametrize("written_out", [True, False])
def test_batch_newton_solves_active_columns_and_leaves_the_others(written_out, monkeypatch):
    # the batch Newton written out for the mechanism (few columns) and numkin.newton.solve_batch
    # (taken when it is absent, and for many columns) meet the same contract
    mech = linkages.four_bar(4, 1, 3, 3)
    assert mech.block_structure.newton_batch is not None
    if not written_out:
        monkeypatch.setattr(mech.block_structure, "newton_batch", None)
    ctx = Continuation(mech, "symbolic", 1e-12, math.radians(30.0), "raise")
    t = np.radians(np.linspace(5.0, 355.0, 50))
    t3, t4 = _four_bar_closed_form(t, 4, 1, 3, 3)
    x = np.vstack([t3 + 0.02 * np.sin(3 * t), t4 - 0.01])
    active = np.ones(t.size, dtype=bool)
    active[::7] = False  # kept as they are
    x[:, 3] = 0.5  # theta3 = theta4: det J = r3 r4 sin(theta3 - theta4) = 0, refused, never divided by
    start = x.copy()
    with np.errstate(all="ignore"):
        got, converged, iterations, f, jac = ctx.newton_batch(x.copy(), t, active)
    assert np.array_equal(got[:, ~active], start[:, ~active]) and not iterations[~active].any()
    assert not converged[3] and np.array_equal(got[:, 3], start[:, 3]) and iterations[3] == 0
    solved = active.copy()
    solved[3] = False
    assert converged[solved].all()
    assert np.abs(got[0, solved] - t3[solved]).max() < 1e-14 and np.abs(got[1, solved] - t4[solved]).max() < 1e-14
    # from errors of 1e-2: about 1e-4, 1e-8, 1e-16, and a last step to see it
    assert 3 <= iterations[solved].min() and iterations.max() <= 4
    # active=None: every column
    with np.errstate(all="ignore"):
        every = ctx.newton_batch(start.copy(), t, None)
    assert every[1].sum() == t.size - 1 and not every[1][3]
    # the residuals and Jacobian rows returned are those at the returned positions
    rows = mech.compiled.FJ_rows(got, t, mech.parameter_values)
    assert np.array_equal(f, np.array(rows[:2])) and all(np.array_equal(a, b) for a, b in zip(jac, rows[2:]))


def test_uniform_hermite_reproduces_a_quintic_and_a_cubic_on_an_even_grid():
    # q(t) = quintic with its exact values, tangents and curvatures at nodes every 6th input of 37
    from numkin.predictors import hermite_uniform, quintic_terms

    t = np.linspace(-1.0, 2.0, 37)
    nodes = np.arange(0, 37, 6)
    q = np.vstack([t**5 - 2 * t**3 + t, 0.5 * t**3 - t])
    d = np.vstack([5 * t**4 - 6 * t**2 + 1, 1.5 * t**2 - 1.0])
    d2 = np.vstack([20 * t**3 - 12 * t, 3.0 * t])
    X, D = q.copy(), d.copy()
    X[:, np.setdiff1d(np.arange(37), nodes)] = np.nan  # only the nodes are read
    D[:, np.setdiff1d(np.arange(37), nodes)] = np.nan
    got = hermite_uniform(t[nodes], X, D, 6, quintic_terms(t, X, D, d2[:, nodes], nodes))
    np.testing.assert_allclose(got, q, rtol=0, atol=1e-13)
    cubic = hermite_uniform(t[nodes], X, D, 6)  # values and tangents: exact for the cubic row only
    np.testing.assert_allclose(cubic[1], q[1], rtol=0, atol=1e-14)
    assert np.abs(cubic[0] - q[0]).max() > 1e-3


@pytest.mark.parametrize("build", [lambda: linkages.four_bar(4, 1, 3, 3), linkages.chained_four_bars,
                                   linkages.quick_return, lambda: linkages.slider_crank(80, 200, 20)])
def test_even_grid_prediction_gives_the_sweep_of_the_general_one_to_rounding(build, monkeypatch):
    import numkin.continuation as continuation

    mech = build()
    t = np.linspace(0.0, 2 * np.pi, 361)
    monkeypatch.setattr(batch_fill, "TURN", False)  # the Hermite predictors on this whole turn too
    even = mech.sweep(t)
    general_fill = continuation.fill
    monkeypatch.setattr(continuation, "fill", lambda *a, every=None, even=False: general_fill(*a, every=None))
    general = mech.sweep(t)
    scale = np.where([u in mech.angles for u in mech.unknowns], 1.0, float(mech.length_scale))[:, None]
    assert np.abs((even.values - general.values) / scale).max() < 1e-13
    np.testing.assert_array_equal(even.iterations, general.iterations)
    assert [e.kind for e in even.events] == [e.kind for e in general.events]

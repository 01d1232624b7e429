"""The batch between a sweep's nodes: its Newton iteration, free node curvatures, the quintic predictor.

References: the sweep's own solution (the batch must reach it column by
column), the four-bar's closed form (circle intersection), polynomials that
the Hermite predictors reproduce exactly, and ``numpy.linalg.cond``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import numkin.batch_fill as batch_fill
import numkin.predictors as predictors
from numkin import linkages
from numkin.batch_fill import nodes_of
from numkin.blocks import BlockStructure
from numkin.march import Continuation
from numkin.newton_rules import has_converged
from numkin.predictors import free_curvatures, free_quintic, hermite, quintic_pays, quintic_terms


def _four_bar_closed_form(t2, r1, r2, r3, r4):
    """Open-branch angles of coupler and rocker by circle intersection, in complex numbers (an independent
    reference): crank pin A, rocker pivot O4 = r1, the coupler turned from A->O4 by the triangle's angle."""
    a = r2 * np.exp(1j * t2)
    to_o4 = r1 - a
    d = np.abs(to_o4)
    t3 = np.angle(to_o4) + np.arccos((r3 * r3 + d * d - r4 * r4) / (2.0 * r3 * d))
    return t3, np.angle(a + r3 * np.exp(1j * t3) - r1)


def _wrapped(a, b):
    return np.abs(np.angle(np.exp(1j * (a - b))))


@pytest.mark.parametrize("build", [lambda: linkages.four_bar(4, 1, 3, 3), linkages.chained_four_bars])
def test_the_written_out_batch_moves_only_active_columns_each_to_its_root(build):
    mech = build()
    ctx = Continuation(mech, "symbolic", 1e-12, math.radians(30.0), "raise")
    t = np.radians(np.arange(0.0, 361.0, 1.0))
    exact = mech.sweep(t).values
    rng = np.random.default_rng(7)
    # most columns close to the root (two steps), a few far (more)
    active = np.ones(t.size, dtype=bool)
    active[::30] = False
    x0 = exact + rng.normal(scale=1e-6, size=exact.shape)
    far = rng.choice(np.flatnonzero(active), 40, replace=False)
    x0[:, far] += 0.02
    comp, bs = mech.compiled, mech.block_structure
    kargs = (*comp.fixed_terms(t, ctx.p), *ctx.pt)
    x_full = x0.copy()
    with np.errstate(all="ignore"):
        conv_f, sing_f, it_f, rows_f, calls = bs.newton_batch(comp.FJ_kernel, x_full, t, kargs, active, 12, ctx.fscale,
                                                              1e-12, 0.0, has_converged)
    assert conv_f[active].all() and not sing_f.any()
    assert not it_f[~active].any() and np.array_equal(x_full[:, ~active], x0[:, ~active])  # inactive: not moved
    assert it_f[far].min() > it_f[np.setdiff1d(np.flatnonzero(active), far)].max()  # the far ones take more steps
    assert calls == it_f.max() + 1  # kernel calls: the first evaluation and one per step
    assert _wrapped(x_full[:, active], exact[:, active]).max() < 1e-13


def test_stopping_rule_on_some_columns_is_the_rule_masked():
    rng = np.random.default_rng(3)
    res = 10.0 ** rng.uniform(-16, -9, 500)
    step = 10.0 ** rng.uniform(-16, -6, 500)
    prev = step * 10.0 ** rng.uniform(-1, 3, 500)
    where = rng.random(500) < 0.7
    for floor in (0.0, 1e-10):
        full = has_converged(res, step, prev, 1e-12, floor)
        assert np.array_equal(has_converged(res, step, prev, 1e-12, floor, where), full & where)
    # the scalar rule, one column at a time
    assert [has_converged(float(a), float(b), float(c), 1e-12) for a, b, c in zip(res, step, prev)] == list(
        has_converged(res, step, prev, 1e-12))


def _quintic(t):
    """A quintic's values, first and second derivatives at ``t``."""
    p = np.polynomial.Polynomial([0.7, 0.1, -0.3, 0.2, 0.03, -0.011])
    return p(t), p.deriv()(t), p.deriv(2)(t)


def test_free_curvatures_are_exact_for_a_quintic_on_uneven_nodes():
    t = np.array([0.0, 0.4, 0.9, 1.1, 1.5, 2.6, 3.0])
    x, d, d2 = _quintic(t)
    nodes = np.arange(t.size)
    got = free_curvatures(t, x[None, :], d[None, :], nodes)
    np.testing.assert_allclose(got[0], d2, rtol=0, atol=1e-12)
    # the weights kept per grid give the same quintic terms
    alpha, beta, gap = free_quintic(t, x[None, :], d[None, :], nodes)
    a2, b2 = quintic_terms(t, x[None, :], d[None, :], got, nodes)
    np.testing.assert_allclose(alpha, a2, rtol=0, atol=1e-13)
    np.testing.assert_allclose(beta, b2, rtol=0, atol=1e-13)
    np.testing.assert_allclose(gap, alpha + 0.5 * beta, rtol=0, atol=1e-13)
    assert free_curvatures(t[:2], x[None, :2], d[None, :2], nodes[:2]) is None


def test_free_curvatures_of_the_four_bar_err_by_order_h4():
    # the closed form's second derivative by central differences, at nodes 30 and 15 deg apart
    errors = []
    for step in (30.0, 15.0):
        t = np.radians(np.arange(0.0, 360.0 + step / 2, step))
        h = 1e-4
        closed = [np.unwrap(np.array(_four_bar_closed_form(t + s * h, 4, 1, 3, 3))) for s in (-1, 0, 1)]
        X, D = closed[1], (closed[2] - closed[0]) / (2 * h)
        d2 = (closed[2] - 2 * closed[1] + closed[0]) / h**2
        got = free_curvatures(t, X, D, np.arange(t.size))
        errors.append(np.abs(got - d2)[:, 1:-1].max())
    assert errors[0] < 0.05 and 10.0 < errors[0] / errors[1] < 25.0  # h^4: 16 times smaller at half the step


def test_quintic_from_terms_is_the_quintic_from_curvatures():
    t = np.linspace(0.0, 2.0, 21)
    nodes = np.array([0, 10, 20])
    x, d, d2 = _quintic(t)
    X, D = x[None, :].copy(), d[None, :].copy()
    k = np.searchsorted(nodes, np.arange(t.size), side="right") - 1
    by_terms = hermite(t, t, X, D, None, nodes, k, quintic_terms(t, X, D, d2[None, nodes], nodes))
    np.testing.assert_allclose(by_terms[0], x, rtol=0, atol=1e-14)
    mixed = d2[None, nodes].copy()
    mixed[0, 2] = np.nan  # the second segment cubic
    np.testing.assert_allclose(hermite(t, t, X, D, None, nodes, k, quintic_terms(t, X, D, mixed, nodes)),
                               hermite(t, t, X, D, mixed, nodes, k), rtol=0, atol=1e-14)


def test_hermite_rows_at_once_and_row_by_row_agree_bit_for_bit(monkeypatch):
    rng = np.random.default_rng(5)
    t = np.linspace(0.0, 3.0, 61)
    nodes = np.array([0, 20, 40, 60])
    X, D = rng.normal(size=(3, 61)), rng.normal(size=(3, 61))
    D2n = rng.normal(size=(3, 4))
    k = np.searchsorted(nodes, np.arange(t.size), side="right") - 1
    terms = quintic_terms(t, X, D, D2n, nodes)
    at_once = [hermite(t, t, X, D, c, nodes, k, tm) for c, tm in ((None, None), (D2n, None), (None, terms))]
    monkeypatch.setattr(predictors, "HERMITE_BLOCK", 0)
    by_row = [hermite(t, t, X, D, c, nodes, k, tm) for c, tm in ((None, None), (D2n, None), (None, terms))]
    assert all(np.array_equal(a, b) for a, b in zip(at_once, by_row))
    assert all(np.array_equal(a[:, nodes], X[:, nodes]) for a in at_once)  # the nodes themselves


def test_quintic_is_chosen_where_it_saves_an_iteration(monkeypatch):
    monkeypatch.setattr(batch_fill, "TURN", False)  # (round a whole turn, the trigonometric fit comes first)
    t = np.radians(np.arange(0.0, 361.0, 1.0))
    mech = linkages.four_bar(4, 1, 3, 3)
    sweep = mech.sweep(t)
    nodes = nodes_of(t, math.radians(30.0))
    fine = np.setdiff1d(np.arange(t.size), nodes)
    t3, t4 = _four_bar_closed_form(t, 4, 1, 3, 3)
    assert max(_wrapped(sweep["theta3"], t3).max(), _wrapped(sweep["theta4"], t4).max()) < 1e-13
    assert sweep.iterations[fine].max() == 2  # the cubic leaves some points a third iteration
    # the choice: the four-bar's quintic changes the prediction by 3e-4 rad at most (its cubic leaves 30 points a
    # third iteration), the chained homework's by 4e-3 (a third iteration either way), a slider-crank's by 1.5e-4
    # (none either way)
    for build, pays in ((lambda: mech, True), (linkages.chained_four_bars, False),
                        (lambda: linkages.slider_crank(1.0, 3.0, 0.5), False)):
        s = build().sweep(t)
        D = np.full_like(s.values, np.nan)
        ctx = Continuation(build(), "symbolic", 1e-12, math.radians(30.0), "raise")
        for j in nodes:
            D[:, j] = ctx.local1(ctx.eval1(s.values[:, j].tolist(), float(t[j])))[0]
        assert quintic_pays(free_quintic(t, s.values, D, nodes)[2], ctx.inv_xs) is pays


def test_sweeps_with_and_without_free_curvatures_agree(monkeypatch):
    monkeypatch.setattr(batch_fill, "TURN", False)  # (round a whole turn, the trigonometric fit comes first)
    t = np.radians(np.arange(0.0, 361.0, 1.0))
    for build in (lambda: linkages.four_bar(4, 1, 3, 3), lambda: linkages.slider_crank(1.0, 3.0, 0.5),
                  linkages.six_bar):
        with_free = build().sweep(t)
        monkeypatch.setattr(batch_fill, "FREE_CURVATURES", False)
        cubic = build().sweep(t)
        monkeypatch.setattr(batch_fill, "FREE_CURVATURES", True)
        assert np.abs(with_free.values - cubic.values).max() < 1e-13
        assert np.abs(with_free.cond - cubic.cond).max() <= 1e-12 * cubic.cond.max()
        assert with_free.iterations.max() <= cubic.iterations.max()
        assert [e.kind for e in with_free.events] == [e.kind for e in cubic.events]


@pytest.mark.parametrize("build", [linkages.chained_four_bars, lambda: linkages.slider_crank(80, 200, 20),
                                   linkages.six_bar])
def test_block_condition_numbers_and_orientations_in_one_pass_match_numpy(build):
    mech = build()
    t = np.radians(np.arange(0.0, 360.0, 7.0))
    sweep = mech.sweep(t)
    bs = mech.block_structure
    J = mech.compiled.J(sweep.values, t, mech.parameter_values)  # (N, n, n)
    col = np.asarray(bs.xscale) / bs.fscale
    rows = [J[:, i // bs.n, i % bs.n] for i in range(bs.n * bs.n)]
    cond, signs = bs.cond_signs(rows, t.size)
    for k, (a, b) in enumerate(bs.blocks):
        np.testing.assert_allclose(cond[k], np.linalg.cond(J[:, a:b, a:b] * col[None, None, a:b]), rtol=1e-12)
        np.testing.assert_array_equal(signs[k], np.sign(np.linalg.det(J[:, a:b, a:b])))
    # an ill-conditioned and an exactly singular 2 x 2 block, against mpmath's singular values (50 digits)
    import mpmath

    one = BlockStructure([slice(0, 2)], 1.0, [1.0, 1.0])
    blocks = [[1.0, 1.0], [1.0, 1.0 + 1e-9]], [[3.0, -2.0], [1.0, 5.0]], [[1.0, 2.0], [2.0, 4.0]]
    cond, signs = one.cond_signs([np.array([m[i][j] for m in blocks]) for i in range(2) for j in range(2)], 3)
    with mpmath.workdps(50):
        for got, m in zip(cond[0][:2], blocks[:2]):
            sv = mpmath.svd_r(mpmath.matrix(m), compute_uv=False)
            assert got == pytest.approx(float(sv[0] / sv[1]), rel=1e-6)
        assert mpmath.det(mpmath.matrix(blocks[2])) == 0
    assert cond[0][2] == math.inf
    assert signs[0].tolist() == [1.0, 1.0, 0.0]

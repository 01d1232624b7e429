"""The sweep's kept Jacobian, the block-triangular derivative solves and the sweep's memory.

References: the Jacobian compiled separately from the sweep's fused kernel,
the complex-step derivative (Newton in complex arithmetic, dense solves),
closed forms of a one-loop slider-crank, and tracemalloc's count of bytes.
"""

from __future__ import annotations

import dataclasses
import math
import tracemalloc

import numpy as np
import pytest

from numkin import analytic, linkages
from numkin.batch_fill import CHUNK
from numkin.compiled import BlockStructure, acceleration_rhs, jacobian_rows, rates

GRID = np.radians(np.arange(0.0, 361.0, 3.0))


@pytest.fixture(scope="module")
def homework():
    return linkages.chained_four_bars().sweep(GRID)


def test_the_sweep_keeps_the_jacobian_at_its_values(homework):
    mech = homework.mechanism
    kept = homework.jacobian_rows
    assert kept is not None and len(kept) == len(mech.unknowns) ** 2
    fresh = jacobian_rows(mech.compiled, homework.values, homework.inputs, mech.parameter_values)
    for row_kept, row_fresh in zip(kept, fresh):
        np.testing.assert_allclose(np.broadcast_to(row_kept, row_fresh.shape), row_fresh, rtol=0, atol=1e-13)


def test_derivatives_without_the_kept_jacobian_are_the_same(homework):
    bare = dataclasses.replace(homework)  # a copy does not inherit the kept Jacobian
    assert bare.jacobian_rows is None
    for a, b in zip(analytic.derivatives(homework), analytic.derivatives(bare)):
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-13)


def test_block_solves_match_the_complex_step_on_a_chain(homework):
    dq, d2q = analytic.derivatives(homework)
    cs1 = analytic.complex_step(homework)
    cs2 = analytic.complex_step(homework, order=2)
    np.testing.assert_allclose(dq, cs1, rtol=0, atol=1e-11 * np.abs(cs1).max())
    np.testing.assert_allclose(d2q, cs2, rtol=0, atol=1e-10 * np.abs(cs2).max())


def test_rates_of_a_slider_crank_against_the_closed_form():
    r, l = 80.0, 200.0
    mech = linkages.slider_crank(r, l)
    sweep = mech.sweep(GRID)
    t = sweep.inputs
    dq, d2q = rates(mech.compiled, mech.block_structure, sweep.values, t, mech.parameter_values)
    # x = r cos t + sqrt(l^2 - r^2 sin^2 t): x' and x'' by hand
    root = np.sqrt(l**2 - r**2 * np.sin(t) ** 2)
    x1 = -r * np.sin(t) - r**2 * np.sin(t) * np.cos(t) / root
    x2 = -r * np.cos(t) - r**2 * np.cos(2 * t) / root - r**4 * np.sin(t) ** 2 * np.cos(t) ** 2 / root**3
    j = mech.unknowns.index("x")
    np.testing.assert_allclose(dq[j], x1, rtol=0, atol=1e-12 * r)
    np.testing.assert_allclose(d2q[j], x2, rtol=0, atol=1e-12 * r)


def test_acceleration_rhs_with_the_unknowns_at_rest():
    mech = linkages.slider_crank(80, 200)
    q = np.array([[math.pi / 2, math.pi / 2], [0.0, 0.0]])  # any q: only cos/sin of the input matter when q' = 0
    t = np.array([0.0, math.pi / 2])
    rows = acceleration_rhs(mech.compiled, q, np.zeros((2, 2)), t, mech.parameter_values)
    # d2/dt2 of the crank's vector (r cos t, r sin t) enters the loop with the sign of the residual
    vec = np.array([np.broadcast_to(r, t.shape) for r in rows])
    assert np.allclose(np.abs(vec[0]), 80 * np.abs(np.cos(t)), atol=1e-12)
    assert np.allclose(np.abs(vec[1]), 80 * np.abs(np.sin(t)), atol=1e-12)


def test_solve_negated_flags_a_singular_block():
    bs = BlockStructure([slice(0, 2)], 1.0, [1.0, 1.0])
    J = [np.array([1.0, 1.0]), np.array([2.0, 0.0]), np.array([2.0, 0.0]), np.array([4.0, 1.0])]
    with np.errstate(all="ignore"):
        dx, bad = bs.solve_negated(J, [np.array([1.0, 1.0]), np.array([1.0, 1.0])], 2)
    assert bad.tolist() == [True, False]
    assert np.isnan(dx[:, 0]).all()
    np.testing.assert_allclose(dx[:, 1], [-1.0, -1.0])  # [[1, 0], [0, 1]] dx = -[1, 1]


@pytest.mark.parametrize("build", [lambda: linkages.four_bar(4, 1, 3, 3), linkages.chained_four_bars])
def test_sweep_memory_per_point_at_36001_points(build):
    mech = build()
    t = np.linspace(0.0, 2 * np.pi, 36_001)
    assert t.size > 4 * CHUNK  # several batches
    mech.sweep(t)  # kernels compiled before counting
    tracemalloc.start()
    try:
        sweep = mech.sweep(t)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak / t.size <= 300
    assert np.max(sweep.residual) <= 10 * sweep.tol


def test_written_out_newtons_on_blocks_of_size_one():
    # f0 = x0^2 - t, f1 = x1 - 2 x0 (a block of size 1 after another): x0 = sqrt(t), x1 = 2 sqrt(t)
    from numkin.newton_rules import has_converged

    bs = BlockStructure([slice(0, 1), slice(1, 2)], 1.0, [1.0, 1.0], zeros={(0, 1)})

    def kernel(x0, x1, t):
        return [x0 * x0 - t, x1 - 2.0 * x0, 2.0 * x0, 0.0, -2.0, 1.0]

    t = np.linspace(1.0, 4.0, 7)
    x = np.vstack([np.sqrt(t) * 1.05, np.zeros(7)])
    active = np.ones(7, dtype=bool)
    active[0] = False
    x[0, 6] = 0.0  # d f0 / d x0 = 0: refused, not moved
    with np.errstate(all="ignore"):
        converged, singular, iterations, rows, evaluations = bs.newton_batch(
            kernel, x, t, (), active, 12, 1.0, 1e-12, 0.0, has_converged)
    ok = np.array([False, True, True, True, True, True, False])
    assert (converged == ok).all() and singular[6] and not iterations[0] and evaluations == iterations.max() + 1
    np.testing.assert_allclose(x[:, ok], np.vstack([np.sqrt(t), 2 * np.sqrt(t)])[:, ok], rtol=1e-15)
    assert x[0, 0] == np.sqrt(t[0]) * 1.05 and x[0, 6] == 0.0
    assert np.array_equal(rows[0], x[0] ** 2 - t)
    # the scalar one, with and without the conditioning rule (blocks of size 1 have condition number 1)
    for cond_max in (None, 1e12):
        xs, status, it, res, v, evals = bs.newton1(lambda a, b, tt: kernel(a, b, tt), [1.0, 0.0], 2.0, (), 12,
                                                   1.0, 1e-12, lambda x, t: 0.0, ArithmeticError,
                                                   cond_max)
        assert status == "converged" and xs == pytest.approx([math.sqrt(2.0), 2 * math.sqrt(2.0)], rel=1e-15)

"""Evaluation counts recorded by sweeps and derivatives, against hand counts on small sweeps.

The counting rule: an evaluation of a compiled function at N inputs counts N;
the continuation's fused residual-and-Jacobian evaluations count once as a
residual (``nfev``) and once as a Jacobian (``njev``); a finite-difference
Jacobian at one input is one Jacobian and n (forward) residuals.

A sweep's path, for these grids (the default guess solved at the first
input, then ``max_step`` wide enough for a single continuation step to the
last node):

* first point: Newton from the guess, ``k0`` steps: the residual and
  Jacobian at the guess and after each step, ``k0 + 1`` evaluations;
* each node after it, reached in one continuation step whose corrector
  takes ``k`` steps: ``k + 1`` evaluations;
* the grid points between the nodes: one Newton batch on all N columns at
  once (N is small, so no column is left out), the residuals and Jacobian
  evaluated before the first step and after each of the ``k_batch`` steps;
  with every point a node, a single evaluation of the whole grid instead.
"""

from __future__ import annotations

import numpy as np
import pytest

from numkin import analytic, linkages, report
from numkin.report.counting import sweep_evaluations


@pytest.fixture(scope="module")
def four_bar():
    return linkages.four_bar(4, 1, 3, 3)  # one loop, unknowns theta3 and theta4


def test_one_point(four_bar):
    s = four_bar.sweep(np.radians([10.0]))
    k0 = int(s.iterations[0])
    assert k0 >= 1 and s.residual[0] < 1e-12
    # Newton from the guess (k0 + 1 fused evaluations), then the grid's final evaluation (1 point)
    assert (s.nfev, s.njev) == (k0 + 2, k0 + 2)


def test_two_nodes(four_bar):
    s = four_bar.sweep(np.radians([0.0, 1.0]))  # two points: both nodes, one step of 1 deg between them
    k0, k1 = (int(k) for k in s.iterations)
    # first point k0 + 1, the continuation step k1 + 1, the final evaluation of both points 2
    assert (s.nfev, s.njev) == (k0 + k1 + 4, k0 + k1 + 4)


def test_nodes_and_a_batch(four_bar):
    s = four_bar.sweep(np.radians([0.0, 1.0, 2.0]), max_step=np.radians(4.0))  # nodes 0 and 2 deg
    k0, kb, k2 = (int(k) for k in s.iterations)
    # first point k0 + 1, one step to 2 deg k2 + 1, the batch (1 deg) on all 3 columns: 3 (kb + 1)
    expected = (k0 + 1) + (k2 + 1) + 3 * (kb + 1)
    assert (s.nfev, s.njev) == (expected, expected)
    with report.count_evaluations(four_bar) as count:
        again = four_bar.sweep(np.radians([0.0, 1.0, 2.0]), max_step=np.radians(4.0))
    assert count.points == {"F": again.nfev, "J": again.njev} == {"F": expected, "J": expected}
    assert sweep_evaluations(again) == 2 * expected


def test_nodes_and_a_batch_with_a_finite_difference_jacobian(four_bar):
    n = 2
    s = four_bar.sweep(np.radians([0.0, 1.0, 2.0]), max_step=np.radians(4.0), jacobian="forward")
    k0, kb, k2 = (int(k) for k in s.iterations)
    # one point, one Newton: its residual and forward-difference Jacobian (1 + n residuals, 1 Jacobian)
    # at the start and after each step, then the fused symbolic evaluation the sweep keeps (1 and 1)
    point_f = lambda k: (k + 1) * (1 + n) + 1  # noqa: E731
    point_j = lambda k: (k + 1) + 1  # noqa: E731
    # the batch, 3 columns: residuals at the start, then per step a Jacobian (n residuals each) and the
    # residuals; then the fused symbolic evaluation kept
    batch_f = 3 + kb * (3 * n + 3) + 3
    batch_j = kb * 3 + 3
    assert s.nfev == point_f(k0) + point_f(k2) + batch_f
    assert s.njev == point_j(k0) + point_j(k2) + batch_j


def test_derivative_counts(four_bar):
    t = np.radians([0.0, 1.0, 2.0])
    s = four_bar.sweep(t, max_step=np.radians(4.0))
    N = t.size
    with report.count_evaluations(four_bar) as velocity:
        analytic.tangent(s)
    assert velocity.points == {"F_t": N}  # the Jacobian is the sweep's own
    with report.count_evaluations(four_bar) as both:
        analytic.derivatives(s)
    assert both.points == {"F_t": N, "second": N}
    with report.count_evaluations(four_bar) as cs:
        analytic.complex_step(s)
    # two complex Newton solves, each on all N columns: residuals once more than Jacobians in each
    assert cs.points["F"] - cs.points["J"] == 2 * N and cs.points["J"] % N == 0 and cs.points["J"] >= 2 * N
    with report.count_evaluations(four_bar) as cs2:
        analytic.complex_step(s, order=2)
    # the same Newton solves, then J and dF/dtheta at the complex solution for q'
    assert cs2.points == {"F": cs.points["F"], "J": cs.points["J"] + N, "F_t": N}

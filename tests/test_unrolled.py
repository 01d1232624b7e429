"""The written-out one-point functions of a continuation step give the same floats as the general ones.

References: ``BlockStructure.solve1`` and ``BlockStructure.cond1`` through
numpy (``np.linalg.cond`` of the scaled blocks), and the list form of
:func:`numkin.predictors.predict`, on random block lower-triangular
Jacobians, tangents and points.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, strategies as st

from numkin.blocks import BlockStructure
from numkin.predictors import predict, unrolled_predict
from numkin.unrolled import scaled_distance

finite = st.floats(-10.0, 10.0, allow_nan=False, allow_infinity=False)


def _structure(sizes, xscale):
    slices, a = [], 0
    for k in sizes:
        slices.append(slice(a, a + k))
        a += k
    return BlockStructure(slices, 2.0, xscale)


@given(sizes=st.lists(st.sampled_from([1, 2]), min_size=1, max_size=4), data=st.data())
def test_local_matches_the_general_solve_and_condition_numbers(sizes, data):
    n = sum(sizes)
    xscale = data.draw(st.lists(st.sampled_from([1.0, 0.5, 80.0]), min_size=n, max_size=n))
    bs = _structure(sizes, xscale)
    v = data.draw(st.lists(finite, min_size=n + n * n + n, max_size=n + n * n + n))
    d, o, cond = bs.local1(v)
    J, rhs = v[n : n + n * n], [-a for a in v[n + n * n :]]
    d_ref, o_ref = bs.solve1(J, rhs)
    assert d == d_ref and o == o_ref
    assert cond == max(bs.cond1(J))
    if d is not None:  # an independent check of the tangent: J d = -dF/dt through numpy
        full = np.array(J).reshape(n, n)
        for a, b in bs.blocks:  # only the lower-triangular blocks count
            full[a:b, b:] = 0.0
        # a backward-stable solve: |J d - rhs| small against 1 + |J| |d| + |rhs| (entries are at most 10),
        # in units of the largest |d| (of 1 at least) so that a near-singular block's huge tangent
        # cannot overflow the tolerance
        s = max(1.0, float(np.abs(d).max()))
        ds, rs = np.array(d) / s, np.array(rhs) / s
        atol = 1e-10 * (1.0 + np.abs(rs).max() + n * np.abs(full).max() * np.abs(ds).max())
        assert math.isfinite(atol)
        np.testing.assert_allclose(full @ ds, rs, rtol=0.0, atol=atol)


def test_local_condition_number_is_numpys_of_the_scaled_block():
    bs = _structure([2], [1.0, 80.0])  # entry (i, j) scaled by xscale_j / fscale
    v = [0.0, 0.0, 3.0, 0.02, -1.0, 0.05, 1.0, 1.0]
    _, o, cond = bs.local1(v)
    scaled = np.array([[3.0, 0.02], [-1.0, 0.05]]) * np.array([1.0, 80.0]) / 2.0
    assert cond == pytest.approx(np.linalg.cond(scaled), rel=1e-12)
    assert o == [1.0]  # det = 3 * 0.05 + 0.02 > 0


def test_local_of_a_singular_block_has_no_tangent_and_infinite_condition():
    bs = _structure([1, 2], [1.0, 1.0, 1.0])
    v = [0.0] * 3 + [1.0, 0.0, 0.0, 2.0, 1.0, 2.0, 4.0, 2.0, 4.0] + [1.0, 1.0, 1.0]
    assert bs.local1(v) == (None, None, math.inf)


@given(n=st.integers(1, 4), data=st.data())
def test_written_out_predictor_is_the_list_predictor(n, data):
    vec = st.lists(finite, min_size=n, max_size=n)
    x, d, x_prev, d_prev = data.draw(vec), data.draw(vec), data.draw(vec), data.draw(vec)
    t, t_prev = data.draw(finite), data.draw(finite)
    t_new = data.draw(finite)
    weights = data.draw(st.sampled_from([None, tuple([1.0] * n), tuple(0.5 + k for k in range(n))]))
    rate = max(abs(a) * w for a, w in zip(d, weights or [1.0] * n))
    with_prev = data.draw(st.booleans())
    with_tangent = data.draw(st.booleans())
    args = (t, x, d, t_prev if with_prev else None, x_prev if with_prev else None, t_new)
    tail = (rate, d_prev if with_tangent else None)
    # the same floats, or the same error (a step of zero length with the previous point at the same input)
    assert _outcome(unrolled_predict(n, weights), *args, *tail) == _outcome(
        predict, *args, list(weights) if weights else None, *tail)


def _outcome(fn, *args):
    try:
        return fn(*args)
    except ArithmeticError as error:
        return type(error)


def test_written_out_predictor_is_exact_for_a_cubic():
    # q(t) = t^3 from t = 0 and 1 with tangents, at 1.5
    assert unrolled_predict(1)(1.0, [1.0], [3.0], 0.0, [0.0], 1.5, 3.0, [0.0]) == [3.375]


@given(n=st.integers(1, 4), data=st.data())
def test_scaled_distance_is_the_largest_weighted_difference(n, data):
    vec = st.lists(finite, min_size=n, max_size=n)
    a, b = data.draw(vec), data.draw(vec)
    w = tuple(data.draw(st.lists(st.sampled_from([1.0, 0.25, 3.0]), min_size=n, max_size=n)))
    assert scaled_distance(n, w)(a, b) == max(abs(x - y) * k for x, y, k in zip(a, b, w))


def test_written_out_kink_test_is_the_extrapolated_tangent_rule():
    # the rule by hand: expected tangent d + (d - d_prev) r, r = (t_new - t) / (t - t_prev) when 0 < r <= reach,
    # else d; kinked when max |d_new - expected| w > turn (1 + rate)
    from numkin.unrolled import unrolled_kink

    rng = np.random.default_rng(7)
    weights = (1.0, 0.25, 1.0)
    kinked = unrolled_kink(3, weights, 0.5, 2.0)
    for _ in range(300):
        t, t_prev = 1.0, 1.0 - rng.uniform(0.1, 1.0)
        t_new = t + rng.uniform(0.05, 2.5)
        d, d_prev, d_new = (rng.normal(size=3).tolist() for _ in range(3))
        rate = float(rng.uniform(0.0, 2.0))
        r = (t_new - t) / (t - t_prev)
        expected = [a + (a - b) * r for a, b in zip(d, d_prev)] if 0.0 < r <= 2.0 else d
        ref = max(abs(a - b) * w for a, b, w in zip(d_new, expected, weights)) > 0.5 * (1.0 + rate)
        assert kinked(t, d, t_prev, d_prev, t_new, d_new, rate) == ref
        assert kinked(t, d, None, None, t_new, d_new, rate) == (
            max(abs(a - b) * w for a, b, w in zip(d_new, d, weights)) > 0.5 * (1.0 + rate))
    assert kinked(t, d, t_prev, d_prev, t_new, None, 0.0) is False

"""Tests for the fused rates function (numkin.rates_kernel, CompiledMechanism.rates_kernel).

References: the four-bar's angular velocities and accelerations written out
here from its loop closure by hand, a two-loop mechanism whose positions are
polynomials of cos(theta), and the block solves of BlockStructure applied to
the separately compiled right-hand sides.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from numkin import Loop, Mechanism, analytic, kernel_cache, linkages
from numkin.compiled import rates
from numkin.rates_kernel import RATES_NARGS, rates_source


def _four_bar_positions(theta, r1, r2, r3, r4):
    """theta3, theta4 of r2 e^{i theta2} + r3 e^{i theta3} = r1 + r4 e^{i theta4}, by circle intersection."""
    ax, ay = r2 * np.cos(theta), r2 * np.sin(theta)
    dx, dy = r1 - ax, -ay  # from the crank pin A to the rocker's pivot
    dist = np.hypot(dx, dy)
    t3 = np.arctan2(dy, dx) + np.arccos((r3**2 + dist**2 - r4**2) / (2 * r3 * dist))
    t4 = np.arctan2(ay + r3 * np.sin(t3), ax + r3 * np.cos(t3) - r1)
    return t3, t4


def _four_bar_rates(theta, t3, t4, r2, r3, r4):
    """d/dtheta and d2/dtheta2 of theta3 and theta4, from the loop closure differentiated by hand.

    r2 e^{i th} + r3 w3 e^{i t3} = r4 w4 e^{i t4} (divided by i); multiplied by e^{-i t4} (e^{-i t3}),
    its imaginary part gives w3 (w4). Differentiated once more, the same for a3 and a4.
    """
    w3 = r2 * np.sin(t4 - theta) / (r3 * np.sin(t3 - t4))
    w4 = r2 * np.sin(theta - t3) / (r4 * np.sin(t4 - t3))
    a3 = (r4 * w4**2 - r2 * np.cos(theta - t4) - r3 * w3**2 * np.cos(t3 - t4)) / (r3 * np.sin(t3 - t4))
    a4 = (r2 * np.cos(theta - t3) + r3 * w3**2 - r4 * w4**2 * np.cos(t4 - t3)) / (r4 * np.sin(t4 - t3))
    return np.array([w3, w4]), np.array([a3, a4])


@settings(max_examples=40, deadline=None)
@given(
    r1=st.floats(3.0, 5.0), r2=st.floats(0.3, 0.9), r3=st.floats(3.0, 5.0), r4=st.floats(3.0, 5.0),
    angles=st.lists(st.floats(0.0, 2 * math.pi), min_size=1, max_size=8),
)
def test_fused_rates_of_any_crank_rocker_match_the_hand_derived_ones(r1, r2, r3, r4, angles):
    m = linkages.four_bar(r1, r2, r3, r4)  # crank shortest, s + l < p + q: assembles at every angle
    theta = np.array(angles)
    q = np.array(_four_bar_positions(theta, r1, r2, r3, r4))
    dq, d2q = rates(m.compiled, m.block_structure, q, theta, m.parameter_values)
    assert "_rates" in vars(m.compiled)  # the fused path was taken
    w, a = _four_bar_rates(theta, *q, r2, r3, r4)
    np.testing.assert_allclose(dq, w, rtol=1e-11, atol=1e-12 * np.abs(w).max())
    np.testing.assert_allclose(d2q, a, rtol=1e-10, atol=1e-11 * np.abs(a).max())


@pytest.mark.parametrize("make", [lambda: linkages.four_bar(4, 1, 3, 3), linkages.chained_four_bars,
                                  lambda: linkages.slider_crank(80, 200, 25), linkages.six_bar, linkages.quick_return])
def test_fused_rates_equal_the_separate_solves(make):
    m = make()
    t = np.radians(np.arange(0.0, 60.0, 0.5))
    s = m.sweep(t)
    q, p, bs, comp = s.values, m.parameter_values, m.block_structure, m.compiled
    assert comp.rates_kernel(bs.blocks) is not None
    dq, d2q = rates(comp, bs, q, t, p, s.jacobian_rows)
    ref_dq, _ = bs.solve_negated(s.jacobian_rows, comp.F_t(q, t, p), t.size)
    ref_d2q, _ = bs.solve_negated(s.jacobian_rows, comp._second(*q, *ref_dq, t, *p), t.size)
    np.testing.assert_array_equal(dq, ref_dq)  # the same operations in the same order
    np.testing.assert_allclose(d2q, ref_d2q, rtol=1e-13, atol=1e-13 * np.abs(ref_d2q).max())


def test_a_loop_of_one_unknown_after_another():
    """x = r cos(t) (loop 1), y = x^2 (loop 2): y' = -r^2 sin(2t), y'' = -2 r^2 cos(2t)."""
    t_, x, y, r = sp.symbols("t x y r", real=True)
    m = Mechanism([Loop([x - r * sp.cos(t_)], [x]), Loop([y - x**2], [y])], t_, {r: 2.0}, guess={"x": 2.0, "y": 4.0})
    t = np.linspace(0.0, 3.0, 31)
    s = m.sweep(t)
    assert m.compiled.rates_kernel(m.block_structure.blocks) is not None
    dq, d2q = analytic.derivatives(s)
    np.testing.assert_allclose(dq, [-2.0 * np.sin(t), -4.0 * np.sin(2 * t)], atol=1e-12)
    np.testing.assert_allclose(d2q, [-2.0 * np.cos(t), -8.0 * np.cos(2 * t)], atol=1e-12)


def test_singular_column_is_nan_in_both_arrays():
    m = linkages.four_bar(4, 1, 3, 3)
    t = np.radians([10.0, 20.0, 30.0])
    s = m.sweep(t)
    jac = [np.array(row, dtype=float) for row in s.jacobian_rows]
    for k in (0, 2):  # the first column of the block zero at the middle point: det = 0
        jac[k][1] = 0.0
    dq, d2q = rates(m.compiled, m.block_structure, s.values, t, m.parameter_values, jac)
    assert np.isnan(dq[:, 1]).all() and np.isnan(d2q[:, 1]).all()
    assert np.isfinite(dq[:, [0, 2]]).all() and np.isfinite(d2q[:, [0, 2]]).all()


def test_blocks_larger_than_two_are_left_to_the_general_solve():
    t, a, b, c = sp.symbols("t a b c")
    residuals = [a - sp.cos(t), b - a, c - b]
    assert rates_source(residuals, [a, b, c], t, [], [(0, 3)]) is None
    assert rates_source(residuals, [a, b, c], t, [], [(0, 1), (2, 3)]) is None  # not covering the unknowns
    assert rates_source(residuals, [a, b, c], t, [], [(0, 1), (1, 2), (2, 3)]) is not None


# ----------------------------------------------------------------- kept between runs
def _counted(source: str):
    """A generator of ``source`` for :func:`kernel_cache.cached_source`, and the list of its calls."""
    built = []

    def build():
        built.append(1)
        return source

    return build, built


def test_a_corrupt_or_tampered_entry_is_rebuilt(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMKIN_CACHE_DIR", str(tmp_path))
    x = sp.Symbol("x")
    build, built = _counted("def f(J, q, t, p, dq, d2q):\n    dq[0] = cos(t)\n    return None\n")

    def value(f):
        out = np.empty((1, 1))
        f(None, None, np.array([0.0]), None, out, None)
        return float(out[0, 0])

    f = kernel_cache.cached_source((sp.cos(x),), (x,), "test", RATES_NARGS, build)
    assert value(f) == 1.0 and len(built) == 1
    (path,) = tmp_path.glob("*.json")
    kernel_cache.cached_source((sp.cos(x),), (x,), "test", RATES_NARGS, build)
    assert len(built) == 1  # read back
    entry = json.loads(path.read_text())
    entry["source"] = entry["source"].replace("cos(t)", "sin(t) + 1.0")  # checksum no longer holds
    path.write_text(json.dumps(entry))
    assert value(kernel_cache.cached_source((sp.cos(x),), (x,), "test", RATES_NARGS, build)) == 1.0
    assert len(built) == 2
    path.write_text("{not json")
    assert value(kernel_cache.cached_source((sp.cos(x),), (x,), "test", RATES_NARGS, build)) == 1.0
    assert len(built) == 3 and json.loads(path.read_text())["key"] == path.stem


def test_code_outside_numpy_is_not_kept():
    assert kernel_cache.kernel_from_source("def f(x):\n    import os\n    return x\n", 1) is None
    assert kernel_cache.kernel_from_source("def f(x):\n    return x.real\n", 1) is None
    assert kernel_cache.kernel_from_source("def f(x):\n    return no_such_function(x)\n", 1) is None
    assert kernel_cache.kernel_from_source("def f(x, y):\n    return x\n", 1) is None


def test_the_fused_function_joins_the_bundle(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMKIN_CACHE_DIR", str(tmp_path / "kernels"))
    t = np.radians(np.arange(0.0, 361.0, 5.0))
    first = linkages.chained_four_bars()
    dq, d2q = analytic.derivatives(first.sweep(t))
    (path,) = [p for p in (tmp_path / "kernels").glob("*.json") if json.loads(p.read_text()).get("kind") == "bundle"]
    kept = kernel_cache.load_bundle(path.stem)[0]["kernels"]
    assert kept["rates"]["blocks"] == [[0, 2], [2, 4]] and kept["rates"]["f"] is not None
    again = linkages.chained_four_bars()
    assert "_rates" in vars(again.compiled)["_loaded"]
    dq2, d2q2 = analytic.derivatives(again.sweep(t))
    assert "_rates" in vars(again.compiled) and "residuals" not in vars(again.compiled)  # no sympy model needed
    np.testing.assert_array_equal(dq2, dq)
    np.testing.assert_array_equal(d2q2, d2q)


def test_a_changed_generator_misses_the_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMKIN_CACHE_DIR", str(tmp_path))
    x = sp.Symbol("x")
    build, built = _counted("def f(J, q, t, p, dq, d2q):\n    return None\n")

    kernel_cache.cached_source((x,), (x,), "test", RATES_NARGS, build)
    kernel_cache.cached_source((x,), (x,), "test", RATES_NARGS, build)
    assert len(built) == 1
    monkeypatch.setattr(kernel_cache, "_deriving_digest", lambda: "another generator")
    kernel_cache.cached_source((x,), (x,), "test", RATES_NARGS, build)
    assert len(built) == 2 and len(list(tmp_path.glob("*.json"))) == 2


@pytest.mark.parametrize("make", [lambda: linkages.four_bar(4, 1, 3, 3), linkages.chained_four_bars, linkages.six_bar,
                                  lambda: linkages.slider_crank(80, 200, 25), linkages.quick_return])
def test_vector_loops_read_their_second_derivative_terms_from_the_jacobian(make):
    """Of the sines and cosines in the rates only those of the input are evaluated: the second
    derivatives of r cos(phi), r sin(phi) (also of sums, as the six-bar's coupler has) are entries of J."""
    m = make()
    source = m.compiled.rates_kernel(m.block_structure.blocks).numkin_kernel["source"]
    assert source.count("sin(") == source.count("sin(t)") == 1
    assert source.count("cos(") == source.count("cos(t)") == 1


def test_regular_sweeps_still_refuse_an_unknown_at_change_point():
    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians([0.0, 10.0]))
    for f in (analytic.derivatives, analytic.tangent):
        with pytest.raises(ValueError, match="at_change_point must be one of"):
            f(sweep, at_change_point="skip")

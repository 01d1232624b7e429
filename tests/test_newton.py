"""Tests for numkin.newton: convergence, Jacobian choices, singular and failing solves, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from numkin import ConvergenceWarning, InputError, linkages, newton
from numkin.newton import has_converged
from numkin.newton import NewtonResult

X, Y = sp.symbols("x y", real=True)
T3, T4 = sp.symbols("t3 t4", real=True)


def four_bar_residuals(theta2, r1, r2, r3, r4):
    """Loop r2 e^{i theta2} + r3 e^{i t3} - r4 e^{i t4} - r1 = 0 at a fixed crank angle, as sympy."""
    return [
        r2 * math.cos(theta2) + r3 * sp.cos(T3) - r4 * sp.cos(T4) - r1,
        r2 * math.sin(theta2) + r3 * sp.sin(T3) - r4 * sp.sin(T4),
    ]


def four_bar_numeric(theta2, r1, r2, r3, r4):
    def fun(v):
        t3, t4 = v
        return np.array(
            [
                r2 * math.cos(theta2) + r3 * math.cos(t3) - r4 * math.cos(t4) - r1,
                r2 * math.sin(theta2) + r3 * math.sin(t3) - r4 * math.sin(t4),
            ]
        )

    def jac(v):
        t3, t4 = v
        return np.array([[-r3 * math.sin(t3), r4 * math.sin(t4)], [r3 * math.cos(t3), -r4 * math.cos(t4)]])

    return fun, jac


def open_four_bar(theta2, r1, r2, r3, r4):
    """Circle intersection (open branch: B to the left of A -> O4), derived here independently."""
    a = np.array([r2 * math.cos(theta2), r2 * math.sin(theta2)])
    o4 = np.array([r1, 0.0])
    d = np.linalg.norm(o4 - a)
    u = (o4 - a) / d
    along = (r3**2 - r4**2 + d**2) / (2 * d)
    h = math.sqrt(r3**2 - along**2)
    b = a + along * u + h * np.array([-u[1], u[0]])
    return math.atan2(b[1] - a[1], b[0] - a[0]), math.atan2(b[1], b[0] - r1)


# ------------------------------------------------------------------ convergence
def test_sympy_system_converges_to_known_root():
    res = newton([X**2 + Y**2 - 4, X - Y], [1.0, 0.5], unknowns=[X, Y])
    assert isinstance(res, NewtonResult)
    assert res.converged
    np.testing.assert_allclose(res.x, [math.sqrt(2), math.sqrt(2)], rtol=0, atol=1e-14)
    assert res.residual_norms.size == res.iterations + 1
    assert res.step_norms.size == res.iterations
    assert "converged" in res.message
    np.testing.assert_allclose(res.residual, [0.0, 0.0], atol=1e-14)


def test_symbolic_jacobian_converges_quadratically():
    theta2 = math.radians(60)
    res = newton(four_bar_residuals(theta2, 4, 1, 3, 3), [0.3, 1.6], unknowns=[T3, T4], fscale=4)
    assert res.converged
    np.testing.assert_allclose(res.x, open_four_bar(theta2, 4, 1, 3, 3), rtol=0, atol=1e-13)
    order = res.convergence_order()
    assert order.size >= 2
    assert abs(order[-1] - 2.0) < 0.05
    assert np.all(order[-2:] > 1.8)
    # quadratic: each step at most C times the square of the previous one
    s = res.step_norms
    assert np.all(s[2:] <= 1.0 * s[1:-1] ** 2)


@pytest.mark.parametrize("jacobian", ["forward", "central"])
def test_finite_difference_jacobians_converge(jacobian):
    theta2 = math.radians(150)
    ref = open_four_bar(theta2, 4, 1, 3, 3)
    res = newton(four_bar_residuals(theta2, 4, 1, 3, 3), [ref[0] + 0.2, ref[1] - 0.2], unknowns=[T3, T4],
                 jacobian=jacobian, fscale=4)
    assert res.converged
    np.testing.assert_allclose(res.x, ref, rtol=0, atol=1e-13)
    assert res.iterations <= 8
    fun, _ = four_bar_numeric(theta2, 4, 1, 3, 3)
    res2 = newton(fun, [ref[0] + 0.2, ref[1] - 0.2], jacobian=jacobian, fscale=4)
    assert res2.converged
    np.testing.assert_allclose(res2.x, ref, rtol=0, atol=1e-13)
    if jacobian == "central":
        assert abs(res2.convergence_order()[-1] - 2.0) < 0.1


def test_callable_function_default_and_callable_jacobian():
    theta2 = math.radians(230)
    ref = open_four_bar(theta2, 4, 1, 3, 3)
    fun, jac = four_bar_numeric(theta2, 4, 1, 3, 3)
    x0 = [ref[0] - 0.15, ref[1] + 0.1]
    res_default = newton(fun, x0, fscale=4)  # central differences
    res_jac = newton(fun, x0, jacobian=jac, fscale=4)
    for res in (res_default, res_jac):
        assert res.converged
        np.testing.assert_allclose(res.x, ref, rtol=0, atol=1e-13)
    assert abs(res_jac.convergence_order()[-1] - 2.0) < 0.05
    # the condition number at the solution, computed here from the same Jacobian (rows / fscale)
    np.testing.assert_allclose(res_jac.cond, np.linalg.cond(jac(res_jac.x) / 4), rtol=1e-10)


def test_args_are_passed_through():
    res = newton(lambda v, c: np.array([v[0] ** 3 - c]), [1.0], args=(27.0,), jacobian="forward")
    assert res.converged
    assert abs(res.x[0] - 3.0) < 1e-13


def test_scaled_system_converges_in_the_same_iterations():
    """Lengths times 1e6 with fscale = 1e6: same iterations, same angles."""
    theta2 = math.radians(75)
    base = newton(four_bar_residuals(theta2, 4, 1, 3, 3), [0.3, 1.6], unknowns=[T3, T4], fscale=4)
    k = 1e6
    big = newton(four_bar_residuals(theta2, 4 * k, 1 * k, 3 * k, 3 * k), [0.3, 1.6], unknowns=[T3, T4], fscale=4 * k)
    assert big.converged and base.converged
    assert big.iterations == base.iterations
    np.testing.assert_allclose(big.x, base.x, rtol=0, atol=1e-12)


# ------------------------------------------------------------- failing solves
def test_singular_jacobian_is_reported_not_divided_through():
    # parallelogram four-bar (5, 2, 5, 2) at theta2 = 0 started where its Jacobian is singular
    x0 = [math.pi, math.pi]
    res = newton(four_bar_residuals(0.0, 5, 2, 5, 2), x0, unknowns=[T3, T4], fscale=5)
    assert not res.converged
    assert "singular" in res.message
    assert res.cond > 1e12
    assert np.all(np.isfinite(res.x))
    np.testing.assert_array_equal(res.x, x0)


def test_parallelogram_change_point_solve_is_singular():
    m = linkages.four_bar(5, 2, 5, 2)
    with pytest.warns(ConvergenceWarning, match="singular"):
        res = m.solve(0.0)
    assert not res.converged and not res.success
    assert "singular" in res.message
    assert not res.cond < 1e12
    assert np.all(np.isfinite(res.x))


def test_non_converging_solve_returns_converged_false_with_message():
    res = newton([X**2 + 1], [0.5], unknowns=[X], maxiter=30)
    assert not res.converged
    assert res.iterations == 30
    assert "did not converge" in res.message and "30" in res.message
    assert res.residual_norms[-1] > 0.1


def test_mechanism_solve_where_it_cannot_assemble():
    with pytest.warns(ConvergenceWarning, match="O2-A-B-O4"):
        res = linkages.four_bar(7, 4, 3, 5).solve(math.pi)  # beyond the triple rocker's 88.98 deg
    assert not res.converged
    assert "O2-A-B-O4" in res.message


# ------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"jacobian": "bogus"}, "jacobian"),
        ({"jacobian": 3}, "jacobian"),
        ({"x0": [1.0, 2.0]}, "x0"),
        ({"x0": [math.nan]}, "x0"),
        ({"x0": [[1.0]]}, "x0"),
        ({"tol": -1.0}, "tol"),
        ({"tol": math.nan}, "tol"),
        ({"maxiter": 0}, "maxiter"),
    ],
)
def test_bad_inputs_name_the_parameter(kwargs, fragment):
    args = {"x0": [1.0]}
    args.update(kwargs)
    x0 = args.pop("x0")
    with pytest.raises(ValueError, match=fragment):
        newton([X**2 - 2], x0, unknowns=[X], **args)


def test_unknown_symbol_in_sympy_residuals_is_named():
    with pytest.raises(ValueError, match=r"\by\b.*unknowns|unknowns.*\by\b"):
        newton([X**2 - Y], [1.0], unknowns=[X])


def test_sympy_system_without_unknowns():
    with pytest.raises(ValueError, match="unknowns"):
        newton([X**2 - 2], [1.0])


@pytest.mark.parametrize(
    "fun, x0",
    [
        ([X**2 - 2, X - 1], [1.0]),  # 2 residuals, 1 unknown
        (lambda v: np.array([v[0], v[1], 1.0]), [1.0, 2.0]),  # callable returning 3 for 2
    ],
)
def test_non_square_system(fun, x0):
    kwargs = {"unknowns": [X]} if isinstance(fun, list) else {}
    with pytest.raises(ValueError, match="square"):
        newton(fun, x0, **kwargs)


def test_symbolic_jacobian_needs_sympy_residuals():
    with pytest.raises(ValueError, match="jacobian"):
        newton(lambda v: v**2 - 2, [1.0], jacobian="symbolic")


def test_callable_jacobian_of_wrong_shape():
    with pytest.raises(ValueError, match="jacobian"):
        newton(lambda v: v**2 - 2, [1.0], jacobian=lambda v: np.eye(2))


@pytest.mark.parametrize(
    "args, kwargs, fragment",
    [
        ((math.nan,), {}, "input_value"),
        (("ninety",), {}, "input_value"),
        ((0.5,), {"tol": 0.0}, "tol"),
        ((0.5,), {"maxiter": 0}, "maxiter"),
        ((0.5,), {"jacobian": "exact"}, "jacobian"),
        ((0.5,), {"guess": [1.0, 2.0, 3.0]}, "guess"),
    ],
)
def test_mechanism_solve_bad_input(args, kwargs, fragment):
    with pytest.raises(ValueError, match=fragment):
        linkages.four_bar(4, 1, 3, 3).solve(*args, **kwargs)


@pytest.mark.parametrize("jacobian", ["symbolic", "forward", "central"])
def test_mechanism_solve_matches_circle_intersection(jacobian):
    for deg in (0.0, 75.0, 200.0, 330.0):
        res = linkages.four_bar(4, 1, 3, 3).solve(math.radians(deg), jacobian=jacobian)
        assert res.converged and res.success and res.nit == res.iterations
        np.testing.assert_allclose(res.x, open_four_bar(math.radians(deg), 4, 1, 3, 3), rtol=0, atol=1e-12)


# --------------------------------------------------------------- iterates and counts
def test_iterates_follow_newtons_recurrence_by_hand():
    # x^2 - 2 from 1: x_{k+1} = x_k - (x_k^2 - 2) / (2 x_k), written out here
    res = newton([X**2 - 2], [1.0], unknowns=[X])
    expected = [1.0]
    for _ in range(res.iterations):
        x = expected[-1]
        expected.append(x - (x * x - 2) / (2 * x))
    np.testing.assert_allclose(res.iterates[:, 0], expected, rtol=1e-15)
    assert res.iterates.shape == (res.iterations + 1, 1)
    assert res.iterates[-1, 0] == res.x[0] and res.converged


@pytest.mark.parametrize("jacobian, per_jacobian", [("symbolic", 0), ("forward", 2), ("central", 4)])
def test_nfev_and_njev_count_as_scipy_does(jacobian, per_jacobian):
    # one residual evaluation at the start and after every step; one Jacobian per step, a
    # finite-difference Jacobian costing n (forward) or 2n (central) residual evaluations (n = 2)
    fun = [X**2 + Y**2 - 4, X - Y]
    if jacobian == "symbolic":
        res = newton(fun, [1.0, 0.5], unknowns=[X, Y])
    else:
        f = sp.lambdify([X, Y], fun)
        res = newton(lambda v: np.array(f(*v)), [1.0, 0.5], jacobian=jacobian)
    assert res.converged
    assert res.njev == res.iterations
    assert res.nfev == 1 + res.iterations * (1 + per_jacobian)


def test_mechanism_solve_keeps_its_iterates():
    m = linkages.four_bar(4, 1, 3, 3)
    res = m.solve(math.radians(90), {"theta3": 0.5, "theta4": 2.0})
    assert res.converged and res.iterates.shape == (res.iterations + 1, 2)
    np.testing.assert_array_equal(res.iterates[0], [0.5, 2.0])
    np.testing.assert_array_equal(res.iterates[-1], res.x)
    assert res.njev == res.iterations and res.nfev == res.iterations + 1


def test_one_stopping_rule_at_the_round_off_floor():
    # a residual stuck above tol at the floor of huge angles, its steps no longer shrinking, has converged
    assert has_converged(3e-12, 1e-13, 1e-13, 1e-12, floor=4e-12)
    assert not has_converged(3e-12, 1e-13, 1e-13, 1e-12)
    assert not has_converged(3e-12, 1e-14, 1e-12, 1e-12, floor=4e-12)  # still shrinking
    arr = has_converged(np.array([3e-12, 5e-12]), np.array([1e-13, 1e-13]),
                                      np.array([1e-13, 1e-13]), 1e-12, 4e-12)
    assert arr.tolist() == [True, False]


def test_scaled_cond_of_a_complex_step_jacobian_is_the_real_ones():
    from numkin.newton_rules import scaled_cond

    rng = np.random.default_rng(3)
    real = rng.normal(size=(5, 3, 3))
    xscale = np.array([1.0, 2.0, 0.5])
    expected = np.linalg.cond(real * xscale[None, None, :] / 4.0)
    np.testing.assert_allclose(scaled_cond(real + 1e-30j * rng.normal(size=real.shape), 4.0, xscale), expected,
                               rtol=1e-12)
    # a finite imaginary part is not dropped: the complex matrix's own condition number
    big = real + 0.5j * rng.normal(size=real.shape)
    np.testing.assert_allclose(scaled_cond(big, 4.0, xscale), np.linalg.cond(big * xscale[None, None, :] / 4.0),
                               rtol=1e-12)


@pytest.mark.parametrize("x0, fragment", [
    ([], "at least one unknown"),
    (None, "a number or a sequence of numbers, got None"),
    ("1.0", "a number or a sequence of numbers"),
    ([[1.0, 2.0]], "1-D guess"),
    ([1.0, math.inf], "non-finite entry at index 1"),
])
def test_a_guess_that_is_not_one_is_named(x0, fragment):
    with pytest.raises(InputError, match=fragment):
        newton(lambda v: v, x0)

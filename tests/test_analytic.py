"""Tests for numkin.analytic: exact velocities and accelerations.

References are independent of the code under test: closed forms derived
here (by hand or with sympy), hand-evaluated textbook formulas, the
homework's numbers, and the complex-step derivative.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from numkin import SingularityWarning, analytic, expressions, linkages
from numkin.errors import InputError
from numkin.units import UnitError

DEG = np.radians(np.arange(0.0, 361.0))  # 1° grid over one turn
RPM_6000 = 6000 * 2 * math.pi / 60  # rad/s


@pytest.fixture(scope="module")
def homework():
    return linkages.chained_four_bars().sweep(DEG)


@pytest.fixture(scope="module")
def six_bar():
    return linkages.six_bar().sweep(DEG)


@pytest.fixture(scope="module")
def slider():
    return linkages.slider_crank(80, 200).sweep(DEG)


# ----------------------------------------------------------------- homework (source 003)
def test_homework_beta_at_100_degrees(homework):
    kin = analytic.kinematics(homework, omega="450 rad/min")
    row = kin.iloc[100]
    assert row["theta"] == pytest.approx(math.radians(100))
    assert row["omega_beta"] == pytest.approx(10.6329, abs=5e-5)
    assert row["alpha_beta"] == pytest.approx(-28.3750, abs=5e-5)
    # the assignment's loose checks
    assert abs(row["omega_beta"] - 10) < 1
    assert abs(row["alpha_beta"] - (-25)) < 4


def test_homework_columns_and_units(homework):
    kin = analytic.kinematics(homework, 7.5)
    assert list(kin.columns) == [
        "theta", "omega_phi", "alpha_phi", "omega_psi", "alpha_psi",
        "omega_beta", "alpha_beta", "omega_gamma", "alpha_gamma",
    ]
    assert kin.attrs["units"]["omega_beta"] == "rad/s"
    assert kin.attrs["units"]["alpha_beta"] == "rad/s^2"
    assert kin.attrs["units"]["theta"] == "rad"
    assert len(kin) == DEG.size


def test_chain_rule_through_first_loop(homework):
    """beta depends on theta only through phi: dbeta/dtheta = dbeta/dalpha * dphi/dtheta.

    dbeta/dalpha is that of linkage 2 alone, from its own loop closure written
    out by hand (differentiate r2 e^{i beta} + r3 e^{i gamma} + r4 e^{i(alpha+pi)} = r1).
    """
    dq, _ = analytic.derivatives(homework)
    u = homework.unknowns
    phi_p, beta_p = dq[u.index("phi")], dq[u.index("beta")]
    beta, gamma = homework["beta"], homework["gamma"]
    alpha = homework["phi"] + math.radians(149)
    r2, r3, r4 = 1.26, 1.87, 2.39
    # r2 b' e^{i beta} i + r3 g' e^{i gamma} i - r4 e^{i alpha} i = 0; eliminate g' (multiply by e^{-i gamma}, take Im)
    dbeta_dalpha = r4 * np.sin(alpha - gamma) / (r2 * np.sin(beta - gamma))
    np.testing.assert_allclose(beta_p, dbeta_dalpha * phi_p, rtol=1e-9, atol=1e-12)


# ----------------------------------------------------------------- slider-crank (source 004)
def _slider_closed_form(theta, r, l, e=0.0):
    """x, x', x'' and theta3, theta3', theta3'' of the slider-crank, differentiated by hand."""
    s, s1, s2 = r * np.sin(theta) - e, r * np.cos(theta), -r * np.sin(theta)
    u = np.sqrt(l**2 - s**2)
    u1 = -s * s1 / u
    u2 = -(s1**2 + s * s2) / u - s**2 * s1**2 / u**3
    x, x1, x2 = r * np.cos(theta) + u, -r * np.sin(theta) + u1, -r * np.cos(theta) + u2
    # sin(theta3) = -s / l
    t3 = -np.arcsin(s / l)
    t31 = -s1 / u
    t32 = -(s2 * u - s1 * u1) / u**2
    return x, x1, x2, t3, t31, t32


def test_piston_acceleration_textbook_values(slider):
    kin = analytic.kinematics(slider, omega="6000 rpm")
    a_m = kin["a_x"].to_numpy() / 1000.0  # mm/s^2 -> m/s^2
    R, L = 0.080, 0.200
    assert -R * RPM_6000**2 * (1 + R / L) == pytest.approx(-44215.8, abs=0.05)
    assert a_m[0] == pytest.approx(-44215.8, abs=0.05)
    assert a_m[90] == pytest.approx(13783.8, abs=0.05)
    assert a_m[180] == pytest.approx(-R * RPM_6000**2 * (-1 + R / L), abs=0.05)


@pytest.mark.parametrize("offset", [0.0, 25.0, -40.0])
def test_slider_crank_against_closed_form(offset):
    sweep = linkages.slider_crank(80, 200, offset).sweep(DEG)
    x, x1, x2, t3, t31, t32 = _slider_closed_form(DEG, 80, 200, offset)
    np.testing.assert_allclose(sweep["x"], x, rtol=1e-12)
    np.testing.assert_allclose(sweep["theta3"], t3, atol=1e-12)
    w, a = RPM_6000, 150.0  # an input that also accelerates
    kin = analytic.kinematics(sweep, w, alpha=a)
    np.testing.assert_allclose(kin["v_x"], w * x1, rtol=1e-10, atol=1e-10 * 80 * w)
    np.testing.assert_allclose(kin["a_x"], w**2 * x2 + a * x1, rtol=1e-10, atol=1e-10 * 80 * w**2)
    np.testing.assert_allclose(kin["omega_theta3"], w * t31, rtol=1e-10, atol=1e-12 * w)
    np.testing.assert_allclose(kin["alpha_theta3"], w**2 * t32 + a * t31, rtol=1e-10, atol=1e-10 * w**2)


def test_piston_as_a_point(slider):
    pk = analytic.point_kinematics(slider, "6000 rpm", points=["P", "A"])
    kin = analytic.kinematics(slider, "6000 rpm")
    assert list(pk.columns) == [
        "theta", "x_P", "y_P", "vx_P", "vy_P", "ax_P", "ay_P", "x_A", "y_A", "vx_A", "vy_A", "ax_A", "ay_A",
    ]
    np.testing.assert_allclose(pk["ax_P"], kin["a_x"], rtol=1e-12, atol=1e-6)
    np.testing.assert_allclose(pk["ay_P"], 0.0, atol=1e-9)
    # crank pin A on a circle of radius 80 mm: v = r w, a = r w^2 towards O
    w = RPM_6000
    np.testing.assert_allclose(pk["vx_A"], -80 * w * np.sin(DEG), atol=1e-9 * 80 * w)
    np.testing.assert_allclose(pk["vy_A"], 80 * w * np.cos(DEG), atol=1e-9 * 80 * w)
    np.testing.assert_allclose(pk["ax_A"], -80 * w**2 * np.cos(DEG), atol=1e-9 * 80 * w**2)
    np.testing.assert_allclose(pk["ay_A"], -80 * w**2 * np.sin(DEG), atol=1e-9 * 80 * w**2)
    assert pk.attrs["units"]["ax_P"] == "mm/s^2"


# ----------------------------------------------------------------- six-bar (source 001)
def _six_bar_closed_form():
    """x_D(theta2) of the six-bar by two circle intersections, and its derivatives (sympy)."""
    t = sp.Symbol("t", real=True)
    l2, l3, l41, l42, l43, l5 = 1, 4, 3, sp.Rational(16, 5), 6, sp.Rational(13, 2)
    o4 = sp.Matrix([sp.Rational(37, 10), -2])
    yd = 3
    A = sp.Matrix([l2 * sp.cos(t), l2 * sp.sin(t)])
    # B: on the circle of radius l3 about A and of radius l41 about O4
    dv = o4 - A
    d = sp.sqrt(dv.dot(dv))
    cg = (l3**2 + d**2 - l41**2) / (2 * l3 * d)
    sg = sp.sqrt(1 - cg**2)
    rot = sp.Matrix([[cg, -sg], [sg, cg]])  # the document's branch: B to the left of A->O4
    B = A + l3 / d * rot * dv
    # C: BC turned from O4B by beta, the exterior angle at B of the triangle O4-B-C
    cb = (l41**2 + sp.Rational(16, 5) ** 2 - l43**2) / (2 * l41 * l42)
    cbeta, sbeta = -cb, sp.sqrt(1 - cb**2)
    u = (B - o4) / l41
    C = B + l42 * sp.Matrix([[cbeta, -sbeta], [sbeta, cbeta]]) * u
    # D on y = yd, at distance l5 from C, to the left of C
    xD = C[0] - sp.sqrt(l5**2 - (C[1] - yd) ** 2)
    x1 = sp.diff(xD, t)
    return [sp.lambdify(t, e, "numpy", cse=True) for e in (xD, x1, sp.diff(x1, t))]


def test_six_bar_slider_against_closed_form(six_bar):
    x, x1, x2 = (f(DEG) for f in _six_bar_closed_form())
    np.testing.assert_allclose(six_bar["x"], x, rtol=0, atol=1e-11)
    w = -10.0  # the crank turns clockwise
    kin = analytic.kinematics(six_bar, "-10 rad/s")
    scale_v, scale_a = np.abs(w * x1).max(), np.abs(w**2 * x2).max()
    np.testing.assert_allclose(kin["v_x"], w * x1, rtol=0, atol=1e-10 * scale_v)
    np.testing.assert_allclose(kin["a_x"], w**2 * x2, rtol=0, atol=1e-10 * scale_a)
    pk = analytic.point_kinematics(six_bar, w, points="D")
    np.testing.assert_allclose(pk["vx_D"], w * x1, rtol=0, atol=1e-10 * scale_v)
    np.testing.assert_allclose(pk["ax_D"], w**2 * x2, rtol=0, atol=1e-10 * scale_a)
    assert kin.attrs["units"]["a_x"] == "cm/s^2"


def test_sign_of_input_speed(six_bar):
    plus = analytic.kinematics(six_bar, 10.0)
    minus = analytic.kinematics(six_bar, -10.0)
    np.testing.assert_array_equal(minus["v_x"], -plus["v_x"])
    np.testing.assert_array_equal(minus["a_x"], plus["a_x"])


# ----------------------------------------------------------------- complex step
@pytest.mark.parametrize(
    "build", [linkages.chained_four_bars, linkages.six_bar, linkages.quick_return,
              lambda: linkages.slider_crank(80, 200, 20)],
    ids=["chained", "six-bar", "quick-return", "slider-crank"],
)
def test_analytic_agrees_with_complex_step(build):
    sweep = build().sweep(DEG)
    dq, d2q = analytic.derivatives(sweep)
    c1 = analytic.complex_step(sweep)
    c2 = analytic.complex_step(sweep, order=2)
    for exact, ref in ((dq, c1), (d2q, c2)):
        scale = np.abs(ref).max(axis=1, keepdims=True)
        assert np.all(np.abs(exact - ref) <= 1e-10 * scale)
    # and as time derivatives: omega = w q', alpha = w^2 q'' + a q'
    w, a = -3.0, 0.5
    kin = analytic.kinematics(sweep, w, alpha=a)
    for k, name in enumerate(sweep.unknowns):
        v, acc = ("omega", "alpha") if name in sweep.mechanism.angles else ("v", "a")
        ref_v, ref_a = w * c1[k], w**2 * c2[k] + a * c1[k]
        assert np.max(np.abs(kin[f"{v}_{name}"] - ref_v)) <= 1e-10 * np.abs(ref_v).max()
        assert np.max(np.abs(kin[f"{acc}_{name}"] - ref_a)) <= 1e-10 * np.abs(ref_a).max()


def test_complex_step_is_a_derivative_of_the_position():
    """Independent of the loop equations' derivatives: compare with the closed form."""
    sweep = linkages.slider_crank(80, 200).sweep(DEG)
    _, x1, x2, _, t31, _ = _slider_closed_form(DEG, 80, 200)
    c1 = analytic.complex_step(sweep, h=1e-20)
    np.testing.assert_allclose(c1[1], x1, rtol=0, atol=1e-12 * 80)
    np.testing.assert_allclose(c1[0], t31, rtol=0, atol=1e-12)
    np.testing.assert_allclose(analytic.complex_step(sweep, order=2)[1], x2, rtol=0, atol=1e-11 * 80)


def test_complex_step_arguments(slider):
    with pytest.raises(ValueError, match="h must be"):
        analytic.complex_step(slider, h=0)
    with pytest.raises(ValueError, match="order"):
        analytic.complex_step(slider, order=3)


# ----------------------------------------------------------------- units and arguments
def test_input_speed_strings(slider):
    a = analytic.kinematics(slider, "6000 rpm")
    b = analytic.kinematics(slider, RPM_6000)
    np.testing.assert_allclose(a["a_x"], b["a_x"], rtol=1e-15)
    c = analytic.kinematics(slider, 10.0, alpha="600 rad/min^2")
    d = analytic.kinematics(slider, "600 rad/min", alpha=600 / 3600)
    np.testing.assert_allclose(c["a_x"], d["a_x"], rtol=1e-14)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"omega": "10 rad/s^2"}, "omega.*angular acceleration, not an angular speed"),
        ({"omega": "5 m/s"}, "omega.*linear speed"),
        ({"omega": 1.0, "alpha": "3 rad/s"}, "alpha.*angular speed, not an angular acceleration"),
        ({"omega": "fast"}, "omega"),
    ],
)
def test_wrong_dimension_is_a_clear_error(slider, kwargs, match):
    with pytest.raises(UnitError, match=match):
        analytic.kinematics(slider, **kwargs)


def test_per_point_input_speed(slider):
    w = np.linspace(100, 200, DEG.size)
    kin = analytic.kinematics(slider, w)
    _, x1, _, _, _, _ = _slider_closed_form(DEG, 80, 200)
    np.testing.assert_allclose(kin["v_x"], w * x1, rtol=1e-10, atol=1e-8)
    with pytest.raises(ValueError, match=r"omega.*shape \(361,\)"):
        analytic.kinematics(slider, np.ones(3))
    with pytest.raises(InputError, match="omega"):
        analytic.kinematics(slider, None)


def test_points_errors(slider):
    with pytest.raises(ValueError, match=r"no points \['Z'\].*\['O', 'A', 'P'\]"):
        analytic.point_kinematics(slider, 1.0, points="Z")


def test_not_a_sweep():
    with pytest.raises(InputError, match="Sweep"):
        analytic.derivatives(np.zeros((2, 3)))


# ----------------------------------------------------------------- laziness and singular points
def test_position_only_never_differentiates():
    mech = linkages.four_bar(4, 1, 3, 3)
    sweep = mech.sweep(np.radians(np.arange(0, 91)))

    def second_compiled():  # the lazily compiled acceleration equations of CompiledMechanism (alone or fused)
        return any(name in ("_second", "_rates") for name in vars(mech.compiled))

    assert not second_compiled()
    analytic.tangent(sweep)
    analytic.complex_step(sweep)
    assert not second_compiled()
    assert mech not in expressions._CACHE
    analytic.derivatives(sweep)
    assert second_compiled()
    analytic.point_kinematics(sweep, 1.0)
    assert mech in expressions._CACHE


def test_singular_points_are_nan_with_a_warning(slider):
    cond = slider.cond.copy()
    cond[45] = 1e15  # as a sweep through a change point with on_singular="report" records it
    bad = dataclasses.replace(slider, cond=cond)
    with pytest.warns(SingularityWarning, match=r"45\.000°"):
        dq, d2q = analytic.derivatives(bad)
    assert np.isnan(dq[:, 45]).all() and np.isnan(d2q[:, 45]).all()
    assert np.isfinite(np.delete(dq, 45, axis=1)).all()


def test_regular_sweep_does_not_warn(slider):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        analytic.kinematics(slider, 1.0)
        analytic.complex_step(slider)


# ----------------------------------------------------------------- properties
def _crank_rocker(dims) -> bool:
    """Grashof crank-rocker whose transmission angle stays within [15°, 165°] (away from toggles)."""
    ground, crank, coupler, rocker = dims
    if linkages.grashof(ground, crank, coupler, rocker) != "Grashof crank-rocker":
        return False
    d2 = ground**2 + crank**2 - 2 * ground * crank * np.cos(np.linspace(0, 2 * np.pi, 721))
    cos_mu = (coupler**2 + rocker**2 - d2) / (2 * coupler * rocker)
    return bool(np.all(np.abs(cos_mu) <= math.cos(math.radians(15))))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(
    st.tuples(st.floats(2.0, 5.0), st.floats(0.3, 1.5), st.floats(2.0, 5.0), st.floats(2.0, 5.0)).filter(_crank_rocker),
    st.sampled_from(["open", "crossed"]),
)
def test_property_four_bar_analytic_equals_complex_step(dims, branch):
    sweep = linkages.four_bar(*dims, branch=branch).sweep(np.radians(np.arange(0.0, 361.0, 5.0)))
    dq, d2q = analytic.derivatives(sweep)
    for exact, ref in ((dq, analytic.complex_step(sweep)), (d2q, analytic.complex_step(sweep, order=2))):
        assert np.all(np.abs(exact - ref) <= 1e-10 * np.abs(ref).max(axis=1, keepdims=True))


@settings(max_examples=15, deadline=None)
@given(st.floats(5.0, 200.0), st.floats(-0.3, 0.3), st.floats(0.25, 4.0))
def test_property_slider_crank_analytic_equals_complex_step(crank, offset, margin):
    """Rod = crank (1 + |offset| + margin): the rod always reaches the piston line, away from toggles."""
    rod = crank * (1 + abs(offset) + margin)
    sweep = linkages.slider_crank(crank, rod, crank * offset).sweep(np.radians(np.arange(0.0, 361.0, 5.0)))
    dq, d2q = analytic.derivatives(sweep)
    for exact, ref in ((dq, analytic.complex_step(sweep)), (d2q, analytic.complex_step(sweep, order=2))):
        assert np.all(np.abs(exact - ref) <= 1e-10 * np.abs(ref).max(axis=1, keepdims=True))
    # and the velocity is the closed form's
    x1 = _slider_closed_form(sweep.inputs, crank, rod, crank * offset)[1]
    np.testing.assert_allclose(dq[1], x1, rtol=0, atol=1e-10 * crank)


def test_exactly_singular_systems_give_nan_not_an_exception():
    def solve(q, t):
        jac = np.where((t == 1.0)[:, None, None], 0.0, np.eye(2))  # singular at t = 1
        return np.linalg.solve(jac, q.T[..., None])[..., 0].T

    from numkin.complex_solve import _columnwise

    out = _columnwise(solve, np.ones((2, 3)), np.array([0.0, 1.0, 2.0]))
    np.testing.assert_array_equal(out[:, [0, 2]], 1.0)
    assert np.isnan(out[:, 1]).all()


# --------------------------------------------------------------------------- change points
def _crossed_antiparallelogram(degrees):
    import warnings as _w

    mech = linkages.four_bar(5, 2, 5, 2, branch="crossed")
    with _w.catch_warnings():
        _w.simplefilter("ignore")
        return mech.sweep(np.radians(degrees), on_singular="report")


def test_change_point_gives_the_kept_branch():
    """Anti-parallelogram 5/2/5/2 at theta2 = 180 deg, where the branches meet.

    With theta2 = pi + e, theta3 = d3, theta4 = pi + d4, the loop
    2 e^(i theta2) + 5 e^(i theta3) = 5 + 2 e^(i theta4) gives, to first order
    in the imaginary part, -2e + 5 d3 = -2 d4, and to second order in the real
    part e^2 - 5 d3^2 / 2 = d4^2.  With r = d4/e: 7 r^2 - 4 r - 3 = 0, so
    r = 1 (parallelogram) or r = -3/7 (crossed), and d3/e = (2 - 2r)/5 = 4/7.
    """
    sweep = _crossed_antiparallelogram(np.arange(1, 360))
    assert any(e.kind == "change point" for e in sweep.events)
    k = int(np.argmin(np.abs(sweep.inputs - np.pi)))
    with pytest.warns(SingularityWarning, match=r"dtheta4/dtheta2 = -0\.4286"):
        dq, d2q = analytic.derivatives(sweep, at_change_point="continue")
    assert dq[1, k] == pytest.approx(-3 / 7, abs=1e-6)
    assert dq[0, k] == pytest.approx(4 / 7, abs=1e-6)
    assert d2q[:, k] == pytest.approx([0.0, 0.0], abs=1e-6)  # symmetric about 180 deg on this branch
    with pytest.warns(SingularityWarning):
        assert analytic.tangent(sweep, at_change_point="continue")[1, k] == pytest.approx(-3 / 7, abs=1e-6)
    with pytest.warns(SingularityWarning):
        kin = analytic.kinematics(sweep, 2.0, at_change_point="continue")
    assert kin["omega_theta4"][k] == pytest.approx(-6 / 7, abs=1e-5)


def test_change_point_is_nan_by_default_with_the_kept_branch_named():
    """Never the number of no branch (0.2857 before): NaN, and the warning gives -3/7."""
    sweep = _crossed_antiparallelogram(np.arange(1, 360))
    k = int(np.argmin(np.abs(sweep.inputs - np.pi)))
    with pytest.warns(SingularityWarning, match=r"set to NaN.*dtheta4/dtheta2 = -0\.4286.*at_change_point='continue'"):
        dq, d2q = analytic.derivatives(sweep)
    assert np.all(np.isnan(dq[:, k])) and np.all(np.isnan(d2q[:, k]))
    assert np.all(np.isfinite(np.delete(dq, k, axis=1)))
    with pytest.raises(ValueError, match="at_change_point"):
        analytic.derivatives(sweep, at_change_point="guess")


def test_change_point_without_neighbours_is_nan_with_the_reason():
    sweep = _crossed_antiparallelogram([178.0, 179.0, 180.0, 181.0])
    with pytest.warns(SingularityWarning, match="fewer than 2 regular samples"):
        dq, _ = analytic.derivatives(sweep)
    assert np.all(np.isnan(dq[:, 2]))
    assert np.all(np.isfinite(dq[:, [0, 1, 3]]))


def test_change_point_found_from_the_jacobian_sign():
    """Found from the sign change of det J between the neighbours, whether or not recorded."""
    sweep = dataclasses.replace(_crossed_antiparallelogram(np.arange(1, 360)), events=[])
    k = int(np.argmin(np.abs(sweep.inputs - np.pi)))
    with pytest.warns(SingularityWarning, match="kept branch continues smoothly"):
        dq, _ = analytic.derivatives(sweep, at_change_point="continue")
    assert dq[1, k] == pytest.approx(-3 / 7, abs=1e-6)


# --------------------------------------------------------------------------- lost digits
def _toggle_reference(distance_deg):
    """theta4 of the 4/2/4.0001/2 four-bar (branch through theta3 = -0.00707 rad) near its
    limit, in 50-digit arithmetic: circle intersection, derivatives by mpmath."""
    import mpmath as mp

    mp.mp.dps = 50
    a, b, c, d = 4, 2, mp.mpf("4.0001"), 2
    limit = mp.acos((a**2 + b**2 - (c - d) ** 2) / (2 * a * b))
    theta = limit + mp.radians(mp.mpf(distance_deg))

    def theta4(t):
        ax, ay = b * mp.cos(t), b * mp.sin(t)
        length = mp.sqrt((a - ax) ** 2 + ay**2)
        t3 = mp.atan2(-ay, a - ax) + mp.acos((c**2 + length**2 - d**2) / (2 * c * length))
        return mp.atan2(ay + c * mp.sin(t3), ax + c * mp.cos(t3) - a)

    return float(theta), float(mp.diff(theta4, theta)), float(mp.diff(theta4, theta, 2))


def test_lost_digits_near_a_toggle_warn_and_bound_the_error():
    theta, d1, d2 = _toggle_reference("1e-9")
    sweep = linkages.four_bar(4, 2, 4.0001, 2).sweep(np.array([theta]))
    with pytest.warns(analytic.LostDigitsWarning, match="estimated relative error"):
        dq, d2q = analytic.derivatives(sweep)
    err1, err2 = abs(dq[1, 0] / d1 - 1), abs(d2q[1, 0] / d2 - 1)
    assert 1e-4 < err1 < 1e-2 and 1e-4 < err2 < 1e-2  # about 0.09 % and 0.27 %
    cond = sweep.cond[0]
    assert analytic.lost_digits(cond, 1) >= err1 and analytic.lost_digits(cond, 2) >= err2


def test_no_lost_digits_warning_far_from_the_toggle():
    import warnings as _w

    theta, d1, _ = _toggle_reference("10")
    sweep = linkages.four_bar(4, 2, 4.0001, 2).sweep(np.array([theta]))
    with _w.catch_warnings():
        _w.simplefilter("error", analytic.LostDigitsWarning)
        dq, _ = analytic.derivatives(sweep)
    assert dq[1, 0] == pytest.approx(d1, rel=1e-10)


def test_kinematics_columns_carry_their_quantities():
    sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 90.0]))
    kin = analytic.kinematics(sweep, "6000 rpm")
    q = kin.attrs["quantities"]
    assert list(q) == list(kin.columns)
    assert (q["a_x"].order, q["a_x"].unit, q["a_x"].source) == (2, "mm/s^2", "analytic")
    assert kin.attrs["units"] == {name: quantity.unit for name, quantity in q.items()}
    pk = analytic.point_kinematics(sweep, "6000 rpm", points="P")
    assert pk.attrs["quantities"]["ay_P"].axis == "y"

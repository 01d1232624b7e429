"""Tests for numkin.kinematics: velocities and accelerations by finite differences.

References: the homework's numbers (source 003), closed forms derived here,
and the analytic derivatives (themselves checked against closed forms and the
complex step in test_analytic.py) for orders of convergence.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from numkin import InputError, analytic, derivatives, kinematics, linkages

DEG = np.radians(np.arange(0.0, 361.0))
W_HW = 450.0 / 60.0  # 450 rad/min in rad/s


@pytest.fixture(scope="module")
def homework():
    return linkages.chained_four_bars().sweep(DEG)


@pytest.fixture(scope="module")
def slider():
    return linkages.slider_crank(80, 200).sweep(DEG)


# ----------------------------------------------------------------- homework (source 003)
def test_homework_centred_and_second_difference(homework):
    fd = kinematics.finite_difference(homework, "450 rad/min")
    assert fd["omega_beta"][100] == pytest.approx(10.6330, abs=5e-5)
    assert fd["alpha_beta"][100] == pytest.approx(-28.3765, abs=5e-5)
    assert fd.attrs["periodic"] is True
    assert fd.attrs["h"] == pytest.approx(math.radians(1))


def test_homework_forward_as_the_student_computed_it(homework):
    """forward at i: (b[i+1] - b[i])/h; forward_of_forward at i: (b[i+2] - 2b[i+1] + b[i])/h^2.

    This is fw_diff applied twice in the homework's code, kept at the left
    sample i; the same numbers come out on the open grid and on the periodic
    one (theta = 100° is interior).
    """
    b = homework["beta"]
    h = math.radians(1)
    by_hand_v = W_HW * (b[101] - b[100]) / h
    by_hand_a = W_HW**2 * (b[102] - 2 * b[101] + b[100]) / h**2
    for periodic in ("auto", False):
        fw = kinematics.finite_difference(
            homework, "450 rad/min", method="forward", second_method="forward_of_forward", periodic=periodic
        )
        assert fw["omega_beta"][100] == pytest.approx(10.59998, abs=1e-5)  # 10.59998
        assert fw["alpha_beta"][100] == pytest.approx(-28.1266, abs=5e-5)
        assert fw["omega_beta"][100] == pytest.approx(by_hand_v, rel=1e-13)
        assert fw["alpha_beta"][100] == pytest.approx(by_hand_a, rel=1e-12)
    # the homework's open 0..360 grid: the last samples use the backward stencils
    fw = kinematics.finite_difference(homework, W_HW, method="forward", periodic=False)
    assert fw["omega_beta"].iloc[-1] == pytest.approx(W_HW * (b[-1] - b[-2]) / h, rel=1e-12)


def test_same_columns_as_analytic(homework):
    fd = kinematics.finite_difference(homework, W_HW)
    an = analytic.kinematics(homework, W_HW)
    assert list(fd.columns) == list(an.columns)
    assert fd.attrs["units"] == an.attrs["units"]
    np.testing.assert_array_equal(fd["theta"], homework.inputs)


def test_partial_sweep_is_an_open_grid(homework):
    part = linkages.chained_four_bars().sweep(np.radians(np.arange(0.0, 181.0)))
    fd = kinematics.finite_difference(part, W_HW)
    assert fd.attrs["periodic"] is False
    full = kinematics.finite_difference(homework, W_HW)
    np.testing.assert_allclose(fd["omega_beta"][1:-1], full["omega_beta"][1:180], rtol=1e-9)
    # one-sided second-order end stencil (-3b0 + 4b1 - b2)/(2h) at theta = 0
    b, h = part["beta"], math.radians(1)
    assert fd["omega_beta"][0] == pytest.approx(W_HW * (-3 * b[0] + 4 * b[1] - b[2]) / (2 * h), rel=1e-12)
    with pytest.raises(ValueError, match="one turn"):
        kinematics.finite_difference(part, W_HW, method="spectral")
    with pytest.raises(ValueError, match=r"exactly one turn.*spans 180°"):
        kinematics.finite_difference(part, W_HW, periodic=True)


# ----------------------------------------------------------------- slider-crank (source 004)
def test_piston_acceleration_by_second_difference(slider):
    fd = kinematics.finite_difference(slider, "6000 rpm")
    a_m = fd["a_x"].to_numpy() / 1000.0
    # closed form: -R w^2 (1 + R/L) at 0 and R^2 w^2 / sqrt(L^2 - R^2) at 90°; the second
    # difference at h = 1° is O(h^2) off: about 1e-4 relative
    assert a_m[0] == pytest.approx(-44215.8, rel=2e-4)
    assert a_m[90] == pytest.approx(13783.8, rel=2e-4)
    assert abs(a_m[90] - 13783.8) > 0.1  # ... and visibly so
    assert a_m[-1] == a_m[0]  # periodic: the last row repeats the first


# ----------------------------------------------------------------- order of convergence
@pytest.fixture(scope="module")
def homework_turns():
    mech = linkages.chained_four_bars()
    out = []
    for n in (90, 180, 360):
        sweep = mech.sweep(np.linspace(0.0, 2 * np.pi, n + 1))
        out.append((2 * np.pi / n, sweep, analytic.derivatives(sweep)))
    return out


@pytest.mark.parametrize(
    "scheme, order",
    [("forward", 1), ("centred", 2), ("five_point", 4), ("richardson", 4),
     ("forward_of_forward", 1), ("second_difference", 2), ("centred_of_centred", 2), ("five_point_second", 4)],
)
def test_observed_order_of_convergence(homework_turns, scheme, order):
    """Log-log slope of the max error over a full turn against h (h = 4°, 2°, 1°)."""
    hs, errors = [], []
    for h, sweep, (dq, d2q) in homework_turns:
        exact = dq if derivatives.get_scheme(scheme).derivative == 1 else d2q
        errors.append(np.max(np.abs(kinematics.sweep_derivative(sweep, scheme) - exact)))
        hs.append(h)
    slope = np.polyfit(np.log(hs), np.log(errors), 1)[0]
    assert slope == pytest.approx(order, abs=0.15)


def test_spectral_on_the_homework_sweep():
    """Spectral differentiation reaches 1e-11 at 180 points per turn, at the default tolerance.

    Its error is then the position error amplified by up to ~N/2, so this also
    checks that the sweep's positions are converged to the last digits.
    """
    sweep = linkages.chained_four_bars().sweep(np.linspace(0.0, 2 * np.pi, 181))
    dq = analytic.complex_step(sweep)
    assert np.max(np.abs(kinematics.sweep_derivative(sweep, "spectral") - dq)) <= 1e-11
    fd = kinematics.finite_difference(sweep, W_HW, method="spectral", second_method="spectral_second")
    an = analytic.kinematics(sweep, W_HW)
    assert np.max(np.abs(fd["omega_beta"] - an["omega_beta"])) <= 1e-11 * W_HW
    assert np.max(np.abs(fd["alpha_beta"] - an["alpha_beta"])) <= 1e-9 * np.abs(an["alpha_beta"]).max()


# ----------------------------------------------------------------- periodic grids and unwrapping
def test_links_that_turn_fully():
    """Double crank: coupler and follower gain 2*pi per turn; the wrap-around adds the offset."""
    mech = linkages.four_bar(1.0, 3.0, 3.5, 3.0)  # ground shortest: Grashof double crank
    sweep = mech.sweep(np.linspace(0.0, 2 * np.pi, 181))
    for name in ("theta3", "theta4"):
        assert sweep[name][-1] - sweep[name][0] == pytest.approx(2 * np.pi, abs=1e-9)
    dq, d2q = analytic.derivatives(sweep)
    h = 2 * np.pi / 180
    # a 2*pi jump reaching a quotient would make errors of order pi/h ~ 90
    for scheme, exact, tol in (("centred", dq, 1e-3), ("spectral", dq, 1e-10),
                               ("second_difference", d2q, 1e-2), ("spectral_second", d2q, 1e-8)):
        err = np.abs(kinematics.sweep_derivative(sweep, scheme) - exact)
        assert err.max() <= tol, scheme
        if "spectral" not in scheme:  # (spectral is at the rounding floor everywhere)
            assert np.all(err[:, 0] <= err[:, 1:-1].max(axis=1)), scheme  # no end effect at the wrap


def test_wrapped_angles_are_unwrapped_with_a_warning(homework):
    """Samples that are not a sweep's own unknowns (as atan2 returns them) are unwrapped before differencing."""
    from numkin.derivatives import get_scheme

    beta = homework["beta"]
    wrapped = (beta + np.pi) % (2 * np.pi) - np.pi
    assert np.any(np.abs(np.diff(wrapped)) > np.pi)
    grid = kinematics.sweep_grid(homework)
    with pytest.warns(UserWarning, match=r"\['beta'\] jump by more than 180°.*wrapped data; unwrapped"):
        rows = kinematics.prepare_rows(wrapped[None], True, ["beta"], homework.inputs, grid, 7.0)
    ref = kinematics.prepare_rows(beta[None], True, ["beta"], homework.inputs, grid, 7.0)
    np.testing.assert_allclose(rows.apply(get_scheme("centred")), ref.apply(get_scheme("centred")), atol=1e-9)
    # a sweep whose values were reduced modulo 2 pi: its tangent tells the wrap from a turn
    wrapped_sweep = dataclasses.replace(homework, values=(homework.values + np.pi) % (2 * np.pi) - np.pi)
    with pytest.warns(UserWarning, match=r"\['beta'\] jump by more than 180°.*wrapped data; unwrapped"):
        fd = kinematics.finite_difference(wrapped_sweep, W_HW)
    np.testing.assert_allclose(fd.drop(columns="theta"), kinematics.finite_difference(homework, W_HW).drop(
        columns="theta"), rtol=1e-7, atol=1e-7)


def test_a_sweep_whose_angle_turns_more_than_half_a_turn_between_samples_is_not_unwrapped():
    """A sweep's angles are continuous: on a grid of 90° steps the double crank's follower turns 199.7° in the
    first step, a real turn, kept (unwrapping it would lose the turn the follower makes per turn of the crank); the
    warning says the grid is too coarse. The spectral derivative's mean over the turn is then the follower's
    turns per turn of the crank, 1 (0 if the turn were unwrapped away)."""
    sweep = linkages.four_bar(1, 2, 2.995, 2).sweep(np.radians(np.linspace(0, 360, 5)))
    assert np.degrees(np.diff(sweep["theta4"]))[0] == pytest.approx(199.7, abs=0.05)
    with pytest.warns(UserWarning, match=r"\['theta4'\] turn by more than 180° .* by 199.7° .* too coarse"):
        fd = kinematics.finite_difference(sweep, 1.0, method="spectral", second_method="spectral_second")
    assert fd["omega_theta4"][:-1].mean() == pytest.approx(1.0, abs=1e-12)
    # compare reads the samples the same way: the same centred values
    from numkin.compare import compare

    with pytest.warns(UserWarning, match=r"\['theta4'\] turn by more than 180°"):
        table = compare(sweep, 1.0, "omega_theta4", schemes=("centred",)).table
    with pytest.warns(UserWarning, match="too coarse"):
        centred = kinematics.finite_difference(sweep, 1.0, method="centred")["omega_theta4"].to_numpy()
    np.testing.assert_array_equal(table["centred [rad/s]"].to_numpy(), centred)


def test_sweep_that_does_not_close(homework):
    values = homework.values.copy()
    values[0, -1] += 0.1
    broken = dataclasses.replace(homework, values=values)
    with pytest.raises(ValueError, match=r"\['phi'\] do not return"):
        kinematics.finite_difference(broken, W_HW, periodic=True)
    with pytest.warns(UserWarning, match="open grid"):
        fd = kinematics.finite_difference(broken, W_HW)
    assert fd.attrs["periodic"] is False


def test_descending_sweep(slider):
    """The same samples in descending order give the same derivatives (reversed)."""
    kw = {"method": "five_point", "second_method": "five_point_second"}
    down = dataclasses.replace(
        slider, inputs=slider.inputs[::-1].copy(), values=slider.values[:, ::-1].copy(), cond=slider.cond[::-1].copy()
    )
    a = kinematics.finite_difference(down, 5.0, **kw)
    b = kinematics.finite_difference(slider, 5.0, **kw)
    assert a.attrs["periodic"]
    np.testing.assert_allclose(a["v_x"][::-1].to_numpy(), b["v_x"].to_numpy(), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(a["a_x"][::-1].to_numpy(), b["a_x"].to_numpy(), rtol=1e-12, atol=1e-9)
    # a sweep solved downwards
    solved = linkages.slider_crank(80, 200).sweep(DEG[::-1])
    fd = kinematics.finite_difference(solved, 5.0, **kw)
    an = analytic.kinematics(solved, 5.0)
    assert np.max(np.abs(fd["a_x"] - an["a_x"])) <= 1e-6 * np.abs(an["a_x"]).max()


def test_accelerating_input(slider):
    w, acc = 20.0, -3.0
    fd = kinematics.finite_difference(slider, w, alpha=acc, method="five_point", second_method="five_point_second")
    h = math.radians(1)
    x = slider["x"]
    expected = w**2 * derivatives.five_point_second(x[:-1], h, periodic=True) + acc * derivatives.five_point(
        x[:-1], h, periodic=True
    )
    np.testing.assert_allclose(fd["a_x"][:-1], expected, rtol=1e-12)


# ----------------------------------------------------------------- errors
def test_non_uniform_grid_is_refused():
    sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 1.0, 2.0, 4.0, 5.0]))
    with pytest.raises(ValueError, match="uniform grid"):
        kinematics.finite_difference(sweep, 1.0)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"method": "second_difference"}, r"method='second_difference' estimates a second derivative"),
        ({"second_method": "centred"}, r"second_method='centred' estimates a first derivative"),
        ({"method": "sixth_order"}, "unknown finite-difference method"),
        ({"periodic": "yes"}, "periodic must be"),
        ({"omega": "3 rad/s^2"}, "omega"),
    ],
)
def test_argument_errors(slider, kwargs, match):
    kwargs = {"omega": 1.0, **kwargs}
    with pytest.raises(ValueError, match=match):
        kinematics.finite_difference(slider, **kwargs)


def test_too_few_points():
    sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 1.0, 2.0]))
    with pytest.raises(ValueError, match="at least"):
        kinematics.finite_difference(sweep, 1.0)


def test_no_warning_on_a_regular_sweep(homework):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        kinematics.finite_difference(homework, W_HW, method="spectral", second_method="spectral_second")


# ----------------------------------------------------------------- properties
def _transmission_ok(ground, crank, coupler, rocker, lo=math.radians(30)):
    """Transmission angle of a crank-rocker stays within [lo, pi - lo] over the turn (no toggle near)."""
    th = np.linspace(0, 2 * np.pi, 721)
    d2 = ground**2 + crank**2 - 2 * ground * crank * np.cos(th)
    cos_mu = (coupler**2 + rocker**2 - d2) / (2 * coupler * rocker)
    return np.all(np.abs(cos_mu) <= math.cos(lo))


crank_rockers = st.tuples(
    st.floats(2.0, 5.0), st.floats(0.4, 1.5), st.floats(2.0, 5.0), st.floats(2.0, 5.0)
).filter(lambda g: _transmission_ok(*g))

slider_cranks = st.tuples(st.floats(10.0, 100.0), st.floats(-0.5, 0.5), st.floats(0.3, 4.0)).map(
    # crank, rod = crank (1 + |offset| + margin), offset: the rod reaches the piston line with a margin (no toggle)
    lambda t: (t[0], t[0] * (1 + abs(t[1]) + t[2]), t[0] * t[1])
)


def _centred_ratio(mech):
    errors = []
    for n in (180, 360):
        sweep = mech.sweep(np.linspace(0.0, 2 * np.pi, n + 1))
        dq = analytic.complex_step(sweep)
        errors.append(np.max(np.abs(kinematics.sweep_derivative(sweep, "centred") - dq)))
    return errors[0] / errors[1]


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(crank_rockers)
def test_centred_error_quarters_when_h_halves_four_bar(dims):
    ground, crank, coupler, rocker = dims
    assume(linkages.grashof(ground, crank, coupler, rocker) == "Grashof crank-rocker")
    ratio = _centred_ratio(linkages.four_bar(ground, crank, coupler, rocker))
    assert ratio == pytest.approx(4.0, rel=0.2)


@settings(max_examples=12, deadline=None)
@given(slider_cranks)
def test_centred_error_quarters_when_h_halves_slider_crank(dims):
    ratio = _centred_ratio(linkages.slider_crank(*dims))
    assert ratio == pytest.approx(4.0, rel=0.2)


# --------------------------------------------------------------------------- rounding
def _slider_velocity(r, l, theta):
    """dx/dtheta from x = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta))."""
    s, c = np.sin(theta), np.cos(theta)
    return -r * s - r**2 * s * c / np.sqrt(l**2 - r**2 * s**2)


def test_rounding_error_estimate_bounds_tiny_steps_and_warns():
    from numkin.analytic import LostDigitsWarning

    mech = linkages.slider_crank(80, 200)
    theta = np.pi / 2 + 1e-9 * np.arange(11)
    sweep = mech.sweep(theta)
    with pytest.warns(LostDigitsWarning, match="forward_of_forward loses digits"):
        fd = kinematics.finite_difference(sweep, 1.0, method="forward", second_method="forward_of_forward")
    actual = np.abs(fd["v_x"].to_numpy() - _slider_velocity(80, 200, theta))
    estimate = kinematics.rounding_error(kinematics.scheme_for("forward", 1, "method"), 1e-9, sweep.values,
                                         sweep.cond, mech.xscale)[1]
    assert np.all(actual <= estimate) and actual.max() > 1e-7  # rounding, not truncation (h/2 x'' ~ 2e-8)


def test_a_rounding_warning_names_the_condition_number_it_used():
    """Next to a change point the estimate takes the largest condition number within the stencil's reach: the
    parallelogram-type 5/2/5/2 (crossed) meets its change point at 180° (the crank and coupler in line), and the
    warning at 179° names the condition number of the 180° sample, not the 179° one."""
    from numkin.analytic import LostDigitsWarning
    from numkin.sweep import SingularityWarning

    mech = linkages.four_bar(5, 2, 5, 2, branch="crossed")
    with pytest.warns(SingularityWarning):
        sweep = mech.sweep(np.radians(np.arange(10, 351)), on_singular="report")
    k179, k180 = 169, 170
    assert sweep.cond[k180] > 1e8 > 1e3 > sweep.cond[k179]
    with pytest.warns(LostDigitsWarning) as caught:
        kinematics.finite_difference(sweep, 10.0)
    text = str(next(w.message for w in caught if issubclass(w.category, LostDigitsWarning)))
    assert f"at input 179.000° (step h = 0.0175 rad, condition number {sweep.cond[k180]:.3g} at 180.000°, within " \
           "the stencil's reach)" in text
    # a descending sweep (340° down to 10°, not symmetric about 180°): the same reading
    with pytest.warns(SingularityWarning):
        down = mech.sweep(np.radians(np.arange(340.0, 9.0, -1.0)), on_singular="report")
    k180 = 160
    assert down.cond[k180] > 1e8
    with pytest.warns(LostDigitsWarning) as caught:
        kinematics.finite_difference(down, 10.0)
    text = str(next(w.message for w in caught if issubclass(w.category, LostDigitsWarning)))
    assert f"at input 181.000° (step h = 0.0175 rad, condition number {down.cond[k180]:.3g} at 180.000°" in text


def test_no_rounding_warning_on_a_degree_grid():
    import warnings

    from numkin.analytic import LostDigitsWarning

    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361)))
    with warnings.catch_warnings():
        warnings.simplefilter("error", LostDigitsWarning)
        kinematics.finite_difference(sweep, 1.0, method="five_point", second_method="five_point_second")


@pytest.mark.parametrize("kwargs, words", [
    ({"method": "centred"},
     "second_method='second_difference' (the default scheme for alpha) needs at least 4 points on an open grid; "
     "the sweep has 3"),
    ({"method": "five_point", "second_method": "centred_of_centred"},
     "method='five_point' (scheme for omega) needs at least 5 points on an open grid; the sweep has 3"),
])
def test_too_short_a_sweep_names_the_argument_and_its_scheme(kwargs, words):
    """Three points: the forward/centred differences fit, the second difference's one-sided ends (4 samples) and
    the five-point stencil do not; the error names the argument whose scheme needs more (a default one too)."""
    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians([0.0, 1.0, 2.0]))
    with pytest.raises(InputError) as caught:
        kinematics.finite_difference(sweep, 1.0, **kwargs)
    assert words in str(caught.value) and "last axis" not in str(caught.value)
    assert caught.value.cause == "too few samples"

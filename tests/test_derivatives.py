"""Tests for numkin.derivatives against closed-form derivatives."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from numkin import derivatives as fd

TWO_PI = 2.0 * np.pi

FIRST_DERIVATIVE = ["forward", "backward", "centred", "five_point", "richardson"]
SECOND_DERIVATIVE = [
    "second_difference",
    "forward_of_forward",
    "centred_of_centred",
    "five_point_second",
]
FINITE_DIFFERENCE = FIRST_DERIVATIVE + SECOND_DERIVATIVE

EXPECTED_ORDER = {
    "forward": 1,
    "backward": 1,
    "centred": 2,
    "five_point": 4,
    "richardson": 4,
    "second_difference": 2,
    "centred_of_centred": 2,
    "forward_of_forward": 1,
    "five_point_second": 4,
}


# Grid sizes for the observed-order fits.  One-sided fourth-order stencils
# for y'' have a large O(h**5) term, so the open grids must be fine enough to
# be asymptotic yet coarse enough that rounding (~eps/h**2) stays negligible:
# a factor-sqrt(2) progression spans that window.
PERIODIC_SIZES = [40, 80, 160, 320, 640]
OPEN_SIZES = [32, 45, 64, 90, 128]


# Closed-form test functions: (f, f', f'')


def exp_sin(x):
    return np.exp(np.sin(x))


def exp_sin_1(x):
    return np.cos(x) * np.exp(np.sin(x))


def exp_sin_2(x):
    return (np.cos(x) ** 2 - np.sin(x)) * np.exp(np.sin(x))


def periodic_grid(n):
    return np.arange(n) * (TWO_PI / n), TWO_PI / n


def open_grid(n, length):
    return np.linspace(0.0, length, n + 1), length / n


def exact(name, first, second):
    return first if fd.SCHEMES[name].derivative == 1 else second


def max_error(name, x, h, f, exact_derivative, periodic):
    estimate = fd.SCHEMES[name].function(f(x), h, periodic=periodic)
    return np.max(np.abs(estimate - exact_derivative(x)))


def observed_order(steps, errors):
    return np.polyfit(np.log(steps), np.log(errors), 1)[0]


# --------------------------------------------------------------------------
# Registry
# --------------------------------------------------------------------------


def test_registry_names():
    assert set(fd.SCHEMES) == set(FINITE_DIFFERENCE) | {"spectral", "spectral_second"}
    for name, scheme in fd.SCHEMES.items():
        assert scheme.name == name
        assert scheme.function is getattr(fd, name)
        assert scheme.derivative in (1, 2)
        assert scheme.stencil and scheme.description


def test_registry_orders_and_flags():
    # every built-in scheme has its order stated here (by hand, from its stencil's Taylor series)
    from numkin.schemes import BUILT_IN

    assert set(EXPECTED_ORDER) | {"spectral", "spectral_second", "complex_step"} == set(BUILT_IN)
    for name, order in EXPECTED_ORDER.items():
        assert fd.SCHEMES[name].order == order
        assert not fd.SCHEMES[name].periodic_only
    assert fd.SCHEMES["spectral"].periodic_only
    assert fd.SCHEMES["spectral_second"].periodic_only
    assert {fd.SCHEMES[name].derivative for name in FIRST_DERIVATIVE} == {1}
    assert {fd.SCHEMES[name].derivative for name in SECOND_DERIVATIVE} == {2}


def test_scheme_is_frozen():
    with pytest.raises(dataclasses.FrozenInstanceError):
        fd.SCHEMES["centred"].order = 3


@pytest.mark.parametrize(
    "alias, name",
    [
        ("central", "centred"),
        ("centered", "centred"),
        ("second", "second_difference"),
        ("five-point", "five_point"),
        ("centred", "centred"),
        ("spectral_second", "spectral_second"),
    ],
)
def test_get_scheme_aliases(alias, name):
    assert fd.get_scheme(alias).name == name


def test_get_scheme_unknown_lists_valid_names():
    with pytest.raises(ValueError, match="bogus") as info:
        fd.get_scheme("bogus")
    for name in fd.SCHEMES:
        assert name in str(info.value)


def test_differentiate_dispatches_by_method():
    x, h = periodic_grid(64)
    y = exp_sin(x)
    dy = fd.differentiate(y, h, method="five-point", periodic=True)
    np.testing.assert_allclose(dy, exp_sin_1(x), atol=1e-4)
    d2y = fd.differentiate(y, h, method="spectral_second", periodic=True)
    np.testing.assert_allclose(d2y, exp_sin_2(x), atol=1e-11)
    with pytest.raises(ValueError, match="nope"):
        fd.differentiate(y, h, method="nope")


# --------------------------------------------------------------------------
# Accuracy against exact derivatives
# --------------------------------------------------------------------------


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("name", FINITE_DIFFERENCE)
def test_sin_on_fine_grid(name, periodic):
    n = 720
    x, h = periodic_grid(n) if periodic else open_grid(n, np.pi)
    first, second = np.cos(x), -np.sin(x)
    estimate = fd.SCHEMES[name].function(np.sin(x), h, periodic=periodic)
    tolerance = {1: 2e-2, 2: 2e-4, 4: 1e-8}[EXPECTED_ORDER[name]]
    np.testing.assert_allclose(estimate, exact(name, first, second), atol=tolerance)


@pytest.mark.parametrize("name", FIRST_DERIVATIVE)
def test_exp_open_grid(name):
    x, h = open_grid(200, 1.0)
    estimate = fd.SCHEMES[name].function(np.exp(x), h)
    tolerance = {1: 1e-2, 2: 1e-4, 4: 1e-8}[EXPECTED_ORDER[name]]
    np.testing.assert_allclose(estimate, np.exp(x), rtol=tolerance)


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("name", FINITE_DIFFERENCE)
def test_observed_order(name, periodic):
    if periodic:
        f, first, second = exp_sin, exp_sin_1, exp_sin_2
        grids = [periodic_grid(n) for n in PERIODIC_SIZES]
    else:
        f = first = second = np.exp
        grids = [open_grid(n, 1.0) for n in OPEN_SIZES]
    steps = [h for _, h in grids]
    errors = [max_error(name, x, h, f, exact(name, first, second), periodic) for x, h in grids]
    assert observed_order(steps, errors) == pytest.approx(EXPECTED_ORDER[name], abs=0.15)


@pytest.mark.parametrize("name", [name for name, order in EXPECTED_ORDER.items() if order > 1])
def test_open_grid_ends_have_interior_order(name):
    """The error at the end samples alone must converge at the stated order."""
    steps, left_errors, right_errors = [], [], []
    for n in OPEN_SIZES:
        x, h = open_grid(n, 1.0)
        error = np.abs(fd.SCHEMES[name].function(np.exp(x), h) - np.exp(x))
        steps.append(h)
        left_errors.append(error[:2].max())
        right_errors.append(error[-2:].max())
    assert observed_order(steps, left_errors) == pytest.approx(EXPECTED_ORDER[name], abs=0.15)
    assert observed_order(steps, right_errors) == pytest.approx(EXPECTED_ORDER[name], abs=0.15)


def test_forward_of_forward_estimates_next_sample():
    x, h = periodic_grid(360)
    estimate = fd.forward_of_forward(exp_sin(x), h, periodic=True)
    shifted_error = np.max(np.abs(estimate - exp_sin_2(x + h)))
    unshifted_error = np.max(np.abs(estimate - exp_sin_2(x)))
    assert shifted_error < 1e-3
    assert unshifted_error > 10 * shifted_error


def test_centred_of_centred_error_is_four_times_second_difference():
    x, h = periodic_grid(360)
    y = np.sin(x)
    wide_error = np.max(np.abs(fd.centred_of_centred(y, h, periodic=True) + np.sin(x)))
    compact_error = np.max(np.abs(fd.second_difference(y, h, periodic=True) + np.sin(x)))
    assert wide_error / compact_error == pytest.approx(4.0, rel=1e-3)


@pytest.mark.parametrize("n", [64, 63])
def test_spectral_exp_sin(n):
    x, h = periodic_grid(n)
    assert np.max(np.abs(fd.spectral(exp_sin(x), h) - exp_sin_1(x))) < 1e-11
    assert np.max(np.abs(fd.spectral_second(exp_sin(x), h) - exp_sin_2(x))) < 1e-9


def test_spectral_is_exact_for_band_limited_data():
    x, h = periodic_grid(16)
    y = 1.5 + np.sin(3 * x) - 0.5 * np.cos(7 * x)
    np.testing.assert_allclose(
        fd.spectral(y, h), 3 * np.cos(3 * x) + 3.5 * np.sin(7 * x), atol=1e-12
    )
    np.testing.assert_allclose(
        fd.spectral_second(y, h), -9 * np.sin(3 * x) + 24.5 * np.cos(7 * x), atol=1e-11
    )


def test_spectral_nyquist_mode_has_zero_first_derivative():
    x, h = periodic_grid(8)
    nyquist = np.cos(4 * x)  # (-1)**i on the grid
    np.testing.assert_allclose(fd.spectral(nyquist, h), 0.0, atol=1e-12)
    np.testing.assert_allclose(fd.spectral_second(nyquist, h), -16 * nyquist, atol=1e-12)


def test_spectral_on_other_period_length():
    period = 0.02  # one crank revolution at 3000 rpm, in seconds
    n = 50
    t = np.arange(n) * (period / n)
    omega = TWO_PI / period
    y = np.sin(omega * t)
    estimate = fd.spectral(y, period / n)
    np.testing.assert_allclose(estimate, omega * np.cos(omega * t), atol=1e-12 * omega)


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("name", FINITE_DIFFERENCE)
def test_two_dimensional_input_is_row_wise(name, periodic):
    n = 400
    x, h = periodic_grid(n) if periodic else open_grid(n, 2.0)
    y = np.vstack([np.sin(x), np.exp(np.sin(x)), 3.0 * np.cos(2 * x)])
    first = np.vstack([np.cos(x), exp_sin_1(x), -6.0 * np.sin(2 * x)])
    second = np.vstack([-np.sin(x), exp_sin_2(x), -12.0 * np.cos(2 * x)])
    estimate = fd.SCHEMES[name].function(y, h, periodic=periodic)
    assert estimate.shape == y.shape
    tolerance = {1: 0.5, 2: 1e-2, 4: 1e-6}[EXPECTED_ORDER[name]]
    np.testing.assert_allclose(estimate, exact(name, first, second), atol=tolerance)


def test_input_is_not_modified():
    x, h = open_grid(50, 1.0)
    y = np.sin(x)
    before = y.copy()
    for name in FINITE_DIFFERENCE:
        fd.SCHEMES[name].function(y, h)
    np.testing.assert_array_equal(y, before)


# --------------------------------------------------------------------------
# period_offset
# --------------------------------------------------------------------------


@pytest.mark.parametrize("name", FIRST_DERIVATIVE + ["spectral"])
def test_period_offset_first_derivative(name):
    x, h = periodic_grid(360)
    y = x + np.sin(x)  # grows by 2*pi per period
    estimate = fd.SCHEMES[name].function(y, h, periodic=True, period_offset=TWO_PI)
    tolerance = {1: 1e-2, 2: 1e-4, 4: 1e-8, 0: 1e-12}[fd.SCHEMES[name].order]
    np.testing.assert_allclose(estimate, 1.0 + np.cos(x), atol=tolerance)


@pytest.mark.parametrize("name", SECOND_DERIVATIVE + ["spectral_second"])
def test_period_offset_second_derivative(name):
    x, h = periodic_grid(360)
    y = x + np.sin(x)
    estimate = fd.SCHEMES[name].function(y, h, periodic=True, period_offset=TWO_PI)
    tolerance = {1: 2e-2, 2: 1e-3, 4: 1e-7, 0: 1e-10}[fd.SCHEMES[name].order]
    np.testing.assert_allclose(estimate, -np.sin(x), atol=tolerance)


def test_period_offset_per_row():
    x, h = periodic_grid(120)
    crank = x + 0.3 * np.sin(x)  # turns once
    rocker = 0.8 + 0.4 * np.sin(x)  # oscillates
    reverse = -2.0 * x  # turns backwards twice
    y = np.vstack([crank, rocker, reverse])
    offsets = np.array([TWO_PI, 0.0, -2.0 * TWO_PI])
    estimate = fd.spectral(y, h, period_offset=offsets)
    expected = np.vstack([1 + 0.3 * np.cos(x), 0.4 * np.cos(x), np.full_like(x, -2.0)])
    np.testing.assert_allclose(estimate, expected, atol=1e-12)


def test_input_angle_in_degrees():
    degrees = np.arange(360.0)
    rate = fd.centred(degrees, 1.0, periodic=True, period_offset=360.0)
    np.testing.assert_allclose(rate, 1.0, atol=1e-12)


# --------------------------------------------------------------------------
# Complex step
# --------------------------------------------------------------------------


def squire_trapp(x):
    return np.exp(x) / np.sqrt(np.sin(x) ** 3 + np.cos(x) ** 3)


def squire_trapp_derivative(x):
    # f = e^x g^(-1/2) with g = sin^3 + cos^3 and g' = 3 sin cos (sin - cos):
    # f' = e^x (g - g'/2) / g^(3/2)
    s, c = np.sin(x), np.cos(x)
    g = s**3 + c**3
    return np.exp(x) * (g - 1.5 * s * c * (s - c)) / g**1.5


def test_complex_step_matches_closed_form():
    estimate = fd.complex_step(squire_trapp, 1.5)
    assert isinstance(estimate, float)
    exact_value = squire_trapp_derivative(1.5)
    assert abs(estimate - exact_value) <= 1e-15 * abs(exact_value)


def test_complex_step_arrays_and_tiny_step():
    x = np.linspace(0.1, 1.5, 30)
    estimate = fd.complex_step(squire_trapp, x, h=1e-200)
    assert estimate.shape == x.shape
    np.testing.assert_allclose(estimate, squire_trapp_derivative(x), rtol=1e-14)


def test_complex_step_rejects_real_only_function():
    with pytest.raises(TypeError, match="complex"):
        fd.complex_step(lambda z: np.abs(z), 1.0)


def test_complex_step_rejects_bad_step():
    with pytest.raises(ValueError, match="h"):
        fd.complex_step(np.sin, 1.0, h=0.0)


# --------------------------------------------------------------------------
# Convergence property on random trigonometric polynomials
# --------------------------------------------------------------------------


@st.composite
def trig_polynomials(draw):
    """(turns, [(frequency, cosine amplitude, sine amplitude), ...])"""
    nonzero_amplitude = st.floats(0.2, 2.0) | st.floats(-2.0, -0.2)
    terms = draw(
        st.lists(
            st.tuples(st.integers(1, 3), nonzero_amplitude, nonzero_amplitude),
            min_size=1,
            max_size=3,
            unique_by=lambda term: term[0],
        )
    )
    turns = draw(st.integers(-1, 1))
    return turns, terms


def evaluate(polynomial, x, derivative):
    turns, terms = polynomial
    value = np.zeros_like(x)
    if derivative == 0:
        value += turns * x
    elif derivative == 1:
        value += turns
    for k, a, b in terms:
        # d^n/dx^n [a cos kx + b sin kx] = k^n [a cos(kx + n pi/2) + b sin(kx + n pi/2)]
        phase = derivative * np.pi / 2
        value += k**derivative * (a * np.cos(k * x + phase) + b * np.sin(k * x + phase))
    return value


def periodic_error(name, polynomial, n):
    x, h = periodic_grid(n)
    y = evaluate(polynomial, x, 0)
    estimate = fd.SCHEMES[name].function(y, h, periodic=True, period_offset=polynomial[0] * TWO_PI)
    return np.max(np.abs(estimate - evaluate(polynomial, x, 1)))


@settings(max_examples=40, deadline=None)
@given(trig_polynomials())
def test_halving_h_divides_centred_error_by_four(polynomial):
    ratio = periodic_error("centred", polynomial, 64) / periodic_error("centred", polynomial, 128)
    assert ratio == pytest.approx(4.0, rel=0.2)


@settings(max_examples=40, deadline=None)
@given(trig_polynomials())
def test_halving_h_divides_forward_error_by_two(polynomial):
    ratio = periodic_error("forward", polynomial, 128) / periodic_error("forward", polynomial, 256)
    assert ratio == pytest.approx(2.0, rel=0.2)


# --------------------------------------------------------------------------
# Validation
# --------------------------------------------------------------------------


ALL_SCHEMES = list(EXPECTED_ORDER) + ["spectral", "spectral_second"]


def call(name, y, h, periodic=None, **kwargs):
    scheme = fd.SCHEMES[name]
    if periodic is None:
        periodic = scheme.periodic_only
    return scheme.function(y, h, periodic=periodic, **kwargs)


@pytest.mark.parametrize("h", [0.0, -0.1, np.inf, np.nan, "0.1", None, True])
@pytest.mark.parametrize("name", ALL_SCHEMES)
def test_bad_step(name, h):
    with pytest.raises(ValueError, match=r"\bh\b"):
        call(name, np.sin(np.linspace(0, 1, 20)), h)


@pytest.mark.parametrize(
    "name, periodic, minimum",
    [
        ("forward", False, 2),
        ("backward", True, 2),
        ("centred", False, 3),
        ("five_point", False, 5),
        ("five_point", True, 5),
        ("richardson", False, 5),
        ("second_difference", False, 4),
        ("second_difference", True, 3),
        ("forward_of_forward", False, 4),  # its mirrored right end at N-2 reaches back to N-4
        ("centred_of_centred", False, 5),
        ("five_point_second", False, 6),
        ("five_point_second", True, 5),
        ("spectral", True, 2),
        ("spectral_second", True, 2),
    ],
)
def test_too_few_samples(name, periodic, minimum):
    y = np.arange(float(minimum))
    call(name, y, 0.1, periodic=periodic)
    with pytest.raises(ValueError, match=rf"{name}.*\b{minimum}\b"):
        call(name, y[:-1], 0.1, periodic=periodic)


@pytest.mark.parametrize("name", ["forward", "backward", "second_difference", "forward_of_forward",
                                  "centred_of_centred", "five_point", "five_point_second", "richardson"])
def test_at_its_fewest_samples_a_scheme_is_exact_on_a_polynomial_of_its_degree(name):
    """A stencil scheme of order p differentiates a polynomial of degree p (p + 1 for a second
    derivative) exactly, end stencils included, down to its fewest samples (no end stencil wraps)."""
    scheme = fd.SCHEMES[name]
    n = scheme.derivative
    degree = scheme.order + n - 1
    for size in range(1, 12):
        try:
            call(name, np.zeros(size), 1.0, periodic=False)
        except ValueError:
            continue
        x = np.arange(float(size)) * 0.5
        y = (x - 0.3) ** degree
        exact = math.factorial(degree) / math.factorial(degree - n) * (x - 0.3) ** (degree - n)
        np.testing.assert_allclose(call(name, y, 0.5, periodic=False), exact, atol=1e-9)
        break


def test_periodic_must_be_a_bool():
    with pytest.raises(ValueError, match="periodic must be True or False, got 'no'"):
        fd.backward(np.arange(5.0), 0.1, periodic="no")


def test_scalar_input_is_rejected():
    with pytest.raises(ValueError, match="y"):
        fd.centred(1.0, 0.1)


@pytest.mark.parametrize("name", ALL_SCHEMES)
def test_nan_names_first_bad_index(name):
    y = np.sin(np.linspace(0, 1, 20))
    y[[7, 12]] = np.nan
    with pytest.raises(ValueError, match=r"index 7\b"):
        call(name, y, 0.1)


def test_nan_index_in_two_dimensional_input():
    y = np.zeros((3, 10))
    y[2, 4] = np.nan
    y[1, 8] = np.nan
    with pytest.raises(ValueError, match=r"index \(1, 8\)"):
        fd.centred(y, 0.1)


@pytest.mark.parametrize("name", ["spectral", "spectral_second"])
def test_spectral_requires_periodic(name):
    y = np.sin(np.linspace(0, 1, 20))
    with pytest.raises(ValueError, match="periodic") as info:
        call(name, y, 0.1, periodic=False)
    assert name in str(info.value)
    with pytest.raises(ValueError, match="periodic"):
        fd.differentiate(y, 0.1, method=name)


def test_period_offset_rejected_on_open_grid():
    with pytest.raises(ValueError, match="period_offset"):
        fd.centred(np.arange(10.0), 0.1, period_offset=TWO_PI)


def test_period_offset_shape_mismatch():
    with pytest.raises(ValueError, match="period_offset"):
        fd.centred(np.zeros((3, 10)), 0.1, periodic=True, period_offset=[1.0, 2.0])

"""Tests for numkin.schemes and numkin.stencils: schemes declared by their stencils."""

from __future__ import annotations

import math
from fractions import Fraction as F

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from numkin import compare, derivatives, kinematics, linkages, schemes
from numkin.stencils import Rule, Stencil


def observed_order(steps, errors):
    """Slope of log(error) against log(h), as findiff's tests measure it."""
    return np.polyfit(np.log(steps), np.log(errors), 1)[0]


@pytest.fixture
def seven_point():
    """A 7-point centred first and second derivative, registered for one test."""
    first = schemes.register("seven_point", range(-3, 4), 1)
    second = schemes.register("seven_point_second", range(-3, 4), 2)
    yield first, second
    schemes.unregister("seven_point_second")
    schemes.unregister("seven_point")


# -------------------------------------------------------------------- textbook weights
# Hand-derived (Taylor expansion) weights, as printed in Fornberg (1988), table 1.
TEXTBOOK = {
    "forward": ((0, 1), (-1, 1)),
    "backward": ((-1, 0), (-1, 1)),
    "centred": ((-1, 1), (F(-1, 2), F(1, 2))),
    "five_point": ((-2, -1, 1, 2), (F(1, 12), F(-2, 3), F(2, 3), F(-1, 12))),
    "second_difference": ((-1, 0, 1), (1, -2, 1)),
    "forward_of_forward": ((0, 1, 2), (1, -2, 1)),
    "centred_of_centred": ((-2, 0, 2), (F(1, 4), F(-1, 2), F(1, 4))),
    "five_point_second": ((-2, -1, 0, 1, 2), (F(-1, 12), F(4, 3), F(-5, 2), F(4, 3), F(-1, 12))),
}


@pytest.mark.parametrize("name", TEXTBOOK)
def test_built_in_weights_are_the_textbook_fractions(name):
    offsets, weights = TEXTBOOK[name]
    scheme = schemes.SCHEMES[name]
    assert scheme.offsets == offsets
    assert scheme.weights == tuple(F(w) for w in weights)
    assert schemes.point_stencil(name).coefficients == tuple(float(w) for w in weights)


def test_end_stencils_are_the_textbook_one_sided_ones():
    left = schemes.SCHEMES["five_point"].rule.left
    assert left[0].offsets == (0, 1, 2, 3, 4)
    assert left[0].weights == (F(-25, 12), F(4), F(-3), F(4, 3), F(-1, 4))
    assert left[1].weights == (F(-1, 4), F(-5, 6), F(3, 2), F(-1, 2), F(1, 12))
    second = schemes.SCHEMES["second_difference"].rule
    assert second.left[0].weights == (2, -5, 4, -1)
    assert second.right[0].offsets == (-3, -2, -1, 0)
    assert second.right[0].weights == (-1, 4, -5, 2)


def test_seven_point_weights_and_error_constant():
    s = Stencil.from_offsets(range(-3, 4), 1)
    assert s.weights == (F(-1, 60), F(3, 20), F(-3, 4), F(3, 4), F(-3, 20), F(1, 60))
    assert (s.order, s.error_constant) == (6, F(1, 140))  # estimate = y' + h**6/140 y^(7)


def test_orders_are_derived_from_the_stencils():
    expected = {"forward": 1, "backward": 1, "centred": 2, "five_point": 4, "second_difference": 2,
                "forward_of_forward": 1, "centred_of_centred": 2, "five_point_second": 4}
    for name, order in expected.items():
        assert schemes.SCHEMES[name].rule.order == order


# -------------------------------------------------------------------- partners and families
def partner_violations(registry) -> list:
    """The partner rule: a second-derivative scheme's partner estimates the first derivative to
    the same order and is of the same family; a first-derivative scheme's partner names it back."""
    bad = []
    for name, s in registry.items():
        if s.partner is None:
            continue
        p = registry[s.partner]
        if p.derivative == s.derivative or p.order != s.order or p.family != s.family:
            bad.append(name)
        if s.derivative == 1 and p.partner != name:
            bad.append(name)
    return bad


def test_partners_follow_the_rule():
    assert partner_violations(dict(schemes.REGISTRY)) == []
    second = [s for s in schemes.SCHEMES.values() if s.derivative == 2]
    assert {s.name for s in second} == set(kinematics.PARTNER)


@pytest.mark.parametrize("mutated, value", [("centred_of_centred", "forward"), ("second_difference", "five_point"),
                                            ("forward_of_forward", "centred")])
def test_partner_mutation_is_caught(mutated, value):
    import dataclasses

    registry = dict(schemes.REGISTRY)
    registry[mutated] = dataclasses.replace(registry[mutated], partner=value)
    assert mutated in partner_violations(registry)


def test_family_mutation_is_caught():
    import dataclasses

    registry = dict(schemes.REGISTRY)
    registry["centred_of_centred"] = dataclasses.replace(registry["centred_of_centred"], family="richardson")
    assert "centred_of_centred" in partner_violations(registry)


@pytest.mark.parametrize("name, once", [("centred_of_centred", "centred"), ("forward_of_forward", "forward")])
def test_of_schemes_are_their_partner_applied_twice(name, once):
    """The stencil of X_of_X is the convolution of X's stencil with itself."""
    s, p = schemes.SCHEMES[name], schemes.SCHEMES[once]
    assert s.partner == once and s.family == once
    twice: dict = {}
    for k1, w1 in zip(p.offsets, p.weights):
        for k2, w2 in zip(p.offsets, p.weights):
            twice[k1 + k2] = twice.get(k1 + k2, 0) + w1 * w2
    twice = {k: w for k, w in sorted(twice.items()) if w}
    assert tuple(twice) == s.offsets and tuple(twice.values()) == s.weights


def test_special_schemes_are_described_in_the_registry():
    assert schemes.REGISTRY["richardson"].kind == "richardson"
    assert schemes.REGISTRY["spectral_second"].partner == "spectral"
    assert schemes.REGISTRY["complex_step"].function is derivatives.complex_step
    assert "complex_step" not in schemes.SCHEMES
    with pytest.raises(ValueError, match="not samples"):
        schemes.get_scheme("complex_step")
    assert schemes.point_stencil("richardson").weights == schemes.SCHEMES["five_point"].weights
    assert schemes.REGISTRY["complex_step"].ends.startswith("none")
    with pytest.raises(ValueError, match="no finite stencil"):
        schemes.point_stencil("spectral")


def test_every_scheme_offsets_and_weights_are_one_stencil():
    """Zipped, a scheme's offsets and weights are its interior stencil: exact on x^d / d! (Richardson's too, the
    five-point stencil it amounts to, its zero weight left out like every other scheme's)."""
    for scheme in schemes.REGISTRY.values():
        if not scheme.offsets:
            continue
        assert len(scheme.offsets) == len(scheme.weights), scheme.name
        d = scheme.derivative
        assert sum(w * F(k) ** d for k, w in zip(scheme.offsets, scheme.weights)) / math.factorial(d) == 1, scheme.name
        assert all(w != 0 for w in scheme.weights), scheme.name
    assert schemes.REGISTRY["richardson"].offsets == schemes.REGISTRY["five_point"].offsets


# -------------------------------------------------------------------- registering at run time
def test_seven_point_observed_order_on_sin(seven_point):
    steps, errors = [], []
    for n in (16, 24, 32, 48):
        x = np.arange(n) * (2 * np.pi / n)
        dy = derivatives.differentiate(np.sin(x), x[1], "seven_point", periodic=True)
        steps.append(x[1])
        errors.append(np.max(np.abs(dy - np.cos(x))))
    assert observed_order(steps, errors) == pytest.approx(6.0, abs=0.2)


def test_seven_point_open_grid_ends_keep_order_six(seven_point):
    steps, errors = [], []
    for n in (24, 32, 48, 64):
        x = np.linspace(0.0, 1.0, n + 1)
        dy = derivatives.differentiate(np.exp(x), x[1], "seven_point")
        steps.append(x[1])
        errors.append(max(np.max(np.abs(dy[:3] - np.exp(x[:3]))), np.max(np.abs(dy[-3:] - np.exp(x[-3:])))))
    assert observed_order(steps, errors) == pytest.approx(6.0, abs=0.2)


def slider_velocity(r, l, theta):
    """dx/dtheta of the slider, from x = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta))."""
    s, c = np.sin(theta), np.cos(theta)
    return -r * s - r**2 * s * c / np.sqrt(l**2 - r**2 * s**2)


def test_seven_point_through_finite_difference_and_compare(seven_point):
    mech = linkages.slider_crank(80, 200)
    steps, errors = [], []
    for n in (72, 96, 144, 180):
        theta = np.linspace(0.0, 2 * np.pi, n + 1)
        sweep = mech.sweep(theta)
        fd = kinematics.finite_difference(sweep, 1.0, method="seven_point", second_method="seven_point_second")
        assert fd.attrs["quantities"]["v_x"].source == "seven_point"
        steps.append(theta[1])
        errors.append(np.max(np.abs(fd["v_x"] - slider_velocity(80, 200, theta))))
    assert observed_order(steps, errors) == pytest.approx(6.0, abs=0.2)
    c = compare.compare(sweep, 1.0, "a_x", schemes=("seven_point_second",), alpha=2.0)
    assert c.summary.loc["seven_point_second", "order"] == "6"


def test_register_rejects_bad_declarations(seven_point):
    with pytest.raises(ValueError, match="already registered"):
        schemes.register("centred", (-1, 0, 1), 1)
    with pytest.raises(ValueError, match="replace=True"):
        schemes.register("seven_point", range(-3, 4), 1)
    with pytest.raises(ValueError, match="order 4"):
        schemes.register("nine_point_second", range(-4, 5), 2, partner="five_point")
    with pytest.raises(ValueError, match="partner="):
        schemes.register("nine_point_second", range(-4, 5), 2)
    with pytest.raises(ValueError, match="distinct integers"):
        schemes.register("bad", (0, 0.5, 1), 1)
    with pytest.raises(ValueError, match="built-in"):
        schemes.unregister("centred")


def test_registered_scheme_is_listed_where_schemes_are_chosen(seven_point):
    assert "seven_point" in derivatives.SCHEMES
    assert schemes.PARTNER["seven_point_second"] == "seven_point"
    with pytest.raises(ValueError, match="seven_point_second"):
        kinematics.scheme_for("centred", 2, "second_method")


def test_point_stencil_evaluates_at_one_input():
    s = schemes.point_stencil("second_difference")
    x, h = 0.3, 1e-3
    value = s.apply(np.sin(x + h * np.array(s.offsets)), h)
    assert value == pytest.approx(-math.sin(x), rel=1e-6)


def test_rule_mirror_needs_a_one_sided_stencil():
    with pytest.raises(ValueError, match="mirror"):
        Rule.build(Stencil.from_offsets((-1, 0, 1), 1), "mirror")


# -------------------------------------------------------------------- properties
@given(
    offsets=st.lists(st.integers(-5, 5), min_size=2, max_size=8, unique=True),
    derivative=st.integers(1, 2),
    data=st.data(),
)
def test_any_stencil_differentiates_polynomials_of_its_degree_exactly(offsets, derivative, data):
    """For any distinct offsets, the weights differentiate every polynomial of degree
    below len(offsets) exactly (in rational arithmetic), and the derived order is at
    least len(offsets) - derivative."""
    if len(offsets) <= derivative:
        return
    s = Stencil.from_offsets(offsets, derivative)
    assert s.order >= len(offsets) - derivative
    coefficients = data.draw(st.lists(st.integers(-9, 9), min_size=len(offsets), max_size=len(offsets)))
    x0 = F(data.draw(st.integers(-3, 3)))
    poly = lambda x: sum(F(c) * x**m for m, c in enumerate(coefficients))  # noqa: E731
    exact = sum(F(c) * math.perm(m, derivative) * x0 ** (m - derivative)
                for m, c in enumerate(coefficients) if m >= derivative)
    assert sum(w * poly(x0 + k) for k, w in zip(s.offsets, s.weights)) == exact


def test_a_built_in_stencil_scheme_is_one_declaration(monkeypatch):
    """A stencil scheme declared in BUILT_IN alone (no function of its own in numkin.derivatives) gets the
    generated one: sixth order, observed from the log-log slope on sin."""
    monkeypatch.setitem(schemes.BUILT_IN, "centred_seven", dict(offsets=tuple(range(-3, 4)), derivative=1))
    monkeypatch.setattr(schemes, "_REGISTRY", {})
    monkeypatch.setattr(schemes, "_LOADED", False)
    scheme = schemes.get_scheme("centred_seven")
    assert (scheme.order, scheme.derivative) == (6, 1) and not hasattr(derivatives, "centred_seven")
    steps, errors = [], []
    for n in (24, 32, 48):
        x = np.linspace(0.0, 2.0 * math.pi, n + 1)
        h = x[1] - x[0]
        steps.append(h)
        errors.append(np.abs(scheme.function(np.sin(x), h)[3:-3] - np.cos(x)[3:-3]).max())
    assert observed_order(steps, errors) == pytest.approx(6.0, abs=0.2)


@pytest.mark.parametrize("offsets, derivative, order", [((1, 2), 1, 1), ((-3, -2, -1), 1, 2), ((1, 2, 3), 2, 1)])
def test_a_window_that_leaves_out_its_own_sample_works_on_open_grids(offsets, derivative, order):
    """Offsets (1, 2) estimate y'(x_i) from y[i+1], y[i+2] (weights -3/2, 2, ... solved exactly): every sample
    of an open grid is differentiated (ends by one-sided stencils) at the stated order, read from the log-log
    slope of the error against h on sin x."""
    name = "window_" + "_".join(str(k).replace("-", "m") for k in offsets) + f"_{derivative}"
    scheme = schemes.register(name, offsets, derivative, partner="forward" if derivative == 2 else None)
    try:
        assert scheme.order == order
        steps, errors = [], []
        for n in (41, 81, 161, 321):
            x = np.linspace(0.0, 1.0, n)
            got = derivatives.differentiate(np.sin(x), x[1], name, periodic=False)
            exact = np.cos(x) if derivative == 1 else -np.sin(x)
            steps.append(x[1])
            errors.append(np.abs(got - exact).max())
        assert observed_order(steps, errors) == pytest.approx(order, abs=0.1)
    finally:
        schemes.unregister(name)

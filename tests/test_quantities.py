"""The quantity catalogue: names, units and derivative orders follow one rule.

The rule is checked against units derived by hand (a velocity is a position
per second, an acceleration per second squared; derivatives with respect to
the input angle are per radian) and against the columns the analytic
solution actually writes.
"""

from __future__ import annotations

import pytest

from numkin import analytic, linkages
from numkin.quantities import Quantity, catalogue, resolve

MECHANISMS = {
    "four-bar": lambda: linkages.four_bar(4, 1, 3, 3),
    "slider-crank": lambda: linkages.slider_crank(80, 200),
    "quick-return": lambda: linkages.quick_return(),
    "chained": lambda: linkages.chained_four_bars(),
}


@pytest.mark.parametrize("key", MECHANISMS)
def test_units_follow_dimensional_analysis(key):
    mech = MECHANISMS[key]()
    for q in catalogue(mech).values():
        base = "rad" if q.dimension == "angle" else mech.length_unit
        assert q.unit == {0: base, 1: f"{base}/s", 2: f"{base}/s^2"}[q.order], q
    for q in catalogue(mech, wrt="input").values():
        base = "rad" if q.dimension == "angle" else mech.length_unit
        assert q.unit == {0: base, 1: f"{base}/rad", 2: f"{base}/rad^2"}[q.order], q


@pytest.mark.parametrize("key", MECHANISMS)
def test_catalogue_names_the_columns_analytic_writes(key):
    mech = MECHANISMS[key]()
    written = analytic.column_units(mech)
    listed = catalogue(mech, orders=(1, 2), points=False)
    assert {k: v for k, v in written.items() if k != str(mech.input_symbol)} == {n: q.unit for n, q in listed.items()}


@pytest.mark.parametrize("key", MECHANISMS)
def test_every_name_resolves_to_itself(key):
    mech = MECHANISMS[key]()
    for wrt in ("time", "input"):
        for name, q in catalogue(mech, wrt=wrt).items():
            assert q.name == name
            assert resolve(mech, name, wrt=wrt) == q
            assert resolve(mech, q) is q


def test_hand_written_names_and_labels():
    q = Quantity("beta", 1, "angle")
    assert (q.name, q.unit, q.kind, q.symbol) == ("omega_beta", "rad/s", "velocity", r"\omega_{\beta}")
    assert q.with_source("centred").label == "omega_beta, centred [rad/s]"
    assert q.derivative().name == "alpha_beta" and q.derivative().unit == "rad/s^2"
    assert q.position().name == "beta" and q.position().unit == "rad"
    p = Quantity("P", 2, "length", length_unit="m", axis="y")
    assert (p.name, p.unit, p.symbol) == ("ay_P", "m/s^2", r"\ddot{y}_{P}")
    d = Quantity("theta4", 2, "angle", wrt="input", input_name="theta2")
    assert (d.name, d.unit) == ("d2theta4/dtheta2^2", "rad/rad^2")
    assert d.symbol == r"\frac{d^2\theta_{4}}{d\theta_{2}^2}"


def test_bad_quantities_are_named():
    mech = linkages.four_bar(4, 1, 3, 3)
    assert resolve(mech, "theta4").kind == "position"
    with pytest.raises(ValueError, match="did you mean 'alpha_theta3'"):
        resolve(mech, "alpha_theta33")
    with pytest.raises(TypeError, match="named by a string"):
        resolve(mech, 3)
    with pytest.raises(ValueError, match="order must be 0, 1 or 2"):
        Quantity("x", 3, "length")
    with pytest.raises(ValueError, match="third derivative"):
        Quantity("x", 2, "length").derivative()

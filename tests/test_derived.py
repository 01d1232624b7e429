"""Derived quantities (numkin.derived, numkin.expressions): values and rates against closed forms."""

import math
import warnings

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import numkin
from numkin import analytic, linkages
from numkin.compare import compare
from numkin.quantities import catalogue, resolve
from numkin.scene import load_scene, run_scene

MU = {"mu": ("theta4 - theta3", "angle")}


def _mu_closed_form(t, ground=4, crank=1, coupler=3, rocker=3):
    """Transmission angle theta4 - theta3 of the open four-bar, by circle intersection (mpmath)."""
    ax, ay = crank * mp.cos(t), crank * mp.sin(t)
    dx, dy = ground - ax, -ay
    d = mp.sqrt(dx**2 + dy**2)
    along = (coupler**2 - rocker**2 + d**2) / (2 * d)
    h = mp.sqrt(coupler**2 - along**2)
    bx = ax + (along * dx - h * dy) / d
    by = ay + (along * dy + h * dx) / d
    return mp.atan2(by, bx - ground) - mp.atan2(by - ay, bx - ax)


@pytest.fixture(scope="module")
def four_bar_sweep():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities(MU)
    return mech.sweep(np.radians(np.arange(0.0, 361.0)))


def test_transmission_angle_and_its_derivatives_match_the_closed_form(four_bar_sweep):
    e, de, d2e = analytic.derived_derivatives(four_bar_sweep)["mu"]
    mp.mp.dps = 30
    for deg in (0, 37, 90, 181, 300):
        t = mp.radians(deg)
        assert e[deg] == pytest.approx(float(_mu_closed_form(t)), abs=1e-13)
        assert de[deg] == pytest.approx(float(mp.diff(_mu_closed_form, t)), abs=1e-11)
        assert d2e[deg] == pytest.approx(float(mp.diff(_mu_closed_form, t, 2)), abs=1e-10)
    # the lone values, nothing differentiated, are the same numbers
    np.testing.assert_array_equal(analytic.derived_values(four_bar_sweep)["mu"], e)


def test_a_length_quantity_in_time_with_an_accelerating_input():
    r, rod = 80.0, 200.0
    mech = linkages.slider_crank(r, rod).add_quantities({"gap": ("x - r*cos(theta)", "length")})
    t = np.radians(np.arange(0.0, 181.0, 5.0))
    kin = analytic.derived_kinematics(mech.sweep(t), omega="600 rpm", alpha=3.0)
    # by hand: gap = sqrt(l^2 - r^2 sin^2), gap' = -r^2 s c / gap, gap'' = -r^2 cos 2t / gap - (r^2 s c)^2 / gap^3
    s, c = np.sin(t), np.cos(t)
    g = np.sqrt(rod**2 - (r * s) ** 2)
    g1 = -(r**2) * s * c / g
    g2 = -(r**2) * np.cos(2 * t) / g - (r**2 * s * c) ** 2 / g**3
    w = 600 * 2 * math.pi / 60
    np.testing.assert_allclose(kin["gap"], g, rtol=1e-13)
    np.testing.assert_allclose(kin["v_gap"], w * g1, atol=1e-9)
    np.testing.assert_allclose(kin["a_gap"], w**2 * g2 + 3.0 * g1, atol=1e-7)
    assert kin.attrs["units"] == {"theta": "rad", "gap": "mm", "v_gap": "mm/s", "a_gap": "mm/s^2"}


def test_the_catalogue_and_compare_take_a_derived_quantity_like_an_unknown(four_bar_sweep):
    mech = four_bar_sweep.mechanism
    names = list(catalogue(mech, orders=(1,), points=False))
    assert names == ["omega_theta3", "omega_theta4", "omega_mu"]
    assert resolve(mech, "alpha_mu").unit == "rad/s^2"
    # centred differences of mu: second order, read from the log-log slope of the error against the step
    errors = []
    for n in (90, 180, 360):
        sweep = mech.sweep(np.linspace(0, 2 * np.pi, n + 1))
        c = compare(sweep, 10.0, "omega_mu", schemes=("centred",))
        t = sweep.inputs
        exact = 10.0 * np.array([float(mp.diff(_mu_closed_form, mp.mpf(x))) for x in t[:: n // 18]])
        np.testing.assert_allclose(c.table["analytic [rad/s]"].to_numpy()[:: n // 18], exact, atol=1e-9)
        errors.append(float(c.summary.loc["centred", "max abs error [rad/s]"]))
    slopes = -np.diff(np.log(errors)) / np.log(2)
    assert slopes == pytest.approx([2, 2], abs=0.05)


def test_a_loop_mechanism_reads_names_as_its_own_symbols():
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4", real=True)
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4", positive=True)
    loop = numkin.Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4])
    plain = sp.Symbol("theta4") - sp.Symbol("theta3")  # no assumptions: still the loop's symbols
    mech = numkin.Mechanism([loop], t2, {r1: 4, r2: 1, r3: 3, r4: 3}, guess={"theta3": 1.0, "theta4": 2.0},
                            quantities={"mu": (plain, "angle"), "reach": ("r2 + r3*cos(theta3)", "length")})
    sweep = mech.sweep(np.radians([90.0]))
    values = analytic.derived_values(sweep)
    assert values["mu"][0] == pytest.approx(float(_mu_closed_form(mp.pi / 2)), abs=1e-13)
    assert values["reach"][0] == pytest.approx(1 + 3 * math.cos(sweep["theta3"][0]), abs=1e-13)


@pytest.mark.parametrize("spec, message", [
    ({"theta3": ("2*theta3", "angle")}, "'theta3' is already the name of an unknown"),
    ({"theta2": ("theta3", "angle")}, "already the name of the input"),
    ({"r1": ("theta3", "length")}, "already the name of a parameter"),
    ({"mu": ("theta4 - foo", "angle")}, r"names \['foo'\], which the mechanism does not have"),
    ({"mu": ("theta4 -", "angle")}, "cannot read the expression"),
    ({"mu": ("theta4", "speed")}, "dimension must be 'angle' or 'length'"),
    ({"mu": "theta4"}, r"must be \(expression, 'angle' or 'length'\)"),
    ({"2mu": ("theta4", "angle")}, "a quantity's name is a letter"),
    (["mu"], "quantities must be a mapping"),
    ({"mu": ("theta3 > 1", "angle")}, "is not arithmetic"),
    ({"mu": ("[theta3]", "angle")}, "is not arithmetic"),
    ({"mu": ("theta3 + sqrt(-1)", "angle")}, "not a finite real expression"),
    ({"k": ("r1 + r2", "length")}, "depends on no unknown and not on the input: it is a constant"),
    ({"k": ("pi", "angle")}, "it is a constant"),
])
def test_a_wrong_declaration_is_named(spec, message):
    with pytest.raises(numkin.InputError, match=message):
        linkages.four_bar(4, 1, 3, 3).add_quantities(spec)


def test_numbers_written_with_exponents_and_an_absolute_value():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("abs(theta4 - theta3) + 1e-3 - 1E-3", "angle")})
    kin = analytic.derived_kinematics(mech.sweep(np.radians([90.0])), 10.0)
    # |mu| = mu where mu > 0: the same value and rates as mu (sign(mu) mu', and no Dirac delta away from 0)
    mp.mp.dps = 30
    assert kin["mu"][0] == pytest.approx(float(_mu_closed_form(mp.pi / 2)), abs=1e-13)
    assert kin["omega_mu"][0] == pytest.approx(10 * float(mp.diff(_mu_closed_form, mp.pi / 2)), abs=1e-10)
    assert kin["alpha_mu"][0] == pytest.approx(100 * float(mp.diff(_mu_closed_form, mp.pi / 2, 2)), abs=1e-8)


def test_a_value_outside_its_domain_is_warned_of_by_name():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"sq": ("sqrt(theta4 - 2)", "angle")})
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0)))  # theta4 < 2 rad on part of the turn
    with pytest.warns(RuntimeWarning, match=r"sq is not finite at \d+ of 361 inputs, first at input [\d.]+°"):
        values = analytic.derived_values(sweep)["sq"]
    np.testing.assert_array_equal(np.isnan(values), sweep["theta4"] < 2)


def test_at_a_change_point_the_rates_continue_the_kept_branch_as_the_unknowns_do():
    """Crossed anti-parallelogram 5/2/5/2 at 180 deg (tests/test_analytic.py derives theta3' = 4/7,
    theta4' = -3/7 there by hand): mu' = theta4' - theta3' = -1; NaN unless asked to continue."""
    import warnings

    mech = linkages.four_bar(5, 2, 5, 2, branch="crossed").add_quantities(MU)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(np.radians(np.arange(1.0, 360.0)), on_singular="report")
        k = int(np.argmin(np.abs(sweep.inputs - np.pi)))
        assert np.isnan(analytic.derived_derivatives(sweep)["mu"][1][k])
        _, de, _ = analytic.derived_derivatives(sweep, at_change_point="continue")["mu"]
        kin = analytic.derived_kinematics(sweep, 2.0, at_change_point="continue")
    assert de[k] == pytest.approx(-1.0, abs=1e-6)
    assert kin["omega_mu"][k] == pytest.approx(-2.0, abs=1e-5)


def test_a_rate_name_already_taken_is_named():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities(MU)
    with pytest.raises(numkin.InputError, match="'mu' is already the name of the quantity mu"):
        mech.add_quantities(MU)
    with pytest.raises(numkin.InputError, match="'omega_theta3' is already the name of a quantity of the unknown"):
        linkages.four_bar(4, 1, 3, 3).add_quantities({"omega_theta3": ("theta3", "angle")})
    with pytest.raises(numkin.InputError, match="'mu': its name 'omega_mu' is already the name of the quantity omega_mu"):
        linkages.four_bar(4, 1, 3, 3).add_quantities({"omega_mu": ("theta3", "length")}).add_quantities(MU)
    # within one declaration too, and a scene's name in degrees
    with pytest.raises(numkin.InputError, match="'omega_mu' is already the name of the quantity mu"):
        linkages.four_bar(4, 1, 3, 3).add_quantities({**MU, "omega_mu": ("r4*cos(theta4)", "length")})
    with pytest.raises(numkin.InputError, match="'theta4_deg' is already the name of a quantity of the unknown theta4"):
        linkages.four_bar(4, 1, 3, 3).add_quantities({"theta4_deg": ("r4*cos(theta4)", "length")})
    with pytest.raises(numkin.InputError, match="'mu_deg' is already the name of the quantity mu"):
        linkages.four_bar(4, 1, 3, 3).add_quantities({**MU, "mu_deg": ("r4*cos(theta4)", "length")})
    with pytest.raises(numkin.InputError, match=r"name at least one of the derived quantities .*\['mu'\]"):
        analytic.derived_kinematics(mech.sweep(np.radians([0.0])), 1.0, names=[])
    with pytest.raises(numkin.InputError, match=r"name at least one of the points"):
        analytic.point_kinematics(linkages.slider_crank(80, 200).sweep(np.radians([0.0])), 1.0, points=[])
    with pytest.raises(numkin.InputError, match="has no derived quantities"):
        analytic.derived_kinematics(linkages.four_bar(4, 1, 3, 3).sweep(np.radians([0.0])), 1.0)


@settings(max_examples=15, deadline=None)
@given(crank=st.floats(0.5, 1.5), coupler=st.floats(3.5, 5.0), rocker=st.floats(3.0, 4.0))
def test_the_rates_of_a_difference_are_the_differences_of_the_rates(crank, coupler, rocker):
    mech = linkages.four_bar(4.5, crank, coupler, rocker).add_quantities(MU)
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0, 15.0)))
    kin = analytic.kinematics(sweep, 7.0, 2.0)
    mu = analytic.derived_kinematics(sweep, 7.0, 2.0)
    np.testing.assert_allclose(mu["mu"], sweep["theta4"] - sweep["theta3"], atol=1e-12)
    for rate in ("omega", "alpha"):
        np.testing.assert_allclose(mu[f"{rate}_mu"], kin[f"{rate}_theta4"] - kin[f"{rate}_theta3"], rtol=1e-11,
                                   atol=1e-11)


SCENE = """
[scene]
description = "transmission angle"

[mechanism]
linkage = "four_bar"

[mechanism.dimensions]
ground = 4
crank = 1
coupler = 3
rocker = 3

[mechanism.quantities]
mu = {{ expression = "theta4 - theta3", dimension = "angle" }}

[input]
speed = "10 rad/s"
step_deg = 1

[output]
quantities = {quantities}
tables = {tables}
{compare}
[[check]]
at_deg = 90
mu_deg = {mu_deg}
"""


def _scene(tmp_path, **fields):
    path = tmp_path / "mu.toml"
    path.write_text(SCENE.format(**fields))
    return load_scene(str(path))


def test_a_scene_declares_checks_compares_and_tabulates_a_derived_quantity(tmp_path):
    mu90 = math.degrees(float(_mu_closed_form(mp.pi / 2)))
    scene = _scene(tmp_path, quantities='["position", "velocity"]', tables='["positions", "kinematics"]',
                   compare='[compare]\nschemes = ["centred"]\n', mu_deg=round(mu90, 4))
    result = run_scene(scene)
    assert result.checks[0].ok == {"mu_deg": True}
    assert result.checks[0].values["omega_mu"] == pytest.approx(10 * float(mp.diff(_mu_closed_form, mp.pi / 2)),
                                                                abs=1e-10)
    assert set(result.comparisons) == {"omega_theta3", "omega_theta4", "omega_mu"}
    positions = result.tables["positions"]
    assert positions["mu [deg]"].iloc[90] == pytest.approx(mu90, abs=1e-11)
    assert "omega_mu [rad/s]" in result.tables["kinematics"]


def test_a_position_only_scene_with_a_derived_quantity_differentiates_nothing(tmp_path):
    scene = _scene(tmp_path, quantities='["position"]', tables='["positions"]', compare="", mu_deg=80.0)
    result = run_scene(scene)
    assert result.kinematics is None and result.derived_kinematics is None
    assert result.checks[0].ok == {"mu_deg": False}
    assert result.checks[0].values["mu_deg"] == pytest.approx(math.degrees(float(_mu_closed_form(mp.pi / 2))),
                                                              abs=1e-11)


def test_a_scene_names_its_wrong_declaration(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(SCENE.format(quantities='["position"]', tables="[]", compare="", mu_deg=80.0)
                    .replace('"theta4 - theta3"', '"theta4 - phi"'))
    with pytest.raises(numkin.NumkinError, match=r"\[mechanism.quantities\].*names \['phi'\]"):
        run_scene(load_scene(str(path)))


def test_a_derived_quantity_that_is_not_periodic_is_compared_on_an_open_grid_and_a_zero_rate_has_no_rel_error():
    # half = theta2/2 + theta3 gains half a turn per turn; arc = r2 theta2 (a rack) has v = r2 omega, a = 0
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"half": ("theta2/2 + theta3", "angle"),
                                                         "arc": ("r2*theta2", "length")})
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0, 10.0)))
    with pytest.warns(UserWarning, match=r"\['arc'\] do not return .* not periodic in the input .* derived quantity"):
        v = compare(sweep, 10.0, "v_arc", schemes=["centred"])
    np.testing.assert_allclose(v.table["centred [mm/s]"], 10.0, rtol=1e-13)   # centred is exact on a line
    assert v.summary["ends abs error [mm/s]"].iloc[0] < 1e-12  # the one-sided end stencils, apart
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # no numpy warning about an all-NaN relative error
        warnings.simplefilter("ignore", UserWarning)
        a = compare(sweep, 10.0, "a_arc", schemes=["second_difference"])
    assert np.isnan(a.summary["max rel error"].iloc[0]) and np.isnan(a.summary["rms rel error"].iloc[0])
    assert a.summary.filter(like="max abs error").iloc[0, 0] < 1e-10
    with pytest.warns(UserWarning, match=r"differenced as an open grid"):
        h = compare(sweep, 10.0, "omega_half", schemes=["centred"])
    t = np.radians(np.arange(0.0, 361.0, 10.0))
    half = np.unwrap(np.asarray(sweep["theta3"])) + t / 2  # interior points: the centred rule, no wrap-round
    centred = (half[2:] - half[:-2]) / (2 * math.radians(10.0)) * 10.0
    np.testing.assert_allclose(h.table["centred [rad/s]"].to_numpy()[1:-1], centred, rtol=1e-12)

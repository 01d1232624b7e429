"""The homework in assignments/: reference values, feedback helpers, and grading with otter.

These tests are fast: the committed reference values are numkin's, the masters are
otter notebooks, the deliberate mistakes apply, and the feedback package
``assignments/kincheck/`` works on its own.  Building and grading with otter is in
``tests/test_grading.py``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from conftest import load_module

ROOT = Path(__file__).resolve().parents[1]
ASSIGNMENTS = ROOT / "assignments"


_load = load_module


build = _load("numkin_assignments_build", ASSIGNMENTS / "build.py")
kc = _load("kincheck", ASSIGNMENTS / "kincheck" / "__init__.py")  # a package: its modules load with it

HOMEWORK = list(build.HOMEWORK)
MISTAKES = [(hw, m["name"]) for hw in HOMEWORK for m in build.mistakes(hw)]


# --------------------------------------------------------------------------
# reference values
# --------------------------------------------------------------------------


@pytest.mark.parametrize("hw", HOMEWORK)
def test_committed_reference_values_are_numkins(hw):
    """expected.json and the master's '# reference:' lines agree with a fresh numkin computation.

    Regenerate with: python assignments/build.py expected
    """
    problems = build.stale(hw)
    assert not problems, "\n".join(problems) + "\nrun: python assignments/build.py expected"


@pytest.mark.parametrize("hw", HOMEWORK)
def test_every_reference_value_is_used_by_a_test(hw):
    assert set(build.master_markers(hw)) == set(build.load_expected(hw))


def test_reference_values_against_the_documents_and_closed_forms():
    """The graded reference values: the source documents' numbers where they give them,
    closed forms derived here where they do not, and numkin's values otherwise (those are
    checked against closed forms in tests/test_linkages.py and tests/test_report.py)."""
    hw1 = build.load_expected("hw1_chained_four_bar")
    # homework 003: exact omega_beta = 10.633 rad/s, alpha_beta = -28.375 rad/s^2 at theta = 100 deg
    assert round(hw1["omega_beta_100"], 3) == 10.633
    assert round(hw1["alpha_beta_100"], 3) == -28.375
    # numkin's differences and positions on the 1 deg grid (README's table)
    assert hw1["dbeta_dt_centred"][100] == pytest.approx(10.6330, abs=1e-4)
    assert hw1["dbeta_dt_forward"][100] == pytest.approx(10.59998, abs=1e-5)
    assert hw1["d2beta_dt2_second"][100] == pytest.approx(-28.3765, abs=1e-4)
    assert hw1["d2beta_dt2_forward_twice"][100] == pytest.approx(-28.1266, abs=1e-4)
    assert math.degrees(hw1["phi"][100]) == pytest.approx(94.4375, abs=1e-4)
    assert math.degrees(hw1["beta"][100]) == pytest.approx(214.7270, abs=1e-4)
    # report 000 at theta2 = 30 deg
    hw2 = build.load_expected("hw2_quick_return")
    assert [hw2["r3_30"], math.degrees(hw2["theta3_30"]), hw2["r4_30"], hw2["r5_30"]] == pytest.approx(
        [87.178, 66.587, 130.767, 51.962], abs=1e-3
    )
    # exam 004's slider-crank (r = 80 mm, l = 200 mm, 6000 rpm): x = r cos t + sqrt(l^2 - r^2 sin^2 t),
    # so a(0) = -w^2 (r + r^2/l) and a(90 deg) = w^2 r^2 / sqrt(l^2 - r^2)
    r, l, w = 0.08, 0.2, 6000 * 2 * math.pi / 60
    hw3 = build.load_expected("hw3_slider_crank")
    assert hw3["a_0"] == pytest.approx(-(w**2) * (r + r**2 / l), rel=1e-9)
    assert hw3["a_90"] == pytest.approx(w**2 * r**2 / math.sqrt(l**2 - r**2), rel=1e-9)
    # numkin's x_D of the six-bar (report 001 shows it only as a plot; README's table)
    hw4 = build.load_expected("hw4_six_bar")
    assert [hw4["x"][0], hw4["x"][90], hw4["x"][180]] == pytest.approx(
        [-1.77881, -3.70858, -5.84838], abs=1e-5
    )


def test_stale_values_are_caught(tmp_path, monkeypatch):
    hw = "hw3_slider_crank"
    fresh = build.compute(hw)
    fresh["a_0"] *= 1.001
    assert any("a_0" in p for p in build.stale(hw, fresh))


def test_rebuilding_keeps_references_that_agree_and_takes_those_that_moved():
    hw = "hw3_slider_crank"
    committed = build.load_expected(hw)
    fresh = build.compute(hw)
    fresh["a_90"] = committed["a_90"] * (1 + 1e-11)  # rounding noise in the last digits: the committed one stays
    fresh["a_0"] = committed["a_0"] * 1.001  # a real change: taken
    kept = build._kept(hw, fresh)
    assert kept["a_90"] == committed["a_90"] and kept["a_0"] == fresh["a_0"]
    assert kept["x"] == committed["x"]


# --------------------------------------------------------------------------
# the masters and their deliberate mistakes
# --------------------------------------------------------------------------


@pytest.mark.parametrize("hw", HOMEWORK)
def test_master_is_an_otter_notebook(hw):
    jupytext = pytest.importorskip("jupytext")
    nb = jupytext.read(build.master_path(hw))
    raw = [c.source for c in nb.cells if c.cell_type == "raw"]
    assert raw[0].startswith("# ASSIGNMENT CONFIG")
    begins = sum(s.startswith("# BEGIN QUESTION") for s in raw)
    ends = sum(s.startswith("# END QUESTION") for s in raw)
    assert begins == ends >= 2
    assert sum(s.startswith("# BEGIN SOLUTION") for s in raw) == begins
    hidden = [c.source for c in nb.cells if c.cell_type == "code" and "hidden: true" in c.source]
    assert hidden, "no hidden tests"


@pytest.mark.parametrize("hw, name", MISTAKES)
def test_mistake_edits_match_the_master_once(hw, name):
    source = build.master_path(hw).read_text()
    (mistake,) = [m for m in build.mistakes(hw) if m["name"] == name]
    assert mistake["feedback"], "a mistake must say which feedback it expects"
    for edit in mistake["edit"]:
        assert source.count(edit["find"]) == 1, edit["find"]


# --------------------------------------------------------------------------
# kincheck: the feedback
# --------------------------------------------------------------------------


def _fails(check, *args, **kwargs) -> str:
    with pytest.raises(AssertionError) as info:
        check(*args, **kwargs)
    return str(info.value)


def test_kincheck_gives_every_name_of_its_modules():
    """``import kincheck`` gives each name of its modules' ``__all__``, defined in one module only."""
    modules = {p.stem for p in (ASSIGNMENTS / "kincheck").glob("*.py")} - {"__init__"}
    names = [(name, getattr(kc, module)) for module in sorted(modules) for name in getattr(kc, module).__all__]
    assert len({name for name, _ in names}) == len(names)
    assert set(kc.__all__) <= {name for name, _ in names}
    for name, module in names:
        assert getattr(kc, name) is getattr(module, name), name


@pytest.mark.parametrize(
    "ratio, words",
    [
        (60.0, "off by a factor 60: rad/min where rad/s is asked?"),
        (3600.0, "3600 (= 60²): rad/min"),
        (1 / 60, "1/60: divided by 60"),
        (180 / math.pi, "57.3 (= 180/π): degrees where radians are asked?"),
        ((math.pi / 180) ** 2, "1/3283 (= (π/180)²)"),
        (60 / (2 * math.pi), "9.549 (= 60/2π): rpm where rad/s is asked?"),
        ((60 / (2 * math.pi)) ** 2, "91.19 (= (60/2π)²)"),
        (1000.0, "millimetres where metres are asked?"),
        (-1.0, "the sign is flipped"),
        (-60.0, "The sign is flipped as well."),
        (60 * 180 / math.pi, "3438 (= 180/π × 60): degrees where radians are asked? And rad/min"),
    ],
)
def test_unit_factors_are_named(ratio, words):
    assert words in kc.explain_factor(ratio, ("deg", "rad/min", "rpm", "mm"))


def test_a_flipped_sign_names_the_sense_of_rotation_only_where_the_check_says_so():
    # the check knows whether the sign of ω can explain it (a rate odd in ω) or what else can
    plain = kc.explain_factor(-1.0, ("deg",))
    assert plain == "the sign is flipped" and "rotation" not in plain
    assert kc.explain_factor(-1.0, ("deg",), flipped=kc.ROTATION).endswith("check the sense of rotation (clockwise is negative)")
    mirror = "a negative length: the mirror solution"
    assert _fails(kc.value, "r3", -87.178, 87.178, unit="mm", flipped=mirror) == f"`r3` = -87.178 mm: {mirror}"
    assert "rotation" not in _fails(kc.series, "a", -np.ones(361), {10: 1.0, 40: 1.0})
    assert "rotation" not in _fails(kc.band, "a", 25.0, -30.0, -20.0, about=-25.0)
    assert _fails(kc.band, "w", -10.0, 8.0, 12.0, about=10.0, flipped=kc.ROTATION).endswith(kc.ROTATION)


def test_an_alternative_formula_is_named_only_where_the_digits_given_tell_it():
    """ω at 100°: exact 10.6329 (mpmath: 10.6328965), forward 10.59998, backward 10.66601, all within 0.5 %. A
    computed forward or backward value is named; 10.6 or 10.63, rounded answers the forward value may round to
    as well, pass (no formula can be told from them)."""
    want, forward, backward = 10.6328965, 10.59997952751215, 10.66601463948
    alternatives = [(forward, "the forward difference"), (backward, "the backward difference")]

    def check(got):
        return kc.value("omega_100", got, want, rtol=5e-3, unit="rad/s", alternatives=alternatives)

    assert _fails(check, forward).endswith("the forward difference")
    assert _fails(check, backward).endswith("the backward difference")
    assert check(10.6) == 10.6 and check(10.63) == 10.63 and check(10.63289649) == 10.63289649
    assert kc.agrees_as_written(10.6, want) and not kc.agrees_as_written(forward, want)
    # a check tighter than the figures given says so: 2.13529 is theta4 = 2.1352859 rad to six figures
    tight = _fails(kc.value, "q_check", 2.13529, 2.1352859, rtol=1e-7, unit="rad")
    assert tight.endswith("off by +0.000192 %; that is the expected value rounded to the 6 figures written: "
                          "give it unrounded")
    assert "rounded" not in _fails(kc.value, "q_check", 2.13539, 2.1352859, rtol=1e-7, unit="rad")


def test_an_array_missing_by_its_rounding_is_told_to_give_it_unrounded():
    """An array rounded to 4 decimals or to 6 figures misses a check of 1e-6 by its rounding alone: the
    message says so (the reference's values, 13.7121192715 rad/s and others, are the homework's centred
    dβ/dt); float32 values are named as such where a check is tighter than float32 holds; a wrong array,
    zeros, or values rounded to one figure get the miss alone."""
    deg = np.arange(361.0)
    full = 13.7121192715 * np.sin(np.radians(deg) * 1.3) + 0.0312
    ref = {d: full[d] for d in range(10, 360, 30)}

    def check(got, rtol=1e-6):
        return _fails(kc.series, "dbeta_dt_c", got, ref, rtol=rtol, unit="rad/s")

    assert check(np.round(full, 4)).endswith(
        "more than the check allows (1e-06 relative): its values are rounded to 4 decimals: "
        "give them unrounded")
    six = np.array([float(f"{v:.6g}") for v in full])
    assert check(six).endswith("its values are rounded to 6 significant figures: give them unrounded")
    assert check(full.astype(np.float32), rtol=1e-9).endswith(
        "its values are single precision (float32), about 7 figures: compute in float64, numpy's default")
    for wrong in (full * 1.001, np.zeros(361), np.round(full / 100, 1)):
        assert "rounded" not in check(wrong) and "float32" not in check(wrong)
    kc.series("dbeta_dt_c", np.round(full, 4), ref, rtol=1e-5)  # a check the rounding meets passes
    # one number: float32 where a check is tighter than float32 holds; a typed number float32 happens to hold is not
    assert _fails(kc.value, "omega", float(np.float32(200 * math.pi)), 200 * math.pi, rtol=1e-9).endswith(
        "it is single precision (float32), about 7 figures: compute in float64, numpy's default")
    for typed, want in ((28.25, 28.26), (1001.0, 1000.4)):
        assert "float32" not in _fails(kc.value, "x", typed, want, rtol=1e-5)
    # float32 values 0.04 % off: more than float32 explains
    assert "float32" not in check((full * 1.0004).astype(np.float32))


def test_an_angle_is_compared_on_the_reference_turn():
    assert kc.angle_value("q", -2.6 + 2 * math.pi, -2.6) == pytest.approx(-2.6 + 2 * math.pi)
    assert "degrees where radians are asked" in _fails(kc.angle_value, "q", math.degrees(-2.6) + 360.0, -2.6)
    # a miss is measured on the reference's turn: -2.59 against -2.6 is 0.385 % off, 0.01 against 6.28 +0.21 %
    assert _fails(kc.angle_value, "q", -2.59, -2.6).endswith("off by -0.385 %")
    assert _fails(kc.angle_value, "q", 0.01, 6.28).endswith("off by +0.21 %")


def test_a_stub_and_an_undefined_name_are_told_apart():
    assert "is not set yet" in _fails(kc.text, ..., "more_accurate")
    assert "is not defined" in _fails(kc.text, None, "more_accurate")
    assert "should be text" in _fails(kc.text, 2, "more_accurate")
    assert kc.text(" Centred", "more_accurate") == "centred"


def test_rev_per_s_is_named_where_the_check_suspects_it():
    rev = ("deg", "rad/min", "rev")
    assert "off by a factor 1/6.283 (= 1/2π): rev/s (turns per second) where rad/s is asked?" in kc.explain_factor(
        1 / (2 * math.pi), rev)
    assert "1/39.48 (= (1/2π)²): rev/s" in kc.explain_factor(1 / (2 * math.pi) ** 2, rev)
    assert "rpm where rad/s is asked" in kc.explain_factor(60 / (2 * math.pi), ("rpm", "rev", "rad/min"))
    assert kc.explain_factor(1 / (2 * math.pi), ("deg", "rad/min")) is None
    for ratio in (1.3, 2.0, 0.5, 7.0):
        assert kc.explain_factor(ratio, rev) is None


@pytest.mark.parametrize("ratio", [1.0, 1.01, 1.3, 2.0, 0.5, 7.0])
def test_other_ratios_are_not_blamed_on_units(ratio):
    assert kc.explain_factor(ratio, ("deg", "rad/min", "rpm", "mm")) is None


SLIDER_CRANK = (0.08, 0.2, 6000 * 2 * math.pi / 60)  # homework 3: crank R, rod L (m), ω (rad/s)


def _piston_x(theta_rad):
    """The piston position (m) of homework 3's slider-crank, in closed form."""
    r, l, _ = SLIDER_CRANK
    return r * np.cos(theta_rad) + np.sqrt(l**2 - (r * np.sin(theta_rad)) ** 2)


def _piston_a_centred(theta_deg, omega):
    """ω² times the centred second difference (step 1°) of the closed-form x, at the angles given (m/s²)."""
    h = math.radians(1.0)
    t = np.radians(np.asarray(theta_deg, dtype=float))
    return omega**2 * (_piston_x(t + h) - 2 * _piston_x(t) + _piston_x(t - h)) / h**2


def test_the_textbook_approximation_of_the_piston_acceleration_is_given_no_unit_slip():
    """a = -Rω²(cos θ + R/L cos 2θ) drops the higher harmonics: at 90° it is Rω² R/L = 12633 m/s², 1/1.091 of the
    exact 13784 m/s², 0.5 % from (180/π)² × (1/60)² = 1/1.097, a pair of unit factors. It is another formula,
    not two slips: the checks report the miss."""
    r, l, omega = SLIDER_CRANK
    theta = np.radians(np.arange(181.0))
    approx = -r * omega**2 * (np.cos(theta) + r / l * np.cos(2 * theta))
    exact_90 = omega**2 * r**2 / math.sqrt(l**2 - r**2)
    assert approx[90] / exact_90 == pytest.approx(1 / 1.091, rel=1e-3)
    assert approx[90] / exact_90 == pytest.approx((180 / math.pi) ** 2 / 60**2, rel=6e-3)
    message = _fails(_master_test(HW3, "test_a_90"), approx)
    assert message.startswith("`a_90` at θ = 90° = 12633 m/s², expected 13784 m/s² (within 0.50%): off by -8.3")
    assert "factor" not in message and "degrees" not in message and "60" not in message
    assert "factor" not in _fails(_master_test(HW3, "test_acceleration_curve"), approx)
    # no pair of the five suspects within 2 % of it is named, whatever the check's tolerance
    suspects = ("deg", "rpm", "rad/min", "rev", "mm")
    assert kc.explain_factor(approx[90] / exact_90, suspects) is None
    assert kc.explain_factor(approx[90] / exact_90, suspects, rtol=5e-3) is None


def test_one_and_two_unit_slips_are_still_named():
    """Slips on a right answer give exact unit factors, alone or two together: the crank speed left in rpm, the
    acceleration in mm/s², or both, on ω² times the centred second difference of x."""
    r, l, omega = SLIDER_CRANK
    rpm = 6000.0
    check = _master_test(HW3, "test_a_90")
    right = _piston_a_centred(90, omega)
    check(right)
    assert "(= (60/2π)²): rpm where rad/s is asked?" in _fails(check, _piston_a_centred(90, rpm))
    assert "off by a factor 1000: millimetres where metres are asked?" in _fails(check, 1000 * right)
    both = _fails(check, 1000 * _piston_a_centred(90, rpm))
    assert "(= (60/2π)² × 1000): rpm where rad/s is asked?" in both and "And millimetres where metres" in both
    curve = _fails(_master_test(HW3, "test_acceleration_curve"), 1000 * _piston_a_centred(np.arange(181), rpm))
    assert "(= (60/2π)² × 1000)" in curve


def test_the_public_check_near_the_exact_value_names_two_slips_only_where_they_are_exact():
    """Homework 3's public check of a at 0° accepts ±1 % of -Rω²(1 + R/L): a number 0.4 % off once a pair of
    unit factors is taken out is no evidence of that pair; the centred value with two slips is."""
    r, l, omega = SLIDER_CRANK
    check = _master_test(HW3, "test_top_dead_centre")
    exact = -r * omega**2 * (1 + r / l)
    pair = (180 / math.pi) ** 2 / 60**2
    message = _fails(check, exact * pair * 1.004)
    assert "factor" not in message and message.endswith("(between -44658 and -43774)")
    both = _fails(check, 1000 * _piston_a_centred(0, 6000.0))
    assert "(= (60/2π)² × 1000): rpm where rad/s is asked?" in both


def test_a_right_piston_acceleration_is_not_blamed_for_a_wrong_position():
    """Homework 3's a comes from x computed beyond the grid, not from `x_piston`: the check of a against ω² times
    the second difference passes a right a whatever `x_piston` holds (metres, x at θ in degrees read as
    radians), and an a made from the student's own `x_piston` as well; a wrong a is told what is wrong."""
    _, _, omega = SLIDER_CRANK
    check = _master_test(HW3, "test_acceleration_is_your_omega_squared_times_the_second_difference")
    theta = np.arange(181.0)
    a = _piston_a_centred(theta, omega)
    x_mm = 1000 * _piston_x(np.radians(theta))
    check(a, x_mm, omega)
    check(a, x_mm / 1000, omega)  # x in metres
    check(a, 1000 * _piston_x(theta), omega)  # x at 0, 1, ..., 180 rad
    check(a / 1000, x_mm / 1000, omega)  # a made from the student's own x, in metres
    check(a * (6000 / omega) ** 2, x_mm, 6000.0)  # ω in rpm: a agrees with it, the check of ω says what is wrong
    message = _fails(check, a * math.radians(1.0) ** 2, x_mm / 1000, omega)  # divided by 1 (degree) for h²
    assert message.startswith("`a_piston`: off by a factor 1/3283 (= h², with h = 0.01745 rad): the division by h² "
                              "is missing?")


def test_x_at_theta_in_degrees_read_as_radians_is_named():
    message = _fails(_master_test(HW3, "test_position_values"), 1000 * _piston_x(np.arange(181.0)))
    assert message.startswith("`x_piston`: this is x at θ = 0, 1, 2, …, 180 rad, not at 0°, 1°, 2°, …, 180°")
    _master_test(HW3, "test_position_values")(1000 * _piston_x(np.radians(np.arange(181.0))))


@pytest.fixture(scope="module")
def hw4_sweep():
    """θ3, θ4, θ5 (rad) and x of D (cm) over θ2 = 0°, 1°, …, 360°, from numkin's six-bar."""
    from numkin import linkages

    sweep = linkages.six_bar().sweep(np.radians(np.arange(361.0)))
    return [np.asarray(sweep[k]) for k in ("theta3", "theta4", "theta5", "x")]


def test_hw4_rates_are_compared_at_interior_angles_only(hw4_sweep):
    """The question leaves the ends to any formula: np.gradient's first-order ends, or the ends copied from
    their neighbours, cost nothing, as the README promises; the interior is checked as before."""
    x = hw4_sweep[3]
    h = H_RAD
    v = -10.0 * np.gradient(x, h)  # centred inside, one-sided first order at 0° and 360°
    a = 100.0 * np.concatenate([[0.0], (x[2:] - 2 * x[1:-1] + x[:-2]) / h**2, [0.0]])
    a[0], a[-1] = a[1], a[-2]
    _master_test(HW4, "test_slider_velocity")(v)
    _master_test(HW4, "test_slider_acceleration")(a)
    _master_test(HW4, "test_rates_follow_from_position")(x, v, a)
    assert "off by up to" in _fails(_master_test(HW4, "test_slider_velocity"), v * (1 + 1e-2))


def test_hw4_x_in_millimetres_is_named(hw4_sweep):
    t3, t4, t5, x = hw4_sweep
    message = _fails(_master_test(HW4, "test_loops_close_on_one_branch"), t3, t4, t5, 10 * x)
    assert message == "`x_D` looks like millimetres: the loops close with x_D / 10; the question asks for centimetres"
    _master_test(HW4, "test_loops_close_on_one_branch")(t3, t4, t5, x)
    message = _fails(_master_test(HW4, "test_slider_position"), 10 * x)
    assert message == "`x_D`: off by a factor 10: millimetres where centimetres are asked? (1 cm = 10 mm)"
    message = _fails(_master_test(HW4, "test_slider_velocity"), -100.0 * np.gradient(x, H_RAD))
    assert message.startswith("`v_D`: off by a factor 10: millimetres where centimetres are asked?")


def test_pairs_of_unit_factors_explain_few_ratios_near_one():
    """Between 1/2 and 2 no single unit factor lies; products of two of homework 3's five suspects lie
    everywhere, so within 2 % they "explained" three ratios in ten. Within the pairs' own tolerance, about
    one in seventy at most."""
    suspects = ("deg", "rpm", "rad/min", "rev", "mm")
    ratios = np.exp(np.linspace(math.log(0.5), math.log(2.0), 4001))
    named = [r for r in ratios if kc.explain_factor(float(r), suspects) is not None]
    assert len(named) / ratios.size < 0.02
    # a check of 0.5 % names no more; one of 1e-6 names none but exact products
    assert [r for r in ratios if kc.explain_factor(float(r), suspects, rtol=5e-3) is not None] == named
    assert all(kc.explain_factor(float(r), suspects, rtol=1e-6) is None for r in named[::10])


def test_value_at_100_degrees_is_picked_from_a_full_turn_array():
    turn = np.arange(361.0) / 10
    assert kc.at(turn, "w", 100) == 10.0
    assert kc.at(turn[:360], "w", 100) == 10.0  # 0..359 is accepted too
    assert kc.at(10.0, "w", 100) == 10.0
    assert kc.at(np.float64(10.0), "w", 100) == 10.0
    assert kc.at([[10.0]], "w", 100) == 10.0
    assert "361 values" in _fails(kc.at, np.zeros(200), "w", 100)
    assert kc.at(turn[1:360], "w", 100) == 10.0  # interior points only (359 values)
    assert "not set yet" in _fails(kc.at, ..., "w", 100)
    # otter passes None for a name the notebook does not define (its cell raised an error)
    undefined = _fails(kc.at, None, "w", 100)
    assert undefined.startswith("`w` is not defined: did the cell that computes it raise an error?")
    assert "not set yet" not in undefined
    assert "should be a number" in _fails(kc.at, "ten", "w", 100)


def test_one_angle_is_read_modulo_whole_turns_and_degrees_are_named():
    want = 2.1352859378
    assert kc.angle_value("q", want + 2 * math.pi, want) == pytest.approx(want + 2 * math.pi)
    kc.angle_value("q", want - 4 * math.pi, want)
    message = _fails(kc.angle_value, "q", math.degrees(want), want, deg=100)
    assert message.startswith("`q` at θ = 100° = 122.34 rad: that is the expected 122.343° in degrees: "
                              "degrees where radians are asked?")
    assert "whole turns" in _fails(kc.angle_value, "q", math.degrees(want) + 360, want)
    assert "off by +38.7 %" in _fails(kc.angle_value, "q", 2.9624, want)


def test_arrays_are_read_with_their_shape_checked():
    assert kc.array(np.zeros((361, 1)), "y").shape == (361,)
    assert kc.array(list(range(181)), "y", grid=(0, 180, 1)).shape == (181,)
    bad = np.zeros(361)
    bad[42] = np.nan
    message = _fails(kc.array, bad, "y")
    assert "θ = 42°" in message and "did Newton" not in message


def test_angles_in_radians_or_degrees_wrapped_or_not():
    ref = {10: 0.5, 100: 1.6, 250: 3.0}
    rad = np.zeros(361)
    for d, v in ref.items():
        rad[d] = v
    assert kc.unit_of("phi", rad, ref) == "rad"
    assert kc.unit_of("phi", rad - 47 * 2 * np.pi, ref) == "rad"  # unwrapped
    assert kc.unit_of("phi", np.degrees(rad) % 360, ref) == "deg"
    assert kc.unit_of("phi", np.degrees(rad) + 720, ref) == "deg"
    message = _fails(kc.unit_of, "beta", np.degrees(rad), ref, allow=("rad",))
    assert "look like degrees; the question asks for radians" in message
    off = rad.copy()
    off[100] += 3e-5
    assert "Newton iteration stopped too early" in _fails(kc.unit_of, "phi", off, ref)
    mirror = rad.copy()
    mirror[250] += np.pi
    assert "mirror solution" in _fails(kc.unit_of, "phi", mirror, ref)


def test_angles_check_says_which_unit_it_read(capsys):
    ref = {10: 0.5}
    kc.angles("phi", np.full(361, math.degrees(0.5)), ref)
    assert "`phi` read as degrees" in capsys.readouterr().out


def test_series_names_the_other_difference_and_unit_factors():
    centred = {10: 6.0, 100: 10.633, 190: -9.09}
    forward = {10: 6.15, 100: 10.600, 190: -9.25}
    y = np.zeros(361)
    for d, v in forward.items():
        y[d] = v
    message = _fails(
        kc.series, "dbeta_dt_c", y, centred,
        alternatives=[(forward, "this matches the forward difference; the question asks for centred")],
    )
    assert message == "`dbeta_dt_c`: this matches the forward difference; the question asks for centred"
    for d, v in centred.items():
        y[d] = v * 60
    assert "off by a factor 60: rad/min" in _fails(kc.series, "w", y, centred)
    for d, v in centred.items():
        y[d] = v * (1 + 1e-4)
    message = _fails(kc.series, "w", y, centred, rtol=1e-6)
    assert "several causes" in message and "np.gradient" in message and "loose Newton" in message
    assert "usually comes from" not in message  # no single cause without the evidence for it
    kc.series("w", y, centred, rtol=1e-3)


@pytest.mark.parametrize("size", [361, 360, 359])
def test_arrays_of_every_plausible_length_are_read_without_a_traceback(size):
    theta = np.radians(np.arange(361.0))
    y = np.sin(theta)
    ref = {d: math.cos(math.radians(d)) for d in range(10, 360, 30)}
    h = math.radians(1.0)
    full = np.gradient(y, h)
    candidates = {361: full, 360: np.diff(y) / h, 359: (y[2:] - y[:-2]) / (2 * h)}
    values = kc.array(candidates[size], "dy")
    assert values.shape == (361,)
    kc.series("dy", candidates[size], ref, rtol=1e-2)  # all three are close to cos at 1 deg


def test_the_forward_difference_applied_twice_is_read_from_the_start():
    h = math.radians(1.0)
    y = np.sin(np.arange(361.0) * h)
    twice = np.diff(y, 2) / h**2  # 359 values, at 0 deg ... 358 deg: (y[i+2] - 2 y[i+1] + y[i]) / h^2
    forward_twice = {d: (y[d + 2] - 2 * y[d + 1] + y[d]) / h**2 for d in range(10, 360, 30)}
    centred = {d: (y[d + 1] - 2 * y[d] + y[d - 1]) / h**2 for d in range(10, 360, 30)}
    named = [(centred, "this matches the centred second difference")]
    kc.series("d2y", twice, forward_twice, rtol=1e-9, forward=True, alternatives=named)
    padded = np.append(twice, [np.nan, np.nan])  # undefined at 359 and 360 deg, neither checked
    kc.series("d2y", padded, forward_twice, rtol=1e-9, forward=True, alternatives=named)
    padded[0] = np.nan  # a forward formula is defined at 0 deg: NaN there is a failed value
    assert "θ = 0°" in _fails(kc.array, padded, "d2y", forward=True)
    # read as interior points (the centred reading), the same values are the centred second difference
    assert "centred second difference" in _fails(kc.series, "d2y", twice, forward_twice, rtol=1e-9,
                                                 alternatives=named)


def test_nan_at_the_ends_is_allowed_unless_the_end_is_checked():
    y = np.cos(np.radians(np.arange(361.0)))
    y[0] = y[-1] = np.nan
    kc.series("dy", y, {10: math.cos(math.radians(10))}, rtol=1e-9)
    message = _fails(kc.series, "dy", y, {0: 1.0}, rtol=1e-9)
    assert "θ = 0°" in message and "end of the grid" in message
    assert "Newton" not in message
    assert "end of the grid" in _fails(kc.at, y, "dy", 360)


def test_own_difference_formulas():
    h = 0.01
    y = np.exp(np.arange(10) * h)
    for kind, want in [("centred", 1.0), ("forward", 1.0), ("second", 1.0), ("forward_twice", 1.0),
                       ("gradient_twice", 1.0)]:
        got = kc.own_difference(y, [4], h, kind)[4] / y[4]
        assert got == pytest.approx(want, rel=2e-2), kind
    twice = np.gradient(np.gradient(y, h), h)
    assert kc.own_difference(y, [4], h, "gradient_twice")[4] == pytest.approx(twice[4], rel=1e-12)


def test_value_and_band_feedback():
    assert "expected 10.633 rad/s (within 0.50%)" in _fails(kc.value, "w", 10.9, 10.633, deg=100, unit="rad/s")
    assert "off by +2.51 %" in _fails(kc.value, "w", 10.9, 10.633, deg=100)
    assert "forward" in _fails(kc.value, "a", -28.13, -28.375, alternatives=[(-28.1266, "forward")])
    kc.band("w", 10.63, 8, 12, about=10)
    message = _fails(kc.band, "w", 10.63 * 60, 8, 12, about=10, deg=100, unit="rad/s")
    assert message.startswith("`w` at θ = 100° = 637.8 rad/s: off by a factor 60")
    assert "the sign is flipped" in _fails(kc.band, "w", -10.6, 8, 12, about=10)
    assert "between 8 and 12" in _fails(kc.band, "w", 13.5, 8, 12, about=10)


def test_loop_closure_and_continuity_feedback():
    theta = np.radians(np.arange(361.0))
    phi = np.full(361, 1.0)
    gap = kc.four_bar_gap(phi, theta, 7.0, 1.94, 6.86, 2.36)
    assert gap.shape == (361,)
    assert "check the equations" in _fails(kc.closure, "phi", gap)
    assert "stops too early" in _fails(kc.closure, "phi", np.full(361, 1e-5))
    kc.closure("phi", np.full(361, 1e-12))
    smooth = np.radians(np.linspace(20, 130, 361))
    kc.continuity("phi", smooth)
    jumpy = smooth.copy()
    jumpy[200:] += np.radians(40)
    assert "continuation" in _fails(kc.continuity, "phi", jumpy)
    kc.continuity("phi", smooth + 2 * np.pi * (np.arange(361) > 100))  # whole turns are no jump


def test_read_angles_picks_the_unit_that_closes_the_loop():
    def gap(a):
        return np.abs(np.sin(a - 1.0))

    unit, angles, residual = kc.read_angles("t", np.full(361, math.degrees(1.0)), gap)
    assert unit == "deg" and np.allclose(angles, 1.0) and residual.max() < 1e-12


def test_chained_angles_are_read_in_the_unit_that_closes_each_loop():
    from numkin import linkages

    theta = np.radians(np.arange(361.0))
    sweep = linkages.chained_four_bars().sweep(theta)
    phi, beta = np.asarray(sweep["phi"]), np.asarray(sweep["beta"])
    phi_rad, beta_rad, unit, residual = kc.chained_four_bar_angles(phi, np.degrees(beta))
    assert unit == "deg" and np.max(residual) < 1e-9
    assert np.allclose(beta_rad, beta) and np.allclose(phi_rad, phi)


def test_the_other_assembly_of_each_chained_linkage_is_named():
    from numkin import linkages

    theta = np.radians(np.arange(361.0))
    sweep = linkages.chained_four_bars().sweep(theta)
    phi, beta = np.asarray(sweep["phi"]), np.asarray(sweep["beta"])
    kc.chained_four_bar_assembly("phi", phi)
    kc.chained_four_bar_assembly("beta", phi, beta)
    kc.chained_four_bar_assembly("beta", phi, np.degrees(beta))
    # the mirror image across the line from the output pivot to the end of the input link closes the loop too
    alpha = phi + np.radians(149.0)
    mirror = 2 * np.angle(1.25 + 2.39 * np.exp(1j * alpha)) - beta
    assert kc.four_bar_gap(mirror, alpha, 1.25, 2.39, 1.87, 1.26).max() < 1e-9
    message = _fails(kc.chained_four_bar_assembly, "beta", phi, mirror)
    assert message.startswith("`beta` is on the other assembly (the other circle intersection) of linkage 2")
    mirror_phi = 2 * np.angle(7.0 + 1.94 * np.exp(1j * theta)) - phi
    assert "of linkage 1" in _fails(kc.chained_four_bar_assembly, "phi", mirror_phi)
    # angles that do not close the loop, or are missing, are left to the other checks
    kc.chained_four_bar_assembly("beta", phi, beta + 0.1)
    kc.chained_four_bar_assembly("beta", phi, None)
    kc.chained_four_bar_assembly("phi", ...)


# --------------------------------------------------------------------------
# the hidden tests of homework 1 on answers near, but not at, the reference
# --------------------------------------------------------------------------

HW1 = "hw1_chained_four_bar"
HW3 = "hw3_slider_crank"
HW4 = "hw4_six_bar"
H_RAD = math.radians(1.0)  # the homework's grid step


def _master_cells(hw):
    jupytext = pytest.importorskip("jupytext")
    return jupytext.read(build.master_path(hw)).cells


def _master_test(hw, name):
    """The test function ``name`` of a master, defined as otter defines it (kincheck importable)."""
    (source,) = [c.source for c in _master_cells(hw) if c.cell_type == "code" and f"def {name}(" in c.source]
    namespace: dict = {}
    exec(source, namespace)
    return namespace[name]


@pytest.fixture(scope="module")
def hw1_sweep():
    """φ and β over θ = 0°, 1°, …, 360° (rad), from numkin's chained four-bars."""
    from numkin import linkages

    sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(361.0)))
    return np.asarray(sweep["phi"]), np.asarray(sweep["beta"])


@pytest.mark.parametrize("word", ["centred", "Centred", " CENTERED ", "Central difference", "centre", "center",
                                  "forward", "Forward difference", "backward", "the centred one", "c", ""])
def test_q1c_public_and_hidden_checks_read_a_word_alike(word):
    """Every answer the hidden check accepts passes the public check: both read the word in any case, by how it
    starts. The public check also lets "forward" through (the form is right, the hidden check marks the choice)."""
    public, hidden = _master_test(HW1, "test_answer_form"), _master_test(HW1, "test_orders")
    centred = word.strip().lower().startswith("cent")
    form = centred or word.strip().lower().startswith("forw")
    if form:
        public(word, 1, 2)
    else:
        assert _fails(public, word, 1, 2).startswith('`more_accurate` should be "forward" or "centred", got')
    if centred:
        hidden(word, 1, 2)
    else:
        assert "the centred difference is the more accurate one" in _fails(hidden, word, 1, 2)


def test_q1c_an_answer_not_set_yet_is_told_so():
    public, hidden = _master_test(HW1, "test_answer_form"), _master_test(HW1, "test_orders")
    for check in (public, hidden):
        assert _fails(check, ..., 1, 2).startswith("`more_accurate` is not set yet: replace its `...`")
        assert _fails(check, None, 1, 2).startswith("`more_accurate` is not defined: did the cell")
        assert _fails(check, "centred", ..., 2).startswith("`order_forward` is not set yet")
    assert _fails(public, 2, 1, 2) == "`more_accurate` should be text (a word, in quotes), got int"
    assert _fails(public, "centred", True, 2) == "`order_forward` should be a number, got True"


def _solved_at_degrees_read_as_radians(mechanism):
    """A numkin sweep at θ = 0, 1, …, 360 rad: what a solver of radians gives when it is handed theta_deg."""
    import warnings

    from numkin import DegreesWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegreesWarning)  # numkin warns of exactly this slip
        return mechanism.sweep(np.arange(361.0))


def test_theta_in_degrees_handed_to_the_sweep_is_named(hw1_sweep):
    """φ solved at θ = 0, 1, 2, … rad closes linkage 1 there and at no asked angle: the checks of q1a say that θ
    was given in degrees, in either unit φ is handed in; the right φ passes, and a φ that closes nowhere is left to
    the closure check."""
    from numkin import linkages

    wrong = np.asarray(_solved_at_degrees_read_as_radians(linkages.chained_four_bars())["phi"])
    assert kc.four_bar_gap(wrong, np.arange(361.0), 7.0, 1.94, 6.86, 2.36).max() < 1e-9
    said = ("`phi` closes the loop at θ = 0, 1, 2, … rad, not at θ = 0°, 1°, 2°, …: the input angles were given in "
            "degrees where the equations take radians; use `theta`, not `theta_deg`")
    public = _master_test(HW1, "test_phi_closes_loop_on_one_branch")
    assert _fails(public, wrong) == said
    assert _fails(public, np.degrees(wrong)) == said
    assert _fails(_master_test(HW1, "test_phi_values"), wrong) == said
    public(hw1_sweep[0])
    assert "does not satisfy the loop-closure equations" in _fails(public, np.full(361, 1.0))


def test_theta2_in_degrees_in_the_six_bar_is_named(hw4_sweep):
    from numkin import linkages

    wrong = _solved_at_degrees_read_as_radians(linkages.six_bar())
    t3, t4, t5, x = (np.asarray(wrong[k]) for k in ("theta3", "theta4", "theta5", "x"))
    message = _fails(_master_test(HW4, "test_loops_close_on_one_branch"), t3, t4, t5, x)
    assert message.startswith("`theta3, theta4, theta5` closes the loop at θ = 0, 1, 2, … rad, not at θ = 0°, 1°, 2°")
    assert message.endswith("use `theta2`, not `theta2_deg`")


def test_alpha_between_the_centred_and_the_forward_twice_value_names_no_formula():
    ref = build.load_expected(HW1)
    centred, forward_twice = ref["alpha_beta_100"], ref["alpha_beta_fw_100"]
    assert forward_twice == pytest.approx(-28.1266, abs=1e-4) and centred == pytest.approx(-28.375, abs=1e-3)
    check = _master_test(HW1, "test_alpha_100")
    # -28.0 is 0.45 % from the forward difference applied twice and 1.3 % from the reference: neither
    message = _fails(check, -28.0)
    assert "forward difference applied twice" not in message
    assert message == "`alpha_100` at θ = 100° = -28 rad/s², expected -28.375 rad/s² (within 0.50%): off by -1.32 %"
    # the forward difference applied twice itself is named, with the number and its unit
    message = _fails(check, forward_twice)
    assert message.startswith("`alpha_100` at θ = 100° = -28.12656 rad/s², expected -28.375 rad/s²: ")
    assert "this matches the forward difference applied twice" in message
    assert kc.matches_alternative(-28.13, forward_twice, centred, 5e-3)
    assert not kc.matches_alternative(-28.0, forward_twice, centred, 5e-3)


def test_omega_100_by_the_forward_difference_is_named_though_within_the_tolerance():
    ref = build.load_expected(HW1)
    exact, forward = ref["omega_beta_100"], ref["omega_beta_fw_100"]
    assert abs(forward / exact - 1) < 5e-3  # inside the 0.5 % the check allows
    check = _master_test(HW1, "test_omega_100")
    message = _fails(check, forward)
    assert message.startswith("`omega_100` at θ = 100° = 10.59998 rad/s, expected 10.6329 rad/s: ")
    assert "this matches the forward difference; the question asks for the centred difference" in message
    check(ref["dbeta_dt_centred"][100])  # the centred value passes, and so does the exact one
    check(exact)
    check(10.62)  # between the two: it names no formula, and it lies within 0.5 %


def test_an_array_between_the_asked_and_another_difference_names_no_formula():
    centred = {10: 6.0, 100: 10.633, 190: -9.09}
    forward = {d: v * 1.003 for d, v in centred.items()}
    y = np.zeros(361)
    for d, v in centred.items():
        y[d] = v * 1.002  # within 1e-3 of the forward values, but barely closer to them
    message = _fails(kc.series, "w", y, centred, rtol=1e-3, alternatives=[(forward, "matches the forward difference")])
    assert "matches the forward difference" not in message and "off by up to" in message


def test_np_diff_without_h_is_named_as_a_missing_division_by_h(hw1_sweep):
    phi, beta = hw1_sweep
    message = _fails(_master_test(HW1, "test_dphi_forward"), np.diff(phi))
    assert message.startswith("`dphi_fw`: off by a factor 1/57.3 (= h, with h = 0.01745 rad): "
                              "a division by the step h is missing?")
    assert "radians where degrees are asked" not in message
    # the reference values agree with the division made: h times the forward difference
    ref = build.load_expected(HW1)["dphi_forward"]
    assert np.diff(phi)[100] / H_RAD == pytest.approx(ref[100], rel=1e-6)
    # a second difference without / h² is named the same way, and so is the public check near -25 rad/s²
    omega = 7.5
    second = omega**2 * np.diff(beta, 2)  # starts at 1°: interior values
    message = _fails(_master_test(HW1, "test_d2beta_dt2_centred"), second)
    assert "(= h², with h = 0.01745 rad): the division by h² is missing?" in message
    message = _fails(_master_test(HW1, "test_near_the_assignment_check"), 10.63, second, omega, beta)
    assert message.startswith("`alpha_100` at θ = 100° = -0.0086") and "the division by h² is missing?" in message


def test_missing_step_is_named_only_for_difference_quotients():
    # without a step the degree slip is named, as before; with it the missing division comes first
    assert "radians where degrees are asked" in kc.explain_factor(H_RAD, ("deg",))
    assert "division by the step h is missing" in kc.explain_factor(H_RAD, ("deg",), step_rad=H_RAD)
    assert "sign is flipped as well" in kc.explain_factor(-H_RAD, ("deg",), step_rad=H_RAD)
    assert kc.explain_factor(1 / H_RAD, ("deg",), step_rad=H_RAD).startswith("off by a factor 57.3")
    assert kc.explain_factor(1.3, ("deg",), step_rad=H_RAD) is None


# --------------------------------------------------------------------------
# the solution and the student version of the masters
# --------------------------------------------------------------------------


def test_hw1_solution_sweep_keeps_angles_continuous_across_a_full_turn():
    """The reference solution's continuation does not wrap angles to [0, 2π): on a drag-link,
    whose output turns fully, its angles pass 2π without a jump that differences would see."""
    cells = [c.source for c in _master_cells(HW1) if c.cell_type == "code"]
    namespace: dict = {}
    exec(cells[0], namespace)  # imports, dimensions, θ grid
    (solver,) = [s for s in cells if "def four_bar_sweep(" in s]
    exec(solver, namespace)
    theta = np.radians(np.arange(0.0, 721.0))
    # fixed link shortest: both cranks turn fully (Grashof drag-link); guess near θ = 0's solution
    out, coupler = namespace["four_bar_sweep"](theta, 1.0, 3.0, 3.5, 3.0, np.radians([10.0, 100.0]))
    gap = kc.four_bar_gap(out, theta, 1.0, 3.0, 3.5, 3.0)
    assert gap.max() < 1e-9
    assert np.ptp(out) > 2 * np.pi  # it turned fully, past 2π
    assert np.degrees(np.abs(np.diff(out))).max() < 5.0
    assert np.degrees(np.abs(np.diff(coupler))).max() < 5.0


def _student_code(hw):
    """The code cells of the student notebook otter assign makes from a master (tests left out)."""
    pytest.importorskip("otter")
    from otter.assign.solutions import replace_solutions

    code, in_solution, in_tests = [], False, False
    for cell in _master_cells(hw):
        text = cell.source.strip()
        if cell.cell_type == "raw":
            in_solution = {"# BEGIN SOLUTION": True, "# END SOLUTION": False}.get(text, in_solution)
            in_tests = {"# BEGIN TESTS": True, "# END TESTS": False}.get(text, in_tests)
        elif cell.cell_type == "code" and not in_tests:
            code.append("\n".join(replace_solutions(cell.source.split("\n"), "python")) if in_solution else cell.source)
    return code


@pytest.mark.parametrize("hw", HOMEWORK)
def test_student_notebook_runs_all_cells(hw, monkeypatch, tmp_path):
    """"Run All" on the student version: the stubs (``...``) run, and the checks then say what is missing."""
    pytest.importorskip("matplotlib").use("Agg")
    monkeypatch.chdir(tmp_path)
    monkeypatch.syspath_prepend(str(build.folder(hw)))
    namespace: dict = {}
    for number, source in enumerate(_student_code(hw)):
        try:
            exec(source, namespace)
        except Exception as error:  # noqa: BLE001 - the cell and the error are the message
            pytest.fail(f"{hw}: student cell {number} raises {type(error).__name__}: {error}\n{source}")
    if hw == HW1:
        assert namespace["phi"] is Ellipsis and namespace["beta"] is Ellipsis
        assert "`phi` is not set yet: replace its `...`" in _fails(kc.array, namespace["phi"], "phi")


def _master_tests(hw):
    """Every test function of a master, public and hidden, defined as otter defines it: [(name, function)]."""
    found = []
    for cell in _master_cells(hw):
        if cell.cell_type == "code" and "def test_" in cell.source:
            namespace: dict = {}
            exec(cell.source, namespace)
            found += [(name, f) for name, f in namespace.items() if name.startswith("test_")]
    return found


@pytest.mark.parametrize("hw", HOMEWORK)
def test_an_untouched_notebook_is_told_what_is_not_done_yet(hw, monkeypatch, tmp_path):
    """The first grader.check of a notebook run as handed out: every check, public and hidden, fails (no point
    for a stub), and says that an answer is not set yet or a function not written yet (its stub returns None),
    not that it has the wrong shape or raised a TypeError."""
    import inspect

    pytest.importorskip("matplotlib").use("Agg")
    monkeypatch.chdir(tmp_path)
    monkeypatch.syspath_prepend(str(build.folder(hw)))
    namespace: dict = {}
    for source in _student_code(hw):
        exec(source, namespace)
    tests = _master_tests(hw)
    assert len(tests) >= 5
    for name, check in tests:
        arguments = [namespace.get(p) for p in inspect.signature(check).parameters]  # otter passes None if missing
        message = _fails(check, *arguments)
        assert "is not set yet: replace its `...`" in message or "is not written yet: `" in message, (name, message)
    if hw == "hw2_quick_return":
        assert _fails(dict(tests)["test_jacobian_matches_residual"], namespace["F"], namespace["J"]) == (
            "`F` is not written yet: `F(x, theta2)` returns None (its body is still `...`, or it has no `return`)")


def test_generated_master_says_the_units_of_its_guess_and_of_q_check(tmp_path):
    """The comment of GUESS names the unknowns' own units; the question says q_check is in rad."""
    pytest.importorskip("sympy")
    scene = tmp_path / "crank-rocker.toml"
    scene.write_text(
        '[scene]\ndescription = "A crank-rocker at 100 rpm"\n[mechanism]\nlinkage = "four_bar"\nunit = "mm"\n'
        "[mechanism.dimensions]\nground = 40\ncrank = 10\ncoupler = 30\nrocker = 30\n"
        '[input]\nspeed = "100 rpm"\nstart_deg = 0\nstop_deg = 360\nstep_deg = 1\n[[check]]\nat_deg = 100\n'
    )
    master = build.master_path(build.new_from_scene(scene, tmp_path)).read_text()
    assert "# (theta3, theta4) at START_DEG, in rad\n" in master
    assert "its value at the check angle in `q_check`,\n# both in rad." in master


def test_the_scene_format_is_linked_to_its_page():
    readme = (ASSIGNMENTS / "README.md").read_text()
    assert "numkin/scene.py" not in readme
    assert "](../docs/scene.rst)" in readme and (ROOT / "docs" / "scene.rst").exists()
    # the docs page includes the README with links under ../docs/ made relative to docs/
    assert ":relative-docs: ../docs/" in (ROOT / "docs" / "assignments.md").read_text()

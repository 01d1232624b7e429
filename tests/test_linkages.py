"""Ready-made linkages against closed forms derived here, and the numbers the source documents give.

Every reference below is computed in this file from the geometry (circle
intersections, Freudenstein's equation, the slider-crank and quick-return
formulas); angles are compared continuously (the sweep's angles must equal the
unwrapped reference up to one constant multiple of 2 pi, and never jump).
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from numkin import linkages

TWO_PI = 2 * math.pi
FULL_TURN = np.radians(np.arange(0.0, 361.0))
POS_TOL = 1e-10


# ------------------------------------------------------------------ helpers
def assert_angle_continuous(got, ref, atol=POS_TOL, max_jump=None):
    """``got`` equals the unwrapped ``ref`` + 2 pi k (one k) everywhere, and has no jumps."""
    got = np.asarray(got, dtype=float)
    ref = np.unwrap(np.asarray(ref, dtype=float))
    k = np.round((got[0] - ref[0]) / TWO_PI)
    np.testing.assert_allclose(got, ref + TWO_PI * k, rtol=0, atol=atol)
    if got.size > 1:
        if max_jump is None:
            max_jump = 1.5 * np.max(np.abs(np.diff(ref))) + 1e-9
        assert np.max(np.abs(np.diff(got))) <= max_jump


def circle_intersection(c1, r1, c2, r2, side):
    """Points at distance r1 from c1 and r2 from c2; ``side`` +1 left of c1 -> c2, -1 right.

    c1, c2 are (2, N) arrays (or broadcastable), r1, r2 numbers.
    """
    c1 = np.asarray(c1, dtype=float)
    c2 = np.asarray(c2, dtype=float)
    delta = c2 - c1
    d = np.hypot(delta[0], delta[1])
    u = delta / d
    along = (r1**2 - r2**2 + d**2) / (2 * d)
    h = np.sqrt(r1**2 - along**2)
    perp = np.array([-u[1], u[0]])
    return c1 + along * u + side * h * perp


def four_bar_reference(theta2, r1, r2, r3, r4, side):
    a = np.array([r2 * np.cos(theta2), r2 * np.sin(theta2)])
    o4 = np.array([np.full_like(theta2, r1), np.zeros_like(theta2)])
    b = circle_intersection(a, r3, o4, r4, side)
    theta3 = np.arctan2(b[1] - a[1], b[0] - a[0])
    theta4 = np.arctan2(b[1] - o4[1], b[0] - o4[0])
    return theta3, theta4


def freudenstein_residual(theta2, theta4, d, a, b, c):
    """K1 cos(t4) - K2 cos(t2) + K3 - cos(t2 - t4) (crank a, coupler b, rocker c, ground d)."""
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    return k1 * np.cos(theta4) - k2 * np.cos(theta2) + k3 - np.cos(theta2 - theta4)


# ----------------------------------------------------------------- four-bar
FOUR_BARS = [
    # (ground, crank, coupler, rocker, inputs)
    pytest.param(4, 1, 3, 3, FULL_TURN, id="crank-rocker"),
    pytest.param(2, 4, 5, 4.5, FULL_TURN, id="double-crank"),
    pytest.param(9.5, 2.5, 7, 6, np.radians(np.arange(-90.0, 271.0, 2.0)), id="crank-rocker-from--90"),
    pytest.param(7, 4, 3, 5, np.radians(np.linspace(-88.0, 88.0, 177)), id="triple-rocker-reachable"),
]


@pytest.mark.parametrize("ground, crank, coupler, rocker, inputs", FOUR_BARS)
@pytest.mark.parametrize("branch, side", [("open", 1.0), ("crossed", -1.0)])
def test_four_bar_matches_circle_intersection(ground, crank, coupler, rocker, inputs, branch, side):
    m = linkages.four_bar(ground, crank, coupler, rocker, branch=branch)
    assert m.unknowns == ("theta3", "theta4")
    assert str(m.input_symbol) == "theta2"
    sweep = m.sweep(inputs)
    t3, t4 = four_bar_reference(inputs, ground, crank, coupler, rocker, side)
    assert_angle_continuous(sweep["theta3"], t3)
    assert_angle_continuous(sweep["theta4"], t4)
    # Freudenstein's equation as a second, independent check
    fr = freudenstein_residual(inputs, sweep["theta4"], ground, crank, coupler, rocker)
    assert np.max(np.abs(fr)) < 1e-11
    # open branch: B left of A -> O4, i.e. sin(theta3 - theta4) > 0 ... for the crossed the other sign
    s = np.sign(np.sin(sweep["theta4"] - sweep["theta3"]))
    assert np.all(s == s[0])


def test_four_bar_points_are_the_linkage():
    m = linkages.four_bar(4, 1, 3, 3)
    sweep = m.sweep(FULL_TURN)
    pts = sweep.points()
    assert set(pts) == {"O2", "A", "B", "O4"}
    a, b, o4 = pts["A"], pts["B"], pts["O4"]
    np.testing.assert_allclose(np.hypot(*a), 1.0, atol=1e-14)
    np.testing.assert_allclose(np.hypot(*(b - a)), 3.0, atol=1e-12)
    np.testing.assert_allclose(np.hypot(*(b - o4)), 3.0, atol=1e-12)
    np.testing.assert_allclose(o4, [[4.0] * 361, [0.0] * 361])


def test_grashof_classes():
    assert linkages.grashof(7, 4, 3, 5) == "non-Grashof triple rocker"
    assert linkages.grashof(4, 1, 3, 3) == "Grashof crank-rocker"
    assert linkages.grashof(2, 4, 5, 4.5) == "Grashof double crank"
    assert linkages.grashof(5, 4, 2, 4.5) == "Grashof double rocker"
    assert linkages.grashof(5, 3, 4, 1.5) == "Grashof rocker-crank"
    assert linkages.grashof(5, 2, 5, 2).startswith("change-point")


# ------------------------------------------------------------- slider-crank
@pytest.mark.parametrize(
    "crank, rod, offset",
    [(80, 200, 0.0), (1.0, 3.0, 0.5), (1.0, 3.0, -0.7), (0.02, 0.05, 0.01)],
)
def test_slider_crank_closed_form(crank, rod, offset):
    m = linkages.slider_crank(crank, rod, offset)
    assert m.unknowns == ("theta3", "x")
    assert m.angles == ("theta3",)
    inputs = FULL_TURN
    sweep = m.sweep(inputs)
    s = crank * np.sin(inputs) - offset
    x_ref = crank * np.cos(inputs) + np.sqrt(rod**2 - s**2)
    t3_ref = np.arcsin(-s / rod)
    np.testing.assert_allclose(sweep["x"], x_ref, rtol=0, atol=POS_TOL * max(rod, 1.0))
    assert_angle_continuous(sweep["theta3"], t3_ref)
    assert sweep.unit("x") == "mm" and sweep.unit("theta3") == "rad"


def test_slider_crank_other_branch_by_guess():
    r, rod, e = 1.0, 3.0, 0.5
    m = linkages.slider_crank(r, rod, e)
    inputs = FULL_TURN
    g = math.sqrt(rod**2 - e**2)
    sweep = m.sweep(inputs, guess={"theta3": math.pi - math.asin(e / rod), "x": r - g})
    s = r * np.sin(inputs) - e
    np.testing.assert_allclose(sweep["x"], r * np.cos(inputs) - np.sqrt(rod**2 - s**2), rtol=0, atol=POS_TOL * rod)
    assert_angle_continuous(sweep["theta3"], np.pi + np.arcsin(s / rod))


# ------------------------------------------------------------- quick-return
def quick_return_reference(theta2, r1, r2, r6):
    r3 = np.sqrt(r1**2 + r2**2 + 2 * r1 * r2 * np.sin(theta2))
    theta3 = np.arctan2(r1 + r2 * np.sin(theta2), r2 * np.cos(theta2))  # tan = (r1 + r2 s) / (r2 c), in (0, pi)
    r4 = (r1 + r6) / np.sin(theta3)
    r5 = r4 * np.cos(theta3)
    return r3, theta3, r4, r5


def test_quick_return_document_numbers():
    """Report 000 at theta2 = 30 deg (its hand value 130.75 for r4 is an arithmetic slip)."""
    m = linkages.quick_return()
    assert m.unknowns == ("r3", "theta3", "r4", "r5")
    res = m.solve(math.radians(30))
    assert res.converged
    r3, t3, r4, r5 = res.x
    assert round(r3, 3) == 87.178
    assert round(math.degrees(t3), 3) == 66.587
    assert round(r4, 3) == 130.767
    assert round(r5, 3) == 51.962
    assert round(m.time_ratio, 3) == 2.735


@pytest.mark.parametrize("r1, r2, r6", [(60.0, 40.0, 60.0), (1.0, 0.3, 2.0)])
def test_quick_return_closed_form_over_a_turn(r1, r2, r6):
    m = linkages.quick_return(r1, r2, r6)
    sweep = m.sweep(FULL_TURN)
    r3, t3, r4, r5 = quick_return_reference(FULL_TURN, r1, r2, r6)
    scale = max(r1, r2, r6)
    for name, ref in (("r3", r3), ("r4", r4), ("r5", r5)):
        np.testing.assert_allclose(sweep[name], ref, rtol=0, atol=POS_TOL * scale)
    assert_angle_continuous(sweep["theta3"], t3)
    # time ratio from its closed form: the rocker's extremes are where O1A is tangent to the crank circle
    b = math.asin(r2 / r1)
    assert m.time_ratio == pytest.approx((math.pi + 2 * b) / (math.pi - 2 * b), rel=1e-12)


def test_quick_return_time_ratio_from_the_stroke_ends():
    """The slider's extreme positions, found on a fine sweep, split the turn 2.735 : 1."""
    m = linkages.quick_return()
    inputs = np.radians(np.arange(0.0, 360.0, 0.01))
    r5 = m.sweep(inputs)["r5"]
    t_max, t_min = inputs[np.argmax(r5)], inputs[np.argmin(r5)]
    arc = (t_min - t_max) % TWO_PI
    ratio = max(arc, TWO_PI - arc) / min(arc, TWO_PI - arc)
    assert ratio == pytest.approx(2.735, abs=2e-3)


# ---------------------------------------------------------------- six-bar
def six_bar_reference(theta2, side_b, side_d):
    l2, l3, l41, l42, l43, l5 = 1.0, 4.0, 3.0, 3.2, 6.0, 6.5
    o4 = np.array([3.7, -2.0])[:, None]
    a = np.array([l2 * np.cos(theta2), l2 * np.sin(theta2)])
    b = circle_intersection(a, l3, o4 + 0 * a, l41, side_b)
    theta3 = np.arctan2(b[1] - a[1], b[0] - a[0])
    theta4 = np.arctan2(b[1] - o4[1], b[0] - o4[0])
    # beta = 180 deg - angle O4-B-C (law of cosines in the ternary link)
    beta = math.pi - math.acos((l41**2 + l42**2 - l43**2) / (2 * l41 * l42))
    c = b + l42 * np.array([np.cos(theta4 + beta), np.sin(theta4 + beta)])
    np.testing.assert_allclose(np.hypot(*(c - o4)), l43, atol=1e-12)  # the ternary link's third side
    with np.errstate(invalid="ignore"):  # other assemblies may not reach the slider line
        x_d = c[0] + side_d * np.sqrt(l5**2 - (3.0 - c[1]) ** 2)
    theta5 = np.arctan2(c[1] - 3.0, c[0] - x_d)  # rod D -> C
    return theta3, theta4, theta5, x_d


def test_six_bar_closed_form_on_the_documents_assembly():
    m = linkages.six_bar()
    assert m.unknowns == ("theta3", "theta4", "theta5", "x")
    assert m.length_unit == "cm"
    sweep = m.sweep(FULL_TURN)
    # Report 001 shows x_D only as plots; its assembly is the one its solver's fixed guesses
    # pick at theta2 = 0: (theta3, theta4) from (0, 1) rad, (theta5, x) from (1 rad, 1 cm).
    sides = [(sb, sd) for sb in (1.0, -1.0) for sd in (1.0, -1.0)]

    def miss(side):
        t3, t4, t5, x = (float(v[0]) for v in six_bar_reference(np.array([0.0]), *side))
        return (abs(math.remainder(t3, TWO_PI)) + abs(math.remainder(t4 - 1.0, TWO_PI))
                + abs(math.remainder(t5 - 1.0, TWO_PI)) + abs(x - 1.0))

    doc = min(sides, key=lambda s: miss(s) if math.isfinite(miss(s)) else math.inf)
    t3, t4, t5, x = six_bar_reference(FULL_TURN, *doc)
    np.testing.assert_allclose(sweep["x"], x, rtol=0, atol=POS_TOL)
    for name, ref in (("theta3", t3), ("theta4", t4), ("theta5", t5)):
        assert_angle_continuous(sweep[name], ref)
    # README's x_D table (numkin's values, not the report's) is the closed form's, to 5 decimals
    for deg, value in ((0, -1.77881), (90, -3.70858), (180, -5.84838)):
        assert round(float(x[deg]), 5) == value
        assert round(float(sweep["x"][deg]), 5) == value


# ------------------------------------------------------- chained four-bars
CHAIN = dict(f1=7.0, i1=1.94, c1=6.86, o1=2.36, f2=1.25, i2=2.39, c2=1.87, o2=1.26)


def homework_linkage(theta, fixed, inp, coupler, out, guess):
    """r2 e^{i phi} + r3 e^{i psi} - r4 e^{i theta} = r1: B = r2 e^{i phi} on two circles.

    The branch is the circle intersection nearest to the homework's guess at
    the first input, kept along the sweep.
    """
    a = np.array([fixed + inp * np.cos(theta), inp * np.sin(theta)])
    origin = np.zeros_like(a)
    best = None
    for side in (1.0, -1.0):
        b = circle_intersection(origin, out, a, coupler, side)
        phi = np.arctan2(b[1], b[0])
        psi = np.arctan2(a[1] - b[1], a[0] - b[0])
        miss = abs(math.remainder(phi[0] - guess[0], TWO_PI)) + abs(math.remainder(psi[0] - guess[1], TWO_PI))
        if best is None or miss < best[0]:
            best = (miss, phi, psi)
    return best[1], best[2]


def test_chained_four_bars_closed_form():
    m = linkages.chained_four_bars()
    assert m.unknowns == ("phi", "psi", "beta", "gamma")
    assert m.length_unit == "in"
    sweep = m.sweep(FULL_TURN)
    phi, psi = homework_linkage(FULL_TURN, CHAIN["f1"], CHAIN["i1"], CHAIN["c1"], CHAIN["o1"],
                                np.radians([45.0, 60.0]))
    alpha = sweep["phi"] + math.radians(149.0)
    beta, gamma = homework_linkage(alpha, CHAIN["f2"], CHAIN["i2"], CHAIN["c2"], CHAIN["o2"],
                                   np.radians([30.0, 270.0]))
    for name, ref in (("phi", phi), ("psi", psi), ("beta", beta), ("gamma", gamma)):
        assert_angle_continuous(sweep[name], ref)
    # README's positions at theta = 100 deg (numkin's values; homework 003 prints none) are the closed form's
    assert round(math.degrees(phi[100]), 4) == 94.4375
    assert round(math.degrees(beta[100]) % 360.0, 4) == 214.7270
    assert round(math.degrees(sweep["phi"][100]), 4) == 94.4375
    assert round(math.degrees(sweep["beta"][100]) % 360.0, 4) == 214.7270


def test_chained_four_bars_dimensions_by_keyword():
    m = linkages.chained_four_bars(fixed1=7.05, output2=1.3, offset=math.radians(148.0))
    inputs = np.radians(np.arange(0.0, 361.0, 5.0))
    sweep = m.sweep(inputs)
    phi, psi = homework_linkage(inputs, 7.05, CHAIN["i1"], CHAIN["c1"], CHAIN["o1"], sweep.values[:2, 0])
    assert_angle_continuous(sweep["phi"], phi)
    assert_angle_continuous(sweep["psi"], psi)
    beta, gamma = homework_linkage(sweep["phi"] + math.radians(148.0), CHAIN["f2"], CHAIN["i2"], CHAIN["c2"],
                                   1.3, sweep.values[2:, 0])
    assert_angle_continuous(sweep["beta"], beta)
    assert_angle_continuous(sweep["gamma"], gamma)


# --------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "factory, kwargs, name",
    [
        (linkages.four_bar, dict(ground=0, crank=1, coupler=3, rocker=3), "ground"),
        (linkages.four_bar, dict(ground=4, crank=-1, coupler=3, rocker=3), "crank"),
        (linkages.four_bar, dict(ground=4, crank=1, coupler=math.nan, rocker=3), "coupler"),
        (linkages.four_bar, dict(ground=4, crank=1, coupler=3, rocker=math.inf), "rocker"),
        (linkages.four_bar, dict(ground=4, crank=1, coupler=3, rocker="three"), "rocker"),
        (linkages.slider_crank, dict(crank=1, rod=0), "rod"),
        (linkages.slider_crank, dict(crank=-2, rod=5), "crank"),
        (linkages.slider_crank, dict(crank=1, rod=5, offset=math.nan), "offset"),
        (linkages.quick_return, dict(r6=-1), "r6"),
        (linkages.quick_return, dict(r1=0), "r1"),
        (linkages.quick_return, dict(r2=70), "r2"),
        (linkages.six_bar, dict(bc=math.nan), "bc"),
        (linkages.six_bar, dict(rod=0), "rod"),
        (linkages.chained_four_bars, dict(coupler2=0), "coupler2"),
        (linkages.chained_four_bars, dict(offset=math.nan), "offset"),
    ],
)
def test_bad_dimensions_name_the_parameter(factory, kwargs, name):
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        factory(**kwargs)


def test_four_bar_branch_name_checked():
    with pytest.raises(ValueError, match="branch"):
        linkages.four_bar(4, 1, 3, 3, branch="upper")


# ------------------------------------------------------------ benchmark code
def test_benchmark_methods_compute_the_same_positions(capsys):
    """numkin.bench's three ways give the same angles (its timings are not tested)."""
    from numkin import bench

    df = bench.run(repeat=1, textbook_points=3, inner_seconds=0.0)
    assert list(df["method"]) == ["textbook", "numkin", "closed form", "numkin build"]
    assert df["max |diff| [rad]"].max() < 1e-10
    assert set(df.attrs) >= {"speedup_vs_textbook", "slowdown_vs_closed_form", "repeat"}
    report = bench.format_report(df)
    assert "textbook / numkin" in report and "numkin / closed form" in report
    assert re.search(r"\b(targets?|met|pass(ed)?|fail(ed)?)\b", report.lower()) is None
    # the closed form of the benchmark is this file's, and the textbook sweep matches numkin
    sweep = linkages.chained_four_bars().sweep(FULL_TURN)
    cf = bench.closed_form_sweep(FULL_TURN)
    for k in range(4):
        assert_angle_continuous(sweep.values[k], cf[k])
    tb = bench.textbook_sweep(np.arange(0.0, 3.0))  # its Newton may end whole turns away (the homework's 13.73 rad)
    np.testing.assert_allclose(np.angle(np.exp(1j * (tb - sweep.values[:, :3]))), 0.0, atol=1e-10)
    with pytest.raises(ValueError, match="textbook_points"):
        bench.run(repeat=1, textbook_points=0)
    with pytest.raises(ValueError, match="repeat"):
        bench.run(repeat=0)
    assert bench.main(["--repeat", "1", "--textbook-points", "1"]) == 0
    assert "closed form" in capsys.readouterr().out

"""Continuation that never jumps a turn, never refuses a healthy linkage, never hangs.

References are independent of numkin: circle intersections written here (in
float64, and in 50-digit mpmath where ulps matter), and a hand derivation of
the anti-parallelogram's velocity ratio at its change point. Every sweep is
checked for continuity with :func:`assert_continuous`: no neighbour step larger
than the grid step times the largest |dq/dtheta| over the step (from the
closed form, on a fine path) plus a margin, never half a turn.
"""

from __future__ import annotations

import math
import re
import warnings

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, assume, event, example, given, settings
from hypothesis import strategies as st

from numkin import AssemblyError, BranchError, ConvergenceError, Loop, Mechanism, SingularityWarning, linkages
from numkin.newton import TOL_MIN

TWO_PI = 2 * math.pi


# ----------------------------------------------------------------- references
def circle_intersection(theta, r1, r2, r3, r4, side):
    """Four-bar by circle intersection: B at r3 from A = r2 e^{i theta}, at r4 from O4 = (r1, 0).

    ``side`` +1 or -1 picks the intersection left or right of A -> O4.
    Returns (theta3, theta4) in (-pi, pi], NaN where it cannot be assembled.
    """
    ax, ay = r2 * np.cos(theta), r2 * np.sin(theta)
    dx, dy = r1 - ax, -ay
    d = np.hypot(dx, dy)
    ux, uy = dx / d, dy / d
    along = (r3**2 - r4**2 + d**2) / (2 * d)
    with np.errstate(invalid="ignore"):
        h = np.sqrt(r3**2 - along**2)
    bx, by = ax + along * ux - side * h * uy, ay + along * uy + side * h * ux
    return np.arctan2(by - ay, bx - ax), np.arctan2(by, bx - r1)


def slider_closed_form(theta, r, l, e):
    """Slider-crank: sin(theta3) = (e - r sin theta) / l, piston on the +x side (cos theta3 > 0)."""
    t3 = np.arcsin((e - r * np.sin(theta)) / l)
    return t3, r * np.cos(theta) + l * np.cos(t3)


def fine_path(t0, t1, h):
    """Inputs from t0 to t1 with at most h between them (both ends included)."""
    m = max(2, int(math.ceil(abs(t1 - t0) / h)) + 1)
    return np.linspace(t0, t1, m)


def four_bar_on_branch(inputs, dims, side):
    """The branch ``side`` unwrapped along a fine path through ``inputs``; (2, N) and max |dq/dtheta|."""
    t = np.asarray(inputs, dtype=float)
    path = np.concatenate([fine_path(a, b, 1e-3)[:-1] for a, b in zip(t[:-1], t[1:])] + [t[-1:]])
    t3, t4 = circle_intersection(path, *dims, side)
    q = np.unwrap(np.array([t3, t4]), axis=1)
    at = np.searchsorted(path, t) if t[-1] > t[0] else path.size - 1 - np.searchsorted(path[::-1], t)
    rate = np.max(np.abs(np.diff(q, axis=1)) / np.abs(np.diff(path)), axis=1) if path.size > 1 else np.zeros(2)
    return q[:, at], rate


def same_branch_continuous(sweep, ref, rate, atol=1e-9):
    """The sweep equals the reference plus one whole number of turns per unknown, over the whole sweep."""
    for k, name in enumerate(sweep.unknowns):
        got = sweep[name]
        turns = np.round((got[0] - ref[k][0]) / TWO_PI)
        np.testing.assert_allclose(got, ref[k] + TWO_PI * turns, rtol=0, atol=atol, err_msg=name)
    assert_continuous(sweep, rate)


def assert_continuous(sweep, rate=None, margin=1e-6):
    """No neighbour step of an angle over the grid step times the largest rate plus a margin (given the rate: an
    angle may turn half a turn or more between the points of a coarse grid, as theta3 of the triple rocker
    6/6.25/3/3 does, by 180.14°, from 1° to -44°); without it, never half a turn."""
    if sweep.inputs.size < 2:
        return
    dt = np.abs(np.diff(sweep.inputs))
    for k, name in enumerate(sweep.unknowns):
        if name not in sweep.mechanism.angles:
            continue
        step = np.abs(np.diff(sweep[name]))
        if rate is None:
            assert np.all(step < math.pi), f"{name} jumps by {step.max():.3g} rad"
        else:
            bound = dt * rate[k] * 1.05 + margin
            worst = int(np.argmax(step - bound))
            assert step[worst] <= bound[worst], f"{name}: step {step[worst]:.3g} > {bound[worst]:.3g} at {worst}"


def side_of(sweep, dims):
    """The closed-form branch (side) of a four-bar sweep's first point."""
    t3, t4 = (sweep["theta3"][0], sweep["theta4"][0])
    errs = []
    for side in (1.0, -1.0):
        r3, r4 = circle_intersection(np.array([sweep.inputs[0]]), *dims, side)
        errs.append(abs(math.remainder(t3 - r3[0], TWO_PI)) + abs(math.remainder(t4 - r4[0], TWO_PI)))
    return 1.0 if errs[0] < errs[1] else -1.0


def quiet_sweep(mech, inputs, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        return mech.sweep(inputs, **kwargs)


def check_four_bar(dims, inputs, atol=1e-9, **kwargs):
    sweep = quiet_sweep(linkages.four_bar(*dims), inputs, **kwargs)
    ref, rate = four_bar_on_branch(inputs, dims, side_of(sweep, dims))
    same_branch_continuous(sweep, ref, rate, atol)
    return sweep


# ------------------------------------------------------- regression: no turn jumps
DOUBLE_CRANK = (4.85497704104289, 4.756397928996022, 5.713254102884517, 5.792098032458305)


@pytest.mark.parametrize("direction", [1, -1])
def test_double_crank_one_turn_in_5_degree_steps_never_jumps_a_turn(direction):
    inputs = np.radians(274.3 + np.arange(0.0, 361.0, 5.0))[::direction]
    check_four_bar(DOUBLE_CRANK, inputs)


def test_scene_double_crank_from_273_to_633_degrees():
    dims = (4.855, 4.756, 5.713, 5.792)
    sweep = check_four_bar(dims, np.radians(np.arange(273.2, 633.21, 5.0)))
    # a double crank's coupler turns once with the crank: at most one turn over one turn of input
    assert np.ptp(sweep["theta3"]) < 2 * TWO_PI


@pytest.mark.parametrize("max_step", [math.radians(30), TWO_PI, 100.0])
def test_large_max_step_is_as_safe(max_step):
    check_four_bar(DOUBLE_CRANK, np.radians(274.3 + np.arange(0.0, 721.0, 5.0)), max_step=max_step)


def test_healthy_near_square_four_bar_over_two_turns_in_tenth_degrees():
    check_four_bar((72.934, 73.51, 73.322, 73.123), np.radians(np.arange(-3600, 3601) / 10))


@pytest.mark.parametrize("max_step_deg", [0.01, 0.1, 1.0, 5.0, 30.0])
def test_smaller_max_step_is_never_less_safe(max_step_deg):
    check_four_bar((4, 1, 3, 3), np.radians(np.arange(0.0, 361.0, 30.0)), max_step=math.radians(max_step_deg))


def test_long_sweep_of_many_turns_stays_continuous():
    check_four_bar((4, 1, 3, 3), np.radians(np.arange(0.0, 50 * 360.0 + 1, 7.0)), atol=1e-8)


# ------------------------------------------------------------- length scales
def _custom_four_bar(scale):
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    a, b, c, d = sp.symbols("a b c d", positive=True)
    loop = Loop.from_vectors([(b, t2), (c, t3), (-d, t4), (-a, 0)], [t3, t4])
    return Mechanism([loop], t2, {a: 4 * scale, b: 1 * scale, c: 3 * scale, d: 3 * scale},
                     guess={"theta3": 0.5, "theta4": 1.5})


@pytest.mark.parametrize("scale", [1e-150, 1e-100, 1e-12, 1e12, 1e77, 1e100, 1e149])
def test_any_representable_length_scale_solves_alike(scale):
    inputs = np.radians(np.arange(0.0, 361.0, 1.0))
    base = _custom_four_bar(1.0).sweep(inputs)
    scaled = _custom_four_bar(scale).sweep(inputs)
    ref, rate = four_bar_on_branch(inputs, (4, 1, 3, 3), side_of(base, (4, 1, 3, 3)))
    same_branch_continuous(scaled, ref, rate, atol=1e-12)
    np.testing.assert_array_equal(scaled.iterations, base.iterations)
    np.testing.assert_allclose(scaled.cond, base.cond, rtol=1e-9)


def _number_four_bar(scale, tilt=None):
    """The 4:1:3:3 four-bar with its lengths written as numbers (times ``scale``); the ground tilted by the
    parameter ``tilt`` (rad) if given."""
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    tilt_symbol = sp.Symbol("tilt", real=True)
    ground = tilt_symbol if tilt is not None else 0
    loop = Loop.from_vectors([(1 * scale, t2), (3 * scale, t3), (-3 * scale, t4), (-4 * scale, ground)], [t3, t4])
    return Mechanism([loop], t2, {tilt_symbol: tilt} if tilt is not None else None,
                     guess={"theta3": 0.5, "theta4": 1.5})


@pytest.mark.parametrize("scale, tilt", [(1e6, None), (1e-6, None), (1.0, 1e-6), (1e6, 1e-9)])
def test_lengths_written_as_numbers_set_the_default_length_scale(scale, tilt):
    """The characteristic length is the largest vector length, written as a number or as a parameter; a
    parameter in a vector's angle (a ground's tilt) is none: the 4:1:3:3 scaled by 1e6, written in numbers,
    was refused ("did not converge", residual 9.3e-10, against a length scale of 1), and a tilt of 1e-6
    rad taken as the length scale made a regular linkage a "bad guess". The closed form of the tilted
    four-bar is the untilted one's at the crank angle less the tilt, plus the tilt."""
    mech = _number_four_bar(scale, tilt)
    assert mech.length_scale == 4 * scale
    inputs = np.radians(np.arange(0.0, 361.0, 1.0))
    sweep = mech.sweep(inputs)
    t = 0.0 if tilt is None else tilt
    ref, rate = four_bar_on_branch(inputs - t, (4, 1, 3, 3), side_of(sweep, (4, 1, 3, 3)))
    same_branch_continuous(sweep, ref + t, rate, atol=1e-9)
    assert sweep.cond.max() < 10


def test_equation_loops_give_their_lengths_to_the_length_scale():
    """Loops written as equations: a parameter outside every sine and cosine of an equation (L of a slider's
    equation beside a four-bar of numbers, L = 1e9: it was left out and the sweep made no progress) is a
    length; one inside them (a tilt gamma = 1e-8 of the four-bar's equations in numbers: it was the length
    scale, and the sweep failed at 90°) or in an equation between angles alone (phi of t5 = t4 + phi,
    n of t5 = n theta2) is none."""
    t2, t3, t4, x, length, gamma = sp.symbols("theta2 theta3 theta4 x L gamma")
    inputs = np.radians(np.arange(0.0, 361.0))
    four_bar = Loop.from_vectors([(1, t2), (3, t3), (-3, t4), (-4, 0)], [t3, t4])
    slider = Loop([x - length * sp.cos(t4) - length], [x])
    mech = Mechanism([four_bar, slider], t2, {length: 1e9}, guess={"theta3": 0.5, "theta4": 1.5, "x": 2e9})
    assert mech.length_scale == 1e9
    sweep = mech.sweep(inputs)
    np.testing.assert_allclose(sweep["x"], 1e9 * (np.cos(sweep["theta4"]) + 1), rtol=1e-14, atol=1e-5)
    equations = Loop([sp.cos(t2) + 3 * sp.cos(t3) - 3 * sp.cos(t4 + gamma) - 4,
                      sp.sin(t2) + 3 * sp.sin(t3) - 3 * sp.sin(t4 + gamma)], [t3, t4])
    tilted = Mechanism([equations], t2, {gamma: 1e-8}, guess={"theta3": 0.5, "theta4": 1.5})
    assert tilted.length_scale == 1.0  # (no length is a parameter: the default)
    t5, phi, n = sp.symbols("theta5 phi n")
    small = Loop.from_vectors([(0.01, t2), (0.03, t3), (-0.03, t4), (-0.04, 0)], [t3, t4])
    for angles, values in ((Loop([t5 - t4 - phi], [t5]), {phi: 1.5}), (Loop([t5 - n * t2], [t5]), {n: 100.0})):
        assert Mechanism([small, angles], t2, values, guess={"theta3": 0.5, "theta4": 1.5, "theta5": 0.0}
                         ).length_scale == 0.04
    sweep = tilted.sweep(inputs)
    ref, _ = four_bar_on_branch(inputs, (4, 1, 3, 3), side_of(sweep, (4, 1, 3, 3)))
    np.testing.assert_allclose(sweep["theta4"] + 1e-8, ref[1] + TWO_PI * np.round((sweep["theta4"][0] - ref[1][0]) / TWO_PI),
                               atol=1e-9)


def test_a_slider_offset_far_smaller_than_the_crank_is_no_length_scale():
    """An offset slider-crank 80/200 with the offset e = 1e-9 a parameter: the length scale is the rod,
    200 (it was e, and the regular linkage was called a toggle at 5.73°); the piston at 0.1 rad from
    its closed form."""
    t2, t3, x = sp.symbols("theta2 theta3 x")
    e = sp.Symbol("e", real=True)
    loop = Loop.from_vectors([(80, t2), (200, t3), (-x, 0), (-e, sp.pi / 2)], [t3, x])
    mech = Mechanism([loop], t2, {e: 1e-9}, guess={"theta3": -0.05, "x": 283.0}, guess_input=0.1)
    assert mech.length_scale == 200.0
    inputs = np.linspace(0.1, 0.1 + 2 * np.pi, 73)
    sweep = mech.sweep(inputs)
    piston = 80 * np.cos(inputs) + np.sqrt(200**2 - (80 * np.sin(inputs) - 1e-9) ** 2)
    np.testing.assert_allclose(sweep["x"], piston, rtol=0, atol=1e-10)
    assert sweep.cond.max() < 10


@pytest.mark.parametrize("scale", [1e-158, 1e-165, 1e-300, 1e154, 1e300])
def test_length_scale_outside_the_range_is_refused_up_front(scale):
    with pytest.raises(ValueError, match=r"1e-150 to 1e\+150"):
        _custom_four_bar(scale)


# ------------------------------------------------------------- diagnostics
def test_bad_guess_is_called_a_bad_guess():
    with pytest.raises(AssemblyError) as err:
        linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0.0, 361.0)), guess=(100, 100))
    assert err.value.cause == "bad guess"
    assert "guess" in str(err.value) and err.value.input_value == 0.0
    assert err.value.loop == "O2-A-B-O4"


def test_dependent_equations_are_named():
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    f = sp.cos(t2) + 3 * sp.cos(t3) - 3 * sp.cos(t4) - 4
    mech = Mechanism([Loop([f, 2 * f], [t3, t4], name="twice")], t2, guess={"theta3": 0.5, "theta4": 1.5})
    with pytest.raises(AssemblyError, match="dependent") as err:
        mech.sweep(np.radians([0.0, 1.0]))
    assert err.value.cause == "dependent equations" and err.value.loop == "twice"


@pytest.mark.parametrize("tol", [1e-20, 1e-16, 0.5 * TOL_MIN])
def test_tolerance_below_the_round_off_floor(tol):
    m = linkages.four_bar(4, 1, 3, 3)
    with pytest.raises(ValueError, match="round-off floor"):
        m.sweep(np.radians([0.0, 1.0]), tol=tol)
    with pytest.raises(ValueError, match="round-off floor"):
        m.solve(0.0, tol=tol)


def test_tolerance_at_the_floor_converges():
    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0.0, 361.0)), tol=TOL_MIN)
    ref, rate = four_bar_on_branch(sweep.inputs, (4, 1, 3, 3), side_of(sweep, (4, 1, 3, 3)))
    same_branch_continuous(sweep, ref, rate, atol=1e-14)


def test_negative_length_of_a_custom_mechanism_is_a_value_error():
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    for assumptions in ({"positive": True}, {}):
        a, b, c, d = sp.symbols("a b c d", **assumptions)
        loop = Loop.from_vectors([(b, t2), (c, t3), (-d, t4), (-a, 0)], [t3, t4])
        with pytest.raises(ValueError, match=r"\bb\b.*-1|-1.*\bb\b"):
            Mechanism([loop], t2, {a: 4, b: -1, c: 3, d: 3})


def test_signed_offset_declared_real_may_be_negative():
    sweep = linkages.slider_crank(80, 200, -30).sweep(np.radians(np.arange(0.0, 361.0, 10.0)))
    t3, x = slider_closed_form(sweep.inputs, 80, 200, -30)
    np.testing.assert_allclose(sweep["theta3"], t3, atol=1e-12)
    np.testing.assert_allclose(sweep["x"], x, atol=1e-10)


def test_change_point_raise_suggests_report_mode():
    with pytest.raises(BranchError) as err:
        linkages.four_bar(5, 2, 5, 2).sweep(np.radians(np.arange(10.0, 351.0)))
    assert err.value.kind == "change point" and "on_singular='report'" in str(err.value)
    assert math.degrees(err.value.input_value) == pytest.approx(180.0, abs=1e-3)


def test_errors_carry_their_facts():
    with pytest.raises(AssemblyError) as err:
        linkages.four_bar(4, 1, 3, 3).sweep(np.radians([0.0, 1.0]), guess=(100, 100))
    e = err.value
    assert (e.input_value, e.loop, e.cause) == (0.0, "O2-A-B-O4", "bad guess")
    assert e.iterations is not None and e.message == str(e)


# ------------------------------------------------------------- change points
def test_anti_parallelogram_keeps_the_crossed_branch_and_names_its_tangent():
    # Hand derivation: an anti-parallelogram (ground = coupler = a, crank = rocker = b) folded at
    # theta2 = pi has dtheta4/dtheta2 = -(a - b)/(a + b); the velocity loop there,
    # -b w2 + a w3 + b w4 = 0, gives dtheta3/dtheta2 = (b - b w4) / a.
    a, b = 5.0, 2.0
    w4 = -(a - b) / (a + b)
    w3 = (b - b * w4) / a
    mech = linkages.four_bar(a, b, a, b, branch="crossed")
    with pytest.warns(SingularityWarning) as caught:  # the change point, and the digits lost next to it
        sweep = mech.sweep(np.radians(np.arange(1.0, 360.0)), on_singular="report")
    messages = [str(w.message) for w in caught]
    assert any(re.search(r"kept .*dtheta4/dtheta2 = -0\.4286", m) for m in messages), messages
    assert any("near a singular position" in m for m in messages), messages
    (event,) = [e for e in sweep.events if e.kind == "change point"]
    assert math.degrees(event.input_value) == pytest.approx(180.0, abs=1e-4)
    assert event.tangent_continuous is True
    np.testing.assert_allclose(event.tangent, [w3, w4], atol=1e-5)
    np.testing.assert_allclose(event.tangent_before, [w3, w4], atol=1e-4)
    np.testing.assert_allclose(event.tangent_after, [w3, w4], atol=1e-4)
    assert "branch" in event.branch
    # the sweep stays on the anti-parallelogram (the crossed circle intersection) on both sides
    dims = (a, b, a, b)
    for part in (slice(0, 179), slice(180, None)):
        inputs = sweep.inputs[part]
        sub = sweep.values[:, part]
        side = side_of(type(sweep)(mech, inputs, sub, sweep.iterations[part], sweep.residual[part],
                                   sweep.cond[part]), dims)
        ref, _ = four_bar_on_branch(inputs, dims, side)
        for k in range(2):
            turns = np.round((sub[k][0] - ref[k][0]) / TWO_PI)
            np.testing.assert_allclose(sub[k], ref[k] + TWO_PI * turns, atol=1e-7)
        # anti-parallelogram: theta4 moves against theta2 (never the parallelogram's theta4 = theta2)
        assert np.all(np.abs(np.diff(sub[1]) - np.diff(inputs)) > 1e-3)
    assert_continuous(sweep)


# ------------------------------------------------------------- the first point
def _mp_circles(p, r_near, r_far, near):
    """B with |B| = r_near and |P - B| = r_far, the one nearest the angle ``near`` (50 digits)."""
    d = mp.sqrt(p.real**2 + p.imag**2)
    u = p / d
    along = (r_near**2 - r_far**2 + d**2) / (2 * d)
    h = mp.sqrt(r_near**2 - along**2)
    cands = [along * u + s * h * 1j * u for s in (1, -1)]
    best = min(cands, key=lambda b: abs(mp.atan2(mp.sin(mp.arg(b) - near), mp.cos(mp.arg(b) - near))))
    return mp.arg(best), mp.arg(p - best)


def test_first_point_from_the_homework_guess_is_polished_to_ulps():
    mech = linkages.chained_four_bars()
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0)))
    mp.mp.dps = 50
    f1, i1, o1, c1 = mp.mpf(7.0), mp.mpf("1.94"), mp.mpf("2.36"), mp.mpf("6.86")
    f2, i2, c2, o2 = mp.mpf("1.25"), mp.mpf("2.39"), mp.mpf("1.87"), mp.mpf("1.26")
    off = mp.radians(149)
    errors = []
    for k in (0, 1, 100, 200, 360):
        th = mp.mpf(float(sweep.inputs[k]))
        phi, psi = _mp_circles(f1 + i1 * mp.expj(th), o1, c1, mp.mpf(float(sweep["phi"][k])))
        alpha = phi + off
        beta, gamma = _mp_circles(f2 + i2 * mp.expj(alpha), o2, c2, mp.mpf(float(sweep["beta"][k])))
        ref = [phi, psi, beta, gamma]
        err = max(abs(mp.atan2(mp.sin(mp.mpf(float(v)) - r), mp.cos(mp.mpf(float(v)) - r)))
                  for v, r in zip(sweep.values[:, k], ref))
        errors.append(float(err))
    assert errors[0] <= 4e-15, errors
    assert errors[0] <= 2 * max(max(errors[1:]), 2e-15), errors
    # on the homework's branch and turn: the guess is phi 45°, psi 60°, beta 30°, gamma 270° at theta = 0
    guess = np.radians([45.0, 60.0, 30.0, 270.0])
    assert np.all(np.abs(sweep.values[:, 0] - guess) < math.pi)


# ------------------------------------------------------------- progress
def test_progress_bar_reaches_the_end(capsys):
    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0.0, 361.0)), progress=True)
    assert sweep.inputs.size == 361
    err = capsys.readouterr().err
    assert "12/12" in err  # 360° in nodes 30° apart


# ------------------------------------------------------------- properties
lengths = st.floats(min_value=0.5, max_value=10.0, allow_nan=False)


@st.composite
def grids(draw):
    start = draw(st.floats(min_value=-720.0, max_value=720.0))
    step = draw(st.sampled_from([0.1, 0.7, 1.0, 5.0, 12.0, 30.0, 45.0]))
    turns = draw(st.floats(min_value=0.05, max_value=2.5))
    direction = draw(st.sampled_from([1.0, -1.0]))
    n = max(2, min(3000, int(turns * 360.0 / step) + 1))
    return np.radians(start + direction * step * np.arange(n))


@st.composite
def four_bars(draw):
    """Any four-bar (mostly not assemblable over a turn), or a Grashof one with the crank shortest
    (it turns fully: a crank-rocker or, with the ground shortest too, a double crank)."""
    if draw(st.booleans()):
        return draw(st.tuples(lengths, lengths, lengths, lengths))
    a, c, d = draw(st.tuples(lengths, lengths, lengths))
    longest = max(a, c, d)
    room = min(a, c, d, a + c + d - 2 * longest)  # Grashof with the crank b: b + longest <= the other two
    assume(room > 0.2)
    b = draw(st.floats(min_value=0.1, max_value=0.95 * room))
    return (a, b, c, d)


max_steps = st.one_of(st.none(), st.sampled_from([0.01, 0.1, 0.5, 1.0, TWO_PI, 100.0]))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(dims=four_bars(), inputs=grids(), max_step=max_steps,
       branch=st.sampled_from(["open", "crossed"]))
@example(dims=(6.0, 6.25, 3.0, 3.0), inputs=np.radians([1.0, -44.0]), max_step=None, branch="open")  # theta3: 180.14°
def test_four_bar_sweeps_are_continuous_and_right_or_refused_for_a_reason(dims, inputs, max_step, branch):
    assume(abs(dims[0] - dims[1]) > 1e-6)  # crank as long as the ground: the crank pin can sit on the rocker pivot
    mech = linkages.four_bar(*dims, branch=branch)
    # where the closed form says the path is assemblable and away from folding, the sweep must succeed
    path = np.concatenate([fine_path(a, b, 2e-3) for a, b in zip(inputs[:-1], inputs[1:])])
    r1, r2, r3, r4 = dims
    d = np.hypot(r1 - r2 * np.cos(path), r2 * np.sin(path))
    slack = np.minimum(r3 + r4 - d, d - abs(r3 - r4)) / max(dims)
    try:
        sweep = quiet_sweep(mech, inputs, max_step=max_step)
    except AssemblyError:
        event("cannot be assembled")
        assert slack.min() < 0  # some input cannot be assembled
        return
    except (BranchError, ConvergenceError):
        event("singular position on the path")
        assert slack.min() < 1e-3  # a toggle or change point is on (or next to) the path
        return
    assert slack.min() > -1e-9
    assume(slack.min() > 1e-3)  # compare with the closed form away from folded positions
    event("compared with the closed form")
    ref, rate = four_bar_on_branch(inputs, dims, side_of(sweep, dims))
    same_branch_continuous(sweep, ref, rate, atol=1e-8)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(r=lengths, rod=st.floats(min_value=0.2, max_value=3.0), e=st.floats(min_value=-0.9, max_value=0.9),
       inputs=grids(), max_step=max_steps)
def test_slider_crank_sweeps_match_the_closed_form_or_are_refused(r, rod, e, inputs, max_step):
    l, off = rod * r, e * r
    mech = linkages.slider_crank(r, l, off)
    s = (off - r * np.sin(inputs)) / l
    try:
        sweep = quiet_sweep(mech, inputs, max_step=max_step)
    except AssemblyError:
        event("cannot be assembled")
        assert np.max(np.abs(s)) > 1 - 1e-9
        return
    except (BranchError, ConvergenceError):
        path = np.concatenate([fine_path(a, b, 2e-3) for a, b in zip(inputs[:-1], inputs[1:])])
        assert np.max(np.abs((off - r * np.sin(path)) / l)) > 1 - 1e-3  # the rod reaches the line only just
        return
    path_s = np.abs((off - r * np.sin(fine_path(inputs[0], inputs[-1], 2e-3))) / l)
    assume(path_s.max() < 1 - 1e-3)
    event("compared with the closed form")
    t3, x = slider_closed_form(sweep.inputs, r, l, off)
    np.testing.assert_allclose(sweep["theta3"], t3, rtol=0, atol=1e-8)
    np.testing.assert_allclose(sweep["x"], x, rtol=0, atol=1e-8 * max(r, l))
    assert_continuous(sweep)


def test_guess_in_degrees_is_warned_about():
    m = linkages.four_bar(4, 1, 3, 3)
    with pytest.warns(UserWarning, match="in degrees"):
        sweep = m.sweep(np.radians(np.arange(0.0, 31.0)), guess=(30.0, 120.0))
    # still the guess's turn, on a continuous branch
    ref, rate = four_bar_on_branch(sweep.inputs, (4, 1, 3, 3), side_of(sweep, (4, 1, 3, 3)))
    same_branch_continuous(sweep, ref, rate)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m.sweep(np.radians(np.arange(0.0, 31.0)), guess=(0.5, 2.1))  # a guess in rad: no warning


@pytest.mark.parametrize("h", [1e-10, 1e-12, 1e-14])
def test_a_sweep_over_a_tiny_span_is_solved_not_taken_for_a_toggle(h):
    # eleven inputs h apart at 30 deg: the whole sweep spans 10 h, below 1e-9 rad; the march's
    # smallest step is relative to the span, and the slider-crank is nowhere near a limit position there
    inputs = math.radians(30.0) + h * np.arange(11)
    sweep = linkages.slider_crank(80, 200, -30).sweep(inputs)
    t3, x = slider_closed_form(inputs, 80, 200, -30)
    np.testing.assert_allclose(sweep["theta3"], t3, atol=1e-14)
    np.testing.assert_allclose(sweep["x"], x, atol=1e-11)
    assert not sweep.events

"""Tests for Loop, Mechanism and the compiled functions, on linkages written by hand."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import sympy as sp

from numkin import AssemblyError, InputError, Loop, Mechanism

TH, T3, X, T4, T5, XS = sp.symbols("theta theta3 x theta4 theta5 xs", real=True)
R, L, E = sp.symbols("r l e", positive=True)
FULL_TURN = np.radians(np.arange(0.0, 361.0))


def slider_loop():
    return Loop.from_vectors([(R, TH), (L, T3), (-X, 0), (-E, sp.pi / 2)], [T3, X], name="crank-rod")


def slider_mechanism(r=1.0, rod=3.0, e=0.4, **kw):
    return Mechanism([slider_loop()], TH, {R: r, L: rod, E: e}, name="slider", **kw)


def slider_closed_form(theta, r, rod, e):
    s = r * np.sin(theta) - e
    root = np.sqrt(rod**2 - s**2)
    return np.arcsin(-s / rod), r * np.cos(theta) + root


# ------------------------------------------------------------------- Loop
def test_from_vectors_residuals_are_the_complex_sum():
    loop = slider_loop()
    assert [str(u) for u in loop.unknowns] == ["theta3", "x"]
    assert {str(a) for a in loop.angles} == {"theta3"}
    assert {str(s) for s in loop.length_symbols} == {"r", "l", "e"}
    rng = np.random.default_rng(1)
    for _ in range(5):
        th, t3, x, r, rod, e = rng.uniform(-3, 3, 6)
        z = r * np.exp(1j * th) + rod * np.exp(1j * t3) - x - 1j * e
        subs = {TH: th, T3: t3, X: x, R: r, L: rod, E: e}
        re, im = (float(res.subs(subs)) for res in loop.residuals)
        assert re == pytest.approx(z.real, abs=1e-12) and im == pytest.approx(z.imag, abs=1e-12)


def test_loop_from_raw_residuals_infers_angles():
    loop = Loop([R * sp.cos(TH) + L * sp.cos(T3) - X, R * sp.sin(TH) + L * sp.sin(T3) - E], ["theta3", "x"])
    assert {str(a) for a in loop.angles} == {"theta3"}
    assert loop.name == "theta3-x"


@pytest.mark.parametrize(
    "make, fragment",
    [
        (lambda: Loop([sp.cos(T3) - 1], [T3, X], name="L1"), "1 equations for 2 unknowns"),
        (lambda: Loop([sp.cos(T3) - 1, T3 - 1], [T3, X], name="L1"), "x appear in no equation"),
        (lambda: Loop([sp.cos(T3) - 1, T3 - 1], [T3, T3], name="L1"), "twice"),
        (lambda: Loop([], [], name="L1"), "no unknowns"),
        (lambda: Loop([sp.cos(T3) - X, X - 1], ["theta 3", "x"]), "not a symbol name"),
        (lambda: Loop([sp.cos(T3) - X, X - 1], [T3, X], angles=["theta4"]), "theta4"),
        (lambda: Loop.from_vectors([(1, T3)], [T3], name="L1"), "at least two vectors"),
        (lambda: Loop.from_vectors([(1, T3), 3], [T3], name="L1"), "vector 1"),
    ],
)
def test_loop_errors(make, fragment):
    with pytest.raises(ValueError, match=fragment):
        make()


# -------------------------------------------------------------- Mechanism
def test_mechanism_attributes():
    m = slider_mechanism(r=1.0, rod=3.0, e=0.4)
    assert m.unknowns == ("theta3", "x")
    assert m.angles == ("theta3",)
    assert str(m.input_symbol) == "theta"
    assert m.length_scale == 3.0  # the largest vector length
    np.testing.assert_array_equal(m.xscale, [1.0, 3.0])
    assert m.loop_slices == [slice(0, 2)]
    np.testing.assert_array_equal(m.parameter_values, [1.0, 3.0, 0.4])
    assert m.length_unit == "mm"
    assert "slider" in repr(m)


def test_hand_written_slider_crank_matches_closed_form():
    r, rod, e = 1.0, 3.0, 0.4
    m = slider_mechanism(r, rod, e, guess={"theta3": 0.0, "x": 3.0}, guess_input=0.0)
    sweep = m.sweep(FULL_TURN)
    t3, x = slider_closed_form(FULL_TURN, r, rod, e)
    np.testing.assert_allclose(sweep["x"], x, rtol=0, atol=1e-10 * rod)
    np.testing.assert_allclose(sweep["theta3"], t3, rtol=0, atol=1e-10)
    res = m.solve(math.radians(40), guess=[0.0, 3.0])
    assert res.converged
    np.testing.assert_allclose(res.x, [v[40] for v in (t3, x)], atol=1e-10 * rod)


def test_sweep_without_any_guess_says_so():
    m = slider_mechanism()
    with pytest.raises(ValueError, match="guess"):
        m.sweep(FULL_TURN)


def test_two_loops_later_loop_uses_earlier_unknowns():
    """A four-bar whose rocker drives a slider through a rod: loop 2 uses theta4 of loop 1."""
    r1, r2, r3, r4, rod, h = 4.0, 1.0, 3.0, 3.0, 5.0, 2.0
    A1, A2, A3, A4, LR, H = sp.symbols("a1 a2 a3 a4 lr h", positive=True)
    t2 = sp.Symbol("theta2", real=True)
    loop1 = Loop.from_vectors([(A2, t2), (A3, T3), (-A4, T4), (-A1, 0)], [T3, T4], name="four-bar")
    loop2 = Loop.from_vectors([(A1, 0), (A4, T4), (LR, T5), (-XS, 0), (-H, sp.pi / 2)], [T5, XS], name="rod")
    m = Mechanism(
        [loop1, loop2], t2, {A1: r1, A2: r2, A3: r3, A4: r4, LR: rod, H: h},
        guess={"theta3": 0.5, "theta4": 2.0, "theta5": -0.3, "xs": 6.0}, guess_input=0.0,
        points={"B": (A1 + A4 * sp.cos(T4), A4 * sp.sin(T4)), "S": (XS, H)}, links=[("B", "S")],
    )
    assert m.unknowns == ("theta3", "theta4", "theta5", "xs")
    assert m.loop_slices == [slice(0, 2), slice(2, 4)]
    sweep = m.sweep(FULL_TURN)
    # closed form: B by circle intersection (open branch), slider to the right of B
    ax, ay = r2 * np.cos(FULL_TURN), r2 * np.sin(FULL_TURN)
    dx, dy = r1 - ax, -ay
    d = np.hypot(dx, dy)
    along = (r3**2 - r4**2 + d**2) / (2 * d)
    hh = np.sqrt(r3**2 - along**2)
    bx = ax + along * dx / d - hh * dy / d
    by = ay + along * dy / d + hh * dx / d
    xs = bx + np.sqrt(rod**2 - (h - by) ** 2)
    np.testing.assert_allclose(sweep["xs"], xs, rtol=0, atol=1e-10 * rod)
    np.testing.assert_allclose(np.cos(sweep["theta4"]), (bx - r1) / r4, atol=1e-10)
    pts = sweep.points()
    np.testing.assert_allclose(pts["B"], [bx, by], atol=1e-10 * rod)
    np.testing.assert_allclose(np.hypot(*(pts["S"] - pts["B"])), rod, atol=1e-11 * rod)
    # block lower-triangular Jacobian: loop 1 does not depend on loop 2's unknowns
    jac = m.compiled.J(sweep.values, sweep.inputs, m.parameter_values)
    assert np.all(jac[:, 0:2, 2:4] == 0)
    res = m.loop_residuals(sweep.values, sweep.inputs)
    assert set(res) == {"four-bar", "rod"}
    assert max(v.max() for v in res.values()) <= 1e-12  # the stopping tolerance
    conds = m.loop_conditions(sweep.values, sweep.inputs)
    assert set(conds) == {"four-bar", "rod"} and all(np.all(c >= 1) for c in conds.values())
    orient = m.loop_orientations(sweep.values, sweep.inputs)
    assert orient.shape == (2, 361)
    assert np.all(orient == orient[:, :1])


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        (dict(parameters={R: 1.0, L: 3.0}), "e"),  # e has no value
        (dict(parameters={R: 1.0, L: 3.0, E: math.nan}), "e"),
        (dict(parameters={R: 1.0, L: "long", E: 0.0}), "l"),
        (dict(parameters={R: 1.0, L: 3.0, E: 0.0, X: 2.0}), "x"),  # an unknown given a value
        (dict(parameters={R: 1.0, L: 3.0, E: 0.0}, links=[("O", "Q")]), "Q"),
        (dict(parameters={R: 1.0, L: 3.0, E: 0.0}, length_scale=-1.0), "length_scale"),
    ],
)
def test_mechanism_errors_name_the_culprit(kwargs, fragment):
    params = kwargs.pop("parameters")
    if "links" in kwargs:
        kwargs["points"] = {"O": (0, 0)}
    with pytest.raises(ValueError, match=rf"\b{fragment}\b"):
        Mechanism([slider_loop()], TH, params, **kwargs)


def test_mechanism_needs_loops():
    with pytest.raises(ValueError, match="loops"):
        Mechanism([], TH, {})


def test_assembly_check_hook():
    m = slider_mechanism(assembly_check=lambda t: "never" if np.any(t > 1) else None, guess=[0.0, 3.0])
    with pytest.raises(AssemblyError, match="never"):
        m.sweep(FULL_TURN)
    assert m.sweep(np.linspace(0.0, 1.0, 5)).values.shape == (2, 5)


# ------------------------------------------------------- compiled functions
def test_compiled_jacobian_tangent_and_second_derivative_against_closed_form():
    r, rod, e = 1.0, 3.0, 0.4
    m = slider_mechanism(r, rod, e)
    c = m.compiled
    p = m.parameter_values
    theta = np.radians(np.arange(0.0, 360.0, 7.0))
    q = np.array(slider_closed_form(theta, r, rod, e))
    np.testing.assert_allclose(c.F(q, theta, p), 0.0, atol=1e-14)
    # Jacobian by complex step through F (F accepts complex arrays)
    h = 1e-30
    for j in range(2):
        dq = np.zeros_like(q, dtype=complex)
        dq[j] = 1j * h
        col = c.F(q + dq, theta, p).imag / h
        np.testing.assert_allclose(c.J(q, theta, p)[:, :, j], col.T, rtol=1e-14, atol=1e-15)
    # dq/dtheta and d2q/dtheta2 from differentiating the closed form with sympy, here
    th = sp.Symbol("th")
    s = r * sp.sin(th) - e
    x_expr = r * sp.cos(th) + sp.sqrt(rod**2 - s**2)
    t3_expr = sp.asin(-s / rod)
    d1 = sp.lambdify(th, [sp.diff(t3_expr, th), sp.diff(x_expr, th)])
    d2 = sp.lambdify(th, [sp.diff(t3_expr, th, 2), sp.diff(x_expr, th, 2)])
    dq = c.tangent(q, theta, p)
    np.testing.assert_allclose(dq, np.array(d1(theta)), rtol=0, atol=1e-13)
    np.testing.assert_allclose(c.second_derivative(q, dq, theta, p), np.array(d2(theta)), rtol=0, atol=1e-12)
    np.testing.assert_allclose(c.F_t(q, theta, p), [-r * np.sin(theta), r * np.cos(theta)], atol=1e-15)


def test_point_function_and_complex_inputs():
    m = slider_mechanism(points={"A": (R * sp.cos(TH), R * sp.sin(TH)), "P": (X, E)})
    theta = np.array([0.0, 1.0])
    q = np.array(slider_closed_form(theta, 1.0, 3.0, 0.4))
    pts = m.point_coordinates(q, theta)
    np.testing.assert_allclose(pts["A"], [np.cos(theta), np.sin(theta)])
    np.testing.assert_allclose(pts["P"], [q[1], [0.4, 0.4]])
    out = m.compiled.F(q.astype(complex), theta + 1e-20j, m.parameter_values)
    assert np.iscomplexobj(out)
    np.testing.assert_allclose(out.imag / 1e-20, m.compiled.F_t(q, theta, m.parameter_values), atol=1e-14)


def test_loops_of_three_and_one_unknowns():
    """Blocks other than 2 x 2: a three-equation loop, then a one-equation loop using its unknowns."""
    y, z = sp.symbols("y z", real=True)
    r, rod, e = 1.0, 3.0, 0.4
    loop3 = Loop(
        [R * sp.cos(TH) + L * sp.cos(T3) - X, R * sp.sin(TH) + L * sp.sin(T3) - E, y - X**2 / 2],
        [T3, X, y], name="three",
    )
    loop1 = Loop([z**3 + z - y], [z], name="one")
    m = Mechanism([loop3, loop1], TH, {R: r, L: rod, E: e}, guess=[0.0, 3.0, 4.5, 1.5], guess_input=0.0)
    sweep = m.sweep(FULL_TURN)
    t3, x = slider_closed_form(FULL_TURN, r, rod, e)
    np.testing.assert_allclose(sweep["x"], x, rtol=0, atol=1e-10 * rod)
    np.testing.assert_allclose(sweep["y"], x**2 / 2, rtol=0, atol=1e-10 * rod**2)
    zz = sweep["z"]
    np.testing.assert_allclose(zz**3 + zz, x**2 / 2, rtol=0, atol=1e-9)
    conds = m.loop_conditions(sweep.values, sweep.inputs)
    assert np.all(conds["one"] == 1.0) and np.all(conds["three"] >= 1.0)
    for jacobian in ("forward", "central"):
        fd = m.sweep(FULL_TURN, jacobian=jacobian)
        np.testing.assert_allclose(fd.values, sweep.values, rtol=0, atol=1e-9)


def test_functions_outside_the_math_module():
    """A residual with a function the math module lacks (``re``) still sweeps: numpy evaluates it."""
    c = sp.Symbol("c")  # not declared real: re(c) stays
    m = Mechanism(
        [Loop([X - 2 - sp.re(c) * sp.sin(TH) / 4], [X], name="re")], TH, {c: 1.0},
        guess=[2.0], guess_input=0.0,
    )
    sweep = m.sweep(np.linspace(0.0, 3.0, 31))
    np.testing.assert_allclose(sweep["x"], 2 + np.sin(np.linspace(0.0, 3.0, 31)) / 4, atol=1e-12)


def test_polish_reaches_the_circle_intersection_to_round_off():
    # closed form of the 4/1/3/3 four-bar at 90°: A = (0, 1), |AB| = 3, |O4 B| = 3, O4 = (4, 0)
    from numkin import ConvergenceError, linkages

    m = linkages.four_bar(4, 1, 3, 3)
    ax, ay, ox = 0.0, 1.0, 4.0
    dx, dy = ox - ax, -ay
    dist = math.hypot(dx, dy)
    h = math.sqrt(9.0 - (dist / 2) ** 2)
    bx, by = ax + dx / 2 - h * dy / dist, ay + dy / 2 + h * dx / dist
    exact = [math.atan2(by - ay, bx - ax), math.atan2(by, bx - ox)]
    x = m.polish(np.array([[0.56], [2.08]]), np.radians([90.0]))
    np.testing.assert_allclose(x[:, 0], exact, rtol=0, atol=4e-15)
    with pytest.raises(ConvergenceError, match="round-off"):
        m.polish(np.array([[0.5], [0.5]]), np.radians([90.0]), maxiter=1)


def test_names_given_as_strings_are_the_equations_own_symbols():
    """README's loops use plain sp.symbols (no assumptions); the unknowns, the input and the parameters
    may be named by strings all the same (theta4 against the four-bar's circle intersection)."""
    import math

    import numpy as np
    import sympy as sp

    from numkin import Loop, Mechanism

    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], ["theta3", "theta4"], name="O2-A-B-O4")
    assert loop.unknowns == [t3, t4]
    mech = Mechanism([loop], "theta2", {"r1": 4, "r2": 1, "r3": 3, "r4": 3}, guess={"theta3": 0.5, "theta4": 2.0})
    assert mech.input_symbol is t2 and set(mech.parameters) == {r1, r2, r3, r4}
    # at theta2 = 90 deg: A = (0, 1), O4 = (4, 0); B at 3 from both, above the line A-O4
    ax, ay, ox = 0.0, 1.0, 4.0
    d = math.hypot(ox - ax, -ay)
    along = d / 2  # equal coupler and rocker: B over the middle of A-O4
    h = math.sqrt(9.0 - along**2)
    bx, by = ax + along * (ox - ax) / d + h * ay / d, ay + along * (-ay) / d + h * (ox - ax) / d
    assert mech.sweep(np.radians([0.0, 90.0]))["theta4"][1] == pytest.approx(math.atan2(by, bx - ox), abs=1e-12)


def _circle_intersections(p, r, q, s):
    """The two points at distance r from p and s from q (complex numbers), each side of the line p-q."""
    d = abs(q - p)
    a = (r * r - s * s + d * d) / (2 * d)
    h = math.sqrt(r * r - a * a)
    m = p + a * (q - p) / d
    off = 1j * h * (q - p) / d
    return m + off, m - off


def test_a_poor_guess_for_one_loop_leaves_the_next_on_its_own_guess_branch():
    """A Watt II six-bar: loop 2 hangs on loop 1's rocker. Loop 1's guess 2.5 rad off, loop 2's exact: the first
    point is solved loop by loop, so loop 2 stays on the branch its guess is on (circle intersections), where Newton
    on both loops at once carried it onto the other."""
    t2, t3, t4, t5, t6 = sp.symbols("theta2 theta3 theta4 theta5 theta6")
    loop1 = Loop.from_vectors([(1, t2), (3.5, t3), (-3, t4), (-4, 0)], [t3, t4], name="O2ABO4")
    loop2 = Loop.from_vectors([(4, 0), (2.5, t4 + 0.6), (3.2, t5), (-2.8, t6), (-7, 0), (-1.5, sp.pi / 2)], [t5, t6],
                              name="O4CDO6")
    a, o4, o6 = 1.0 + 0j, 4.0 + 0j, 7.0 + 1.5j  # at theta2 = 0
    b = _circle_intersections(a, 3.5, o4, 3.0)[0]  # the open branch, B above the ground
    th3, th4 = np.angle(b - a), np.angle(b - o4)
    c = o4 + 2.5 * np.exp(1j * (th4 + 0.6))
    for d in _circle_intersections(c, 3.2, o6, 2.8):
        exact = np.array([th3, th4, np.angle(d - c), np.angle(d - o6)])
        sweep = Mechanism([loop1, loop2], t2, {}).sweep(np.radians([0.0, 5.0]), guess=exact + [2.5, -2.5, 0.0, 0.0])
        np.testing.assert_allclose(sweep.values[:, 0], exact, atol=1e-12)


def test_an_angle_another_loop_turns_by_is_an_angle():
    """An arm held 0.6 rad from the crank, written as the equation t5 - t2 - 0.6 (no sine of t5 in its loop),
    drives a dyad: t5 is an angle (the dyad takes its cosine), and so is one set by an equation between
    angles that nothing turns by; a rack's travel rolled off by the crank (x - 2 t2) stays a length."""
    t2, t5, t6, t7, t8 = sp.symbols("theta2 theta5 theta6 theta7 theta8")
    x = sp.Symbol("x")
    arm = Loop([t5 - t2 - 0.6], [t5], name="arm")
    dyad = Loop.from_vectors([(1.0, t5), (3.5, t6), (-3.0, t7), (-4, 0), (-0.5, sp.pi / 2)], [t6, t7], name="dyad")
    follower = Loop([t8 - t7 + sp.atan2(1, 2)], [t8], name="follower")
    rack = Loop([x - 2 * t2], [x], name="rack")
    guess = {"theta5": 0.6, "theta6": 0.29, "theta7": 1.52, "theta8": 1.06}
    mech = Mechanism([arm, dyad, follower], t2, guess=guess, guess_input=0.0)
    assert set(mech.angles) == {"theta5", "theta6", "theta7", "theta8"}
    assert arm.angles == set()  # the loop alone cannot tell
    assert set(Mechanism([arm, dyad, follower, rack], t2, guess={**guess, "x": 0.0}).angles) == set(mech.angles)
    # a wheel of radius R rolled by x: a point turns by x / R, which leaves x a length
    radius = sp.Symbol("R", positive=True)
    slider = Loop([80 * sp.cos(t2) + 200 * sp.cos(t6) - x, 80 * sp.sin(t2) + 200 * sp.sin(t6)], [t6, x])
    wheel = Mechanism([slider], t2, {radius: 30.0}, guess=[0.0, 250.0],
                      points={"P": (x - radius * sp.sin(x / radius), radius - radius * sp.cos(x / radius))})
    assert wheel.angles == ("theta6",)
    inputs = np.linspace(0.0, 2 * np.pi, 361)
    sweep = mech.sweep(inputs)
    assert "theta5 [deg]" in sweep.to_frame().columns
    np.testing.assert_allclose(sweep["theta5"], inputs + 0.6, atol=1e-12)
    from numkin import analytic, kinematics

    frame = analytic.kinematics(sweep, 10.0)
    assert frame.attrs["units"]["omega_theta5"] == "rad/s"
    np.testing.assert_allclose(frame["omega_theta5"], 10.0, atol=1e-9)
    spectral = kinematics.finite_difference(sweep, 10.0, method="spectral", second_method="spectral_second")
    np.testing.assert_allclose(spectral["omega_theta5"], 10.0, atol=1e-9)  # one turn: periodic


def test_symbols_of_one_name_with_other_assumptions():
    """An input or a parameter made again with other assumptions means the loops' symbol of that name (the
    4:1:3:3 four-bar's theta4 at 90° by circle intersection: 119.3714°); two such symbols in the loops'
    equations are refused, naming both and their loops."""
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4", positive=True)
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2ABO4")
    mech = Mechanism([loop], sp.Symbol("theta2", real=True), {r1: 4, r2: 1, r3: 3, sp.Symbol("r4"): 3},
                     guess=[0.5, 2.0])
    assert round(math.degrees(mech.sweep(np.radians([90.0]))["theta4"][0]), 4) == 119.3714
    t5, t6 = sp.symbols("theta5 theta6")
    second = Loop.from_vectors([(r1, 0), (r4, sp.Symbol("theta4", real=True)), (3, t5), (-3, t6), (-7, 0)], [t5, t6],
                               name="second")
    with pytest.raises(InputError, match=r"loop 'O2ABO4' writes Symbol\('theta4'\) and loop 'second' "
                                         r"Symbol\('theta4', real=True\): two different sympy symbols named 'theta4'"):
        Mechanism([loop, second], t2, {r1: 4, r2: 1, r3: 3, r4: 3})


def test_an_input_that_is_a_length_is_warned_of():
    """A rocker pushed by a cylinder of length d, d taken as the input: numkin reads the input as an angle
    (its tables show it in degrees), and says so, written as vectors or as equations. An input the loops
    turn by, gear (t5 = 2 t2) or roll a rack off (x = r t2), or put in a square root, is none."""
    t, phi, d, x, t5, t6, t7 = sp.symbols("theta phi d x theta5 theta6 theta7")
    loop = Loop.from_vectors([(100, t), (-d, phi), (-150, 0)], [t, phi], name="cylinder")
    written = Loop([100 * sp.cos(t) - d * sp.cos(phi) - 150, 100 * sp.sin(t) - d * sp.sin(phi)], [t, phi])
    for lp in (loop, written):
        with pytest.warns(UserWarning, match=r"the input d is a length: the loops take no sine or cosine of it.*"
                                             r"make the input the angle of a link it moves and the length an unknown"):
            Mechanism([lp], d, guess=[0.7227, 2.4146], guess_input=100.0)
    r = sp.Symbol("r", positive=True)
    dyad = Loop.from_vectors([(1, t5), (3.5, t6), (-3, t7), (-4, 0)], [t6, t7])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rocker = Loop.from_vectors([(100, t), (-d, phi), (-150, 0)], [d, phi], name="cylinder")
        Mechanism([rocker], t, guess=[100.0, 2.4])  # the rocker's angle as the input: d solved for
        Mechanism([Loop([x - sp.sin(t)], [x])], t, guess=[0.2])  # a sine of it
        geared = Mechanism([Loop([t5 - 2 * t], [t5]), dyad], t, guess=[0.0, 0.3, 1.5])
        assert set(geared.angles) == {"theta5", "theta6", "theta7"}
        rack = Mechanism([Loop([x - r * t], [x])], t, {r: 20.0}, guess=[0.0])
        assert rack.angles == ()
        Mechanism([Loop([x - sp.sqrt(2 - t)], [x])], t, guess=[1.4])


def test_functions_without_a_code_derivative_or_a_complex_form_name_the_loop():
    """Abs of symbols not declared real differentiates to a Derivative sympy cannot print: refused naming the
    loop and the equation (declared real, the same loop compiles); atan2 has no complex form in numpy, so the
    complex step says so and points at the exact derivatives."""
    t2, t3 = sp.symbols("theta2 theta3")
    x = sp.Symbol("x", real=True)
    residuals = [x - 50 * sp.cos(t2) - 150 * sp.cos(t3), sp.Abs(50 * sp.sin(t2) + 150 * sp.sin(t3) + 200) - 200]
    with pytest.raises(InputError, match=r"loop 'abs': equation 2 has no derivative sympy can write as code .*"
                                         r"declare them real"):
        Mechanism([Loop(residuals, [t3, x], name="abs")], t2, guess=[0.0, 200.0])
    r2, r3 = sp.symbols("theta2 theta3", real=True)
    real = [x - 50 * sp.cos(r2) - 150 * sp.cos(r3), sp.Abs(50 * sp.sin(r2) + 150 * sp.sin(r3) + 200) - 200]
    Mechanism([Loop(real, [r3, x], name="abs")], r2, guess=[0.0, 200.0])
    s = sp.sqrt(150**2 - (50 * sp.sin(t2)) ** 2)
    mech = Mechanism([Loop([x - 50 * sp.cos(t2) - s, t3 - sp.atan2(-50 * sp.sin(t2), s)], [x, t3], name="atan2")], t2,
                     guess=[200.0, 0.0])
    sweep = mech.sweep(np.radians([80.0, 90.0, 100.0]))
    from numkin import analytic

    with pytest.raises(InputError, match="no complex form in numpy .*analytic.derivatives differentiates them"):
        analytic.complex_step(sweep)
    dq, _ = analytic.derivatives(sweep)
    # dx/dtheta2 = -r sin(theta2) - r^2 sin(theta2) cos(theta2) / sqrt(l^2 - r^2 sin^2(theta2)): -50 at 90°
    assert dq[0, 1] == pytest.approx(-50.0, abs=1e-12)


def test_a_misspelt_parameter_is_named():
    """A misspelt parameter (r_4 for r4) is named beside the symbol left without a value."""
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4", positive=True)
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2ABO4")
    with pytest.raises(InputError, match=r"uses symbol\(s\) r4 that are neither .*; parameter r_4 is given but used "
                                         r"by no loop: a misspelling of r4\?"):
        Mechanism([loop], t2, {"r1": 4, "r2": 1, "r3": 3, "r_4": 3})

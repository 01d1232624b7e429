"""Input mistakes a new user makes are refused or said, never turned into a silently wrong number.

Positions are checked against the four-bar's closed form derived here (two
circles intersected) and the offset slider-crank's (an arcsine); messages
by the key parts of their text.
"""

from __future__ import annotations

import math
import re
import textwrap
import warnings

import numpy as np
import pytest
import sympy as sp

from numkin import Loop, Mechanism, linkages
from numkin.errors import AssemblyError, BranchError, ConvergenceWarning, DegreesWarning, GuessWarning, InputError
from numkin.scene import SceneError, load_scene, run_scene
from test_cli import one_line_error, run


def four_bar_closed_form(t2, r1=4.0, r2=1.0, r3=3.0, r4=3.0, sign=1.0):
    """(theta3, theta4) of the four-bar O2-A-B-O4, pivots O2 = (0, 0) and O4 = (r1, 0), rad; sign 1 the
    open branch (B to the left of A -> O4), -1 the crossed one."""
    ax, ay = r2 * math.cos(t2), r2 * math.sin(t2)
    dx, dy = r1 - ax, -ay
    d = math.hypot(dx, dy)
    a = (r3**2 - r4**2 + d**2) / (2 * d)
    h = sign * math.sqrt(r3**2 - a**2)
    bx, by = ax + a * dx / d - h * dy / d, ay + a * dy / d + h * dx / d
    return math.atan2(by - ay, bx - ax), math.atan2(by, bx - r1)


LOOPS = """
[scene]
description = "the four-bar {r1}, {r2}, {r3}, {r4} written as loops"
[mechanism]
input = "theta2"
unit = "mm"
[mechanism.dimensions]
r1 = {r1}
r2 = {r2}
r3 = {r3}
r4 = {r4}
[[mechanism.loops]]
name = "O2-A-B-O4"
unknowns = ["theta3", "theta4"]
vectors = [["r2", "theta2"], ["r3", "theta3"], ["-r4", "theta4"], ["-r1", "0"]]
[input]
{speed}stop_deg = {stop}
step_deg = {step}
[guess]
theta3_deg = {theta3}
theta4_deg = {theta4}
"""


def loops_scene(tmp_path, *, r1=4, r2=1, r3=3, r4=3, theta3=60, theta4=120, stop=360, step=1, speed=None,
                output="", edits=(), name="loops.toml"):
    """The four-bar O2-A-B-O4 as a scene written as loops (from 0 deg), with ``output`` (the ``[output]``
    keys) appended and each ``(old, new)`` of ``edits`` replaced in it (``old`` must be there); its path."""
    text = textwrap.dedent(LOOPS.format(r1=r1, r2=r2, r3=r3, r4=r4, theta3=theta3, theta4=theta4, stop=stop, step=step,
                                        speed=f'speed = "{speed}"\n' if speed else ""))
    if output:
        text += f"[output]\n{output}\n"
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def warning_lines(err: str) -> list:
    """The warning lines a command printed on stderr."""
    return [line for line in err.splitlines() if line.startswith("numkin: warning: ")]


# ---------------------------------------------------------- a negative length
def test_negative_length_in_a_loops_scene_is_refused(capsys, tmp_path):
    code, out, err = run(capsys, "run", loops_scene(tmp_path, r2=-1))
    assert code == 2 and out == ""
    line = one_line_error(err)
    assert "loops.toml: [mechanism.dimensions] r2:" in line
    assert "length r2 = -1 is negative" in line and "lengths must be positive" in line
    assert "theta3" not in line  # refused before anything is solved


def test_negative_length_is_refused_by_the_mechanism_with_the_same_words(tmp_path):
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")  # sign undeclared: lengths
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2-A-B-O4")
    with pytest.raises(ValueError, match=r"length r2 = -1 is negative .*: lengths must be positive"):
        Mechanism([loop], t2, {r1: 4, r2: -1, r3: 3, r4: 3})
    with pytest.raises(SceneError, match=r"\[mechanism.dimensions\] r2: .*lengths must be positive"):
        load_scene(loops_scene(tmp_path, r2=-1)).build_mechanism()


def test_positive_lengths_in_a_loops_scene_solve_to_the_closed_form(tmp_path):
    result = run_scene(load_scene(loops_scene(tmp_path)), at=90)
    t3, t4 = four_bar_closed_form(math.radians(90))
    assert result.at.values["theta3_deg"] == pytest.approx(math.degrees(t3), abs=1e-9)
    assert result.at.values["theta4_deg"] == pytest.approx(math.degrees(t4), abs=1e-9)


SIGNED = """
[scene]
description = "offset slider-crank, its offset below the crank pivot"
[mechanism]
input = "theta2"
[mechanism.dimensions]
r2 = 1
r3 = 3
e = -0.4
[[mechanism.loops]]
name = "O2-A-B"
unknowns = ["theta3", "x"]
equations = ["r2*cos(theta2) + r3*cos(theta3) - x", "r2*sin(theta2) + r3*sin(theta3) - e"]
[input]
stop_deg = 180
step_deg = 10
[guess]
theta3_deg = 10
x = 3.9
"""


@pytest.mark.parametrize("loop", [
    'equations = ["r2*cos(theta2) + r3*cos(theta3) - x", "r2*sin(theta2) + r3*sin(theta3) - e"]',
    # a vector of fixed direction is an offset: its length may be negative
    'vectors = [["r2", "theta2"], ["r3", "theta3"], ["-x", "0"], ["-e", "pi/2"]]',
])
def test_a_signed_offset_is_accepted(tmp_path, loop):
    path = tmp_path / "offset.toml"
    path.write_text(textwrap.dedent(SIGNED).replace(
        'equations = ["r2*cos(theta2) + r3*cos(theta3) - x", "r2*sin(theta2) + r3*sin(theta3) - e"]', loop))
    result = run_scene(load_scene(str(path)), at=90)
    t3 = math.asin((-0.4 - 1.0) / 3.0)  # r2 sin(theta2) + r3 sin(theta3) = e at theta2 = 90°
    assert result.at.values["theta3_deg"] == pytest.approx(math.degrees(t3), abs=1e-9)
    assert result.at.values["x"] == pytest.approx(3.0 * math.cos(t3), abs=1e-9)


# ---------------------------------------------------- a solve that fails
def test_solve_that_does_not_converge_warns_where_and_why():
    m = linkages.four_bar(4, 1, 3, 3)
    with pytest.warns(ConvergenceWarning) as record:
        res = m.solve(np.radians(90), guess=[30, 120])
    assert not res.converged
    t2, (t3, t4) = math.pi / 2, res.x
    loop = [math.cos(t2) + 3 * math.cos(t3) - 3 * math.cos(t4) - 4, math.sin(t2) + 3 * math.sin(t3) - 3 * math.sin(t4)]
    residual = max(abs(v) for v in loop) / 4.0  # scaled by the largest length
    text = str(record[0].message)
    assert "did not converge at input 90.000°" in text and "loop 'O2-A-B-O4'" in text
    assert f"residual {residual:.3g}" in text and "converged=False" in text
    assert "theta3 = 30, theta4 = 120 is more than a turn from zero" in text and "degrees" in text


def test_solve_that_converges_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = linkages.four_bar(4, 1, 3, 3).solve(np.radians(90), guess=[0.5, 2.0])
    assert res.converged
    assert tuple(res.x) == pytest.approx(four_bar_closed_form(math.pi / 2), abs=1e-12)


def test_solve_from_a_guess_within_a_turn_does_not_ask_about_degrees():
    with pytest.warns(ConvergenceWarning) as record:
        res = linkages.four_bar(4, 1, 3, 3).solve(np.radians(90), guess=[0.5, 2.0], maxiter=1)
    assert not res.converged
    assert "degrees" not in str(record[0].message)


# --------------------------------------------- guesses given in degrees
def test_chained_four_bars_first_guess_in_degrees_is_named():
    # phi = psi: the first loop's two vectors parallel, its Jacobian singular from the guess on
    with pytest.raises(AssemblyError) as info:
        linkages.chained_four_bars(guess1=(60, 60)).sweep(np.radians(np.arange(0, 361)))
    text = str(info.value)
    assert "the guess phi = 60, psi = 60 is more than a turn from zero" in text
    assert "was it given in degrees?" in text
    assert "beta =" not in text and "gamma =" not in text  # those were given in rad
    assert info.value.far_guess == [("phi", 60.0), ("psi", 60.0)]


def test_chained_four_bars_in_rad_solve():
    sweep = linkages.chained_four_bars().sweep(np.radians([0.0, 1.0]))
    assert np.all(np.abs(sweep.values) < 2 * math.pi)


def test_degrees_warning_names_every_unknown():
    with pytest.warns(GuessWarning) as record:
        linkages.four_bar(4, 1, 3, 3).sweep(np.radians([0, 10]), guess={"theta3": 60, "theta4": 120})
    text = str(record[0].message)
    assert "theta3 = 60, theta4 = 120 is more than a turn from zero" in text
    assert [name for name, _ in record[0].message.far] == ["theta3", "theta4"]


def test_scene_guess_in_degrees_is_not_asked_whether_it_was_in_degrees(capsys, tmp_path):
    code, out, err = run(capsys, "run", loops_scene(tmp_path, theta3=1e6, stop=10, step=5))
    assert code == 0
    warning = warning_lines(err)
    assert len(warning) == 1, err
    assert "[guess] theta3_deg = 1e+06 is more than a turn from zero (in degrees)" in warning[0]
    assert "was it given in degrees" not in warning[0]
    # the solution at 0° (theta3 = 60°, an equilateral triangle) on the guess's turn
    assert f"theta3 at {60 + 360 * round((1e6 - 60) / 360):.6g}°" in warning[0]


CHAINED = """
[scene]
description = "the homework, its first guess written as rad in a _deg key"
[mechanism]
linkage = "chained_four_bars"
[guess]
phi_deg = {phi!r}
psi_deg = {psi!r}
beta_deg = 30
gamma_deg = 270
"""


@pytest.mark.parametrize("command", ["run", "report"])
def test_scene_failing_from_a_guess_in_degrees_says_it_in_degrees(capsys, tmp_path, command):
    path = tmp_path / "chained.toml"
    phi = psi = math.degrees(60)  # guesses of linkage 1 that fail in rad (vectors parallel), as degrees
    path.write_text(textwrap.dedent(CHAINED.format(phi=phi, psi=psi)))
    code, out, err = run(capsys, command, str(path))
    assert code == 2
    line = one_line_error(err)
    assert f"[guess] phi_deg = {phi:.6g}, psi_deg = {psi:.6g} is more than a turn from zero (in degrees)" in line
    assert "was it given in degrees" not in line


def test_report_says_a_far_guess_once_and_in_degrees(capsys, tmp_path):
    # the report sweeps many grids from the same guess: one warning, as the scene writes the guess
    code, out, err = run(capsys, "report", loops_scene(tmp_path, theta3=1950, stop=360, step=10))
    assert code == 0
    warning = warning_lines(err)
    assert len(warning) == 1, err
    assert "[guess] theta3_deg = 1950 is more than a turn from zero (in degrees)" in warning[0]
    assert "was it given in degrees" not in warning[0]
    assert f"theta3 at {60 + 360 * 5:.6g}°" in warning[0]  # 1950° is nearest 60° + 5 turns


def test_figures_say_a_far_guess_once_and_in_degrees(capsys, tmp_path):
    # the positions, then the convergence figure's table from many grids: one warning line in all
    path = loops_scene(tmp_path, theta3=1950, stop=360, step=10, speed="10 rad/s", output='figures = ["convergence"]')
    code, out, err = run(capsys, "figures", path, "--out", str(tmp_path / "figures"), "--formats", "png")
    assert code == 0
    warning = warning_lines(err)
    assert len(warning) == 1, err
    assert "[guess] theta3_deg = 1950 is more than a turn from zero (in degrees)" in warning[0]


# ------------------------------------------------------------ the command
def test_a_directory_is_not_a_scene_file(capsys, tmp_path):
    code, out, err = run(capsys, "run", str(tmp_path))
    assert code == 2
    assert "is a directory" in one_line_error(err) and "not found" not in err


@pytest.mark.parametrize("stop, step, key", [(1e12, 1, "stop_deg"), (360, 1e-6, "step_deg")])
def test_too_many_points_blame_the_key_that_makes_them(capsys, tmp_path, stop, step, key):
    code, out, err = run(capsys, "run", loops_scene(tmp_path, stop=stop, step=step))
    assert code == 2
    line = one_line_error(err)
    assert f"[input] {key}:" in line and "more than ten million" in line


def test_warnings_point_at_the_line_that_called_numkin():
    m = linkages.four_bar(4, 1, 3, 3)
    with pytest.warns(ConvergenceWarning) as solved:
        m.solve(np.radians(90), guess=[30, 120])
    with pytest.warns(UserWarning, match="more than a turn from zero") as swept:  # from deep in the sweep
        m.sweep(np.radians([0.0, 10.0]), guess={"theta3": 60, "theta4": 120})
    assert solved[0].filename == __file__ and swept[0].filename == __file__


# ------------------------------------------------------------ change points in a scene
PARALLELOGRAM = """
[scene]
description = "the crossed parallelogram four-bar, through its change point at 180 deg"
[mechanism]
linkage = "four_bar"
branch = "crossed"
[mechanism.dimensions]
ground = 5
crank = 2
coupler = 5
rocker = 2
[input]
start_deg = 10
stop_deg = 350
step_deg = 5
{extra}
"""


def _parallelogram_refused(capsys, tmp_path, extra: str) -> str:
    """The one line `numkin run` refuses the parallelogram scene with, `extra` added to its [input]."""
    path = tmp_path / "par.toml"
    path.write_text(textwrap.dedent(PARALLELOGRAM.format(extra=extra)))
    code, out, err = run(capsys, "run", str(path))
    assert code == 2
    return one_line_error(err)


def test_a_scene_through_a_change_point_is_told_its_own_key(capsys, tmp_path):
    line = _parallelogram_refused(capsys, tmp_path, "")
    assert "change point" in line and 'set on_singular = "report" in [input]' in line
    assert "pass on_singular" not in line


def test_a_branch_and_a_guess_together_are_refused(capsys, tmp_path):
    """Both pick the assembly: a [guess] on the other branch silently overruled `branch` before."""
    line = _parallelogram_refused(capsys, tmp_path, "[guess]\ntheta3_deg = 10\ntheta4_deg = 100")
    assert '[mechanism] branch: "crossed" and a [guess] both pick the assembly branch: give one' in line


def test_a_scene_with_on_singular_report_keeps_the_branch_through_the_change_point(tmp_path):
    path = tmp_path / "par.toml"
    path.write_text(textwrap.dedent(PARALLELOGRAM.format(extra='on_singular = "report"')))
    with pytest.warns(Warning):
        result = run_scene(load_scene(str(path)))
    assert [e.kind for e in result.sweep.events][0] == "change point"
    # Where the branches meet (180 deg) the sweep keeps the antiparallelogram (coupler crossing the
    # ground, theta3 != 0), whose tangent is continuous, not the parallelogram (theta3 = 0, theta4 = theta2):
    # the circle intersection on the crossed side before 180 deg, on the other side after it.
    for deg, sign in ((90, -1.0), (270, 1.0)):
        t3, t4 = four_bar_closed_form(math.radians(deg), 5.0, 2.0, 5.0, 2.0, sign)
        got = result.sweep.values[:, int((deg - 10) / 5)]
        assert abs(math.remainder(got[0] - t3, 2 * math.pi)) < 1e-9 and abs(t3) > 0.5
        assert abs(math.remainder(got[1] - t4, 2 * math.pi)) < 1e-9


def test_on_singular_takes_raise_or_report_only(capsys, tmp_path):
    line = _parallelogram_refused(capsys, tmp_path, 'on_singular = "maybe"')
    assert '[input] on_singular: must be "raise" or "report"' in line


# ------------------------------------------------------------ equations and symbols
@pytest.mark.parametrize("equations, words", [
    ('[1, 2]', 'equation 1: must be a string'),
    ('["a = b = c", "r2*sin(theta2) + r3*sin(theta3) - r4*sin(theta4)"]', "has 2 '=' signs"),
])
def test_equations_that_are_not_one_equation_each_are_named(capsys, tmp_path, equations, words):
    path = loops_scene(tmp_path, step=10, edits=[(
        'vectors = [["r2", "theta2"], ["r3", "theta3"], ["-r4", "theta4"], ["-r1", "0"]]', f"equations = {equations}")])
    code, out, err = run(capsys, "run", path)
    assert code == 2
    assert words in one_line_error(err)


def test_an_input_that_appears_in_no_loop_is_named():
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2-A-B-O4")
    with pytest.raises(ValueError, match=r"the input theta22 appears in no loop: the loops use theta2, which has no value"):
        Mechanism([loop], "theta22", {r1: 4, r2: 1, r3: 3, r4: 3})


def test_a_loops_scene_missing_a_guess_is_not_told_of_a_default(capsys, tmp_path):
    path = loops_scene(tmp_path, step=10, edits=[("theta4_deg = 120\n", "")])
    code, out, err = run(capsys, "run", path)
    assert code == 2
    line = one_line_error(err)
    assert "lacks theta4_deg" in line and "has no default guess" in line and "leave out" not in line


# ------------------------------------------------------------ a zero length
def test_zero_length_in_a_loops_scene_is_refused(capsys, tmp_path):
    code, out, err = run(capsys, "run", loops_scene(tmp_path, r2=0))
    assert code == 2
    line = one_line_error(err)
    assert "[mechanism.dimensions] r2:" in line and "length r2 is zero" in line and "lengths must be positive" in line


@pytest.mark.parametrize("zero", ["r2", "r3"])
def test_zero_length_is_refused_by_the_mechanism(zero):
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2-A-B-O4")
    values = {r1: 4, r2: 1, r3: 3, r4: 3}
    values[sp.Symbol(zero)] = 0
    with pytest.raises(ValueError, match=rf"length {zero} is zero .*lengths must be positive"):
        Mechanism([loop], t2, values)


# ------------------------------------------------------------ a dimension of the wrong kind
@pytest.mark.parametrize("edits, words", [
    ([("r1 = 4", "r1_deg = 4")], "1 vector 4 length: 'r1' is an angle (given as r1_deg"),
    ([("r1 = 4", "r1 = 4\ngamma = 5"), ('["r2", "theta2"]', '["r2", "theta2 + gamma"]')],
     "vector 1 angle: 'gamma' is a length (in mm"),
    # the transmission angle written as a point: its "x" would be labelled mm and hold rad
    ([("[input]", '[mechanism.points]\nO2 = ["0", "0"]\nMU = ["theta4 - theta3", "0"]\n[input]')],
     "[mechanism.points] MU x: 'theta3' is an angle but is a whole term of the point's coordinate"),
    ([("[input]", '[mechanism.points]\nA = ["r2*cos(theta2)", "2*theta2"]\n[input]')],
     "[mechanism.points] A y: 'theta2' is an angle"),
    # a coupler point's angle offset given as a length (gamma = 30 for gamma_deg = 30): inside cos, a length
    ([("r1 = 4", "r1 = 4\ngamma = 30"),
      ("[input]", '[mechanism.points]\nC = ["r2*cos(theta2) + 2*cos(theta3 + gamma)", "0"]\n[input]')],
     "[mechanism.points] C x: 'gamma' is a length (in mm, [mechanism.dimensions]) but is added to an angle (the "
     "argument of cos)"),
    # degrees written as a number in an angle: 30 rad, 180 rad
    ([("[input]", '[mechanism.points]\nC = ["r2*cos(theta2) + 2*cos(theta3 + 30)", "0"]\n[input]')],
     "[mechanism.points] C x: the number 30 in an angle (the argument of cos) is more than a turn: a number in an "
     "angle is rad (30 rad = 1719°)"),
    ([('["-r1", "0"]', '["r1", "180"]')], "1 vector 4 angle: the number 180 in an angle is more than a turn"),
    ([('["-r1", "0"]', '["r1", "theta2 - 180"]')], "1 vector 4 angle: the number -180 in an angle is more than"),
    ([('["-r1", "0"]', '["r1", "theta2 + 400/57.3"]')], "1 vector 4 angle: the number 6.9808 in an angle is more"),
    # an equation "lhs = rhs" is checked on both sides
    ([('vectors = [["r2", "theta2"], ["r3", "theta3"], ["-r4", "theta4"], ["-r1", "0"]]',
       'equations = ["r2*cos(theta2) + r3*cos(theta3 + r1) = r4*cos(theta4) + r1", '
       '"r2*sin(theta2) + r3*sin(theta3) = r4*sin(theta4)"]')],
     "1 equation 1: 'r1' is a length (in mm, [mechanism.dimensions]) but is added to an angle (the argument of cos)"),
    # a derived angle with a length as a whole term
    ([("[input]", '[mechanism.quantities]\nmu = { expression = "theta4 - theta3 + r1", dimension = "angle" }\n'
                  '[input]')],
     "[mechanism.quantities] mu expression: 'r1' is a length (in mm, [mechanism.dimensions]) but is a whole term "
     "of an angle"),
])
def test_a_dimension_used_as_the_other_kind_is_refused(capsys, tmp_path, edits, words):
    code, out, err = run(capsys, "run", loops_scene(tmp_path, step=10, edits=edits))
    assert code == 2
    assert words in one_line_error(err)


@pytest.mark.parametrize("angle", ["theta2 + 30/57.29578", "theta2 + 30*0.01745329", "theta2 + 6.2832",
                                   "theta2 - 10*pi", "2*pi - theta2", "theta2 + pi/6"])
def test_numbers_in_an_angle_that_are_rad_are_fine(tmp_path, angle):
    """A conversion written out (30/57.29578), a turn to a few figures, multiples of pi: rad on purpose."""
    path = loops_scene(tmp_path, step=10, edits=[("[input]", f'[mechanism.points]\nO2 = ["0", "0"]\n'
                                                            f'C = ["cos({angle})", "sin({angle})"]\n[input]')])
    assert load_scene(path).custom["points"]["C"] == [f"cos({angle})", f"sin({angle})"]


def test_an_angle_from_lengths_and_a_projected_length_are_fine(tmp_path):
    # atan2 of two lengths is an angle, and a length times the cosine of an angle a length: both legitimate;
    # the loop O2-A-B-O4 with O4 given by its distance and direction, checked against the closed form
    path = loops_scene(tmp_path, step=10, edits=[("r1 = 4", "r1 = 4\nh = 0\ntilt_deg = 0"),
                                                 ('["-r1", "0"]', '["-r1*cos(tilt + 2*pi)", "atan2(h, r1)"]')])
    result = run_scene(load_scene(path), at=90)
    t3, t4 = four_bar_closed_form(math.radians(90))
    assert result.at.values["theta4_deg"] == pytest.approx(math.degrees(t4), abs=1e-9)


# ------------------------------------------------------------ a linkage that cannot turn fully
def part_turn(tmp_path, theta3, theta4):
    """The non-Grashof four-bar (4, 2, 1.5, 3) over 0..80 deg of its input, with velocities."""
    return loops_scene(tmp_path, r2=2, r3=1.5, theta3=theta3, theta4=theta4, stop=80, speed="10 rad/s",
                       output='quantities = ["position", "velocity"]')


def test_report_of_a_scene_that_cannot_turn_fully_sweeps_the_scene_s_range(capsys, tmp_path):
    # |A O4|^2 = 20 - 16 cos(theta2) reaches (r3 + r4)^2 = 20.25 at 90.895 deg, a toggle: a full turn
    # cannot be swept; the report keeps to the scene's 0..80 deg
    code, out, err = run(capsys, "report", part_turn(tmp_path, 117, 154))
    assert code == 0, err
    assert "toggle" not in err
    assert "360 points per turn over 80 deg from 0 deg" in " ".join(out.split())


def test_a_scene_s_failing_guess_is_told_in_degrees(capsys, tmp_path):
    code, out, err = run(capsys, "run", part_turn(tmp_path, 60, 100))
    assert code == 2
    line = one_line_error(err)
    assert "cannot assemble at input 0.000°" in line
    assert "better [guess] (angles as <unknown>_deg, in degrees)" in line and "in rad" not in line


# ------------------------------------------------------------ a toggle is not a change point
def test_a_toggle_met_in_a_sweep_is_said_as_a_toggle_in_either_mode():
    # |A O4| = sqrt(40^2 + 10^2 - 800 cos(theta2)) must reach r3 - r4 = 30.01: it cannot within
    # 0.01 of theta2 = 0 (|A O4| = 30 there); the branch folds back (a toggle) at
    # cos(theta2) = (1700 - 30.01^2) / 800, 357.78 deg
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2-A-B-O4")
    mech = Mechanism([loop], t2, {r1: 40, r2: 10, r3: 40.01, r4: 10}, guess={"theta3": 0.0, "theta4": 0.3})
    toggle = 360 - math.degrees(math.acos((1700 - 30.01**2) / 800))
    for mode in ("raise", "report"):
        with pytest.raises(BranchError) as caught, warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mech.sweep(np.radians(np.arange(5, 725, 1.0)), on_singular=mode)
        assert caught.value.kind == "toggle" and "change point" not in str(caught.value)
        assert math.degrees(caught.value.input_value) == pytest.approx(toggle, abs=1e-2)


def test_a_python_offset_of_fixed_direction_may_be_negative_like_in_a_scene():
    # the offset slider-crank: r e^{i theta2} + l e^{i theta3} - x - e i = 0, e = -30 (the piston line
    # 30 below the crank pivot): r sin(theta2) + l sin(theta3) = e, x = r cos(theta2) + l cos(theta3)
    t2, t3, x = sp.symbols("theta2 theta3 x")
    r, rod, e = sp.symbols("r l e")  # plain symbols: lengths unless their vector has a fixed direction
    loop = Loop.from_vectors([(r, t2), (rod, t3), (-x, 0), (-e, sp.pi / 2)], [t3, x], name="slider")
    mech = Mechanism([loop], t2, {r: 80, rod: 200, e: -30}, guess={"theta3": 0.1, "x": 280})
    s = mech.sweep(np.radians([0.0, 90.0]))
    t3_90 = math.asin((-30 - 80) / 200)
    assert s.values[0, 1] == pytest.approx(t3_90, abs=1e-12)
    assert s.values[1, 1] == pytest.approx(200 * math.cos(t3_90), abs=1e-9)
    with pytest.raises(ValueError, match=r"length r = -80 is negative"):
        Mechanism([loop], t2, {r: -80, rod: 200, e: -30})


def test_a_loop_that_can_never_close_is_said_so_not_blamed_on_the_guess():
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2-A-B-O4")
    mech = Mechanism([loop], t2, {r1: 100, r2: 10, r3: 30, r4: 30}, guess={"theta3": 0.5, "theta4": 2.0})
    with pytest.raises(AssemblyError, match=r"loop 'O2-A-B-O4' cannot close at any input: its vector of length "
                                            r"r1 = 100 is longer than all the others together \(70\)") as caught:
        mech.sweep(np.radians([0.0, 10.0]))
    assert caught.value.cause == "cannot close" and "guess" not in str(caught.value)
    # a loop that closes, from a guess where its Jacobian is singular (both links along x): the guess's fault
    poor = Mechanism([loop], t2, {r1: 4, r2: 1, r3: 3, r4: 3}, guess={"theta3": 0.0, "theta4": 0.0})
    with pytest.raises(AssemblyError) as caught:
        poor.sweep(np.radians([0.0, 10.0]))
    assert caught.value.cause == "bad guess"


@pytest.mark.parametrize("build, inputs_deg, first_refused, cause, words", [
    # 7/4/3/5 reaches |A - O4| = 8 up to cos t = (49 + 16 - 64) / 56: |theta2| <= 88.98°
    (lambda: linkages.four_bar(7, 4, 3, 5), np.arange(0.0, 361.0), 89.0, "not assemblable",
     "a non-Grashof triple rocker: it can be assembled only for |theta2| <= 88.98°"),
    (lambda: linkages.four_bar(10, 6, 1, 1), np.arange(30.0, 361.0), 30.0, "cannot close",
     "a non-assemblable four-bar (l > s + p + q): it cannot be assembled at any input angle"),
    (lambda: linkages.four_bar(10, 1, 1, 1), np.arange(-5.0, 5.0), -5.0, "cannot close", "at any input angle"),
    # rod 0.05 reaches the piston line while 0.08 |sin t| <= 0.05: up to asin(5/8) = 38.68°
    (lambda: linkages.slider_crank(0.08, 0.05), np.arange(0.0, 361.0), 39.0, "not assemblable",
     "the rod cannot reach the piston line"),
])
def test_a_ready_made_linkage_that_cannot_assemble_names_the_input_loop_and_cause(build, inputs_deg, first_refused,
                                                                                  cause, words):
    mech = build()
    with pytest.raises(AssemblyError) as caught:
        mech.sweep(np.radians(inputs_deg))
    err = caught.value
    assert words in str(err) and "triple rocker" not in str(err).replace("non-Grashof triple rocker: it can be "
                                                                         "assembled only", "")
    assert err.input_value == pytest.approx(math.radians(first_refused), abs=1e-12)
    assert err.loop == mech.loops[0].name and err.cause == cause


def test_a_sweep_in_degrees_is_warned_of_and_one_in_rad_is_not():
    mech = linkages.four_bar(4, 1, 3, 3)
    with pytest.warns(DegreesWarning, match=r"run from 0 to 360 in steps of 1; if the input is an angle, that is "
                                            r"57.3 turns in steps of 57.3°"):
        mech.sweep(np.arange(0.0, 361.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error", DegreesWarning)
        mech.sweep(np.radians(np.arange(0.0, 361.0)))
        mech.sweep(np.arange(0.0, 20.0))  # 20 rad in steps of 1: a few turns, not degrees
        mech.sweep(np.linspace(0.0, 20 * np.pi, 2001))  # ten turns in steps of 1.8°
        mech.sweep(np.linspace(0.0, 40 * np.pi, 200))  # twenty turns in steps of 36°
    assert issubclass(GuessWarning, DegreesWarning)


@pytest.mark.parametrize("inputs, words", [
    (np.arange(0.0, 360.0, 0.5), "run from 0 to 359.5 in steps of 0.5; if the input is an angle, that is 57.2 turns"),
    (np.linspace(0.0, 360.0, 100), "run from 0 to 360 in steps of 3.63636"),
    (np.arange(30.0, 61.0), "run from 30 to 60 in steps of 1; if the input is an angle, that is 4.77 turns"),
])
def test_more_sweeps_in_degrees_are_warned_of(inputs, words):
    with pytest.warns(DegreesWarning, match=re.escape(words)):
        linkages.four_bar(4, 1, 3, 3).sweep(inputs)


def test_a_guess_input_or_an_angle_parameter_in_degrees_is_warned_of():
    """guess_input = 90 and an offset delta = 34.4 added to the crank's angle: degrees by their size; a gear
    ratio n = 10 multiplying it is no angle."""
    import sympy as sp

    from numkin import Loop, Mechanism

    t2, t3, t4, delta, n = sp.symbols("theta2 theta3 theta4 delta n")
    dims = dict(zip(sp.symbols("r1 r2 r3 r4"), (4, 1, 3, 3)))
    r1, r2, r3, r4 = dims
    plain = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4])
    with pytest.warns(DegreesWarning, match=r"guess_input = 90 is an angle more than a turn from zero: angles are "
                                            r"in rad"):
        Mechanism([plain], t2, dims, guess=[0.57, 2.08], guess_input=90.0)
    offset = Loop.from_vectors([(r2, t2 + delta), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4])
    with pytest.warns(DegreesWarning, match=r"parameter delta = 34.4 is an angle more than a turn from zero"):
        Mechanism([offset], t2, {**dims, delta: 34.4}, guess=[0.57, 2.08])
    geared = Loop.from_vectors([(r2, n * t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4])
    with warnings.catch_warnings():
        warnings.simplefilter("error", DegreesWarning)
        Mechanism([geared], t2, {**dims, n: 10}, guess=[0.57, 2.08], guess_input=6.0)
        Mechanism([offset], t2, {**dims, delta: 0.6}, guess=[0.57, 2.08])


# ------------------------------------------------------------ the report and the figures of a scene
RANGE = """
[scene]
description = "a four-bar that assembles for |theta2| <= 78.58 deg"
[mechanism]
linkage = "four_bar"
[mechanism.dimensions]
ground = 4
crank = 3
coupler = 2
rocker = 2.5
[input]
speed = "10 rad/s"
start_deg = -78
stop_deg = 78
step_deg = 1
{extra}
[output]
quantities = ["position", "velocity"]
[report]
grids = [36, 72, 144]
{report}
"""


def test_report_on_less_than_a_turn_checks_in_the_middle_and_says_why_an_end_fails(capsys, tmp_path):
    # cos(theta2) >= (4^2 + 3^2 - 4.5^2) / (2 * 4 * 3): |theta2| <= 78.58 deg; the round-off scan and the
    # Newton table solve around the check angle, which by default is the middle of the sweep (0 deg)
    path = tmp_path / "range.toml"
    path.write_text(textwrap.dedent(RANGE.format(extra="", report="")))
    code, out, err = run(capsys, "report", str(path))
    assert code == 0, err
    path.write_text(textwrap.dedent(RANGE.format(extra="", report="check_deg = -78")))
    code, out, err = run(capsys, "report", str(path))
    assert code == 2
    line = one_line_error(err)
    assert "not solved by Newton" in line and "[report] check_deg" in line


def test_report_through_a_change_point_says_the_tables_need_none(capsys, tmp_path):
    path = tmp_path / "par.toml"
    path.write_text(textwrap.dedent(PARALLELOGRAM.format(extra='on_singular = "report"\nspeed = "10 rad/s"')))
    code, out, err = run(capsys, "report", str(path))
    assert code == 2
    line = one_line_error(err)
    assert "change point" in line and "tables sweep the scene's range and need it free of change points" in line
    assert "pass on_singular" not in line


def test_warnings_are_said_when_a_later_stage_fails(capsys, tmp_path):
    path = tmp_path / "par.toml"
    path.write_text(textwrap.dedent(PARALLELOGRAM.format(extra='on_singular = "report"')) + '[output]\ntables = ["positions"]\n')
    out_dir = tmp_path / "out"
    (out_dir / "par-positions.csv").mkdir(parents=True)  # the table's file is a folder: writing it fails
    code, out, err = run(capsys, "run", str(path), "--out", str(out_dir))
    assert code == 2 and "par-positions.csv" in err.split("numkin: error:")[1]
    assert "change point" in err.split("numkin: error:")[0]  # the sweep's warning, before the error line


def test_each_scene_of_a_command_says_its_own_warnings(capsys, tmp_path):
    # positions only: the figure is skipped
    paths = [loops_scene(tmp_path, step=10, output='figures = ["kinematics:theta4"]', name=f"{name}.toml")
             for name in ("one", "two")]
    code, out, err = run(capsys, "figures", *paths, "--out", str(tmp_path / "figures"))
    assert code == 0
    assert sum("skipped" in line for line in err.splitlines()) == 2, err


def test_a_zero_length_declared_positive_is_refused():
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4", positive=True)
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2-A-B-O4")
    with pytest.raises(ValueError, match="length r2 is zero"):
        Mechanism([loop], t2, {r1: 4, r2: 0, r3: 3, r4: 3})


# ------------------------------------------------------------ values no library below numkin checks
@pytest.mark.parametrize("angle", ["nan", "-nan", "Infinity", "inf"])
def test_a_mechanism_figure_at_an_angle_that_is_not_finite_is_refused(capsys, tmp_path, angle):
    path = loops_scene(tmp_path, step=10, output=f'figures = ["mechanism:{angle}"]')
    code, out, err = run(capsys, "run", path, "--out", str(tmp_path / "out"))
    assert code == 2 and "the angle must be a finite number of degrees" in one_line_error(err)


def test_a_point_name_that_is_not_a_symbol_is_refused(capsys, tmp_path):
    path = loops_scene(tmp_path, step=10, edits=[("[input]", '[mechanism.points]\n"$B^$" = ["r1", "0"]\n[input]')])
    code, out, err = run(capsys, "run", path)
    assert code == 2 and "[mechanism.points] $B^$: '$B^$' is not a usable symbol name" in one_line_error(err)


def test_a_dimension_a_ready_made_linkage_refuses_is_said_where_the_scene_gives_it(capsys, tmp_path):
    path = tmp_path / "huge.toml"
    path.write_text('[scene]\ndescription = "d"\n[mechanism]\nlinkage = "four_bar"\n[mechanism.dimensions]\n'
                    'ground = 4\ncrank = 1e200\ncoupler = 3\nrocker = 3\n')
    code, out, err = run(capsys, "run", str(path))
    assert code == 2 and "huge.toml: [mechanism]: crank = 1e+200 is outside" in one_line_error(err)


def test_a_report_grid_too_coarse_for_a_part_turn_gets_no_advice_about_the_check_angle(capsys, tmp_path):
    path = loops_scene(tmp_path, stop=90, step=5, speed="10 rad/s", output='quantities = ["position", "velocity"]',
                       edits=[("[guess]", "[report]\npoints_per_turn = 7\n[guess]")])
    code, out, err = run(capsys, "report", path)
    line = one_line_error(err)
    assert code == 2 and "fewer than" in line and "check angle" not in line


@pytest.mark.parametrize("edit, words", [
    ('["-r1", "0"]', '["-r1/0", "0"]'),
    ('["r2", "theta2"]', '["sqrt(-r2)", "theta2"]'),
])
def test_a_vector_length_that_is_infinite_or_not_real_is_one_line(capsys, tmp_path, edit, words):
    code, out, err = run(capsys, "run", loops_scene(tmp_path, step=10, edits=[(edit, words)]))
    line = one_line_error(err)
    assert code == 2 and ("is infinite or undefined" in line or "is not a finite real number" in line)


@pytest.mark.parametrize("report_keys, words", [
    ("schemes = []", "[report] schemes: is empty"),
    ("grids = [36, 36]", "[report] grids: names a grid twice"),
    ("points_per_turn = 1000000000", "[report] points_per_turn: at most 100,000"),
    ("grids = [36, 1000000000]", "[report] grids: at most 100,000 points per turn"),
])
def test_report_keys_that_cannot_make_a_table_are_refused(capsys, tmp_path, report_keys, words):
    path = loops_scene(tmp_path, step=10, speed="10 rad/s", edits=[("[guess]", f"[report]\n{report_keys}\n[guess]")])
    code, out, err = run(capsys, "report", path)
    assert code == 2 and words in one_line_error(err)


# ------------------------------------------------------------ the Python API
def test_vectors_and_parameters_a_mechanism_cannot_use_are_named():
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")
    for length, words in ((r2 * sp.I, "I\\*r2"), (sp.nan, "nan"), (r2 / 0, "zoo\\*r2")):
        with pytest.raises(ValueError, match=rf"vector 0 of loop 'L': its length {words} is not a finite real"):
            Loop.from_vectors([(length, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="L")
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="L")
    with pytest.raises(ValueError, match="theta2 is the input; it cannot also be a parameter"):
        Mechanism([loop], t2, {r1: 4, r2: 1, r3: 3, r4: 3, t2: 1.0})
    with pytest.raises(ValueError, match="parameters must map symbols"):
        Mechanism([loop], t2, [4, 1, 3, 3])


def test_rates_of_an_input_at_rest_are_not_compared():
    from numkin import compare, linkages, report

    mech = linkages.four_bar(4, 1, 3, 3)
    with pytest.raises(ValueError, match="omega = 0: the input is at rest"):
        compare.compare(mech.sweep(np.linspace(0, 2 * np.pi, 37)), 0.0, "omega_theta4")
    with pytest.raises(ValueError, match="omega = 0: the input is at rest"):
        report.convergence_table(mech, omega=0, quantity="theta4", grids=(36,))


# ------------------------------------------------------------ a sweep too short for a scheme
SHORT = """
[scene]
description = "a sweep of three points"
[mechanism]
linkage = "slider_crank"
[mechanism.dimensions]
crank = 50
rod = 60
offset = 20
[input]
speed = "10 rad/s"
start_deg = 45
stop_deg = 46
step_deg = 0.5
[output]
quantities = ["position", "velocity", "acceleration"]
[compare]
{compare}
"""


@pytest.mark.parametrize("compare, words", [
    ('schemes = ["five_point"]',
     "[compare] schemes: 'five_point' needs at least 5 points on an open grid; the sweep (45° to 46° in steps of "
     "0.5°) has 3: widen the sweep"),
    ('second_schemes = ["five_point_second"]', "[compare] second_schemes: 'five_point_second' needs at least 6 points"),
])
def test_a_sweep_too_short_for_a_compared_scheme_names_the_key(capsys, tmp_path, compare, words):
    path = tmp_path / "short.toml"
    path.write_text(textwrap.dedent(SHORT.format(compare=compare)))
    code, out, err = run(capsys, "run", str(path))
    assert code == 2
    line = one_line_error(err)
    assert words in line and "last axis" not in line


def test_a_full_turn_too_coarse_for_a_compared_scheme_asks_for_a_smaller_step(capsys, tmp_path):
    path = tmp_path / "coarse.toml"
    path.write_text(textwrap.dedent(SHORT.format(compare='schemes = ["five_point"]')).replace(
        "start_deg = 45", "start_deg = 0").replace("stop_deg = 46", "stop_deg = 360").replace(
        "step_deg = 0.5", "step_deg = 120").replace("rod = 60", "rod = 160"))
    code, out, err = run(capsys, "run", str(path))
    assert code == 2
    assert one_line_error(err).endswith(
        "[compare] schemes: 'five_point' needs at least 5 points on a periodic grid; the sweep (0° to 360° in steps "
        "of 120°) has 3 per turn: make its step smaller, or choose a scheme of fewer points")


def test_compare_names_its_argument_when_the_sweep_is_too_short():
    from numkin import compare
    from numkin.errors import InputError

    sweep = linkages.slider_crank(50, 60, 20).sweep(np.radians([45.0, 45.5, 46.0]))
    with pytest.raises(InputError, match=r"schemes='five_point' \(scheme for omega_theta3\) needs at least 5 points "
                                         r"on an open grid; the sweep has 3"):
        compare.compare(sweep, 10.0, "omega_theta3", schemes=("five_point",))


def test_a_scene_error_names_the_linkage_with_its_unit(capsys, tmp_path):
    """numkin run heads its output with the dimensions and their unit; its errors name the linkage the same way.
    4/3/2/2.5 cm reaches |A - O4| = 4.5 up to cos t = (16 + 9 - 20.25) / 24: |theta2| <= 78.58°."""
    path = tmp_path / "toggle.toml"  # RANGE's four-bar in cm, driven to 120°
    path.write_text(RANGE.format(extra="", report="").replace('linkage = "four_bar"', 'linkage = "four_bar"\nunit = "cm"')
                    .replace("stop_deg = 78", "stop_deg = 120"))
    code, out, err = run(capsys, "run", str(path))
    assert code == 2
    assert ("four-bar (ground 4 cm, crank 3 cm, coupler 2 cm, rocker 2.5 cm): a non-Grashof triple rocker: it can be "
            "assembled only for |theta2| <= 78.58°") in one_line_error(err)


def test_a_report_grid_too_coarse_for_a_scheme_names_the_key(capsys, tmp_path):
    """40° of sweep hold 5 points of the 36-point grid (10° steps); five_point_second needs 6 on an open grid: a
    grid the scene asks for is refused, a default one left out (and the captions say so)."""
    path = tmp_path / "short.toml"
    text = textwrap.dedent(SHORT.format(compare="")).replace("start_deg = 45", "start_deg = 310").replace(
        "stop_deg = 46", "stop_deg = 350")
    path.write_text(text + "[report]\ngrids = [36, 72]\n")
    code, out, err = run(capsys, "report", str(path))
    assert code == 2
    line = one_line_error(err)
    assert line.endswith("[report] grids: the 36-point grid holds 5 points over 40 deg, and scheme 'five_point_second' "
                         "needs at least 6 on an open grid: give grids of more points per turn (or leave the scheme "
                         "out of [report] schemes)")
    path.write_text(text)
    code, out, err = run(capsys, "report", str(path))
    assert code == 0, err
    assert ("The default grids of 36 points per turn are left out: over the scene's 40 deg the finest of them holds "
            "5 points, fewer than five_point_second needs (6).") in " ".join(out.split())
    from numkin import report
    from numkin.errors import InputError

    with pytest.raises(InputError, match=r"^grids: the 36-point grid holds 5 points over 40 deg, and scheme "
                                         r"'five_point_second' needs at least 6"):
        report.convergence_table(linkages.slider_crank(50, 60, 20), omega=10.0, quantity="x", grids=(36, 72),
                                 span=math.radians(40), start=math.radians(310))


def test_a_first_point_short_of_steps_and_inputs_out_of_order_say_so():
    mech = linkages.four_bar(4, 1, 3, 3)
    with pytest.raises(AssemblyError, match=r"did not converge .* after 1 iterations.*or allow more than maxiter=1 "
                                            r"steps"):
        mech.sweep(np.radians([0.0, 10.0]), maxiter=1, guess=[2.5, 0.3])
    with pytest.raises(InputError, match=re.escape("check inputs[1:3] = 0.174533, 0.0872665 rad: 10.0000°, 5.0000°")):
        mech.sweep(np.radians([0.0, 10.0, 5.0]))

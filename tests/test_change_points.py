"""A change point passed in report mode: every grid point stays on the branch the sweep kept.

The anti-parallelogram 5/2/5/2 (crossed) meets the parallelogram at theta2 = 180°,
where the parallelogram turns its rocker with the crank (dtheta4/dtheta2 = 1) and the
crossed branch against it (dtheta4/dtheta2 = -(a - b)/(a + b) = -3/7 there, a = 5,
b = 2). Whatever the grid, the kept branch has a continuous tangent, so no second
difference of theta4 shows the kink (1 + 3/7) h of a switch between the two.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from numkin import BranchError, linkages
from numkin.linkages.four_bar import closed_form


@pytest.mark.parametrize(
    "start, stop, step",
    [(176, 184, 1), (170, 190, 5), (100, 260, 0.5), (1, 359, 1), (359, 1, -1), (185, 175, -0.25)],
)
def test_grid_points_beyond_a_change_point_keep_the_branch(start, stop, step):
    mech = linkages.four_bar(5, 2, 5, 2, branch="crossed")
    inputs = np.radians(np.arange(start, stop + step / 2, step))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(inputs, on_singular="report")
    kinds = [e.kind for e in sweep.events]
    assert "change point" in kinds or "singular" in kinds  # 180° itself is on some grids
    theta4 = sweep["theta4"]
    h = abs(np.radians(step))
    kink = (1 + 3 / 7) * h
    assert np.max(np.abs(np.diff(theta4, 2))) < 0.1 * kink
    # every point is a closed-form assembly (either circle intersection), to the digits a
    # change point leaves (the Jacobian is singular at 180°)
    miss = np.minimum(*[
        np.abs(np.angle(np.exp(1j * (theta4 - closed_form(inputs, 5, 2, 5, 2, sign)[1]))))
        for sign in (1.0, -1.0)
    ])
    assert miss.max() < 1e-7
    if inputs[0] < np.pi:
        # started on the anti-parallelogram: never the parallelogram's rotation with the crank
        # (circle-intersection signs swap at the change point, so a start above 180° with
        # branch="crossed" is the parallelogram, and stays on it)
        away = np.abs(inputs - np.pi) > 1e-9
        assert not np.any(np.abs(np.angle(np.exp(1j * (theta4 - inputs))))[away] < 1e-6)


def _wrap(angle):
    return np.abs(np.angle(np.exp(1j * angle)))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
# a grid point a hair (1e-6 rad) past a change point: its tangent is noise and its orientation the other
# branch's too, so only a step localised like a crossing keeps the branch
@example(a=2.0, ratio=0.75, branch="crossed", start=6.103515625e-05, count=73, step=5.0, direction=1.0, max_step=1.0)
@given(
    a=st.floats(2.0, 6.0),
    ratio=st.floats(0.1, 0.9),
    branch=st.sampled_from(["open", "crossed"]),
    start=st.floats(-400.0, 400.0),
    count=st.integers(5, 400),
    step=st.sampled_from([0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 7.5, 10.0]),
    direction=st.sampled_from([1.0, -1.0]),
    max_step=st.sampled_from([1.0, 5.0, 10.0, 30.0]),
)
def test_change_point_linkages_never_switch_branch(a, ratio, branch, start, count, step, direction, max_step):
    """A linkage a/b/a/b meets its other branch at 0° and 180°: a sweep stays on one.

    Its two branches, in closed form: the parallelogram (theta3 = 0, theta4 = theta2)
    and the anti-parallelogram (either circle intersection elsewhere). A sweep over any
    grid, in either direction, is all one or all the other, but for the change points
    themselves, and every point is an assembly of the linkage.
    """
    b = ratio * a
    mech = linkages.four_bar(a, b, a, b, branch=branch)
    inputs = np.radians(start + direction * step * np.arange(count))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            sweep = mech.sweep(inputs, on_singular="report", max_step=np.radians(max_step))
        except BranchError as err:  # justified only where the branches meet: none to choose
            assert "singular" in str(err)
            assert min(_wrap(inputs[0]), _wrap(inputs[0] - np.pi)) < 1e-6
            return
    theta3, theta4 = sweep["theta3"], sweep["theta4"]
    parallelogram = (_wrap(theta4 - inputs) < 1e-6) & (_wrap(theta3) < 1e-6)
    meeting = (_wrap(inputs) < 1e-6) | (_wrap(inputs - np.pi) < 1e-6)
    assert (parallelogram | meeting).all() or (~parallelogram | meeting).all()
    miss = np.minimum(*[_wrap(theta4 - closed_form(inputs, a, b, a, b, sign)[1]) for sign in (1.0, -1.0)])
    assert miss[~meeting].max(initial=0.0) < 1e-6
    # where the branches meet the root is double: Newton halves its error per step there and
    # stops once the residual (the error squared) is at the round-off floor
    assert miss[meeting].max(initial=0.0) < 1e-5
    if count > 1:  # and the angles are continuous: no neighbour step near a turn
        assert np.abs(np.diff(theta4)).max() < np.pi


# ---------------------------------------------------------------- a singular position at a march's end
def _four_bar_loop(dims, guess, guess_input):
    """A four-bar written as a loop, with a default guess at ``guess_input`` (reached by a march)."""
    import sympy as sp

    from numkin import Loop, Mechanism

    t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4", positive=True)
    loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="L")
    return Mechanism([loop], t2, dict(zip((r1, r2, r3, r4), dims)), guess=guess, guess_input=guess_input)


@pytest.mark.parametrize("dims, guess_input", [((5, 2, 5, 2), 1.0), ((3, 2, 3, 2), 0.5), ((3, 2, 3, 2), 1.0)])
@pytest.mark.parametrize("start", [0.0, 1.7e-11, 1e-9])
def test_a_start_on_a_change_point_reached_from_the_guess_keeps_the_guess_branch(dims, guess_input, start):
    """The guess (theta3 = 0, theta4 = its input) is on the parallelogram; the march from it ends on the
    change point at 0°, where the point's own tangent and orientation are noise: the sweep goes on with
    the guess branch's, so it passes the change point (raised, or reported and kept) and never takes
    the anti-parallelogram (theta3 = 1.333° at -1° for 5/2/5/2) nor calls the change point a toggle."""
    mech = _four_bar_loop(dims, {"theta3": 0.0, "theta4": guess_input}, guess_input)
    inputs = np.array([start, np.radians(-1.0), np.radians(-2.0)])
    with pytest.raises(BranchError) as err:
        mech.sweep(inputs)
    assert err.value.kind == "change point" and abs(err.value.input_value) < 1e-4
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(inputs, on_singular="report")
    assert [e.kind for e in sweep.events][0] == "change point"
    np.testing.assert_allclose(sweep["theta3"], 0.0, atol=1e-7)  # the parallelogram: theta3 = 0, theta4 = theta2
    np.testing.assert_allclose(sweep["theta4"], inputs, atol=1e-7)
    # the other way from the change point: no passing, the parallelogram on the grid's side
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ahead = mech.sweep(np.radians([start, 1.0, 2.0]), on_singular="report")
    np.testing.assert_allclose(ahead["theta4"], np.radians([start, 1.0, 2.0]), atol=1e-7)
    assert "toggle" not in [e.kind for e in ahead.events]


def test_a_change_point_passed_before_the_sweep_is_said_to_be_there():
    """4/2/3/3 (2 + 4 = 3 + 3) meets its other assembly at 180°. Swept from 200° to 300° with the default
    guess at 0°, the march to the sweep's start passes it: raised or reported as met on that way, before
    the sweep, not as if the sweep went through 180°; the sweep keeps the guess's branch carried on
    with a continuous tangent (at 200° the other circle intersection than at 0°)."""
    mech = _four_bar_loop((4.0, 2.0, 3.0, 3.0), {"theta3": 0.3, "theta4": 1.5}, 0.0)
    inputs = np.radians(np.arange(200.0, 301.0))
    where = "on the way from the default guess at 0.000° to the sweep's first input 200.000°, before the sweep"
    with pytest.raises(BranchError) as err:
        mech.sweep(inputs)
    assert err.value.kind == "change point" and abs(err.value.input_value - np.pi) < 1e-6
    assert where in str(err.value) and "a guess at its first input" in str(err.value)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(inputs, on_singular="report")
        through = mech.sweep(np.radians(np.arange(170.0, 191.0)), on_singular="report")
    (event,) = [e for e in sweep.events if e.kind == "change point"]
    assert where in event.message and "kept the branch the guess was on" in event.message
    (inside,) = [e for e in through.events if e.kind == "change point"]
    assert "before the sweep" not in inside.message and "kept the branch the sweep was on" in inside.message
    near_guess = np.radians([0.0, 10.0, 20.0])
    start = mech.sweep(near_guess)  # the guess's branch by the guess: the open one
    open_ = closed_form(near_guess, 4.0, 2.0, 3.0, 3.0, 1.0)
    assert max(_wrap(start["theta3"] - open_[0]).max(), _wrap(start["theta4"] - open_[1]).max()) < 1e-9
    crossed = closed_form(inputs, 4.0, 2.0, 3.0, 3.0, -1.0)
    assert max(_wrap(sweep["theta3"] - crossed[0]).max(), _wrap(sweep["theta4"] - crossed[1]).max()) < 1e-9


@pytest.mark.parametrize("dims, guess_input, inputs, expected", [
    # two change points on the way (the tangent's marches at the first pass the second: still on the way)
    ((5.0, 2.0, 5.0, 2.0), 1.0, np.arange(370.0, 401.0), [(180.0, True), (360.0, True)]),
    # the way ends on a change point, which the sweep then passes: the sweep's
    ((5.0, 2.0, 5.0, 2.0), 1.0, np.arange(-180.0, -250.0, -1.0), [(0.0, True), (-180.0, False)]),
    # the sweep comes back to the change point passed on the way, and ends on it: still passed, on the way
    ((4.0, 2.0, 3.0, 3.0), 0.0, np.arange(300.0, 179.0, -1.0), [(180.0, True)]),
    # the sweep goes back across it: the sweep's
    ((4.0, 2.0, 3.0, 3.0), 0.0, np.arange(200.0, 99.0, -1.0), [(180.0, False)]),
    # passed on the way down from 190°, the sweep comes back up and ends on it
    ((5.0, 2.0, 5.0, 2.0), np.radians(190.0), np.arange(170.0, 180.5, 1.0), [(180.0, True)]),
])
def test_each_change_point_is_placed_on_the_way_or_in_the_sweep(dims, guess_input, inputs, expected):
    """Every change point passed is reported once (report mode), said to lie on the way from the default
    guess to the sweep's start where only that march passes it, with the event's branch in the same words."""
    guess = {"theta3": 0.3, "theta4": 1.0 if guess_input else 1.5}
    if guess_input > 3.0:  # (near the parallelogram at 190°)
        guess = {"theta3": 0.1, "theta4": guess_input - 0.07}
    mech = _four_bar_loop(dims, guess, guess_input)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(np.radians(inputs), on_singular="report")
    events = [e for e in sweep.events if e.kind == "change point"]
    got = [(round(float(np.degrees(e.input_value)), 4), "before the sweep" in e.message) for e in events]
    assert got == expected
    for e, (_, before) in zip(events, expected):
        assert (e.branch == "the branch the guess was on") == before


# The non-Grashof four-bar 4/3/2/2.5: its crank reaches a limit where coupler and rocker line up,
# |A - O4| = r3 + r4, at cos t = (16 + 9 - 20.25) / 24.
TOGGLE_DIMS = (4.0, 3.0, 2.0, 2.5)
TOGGLE = float(np.arccos((16.0 + 9.0 - 4.5**2) / 24.0))


def _toggle_branch(inputs):
    """theta4 (rad) of the 4/3/2/2.5 on the guess's branch, by circle intersection."""
    return closed_form(inputs, *TOGGLE_DIMS, 1.0)[1]


@pytest.mark.parametrize("inputs", [
    np.linspace(TOGGLE - 0.5, TOGGLE, 11),  # a sweep that ends on the toggle
    np.linspace(TOGGLE - 0.5, TOGGLE, 2),
    np.linspace(TOGGLE, TOGGLE - 0.5, 11),  # one that starts on it (reached from the guess) and goes back
])
@pytest.mark.parametrize("on_singular", ["raise", "report"])
def test_a_toggle_at_a_march_end_is_reached_not_called_a_change_point(inputs, on_singular):
    """The crank is driven up to its limit and no further: the point there is a solution (the two
    assemblies meet), near-singular, and no change point is passed (a march ending on it saw either
    sign of the Jacobian there: a change point was reported, or raised, before)."""
    mech = _four_bar_loop(TOGGLE_DIMS, {"theta3": 0.5, "theta4": 1.5}, TOGGLE - 0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(inputs, on_singular=on_singular)
    assert [e.kind for e in sweep.events] == ["near-singular"]
    miss = _wrap(sweep["theta4"] - _toggle_branch(inputs))
    at = np.abs(inputs - TOGGLE) < 1e-12
    assert miss[~at].max() < 1e-9
    assert miss[at].max() < 1e-6  # a double root: half the digits
    with pytest.raises(BranchError) as err:  # and not past it
        mech.sweep(np.linspace(TOGGLE - 0.5, TOGGLE + 0.01, 11), on_singular=on_singular)
    assert err.value.kind == "toggle"


# ------------------------------------------------------ where a change point is placed, and once
@pytest.mark.parametrize("ratio", [0.9, 0.1, 0.01])
def test_a_change_point_is_raised_where_it_is(ratio):
    """a/b/a/b meets its other branch at 180°: on a grid around it (not on it), in raise mode, the
    error's input is 180° to the localisation of a crossing (far below a 1e-5 rad step), whatever the crank."""
    mech = linkages.four_bar(1.0, ratio, 1.0, ratio)
    with pytest.raises(BranchError) as err:
        mech.sweep(np.radians(np.arange(170.5, 190.0, 1.0)))
    assert err.value.kind == "change point" and abs(err.value.input_value - np.pi) < 1e-6


def test_a_change_point_passed_is_reported_once():
    mech = linkages.four_bar(1.0, 0.01, 1.0, 0.01)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(np.radians(np.arange(170.0, 191.0)), on_singular="report")
    changes = [e for e in sweep.events if e.kind == "change point"]
    assert len(changes) == 1 and abs(changes[0].input_value - np.pi) < 1e-6
    assert np.abs(_wrap(sweep["theta4"] - sweep.inputs)).max() < 1e-6  # the parallelogram, kept


def test_nodes_on_change_points_keep_the_tangent_continuous_branch():
    """4/0.2/8.2/4.4 (0.2 + 8.2 = 4 + 4.4) meets its other assembly at 0° each turn; with 1° nodes every
    45° grid point is a node, 360° and 720° among them. The branch whose tangent is continuous swaps
    circle intersections at each (closed form), and each change point is reported there."""
    dims = (4.0, 0.2, 8.2, 4.4)
    deg = np.arange(270.0, 946.0, 45.0)
    inputs = np.radians(deg)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = linkages.four_bar(*dims).sweep(inputs, on_singular="report", max_step=np.radians(1.0))
    changes = sorted(e.input_value for e in sweep.events if e.kind == "change point")
    np.testing.assert_allclose(changes, np.radians([360.0, 720.0]), atol=1e-6)
    open_side = (deg < 360) | (deg > 720)
    reference = np.where(open_side, closed_form(inputs, *dims, 1.0)[1], closed_form(inputs, *dims, -1.0)[1])
    miss = _wrap(sweep["theta4"] - reference)
    on = (deg == 360) | (deg == 720)
    assert miss[~on].max() < 1e-12 and miss[on].max() < 1e-6


def _two_change_point_loops(delta):
    """Two 4/2/3/3 four-bars (2 + 4 = 3 + 3) on one crank, the second's ground turned by ``delta`` (rad):
    change points at 180° (loop A) and 180° + delta (loop B), where each loop's crank, coupler and
    rocker line up. The default guess at 0°."""
    import sympy as sp

    from numkin import Loop, Mechanism

    t2, t3, t4, t5, t6 = sp.symbols("theta2 theta3 theta4 theta5 theta6")
    a = Loop.from_vectors([(2, t2), (3, t3), (-3, t4), (-4, 0)], [t3, t4], name="A")
    b = Loop.from_vectors([(2, t2), (3, t5), (-3, t6), (-4, delta)], [t5, t6], name="B")
    guess = {"theta3": 0.3, "theta4": 1.5, "theta5": 0.3, "theta6": 1.5}
    return Mechanism([a, b], t2, {}, guess=guess, guess_input=0.0)


def test_two_loops_on_change_points_in_one_step_are_both_reported():
    """Both loops pass their change point at 180° in the same step: report mode describes each, raise
    mode raises at the first."""
    mech = _two_change_point_loops(0.0)
    inputs = np.radians(np.arange(170.0, 191.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(inputs, on_singular="report")
    changes = [(e.loop, e.input_value) for e in sweep.events if e.kind == "change point"]
    assert sorted(loop for loop, _ in changes) == ["A", "B"]
    assert all(abs(tc - np.pi) < 1e-7 for _, tc in changes)
    with pytest.raises(BranchError) as err:
        mech.sweep(inputs)
    assert err.value.kind == "change point" and abs(err.value.input_value - np.pi) < 1e-7


@pytest.mark.parametrize("downward", [False, True])
def test_the_first_of_two_close_change_points_is_raised(downward):
    """Change points 5e-6 rad apart (loop A at 180°, loop B just after): raise mode names the first the
    sweep passes, A going up, B coming down; report mode lists both, in the order passed."""
    delta = 5e-6
    mech = _two_change_point_loops(delta)
    deg = np.arange(190.0, 169.0, -1.0) if downward else np.arange(170.0, 191.0)
    inputs = np.radians(deg)
    start = closed_form(inputs[:1], 4.0, 2.0, 3.0, 3.0, 1.0 if downward else -1.0)  # the branch at the start
    turned = closed_form(inputs[:1] - delta, 4.0, 2.0, 3.0, 3.0, 1.0 if downward else -1.0)
    guess = np.array([start[0][0], start[1][0], turned[0][0] + delta, turned[1][0] + delta])
    first, second = (("B", np.pi + delta), ("A", np.pi)) if downward else (("A", np.pi), ("B", np.pi + delta))
    with pytest.raises(BranchError) as err:
        mech.sweep(inputs, guess=guess)
    assert (err.value.loop, err.value.kind) == (first[0], "change point")
    assert abs(err.value.input_value - first[1]) < 1e-8
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep = mech.sweep(inputs, guess=guess, on_singular="report")
    changes = [(e.loop, e.input_value) for e in sweep.events if e.kind == "change point"]
    assert [loop for loop, _ in changes] == [first[0], second[0]]
    assert abs(changes[0][1] - first[1]) < 1e-8 and abs(changes[1][1] - second[1]) < 1e-8

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

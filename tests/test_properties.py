"""Property-based tests (hypothesis) over random assemblable linkages.

* loop closure holds at every point (the residual recomputed here from the
  lengths and the solved angles);
* the sweep stays on one branch (the sign of sin(theta3 - theta4) is
  constant, the angles never jump, and they equal the circle intersection);
* scaling every length by k scales the lengths by k and leaves the angles
  unchanged.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from numkin import linkages

SETTINGS = settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
SCALES = st.sampled_from([1e-6, 1e-3, 0.37, 1.0, 12.5, 1e3])
TWO_PI = 2 * math.pi


@st.composite
def crank_rockers(draw):
    """Grashof crank-rockers: the crank strictly shortest, s + l at least 5 % of l below p + q."""
    crank = draw(st.floats(0.2, 2.0))
    ground, coupler, rocker = (draw(st.floats(1.25 * crank, 10.0)) for _ in range(3))
    s, p, q, l = sorted([crank, ground, coupler, rocker])
    assume(s == crank)
    assume(p + q - (s + l) >= 0.05 * l)
    return ground, crank, coupler, rocker


@st.composite
def slider_cranks(draw):
    crank = draw(st.floats(0.2, 2.0))
    offset = draw(st.floats(-1.5, 1.5))
    rod = draw(st.floats(crank + abs(offset) + 0.1 * crank, 12.0))
    return crank, rod, offset


def inputs_from(start):
    return start + np.radians(np.arange(0.0, 361.0, 5.0))


def circle_intersection_open(theta2, r1, r2, r3, r4):
    ax, ay = r2 * np.cos(theta2), r2 * np.sin(theta2)
    dx, dy = r1 - ax, -ay
    d = np.hypot(dx, dy)
    along = (r3**2 - r4**2 + d**2) / (2 * d)
    h = np.sqrt(np.maximum(r3**2 - along**2, 0.0))
    bx, by = ax + (along * dx - h * dy) / d, ay + (along * dy + h * dx) / d
    return np.arctan2(by - ay, bx - ax), np.arctan2(by, bx - r1)


def same_angles(a, b, atol):
    """Equal up to one 2 pi multiple per row."""
    k = np.round((a[..., :1] - b[..., :1]) / TWO_PI)
    np.testing.assert_allclose(a, b + TWO_PI * k, rtol=0, atol=atol)


@SETTINGS
@given(dims=crank_rockers(), start=st.floats(-math.pi, math.pi))
def test_four_bar_closure_branch_and_closed_form(dims, start):
    r1, r2, r3, r4 = dims
    theta2 = inputs_from(start)
    sweep = linkages.four_bar(*dims).sweep(theta2)
    t3, t4 = sweep["theta3"], sweep["theta4"]
    scale = max(dims)
    # loop closure, recomputed from the lengths and the solved angles
    re = r2 * np.cos(theta2) + r3 * np.cos(t3) - r4 * np.cos(t4) - r1
    im = r2 * np.sin(theta2) + r3 * np.sin(t3) - r4 * np.sin(t4)
    assert np.max(np.hypot(re, im)) <= 1e-11 * scale
    # one branch: the transmission angle never passes 0 or pi, angles never jump
    sign = np.sign(np.sin(t4 - t3))
    assert np.all(sign == sign[0]) and sign[0] != 0
    assert np.max(np.abs(np.diff(t3))) < 1.0 and np.max(np.abs(np.diff(t4))) < 1.0
    ref3, ref4 = circle_intersection_open(theta2, *dims)
    same_angles(t3, np.unwrap(ref3), 1e-9)
    same_angles(t4, np.unwrap(ref4), 1e-9)


@SETTINGS
@given(dims=crank_rockers(), k=SCALES)
def test_four_bar_scaling(dims, k):
    theta2 = inputs_from(0.3)
    base = linkages.four_bar(*dims).sweep(theta2)
    scaled = linkages.four_bar(*(k * d for d in dims)).sweep(theta2)
    np.testing.assert_allclose(scaled.values, base.values, rtol=0, atol=1e-10)
    pb, ps = base.points(), scaled.points()
    for name in ("A", "B", "O4"):
        np.testing.assert_allclose(ps[name], k * pb[name], rtol=0, atol=1e-10 * k * max(dims))
    assert np.max(np.abs(scaled.iterations - base.iterations)) <= 1  # same work, up to a borderline step


@SETTINGS
@given(dims=slider_cranks(), start=st.floats(-math.pi, math.pi))
def test_slider_crank_closure_and_closed_form(dims, start):
    r, rod, e = dims
    theta = inputs_from(start)
    sweep = linkages.slider_crank(*dims).sweep(theta)
    t3, x = sweep["theta3"], sweep["x"]
    re = r * np.cos(theta) + rod * np.cos(t3) - x
    im = r * np.sin(theta) + rod * np.sin(t3) - e
    assert np.max(np.hypot(re, im)) <= 1e-11 * max(r, rod, abs(e))
    assert np.all(np.cos(t3) > 0)  # piston on the +x side throughout: one branch
    s = r * np.sin(theta) - e
    np.testing.assert_allclose(x, r * np.cos(theta) + np.sqrt(rod**2 - s**2), rtol=0, atol=1e-10 * rod)
    same_angles(t3, np.arcsin(-s / rod), 1e-10)


@SETTINGS
@given(dims=slider_cranks(), k=SCALES)
def test_slider_crank_scaling(dims, k):
    theta = inputs_from(-1.0)
    base = linkages.slider_crank(*dims).sweep(theta)
    scaled = linkages.slider_crank(*(k * d for d in dims)).sweep(theta)
    np.testing.assert_allclose(scaled["theta3"], base["theta3"], rtol=0, atol=1e-10)
    np.testing.assert_allclose(scaled["x"], k * base["x"], rtol=0, atol=1e-10 * k * dims[1])

"""The six-bar with a slider of the source document 001."""

from __future__ import annotations

import math

from ..errors import InputError
from .base import Dimension, LinkageSpec, build, finite, length, pair

__all__ = ["six_bar", "SPEC"]


def six_bar(
    crank=1.0, coupler=4.0, o4b=3.0, bc=3.2, o4c=6.0, rod=6.5, o4=(3.7, -2.0), slider_y=3.0,
    *, length_unit: str = "cm",
):
    """The six-bar with a slider of the source document 001.

    Crank O2A (``crank``, angle theta2) about the origin; coupler AB
    (``coupler``, theta3); ternary rocker O4-B-C about ``o4`` with O4B =
    ``o4b`` (angle theta4), BC = ``bc``, O4C = ``o4c``; rod CD (``rod``,
    theta5, the angle of D->C) to the slider D on the line y = ``slider_y``,
    at x (measured from O2). BC makes the fixed angle beta = pi - angle(O4BC)
    with O4B. Loops::

        r2 e^{i theta2} + r3 e^{i theta3} - r4 e^{i theta4} - O4 = 0
        O4 + r4 e^{i theta4} + bc e^{i(theta4 + beta)} - r5 e^{i theta5} - (x + i y_D) = 0

    Returns
    -------
    Mechanism
        Input ``theta2``; unknowns ``theta3``, ``theta4``, ``theta5``, ``x``.
        The default branch is the one report 001's fixed guesses pick at theta2 = 0
        (x_D(0) = -1.77881; the report shows x_D only as plots).

    Examples
    --------
    >>> import numpy as np
    >>> res = six_bar().solve(0.0)
    >>> round(float(res.x[3]), 5)
    -1.77881
    """
    l2, l3 = length("crank", crank), length("coupler", coupler)
    l41, l42, l43, l5 = length("o4b", o4b), length("bc", bc), length("o4c", o4c), length("rod", rod)
    ox, oy = pair("o4", o4)
    yd = finite("slider_y", slider_y)
    cos_b = (l41**2 + l42**2 - l43**2) / (2 * l41 * l42)
    if not -1 < cos_b < 1:
        raise InputError(f"o4b = {l41:g}, bc = {l42:g}, o4c = {l43:g} do not form a triangle (ternary link)")
    beta_val = math.pi - math.acos(cos_b)

    def guess(theta2):
        ax, ay = l2 * math.cos(theta2), l2 * math.sin(theta2)
        dx, dy = ox - ax, oy - ay
        d = math.hypot(dx, dy)
        g = math.acos(max(-1.0, min(1.0, (l3**2 + d**2 - l41**2) / (2 * l3 * d))))
        th3 = math.atan2(dy, dx) + g
        bx, by = ax + l3 * math.cos(th3), ay + l3 * math.sin(th3)
        th4 = math.atan2(by - oy, bx - ox)
        cx, cy = bx + l42 * math.cos(th4 + beta_val), by + l42 * math.sin(th4 + beta_val)
        s = max(-1.0, min(1.0, (cy - yd) / l5))
        th5 = math.asin(s)
        return {"theta3": th3, "theta4": th4, "theta5": th5, "x": cx - l5 * math.cos(th5)}

    return build(
        SPEC, _model, [l2, l3, l41, l42, l5, ox, oy, yd, beta_val], name="six-bar with slider", guess=guess,
        length_unit=length_unit, length_scale=max(l2, l3, l41, l42, l43, l5),
    )


def _model():
    """The loops and points, dimensions as symbols (see :func:`numkin.linkages.base.build`)."""
    import sympy as sp

    from ..loops import Loop

    t2, t3, t4, t5, x = sp.symbols("theta2 theta3 theta4 theta5 x", real=True)
    L2, L3, L41, L42, L5, OX, OY, YD, BETA = sp.symbols("l2 l3 l41 l42 l5 o4x o4y y_d beta", real=True)
    half = sp.pi / 2
    loop1 = Loop.from_vectors(
        [(L2, t2), (L3, t3), (-L41, t4), (-OX, 0), (-OY, half)], [t3, t4], name="O2-A-B-O4"
    )
    loop2 = Loop.from_vectors(
        [(OX, 0), (OY, half), (L41, t4), (L42, t4 + BETA), (-L5, t5), (-x, 0), (-YD, half)],
        [t5, x], name="O4-B-C-D",
    )
    points = {
        "O2": (0, 0), "A": (L2 * sp.cos(t2), L2 * sp.sin(t2)), "O4": (OX, OY),
        "B": (OX + L41 * sp.cos(t4), OY + L41 * sp.sin(t4)),
        "C": (OX + L41 * sp.cos(t4) + L42 * sp.cos(t4 + BETA), OY + L41 * sp.sin(t4) + L42 * sp.sin(t4 + BETA)),
        "D": (x, YD),
    }
    return [loop1, loop2], t2, (L2, L3, L41, L42, L5, OX, OY, YD, BETA), points


SPEC = LinkageSpec(
    name="six_bar",
    build=six_bar,
    summary="six-bar with a slider: four-bar O2-A-B-O4, ternary rocker O4-B-C, rod CD to the slider D",
    dimensions=(
        Dimension("crank", "length", "O2A", default=1.0),
        Dimension("coupler", "length", "AB", default=4.0),
        Dimension("o4b", "length", "O4B", default=3.0),
        Dimension("bc", "length", "BC", default=3.2),
        Dimension("o4c", "length", "O4C", default=6.0),
        Dimension("rod", "length", "CD", default=6.5),
        Dimension("o4", "pair", "the rocker pivot O4 (x, y)", default=(3.7, -2.0)),
        Dimension("slider_y", "signed", "height of the slider line of D", default=3.0),
    ),
    input="theta2",
    unknowns=(("theta3", "angle"), ("theta4", "angle"), ("theta5", "angle"), ("x", "length")),
    length_unit="cm",
    guess="the branch report 001's fixed guesses pick (x_D(0) = -1.77881), by circle intersections at every input",
    points=("O2", "A", "O4", "B", "C", "D"),
    links=(("O2", "A"), ("A", "B"), ("O4", "B", "C", "O4"), ("C", "D")),
    ground=("O2", "O4"),
)

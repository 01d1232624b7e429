"""The four-bar linkage (crank O2A, coupler AB, rocker O4B) and its Grashof class."""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from .base import Dimension, LinkageSpec, build, length

__all__ = ["four_bar", "grashof", "SPEC"]


def grashof(ground: float, crank: float, coupler: float, rocker: float) -> str:
    """Grashof class of a four-bar, as a phrase.

    ``s + l < p + q`` is Grashof (the shortest link turns fully), ``s + l =
    p + q`` a change-point linkage, ``s + l > p + q`` a non-Grashof triple
    rocker, unless ``l > s + p + q``: then the four links never close.

    Examples
    --------
    >>> grashof(7, 4, 3, 5)
    'non-Grashof triple rocker'
    >>> grashof(10, 6, 1, 1)
    'non-assemblable four-bar (l > s + p + q)'
    >>> grashof(4, 1, 3, 3)
    'Grashof crank-rocker'
    """
    links = {name: length(name, value)
             for name, value in (("ground", ground), ("crank", crank), ("coupler", coupler), ("rocker", rocker))}
    ordered = sorted(links.values())
    s, p, q, l = ordered
    total = s + l - (p + q)
    if l > (s + p + q) * (1.0 + 1e-12):
        return "non-assemblable four-bar (l > s + p + q)"
    if abs(total) <= 1e-12 * l:
        return "change-point (s + l = p + q)"
    if total > 0:
        return "non-Grashof triple rocker"
    shortest = min(links, key=links.get)
    return {
        "ground": "Grashof double crank",
        "crank": "Grashof crank-rocker",
        "coupler": "Grashof double rocker",
        "rocker": "Grashof rocker-crank",
    }[shortest]


def closed_form(t2, r1, r2, r3, r4, sign):
    """Circle intersection: (theta3, theta4) of the crank-at-origin four-bar; sign +1 open, -1 crossed.

    Examples
    --------
    >>> t3, t4 = closed_form(0.0, 4, 1, 3, 3, 1.0)
    >>> round(float(np.degrees(t4)), 4)
    120.0
    """
    ax, ay = r2 * np.cos(t2), r2 * np.sin(t2)
    dx, dy = r1 - ax, -ay
    d = np.hypot(dx, dy)
    # with A on O4 (d = 0) the coupler's direction is free: any angle is as good a guess
    cos_gamma = (r3**2 + d**2 - r4**2) / (2 * r3 * np.where(d > 0, d, 1.0))
    gamma = np.arccos(np.clip(np.where(d > 0, cos_gamma, 0.0), -1, 1))
    t3 = np.arctan2(dy, dx) + sign * gamma
    bx, by = ax + r3 * np.cos(t3), ay + r3 * np.sin(t3)
    t4 = np.arctan2(by, bx - r1)
    return t3, t4


def _closed_form1(t2: float, r1, r2, r3, r4, sign) -> tuple[float, float]:
    """:func:`closed_form` at one input, in plain floats (a sweep's default guess: no arrays to set up).

    Examples
    --------
    >>> t2 = np.radians(73.0)
    >>> np.allclose(_closed_form1(t2, 4, 1, 3, 3, -1.0), closed_form(t2, 4, 1, 3, 3, -1.0), rtol=0, atol=1e-15)
    True
    """
    ax, ay = r2 * math.cos(t2), r2 * math.sin(t2)
    dx, dy = r1 - ax, -ay
    d = math.hypot(dx, dy)
    cos_gamma = (r3**2 + d**2 - r4**2) / (2 * r3 * d) if d > 0 else 0.0
    t3 = math.atan2(dy, dx) + sign * math.acos(min(1.0, max(-1.0, cos_gamma)))
    return t3, math.atan2(ay + r3 * math.sin(t3), ax + r3 * math.cos(t3) - r1)


def crank_range_check(r1, r2, r3, r4, klass, input_name="theta2"):
    """Assembly check of a four-bar loop: the crank tip must be within reach of the rocker pivot.

    Returns ``check(inputs) -> str | None`` (see ``Mechanism(assembly_check=)``).

    Examples
    --------
    >>> check = crank_range_check(4, 1, 3, 1.5, "non-Grashof triple rocker")
    >>> check(np.radians([0.0])) is None
    True
    >>> check(np.radians([180.0]))
    'a non-Grashof triple rocker: it can be assembled only for |theta2| <= 113.97° (angles mod 360°); the sweep asks for theta2 = 180.00°'
    """
    lo, hi = abs(r3 - r4), r3 + r4

    def cos_limit(dist):
        return (r1**2 + r2**2 - dist**2) / (2 * r1 * r2)

    # d(theta)^2 = r1^2 + r2^2 - 2 r1 r2 cos(theta) must lie in [lo^2, hi^2]
    c_min, c_max = cos_limit(hi), cos_limit(lo)  # need c_min <= cos(theta) <= c_max

    def check(inputs):
        if c_min - 1e-12 <= -1.0 and c_max + 1e-12 >= 1.0:  # every crank angle reaches: nothing to test
            return None
        c = np.cos(inputs)
        bad = (c < c_min - 1e-12) | (c > c_max + 1e-12)
        if not bad.any():
            return None
        first = float(inputs[np.flatnonzero(bad)[0]])
        asked = f"the sweep asks for {input_name} = {math.degrees(first):.2f}°"
        if c_min > 1 or c_max < -1 or c_min > c_max:
            return f"a {klass}: it cannot be assembled at any input angle; {asked}"
        parts = []
        if c_min > -1:
            parts.append(f"|{input_name}| <= {math.degrees(math.acos(c_min)):.2f}°")
        if c_max < 1:
            parts.append(f"|{input_name}| >= {math.degrees(math.acos(c_max)):.2f}°")
        return f"a {klass}: it can be assembled only for {' and '.join(parts)} (angles mod 360°); {asked}"

    return check


def four_bar(ground, crank, coupler, rocker, *, branch: str = "open", length_unit: str = "mm"):
    """Four-bar linkage: crank pivot O2 at the origin, rocker pivot O4 at (ground, 0).

    Loop ``r2 e^{i theta2} + r3 e^{i theta3} - r4 e^{i theta4} - r1 = 0``;
    angles from +x, counter-clockwise, rad.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths r1, r2, r3, r4 (positive).
    branch : {"open", "crossed"}
        Assembly branch: ``"open"`` has the coupler turned counter-clockwise
        from the line A-O4 (a convex quadrilateral for 0 < theta2 < pi).

    Returns
    -------
    Mechanism
        Input ``theta2``; unknowns ``theta3`` (coupler), ``theta4`` (rocker).

    Examples
    --------
    >>> import numpy as np
    >>> m = four_bar(4, 1, 3, 3)
    >>> res = m.solve(np.radians(90))
    >>> np.round(np.degrees(res.x), 4)
    array([ 32.5561, 119.3714])
    """
    r1, r2 = length("ground", ground), length("crank", crank)
    r3, r4 = length("coupler", coupler), length("rocker", rocker)
    if branch not in SPEC.branches:
        raise InputError(f"branch must be 'open' or 'crossed', got {branch!r}")
    sign = 1.0 if branch == "open" else -1.0
    klass = grashof(r1, r2, r3, r4)
    label = f"four-bar (ground {r1:g}, crank {r2:g}, coupler {r3:g}, rocker {r4:g})"

    def guess(theta2):
        a, b = _closed_form1(float(theta2), r1, r2, r3, r4, sign)
        return {"theta3": a, "theta4": b}

    return build(
        SPEC, _model, [r1, r2, r3, r4], name=label, guess=guess, length_unit=length_unit, branch=branch,
        assembly_check=crank_range_check(r1, r2, r3, r4, klass),
    )


def _model():
    """The loop and points, dimensions as symbols r1..r4 (see :func:`numkin.linkages.base.build`)."""
    import sympy as sp

    from ..loops import Loop

    t2, t3, t4 = sp.symbols("theta2 theta3 theta4", real=True)
    R1, R2, R3, R4 = sp.symbols("r1 r2 r3 r4", real=True)
    loop = Loop.from_vectors([(R2, t2), (R3, t3), (-R4, t4), (-R1, 0)], [t3, t4], name="O2-A-B-O4")
    points = {
        "O2": (0, 0), "A": (R2 * sp.cos(t2), R2 * sp.sin(t2)),
        "B": (R1 + R4 * sp.cos(t4), R4 * sp.sin(t4)), "O4": (R1, 0),
    }
    return [loop], t2, (R1, R2, R3, R4), points


SPEC = LinkageSpec(
    name="four_bar",
    build=four_bar,
    summary="four-bar: crank O2A, coupler AB, rocker O4B, ground O2O4 along +x",
    dimensions=(
        Dimension("ground", "length", "r1, O2O4"),
        Dimension("crank", "length", "r2, O2A"),
        Dimension("coupler", "length", "r3, AB"),
        Dimension("rocker", "length", "r4, O4B"),
    ),
    input="theta2",
    unknowns=(("theta3", "angle"), ("theta4", "angle")),
    length_unit="mm",
    branches=("open", "crossed"),
    guess="circle intersection on the chosen branch, at every input",
    points=("O2", "A", "B", "O4"),
    links=(("O2", "A"), ("A", "B"), ("B", "O4")),
    ground=("O2", "O4"),
)

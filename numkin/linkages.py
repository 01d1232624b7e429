"""Ready-made linkages, built on the same loop API a user writes.

Every function returns a :class:`~numkin.Mechanism` whose unknowns carry the
source documents' names, with a default guess on its documented branch, so
``linkage.sweep(inputs)`` works without a guess. Lengths are in the unit the
dimensions are given in (default mm); angles in rad.

=======================  ===================================  ==========================
linkage                  unknowns                             input
=======================  ===================================  ==========================
``four_bar``             theta3, theta4                       theta2 (crank)
``slider_crank``         theta3, x                            theta (crank)
``quick_return``         r3, theta3, r4, r5                   theta2 (crank)
``six_bar``              theta3, theta4, theta5, x            theta2 (crank)
``chained_four_bars``    phi, psi, beta, gamma                theta (input of linkage 1)
=======================  ===================================  ==========================
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from .loops import Loop
from .mechanism import Mechanism

__all__ = ["four_bar", "slider_crank", "quick_return", "six_bar", "chained_four_bars", "grashof"]

_pi = sp.pi


def _length(name: str, value) -> float:
    """A link length: a finite positive number, or a ValueError naming it."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is not a number") from None
    if not math.isfinite(v) or v <= 0:
        raise ValueError(f"{name} = {value!r} must be a positive, finite length")
    return v


def _finite(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is not a number") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} = {value!r} is not finite")
    return v


def _symbols(names: str):
    return sp.symbols(names, real=True)


# --------------------------------------------------------------------- four-bar
def grashof(ground: float, crank: float, coupler: float, rocker: float) -> str:
    """Grashof class of a four-bar, as a phrase.

    ``s + l < p + q`` is Grashof (the shortest link turns fully), ``s + l =
    p + q`` a change-point linkage, ``s + l > p + q`` a non-Grashof triple
    rocker.

    Examples
    --------
    >>> grashof(7, 4, 3, 5)
    'non-Grashof triple rocker'
    >>> grashof(4, 1, 3, 3)
    'Grashof crank-rocker'
    """
    links = {"ground": ground, "crank": crank, "coupler": coupler, "rocker": rocker}
    ordered = sorted(links.values())
    s, p, q, l = ordered
    total = s + l - (p + q)
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


def _four_bar_closed_form(t2, r1, r2, r3, r4, sign):
    """Circle intersection: (theta3, theta4) of the crank-at-origin four-bar; sign +1 open, -1 crossed."""
    ax, ay = r2 * np.cos(t2), r2 * np.sin(t2)
    dx, dy = r1 - ax, -ay
    d = np.hypot(dx, dy)
    gamma = np.arccos(np.clip((r3**2 + d**2 - r4**2) / (2 * r3 * d), -1, 1))
    t3 = np.arctan2(dy, dx) + sign * gamma
    bx, by = ax + r3 * np.cos(t3), ay + r3 * np.sin(t3)
    t4 = np.arctan2(by, bx - r1)
    return t3, t4


def _crank_range_check(r1, r2, r3, r4, klass, input_name="theta2"):
    """Assembly check of a four-bar loop: the crank tip must be within reach of the rocker pivot."""
    lo, hi = abs(r3 - r4), r3 + r4

    def cos_limit(dist):
        return (r1**2 + r2**2 - dist**2) / (2 * r1 * r2)

    # d(theta)^2 = r1^2 + r2^2 - 2 r1 r2 cos(theta) must lie in [lo^2, hi^2]
    c_min, c_max = cos_limit(hi), cos_limit(lo)  # need c_min <= cos(theta) <= c_max

    def check(inputs):
        c = np.cos(inputs)
        bad = (c < c_min - 1e-12) | (c > c_max + 1e-12)
        if not bad.any():
            return None
        first = float(inputs[np.flatnonzero(bad)[0]])
        if c_min > 1 or c_max < -1 or c_min > c_max:
            where = "at no input angle (it cannot be assembled at all)"
        else:
            parts = []
            if c_min > -1:
                parts.append(f"|{input_name}| <= {math.degrees(math.acos(c_min)):.2f}°")
            if c_max < 1:
                parts.append(f"|{input_name}| >= {math.degrees(math.acos(c_max)):.2f}°")
            where = "only for " + " and ".join(parts) + " (angles mod 360°)"
        return (
            f"a {klass}: it can be assembled {where}; "
            f"the sweep asks for {input_name} = {math.degrees(first):.2f}°"
        )

    return check


def four_bar(ground, crank, coupler, rocker, *, branch: str = "open", length_unit: str = "mm") -> Mechanism:
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
    r1, r2 = _length("ground", ground), _length("crank", crank)
    r3, r4 = _length("coupler", coupler), _length("rocker", rocker)
    if branch not in ("open", "crossed"):
        raise ValueError(f"branch must be 'open' or 'crossed', got {branch!r}")
    sign = 1.0 if branch == "open" else -1.0
    t2, t3, t4 = _symbols("theta2 theta3 theta4")
    R1, R2, R3, R4 = _symbols("r1 r2 r3 r4")
    loop = Loop.from_vectors([(R2, t2), (R3, t3), (-R4, t4), (-R1, 0)], [t3, t4], name="O2-A-B-O4")
    klass = grashof(r1, r2, r3, r4)
    label = f"four-bar (ground {r1:g}, crank {r2:g}, coupler {r3:g}, rocker {r4:g})"

    def guess(theta2):
        a, b = _four_bar_closed_form(theta2, r1, r2, r3, r4, sign)
        return {"theta3": float(a), "theta4": float(b)}

    return Mechanism(
        [loop], t2, {R1: r1, R2: r2, R3: r3, R4: r4},
        name=label, guess=guess, length_unit=length_unit,
        points={
            "O2": (0, 0), "A": (R2 * sp.cos(t2), R2 * sp.sin(t2)),
            "B": (R1 + R4 * sp.cos(t4), R4 * sp.sin(t4)), "O4": (R1, 0),
        },
        links=[("O2", "A"), ("A", "B"), ("B", "O4")], ground=("O2", "O4"),
        assembly_check=_crank_range_check(r1, r2, r3, r4, klass),
    )


# ------------------------------------------------------------------ slider-crank
def slider_crank(crank, rod, offset=0.0, *, length_unit: str = "mm") -> Mechanism:
    """In-line or offset slider-crank: crank about the origin, piston on the line y = offset.

    Loop ``r e^{i theta} + l e^{i theta3} - x - i e = 0``: the piston pin at
    (x, e), on the +x side of the crank.

    Parameters
    ----------
    crank, rod : float
        Crank radius r and connecting-rod length l (positive).
    offset : float
        Piston line offset e (may be zero or negative).

    Returns
    -------
    Mechanism
        Input ``theta``; unknowns ``theta3`` (rod angle, rad) and ``x`` (piston).

    Examples
    --------
    >>> import numpy as np
    >>> sc = slider_crank(80, 200)
    >>> round(float(sc.solve(np.pi / 2).x[1]), 6)   # sqrt(200**2 - 80**2)
    183.303028
    """
    r, rod_l = _length("crank", crank), _length("rod", rod)
    e = _finite("offset", offset)
    th, t3, x = _symbols("theta theta3 x")
    R, L, E = _symbols("r l e")
    loop = Loop.from_vectors([(R, th), (L, t3), (-x, 0), (-E, _pi / 2)], [t3, x], name="O-A-P")
    label = f"slider-crank (crank {r:g}, rod {rod_l:g}, offset {e:g})"

    def guess(theta):
        s = r * math.sin(theta) - e
        if abs(s) > rod_l:
            s = math.copysign(rod_l, s)
        return {"theta3": math.atan2(-s, math.sqrt(rod_l**2 - s**2)), "x": r * math.cos(theta) + math.sqrt(rod_l**2 - s**2)}

    def check(inputs):
        s = r * np.sin(inputs) - e
        bad = np.abs(s) > rod_l * (1 + 1e-12)
        if not bad.any():
            return None
        first = float(inputs[np.flatnonzero(bad)[0]])
        return (
            "the rod cannot reach the piston line where |r sin(theta) - e| > l, "
            f"e.g. theta = {math.degrees(first):.2f}° (a full turn needs rod >= crank + |offset|)"
        )

    return Mechanism(
        [loop], th, {R: r, L: rod_l, E: e},
        name=label, guess=guess, length_unit=length_unit, length_scale=max(r, rod_l, abs(e)),
        points={"O": (0, 0), "A": (R * sp.cos(th), R * sp.sin(th)), "P": (x, E)},
        links=[("O", "A"), ("A", "P")], ground=("O",), assembly_check=check,
    )


# ------------------------------------------------------------------ quick return
def quick_return(r1=60.0, r2=40.0, r6=60.0, *, length_unit: str = "mm") -> Mechanism:
    """The quick-return mechanism of the source document 000 (crank and slotted rocker).

    Rocker pivot O1 at the origin, crank pivot O2 = (0, r1); the crank O2A
    (length r2, angle theta2) drives the slider A in the slotted rocker O1B;
    the output slider B moves on the horizontal line y = r1 + r6, at r5 from
    C = (0, r1 + r6). Loops::

        i r1 + r2 e^{i theta2} - r3 e^{i theta3} = 0          (unknowns r3, theta3)
        i r1 + i r6 + r5 - r4 e^{i theta3} = 0                (unknowns r4, r5)

    Parameters
    ----------
    r1, r2, r6 : float
        O2O1, crank O2A and O2C, with r2 < r1 so the crank never passes O1.

    Returns
    -------
    Mechanism
        Input ``theta2``; unknowns ``r3``, ``theta3``, ``r4``, ``r5``;
        attribute ``time_ratio`` (forward / return stroke time).

    Examples
    --------
    >>> import numpy as np
    >>> qr = quick_return()
    >>> res = qr.solve(np.radians(30))
    >>> [round(float(v), 3) for v in (res.x[0], np.degrees(res.x[1]), res.x[2], res.x[3])]
    [87.178, 66.587, 130.767, 51.962]
    >>> round(qr.time_ratio, 3)
    2.735
    """
    a, b, c = _length("r1", r1), _length("r2", r2), _length("r6", r6)
    if b >= a:
        raise ValueError(f"r2 = {b:g} must be shorter than r1 = {a:g}: otherwise the crank passes the rocker pivot O1")
    t2, r3, t3, r4, r5 = _symbols("theta2 r3 theta3 r4 r5")
    R1, R2, R6 = _symbols("r1 r2 r6")
    loop1 = Loop.from_vectors([(R1, _pi / 2), (R2, t2), (-r3, t3)], [r3, t3], name="O1-O2-A")
    loop2 = Loop.from_vectors([(R1 + R6, _pi / 2), (r5, 0), (-r4, t3)], [r4, r5], name="O1-C-B")

    def guess(theta2):
        ax, ay = b * math.cos(theta2), a + b * math.sin(theta2)
        th3 = math.atan2(ay, ax)
        return {"r3": math.hypot(ax, ay), "theta3": th3, "r4": (a + c) / math.sin(th3), "r5": (a + c) / math.tan(th3)}

    beta = math.acos(b / a)
    mech = Mechanism(
        [loop1, loop2], t2, {R1: a, R2: b, R6: c},
        name=f"quick-return (r1 {a:g}, r2 {b:g}, r6 {c:g})", guess=guess, length_unit=length_unit,
        points={
            "O1": (0, 0), "O2": (0, R1), "A": (R2 * sp.cos(t2), R1 + R2 * sp.sin(t2)),
            "B": (r5, R1 + R6), "C": (0, R1 + R6),
        },
        links=[("O2", "A"), ("O1", "B")], ground=("O1", "O2"),
    )
    mech.time_ratio = (math.pi - beta) / beta
    return mech


# ---------------------------------------------------------------------- six-bar
def six_bar(
    crank=1.0, coupler=4.0, o4b=3.0, bc=3.2, o4c=6.0, rod=6.5, o4=(3.7, -2.0), slider_y=3.0,
    *, length_unit: str = "cm",
) -> Mechanism:
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
        The default branch is the document's (x_D(0) = -1.77881).

    Examples
    --------
    >>> import numpy as np
    >>> res = six_bar().solve(0.0)
    >>> round(float(res.x[3]), 5)
    -1.77881
    """
    l2, l3 = _length("crank", crank), _length("coupler", coupler)
    l41, l42, l43, l5 = _length("o4b", o4b), _length("bc", bc), _length("o4c", o4c), _length("rod", rod)
    ox, oy = _finite("o4[0]", o4[0]), _finite("o4[1]", o4[1])
    yd = _finite("slider_y", slider_y)
    cos_b = (l41**2 + l42**2 - l43**2) / (2 * l41 * l42)
    if not -1 < cos_b < 1:
        raise ValueError(f"o4b = {l41:g}, bc = {l42:g}, o4c = {l43:g} do not form a triangle (ternary link)")
    beta_val = math.pi - math.acos(cos_b)
    t2, t3, t4, t5, x = _symbols("theta2 theta3 theta4 theta5 x")
    L2, L3, L41, L42, L5, OX, OY, YD, BETA = _symbols("l2 l3 l41 l42 l5 o4x o4y y_d beta")
    loop1 = Loop.from_vectors(
        [(L2, t2), (L3, t3), (-L41, t4), (-OX, 0), (-OY, _pi / 2)], [t3, t4], name="O2-A-B-O4"
    )
    loop2 = Loop.from_vectors(
        [(OX, 0), (OY, _pi / 2), (L41, t4), (L42, t4 + BETA), (-L5, t5), (-x, 0), (-YD, _pi / 2)],
        [t5, x], name="O4-B-C-D",
    )
    params = {L2: l2, L3: l3, L41: l41, L42: l42, L5: l5, OX: ox, OY: oy, YD: yd, BETA: beta_val}

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

    return Mechanism(
        [loop1, loop2], t2, params,
        name="six-bar with slider", guess=guess, length_unit=length_unit,
        length_scale=max(l2, l3, l41, l42, l43, l5),
        points={
            "O2": (0, 0), "A": (L2 * sp.cos(t2), L2 * sp.sin(t2)), "O4": (OX, OY),
            "B": (OX + L41 * sp.cos(t4), OY + L41 * sp.sin(t4)),
            "C": (OX + L41 * sp.cos(t4) + L42 * sp.cos(t4 + BETA), OY + L41 * sp.sin(t4) + L42 * sp.sin(t4 + BETA)),
            "D": (x, YD),
        },
        links=[("O2", "A"), ("A", "B"), ("O4", "B", "C", "O4"), ("C", "D")], ground=("O2", "O4"),
    )


# ------------------------------------------------------------ chained four-bars
def chained_four_bars(
    fixed1=7.0, input1=1.94, coupler1=6.86, output1=2.36,
    fixed2=1.25, input2=2.39, coupler2=1.87, output2=1.26,
    offset=math.radians(149.0),
    guess1=(math.radians(45.0), math.radians(60.0)),
    guess2=(math.radians(30.0), math.radians(270.0)),
    *, length_unit: str = "in",
) -> Mechanism:
    """The two chained four-bars of the homework (source document 003).

    Written in the homework's own loop form: linkage 1,
    ``r2 e^{i phi} + r3 e^{i psi} + r4 e^{i(theta + pi)} = r1`` with r1 the
    fixed link, r4 the input, r3 the coupler and r2 the output; linkage 2 the
    same with its own lengths, unknowns (beta, gamma), and input angle
    ``alpha = phi + offset`` (149°: alpha = phi + 180° - 31°).

    Parameters
    ----------
    fixed1, input1, coupler1, output1 : float
        Linkage 1 (default 7.0, 1.94, 6.86, 2.36 in).
    fixed2, input2, coupler2, output2 : float
        Linkage 2 (default 1.25, 2.39, 1.87, 1.26 in).
    offset : float
        alpha - phi, rad.
    guess1, guess2 : pair of float
        The homework's starting guesses (phi, psi) and (beta, gamma) at theta = 0, rad.

    Returns
    -------
    Mechanism
        Input ``theta``; unknowns ``phi``, ``psi``, ``beta``, ``gamma``.

    Examples
    --------
    >>> import numpy as np
    >>> sweep = chained_four_bars().sweep(np.radians(np.arange(0, 101)))
    >>> round(float(np.degrees(sweep["phi"][100])), 4), round(float(np.degrees(sweep["beta"][100])), 4)
    (94.4375, 214.727)
    """
    names = ["fixed1", "input1", "coupler1", "output1", "fixed2", "input2", "coupler2", "output2"]
    vals = [fixed1, input1, coupler1, output1, fixed2, input2, coupler2, output2]
    f1, i1, c1, o1, f2, i2, c2, o2 = (_length(n, v) for n, v in zip(names, vals))
    off = _finite("offset", offset)
    g = [_finite(f"guess{k}", v) for k, pair in ((1, guess1), (2, guess2)) for v in pair]
    th, phi, psi, beta, gamma = _symbols("theta phi psi beta gamma")
    F1, I1, C1, O1, F2, I2, C2, O2, OFF = _symbols("fixed1 input1 coupler1 output1 fixed2 input2 coupler2 output2 offset")
    loop1 = Loop.from_vectors([(O1, phi), (C1, psi), (I1, th + _pi), (-F1, 0)], [phi, psi], name="linkage 1")
    alpha = phi + OFF
    loop2 = Loop.from_vectors([(O2, beta), (C2, gamma), (I2, alpha + _pi), (-F2, 0)], [beta, gamma], name="linkage 2")
    params = {F1: f1, I1: i1, C1: c1, O1: o1, F2: f2, I2: i2, C2: c2, O2: o2, OFF: off}
    return Mechanism(
        [loop1, loop2], th, params,
        name="chained four-bars", guess={"phi": g[0], "psi": g[1], "beta": g[2], "gamma": g[3]},
        guess_input=0.0, length_unit=length_unit, length_scale=max(f1, i1, c1, o1, f2, i2, c2, o2),
        points={
            "C": (0, 0), "B": (O1 * sp.cos(phi), O1 * sp.sin(phi)),
            "A": (F1 + I1 * sp.cos(th), I1 * sp.sin(th)), "D": (F1, 0),
            # linkage 2 drawn with its input pivot on linkage 1's output pivot C
            "E": (I2 * sp.cos(alpha), I2 * sp.sin(alpha)),
            "F": (-F2 + O2 * sp.cos(beta), O2 * sp.sin(beta)), "G": (-F2, 0),
        },
        links=[("D", "A"), ("A", "B"), ("B", "C"), ("C", "E"), ("E", "F"), ("F", "G")],
        ground=("C", "D", "G"),
    )

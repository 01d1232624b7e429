"""The quick-return mechanism of the source document 000 (crank and slotted rocker)."""

from __future__ import annotations

import math

from ..errors import InputError
from .base import Dimension, LinkageSpec, build, length

__all__ = ["quick_return", "SPEC"]


def quick_return(r1=60.0, r2=40.0, r6=60.0, *, length_unit: str = "mm"):
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
    a, b, c = length("r1", r1), length("r2", r2), length("r6", r6)
    if b >= a:
        raise InputError(f"r2 = {b:g} must be shorter than r1 = {a:g}: otherwise the crank passes the rocker pivot O1")

    def guess(theta2):
        ax, ay = b * math.cos(theta2), a + b * math.sin(theta2)
        th3 = math.atan2(ay, ax)
        return {"r3": math.hypot(ax, ay), "theta3": th3, "r4": (a + c) / math.sin(th3), "r5": (a + c) / math.tan(th3)}

    beta = math.acos(b / a)
    mech = build(SPEC, _model, [a, b, c], name=f"quick-return (r1 {a:g}, r2 {b:g}, r6 {c:g})", guess=guess,
                 length_unit=length_unit)
    mech.time_ratio = (math.pi - beta) / beta
    return mech


def _model():
    """The loops and points, dimensions as symbols r1, r2, r6 (see :func:`numkin.linkages.base.build`)."""
    import sympy as sp

    from ..loops import Loop

    t2, r3, t3, r4, r5 = sp.symbols("theta2 r3 theta3 r4 r5", real=True)
    R1, R2, R6 = sp.symbols("r1 r2 r6", real=True)
    loop1 = Loop.from_vectors([(R1, sp.pi / 2), (R2, t2), (-r3, t3)], [r3, t3], name="O1-O2-A")
    loop2 = Loop.from_vectors([(R1 + R6, sp.pi / 2), (r5, 0), (-r4, t3)], [r4, r5], name="O1-C-B")
    points = {
        "O1": (0, 0), "O2": (0, R1), "A": (R2 * sp.cos(t2), R1 + R2 * sp.sin(t2)),
        "B": (r5, R1 + R6), "C": (0, R1 + R6),
    }
    return [loop1, loop2], t2, (R1, R2, R6), points


SPEC = LinkageSpec(
    name="quick_return",
    build=quick_return,
    summary="quick-return: crank O2A drives slider A in the slotted rocker O1B; slider B on y = r1 + r6",
    dimensions=(
        Dimension("r1", "length", "O2O1, crank pivot above the rocker pivot", default=60.0),
        Dimension("r2", "length", "crank O2A (shorter than r1)", default=40.0),
        Dimension("r6", "length", "O2C, the output slider's line above O2", default=60.0),
    ),
    input="theta2",
    unknowns=(("r3", "length"), ("theta3", "angle"), ("r4", "length"), ("r5", "length")),
    length_unit="mm",
    guess="the slider A on the crank circle, at every input",
    points=("O1", "O2", "A", "B", "C"),
    links=(("O2", "A"), ("O1", "B")),
    ground=("O1", "O2"),
    dimension_lines=(
        ("O1", "O2", "r_1", 1.0), ("O2", "C", "r_6", 1.0), ("O2", "A", "r_2", 1.0),
        ("O1", "A", "r_3", -1.0), ("O1", "B", "r_4", -2.2), ("C", "B", "r_5", 1.0),
    ),
)

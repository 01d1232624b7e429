"""The in-line or offset slider-crank (crank OA, rod AP, piston P on a line)."""

from __future__ import annotations

import math

import numpy as np

from .base import Dimension, LinkageSpec, build, finite, length

__all__ = ["slider_crank", "SPEC"]


def slider_crank(crank, rod, offset=0.0, *, length_unit: str = "mm"):
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
    r, rod_l = length("crank", crank), length("rod", rod)
    e = finite("offset", offset)
    label = f"slider-crank (crank {r:g}, rod {rod_l:g}, offset {e:g})"

    def guess(theta):
        s = r * math.sin(theta) - e
        if abs(s) > rod_l:
            s = math.copysign(rod_l, s)
        return {"theta3": math.atan2(-s, math.sqrt(rod_l**2 - s**2)), "x": r * math.cos(theta) + math.sqrt(rod_l**2 - s**2)}

    def check(inputs):
        if r + abs(e) <= rod_l:  # the rod reaches at every crank angle: nothing to test
            return None
        s = r * np.sin(inputs) - e
        bad = np.abs(s) > rod_l * (1 + 1e-12)
        if not bad.any():
            return None
        first = float(inputs[np.flatnonzero(bad)[0]])
        return (
            "the rod cannot reach the piston line where |r sin(theta) - e| > l, "
            f"e.g. theta = {math.degrees(first):.2f}° (a full turn needs rod >= crank + |offset|)"
        )

    return build(
        SPEC, _model, [r, rod_l, e], name=label, guess=guess, length_unit=length_unit,
        length_scale=max(r, rod_l, abs(e)), assembly_check=check,
    )


def _model():
    """The loop and points, dimensions as symbols r, l, e (see :func:`numkin.linkages.base.build`)."""
    import sympy as sp

    from ..loops import Loop

    th, t3, x = sp.symbols("theta theta3 x", real=True)
    R, L, E = sp.symbols("r l e", real=True)
    loop = Loop.from_vectors([(R, th), (L, t3), (-x, 0), (-E, sp.pi / 2)], [t3, x], name="O-A-P")
    points = {"O": (0, 0), "A": (R * sp.cos(th), R * sp.sin(th)), "P": (x, E)}
    return [loop], th, (R, L, E), points


SPEC = LinkageSpec(
    name="slider_crank",
    build=slider_crank,
    summary="slider-crank: crank OA, rod AP, piston P on the line y = offset",
    dimensions=(
        Dimension("crank", "length", "crank radius r, OA"),
        Dimension("rod", "length", "connecting-rod length l, AP"),
        Dimension("offset", "signed", "piston line offset e", default=0.0),
    ),
    input="theta",
    unknowns=(("theta3", "angle"), ("x", "length")),
    length_unit="mm",
    guess="the piston on the +x side of the crank, at every input",
    points=("O", "A", "P"),
    links=(("O", "A"), ("A", "P")),
    ground=("O",),
)

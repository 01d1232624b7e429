"""The two chained four-bars of the homework (source document 003)."""

from __future__ import annotations

import math

from .base import Dimension, LinkageSpec, build, finite, length, pair

__all__ = ["chained_four_bars", "SPEC"]


def chained_four_bars(
    fixed1=7.0, input1=1.94, coupler1=6.86, output1=2.36,
    fixed2=1.25, input2=2.39, coupler2=1.87, output2=1.26,
    offset=math.radians(149.0),
    guess1=(math.radians(45.0), math.radians(60.0)),
    guess2=(math.radians(30.0), math.radians(270.0)),
    *, length_unit: str = "in",
):
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
    f1, i1, c1, o1, f2, i2, c2, o2 = (length(n, v) for n, v in zip(names, vals))
    off = finite("offset", offset)
    g = [*pair("guess1", guess1), *pair("guess2", guess2)]
    return build(
        SPEC, _model, [f1, i1, c1, o1, f2, i2, c2, o2, off],
        name="chained four-bars", guess={"phi": g[0], "psi": g[1], "beta": g[2], "gamma": g[3]},
        guess_input=0.0, length_unit=length_unit, length_scale=max(f1, i1, c1, o1, f2, i2, c2, o2),
    )


def _model():
    """The loops and points, dimensions as symbols (see :func:`numkin.linkages.base.build`)."""
    import sympy as sp

    from ..loops import Loop

    th, phi, psi, beta, gamma = sp.symbols("theta phi psi beta gamma", real=True)
    F1, I1, C1, O1, F2, I2, C2, O2, OFF = sp.symbols(
        "fixed1 input1 coupler1 output1 fixed2 input2 coupler2 output2 offset", real=True
    )
    loop1 = Loop.from_vectors([(O1, phi), (C1, psi), (I1, th + sp.pi), (-F1, 0)], [phi, psi], name="linkage 1")
    alpha = phi + OFF
    loop2 = Loop.from_vectors([(O2, beta), (C2, gamma), (I2, alpha + sp.pi), (-F2, 0)], [beta, gamma], name="linkage 2")
    points = {
        "C": (0, 0), "B": (O1 * sp.cos(phi), O1 * sp.sin(phi)),
        "A": (F1 + I1 * sp.cos(th), I1 * sp.sin(th)), "D": (F1, 0),
        # linkage 2 drawn with its input pivot on linkage 1's output pivot C
        "E": (I2 * sp.cos(alpha), I2 * sp.sin(alpha)),
        "F": (-F2 + O2 * sp.cos(beta), O2 * sp.sin(beta)), "G": (-F2, 0),
    }
    return [loop1, loop2], th, (F1, I1, C1, O1, F2, I2, C2, O2, OFF), points


SPEC = LinkageSpec(
    name="chained_four_bars",
    build=chained_four_bars,
    summary="two chained four-bars: linkage 2's input is linkage 1's output phi plus a fixed offset",
    dimensions=(
        Dimension("fixed1", "length", "linkage 1: fixed link r1", default=7.0),
        Dimension("input1", "length", "linkage 1: input link r4", default=1.94),
        Dimension("coupler1", "length", "linkage 1: coupler r3", default=6.86),
        Dimension("output1", "length", "linkage 1: output link r2", default=2.36),
        Dimension("fixed2", "length", "linkage 2: fixed link", default=1.25),
        Dimension("input2", "length", "linkage 2: input link", default=2.39),
        Dimension("coupler2", "length", "linkage 2: coupler", default=1.87),
        Dimension("output2", "length", "linkage 2: output link", default=1.26),
        Dimension("offset", "angle", "alpha - phi", default=math.radians(149.0)),
    ),
    input="theta",
    unknowns=(("phi", "angle"), ("psi", "angle"), ("beta", "angle"), ("gamma", "angle")),
    length_unit="in",
    guess="the homework's guesses at theta = 0: (phi, psi) = (45°, 60°), (beta, gamma) = (30°, 270°)",
    points=("C", "B", "A", "D", "E", "F", "G"),
    links=(("D", "A"), ("A", "B"), ("B", "C"), ("C", "E"), ("E", "F"), ("F", "G")),
    ground=("C", "D", "G"),
)

"""What the symbols of a mechanism's loops are: angles or lengths, and what sets the loops' scale.

A loop knows its own angles (declared, or inside a sine or cosine of its
equations: ``Loop.angles``). Across a mechanism more follows
(:func:`angle_unknowns`): an unknown that another loop or a point turns by,
or that an equation sets to a sum of angles, is an angle too, and the input
is one unless the loops use it as a length only (the length of a vector: a
cylinder). Which parameters scale the loops (:func:`scale_names`) gives the
default length scale (:func:`default_length_scale`); which are added to
angles (:func:`angle_offsets`) are angles themselves, so that one more than
a turn from zero was most likely given in degrees.
"""

from __future__ import annotations

import math

from .errors import DegreesWarning, warn

__all__ = ["angle_unknowns", "angle_offsets", "scale_names", "default_length_scale", "warn_degrees"]

_INVERSE_TRIG = ("atan2", "asin", "acos", "atan", "acot")


def _unit_terms(expr) -> set:
    """The symbols that are terms of ``expr`` with coefficient 1 or -1 (``t4`` and ``delta`` of ``t4 + delta``;
    not ``x`` of ``x / R`` or of ``2 x``)."""
    import sympy as sp

    out = set()
    for term in sp.Add.make_args(sp.sympify(expr)):
        coeff, rest = term.as_coeff_Mul()
        if rest.is_Symbol and abs(coeff) == 1:
            out.add(rest)
    return out


def _angle_sum(expr, known) -> set:
    """The symbols of ``expr`` where it is a sum of symbols and inverse trigonometric functions, each with
    coefficient 1 or -1, and constants, holding at least one angle (a symbol in ``known``, or an inverse
    trigonometric function): an equation between angles, ``t5 - t4 - 0.6`` or ``t3 - atan2(y, x)``. Else
    the empty set (``x - r t2``, ``x - 2 t2``: a length rolled off by an angle)."""
    symbols, angle = set(), False
    for term in expr.as_ordered_terms() if expr.is_Add else [expr]:
        coeff, rest = term.as_coeff_Mul()
        if rest.is_number:
            continue
        if abs(coeff) != 1:
            return set()
        if rest.is_Symbol:
            symbols.add(rest)
            angle = angle or rest in known
        elif type(rest).__name__ in _INVERSE_TRIG:
            angle = True
        else:
            return set()
    return symbols if angle else set()


def _input_is_length(loops, input_symbol, trig) -> bool:
    """Whether the loops use the input as a length only: in no sine or cosine, but as a vector's length or
    a factor of a term with a sine or cosine (``d cos(phi)``: a cylinder's length)."""
    import sympy as sp

    if any(input_symbol in fn.free_symbols for fn in trig):
        return False
    for lp in loops:
        if any(input_symbol in length for length, _ in lp.vector_symbols):
            return True
        for r in lp.residuals:
            for term in sp.Add.make_args(r):
                if term.is_Mul and input_symbol in term.args and term.atoms(sp.sin, sp.cos):
                    return True
    return False


def angle_unknowns(loops, input_symbol, points=None) -> tuple[set, bool]:
    """The unknowns of a mechanism's loops that are angles (rad), and whether the input is one.

    Each loop's own (``Loop.angles``); and, of a loop whose angles
    were not declared, every unknown that another loop's sine or cosine, or
    a point's, turns by (a term of its argument: ``t5`` of ``cos(t5 + 0.6)``,
    not ``x`` of ``sin(x / R)``), and every unknown an equation of it sets to
    a sum of angles and constants (``t5 - t2 - 0.6``, ``t3 - atan2(y, x)``):
    an angle that a later loop or a point turns by, or that others define, is
    an angle though its own loop has no sine of it. The input is an angle
    unless the loops use it as a length only (a vector's length, ``d cos(phi)``).

    Examples
    --------
    >>> import sympy as sp
    >>> from numkin import Loop
    >>> t2, t5, t6, t7 = sp.symbols("theta2 theta5 theta6 theta7")
    >>> arm = Loop([t5 - t2 - 0.6], [t5], name="arm")
    >>> dyad = Loop.from_vectors([(1, t5), (3.5, t6), (-3, t7), (-4, 0)], [t6, t7])
    >>> angles, input_angle = angle_unknowns([arm, dyad], t2)
    >>> sorted(map(str, arm.angles)), sorted(map(str, angles)), input_angle
    ([], ['theta5', 'theta6', 'theta7'], True)
    """
    import sympy as sp

    exprs = [r for lp in loops for r in lp.residuals]
    exprs += [c for xy in (points or {}).values() for c in xy if isinstance(c, sp.Basic)]
    trig = {fn for e in exprs for fn in e.atoms(sp.sin, sp.cos, sp.tan)}
    turned = set().union(*(_unit_terms(fn.args[0]) for fn in trig))
    angles = set().union(*(lp.angles for lp in loops))
    inferred = [lp for lp in loops if not lp.angles_declared]
    for lp in inferred:
        angles |= set(lp.unknowns) & turned
    input_angle = not _input_is_length(loops, input_symbol, trig)
    known = angles | ({input_symbol} if input_angle else set())
    grown = True
    while grown:  # (an equation may set an angle from one a later equation makes an angle)
        grown = False
        for lp in inferred:
            for r in lp.residuals:
                new = (_angle_sum(r, known) & set(lp.unknowns)) - angles
                if new:
                    angles |= new
                    known |= new
                    grown = True
    return angles, input_angle


def angle_offsets(lp, moving) -> list:
    """The names of the parameters a loop adds to an angle, each with coefficient 1 or -1 (``t4 + delta`` in a
    vector's angle or inside a sine or cosine): angles themselves (rad). Not a gear ratio's ``n`` of ``n t2``;
    ``moving`` (the input and the unknowns) left out."""
    import sympy as sp

    if lp.vectors:
        args = [angle for _, angle in lp.vectors]
    else:
        args = [fn.args[0] for r in lp.residuals for fn in r.atoms(sp.sin, sp.cos, sp.tan)]
    return sorted(str(s) for s in set().union(set(), *(_unit_terms(a) for a in args)) - set(moving))


def scale_names(lp, moving) -> dict:
    """``{"scales": [...], "angle_parameters": [...]}`` of a loop (its scaling and angle symbols, computed once), the
    moving symbols left out."""
    lengths, angles = _scale_symbols(lp)
    return {"scales": sorted(str(s) for s in lengths - moving),
            "angle_parameters": sorted(str(s) for s in angles - moving)}


def _scale_symbols(lp) -> tuple[set, set]:
    """The symbols that scale a loop and those in its angles.

    Of a loop of vectors: those of its lengths, and of its angles. Of a loop
    written as equations: those outside every sine, cosine and tangent of a
    residual that has one (an equation between angles alone, ``t5 - t4 -
    phi``, scales nothing), and those inside them.
    """
    if lp.vectors:
        return set(lp.length_symbols), {s for _, angle in lp.vectors for s in angle.free_symbols}
    import sympy as sp

    lengths, angles = set(), set()
    for r in lp.residuals:
        trig = r.atoms(sp.sin, sp.cos, sp.tan)
        if trig:
            lengths |= r.xreplace({f: sp.Dummy() for f in trig}).free_symbols
            angles |= {s for f in trig for s in f.free_symbols}
    return {s for s in lengths if not isinstance(s, sp.Dummy)} - set(lp.unknowns), angles


def default_length_scale(model: dict, value_of: dict) -> float:
    """The characteristic length of a mechanism: the largest of its lengths.

    That is the largest value of a parameter that scales a loop (a
    parameter in a vector's length; in a loop written as equations, one
    outside every sine, cosine and tangent of an equation that has one) or
    of a vector length written as a number. Where there is no such length
    (loops of equations in numbers), the largest parameter that is not in an
    angle (a ground's tilt is none); else 1. ``model`` is
    :func:`numkin.loops.describe`'s.

    Examples
    --------
    >>> import sympy as sp
    >>> from numkin.loops import Loop, describe
    >>> t2, t3, t4, tilt = sp.symbols("theta2 theta3 theta4 tilt")
    >>> loop = Loop.from_vectors([(1e6, t2), (3e6, t3), (-3e6, t4), (-4e6, tilt)], [t3, t4])
    >>> default_length_scale(describe([loop], t2, {tilt: 1e-6}, None), {"tilt": 1e-6})
    4000000.0
    """
    scales = {s for lp in model["loops"] for s in lp.get("scales", lp["lengths"])}
    values = [abs(v) for s, v in value_of.items() if s in scales]
    values += [lp.get("numbers", 0.0) for lp in model["loops"]]
    if not any(values):
        angles = {s for lp in model["loops"] for s in lp.get("angle_parameters", ())}
        values = [abs(v) for s, v in value_of.items() if s not in angles]
    return max(values) if values and max(values) > 0 else 1.0


def warn_degrees(name, model, value_of, guess_input) -> None:
    """A :class:`~numkin.errors.DegreesWarning` for a ``guess_input`` or a parameter added to an angle
    (:func:`angle_offsets`) more than a turn from zero: most likely given in degrees. ``model`` is
    :func:`numkin.loops.describe`'s, ``value_of`` maps parameter names to values.

    Examples
    --------
    >>> import warnings
    >>> model = {"loops": [{"angle_offsets": ["delta"]}], "input_is_angle": True}
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_degrees("arm", model, {"delta": 34.4, "r": 100.0}, None)
    >>> str(caught[0].message)
    'arm: parameter delta = 34.4 is an angle more than a turn from zero: angles are in rad (was it given in degrees? np.radians converts)'
    """
    offsets = {p for lp in model["loops"] for p in lp.get("angle_offsets", ())}
    far = [f"parameter {p} = {v:g}" for p, v in value_of.items() if p in offsets and abs(v) > 2.0 * math.pi]
    if guess_input is not None and model.get("input_is_angle", True) and abs(guess_input) > 2.0 * math.pi:
        far.append(f"guess_input = {guess_input:g}")
    if far:
        warn(DegreesWarning(
            f"{name}: {', '.join(far)} {'is' if len(far) == 1 else 'are'} an angle more than a turn from zero: "
            "angles are in rad (was it given in degrees? np.radians converts)"
        ))

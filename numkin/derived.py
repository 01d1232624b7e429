"""Derived quantities: named expressions of a mechanism's unknowns, input and parameters.

A four-bar's transmission angle ``mu = theta4 - theta3``, a coupler's slope, a
slider's distance from a pivot: what a course asks about besides the unknowns.
Declared once, a derived quantity is everywhere an unknown is:
:func:`numkin.quantities.catalogue` lists ``mu`` [rad], ``omega_mu`` [rad/s]
and ``alpha_mu`` [rad/s^2]; :func:`numkin.analytic.derived_kinematics` gives
its values and exact rates (the chain rule through the unknowns' derivatives,
derived once with sympy); :func:`numkin.compare.compare` sets the difference
schemes against them; a scene declares it under ``[mechanism.quantities]``.

Examples
--------
>>> import numpy as np
>>> from numkin import analytic, linkages
>>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
>>> kin = analytic.derived_kinematics(mech.sweep(np.radians([90.0])), omega=10.0)
>>> print(f"{np.degrees(kin['mu'][0]):.4f} deg, {kin['omega_mu'][0]:.4f} rad/s")
86.8153 deg, 4.4513 rad/s
"""

from __future__ import annotations

import ast
import math
import re
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from .errors import InputError, warn

__all__ = ["Derived", "DIMENSIONS", "FUNCTIONS", "read_quantities", "taken_names", "names_of", "bind",
           "refuse_unknown_names", "names_in", "warn_not_finite"]

#: What a derived quantity's value is: an angle (rad) or a length (the mechanism's length unit).
DIMENSIONS = ("angle", "length")

_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
#: Names an expression string may use besides the mechanism's own.
FUNCTIONS = frozenset({"sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "sqrt", "exp",
                       "log", "abs", "Abs", "pi", "E"})


@dataclass(frozen=True)
class Derived:
    """One derived quantity: its name, its expression and whether it is an angle or a length.

    Parameters
    ----------
    name : str
        A name such as ``"mu"``; its rates are named by the rule of
        :mod:`numkin.quantities` (``omega_mu``, ``alpha_mu``; ``v_s``, ``a_s``).
    expression : sympy expression or str
        In the unknowns, the input and the parameters, by their names.
    dimension : {"angle", "length"}
    """

    name: str
    expression: Any
    dimension: str


def read_quantities(spec, taken: Mapping[str, str], owner: str = "mechanism", known=None) -> dict:
    """Validate ``{name: (expression, dimension)}`` into ``{name: Derived}`` (names only, no sympy).

    ``taken`` maps every name the mechanism already uses (unknowns, input,
    parameters, points and the names of their rates) to what it is, so a
    derived quantity can neither shadow one nor be shadowed. ``known``: the
    names an expression may use, as ``(unknowns, input name, parameters)``, if
    given (:func:`refuse_unknown_names`).

    Examples
    --------
    >>> read_quantities({"mu": ("theta4 - theta3", "angle")}, {"theta3": "an unknown"})["mu"].dimension
    'angle'
    >>> read_quantities({"theta3": ("2*theta3", "angle")}, {"theta3": "an unknown"})
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: mechanism: quantity 'theta3' is already the name of an unknown
    """
    if spec is None:
        return {}
    if not isinstance(spec, Mapping):
        raise InputError(f"{owner}: quantities must be a mapping name -> (expression, 'angle' or 'length'), "
                         f"got {type(spec).__name__}")
    out = {}
    for name, value in spec.items():
        where = f"{owner}: quantity {name!r}"
        if isinstance(value, Derived):
            value = (value.expression, value.dimension)
        if not (isinstance(name, str) and _NAME.fullmatch(name)):
            raise InputError(f"{where}: a quantity's name is a letter then letters, digits or _")
        if not (isinstance(value, (tuple, list)) and len(value) == 2):
            raise InputError(f"{where} must be (expression, 'angle' or 'length'), got {value!r}")
        expression, dimension = value
        if dimension not in DIMENSIONS:
            raise InputError(f"{where}: dimension must be 'angle' or 'length', got {dimension!r}")
        if isinstance(expression, bool) or not (isinstance(expression, str) and expression.strip()
                                                 or hasattr(expression, "free_symbols")):
            raise InputError(f"{where}: the expression must be a string or a sympy expression, got {expression!r}")
        used = {str(s) for s in expression.free_symbols} if hasattr(expression, "free_symbols") else None
        if isinstance(expression, str):
            used = names_in(expression, where)
        if known is not None:
            refuse_unknown_names(where, used, *known)
        for own in names_of(name, dimension):
            if own in taken:
                raise InputError(f"{where} is already the name of {taken[own]}" if own == name else
                                 f"{where}: its name {own!r} is already the name of {taken[own]}")
        taken.update({own: f"the quantity {name}" for own in names_of(name, dimension)})  # and within one call
        out[name] = Derived(name, expression, dimension)
    return out


#: What an expression string may be made of: numbers, names, arithmetic and calls of functions.
_NODES = (ast.Expression, ast.BinOp, ast.UnaryOp, ast.Call, ast.Name, ast.Constant, ast.Load, ast.Add, ast.Sub,
          ast.Mult, ast.Div, ast.Pow, ast.USub, ast.UAdd)


def names_in(expression: str, where: str) -> set:
    """The names an expression string uses besides :data:`FUNCTIONS`; refuses what is not arithmetic.

    Read with ``ast``, never evaluated: what sympy would run (``__import__``, attributes,
    comparisons) is refused before sympy reads the string.

    Examples
    --------
    >>> sorted(names_in("r2*cos(theta2) + e", "point 'P' x"))
    ['e', 'r2', 'theta2']
    >>> names_in("theta2.real", "point 'P' x")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: point 'P' x: the expression 'theta2.real' is not arithmetic of numbers, names and the functions Abs, abs, acos, asin, atan, atan2, cos, cosh, exp, log, sin, sinh, sqrt, tan, tanh
    """
    try:
        tree = ast.parse(expression.replace("^", "**").strip(), mode="eval")
    except SyntaxError:
        raise InputError(f"{where}: cannot read the expression {expression!r}") from None
    for node in ast.walk(tree):
        if not isinstance(node, _NODES) or isinstance(node, ast.Constant) and not isinstance(node.value, (int, float)) \
                or isinstance(node, ast.Call) and not (isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS):
            raise InputError(f"{where}: the expression {expression!r} is not arithmetic of numbers, names and "
                             f"the functions {', '.join(sorted(FUNCTIONS - {'pi', 'E'}))}")
    return {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)} - FUNCTIONS


def names_of(name: str, dimension: str) -> tuple:
    """The names of a quantity and its two rates, and for an angle its scene name in degrees.

    Examples
    --------
    >>> names_of("mu", "angle"), names_of("s", "length")
    (('mu', 'omega_mu', 'alpha_mu', 'mu_deg'), ('s', 'v_s', 'a_s'))
    """
    if dimension == "angle":
        return name, f"omega_{name}", f"alpha_{name}", f"{name}_deg"
    return name, f"v_{name}", f"a_{name}"


def taken_names(unknowns, angles, input_name, parameters, points) -> dict:
    """Name -> what it is, for every name a mechanism's own quantities and symbols use."""
    taken = {input_name: "the input", **{p: "a parameter" for p in parameters}}
    for u in unknowns:
        for own in names_of(u, "angle" if u in angles else "length"):
            taken[own] = "an unknown" if own == u else f"a quantity of the unknown {u}"
    for p in points:
        for prefix in ("", "v", "a"):
            for axis in "xy":
                taken[f"{prefix}{axis}_{p}"] = f"a coordinate of the point {p}"
        taken[p] = "a point"
    return taken


def refuse_unknown_names(where: str, used, unknowns, input_name: str, parameters) -> None:
    """Refuse an expression that names something other than an unknown, the input or a parameter.

    The one check of what an expression of a mechanism may name: a derived
    quantity's (:func:`read_quantities`, :func:`bind`) and a named point's
    coordinates (:func:`numkin.loops.check_point_names`).

    Parameters
    ----------
    where : str
        What the expression belongs to, first in the message (``"four-bar: point 'B'"``).
    used : iterable of str
        The names the expression uses (functions and constants left out).
    unknowns, parameters : sequence of str
    input_name : str

    Raises
    ------
    InputError
        Naming ``where``, the names the mechanism does not have and those it has.

    Examples
    --------
    >>> refuse_unknown_names("four-bar: point 'B'", {"r2", "theta3"}, ["theta3", "theta4"], "theta2", ["r2"])
    >>> refuse_unknown_names("four-bar: point 'B'", {"r2", "theta33"}, ["theta3", "theta4"], "theta2", ["r2"])
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: four-bar: point 'B' names ['theta33'], which the mechanism does not have: it may use the unknowns ['theta3', 'theta4'], the input theta2 and the parameters ['r2']
    """
    strange = sorted(set(used) - {*unknowns, input_name, *parameters})
    if strange:
        raise InputError(f"{where} names {strange}, which the mechanism does not have: it may use the unknowns "
                         f"{list(unknowns)}, the input {input_name} and the parameters {list(parameters)}")


def bind(mechanism, derived: Derived):
    """The expression of ``derived`` in the mechanism's own symbols (sympy).

    Raises
    ------
    InputError
        If the expression names something that is neither an unknown, the
        input nor a parameter, or cannot be read.
    """
    import sympy as sp

    symbols = {str(s): s for s in (*mechanism.unknown_symbols, mechanism.input_symbol, *mechanism.parameters)}
    where = f"{mechanism.name}: quantity {derived.name!r}"
    try:
        expr = sp.sympify(derived.expression, locals=dict(symbols), rational=False)
    except (sp.SympifyError, SyntaxError, TypeError) as error:
        raise InputError(f"{where}: cannot read the expression {derived.expression!r} ({error})") from None
    if not isinstance(expr, sp.Expr):
        raise InputError(f"{where}: the expression {derived.expression!r} is not a number-valued expression")
    refuse_unknown_names(where, {str(s) for s in expr.free_symbols}, [str(u) for u in mechanism.unknown_symbols],
                         str(mechanism.input_symbol), [str(p) for p in mechanism.parameters])
    expr = expr.xreplace({s: symbols[str(s)] for s in expr.free_symbols})  # a name means the loops' own symbol
    if not expr.free_symbols & {*mechanism.unknown_symbols, mechanism.input_symbol}:
        raise InputError(f"{where}: {derived.expression!r} depends on no unknown and not on the input: it is a "
                         "constant, with no motion to differentiate")
    if expr.has(sp.I) or expr.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
        raise InputError(f"{where}: the expression {derived.expression!r} is not a finite real expression")
    return expr


def warn_not_finite(mech, names, rows, q, t) -> None:
    """Warn, naming the quantity and the first input, of values that are not finite where the unknowns ``q`` are.

    ``rows[k]`` holds the values of ``names[k]`` at the inputs ``t`` (rad): an
    expression outside its domain (``sqrt`` of a negative number) there.

    Examples
    --------
    >>> import warnings
    >>> from numkin import linkages
    >>> mech = linkages.slider_crank(80, 200)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_not_finite(mech, ["x_P"], np.array([[1.0, np.nan]]), np.zeros((2, 2)), np.radians([0.0, 10.0]))
    >>> print(caught[0].message)
    slider-crank (crank 80, rod 200, offset 0): x_P is not finite at 1 of 2 inputs, first at input 10°: its expression is undefined there (outside its domain)
    """
    t = np.asarray(t, dtype=float)
    solved = np.all(np.isfinite(q), axis=0)
    for name, values in zip(names, rows):
        bad = np.flatnonzero(~np.isfinite(values) & solved)
        if bad.size:
            warn(f"{mech.name}: {name} is not finite at {bad.size} of {t.size} inputs, first at input "
                 f"{math.degrees(t[bad[0]]):.6g}°: its expression is undefined there (outside its domain)",
                 RuntimeWarning)

"""Positions and exact rates of expressions of the solution: named points and derived quantities.

A named point ``P = (x(q, theta), y(q, theta))`` and a derived quantity
``mu = e(q, theta)`` (:mod:`numkin.derived`) are expressions of the unknowns
``q`` and the input ``theta``. Their derivatives along the solution follow
from the unknowns' ones (:func:`numkin.analytic.derivatives`) by the chain
rule::

    e'  = e_q q' + e_theta
    e'' = (e')_q q' + (e')_q' q'' + (e')_theta

derived once per mechanism with sympy, compiled once, and evaluated over the
whole sweep; time rates as for the unknowns, ``omega_in e'`` and
``omega_in**2 e'' + alpha_in e'``. The functions are also reached as
``numkin.analytic.point_kinematics`` and so on.

Examples
--------
>>> import numpy as np
>>> from numkin import linkages
>>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0]))
>>> kin = point_kinematics(sweep, "6000 rpm", points="P")
>>> print(f"{kin['x_P'][0]:.1f} mm, {kin['ax_P'][0] / 1000:.1f} m/s^2")
280.0 mm, -44215.8 m/s^2
"""

from __future__ import annotations

import weakref
from collections.abc import Iterable

import numpy as np

from .analytic import check_sweep, derivatives, input_rates, label_frame, scalar_attr
from .compiled import vector_function
from .derived import bind, warn_not_finite
from .errors import InputError
from .quantities import Quantity, input_quantity, point_quantities

__all__ = ["point_derivatives", "point_kinematics", "derived_values", "derived_derivatives", "derived_kinematics",
           "expression_functions", "derived_functions"]

_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()

#: The parameters every ``*_kinematics`` function here shares, written once.
_RATES = """sweep : Sweep
    omega : float, str or array_like
        Input angular speed (rad/s, or a string with units), see :func:`numkin.analytic.kinematics`.
    alpha : float, str or array_like, default 0
        Input angular acceleration (rad/s^2, or a string with units)."""

#: The change-point parameter every function here shares.
_CHANGE = """at_change_point : {"nan", "continue"}, default "nan"
        Rates at a change point, as in :func:`numkin.analytic.derivatives`."""


def _shared(*functions) -> None:
    """Write the shared parameters into the functions' docstrings (their ``%(rates)s``)."""
    for function in functions:
        function.__doc__ = function.__doc__.replace("%(rates)s", _RATES).replace("%(change)s", _CHANGE)


def expression_functions(mech, key, expressions, rates: bool = True):
    """Compiled ``(e, de/dtheta, d2e/dtheta2)`` of expressions of the unknowns, input and parameters.

    Derived once per mechanism and ``key``; ``expressions()`` gives the sympy
    expressions when they are first needed. Each function takes
    ``(*q, *dq, *d2q, theta, *parameters)`` and returns one row per expression.
    ``rates=False``: ``(e,)`` alone, taking ``(*q, theta, *parameters)`` (nothing differentiated).
    """
    cache = _CACHE.setdefault(mech, {})
    if not rates and (key, "values") not in cache:
        import sympy as sp

        q, t = list(mech.compiled.unknowns), mech.compiled.input_symbol
        exprs = [sp.sympify(e) for e in expressions()]
        cache[key, "values"] = (vector_function(exprs, [*q, t, *mech.compiled.parameters], [*q, t]),)
    if not rates:
        return cache[key, "values"]
    if key not in cache:
        import sympy as sp

        q = list(mech.compiled.unknowns)
        t = mech.compiled.input_symbol
        params = list(mech.compiled.parameters)
        dq = [sp.Dummy(f"d{u}") for u in q]
        d2q = [sp.Dummy(f"dd{u}") for u in q]
        exprs = [sp.sympify(e) for e in expressions()]
        first = [sum((sp.diff(e, u) * du for u, du in zip(q, dq)), sp.S.Zero) + sp.diff(e, t) for e in exprs]
        second = [
            sum((sp.diff(f, u) * du for u, du in zip(q, dq)), sp.S.Zero)
            + sum((sp.diff(f, du) * ddu for du, ddu in zip(dq, d2q)), sp.S.Zero)
            + sp.diff(f, t)
            for f in first
        ]
        # |e| differentiates to sign(e) e' and a Dirac delta at e = 0: its value everywhere else is 0
        first, second = ([r.replace(sp.DiracDelta, lambda *_: sp.S.Zero) for r in rows] for rows in (first, second))
        varying = [*q, *dq, *d2q, t]
        args = [*q, *dq, *d2q, t, *params]
        cache[key] = tuple(vector_function(rows, args, varying) for rows in (exprs, first, second))
    return cache[key]


def _evaluate(sweep, groups, names: list, rates: bool = True, at_change_point: str = "nan"):
    """Values (and theta-derivatives) of the expressions named ``names`` over a sweep: (rows, N) arrays.

    ``groups``: ``(key, expressions, rows)`` for each point or derived quantity, compiled once per
    mechanism and key (:func:`expression_functions`) whatever other names a call asks for with it;
    the unknowns' rates are solved once for all. Values that are not finite where the unknowns are (an
    expression outside its domain, ``sqrt`` of a negative number) are warned of, naming the quantity
    and the input.
    """
    mech, t, q = check_sweep(sweep)
    args = (*q, t, *mech.parameter_values)
    if rates:
        dq, d2q = derivatives(sweep, at_change_point=at_change_point)
        args = (*q, *dq, *d2q, t, *mech.parameter_values)
    blocks = []
    with np.errstate(all="ignore"):
        for key, expressions, rows in groups:
            blocks.append([np.broadcast_to(np.asarray(f(*args), dtype=float).reshape(rows, -1), (rows, t.size))
                           for f in expression_functions(mech, key, expressions, rates)])
    out = [np.vstack(rows) for rows in zip(*blocks)]
    warn_not_finite(mech, names, out[0], q, t)
    return out


def derived_functions(mech, name: str, rates: bool = True):
    """:func:`expression_functions` of one derived quantity of ``mech`` (one row each), compiled once.

    Examples
    --------
    >>> from numkin import linkages
    >>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
    >>> (f,) = derived_functions(mech, "mu", rates=False)
    >>> f(0.5, 2.0, 0.0, *mech.parameter_values).tolist()   # theta3, theta4, theta2, r1..r4: one row
    [1.5]
    """
    return expression_functions(mech, *_derived_group(mech, name)[:2], rates)


def _derived_group(mech, name: str):
    """``(key, expressions, rows)`` of one derived quantity for :func:`_evaluate`."""
    d = mech.derived[name]
    return ("derived", d.name, str(d.expression), d.dimension), (lambda: [bind(mech, d)]), 1


def _point_group(mech, name: str):
    """``(key, expressions, rows)`` of one named point (its x and y) for :func:`_evaluate`."""
    return ("point", name), (lambda: list(mech.points[name])), 2


def _names(mech, wanted, have, what: str, how: str, argument: str) -> list:
    """The names asked for (the ``argument``) among ``have`` (all of them when ``wanted`` is None)."""
    if not have:
        raise InputError(f"{mech.name} has no {what} (give {how} when building the Mechanism)")
    if wanted is None:
        return list(have)
    if not isinstance(wanted, (str, Iterable)):
        raise InputError(f"{argument} must be a name or a list of names of the {what} of {mech.name} "
                         f"{list(have)}, got {type(wanted).__name__} {wanted!r:.60}")
    names = [wanted] if isinstance(wanted, str) else list(wanted)
    if not names:
        raise InputError(f"name at least one of the {what} of {mech.name}: {list(have)}")
    unknown = [p for p in names if p not in have]
    if unknown:
        raise InputError(f"{mech.name} has no {what} {unknown}; its {what} are {list(have)}")
    return names


# --------------------------------------------------------------------------- points
def point_derivatives(sweep, points=None, *, at_change_point: str = "nan") -> dict:
    """Positions of named points and their first and second derivatives with respect to the input.

    Parameters
    ----------
    sweep : Sweep
    points : str or sequence of str, optional
        Point names (default: all of ``sweep.mechanism.points``).
    %(change)s

    Returns
    -------
    dict
        name -> (P, dP, d2P), each an array of shape (2, N) (rows x and y;
        length unit, per rad, per rad^2).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([90.0]))
    >>> P, dP, d2P = point_derivatives(sweep, "A")["A"]
    >>> print(np.round(dP[:, 0], 9), np.round(d2P[:, 0], 9))
    [-80.   0.] [ -0. -80.]
    """
    mech = check_sweep(sweep)[0]
    names = _names(mech, points, list(mech.points), "points", "points=", "points")
    P, dP, d2P = _evaluate(sweep, [_point_group(mech, name) for name in names],
                           [f"{axis}_{name}" for name in names for axis in "xy"], at_change_point=at_change_point)
    return {name: (P[2 * k : 2 * k + 2], dP[2 * k : 2 * k + 2], d2P[2 * k : 2 * k + 2]) for k, name in enumerate(names)}


def point_kinematics(sweep, omega, alpha=0.0, points=None, *, at_change_point: str = "nan"):
    """Positions, velocities and accelerations of named points over a sweep.

    Parameters
    ----------
    %(rates)s
    points : str or sequence of str, optional
        Point names (default: all named points of the mechanism).
    %(change)s

    Returns
    -------
    pandas.DataFrame
        Column ``<input>`` (rad), then for each point P: ``x_P``, ``y_P``
        [length unit], ``vx_P``, ``vy_P`` [length unit/s], ``ax_P``, ``ay_P``
        [length unit/s^2]. Units also in ``frame.attrs["units"]``.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([90.0]))
    >>> kin = point_kinematics(sweep, "6000 rpm", points="A")
    >>> print(f"{kin['vx_A'][0] / 1000:.4f} m/s")
    -50.2655 m/s
    """
    mech, t, _ = check_sweep(sweep)
    w, a = input_rates(omega, alpha, t.size)
    data = point_derivatives(sweep, points, at_change_point=at_change_point)
    columns = []
    for name, (P, dP, d2P) in data.items():
        for pair, v in zip(point_quantities(mech, name), (P, w * dP, w**2 * d2P + a * dP)):
            columns += [(q, v[k]) for k, q in enumerate(pair)]
    return _frame(mech, t, w, a, columns)


# --------------------------------------------------------------------------- derived quantities
def derived_derivatives(sweep, names=None, *, at_change_point: str = "nan") -> dict:
    """Values of derived quantities and their first and second derivatives with respect to the input.

    Parameters
    ----------
    sweep : Sweep
    names : str or sequence of str, optional
        Names of the mechanism's derived quantities (default: all of
        ``sweep.mechanism.derived``).
    %(change)s

    Returns
    -------
    dict
        name -> (e, de, d2e), each an array of shape (N,) (rad or length
        unit; per rad; per rad^2).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.slider_crank(80, 200).add_quantities({"gap": ("x - r*cos(theta)", "length")})
    >>> e, de, d2e = derived_derivatives(mech.sweep(np.radians([90.0])))["gap"]
    >>> print(f"{e[0]:.4f} mm, {abs(de[0]):.4f} mm/rad, {d2e[0]:.4f} mm/rad^2")  # r^2/sqrt(l^2 - r^2) at 90 deg
    183.3030 mm, 0.0000 mm/rad, 34.9149 mm/rad^2
    """
    mech = check_sweep(sweep)[0]
    names = _derived(mech, names)
    e, de, d2e = _evaluate(sweep, [_derived_group(mech, name) for name in names], names,
                           at_change_point=at_change_point)
    return {name: (e[k], de[k], d2e[k]) for k, name in enumerate(names)}


def derived_values(sweep, names=None) -> dict:
    """Values of derived quantities over a sweep; nothing is differentiated.

    Parameters
    ----------
    sweep : Sweep
    names : str or sequence of str, optional
        Names of the mechanism's derived quantities (default: all of them).

    Returns
    -------
    dict
        name -> (N,) array (rad or the length unit).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
    >>> print(np.degrees(derived_values(mech.sweep(np.radians([0.0, 90.0])))["mu"]).round(4))
    [60.     86.8153]
    """
    mech = check_sweep(sweep)[0]
    names = _derived(mech, names)
    (e,) = _evaluate(sweep, [_derived_group(mech, name) for name in names], names, rates=False)
    return {name: e[k] for k, name in enumerate(names)}


def _derived(mech, names):
    """The derived quantities' names asked for, checked."""
    return _names(mech, names, list(mech.derived), "derived quantities", "quantities=", "names")


def derived_kinematics(sweep, omega, alpha=0.0, names=None, *, at_change_point: str = "nan"):
    """Values, rates and accelerations of derived quantities over a sweep.

    Parameters
    ----------
    %(rates)s
    names : str or sequence of str, optional
        Derived quantities (default: all the mechanism's).
    %(change)s

    Returns
    -------
    pandas.DataFrame
        Column ``<input>`` (rad), then for each derived quantity ``mu`` (an
        angle): ``mu`` [rad], ``omega_mu`` [rad/s], ``alpha_mu`` [rad/s^2];
        for ``s`` (a length): ``s``, ``v_s``, ``a_s`` in the length unit
        (per s, per s^2). Units also in ``frame.attrs["units"]``.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
    >>> kin = derived_kinematics(mech.sweep(np.radians([90.0])), omega=10.0)
    >>> print(f"{np.degrees(kin['mu'][0]):.4f} deg, {kin['omega_mu'][0]:.4f} rad/s")
    86.8153 deg, 4.4513 rad/s
    """
    mech, t, _ = check_sweep(sweep)
    w, a = input_rates(omega, alpha, t.size)
    columns = []
    for name, (e, de, d2e) in derived_derivatives(sweep, names, at_change_point=at_change_point).items():
        common = dict(length_unit=mech.length_unit, input_name=mech.input_name)
        for order, v in enumerate((e, w * de, w**2 * d2e + a * de)):
            q = Quantity(name, order, mech.derived[name].dimension, source="solved" if order == 0 else "analytic",
                         **common)
            columns.append((q, v))
    return _frame(mech, t, w, a, columns)


def _frame(mech, t, w, a, columns):
    """The DataFrame of ``[(Quantity, values)]`` after the input column, labelled."""
    import pandas as pd

    quantities = {mech.input_name: input_quantity(mech)}
    cols = {mech.input_name: t}
    for q, v in columns:
        quantities[q.name], cols[q.name] = q, v
    frame = pd.DataFrame(cols)
    label_frame(frame, quantities)
    frame.attrs.update({"omega": scalar_attr(w), "alpha": scalar_attr(a), "method": "analytic"})
    return frame


_shared(point_derivatives, point_kinematics, derived_derivatives, derived_kinematics)

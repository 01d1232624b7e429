"""Exact velocity and acceleration from the differentiated loop equations.

The position of a mechanism satisfies its stacked loop equations
``F(q(theta), theta) = 0`` at every input ``theta``. Differentiating once
and twice along the solution gives two *linear* systems with the position
Jacobian ``J = dF/dq``::

    J q'  = -F_theta                                  (velocity equations)
    J q'' = -(G_q q' + G_theta),  G = J q' + F_theta  (acceleration equations)

where ``'`` is d/dtheta. The right-hand sides are derived once with sympy
when the mechanism is built (the acceleration one only on first use, so a
position-only run never differentiates) and are solved here at every point
of a sweep at once. Loops are stacked in solving order, so ``J`` is block
lower-triangular: the chain rule through earlier loops (chained four-bars,
six-bar) is part of the one solve. For loops of one or two unknowns both
systems are solved by one generated function (:mod:`numkin.rates_kernel`)
that reuses the sweep's Jacobian for the terms they share with it; the
checks for singular, change and digit-losing points cost one maximum of the
sweep's condition numbers when none is near.

Time derivatives follow from the input's angular speed ``omega_in`` and
acceleration ``alpha_in``::

    omega = omega_in * q'          alpha = omega_in**2 * q'' + alpha_in * q'

Units
-----
* input angle: rad; ``omega`` in rad/s and ``alpha`` in rad/s^2 (numbers),
  or strings with units parsed by :mod:`numkin.units` (``"450 rad/min"``,
  ``"6000 rpm"``, ``"-10 rad/s"``, ``"2 rad/s^2"``);
* angle unknowns: ``omega_<name>`` in rad/s, ``alpha_<name>`` in rad/s^2;
* length unknowns and point coordinates: ``v_<name>`` in the mechanism's
  length unit per s, ``a_<name>`` in that unit per s^2 (mm/s and mm/s^2
  for a mechanism in mm: divide by 1000 for m/s and m/s^2).

The unit of every column is also stored in ``frame.attrs["units"]``.

Work
----
The derivatives record the point evaluations of compiled functions they
spend (``"F_t"`` dF/dtheta, ``"second"`` the acceleration right-hand side,
``"J"`` a Jacobian not kept by the sweep, ``"F"`` and ``"J"`` of the
complex-step Newton) to any :func:`numkin.sweep.count_evaluations` open for
the mechanism: the velocity equations reuse the sweep's Jacobian and take
dF/dtheta at every point, the acceleration equations also their
right-hand side.

A reference independent of these formulas is :func:`~numkin.complex_solve.complex_step`: the
loop equations are solved at the complex input ``theta + i h`` and the
derivative read off the imaginary part, to machine precision.

Examples
--------
>>> import numpy as np
>>> from numkin import analytic, linkages
>>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 90.0]))
>>> kin = analytic.kinematics(sweep, omega="6000 rpm")
>>> print(np.round(kin["a_x"].to_numpy() / 1000, 1))   # mm/s^2 -> m/s^2
[-44215.8  13783.8]
"""

from __future__ import annotations

import numpy as np

from .compiled import jacobian_rows, rates as rates_of
from .conditioning import (
    CHANGE_COND,
    DIGITS_RTOL,
    LostDigitsWarning,
    change_points,
    check_at_change_point,
    condition_numbers,
    continue_branch,
    lost_digits,
    warn_lost_digits,
)
from .errors import warn
from .quantities import input_quantity, unknown_quantities
from .units import deg_text, input_rates
from .complex_solve import COMPLEX_STEP, complex_positions, complex_step, complex_tangent
from .sweep import COND_MAX, SingularityWarning, check_sweep, record_evaluations

__all__ = [
    "derivatives",
    "tangent",
    "kinematics",
    "rates",
    "point_derivatives",
    "point_kinematics",
    "derived_values",
    "derived_derivatives",
    "derived_kinematics",
    "complex_step",
    "complex_positions",
    "complex_tangent",
    "COMPLEX_STEP",
    "input_rates",
    "column_units",
    "check_sweep",
    "kinematics_frame",
    "label_frame",
    "scalar_attr",
    "LostDigitsWarning",
    "lost_digits",
    "DIGITS_RTOL",
]


# --------------------------------------------------------------------------- helpers
def column_units(mechanism) -> dict:
    """Units of the columns of :func:`kinematics` for a mechanism, column -> unit string.

    Examples
    --------
    >>> from numkin import linkages
    >>> column_units(linkages.slider_crank(80, 200))
    {'theta': 'rad', 'omega_theta3': 'rad/s', 'alpha_theta3': 'rad/s^2', 'v_x': 'mm/s', 'a_x': 'mm/s^2'}
    """
    return {name: q.unit for name, q in _unknown_columns(mechanism).items()}


def _unknown_columns(mech, source: str = "analytic", second_source: str | None = None) -> dict:
    """Column name -> :class:`~numkin.quantities.Quantity` of a kinematics table, in column order."""
    cols = {mech.input_name: input_quantity(mech)}
    for pair in unknown_quantities(mech, source, second_source):
        cols.update((q.name, q) for q in pair)
    return cols


def _singular_mask(sweep, mech, inputs, what: str, skip=()) -> np.ndarray:
    """Points whose Jacobian is singular (condition number above COND_MAX), but for `skip`; warns once."""
    cond = condition_numbers(sweep, inputs)
    if not cond.size or cond.max() <= COND_MAX:  # (a NaN fails the test)
        return np.zeros(cond.size, dtype=bool)
    bad = ~(cond <= COND_MAX)
    bad[list(skip)] = False
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        warn(
            f"{mech.name}: {what} undefined at {int(bad.sum())} point(s) where the Jacobian is singular "
            f"(a toggle or change point; first at input {deg_text(inputs[k])}, condition number {cond[k]:.3g}): "
            "set to NaN",
            SingularityWarning,
        )
    return bad


def _regular(cond, rtol=None) -> bool:
    """Whether every condition number is below those that make a point singular (``COND_MAX``), a
    change point (``CHANGE_COND``) or, given ``rtol``, one losing digits beyond it: one maximum decides all."""
    if not cond.size:
        return False
    top = float(cond.max())
    return top <= CHANGE_COND and top <= COND_MAX and (rtol is None or lost_digits(top, 2) <= rtol)  # (a NaN fails)


def _sweep_jacobian(sweep, q):
    """The Jacobian rows the sweep kept at its values, or None (then they are computed)."""
    rows = getattr(sweep, "jacobian_rows", None)
    if rows is None or len(rows) != q.shape[0] ** 2 or getattr(sweep, "values", None) is not q:
        return None
    return rows


def _change_point_checks(mech, t, cond) -> None:
    """Record the Jacobians :func:`~numkin.conditioning.change_points` evaluates: at both
    neighbours of every interior sample whose condition number exceeds ``CHANGE_COND``."""
    if t.size > 2 and not cond.max() <= CHANGE_COND:
        record_evaluations(mech, "J", 2 * int(np.count_nonzero(~(cond[1:-1] <= CHANGE_COND))))


def _rates(sweep, mech, q, t, p):
    """dq/dtheta and d2q/dtheta2 by block-triangular solves on the sweep's Jacobian (NaN where singular)."""
    jac = _sweep_jacobian(sweep, q)
    if jac is None:
        record_evaluations(mech, "J", t.size)
    record_evaluations(mech, "F_t", t.size)
    record_evaluations(mech, "second", t.size)
    return rates_of(mech.compiled, mech.block_structure, q, t, p, jac)


def _velocity(sweep, mech, q, t, p):
    """dq/dtheta alone by block-triangular solves on the sweep's Jacobian (NaN where singular)."""
    comp = mech.compiled
    jac = _sweep_jacobian(sweep, q)
    with np.errstate(all="ignore"):
        if jac is None:
            record_evaluations(mech, "J", t.size)
            jac = jacobian_rows(comp, q, t, p)
        record_evaluations(mech, "F_t", t.size)
        dq, _ = mech.block_structure.solve_negated(jac, comp.F_t(q, t, p), t.size)
    return dq


# --------------------------------------------------------------------------- unknowns
def tangent(sweep, *, at_change_point: str = "nan") -> np.ndarray:
    """First derivatives dq/dtheta of all unknowns, from the velocity equations only.

    Parameters
    ----------
    sweep : Sweep

    Returns
    -------
    ndarray, shape (n, N)
        Rows in ``sweep.unknowns`` order, per rad of input (rad/rad for
        angles, length unit/rad for lengths). NaN at singular points (with a
        :class:`~numkin.SingularityWarning`).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([90.0]))
    >>> print(np.round(analytic.tangent(sweep)[1], 6))   # dx/dtheta = -r at 90 deg
    [-80.]
    """
    mech, t, q = check_sweep(sweep)
    cond = condition_numbers(sweep, t)
    if _regular(cond):  # no singular or change point: nothing to mask
        check_at_change_point(at_change_point)
        return _velocity(sweep, mech, q, t, mech.parameter_values)
    change = change_points(sweep, mech, q, t, cond)
    _change_point_checks(mech, t, cond)
    bad = _singular_mask(sweep, mech, t, "dq/dtheta is", change)
    dq = _velocity(sweep, mech, q, t, mech.parameter_values)
    if bad.any():
        dq[:, bad] = np.nan
    continue_branch(mech, t, cond, change, [dq], "dq/dtheta", at_change_point)
    return dq


def derivatives(sweep, *, rtol: float = DIGITS_RTOL, at_change_point: str = "nan") -> tuple[np.ndarray, np.ndarray]:
    """dq/dtheta and d2q/dtheta2 of all unknowns from the differentiated loop equations.

    Solves ``J q' = -dF/dtheta`` and then ``J q'' = -(G_q q' + G_theta)``
    (with ``G = J q' + dF/dtheta``) at every point of the sweep in one
    vectorised batch. The stacked Jacobian of a multi-loop mechanism is
    block lower-triangular, so the chain rule through earlier loops is
    included.

    Parameters
    ----------
    sweep : Sweep
        A solved sweep (:meth:`Mechanism.sweep`).

    Returns
    -------
    dq, d2q : ndarray, shape (n, N)
        Rows in ``sweep.unknowns`` order, derivatives per rad of input
        (angles rad/rad and rad/rad^2; lengths in length unit per rad and
        per rad^2). NaN at points where the Jacobian is singular (toggle
        points), with a :class:`~numkin.SingularityWarning`.

    Other Parameters
    ----------------
    rtol : float, default DIGITS_RTOL
        Relative error above which the estimate of :func:`lost_digits`
        warns (:class:`~numkin.LostDigitsWarning`).
    at_change_point : {"nan", "continue"}, default "nan"
        The derivatives at a change point (see the notes): NaN, with the kept
        branch's values in the warning, or those values.

    Notes
    -----
    At a change point passed by a sweep run with ``on_singular="report"``
    (a sample with condition number above ``CHANGE_COND`` nearest a change
    point the sweep recorded, or between neighbours whose Jacobian
    determinants differ in sign)
    no value belongs to both branches. The branch the sweep kept continues
    smoothly through it: the polynomial through the ``CHANGE_NEIGHBOURS``
    regular samples on each side, evaluated at the change point, gives its
    derivatives there. They are named in a :class:`~numkin.SingularityWarning`
    and returned with ``at_change_point="continue"``; otherwise (and if
    there are too few samples on either side) the derivatives are NaN.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0]))
    >>> dq, d2q = analytic.derivatives(sweep)
    >>> float(d2q[1, 0])               # x'' = -r (1 + r/l) at theta = 0
    -112.0
    """
    mech, t, q = check_sweep(sweep)
    p = mech.parameter_values
    cond = condition_numbers(sweep, t)
    if _regular(cond, rtol):  # no singular, change or digit-losing point: nothing to mask, nothing to say
        check_at_change_point(at_change_point)
        return _rates(sweep, mech, q, t, p)
    change = change_points(sweep, mech, q, t, cond)
    _change_point_checks(mech, t, cond)
    bad = _singular_mask(sweep, mech, t, "dq/dtheta and d2q/dtheta2 are", change)
    dq, d2q = _rates(sweep, mech, q, t, p)  # (d2q is NaN wherever dq is not finite)
    if bad.any():
        dq[:, bad] = np.nan
        d2q[:, bad] = np.nan
    continue_branch(mech, t, cond, change, [dq, d2q], "dq/dtheta and d2q/dtheta2", at_change_point)
    warn_lost_digits(mech, t, cond, change, rtol)
    return dq, d2q


def kinematics(sweep, omega, alpha=0.0, *, at_change_point="nan"):
    """Angular velocities and accelerations (and linear ones of length unknowns) over a sweep.

    Parameters
    ----------
    sweep : Sweep
        A solved sweep of the mechanism.
    omega : float, str or array_like
        Angular speed of the input: a number in rad/s (either sign; the
        six-bar's crank turns clockwise at -10 rad/s), a string with units
        (``"450 rad/min"``, ``"6000 rpm"``), or one value per point of the
        sweep.
    alpha : float, str or array_like, default 0
        Angular acceleration of the input: rad/s^2, a string
        (``"2 rad/s^2"``), or one value per point. The input is taken to
        have speed `omega` and acceleration `alpha` at every listed
        position (for a constant speed, ``alpha = 0``).
    at_change_point : {"nan", "continue"}, default "nan"
        Values at a change point, as in :func:`derivatives`.

    Returns
    -------
    pandas.DataFrame
        One row per input. Column ``<input>`` (the input angle, rad); then,
        in unknown order, ``omega_<name>`` [rad/s] and ``alpha_<name>``
        [rad/s^2] for each angle unknown, ``v_<name>`` [length unit/s] and
        ``a_<name>`` [length unit/s^2] for each length unknown. Units are
        also in ``frame.attrs["units"]``.

    Raises
    ------
    numkin.units.UnitError
        If `omega` or `alpha` has the wrong dimension or cannot be read.

    Notes
    -----
    ``omega_q = omega_in q'`` and ``alpha_q = omega_in**2 q'' + alpha_in q'``
    with ``q'`` and ``q''`` from :func:`derivatives`.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 101)))
    >>> kin = analytic.kinematics(sweep, omega="450 rad/min")
    >>> row = kin.iloc[100]
    >>> print(f"{row['omega_beta']:.4f} rad/s, {row['alpha_beta']:.4f} rad/s^2")
    10.6329 rad/s, -28.3750 rad/s^2
    """
    mech, t, _ = check_sweep(sweep)
    w, a = input_rates(omega, alpha, t.size)
    first, second = rates(sweep, w, a, at_change_point=at_change_point)
    return kinematics_frame(mech, t, first, second, {"omega": w, "alpha": a, "method": "analytic"})


def rates(sweep, omega, alpha=0.0, *, at_change_point="nan") -> tuple[np.ndarray, np.ndarray]:
    """Time derivatives of all unknowns as arrays, without a DataFrame.

    The numbers of :func:`kinematics` (which builds its table from them):
    ``omega_in q'`` and ``omega_in**2 q'' + alpha_in q'``.

    Parameters
    ----------
    sweep : Sweep
    omega, alpha : float, str or array_like
        Input speed (rad/s) and acceleration (rad/s^2), as in :func:`kinematics`.
    at_change_point : {"nan", "continue"}, default "nan"
        As in :func:`derivatives`.

    Returns
    -------
    first, second : ndarray, shape (n, N)
        Rows in ``sweep.unknowns`` order: rad/s and rad/s^2 for angles,
        length unit/s and /s^2 for lengths.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 90.0]))
    >>> v, acc = analytic.rates(sweep, "6000 rpm")
    >>> print(np.round(acc[1] / 1000, 1))   # a_x in m/s^2
    [-44215.8  13783.8]
    """
    _, t, _ = check_sweep(sweep)
    w, a = input_rates(omega, alpha, t.size)
    dq, d2q = derivatives(sweep, at_change_point=at_change_point)
    d2q *= w * w  # the arrays are this call's own: scaled in place
    if np.any(a != 0):  # (d2q is NaN wherever dq is not finite, so a zero alpha adds nothing)
        d2q += a * dq
    dq *= w
    return dq, d2q


def scalar_attr(values: np.ndarray):
    """A rate for ``DataFrame.attrs``: a float when constant, else a tuple (never an array)."""
    values = np.asarray(values, dtype=float)
    return float(values[0]) if values.size and np.all(values == values[0]) else tuple(values.tolist())


def kinematics_frame(mech, t, first, second, attrs, source="analytic", second_source=None):
    """The kinematics DataFrame from time derivatives (n, N) of the unknowns.

    ``frame.attrs["quantities"]`` maps each column to its
    :class:`~numkin.quantities.Quantity` (source included) and
    ``frame.attrs["units"]`` each column to its unit.
    """
    import pandas as pd

    attrs = {k: scalar_attr(v) if k in ("omega", "alpha") else v for k, v in attrs.items()}
    quantities = _unknown_columns(mech, source, second_source)
    n = len(mech.unknowns)
    table = np.empty((t.size, 1 + 2 * n))  # one float block: the frame is built without a copy per column
    table[:, 0] = t
    table[:, 1::2] = np.asarray(first, dtype=float)[:n].T
    table[:, 2::2] = np.asarray(second, dtype=float)[:n].T
    frame = pd.DataFrame(table, columns=list(quantities), copy=False)
    label_frame(frame, quantities)
    frame.attrs.update(attrs)
    return frame


def label_frame(frame, quantities: dict) -> None:
    """Store each column's :class:`~numkin.quantities.Quantity` and unit in ``frame.attrs``."""
    frame.attrs["quantities"] = quantities
    frame.attrs["units"] = {name: q.unit for name, q in quantities.items()}


_EXPRESSIONS = ("point_derivatives", "point_kinematics", "derived_values", "derived_derivatives", "derived_kinematics")


def __getattr__(name):
    """The rates of named points and derived quantities live in :mod:`numkin.expressions`."""
    if name in _EXPRESSIONS:
        from . import expressions

        return getattr(expressions, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

"""What every error-analysis table computes alike: the input speed, the quantity studied, sweeps and points.

The table modules of :mod:`numkin.report` (:mod:`~numkin.report.convergence`,
:mod:`~numkin.report.workprecision`, :mod:`~numkin.report.roundoff`,
:mod:`~numkin.report.newton_tables`, :mod:`~numkin.report.tolerance`) build on
these: the input speed and the quantity studied (an unknown or a derived
quantity of :mod:`numkin.derived`, checked once; over a sweep it is a
:class:`~numkin.report.studied.StudiedQuantity`); the names and units of the
quantities; sweeps and one-point solves on the branch of the sweep from the
starting guess (:func:`branch_point`), by numkin's Newton
(:func:`solve_points`), shared by the tables of one report
(:func:`shared_results`); the solved positions a table carries in
``DataFrame.attrs``. The grids are in :mod:`~numkin.report.grids`, the
captions in :mod:`~numkin.report.captions`.

Examples
--------
>>> import math
>>> from numkin import linkages
>>> mech = linkages.chained_four_bars()
>>> quantity_labels(mech, "beta")[1], unknown_index(mech, "beta")
('omega_beta [rad/s]', 2)
>>> point = branch_point(mech, math.radians(100))   # continued from the guess at 0 deg
>>> round(math.degrees(float(point["beta"][0])) % 360, 4)
214.727
"""

from __future__ import annotations

import math
import warnings
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Callable, Mapping

import numpy as np

from .. import analytic, kinematics, units
from ..errors import InputError
from ..sweep import Sweep

__all__ = [
    "EPS",
    "input_speed",
    "unknown_index",
    "check_quantity",
    "quantity_labels",
    "table_quantities",
    "silenced",
    "shared_results",
    "shared_result",
    "solve_points",
    "solve_sweep",
    "branch_point",
    "position_record",
    "differenced",
    "exact_derivatives",
    "warned_once",
]

EPS = float(np.finfo(float).eps)


def input_speed(omega) -> float:
    """Input speed in rad/s from a number or a string with units (:func:`numkin.units.input_rate`); not 0,
    for the tables compare rates (a scene without a speed is reported per rad/s)."""
    w = units.input_rate(omega, "speed")
    if w == 0:
        raise InputError("omega = 0: the input is at rest and every rate is 0; give the input's speed (rad/s)")
    return w


def unknown_index(mechanism, quantity: str) -> int:
    """Row of the unknown `quantity` among the mechanism's unknowns (an InputError for anything else)."""
    if quantity not in mechanism.unknowns:
        raise InputError(
            f"quantity {quantity!r} is not an unknown of {mechanism.name}; choose one of {list(mechanism.unknowns)}"
        )
    return mechanism.unknowns.index(quantity)


def check_quantity(mechanism, quantity) -> None:
    """An InputError unless `quantity` names an unknown or a derived quantity (:mod:`numkin.derived`) of the
    mechanism: what an error table can study."""
    derived = list(getattr(mechanism, "derived", {}))
    if isinstance(quantity, str) and (quantity in mechanism.unknowns or quantity in derived):
        return
    also = f" (unknowns) or {derived} (derived quantities)" if derived else (
        " (unknowns), or declare a derived quantity (Mechanism.add_quantities, [mechanism.quantities])")
    raise InputError(f"quantity {quantity!r} is neither an unknown nor a derived quantity of {mechanism.name}; "
                     f"choose one of {list(mechanism.unknowns)}{also}")


def _rates(mechanism, quantity: str) -> dict:
    """The Quantities of one quantity's rates: 1, 2 (with respect to time), "d1", "d2" (to the input)."""
    from ..quantities import catalogue

    check_quantity(mechanism, quantity)
    position = catalogue(mechanism, (0,), points=False)[quantity].with_source("analytic")
    first, by_input = position.derivative(), position.derivative("input")
    return {1: first, 2: first.derivative(), "d1": by_input, "d2": by_input.derivative()}


def quantity_labels(mechanism, quantity: str) -> dict:
    """Labels, names and units of dq/dt, d2q/dt2, dq/dtheta and d2q/dtheta2 for one unknown or derived
    quantity, as its :class:`~numkin.quantities.Quantity` objects give them (``table_quantities`` maps each
    label back)."""
    q = _rates(mechanism, quantity)
    return {
        "unit": q[1].position().unit,
        1: q[1].label, 2: q[2].label, "d1": q["d1"].label, "d2": q["d2"].label,
        "name1": q[1].name, "name2": q[2].name, "unit1": q[1].unit, "unit2": q[2].unit,
        "input": mechanism.input_name,
    }


def table_quantities(mechanism, quantity: str) -> dict:
    """``attrs["quantities"]`` of a table about one unknown or derived quantity: each label of
    :func:`quantity_labels` -> its Quantity.

    Figures read the quantity, its symbol and unit from here, never from
    the label's text.

    Examples
    --------
    >>> from numkin import linkages
    >>> q = table_quantities(linkages.slider_crank(80, 200), "x")
    >>> q["v_x [mm/s]"].unit, q["d2x/dtheta^2 [mm/rad^2]"].order
    ('mm/s', 2)
    """
    return {q.label: q for q in _rates(mechanism, quantity).values()}


def silenced(fn, *args, **kwargs):
    """Call fn with numkin's warnings silenced (callers report what matters in the tables)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*args, **kwargs)


def solve_points(mechanism, x0, t, *, what: str = "position") -> np.ndarray:
    """Positions at the inputs `t` (rad, shape (M,)) by numkin's Newton from the starting points `x0` (n, M).

    One batch of ``numkin.newton.iterate`` with the mechanism's residual
    and symbolic Jacobian: the stopping rule of :mod:`numkin.newton` (scaled
    residual at ``tol = 1e-12``, superlinear steps down to ``tol**(2/3)``, so
    the error left is ``<= tol**(4/3)``) and its conditioning check (a
    Jacobian with scaled condition number above 1e12 is refused, never
    divided through). Each point is solved on its own from its starting
    point, so a starting point on a branch keeps that branch.

    Raises
    ------
    ConvergenceError
        If a point does not converge or meets a singular Jacobian, naming
        its input angle (a ``RuntimeError`` too).
    """
    from ..errors import ConvergenceError
    from ..newton import iterate

    t = np.asarray(t, dtype=float).reshape(-1)
    x0 = np.asarray(x0, dtype=float).reshape(len(mechanism.unknowns), t.size)
    out = iterate(
        mechanism.residual_function(t), mechanism.jacobian_function(t), x0,
        fscale=mechanism.length_scale, xscale=mechanism.xscale,
    )
    bad = np.flatnonzero(~out.converged)
    if bad.size:
        k = int(bad[0])
        why = "singular Jacobian" if out.singular[k] else f"scaled residual {float(out.residual[k]):.3g}"
        raise ConvergenceError(
            f"{mechanism.name}: {what} at input {math.degrees(float(t[k])):.6g} deg not solved by Newton ({why}; "
            f"{bad.size} of {t.size} points)",
            input_value=float(t[k]), cause="singular" if out.singular[k] else "no convergence",
        )
    return out.x


#: Results shared by the tables of one report (:func:`shared_results`); None outside one.
_SHARED: ContextVar = ContextVar("numkin_report_shared", default=None)


@contextmanager
def shared_results():
    """Within this block, the tables computed share their sweeps and derivatives instead of recomputing them.

    The convergence and work-precision tables sweep the same grids and
    difference them with the same schemes, the tolerance table sweeps one
    of those grids again: inside the block each sweep (same mechanism,
    inputs, guess and settings), its analytic derivatives and each scheme's
    differences on it are computed once. Every result is what the call would
    compute (the same function on the same arguments); the warnings a
    computation raised are raised again for every caller that asks for
    them (``quiet=False``). Nested blocks share the outer block's results.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.slider_crank(80, 200)
    >>> inputs = np.radians(np.arange(0.0, 361.0, 10.0))
    >>> with shared_results():
    ...     a = solve_sweep(mech, inputs)
    ...     b = solve_sweep(mech, inputs)
    >>> a is b, solve_sweep(mech, inputs) is a
    (True, False)
    """
    token = _SHARED.set({}) if _SHARED.get() is None else None
    try:
        yield
    finally:
        if token is not None:
            _SHARED.reset(token)


def _key(value):
    """A hashable, exact key for an argument (arrays by their bytes), or None if there is none."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return (type(value).__name__, value)
    if isinstance(value, np.ndarray):
        return ("array", value.dtype.str, value.shape, value.tobytes())
    if isinstance(value, np.generic):
        return ("scalar", value.dtype.str, value.tobytes())
    if isinstance(value, (list, tuple)):
        parts = tuple(_key(v) for v in value)
        return None if any(p is None for p in parts) else (type(value).__name__, parts)
    if isinstance(value, Mapping):
        parts = tuple((str(k), _key(v)) for k, v in value.items())
        return None if any(p[1] is None for p in parts) else ("mapping", parts)
    return None


def shared_result(key, compute: Callable, quiet: bool = True, keep=(), fresh: bool = False):
    """``compute()`` (its warnings silenced if `quiet`), once per `key` inside :func:`shared_results`.

    `keep` holds the objects whose ``id`` is in `key`, so that no other object takes that id while the
    result is kept. With `fresh`, computed anew (counted or timed) and kept for later callers.
    """
    store = _SHARED.get()
    if store is None or key is None:
        return silenced(compute) if quiet else compute()
    if fresh or key not in store:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            value = compute()
        store[key] = (value, list(caught), keep)
    value, caught, _ = store[key]
    if not quiet:
        for w in caught:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return value


def solve_sweep(mechanism, inputs, guess=None, *, quiet: bool = True, shared: bool = True, **kwargs) -> Sweep:
    """A sweep; with ``quiet=False`` its warnings (near-singular points, ...) reach the caller.

    Inside :func:`shared_results` (and with `shared`), one sweep per
    mechanism, inputs, guess and settings; pass ``shared=False`` to time it.
    """
    parts = _key((np.asarray(inputs, dtype=float), guess, sorted(kwargs.items()))) if shared else None
    key = None if parts is None else ("sweep", id(mechanism), parts)
    return shared_result(key, lambda: mechanism.sweep(inputs, guess, **kwargs), quiet, keep=(mechanism,))


def branch_point(mechanism, angle: float, guess=None, start: float = 0.0) -> Sweep:
    """A one-point sweep at `angle` on the branch of the sweep from `start`.

    `guess` is the starting guess at `start` (as for every sweep of this
    module: default the mechanism's own). The point is reached by
    continuation from `start` to `angle` in steps of at most 1 deg, as the
    scenes' sweeps go, never by applying the guess at `angle`; one more
    Newton solve (:func:`solve_points`) from the sweep's value then brings
    it to the last digits, the first point of a sweep included.
    """
    a, s0 = float(angle), float(start)
    if not (math.isfinite(a) and math.isfinite(s0)):
        raise InputError(f"the check angle and the start must be finite angles in rad, got {angle!r} and {start!r}")
    count = max(2, int(math.ceil(abs(a - s0) / math.radians(1.0))) + 1)
    inputs = np.array([s0]) if a == s0 else np.linspace(s0, a, count)
    s = solve_sweep(mechanism, inputs, guess)
    last = slice(inputs.size - 1, inputs.size)
    x = solve_points(mechanism, s.values[:, last], s.inputs[last], what="branch point")
    return Sweep(mechanism, s.inputs[last], x, s.iterations[last], s.residual[last], s.cond[last], list(s.events),
                 s.jacobian, s.tol)


def position_record(what: str, mechanism, angle: float, x) -> dict:
    """One solved position of a table, as kept in ``DataFrame.attrs["positions"]``."""
    x = np.asarray(x, dtype=float).reshape(-1)
    return {"what": what, "input [rad]": float(angle), **{u: float(v) for u, v in zip(mechanism.unknowns, x)}}


def differenced(sweep: Sweep, scheme, quiet: bool = True, *, fresh: bool = False) -> np.ndarray:
    """d/dtheta (or d2/dtheta2) of every unknown of `sweep` by the finite-difference `scheme` (a Scheme).

    Inside :func:`shared_results`, once per sweep and scheme; with `fresh`
    (where the work is counted or timed) computed anew, and kept.
    """
    return shared_result(("differenced", id(sweep), scheme.name), lambda: kinematics.sweep_derivative(sweep, scheme.name),
                   quiet, keep=(sweep,), fresh=fresh)


def exact_derivatives(sweep: Sweep, quiet: bool = True, *, fresh: bool = False) -> tuple:
    """The analytic ``(dq/dtheta, d2q/dtheta2)`` of `sweep` (:func:`numkin.analytic.derivatives`).

    Inside :func:`shared_results`, once per sweep; with `fresh` (where the
    evaluations are counted or timed) computed anew, and kept.
    """
    return shared_result(("exact", id(sweep)), lambda: analytic.derivatives(sweep), quiet, keep=(sweep,), fresh=fresh)


def warned_once(seen: set, fn, *args, **kwargs):
    """``fn(*args, **kwargs)``, its warnings raised again unless one like it was raised before under `seen`.

    Alike: the same category and text but for its numbers (the same wrapped angle on every grid and
    scheme of a table names other inputs), so a table warns once for each.

    Examples
    --------
    >>> import warnings
    >>> seen = set()
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     for k in (1, 2):
    ...         _ = warned_once(seen, warnings.warn, f"jump at {k}0 deg")
    >>> [str(w.message) for w in caught]
    ['jump at 10 deg']
    """
    import re

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = fn(*args, **kwargs)
    for w in caught:
        key = (w.category, re.sub(r"[-+]?\d[\d.eE+-]*", "#", str(w.message)))
        if key not in seen:
            seen.add(key)
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return out

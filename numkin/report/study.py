"""What every error-analysis table shares: settings, grids, labels, branch points, captions.

The table modules of :mod:`numkin.report` (:mod:`~numkin.report.convergence`,
:mod:`~numkin.report.workprecision`, :mod:`~numkin.report.roundoff`,
:mod:`~numkin.report.newton_tables`, :mod:`~numkin.report.tolerance`) build on
these: the input speed and the quantity studied (an unknown or a derived
quantity of :mod:`numkin.derived`, checked once; over a sweep it is a
:class:`~numkin.report.studied.StudiedQuantity`); the grids in points per
turn; the names and units of the quantities; sweeps and one-point
solves on the branch of the sweep from the starting guess (:func:`branch_point`),
by numkin's Newton (:func:`solve_points`); the caption and the solved positions a table
carries in ``DataFrame.attrs``.

Examples
--------
>>> import math
>>> from numkin import linkages
>>> mech = linkages.chained_four_bars()
>>> quantity_labels(mech, "beta")[1], unknown_index(mech, "beta")
('omega_beta [rad/s]', 2)
>>> grid_inputs(36, 0.0, TURN).size                 # a full turn: N + 1 samples
37
>>> point = branch_point(mech, math.radians(100))   # continued from the guess at 0 deg
>>> round(math.degrees(float(point["beta"][0])) % 360, 4)
214.727
"""

from __future__ import annotations

import math
import warnings
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Callable, Mapping, Sequence

import numpy as np

from .. import analytic, kinematics, units
from ..derivatives import SCHEMES, get_scheme
from ..errors import InputError
from ..sweep import Sweep

__all__ = [
    "EPS",
    "TURN",
    "DEFAULT_GRIDS",
    "UNIT",
    "VARIES",
    "input_speed",
    "unknown_index",
    "check_quantity",
    "quantity_labels",
    "table_quantities",
    "deg_text",
    "scheme_list",
    "too_coarse",
    "full_turn",
    "grid_inputs",
    "grid_list",
    "grid_study",
    "check_index",
    "silenced",
    "shared_results",
    "shared_result",
    "solve_points",
    "solve_sweep",
    "branch_point",
    "position_record",
    "differenced",
    "exact_derivatives",
    "order_text",
    "set_caption",
    "set_views",
    "grid_positions",
    "relative",
    "PEAK",
    "at_angle",
    "relative_text",
    "zero_text",
    "warned_once",
]

EPS = float(np.finfo(float).eps)
TURN = 2.0 * math.pi
#: Default grids, in points per turn of the input.
DEFAULT_GRIDS = (36, 72, 180, 360, 720, 1440, 3600)
#: Column names of absolute errors say this unit.
UNIT = "[unit of quantity]"
#: Column names of timings (and of what is chosen by them) say this: they vary between runs.
VARIES = "(varies)"


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


def deg_text(angle: float) -> str:
    return f"{math.degrees(angle):.6g}"


def scheme_list(names, periodic: bool | None = None, why: str | None = None) -> list:
    """Scheme objects for `names` (default: every registered scheme, the spectral ones only if periodic).

    A spectral scheme named on a grid that is not periodic is refused: ``why`` says what it needs
    (default: a grid over one full turn).
    """
    if names is None:
        return [s for s in SCHEMES.values() if periodic or not s.periodic_only]
    if isinstance(names, str):
        names = [names]
    out = [get_scheme(n) for n in names]
    if not out:
        raise InputError("schemes is empty: name at least one scheme, or pass None for all")
    if periodic is False:
        bad = [s.name for s in out if s.periodic_only]
        if bad:
            raise InputError(f"scheme(s) {bad} need {why or 'a grid over one full turn (span = 2 pi)'}")
    return out


def full_turn(span: float) -> bool:
    """Whether an input range of `span` rad is one full turn (a periodic grid)."""
    return abs(span - TURN) <= 1e-12 * TURN


def grid_inputs(points: int, start: float, span: float) -> np.ndarray:
    """Inputs of a grid with `points` per turn: a full turn (N + 1 samples) or `span` rad."""
    if isinstance(points, bool) or int(points) != points or points < 4:
        raise InputError(f"points per turn must be an integer >= 4, got {points!r}")
    points = int(points)
    h = TURN / points
    if full_turn(span):
        return start + h * np.arange(points + 1)
    if not (0 < span < TURN):
        raise InputError(f"span must be in (0, 2 pi] rad, got {span!r}")
    count = int(math.floor(span / h + 1e-9)) + 1
    if count < 5:
        raise InputError(f"span {math.degrees(span):.4g} deg holds fewer than 5 points of a {points}-point grid")
    return start + h * np.arange(count)


def grid_list(grids) -> list:
    if isinstance(grids, (int, np.integer)):
        grids = [grids]
    if isinstance(grids, str):
        raise InputError(f"grids must be points per turn (integers), got {grids!r}")
    out = []
    for g in grids:
        if isinstance(g, bool) or not isinstance(g, (int, np.integer, float)) or not math.isfinite(g) or g != int(g) \
                or g < 4:
            raise InputError(f"grids must be points per turn (integers >= 4), got {g!r} in {list(grids)!r}")
        out.append(int(g))
    if not out:
        raise InputError("grids must name at least one grid (points per turn)")
    if len(set(out)) != len(out):
        raise InputError(f"grids names a grid twice ({out}): the observed order needs distinct steps")
    return out


def grid_study(mechanism, omega, quantity: str, grids, span: float, schemes, start: float = 0.0,
               guess=None) -> tuple:
    """The checked arguments of a study over grids: ``(w, studied, grids, periodic, schemes)``.

    `w` is the input speed in rad/s, `studied` the :class:`StudiedQuantity`
    of `quantity` (an unknown or a derived quantity), `periodic` whether
    `span` is a full turn and the quantity returns to its start over it
    (:meth:`StudiedQuantity.closes`, decided on the tight sweep of the
    coarsest grid): a derived quantity that does not is studied on an open
    grid, as a part of a turn is.
    """
    from .studied import studied_quantity

    w = input_speed(omega)
    studied = studied_quantity(mechanism, quantity)
    grids = grid_list(grids)
    periodic, why = full_turn(span), None
    if periodic and studied.derived:
        coarse = solve_sweep(mechanism, grid_inputs(min(grids), start, span), guess)
        periodic = studied.closes(coarse)
        if not periodic:
            why = (f"a quantity that returns to its start after the turn; {studied.name} misses it by "
                   f"{studied.gap_text(coarse)}: leave the spectral schemes out")
    chosen = scheme_list(schemes, periodic, why)
    _grids_hold(chosen, grids, start, span, periodic)
    return w, studied, grids, periodic, chosen


def too_coarse(schemes, grids, start: float, span: float, periodic: bool) -> list:
    """The grids (points per turn) that hold fewer points over `span` than one of `schemes` needs, each as
    ``(grid, points, scheme name, points needed, "an open" or "a periodic")``, coarsest first."""
    out = []
    for n in sorted(grids):
        try:
            count = grid_inputs(n, start, span).size - (1 if periodic else 0)
        except InputError:  # fewer than 5 points over the span: too coarse for any table
            out.append((n, None, None, 5, "an open"))
            continue
        for s in schemes:
            try:
                s.function(np.zeros((1, count)), 1.0, periodic=periodic)
            except InputError as error:
                if error.cause != "too few samples":
                    raise
                out.append((n, count, s.name, error.minimum, error.grid))
                break
    return out


def _grids_hold(schemes, grids, start: float, span: float, periodic: bool) -> None:
    """An InputError naming ``grids`` where a grid over `span` holds fewer points than a scheme needs (before any
    sweep: a scheme on a grid too coarse for it has no value to tabulate)."""
    short = too_coarse(schemes, [min(grids)], start, span, periodic)
    if short and short[0][2] is not None:  # (fewer than 5 points: the table's own grid_inputs says so)
        n, count, name, minimum, grid = short[0]
        raise InputError(
            f"grids: the {n}-point grid holds {count} points over {math.degrees(span):.4g} deg, and scheme "
            f"'{name}' needs at least {minimum} on {grid} grid: give grids of more points per turn "
            "(or leave the scheme out)", cause="too few samples")


def check_index(inputs: np.ndarray, angle: float | None) -> int | None:
    """Index of the grid point at `angle` (mod 2 pi), or None if the grid does not hold it."""
    if angle is None:
        return None
    d = np.abs(np.remainder(inputs - angle + math.pi, TURN) - math.pi)
    k = int(np.argmin(d))
    return k if d[k] <= 1e-9 else None


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
    >>> with shared_results():
    ...     a = solve_sweep(mech, grid_inputs(36, 0.0, TURN))
    ...     b = solve_sweep(mech, grid_inputs(36, 0.0, TURN))
    >>> a is b, solve_sweep(mech, grid_inputs(36, 0.0, TURN)) is a
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


def order_text(scheme) -> str:
    return "spectral" if scheme.order == 0 else str(scheme.order)


def set_caption(df, text: str, positions: Sequence[dict] | None = None):
    """Set a table's caption and, if given, the positions it was computed at (``attrs["positions"]``)."""
    df.attrs["caption"] = text
    if positions is not None:
        df.attrs["positions"] = list(positions)
    return df


def set_views(df, views: Sequence, row_keys: Sequence | None = None) -> object:
    """Say how a wide table is read: ``attrs["views"]``, a list of ``[title, [columns]]``.

    Each view is one idea of the table, a few columns wide, and becomes a
    table of its own in Markdown, LaTeX and on the terminal
    (:mod:`~numkin.report.writers`; columns no view names make a last
    part); CSV keeps every column in one table. Columns not in `df` are
    dropped from a view; a view left with nothing but the columns that name
    a row (a table of run times, not timed) is left out. `row_keys`
    (``attrs["row_keys"]``) are the columns that name a row; the terminal
    repeats them in each part of a view too wide for one screen.
    """
    keys = [str(c) for c in (row_keys or ()) if c in df.columns]
    if row_keys is not None:
        df.attrs["row_keys"] = keys
    out = []
    for title, cols in views:
        cols = [c for c in cols if c in df.columns]
        if any(str(c) not in keys for c in cols):
            out.append([str(title), list(cols)])
    df.attrs["views"] = out
    return df


def grid_positions(mechanism, sweeps: Mapping, angle: float | None) -> list:
    """``attrs["positions"]`` of a table of sweeps: each sweep at `angle` (or its middle sample, if None)."""
    out = []
    for n, s in sweeps.items():
        k = s.inputs.size // 2 if angle is None else check_index(s.inputs, angle)
        if k is not None:
            out.append(position_record(f"{n} points per turn", mechanism, s.inputs[k], s.values[:, k]))
    return out


def relative(error: float, exact) -> float:
    """``error / max|exact|``; NaN where the exact values are all 0 (a relative error is undefined there).

    The exact derivative of a quantity linear in the input (``r2*theta2``) is 0 to the last bit: the
    chain rule of :mod:`numkin.expressions` gives it so; then say so in the caption (:func:`zero_text`).

    Examples
    --------
    >>> relative(0.5, [1.0, -2.0]), relative(0.5, [0.0, 0.0])
    (0.25, nan)
    """
    peak = float(np.max(np.abs(np.asarray(exact, dtype=float))))
    return error / peak if peak > 0 else math.nan


#: Denominator of a relative error taken over the sweep (:func:`relative`), as :func:`relative_text` names it.
PEAK = "the largest |exact value| over the sweep"


def at_angle(where: str) -> str:
    """Denominator of a relative error taken at one input angle, ``"theta = 100 deg"``, for :func:`relative_text`."""
    return f"|exact value| at {where}"


def relative_text(columns: Mapping[str, str]) -> str:
    """A caption's sentence naming the denominator of each relative-error column.

    Parameters
    ----------
    columns : mapping
        Column (or its name as the caption calls it) -> denominator
        (:data:`PEAK`, :func:`at_angle` or a phrase of the same kind).
        Columns of one denominator are named together, in the given order.

    Returns
    -------
    str
        A sentence with a leading space, to append to a caption ("" for no column).

    Examples
    --------
    >>> relative_text({"max rel error [-]": PEAK})
    ' Relative errors: max rel error [-] is divided by the largest |exact value| over the sweep.'
    >>> text = relative_text({"max rel error": PEAK, "rel error at 5 deg": at_angle("5 deg")})
    >>> print(text.strip())  # doctest: +NORMALIZE_WHITESPACE
    Relative errors: max rel error is divided by the largest |exact value| over the sweep; rel error at 5 deg by
    |exact value| at 5 deg.
    """
    groups: dict = {}
    for column, denominator in columns.items():
        groups.setdefault(denominator, []).append(str(column))
    parts = []
    for k, (denominator, names) in enumerate(groups.items()):
        verb = ("is" if len(names) == 1 else "are") + " divided by" if k == 0 else "by"
        listed = names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"
        parts.append(f"{listed} {verb} {denominator}")
    return " Relative errors: " + "; ".join(parts) + "." if parts else ""


def zero_text(names) -> str:
    """A caption's sentence on the quantities whose exact value is 0 over the whole sweep (relative errors blank)."""
    if not names:
        return ""
    return (f" The exact {' and '.join(sorted(names))} is 0 over the whole sweep: its relative error is undefined and "
            "left blank (its absolute errors stand).")


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

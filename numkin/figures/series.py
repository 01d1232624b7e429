"""What a curve figure draws of a name: an unknown of the sweep, or a derived quantity of its mechanism.

A derived quantity (``mu = theta4 - theta3``, declared with
:meth:`numkin.Mechanism.add_quantities` or a scene's ``[mechanism.quantities]``)
is drawn wherever an unknown is. Its samples over the sweep are its
expression evaluated at the solved unknowns (:func:`numkin.analytic.derived_values`),
an angle unwrapped as the unknowns' angles are continuous (:func:`sampled`).
Its rates come from the frames a figure is given (:func:`with_rates`): the
analytic ones from :func:`numkin.analytic.derived_kinematics` at the frame's
input speed, the finite-difference ones by the frame's own schemes applied
to the samples, as :func:`numkin.kinematics.finite_difference` does for an
unknown (unwrapped, periodicity settled by :func:`numkin.kinematics.prepare_rows`,
as :func:`numkin.compare.compare` does for a derived quantity).

Examples
--------
>>> import numpy as np
>>> from numkin import linkages
>>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
>>> sweep = mech.sweep(np.radians([0.0, 90.0]))
>>> print(np.degrees(sampled(sweep, "mu")).round(4))
[60.     86.8153]
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, warn
from ..units import is_full_turn
from .labels import derived_of, input_name, is_angle, length_unit, rate_columns

__all__ = ["sampled", "with_rates"]


def sampled(sweep, name: str) -> np.ndarray:
    """The values of an unknown or derived quantity over the sweep (rad or the length unit).

    An unknown's are the sweep's own. A derived angle is unwrapped as
    :func:`numkin.kinematics.prepare_rows` unwraps it before differencing
    (:func:`numkin.kinematics.unwrap_angles`, with its tangent from the chain
    rule): where neighbouring samples jump by more than half a turn (an
    ``atan2`` crossing ±180°), the whole turns the tangent does not account
    for are removed, with the same warning (``wrapped data``); a real turn of
    more than half a turn between samples is kept, and warned of as a grid
    too coarse. Samples where its expression is undefined stay NaN.
    """
    if name in sweep.unknowns:
        return sweep[name]
    from ..expressions import derived_values

    y = np.array(derived_values(sweep, [name])[name], dtype=float)
    return _unwrapped(sweep, name, y) if is_angle(sweep, name) else y


def _derived_tangent(sweep, name: str) -> np.ndarray:
    """A derived quantity's derivative with respect to the input over the sweep (chain rule; NaN where undefined)."""
    from ..expressions import derived_derivatives

    return np.asarray(derived_derivatives(sweep, [name])[name][1], dtype=float)


def _unwrapped(sweep, name: str, y: np.ndarray) -> np.ndarray:
    """A derived angle's samples unwrapped by their tangent (:func:`numkin.kinematics.unwrap_angles`): each run
    of samples where it is defined on its own (a step across undefined samples is left as it is)."""
    from ..kinematics import unwrap_angles

    if np.isfinite(y).sum() < 2:
        return y
    return unwrap_angles(y[None], [True], [name], np.asarray(sweep.inputs), lambda: _derived_tangent(sweep, name)[None],
                         "drawing and differencing")[0]


def _span(t: np.ndarray) -> str:
    return f"{t.size} inputs from {math.degrees(t[0]):.6g}° to {math.degrees(t[-1]):.6g}°" if t.size else "no inputs"


def _rows_on(frame, sweep):
    """Indices of the sweep's inputs at the frame's rows, or None when some row is at no input of the sweep."""
    col = input_name(sweep)
    if col not in frame.columns:
        return np.arange(len(sweep)) if len(frame) == len(sweep) else None
    t = np.asarray(frame[col], dtype=float)
    s = sweep.inputs
    if t.size == 0 or not np.isfinite(t).all():
        return None
    order = np.argsort(s, kind="stable")
    pos = np.clip(np.searchsorted(s[order], t), 1, s.size - 1) if s.size > 1 else np.zeros(t.size, dtype=int)
    near = np.where(np.abs(s[order][pos - 1] - t) <= np.abs(s[order][pos] - t), pos - 1, pos) if s.size > 1 else pos
    idx = order[near]
    return idx if np.all(np.abs(s[idx] - t) <= 1e-12) else None


def _grid(sweep, idx: np.ndarray, periodic):
    """The grid of the frame's inputs: the sweep's own, or that of a uniform subset of them (None if not uniform)."""
    from ..kinematics import SweepGrid, sweep_grid

    if idx.size == len(sweep) and np.array_equal(idx, np.arange(len(sweep))):
        return sweep_grid(sweep, periodic)
    t = sweep.inputs[idx]
    d = np.diff(t)
    if t.size < 2 or not np.allclose(d, d[0], rtol=1e-9, atol=1e-14):
        return None
    full = is_full_turn(t)
    h = float(np.mean(d))
    return SweepGrid(h=abs(h), periodic=full and periodic is not False, reverse=h < 0, full_turn=full)


def _cannot(frame, sweep, name: str, needed: tuple, maker: str):
    """Why the rates of `name` cannot be added to a frame (None if they can), and the rows of the sweep it lies on."""
    vcol, _ = rate_columns(sweep, name)
    missing = [a for a in needed if a not in frame.attrs]
    if missing:
        return (f"holds no {vcol!r} column and lacks the attrs {missing} that say how it was made "
                f"({maker} sets them; they are lost when a frame is rebuilt)"), None
    idx = _rows_on(frame, sweep)
    if idx is None:
        col = input_name(sweep)
        t = np.asarray(frame[col], dtype=float) if col in frame.columns else np.array([])
        return (f"lies on {_span(t) if t.size else f'{len(frame)} rows without a {col!r} column'}, not on "
                f"inputs of this sweep ({_span(sweep.inputs)}): the values of {name!r} are known only at the "
                f"sweep's inputs; give the frame made from this sweep (or from a sweep with the frame's inputs)"), None
    return None, idx


def _analytic_rates(sweep, name: str, frame, idx):
    """``frame`` with the exact rates of the derived quantity `name` added, at the frame's input speed."""
    from ..expressions import derived_kinematics

    attrs = frame.attrs
    kin = derived_kinematics(sweep, attrs["omega"], attrs.get("alpha", 0.0), names=[name])
    out = frame.copy()
    for col in rate_columns(sweep, name):
        out[col] = kin[col].to_numpy()[idx]
    return out


def _closes(sweep, name: str, y: np.ndarray):
    """``(closes, text of value[-1] - value[0])``: whether `y` returns to its start after one turn (whole turns
    for an angle), by the tolerance :func:`numkin.kinematics.prepare_rows` applies to an unknown."""
    from ..kinematics import closes

    off = float(y[-1] - y[0])
    angle = is_angle(sweep, name)
    text = f"{math.degrees(off):.6g}°" if angle else f"{off:.6g} {length_unit(sweep)}"
    return closes(off, angle, sweep.mechanism.length_scale), text


def _runs_rates(y: np.ndarray, grid, s1, s2) -> tuple[np.ndarray, np.ndarray]:
    """First and second differences of samples with NaN gaps: each run of defined samples on its own (open
    grid), NaN wherever an interior stencil would reach into a gap (values of one-sided stencils at a gap
    are not drawn as if interior ones) or a run is too short for the schemes."""
    from ..kinematics import Rows
    from .ends import scheme_reach

    ya = y[::-1] if grid.reverse else y
    d1, d2 = np.full(ya.size, np.nan), np.full(ya.size, np.nan)
    (b1, f1), (b2, f2) = scheme_reach([s1.name]), scheme_reach([s1.name, s2.name])
    edges = np.flatnonzero(np.diff(np.concatenate([[0], np.isfinite(ya).astype(int), [0]])))
    for i0, i1 in zip(edges[::2], edges[1::2]):
        rows = Rows(ya[None, i0:i1], grid.h, False, False, None)
        try:
            a1, a2 = rows.apply(s1)[0], rows.apply(s2)[0]
        except (InputError, ValueError):  # too few samples in this run for the stencils
            continue
        if i0 > 0:
            a1[:b1], a2[:b2] = np.nan, np.nan
        if i1 < ya.size:
            a1[a1.size - f1:], a2[a2.size - f2:] = np.nan, np.nan
        d1[i0:i1], d2[i0:i1] = a1, a2
    return (d1[::-1], d2[::-1]) if grid.reverse else (d1, d2)


def _scheme_rates(sweep, name: str, key, frame, values: np.ndarray, idx):
    """``frame`` with the rates of `name` by the frame's schemes (``attrs["method"]``, ``"second_method"``).

    A quantity undefined (NaN) at some inputs is differenced run by run of
    defined samples (:func:`_runs_rates`), as an open grid. One that does
    not return to its starting value after a full turn is differenced as
    open (with a warning), as an unknown's frame with ``periodic="auto"`` is.
    """
    from dataclasses import replace

    from ..analytic import input_rates
    from ..kinematics import prepare_rows, scheme_for

    attrs = frame.attrs
    s1 = scheme_for(attrs["method"], 1, "method")
    s2 = scheme_for(attrs["second_method"], 2, "second_method")
    periodic = "auto" if attrs.get("periodic") else False
    grid = _grid(sweep, idx, periodic)
    t, y = sweep.inputs[idx], values[idx]
    if grid is None:
        raise InputError(f"finite[{key!r}]: its inputs ({_span(t)}) are not a uniform grid: the schemes cannot be "
                         f"applied to {name!r}")
    defined = bool(np.isfinite(y).all())
    why = None
    if not defined:
        why = f"{name!r} is undefined (NaN) at {int((~np.isfinite(y)).sum())} of its inputs"
    elif grid.periodic:
        ok, off = _closes(sweep, name, y)
        if not ok:
            why = (f"{name!r} does not return to its starting value after one turn of the input "
                   f"({name}[-1] - {name}[0] = {off}, not a whole number of turns)")
    periodic_only = [s.name for s in (s1, s2) if s.periodic_only]
    if periodic_only and (why or not grid.periodic):
        raise InputError(f"finite[{key!r}]: scheme {periodic_only[0]!r} needs a quantity periodic over exactly one "
                         f"turn of the input, and {why or 'the grid is open'}: give {name!r} a frame of a stencil "
                         "scheme (centred, five_point)")
    if defined:
        if why:
            expr = derived_of(sweep)[name].expression
            warn(f"{why}: {name} = {expr} is not periodic in {input_name(sweep)}; finite[{key!r}] differences it "
                 "as an open grid", UserWarning)
            grid, periodic = replace(grid, periodic=False), False
        rows = prepare_rows(y[None, :], [is_angle(sweep, name)], [name], t, grid, sweep.mechanism.length_scale,
                            periodic, tangent=lambda: _derived_tangent(sweep, name)[idx][None])
        d1, d2, is_periodic = rows.apply(s1)[0], rows.apply(s2)[0], rows.periodic
    else:
        (d1, d2), is_periodic = _runs_rates(y, grid, s1, s2), False
    w, a = input_rates(attrs["omega"], attrs.get("alpha", 0.0), t.size)
    vcol, acol = rate_columns(sweep, name)
    out = frame.copy()
    out[vcol], out[acol] = w * d1, w**2 * d2 + a * d1
    out.attrs["periodic"] = is_periodic  # a derived quantity that does not close is differenced as open
    return out


def with_rates(sweep, name: str, analytic=None, finite=None, *, where: str = "kinematics", strict: bool = True):
    """The frames a curve figure draws `name` from, with a derived quantity's rates added where missing.

    For an unknown, or a derived quantity whose columns a frame already
    holds (a scene's comparisons, :func:`numkin.analytic.derived_kinematics`
    joined to the kinematics), the frames are returned as given. A frame
    without them gains them when it says how it was made and lies on
    inputs of the sweep (all of them, or a uniform subset: a frame of a
    coarser sweep of the same mechanism): the analytic frame of
    :func:`numkin.analytic.kinematics` (its ``attrs`` ``omega``, ``alpha``)
    the exact rates, a frame of :func:`numkin.kinematics.finite_difference`
    (its ``method``, ``second_method``, ``omega``, ``alpha``, ``periodic``)
    the same schemes applied to the derived quantity's samples at its
    inputs; a quantity undefined (NaN) at some inputs is differenced run by
    run of defined samples, NaN wherever a stencil reaches a gap; one that
    does not return to its start after a full turn is differenced as open,
    with a warning. Frames are copied, never changed. A frame that cannot gain them
    (its attrs lost, or its inputs not the sweep's) is refused by name, never
    left out silently.

    Parameters
    ----------
    sweep : Sweep
    name : str
        An unknown or a derived quantity of the sweep's mechanism.
    analytic : DataFrame, optional
    finite : mapping of str to DataFrame, optional
    where : str
        The figure, for messages.
    strict : bool
        Raise for a frame that cannot gain the rates; if False, warn and
        leave it out (:func:`numkin.figures.render` draws what it can).

    Returns
    -------
    tuple
        ``(analytic, finite)``: the analytic frame (or None) and a dict.

    Raises
    ------
    InputError
        With `strict`, for a frame that cannot gain the rates, naming it
        and why.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> from numkin.kinematics import finite_difference
    >>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
    >>> sweep = mech.sweep(np.radians(np.arange(0, 361)))
    >>> exact, fd = with_rates(sweep, "mu", analytic.kinematics(sweep, 10.0),
    ...                        {"centred": finite_difference(sweep, 10.0)})
    >>> print(f"{exact['omega_mu'][90]:.4f} rad/s exact, {fd['centred']['omega_mu'][90]:.4f} rad/s centred")
    4.4513 rad/s exact, 4.4511 rad/s centred
    """
    finite = dict(finite or {})
    if name not in derived_of(sweep):
        return analytic, finite
    cols = set(rate_columns(sweep, name))
    refused = []
    if analytic is not None and not cols & set(analytic.columns):
        why, idx = _cannot(analytic, sweep, name, ("omega",), "numkin.analytic.kinematics")
        if why:
            refused.append(("analytic", why))
            analytic = None
        else:
            analytic = _analytic_rates(sweep, name, analytic, idx)
    values = None
    for key, frame in list(finite.items()):
        if cols & set(frame.columns):
            continue
        why, idx = _cannot(frame, sweep, name, ("method", "second_method", "omega"),
                           "numkin.kinematics.finite_difference")
        if why:
            refused.append((f"finite[{key!r}]", why))
            del finite[key]
            continue
        if values is None:
            values = sampled(sweep, name)
        finite[key] = _scheme_rates(sweep, name, key, frame, values, idx)
    if refused:
        text = "; ".join(f"{which} {why}" for which, why in refused)
        if strict:
            raise InputError(f"{where} of the derived quantity {name!r}: {text}")
        warn(f"{where} of the derived quantity {name!r}: {text}; not drawn", UserWarning)
    return analytic, finite

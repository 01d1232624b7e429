"""The grids of the error tables: points per turn, the inputs of a grid, the schemes a grid can hold.

A grid is given in points per turn of the input (:data:`DEFAULT_GRIDS`); over
a full turn it is periodic (N + 1 samples, the last one the first a turn
on), over a part of a turn it is open. :func:`grid_study` checks the
arguments every table over grids takes (the input speed, the quantity, the
grids, the schemes, whether the grid is periodic for that quantity);
:func:`too_coarse` finds the grids too coarse for a scheme over a span.

Examples
--------
>>> grid_inputs(36, 0.0, TURN).size                 # a full turn: N + 1 samples
37
>>> grid_inputs(36, 0.0, math.radians(90)).size     # a quarter turn, open: 0, 10, ..., 90 deg
10
>>> check_index(grid_inputs(36, 0.0, TURN), math.radians(100))
10
"""

from __future__ import annotations

import math
from typing import Mapping

import numpy as np

from ..derivatives import SCHEMES, get_scheme
from ..errors import InputError
from .study import input_speed, position_record, solve_sweep

#: One turn of the input, rad.
TURN = 2.0 * math.pi

__all__ = ["TURN", "DEFAULT_GRIDS", "scheme_list", "full_turn", "grid_inputs", "grid_list", "grid_study", "too_coarse",
           "check_index", "grid_positions"]

#: Default grids, in points per turn of the input.
DEFAULT_GRIDS = (36, 72, 180, 360, 720, 1440, 3600)


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
    """Grids (points per turn: an integer or a sequence of them) as a list of distinct integers of at least 4.

    >>> grid_list(36), grid_list([36.0, 72])
    ([36], [36, 72])
    """
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


def grid_positions(mechanism, sweeps: Mapping, angle: float | None) -> list:
    """``attrs["positions"]`` of a table of sweeps: each sweep at `angle` (or its middle sample, if None)."""
    out = []
    for n, s in sweeps.items():
        k = s.inputs.size // 2 if angle is None else check_index(s.inputs, angle)
        if k is not None:
            out.append(position_record(f"{n} points per turn", mechanism, s.inputs[k], s.values[:, k]))
    return out

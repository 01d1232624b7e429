"""Reading what a student handed in: a name still ``...`` or not defined, a function not written yet, text, numbers,
arrays on a grid of angles in degrees, and angles read in radians or in degrees.

Arrays are sampled on a grid of input angles in degrees, for example
``grid=(0, 360, 1)`` for θ = 0°, 1°, …, 360° (:data:`FULL_TURN`).  Each reader
returns the student's values as floats or raises ``AssertionError`` with the
student's message: not set yet, not defined, the wrong shape, not finite where
it is checked, angles in another unit than the one asked (:func:`unit_of`).
"""

from __future__ import annotations

import math

import numpy as np

from .diagnose import _pair

__all__ = [
    "FULL_TURN",
    "returned",
    "text",
    "floats",
    "array",
    "rows",
    "at",
    "unit_of",
    "angles",
]


FULL_TURN = (0, 360, 1)
"""The default grid: θ = 0°, 1°, …, 360° (361 samples)."""


def _present(x, name: str) -> None:
    """The student's message for a name still set to the stub's ``...`` (not set yet) or not defined (None)."""
    if x is Ellipsis:
        raise AssertionError(
            f"`{name}` is not set yet: replace its `...` with your answer and run the cell that computes it"
        )
    if x is None:
        raise AssertionError(
            f"`{name}` is not defined: did the cell that computes it raise an error? run it and read the "
            "error (or it is None, which a function without `return` gives)"
        )


def returned(x, name: str, call: str):
    """What the student's function ``name`` returned (``call`` shows how it was called), or the student's
    message: a function that returns None is not written yet (the stub's body is ``...``) or has no ``return``.

    >>> returned(None, "F", "F(x, theta2)")
    Traceback (most recent call last):
    AssertionError: `F` is not written yet: `F(x, theta2)` returns None (its body is still `...`, or it has no `return`)
    """
    if x is None:
        raise AssertionError(
            f"`{name}` is not written yet: `{call}` returns None (its body is still `...`, or it has no `return`)"
        )
    return x


def text(x, name: str) -> str:
    """``x`` as text (an answer in words), or the student's message: not set yet, not defined, or not text.

    >>> text("  Centred ", "more_accurate")
    'centred'
    """
    _present(x, name)
    if not isinstance(x, str):
        raise AssertionError(f"`{name}` should be text (a word, in quotes), got {type(x).__name__}")
    return x.strip().lower()


def floats(x, name: str, what: str = "an array of numbers") -> np.ndarray:
    """``x`` as a float array, or the student's message: not set yet, not defined, or not ``what``.

    A name still set to the stub's ``...`` is not set yet.  A name the notebook
    does not define reaches the checks as None (otter passes None for a missing
    variable): the cell that should define it raised an error before it got
    there, or it holds what a function without ``return`` gives.
    """
    _present(x, name)
    try:
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise AssertionError(f"`{name}` should be {what}, got {type(x).__name__}") from None


def _grid_angles(grid) -> np.ndarray:
    start, stop, step = grid
    return np.arange(start, stop + step / 2, step, dtype=float)


def _grid_text(grid) -> str:
    start, stop, step = grid
    return f"θ = {start:g}°, {start + step:g}°, …, {stop:g}°"


def array(x, name: str, grid=FULL_TURN, *, forward: bool = False) -> np.ndarray:
    """``x`` as a 1-D float array with one value per grid angle.

    A grid that stops one step short (0°, 1°, …, 359°) is accepted too.
    ``forward``: the values of a forward formula (the forward difference
    applied twice), which are undefined at the last angles only: a short
    array is read from 0°, and NaN is allowed at the last two angles.
    """
    values = floats(x, name)
    values = np.atleast_1d(np.squeeze(values))
    count = _grid_angles(grid).size
    if values.ndim != 1 or values.size not in (count, count - 1, count - 2):
        raise AssertionError(
            f"`{name}` should hold {count} values, one for each {_grid_text(grid)}; "
            f"got shape {np.shape(x)}"
        )
    if values.size == count - 1:  # stops one step short (np.diff, or 0°…359°): read from the start
        values = np.append(values, np.nan)
    elif values.size == count - 2 and forward:  # np.diff(y, 2): from 0° to 358°
        values = np.append(values, [np.nan, np.nan])
    elif values.size == count - 2:  # interior points only, e.g. (y[2:] - y[:-2]) / (2h)
        values = np.concatenate([[np.nan], values, [np.nan]])
    first, last = (0, -2) if forward else (1, -1)  # a forward formula is defined at 0°
    bad = np.flatnonzero(~np.isfinite(values[first:last])) + first
    if bad.size:  # NaN at the two ends is allowed: the checks compare interior angles
        where = _grid_angles(grid)[bad[0]]
        raise AssertionError(
            f"`{name}` is {values[bad[0]]} at θ = {where:g}° ({bad.size} such interior values): "
            "a solve that failed there, or a formula that left it undefined"
        )
    return values


def rows(x, name: str, width: int, grid=FULL_TURN) -> np.ndarray:
    """``x`` as a float array of one row of ``width`` unknowns per grid angle, all finite."""
    values = floats(x, name)
    count = _grid_angles(grid).size
    if values.ndim == 2 and values.shape == (width, count):
        values = values.T
    if values.ndim != 2 or values.shape != (count, width):
        raise AssertionError(
            f"`{name}` should have one row of {width} unknowns for each {_grid_text(grid)} "
            f"({count} × {width}); got shape {np.shape(x)}"
        )
    bad = np.flatnonzero(~np.isfinite(values).all(axis=1))
    if bad.size:
        raise AssertionError(
            f"`{name}` is not finite at θ = {_grid_angles(grid)[bad[0]]:g}° ({bad.size} such rows): "
            "the solve failed or was not stored there"
        )
    return values


def _index(grid, deg: float) -> int:
    start, _, step = grid
    return int(round((float(deg) - start) / step))


def at(x, name: str, deg: float, grid=FULL_TURN) -> float:
    """The value of ``x`` at θ = ``deg``: a number, or picked from an array over the grid."""
    values = floats(x, name, "a number")
    if values.size == 1:
        result = float(values.reshape(-1)[0])
    else:
        values = array(x, name, grid)
        result = float(values[_index(grid, deg)])
    if not math.isfinite(result):
        end = _index(grid, deg) in (0, _grid_angles(grid).size - 1)
        raise AssertionError(
            f"`{name}` is {result} at θ = {deg:g}°"
            + (": an end of the grid, where the question asks for a value too (use a one-sided "
               "formula there, or values beyond the end)" if end else "")
        )
    return result


_current = ["the array"]  # name of the array being checked, for _pick's message


def _pick(values: np.ndarray, ref: dict, grid) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    degs = np.array(sorted(float(d) for d in ref))
    got = np.array([values[_index(grid, d)] for d in degs])
    want = np.array([float(ref[d]) for d in sorted(ref, key=float)])
    missing = np.flatnonzero(~np.isfinite(got))
    if missing.size:
        raise AssertionError(
            f"`{_current[0]}` has no value at θ = {degs[missing[0]]:g}°, an end of the grid that is "
            "checked: use a one-sided formula there, or values beyond the end"
        )
    return degs, got, want


def _wrapped(difference: np.ndarray) -> np.ndarray:
    return (difference + np.pi) % (2 * np.pi) - np.pi


def unit_of(name: str, x, ref: dict, *, grid=FULL_TURN, tol: float = 1e-6, allow=("rad", "deg")):
    """``"rad"`` or ``"deg"``: the unit in which the angles ``x`` match ``ref`` (radians).

    Angles are compared modulo a full turn, so wrapped (``% 360``) and
    unwrapped arrays are both accepted.  Raises with a message saying how far
    off the values are (and in which unit they were read) when neither fits.
    """
    values = array(x, name, grid)
    _current[0] = name
    degs, got, want = _pick(values, ref, grid)
    errors = {}
    for unit in ("rad", "deg"):
        read = got if unit == "rad" else np.radians(got)
        errors[unit] = np.abs(_wrapped(read - want))
        if unit in allow and errors[unit].max() <= tol:
            return unit
    for unit in ("rad", "deg"):
        if unit not in allow and errors[unit].max() <= tol:
            asked = "radians" if unit == "deg" else "degrees"
            word = "degrees" if unit == "deg" else "radians"
            raise AssertionError(
                f"`{name}`: the values look like {word}; the question asks for {asked}"
            )
    # neither unit fits everywhere: read it in the unit that fits at more angles
    def fitness(u):
        magnitude_says = (np.max(np.abs(values)) > 2 * np.pi + 0.5) == (u == "deg")
        return (int(np.sum(errors[u] <= tol)), magnitude_says)

    unit = max(allow, key=fitness)
    worst = int(np.argmax(errors[unit]))
    word = "radians" if unit == "rad" else "degrees"
    expected = want[worst] if unit == "rad" else math.degrees(want[worst])
    error_rad = errors[unit][worst]
    hint = ""
    if error_rad < 1e-2:
        hint = (
            " This is small: is your Newton iteration stopped too early (a loose tolerance"
            " such as |F| < 1e-4)?"
        )
    elif abs(error_rad - math.pi) < 1e-3:
        hint = (
            " Off by 180°: that is the mirror solution (a negative length along the link)."
            " Start each solve from the previous solution."
        )
    shown_want, shown_got = _pair(expected, got[worst])
    raise AssertionError(
        f"`{name}` (read as {word}) is off by up to {math.degrees(error_rad):.3g}° "
        f"({error_rad:.3g} rad): at θ = {degs[worst]:g}° expected {shown_want} "
        f"(or that plus whole turns), got {shown_got}.{hint}"
    )


def angles(name: str, x, ref: dict, *, grid=FULL_TURN, tol: float = 1e-6, allow=("rad", "deg")):
    """Check angles against ``ref`` (radians) in either allowed unit; print which was read."""
    unit = unit_of(name, x, ref, grid=grid, tol=tol, allow=allow)
    print(f"`{name}` read as {'radians' if unit == 'rad' else 'degrees'}")
    return unit

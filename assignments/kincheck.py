"""Feedback checks for the numkin homework.

Every homework folder ships this module next to its notebook, and the
autograder tests (``grader.check("q2")`` in the notebook, ``otter run`` for
grading) call it.  It holds no answers: the hidden tests pass in the reference
values, which ``python assignments/build.py expected`` computes with numkin.

Each check either returns quietly or raises ``AssertionError`` with a message
that says what looks off: a unit (degrees where radians are asked, rad/min
where rad/s is asked, rpm, rev/s, mm), a sign, the forward difference where the
centred one is asked, a Newton iteration stopped too early, a branch jump.

Arrays are sampled on a grid of input angles in degrees, for example
``grid=(0, 360, 1)`` for θ = 0°, 1°, …, 360°.  Reference values are given as
``{angle in degrees: value}`` and compared at those angles only, so that the
end points (where students pick their own one-sided formulas) do not matter.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

__all__ = [
    "ALTERNATIVE_CLOSER",
    "FLIPPED",
    "ROTATION",
    "SUSPECTS",
    "angles",
    "angle_value",
    "array",
    "floats",
    "text",
    "agrees_as_written",
    "as_written",
    "at",
    "band",
    "closure",
    "continuity",
    "chained_four_bar_angles",
    "chained_four_bar_assembly",
    "four_bar_side",
    "four_bar_gap",
    "own_difference",
    "quick_return_input_unit",
    "listed",
    "read_angle_group",
    "rows",
    "read_angles",
    "six_bar_gap",
    "explain_factor",
    "matches_alternative",
    "series",
    "unit_of",
    "value",
]

FULL_TURN = (0, 360, 1)
"""The default grid: θ = 0°, 1°, …, 360° (361 samples)."""

# name: (factor, hint when the answer is too large by it, hint when too small)
SUSPECTS = {
    "rad/min": (
        60.0,
        "rad/min where rad/s is asked? (1 rad/min = 1/60 rad/s)",
        "divided by 60 once too often? (1 rad/min = 1/60 rad/s)",
    ),
    "deg": (
        180.0 / math.pi,
        "degrees where radians are asked?",
        "radians where degrees are asked, or a step h in degrees under an angle in radians?",
    ),
    "rpm": (
        60.0 / (2.0 * math.pi),
        "rpm where rad/s is asked? (1 rpm = 2π/60 rad/s)",
        "converted rpm to rad/s twice?",
    ),
    "mm": (
        1000.0,
        "millimetres where metres are asked?",
        "metres where millimetres are asked?",
    ),
    "rev": (
        2.0 * math.pi,
        "multiplied by 2π once too often? (1 rev/s = 2π rad/s)",
        "rev/s (turns per second) where rad/s is asked? (1 rev/s = 2π rad/s)",
    ),
}

_FACTOR_TOLERANCE = 0.02  # relative, for recognising a unit factor

FLIPPED = "the sign is flipped"
"""What a check says of an answer that is the reference times −1, unless it is told more (``flipped=``).

A check knows what can flip the sign of its quantity and says so with ``flipped``:
:data:`ROTATION` for a rate linear in ω, a pointer to the minus sign of a formula, or
to the mirror solution for a negative length.
"""

ROTATION = FLIPPED + ": check the sense of rotation (clockwise is negative)"
"""The flipped sign of a quantity odd in ω (a velocity, ω dq/dθ): the sign of ω explains it.
An acceleration ω² d²q/dθ² or a position does not change sign with the sense of rotation."""

NEWTON_HINT = (
    "Differences this small have several causes: a difference formula other than the one "
    "asked (np.gradient, a one-sided or shifted formula, another step), or positions that "
    "are not converged (a loose Newton tolerance, which finite differences magnify; the "
    "position checks say whether yours are)"
)
"""The hint of a small miss that no alternative explains: it lists the causes, it does not pick one."""


# --------------------------------------------------------------------------
# reading what the student handed in
# --------------------------------------------------------------------------


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


def listed(name: str, x, want, *, rtol: float = 1e-3, unit: str = "") -> None:
    """Compare a short list of numbers with ``want`` element by element (relative ``rtol``)."""
    got = np.atleast_1d(floats(x, name, "a list of numbers")).ravel()
    want = np.asarray(want, dtype=float)
    if got.shape != want.shape:
        raise AssertionError(f"`{name}` should hold {want.size} numbers, got {got.size}")
    off = np.abs(got - want) > rtol * np.abs(want)
    if off.any():
        i = int(np.flatnonzero(off)[0])
        unit_text = f" {unit}" if unit else ""
        raise AssertionError(
            f"`{name}`[{i}] = {_fmt(got[i])}{unit_text}, expected {_fmt(want[i])}{unit_text} "
            f"(within {rtol:.2g} relative)"
        )


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


# --------------------------------------------------------------------------
# diagnosing a wrong number
# --------------------------------------------------------------------------


def _fmt(x: float) -> str:
    return f"{x:.5g}"


def _pair(want: float, got: float) -> tuple[str, str]:
    """``want`` and ``got`` with enough digits to show where they differ."""
    error = abs(got - want)
    size = max(abs(want), abs(got))
    digits = 5
    if error > 0 and size > 0:
        digits = min(12, max(5, math.ceil(math.log10(size / error)) + 2))
    return f"{want:.{digits}g}", f"{got:.{digits}g}"


_SYMBOLS = {
    # name: (symbol of the factor, symbol of its inverse)
    "rad/min": ("60", "1/60"),
    "deg": ("180/π", "π/180"),
    "rpm": ("60/2π", "2π/60"),
    "mm": ("1000", "1/1000"),
    "rev": ("2π", "1/2π"),
}


def _combinations(suspects):
    """Every (factor, [(name, power), ...]) from one or two suspects to the powers ±1, ±2."""
    names = [s for s in suspects if s in SUSPECTS]
    for count in (1, 2):
        for combo in itertools.combinations(names, count):
            for powers in itertools.product((-2, -1, 1, 2), repeat=count):
                factor = math.prod(SUSPECTS[n][0] ** p for n, p in zip(combo, powers))
                yield factor, list(zip(combo, powers))


def _describe(factor: float, terms, sign: float) -> str:
    parts, hints = [], []
    for n, p in terms:
        symbol = _SYMBOLS[n][0 if p > 0 else 1]
        if abs(p) == 2:
            symbol = f"({symbol})²" if "/" in symbol or "π" in symbol else f"{symbol}²"
        parts.append(symbol)
        hints.append(SUSPECTS[n][1 if p > 0 else 2])
    shown = f"{factor:.4g}" if factor >= 1 else f"1/{1 / factor:.4g}"
    explanation = " × ".join(parts)
    text = f"off by a factor {shown}"
    if explanation != shown:
        text += f" (= {explanation})"
    text += ": " + " And ".join(hints)
    if sign < 0:
        text += " The sign is flipped as well."
    return text


def _missing_step(ratio: float, step_rad: float | None) -> str | None:
    """The hint for a difference quotient that is ``h`` or ``h²`` times too small, else None.

    ``np.diff(y)`` without ``/ h`` (or a step of 1 where ``h`` is a degree in
    radians) gives exactly that ratio; it is named before any unit factor,
    because a missing division is the likelier slip when the quantity is a
    difference quotient.
    """
    if step_rad is None or not math.isfinite(ratio) or ratio == 0:
        return None
    for power, what in ((1, "a division by the step h is missing"), (2, "the division by h² is missing")):
        factor = step_rad**power
        if abs(math.log(abs(ratio) / factor)) < _FACTOR_TOLERANCE:
            symbol = "h" if power == 1 else "h²"
            text = (
                f"off by a factor 1/{1 / factor:.4g} (= {symbol}, with h = {step_rad:.4g} rad): "
                f"{what}? A difference quotient divides the differences (np.diff) by "
                f"{symbol}, with h in radians, not in degrees."
            )
            if ratio < 0:
                text += " The sign is flipped as well."
            return text
    return None


def explain_factor(
    ratio: float, suspects=("deg", "rad/min"), *, step_rad: float | None = None, flipped: str = FLIPPED
) -> str | None:
    """Name a unit mix-up that turns the right answer into ``ratio`` times it.

    Tries the listed ``SUSPECTS`` alone and in pairs, to the powers ±1 and ±2
    (an acceleration goes with ω², a second difference with 1/h²), with either
    sign.  Returns a message such as ``"off by a factor 60: rad/min where
    rad/s is asked? ..."``, or None when no combination fits within 2 %.

    ``step_rad`` is the grid step h (rad) when the quantity is a difference
    quotient: a ratio of h or h² is then named first as a missing division by
    the step (for a 1° grid that ratio is also π/180, which a degree slip gives).

    ``flipped`` is the message of a ratio of −1: what can flip the sign of this
    quantity (see :data:`FLIPPED` and :data:`ROTATION`).

    >>> explain_factor(math.pi / 180, ("deg",), step_rad=math.pi / 180)[:55]
    'off by a factor 1/57.3 (= h, with h = 0.01745 rad): a d'
    """
    if not math.isfinite(ratio) or ratio == 0:
        return None
    if abs(ratio + 1.0) < _FACTOR_TOLERANCE:
        return flipped
    size, sign = abs(ratio), math.copysign(1.0, ratio)
    if abs(size - 1.0) < _FACTOR_TOLERANCE:
        return None
    step_hint = _missing_step(ratio, step_rad)
    if step_hint:
        return step_hint
    best = None
    for factor, terms in _combinations(suspects):
        miss = abs(math.log(size / factor))
        if miss < _FACTOR_TOLERANCE and (best is None or (len(terms), miss) < best[0]):
            best = ((len(terms), miss), factor, terms)
    if best is None:
        return None
    return _describe(best[1], best[2], sign)


def _ratio(got: np.ndarray, want: np.ndarray) -> float | None:
    """The common ratio got/want, if the values are a constant multiple of the reference."""
    scale = np.max(np.abs(want))
    if scale == 0:
        return None
    keep = np.abs(want) > 0.2 * scale
    ratios = got[keep] / want[keep]
    middle = float(np.median(ratios))
    if middle == 0 or np.max(np.abs(ratios / middle - 1.0)) > _FACTOR_TOLERANCE:
        return None
    return middle


def _close(got, want, rtol: float, atol: float) -> np.ndarray:
    scale = np.max(np.abs(want)) if np.size(want) else 0.0
    return np.abs(np.asarray(got) - np.asarray(want)) <= atol + rtol * scale


# --------------------------------------------------------------------------
# checks
# --------------------------------------------------------------------------


def series(
    name: str,
    x,
    ref: dict,
    *,
    grid=FULL_TURN,
    unit: str = "",
    rtol: float = 1e-4,
    atol: float = 0.0,
    alternatives: tuple = (),
    suspects=("deg", "rad/min"),
    small_hint: str | None = NEWTON_HINT,
    step_rad: float | None = None,
    forward: bool = False,
    flipped: str = FLIPPED,
) -> None:
    """Compare an array over the grid with reference values at some angles.

    Passes when every ``|x - ref| <= atol + rtol * max|ref|``.  Otherwise
    ``alternatives`` — ``(reference dict, message)`` pairs such as the forward
    difference when the centred one is asked — are tried first (named when
    every value lies within that tolerance of the alternative and the largest
    miss from it is ``ALTERNATIVE_CLOSER`` times smaller than from ``ref``), then a unit
    factor (see :func:`explain_factor`; ``step_rad`` is the step h of a
    difference quotient), then the largest difference is reported.
    ``forward``: read ``x`` as the values of a forward formula (see :func:`array`).
    ``flipped``: the message of values that are the reference times −1 (see :data:`FLIPPED`).
    """
    values = array(x, name, grid, forward=forward)
    _current[0] = name
    degs, got, want = _pick(values, ref, grid)
    if _close(got, want, rtol, atol).all():
        return
    for alt_ref, message in alternatives:
        _, alt_got, alt_want = _pick(values, alt_ref, grid)
        closer = ALTERNATIVE_CLOSER * np.max(np.abs(alt_got - alt_want)) <= np.max(np.abs(got - want))
        if _close(alt_got, alt_want, rtol, atol).all() and closer:
            raise AssertionError(f"`{name}`: {message}")
    ratio = _ratio(got, want)
    if ratio is not None:
        hint = explain_factor(ratio, suspects, step_rad=step_rad, flipped=flipped)
        if hint:
            raise AssertionError(f"`{name}`: {hint}")
    worst = int(np.argmax(np.abs(got - want)))
    error = abs(got[worst] - want[worst])
    unit_text = f" {unit}" if unit else ""
    written = as_written(got, want, atol + rtol * np.max(np.abs(want)))
    if written:
        raise AssertionError(f"`{name}` is off by up to {error:.3g}{unit_text}, more than the check allows "
                             f"({_tolerance(rtol)}): {_written_hint(written, 'its values')}")
    shown_want, shown_got = _pair(want[worst], got[worst])
    message = (
        f"`{name}` is off by up to {error:.3g}{unit_text}: "
        f"at θ = {degs[worst]:g}° expected {shown_want}, got {shown_got}"
    )
    if small_hint and error < 0.05 * np.max(np.abs(want)):
        message += f". {small_hint}"
    raise AssertionError(message)


def _tolerance(rtol: float) -> str:
    return f"{rtol:.2%}" if rtol >= 1e-4 else f"{rtol:.1g} relative"


def value(
    name: str,
    x,
    want: float,
    *,
    deg: float | None = None,
    grid=FULL_TURN,
    unit: str = "",
    rtol: float = 5e-3,
    alternatives: tuple = (),
    suspects=("deg", "rad/min"),
    step_rad: float | None = None,
    flipped: str = FLIPPED,
) -> float:
    """Compare one number (or the value at θ = ``deg`` of an array) with ``want``.

    Passes within the relative tolerance ``rtol`` (0.5 % by default), unless
    it matches one of the ``alternatives``, ``(value, message)`` pairs such as
    the forward difference where the centred one is asked: an alternative's
    message is given when the number matches it (see
    :func:`matches_alternative`), even within ``rtol`` of ``want`` (a forward
    ω at 100° lies 0.3 % from the exact one, but 300 times closer to the
    forward value than the centred answer is).  Then a unit factor is
    tried (see :func:`explain_factor`; ``step_rad`` is the step h of a
    difference quotient; ``flipped`` is the message of the reference times
    −1, see :data:`FLIPPED`), then the miss is reported.  Returns the
    student's number.
    """
    got = at(x, name, deg, grid) if deg is not None else at(x, name, 0, grid)
    where = f" at θ = {deg:g}°" if deg is not None else ""
    unit_text = f" {unit}" if unit else ""
    for alt, message in alternatives:
        if matches_alternative(got, alt, want, rtol) and not agrees_as_written(got, want):
            raise AssertionError(f"`{name}`{where} = {got:.7g}{unit_text}, expected {want:.6g}{unit_text}: {message}")
    if abs(got - want) <= rtol * abs(want):
        return got
    hint = explain_factor(got / want, suspects, step_rad=step_rad, flipped=flipped) if want else None
    if hint:
        raise AssertionError(f"`{name}`{where} = {_fmt(got)}{unit_text}: {hint}")
    shown_want, shown_got = _pair(want, got)
    if agrees_as_written(got, want):
        rounded = f"; that is the expected value rounded to the {_figures(got)} figures written: give it unrounded"
    elif as_written(got, want) == SINGLE:
        rounded = f"; {_written_hint(SINGLE, 'it')}"
    else:
        rounded = ""
    raise AssertionError(
        f"`{name}`{where} = {shown_got}{unit_text}, expected {shown_want}{unit_text} "
        f"(within {_tolerance(rtol)}): "
        f"off by {100 * (got - want) / want:+.3g} %{rounded}"
    )


def angle_value(
    name: str, x, want: float, *, deg: float | None = None, grid=FULL_TURN, tol: float = 1e-7
) -> float:
    """Compare one angle (or the value at θ = ``deg`` of an array) with ``want`` (rad), modulo whole turns.

    Passes when the angle, in radians, is ``want`` plus whole turns (within
    ``tol`` relative to max(|want|, 1)).  An angle that is ``want`` in degrees
    (plus whole turns) is named as degrees where radians are asked; it is read
    before any reduction to one turn, which would hide the factor 180/π.  Any
    other miss is reported after reduction to one turn.  Returns the student's
    number.
    """
    got = at(x, name, deg, grid) if deg is not None else at(x, name, 0, grid)
    size = tol * max(abs(want), 1.0)

    def miss(angle_rad: float) -> float:
        return abs(float(_wrapped(np.float64(angle_rad - want))))

    if miss(got) <= size:
        return got
    where = f" at θ = {deg:g}°" if deg is not None else ""
    if miss(math.radians(got)) <= size:
        turns = round((got - math.degrees(want)) / 360.0)
        extra = f" plus {turns} whole turns" if turns else ""
        raise AssertionError(
            f"`{name}`{where} = {_fmt(got)} rad: that is the expected {math.degrees(want):.6g}°{extra} in degrees: "
            f"degrees where radians are asked? (expected {want:.6g} rad; use np.radians)"
        )
    nearest = want + float(_wrapped(np.float64(got - want)))  # the answer on the reference's turn
    return value(name, nearest, want, rtol=tol, unit="rad", suspects=())


ALTERNATIVE_CLOSER = 10.0
"""How many times closer to an alternative than to the reference a number must be for the alternative to be named."""


def agrees_as_written(got: float, want: float) -> bool:
    """Whether ``want``, rounded to the significant figures ``got`` is written with, is ``got``.

    A rounded answer (10.6 for 10.6329) may also round another formula's value
    (10.59998): no formula can be named from it.  Figures are those of the
    shortest repr of the float; a computed number (15 figures or more) is not
    rounded.

    >>> agrees_as_written(10.6, 10.6328965), agrees_as_written(10.59997952751215, 10.6328965)
    (True, False)
    """
    figures = _figures(got)
    return 0 < figures < 15 and float(f"{want:.{figures}g}") == float(f"{got:.{figures}g}")


SINGLE = "single precision (float32)"
"""What :func:`as_written` calls numbers that float32 holds exactly, near the reference."""


def as_written(got, want, allowed: float = 0.0) -> str | None:
    """How the numbers ``got`` are written, where that explains every miss from ``want``: ``"rounded to d
    decimals"`` (or to whole numbers), ``"rounded to s significant figures"``, :data:`SINGLE`; None where
    no rounding does.

    A number is read as rounded to d decimals (or s figures) when it is one, and its miss from the reference
    is at most half a unit of its last place, plus ``allowed`` (the check's own tolerance: the answer
    rounded may be of a value that was not quite the reference); the largest keeps at least two figures
    (zeros, or 0 and 1 for values below one, are no rounded answer).  Numbers that float32 holds exactly,
    most of them written with 8 figures or more (as a float32 value reads in float64; a typed 28.25 is
    no float32 answer), and that miss by at most 1e-4 of the largest reference are read as computed in
    single precision.  Non-finite entries are left out.

    >>> import numpy as np
    >>> want = np.array([10.63289649, -3.0512741, 0.00471233])
    >>> as_written(np.round(want, 4), want), as_written([10.633, -3.0513, 0.0047123], want)
    ('rounded to 4 decimals', 'rounded to 5 significant figures')
    >>> as_written(want.astype(np.float32), want), as_written(want + 1e-3, want), as_written(28.25, 28.26)
    ('single precision (float32)', None, None)
    """
    got = np.atleast_1d(np.asarray(got, dtype=float)).ravel()
    want = np.atleast_1d(np.asarray(want, dtype=float)).ravel()
    keep = np.isfinite(got) & np.isfinite(want)
    got, want = got[keep], want[keep]
    if not got.size:
        return None
    miss = np.abs(got - want) - allowed
    ulp = 4.0 * np.finfo(float).eps * np.abs(got)
    largest = float(np.max(np.abs(got)))
    for d in range(13):  # the fewest decimals the numbers are written with
        if np.all(np.abs(np.round(got, d) - got) <= ulp):
            if largest >= 10.0 ** (1 - d) and np.all(miss <= 0.5 * 10.0**-d + ulp):
                return "rounded to whole numbers" if d == 0 else f"rounded to {d} decimal{'s' if d > 1 else ''}"
            break
    for s in range(1, 15):  # the fewest significant figures
        if all(float(f"{g:.{s}g}") == g for g in got.tolist()):
            size = np.maximum(np.abs(got), np.abs(want))
            last = 10.0 ** (np.floor(np.log10(np.where(size > 0, size, 1.0))) - s + 1)
            if s >= 2 and np.all(miss <= 0.5 * last + ulp):
                return f"rounded to {s} significant figures"
            break
    long = sum(_figures(g) >= 8 for g in got.tolist())
    if (np.array_equal(got.astype(np.float32).astype(float), got) and 2 * long >= got.size
            and np.all(miss <= 1e-4 * np.max(np.abs(want)))):
        return SINGLE
    return None


def _written_hint(written: str, what: str) -> str:
    """What to do about numbers :func:`as_written` explains; ``what`` names them ("its values", "it")."""
    if written == SINGLE:
        return f"{what} {'is' if what == 'it' else 'are'} {SINGLE}, about 7 figures: compute in float64, numpy's default"
    return f"{what} {'is' if what == 'it' else 'are'} {written}: give {'it' if what == 'it' else 'them'} unrounded"


def _figures(got: float) -> int:
    """The significant figures of the shortest repr of ``got`` (10.6: 3)."""
    mantissa = repr(float(got)).split("e")[0]
    return len(mantissa.replace("-", "").replace(".", "").lstrip("0"))


def matches_alternative(got: float, alt: float, want: float, rtol: float) -> bool:
    """Whether ``got`` is evidence of the alternative formula ``alt`` rather than of ``want``.

    Both must hold: ``got`` lies within the check's own tolerance of the
    alternative (``|got - alt| <= rtol |alt|``), and it is at least
    ``ALTERNATIVE_CLOSER`` (10) times closer to the alternative than to the
    reference.  A number between the two, or near neither, names no formula.

    >>> matches_alternative(2.00, 2.00, 2.05, 5e-2)
    True
    >>> matches_alternative(2.03, 2.00, 2.05, 5e-2)  # 1.5 % from it, 1 % from the reference
    False
    """
    to_alt, to_want = abs(got - alt), abs(got - want)
    return to_alt <= rtol * abs(alt) and ALTERNATIVE_CLOSER * to_alt <= to_want


def band(
    name: str,
    x,
    low: float,
    high: float,
    *,
    about: float,
    deg: float | None = None,
    grid=FULL_TURN,
    unit: str = "",
    suspects=("deg", "rad/min"),
    step_rad: float | None = None,
    flipped: str = FLIPPED,
) -> float:
    """A loose check: the number (or the value at θ = ``deg``) lies in [low, high].

    ``about`` is the rough value the assignment quotes; a miss by a unit
    factor from it is named, or, when ``step_rad`` (the step h of a difference
    quotient) is given, a missing division by h or h²; ``flipped`` is the
    message of a number whose sign is flipped (see :data:`FLIPPED`).  Returns
    the student's number.
    """
    got = at(x, name, deg, grid) if deg is not None else at(x, name, 0, grid)
    if low <= got <= high:
        return got
    where = f" at θ = {deg:g}°" if deg is not None else ""
    unit_text = f" {unit}" if unit else ""
    hint = None
    if step_rad is not None:
        for power in (1, 2):
            if low <= got / step_rad**power <= high:
                hint = _missing_step(step_rad**power, step_rad)
                break
    hint = hint or _loose_factor(got, low, high, suspects, flipped)
    if hint:
        raise AssertionError(f"`{name}`{where} = {_fmt(got)}{unit_text}: {hint}")
    raise AssertionError(
        f"`{name}`{where} = {_fmt(got)}{unit_text}; it should be about {_fmt(about)}{unit_text} "
        f"(between {_fmt(low)} and {_fmt(high)})"
    )


def _loose_factor(got: float, low: float, high: float, suspects, flipped: str = FLIPPED) -> str | None:
    """Unit mix-ups that would bring ``got`` back into [low, high] (at most two named).

    A flipped sign is tried first, then single unit factors, then pairs.
    """
    if low <= -got <= high:
        return flipped
    middle = 0.5 * (low + high)
    found = []
    for factor, terms in _combinations(suspects):
        if found and len(terms) > min(n for n, _, _ in found):
            continue
        for sign in (1.0, -1.0):
            fixed = got / (sign * factor)
            if low <= fixed <= high:
                miss = abs(math.log(abs(fixed / middle)))
                found.append((len(terms), miss, _describe(factor, terms, sign)))
    if not found:
        return None
    fewest = min(n for n, _, _ in found)
    texts = [t for n, _, t in sorted(found) if n == fewest][:2]
    return texts[0] if len(texts) == 1 else f"{texts[0]} Or {texts[1]}"


def own_difference(y, degs, h: float, kind: str, factor: float = 1.0) -> dict:
    """``{angle: factor × difference of y}`` at the listed grid indices (angles in grid steps).

    ``kind`` is ``"centred"``, ``"forward"``, ``"second"`` (centred second difference),
    ``"forward_twice"`` or ``"gradient_twice"`` (``np.gradient`` applied twice, which at
    interior points is the centred second difference of step 2h).  Used to check a
    student's rate against the student's own positions, so that one slip upstream does
    not cost every check downstream.
    """
    y = np.asarray(y, dtype=float)
    formulas = {
        "centred": lambda k: (y[k + 1] - y[k - 1]) / (2 * h),
        "forward": lambda k: (y[k + 1] - y[k]) / h,
        "second": lambda k: (y[k + 1] - 2 * y[k] + y[k - 1]) / h**2,
        "forward_twice": lambda k: (y[k + 2] - 2 * y[k + 1] + y[k]) / h**2,
        "gradient_twice": lambda k: (y[k + 2] - 2 * y[k] + y[k - 2]) / (4 * h**2),
    }
    return {d: factor * float(formulas[kind](int(d))) for d in degs}


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


def four_bar_gap(out_rad, in_rad, r_fixed, r_in, r_coupler, r_out) -> np.ndarray:
    """Loop-closure residual of the homework's four-bar, one value per sample.

    The loop ``r_out e^{i out} + r_coupler e^{i coupler} + r_in e^{i(in + π)} = r_fixed``
    closes for some coupler angle exactly when the distance
    ``|r_fixed - r_out e^{i out} + r_in e^{i in}|`` equals ``r_coupler``; the
    difference is returned (same length unit as the links).
    """
    out_rad = np.asarray(out_rad, dtype=float)
    in_rad = np.asarray(in_rad, dtype=float)
    reach = np.abs(r_fixed - r_out * np.exp(1j * out_rad) + r_in * np.exp(1j * in_rad))
    return np.abs(reach - r_coupler)


def chained_four_bar_angles(phi, beta):
    """φ and β of the chained four-bars homework read in radians, each unit decided by its loop.

    Returns ``(phi_rad, beta_rad, beta_unit, beta_residual)``.
    """
    def gap1(a):
        return four_bar_gap(a, np.radians(np.arange(a.size)), 7.0, 1.94, 6.86, 2.36)

    _, phi_rad, _ = read_angles("phi", phi, gap1)

    def gap2(b):
        return four_bar_gap(b, phi_rad[: b.size] + np.radians(149.0), 1.25, 2.39, 1.87, 1.26)

    unit, beta_rad, residual = read_angles("beta", beta, gap2)
    return phi_rad, beta_rad, unit, residual


def four_bar_side(out_rad, in_rad, r_fixed, r_in, r_out) -> np.ndarray:
    """Which of the two assemblies of the homework's four-bar the angles are on, one value per sample.

    With the output pivot at the origin, the end of the input link is
    ``P = r_fixed + r_in e^{i in}`` and the output joint ``Q = r_out e^{i out}``;
    the coupler joins them.  For a given input the loop closes at the two
    intersections of the circles about the origin (radius ``r_out``) and about
    ``P`` (radius of the coupler), mirror images across the line from the origin
    to ``P``.  The sine of the angle from ``P`` to ``Q`` is returned: positive on
    one assembly, negative on the other, zero only at a toggle position.
    """
    p = r_fixed + r_in * np.exp(1j * np.asarray(in_rad, dtype=float))
    q = np.exp(1j * np.asarray(out_rad, dtype=float))
    return np.imag(np.conj(p) * q) / np.abs(p)


_CHAINED = {
    # name: (dimensions fixed, input, output, the side of the assembly asked, the question's guess at θ = 0)
    "phi": ((7.0, 1.94, 2.36), 1.0, "linkage 1", "(φ, ψ) = (45°, 60°)"),
    "beta": ((1.25, 2.39, 1.26), -1.0, "linkage 2", "(β, γ) = (30°, 270°)"),
}


def chained_four_bar_assembly(name: str, phi, beta=None) -> None:
    """Raise if φ (``name`` "phi") or β ("beta") closes its loop on the other assembly than the one asked.

    The question's guesses at θ = 0 lead, by continuation, to one assembly of each
    linkage; a guess near the other circle intersection leads to its mirror image,
    which closes the loop and turns without a jump, so that only its side
    (:func:`four_bar_side`) tells it apart.  Raises only on that evidence: angles
    that cannot be read or do not close the loop are left to the other checks.
    """
    try:
        if name == "phi":
            _, out, residual = read_angles(
                "phi", phi, lambda a: four_bar_gap(a, np.radians(np.arange(a.size)), 7.0, 1.94, 6.86, 2.36)
            )
            inputs = np.radians(np.arange(out.size))
        else:
            phi_rad, out, _, residual = chained_four_bar_angles(phi, beta)
            inputs = phi_rad[: out.size] + np.radians(149.0)
    except AssertionError:
        return
    (r_fixed, r_in, r_out), side, linkage, guess = _CHAINED[name]
    sides = four_bar_side(out, inputs, r_fixed, r_in, r_out)
    closes = np.isfinite(sides) & (np.nan_to_num(np.abs(residual), nan=1.0) < 1e-6)
    if not closes.any() or np.any(sides[closes] * side > 0):
        return
    first = int(np.flatnonzero(closes)[0])
    raise AssertionError(
        f"`{name}` is on the other assembly (the other circle intersection) of {linkage}: the loop closes "
        f"and turns without a jump, but from θ = {first}° on, the output link lies on the other side of the line "
        "from its pivot to the end of the input link, the mirror image of the asked assembly. Start at θ = 0 "
        f"from the question's guess {guess} and then from each previous solution."
    )


def six_bar_gap(crank_rad, t3, t4, t5, x, *, crank=1.0, coupler=4.0, o4=(3.7, -2.0), o4b=3.0, bc=3.2,
                o4c=6.0, rod=6.5, slider_y=3.0) -> np.ndarray:
    """Loop-closure residual of the six-bar homework, the larger of its two loops per sample.

    Loop 1 ``crank e^{i θ2} + coupler e^{i θ3} - o4b e^{i θ4} - O4`` and loop 2
    ``O4 + o4b e^{i θ4} + bc e^{i(θ4 + β)} - rod e^{i θ5} - (x + i slider_y)``,
    with ``β = π - angle(O4 B C)`` from the ternary link's sides; the defaults
    are the homework's dimensions (cm).
    """
    beta = np.pi - np.arccos((o4b**2 + bc**2 - o4c**2) / (2 * o4b * bc))
    pivot = complex(*o4)
    one = crank * np.exp(1j * crank_rad) + coupler * np.exp(1j * t3) - o4b * np.exp(1j * t4) - pivot
    two = (pivot + o4b * np.exp(1j * t4) + bc * np.exp(1j * (t4 + beta)) - rod * np.exp(1j * t5)
           - (np.asarray(x) + 1j * slider_y))
    return np.maximum(np.abs(one), np.abs(two))


def quick_return_input_unit(values, theta2_deg: float) -> None:
    """Raise if (r3, θ3, r4, r5) close the quick-return loop at θ2 = ``theta2_deg`` *radians*.

    That is the evidence of θ2 passed in degrees to functions that take radians; the
    message names it only when the loop closes there and not at the asked angle.
    """
    r3, t3, r4, r5 = (float(v) for v in values)

    def worst(t2, t3):
        return max(abs(40.0 * math.cos(t2) - r3 * math.cos(t3)),
                   abs(60.0 + 40.0 * math.sin(t2) - r3 * math.sin(t3)),
                   abs(120.0 - r4 * math.sin(t3)), abs(r5 - r4 * math.cos(t3)))

    for t3_rad in (t3, math.radians(t3)):
        if worst(math.radians(theta2_deg), t3_rad) < 1e-6:
            return  # closes at the asked angle
    for t3_rad in (t3, math.radians(t3)):
        if worst(theta2_deg, t3_rad) < 1e-6:
            raise AssertionError(
                f"your r3, θ3, r4, r5 close the loop at θ2 = {theta2_deg:g} rad "
                f"(= {math.degrees(theta2_deg) % 360:.1f}° after whole turns), not at {theta2_deg:g}°: "
                f"θ2 was given in degrees where F and J take radians; use np.radians({theta2_deg:g})"
            )


def read_angle_group(arrays, gap):
    """Read several angle arrays in one unit, deciding it by the loop equations.

    ``gap(*angles_rad)`` returns the loop-closure residual; the unit (radians
    or degrees) in which it is smaller wins.  Returns ``(unit, [angles in
    radians], residual)``.
    """
    best = None
    for unit in ("rad", "deg"):
        read = [a if unit == "rad" else np.radians(a) for a in arrays]
        residual = np.asarray(gap(*read), dtype=float)
        if best is None or np.max(residual) < np.max(best[2]):
            best = (unit, read, residual)
    return best


def read_angles(name: str, x, gap, *, grid=FULL_TURN):
    """Read the angle array ``x`` in radians, deciding its unit by the loop equations.

    ``gap(angles_rad)`` returns the loop-closure residual of the angles; the
    unit (radians or degrees) in which the residual is smaller wins.  Returns
    ``(unit, angles in radians, residual)``.
    """
    unit, (read,), residual = read_angle_group([array(x, name, grid)], gap)
    return unit, read, residual


def closure(
    name: str,
    gap,
    *,
    tol: float = 1e-9,
    grid=FULL_TURN,
    step_rad: float | None = None,
    broken: float = 1e-2,
):
    """Check that loop-closure residuals ``gap`` (one per grid angle) are all below ``tol``.

    A residual above ``broken`` means the equations or the data are wrong; one
    between ``tol`` and ``broken`` means the Newton iteration stopped before it
    converged, and the message says how finite differences magnify it.
    """
    gap = np.nan_to_num(np.abs(np.asarray(gap, dtype=float)), nan=0.0)  # NaN ends: not checked
    worst = int(np.argmax(gap))
    if gap[worst] <= tol:
        return
    where = _grid_angles(grid)[worst]
    if gap[worst] > broken:
        raise AssertionError(
            f"`{name}` does not satisfy the loop-closure equations (|F| up to {gap[worst]:.3g} "
            f"at θ = {where:g}°) in radians or in degrees: check the equations, the link "
            "lengths and the input angles"
        )
    h = step_rad if step_rad is not None else math.radians(grid[2])
    raise AssertionError(
        f"`{name}` satisfies the loop-closure equations only to |F| ≈ {gap[worst]:.1g} "
        f"(worst at θ = {where:g}°): the Newton iteration stops too early, e.g. at |F| < 1e-4. "
        f"Iterate until the step |Δx| < 1e-10. A first difference divides this error by "
        f"h = {h:.3g}, a second difference by h² = {h * h:.2g}."
    )


def continuity(name: str, angles_rad, *, grid=FULL_TURN, max_step_deg: float = 10.0):
    """Check that angles (radians) move by less than ``max_step_deg`` between grid points."""
    values = np.asarray(angles_rad, dtype=float)
    steps = np.nan_to_num(np.degrees(np.abs(_wrapped(np.diff(values)))), nan=0.0)
    worst = int(np.argmax(steps))
    if steps[worst] <= max_step_deg:
        return
    where = _grid_angles(grid)
    raise AssertionError(
        f"`{name}` jumps by {steps[worst]:.3g}° between θ = {where[worst]:g}° and "
        f"{where[worst + 1]:g}°: Newton has jumped to the other assembly branch. Start each "
        "solve from the previous solution (continuation), not from the same fixed guess."
    )


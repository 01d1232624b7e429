"""Naming what makes a number wrong, for the messages of the checks.

A miss by a constant factor is read as a unit mix-up (:data:`SUSPECTS`: degrees
where radians are asked, rad/min, rpm, rev/s, mm where m or cm are asked), a flipped sign (:data:`FLIPPED`,
:data:`ROTATION`) or a difference quotient not divided by its step h
(:func:`explain_factor`); a miss within the rounding of the numbers as written is
read as rounding or single precision (:func:`as_written`,
:func:`agrees_as_written`).  Also here: how numbers are written into a message.
Nothing here raises: the checks of the other modules put these words in their messages.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

__all__ = [
    "SUSPECTS",
    "FLIPPED",
    "ROTATION",
    "SINGLE",
    "explain_factor",
    "agrees_as_written",
    "as_written",
]


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
    "cm": (
        10.0,
        "millimetres where centimetres are asked? (1 cm = 10 mm)",
        "divided by 10 once too often? (1 cm = 10 mm)",
    ),
}

_FACTOR_TOLERANCE = 0.02  # relative, for recognising one unit factor

_PAIR_TOLERANCE = 1e-3
"""How far (relative) a ratio may lie from a product of two unit factors to be named as two slips, at most.

A product of two unit factors is exact: two slips on an otherwise right answer miss it by that answer's own
error (below 2e-4 for the homework's centred differences against exact values), and a check passes its own,
tighter tolerance.  The 2 % that recognises one factor would find a pair of hw3's five suspects for three
ratios in ten between 1/2 and 2 (the textbook a = -Rω²(cos θ + R/L cos 2θ) at 90° is 1/1.097 of the exact
value, 0.5 % from (180/π)² × (1/60)²); within 1e-3, for about one in seventy."""

FLIPPED = "the sign is flipped"
"""What a check says of an answer that is the reference times −1, unless it is told more (``flipped=``).

A check knows what can flip the sign of its quantity and says so with ``flipped``:
:data:`ROTATION` for a rate linear in ω, a pointer to the minus sign of a formula, or
to the mirror solution for a negative length.
"""

ROTATION = FLIPPED + ": check the sense of rotation (clockwise is negative)"
"""The flipped sign of a quantity odd in ω (a velocity, ω dq/dθ): the sign of ω explains it.
An acceleration ω² d²q/dθ² or a position does not change sign with the sense of rotation."""


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
    "cm": ("10", "1/10"),
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
    ratio: float,
    suspects=("deg", "rad/min"),
    *,
    step_rad: float | None = None,
    flipped: str = FLIPPED,
    rtol: float = _PAIR_TOLERANCE,
) -> str | None:
    """Name a unit mix-up that turns the right answer into ``ratio`` times it.

    Tries the listed ``SUSPECTS`` alone and in pairs, to the powers ±1 and ±2
    (an acceleration goes with ω², a second difference with 1/h²), with either
    sign.  Returns a message such as ``"off by a factor 60: rad/min where
    rad/s is asked? ..."``, or None when no single factor fits within 2 % and
    no pair within ``rtol`` (the check's own tolerance; at most
    :data:`_PAIR_TOLERANCE`, 1e-3): a pair's product is exact, and pairs are
    so many that a looser match names two slips for ratios no slip explains.

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
        allowed = _FACTOR_TOLERANCE if len(terms) == 1 else min(rtol, _PAIR_TOLERANCE)
        if miss <= allowed and (best is None or (len(terms), miss) < best[0]):
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


def _loose_factor(
    got: float, low: float, high: float, suspects, flipped: str = FLIPPED, about: float | None = None
) -> str | None:
    """Unit mix-ups that would bring ``got`` back into [low, high] (at most two named).

    A flipped sign is tried first, then single unit factors, then pairs: a pair only where it brings
    ``got`` within :data:`_PAIR_TOLERANCE` of ``about`` (a band as wide as a check's rough value holds
    a product of two unit factors for many a number no slip explains).
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
            if len(terms) > 1 and (not about or abs(fixed / about - 1.0) > _PAIR_TOLERANCE):
                continue
            if low <= fixed <= high:
                miss = abs(math.log(abs(fixed / middle)))
                found.append((len(terms), miss, _describe(factor, terms, sign)))
    if not found:
        return None
    fewest = min(n for n, _, _ in found)
    texts = [t for n, _, t in sorted(found) if n == fewest][:2]
    return texts[0] if len(texts) == 1 else f"{texts[0]} Or {texts[1]}"


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

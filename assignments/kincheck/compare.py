"""Comparing a student's numbers and series with the reference values, with feedback.

:func:`value` (one number), :func:`angle_value` (one angle, modulo whole turns),
:func:`series` (an array over the grid at some angles), :func:`band` (a loose
range), :func:`listed` (a short list): each returns quietly or raises
``AssertionError`` saying what looks off, naming another formula the answer
matches (:func:`matches_alternative`), else a unit factor or the rounding
(``diagnose``), else the miss.  :func:`own_difference` gives the reference of a
rate from the student's own positions.
"""

from __future__ import annotations

import math

import numpy as np

from .diagnose import (
    FLIPPED,
    SINGLE,
    _figures,
    _fmt,
    _loose_factor,
    _missing_step,
    _pair,
    _ratio,
    _written_hint,
    agrees_as_written,
    as_written,
    explain_factor,
)
from .reading import FULL_TURN, _current, _pick, _wrapped, array, at, floats

__all__ = [
    "NEWTON_HINT",
    "ALTERNATIVE_CLOSER",
    "value",
    "angle_value",
    "series",
    "band",
    "listed",
    "matches_alternative",
    "own_difference",
]


NEWTON_HINT = (
    "Differences this small have several causes: a difference formula other than the one "
    "asked (np.gradient, a one-sided or shifted formula, another step), or positions that "
    "are not converged (a loose Newton tolerance, which finite differences magnify; the "
    "position checks say whether yours are)"
)
"""The hint of a small miss that no alternative explains: it lists the causes, it does not pick one."""


def _close(got, want, rtol: float, atol: float) -> np.ndarray:
    scale = np.max(np.abs(want)) if np.size(want) else 0.0
    return np.abs(np.asarray(got) - np.asarray(want)) <= atol + rtol * scale


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
        hint = explain_factor(ratio, suspects, step_rad=step_rad, flipped=flipped, rtol=rtol)
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
    hint = explain_factor(got / want, suspects, step_rad=step_rad, flipped=flipped, rtol=rtol) if want else None
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
    hint = hint or _loose_factor(got, low, high, suspects, flipped, about)
    if hint:
        raise AssertionError(f"`{name}`{where} = {_fmt(got)}{unit_text}: {hint}")
    raise AssertionError(
        f"`{name}`{where} = {_fmt(got)}{unit_text}; it should be about {_fmt(about)}{unit_text} "
        f"(between {_fmt(low)} and {_fmt(high)})"
    )


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

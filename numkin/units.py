"""Unit parsing for user input.

Angular speeds are returned in rad/s and angular accelerations in rad/s^2;
lengths are converted with metre-based factors.  The functions are meant
for values given by a user (a scene file, the command line, a notebook
cell) at the edge of the program:

>>> from numkin.units import angular_speed, angular_acceleration, convert_length
>>> angular_speed("6000 rpm")
628.3185307179587
>>> angular_acceleration("-2 rad/s^2")
-2.0
>>> convert_length(25.4, "mm", "in")
1.0

A bare number is taken to be in the SI unit already.  Anything that is not
understood raises :class:`UnitError`, a :class:`ValueError` whose message
repeats the input and lists the accepted units.
"""

from __future__ import annotations

import math
import numbers
import re

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import InputError

__all__ = [
    "finite",
    "is_number",
    "number_array",
    "with_length_unit",
    "input_degrees",
    "deg_text",
    "is_full_turn",
    "UnitError",
    "angular_speed",
    "angular_acceleration",
    "input_rate",
    "input_rates",
    "length_factor",
    "convert_length",
]

_TURN = 2.0 * math.pi
_DEGREE = math.pi / 180.0

# rad/s per unit (canonical spellings, see _canonical_unit)
_ANGULAR_SPEED_UNITS: dict[str, float] = {
    "rad/s": 1.0,
    "rad/min": 1.0 / 60.0,
    "rpm": _TURN / 60.0,
    "rev/min": _TURN / 60.0,
    "rev/s": _TURN,
    "rps": _TURN,
    "deg/s": _DEGREE,
    "deg/min": _DEGREE / 60.0,
}

# rad/s^2 per unit
_ANGULAR_ACCELERATION_UNITS: dict[str, float] = {
    "rad/s^2": 1.0,
    "rad/min^2": 1.0 / 3600.0,
    "rpm/s": _TURN / 60.0,
    "rev/s^2": _TURN,
    "deg/s^2": _DEGREE,
}

# millimetres per unit: exact decimal factors, so that e.g. 25.4 mm is exactly 1 in
_MILLIMETRES: dict[str, float] = {
    "m": 1000.0,
    "mm": 1.0,
    "cm": 10.0,
    "km": 1e6,
    "in": 25.4,
    "ft": 304.8,
}

_QUANTITY = re.compile(
    r"""
    ^\s*
    (?P<number>[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
    \s*
    (?P<unit>.*?)
    \s*$
    """,
    re.VERBOSE,
)


class UnitError(InputError):
    """A quantity with a missing, unknown or wrong-dimension unit.

    Examples
    --------
    >>> from numkin.units import UnitError, angular_speed
    >>> try:
    ...     angular_speed("10 mm")
    ... except UnitError as error:
    ...     print(error)  # doctest: +ELLIPSIS
    '10 mm' is a length, not an angular speed; accepted units: rad/s, ...
    """


def _canonical_unit(unit: str) -> str:
    """Lower-case, unspaced spelling: 'Rad / sec**2' -> 'rad/s^2'."""
    unit = re.sub(r"\s+", "", unit.lower())
    unit = unit.replace("**", "^").replace("\N{SUPERSCRIPT TWO}", "^2")
    unit = unit.replace("\N{DEGREE SIGN}", "deg")
    unit = re.sub(r"/(sec|second)(?![a-z])", "/s", unit)
    unit = re.sub(r"/(s|min)2$", r"/\1^2", unit)
    unit = re.sub(r"^(radian|radians)/", "rad/", unit)
    unit = re.sub(r"^(degree|degrees)/", "deg/", unit)
    return unit


def _dimension_of(unit: str) -> str | None:
    canonical = _canonical_unit(unit)
    if canonical in _ANGULAR_SPEED_UNITS:
        return "an angular speed"
    if canonical in _ANGULAR_ACCELERATION_UNITS:
        return "an angular acceleration"
    if unit in _MILLIMETRES:
        return "a length"
    if re.fullmatch(r"(m|mm|cm|km|in|ft)/s", canonical):
        return "a linear speed"
    if re.fullmatch(r"(m|mm|cm|km|in|ft)/s\^2", canonical):
        return "a linear acceleration"
    return None


def _parse(value: str | float, quantity: str, units: dict[str, float]) -> float:
    """Convert `value` to the SI unit of `quantity` using the factors in `units`."""
    if isinstance(value, bool) or not isinstance(value, (str, numbers.Real)):
        raise TypeError(
            f"{quantity} must be a number or a string such as '10 rad/s', "
            f"got {type(value).__name__}"
        )
    accepted = f"accepted units: {', '.join(units)}"
    if isinstance(value, numbers.Real):
        number = float(value)
        if not math.isfinite(number):
            raise UnitError(f"{quantity} must be finite, got {value!r}")
        return number

    text = value.replace("\N{MINUS SIGN}", "-")
    match = _QUANTITY.match(text)
    if match is None:
        raise UnitError(
            f"cannot read {value!r} as {quantity}; expected '<number> <unit>', {accepted}"
        )
    number = float(match["number"])
    unit = match["unit"]
    factor = units.get(_canonical_unit(unit)) if unit else 1.0
    if factor is not None:
        converted = number * factor
        if not math.isfinite(converted):
            raise UnitError(f"{value!r} overflows as {quantity}")
        return converted
    dimension = _dimension_of(unit)
    if dimension is not None:
        raise UnitError(f"{value!r} is {dimension}, not {quantity}; {accepted}")
    raise UnitError(f"unknown unit {unit!r} in {value!r}; {accepted}")


_RATE_DOC = """Angular {what} in {unit}.

    Parameters
    ----------
    value : float or str
{value}

    Returns
    -------
    float
        The {what} in {unit}.

    Raises
    ------
    UnitError
        For a malformed string, an unknown unit or a unit of another
        dimension ({others}).
    TypeError
        If `value` is neither a number nor a string.

    Examples
    --------
{examples}
    """


def angular_speed(value: str | float) -> float:
    return _parse(value, "an angular speed", _ANGULAR_SPEED_UNITS)


def angular_acceleration(value: str | float) -> float:
    return _parse(value, "an angular acceleration", _ANGULAR_ACCELERATION_UNITS)


angular_speed.__doc__ = _RATE_DOC.format(
    what="speed", unit="rad/s", others='``"10 mm"``, ``"5 m/s"``',
    value="""        A number, taken to be rad/s, or a string ``"<number> <unit>"`` (the
        space is optional).  Units: rad/s, rad/min, rpm (= rev/min), rev/s
        (= rps), deg/s, deg/min.  ``sec`` may be written for ``s``, case is
        ignored, and a string without a unit is taken to be rad/s.""",
    examples="""    >>> from numkin.units import angular_speed
    >>> angular_speed("450 rad/min")
    7.5
    >>> angular_speed("-10rad/s")
    -10.0
    >>> round(angular_speed("3 rev/s"), 6)
    18.849556
    >>> angular_speed(12)
    12.0""",
)
angular_acceleration.__doc__ = _RATE_DOC.format(
    what="acceleration", unit="rad/s^2", others='``"10 rad/s"``, ``"9.81 m/s^2"``',
    value="""        A number, taken to be rad/s^2, or a string ``"<number> <unit>"``.
        Units: rad/s^2, rad/min^2, rpm/s, rev/s^2, deg/s^2.  The square may
        be written ``^2``, ``2``, ``**2`` or ``²``; ``sec`` may be written
        for ``s``; case is ignored, and a string without a unit is taken to
        be rad/s^2.""",
    examples="""    >>> from numkin.units import angular_acceleration
    >>> angular_acceleration("3600 rad/min^2")
    1.0
    >>> angular_acceleration("-4 rad/s**2")
    -4.0
    >>> round(angular_acceleration("60 rpm/s"), 6)
    6.283185""",
)


def length_factor(unit: str) -> float:
    """Metres per `unit`.

    Parameters
    ----------
    unit : str
        One of ``"m"``, ``"mm"``, ``"cm"``, ``"km"``, ``"in"``, ``"ft"``
        (case-sensitive; surrounding spaces are ignored).

    Returns
    -------
    float
        Length of one `unit` in metres.

    Raises
    ------
    UnitError
        For any other unit.

    Examples
    --------
    >>> from numkin.units import length_factor
    >>> length_factor("mm")
    0.001
    >>> length_factor("in")
    0.0254
    """
    return _millimetres_per(unit) / 1000.0


def _millimetres_per(unit: str) -> float:
    factor = _MILLIMETRES.get(unit.strip()) if isinstance(unit, str) else None
    if factor is None:
        raise UnitError(
            f"unknown length unit {unit!r}; accepted units: {', '.join(_MILLIMETRES)}"
        )
    return factor


def convert_length(
    value: float | ArrayLike, from_unit: str, to_unit: str
) -> float | NDArray[np.float64]:
    """Convert a length (or an array of lengths) between units.

    Parameters
    ----------
    value : float or array_like
        Length(s) in `from_unit`.
    from_unit, to_unit : str
        Units accepted by :func:`length_factor`.

    Returns
    -------
    float or numpy.ndarray
        Length(s) in `to_unit`: a float for scalar input, otherwise an array.

    Raises
    ------
    UnitError
        If either unit is unknown.

    Examples
    --------
    >>> from numkin.units import convert_length
    >>> convert_length(2.5, "in", "mm")
    63.5
    >>> convert_length([100.0, 250.0], "mm", "m")
    array([0.1 , 0.25])
    """
    from_mm, to_mm = _millimetres_per(from_unit), _millimetres_per(to_unit)
    converted = np.asarray(value, dtype=float) * from_mm / to_mm
    return float(converted) if converted.ndim == 0 else converted



def finite(name: str, value) -> float:
    """A finite number, or a ValueError naming it: the one check of numbers given by name.

    Examples
    --------
    >>> finite("offset", -1)
    -1.0
    >>> finite("parameter r2", "x")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: parameter r2 = 'x' is not a number
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} = {value!r} is not a number") from None
    if not math.isfinite(v):
        raise InputError(f"{name} = {value!r} is not finite")
    return v


#: What a number in an array of numbers is never, though numpy would read it as one (text as its value,
#: a bool as 0 or 1).
_NOT_NUMBERS = (str, bytes, bool, np.bool_)

#: Types of the items of a list read as numbers at once (no item looked at on its own).
_PLAIN = {float, int, np.float64}


def is_number(value, *, finite: bool = False) -> bool:
    """Whether ``value`` is one real number: anything ``float()`` reads as one that is not a bool, text
    or an array of more than one value (a Python, numpy, ``Fraction``, ``Decimal`` or sympy number, a
    0-d array); with ``finite``, a finite one. The items :func:`number_array` accepts.

    Examples
    --------
    >>> [is_number(v) for v in (2, 0.5, np.float32(1), np.array(3.0), True, "1", None, [1.0], 1j)]
    [True, True, True, True, False, False, False, False, False]
    >>> is_number(float("inf")), is_number(float("inf"), finite=True)
    (True, False)
    """
    if value is None or isinstance(value, _NOT_NUMBERS) or isinstance(value, complex):
        return False
    if isinstance(value, np.ndarray) and (value.ndim != 0 or value.dtype.kind not in "iufO"):
        return False
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        return False
    return not finite or math.isfinite(v)


def number_array(value, what: str, *, complex_ok: bool = False, shown=None) -> np.ndarray:
    """``value`` (numbers, nested sequences of numbers or an array) as a float array, complex where
    ``complex_ok`` and a value is complex; or an :class:`~numkin.errors.InputError` saying ``what``
    it must be (a string, or a function giving it) and the value given (or ``shown``). Text, None and booleans are refused wherever they
    stand (numpy would read ``"1"`` as 1.0, ``True`` as 1.0), complex numbers unless ``complex_ok``; a
    masked array is read as its data, as :func:`numpy.asarray` reads it.

    Examples
    --------
    >>> number_array([0, 0.5], "inputs must be numbers").tolist()
    [0.0, 0.5]
    >>> number_array([0.5, "1"], "inputs must be numbers")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: inputs must be numbers, got [0.5, '1']
    """
    kinds = "iufc" if complex_ok else "iuf"
    if type(value) in (list, tuple) and set(map(type, value)) <= _PLAIN:
        return np.array(value, dtype=float)  # (a short cut for plain numbers)
    try:
        if isinstance(value, np.ndarray) and value.dtype.kind in kinds:
            value = np.asarray(value)  # (a subclass, a masked array: its data)
            return value.astype(complex if value.dtype.kind == "c" else float, copy=False)
        items = np.asarray(value, dtype=object).ravel().tolist()
        for v in items:
            if v is None or isinstance(v, _NOT_NUMBERS) or (not complex_ok and isinstance(v, complex)):
                raise TypeError(type(v))
        raw = np.asarray(value)
        if raw.dtype.kind not in kinds and raw.dtype.kind != "O":
            raise TypeError(raw.dtype)
        if raw.dtype.kind == "c":
            return raw.astype(complex)
        try:
            return raw.astype(float)
        except TypeError:
            if not complex_ok:
                raise
            return raw.astype(complex)
    except (TypeError, ValueError, OverflowError):
        what = what() if callable(what) else what
        raise InputError(f"{what}, got {value if shown is None else shown!r:.80}") from None


_RATE_PARSERS = {"speed": ("omega", angular_speed), "acceleration": ("alpha", angular_acceleration)}


def input_rate(value, kind: str = "speed", count: int | None = None, name: str | None = None):
    """The input's angular speed (rad/s) or acceleration (rad/s^2), parsed once at the edge.

    The one reader of input rates: scenes, the command line, tables and the
    kinematics all call it, and pass the number (or array) on.

    Parameters
    ----------
    value : float, str or array_like
        A number in rad/s (rad/s^2), a string with units (``"450 rad/min"``,
        ``"6000 rpm"``, ``"2 rad/s^2"``), or, with `count`, one number per point.
    kind : {"speed", "acceleration"}
    count : int, optional
        Number of points: the result is then an array of shape ``(count,)``
        (a scalar is repeated). Without it, a float.
    name : str, optional
        Parameter name for messages (default ``omega`` or ``alpha``).

    Returns
    -------
    float or numpy.ndarray

    Raises
    ------
    UnitError
        For an unreadable string or a unit of the wrong dimension; the
        message names the parameter.
    InputError
        For a value that is not a number, string or array, an array of the
        wrong length, or a value that is not finite.

    Examples
    --------
    >>> from numkin.units import input_rate
    >>> input_rate("450 rad/min")
    7.5
    >>> input_rate("60 rpm/s", "acceleration", count=2)
    array([6.28318531, 6.28318531])
    >>> input_rate("5 m/s")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    numkin.units.UnitError: omega: '5 m/s' is a linear speed, not an angular speed; ...
    """
    if kind not in _RATE_PARSERS:
        raise InputError(f"kind must be 'speed' or 'acceleration', got {kind!r}")
    default, parse = _RATE_PARSERS[kind]
    name = name or default

    def expected():
        return InputError(f"{name} must be a number, a string with units or an array of numbers, got {value!r:.60}")

    if isinstance(value, (str, numbers.Real)) and not isinstance(value, bool):
        try:
            v = parse(value)
        except (ValueError, TypeError) as exc:
            raise type(exc)(f"{name}: {exc}") from None
        return v if count is None else np.full(count, v)
    if isinstance(value, bool) or value is None:
        raise expected()
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise expected() from None
    if arr.ndim == 0:
        return input_rate(float(arr), kind, count, name)
    if count is None or arr.shape != (count,):
        want = "a single value" if count is None else f"one value per input of the sweep, shape ({count},)"
        raise InputError(f"{name} as an array must have {want}, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name}[{int(np.flatnonzero(~np.isfinite(arr))[0])}] is not finite")
    return arr


def input_rates(omega, alpha=0.0, count: int | None = None):
    """``(input_rate(omega, "speed", count), input_rate(alpha, "acceleration", count))``.

    Examples
    --------
    >>> from numkin.units import input_rates
    >>> input_rates("450 rad/min", 0, 3)
    (array([7.5, 7.5, 7.5]), array([0., 0., 0.]))
    """
    return input_rate(omega, "speed", count), input_rate(alpha, "acceleration", count)


def input_degrees(t) -> np.ndarray:
    """Input angles (rad) in degrees for a table's input column, rounded to 1e-9 degree.

    A grid written in degrees reads as written: 30° taken to rad and back is
    29.999999999999996, a value no filter or join on 30 finds.

    Examples
    --------
    >>> float(np.degrees(np.radians(30.0))), float(input_degrees(np.radians(30.0)))
    (29.999999999999996, 30.0)
    """
    return np.round(np.degrees(t), 9) + 0.0  # (+ 0.0: no -0.0)


def is_full_turn(inputs) -> bool:
    """Whether a grid of inputs (rad), three or more, spans exactly one turn (to 1e-9 relative): a periodic grid,
    its last sample the first one turn on, either way round.

    Examples
    --------
    >>> is_full_turn(np.radians(np.arange(0.0, 361.0))), is_full_turn(np.radians([360.0, 180.0, 0.0]))
    (True, True)
    >>> is_full_turn(np.radians(np.arange(0.0, 360.0))), is_full_turn(np.radians([0.0, 360.0]))
    (False, False)
    """
    t = np.asarray(inputs, dtype=float)
    return bool(t.size >= 3 and abs(abs(float(t[-1] - t[0])) - _TURN) <= 1e-9 * _TURN)


def deg_text(t: float, digits: int = 3) -> str:
    """An input angle (rad) written in degrees with the unit, for messages (no sign on a zero).

    Examples
    --------
    >>> deg_text(math.radians(100.0)), deg_text(-1e-12, 4), deg_text(math.radians(-30.0), 1)
    ('100.000°', '0.0000°', '-30.0°')
    """
    text = f"{math.degrees(float(t)):.{digits}f}°"
    return text[1:] if text.startswith("-") and not text.strip("-0.°") else text


def with_length_unit(name: str, unit: str) -> str:
    """A linkage's name with its unit after each dimension that has none (for titles and summaries).

    Examples
    --------
    >>> with_length_unit("slider-crank (crank 0.08, rod 0.2, offset 0)", "m")
    'slider-crank (crank 0.08 m, rod 0.2 m, offset 0 m)'
    >>> with_length_unit("quick-return (r1 60 mm, r2 40)", "mm"), with_length_unit("chained four-bars", "in")
    ('quick-return (r1 60 mm, r2 40 mm)', 'chained four-bars')
    """
    head, paren, rest = str(name).partition(" (")
    if not paren or not rest.endswith(")"):
        return str(name)
    items = [re.sub(r"^(\w+ [-+0-9.eE]+)$", rf"\1 {unit}", item) for item in rest[:-1].split(", ")]
    return f"{head} ({', '.join(items)})"


"""Labels, units and number formats of figures, and checks of the data they are given.

Symbols are written in mathtext (``theta2`` -> ``$\\theta_{2}$``), input angles
in degrees, every number with a true minus sign and never as ``−0``.

Examples
--------
>>> from numkin.figures.labels import sym, value_text, deg_text
>>> print(sym("theta2"), value_text(-0.0), deg_text(-1e-12))
$\\theta_{2}$ 0.000 0°
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..quantities import GREEK, tex

__all__ = [
    "ANGLE_DECIMALS", "GREEK", "angle_text", "axis_label", "axis_unit", "check_points", "check_unknown", "deg_text", "derived_of",
    "degree_ticks", "frame_column", "frame_input", "input_label", "input_name", "is_angle", "length_text", "length_unit",
    "mechanism_title", "no_negative_zero", "quantities_of", "quantity_labels", "rate_columns", "sig5", "sym", "table_column",
    "tex", "uniform_step", "value_text",
]

def sym(name: str) -> str:
    """Mathtext symbol of a name: ``"beta"`` -> ``"$\\beta$"``."""
    return f"${tex(name)}$"


def input_name(sweep) -> str:
    """Name of the sweep's input angle (``"theta2"``)."""
    return sweep.mechanism.input_name


def mechanism_title(mechanism) -> str:
    """The mechanism's name for a title, its dimensions with their unit.

    ``"slider-crank (crank 0.08, rod 0.2, offset 0)"`` in metres becomes
    ``"slider-crank (crank 0.08 m, rod 0.2 m, offset 0 m)"``; a number that
    already has a unit, or a name without numbers, is left as it is.

    Examples
    --------
    >>> from numkin import linkages
    >>> mechanism_title(linkages.slider_crank(80, 200))
    'slider-crank (crank 80 mm, rod 200 mm, offset 0 mm)'
    """
    return mechanism.title


def input_label(sweep) -> str:
    """Axis label of the input angle, in degrees."""
    return f"{sym(input_name(sweep))} [deg]"


def derived_of(sweep) -> dict:
    """The derived quantities of the sweep's mechanism, name -> :class:`~numkin.derived.Derived` (see
    :meth:`numkin.Mechanism.add_quantities`); empty when it declares none."""
    return dict(getattr(sweep.mechanism, "derived", None) or {})


def is_angle(sweep, name: str) -> bool:
    """Whether an unknown or derived quantity of the sweep is an angle (else a length).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.slider_crank(80, 200).add_quantities({"mu": ("theta3 + theta", "angle")})
    >>> sweep = mech.sweep(np.radians([0.0, 1.0]))
    >>> is_angle(sweep, "theta3"), is_angle(sweep, "x"), is_angle(sweep, "mu")
    (True, False, True)
    """
    if name in sweep.mechanism.angles:
        return True
    derived = derived_of(sweep).get(name)
    return derived is not None and derived.dimension == "angle"


def length_unit(sweep) -> str:
    """The mechanism's length unit (``"mm"``)."""
    return sweep.mechanism.length_unit


def quantities_of(sweep, name: str) -> list:
    """The position, velocity and acceleration :class:`~numkin.quantities.Quantity` of an unknown or
    derived quantity of the sweep's mechanism.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 1.0]))
    >>> [q.name for q in quantities_of(sweep, "theta3")]
    ['theta3', 'omega_theta3', 'alpha_theta3']
    """
    from ..quantities import Quantity

    mech = sweep.mechanism
    dim = "angle" if is_angle(sweep, name) else "length"
    return [Quantity(name, order, dim, length_unit=mech.length_unit, input_name=input_name(sweep))
            for order in (0, 1, 2)]


def axis_unit(quantity) -> str:
    """The unit a figure gives a quantity's values in: degrees for an angle's position (drawn in degrees),
    else the Quantity's own unit, its squares written ``²``.

    Examples
    --------
    >>> from numkin.quantities import Quantity
    >>> axis_unit(Quantity("beta", 0, "angle")), axis_unit(Quantity("x", 2, "length", length_unit="cm"))
    ('deg', 'cm/s²')
    """
    return "deg" if quantity.in_degrees else quantity.unit.replace("^2", "²")


def axis_label(quantity) -> str:
    """A figure's axis label of a quantity: its mathtext symbol and :func:`axis_unit` in brackets.

    Examples
    --------
    >>> from numkin.quantities import Quantity
    >>> print(axis_label(Quantity("beta", 1, "angle")))
    $\\omega_{\\beta}$ [rad/s]
    """
    return f"${quantity.symbol}$ [{axis_unit(quantity)}]"


def quantity_labels(sweep, name: str) -> tuple[str, str, str]:
    """Axis labels of position, velocity and acceleration of an unknown or derived quantity, with units.

    Symbols and units from :class:`~numkin.quantities.Quantity` (:func:`axis_label`); angles drawn in degrees.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 1.0]))
    >>> quantity_labels(sweep, "x")
    ('$x$ [mm]', '$v_{x}$ [mm/s]', '$a_{x}$ [mm/s²]')
    """
    return tuple(axis_label(q) for q in quantities_of(sweep, name))


def rate_columns(sweep, name: str) -> tuple[str, str]:
    """Velocity and acceleration column names of an unknown or derived quantity in the kinematics frames
    (Quantity names: ``omega_mu``, ``alpha_mu`` of an angle, ``v_s``, ``a_s`` of a length)."""
    _, vel, acc = quantities_of(sweep, name)
    return vel.name, acc.name


def no_negative_zero(text: str) -> str:
    """A true minus sign, and no sign on a zero (``"-0.000"`` -> ``"0.000"``)."""
    if text.startswith("-") and not any(ch in "123456789" for ch in text.split("e")[0]):
        text = text[1:]
    return text.replace("-", "−")


def sig5(value: float, zeros: bool = True) -> str:
    """Five significant digits (trailing zeros kept if `zeros`), a true minus sign, no ``−0``.

    Examples
    --------
    >>> sig5(-1.5e-3), sig5(-0.0), sig5(2.0, zeros=False)
    ('−0.0015000', '0.0000', '2')
    """
    text = f"{value:#.5g}" if zeros else f"{value:.5g}"
    if "e" not in text:
        text = text.rstrip(".")
    return no_negative_zero(text)


def value_text(value: float) -> str:
    """At least three decimals and five significant digits (87.178, 130.767, 0.18330), true minus."""
    v = float(value)
    digits = 3 if v == 0 or not math.isfinite(v) else max(3, 4 - math.floor(math.log10(abs(v))))
    return no_negative_zero(f"{v:.{digits}f}")


def length_text(value: float) -> str:
    """A dimension: as :func:`value_text`, trailing zeros dropped (60, 6.5, 130.767, 0.08)."""
    text = value_text(value)
    return text.rstrip("0").rstrip(".") if "." in text else text


#: Decimals of an angle a figure gives as a value (the mechanism figure's title, arcs and box, the check values of the
#: kinematics figure): one rule, so that one angle reads the same in each.
ANGLE_DECIMALS = 3


def angle_text(rad: float) -> str:
    """An angle's value in degrees: whole degrees plain, else :data:`ANGLE_DECIMALS` decimals.

    Examples
    --------
    >>> angle_text(math.radians(154.7153)), angle_text(math.radians(100))
    ('154.715°', '100°')
    """
    return deg_text(rad, ANGLE_DECIMALS)


def deg_text(rad: float, decimals: int = 2) -> str:
    """An angle given in rad, written in degrees: whole degrees plain, else `decimals` decimals.

    Examples
    --------
    >>> deg_text(math.radians(-30)), deg_text(math.radians(12.345)), deg_text(-1e-12)
    ('−30°', '12.35°', '0°')
    >>> deg_text(math.radians(154.7153), 3)
    '154.715°'
    """
    d = math.degrees(rad)
    text = f"{round(d):.0f}°" if abs(d - round(d)) < 1e-6 else f"{d:.{decimals}f}°"
    return no_negative_zero(text)


def degree_ticks(ax, degrees: np.ndarray) -> None:
    """Ticks every 30, 45 or 90 degrees, depending on the span."""
    from matplotlib.ticker import MultipleLocator

    span = float(np.nanmax(degrees) - np.nanmin(degrees)) if degrees.size else 0.0
    if span >= 270:
        ax.xaxis.set_major_locator(MultipleLocator(45 if span <= 400 else 90))
    elif span >= 90:
        ax.xaxis.set_major_locator(MultipleLocator(30))
    ax.set_xlim(float(np.nanmin(degrees)), float(np.nanmax(degrees))) if span > 0 else None


def check_unknown(sweep, name: str, parameter: str = "name") -> str:
    """`name`, if it is an unknown of the sweep or a derived quantity of its mechanism; else an
    :class:`~numkin.InputError` listing them (`parameter`: the argument that gave it, named when it
    is not a string).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")}).sweep([0.0])
    >>> check_unknown(sweep, "mu")
    'mu'
    >>> try:
    ...     check_unknown(sweep, "nu")
    ... except ValueError as error:
    ...     print(str(error).split("; ")[1])
    unknowns are ['theta3', 'theta4'], derived quantities ['mu']
    """
    if not isinstance(name, str):
        raise InputError(f"{parameter} must be the name of an unknown or derived quantity (a string such as "
                         f"{sweep.unknowns[0]!r}), got {type(name).__name__} {name!r}")
    derived = list(derived_of(sweep))
    if name not in sweep.unknowns and name not in derived:
        also = f", derived quantities {derived}" if derived else ""
        raise InputError(
            f"{name!r} is not an unknown of {sweep.mechanism.name}; unknowns are {list(sweep.unknowns)}{also}"
        )
    return name


def uniform_step(sweep) -> float:
    """The sweep's input step (rad); a ValueError if the grid is not uniform."""
    h = sweep.step
    if h is None:
        raise InputError(
            f"sweep of {sweep.mechanism.name}: finite differences need a uniform input step; "
            "sweep a grid like np.radians(np.arange(0, 361))"
        )
    return h


def frame_input(frame, sweep) -> np.ndarray:
    """Input values (rad) of a kinematics frame: its input column, or the sweep's inputs."""
    col = input_name(sweep)
    if col in frame.columns:
        return np.asarray(frame[col], dtype=float)
    if len(frame) != len(sweep):
        raise InputError(
            f"kinematics frame has {len(frame)} rows and no {col!r} column; the sweep has {len(sweep)} inputs"
        )
    return sweep.inputs


def frame_column(frame, column: str, what: str) -> np.ndarray:
    """A column of a frame as floats; a ValueError naming `what` if it is absent."""
    if column not in frame.columns:
        raise InputError(f"{what} has no column {column!r}; columns are {list(frame.columns)}")
    return np.asarray(frame[column], dtype=float)


def check_points(check_angles, inputs, strict: bool = True) -> list[float]:
    """The check angles (rad) within the range of the inputs; an angle outside it is refused (named in
    degrees: perhaps given in degrees), or with ``strict=False`` left out (a scene's checks on a figure
    that draws one turn of a longer sweep)."""
    if check_angles is None:
        return []
    if np.ndim(check_angles) == 0:
        check_angles = [check_angles]
    lo, hi = float(np.min(inputs)), float(np.max(inputs))
    tol = 1e-9 * max(1.0, abs(hi))
    inside = [float(a) for a in check_angles if lo - tol <= float(a) <= hi + tol]
    if strict and len(inside) != len(list(check_angles)):
        outside = [f"{math.degrees(float(a)):.6g}" for a in check_angles if not lo - tol <= float(a) <= hi + tol]
        raise InputError(f"check_angles {', '.join(outside)} deg lie outside the sweep, {math.degrees(lo):.6g} to "
                         f"{math.degrees(hi):.6g} deg (check angles are in rad)")
    return inside


def table_column(table, prefix: str, what: str, required: bool = True):
    """The first column whose name starts with `prefix`."""
    for c in table.columns:
        if str(c).startswith(prefix):
            return c
    if required:
        raise InputError(f"{what}: no column starting with {prefix!r}; columns are {list(table.columns)}")
    return None

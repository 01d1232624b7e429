"""Quantities: what numkin computes, each knowing its name, unit and source.

A :class:`Quantity` is the identity of one column of numbers: the unknown or
named point it belongs to, its derivative order (0 position, 1 velocity,
2 acceleration), with respect to time or to the input angle, its unit, and
the source that computed it (``"analytic"``, a difference scheme by name,
``"complex_step"``). Tables take their column labels from it, figures their
axis labels, JSON its keys and checks their messages; nothing parses a
column header back into a quantity.

Names follow one rule:

============  ================  ===================  =====================
of            position          velocity             acceleration
============  ================  ===================  =====================
angle ``b``   ``b`` [rad]       ``omega_b`` [rad/s]  ``alpha_b`` [rad/s^2]
length ``x``  ``x`` [unit]      ``v_x`` [unit/s]     ``a_x`` [unit/s^2]
point ``P``   ``x_P``, ``y_P``  ``vx_P``, ``vy_P``   ``ax_P``, ``ay_P``
============  ================  ===================  =====================

Derivatives with respect to the input angle ``theta`` are named
``dq/dtheta`` and ``d2q/dtheta^2`` (``dbeta/dtheta`` [rad/rad],
``d2x/dtheta^2`` [mm/rad^2]).

Examples
--------
>>> from numkin import linkages
>>> from numkin.quantities import catalogue, resolve
>>> mech = linkages.slider_crank(80, 200)
>>> q = resolve(mech, "a_x")
>>> q.unit, q.order, q.of, q.kind
('mm/s^2', 2, 'x', 'acceleration')
>>> q.with_source("second_difference").label
'a_x, second_difference [mm/s^2]'
>>> sorted(catalogue(mech, orders=(1,), points=False))
['omega_theta3', 'v_x']
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass, replace

from .errors import InputError

__all__ = ["Quantity", "catalogue", "resolve", "input_quantity", "unknown_quantities", "point_quantities", "KINDS", "SOURCES",
           "GREEK", "tex"]

#: Names of the derivative orders.
KINDS = ("position", "velocity", "acceleration")
#: Sources that are not difference schemes.
SOURCES = ("analytic", "complex_step", "solved", "input")

_PREFIX = {  # (dimension, order) -> name prefix, time derivatives
    ("angle", 1): "omega_",
    ("angle", 2): "alpha_",
    ("length", 1): "v_",
    ("length", 2): "a_",
}
_POINT_PREFIX = {0: "", 1: "v", 2: "a"}
#: Names written as Greek letters.
GREEK = {
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa", "lambda",
    "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega",
    "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi", "Omega",
}


@dataclass(frozen=True)
class Quantity:
    """One computed quantity of a mechanism.

    Parameters
    ----------
    of : str
        The unknown (``"beta"``, ``"x"``) or named point (``"P"``) it belongs to.
    order : int
        Derivative order: 0 position, 1 velocity, 2 acceleration.
    dimension : {"angle", "length"}
        What the position is.
    length_unit : str
        The mechanism's length unit (``"mm"``).
    axis : {"x", "y"} or None
        The coordinate, for a point.
    wrt : {"time", "input"}
        Derivative with respect to time (s) or to the input angle (rad).
    source : str
        What computed the values: ``"analytic"``, ``"solved"`` (positions
        from Newton), ``"complex_step"`` or a difference scheme's name.
    input_name : str
        Name of the input angle, for derivatives with respect to it.
    """

    of: str
    order: int
    dimension: str
    length_unit: str = "mm"
    axis: str | None = None
    wrt: str = "time"
    source: str = "analytic"
    input_name: str = "theta"

    def __post_init__(self):
        if self.order not in (0, 1, 2):
            raise InputError(f"order must be 0, 1 or 2, got {self.order!r}")
        if self.dimension not in ("angle", "length"):
            raise InputError(f"dimension must be 'angle' or 'length', got {self.dimension!r}")
        if self.wrt not in ("time", "input"):
            raise InputError(f"wrt must be 'time' or 'input', got {self.wrt!r}")
        if self.axis not in (None, "x", "y"):
            raise InputError(f"axis must be 'x', 'y' or None, got {self.axis!r}")

    def __copy__(self) -> "Quantity":
        return self  # immutable: frozen, every field a str, an int or None

    def __deepcopy__(self, memo) -> "Quantity":
        return self  # pandas deep-copies a table's attrs (which hold Quantities) on every derived frame

    # ------------------------------------------------------------ identity
    @property
    def kind(self) -> str:
        """``"position"``, ``"velocity"`` or ``"acceleration"``."""
        return KINDS[self.order]

    @property
    def is_point(self) -> bool:
        """Whether this is a coordinate of a named point."""
        return self.axis is not None

    @property
    def in_degrees(self) -> bool:
        """Whether its values are written in degrees at the edges (scene keys and tables, the CLI, figures):
        the position of an angle (``theta3 [deg]``, scene key ``theta3_deg``), not its rates."""
        return self.order == 0 and self.dimension == "angle" and not self.is_point

    @property
    def name(self) -> str:
        """The quantity's name, without its source (``"omega_beta"``, ``"vx_P"``, ``"dbeta/dtheta"``)."""
        base = f"{self.axis}_{self.of}" if self.is_point else self.of
        if self.wrt == "input" and self.order:
            # d2x/dtheta2^2, not d2x/dtheta22: an input named with a digit keeps its name
            return f"d{base}/d{self.input_name}" if self.order == 1 else f"d2{base}/d{self.input_name}^2"
        if self.is_point:
            return f"{_POINT_PREFIX[self.order]}{base}"
        return _PREFIX.get((self.dimension, self.order), "") + self.of

    @property
    def unit(self) -> str:
        """SI-style unit string of the values (``"rad/s"``, ``"mm/s^2"``, ``"rad/rad"``)."""
        base = "rad" if self.dimension == "angle" else self.length_unit
        if not self.order:
            return base
        per = "s" if self.wrt == "time" else "rad"
        return f"{base}/{per}" if self.order == 1 else f"{base}/{per}^2"

    @property
    def label(self) -> str:
        """Column or axis label: name, source unless analytic or solved, and unit in brackets."""
        source = "" if self.source in ("analytic", "solved", "input") else f", {self.source}"
        return f"{self.name}{source} [{self.unit}]"

    def source_label(self, what: str = "") -> str:
        """Column label of this quantity among several sources: ``"centred [rad/s]"``,
        ``"centred abs error [rad/s]"`` (with ``what="abs error"``)."""
        return f"{self.source}{' ' + what if what else ''} [{self.unit}]"

    @property
    def symbol(self) -> str:
        r"""Mathtext symbol for figures (``"\omega_{\beta}"``, ``"v_{x}"``, ``"\ddot{x}_{P}"``)."""
        of = tex(self.of)
        if self.wrt == "input" and self.order:
            top = "d" if self.order == 1 else "d^2"
            bottom = f"d{tex(self.input_name)}" + ("" if self.order == 1 else "^2")
            inner = f"{self.axis}_{{{of}}}" if self.is_point else of
            return rf"\frac{{{top}{inner}}}{{{bottom}}}"
        if self.is_point:
            base = self.axis
            dots = ("", r"\dot", r"\ddot")[self.order]
            return f"{dots}{{{base}}}_{{{of}}}" if dots else f"{base}_{{{of}}}"
        if self.order:  # as the names: omega_beta, alpha_beta; v_x, a_x
            heads = (r"\omega", r"\alpha") if self.dimension == "angle" else ("v", "a")
            return heads[self.order - 1] + f"_{{{of}}}"
        return of

    # ------------------------------------------------------------ variants
    def with_source(self, source: str) -> "Quantity":
        """The same quantity computed by another source."""
        return replace(self, source=str(source))

    def derivative(self, wrt: str | None = None) -> "Quantity":
        """The next derivative (velocity of a position, acceleration of a velocity)."""
        if self.order == 2:
            raise InputError(f"{self.name} is an acceleration: numkin computes no third derivative")
        return replace(self, order=self.order + 1, wrt=self.wrt if wrt is None else wrt)

    def position(self) -> "Quantity":
        """The position this quantity is a derivative of."""
        return replace(self, order=0, wrt="time", source="solved")

    def __str__(self) -> str:
        return self.label


def tex(name: str) -> str:
    r"""Mathtext body of a symbol's name: ``theta2`` -> ``\theta_{2}``, ``x_P`` -> ``x_{P}``, ``xD`` -> ``\mathrm{xD}``.

    Examples
    --------
    >>> tex("theta2"), tex("r3"), tex("beta"), tex("x_P"), tex("xD")
    ('\\theta_{2}', 'r_{3}', '\\beta', 'x_{P}', '\\mathrm{xD}')
    """
    m = re.fullmatch(r"([A-Za-z]+?)_?(\d+|_[A-Za-z0-9]+)?", name)
    if not m:
        return r"\mathrm{" + re.sub(r"([_{}$\\])", r"\\\1", name) + "}"
    base, sub = m.group(1), (m.group(2) or "").lstrip("_")
    if base in GREEK:
        base = "\\" + base
    elif len(base) > 1:
        base = r"\mathrm{" + base + "}"
    return base + ("_{" + sub + "}" if sub else "")


def catalogue(mechanism, orders=(0, 1, 2), *, wrt: str = "time", points: bool = True) -> dict:
    """Every quantity numkin computes for a mechanism: name -> :class:`Quantity`.

    The unknowns come first, then the derived quantities (:mod:`numkin.derived`),
    then the points, at each order.

    Parameters
    ----------
    mechanism : Mechanism
    orders : sequence of int
        Derivative orders to list (0 positions, 1 velocities, 2 accelerations).
    wrt : {"time", "input"}
        Derivatives with respect to time or to the input angle.
    points : bool
        Whether to list the coordinates of the named points too.

    Examples
    --------
    >>> from numkin import linkages
    >>> [q.label for q in catalogue(linkages.four_bar(4, 1, 3, 3), orders=(2,), points=False).values()]
    ['alpha_theta3 [rad/s^2]', 'alpha_theta4 [rad/s^2]']
    """
    lu = mechanism.length_unit
    common = dict(length_unit=lu, wrt=wrt, input_name=mechanism.input_name)
    out = {}
    for order in orders:
        source = "solved" if order == 0 else "analytic"
        for name in mechanism.unknowns:
            dim = "angle" if name in mechanism.angles else "length"
            q = Quantity(name, order, dim, source=source, **common)
            out[q.name] = q
        for name, derived in getattr(mechanism, "derived", {}).items():
            q = Quantity(name, order, derived.dimension, source=source, **common)
            out[q.name] = q
        for point in mechanism.points if points else ():
            for axis in "xy":
                q = Quantity(point, order, "length", axis=axis, source=source, **common)
                out.setdefault(q.name, q)
    return out


def resolve(mechanism, name, *, wrt: str = "time") -> Quantity:
    """The :class:`Quantity` of a mechanism named ``name`` (a Quantity is returned as it is).

    Raises
    ------
    ValueError
        For a name the mechanism does not have; the message suggests the
        nearest valid name and lists them all.

    Examples
    --------
    >>> from numkin import linkages
    >>> resolve(linkages.four_bar(4, 1, 3, 3), "omega_theta4").unit
    'rad/s'
    >>> resolve(linkages.four_bar(4, 1, 3, 3), "omega_theta5")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: unknown quantity 'omega_theta5' for four-bar ... (did you mean 'omega_theta4'?); valid: ...
    """
    if isinstance(name, Quantity):
        return name
    if not isinstance(name, str):
        raise TypeError(f"a quantity is named by a string such as 'omega_{mechanism.unknowns[0]}', got {name!r}")
    table = catalogue(mechanism, wrt=wrt)
    if name in table:
        return table[name]
    near = difflib.get_close_matches(name, list(table), n=1)
    hint = f" (did you mean {near[0]!r}?)" if near else ""
    raise InputError(f"unknown quantity {name!r} for {mechanism.name}{hint}; valid: {', '.join(table)}")


def input_quantity(mechanism) -> Quantity:
    """The input angle as a quantity (column ``theta`` [rad], source ``"input"``).

    Examples
    --------
    >>> from numkin import linkages
    >>> input_quantity(linkages.slider_crank(80, 200)).label
    'theta [rad]'
    """
    name = mechanism.input_name
    return Quantity(name, 0, "angle", length_unit=mechanism.length_unit, source="input", input_name=name)


def unknown_quantities(mechanism, source: str = "analytic", second_source: str | None = None) -> list:
    """``[(velocity, acceleration)]`` quantities of each unknown, in unknown order.

    `second_source` (default `source`) is the source of the accelerations.

    Examples
    --------
    >>> from numkin import linkages
    >>> [(v.name, a.label) for v, a in unknown_quantities(linkages.slider_crank(80, 200), "centred",
    ...                                                   "second_difference")]
    [('omega_theta3', 'alpha_theta3, second_difference [rad/s^2]'), ('v_x', 'a_x, second_difference [mm/s^2]')]
    """
    cat = catalogue(mechanism, orders=(1, 2), points=False)
    by = {(q.of, q.order): q for q in cat.values()}
    return [
        (by[name, 1].with_source(source), by[name, 2].with_source(second_source or source))
        for name in mechanism.unknowns
    ]


def point_quantities(mechanism, point: str, source: str = "analytic") -> list:
    """The six quantities of a named point: ``[(x, y), (vx, vy), (ax, ay)]``.

    Examples
    --------
    >>> from numkin import linkages
    >>> [[q.name for q in pair] for pair in point_quantities(linkages.slider_crank(80, 200), "P")]
    [['x_P', 'y_P'], ['vx_P', 'vy_P'], ['ax_P', 'ay_P']]
    """
    common = dict(length_unit=mechanism.length_unit, input_name=mechanism.input_name)
    return [
        tuple(Quantity(point, order, "length", axis=axis, source="solved" if order == 0 else source, **common)
              for axis in "xy")
        for order in (0, 1, 2)
    ]

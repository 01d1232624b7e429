"""The quantity an error table studies: an unknown or a derived quantity, over any sweep.

The tables of :mod:`numkin.report` study one quantity of a mechanism: an
unknown (``"beta"``) or a derived quantity declared with
:meth:`numkin.Mechanism.add_quantities` or a scene's
``[mechanism.quantities]`` (:mod:`numkin.derived`, e.g. a four-bar's
transmission angle ``mu = theta4 - theta3``). A :class:`StudiedQuantity`
gives what every table needs of it, in one place instead of a row index:
its values over a sweep or at any solved positions, its exact derivatives
with respect to the input (for a derived quantity, the chain rule of
:mod:`numkin.expressions` applied to the unknowns' rates), its finite
differences (an angle unwrapped and a full turn differenced as periodic, as
:mod:`numkin.kinematics` differences the unknowns; as an open grid where a
derived quantity does not return to its start after the turn,
:meth:`StudiedQuantity.closes`), its values in complex arithmetic for the
complex step (:meth:`StudiedQuantity.complex_at`), whether it is an angle,
and its labels and units (:mod:`numkin.quantities`).

Examples
--------
>>> from numkin import linkages
>>> mu = studied_quantity(linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")}), "mu")
>>> mu.is_angle, mu.labels[2], mu.title
(True, 'alpha_mu [rad/s^2]', 'mu = theta4 - theta3')
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import kinematics
from ..errors import InputError
from .study import check_quantity, differenced, exact_derivatives, quantity_labels, shared_result, table_quantities

__all__ = ["StudiedQuantity", "studied_quantity"]

TURN = 2.0 * math.pi



def _row(value, size: int) -> np.ndarray:
    """One row of a compiled expression's output as an (size,) array (a constant broadcast)."""
    return np.array(np.broadcast_to(np.asarray(value).reshape(-1), (size,)))


@dataclass(frozen=True, eq=False)
class StudiedQuantity:
    """What an error table studies: an unknown or a derived quantity, over any sweep of its mechanism.

    The tables of :mod:`numkin.report` ask it, never a row index, for the
    quantity's sampled values, its exact derivatives with respect to the
    input and its finite differences, so that an unknown (``"beta"``) and
    a derived quantity (``"mu"``, :mod:`numkin.derived`) are studied alike.
    Made by :func:`studied_quantity`.

    Attributes
    ----------
    mechanism : Mechanism
    name : str
    dimension : {"angle", "length"}
        An angle (rad) is differenced unwrapped, and a full turn may add
        whole turns to it, as the unknowns' angles
        (:func:`numkin.kinematics.prepare_rows`).
    index : int or None
        Its row among the unknowns; None for a derived quantity.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.slider_crank(80, 200).add_quantities({"gap": ("x - r*cos(theta)", "length")})
    >>> gap = studied_quantity(mech, "gap")
    >>> s = mech.sweep(np.radians([0.0, 90.0]))
    >>> print(gap.values(s).round(4), gap.exact(s)[1].round(4))   # sqrt(l^2 - r^2 sin^2), its d2/dtheta2
    [200.    183.303] [-32.      34.9149]
    """

    mechanism: Any
    name: str
    dimension: str
    index: int | None = None

    @property
    def is_angle(self) -> bool:
        """Whether the quantity is an angle (rad)."""
        return self.dimension == "angle"

    @property
    def derived(self) -> bool:
        """Whether it is a derived quantity (not an unknown)."""
        return self.index is None

    @property
    def title(self) -> str:
        """Its name, and for a derived quantity its expression: ``"beta"``, ``"mu = theta4 - theta3"``."""
        if not self.derived:
            return self.name
        return f"{self.name} = {self.mechanism.derived[self.name].expression}"

    @property
    def labels(self) -> dict:
        """:func:`~numkin.report.study.quantity_labels` of the quantity."""
        return quantity_labels(self.mechanism, self.name)

    @property
    def quantities(self) -> dict:
        """:func:`~numkin.report.study.table_quantities` of the quantity (a table's ``attrs["quantities"]``)."""
        return table_quantities(self.mechanism, self.name)

    def work(self, sweep) -> int:
        """Point evaluations of the derived quantity's compiled expression a method spends over `sweep`.

        Every method evaluates it once per input (its values for the
        differences, its chain rule for the exact derivatives): the sweep's
        input count; 0 for an unknown, whose values are the sweep's own.
        """
        return int(np.asarray(sweep.inputs).size) if self.derived else 0

    def _functions(self, rates: bool = True) -> tuple:
        from ..expressions import derived_functions

        return derived_functions(self.mechanism, self.name, rates)  # compiled once per mechanism

    def _finite(self, values, given, t, what: str) -> np.ndarray:
        """`values`, or an InputError naming the first input where they are not finite while `given` is."""
        bad = np.flatnonzero(~np.isfinite(values) & np.all(np.isfinite(given), axis=0))
        if bad.size:
            raise InputError(
                f"{self.mechanism.name}: {what} of the quantity {self.title!r} is not finite at input "
                f"{math.degrees(float(t[bad[0]])):.6g} deg ({bad.size} of {t.size} inputs): its expression is "
                "undefined there; the error tables need it over the whole sweep"
            )
        return values

    def at(self, x, t, *, check: bool = True) -> np.ndarray:
        """Its values at the positions `x` (n, M) of the unknowns and the inputs `t` (M,), rad.

        An InputError where the expression is undefined (not finite) at finite positions; with
        ``check=False``, NaN there instead.
        """
        t = np.atleast_1d(np.asarray(t, dtype=float))
        x = np.asarray(x, dtype=float).reshape(-1, t.size)
        if not self.derived:
            return x[self.index].copy()
        (f,) = self._functions(rates=False)
        with np.errstate(all="ignore"):
            e = _row(f(*x, t, *self.mechanism.parameter_values), t.size)
        return self._finite(e, x, t, "the value") if check else np.where(np.isfinite(e), e, np.nan)

    def complex_at(self, x, t):
        """Its values at complex positions `x` (n, M) and complex inputs `t` (M,), or a str saying why not.

        What the complex step of the quantity needs: ``Im(q(x(theta + i h), theta + i h)) / h``. An
        unknown's row; a derived quantity's compiled expression evaluated in complex arithmetic, where it
        is analytic. An expression through a function that is not (``abs``, ``atan2``, ``sign``, ...),
        or that the compiled function refuses or returns real for complex input, gives the reason
        instead: a complex step through it is meaningless.

        Examples
        --------
        >>> import numpy as np
        >>> from numkin import linkages
        >>> m = linkages.slider_crank(80, 200).add_quantities({"g": ("x - r*cos(theta)", "length"),
        ...                                                     "a": ("abs(x - 250)", "length")})
        >>> x, t = np.array([[0.0], [280.0 + 1e-20j]]), np.array([0.0 + 1e-20j])
        >>> print(studied_quantity(m, "g").complex_at(x, t).imag / 1e-20)   # x' + r sin(theta): 1 + 0
        [1.]
        >>> studied_quantity(m, "a").complex_at(x, t)
        'its expression is not analytic (Abs): no complex step through it'
        """
        t = np.atleast_1d(np.asarray(t, dtype=complex))
        x = np.asarray(x, dtype=complex).reshape(-1, t.size)
        if not self.derived:
            return x[self.index].copy()
        import sympy as sp

        (f,) = self._functions(rates=False)
        kinds = (sp.Abs, sp.atan2, sp.sign, sp.Heaviside, sp.Min, sp.Max, sp.floor, sp.ceiling, sp.re, sp.im,
                 sp.arg, sp.conjugate, sp.Piecewise, sp.Mod)
        found = sorted({type(a).__name__ for e in getattr(f, "expressions", ()) for a in e.atoms(*kinds)})
        if found:
            return f"its expression is not analytic ({', '.join(found)}): no complex step through it"
        try:
            with np.errstate(all="ignore"):
                e = np.asarray(f(*x, t, *self.mechanism.parameter_values))
        except (TypeError, ValueError, AttributeError) as exc:
            return f"its compiled expression refuses complex input ({type(exc).__name__}): no complex step through it"
        if not np.iscomplexobj(e):
            return "its compiled expression returns real values for complex input: no complex step through it"
        return np.array(np.broadcast_to(e.reshape(-1), (t.size,)))

    def near(self, values, reference) -> np.ndarray:
        """`values` moved by whole turns to lie within pi of `reference`, for an angle; as they are otherwise.

        A derived angle may be reduced to (-pi, pi] by its expression
        (``atan2``): samples of one stencil across that cut are brought
        together before they are differenced. Values already within pi are
        returned bit for bit.
        """
        values = np.asarray(values, dtype=float)
        if not self.is_angle:
            return values
        return values - TURN * np.round((values - reference) / TURN)

    def values(self, sweep) -> np.ndarray:
        """Its values over `sweep` (rad or the length unit)."""
        return self.at(sweep.values, sweep.inputs)

    def rates(self, x, t, dq, d2q=None) -> tuple:
        """``(de/dtheta, d2e/dtheta2)`` from the unknowns' rates `dq`, `d2q` (n, M) at `x`, `t`.

        The chain rule of :mod:`numkin.expressions` for a derived quantity
        (exact: the unknowns' rates carry all the error); the unknown's own
        row for an unknown. Without `d2q`, the second is None.
        """
        t = np.atleast_1d(np.asarray(t, dtype=float))
        dq = np.asarray(dq, dtype=float).reshape(-1, t.size)
        if d2q is not None:
            d2q = np.asarray(d2q, dtype=float).reshape(-1, t.size)
        if not self.derived:
            return dq[self.index].copy(), None if d2q is None else d2q[self.index].copy()
        _, f1, f2 = self._functions()
        x = np.asarray(x, dtype=float).reshape(-1, t.size)
        args = (*x, *dq, *(np.zeros_like(dq) if d2q is None else d2q), t, *self.mechanism.parameter_values)
        with np.errstate(all="ignore"):
            first = _row(f1(*args), t.size)
        if not np.all(np.isfinite(first)):
            self.at(x, t)  # where the value itself is undefined, say so
        with np.errstate(all="ignore"):
            first = self._finite(first, np.vstack([x, dq]), t, "the first derivative")
            second = None if d2q is None else self._finite(_row(f2(*args), t.size), np.vstack([x, dq, d2q]), t,
                                                         "the second derivative")
        return first, second

    def exact(self, sweep, quiet: bool = True, *, fresh: bool = False) -> tuple:
        """The exact ``(dq/dtheta, d2q/dtheta2)`` of the quantity over `sweep`.

        From the unknowns' analytic rates (:func:`~numkin.report.study.exact_derivatives`, shared by the
        tables of one report).
        """
        dq, d2q = exact_derivatives(sweep, quiet, fresh=fresh)
        return self.rates(sweep.values, sweep.inputs, dq, d2q)

    def closure_gap(self, sweep) -> float:
        """How far the quantity's end misses its start over the full-turn `sweep`, whole turns aside (angle).

        0 for an unknown: an unknown always closes after a turn of the input
        (modulo whole turns). A derived quantity closes only if its values
        at the two ends of the turn differ by whole turns (an angle) or by
        nothing (a length): ``theta2/2 + theta3`` or ``r2*theta2`` do not.
        Decide it on a tightly solved sweep (the tables' own), never on a
        loosely solved one, whose end misses its start by its position error.
        """
        if not self.derived:
            return 0.0
        t = np.asarray(sweep.inputs, dtype=float)
        ends = self.at(np.asarray(sweep.values)[:, [0, -1]], t[[0, -1]])
        return kinematics.closure_gap(float(ends[1] - ends[0]), self.is_angle)

    def closes(self, sweep) -> bool:
        """Whether the quantity returns to its start after the full turn `sweep` (:meth:`closure_gap`).

        Within :data:`numkin.kinematics.CLOSURE_TOL` (rad, or times the mechanism's length
        scale for a length): the solve's accuracy is far finer, a quantity
        that does not close misses by far more.

        Examples
        --------
        >>> from numkin import linkages
        >>> from numkin.report.grids import TURN, grid_inputs
        >>> m = linkages.four_bar(4, 1, 3, 3).add_quantities({"half": ("theta2/2 + theta3", "angle")})
        >>> s = m.sweep(grid_inputs(36, 0.0, TURN))
        >>> studied_quantity(m, "theta3").closes(s), studied_quantity(m, "half").closes(s)
        (True, False)
        >>> round(abs(studied_quantity(m, "half").closure_gap(s)), 6)   # half a turn
        3.141593
        """
        return kinematics.closes(self.closure_gap(sweep), self.is_angle, float(self.mechanism.length_scale))

    def closure_text(self, sweep) -> str:
        """A caption's sentence on a full turn differenced as an open grid because the quantity does not close."""
        return (
            f" {self.name} does not return to its start after the turn (its end misses its start by "
            f"{self.gap_text(sweep)}): the full turn is differenced as an open grid."
        )

    def gap_text(self, sweep) -> str:
        """:meth:`closure_gap` with its unit, for messages (``"3.14159 rad, whole turns aside"``, ``"6.28319 mm"``)."""
        unit = "rad, whole turns aside" if self.is_angle else self.mechanism.length_unit
        return f"{self.closure_gap(sweep):.6g} {unit}"

    def differenced(self, sweep, scheme, quiet: bool = True, *, fresh: bool = False, close: bool = False,
                    periodic: bool | None = None, gap: float = 0.0):
        """d/dtheta (or d2/dtheta2) of the quantity over `sweep` by the finite-difference `scheme` (a Scheme).

        An unknown's row of :func:`~numkin.report.study.differenced`; a derived quantity's
        values differenced as the unknowns are (angles unwrapped, a full
        turn as periodic). With `close`, a full turn is differenced as
        periodic even where its end misses its start by the solver's error
        (:func:`numkin.kinematics.sweep_derivative`): the period offset is
        then whole turns plus ``gap``, the derived quantity's own
        :meth:`closure_gap` measured on a tightly solved sweep (a quantity
        within :data:`numkin.kinematics.CLOSURE_TOL` of closing, ``theta3 + 1e-8*theta2``,
        keeps its small gap). ``periodic=False``
        differences a derived quantity's full turn as an open grid (one that
        does not close, :meth:`closes`); an unknown ignores it.
        """
        if not self.derived and not close:
            return differenced(sweep, scheme, quiet, fresh=fresh)[self.index]
        if not self.derived:
            return kinematics.sweep_derivative(sweep, scheme.name, periodic=True, close=True)[self.index]
        if periodic is False:
            close = False

        def compute():
            mech, t = self.mechanism, np.asarray(sweep.inputs, dtype=float)
            periodic_ = False if periodic is False else True if close else "auto"
            rows = kinematics.prepare_rows(self.values(sweep)[None], [self.is_angle], [self.name], t,
                                           kinematics.sweep_grid(sweep, periodic_), mech.length_scale, periodic_,
                                           close=close, tangent=lambda: self.exact(sweep, quiet)[0][None])
            if close and rows.periodic and gap:
                rows.offset = rows.offset + gap  # whole turns (the solver's error dropped) and the quantity's own gap
            return rows.apply(scheme)[0]

        key = ("differenced", id(sweep), scheme.name, self.name, close, periodic, gap)
        return shared_result(key, compute, quiet, keep=(sweep,), fresh=fresh)


def studied_quantity(mechanism, quantity) -> StudiedQuantity:
    """The quantity an error table studies: an unknown or a derived quantity, by name (checked).

    Raises
    ------
    InputError
        If `quantity` is neither, naming the unknowns and derived quantities.

    Examples
    --------
    >>> from numkin import linkages
    >>> studied_quantity(linkages.slider_crank(80, 200), "x").index
    1
    >>> studied_quantity(linkages.slider_crank(80, 200), "mu")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: quantity 'mu' is neither an unknown nor a derived quantity of slider-crank ...
    """
    if isinstance(quantity, StudiedQuantity):
        return quantity
    check_quantity(mechanism, quantity)
    if quantity in mechanism.unknowns:
        dimension = "angle" if quantity in mechanism.angles else "length"
        return StudiedQuantity(mechanism, quantity, dimension, mechanism.unknowns.index(quantity))
    return StudiedQuantity(mechanism, quantity, mechanism.derived[quantity].dimension)

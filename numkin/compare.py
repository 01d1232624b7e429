"""Finite-difference schemes side by side with the exact (analytic) kinematics.

:func:`compare` takes one quantity of a sweep -- the angular velocity of a
link, the acceleration of a slider, the velocity of a named point -- and
returns, per input angle, the analytic value (:mod:`numkin.analytic`), the
value of each requested finite-difference scheme (:mod:`numkin.kinematics`)
and their errors, plus a summary of the max and RMS error per scheme.

Quantities
----------
The names of the columns of :func:`numkin.analytic.kinematics` and
:func:`numkin.analytic.point_kinematics`:

* ``omega_<angle>`` [rad/s], ``alpha_<angle>`` [rad/s^2];
* ``v_<length>`` [unit/s], ``a_<length>`` [unit/s^2];
* ``vx_<P>``, ``vy_<P>`` [unit/s], ``ax_<P>``, ``ay_<P>`` [unit/s^2] of a
  named point P;
* the rates of a derived quantity (:mod:`numkin.derived`), named as an
  unknown's (``omega_mu``, ``alpha_mu`` of a transmission angle ``mu``).

Velocities are compared with first-derivative schemes, accelerations with
second-derivative ones. For an accelerating input the ``alpha_in q'`` term
of an acceleration uses the first-derivative scheme of the same family
(:data:`numkin.kinematics.PARTNER`: forward with forward_of_forward, centred
with second_difference and centred_of_centred, five_point with
five_point_second, spectral with spectral_second).

Errors
------
``abs error = |scheme - analytic|`` (in the quantity's unit). Two relative
errors, both dimensionless:

* ``rel error = abs error / max|analytic|``, the error relative to the
  largest value of the quantity over the sweep. It stays meaningful where
  the quantity crosses zero, and it is the one summarised (NaN where the
  quantity is zero over the whole sweep, e.g. the acceleration of a length
  linear in the input);
* ``pointwise rel error = abs error / |analytic|``, which grows without
  bound near a zero crossing of the quantity (NaN where it is exactly 0).

On a periodic (full-turn) sweep the last row repeats the first and is left
out of the RMS values.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from . import derivatives as _d
from .analytic import check_sweep, derivatives, input_rates
from .column_kinds import set_kinds
from .expressions import derived_derivatives, point_derivatives
from .errors import InputError
from .kinematics import PARTNER, apply_scheme, prepare_rows, scheme_for, sweep_grid
from .quantities import Quantity, catalogue, input_quantity
from .schemes import NameList, default_schemes, own_stencil_points
from .units import input_degrees

__all__ = ["Comparison", "SummaryColumn", "compare", "quantities", "DEFAULT_SCHEMES"]

#: Schemes compared by default on an open sweep: first-derivative quantities / second-derivative ones
#: (:func:`numkin.schemes.default_schemes`: the ``default`` first-derivative schemes and their partners;
#: always current). The spectral ones are added on a periodic (full-turn) sweep.
DEFAULT_SCHEMES = {d: NameList(lambda d=d: default_schemes(d, periodic=False)) for d in (1, 2)}


@dataclass(frozen=True)
class Comparison:
    """Result of :func:`compare`.

    Attributes
    ----------
    quantity : str
        The compared quantity, e.g. ``"omega_beta"``.
    unit : str
        Its unit, e.g. ``"rad/s"``.
    table : pandas.DataFrame
        One row per input: ``<input> [deg]``, ``analytic [unit]``, and for
        each scheme ``<scheme> [unit]``, ``<scheme> abs error [unit]``,
        ``<scheme> rel error`` and ``<scheme> pointwise rel error``.
    summary : pandas.DataFrame
        One row per scheme (index ``scheme``): ``order`` (of the truncation
        error; "spectral" for the FFT schemes), ``max abs error [unit]``,
        ``rms abs error [unit]``, ``max rel error``, ``rms rel error`` and
        ``max at <input> [deg]`` (where the largest error occurs), over the
        points where the scheme's own stencil applies; on an open grid also
        ``ends abs error [unit]``, the largest error of the one-sided end
        stencils at the first and last points (``table.attrs["ends"]``:
        scheme -> how many points at the start and at the end take them).
        ``summary.attrs["columns"]`` names each column's role and unit
        (:class:`SummaryColumn`); :meth:`summary_records` gives the values by role.
    scale : float
        ``max|analytic|`` over the sweep, the denominator of ``rel error``.
    h : float
        Grid step, rad.
    periodic : bool
        Whether the sweep was differenced as one periodic turn.
    target : Quantity or None
        The compared :class:`~numkin.quantities.Quantity`; ``table.attrs["quantities"]``
        maps each value column (analytic and each scheme) to its Quantity.
    """

    quantity: str
    unit: str
    table: object
    summary: object
    scale: float
    h: float
    periodic: bool
    target: Quantity | None = None

    def summary_records(self) -> dict:
        """The summary by role: scheme -> {key: value}, keys of :class:`SummaryColumn` in the summary's order.

        The order is text (``"2"``, ``"spectral"``), every other value a float (NaN where undefined).

        Examples
        --------
        >>> import numpy as np
        >>> from numkin import linkages
        >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361)))
        >>> c = compare(sweep, 1.0, "v_x", schemes=("centred",))
        >>> record = c.summary_records()["centred"]
        >>> list(record)
        ['order', 'max_abs_error', 'rms_abs_error', 'max_rel_error', 'rms_rel_error', 'max_at_deg']
        >>> bool(record["max_abs_error"] == c.summary.loc["centred", "max abs error [mm/s]"])
        True
        """
        columns = self.summary.attrs["columns"]
        return {
            str(scheme): {key: _plain(row[column.header]) for key, column in columns.items()}
            for scheme, row in self.summary.iterrows()
        }

    def __repr__(self) -> str:
        return (
            f"Comparison({self.quantity!r} [{self.unit}], h = {math.degrees(self.h):.6g}°, "
            f"{'periodic' if self.periodic else 'open'} grid, {len(self.table)} points)\n"
            f"{self.summary.to_string()}"
        )


@dataclass(frozen=True)
class SummaryColumn:
    """What one column of a comparison's summary holds: its role, its label and the unit of its values.

    ``Comparison.summary.attrs["columns"]`` maps each role (``key``) to
    its column, in the summary's order; outputs read a value by its role,
    never by taking a label apart.

    Attributes
    ----------
    key : str
        The column's role, also its key in JSON: ``"order"``,
        ``"max_abs_error"``, ``"rms_abs_error"``, ``"max_rel_error"``,
        ``"rms_rel_error"``, ``"max_at_deg"`` (the input angle of the largest
        error) or ``"ends_abs_error"`` (open grids only).
    name : str
        Its label without the unit (``"max abs error"``, ``"max at theta"``).
    unit : str or None
        Unit of its values (``"rad/s"``, ``"deg"``); None for the relative
        errors (dimensionless) and the order (text).
    quantity_unit : bool
        Whether the unit is the compared quantity's (the absolute errors):
        a table of several quantities gives that unit once per row instead.
    kind : str or None
        What its numbers are (:mod:`numkin.column_kinds`: ``"error"``, or
        ``"input"`` for the angle of the largest error); None for the order (text).

    Examples
    --------
    >>> SummaryColumn("max_abs_error", "max abs error", "rad/s", True).header
    'max abs error [rad/s]'
    """

    key: str
    name: str
    unit: str | None = None
    quantity_unit: bool = False
    kind: str | None = None

    @property
    def header(self) -> str:
        """The column's label in the summary: its name, and its unit in brackets if it has one."""
        return f"{self.name} [{self.unit}]" if self.unit else self.name


def _summary_columns(target: Quantity, input_name: str, periodic: bool) -> dict:
    """The columns of a comparison's summary, role -> :class:`SummaryColumn`, in the summary's order."""
    unit = target.unit
    columns = [
        SummaryColumn("order", "order"),
        SummaryColumn("max_abs_error", "max abs error", unit, True, "error"),
        SummaryColumn("rms_abs_error", "rms abs error", unit, True, "error"),
        SummaryColumn("max_rel_error", "max rel error", kind="error"),
        SummaryColumn("rms_rel_error", "rms rel error", kind="error"),
        SummaryColumn("max_at_deg", f"max at {input_name}", "deg", kind="input"),
    ]
    if not periodic:  # the one-sided end stencils, apart
        columns.append(SummaryColumn("ends_abs_error", "ends abs error", unit, True, "error"))
    return {c.key: c for c in columns}


def _plain(value):
    """A summary's cell as Python data: text as it is, a number as a float."""
    return value if isinstance(value, str) else float(value)


# --------------------------------------------------------------------------- quantities
def _catalog(mechanism) -> dict:
    """Velocities and accelerations (name -> :class:`~numkin.quantities.Quantity`) that compare accepts."""
    return catalogue(mechanism, orders=(1, 2))


def quantities(mechanism) -> dict:
    """The quantities :func:`compare` accepts for a mechanism, name -> (derivative order, unit).

    Examples
    --------
    >>> from numkin import linkages
    >>> q = quantities(linkages.slider_crank(80, 200))
    >>> q["alpha_theta3"], q["v_x"], q["ax_P"]
    ((2, 'rad/s^2'), (1, 'mm/s'), (2, 'mm/s^2'))
    """
    from .mechanism import Mechanism

    if not isinstance(mechanism, Mechanism):
        raise InputError(f"mechanism must be a numkin.Mechanism, got {type(mechanism).__name__} {mechanism!r:.60}")
    return {k: (q.order, q.unit) for k, q in _catalog(mechanism).items()}


def _resolve(mech, quantity) -> Quantity:
    """The :class:`~numkin.quantities.Quantity` of a velocity or acceleration, or a ValueError listing the valid ones."""
    catalog = _catalog(mech)
    if isinstance(quantity, Quantity):
        # one of this mechanism's own quantities, as resolve() gives it: a Quantity made elsewhere may
        # carry another unit or dimension, which would label the comparison's columns wrongly
        own = catalog.get(quantity.name)
        if own is None or own != quantity or own.order not in (1, 2):
            what = "a velocity or acceleration" if own is None or own.order not in (1, 2) else repr(own)
            raise InputError(f"quantity {quantity!r} is not {what} of {mech.name}: give its name, or the Quantity "
                             f"numkin.quantities.resolve(mechanism, name) returns; valid: {sorted(catalog)}")
        return own
    if not isinstance(quantity, str):
        raise InputError(f"quantity must be a name such as 'omega_{mech.unknowns[0]}', got {type(quantity).__name__} "
                         f"{quantity!r:.60}; valid: {sorted(catalog)}")
    if quantity in catalog:
        return catalog[quantity]
    hint = ""
    if quantity in mech.unknowns or quantity in mech.derived:
        velocity, acceleration = (catalog[n] for n in catalogue(mech, (1, 2), points=False) if catalog[n].of == quantity)
        what = "unknown" if quantity in mech.unknowns else "quantity"
        hint = f" (for the {what} {quantity!r} use {velocity.name!r} or {acceleration.name!r})"
    raise InputError(f"unknown quantity {quantity!r} for {mech.name}{hint}; valid: {sorted(catalog)}")


# --------------------------------------------------------------------------- compare
def compare(sweep, omega, quantity, schemes=None, alpha=0.0, periodic="auto") -> Comparison:
    """Compare finite-difference schemes with the analytic value of one quantity over a sweep.

    Parameters
    ----------
    sweep : Sweep
        A solved sweep on a uniform grid.
    omega : float, str or array_like
        Input angular speed: rad/s or a string with units (``"450 rad/min"``).
    quantity : str
        A column name of :func:`numkin.analytic.kinematics` (``"omega_beta"``,
        ``"alpha_beta"``, ``"v_x"``, ``"a_x"``) or of
        :func:`numkin.analytic.point_kinematics` (``"vx_D"``, ``"ax_D"``) or
        :func:`numkin.analytic.derived_kinematics` (``"omega_mu"``).
    schemes : sequence of str, optional
        Scheme names of :data:`numkin.derivatives.SCHEMES` estimating the
        quantity's derivative (first for velocities, second for
        accelerations). Default :data:`DEFAULT_SCHEMES`, plus the spectral
        scheme on a periodic sweep.
    alpha : float, str or array_like, default 0
        Input angular acceleration: rad/s^2 or a string with units.
    periodic : {"auto", True, False}, default "auto"
        As in :func:`numkin.kinematics.finite_difference`.

    Returns
    -------
    Comparison
        ``.table`` per input and ``.summary`` per scheme (see
        :class:`Comparison` and the module notes on the relative errors).

    Raises
    ------
    ValueError
        For an unknown quantity (the message lists the valid ones), a
        scheme of the wrong derivative order, or a grid the schemes cannot
        use.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> from numkin.compare import compare
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    >>> c = compare(sweep, "450 rad/min", "omega_beta", schemes=("forward", "centred"))
    >>> print(c.table.loc[100, ["theta [deg]", "analytic [rad/s]", "forward [rad/s]", "centred [rad/s]"]]
    ...       .round(4).to_string())
    theta [deg]         100.0000
    analytic [rad/s]     10.6329
    forward [rad/s]      10.6000
    centred [rad/s]      10.6330
    >>> print(c.summary["order"].to_dict())
    {'forward': '1', 'centred': '2'}
    """
    import pandas as pd

    mech, t, q = check_sweep(sweep)
    target = _resolve(mech, quantity)
    quantity, order, unit, name = target.name, target.order, target.unit, target.of
    grid = sweep_grid(sweep, periodic)
    w, a = input_rates(omega, alpha, t.size)
    if not (np.any(w != 0) or (order == 2 and np.any(a != 0))):
        raise InputError(f"omega = 0{' and alpha = 0' if order == 2 else ''}: the input is at rest and every "
                         f"{target.kind} is 0, so no scheme's error can be compared; give the input's speed")

    # the signal and its exact theta-derivatives
    if name in mech.derived and not target.is_point:
        y, d1, d2 = derived_derivatives(sweep, name)[name]
        is_angle = target.dimension == "angle"
    elif not target.is_point:
        k = mech.unknowns.index(name)
        dq, d2q = derivatives(sweep)
        y, d1, d2 = q[k], dq[k], d2q[k]
        is_angle = target.dimension == "angle"
    else:
        axis = "xy".index(target.axis)
        P, dP, d2P = point_derivatives(sweep, name)[name]
        y, d1, d2 = P[axis], dP[axis], d2P[axis]
        is_angle = False
    rows = prepare_rows(y[None, :], [is_angle], [name], t, grid, mech.length_scale, periodic, tangent=d1[None, :])
    exact = w * d1 if order == 1 else w**2 * d2 + a * d1

    if schemes is None:
        schemes = default_schemes(order, periodic=rows.periodic)
    elif isinstance(schemes, str) or not isinstance(schemes, Iterable):
        schemes = (schemes,)  # one scheme: scheme_for names it if it is none
    parameter = "schemes" + ("" if order == 1 else f" (for the acceleration {quantity})")
    chosen = [scheme_for(s, order, parameter) for s in schemes]
    if not chosen:
        raise InputError("schemes must name at least one finite-difference scheme")

    in_col = f"{input_quantity(mech).name} [deg]"
    analytic_q = target.with_source("analytic")
    table = {in_col: input_degrees(t), analytic_q.source_label(): exact}
    columns = {analytic_q.source_label(): analytic_q}
    scale = float(np.nanmax(np.abs(exact))) if np.any(np.isfinite(exact)) else float("nan")
    summary_columns = _summary_columns(target, input_quantity(mech).name, rows.periodic)
    summary = []
    ends_of = {}  # scheme -> rows at the start and at the end taken by one-sided end stencils
    for s in chosen:
        used = [s]  # the schemes the value is made of
        if order == 1:
            value = w * apply_scheme(rows, s, "schemes", target.name)[0]
        else:
            value = w**2 * apply_scheme(rows, s, "schemes", target.name)[0]
            if np.any(a != 0):  # the input's acceleration times dq/dtheta, by the scheme's partner
                used.append(_d.get_scheme(PARTNER[s.name]))
                value = value + a * apply_scheme(rows, used[1], f"schemes ({s.name}'s partner)", target.name)[0]
        # the rows where the scheme's own stencil applies: on an open grid its ends take one-sided stencils
        own = own_stencil_points(used, t.size, rows.periodic)  # (counted along increasing input)
        if rows.reverse:  # a descending sweep: its first samples are the grid's last
            own = slice(t.size - own.stop, t.size - own.start)
        keep = np.zeros(t.size, dtype=bool)
        keep[own] = True
        if not rows.periodic:
            ends_of[s.name] = (int(own.start), int(t.size - own.stop))
        if not keep.any():
            keep[:] = True
        err = np.abs(value - exact)
        rel = err / scale if scale > 0 else np.full_like(err, np.nan)
        with np.errstate(divide="ignore", invalid="ignore"):
            pointwise = np.where(exact != 0, err / np.abs(exact), np.nan)
        sq = target.with_source(s.name)
        columns[sq.source_label()] = sq
        table[sq.source_label()] = value
        table[sq.source_label("abs error")] = err
        table[f"{s.name} rel error"] = rel
        table[f"{s.name} pointwise rel error"] = pointwise
        inner = np.where(keep, err, np.nan)
        worst = int(np.nanargmax(inner)) if np.any(np.isfinite(inner)) else 0
        values = {
            "order": "spectral" if s.order == 0 else str(s.order),
            "max_abs_error": float(np.nanmax(inner)),
            "rms_abs_error": float(np.sqrt(np.nanmean(err[keep] ** 2))),
            # (NaN where the analytic value is zero over the whole sweep: no error is relative to it)
            "max_rel_error": float(np.nanmax(np.where(keep, rel, np.nan))) if scale > 0 else np.nan,
            "rms_rel_error": float(np.sqrt(np.nanmean(rel[keep] ** 2))) if scale > 0 else np.nan,
            "max_at_deg": float(input_degrees(t[worst])),
        }
        if not rows.periodic:  # the one-sided end stencils, apart
            ends = ~keep
            values["ends_abs_error"] = float(np.nanmax(err[ends])) if ends.any() else np.nan
        row = {"scheme": s.name, **{summary_columns[key].header: value for key, value in values.items()}}
        summary.append(row)
    table_df = pd.DataFrame(table)
    summary_df = pd.DataFrame(summary).set_index("scheme")
    for df in (table_df, summary_df):
        df.attrs.update({"quantity": quantity, "unit": unit, "h": rows.h, "periodic": rows.periodic,
                         "descending": rows.reverse, "target": target})
    summary_df.attrs["columns"] = summary_columns
    set_kinds(summary_df, {c.header: c.kind for c in summary_columns.values() if c.kind})
    # the input, the values (analytic and each scheme's: a Quantity each), and their errors
    set_kinds(table_df, {c: "input" if c == in_col else "value" if c in columns else "error" for c in table_df.columns})
    table_df.attrs["quantities"] = columns
    table_df.attrs["ends"] = ends_of
    return Comparison(quantity, unit, table_df, summary_df, scale, rows.h, rows.periodic, target)

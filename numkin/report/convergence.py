"""The convergence table: error of every scheme on every grid against the analytic solution."""

from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np

from ..column_kinds import set_kinds
from ..errors import InputError
from ..schemes import own_stencil_points
from .captions import UNIT, deg_text, PEAK, order_text, relative, relative_text, set_caption, set_views, zero_text
from .grids import DEFAULT_GRIDS, TURN, check_index, full_turn, grid_inputs, grid_positions, grid_study
from .study import EPS, solve_sweep, warned_once

__all__ = [
    "convergence_table",
    "ROUNDOFF_UNITS",
]

#: Errors at most this many units of ``eps max|q| / h^n`` are at the round-off floor of an n-th
#: derivative by differences of samples known to ``eps |q|``: no observed order is given from them.
ROUNDOFF_UNITS = 16.0


def convergence_table(
    mechanism,
    *,
    omega,
    quantity: str,
    check_angle: float | None = None,
    grids: Iterable[int] = DEFAULT_GRIDS,
    schemes: Sequence[str] | None = None,
    start: float = 0.0,
    span: float = TURN,
    guess=None,
):
    """Error of each scheme on each grid against the analytic solution, with the observed order.

    Parameters
    ----------
    mechanism : Mechanism
    omega : float or str
        Constant input speed, rad/s or a string with units (``"450 rad/min"``).
    quantity : str
        The unknown, or derived quantity (:mod:`numkin.derived`, e.g. a
        four-bar's transmission angle ``"mu"``), whose velocity
        (first-derivative schemes) and acceleration (second-derivative
        schemes) are compared. A derived quantity's values over each sweep
        are differenced as an unknown's are (an angle unwrapped, a full turn
        as periodic) and compared with its exact derivatives
        (:func:`numkin.expressions.derived_derivatives`); one that does not
        return to its start after the turn (``theta2/2 + theta3``) has its
        full turn studied as an open grid. Where the exact derivative is 0
        over the sweep, ``max rel error`` is blank (the caption says so).
    check_angle : float, optional
        Input angle (rad) where the error is also reported; NaN on a grid
        that does not hold it.
    grids : iterable of int
        Points per turn of the input (h = 360/N deg).
    schemes : sequence of str, optional
        Names from :data:`numkin.derivatives.SCHEMES`; default all (the
        spectral ones only on a full turn).
    start : float
        First input angle, rad.
    span : float
        Input range, rad: a full turn (periodic, default) or less (open grid).
    guess : optional
        Starting guess of the sweeps (default: the mechanism's).

    Returns
    -------
    pandas.DataFrame
        One row per scheme and grid (scheme order, then grids as given):
        ``scheme``, ``formal order``, ``quantity``, ``points per turn``,
        ``h [deg]``, ``max abs error``, ``RMS abs error`` (both ``[unit of
        quantity]``), ``max rel error [-]`` (over ``max |exact|``), all over the
        points where the scheme's own stencil applies; on an open grid
        ``ends abs error`` (the largest error of the one-sided end stencils at
        the first and last points); the abs error at the check angle, and
        ``observed order [-]``
        ``log(e_prev / e) / log(h_prev / h)`` from the max error of the row
        above (same scheme); NaN where either error is at the round-off
        floor (:data:`ROUNDOFF_UNITS` ``* eps * max|q| * |omega|^n / h^n``).

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> t = convergence_table(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                       grids=(90, 180), schemes=("forward",))
    >>> print(t["quantity"].iloc[0], round(float(t["observed order [-]"].iloc[1]), 1))
    v_x [mm/s] 1.0
    >>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
    >>> t = convergence_table(mech, omega=10.0, quantity="mu", grids=(180, 360), schemes=("centred",))
    >>> print(t["quantity"].iloc[0], round(float(t["observed order [-]"].iloc[1]), 2))
    omega_mu [rad/s] 2.0
    """
    w, studied, grid_list, periodic, scheme_list = grid_study(mechanism, omega, quantity, grids, span, schemes,
                                                              start, guess)
    lab = studied.labels
    check_col = (
        f"abs error at {lab['input']} = {deg_text(check_angle)} deg {UNIT}" if check_angle is not None else None
    )
    if check_angle is not None:
        if not (isinstance(check_angle, (int, float, np.number)) and math.isfinite(check_angle)):
            raise InputError(f"check_angle must be a finite angle in rad, got {check_angle!r}")
        if all(check_index(grid_inputs(n, start, span), check_angle) is None for n in grid_list):
            raise InputError(
                f"check_angle {math.degrees(check_angle):.6g} deg is on none of the grids {grid_list} from "
                f"{math.degrees(start):.6g} deg over {math.degrees(span):.6g} deg (angles in rad)"
            )
    data = {}
    for n in grid_list:
        s = solve_sweep(mechanism, grid_inputs(n, start, span), guess, quiet=False)
        dq, d2q = studied.exact(s, quiet=False)
        data[n] = (s, dq, d2q)
    rows = []
    at_end = set()  # schemes whose error at the check angle is their end stencil's
    floored = set()  # schemes whose error reached the round-off floor on some grid
    zero = set()  # the quantities (velocity, acceleration) whose exact value is 0 over the sweep
    warned = set()  # the differences' warnings: once per table (a wrapped angle on every grid and scheme)
    for scheme in scheme_list:
        scale = w if scheme.derivative == 1 else w * w
        prev = None
        for n in grid_list:
            s, dq, d2q = data[n]
            exact = scale * (dq if scheme.derivative == 1 else d2q)
            est = scale * warned_once(warned, studied.differenced, s, scheme, quiet=False, periodic=periodic)
            err = np.abs(est - exact)
            # statistics where the scheme's own stencil applies: one period of a periodic grid; on an
            # open grid the first and last points (one-sided end stencils) have their own column
            keep = own_stencil_points([scheme], err.size, periodic)
            inner = err[keep]
            e_max = float(np.max(inner))
            h = TURN / n
            row = {
                "scheme": scheme.name,
                "formal order": order_text(scheme),
                "quantity": lab[scheme.derivative],
                "points per turn": n,
                "h [deg]": 360.0 / n,
                f"max abs error {UNIT}": e_max,
                f"RMS abs error {UNIT}": float(np.sqrt(np.mean(inner**2))),
                "max rel error [-]": relative(e_max, exact[: err.size - 1 if periodic else None]),
            }
            if not periodic:
                ends = np.ones(err.size, dtype=bool)
                ends[keep] = False
                row[f"ends abs error {UNIT}"] = float(np.max(err[ends])) if ends.any() else math.nan
            if check_col is not None:
                k = check_index(s.inputs, check_angle)
                row[check_col] = float(err[k]) if k is not None else math.nan
                if k is not None and not periodic and not keep.start <= k < keep.stop:
                    at_end.add(scheme.name)
            # the rounding error of differencing samples known to eps |q|: about eps max|q| / h^n
            floor = ROUNDOFF_UNITS * EPS * float(np.max(np.abs(studied.values(s)))) * abs(scale) / h**scheme.derivative
            at_floor = e_max <= floor
            order = math.nan
            if prev is not None and prev[0] > 0 and e_max > 0 and not (at_floor or prev[2]):
                order = math.log(prev[0] / e_max) / math.log(prev[1] / h)
            row["observed order [-]"] = order
            if at_floor:
                floored.add(scheme.name)
            if math.isnan(row["max rel error [-]"]):
                zero.add(lab[f"name{scheme.derivative}"])
            prev = (e_max, h, at_floor)
            rows.append(row)
    import pandas as pd

    df = pd.DataFrame(rows)
    df.attrs["quantities"] = studied.quantities
    df.attrs["units"] = {"h [deg]": "deg"}  # what a figure writes on its axis
    if check_angle is not None:
        df.attrs["check"] = (mechanism.input_name, math.degrees(check_angle))  # the input's name and angle (deg)
    errors = [f"max abs error {UNIT}", f"RMS abs error {UNIT}", "max rel error [-]", f"ends abs error {UNIT}", check_col]
    set_kinds(df, {"points per turn": "count", "h [deg]": "input", **{c: "error" for c in errors if c},
                   "observed order [-]": "order"})
    ends_col = None if periodic else f"ends abs error {UNIT}"
    set_views(df, [
        ("error over the sweep", ["scheme", "formal order", "points per turn", "h [deg]",
                                  f"max abs error {UNIT}", "max rel error [-]", "observed order [-]"]),
        ("RMS error, and the error at the check angle" + ("" if periodic else " and at the ends"),
         ["scheme", "quantity", "points per turn", f"RMS abs error {UNIT}", check_col, ends_col]),
    ], row_keys=["scheme", "points per turn"])
    ends_text = "" if periodic else (
        " On this open grid the first and last points take one-sided end stencils: the max, RMS and relative "
        "errors and the observed order are over the points where each scheme's own stencil applies, and the "
        "ends' largest error is its own column"
        + (f"; the check angle is an end point for {', '.join(sorted(at_end))}, whose error there is the end "
           "stencil's" if at_end else "") + "."
    )
    closure_text = "" if periodic or not full_turn(span) else studied.closure_text(data[grid_list[0]][0])
    off_grid = [n for n in grid_list if check_angle is not None and check_index(data[n][0].inputs, check_angle) is None]
    off_text = "" if not off_grid else (
        f" The error at {lab['input']} = {deg_text(check_angle)} deg is blank on the grid(s) of "
        f"{', '.join(map(str, off_grid))} points per turn, which do not hold that angle."
    )
    floor_text = "" if not floored else (
        f" An observed order is left blank where either grid's error is at the round-off floor "
        f"({ROUNDOFF_UNITS:g} eps max|q| |omega|^n / h^n for an n-th derivative): {', '.join(sorted(floored))}."
    )
    return set_caption(
        df,
        f"Convergence: {mechanism.title}, {studied.title}, input speed {w:g} rad/s; error of each scheme "
        "against the analytic solution over the sweep; observed order from successive grids. Absolute errors "
        f"in {lab['unit1']} ({lab['name1']}, first-derivative schemes) or {lab['unit2']} ({lab['name2']}, "
        "second-derivative schemes)." + relative_text({"max rel error [-]": PEAK}) + closure_text + ends_text
        + off_text + floor_text + zero_text(zero),
        grid_positions(mechanism, {n: data[n][0] for n in grid_list}, check_angle),
    )

"""Work and run time against precision, and the cheapest method for a wanted accuracy."""

from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np

from .. import analytic
from ..errors import InputError
from ..schemes import REGISTRY, own_stencil_points
from .counting import count_evaluations, stencil_evaluations, sweep_evaluations
from .captions import PEAK, UNIT, VARIES, relative, relative_text, set_caption, set_views, zero_text
from .grids import DEFAULT_GRIDS, TURN, full_turn, grid_inputs, grid_positions, grid_study
from .study import EPS, exact_derivatives, silenced, solve_sweep
from .timing import median_time, timing_repeats

__all__ = [
    "work_precision_table",
    "cheapest_table",
    "ROUNDOFF_TIE",
]

#: Work columns of :func:`work_precision_table` (exact counts; see its docstring).
_WORK_SWEEP = "sweep work [evaluations]"
_WORK_DERIVATIVE = "derivative work [evaluations]"
_WORK = "work [evaluations]"
_PARETO_WORK = "Pareto front by work"
#: Denominator of the relative errors of :func:`work_precision_table` (and so of :func:`cheapest_table`).
_WP_DENOMINATOR = f"{PEAK} (the analytic rows: the largest |complex step| over the sweep, their reference)"
#: Total time of a row of :func:`work_precision_table`: the sum of its sweep and derivative medians.
_TIME = f"sweep + derivative time [ms] {VARIES}"


def work_precision_table(
    mechanism,
    *,
    omega,
    quantity: str,
    grids: Iterable[int] = DEFAULT_GRIDS,
    schemes: Sequence[str] | None = None,
    repeat: int | None = None,
    start: float = 0.0,
    span: float = TURN,
    guess=None,
):
    """Work and run time against error for every scheme and grid, the analytic solution and the complex step.

    Two measures of cost stand beside the error reached:

    * **work** -- exact counts, the same in every run: they depend on the
      algorithms and the data, not on the machine's speed or load.
      ``sweep work`` is the number of *point evaluations* of the
      mechanism's compiled loop equations spent by ``Mechanism.sweep``:
      evaluations of the residuals plus evaluations of the Jacobian, each
      at one input angle, as the sweep records them (``Sweep.nfev +
      Sweep.njev``; an evaluation of both together counts once in each).
      ``derivative work`` is what the derivative adds: for the analytic
      solution and the complex step, point evaluations again, as
      :mod:`numkin.analytic` records them (:func:`count_evaluations`): the
      velocity equations ``J q' = -dF/dtheta`` reuse the sweep's Jacobian
      and take dF/dtheta at every point, the acceleration equations also
      their right-hand side at every point; the complex step runs Newton in
      complex arithmetic at every point (residuals and Jacobian counted as
      in the sweep; for the second derivative also J and dF/dtheta at the
      complex solution); for a finite-difference scheme, which
      evaluates no compiled function, the *stencil evaluations*: one per
      grid point at which its formula is applied (to all unknowns at once,
      as a compiled function is). ``work`` is their sum. It tracks the run
      time because what a row costs is set by how often the loop equations
      are evaluated: the number of points, Newton iterations and linear
      solves. A stencil evaluation (a few multiply-adds) is cheaper than a
      point evaluation (trigonometric functions), so counting each as one
      overstates, if anything, the cost of the finite differences. For a
      derived quantity (:mod:`numkin.derived`) every method also evaluates
      its compiled expression once per input (its values for the
      differences; its chain rule, applied to the unknowns' rates, for the
      analytic solution and the complex step): the sweep's input count,
      added to ``derivative work`` of every row alike;
    * **run time** (only when asked for, with `repeat`) -- medians over `repeat` repeats of
      :func:`time.perf_counter` (after an untimed warm-up): the sweep, the
      derivative alone (:func:`numkin.kinematics.sweep_derivative`, or
      :func:`numkin.analytic.tangent` / :func:`~numkin.analytic.derivatives`,
      or :func:`numkin.analytic.complex_step`), and their sum, the total
      that the Pareto front by time and :func:`cheapest_table` rank on.
      These vary between runs and say so in their column names.

    Parameters
    ----------
    mechanism : Mechanism
    omega : float or str
        Input speed (rad/s or a string with units).
    quantity : str
        The unknown or derived quantity studied (see :func:`convergence_table`).
        For a derived quantity the complex-step rows are the unknowns'
        complex-step rates carried through its exact chain rule.
    grids : iterable of int
        Points per turn.
    schemes : sequence of str, optional
        Finite-difference schemes (default all applicable).
    repeat : int, optional
        Timing repeats. Default None: no timing; the table holds the exact
        work only, is the same in every run and takes a fraction of the
        time (timing calls every method many times over).
    start, span, guess
        As in :func:`convergence_table`.

    Returns
    -------
    pandas.DataFrame
        Rows: for the first derivative, then the second: ``analytic``,
        ``complex step``, then each scheme of that derivative order; each on
        every grid. Columns ``method``, ``quantity``, ``points per turn``,
        ``h [deg]``, ``sweep work [evaluations]``, ``derivative work
        [evaluations]``, ``work [evaluations]`` (their sum; integers),
        ``sweep time [ms] (varies)``, ``derivative time [ms] (varies)``,
        ``sweep + derivative time [ms] (varies)`` (the sum of the two
        medians before it), ``max abs error [unit of quantity]``, ``max rel
        error [-]`` (over the largest ``|exact value|`` over the sweep; the
        analytic rows' over the complex step's), ``Pareto front (varies)`` (no
        other row of the same quantity is both faster, by that total time, and at
        least as accurate) and ``Pareto front by work`` (the same by
        ``work``: the same in every run). The time and ``Pareto front
        (varies)`` columns are there only with `repeat`. The error of the analytic rows is
        measured against the complex step, all others against the analytic
        solution.

    Examples
    --------
    >>> from numkin import linkages
    >>> t = work_precision_table(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                          grids=(36,), schemes=("centred",))
    >>> list(t["method"])
    ['analytic', 'complex step', 'centred', 'analytic', 'complex step']
    >>> wd = t["derivative work [evaluations]"]
    >>> int(wd[0]), int(wd[2])   # analytic: dF/dtheta at the 37 inputs; centred: 36 distinct points
    (37, 36)
    """
    import pandas as pd

    w, studied, grid_list, periodic, scheme_list = grid_study(mechanism, omega, quantity, grids, span, schemes,
                                                              start, guess)
    lab = studied.labels
    repeat = timing_repeats(repeat)
    rows = []
    per_grid = {}
    zero = set()  # the quantities (velocity, acceleration) whose exact value is 0 over the sweep
    for n in grid_list:
        inputs = grid_inputs(n, start, span)

        def run_sweep(inputs=inputs):  # timed: computed each time
            return solve_sweep(mechanism, inputs, guess, shared=False)

        s = solve_sweep(mechanism, inputs, guess)
        dq, d2q = studied.exact(s)
        done = {}  # the complex step, counted once: the reference of the analytic rows and a row of its own
        h = analytic.COMPLEX_STEP
        with count_evaluations(mechanism) as cs_count:  # one complex solve serves both orders
            x, failed, _ = silenced(analytic.complex_positions, mechanism, s.values, s.inputs, h)
        solve_count = cs_count.total
        with count_evaluations(mechanism) as cs_count:
            d2 = silenced(analytic.complex_tangent, mechanism, x, s.inputs, h)
        d1 = x.imag / h
        cs1, cs2 = studied.rates(s.values, s.inputs, d1, d2)
        cs1[failed] = np.nan
        cs2[failed] = np.nan
        done[1] = (cs1, solve_count)
        done[2] = (cs2, solve_count + cs_count.total)
        t_sweep = median_time(run_sweep, repeat) if repeat else math.nan
        # a derived quantity that does not close is differenced at every sample of its open grid
        stencils = stencil_evaluations(s) if periodic or not studied.derived else int(s.inputs.size)
        per_grid[n] = (s, dq, d2q, cs1, cs2, t_sweep, sweep_evaluations(s), stencils, done)

    def analytic_rates(s, order):  # the quantity's; counted (and timed): never taken from shared results
        if order == 1:
            return studied.rates(s.values, s.inputs, silenced(analytic.tangent, s))[0]
        return studied.rates(s.values, s.inputs, *exact_derivatives(s, fresh=True))[1]

    def complex_rates(s, order):  # timed only (the rows' values are the complex step counted above)
        if not studied.derived:
            return silenced(analytic.complex_step, s, order=order)[studied.index]
        h = analytic.COMPLEX_STEP  # one complex solve serves both orders, as for the rows' values above
        x, _, _ = silenced(analytic.complex_positions, mechanism, s.values, s.inputs, h)
        d2q = silenced(analytic.complex_tangent, mechanism, x, s.inputs, h) if order == 2 else None
        return studied.rates(s.values, s.inputs, x.imag / h, d2q)[order - 1]

    def method_fns(order):  # (scheme, None for the analytic solution; its function; whether it differences samples)
        fns = [
            # counted (and timed): computed here, never taken from results shared with other tables
            (None, lambda s: analytic_rates(s, order), False),
            (REGISTRY["complex_step"], lambda s: complex_rates(s, order), False),
        ]
        for scheme in scheme_list:
            if scheme.derivative == order:
                fns.append((scheme, lambda s, sc=scheme: studied.differenced(s, sc, fresh=True, periodic=periodic),
                            True))
        return fns

    for order in (1, 2):
        scale = w if order == 1 else w * w
        for scheme, fn, differences in method_fns(order):
            name = "analytic" if scheme is None else scheme.label
            for n in grid_list:
                s, dq, d2q, cs1, cs2, t_sweep, sweep_work, stencils, done = per_grid[n]
                exact = dq if order == 1 else d2q
                if scheme is not None and scheme.kind == "complex_step":
                    out, counted = done[order]
                else:
                    with count_evaluations(mechanism) as count:
                        out = fn(s)
                    counted = count.total
                derivative_work = counted + (stencils if differences else 0) + studied.work(s)
                if scheme is None:
                    est, ref = exact, (cs1 if order == 1 else cs2)
                else:
                    est, ref = out, exact
                err = abs(scale) * np.abs(est - ref)  # the input may turn either way: omega < 0
                # one period; on an open grid the points where a scheme's own stencil applies (as the
                # convergence table), the one-sided ends apart; every point for the exact methods
                own = own_stencil_points([scheme], err.size, periodic) if differences else (
                    slice(0, err.size - 1) if periodic else slice(None))
                e_max = float(np.max(err[own]))
                row = {
                    "method": name,
                    "quantity": lab[order],
                    "points per turn": n,
                    "h [deg]": 360.0 / n,
                    _WORK_SWEEP: int(sweep_work),
                    _WORK_DERIVATIVE: int(derivative_work),
                    _WORK: int(sweep_work + derivative_work),
                }
                if repeat:
                    t_diff = median_time(lambda fn=fn, s=s: fn(s), repeat)
                    row[f"sweep time [ms] {VARIES}"] = 1e3 * t_sweep
                    row[f"derivative time [ms] {VARIES}"] = 1e3 * t_diff
                    # the sum of the two medians: the cost of the row, and what the front and the cheapest rank on
                    row[_TIME] = row[f"sweep time [ms] {VARIES}"] + row[f"derivative time [ms] {VARIES}"]
                row[f"max abs error {UNIT}"] = e_max
                row["max rel error [-]"] = relative(e_max, scale * ref)
                if math.isnan(row["max rel error [-]"]):
                    zero.add(lab[f"name{order}"])
                rows.append(row)
    df = pd.DataFrame(rows)
    df.attrs["quantities"] = studied.quantities
    df.attrs["units"] = {c: "ms" for c in df.columns if " time [ms] " in c} | {"h [deg]": "deg"}
    if repeat:
        df[f"Pareto front {VARIES}"] = _pareto(df, _TIME)
    df[_PARETO_WORK] = _pareto(df, _WORK)
    key = ["method", "quantity", "points per turn"]
    set_views(df, [
        ("error against work", key + [_WORK, f"max abs error {UNIT}", "max rel error [-]", _PARETO_WORK]),
        ("where the work goes", key + ["h [deg]", _WORK_SWEEP, _WORK_DERIVATIVE]),
        ("run time (varies between runs)", key + [
            f"sweep time [ms] {VARIES}", f"derivative time [ms] {VARIES}", _TIME, f"Pareto front {VARIES}"]),
    ], row_keys=key)
    timing = (f"; median times of {int(repeat)} repeats of the sweep and of the derivative (vary between runs), "
              "the sweep + derivative time their sum, on which the Pareto front by time ranks" if repeat
              else "; not timed (pass repeat to time each row)")
    return set_caption(
        df,
        f"Work and precision: {mechanism.title}, {studied.title}, input speed {w:g} rad/s; work = point evaluations of "
        "the compiled loop equations (sweep, analytic and complex-step derivatives) plus stencil evaluations "
        f"(finite differences), exact and the same in every run{timing}; beside the max error over the sweep, "
        "against the analytic solution, the analytic rows' against the complex step (the two rows show their "
        "difference, both exact to round-off)"
        + ("" if periodic else "; on this open grid a scheme's error is over the points where its own stencil "
           "applies (the one-sided end stencils at the first and last points apart, as in the convergence table)")
        + "." + relative_text({"max rel error [-]": _WP_DENOMINATOR})
        + ("" if periodic or not full_turn(span) else studied.closure_text(per_grid[grid_list[0]][0]))
        + zero_text(zero),
        grid_positions(mechanism, {n: per_grid[n][0] for n in grid_list}, None),
    )


#: Relative errors closer than this are equal on a Pareto front: differences of round-off.
ROUNDOFF_TIE = 64 * EPS


def _pareto(df, cost: str) -> list:
    """Rows on the Pareto front (`cost` column, max rel error) within their quantity.

    A row is on the front if no other row of its quantity costs no more and
    is no less accurate, and is strictly better in one of the two; relative
    errors that differ by less than :data:`ROUNDOFF_TIE` are equal (two
    methods exact to round-off are not told apart by the last digits of
    their errors). Rows without a finite cost and error are not on it.
    """
    t = df[cost].to_numpy(dtype=float)
    e = df["max rel error [-]"].to_numpy(dtype=float)
    q = df["quantity"].to_numpy()
    ok = np.isfinite(t) & np.isfinite(e)
    out = []
    for k in range(len(df)):
        if not ok[k]:
            out.append(False)
            continue
        same = (q == q[k]) & ok
        no_worse, better = e <= e[k] + ROUNDOFF_TIE, e < e[k] - ROUNDOFF_TIE
        dominated = same & (t <= t[k]) & no_worse & ((t < t[k]) | better)
        out.append(not bool(dominated.any()))
    return out


def cheapest_table(work_precision, targets: Sequence[float] = (1e-2, 1e-4, 1e-6, 1e-8, 1e-10), *, by: str = "time"):
    """The cheapest method reaching each wanted max relative error: by total run time or by work.

    Parameters
    ----------
    work_precision : pandas.DataFrame
        A table from :func:`work_precision_table`.
    targets : sequence of float
        Wanted max relative errors.
    by : {"time", "work"}
        ``"time"``: the fastest by ``sweep + derivative time`` (the sum of
        the measured sweep and derivative medians, so the choice varies
        between runs). ``"work"``: the least ``work
        [evaluations]`` (exact: the same in every run); among equal work
        the more accurate.

    Returns
    -------
    pandas.DataFrame
        One row per quantity and target: ``quantity``, ``wanted max rel
        error [-]``, and the choice: with ``by="time"`` ``cheapest method
        (varies)``, ``points per turn (varies)``, ``time [ms] (varies)``,
        ``max rel error [-] (varies)``; with ``by="work"`` ``cheapest
        method``, ``points per turn``, ``work [evaluations]``, ``max rel
        error [-]``. The method is ``"none"`` (and the rest blank) if no
        row reaches the target.

    Examples
    --------
    >>> import pandas as pd
    >>> wp = pd.DataFrame({"method": ["centred", "analytic"], "quantity": ["omega_b [rad/s]"] * 2,
    ...                    "points per turn": [36, 36], "sweep + derivative time [ms] (varies)": [1.0, 2.0],
    ...                    "work [evaluations]": [180, 218], "max rel error [-]": [1e-3, 1e-15]})
    >>> list(cheapest_table(wp, targets=(1e-2, 1e-6))["cheapest method (varies)"])
    ['centred', 'analytic']
    >>> list(cheapest_table(wp, targets=(1e-2, 1e-6), by="work")["work [evaluations]"])
    [180.0, 218.0]
    """
    import pandas as pd

    if by == "time":
        cost, tag = _TIME, f" {VARIES}"
        names = (f"cheapest method{tag}", f"points per turn{tag}", f"time [ms]{tag}", f"max rel error [-]{tag}")
        caption = "Cheapest method for a wanted accuracy (chosen by timings: varies between runs)."
    elif by == "work":
        cost = _WORK
        names = ("cheapest method", "points per turn", _WORK, "max rel error [-]")
        caption = ("Cheapest method for a wanted accuracy, by work (point evaluations of the compiled loop "
                   "equations plus stencil evaluations: the same in every run).")
    else:
        raise InputError(f"by must be 'time' or 'work', got {by!r}")
    caption += relative_text({names[3]: _WP_DENOMINATOR, "wanted max rel error [-]": _WP_DENOMINATOR})
    if cost not in work_precision.columns:
        raise InputError(f"work_precision table has no column {cost!r}; columns are {list(work_precision.columns)}")
    err = "max rel error [-]"
    rows = []
    for quantity in dict.fromkeys(work_precision["quantity"]):
        sub = work_precision[work_precision["quantity"] == quantity]
        for target in targets:
            ok = sub[(sub[err] <= target) & np.isfinite(sub[cost].to_numpy(dtype=float))]
            if len(ok):
                best = ok.sort_values([cost, err], kind="mergesort").iloc[0]
                method, n = best["method"], float(best["points per turn"])
                c, e = float(best[cost]), float(best[err])
            else:
                method, n, c, e = "none", math.nan, math.nan, math.nan
            rows.append(
                {"quantity": quantity, "wanted max rel error [-]": float(target),
                 names[0]: method, names[1]: n, names[2]: c, names[3]: e}
            )
    df = pd.DataFrame(rows)
    if work_precision.attrs.get("quantities"):
        df.attrs["quantities"] = dict(work_precision.attrs["quantities"])
    return set_caption(df, caption)

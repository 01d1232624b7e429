"""Newton tables: norms per iteration of one solve, and the choice of Jacobian."""

from __future__ import annotations

import math

import numpy as np

from ..column_kinds import set_kinds
from .captions import VARIES, deg_text, set_caption, set_views
from .grids import TURN, grid_inputs
from .study import branch_point, position_record, solve_sweep
from .timing import median_time, timing_repeats

__all__ = [
    "newton_table",
    "jacobian_table",
]


def _solve_points(mechanism, check_angle, start_offset, guess, start) -> tuple:
    """``(x_start, x_star)``: the sweep's positions at ``check_angle - start_offset`` and at `check_angle`.

    Both on the branch of the sweep from `start` (where `guess` applies),
    by numkin's Newton: the starting point of one Newton solve
    and the solution it should reach.
    """
    x_start = branch_point(mechanism, check_angle - start_offset, guess, start).values[:, 0]
    x_star = branch_point(mechanism, check_angle, guess, start).values[:, 0]
    return x_start, x_star


def _solve_positions(mechanism, check_angle, start_offset, x_start, solves) -> list:
    """``attrs["positions"]`` of a table of Newton solves: the start, then each solve's result."""
    out = [position_record("start of the solve", mechanism, check_angle - start_offset, x_start)]
    out += [position_record(f"{what} solve", mechanism, check_angle, x) for what, x in solves]
    return out


def _error_orders(errors: np.ndarray, floor: float = 1e-14) -> np.ndarray:
    """p_k = log(e_k / e_{k-1}) / log(e_{k-1} / e_{k-2}) where all three are above `floor`."""
    out = np.full(errors.size, np.nan)
    for k in range(2, errors.size):
        a, b, c = errors[k - 2], errors[k - 1], errors[k]
        if min(a, b, c) > floor and a != b:
            out[k] = math.log(c / b) / math.log(b / a)
    return out


def _step_orders(steps: np.ndarray, floor: float = 1e-14) -> np.ndarray:
    """The same estimate from step norms; entry k uses steps k-2, k-1, k (step k leads to iterate k)."""
    out = np.full(steps.size + 1, np.nan)
    for k in range(3, steps.size + 1):
        a, b, c = steps[k - 3], steps[k - 2], steps[k - 1]
        if min(a, b, c) > floor and a != b:
            out[k] = math.log(c / b) / math.log(b / a)
    return out


def _one_solve(mechanism, check_angle, x_start, jacobian, tol=1e-12, maxiter=50):
    """A solve and its iterates: (NewtonResult, iterates (n, k+1)), as the solve recorded them."""
    res = mechanism.solve(check_angle, x_start, jacobian=jacobian, tol=tol, maxiter=maxiter)
    return res, np.asarray(res.iterates, dtype=float).T


def newton_table(
    mechanism,
    *,
    check_angle: float,
    start_offset: float = math.radians(20.0),
    jacobian: str = "symbolic",
    tol: float = 1e-12,
    guess=None,
    start: float = 0.0,
):
    """Residual, step and error norms per Newton iteration of one solve, with the order of convergence.

    The solve is :meth:`Mechanism.solve` at `check_angle`, started from the
    solution at ``check_angle - start_offset`` (as a continuation without
    predictor would). Both that solution and the reference the errors are
    measured against (brought to the last digits by one more Newton solve) are the sweep's,
    continued from `start` where `guess` applies. All norms are scaled max-norms (lengths divided by
    the mechanism's length scale, angles in rad).

    Parameters
    ----------
    mechanism : Mechanism
    check_angle : float
        Input angle of the solve, rad.
    start_offset : float
        How far back (rad) the starting guess was solved.
    jacobian : {"symbolic", "forward", "central"}
    tol : float
        numkin's stopping tolerance.
    guess : optional
        Starting guess at `start` (default: the mechanism's); picks the branch.
    start : float
        Input (rad) where the sweep to the solve's inputs starts.

    Returns
    -------
    pandas.DataFrame
        One row per iterate k = 0 ... (the start, then after each step):
        ``iteration``, ``residual norm [-]``, ``step norm [-]`` (of the step
        that led to iterate k), ``error norm [-]``, ``order estimate from
        errors [-]`` ``log(e_k/e_{k-1}) / log(e_{k-1}/e_{k-2})`` and ``order
        estimate from steps [-]`` (the same from step norms, as
        :meth:`NewtonResult.convergence_order`); NaN where the norms are at
        round-off (< 1e-14) or too few. ``attrs["positions"]`` holds the
        starting point and the solve's result.

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> t = newton_table(linkages.four_bar(4, 1, 3, 3), check_angle=math.radians(90))
    >>> bool(t["error norm [-]"].iloc[-1] < 1e-14)
    True
    """
    import pandas as pd

    x_start, x_star = _solve_points(mechanism, check_angle, start_offset, guess, start)
    res, iterates = _one_solve(mechanism, check_angle, x_start, jacobian, tol)
    errors = np.max(np.abs(iterates - x_star[:, None]) / mechanism.xscale[:, None], axis=0)
    steps = np.asarray(res.step_norms, dtype=float)
    k = np.arange(res.iterations + 1)
    df = pd.DataFrame(
        {
            "iteration": k,
            "residual norm [-]": np.asarray(res.residual_norms, dtype=float)[: k.size],
            "step norm [-]": np.concatenate([[math.nan], steps[: k.size - 1]]),
            "error norm [-]": errors,
            "order estimate from errors [-]": _error_orders(errors),
            "order estimate from steps [-]": _step_orders(steps[: k.size - 1]),
        }
    )
    set_kinds(df, {"iteration": "count", "residual norm [-]": "error", "step norm [-]": "error",
                   "error norm [-]": "error", "order estimate from errors [-]": "order",
                   "order estimate from steps [-]": "order"})
    df.attrs["jacobian"] = jacobian
    df.attrs["check"] = (mechanism.input_name, math.degrees(check_angle))  # the input's name and angle (deg)
    return set_caption(
        df,
        f"Newton iterations: {mechanism.title} at {mechanism.input_name} = {deg_text(check_angle)} deg, "
        f"{jacobian} Jacobian, started from the solution at {deg_text(check_angle - start_offset)} deg "
        f"({res.message}).",
        _solve_positions(mechanism, check_angle, start_offset, x_start, [(jacobian, res.x)]),
    )


def jacobian_table(
    mechanism,
    *,
    check_angle: float,
    points_per_turn: int = 360,
    repeat: int | None = None,
    start_offset: float = math.radians(20.0),
    start: float = 0.0,
    span: float = TURN,
    guess=None,
):
    """Symbolic against forward and central finite-difference Jacobians in Newton.

    For each Jacobian: one solve at `check_angle` from the solution at
    ``check_angle - start_offset`` (iterations, last order estimate, final
    residual and error), and a sweep on a `points_per_turn` grid (median
    time, total Newton iterations, largest difference from the sweep with
    the symbolic Jacobian).

    Parameters
    ----------
    mechanism : Mechanism
    check_angle : float
        Input angle of the single solve, rad.
    points_per_turn : int
        Points per turn of the sweep.
    repeat : int, optional
        Timing repeats of the sweep time; default None: not timed (the
        column is left out), so the table is the same in every run.
    start_offset, start, span, guess
        As in :func:`newton_table` and :func:`convergence_table`.

    Returns
    -------
    pandas.DataFrame
        Rows ``symbolic``, ``forward``, ``central``; columns ``Jacobian``,
        ``iterations (one solve)``, ``order estimate, last (one solve) [-]``,
        ``final residual (one solve) [-]``, ``final error (one solve) [-]``,
        ``sweep time [ms] (varies)`` (only with `repeat`), ``Newton iterations (sweep total)``,
        ``max difference from symbolic sweep [-]`` (scaled max-norm).

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> t = jacobian_table(linkages.four_bar(4, 1, 3, 3), check_angle=math.radians(90), points_per_turn=36)
    >>> list(t["Jacobian"])
    ['symbolic', 'forward', 'central']
    """
    import pandas as pd

    repeat = timing_repeats(repeat)
    x_start, x_star = _solve_points(mechanism, check_angle, start_offset, guess, start)
    inputs = grid_inputs(points_per_turn, start, span)
    ref = None
    rows = []
    solved = []
    for jac in ("symbolic", "forward", "central"):
        res, iterates = _one_solve(mechanism, check_angle, x_start, jac)
        solved.append((jac, res.x))
        errors = np.max(np.abs(iterates - x_star[:, None]) / mechanism.xscale[:, None], axis=0)
        orders = _error_orders(errors)
        finite = orders[np.isfinite(orders)]

        def run(jac=jac):
            return solve_sweep(mechanism, inputs, guess, jacobian=jac, shared=False)  # timed: computed each time

        # the symbolic Jacobian is the sweep's default: the sweep the other tables of a report share
        s = solve_sweep(mechanism, inputs, guess, **({} if jac == "symbolic" else {"jacobian": jac}))
        if ref is None:
            ref = s.values
        rows.append(
            {
                "Jacobian": jac,
                "iterations (one solve)": res.iterations,
                "order estimate, last (one solve) [-]": float(finite[-1]) if finite.size else math.nan,
                "final residual (one solve) [-]": float(res.residual_norms[-1]),
                "final error (one solve) [-]": float(errors[-1]),
                **({f"sweep time [ms] {VARIES}": 1e3 * median_time(run, repeat)} if repeat else {}),
                "Newton iterations (sweep total)": int(np.sum(s.iterations)),
                "max difference from symbolic sweep [-]": float(
                    np.max(np.abs(s.values - ref) / mechanism.xscale[:, None])
                ),
            }
        )
    df = pd.DataFrame(rows)
    df.attrs["check"] = (mechanism.input_name, math.degrees(check_angle))  # the input's name and angle (deg)
    set_kinds(df, {
        "iterations (one solve)": "count", "order estimate, last (one solve) [-]": "order",
        "final residual (one solve) [-]": "error", "final error (one solve) [-]": "error",
        f"sweep time [ms] {VARIES}": "error", "Newton iterations (sweep total)": "count",
        "max difference from symbolic sweep [-]": "error",
    })
    set_views(df, [
        ("one solve", ["Jacobian", "iterations (one solve)", "order estimate, last (one solve) [-]",
                       "final residual (one solve) [-]", "final error (one solve) [-]"]),
        ("a sweep", ["Jacobian", f"sweep time [ms] {VARIES}", "Newton iterations (sweep total)",
                     "max difference from symbolic sweep [-]"]),
    ], row_keys=["Jacobian"])
    return set_caption(
        df,
        f"Jacobian choice: {mechanism.title}; one solve at {deg_text(check_angle)} deg and a sweep of "
        f"{int(points_per_turn)} points per turn" + (" (times vary between runs)." if repeat else "."),
        _solve_positions(mechanism, check_angle, start_offset, x_start, solved),
    )

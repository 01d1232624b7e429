"""The tolerance table: what loose Newton stopping rules do to differenced velocity and acceleration."""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..column_kinds import set_kinds
from ..derivatives import get_scheme
from ..errors import InputError, NumkinError
from ..newton_rules import check_tol
from ..schemes import own_stencil_points
from ..sweep import Sweep
from .captions import PEAK, at_angle, deg_text, relative, relative_text, set_caption, set_views, zero_text
from .grids import TURN, check_index, full_turn, grid_inputs
from .study import input_speed, position_record, solve_sweep
from .studied import studied_quantity

__all__ = [
    "STUDENT_RULES",
    "student_sweep",
    "tolerance_table",
]

#: Stopping rules of :func:`student_sweep`: absolute step, relative step (loop by loop), residual.
STUDENT_RULES = ("step", "relative", "residual")


def student_sweep(
    mechanism,
    inputs,
    *,
    rule: str = "step",
    tol: float = 1e-4,
    guess=None,
    maxiter: int = 100,
) -> Sweep:
    """A sweep solved "as students do it": plain Newton from the previous solution, a loose stopping rule.

    This is a teaching device for :func:`tolerance_table`, not a solver to
    use. It reproduces the loops of the source documents: at each input,
    Newton-Raphson with the symbolic Jacobian starts from the solution at
    the previous input (from `guess` at the first) and stops by one rule
    only:

    * ``rule="step"``: the absolute step rule, after a step ``dx`` with
      ``||dx||_2 < tol`` (in rad and length units, unscaled), as in report
      001;
    * ``rule="relative"``: the relative step rule of homework 003, after a
      step with ``||dx||_2 / ||x + dx||_2 < tol``, applied as the homework
      does it: loop by loop (each loop's unknowns by Newton on its own
      equations, the earlier loops' unknowns held), from the previous
      solution as it stands. ``||x||`` counts every turn the angles have
      wandered through (a first Newton from a far guess can leave them
      hundreds of rad from [0, 2 pi)), and the larger it is, the looser the
      rule: on the homework it stops after one step per point on linkage 1
      and two on linkage 2;
    * ``rule="residual"``: the residual rule, as soon as ``max|F| < tol``
      (length units, unscaled), checked before each step.

    No predictor, no check of the branch, no scaling: what numkin's sweep
    (:mod:`numkin.sweep`, :mod:`numkin.newton`) does differently.

    Parameters
    ----------
    mechanism : Mechanism
    inputs : array_like
        Input angles, rad.
    rule : {"step", "relative", "residual"}
    tol : float
    guess : optional
        Starting guess at ``inputs[0]`` (default: the mechanism's default
        guess, taken as given, at ``inputs[0]``).
    maxiter : int
        Newton steps allowed per input before a RuntimeError.

    Returns
    -------
    Sweep
        With ``iterations`` the Newton steps per point, ``residual`` and
        ``cond`` as in numkin's sweeps, and ``jacobian`` set to
        ``"student <rule> rule"``.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> s = student_sweep(linkages.four_bar(4, 1, 3, 3), np.radians([0.0, 1.0, 2.0]), rule="step")
    >>> np.round(np.degrees(s["theta4"]), 4)
    array([120.    , 119.6689, 119.3426])
    """
    if rule not in STUDENT_RULES:
        raise InputError(f"rule must be one of {list(STUDENT_RULES)}, got {rule!r}")
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
        raise InputError(f"tol must be a positive number, got {tol!r}")
    t = np.atleast_1d(np.asarray(inputs, dtype=float))
    comp, p = mechanism.compiled, mechanism.parameter_values
    g = mechanism.default_guess if guess is None else guess
    x = mechanism.guess_vector(g, float(t[0])).copy()
    n, N = x.size, t.size
    blocks = list(mechanism.loop_slices) if rule == "relative" else [slice(0, n)]
    values = np.empty((n, N))
    iters = np.zeros(N, dtype=int)
    for k in range(N):
        tk = t[k : k + 1]
        for block in blocks:
            steps = _student_newton(comp, p, x, tk, block, rule, tol, maxiter)
            if steps is None:
                raise RuntimeError(
                    f"{mechanism.name}: the {rule} rule was not met after {maxiter} Newton steps at input "
                    f"{math.degrees(t[k]):.3f} deg"
                )
            iters[k] += steps
        values[:, k] = x
    residual = np.max(np.stack(list(mechanism.loop_residuals(values, t).values())), axis=0)
    cond = np.max(np.stack(list(mechanism.loop_conditions(values, t).values())), axis=0)
    return Sweep(mechanism, t, values, iters, residual, cond, [], f"student {rule} rule", float(tol))


def _student_newton(comp, p, x, tk, block: slice, rule: str, tol: float, maxiter: int) -> int | None:
    """Newton on the unknowns `block` of `x` (updated in place) at input `tk` until `rule` holds.

    Residuals and Jacobian at the one point come from the mechanism's
    one-point kernel (``scalar_FJT``, floats, as the sweep's own Newton
    evaluates them), or from the array kernels where a value is undefined
    there (NaN, as the array kernels give it, instead of an exception).

    Returns the number of steps taken, or None if `maxiter` steps did not
    meet the rule.
    """
    from ..compiled import MATH_ERRORS

    n = x.size
    point, t, pt = comp.scalar_FJT, float(tk[0]), tuple(np.asarray(p, dtype=float).tolist())
    for it in range(maxiter + 1):
        try:
            v = np.array(point(*x.tolist(), t, *pt)[: n + n * n], dtype=float)
            f, jac = v[:n], v[n:].reshape(n, n)
        except MATH_ERRORS:
            f, jac = comp.F(x[:, None], tk, p)[:, 0], None
        if rule == "residual" and np.max(np.abs(f)) < tol:
            return it
        if it == maxiter:
            return None
        if jac is None:
            jac = comp.J(x[:, None], tk, p)[0]
        dx = np.linalg.solve(jac[block, block], -f[block])
        x[block] += dx
        size = np.linalg.norm(dx)
        if rule == "relative":
            size /= np.linalg.norm(x[block])
        if rule != "residual" and size < tol:
            return it + 1
    return None  # pragma: no cover - the loop returns at it == maxiter


def _percent(value, exact, exact_all) -> float:
    """``100 |value - exact| / |exact|``; NaN where the exact value is zero (below 1e-12 of its peak)."""
    if not abs(exact) > 1e-12 * float(np.max(np.abs(exact_all))):
        return math.nan
    return 100.0 * float(abs(value - exact) / abs(exact))


#: Short names of the rules (the ``rule`` column of :func:`tolerance_table`).
_SHORT = {"step": "absolute step (report 001)", "relative": "relative step (homework 003)", "residual": "residual"}

#: Row labels of :func:`tolerance_table` for the rules of :func:`student_sweep`.
_RULE_LABELS = {
    "step": "absolute step rule ||dx||_2 < tol, Newton from the previous solution (as in report 001)",
    "relative": ("relative step rule ||dx||_2 / ||x||_2 < tol (x after the step), loop by loop, Newton from the "
                 "previous solution (as in homework 003)"),
    "residual": "residual rule max|F| < tol, Newton from the previous solution",
}


def tolerance_table(
    mechanism,
    *,
    omega,
    quantity: str,
    check_angle: float,
    points_per_turn: int = 360,
    loose_tol: float = 1e-4,
    method: str = "centred",
    second_method: str = "second_difference",
    start: float = 0.0,
    guess=None,
    span: float = TURN,
):
    """What a loose stopping rule does to differenced velocity and acceleration.

    The sweep (`points_per_turn` to a turn, over `span`) is solved five ways: by
    :func:`student_sweep` at `loose_tol` with the absolute step rule (as in
    report 001), the relative step rule (as in homework 003) and the
    residual rule, and by numkin's own sweep at `loose_tol` and at its
    default 1e-12. Each is differenced with `method`
    (omega) and `second_method` (alpha) and compared with the analytic
    values of the tight sweep. A rule that stops while the position is still
    off by e leaves an error ~e/h in omega and ~e/h**2 in alpha: negligible
    in the position, visible in alpha.

    Parameters
    ----------
    mechanism : Mechanism
    omega : float or str
        Input speed.
    quantity : str
        The unknown, or derived quantity (:mod:`numkin.derived`), studied:
        a derived quantity's values on each solve's sweep are differenced.
    check_angle : float
        Input angle (rad) of the point values; must be on the grid.
    points_per_turn : int
        Points per turn of the grid.
    loose_tol : float
        Tolerance of the loose rules.
    method, second_method : str
        Finite-difference schemes for omega and alpha.
    start, guess
        First input (rad) and starting guess.
    span : float
        Input range swept, rad: a full turn (default) or less.

    Returns
    -------
    pandas.DataFrame
        Rows: the analytic reference, then the five solves. Columns
        ``rule`` (a short name), ``stopping rule`` (in full), ``tol`` (in the rule's own terms), ``Newton iterations per point
        (mean)``, ``max |F| [length unit]``, ``<quantity> error estimate
        max|J^-1 F| [unit]`` (the studied unknown's Newton step still
        missing; for a derived quantity q, ``q error estimate max|q(x + dx)
        - q(x)|, dx = -J^-1 F [unit]``: the change of its value that step
        would make), the velocity and acceleration at the check angle
        with their relative errors [%] (over ``|exact|`` at the check angle;
        blank where the exact value is 0),
        their largest relative errors over
        the sweep [%] (over ``max |exact|``; blank where the exact values are
        all 0) and where the acceleration error is
        largest [deg], and ``note`` (a branch change is named there). A
        derived quantity that does not return to its start after a full
        turn is differenced as an open grid on every row (decided on the
        tight sweep).

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> t = tolerance_table(linkages.chained_four_bars(), omega="450 rad/min", quantity="beta",
    ...                     check_angle=math.radians(100))
    >>> print(round(float(t["alpha_beta at theta = 100 deg [rad/s^2]"].iloc[0]), 4))   # exact
    -28.375
    """
    import pandas as pd

    w = input_speed(omega)
    studied = studied_quantity(mechanism, quantity)
    lab = studied.labels
    loose_tol = check_tol(loose_tol, "loose_tol")
    s1, s2 = get_scheme(method), get_scheme(second_method)
    if s1.derivative != 1 or s2.derivative != 2:
        raise InputError("method must be a first-derivative scheme and second_method a second-derivative one")
    inputs = grid_inputs(points_per_turn, start, span)
    k = check_index(inputs, check_angle)
    if k is None:
        raise InputError(
            f"check_angle {math.degrees(check_angle):.6g} deg is not on the {points_per_turn}-point grid from "
            f"{math.degrees(start):.6g} deg"
        )
    ref = solve_sweep(mechanism, inputs, guess, quiet=False)
    dq, d2q = studied.exact(ref, quiet=False)
    w_ex, a_ex = w * dq, w * w * d2q
    deg = deg_text(check_angle)
    at = f"at {lab['input']} = {deg} deg"
    cols = {
        "w": f"{lab['name1']} {at} [{lab['unit1']}]",
        "we": f"{lab['name1']} rel error {at} [%]",
        "a": f"{lab['name2']} {at} [{lab['unit2']}]",
        "ae": f"{lab['name2']} rel error {at} [%]",
        "wm": f"{lab['name1']} max rel error [%]",
        "am": f"{lab['name2']} max rel error [%]",
        "where": f"{lab['name2']} largest error at {lab['input']} [deg]",
        # the Newton step still missing, dx = -J^-1 F: its own row for an unknown; what it changes for a derived quantity
        "est": (f"{quantity} error estimate max|{quantity}(x + dx) - {quantity}(x)|, dx = -J^-1 F [{lab['unit']}]"
                if studied.derived else f"{quantity} error estimate max|J^-1 F| [{lab['unit']}]"),
    }
    lu = mechanism.length_unit
    rows = [
        {
            "rule": "analytic",
            "stopping rule": "analytic (reference, on the tol = 1e-12 sweep)",
            "tol": math.nan,
            "Newton iterations per point (mean)": math.nan,
            f"max |F| [{lu}]": math.nan,
            cols["est"]: math.nan,
            cols["w"]: float(w_ex[k]),
            cols["we"]: 0.0,
            cols["a"]: float(a_ex[k]),
            cols["ae"]: 0.0,
            cols["wm"]: 0.0,
            cols["am"]: 0.0 if np.any(a_ex != 0) else math.nan,
            cols["where"]: math.nan,
            "note": "",
        }
    ]
    solves = [
        (_SHORT[rule], _RULE_LABELS[rule], loose_tol,
         lambda rule=rule: student_sweep(mechanism, inputs, rule=rule, tol=loose_tol, guess=guess))
        for rule in STUDENT_RULES
    ] + [
        (f"numkin, tol = {loose_tol:g}", f"numkin sweep, tol = {loose_tol:g}: scaled residual <= tol, step <= tol^(2/3) = {loose_tol ** (2 / 3):.3g} "
         "(passes at once: in effect a residual rule)", loose_tol,
         lambda: solve_sweep(mechanism, inputs, guess, tol=loose_tol)),
        ("numkin, tol = 1e-12", "numkin sweep, tol = 1e-12 (default)", 1e-12, lambda: ref),
    ]
    comp, p = mechanism.compiled, mechanism.parameter_values
    angle_rows = np.array([u in mechanism.angles for u in mechanism.unknowns])
    # the largest errors where each scheme's own stencil applies (one period; an open grid's ends apart)
    # a derived quantity that does not return to its start after the turn: an open grid (decided on the tight sweep)
    periodic = full_turn(span) and studied.closes(ref)
    gap = studied.closure_gap(ref) if periodic else 0.0  # a derived quantity's own, measured on the tight sweep
    keep1, keep2 = (own_stencil_points([s], inputs.size, periodic) for s in (s1, s2))
    ends = [] if periodic else [s.name for s, keep in ((s1, keep1), (s2, keep2)) if not keep.start <= k < keep.stop]
    positions = []
    for short, label, tol, solve in solves:
        try:
            s = solve()
        except (RuntimeError, ValueError, NumkinError) as exc:  # a loose solver that fails is a result too
            rows.append({**{c: math.nan for c in rows[0]}, "rule": short, "stopping rule": label, "tol": float(tol),
                         "note": f"failed: {exc}"})
            continue
        positions.append(position_record(label, mechanism, inputs[k], s.values[:, k]))
        diff = s.values - ref.values
        diff[angle_rows] = np.remainder(diff[angle_rows] + math.pi, TURN) - math.pi
        scaled = np.max(np.abs(diff) / mechanism.xscale[:, None], axis=0)
        note = ""
        jumped = np.flatnonzero(scaled > 1e-2)
        if jumped.size:
            note = (
                f"left the branch of the reference sweep at {lab['input']} = "
                f"{math.degrees(inputs[jumped[0]]):.6g} deg: these errors are a branch change"
            )
        f = comp.F(s.values, inputs, p)
        step = np.linalg.solve(comp.J(s.values, inputs, p), -f.T[..., None])[..., 0].T
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                # periodic: every row alike, a loose sweep's end mismatch is its position error
                d1 = w * studied.differenced(s, s1, close=periodic, periodic=periodic, gap=gap)
                d2 = w * w * studied.differenced(s, s2, close=periodic, periodic=periodic, gap=gap)
            except ValueError as exc:  # e.g. a student sweep that cannot be differenced
                d1 = d2 = np.full(inputs.size, math.nan)
                note = (note + "; " if note else "") + f"not differenced: {exc}"
        e1, e2 = np.abs(d1 - w_ex)[keep1], np.abs(d2 - a_ex)[keep2]
        rows.append(
            {
                "rule": short,
                "stopping rule": label,
                "tol": float(tol),
                "Newton iterations per point (mean)": float(np.mean(s.iterations)),
                f"max |F| [{lu}]": float(np.max(np.abs(f))),
                cols["est"]: _missing(studied, s, step),
                cols["w"]: float(d1[k]),
                cols["we"]: _percent(d1[k], w_ex[k], w_ex),
                cols["a"]: float(d2[k]),
                cols["ae"]: _percent(d2[k], a_ex[k], a_ex),
                cols["wm"]: 100.0 * relative(float(np.max(e1)), w_ex),
                cols["am"]: 100.0 * relative(float(np.max(e2)), a_ex),
                cols["where"]: (
                    math.degrees(float(inputs[keep2][int(np.nanargmax(e2))])) if np.any(np.isfinite(e2)) else math.nan
                ),
                "note": note,
            }
        )
    df = pd.DataFrame(rows)
    df.attrs["quantities"] = studied.quantities
    df.attrs["check"] = (mechanism.input_name, math.degrees(check_angle))  # the input's name and angle (deg)
    set_kinds(df, {
        "tol": "input", "Newton iterations per point (mean)": "mean", f"max |F| [{lu}]": "error", cols["est"]: "error",
        cols["w"]: "value", cols["a"]: "value", **{cols[k]: "error" for k in ("we", "ae", "wm", "am")},
        cols["where"]: "input",  # the input angle of the largest error
    })
    set_views(df, [
        ("the stopping rules", ["rule", "stopping rule", "tol"]),
        ("what each leaves in the positions", ["rule", "Newton iterations per point (mean)", f"max |F| [{lu}]",
                                               cols["est"], "note"]),
        (f"velocity and acceleration {at}", ["rule", cols["w"], cols["we"], cols["a"], cols["ae"]]),
        ("largest errors over the sweep", ["rule", cols["wm"], cols["am"], cols["where"]]),
    ], row_keys=["rule"])
    return set_caption(
        df,
        f"Solver tolerance: {mechanism.title}, {studied.title}, {int(points_per_turn)} points per turn"
        + ("" if full_turn(span) else f" over {math.degrees(span):g} deg from {math.degrees(start):g} deg")
        + f", input speed {w:g} rad/s; "
        f"{lab['name1']} by {s1.name}, {lab['name2']} by {s2.name}, against the analytic values"
        + ("; a full turn is differenced as periodic, a loosely solved sweep too (its end misses its start "
           "by its position error)" if periodic else
           "; largest errors over the points where each scheme's own stencil applies (one-sided end stencils "
           "at the first and last points)")
        + ("" if periodic or not full_turn(span) else ";" + studied.closure_text(ref)[:-1])
        + (f"; at the check angle, an end point, {' and '.join(ends)} use the one-sided end stencil" if ends else "")
        + "." + relative_text({cols["wm"]: PEAK, cols["am"]: PEAK, cols["we"]: at_angle(f"{lab['input']} = {deg} deg"),
                               cols["ae"]: at_angle(f"{lab['input']} = {deg} deg")})
        + zero_text([lab[f"name{d}"] for d, ex in ((1, w_ex), (2, a_ex)) if math.isnan(relative(1.0, ex))]),
        positions,
    )


def _missing(studied, sweep, step) -> float:
    """The largest change of the studied quantity that the Newton `step` (n, N) still missing would make."""
    if not studied.derived:
        return float(np.max(np.abs(step[studied.index])))
    now = studied.values(sweep)
    return float(np.max(np.abs(studied.near(studied.at(sweep.values + step, sweep.inputs), now) - now)))

"""Stability suite: stiff and extreme cases, each run through the solver and every scheme.

:data:`CASES` names the cases; :func:`run_suite` runs them and summarises
each in one row of a table: what happened, the largest condition number of
the Jacobian, the Newton iterations, the error of every finite-difference
scheme against the analytic solution, and the error or warning raised. A
scheme's error is taken, as :func:`numkin.compare.compare` takes it, over
the points where its own stencil applies; on an open sweep the one-sided
end stencils, at the points near either end its stencil reaches past (the
first and last for centred, two at each end for five-point, the last for
forward), have a column of their own.

========================================  ======================================================  ================
case                                      what it probes                                          expected
========================================  ======================================================  ================
near toggle (4, 2, 4.0001, 2)             non-Grashof by 1e-4: limits at +-0.405 deg; 1..359 deg  ok
near toggle, 1e-6 deg from its limit      the analytic derivatives lose digits (cond ~ 1.6e5)     ok, with warning
nearly aligned, delta = 1e-2, 1e-4, 1e-6  coupler and rocker almost in line at 180 deg            ok
change point (5, 2, 5, 2), from 0 deg     parallelogram, singular at the first input              BranchError
change point (5, 2, 5, 2), through 180    the branches meet: reported, never switched             BranchError
non-Grashof (7, 4, 3, 5), full turn       driven past its limit                                   AssemblyError
cannot assemble (10, 6, 1, 1)             no input angle works                                    AssemblyError
slider-crank 80/200 at 6000 rpm           accelerations ~4e4 m/s^2                                ok
homework, homework x 1e-6, x 1e3          relative errors must not change with scale              ok
homework, 12 and 100 000 points per turn  extreme grids                                           ok
========================================  ======================================================  ================

Nothing in the suite may produce a silently wrong number: an expected
error (:class:`~numkin.AssemblyError`, :class:`~numkin.BranchError`) is
caught and shown as the outcome; a completed sweep is checked (finite
values, residuals at the tolerance, analytic derivatives equal to the
complex-step ones) and marked ``WRONG`` if a check fails; the size of the
finite-difference errors is in the table, next to the grid that caused it.

Examples
--------
>>> from numkin import stability
>>> table = stability.run_suite(["cannot assemble (10, 6, 1, 1)"])
>>> table[["outcome", "as expected"]].values.tolist()
[['AssemblyError', True]]
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Callable, Iterable

import numpy as np

from . import analytic, kinematics, linkages
from .conditioning import LostDigitsWarning, lost_digits
from .derivatives import SCHEMES
from .schemes import own_stencil_points
from .errors import AssemblyError, BranchError, ConvergenceError, InputError, NumkinError
from .sweep import Sweep
from .units import input_rate

__all__ = ["Case", "CASES", "run_suite", "report_tables"]

#: Largest relative difference allowed between the analytic and the complex-step dq/dtheta.
ANALYTIC_CHECK = 1e-6
#: Relative errors below this are round-off: a case compared with another (same linkage, other scale)
#: is compared on the schemes whose errors are above it.
ROUNDOFF_LEVEL = 1e-9


@dataclass(frozen=True)
class Case:
    """One case of the stability suite.

    Attributes
    ----------
    name : str
    description : str
    build : callable
        ``build() -> Mechanism``.
    inputs : tuple
        ``(first_deg, last_deg, count)``: the sweep is
        ``np.radians(np.linspace(first_deg, last_deg, count))``.
    quantity : str
        The unknown whose velocity and acceleration are differenced.
    omega : float or str
        Input speed.
    expect : str
        ``"ok"``, ``"AssemblyError"`` or ``"BranchError"``.
    compare_to : str, optional
        A case whose relative errors this one must reproduce (scale cases).
    """

    name: str
    description: str
    build: Callable
    inputs: tuple
    quantity: str
    omega: object
    expect: str = "ok"
    compare_to: str | None = None

    def input_values(self) -> np.ndarray:
        first, last, count = self.inputs
        return np.radians(np.linspace(first, last, int(count)))


def _homework(scale: float = 1.0):
    """The homework's chained four-bars (the spec's default dimensions), every length times `scale`."""
    spec = linkages.spec("chained_four_bars")
    lengths = {d.name: d.default * scale for d in spec.dimensions if d.kind == "length"}
    return lambda: spec.build(**lengths)


#: Limit position of the 4/2/4.0001/2 four-bar, deg: ``|A - O4| = r3 - r4``, by the law of cosines.
_TOGGLE_LIMIT_DEG = math.degrees(math.acos((4**2 + 2**2 - (4.0001 - 2) ** 2) / (2 * 4 * 2)))


def _cases() -> dict:
    hw = "450 rad/min"
    full = (0.0, 360.0, 361)
    cases = [
        Case("near toggle (4, 2, 4.0001, 2)",
             "non-Grashof by 1e-4: limit positions at +-0.405 deg, nearly extended at 180 deg; swept 1..359 deg",
             lambda: linkages.four_bar(4, 2, 4.0001, 2), (1.0, 359.0, 359), "theta4", 10.0),
        Case("near toggle, 1e-6 deg from its limit",
             "the same four-bar swept from 1e-6 deg past its limit position: cond ~ 1.6e5, the analytic "
             "derivatives lose digits (LostDigitsWarning)",
             lambda: linkages.four_bar(4, 2, 4.0001, 2), (_TOGGLE_LIMIT_DEG + 1e-6, _TOGGLE_LIMIT_DEG + 1.0, 101),
             "theta4", 10.0),
    ]
    for delta in (1e-2, 1e-4, 1e-6):
        cases.append(
            Case(f"nearly aligned, delta = {delta:.0e}",
                 f"ground 4, crank 1, coupler 3, rocker 2 + {delta:g}: coupler and rocker almost in line at 180 deg",
                 lambda d=delta: linkages.four_bar(4, 1, 3, 2 + d), full, "theta4", 10.0)
        )
    cases += [
        Case("change point (5, 2, 5, 2), from 0 deg",
             "parallelogram: all links in line at 0 deg, where the sweep starts",
             lambda: linkages.four_bar(5, 2, 5, 2), full, "theta4", 10.0, expect="BranchError"),
        Case("change point (5, 2, 5, 2), through 180 deg",
             "parallelogram swept 10..350 deg: the branches meet at 180 deg",
             lambda: linkages.four_bar(5, 2, 5, 2), (10.0, 350.0, 341), "theta4", 10.0, expect="BranchError"),
        Case("non-Grashof (7, 4, 3, 5), full turn",
             "a triple rocker driven past its limit", lambda: linkages.four_bar(7, 4, 3, 5), full, "theta4", 10.0,
             expect="AssemblyError"),
        Case("cannot assemble (10, 6, 1, 1)", "coupler and rocker too short for any input",
             lambda: linkages.four_bar(10, 6, 1, 1), full, "theta4", 10.0, expect="AssemblyError"),
        Case("slider-crank 80/200 at 6000 rpm", "piston accelerations ~4e4 m/s^2 (4e7 mm/s^2)",
             lambda: linkages.slider_crank(80, 200), full, "x", "6000 rpm"),
        Case("homework", "chained four-bars of the homework, 1 deg grid", _homework(1.0), full, "beta", hw),
        Case("homework x 1e-6", "all lengths scaled by 1e-6", _homework(1e-6), full, "beta", hw,
             compare_to="homework"),
        Case("homework x 1e3", "all lengths scaled by 1e3", _homework(1e3), full, "beta", hw, compare_to="homework"),
        Case("homework, 12 points per turn", "30 deg grid", _homework(1.0), (0.0, 360.0, 13), "beta", hw),
        Case("homework, 100 000 points per turn", "0.0036 deg grid", _homework(1.0), (0.0, 360.0, 100_001),
             "beta", hw),
    ]
    return {c.name: c for c in cases}


#: The named cases of the suite, name -> :class:`Case`, in run order.
CASES: dict = _cases()


#: Largest number of points checked against the complex step (evenly spread over the sweep).
CHECK_POINTS = 3601


def _subsweep(sweep, count: int):
    """The sweep at no more than `count` evenly spread points (same mechanism and branch)."""
    n = sweep.inputs.size
    if n <= count:
        return sweep
    idx = np.unique(np.linspace(0, n - 1, count).round().astype(int))
    return Sweep(
        sweep.mechanism, sweep.inputs[idx], sweep.values[:, idx], sweep.iterations[idx], sweep.residual[idx],
        sweep.cond[idx], list(sweep.events), sweep.jacobian, sweep.tol,
    )


def _scheme_errors(sweep, j, schemes, dq, d2q) -> dict:
    """Each scheme's ``(interior, ends)`` errors of unknown `j`, over ``max |exact|`` (d/dtheta: independent of omega).

    As :func:`numkin.compare.compare` does: the unknown's row is differenced
    on its own (:func:`numkin.kinematics.prepare_rows`), and the interior
    error is the largest over the points where the scheme's own stencil
    applies (:func:`numkin.schemes.own_stencil_points`: one period of a full
    turn; on an open sweep all but the points near either end that its
    stencil reaches past, which take one-sided end stencils); the ends'
    largest error is the second number
    (NaN on a periodic sweep). Both divide by the largest ``|exact|`` over
    the whole sweep. NaN, NaN for a scheme that does not apply (a spectral
    one on an open sweep).
    """
    mech = sweep.mechanism
    name = mech.unknowns[j]
    grid = kinematics.sweep_grid(sweep)
    rows = kinematics.prepare_rows(sweep.values[j:j + 1], [name in mech.angles], [name], sweep.inputs, grid,
                                   mech.length_scale)
    n = sweep.inputs.size
    out = {}
    for scheme in schemes:
        if scheme.periodic_only and not rows.periodic:
            out[scheme.name] = (math.nan, math.nan)
            continue
        exact = dq[j] if scheme.derivative == 1 else d2q[j]
        err = np.abs(rows.apply(scheme)[0] - exact) / np.max(np.abs(exact))
        keep = np.zeros(n, dtype=bool)
        keep[own_stencil_points([scheme], n, rows.periodic)] = True
        ends = np.zeros(n, dtype=bool) if rows.periodic else ~keep
        out[scheme.name] = (float(np.max(err[keep])) if keep.any() else math.nan,
                            float(np.max(err[ends])) if ends.any() else math.nan)
    return out


def _sharpest_turn(mech, sweep, j, samples: int = 801) -> float:
    """Input range (deg) over which the studied unknown turns most sharply: jump of dq/dtheta over ``max |d2q|``.

    Where ``|d2q/dtheta2|`` is largest on the sweep, the position is solved
    again on a fine grid of `samples` points two grid steps either side
    (continued from the sweep's value there), and the range is the change of
    dq/dtheta across that window divided by the largest ``|d2q/dtheta2|`` in it:
    about the width of the turn, however narrow.
    """
    n = sweep.inputs.size
    if n < 5:
        return math.nan
    d2 = analytic.derivatives(_subsweep(sweep, n))[1][j]
    k = int(np.clip(np.argmax(np.abs(d2)), 2, n - 3))
    fine = np.linspace(sweep.inputs[k - 2], sweep.inputs[k + 2], samples)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            local = mech.sweep(fine[(samples - 1) // 2:], sweep.values[:, k])
            left = mech.sweep(fine[: (samples + 1) // 2][::-1], sweep.values[:, k])
            dq_r, d2q_r = analytic.derivatives(local)
            dq_l, d2q_l = analytic.derivatives(left)
    except InputError:
        raise
    except NumkinError:  # the local sweep could not be solved: no width to give
        return math.nan
    dq = np.concatenate([dq_l[j], dq_r[j]])
    d2q = np.concatenate([d2q_l[j], d2q_r[j]])
    peak = float(np.max(np.abs(d2q)))
    width = math.degrees(float(np.ptp(dq)) / peak) if peak > 0 else math.nan
    step = math.degrees(float(np.mean(np.abs(np.diff(sweep.inputs)))))
    return width if width < 3 * step else math.nan  # the window is 4 steps wide: wider turns are not measured


def _run_case(case: Case, schemes) -> dict:
    row = {
        "case": case.name,
        "expected": case.expect,
        "outcome": "",
        "as expected": False,
        "what happened": "",
        "points": int(case.inputs[2]),
        "max cond [-]": math.nan,
        "Newton iterations (max)": math.nan,
        "analytic vs complex step [-]": math.nan,
        "sharpest turn [deg]": math.nan,
        "analytic lost digits": False,
    }
    for scheme in schemes:
        row[f"{scheme.name} max rel error [-]"] = math.nan
    for scheme in schemes:
        row[f"{scheme.name} ends rel error [-]"] = math.nan
    row["error or warning raised"] = ""
    raised = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            mech = case.build()
            j = mech.unknowns.index(case.quantity)
            sweep = mech.sweep(case.input_values())
            row["max cond [-]"] = float(np.max(sweep.cond))
            row["Newton iterations (max)"] = int(np.max(sweep.iterations))
            dq, d2q = analytic.derivatives(sweep)
            sub = _subsweep(sweep, CHECK_POINTS)
            cs = analytic.complex_step(sub)[j]
            dq_sub = analytic.derivatives(sub)[0][j] if sub is not sweep else dq[j]
            check = float(np.max(np.abs(cs - dq_sub)) / np.max(np.abs(dq_sub)))
            row["analytic vs complex step [-]"] = check
            both = _scheme_errors(sweep, j, schemes, dq, d2q)
            errors = {name: inner for name, (inner, _) in both.items()}
            for name, (inner, ends) in both.items():
                row[f"{name} max rel error [-]"] = inner
                row[f"{name} ends rel error [-]"] = ends
            wrong = []
            if not np.all(np.isfinite(sweep.values)):
                wrong.append("non-finite positions")
            if not np.max(sweep.residual) <= 10 * sweep.tol:
                wrong.append(f"residual {np.max(sweep.residual):.3g} above the tolerance")
            if not check <= ANALYTIC_CHECK:
                wrong.append(f"analytic and complex-step derivatives differ by {check:.3g}")
            w = input_rate(case.omega)
            peak1, peak2 = abs(w) * np.max(np.abs(dq[j])), w * w * np.max(np.abs(d2q[j]))
            unit = "rad" if case.quantity in mech.angles else mech.length_unit
            finite = [e for e in errors.values() if np.isfinite(e)]
            best = min(finite) if finite else math.nan
            text = (
                f"solved {sweep.inputs.size} points; peak |d/dt| = {peak1:.4g} {unit}/s, "
                f"peak |d2/dt2| = {peak2:.4g} {unit}/s^2"
            )
            comp, p = mech.compiled, mech.parameter_values
            f = comp.F(sweep.values, sweep.inputs, p)
            delta = float(np.max(np.abs(np.linalg.solve(comp.J(sweep.values, sweep.inputs, p), -f.T[..., None])[..., 0][:, j])))
            text += f"; position error left by the solver (Newton estimate |J^-1 F|) {delta:.2g} {unit}"
            h = float(np.mean(np.abs(np.diff(sweep.inputs))))
            floor = 4 * delta / h**2 / max(float(np.max(np.abs(d2q[j]))), 1e-300)
            if floor > 1e-6:
                text += f", a floor of 4 delta/h^2 = {floor:.2g} (relative) under the second-derivative schemes"
            turn = _sharpest_turn(mech, sweep, j)
            row["sharpest turn [deg]"] = turn
            if math.isfinite(turn) and turn < 3 * math.degrees(h):
                text += (
                    f"; the output turns within {turn:.2g} deg, under 3 grid steps of {math.degrees(h):.3g} deg: "
                    "first-derivative errors peak when the turn is about one step wide and fall again when it is "
                    "narrower (a corner between grid points: the neighbours see straight lines on either side, "
                    "only the point at the corner is wrong), while second-derivative errors grow as the turn "
                    "sharpens"
                )
            if best > 1e-2:
                text += f"; the grid does not resolve the motion: every scheme is off by {100 * best:.3g}% or more"
            lost = [w for w in caught if issubclass(w.category, LostDigitsWarning)]
            row["analytic lost digits"] = bool(lost)
            if lost:
                est = float(np.max(lost_digits(sweep.cond, 2)))
                text += (f"; the analytic derivatives lose digits near the singular position (LostDigitsWarning): "
                         f"estimated relative error of the accelerations up to {est:.2g}")
            if wrong:
                row["outcome"] = "WRONG: " + "; ".join(wrong)
            else:
                row["outcome"] = "ok" if not (sweep.events or lost) else "ok, with warning"
            row["what happened"] = text
        except (AssemblyError, BranchError, ConvergenceError) as exc:
            kind = type(exc).__name__
            row["outcome"] = kind
            if isinstance(exc, BranchError):
                row["what happened"] = f"stopped: {exc.kind} at input {math.degrees(exc.input_value):.3f} deg"
            elif isinstance(exc, AssemblyError):
                row["what happened"] = "refused before solving"
            else:
                row["what happened"] = "Newton failed"
            raised.append(f"{kind}: {exc}")
        except NumkinError as exc:  # any other deliberate error: shown, never hidden
            row["outcome"] = type(exc).__name__
            raised.append(f"{type(exc).__name__}: {exc}")
        except Exception as exc:  # an unexpected failure is a finding of the suite
            row["outcome"] = f"unexpected {type(exc).__name__}"
            raised.append(f"{type(exc).__name__}: {exc}")
    for w in caught:
        msg = f"{w.category.__name__}: {w.message}"
        if msg not in raised:
            raised.append(msg)
    row["error or warning raised"] = " | ".join(raised)
    row["as expected"] = row["outcome"].split(",")[0] == case.expect
    return row


def run_suite(cases: Iterable[str] | None = None, *, schemes: Iterable[str] | None = None):
    """Run the stability cases and summarise them in one table.

    Parameters
    ----------
    cases : iterable of str, optional
        Names of :data:`CASES` (default: all, in their order).
    schemes : iterable of str, optional
        Finite-difference schemes (default: every scheme of
        :data:`numkin.derivatives.SCHEMES`; the spectral ones are blank on a
        grid that is not one full turn).

    Returns
    -------
    pandas.DataFrame
        One row per case: ``case``, ``expected``, ``outcome`` (``ok``,
        ``ok, with warning``, the name of the error raised, or ``WRONG: ...``
        if a completed sweep fails its checks), ``as expected``, ``what
        happened``, ``points``, ``max cond [-]`` (the largest condition
        number of a loop's block of the scaled Jacobian), ``Newton iterations
        (max)`` (blank, NaN, if nothing was solved), ``analytic vs complex
        step [-]`` (max relative difference of dq/dtheta, at up to
        ``CHECK_POINTS`` points spread evenly over the sweep), ``sharpest
        turn [deg]`` (the input range over which the unknown's derivative
        turns, measured on a fine local sweep where ``|d2q/dtheta2|`` is
        largest; blank where wider than 3 grid steps), ``analytic lost
        digits`` (whether the analytic derivatives raised
        :class:`~numkin.conditioning.LostDigitsWarning`; ``what happened``
        then gives the estimated error), ``<scheme> max rel error [-]``
        (the largest error over the points where the scheme's own stencil
        applies, as in :func:`numkin.compare.compare`: one period of a full
        turn; on an open sweep all but the points near either end that its
        stencil reaches past), ``<scheme> ends rel error [-]`` (the largest
        error of the one-sided end stencils at those points; blank on a full turn),
        both divided by the largest ``|exact|`` derivative over the sweep,
        and ``error or warning raised``. Scale cases (with
        ``compare_to``) say in ``what happened`` how far their relative
        errors are from those of the case they scale.

    Examples
    --------
    >>> t = run_suite(["homework x 1e3"], schemes=["centred"])
    >>> round(float(t["centred max rel error [-]"].iloc[0]), 6)
    0.000182
    """
    import pandas as pd

    from .derivatives import get_scheme
    from .report.captions import PEAK, relative_text, set_views

    names = list(CASES) if cases is None else ([cases] if isinstance(cases, str) else list(cases))
    unknown = [n for n in names if n not in CASES]
    if unknown:
        raise InputError(f"unknown stability case(s) {unknown}; the cases are {list(CASES)}")
    scheme_list = list(SCHEMES.values()) if schemes is None else [get_scheme(s) for s in schemes]
    rows = {}
    for name in names:
        case = CASES[name]
        row = _run_case(case, scheme_list)
        if case.compare_to is not None:
            ref = rows.get(case.compare_to) or _run_case(CASES[case.compare_to], scheme_list)
            cols = [f"{s.name} max rel error [-]" for s in scheme_list]
            a = np.array([row[c] for c in cols], dtype=float)
            b = np.array([ref[c] for c in cols], dtype=float)
            # schemes whose error is truncation, well above round-off (~1e-13 here): the ones a change of
            # scale or grid could move; round-off-level errors differ from run to run in any case
            ok = np.isfinite(a) & np.isfinite(b) & (b > ROUNDOFF_LEVEL)
            if ok.any():
                change = float(np.max(np.abs(a[ok] / b[ok] - 1)))
                row["what happened"] += (
                    f"; the schemes' relative errors above round-off ({ROUNDOFF_LEVEL:.0e}) equal those of case "
                    f"'{case.compare_to}' to {change:.1e} (relative)")
        rows[name] = row
    df = pd.DataFrame(list(rows.values()))
    df.attrs["caption"] = (
        "Stability suite: each case through the solver and every finite-difference scheme; expected errors are "
        "outcomes. A scheme's max rel error is its largest error of dq/dtheta (d2q/dtheta2) over the points where "
        "its own stencil applies: one period of a full turn; on an open sweep all but the points near either end "
        f"that its stencil reaches past{_ends_text(scheme_list)}, which take one-sided end stencils and whose largest "
        "error is the scheme's ends rel error (blank on a full turn)."
        + relative_text({"max rel error": PEAK, "ends rel error": PEAK})
        + " Max cond: the largest 2-norm condition "
        "number of a loop's own block of the scaled Jacobian over the sweep. Sharpest turn: the input range over "
        "which the output turns (jump of dq/dtheta over max |d2q/dtheta2|), blank where wider than 3 grid steps. "
        "Errors need not grow with the stiffness: a first-derivative error peaks when the turn is about one grid "
        "step wide and falls when the turn becomes a corner between grid points (nearly aligned, delta = 1e-4 "
        "against 1e-6); second-derivative errors grow as the turn sharpens."
    )
    first = [f"{s.name} max rel error [-]" for s in scheme_list if s.derivative == 1]
    second = [f"{s.name} max rel error [-]" for s in scheme_list if s.derivative == 2]
    ends = [f"{s.name} ends rel error [-]" for s in scheme_list]

    set_views(df, [
        ("outcome", ["case", "expected", "outcome", "as expected"]),
        ("the solver", ["case", "points", "max cond [-]", "Newton iterations (max)", "analytic vs complex step [-]",
                        "analytic lost digits"]),
        ("first-derivative schemes: max error of dq/dtheta over its peak", ["case", "sharpest turn [deg]"] + first),
        ("second-derivative schemes: max error of d2q/dtheta2 over its peak", ["case", "sharpest turn [deg]"] + second),
        ("one-sided end stencils of an open sweep: max error at the points near either end over the peak",
         ["case"] + ends),
        ("what happened", ["case", "what happened"]),
        ("errors and warnings raised", ["case", "error or warning raised"]),
    ], row_keys=["case"])
    return df


_COUNT = {2: "two", 3: "three", 4: "four", 5: "five", 6: "six", 7: "seven", 8: "eight", 9: "nine"}


def _ends_text(schemes) -> str:
    """Which points of an open sweep each scheme leaves to its end stencils, in words, from its reach.

    `` (the first and last for centred and the second difference, the last for forward)``: one
    phrase per reach (``Scheme.reach``), symmetric reaches first, then the shorter
    first, the end before the start; the schemes of one family that all share a reach (two or
    more) are named together (``the five-point schemes``). Empty if no scheme has an end.
    """
    groups: dict = {}
    for scheme in schemes:
        if any(scheme.reach):
            groups.setdefault(scheme.reach, []).append(scheme)

    def count(n, end):
        return f"the {end}" if n == 1 else f"the {end} {_COUNT.get(n, n)}"

    def where(before, after):
        if before == after:
            return "the first and last" if before == 1 else f"{_COUNT.get(before, before)} at each end"
        return " and ".join(count(n, end) for n, end in ((before, "first"), (after, "last")) if n)

    def names(group):
        out = []
        for scheme in group:
            family = [s for s in schemes if s.family == scheme.family]
            if len(family) < 2 or not all(s in group for s in family):
                out.append(scheme.prose)
            elif scheme is family[0]:
                out.append(f"the {scheme.family.replace('_', '-')} schemes")
        return out[0] if len(out) == 1 else f"{', '.join(out[:-1])} and {out[-1]}"

    order = sorted(groups, key=lambda r: (r[0] != r[1], max(r), r[0] > r[1]))
    text = ", ".join(f"{where(*reach)} for {names(groups[reach])}" for reach in order)
    return f" ({text})" if text else ""


def report_tables(cases: Iterable[str] | None = None, *, schemes: Iterable[str] | None = None) -> dict:
    """The stability scene's report: its tables by name, as :func:`numkin.report.full_report` gives a mechanism's.

    Write them with :func:`numkin.report.write_tables` and print them with
    :func:`numkin.report.format_text`.

    Returns
    -------
    dict
        ``{"stability": run_suite(cases, schemes=schemes)}``.

    Examples
    --------
    >>> list(report_tables(["cannot assemble (10, 6, 1, 1)"]))
    ['stability']
    """
    return {"stability": run_suite(cases, schemes=schemes)}

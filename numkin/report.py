"""Error-analysis reports: error against step, error against run time, solver settings.

Every table is a :class:`pandas.DataFrame` returned by one function, built
from a mechanism and plain settings (input speed, the unknown to study, a
check angle in rad, grids, schemes), so that a notebook can call each one
and :func:`full_report` can call them all for a scene:

============================  ===============================================================
function                      what the table shows
============================  ===============================================================
:func:`convergence_table`     max / RMS error of every scheme on every grid against the
                              analytic solution, the error at a check angle, observed order
:func:`work_precision_table`  work (exact counts of evaluations, the same in every run) and
                              run time (sweep, differencing, both) beside the error reached,
                              with the analytic solution and the complex step as rows, and
                              the Pareto fronts by work and by time
:func:`cheapest_table`        from a work-precision table: the cheapest method for each
                              wanted accuracy, by run time or by work
:func:`count_evaluations`     context manager counting the point evaluations of a
                              mechanism's compiled loop equations (the work measure)
:func:`roundoff_table`        error against the step h (1e-1 ... 1e-12 rad) at one angle;
                              the measured optimal h beside the textbook estimates
:func:`newton_table`          residual, step and error norms per Newton iteration of one
                              solve, with the estimated order of convergence
:func:`jacobian_table`        symbolic against forward / central finite-difference
                              Jacobians: iterations, time, final accuracy
:func:`tolerance_table`       loose stopping rules (as in the source documents) against
                              numkin's rule, and what they do to differenced omega and alpha
============================  ===============================================================

Conventions
-----------
* Angles are in rad inside; tables show degrees only in labelled columns
  (``"h [deg]"``) and in the text of column names such as
  ``"abs error at theta = 100 deg [unit of quantity]"``.
* A row's ``quantity`` names what was differentiated, with its unit:
  ``"omega_beta [rad/s]"`` (first-derivative schemes) or
  ``"alpha_beta [rad/s^2]"`` (second-derivative schemes); for a length
  unknown ``"v_x [mm/s]"`` / ``"a_x [mm/s^2]"``. Absolute errors are in
  that unit (column names say ``[unit of quantity]``); relative errors are
  divided by the largest magnitude of the exact quantity over the sweep,
  ``[-]``.
* Grids are given in points per turn N; a full-turn grid is
  ``np.linspace(start, start + 2 pi, N + 1)`` (the last sample repeats the
  first), differenced as periodic by :mod:`numkin.kinematics`; errors
  are taken over the N distinct points.
* Row order is fixed by the arguments (scheme order, then grid order), so
  two runs give the same table; **timings are the only entries that vary
  between runs**, and every column holding them (or chosen by them) says
  ``(varies)``. Work is measured by exact counts instead
  (``work [evaluations]``, see :func:`work_precision_table`): the same in
  every run, so figures drawn from it are reproducible byte for byte.
* Warnings of the main sweeps (a near-singular point, data that had to be
  differenced as an open grid) reach the caller; the repeated sweeps of
  the timings and of the loose-tolerance solves are quiet.

:func:`write_tables` writes the tables as Markdown (needs ``tabulate``),
CSV and LaTeX (booktabs rules, written here without jinja2).

Examples
--------
>>> import math
>>> from numkin import linkages, report
>>> mech = linkages.chained_four_bars()
>>> conv = report.convergence_table(mech, omega="450 rad/min", quantity="beta",
...                                 check_angle=math.radians(100), grids=(180, 360),
...                                 schemes=("centred",))
>>> print(round(float(conv["observed order [-]"].iloc[1]), 2))
2.0
"""

from __future__ import annotations

import math
import statistics
import time
import warnings
from contextlib import contextmanager
from functools import cached_property
from pathlib import Path
from typing import Callable, Iterable, Iterator, Mapping, Sequence

import numpy as np

from . import analytic, kinematics, units
from .derivatives import SCHEMES, get_scheme
from .errors import NumkinError
from .sweep import Sweep

__all__ = [
    "DEFAULT_GRIDS",
    "ROUNDOFF_SCHEMES",
    "COUNTED_FUNCTIONS",
    "EvaluationCounter",
    "count_evaluations",
    "convergence_table",
    "work_precision_table",
    "cheapest_table",
    "roundoff_table",
    "newton_table",
    "jacobian_table",
    "tolerance_table",
    "student_sweep",
    "STUDENT_RULES",
    "full_report",
    "write_tables",
]

EPS = float(np.finfo(float).eps)
TURN = 2.0 * math.pi
#: Default grids, in points per turn of the input.
DEFAULT_GRIDS = (36, 72, 180, 360, 720, 1440, 3600)
#: Default schemes of :func:`roundoff_table` (``"complex_step"`` is not a finite difference).
ROUNDOFF_SCHEMES = ("forward", "centred", "five_point", "second_difference", "complex_step")
#: Stopping rules of :func:`student_sweep`: absolute step, relative step (loop by loop), residual.
STUDENT_RULES = ("step", "relative", "residual")
#: Steps shown as columns of :func:`roundoff_table`, rad.
ROUNDOFF_STEPS = tuple(10.0 ** -k for k in range(1, 13))
_UNIT = "[unit of quantity]"
_VARIES = "(varies)"
#: Work columns of :func:`work_precision_table` (exact counts; see its docstring).
_WORK_SWEEP = "sweep work [evaluations]"
_WORK_DERIVATIVE = "derivative work [evaluations]"
_WORK = "work [evaluations]"
_PARETO_WORK = "Pareto front by work"


# =========================================================================== helpers
def _omega(omega) -> float:
    """Input speed in rad/s from a number or a string with units."""
    if isinstance(omega, str):
        return units.angular_speed(omega)
    if isinstance(omega, bool) or omega is None:
        raise TypeError(f"omega must be a number (rad/s) or a string with units, got {omega!r}")
    try:
        w = float(omega)
    except (TypeError, ValueError):
        raise TypeError(f"omega must be a number (rad/s) or a string with units, got {omega!r}") from None
    if not math.isfinite(w):
        raise ValueError(f"omega = {omega!r} is not finite")
    return w


def _index(mechanism, quantity: str) -> int:
    if quantity not in mechanism.unknowns:
        raise ValueError(
            f"quantity {quantity!r} is not an unknown of {mechanism.name}; choose one of {list(mechanism.unknowns)}"
        )
    return mechanism.unknowns.index(quantity)


def _labels(mechanism, quantity: str) -> dict:
    """Names and units of q, dq/dt, d2q/dt2, dq/dtheta and d2q/dtheta2 for one unknown."""
    if quantity in mechanism.angles:
        u = "rad"
        first, second = f"omega_{quantity}", f"alpha_{quantity}"
    else:
        u = mechanism.length_unit
        first, second = f"v_{quantity}", f"a_{quantity}"
    t = str(mechanism.input_symbol)
    return {
        "unit": u,
        1: f"{first} [{u}/s]",
        2: f"{second} [{u}/s^2]",
        "name1": first,
        "name2": second,
        "unit1": f"{u}/s",
        "unit2": f"{u}/s^2",
        "d1": f"d{quantity}/d{t} [{u}/rad]",
        "d2": f"d2{quantity}/d{t}2 [{u}/rad^2]",
        "input": t,
    }


def _deg_text(angle: float) -> str:
    return f"{math.degrees(angle):.6g}"


def _schemes(names, periodic: bool | None = None) -> list:
    """Scheme objects for `names` (default: every registered scheme, the spectral ones only if periodic)."""
    if names is None:
        return [s for s in SCHEMES.values() if periodic or not s.periodic_only]
    if isinstance(names, str):
        names = [names]
    out = [get_scheme(n) for n in names]
    if periodic is False:
        bad = [s.name for s in out if s.periodic_only]
        if bad:
            raise ValueError(f"scheme(s) {bad} need a grid over one full turn (span = 2 pi)")
    return out


def _full_turn(span: float) -> bool:
    """Whether an input range of `span` rad is one full turn (a periodic grid)."""
    return abs(span - TURN) <= 1e-12 * TURN


def _grid(points: int, start: float, span: float) -> np.ndarray:
    """Inputs of a grid with `points` per turn: a full turn (N + 1 samples) or `span` rad."""
    if isinstance(points, bool) or int(points) != points or points < 4:
        raise ValueError(f"points per turn must be an integer >= 4, got {points!r}")
    points = int(points)
    h = TURN / points
    if _full_turn(span):
        return start + h * np.arange(points + 1)
    if not (0 < span < TURN):
        raise ValueError(f"span must be in (0, 2 pi] rad, got {span!r}")
    count = int(math.floor(span / h + 1e-9)) + 1
    if count < 5:
        raise ValueError(f"span {math.degrees(span):.4g} deg holds fewer than 5 points of a {points}-point grid")
    return start + h * np.arange(count)


def _grids(grids) -> list:
    if isinstance(grids, (int, np.integer)):
        grids = [grids]
    out = [int(g) for g in grids]
    if not out:
        raise ValueError("grids must name at least one grid (points per turn)")
    return out


def _grid_study(mechanism, omega, quantity: str, grids, span: float, schemes) -> tuple:
    """The checked arguments of a study over grids: ``(w, j, labels, grid_list, periodic, scheme_list)``.

    `w` is the input speed in rad/s, `j` the index of `quantity` among the
    unknowns, `periodic` whether `span` is a full turn.
    """
    w = _omega(omega)
    j = _index(mechanism, quantity)
    lab = _labels(mechanism, quantity)
    grid_list = _grids(grids)
    periodic = _full_turn(span)
    return w, j, lab, grid_list, periodic, _schemes(schemes, periodic)


def _check_index(inputs: np.ndarray, angle: float | None) -> int | None:
    """Index of the grid point at `angle` (mod 2 pi), or None if the grid does not hold it."""
    if angle is None:
        return None
    d = np.abs(np.remainder(inputs - angle + math.pi, TURN) - math.pi)
    k = int(np.argmin(d))
    return k if d[k] <= 1e-9 else None


def _quiet(fn, *args, **kwargs):
    """Call fn with numkin's warnings silenced (callers report what matters in the tables)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*args, **kwargs)


def _median_time(fn: Callable[[], object], repeat: int, warmup: bool = True) -> float:
    """Median wall time of ``fn()`` in seconds over `repeat` repeats.

    With `warmup`, one untimed call comes first, and calls shorter than
    2 ms are looped inside each repeat so that every timed block lasts at
    least ~2 ms.
    """
    number = 1
    if warmup:
        t0 = time.perf_counter()
        fn()
        first = time.perf_counter() - t0
        number = 1 if first >= 2e-3 else min(1000, max(1, int(2e-3 / max(first, 1e-7))))
    samples = []
    for _ in range(max(1, int(repeat))):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        samples.append((time.perf_counter() - t0) / number)
    return statistics.median(samples)


# ================================================================ counting the work
#: Functions of :class:`~numkin.compiled.CompiledMechanism` counted by :func:`count_evaluations`,
#: and where each call finds its input angles: ``"qt"`` ``f(q, t, ...)``, ``"t"`` ``f(t, ...)``,
#: ``"second"`` ``f(*q, *dq, t, *p)``, ``"scalar"`` one point per call. Methods built on these
#: (``tangent``, ``second_derivative``) are counted through them.
COUNTED_FUNCTIONS = {
    "F": "qt",
    "J": "qt",
    "F_t": "qt",
    "FJ_rows": "qt",
    "fixed_terms": "t",
    "_second": "second",
    "scalar_F": "scalar",
    "scalar_FJT": "scalar",
}


class EvaluationCounter:
    """Point evaluations of a mechanism's compiled functions, as counted by :func:`count_evaluations`.

    A *point evaluation* is one call of one compiled function of the loop
    equations (residuals, Jacobian, both together, dF/dtheta, the terms of
    the input alone, the acceleration right-hand side) at one input angle,
    real or complex: a call on N inputs counts N.

    Attributes
    ----------
    calls : dict
        Function name -> number of calls.
    points : dict
        Function name -> point evaluations.
    """

    def __init__(self) -> None:
        self.calls: dict = {}
        self.points: dict = {}

    @property
    def total(self) -> int:
        """All point evaluations counted."""
        return int(sum(self.points.values()))

    def add(self, name: str, points: int) -> None:
        self.calls[name] = self.calls.get(name, 0) + 1
        self.points[name] = self.points.get(name, 0) + int(points)

    def __repr__(self) -> str:
        return f"EvaluationCounter(total={self.total}, points={self.points})"


_ABSENT = object()


def _size(shape) -> int:
    return int(np.prod(shape, dtype=np.int64)) if shape else 1


def _points_of(kind: str, n: int, args, kwargs) -> int:
    """Number of input angles a call of a counted function evaluates at."""
    if kind == "scalar":
        return 1
    if kind == "t":
        t = args[0] if args else kwargs["t"]
        return _size(np.shape(t))
    if kind == "second":
        q0, t = args[0], args[2 * n]
    else:
        q = args[0] if args else kwargs["q"]
        t = args[1] if len(args) > 1 else kwargs["t"]
        q0 = q[0] if len(q) else 0.0
    return _size(np.broadcast_shapes(np.shape(t), np.shape(q0)))


@contextmanager
def count_evaluations(mechanism) -> Iterator[EvaluationCounter]:
    """Count the point evaluations of a mechanism's compiled functions inside a ``with`` block.

    The functions named in :data:`COUNTED_FUNCTIONS` of ``mechanism.compiled``
    are wrapped, for the duration of the block, by counters of calls and of
    input angles (a call on N inputs is N point evaluations; a call of a
    scalar function one). Everything that evaluates the loop equations --
    the sweep's sequential and batched Newton steps, the tangent and
    acceleration solves of :mod:`numkin.analytic`, the complex-step Newton
    -- goes through them, so the count is exact: it is what the code did,
    not an estimate, and it is the same in every run (it depends on the
    algorithm and the data, not on the machine's speed or load).

    The wrappers sit on this mechanism's ``compiled`` object only and are
    removed on leaving the block (functions compiled meanwhile are kept);
    calls from other threads during the block are counted too.

    Parameters
    ----------
    mechanism : Mechanism

    Yields
    ------
    EvaluationCounter

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> mech = linkages.slider_crank(80, 200)
    >>> sweep = mech.sweep(np.radians(np.arange(0, 91, 10)))      # 10 points
    >>> with count_evaluations(mech) as count:
    ...     dq = analytic.tangent(sweep)                            # J q' = -dF/dtheta
    >>> count.total, count.points                                   # J and dF/dtheta at 10 points
    (20, {'F_t': 10, 'J': 10})
    """
    comp = mechanism.compiled
    counter = EvaluationCounter()
    n = len(mechanism.unknowns)
    saved = []  # (name, value in the instance's __dict__ before, or _ABSENT; lazily compiled box)
    try:
        for name, kind in COUNTED_FUNCTIONS.items():
            attr = getattr(type(comp), name, None)
            box: dict = {}
            if name in vars(comp):  # a function stored on the instance, or a cached property already compiled
                box["f"] = vars(comp)[name]
                before = vars(comp)[name]
            elif isinstance(attr, cached_property):  # compiled on first use: not before (position-only work
                before = _ABSENT                      # must not compile the acceleration equations)

                def compile_now(_attr=attr):
                    return _attr.func(comp)

                box["compile"] = compile_now
            elif callable(attr):
                box["f"] = getattr(comp, name)  # a method, bound
                before = _ABSENT
            else:
                continue

            def counted(*args, _box=box, _name=name, _kind=kind, **kwargs):
                if "f" not in _box:
                    _box["f"] = _box["compile"]()
                counter.add(_name, _points_of(_kind, n, args, kwargs))
                return _box["f"](*args, **kwargs)

            saved.append((name, before, box, isinstance(attr, cached_property)))
            setattr(comp, name, counted)
        yield counter
    finally:
        for name, before, box, lazy in reversed(saved):
            if before is not _ABSENT:
                setattr(comp, name, before)
            elif lazy and "f" in box:  # compiled meanwhile: keep it, as the cached property would
                setattr(comp, name, box["f"])
            else:
                delattr(comp, name)


def _stencil_evaluations(sweep: Sweep) -> int:
    """Grid points at which a finite-difference scheme is evaluated on `sweep`.

    As :func:`numkin.kinematics.sweep_derivative` does it: every sample of
    an open grid; on a full turn differenced as periodic, the N distinct
    samples (the closing sample repeats the first and is copied).
    """
    mech = sweep.mechanism
    grid = kinematics.sweep_grid(sweep)
    angle = np.array([u in mech.angles for u in mech.unknowns], dtype=bool)
    rows = _quiet(kinematics.prepare_rows, np.asarray(sweep.values), angle, mech.unknowns, sweep.inputs, grid,
                  mech.length_scale)
    return int(rows.y.shape[-1] - (1 if rows.periodic else 0))


def _polish(mechanism, x, t, *, max_iterations: int = 30):
    """Newton on a batch until the step stops shrinking: positions to machine precision.

    ``x`` (n, M) real or complex starting points at inputs ``t`` (M,), real
    or complex. Raises RuntimeError if the residual is not at round-off.
    """
    comp, p = mechanism.compiled, mechanism.parameter_values
    xs = mechanism.xscale[:, None]
    x = np.array(x, dtype=np.result_type(x, t), copy=True)
    prev = np.inf
    extra = 0
    for _ in range(max_iterations):
        f = comp.F(x, t, p)
        dx = np.linalg.solve(comp.J(x, t, p), -f.T[..., None])[..., 0].T
        x = x + dx
        step = float(np.max(np.abs(dx) / xs))
        if step <= 1e-15 or step >= prev:
            extra += 1
            if extra >= 2:
                break
        prev = min(prev, step)
    res = np.max(np.abs(comp.F(x, t, p))) / mechanism.length_scale
    if not res <= 1e-12:
        raise RuntimeError(f"{mechanism.name}: position not solved to round-off (scaled residual {res:.3g})")
    return x


def _sweep(mechanism, inputs, guess=None, *, quiet: bool = True, **kwargs) -> Sweep:
    """A sweep; with ``quiet=False`` its warnings (near-singular points, ...) reach the caller."""
    if quiet:
        return _quiet(mechanism.sweep, inputs, guess, **kwargs)
    return mechanism.sweep(inputs, guess, **kwargs)


def _one_point(mechanism, angle: float, guess=None, start: float = 0.0) -> Sweep:
    """A one-point sweep at `angle` on the branch of the sweep from `start`, polished to machine precision.

    `guess` is the starting guess at `start` (as for every sweep of this
    module: default the mechanism's own); the point is reached by
    continuation from `start` to `angle`, never by applying the guess at
    `angle`, so that it lies on the branch the tables' sweeps follow.
    """
    a, s0 = float(angle), float(start)
    inputs = np.array([s0]) if a == s0 else np.array([s0, a])
    s = _sweep(mechanism, inputs, guess)
    last = slice(inputs.size - 1, inputs.size)
    x = _polish(mechanism, s.values[:, last], s.inputs[last])
    return Sweep(mechanism, s.inputs[last], x, s.iterations[last], s.residual[last], s.cond[last], list(s.events),
                 s.jacobian, s.tol)


def _position(what: str, mechanism, angle: float, x) -> dict:
    """One solved position of a table, as kept in ``DataFrame.attrs["positions"]``."""
    x = np.asarray(x, dtype=float).reshape(-1)
    return {"what": what, "input [rad]": float(angle), **{u: float(v) for u, v in zip(mechanism.unknowns, x)}}


def _derivative(sweep: Sweep, scheme, quiet: bool = True) -> np.ndarray:
    if quiet:
        return _quiet(kinematics.sweep_derivative, sweep, scheme.name)
    return kinematics.sweep_derivative(sweep, scheme.name)


def _exact(sweep: Sweep, quiet: bool = True) -> tuple:
    return _quiet(analytic.derivatives, sweep) if quiet else analytic.derivatives(sweep)


def _order_text(scheme) -> str:
    return "spectral" if scheme.order == 0 else str(scheme.order)


def _caption(df, text: str, positions: Sequence[dict] | None = None):
    """Set a table's caption and, if given, the positions it was computed at (``attrs["positions"]``)."""
    df.attrs["caption"] = text
    if positions is not None:
        df.attrs["positions"] = list(positions)
    return df


# ======================================================================= convergence
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
        The unknown whose velocity (first-derivative schemes) and
        acceleration (second-derivative schemes) are compared.
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
        quantity]``), ``max rel error [-]`` (over max |exact|), the abs error
        at the check angle, and ``observed order [-]``
        ``log(e_prev / e) / log(h_prev / h)`` from the max error of the row
        above (same scheme).

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> t = convergence_table(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                       grids=(90, 180), schemes=("forward",))
    >>> print(t["quantity"].iloc[0], round(float(t["observed order [-]"].iloc[1]), 1))
    v_x [mm/s] 1.0
    """
    w, j, lab, grid_list, periodic, scheme_list = _grid_study(mechanism, omega, quantity, grids, span, schemes)
    check_col = (
        f"abs error at {lab['input']} = {_deg_text(check_angle)} deg {_UNIT}" if check_angle is not None else None
    )
    data = {}
    for n in grid_list:
        s = _sweep(mechanism, _grid(n, start, span), guess, quiet=False)
        dq, d2q = _exact(s, quiet=False)
        data[n] = (s, dq[j], d2q[j])
    rows = []
    for scheme in scheme_list:
        scale = w if scheme.derivative == 1 else w * w
        prev = None
        for n in grid_list:
            s, dq, d2q = data[n]
            exact = scale * (dq if scheme.derivative == 1 else d2q)
            est = scale * _derivative(s, scheme, quiet=False)[j]
            err = np.abs(est - exact)
            if periodic:  # the last sample repeats the first: statistics over one period
                err, exact = err[:-1], exact[:-1]
            e_max = float(np.max(err))
            h = TURN / n
            row = {
                "scheme": scheme.name,
                "formal order": _order_text(scheme),
                "quantity": lab[scheme.derivative],
                "points per turn": n,
                "h [deg]": 360.0 / n,
                f"max abs error {_UNIT}": e_max,
                f"RMS abs error {_UNIT}": float(np.sqrt(np.mean(err**2))),
                "max rel error [-]": e_max / float(np.max(np.abs(exact))),
            }
            if check_col is not None:
                k = _check_index(s.inputs, check_angle)
                row[check_col] = float(err[k]) if k is not None else math.nan
            order = math.nan
            if prev is not None and prev[0] > 0 and e_max > 0:
                order = math.log(prev[0] / e_max) / math.log(prev[1] / h)
            row["observed order [-]"] = order
            prev = (e_max, h)
            rows.append(row)
    import pandas as pd

    df = pd.DataFrame(rows)
    return _caption(
        df,
        f"Convergence: {mechanism.name}, {quantity}, input speed {w:g} rad/s; error of each scheme "
        "against the analytic solution over the sweep; observed order from successive grids.",
        _grid_positions(mechanism, {n: data[n][0] for n in grid_list}, check_angle),
    )


def _grid_positions(mechanism, sweeps: Mapping, angle: float | None) -> list:
    """``attrs["positions"]`` of a table of sweeps: each sweep at `angle` (or its middle sample, if None)."""
    out = []
    for n, s in sweeps.items():
        k = s.inputs.size // 2 if angle is None else _check_index(s.inputs, angle)
        if k is not None:
            out.append(_position(f"{n} points per turn", mechanism, s.inputs[k], s.values[:, k]))
    return out


# ==================================================================== work-precision
def work_precision_table(
    mechanism,
    *,
    omega,
    quantity: str,
    grids: Iterable[int] = DEFAULT_GRIDS,
    schemes: Sequence[str] | None = None,
    repeat: int = 3,
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
      calls of the compiled residuals, Jacobian, dF/dtheta (and the
      functions combining them) times the input angles of each call,
      counted by instrumenting them (:func:`count_evaluations`).
      ``derivative work`` is what the derivative adds: for the analytic
      solution and the complex step, point evaluations again, counted the
      same way (the velocity equations ``J q' = -dF/dtheta`` take J and
      dF/dtheta at every point, the acceleration equations another J and
      their right-hand side; the complex step runs Newton in complex
      arithmetic at every point); for a finite-difference scheme, which
      evaluates no compiled function, the *stencil evaluations*: one per
      grid point at which its formula is applied (to all unknowns at once,
      as a compiled function is). ``work`` is their sum. It tracks the run
      time because what a row costs is set by how often the loop equations
      are evaluated: the number of points, Newton iterations and linear
      solves. A stencil evaluation (a few multiply-adds) is cheaper than a
      point evaluation (trigonometric functions), so counting each as one
      overstates, if anything, the cost of the finite differences;
    * **run time** -- medians over `repeat` repeats of
      :func:`time.perf_counter` (after an untimed warm-up): the sweep, the
      derivative alone (:func:`numkin.kinematics.sweep_derivative`, or
      :func:`numkin.analytic.tangent` / :func:`~numkin.analytic.derivatives`,
      or :func:`numkin.analytic.complex_step`), and both in one timed block.
      These vary between runs and say so in their column names.

    Parameters
    ----------
    mechanism : Mechanism
    omega : float or str
        Input speed (rad/s or a string with units).
    quantity : str
        The unknown studied.
    grids : iterable of int
        Points per turn.
    schemes : sequence of str, optional
        Finite-difference schemes (default all applicable).
    repeat : int
        Timing repeats.
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
        ``sweep + derivative time [ms] (varies)``, ``max abs error [unit of
        quantity]``, ``max rel error [-]``, ``Pareto front (varies)`` (no
        other row of the same quantity is both faster, by total time, and at
        least as accurate) and ``Pareto front by work`` (the same by
        ``work``: the same in every run). The error of the analytic rows is
        measured against the complex step, all others against the analytic
        solution.

    Examples
    --------
    >>> from numkin import linkages
    >>> t = work_precision_table(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                          grids=(36,), schemes=("centred",), repeat=1)
    >>> list(t["method"])
    ['analytic', 'complex step', 'centred', 'analytic', 'complex step']
    >>> wd = t["derivative work [evaluations]"]
    >>> int(wd[0]), int(wd[2])   # analytic: J and dF/dtheta at the 37 inputs; centred: 36 distinct points
    (74, 36)
    """
    import pandas as pd

    w, j, lab, grid_list, periodic, scheme_list = _grid_study(mechanism, omega, quantity, grids, span, schemes)
    rows = []
    per_grid = {}
    for n in grid_list:
        inputs = _grid(n, start, span)

        def run_sweep(inputs=inputs):
            return _sweep(mechanism, inputs, guess)

        with count_evaluations(mechanism) as count:
            s = run_sweep()
        if count.total <= 0:  # pragma: no cover - numkin.compiled no longer goes through the counted functions
            raise RuntimeError(
                f"{mechanism.name}: no evaluation of the compiled loop equations was counted during the sweep; "
                f"report.COUNTED_FUNCTIONS {sorted(COUNTED_FUNCTIONS)} no longer match numkin.compiled"
            )
        dq, d2q = _exact(s)
        cs1 = _quiet(analytic.complex_step, s, order=1)[j]
        cs2 = _quiet(analytic.complex_step, s, order=2)[j]
        per_grid[n] = (run_sweep, s, dq[j], d2q[j], cs1, cs2, _median_time(run_sweep, repeat), count.total,
                       _stencil_evaluations(s))

    def method_fns(order):
        fns = [
            ("analytic", (lambda s: _quiet(analytic.tangent, s)) if order == 1 else _exact, False),
            ("complex step", lambda s, o=order: _quiet(analytic.complex_step, s, order=o), False),
        ]
        for scheme in scheme_list:
            if scheme.derivative == order:
                fns.append((scheme.name, lambda s, sc=scheme: _derivative(s, sc), True))
        return fns

    for order in (1, 2):
        scale = w if order == 1 else w * w
        for name, fn, differences in method_fns(order):
            for n in grid_list:
                run_sweep, s, dq, d2q, cs1, cs2, t_sweep, sweep_work, stencils = per_grid[n]
                exact = dq if order == 1 else d2q
                with count_evaluations(mechanism) as count:
                    out = fn(s)
                derivative_work = count.total + (stencils if differences else 0)
                if name == "analytic":
                    est, ref = exact, (cs1 if order == 1 else cs2)
                else:
                    est = (out[1] if order == 2 and isinstance(out, tuple) else out)
                    est = est[j] if np.ndim(est) == 2 else est
                    ref = exact
                err = scale * np.abs(est - ref)
                ref_peak = float(np.max(np.abs(scale * ref)))
                if periodic:  # the last sample repeats the first
                    err = err[:-1]
                t_diff = _median_time(lambda fn=fn, s=s: fn(s), repeat)
                t_both = _median_time(lambda fn=fn, run_sweep=run_sweep: fn(run_sweep()), repeat, warmup=False)
                e_max = float(np.max(err))
                rows.append(
                    {
                        "method": name,
                        "quantity": lab[order],
                        "points per turn": n,
                        "h [deg]": 360.0 / n,
                        _WORK_SWEEP: int(sweep_work),
                        _WORK_DERIVATIVE: int(derivative_work),
                        _WORK: int(sweep_work + derivative_work),
                        f"sweep time [ms] {_VARIES}": 1e3 * t_sweep,
                        f"derivative time [ms] {_VARIES}": 1e3 * t_diff,
                        f"sweep + derivative time [ms] {_VARIES}": 1e3 * t_both,
                        f"max abs error {_UNIT}": e_max,
                        "max rel error [-]": e_max / ref_peak,
                    }
                )
    df = pd.DataFrame(rows)
    df[f"Pareto front {_VARIES}"] = _pareto(df, f"sweep + derivative time [ms] {_VARIES}")
    df[_PARETO_WORK] = _pareto(df, _WORK)
    return _caption(
        df,
        f"Work and precision: {mechanism.name}, {quantity}, input speed {w:g} rad/s; work = point evaluations of "
        "the compiled loop equations (sweep, analytic and complex-step derivatives) plus stencil evaluations "
        f"(finite differences), exact and the same in every run; median times of {int(repeat)} repeats (vary "
        "between runs); beside the max error over the sweep.",
        _grid_positions(mechanism, {n: per_grid[n][1] for n in grid_list}, None),
    )


def _pareto(df, cost: str) -> list:
    """Rows on the Pareto front (`cost` column, max rel error) within their quantity.

    A row is on the front if no other row of its quantity costs no more and
    is no less accurate, and is strictly better in one of the two; rows
    without a finite cost and error are not on it.
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
        dominated = same & (t <= t[k]) & (e <= e[k]) & ((t < t[k]) | (e < e[k]))
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
        ``"time"``: the fastest by ``sweep + derivative time`` (measured, so
        the choice varies between runs). ``"work"``: the least ``work
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
        cost, tag = f"sweep + derivative time [ms] {_VARIES}", f" {_VARIES}"
        names = (f"cheapest method{tag}", f"points per turn{tag}", f"time [ms]{tag}", f"max rel error [-]{tag}")
        caption = "Cheapest method for a wanted accuracy (chosen by timings: varies between runs)."
    elif by == "work":
        cost = _WORK
        names = ("cheapest method", "points per turn", _WORK, "max rel error [-]")
        caption = ("Cheapest method for a wanted accuracy, by work (point evaluations of the compiled loop "
                   "equations plus stencil evaluations: the same in every run).")
    else:
        raise ValueError(f"by must be 'time' or 'work', got {by!r}")
    if cost not in work_precision.columns:
        raise ValueError(f"work_precision table has no column {cost!r}; columns are {list(work_precision.columns)}")
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
    return _caption(df, caption)


# ========================================================================== roundoff
_TEXTBOOK = {
    # (derivative, order) -> rule text
    (1, 1): "sqrt(eps)",
    (1, 2): "cbrt(eps)",
    (1, 4): "eps^(1/5)",
    (2, 1): "cbrt(eps)",
    (2, 2): "eps^(1/4)",
    (2, 4): "eps^(1/6)",
}


def roundoff_table(
    mechanism,
    *,
    quantity: str,
    check_angle: float,
    schemes: Sequence[str] = ROUNDOFF_SCHEMES,
    steps: Sequence[float] = ROUNDOFF_STEPS,
    scan_per_decade: int = 8,
    guess=None,
    start: float = 0.0,
):
    """Error against the step h at one input angle: truncation above, rounding below the optimum.

    The position at the check angle is the sweep's, continued from `start`
    (where `guess` applies) and solved to machine precision (Newton
    iterated until the step stops shrinking); from it, the positions at
    ``theta + k h`` for the stencil offsets k; each
    scheme of :mod:`numkin.derivatives` is applied to those samples, and
    ``"complex_step"`` solves the position at ``theta + i h``
    (:func:`numkin.analytic.complex_step`). Steps are rounded so that
    ``theta + h`` is a floating-point number, the classic remedy; what is
    left is the rounding of the position values, ~eps, divided by h (first
    derivative) or h**2 (second): the second difference at h = 1e-8 rad is
    wrong by orders of magnitude, and the table shows it.

    The optimum is measured on a finer scan (`scan_per_decade` steps per
    decade over the range of `steps`) and set beside the textbook estimate
    ``h* ~ eps**(1/(p + n))`` with error ``~ eps**(p/(p + n))`` (p the
    order, n the derivative: sqrt(eps) forward, cbrt(eps) centred,
    eps^(1/4) second difference, eps^(1/5) five-point).

    Parameters
    ----------
    mechanism : Mechanism
    quantity : str
        The unknown differentiated.
    check_angle : float
        Input angle (rad).
    schemes : sequence of str
        Scheme names, and ``"complex_step"``.
    steps : sequence of float
        Steps shown as columns, rad.
    scan_per_decade : int
        Density of the scan for the measured optimum.
    guess : optional
        Starting guess at `start` (default: the mechanism's); picks the branch.
    start : float
        Input (rad) where the sweep to the check angle starts.

    Returns
    -------
    pandas.DataFrame
        One row per scheme: ``scheme``, ``formal order``, ``quantity``
        (``dq/dtheta [rad/rad]`` or ``d2q/dtheta2 [rad/rad^2]``), ``exact
        value [unit of quantity]``, ``rel error at h = 1e-01 rad [-]`` ...
        (one column per step), ``measured optimal h [rad]``, ``rel error at
        measured optimal h [-]``, ``textbook rule``, ``textbook optimal h
        [rad]``, ``textbook error [-]``. Errors are relative to the exact
        value (absolute if it is exactly 0). ``attrs["positions"]`` holds
        the position at the check angle.

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> t = roundoff_table(linkages.chained_four_bars(), quantity="beta",
    ...                    check_angle=math.radians(100), schemes=("second_difference",))
    >>> bool(t["rel error at h = 1e-08 rad [-]"].iloc[0] > 1.0)   # wrong by more than 100 %
    True
    """
    import pandas as pd

    j = _index(mechanism, quantity)
    lab = _labels(mechanism, quantity)
    steps = [float(h) for h in steps]
    if not steps or not all(math.isfinite(h) and 0 < h < 1 for h in steps):
        raise ValueError(f"steps must be positive and below 1 rad, got {steps!r}")
    names = [schemes] if isinstance(schemes, str) else list(schemes)
    sch = [None if n == "complex_step" else get_scheme(n) for n in names]
    if any(s is not None and s.periodic_only for s in sch):
        raise ValueError("spectral schemes need a full periodic sweep; they have no step h at one angle")
    theta = float(check_angle)
    base = _one_point(mechanism, theta, guess, start)
    dq, d2q = _exact(base)
    x0, q1, q2 = base.values[:, 0], dq[:, 0], d2q[:, 0]
    lo, hi = math.log10(min(steps)), math.log10(max(steps))
    m = int(round((hi - lo) * scan_per_decade))
    scan = sorted(set(steps) | set(10.0 ** np.linspace(hi, lo, m + 1)), reverse=True)
    # representable steps: theta + h is a float and h = (theta + h) - theta exactly
    eff = np.array([(theta + h) - theta for h in scan])
    offsets = np.arange(-2, 3)
    tt = theta + eff[:, None] * offsets[None, :]  # (S, 5)
    dt = tt - theta
    pred = x0[:, None, None] + q1[:, None, None] * dt + 0.5 * q2[:, None, None] * dt**2
    S = len(scan)
    vals = _polish(mechanism, pred.reshape(len(x0), -1), tt.reshape(-1)).reshape(len(x0), S, 5)[j]
    vals[:, 2] = x0[j]
    rows = []
    shown = {h: k for k, h in enumerate(scan)}
    for name, scheme in zip(names, sch):
        err = np.empty(S)
        if scheme is None:
            deriv, order, exact = 1, None, q1[j]
            for k, h in enumerate(eff):
                one = _quiet(analytic.complex_step, base, h=float(h), order=1)
                err[k] = abs(one[j, 0] - exact)
        else:
            deriv, order = scheme.derivative, scheme.order
            exact = q1[j] if deriv == 1 else q2[j]
            for k, h in enumerate(eff):
                err[k] = abs(scheme.function(vals[k], float(h), periodic=False)[2] - exact)
        rel = err / abs(exact) if exact != 0 else err  # an exact zero: absolute errors
        row = {
            "scheme": "complex step" if scheme is None else scheme.name,
            "formal order": "2" if scheme is None else _order_text(scheme),
            "quantity": lab["d1"] if deriv == 1 else lab["d2"],
            f"exact value {_UNIT}": float(exact),
        }
        for h in steps:
            row[f"rel error at h = {h:.0e} rad [-]"] = float(rel[shown[h]])
        best = int(np.argmin(rel))
        row["measured optimal h [rad]"] = float(eff[best])
        row["rel error at measured optimal h [-]"] = float(rel[best])
        if scheme is None:
            row["textbook rule"] = "any h <= sqrt(eps): no cancellation"
            row["textbook optimal h [rad]"] = math.sqrt(EPS)
            row["textbook error [-]"] = EPS
        else:
            p, n = order, deriv
            row["textbook rule"] = _TEXTBOOK.get((n, p), f"eps^(1/{p + n})")
            row["textbook optimal h [rad]"] = EPS ** (1.0 / (p + n))
            row["textbook error [-]"] = EPS ** (p / (p + n))
        rows.append(row)
    df = pd.DataFrame(rows)
    caption = (
        f"Round-off floor: {mechanism.name}, {quantity} at {lab['input']} = {_deg_text(theta)} deg; relative "
        "error against the step h, positions solved to machine precision."
    )
    zero = [lab["d1"] if abs(v) <= 1e-12 * (abs(x0[j]) + 1.0) else None for v in (q1[j],)] + [
        lab["d2"] if abs(q2[j]) <= 1e-12 * (abs(x0[j]) + 1.0) else None
    ]
    zero = [z for z in zero if z]
    if zero:
        caption += (
            f" The exact {' and '.join(zero)} is 0 at this angle: errors are absolute, and symmetric stencils "
            "may be exact by symmetry; choose another angle to see the round-off floor."
        )
    return _caption(df, caption, [_position("check angle", mechanism, theta, x0)])


# ============================================================================ Newton
def _solve_points(mechanism, check_angle, start_offset, guess, start) -> tuple:
    """``(x_start, x_star)``: the sweep's positions at ``check_angle - start_offset`` and at `check_angle`.

    Both on the branch of the sweep from `start` (where `guess` applies),
    polished to machine precision: the starting point of one Newton solve
    and the solution it should reach.
    """
    x_start = _one_point(mechanism, check_angle - start_offset, guess, start).values[:, 0]
    x_star = _one_point(mechanism, check_angle, guess, start).values[:, 0]
    return x_start, x_star


def _solve_positions(mechanism, check_angle, start_offset, x_start, solves) -> list:
    """``attrs["positions"]`` of a table of Newton solves: the start, then each solve's result."""
    out = [_position("start of the solve", mechanism, check_angle - start_offset, x_start)]
    out += [_position(f"{what} solve", mechanism, check_angle, x) for what, x in solves]
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
    """A solve and its iterates: (NewtonResult, iterates (n, k+1))."""
    res = mechanism.solve(check_angle, x_start, jacobian=jacobian, tol=tol, maxiter=maxiter)
    iterates = [np.asarray(x_start, dtype=float)]
    for k in range(1, res.iterations + 1):
        iterates.append(mechanism.solve(check_angle, x_start, jacobian=jacobian, tol=tol, maxiter=k).x)
    return res, np.array(iterates).T


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
    measured against (polished to machine precision) are the sweep's,
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
    return _caption(
        df,
        f"Newton iterations: {mechanism.name} at {mechanism.input_symbol} = {_deg_text(check_angle)} deg, "
        f"{jacobian} Jacobian, started from the solution at {_deg_text(check_angle - start_offset)} deg "
        f"({res.message}).",
        _solve_positions(mechanism, check_angle, start_offset, x_start, [(jacobian, res.x)]),
    )


def jacobian_table(
    mechanism,
    *,
    check_angle: float,
    points_per_turn: int = 360,
    repeat: int = 3,
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
    repeat : int
        Timing repeats.
    start_offset, start, span, guess
        As in :func:`newton_table` and :func:`convergence_table`.

    Returns
    -------
    pandas.DataFrame
        Rows ``symbolic``, ``forward``, ``central``; columns ``Jacobian``,
        ``iterations (one solve)``, ``order estimate, last (one solve) [-]``,
        ``final residual (one solve) [-]``, ``final error (one solve) [-]``,
        ``sweep time [ms] (varies)``, ``Newton iterations (sweep total)``,
        ``max difference from symbolic sweep [-]`` (scaled max-norm).

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> t = jacobian_table(linkages.four_bar(4, 1, 3, 3), check_angle=math.radians(90), points_per_turn=36, repeat=1)
    >>> list(t["Jacobian"])
    ['symbolic', 'forward', 'central']
    """
    import pandas as pd

    x_start, x_star = _solve_points(mechanism, check_angle, start_offset, guess, start)
    inputs = _grid(points_per_turn, start, span)
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
            return _sweep(mechanism, inputs, guess, jacobian=jac)

        s = run()
        if ref is None:
            ref = s.values
        rows.append(
            {
                "Jacobian": jac,
                "iterations (one solve)": res.iterations,
                "order estimate, last (one solve) [-]": float(finite[-1]) if finite.size else math.nan,
                "final residual (one solve) [-]": float(res.residual_norms[-1]),
                "final error (one solve) [-]": float(errors[-1]),
                f"sweep time [ms] {_VARIES}": 1e3 * _median_time(run, repeat),
                "Newton iterations (sweep total)": int(np.sum(s.iterations)),
                "max difference from symbolic sweep [-]": float(
                    np.max(np.abs(s.values - ref) / mechanism.xscale[:, None])
                ),
            }
        )
    df = pd.DataFrame(rows)
    return _caption(
        df,
        f"Jacobian choice: {mechanism.name}; one solve at {_deg_text(check_angle)} deg and a sweep of "
        f"{int(points_per_turn)} points per turn (times vary between runs).",
        _solve_positions(mechanism, check_angle, start_offset, x_start, solved),
    )


# ========================================================================= tolerance
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
      rule: on the homework it stops after about one step per loop;
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
        raise ValueError(f"rule must be one of {list(STUDENT_RULES)}, got {rule!r}")
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
        raise ValueError(f"tol must be a positive number, got {tol!r}")
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

    Returns the number of steps taken, or None if `maxiter` steps did not
    meet the rule.
    """
    for it in range(maxiter + 1):
        f = comp.F(x[:, None], tk, p)[:, 0]
        if rule == "residual" and np.max(np.abs(f)) < tol:
            return it
        if it == maxiter:
            return None
        dx = np.linalg.solve(comp.J(x[:, None], tk, p)[0][block, block], -f[block])
        x[block] += dx
        size = np.linalg.norm(dx)
        if rule == "relative":
            size /= np.linalg.norm(x[block])
        if rule != "residual" and size < tol:
            return it + 1
    return None  # pragma: no cover - the loop returns at it == maxiter


def _percent(value, exact, exact_all) -> float:
    """100 |value - exact| / |exact|; NaN where the exact value is zero (below 1e-12 of its peak)."""
    if not abs(exact) > 1e-12 * float(np.max(np.abs(exact_all))):
        return math.nan
    return 100.0 * float(abs(value - exact) / abs(exact))


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
):
    """What a loose stopping rule does to differenced velocity and acceleration.

    The sweep (`points_per_turn`, one full turn) is solved five ways: by
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
        The unknown studied.
    check_angle : float
        Input angle (rad) of the point values; must be on the grid.
    points_per_turn : int
        Points per turn (a full turn is swept).
    loose_tol : float
        Tolerance of the loose rules.
    method, second_method : str
        Finite-difference schemes for omega and alpha.
    start, guess
        First input (rad) and starting guess.

    Returns
    -------
    pandas.DataFrame
        Rows: the analytic reference, then the five solves. Columns
        ``stopping rule``, ``tol`` (in the rule's own terms), ``Newton iterations per point
        (mean)``, ``max |F| [length unit]``, ``position error estimate
        max|J^-1 F| [unit]`` (of the quantity, the size of the Newton step
        still missing), the velocity and acceleration at the check angle
        with their relative errors [%] (blank where the exact value is 0),
        their largest relative errors over
        the sweep [%] (over max |exact|) and where the acceleration error is
        largest [deg], and ``note`` (a branch change is named there).

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

    w = _omega(omega)
    j = _index(mechanism, quantity)
    lab = _labels(mechanism, quantity)
    s1, s2 = get_scheme(method), get_scheme(second_method)
    if s1.derivative != 1 or s2.derivative != 2:
        raise ValueError("method must be a first-derivative scheme and second_method a second-derivative one")
    inputs = _grid(points_per_turn, start, TURN)
    k = _check_index(inputs, check_angle)
    if k is None:
        raise ValueError(
            f"check_angle {math.degrees(check_angle):.6g} deg is not on the {points_per_turn}-point grid from "
            f"{math.degrees(start):.6g} deg"
        )
    ref = _sweep(mechanism, inputs, guess, quiet=False)
    dq, d2q = _exact(ref, quiet=False)
    w_ex, a_ex = w * dq[j], w * w * d2q[j]
    deg = _deg_text(check_angle)
    at = f"at {lab['input']} = {deg} deg"
    cols = {
        "w": f"{lab['name1']} {at} [{lab['unit1']}]",
        "we": f"{lab['name1']} rel error {at} [%]",
        "a": f"{lab['name2']} {at} [{lab['unit2']}]",
        "ae": f"{lab['name2']} rel error {at} [%]",
        "wm": f"{lab['name1']} max rel error [%]",
        "am": f"{lab['name2']} max rel error [%]",
        "where": f"{lab['name2']} largest error at {lab['input']} [deg]",
    }
    lu = mechanism.length_unit
    rows = [
        {
            "stopping rule": "analytic (reference, on the tol = 1e-12 sweep)",
            "tol": math.nan,
            "Newton iterations per point (mean)": math.nan,
            f"max |F| [{lu}]": math.nan,
            f"position error estimate max|J^-1 F| [{lab['unit']}]": math.nan,
            cols["w"]: float(w_ex[k]),
            cols["we"]: 0.0,
            cols["a"]: float(a_ex[k]),
            cols["ae"]: 0.0,
            cols["wm"]: 0.0,
            cols["am"]: 0.0,
            cols["where"]: math.nan,
            "note": "",
        }
    ]
    solves = [
        (_RULE_LABELS[rule], loose_tol,
         lambda rule=rule: student_sweep(mechanism, inputs, rule=rule, tol=loose_tol, guess=guess))
        for rule in STUDENT_RULES
    ] + [
        (f"numkin sweep, tol = {loose_tol:g}: scaled residual <= tol, step <= tol^(2/3) = {loose_tol ** (2 / 3):.3g} "
         "(passes at once: in effect a residual rule)", loose_tol,
         lambda: _sweep(mechanism, inputs, guess, tol=loose_tol)),
        ("numkin sweep, tol = 1e-12 (default)", 1e-12, lambda: ref),
    ]
    comp, p = mechanism.compiled, mechanism.parameter_values
    angle_rows = np.array([u in mechanism.angles for u in mechanism.unknowns])
    positions = []
    for label, tol, solve in solves:
        try:
            s = solve()
        except (RuntimeError, ValueError, NumkinError) as exc:  # a loose solver that fails is a result too
            rows.append({**{c: math.nan for c in rows[0]}, "stopping rule": label, "tol": float(tol),
                         "note": f"failed: {exc}"})
            continue
        positions.append(_position(label, mechanism, inputs[k], s.values[:, k]))
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
                d1 = w * _derivative(s, s1)[j]
                d2 = w * w * _derivative(s, s2)[j]
            except ValueError as exc:  # e.g. a student sweep that does not close after one turn
                d1 = d2 = np.full(inputs.size, math.nan)
                note = (note + "; " if note else "") + f"not differenced: {exc}"
        rows.append(
            {
                "stopping rule": label,
                "tol": float(tol),
                "Newton iterations per point (mean)": float(np.mean(s.iterations)),
                f"max |F| [{lu}]": float(np.max(np.abs(f))),
                f"position error estimate max|J^-1 F| [{lab['unit']}]": float(np.max(np.abs(step[j]))),
                cols["w"]: float(d1[k]),
                cols["we"]: _percent(d1[k], w_ex[k], w_ex),
                cols["a"]: float(d2[k]),
                cols["ae"]: _percent(d2[k], a_ex[k], a_ex),
                cols["wm"]: 100.0 * float(np.max(np.abs(d1 - w_ex)) / np.max(np.abs(w_ex))),
                cols["am"]: 100.0 * float(np.max(np.abs(d2 - a_ex)) / np.max(np.abs(a_ex))),
                cols["where"]: (
                    math.degrees(float(inputs[int(np.nanargmax(np.abs(d2 - a_ex)))]))
                    if np.any(np.isfinite(d2)) else math.nan
                ),
                "note": note,
            }
        )
    df = pd.DataFrame(rows)
    return _caption(
        df,
        f"Solver tolerance: {mechanism.name}, {quantity}, {int(points_per_turn)} points per turn, input speed {w:g} rad/s; "
        f"omega by {s1.name}, alpha by {s2.name}, against the analytic values.",
        positions,
    )


# ============================================================================= report
def full_report(
    mechanism,
    *,
    omega,
    quantity: str,
    check_angle: float,
    grids: Iterable[int] = DEFAULT_GRIDS,
    schemes: Sequence[str] | None = None,
    points_per_turn: int = 360,
    repeat: int = 3,
    start: float = 0.0,
    guess=None,
) -> dict:
    """Every table of this module for one mechanism, in a fixed order.

    Parameters
    ----------
    mechanism : Mechanism
    omega : float or str
        Input speed (rad/s or a string with units).
    quantity : str
        The unknown studied.
    check_angle : float
        Input angle (rad) of the point values, the round-off scan and the
        Newton solve; it should lie on every grid.
    grids : iterable of int
        Points per turn for the convergence and work-precision tables.
    schemes : sequence of str, optional
        Finite-difference schemes (default all).
    points_per_turn : int
        Points per turn of the Jacobian and tolerance sweeps.
    repeat : int
        Timing repeats.
    start : float
        First input angle, rad.
    guess : optional
        Starting guess at `start` (default: the mechanism's); picks the branch of every table.

    Returns
    -------
    dict
        name -> DataFrame: ``convergence``, ``work_precision``,
        ``cheapest``, ``roundoff``, ``newton``, ``jacobian``, ``tolerance``.

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> tables = full_report(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                      check_angle=0.0, grids=(36, 72), schemes=("centred",), points_per_turn=36, repeat=1)
    >>> list(tables)
    ['convergence', 'work_precision', 'cheapest', 'roundoff', 'newton', 'jacobian', 'tolerance']
    """
    wp = work_precision_table(
        mechanism, omega=omega, quantity=quantity, grids=grids, schemes=schemes, repeat=repeat, start=start,
        guess=guess,
    )
    return {
        "convergence": convergence_table(
            mechanism, omega=omega, quantity=quantity, check_angle=check_angle, grids=grids, schemes=schemes,
            start=start, guess=guess,
        ),
        "work_precision": wp,
        "cheapest": cheapest_table(wp),
        "roundoff": roundoff_table(mechanism, quantity=quantity, check_angle=check_angle, guess=guess, start=start),
        "newton": newton_table(mechanism, check_angle=check_angle, guess=guess, start=start),
        "jacobian": jacobian_table(
            mechanism, check_angle=check_angle, points_per_turn=points_per_turn, repeat=repeat, start=start, guess=guess
        ),
        "tolerance": tolerance_table(
            mechanism, omega=omega, quantity=quantity, check_angle=check_angle, points_per_turn=points_per_turn, start=start,
            guess=guess,
        ),
    }


# ============================================================================ writing
def _cell(value) -> str:
    """One table cell as text: 6 significant digits, blanks for NaN, yes/no for booleans."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        if math.isnan(value):
            return ""
        return f"{float(value):.6g}"
    return "" if value is None else str(value)


_TEX_SPECIAL = {
    "\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
    "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "|": r"\textbar{}", "<": r"\textless{}",
    ">": r"\textgreater{}", "°": r"\textdegree{}",
}


def _tex(text: str) -> str:
    """Escape text for LaTeX; ``^2`` and ``^(1/4)`` become superscripts."""
    import re

    out = []
    parts = re.split(r"(\^\([^)]*\)|\^-?\d+)", text)
    for part in parts:
        if part.startswith("^"):
            out.append(r"\textsuperscript{" + "".join(_TEX_SPECIAL.get(c, c) for c in part[1:].strip("()")) + "}")
        else:
            out.append("".join(_TEX_SPECIAL.get(c, c) for c in part))
    return "".join(out)


def _booktabs(df, name: str) -> str:
    """A LaTeX table with booktabs rules (needs \\usepackage{booktabs}); no jinja2."""
    numeric = [
        df[c].dtype.kind in "iuf" for c in df.columns
    ]
    spec = "".join("r" if isnum else "l" for isnum in numeric)
    lines = [
        "% needs \\usepackage{booktabs}",
        "\\begin{table}[htbp]",
        "\\centering",
    ]
    caption = df.attrs.get("caption")
    if caption:
        lines.append("\\caption{" + _tex(caption) + "}")
    lines.append("\\label{tab:" + name.replace("_", "-") + "}")
    lines.append("\\begin{tabular}{" + spec + "}")
    lines.append("\\toprule")
    lines.append(" & ".join(_tex(str(c)) for c in df.columns) + " \\\\")
    lines.append("\\midrule")
    for row in df.itertuples(index=False):
        lines.append(" & ".join(_tex(_cell(v)) for v in row) + " \\\\")
    lines.append("\\bottomrule")
    lines.append("\\end{tabular}")
    lines.append("\\end{table}")
    return "\n".join(lines) + "\n"


def _require_tabulate() -> None:
    try:
        import tabulate  # noqa: F401  (pandas.DataFrame.to_markdown needs it)
    except ImportError:
        raise ImportError(
            "writing Markdown tables needs the 'tabulate' package (pip install tabulate); "
            "or call write_tables(..., formats=('csv', 'tex'))"
        ) from None


def _markdown(df) -> str:
    _require_tabulate()
    align = ["right" if df[c].dtype.kind in "iuf" else "left" for c in df.columns]
    text = df.map(_cell).to_markdown(index=False, disable_numparse=True, colalign=align)
    caption = df.attrs.get("caption")
    return (f"{caption}\n\n" if caption else "") + text + "\n"


def write_tables(tables: Mapping, out_dir, formats: Sequence[str] = ("md", "csv", "tex")) -> list:
    """Write tables as Markdown, CSV and LaTeX (booktabs) files, one file per table and format.

    Parameters
    ----------
    tables : mapping
        name -> DataFrame (e.g. from :func:`full_report`); the name is the file stem.
    out_dir : str or Path
        Directory, created if needed.
    formats : sequence of {"md", "csv", "tex"}
        Markdown (``DataFrame.to_markdown``, needs ``tabulate``), CSV (full
        precision, empty cells for NaN) and LaTeX with booktabs rules. A
        table's ``attrs["caption"]`` heads the Markdown and becomes the
        LaTeX caption.

    Returns
    -------
    list of Path
        The files written, table by table in the mapping's order, formats
        in the given order.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> df = pd.DataFrame({"h [deg]": [1.0, 0.5], "max abs error [rad/s]": [2e-4, 5e-5]})
    >>> with tempfile.TemporaryDirectory() as d:
    ...     [p.name for p in write_tables({"demo": df}, d, formats=("csv", "tex"))]
    ['demo.csv', 'demo.tex']
    """
    allowed = ("md", "csv", "tex")
    formats = [formats] if isinstance(formats, str) else list(formats)
    bad = [f for f in formats if f not in allowed]
    if bad:
        raise ValueError(f"unknown table format(s) {bad}; choose from {list(allowed)}")
    if "md" in formats:
        _require_tabulate()  # fail before any file is written
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, df in tables.items():
        for fmt in formats:
            path = out / f"{name}.{fmt}"
            if fmt == "md":
                text = _markdown(df)
            elif fmt == "csv":
                text = df.to_csv(index=False)
            else:
                text = _booktabs(df, str(name))
            path.write_text(text, encoding="utf-8")
            written.append(path)
    return written

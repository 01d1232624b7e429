"""What every error-analysis table shares: settings, grids, labels, branch points, captions.

The table modules of :mod:`numkin.report` (:mod:`~numkin.report.convergence`,
:mod:`~numkin.report.workprecision`, :mod:`~numkin.report.roundoff`,
:mod:`~numkin.report.newton_tables`, :mod:`~numkin.report.tolerance`) build on
these: the input speed and the unknown studied, checked once; the grids in
points per turn; the names and units of the quantities; sweeps and one-point
solves on the branch of the sweep from the starting guess (:func:`branch_point`),
polished to machine precision; the caption and the solved positions a table
carries in ``DataFrame.attrs``.

Examples
--------
>>> import math
>>> from numkin import linkages
>>> mech = linkages.chained_four_bars()
>>> quantity_labels(mech, "beta")[1], unknown_index(mech, "beta")
('omega_beta [rad/s]', 2)
>>> grid_inputs(36, 0.0, TURN).size                 # a full turn: N + 1 samples
37
>>> point = branch_point(mech, math.radians(100))   # continued from the guess at 0 deg
>>> round(math.degrees(float(point["beta"][0])) % 360, 4)
214.727
"""

from __future__ import annotations

import math
import statistics
import time
import warnings
from typing import Callable, Mapping, Sequence

import numpy as np

from .. import analytic, kinematics, units
from ..derivatives import SCHEMES, get_scheme
from ..sweep import Sweep

__all__ = [
    "EPS",
    "TURN",
    "DEFAULT_GRIDS",
    "UNIT",
    "VARIES",
    "input_speed",
    "unknown_index",
    "quantity_labels",
    "deg_text",
    "scheme_list",
    "full_turn",
    "grid_inputs",
    "grid_list",
    "grid_study",
    "check_index",
    "silenced",
    "median_time",
    "polish",
    "solve_sweep",
    "branch_point",
    "position_record",
    "differenced",
    "exact_derivatives",
    "order_text",
    "set_caption",
    "grid_positions",
]

EPS = float(np.finfo(float).eps)
TURN = 2.0 * math.pi
#: Default grids, in points per turn of the input.
DEFAULT_GRIDS = (36, 72, 180, 360, 720, 1440, 3600)
#: Column names of absolute errors say this unit.
UNIT = "[unit of quantity]"
#: Column names of timings (and of what is chosen by them) say this: they vary between runs.
VARIES = "(varies)"


def input_speed(omega) -> float:
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


def unknown_index(mechanism, quantity: str) -> int:
    if quantity not in mechanism.unknowns:
        raise ValueError(
            f"quantity {quantity!r} is not an unknown of {mechanism.name}; choose one of {list(mechanism.unknowns)}"
        )
    return mechanism.unknowns.index(quantity)


def quantity_labels(mechanism, quantity: str) -> dict:
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


def deg_text(angle: float) -> str:
    return f"{math.degrees(angle):.6g}"


def scheme_list(names, periodic: bool | None = None) -> list:
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


def full_turn(span: float) -> bool:
    """Whether an input range of `span` rad is one full turn (a periodic grid)."""
    return abs(span - TURN) <= 1e-12 * TURN


def grid_inputs(points: int, start: float, span: float) -> np.ndarray:
    """Inputs of a grid with `points` per turn: a full turn (N + 1 samples) or `span` rad."""
    if isinstance(points, bool) or int(points) != points or points < 4:
        raise ValueError(f"points per turn must be an integer >= 4, got {points!r}")
    points = int(points)
    h = TURN / points
    if full_turn(span):
        return start + h * np.arange(points + 1)
    if not (0 < span < TURN):
        raise ValueError(f"span must be in (0, 2 pi] rad, got {span!r}")
    count = int(math.floor(span / h + 1e-9)) + 1
    if count < 5:
        raise ValueError(f"span {math.degrees(span):.4g} deg holds fewer than 5 points of a {points}-point grid")
    return start + h * np.arange(count)


def grid_list(grids) -> list:
    if isinstance(grids, (int, np.integer)):
        grids = [grids]
    out = [int(g) for g in grids]
    if not out:
        raise ValueError("grids must name at least one grid (points per turn)")
    return out


def grid_study(mechanism, omega, quantity: str, grids, span: float, schemes) -> tuple:
    """The checked arguments of a study over grids: ``(w, j, labels, grids, periodic, schemes)``.

    `w` is the input speed in rad/s, `j` the index of `quantity` among the
    unknowns, `periodic` whether `span` is a full turn.
    """
    w = input_speed(omega)
    j = unknown_index(mechanism, quantity)
    lab = quantity_labels(mechanism, quantity)
    periodic = full_turn(span)
    return w, j, lab, grid_list(grids), periodic, scheme_list(schemes, periodic)


def check_index(inputs: np.ndarray, angle: float | None) -> int | None:
    """Index of the grid point at `angle` (mod 2 pi), or None if the grid does not hold it."""
    if angle is None:
        return None
    d = np.abs(np.remainder(inputs - angle + math.pi, TURN) - math.pi)
    k = int(np.argmin(d))
    return k if d[k] <= 1e-9 else None


def silenced(fn, *args, **kwargs):
    """Call fn with numkin's warnings silenced (callers report what matters in the tables)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*args, **kwargs)


def median_time(fn: Callable[[], object], repeat: int, warmup: bool = True) -> float:
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


def polish(mechanism, x, t, *, max_iterations: int = 30):
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


def solve_sweep(mechanism, inputs, guess=None, *, quiet: bool = True, **kwargs) -> Sweep:
    """A sweep; with ``quiet=False`` its warnings (near-singular points, ...) reach the caller."""
    if quiet:
        return silenced(mechanism.sweep, inputs, guess, **kwargs)
    return mechanism.sweep(inputs, guess, **kwargs)


def branch_point(mechanism, angle: float, guess=None, start: float = 0.0) -> Sweep:
    """A one-point sweep at `angle` on the branch of the sweep from `start`, polished to machine precision.

    `guess` is the starting guess at `start` (as for every sweep of this
    module: default the mechanism's own); the point is reached by
    continuation from `start` to `angle`, never by applying the guess at
    `angle`, so that it lies on the branch the tables' sweeps follow.
    """
    a, s0 = float(angle), float(start)
    inputs = np.array([s0]) if a == s0 else np.array([s0, a])
    s = solve_sweep(mechanism, inputs, guess)
    last = slice(inputs.size - 1, inputs.size)
    x = polish(mechanism, s.values[:, last], s.inputs[last])
    return Sweep(mechanism, s.inputs[last], x, s.iterations[last], s.residual[last], s.cond[last], list(s.events),
                 s.jacobian, s.tol)


def position_record(what: str, mechanism, angle: float, x) -> dict:
    """One solved position of a table, as kept in ``DataFrame.attrs["positions"]``."""
    x = np.asarray(x, dtype=float).reshape(-1)
    return {"what": what, "input [rad]": float(angle), **{u: float(v) for u, v in zip(mechanism.unknowns, x)}}


def differenced(sweep: Sweep, scheme, quiet: bool = True) -> np.ndarray:
    """d/dtheta (or d2/dtheta2) of every unknown of `sweep` by the finite-difference `scheme` (a Scheme)."""
    if quiet:
        return silenced(kinematics.sweep_derivative, sweep, scheme.name)
    return kinematics.sweep_derivative(sweep, scheme.name)


def exact_derivatives(sweep: Sweep, quiet: bool = True) -> tuple:
    """The analytic ``(dq/dtheta, d2q/dtheta2)`` of `sweep` (:func:`numkin.analytic.derivatives`)."""
    return silenced(analytic.derivatives, sweep) if quiet else analytic.derivatives(sweep)


def order_text(scheme) -> str:
    return "spectral" if scheme.order == 0 else str(scheme.order)


def set_caption(df, text: str, positions: Sequence[dict] | None = None):
    """Set a table's caption and, if given, the positions it was computed at (``attrs["positions"]``)."""
    df.attrs["caption"] = text
    if positions is not None:
        df.attrs["positions"] = list(positions)
    return df


def grid_positions(mechanism, sweeps: Mapping, angle: float | None) -> list:
    """``attrs["positions"]`` of a table of sweeps: each sweep at `angle` (or its middle sample, if None)."""
    out = []
    for n, s in sweeps.items():
        k = s.inputs.size // 2 if angle is None else check_index(s.inputs, angle)
        if k is not None:
            out.append(position_record(f"{n} points per turn", mechanism, s.inputs[k], s.values[:, k]))
    return out

"""Position sweeps by continuation, on one assembly branch.

Algorithm
---------
1. Solve at the first input from the guess, loop after loop, each loop from
   its own guess with the loops before it solved (Newton, up to ``maxiter``
   steps a loop, refusing near-singular Jacobians: a poor guess for one loop
   then moves no later loop off the branch its guess is on); the angles are
   then reduced to the guess's turn and polished by further Newton steps, so
   the first point is as accurate as every other.
2. March sequentially to *nodes*, grid points about ``max_step`` apart (30°
   by default): each step predicts with the tangent ``q' = -J^-1 dF/dt``
   (and the previous point and its tangent, a cubic, or the previous point
   alone, a quadratic, only when that point is a sane distance away and the
   added terms stay below the step times the tangent) and corrects with
   Newton (its updates written out for the mechanism's loops). The predicted change of every unknown
   is at most :data:`MAX_PREDICTION` (scaled), so no prediction can reach
   another turn. The corrected angles are taken nearest the prediction.
   A step is accepted only if Newton converges, the correction is small
   (:data:`MAX_CORRECTION`) and the sign of every loop's Jacobian
   determinant (its *orientation*, constant along a branch) is unchanged
   and the tangent differs by at most :data:`MAX_TANGENT_TURN` (1 + ``|q'|``)
   from the one expected (the last tangent, extrapolated linearly through
   the one before when that is at most :data:`TREND_REACH` steps back)
   (where two branches meet, the other one keeps the orientation, and only
   the kink in the tangent shows the switch; next to a singular position,
   where the tangent is noise, neither shows it, so such a step is
   localised like a crossing);
   otherwise the step is halved, so a large ``max_step`` costs no safety and
   a small one loses none. A change of orientation is localised to
   :data:`CROSSING_STEP` and placed where the determinant, linear between
   the two points, is zero.
3. Fill the grid points between nodes in one batch: a Hermite predictor from
   the nodes' values and tangents (cubic), and, where the segments hold many
   points, their curvatures too (quintic); with fewer points, the quintic on
   curvatures found from the neighbouring nodes where it is expected to save a
   Newton iteration; on an even grid round a whole turn, the trigonometric
   polynomial through the nodes where its highest harmonics show it is
   accurate (:mod:`numkin.turn_predictor`); then Newton on all points at once.
   A point that fails the same acceptance tests (converged, small
   correction, the orientation of its nodes) is re-solved sequentially from
   its neighbour; a segment between two nodes where neighbouring batch
   points differ by half a turn or more (a run of points on another turn)
   is marched sequentially point by point.

The sequential steps work on plain floats (``math``-module functions, the
Jacobian's block-triangular shape solved by Cramer's rule per loop), the
batch on numpy arrays; both apply the stopping rule and the conditioning
rule of :mod:`numkin.newton`. Every loop is bounded.

A change of orientation between two accepted points means the linkage passed
a singular position (a change point, where branches meet); a step that
shrinks to nothing where the Jacobian is ill-conditioned (or has become so
along the step) is a limit (toggle) position. Both raise
:class:`~numkin.BranchError` (or, with ``on_singular="report"``, a change
point is recorded in ``Sweep.events`` with a warning naming the branch
kept, the one whose tangent is continuous, and the sweep goes on; a toggle
cannot be passed). A Newton that fails elsewhere raises
:class:`~numkin.ConvergenceError`; a linkage that cannot be assembled at the
start raises :class:`~numkin.AssemblyError` (``cause`` says whether the
guess was poor or the equations dependent).
"""

from __future__ import annotations

import math

import numpy as np

from .batch_fill import fill, nodes_of, report_near_singular
from .errors import DegreesWarning, InputError, warn
from .first_point import solve_start
from .march import CROSSING_STEP, DEFAULT_MAX_STEP, MAX_CORRECTION, MAX_TANGENT_TURN, TREND_REACH, Continuation
from .newton import JACOBIANS, check_tol
from .predictors import MAX_PREDICTION
from .sweep import Sweep, record_evaluations
from .units import deg_text, number_array

__all__ = ["run_sweep", "DEFAULT_MAX_STEP", "MAX_CORRECTION", "MAX_PREDICTION", "MAX_TANGENT_TURN", "TREND_REACH",
           "CROSSING_STEP", "EVEN_STEPS"]


#: Relative spread of the input steps up to which a grid counts as evenly spaced: its batch points are
#: predicted at ``j / every`` of their segments (:func:`numkin.predictors.hermite_uniform`).
EVEN_STEPS = 1e-9


def _validate_inputs(inputs):
    """The inputs as a float array, checked; the largest step between neighbours (0.0 for one input); and
    whether the steps are all equal to :data:`EVEN_STEPS` of it (an evenly spaced grid)."""
    if type(inputs) is np.ndarray and inputs.dtype == np.float64:  # what np.asarray would return
        t = inputs
    else:
        t = number_array(inputs, "inputs must be numbers (input values, rad)")
    if t.ndim == 0:
        t = t.reshape(1)
    if t.ndim != 1 or t.size == 0:
        raise InputError(f"inputs must be a non-empty 1-D array of input values (rad), got shape {t.shape}")
    if not math.isfinite(np.add.reduce(t)):
        raise InputError(f"inputs[{int(np.flatnonzero(~np.isfinite(t))[0])}] is not finite")
    if t.size == 1:
        return t, 0.0, True
    d = t[1:] - t[:-1]  # finite or infinite, never NaN: the sum above was finite
    low = np.minimum.reduce(d)
    if low > 0:
        high = float(np.maximum.reduce(d))
        return t, high, high - low <= EVEN_STEPS * high
    high = np.maximum.reduce(d)
    if high < 0:
        return t, float(-low), high - low <= EVEN_STEPS * -low
    k = int(np.flatnonzero(np.sign(d) != np.sign(d[0]))[0]) if np.any(d != 0) else 0
    raise InputError(f"inputs must be strictly monotonic for continuation (check inputs[{k}:{k + 2}] = "
                     f"{t[k]:g}, {t[k + 1]:g} rad: {deg_text(t[k], 4)}, {deg_text(t[k + 1], 4)})")


def _warn_if_degrees(mech, t) -> None:
    """A :class:`~numkin.errors.DegreesWarning` where the inputs of an angle look like degrees: steps of at least
    0.5 over a range of 90 or more from and to multiples of 0.5 (``np.linspace(0, 360, 100)``; in rad, more than
    14 turns in steps of 29° or more), or whole numbers in steps of at least 1 over a range of 30 or more
    (``np.arange(30, 61)``: in rad, nearly five turns in steps of 57°; a range of 20, three turns, is left
    alone)."""
    span = abs(t[-1] - t[0]) if t.size >= 3 else 0.0
    if span < 30.0 or not getattr(mech, "input_is_angle", True):
        return
    steps = np.abs(np.diff(t))
    low = steps.min()
    round_ends = float(2.0 * t[0]).is_integer() and float(2.0 * t[-1]).is_integer()
    if not (low >= 0.5 and span >= 90.0 and round_ends or low >= 1.0 and np.array_equal(t, np.round(t))):
        return
    step = float(steps.min())
    warn(DegreesWarning(
        f"{mech.name}: the inputs run from {t[0]:g} to {t[-1]:g} in steps of {step:g}; if the input is an angle, "
        f"that is {abs(t[-1] - t[0]) / (2 * math.pi):.3g} turns in steps of {math.degrees(step):.4g}°: input angles "
        "are in rad (np.radians converts degrees)"
    ))


def run_sweep(mech, inputs, guess=None, *, jacobian="symbolic", tol=1e-12, maxiter=50,
              max_step=DEFAULT_MAX_STEP, on_singular="raise", progress=False):
    """Solve ``mech`` over ``inputs`` by continuation; see :meth:`Mechanism.sweep`.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> s = run_sweep(linkages.four_bar(4, 1, 3, 3), np.radians([0.0, 90.0]))
    >>> np.round(np.degrees(s["theta4"]), 4)
    array([120.    , 119.3714])
    """
    if on_singular not in ("raise", "report"):
        raise InputError(f"on_singular must be 'raise' or 'report', got {on_singular!r}")
    if max_step is None:
        max_step = DEFAULT_MAX_STEP
    if not (isinstance(max_step, (int, float, np.number)) and max_step > 0 and math.isfinite(max_step)):
        raise InputError(f"max_step must be a positive angle in rad, got {max_step!r}")
    tol = check_tol(tol)
    if isinstance(maxiter, bool) or not isinstance(maxiter, (int, np.integer)) or maxiter < 1:
        raise InputError(f"maxiter must be a positive integer, got {maxiter!r}")
    if jacobian not in JACOBIANS:
        raise InputError(f"jacobian must be one of {JACOBIANS}, got {jacobian!r}")
    t, largest_step, evenly = _validate_inputs(inputs)
    _warn_if_degrees(mech, t)
    mech.check_assembly(t)
    ctx = Continuation(mech, jacobian, tol, float(max_step), on_singular)
    n, N = ctx.n, t.size
    X = np.empty((n, N))
    D = np.empty((n, N))
    D.fill(np.nan)
    O = np.zeros((len(mech.loops), N))
    iters = np.zeros(N, dtype=int)

    with np.errstate(all="ignore"):
        x0, iters[0], d0, o0 = solve_start(ctx, float(t[0]), guess, maxiter)
        X[:, 0], D[:, 0], O[:, 0] = x0, d0, o0

        nodes = nodes_of(t, max_step, largest_step)
        x, d, o = x0, d0, o0
        ctx.last_previous = None
        pairs = zip(nodes[:-1].tolist(), nodes[1:].tolist())
        if progress:
            from tqdm.auto import tqdm

            pairs = tqdm(pairs, total=nodes.size - 1, desc=mech.name, unit="node")
        xs, ds, os_ = [], [], []  # the nodes' solutions, written into the columns at once
        for a, b in pairs:
            x, d, o, iters[b] = ctx.march(float(t[a]), x, d, o, float(t[b]), ctx.last_previous)
            xs.append(x)
            ds.append(d if d is not None else [math.nan] * n)
            os_.append(o)
        if xs:
            os_[-1] = ctx.unpassed_crossings(float(t[-1]), os_[-1])  # (at the last input: a toggle, or not passed)
            X[:, nodes[1:]] = np.array(xs).T
            D[:, nodes[1:]] = np.array(ds).T
            O[:, nodes[1:]] = np.array(os_).T

        ctx.raise_pending()  # a change point passed in the last step of the march
        every = int(nodes[1]) if evenly and nodes.size > 1 else 0
        # the nodes every `every`-th input, the last one included, of an evenly spaced grid
        every = every if every and t.size - 1 == every * (nodes.size - 1) else None
        residual, cond, jac = fill(ctx, t, X, D, O, iters, nodes, every=every, even=evenly)
        ctx.raise_pending()
        if ctx.crossings:
            ctx.describe_crossings(t, X, O, cond)
    report_near_singular(ctx, t, X, cond)
    sweep = Sweep(mech, t, X, iters, residual, cond, ctx.events, jacobian, tol, ctx.nfev, ctx.njev)
    record_evaluations(mech, "F", ctx.nfev)
    record_evaluations(mech, "J", ctx.njev)
    sweep.jacobian_rows = jac
    return sweep

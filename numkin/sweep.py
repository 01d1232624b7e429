"""Position sweeps by continuation, on one assembly branch.

Algorithm
---------
1. Solve at the first input from the guess (Newton, up to ``maxiter`` steps,
   refusing near-singular Jacobians); angles are taken nearest to the guess.
2. March sequentially to *nodes*, grid points about ``max_step`` apart (30°
   by default): each step predicts with the tangent ``q' = -J^-1 dF/dt``
   (and the previous point: a quadratic) and corrects with Newton. A step is
   accepted only if Newton converges, the correction is small
   (:data:`MAX_CORRECTION`) and the sign of every loop's Jacobian determinant
   (its *orientation*, constant along a branch) is unchanged; otherwise the
   step is halved, so a large ``max_step`` costs no safety.
3. Fill the grid points between nodes in one batch: a cubic Hermite predictor
   from the nodes' values and tangents, then Newton on all points at once.
   A point that fails the same acceptance tests (converged, small
   correction, the orientation of its nodes) is re-solved sequentially from
   its neighbour.

The sequential steps work on plain floats (``math``-module functions, the
Jacobian's block-triangular shape solved by Cramer's rule per loop), the
batch on numpy arrays; both apply the stopping rule of :mod:`numkin.newton`.

A change of orientation between two accepted points means the linkage passed
a singular position (a change point, where branches meet); a step that
shrinks to nothing where the Jacobian is ill-conditioned (or has become so
along the step) is a limit (toggle) position. Both raise
:class:`~numkin.BranchError` (or, with ``on_singular="report"``, a change
point is recorded in :attr:`Sweep.events` with a warning and the sweep goes
on along the smooth continuation; a toggle cannot be passed). A Newton that
fails elsewhere raises :class:`~numkin.ConvergenceError`; a linkage that
cannot be assembled at the start raises :class:`~numkin.AssemblyError`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from .compiled import MATH_ERRORS, _stack
from .errors import AssemblyError, BranchError, ConvergenceError
from .newton import _FD_STEP as FD_STEP
from .newton import JACOBIANS, fd_jacobian, has_converged

__all__ = ["Sweep", "SweepEvent", "SingularityWarning", "run_sweep"]

#: Correction (scaled: rad, or lengths / length_scale) above which a continuation step is refused.
MAX_CORRECTION = 0.3
#: Condition number above which a point is reported as near-singular.
COND_WARN = 1e8
#: Condition number above which a Jacobian is treated as singular.
COND_MAX = 1e12
#: Newton steps allowed for a continuation corrector.
CORRECTOR_ITERATIONS = 12
#: Batches smaller than this always iterate on whole arrays (gathering the few active
#: columns costs more than it saves).
COMPACT_MIN = 2000
#: Default largest input step (rad) between the sequentially solved nodes of a sweep.
DEFAULT_MAX_STEP = math.radians(30.0)
#: A step that shrinks to nothing where the condition number exceeds this (or has grown
#: TOGGLE_GROWTH-fold since the start of the march) is a limit (toggle) position.
TOGGLE_COND = 1e3
TOGGLE_GROWTH = 30.0


class SingularityWarning(UserWarning):
    """A sweep passed close to, or through, a singular position."""


@dataclass(frozen=True)
class SweepEvent:
    """Something a sweep met on its way: a near-singular point or a change point.

    Attributes
    ----------
    kind : str
        ``"near-singular"``, ``"change point"`` or ``"singular"``.
    input_value : float
        Input (rad) where it was met.
    loop : str
        Loop concerned.
    message : str
    """

    kind: str
    input_value: float
    loop: str
    message: str


def _deg(t: float, digits: int = 3) -> str:
    return f"{math.degrees(t):.{digits}f}°"


@dataclass
class Sweep:
    """Positions of a mechanism over a sweep of its input.

    Attributes
    ----------
    mechanism : Mechanism
    inputs : ndarray (N,)
        Input values, rad.
    values : ndarray (n, N)
        Unknowns in ``mechanism.unknowns`` order. Angles in rad, continuous
        along the sweep (unwrapped: no 2 pi jumps); lengths in the
        mechanism's length unit.
    iterations : ndarray (N,)
        Newton iterations spent at each point (by its last corrector).
    residual : ndarray (N,)
        Scaled residual norm at each point.
    cond : ndarray (N,)
        Largest condition number of the loops' scaled Jacobian blocks.
    events : list of SweepEvent
    jacobian : str
        How Newton's Jacobian was computed.
    tol : float
        Stopping tolerance used.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0, 361)))
    >>> sweep["theta4"].shape
    (361,)
    >>> list(sweep.to_frame().columns[:3])
    ['theta2 [deg]', 'theta3 [deg]', 'theta4 [deg]']
    """

    mechanism: object
    inputs: np.ndarray
    values: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    cond: np.ndarray
    events: list = field(default_factory=list)
    jacobian: str = "symbolic"
    tol: float = 1e-12

    @property
    def unknowns(self) -> tuple:
        return self.mechanism.unknowns

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.values[self.unknowns.index(name)]
        except ValueError:
            if name == str(self.mechanism.input_symbol):
                return self.inputs
            raise KeyError(f"{name!r} is not an unknown of {self.mechanism.name}; unknowns are {list(self.unknowns)}") from None

    def __contains__(self, name) -> bool:
        return name in self.unknowns

    def __len__(self) -> int:
        return self.inputs.size

    def unit(self, name: str) -> str:
        """Unit of an unknown's values: ``"rad"`` or the length unit."""
        return "rad" if name in self.mechanism.angles else self.mechanism.length_unit

    @property
    def step(self) -> float | None:
        """The uniform input step (rad), or None if the grid is not uniform."""
        if self.inputs.size < 2:
            return None
        d = np.diff(self.inputs)
        return float(d.mean()) if np.allclose(d, d[0], rtol=1e-9, atol=1e-14) else None

    def index(self, input_value: float) -> int:
        """Index of the grid point nearest to ``input_value`` (rad)."""
        return int(np.argmin(np.abs(self.inputs - input_value)))

    def points(self) -> dict:
        """Coordinates of the mechanism's named points: name -> (2, N) array."""
        return self.mechanism.point_coordinates(self.values, self.inputs)

    def to_frame(self, degrees: bool = True):
        """A pandas DataFrame: one row per input, columns labelled with units.

        Angles are given in degrees (``"theta3 [deg]"``) when ``degrees`` is
        true, else in rad; lengths in the mechanism's unit; then the Newton
        diagnostics ``iterations``, ``residual`` and ``cond``.
        """
        import pandas as pd

        angle_unit = "deg" if degrees else "rad"
        conv = np.degrees if degrees else (lambda a: a)
        cols = {f"{self.mechanism.input_symbol} [{angle_unit}]": conv(self.inputs)}
        for name, vals in zip(self.unknowns, self.values):
            if name in self.mechanism.angles:
                cols[f"{name} [{angle_unit}]"] = conv(vals)
            else:
                cols[f"{name} [{self.mechanism.length_unit}]"] = vals
        cols["iterations"] = self.iterations
        cols["residual"] = self.residual
        cols["cond"] = self.cond
        return pd.DataFrame(cols)

    def __repr__(self) -> str:
        lo, hi = (_deg(self.inputs[0]), _deg(self.inputs[-1])) if self.inputs.size else ("", "")
        return (
            f"Sweep({self.mechanism.name!r}, {self.inputs.size} points {lo}..{hi}, "
            f"unknowns={list(self.unknowns)}, max iterations={int(self.iterations.max(initial=0))}, "
            f"max cond={float(self.cond.max(initial=0)):.3g}, events={len(self.events)})"
        )


# --------------------------------------------------------------------------- algorithm
class _Continuation:
    """State and numerical kernels shared by the steps of one sweep.

    Two kernels solve the same loop equations with the same stopping rule
    (:mod:`numkin.newton`): a *scalar* one for the sequential steps (plain
    floats, ``math``-module functions and the block-triangular solve of
    :class:`~numkin.compiled.BlockStructure`: no numpy overhead on single
    points), and a *batched* one that solves all remaining grid points at
    once.
    """

    def __init__(self, mech, jacobian, tol, max_step, on_singular):
        self.mech = mech
        self.jacobian = jacobian
        self.symbolic = jacobian == "symbolic"
        self.tol = tol
        self.max_step = max_step
        self.on_singular = on_singular
        self.events: list = []
        comp = mech.compiled
        self.comp = comp
        self.n = len(mech.unknowns)
        self.nn = self.n * self.n
        self.p = mech.parameter_values
        self.pt = tuple(self.p.tolist())
        self.fscale = float(mech.length_scale)
        self.xs = mech.xscale.tolist()
        self.blocks = mech.block_structure
        self.inv_xs = self.blocks.inv_xscale
        self.loop_names = [lp.name for lp in mech.loops]
        self._fjt = comp.scalar_FJT
        self._f = comp.scalar_F

    # ------------------------------------------------------------ one point
    def eval1(self, x, t):
        """Residuals, Jacobian rows and dF/dt at one point (flat list), or None where undefined."""
        try:
            v = self._fjt(*x, t, *self.pt)
        except MATH_ERRORS:
            return None
        return v if math.isfinite(sum(v)) else None

    def resid1(self, x, t):
        try:
            f = self._f(*x, t, *self.pt)
        except MATH_ERRORS:
            return None
        return f if math.isfinite(sum(f)) else None

    def fd1(self, x, t, f0):
        """Finite-difference Jacobian rows at one point (the step rule of :mod:`numkin.newton`)."""
        n = self.n
        c = FD_STEP[self.jacobian]
        jac = [0.0] * self.nn
        for j in range(n):
            xj = x[j]
            xp = list(x)
            xp[j] = xj + c * max(abs(xj), self.xs[j])
            h = xp[j] - xj
            fp = self.resid1(xp, t)
            if fp is None:
                return None
            if self.jacobian == "forward":
                col = [(a - b) / h for a, b in zip(fp, f0)]
            else:
                xm = list(x)
                xm[j] = xj - h
                fm = self.resid1(xm, t)
                if fm is None:
                    return None
                col = [(a - b) / (2.0 * h) for a, b in zip(fp, fm)]
            for i in range(n):
                jac[i * n + j] = col[i]
        return jac

    def newton1(self, x, t, maxiter, cond_max=None):
        """Newton-Raphson at one input from ``x`` (list).

        Returns ``(x, status, iterations, residual, v)``: status is
        ``"converged"``, ``"singular"``, ``"diverged"`` or ``"maxiter"``;
        ``v`` is :meth:`eval1` at the returned ``x`` (None if unknown).
        With ``cond_max`` a Jacobian whose loop blocks have a larger scaled
        condition number is refused as singular; otherwise only an exactly
        singular or non-finite solve is.
        """
        if not self.symbolic:
            return self._newton1_fd(x, t, maxiter, cond_max)
        n, nn, fscale, tol = self.n, self.nn, self.fscale, self.tol
        update, eval1 = self.blocks.update1, self.eval1
        v = eval1(x, t)
        if v is None:
            return x, "diverged", 0, math.nan, None
        res = max([abs(a) for a in v[:n]]) / fscale
        prev = math.inf
        it = 0
        while it < maxiter:
            if cond_max is not None and not max(self.blocks.cond1(v[n : n + nn])) <= cond_max:
                return x, "singular", it, res, v
            x_new, step = update(v, x)
            if x_new is None:
                return x, "singular", it, res, v
            x = x_new
            it += 1
            v = eval1(x, t)
            if v is None:
                return x, "diverged", it, math.nan, None
            res = max([abs(a) for a in v[:n]]) / fscale
            if has_converged(res, step, prev, tol):
                return x, "converged", it, res, v
            prev = step
        return x, "maxiter", it, res, v

    def _newton1_fd(self, x, t, maxiter, cond_max):
        """:meth:`newton1` with a finite-difference Jacobian."""
        fscale, tol = self.fscale, self.tol
        f = self.resid1(x, t)
        if f is None:
            return x, "diverged", 0, math.nan, None
        res = max([abs(a) for a in f]) / fscale
        prev = math.inf
        it = 0
        while it < maxiter:
            jac = self.fd1(x, t, f)
            if jac is None:
                return x, "diverged", it, math.nan, None
            if cond_max is not None and not max(self.blocks.cond1(jac)) <= cond_max:
                return x, "singular", it, res, self.eval1(x, t)
            dx, _ = self.blocks.solve1(jac, [-a for a in f])
            if dx is None:
                return x, "singular", it, res, self.eval1(x, t)
            x = [a + b for a, b in zip(x, dx)]
            it += 1
            step = max([abs(a) * w for a, w in zip(dx, self.inv_xs)])
            f = self.resid1(x, t)
            if f is None:
                return x, "diverged", it, math.nan, None
            res = max([abs(a) for a in f]) / fscale
            if has_converged(res, step, prev, tol):
                return x, "converged", it, res, self.eval1(x, t)
            prev = step
        return x, "maxiter", it, res, self.eval1(x, t)

    def local1(self, v):
        """Tangent dq/dt and loop orientations at a solved point; (None, None) if its Jacobian is singular."""
        n, nn = self.n, self.nn
        if v is None:
            return None, None
        return self.blocks.solve1(v[n : n + nn], [-a for a in v[n + nn :]])

    def small_correction(self, x, x_pred) -> bool:
        return max([abs(a - b) * w for a, b, w in zip(x, x_pred, self.inv_xs)]) <= MAX_CORRECTION

    def worst1(self, x, t, which="residual"):
        """(loop name, value) of the loop with the largest residual or condition number at one point."""
        v = self.eval1(x, t)
        if v is None:
            return self.loop_names[0], math.nan
        if which == "residual":
            vals = [max(abs(a) for a in v[a0:b0]) / self.fscale for a0, b0 in self.blocks.blocks]
        else:
            vals = self.blocks.cond1(v[self.n : self.n + self.nn])
        k = max(range(len(vals)), key=lambda i: math.inf if vals[i] != vals[i] else vals[i])
        return self.loop_names[k], float(vals[k])

    # ------------------------------------------------------------ many points
    def eval_batch(self, x, t, fixed=None):
        """Residuals (n, N) and Jacobian rows (list of n*n arrays or numbers) at many points.

        ``fixed``: :meth:`CompiledMechanism.fixed_terms` at ``t``, if known.
        """
        v = self.comp.FJ_rows(x, t, self.p, fixed)
        return _stack(v[: self.n], t.size), v[self.n :]

    def newton_batch(self, x, t, active, maxiter=CORRECTOR_ITERATIONS):
        """Newton on the columns ``active`` of ``x`` (n, N) at the inputs ``t``; other columns are kept.

        The same iteration and stopping rule as :func:`numkin.newton.iterate`.
        While most columns are active it works on whole arrays; once few are
        left, on those columns only. Returns ``x``, ``converged`` (N,),
        ``iterations`` (N,), and the residuals (n, N) and (symbolic) Jacobian
        rows at the returned ``x``. Call it under ``numpy.errstate(all="ignore")``.
        """
        nn, tol = self.nn, self.tol
        inv_xs = np.asarray(self.inv_xs)[:, None]
        unit_scale = bool(np.all(inv_xs == 1.0))
        xs = np.asarray(self.xs)
        x = np.array(x, dtype=float)
        N = x.shape[1]
        sym = self.symbolic
        comp, p = self.comp, self.p
        newton_step = self.blocks.newton_step

        fixed_all = comp.fixed_terms(t, p) if sym else None

        def evaluate(z, tz, fixed=None):
            if sym:
                return self.eval_batch(z, tz, fixed_all if fixed is None else fixed)
            return comp.F(z, tz, p), None

        def jacobian(z, tz, fz, jz):
            if sym:
                return jz
            return list(fd_jacobian(lambda w: comp.F(w, tz, p), z, fz, self.jacobian, xs).reshape(z.shape[1], nn).T)

        def scaled_max(dx):
            return _colmax(np.abs(dx) if unit_scale else np.abs(dx) * inv_xs)

        f, jac = evaluate(x, t)
        fmax = _colmax(np.abs(f))
        converged = np.zeros(N, dtype=bool)
        iterations = np.zeros(N, dtype=int)
        act = active & np.isfinite(fmax)
        prev = np.full(N, np.inf)
        for _ in range(maxiter):
            idx = np.flatnonzero(act)
            M = idx.size
            if M == 0:
                break
            if M * 4 > N or N < COMPACT_MIN:  # whole arrays; the inactive columns do not move
                dx, bad = newton_step(jacobian(x, t, f, jac), f)
                upd = act & ~bad
                if M < N or bad.any():
                    dx[:, ~upd] = 0.0
                x = x + dx
                step = scaled_max(dx)
                f, jac = evaluate(x, t)
                fmax = _colmax(np.abs(f))
            else:  # the active columns only
                tz = t.take(idx)
                z, fz = x.take(idx, axis=1), f.take(idx, axis=1)
                jz = [r.take(idx) if np.ndim(r) else r for r in jac] if sym else None
                dx, bad_z = newton_step(jacobian(z, tz, fz, jz), fz)
                if bad_z.any():
                    dx[:, bad_z] = 0.0
                z = z + dx
                fz, jz = evaluate(z, tz, [u.take(idx) if np.ndim(u) else u for u in fixed_all] if sym else None)
                x[:, idx] = z
                f[:, idx] = fz
                if sym:
                    jac = [_scatter(r, rz, idx, N) for r, rz in zip(jac, jz)]
                bad = np.zeros(N, dtype=bool)
                bad[idx] = bad_z
                upd = act & ~bad
                step = np.full(N, np.inf)
                step[idx] = scaled_max(dx)
                fmax[idx] = _colmax(np.abs(fz))
            iterations += upd
            done = upd & has_converged(fmax / self.fscale, step, prev, tol)
            converged |= done
            act &= ~(done | bad) & np.isfinite(fmax)
            prev = np.where(upd, step, prev)
        if not sym:
            f, jac = self.eval_batch(x, t)
        return x, converged, iterations, f, jac

    # ------------------------------------------------------------ events
    def record(self, kind, t, loop, message, *, raise_kind=None):
        """Raise (``on_singular="raise"``) or record an event once and warn."""
        if raise_kind is not None and self.on_singular == "raise":
            raise BranchError(message, kind=raise_kind, input_value=float(t), loop=loop)
        for e in self.events:  # the same crossing met again (from a node, then from a grid point)
            if e.kind == kind and e.loop == loop and abs(e.input_value - t) <= 1e-6 * max(1.0, abs(t)):
                return
        self.events.append(SweepEvent(kind, float(t), loop, message))
        warnings.warn(message, SingularityWarning, stacklevel=4)

    # -------------------------------------------------------------- sequential
    def march(self, t0, x0, d0, o0, t1, previous=None):
        """Continue from (t0, x0), tangent d0 and orientations o0, to the input t1.

        ``previous`` is an earlier point ``(t, x)`` of the same branch for the
        quadratic predictor of the first step. Returns ``(x, d, o,
        iterations)`` at t1; :attr:`last_previous` keeps the point before it.
        """
        span = t1 - t0
        direction = 1.0 if span > 0 else -1.0
        step = min(self.max_step, abs(span))
        if previous is None:
            step = min(step, 0.5 * self.max_step)  # the first predictor is linear: start shorter
        min_step = 1e-9 * max(1.0, abs(span))
        end_tol = 1e-15 * max(1.0, abs(t1))
        t, x, d, o = t0, x0, d0, o0
        t_prev, x_prev = previous if previous is not None else (None, None)
        iters = 0
        while abs(t1 - t) > end_tol:
            dt = direction * min(step, abs(t1 - t))
            t_new = t1 if abs(t + dt - t1) <= end_tol else t + dt
            x_pred = _predict(t, x, d, t_prev, x_prev, t_new)
            x_new, status, it, res, v = self.newton1(x_pred, t_new, CORRECTOR_ITERATIONS)
            reason = status
            ok = status == "converged"
            if ok and not self.small_correction(x_new, x_pred):
                ok, reason = False, "correction"
            if ok:
                d_new, o_new = self.local1(v)
                if o_new is None:
                    ok, reason = False, "singular"
                elif o_new != o:
                    k = next(i for i, (a, b) in enumerate(zip(o_new, o)) if a != b)
                    loop = self.loop_names[k]
                    if step > 64 * min_step:
                        ok, reason = False, "orientation"  # localise the crossing before deciding
                    else:
                        self.record(
                            "change point", t_new, loop,
                            f"{self.mech.name}: loop '{loop}' passes a singular position at input "
                            f"{_deg(t_new, 6)} (its Jacobian changes sign): the branches meet there "
                            "and the continuation is ambiguous",
                            raise_kind="change point",
                        )
            if ok:
                t_prev, x_prev = t, x
                t, x, d, o = t_new, x_new, d_new, o_new
                iters = it
                step = min(self.max_step, 2.0 * step)
                continue
            step /= 2.0
            if step < min_step:
                self.fail(t0, x0, t, x, t_new, x_new, status, reason, it, res)
        self.last_previous = (t_prev, x_prev) if t_prev is not None else None
        return x, d, o, iters

    def fail(self, t0, x0, t, x, t_next, x_try, status, reason, iterations, res):
        """Explain why the continuation cannot go from t to t_next, and raise.

        The step has shrunk to nothing. If the Jacobian at the last point
        reached is ill-conditioned (or has grown so since the start of the
        march) the linkage is at a limit position: a toggle. Otherwise Newton
        failed, or the solution jumps, at a regular point.
        """
        loop, cond = self.worst1(x, t, which="cond")
        _, cond0 = self.worst1(x0, t0, which="cond")
        if reason == "singular" or not cond < TOGGLE_COND or not cond < TOGGLE_GROWTH * cond0:
            raise BranchError(
                f"{self.mech.name}: limit (toggle) position of loop '{loop}' near {_deg(t, 3)} "
                f"(condition number {cond:.3g}): the input cannot be driven past it on this branch",
                kind="toggle", input_value=float(t), loop=loop,
            )
        bad_loop, bad_res = self.worst1(x_try, t_next)
        if reason in ("correction", "orientation"):
            what = (
                "moves the solution too far" if reason == "correction" else "lands on another assembly branch"
            )
            msg = (
                f"{self.mech.name}: no continuous solution from input {_deg(t, 6)} to {_deg(t_next, 6)}: "
                f"the smallest step {what} (loop '{bad_loop}'); the loop equations jump there"
            )
        else:
            msg = (
                f"{self.mech.name}: Newton did not converge at input {_deg(t_next, 3)}: loop '{bad_loop}' "
                f"residual {bad_res:.3g} after {iterations} iterations"
            )
        raise ConvergenceError(msg, input_value=float(t_next), loop=bad_loop, residual=bad_res, iterations=iterations)


def _colmax(a):
    """Largest entry of every column of a small (n, N) array (faster than ``a.max(axis=0)``)."""
    out = a[0]
    for row in a[1:]:
        out = np.maximum(out, row)
    return out


def _scatter(row, sub, idx, N):
    """A Jacobian row (array or number) with the columns ``idx`` replaced by ``sub``."""
    if not np.ndim(row):
        if not np.ndim(sub):
            return row
        row = np.full(N, row, dtype=np.result_type(row, sub))
    row[idx] = sub
    return row


def _predict(t, x, d, t_prev, x_prev, t_new):
    """Predictor of a continuation step: the quadratic through the previous point
    with the current tangent, or the tangent alone at the first step."""
    s = t_new - t
    if d is None:
        if x_prev is None:
            return list(x)
        r = s / (t - t_prev)
        return [a + (a - b) * r for a, b in zip(x, x_prev)]
    if x_prev is None:
        return [a + da * s for a, da in zip(x, d)]
    h = t_prev - t
    s2 = s * s / (h * h)
    return [a + da * s + (b - a - da * h) * s2 for a, da, b in zip(x, d, x_prev)]


def _validate_inputs(inputs) -> np.ndarray:
    t = np.asarray(inputs, dtype=float)
    if t.ndim == 0:
        t = t.reshape(1)
    if t.ndim != 1 or t.size == 0:
        raise ValueError(f"inputs must be a non-empty 1-D array of input values (rad), got shape {t.shape}")
    if not math.isfinite(t.sum()):
        raise ValueError(f"inputs[{int(np.flatnonzero(~np.isfinite(t))[0])}] is not finite")
    if t.size > 1:
        d = t[1:] - t[:-1]
        if not ((d > 0).all() or (d < 0).all()):
            k = int(np.flatnonzero(np.sign(d) != np.sign(d[0]))[0]) if np.any(d != 0) else 0
            raise ValueError(f"inputs must be strictly monotonic for continuation (check inputs[{k}:{k + 2}])")
    return t


def _start(ctx: _Continuation, t0: float, guess, maxiter: int):
    """Solve the first point from the guess (continuing from ``guess_input`` if needed).

    Returns ``(x, iterations, v)``.
    """
    mech = ctx.mech
    g = mech.default_guess if guess is None else guess
    if guess is None and g is not None and not callable(g) and mech.guess_input is not None and mech.guess_input != t0:
        tg = float(mech.guess_input)
        x_g, _, v = _solve_first(ctx, tg, mech.guess_vector(g, tg), maxiter)
        d, o = ctx.local1(v)
        x, _, _, iters = ctx.march(tg, x_g, d, o, t0)
        return x, iters, ctx.eval1(x, t0)
    return _solve_first(ctx, t0, mech.guess_vector(g, t0), maxiter)


def _solve_first(ctx, t0, x_guess, maxiter):
    mech = ctx.mech
    guess = x_guess.tolist()
    x, status, it, res, v = ctx.newton1(guess, t0, maxiter, cond_max=COND_MAX)
    if status == "singular":
        loop, cond = ctx.worst1(x, t0, which="cond")
        raise BranchError(
            f"{mech.name}: the Jacobian of loop '{loop}' is singular at input {_deg(t0, 3)} "
            f"(condition number {cond:.3g}): a toggle or change point, where the branch cannot be chosen; "
            "start the sweep at another input",
            kind="singular", input_value=float(t0), loop=loop,
        )
    if status != "converged":
        loop, res = ctx.worst1(x, t0)
        raise AssemblyError(
            f"{mech.name}: cannot assemble at input {_deg(t0, 3)}: Newton from the guess did not converge "
            f"(loop '{loop}' residual {res:.3g} after {it} iterations); "
            "check the dimensions or give a better guess"
        )
    shifted = False
    for k, name in enumerate(mech.unknowns):
        if name in mech.angles:
            a = guess[k] + math.remainder(x[k] - guess[k], 2 * math.pi)
            shifted |= a != x[k]
            x[k] = a
    if shifted:
        v = ctx.eval1(x, t0)
    return x, it, v


def _nodes(t: np.ndarray, max_step: float) -> np.ndarray:
    """Grid indices marched sequentially: at most ``max_step`` apart where the grid allows."""
    if t.size <= 2:
        return np.arange(t.size)
    h = np.abs(np.diff(t)).max()
    every = max(1, int(max_step / h * (1.0 + 1e-9))) if h > 0 else 1
    idx = np.arange(0, t.size, every)
    if idx[-1] != t.size - 1:
        idx = np.append(idx, t.size - 1)
    return idx


def run_sweep(mech, inputs, guess=None, *, jacobian="symbolic", tol=1e-12, maxiter=50,
              max_step=DEFAULT_MAX_STEP, on_singular="raise"):
    """Solve ``mech`` over ``inputs`` by continuation; see :meth:`Mechanism.sweep`."""
    if on_singular not in ("raise", "report"):
        raise ValueError(f"on_singular must be 'raise' or 'report', got {on_singular!r}")
    if max_step is None:
        max_step = DEFAULT_MAX_STEP
    if not (isinstance(max_step, (int, float, np.number)) and max_step > 0 and math.isfinite(max_step)):
        raise ValueError(f"max_step must be a positive angle in rad, got {max_step!r}")
    if not (isinstance(tol, (int, float, np.number)) and tol > 0 and math.isfinite(tol)):
        raise ValueError(f"tol must be a positive number, got {tol!r}")
    if isinstance(maxiter, bool) or not isinstance(maxiter, (int, np.integer)) or maxiter < 1:
        raise ValueError(f"maxiter must be a positive integer, got {maxiter!r}")
    if jacobian not in JACOBIANS:
        raise ValueError(f"jacobian must be one of {JACOBIANS}, got {jacobian!r}")
    t = _validate_inputs(inputs)
    mech.check_assembly(t)
    ctx = _Continuation(mech, jacobian, float(tol), float(max_step), on_singular)
    n, N = ctx.n, t.size
    tl = t.tolist()
    X = np.empty((n, N))
    D = np.full((n, N), np.nan)
    O = np.zeros((len(mech.loops), N))
    iters = np.zeros(N, dtype=int)

    with np.errstate(all="ignore"):
        x0, iters[0], v0 = _start(ctx, tl[0], guess, maxiter)
        d0, o0 = ctx.local1(v0)
        X[:, 0], D[:, 0], O[:, 0] = x0, d0, o0

        nodes = _nodes(t, max_step)
        x, d, o = x0, d0, o0
        ctx.last_previous = None
        for a, b in zip(nodes[:-1].tolist(), nodes[1:].tolist()):
            x, d, o, iters[b] = ctx.march(tl[a], x, d, o, tl[b], ctx.last_previous)
            X[:, b], D[:, b], O[:, b] = x, d, o

        f, jac = _fill(ctx, t, X, D, O, iters, nodes)
        residual = _colmax(np.abs(f)) / ctx.fscale
        cond = _colmax(ctx.blocks.cond(jac, N))
    _report_near_singular(ctx, t, X, cond)
    return Sweep(mech, t, X, iters, residual, cond, ctx.events, jacobian, tol)


def _fill(ctx, t, X, D, O, iters, nodes):
    """Solve the grid points between nodes in one Newton batch (cubic Hermite predictor).

    Returns the residuals (n, N) and Jacobian rows at every point of the sweep.
    """
    N = t.size
    if nodes.size == N:
        return ctx.eval_batch(X, t)
    fine_mask = np.ones(N, dtype=bool)
    fine_mask[nodes] = False
    # every column's left and right node (a node is its own left node, at s = 0)
    k = np.searchsorted(nodes, np.arange(N), side="right") - 1
    a = nodes.take(k)
    b = nodes.take(np.minimum(k + 1, nodes.size - 1))
    ta = t.take(a)
    delta = t.take(b) - ta
    delta[a == b] = 1.0
    s = (t - ta) / delta
    s2 = s * s
    s3 = s2 * s
    h01 = 3 * s2 - 2 * s3
    h10, h11 = (s3 - 2 * s2 + s) * delta, (s3 - s2) * delta
    xa = X.take(a, axis=1)
    x_pred = xa + h01 * (X.take(b, axis=1) - xa) + h10 * D.take(a, axis=1) + h11 * D.take(b, axis=1)
    x, converged, it, f, jac = ctx.newton_batch(x_pred, t, fine_mask)
    # accept a point if Newton converged, the correction is small and no loop changed orientation
    o = ctx.blocks.signs(jac, N)
    corr = np.abs(x - x_pred)
    if not all(w == 1.0 for w in ctx.inv_xs):
        corr *= np.asarray(ctx.inv_xs)[:, None]
    ok = converged & (_colmax(corr) <= MAX_CORRECTION)
    On = O.take(nodes, axis=1)
    if (On == On[:, :1]).all():  # one orientation at all nodes: compare with it
        for kk in range(O.shape[0]):
            ok &= o[kk] == On[kk, 0]
    else:
        Oa, Ob = O.take(a, axis=1), O.take(b, axis=1)
        for kk in range(O.shape[0]):
            ok &= (o[kk] == Oa[kk]) & (Oa[kk] == Ob[kk])
    ok |= ~fine_mask
    X[...] = x  # the nodes were not active: unchanged
    O[...] = np.where(fine_mask, o, O)
    iters[...] = np.where(fine_mask, it, iters)
    redo = np.flatnonzero(~ok)
    if redo.size:
        # Points the batch could not place safely are reached one by one from their left neighbour.
        tl = t.tolist()
        for k in redo.tolist():
            left = k - 1
            xl = X[:, left].tolist()
            if np.all(np.isfinite(D[:, left])):
                dl = D[:, left].tolist()
            else:
                dl, _ = ctx.local1(ctx.eval1(xl, tl[left]))
            xk, dk, ok_, iters[k] = ctx.march(tl[left], xl, dl, O[:, left].tolist(), tl[k])
            X[:, k], D[:, k], O[:, k] = xk, dk, ok_
        f_redo, jac_redo = ctx.eval_batch(X[:, redo], t[redo])
        f[:, redo] = f_redo
        jac = _stack(jac, N)
        jac[:, redo] = _stack(jac_redo, redo.size)
    return f, jac


def _report_near_singular(ctx, t, X, cond):
    singular = np.flatnonzero(~(cond <= COND_MAX))
    if singular.size:
        k = singular[0]
        loop, _ = ctx.worst1(X[:, k].tolist(), float(t[k]), which="cond")
        ctx.record(
            "singular", t[k], loop,
            f"{ctx.mech.name}: the Jacobian of loop '{loop}' is singular at input {_deg(t[k], 3)} "
            f"(condition number {cond[k]:.3g}): a toggle or change point, where the branch cannot be told",
            raise_kind="singular",
        )
    near = np.flatnonzero((cond > COND_WARN) & (cond <= COND_MAX))
    if near.size == 0:
        return
    k = near[np.argmax(cond[near])]
    loop, _ = ctx.worst1(X[:, k].tolist(), float(t[k]), which="cond")
    ctx.events.append(
        SweepEvent(
            "near-singular", float(t[k]), loop,
            f"{ctx.mech.name}: {near.size} point(s) near a singular position of loop '{loop}' "
            f"(condition number up to {cond[k]:.3g} at {_deg(t[k], 3)}): expect lost digits there",
        )
    )
    warnings.warn(ctx.events[-1].message, SingularityWarning, stacklevel=3)

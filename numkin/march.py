"""The steps of a continuation: Newton kernels, the predictor and the march between nodes.

:class:`Continuation` holds what the steps of one sweep share: the scalar
Newton kernel (plain floats, ``math``-module functions and the loops'
block-triangular solve; the symbolic or finite-difference Jacobian plugged
in), the batched one (``numkin.newton.solve_batch`` with the fused
residual-and-Jacobian rows), the march from one node to the next with its
acceptance tests; what it meets on the way, the change points passed, is
recorded and described by :class:`numkin.crossings.Crossings`. See
:mod:`numkin.continuation` for the algorithm as a whole.
"""

from __future__ import annotations

import math

import numpy as np

from .compiled import MATH_ERRORS, stack_rows
from .crossings import Crossings
from .errors import BranchError, ConvergenceError
from .newton import (
    COMPACT_MIN,
    fd_jacobian,
    has_converged,
    is_singular,
    residual_floor,
    solve_batch,
)
from .predictors import MAX_PREDICTION, unrolled_predict
from .units import deg_text
from .unrolled import scaled_distance, scaled_size, unrolled_kink

__all__ = ["Continuation", "MAX_CORRECTION", "CORRECTOR_ITERATIONS",
           "DEFAULT_MAX_STEP", "FAR", "TWO_PI", "MAX_TANGENT_TURN", "TREND_REACH", "CROSSING_STEP", "COND_TANGENT"]

#: Correction (scaled: rad, or lengths / length_scale) above which a continuation step is refused.
MAX_CORRECTION = 0.3
#: Condition number above which a solved point's tangent is not used to predict (it carries
#: the position's error times the condition number: noise next to a change point).
COND_TANGENT = 1e6
#: Largest change of the (scaled) tangent in one continuation step, relative to 1 + its size:
#: a larger one is halved until the step is resolved, so a switch to another branch where
#: branches meet (same orientation, a kink in the tangent) is never taken for a step.
MAX_TANGENT_TURN = 0.5
#: The kink test expects the tangent to go on changing as it did over the last step, extrapolated
#: at most this many times that step ahead (a smooth branch then passes in long steps).
TREND_REACH = 2.0
#: Step (rad) to which a change of orientation is localised before it is taken for a change
#: point: small enough to place it, large enough that the branches meeting there are still
#: told apart (their distance, ~ step, stays far above Newton's noise, ~ eps / step).
CROSSING_STEP = 1e-5
#: Newton steps allowed for a continuation corrector.
CORRECTOR_ITERATIONS = 12
#: Trial steps allowed for one march between nodes (accepted or refused).
MAX_TRIALS = 100_000
#: Default largest input step (rad) between the sequentially solved nodes of a sweep.
DEFAULT_MAX_STEP = math.radians(30.0)
#: A step that shrinks to nothing where the condition number exceeds this (or has grown
#: TOGGLE_GROWTH-fold since the start of the march) is a limit (toggle) position.
TOGGLE_COND = 1e3
TOGGLE_GROWTH = 30.0
#: Scaled residual above which a point where Newton met a singular Jacobian is not a solution.
FAR = 1e-6
TWO_PI = 2.0 * math.pi

class Continuation(Crossings):
    """State and numerical kernels shared by the steps of one sweep.

    One scalar Newton kernel (:meth:`newton1`: plain floats, ``math``-module
    functions and the block-triangular solve of
    :class:`~numkin.compiled.BlockStructure`, with the symbolic or the
    finite-difference Jacobian of :func:`numkin.newton.fd_jacobian` plugged
    in) for the sequential steps, and a batched one (:meth:`newton_batch`)
    for the remaining grid points; both apply the stopping rule of
    :mod:`numkin.newton`.
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
        self.xs_arr = np.asarray(mech.xscale, dtype=float)
        self.blocks = mech.block_structure
        self.inv_xs = self.blocks.inv_xscale
        self.unit_scale = all(w == 1.0 for w in self.inv_xs)  # angles only: no scaling in the step tests
        self.loop_names = [lp.name for lp in mech.loops]
        self.angle_idx = [k for k, u in enumerate(mech.unknowns) if u in mech.angles]
        self.predict1 = unrolled_predict(self.n, None if self.unit_scale else tuple(self.inv_xs))
        self.distance = scaled_distance(self.n, tuple(self.inv_xs))  # max |a - b| / xscale of two points
        self.size = scaled_size(self.n, tuple(self.inv_xs))  # max |a| / xscale of a point or tangent
        #: whether a tangent turned faster than :data:`MAX_TANGENT_TURN` allows (:func:`numkin.unrolled.unrolled_kink`)
        self.kinked1 = unrolled_kink(self.n, tuple(self.inv_xs), MAX_TANGENT_TURN, TREND_REACH)
        self._fjt = comp.scalar_FJT
        self._newton1 = self.blocks.newton1 if self.symbolic else None
        self._f = comp.scalar_F
        self.last_previous = None
        self.started_on_default = False
        self.crossings: list = []  # change points passed: (input, loop)
        self.pending = None  # a change point passed, raised once the march has gone on past it
        #: (input of the default guess, the sweep's first input) while the march goes from one to the other
        self.approach = None
        self.before_sweep: list = []  # change points passed on that way only: (input, loop)
        self.passed_on_way: list = []  # every change point passed on that way, passed again by the sweep or not
        self.floor = 0.0  # round-off floor of the batch's residuals (set before the batch)
        #: Point evaluations of the residuals and of the Jacobian so far (a fused evaluation counts
        #: in both; a finite-difference Jacobian is one Jacobian and its n or 2n residuals).
        self.nfev = 0
        self.njev = 0
        self.fd_cost = 0 if self.symbolic else (self.n if jacobian == "forward" else 2 * self.n)

    # ------------------------------------------------------------ one point
    def eval1(self, x, t):
        """Residuals, Jacobian rows and dF/dt at one point (flat list), or None where undefined."""
        self.nfev += 1
        self.njev += 1
        try:
            v = self._fjt(*x, t, *self.pt)
        except MATH_ERRORS:
            return None
        return v if math.isfinite(sum(v)) else None

    def resid1(self, x, t):
        self.nfev += 1
        try:
            f = self._f(*x, t, *self.pt)
        except MATH_ERRORS:
            return None
        return f if math.isfinite(sum(f)) else None

    def eval1_fd(self, x, t):
        """Residuals and finite-difference Jacobian rows at one point (flat list), or None."""
        f = self.resid1(x, t)
        if f is None:
            return None
        tt = np.array([t])
        comp, p = self.comp, self.p
        self.nfev += self.fd_cost
        self.njev += 1
        jac = fd_jacobian(lambda z: comp.F(z, tt, p), np.array(x, dtype=float)[:, None],
                          np.array(f, dtype=float)[:, None], self.jacobian, self.xs_arr)
        rows = jac[0].ravel().tolist()
        return f + rows if math.isfinite(sum(rows)) else None

    def _floor(self, x, t):
        """The round-off floor of the scaled residual at the point ``x`` (list) and input ``t``."""
        return residual_floor([a * w for a, w in zip(x, self.inv_xs)], t)

    def newton1(self, x, t, maxiter, cond_max=None, loop=None):
        """Newton-Raphson at one input from ``x`` (list): the scalar kernel.

        ``loop``: the index of one loop, whose unknowns alone Newton moves,
        every other unknown held (the residual, the step and the conditioning
        rule are that loop's: :meth:`numkin.blocks.BlockStructure.update1_loop`).

        Returns ``(x, status, iterations, residual, v)``: status is
        ``"converged"``, ``"singular"``, ``"diverged"`` or ``"maxiter"``;
        ``v`` is :meth:`eval1` at the returned ``x`` (None if unknown).
        With ``cond_max`` a Jacobian whose loop blocks have a larger scaled
        condition number is refused as singular (the conditioning rule of
        :mod:`numkin.newton`); otherwise only an exactly singular or
        non-finite solve is, and an exactly singular one where the residual is
        already within ``tol`` (a root on a singular position) has converged.
        """
        n, nn, fscale, tol = self.n, self.nn, self.fscale, self.tol
        written_out = self._newton1 if loop is None else self.symbolic and self.blocks.loop_newton1(loop)
        if written_out:
            x, status, it, res, v, evals = written_out(self._fjt, x, t, self.pt, maxiter, fscale, tol, self._floor,
                                                       MATH_ERRORS, cond_max)
            self.nfev += evals
            self.njev += evals
            return x, status, it, res, v
        if loop is None:
            update, (a, b) = self.blocks.update1, (0, n)
        else:
            update, (a, b) = (lambda v_, x_: self.blocks.update1_loop(v_, x_, loop)), self.blocks.blocks[loop]
        evaluate = self.eval1 if self.symbolic else self.eval1_fd
        v = evaluate(x, t)
        if v is None:
            return x, "diverged", 0, math.nan, None
        res = max([abs(f) for f in v[a:b]]) / fscale
        prev = math.inf
        it = 0
        status = "maxiter"
        while it < maxiter:
            if cond_max is not None:
                conds = self.blocks.cond1(v[n : n + nn])
                if is_singular(max(conds) if loop is None else conds[loop], cond_max):
                    status = "singular"
                    break
            x_new, step = update(v, x)
            if x_new is None:  # no step; none needed if x is a root already (on a singular position)
                status = "converged" if cond_max is None and res <= tol else "singular"
                break
            x = x_new
            it += 1
            v = evaluate(x, t)
            if v is None:
                return x, "diverged", it, math.nan, None
            res = max([abs(f) for f in v[a:b]]) / fscale
            floor = 0.0
            if res > tol and step >= 0.9 * prev:  # stalled above tol: is it the round-off floor?
                floor = self._floor(x, t)
            if has_converged(res, step, prev, tol, floor):
                status = "converged"
                break
            prev = step
        if not self.symbolic:
            v = self.eval1(x, t)
        return x, status, it, res, v

    def nearest_turn(self, x, ref):
        """``x`` with every angle moved by whole turns to lie nearest ``ref``; and whether any moved."""
        moved = False
        for k in self.angle_idx:
            if abs(x[k] - ref[k]) > math.pi:
                if not moved:
                    x, moved = list(x), True
                x[k] = ref[k] + math.remainder(x[k] - ref[k], TWO_PI)
        return x, moved

    def local1(self, v):
        """Tangent dq/dt and loop orientations at a solved point; (None, None) if its Jacobian is singular."""
        if v is None:
            return None, None
        d, o, _ = self.blocks.local1(v)
        return d, o

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
        self.nfev += t.size
        self.njev += t.size
        v = self.comp.FJ_rows(x, t, self.p, fixed)
        return stack_rows(v[: self.n], t.size), v[self.n :]

    def newton_batch(self, x, t, active, maxiter=CORRECTOR_ITERATIONS, overwrite=False):
        """Newton on the columns ``active`` of ``x`` (n, N) at the inputs ``t``; other columns are kept.

        ``numkin.newton.solve_batch`` with the fused residual-and-Jacobian
        rows of :meth:`CompiledMechanism.FJ_rows` (the terms of the input
        alone computed once) and the block-triangular solve. Returns ``x``,
        ``converged`` (N,), ``iterations`` (N,), and the residuals (n, N) and
        Jacobian rows at the returned ``x``. ``overwrite``: iterate in ``x``
        itself (a float array the caller no longer needs). Call it under
        ``numpy.errstate(all="ignore")``.
        """
        nn = self.nn
        x = np.asarray(x, dtype=float)
        comp, p = self.comp, self.p
        floor = self.floor
        N = x.shape[1]
        if self.symbolic:
            fixed_all = comp.fixed_terms(t, p)
            if self.blocks.newton_batch is not None and N < COMPACT_MIN:
                # few columns: every column at every iteration, the iteration written out
                if not (overwrite and x.flags.writeable and x.flags.c_contiguous):
                    x = np.array(x, dtype=float, order="C")
                act = np.ones(N, dtype=bool) if active is None else np.asarray(active, dtype=bool)
                out = self.blocks.newton_batch(comp.FJ_kernel, x, t, (*fixed_all, *self.pt), act, maxiter, self.fscale,
                                               self.tol, floor, has_converged)
                if out is not None:
                    converged, _, iterations, v, evaluations = out
                    self.nfev += evaluations * N
                    self.njev += evaluations * N
                    return x, converged, iterations, stack_rows(v[: self.n], N), v[self.n :]

            def evaluate(z, idx):
                if idx is None:
                    return self.eval_batch(z, t, fixed_all)
                return self.eval_batch(z, t.take(idx), [u.take(idx) if np.ndim(u) else u for u in fixed_all])

            def jacobian(z, idx, fz, jz):
                return jz

        else:
            xs = self.xs_arr

            def evaluate(z, idx):
                self.nfev += z.shape[1]
                return comp.F(z, t if idx is None else t.take(idx), p), None

            def jacobian(z, idx, fz, jz):
                tz = t if idx is None else t.take(idx)
                self.nfev += self.fd_cost * z.shape[1]
                self.njev += z.shape[1]
                return list(fd_jacobian(lambda w: comp.F(w, tz, p), z, fz, self.jacobian, xs).reshape(z.shape[1], nn).T)

        step = self.blocks.newton_step
        out = solve_batch(
            evaluate, jacobian, lambda jac, f, idx: step(jac, f), x, fscale=self.fscale, xscale=self.xs_arr,
            tol=self.tol, maxiter=maxiter, active=active, floor=floor, fd_cost=self.fd_cost, compact_min=COMPACT_MIN,
            history=False,
            take=lambda jac, idx: [r.take(idx) if np.ndim(r) else r for r in jac],
            put=lambda jac, sub, idx: [_scatter(r, rz, idx, N) for r, rz in zip(jac, sub)], overwrite=overwrite,
        )
        if self.symbolic:
            return out.x, out.converged, out.iterations, out.f, out.jac
        f, jac = self.eval_batch(out.x, t)
        return out.x, out.converged, out.iterations, f, jac

    # -------------------------------------------------------------- sequential
    def march(self, t0, x0, d0, o0, t1, previous=None):
        """Continue from (t0, x0), tangent d0 and orientations o0, to the input t1.

        ``previous`` is an earlier point ``(t, x)`` of the same branch for the
        quadratic predictor of the first step. Returns ``(x, d, o,
        iterations)`` at t1; ``last_previous`` keeps the point before it.
        """
        span = t1 - t0
        direction = 1.0 if span > 0 else -1.0
        step = min(self.max_step, abs(span))
        if previous is None:
            step = min(step, 0.5 * self.max_step)  # the first predictor is linear: start shorter
        min_step = 1e-9 * abs(span)  # (relative: a sweep over a tiny span is marched as any other)
        crossing_step = max(CROSSING_STEP, 64 * min_step)
        t, x, d, o = t0, x0, d0, o0
        t_prev, x_prev = previous[:2] if previous is not None else (None, None)
        d_prev = previous[2] if previous is not None and len(previous) > 2 else None
        iters = 0
        size = self.size
        newton1, fjt, pt, fscale, tol, floor = self._newton1, self._fjt, self.pt, self.fscale, self.tol, self._floor
        local1 = self.blocks.local1
        kinked = self.kinked1
        for _ in range(MAX_TRIALS):
            if t == t1:
                break
            remaining = abs(t1 - t)
            dt = step
            rate = 0.0
            if d is not None:  # no predicted change above MAX_PREDICTION
                rate = size(d)
                if rate * dt > MAX_PREDICTION:
                    dt = MAX_PREDICTION / rate
            if remaining <= dt * (1.0 + 1e-9):
                t_new = t1
            else:
                if remaining < 2.0 * dt:  # no short last step: split what is left in two
                    dt = 0.5 * remaining
                t_new = t + direction * dt
            if dt < min_step or t_new == t:
                self.fail(t0, x0, t, x, t_new, x, "singular", "singular", 0, math.nan)
            x_pred = self.predict1(t, x, d, t_prev, x_prev, t_new, rate, d_prev)
            # Newton from the prediction, the angles then taken on the prediction's turn: looked for only
            # where an angle moved by more than half a turn (angles are scaled by one: a smaller distance moves none)
            if newton1 is not None:
                x_new, status, it, res, v, evals = newton1(fjt, x_pred, t_new, pt, CORRECTOR_ITERATIONS, fscale, tol,
                                                           floor, MATH_ERRORS, None)
                self.nfev += evals
                self.njev += evals
            else:
                x_new, status, it, res, v = self.newton1(x_pred, t_new, CORRECTOR_ITERATIONS)
            ok = status == "converged"
            if ok:
                moved = self.distance(x_new, x_pred)
                if not moved <= math.pi:
                    x_new, turned = self.nearest_turn(x_new, x_pred)
                    if turned:  # polished on the prediction's turn
                        x_new, status, it2, res, v = self.newton1(x_new, t_new, CORRECTOR_ITERATIONS)
                        it += it2
                        ok = status == "converged"
                    moved = self.distance(x_new, x_pred)
            reason = status
            if ok and not moved <= MAX_CORRECTION:
                ok, reason = False, "correction"
            if ok:
                d_new, o_new, cond = local1(v) if v is not None else (None, None, math.inf)
                if o_new is None and d is not None and v is not None:
                    # a root where the Jacobian is singular (a change point on the grid, reached exactly):
                    # no tangent or orientation of its own; the branch's go on from the side it came from
                    d_new, o_new = d, o
                elif o_new is None:
                    ok, reason = False, "singular"
                elif o_new != o:
                    if dt > crossing_step:
                        ok, reason = False, "orientation"  # localise the crossing before deciding
                    else:
                        # every loop that changed orientation in this step, in the order the step passes them
                        places = {k: self.crossing(t, x, t_new, v, k) for k, (a, b) in enumerate(zip(o_new, o))
                                  if a != b}
                        for k in sorted(places, key=lambda k: direction * (places[k] - t)):
                            self.change_point(t, t_new, self.loop_names[k], places[k])
            if ok and d is not None:
                if not cond <= COND_TANGENT:
                    if dt > crossing_step:
                        # Next to a singular position the tangent is noise, so neither it nor the orientation
                        # (the other branch keeps it) tells the branches apart: localise as for a crossing.
                        ok, reason = False, "singular"
                    d_new = d  # a tangent solved through a near-singular Jacobian is noise: keep the last good one
                elif dt > crossing_step and kinked(t, d, t_prev, d_prev, t_new, d_new, rate):
                    # Where branches meet, the other branch keeps the orientation: only the
                    # tangent shows the switch. A smooth branch passes once the step is small.
                    ok, reason = False, "kink"
            if ok:
                if self.pending is not None and not min(t, t_new) <= self.pending[0] <= max(t, t_new):
                    self.raise_pending()  # a step wholly past the change point: the linkage goes on there
                t_prev, x_prev, d_prev = t, x, d
                t, x, d, o = t_new, x_new, d_new, o_new
                iters = it
                step = min(self.max_step, 2.0 * dt)
                continue
            step = 0.5 * dt
            if step < min_step:
                self.fail(t0, x0, t, x, t_new, x_new, status, reason, it, res)
        else:
            raise ConvergenceError(
                f"{self.mech.name}: the continuation from input {deg_text(t0, 3)} to {deg_text(t1, 3)} made no "
                f"progress in {MAX_TRIALS} trial steps (stopped at {deg_text(t, 6)})",
                input_value=float(t), loop=self.loop_names[0], iterations=MAX_TRIALS, cause="no progress",
            )
        self.last_previous = (t_prev, x_prev, d_prev) if t_prev is not None else None
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
                f"{self.mech.name}: limit (toggle) position of loop '{loop}' near {deg_text(t, 3)} "
                f"(condition number {cond:.3g}): the input cannot be driven past it on this branch",
                kind="toggle", input_value=float(t), loop=loop, cond=cond,
            )
        bad_loop, bad_res = self.worst1(x_try, t_next)
        if reason in ("correction", "orientation", "kink"):
            what = {
                "correction": "moves the solution too far",
                "orientation": "lands on another assembly branch",
                "kink": "turns the tangent abruptly (another branch meets this one)",
            }[reason]
            msg = (
                f"{self.mech.name}: no continuous solution from input {deg_text(t, 6)} to {deg_text(t_next, 6)}: "
                f"the smallest step {what} (loop '{bad_loop}'); the loop equations jump there"
            )
            cause = "jump"
        else:
            msg = (
                f"{self.mech.name}: Newton did not converge at input {deg_text(t_next, 3)} (condition number "
                f"{cond:.3g}): loop '{bad_loop}' residual {bad_res:.3g} after {iterations} iterations"
            )
            cause = "no convergence"
        raise ConvergenceError(msg, input_value=float(t_next), loop=bad_loop, residual=bad_res, iterations=iterations,
                               cause=cause)

def _scatter(row, sub, idx, N):
    """A Jacobian row (array or number) with the columns ``idx`` replaced by ``sub``."""
    if not np.ndim(row):
        if not np.ndim(sub):
            return row
        row = np.full(N, row, dtype=np.result_type(row, sub))
    row[idx] = sub
    return row

"""Position sweeps by continuation, on one assembly branch.

Algorithm
---------
1. Solve at the first input from the guess (Newton, up to ``maxiter`` steps);
   angles are taken nearest to the guess.
2. March sequentially to *nodes* no more than ``max_step`` apart: each step
   predicts with the tangent ``q' = -J^-1 dF/dt`` and corrects with Newton.
   A step is accepted only if Newton converges, the correction is small and
   the sign of every loop's Jacobian determinant (its *orientation*, constant
   along a branch) is unchanged; otherwise the step is halved.
3. Fill the grid points between nodes in one batch: a cubic Hermite predictor
   from the nodes' values and tangents, then Newton on all points at once.
   A point that fails the same acceptance tests is re-solved sequentially.

A change of orientation between two accepted points means the linkage passed
a singular position (a change point, where branches meet); a step that
shrinks to nothing against a growing condition number is a limit (toggle)
position. Both raise :class:`~numkin.BranchError` (or, with
``on_singular="report"``, are recorded in :attr:`Sweep.events` with a
warning). A Newton that fails elsewhere raises
:class:`~numkin.ConvergenceError`; a linkage that cannot be assembled at the
start raises :class:`~numkin.AssemblyError`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from .errors import AssemblyError, BranchError, ConvergenceError
from .newton import iterate, scaled_cond

__all__ = ["Sweep", "SweepEvent", "SingularityWarning", "run_sweep"]

#: Correction (scaled: rad, or lengths / length_scale) above which a continuation step is refused.
MAX_CORRECTION = 0.3
#: Condition number above which a point is reported as near-singular.
COND_WARN = 1e8
#: Condition number above which a Jacobian is treated as singular.
COND_MAX = 1e12
#: Newton steps allowed for a continuation corrector.
CORRECTOR_ITERATIONS = 12


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


def _deg(t: float) -> str:
    return f"{math.degrees(t):.3f}°"


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
    """State shared by the steps of one sweep."""

    def __init__(self, mech, jacobian, tol, max_step, on_singular):
        self.mech = mech
        self.jacobian = jacobian
        self.tol = tol
        self.max_step = max_step
        self.on_singular = on_singular
        self.events: list = []
        self.p = mech.parameter_values

    def newton(self, x0, t, maxiter=CORRECTOR_ITERATIONS, check_cond=True):
        F = self.mech.residual_function(t)
        J = self.mech.jacobian_function(t, self.jacobian)
        return iterate(
            F, J, x0, fscale=self.mech.length_scale, xscale=self.mech.xscale, tol=self.tol,
            maxiter=maxiter, cond_max=COND_MAX, check_cond=check_cond,
        )

    def local(self, x, t):
        """Orientation (loops, M) and tangent dq/dt (n, M) at solved points, from one Jacobian.

        The tangent is NaN where the Jacobian cannot be solved.
        """
        mech = self.mech
        jac = mech.compiled.J(x, t, self.p)
        orient = np.array([np.sign(np.linalg.det(jac[:, s, s])) for s in mech.loop_slices])
        rhs = -mech.compiled.F_t(x, t, self.p).T[..., None]
        try:
            d = np.linalg.solve(jac, rhs)[..., 0].T
        except np.linalg.LinAlgError:
            d = np.full(x.shape, np.nan)
        return orient, np.where(np.all(np.isfinite(d), axis=0), d, np.nan)

    def worst_loop(self, x, t, which="residual"):
        table = self.mech.loop_residuals(x, t) if which == "residual" else self.mech.loop_conditions(x, t)
        name, vals = max(table.items(), key=lambda kv: np.nan_to_num(kv[1][0], nan=np.inf))
        return name, float(vals[0])

    def record(self, kind, t, loop, message, *, raise_kind=None):
        if raise_kind is not None and self.on_singular == "raise":
            raise BranchError(message, kind=raise_kind, input_value=float(t), loop=loop)
        self.events.append(SweepEvent(kind, float(t), loop, message))
        warnings.warn(message, SingularityWarning, stacklevel=4)

    def correction_ok(self, x, x_pred):
        return np.max(np.abs(x - x_pred) / self.mech.xscale[:, None], axis=0) <= MAX_CORRECTION

    # -------------------------------------------------------------- sequential
    def march(self, t0, x0, d0, o0, t1):
        """Continue from (t0, x0) with tangent d0 and orientation o0 to input t1."""
        span = t1 - t0
        direction = math.copysign(1.0, span)
        step = min(self.max_step, abs(span))
        min_step = 1e-9 * max(1.0, abs(span))
        t, x, d, o = t0, x0, d0, o0
        t_prev = x_prev = None
        iters = 0
        while abs(t1 - t) > 1e-15 * max(1.0, abs(t1)):
            dt = direction * min(step, abs(t1 - t))
            t_new = t1 if abs(t + dt - t1) <= 1e-15 * max(1.0, abs(t1)) else t + dt
            tt = np.array([t_new])
            x_pred = _predict(t, x, d, t_prev, x_prev, t_new)
            out = self.newton(x_pred[:, None], tt, check_cond=False)
            ok = bool(out.converged[0]) and bool(self.correction_ok(out.x, x_pred[:, None])[0])
            if ok:
                o_new, d_new = self.local(out.x, tt)
                o_new, d_new = o_new[:, 0], d_new[:, 0]
                if np.any(o_new == 0):
                    ok = False
                elif np.any(o_new != o):
                    k = int(np.flatnonzero(o_new != o)[0])
                    loop = self.mech.loops[k].name
                    if step > 64 * min_step:
                        ok = False  # localise the crossing before deciding
                    else:
                        self.record(
                            "change point", t_new, loop,
                            f"{self.mech.name}: loop '{loop}' passes a singular position between "
                            f"{_deg(t)} and {_deg(t_new)} (its Jacobian changes sign): the branches meet "
                            "there and the continuation is ambiguous",
                            raise_kind="change point",
                        )
            if ok:
                t_prev, x_prev = t, x
                t, x, o, d = t_new, out.x[:, 0], o_new, d_new
                iters = int(out.iterations[0])
                step = min(self.max_step, 2.0 * step)
                continue
            step /= 2.0
            if step < min_step:
                self.fail(t, x, t_new, out)
        return x, d, o, iters

    def fail(self, t, x, t_next, out):
        """Explain why the continuation cannot go from t to t_next, and raise."""
        loop, cond = self.worst_loop(x[:, None], np.array([t]), which="cond")
        if cond > 1e5 or bool(out.singular[0]):
            raise BranchError(
                f"{self.mech.name}: limit (toggle) position of loop '{loop}' near {_deg(t)} "
                f"(condition number {cond:.3g}): the input cannot be driven past it on this branch",
                kind="toggle", input_value=float(t), loop=loop,
            )
        bad_loop, res = self.worst_loop(out.x, np.array([t_next]))
        raise ConvergenceError(
            f"{self.mech.name}: Newton did not converge at input {_deg(t_next)}: loop '{bad_loop}' "
            f"residual {res:.3g} after {int(out.iterations[0])} iterations",
            input_value=float(t_next), loop=bad_loop, residual=res, iterations=int(out.iterations[0]),
        )


def _predict(t, x, d, t_prev, x_prev, t_new):
    """Predictor of a continuation step: the quadratic through the previous point
    with the current tangent, or the tangent alone at the first step."""
    if not np.all(np.isfinite(d)):
        return x if x_prev is None else x + (x - x_prev) * (t_new - t) / (t - t_prev)
    s = t_new - t
    if x_prev is None:
        return x + d * s
    h = t_prev - t
    c = (x_prev - x - d * h) / (h * h)
    return x + d * s + c * s * s


def _validate_inputs(inputs) -> np.ndarray:
    t = np.asarray(inputs, dtype=float)
    if t.ndim == 0:
        t = t.reshape(1)
    if t.ndim != 1 or t.size == 0:
        raise ValueError(f"inputs must be a non-empty 1-D array of input values (rad), got shape {t.shape}")
    if not np.all(np.isfinite(t)):
        raise ValueError(f"inputs[{int(np.flatnonzero(~np.isfinite(t))[0])}] is not finite")
    if t.size > 1:
        d = np.diff(t)
        if not (np.all(d > 0) or np.all(d < 0)):
            k = int(np.flatnonzero(np.sign(d) != np.sign(d[0]))[0]) if np.any(d != 0) else 0
            raise ValueError(f"inputs must be strictly monotonic for continuation (check inputs[{k}:{k + 2}])")
    return t


def _start(ctx: _Continuation, t0: float, guess, maxiter: int) -> np.ndarray:
    """Solve the first point from the guess (continuing from ``guess_input`` if needed)."""
    mech = ctx.mech
    g = mech.default_guess if guess is None else guess
    if guess is None and g is not None and not callable(g) and mech.guess_input is not None and mech.guess_input != t0:
        x_g = _solve_first(ctx, mech.guess_input, mech.guess_vector(g, mech.guess_input), maxiter)
        o, d = ctx.local(x_g[:, None], np.array([mech.guess_input]))
        x, _, _, _ = ctx.march(mech.guess_input, x_g, d[:, 0], o[:, 0], t0)
        return x
    return _solve_first(ctx, t0, mech.guess_vector(g, t0), maxiter)


def _solve_first(ctx, t0, x_guess, maxiter):
    mech = ctx.mech
    tt = np.array([t0])
    out = ctx.newton(x_guess[:, None], tt, maxiter=maxiter)
    if out.singular[0]:
        loop, cond = ctx.worst_loop(out.x, tt, which="cond")
        raise BranchError(
            f"{mech.name}: the Jacobian of loop '{loop}' is singular at input {_deg(t0)} "
            f"(condition number {cond:.3g}): a toggle or change point, where the branch cannot be chosen; "
            "start the sweep at another input",
            kind="singular", input_value=float(t0), loop=loop,
        )
    if not out.converged[0]:
        loop, res = ctx.worst_loop(out.x, tt)
        raise AssemblyError(
            f"{mech.name}: cannot assemble at input {_deg(t0)}: Newton from the guess did not converge "
            f"(loop '{loop}' residual {res:.3g} after {int(out.iterations[0])} iterations); "
            "check the dimensions or give a better guess"
        )
    x = out.x[:, 0].copy()
    for k, name in enumerate(mech.unknowns):
        if name in mech.angles:
            x[k] = x_guess[k] + math.remainder(x[k] - x_guess[k], 2 * math.pi)
    return x


def _nodes(t: np.ndarray, max_step: float) -> np.ndarray:
    """Grid indices marched sequentially: at most ``max_step`` apart where the grid allows."""
    if t.size <= 2:
        return np.arange(t.size)
    h = np.abs(np.diff(t)).max()
    every = max(1, int(max_step // h)) if h > 0 else 1
    idx = np.arange(0, t.size, every)
    if idx[-1] != t.size - 1:
        idx = np.append(idx, t.size - 1)
    return idx


def run_sweep(mech, inputs, guess=None, *, jacobian="symbolic", tol=1e-12, maxiter=50,
              max_step=math.radians(10.0), on_singular="raise"):
    """Solve ``mech`` over ``inputs`` by continuation; see :meth:`Mechanism.sweep`."""
    if on_singular not in ("raise", "report"):
        raise ValueError(f"on_singular must be 'raise' or 'report', got {on_singular!r}")
    if not (max_step > 0 and math.isfinite(max_step)):
        raise ValueError(f"max_step must be a positive angle in rad, got {max_step!r}")
    if not (tol > 0 and math.isfinite(tol)):
        raise ValueError(f"tol must be a positive number, got {tol!r}")
    t = _validate_inputs(inputs)
    mech.jacobian_function(t, jacobian)  # validates the name
    mech.check_assembly(t)
    ctx = _Continuation(mech, jacobian, tol, max_step, on_singular)
    n, N = len(mech.unknowns), t.size
    X = np.full((n, N), np.nan)
    D = np.full((n, N), np.nan)
    O = np.zeros((len(mech.loops), N))
    iters = np.zeros(N, dtype=int)

    x0 = _start(ctx, t[0], guess, maxiter)
    X[:, 0] = x0
    o0, d0 = ctx.local(x0[:, None], t[:1])
    O[:, 0], D[:, 0] = o0[:, 0], d0[:, 0]

    nodes = _nodes(t, max_step)
    for a, b in zip(nodes[:-1], nodes[1:]):
        X[:, b], D[:, b], O[:, b], iters[b] = ctx.march(t[a], X[:, a], D[:, a], O[:, a], t[b])

    _fill(ctx, t, X, D, O, iters, nodes)

    cond = np.max(np.stack(list(mech.loop_conditions(X, t).values())), axis=0)
    residual = np.max(np.stack(list(mech.loop_residuals(X, t).values())), axis=0)
    _report_near_singular(ctx, t, X, cond)
    return Sweep(mech, t, X, iters, residual, cond, ctx.events, jacobian, tol)


def _fill(ctx, t, X, D, O, iters, nodes):
    """Solve the grid points between nodes in one Newton batch (cubic Hermite predictor)."""
    fine = np.setdiff1d(np.arange(t.size), nodes)
    if fine.size == 0:
        return
    right = np.searchsorted(nodes, fine)
    a, b = nodes[right - 1], nodes[right]
    delta = t[b] - t[a]
    s = (t[fine] - t[a]) / delta
    h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
    h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
    x_pred = h00 * X[:, a] + h10 * delta * D[:, a] + h01 * X[:, b] + h11 * delta * D[:, b]
    out = ctx.newton(x_pred, t[fine], check_cond=False)
    o = ctx.mech.loop_orientations(out.x, t[fine])
    ok = (
        out.converged
        & ctx.correction_ok(out.x, x_pred)
        & np.all(o == O[:, a], axis=0)
        & np.all(O[:, a] == O[:, b], axis=0)
    )
    good = fine[ok]
    X[:, good] = out.x[:, ok]
    O[:, good] = o[:, ok]
    iters[good] = out.iterations[ok]
    # Points the batch could not place safely are reached one by one from their left node.
    for k in fine[~ok]:
        left = k - 1
        if not np.all(np.isfinite(D[:, left])):
            D[:, left] = ctx.local(X[:, left : left + 1], t[left : left + 1])[1][:, 0]
        X[:, k], D[:, k], O[:, k], iters[k] = ctx.march(t[left], X[:, left], D[:, left], O[:, left], t[k])


def _report_near_singular(ctx, t, X, cond):
    singular = np.flatnonzero(~(cond <= COND_MAX))
    if singular.size:
        k = singular[0]
        loop, _ = ctx.worst_loop(X[:, k : k + 1], t[k : k + 1], which="cond")
        ctx.record(
            "singular", t[k], loop,
            f"{ctx.mech.name}: the Jacobian of loop '{loop}' is singular at input {_deg(t[k])} "
            f"(condition number {cond[k]:.3g}): a toggle or change point, where the branch cannot be told",
            raise_kind="singular",
        )
    near = np.flatnonzero((cond > COND_WARN) & (cond <= COND_MAX))
    if near.size == 0:
        return
    k = near[np.argmax(cond[near])]
    loop, _ = ctx.worst_loop(X[:, k : k + 1], t[k : k + 1], which="cond")
    ctx.events.append(
        SweepEvent(
            "near-singular", float(t[k]), loop,
            f"{ctx.mech.name}: {near.size} point(s) near a singular position of loop '{loop}' "
            f"(condition number up to {cond[k]:.3g} at {_deg(t[k])}): expect lost digits there",
        )
    )
    warnings.warn(ctx.events[-1].message, SingularityWarning, stacklevel=3)

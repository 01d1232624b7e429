"""Multivariable Newton-Raphson with a symbolic or finite-difference Jacobian.

The iteration is written once, for a *batch* of independent systems (one per
input angle of a sweep), and :func:`newton` is that iteration applied to a
batch of one. Each step solves ``J(x) dx = -F(x)``; a Jacobian whose
condition number exceeds ``cond_max`` is reported as singular and never
divided through.

The stopping, conditioning and finite-difference rules are in
:mod:`numkin.newton_rules` (their names are importable from here too).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np

from .errors import InputError
from .newton_rules import (  # noqa: F401  (re-exported: one place for the rules, importable from here)
    COND_MAX,
    COND_WARN,
    EPS,
    JACOBIANS,
    TOL_MIN,
    check_tol,
    colmax,
    fd_jacobian,
    fd_step,
    has_converged,
    is_singular,
    residual_floor,
    scaled_cond,
)

__all__ = [
    "newton", "NewtonResult", "JACOBIANS", "has_converged", "check_tol", "is_singular", "fd_step",
    "fd_jacobian", "COND_MAX", "COND_WARN", "TOL_MIN", "solve_batch", "dense_solver", "colmax", "iterate",
    "residual_floor", "scaled_cond", "BatchResult", "COMPACT_MIN",
]

@dataclass(frozen=True, repr=False)
class NewtonResult:
    """Outcome of one Newton-Raphson solve (fields as in scipy's ``OptimizeResult``).

    Attributes
    ----------
    x : ndarray
        Last iterate (the solution when ``converged``).
    converged : bool
        Whether the stopping rule was met.
    iterations : int
        Newton steps taken.
    residual_norms : ndarray
        Scaled residual norm at the start and after every step
        (``iterations + 1`` values).
    step_norms : ndarray
        Scaled step norm of every step (``iterations`` values).
    cond : float
        Condition number of the (scaled) Jacobian at the last iterate.
    message : str
        What happened, in words.
    residual : ndarray
        Residual vector at ``x``.
    iterates : ndarray, shape (iterations + 1, n)
        The starting point and every iterate, in order (the last is ``x``).
    nfev : int
        Evaluations of the residual function (finite-difference columns
        included), as scipy counts them.
    njev : int
        Evaluations of the Jacobian (symbolic or by finite differences).
    success : bool
        ``converged`` under scipy's name.
    nit : int
        ``iterations`` under scipy's name.
    """

    x: np.ndarray
    converged: bool
    iterations: int
    residual_norms: np.ndarray
    step_norms: np.ndarray
    cond: float
    message: str
    residual: np.ndarray = field(default_factory=lambda: np.empty(0))
    iterates: np.ndarray = field(default_factory=lambda: np.empty((0, 0)))
    nfev: int = 0
    njev: int = 0

    @classmethod
    def from_batch(cls, out, k, cond, message):
        """The result of column ``k`` of a ``BatchResult`` (recorded with ``record=True``)."""
        it = int(out.iterations[k])
        iterates = np.array([h[:, k] for h in out.x_history])[: it + 1] if out.x_history else np.empty((0, 0))
        return cls(
            x=out.x[:, k],
            converged=bool(out.converged[k]),
            iterations=it,
            residual_norms=np.array([h[k] for h in out.residual_history])[: it + 1],
            step_norms=np.array([s[k] for s in out.step_history if np.isfinite(s[k])]),
            cond=float(cond),
            message=message,
            residual=out.f[:, k],
            iterates=iterates,
            nfev=int(out.nfev[k]),
            njev=int(out.njev[k]),
        )

    @property
    def success(self) -> bool:
        """``converged``, as scipy's ``OptimizeResult`` names it."""
        return self.converged

    @property
    def nit(self) -> int:
        """``iterations``, as scipy's ``OptimizeResult`` names it."""
        return self.iterations

    def __repr__(self) -> str:
        return (
            f"NewtonResult(converged={self.converged}, iterations={self.iterations}, "
            f"x={np.array2string(np.asarray(self.x), precision=10)}, "
            f"residual={self.residual_norms[-1]:.3g}, cond={self.cond:.3g}, "
            f"message={self.message!r})"
        )

    def convergence_order(self) -> np.ndarray:
        """Estimated order ``p_k = log(s_{k+1}/s_k) / log(s_k/s_{k-1})`` from the step norms.

        Values near 2 show quadratic convergence; steps at the round-off
        floor (below ``1e-14``) are left out.
        """
        s = np.asarray(self.step_norms, dtype=float)
        s = s[s > 1e-14]
        if s.size < 3:
            return np.empty(0)
        return np.log(s[2:] / s[1:-1]) / np.log(s[1:-1] / s[:-2])


@dataclass
class BatchResult:
    """Newton on a batch of systems: every field has one entry per system."""

    x: np.ndarray  # (n, N)
    converged: np.ndarray  # (N,)
    singular: np.ndarray  # (N,)
    iterations: np.ndarray  # (N,)
    residual: np.ndarray  # (N,) scaled max-norm
    residual_history: list  # of (N,) arrays
    step_history: list  # of (N,) arrays
    f: np.ndarray  # (n, N) residual vectors
    nfev: np.ndarray = None  # (N,) residual evaluations per system
    njev: np.ndarray = None  # (N,) Jacobian evaluations per system
    x_history: list = field(default_factory=list)  # of (n, N) arrays, with record=True
    jac: object = None  # the fused Jacobian at x, from solve_batch


def _solve(jac, rhs, fscale, xscale, cond_max):
    """Solve a batch ``jac @ dx = rhs``; systems that are (near) singular get NaN and a flag."""
    try:
        dx = np.linalg.solve(jac, rhs[..., None])[..., 0]
        bad = ~np.all(np.isfinite(dx), axis=1)
    except np.linalg.LinAlgError:
        dx = np.full(rhs.shape, np.nan, dtype=np.result_type(jac, rhs))
        bad = np.ones(rhs.shape[0], dtype=bool)
    # Only a condition number tells "solvable" from "solved through a singular matrix".
    cond = scaled_cond(jac, fscale, xscale) if cond_max is not None else None
    if cond is not None:
        bad |= ~(cond <= cond_max)
    if bad.any():
        for k in np.flatnonzero(bad):
            if cond is not None and cond[k] <= cond_max:
                dx[k] = np.linalg.solve(jac[k], rhs[k])
                bad[k] = False
            else:
                dx[k] = np.nan
    return dx, bad


#: Batches smaller than this iterate on whole arrays to the end (gathering the few active
#: columns costs more than it saves); larger ones on the active columns once few are left.
COMPACT_MIN = 2000


def _take_dense(jac, idx):
    return jac[idx]


def _put_dense(jac, sub, idx):
    jac[idx] = sub
    return jac


def solve_batch(evaluate, jacobian, solve, x0, *, fscale, xscale, tol=1e-12, maxiter=50, active=None, floor=0.0,
                record=False, history=True, take=_take_dense, put=_put_dense, fd_cost=0, compact_min=COMPACT_MIN,
                overwrite=False):
    """The one Newton-Raphson iteration of numkin, on a batch of independent systems.

    Every Newton path (:func:`newton`, :meth:`Mechanism.solve`, the
    complex-step derivatives, the batch of a sweep) is this loop with its own
    evaluation and linear solve plugged in; the stopping rule is
    :func:`has_converged`, the conditioning rule the ``solve`` plug's.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(x, idx) -> (f, jac)``: residuals (n, M) at ``x`` (n, M),
        the columns ``idx`` of the batch (an index array, or None for all),
        and the Jacobian if it comes with them (fused), else None.
    jacobian : callable
        ``jacobian(x, idx, f, jac) -> J``: the Jacobian in the form ``solve``
        takes (returns ``jac`` itself when it is fused).
    solve : callable
        ``solve(J, f, idx) -> (dx, bad)``: the Newton step ``-J^-1 f`` (n, M)
        and a mask of the systems refused (singular, non-finite, or over the
        condition-number limit); their ``dx`` is ignored.
    x0 : ndarray (n, N)
    fscale : float or ndarray (N,)
        Residual scale.
    xscale : ndarray (n,)
        Unknown scales.
    active : ndarray of bool (N,), optional
        Systems to solve; the others are kept as they are.
    floor : float
        Round-off floor of the scaled residual (see :func:`has_converged`).
    record : bool
        Keep every iterate in ``BatchResult.x_history``.
    history : bool
        Keep the residual and step norms of every iteration and count
        evaluations (``nfev``, ``njev``); a sweep's batch goes without.
    take, put : callable
        Gather / scatter the columns ``idx`` of a fused Jacobian (for
        compaction).
    fd_cost : int
        Residual evaluations per Jacobian (finite differences), for ``nfev``.
    overwrite : bool
        Iterate in ``x0`` itself (a float array the caller no longer needs)
        instead of a copy.

    Returns
    -------
    BatchResult
        With ``jac``, the fused Jacobian at the returned ``x`` (None if not fused).
    """
    x = x0 if overwrite and isinstance(x0, np.ndarray) and x0.flags.writeable else np.array(x0, copy=True)
    n, N = x.shape
    inv_xs = 1.0 / np.asarray(xscale, dtype=float)[:, None]
    unit = bool(np.all(inv_xs == 1.0))
    fscale = float(fscale) if not np.ndim(fscale) else np.broadcast_to(np.asarray(fscale, dtype=float), (N,))
    f, jac = evaluate(x, None)
    fmax = colmax(np.abs(f))
    converged = np.zeros(N, dtype=bool)
    singular = np.zeros(N, dtype=bool)
    iterations = np.zeros(N, dtype=int)
    nfev = np.ones(N, dtype=int) if history else None
    njev = np.zeros(N, dtype=int) if history else None
    act = np.isfinite(fmax) if active is None else np.asarray(active, dtype=bool) & np.isfinite(fmax)
    res_hist = [fmax / fscale]
    step_hist = []
    x_hist = [x.copy()] if record else []
    prev = np.full(N, np.inf)
    for _ in range(maxiter):
        M = int(np.count_nonzero(act))
        if M == 0:
            break
        if M * 4 > N or N < compact_min:  # whole arrays; the inactive columns do not move
            dx, bad = solve(jacobian(x, None, f, jac), f, None)
            f = jac = None  # not needed again: freed before the next evaluation
            bad = bad & act  # (the plug's array is left as it was)
            upd = act & ~bad
            if M < N or bad.any():
                dx[:, ~upd] = 0.0
            if dx.dtype == x.dtype:
                x += dx  # in place: no copy per iteration (recorded iterates are copies)
            else:
                x = x + dx
            np.abs(dx, out=dx)
            if not unit:
                dx *= inv_xs
            step = colmax(dx)
            del dx
            f, jac = evaluate(x, None)
            fmax = colmax(np.abs(f))
        else:  # the active columns only
            idx = np.flatnonzero(act)
            z, fz = x.take(idx, axis=1), f.take(idx, axis=1)
            dx, bad_z = solve(jacobian(z, idx, fz, None if jac is None else take(jac, idx)), fz, idx)
            if bad_z.any():
                dx[:, bad_z] = 0.0
            z = z + dx
            fz, jz = evaluate(z, idx)
            x[:, idx] = z
            f[:, idx] = fz
            if jac is not None:
                jac = put(jac, jz, idx)
            bad = np.zeros(N, dtype=bool)
            bad[idx] = bad_z
            upd = act & ~bad
            step = np.full(N, np.inf)
            step[idx] = colmax(np.abs(dx) if unit else np.abs(dx) * inv_xs)
            fmax[idx] = colmax(np.abs(fz))
        iterations += upd
        singular |= bad
        res = fmax / fscale
        done = upd & has_converged(res, step, prev, tol, floor)
        if history:
            njev += act
            nfev += act * fd_cost + upd
            step_hist.append(np.where(upd, step, np.nan))
            res_hist.append(res)
        if record:
            x_hist.append(x.copy())
        converged |= done
        act &= ~(done | bad) & np.isfinite(fmax)
        prev = np.where(upd, step, prev)
    return BatchResult(x, converged, singular, iterations, fmax / fscale, res_hist, step_hist, f, nfev, njev, x_hist,
                       jac)


def dense_solver(fscale, xscale, cond_max=COND_MAX):
    """The ``solve`` plug for (M, n, n) Jacobians: LU with the conditioning rule (``cond_max=None``:
    only exactly singular or non-finite solves are refused)."""
    fscale = np.broadcast_to(np.asarray(fscale, dtype=float), (np.size(fscale),)) if np.ndim(fscale) else fscale
    xscale = np.asarray(xscale, dtype=float)

    def solve(jac, f, idx):
        fs = fscale if not np.ndim(fscale) else (fscale if idx is None else fscale[idx])
        dx, bad = _solve(jac, -f.T, np.broadcast_to(fs, (jac.shape[0],)), xscale, cond_max)
        return dx.T, bad

    return solve


def iterate(F, J, x0, *, fscale, xscale, tol=1e-12, maxiter=50, cond_max=COND_MAX, check_cond=True, record=False,
            floor=0.0):
    """Newton-Raphson on a batch of independent systems, dense linear solves (``solve_batch``).

    Parameters
    ----------
    F : callable
        ``F(x, idx)`` returns residuals of shape (n, M) for ``x`` of shape
        (n, M), the columns ``idx`` (an index array) of the batch: a
        mechanism uses ``idx`` to pick the matching input angles.
    J : callable or str
        ``J(x, idx)`` returns Jacobians of shape (M, n, n), or ``"forward"`` /
        ``"central"`` for finite differences of ``F``.
    x0 : ndarray, shape (n, N)
        Starting points.
    fscale : float or ndarray (N,)
        Residual scale (a length).
    xscale : ndarray (n,)
        Unknown scales (1 for angles, a length for lengths).
    check_cond : bool
        Compute condition numbers at every step to refuse near-singular
        solves (``cond > cond_max``). With ``False`` only an exactly singular
        or non-finite solve is refused.
    record : bool
        Keep every iterate in ``BatchResult.x_history``.
    floor : float
        Round-off floor of the scaled residual (see :func:`has_converged`).

    Returns
    -------
    BatchResult
    """
    x0 = np.asarray(x0)
    n, N = x0.shape
    xscale = np.asarray(xscale, dtype=float)
    every = np.arange(N)

    def evaluate(x, idx):
        return F(x, every if idx is None else idx), None

    if isinstance(J, str):
        method = J

        def jacobian(x, idx, f, _):
            i = every if idx is None else idx
            return fd_jacobian(lambda z: F(z, i), x, f, method, xscale)

        fd_cost = n if method == "forward" else 2 * n
    else:

        def jacobian(x, idx, f, _):
            return J(x, every if idx is None else idx)

        fd_cost = 0
    solve = dense_solver(fscale, xscale, cond_max if check_cond else None)
    return solve_batch(evaluate, jacobian, solve, x0, fscale=fscale, xscale=xscale, tol=tol, maxiter=maxiter,
                       record=record, fd_cost=fd_cost, compact_min=0, floor=floor)


def _sympy_system(exprs, unknowns):
    """Compile a sympy system once: residual and symbolic Jacobian functions of x."""
    import sympy as sp

    from .compiled import vector_function

    exprs = list(exprs)
    syms = [sp.Symbol(u) if isinstance(u, str) else u for u in unknowns]
    extra = set().union(*(sp.sympify(e).free_symbols for e in exprs)) - set(syms)
    if extra:
        names = ", ".join(sorted(str(s) for s in extra))
        raise InputError(
            f"unknown symbol(s) {names} in the residuals: substitute a value (expr.subs) "
            "or list them in `unknowns`"
        )
    if len(exprs) != len(syms):
        raise InputError(
            f"`fun` has {len(exprs)} residuals for {len(syms)} unknowns: the system must be square"
        )
    jac = sp.Matrix(exprs).jacobian(syms)
    f = vector_function(exprs, syms)
    j = vector_function(list(jac), syms)
    n = len(syms)

    def F(x, idx=None):
        return f(*x)

    def J(x, idx=None):
        return np.moveaxis(j(*x).reshape(n, n, -1), -1, 0)

    return F, J


def newton(
    fun,
    x0,
    *,
    unknowns: Sequence | None = None,
    jacobian: str | Callable = None,
    args: tuple = (),
    tol: float = 1e-12,
    maxiter: int = 50,
    fscale: float = 1.0,
    xscale=1.0,
    cond_max: float = 1e12,
) -> NewtonResult:
    """Solve ``F(x) = 0`` by multivariable Newton-Raphson.

    Parameters
    ----------
    fun : callable or sequence of sympy expressions
        ``fun(x, *args)`` returning the residual vector, or the residual
        expressions themselves (then ``unknowns`` names their symbols).
    x0 : array_like, shape (n,)
        Starting guess.
    unknowns : sequence of sympy symbols or str, optional
        Required when ``fun`` is symbolic; gives the order of ``x``.
    jacobian : {"symbolic", "forward", "central"} or callable, optional
        ``"symbolic"`` (default for sympy systems) differentiates with sympy
        and lambdifies once; ``"forward"``/``"central"`` (default
        ``"central"`` for callables) use finite differences with the step rule
        of this module; a callable ``jac(x, *args)`` returns the (n, n) matrix.
    tol : float
        Relative tolerance of the stopping rule (module docstring).
    maxiter : int
        Maximum number of Newton steps.
    fscale, xscale : float or array_like
        Residual and unknown scales of the stopping rule.
    cond_max : float
        Jacobians with a larger (scaled) condition number are refused as singular.

    Returns
    -------
    NewtonResult

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> res = newton([x**2 + y**2 - 4, x - y], [1.0, 0.5], unknowns=[x, y])
    >>> res.converged, round(float(res.x[0]), 12)
    (True, 1.414213562373)
    >>> import numpy as np
    >>> res = newton(lambda v: np.array([np.cos(v[0]) - v[0]]), [1.0], jacobian="forward")
    >>> round(float(res.x[0]), 10)
    0.7390851332
    """
    if x0 is None or isinstance(x0, (str, bytes, dict)):
        raise InputError(f"x0 must be the guess, a number or a sequence of numbers, got {x0!r}")
    try:
        x0 = np.atleast_1d(np.asarray(x0, dtype=float if not np.iscomplexobj(x0) else complex))
    except (TypeError, ValueError):
        raise InputError(f"x0 must be the guess, a number or a sequence of numbers, got {x0!r}") from None
    if x0.ndim != 1 or not x0.size:
        raise InputError(f"x0 must be a 1-D guess of at least one unknown, got shape {x0.shape}")
    if not np.all(np.isfinite(x0)):
        raise InputError(f"x0 has a non-finite entry at index {int(np.flatnonzero(~np.isfinite(x0))[0])}")
    tol = check_tol(tol)
    if isinstance(maxiter, bool) or not isinstance(maxiter, (int, np.integer)) or maxiter < 1:
        raise InputError(f"maxiter must be a positive integer, got {maxiter!r}")
    n = x0.size
    symbolic = not callable(fun)
    if symbolic:
        if unknowns is None:
            raise InputError("a symbolic system needs `unknowns` (the symbols solved for)")
        if len(unknowns) != n:
            raise InputError(f"x0 has {n} entries but `unknowns` names {len(unknowns)}")
        F, Jsym = _sympy_system(fun, unknowns)
        jacobian = "symbolic" if jacobian is None else jacobian
    else:
        jacobian = "central" if jacobian is None else jacobian

        def F(x, idx=None):
            cols = [np.asarray(fun(x[:, k], *args)).reshape(-1) for k in range(x.shape[1])]
            return np.stack(cols, axis=1)

    if callable(jacobian):
        user_jac = jacobian

        def J(x, idx=None):
            mats = [np.asarray(user_jac(x[:, k], *args), dtype=x.dtype) for k in range(x.shape[1])]
            for m in mats:
                if m.shape != (n, n):
                    raise InputError(f"the callable jacobian returned shape {m.shape}; expected ({n}, {n})")
            return np.stack(mats)

    elif jacobian == "symbolic":
        if not symbolic:
            raise InputError(
                "jacobian='symbolic' needs sympy expressions; pass a callable jacobian or use 'forward'/'central'"
            )
        J = Jsym
    elif jacobian in ("forward", "central"):
        J = jacobian
    else:
        raise InputError(f"jacobian must be one of {JACOBIANS} or a callable, got {jacobian!r}")

    f0 = F(x0[:, None])
    if f0.shape[0] != n:
        raise InputError(
            f"`fun` has {f0.shape[0]} residual components for {n} unknowns (the size of x0): "
            "the system must be square"
        )
    xs = np.broadcast_to(np.asarray(xscale, dtype=float), (n,))
    out = iterate(F, J, x0[:, None], fscale=fscale, xscale=xs, tol=tol, maxiter=maxiter, cond_max=cond_max,
                  record=True)
    jac_end = J(out.x) if not isinstance(J, str) else fd_jacobian(F, out.x, out.f, J, xs)
    cond = float(scaled_cond(jac_end, np.array([fscale]), xs)[0])
    if out.converged[0]:
        msg = f"converged in {out.iterations[0]} iterations"
    elif out.singular[0]:
        msg = (
            f"singular Jacobian after {out.iterations[0]} iterations "
            f"(condition number {cond:.3g} > {cond_max:.3g}): not divided through"
        )
    elif not np.isfinite(out.residual[0]):
        msg = f"diverged after {out.iterations[0]} iterations"
    else:
        msg = f"did not converge in {maxiter} iterations (scaled residual {out.residual[0]:.3g})"
    return NewtonResult.from_batch(out, 0, cond, msg)

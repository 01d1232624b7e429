"""The rules every Newton path of numkin applies: stopping, conditioning, finite differences.

``numkin.newton.solve_batch`` (and through it :func:`numkin.newton`,
:meth:`Mechanism.solve`, :meth:`Mechanism.polish`, the complex-step
derivatives and the batch of a sweep) and the scalar kernel of a
continuation (:class:`numkin.march.Continuation`) all use these.

Stopping rule
-------------
A system has converged when, after a step,

* the scaled residual ``max|F| / fscale`` is at most ``tol`` **and**
* the scaled step ``max|dx / xscale|`` that led there is either at most
  ``tol``, or at most ``tol**(2/3)`` *and* at most a quarter of the step
  before it (convergence is superlinear, so the error left is of order
  ``step**2 <= tol**(4/3)``, well below ``tol``), or no smaller than 0.9
  times the step before it (it is stuck at the round-off floor
  ``~eps * cond(J)``).

Linear convergence, the signature of a singular Jacobian at the root (steps
that halve at a double root), meets none of these until the error itself is
below ``tol`` or at the round-off floor, where the condition number reported
with the result tells how many digits are left (of two or more equations:
one equation's condition number is always 1, and near a multiple root its
steps tell more).

``fscale`` is the mechanism's characteristic length (residuals of vector
loops are lengths); ``xscale`` is 1 rad for angles and the characteristic
length for lengths. Both tests are relative, so a linkage scaled by 1e-6 or
1e3 converges in the same iterations to the same relative accuracy.

Finite-difference Jacobian step rule
------------------------------------
Column ``j`` is differenced with ``h_j = c * max(|x_j|, xscale_j)`` where
``c = sqrt(eps) ~ 1.5e-8`` for ``"forward"`` and ``c = eps**(1/3) ~ 6.1e-6``
for ``"central"``; ``h_j`` is then rounded so that ``x_j + h_j`` is exactly
representable.

A residual that has stopped shrinking at its own round-off floor
(:func:`residual_floor`, above ``tol`` only for angles of thousands of
turns) has converged too. A ``tol`` below :data:`TOL_MIN` is refused
(:func:`check_tol`).

Conditioning rule
-----------------
A Jacobian whose scaled condition number (rows / ``fscale``, columns *
``xscale``) exceeds :data:`COND_MAX` is singular (:func:`is_singular`):
never divided through.
"""

from __future__ import annotations

import math

import numpy as np

from .errors import InputError

__all__ = [
    "EPS", "JACOBIANS", "COND_MAX", "COND_WARN", "TOL_MIN", "has_converged", "residual_floor", "check_tol",
    "is_singular", "fd_step", "fd_jacobian", "scaled_cond", "colmax",
]

EPS = np.finfo(float).eps
#: Jacobian choices accepted by :func:`newton` and :meth:`Mechanism.sweep`.
JACOBIANS = ("symbolic", "forward", "central")
_FD_STEP = {"forward": np.sqrt(EPS), "central": EPS ** (1.0 / 3.0)}
#: The conditioning rule: a Jacobian whose scaled condition number exceeds this is singular.
COND_MAX = 1e12
#: Condition number above which a solved point is reported as near-singular (digits lost).
COND_WARN = 1e8
#: Smallest tolerance accepted: a scaled residual of a few units of round-off is the floor.
TOL_MIN = 4.0 * EPS


def has_converged(res, step, prev_step, tol, floor=0.0, where=None):
    """The stopping rule of the module docstring, for floats or arrays.

    ``res`` is the scaled residual after a step, ``step`` the scaled step
    that led to it and ``prev_step`` the one before (``inf`` at the first).
    ``floor`` is the round-off floor of the residual where it exceeds ``tol``
    (angles of many turns evaluate their sines to ``eps * |angle|``): a
    residual at the floor whose steps have stopped shrinking has converged
    as far as float64 allows. ``where`` (arrays): the columns to test (the
    others are False), e.g. those a step has just moved.

    Examples
    --------
    >>> import numpy as np
    >>> has_converged(np.array([1e-13, 1e-13, 1e-9]), np.array([1e-9, 1e-13, 1e-13]), np.array([1e-3, 1e-7, 1e-7]),
    ...               1e-12, where=np.array([True, False, True])).tolist()
    [True, False, False]
    """
    if isinstance(res, float):  # one point (the continuation's scalar kernel): plain logic, no arrays
        stuck = step >= 0.9 * prev_step
        if res <= tol:
            return step <= tol or (step <= tol ** (2.0 / 3.0) and step <= 0.25 * prev_step) or stuck
        return stuck and res <= floor
    low = res <= tol
    if where is not None:
        low &= where
    no_floor = isinstance(floor, float) and floor <= tol  # the floor clause adds nothing then
    if no_floor and not np.count_nonzero(low):
        return low
    superlinear = step <= tol ** (2.0 / 3.0)
    superlinear &= step <= 0.25 * prev_step
    stuck = step >= 0.9 * prev_step
    done = step <= tol
    done |= superlinear
    done |= stuck
    done &= low
    if no_floor:
        return done
    done |= (res <= floor) & stuck if where is None else (res <= floor) & stuck & where
    return done


def residual_floor(x, t=0.0):
    """Round-off floor of a scaled residual at the point ``x`` (scaled unknowns) and input ``t``.

    Sines and cosines of an argument ``a`` are known to ``eps * |a|``; a few
    terms add up. Below ``tol`` for any sweep of fewer than about 1e3 turns.
    """
    big = max(1.0, abs(t), *(abs(v) for v in x)) if not isinstance(x, np.ndarray) else max(
        1.0, abs(t), float(np.max(np.abs(x), initial=0.0)))
    return 16.0 * EPS * big


def check_tol(tol, name="tol"):
    """``tol`` as a float, or ValueError if it is not a number in [TOL_MIN, 1)."""
    if isinstance(tol, bool) or not isinstance(tol, (int, float, np.number)) or not math.isfinite(tol) or tol <= 0:
        raise InputError(f"{name} must be a positive number, got {tol!r}")
    if tol < TOL_MIN:
        raise InputError(
            f"{name}={tol:.3g} is below the round-off floor of float64 residuals (about {TOL_MIN:.1e}, "
            f"a few units of eps = {EPS:.3g}): no Newton step can meet it; use {name} >= {TOL_MIN:.1e}"
        )
    if tol >= 1:
        raise InputError(f"{name} must be below 1 (a relative tolerance), got {tol!r}")
    return float(tol)


def is_singular(cond, cond_max=COND_MAX):
    """The conditioning rule every Newton path applies: True (or a mask) where ``cond`` exceeds ``cond_max`` or is NaN."""
    if isinstance(cond, float):
        return not cond <= cond_max
    return ~(np.asarray(cond) <= cond_max) if np.ndim(cond) else not cond <= cond_max


def fd_step(xj, scale, method):
    """The finite-difference step of the module docstring for one unknown (float or array),
    rounded so that ``xj + h`` is exact; returns ``(xj + h, h)``."""
    h = _FD_STEP[method] * np.maximum(np.abs(xj), scale)
    xp = xj + h
    return xp, xp - xj


def fd_jacobian(F, x, f0, method, xscale):
    """Finite-difference Jacobian of ``F`` at a batch ``x`` of shape (n, N) -> (N, n, n)."""
    n, N = x.shape
    jac = np.empty((N, f0.shape[0], n), dtype=np.result_type(x, f0))
    for j in range(n):
        xp = x.copy()
        xp[j], h = fd_step(x[j], xscale[j], method)
        if method == "forward":
            col = (F(xp) - f0) / h
        else:
            xm = x.copy()
            xm[j] = x[j] - h
            col = (F(xp) - F(xm)) / (2.0 * h)
        jac[:, :, j] = col.T
    return jac


def scaled_cond(jac, fscale, xscale):
    """2-norm condition numbers of a batch of Jacobians, rows / fscale and columns * xscale.

    A complex Jacobian whose imaginary part is below round-off of its real
    part (a complex step's) has the real part's condition number, to rounding.
    """
    js = jac * (xscale[None, None, :] / np.asarray(fscale).reshape(-1, 1, 1))
    if np.iscomplexobj(js) and np.abs(js.imag).max(initial=0.0) <= EPS * np.abs(js.real).max(initial=0.0):
        js = js.real
    if not np.all(np.isfinite(js)):
        out = np.full(js.shape[0], np.inf)
        ok = np.all(np.isfinite(js), axis=(1, 2))
        if ok.any():
            out[ok] = np.linalg.cond(js[ok])
        return out
    return np.linalg.cond(js)


def colmax(a):
    """Largest entry of every column of a small (n, N) array (faster than ``a.max(axis=0)``)."""
    out = a[0]
    for row in a[1:]:
        out = np.maximum(out, row)
    return out

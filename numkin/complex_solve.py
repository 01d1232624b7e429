"""Derivatives by the complex step through the Newton solve: an independent check of the exact ones.

The loop equations are solved at complex inputs ``theta + i h`` by
Newton-Raphson in complex arithmetic from a sweep's real positions
(:func:`complex_positions`); the solution is ``q(theta) + i h q'(theta) +
O(h**2)``, so ``q' = Im(q) / h`` without subtractive cancellation, to machine
precision for any tiny ``h`` (:func:`complex_step`). It uses only the
residuals and the position Jacobian (and, for the second derivative, the
velocity equations: :func:`complex_tangent`), not the acceleration
equations of :mod:`numkin.analytic`, which re-exports these names.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from .errors import InputError, warn
from .units import deg_text
from .newton import iterate
from .sweep import COND_MAX, SingularityWarning, check_sweep, record_evaluations

__all__ = ["complex_step", "complex_positions", "complex_tangent", "COMPLEX_STEP"]


def _columnwise(solve, q, t) -> np.ndarray:
    """``solve(q, t)`` on the whole batch, or column by column (NaN where singular)."""
    try:
        return np.asarray(solve(q, t))
    except np.linalg.LinAlgError:
        out = np.full(q.shape, np.nan, dtype=np.result_type(q, t))
        for k in range(t.size):
            try:
                out[:, k] = np.asarray(solve(q[:, k : k + 1], t[k : k + 1]))[:, 0]
            except np.linalg.LinAlgError:
                pass
        return out


def _tangent(mech, q, t, p):
    """dq/dtheta from ``J q' = -F_theta`` (NaN where J is singular)."""

    def solve(q_, t_):
        record_evaluations(mech, "J", t_.size)
        record_evaluations(mech, "F_t", t_.size)
        return mech.compiled.tangent(q_, t_, p)

    return _columnwise(solve, q, t)


#: Default imaginary step of :func:`complex_step` (rad).
COMPLEX_STEP = 1e-30


def complex_tangent(mech, x, t, h) -> np.ndarray:
    """d2q/dtheta2 from the complex positions ``x`` at ``t + i h`` (:func:`complex_positions`).

    The complex step of the first-derivative formula, ``Im(q'(x, t + i h)) / h``
    with ``q'(q, theta) = -J^-1 dF/dtheta`` (the velocity equations, not the
    acceleration equations), as :func:`complex_step` with ``order=2``.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> m = linkages.slider_crank(80, 200)
    >>> s = m.sweep(np.radians([0.0]))
    >>> x, _, _ = complex_positions(m, s.values, s.inputs, 1e-30)
    >>> print(np.round(complex_tangent(m, x, s.inputs, 1e-30)[1], 9))   # x'' = -r (1 + r/l) at 0
    [-112.]
    """
    tc = np.asarray(t, dtype=float) + 1j * np.asarray(h, dtype=float)
    return _tangent(mech, x, tc, mech.parameter_values).imag / h


def complex_positions(mech, q, t, h):
    """The positions at the complex inputs ``t + i h`` by Newton-Raphson in complex arithmetic.

    The solve of :func:`complex_step`: from the real positions ``q`` (n, N)
    at the inputs ``t`` (N,), two passes of ``numkin.newton.iterate``
    (``tol = 1e-13``, at most 8 steps, the conditioning rule), the first also
    removing the real residual the positions leave, the second recomputing
    the imaginary part at the polished real solution. ``h`` (rad) is one
    step or one per input (N,).

    Returns
    -------
    x : ndarray of complex, shape (n, N)
        ``q(t) + i h q'(t) + O(h**2)`` where the solve converged.
    failed : ndarray of bool, shape (N,)
        Where it did not converge.
    singular : ndarray of bool, shape (N,)
        Where it stopped at a singular Jacobian.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> m = linkages.slider_crank(80, 200)
    >>> s = m.sweep(np.radians([90.0]))
    >>> q, t = np.repeat(s.values, 2, axis=1), np.repeat(s.inputs, 2)  # one input twice: two steps at once
    >>> x, failed, _ = complex_positions(m, q, t, np.array([1e-3, 1e-30]))
    >>> print(np.round(x.imag[1] / [1e-3, 1e-30], 6), failed)   # dx/dtheta = -r at 90 deg; O(h^2) at h = 1e-3
    [-80.000013 -80.      ] [False False]
    """
    comp, p = mech.compiled, mech.parameter_values
    tc = np.asarray(t, dtype=float) + 1j * np.asarray(h, dtype=float)

    def F(x, idx):
        record_evaluations(mech, "F", x.shape[1])
        return comp.F(x, tc[idx], p)

    def J(x, idx):
        record_evaluations(mech, "J", x.shape[1])
        return comp.J(x, tc[idx], p)

    x = np.asarray(q, dtype=float).astype(complex)
    for _ in range(2):
        out = iterate(F, J, x, fscale=mech.length_scale, xscale=mech.xscale, tol=1e-13, maxiter=8,
                      cond_max=COND_MAX)
        x = np.where(out.converged, out.x, x)
    return x, ~out.converged, out.singular & ~out.converged


def complex_step(sweep, h: float = COMPLEX_STEP, *, order: int = 1) -> np.ndarray:
    """Derivatives of the unknowns by the complex-step method through the Newton solve.

    The loop equations are solved at the complex inputs ``theta + i h`` by
    Newton-Raphson in complex arithmetic (``numkin.newton.iterate``),
    starting from the sweep's real solution. The solution is
    ``q(theta) + i h q'(theta) + O(h**2)``, so ``q' = Im(q) / h`` with no
    subtractive cancellation: accurate to machine precision for any tiny
    `h`. It uses only the residuals and the position Jacobian, not the
    derived velocity or acceleration equations, so it is an independent
    check of :func:`derivatives`.

    Parameters
    ----------
    sweep : Sweep
    h : float, default 1e-30
        Imaginary step (rad), finite and positive.
    order : {1, 2}, default 1
        1: dq/dtheta. 2: d2q/dtheta2, as the complex step of the
        first-derivative formula: ``Im(q'(q_c, theta + i h)) / h`` where
        ``q_c`` is the complex solution and ``q'(q, theta) = -J^-1 dF/dtheta``
        (this uses the velocity equations, not the acceleration equations).

    Returns
    -------
    ndarray, shape (n, N)
        Rows in ``sweep.unknowns`` order, per rad (order 1) or per rad^2
        (order 2). NaN where the complex Newton solve fails (a singular
        Jacobian), with a :class:`~numkin.SingularityWarning`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive or `order` is not 1 or 2, or
        (:class:`~numkin.errors.InputError`) if a function of the loop
        equations has no complex form (``atan2``).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([0.0, 90.0]))
    >>> print(np.round(analytic.complex_step(sweep)[1], 9))           # dx/dtheta
    [  0. -80.]
    >>> print(np.round(analytic.complex_step(sweep, order=2)[1], 6))  # d2x/dtheta2
    [-112.         34.914862]
    """
    if isinstance(h, bool) or not isinstance(h, numbers.Real) or not (math.isfinite(h) and h > 0):
        raise InputError(f"h must be a finite positive number, got {h!r}")
    if order not in (1, 2):
        raise InputError(f"order must be 1 (dq/dtheta) or 2 (d2q/dtheta2), got {order!r}")
    mech, t, q = check_sweep(sweep)
    try:
        x, failed, singular = complex_positions(mech, q, t, float(h))
    except TypeError as error:  # numpy's functions with no complex form, as arctan2
        if "ufunc" not in str(error):
            raise
        raise InputError(
            f"{mech.name}: the complex step evaluates the loop equations at complex inputs, and one of their "
            f"functions has no complex form in numpy ({error}); analytic.derivatives differentiates them exactly"
        ) from None
    if failed.any():
        k = int(np.flatnonzero(failed)[0])
        warn(
            f"{mech.name}: complex-step Newton failed at {int(failed.sum())} point(s) (first at input "
            f"{deg_text(t[k])}: {'singular Jacobian' if singular[k] else 'no convergence'}): set to NaN",
            SingularityWarning,
        )
    d = x.imag / h if order == 1 else complex_tangent(mech, x, t, float(h))
    d[:, failed] = np.nan
    return d

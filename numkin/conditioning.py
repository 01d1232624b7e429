"""Conditioning of derived values: change points and lost digits.

Near a singular position of the loop equations, values computed from the
solved positions lose accuracy. This module estimates how much, warns when
the loss exceeds a stated tolerance (:class:`LostDigitsWarning`), and gives
the derivatives at a change point (where two assembly branches meet and the
Jacobian is singular) from the branch a sweep kept.

Examples
--------
>>> from numkin.conditioning import lost_digits
>>> print(f"{lost_digits(10.0, 1):.1e}")   # a well-conditioned point
2.2e-14
"""

from __future__ import annotations


import numpy as np

from .errors import InputError, warn
from .quantities import catalogue
from .sweep import COND_MAX, SingularityWarning
from .units import deg_text

__all__ = [
    "DIGITS_RTOL",
    "CHANGE_COND",
    "CHANGE_NEIGHBOURS",
    "AT_CHANGE_POINT",
    "LostDigitsWarning",
    "condition_numbers",
    "lost_digits",
    "rounding_error",
    "change_points",
    "continue_branch",
    "check_at_change_point",
    "warn_lost_digits",
    "warn_rounding",
]

#: Relative accuracy an analytic or differenced value is expected to keep: an
#: estimated error (see :func:`lost_digits`) above it warns with :class:`LostDigitsWarning`.
DIGITS_RTOL = 1e-6
#: The sample nearest a change point (an event of the sweep) is continued from its
#: neighbours when its condition number exceeds this.
CHANGE_COND = 1e6
#: Neighbouring samples on each side used to continue a branch through a change point.
CHANGE_NEIGHBOURS = 3
_EPS = float(np.finfo(float).eps)



class LostDigitsWarning(SingularityWarning):
    """The estimated rounding error of a value, from the condition number, exceeds the stated tolerance."""




def condition_numbers(sweep, inputs) -> np.ndarray:
    """The sweep's condition number at each input (ones if it has none)."""
    return np.asarray(getattr(sweep, "cond", np.ones(inputs.size)), dtype=float)


def change_points(sweep, mech, q, t, cond) -> list:
    """Samples where the sweep passes a change point: nearest a change-point event of the
    sweep, or between two neighbours whose Jacobian determinants differ in sign; and with a
    condition number above CHANGE_COND."""
    out = set()
    for event in getattr(sweep, "events", ()):
        if getattr(event, "kind", "") == "change point" and t.size:
            out.add(int(np.argmin(np.abs(t - event.input_value))))
    if not out and (not cond.size or cond.max() <= CHANGE_COND):  # (a NaN fails the test)
        return []
    high = [k for k in np.flatnonzero(~(cond <= CHANGE_COND)) if 0 < k < t.size - 1]
    if high:
        idx = np.array([[k - 1, k + 1] for k in high]).ravel()
        sign = np.sign(np.linalg.det(mech.compiled.J(q[:, idx], t[idx], mech.parameter_values))).reshape(-1, 2)
        out.update(k for k, (a, b) in zip(high, sign) if a * b < 0)
    return sorted(k for k in out if not cond[k] <= CHANGE_COND)


def _lagrange_at(x: np.ndarray, x0: float) -> np.ndarray:
    """Weights of the interpolating polynomial through nodes `x`, evaluated at `x0`."""
    w = np.ones(x.size)
    for j in range(x.size):
        others = np.delete(x, j)
        w[j] = np.prod((x0 - others) / (x[j] - others))
    return w


#: What the derivatives at a change point are: ``"nan"`` (with the kept branch's
#: values in the warning) or ``"continue"`` (those values).
AT_CHANGE_POINT = ("nan", "continue")


def check_at_change_point(at_change_point: str) -> None:
    """A ValueError unless `at_change_point` is one of :data:`AT_CHANGE_POINT`.

    Examples
    --------
    >>> check_at_change_point("continue")
    >>> check_at_change_point("skip")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: at_change_point must be one of ('nan', 'continue'), got 'skip'
    """
    if at_change_point not in AT_CHANGE_POINT:
        raise InputError(f"at_change_point must be one of {AT_CHANGE_POINT}, got {at_change_point!r}")


def continue_branch(mech, t, cond, change, arrays, what: str, at_change_point: str = "nan") -> None:
    """At each change-point sample, set the columns of `arrays` to NaN (``at_change_point="nan"``)
    or to the kept branch's smooth continuation (``"continue"``): the polynomial through the
    neighbouring regular samples, evaluated there. Warns, giving the continued values."""
    check_at_change_point(at_change_point)
    if not change:
        return
    good = np.isfinite(cond) & (cond <= CHANGE_COND) & np.all(np.isfinite(arrays[0]), axis=0)
    good[change] = False
    names = list(catalogue(mech, orders=(1,), wrt="input", points=False))
    for k in change:
        left = [j for j in range(k - 1, -1, -1) if good[j]][:CHANGE_NEIGHBOURS]
        right = [j for j in range(k + 1, t.size) if good[j]][:CHANGE_NEIGHBOURS]
        where = (f"{mech.name}: the Jacobian is singular at the change point at input {deg_text(t[k])} "
                 f"(condition number {cond[k]:.3g}), where the branches meet")
        if len(left) < 2 or len(right) < 2:
            for a in arrays:
                a[:, k] = np.nan
            warn(f"{where}; {what} set to NaN there: fewer than 2 regular samples of the kept "
                          "branch on each side to continue it from", SingularityWarning)
            continue
        idx = np.array(left[::-1] + right)
        w = _lagrange_at(t[idx] - t[k], 0.0)
        continued = [a[:, idx] @ w for a in arrays]
        values = ", ".join(f"{n} = {v:.4g}" for n, v in zip(names, continued[0]))
        how = f"the kept branch continues smoothly through it (polynomial through {idx.size} neighbouring samples)"
        if at_change_point == "continue":
            for a, c in zip(arrays, continued):
                a[:, k] = c
            message = f"{where}; {what} there are those of {how}: {values}"
        else:
            for a in arrays:
                a[:, k] = np.nan
            message = (f"{where}; {what} set to NaN there (no value belongs to both branches); {how} with "
                       f"{values}: pass at_change_point='continue' for these values")
        warn(message, SingularityWarning)


def lost_digits(cond, order: int = 1) -> np.ndarray:
    """Estimated relative error of an n-th derivative solved at a point of condition number `cond`.

    ``(2n - 1) * eps * cond**2``: the position is known to about ``eps * cond``
    (relative), and the derivative equations amplify that error by the
    condition number again; near a toggle, where ``q ~ sqrt(distance)``, the
    second derivative loses three times what the first does. On the toggle
    of the 4/2/4.0001/2 four-bar this bounds the errors measured against
    mpmath (40 digits) by a factor 6-20 from 1e-9 deg to 1e-1 deg off the limit.

    Examples
    --------
    >>> print(f"{lost_digits(5.03e6, 1):.1e} {lost_digits(5.03e6, 2):.1e}")
    5.6e-03 1.7e-02
    """
    if isinstance(cond, float):  # (numpy's floats too) one number: plain arithmetic
        return (2 * order - 1) * _EPS * cond * cond
    return (2 * order - 1) * _EPS * np.asarray(cond, dtype=float) ** 2


def warn_lost_digits(mech, t, cond, skip, rtol, what="analytic") -> None:
    """Warn if the estimated error of the second derivative (the larger) exceeds `rtol` anywhere."""
    if not cond.size or lost_digits(cond.max(), 2) <= rtol:  # (a NaN fails the test)
        return
    est = lost_digits(cond, 2)
    over = (est > rtol) & (cond <= COND_MAX)
    over[list(skip)] = False
    if over.any():
        k = int(np.flatnonzero(over)[np.argmax(est[over])])
        warn(
            f"{mech.name}: {what} derivatives lose digits near a singular position at {int(over.sum())} "
            f"point(s): at input {deg_text(t[k])} (condition number {cond[k]:.3g}) the estimated relative error "
            f"is {lost_digits(cond[k], 1):.1e} for velocities and {est[k]:.1e} for accelerations, above the "
            f"tolerance {rtol:.0e}",
            LostDigitsWarning,
        )


def rounding_error(scheme, h: float, values, cond, xscale) -> np.ndarray:
    """Estimated rounding error of a difference quotient, per sample (unit of the derivative per rad^n).

    ``sum|w_k| / h**n * delta``, with ``delta = eps * max(cond, 1) * max(max|q|, xscale)``
    the error of the solved positions (relative error ``eps`` amplified by the
    condition number of the loop equations; ``max|q|`` over the row). The
    largest condition number within the stencil's reach is used. The
    spectral schemes are estimated with the five-point stencil of the same
    derivative.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import get_scheme
    >>> e = rounding_error(get_scheme("centred"), 1e-8, np.ones((1, 5)), np.ones(5), np.ones(1))
    >>> print(f"{e[0, 2]:.1e}")   # eps / h
    2.2e-08
    """
    stencil = _bounding_stencil(scheme)
    eps = float(np.finfo(float).eps)
    values = np.atleast_2d(np.asarray(values, dtype=float))
    cond = np.maximum(np.nan_to_num(np.asarray(cond, dtype=float), nan=1.0), 1.0)
    spread = cond.copy()
    for k in range(1, _reach(stencil) + 1):
        np.maximum(spread[:-k], cond[k:], out=spread[:-k])
        np.maximum(spread[k:], cond[:-k], out=spread[k:])
    magnitude = np.maximum(np.max(np.abs(values), axis=1), np.asarray(xscale, dtype=float))
    factor = eps * sum(abs(c) for c in stencil.coefficients) / h**scheme.derivative
    return factor * magnitude[:, None] * spread[None, :]


def _bounding_stencil(scheme):
    """The stencil whose weights bound a scheme's rounding error: its own; the five-point stencil of the same
    derivative for the spectral schemes."""
    from . import schemes as _s

    try:
        return _s.point_stencil(scheme.name)
    except ValueError:
        return _s.point_stencil("five_point" if scheme.derivative == 1 else "five_point_second")


def _reach(stencil) -> int:
    """Samples on either side of its own that a stencil (or its mirror at the far end) may read."""
    return max(-min(stencil.offsets), max(stencil.offsets))


def warn_rounding(sweep, mech, t, rows, scheme, d, rtol) -> None:
    """Warn if the estimated rounding error of a scheme's values `d` exceeds `rtol` (relative to each row's scale)."""
    cond = np.asarray(getattr(sweep, "cond", np.ones(t.size)), dtype=float)  # in the sweep's order, as t
    err = rounding_error(scheme, rows.h, rows.y, cond[::-1] if rows.reverse else cond, mech.xscale)
    if rows.reverse:
        err = err[:, ::-1]
    scale = np.maximum(np.nanmax(np.abs(d), axis=1), mech.xscale)  # a column of zeros: per unit of the unknown
    rel = err / scale[:, None]
    if np.any(rel > rtol):
        j, k = np.unravel_index(int(np.nanargmax(rel)), rel.shape)
        reach = _reach(_bounding_stencil(scheme))
        lo = max(0, k - reach)
        m = lo + int(np.nanargmax(np.nan_to_num(cond[lo : k + reach + 1], nan=1.0)))  # the condition number used
        at = "" if m == k else f" at {deg_text(t[m])}, within the stencil's reach"
        warn(
            f"{mech.name}: {scheme.name} loses digits to rounding: at input {deg_text(t[k])} "
            f"(step h = {rows.h:.3g} rad, condition number {cond[m]:.3g}{at}) the estimated rounding error of "
            f"d{'' if scheme.derivative == 1 else '2'}{mech.unknowns[j]} is {rel[j, k]:.1e} of its largest value (or of 1 unit per rad), "
            f"above the tolerance {rtol:.0e}",
            LostDigitsWarning,
        )

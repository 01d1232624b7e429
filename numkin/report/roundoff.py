"""The round-off table: error against the step h at one angle, the optimal step beside the textbook's."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from .. import analytic
from ..derivatives import get_scheme
from .study import (
    EPS, UNIT, branch_point, deg_text, exact_derivatives, order_text, polish, position_record, quantity_labels,
    set_caption, silenced, unknown_index,
)

__all__ = [
    "ROUNDOFF_SCHEMES",
    "ROUNDOFF_STEPS",
    "roundoff_table",
]

#: Default schemes of :func:`roundoff_table` (``"complex_step"`` is not a finite difference).
ROUNDOFF_SCHEMES = ("forward", "centred", "five_point", "second_difference", "complex_step")
#: Steps shown as columns of :func:`roundoff_table`, rad.
ROUNDOFF_STEPS = tuple(10.0 ** -k for k in range(1, 13))
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

    j = unknown_index(mechanism, quantity)
    lab = quantity_labels(mechanism, quantity)
    steps = [float(h) for h in steps]
    if not steps or not all(math.isfinite(h) and 0 < h < 1 for h in steps):
        raise ValueError(f"steps must be positive and below 1 rad, got {steps!r}")
    names = [schemes] if isinstance(schemes, str) else list(schemes)
    sch = [None if n == "complex_step" else get_scheme(n) for n in names]
    if any(s is not None and s.periodic_only for s in sch):
        raise ValueError("spectral schemes need a full periodic sweep; they have no step h at one angle")
    theta = float(check_angle)
    base = branch_point(mechanism, theta, guess, start)
    dq, d2q = exact_derivatives(base)
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
    vals = polish(mechanism, pred.reshape(len(x0), -1), tt.reshape(-1)).reshape(len(x0), S, 5)[j]
    vals[:, 2] = x0[j]
    rows = []
    shown = {h: k for k, h in enumerate(scan)}
    for name, scheme in zip(names, sch):
        err = np.empty(S)
        if scheme is None:
            deriv, order, exact = 1, None, q1[j]
            for k, h in enumerate(eff):
                one = silenced(analytic.complex_step, base, h=float(h), order=1)
                err[k] = abs(one[j, 0] - exact)
        else:
            deriv, order = scheme.derivative, scheme.order
            exact = q1[j] if deriv == 1 else q2[j]
            for k, h in enumerate(eff):
                err[k] = abs(scheme.function(vals[k], float(h), periodic=False)[2] - exact)
        rel = err / abs(exact) if exact != 0 else err  # an exact zero: absolute errors
        row = {
            "scheme": "complex step" if scheme is None else scheme.name,
            "formal order": "2" if scheme is None else order_text(scheme),
            "quantity": lab["d1"] if deriv == 1 else lab["d2"],
            f"exact value {UNIT}": float(exact),
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
        f"Round-off floor: {mechanism.name}, {quantity} at {lab['input']} = {deg_text(theta)} deg; relative "
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
    return set_caption(df, caption, [position_record("check angle", mechanism, theta, x0)])

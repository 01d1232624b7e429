"""The round-off table: error against the step h at one angle, the optimal step beside the textbook's."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from ..errors import InputError
from ..schemes import NameList, REGISTRY, lookup, point_stencil
from .captions import UNIT, at_angle, deg_text, order_text, relative_text, set_caption, set_views
from .study import EPS, branch_point, exact_derivatives, position_record, solve_points
from .studied import studied_quantity

__all__ = [
    "ROUNDOFF_SCHEMES",
    "ROUNDOFF_STEPS",
    "roundoff_table",
    "stencil",
    "fitted_optimum",
    "complex_step_scan",
    "quantity_complex_step",
]

#: Default schemes of :func:`roundoff_table`: every ``default`` scheme of the registry that has a step h (not
#: the periodic-only ones), in registry order; always current. ``"complex_step"`` is not a finite difference.
ROUNDOFF_SCHEMES = NameList(lambda: tuple(n for n, s in REGISTRY.items() if s.default and not s.periodic_only))
#: Steps shown as columns of :func:`roundoff_table`, rad.
ROUNDOFF_STEPS = tuple(10.0 ** -k for k in range(1, 13))
#: Columns of :func:`roundoff_table`: the error at the textbook step on the fitted curve, and measured there.
_ON_CURVE_TEXTBOOK = "rel error on fitted curve at textbook h [-]"
_AT_TEXTBOOK = "rel error measured at textbook h [-]"
_TEXTBOOK = {
    # (derivative, order) -> rule text
    (1, 1): "sqrt(eps)",
    (1, 2): "cbrt(eps)",
    (1, 4): "eps^(1/5)",
    (2, 1): "cbrt(eps)",
    (2, 2): "eps^(1/4)",
    (2, 4): "eps^(1/6)",
}


def stencil(scheme) -> tuple:
    """Offsets and weights of a scheme's interior formula: ``d^n q/dtheta^n ~ sum(w_k q(theta + k h)) / h**n``.

    Read from the registry (:func:`numkin.schemes.point_stencil`), so a
    scheme added at run time with :func:`numkin.schemes.register` works too.

    Parameters
    ----------
    scheme : Scheme
        A finite-difference scheme (not a spectral one).

    Returns
    -------
    (ndarray of int, ndarray of float)
        Offsets k and weights w_k (for h = 1).

    Examples
    --------
    >>> from numkin.derivatives import get_scheme
    >>> k, w = stencil(get_scheme("second_difference"))
    >>> k.tolist(), w.tolist()
    ([-1, 0, 1], [1.0, -2.0, 1.0])
    """
    found = point_stencil(scheme.name)
    return np.asarray(found.offsets, dtype=int), np.asarray(found.coefficients, dtype=float)


def fitted_optimum(h, err, order: int, derivative: int) -> tuple:
    """The optimal step where the fitted truncation and rounding lines meet, and the error there.

    The errors ``err`` against the steps ``h`` are split, at every place
    along the scan, into a truncation side (larger steps) and a rounding
    side; on each side the median of ``err / h**p`` and of
    ``err * h**n / eps`` gives the lines ``C_t h**p`` and ``C_r eps / h**n``
    (p the order, n the derivative; n = 0 for a floor at eps). The split
    whose model ``C_t h**p + C_r eps / h**n`` lies closest to the
    measurements (sum of absolute log differences) is kept. Medians ignore
    the lucky cancellations that make single rounding errors far smaller
    than their neighbours, so the estimate is the same for every scan that
    samples the same curve.

    Returns
    -------
    (float, float)
        ``h* = (C_r eps / C_t)**(1/(p + n))`` and the model's error there,
        ``2 C_t h***p``; NaN if the scan does not show both sides or they do
        not meet inside it.

    Examples
    --------
    >>> import numpy as np
    >>> h = 10.0 ** -np.linspace(1, 12, 45)
    >>> err = 0.5 * h**2 + 2.2e-16 / h              # centred: C_t = 0.5, C_r = 1
    >>> hs, es = fitted_optimum(h, err, 2, 1)
    >>> bool(abs(hs / (2.2e-16 / 0.5) ** (1 / 3) - 1) < 0.05)
    True
    """
    lines = _fitted_lines(h, err, order, derivative)
    if lines is None:
        return math.nan, math.nan
    ct, cr, lo, hi = lines
    p, n = int(order), int(derivative)
    hstar = (cr * EPS / ct) ** (1.0 / (p + n))
    if not (lo <= hstar <= hi):
        return math.nan, math.nan
    return float(hstar), float(ct * hstar**p + cr * EPS / hstar**n)


def _fitted_lines(h, err, order: int, derivative: int):
    """``(C_t, C_r, smallest h, largest h)`` of :func:`fitted_optimum`'s fit; None if the scan is too short."""
    h = np.asarray(h, dtype=float)
    err = np.asarray(err, dtype=float)
    ok = np.isfinite(err) & (err > 0) & np.isfinite(h) & (h > 0)
    h, err = h[ok], err[ok]
    order_idx = np.argsort(-h, kind="stable")
    h, err = h[order_idx], err[order_idx]
    p, n = int(order), int(derivative)
    if h.size < 4 or p <= 0:
        return None
    trunc = err / h**p
    rnd = err * h**n / EPS
    best = None
    for m in range(2, h.size - 1):
        ct, cr = float(np.median(trunc[:m])), float(np.median(rnd[m:]))
        model = ct * h**p + cr * EPS / h**n
        cost = float(np.sum(np.abs(np.log(err / model))))
        if best is None or cost < best[0]:
            best = (cost, ct, cr)
    return best[1], best[2], float(h.min()), float(h.max())


def _on_fitted_curve(h, err, order: int, derivative: int, at: float) -> float:
    """The fitted model ``C_t at**p + C_r eps / at**n`` of :func:`fitted_optimum`.

    NaN where the fit finds no optimum, or `at` lies outside the scanned steps.
    """
    if not math.isfinite(fitted_optimum(h, err, order, derivative)[0]):
        return math.nan
    ct, cr, lo, hi = _fitted_lines(h, err, order, derivative)
    if not lo <= at <= hi:  # outside the scan: no line was measured there
        return math.nan
    return float(ct * at**int(order) + cr * EPS / at**int(derivative))


def complex_step_scan(mechanism, point, steps) -> np.ndarray:
    """dq/dtheta at one solved point by the complex step, for many steps h in one batch of Newton solves.

    Column ``k`` is what :func:`numkin.analytic.complex_step` gives for the
    one-point sweep `point` with ``h = steps[k]``: its complex Newton
    (:func:`numkin.analytic.complex_positions`) on every step at once. The
    batch's systems are independent (each stops when it converges), so each
    column is the one-by-one solve's.

    Parameters
    ----------
    mechanism : Mechanism
    point : Sweep
        A one-point sweep (from :func:`~numkin.report.study.branch_point`).
    steps : array_like, shape (S,)
        Imaginary steps h, rad, finite and positive.

    Returns
    -------
    ndarray, shape (n, S)
        dq/dtheta of every unknown (rows in ``mechanism.unknowns`` order) per
        step; NaN where the complex Newton solve fails.

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> from numkin.report.study import branch_point
    >>> mech = linkages.slider_crank(80, 200)
    >>> d = complex_step_scan(mech, branch_point(mech, math.radians(90)), [1e-3, 1e-30])
    >>> print(round(float(d[1, 1]), 12))     # dx/dtheta = -r at 90 deg
    -80.0
    """
    x, failed, h = _complex_scan(mechanism, point, steps)
    d = x.imag / h
    d[:, failed] = np.nan
    return d


def _complex_scan(mechanism, point, steps) -> tuple:
    """``(x, failed, h)``: the complex positions (n, S) at ``theta + i h`` for every step of `steps` (S,)."""
    from ..analytic import complex_positions

    h = np.asarray(steps, dtype=float).reshape(-1)
    if not np.all(np.isfinite(h) & (h > 0)):
        raise InputError(f"steps must be finite and positive, got {steps!r}")
    q = np.repeat(np.asarray(point.values, dtype=float)[:, :1], h.size, axis=1)
    t = np.full(h.size, float(np.asarray(point.inputs, dtype=float)[0]))
    x, failed, _ = complex_positions(mechanism, q, t, h)
    return x, failed, h


def quantity_complex_step(studied, point, steps):
    """d/dtheta of the studied quantity at one solved point by its own complex step, for many steps h.

    ``Im(q(x(theta + i h), theta + i h)) / h``: the unknowns solved at the
    complex input (:func:`complex_step_scan`'s Newton) and the quantity's
    expression evaluated there in complex arithmetic
    (:meth:`~numkin.report.studied.StudiedQuantity.complex_at`). For an
    unknown, :func:`complex_step_scan`'s row. A str saying why, where the
    expression is not analytic. NaN where the complex solve fails.

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> from numkin.report.study import branch_point
    >>> from numkin.report.studied import studied_quantity
    >>> m = linkages.slider_crank(80, 200).add_quantities({"gap": ("x - r*cos(theta)", "length")})
    >>> gap = studied_quantity(m, "gap")
    >>> d = quantity_complex_step(gap, branch_point(m, math.radians(90)), [1e-30])
    >>> print(round(float(d[0]), 12))   # d/dtheta sqrt(l^2 - r^2 sin^2) = 0 at 90 deg
    0.0
    """
    x, failed, h = _complex_scan(studied.mechanism, point, steps)
    t = np.full(h.size, float(np.asarray(point.inputs, dtype=float)[0])) + 1j * h
    q = studied.complex_at(x, t)
    if isinstance(q, str):
        return q
    d = np.asarray(q).imag / h
    d[failed] = np.nan
    return d


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

    Any non-spectral scheme of the registry works: its stencil (offsets and
    weights) is read by :func:`stencil`.

    The optimum is measured on a finer scan (`scan_per_decade` steps per
    decade over the range of `steps`): the truncation line ``C_t h**p`` and
    the rounding line ``C_r eps / h**n`` are fitted to the scan's errors
    (:func:`fitted_optimum`, robust to the lucky cancellations of single
    steps) and meet at the measured optimal h; the error given there is the
    fitted curve's, and the error measured at that very step stands
    beside it. The textbook step ``h* ~ eps**(1/(p + n))`` (p the order,
    n the derivative: sqrt(eps) forward, cbrt(eps) centred, eps^(1/4)
    second difference, eps^(1/5) five-point; sqrt(eps) for the complex
    step, below which it has no cancellation) stands beside them, with the
    error there on the same fitted curve and the error measured at that
    step: what the textbook's choice gives here, not its estimate
    ``eps**(p/(p + n))``, which takes the constants of both lines as 1 (a
    single measured error may be far below the curve, by a lucky
    cancellation of rounding errors). The scan itself is kept in
    ``attrs["scan"]`` (``"h [rad]"`` and the relative error of each scheme)
    for plots, and each shown column's step in ``attrs["steps"]`` (column ->
    h in rad).

    Parameters
    ----------
    mechanism : Mechanism
    quantity : str
        The unknown, or derived quantity (:mod:`numkin.derived`),
        differentiated. A derived quantity's stencil samples are its
        expression at the unknowns solved at ``theta + k h``; its complex
        step is its own, ``Im(q(x(theta + i h), theta + i h)) / h`` with the
        unknowns solved at the complex input and its expression evaluated
        in complex arithmetic (:func:`quantity_complex_step`); blank, with
        the reason in the caption, where the expression is not analytic
        (``abs``, ``atan2``, ...).
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
        measured optimal h [-]`` (on the fitted curve), ``rel error measured
        at that h [-]``, ``textbook rule``, ``textbook optimal h
        [rad]``, ``rel error on fitted curve at textbook h [-]``, ``rel
        error measured at textbook h [-]``. Errors are
        relative to the exact value at the check angle (absolute if it is
        exactly 0). ``attrs["positions"]`` holds
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

    studied = studied_quantity(mechanism, quantity)
    lab = studied.labels
    steps = [float(h) for h in steps]
    if not steps or not all(math.isfinite(h) and 0 < h < 1 for h in steps):
        raise InputError(f"steps must be positive and below 1 rad, got {steps!r}")
    names = [schemes] if isinstance(schemes, str) else list(schemes)
    sch = [lookup(n) for n in names]
    if any(s.periodic_only for s in sch):
        raise InputError("spectral schemes need a full periodic sweep; they have no step h at one angle")
    stencils = {s.name: stencil(s) for s in sch if not _complex(s)}
    theta = float(check_angle)
    base = branch_point(mechanism, theta, guess, start)
    x0 = base.values[:, 0]
    v0 = float(studied.values(base)[0])
    q1, q2 = (float(d[0]) for d in studied.exact(base))
    lo, hi = math.log10(min(steps)), math.log10(max(steps))
    m = int(round((hi - lo) * scan_per_decade))
    # the scan's steps, the given ones among them in place of those they equal but for rounding (10**-5 from the
    # linspace of exponents is not 1e-5)
    grid = [g for g in (10.0 ** np.linspace(hi, lo, m + 1)).tolist() if not any(abs(g - h) <= 1e-9 * h for h in steps)]
    scan = sorted(set(steps) | set(grid), reverse=True)
    # representable steps: theta + h is a float and h = (theta + h) - theta exactly
    eff = np.array([(theta + h) - theta for h in scan])
    S = len(scan)
    offsets = sorted({int(k) for k, _ in stencils.values() for k in k} - {0})
    samples = {0: np.full(S, v0)}
    outside = np.zeros(S, dtype=bool)
    if offsets:
        kk = np.array(offsets, dtype=float)
        tt = theta + eff[:, None] * kk[None, :]  # (S, K)
        solved = _samples(mechanism, base, tt.reshape(-1))
        # stencil samples outside the quantity's domain (its expression undefined at theta + k h): NaN, and
        # the steps that take them are blank
        vals = studied.near(studied.at(solved, tt.reshape(-1), check=False), v0).reshape(S, len(offsets))
        outside = ~np.all(np.isfinite(vals), axis=1)
        samples.update({k: vals[:, c] for c, k in enumerate(offsets)})
    rows = []
    no_complex = ""
    scan_errors = {}
    shown = {h: k for k, h in enumerate(scan)}
    for scheme in sch:
        deriv, order = scheme.derivative, scheme.order
        exact = q1 if deriv == 1 else q2
        if _complex(scheme):
            est = quantity_complex_step(studied, base, eff)
            if isinstance(est, str):  # not analytic: no complex step of the quantity
                no_complex = est
                est = np.full(S, math.nan)
        else:
            ks, ws = stencils[scheme.name]
            est = sum(w * samples[int(k)] for k, w in zip(ks, ws)) / eff**deriv
        err = np.abs(est - exact)
        rel = err / abs(exact) if exact != 0 else err  # an exact zero: absolute errors
        row = {
            "scheme": scheme.label,
            "formal order": order_text(scheme),
            "quantity": lab["d1"] if deriv == 1 else lab["d2"],
            f"exact value {UNIT}": float(exact),
        }
        for h in steps:
            row[f"rel error at h = {h:.0e} rad [-]"] = float(rel[shown[h]])
        # the floor of the complex step is eps itself (no cancellation): derivative 0 in the rounding line
        floor = 0 if _complex(scheme) else deriv
        hstar, estar = fitted_optimum(eff, rel, order, floor)
        row["measured optimal h [rad]"] = hstar
        row["rel error at measured optimal h [-]"] = estar
        row["rel error measured at that h [-]"] = (
            _error_at(studied, base, scheme, stencils, theta, hstar, exact) if math.isfinite(hstar) else math.nan
        )
        scan_errors[row["scheme"]] = [float(v) for v in rel]
        if _complex(scheme):
            row["textbook rule"] = "any h <= sqrt(eps): no cancellation"
            row["textbook optimal h [rad]"] = math.sqrt(EPS)
        else:
            p, n = order, deriv
            row["textbook rule"] = _TEXTBOOK.get((n, p), f"eps^(1/{p + n})")
            row["textbook optimal h [rad]"] = EPS ** (1.0 / (p + n))
        h_tb = row["textbook optimal h [rad]"]
        row[_ON_CURVE_TEXTBOOK] = _on_fitted_curve(eff, rel, order, floor, h_tb)
        row[_AT_TEXTBOOK] = math.nan if _complex(scheme) and no_complex else _error_at(
            studied, base, scheme, stencils, theta, h_tb, exact)
        rows.append(row)
    df = pd.DataFrame(rows)
    df.attrs["quantities"] = studied.quantities
    caption = (
        f"Round-off floor: {mechanism.title}, {studied.title} at {lab['input']} = {deg_text(theta)} deg on the sweep's "
        "branch; relative error against the step h, positions solved by Newton to the stopping rule's "
        "tol^(4/3). Measured optimum: where the truncation line C_t h^p and the rounding line C_r eps/h^n, "
        f"fitted to {S} steps, meet (the error there is on the fitted curve; beside it the error measured at that "
        "step). Textbook step: eps^(1/(p+n)) (sqrt(eps) for the complex step), with the error on the same fitted "
        "curve there and the error measured at that step."
    )
    caption += relative_text({"every error": at_angle(f"{lab['input']} = {deg_text(theta)} deg")})
    zero = [lab[d] for d, v in (("d1", q1), ("d2", q2)) if abs(v) <= 1e-12 * (abs(v0) + 1.0)]
    if zero:
        caption += (
            f" The exact {' and '.join(zero)} is 0 at this angle: errors are absolute, and symmetric stencils "
            "may be exact by symmetry; choose another angle to see the round-off floor."
        )
    blank = [h for h in steps if outside[shown[h]]]
    if blank:
        caption += (
            f" At h >= {min(blank):.0e} rad the stencils reach inputs theta + k h where {studied.title} is undefined "
            "(outside its domain): those steps are blank for the schemes that use them."
        )
    if no_complex:
        caption += f" The complex-step row is blank: {studied.title}: {no_complex}."
    key = ["scheme", "formal order", "quantity"]
    cols = [c for c in df.columns if c.startswith("rel error at h =")]
    third = (len(cols) + 2) // 3
    set_views(df, [
        ("relative error against the step h: the larger steps", key[:1] + cols[:third]),
        ("relative error against the step h: the middle steps", key[:1] + cols[third:2 * third]),
        ("relative error against the step h: the smaller steps", key[:1] + cols[2 * third:]),
        ("optimal step: measured (fitted lines)", key[:1] + key[2:] + [
            f"exact value {UNIT}", "measured optimal h [rad]", "rel error at measured optimal h [-]",
            "rel error measured at that h [-]"]),
        ("optimal step: textbook", key[:2] + ["textbook rule", "textbook optimal h [rad]", _ON_CURVE_TEXTBOOK,
                                               _AT_TEXTBOOK]),
    ], row_keys=["scheme"])
    df.attrs["scan"] = {"h [rad]": [float(h) for h in eff], **scan_errors}
    df.attrs["steps"] = {f"rel error at h = {h:.0e} rad [-]": float(h) for h in steps}
    df.attrs["check"] = (mechanism.input_name, math.degrees(theta))  # the input's name and angle (deg)
    return set_caption(df, caption, [position_record("check angle", mechanism, theta, x0)])


def _complex(scheme) -> bool:
    """Whether a scheme is the complex step (of a function, not of samples: solved at ``theta + i h``)."""
    return scheme.kind == "complex_step"


def _samples(mechanism, base, tt) -> np.ndarray:
    """The positions (n, M) at the inputs `tt` near the one-point sweep `base`, solved by Newton.

    Each from the second-order Taylor prediction of the exact rates at the base point.
    """
    x0 = base.values[:, :1]
    dq, d2q = exact_derivatives(base)
    dt = np.asarray(tt, dtype=float)[None, :] - float(base.inputs[0])
    pred = x0 + dq[:, :1] * dt + 0.5 * d2q[:, :1] * dt**2
    return solve_points(mechanism, pred, tt, what="round-off sample")


def _error_at(studied, base, scheme, stencils, theta, h, exact) -> float:
    """The relative error of one scheme (the complex step too) measured at the step `h`."""
    h = (theta + h) - theta
    if _complex(scheme):
        est = float(quantity_complex_step(studied, base, [h])[0])
    else:
        ks, ws = stencils[scheme.name]
        tt = theta + h * ks.astype(float)
        v0 = studied.values(base)[0]
        vals = studied.near(studied.at(_samples(studied.mechanism, base, tt), tt, check=False), v0)
        vals[ks == 0] = v0
        est = float(np.sum(ws * vals) / h**scheme.derivative)
    err = abs(est - exact)
    return err / abs(exact) if exact != 0 else err

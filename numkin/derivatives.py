"""Finite-difference derivatives of sampled data.

Every scheme takes values ``y`` sampled on a uniform grid of spacing ``h``
and differentiates along the last axis, so ``y`` may hold one signal of
shape ``(N,)`` or several of shape ``(k, N)``.  The result has the shape of
``y``.

Schemes
-------
==================  =====  =========  =====================================================
name                d/dx   order p    interior stencil
==================  =====  =========  =====================================================
forward             1st    1          (y[i+1] - y[i]) / h
backward            1st    1          (y[i] - y[i-1]) / h
centred             1st    2          (y[i+1] - y[i-1]) / (2h)
five_point          1st    4          (-y[i+2] + 8y[i+1] - 8y[i-1] + y[i-2]) / (12h)
richardson          1st    4          (4 D(h) - D(2h)) / 3, D = centred difference
spectral            1st    spectral   FFT: multiply mode k by ik (periodic grids only)
second_difference   2nd    2          (y[i+1] - 2y[i] + y[i-1]) / h^2
forward_of_forward  2nd    1          (y[i+2] - 2y[i+1] + y[i]) / h^2
centred_of_centred  2nd    2          (y[i+2] - 2y[i] + y[i-2]) / (4h^2)
five_point_second   2nd    4          (-y[i+2] + 16y[i+1] - 30y[i] + 16y[i-1] - y[i-2]) / (12h^2)
spectral_second     2nd    spectral   FFT: multiply mode k by -k^2 (periodic grids only)
==================  =====  =========  =====================================================

The same table is available at run time as :data:`SCHEMES`.

Grids
-----
``periodic=True``
    The N samples cover exactly one period: sample N would repeat sample 0
    (for example a crank sweep 0, 1, ..., 359 degrees).  Stencils wrap
    around, so there are no end effects.  Angles that grow by a constant
    every period (the input angle itself, or a link that turns fully) are
    handled with ``period_offset``: the value that sample N would have is
    ``y[0] + period_offset`` (``2*pi`` for one full turn), and a stencil
    that reaches past either end adds or subtracts that offset.  For a
    ``(k, N)`` input it may also be an array of k offsets, one per row.
    The values in ``y`` are never wrapped.
``periodic=False`` (default)
    An open grid such as 0..180 degrees inclusive.  Points near the ends,
    where the interior stencil would reach outside the data, use one-sided
    stencils of the same order as the interior; each function documents
    its end stencils.

Step rule
---------
With truncation order p the error of an n-th derivative behaves like
``C h**p + eps*max|y| / h**n`` (``eps`` ~ 2.2e-16 is the rounding error of
the samples): halving h divides the truncation error by ``2**p`` until the
rounding term takes over, near ``h ~ eps**(1/(p + n))`` (about 1e-8 for
``forward``, 6e-6 for ``centred``, 7e-4 for ``five_point``, 1e-4 for
``second_difference``).  ``h`` must be measured in the unit of the
independent variable the derivative is taken with respect to: for a sweep
in degrees, pass ``h = np.deg2rad(step)`` to get derivatives per radian.
:func:`complex_step` has no rounding term and can use ``h = 1e-20``.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "Scheme",
    "SCHEMES",
    "get_scheme",
    "differentiate",
    "forward",
    "backward",
    "centred",
    "five_point",
    "richardson",
    "spectral",
    "second_difference",
    "forward_of_forward",
    "centred_of_centred",
    "five_point_second",
    "spectral_second",
    "complex_step",
]

FloatArray = NDArray[np.float64]


# --------------------------------------------------------------------------
# Stencils
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class _Stencil:
    """``sum(weights[j] * y[i + offsets[j]]) / denominator`` at sample i."""

    offsets: tuple[int, ...]
    weights: tuple[float, ...]
    denominator: float = 1.0

    @property
    def width(self) -> int:
        return max(self.offsets) - min(self.offsets) + 1

    def mirrored(self, derivative: int) -> _Stencil:
        """The same stencil reflected about sample i (for the right-hand end)."""
        sign = (-1) ** derivative
        return _Stencil(
            tuple(-offset for offset in self.offsets),
            tuple(sign * weight for weight in self.weights),
            self.denominator,
        )


@dataclass(frozen=True)
class _Rule:
    """Interior stencil plus the one-sided stencils used at the ends of an open grid.

    ``left[j]`` is used at sample ``j`` and ``right[j]`` at sample ``N-1-j``.
    """

    derivative: int
    interior: _Stencil
    left: tuple[_Stencil, ...] = ()
    right: tuple[_Stencil, ...] = ()

    def __post_init__(self) -> None:
        if len(self.left) != -min(self.interior.offsets) or len(self.right) != max(
            self.interior.offsets
        ):
            raise ValueError("end stencils must cover exactly the points the interior cannot")

    def min_samples(self, periodic: bool) -> int:
        if periodic:
            return self.interior.width
        return max(stencil.width for stencil in (self.interior, *self.left, *self.right))


def _symmetric_rule(derivative: int, interior: _Stencil, left: tuple[_Stencil, ...]) -> _Rule:
    """Rule whose right-hand end stencils are the mirror images of the left-hand ones."""
    right = tuple(stencil.mirrored(derivative) for stencil in left)
    return _Rule(derivative, interior, left, right)


_FORWARD_STEP = _Stencil((0, 1), (-1, 1))
_FORWARD_OF_FORWARD_STEP = _Stencil((0, 1, 2), (1, -2, 1))

_FORWARD = _Rule(1, _FORWARD_STEP, right=(_FORWARD_STEP.mirrored(1),))
_BACKWARD = _Rule(1, _FORWARD_STEP.mirrored(1), left=(_FORWARD_STEP,))
_CENTRED = _symmetric_rule(
    1,
    _Stencil((-1, 1), (-1, 1), 2),
    left=(_Stencil((0, 1, 2), (-3, 4, -1), 2),),
)
_FIVE_POINT = _symmetric_rule(
    1,
    _Stencil((-2, -1, 1, 2), (1, -8, 8, -1), 12),
    left=(
        _Stencil((0, 1, 2, 3, 4), (-25, 48, -36, 16, -3), 12),
        _Stencil((-1, 0, 1, 2, 3), (-3, -10, 18, -6, 1), 12),
    ),
)
_SECOND_DIFFERENCE_END = _Stencil((0, 1, 2, 3), (2, -5, 4, -1))
_SECOND_DIFFERENCE = _symmetric_rule(
    2,
    _Stencil((-1, 0, 1), (1, -2, 1)),
    left=(_SECOND_DIFFERENCE_END,),
)
_FORWARD_OF_FORWARD = _Rule(
    2,
    _FORWARD_OF_FORWARD_STEP,
    right=(_FORWARD_OF_FORWARD_STEP.mirrored(2),) * 2,
)
_CENTRED_OF_CENTRED = _symmetric_rule(
    2,
    _Stencil((-2, 0, 2), (1, -2, 1), 4),
    left=(_SECOND_DIFFERENCE_END, _Stencil((-1, 0, 1), (1, -2, 1))),
)
_FIVE_POINT_SECOND = _symmetric_rule(
    2,
    _Stencil((-2, -1, 0, 1, 2), (-1, 16, -30, 16, -1), 12),
    left=(
        _Stencil((0, 1, 2, 3, 4, 5), (45, -154, 214, -156, 61, -10), 12),
        _Stencil((-1, 0, 1, 2, 3, 4), (10, -15, -4, 14, -6, 1), 12),
    ),
)


# --------------------------------------------------------------------------
# Validation
# --------------------------------------------------------------------------


def _check_step(h: float) -> float:
    if isinstance(h, bool) or not isinstance(h, numbers.Real) or not (
        math.isfinite(h) and h > 0
    ):
        raise ValueError(f"h must be a finite positive number, got {h!r}")
    return float(h)


def _check_samples(y: ArrayLike, scheme: str, minimum: int, periodic: bool) -> FloatArray:
    samples = np.asarray(y, dtype=float)
    if samples.ndim == 0:
        raise ValueError(f"y must be an array of samples, got the scalar {samples.item()!r}")
    count = samples.shape[-1]
    if count < minimum:
        grid = "a periodic" if periodic else "an open"
        raise ValueError(
            f"scheme {scheme!r} needs at least {minimum} samples along the last axis "
            f"on {grid} grid, got {count}"
        )
    bad = ~np.isfinite(samples)
    if bad.any():
        first = tuple(int(i) for i in np.argwhere(bad)[0])
        index = first[0] if samples.ndim == 1 else first
        raise ValueError(f"y contains {samples[first]} at index {index}")
    return samples


def _check_offset(period_offset: ArrayLike, periodic: bool, samples: FloatArray) -> FloatArray:
    """Return the offset shaped to broadcast against ``samples`` (trailing axis of length 1)."""
    offset = np.asarray(period_offset, dtype=float)
    if not np.all(np.isfinite(offset)):
        raise ValueError(f"period_offset must be finite, got {period_offset!r}")
    if not periodic and np.any(offset != 0):
        raise ValueError("period_offset only applies to periodic grids (periodic=True)")
    try:
        offset = np.broadcast_to(offset, samples.shape[:-1])
    except ValueError:
        raise ValueError(
            f"period_offset must be a float or have shape {samples.shape[:-1]} "
            f"(one offset per row of y), got shape {offset.shape}"
        ) from None
    return offset[..., np.newaxis]


def _validated(
    scheme: str,
    y: ArrayLike,
    h: float,
    periodic: bool,
    period_offset: ArrayLike,
    minimum: int,
) -> tuple[FloatArray, float, FloatArray]:
    step = _check_step(h)
    samples = _check_samples(y, scheme, minimum, periodic)
    offset = _check_offset(period_offset, periodic, samples)
    return samples, step, offset


def _require_periodic(scheme: str, periodic: bool) -> None:
    if not periodic:
        raise ValueError(
            f"scheme {scheme!r} requires periodic=True (N samples covering exactly one "
            "period); use five_point or five_point_second on open grids"
        )


# --------------------------------------------------------------------------
# Stencil application
# --------------------------------------------------------------------------


def _wrapped(samples: FloatArray, shift: int, offset: FloatArray) -> FloatArray:
    """``y[i + shift]`` for every i, continuing periodically with ``y[N] = y[0] + offset``."""
    count = samples.shape[-1]
    index = np.arange(count) + shift
    return samples[..., index % count] + offset * (index // count)


def _periodic_sum(samples: FloatArray, stencil: _Stencil, offset: FloatArray) -> FloatArray:
    total = np.zeros_like(samples)
    for shift, weight in zip(stencil.offsets, stencil.weights):
        total += weight * _wrapped(samples, shift, offset)
    return total / stencil.denominator


def _interior_sum(samples: FloatArray, stencil: _Stencil) -> FloatArray:
    """Stencil at every sample where it fits inside the data (open grid)."""
    first = -min(stencil.offsets)
    count = samples.shape[-1] - first - max(stencil.offsets)
    total = np.zeros(samples.shape[:-1] + (count,))
    for shift, weight in zip(stencil.offsets, stencil.weights):
        start = first + shift
        total += weight * samples[..., start : start + count]
    return total / stencil.denominator


def _point_sum(samples: FloatArray, index: int, stencil: _Stencil) -> FloatArray:
    total = sum(
        weight * samples[..., index + shift]
        for shift, weight in zip(stencil.offsets, stencil.weights)
    )
    return total / stencil.denominator


def _fill_ends(out: FloatArray, samples: FloatArray, rule: _Rule) -> None:
    last = samples.shape[-1] - 1
    for j, stencil in enumerate(rule.left):
        out[..., j] = _point_sum(samples, j, stencil)
    for j, stencil in enumerate(rule.right):
        out[..., last - j] = _point_sum(samples, last - j, stencil)


def _apply(
    rule: _Rule,
    scheme: str,
    y: ArrayLike,
    h: float,
    periodic: bool,
    period_offset: ArrayLike,
) -> FloatArray:
    samples, step, offset = _validated(
        scheme, y, h, periodic, period_offset, rule.min_samples(periodic)
    )
    scale = step**rule.derivative
    if periodic:
        return _periodic_sum(samples, rule.interior, offset) / scale
    out = np.empty_like(samples)
    out[..., len(rule.left) : samples.shape[-1] - len(rule.right)] = _interior_sum(
        samples, rule.interior
    )
    _fill_ends(out, samples, rule)
    return out / scale


# --------------------------------------------------------------------------
# First derivative
# --------------------------------------------------------------------------


def forward(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """First derivative by forward differences, O(h).

    ``y'[i] ~ (y[i+1] - y[i]) / h``; the truncation error is ``h/2 y''``.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 2 samples.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``
        (``2*pi`` for an angle that turns once per period).

    Returns
    -------
    numpy.ndarray
        Estimate of dy/dx at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    Open grid: the last sample has no right neighbour and uses the backward
    difference ``(y[N-1] - y[N-2]) / h``, also O(h).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import forward
    >>> x = np.linspace(0.0, 1.0, 101)
    >>> print(f"{forward(np.exp(x), x[1] - x[0])[0]:.4f}")  # exact: 1
    1.0050
    """
    return _apply(_FORWARD, "forward", y, h, periodic, period_offset)


def backward(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """First derivative by backward differences, O(h).

    ``y'[i] ~ (y[i] - y[i-1]) / h``; the truncation error is ``-h/2 y''``.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 2 samples.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of dy/dx at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    Open grid: the first sample has no left neighbour and uses the forward
    difference ``(y[1] - y[0]) / h``, also O(h).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import backward
    >>> x = np.linspace(0.0, 1.0, 101)
    >>> print(f"{backward(np.exp(x), x[1] - x[0])[-1]:.4f}")  # exact: e = 2.7183
    2.7047
    """
    return _apply(_BACKWARD, "backward", y, h, periodic, period_offset)


def centred(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """First derivative by centred differences, O(h**2).

    ``y'[i] ~ (y[i+1] - y[i-1]) / (2h)``; the truncation error is
    ``h**2/6 y'''``.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 3 samples.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of dy/dx at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    Open grid, second-order one-sided 3-point stencils at the ends:

    - ``y'[0] ~ (-3y[0] + 4y[1] - y[2]) / (2h)``
    - ``y'[N-1] ~ (3y[N-1] - 4y[N-2] + y[N-3]) / (2h)``

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import centred
    >>> x = np.linspace(0.0, np.pi, 181)  # 1 degree steps
    >>> dy = centred(np.sin(x), x[1] - x[0])
    >>> print(f"{dy[60]:.6f}")  # exact: cos(60 deg) = 0.5
    0.499975

    A crank angle that turns once over a full periodic sweep:

    >>> theta = np.linspace(0.0, 2 * np.pi, 360, endpoint=False)
    >>> rate = centred(theta, theta[1], periodic=True, period_offset=2 * np.pi)
    >>> print(np.allclose(rate, 1.0))
    True
    """
    return _apply(_CENTRED, "centred", y, h, periodic, period_offset)


def five_point(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """First derivative by the five-point centred stencil, O(h**4).

    ``y'[i] ~ (-y[i+2] + 8y[i+1] - 8y[i-1] + y[i-2]) / (12h)``; the
    truncation error is ``-h**4/30 y^(5)``.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 5 samples.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of dy/dx at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    Open grid, fourth-order 5-point stencils at the two samples of each end
    (truncation errors ``h**4/5 y^(5)`` and ``-h**4/20 y^(5)``):

    - ``y'[0] ~ (-25y[0] + 48y[1] - 36y[2] + 16y[3] - 3y[4]) / (12h)``
    - ``y'[1] ~ (-3y[0] - 10y[1] + 18y[2] - 6y[3] + y[4]) / (12h)``
    - ``y'[N-2] ~ (3y[N-1] + 10y[N-2] - 18y[N-3] + 6y[N-4] - y[N-5]) / (12h)``
    - ``y'[N-1] ~ (25y[N-1] - 48y[N-2] + 36y[N-3] - 16y[N-4] + 3y[N-5]) / (12h)``

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import five_point
    >>> x = np.linspace(0.0, np.pi, 181)
    >>> dy = five_point(np.sin(x), x[1] - x[0])
    >>> print(f"{dy[60]:.9f}")  # exact: 0.5
    0.499999998
    """
    return _apply(_FIVE_POINT, "five_point", y, h, periodic, period_offset)


_CENTRED_STEP_H = _Stencil((-1, 1), (-1, 1), 2)
_CENTRED_STEP_2H = _Stencil((-2, 2), (-1, 1), 4)


def richardson(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """First derivative by Richardson extrapolation of centred differences, O(h**4).

    With ``D(h) = (y[i+1] - y[i-1]) / (2h)`` and
    ``D(2h) = (y[i+2] - y[i-2]) / (4h)``, both with error ``c h**2 + O(h**4)``
    for the same c, the combination ``(4 D(h) - D(2h)) / 3`` cancels the
    ``h**2`` term.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 5 samples.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of dy/dx at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    See Also
    --------
    five_point : the same stencil written out; the two agree to rounding.

    Notes
    -----
    Expanded, ``(4 D(h) - D(2h)) / 3`` is exactly the five-point stencil
    ``(-y[i+2] + 8y[i+1] - 8y[i-1] + y[i-2]) / (12h)``.  On an open grid
    ``D(2h)`` is unavailable at the two samples of each end, which use the
    fourth-order one-sided stencils of :func:`five_point`.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import richardson
    >>> x = np.linspace(0.0, np.pi, 181)
    >>> dy = richardson(np.sin(x), x[1] - x[0])
    >>> print(f"{dy[60]:.9f}")  # exact: 0.5
    0.499999998
    """
    samples, step, offset = _validated("richardson", y, h, periodic, period_offset, 5)
    if periodic:
        d_h = _periodic_sum(samples, _CENTRED_STEP_H, offset)
        d_2h = _periodic_sum(samples, _CENTRED_STEP_2H, offset)
        return (4.0 * d_h - d_2h) / (3.0 * step)
    d_h = _interior_sum(samples, _CENTRED_STEP_H)[..., 1:-1]
    d_2h = _interior_sum(samples, _CENTRED_STEP_2H)
    out = np.empty_like(samples)
    out[..., 2:-2] = (4.0 * d_h - d_2h) / 3.0
    _fill_ends(out, samples, _FIVE_POINT)
    return out / step


def _angular_wavenumbers(count: int, step: float) -> FloatArray:
    return 2.0 * np.pi * np.fft.rfftfreq(count, d=step)


def spectral(
    y: ArrayLike, h: float, periodic: bool = True, period_offset: float = 0.0
) -> FloatArray:
    """First derivative by FFT (spectral) differentiation of one full period.

    Each Fourier mode ``exp(i k x)`` is multiplied by ``i k``.  For
    band-limited data (a trigonometric polynomial of degree below N/2) the
    result is exact to rounding; for smooth periodic data the error falls
    faster than any power of h.

    Parameters
    ----------
    y : array_like
        N samples covering exactly one period (sample N would repeat
        sample 0), along the last axis; at least 2 samples.
    h : float
        Grid spacing, finite and positive (the period is ``N*h``).
    periodic : bool, default True
        Must be True; the argument exists so that all schemes share one
        signature.
    period_offset : float, default 0.0
        Sample N equals ``y[0] + period_offset``.  The linear trend
        ``period_offset * i / N`` is removed before the transform and its
        slope ``period_offset / (N*h)`` added back.

    Returns
    -------
    numpy.ndarray
        dy/dx at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `periodic` is False, `h` is not finite and positive, or `y` is
        too short or contains NaN.

    Notes
    -----
    For even N the Nyquist mode ``cos(pi x / h)`` is sampled as
    ``(-1)**i``; its derivative vanishes at every sample, so that mode is
    set to zero.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import spectral
    >>> x = np.linspace(0.0, 2 * np.pi, 64, endpoint=False)
    >>> error = spectral(np.exp(np.sin(x)), x[1]) - np.cos(x) * np.exp(np.sin(x))
    >>> print(np.max(np.abs(error)) < 1e-12)
    True
    """
    _require_periodic("spectral", periodic)
    samples, step, offset = _validated("spectral", y, h, periodic, period_offset, 2)
    count = samples.shape[-1]
    trend = offset * (np.arange(count) / count)
    factor = 1j * _angular_wavenumbers(count, step)
    if count % 2 == 0:
        factor[-1] = 0.0
    coefficients = np.fft.rfft(samples - trend, axis=-1)
    return np.fft.irfft(factor * coefficients, n=count, axis=-1) + offset / (count * step)


# --------------------------------------------------------------------------
# Second derivative
# --------------------------------------------------------------------------


def second_difference(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """Second derivative by the centred second difference, O(h**2).

    ``y''[i] ~ (y[i+1] - 2y[i] + y[i-1]) / h**2``; the truncation error is
    ``h**2/12 y''''``.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 3 samples on a periodic grid, 4 on an open one.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of d2y/dx2 at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    Open grid, second-order one-sided 4-point stencils at the ends:

    - ``y''[0] ~ (2y[0] - 5y[1] + 4y[2] - y[3]) / h**2``
    - ``y''[N-1] ~ (2y[N-1] - 5y[N-2] + 4y[N-3] - y[N-4]) / h**2``

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import second_difference
    >>> x = np.linspace(0.0, np.pi, 181)
    >>> d2y = second_difference(np.sin(x), x[1] - x[0])
    >>> print(f"{d2y[90]:.6f}")  # exact: -sin(90 deg) = -1
    -0.999975
    """
    return _apply(_SECOND_DIFFERENCE, "second_difference", y, h, periodic, period_offset)


def forward_of_forward(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """Second derivative as the forward difference of the forward difference, O(h).

    ``(y[i+2] - 2y[i+1] + y[i]) / h**2``, which is what applying
    :func:`forward` twice gives.  The stencil is centred on sample i+1: it
    estimates ``y''`` at ``x[i+1]`` to O(h**2), so as an estimate of
    ``y''[i]`` it is shifted by one sample and only O(h), with error
    ``h y'''``.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 3 samples.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.  The result then
        equals ``forward(forward(y))`` exactly.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of d2y/dx2 at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    Open grid: the last two samples have no ``y[i+2]`` and use the mirror
    image ``(y[i] - 2y[i-1] + y[i-2]) / h**2`` (backward of backward, also
    O(h)).  Applying :func:`forward` twice literally would give 0 there.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import forward_of_forward
    >>> x = np.linspace(0.0, np.pi, 181)
    >>> d2y = forward_of_forward(np.sin(x), x[1] - x[0])
    >>> print(f"{d2y[89]:.6f}")  # estimates y'' at x[90]: exact -1
    -0.999975
    """
    return _apply(_FORWARD_OF_FORWARD, "forward_of_forward", y, h, periodic, period_offset)


def centred_of_centred(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """Second derivative as the centred difference of the centred difference, O(h**2).

    ``(y[i+2] - 2y[i] + y[i-2]) / (4h**2)``, which is what applying
    :func:`centred` twice gives: a second difference over a 2h-wide
    stencil, with truncation error ``h**2/3 y''''``, four times that of
    :func:`second_difference`.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 5 samples.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.  The result then
        equals ``centred(centred(y))`` exactly.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of d2y/dx2 at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    On an open grid, applying :func:`centred` twice is only O(h) at the two
    samples of each end, because the one-sided first derivatives there have
    a different error constant.  Those samples use second-order stencils
    instead:

    - ``y''[0] ~ (2y[0] - 5y[1] + 4y[2] - y[3]) / h**2``
    - ``y''[1] ~ (y[0] - 2y[1] + y[2]) / h**2``
    - ``y''[N-2] ~ (y[N-1] - 2y[N-2] + y[N-3]) / h**2``
    - ``y''[N-1] ~ (2y[N-1] - 5y[N-2] + 4y[N-3] - y[N-4]) / h**2``

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import centred_of_centred
    >>> x = np.linspace(0.0, np.pi, 181)
    >>> d2y = centred_of_centred(np.sin(x), x[1] - x[0])
    >>> print(f"{d2y[90]:.6f}")  # exact: -1
    -0.999898
    """
    return _apply(_CENTRED_OF_CENTRED, "centred_of_centred", y, h, periodic, period_offset)


def five_point_second(
    y: ArrayLike, h: float, periodic: bool = False, period_offset: float = 0.0
) -> FloatArray:
    """Second derivative by the five-point centred stencil, O(h**4).

    ``y''[i] ~ (-y[i+2] + 16y[i+1] - 30y[i] + 16y[i-1] - y[i-2]) / (12h**2)``;
    the truncation error is ``-h**4/90 y^(6)``.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``; at least 5 samples on a periodic grid, 6 on an open one.
    h : float
        Grid spacing, finite and positive.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0); stencils then wrap around.
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        Estimate of d2y/dx2 at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive, `y` is too short or contains
        NaN, or `period_offset` is non-zero on an open grid.

    Notes
    -----
    Open grid, fourth-order 6-point stencils at the two samples of each end
    (the right-hand ones are the mirror images, with the same weights):

    - ``y''[0] ~ (45y[0] - 154y[1] + 214y[2] - 156y[3] + 61y[4] - 10y[5]) / (12h**2)``
    - ``y''[1] ~ (10y[0] - 15y[1] - 4y[2] + 14y[3] - 6y[4] + y[5]) / (12h**2)``
    - ``y''[N-2] ~ (10y[N-1] - 15y[N-2] - 4y[N-3] + 14y[N-4] - 6y[N-5] + y[N-6]) / (12h**2)``
    - ``y''[N-1] ~ (45y[N-1] - 154y[N-2] + 214y[N-3] - 156y[N-4] + 61y[N-5]
      - 10y[N-6]) / (12h**2)``

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import five_point_second
    >>> x = np.linspace(0.0, np.pi, 181)
    >>> d2y = five_point_second(np.sin(x), x[1] - x[0])
    >>> print(f"{d2y[90]:.8f}")  # exact: -1
    -1.00000000
    """
    return _apply(_FIVE_POINT_SECOND, "five_point_second", y, h, periodic, period_offset)


def spectral_second(
    y: ArrayLike, h: float, periodic: bool = True, period_offset: float = 0.0
) -> FloatArray:
    """Second derivative by FFT (spectral) differentiation of one full period.

    Each Fourier mode ``exp(i k x)`` is multiplied by ``-k**2``.  For
    band-limited data the result is exact to rounding.

    Parameters
    ----------
    y : array_like
        N samples covering exactly one period (sample N would repeat
        sample 0), along the last axis; at least 2 samples.
    h : float
        Grid spacing, finite and positive (the period is ``N*h``).
    periodic : bool, default True
        Must be True; the argument exists so that all schemes share one
        signature.
    period_offset : float, default 0.0
        Sample N equals ``y[0] + period_offset``.  The linear trend
        ``period_offset * i / N`` is removed before the transform; it has
        no second derivative.

    Returns
    -------
    numpy.ndarray
        d2y/dx2 at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        If `periodic` is False, `h` is not finite and positive, or `y` is
        too short or contains NaN.

    Notes
    -----
    For even N the Nyquist mode ``(-1)**i`` is kept: it is real, and its
    second derivative ``-(pi/h)**2 (-1)**i`` is consistent with the samples.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import spectral_second
    >>> x = np.linspace(0.0, 2 * np.pi, 32, endpoint=False)
    >>> d2y = spectral_second(np.sin(3 * x), x[1])
    >>> print(np.allclose(d2y, -9 * np.sin(3 * x)))
    True
    """
    _require_periodic("spectral_second", periodic)
    samples, step, offset = _validated("spectral_second", y, h, periodic, period_offset, 2)
    count = samples.shape[-1]
    trend = offset * (np.arange(count) / count)
    factor = -_angular_wavenumbers(count, step) ** 2
    coefficients = np.fft.rfft(samples - trend, axis=-1)
    return np.fft.irfft(factor * coefficients, n=count, axis=-1)


# --------------------------------------------------------------------------
# Complex step
# --------------------------------------------------------------------------


def complex_step(
    f: Callable[[NDArray[np.complex128]], ArrayLike], x: ArrayLike, h: float = 1e-20
) -> float | FloatArray:
    """First derivative of a function by the complex-step method.

    ``f'(x) ~ Im(f(x + i h)) / h`` with error ``-h**2/6 f'''(x)``.  No
    difference of nearly equal numbers is formed, so there is no
    subtractive cancellation and `h` can be tiny: with the default 1e-20
    the truncation error is far below rounding and the result is accurate
    to machine precision.

    Parameters
    ----------
    f : callable
        Real-analytic function that accepts complex arrays and propagates
        the imaginary part (use ``np.sin``, ``np.exp``, ``**``, ...; avoid
        ``abs``, ``np.real`` and comparisons on the argument).
    x : float or array_like
        Point(s) at which to differentiate.
    h : float, default 1e-20
        Imaginary step, finite and positive.

    Returns
    -------
    float or numpy.ndarray
        ``f'(x)``: a float for scalar `x`, otherwise an array shaped like `x`.

    Raises
    ------
    ValueError
        If `h` is not finite and positive.
    TypeError
        If `f` returns real values for a complex argument (the imaginary
        part, and with it the derivative, would be lost).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import complex_step
    >>> print(complex_step(np.sin, 0.0))
    1.0
    >>> print(np.round(complex_step(lambda x: x**3, [1.0, 2.0]), 12))
    [ 3. 12.]
    """
    step = _check_step(h)
    points = np.asarray(x, dtype=float)
    values = np.asarray(f(points + 1j * step))
    if not np.iscomplexobj(values):
        raise TypeError(
            "f returned real values for a complex argument; complex_step needs a "
            "function that propagates complex numbers"
        )
    derivative = values.imag / step
    return float(derivative) if derivative.ndim == 0 else derivative


# --------------------------------------------------------------------------
# Registry
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Scheme:
    """Description of one finite-difference scheme in :data:`SCHEMES`.

    Attributes
    ----------
    name : str
        Registry name, also the name of the function.
    derivative : int
        Which derivative the scheme estimates: 1 or 2.
    order : int
        Order p of the truncation error O(h**p) on uniform grids, ends
        included.  0 marks the spectral schemes, whose error on smooth
        periodic data falls faster than any power of h.
    stencil : str
        Interior formula, for tables and plot legends.
    function : callable
        ``function(y, h, periodic=..., period_offset=0.0)``.
    periodic_only : bool
        True if the scheme needs ``periodic=True``.
    description : str
        One-line description.

    Examples
    --------
    >>> from numkin.derivatives import SCHEMES
    >>> scheme = SCHEMES["centred"]
    >>> print(scheme.order, scheme.stencil)
    2 (y[i+1] - y[i-1])/(2h)
    """

    name: str
    derivative: int
    order: int
    stencil: str
    function: Callable[..., FloatArray]
    periodic_only: bool
    description: str


def _registry(*schemes: Scheme) -> dict[str, Scheme]:
    return {scheme.name: scheme for scheme in schemes}


SCHEMES: dict[str, Scheme] = _registry(
    Scheme(
        name="forward",
        derivative=1,
        order=1,
        stencil="(y[i+1] - y[i])/h",
        function=forward,
        periodic_only=False,
        description="forward difference",
    ),
    Scheme(
        name="backward",
        derivative=1,
        order=1,
        stencil="(y[i] - y[i-1])/h",
        function=backward,
        periodic_only=False,
        description="backward difference",
    ),
    Scheme(
        name="centred",
        derivative=1,
        order=2,
        stencil="(y[i+1] - y[i-1])/(2h)",
        function=centred,
        periodic_only=False,
        description="centred difference",
    ),
    Scheme(
        name="five_point",
        derivative=1,
        order=4,
        stencil="(-y[i+2] + 8y[i+1] - 8y[i-1] + y[i-2])/(12h)",
        function=five_point,
        periodic_only=False,
        description="five-point centred difference",
    ),
    Scheme(
        name="richardson",
        derivative=1,
        order=4,
        stencil="(4 D(h) - D(2h))/3",
        function=richardson,
        periodic_only=False,
        description="Richardson extrapolation of centred differences with steps h and 2h",
    ),
    Scheme(
        name="spectral",
        derivative=1,
        order=0,
        stencil="ik Y_k (FFT)",
        function=spectral,
        periodic_only=True,
        description="FFT differentiation of one full period",
    ),
    Scheme(
        name="second_difference",
        derivative=2,
        order=2,
        stencil="(y[i+1] - 2y[i] + y[i-1])/h^2",
        function=second_difference,
        periodic_only=False,
        description="centred second difference",
    ),
    Scheme(
        name="forward_of_forward",
        derivative=2,
        order=1,
        stencil="(y[i+2] - 2y[i+1] + y[i])/h^2",
        function=forward_of_forward,
        periodic_only=False,
        description="forward difference applied twice (centred on sample i+1)",
    ),
    Scheme(
        name="centred_of_centred",
        derivative=2,
        order=2,
        stencil="(y[i+2] - 2y[i] + y[i-2])/(4h^2)",
        function=centred_of_centred,
        periodic_only=False,
        description="centred difference applied twice (2h-wide second difference)",
    ),
    Scheme(
        name="five_point_second",
        derivative=2,
        order=4,
        stencil="(-y[i+2] + 16y[i+1] - 30y[i] + 16y[i-1] - y[i-2])/(12h^2)",
        function=five_point_second,
        periodic_only=False,
        description="five-point centred second difference",
    ),
    Scheme(
        name="spectral_second",
        derivative=2,
        order=0,
        stencil="-k^2 Y_k (FFT)",
        function=spectral_second,
        periodic_only=True,
        description="FFT second derivative of one full period",
    ),
)

_ALIASES = {
    "central": "centred",
    "centered": "centred",
    "second": "second_difference",
    "five-point": "five_point",
}


def get_scheme(name: str) -> Scheme:
    """Look up a scheme by name or alias.

    Parameters
    ----------
    name : str
        A key of :data:`SCHEMES` or one of the aliases ``"central"`` and
        ``"centered"`` (centred), ``"second"`` (second_difference) and
        ``"five-point"`` (five_point).  Case and surrounding spaces are
        ignored.

    Returns
    -------
    Scheme

    Raises
    ------
    ValueError
        For any other name; the message lists the valid names.

    Examples
    --------
    >>> from numkin.derivatives import get_scheme
    >>> get_scheme("central").name
    'centred'
    """
    key = name.strip().lower() if isinstance(name, str) else name
    try:
        return SCHEMES[_ALIASES.get(key, key)]
    except (KeyError, TypeError):
        raise ValueError(
            f"unknown finite-difference method {name!r}; valid names: "
            f"{', '.join(SCHEMES)} (aliases: {', '.join(_ALIASES)})"
        ) from None


def differentiate(
    y: ArrayLike,
    h: float,
    method: str = "centred",
    periodic: bool = False,
    period_offset: float = 0.0,
) -> FloatArray:
    """Differentiate sampled data with a scheme chosen by name.

    Parameters
    ----------
    y : array_like
        Samples on a uniform grid along the last axis, shape ``(N,)`` or
        ``(k, N)``.
    h : float
        Grid spacing, finite and positive.
    method : str, default "centred"
        Scheme name or alias, see :func:`get_scheme`.  Second-derivative
        schemes return the second derivative.
    periodic : bool, default False
        True if the N samples cover exactly one period (sample N would
        repeat sample 0).  Required by "spectral" and "spectral_second".
    period_offset : float, default 0.0
        Periodic grids only: sample N equals ``y[0] + period_offset``.

    Returns
    -------
    numpy.ndarray
        The derivative at every sample, same shape as `y`.

    Raises
    ------
    ValueError
        For an unknown method, or any error of the chosen scheme.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.derivatives import differentiate
    >>> x = np.linspace(0.0, 2 * np.pi, 90, endpoint=False)
    >>> dy = differentiate(np.sin(x), x[1], method="five_point", periodic=True)
    >>> print(f"{np.max(np.abs(dy - np.cos(x))):.1e}")
    7.9e-07
    """
    scheme = get_scheme(method)
    return scheme.function(y, h, periodic=periodic, period_offset=period_offset)

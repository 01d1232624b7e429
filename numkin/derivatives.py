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

The same table is available at run time as :data:`SCHEMES`.  The stencil
schemes are declared in :mod:`numkin.schemes` by their offsets alone: their
weights, orders, error terms and end stencils (and the formulas in the
docstrings below) are computed by :mod:`numkin.stencils`, and
:func:`numkin.schemes.register` adds a scheme at run time.

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

from typing import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import stencils as _st
from .errors import InputError
from .schemes import BUILT_IN, SCHEMES, Scheme, get_scheme

__all__ = [
    "Scheme",
    "SCHEMES",
    "get_scheme",
    "differentiate",
    "scheme_function",
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
# One docstring for every scheme of sampled data
# --------------------------------------------------------------------------

_TEMPLATE = """{summary}

{body}

Parameters
----------
y : array_like
    Samples on a uniform grid along the last axis, shape ``(N,)`` or
    ``(k, N)``; {samples}.
h : float
    Grid spacing, finite and positive{h_note}.
periodic : bool, default {periodic}
    {periodic_text}
period_offset : float or array_like, default 0.0
    Periodic grids only: sample N equals ``y[0] + period_offset``
    (``2*pi`` for an angle that turns once per period; one value per row
    of a ``(k, N)`` input).

Returns
-------
numpy.ndarray
    Estimate of {what} at every sample, same shape as `y`.

Raises
------
ValueError
    If `h` is not finite and positive, `y` is too short or contains
    NaN, or {raises}.
{notes}
Examples
--------
{examples}
"""

_PERIODIC_TEXT = {
    False: "True if the N samples cover exactly one period (sample N would\n"
    "    repeat sample 0); stencils then wrap around.",
    True: "Must be True; the argument exists so that all schemes share one\n    signature.",
}


def _samples_text(rule: _st.Rule) -> str:
    closed, opened = rule.min_samples(True), rule.min_samples(False)
    if closed == opened:
        return f"at least {closed} samples"
    return f"at least {closed} samples on a periodic grid, {opened} on an open one"


def _document(function, derivative: int, rule: _st.Rule | None = None, *, summary: str = "", body: str = "",
              notes: str = "", examples: str = "", spectral: bool = False, samples: str = "") -> None:
    """Fill `function`'s docstring from the shared template (formula and end stencils from `rule`)."""
    if rule is not None:
        s, tick = rule.interior, "'" * derivative
        body = body or (
            f"``y{tick}[i] ~ {s.formula()}``; the truncation error is "
            f"``{s.error_constant} h**{s.order} y^({s.order + derivative})``."
        )
        ends = rule.end_formulas()
        if ends:
            lines = "\n".join(f"- {e}" for e in ends)
            notes = (notes + "\n\n" if notes else "") + f"Open grid, end stencils ({rule.ends}, order {rule.order}):\n\n{lines}"
        samples = samples or _samples_text(rule)
    function.__doc__ = _TEMPLATE.format(
        summary=summary or f"{('First', 'Second')[derivative - 1]} derivative by the stencil {function.__name__}.",
        body=body,
        samples=samples,
        h_note=" (the period is ``N*h``)" if spectral else "",
        periodic=spectral,
        periodic_text=_PERIODIC_TEXT[spectral],
        what=("dy/dx", "d2y/dx2")[derivative - 1],
        raises="`periodic` is False" if spectral else "`period_offset` is non-zero on an open grid",
        notes=f"\nNotes\n-----\n{notes}\n" if notes else "",
        examples=examples or ">>> None",
    )


def scheme_function(name: str, rule: _st.Rule, **doc) -> Callable[..., FloatArray]:
    """The function ``f(y, h, periodic=False, period_offset=0.0)`` of a stencil scheme.

    Used by :func:`numkin.schemes.register`; `doc` fills the shared docstring
    (``summary``, ``body``, ``notes``, ``examples``).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.stencils import Rule, Stencil
    >>> f = scheme_function("my_centred", Rule.build(Stencil.from_offsets((-1, 0, 1), 1)))
    >>> f(np.array([0.0, 1.0, 4.0, 9.0]), 1.0)     # y = x**2: y' = 2x, exact for a parabola
    array([0., 2., 4., 6.])
    """

    def function(y: ArrayLike, h: float, periodic: bool = False, period_offset: ArrayLike = 0.0) -> FloatArray:
        return _st.apply_rule(rule, name, y, h, periodic, period_offset)

    function.__name__ = function.__qualname__ = name
    _document(function, rule.derivative, rule, **doc)
    return function


def _built_in(name: str, **doc) -> Callable[..., FloatArray]:
    decl = BUILT_IN[name]
    interior = _st.Stencil.from_offsets(decl["offsets"], decl["derivative"])
    return scheme_function(name, _st.Rule.build(interior, decl.get("ends", "one-sided")), **doc)


def _require_periodic(scheme: str, periodic: bool) -> None:
    if not periodic:
        raise InputError(
            f"scheme {scheme!r} requires periodic=True (N samples covering exactly one "
            "period); use five_point or five_point_second on open grids"
        )


# --------------------------------------------------------------------------
# Stencil schemes (formulas, errors and end stencils come from the stencils)
# --------------------------------------------------------------------------

def _example(name: str, stop: str, count: int, func: str, index: int, digits: int, expected: str,
             note: str, more: str = "") -> str:
    """A doctest: `name` applied to ``func(x)`` on ``linspace(0, stop, count)``, printed at `index`."""
    return (
        f">>> import numpy as np\n>>> from numkin.derivatives import {name}\n"
        f">>> x = np.linspace(0.0, {stop}, {count})\n"
        f'>>> print(f"{{{name}(np.{func}(x), x[1] - x[0])[{index}]:.{digits}f}}")  # {note}\n{expected}{more}'
    )


forward = _built_in(
    "forward",
    summary="First derivative by forward differences, O(h).",
    examples=_example("forward", "1.0", 101, "exp", 0, 4, "1.0050", "exact: 1"),
)
backward = _built_in(
    "backward",
    summary="First derivative by backward differences, O(h).",
    examples=_example("backward", "1.0", 101, "exp", -1, 4, "2.7047", "exact: e = 2.7183"),
)
centred = _built_in(
    "centred",
    summary="First derivative by centred differences, O(h**2).",
    examples=_example("centred", "np.pi", 181, "sin", 60, 6, "0.499975", "1 deg steps; exact: cos(60 deg) = 0.5",
                      """

A crank angle that turns once over a full periodic sweep:

>>> theta = np.linspace(0.0, 2 * np.pi, 360, endpoint=False)
>>> rate = centred(theta, theta[1], periodic=True, period_offset=2 * np.pi)
>>> print(np.allclose(rate, 1.0))
True"""),
)
five_point = _built_in(
    "five_point",
    summary="First derivative by the five-point centred stencil, O(h**4).",
    examples=_example("five_point", "np.pi", 181, "sin", 60, 9, "0.499999998", "exact: 0.5"),
)
second_difference = _built_in(
    "second_difference",
    summary="Second derivative by the centred second difference, O(h**2).",
    examples=_example("second_difference", "np.pi", 181, "sin", 90, 6, "-0.999975", "exact: -sin(90 deg) = -1"),
)
forward_of_forward = _built_in(
    "forward_of_forward",
    summary="Second derivative as the forward difference of the forward difference, O(h).",
    body="""``(y[i+2] - 2y[i+1] + y[i]) / h**2``, which is what applying
:func:`forward` twice gives (on a periodic grid exactly
``forward(forward(y))``).  The stencil is centred on sample i+1: it
estimates ``y''`` at ``x[i+1]`` to O(h**2), so as an estimate of
``y''[i]`` it is shifted by one sample and only O(h), with error
``h y'''``.""",
    notes="""On an open grid the last two samples have no ``y[i+2]`` and use the
mirror image (backward of backward, also O(h)); applying :func:`forward`
twice literally would give 0 there.""",
    examples=_example("forward_of_forward", "np.pi", 181, "sin", 89, 6, "-0.999975",
                      "estimates y'' at x[90]: exact -1"),
)
centred_of_centred = _built_in(
    "centred_of_centred",
    summary="Second derivative as the centred difference of the centred difference, O(h**2).",
    body="""``(y[i+2] - 2y[i] + y[i-2]) / (4h**2)``, which is what applying
:func:`centred` twice gives (on a periodic grid exactly
``centred(centred(y))``): a second difference over a 2h-wide stencil,
with truncation error ``h**2/3 y''''``, four times that of
:func:`second_difference`.""",
    notes="""Applying :func:`centred` twice on an open grid is only O(h) at the two
samples of each end (the one-sided first derivatives there have a different
error constant); those samples use second-order stencils instead.""",
    examples=_example("centred_of_centred", "np.pi", 181, "sin", 90, 6, "-0.999898", "exact: -1"),
)
five_point_second = _built_in(
    "five_point_second",
    summary="Second derivative by the five-point centred stencil, O(h**4).",
    examples=_example("five_point_second", "np.pi", 181, "sin", 90, 8, "-1.00000000", "exact: -1"),
)


# --------------------------------------------------------------------------
# Richardson extrapolation
# --------------------------------------------------------------------------

_CENTRED_H = _st.Stencil.from_offsets((-1, 1), 1)
_CENTRED_2H = _st.Stencil((-2, 2), tuple(w / 2 for w in _CENTRED_H.weights), 1, 2, 4 * _CENTRED_H.error_constant)


def richardson(y: ArrayLike, h: float, periodic: bool = False, period_offset: ArrayLike = 0.0) -> FloatArray:
    samples, step, offset = _st.validated("richardson", y, h, periodic, period_offset, 5)
    if periodic:
        d_h = _st.periodic_sum(samples, _CENTRED_H, offset)
        d_2h = _st.periodic_sum(samples, _CENTRED_2H, offset)
        return (4.0 * d_h - d_2h) / (3.0 * step)
    d_h = _st.interior_sum(samples, _CENTRED_H)[..., 1:-1]
    d_2h = _st.interior_sum(samples, _CENTRED_2H)
    out = np.empty_like(samples)
    out[..., 2:-2] = (4.0 * d_h - d_2h) / 3.0
    _st.fill_ends(out, samples, get_scheme("five_point").rule)
    return out / step


_document(
    richardson,
    1,
    summary="First derivative by Richardson extrapolation of centred differences, O(h**4).",
    body="""With ``D(h) = (y[i+1] - y[i-1]) / (2h)`` and
``D(2h) = (y[i+2] - y[i-2]) / (4h)``, both with error ``c h**2 + O(h**4)``
for the same c, the combination ``(4 D(h) - D(2h)) / 3`` cancels the
``h**2`` term.""",
    notes="""Expanded, ``(4 D(h) - D(2h)) / 3`` is exactly the five-point stencil
``(-y[i+2] + 8y[i+1] - 8y[i-1] + y[i-2]) / (12h)`` (:func:`five_point`; the
two agree to rounding).  On an open grid ``D(2h)`` is unavailable at the two
samples of each end, which use the fourth-order one-sided stencils of
:func:`five_point`.""",
    samples="at least 5 samples",
    examples=_example("richardson", "np.pi", 181, "sin", 60, 9, "0.499999998", "exact: 0.5"),
)


# --------------------------------------------------------------------------
# Spectral (FFT) schemes
# --------------------------------------------------------------------------


def _spectral(name: str, y, h, periodic, period_offset, power: int) -> FloatArray:
    """``irfft((ik)**power * rfft(y - trend))``, plus the trend's slope for the first derivative."""
    _require_periodic(name, periodic)
    samples, step, offset = _st.validated(name, y, h, periodic, period_offset, 2)
    count = samples.shape[-1]
    trend = offset * (np.arange(count) / count)
    wavenumbers = 2.0 * np.pi * np.fft.rfftfreq(count, d=step)
    if power == 1:
        factor = 1j * wavenumbers
        if count % 2 == 0:
            factor[-1] = 0.0
    else:
        factor = -(wavenumbers**2)
    out = np.fft.irfft(factor * np.fft.rfft(samples - trend, axis=-1), n=count, axis=-1)
    return out + offset / (count * step) if power == 1 else out


def spectral(y: ArrayLike, h: float, periodic: bool = True, period_offset: ArrayLike = 0.0) -> FloatArray:
    return _spectral("spectral", y, h, periodic, period_offset, 1)


def spectral_second(y: ArrayLike, h: float, periodic: bool = True, period_offset: ArrayLike = 0.0) -> FloatArray:
    return _spectral("spectral_second", y, h, periodic, period_offset, 2)


_SPECTRAL_NOTE = """The N samples cover exactly one period.  The linear trend
``period_offset * i / N`` (sample N equals ``y[0] + period_offset``) is
removed before the transform"""
_document(
    spectral,
    1,
    spectral=True,
    samples="at least 2 samples",
    summary="First derivative by FFT (spectral) differentiation of one full period.",
    body="""Each Fourier mode ``exp(i k x)`` is multiplied by ``i k``.  For
band-limited data (a trigonometric polynomial of degree below N/2) the
result is exact to rounding; for smooth periodic data the error falls
faster than any power of h.""",
    notes=_SPECTRAL_NOTE + """ and its slope ``period_offset / (N*h)`` added back.
For even N the Nyquist mode ``cos(pi x / h)`` is sampled as ``(-1)**i``;
its derivative vanishes at every sample, so that mode is set to zero.""",
    examples=""">>> import numpy as np
>>> from numkin.derivatives import spectral
>>> x = np.linspace(0.0, 2 * np.pi, 64, endpoint=False)
>>> error = spectral(np.exp(np.sin(x)), x[1]) - np.cos(x) * np.exp(np.sin(x))
>>> print(np.max(np.abs(error)) < 1e-12)
True""",
)
_document(
    spectral_second,
    2,
    spectral=True,
    samples="at least 2 samples",
    summary="Second derivative by FFT (spectral) differentiation of one full period.",
    body="""Each Fourier mode ``exp(i k x)`` is multiplied by ``-k**2``.  For
band-limited data the result is exact to rounding.""",
    notes=_SPECTRAL_NOTE + """; it has no second derivative.  For even N the
Nyquist mode ``(-1)**i`` is kept: it is real, and its second derivative
``-(pi/h)**2 (-1)**i`` is consistent with the samples.""",
    examples=""">>> import numpy as np
>>> from numkin.derivatives import spectral_second
>>> x = np.linspace(0.0, 2 * np.pi, 32, endpoint=False)
>>> d2y = spectral_second(np.sin(3 * x), x[1])
>>> print(np.allclose(d2y, -9 * np.sin(3 * x)))
True""",
)


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
    step = _st.check_step(h)
    points = np.asarray(x, dtype=float)
    values = np.asarray(f(points + 1j * step))
    if not np.iscomplexobj(values):
        raise TypeError(
            "f returned real values for a complex argument; complex_step needs a "
            "function that propagates complex numbers"
        )
    derivative = values.imag / step
    return float(derivative) if derivative.ndim == 0 else derivative


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

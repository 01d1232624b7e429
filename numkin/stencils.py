"""Finite-difference stencils: exact weights from offsets, and their application to samples.

A stencil estimates the n-th derivative at sample i from samples at offsets
``k`` (integers, in steps h)::

    y^(n)[i] ~ sum_k w_k y[i + k] / h**n

The weights come from the Taylor expansion ``y[i + k] = sum_m k**m h**m
y^(m) / m!``: requiring ``sum_k w_k k**m / m! = [m == n]`` for ``m < len(k)``
is a Vandermonde system, solved here exactly in rational arithmetic
(:class:`fractions.Fraction`), so the weights are the textbook fractions.
The order of accuracy p is derived, not declared: the first ``m > n`` with
``c_m = sum_k w_k k**m / m! != 0`` gives ``p = m - n`` and the leading
truncation error ``c_m h**p y^(m)``.

A :class:`Rule` adds the stencils used at the ends of an open grid, where
the interior stencil would reach outside the data.

Examples
--------
>>> from numkin.stencils import Stencil
>>> s = Stencil.from_offsets((-1, 0, 1), 1)
>>> s.weights, s.order, s.error_constant
((Fraction(-1, 2), Fraction(1, 2)), 2, Fraction(1, 6))
>>> s.formula()
'(y[i+1] - y[i-1])/(2h)'
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property, lru_cache, reduce

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import InputError

__all__ = ["Stencil", "Rule", "weights", "apply_rule", "check_step", "validated"]

FloatArray = NDArray[np.float64]


def weights(offsets, derivative: int) -> tuple[Fraction, ...]:
    """Exact weights ``w_k`` of the `derivative`-th derivative on integer `offsets`.

    Solves ``sum_k w_k k**m / m! = [m == derivative]`` for ``m = 0 .. len(offsets) - 1``
    by Gauss-Jordan elimination in :class:`fractions.Fraction`.

    Raises
    ------
    ValueError
        For repeated or non-integer offsets, or too few of them for the derivative.

    Examples
    --------
    >>> [str(w) for w in weights((-2, -1, 0, 1, 2), 2)]
    ['-1/12', '4/3', '-5/2', '4/3', '-1/12']
    """
    ks = _offsets(offsets)
    n = len(ks)
    if isinstance(derivative, bool) or not isinstance(derivative, numbers.Integral) or derivative < 1:
        raise InputError(f"derivative must be a positive integer, got {derivative!r}")
    if n <= derivative:
        raise InputError(f"a derivative of order {derivative} needs at least {derivative + 1} offsets, got {ks}")
    rows = [[Fraction(k) ** m / math.factorial(m) for k in ks] + [Fraction(int(m == derivative))] for m in range(n)]
    for col in range(n):
        pivot = next(r for r in range(col, n) if rows[r][col] != 0)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        p = rows[col][col]
        rows[col] = [v / p for v in rows[col]]
        for r in range(n):
            if r != col and rows[r][col] != 0:
                f = rows[r][col]
                rows[r] = [a - f * b for a, b in zip(rows[r], rows[col])]
    return tuple(row[-1] for row in rows)


def _offsets(offsets) -> tuple[int, ...]:
    try:
        ks = tuple(int(k) for k in offsets)
    except (TypeError, ValueError):
        raise InputError(f"offsets must be integers (steps h), got {offsets!r}") from None
    if any(k != o for k, o in zip(ks, offsets)) or len(set(ks)) != len(ks):
        raise InputError(f"offsets must be distinct integers, got {tuple(offsets)!r}")
    return ks


def _moments(ks, ws, derivative):
    """(order p, leading error constant) of a stencil."""
    for m in range(derivative + 1, derivative + len(ks) + 3):
        c = sum((w * Fraction(k) ** m for k, w in zip(ks, ws)), Fraction(0)) / math.factorial(m)
        if c != 0:
            return m - derivative, c
    raise InputError("stencil is exact for every polynomial it can see: no truncation error found")


@dataclass(frozen=True)
class Stencil:
    """``sum(weights[j] * y[i + offsets[j]]) / h**derivative`` at sample i.

    Build one with ``Stencil.from_offsets``; offsets whose weight is zero are dropped.

    Attributes
    ----------
    offsets : tuple of int
    weights : tuple of Fraction
    derivative : int
    order : int
        Order p of the truncation error ``error_constant * h**p * y^(p + derivative)``.
    error_constant : Fraction
    """

    offsets: tuple[int, ...]
    weights: tuple[Fraction, ...]
    derivative: int
    order: int
    error_constant: Fraction

    @classmethod
    def from_offsets(cls, offsets, derivative: int) -> "Stencil":
        """The stencil on integer ``offsets`` (weights solved exactly; solved once per offsets and derivative)."""
        ks = _offsets(offsets)
        if isinstance(derivative, bool) or not isinstance(derivative, numbers.Integral):
            return cls._solve(ks, derivative)
        if cls is Stencil:
            return _solved(ks, int(derivative))
        return cls._solve(ks, derivative)

    @classmethod
    def _solve(cls, ks, derivative) -> "Stencil":
        ws = weights(ks, derivative)
        p, c = _moments(ks, ws, derivative)
        keep = [(k, w) for k, w in sorted(zip(ks, ws)) if w != 0]
        return cls(tuple(k for k, _ in keep), tuple(w for _, w in keep), int(derivative), p, c)

    @cached_property
    def coefficients(self) -> tuple[float, ...]:
        """The weights as floats."""
        return tuple(float(w) for w in self.weights)

    @cached_property
    def numerators(self) -> tuple[float, ...]:
        """The weights times :attr:`denominator` (integers, as floats)."""
        d = self.denominator
        return tuple(float(w * d) for w in self.weights)

    @cached_property
    def width(self) -> int:
        return max(self.offsets) - min(self.offsets) + 1

    @cached_property
    def denominator(self) -> int:
        """Least common denominator of the weights (12 for the five-point stencils)."""
        return reduce(math.lcm, (w.denominator for w in self.weights), 1)

    def mirrored(self) -> "Stencil":
        """The stencil reflected about sample i."""
        return Stencil.from_offsets(tuple(-k for k in self.offsets), self.derivative)

    def formula(self, at: int | None = None, end: str = "left") -> str:
        """The stencil as text: ``(y[i+1] - y[i-1])/(2h)``; at sample `at` of the `end` given."""
        d = self.denominator
        terms = []
        for k, w in sorted(zip(self.offsets, self.weights), reverse=at is None or end != "left"):
            a = int(w * d)
            if at is None:
                idx = "i" if k == 0 else f"i{k:+d}"
            elif end == "left":
                idx = str(at + k)
            else:
                j = at - k
                idx = "N-1" if j == 0 else f"N-{1 + j}"
            mag = "" if abs(a) == 1 else str(abs(a))
            sign = "-" if a < 0 else "+"
            terms.append((sign, f"{mag}y[{idx}]"))
        text = ("-" if terms[0][0] == "-" else "") + terms[0][1]
        text += "".join(f" {s} {t}" for s, t in terms[1:])
        hh = "h" if self.derivative == 1 else f"h^{self.derivative}"
        return f"({text})/{hh}" if d == 1 else f"({text})/({d}{hh})"

    def apply(self, values: ArrayLike, h: float) -> FloatArray:
        """The estimate from `values` at the offsets (last axis, in ``offsets`` order)."""
        v = np.asarray(values, dtype=float)
        return np.tensordot(v, np.array(self.coefficients), axes=([-1], [0])) / check_step(h) ** self.derivative


@lru_cache(maxsize=256)
def _solved(ks: tuple, derivative: int) -> Stencil:
    """:meth:`Stencil.from_offsets`, solved once per offsets and derivative (stencils are immutable)."""
    return Stencil._solve(ks, derivative)


def _one_sided(derivative: int, order: int, first: int, step: int) -> Stencil:
    """Smallest window ``first, first + step, ...`` (contiguous) of at least `order`."""
    m = derivative + 1
    while True:
        s = Stencil.from_offsets(tuple(first + step * j for j in range(m)), derivative)
        if s.order >= order:
            return s
        m += 1


@dataclass(frozen=True)
class Rule:
    """Interior stencil plus the stencils at the ends of an open grid.

    ``left[j]`` is used at sample ``j`` and ``right[j]`` at sample ``N-1-j``.
    ``ends="one-sided"``: the smallest one-sided window of at least the
    interior's order; ``ends="mirror"``: the interior stencil reflected
    (backward of backward at the right end of forward_of_forward).
    """

    interior: Stencil
    ends: str = "one-sided"
    left: tuple[Stencil, ...] = ()
    right: tuple[Stencil, ...] = ()

    @classmethod
    def build(cls, interior: Stencil, ends: str = "one-sided") -> "Rule":
        lo, hi = -min(interior.offsets, default=0), max(interior.offsets, default=0)
        lo, hi = max(lo, 0), max(hi, 0)
        d, p = interior.derivative, interior.order
        if ends == "one-sided":
            left = tuple(_one_sided(d, p, -j, 1) for j in range(lo))
            right = tuple(_one_sided(d, p, j, -1) for j in range(hi))
        elif ends == "mirror":
            m = interior.mirrored()
            if (lo and min(m.offsets) < 0) or (hi and max(m.offsets) > 0):
                raise InputError(f"ends='mirror' needs a one-sided stencil, got offsets {interior.offsets}")
            left, right = (m,) * lo, (m,) * hi
        else:
            raise InputError(f"ends must be 'one-sided' or 'mirror', got {ends!r}")
        return cls(interior, ends, left, right)

    @property
    def derivative(self) -> int:
        return self.interior.derivative

    @property
    def order(self) -> int:
        """Order on an open grid, ends included."""
        return min(s.order for s in (self.interior, *self.left, *self.right))

    def min_samples(self, periodic: bool) -> int:
        """Fewest samples the rule differentiates: on an open grid, every end stencil must fit inside
        the data from its own sample (the j-th from the right reaches ``j - min(offsets)`` back).

        Examples
        --------
        >>> rule = Rule.build(Stencil.from_offsets((0, 1, 2), 2), "mirror")   # forward of forward
        >>> rule.min_samples(periodic=False), rule.min_samples(periodic=True)
        (4, 3)
        """
        if periodic:
            return self.interior.width
        need = max(self.interior.width, len(self.left) + len(self.right))
        need = max([need] + [j + max(s.offsets) + 1 for j, s in enumerate(self.left)])
        return max([need] + [j - min(s.offsets) + 1 for j, s in enumerate(self.right)])

    def end_formulas(self) -> list[str]:
        """One line per end sample: ``y'[0] ~ (...)``."""
        tick = "'" * self.derivative
        out = [f"``y{tick}[{j}] ~ {s.formula(j)}``" for j, s in enumerate(self.left)]
        out += [f"``y{tick}[N-{1 + j}] ~ {s.formula(j, 'right')}``" for j, s in reversed(list(enumerate(self.right)))]
        return out


# --------------------------------------------------------------------------- validation
def check_step(h) -> float:
    """`h` as a float, or a ValueError if it is not finite and positive (a 0-d array is its number)."""
    if isinstance(h, np.ndarray) and h.ndim == 0 and h.dtype.kind in "iuf":
        h = h.item()
    if isinstance(h, bool) or not isinstance(h, numbers.Real) or not (math.isfinite(h) and h > 0):
        raise InputError(f"h must be a finite positive number, got {h!r}")
    return float(h)


def _check_samples(y: ArrayLike, scheme: str, minimum: int, periodic: bool) -> FloatArray:
    if np.iscomplexobj(y):
        raise InputError("y must be real samples, got complex values (the complex step differentiates a function: "
                         "numkin.derivatives.complex_step)")
    try:
        samples = np.asarray(y, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"y must be an array of numbers (samples), got {y!r:.80}") from None
    if samples.ndim == 0:
        raise InputError(f"y must be an array of samples, got the scalar {samples.item()!r}")
    if samples.shape[-1] < minimum:
        grid = "a periodic" if periodic else "an open"
        error = InputError(f"scheme {scheme!r} needs at least {minimum} samples along the last axis "
                           f"on {grid} grid, got {samples.shape[-1]}", cause="too few samples")
        error.minimum, error.grid = minimum, grid
        raise error
    bad = ~np.isfinite(samples)
    if bad.any():
        first = tuple(int(i) for i in np.argwhere(bad)[0])
        index = first[0] if samples.ndim == 1 else first
        raise InputError(f"y contains {samples[first]} at index {index}")
    return samples


def _check_offset(period_offset: ArrayLike, periodic: bool, samples: FloatArray) -> FloatArray:
    offset = np.asarray(period_offset, dtype=float)
    if not np.all(np.isfinite(offset)):
        raise InputError(f"period_offset must be finite, got {period_offset!r}")
    if not periodic and np.any(offset != 0):
        raise InputError("period_offset only applies to periodic grids (periodic=True)")
    try:
        offset = np.broadcast_to(offset, samples.shape[:-1])
    except ValueError:
        raise InputError(
            f"period_offset must be a float or have shape {samples.shape[:-1]} "
            f"(one offset per row of y), got shape {offset.shape}"
        ) from None
    return offset[..., np.newaxis]


def validated(scheme: str, y, h, periodic: bool, period_offset, minimum: int):
    """(samples, h, period offset shaped to broadcast along the last axis), or a ValueError."""
    if not isinstance(periodic, (bool, np.bool_)):
        raise InputError(f"periodic must be True or False, got {periodic!r}")
    step = check_step(h)
    samples = _check_samples(y, scheme, minimum, periodic)
    return samples, step, _check_offset(period_offset, periodic, samples)


# --------------------------------------------------------------------------- application
def _wrapped(samples: FloatArray, shift: int, offset: FloatArray) -> FloatArray:
    """``y[i + shift]`` for every i, continuing periodically with ``y[N] = y[0] + offset``."""
    count = samples.shape[-1]
    index = np.arange(count) + shift
    return samples[..., index % count] + offset * (index // count)


def periodic_sum(samples: FloatArray, stencil: Stencil, offset: FloatArray) -> FloatArray:
    """The stencil's weighted sum (without ``1/h**n``) at every sample of a periodic grid."""
    total = np.zeros_like(samples)
    for shift, w in zip(stencil.offsets, stencil.numerators):
        total += w * _wrapped(samples, shift, offset)
    return total / stencil.denominator


def interior_sum(samples: FloatArray, stencil: Stencil) -> FloatArray:
    """The weighted sum at every sample where the stencil fits inside the data (open grid): samples
    ``lo .. N-1-hi`` with ``lo = max(-min(offsets), 0)``, ``hi = max(max(offsets), 0)`` (the window need not
    hold the sample itself: offsets ``(1, 2)`` differentiate at sample i from samples i+1 and i+2)."""
    first = max(-min(stencil.offsets), 0)
    count = samples.shape[-1] - first - max(max(stencil.offsets), 0)
    total = np.zeros(samples.shape[:-1] + (count,))
    for shift, w in zip(stencil.offsets, stencil.numerators):
        total += w * samples[..., first + shift : first + shift + count]
    return total / stencil.denominator


def fill_ends(out: FloatArray, samples: FloatArray, rule: Rule) -> None:
    """Write the end stencils' weighted sums into the first and last samples of `out`."""
    last = samples.shape[-1] - 1
    for j, s in enumerate(rule.left):
        out[..., j] = sum(w * samples[..., j + k] for k, w in zip(s.offsets, s.numerators)) / s.denominator
    for j, s in enumerate(rule.right):
        i = last - j
        out[..., i] = sum(w * samples[..., i + k] for k, w in zip(s.offsets, s.numerators)) / s.denominator


def apply_rule(rule: Rule, scheme: str, y, h, periodic: bool, period_offset) -> FloatArray:
    """Differentiate samples `y` along the last axis with `rule` (validated; `scheme` names it in errors)."""
    samples, step, offset = validated(scheme, y, h, periodic, period_offset, rule.min_samples(periodic))
    scale = step**rule.derivative
    if periodic:
        return periodic_sum(samples, rule.interior, offset) / scale
    lo, hi = len(rule.left), len(rule.right)
    out = np.empty_like(samples)
    out[..., lo : samples.shape[-1] - hi] = interior_sum(samples, rule.interior)
    fill_ends(out, samples, rule)
    return out / scale

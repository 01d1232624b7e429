"""Tick labels of log axes in the axis font: ``10⁻¹²`` written with Unicode superscripts.

matplotlib labels a log axis ``$\\mathdefault{10^{-12}}$``: mathtext, which is
parsed again for every figure, every resolution and every format. The same
labels written with the superscript digits and minus of the tick font
(DejaVu Sans has them) are plain text: they look alike and cost a fraction
of the time. Only the labels' text changes; which ticks are labelled
(decades, and 2×10⁻³ and so on when an axis spans few decades) is
matplotlib's :class:`~matplotlib.ticker.LogFormatterSciNotation`.

Imports matplotlib (the figure functions import this module when they draw).

Examples
--------
>>> from numkin.figures.ticks import power_text
>>> power_text(r"$\\mathdefault{10^{-12}}$"), power_text(r"$\\mathdefault{2\\times10^{-3}}$")
('10⁻¹²', '2×10⁻³')
>>> power_text(r"$\\mathdefault{10^{0}}$"), power_text("")
('10⁰', '')
"""

from __future__ import annotations

import re

from matplotlib.ticker import LogFormatterSciNotation

from .labels import no_negative_zero

__all__ = ["PowerFormatter", "log_axis", "log_scale", "power_text"]

#: Digits and minus sign -> their superscript forms.
SUPERSCRIPT = str.maketrans("0123456789-−", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁻")

_MATH = re.compile(r"\$\\mathdefault\{(.*)\}\$")
_POWER = re.compile(r"(-?)(?:([0-9.]+)\\times)?(\d+)\^\{(-?\d+)\}")
_NUMBER = re.compile(r"-?[0-9.]+")


def power_text(label: str) -> str:
    """A label of :class:`~matplotlib.ticker.LogFormatterSciNotation` without mathtext.

    ``b^{k}`` and ``c\\times b^{k}`` become ``bᵏ`` and ``c×bᵏ`` (superscript
    digits, a true minus); a plain number stays a number; any other text
    (which this formatter does not write) is returned unchanged.
    """
    m = _MATH.fullmatch(label)
    if not m:
        return label
    body = m.group(1)
    power = _POWER.fullmatch(body)
    if power:
        sign, coeff, base, exponent = power.groups()
        return ("−" if sign else "") + (f"{coeff}×" if coeff else "") + base + exponent.translate(SUPERSCRIPT)
    if _NUMBER.fullmatch(body):
        return no_negative_zero(body)
    return label


class PowerFormatter(LogFormatterSciNotation):
    """:class:`~matplotlib.ticker.LogFormatterSciNotation` writing ``10⁻¹²`` in the tick font.

    Examples
    --------
    >>> PowerFormatter(10)(1e-12), PowerFormatter(10)(1.0), PowerFormatter(10)(1e3)
    ('10⁻¹²', '10⁰', '10³')
    """

    def __call__(self, x, pos=None):
        return power_text(super().__call__(x, pos))


def log_axis(axis) -> None:
    """Label a log-scaled axis (major and minor ticks) with :class:`PowerFormatter`.

    The formatters that the log scale set keep their settings (which ticks
    they label); formatters set by hand are left alone.
    """
    base = getattr(axis.get_transform(), "base", 10.0)
    for get, put in ((axis.get_major_formatter, axis.set_major_formatter),
                     (axis.get_minor_formatter, axis.set_minor_formatter)):
        old = get()
        if type(old) is LogFormatterSciNotation:
            put(PowerFormatter(base, labelOnlyBase=old.labelOnlyBase, minor_thresholds=old.minor_thresholds))


def log_scale(ax, which: str = "xy") -> None:
    """Log scale on the axes `which` (``"x"``, ``"y"`` or ``"xy"``) of `ax`, labelled by :func:`log_axis`.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> ax = Figure().subplots()
    >>> log_scale(ax, "y")
    >>> ax.get_yscale(), type(ax.yaxis.get_major_formatter()).__name__
    ('log', 'PowerFormatter')
    """
    for name in which:
        getattr(ax, f"set_{name}scale")("log")
        log_axis(getattr(ax, f"{name}axis"))

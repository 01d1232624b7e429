"""The words of the error tables: captions, the views a wide table is read in, relative errors and their
denominators, angles and orders as the captions write them.

Every table of :mod:`numkin.report` keeps its caption in ``attrs["caption"]``
(:func:`set_caption`) and the groups of columns it is read in, in
``attrs["views"]`` (:func:`set_views`); a relative error names its
denominator (:func:`relative_text`: the largest ``|exact value|`` over the
sweep, :data:`PEAK`, or the ``|exact value|`` at one angle, :func:`at_angle`).

Examples
--------
>>> relative(0.5, [1.0, -2.0]), order_text(type("S", (), {"order": 0})())
(0.25, 'spectral')
"""

from __future__ import annotations

import math
from typing import Mapping, Sequence

import numpy as np

__all__ = ["UNIT", "VARIES", "PEAK", "deg_text", "order_text", "set_caption", "set_views", "relative", "at_angle",
           "relative_text", "zero_text"]

#: Column names of absolute errors say this unit.
UNIT = "[unit of quantity]"


#: Column names of timings (and of what is chosen by them) say this: they vary between runs.
VARIES = "(varies)"


def deg_text(angle: float) -> str:
    """An angle (rad) in degrees, to 6 significant figures, without the unit: a caption's number.

    >>> deg_text(1.0)
    '57.2958'
    """
    return f"{math.degrees(angle):.6g}"


def order_text(scheme) -> str:
    """A scheme's order of accuracy in words: its number, or ``"spectral"`` (order 0 in the registry)."""
    return "spectral" if scheme.order == 0 else str(scheme.order)


def set_caption(df, text: str, positions: Sequence[dict] | None = None):
    """Set a table's caption and, if given, the positions it was computed at (``attrs["positions"]``)."""
    df.attrs["caption"] = text
    if positions is not None:
        df.attrs["positions"] = list(positions)
    return df


def set_views(df, views: Sequence, row_keys: Sequence | None = None) -> object:
    """Say how a wide table is read: ``attrs["views"]``, a list of ``[title, [columns]]``.

    Each view is one idea of the table, a few columns wide, and becomes a
    table of its own in Markdown, LaTeX and on the terminal
    (:mod:`~numkin.report.writers`; columns no view names make a last
    part); CSV keeps every column in one table. Columns not in `df` are
    dropped from a view; a view left with nothing but the columns that name
    a row (a table of run times, not timed) is left out. `row_keys`
    (``attrs["row_keys"]``) are the columns that name a row; the terminal
    repeats them in each part of a view too wide for one screen.
    """
    keys = [str(c) for c in (row_keys or ()) if c in df.columns]
    if row_keys is not None:
        df.attrs["row_keys"] = keys
    out = []
    for title, cols in views:
        cols = [c for c in cols if c in df.columns]
        if any(str(c) not in keys for c in cols):
            out.append([str(title), list(cols)])
    df.attrs["views"] = out
    return df


def relative(error: float, exact) -> float:
    """``error / max|exact|``; NaN where the exact values are all 0 (a relative error is undefined there).

    The exact derivative of a quantity linear in the input (``r2*theta2``) is 0 to the last bit: the
    chain rule of :mod:`numkin.expressions` gives it so; then say so in the caption (:func:`zero_text`).

    Examples
    --------
    >>> relative(0.5, [1.0, -2.0]), relative(0.5, [0.0, 0.0])
    (0.25, nan)
    """
    peak = float(np.max(np.abs(np.asarray(exact, dtype=float))))
    return error / peak if peak > 0 else math.nan


#: Denominator of a relative error taken over the sweep (:func:`relative`), as :func:`relative_text` names it.
PEAK = "the largest |exact value| over the sweep"


def at_angle(where: str) -> str:
    """Denominator of a relative error taken at one input angle, ``"theta = 100 deg"``, for :func:`relative_text`."""
    return f"|exact value| at {where}"


def relative_text(columns: Mapping[str, str]) -> str:
    """A caption's sentence naming the denominator of each relative-error column.

    Parameters
    ----------
    columns : mapping
        Column (or its name as the caption calls it) -> denominator
        (:data:`PEAK`, :func:`at_angle` or a phrase of the same kind).
        Columns of one denominator are named together, in the given order.

    Returns
    -------
    str
        A sentence with a leading space, to append to a caption ("" for no column).

    Examples
    --------
    >>> relative_text({"max rel error [-]": PEAK})
    ' Relative errors: max rel error [-] is divided by the largest |exact value| over the sweep.'
    >>> text = relative_text({"max rel error": PEAK, "rel error at 5 deg": at_angle("5 deg")})
    >>> print(text.strip())  # doctest: +NORMALIZE_WHITESPACE
    Relative errors: max rel error is divided by the largest |exact value| over the sweep; rel error at 5 deg by
    |exact value| at 5 deg.
    """
    groups: dict = {}
    for column, denominator in columns.items():
        groups.setdefault(denominator, []).append(str(column))
    parts = []
    for k, (denominator, names) in enumerate(groups.items()):
        verb = ("is" if len(names) == 1 else "are") + " divided by" if k == 0 else "by"
        listed = names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"
        parts.append(f"{listed} {verb} {denominator}")
    return " Relative errors: " + "; ".join(parts) + "." if parts else ""


def zero_text(names) -> str:
    """A caption's sentence on the quantities whose exact value is 0 over the whole sweep (relative errors blank)."""
    if not names:
        return ""
    return (f" The exact {' and '.join(sorted(names))} is 0 over the whole sweep: its relative error is undefined and "
            "left blank (its absolute errors stand).")

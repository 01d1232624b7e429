"""Titles that fit their figure: broken into lines, or set smaller, where the layout put them.

matplotlib's constrained layout leaves the width of a title out of the
margins it makes (``for_layout_only``): a title wider than its axes is
centred over them all the same, and runs off the figure when the axes sit
off-centre (legends beside them) or when the title is wider than the
figure. :func:`fit_titles` measures each title where the layout put it,
with the renderer the figure is saved with, and one that reaches past the
figure's edge (less :data:`MARGIN` points) is broken into lines: first
at ``": "`` (each part a line of its own, the colon dropped, as
``"head: title"`` becomes ``"head"`` over ``"title"``), then after commas
and before an opening parenthesis, then at any space, never inside
``$...$`` mathtext. A word that still does not fit is set in a smaller
font. :func:`numkin.figures.save` lays a figure out again when a title
changed, so that its new height is made room for.

Examples
--------
>>> from numkin.figures.fitting import wrap_lines
>>> wrap_lines("four-bar (ground 20 mm, crank 50 mm): $\\\\theta_{4}$, velocity", lambda s: len(s) <= 24)
['four-bar (ground 20 mm,', 'crank 50 mm)', '$\\\\theta_{4}$, velocity']
"""

from __future__ import annotations

import math
from typing import Callable

__all__ = ["MARGIN", "fit_text", "fit_titles", "titles", "wrap_lines"]

#: Space kept between a title and the figure's edge, in points.
MARGIN = 3.0

#: Smallest step (points) by which a title's font is made smaller when a word does not fit.
_FONT_STEP = 0.1


def _breaks(line: str, level: int) -> list[str]:
    """`line` split at its spaces outside ``$...$`` that break at `level`.

    Level 0: a space after ``":"``; level 1: a space after ``","`` or before
    ``"("``; level 2: any space. The spaces themselves are dropped.
    """
    pieces, start, math_mode = [], 0, False
    for i, ch in enumerate(line):
        if ch == "$" and (i == 0 or line[i - 1] != "\\"):
            math_mode = not math_mode
        if ch != " " or math_mode or i == 0:
            continue
        before, after = line[i - 1], line[i + 1:i + 2]
        if level == 0:
            cut = before == ":"
        elif level == 1:
            cut = before == "," or after == "("
        else:
            cut = True
        if cut:
            pieces.append(line[start:i])
            start = i + 1
    pieces.append(line[start:])
    return [p for p in pieces if p]


def _wrap(line: str, fits: Callable[[str], bool], level: int) -> list[str]:
    if level > 2 or fits(line):
        return [line]
    pieces = _breaks(line, level)
    if len(pieces) == 1:
        return _wrap(line, fits, level + 1)
    if level == 0:  # every part of "head: title" on a line of its own, the colon dropped
        out = []
        for k, piece in enumerate(pieces):
            out += _wrap(piece[:-1] if k < len(pieces) - 1 else piece, fits, 1)
        return out
    lines: list[str] = []
    current = None
    for piece in pieces:
        trial = piece if current is None else f"{current} {piece}"
        if fits(trial):
            current = trial
            continue
        if current is not None:
            lines.append(current)
        sub = _wrap(piece, fits, level + 1)
        lines += sub[:-1]
        current = sub[-1]
    lines.append(current)
    return lines


def wrap_lines(text: str, fits: Callable[[str], bool]) -> list[str]:
    """The lines `text` is broken into so that each line `fits` (as far as its words allow).

    Parameters
    ----------
    text : str
        Lines already broken (``"\\n"``) are kept and broken further.
    fits : callable
        ``fits(line) -> bool``: whether one line fits.

    Returns
    -------
    list of str
        ``text`` itself, as its only line, when every line of it fits.

    Examples
    --------
    >>> wrap_lines("Newton: residual per iteration", lambda s: len(s) <= 20)
    ['Newton', 'residual per', 'iteration']
    >>> wrap_lines("short: enough", lambda s: True)
    ['short: enough']
    """
    out = []
    for line in text.split("\n"):
        out += _wrap(line, fits, 0)
    return out


def _room(text, renderer, fig_box, margin: float) -> tuple[float, float]:
    """Width (pixels) the text's line may take, and its current width, where its alignment anchors it."""
    box = text.get_window_extent(renderer)
    lo, hi = fig_box.x0 + margin, fig_box.x1 - margin
    align = text.get_horizontalalignment()
    if align == "left":
        room = hi - box.x0
    elif align == "right":
        room = box.x1 - lo
    else:
        centre = 0.5 * (box.x0 + box.x1)
        room = 2.0 * min(centre - lo, hi - centre)
    return room, box.width


def fit_text(text, renderer, room: float, top: float | None = None) -> bool:
    """Break `text` into lines, then set it smaller, until it is at most `room` pixels wide.

    Parameters
    ----------
    text : matplotlib.text.Text
    renderer
        The renderer the figure is drawn with (its dpi sets the pixels).
    room : float
        Width allowed, in pixels.
    top : float, optional
        Height (pixels) the text's top may not pass: a text broken into
        lines that would reach above it is kept on its line and set smaller.
        None: no limit (the layout makes room for the lines).

    Returns
    -------
    bool
        Whether the text changed.
    """
    original = text.get_text()

    def width(s: str) -> float:
        text.set_text(s)
        return text.get_window_extent(renderer).width

    if width(original) <= room:
        return False
    joined = "\n".join(wrap_lines(original, lambda s: width(s) <= room))
    now = width(joined)
    if top is not None and text.get_window_extent(renderer).y1 > top:
        now = width(original)
    if now > room:
        # never below two pixels a character (a font of less than a pixel is refused by FreeType)
        size = text.get_fontsize()
        smallest = min(size, max(_FONT_STEP, math.ceil(2.0 * 72.0 / renderer.dpi / _FONT_STEP) * _FONT_STEP))
        size = max(smallest, math.floor(size * room / now / _FONT_STEP) * _FONT_STEP)
        while True:
            text.set_fontsize(round(size, 1))
            if size - _FONT_STEP < smallest or text.get_window_extent(renderer).width <= room:
                break
            size -= _FONT_STEP
    return True


def titles(fig) -> list:
    """The figure's title and its axes' titles (centre, left and right) that are shown and not empty."""
    found = [getattr(fig, "_suptitle", None)]
    for ax in fig.axes:
        found += [ax.title, getattr(ax, "_left_title", None), getattr(ax, "_right_title", None)]
    return [t for t in found if t is not None and t.get_visible() and t.get_text()]


def fit_titles(fig, renderer=None, relayout: bool = True) -> bool:
    """Break into lines, or set smaller, every title of `fig` that reaches past the figure's edge.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Laid out: the titles are measured where they are.
    renderer : optional
        Default the figure canvas's, at the figure's dpi.
    relayout : bool
        Whether the figure is laid out again after (its layout engine
        makes room for a title of more lines). If not (axes that stay
        where they are), a title is broken into lines only as far as it
        stays inside the figure's top, else set smaller.

    Returns
    -------
    bool
        Whether a title changed (the figure should be laid out again).

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from matplotlib.backends.backend_agg import FigureCanvasAgg
    >>> fig = Figure(figsize=(3, 2))
    >>> _ = FigureCanvasAgg(fig)
    >>> _ = fig.subplots().set_title("a title far too long for three inches: it is broken into lines")
    >>> fit_titles(fig), fig.axes[0].get_title().count("\\n") > 0
    (True, True)
    """
    renderer = renderer or fig.canvas.get_renderer()
    margin = MARGIN * fig.dpi / 72.0
    top = None if relayout else fig.bbox.y1 - margin
    changed = False
    for text in titles(fig):
        room, now = _room(text, renderer, fig.bbox, margin)
        if now > room:
            changed = fit_text(text, renderer, max(room, 1.0), top) or changed
    return changed

"""Animated GIF of a mechanism over its sweep.

The links are drawn as polylines of the mechanism's named points, the joints
as circles, the ground pivots hatched and the sliders as blocks on their
guides (a fixed line, or the link they slide on), with the input angle
stamped on each frame. Optionally the paths of named points (coupler
curves) are drawn, and velocity or acceleration arrows on the moving points,
on one scale for the whole animation, written under the drawing.

A mechanism whose input can turn fully is animated over a full turn even
when the sweep covers less (``turn="sweep"`` keeps the sweep's own range).

Frames are written with Pillow (:class:`matplotlib.animation.PillowWriter`;
no ffmpeg), with the package style, fixed axis limits (from the whole
animation) and a fixed frame count, so the file is the same bytes each time.
One figure is drawn for all frames and closed at the end.

Examples
--------
>>> import numpy as np
>>> from numkin import linkages
>>> from numkin.animate import animate
>>> sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))
>>> animate(sweep, "/tmp/numkin-doc-quick-return.gif", frames=12).name
'numkin-doc-quick-return.gif'
"""

from __future__ import annotations

import math
import numbers
import warnings
from pathlib import Path

import numpy as np

from .errors import InputError
from .folders import made_folder
from .figures.drawing import (
    arrow_scale, arrow_vectors, block_corners, block_directions, bounds, draw_ground, guided_points, link_colors,
    scale_text, slider_points, tip_offset,
)
from .figures.labels import deg_text, input_name, length_unit, mechanism_title, sym
from .figures.fitting import fit_text, fit_titles
from .figures.style import close, style
from .units import is_full_turn

__all__ = ["animate", "frame_indices", "full_turn", "labels_inside"]

_TURN = 2.0 * math.pi


#: Space kept between the axis labels and the frame's edge, in points.
_EDGE = 3.0


def labels_inside(fig, ax) -> bool:
    """Move the edges of ``ax`` in until its labels are inside ``fig``, and a title too wide for one line has two.

    An animation's axes are placed once, as fractions of the frame, with no
    layout engine (the frames must not jitter); the labels are in points, so
    a narrow frame (``width=3``) would cut the y-label off. The left and
    bottom edges move in until the tick labels and axis labels are inside;
    where the title is wider than the frame, the top edge comes down by a
    line of it, which :func:`numkin.figures.fitting.fit_titles` (called
    next) breaks it into. Measured once, before the first frame: the limits
    are fixed, so the tick labels do not change. Returns whether the axes
    moved (never on frames wide enough).
    """
    renderer = fig.canvas.get_renderer()
    edge = _EDGE * fig.dpi / 72.0
    shown = ax.title.get_visible()
    moved = False
    ax.title.set_visible(False)
    try:
        for _ in range(3):  # (the labels move with the axes: once or twice is enough)
            tight = ax.get_tightbbox(renderer)
            dx = max(0.0, fig.bbox.x0 + edge - tight.x0) / fig.bbox.width
            dy = max(0.0, fig.bbox.y0 + edge - tight.y0) / fig.bbox.height
            if dx <= 0.0 and dy <= 0.0:
                break
            pos = ax.get_position()
            ax.set_position((pos.x0 + dx, pos.y0 + dy, pos.width - dx, pos.height - dy))
            moved = True
    finally:
        ax.title.set_visible(shown)
    if shown and ax.title.get_text() and ax.title.get_window_extent(renderer).width > fig.bbox.width - 2.0 * edge:
        line = 1.2 * ax.title.get_fontsize() * fig.dpi / 72.0 / fig.bbox.height
        pos = ax.get_position()
        ax.set_position((pos.x0, pos.y0, pos.width, pos.height - line))
        moved = True
    fig.draw_without_rendering()  # (the title placed again, over the axes where they are now)
    return moved


def frame_indices(inputs, frames: int) -> np.ndarray:
    """Indices of the sweep's inputs shown in each frame.

    Evenly spaced over the sweep; for a sweep over exactly one turn (last
    input = first ± 2π, the same position) the last input is left out so
    that the animation loops without a repeated frame.

    Parameters
    ----------
    inputs : array_like (N,)
        The sweep's inputs, rad.
    frames : int
        Number of frames, at least 2 and at most the number of distinct inputs.

    Returns
    -------
    ndarray of int, shape (frames,)

    Examples
    --------
    >>> import numpy as np
    >>> frame_indices(np.radians(np.arange(0, 361)), 8).tolist()
    [0, 45, 90, 135, 180, 225, 270, 315]
    >>> frame_indices(np.radians(np.arange(0, 181)), 5).tolist()
    [0, 45, 90, 135, 180]
    """
    t = np.asarray(inputs, dtype=float)
    if isinstance(frames, bool) or not isinstance(frames, numbers.Integral) or frames < 2:
        raise InputError(f"frames must be an integer >= 2, got {frames!r}")
    n = t.size
    full = is_full_turn(t)
    distinct = n - 1 if full else n
    if frames > distinct:
        raise InputError(
            f"frames = {frames} is more than the {distinct} distinct inputs of the sweep; "
            "ask for fewer frames or sweep a finer grid"
        )
    if full:
        return np.floor(np.arange(frames) * distinct / frames + 0.5).astype(int)
    return np.floor(np.linspace(0, n - 1, frames) + 0.5).astype(int)


def full_turn(sweep):
    """The sweep extended to one full turn of the input from its first input, on the same branch.

    The step is the sweep's own (1° if it has no uniform step). Returns the
    sweep itself if it already covers a full turn, and None if the input
    cannot turn fully (the linkage cannot be assembled, or meets a dead
    point, somewhere on the turn).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> half = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    >>> whole = full_turn(half)
    >>> round(float(np.degrees(whole.inputs[-1] - whole.inputs[0])), 9), len(whole)
    (360.0, 361)
    >>> rocker = linkages.four_bar(4, 3, 2, 2).sweep(np.radians(np.arange(0, 11)))
    >>> full_turn(rocker) is None   # crank 3, ground 4, coupler and rocker 2: no full turn
    True
    """
    from .errors import NumkinError

    t = np.asarray(sweep.inputs, dtype=float)
    if is_full_turn(t):
        return sweep
    step = abs(sweep.step) if sweep.step else math.radians(1.0)
    n = max(int(round(_TURN / step)), 4)
    direction = -1.0 if t.size > 1 and t[-1] < t[0] else 1.0
    inputs = t[0] + direction * _TURN * np.arange(n + 1) / n
    # a sweep that went through change points (on_singular="report") goes through them again
    through = "report" if any(e.kind == "change point" for e in getattr(sweep, "events", ())) else "raise"
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the sweep's own warnings were said already
            turned = sweep.mechanism.sweep(inputs, guess=np.asarray(sweep.values[:, 0], dtype=float),
                                           on_singular=through)
    except (NumkinError, ValueError, ArithmeticError):
        return None
    values = np.asarray(turned.values, dtype=float)
    if not np.all(np.isfinite(values)):
        return None
    return turned


def animate(sweep, path, frames: int = 72, fps: float = 24, *, dpi: int = 80, width: float = 5.6,
            turn: str = "full", traces=(), arrows: str | None = None, omega=None, alpha=0.0,
            arrow_points=None) -> Path:
    """Write an animated GIF of the mechanism moving through its sweep.

    Parameters
    ----------
    sweep : Sweep
        Its mechanism must have named points and links.
    path : str or Path
        Output file, ending in ``.gif``; missing folders are created.
    frames : int
        Number of frames (inputs evenly spaced over the animation, see
        :func:`frame_indices`).
    fps : float
        Frames per second.
    dpi : int
        Resolution of the frames, dots per inch: the GIF is
        ``round(width * dpi)`` pixels wide (448 by default).
    width : float
        Width of the frames, inches (the height follows the drawing).
    turn : {"full", "sweep"}
        ``"full"`` (default): one full turn of the input from the sweep's
        first input when the mechanism can turn fully (:func:`full_turn`),
        else the sweep; ``"sweep"``: the sweep's own inputs (a half turn
        when that is what the sweep covers).
    traces : sequence of str
        Named points whose paths (coupler curves) are drawn.
    arrows : {"velocity", "acceleration"}, optional
        Arrows of the velocity or acceleration of each point of
        `arrow_points` (default every point that is not a ground pivot),
        from :func:`numkin.analytic.point_kinematics`, on one scale for the
        whole animation (the longest a quarter of the drawing).
    omega, alpha
        Input speed and acceleration for `arrows` (``"10 rad/s"``).
    arrow_points : sequence of str, optional

    Returns
    -------
    Path
        The file written.

    Examples
    --------
    >>> import numpy as np
    >>> from PIL import Image
    >>> from numkin import linkages
    >>> from numkin.animate import animate
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    >>> gif = animate(sweep, "/tmp/numkin-doc-slider-crank.gif", frames=10, dpi=50, width=6.0,
    ...               arrows="velocity", omega="10 rad/s", traces=["A"])
    >>> with Image.open(gif) as im:
    ...     im.n_frames, im.size[0]
    (10, 300)
    """
    import matplotlib
    from matplotlib.animation import PillowWriter
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Polygon

    mech = sweep.mechanism
    if not mech.points or not mech.links:
        raise InputError(f"{mech.name} has no named points and links to animate")
    path = Path(path)
    if path.suffix.lower() != ".gif":
        raise InputError(f"path must end in .gif (the Pillow writer writes GIF), got {str(path)!r}")
    if not (isinstance(fps, numbers.Real) and math.isfinite(fps) and fps > 0):
        raise InputError(f"fps must be a positive number, got {fps!r}")
    if isinstance(dpi, bool) or not isinstance(dpi, numbers.Integral) or not 10 <= dpi <= 600:
        raise InputError(f"dpi must be an integer from 10 to 600, got {dpi!r}")
    if isinstance(width, bool) or not isinstance(width, numbers.Real) or not (1.0 <= width <= 40.0):
        raise InputError(f"width must be a number of inches from 1 to 40, got {width!r}")
    if turn not in ("full", "sweep"):
        raise InputError(f"turn must be 'full' or 'sweep', got {turn!r}")
    traces = [traces] if isinstance(traces, str) else list(traces or ())
    for n in traces:
        if n not in mech.points:
            raise InputError(f"traces: {n!r} is not a named point of {mech.name}; points are {list(mech.points)}")
    if arrows is not None and omega is None:
        raise InputError("arrows: give the input speed omega (for example omega='10 rad/s')")
    if turn == "full":
        sweep = full_turn(sweep) or sweep
    idx = frame_indices(sweep.inputs, frames)
    made_folder(path.parent, "path")

    pts = sweep.points()
    ground = list(mech.ground or ())
    blocks = {**slider_points(pts, ground), **guided_points(mech.links, pts, ground)}
    (x0, x1), (y0, y1), span = bounds(list(pts.values()), margin=0.1)
    vectors, vec_unit, scale = {}, "", 0.0
    if arrows is not None:
        vectors, vec_unit = arrow_vectors(sweep, arrows, omega, alpha, arrow_points)
        scale = arrow_scale(vectors, span)
        tips = [pts[n][:, idx] + scale * v[:, idx] for n, v in vectors.items()]
        (x0, x1), (y0, y1), span = bounds(list(pts.values()) + tips, margin=0.1)
    height = float(np.clip(width * 0.86 * (y1 - y0) / (x1 - x0) + 0.9 + (0.3 if vectors else 0.0),
                           0.55 * width, 1.35 * width))
    joints = sorted({n for link in mech.links for n in link} | set(ground))
    unit = length_unit(sweep)
    symbol = sym(input_name(sweep))
    color = "#8E44AD" if arrows == "velocity" else "#C0392B"
    head = "v" if arrows == "velocity" else "a"

    fig = None
    try:
        # no layout engine: fixed axes, so the frames do not jitter (and savefig, which
        # restores the engine from rcParams after each frame, must not turn one on)
        with style(), matplotlib.rc_context({"figure.constrained_layout.use": False, "figure.autolayout": False}):
            fig = Figure(figsize=(width, height), dpi=dpi, layout="none")
            FigureCanvasAgg(fig)
            bottom = 0.16 if vectors else 0.11
            ax = fig.add_axes((0.13, bottom, 0.83, 0.91 - bottom))
            ax.set_aspect("equal", adjustable="box")
            ax.set_xlim(x0, x1)
            ax.set_ylim(y0, y1)
            ax.set_autoscale_on(False)
            ax.set_xlabel(f"$x$ [{unit}]")
            ax.set_ylabel(f"$y$ [{unit}]")
            ax.grid(True, alpha=0.25)
            ax.set_title(mechanism_title(mech), fontsize=9)
            for name, guide in blocks.items():
                if guide[0] in ("h", "v"):
                    (ax.axhline if guide[0] == "h" else ax.axvline)(guide[1], color="0.5", linestyle="--",
                                                                    linewidth=0.8, zorder=1)
            for name in traces:
                ax.plot(pts[name][0], pts[name][1], color="0.35", linestyle=(0, (4, 2)), linewidth=0.9, zorder=2)
            for name in ground:
                gx, gy = pts[name][:, 0]
                draw_ground(ax, gx, gy, size=0.025 * span, zorder=2)
            links = [
                ax.plot([], [], color=c, linewidth=3.0, solid_capstyle="round", zorder=3)[0]
                for c in link_colors(len(mech.links))
            ]
            patches = {}
            for name in blocks:
                patches[name] = Polygon(np.zeros((4, 2)), closed=True, facecolor="0.8", edgecolor="0.2",
                                        linewidth=1.0, zorder=4)
                ax.add_patch(patches[name])
            dots = ax.plot([], [], "o", markersize=5.5, markerfacecolor="white", markeredgecolor="black",
                           markeredgewidth=1.1, zorder=5)[0]
            arrow_artists = {}
            for name in vectors:
                arrow = ax.annotate("", xy=(0, 0), xytext=(0, 0), zorder=6,
                                    arrowprops={"arrowstyle": "-|>", "color": color, "linewidth": 1.5,
                                                "shrinkA": 0, "shrinkB": 0, "mutation_scale": 10})
                label = ax.annotate(f"${head}_{{{name}}}$", (0, 0), xytext=(0, 0), textcoords="offset points",
                                    ha="center", va="center", fontsize=8, color=color, zorder=7)
                arrow_artists[name] = (arrow, label)
            if vectors:
                footer = fig.text(0.13, 0.015, f"{arrows} arrows: {scale_text(scale, vec_unit, span, unit)}",
                                  ha="left", va="bottom", fontsize=8, color=color)
                renderer = fig.canvas.get_renderer()
                room = fig.bbox.x1 - _EDGE * fig.dpi / 72.0 - footer.get_window_extent(renderer).x0
                fit_text(footer, renderer, room, top=footer.get_window_extent(renderer).y1)  # (one line, smaller)
            stamp = ax.text(0.03, 0.96, "", transform=ax.transAxes, ha="left", va="top", fontsize=11, zorder=8,
                            bbox={"boxstyle": "square,pad=0.3", "facecolor": "white", "edgecolor": "0.6"})
            labels_inside(fig, ax)
            fit_titles(fig, relayout=False)  # the axes stay where they are
            writer = PillowWriter(fps=fps)
            with writer.saving(fig, str(path), dpi=dpi):
                for k in idx:
                    for line, link in zip(links, mech.links):
                        line.set_data([pts[n][0, k] for n in link], [pts[n][1, k] for n in link])
                    for name, direction in block_directions(blocks, pts, k).items():
                        patches[name].set_xy(block_corners(pts[name][:, k], direction, 0.075 * span, 0.045 * span))
                    dots.set_data([pts[n][0, k] for n in joints], [pts[n][1, k] for n in joints])
                    for name, (arrow, label) in arrow_artists.items():
                        base = pts[name][:, k]
                        vec = vectors[name][:, k]
                        tip = base + scale * vec if np.all(np.isfinite(vec)) else base
                        shown = float(np.hypot(*(tip - base))) > 1e-3 * span
                        arrow.xy, arrow.xyann = tuple(tip), tuple(base)
                        arrow.set_visible(shown)
                        label.xy = tuple(tip)
                        label.xyann = tip_offset(vec)
                        label.set_visible(shown)
                    stamp.set_text(f"{symbol} = {deg_text(float(sweep.inputs[k]))}")
                    writer.grab_frame()
    finally:
        if fig is not None:
            close(fig)
    return path

"""Animated GIF of a mechanism over its sweep.

The links are drawn as polylines of the mechanism's named points, the joints
as circles, the ground pivots hatched and the sliders as blocks on their
guides, with the input angle stamped on each frame. Frames are written with
Pillow (:class:`matplotlib.animation.PillowWriter`; no ffmpeg), with the
package style, fixed axis limits (from the whole sweep) and a fixed frame
count, so the file is the same bytes each time. One figure is drawn for all
frames and closed at the end.

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
from pathlib import Path

import numpy as np

from .figures.drawing import bounds, draw_ground, link_colors, slider_points
from .figures.labels import deg_text, input_name, length_unit, sym
from .figures.style import close, style

__all__ = ["animate", "frame_indices"]


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
        raise ValueError(f"frames must be an integer >= 2, got {frames!r}")
    n = t.size
    full_turn = n > 2 and abs(abs(t[-1] - t[0]) - 2 * math.pi) <= 1e-9 * max(1.0, abs(t[-1]))
    distinct = n - 1 if full_turn else n
    if frames > distinct:
        raise ValueError(
            f"frames = {frames} is more than the {distinct} distinct inputs of the sweep; "
            "ask for fewer frames or sweep a finer grid"
        )
    if full_turn:
        return np.floor(np.arange(frames) * distinct / frames + 0.5).astype(int)
    return np.floor(np.linspace(0, n - 1, frames) + 0.5).astype(int)


def animate(sweep, path, frames: int = 72, fps: float = 24, *, dpi: int = 80) -> Path:
    """Write an animated GIF of the mechanism moving through its sweep.

    Parameters
    ----------
    sweep : Sweep
        Its mechanism must have named points and links.
    path : str or Path
        Output file, ending in ``.gif``; missing folders are created.
    frames : int
        Number of frames (inputs evenly spaced over the sweep, see
        :func:`frame_indices`).
    fps : float
        Frames per second.
    dpi : int
        Resolution of the frames (the figure is 5.6 in wide).

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
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361)))
    >>> with Image.open(animate(sweep, "/tmp/numkin-doc-slider-crank.gif", frames=10)) as im:
    ...     im.n_frames
    10
    """
    import matplotlib
    from matplotlib.animation import PillowWriter
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    mech = sweep.mechanism
    if not mech.points or not mech.links:
        raise ValueError(f"{mech.name} has no named points and links to animate")
    path = Path(path)
    if path.suffix.lower() != ".gif":
        raise ValueError(f"path must end in .gif (the Pillow writer writes GIF), got {str(path)!r}")
    if not (isinstance(fps, numbers.Real) and math.isfinite(fps) and fps > 0):
        raise ValueError(f"fps must be a positive number, got {fps!r}")
    idx = frame_indices(sweep.inputs, frames)
    path.parent.mkdir(parents=True, exist_ok=True)

    pts = sweep.points()
    ground = list(mech.ground or ())
    sliders = slider_points(pts, ground)
    (x0, x1), (y0, y1), span = bounds(list(pts.values()), margin=0.1)
    width = 5.6
    height = float(np.clip(width * 0.86 * (y1 - y0) / (x1 - x0) + 0.9, 3.0, 7.5))
    joints = sorted({n for link in mech.links for n in link} | set(ground))
    unit = length_unit(sweep)
    symbol = sym(input_name(sweep))

    fig = None
    try:
        # no layout engine: fixed axes, so the frames do not jitter (and savefig, which
        # restores the engine from rcParams after each frame, must not turn one on)
        with style(), matplotlib.rc_context({"figure.constrained_layout.use": False, "figure.autolayout": False}):
            fig = Figure(figsize=(width, height), dpi=dpi, layout="none")
            FigureCanvasAgg(fig)
            ax = fig.add_axes((0.13, 0.11, 0.83, 0.8))
            ax.set_aspect("equal", adjustable="box")
            ax.set_xlim(x0, x1)
            ax.set_ylim(y0, y1)
            ax.set_autoscale_on(False)
            ax.set_xlabel(f"$x$ [{unit}]")
            ax.set_ylabel(f"$y$ [{unit}]")
            ax.grid(True, alpha=0.25)
            ax.set_title(mech.name, fontsize=9)
            for name, (kind, c) in sliders.items():
                (ax.axhline if kind == "h" else ax.axvline)(c, color="0.5", linestyle="--", linewidth=0.8, zorder=1)
            for name in ground:
                gx, gy = pts[name][:, 0]
                draw_ground(ax, gx, gy, size=0.025 * span, zorder=2)
            links = [
                ax.plot([], [], color=color, linewidth=3.0, solid_capstyle="round", zorder=3)[0]
                for color in link_colors(len(mech.links))
            ]
            blocks = ax.plot([], [], "s", markersize=13, markerfacecolor="0.8", markeredgecolor="0.2", zorder=4)[0]
            dots = ax.plot([], [], "o", markersize=5.5, markerfacecolor="white", markeredgecolor="black",
                           markeredgewidth=1.1, zorder=5)[0]
            stamp = ax.text(0.03, 0.96, "", transform=ax.transAxes, ha="left", va="top", fontsize=11, zorder=6,
                            bbox={"boxstyle": "square,pad=0.3", "facecolor": "white", "edgecolor": "0.6"})
            writer = PillowWriter(fps=fps)
            with writer.saving(fig, str(path), dpi=dpi):
                for k in idx:
                    for line, link in zip(links, mech.links):
                        line.set_data([pts[n][0, k] for n in link], [pts[n][1, k] for n in link])
                    blocks.set_data([pts[n][0, k] for n in sliders], [pts[n][1, k] for n in sliders])
                    dots.set_data([pts[n][0, k] for n in joints], [pts[n][1, k] for n in joints])
                    stamp.set_text(f"{symbol} = {deg_text(float(sweep.inputs[k]))}")
                    writer.grab_frame()
    finally:
        if fig is not None:
            close(fig)
    return path

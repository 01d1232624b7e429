"""Drawing a linkage: links, joints, ground pivots, sliders, dimensions, traces and arrows.

The pieces are shared by :func:`mechanism` (one position, dimensioned) and
:mod:`numkin.animate` (every frame of a sweep).
"""

from __future__ import annotations

import math
import warnings
from typing import Iterable, Mapping, Sequence

import numpy as np

from .labels import (
    angle_text, deg_text, input_name, is_angle, length_text, length_unit, mechanism_title, no_negative_zero, sym,
    value_text,
)
from ..errors import ConvergenceWarning, InputError
from .registries import dimensions_of
from .style import CYCLE, new_figure, shared_doc, style

__all__ = [
    "arrow_scale", "arrow_vectors", "block_corners", "block_directions", "bounds",
    "draw_block", "draw_ground", "guided_points", "link_colors", "mechanism", "scale_text", "slider_points",
    "tip_offset",
]


def slider_points(points: Mapping, ground: Sequence[str]) -> dict:
    """Points that move along a fixed line: name -> ("h", y) or ("v", x).

    Examples
    --------
    >>> import numpy as np
    >>> slider_points({"P": np.array([[1.0, 2.0, 3.0], [0.5, 0.5, 0.5]])}, ())
    {'P': ('h', 0.5)}
    """
    out = {}
    for name, xy in points.items():
        if name in ground or xy.shape[1] < 2:
            continue
        fx = np.ptp(xy[0]) <= 1e-9 * max(1.0, np.abs(xy[0]).max())
        fy = np.ptp(xy[1]) <= 1e-9 * max(1.0, np.abs(xy[1]).max())
        if fy and not fx:
            out[name] = ("h", float(xy[1, 0]))
        elif fx and not fy:
            out[name] = ("v", float(xy[0, 0]))
    return out


def guided_points(links: Sequence[Sequence[str]], points: Mapping, ground: Sequence[str]) -> dict:
    """Joints that slide along a moving link: name -> (a, b), the segment a-b they slide on.

    A point of one link that lies on the line of a segment of another link
    (not one of that link's own points) at every input of the sweep, such as
    the slider A of a slotted-rocker quick-return on the rocker O1-B.

    Parameters
    ----------
    links : sequence of sequences of str
    points : mapping of str to array (2, N)
        Coordinates over the sweep (:meth:`Sweep.points`).
    ground : sequence of str

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.quick_return()
    >>> sweep = mech.sweep(np.radians(np.arange(0, 361, 10)))
    >>> guided_points(mech.links, sweep.points(), mech.ground)
    {'A': ('O1', 'B')}
    """
    out = {}
    for name, xy in points.items():
        if name in ground or xy.shape[-1] < 2:
            continue
        for link in links:
            if name in link:
                continue
            for a, b in zip(link[:-1], link[1:]):
                d = points[b] - points[a]
                e = xy - points[a]
                length = np.hypot(*d)
                scale = max(float(np.max(np.abs(np.concatenate([d, e])))), 1e-300)
                cross = d[0] * e[1] - d[1] * e[0]
                if np.all(length > 1e-9 * scale) and np.all(np.abs(cross) <= 1e-9 * scale * length):
                    out[name] = (a, b)
                    break
            if name in out:
                break
    return out


def block_corners(centre, direction, length: float, width: float) -> np.ndarray:
    """Corners (4, 2) of a slider block centred on `centre`, its long side along `direction`.

    Examples
    --------
    >>> block_corners((0.0, 0.0), (1.0, 0.0), 2.0, 1.0).tolist()
    [[-1.0, -0.5], [1.0, -0.5], [1.0, 0.5], [-1.0, 0.5]]
    """
    c = np.asarray(centre, dtype=float)
    u = np.asarray(direction, dtype=float)
    n = float(np.hypot(*u))
    u = u / n if n > 0 else np.array([1.0, 0.0])
    v = np.array([-u[1], u[0]])
    hl, hw = 0.5 * length * u, 0.5 * width * v
    return np.array([c - hl - hw, c + hl - hw, c + hl + hw, c - hl + hw]) + 0.0


def block_directions(blocks: Mapping, points: Mapping, k: int | None = None) -> dict:
    """Direction (x, y) of each slider block: its fixed guide, or the segment it slides on.

    `blocks` maps a name to ``("h", y)``, ``("v", x)`` (:func:`slider_points`)
    or ``(a, b)`` (:func:`guided_points`); `points` holds coordinates (2,) or
    (2, N), column `k` taken when given.
    """
    out = {}
    for name, guide in blocks.items():
        if guide[0] == "h":
            out[name] = np.array([1.0, 0.0])
        elif guide[0] == "v":
            out[name] = np.array([0.0, 1.0])
        else:
            a, b = (points[n] if k is None else points[n][:, k] for n in guide)
            out[name] = np.asarray(b, dtype=float) - np.asarray(a, dtype=float)
    return out


def draw_block(ax, centre, direction, span: float, zorder: float = 4.0):
    """A slider block (a grey rectangle) on the drawing; returns its Polygon (``set_xy`` moves it)."""
    from matplotlib.patches import Polygon

    patch = Polygon(block_corners(centre, direction, 0.075 * span, 0.045 * span), closed=True, facecolor="0.8",
                    edgecolor="0.2", linewidth=1.0, zorder=zorder)
    ax.add_patch(patch)
    return patch


def arrow_vectors(sweep, kind: str, omega, alpha=0.0, points: Sequence[str] | None = None) -> tuple[dict, str]:
    """Velocity or acceleration vectors of named points over the sweep, from the analytic point kinematics.

    Parameters
    ----------
    sweep : Sweep
    kind : {"velocity", "acceleration"}
    omega, alpha
        Input speed and acceleration (see :func:`numkin.analytic.point_kinematics`).
    points : sequence of str, optional
        Default: every named point that is not a ground pivot.

    Returns
    -------
    (dict, str)
        name -> array (2, N) in the length unit per s (or s²), and that unit.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians([90.0]))
    >>> vec, unit = arrow_vectors(sweep, "velocity", "10 rad/s", points=["A"])
    >>> np.round(vec["A"][:, 0], 6).tolist(), unit
    ([-800.0, 0.0], 'mm/s')
    """
    from .. import analytic

    if kind not in ("velocity", "acceleration"):
        raise InputError(f"arrows: {kind!r} is neither 'velocity' nor 'acceleration'")
    mech = sweep.mechanism
    if points is None:
        points = [n for n in mech.points if n not in (mech.ground or ())]
    points = [points] if isinstance(points, str) else list(points)
    for n in points:
        if n not in mech.points:
            raise InputError(f"arrows: {n!r} is not a named point of {mech.name}; points are {list(mech.points)}")
    frame = analytic.point_kinematics(sweep, omega, alpha, points=points)
    head = "v" if kind == "velocity" else "a"
    unit = f"{mech.length_unit}/s" if kind == "velocity" else f"{mech.length_unit}/s²"
    vectors = {n: np.vstack([np.asarray(frame[f"{head}x_{n}"], dtype=float),
                             np.asarray(frame[f"{head}y_{n}"], dtype=float)]) for n in points}
    return vectors, unit


def tip_offset(vector, distance: float = 9.0) -> tuple[float, float]:
    """Offset (points) of an arrow's label from its tip: `distance` further along the arrow.

    Examples
    --------
    >>> tip_offset((0.0, -2.0))
    (0.0, -9.0)
    """
    v = np.asarray(vector, dtype=float)
    n = float(np.hypot(*v))
    if not n or not math.isfinite(n):
        return (0.0, distance)
    return (float(distance * v[0] / n) + 0.0, float(distance * v[1] / n) + 0.0)


def arrow_scale(vectors: Mapping, span: float, fraction: float = 0.25) -> float:
    """Drawing length per unit of the vectors: the longest vector drawn `fraction` of `span` long.

    Examples
    --------
    >>> import numpy as np
    >>> arrow_scale({"A": np.array([[3.0], [4.0]])}, 100.0)
    5.0
    """
    longest = max((float(np.max(np.hypot(*v))) for v in vectors.values() if np.size(v)), default=0.0)
    return fraction * span / longest if longest > 0 and math.isfinite(longest) else 0.0


def scale_text(scale: float, unit: str, span: float, length_unit_: str) -> str:
    """Legend of an arrow scale: a round length of the drawing and the value it stands for.

    Examples
    --------
    >>> scale_text(0.5, "mm/s", 120.0, "mm")
    '10 mm of drawing = 20 mm/s'
    """
    if scale <= 0:
        return ""
    draw = 10.0 ** math.floor(math.log10(0.1 * span))
    return f"{length_text(draw)} {length_unit_} of drawing = {no_negative_zero(f'{draw / scale:.3g}')} {unit}"


def bounds(xy_list: Iterable[np.ndarray], margin: float = 0.12):
    """x and y limits around all points (arrays (2, ...)) with a margin, and the larger span."""
    xs = np.concatenate([np.ravel(xy[0]) for xy in xy_list])
    ys = np.concatenate([np.ravel(xy[1]) for xy in xy_list])
    xs, ys = xs[np.isfinite(xs)], ys[np.isfinite(ys)]
    x0, x1, y0, y1 = xs.min(), xs.max(), ys.min(), ys.max()
    span = max(x1 - x0, y1 - y0, 1e-9)
    m = margin * span
    return (x0 - m, x1 + m), (y0 - m, y1 + m), span


def draw_ground(ax, x: float, y: float, size: float, zorder: float = 2.0) -> None:
    """A ground pivot: a hatched triangle under the joint."""
    from matplotlib.patches import Polygon

    tri = Polygon([(x, y), (x - size, y - 1.5 * size), (x + size, y - 1.5 * size)], closed=True,
                  facecolor="0.85", edgecolor="0.25", linewidth=1.0, zorder=zorder)
    ax.add_patch(tri)
    yb = y - 1.5 * size
    ax.plot([x - 1.4 * size, x + 1.4 * size], [yb, yb], color="0.25", linewidth=1.2, zorder=zorder)
    for k in range(6):
        x0 = x - 1.3 * size + k * 0.5 * size
        ax.plot([x0, x0 - 0.4 * size], [yb, yb - 0.45 * size], color="0.25", linewidth=0.8, zorder=zorder)


def link_colors(n: int) -> list[str]:
    """Colours of `n` links (the colour cycle without black)."""
    return [CYCLE[k % (len(CYCLE) - 1)] for k in range(n)]


def _setup_mechanism_axes(ax, sweep, xlim, ylim) -> None:
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    u = length_unit(sweep)
    ax.set_xlabel(f"$x$ [{u}]")
    ax.set_ylabel(f"$y$ [{u}]")


def _angle_arcs(sweep, pts: Mapping, values: Mapping, segments: Sequence[tuple[str, str]]):
    """(centre, angle, symbol) for the input and angle unknowns that are the direction of a segment."""
    arcs = []
    for name, value in values.items():
        if name != input_name(sweep) and not is_angle(sweep, name):
            continue
        for p, q in segments:
            d = pts[q] - pts[p]
            if np.hypot(*d) == 0:
                continue
            direction = math.atan2(d[1], d[0])
            if abs(math.remainder(direction - value, 2 * math.pi)) < 1e-7:
                arcs.append((p, math.remainder(value, 2 * math.pi), name))
                break
    return arcs


def _clear_labels(ax, labels, joints, span: float) -> None:
    """Move each angle label outward along its arc's bisector (or below the reference line) until it
    covers no joint and no other text; a label that finds no clear place stays where it was."""
    import matplotlib

    fig = ax.figure
    # measured at the resolution the figure is saved at (the text as the PNG draws it, measured once
    # for both); the clearance round a joint is 0.07 in
    dpi = fig.dpi
    fig.set_dpi(matplotlib.rcParams["savefig.dpi"])
    try:
        _place_labels(fig, ax, labels, joints, span, 0.07 * fig.dpi)
    finally:
        fig.set_dpi(dpi)


def _place_labels(fig, ax, labels, joints, span: float, pad: float) -> None:
    """The search of :func:`_clear_labels`, at the figure's dpi; `pad` (pixels) round each joint."""
    # the layout (and the equal aspect it leaves room for), so that data coordinates map to the pixels
    # of the drawn figure; nothing is drawn
    if fig.get_layout_engine() is not None:
        fig.get_layout_engine().execute(fig)
    ax.apply_aspect()
    renderer = fig.canvas.get_renderer()
    joints_px = [ax.transData.transform(p) for p in joints]

    def clear(text) -> bool:
        box = text.get_window_extent(renderer).expanded(1.04, 1.15)
        if any(box.x0 - pad <= x <= box.x1 + pad and box.y0 - pad <= y <= box.y1 + pad for x, y in joints_px):
            return False
        others = [t for t in ax.texts if t is not text and t.get_text()]
        return not any(box.overlaps(t.get_window_extent(renderer)) for t in others)

    for text, (cx, cy), radius, mid in labels:
        start = text.get_position()
        for factor in (1.0, 1.35, 1.7, 2.0):
            for turn in (0.0, -0.45, 0.45, -0.9, 0.9):
                a = mid + turn
                text.set_position((cx + factor * radius * math.cos(a) + 0.02 * span, cy + factor * radius * math.sin(a)))
                if clear(text):
                    break
            else:
                continue
            break
        else:
            text.set_position(start)


def _one_point(sweep, at: float, q):
    """A sweep of one input `at`, solved at `q`, on the branch of `sweep` (for the point kinematics there)."""
    mech = sweep.mechanism
    return mech.sweep(np.array([at]), guess=np.asarray(q, dtype=float))


@shared_doc
def mechanism(sweep, at: float | None = None, *, dimensions: Sequence | None = None,
              traces: Sequence[str] | None = None, arrows: str | None = None, omega=None, alpha=0.0,
              arrow_points: Sequence[str] | None = None):
    """The linkage drawn at one input angle, with its dimensions and the solved unknowns.

    Links are drawn as polylines of the mechanism's named points, joints as
    circles, ground pivots hatched, sliders as blocks on their (dashed)
    guides. Dimensions are drawn as offset dimension lines labelled with
    their lengths; the input and the angle unknowns that are the direction
    of a drawn segment as arcs; the values of all unknowns in a box.

    Parameters
    ----------
    sweep : Sweep
        Its mechanism must have named points and links.
    at : float, optional
        The input (rad); default the first input of the sweep. When it is
        not a grid point, the position is solved there from the nearest one.
    dimensions : sequence of (str, str, str[, float]), optional
        ``(P, Q, symbol, side)``: a dimension line from point P to Q,
        labelled ``symbol = length unit``, offset to the left (side > 0) or
        right (side < 0) of P→Q, ``|side|`` times the standard offset.
        Default: the ready-made linkage's own (quick-return: r1 ... r6);
        for other linkages the length of every link segment is written
        along it. ``[]`` draws no dimensions.
    traces : sequence of str, optional
        Named points (a coupler point, say) whose paths over the whole
        sweep are drawn, thin and labelled.
    arrows : {"velocity", "acceleration"}, optional
        Draw the velocity or acceleration vector of each point of
        `arrow_points` (default: every point that is not a ground pivot),
        from :func:`numkin.analytic.point_kinematics`, scaled so that the
        longest is a quarter of the drawing, the scale written below it.
    omega, alpha
        Input speed and acceleration for `arrows` (``"10 rad/s"``, see
        :func:`numkin.analytic.kinematics`); `omega` is needed with arrows.
    arrow_points : sequence of str, optional

    {{returns_figure}}

    {{example_figures}}
    >>> sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))
    >>> fig = figures.mechanism(sweep, np.radians(30))
    >>> figures.save(fig, "/tmp/numkin-doc-qr", ["png"])[0].suffix
    '.png'
    >>> fig = figures.mechanism(sweep, np.radians(30), traces=["B"], arrows="velocity", omega="10 rad/s")
    >>> figures.save(fig, "/tmp/numkin-doc-qr-v", ["png"])[0].suffix
    '.png'
    """
    from .arguments import need_angle, need_names, need_sweep

    need_sweep(sweep, "mechanism")
    need_angle(at, "at", "mechanism")
    traces = need_names(traces, "traces", "mechanism")
    arrow_points = need_names(arrow_points, "arrow_points", "mechanism")
    mech = sweep.mechanism
    if not mech.points or not mech.links:
        raise InputError(f"{mech.name} has no named points and links to draw")
    at = float(sweep.inputs[0]) if at is None else float(at)
    if not math.isfinite(at):
        raise InputError(f"at must be a finite input angle in rad, got {at!r}")
    k = sweep.index(at)
    q = sweep.values[:, k]
    if abs(sweep.inputs[k] - at) > 1e-12 * max(1.0, abs(at)):
        with warnings.catch_warnings():  # a failure is raised below, in the drawing's words
            warnings.simplefilter("ignore", ConvergenceWarning)
            res = mech.solve(at, guess=q)
        if not res.converged:
            raise InputError(f"{mech.name}: cannot solve the position at input {deg_text(at)} to draw it")
        q = np.asarray(res.x, dtype=float).reshape(-1)
    pts = {n: xy[:, 0] for n, xy in mech.point_coordinates(q[:, None], np.array([at])).items()}
    all_pts = sweep.points()
    ground = list(mech.ground or ())
    sliders = slider_points(all_pts, ground)
    blocks = {**sliders, **guided_points(mech.links, all_pts, ground)}
    unit = length_unit(sweep)
    traces = [traces] if isinstance(traces, str) else list(traces or ())
    for n in traces:
        if n not in all_pts:
            raise InputError(f"traces: {n!r} is not a named point of {mech.name}; points are {list(all_pts)}")
    vectors, vec_unit = {}, ""
    if arrows is not None:
        if omega is None:
            raise InputError("arrows: give the input speed omega (for example omega='10 rad/s')")
        one = _one_point(sweep, at, q)
        vectors, vec_unit = arrow_vectors(one, arrows, omega, alpha, arrow_points)
        vectors = {n: v[:, 0] for n, v in vectors.items()}
    values = {input_name(sweep): at, **dict(zip(sweep.unknowns, q))}

    if dimensions is None:
        dimensions = dimensions_of(mech)
    dims = []
    for d in dimensions or ():
        p, r, label = d[0], d[1], d[2]
        side = float(d[3]) if len(d) > 3 else 1.0
        for n in (p, r):
            if n not in pts:
                raise InputError(f"dimensions: {n!r} is not a named point of {mech.name}; points are {list(pts)}")
        dims.append((p, r, label, side))
    # without dimension lines, every link segment is labelled with its length
    plain = []
    if dimensions is None:
        seen = set()
        for link in mech.links:
            for p, r in zip(link[:-1], link[1:]):
                if frozenset((p, r)) not in seen:
                    seen.add(frozenset((p, r)))
                    plain.append((p, r))

    xlim, ylim, span = bounds([xy[:, None] for xy in pts.values()] + [all_pts[n] for n in traces], margin=0.16)
    off = 0.045 * span
    segments = [(p, r) for link in mech.links for p, r in zip(link[:-1], link[1:])] + [(p, r) for p, r, _, _ in dims]
    arcs = _angle_arcs(sweep, pts, values, segments)
    aspect = (ylim[1] - ylim[0]) / (xlim[1] - xlim[0])
    size = (7.4, float(np.clip(4.6 * aspect + 1.0, 3.4, 8.0)))

    with style():
        fig, axes = new_figure(size=size)
        ax = axes[0, 0]
        ax.grid(True, alpha=0.25)
        # guides of the sliders, horizontal reference lines of the angles
        for name, (kind, c) in sliders.items():
            if kind == "h":
                ax.axhline(c, color="0.5", linestyle="--", linewidth=0.8, zorder=1)
            else:
                ax.axvline(c, color="0.5", linestyle="--", linewidth=0.8, zorder=1)
        radii: dict = {}
        arc_geometry = []
        for centre_name, ang, name in arcs:
            radius = radii[centre_name] = radii.get(centre_name, 0.05 * span) + 0.05 * span
            arc_geometry.append((centre_name, ang, name, radius))
            cx, cy = pts[centre_name]
            ax.plot([cx, cx + radius + 0.06 * span], [cy, cy], color="0.5", linestyle="--", linewidth=0.7, zorder=1)
        for name in ground:
            draw_ground(ax, *pts[name], size=0.025 * span, zorder=2)
        for link, color in zip(mech.links, link_colors(len(mech.links))):
            xy = np.array([pts[n] for n in link])
            ax.plot(xy[:, 0], xy[:, 1], color=color, linewidth=3.2, solid_capstyle="round", zorder=3)
        for name, direction in block_directions(blocks, pts).items():
            draw_block(ax, pts[name], direction, span)
        for j, name in enumerate(traces):
            path = all_pts[name]
            ax.plot(path[0], path[1], color="0.35", linestyle=(0, (4, 2)), linewidth=0.9, zorder=2)
            top = int(np.argmax(path[1]))
            ax.annotate(f"path of {name}", (path[0, top], path[1, top]), xytext=(0, 4), textcoords="offset points",
                        ha="center", va="bottom", fontsize=8, color="0.25", zorder=6)
        if vectors:
            scale = arrow_scale(vectors, span)
            color = "#8E44AD" if arrows == "velocity" else "#C0392B"
            head = "v" if arrows == "velocity" else "a"
            for name, vec in vectors.items():
                if not np.all(np.isfinite(vec)) or np.hypot(*vec) * scale < 1e-3 * span:
                    continue
                tip = pts[name] + scale * vec
                ax.annotate("", xy=tip, xytext=pts[name], zorder=6,
                            arrowprops={"arrowstyle": "-|>", "color": color, "linewidth": 1.6, "shrinkA": 0,
                                        "shrinkB": 0, "mutation_scale": 11})
                ax.annotate(f"${head}_{{{name}}}$", tip, xytext=tip_offset(vec), textcoords="offset points",
                            ha="center", va="center", fontsize=8.5, color=color, zorder=7)
            ax.text(0.0, -0.13, f"{arrows} arrows: {scale_text(scale, vec_unit, span, unit)}",
                    transform=ax.transAxes, ha="left", va="top", fontsize=8, color=color)
        joints = sorted({n for link in mech.links for n in link} | set(ground))
        for name in joints:
            ax.plot(*pts[name], "o", markersize=6, markerfacecolor="white", markeredgecolor="black",
                    markeredgewidth=1.2, zorder=5)
        # point names, pushed away from the centre of the drawing
        centre = np.mean(np.array(list(pts.values())), axis=0)
        for name, (px, py) in pts.items():
            if name in ground:  # under the ground symbol
                ax.text(px, py - 2.3 * 0.025 * span, name, ha="center", va="top", fontsize=9,
                        fontweight="bold", zorder=6)
                continue
            d = np.array([px, py]) - centre
            nrm = np.hypot(*d)
            d = d / nrm if nrm > 0 else np.array([0.0, 1.0])
            dist = 21.0 if name in blocks else 12.0
            ax.annotate(name, (px, py), xytext=(dist * d[0] - 8 * d[1], dist * d[1] + 8 * d[0]),
                        textcoords="offset points", ha="center", va="center", fontsize=9, fontweight="bold",
                        zorder=6)
        label_box = {"boxstyle": "square,pad=0.1", "facecolor": "white", "edgecolor": "none", "alpha": 0.85}

        def _along(a, b, text, shift):
            v = b - a
            rot = math.degrees(math.atan2(v[1], v[0]))
            rot = rot - 180 if rot > 90 else (rot + 180 if rot <= -90 else rot)
            mid = 0.5 * (a + b) + shift
            ax.text(*mid, text, rotation=rot, rotation_mode="anchor", ha="center", va="center", fontsize=8,
                    color="0.15", zorder=6, bbox=label_box)

        # dimension lines
        for p, r, label, side in dims:
            a, b = pts[p], pts[r]
            v = b - a
            length = float(np.hypot(*v))
            if length == 0:
                continue
            nrm = np.array([-v[1], v[0]]) / length * side * off
            a2, b2 = a + nrm, b + nrm
            ext = nrm * (1.0 + 0.25 / abs(side))
            for e in (a, b):
                ax.plot([e[0], e[0] + ext[0]], [e[1], e[1] + ext[1]], color="0.35", linewidth=0.6, zorder=2)
            ax.annotate("", xy=b2, xytext=a2, zorder=2,
                        arrowprops={"arrowstyle": "<|-|>", "color": "0.35", "linewidth": 0.7,
                                    "shrinkA": 0, "shrinkB": 0, "mutation_scale": 7})
            value = length_text(length)
            text = f"{value} {unit}" if label is None else f"${label}$ = {value} {unit}"
            _along(a2, b2, text, 0.0 * nrm)
        # plain length labels
        for p, r in plain:
            a, b = pts[p], pts[r]
            v = b - a
            length = float(np.hypot(*v))
            if length > 0:
                _along(a, b, f"{length_text(length)} {unit}", np.array([-v[1], v[0]]) / length * 0.03 * span)
        # angle arcs
        from matplotlib.patches import Arc

        labels = []
        for centre_name, ang, name, radius in arc_geometry:
            cx, cy = pts[centre_name]
            lo, hi = (0.0, math.degrees(ang)) if ang >= 0 else (math.degrees(ang), 0.0)
            ax.add_patch(Arc((cx, cy), 2 * radius, 2 * radius, theta1=lo, theta2=hi, color="0.2",
                             linewidth=0.9, zorder=2))
            mid = math.radians(0.5 * (lo + hi))
            labels.append((ax.text(cx + radius * math.cos(mid) + 0.02 * span, cy + radius * math.sin(mid),
                                   f"{sym(name)} = {angle_text(values[name])}", fontsize=8.5, ha="left",
                                   va="center", zorder=6, bbox=label_box), (cx, cy), radius, mid))
        # the solved unknowns, beside the drawing
        lines = [f"{sym(input_name(sweep))} = {angle_text(at)}"]
        for name, v in zip(sweep.unknowns, q):
            lines.append(f"{sym(name)} = {angle_text(v)}" if is_angle(sweep, name)
                         else f"{sym(name)} = {value_text(v)} {unit}")
        ax.text(1.03, 1.0, "\n".join(lines), transform=ax.transAxes, ha="left", va="top", fontsize=9,
                zorder=7, bbox={"boxstyle": "square,pad=0.4", "facecolor": "white", "edgecolor": "0.6"})
        _setup_mechanism_axes(ax, sweep, xlim, ylim)
        ax.set_title(f"{mechanism_title(mech)} at {sym(input_name(sweep))} = {angle_text(at)}")
        _clear_labels(ax, labels, [pts[n] for n in joints], span)
    return fig

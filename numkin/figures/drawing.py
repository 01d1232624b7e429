"""Drawing a linkage: links, joints, ground pivots, sliders, dimensions, traces and arrows.

The pieces are shared by :func:`mechanism` (one position, dimensioned) and
:mod:`numkin.animate` (every frame of a sweep).
"""

from __future__ import annotations

import math
from typing import Iterable, Mapping, Sequence

import numpy as np

from .labels import deg_text, input_name, is_angle, length_text, length_unit, sym, value_text
from .registries import dimensions_of
from .style import CYCLE, new_figure, style

__all__ = ["bounds", "draw_ground", "link_colors", "mechanism", "slider_points"]


def slider_points(points: Mapping, ground: Sequence[str]) -> dict:
    """Points that move along a fixed line: name -> ("h", y) or ("v", x)."""
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


def bounds(xy_list: Iterable[np.ndarray], margin: float = 0.12):
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


def mechanism(sweep, at: float | None = None, *, dimensions: Sequence | None = None):
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

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))
    >>> fig = figures.mechanism(sweep, np.radians(30))
    >>> figures.save(fig, "/tmp/numkin-doc-qr", ["png"])[0].suffix
    '.png'
    """
    mech = sweep.mechanism
    if not mech.points or not mech.links:
        raise ValueError(f"{mech.name} has no named points and links to draw")
    at = float(sweep.inputs[0]) if at is None else float(at)
    k = sweep.index(at)
    q = sweep.values[:, k]
    if abs(sweep.inputs[k] - at) > 1e-12 * max(1.0, abs(at)):
        res = mech.solve(at, guess=q)
        if not res.converged:
            raise ValueError(f"{mech.name}: cannot solve the position at input {deg_text(at)} to draw it")
        q = np.asarray(res.x, dtype=float).reshape(-1)
    pts = {n: xy[:, 0] for n, xy in mech.point_coordinates(q[:, None], np.array([at])).items()}
    all_pts = sweep.points()
    ground = list(mech.ground or ())
    sliders = slider_points(all_pts, ground)
    unit = length_unit(sweep)
    values = {input_name(sweep): at, **dict(zip(sweep.unknowns, q))}

    if dimensions is None:
        dimensions = dimensions_of(mech.name)
    dims = []
    for d in dimensions or ():
        p, r, label = d[0], d[1], d[2]
        side = float(d[3]) if len(d) > 3 else 1.0
        for n in (p, r):
            if n not in pts:
                raise ValueError(f"dimensions: {n!r} is not a named point of {mech.name}; points are {list(pts)}")
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

    xlim, ylim, span = bounds([xy[:, None] for xy in pts.values()], margin=0.16)
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
        for name in sliders:
            ax.plot(*pts[name], marker="s", markersize=15, markerfacecolor="0.8", markeredgecolor="0.2", zorder=4)
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
            dist = 19.0 if name in sliders else 12.0
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

        for centre_name, ang, name, radius in arc_geometry:
            cx, cy = pts[centre_name]
            lo, hi = (0.0, math.degrees(ang)) if ang >= 0 else (math.degrees(ang), 0.0)
            ax.add_patch(Arc((cx, cy), 2 * radius, 2 * radius, theta1=lo, theta2=hi, color="0.2",
                             linewidth=0.9, zorder=2))
            mid = math.radians(0.5 * (lo + hi))
            ax.text(cx + radius * math.cos(mid) + 0.02 * span, cy + radius * math.sin(mid),
                    f"{sym(name)} = {deg_text(values[name])}", fontsize=8.5, ha="left", va="center", zorder=6,
                    bbox=label_box)
        # the solved unknowns, beside the drawing
        lines = [f"{sym(input_name(sweep))} = {deg_text(at)}"]
        for name, v in zip(sweep.unknowns, q):
            lines.append(f"{sym(name)} = {math.degrees(v):.3f}°".replace("-", "−") if is_angle(sweep, name)
                         else f"{sym(name)} = {value_text(v)} {unit}")
        ax.text(1.03, 1.0, "\n".join(lines), transform=ax.transAxes, ha="left", va="top", fontsize=9,
                zorder=7, bbox={"boxstyle": "square,pad=0.4", "facecolor": "white", "edgecolor": "0.6"})
        _setup_mechanism_axes(ax, sweep, xlim, ylim)
        ax.set_title(f"{mech.name} at {sym(input_name(sweep))} = {deg_text(at)}")
    return fig

"""Figures of curves against the input angle: positions, dq/dθ, velocities and accelerations."""

from __future__ import annotations

import math
from typing import Iterable, Mapping, Sequence

import numpy as np

from ..errors import InputError
from .labels import (
    angle_text, axis_label, axis_unit, check_points, check_unknown, deg_text, degree_ticks, derived_of, frame_column,
    frame_input, input_label, input_name, is_angle, length_unit, mechanism_title, quantities_of, rate_columns, sig5, sym,
    tex, uniform_step,
)
from .arguments import need_angles, need_frame, need_frames, need_names, need_sweep
from .ends import END_LABEL, end_mask, frame_ends, scheme_reach
from .series import sampled, with_rates
from .style import CYCLE, SOURCE_STYLE, new_figure, shared_doc, source_label, source_style, style

__all__ = ["acceleration_comparison", "derivative", "difference", "kinematics", "position", "slider"]


def _plot_estimate(ax, x, y, ends, label: str, style_: dict) -> None:
    """A finite-difference estimate: its interior as a line labelled `label`, its end-stencil values as markers.

    `ends` is the mask of :func:`numkin.figures.ends.end_mask`; the line
    holds NaN there, so every drawn value is named by the stencil that made it.
    """
    y = np.asarray(y, dtype=float)
    ax.plot(x, np.where(ends, np.nan, y), label=label, **style_)
    if ends.any():
        ax.plot(np.asarray(x)[ends], y[ends], linestyle="none", marker="s", markersize=5.0, markerfacecolor="none",
                markeredgecolor=style_["color"], markeredgewidth=1.2, label=f"{label}: {END_LABEL}")


@shared_doc
def position(sweep, names: Sequence[str] | None = None):
    """Unknowns and derived quantities against the input angle (angles in degrees, lengths in the sweep's unit).

    Parameters
    ----------
    sweep : Sweep
    names : str or sequence of str, optional
        Unknowns, or derived quantities of the mechanism (``"mu"``, see
        :meth:`numkin.Mechanism.add_quantities`), to draw; default all the
        unknowns, then the derived quantities. Angles and lengths go to
        separate panels.

    {{returns_figure}}

    {{example_homework}}
    >>> fig = figures.position(sweep, ["phi"])
    >>> fig.axes[0].get_ylabel()
    '$\\\\phi$ [deg]'
    >>> figures.save(fig, "/tmp/numkin-doc-phi", ["png"])[0].name
    'numkin-doc-phi.png'
    """
    need_sweep(sweep, "position")
    names = need_names(names, "names", "position")
    if isinstance(names, str):
        names = [names]
    if names is None:
        names = [*sweep.unknowns, *derived_of(sweep)]
    else:
        names = [check_unknown(sweep, n, "position: names") for n in names]
    if not names:
        raise InputError("names: no unknown to draw")
    groups: dict[str, list[str]] = {}
    for n in names:
        groups.setdefault("deg" if is_angle(sweep, n) else length_unit(sweep), []).append(n)
    x = np.degrees(sweep.inputs)
    with style():
        fig, axes = new_figure(len(groups), 1, sharex=True, size=(6.4, 2.2 + 2.0 * len(groups)))
        for ax, (unit, group) in zip(axes[:, 0], groups.items()):
            for k, n in enumerate(group):
                y = sampled(sweep, n)
                y = np.degrees(y) if unit == "deg" else y
                ax.plot(x, y, color=CYCLE[k % len(CYCLE)], label=sym(n))
            what = "angle" if unit == "deg" else "length"
            ax.set_ylabel(f"{sym(group[0])} [{unit}]" if len(group) == 1
                          else f"{what} {', '.join(sym(n) for n in group)} [{unit}]")
            if len(group) > 1:
                ax.legend(loc="best")
        axes[-1, 0].set_xlabel(input_label(sweep))
        degree_ticks(axes[-1, 0], x)
        title = f"{', '.join(sym(n) for n in names)} against {sym(input_name(sweep))}"
        head = mechanism_title(sweep.mechanism)
        _title(fig, axes[0, 0], head, title)
    return fig


def _title(fig, ax, head: str, title: str) -> None:
    """``head: title`` on one line, or on two lines when the rendered line would not fit in the figure's width.

    The width is measured by the figure's renderer, in the title's font,
    less a margin of 3 % on each side.
    """
    text = ax.set_title(f"{head}: {title}")
    width = text.get_window_extent(fig.canvas.get_renderer()).width
    if width > 0.94 * fig.bbox.width:
        text.set_text(f"{head}\n{title}")


def _side_columns(fig, panels, texts, box: dict) -> None:
    """Beside each panel its legend, and under it a box of the lines of `texts` for that panel.

    The box hangs from the legend's lower edge (from the panel's top without
    a legend), so the two never overlap; the figure is made taller when a
    column needs more height than a panel of the default figure has (the
    layout engine would otherwise widen the gap under that panel).
    """
    fontsize = 8.0
    pad = 0.3 * fontsize  # the box's pad, in points (its boxstyle's pad is in font sizes)
    gap = 5.0
    renderer = fig.canvas.get_renderer()
    tallest = 0.0  # pixels at the figure's dpi
    for panel, lines in zip(panels, texts):
        legend = None
        height = 0.0
        if panel.get_legend_handles_labels()[0]:
            legend = panel.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
            height += legend.get_window_extent(renderer).height
        if lines:
            where = ({"xy": (0.0, 0.0), "xycoords": legend, "xytext": (pad, -pad - gap)} if legend is not None
                     else {"xy": (1.02, 1.0), "xycoords": "axes fraction", "xytext": (pad, -pad)})
            text = panel.annotate("\n".join(lines), **where, textcoords="offset points", ha="left", va="top",
                                  fontsize=fontsize, bbox=box, zorder=6, annotation_clip=False)
            space = 2 * pad + (gap if legend is not None else 0.0)  # points
            height += text.get_window_extent(renderer).height + space * fig.dpi / 72
        tallest = max(tallest, height)
    # a panel of the default figure: its height less the title, axis label and gaps (about 1.25 in)
    width, height = fig.get_size_inches()
    needed = len(panels) * (tallest / fig.dpi + 0.1) + 1.25
    if needed > height:
        fig.set_size_inches(width, math.ceil(needed * 10) / 10)


def _derivative_units(sweep, name: str) -> tuple[str, str]:
    if is_angle(sweep, name):
        return "rad/rad", "rad/rad²"
    u = length_unit(sweep)
    return f"{u}/rad", f"{u}/rad²"


@shared_doc
def derivative(sweep, name: str, schemes: Sequence[str] = ("forward", "centred")):
    """dq/dθ of one unknown or derived quantity by finite differences of the sweep, all schemes on one graph.

    Derivatives are per radian of input (``h`` = the sweep's step in rad),
    with the open-grid stencils of :mod:`numkin.derivatives`: each scheme's
    curve holds the points its own stencil reaches, and the values of the
    one-sided end stencils are separate markers with their own legend entry.
    The input axis is in degrees.

    Parameters
    ----------
    {{uniform_sweep_name}}
    schemes : sequence of str
        First-derivative schemes of :mod:`numkin.derivatives`.

    {{returns_figure}}

    {{example_homework}}
    >>> fig = figures.derivative(sweep, "phi")
    >>> [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    ['forward', 'forward: one-sided end stencil', 'centred', 'centred: one-sided end stencil']
    >>> figures.save(fig, "/tmp/numkin-doc-dphi", ["png"])[0].suffix
    '.png'
    """
    from .. import derivatives as fd

    need_sweep(sweep, "derivative")
    check_unknown(sweep, name, "derivative: name")
    schemes = need_names(schemes, "schemes", "derivative")
    h = uniform_step(sweep)
    if isinstance(schemes, str):
        schemes = [schemes]
    resolved = []
    for s in schemes:
        sch = fd.get_scheme(s)
        if sch.derivative != 1:
            raise InputError(f"schemes: {s!r} estimates a second derivative; give first-derivative schemes")
        resolved.append(sch.name)
    x = np.degrees(sweep.inputs)
    y = sampled(sweep, name)
    t, ti = tex(name), tex(input_name(sweep))
    unit, _ = _derivative_units(sweep, name)
    with style():
        fig, axes = new_figure()
        ax = axes[0, 0]
        for k, s in enumerate(resolved):
            _plot_estimate(ax, x, fd.differentiate(y, h, method=s), end_mask(x.size, scheme_reach([s])),
                           source_label(s), source_style(s, k))
        ax.axhline(0.0, color="black", linewidth=0.5)
        ax.set_xlabel(input_label(sweep))
        ax.set_ylabel(f"$d{t}/d{ti}$ [{unit}]")
        degree_ticks(ax, x)
        ax.legend(loc="best")
        ax.set_title(f"$d{t}/d{ti}$ by finite differences, $h$ = {deg_text(h)}")
    return fig


@shared_doc
def difference(sweep, name: str):
    """Δ = ``|centred − forward|`` dq/dθ over θ, on twin axes with d²q/dθ².

    The leading error of the forward difference is ``(h/2) q''``, that of
    the centred one is of order h²; so Δ ≈ ``(h/2) |q''|`` and Δ → 0 where
    q'' = 0. The zeros of q'' are marked by dotted lines. Both curves are
    drawn at the interior points of the sweep, where each is the stencil
    its label names (the open grid's one-sided end stencils are left out).

    Parameters
    ----------
    {{uniform_sweep_name}}

    {{returns_figure}}

    {{example_homework}}
    >>> fig = figures.difference(sweep, "phi")
    >>> len(fig.axes)   # Δ and the twin axis of d2phi/dtheta2
    2
    >>> figures.save(fig, "/tmp/numkin-doc-delta", ["png"])[0].suffix
    '.png'
    """
    from .. import derivatives as fd

    need_sweep(sweep, "difference")
    check_unknown(sweep, name, "difference: name")
    h = uniform_step(sweep)
    y = sampled(sweep, name)
    # interior points only: there every curve is the stencil its label names (no one-sided end stencils)
    delta = np.abs(fd.centred(y, h) - fd.forward(y, h))
    delta[end_mask(delta.size, scheme_reach(["centred", "forward"]))] = np.nan
    second = fd.second_difference(y, h)
    second[end_mask(second.size, scheme_reach(["second_difference"]))] = np.nan
    x = np.degrees(sweep.inputs)
    t, ti = tex(name), tex(input_name(sweep))
    unit1, unit2 = _derivative_units(sweep, name)
    # zeros of q'' between interior samples (linear interpolation of the sign change)
    s = second[1:-1]
    k = np.flatnonzero(np.sign(s[:-1]) * np.sign(s[1:]) < 0) + 1
    zeros = x[k] - second[k] * (x[k + 1] - x[k]) / (second[k + 1] - second[k])
    with style():
        fig, axes = new_figure(size=(6.8, 4.8))
        ax = axes[0, 0]
        ax2 = ax.twinx()
        ax2.grid(False)
        ax2.spines["right"].set_visible(True)
        c1, c2 = "#8E44AD", "#0072B2"
        l1 = ax.plot(x, delta, color=c1, label=rf"$\Delta$ = |centred − forward| $d{t}/d{ti}$")
        l2 = ax2.plot(x, second, color=c2, linestyle="--", label=f"$d^2{t}/d{ti}^2$ (second difference)")
        ax2.axhline(0.0, color=c2, linewidth=0.5)
        lines = l1 + l2
        for j, z in enumerate(zeros):
            v = ax.axvline(z, color="0.45", linestyle=":", linewidth=1.0,
                           label=f"$d^2{t}/d{ti}^2 = 0$" if j == 0 else None)
            if j == 0:
                lines.append(v)
        ax.set_ylim(bottom=0.0)
        ax.set_xlabel(input_label(sweep))
        ax.set_ylabel(rf"$\Delta$ [{unit1}]", color=c1)
        ax2.set_ylabel(f"$d^2{t}/d{ti}^2$ [{unit2}]", color=c2)
        ax.tick_params(axis="y", colors=c1)
        ax2.tick_params(axis="y", colors=c2)
        degree_ticks(ax, x)
        ax.legend(lines, [ln.get_label() for ln in lines], loc="upper center", bbox_to_anchor=(0.5, -0.14), ncols=3,
                  fontsize=8)
        ax.set_title(rf"$\Delta \to 0$ where $d^2{t}/d{ti}^2 = 0$ ($h$ = {deg_text(h)})")
    return fig


@shared_doc
def kinematics(
    sweep,
    name: str,
    *,
    analytic=None,
    finite: Mapping | None = None,
    check_angles: Iterable[float] = (),
    title: str | None = None,
):
    """Position, velocity and acceleration of one unknown or derived quantity against the input angle.

    Three panels: the unknown from the sweep; its velocity and acceleration
    from each finite-difference scheme and from the analytic solution,
    whichever are given; each check angle marked, with its values. On an
    open grid the values of the one-sided end stencils are markers of their
    own (see :mod:`numkin.figures.ends`), and a check value taken from one
    says so.

    A derived quantity of the mechanism (``"mu"``, see
    :meth:`numkin.Mechanism.add_quantities`) is drawn as an unknown is: its
    values from its expression at the solved unknowns (an angle unwrapped
    and in degrees); its exact rates from
    :func:`numkin.analytic.derived_kinematics` at the analytic frame's input
    speed, unless the frame holds them already; its finite-difference rates
    by each frame's own schemes applied to its sampled values (see
    :func:`numkin.figures.series.with_rates`). Where its expression is
    undefined (``acos`` of more than 1) its samples are NaN, and so is every
    rate whose stencil reaches one: the curves break there. A frame that
    cannot give it rates (its attrs lost, its inputs not the sweep's) is
    refused by name.

    Parameters
    ----------
    sweep : Sweep
    name : str
        The unknown (``"beta"``, ``"x"``) or derived quantity (``"mu"``).
    analytic : DataFrame, optional
        From :func:`numkin.analytic.kinematics`: columns ``omega_<name>``,
        ``alpha_<name>`` (angles) or ``v_<name>``, ``a_<name>`` (lengths).
    finite : mapping of str to DataFrame, optional
        Scheme name -> frame from :func:`numkin.kinematics.finite_difference`.
    check_angles : iterable of float
        Inputs (rad) to mark and annotate (those outside the sweep are ignored).
    title : str, optional

    {{returns_figure}}

    {{example_figures}}
    >>> from numkin.kinematics import finite_difference
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    >>> fd = {"centred": finite_difference(sweep, "450 rad/min")}
    >>> fig = figures.kinematics(sweep, "beta", finite=fd, check_angles=[np.radians(100)])
    >>> fig.axes[1].get_ylabel()
    '$\\\\omega_{\\\\beta}$ [rad/s]'
    >>> figures.save(fig, "/tmp/numkin-doc-beta", ["png"])[0].suffix
    '.png'
    """
    need_sweep(sweep, "kinematics")
    check_unknown(sweep, name, "kinematics: name")
    need_frame(analytic, "analytic", "kinematics")
    finite = need_frames(finite, "finite", "kinematics")
    check_angles = need_angles(check_angles, "check_angles", "kinematics")
    analytic, finite = with_rates(sweep, name, analytic, finite, where="kinematics")
    vcol, acol = rate_columns(sweep, name)
    # the sources of each panel: every frame that holds its column, analytic last (drawn on top)
    panels = []
    for col in (vcol, acol):
        src = [(key, frame) for key, frame in finite.items() if col in frame.columns]
        if analytic is not None and col in analytic.columns:
            src.append(("analytic", analytic))
        panels.append(src)
    if not panels[0] and not panels[1]:
        raise InputError(
            f"kinematics of {name!r}: no analytic or finite-difference frame holds {vcol!r} or {acol!r}"
        )
    quantities = quantities_of(sweep, name)  # position, velocity, acceleration: each panel's symbol and unit
    labels = [axis_label(q) for q in quantities]
    units = [axis_unit(q) for q in quantities]
    x = np.degrees(sweep.inputs)
    checks = check_points(check_angles, sweep.inputs)
    pos = sampled(sweep, name)
    pos = np.degrees(pos) if quantities[0].in_degrees else pos
    box = {"boxstyle": "square,pad=0.3", "facecolor": "white", "edgecolor": "0.7", "alpha": 0.9}
    with style():
        fig, axes = new_figure(3, 1, sharex=True, size=(8.4, 7.6))
        ax0 = axes[0, 0]
        ax0.plot(x, pos, color="black", linewidth=1.2)
        ax0.set_ylabel(labels[0])
        for j, (panel, col, src) in enumerate(zip(axes[1:, 0], (vcol, acol), panels), start=1):
            panel.set_ylabel(labels[j])
            panel.axhline(0.0, color="black", linewidth=0.4)
            if not src:
                panel.text(0.5, 0.5, "not computed", transform=panel.transAxes, ha="center", va="center",
                           color="0.4")
                continue
            for k, (key, frame) in enumerate(src):
                _plot_estimate(panel, np.degrees(frame_input(frame, sweep)), frame[col],
                               end_mask(len(frame), frame_ends(key, frame, j)), source_label(key),
                               source_style(key, k))
        # check points: a marker on each curve, the values in one box per panel
        texts = {0: [], 1: [], 2: []}
        for a in checks:
            for j, panel in enumerate(axes[:, 0]):
                panel.axvline(math.degrees(a), color="0.4", linestyle=":", linewidth=0.9)
            k = sweep.index(a)
            ax0.plot(x[k], pos[k], "o", color="black", markersize=5, zorder=5)
            value = angle_text(math.radians(pos[k])) if quantities[0].in_degrees else f"{sig5(pos[k])} {units[0]}"
            texts[0].append(f"{sym(name)}({deg_text(sweep.inputs[k])}) = {value}")
            for j, (panel, col, src) in enumerate(zip(axes[1:, 0], (vcol, acol), panels), start=1):
                if not src:
                    continue
                lines = []
                for n_key, (key, frame) in enumerate(src):
                    xin = frame_input(frame, sweep)
                    i = int(np.argmin(np.abs(xin - a)))
                    v = float(frame[col].iloc[i])
                    st = source_style(key, n_key)
                    panel.plot(math.degrees(xin[i]), v, "o", color=st["color"], markersize=5, zorder=5)
                    how = f" ({END_LABEL})" if end_mask(len(frame), frame_ends(key, frame, j))[i] else ""
                    lines.insert(0, f"  {source_label(key)}{how}: {sig5(v)} {units[j]}")
                texts[j] += [f"${quantities[j].symbol}$ at {sym(input_name(sweep))} = {deg_text(a)}", *lines]
        # legends and check values beside the panels, nothing hiding the curves
        _side_columns(fig, axes[:, 0], [texts[j] for j in range(3)], box)
        axes[-1, 0].set_xlabel(input_label(sweep))
        degree_ticks(axes[-1, 0], x)
        ax0.set_title(title or f"{mechanism_title(sweep.mechanism)}: {sym(name)}, velocity and acceleration")
    return fig


@shared_doc
def slider(sweep, name: str | None = None, *, analytic=None, finite: Mapping | None = None,
           check_angles: Iterable[float] = ()):
    """x, v and a of a slider (a length unknown) against the input angle.

    :func:`kinematics` for a length unknown (or a length-valued derived
    quantity): the first length unknown of the sweep when `name` is not given.

    {{example_figures}}
    >>> from numkin.analytic import kinematics
    >>> sweep = linkages.six_bar().sweep(np.radians(np.arange(0, 361)))
    >>> fig = figures.slider(sweep, analytic=kinematics(sweep, "-10 rad/s"))
    >>> fig.axes[2].get_ylabel()
    '$a_{x}$ [cm/s²]'
    >>> figures.save(fig, "/tmp/numkin-doc-slider", ["png"])[0].suffix
    '.png'
    """
    need_sweep(sweep, "slider")
    if name is None:
        lengths = [n for n in sweep.unknowns if not is_angle(sweep, n)]
        if not lengths:
            raise InputError(f"{sweep.mechanism.name} has no length unknown (slider) to draw")
        name = "x" if "x" in lengths else lengths[0]
    what = "" if name in derived_of(sweep) else "slider "  # a derived length is no slider
    return kinematics(
        sweep, name, analytic=analytic, finite=finite, check_angles=check_angles,
        title=f"{mechanism_title(sweep.mechanism)}: {what}{sym(name)}, $v$, $a$",
    )


@shared_doc
def acceleration_comparison(sweep, name: str, analytic, finite: Mapping):
    """Numerical against analytic acceleration of one unknown or derived quantity, and the error of each scheme.

    Top: the acceleration by each finite-difference scheme and the
    analytic one; bottom: the absolute error of each scheme (log scale).
    On an open grid the values of the one-sided end stencils, and their
    errors, are markers of their own (see :mod:`numkin.figures.ends`).

    Parameters
    ----------
    sweep : Sweep
    name : str
        The unknown (``"x"`` for a piston) or a derived quantity, whose
        rates are added to the frames as :func:`kinematics` does.
    analytic : DataFrame
        From :func:`numkin.analytic.kinematics`.
    finite : mapping of str to DataFrame
        Scheme name -> frame from :func:`numkin.kinematics.finite_difference`.

    {{returns_figure}}

    {{example_figures}}
    >>> from numkin.analytic import kinematics
    >>> from numkin.kinematics import finite_difference
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    >>> fig = figures.acceleration_comparison(
    ...     sweep, "x", kinematics(sweep, "6000 rpm"), {"centred": finite_difference(sweep, "6000 rpm")})
    >>> fig.axes[1].get_yscale()
    'log'
    >>> figures.save(fig, "/tmp/numkin-doc-piston", ["png"])[0].suffix
    '.png'
    """
    need_sweep(sweep, "acceleration_comparison")
    check_unknown(sweep, name, "acceleration_comparison: name")
    need_frame(analytic, "analytic", "acceleration_comparison")
    finite = need_frames(finite, "finite", "acceleration_comparison")
    if analytic is None or not finite:
        raise InputError(f"acceleration of {name!r}: needs both the analytic frame and finite-difference frames")
    analytic, finite = with_rates(sweep, name, analytic, finite, where="acceleration_comparison")
    _, acol = rate_columns(sweep, name)
    acceleration = quantities_of(sweep, name)[2]
    alabel, unit = axis_label(acceleration), axis_unit(acceleration)
    xa_in = frame_input(analytic, sweep)
    ya = frame_column(analytic, acol, "analytic kinematics")
    x = np.degrees(xa_in)
    with style():
        from .ticks import log_scale

        fig, axes = new_figure(2, 1, sharex=True, size=(6.4, 6.0), height_ratios=[3, 2])
        ax, axe = axes[:, 0]
        for k, (key, frame) in enumerate(finite.items()):
            xin = frame_input(frame, sweep)
            y = frame_column(frame, acol, f"{key} kinematics")
            st = source_style(key, k)
            ends = end_mask(y.size, frame_ends(key, frame, 2))
            _plot_estimate(ax, np.degrees(xin), y, ends, source_label(key), st)
            if xin.shape == xa_in.shape and np.allclose(xin, xa_in, rtol=0, atol=1e-12):
                err = np.abs(y - ya)
                shown = np.where(err > 0, err, np.nan)
                _plot_estimate(axe, x, shown, ends, source_label(key),
                               {"color": st["color"], "linestyle": "-", "linewidth": 1.2})
        ax.plot(x, ya, label="analytic", **SOURCE_STYLE["analytic"])
        ax.axhline(0.0, color="black", linewidth=0.4)
        ax.set_ylabel(alabel)
        ax.legend(loc="best")
        log_scale(axe, "y")
        if len(axe.get_lines()) > 1:
            axe.legend(loc="best")
        axe.set_ylabel(f"|numerical − analytic| [{unit}]")
        axe.set_xlabel(input_label(sweep))
        degree_ticks(axe, x)
        ax.set_title(f"{mechanism_title(sweep.mechanism)}: ${acceleration.symbol}$, numerical against analytic")
    return fig

"""Figures of sweeps, velocities, accelerations and error tables.

One function per figure. Each takes plain data (a :class:`~numkin.Sweep`,
the DataFrames of :func:`numkin.analytic.kinematics` and
:func:`numkin.kinematics.finite_difference`, the tables of
:mod:`numkin.report`), draws only what it is given and returns a
:class:`matplotlib.figure.Figure` that is not registered with pyplot.
:func:`save` writes it (PNG and SVG by default) and closes it;
:func:`render` draws and saves the figures a scene asks for.

Figures use the package style (``numkin/numkin.mplstyle``: fixed size, dpi
and fonts, matplotlib's defaults underneath, the user's matplotlibrc
ignored), the Agg renderer and no dates or version strings in the files, so
regenerating a figure gives the same bytes. Input angles are drawn in
degrees, every axis is labelled with its unit.

Importing this module does not import matplotlib (the figure functions do),
so :data:`FIGURES` and :func:`parse_spec` can be used to check a scene's
figure list cheaply.

=========================  ======================================================  ====================
name                       figure                                                  needs
=========================  ======================================================  ====================
``position``               unknowns against the input                              sweep
``derivative``             dq/dθ by forward and centred differences                sweep (uniform step)
``difference``             Δ = |centred − forward| with d²q/dθ² on twin axes       sweep (uniform step)
``kinematics``             q, q̇, q̈ against θ: schemes, analytic, check points      analytic and/or finite
``slider``                 x, v, a of a slider                                     analytic and/or finite
``acceleration``           numerical against analytic acceleration, and the error  analytic and finite
``mechanism``              the linkage drawn at one input, dimensions labelled     sweep with points
``convergence``            error against h (log-log), reference slopes 1, 2, 4     convergence table
``work-precision``         error against work (exact evaluation counts)            work-precision table
``roundoff``               error against h down to rounding: the V-curve           roundoff table
``newton``                 Newton's residual per iteration, per Jacobian           newton table
=========================  ======================================================  ====================

A scene names a figure as ``"name"`` or ``"name:unknown"`` (``"kinematics:beta"``),
see :func:`parse_spec`.

Examples
--------
>>> import numpy as np
>>> from numkin import linkages, figures
>>> sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0, 361)))
>>> fig = figures.position(sweep, ["theta4"])
>>> [p.suffix for p in figures.save(fig, "/tmp/numkin-doc-theta4")]
['.png', '.svg']
"""

from __future__ import annotations

import math
import re
import sys
import warnings
from contextlib import contextmanager
from pathlib import Path
from typing import Iterable, Mapping, Sequence

import numpy as np

__all__ = [
    "FIGURES",
    "FigureSkipped",
    "STYLE",
    "acceleration_comparison",
    "convergence",
    "derivative",
    "difference",
    "kinematics",
    "mechanism",
    "newton_residuals",
    "parse_spec",
    "position",
    "render",
    "roundoff",
    "save",
    "slider",
    "style",
    "work_precision",
]

#: The package style file.
STYLE = Path(__file__).with_name("numkin.mplstyle")

#: Figure names a scene may ask for -> one-line description.
FIGURES: dict[str, str] = {
    "position": "unknowns against the input angle",
    "derivative": "dq/dθ by forward and centred differences on one graph",
    "difference": "Δ between the forward and centred dq/dθ, twin axes with d²q/dθ²",
    "kinematics": "position, velocity and acceleration of one unknown: schemes, analytic, check points",
    "slider": "x, v and a of a slider",
    "acceleration": "numerical against analytic acceleration of one unknown, with the error",
    "mechanism": "the linkage drawn at one input angle with its dimensions",
    "convergence": "error against step h (log-log) with reference slopes 1, 2, 4",
    "work-precision": "error against work (evaluations; or against run time)",
    "roundoff": "error against h down to rounding: the V-curve",
    "newton": "Newton's residual per iteration for each Jacobian",
}

#: Figures that take an unknown (``"name:unknown"``).
_WITH_UNKNOWN = ("position", "derivative", "difference", "kinematics", "slider", "acceleration")

#: Metadata written into each format: nothing that changes between runs or versions.
_METADATA = {
    "png": {"Software": None},
    "svg": {"Date": None, "Creator": None},
    "pdf": {"CreationDate": None, "ModDate": None, "Producer": None, "Creator": None},
}

_GREEK = {
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa", "lambda",
    "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega",
    "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi", "Omega",
}

#: Fixed colours and line styles of the derivative sources (others take the colour cycle).
_SOURCE_STYLE = {
    "analytic": {"color": "black", "linestyle": "-", "linewidth": 1.0, "zorder": 4},
    "forward": {"color": "#D55E00", "linestyle": "--", "linewidth": 1.8},
    "backward": {"color": "#CC79A7", "linestyle": "--", "linewidth": 1.8},
    "centred": {"color": "#0072B2", "linestyle": "-", "linewidth": 2.6, "alpha": 0.55},
    "five_point": {"color": "#009E73", "linestyle": ":", "linewidth": 2.0},
    "richardson": {"color": "#E69F00", "linestyle": "-.", "linewidth": 1.6},
    "spectral": {"color": "#56B4E9", "linestyle": "-.", "linewidth": 1.6},
}
_CYCLE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]

#: Dimensions drawn on the ready-made linkages: (from point, to point, symbol, side of the offset).
_DIMENSIONS = {
    "quick-return": [
        ("O1", "O2", "r_1", 1.0), ("O2", "C", "r_6", 1.0), ("O2", "A", "r_2", 1.0),
        ("O1", "A", "r_3", -1.0), ("O1", "B", "r_4", -2.2), ("C", "B", "r_5", 1.0),
    ],
}


class FigureSkipped(UserWarning):
    """A figure a scene asked for could not be drawn from the data at hand."""


class _Missing(Exception):
    """Data a figure needs is absent (render skips the figure)."""


# ============================================================================ style, save
@contextmanager
def style():
    """Context in which numkin draws and saves: matplotlib's defaults plus :data:`STYLE`.

    Examples
    --------
    >>> import matplotlib
    >>> from numkin.figures import style
    >>> with style():
    ...     matplotlib.rcParams["svg.hashsalt"]
    'numkin'
    """
    import matplotlib.style

    with matplotlib.style.context(str(STYLE), after_reset=True):
        yield


def _new_figure(nrows=1, ncols=1, *, size=None, sharex=False, height_ratios=None):
    """A Figure with an Agg canvas (not known to pyplot) and a grid of axes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    gridspec = {"height_ratios": height_ratios} if height_ratios else None
    axes = fig.subplots(nrows, ncols, sharex=sharex, squeeze=False, gridspec_kw=gridspec)
    return fig, axes


def _close(fig) -> None:
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close(fig)


def save(fig, path_stem, formats: Sequence[str] = ("png", "svg")) -> list[Path]:
    """Save a figure in each format, deterministically, and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path_stem : str or Path
        Path without the extension; ``".png"``, ``".svg"`` (or ``".pdf"``)
        is appended. Missing folders are created.
    formats : sequence of {"png", "svg", "pdf"}

    Returns
    -------
    list of Path
        The files written, in the order of `formats`.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    >>> [p.name for p in figures.save(figures.position(sweep, ["x"]), "/tmp/numkin-doc-x", ["png"])]
    ['numkin-doc-x.png']
    """
    if isinstance(formats, str):
        formats = (formats,)
    fmts = [str(f).lower().lstrip(".") for f in formats]
    try:
        bad = [f for f in fmts if f not in _METADATA]
        if bad or not fmts:
            raise ValueError(
                f"formats: {bad[0] if bad else 'nothing'!r} is not a figure format numkin writes; "
                f"choose from {sorted(_METADATA)}"
            )
        stem = Path(path_stem)
        stem.parent.mkdir(parents=True, exist_ok=True)
        paths = []
        with style():
            for fmt in fmts:
                path = stem.with_name(f"{stem.name}.{fmt}")
                fig.savefig(path, format=fmt, metadata=_METADATA[fmt])
                paths.append(path)
        return paths
    finally:
        _close(fig)


# ============================================================================ labels
def _tex(name: str) -> str:
    """Mathtext body for a symbol name: ``theta2`` -> ``\\theta_{2}``, ``r3`` -> ``r_{3}``."""
    m = re.fullmatch(r"([A-Za-z]+?)_?(\d+|_[A-Za-z0-9]+)?", name)
    if not m:
        return r"\mathrm{" + re.sub(r"([_{}$\\])", r"\\\1", name) + "}"
    base, sub = m.group(1), (m.group(2) or "").lstrip("_")
    if base in _GREEK:
        base = "\\" + base
    elif len(base) > 1:
        base = r"\mathrm{" + base + "}"
    return base + ("_{" + sub + "}" if sub else "")


def _sym(name: str) -> str:
    return f"${_tex(name)}$"


def _input_name(sweep) -> str:
    return str(sweep.mechanism.input_symbol)


def _input_label(sweep) -> str:
    return f"{_sym(_input_name(sweep))} [deg]"


def _is_angle(sweep, name: str) -> bool:
    return name in sweep.mechanism.angles


def _length_unit(sweep) -> str:
    return sweep.mechanism.length_unit


def _quantity_labels(sweep, name: str) -> tuple[str, str, str]:
    """Axis labels of position, velocity and acceleration of an unknown, with units."""
    t = _tex(name)
    if _is_angle(sweep, name):
        return f"${t}$ [deg]", rf"$\omega_{{{t}}}$ [rad/s]", rf"$\alpha_{{{t}}}$ [rad/s²]"
    u = _length_unit(sweep)
    return f"${t}$ [{u}]", f"$v_{{{t}}}$ [{u}/s]", f"$a_{{{t}}}$ [{u}/s²]"


def _columns(sweep, name: str) -> tuple[str, str]:
    """Velocity and acceleration column names of an unknown in the kinematics frames."""
    return (f"omega_{name}", f"alpha_{name}") if _is_angle(sweep, name) else (f"v_{name}", f"a_{name}")


def _fmt(value: float, zeros: bool = True) -> str:
    """Five significant digits (trailing zeros kept if `zeros`), a true minus sign."""
    text = f"{value:#.5g}" if zeros else f"{value:.5g}"
    if "e" not in text:
        text = text.rstrip(".")
    return text.replace("-", "−")


def _value_text(value: float) -> str:
    """At least three decimals and five significant digits (87.178, 130.767, 0.18330), true minus."""
    v = float(value)
    digits = 3 if v == 0 or not math.isfinite(v) else max(3, 4 - math.floor(math.log10(abs(v))))
    return f"{v:.{digits}f}".replace("-", "−")


def _length_text(value: float) -> str:
    """A dimension: as :func:`_value_text`, trailing zeros dropped (60, 6.5, 130.767, 0.08)."""
    text = _value_text(value)
    return text.rstrip("0").rstrip(".") if "." in text else text


def _deg_text(rad: float) -> str:
    d = math.degrees(rad)
    text = f"{round(d):.0f}°" if abs(d - round(d)) < 1e-6 else f"{d:.2f}°"
    return text.replace("-", "−")


def _degree_ticks(ax, degrees: np.ndarray) -> None:
    """Ticks every 30, 45 or 90 degrees, depending on the span."""
    from matplotlib.ticker import MultipleLocator

    span = float(np.nanmax(degrees) - np.nanmin(degrees)) if degrees.size else 0.0
    if span >= 270:
        ax.xaxis.set_major_locator(MultipleLocator(45 if span <= 400 else 90))
    elif span >= 90:
        ax.xaxis.set_major_locator(MultipleLocator(30))
    ax.set_xlim(float(np.nanmin(degrees)), float(np.nanmax(degrees))) if span > 0 else None


#: Second-derivative scheme -> first-derivative scheme of the same family (same colour).
_FAMILY = {
    "second_difference": "centred", "forward_of_forward": "forward", "centred_of_centred": "richardson",
    "five_point_second": "five_point", "spectral_second": "spectral", "complex_step": "analytic",
    "complex step": "analytic",
}


def _source_label(key: str) -> str:
    return str(key).replace("_", " ")


def _source_style(key: str, k: int) -> dict:
    key = str(key)
    style_ = _SOURCE_STYLE.get(key) or _SOURCE_STYLE.get(_FAMILY.get(key, ""))
    if key in ("complex_step", "complex step"):
        style_ = {"color": "0.45", "linestyle": "-", "linewidth": 1.2}
    if style_ is None:
        style_ = {"color": _CYCLE[k % len(_CYCLE)], "linestyle": "-.", "linewidth": 1.5}
    return dict(style_)


def _check_name(sweep, name: str) -> str:
    if name not in sweep.unknowns:
        raise ValueError(
            f"{name!r} is not an unknown of {sweep.mechanism.name}; unknowns are {list(sweep.unknowns)}"
        )
    return name


def _uniform_step(sweep) -> float:
    h = sweep.step
    if h is None:
        raise ValueError(
            f"sweep of {sweep.mechanism.name}: finite differences need a uniform input step; "
            "sweep a grid like np.radians(np.arange(0, 361))"
        )
    return h


def _frame_input(frame, sweep) -> np.ndarray:
    """Input values (rad) of a kinematics frame: its input column, or the sweep's inputs."""
    col = _input_name(sweep)
    if col in frame.columns:
        return np.asarray(frame[col], dtype=float)
    if len(frame) != len(sweep):
        raise ValueError(
            f"kinematics frame has {len(frame)} rows and no {col!r} column; the sweep has {len(sweep)} inputs"
        )
    return sweep.inputs


def _frame_column(frame, column: str, what: str) -> np.ndarray:
    if column not in frame.columns:
        raise ValueError(f"{what} has no column {column!r}; columns are {list(frame.columns)}")
    return np.asarray(frame[column], dtype=float)


def _check_points(check_angles, inputs) -> list[float]:
    """The check angles (rad) that lie within the range of the inputs."""
    if check_angles is None:
        return []
    if np.ndim(check_angles) == 0:
        check_angles = [check_angles]
    lo, hi = float(np.min(inputs)), float(np.max(inputs))
    tol = 1e-9 * max(1.0, abs(hi))
    return [float(a) for a in check_angles if lo - tol <= float(a) <= hi + tol]


# ============================================================================ sweep figures
def position(sweep, names: Sequence[str] | None = None):
    """Unknowns against the input angle (angles in degrees, lengths in the sweep's unit).

    Parameters
    ----------
    sweep : Sweep
    names : sequence of str, optional
        Unknowns to draw; default all. Angles and lengths go to separate panels.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    >>> fig = figures.position(sweep, ["phi"])
    >>> fig.axes[0].get_ylabel()
    '$\\\\phi$ [deg]'
    >>> figures.save(fig, "/tmp/numkin-doc-phi", ["png"])[0].name
    'numkin-doc-phi.png'
    """
    if isinstance(names, str):
        names = [names]
    names = list(sweep.unknowns) if names is None else [_check_name(sweep, n) for n in names]
    if not names:
        raise ValueError("names: no unknown to draw")
    groups: dict[str, list[str]] = {}
    for n in names:
        groups.setdefault("deg" if _is_angle(sweep, n) else _length_unit(sweep), []).append(n)
    x = np.degrees(sweep.inputs)
    with style():
        fig, axes = _new_figure(len(groups), 1, sharex=True, size=(6.4, 2.2 + 2.0 * len(groups)))
        for ax, (unit, group) in zip(axes[:, 0], groups.items()):
            for k, n in enumerate(group):
                y = np.degrees(sweep[n]) if unit == "deg" else sweep[n]
                ax.plot(x, y, color=_CYCLE[k % len(_CYCLE)], label=_sym(n))
            ax.set_ylabel(f"{_sym(group[0])} [{unit}]" if len(group) == 1 else f"[{unit}]")
            if len(group) > 1:
                ax.legend(loc="best")
        axes[-1, 0].set_xlabel(_input_label(sweep))
        _degree_ticks(axes[-1, 0], x)
        title = ", ".join(_sym(n) for n in names)
        axes[0, 0].set_title(f"{sweep.mechanism.name}: {title} against {_sym(_input_name(sweep))}")
    return fig


def _derivative_units(sweep, name: str) -> tuple[str, str]:
    if _is_angle(sweep, name):
        return "rad/rad", "rad/rad²"
    u = _length_unit(sweep)
    return f"{u}/rad", f"{u}/rad²"


def derivative(sweep, name: str, schemes: Sequence[str] = ("forward", "centred")):
    """dq/dθ of one unknown by finite differences of the sweep, all schemes on one graph.

    Derivatives are per radian of input (``h`` = the sweep's step in rad),
    with the open-grid stencils of :mod:`numkin.derivatives` (one-sided,
    same order, at the two ends); the input axis is in degrees.

    Parameters
    ----------
    sweep : Sweep
        On a uniform grid.
    name : str
        The unknown.
    schemes : sequence of str
        First-derivative schemes of :mod:`numkin.derivatives`.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    >>> fig = figures.derivative(sweep, "phi")
    >>> [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    ['forward', 'centred']
    >>> figures.save(fig, "/tmp/numkin-doc-dphi", ["png"])[0].suffix
    '.png'
    """
    from . import derivatives as fd

    _check_name(sweep, name)
    h = _uniform_step(sweep)
    if isinstance(schemes, str):
        schemes = [schemes]
    resolved = []
    for s in schemes:
        sch = fd.get_scheme(s)
        if sch.derivative != 1:
            raise ValueError(f"schemes: {s!r} estimates a second derivative; give first-derivative schemes")
        resolved.append(sch.name)
    x = np.degrees(sweep.inputs)
    t, ti = _tex(name), _tex(_input_name(sweep))
    unit, _ = _derivative_units(sweep, name)
    with style():
        fig, axes = _new_figure()
        ax = axes[0, 0]
        for k, s in enumerate(resolved):
            ax.plot(x, fd.differentiate(sweep[name], h, method=s), label=_source_label(s), **_source_style(s, k))
        ax.axhline(0.0, color="black", linewidth=0.5)
        ax.set_xlabel(_input_label(sweep))
        ax.set_ylabel(f"$d{t}/d{ti}$ [{unit}]")
        _degree_ticks(ax, x)
        ax.legend(loc="best")
        ax.set_title(f"$d{t}/d{ti}$ by finite differences, $h$ = {_deg_text(h)}")
    return fig


def difference(sweep, name: str):
    """Δ = |centred − forward| dq/dθ over θ, on twin axes with d²q/dθ².

    The leading error of the forward difference is ``(h/2) q''``, that of
    the centred one is of order h²; so Δ ≈ (h/2)|q''| and Δ → 0 where
    q'' = 0. The zeros of q'' are marked by dotted lines.

    Parameters
    ----------
    sweep : Sweep
        On a uniform grid.
    name : str
        The unknown.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    >>> fig = figures.difference(sweep, "phi")
    >>> len(fig.axes)   # Δ and the twin axis of d2phi/dtheta2
    2
    >>> figures.save(fig, "/tmp/numkin-doc-delta", ["png"])[0].suffix
    '.png'
    """
    from . import derivatives as fd

    _check_name(sweep, name)
    h = _uniform_step(sweep)
    y = sweep[name]
    delta = np.abs(fd.centred(y, h) - fd.forward(y, h))
    second = fd.second_difference(y, h)
    x = np.degrees(sweep.inputs)
    t, ti = _tex(name), _tex(_input_name(sweep))
    unit1, unit2 = _derivative_units(sweep, name)
    # zeros of q'' between interior samples (linear interpolation of the sign change)
    s = second[1:-1]
    k = np.flatnonzero(np.sign(s[:-1]) * np.sign(s[1:]) < 0) + 1
    zeros = x[k] - second[k] * (x[k + 1] - x[k]) / (second[k + 1] - second[k])
    with style():
        fig, axes = _new_figure(size=(6.8, 4.2))
        ax = axes[0, 0]
        ax2 = ax.twinx()
        ax2.grid(False)
        ax2.spines["right"].set_visible(True)
        c1, c2 = "#8E44AD", "#0072B2"
        l1 = ax.plot(x, delta, color=c1, label=rf"$\Delta = |(d{t}/d{ti})_C - (d{t}/d{ti})_{{FW}}|$")
        l2 = ax2.plot(x, second, color=c2, linestyle="--", label=f"$d^2{t}/d{ti}^2$ (second difference)")
        ax2.axhline(0.0, color=c2, linewidth=0.5)
        lines = l1 + l2
        for j, z in enumerate(zeros):
            v = ax.axvline(z, color="0.45", linestyle=":", linewidth=1.0,
                           label=f"$d^2{t}/d{ti}^2 = 0$" if j == 0 else None)
            if j == 0:
                lines.append(v)
        ax.set_ylim(bottom=0.0)
        ax.set_xlabel(_input_label(sweep))
        ax.set_ylabel(rf"$\Delta$ [{unit1}]", color=c1)
        ax2.set_ylabel(f"$d^2{t}/d{ti}^2$ [{unit2}]", color=c2)
        ax.tick_params(axis="y", colors=c1)
        ax2.tick_params(axis="y", colors=c2)
        _degree_ticks(ax, x)
        ax.legend(lines, [ln.get_label() for ln in lines], loc="upper right")
        ax.set_title(rf"$\Delta \to 0$ where $d^2{t}/d{ti}^2 = 0$ ($h$ = {_deg_text(h)})")
    return fig


def kinematics(
    sweep,
    name: str,
    *,
    analytic=None,
    finite: Mapping | None = None,
    check_angles: Iterable[float] = (),
    title: str | None = None,
):
    """Position, velocity and acceleration of one unknown against the input angle.

    Three panels: the unknown from the sweep; its velocity and acceleration
    from each finite-difference scheme and from the analytic solution,
    whichever are given; each check angle marked, with its values.

    Parameters
    ----------
    sweep : Sweep
    name : str
        The unknown (``"beta"``, ``"x"``).
    analytic : DataFrame, optional
        From :func:`numkin.analytic.kinematics`: columns ``omega_<name>``,
        ``alpha_<name>`` (angles) or ``v_<name>``, ``a_<name>`` (lengths).
    finite : mapping of str to DataFrame, optional
        Scheme name -> frame from :func:`numkin.kinematics.finite_difference`.
    check_angles : iterable of float
        Inputs (rad) to mark and annotate (those outside the sweep are ignored).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> from numkin.kinematics import finite_difference
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    >>> fd = {"centred": finite_difference(sweep, "450 rad/min")}
    >>> fig = figures.kinematics(sweep, "beta", finite=fd, check_angles=[np.radians(100)])
    >>> fig.axes[1].get_ylabel()
    '$\\\\omega_{\\\\beta}$ [rad/s]'
    >>> figures.save(fig, "/tmp/numkin-doc-beta", ["png"])[0].suffix
    '.png'
    """
    _check_name(sweep, name)
    finite = dict(finite or {})
    vcol, acol = _columns(sweep, name)
    # the sources of each panel: every frame that holds its column, analytic last (drawn on top)
    panels = []
    for col in (vcol, acol):
        src = [(key, frame) for key, frame in finite.items() if col in frame.columns]
        if analytic is not None and col in analytic.columns:
            src.append(("analytic", analytic))
        panels.append(src)
    if not panels[0] and not panels[1]:
        raise ValueError(
            f"kinematics of {name!r}: no analytic or finite-difference frame holds {vcol!r} or {acol!r}"
        )
    labels = _quantity_labels(sweep, name)
    units = [_unit_of(lab) for lab in labels]
    x = np.degrees(sweep.inputs)
    checks = _check_points(check_angles, sweep.inputs)
    pos = np.degrees(sweep[name]) if _is_angle(sweep, name) else sweep[name]
    box = {"boxstyle": "square,pad=0.3", "facecolor": "white", "edgecolor": "0.7", "alpha": 0.9}
    with style():
        fig, axes = _new_figure(3, 1, sharex=True, size=(8.4, 7.6))
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
                panel.plot(np.degrees(_frame_input(frame, sweep)), np.asarray(frame[col], dtype=float),
                           label=_source_label(key), **_source_style(key, k))
        # check points: a marker on each curve, the values in one box per panel
        texts = {0: [], 1: [], 2: []}
        for a in checks:
            for j, panel in enumerate(axes[:, 0]):
                panel.axvline(math.degrees(a), color="0.4", linestyle=":", linewidth=0.9)
            k = sweep.index(a)
            ax0.plot(x[k], pos[k], "o", color="black", markersize=5, zorder=5)
            texts[0].append(f"{_sym(name)}({_deg_text(sweep.inputs[k])}) = {_fmt(pos[k])} {units[0]}")
            for j, (panel, col, src) in enumerate(zip(axes[1:, 0], (vcol, acol), panels), start=1):
                if not src:
                    continue
                lines = []
                for n_key, (key, frame) in enumerate(src):
                    xin = _frame_input(frame, sweep)
                    i = int(np.argmin(np.abs(xin - a)))
                    v = float(frame[col].iloc[i])
                    st = _source_style(key, n_key)
                    panel.plot(math.degrees(xin[i]), v, "o", color=st["color"], markersize=5, zorder=5)
                    lines.insert(0, f"  {_source_label(key)}: {_fmt(v)} {units[j]}")
                sym = labels[j].split(" [")[0]
                texts[j] += [f"{sym} at {_sym(_input_name(sweep))} = {_deg_text(a)}", *lines]
        # legends and check values beside the panels: nothing hides the curves
        for j, panel in enumerate(axes[:, 0]):
            if panel.get_legend_handles_labels()[0]:
                panel.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
            if texts[j]:
                panel.text(1.02, 0.0, "\n".join(texts[j]), transform=panel.transAxes, ha="left", va="bottom",
                           fontsize=8, bbox=box, zorder=6)
        axes[-1, 0].set_xlabel(_input_label(sweep))
        _degree_ticks(axes[-1, 0], x)
        ax0.set_title(title or f"{sweep.mechanism.name}: {_sym(name)}, velocity and acceleration")
    return fig


def slider(sweep, name: str | None = None, *, analytic=None, finite: Mapping | None = None,
           check_angles: Iterable[float] = ()):
    """x, v and a of a slider (a length unknown) against the input angle.

    :func:`kinematics` for a length unknown: the first one of the sweep
    when `name` is not given.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> from numkin.analytic import kinematics
    >>> sweep = linkages.six_bar().sweep(np.radians(np.arange(0, 361)))
    >>> fig = figures.slider(sweep, analytic=kinematics(sweep, "-10 rad/s"))
    >>> fig.axes[2].get_ylabel()
    '$a_{x}$ [cm/s²]'
    >>> figures.save(fig, "/tmp/numkin-doc-slider", ["png"])[0].suffix
    '.png'
    """
    if name is None:
        lengths = [n for n in sweep.unknowns if not _is_angle(sweep, n)]
        if not lengths:
            raise ValueError(f"{sweep.mechanism.name} has no length unknown (slider) to draw")
        name = "x" if "x" in lengths else lengths[0]
    return kinematics(
        sweep, name, analytic=analytic, finite=finite, check_angles=check_angles,
        title=f"{sweep.mechanism.name}: slider {_sym(name)}, $v$, $a$",
    )


def acceleration_comparison(sweep, name: str, analytic, finite: Mapping):
    """Numerical against analytic acceleration of one unknown, and the error of each scheme.

    Top: the acceleration by each finite-difference scheme and the
    analytic one; bottom: the absolute error of each scheme (log scale).

    Parameters
    ----------
    sweep : Sweep
    name : str
        The unknown (``"x"`` for a piston).
    analytic : DataFrame
        From :func:`numkin.analytic.kinematics`.
    finite : mapping of str to DataFrame
        Scheme name -> frame from :func:`numkin.kinematics.finite_difference`.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
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
    _check_name(sweep, name)
    if analytic is None or not finite:
        raise ValueError(f"acceleration of {name!r}: needs both the analytic frame and finite-difference frames")
    _, acol = _columns(sweep, name)
    _, _, alabel = _quantity_labels(sweep, name)
    unit = _unit_of(alabel)
    xa_in = _frame_input(analytic, sweep)
    ya = _frame_column(analytic, acol, "analytic kinematics")
    x = np.degrees(xa_in)
    with style():
        fig, axes = _new_figure(2, 1, sharex=True, size=(6.4, 6.0), height_ratios=[3, 2])
        ax, axe = axes[:, 0]
        for k, (key, frame) in enumerate(finite.items()):
            xin = _frame_input(frame, sweep)
            y = _frame_column(frame, acol, f"{key} kinematics")
            st = _source_style(key, k)
            ax.plot(np.degrees(xin), y, label=_source_label(key), **st)
            if xin.shape == xa_in.shape and np.allclose(xin, xa_in, rtol=0, atol=1e-12):
                err = np.abs(y - ya)
                shown = np.where(err > 0, err, np.nan)
                axe.plot(x, shown, label=_source_label(key), color=st["color"], linestyle="-", linewidth=1.2)
        ax.plot(x, ya, label="analytic", **_SOURCE_STYLE["analytic"])
        ax.axhline(0.0, color="black", linewidth=0.4)
        ax.set_ylabel(alabel)
        ax.legend(loc="best")
        axe.set_yscale("log")
        axe.set_ylabel(f"|numerical − analytic| [{unit}]")
        axe.set_xlabel(_input_label(sweep))
        _degree_ticks(axe, x)
        ax.set_title(f"{sweep.mechanism.name}: {alabel.split(' [')[0]}, numerical against analytic")
    return fig


# ============================================================================ drawing the linkage
def _slider_points(points: Mapping, ground: Sequence[str]) -> dict:
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


def _bounds(xy_list: Iterable[np.ndarray], margin: float = 0.12):
    xs = np.concatenate([np.ravel(xy[0]) for xy in xy_list])
    ys = np.concatenate([np.ravel(xy[1]) for xy in xy_list])
    xs, ys = xs[np.isfinite(xs)], ys[np.isfinite(ys)]
    x0, x1, y0, y1 = xs.min(), xs.max(), ys.min(), ys.max()
    span = max(x1 - x0, y1 - y0, 1e-9)
    m = margin * span
    return (x0 - m, x1 + m), (y0 - m, y1 + m), span


def _draw_ground(ax, x: float, y: float, size: float, zorder: float = 2.0) -> None:
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


def _link_colors(n: int) -> list[str]:
    return [_CYCLE[k % (len(_CYCLE) - 1)] for k in range(n)]


def _setup_mechanism_axes(ax, sweep, xlim, ylim) -> None:
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    u = _length_unit(sweep)
    ax.set_xlabel(f"$x$ [{u}]")
    ax.set_ylabel(f"$y$ [{u}]")


def _angle_arcs(sweep, pts: Mapping, values: Mapping, segments: Sequence[tuple[str, str]]):
    """(centre, angle, symbol) for the input and angle unknowns that are the direction of a segment."""
    arcs = []
    for name, value in values.items():
        if name != _input_name(sweep) and not _is_angle(sweep, name):
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
            raise ValueError(f"{mech.name}: cannot solve the position at input {_deg_text(at)} to draw it")
        q = np.asarray(res.x, dtype=float).reshape(-1)
    pts = {n: xy[:, 0] for n, xy in mech.point_coordinates(q[:, None], np.array([at])).items()}
    all_pts = sweep.points()
    ground = list(mech.ground or ())
    sliders = _slider_points(all_pts, ground)
    unit = _length_unit(sweep)
    values = {_input_name(sweep): at, **dict(zip(sweep.unknowns, q))}

    if dimensions is None:
        dimensions = next((v for key, v in _DIMENSIONS.items() if mech.name.startswith(key)), None)
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

    xlim, ylim, span = _bounds([xy[:, None] for xy in pts.values()], margin=0.16)
    off = 0.045 * span
    segments = [(p, r) for link in mech.links for p, r in zip(link[:-1], link[1:])] + [(p, r) for p, r, _, _ in dims]
    arcs = _angle_arcs(sweep, pts, values, segments)
    aspect = (ylim[1] - ylim[0]) / (xlim[1] - xlim[0])
    size = (7.4, float(np.clip(4.6 * aspect + 1.0, 3.4, 8.0)))

    with style():
        fig, axes = _new_figure(size=size)
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
            _draw_ground(ax, *pts[name], size=0.025 * span, zorder=2)
        for link, color in zip(mech.links, _link_colors(len(mech.links))):
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
            value = _length_text(length)
            text = f"{value} {unit}" if label is None else f"${label}$ = {value} {unit}"
            _along(a2, b2, text, 0.0 * nrm)
        # plain length labels
        for p, r in plain:
            a, b = pts[p], pts[r]
            v = b - a
            length = float(np.hypot(*v))
            if length > 0:
                _along(a, b, f"{_length_text(length)} {unit}", np.array([-v[1], v[0]]) / length * 0.03 * span)
        # angle arcs
        from matplotlib.patches import Arc

        for centre_name, ang, name, radius in arc_geometry:
            cx, cy = pts[centre_name]
            lo, hi = (0.0, math.degrees(ang)) if ang >= 0 else (math.degrees(ang), 0.0)
            ax.add_patch(Arc((cx, cy), 2 * radius, 2 * radius, theta1=lo, theta2=hi, color="0.2",
                             linewidth=0.9, zorder=2))
            mid = math.radians(0.5 * (lo + hi))
            ax.text(cx + radius * math.cos(mid) + 0.02 * span, cy + radius * math.sin(mid),
                    f"{_sym(name)} = {_deg_text(values[name])}", fontsize=8.5, ha="left", va="center", zorder=6,
                    bbox=label_box)
        # the solved unknowns, beside the drawing
        lines = [f"{_sym(_input_name(sweep))} = {_deg_text(at)}"]
        for name, v in zip(sweep.unknowns, q):
            lines.append(f"{_sym(name)} = {math.degrees(v):.3f}°".replace("-", "−") if _is_angle(sweep, name)
                         else f"{_sym(name)} = {_value_text(v)} {unit}")
        ax.text(1.03, 1.0, "\n".join(lines), transform=ax.transAxes, ha="left", va="top", fontsize=9,
                zorder=7, bbox={"boxstyle": "square,pad=0.4", "facecolor": "white", "edgecolor": "0.6"})
        _setup_mechanism_axes(ax, sweep, xlim, ylim)
        ax.set_title(f"{mech.name} at {_sym(_input_name(sweep))} = {_deg_text(at)}")
    return fig


# ============================================================================ report tables
def _col(table, prefix: str, what: str, required: bool = True):
    """The first column whose name starts with `prefix`."""
    for c in table.columns:
        if str(c).startswith(prefix):
            return c
    if required:
        raise ValueError(f"{what}: no column starting with {prefix!r}; columns are {list(table.columns)}")
    return None


def _quantity_text(q: str) -> tuple[str, str]:
    """``"omega_beta [rad/s]"`` -> (``"$\\omega_{\\beta}$"``, ``"rad/s"``); ``"^2"`` shown as ``"²"``."""
    q = str(q)
    m = re.fullmatch(r"\s*(.*?)\s*\[(.*)\]\s*", q)
    name, unit = (m.group(1), m.group(2)) if m else (q, "")
    unit = unit.replace("^2", "²")
    pm = re.fullmatch(r"(omega|alpha|v|a|vx|vy|ax|ay)_(.+)", name)
    if pm:
        head = {"omega": r"\omega", "alpha": r"\alpha"}.get(pm.group(1), pm.group(1))
        return f"${head}_{{{_tex(pm.group(2))}}}$", unit
    dm = re.fullmatch(r"d(2?)q/dtheta(2?)", name)
    if dm:
        return (r"$d^2q/d\theta^2$" if dm.group(1) else r"$dq/d\theta$"), unit
    return name, unit


def _panel_text(quantity, error: str) -> tuple[str, str]:
    """Title text and error unit of one panel of a report figure (``"–"`` for a relative error)."""
    qtext, unit = _quantity_text(quantity) if quantity is not None else ("", "")
    if "rel" in error:
        unit = "–"
    return qtext, unit


def _unit_of(label: str) -> str:
    """``"$\\omega$ [rad/s]"`` -> ``"rad/s"``: the unit in the last brackets of an axis label."""
    return label.rsplit("[", 1)[1].rstrip("]")


def _order_label(scheme: str, order) -> str:
    """A scheme's legend label, with its formal order when known."""
    return _source_label(scheme) + (f" (order {order})" if order is not None else "")


def _table_caption(table) -> str:
    """The caption a report table carries in its ``attrs`` ("" if none)."""
    return table.attrs.get("caption", "") if hasattr(table, "attrs") else ""


def _groups(table, column: str = "quantity") -> list:
    """(value, sub-table) in order of first appearance; one group if the column is absent."""
    if column not in table.columns:
        return [(None, table)]
    out = []
    for value in dict.fromkeys(table[column]):
        out.append((value, table[table[column] == value]))
    return out


def _positive(values) -> np.ndarray:
    v = np.asarray(values, dtype=float)
    return np.where(v > 0, v, np.nan)


def _plain_log_ticks(axis, values) -> None:
    """Log-axis ticks at 1, 2, 5 x 10^k written as plain numbers, when the data span under 3 decades."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size and v.max() / v.min() < 1e3:
        axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
        axis.set_minor_formatter(NullFormatter())


def _caption_title(caption: str) -> str:
    """The first clause of a report table's caption, ``theta = 100 deg`` written as ``θ = 100°``."""
    head = caption.split(";")[0]
    return re.sub(r"\b(\w+) = ([-0-9.]+) deg\b", lambda m: f"{_sym(m.group(1))} = {m.group(2)}°", head)


def _log_limits(values, pad: float = 3.0) -> tuple[float, float]:
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        return 1e-16, 1.0
    return float(v.min()) / pad, float(v.max()) * pad


def convergence(table, *, error: str = "max abs error"):
    """Error against step h (log-log) for each scheme, with reference slopes 1, 2 and 4.

    Parameters
    ----------
    table : DataFrame
        From :func:`numkin.report.convergence_table`: columns ``scheme``,
        ``formal order``, ``quantity``, ``h [deg]`` and the error column.
        One panel per quantity (velocity schemes, acceleration schemes).
    error : str
        Start of the error column's name: ``"max abs error"`` (default),
        ``"RMS abs error"`` or ``"max rel error"``.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import math
    >>> from numkin import linkages, report, figures
    >>> conv = report.convergence_table(linkages.chained_four_bars(), omega="450 rad/min", quantity="beta",
    ...                                 grids=(36, 72, 180), schemes=("forward", "centred"))
    >>> fig = figures.convergence(conv)
    >>> fig.axes[0].get_xscale(), fig.axes[0].get_yscale()
    ('log', 'log')
    >>> figures.save(fig, "/tmp/numkin-doc-convergence", ["png"])[0].suffix
    '.png'
    """
    what = "convergence table"
    hcol = _col(table, "h [", what)
    ecol = _col(table, error, what)
    scol = _col(table, "scheme", what)
    h_unit = str(hcol)[3:-1]
    groups = _groups(table)
    with style():
        fig, axes = _new_figure(1, len(groups), size=(6.4 if len(groups) == 1 else 9.6, 4.4))
        for ax, (quantity, sub) in zip(axes[0], groups):
            qtext, unit = _panel_text(quantity, error)
            h_all = np.asarray(sub[hcol], dtype=float)
            e_all = _positive(sub[ecol])
            for k, scheme in enumerate(dict.fromkeys(sub[scol])):
                rows = sub[sub[scol] == scheme].sort_values(hcol)
                order = rows["formal order"].iloc[0] if "formal order" in rows.columns else None
                label = _order_label(scheme, order)
                st = _source_style(scheme, k)
                st["linewidth"] = min(st.get("linewidth", 1.5), 1.6)
                st.pop("alpha", None)
                ax.plot(rows[hcol], _positive(rows[ecol]), marker="o", label=label, **st)
            ylo, yhi = _log_limits(e_all)
            hmin, hmax = float(np.nanmin(h_all)), float(np.nanmax(h_all))
            # reference slopes, from the largest step, under the data
            at_max = e_all[np.isclose(h_all, hmax)]
            anchor = float(np.nanmin(at_max)) / 4 if np.isfinite(at_max).any() else yhi / 10
            hh = np.geomspace(hmin, hmax, 50)
            for p, ls in ((1, (0, (6, 2))), (2, (0, (3, 2))), (4, (0, (1, 1.5)))):
                yy = anchor * (hh / hmax) ** p
                ax.plot(hh, yy, color="0.35", linestyle=ls, linewidth=0.9, scalex=False, scaley=False)
                inside = np.flatnonzero(yy >= ylo * 1.5)
                j = inside[0] if inside.size else hh.size - 1
                ax.text(hh[j], yy[j], f"slope {p}", fontsize=7.5, color="0.25", ha="right", va="bottom")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylim(ylo, yhi)
            ax.set_xlim(hmin / 1.6, hmax * 1.3)
            ax.set_xlabel(f"step $h$ [{h_unit}]")
            ax.set_ylabel(f"{error} [{unit}]")
            ax.set_title(f"{qtext}" if qtext else "error against step")
            ax.legend(loc="lower right", fontsize=7.5)
        caption = _table_caption(table)
        if caption:
            fig.suptitle(_caption_title(caption), fontsize=9)
    return fig


def _front(x, y) -> np.ndarray:
    """Pareto front of points (cost x, error y): no other point is no worse in both and better in one.

    Points with a non-finite or non-positive coordinate are not on it.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    out = np.zeros(x.size, dtype=bool)
    for k in np.flatnonzero(ok):
        dominated = ok & (x <= x[k]) & (y <= y[k]) & ((x < x[k]) | (y < y[k]))
        out[k] = not dominated.any()
    return out


#: Markers of the work-precision figure: (marker, size, filled). Methods that give the same points
#: (forward and backward, five-point and Richardson: the same errors on the same grids) stay
#: visible one over the other: a large open marker around a small filled one.
_WP_MARKERS = {
    "analytic": ("o", 4.0, True), "complex step": ("s", 8.0, False),
    "forward": ("^", 8.5, False), "backward": ("v", 4.5, True), "centred": ("o", 4.5, True),
    "five_point": ("D", 8.0, False), "richardson": ("o", 3.5, True), "spectral": ("*", 7.0, True),
    "second_difference": ("o", 4.5, True), "forward_of_forward": ("^", 5.5, True),
    "centred_of_centred": ("v", 5.5, True), "five_point_second": ("D", 8.0, False),
    "spectral_second": ("*", 7.0, True),
}


def work_precision(table, *, work: str = "work", time: str | None = None, error: str = "max abs error"):
    """Error against work (log-log) for each method, the Pareto front ringed; or against run time.

    By default the cost is the table's exact work count (``work
    [evaluations]``: point evaluations of the compiled loop equations plus
    stencil evaluations, see :func:`numkin.report.work_precision_table`),
    the same in every run, so the figure is reproducible byte for byte.
    With `time` the measured run time is drawn instead, and the axis says
    that it varies between runs. The Pareto front (no other point of the
    panel has less cost and no larger error) is computed from the points
    drawn, so it always matches the axes.

    Parameters
    ----------
    table : DataFrame
        From :func:`numkin.report.work_precision_table`: columns ``method``,
        ``quantity``, the work or time column and the error column. One
        panel per quantity.
    work : str
        Start of the work column's name: ``"work"`` (sweep + derivative,
        default), ``"sweep work"`` or ``"derivative work"``.
    time : str, optional
        Start of a time column's name (``"sweep + derivative time"``,
        ``"sweep time"``, ``"derivative time"``): draw the measured time
        (ms, varies between runs) instead of the work.
    error : str
        Start of the error column's name.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from numkin import linkages, report, figures
    >>> wp = report.work_precision_table(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                                  grids=(36, 72), schemes=("centred", "second_difference"), repeat=1)
    >>> fig = figures.work_precision(wp)
    >>> fig.axes[0].get_xlabel()
    'work [point evaluations + stencil evaluations]'
    >>> figures.save(fig, "/tmp/numkin-doc-wp", ["png"])[0].suffix
    '.png'
    >>> figures.work_precision(wp, time="sweep + derivative time").axes[0].get_xlabel()
    'sweep + derivative time [ms] (varies between runs)'
    """
    what = "work-precision table"
    if time is not None:
        xcol = _col(table, time, what)
        unit = re.search(r"\[(.*?)\]", str(xcol))
        xlabel = f"{time} [{unit.group(1) if unit else 's'}] (varies between runs)"
        title = "error against run time, each method from coarse to fine grid (times vary between runs)"
    else:
        xcol = _col(table, work, what, required=False)
        if xcol is None:
            raise ValueError(
                f"{what}: no column starting with {work!r} (a table from an older numkin?); columns are "
                f"{list(table.columns)}; pass time='sweep + derivative time' to draw the measured run time"
            )
        xlabel = f"{work} [point evaluations + stencil evaluations]"
        title = ("error against work: evaluations of the loop equations + stencil evaluations, "
                 "each method from coarse to fine grid")
    ecol = _col(table, error, what)
    mcol = _col(table, "method", what)
    groups = _groups(table)
    with style():
        fig, axes = _new_figure(1, len(groups), size=(6.4 if len(groups) == 1 else 9.6, 5.0))
        for ax, (quantity, sub) in zip(axes[0], groups):
            qtext, unit = _panel_text(quantity, error)
            order_col = "points per turn" if "points per turn" in sub.columns else xcol
            for k, method in enumerate(dict.fromkeys(sub[mcol])):
                rows = sub[sub[mcol] == method].sort_values(order_col, kind="mergesort")
                st = _source_style(method, k)
                st["linewidth"] = min(st.get("linewidth", 1.5), 1.4)
                st.pop("alpha", None)
                st.pop("zorder", None)
                marker, size, filled = _WP_MARKERS.get(str(method), ("o", 4.5, True))
                ax.plot(np.asarray(rows[xcol], dtype=float), _positive(rows[ecol]), marker=marker, markersize=size,
                        markerfacecolor=st["color"] if filled else "none", markeredgecolor=st["color"],
                        markeredgewidth=1.0, label=_source_label(method), **st)
            on_front = _front(sub[xcol], sub[ecol])
            front = sub[on_front]
            ax.plot(np.asarray(front[xcol], dtype=float), _positive(front[ecol]), linestyle="none", marker="o",
                    markersize=14, markerfacecolor="none", markeredgecolor="black", markeredgewidth=1.0,
                    label="Pareto front", zorder=5)
            ax.set_xscale("log")
            ax.set_yscale("log")
            _plain_log_ticks(ax.xaxis, sub[xcol])
            ax.set_xlabel(xlabel)
            ax.set_ylabel(f"{error} [{unit}]")
            ax.set_title(qtext or "work and precision")
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncols=3, fontsize=7.5)
        fig.suptitle(title, fontsize=9)
    return fig


def roundoff(table):
    """Relative error against the step h at one angle: truncation error above, rounding below.

    Each scheme's V-curve, its measured optimal step (filled marker) and
    the textbook estimate ``h* ~ eps**(1/(p+n))`` (open marker); machine
    epsilon dotted.

    Parameters
    ----------
    table : DataFrame
        From :func:`numkin.report.roundoff_table`: ``scheme``, columns
        ``rel error at h = 1e-01 rad [-]`` ..., ``measured optimal h [rad]``,
        ``rel error at measured optimal h [-]``, ``textbook optimal h [rad]``,
        ``textbook error [-]``.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import math
    >>> from numkin import linkages, report, figures
    >>> ro = report.roundoff_table(linkages.chained_four_bars(), quantity="beta", check_angle=math.radians(100),
    ...                            schemes=("forward", "centred"))
    >>> figures.save(figures.roundoff(ro), "/tmp/numkin-doc-roundoff", ["png"])[0].suffix
    '.png'
    """
    what = "round-off table"
    scol = _col(table, "scheme", what)
    cols = [(float(m.group(1)), c) for c in table.columns
            if (m := re.match(r"rel error at h = ([0-9.eE+-]+) rad", str(c)))]
    if not cols:
        raise ValueError(f"{what}: no 'rel error at h = ... rad [-]' columns; columns are {list(table.columns)}")
    cols.sort()
    hs = np.array([h for h, _ in cols])
    eps = float(np.finfo(float).eps)
    with style():
        fig, axes = _new_figure(size=(6.4, 5.2))
        ax = axes[0, 0]
        allv = []
        for k, (_, row) in enumerate(table.iterrows()):
            scheme = str(row[scol])
            st = _source_style(scheme, k)
            st.pop("alpha", None)
            st.pop("zorder", None)
            st["linewidth"] = 1.4
            second = scheme in _FAMILY and scheme not in ("complex_step", "complex step")
            st["linestyle"] = "--" if second else "-"
            errs = _positive([row[c] for _, c in cols])
            allv.extend(errs)
            order = row.get("formal order")
            label = _order_label(scheme, order)
            ax.plot(hs, errs, marker="o", markersize=3.5, label=label, **st)
            if "measured optimal h [rad]" in row.index:
                ax.plot(row["measured optimal h [rad]"], row.get("rel error at measured optimal h [-]", np.nan),
                        marker="*", markersize=11, color=st["color"], markeredgecolor="black",
                        markeredgewidth=0.5, linestyle="none", zorder=5)
            if "textbook optimal h [rad]" in row.index and scheme not in ("complex step", "complex_step"):
                ax.plot(row["textbook optimal h [rad]"], row.get("textbook error [-]", np.nan), marker="D",
                        markersize=6, markerfacecolor="white", markeredgecolor=st["color"], markeredgewidth=1.3,
                        linestyle="none", zorder=5)
        ax.axhline(eps, color="0.4", linestyle=":", linewidth=0.9)
        ax.text(hs.max(), eps * 1.6, "machine ε", ha="right", va="bottom", fontsize=7.5, color="0.3")
        # legend entries for the markers
        ax.plot([], [], marker="*", markersize=10, color="0.5", markeredgecolor="black", markeredgewidth=0.5,
                linestyle="none", label="measured optimum")
        ax.plot([], [], marker="D", markersize=6, markerfacecolor="white", markeredgecolor="0.3",
                linestyle="none", label=r"textbook $h^* \sim \varepsilon^{1/(p+n)}$")
        ax.set_xscale("log")
        ax.set_yscale("log")
        lo, hi = _log_limits(allv + [eps])
        ax.set_ylim(lo, hi)
        ax.set_xlabel("step $h$ [rad]")
        ax.set_ylabel("relative error [–]")
        caption = _table_caption(table)
        ax.set_title(_caption_title(caption) if caption else "round-off: error against step", fontsize=9)
        fig.legend(loc="outside lower center", fontsize=7.5, ncols=3)
    return fig


def newton_residuals(tables):
    """Newton's residual norm per iteration (log scale), one curve per Jacobian.

    Parameters
    ----------
    tables : DataFrame or mapping of str to DataFrame
        From :func:`numkin.report.newton_table` (columns ``iteration``,
        ``residual norm [-]``): Jacobian name -> table, or one table (a
        ``Jacobian`` column, if present, splits it into curves).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import math
    >>> from numkin import linkages, report, figures
    >>> mech = linkages.chained_four_bars()
    >>> tables = {j: report.newton_table(mech, check_angle=math.radians(100), jacobian=j)
    ...           for j in ("symbolic", "forward", "central")}
    >>> fig = figures.newton_residuals(tables)
    >>> fig.axes[0].get_yscale()
    'log'
    >>> figures.save(fig, "/tmp/numkin-doc-newton", ["png"])[0].suffix
    '.png'
    """
    if hasattr(tables, "columns"):
        if "Jacobian" in tables.columns:
            tables = {str(j): sub for j, sub in _groups(tables, "Jacobian")}
        else:
            tables = {_jacobian_of(tables, "newton"): tables}
    if not tables:
        raise ValueError("newton_residuals: no Newton table given")
    # overlapping curves stay visible: large open, medium open, small filled markers
    styles = {"symbolic": ("black", "-", "o", 10, "none"), "forward": ("#D55E00", "--", "s", 6.5, "none"),
              "central": ("#0072B2", ":", "^", 4.5, "#0072B2")}
    with style():
        fig, axes = _new_figure(size=(6.4, 4.2))
        ax = axes[0, 0]
        kmax = 0
        for k, (name, t) in enumerate(tables.items()):
            it = _col(t, "iteration", "Newton table")
            rc = _col(t, "residual norm", "Newton table")
            color, ls, marker, size, face = styles.get(str(name), (_CYCLE[k % len(_CYCLE)], "-.", "D", 5, "none"))
            ax.plot(t[it], _positive(t[rc]), color=color, linestyle=ls, marker=marker, markersize=size,
                    markerfacecolor=face, markeredgewidth=1.2, label=f"{name} Jacobian")
            kmax = max(kmax, int(np.max(t[it])))
        from matplotlib.ticker import MaxNLocator

        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_yscale("log")
        ax.set_xlabel("iteration $k$ [–]")
        ax.set_ylabel("residual norm (scaled) [–]")
        first = next(iter(tables.values()))
        caption = _table_caption(first)
        where = re.search(r" at (\w+) = ([-0-9.]+) deg", caption)
        at = f" at {_sym(where.group(1))} = {where.group(2)}°" if where else ""
        ax.set_title(f"Newton: residual per iteration{at}")
        ax.legend(loc="upper right")
    return fig


def _jacobian_of(table, key: str) -> str:
    """Name of the Jacobian of a Newton table: from its key (``newton_forward``) or caption."""
    m = re.fullmatch(r"newton[_-](\w+)", key)
    if m:
        return m.group(1)
    caption = _table_caption(table)
    m = re.search(r"(\w+) Jacobian", caption)
    return m.group(1) if m else "symbolic"


# ============================================================================ render
def parse_spec(spec: str) -> tuple[str, str | None]:
    """Split a figure name of a scene: ``"kinematics:beta"`` -> ``("kinematics", "beta")``.

    The name may be written with ``_`` for ``-`` (``work_precision``). The
    part after ``:`` is an unknown (``position``, ``derivative``,
    ``difference``, ``kinematics``, ``slider``, ``acceleration``) or the
    input angle in degrees (``mechanism:30``); the table figures take none.
    Does not import matplotlib.

    Raises
    ------
    ValueError
        For an unknown figure name or an argument a figure does not take.

    Examples
    --------
    >>> parse_spec("kinematics:beta")
    ('kinematics', 'beta')
    >>> parse_spec("work_precision")
    ('work-precision', None)
    >>> parse_spec("mechanism:30")
    ('mechanism', '30')
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError(f"figure name must be a non-empty string, got {spec!r}")
    name, _, arg = spec.strip().partition(":")
    kind = name.strip().lower().replace("_", "-")
    arg = arg.strip() or None
    if kind not in FIGURES:
        import difflib

        near = difflib.get_close_matches(kind, list(FIGURES), n=1)
        hint = f" (did you mean '{near[0]}'?)" if near else ""
        raise ValueError(f"unknown figure {spec!r}{hint}; figures are: {', '.join(FIGURES)}")
    if arg is not None and kind not in _WITH_UNKNOWN and kind != "mechanism":
        raise ValueError(f"figure {spec!r}: '{kind}' takes no ':' argument")
    if arg is not None and kind == "mechanism":
        try:
            float(arg)
        except ValueError:
            raise ValueError(f"figure {spec!r}: 'mechanism:<angle in degrees>', got {arg!r}") from None
    return kind, arg


class _Data:
    """What a result holds for figures (duck-typed; see :func:`render`)."""

    def __init__(self, result):
        self.sweep = getattr(result, "sweep", None)
        self.analytic = getattr(result, "analytic", None)
        if self.analytic is None:
            k = getattr(result, "kinematics", None)
            self.analytic = k if hasattr(k, "columns") else None
        finite = getattr(result, "finite", None)
        self.finite = dict(finite) if finite else _frames_from_comparisons(getattr(result, "comparisons", None),
                                                                            self.sweep)
        self.tables = dict(getattr(result, "tables", None) or {})
        checks = getattr(result, "check_angles", None)
        if checks is None:
            checks = [math.radians(float(c.at_deg)) for c in getattr(result, "checks", None) or ()
                      if getattr(c, "at_deg", None) is not None]
        self.check_angles = [float(a) for a in np.atleast_1d(checks)] if checks is not None else []
        scene = getattr(result, "scene", None)
        self.quantity = getattr(result, "quantity", None) or (getattr(scene, "report", None) or {}).get("quantity")
        self.unknowns = tuple(getattr(scene, "unknowns", None) or ())

    def need_sweep(self):
        if self.sweep is None:
            raise _Missing("no sweep in the result (a stability scene?)")
        return self.sweep

    def unknown(self, arg, kind="angle"):
        sweep = self.need_sweep()
        if arg is not None:
            return _check_name(sweep, arg)
        wanted = (lambda n: _is_angle(sweep, n)) if kind == "angle" else (lambda n: not _is_angle(sweep, n))
        for cand in (self.quantity, *self.unknowns):
            if cand in sweep.unknowns and wanted(cand):
                return cand
        pool = [n for n in sweep.unknowns if wanted(n)]
        if kind == "length" and "x" in pool:
            return "x"
        if not pool:
            raise _Missing(f"{sweep.mechanism.name} has no {kind} unknown")
        return pool[0]

    def table(self, *keys):
        for key in keys:
            if key in self.tables:
                return self.tables[key]
        raise _Missing(f"no '{keys[0]}' table in the result (numkin.report makes it)")


def _frames_from_comparisons(comparisons, sweep) -> dict:
    """scheme -> frame (``<input>`` in rad and the compared quantities) from numkin.compare results."""
    if not comparisons or sweep is None:
        return {}
    import pandas as pd

    inp = _input_name(sweep)
    cols: dict = {}
    for quantity, comp in comparisons.items():
        table = getattr(comp, "table", None)
        if table is None:
            continue
        xcol = _col(table, f"{inp} [deg]", "comparison table", required=False)
        if xcol is None:
            continue
        unit = getattr(comp, "unit", None)
        for c in table.columns:
            m = re.fullmatch(r"(.+?) \[(.*)\]", str(c))
            if not m or m.group(1) in (inp, "analytic") or " " in m.group(1):
                continue
            scheme = m.group(1)
            if unit is not None and m.group(2) != unit:
                continue
            frame = cols.setdefault(scheme, {inp: np.radians(np.asarray(table[xcol], dtype=float))})
            frame[getattr(comp, "quantity", quantity)] = np.asarray(table[c], dtype=float)
    return {k: pd.DataFrame(v) for k, v in cols.items()}


def _build(kind: str, arg, d: _Data):
    """(figure, file stem) for one figure, or raise _Missing."""
    if kind == "position":
        sweep = d.need_sweep()
        names = [_check_name(sweep, arg)] if arg else [n for n in d.unknowns if n in sweep.unknowns] or None
        return position(sweep, names), "position" + (f"-{arg}" if arg else "")
    if kind in ("derivative", "difference"):
        sweep = d.need_sweep()
        name = d.unknown(arg)
        if sweep.step is None:
            raise _Missing("finite differences need a sweep with a uniform step")
        fn = derivative if kind == "derivative" else difference
        return fn(sweep, name), f"{kind}-{name}"
    if kind in ("kinematics", "slider"):
        sweep = d.need_sweep()
        name = d.unknown(arg, "angle" if kind == "kinematics" else "length")
        vcol, acol = _columns(sweep, name)
        frames = [f for f in [d.analytic, *d.finite.values()] if f is not None]
        if not any(vcol in f.columns or acol in f.columns for f in frames):
            raise _Missing(f"no velocity or acceleration of {name!r} in the result (ask for them in the scene)")
        fn = kinematics if kind == "kinematics" else slider
        return fn(sweep, name, analytic=d.analytic, finite=d.finite, check_angles=d.check_angles), f"{kind}-{name}"
    if kind == "acceleration":
        sweep = d.need_sweep()
        name = d.unknown(arg, "length")
        _, acol = _columns(sweep, name)
        if d.analytic is None or acol not in d.analytic.columns:
            raise _Missing(f"no analytic {acol} in the result (ask for accelerations in the scene)")
        finite = {k: f for k, f in d.finite.items() if acol in f.columns}
        if not finite:
            raise _Missing(f"no finite-difference {acol} in the result (give second-derivative schemes)")
        return acceleration_comparison(sweep, name, d.analytic, finite), f"acceleration-{name}"
    if kind == "mechanism":
        sweep = d.need_sweep()
        if not sweep.mechanism.points or not sweep.mechanism.links:
            raise _Missing(f"{sweep.mechanism.name} has no points and links to draw")
        at = math.radians(float(arg)) if arg is not None else (d.check_angles[0] if d.check_angles else None)
        return mechanism(sweep, at), "mechanism" + (f"-{arg}deg" if arg is not None else "")
    if kind == "convergence":
        return convergence(d.table("convergence")), "convergence"
    if kind == "work-precision":
        return work_precision(d.table("work_precision", "work-precision")), "work-precision"
    if kind == "roundoff":
        return roundoff(d.table("roundoff")), "roundoff"
    if kind == "newton":
        found = {_jacobian_of(t, key): t for key, t in d.tables.items() if re.fullmatch(r"newton([_-]\w+)?", key)}
        if not found:
            raise _Missing("no 'newton' table in the result (numkin.report.newton_table makes it)")
        return newton_residuals(found), "newton"
    raise ValueError(f"unknown figure {kind!r}")  # pragma: no cover - parse_spec checked it


def render(result, names: Sequence[str] | None = None, out_dir=".", formats: Sequence[str] = ("png", "svg")) -> list[Path]:
    """Draw and save the figures a scene asks for; skip, with a warning, those whose data is absent.

    Parameters
    ----------
    result : object
        Duck-typed: ``sweep`` (Sweep), and as available ``analytic`` (or
        ``kinematics``: the DataFrame of :func:`numkin.analytic.kinematics`),
        ``finite`` (scheme -> DataFrame of
        :func:`numkin.kinematics.finite_difference`; else taken from
        ``comparisons``, quantity -> :class:`numkin.compare.Comparison`),
        ``tables`` (name -> DataFrame, the names of
        :func:`numkin.report.full_report`; Newton tables as ``newton`` or
        ``newton_<jacobian>``), ``check_angles`` (rad; else the ``at_deg``
        of ``checks``), ``figures`` (else ``scene.figures``) and
        ``scene.report["quantity"]`` / ``scene.unknowns`` for the default
        unknown.
    names : sequence of str, optional
        Figure names (see :func:`parse_spec`); default the result's.
    out_dir : str or Path
        Folder of the files ``<figure>[-<unknown>].<format>``.
    formats : sequence of str

    Returns
    -------
    list of Path
        Files written.

    Warns
    -----
    FigureSkipped
        For each figure whose data the result does not hold.

    Raises
    ------
    ValueError
        For an unknown figure name or format, or an unknown that the
        mechanism does not have.

    Examples
    --------
    >>> import math, types
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))
    >>> result = types.SimpleNamespace(sweep=sweep, check_angles=[math.radians(30)], figures=["mechanism"])
    >>> [p.name for p in figures.render(result, out_dir="/tmp/numkin-doc-render")]
    ['mechanism.png', 'mechanism.svg']
    """
    if names is None:
        names = getattr(result, "figures", None)
        if names is None:
            names = getattr(getattr(result, "scene", None), "figures", None) or ()
    if isinstance(names, str):
        names = [names]
    specs = [(spec, *parse_spec(spec)) for spec in names]
    if isinstance(formats, str):
        formats = (formats,)
    bad = [f for f in formats if str(f).lower().lstrip(".") not in _METADATA]
    if bad or not formats:
        raise ValueError(
            f"formats: {bad[0] if bad else 'nothing'!r} is not a figure format numkin writes; choose from {sorted(_METADATA)}"
        )
    data = _Data(result)
    out = Path(out_dir)
    written: list[Path] = []
    for spec, kind, arg in specs:
        try:
            fig, stem = _build(kind, arg, data)
        except _Missing as why:
            warnings.warn(f"figure '{spec}' skipped: {why}", FigureSkipped, stacklevel=2)
            continue
        written += save(fig, out / stem, formats)
    return written

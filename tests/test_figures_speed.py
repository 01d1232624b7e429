"""Saving figures without redundant work: each format drawn once from one layout, log-axis tick
labels in plain text (no mathtext) that still name their ticks."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from numkin import figures, linkages, report
from numkin.analytic import kinematics as analytic_kinematics
from numkin.figures.ticks import PowerFormatter, log_axis, log_scale, power_text
from numkin.kinematics import finite_difference

SUPERSCRIPT = dict(zip("⁰¹²³⁴⁵⁶⁷⁸⁹⁻", "0123456789-"))


def label_value(text: str) -> float:
    """The number a label ``c×10ᵏ`` / ``10ᵏ`` / plain number names (read back independently)."""
    m = re.fullmatch(r"(?:([0-9.]+)×)?10([⁰¹²³⁴⁵⁶⁷⁸⁹⁻]+)", text)
    if m:
        exponent = int("".join(SUPERSCRIPT[ch] for ch in m.group(2)))
        return float(m.group(1) or 1) * 10.0**exponent
    return float(text.replace("−", "-"))


# ----------------------------------------------------------------------------- labels
@pytest.mark.parametrize("mathtext, plain", [
    (r"$\mathdefault{10^{-12}}$", "10⁻¹²"),
    (r"$\mathdefault{10^{0}}$", "10⁰"),
    (r"$\mathdefault{10^{3}}$", "10³"),
    (r"$\mathdefault{10^{-1}}$", "10⁻¹"),
    (r"$\mathdefault{2\times10^{-3}}$", "2×10⁻³"),
    (r"$\mathdefault{-10^{5}}$", "−10⁵"),
    (r"$\mathdefault{0}$", "0"),
    ("", ""),
    (r"$\frac{1}{2}$", r"$\frac{1}{2}$"),  # not a power: left to mathtext
])
def test_power_text(mathtext, plain):
    assert power_text(mathtext) == plain


@pytest.mark.parametrize("k", range(-16, 17))
def test_decade_labels_read_back_as_their_value(k):
    text = PowerFormatter(10)(10.0**k)
    assert "$" not in text
    assert label_value(text) == pytest.approx(10.0**k, rel=1e-12)


@pytest.mark.parametrize("limits", [(1e-14, 1.0), (1e-3, 6e-3), (0.02, 0.5), (3.0, 4000.0)])
def test_log_axis_labels_the_ticks_matplotlib_labels_with_their_values(limits):
    """Same ticks labelled as matplotlib's own log formatter (decades, and 2×10ᵏ... on short spans)."""
    from matplotlib.figure import Figure

    labels = []
    for ours in (False, True):
        fig = Figure()
        ax = fig.subplots()
        ax.plot(limits, limits)
        ax.set_yscale("log")
        if ours:
            log_axis(ax.yaxis)
        ax.set_ylim(*limits)
        fig.draw_without_rendering()
        ticks = [*ax.yaxis.get_major_ticks(), *ax.yaxis.get_minor_ticks()]
        locs = [*ax.yaxis.get_majorticklocs(), *ax.yaxis.get_minorticklocs()]
        labels.append([(loc, t.label1.get_text()) for loc, t in zip(locs, ticks)])
    mathtext, plain = labels
    assert [bool(t) for _, t in mathtext] == [bool(t) for _, t in plain]
    assert any(t for _, t in plain)
    for loc, text in plain:
        if text:
            assert "$" not in text
            assert label_value(text) == pytest.approx(loc, rel=1e-9), text


def test_log_scale_keeps_formatters_set_by_hand():
    from matplotlib.figure import Figure
    from matplotlib.ticker import NullFormatter

    ax = Figure().subplots()
    log_scale(ax, "x")
    assert isinstance(ax.xaxis.get_major_formatter(), PowerFormatter)
    ax.xaxis.set_minor_formatter(NullFormatter())
    log_axis(ax.xaxis)
    assert isinstance(ax.xaxis.get_minor_formatter(), NullFormatter)
    assert ax.get_yscale() == "linear"


def _log_tick_labels(fig):
    fig.canvas.draw()
    out = []
    for ax in fig.axes:
        for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
            if scale == "log":
                lo, hi = sorted(axis.get_view_interval())
                for loc, t in zip(axis.get_majorticklocs(), axis.get_major_ticks()):
                    if lo <= loc <= hi and t.label1.get_text():
                        out.append((loc, t.label1.get_text()))
    return out


def test_newton_and_acceleration_figures_label_log_axes_in_plain_text():
    mech = linkages.chained_four_bars()
    tables = {j: report.newton_table(mech, check_angle=math.radians(100), jacobian=j) for j in ("symbolic", "forward")}
    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    acc = figures.acceleration_comparison(sweep, "x", analytic_kinematics(sweep, "6000 rpm"),
                                          {"second_difference": finite_difference(sweep, "6000 rpm")})
    for fig in (figures.newton_residuals(tables), acc):
        labels = _log_tick_labels(fig)
        assert len(labels) >= 3
        for loc, text in labels:
            assert "$" not in text
            assert label_value(text) == pytest.approx(loc, rel=1e-9), text


# ----------------------------------------------------------------------------- saving
def _position_figure():
    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0, 361)))
    return figures.position(sweep, ["theta4"])


def test_png_and_svg_each_drawn_once(tmp_path):
    fig = _position_figure()
    draws = []
    fig.canvas.mpl_connect("draw_event", lambda event: draws.append(event))
    figures.save(fig, tmp_path / "f", ["png", "svg"])
    assert len(draws) == 2


@pytest.mark.parametrize("fmt", ["png", "svg"])
def test_one_layout_whatever_else_is_written(tmp_path, fmt):
    """A format's bytes do not depend on which other formats are written with it."""
    alone = figures.save(_position_figure(), tmp_path / "alone", [fmt])[0]
    both = figures.save(_position_figure(), tmp_path / "both", ["png", "svg"])
    together = [p for p in both if p.suffix == f".{fmt}"][0]
    assert alone.read_bytes() == together.read_bytes()


def test_saved_twice_gives_identical_bytes(tmp_path):
    first = figures.save(_position_figure(), tmp_path / "a", ["png", "svg"])
    second = figures.save(_position_figure(), tmp_path / "b", ["png", "svg"])
    for a, b in zip(first, second):
        assert a.read_bytes() == b.read_bytes(), a.name


def test_gc_paused_restores_the_collector_state():
    import gc

    from numkin.figures.style import gc_paused

    assert gc.isenabled()
    with pytest.raises(RuntimeError):
        with gc_paused():
            assert not gc.isenabled()
            raise RuntimeError("inside")
    assert gc.isenabled()
    gc.disable()
    try:
        with gc_paused():
            pass
        assert not gc.isenabled()  # a caller's choice is kept
    finally:
        gc.enable()

"""Figures name the stencil behind every value they draw: on an open grid the values at the
ends come from one-sided stencils, not from the scheme's interior formula, and are drawn and
labelled apart. The references are the closed form of the slider-crank, x = r cos t +
sqrt(l² − r² sin² t), and its differences evaluated by mpmath at 40 digits."""

from __future__ import annotations

import re

import mpmath
import numpy as np
import pytest

pytest.importorskip("matplotlib")
import matplotlib  # noqa: E402

matplotlib.use("Agg")

from numkin import figures, linkages  # noqa: E402
from numkin.figures import dispatch  # noqa: E402
from numkin.scene import load_scene, render_figures, run_scene  # noqa: E402

R, L = mpmath.mpf("0.08"), mpmath.mpf("0.2")  # m
W = 2 * mpmath.pi * 6000 / 60  # rad/s
H = mpmath.pi / 180  # the scene's step, 1 degree


def x_exact(t):
    return R * mpmath.cos(t) + mpmath.sqrt(L**2 - R**2 * mpmath.sin(t) ** 2)


def a_exact(t):
    return W**2 * mpmath.diff(x_exact, t, 2)


def second_difference(t):
    """omega² (x(t+h) − 2x(t) + x(t−h))/h²: the centred formula, wherever x is known."""
    return W**2 * (x_exact(t + H) - 2 * x_exact(t) + x_exact(t - H)) / H**2


def one_sided_second(t0, sign=1):
    """omega² (2y0 − 5y1 + 4y2 − y3)/h², y_k = x(t0 + sign k h): the end stencil of an open grid."""
    y = [x_exact(t0 + sign * k * H) for k in range(4)]
    return W**2 * (2 * y[0] - 5 * y[1] + 4 * y[2] - y[3]) / H**2


def one_sided_first(t0, sign=1):
    """omega (−3y0 + 4y1 − y2)/(2 sign h): the end stencil of the centred first difference."""
    y = [x_exact(t0 + sign * k * H) for k in range(3)]
    return W * (-3 * y[0] + 4 * y[1] - y[2]) / (2 * sign * H)


def drawn(scene_name, monkeypatch, tmp_path) -> dict:
    """The scene's figures as Figure objects, by file stem (drawn as `numkin figures` draws them)."""
    kept = {}

    def keep(fig, path, formats):
        kept[path.name] = fig
        return []

    monkeypatch.setattr(dispatch, "save", keep)
    mpmath.mp.dps = 40
    render_figures(run_scene(load_scene(scene_name), figures=False), tmp_path)
    return kept


def box_lines(fig) -> list[str]:
    return [line for t in fig.findobj(matplotlib.text.Text) for line in t.get_text().splitlines()]


def number(line: str) -> float:
    return float(re.search(r": (\S+) m/s", line).group(1).replace("−", "-"))


def lines_by_label(ax) -> dict:
    return {ln.get_label(): ln for ln in ax.get_lines()}


def test_the_references():
    """The numbers of the slider-crank at 0°: exact, centred and one-sided second differences."""
    mpmath.mp.dps = 40
    assert float(a_exact(0)) == pytest.approx(float(-R * W**2 * (1 + R / L)), rel=1e-15)
    assert float(a_exact(0)) == pytest.approx(-44215.828, abs=1e-3)
    assert float(second_difference(0)) == pytest.approx(-44213.897, abs=1e-3)
    assert float(one_sided_second(0)) == pytest.approx(-44237.056, abs=1e-3)


def test_slider_check_values_at_the_dead_centre_name_the_end_stencil(monkeypatch, tmp_path):
    fig = drawn("slider-crank", monkeypatch, tmp_path)["slider-x"]
    lines = box_lines(fig)
    at0 = [ln for ln in lines if "one-sided end stencil):" in ln]
    # the centred velocity and the second-difference acceleration at 0°, both from the end stencils
    assert len(at0) == 2, lines
    v0 = next(ln for ln in at0 if ln.strip().startswith("centred"))
    a0 = next(ln for ln in at0 if ln.strip().startswith("second difference"))
    assert number(v0) == pytest.approx(float(one_sided_first(0)), rel=1e-4)
    assert number(a0) == pytest.approx(float(one_sided_second(0)), rel=1e-4)
    assert abs(number(a0) - float(second_difference(0))) > 20  # not what the interior formula gives
    # at 90° the interior formula, under its own name
    a90 = [ln for ln in lines if ln.strip().startswith("second difference:") and "m/s" in ln]
    assert len(a90) == 1 and number(a90[0]) == pytest.approx(float(second_difference(mpmath.pi / 2)), rel=1e-4)
    for ax in fig.axes[1:]:  # the end values are legend entries of their own
        assert any(lab.endswith(": one-sided end stencil") for lab in ax.get_legend_handles_labels()[1])


def test_acceleration_figure_draws_each_stencil_under_its_name(monkeypatch, tmp_path):
    fig = drawn("slider-crank", monkeypatch, tmp_path)["acceleration-x"]
    ax, axe = fig.axes
    mpmath.mp.dps = 40
    t = [mpmath.radians(d) for d in range(181)]
    exact = np.array([float(a_exact(v)) for v in t])
    centred = np.array([float(second_difference(v)) for v in t])
    ends = np.array([float(one_sided_second(0)), float(one_sided_second(mpmath.pi, -1))])
    top, bottom = lines_by_label(ax), lines_by_label(axe)
    for panel, want in ((top, centred), (bottom, np.abs(centred - exact))):
        deg, y = (np.asarray(v, dtype=float) for v in panel["second difference"].get_data())
        assert np.allclose(deg, np.arange(181.0), rtol=0, atol=1e-9)
        assert np.isnan(y[[0, -1]]).all()  # the interior formula cannot reach the ends
        assert np.allclose(y[1:-1], want[1:-1], rtol=0, atol=1e-6 * np.abs(exact).max())
    deg, y = (np.asarray(v, dtype=float) for v in top["second difference: one-sided end stencil"].get_data())
    assert np.allclose(deg, [0.0, 180.0], rtol=0, atol=1e-9) and np.allclose(y, ends, rtol=1e-9)
    deg, e = (np.asarray(v, dtype=float) for v in bottom["second difference: one-sided end stencil"].get_data())
    assert np.allclose(deg, [0.0, 180.0], rtol=0, atol=1e-9) and np.allclose(e, np.abs(ends - exact[[0, -1]]), rtol=1e-5)
    # the end stencil errs 11 times as much as the interior formula at the dead centre (11/12 h² x'''' vs h²/12 x'''')
    assert e[0] / abs(centred[0] - exact[0]) == pytest.approx(11, rel=0.02)
    assert axe.get_legend() is not None


def test_a_periodic_turn_has_no_end_stencils():
    from numkin.analytic import kinematics
    from numkin.kinematics import finite_difference

    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361)))  # one turn: periodic
    fig = figures.slider(sweep, analytic=kinematics(sweep, "6000 rpm"),
                         finite={"centred": finite_difference(sweep, "6000 rpm")}, check_angles=[0.0])
    assert not any("end stencil" in line for line in box_lines(fig))
    for ax in fig.axes[1:]:
        y = lines_by_label(ax)["centred"].get_ydata()
        assert np.isfinite(np.asarray(y, dtype=float)).all()


def test_derivative_figure_marks_where_each_scheme_leaves_its_formula():
    """forward reaches one point ahead (its last value is a backward difference), centred one either side."""
    sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    ax = figures.derivative(sweep, "phi").axes[0]
    by = lines_by_label(ax)
    assert np.asarray(by["forward: one-sided end stencil"].get_xdata(), dtype=float).tolist() == [360.0]
    assert np.asarray(by["centred: one-sided end stencil"].get_xdata(), dtype=float).tolist() == [0.0, 360.0]
    fwd = np.asarray(by["forward"].get_ydata(), dtype=float)
    assert np.isnan(fwd[-1]) and np.isfinite(fwd[:-1]).all()

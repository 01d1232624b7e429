"""Layout of saved figures, measured with matplotlib's renderer: titles inside the figure, boxes of
check values clear of the legends, one rounding of an angle throughout the mechanism figure."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from numkin import figures, linkages
from numkin.analytic import kinematics as analytic_kinematics
from numkin.figures import dispatch
from numkin.figures.fitting import MARGIN, fit_titles, titles, wrap_lines
from numkin.kinematics import finite_difference
from numkin.scene import load_scene, render_figures, run_scene

SAVE_DPI = 150  # savefig.dpi of numkin.mplstyle

FOUR_BAR_SCENE = """
[scene]
description = "four-bar"

[mechanism]
linkage = "four_bar"
unit = "{unit}"
branch = "{branch}"

[mechanism.dimensions]
ground = {ground}
crank = {crank}
coupler = {coupler}
rocker = {rocker}

[input]
speed = "{speed}"
start_deg = {start}
stop_deg = {stop}
step_deg = {step}

[output]
quantities = ["position", "velocity", "acceleration"]
figures = {figures}

[compare]
schemes = {schemes}
second_schemes = ["second_difference"]

{checks}
"""


def scene_figures(tmp_path, monkeypatch, **values) -> dict:
    """Stem -> Figure of a four-bar scene, each laid out and saved (PNG) as ``numkin figures`` saves it."""
    values = {"unit": "mm", "branch": "open", "start": 0, "stop": 360, "step": 1, "schemes": '["forward", "centred"]',
              "checks": "[[check]]\nat_deg = 100", **values}
    values["figures"] = "[" + ", ".join(f'"{f}"' for f in values["figures"]) + "]"
    path = tmp_path / "four-bar.toml"
    path.write_text(FOUR_BAR_SCENE.format(**values), encoding="utf-8")
    kept = {}

    def keep(fig, stem, formats):
        kept[stem.name] = fig
        return figures.save(fig, stem, ["png"])

    monkeypatch.setattr(dispatch, "save", keep)
    render_figures(run_scene(load_scene(str(path)), figures=False), tmp_path / "out")
    return kept


def drawn(fig):
    """The renderer of `fig` drawn at the saving resolution, from the layout :func:`figures.save` froze."""
    fig.set_dpi(SAVE_DPI)
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def boxes_and_legends(fig, renderer) -> list[tuple[str, object]]:
    """(what, window extent) of every legend and every text drawn in a box."""
    found = []
    for ax in fig.axes:
        if ax.get_legend() is not None:
            found.append(("legend", ax.get_legend().get_window_extent(renderer)))
        for text in ax.texts:
            patch = text.get_bbox_patch()
            if patch is not None and text.get_visible() and patch.get_edgecolor()[3] > 0:
                found.append((text.get_text().split("\n")[0], patch.get_window_extent(renderer)))
    return found


def assert_titles_inside(fig, renderer):
    box = fig.bbox
    shown = titles(fig)
    assert shown
    for title in shown:
        extent = title.get_window_extent(renderer)
        assert box.x0 <= extent.x0 and extent.x1 <= box.x1, (title.get_text(), extent, box)
        assert box.y0 <= extent.y0 and extent.y1 <= box.y1, (title.get_text(), extent, box)


# ----------------------------------------------------------------------------- titles
@pytest.mark.parametrize("values, stem", [
    ({"ground": 20, "crank": 50, "coupler": 40, "rocker": 50, "branch": "crossed", "speed": "-300 deg/s",
      "figures": ["kinematics:theta4", "kinematics:theta3", "mechanism"]}, "kinematics-theta4"),
    ({"ground": 10, "crank": 3, "coupler": 8, "rocker": 6, "unit": "cm", "speed": "2 rev/s", "start": 45,
      "stop": 200, "step": 0.5, "figures": ["kinematics:theta3", "position:theta3", "mechanism"]},
     "kinematics-theta3"),
])
def test_long_titles_of_four_bar_scenes_stay_inside_the_figure(tmp_path, monkeypatch, values, stem):
    kept = scene_figures(tmp_path, monkeypatch, **values)
    assert stem in kept
    for name, fig in kept.items():
        assert_titles_inside(fig, drawn(fig))
    title = kept[stem].axes[0].get_title()
    assert "\n" in title  # broken into lines, the mechanism's name whole on the first
    assert title.split("\n")[0] == f"four-bar (ground {values['ground']} {values.get('unit', 'mm')}, crank " \
                                   f"{values['crank']} {values.get('unit', 'mm')}, coupler {values['coupler']} " \
                                   f"{values.get('unit', 'mm')}, rocker {values['rocker']} {values.get('unit', 'mm')})"


def test_a_title_that_fits_is_left_as_it_is(tmp_path):
    sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    fig = figures.kinematics(sweep, "beta", finite={"centred": finite_difference(sweep, "450 rad/min")})
    before = fig.axes[0].get_title()
    figures.save(fig, tmp_path / "beta", ["png"])
    assert fig.axes[0].get_title() == before and "\n" not in before
    assert fig.axes[0].title.get_fontsize() == pytest.approx(10.0)


def test_a_title_wider_than_any_line_is_set_smaller_to_fit(tmp_path):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(2.0, 1.5), dpi=SAVE_DPI, layout="none")
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.2, 0.2, 0.7, 0.6))
    ax.set_title("Supercalifragilisticexpialidocious")
    renderer = fig.canvas.get_renderer()
    assert ax.title.get_window_extent(renderer).width > fig.bbox.width
    assert fit_titles(fig, renderer, relayout=False)
    assert ax.title.get_text() == "Supercalifragilisticexpialidocious"
    assert ax.title.get_fontsize() < 10
    extent = ax.title.get_window_extent(renderer)
    margin = MARGIN * SAVE_DPI / 72
    assert fig.bbox.x0 + margin - 0.5 <= extent.x0 and extent.x1 <= fig.bbox.x1 - margin + 0.5
    assert not fit_titles(fig, renderer, relayout=False)  # fitted once, left alone after


def test_wrap_lines_breaks_at_colons_then_commas_never_inside_mathtext():
    def fits(n):
        return lambda s: len(s) <= n

    assert wrap_lines("head (a 1, b 2): $x$, velocity", fits(40)) == ["head (a 1, b 2): $x$, velocity"]
    assert wrap_lines("head (a 1, b 2): $x$, velocity", fits(20)) == ["head (a 1, b 2)", "$x$, velocity"]
    assert wrap_lines("head (a 1, b 2): $x$, velocity", fits(9)) == ["head", "(a 1,", "b 2)", "$x$,", "velocity"]
    assert wrap_lines(r"$\omega_{a, b} = 1$ and more", fits(5)) == [r"$\omega_{a, b} = 1$", "and", "more"]
    assert wrap_lines("one\ntwo words", fits(4)) == ["one", "two", "words"]


# ----------------------------------------------------------------------------- boxes and legends
def test_check_values_do_not_cover_the_legend_of_three_schemes(tmp_path, monkeypatch):
    """Three schemes on an open grid (each with its end-stencil entry) and two check angles: the box of
    check values under each legend, the layout taller where they need it."""
    kept = scene_figures(tmp_path, monkeypatch, ground=10, crank=3, coupler=8, rocker=6, unit="cm",
                         speed="2 rev/s", start=45, stop=200, step=0.5,
                         schemes='["centred", "forward", "five_point"]', figures=["kinematics:theta3"],
                         checks="[[check]]\nat_deg = 100\n[[check]]\nat_deg = 150")
    fig = kept["kinematics-theta3"]
    renderer = drawn(fig)
    assert "five point" in [t.get_text() for t in fig.axes[1].get_legend().get_texts()]
    found = boxes_and_legends(fig, renderer)
    assert sum(what == "legend" for what, _ in found) == 2 and len(found) == 5
    for i, (a, box_a) in enumerate(found):
        assert fig.bbox.x0 <= box_a.x0 and box_a.x1 <= fig.bbox.x1 and fig.bbox.y0 <= box_a.y0, a
        for b, box_b in found[i + 1:]:
            assert not box_a.overlaps(box_b), (a, b)


def test_homework_check_values_clear_of_their_legends(tmp_path):
    sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    finite = {s: finite_difference(sweep, "450 rad/min", method=s) for s in ("centred", "forward", "five_point")}
    fig = figures.kinematics(sweep, "beta", analytic=analytic_kinematics(sweep, "450 rad/min"), finite=finite,
                             check_angles=np.radians([30, 100, 250]))
    figures.save(fig, tmp_path / "beta", ["png"])
    found = boxes_and_legends(fig, drawn(fig))
    assert len(found) == 5
    for i, (a, box_a) in enumerate(found):
        for b, box_b in found[i + 1:]:
            assert not box_a.overlaps(box_b), (a, b)


# ----------------------------------------------------------------------------- angles
def test_the_mechanism_figure_writes_each_angle_one_way(tmp_path):
    sweep = linkages.four_bar(10, 3, 8, 6, length_unit="cm").sweep(np.radians(np.arange(45, 200.5, 0.5)))
    fig = figures.mechanism(sweep, math.radians(100))
    figures.save(fig, tmp_path / "mechanism", ["png"])
    ax = fig.axes[0]
    (box,) = [t for t in ax.texts if t.get_text().count("\n") >= 2]
    written = dict(line.split(" = ") for line in box.get_text().split("\n"))
    arc = re.compile(r"\$\\theta_\{\d\}\$ = \S+°")
    arcs = [t.get_text() for t in ax.texts if t is not box and arc.fullmatch(t.get_text())]
    assert len(arcs) >= 2
    decimals = {len(v.rstrip("°").partition(".")[2]) for v in written.values() if "." in v}
    assert decimals == {3}
    for arc in arcs:
        name, value = arc.split(" = ")
        assert written[name] == value, arc
    assert ax.get_title().endswith("= " + written[r"$\theta_{2}$"])

"""Animations: a full turn where the input can turn, size and speed options, sliders as
blocks, traces and arrows; the same bytes from the same call."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("matplotlib")
from PIL import Image

from numkin import linkages
from numkin.animate import animate, full_turn

DEG = math.pi / 180


def test_half_sweep_of_a_slider_crank_animates_a_full_turn():
    """The crank of 80 mm against a rod of 200 mm turns fully: the animation covers 0..360 degrees."""
    half = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    whole = full_turn(half)
    t = whole.inputs
    assert t[0] == 0.0 and t[-1] == pytest.approx(2 * math.pi, abs=1e-12) and len(whole) == 361
    # piston position from the closed form x = r cos t + sqrt(l^2 - r^2 sin^2 t), over the whole turn
    x = 80 * np.cos(t) + np.sqrt(200**2 - (80 * np.sin(t)) ** 2)
    np.testing.assert_allclose(whole["x"], x, rtol=0, atol=1e-9)


def test_no_full_turn_where_the_input_cannot_turn():
    # ground 4, crank 3, coupler 2, rocker 2: at theta = 180 deg the pin is 7 from the rocker pivot > 2 + 2
    sweep = linkages.four_bar(4, 3, 2, 2).sweep(np.radians(np.arange(0, 11)))
    assert full_turn(sweep) is None


def _frames(path):
    out = []
    with Image.open(path) as im:
        for k in range(im.n_frames):
            im.seek(k)
            out.append(np.asarray(im.convert("RGB")))
        return out, im.size


def test_full_turn_loops_and_turn_sweep_keeps_the_half(tmp_path):
    half = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    full, _ = _frames(animate(half, tmp_path / "full.gif", frames=8, dpi=30))
    kept, _ = _frames(animate(half, tmp_path / "half.gif", frames=8, dpi=30, turn="sweep"))
    # full turn: frames at 0, 45, ..., 315 deg: the 180-deg frame is the fifth, and no frame repeats the first
    assert not any(np.array_equal(full[0], f) for f in full[1:])
    # half turn: frames from 0 to 180 deg, the last one at the other dead centre
    assert not np.array_equal(kept[-1], kept[0])
    with pytest.raises(ValueError, match="turn must be 'full' or 'sweep'"):
        animate(half, tmp_path / "x.gif", turn="half")


def test_size_dpi_and_fps(tmp_path):
    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361, 5)))
    path = animate(sweep, tmp_path / "big.gif", frames=4, fps=10, dpi=50, width=8.0)
    with Image.open(path) as im:
        assert im.size[0] == 400 and im.info["duration"] == 100
    with pytest.raises(ValueError, match="dpi must be an integer"):
        animate(sweep, tmp_path / "x.gif", dpi=0)
    with pytest.raises(ValueError, match="width must be a number of inches"):
        animate(sweep, tmp_path / "x.gif", width=0.1)


def test_arrows_and_traces_deterministic(tmp_path):
    sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361, 2)))
    kwargs = dict(frames=6, dpi=40, traces=["B"], arrows="acceleration", omega="10 rad/s")
    paths = [animate(sweep, tmp_path / f"run{k}" / "qr.gif", **kwargs) for k in range(2)]
    assert paths[0].read_bytes() == paths[1].read_bytes()
    plain = animate(sweep, tmp_path / "plain.gif", frames=6, dpi=40)
    assert plain.read_bytes() != paths[0].read_bytes()
    with pytest.raises(ValueError, match="give the input speed omega"):
        animate(sweep, tmp_path / "x.gif", arrows="velocity")
    with pytest.raises(ValueError, match="traces: 'Z' is not a named point"):
        animate(sweep, tmp_path / "x.gif", traces=["Z"])


def test_cli_animation_twice_gives_identical_bytes(tmp_path):
    from numkin.cli import main

    paths = [tmp_path / f"qr{k}.gif" for k in range(2)]
    for p in paths:
        assert main(["animate", "quick-return", "--out", str(p), "--frames", "6"]) == 0
    assert paths[0].read_bytes() == paths[1].read_bytes()


def test_full_turn_goes_through_the_change_points_the_sweep_went_through():
    # the crossed parallelogram four-bar swept from 10 to 350 deg through its change point at 180 deg
    # (on_singular="report"): its full turn does the same, on the branch the sweep kept
    import warnings

    from numkin import linkages
    from numkin.animate import full_turn

    mech = linkages.four_bar(5, 2, 5, 2, branch="crossed")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        part = mech.sweep(np.radians(np.arange(10.0, 351.0)), on_singular="report")
    whole = full_turn(part)
    assert whole is not None and len(whole) == 361
    np.testing.assert_allclose(whole.values[:, :341], part.values, atol=1e-9)


def test_a_long_title_fits_a_narrow_animation(tmp_path, monkeypatch):
    """A title too wide for a narrow animation is broken into lines over axes brought down for them, inside the
    frame, its font kept."""
    import numkin.animate as animate_module
    from numkin.figures.fitting import fit_titles

    seen = []

    def fit_and_keep(fig, *args, **kwargs):
        changed = fit_titles(fig, *args, **kwargs)
        renderer = fig.canvas.get_renderer()
        seen.append((changed, fig.axes[0].title, fig.axes[0].title.get_window_extent(renderer), fig.bbox.frozen()))
        return changed

    monkeypatch.setattr(animate_module, "fit_titles", fit_and_keep)
    sweep = linkages.four_bar(20, 50, 40, 50, branch="crossed").sweep(np.radians(np.arange(0, 361)))
    animate(sweep, tmp_path / "narrow.gif", frames=2, width=3.0, dpi=60)
    ((changed, title, extent, box),) = seen
    assert changed and title.get_text().count("\n") >= 1 and title.get_fontsize() == 9
    assert box.x0 <= extent.x0 and extent.x1 <= box.x1 and extent.y1 <= box.y1


def test_a_narrow_animation_keeps_its_axis_labels_inside(tmp_path, monkeypatch):
    """At 3 inches the y-label and tick labels are inside the frame; at the default width the axes do not move."""
    import numkin.animate as animate_module

    original = animate_module.labels_inside
    seen = []

    def inside_and_keep(fig, ax):
        moved = original(fig, ax)
        renderer = fig.canvas.get_renderer()
        ax.title.set_visible(False)
        seen.append((moved, ax.get_tightbbox(renderer), ax.yaxis.label.get_window_extent(renderer), fig.bbox.frozen()))
        ax.title.set_visible(True)
        return moved

    monkeypatch.setattr(animate_module, "labels_inside", inside_and_keep)
    sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    animate(sweep, tmp_path / "narrow.gif", frames=2, width=3.0, dpi=100)
    animate(sweep, tmp_path / "wide.gif", frames=2, dpi=100)
    (moved3, tight3, ylabel3, box3), (moved_default, tight, _, box) = seen
    assert moved3 and not moved_default
    assert box3.x0 < ylabel3.x0 and box3.x0 < tight3.x0 and box3.y0 < tight3.y0
    assert box.x0 < tight.x0 and box.y0 < tight.y0


@pytest.mark.parametrize("width, dpi, arrows", [(1.0, 30, None), (3.0, 10, "acceleration"), (1.25, 30, "velocity")])
def test_the_smallest_frames_allowed_are_drawn(tmp_path, width, dpi, arrows):
    """Width 1 to 40 inches and 10 to 600 dpi are allowed: a title or scale line set smaller to fit keeps a
    font of at least two pixels (FreeType refused one of less than a pixel, and the animation was lost)."""
    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361, 10)))
    path = animate(sweep, tmp_path / "small.gif", frames=2, width=width, dpi=dpi, arrows=arrows, omega=10.0)
    assert abs(Image.open(path).size[0] - width * dpi) <= 1

"""Derived quantities in figures: what is plotted checked against closed forms derived here (the four-bar
by circle intersection, the slider-crank's gap by hand), a scene's figure of a derived quantity rendered
twice to the same bytes, and the figure functions naming a wrong kind of argument."""

from __future__ import annotations

import dataclasses
import math
import types
import warnings

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

pytest.importorskip("matplotlib")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (only to check that no figure is left open)

import numkin  # noqa: E402
from numkin import figures, linkages  # noqa: E402
from numkin.analytic import kinematics as analytic_kinematics  # noqa: E402
from numkin.kinematics import finite_difference  # noqa: E402
from test_derived import _mu_closed_form as _mu_mp  # noqa: E402  (theta4 - theta3 by circle intersection, mpmath)

OMEGA = 10.0  # rad/s
MU = {"mu": ("theta4 - theta3", "angle")}


# ----------------------------------------------------------------------------- references
def _mu(t: np.ndarray) -> np.ndarray:
    mp.mp.dps = 30
    return np.array([float(_mu_mp(mp.mpf(float(x)))) for x in np.atleast_1d(t)])


def line(ax, label):
    """(x, y) of the line labelled `label` on an axes."""
    for ln in ax.get_lines():
        if ln.get_label() == label:
            return np.asarray(ln.get_xdata(), dtype=float), np.asarray(ln.get_ydata(), dtype=float)
    raise AssertionError(f"no line {label!r}; lines: {[ln.get_label() for ln in ax.get_lines()]}")


@pytest.fixture(autouse=True)
def no_open_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def four_bar():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities(
        {**MU, "wrapped": ("atan2(sin(theta4 - theta3 + 2), cos(theta4 - theta3 + 2))", "angle")})
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0)))
    finite = {
        "forward": finite_difference(sweep, OMEGA, method="forward", second_method="forward_of_forward"),
        "centred": finite_difference(sweep, OMEGA),
    }
    return types.SimpleNamespace(sweep=sweep, analytic=analytic_kinematics(sweep, OMEGA), finite=finite)


# ----------------------------------------------------------------------------- an angle
def test_kinematics_of_the_transmission_angle_against_the_circle_intersection(four_bar):
    sweep = four_bar.sweep
    fig = figures.kinematics(sweep, "mu", analytic=four_bar.analytic, finite=four_bar.finite,
                             check_angles=[math.radians(90)])
    ax0, ax1, ax2 = fig.axes[:3]
    assert [ax.get_ylabel() for ax in (ax0, ax1, ax2)] == ["$\\mu$ [deg]", "$\\omega_{\\mu}$ [rad/s]",
                                                           "$\\alpha_{\\mu}$ [rad/s²]"]
    x, y = ax0.get_lines()[0].get_data()
    np.testing.assert_allclose(x, np.arange(0.0, 361.0), rtol=0, atol=1e-12)
    t = np.radians(x)
    mu = _mu(t)
    np.testing.assert_allclose(y, np.degrees(mu), atol=1e-10)
    assert y[90] == pytest.approx(86.8153, abs=5e-5)  # the value derived.py's example prints

    # exact rates against mpmath derivatives of the closed form
    mp.mp.dps = 30
    at = [0, 37, 90, 181, 300]
    d1 = np.array([float(mp.diff(_mu_mp, mp.radians(d))) for d in at])
    d2 = np.array([float(mp.diff(_mu_mp, mp.radians(d), 2)) for d in at])
    np.testing.assert_allclose(line(ax1, "analytic")[1][at], OMEGA * d1, atol=1e-9)
    np.testing.assert_allclose(line(ax2, "analytic")[1][at], OMEGA**2 * d2, atol=1e-7)

    # the schemes applied to the sampled values: the same differences of the closed form, taken here
    h = math.radians(1.0)
    up, down = np.roll(mu[:-1], -1), np.roll(mu[:-1], 1)  # one turn: periodic, the last row repeats the first
    centred = np.append((up - down) / (2 * h), 0.0)
    centred[-1] = centred[0]
    second = np.append((up - 2 * mu[:-1] + down) / h**2, 0.0)
    second[-1] = second[0]
    forward = np.append((up - mu[:-1]) / h, 0.0)
    forward[-1] = forward[0]
    np.testing.assert_allclose(line(ax1, "centred")[1], OMEGA * centred, atol=1e-8)
    np.testing.assert_allclose(line(ax1, "forward")[1], OMEGA * forward, atol=1e-8)
    # each frame's second scheme on the acceleration panel, under the frame's name
    np.testing.assert_allclose(line(ax2, "centred")[1], OMEGA**2 * second, atol=1e-5)
    # and they err as their orders say: forward O(h), centred O(h^2)
    err_forward = np.max(np.abs(line(ax1, "forward")[1][at] - OMEGA * d1))
    err_centred = np.max(np.abs(line(ax1, "centred")[1][at] - OMEGA * d1))
    assert err_centred < 1e-3 * OMEGA < err_forward
    # the check angle's values are written beside the panels
    texts = " ".join(t.get_text() for ax in fig.axes for t in ax.texts)
    assert "$\\mu$(90°) = 86.815°" in texts


def test_a_wrapped_angle_is_drawn_and_differenced_unwrapped(four_bar):
    """atan2(...) of mu + 2 rad jumps from +180° to -180°: drawn continuous, its rates those of mu, with the
    warning an unknown angle's wrapped data give (numkin.kinematics.prepare_rows)."""
    sweep = four_bar.sweep
    with pytest.warns(UserWarning, match=r"\['wrapped'\] jump by more than 180°.*wrapped data; unwrapped"):
        fig = figures.kinematics(sweep, "wrapped", analytic=four_bar.analytic, finite=four_bar.finite)
    _, y = fig.axes[0].get_lines()[0].get_data()
    assert np.max(np.abs(np.diff(y))) < 5.0
    offset = y - np.degrees(_mu(sweep.inputs)) - math.degrees(2.0)
    np.testing.assert_allclose(offset, np.round(offset[0] / 360) * 360, atol=1e-9)  # one whole-turn offset
    ref = figures.kinematics(sweep, "mu", analytic=four_bar.analytic, finite=four_bar.finite)
    for j, label in ((1, "centred"), (1, "analytic"), (2, "centred"), (2, "forward"), (2, "analytic")):
        np.testing.assert_allclose(line(fig.axes[j], label)[1], line(ref.axes[j], label)[1], atol=1e-7)


def test_position_derivative_and_difference_of_a_derived_angle(four_bar):
    sweep = four_bar.sweep
    with pytest.warns(UserWarning, match=r"\['wrapped'\] jump by more than 180°"):
        fig = figures.position(sweep)  # by default the unknowns and then the derived quantities
    assert [ln.get_label() for ln in fig.axes[0].get_lines()] == ["$\\theta_{3}$", "$\\theta_{4}$", "$\\mu$",
                                                                 "$\\mathrm{wrapped}$"]
    _, y = line(fig.axes[0], "$\\mu$")
    mu = _mu(sweep.inputs)
    np.testing.assert_allclose(y, np.degrees(mu), atol=1e-10)
    fig = figures.derivative(sweep, "mu")
    assert fig.axes[0].get_ylabel() == "$d\\mu/d\\theta_{2}$ [rad/rad]"
    h = math.radians(1.0)
    x, forward = line(fig.axes[0], "forward")
    interior = np.isfinite(forward)
    np.testing.assert_allclose(forward[interior], ((mu[1:] - mu[:-1]) / h)[interior[:-1]], atol=1e-8)
    fig = figures.difference(sweep, "mu")
    _, delta = fig.axes[0].get_lines()[0].get_data()
    k = np.arange(1, 360)
    expected = np.abs((mu[k + 1] - mu[k - 1]) / (2 * h) - (mu[k + 1] - mu[k]) / h)
    np.testing.assert_allclose(np.asarray(delta, dtype=float)[k], expected, atol=1e-8)


@settings(max_examples=12, deadline=None)
@given(crank=st.floats(0.5, 1.5), coupler=st.floats(3.5, 5.0), rocker=st.floats(3.0, 4.0),
       schemes=st.sampled_from([("centred", "second_difference"), ("forward", "forward_of_forward"),
                                ("five_point", "five_point_second"), ("spectral", "spectral_second")]),
       turn=st.booleans())
def test_schemes_on_a_difference_of_unknowns_are_the_differences_of_their_estimates(crank, coupler, rocker,
                                                                                  schemes, turn):
    """The schemes are linear: applied to mu = theta4 - theta3 they give the frame's estimates of theta4 minus
    those of theta3, on a full turn (periodic) or an open arc, with an accelerating input; for every valid
    crank-rocker."""
    from numkin.figures.series import with_rates

    mech = linkages.four_bar(4.5, crank, coupler, rocker).add_quantities(MU)
    stop = 360.0 if turn or schemes[0] == "spectral" else 200.0
    sweep = mech.sweep(np.radians(np.arange(0.0, stop + 1.0, 5.0)))
    frame = finite_difference(sweep, 7.0, 2.0, method=schemes[0], second_method=schemes[1])
    exact = analytic_kinematics(sweep, 7.0, 2.0)
    with_mu, finite = with_rates(sweep, "mu", exact, {"fd": frame})
    for rate in ("omega", "alpha"):
        for got_, ref in ((finite["fd"], frame), (with_mu, exact)):
            np.testing.assert_allclose(got_[f"{rate}_mu"], ref[f"{rate}_theta4"] - ref[f"{rate}_theta3"],
                                       rtol=1e-9, atol=1e-9)
    assert finite["fd"].attrs["periodic"] == frame.attrs["periodic"]
    assert "omega_mu" not in frame.columns  # the given frames are copied, not changed


def test_a_derived_quantity_the_mechanism_lacks_is_named_with_the_ones_it_has(four_bar):
    with pytest.raises(numkin.InputError, match=r"'nu' is not an unknown .*derived quantities \['mu', 'wrapped'\]"):
        figures.kinematics(four_bar.sweep, "nu", analytic=four_bar.analytic)


# ----------------------------------------------------------------------------- a length
def test_a_length_quantity_of_the_slider_crank_against_its_hand_derivation():
    r, rod = 80.0, 200.0
    mech = linkages.slider_crank(r, rod).add_quantities({"gap": ("x - r*cos(theta)", "length")})
    sweep = mech.sweep(np.radians(np.arange(0.0, 181.0)))
    w, alpha = 600 * 2 * math.pi / 60, 3.0
    exact = analytic_kinematics(sweep, "600 rpm", alpha=alpha)
    fd = {"centred": finite_difference(sweep, "600 rpm", alpha=alpha)}
    fig = figures.slider(sweep, "gap", analytic=exact, finite=fd)
    assert [ax.get_ylabel() for ax in fig.axes[:3]] == ["$\\mathrm{gap}$ [mm]", "$v_{\\mathrm{gap}}$ [mm/s]",
                                                        "$a_{\\mathrm{gap}}$ [mm/s²]"]
    assert fig.axes[0].get_title().endswith("offset 0 mm): $\\mathrm{gap}$, $v$, $a$")  # a length, not a slider
    # by hand: gap = sqrt(l^2 - r^2 sin^2), gap' = -r^2 s c / gap, gap'' = -r^2 cos 2t / gap - (r^2 s c)^2 / gap^3
    t = sweep.inputs
    s, c = np.sin(t), np.cos(t)
    g = np.sqrt(rod**2 - (r * s) ** 2)
    g1 = -(r**2) * s * c / g
    g2 = -(r**2) * np.cos(2 * t) / g - (r**2 * s * c) ** 2 / g**3
    np.testing.assert_allclose(fig.axes[0].get_lines()[0].get_ydata(), g, rtol=1e-12)
    np.testing.assert_allclose(line(fig.axes[1], "analytic")[1], w * g1, atol=1e-8)
    np.testing.assert_allclose(line(fig.axes[2], "analytic")[1], w**2 * g2 + alpha * g1, atol=1e-6)
    # centred differences of the sampled gap on the open grid 0..180 deg: the interior, by hand
    h = math.radians(1.0)
    _, v = line(fig.axes[1], "centred")
    np.testing.assert_allclose(v[1:-1], w * (g[2:] - g[:-2]) / (2 * h), atol=1e-7)
    assert np.isnan(v[0]) and np.isnan(v[-1])  # the one-sided end stencils are markers of their own
    ends = line(fig.axes[1], "centred: one-sided end stencil")[1]
    np.testing.assert_allclose(ends, w * np.array([(-3 * g[0] + 4 * g[1] - g[2]) / (2 * h),
                                                   (3 * g[-1] - 4 * g[-2] + g[-3]) / (2 * h)]), atol=1e-7)
    _, a = line(fig.axes[2], "centred")  # the frame's second difference, with alpha times its centred one
    np.testing.assert_allclose(a[1:-1], w**2 * (g[2:] - 2 * g[1:-1] + g[:-2]) / h**2
                               + alpha * (g[2:] - g[:-2]) / (2 * h), atol=1e-5)
    # beside the piston's x on one length panel
    fig = figures.position(sweep, ["x", "gap"])
    assert len(fig.axes) == 1 and fig.axes[0].get_ylabel() == "length $x$, $\\mathrm{gap}$ [mm]"
    # the acceleration figure compares it as it does an unknown
    fig = figures.acceleration_comparison(sweep, "gap", exact, fd)
    _, err = line(fig.axes[1], "centred")
    ref = np.abs(w**2 * (g[2:] - 2 * g[1:-1] + g[:-2]) / h**2 + alpha * (g[2:] - g[:-2]) / (2 * h)
                 - (w**2 * g2 + alpha * g1)[1:-1])
    np.testing.assert_allclose(err[1:-1], ref, rtol=1e-6, atol=1e-6)


# ----------------------------------------------------------------------------- a scene
SCENE = """
[scene]
description = "transmission angle"

[mechanism]
linkage = "four_bar"

[mechanism.dimensions]
ground = 4
crank = 1
coupler = 3
rocker = 3

[mechanism.quantities]
mu = { expression = "theta4 - theta3", dimension = "angle" }
reach = { expression = "r3*cos(theta3) + r4", dimension = "length" }

[input]
speed = "10 rad/s"
step_deg = 2

[output]
quantities = ["position", "velocity", "acceleration"]
figures = FIGURES

[compare]
schemes = ["forward", "centred"]
second_schemes = ["second_difference"]

[[check]]
at_deg = 90
"""

WANTED = '["kinematics:mu", "position:mu", "slider:reach"]'


def _scene(tmp_path, figures_=WANTED):
    from numkin.scene import load_scene

    path = tmp_path / "mu.toml"
    path.write_text(SCENE.replace("FIGURES", figures_))
    return load_scene(str(path))


def test_a_scene_renders_the_figures_of_its_derived_quantities(tmp_path):
    """The scene pipeline's figures (render_figures) of a derived angle and length, twice: the same bytes."""
    from numkin.scene import render_figures, run_scene

    scene = _scene(tmp_path)
    result = run_scene(dataclasses.replace(scene, figures=()))
    result.scene = scene
    runs = []
    for k in range(2):
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # nothing skipped
            runs.append(render_figures(result, tmp_path / f"run{k}"))
        assert plt.get_fignums() == []
    assert sorted(p.name for p in runs[0]) == sorted(
        f"{stem}.{ext}" for stem in ("kinematics-mu", "position-mu", "slider-reach") for ext in ("png", "svg"))
    for a, b in zip(runs[0], runs[1]):
        assert a.read_bytes() == b.read_bytes(), a.name
    svg = next(p for p in runs[0] if p.name == "kinematics-mu.svg").read_text()
    assert "forward" in svg and "centred" in svg and "second difference" in svg


def test_a_scene_draws_the_scheme_values_it_compared(tmp_path, monkeypatch):
    """The scene's curves are its comparisons' and its derived kinematics' columns, the same numbers."""
    from numkin.figures import dispatch
    from numkin.scene import render_figures, run_scene

    scene = _scene(tmp_path, '["kinematics:mu"]')
    result = run_scene(dataclasses.replace(scene, figures=()))
    result.scene = scene
    drawn = []

    def spy(*args, _real=dispatch.kinematics, **kwargs):
        drawn.append(_real(*args, **kwargs))
        return drawn[-1]

    monkeypatch.setattr(dispatch, "kinematics", spy)
    render_figures(result, tmp_path / "out", formats=("png",))
    (fig,) = drawn
    compared = result.comparisons["omega_mu"].table
    np.testing.assert_array_equal(line(fig.axes[1], "centred")[1], compared["centred [rad/s]"].to_numpy())
    np.testing.assert_array_equal(line(fig.axes[1], "analytic")[1], result.derived_kinematics["omega_mu"].to_numpy())
    np.testing.assert_array_equal(line(fig.axes[2], "second difference")[1],
                                  result.comparisons["alpha_mu"].table["second_difference [rad/s^2]"].to_numpy())
    t = result.sweep.inputs[::15]
    np.testing.assert_allclose(fig.axes[0].get_lines()[0].get_ydata()[::15], np.degrees(_mu(t)), atol=1e-10)


def test_numkin_run_of_a_scene_with_a_derived_figure_writes_it_twice_the_same(tmp_path):
    from numkin.scene import run_scene

    scene = _scene(tmp_path, '["kinematics:mu"]')
    first = run_scene(scene, out=tmp_path / "a")
    second = run_scene(scene, out=tmp_path / "b")
    names = sorted(p.name for p in first.written)
    assert names == ["kinematics-mu.png", "kinematics-mu.svg"]
    for a, b in zip(sorted(first.written), sorted(second.written)):
        assert a.read_bytes() == b.read_bytes()


# ----------------------------------------------------------------------------- wrong arguments
def _wrong_calls(sweep, exact, fd):
    return [
        (lambda: figures.position("sweep", ["theta3"]), r"position: sweep must be a numkin Sweep.*got str 'sweep'"),
        (lambda: figures.position(sweep.mechanism), r"position: sweep must be a numkin Sweep.*a Mechanism: give "
                                                    r"mechanism.sweep\(inputs\)"),
        (lambda: figures.position(sweep, 3), r"position: names must be a name or a list of names \(str\), got int 3"),
        (lambda: figures.position(sweep, ["mu", 4]), r"position: names must be .*got list \['mu', 4\]"),
        (lambda: figures.derivative(sweep, 3), r"derivative: name must be the name of an unknown or derived"),
        (lambda: figures.derivative(sweep, "mu", schemes=2), r"derivative: schemes must be"),
        (lambda: figures.difference(None, "mu"), r"difference: sweep must be a numkin Sweep \(Mechanism"),
        (lambda: figures.kinematics(sweep, "mu", analytic="exact"),
         r"kinematics: analytic must be a DataFrame.*got str 'exact'"),
        (lambda: figures.kinematics(sweep, "mu", finite=fd["centred"]),
         r"kinematics: finite must map scheme names to DataFrames, got one DataFrame"),
        (lambda: figures.kinematics(sweep, "mu", finite=[fd["centred"]]),
         r"kinematics: finite must map scheme names .*got a list of 1 item"),
        (lambda: figures.kinematics(sweep, "mu", finite={"centred": 1.0}),
         r"kinematics: finite\['centred'\] must be a DataFrame, got float 1.0"),
        (lambda: figures.kinematics(sweep, "mu", analytic=exact, check_angles="90"),
         r"kinematics: check_angles must be input angles in rad \(numbers\), got str '90'"),
        (lambda: figures.kinematics(sweep, "mu", analytic=exact, check_angles=[True]),
         r"kinematics: check_angles must be input angles in rad \(numbers\), got bool True among them"),
        (lambda: figures.kinematics(sweep, "mu", analytic=exact, check_angles=sweep.inputs > 1.0),
         r"kinematics: check_angles must be input angles in rad \(numbers\), got an array of bool"),
        (lambda: figures.mechanism(sweep, True), r"mechanism: at must be an input angle in rad .*got bool True"),
        (lambda: figures.slider(42), r"slider: sweep must be a numkin Sweep"),
        (lambda: figures.acceleration_comparison(sweep, "mu", exact, fd["centred"]),
         r"acceleration_comparison: finite must map scheme names"),
        (lambda: figures.mechanism("sweep"), r"mechanism: sweep must be a numkin Sweep"),
        (lambda: figures.mechanism(sweep, "30"), r"mechanism: at must be an input angle in rad .*got str '30'"),
        (lambda: figures.mechanism(sweep, 0.5, traces=7), r"mechanism: traces must be"),
        (lambda: figures.convergence("table"), r"convergence: table must be a DataFrame from numkin.report"),
        (lambda: figures.work_precision(3), r"work_precision: table must be a DataFrame"),
        (lambda: figures.roundoff(None), r"roundoff: table must be a DataFrame"),
        (lambda: figures.newton_residuals("newton"), r"newton_residuals: tables must be a DataFrame or a mapping"),
        (lambda: figures.newton_residuals({"symbolic": 1}), r"newton_residuals: tables\['symbolic'\] must be"),
        (lambda: figures.save("fig", "/tmp/x"), r"save: fig must be a matplotlib Figure"),
        (lambda: figures.render("result"), r"render: result must be a SceneResult"),
        (lambda: figures.render(types.SimpleNamespace(sweep=sweep), names=3), r"render: names must be"),
        (lambda: figures.render(types.SimpleNamespace(sweep=sweep), names=["position"], formats=[1]),
         r"render: formats must be"),
    ]


def test_figure_functions_name_a_wrong_argument(four_bar):
    sweep = four_bar.sweep
    for call, message in _wrong_calls(sweep, four_bar.analytic, four_bar.finite):
        with pytest.raises(numkin.InputError, match=message):
            call()
    assert plt.get_fignums() == []


def test_save_names_a_wrong_path(four_bar, tmp_path):
    fig = figures.position(four_bar.sweep, "mu")
    with pytest.raises(numkin.InputError, match=r"save: path_stem must be a file path .*got int 3"):
        figures.save(fig, 3)
    assert [p.name for p in figures.save(fig, tmp_path / "mu", ["png"])] == ["mu.png"]


def test_render_draws_a_derived_quantity_from_the_frames_of_the_unknowns(four_bar, tmp_path, monkeypatch):
    """A duck-typed result holding only the unknowns' frames: the derived rates come from their speed and
    schemes, the same numbers as figures.kinematics draws, and those of the closed form's differences."""
    result = types.SimpleNamespace(sweep=four_bar.sweep, analytic=four_bar.analytic, finite=four_bar.finite,
                                   check_angles=[math.radians(90)], figures=["kinematics:mu", "acceleration:mu"])
    drawn = _render_spy(monkeypatch)
    written = figures.render(result, out_dir=tmp_path, formats=["svg"])
    assert [p.name for p in written] == ["kinematics-mu.svg", "acceleration-mu.svg"]
    direct = figures.kinematics(four_bar.sweep, "mu", analytic=four_bar.analytic, finite=four_bar.finite,
                                check_angles=[math.radians(90)])
    for j in (1, 2):
        for label in ("forward", "centred", "analytic"):
            np.testing.assert_array_equal(line(drawn[0].axes[j], label)[1], line(direct.axes[j], label)[1])
    mu = _mu(four_bar.sweep.inputs)
    np.testing.assert_allclose(line(drawn[0].axes[1], "centred")[1], OMEGA * _centred_periodic(mu, math.radians(1)),
                               atol=1e-8)
    again = figures.render(result, out_dir=tmp_path / "again", formats=["svg"])
    assert [p.read_bytes() for p in written] == [p.read_bytes() for p in again]


def test_figure_functions_take_any_iterable_of_names_and_any_path(four_bar, tmp_path):
    """Names as arrays, indexes, dict keys or generators; check angles as 0-d or object arrays; path-likes."""
    import os

    import pandas as pd

    sweep, exact, fd = four_bar.sweep, four_bar.analytic, four_bar.finite
    for names in (np.array(["theta3", "mu"]), pd.Index(["theta3", "mu"]), {"theta3": 1, "mu": 2}.keys(),
                  (n for n in ["theta3", "mu"])):
        fig = figures.position(sweep, names)
        assert [ln.get_label() for ln in fig.axes[0].get_lines()] == ["$\\theta_{3}$", "$\\mu$"]
    fig = figures.derivative(sweep, "mu", np.array(["forward", "centred"]))
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()][::2] == ["forward", "centred"]
    for checks in ([np.array(math.radians(90))], np.array([math.radians(90)], dtype=object),
                   (a for a in [math.radians(90)])):
        fig = figures.kinematics(sweep, "mu", analytic=exact, check_angles=checks)
        assert "$\\mu$(90°) = 86.815°" in " ".join(t.get_text() for t in fig.axes[0].texts)
    fig = figures.kinematics(sweep, "mu", finite=[("centred", fd["centred"])])
    assert "centred" in [ln.get_label() for ln in fig.axes[1].get_lines()]
    assert figures.mechanism(sweep, 0.5, traces=np.array(["B"])).axes

    class Stem(os.PathLike):
        def __fspath__(self):
            return str(tmp_path / "pathlike")

    fig = figures.position(sweep, "mu")
    assert [p.name for p in figures.save(fig, Stem(), {"png"})] == ["pathlike.png"]
    fig = figures.position(sweep, "mu")
    assert [p.name for p in figures.save(fig, tmp_path / "arr", np.array(["png", "svg"]))] == ["arr.png", "arr.svg"]
    fig = figures.position(sweep, "mu")
    assert [p.name for p in figures.save(fig, tmp_path / "gen", (f for f in ["svg"]))] == ["gen.svg"]
    result = types.SimpleNamespace(sweep=sweep)
    assert [p.name for p in figures.render(result, ["position:mu"], tmp_path, {"png"})] == ["position-mu.png"]


# ----------------------------------------------------------------------------- what the frames hold
def test_a_derived_angle_moving_more_than_half_a_turn_per_sample_is_kept_and_said_so():
    """5 theta2 on a 40° grid moves 200° per sample, as its tangent (5) says: a real turn, kept (not bent back by
    -360°), and the grid said to be too coarse, as for an unknown's angle; the drawn values are 5 theta2."""
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"gear": ("5*theta2", "angle")})
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0, 40.0)))
    for draw in (lambda: figures.position(sweep, "gear"),
                 lambda: figures.kinematics(sweep, "gear", finite={"centred": finite_difference(sweep, 2.0)}),
                 lambda: figures.derivative(sweep, "gear")):
        with pytest.warns(UserWarning, match=r"\['gear'\] turn by more than 180° between neighbouring samples \(first "
                                             r"gear, by 200.0° between inputs 0.000° and 40.000°\): the grid is too "
                                             r"coarse"):
            draw()
    from numkin.figures.series import sampled

    with pytest.warns(UserWarning, match="too coarse"):
        np.testing.assert_allclose(sampled(sweep, "gear"), 5 * sweep.inputs, atol=1e-12)
    # and differenced as it is: the centred difference of 5 theta2 is exactly 5 (times omega = 2), ends too
    with pytest.warns(UserWarning, match="too coarse"):
        fig = figures.kinematics(sweep, "gear", finite={"centred": finite_difference(sweep, 2.0)})
    drawn = np.concatenate([ln.get_ydata() for ln in fig.axes[1].get_lines() if "centred" in ln.get_label()
                            or "one-sided" in ln.get_label()])
    np.testing.assert_allclose(drawn, 10.0, atol=1e-9)
    # a fine grid needs no unwrapping: the rates are 5 omega, quietly
    fine = mech.sweep(np.radians(np.arange(0.0, 361.0, 5.0)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig = figures.kinematics(fine, "gear", finite={"centred": finite_difference(fine, 2.0)})
    np.testing.assert_allclose(line(fig.axes[1], "centred")[1], 10.0, atol=1e-9)


def _centred_periodic(y, h):
    """Centred difference of one turn (the last sample repeats the first), computed here."""
    up, down = np.roll(y[:-1], -1), np.roll(y[:-1], 1)
    d = (up - down) / (2 * h)
    return np.append(d, d[0])


def _second_periodic(y, h):
    up, down = np.roll(y[:-1], -1), np.roll(y[:-1], 1)
    d = (up - 2 * y[:-1] + down) / h**2
    return np.append(d, d[0])


def test_a_frame_of_a_coarser_sweep_is_drawn_for_a_derived_quantity_at_its_own_inputs():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities(MU)
    fine = mech.sweep(np.radians(np.arange(0.0, 361.0, 1.0)))
    coarse = mech.sweep(np.radians(np.arange(0.0, 361.0, 10.0)))
    omega, alpha = -7.0, 3.0
    exact = analytic_kinematics(fine, omega, alpha)
    finite = {"centred h=1": finite_difference(fine, omega, alpha),
              "centred h=10": finite_difference(coarse, omega, alpha)}
    fig = figures.kinematics(fine, "mu", analytic=exact, finite=finite)
    x, w = line(fig.axes[1], "centred h=10")
    np.testing.assert_allclose(x, np.arange(0.0, 361.0, 10.0), atol=1e-12)
    t, h = np.radians(x), math.radians(10.0)
    mu = _mu(t)
    d1, d2 = _centred_periodic(mu, h), _second_periodic(mu, h)
    np.testing.assert_allclose(w, omega * d1, atol=1e-9)
    np.testing.assert_allclose(line(fig.axes[2], "centred h=10")[1], omega**2 * d2 + alpha * d1, atol=1e-7)
    fig = figures.acceleration_comparison(fine, "mu", exact, finite)
    np.testing.assert_allclose(line(fig.axes[0], "centred h=10")[1], omega**2 * d2 + alpha * d1, atol=1e-7)


def test_a_frame_that_cannot_give_a_derived_quantity_its_rates_is_refused_by_name(four_bar):
    import pandas as pd

    sweep, exact = four_bar.sweep, four_bar.analytic
    bare = pd.DataFrame(four_bar.finite["centred"].to_dict())  # rebuilt: its attrs are lost
    assert bare.attrs == {}
    figures.kinematics(sweep, "theta4", analytic=exact, finite={"bare": bare})  # an unknown's columns it holds
    with pytest.raises(numkin.InputError, match=r"kinematics of the derived quantity 'mu': finite\['bare'\] holds "
                                                r"no 'omega_mu' column and lacks the attrs \['method', "):
        figures.kinematics(sweep, "mu", analytic=exact, finite={"bare": bare})
    shifted = sweep.mechanism.sweep(sweep.inputs + math.radians(1.0))
    with pytest.raises(numkin.InputError, match=r"finite\['shifted'\] lies on 361 inputs from 1° to 361°, not on "
                                                r"inputs of this sweep \(361 inputs from 0° to 360°\)"):
        figures.acceleration_comparison(sweep, "mu", exact, {"shifted": finite_difference(shifted, OMEGA)})
    with pytest.raises(numkin.InputError, match=r"analytic holds no 'omega_mu' column and lacks the attrs "
                                                r"\['omega'\]"):
        figures.kinematics(sweep, "mu", analytic=pd.DataFrame(exact.to_dict()), finite=four_bar.finite)


def _render_spy(monkeypatch):
    from numkin.figures import dispatch

    drawn = []

    def spy(*args, _real=dispatch.kinematics, **kwargs):
        drawn.append(_real(*args, **kwargs))
        return drawn[-1]

    monkeypatch.setattr(dispatch, "kinematics", spy)
    return drawn


def test_render_joins_derived_kinematics_only_on_the_same_inputs(four_bar, tmp_path, monkeypatch):
    """The derived frame's columns are drawn when it lies on the analytic frame's inputs, never when shifted."""
    import pandas as pd

    from numkin.expressions import derived_kinematics

    sweep = four_bar.sweep
    bare = pd.DataFrame(four_bar.analytic.to_dict())  # no attrs: the derived rates can only come from the join
    derived = derived_kinematics(sweep, OMEGA, names=["mu"])
    drawn = _render_spy(monkeypatch)
    result = types.SimpleNamespace(sweep=sweep, analytic=bare, derived_kinematics=derived, figures=["kinematics:mu"])
    assert [p.name for p in figures.render(result, out_dir=tmp_path, formats=["png"])] == ["kinematics-mu.png"]
    mp.mp.dps = 30
    at = [0, 90, 200]
    d1 = np.array([float(mp.diff(_mu_mp, mp.radians(d))) for d in at])
    np.testing.assert_allclose(line(drawn[-1].axes[1], "analytic")[1][at], OMEGA * d1, atol=1e-9)
    shifted = derived_kinematics(sweep.mechanism.sweep(sweep.inputs + math.radians(1.0)), OMEGA, names=["mu"])
    result.derived_kinematics = shifted
    with pytest.warns(UserWarning, match=r"derived_kinematics lies on other inputs than the analytic kinematics"), \
            pytest.warns(UserWarning, match=r"figure 'kinematics' of the derived quantity 'mu': analytic holds no "
                                            r"'omega_mu' column .*; not drawn"), \
            pytest.warns(figures.FigureSkipped, match=r"figure 'kinematics:mu' skipped"):
        assert figures.render(result, out_dir=tmp_path / "shifted", formats=["png"]) == []


def test_a_position_title_goes_on_two_lines_only_when_one_line_does_not_fit():
    """The four-bar's title of two unknowns fits on one line (as it always did); with three derived
    quantities more it would run off the figure, so the mechanism's name gets a line of its own."""
    plain = linkages.four_bar(4, 1, 3, 3)
    sweep = plain.sweep(np.radians(np.arange(0.0, 361.0, 5.0)))
    title = figures.position(sweep).axes[0].get_title()
    assert title == ("four-bar (ground 4 mm, crank 1 mm, coupler 3 mm, rocker 3 mm): $\\theta_{3}$, $\\theta_{4}$ "
                     "against $\\theta_{2}$")
    more = plain.add_quantities({**MU, "gamma": ("theta3 + theta2", "angle"), "s": ("3*cos(theta3)", "length")})
    fig = figures.position(more.sweep(sweep.inputs))
    head, _, rest = fig.axes[0].get_title().partition("\n")
    assert head == "four-bar (ground 4 mm, crank 1 mm, coupler 3 mm, rocker 3 mm)"
    assert rest == "$\\theta_{3}$, $\\theta_{4}$, $\\mu$, $\\gamma$, $s$ against $\\theta_{2}$"
    text = fig.axes[0].title
    text.set_text(f"{head}: {rest}")
    assert text.get_window_extent(fig.canvas.get_renderer()).width > 0.94 * fig.bbox.width


# ----------------------------------------------------------------------------- grids, signs and gaps
def _forward_periodic(y, h):
    d = (np.roll(y[:-1], -1) - y[:-1]) / h
    return np.append(d, d[0])


def _forward_of_forward_periodic(y, h):
    d = (np.roll(y[:-1], -2) - 2 * np.roll(y[:-1], -1) + y[:-1]) / h**2
    return np.append(d, d[0])


def test_negative_speed_and_acceleration_and_forward_of_forward_against_differences_taken_here():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities(MU)
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0, 2.0)))
    omega, alpha = -6.0, -4.0
    finite = {"f": finite_difference(sweep, omega, alpha, method="forward", second_method="forward_of_forward"),
              "c": finite_difference(sweep, omega, alpha)}
    fig = figures.kinematics(sweep, "mu", analytic=analytic_kinematics(sweep, omega, alpha), finite=finite)
    h, mu = math.radians(2.0), _mu(sweep.inputs)
    f1, f2 = _forward_periodic(mu, h), _forward_of_forward_periodic(mu, h)
    c1, c2 = _centred_periodic(mu, h), _second_periodic(mu, h)
    np.testing.assert_allclose(line(fig.axes[1], "f")[1], omega * f1, atol=1e-8)
    np.testing.assert_allclose(line(fig.axes[2], "f")[1], omega**2 * f2 + alpha * f1, atol=1e-6)
    np.testing.assert_allclose(line(fig.axes[1], "c")[1], omega * c1, atol=1e-8)
    np.testing.assert_allclose(line(fig.axes[2], "c")[1], omega**2 * c2 + alpha * c1, atol=1e-6)
    mp.mp.dps = 30
    at = [0, 45, 133]
    d1 = np.array([float(mp.diff(_mu_mp, mp.radians(2 * k))) for k in at])
    d2 = np.array([float(mp.diff(_mu_mp, mp.radians(2 * k), 2)) for k in at])
    np.testing.assert_allclose(line(fig.axes[1], "analytic")[1][at], omega * d1, atol=1e-9)
    np.testing.assert_allclose(line(fig.axes[2], "analytic")[1][at], omega**2 * d2 + alpha * d1, atol=1e-7)


def test_a_frame_differenced_as_open_draws_the_end_stencils_of_a_derived_quantity(four_bar):
    """periodic=False on a full turn: mu differenced on the open grid, its one-sided ends drawn apart."""
    sweep = four_bar.sweep
    fd = finite_difference(sweep, OMEGA, periodic=False)
    fig = figures.kinematics(sweep, "mu", finite={"c": fd})
    h, mu = math.radians(1.0), _mu(sweep.inputs)
    x, ends = line(fig.axes[1], "c: one-sided end stencil")
    np.testing.assert_allclose(x, [0.0, 360.0], atol=1e-12)
    one_sided = [(-3 * mu[0] + 4 * mu[1] - mu[2]) / (2 * h), (3 * mu[-1] - 4 * mu[-2] + mu[-3]) / (2 * h)]
    np.testing.assert_allclose(ends, OMEGA * np.array(one_sided), atol=1e-8)
    interior = line(fig.axes[1], "c")[1]
    np.testing.assert_allclose(interior[1:-1], OMEGA * (mu[2:] - mu[:-2]) / (2 * h), atol=1e-8)


def test_a_derived_quantity_that_does_not_close_is_differenced_open_and_says_why():
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"half": ("theta2/2", "angle")})
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0, 2.0)))
    fd = finite_difference(sweep, OMEGA)
    assert fd.attrs["periodic"] is True  # the unknowns close
    with pytest.warns(UserWarning, match=r"'half' does not return to its starting value after one turn of the "
                                         r"input \(half\[-1\] - half\[0\] = 180°, not a whole number of turns\): "
                                         r"half = theta2/2 is not periodic in theta2") as caught:
        fig = figures.kinematics(sweep, "half", finite={"c": fd})
    assert not any("branch" in str(w.message) for w in caught)
    x, ends = line(fig.axes[1], "c: one-sided end stencil")  # its open grid's ends, drawn apart
    np.testing.assert_allclose(x, [0.0, 360.0], atol=1e-12)
    np.testing.assert_allclose(ends, OMEGA * 0.5, atol=1e-9)
    spectral = finite_difference(sweep, OMEGA, method="spectral", second_method="spectral_second")
    with pytest.raises(numkin.InputError, match=r"finite\['s'\]: scheme 'spectral' needs a quantity periodic over "
                                                r"exactly one turn of the input, and 'half' does not return"):
        figures.kinematics(sweep, "half", finite={"s": spectral})


def test_a_derived_angle_undefined_on_part_of_the_sweep_is_drawn_where_it_is_defined():
    """acos(mu / 1.3) exists only where mu <= 1.3 rad: NaN elsewhere and wherever a stencil reaches a gap."""
    mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"nanq": ("acos((theta4 - theta3)/1.3)", "angle")})
    sweep = mech.sweep(np.radians(np.arange(0.0, 361.0, 2.0)))
    with pytest.warns(RuntimeWarning, match=r"nanq is not finite at .* first at input 62°"):
        fig = figures.kinematics(sweep, "nanq", analytic=analytic_kinematics(sweep, OMEGA),
                                 finite={"c": finite_difference(sweep, OMEGA)})
    with np.errstate(invalid="ignore"):
        q = np.arccos(_mu(sweep.inputs) / 1.3)
    h = math.radians(2.0)
    ref = np.full(q.size, np.nan)
    ref[1:-1] = (q[2:] - q[:-2]) / (2 * h)
    _, drawn = line(fig.axes[1], "c")
    np.testing.assert_array_equal(np.isnan(drawn[1:-1]), np.isnan(ref[1:-1]))
    np.testing.assert_allclose(drawn[1:-1], OMEGA * ref[1:-1], atol=1e-8)
    assert np.isnan(drawn).sum() > np.isnan(q).sum()  # the stencils at each gap's edge are left out


def test_an_ordinary_step_next_to_a_toggle_is_not_read_by_the_tangent():
    """psi = atan2(sin(theta3 + 2.6), cos(theta3 + 2.6)) wraps once on the way to the crank's toggle of the
    four-bar 4:3:1.5:3 (where d theta3/d theta2 grows without bound): unwrapped, it is theta3 + 2.6 plus one
    constant whole number of turns, the last steps (ordinary ones, under half a turn) included."""
    from numkin.figures.series import sampled

    mech = linkages.four_bar(4, 3, 1.5, 3).add_quantities(
        {"psi": ("atan2(sin(theta3 + 2.6), cos(theta3 + 2.6))", "angle")})
    limit = math.degrees(math.acos(4.75 / 24))  # |A O4| = r3 + r4: 16 + 9 - 24 cos t = 20.25
    sweep = mech.sweep(np.radians(np.linspace(30.0, limit - 1e-9, 60)))
    with pytest.warns(UserWarning, match="wrapped data"):
        psi = sampled(sweep, "psi")
    offset = psi - (sweep["theta3"] + 2.6)
    turns = offset / (2 * math.pi)
    assert np.ptp(offset) < 1e-9 and abs(turns[0] - round(turns[0])) < 1e-9

"""Figures and animations: each figure from real data, checked against independent
references (closed forms derived here, the numbers listed for the source documents); byte-identical
output when rendered twice; no figure left open; matplotlib only imported on demand."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import types
import warnings

import numpy as np
import pytest

pytest.importorskip("matplotlib")
from PIL import Image

from numkin import linkages, report
from numkin.analytic import kinematics as analytic_kinematics
from numkin.kinematics import finite_difference

from numkin import figures
from numkin.animate import animate, frame_indices

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (only to check that no figure is left open)

DEG = math.pi / 180
OMEGA_HW = 7.5  # 450 rad/min
THETA_CHECK = 100 * DEG


# ----------------------------------------------------------------------------- data
@pytest.fixture(scope="module")
def hw():
    """The homework's chained four-bars over one turn, 1° steps, with analytic and finite differences."""
    sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    finite = {
        "forward": finite_difference(sweep, "450 rad/min", method="forward", second_method="forward_of_forward"),
        "centred": finite_difference(sweep, "450 rad/min"),
    }
    return types.SimpleNamespace(sweep=sweep, analytic=analytic_kinematics(sweep, "450 rad/min"), finite=finite)


@pytest.fixture(scope="module")
def crank():
    """The exam's slider-crank (80 mm, 200 mm, 6000 rpm), 0..180° in 1° steps."""
    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    return types.SimpleNamespace(
        sweep=sweep, analytic=analytic_kinematics(sweep, "6000 rpm"),
        finite={"second_difference": finite_difference(sweep, "6000 rpm")},
    )


def _work_precision_table(mech=None):
    """A fresh work-precision table of the homework's beta (its timings measured anew)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return report.work_precision_table(
            mech or linkages.chained_four_bars(), omega="450 rad/min", quantity="beta", grids=(36, 72, 180),
            schemes=("forward", "centred"), repeat=1,
        )


@pytest.fixture(scope="module")
def tables():
    """Real report tables for the homework's beta, on small grids."""
    mech = linkages.chained_four_bars()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = {
            "convergence": report.convergence_table(
                mech, omega="450 rad/min", quantity="beta", check_angle=THETA_CHECK, grids=(36, 72, 180, 360),
                schemes=("forward", "centred", "five_point", "second_difference"),
            ),
            "work_precision": _work_precision_table(mech),
            "roundoff": report.roundoff_table(
                mech, quantity="beta", check_angle=THETA_CHECK, schemes=("forward", "centred", "second_difference"),
                scan_per_decade=2,
            ),
        }
        for jac in ("symbolic", "forward", "central"):
            out[f"newton_{jac}"] = report.newton_table(mech, check_angle=THETA_CHECK, jacobian=jac)
    return out


@pytest.fixture(autouse=True)
def no_open_figures():
    yield
    assert plt.get_fignums() == []


def _abs_c(f, r, t):
    """|f + r e^{it}|, continued analytically to complex t (for the complex step)."""
    return np.sqrt(f * f + r * r + 2 * f * r * np.cos(t))


def _arg_c(f, r, t):
    """arg(f + r e^{it}), continued analytically to complex t (f > r: no branch cut)."""
    return np.arctan(r * np.sin(t) / (f + r * np.cos(t)))


def _phi_branches(theta):
    """Both circle intersections of the homework's linkage 1 (document 003's dimensions).

    B = 2.36 e^{i phi} about C = 0 and |B - A| = 6.86, with A = 7 + 1.94 e^{i theta}.
    """
    d = _abs_c(7.0, 1.94, theta)
    gamma = np.arccos((2.36**2 + d**2 - 6.86**2) / (2 * 2.36 * d))
    arg = _arg_c(7.0, 1.94, theta)
    return arg + gamma, arg - gamma


# the branch of the homework's starting guess phi(0) = 45°
_BRANCH = 0 if abs(_phi_branches(0.0)[0] - 45 * DEG) < abs(_phi_branches(0.0)[1] - 45 * DEG) else 1


def phi_closed_form(theta):
    return _phi_branches(theta)[_BRANCH]


def phi_exact(theta):
    return np.real(phi_closed_form(np.asarray(theta, dtype=float)))


def dphi_exact(theta, h=1e-20):
    return np.imag(phi_closed_form(np.asarray(theta, dtype=float) + 1j * h)) / h


def line(ax, label):
    for ln in ax.get_lines():
        if ln.get_label() == label:
            return np.asarray(ln.get_xdata(), dtype=float), np.asarray(ln.get_ydata(), dtype=float)
    raise AssertionError(f"no line {label!r}; lines: {[ln.get_label() for ln in ax.get_lines()]}")


def all_text(fig) -> str:
    return "\n".join(t.get_text() for t in fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "get_position")))


# ----------------------------------------------------------------------------- imports
def test_importing_numkin_scene_and_figure_names_does_not_import_matplotlib():
    code = (
        "import sys, numkin, numkin.scene, numkin.figures, numkin.animate\n"
        "assert numkin.figures.parse_spec('kinematics:beta') == ('kinematics', 'beta')\n"
        "print('matplotlib' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_closed_form_reference_is_the_homework_branch(hw):
    # the test's own reference agrees with the solved sweep (so the figure checks below are meaningful)
    assert np.allclose(np.unwrap(phi_exact(hw.sweep.inputs)), np.unwrap(hw.sweep["phi"]), atol=1e-9)


# ----------------------------------------------------------------------------- sweep figures
def test_position_plots_phi_in_degrees(hw):
    fig = figures.position(hw.sweep, ["phi"])
    ax = fig.axes[0]
    x, y = ax.get_lines()[0].get_data()
    assert ax.get_xlabel() == r"$\theta$ [deg]" and ax.get_ylabel() == r"$\phi$ [deg]"
    k = 100
    assert x[k] == pytest.approx(100.0)
    assert y[k] == pytest.approx(math.degrees(phi_exact(THETA_CHECK)), abs=1e-8)


def test_derivative_forward_and_centred_against_closed_form(hw):
    fig = figures.derivative(hw.sweep, "phi")
    ax = fig.axes[0]
    h = 1 * DEG
    t = THETA_CHECK
    _, fwd = line(ax, "forward")
    _, cen = line(ax, "centred")
    assert fwd[100] == pytest.approx((phi_exact(t + h) - phi_exact(t)) / h, abs=1e-8)
    assert cen[100] == pytest.approx((phi_exact(t + h) - phi_exact(t - h)) / (2 * h), abs=1e-8)
    # the centred one is the more accurate, as the homework expects
    exact = dphi_exact(t)
    assert abs(cen[100] - exact) < abs(fwd[100] - exact) / 10
    assert "rad/rad" in ax.get_ylabel()


def test_difference_vanishes_where_second_derivative_does(hw):
    fig = figures.difference(hw.sweep, "phi")
    ax, ax2 = fig.axes
    x, delta = ax.get_lines()[0].get_data()
    h = 1 * DEG
    # zeros of phi'' from the closed form, on a fine grid
    tt = np.radians(np.linspace(0, 360, 36001))
    d2 = np.gradient(dphi_exact(tt), tt)
    zeros = np.degrees(tt[1:][np.sign(d2[1:]) != np.sign(d2[:-1])])
    marks = [ln.get_xdata()[0] for ln in ax.get_lines()[1:] if ln.get_linestyle() == ":"]
    assert len(marks) == len(zeros) >= 2
    assert np.allclose(np.sort(marks), np.sort(zeros), atol=0.6)
    # drawn at the interior points only, where Delta is the two interior formulas' difference
    assert np.isnan(delta[[0, -1]]).all() and np.isfinite(delta[1:-1]).all()
    for z in zeros:  # Delta has a minimum, near zero, at each of them
        k = int(round(z))
        assert delta[k] < 0.1 * np.nanmax(delta)
    # Delta ~ (h/2)|phi''|: the forward difference's leading error
    assert np.nanmax(delta) == pytest.approx(h / 2 * np.max(np.abs(d2)), rel=0.05)


def test_kinematics_of_beta_marks_the_check_point(hw):
    fig = figures.kinematics(hw.sweep, "beta", analytic=hw.analytic, finite=hw.finite, check_angles=[THETA_CHECK])
    ax0, ax1, ax2 = fig.axes
    assert ax1.get_ylabel() == r"$\omega_{\beta}$ [rad/s]" and ax2.get_ylabel() == r"$\alpha_{\beta}$ [rad/s²]"
    for ax in (ax1, ax2):
        assert {"forward", "centred", "analytic"} <= {ln.get_label() for ln in ax.get_lines()}
    text = all_text(fig)
    # the exact omega_beta(100°) = 10.633 rad/s, alpha_beta(100°) = -28.375 rad/s² listed for document 003
    assert "analytic: 10.633 rad/s" in text
    assert "analytic: −28.375 rad/s²" in text
    assert r"$\beta$(100°) = 214.727°" in text  # as the mechanism figure writes it (README: 214.7270)
    assert any(abs(ln.get_xdata()[0] - 100) < 1e-12 for ln in ax1.get_lines() if ln.get_linestyle() == ":")


def test_slider_of_the_six_bar():
    sweep = linkages.six_bar().sweep(np.radians(np.arange(0, 361, 2)))
    fig = figures.slider(sweep, analytic=analytic_kinematics(sweep, "-10 rad/s"))
    _, x = fig.axes[0].get_lines()[0].get_data()
    # x_D(0) of the default branch: the closed form of tests/test_linkages.py gives -1.77881 cm to 5 decimals
    # (document 001 shows x_D only as plots)
    assert x[0] == pytest.approx(-1.77881, abs=1e-5)
    assert [ax.get_ylabel() for ax in fig.axes[:3]] == ["$x$ [cm]", "$v_{x}$ [cm/s]", "$a_{x}$ [cm/s²]"]


def test_piston_acceleration_against_the_exam_closed_form(crank):
    fig = figures.acceleration_comparison(crank.sweep, "x", crank.analytic, crank.finite)
    ax, axe = fig.axes
    deg, a = line(ax, "analytic")
    t = np.radians(deg)
    r, l, w = 80.0, 200.0, 6000 * 2 * math.pi / 60
    s, c = np.sin(t), np.cos(t)
    root = np.sqrt(l * l - r * r * s * s)
    x2 = -r * c - r * r * (c * c - s * s) / root - r**4 * s * s * c * c / root**3
    assert np.allclose(a, w * w * x2, rtol=0, atol=1e-9 * np.max(np.abs(w * w * x2)))
    _, num = line(ax, "second difference")
    _, err = line(axe, "second difference")
    assert np.allclose(err, np.abs(num - a), equal_nan=True)
    assert axe.get_yscale() == "log"
    # O(h²) with h = 1°: relative error well under 1e-3
    assert np.nanmax(err) < 1e-3 * np.max(np.abs(a))


def test_quick_return_drawn_with_its_dimensions():
    sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))
    fig = figures.mechanism(sweep, 30 * DEG)
    text = all_text(fig)
    # the values listed for document 000 at theta2 = 30°, and its dimensions
    for expected in ("$r_{3}$ = 87.178 mm", r"$\theta_{3}$ = 66.587°", "$r_{4}$ = 130.767 mm", "$r_{5}$ = 51.962 mm",
                     "$r_1$ = 60 mm", "$r_2$ = 40 mm", "$r_6$ = 60 mm", "$r_3$ = 87.178 mm", "$r_4$ = 130.767 mm"):
        assert expected in text, expected
    assert r"at $\theta_{2}$ = 30°" in text
    # off the grid: solved there, not taken from the nearest point
    fig2 = figures.mechanism(sweep, 30.5 * DEG)
    assert "$r_{3}$ = 87.178 mm" not in all_text(fig2)


# ----------------------------------------------------------------------------- table figures
def test_convergence_reference_slopes_and_observed_order(tables):
    fig = figures.convergence(tables["convergence"])
    ax = fig.axes[0]
    assert (ax.get_xscale(), ax.get_yscale()) == ("log", "log")
    refs = [ln for ln in ax.get_lines() if ln.get_label().startswith("_") and len(ln.get_xdata()) == 50]
    slopes = sorted(round(float(np.polyfit(np.log(ln.get_xdata()), np.log(ln.get_ydata()), 1)[0]), 9) for ln in refs)
    assert slopes == [1.0, 2.0, 4.0]
    h, e = line(ax, "centred (order 2)")
    assert np.log(e[-1] / e[-2]) / np.log(h[-1] / h[-2]) == pytest.approx(2.0, abs=0.1)
    assert {"slope 1", "slope 2", "slope 4"} <= set(all_text(fig).split("\n"))


def test_convergence_draws_the_reference_slope_of_a_registered_higher_order_scheme():
    """A sixth-order scheme registered by its stencil gets a slope-6 reference beside its own line,
    and its own line falls with that slope (observed from the log-log slope of its last two grids)."""
    from numkin import linkages, report, schemes

    schemes.register("seven_point_check", range(-3, 4), 1)
    try:
        conv = report.convergence_table(linkages.chained_four_bars(), omega="450 rad/min", quantity="beta",
                                        grids=(72, 144, 360), schemes=("centred", "seven_point_check"))
        fig = figures.convergence(conv)
    finally:
        schemes.unregister("seven_point_check")
    ax = fig.axes[0]
    refs = [ln for ln in ax.get_lines() if ln.get_label().startswith("_") and len(ln.get_xdata()) == 50]
    slopes = sorted(round(float(np.polyfit(np.log(ln.get_xdata()), np.log(ln.get_ydata()), 1)[0]), 9) for ln in refs)
    assert slopes == [1.0, 2.0, 4.0, 6.0] and "slope 6" in all_text(fig).split("\n")
    h, e = line(ax, "seven point check (order 6)")
    assert np.log(e[-1] / e[-2]) / np.log(h[-1] / h[-2]) == pytest.approx(6.0, abs=0.5)
    plt.close(fig)


def test_roundoff_v_curves(tables):
    fig = figures.roundoff(tables["roundoff"])
    ax = fig.axes[0]
    h, fwd = line(ax, "forward (order 1)")
    k = int(np.nanargmin(fwd))
    assert 0 < k < h.size - 1  # a V: truncation to the right, rounding to the left
    textbook = [ln for ln in ax.get_lines() if ln.get_marker() == "D" and len(ln.get_xdata()) == 1]
    assert min(abs(ln.get_xdata()[0] - math.sqrt(np.finfo(float).eps)) for ln in textbook) < 1e-15
    # the markers are the table's numbers: each step at the error the table measured there
    table = tables["roundoff"].set_index("scheme")
    stars = {(float(ln.get_xdata()[0]), float(ln.get_ydata()[0])) for ln in ax.get_lines()
             if ln.get_marker() == "*" and len(ln.get_xdata()) == 1}
    diamonds = {(float(ln.get_xdata()[0]), float(ln.get_ydata()[0])) for ln in textbook}
    for scheme, row in table.iterrows():
        assert (float(row["measured optimal h [rad]"]), float(row["rel error measured at that h [-]"])) in stars
        if "complex" not in scheme:
            assert (float(row["textbook optimal h [rad]"]), float(row["rel error measured at textbook h [-]"])) in diamonds
    eps_lines = [ln for ln in ax.get_lines() if list(ln.get_ydata()) == [np.finfo(float).eps] * 2]
    assert eps_lines


def test_newton_residuals_per_jacobian(tables):
    newton = {k.split("_", 1)[1]: v for k, v in tables.items() if k.startswith("newton_")}
    fig = figures.newton_residuals(newton)
    ax = fig.axes[0]
    assert ax.get_yscale() == "log"
    for jac in ("symbolic", "forward", "central"):
        k, r = line(ax, f"{jac} Jacobian")
        assert list(k) == list(range(len(k)))
        assert r[-1] < 1e-12 < r[0]
        # quadratic convergence: digits roughly double from iterate 1 to 2 to 3
        assert np.log10(r[3]) / np.log10(r[2]) > 1.6


def test_table_figures_read_what_a_table_carries_not_its_text(tables):
    """The Newton figure takes its Jacobian and check angle from the table's attrs, the round-off figure
    the step of each error column: neither is parsed from a caption or a header."""
    newton = tables["newton_forward"].copy()
    newton.attrs = {**newton.attrs, "caption": ""}
    fig = figures.newton_residuals(newton)
    ax = fig.axes[0]
    assert line(ax, "forward Jacobian")[1][-1] < 1e-12
    assert ax.get_title() == "Newton: residual per iteration at $\\theta$ = 100°"
    plt.close(fig)

    ro = tables["roundoff"].copy()
    steps = dict(ro.attrs["steps"])
    renamed = {column: f"error at step {k}" for k, column in enumerate(steps)}
    ro = ro.rename(columns=renamed)
    ro.attrs = {**tables["roundoff"].attrs, "steps": {renamed[c]: h for c, h in steps.items()}}
    plain = figures.roundoff(tables["roundoff"])
    fig = figures.roundoff(ro)
    assert [list(ln.get_xdata()) for ln in fig.axes[0].get_lines()] == \
        [list(ln.get_xdata()) for ln in plain.axes[0].get_lines()]
    plt.close(fig)
    plt.close(plain)
    ro.attrs = {k: v for k, v in ro.attrs.items() if k != "steps"}
    with pytest.raises(ValueError, match=r"attrs\['steps'\]"):
        figures.roundoff(ro)


def _pareto_points(x, y):
    """Points (x, y) that no other point beats in one coordinate without losing in the other."""
    pts = list(zip(x, y))
    return {(a, b) for a, b in pts if not any(c <= a and d <= b and (c, d) != (a, b) for c, d in pts)}


def test_work_precision_plots_error_against_work_and_rings_the_pareto_front(tables):
    wp = tables["work_precision"]
    fig = figures.work_precision(wp)
    assert len(fig.axes) == 2  # omega_beta, alpha_beta
    for ax, quantity in zip(fig.axes, ["omega_beta [rad/s]", "alpha_beta [rad/s^2]"]):
        assert (ax.get_xscale(), ax.get_yscale()) == ("log", "log")
        assert ax.get_xlabel() == "work [point evaluations + stencil evaluations]"
        assert "varies" not in ax.get_xlabel()
        sub = wp[wp["quantity"] == quantity]
        x, y = sub["work [evaluations]"].to_numpy(float), sub["max abs error [unit of quantity]"].to_numpy(float)
        # each method's curve is its rows' work and error, coarse grid first
        method = "centred" if quantity.startswith("omega") else "analytic"
        k, e = line(ax, method)
        rows = sub[sub["method"] == method]
        assert list(k) == list(rows["work [evaluations]"])
        assert list(e) == list(rows["max abs error [unit of quantity]"])
        # the ringed points are exactly the non-dominated ones (computed here), the same in every run
        fx, fy = line(ax, "Pareto front")
        assert set(zip(fx, fy)) == _pareto_points(x, y)
        assert fx.size >= 1
    assert fig.get_suptitle().startswith("error against work")


def test_work_precision_against_measured_time_says_it_varies(tables):
    fig = figures.work_precision(tables["work_precision"], time="sweep + derivative time")
    ax = fig.axes[0]
    assert ax.get_xlabel() == "sweep + derivative time [ms] (varies between runs)"
    wp = tables["work_precision"]
    sub = wp[wp["quantity"] == "omega_beta [rad/s]"]
    fx, fy = line(ax, "Pareto front")
    assert set(zip(fx, fy)) == _pareto_points(sub["sweep + derivative time [ms] (varies)"].to_numpy(float),
                                              sub["max abs error [unit of quantity]"].to_numpy(float))
    with pytest.raises(ValueError, match="time='sweep \\+ derivative time'"):
        figures.work_precision(wp.drop(columns=[c for c in wp.columns if c.startswith("work")]))


# ----------------------------------------------------------------------------- render + determinism
def _results(hw, crank, tables):
    homework = types.SimpleNamespace(
        sweep=hw.sweep, analytic=hw.analytic, finite=hw.finite, tables=tables, omega=OMEGA_HW,
        check_angles=[THETA_CHECK],
        figures=["position:phi", "derivative:phi", "difference:phi", "kinematics:beta", "mechanism",
                 "convergence", "work-precision", "roundoff", "newton"],
    )
    piston = types.SimpleNamespace(
        sweep=crank.sweep, analytic=crank.analytic, finite=crank.finite, tables={}, omega=200 * math.pi,
        check_angles=[90 * DEG], figures=["slider", "acceleration", "mechanism:90"],
    )
    return homework, piston


def test_render_twice_gives_identical_bytes(hw, crank, tables, tmp_path):
    runs = []
    for k in range(2):
        out = tmp_path / f"run{k}"
        written = []
        # the work-precision table is computed anew for each run, as `numkin figures` does: its timings
        # differ between the runs, its work counts do not, and the figure is drawn from the counts
        fresh = dict(tables, work_precision=_work_precision_table())
        for result in _results(hw, crank, fresh):
            written += figures.render(result, out_dir=out)
        runs.append(written)
        assert plt.get_fignums() == []
    names = sorted(p.name for p in runs[0])
    assert names == sorted(p.name for p in runs[1])
    assert len(names) == 2 * 12
    assert {"kinematics-beta.png", "difference-phi.svg", "acceleration-x.png", "mechanism-90deg.svg",
            "newton.png", "convergence.svg"} <= set(names)
    for a, b in zip(sorted(runs[0]), sorted(runs[1])):
        assert a.read_bytes() == b.read_bytes(), a.name
    png = next(p for p in runs[0] if p.name == "derivative-phi.png")
    with Image.open(png) as im:
        assert im.size == (960, 630)  # 6.4 x 4.2 in at 150 dpi
        assert "Software" not in im.info
    svg = next(p for p in runs[0] if p.name == "derivative-phi.svg").read_text()
    assert "<dc:date>" not in svg and "Matplotlib v" not in svg and "matplotlib.org/" not in svg.split("<metadata>")[1].split("</metadata>")[0]


def test_same_bytes_from_a_fresh_process(tmp_path):
    """Sweeps and drawing are deterministic across processes (and hash seeds)."""
    code = (
        "import sys, numpy as np\n"
        "from numkin import linkages, figures\n"
        "s = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))\n"
        "figures.save(figures.mechanism(s, np.radians(30)), sys.argv[1])\n"
    )
    for k, seed in enumerate(("1", "2")):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        subprocess.run([sys.executable, "-c", code, str(tmp_path / f"qr{k}")], check=True, env=env)
    for ext in ("png", "svg"):
        assert (tmp_path / f"qr0.{ext}").read_bytes() == (tmp_path / f"qr1.{ext}").read_bytes()


def test_render_skips_what_is_absent_and_rejects_mistakes(hw, tmp_path):
    position_only = types.SimpleNamespace(sweep=hw.sweep, figures=["kinematics:beta", "convergence", "position:beta"])
    with pytest.warns(figures.FigureSkipped) as record:
        written = figures.render(position_only, out_dir=tmp_path)
    assert [p.name for p in written] == ["position-beta.png", "position-beta.svg"]
    messages = [str(w.message) for w in record]
    assert any("'kinematics:beta' skipped" in m and "velocity or acceleration" in m for m in messages)
    assert any("'convergence' skipped" in m for m in messages)
    with pytest.raises(ValueError, match="unknown figure 'kinematic'.*did you mean 'kinematics'"):
        figures.render(position_only, names=["kinematic"], out_dir=tmp_path)
    with pytest.raises(ValueError, match="'omega' is not an unknown"):
        figures.render(position_only, names=["position:omega"], out_dir=tmp_path)
    with pytest.raises(ValueError, match="formats: 'jpg'"):
        figures.render(position_only, names=["position"], out_dir=tmp_path, formats=["jpg"])
    assert figures.parse_spec("work_precision") == ("work-precision", None)
    assert figures.parse_spec(" mechanism:30 ") == ("mechanism", "30")
    with pytest.raises(ValueError, match="takes no"):
        figures.parse_spec("newton:beta")


def test_save_closes_a_pyplot_figure(tmp_path):
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    assert plt.get_fignums()
    paths = figures.save(fig, tmp_path / "sub" / "line", formats=("png", "svg", "pdf"))
    assert [p.suffix for p in paths] == [".png", ".svg", ".pdf"]
    assert plt.get_fignums() == []


# ----------------------------------------------------------------------------- animation
def test_frame_indices():
    assert frame_indices(np.radians(np.arange(0, 361)), 72).tolist() == list(range(0, 360, 5))
    assert frame_indices(np.radians(np.arange(0, 181)), 7).tolist() == [0, 30, 60, 90, 120, 150, 180]
    with pytest.raises(ValueError, match="frames = 400 is more than the 360 distinct inputs"):
        frame_indices(np.radians(np.arange(0, 361)), 400)
    with pytest.raises(ValueError, match="frames must be an integer >= 2"):
        frame_indices(np.radians(np.arange(0, 361)), 1)


def test_gif_frame_count_and_identical_bytes(tmp_path):
    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361, 5)))
    paths = [animate(sweep, tmp_path / f"run{k}" / "crank.gif", frames=12, fps=24) for k in range(2)]
    assert plt.get_fignums() == []
    with Image.open(paths[0]) as im:
        assert im.format == "GIF" and im.n_frames == 12
        assert im.info["duration"] == 40  # 1000 / 24 ms, in GIF units of 10 ms
        first = np.asarray(im.convert("RGB"))
        im.seek(3)
        fourth = np.asarray(im.convert("RGB"))
    assert not np.array_equal(first, fourth)
    assert paths[0].read_bytes() == paths[1].read_bytes()
    with pytest.raises(ValueError, match="must end in .gif"):
        animate(sweep, tmp_path / "crank.mp4")


# ----------------------------------------------------------------------------- readable figures
def test_roundoff_optimum_lies_on_its_curve(tables):
    """Each measured-optimum star sits at the table's optimal h, at the error measured there, within the noise of
    the drawn fine scan of its scheme.

    The fine scan is the table's ``attrs["scan"]`` (the steps the optimum is
    measured on), drawn as a thin line of the scheme's colour.
    """
    table = tables["roundoff"]
    scan = table.attrs["scan"]
    ax = figures.roundoff(table).axes[0]
    stars = [ln for ln in ax.get_lines() if ln.get_marker() == "*" and len(ln.get_xdata()) == 1]
    assert len(stars) == len(table)
    for star, (_, row) in zip(stars, table.iterrows()):
        h_star, e_star = float(star.get_xdata()[0]), float(star.get_ydata()[0])
        assert h_star == row["measured optimal h [rad]"]
        curve = next(c for c in ax.get_lines() if c.get_label() == f"_scan {row['scheme']}")
        assert curve.get_color() == star.get_color() and curve.get_linewidth() < 1
        h, e = np.asarray(curve.get_xdata(), float), np.asarray(curve.get_ydata(), float)
        # the thin line is the table's scan, in increasing h
        expected_h = np.asarray(scan["h [rad]"], float)
        order = np.argsort(expected_h)
        assert np.array_equal(h, expected_h[order])
        expected_e = np.asarray(scan[row["scheme"]], float)[order]
        assert np.array_equal(np.isfinite(e), expected_e > 0)
        assert np.array_equal(e[np.isfinite(e)], expected_e[expected_e > 0])
        ok = np.isfinite(e)
        # straight line between the two neighbouring points on log-log axes, computed here
        j = np.searchsorted(h[ok], h_star)
        h0, h1, e0, e1 = h[ok][j - 1], h[ok][j], e[ok][j - 1], e[ok][j]
        expected = e0 * (e1 / e0) ** (math.log(h_star / h0) / math.log(h1 / h0))
        assert e_star == row["rel error measured at that h [-]"]
        assert 0.2 < e_star / expected < 5  # the measurement at that step, near the scan's line through it


def test_scheme_families_agree_with_the_partners():
    from numkin.figures.registries import SCHEME_FAMILY
    from numkin.kinematics import PARTNER

    for second, first in PARTNER.items():
        assert SCHEME_FAMILY[second] == first


def test_coinciding_schemes_stay_visible():
    """Forward and backward (and five-point and Richardson) differ in dash phase or marker, not only colour."""
    from numkin.figures.style import SOURCE_MARKERS, source_style

    for a, b in (("forward", "backward"), ("five_point", "richardson")):
        sa, sb = source_style(a, 0), source_style(b, 1)
        assert sa["linestyle"] != sb["linestyle"]
        assert SOURCE_MARKERS[a][:2] != SOURCE_MARKERS[b][:2]


def test_no_negative_zero_and_units_in_titles(crank):
    from numkin.figures.labels import deg_text, sig5, value_text

    assert sig5(-0.0) == "0.0000" and value_text(-0.0) == "0.000" and deg_text(-1e-13) == "0°"
    assert sig5(-2.5) == "−2.5000"
    sweep = crank.sweep
    fig = figures.slider(sweep, analytic=crank.analytic, finite=crank.finite, check_angles=[0.0, 90 * DEG])
    text = all_text(fig)
    plt.close(fig)
    assert "−0.0000" not in text and "-0.0000" not in text
    # the closed form: v = 0 at the dead centre, printed as a plain zero
    assert "analytic: 0.0000 mm/s" in text
    assert "crank 80 mm, rod 200 mm, offset 0 mm" in fig.axes[0].get_title()


def test_position_axis_names_quantity_and_unit():
    sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361, 5)))
    fig = figures.position(sweep)
    labels = [ax.get_ylabel() for ax in fig.axes]
    plt.close(fig)
    assert labels[0] == "length $r_{3}$, $r_{4}$, $r_{5}$ [mm]"
    assert "r1 60 mm" in fig.axes[0].get_title()


def test_angle_labels_do_not_cover_joints():
    """At theta2 = 0 the six-bar's crank lies along the reference line: its label keeps clear of joint A."""
    sweep = linkages.six_bar().sweep(np.radians(np.arange(0, 361)))
    fig = figures.mechanism(sweep, 0.0)
    ax = fig.axes[0]
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    a = ax.transData.transform(sweep.points()["A"][:, 0])
    for t in ax.texts:
        if t.get_text().startswith("$\\theta"):
            box = t.get_window_extent(renderer)
            assert not (box.x0 - 5 <= a[0] <= box.x1 + 5 and box.y0 - 5 <= a[1] <= box.y1 + 5), t.get_text()
    plt.close(fig)


def test_quick_return_slider_a_is_a_block_along_the_rocker():
    """A slides on O1-B: its block is a rectangle whose long side is parallel to O1B (theta3 from the closed form)."""
    from matplotlib.patches import Polygon

    sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))
    fig = figures.mechanism(sweep, 30 * DEG)
    blocks = [p for p in fig.axes[0].patches if isinstance(p, Polygon) and len(p.get_xy()) >= 4
              and np.isclose(np.mean(p.get_xy()[:4], axis=0), [40 * math.cos(30 * DEG), 60 + 40 * math.sin(30 * DEG)]).all()]
    plt.close(fig)
    assert len(blocks) == 1
    xy = blocks[0].get_xy()[:4]
    side = xy[1] - xy[0]
    # A = O2 + r2 e^{i theta2} with O2 = (0, 60), O1 = (0, 0): theta3 = atan2(A_y, A_x)
    theta3 = math.atan2(60 + 40 * math.sin(30 * DEG), 40 * math.cos(30 * DEG))
    assert math.atan2(side[1], side[0]) == pytest.approx(theta3, abs=1e-9)


def test_velocity_arrows_of_the_crank_pin(crank):
    """v_A = omega r2 perpendicular to O A (closed form), drawn to the stated scale."""
    from numkin.figures.drawing import arrow_vectors

    sweep = crank.sweep
    vec, unit = arrow_vectors(sweep, "velocity", "10 rad/s", points=["A"])
    t = sweep.inputs
    assert unit == "mm/s"
    np.testing.assert_allclose(vec["A"][0], -800 * np.sin(t), atol=1e-9)
    np.testing.assert_allclose(vec["A"][1], 800 * np.cos(t), atol=1e-9)
    fig = figures.mechanism(sweep, 90 * DEG, arrows="velocity", omega="10 rad/s", traces=["A"])
    assert "velocity arrows:" in all_text(fig) and "$v_{A}$" in all_text(fig)
    plt.close(fig)
    with pytest.raises(ValueError, match="give the input speed omega"):
        figures.mechanism(sweep, arrows="velocity")
    with pytest.raises(ValueError, match="traces: 'Q' is not a named point"):
        figures.mechanism(sweep, traces=["Q"])


def test_error_figures_prefer_the_quantity_a_table_carries(tables):
    """A Quantity in attrs names the panel and its unit; without one the table's text stands as it is,
    never parsed back into a quantity."""
    from numkin.quantities import Quantity

    table = tables["convergence"].copy()
    plain = figures.convergence(table)
    titles = [ax.get_title() for ax in plain.axes]
    plt.close(plain)
    assert titles[0] == "$\\omega_{\\beta}$"
    first = table["quantity"].iloc[0]
    table.attrs = {**table.attrs, "quantities": {first: Quantity("x", 1, "length", length_unit="cm")},
                   "title": "piston"}
    fig = figures.convergence(table)
    ax = fig.axes[0]
    assert ax.get_title() == "$v_{x}$" and ax.get_ylabel().endswith("[cm/s]")
    assert fig._suptitle.get_text() == "piston"
    plt.close(fig)
    table.attrs = {k: v for k, v in table.attrs.items() if k != "quantities"}
    fig = figures.convergence(table)
    assert fig.axes[0].get_title() == first and "[rad/s]" not in fig.axes[0].get_ylabel()
    plt.close(fig)


@pytest.mark.slow
def test_cli_figures_all_twice_gives_identical_bytes(tmp_path):
    from numkin.cli import main

    outs = [tmp_path / f"run{k}" for k in range(2)]
    for out in outs:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert main(["figures", "--all", "--out", str(out)]) == 0
    files = sorted(p.relative_to(outs[0]) for p in outs[0].rglob("*") if p.is_file())
    assert files and files == sorted(p.relative_to(outs[1]) for p in outs[1].rglob("*") if p.is_file())
    for rel in files:
        assert (outs[0] / rel).read_bytes() == (outs[1] / rel).read_bytes(), rel


def test_dimension_lines_come_from_the_linkage_spec(monkeypatch):
    """The quick-return is dimensioned by its spec's lines; a changed spec changes the drawing;
    a linkage without dimension lines (the four-bar) labels each link with its length."""
    import dataclasses

    from numkin.figures.registries import dimensions_of

    mech = linkages.quick_return()
    assert dimensions_of(mech) == [tuple(d) for d in linkages.spec("quick_return").dimension_lines]
    assert dimensions_of(linkages.four_bar(4, 1, 3, 3)) is None
    changed = dataclasses.replace(linkages.spec("quick_return"), dimension_lines=(("O1", "O2", "d_{12}", 1.0),))
    monkeypatch.setitem(linkages.SPECS, "quick_return", changed)
    sweep = mech.sweep(np.radians(np.arange(0, 361)))
    text = all_text(figures.mechanism(sweep, 30 * DEG))
    assert "$d_{12}$ = 60 mm" in text and "$r_1$ = 60 mm" not in text


def test_scene_figures_are_never_timed_and_start_where_the_scene_starts(tmp_path, monkeypatch):
    """render_figures: the work-precision figure's table is not timed even when [report] asks for
    timing repeats (the figure plots work counts); the round-off and Newton tables start at start_deg."""
    from numkin import report
    from numkin.scene import load_scene, render_figures, run_scene

    scene_file = tmp_path / "crank.toml"
    scene_file.write_text(
        '[scene]\ndescription = "crank"\n[mechanism]\nlinkage = "slider_crank"\n[mechanism.dimensions]\n'
        'crank = 80\nrod = 200\n[input]\nspeed = "10 rad/s"\nstart_deg = -90\nstop_deg = 270\nstep_deg = 10\n'
        '[output]\nfigures = ["work-precision", "roundoff", "newton"]\n'
        '[report]\nquantity = "x"\ncheck_deg = 60\ngrids = [36, 72]\nschemes = ["centred"]\nrepeat = 3\n'
    )
    calls = {}
    for name in ("work_precision_table", "roundoff_table", "newton_table"):
        real = getattr(report, name)

        def spy(*args, _real=real, _name=name, **kwargs):
            calls.setdefault(_name, []).append(kwargs)
            return _real(*args, **kwargs)

        monkeypatch.setattr(report, name, spy)
    result = run_scene(load_scene(str(scene_file)), figures=False)
    written = render_figures(result, tmp_path / "out", formats=("png",))
    assert sorted(p.name for p in written) == ["newton.png", "roundoff.png", "work-precision.png"]
    assert [kw.get("repeat") for kw in calls["work_precision_table"]] == [None]
    assert not any("time" in str(c) for c in result.report["work_precision"].columns)
    for name in ("roundoff_table", "newton_table"):
        assert calls[name] and all(kw["start"] == pytest.approx(math.radians(-90)) for kw in calls[name]), name


def test_a_check_angle_outside_the_sweep_is_refused_not_dropped():
    """figures.kinematics(check_angles=[100]) (degrees by mistake: 5729.58 deg) said nothing and drew no check."""
    from numkin import analytic, linkages

    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0.0, 361.0, 5.0)))
    with pytest.raises(ValueError, match=r"check_angles 5729.58 deg lie outside the sweep, 0 to 360 deg"):
        figures.kinematics(sweep, "theta4", analytic=analytic.kinematics(sweep, 1.0), check_angles=[100.0])


def test_second_derivative_schemes_drawn_together_have_their_own_colours():
    """Schemes of one panel must be told apart in its legend (whose short handles hide dash patterns)."""
    from numkin.derivatives import SCHEMES
    from numkin.figures.style import source_style

    for derivative in (1, 2):
        names = [s.name for s in SCHEMES.values() if s.derivative == derivative]
        colours = [source_style(name, k)["color"] for k, name in enumerate(names)]
        assert len(set(colours)) == len(colours), dict(zip(names, colours))


def test_a_roundoff_error_measured_as_zero_keeps_its_star_on_the_log_axis():
    """theta4 of the four-bar 4:1:3:3 at 100°: the complex step's error at its optimum is measured as exactly 0,
    which a log axis cannot show; its star sits on the drawn scan there, at a positive error."""
    ro = report.roundoff_table(linkages.four_bar(4, 1, 3, 3), quantity="theta4", check_angle=math.radians(100))
    row = ro.set_index("scheme").loc["complex step"]
    assert row["rel error measured at that h [-]"] == 0.0
    ax = figures.roundoff(ro).axes[0]
    star = next(ln for ln in ax.get_lines() if ln.get_marker() == "*" and len(ln.get_xdata()) == 1
                and ln.get_xdata()[0] == row["measured optimal h [rad]"])
    assert 0 < star.get_ydata()[0] < 1e-12
    plt.close(ax.figure)

"""The ``numkin`` command: subcommands in-process through ``numkin.cli.main``, one real subprocess.

Numbers are checked against the source documents' values (the homework's exact
omega_beta = 10.633 rad/s and alpha_beta = -28.375 rad/s^2 at theta = 100°)
and closed forms derived here (the slider-crank's piston).
"""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
import textwrap

import pytest

from numkin.cli import main

from numkin.schema import SCENES_DIR

#: Every built-in scene: the scene files shipped with numkin.
BUILTINS = sorted(p.stem for p in SCENES_DIR.glob("*.toml"))


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("numkin: error: ") and "Traceback" not in err
    return lines[0]


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return str(path)


FOUR_BAR = """
[scene]
description = "four-bar"
[mechanism]
linkage = "four_bar"
[mechanism.dimensions]
ground = {ground}
crank = {crank}
coupler = {coupler}
rocker = {rocker}
[input]
speed = "{speed}"
stop_deg = 90
step_deg = 5
[output]
quantities = ["position", "velocity"]
"""


def four_bar(tmp_path, ground=4, crank=1, coupler=3, rocker=3, speed="10 rad/s", extra=""):
    text = FOUR_BAR.format(ground=ground, crank=crank, coupler=coupler, rocker=rocker, speed=speed) + extra
    return write(tmp_path, text)


# ------------------------------------------------------------------- scenes
def test_scenes_lists_every_builtin(capsys):
    code, out, err = run(capsys, "scenes")
    assert code == 0 and err == ""
    names = [line.split()[0] for line in out.strip().splitlines()]
    assert sorted(names) == BUILTINS and len(names) == len(BUILTINS)
    # the course's scenes first, in the order of its documents; the stability suite after them
    assert names[:5] == ["homework", "quick-return", "six-bar", "slider-crank", "stability"]
    assert all(len(line.split(None, 1)) == 2 for line in out.strip().splitlines())


# ---------------------------------------------------------------------- run
def test_run_homework_prints_the_check_point(capsys):
    code, out, err = run(capsys, "run", "homework")
    assert code == 0
    line = next(x for x in out.splitlines() if x.strip().startswith("omega_beta [rad/s]"))
    assert "10.633" in line and "expected 10.633 ok" in line
    line = next(x for x in out.splitlines() if x.strip().startswith("alpha_beta [rad/s^2]"))
    assert "-28.375" in line
    assert "largest error over the sweep" in out


def test_run_homework_json(capsys):
    code, out, _ = run(capsys, "run", "homework", "--format", "json", "--at", "100")
    assert code == 0
    data = json.loads(out)
    check = data["checks"][0]
    assert check["at_deg"] == 100 and check["passed"] and data["passed"]
    assert round(check["values"]["omega_beta"], 3) == 10.633
    assert round(check["values"]["alpha_beta"], 3) == -28.375
    assert check["units"]["omega_beta"] == "rad/s" and check["units"]["alpha_beta"] == "rad/s^2"
    # --at prints every quantity: all four unknowns, not only the reported phi and beta
    at = data["at"]
    assert {"phi_deg", "psi_deg", "beta_deg", "gamma_deg", "omega_gamma", "alpha_psi"} <= set(at["values"])
    assert at["values"]["omega_beta"] == check["values"]["omega_beta"]
    errors = data["errors"]["omega_beta"]
    assert errors["unit"] == "rad/s" and errors["forward"]["max_abs_error"] > errors["centred"]["max_abs_error"]
    assert data["input"] == {
        "name": "theta", "start_deg": 0, "stop_deg": 360, "step_deg": 1, "points": 361,
        "speed_rad_s": 7.5, "acceleration_rad_s2": 0,
    }


def test_run_at_between_grid_points_and_out(capsys, tmp_path):
    out_dir = tmp_path / "results"
    code, out, _ = run(capsys, "run", "slider-crank", "--at", "33.3", "--out", str(out_dir))
    assert code == 0
    assert "every quantity at theta = 33.3° (between grid points" in out
    R, L, w = 0.080, 0.200, 200 * math.pi
    t = math.radians(33.3)
    s, c = math.sin(t), math.cos(t)
    root = math.sqrt(L**2 - (R * s) ** 2)
    x = R * c + root
    # the last x line is the --at block's (6 significant digits)
    lines = [x_ for x_ in out.splitlines() if x_.strip().startswith("x [m]")]
    assert float(lines[-1].split()[-1]) == pytest.approx(x, rel=1e-5)
    files = sorted(p.name for p in out_dir.iterdir())
    assert "slider-crank-kinematics.csv" in files and "slider-crank-positions.csv" in files
    assert "acceleration-x.png" in files and "slider-x.svg" in files  # the figures it asks for
    with open(out_dir / "slider-crank-kinematics.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0]) == ["theta [deg]", "v_x [m/s]", "a_x [m/s^2]"]
    assert len(rows) == 181
    # piston at theta = 90°: v = -R w, a = R^2 w^2 / sqrt(L^2 - R^2)
    assert float(rows[90]["v_x [m/s]"]) == pytest.approx(-R * w, rel=1e-9)
    assert float(rows[90]["a_x [m/s^2]"]) == pytest.approx(R**2 * w**2 / math.sqrt(L**2 - R**2), rel=1e-9)


def test_run_quick_return_json_without_speed(capsys):
    code, out, _ = run(capsys, "run", "quick-return", "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["input"]["speed_rad_s"] is None and data["errors"] == {}
    assert [round(data["checks"][0]["values"][k], 3) for k in ("r3", "theta3_deg", "r4", "r5")] == [
        87.178, 66.587, 130.767, 51.962,
    ]


def test_failed_check_exits_1(capsys, tmp_path):
    path = four_bar(tmp_path, extra="[[check]]\nat_deg = 90\ntheta4_deg = 100\n")
    code, out, err = run(capsys, "run", path)
    assert code == 1
    assert "MISMATCH" in out
    assert err.startswith("numkin: check failed: theta4_deg = 119.371 at 90° (expected 100)")
    # the value that missed, to 6 figures (circle intersection: 119.3714°), not to the expected value's 0 decimals
    assert "119.371   expected 100 MISMATCH" in out
    assert len(err.strip().splitlines()) == 1


def test_a_check_agrees_to_the_decimals_as_written_trailing_zeros_too(capsys, tmp_path):
    """TOML reads 119.370 as 119.37; the check still takes the three decimals written (tolerance 5e-4), so
    theta4 = 119.3714° (circle intersection of the 4:1:3:3 four-bar at 90°) misses it, where 119.37 (two
    decimals, tolerance 5e-3) is met; the expected value is shown as written."""
    t2 = math.radians(90.0)
    ax, ay = math.cos(t2), math.sin(t2)  # crank 1 at 90°; ground 4; coupler and rocker 3
    d = math.hypot(4 - ax, ay)
    theta4 = math.degrees(math.atan2(-ay, 4 - ax) + math.pi - math.acos(d / 6))  # isosceles A-B-O4
    assert round(theta4, 4) == 119.3714
    for written, ok in (("119.370", False), ("119.37", True), ("1.1937e2", True), ("119.3714", True),
                        ("119_370e-3", False)):
        path = four_bar(tmp_path, extra=f"[[check]]\nat_deg = 90\ntheta4_deg = {written}  # deg\n")
        code, out, err = run(capsys, "run", path)
        assert code == (0 if ok else 1), (written, out)
        shown = written.replace("_", "")
        if "e" not in shown:
            assert f"expected {shown} {'ok' if ok else 'MISMATCH'}" in out, out
    path = four_bar(tmp_path, extra="[[check]]\nat_deg = 90\ntheta4_deg = 119.370\n")
    code, out, err = run(capsys, "run", path)
    assert "tolerance 0.0005" in out and "theta4_deg = 119.37139 at 90° (expected 119.370)" in err
    # the same check written as an inline array of tables, before the scene's first table
    inline = write(tmp_path, "check = [{ at_deg = 90, theta4_deg = 119.370 }]\n" + open(four_bar(tmp_path)).read())
    code, out, err = run(capsys, "run", inline)
    assert code == 1 and "tolerance 0.0005" in out and "(expected 119.370)" in err


# -------------------------------------------------------------- error paths
@pytest.mark.parametrize(
    "make, words",
    [
        (lambda p: "homwork", ["unknown scene 'homwork'", "did you mean 'homework'"]),
        (lambda p: str(p / "absent.toml"), ["not found"]),
        (lambda p: write(p, "[scene]\ndescription = 'x\n"), ["malformed TOML"]),
        (lambda p: write(p, open(four_bar(p)).read().replace("crank =", "crnak =")),
         ["unknown key 'crnak'", "did you mean 'crank'"]),
        (lambda p: four_bar(p, speed="450 rad/mn"), ["[input] speed", "rad/mn"]),
        (lambda p: four_bar(p, rocker='"3 lightyears"'), ["rocker", "lightyears"]),
        (lambda p: write(p, open(four_bar(p)).read().replace("rocker = 3\n", "")), ["missing dimension 'rocker'"]),
        (lambda p: four_bar(p, ground=10, crank=6, coupler=1, rocker=1),
         ["cannot be assembled at any input angle", "non-assemblable four-bar (l > s + p + q)"]),
        (lambda p: write(p, open(four_bar(p)).read() + "\n[[check]]\nat_dg = 90\ntheta4_deg = 119.371\n"),
         ["[[check]] 1: missing key 'at_deg'", "('at_dg' is written there: did you mean 'at_deg'?)"]),
    ],
    ids=["unknown-scene", "missing-file", "bad-toml", "unknown-key", "bad-unit", "bad-length-unit",
         "missing-dimension", "cannot-assemble", "misspelt-at-deg"],
)
def test_scene_mistakes_exit_2_with_one_line(capsys, tmp_path, make, words):
    code, out, err = run(capsys, "run", make(tmp_path))
    assert code == 2 and out == ""
    line = one_line_error(err)
    for word in words:
        assert word in line


def test_at_outside_the_sweep_exits_2(capsys):
    code, _, err = run(capsys, "run", "quick-return", "--at", "400")
    assert code == 2 and "outside the sweep" in one_line_error(err)


@pytest.mark.parametrize(
    "argv", [["run"], ["run", "homework", "--format", "xml"], ["run", "homework", "--at", "ten"], ["frobnicate"], []],
)
def test_usage_errors_exit_2(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) <= 2 and "error:" in err and "Traceback" not in err


def test_figures_needs_scenes_or_all(capsys, tmp_path):
    code, _, err = run(capsys, "figures", "--out", str(tmp_path))
    assert code == 2 and "--all" in one_line_error(err)
    code, _, err = run(capsys, "figures", "homework", "--all", "--out", str(tmp_path))
    assert code == 2


def test_animate_wants_a_gif(capsys, tmp_path):
    code, _, err = run(capsys, "animate", "quick-return", "--out", str(tmp_path / "a.mp4"))
    assert code == 2 and ".gif" in one_line_error(err)


# --------------------------------------------------------------------- help
@pytest.mark.parametrize("command", ["", "scenes", "run", "report", "figures", "animate", "bench"])
def test_help_has_an_example(capsys, command):
    code, out, _ = run(capsys, *([command] if command else []), "--help")
    assert code == 0
    assert "example" in out and "numkin" in out


# --------------------------------------------------------------- subprocess
def test_console_command_in_a_subprocess():
    proc = subprocess.run(
        [sys.executable, "-m", "numkin", "run", "homework", "--format", "json"],
        capture_output=True, text=True, timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert round(data["checks"][0]["values"]["omega_beta"], 3) == 10.633
    proc = subprocess.run([sys.executable, "-m", "numkin", "run", "nosuch"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and proc.stdout == ""
    one_line_error(proc.stderr)


# ------------------------------------------------- figures, animate, report, bench
def test_figures_of_a_scene_twice_give_the_same_bytes(capsys, tmp_path):
    runs = []
    for k in range(2):
        code, out, err = run(capsys, "figures", "quick-return", "--out", str(tmp_path / f"run{k}"))
        assert code == 0, err
        runs.append(sorted(out.split()))
    names = [p.rsplit("/", 1)[1] for p in runs[0]]
    assert names == ["mechanism-30deg.png", "mechanism-30deg.svg", "position.png", "position.svg"]
    for a, b in zip(*runs):
        assert a.split("/run0/")[1] == b.split("/run1/")[1]
        assert open(a, "rb").read() == open(b, "rb").read()


def test_homework_figures_twice_give_the_same_bytes(capsys, tmp_path):
    """Every figure of the homework, work-precision included: its tables (and their timings) are computed
    anew in each run, and the figure is drawn from exact work counts, not from times."""
    runs = []
    for k in range(2):
        code, out, err = run(capsys, "figures", "homework", "--out", str(tmp_path / f"run{k}"))
        assert code == 0, err
        runs.append(sorted(out.split()))
    names = [p.rsplit("/", 1)[1] for p in runs[0]]
    stems = ["convergence", "derivative-phi", "difference-phi", "kinematics-beta", "mechanism", "newton",
             "position-phi", "roundoff", "work-precision"]
    assert names == sorted(f"{stem}.{ext}" for stem in stems for ext in ("png", "svg"))
    for a, b in zip(*runs):
        assert a.split("/run0/")[1] == b.split("/run1/")[1]
        assert open(a, "rb").read() == open(b, "rb").read(), a


def test_unknown_figure_is_a_scene_mistake(capsys, tmp_path):
    text = open(four_bar(tmp_path)).read().replace("[output]\n", '[output]\nfigures = ["kinematik:theta4"]\n')
    path = write(tmp_path, text)
    code, _, err = run(capsys, "figures", path, "--out", str(tmp_path / "figs"))
    assert code == 2
    line = one_line_error(err)
    assert "[output] figures" in line and "did you mean 'kinematics'" in line


def test_animate_writes_a_gif(capsys, tmp_path):
    from PIL import Image

    gif = tmp_path / "qr.gif"
    code, out, err = run(capsys, "animate", "quick-return", "--out", str(gif), "--frames", "4")
    assert code == 0, err
    with Image.open(gif) as im:
        assert im.n_frames == 4


SMALL_REPORT = """
[scene]
description = "slider-crank report on small grids"
[mechanism]
linkage = "slider_crank"
unit = "m"
[mechanism.dimensions]
crank = "80 mm"
rod = "200 mm"
[input]
speed = "6000 rpm"
step_deg = 10
[[check]]
at_deg = 0
[report]
quantity = "x"
grids = [36, 72]
schemes = ["centred", "second_difference"]
points_per_turn = 36
"""


def test_report_writes_the_error_tables(capsys, tmp_path):
    pytest.importorskip("tabulate")
    path = write(tmp_path, SMALL_REPORT + "repeat = 1\n")
    out_dir = tmp_path / "report"
    code, out, err = run(capsys, "report", path, "--out", str(out_dir))
    assert code == 0, err
    for name in ("convergence", "work_precision", "roundoff", "newton", "jacobian", "tolerance"):
        assert f"## {name}" in out
        assert (out_dir / f"scene-{name}.csv").is_file()
    with open(out_dir / "scene-convergence.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert {r["scheme"] for r in rows} == {"centred", "second_difference"}


def test_bench_prints_the_report(capsys, monkeypatch):
    import types

    import numkin
    import numkin.bench  # noqa: F401  (the real module is what the patches below restore)

    calls = {}
    fake = types.SimpleNamespace(
        run=lambda **kw: calls.setdefault("run", kw) or "table",
        format_report=lambda table: f"speed report of {table!r}",
    )
    monkeypatch.setitem(sys.modules, "numkin.bench", fake)
    monkeypatch.setattr(numkin, "bench", fake, raising=False)
    code, out, _ = run(capsys, "bench", "--repeat", "2")
    assert code == 0 and out.strip() == "speed report of {'repeat': 2}"
    assert calls["run"] == {"repeat": 2}
    calls.clear()
    code, _, _ = run(capsys, "bench", "--textbook-points", "3")  # as README's Speed section names it
    assert code == 0 and calls["run"] == {"textbook_points": 3}


def test_stability_scene_with_chosen_cases(capsys, tmp_path):
    scene = '[scene]\ndescription = "two cases"\n[stability]\ncases = ["cannot assemble (10, 6, 1, 1)", "{second}"]\n'
    path = write(tmp_path, scene.format(second="non-Grashof (7, 4, 3, 5), full turn"))
    code, out, err = run(capsys, "run", path, "--format", "json")
    assert code == 0, err
    data = json.loads(out)
    assert [c["outcome"] for c in data["stability"]] == ["AssemblyError", "AssemblyError"] and data["passed"]
    path = write(tmp_path, scene.format(second="cannot asemble (10, 6, 1, 1)"))
    code, _, err = run(capsys, "run", path)
    assert code == 2 and "did you mean 'cannot assemble (10, 6, 1, 1)'" in one_line_error(err)


# ------------------------------------------------- solver errors, start-up
def test_solver_error_is_one_line_naming_the_scene_file(capsys, tmp_path):
    text = FOUR_BAR.format(ground=10, crank=6, coupler=1, rocker=1, speed="1 rad/s")
    path = write(tmp_path, text, name="cannot-assemble.toml")
    code, out, err = run(capsys, "run", path)
    line = one_line_error(err)
    assert code == 2 and out == ""
    assert line.startswith("numkin: error: cannot-assemble.toml: ") and "cannot be assembled at any input angle" in line


def test_overflowing_dimensions_are_one_line_naming_the_scene_file(capsys, tmp_path):
    text = FOUR_BAR.format(ground=4e160, crank=1e160, coupler=3e160, rocker=3e160, speed="1 rad/s")
    path = write(tmp_path, text, name="huge.toml")
    code, _, err = run(capsys, "run", path)
    line = one_line_error(err)
    assert code == 2 and line.startswith("numkin: error: huge.toml: ")


def test_report_of_a_stability_scene_is_its_suite(capsys, tmp_path):
    cases = ["cannot assemble (10, 6, 1, 1)", "non-Grashof (7, 4, 3, 5), full turn"]
    path = write(tmp_path, f'[scene]\ndescription = "two cases"\n[stability]\ncases = {json.dumps(cases)}\n')
    out_dir = tmp_path / "report"
    code, out, err = run(capsys, "report", path, "--out", str(out_dir))
    assert code == 0, err
    assert out.startswith("## stability") and all(c in out for c in cases)
    with open(out_dir / "scene-stability.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["case"] for r in rows] == cases and {r["outcome"] for r in rows} == {"AssemblyError"}
    assert (out_dir / "scene-stability.md").is_file() and (out_dir / "scene-stability.tex").is_file()


@pytest.mark.parametrize("name", BUILTINS)
def test_report_of_every_builtin_scene(capsys, tmp_path, name):
    """``numkin report`` works for every built-in scene (one without input speed, the stability suite)
    and writes each table as Markdown, CSV and LaTeX; the terminal shows lines of at most 120 characters."""
    code, out, err = run(capsys, "report", name, "--out", str(tmp_path))
    assert code == 0, err
    tables = sorted(line[3:] for line in out.splitlines() if line.startswith("## "))
    assert tables
    for table in tables:
        for suffix in ("md", "csv", "tex"):
            assert (tmp_path / f"{name}-{table}.{suffix}").is_file(), (table, suffix)
    assert max(len(line) for line in out.splitlines()) <= 120
    assert "nan" not in out.lower().split()


def test_report_settings_of_a_scene_without_speed(capsys, tmp_path):
    """[report] settings apply without an input speed: the tables are per rad/s of input speed."""
    path = write(tmp_path, SMALL_REPORT.replace('speed = "6000 rpm"\n', ""))
    code, out, err = run(capsys, "report", path, "--out", str(tmp_path))
    assert code == 0, err
    with open(tmp_path / "scene-convergence.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert {r["scheme"] for r in rows} == {"centred", "second_difference"}
    assert {r["points per turn"] for r in rows} == {"36", "72"}
    assert "per rad/s of input speed" in out


def test_report_is_timed_only_with_repeat(capsys, tmp_path):
    path = write(tmp_path, SMALL_REPORT)
    headers = {}
    for argv in ([], ["--repeat", "1"]):
        out_dir = tmp_path / f"out{len(argv)}"
        code, out, err = run(capsys, "report", path, "--out", str(out_dir), *argv)
        assert code == 0, err
        with open(out_dir / "scene-work_precision.csv") as fh:
            headers[len(argv)] = next(csv.reader(fh))
    timed = [h for h in headers[2] if "time [ms]" in h]
    assert timed and all("(varies)" in h for h in timed)
    assert not any("time" in h for h in headers[0])
    code, _, err = run(capsys, "report", path, "--repeat", "0")
    assert code == 2 and err.startswith("numkin report: error: argument --repeat") and len(err.splitlines()) == 1


def test_stability_iterations_blank_where_nothing_was_solved(capsys, tmp_path):
    cases = ["cannot assemble (10, 6, 1, 1)", "slider-crank 80/200 at 6000 rpm"]
    path = write(tmp_path, f'[scene]\ndescription = "two cases"\n[stability]\ncases = {json.dumps(cases)}\n')
    code, out, err = run(capsys, "report", path, "--out", str(tmp_path))
    assert code == 0, err
    with open(tmp_path / "scene-stability.csv") as fh:
        rows = {r["case"]: r for r in csv.DictReader(fh)}
    assert rows[cases[0]]["Newton iterations (max)"] == ""
    assert int(float(rows[cases[1]]["Newton iterations (max)"])) >= 1
    code, out, err = run(capsys, "run", path)
    assert code == 0, err
    line = next(ln for ln in out.splitlines() if ln.strip().startswith(cases[0]))
    assert "AssemblyError" in line and " - " in line and "-1" not in line


# ------------------------------------------------- animate options
def _animate_calls(monkeypatch):
    import numkin.animate

    calls = []

    def fake(sweep, path, **kwargs):
        calls.append((sweep, kwargs))
        return path

    monkeypatch.setattr(numkin.animate, "animate", fake)
    return calls


def test_animate_options_reach_animate(capsys, tmp_path, monkeypatch):
    calls = _animate_calls(monkeypatch)
    code, _, err = run(capsys, "animate", "homework", "--out", str(tmp_path / "h.gif"), "--frames", "8", "--fps", "12.5",
                       "--dpi", "50", "--width", "4", "--turn", "sweep", "--trace", "B", "C", "--arrows", "velocity")
    assert code == 0, err
    sweep, kwargs = calls[0]
    # the homework's speed is 450 rad/min = 7.5 rad/s, kept though the animation solves positions only
    assert kwargs == {"frames": 8, "fps": 12.5, "dpi": 50, "width": 4.0, "turn": "sweep", "traces": ["B", "C"],
                      "arrows": "velocity", "omega": pytest.approx(7.5, rel=1e-15)}
    assert sweep.inputs.size == 361
    calls.clear()
    code, _, err = run(capsys, "animate", "homework", "--out", str(tmp_path / "h.gif"))
    assert code == 0, err
    assert calls[0][1] == {"frames": 72}  # nothing but the scene's frame count: animate's own defaults


def test_animate_defaults_from_the_scene_and_acceleration_for_arrows(capsys, tmp_path, monkeypatch):
    text = FOUR_BAR.format(ground=4, crank=1, coupler=3, rocker=3, speed="10 rad/s").replace(
        "stop_deg", 'acceleration = "-2 rad/s^2"\nstop_deg')
    path = write(tmp_path, text + (
        '\n[animation]\nframes = 6\nfps = 10\ndpi = 40\nwidth = 3\nturn = "sweep"\ntraces = ["B"]\n'
        'arrows = "acceleration"\n'
    ))
    calls = _animate_calls(monkeypatch)
    code, _, err = run(capsys, "animate", path, "--out", str(tmp_path / "a.gif"), "--dpi", "60")
    assert code == 0, err
    assert calls[0][1] == {"frames": 6, "fps": 10.0, "dpi": 60, "width": 3.0, "turn": "sweep", "traces": ["B"],
                           "arrows": "acceleration", "omega": 10.0, "alpha": -2.0}


def test_animate_gif_size_follows_width_and_dpi(capsys, tmp_path):
    from PIL import Image

    gif = tmp_path / "sc.gif"
    code, _, err = run(capsys, "animate", "slider-crank", "--out", str(gif), "--frames", "3", "--dpi", "20",
                       "--width", "6", "--arrows", "velocity", "--trace", "A")
    assert code == 0, err
    with Image.open(gif) as im:
        assert (im.n_frames, im.size[0]) == (3, 120)


@pytest.mark.parametrize("argv, words", [
    (["--dpi", "601"], "--dpi"), (["--dpi", "9"], "--dpi"), (["--width", "0.5"], "--width"),
    (["--width", "41"], "--width"), (["--fps", "0"], "--fps"), (["--turn", "half"], "--turn"),
    (["--arrows", "speed"], "--arrows"), (["--arrows", "velocity"], "no [input] speed"),
])
def test_animate_option_mistakes_exit_2(capsys, tmp_path, argv, words):
    code, _, err = run(capsys, "animate", "quick-return", "--out", str(tmp_path / "q.gif"), *argv)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and "Traceback" not in err
    assert lines[0].startswith(("numkin: error: ", "numkin animate: error: ")) and words in lines[0]
    assert not (tmp_path / "q.gif").exists()


@pytest.mark.parametrize("argv", [[], ["--help"], ["scenes"]])
def test_start_up_loads_no_sympy_pandas_or_matplotlib(argv):
    """``import numkin``, ``numkin --help`` and ``numkin scenes`` stay light (a fresh interpreter each):
    not even numpy is needed to list the scenes."""
    code = (
        "import sys, contextlib, io\n"
        "import numkin\n"
        "from numkin.cli import main\n"
        f"argv = {argv!r}\n"
        "if argv:\n"
        "    with contextlib.redirect_stdout(io.StringIO()):\n"
        "        assert main(argv) == 0\n"
        "heavy = [m for m in ('sympy', 'pandas', 'matplotlib', 'numpy') if m in sys.modules]\n"
        "assert not heavy, heavy\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr


def test_lazy_names_of_the_package():
    import numkin

    assert numkin.Mechanism.__name__ == "Mechanism" and callable(numkin.newton)
    import numkin.newton as _  # noqa: F401  (importing the submodule keeps numkin.newton the function)

    assert callable(numkin.newton) and numkin.newton.__name__ == "newton"
    with pytest.raises(AttributeError, match="no attribute 'nonexistent'"):
        numkin.nonexistent  # noqa: B018


def test_an_error_numkin_does_not_check_for_is_told_apart_from_a_mistake(capsys, monkeypatch):
    """A mistake numkin checks for is a NumkinError (exit 2); any other ValueError is a check numkin
    lacks or a defect: one line that says so (exit 3), the traceback with NUMKIN_TRACEBACK=1."""
    import numkin.cli as cli

    def broken(args):
        raise ValueError("operands could not be broadcast together with shapes (3,) (4,)")

    monkeypatch.setattr(cli, "_cmd_scenes", broken)
    monkeypatch.delenv("NUMKIN_TRACEBACK", raising=False)
    code, out, err = run(capsys, "scenes")
    line = one_line_error(err)
    assert code == 3 and out == ""
    assert "broadcast" in line and "not an error numkin checks for" in line and "NUMKIN_TRACEBACK=1" in line
    monkeypatch.setenv("NUMKIN_TRACEBACK", "1")
    with pytest.raises(ValueError, match="broadcast"):
        main(["scenes"])


def test_every_error_numkin_raises_on_purpose_is_a_numkin_error():
    """Input checks raise InputError (a NumkinError and a ValueError), never a bare ValueError,
    so that the command can tell a user's mistake from a defect."""
    import pathlib

    import numkin
    from numkin import linkages

    with pytest.raises(numkin.InputError, match="crank") as caught:
        linkages.four_bar(4.0, -1.0, 3.0, 3.0)
    assert isinstance(caught.value, ValueError) and isinstance(caught.value, numkin.NumkinError)
    package = pathlib.Path(numkin.__file__).parent
    bare = [f"{path.relative_to(package)}:{number}" for path in sorted(package.rglob("*.py"))
            for number, text in enumerate(path.read_text().splitlines(), 1)
            if "raise ValueError(" in text or "= ValueError(" in text]
    assert bare == []


def test_run_summary_gives_the_dimensions_with_their_unit(capsys):
    # the scene works in metres (crank 80 mm, rod 200 mm): the summary's dimensions say so
    assert main(["run", "slider-crank"]) == 0
    out = capsys.readouterr().out
    assert "  slider-crank (crank 0.08 m, rod 0.2 m, offset 0 m); theta 0..180° step 1°" in out


def test_a_mismatching_check_value_never_reads_as_its_expected_value():
    from numkin.cli_text import fmt_value

    assert fmt_value(123456.789, 123457.0, mismatch=True) == "123456.79"
    assert fmt_value(0.004, 0.0, mismatch=True) == "0.00400000"
    assert fmt_value(6.3701234, 6.371, mismatch=True) == "6.37012"
    assert fmt_value(6.3701234, 6.371) == "6.370"  # a value that passes: to the expected value's decimals

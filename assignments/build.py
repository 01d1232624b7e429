#!/usr/bin/env python
"""Build, check and grade the numkin homework with otter-grader.

Each homework folder ``assignments/<hw>/`` holds an otter master notebook kept
as a jupytext percent-format source ``<hw>.py``, the reference values its
hidden tests use (``expected.json``) and the deliberate mistakes used to test
the feedback (``mistakes.toml``).  ``kincheck/`` (next to this script) is the
feedback package every homework ships.

Commands::

    python assignments/build.py expected           # recompute references with numkin, rewrite them
    python assignments/build.py expected --check   # fail if the committed references are stale
    python assignments/build.py assign [HW ...]    # jupytext -> .ipynb -> otter assign, into assignments/dist/
    python assignments/build.py grade HW SUBMISSION ... [--out DIR] [--venv DIR] [--timeout S]  # otter run on each
    python assignments/build.py mistakes [HW ...] [--venv DIR]  # grade the deliberate mistakes, show the feedback
    python assignments/build.py new SCENE.toml     # a homework master generated from a scene

With ``--venv DIR`` grading happens in a virtual environment made from the
autograder zip's requirements alone (otter-grader, numpy, matplotlib), as on
Gradescope or with ``otter grade``; see ``grading.py``.  Homework 5's reference
values come from mpmath (``exam004.py``), a generated homework's from its scene
(``fromscene.py``).

The reference values are computed by numkin from its ready-made linkages
(``numkin.linkages``), its finite-difference schemes (``numkin.derivatives``)
and its analytic velocity and acceleration (``numkin.analytic``).  They are
written to ``expected.json`` and into the master source, on every line that
ends with ``# reference: <key>``.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))  # fromscene.py, grading.py, exam004.py

from grading import (  # noqa: E402,F401
    TIMEOUT,
    GradingError,
    environment,
    grading_venv,
    isolated_env,
    run,
    tool,
    zip_requirements,
)
KINCHECK = HERE / "kincheck"  # the feedback package, a folder of modules
DIST = HERE / "dist"

HOMEWORK = (
    "hw1_chained_four_bar",
    "hw2_quick_return",
    "hw3_slider_crank",
    "hw4_six_bar",
    "hw5_quadrature_pendulum",
)

MARKER = re.compile(r"^(?P<head>\s*\w+ = )(?P<value>.*?)(?P<tail>\s+# reference: (?P<key>[\w.]+)\s*)$")
SIGNIFICANT = 12  # digits kept in the committed reference values


# --------------------------------------------------------------------------
# reference values, computed with numkin
# --------------------------------------------------------------------------


def _np():
    import numpy as np

    return np


def _at(values, inputs_deg, degrees) -> dict:
    """{angle: value} for the listed angles (degrees) of a sampled array."""
    np = _np()
    inputs_deg = np.asarray(inputs_deg, dtype=float)
    out = {}
    for d in degrees:
        k = int(np.argmin(np.abs(inputs_deg - d)))
        assert abs(inputs_deg[k] - d) < 1e-9, f"{d} deg is not on the grid"
        out[int(d)] = float(values[k])
    return out


def _wrap(angles):
    np = _np()
    return np.mod(angles, 2 * np.pi)


def _analytic(sweep, omega):
    """numkin's analytic velocities and accelerations of a sweep (a DataFrame)."""
    from numkin import analytic

    return analytic.kinematics(sweep, omega=omega)


def _column(frame, *names):
    for name in names:
        if name in frame.columns:
            return frame[name].to_numpy()
    raise KeyError(f"none of {names} in numkin.analytic.kinematics columns {list(frame.columns)}")


def expected_hw1() -> dict:
    """Chained four-bars (source 003): φ, β and their differences, ω = 450 rad/min."""
    np = _np()
    from numkin import derivatives, linkages

    check = list(range(10, 360, 30))  # 10, 40, ..., 340: interior, includes 100
    theta_deg = np.arange(0, 361)
    sweep = linkages.chained_four_bars().sweep(np.radians(theta_deg))
    h = math.radians(1.0)
    omega = 450.0 / 60.0
    phi, beta = sweep["phi"], sweep["beta"]
    kin = _analytic(sweep, "450 rad/min")
    i100 = int(np.flatnonzero(theta_deg == 100)[0])
    return {
        "phi": _at(_wrap(phi), theta_deg, check),
        "beta": _at(_wrap(beta), theta_deg, check),
        "dphi_forward": _at(derivatives.forward(phi, h), theta_deg, check),
        "dphi_centred": _at(derivatives.centred(phi, h), theta_deg, check),
        "dphi_backward": _at(derivatives.backward(phi, h), theta_deg, check),
        "dbeta_dt_forward": _at(omega * derivatives.forward(beta, h), theta_deg, check),
        "dbeta_dt_centred": _at(omega * derivatives.centred(beta, h), theta_deg, check),
        "dbeta_dt_backward": _at(omega * derivatives.backward(beta, h), theta_deg, check),
        "d2beta_dt2_second": _at(omega**2 * derivatives.second_difference(beta, h), theta_deg, check),
        "d2beta_dt2_forward_twice": _at(
            omega**2 * derivatives.forward_of_forward(beta, h), theta_deg, check
        ),
        # np.gradient is numpy's, applied to numkin's sweep: what a student who calls it twice gets
        "d2beta_dt2_gradient_twice": _at(omega**2 * np.gradient(np.gradient(beta, h), h), theta_deg, check),
        "omega_beta_100": float(_column(kin, "omega_beta")[i100]),
        "alpha_beta_100": float(_column(kin, "alpha_beta")[i100]),
        "omega_beta_fw_100": float(omega * derivatives.forward(beta, h)[i100]),
        "omega_beta_bw_100": float(omega * derivatives.backward(beta, h)[i100]),
        "alpha_beta_fw_100": float(omega**2 * derivatives.forward_of_forward(beta, h)[i100]),
    }


def expected_hw2() -> dict:
    """Quick-return mechanism (source 000): position at θ2 = 30° and over a turn."""
    np = _np()
    from numkin import linkages

    mech = linkages.quick_return(r1=60, r2=40, r6=60)
    at30 = mech.sweep([math.radians(30.0)])
    check = list(range(0, 360, 30))
    theta_deg = np.arange(0, 361)
    turn = mech.sweep(np.radians(theta_deg))
    return {
        "x_30": [float(at30[name][0]) for name in ("r3", "theta3", "r4", "r5")],
        "r3_30": float(at30["r3"][0]),
        "theta3_30": float(_wrap(at30["theta3"])[0]),
        "r4_30": float(at30["r4"][0]),
        "r5_30": float(at30["r5"][0]),
        "theta3": _at(_wrap(turn["theta3"]), theta_deg, check),
        "r5": _at(turn["r5"], theta_deg, check),
    }


def expected_hw3() -> dict:
    """Slider-crank (source 004, problem 1): piston position and acceleration at 6000 rpm."""
    import warnings

    from numkin import DegreesWarning, derivatives, linkages

    np = _np()
    theta_deg = np.arange(0, 181)
    check = list(range(0, 181, 20))
    mech = linkages.slider_crank(crank=80, rod=200)
    sweep = mech.sweep(np.radians(theta_deg))
    kin = _analytic(sweep, "6000 rpm")
    accel = _column(kin, "a_x", "acc_x", "xddot", "x_ddot", "alpha_x") / 1000.0  # mm/s² -> m/s²
    inside = check[1:-1]  # 20, ..., 160: the centred second difference of the grid's own x
    second = derivatives.second_difference(np.asarray(sweep["x"]) / 1000.0, math.radians(1.0))  # m/rad²
    # θ in degrees handed to a function of radians: x at θ = 0, 1, ..., 180 rad, which numkin warns of
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegreesWarning)
        in_radians = mech.sweep(theta_deg.astype(float))
    return {
        "x": _at(sweep["x"], theta_deg, check),
        "x_at_degrees_as_radians": _at(in_radians["x"], theta_deg, check),
        "d2x_second": _at(second, theta_deg, inside),
        "a": _at(accel, theta_deg, check),
        "a_0": float(accel[0]),
        "a_90": float(accel[90]),
    }


def expected_hw4() -> dict:
    """Six-bar with a slider (source 001): x, v, a of D, ω2 = -10 rad/s."""
    np = _np()
    from numkin import linkages

    theta_deg = np.arange(0, 361)
    sweep = linkages.six_bar().sweep(np.radians(theta_deg))
    kin = _analytic(sweep, "-10 rad/s")
    velocity = _column(kin, "v_x", "vel_x", "xdot", "x_dot", "omega_x")
    accel = _column(kin, "a_x", "acc_x", "xddot", "x_ddot", "alpha_x")
    check = list(range(0, 360, 30))
    inside = check[1:]  # rates at interior angles only: any formula may be used at the ends
    return {
        "x": _at(sweep["x"], theta_deg, check),
        "v": _at(velocity, theta_deg, inside),
        "a": _at(accel, theta_deg, inside),
    }


EXPECTED = {
    "hw1_chained_four_bar": expected_hw1,
    "hw2_quick_return": expected_hw2,
    "hw3_slider_crank": expected_hw3,
    "hw4_six_bar": expected_hw4,
    "hw5_quadrature_pendulum": lambda: __import__("exam004").expected(),
}


# --------------------------------------------------------------------------
# writing and checking the committed values
# --------------------------------------------------------------------------


def _round(x: float) -> float:
    return float(f"{x:.{SIGNIFICANT}g}")


def _rounded(value):
    if isinstance(value, dict):
        return {int(k): _round(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_round(v) for v in value]
    return _round(value)


def _literal(value) -> str:
    """The Python literal written into a master source."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {v!r}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(repr(v) for v in value) + "]"
    return repr(value)


def folder(hw) -> Path:
    """The folder of a homework: a name in assignments/, or the path of a folder (generated ones)."""
    path = Path(hw)
    if str(hw) in HOMEWORK or not path.is_dir():
        return HERE / str(hw)
    return path.resolve()


def master_path(hw) -> Path:
    where = folder(hw)
    return where / f"{where.name}.py"


def expected_path(hw) -> Path:
    return folder(hw) / "expected.json"


def compute(hw) -> dict:
    """Reference values of one homework, freshly computed by numkin and rounded."""
    where = folder(hw)
    if (where / "scene.toml").exists():
        import fromscene

        values = fromscene.expected(where)
    else:
        values = EXPECTED[where.name]()
    return {k: _rounded(v) for k, v in values.items()}


def new_from_scene(scene: Path, root: Path = HERE) -> Path:
    """A homework master generated from a scene file, with its reference values; returns its folder."""
    import fromscene

    where = fromscene.generate(Path(scene), Path(root))
    write(where, compute(where))
    return where


def load_expected(hw: str) -> dict:
    data = json.loads(expected_path(hw).read_text())
    return {
        k: ({int(d): v for d, v in value.items()} if isinstance(value, dict) else value)
        for k, value in data["values"].items()
    }


def master_markers(hw: str) -> dict:
    """{key: [values written on each marker line]} of a master source."""
    import ast

    found: dict = {}
    for line in master_path(hw).read_text().splitlines():
        match = MARKER.match(line)
        if match:
            found.setdefault(match["key"], []).append(ast.literal_eval(match["value"]))
    return found


def write(hw: str, values: dict) -> None:
    """Write expected.json and the marker lines of the master source."""
    payload = {
        "about": (
            f"Reference values of {folder(hw).name}, computed by "
            + ("mpmath (assignments/exam004.py)" if folder(hw).name == "hw5_quadrature_pendulum" else "numkin")
            + " (python assignments/build.py expected). Angles in rad, keys of "
            "dictionaries are input angles in degrees."
        ),
        "values": {
            k: ({str(d): x for d, x in v.items()} if isinstance(v, dict) else v)
            for k, v in values.items()
        },
    }
    expected_path(hw).write_text(json.dumps(payload, indent=1, ensure_ascii=False) + "\n")

    lines, used = [], set()
    for line in master_path(hw).read_text().splitlines(keepends=True):
        match = MARKER.match(line.rstrip("\n"))
        if match:
            key = match["key"]
            if key not in values:
                raise KeyError(f"{master_path(hw)}: marker key {key!r} is not computed by numkin")
            used.add(key)
            line = f"{match['head']}{_literal(values[key])}{match['tail']}\n"
        lines.append(line)
    master_path(hw).write_text("".join(lines))
    unused = set(values) - used
    if unused:
        print(f"{hw}: not used in the master: {sorted(unused)}", file=sys.stderr)


AGREE = 1e-7
"""Committed and fresh values agree when they differ by at most this fraction of their size
(the largest magnitude of a dictionary or list): far below the tolerances of the checks
(1e-6 and up), far above the rounding noise of numkin's sweeps (1e-9 in second differences)."""


def _differs(a, b, rtol: float = AGREE) -> bool:
    if isinstance(a, dict) or isinstance(b, dict):
        if not (isinstance(a, dict) and isinstance(b, dict)) or set(a) != set(b):
            return True
        a, b = [a[k] for k in sorted(a)], [b[k] for k in sorted(a)]
    if isinstance(a, list) or isinstance(b, list):
        if not (isinstance(a, list) and isinstance(b, list)) or len(a) != len(b):
            return True
    else:
        a, b = [a], [b]
    scale = max(max(abs(x), abs(y)) for x, y in zip(a, b))
    return any(abs(x - y) > rtol * scale for x, y in zip(a, b))


def _committed(hw: str) -> dict:
    try:
        return load_expected(hw)
    except FileNotFoundError:
        return {}


def _kept(hw: str, fresh: dict) -> dict:
    """``fresh``, but for the values whose committed version agrees with it (:data:`AGREE`): those stay as
    committed, so that rebuilding unchanged references leaves the files as they are (fresh values differ
    from run to run and version to version only by rounding noise, in their last digits)."""
    committed = _committed(hw)
    return {k: committed[k] if k in committed and not _differs(committed[k], v) else v for k, v in fresh.items()}


def stale(hw: str, fresh: dict | None = None) -> list[str]:
    """Disagreements between committed references (json and master) and numkin's values."""
    problems = []
    fresh = compute(hw) if fresh is None else fresh
    try:
        committed = load_expected(hw)
    except FileNotFoundError:
        return [f"{hw}: {expected_path(hw).name} is missing"]
    for key in sorted(set(fresh) | set(committed)):
        if key not in committed:
            problems.append(f"{hw}: {key} missing from expected.json")
        elif key not in fresh:
            problems.append(f"{hw}: {key} in expected.json is no longer computed")
        elif _differs(committed[key], fresh[key]):
            problems.append(f"{hw}: {key} committed {committed[key]} but numkin gives {fresh[key]}")
    for key, written in master_markers(hw).items():
        for value in written:
            if key not in committed or _differs(value, committed[key], 0.0):
                problems.append(f"{hw}: master line '# reference: {key}' disagrees with expected.json")
    return problems


# --------------------------------------------------------------------------
# otter
# --------------------------------------------------------------------------


def notebook(hw, dest: Path) -> Path:
    """Convert the jupytext master to ``dest/<hw>.ipynb``; copy kincheck/ and the folder's other .py files beside it."""
    import jupytext

    dest.mkdir(parents=True, exist_ok=True)
    nb = jupytext.read(master_path(hw))
    path = dest / f"{folder(hw).name}.ipynb"
    jupytext.write(nb, path)
    no_bytecode = shutil.ignore_patterns("__pycache__")
    shutil.copytree(KINCHECK, dest / KINCHECK.name, ignore=no_bytecode, dirs_exist_ok=True)
    for extra in sorted(folder(hw).glob("*.py")):  # linkage.py, odecheck.py: listed in the config's files
        if extra != master_path(hw):
            shutil.copy(extra, dest / extra.name)
    return path


def assign(hw, out: Path = DIST, *, run_tests: bool = True) -> Path:
    """``otter assign`` one homework into ``out/<hw>/{student,autograder}``; returns ``out/<hw>``."""
    result = Path(out).resolve() / folder(hw).name
    if result.exists():
        shutil.rmtree(result)
    source = notebook(hw, result / "source")
    cmd = [tool("otter"), "assign", str(source), str(result)]
    if not run_tests:
        cmd.append("--no-run-tests")
    subprocess.run(cmd, check=True)
    return result


def autograder_zip(result: Path) -> Path:
    zips = sorted((result / "autograder").glob("*-autograder_*.zip"))
    if not zips:
        raise FileNotFoundError(f"no autograder zip in {result / 'autograder'}: run assign first")
    return zips[-1]


def score(results: dict) -> tuple[float, float]:
    """(score, possible) of an otter results.json."""
    got = sum(t.get("score") or 0.0 for t in results["tests"] if "max_score" in t)
    possible = sum(t.get("max_score") or 0.0 for t in results["tests"] if "max_score" in t)
    return got, possible


def mistakes(hw: str) -> list[dict]:
    """The deliberate mistakes of a homework (``mistakes.toml``)."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python < 3.11
        import tomli as tomllib

    path = folder(hw) / "mistakes.toml"
    if not path.exists():
        return []
    return tomllib.loads(path.read_text())["mistake"]


def apply_mistake(solution: Path, mistake: dict, dest: Path) -> Path:
    """Write a copy of the solution notebook with the mistake's edits made, as ``dest``."""
    import nbformat

    nb = nbformat.read(solution, as_version=4)
    for edit in mistake["edit"]:
        hits = [cell for cell in nb.cells if edit["find"] in cell.source]
        count = sum(cell.source.count(edit["find"]) for cell in hits)
        if count != 1:
            raise ValueError(
                f"mistake {mistake['name']!r}: {edit['find']!r} occurs {count} times in {solution}"
            )
        hits[0].source = hits[0].source.replace(edit["find"], edit["replace"])
    dest.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, dest)
    return dest


def feedback(results: dict) -> str:
    """All test output of an otter results.json, public and hidden, as one text."""
    return "\n".join(t.get("output", "") for t in results["tests"])


def grade(hw_or_zip: str, submissions: list[Path], out: Path, venv: Path | None = None,
          timeout: float | None = TIMEOUT) -> Path:
    """Run ``otter run`` on every submission; write one results folder each and scores.csv.

    A submission that cannot be graded (``otter run`` fails, or takes more than ``timeout``
    seconds) gets a row of its own, with no score and the reason in ``error``, and the
    others are graded all the same.
    """
    target = Path(hw_or_zip)
    autograder = target if target.suffix == ".zip" else autograder_zip(DIST / hw_or_zip)
    bin_dir = environment(autograder, venv)
    rows = []
    for submission in submissions:
        folder = out / submission.stem
        try:
            results = run(submission, autograder, folder, bin_dir=bin_dir, timeout=timeout)
        except GradingError as error:
            rows.append({"submission": submission.name, "score": "", "possible": "", "error": str(error)})
            print(f"{submission.name}: not graded: {error} (see {error.log})")
            continue
        got, possible = score(results)
        rows.append({"submission": submission.name, "score": got, "possible": possible, "error": ""})
        print(f"{submission.name}: {got:g} / {possible:g}")
    out.mkdir(parents=True, exist_ok=True)
    table = out / "scores.csv"
    with table.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["submission", "score", "possible", "error"])
        writer.writeheader()
        writer.writerows(rows)
    return table


def ungraded(table: Path) -> list[str]:
    """The submissions of a scores.csv that could not be graded."""
    with table.open(newline="") as f:
        return [row["submission"] for row in csv.DictReader(f) if row["error"]]


# --------------------------------------------------------------------------
# command line
# --------------------------------------------------------------------------


def _homework(names: list[str]) -> list[str]:
    if not names:
        return list(HOMEWORK)
    unknown = [n for n in names if n not in HOMEWORK and not (Path(n) / "mistakes.toml").exists()]
    if unknown:
        raise SystemExit(f"unknown homework {unknown}; choose from {list(HOMEWORK)}")
    return names


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="build.py", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("expected", help="recompute the reference values with numkin")
    p.add_argument("homework", nargs="*", help=f"default: all of {', '.join(HOMEWORK)}")
    p.add_argument("--check", action="store_true", help="only compare; exit 1 if stale")

    p = sub.add_parser("new", help="generate a homework master from a scene file (numkin scene TOML)")
    p.add_argument("scene", type=Path, help="a scene .toml with a [mechanism] and an [input] speed")
    p.add_argument("--root", type=Path, default=HERE, help="folder to write hw_<scene>/ in (default: assignments/)")

    p = sub.add_parser("assign", help="build student and autograder versions with otter assign")
    p.add_argument("homework", nargs="*")
    p.add_argument("--out", type=Path, default=DIST)
    p.add_argument("--no-run-tests", action="store_true", help="skip otter's check of the solutions")

    p = sub.add_parser("grade", help="grade submissions with otter run (no Docker)")
    p.add_argument("homework", help="homework name (uses assignments/dist) or autograder zip")
    p.add_argument("submissions", nargs="+", type=Path, help=".ipynb or .zip files, or folders of them")
    p.add_argument("--out", type=Path, default=Path("grades"))
    p.add_argument("--venv", type=Path, help="grade in this virtual environment, made from the zip's "
                   "requirements alone if it does not exist (as Gradescope / otter grade do)")
    p.add_argument("--timeout", type=float, default=TIMEOUT, metavar="SECONDS",
                   help=f"stop a submission that takes longer and record it as timed out (default {TIMEOUT:g}; "
                   "0: no limit)")

    p = sub.add_parser("mistakes", help="grade the solution and each deliberate mistake, print feedback")
    p.add_argument("homework", nargs="*")
    p.add_argument("--out", type=Path, default=DIST)
    p.add_argument("--venv", type=Path, help="as for grade")

    args = parser.parse_args(argv)
    try:
        return _run(args)
    except FileNotFoundError as error:
        raise SystemExit(str(error)) from None


def _run(args) -> int:
    if args.command == "expected":
        failed = False
        for hw in _homework(args.homework):
            fresh = compute(hw)
            if args.check:
                problems = stale(hw, fresh)
                for problem in problems:
                    print(problem)
                failed |= bool(problems)
            else:
                committed = _committed(hw)
                write(hw, _kept(hw, fresh))
                moved = sum(1 for k, v in fresh.items() if k not in committed or _differs(committed[k], v))
                print(f"{hw}: {len(fresh)} reference values written ({moved} new or changed beyond rounding noise)")
        return 1 if failed else 0
    if args.command == "new":
        where = new_from_scene(args.scene, args.root)
        print(f"{where.name}: master {master_path(where)}; next: python assignments/build.py assign {where}")
        return 0
    if args.command == "assign":
        for hw in _homework(args.homework):
            result = assign(hw, args.out, run_tests=not args.no_run_tests)
            print(f"{hw}: student version in {result / 'student'}, autograder in {autograder_zip(result)}")
        return 0
    if args.command == "grade":
        files = []
        for path in args.submissions:
            files += sorted(path.glob("*.zip")) + sorted(path.glob("*.ipynb")) if path.is_dir() else [path]
        table = grade(args.homework, files, args.out, args.venv, args.timeout or None)
        print(f"scores written to {table}")
        missing = ungraded(table)
        if missing:
            print(f"not graded ({len(missing)}): {', '.join(missing)}; the reason is in scores.csv's error column")
        return 1 if missing else 0
    if args.command == "mistakes":
        for hw in _homework(args.homework):
            result = assign(hw, args.out, run_tests=False)
            name = result.name
            bin_dir = environment(autograder_zip(result), args.venv)
            solution = result / "autograder" / f"{name}.ipynb"
            graded = run(solution, autograder_zip(result), result / "graded" / "solution", bin_dir=bin_dir)
            print(f"{name} solution: {'%g / %g' % score(graded)}")
            for mistake in mistakes(hw):
                wrong = apply_mistake(solution, mistake, result / "mistakes" / mistake["name"] / f"{name}.ipynb")
                graded = run(wrong, autograder_zip(result), wrong.parent, bin_dir=bin_dir)
                print(f"\n{name} {mistake['name']} ({mistake['about']}): {'%g / %g' % score(graded)}"
                      f" (mistakes.toml: {mistake.get('score')})")
                for test in graded["tests"]:
                    if test.get("max_score") and test.get("score") != test.get("max_score"):
                        print(f"  {test['name']}: {test.get('score'):g} / {test['max_score']:g}")
                print(feedback(graded))
        return 0
    return 2


if __name__ == "__main__":
    sys.exit(main())

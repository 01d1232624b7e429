"""Build every homework with otter and grade it the way the autograder image does.

Gradescope and ``otter grade`` (Docker) grade in an environment built from the
autograder zip alone: otter-grader and the ``requirements`` of the master's
ASSIGNMENT CONFIG, as listed in the zip's ``environment.yml``.  These tests build
each autograder zip with ``otter assign``, then build one fresh virtual
environment per distinct requirement list, holding only those packages (no numkin,
nothing of the development environment), and grade there with ``otter run``:

* the solution scores full marks;
* every deliberate mistake of ``assignments/<hw>/mistakes.toml`` scores exactly the
  ``score`` it states (its ``rubric`` says which checks fail) and gets the feedback
  it names;
* homework generated from scenes none of the ready homework uses (an offset
  slider-crank, whose output is a length, and a crank-rocker, whose output is an
  angle) build and grade the same way, with the mistakes ``build.py new`` writes;
* ``build.py grade`` records a submission it cannot grade, or that never ends, and
  goes on with the others;
* what the README tells students to install runs the student notebook.

Everything is built once per pytest run; the submissions are graded two at a
time.  The environment needs PyPI (or a local index) to be reachable.
"""

from __future__ import annotations

import csv
import json
import os
import re
import shutil
import subprocess
import time
import zipfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from conftest import load_module

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
ASSIGNMENTS = ROOT / "assignments"
WORKERS = max(1, min(2, os.cpu_count() or 1))


_load = load_module


build = _load("numkin_assignments_build", ASSIGNMENTS / "build.py")

HOMEWORK = list(build.HOMEWORK)
KINCHECK = sorted(p.name for p in build.KINCHECK.glob("*.py"))  # the feedback package's modules
MISTAKES = [(hw, m["name"]) for hw in HOMEWORK for m in build.mistakes(hw)]

OFFSET_SLIDER_CRANK = """\
[scene]
description = "Offset slider-crank: crank 30 mm, rod 100 mm, offset 12 mm, 300 rpm"

[mechanism]
linkage = "slider_crank"
unit = "mm"

[mechanism.dimensions]
crank = 30
rod = 100
offset = 12

[input]
speed = "300 rpm"
start_deg = 0
stop_deg = 360
step_deg = 1

[[check]]
at_deg = 60
"""

CRANK_ROCKER = """\
[scene]
description = "A crank-rocker at 100 rpm"

[mechanism]
linkage = "four_bar"
unit = "mm"

[mechanism.dimensions]
ground = 40
crank = 10
coupler = 30
rocker = 30

[input]
speed = "100 rpm"
start_deg = 0
stop_deg = 360
step_deg = 1

[[check]]
at_deg = 100
"""

GENERATED = {"hw_offset_slider_crank": OFFSET_SLIDER_CRANK, "hw_crank_rocker": CRANK_ROCKER}


@pytest.fixture(scope="session")
def built(tmp_path_factory):
    """otter assign of every homework and of those generated from scenes: {name: result folder}."""
    pytest.importorskip("otter")
    pytest.importorskip("jupytext")
    out = tmp_path_factory.mktemp("assignments")
    generated = []
    for name, text in GENERATED.items():
        scene = out / f"{name.removeprefix('hw_').replace('_', '-')}.toml"
        scene.write_text(text)
        generated.append(build.new_from_scene(scene, out / "masters"))
    names = [*HOMEWORK, *generated]
    with ThreadPoolExecutor(WORKERS) as pool:
        folders = list(pool.map(lambda hw: build.assign(hw, out / "dist", run_tests=False), names))
    return {Path(str(hw)).name: (hw, folder) for hw, folder in zip(names, folders)}


@pytest.fixture(scope="session")
def environments(built, tmp_path_factory):
    """One fresh virtual environment per distinct requirement list of the zips: {zip: bin folder}."""
    root = tmp_path_factory.mktemp("grading-venv")
    wanted: dict[tuple, list[Path]] = {}
    for _, folder in built.values():
        autograder = build.autograder_zip(folder)
        wanted.setdefault(tuple(build.zip_requirements(autograder)), []).append(autograder)
    found = {}
    for k, (requirements, zips) in enumerate(sorted(wanted.items())):
        bin_dir = build.grading_venv(list(requirements), root / f"env{k}")
        found.update({z: bin_dir for z in zips})
    return found


@pytest.fixture(scope="session")
def graded(built, environments):
    """Grade every solution and every deliberate mistake in the fresh environments."""
    jobs = []
    for name, (hw, folder) in built.items():
        solution = folder / "autograder" / f"{name}.ipynb"
        jobs.append((name, "solution", solution, folder / "graded" / "solution"))
        for mistake in build.mistakes(hw):
            wrong = folder / "mistakes" / mistake["name"] / f"{name}.ipynb"
            build.apply_mistake(solution, mistake, wrong)
            jobs.append((name, mistake["name"], wrong, wrong.parent))

    def grade(job):
        name, _, submission, out = job
        autograder = build.autograder_zip(built[name][1])
        try:
            return build.run(submission, autograder, out, bin_dir=environments[autograder])
        except Exception as error:  # reported by the test that needs it
            return error

    with ThreadPoolExecutor(WORKERS) as pool:
        return dict(zip([(j[0], j[1]) for j in jobs], pool.map(grade, jobs)))


def _results(graded, hw, name) -> dict:
    outcome = graded[(hw, name)]
    if isinstance(outcome, Exception):
        raise outcome
    return outcome


# --------------------------------------------------------------------------
# what otter assign builds
# --------------------------------------------------------------------------


@pytest.mark.parametrize("hw", HOMEWORK)
def test_otter_assign_builds_student_and_autograder_versions(built, hw):
    result = built[hw][1]
    student = (result / "student" / f"{hw}.ipynb").read_text()
    autograder = (result / "autograder" / f"{hw}.ipynb").read_text()
    assert sorted(p.name for p in (result / "student" / "kincheck").iterdir()) == KINCHECK  # all, no bytecode
    assert "grader.check(" in student
    assert "BEGIN SOLUTION" not in student and "hidden: true" not in student
    expected = build.load_expected(hw)
    for key, value in expected.items():
        values = value.values() if isinstance(value, dict) else value if isinstance(value, list) else [value]
        precise = [repr(v) for v in values if len(repr(v)) >= 10]  # not round numbers like 80.0
        assert precise, key
        for text in precise:
            assert text not in student, f"reference value {key} ({text}) leaked into the student notebook"
            assert text in autograder, f"reference value {key} ({text}) missing from the hidden tests"
    with zipfile.ZipFile(build.autograder_zip(result)) as archive:
        names = archive.namelist()
        tests = "".join(archive.read(n).decode() for n in names if re.match(r"tests/.*\.py$", n))
    assert sorted(n for n in names if n.startswith("files/kincheck/")) == [f"files/kincheck/{m}" for m in KINCHECK]
    assert "hidden=True" in tests


def _solution_lines(hw: str) -> list[str]:
    """Code the master marks as solution: lines in '# BEGIN SOLUTION' blocks, '# SOLUTION' lines."""
    found, inside = [], False
    for line in build.master_path(hw).read_text().splitlines():
        text = line.strip()
        if text.startswith("# BEGIN SOLUTION"):
            inside = True
        elif text.startswith("# END SOLUTION"):
            inside = False
        elif inside:
            found.append(text)
        elif text.endswith("# SOLUTION"):
            found.append(text.removesuffix("# SOLUTION").strip())
    return [line for line in found if len(line) >= 20 and not line.startswith("#")]


@pytest.mark.parametrize("hw", HOMEWORK)
def test_student_version_has_no_solutions(built, hw):
    cells = json.loads((built[hw][1] / "student" / f"{hw}.ipynb").read_text())["cells"]
    student = "\n".join("".join(cell["source"]) for cell in cells)
    lines = _solution_lines(hw)
    assert len(lines) >= 3
    leaked = [line for line in lines if line in student]
    assert not leaked, f"solution code in the student notebook: {leaked}"
    assert student.count("= ...") + student.count("    ...") >= 2


def _public_points(text: str) -> list[str]:
    return re.findall(r"@test_case\(points=([\d.]+), hidden=False", text)


@pytest.mark.parametrize("hw", [*HOMEWORK, *GENERATED])
def test_zip_asks_for_what_the_notebook_imports_and_logs_match(built, hw):
    """The image gets numpy and matplotlib; public checks carry the same points for
    students as for grading, so otter run finds no "differs from logged score"."""
    result = built[hw][1]
    requirements = build.zip_requirements(build.autograder_zip(result))
    names = {re.split(r"[<>=\[ ]", r)[0].lower() for r in requirements}
    assert {"otter-grader", "numpy", "matplotlib"} <= names
    assert "numkin" not in names
    with zipfile.ZipFile(build.autograder_zip(result)) as archive:
        for test in (result / "student" / "tests").glob("*.py"):
            graded = archive.read(f"tests/{test.name}").decode()
            assert _public_points(test.read_text()) == _public_points(graded), test.name


def test_grading_environment_is_isolated(built, environments, tmp_path):
    bin_dir = next(iter(environments.values()))
    env = build.isolated_env(bin_dir)
    python = str(bin_dir / "python")
    numkin = subprocess.run([python, "-c", "import numkin"], env=env, capture_output=True, text=True, cwd=tmp_path)
    assert "No module named 'numkin'" in numkin.stderr, "numkin is importable in the grading environment"
    sympy = subprocess.run([python, "-c", "import sympy"], env=env, capture_output=True, text=True, cwd=tmp_path)
    assert "No module named 'sympy'" in sympy.stderr, "the grading environment holds numkin's dependencies"
    plot = subprocess.run([python, "-c", "import matplotlib, numpy, otter"], env=env, cwd=tmp_path)
    assert plot.returncode == 0


# --------------------------------------------------------------------------
# grading in the fresh environment
# --------------------------------------------------------------------------


@pytest.mark.parametrize("hw", [*HOMEWORK, *GENERATED])
def test_solution_scores_full_marks(graded, hw):
    results = _results(graded, hw, "solution")
    got, possible = build.score(results)
    assert possible > 0
    assert got == possible, build.feedback(results)


@pytest.mark.parametrize("hw, name", MISTAKES)
def test_mistake_scores_what_mistakes_toml_states_and_is_named(graded, hw, name):
    results = _results(graded, hw, name)
    got, possible = build.score(results)
    text = build.feedback(results)
    (mistake,) = [m for m in build.mistakes(hw) if m["name"] == name]
    assert got == mistake["score"], f"{name}: {got} / {possible}, mistakes.toml says {mistake['score']}\n{text}"
    assert 0 < got <= possible
    for words in mistake["feedback"]:
        assert words in text, f"{name}: feedback lacks {words!r}:\n{text}"
    for words in mistake.get("not_feedback", []):
        assert words not in text, f"{name}: feedback names a cause the evidence does not support {words!r}:\n{text}"
    assert "Traceback" not in text and "ValueError" not in text, text


@pytest.mark.parametrize("name", GENERATED)
def test_generated_homework_mistakes(built, graded, name):
    hw, _ = built[name]
    names = [m["name"] for m in build.mistakes(hw)]
    assert ("q-check-degrees" in names) == (name == "hw_crank_rocker")  # only where the output is an angle
    for mistake in build.mistakes(hw):
        results = _results(graded, name, mistake["name"])
        got, _ = build.score(results)
        text = build.feedback(results)
        assert got == mistake["score"], f"{mistake['name']}: {got}\n{text}"
        for words in mistake["feedback"]:
            assert words in text, f"{mistake['name']}: feedback lacks {words!r}:\n{text}"
        for words in mistake.get("not_feedback", []):
            assert words not in text, f"{mistake['name']}: feedback names {words!r}:\n{text}"


def _processes_mentioning(text: str) -> list[int]:
    """Ids of this user's processes whose environment or command line mentions ``text`` (Linux /proc)."""
    found = []
    for proc in Path("/proc").glob("[0-9]*"):
        try:
            seen = (proc / "environ").read_bytes() + (proc / "cmdline").read_bytes()
        except OSError:
            continue
        if text.encode() in seen and int(proc.name) != os.getpid():
            found.append(int(proc.name))
    return found


def test_grade_goes_on_past_a_submission_that_fails_or_never_ends(built, environments, tmp_path):
    """``build.py grade`` on a folder holding a right notebook, one whose cell never ends and one that is no
    notebook: each gets its row in scores.csv (the last two with the reason, no score), the loop is stopped
    after --timeout seconds with its kernel, and the exit status says that some were not graded."""
    nbformat = pytest.importorskip("nbformat")
    hw = "hw3_slider_crank"
    folder = built[hw][1]
    autograder = build.autograder_zip(folder)
    solution = folder / "autograder" / f"{hw}.ipynb"
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    shutil.copy(solution, submissions / "alice.ipynb")
    notebook = nbformat.read(solution, as_version=4)
    notebook.cells.insert(3, nbformat.v4.new_code_cell("while True:\n    pass"))
    nbformat.write(notebook, submissions / "bob.ipynb")
    (submissions / "carol.ipynb").write_text("{ this is not a notebook")
    out = tmp_path / "grades"
    timeout = 45
    start = time.monotonic()
    status = build.main(["grade", str(autograder), str(submissions), "--out", str(out),
                         "--venv", str(environments[autograder].parent), "--timeout", str(timeout)])
    elapsed = time.monotonic() - start
    assert status == 1
    with (out / "scores.csv").open(newline="") as f:
        rows = {row["submission"]: row for row in csv.DictReader(f)}
    assert list(rows) == ["alice.ipynb", "bob.ipynb", "carol.ipynb"]
    assert float(rows["alice.ipynb"]["score"]) == float(rows["alice.ipynb"]["possible"]) == 8  # hw3: 8 points
    assert rows["alice.ipynb"]["error"] == ""
    assert rows["bob.ipynb"]["score"] == "" and rows["bob.ipynb"]["error"].startswith(f"timed out after {timeout} s")
    assert rows["carol.ipynb"]["score"] == ""
    assert rows["carol.ipynb"]["error"].startswith("otter run failed (exit status 1): ")
    assert "Notebook does not appear to be JSON" in rows["carol.ipynb"]["error"]
    assert (out / "alice" / "results.json").exists() and (out / "carol" / "otter-run.log").exists()
    assert timeout <= elapsed < timeout + 120
    deadline = time.monotonic() + 10  # the kernel stops within a second or two of otter
    while _processes_mentioning(str(out / "bob")) and time.monotonic() < deadline:
        time.sleep(0.5)
    assert not _processes_mentioning(str(out / "bob")), "the submission that never ends is still running"


def _student_install() -> list[str]:
    """The packages of the students' install line in assignments/README.md ("2. Distribute")."""
    readme = (ASSIGNMENTS / "README.md").read_text()
    section = readme[readme.index("## 2. Distribute"):readme.index("## 3. Collect")]
    (line,) = re.findall(r"`pip install ([^`]+)`", section)
    return line.split()


def test_the_students_install_line_runs_the_student_notebook(built, tmp_path):
    """A fresh environment holding what the README tells students to install runs the student version with
    nbclient, as Jupyter would: a kernel is there, every cell runs, and grader.check says what is not set yet."""
    hw = "hw3_slider_crank"
    packages = _student_install()
    assert {"otter-grader", "numpy", "matplotlib"} <= set(packages)
    bin_dir = build.grading_venv(packages, tmp_path / "student-env")
    work = tmp_path / "student"
    shutil.copytree(built[hw][1] / "student", work)
    script = (
        "import nbformat, nbclient\n"
        f"nb = nbformat.read({str(work / (hw + '.ipynb'))!r}, as_version=4)\n"
        "nbclient.NotebookClient(nb, kernel_name='python3', timeout=300,"
        f" resources={{'metadata': {{'path': {str(work)!r}}}}}).execute()\n"
        "print('\\n'.join(str(o.get('text', '')) for c in nb.cells if c.cell_type == 'code' for o in c.outputs))\n"
    )
    ran = subprocess.run([str(bin_dir / "python"), "-c", script], capture_output=True, text=True, cwd=work,
                         env=build.isolated_env(bin_dir, tmp_path / "home"), timeout=600)
    assert ran.returncode == 0, ran.stderr[-3000:]
    assert "`x_piston` is not set yet" in ran.stdout and "q1 results:" in ran.stdout, ran.stdout[-3000:]

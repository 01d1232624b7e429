"""Grading with ``otter run`` the way the autograder image does.

Gradescope and ``otter grade`` build their environment from the autograder zip's
``environment.yml`` alone: otter-grader and the ``requirements`` of the master's
ASSIGNMENT CONFIG.  :func:`grading_venv` makes a virtual environment holding just
that, and :func:`run` grades a submission with it (or with the current environment).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

__all__ = ["zip_requirements", "grading_venv", "isolated_env", "environment", "run", "tool", "GradingError",
           "TIMEOUT"]

TIMEOUT = 600.0
"""Seconds ``otter run`` may take on one submission before it is stopped (a cell that never ends)."""


class GradingError(RuntimeError):
    """``otter run`` could not grade a submission: it failed, wrote no results, or ran out of time.

    The message says which, in a few words fit for a row of ``scores.csv``; ``log`` is the file
    holding what ``otter run`` wrote to stderr.
    """

    def __init__(self, message: str, log: Path | None = None):
        super().__init__(message)
        self.log = log


def tool(name: str) -> str:
    """Path of a console script installed next to this Python (or on PATH)."""
    local = Path(sys.executable).with_name(name)
    return str(local) if local.exists() else name


def zip_requirements(autograder: Path) -> list[str]:
    """What the autograder image installs: the pip packages of the zip's environment.yml.

    Gradescope and ``otter grade`` build a conda environment from this file:
    Python, pip, ``jupyter_server`` and these pip packages (otter-grader and the
    ``requirements`` of the master's ASSIGNMENT CONFIG), nothing else.
    """
    import zipfile

    import yaml

    with zipfile.ZipFile(autograder) as archive:
        environment = yaml.safe_load(archive.read("environment.yml"))
    pip = [d["pip"] for d in environment["dependencies"] if isinstance(d, dict) and "pip" in d]
    conda = [d for d in environment["dependencies"] if isinstance(d, str)]
    from_conda = [d for d in conda if d.split("=")[0] not in ("python", "pip")]
    return [*from_conda, *(pip[0] if pip else [])]


def grading_venv(requirements: list[str], dest: Path) -> Path:
    """A fresh virtual environment holding only ``requirements``; returns its ``bin`` folder.

    This stands in for the autograder image: nothing of numkin or of the
    instructor's environment is visible in it.
    """
    import venv

    venv.EnvBuilder(with_pip=True, clear=True).create(dest)
    bin_dir = dest / ("Scripts" if sys.platform == "win32" else "bin")
    subprocess.run(
        [str(bin_dir / "python"), "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
         *requirements],
        check=True,
        env=isolated_env(bin_dir),
    )
    return bin_dir


def isolated_env(bin_dir: Path | None, home: Path | None = None) -> dict:
    """Environment variables for a process that must see only ``bin_dir``'s Python."""
    import os

    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "VIRTUAL_ENV", "JUPYTER"))}
    if bin_dir is not None:
        env["PATH"] = os.pathsep.join([str(bin_dir), env.get("PATH", "")])
        env["VIRTUAL_ENV"] = str(bin_dir.parent)
        env["PYTHONNOUSERSITE"] = "1"  # no packages from the user's site folder
    if home is not None:  # no user kernelspecs: the kernel is the venv's own Python
        env["JUPYTER_DATA_DIR"] = str(home / "jupyter-data")
        env["JUPYTER_CONFIG_DIR"] = str(home / "jupyter-config")
        env["IPYTHONDIR"] = str(home / "ipython")
    return env


def run(submission: Path, autograder: Path, out: Path, *, bin_dir: Path | None = None,
        timeout: float | None = None) -> dict:
    """``otter run`` one submission; returns its results.json.

    With ``bin_dir`` (see :func:`grading_venv`) the submission is graded with
    that environment's otter and Python only, as the autograder image would.
    With ``timeout`` (seconds) a run that takes longer is stopped, with the
    notebook's kernel.  Raises :class:`GradingError` when the submission could
    not be graded; what ``otter run`` wrote to stderr is in ``out/otter-run.log``.
    """
    submission, autograder, out = submission.resolve(), autograder.resolve(), out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    otter = str(bin_dir / "otter") if bin_dir is not None else tool("otter")
    log = out / "otter-run.log"
    results = out / "results.json"
    results.unlink(missing_ok=True)  # a results.json of an earlier run is not this run's
    with log.open("w") as stderr:
        process = subprocess.Popen(
            [otter, "run", "-a", str(autograder), "-o", str(out), "--no-logo", str(submission)],
            stdout=subprocess.DEVNULL,
            stderr=stderr,
            cwd=out,
            env=isolated_env(bin_dir, out if bin_dir is not None else None),
            start_new_session=True,  # its own process group, stopped as a whole on a timeout
        )
        try:
            code = process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            _stop(process)
            raise GradingError(f"timed out after {timeout:g} s (a cell that never ends?)", log) from None
        except BaseException:  # interrupted: leave no grading running
            _stop(process)
            raise
    if code != 0:
        raise GradingError(f"otter run failed (exit status {code}): {_last_line(log)}", log)
    if not results.exists():
        raise GradingError(f"otter run wrote no results.json: {_last_line(log)}", log)
    return json.loads(results.read_text())


def _stop(process: subprocess.Popen) -> None:
    """Kill ``otter run`` and its process group (the notebook's kernel stops when its parent is gone)."""
    try:
        if sys.platform == "win32":
            process.kill()
        else:
            os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    process.wait()


def _last_line(log: Path) -> str:
    """The last line of ``log`` that says something (an error's last line), or where to look."""
    lines = [line.strip() for line in log.read_text(errors="replace").splitlines() if line.strip()]
    lines = [line for line in lines if "WARNING" not in line and "warn(" not in line]
    return lines[-1][:300] if lines else f"see {log}"


def environment(autograder: Path, venv: Path | None) -> Path | None:
    """The ``bin`` folder of ``venv``, made from the zip's requirements if it does not exist yet."""
    if venv is None:
        return None
    bin_dir = venv / ("Scripts" if sys.platform == "win32" else "bin")
    if not (bin_dir / "otter").exists():
        print(f"building {venv} with {' '.join(zip_requirements(autograder))}")
        grading_venv(zip_requirements(autograder), venv)
    return bin_dir



"""Benchmark: the chained four-bars over 361 input angles, three ways, side by side.

(a) **textbook** -- the homework's way (source document 003): for every angle
    a Newton solve whose sympy residuals and Jacobian are built and
    lambdified inside the call, the angles one after the other, each started
    from the previous solution. It costs tens of milliseconds per angle, so
    only the first ``textbook_points`` angles are timed and the time is scaled
    to all 361 (the work per angle is the same at every angle).
(b) **numkin** -- ``linkages.chained_four_bars().sweep(inputs)``: compiled
    once, continuation on one branch, the grid solved in batches. The
    mechanism is built before the timing; that one-off cost is measured on
    its own, twice (:func:`build_times`): compiled with sympy in a new
    process with an empty kernel cache (row ``numkin build``), and read from
    that kernel cache in this process (the line below the table).
(c) **closed form** -- both four-bars by circle intersection, vectorised with
    numpy over all angles (the reference numkin is checked against).

Each time is the median of ``repeat`` runs (:func:`time.perf_counter`); the
three are measured in turn within every repeat, so that a busy machine slows
them alike. sympy is imported, and the textbook way run once, before the
timing, so that no import is counted (and scaled) in its time. Every
method's angles are compared with numkin's (column ``max |diff| [rad]``):
all three compute the same positions.

Run ``python -m numkin.bench`` (or ``numkin bench``).

Examples
--------
>>> from numkin import bench
>>> df = bench.run(repeat=1, textbook_points=2)
>>> list(df["method"])
['textbook', 'numkin', 'closed form', 'numkin build']
>>> sorted(df.attrs)
['build_from_cache', 'repeat', 'slowdown_vs_closed_form', 'speedup_vs_textbook', 'textbook_points', 'version']
>>> bool(df["max |diff| [rad]"].max() < 1e-10)
True
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from . import linkages
from .errors import InputError

__all__ = ["run", "format_report", "textbook_sweep", "closed_form_sweep", "build_times", "main"]

_HOMEWORK = linkages.spec("chained_four_bars").defaults()
#: The homework's dimensions (in, from the chained four-bars' spec) and starting guesses (deg).
LINKAGE_1 = dict(fixed=_HOMEWORK["fixed1"], inp=_HOMEWORK["input1"], coupler=_HOMEWORK["coupler1"],
                 out=_HOMEWORK["output1"], guess=(45.0, 60.0))
LINKAGE_2 = dict(fixed=_HOMEWORK["fixed2"], inp=_HOMEWORK["input2"], coupler=_HOMEWORK["coupler2"],
                 out=_HOMEWORK["output2"], guess=(30.0, 270.0))
OFFSET_DEG = math.degrees(_HOMEWORK["offset"])


# --------------------------------------------------------------------- (a)
def _textbook_newton(theta_deg, r4_input, r3_coupler, r2_output, r1_fixed, initial_guess, tol=1e-12, max_iter=100):
    """One solve as in the homework: symbols, residuals, Jacobian and lambdify built per call."""
    import sympy as sp

    theta4 = np.deg2rad(180.0 + theta_deg)
    theta2, theta3 = sp.symbols("theta2 theta3")
    f1 = r2_output * sp.cos(theta2) + r3_coupler * sp.cos(theta3) + r4_input * sp.cos(theta4) - r1_fixed
    f2 = r2_output * sp.sin(theta2) + r3_coupler * sp.sin(theta3) + r4_input * sp.sin(theta4)
    F = sp.Matrix([f1, f2])
    J = F.jacobian([theta2, theta3])
    F_func = sp.lambdify((theta2, theta3), F, "numpy")
    J_func = sp.lambdify((theta2, theta3), J, "numpy")
    x = np.deg2rad(np.asarray(initial_guess, dtype=float))
    for _ in range(max_iter):
        F_val = np.array(F_func(x[0], x[1]), dtype=np.float64).flatten()
        J_val = np.array(J_func(x[0], x[1]), dtype=np.float64)
        delta = np.linalg.solve(J_val, -F_val)
        x = x + delta
        if np.linalg.norm(delta) / np.linalg.norm(x) < tol:
            break
    return np.rad2deg(x)


def textbook_sweep(theta_deg) -> np.ndarray:
    """(a) The homework's sequential sweep: returns phi, psi, beta, gamma (rad), shape (4, N).

    Linkage 1 over all angles, each solve started from the previous
    solution; then linkage 2 at alpha = phi + 149 deg the same way. The
    stopping rule is tightened to a relative step of 1e-12 (the homework
    used 1e-4) so that the answer is as accurate as the others'.
    """
    theta_deg = np.asarray(theta_deg, dtype=float)
    out = np.empty((4, theta_deg.size))
    for row, link, angles in ((0, LINKAGE_1, theta_deg), (2, LINKAGE_2, None)):
        if angles is None:
            angles = np.degrees(out[0]) + OFFSET_DEG
        guess = link["guess"]
        for k, angle in enumerate(angles):
            guess = _textbook_newton(angle, link["inp"], link["coupler"], link["out"], link["fixed"], guess)
            out[row : row + 2, k] = np.radians(guess)
    return out


# --------------------------------------------------------------------- (c)
def _circle_intersection(theta, fixed, inp, coupler, out, side):
    """r2 e^{i phi} + r3 e^{i psi} = r1 + r4 e^{i theta}: B = r2 e^{i phi} on two circles."""
    ax = fixed + inp * np.cos(theta)
    ay = inp * np.sin(theta)
    d = np.hypot(ax, ay)
    gamma = np.arccos((out * out + d * d - coupler * coupler) / (2.0 * out * d))
    phi = np.arctan2(ay, ax) + side * gamma
    psi = np.arctan2(ay - out * np.sin(phi), ax - out * np.cos(phi))
    return phi, psi


def closed_form_sweep(theta) -> np.ndarray:
    """(c) phi, psi, beta, gamma (rad) by circle intersection, vectorised; shape (4, N).

    The assembly is the homework's (the branch its starting guesses pick):
    B left of the line from the output pivot to A in linkage 1, right of it
    in linkage 2. Angles are in (-pi, pi] (wrapped, not continued).
    """
    theta = np.asarray(theta, dtype=float)
    l1, l2 = LINKAGE_1, LINKAGE_2
    phi, psi = _circle_intersection(theta, l1["fixed"], l1["inp"], l1["coupler"], l1["out"], 1.0)
    alpha = phi + math.radians(OFFSET_DEG)
    beta, gamma = _circle_intersection(alpha, l2["fixed"], l2["inp"], l2["coupler"], l2["out"], -1.0)
    return np.array([phi, psi, beta, gamma])


# --------------------------------------------------------------- (b)'s build
#: Run in a new process: build the chained four-bars and sweep them once over the input
#: angles given as JSON (rad) in its first argument; print the seconds taken.
_BUILD_SCRIPT = """
import json, sys, time
import numpy as np
from numkin import linkages
theta = np.array(json.loads(sys.argv[1]), dtype=float)
t0 = time.perf_counter()
linkages.chained_four_bars().sweep(theta)
print(time.perf_counter() - t0)
"""


def build_times(theta) -> tuple:
    """The one-off cost of numkin's mechanism, compiled with sympy and read from the kernel cache.

    Parameters
    ----------
    theta : array_like
        Input angles (rad) of the first sweep that is part of the build.

    Returns
    -------
    compiled : float
        Seconds taken by ``chained_four_bars()`` and its first sweep in a new
        Python process whose kernel cache (:mod:`numkin.kernel_cache`) is an
        empty temporary folder: sympy is imported, derives the loop equations
        and they are compiled to numpy.
    cached : float
        Seconds taken by the same build in this process, read from the kernel
        cache the new process has just written (no sympy); NaN if it wrote none.
    mechanism : Mechanism
        The mechanism of that second build. The caller's kernel cache setting
        is left as it was.

    Examples
    --------
    >>> import numpy as np
    >>> compiled, cached, mech = build_times(np.radians([0.0, 1.0]))
    >>> mech.unknowns, compiled > 0, cached > 0
    (('phi', 'psi', 'beta', 'gamma'), True, True)
    """
    import json

    from . import kernel_cache, linkages

    with tempfile.TemporaryDirectory(prefix="numkin-bench-") as folder:
        env = dict(os.environ)
        env[kernel_cache.ENV_VAR] = folder
        source = str(Path(__file__).resolve().parents[1])
        env["PYTHONPATH"] = os.pathsep.join(p for p in (source, env.get("PYTHONPATH")) if p)
        angles = json.dumps(np.asarray(theta, dtype=float).reshape(-1).tolist())
        done = subprocess.run([sys.executable, "-c", _BUILD_SCRIPT, angles], env=env, capture_output=True, text=True)
        if done.returncode != 0:
            raise RuntimeError(f"the build in a new process failed: {done.stderr.strip().splitlines()[-1:]}")
        compiled = float(done.stdout.split()[-1])
        written = any(Path(folder).glob("*.json"))
        before = os.environ.get(kernel_cache.ENV_VAR)
        os.environ[kernel_cache.ENV_VAR] = folder
        try:
            t0 = time.perf_counter()
            mech = linkages.chained_four_bars()
            mech.sweep(theta)
            cached = time.perf_counter() - t0
        finally:
            if before is None:
                del os.environ[kernel_cache.ENV_VAR]
            else:
                os.environ[kernel_cache.ENV_VAR] = before
    return compiled, (cached if written else math.nan), mech


# -------------------------------------------------------------------- timing
def _median_time(fn, repeat, inner):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        times.append((time.perf_counter() - t0) / inner)
    return statistics.median(times)


def _inner(fn, seconds):
    t0 = time.perf_counter()
    fn()
    once = time.perf_counter() - t0
    return max(1, int(seconds / max(once, 1e-9)))


def _wrapped_diff(a, b) -> float:
    return float(np.max(np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b)))))))


def run(repeat: int = 5, *, textbook_points: int = 12, inner_seconds: float = 0.05):
    """Time (a) the textbook way, (b) numkin's sweep and (c) the closed form on 361 angles.

    Parameters
    ----------
    repeat : int
        Repeats; every time reported is the median.
    textbook_points : int
        Angles of the textbook sweep actually timed (its time is scaled to 361).
    inner_seconds : float
        Each repeat of (b) and (c) runs them back to back for about this long
        and takes the mean, so that a timer tick does not dominate.

    Returns
    -------
    pandas.DataFrame
        One row per method: ``method``, ``description``, ``angles timed``,
        ``time [ms]`` (for all 361 angles), ``time / numkin`` and
        ``max |diff| [rad]`` (largest difference from numkin's angles, mod
        2 pi); the last row, ``numkin build``, is the one-off build compiled
        with sympy (:func:`build_times`). ``attrs`` hold
        ``speedup_vs_textbook`` (a / b), ``slowdown_vs_closed_form`` (b / c),
        ``build_from_cache`` (the build read from the kernel cache, s) and
        ``repeat``.
    """
    import pandas as pd

    from . import __version__, linkages

    if isinstance(repeat, bool) or not isinstance(repeat, int) or repeat < 1:
        raise InputError(f"repeat must be a positive integer, got {repeat!r}")
    if isinstance(textbook_points, bool) or not isinstance(textbook_points, int) or not 1 <= textbook_points <= 361:
        raise InputError(f"textbook_points must be an integer from 1 to 361, got {textbook_points!r}")
    theta_deg = np.arange(0.0, 361.0)
    theta = np.radians(theta_deg)

    build, build_from_cache, mech = build_times(theta)
    reference = mech.sweep(theta).values

    def numkin_sweep():
        return mech.sweep(theta)

    def closed():
        return closed_form_sweep(theta)

    def textbook():
        return textbook_sweep(theta_deg[:textbook_points])

    import sympy  # noqa: F401  (imported before the timing: the textbook way's first call must not count it)

    textbook_sweep(theta_deg[:1])
    inner_b, inner_c = _inner(numkin_sweep, inner_seconds), _inner(closed, inner_seconds)
    times = {"textbook": [], "numkin": [], "closed form": []}
    for _ in range(repeat):
        times["textbook"].append(_median_time(textbook, 1, 1) * 361 / textbook_points)
        times["numkin"].append(_median_time(numkin_sweep, 1, inner_b))
        times["closed form"].append(_median_time(closed, 1, inner_c))
    med = {k: statistics.median(v) for k, v in times.items()}

    diff = {
        "textbook": _wrapped_diff(textbook_sweep(theta_deg[:textbook_points]), reference[:, :textbook_points]),
        "numkin": 0.0,
        "closed form": _wrapped_diff(closed_form_sweep(theta), reference),
    }
    rows = [
        ("textbook", "sympy Jacobian built and lambdified in every Newton call, one angle after another",
         textbook_points, med["textbook"]),
        ("numkin", "Mechanism.sweep: compiled once, branch-safe continuation, batched Newton", 361, med["numkin"]),
        ("closed form", "circle intersections, vectorised with numpy", 361, med["closed form"]),
        ("numkin build", "chained_four_bars() and its first sweep in a new process, kernel cache empty: "
         "sympy imported, equations derived and compiled", 361, build),
    ]
    df = pd.DataFrame(
        {
            "method": [r[0] for r in rows],
            "description": [r[1] for r in rows],
            "angles timed": [r[2] for r in rows],
            "time [ms]": [1e3 * r[3] for r in rows],
            "time / numkin": [r[3] / med["numkin"] for r in rows],
            "max |diff| [rad]": [diff.get(r[0], 0.0) for r in rows],
        }
    )
    df.attrs.update(
        {
            "speedup_vs_textbook": med["textbook"] / med["numkin"],
            "slowdown_vs_closed_form": med["numkin"] / med["closed form"],
            "build_from_cache": build_from_cache,
            "repeat": repeat,
            "textbook_points": textbook_points,
            "version": __version__,
        }
    )
    return df


def format_report(df) -> str:
    """A plain-text report of :func:`run`'s table: times and ratios (measurements only)."""
    a = df.attrs
    lines = [
        f"chained four-bars, 361 input angles (median of {a.get('repeat', '?')} repeats; "
        f"textbook timed on {a.get('textbook_points', '?')} angles and scaled to 361)",
        "",
        f"{'method':<14}{'time [ms]':>14}{'time / numkin':>16}{'max |diff| [rad]':>18}  description",
    ]
    for _, row in df.iterrows():
        lines.append(
            f"{row['method']:<14}{row['time [ms]']:>14.4g}{row['time / numkin']:>16.4g}"
            f"{row['max |diff| [rad]']:>18.2e}  {row['description']}"
        )
    speed, slow = a["speedup_vs_textbook"], a["slowdown_vs_closed_form"]
    lines += [
        "",
        f"textbook / numkin:    {speed:,.0f}",
        f"numkin / closed form: {slow:.1f}",
    ]
    if "build_from_cache" in a:
        lines.append(
            f"numkin build read from the kernel cache (chained_four_bars() and its first sweep, no sympy): "
            f"{1e3 * a['build_from_cache']:.4g} ms"
        )
    return "\n".join(lines)


def main(argv=None) -> int:
    """Command line: ``python -m numkin.bench [--repeat N] [--textbook-points K]``."""
    parser = argparse.ArgumentParser(prog="python -m numkin.bench", description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=5, help="repeats; times are medians (default 5)")
    parser.add_argument(
        "--textbook-points", type=int, default=12,
        help="angles of the textbook sweep actually timed, scaled to 361 (default 12)",
    )
    args = parser.parse_args(argv)
    try:
        df = run(args.repeat, textbook_points=args.textbook_points)
    except ValueError as err:
        parser.error(str(err))
    print(format_report(df))
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

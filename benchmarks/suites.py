"""The benchmark's measurements, one function per table.

Each function returns a :class:`Table`: a title, column names, rows and
notes. Times are medians of interleaved rounds (:mod:`benchmarks.timing`);
every ratio is formed from times measured in the same rounds of the same
process. In-process times are CPU seconds of the benchmark process.

Examples
--------
>>> table = sweep_scaling(Settings.quick(), sizes=(36,), linkages=("four-bar",))
>>> table.columns[:3]
['linkage', 'N', 'numkin sweep [ms]']
>>> len(table.rows)
1
"""

from __future__ import annotations

import math
import os
import shutil
import sys
import tempfile
import tracemalloc
from dataclasses import dataclass, field

import numpy as np

from . import chains, others, reference
from .timing import interleaved, interleaved_commands

__all__ = [
    "Settings",
    "Table",
    "FOUR_BAR",
    "GIVEN_DIMENSIONS",
    "OMEGA",
    "startup",
    "cli_workloads",
    "contenders",
    "sweep_scaling",
    "loop_scaling",
    "predictor_linkages",
    "rebuild",
]

#: numkin.linkages.four_bar's docstring example: ground, crank, coupler, rocker (a crank-rocker).
FOUR_BAR = (4.0, 1.0, 3.0, 3.0)
#: Input speed (rad/s) for every omega, alpha computation; input acceleration 0.
OMEGA = 10.0


@dataclass
class Settings:
    """How much to measure: rounds, the time of one sample, and the sizes."""

    repeat: int = 9
    min_time: float = 0.1
    command_repeat: int = 5
    cli_repeat: int = 3
    sizes: tuple = (36, 361, 3601, 36001, 360001)
    kinematics_sizes: tuple = (361, 36001)
    loops: tuple = (1, 2, 4, 8, 16)
    rebuild_loops: tuple = (1, 2, 4, 8, 16)
    rebuild_repeat: int = 3
    textbook_angles: int = 8
    quick: bool = False

    @classmethod
    def quick(cls) -> "Settings":
        """Settings that finish in well under a minute on a loaded two-core machine."""
        return cls(repeat=3, min_time=0.01, command_repeat=1, cli_repeat=1, sizes=(36, 361, 3601),
                   kinematics_sizes=(361,), loops=(1, 2, 4), rebuild_loops=(1, 2, 4), rebuild_repeat=1,
                   textbook_angles=2, quick=True)


@dataclass
class Table:
    title: str
    columns: list
    rows: list = field(default_factory=list)
    notes: list = field(default_factory=list)


def _ms(seconds) -> float:
    return 1e3 * seconds


def _angles(n: int) -> np.ndarray:
    """``n`` input angles spanning one turn, 0 to 360 deg inclusive (rad)."""
    return np.linspace(0.0, 2.0 * math.pi, n)


# ------------------------------------------------------------------ start-up and CLI
def _numkin_command() -> list:
    script = shutil.which("numkin", path=os.path.dirname(sys.executable))
    return [script] if script else [sys.executable, "-m", "numkin"]


def startup(settings: Settings) -> Table:
    """Wall-clock time of ``numkin --help``, ``numkin scenes`` and a repeated ``numkin run homework`` against Python's own floors."""
    nk, py = _numkin_command(), sys.executable
    commands = {
        'python -c "import argparse"': [py, "-c", "import argparse"],
        'python -c "import numpy, pandas"': [py, "-c", "import numpy, pandas"],
        'python -c "import numkin"': [py, "-c", "import numkin"],
        "numkin --help": nk + ["--help"],
        "numkin scenes": nk + ["scenes"],
        "numkin run homework": nk + ["run", "homework"],
    }
    against = {
        'python -c "import numkin"': 'python -c "import argparse"',
        "numkin --help": 'python -c "import argparse"',
        "numkin scenes": 'python -c "import argparse"',
        "numkin run homework": 'python -c "import numpy, pandas"',
    }
    with tempfile.TemporaryDirectory() as tmp:
        times = interleaved_commands(commands, settings.command_repeat, cwd=tmp, bytecode=True)
    table = Table("Start-up (separate processes)",
                  ["command", "wall [s]", "CPU [s]", "wall ratio", "CPU ratio", "against"])
    for name, (wall, cpu) in times.items():
        ref = against.get(name)
        ratios = [f"{wall / times[ref][0]:.2f}", f"{cpu / times[ref][1]:.2f}"] if ref else ["", ""]
        table.rows.append([f"`{name}`", f"{wall:.3f}", f"{cpu:.3f}", *ratios, f"`{ref}`" if ref else ""])
    table.notes.append(f"median of {settings.command_repeat} interleaved rounds after one untimed run of each "
                       "(so `numkin run homework` is a repeated run, with the kernel cache and the bytecode of the "
                       "first run kept, the latter in a temporary folder); CPU is the child's user + system time")
    return table


def cli_workloads(settings: Settings) -> Table:
    """Wall-clock time of ``numkin report homework`` and ``numkin figures --all`` (figures into a temporary folder)."""
    nk, py = _numkin_command(), sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        commands = {
            'python -c "import numpy, pandas"': [py, "-c", "import numpy, pandas"],
            "numkin report homework": nk + ["report", "homework"],
            "numkin figures --all --out DIR": nk + ["figures", "--all", "--out", os.path.join(tmp, "figures")],
        }
        times = interleaved_commands(commands, settings.cli_repeat, cwd=tmp, warmup=False, bytecode=True)
    floor = times['python -c "import numpy, pandas"']
    table = Table("Commands users wait for (separate processes)",
                  ["command", "wall [s]", "CPU [s]", 'wall ratio to `python -c "import numpy, pandas"`', "CPU ratio"])
    for name, (wall, cpu) in times.items():
        table.rows.append([f"`{name}`", f"{wall:.3f}", f"{cpu:.3f}", f"{wall / floor[0]:.1f}", f"{cpu / floor[1]:.1f}"])
    table.notes.append(f"median of {settings.cli_repeat} interleaved rounds (no untimed run first; the bytecode "
                       "compiled in the first round is kept in a temporary folder for the next, as an installed "
                       "package keeps it); CPU is the child's user + system time")
    return table


# ------------------------------------------------------------------ one linkage, every contender
def _numkin_contenders(mech, t, x0):
    from numkin import analytic

    def sweep():
        return mech.sweep(t)

    def sweep_from_start():
        return mech.sweep(t, guess=x0)

    def sweep_rates():
        s = mech.sweep(t)
        dq, d2q = analytic.derivatives(s)
        return s.values, OMEGA * dq, OMEGA**2 * d2q

    def sweep_frame():
        return analytic.kinematics(mech.sweep(t), omega=OMEGA)

    return {
        "numkin sweep": (sweep, "Mechanism.sweep"),
        "numkin sweep, handed the start": (sweep_from_start, "Mechanism.sweep given the solution at the first angle "
                                                               "as its guess, as the hand-written Newton is"),
        "numkin sweep + ω, α (arrays)": (sweep_rates, "sweep, then analytic.derivatives times omega, omega^2"),
        "numkin sweep + kinematics (DataFrame)": (sweep_frame, "sweep, then analytic.kinematics"),
    }


def contenders(settings: Settings, linkage: str, n: int, *, packages: bool = True, textbook: bool = True) -> Table:
    """Every contender on one linkage (``"four-bar"`` or ``"chained homework"``) at ``n`` input angles.

    Ratios are to the closed-form positions, to the closed form with omega and
    alpha, and to the hand-written vectorised Newton, all timed in the same rounds.
    """
    from numkin import linkages

    if linkage == "four-bar":
        chain, mech = reference.four_bar_chain(*FOUR_BAR), linkages.four_bar(*FOUR_BAR)
    else:
        chain, mech = reference.homework_chain(), linkages.chained_four_bars()
    t = _angles(n)
    solved = mech.sweep(t)
    signs = reference.pick_signs(chain, t, solved.values)
    x0 = solved.values[:, 0]
    fns = {
        "closed form": (lambda: reference.closed_form(chain, t, signs), "circle intersections, vectorised"),
        "closed form + ω, α": (lambda: reference.closed_form_rates(chain, t, signs, OMEGA),
                               "plus 2x2 Cramer rules, vectorised"),
        "hand-written vectorised Newton": (lambda: reference.ideal_sweep(chain, t, x0),
                                           "13 scalar nodes, Hermite predictor, Cramer Newton"),
    }
    fns.update(_numkin_contenders(mech, t, x0))
    scale = {}
    if textbook:
        k = min(settings.textbook_angles, n)
        fns["textbook"] = (lambda: reference.textbook_sweep(chain, t[:k], x0),
                           f"sympy Jacobian lambdified in every Newton call; timed on {k} angles, scaled to {n}")
        scale["textbook"] = n / k
    if packages and linkage == "four-bar":
        for found in (others.pylinkage_four_bar(*FOUR_BAR, n, OMEGA), others.mechanism_four_bar(*FOUR_BAR, n, OMEGA)):
            fns.update(found or {})
    elif packages:
        fns.update(others.pylinkage_chained(n, OMEGA) or {})
    times = interleaved({name: fn for name, (fn, _) in fns.items()}, settings.repeat, settings.min_time, scale)
    cf, cfr, ideal = times["closed form"], times["closed form + ω, α"], times["hand-written vectorised Newton"]
    table = Table(f"{linkage}, N = {n} input angles (one process)",
                  ["contender", "time [ms]", "/ closed form", "/ closed form + ω, α", "/ hand-written Newton", "what"])
    for name, t_ in times.items():
        table.rows.append([name, f"{_ms(t_):.4g}", f"{t_ / cf:.3g}", f"{t_ / cfr:.3g}", f"{t_ / ideal:.3g}",
                           fns[name][1]])
    check = [reference.wrapped_max_diff(reference.closed_form(chain, t, signs), solved.values),
             reference.wrapped_max_diff(reference.ideal_sweep(chain, t, x0), solved.values)]
    table.notes.append(f"CPU time, median of {settings.repeat} interleaved rounds; numkin's positions differ from the closed "
                       f"form by at most {check[0]:.1e} rad and from the hand-written Newton by {check[1]:.1e} rad; "
                       f"input speed {OMEGA:g} rad/s")
    if packages:
        missing = [p for p in others.PACKAGES if others.status(p) is None]
        if linkage != "four-bar":
            table.notes.append("on this linkage only pylinkage of the other packages is measured")
        if missing:
            table.notes.append("not installed here, so not measured: " + ", ".join(missing))
    return table


# ------------------------------------------------------------------ scaling with N and with loops
def _memory_per_point(mech, t) -> float:
    """Peak bytes traced by tracemalloc during one sweep, per input angle."""
    tracemalloc.start()
    try:
        mech.sweep(t)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return peak / t.size


def sweep_scaling(settings: Settings, sizes=None, linkages=("four-bar", "chained homework")) -> Table:
    """Sweep alone against the closed form and the hand-written Newton, N from 36 up; memory per point."""
    from numkin import linkages as lk

    table = Table("Sweep alone against N (one process)",
                  ["linkage", "N", "numkin sweep [ms]", "closed form [ms]", "hand-written Newton [ms]",
                   "numkin / closed form", "numkin / hand-written", "peak traced memory [B / point]"])
    for name in linkages:
        if name == "four-bar":
            chain, mech = reference.four_bar_chain(*FOUR_BAR), lk.four_bar(*FOUR_BAR)
        else:
            chain, mech = reference.homework_chain(), lk.chained_four_bars()
        for n in sizes or settings.sizes:
            t = _angles(n)
            solved = mech.sweep(t)
            signs = reference.pick_signs(chain, t, solved.values)
            x0 = solved.values[:, 0]
            times = interleaved({
                "numkin": lambda: mech.sweep(t),
                "closed": lambda: reference.closed_form(chain, t, signs),
                "ideal": lambda: reference.ideal_sweep(chain, t, x0),
            }, settings.repeat, settings.min_time)
            table.rows.append([name, n, f"{_ms(times['numkin']):.4g}", f"{_ms(times['closed']):.4g}",
                               f"{_ms(times['ideal']):.4g}", f"{times['numkin'] / times['closed']:.3g}",
                               f"{times['numkin'] / times['ideal']:.3g}", f"{_memory_per_point(mech, t):.0f}"])
    table.notes.append(f"CPU time, median of {settings.repeat} interleaved rounds; memory is tracemalloc's peak during one "
                       "sweep divided by N (numpy's arrays are traced)")
    return table


#: The dimensions the benchmark gives a ready-made linkage whose spec has no default for them, in the spec's order
#: (every other dimension is the spec's default): linkage name -> values.
GIVEN_DIMENSIONS = {"four_bar": FOUR_BAR, "slider_crank": (80.0, 200.0)}


def predictor_linkages() -> dict:
    """The linkages of the predictor table: every ready-made linkage of ``numkin.linkages.SPECS``, in its order.

    Each built with its spec's defaults, and :data:`GIVEN_DIMENSIONS` for the dimensions that have none;
    named by its registry name, those given values after it (``"four-bar 4:1:3:3"``).

    Returns
    -------
    dict
        Row name -> a function of no arguments that builds the linkage.

    Raises
    ------
    ValueError
        For a linkage with a dimension that has no default and no value in :data:`GIVEN_DIMENSIONS`.

    Examples
    --------
    >>> list(predictor_linkages())[:2]
    ['four-bar 4:1:3:3', 'slider-crank 80:200']
    """
    import functools

    from numkin import linkages

    out = {}
    for spec in linkages.SPECS.values():
        required = [d.name for d in spec.dimensions if d.required]
        given = tuple(GIVEN_DIMENSIONS.get(spec.name, ()))
        if len(given) != len(required):
            raise ValueError(f"the predictor table needs {spec.name}'s {', '.join(required)} (no defaults): give "
                             f"them in GIVEN_DIMENSIONS, got {given}")
        name = spec.name.replace("_", "-") + (" " + ":".join(f"{v:g}" for v in given) if given else "")
        out[name] = functools.partial(spec.build, **spec.defaults(), **dict(zip(required, given)))
    return out


def predictors(settings: Settings, sizes=None) -> Table:
    """The batch's predictor round a whole turn (``numkin.turn_predictor``) switched off and on in one process.

    ``numkin.batch_fill.TURN`` is set before every call of each contender, so the two are the same sweep
    with and without the fit; ``nfev`` counts the residual evaluations of one sweep of each.
    """
    from numkin import batch_fill

    table = Table("The batch's predictor round a whole turn, off and on (one process)",
                  ["linkage", "N", "off [ms]", "on [ms]", "on / off", "nfev off → on"])
    was = batch_fill.TURN
    try:
        for name, build in predictor_linkages().items():
            mech = build()
            for n in sizes or settings.sizes:
                t = _angles(n)

                def sweep(flag, t=t, mech=mech):
                    batch_fill.TURN = flag
                    return mech.sweep(t)

                times = interleaved({"off": lambda: sweep(False), "on": lambda: sweep(True)},
                                    settings.repeat, settings.min_time)
                table.rows.append([name, n, f"{_ms(times['off']):.4g}", f"{_ms(times['on']):.4g}",
                                   f"{times['on'] / times['off']:.3f}", f"{sweep(False).nfev} → {sweep(True).nfev}"])
    finally:
        batch_fill.TURN = was
    table.notes.append(f"CPU time, median of {settings.repeat} interleaved rounds; inputs np.linspace(0, 2 pi, N)")
    return table


def loop_scaling(settings: Settings, n: int = 361) -> Table:
    """Chains of K four-bars: sweep and sweep + ω, α against the closed form, K from 1 up."""
    from numkin import analytic

    table = Table(f"Chains of K four-bars, N = {n} (one process)",
                  ["K loops", "numkin sweep [ms]", "sweep / closed form", "sweep + ω, α [ms]",
                   "(sweep + ω, α) / (closed form + ω, α)", "ω, α share of sweep + ω, α"])
    t = _angles(n)
    for k in settings.loops:
        chain = reference.repeated_chain(k)
        mech = chains.build(chain)
        signs = [1.0] * k

        def omega_alpha(s):
            dq, d2q = analytic.derivatives(s)
            return OMEGA * dq, OMEGA**2 * d2q

        solved = mech.sweep(t)
        times = interleaved({
            "sweep": lambda mech=mech: mech.sweep(t),
            "rates": lambda mech=mech: omega_alpha(mech.sweep(t)),
            "rates alone": lambda solved=solved: omega_alpha(solved),
            "closed": lambda chain=chain: reference.closed_form(chain, t, signs),
            "closed rates": lambda chain=chain: reference.closed_form_rates(chain, t, signs, OMEGA),
        }, settings.repeat, settings.min_time)
        # timed on its own (a difference of two medians can come out negative)
        share = times["rates alone"] / (times["sweep"] + times["rates alone"])
        table.rows.append([k, f"{_ms(times['sweep']):.4g}", f"{times['sweep'] / times['closed']:.3g}",
                           f"{_ms(times['rates']):.4g}", f"{times['rates'] / times['closed rates']:.3g}",
                           f"{100 * share:.0f} %"])
    table.notes.append(f"CPU time, median of {settings.repeat} interleaved rounds; each loop a copy of the homework's "
                       "first four-bar, driven by the previous loop's output plus 149°; built with numkin.Loop and "
                       "numkin.Mechanism; the ω, α share is the time of ω, α on a solved sweep over that plus the "
                       "sweep's")
    return table


def rebuild(settings: Settings, n: int = 36) -> Table:
    """Time to build a same-shape chain of K four-bars and get its first ω, α, against K."""
    from numkin import analytic

    counter = iter(range(1, 10**6))

    def make(k):
        def go():
            chain = reference.repeated_chain(k)
            mech = chains.build(chain, scale=1.0 + 1e-3 * next(counter))
            s = mech.sweep(_angles(n))
            analytic.derivatives(s)
        return go

    build_only = {k: (lambda k=k: chains.build(reference.repeated_chain(k), scale=1.0 + 1e-3 * next(counter)))
                  for k in settings.rebuild_loops}
    full = {k: make(k) for k in settings.rebuild_loops}
    fns = {("build", k): f for k, f in build_only.items()} | {("full", k): f for k, f in full.items()}
    times = interleaved(fns, settings.rebuild_repeat, min_time=0.0)
    code = ("import numpy as np; from benchmarks import chains, reference; from numkin import analytic; "
            "analytic.derivatives(chains.build(reference.repeated_chain({k})).sweep(np.linspace(0, 2 * np.pi, {n})))")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    fresh = interleaved_commands({k: [sys.executable, "-c", code.format(k=k, n=n)] for k in settings.rebuild_loops},
                                 settings.rebuild_repeat, cwd=root)
    table = Table("Rebuild of a same-shape chain of K four-bars",
                  ["K loops", "Mechanism(...) [ms]", f"build + sweep of {n} + first ω, α [ms]", "ratio to K = 1",
                   "the same in a new process, with imports [s CPU]"])
    base = times[("full", settings.rebuild_loops[0])]
    for k in settings.rebuild_loops:
        table.rows.append([k, f"{_ms(times[('build', k)]):.4g}", f"{_ms(times[('full', k)]):.4g}",
                           f"{times[('full', k)] / base:.3g}", f"{fresh[k][1]:.3f}"])
    ks = np.array(settings.rebuild_loops, dtype=float)
    if ks.size > 1:
        slope = np.polyfit(np.log(ks), np.log([times[("full", int(k))] for k in ks]), 1)[0]
        table.notes.append(f"log-log slope of build + sweep + first ω, α against K: {slope:.2f}")
    table.notes.append(f"CPU time, median of {settings.rebuild_repeat} interleaved rounds; in process, after a first "
                       "build of each K, every build has new lengths (same expressions, new values); the new-process "
                       "column is the child's user + system time of a repeated run (one untimed run first)")
    return table

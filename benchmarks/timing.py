"""Interleaved timing: every contender runs once per round, rounds repeat, medians are kept.

Running A, B, A, B, ... rather than all of A then all of B makes a machine
whose load changes during the measurement slow every contender alike, so
their ratio stays meaningful even when the absolute times do not.

In-process times are CPU seconds of this process (:func:`time.process_time`)
by default: on a machine shared with other busy processes, time spent
waiting for a core is not counted. Commands in separate processes are timed
by the wall clock and by the CPU time the child used (user + system, from
:func:`os.wait4`).

Examples
--------
>>> times = interleaved({"sum": lambda: sum(range(100)), "len": lambda: len("abc")}, repeat=3, min_time=0.001)
>>> sorted(times)
['len', 'sum']
>>> all(t > 0 for t in times.values())
True
"""

from __future__ import annotations

import os
import statistics
import subprocess
import time

__all__ = ["interleaved", "interleaved_commands", "calibrate", "run_command"]


def calibrate(fn, min_time: float, clock=time.process_time) -> int:
    """How many back-to-back calls of ``fn`` take at least ``min_time`` seconds (at least 1)."""
    t0 = clock()
    fn()
    once = clock() - t0
    return max(1, int(min_time / max(once, 1e-9)) + 1) if once < min_time else 1


def interleaved(fns: dict, repeat: int, min_time: float = 0.02, scale: dict | None = None,
                clock=time.process_time) -> dict:
    """Median seconds per call of every function in ``fns``, timed in interleaved rounds.

    Each function is first called once (warm-up and calibration); in each of
    ``repeat`` rounds every function then runs ``n`` times back to back
    (``n`` chosen so that this takes about ``min_time``) and the mean is one
    sample. ``scale`` multiplies a function's time (for a contender timed on
    part of the work and scaled to all of it). ``clock`` is
    :func:`time.process_time` (CPU time) unless given, e.g.
    :func:`time.perf_counter` for the wall clock.
    """
    inner = {name: calibrate(fn, min_time, clock) for name, fn in fns.items()}
    samples = {name: [] for name in fns}
    for _ in range(repeat):
        for name, fn in fns.items():
            n = inner[name]
            t0 = clock()
            for _ in range(n):
                fn()
            samples[name].append((clock() - t0) / n)
    scale = scale or {}
    return {name: statistics.median(v) * scale.get(name, 1.0) for name, v in samples.items()}


def run_command(args, cwd=None, env=None) -> tuple:
    """Run ``args`` (no shell) to the end: (wall seconds, CPU seconds of the child: user + system).

    Raises :class:`RuntimeError` with the last line of error output if the
    command exits non-zero.
    """
    t0 = time.perf_counter()
    proc = subprocess.Popen(args, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    proc.stderr.close()
    if proc.returncode != 0:
        last = (err.strip().splitlines() or ["(no error output)"])[-1]
        raise RuntimeError(f"{' '.join(map(str, args))} exited {proc.returncode}: {last}")
    return wall, usage.ru_utime + usage.ru_stime


def interleaved_commands(commands: dict, repeat: int, cwd=None, warmup: bool = True, bytecode: bool = False) -> dict:
    """Median (wall, CPU) seconds of commands (lists of arguments, no shell), run in interleaved rounds.

    With ``warmup`` every command runs once untimed first (so that a second,
    "repeated" run is what is measured, with the operating system's file
    cache warm). With ``bytecode`` (and ``cwd`` given) the children keep the
    bytecode they compile in ``cwd/pycache`` (``PYTHONPYCACHEPREFIX``), even
    where ``PYTHONDONTWRITEBYTECODE`` is set: a repeated run then reads it, as
    every run of an installed package does.
    """
    env = dict(os.environ)
    env.setdefault("PYTHONHASHSEED", "0")
    if bytecode and cwd is not None:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = os.path.join(cwd, "pycache")
    if warmup:
        for args in commands.values():
            run_command(args, cwd, env)
    samples = {name: [] for name in commands}
    for _ in range(repeat):
        for name, args in commands.items():
            samples[name].append(run_command(args, cwd, env))
    return {name: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v))
            for name, v in samples.items()}

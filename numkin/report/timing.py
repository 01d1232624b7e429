"""Run times of the error tables: opt-in repeats and their median.

Every table is exact and the same in every run by default (no timing);
``repeat`` asks for run times, which vary between runs and machines.

Examples
--------
>>> timing_repeats(None), timing_repeats(3)
(0, 3)
>>> median_time(lambda: sum(range(100)), 3) > 0
True
"""

from __future__ import annotations

import statistics
import time
from typing import Callable

from ..errors import InputError

__all__ = ["timing_repeats", "median_time"]


def timing_repeats(repeat) -> int:
    """Timing repeats asked for: None or 0 means no timing (the default of every table); else an integer >= 1."""
    if repeat is None:
        return 0
    if isinstance(repeat, bool) or int(repeat) != repeat or repeat < 0:
        raise InputError(f"repeat must be None (no timing) or a non-negative integer, got {repeat!r}")
    return int(repeat)


def median_time(fn: Callable[[], object], repeat: int, warmup: bool = True) -> float:
    """Median wall time of ``fn()`` in seconds over `repeat` repeats.

    With `warmup`, one untimed call comes first, and calls shorter than
    2 ms are looped inside each repeat so that every timed block lasts at
    least ~2 ms.
    """
    number = 1
    if warmup:
        t0 = time.perf_counter()
        fn()
        first = time.perf_counter() - t0
        number = 1 if first >= 2e-3 else min(1000, max(1, int(2e-3 / max(first, 1e-7))))
    samples = []
    for _ in range(max(1, int(repeat))):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        samples.append((time.perf_counter() - t0) / number)
    return statistics.median(samples)

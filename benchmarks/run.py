"""Run numkin's benchmarks and print the measurements as Markdown tables.

Usage, from the repository root::

    python -m benchmarks [--quick] [--output FILE] [--only NAME ...]
    python benchmarks/run.py [--quick] [--output FILE] [--only NAME ...]

``--quick`` measures fewer sizes with fewer repeats (well under a minute);
the default measures everything (several minutes). Times are medians of
interleaved rounds; ratios come from times measured in the same rounds.

Examples
--------
>>> text = main(["--quick", "--only", "sweep", "--sizes", "36"], echo=False)
>>> text.splitlines()[0]
'# numkin benchmarks'
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import sys
import time

if __package__ in (None, ""):  # run as a script: python benchmarks/run.py
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    __package__ = "benchmarks"

from benchmarks import others, suites  # noqa: E402

__all__ = ["main", "to_markdown", "machine", "GROUPS"]

#: Table groups in the order they run.
GROUPS = ("startup", "cli", "four-bar", "chained", "sweep", "predictors", "loops", "rebuild")


def machine() -> list:
    """Lines describing where the measurements were taken."""
    import numpy

    import numkin

    try:
        load = "load average %.2f %.2f %.2f" % os.getloadavg()
    except OSError:
        load = "load average unknown"
    versions = ", ".join(f"{p} {others.status(p) or 'not installed'}" for p in ("numba",) + others.PACKAGES)
    return [
        f"- date (UTC): {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M}",
        f"- machine: {platform.machine()}, {os.cpu_count()} logical CPUs, {platform.system()} {platform.release()}; {load} at start",
        f"- Python {platform.python_version()}, numpy {numpy.__version__}, numkin {numkin.__version__}",
        f"- others: {versions}",
    ]


def to_markdown(table) -> str:
    lines = [f"## {table.title}", "", "| " + " | ".join(table.columns) + " |",
             "|" + "|".join("---" for _ in table.columns) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in table.rows]
    if table.notes:
        lines.append("")
        lines += [f"{note[0].upper()}{note[1:]}." for note in table.notes]
    return "\n".join(lines)


def _tables(group, settings, sizes):
    if group == "startup":
        yield suites.startup(settings)
    elif group == "cli":
        yield suites.cli_workloads(settings)
    elif group == "four-bar":
        yield suites.contenders(settings, "four-bar", 361)
    elif group == "chained":
        for n in settings.kinematics_sizes:
            yield suites.contenders(settings, "chained homework", n, textbook=n <= 3601)
    elif group == "sweep":
        yield suites.sweep_scaling(settings, sizes=sizes)
    elif group == "predictors":
        yield suites.predictors(settings, sizes=sizes)
    elif group == "loops":
        yield suites.loop_scaling(settings)
    elif group == "rebuild":
        yield suites.rebuild(settings)


def main(argv=None, echo: bool = True) -> str:
    """Command line; returns the Markdown text (also printed, and written to ``--output``)."""
    parser = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer sizes and repeats (under a minute)")
    parser.add_argument("--output", metavar="FILE", help="also write the Markdown tables to FILE")
    parser.add_argument("--only", nargs="+", choices=GROUPS, metavar="NAME",
                        help=f"run only these groups: {', '.join(GROUPS)}")
    parser.add_argument("--sizes", nargs="+", type=int, metavar="N",
                        help="input-angle counts of the sweep-against-N table")
    args = parser.parse_args(argv)
    settings = suites.Settings.quick() if args.quick else suites.Settings()
    t0 = time.perf_counter()
    parts = ["# numkin benchmarks", "", *machine(), f"- mode: {'--quick' if args.quick else 'full'}", ""]
    if echo:
        print("\n".join(parts), flush=True)
    groups = args.only or [g for g in GROUPS if not (args.quick and g == "cli")]
    if args.quick and not args.only:
        parts.append("`--quick` leaves out `numkin report homework` and `numkin figures --all` "
                     "(`--only cli` runs them).\n")
    for group in groups:
        for table in _tables(group, settings, args.sizes):
            text = to_markdown(table) + "\n"
            parts.append(text)
            if echo:
                print(text, flush=True)
    tail = f"Total benchmark time: {time.perf_counter() - t0:.0f} s."
    parts.append(tail)
    if echo:
        print(tail)
    text = "\n".join(parts) + "\n"
    if args.output:
        with open(args.output, "w", encoding="utf-8") as fh:
            fh.write(text)
    return text


if __name__ == "__main__":
    main()

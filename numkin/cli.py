"""The ``numkin`` command: run scenes, write their tables, figures and animations.

::

    numkin scenes                                   list the built-in scenes
    numkin run SCENE [--out DIR] [--at ANGLE_DEG] [--format text|json]
    numkin report SCENE [--out DIR] [--repeat N]    error-analysis tables
    numkin figures [SCENE ... | --all] --out DIR    regenerate figures
    numkin animate SCENE --out FILE.gif [--frames N] [--fps F] [--dpi D] [--width IN]
                   [--turn full|sweep] [--trace P ...] [--arrows velocity|acceleration]
    numkin bench [--repeat N]                       speed comparison

SCENE is a built-in name (``numkin scenes``) or the path of a scene file
(see :mod:`numkin.scene` for the format). A mistake in a scene or in the
arguments is reported on one line of stderr with exit status 2; a check point
that disagrees with its expected value gives exit status 1; an error numkin
does not check for (a ``ValueError`` that is not a
:class:`~numkin.NumkinError`) is one line with exit status 3, its traceback
shown with the environment variable ``NUMKIN_TRACEBACK=1``.

Examples
--------
The command prints; ``main`` returns the exit status:

>>> import contextlib, io, json
>>> from numkin.cli import main
>>> printed = io.StringIO()
>>> with contextlib.redirect_stdout(printed):
...     status = main(["run", "quick-return", "--at", "30", "--format", "json"])
>>> result = json.loads(printed.getvalue())
>>> status, result["passed"], round(result["checks"][0]["values"]["r3"], 3)
(0, True, 87.178)
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import warnings
from contextlib import contextmanager
from pathlib import Path

from .cli_text import fmt_value, format_result
from .errors import InputError, NumkinError

__all__ = ["main", "build_parser", "format_result"]

PROG = "numkin"


# ----------------------------------------------------------------------- progress
@contextmanager
def _progress(desc: str, total: int | None = None):
    """A tqdm bar on stderr, shown only on a terminal and only after a second of work.

    Yields ``step(label, advance=True)``: advance by one (not before the first
    step) and show ``label``.
    """
    if not sys.stderr.isatty():  # no bar to show: tqdm is not even imported
        yield lambda label="", advance=True: None
        return
    from tqdm import tqdm

    bar = tqdm(
        total=total, desc=desc, file=sys.stderr, disable=not sys.stderr.isatty(), delay=1.0,
        leave=False, dynamic_ncols=True, unit="step",
    )
    started = [False]

    def step(label: str = "", advance: bool = True) -> None:
        if advance and started[0]:
            bar.update(1)
        started[0] = started[0] or advance
        if label:
            bar.set_postfix_str(label, refresh=False)

    try:
        yield step
    finally:
        bar.close()


@contextmanager
def _about(scene):
    """Errors of the solver (and numerical failures) raised inside carry the scene's file name.

    A :class:`~numkin.scene.SceneError` already names its file; any other
    :class:`~numkin.NumkinError`, ``ValueError`` or ``ArithmeticError`` gets the
    attribute ``scene_source``, which :func:`main` prints before the message.
    """
    lines = warnings.showwarning
    if isinstance(lines, _WarningLines):
        lines.shown.clear()  # each scene's warnings said once for it, though another scene said the same
    try:
        yield
    except (NumkinError, ValueError, ArithmeticError) as error:
        from .scene import SceneError

        if not isinstance(error, SceneError) and getattr(error, "scene_source", None) is None:
            try:
                error.scene_source = scene.source
            except AttributeError:  # pragma: no cover - exceptions without a __dict__
                pass
        raise


# ----------------------------------------------------------------------- commands
def _cmd_scenes(args) -> int:
    from .schema import list_scenes

    scenes = list_scenes()
    width = max(map(len, scenes), default=0)
    for name, description in scenes.items():
        print(f"{name:<{width}}  {description}")
    return 0


def _out_checked(out) -> None:
    """``--out`` refused before any work when it is a file or lies under one (:func:`numkin.folders.output_folder`)."""
    if out is not None:
        from .folders import output_folder

        output_folder(out, "--out")


def _cmd_run(args) -> int:
    from .scene import load_scene, run_scene

    scene = load_scene(args.scene)
    _out_checked(args.out)
    with _progress(scene.name) as step, _about(scene):
        result = run_scene(scene, out=args.out, at=args.at, progress=step)
    if args.format == "json":
        print(json.dumps(result.to_dict(), indent=2, allow_nan=False))
    else:
        print(format_result(result))
    if args.out and not result.written:
        print(f"{PROG}: note: scene '{scene.name}' asks for no tables or figures; nothing written to {args.out}", file=sys.stderr)
    if result.scene.kind == "stability" and "as expected" in result.suite:
        bad = [str(c) for c, ok in zip(result.suite["case"], result.suite["as expected"]) if not ok]
        if bad:
            print(f"{PROG}: not as expected: " + "; ".join(bad), file=sys.stderr)
            return 1
    failed = [
        f"{key} = {fmt_value(c.values[key], c.expected[key], mismatch=True, written=c.written.get(key))} at "
        f"{c.at_deg:g}° (expected {fmt_value(c.expected[key], c.expected[key], written=c.written.get(key))})"
        for c in result.checks for key, ok in c.ok.items() if not ok
    ]
    if failed:
        print(f"{PROG}: check failed: " + "; ".join(failed), file=sys.stderr)
        return 1
    return 0


def _cmd_report(args) -> int:
    from .report import format_text, scene_report
    from .scene import load_scene

    scene = load_scene(args.scene)
    _out_checked(args.out)
    with _progress(f"{scene.name} report") as step, _about(scene):
        step("tables")
        tables = scene_report(scene, repeat=args.repeat)
    written = []
    if args.out:
        from .report import write_tables

        named = {f"{scene.name}-{k}": v for k, v in tables.items()}
        written = list(write_tables(named, Path(args.out)))
    for name, table in tables.items():
        print(f"## {name}\n{format_text(table)}\n")
    for path in written:
        print(f"written: {path}")
    return 0


def _scenes_for_figures(args) -> list[str]:
    from .schema import list_scenes

    if args.all and args.scenes:
        raise InputError("give scene names or --all, not both")
    if args.all:
        return list(list_scenes())
    if not args.scenes:
        raise InputError("name at least one scene, or give --all")
    return list(args.scenes)


def _cmd_figures(args) -> int:
    from .scene import load_scene, render_figures, run_scene

    names = _scenes_for_figures(args)
    scenes = [load_scene(n) for n in names]  # every file checked before any work
    _out_checked(args.out)
    out = Path(args.out)
    written = []
    with _progress("figures", total=len(scenes)) as step:
        for scene in scenes:
            step(scene.name)
            if not scene.figures:
                if not args.all:
                    print(f"{PROG}: scene '{scene.name}' asks for no figures", file=sys.stderr)
                continue
            with _about(scene):
                result = run_scene(scene, figures=False)
                written += render_figures(result, out / scene.name, formats=tuple(args.formats),
                                          progress=lambda label: step(f"{scene.name}: {label}", advance=False))
        step()
    for path in written:
        print(path)
    return 0


def _animation_options(args, scene) -> dict:
    """Keyword arguments of :func:`numkin.animate.animate`: the command's options, else the scene's ``[animation]``."""
    defaults = scene.animation
    options = {"frames": args.frames or defaults.get("frames", 72)}
    for key, value in (("fps", args.fps), ("dpi", args.dpi), ("width", args.width), ("turn", args.turn),
                       ("traces", args.trace), ("arrows", args.arrows)):
        value = defaults.get(key) if value is None else value
        if value is not None:
            options[key] = list(value) if key == "traces" else value
    if options.get("arrows"):
        if not scene.speed:
            raise InputError(f"--arrows {options['arrows']}: scene '{scene.name}' has no [input] speed")
        options["omega"] = scene.speed
        if scene.acceleration:
            options["alpha"] = scene.acceleration
    return options


def _cmd_animate(args) -> int:
    from .scene import load_scene, run_scene

    scene = load_scene(args.scene)
    if scene.kind != "mechanism":
        raise InputError(f"scene '{scene.name}' has no mechanism to animate")
    path = Path(args.out)
    if path.suffix.lower() != ".gif":
        raise InputError(f"--out {args.out!r}: the animation is written as a GIF (Pillow); give a .gif file")
    if path.is_dir():
        raise InputError(f"--out: '{path}' is a folder; give the path of a .gif file")
    _out_checked(path.parent)
    options = _animation_options(args, scene)  # the input speed read before positions_only()
    scene = scene.positions_only()
    with _progress(f"{scene.name} animation") as step, _about(scene):
        result = run_scene(scene, progress=step)
        step("frames")
        from . import animate

        written = animate.animate(result.sweep, path, **options)
    print(written if written is not None else path)
    return 0


def _cmd_bench(args) -> int:
    from . import bench

    kwargs = {} if args.repeat is None else {"repeat": args.repeat}
    if args.textbook_points is not None:
        kwargs["textbook_points"] = args.textbook_points
    with _progress("bench") as step:
        step("timing")
        table = bench.run(**kwargs)
    print(bench.format_report(table))
    return 0


# ----------------------------------------------------------------------- parser
class _Formatter(argparse.RawDescriptionHelpFormatter):
    pass


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def _bounded(kind, low, high, *, low_open: bool = False):
    """An argparse type: a number of `kind` (int or float) in [low, high] ((low, high] if `low_open`)."""
    noun = "an integer" if kind is int else "a number"

    def parse(text: str):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {noun}") from None
        if not math.isfinite(value) or value < low or value > high or (low_open and value == low):
            span = f"({low:g}, {high:g}]" if low_open else f"from {low:g} to {high:g}"
            raise argparse.ArgumentTypeError(f"must be {span}, got {text}")
        return value

    parse.__name__ = kind.__name__
    return parse


def _finite_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number (degrees)") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose usage errors are one line (and exit status 2)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _add_command(sub, name: str, func, *, help: str, description: str, epilog: str) -> argparse.ArgumentParser:
    """The parser of subcommand `name`, run by `func`."""
    p = sub.add_parser(name, help=help, formatter_class=_Formatter, description=description, epilog=epilog)
    p.set_defaults(func=func)
    return p


def _add_scene_argument(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", metavar="SCENE", help="built-in scene name or path of a .toml file")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``numkin`` command."""
    parser = _Parser(
        prog=PROG,
        formatter_class=_Formatter,
        description=(
            "Numerical kinematics of planar linkages: solve a scene (a problem declared in a TOML\n"
            "file), compare finite-difference velocities and accelerations with the exact ones,\n"
            "and write the tables, figures and animations it asks for."
        ),
        epilog=(
            "examples:\n"
            "  numkin scenes\n"
            "  numkin run homework                 # omega_beta and alpha_beta at theta = 100°\n"
            "  numkin run homework --at 100 --format json\n"
            "  numkin run my-linkage.toml --out results/\n"
            "  numkin figures --all --out figures/\n"
            "\nSCENE is a built-in name (numkin scenes) or the path of a .toml scene file."
        ),
    )
    from . import __version__

    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    _add_command(
        sub, "scenes", _cmd_scenes, help="list the built-in scenes",
        description="List the built-in scenes with a one-line description each.",
        epilog="example:\n  numkin scenes",
    )

    p = _add_command(
        sub, "run", _cmd_run, help="solve a scene and print its check points and errors",
        description=(
            "Solve a scene: the positions over the input sweep, and the velocities and accelerations\n"
            "(exact and by the scene's finite-difference schemes) if it asks for them. Prints the\n"
            "check points and the largest error of each scheme; with --out, writes the tables and\n"
            "figures the scene asks for. Exit status 1 if a check point disagrees."
        ),
        epilog=(
            "examples:\n"
            "  numkin run homework\n"
            "  numkin run homework --at 100                # every quantity at theta = 100°\n"
            "  numkin run slider-crank --out results/     # tables (and figures) into results/\n"
            "  numkin run homework --format json | python -m json.tool"
        ),
    )
    _add_scene_argument(p)
    p.add_argument("--out", metavar="DIR", help="write the scene's tables and figures into DIR")
    p.add_argument("--at", metavar="ANGLE_DEG", type=_finite_float, help="print every quantity at this input angle (degrees)")
    p.add_argument("--format", choices=("text", "json"), default="text", help="output format (default text)")

    p = _add_command(
        sub, "report", _cmd_report, help="write the error-analysis tables of a scene",
        description=(
            "Error-analysis tables of a scene: convergence with the step, error against run time,\n"
            "the roundoff floor, Newton's iterations and Jacobians, the solver tolerance; for the\n"
            "stability scene, its suite. Prints them (wide tables in parts); with --out also writes\n"
            "them as Markdown, CSV and LaTeX. Not timed unless --repeat is given (timings vary\n"
            "between runs; everything else is the same on every run)."
        ),
        epilog="examples:\n  numkin report homework --out report/\n  numkin report homework --repeat 5\n  numkin report stability",
    )
    _add_scene_argument(p)
    p.add_argument("--out", metavar="DIR", help="write the tables into DIR")
    p.add_argument("--repeat", metavar="N", type=_positive_int,
                   help="time the work-precision and Jacobian tables with N repeats (default: not timed)")

    p = _add_command(
        sub, "figures", _cmd_figures, help="regenerate the figures of scenes",
        description=(
            "Regenerate the figures the scenes ask for, into DIR/<scene>/ (PNG and SVG, the same\n"
            "bytes on every run)."
        ),
        epilog="examples:\n  numkin figures homework --out figures/\n  numkin figures --all --out figures/",
    )
    p.add_argument("scenes", metavar="SCENE", nargs="*", help="built-in scene names or .toml paths")
    p.add_argument("--all", action="store_true", help="every built-in scene")
    p.add_argument("--out", metavar="DIR", required=True, help="folder for the figures")
    p.add_argument("--formats", metavar="FMT", nargs="+", default=["png", "svg"], choices=("png", "svg", "pdf"),
                   help="file formats (default png svg)")

    p = _add_command(
        sub, "animate", _cmd_animate, help="animate the mechanism of a scene as a GIF",
        description=(
            "Animate a scene's mechanism over its input sweep: links, joints and ground pivots, the\n"
            "input angle stamped on each frame. Written as a GIF with Pillow (no ffmpeg needed)."
        ),
        epilog=(
            "examples:\n  numkin animate quick-return --out quick-return.gif --frames 90\n"
            "  numkin animate six-bar --out six-bar.gif --trace B --arrows velocity --dpi 100\n"
            "\nDefaults of the options come from the scene's [animation] section when it gives them."
        ),
    )
    _add_scene_argument(p)
    p.add_argument("--out", metavar="FILE.gif", required=True, help="the GIF to write")
    p.add_argument("--frames", metavar="N", type=_positive_int, help="frame count (default: the scene's, else 72)")
    p.add_argument("--fps", metavar="F", type=_bounded(float, 0.0, 100.0, low_open=True),
                   help="frames per second (default: the scene's, else 24)")
    p.add_argument("--dpi", metavar="D", type=_bounded(int, 10, 600),
                   help="dots per inch, 10 to 600 (default: the scene's, else 80)")
    p.add_argument("--width", metavar="INCHES", type=_bounded(float, 1.0, 40.0),
                   help="frame width in inches, 1 to 40; the GIF is width * dpi pixels wide (default 5.6)")
    p.add_argument("--turn", choices=("full", "sweep"),
                   help="full: one full turn when the input can turn fully (default); sweep: the scene's sweep")
    p.add_argument("--trace", metavar="P", nargs="+", help="named points whose paths are drawn")
    p.add_argument("--arrows", choices=("velocity", "acceleration"),
                   help="velocity or acceleration arrows on the moving points (the scene's input speed)")

    p = _add_command(
        sub, "bench", _cmd_bench, help="time numkin's sweep against the textbook way",
        description=(
            "Time the chained four-bars over 361 angles three ways, side by side: a sympy Jacobian\n"
            "rebuilt in every Newton call (the textbook way), numkin's sweep, and the vectorised\n"
            "closed form. Prints the times and ratios."
        ),
        epilog="example:\n  numkin bench",
    )
    p.add_argument("--repeat", metavar="N", type=_positive_int, help="timing repeats")
    p.add_argument("--textbook-points", metavar="K", type=_positive_int,
                   help="angles of the textbook sweep actually timed, scaled to 361 (default 12)")
    return parser


def main(argv=None) -> int:
    """Run the ``numkin`` command; returns the exit status.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success, 1 if a check point disagrees, 2 for a mistake in a scene
        or in the arguments (one line on stderr), 3 for an error numkin does
        not check for (one line; with the environment variable
        ``NUMKIN_TRACEBACK=1`` the traceback).
    """
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:
        return exit_.code if isinstance(exit_.code, int) else (0 if exit_.code is None else 2)
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _WarningLines()
            return args.func(args)
    except NumkinError as error:
        print(f"{PROG}: error: {_where(error)}{_one_line(error)}", file=sys.stderr)
        return 2
    except ValueError as error:  # not a mistake numkin checks for: a check it lacks, or a defect
        if os.environ.get("NUMKIN_TRACEBACK"):
            raise
        print(f"{PROG}: error: {_where(error)}{_one_line(error)} ({type(error).__name__}, not an error numkin "
              "checks for; NUMKIN_TRACEBACK=1 shows where it was raised)", file=sys.stderr)
        return 3
    except ArithmeticError as error:  # overflow or division by zero deep in the numbers
        print(f"{PROG}: error: {_where(error)}numerical failure ({type(error).__name__}: {_one_line(error)}); "
              "check the scene's dimensions and their unit", file=sys.stderr)
        return 2
    except OSError as error:
        where = f" {error.filename!r}" if error.filename else ""
        print(f"{PROG}: error: cannot write or read{where}: {error.strerror or error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130


class _WarningLines:
    """``warnings.showwarning`` of a command: each warning (near-singular positions, skipped figures, a
    far guess) as one line on stderr, and each distinct line once per scene, however many stages meet it."""

    def __init__(self):
        self.shown: set = set()

    def __call__(self, message, category, filename, lineno, file=None, line=None) -> None:
        text = f"{PROG}: warning: {_one_line(message)}"
        if text not in self.shown:
            self.shown.add(text)
            print(text, file=sys.stderr)


def _where(error: BaseException) -> str:
    """``"<scene file>: "`` for an error raised while solving a scene, else nothing."""
    source = getattr(error, "scene_source", None)
    return f"{source}: " if source else ""


def _one_line(error: BaseException) -> str:
    text = " ".join(str(error).split())
    return text or type(error).__name__

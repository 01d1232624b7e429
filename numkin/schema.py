"""Scene schema: read a scene file, check every key, and hold it as a :class:`Scene`.

The file format is described in :mod:`numkin.scene`. :func:`load_scene`
reads a built-in scene or a path, validates it section by section and
returns a :class:`Scene`; every mistake raises :class:`SceneError` with one
line naming the file, the key and the value. Validation imports neither
sympy, pandas nor matplotlib (and listing the scenes not even numpy); the ``[mechanism]`` section is read by
:mod:`numkin.assemble`, which also builds the mechanism.

Examples
--------
>>> scene = load_scene("homework", {"input": {"step_deg": 5}})
>>> scene.n_points, scene.speed, scene.linkage
(73, 7.5, 'chained_four_bars')
"""

from __future__ import annotations

import copy
import math
import numbers
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

from .errors import InputError, NumkinError
from .scene_sections import (QUANTITIES, TABLE_FORMATS, TABLES, in_range, input_rate, is_int, nearest, read_animation,
                             checks_as_written, read_checks, read_compare, read_figures, read_input, read_output)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = [
    "Scene",
    "SceneError",
    "SceneReader",
    "SCENES_DIR",
    "QUANTITIES",
    "TABLES",
    "TABLE_FORMATS",
    "load_scene",
    "check_scene_argument",
    "list_scenes",
    "scene_path",
    "nearest",
    "one_line",
    "in_range",
    "input_rate",
]

#: Folder of the built-in scene files (package data).
SCENES_DIR = Path(__file__).with_name("scenes")

#: Most points per turn of a report's grids (each is solved and differenced several times).
_REPORT_POINTS = 100_000

#: Built-in scenes listed first, in this order.
_BUILTIN_ORDER = ("homework", "quick-return", "six-bar", "slider-crank", "stability")



class SceneError(NumkinError, ValueError):
    """A mistake in a scene file: the message names the file, the key and the value."""



# ------------------------------------------------------------------ schema
_TOP = ("scene", "mechanism", "input", "guess", "output", "compare", "check", "report", "animation", "stability")
_SECTIONS = {
    "scene": ("description", "title"),
    "mechanism": ("linkage", "unit", "dimensions", "branch", "input", "loops", "points", "links", "ground", "name",
                  "quantities"),
    "input": ("speed", "acceleration", "start_deg", "stop_deg", "step_deg", "on_singular"),
    "output": ("quantities", "unknowns", "points", "tables", "table_formats", "figures"),
    "compare": ("schemes", "second_schemes"),
    "report": ("quantity", "check_deg", "schemes", "grids", "points_per_turn", "repeat"),
    "animation": ("frames", "fps", "dpi", "width", "turn", "traces", "arrows"),
    "stability": ("cases",),
}


def one_line(text: str) -> str:
    """``text`` on one line, its runs of white space (newlines included) one space each.

    >>> one_line("malformed TOML:\\n  line 2")
    'malformed TOML: line 2'
    """
    return " ".join(str(text).split())


class SceneReader:
    """Validation helpers that raise SceneError prefixed with the scene's source."""

    def __init__(self, source: str):
        self.source = source

    def fail(self, where: str, message: str):
        prefix = f"{self.source}: " if self.source else ""
        where = f"{where}: " if where else ""
        raise SceneError(one_line(f"{prefix}{where}{message}"))

    def table(self, value, where: str) -> dict:
        if not isinstance(value, dict):
            self.fail(where, f"must be a table, got {value!r}")
        return value

    def keys(self, table: dict, allowed, where: str):
        for key in table:
            if key not in allowed:
                self.fail(where, f"unknown key '{key}'{nearest(key, allowed)}; valid keys: {', '.join(allowed)}")

    def string(self, value, where: str) -> str:
        if not isinstance(value, str) or not value.strip():
            self.fail(where, f"must be a non-empty string, got {value!r}")
        return value.strip()

    def number(self, value, where: str) -> float:
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            self.fail(where, f"must be a number, got {value!r}")
        v = float(value)
        if not math.isfinite(v):
            self.fail(where, f"must be finite, got {value!r}")
        return v

    def strings(self, value, where: str, choices=None) -> tuple:
        if isinstance(value, str):
            value = [value]
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            self.fail(where, f"must be a list of strings, got {value!r}")
        if choices is not None:
            for v in value:
                if v not in choices:
                    self.fail(where, f"unknown value '{v}'{nearest(v, choices)}; valid values: {', '.join(choices)}")
        if len(set(value)) != len(value):
            self.fail(where, f"lists a value twice: {value!r}")
        return tuple(value)

    def length(self, value, where: str, unit: str, *, positive: bool = True) -> float:
        """A length in the working unit: a number, or a string '<number> <unit>'."""
        if isinstance(value, str):
            m = re.fullmatch(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([A-Za-z]+)\s*", value)
            if m is None:
                self.fail(where, f"cannot read {value!r} as a length; write a number (in {unit}) or e.g. '80 mm'")
            from .units import UnitError, convert_length

            try:
                v = float(convert_length(float(m[1]), m[2], unit))
            except UnitError as error:
                self.fail(where, f"{value!r}: {error}")
        else:
            v = self.number(value, where)
        if positive and not v > 0:
            self.fail(where, f"must be a positive length, got {value!r}")
        return v



# ------------------------------------------------------------------- scene
@dataclass
class Scene:
    """A validated scene (see the module docstring for the file format).

    Attributes
    ----------
    name : str
        The built-in name, or the file's stem.
    description, title : str
    source : str
        Where it came from (file name), used in error messages.
    kind : {"mechanism", "stability"}
    linkage : str or None
        Ready-made linkage (a key of :data:`numkin.linkages.SPECS`), or None for loops.
    unit : str
        Working length unit.
    dimensions : dict
        Ready-made: keyword -> value (lengths in ``unit``, angles in rad, pairs
        as tuples). Loops: parameter name -> value (rad for ``_deg`` keys).
    speed, acceleration : float or None
        Input angular speed [rad/s] and acceleration [rad/s^2].
    start_deg, stop_deg, step_deg : float
        The input sweep (degrees, inclusive).
    on_singular : {"raise", "report"}
        What the sweep does at a change point (:meth:`numkin.Mechanism.sweep`).
    quantities : tuple of str
        Subset of ("position", "velocity", "acceleration").
    unknowns, points : tuple of str or None
        Unknowns (None = all) and named points reported.
    derived : dict
        ``[mechanism.quantities]``: name -> (expression, "angle" or "length"),
        always reported (:mod:`numkin.derived`).
    schemes, second_schemes : tuple of str
        Finite-difference schemes compared for velocity and acceleration.
    checks : list of dict
        ``{"at_deg": float, "expected": {quantity: value}, "tolerance": float | None, "written": {quantity:
        text}}``: ``written`` holds each expected value as the scene file writes it (``"122.340"``), whose
        last decimal sets the default tolerance.
    tables, figures, table_formats : tuple of str
    report, animation : dict
    stability_cases : tuple of str or None
    data : dict
        The TOML as read (after overrides).
    """

    name: str
    description: str
    source: str
    data: dict
    kind: str = "mechanism"
    title: str = ""
    linkage: str | None = None
    unit: str = "mm"
    dimensions: dict = field(default_factory=dict)
    branch: str | None = None
    custom: dict | None = None
    derived: dict = field(default_factory=dict)
    speed: float | None = None
    speed_text: str | None = None
    acceleration: float = 0.0
    acceleration_text: str | None = None
    start_deg: float = 0.0
    stop_deg: float = 360.0
    step_deg: float = 1.0
    on_singular: str = "raise"
    guess: dict | None = None
    quantities: tuple = ("position",)
    unknowns: tuple | None = None
    points: tuple = ()
    tables: tuple = ()
    table_formats: tuple = ("csv",)
    figures: tuple = ()
    schemes: tuple = ()
    second_schemes: tuple = ()
    checks: list = field(default_factory=list)
    report: dict = field(default_factory=dict)
    animation: dict = field(default_factory=dict)
    stability_cases: tuple | None = None

    # ------------------------------------------------------------- queries
    def wants(self, quantity: str) -> bool:
        """True if the scene asks for ``quantity`` ("position", "velocity", "acceleration")."""
        return quantity in self.quantities

    @property
    def differentiates(self) -> bool:
        """True if the scene needs velocities or accelerations."""
        return self.wants("velocity") or self.wants("acceleration")

    @property
    def n_points(self) -> int:
        return int(round((self.stop_deg - self.start_deg) / self.step_deg)) + 1

    def inputs(self):
        """The input sweep, rad (a numpy array)."""
        import numpy as np

        return np.radians(self.start_deg + self.step_deg * np.arange(self.n_points))

    def fail(self, where: str, message: str):
        SceneReader(self.source).fail(where, message)

    def report_options(self, mech) -> dict:
        """Keyword arguments of :func:`numkin.report.full_report` for this scene's mechanism."""
        options = dict(self.report)
        quantity = options.pop("quantity", None) or (self.unknowns or mech.unknowns)[0]
        check_deg = options.pop("check_deg", None)
        span = self.stop_deg - self.start_deg  # the report sweeps a turn at most, the scene's sweep if less
        if check_deg is None and self.checks:
            check_deg = self.checks[0]["at_deg"]
        elif check_deg is None:  # the start; on less than a turn, the coarsest report grid's point nearest the
            # middle (on the finer grids too where they are its multiples)
            from .report.grids import DEFAULT_GRIDS

            coarse = 360.0 / min(options.get("grids", DEFAULT_GRIDS))
            check_deg = self.start_deg if span >= 360.0 else self.start_deg + coarse * round(0.5 * span / coarse)
        return {
            "omega": self.speed, "quantity": quantity, "check_angle": math.radians(check_deg),
            "start": math.radians(self.start_deg), "guess": self.guess_values(mech),
            **({} if span >= 360.0 else {"span": math.radians(span)}), **options,
        }

    def positions_only(self) -> "Scene":
        """A copy that asks for positions only: no differentiation, tables, figures or checks."""
        import dataclasses

        return dataclasses.replace(
            self, quantities=("position",), schemes=(), second_schemes=(), checks=[], tables=(), figures=(),
        )

    # -------------------------------------------------------------- build
    def build_mechanism(self):
        """The scene's :class:`~numkin.Mechanism`; names in the scene are checked against it."""
        from .assemble import build_mechanism

        mech = build_mechanism(self)
        if self.custom is not None:
            try:
                mech.check_lengths(every_link=True)
            except ValueError as error:
                self.fail(f"[mechanism.dimensions] {error.parameter}", str(error))
        return mech

    def guess_values(self, mech) -> dict | None:
        """The ``[guess]`` table as ``{unknown: value}`` (rad, working unit), or None."""
        from .assemble import guess_values

        return guess_values(self, mech)

    def quantity_names(self, mech, *, all_unknowns: bool = False) -> list[str]:
        """Names of the quantities the scene computes (see :mod:`numkin.scene`)."""
        from .scene_quantities import quantity_names

        return quantity_names(self, mech, all_unknowns=all_unknowns)


# ------------------------------------------------------------------- loading
def list_scenes() -> dict[str, str]:
    """Built-in scenes: name -> one-line description, in a fixed order.

    Examples
    --------
    >>> list(list_scenes())[:2]
    ['homework', 'quick-return']
    """
    files = {p.stem: p for p in SCENES_DIR.glob("*.toml")}
    order = [n for n in _BUILTIN_ORDER if n in files] + sorted(set(files) - set(_BUILTIN_ORDER))
    out = {}
    for name in order:
        with open(files[name], "rb") as fh:
            out[name] = tomllib.load(fh).get("scene", {}).get("description", "")
    return out


def scene_path(name_or_path) -> Path:
    """The file of a built-in scene name, or the path given (must exist)."""
    text = str(name_or_path)
    builtin = SCENES_DIR / f"{text}.toml"
    if isinstance(name_or_path, str) and "/" not in text and not text.endswith(".toml") and builtin.is_file():
        return builtin
    path = Path(name_or_path)
    if path.suffix == ".toml" or path.is_file() or "/" in text or "\\" in text:
        if path.is_dir():
            raise SceneError(f"scene file {text!r} is a directory; give a scene's .toml file")
        if not path.is_file():
            raise SceneError(f"scene file {text!r} not found")
        return path
    names = list(list_scenes())
    raise SceneError(
        f"unknown scene '{text}'{nearest(text, names)}; built-in scenes: {', '.join(names)} "
        "(or give the path of a .toml file)"
    )


def check_scene_argument(value, argument: str = "name_or_path") -> None:
    """Refuse what is neither a scene's name nor a path, naming ``argument`` and what was given.

    Examples
    --------
    >>> check_scene_argument("homework")
    >>> check_scene_argument(None)
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: name_or_path must be a built-in scene's name or the path of a .toml file (str or pathlib.Path), got NoneType None
    """
    if isinstance(value, bytes) or not isinstance(value, (str, os.PathLike)):
        raise InputError(f"{argument} must be a built-in scene's name or the path of a .toml file (str or "
                         f"pathlib.Path), got {type(value).__name__} {value!r:.60}")


def load_scene(name_or_path, overrides: Mapping | None = None) -> Scene:
    """Read and validate a scene: a built-in name (``numkin scenes``) or a .toml path.

    Parameters
    ----------
    name_or_path : str or path
    overrides : mapping, optional
        Nested values merged into the file before validation, e.g.
        ``{"input": {"step_deg": 5}}`` for a coarser, faster sweep.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        A mistake in the scene or its file (missing, a folder, not TOML, not
        text): one line naming the file, the key and what is wrong.
    InputError
        If ``name_or_path`` is not a ``str`` or path, or ``overrides`` not a
        mapping (the message names the argument and what was given).

    Examples
    --------
    >>> scene = load_scene("homework")
    >>> scene.speed, scene.n_points
    (7.5, 361)
    >>> load_scene("homework", overrides=[("input", 5)])
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: overrides must be a mapping of the scene's sections, e.g. {'input': {'step_deg': 5}}, got list [('input', 5)]
    """
    check_scene_argument(name_or_path)
    if overrides is not None and not isinstance(overrides, Mapping):
        raise InputError("overrides must be a mapping of the scene's sections, e.g. {'input': {'step_deg': 5}}, "
                         f"got {type(overrides).__name__} {overrides!r:.60}")
    path = scene_path(name_or_path)
    builtin = path.parent == SCENES_DIR
    source = path.name
    try:
        with open(path, "rb") as fh:
            raw = fh.read()
        # a byte-order mark, which some editors write at the start of UTF-8 text, is no TOML: read past it
        data = tomllib.loads(raw.decode("utf-8-sig"))
    except tomllib.TOMLDecodeError as error:
        raise SceneError(one_line(f"{source}: malformed TOML: {error}")) from None
    except UnicodeDecodeError as error:
        raise SceneError(f"{source}: not a text file ({error.reason})") from None
    except OSError as error:
        raise SceneError(f"{source}: cannot read: {error.strerror}") from None
    written = checks_as_written(raw.decode("utf-8-sig")) if not (overrides and "check" in overrides) else None
    if overrides:
        data = _merge(copy.deepcopy(data), overrides)
    return _validate(data, name=path.stem, source=source if not builtin else f"{path.stem} (built-in {source})",
                     written=written)


def _merge(base: dict, extra: Mapping) -> dict:
    for key, value in extra.items():
        if isinstance(value, Mapping) and isinstance(base.get(key), dict):
            _merge(base[key], value)
        else:
            base[key] = copy.deepcopy(value)
    return base


def _validate(data: dict, *, name: str, source: str, written=None) -> Scene:
    r = SceneReader(source)
    r.keys(data, _TOP, "")
    for section, allowed in _SECTIONS.items():
        if section in data:
            r.keys(r.table(data[section], f"[{section}]"), allowed, f"[{section}]")
    if "scene" not in data:
        r.fail("", "missing [scene] section (with a description)")
    head = r.table(data["scene"], "[scene]")
    if "description" not in head:
        r.fail("[scene]", "missing key 'description' (one line, shown by `numkin scenes`)")
    scene = Scene(
        name=name, source=source, data=data,
        description=r.string(head["description"], "[scene] description"),
        title=r.string(head["title"], "[scene] title") if "title" in head else "",
    )
    if "stability" in data:
        if "mechanism" in data:
            r.fail("", "a scene has either a [mechanism] or a [stability] section, not both")
        scene.kind = "stability"
        st = data["stability"]
        scene.stability_cases = r.strings(st["cases"], "[stability] cases") if "cases" in st else None
        out = r.table(data.get("output", {}), "[output]")
        scene.tables = r.strings(out.get("tables", ["stability"]), "[output] tables", ("stability",))
        scene.table_formats = r.strings(out.get("table_formats", ["csv"]), "[output] table_formats", TABLE_FORMATS)
        scene.figures = read_figures(r, out)
        for section in ("input", "guess", "compare", "check", "report", "animation"):
            if section in data:
                r.fail(f"[{section}]", "does not apply to a [stability] scene")
        return scene
    if "mechanism" not in data:
        r.fail("", "missing [mechanism] section (a ready-made `linkage` or `loops`)")
    from .assemble import read_mechanism

    read_mechanism(r, scene, r.table(data["mechanism"], "[mechanism]"))
    read_output(r, scene, r.table(data.get("output", {}), "[output]"))
    read_input(r, scene, r.table(data.get("input", {}), "[input]"))
    if "guess" in data:
        guess = r.table(data["guess"], "[guess]")
        if scene.custom is None and not guess:
            r.fail("[guess]", "is empty")
        if scene.branch is not None:  # both pick the assembly: one could silently overrule the other
            r.fail("[mechanism] branch", f"\"{scene.branch}\" and a [guess] both pick the assembly branch: give one "
                                         "(branch for the ready-made one, or a [guess] of the unknowns)")
        scene.guess = dict(guess)
    elif scene.custom is not None:
        r.fail("", "missing [guess] section: a mechanism written as loops needs values for its unknowns at start_deg")
    read_compare(r, scene, r.table(data.get("compare", {}), "[compare]"))
    read_checks(r, scene, data.get("check", []), written)
    if "report" in data:
        rep = data["report"]
        report = {}
        if "quantity" in rep:
            report["quantity"] = r.string(rep["quantity"], "[report] quantity")
        if "check_deg" in rep:
            report["check_deg"] = r.number(rep["check_deg"], "[report] check_deg")
        if "schemes" in rep:
            from .derivatives import SCHEMES, get_scheme

            names = []
            for name in r.strings(rep["schemes"], "[report] schemes"):
                try:
                    names.append(get_scheme(name).name)
                except ValueError:
                    r.fail("[report] schemes", f"unknown scheme '{name}'{nearest(name, SCHEMES)}; schemes: {', '.join(SCHEMES)}")
            if not names:
                r.fail("[report] schemes", "is empty: name at least one scheme, or leave the key out for all")
            report["schemes"] = tuple(names)
        if "grids" in rep:
            grids = rep["grids"]
            if not isinstance(grids, list) or not grids or not all(is_int(v, 4) for v in grids):
                r.fail("[report] grids", f"must be a list of points per turn (integers >= 4), got {grids!r}")
            if len(set(grids)) != len(grids):
                r.fail("[report] grids", f"names a grid twice ({grids!r}): the observed order needs distinct steps")
            if max(grids) > _REPORT_POINTS:
                r.fail("[report] grids", f"at most {_REPORT_POINTS:,} points per turn, got {max(grids):,}")
            report["grids"] = tuple(grids)
        for key, least, most in (("points_per_turn", 4, _REPORT_POINTS), ("repeat", 1, 1000)):
            if key in rep:
                if not is_int(rep[key], least):
                    r.fail(f"[report] {key}", f"must be an integer >= {least}, got {rep[key]!r}")
                if rep[key] > most:
                    r.fail(f"[report] {key}", f"at most {most:,}, got {rep[key]:,}")
                report[key] = rep[key]
        scene.report = report  # without [input] speed the report is per rad/s (numkin.report.scene_report)
    if "animation" in data:
        scene.animation = read_animation(r, scene, r.table(data["animation"], "[animation]"))
    return scene

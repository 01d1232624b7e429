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
import difflib
import math
import numbers
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

from .errors import NumkinError

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
    "list_scenes",
    "scene_path",
    "nearest",
    "one_line",
    "in_range",
    "input_rate",
]

#: Folder of the built-in scene files (package data).
SCENES_DIR = Path(__file__).with_name("scenes")

#: Built-in scenes listed first, in this order.
_BUILTIN_ORDER = ("homework", "quick-return", "six-bar", "slider-crank", "stability")

QUANTITIES = ("position", "velocity", "acceleration")
TABLES = ("positions", "kinematics", "points", "comparison", "summary", "checks", "stability")
TABLE_FORMATS = ("csv", "md", "tex")


class SceneError(NumkinError, ValueError):
    """A mistake in a scene file: the message names the file, the key and the value."""



# ------------------------------------------------------------------ schema
_TOP = ("scene", "mechanism", "input", "guess", "output", "compare", "check", "report", "animation", "stability")
_SECTIONS = {
    "scene": ("description", "title"),
    "mechanism": ("linkage", "unit", "dimensions", "branch", "input", "loops", "points", "links", "ground", "name"),
    "input": ("speed", "acceleration", "start_deg", "stop_deg", "step_deg"),
    "output": ("quantities", "unknowns", "points", "tables", "table_formats", "figures"),
    "compare": ("schemes", "second_schemes"),
    "report": ("quantity", "check_deg", "schemes", "grids", "points_per_turn", "repeat"),
    "animation": ("frames", "fps", "dpi", "width", "turn", "traces", "arrows"),
    "stability": ("cases",),
}


def nearest(word: str, choices) -> str:
    match = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.5)
    return f" (did you mean '{match[0]}'?)" if match else ""


def one_line(text: str) -> str:
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
    quantities : tuple of str
        Subset of ("position", "velocity", "acceleration").
    unknowns, points : tuple of str or None
        Unknowns (None = all) and named points reported.
    schemes, second_schemes : tuple of str
        Finite-difference schemes compared for velocity and acceleration.
    checks : list of dict
        ``{"at_deg": float, "expected": {quantity: value}, "tolerance": float | None}``.
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
    speed: float | None = None
    speed_text: str | None = None
    acceleration: float = 0.0
    acceleration_text: str | None = None
    start_deg: float = 0.0
    stop_deg: float = 360.0
    step_deg: float = 1.0
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
        if check_deg is None:
            check_deg = self.checks[0]["at_deg"] if self.checks else self.start_deg
        return {
            "omega": self.speed, "quantity": quantity, "check_angle": math.radians(check_deg),
            "start": math.radians(self.start_deg), "guess": self.guess_values(mech), **options,
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
        if self.custom is not None:  # loops: every dimension but the angles (<name>_deg) is a length
            lengths = {k for k in self.data["mechanism"].get("dimensions", {}) if not k.endswith("_deg")}
            try:
                mech.check_lengths(lengths)
            except ValueError as error:
                self.fail(f"[mechanism.dimensions] {error.parameter}", str(error))
        return mech

    def guess_values(self, mech) -> dict | None:
        """The ``[guess]`` table as ``{unknown: value}`` (rad, working unit), or None."""
        from .assemble import guess_values

        return guess_values(self, mech)

    def quantity_names(self, mech, *, all_unknowns: bool = False) -> list[str]:
        """Names of the quantities the scene computes (see :mod:`numkin.scene`)."""
        from .assemble import quantity_names

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
        One line naming the file, the key and what is wrong.

    Examples
    --------
    >>> scene = load_scene("homework")
    >>> scene.speed, scene.n_points
    (7.5, 361)
    """
    path = scene_path(name_or_path)
    builtin = path.parent == SCENES_DIR
    source = path.name
    try:
        with open(path, "rb") as fh:
            data = tomllib.load(fh)
    except tomllib.TOMLDecodeError as error:
        raise SceneError(one_line(f"{source}: malformed TOML: {error}")) from None
    except UnicodeDecodeError as error:
        raise SceneError(f"{source}: not a text file ({error.reason})") from None
    except OSError as error:
        raise SceneError(f"{source}: cannot read: {error.strerror}") from None
    if overrides:
        data = _merge(copy.deepcopy(data), overrides)
    return _validate(data, name=path.stem, source=source if not builtin else f"{path.stem} (built-in {source})")


def _merge(base: dict, extra: Mapping) -> dict:
    for key, value in extra.items():
        if isinstance(value, Mapping) and isinstance(base.get(key), dict):
            _merge(base[key], value)
        else:
            base[key] = copy.deepcopy(value)
    return base


def _validate(data: dict, *, name: str, source: str) -> Scene:
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
        scene.figures = _read_figures(r, out)
        for section in ("input", "guess", "compare", "check", "report", "animation"):
            if section in data:
                r.fail(f"[{section}]", "does not apply to a [stability] scene")
        return scene
    if "mechanism" not in data:
        r.fail("", "missing [mechanism] section (a ready-made `linkage` or `loops`)")
    from .assemble import read_mechanism

    read_mechanism(r, scene, r.table(data["mechanism"], "[mechanism]"))
    _read_output(r, scene, r.table(data.get("output", {}), "[output]"))
    _read_input(r, scene, r.table(data.get("input", {}), "[input]"))
    if "guess" in data:
        guess = r.table(data["guess"], "[guess]")
        if scene.custom is None and not guess:
            r.fail("[guess]", "is empty")
        scene.guess = dict(guess)
    elif scene.custom is not None:
        r.fail("", "missing [guess] section: a mechanism written as loops needs values for its unknowns at start_deg")
    _read_compare(r, scene, r.table(data.get("compare", {}), "[compare]"))
    _read_checks(r, scene, data.get("check", []))
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
            report["schemes"] = tuple(names)
        if "grids" in rep:
            grids = rep["grids"]
            if not isinstance(grids, list) or not grids or not all(_is_int(v, 4) for v in grids):
                r.fail("[report] grids", f"must be a list of points per turn (integers >= 4), got {grids!r}")
            report["grids"] = tuple(grids)
        for key, least in (("points_per_turn", 4), ("repeat", 1)):
            if key in rep:
                if not _is_int(rep[key], least):
                    r.fail(f"[report] {key}", f"must be an integer >= {least}, got {rep[key]!r}")
                report[key] = rep[key]
        scene.report = report  # without [input] speed the report is per rad/s (numkin.report.scene_report)
    if "animation" in data:
        scene.animation = _read_animation(r, scene, r.table(data["animation"], "[animation]"))
    return scene


#: Choices of ``[animation] turn`` and ``arrows`` (as ``numkin animate`` takes them).
ANIMATION_TURNS = ("full", "sweep")
ANIMATION_ARROWS = ("velocity", "acceleration")
#: Ranges of ``[animation]`` (and ``numkin animate``) dpi and width [in].
ANIMATION_DPI = (10, 600)
ANIMATION_WIDTH_IN = (1.0, 40.0)


def _read_animation(r: SceneReader, scene, table: dict) -> dict:
    """The ``[animation]`` section: defaults of ``numkin animate``'s options (only the keys given, and frames)."""
    out = {}
    frames = table.get("frames", 72)
    if not _is_int(frames, 2):
        r.fail("[animation] frames", f"must be an integer >= 2, got {frames!r}")
    out["frames"] = frames
    if "fps" in table:
        fps = r.number(table["fps"], "[animation] fps")
        if not 0 < fps <= 100:
            r.fail("[animation] fps", f"must be a number of frames per second in (0, 100], got {table['fps']!r}")
        out["fps"] = fps
    if "dpi" in table:
        low, high = ANIMATION_DPI
        if not (_is_int(table["dpi"], low) and table["dpi"] <= high):
            r.fail("[animation] dpi", f"must be an integer from {low} to {high} (dots per inch), got {table['dpi']!r}")
        out["dpi"] = table["dpi"]
    if "width" in table:
        low, high = ANIMATION_WIDTH_IN
        width = r.number(table["width"], "[animation] width")
        if not low <= width <= high:
            r.fail("[animation] width", f"must be from {low:g} to {high:g} (inches), got {table['width']!r}")
        out["width"] = width
    if "turn" in table:
        if not isinstance(table["turn"], str):
            r.fail("[animation] turn", f"must be one of {', '.join(ANIMATION_TURNS)}, got {table['turn']!r}")
        out["turn"] = r.strings(table["turn"], "[animation] turn", ANIMATION_TURNS)[0]
    if "traces" in table:
        out["traces"] = r.strings(table["traces"], "[animation] traces")
    if "arrows" in table:
        if not isinstance(table["arrows"], str):
            r.fail("[animation] arrows", f"must be one of {', '.join(ANIMATION_ARROWS)}, got {table['arrows']!r}")
        out["arrows"] = r.strings(table["arrows"], "[animation] arrows", ANIMATION_ARROWS)[0]
        if not scene.speed:
            r.fail("[animation] arrows", "needs [input] speed (the arrows are velocities or accelerations)")
    return out


def _is_int(value, least: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= least



def input_rate(value, order: int, name: str | None = None) -> float:
    """The input's speed (``order`` 1, rad/s) or acceleration (2, rad/s^2) from a scene value.

    Read by :func:`numkin.units.input_rate`, the one parser of input rates;
    everything downstream receives the float. `name` names the value in
    messages.

    Examples
    --------
    >>> input_rate("450 rad/min", 1), input_rate("2 rev/s^2", 2) / math.pi
    (7.5, 4.0)
    """
    from .units import input_rate as parse

    return parse(value, "speed" if order == 1 else "acceleration", name=name)


def _read_input(r: SceneReader, scene: Scene, inp: dict) -> None:
    from .units import UnitError

    for key, order in (("speed", 1), ("acceleration", 2)):
        if key not in inp:
            continue
        setattr(scene, f"{key}_text", str(inp[key]))
        try:
            setattr(scene, key, input_rate(inp[key], order, name=f"[input] {key}"))
        except (UnitError, TypeError, ValueError) as error:
            r.fail("", str(error))
    if "speed" in inp and scene.speed == 0:
        r.fail("[input] speed", f"must not be zero, got {inp['speed']!r}")
    if "speed" not in inp and scene.differentiates:
        r.fail("[input]", "missing key 'speed' (e.g. \"450 rad/min\"), needed for velocity and acceleration")
    scene.start_deg = r.number(inp.get("start_deg", 0.0), "[input] start_deg")
    scene.stop_deg = r.number(inp.get("stop_deg", 360.0), "[input] stop_deg")
    scene.step_deg = r.number(inp.get("step_deg", 1.0), "[input] step_deg")
    if not scene.step_deg > 0:
        r.fail("[input] step_deg", f"must be positive, got {inp.get('step_deg')!r}")
    span = scene.stop_deg - scene.start_deg
    if not span > 0:
        r.fail("[input] stop_deg", f"must be greater than start_deg = {scene.start_deg:g}, got {scene.stop_deg:g}")
    count = span / scene.step_deg
    if abs(count - round(count)) > 1e-9 * max(1.0, count):
        r.fail("[input] step_deg", f"stop_deg - start_deg = {span:g} is not a multiple of step_deg = {scene.step_deg:g}")
    if round(count) < 2 and scene.differentiates:
        r.fail("[input] step_deg", "the sweep needs at least 3 points to be differentiated")
    if round(count) > 10_000_000:  # blamed on the step or the sweep's end, whichever is further from 1° over 360°
        end = "start_deg" if abs(scene.start_deg) > abs(scene.stop_deg) else "stop_deg"
        r.fail(
            f"[input] {end if span / 360.0 > 1.0 / scene.step_deg else 'step_deg'}",
            f"{count:.3g} points from start_deg = {scene.start_deg:g} to stop_deg = {scene.stop_deg:g} at "
            f"step_deg = {scene.step_deg:g}: more than ten million",
        )


def _read_output(r: SceneReader, scene: Scene, out: dict) -> None:
    scene.quantities = r.strings(out.get("quantities", ["position"]), "[output] quantities", QUANTITIES)
    if not scene.quantities:
        r.fail("[output] quantities", "is empty; ask for at least \"position\"")
    if "position" not in scene.quantities:
        scene.quantities = ("position", *scene.quantities)
    scene.unknowns = r.strings(out["unknowns"], "[output] unknowns") if "unknowns" in out else None
    scene.points = r.strings(out.get("points", []), "[output] points")
    scene.tables = r.strings(out.get("tables", []), "[output] tables", TABLES[:-1])
    scene.table_formats = r.strings(out.get("table_formats", ["csv"]), "[output] table_formats", TABLE_FORMATS)
    scene.figures = _read_figures(r, out)
    needs = {"kinematics": "velocity", "comparison": "velocity"}
    for table, quantity in needs.items():
        if table in scene.tables and not scene.differentiates:
            r.fail("[output] tables", f"'{table}' needs \"velocity\" or \"acceleration\" in [output] quantities")
    if "points" in scene.tables and not scene.points:
        r.fail("[output] tables", "'points' needs [output] points")


def _read_figures(r: SceneReader, out: dict) -> tuple:
    names = r.strings(out.get("figures", []), "[output] figures")
    if names:
        from .figures import parse_spec  # does not import matplotlib

        for name in names:
            try:
                parse_spec(name)
            except ValueError as error:
                r.fail("[output] figures", str(error))
    return names


def _read_compare(r: SceneReader, scene: Scene, cmp: dict) -> None:
    from .derivatives import SCHEMES, get_scheme

    for key, order, quantity in (("schemes", 1, "velocity"), ("second_schemes", 2, "acceleration")):
        if key not in cmp:
            continue
        names = []
        for s in r.strings(cmp[key], f"[compare] {key}"):
            try:
                scheme = get_scheme(s)
            except ValueError:
                r.fail(f"[compare] {key}", f"unknown scheme '{s}'{nearest(s, SCHEMES)}; schemes: {', '.join(SCHEMES)}")
            if scheme.derivative != order:
                other = "second_schemes" if order == 1 else "schemes"
                which = "second" if order == 1 else "first"
                r.fail(f"[compare] {key}", f"'{s}' is a {which}-derivative scheme: list it in {other}")
            if scheme.periodic_only and abs(scene.stop_deg - scene.start_deg - 360.0) > 1e-9:
                r.fail(f"[compare] {key}", f"'{s}' needs a sweep of exactly one turn (stop_deg - start_deg = 360)")
            names.append(scheme.name)
        if names and not scene.wants(quantity):
            r.fail(f"[compare] {key}", f"compares {quantity}: add \"{quantity}\" to [output] quantities")
        setattr(scene, key, tuple(names))
    if "comparison" in scene.tables and not (scene.schemes or scene.second_schemes):
        r.fail("[output] tables", "'comparison' needs [compare] schemes or second_schemes")
    if "summary" in scene.tables and not (scene.schemes or scene.second_schemes):
        r.fail("[output] tables", "'summary' needs [compare] schemes or second_schemes")


def _read_checks(r: SceneReader, scene: Scene, checks) -> None:
    if isinstance(checks, dict):
        checks = [checks]
    if not isinstance(checks, list):
        r.fail("[[check]]", f"must be an array of tables, got {checks!r}")
    for k, check in enumerate(checks):
        where = f"[[check]] {k + 1}"
        r.table(check, where)
        if "at_deg" not in check:
            r.fail(where, "missing key 'at_deg' (the input angle of the check point, degrees)")
        at = r.number(check["at_deg"], f"{where} at_deg")
        in_range(r, scene, at, f"{where} at_deg")
        tol = None
        if "tolerance" in check:
            tol = r.number(check["tolerance"], f"{where} tolerance")
            if not tol > 0:
                r.fail(f"{where} tolerance", f"must be positive, got {tol!r}")
        expected = {}
        for key, value in check.items():
            if key in ("at_deg", "tolerance"):
                continue
            expected[key] = r.number(value, f"{where} {key}")
        scene.checks.append({"at_deg": at, "expected": expected, "tolerance": tol})


def in_range(r: SceneReader, scene: Scene, at: float, where: str) -> None:
    if not scene.start_deg - 1e-9 <= at <= scene.stop_deg + 1e-9:
        r.fail(where, f"{at:g}° is outside the sweep {scene.start_deg:g}..{scene.stop_deg:g}°")



"""Scenes: one kinematics problem declared in a TOML file.

A scene names the mechanism, the input motion, what to compute, which
finite-difference schemes to compare, the check points and the tables and
figures wanted. :func:`load_scene` reads and validates it (built-in name or
path), :func:`run_scene` computes exactly what it asks for and nothing more:
a position-only scene never differentiates (nothing of ``numkin.analytic``,
``numkin.kinematics`` or ``numkin.compare`` is called, and the acceleration
equations are never derived), and a scene that asks for no figure never
imports matplotlib.

Degrees appear only at the edge and are labelled in the key names
(``start_deg``, ``theta3_deg``); everything inside is in radians.

Scene file
----------
All sections but ``[scene]`` and one of ``[mechanism]`` / ``[stability]``
are optional. ::

    [scene]
    description = "one line, shown by `numkin scenes`"    # required
    title = "heading printed by `numkin run`"              # optional

    [mechanism]
    linkage = "four_bar"     # a ready-made linkage (table below) ...
    unit = "mm"              # working length unit: mm, cm, m, in, ft (default mm)
    branch = "open"          # four_bar only: "open" or "crossed"
    [mechanism.dimensions]   # numbers in `unit`, or strings with their own unit
    ground = 4               # ("80 mm"); angles as <name>_deg
    crank = 1
    coupler = 3
    rocker = 3

    [input]
    speed = "450 rad/min"    # needed for velocity/acceleration: rad/s, rad/min, rpm,
                             # rev/s, deg/s (a bare number is rad/s); sign = direction
    acceleration = "0 rad/s^2"   # optional input angular acceleration
    start_deg = 0            # sweep of the input, inclusive, uniform step
    stop_deg = 360
    step_deg = 1

    [guess]                  # values at start_deg: picks the assembly branch;
    theta3_deg = 30          # all unknowns (angles as <name>_deg, lengths in `unit`);
    theta4_deg = 120         # optional for ready-made linkages

    [output]
    quantities = ["position", "velocity", "acceleration"]   # default ["position"]
    unknowns = ["theta4"]    # which unknowns to report (default all)
    points = ["B"]           # named points whose x, y (vx, vy, ax, ay) are wanted
    tables = ["positions", "kinematics", "points", "comparison", "summary", "checks"]
    table_formats = ["csv"]  # csv, md, tex
    figures = ["..."]        # names understood by numkin.figures (default none)

    [compare]                # finite differences against the analytic solution
    schemes = ["forward", "centred"]            # first derivative -> velocity
    second_schemes = ["second_difference"]      # second derivative -> acceleration

    [[check]]                # a check point; expected values are optional
    at_deg = 100
    omega_theta4 = 10.633    # agrees to the decimals written, or give
    tolerance = 1e-3         # an absolute tolerance

    [report]                 # settings of the error-analysis tables (numkin.report):
    quantity = "theta4"      # the unknown studied (default: the first reported)
    check_deg = 100          # check angle (default: the first [[check]])
    grids = [36, 72, 180, 360]   # points per turn of the convergence tables
    schemes = ["forward", "centred"]   # default: all
    points_per_turn = 360    # grid of the Jacobian and tolerance tables
    repeat = 3               # timing repeats

    [animation]
    frames = 72              # frame count of `numkin animate`

Mechanism written as loops (instead of ``linkage``)::

    [mechanism]
    input = "theta2"         # the input symbol (an angle, rad)
    unit = "mm"
    links = [["O2", "A", "B", "O4"]]    # optional, for drawing
    ground = ["O2", "O4"]
    [mechanism.dimensions]   # parameters: lengths in `unit`; <name>_deg an angle
    r1 = 4
    r2 = 1
    r3 = 3
    r4 = 3
    [[mechanism.loops]]
    name = "O2-A-B-O4"
    unknowns = ["theta3", "theta4"]
    vectors = [["r2", "theta2"], ["r3", "theta3"], ["-r4", "theta4"], ["-r1", "0"]]
    # or: equations = ["r2*cos(theta2) + ... ", "..."]   (each = 0, or "lhs = rhs")
    [mechanism.points]
    A = ["r2*cos(theta2)", "r2*sin(theta2)"]

Expressions are sympy-parsable strings in the input, the dimensions, the
unknowns of this and earlier loops, ``pi`` and ``sin cos tan asin acos atan
atan2 sqrt exp abs``. A loop of vectors sums (length, angle) pairs to zero
(angles in rad from +x, counter-clockwise).

Quantity names (for ``[[check]]``, ``--at``, JSON): an angle unknown's position
``<u>_deg``, a length unknown ``<u>`` [unit]; ``omega_<u>`` [rad/s] and
``alpha_<u>`` [rad/s^2]; ``v_<u>`` [unit/s] and ``a_<u>`` [unit/s^2]; points
``x_<P>``, ``y_<P>``, ``vx_<P>``, ``vy_<P>``, ``ax_<P>``, ``ay_<P>``.

The stability suite is a scene too: ``[stability] cases = [...]`` (default all
of :data:`numkin.stability.CASES`) instead of ``[mechanism]``.

============================  ======================================================  ============
``linkage``                   dimensions (all required unless marked)                 unknowns
============================  ======================================================  ============
``four_bar``                  ground, crank, coupler, rocker (+ ``branch``)            theta3, theta4
``slider_crank``              crank, rod, offset (optional, 0)                         theta3, x
``quick_return``              r1, r2, r6                                               r3, theta3, r4, r5
``six_bar``                   crank, coupler, o4b, bc, o4c, rod, o4 = [x, y],          theta3, theta4,
                              slider_y                                                 theta5, x
``chained_four_bars``         fixed1, input1, coupler1, output1, fixed2, input2,        phi, psi,
                              coupler2, output2, offset_deg                            beta, gamma
============================  ======================================================  ============

A mistake in a scene (an unknown key, with the nearest valid one suggested; a
missing dimension; a bad unit; malformed TOML) raises :class:`SceneError`, a
``ValueError`` whose one-line message names the file, the key and the value.

Examples
--------
>>> from numkin.scene import load_scene, run_scene
>>> scene = load_scene("quick-return")
>>> result = run_scene(scene)
>>> check = result.checks[0]
>>> round(check.values["r3"], 3), round(check.values["theta3_deg"], 3)
(87.178, 66.587)
"""

from __future__ import annotations

import copy
import difflib
import json
import math
import numbers
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np

from .errors import NumkinError
from .units import UnitError, angular_acceleration, angular_speed, convert_length

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = [
    "Scene",
    "SceneResult",
    "CheckResult",
    "SceneError",
    "LINKAGES",
    "SCENES_DIR",
    "load_scene",
    "list_scenes",
    "scene_path",
    "run_scene",
    "render_figures",
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


# ---------------------------------------------------------------- linkages
@dataclass(frozen=True)
class _LinkageSpec:
    """How a ready-made linkage's dimensions are written in a scene."""

    lengths: tuple = ()  # positive lengths
    signed: tuple = ()  # signed lengths (coordinates)
    pairs: tuple = ()  # (x, y) points
    angles: tuple = ()  # angles, written <name>_deg
    optional: Mapping = field(default_factory=dict)  # name -> default (function convention)
    branch: bool = False
    input: str = "theta2"
    unknowns: tuple = ()

    def keys(self) -> list[str]:
        return [*self.lengths, *self.signed, *self.pairs, *(f"{a}_deg" for a in self.angles)]


#: The ready-made linkages a scene may name, with their dimension keys.
LINKAGES: dict[str, _LinkageSpec] = {
    "four_bar": _LinkageSpec(
        lengths=("ground", "crank", "coupler", "rocker"), branch=True, unknowns=("theta3", "theta4"),
    ),
    "slider_crank": _LinkageSpec(
        lengths=("crank", "rod"), signed=("offset",), optional={"offset": 0.0}, input="theta",
        unknowns=("theta3", "x"),
    ),
    "quick_return": _LinkageSpec(lengths=("r1", "r2", "r6"), unknowns=("r3", "theta3", "r4", "r5")),
    "six_bar": _LinkageSpec(
        lengths=("crank", "coupler", "o4b", "bc", "o4c", "rod"), signed=("slider_y",), pairs=("o4",),
        unknowns=("theta3", "theta4", "theta5", "x"),
    ),
    "chained_four_bars": _LinkageSpec(
        lengths=("fixed1", "input1", "coupler1", "output1", "fixed2", "input2", "coupler2", "output2"),
        angles=("offset",), input="theta", unknowns=("phi", "psi", "beta", "gamma"),
    ),
}

# ------------------------------------------------------------------ schema
_TOP = ("scene", "mechanism", "input", "guess", "output", "compare", "check", "report", "animation", "stability")
_SECTIONS = {
    "scene": ("description", "title"),
    "mechanism": ("linkage", "unit", "dimensions", "branch", "input", "loops", "points", "links", "ground", "name"),
    "input": ("speed", "acceleration", "start_deg", "stop_deg", "step_deg"),
    "output": ("quantities", "unknowns", "points", "tables", "table_formats", "figures"),
    "compare": ("schemes", "second_schemes"),
    "report": ("quantity", "check_deg", "schemes", "grids", "points_per_turn", "repeat"),
    "animation": ("frames",),
    "stability": ("cases",),
}
_LOOP_KEYS = ("name", "unknowns", "vectors", "equations")


def _nearest(word: str, choices) -> str:
    match = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.5)
    return f" (did you mean '{match[0]}'?)" if match else ""


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


class _Reader:
    """Validation helpers that raise SceneError prefixed with the scene's source."""

    def __init__(self, source: str):
        self.source = source

    def fail(self, where: str, message: str):
        prefix = f"{self.source}: " if self.source else ""
        where = f"{where}: " if where else ""
        raise SceneError(_one_line(f"{prefix}{where}{message}"))

    def table(self, value, where: str) -> dict:
        if not isinstance(value, dict):
            self.fail(where, f"must be a table, got {value!r}")
        return value

    def keys(self, table: dict, allowed, where: str):
        for key in table:
            if key not in allowed:
                self.fail(where, f"unknown key '{key}'{_nearest(key, allowed)}; valid keys: {', '.join(allowed)}")

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
                    self.fail(where, f"unknown value '{v}'{_nearest(v, choices)}; valid values: {', '.join(choices)}")
        if len(set(value)) != len(value):
            self.fail(where, f"lists a value twice: {value!r}")
        return tuple(value)

    def length(self, value, where: str, unit: str, *, positive: bool = True) -> float:
        """A length in the working unit: a number, or a string '<number> <unit>'."""
        if isinstance(value, str):
            m = re.fullmatch(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([A-Za-z]+)\s*", value)
            if m is None:
                self.fail(where, f"cannot read {value!r} as a length; write a number (in {unit}) or e.g. '80 mm'")
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
        Ready-made linkage (a key of :data:`LINKAGES`), or None for loops.
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

    def inputs(self) -> np.ndarray:
        """The input sweep, rad."""
        return np.radians(self.start_deg + self.step_deg * np.arange(self.n_points))

    def fail(self, where: str, message: str):
        _Reader(self.source).fail(where, message)

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
        if self.kind != "mechanism":
            raise SceneError(f"{self.source}: a {self.kind} scene has no mechanism")
        mech = self._build_linkage() if self.linkage else self._build_loops()
        self._check_names(mech)
        return mech

    def _build_linkage(self):
        from . import linkages

        kwargs = dict(self.dimensions)
        if self.branch is not None:
            kwargs["branch"] = self.branch
        try:
            return getattr(linkages, self.linkage)(**kwargs, length_unit=self.unit)
        except NumkinError:
            raise
        except ValueError as error:
            self.fail("[mechanism]", str(error))

    def _build_loops(self):
        import sympy as sp

        from .loops import Loop
        from .mechanism import Mechanism

        spec = self.custom
        input_sym = sp.Symbol(spec["input"], real=True)
        names = {spec["input"]: input_sym}
        params = {}
        for key, value in self.dimensions.items():
            sym = sp.Symbol(key, real=True)
            names[key] = sym
            params[sym] = value
        loops = []
        for k, lp in enumerate(spec["loops"]):
            where = f"[[mechanism.loops]] {k + 1} ('{lp['name']}')"
            unknowns = []
            for u in lp["unknowns"]:
                if u in names:
                    self.fail(where, f"unknown '{u}' is already the input, a dimension or an earlier unknown")
                unknowns.append(sp.Symbol(u, real=True))
            local = dict(names)
            local.update({str(u): u for u in unknowns})
            try:
                if lp["vectors"] is not None:
                    vectors = [
                        (
                            _parse_expr(self, length, local, f"{where} vector {j + 1} length"),
                            _parse_expr(self, angle, local, f"{where} vector {j + 1} angle"),
                        )
                        for j, (length, angle) in enumerate(lp["vectors"])
                    ]
                    loop = Loop.from_vectors(vectors, unknowns, name=lp["name"])
                else:
                    eqs = [_parse_equation(self, e, local, f"{where} equation {j + 1}") for j, e in enumerate(lp["equations"])]
                    loop = Loop(eqs, unknowns, name=lp["name"])
            except SceneError:
                raise
            except ValueError as error:
                self.fail(where, str(error))
            loops.append(loop)
            names.update({str(u): u for u in unknowns})
        points = {
            p: tuple(_parse_expr(self, c, names, f"[mechanism.points] {p}") for c in xy) for p, xy in spec["points"].items()
        }
        try:
            return Mechanism(
                loops, input_sym, params, name=spec.get("name") or self.title or self.name, points=points,
                links=spec["links"], ground=spec["ground"], length_unit=self.unit,
            )
        except ValueError as error:
            self.fail("[mechanism]", str(error))

    def _check_names(self, mech) -> None:
        """Unknowns, points, guesses and check quantities named in the scene exist in ``mech``."""
        unknowns = list(mech.unknowns)
        for u in self.unknowns or ():
            if u not in unknowns:
                self.fail("[output] unknowns", f"'{u}' is not an unknown{_nearest(u, unknowns)}; unknowns: {', '.join(unknowns)}")
        for p in self.points:
            if p not in mech.points:
                points = ", ".join(mech.points) or "none"
                self.fail("[output] points", f"'{p}' is not a point{_nearest(p, mech.points)}; points: {points}")
        if self.guess is not None:
            self.guess_values(mech)
        valid = self.quantity_names(mech, all_unknowns=True)
        for k, check in enumerate(self.checks):
            for key in check["expected"]:
                if key not in valid:
                    m = re.fullmatch(r"(?:x|y|vx|vy|ax|ay)_(.+)", key)
                    if m and m[1] in mech.points and m[1] not in self.points:
                        self.fail(f"[[check]] {k + 1}", f"'{key}' needs '{m[1]}' in [output] points")
                    needs = _quantity_needs(key, mech)
                    if needs and not self.wants(needs):
                        self.fail(f"[[check]] {k + 1}", f"'{key}' needs \"{needs}\" in [output] quantities")
                    self.fail(
                        f"[[check]] {k + 1}",
                        f"unknown key '{key}'{_nearest(key, valid + ['at_deg', 'tolerance'])}; "
                        f"quantities: {', '.join(valid)}",
                    )
        quantity = self.report.get("quantity")
        if quantity is not None and quantity not in unknowns:
            self.fail("[report] quantity", f"'{quantity}' is not an unknown{_nearest(quantity, unknowns)}; unknowns: {', '.join(unknowns)}")

    def guess_values(self, mech) -> dict | None:
        """The ``[guess]`` table as ``{unknown: value}`` (rad, working unit), or None."""
        if self.guess is None:
            return None
        out = {}
        expect = {(f"{u}_deg" if u in mech.angles else u): u for u in mech.unknowns}
        for key, value in self.guess.items():
            if key not in expect:
                hint = ""
                if key in mech.angles:
                    hint = f" ('{key}' is an angle: write {key}_deg)"
                elif key.endswith("_deg") and key[:-4] in mech.unknowns:
                    hint = f" ('{key[:-4]}' is a length in {self.unit}: write {key[:-4]})"
                self.fail(
                    "[guess]", f"unknown key '{key}'{hint or _nearest(key, expect)}; valid keys: {', '.join(expect)}"
                )
            u = expect[key]
            where = f"[guess] {key}"
            if u in mech.angles:
                out[u] = math.radians(_Reader(self.source).number(value, where))
            else:
                out[u] = _Reader(self.source).length(value, where, self.unit, positive=False)
        missing = [k for k, u in expect.items() if u not in out]
        if missing:
            self.fail("[guess]", f"lacks {', '.join(missing)} (give every unknown, or leave out [guess] for the linkage's default)")
        return out

    def quantity_names(self, mech, *, all_unknowns: bool = False) -> list[str]:
        """Names of the quantities the scene computes (see the module docstring)."""
        unknowns = mech.unknowns if all_unknowns or self.unknowns is None else self.unknowns
        names = []
        for u in unknowns:
            angle = u in mech.angles
            if self.wants("position"):
                names.append(f"{u}_deg" if angle else u)
            if self.wants("velocity"):
                names.append(f"omega_{u}" if angle else f"v_{u}")
            if self.wants("acceleration"):
                names.append(f"alpha_{u}" if angle else f"a_{u}")
        for p in self.points:
            if self.wants("position"):
                names += [f"x_{p}", f"y_{p}"]
            if self.wants("velocity"):
                names += [f"vx_{p}", f"vy_{p}"]
            if self.wants("acceleration"):
                names += [f"ax_{p}", f"ay_{p}"]
        return names


def _quantity_needs(key: str, mech) -> str | None:
    """Which quantity ("position", ...) a quantity name belongs to, if it names a real one."""
    if key.endswith("_deg") and key[:-4] in mech.angles:
        return "position"
    if key in mech.unknowns:
        return "position"
    m = re.fullmatch(r"(omega|alpha|v|a)_(.+)", key)
    if m and m[2] in mech.unknowns:
        return "velocity" if m[1] in ("omega", "v") else "acceleration"
    m = re.fullmatch(r"(x|y|vx|vy|ax|ay)_(.+)", key)
    if m and m[2] in mech.points:
        return {"x": "position", "y": "position", "vx": "velocity", "vy": "velocity"}.get(m[1], "acceleration")
    return None


# -------------------------------------------------------------- expressions
_EXPR_CHARS = re.compile(r"[A-Za-z0-9_+\-*/^().,\s]*")
_FUNCTIONS = ("sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "abs")


def _parse_expr(scene: Scene, text, names: Mapping, where: str):
    import sympy as sp
    from sympy.parsing.sympy_parser import convert_xor, parse_expr, standard_transformations

    if isinstance(text, bool):
        scene.fail(where, f"must be an expression string or a number, got {text!r}")
    if isinstance(text, numbers.Real):
        return sp.Float(text) if isinstance(text, float) else sp.Integer(text)
    if not isinstance(text, str) or not text.strip():
        scene.fail(where, f"must be an expression string or a number, got {text!r}")
    if "__" in text or not _EXPR_CHARS.fullmatch(text):
        scene.fail(
            where,
            f"{text!r}: an expression may contain names, numbers, + - * / ^ ( ) and the functions {', '.join(_FUNCTIONS)}",
        )
    funcs = {
        "sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "asin": sp.asin, "acos": sp.acos, "atan": sp.atan,
        "atan2": sp.atan2, "sqrt": sp.sqrt, "exp": sp.exp, "abs": sp.Abs, "pi": sp.pi,
    }
    local = {**funcs, **names}
    glob = {"Integer": sp.Integer, "Float": sp.Float, "Rational": sp.Rational, "Symbol": sp.Symbol, "Function": sp.Function}
    try:
        expr = parse_expr(text, local_dict=local, global_dict=glob, transformations=standard_transformations + (convert_xor,))
    except Exception as error:  # tokenizer and syntax errors of all kinds
        scene.fail(where, f"cannot read {text!r} as an expression ({type(error).__name__})")
    if not isinstance(expr, sp.Basic):
        scene.fail(where, f"{text!r} is not an expression")
    undefined = sorted({type(f).__name__ for f in expr.atoms(sp.core.function.AppliedUndef)})
    if undefined:
        scene.fail(where, f"{text!r} calls unknown function '{undefined[0]}'; functions: {', '.join(_FUNCTIONS)}")
    for sym in expr.free_symbols:
        if sym.name not in names:
            scene.fail(
                where,
                f"{text!r} uses '{sym.name}', which is not the input, a dimension or an unknown"
                f"{_nearest(sym.name, names)}; known names: {', '.join(names)}",
            )
    return expr


def _parse_equation(scene: Scene, text, names: Mapping, where: str):
    if isinstance(text, str) and text.count("=") == 1:
        lhs, rhs = text.split("=")
        return _parse_expr(scene, lhs, names, where) - _parse_expr(scene, rhs, names, where)
    return _parse_expr(scene, text, names, where)


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
        if not path.is_file():
            raise SceneError(f"scene file {text!r} not found")
        return path
    names = list(list_scenes())
    raise SceneError(
        f"unknown scene '{text}'{_nearest(text, names)}; built-in scenes: {', '.join(names)} "
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
        raise SceneError(_one_line(f"{source}: malformed TOML: {error}")) from None
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
    r = _Reader(source)
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
    _read_mechanism(r, scene, r.table(data["mechanism"], "[mechanism]"))
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
                    r.fail("[report] schemes", f"unknown scheme '{name}'{_nearest(name, SCHEMES)}; schemes: {', '.join(SCHEMES)}")
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
        if not scene.speed:
            r.fail("[report]", "needs [input] speed (the error tables are of velocities and accelerations)")
        scene.report = report
    if "animation" in data:
        frames = data["animation"].get("frames", 72)
        if isinstance(frames, bool) or not isinstance(frames, int) or frames < 2:
            r.fail("[animation] frames", f"must be an integer >= 2, got {frames!r}")
        scene.animation = {"frames": frames}
    return scene


def _is_int(value, least: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= least


def _read_mechanism(r: _Reader, scene: Scene, mech: dict) -> None:
    scene.unit = r.string(mech.get("unit", "mm"), "[mechanism] unit")
    try:
        convert_length(1.0, scene.unit, "mm")
    except UnitError as error:
        r.fail("[mechanism] unit", str(error))
    dims = r.table(mech.get("dimensions", {}), "[mechanism.dimensions]")
    if "linkage" in mech:
        linkage = r.string(mech["linkage"], "[mechanism] linkage")
        if linkage not in LINKAGES:
            r.fail(
                "[mechanism] linkage",
                f"unknown linkage '{linkage}'{_nearest(linkage, LINKAGES)}; ready-made linkages: {', '.join(LINKAGES)}",
            )
        for key in ("input", "loops", "points", "links", "ground", "name"):
            if key in mech:
                r.fail(f"[mechanism] {key}", f"applies to loops, not to a ready-made linkage ('{linkage}')")
        spec = LINKAGES[linkage]
        scene.linkage = linkage
        valid = spec.keys()
        r.keys(dims, valid, f"[mechanism.dimensions] of {linkage}")
        out = {}
        for key in valid:
            where = f"[mechanism.dimensions] {key}"
            if key not in dims:
                base = key[:-4] if key.endswith("_deg") else key
                if base in spec.optional:
                    continue
                r.fail("[mechanism.dimensions]", f"missing dimension '{key}' of {linkage}; it needs {', '.join(valid)}")
            value = dims[key]
            if key in spec.lengths:
                out[key] = r.length(value, where, scene.unit)
            elif key in spec.signed:
                out[key] = r.length(value, where, scene.unit, positive=False)
            elif key in spec.pairs:
                if not isinstance(value, list) or len(value) != 2:
                    r.fail(where, f"must be a pair [x, y], got {value!r}")
                out[key] = tuple(r.length(v, f"{where}[{i}]", scene.unit, positive=False) for i, v in enumerate(value))
            else:
                out[key[:-4]] = math.radians(r.number(value, where))
        scene.dimensions = out
        if "branch" in mech:
            if not spec.branch:
                r.fail("[mechanism] branch", f"applies to four_bar only; pick the branch of {linkage} with [guess]")
            branch = r.string(mech["branch"], "[mechanism] branch")
            if branch not in ("open", "crossed"):
                r.fail("[mechanism] branch", f"must be 'open' or 'crossed', got {branch!r}")
            scene.branch = branch
        return
    if "loops" not in mech:
        r.fail("[mechanism]", "needs either `linkage` (a ready-made one) or [[mechanism.loops]]")
    if "branch" in mech:
        r.fail("[mechanism] branch", "applies to the ready-made four_bar only; pick the branch of loops with [guess]")
    if "input" not in mech:
        r.fail("[mechanism]", "missing key 'input' (the input symbol, e.g. 'theta2')")
    input_name = r.string(mech["input"], "[mechanism] input")
    _identifier(r, input_name, "[mechanism] input")
    params = {}
    for key, value in dims.items():
        where = f"[mechanism.dimensions] {key}"
        if key.endswith("_deg"):
            name = key[:-4]
            _identifier(r, name, where)
            params[name] = math.radians(r.number(value, where))
        else:
            _identifier(r, key, where)
            params[key] = r.length(value, where, scene.unit, positive=False)
        if (key[:-4] if key.endswith("_deg") else key) == input_name:
            r.fail(where, f"'{input_name}' is the input symbol; a dimension needs another name")
    loops_raw = mech["loops"]
    if not isinstance(loops_raw, list) or not loops_raw:
        r.fail("[[mechanism.loops]]", "must be a non-empty array of tables")
    loops = []
    for k, lp in enumerate(loops_raw):
        where = f"[[mechanism.loops]] {k + 1}"
        r.keys(r.table(lp, where), _LOOP_KEYS, where)
        if not lp.get("unknowns"):
            r.fail(where, "missing key 'unknowns' (the names this loop solves for)")
        unknowns = r.strings(lp["unknowns"], f"{where} unknowns")
        for u in unknowns:
            _identifier(r, u, f"{where} unknowns")
        if ("vectors" in lp) == ("equations" in lp):
            r.fail(where, "give either `vectors` or `equations`")
        vectors = lp.get("vectors")
        if vectors is not None:
            if not isinstance(vectors, list) or not all(isinstance(v, list) and len(v) == 2 for v in vectors):
                r.fail(f"{where} vectors", f"must be a list of [length, angle] pairs, got {vectors!r}")
        equations = lp.get("equations")
        if equations is not None and (not isinstance(equations, list) or not equations):
            r.fail(f"{where} equations", f"must be a list of expressions, got {equations!r}")
        name = r.string(lp["name"], f"{where} name") if "name" in lp else f"loop {k + 1}"
        loops.append({"name": name, "unknowns": unknowns, "vectors": vectors, "equations": equations})
    points = r.table(mech.get("points", {}), "[mechanism.points]")
    for p, xy in points.items():
        if not isinstance(xy, list) or len(xy) != 2:
            r.fail(f"[mechanism.points] {p}", f"must be a pair [x, y] of expressions, got {xy!r}")
    links = mech.get("links", [])
    if not isinstance(links, list) or not all(isinstance(link, list) and all(isinstance(q, str) for q in link) for link in links):
        r.fail("[mechanism] links", f"must be a list of lists of point names, got {links!r}")
    ground = r.strings(mech.get("ground", []), "[mechanism] ground")
    for p in [q for link in links for q in link] + list(ground):
        if p not in points:
            r.fail("[mechanism] links/ground", f"point '{p}' is not in [mechanism.points]{_nearest(p, points)}")
    scene.dimensions = params
    scene.custom = {
        "input": input_name, "loops": loops, "points": points, "links": links, "ground": ground,
        "name": r.string(mech["name"], "[mechanism] name") if "name" in mech else None,
    }


def _identifier(r: _Reader, name: str, where: str) -> None:
    if not name.isidentifier() or name.startswith("_") or name in _FUNCTIONS or name == "pi":
        r.fail(where, f"'{name}' is not a usable symbol name (an identifier such as 'theta3', not a function name)")


def _read_input(r: _Reader, scene: Scene, inp: dict) -> None:
    if "speed" in inp:
        scene.speed_text = str(inp["speed"])
        try:
            scene.speed = angular_speed(inp["speed"])
        except (UnitError, TypeError) as error:
            r.fail("[input] speed", str(error))
        if scene.speed == 0:
            r.fail("[input] speed", f"must not be zero, got {inp['speed']!r}")
    elif scene.differentiates:
        r.fail("[input]", "missing key 'speed' (e.g. \"450 rad/min\"), needed for velocity and acceleration")
    if "acceleration" in inp:
        scene.acceleration_text = str(inp["acceleration"])
        try:
            scene.acceleration = angular_acceleration(inp["acceleration"])
        except (UnitError, TypeError) as error:
            r.fail("[input] acceleration", str(error))
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
    if round(count) > 10_000_000:
        r.fail("[input] step_deg", f"{scene.step_deg:g} gives more than ten million points")


def _read_output(r: _Reader, scene: Scene, out: dict) -> None:
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


def _read_figures(r: _Reader, out: dict) -> tuple:
    names = r.strings(out.get("figures", []), "[output] figures")
    if names:
        from .figures import parse_spec  # does not import matplotlib

        for name in names:
            try:
                parse_spec(name)
            except ValueError as error:
                r.fail("[output] figures", str(error))
    return names


def _read_compare(r: _Reader, scene: Scene, cmp: dict) -> None:
    from .derivatives import SCHEMES, get_scheme

    for key, order, quantity in (("schemes", 1, "velocity"), ("second_schemes", 2, "acceleration")):
        if key not in cmp:
            continue
        names = []
        for s in r.strings(cmp[key], f"[compare] {key}"):
            try:
                scheme = get_scheme(s)
            except ValueError:
                r.fail(f"[compare] {key}", f"unknown scheme '{s}'{_nearest(s, SCHEMES)}; schemes: {', '.join(SCHEMES)}")
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


def _read_checks(r: _Reader, scene: Scene, checks) -> None:
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
        _in_range(r, scene, at, f"{where} at_deg")
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


def _in_range(r: _Reader, scene: Scene, at: float, where: str) -> None:
    if not scene.start_deg - 1e-9 <= at <= scene.stop_deg + 1e-9:
        r.fail(where, f"{at:g}° is outside the sweep {scene.start_deg:g}..{scene.stop_deg:g}°")


# --------------------------------------------------------------------- results
@dataclass
class CheckResult:
    """Every quantity of a scene at one input angle.

    Attributes
    ----------
    at_deg : float
        Input angle (degrees).
    values : dict
        Quantity name -> value: the Newton solution for positions, the
        analytic solution for velocities and accelerations (units in ``units``).
    units : dict
        Quantity name -> unit label.
    schemes : dict
        Scheme name -> {quantity name -> value} for the compared schemes (only
        at grid points).
    expected : dict
        Expected values from the scene file.
    ok : dict
        Quantity name -> whether the value agrees with the expected one.
    on_grid : bool
        True if the angle is a point of the sweep.
    """

    at_deg: float
    values: dict
    units: dict
    schemes: dict = field(default_factory=dict)
    expected: dict = field(default_factory=dict)
    tolerance: dict = field(default_factory=dict)
    ok: dict = field(default_factory=dict)
    on_grid: bool = True

    @property
    def passed(self) -> bool:
        """True if every expected value agrees."""
        return all(self.ok.values())

    def to_dict(self) -> dict:
        return {
            "at_deg": self.at_deg, "on_grid": self.on_grid, "values": self.values, "units": self.units,
            "schemes": self.schemes, "expected": self.expected, "tolerance": self.tolerance, "ok": self.ok,
            "passed": self.passed,
        }


@dataclass
class SceneResult:
    """What :func:`run_scene` computed: only what the scene asked for.

    Attributes
    ----------
    scene : Scene
    mechanism : Mechanism or None
    sweep : Sweep or None
        Positions over the input sweep.
    omega, alpha : float or None
        Input speed [rad/s] and acceleration [rad/s^2].
    kinematics : pandas.DataFrame or None
        ``numkin.analytic.kinematics`` (velocity/acceleration scenes only).
    point_kinematics : pandas.DataFrame or None
        ``numkin.analytic.point_kinematics`` of the wanted points.
    comparisons : dict
        Quantity name (``omega_beta``, ``alpha_beta``, ``a_x``) -> ``numkin.compare.Comparison``.
    checks : list of CheckResult
        The scene's check points.
    at : CheckResult or None
        Every quantity at the angle asked for by ``run_scene(..., at=)``.
    tables : dict
        Table name -> DataFrame (the tables the scene asked for).
    suite : pandas.DataFrame or None
        The stability suite's table (stability scenes).
    report : dict
        Error-analysis tables of :mod:`numkin.report` computed for figures
        that are drawn from them (``convergence``, ``work_precision``,
        ``roundoff``, ``newton_<jacobian>``).
    written : list of Path
        Files written (tables, figures).
    """

    scene: Scene
    mechanism: Any = None
    sweep: Any = None
    omega: float | None = None
    alpha: float | None = None
    kinematics: Any = None
    point_kinematics: Any = None
    comparisons: dict = field(default_factory=dict)
    checks: list = field(default_factory=list)
    at: CheckResult | None = None
    tables: dict = field(default_factory=dict)
    suite: Any = None
    report: dict = field(default_factory=dict)
    written: list = field(default_factory=list)

    @property
    def passed(self) -> bool:
        """True if every check point agrees (and, for the stability suite, every case went as expected)."""
        if self.suite is not None and "as expected" in self.suite:
            return bool(self.suite["as expected"].all())
        return all(c.passed for c in self.checks)

    def value(self, name: str, at_deg: float) -> float:
        """One quantity (see the module docstring for names) at an input angle (degrees)."""
        return _evaluate(self, at_deg).values[name]

    def to_dict(self) -> dict:
        """A JSON-ready summary: input, check points, per-scheme errors, files written."""
        s = self.scene
        out = {"scene": s.name, "description": s.description, "kind": s.kind}
        if s.kind == "stability":
            out["stability"] = json.loads(self.suite.to_json(orient="records")) if self.suite is not None else None
            out["passed"] = self.passed
        else:
            mech = self.mechanism
            out["mechanism"] = mech.name
            out["unit"] = s.unit
            out["input"] = {
                "name": str(mech.input_symbol), "start_deg": s.start_deg, "stop_deg": s.stop_deg,
                "step_deg": s.step_deg, "points": s.n_points,
                "speed_rad_s": self.omega, "acceleration_rad_s2": self.alpha if self.omega is not None else None,
            }
            sw = self.sweep
            out["newton"] = {
                "max_iterations": int(np.max(sw.iterations)), "max_residual": float(np.max(sw.residual)),
                "max_cond": float(np.max(sw.cond)), "events": [e.message for e in sw.events],
            }
            out["checks"] = [c.to_dict() for c in self.checks]
            if self.at is not None:
                out["at"] = self.at.to_dict()
            out["errors"] = _error_summary(self)
            out["passed"] = self.passed
        out["written"] = [str(p) for p in self.written]
        return _jsonable(out)


def _jsonable(obj):
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


# --------------------------------------------------------------------- running
def run_scene(
    scene,
    out=None,
    at: float | None = None,
    *,
    figures: bool = True,
    progress: Callable[[str], None] | None = None,
) -> SceneResult:
    """Compute what a scene asks for, and write its tables and figures to ``out``.

    Parameters
    ----------
    scene : Scene or str or path
        A scene, a built-in name or a .toml path.
    out : path, optional
        Folder for the tables (``<scene>-<table>.<format>``) and the figures
        the scene asks for; nothing is written without it.
    at : float, optional
        An input angle (degrees): ``result.at`` then holds every quantity there.
    figures : bool
        Render the scene's figures when ``out`` is given (default True).
    progress : callable, optional
        Called with the name of each stage as it starts (for progress bars).

    Returns
    -------
    SceneResult

    Examples
    --------
    >>> result = run_scene("quick-return", at=30)
    >>> round(result.at.values["r4"], 3)
    130.767
    """
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    step = progress or (lambda stage: None)
    result = SceneResult(scene=scene)
    if scene.kind == "stability":
        if at is not None:
            scene.fail("--at", "applies to a scene with a mechanism, not to the stability suite")
        step("stability suite")
        from . import stability

        cases = list(scene.stability_cases) if scene.stability_cases is not None else None
        if cases is not None:
            valid = list(stability.CASES)
            for c in cases:
                if c not in valid:
                    scene.fail("[stability] cases", f"unknown case '{c}'{_nearest(c, valid)}; cases: {', '.join(valid)}")
        result.suite = stability.run_suite(cases)
        result.tables["stability"] = result.suite
    else:
        if at is not None:
            _in_range(_Reader(scene.source), scene, float(at), "--at")
        step("mechanism")
        mech = scene.build_mechanism()
        result.mechanism = mech
        step("positions")
        result.sweep = mech.sweep(scene.inputs(), guess=scene.guess_values(mech))
        if scene.differentiates:
            result.omega, result.alpha = scene.speed, scene.acceleration
            step("velocity and acceleration")
            _differentiate(result)
        step("check points")
        result.checks = [_evaluate(result, c["at_deg"], c) for c in scene.checks]
        if at is not None:
            result.at = _evaluate(result, float(at), None, every=True)
        result.tables = _tables(result)
    if out is not None:
        out = Path(out)
        if result.tables and scene.tables:
            step("tables")
            result.written += _write_tables(scene, result.tables, out)
        if figures and scene.figures:
            result.written += render_figures(result, out, progress=step)
    return result


#: Figures drawn from the error-analysis tables of numkin.report, and the table each needs.
_REPORT_FIGURES = {
    "convergence": "convergence", "work-precision": "work_precision", "roundoff": "roundoff", "newton": "newton",
}


def render_figures(result: SceneResult, out_dir, *, formats=("png", "svg"), progress=None) -> list:
    """Draw and save the figures a scene asks for (:func:`numkin.figures.render`).

    The error-analysis tables that some figures are drawn from (convergence,
    work-precision, roundoff, Newton) are computed here, only those asked for,
    with the scene's ``[report]`` settings, and kept in ``result.report``.
    """
    from . import figures as fig

    step = progress or (lambda stage: None)
    scene = result.scene
    kinds = {fig.parse_spec(name)[0] for name in scene.figures}
    wanted = [kind for kind in _REPORT_FIGURES if kind in kinds and _REPORT_FIGURES[kind] not in result.report]
    if wanted and result.mechanism is not None and scene.speed:
        from . import report

        options = scene.report_options(result.mechanism)
        span = math.radians(scene.stop_deg - scene.start_deg)
        common = {k: options[k] for k in ("quantity", "guess")}
        sweep_opts = {"start": options["start"], "span": span, **{k: options[k] for k in ("grids", "schemes") if k in options}}
        for kind in wanted:
            step(f"{kind} table")
            if kind == "convergence":
                table = report.convergence_table(
                    result.mechanism, omega=scene.speed, check_angle=options["check_angle"], **common, **sweep_opts,
                )
            elif kind == "work-precision":
                extra = {"repeat": options["repeat"]} if "repeat" in options else {}
                table = report.work_precision_table(result.mechanism, omega=scene.speed, **common, **sweep_opts, **extra)
            elif kind == "roundoff":
                table = report.roundoff_table(result.mechanism, check_angle=options["check_angle"], **common)
            else:
                for jacobian in ("symbolic", "forward", "central"):
                    result.report[f"newton_{jacobian}"] = report.newton_table(
                        result.mechanism, check_angle=options["check_angle"], jacobian=jacobian, guess=options["guess"],
                    )
                continue
            result.report[_REPORT_FIGURES[kind]] = table
    step("figures")
    view = copy.copy(result)
    view.tables = {**result.tables, **result.report}
    return list(fig.render(view, out_dir=Path(out_dir), formats=formats))


def _differentiate(result: SceneResult) -> None:
    """Analytic velocity/acceleration and the scheme comparisons (never for position-only scenes)."""
    from . import analytic

    scene, sweep = result.scene, result.sweep
    result.kinematics = analytic.kinematics(sweep, result.omega, result.alpha)
    if scene.points:
        result.point_kinematics = analytic.point_kinematics(sweep, result.omega, result.alpha, points=list(scene.points))
    if scene.schemes or scene.second_schemes:
        from .compare import compare

        mech = result.mechanism
        for u in scene.unknowns or mech.unknowns:
            angle = u in mech.angles
            if scene.schemes:
                name = f"omega_{u}" if angle else f"v_{u}"
                result.comparisons[name] = compare(sweep, result.omega, name, schemes=scene.schemes, alpha=result.alpha)
            if scene.second_schemes:
                name = f"alpha_{u}" if angle else f"a_{u}"
                result.comparisons[name] = compare(
                    sweep, result.omega, name, schemes=scene.second_schemes, alpha=result.alpha,
                )


def _units(mech, unit: str) -> Callable[[str], str]:
    def unit_of(name: str) -> str:
        if name.endswith("_deg"):
            return "deg"
        if name.startswith("omega_"):
            return "rad/s"
        if name.startswith("alpha_"):
            return "rad/s^2"
        if re.match(r"(v|vx|vy)_", name):
            return f"{unit}/s"
        if re.match(r"(a|ax|ay)_", name):
            return f"{unit}/s^2"
        return unit

    return unit_of


def _evaluate(result: SceneResult, at_deg: float, check: dict | None = None, *, every: bool = False) -> CheckResult:
    """The quantities at one input angle; positions from Newton, the rest analytic."""
    scene, mech, sweep = result.scene, result.mechanism, result.sweep
    at = math.radians(at_deg)
    i = sweep.index(at)
    on_grid = bool(abs(sweep.inputs[i] - at) <= 1e-9 * max(1.0, abs(at)))
    if on_grid:
        sub, j, kin, pk = sweep, i, result.kinematics, result.point_kinematics
    else:  # solve there by continuation from the nearest grid point
        sub = mech.sweep(np.array([sweep.inputs[i], at]), guess=sweep.values[:, i])
        j, kin, pk = 1, None, None
        if result.kinematics is not None:
            from . import analytic

            kin = analytic.kinematics(sub, result.omega, result.alpha)
            if scene.points:
                pk = analytic.point_kinematics(sub, result.omega, result.alpha, points=list(scene.points))
    unknowns = mech.unknowns if every or scene.unknowns is None else scene.unknowns
    values = {}
    for u in unknowns:
        angle = u in mech.angles
        values[f"{u}_deg" if angle else u] = math.degrees(sub[u][j]) if angle else float(sub[u][j])
        if kin is not None:
            if scene.wants("velocity"):
                key = f"omega_{u}" if angle else f"v_{u}"
                values[key] = float(kin[key].iloc[j])
            if scene.wants("acceleration"):
                key = f"alpha_{u}" if angle else f"a_{u}"
                values[key] = float(kin[key].iloc[j])
    if scene.points:
        xy = mech.point_coordinates(sub.values[:, j : j + 1], sub.inputs[j : j + 1])
        for p in scene.points:
            values[f"x_{p}"], values[f"y_{p}"] = float(xy[p][0, 0]), float(xy[p][1, 0])
            if pk is not None:
                for c in ("vx", "vy") if scene.wants("velocity") else ():
                    values[f"{c}_{p}"] = float(pk[f"{c}_{p}"].iloc[j])
                for c in ("ax", "ay") if scene.wants("acceleration") else ():
                    values[f"{c}_{p}"] = float(pk[f"{c}_{p}"].iloc[j])
    if check is not None:  # also the checked quantities of unknowns not reported
        for key in check["expected"]:
            if key not in values:
                values[key] = _evaluate(result, at_deg, None, every=True).values[key]
    unit_of = _units(mech, scene.unit)
    res = CheckResult(at_deg=at_deg, values=values, units={k: unit_of(k) for k in values}, on_grid=on_grid)
    if on_grid:
        for name, comparison in result.comparisons.items():
            if name not in values:
                continue
            for scheme, value in _scheme_values(comparison, i).items():
                res.schemes.setdefault(scheme, {})[name] = value
    if check is not None:
        for key, expected in check["expected"].items():
            tol = check["tolerance"] if check["tolerance"] is not None else _written_tolerance(expected)
            diff = values[key] - expected
            if key.endswith("_deg"):
                diff = math.remainder(diff, 360.0)
            res.expected[key] = expected
            res.tolerance[key] = tol
            res.ok[key] = bool(abs(diff) <= tol)
    return res


def _written_tolerance(value: float) -> float:
    """Half a unit of the last decimal written: 10.633 -> 5e-4 (plus a rounding allowance)."""
    text = repr(float(value))
    if "e" in text or "E" in text:
        mantissa, exponent = text.lower().split("e")
        decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
        if mantissa.endswith(".0"):
            decimals = 0
        return 0.5 * 10.0 ** (int(exponent) - decimals) * (1 + 1e-9)
    decimals = len(text.split(".")[1]) if not text.endswith(".0") else 0
    return 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)


def _scheme_values(comparison, i: int) -> dict:
    """Each scheme's value at grid index ``i`` from a Comparison's table."""
    table = comparison.table
    return {str(s): float(table[f"{s} [{comparison.unit}]"].iloc[i]) for s in comparison.summary.index}


def _error_summary(result: SceneResult) -> dict:
    """{quantity: {scheme: {max_abs, rms_abs, max_rel}}} from the comparisons."""
    out = {}
    for name, comparison in result.comparisons.items():
        rows = {"unit": comparison.unit}
        for scheme, row in comparison.summary.iterrows():
            record = {}
            for column, value in row.items():
                key = re.sub(r"\s*\[[^\]]*\]$", "", str(column)).replace(" ", "_")
                if key.startswith("max_at_"):
                    key = "max_at_deg"
                record[key] = value if isinstance(value, str) else float(value)
            rows[str(scheme)] = record
        out[name] = rows
    return out


def _tables(result: SceneResult) -> dict:
    """The DataFrames the scene asks for (only those)."""
    scene, mech, sweep = result.scene, result.mechanism, result.sweep
    import pandas as pd

    wanted = set(scene.tables)
    tables = {}
    unknowns = scene.unknowns or mech.unknowns
    input_col = f"{mech.input_symbol} [deg]"
    unit_of = _units(mech, scene.unit)
    if "positions" in wanted:
        frame = sweep.to_frame()
        if scene.points:
            xy = sweep.points()
            for p in scene.points:
                frame[f"x_{p} [{scene.unit}]"] = xy[p][0]
                frame[f"y_{p} [{scene.unit}]"] = xy[p][1]
        tables["positions"] = frame
    if "kinematics" in wanted and result.kinematics is not None:
        cols = {input_col: np.degrees(sweep.inputs)}
        for u in unknowns:
            angle = u in mech.angles
            keys = (("velocity", f"omega_{u}" if angle else f"v_{u}"), ("acceleration", f"alpha_{u}" if angle else f"a_{u}"))
            for q, key in keys:
                if scene.wants(q):
                    cols[f"{key} [{unit_of(key)}]"] = result.kinematics[key].to_numpy()
        tables["kinematics"] = pd.DataFrame(cols)
    if "points" in wanted and scene.points:
        cols = {input_col: np.degrees(sweep.inputs)}
        xy = sweep.points()
        for p in scene.points:
            cols[f"x_{p} [{scene.unit}]"] = xy[p][0]
            cols[f"y_{p} [{scene.unit}]"] = xy[p][1]
            if result.point_kinematics is not None:
                for c in ("vx", "vy", "ax", "ay"):
                    key = f"{c}_{p}"
                    if key in result.point_kinematics and scene.wants("velocity" if c.startswith("v") else "acceleration"):
                        cols[f"{key} [{unit_of(key)}]"] = result.point_kinematics[key].to_numpy()
        tables["points"] = pd.DataFrame(cols)
    if "comparison" in wanted:
        for name, comparison in result.comparisons.items():
            tables[f"comparison-{name}"] = comparison.table
    if "summary" in wanted and result.comparisons:
        frames = []
        for name, comparison in result.comparisons.items():
            s = comparison.summary.reset_index()
            s.columns = [c.replace(f" [{comparison.unit}]", "") for c in s.columns]
            s.insert(0, "unit", comparison.unit)
            s.insert(0, "quantity", name)
            frames.append(s)
        tables["summary"] = pd.concat(frames, ignore_index=True)
    if "checks" in wanted and result.checks:
        rows = []
        for c in result.checks:
            for key, value in c.values.items():
                row = {input_col: c.at_deg, "quantity": key, "unit": c.units[key], "value": value}
                for scheme, vals in c.schemes.items():
                    row[scheme] = vals.get(key, np.nan)
                row["expected"] = c.expected.get(key, np.nan)
                row["ok"] = c.ok.get(key, "")
                rows.append(row)
        tables["checks"] = pd.DataFrame(rows)
    return tables


def _write_tables(scene: Scene, tables: dict, out: Path) -> list[Path]:
    out.mkdir(parents=True, exist_ok=True)
    written = []
    if "csv" in scene.table_formats:
        for name, frame in tables.items():
            path = out / f"{scene.name}-{name}.csv"
            frame.to_csv(path, index=False)
            written.append(path)
    others = tuple(f for f in scene.table_formats if f != "csv")
    if others:
        from .report import write_tables

        written += list(write_tables({f"{scene.name}-{k}": v for k, v in tables.items()}, out, formats=others))
    return written

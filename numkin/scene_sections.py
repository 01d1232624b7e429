"""The sections of a scene file after ``[mechanism]``, each read and checked into a :class:`~numkin.schema.Scene`.

``[input]`` (sweep and input speed), ``[output]`` (quantities, tables,
figures), ``[compare]`` (schemes), ``[[check]]`` (check points) and
``[animation]``; every mistake is reported through the
:class:`~numkin.schema.SceneReader` with one line naming the key. The file
format is described in :mod:`numkin.scene`; :func:`numkin.schema.load_scene`
calls these.
"""

from __future__ import annotations

import difflib
import sys
from typing import TYPE_CHECKING

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

if TYPE_CHECKING:  # pragma: no cover - for annotations only
    from .schema import Scene, SceneReader

__all__ = [
    "QUANTITIES", "TABLES", "TABLE_FORMATS", "ANIMATION_TURNS", "ANIMATION_ARROWS", "ANIMATION_DPI",
    "ANIMATION_WIDTH_IN", "nearest", "is_int", "input_rate", "in_range", "read_input", "read_output",
    "read_figures", "read_compare", "read_checks", "checks_as_written", "read_animation",
]

#: What a scene may ask for (``[output] quantities``), the tables it may write and their formats.
QUANTITIES = ("position", "velocity", "acceleration")
TABLES = ("positions", "kinematics", "points", "comparison", "summary", "checks", "stability")
TABLE_FORMATS = ("csv", "md", "tex")


def nearest(word: str, choices) -> str:
    """The closest of `choices` to a mistyped `word`, as a message's hint (empty if none is close).

    Examples
    --------
    >>> nearest("homwork", ["homework", "six-bar"])
    " (did you mean 'homework'?)"
    """
    match = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.5)
    return f" (did you mean '{match[0]}'?)" if match else ""


#: Choices of ``[animation] turn`` and ``arrows`` (as ``numkin animate`` takes them).
ANIMATION_TURNS = ("full", "sweep")
ANIMATION_ARROWS = ("velocity", "acceleration")
#: Ranges of ``[animation]`` (and ``numkin animate``) dpi and width [in].
ANIMATION_DPI = (10, 600)
ANIMATION_WIDTH_IN = (1.0, 40.0)


def read_animation(r: SceneReader, scene, table: dict) -> dict:
    """The ``[animation]`` section: defaults of ``numkin animate``'s options (only the keys given, and frames)."""
    out = {}
    frames = table.get("frames", 72)
    if not is_int(frames, 2):
        r.fail("[animation] frames", f"must be an integer >= 2, got {frames!r}")
    out["frames"] = frames
    if "fps" in table:
        fps = r.number(table["fps"], "[animation] fps")
        if not 0 < fps <= 100:
            r.fail("[animation] fps", f"must be a number of frames per second in (0, 100], got {table['fps']!r}")
        out["fps"] = fps
    if "dpi" in table:
        low, high = ANIMATION_DPI
        if not (is_int(table["dpi"], low) and table["dpi"] <= high):
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


def is_int(value, least: int) -> bool:
    """Whether a scene value is an integer (not a bool) of at least `least`."""
    return isinstance(value, int) and not isinstance(value, bool) and value >= least



def input_rate(value, order: int, name: str | None = None) -> float:
    """The input's speed (``order`` 1, rad/s) or acceleration (2, rad/s^2) from a scene value.

    Read by :func:`numkin.units.input_rate`, the one parser of input rates;
    everything downstream receives the float. `name` names the value in
    messages.

    Examples
    --------
    >>> import math
    >>> input_rate("450 rad/min", 1), input_rate("2 rev/s^2", 2) / math.pi
    (7.5, 4.0)
    """
    from .units import input_rate as parse

    return parse(value, "speed" if order == 1 else "acceleration", name=name)


def read_input(r: SceneReader, scene: Scene, inp: dict) -> None:
    """``[input]`` into ``scene``: the input speed and acceleration (read with their units), the sweep's
    ``start_deg``, ``stop_deg`` and ``step_deg``, and ``on_singular``; each mistake fails the scene naming
    its key."""
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
    scene.on_singular = r.string(inp.get("on_singular", "raise"), "[input] on_singular")
    if scene.on_singular not in ("raise", "report"):
        r.fail("[input] on_singular", f"must be \"raise\" or \"report\", got {scene.on_singular!r}")
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


def read_output(r: SceneReader, scene: Scene, out: dict) -> None:
    """``[output]`` into ``scene``: the quantities (position always among them), the unknowns and points
    reported, the tables and their formats, and the figures (:func:`read_figures`)."""
    scene.quantities = r.strings(out.get("quantities", ["position"]), "[output] quantities", QUANTITIES)
    if not scene.quantities:
        r.fail("[output] quantities", "is empty; ask for at least \"position\"")
    if "position" not in scene.quantities:
        scene.quantities = ("position", *scene.quantities)
    scene.unknowns = r.strings(out["unknowns"], "[output] unknowns") if "unknowns" in out else None
    scene.points = r.strings(out.get("points", []), "[output] points")
    scene.tables = r.strings(out.get("tables", []), "[output] tables", TABLES[:-1])
    scene.table_formats = r.strings(out.get("table_formats", ["csv"]), "[output] table_formats", TABLE_FORMATS)
    scene.figures = read_figures(r, out)
    needs = {"kinematics": "velocity", "comparison": "velocity"}
    for table, quantity in needs.items():
        if table in scene.tables and not scene.differentiates:
            r.fail("[output] tables", f"'{table}' needs \"velocity\" or \"acceleration\" in [output] quantities")
    if "points" in scene.tables and not scene.points:
        r.fail("[output] tables", "'points' needs [output] points")


def read_figures(r: SceneReader, out: dict) -> tuple:
    """``[output] figures`` as a tuple of names, each read as :func:`numkin.figures.specs.parse_spec` reads it
    (a misspelt name fails the scene with the nearest one)."""
    names = r.strings(out.get("figures", []), "[output] figures")
    if names:
        from .figures.specs import parse_spec  # (not the modules that draw)

        for name in names:
            try:
                parse_spec(name)
            except ValueError as error:
                r.fail("[output] figures", str(error))
    return names


def read_compare(r: SceneReader, scene: Scene, cmp: dict) -> None:
    """``[compare]`` into ``scene``: the first- and second-derivative schemes (registered names of the right
    order, the quantity they need asked for in ``[output]``)."""
    for key, order, quantity in (("schemes", 1, "velocity"), ("second_schemes", 2, "acceleration")):
        if key not in cmp:
            continue
        from .derivatives import SCHEMES, get_scheme  # (the schemes only for a scene that compares them)

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


class _Written(float):
    """A TOML float that keeps the text it was written as (``parse_float`` of :func:`checks_as_written`)."""

    __slots__ = ("text",)

    def __new__(cls, text):
        value = super().__new__(cls, text)
        value.text = text
        return value


def checks_as_written(text: str) -> list:
    r"""The numbers of each ``[[check]]`` table as written in a scene's TOML text: ``[{key: "122.340"}, ...]``.

    TOML reads ``122.340`` as the float 122.34; the text keeps the decimals
    the author wrote, which the check's default tolerance is half a unit of.
    The text is read by the TOML parser itself (its ``parse_float`` hands over
    every float as written), so a check written as an inline table, with
    quoted keys or over several lines is read as one written as a
    ``[[check]]`` table; an integer is written as its digits. ``[]`` for a
    text that is no TOML.

    Examples
    --------
    >>> checks_as_written("[input]\nstart_deg = 0\n[[check]]\nat_deg = 100\ntheta4_deg = 122.340  # deg\n"
    ...                   "[[check]]\nat_deg = 1_0\n")
    [{'at_deg': '100', 'theta4_deg': '122.340'}, {'at_deg': '10'}]
    >>> checks_as_written('check = [{at_deg = 100, "omega_beta" = 10.6330}]')
    [{'at_deg': '100', 'omega_beta': '10.6330'}]
    """
    try:
        checks = tomllib.loads(text, parse_float=_Written).get("check", [])
    except tomllib.TOMLDecodeError:
        return []
    if isinstance(checks, dict):
        checks = [checks]
    if not isinstance(checks, list):
        return []
    found = []
    for check in checks:
        numbers = {}
        if isinstance(check, dict):
            for key, value in check.items():
                if isinstance(value, _Written):
                    numbers[key] = value.text
                elif isinstance(value, int) and not isinstance(value, bool):
                    numbers[key] = str(value)
        found.append(numbers)
    return found


def read_checks(r: SceneReader, scene: Scene, checks, written=None) -> None:
    """``[[check]]`` into ``scene.checks``; ``written``: :func:`checks_as_written` of the scene's text, if read
    from a file (each expected value's tolerance is then half a unit of its last decimal as written)."""
    if isinstance(checks, dict):
        checks = [checks]
    if not isinstance(checks, list):
        r.fail("[[check]]", f"must be an array of tables, got {checks!r}")
    if written is not None and len(written) != len(checks):
        written = None  # (not the scene's own checks: read from the floats)
    for k, check in enumerate(checks):
        where = f"[[check]] {k + 1}"
        r.table(check, where)
        if "at_deg" not in check:
            # a mistyped at_deg (not a quantity's name such as theta4_deg, which is as near by difflib's default)
            near = next((f" ('{k}' is written there: did you mean 'at_deg'?)" for k in check
                         if difflib.SequenceMatcher(None, k, "at_deg").ratio() >= 0.75), "")
            r.fail(where, f"missing key 'at_deg' (the input angle of the check point, degrees){near}")
        at = r.number(check["at_deg"], f"{where} at_deg")
        in_range(r, scene, at, f"{where} at_deg")
        tol = None
        if "tolerance" in check:
            tol = r.number(check["tolerance"], f"{where} tolerance")
            if not tol > 0:
                r.fail(f"{where} tolerance", f"must be positive, got {tol!r}")
        expected, as_written = {}, {}
        for key, value in check.items():
            if key in ("at_deg", "tolerance"):
                continue
            expected[key] = r.number(value, f"{where} {key}")
            text = written[k].get(key) if written is not None else None
            if text is not None and float(text.replace("_", "")) == expected[key]:
                as_written[key] = text.replace("_", "")
        scene.checks.append({"at_deg": at, "expected": expected, "tolerance": tol, "written": as_written})


def in_range(r: SceneReader, scene: Scene, at: float, where: str) -> None:
    """Fail the scene at ``where`` unless the angle ``at`` (deg) lies in the sweep (to 1e-9°)."""
    if not scene.start_deg - 1e-9 <= at <= scene.stop_deg + 1e-9:
        r.fail(where, f"{at:g}° is outside the sweep {scene.start_deg:g}..{scene.stop_deg:g}°")



"""From a scene to a mechanism: the ``[mechanism]`` section and the names a scene uses.

:func:`read_mechanism` validates the ``[mechanism]`` section of a scene
file: a ready-made linkage's dimensions are read from its
:class:`~numkin.linkages.LinkageSpec` (names, kinds, units, defaults), a
mechanism written as loops from its expressions. :func:`build_mechanism`
then builds the :class:`~numkin.Mechanism` (sympy is imported here, on
first use) and checks the unknowns, points, guesses and check quantities
the scene names against it (what a scene calls its quantities is
:mod:`numkin.scene_quantities`).

Examples
--------
>>> from numkin.schema import load_scene
>>> mech = build_mechanism(load_scene("quick-return"))
>>> list(mech.unknowns)
['r3', 'theta3', 'r4', 'r5']
"""

from __future__ import annotations

import ast
import math
import numbers
import re
from typing import Mapping

from .errors import InputError, NumkinError
from .schema import Scene, SceneError, SceneReader, nearest
from .scene_quantities import quantity_names, scene_quantity
from .units import UnitError, convert_length

__all__ = [
    "read_mechanism",
    "build_mechanism",
    "guess_values",
    "parse_expression",
    "parse_equation",
    "FUNCTIONS",
]
#: Keys of a ``[[mechanism.loops]]`` table.
_LOOP_KEYS = ("name", "unknowns", "vectors", "equations")


def read_mechanism(r: SceneReader, scene: Scene, mech: dict) -> None:
    """Validate a scene's ``[mechanism]`` table into ``scene`` (unit, linkage or loops, dimensions)."""
    scene.unit = r.string(mech.get("unit", "mm"), "[mechanism] unit")
    try:
        convert_length(1.0, scene.unit, "mm")
    except UnitError as error:
        r.fail("[mechanism] unit", str(error))
    dims = r.table(mech.get("dimensions", {}), "[mechanism.dimensions]")
    _read_quantities(r, scene, mech)
    if "linkage" in mech:
        _read_linkage(r, scene, mech, dims)  # (its quantities are checked against the mechanism when it is built)
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
        _identifier(r, p, f"[mechanism.points] {p}")  # a name figures write as a symbol
        if not isinstance(xy, list) or len(xy) != 2:
            r.fail(f"[mechanism.points] {p}", f"must be a pair [x, y] of expressions, got {xy!r}")
    links = mech.get("links", [])
    if not isinstance(links, list) or not all(isinstance(link, list) and all(isinstance(q, str) for q in link) for link in links):
        r.fail("[mechanism] links", f"must be a list of lists of point names, got {links!r}")
    ground = r.strings(mech.get("ground", []), "[mechanism] ground")
    for p in [q for link in links for q in link] + list(ground):
        if p not in points:
            r.fail("[mechanism] links/ground", f"point '{p}' is not in [mechanism.points]{nearest(p, points)}")
    angles = {key[:-4] for key in dims if key.endswith("_deg")}
    for k, lp in enumerate(loops):
        for j, (length, angle) in enumerate(lp["vectors"] or ()):
            _check_kinds(r, f"[[mechanism.loops]] {k + 1} vector {j + 1}", length, angle, angles,
                         set(params) - angles, scene.unit)
    # a name that is a whole term of a vector's angle is an angle: never a whole term of a point's coordinate
    turning = angles | {n for lp in loops for _, angle in (lp["vectors"] or ()) for n in _bare_names(angle)}
    lengths = set(params) - angles
    for p, xy in points.items():
        for axis, text in zip("xy", xy):
            for name in sorted(_bare_names(text) & turning):
                r.fail(f"[mechanism.points] {p} {axis}",
                       f"'{name}' is an angle but is a whole term of the point's coordinate, which is a length "
                       f"in {scene.unit} (a length times cos or sin of an angle, e.g. 'r*cos({name})')")
            _check_trig_arguments(r, f"[mechanism.points] {p} {axis}", text, lengths, scene.unit)
    for k, lp in enumerate(loops):
        for j, (length, angle) in enumerate(lp["vectors"] or ()):
            _check_trig_arguments(r, f"[[mechanism.loops]] {k + 1} vector {j + 1} length", length, lengths, scene.unit)
            _check_trig_arguments(r, f"[[mechanism.loops]] {k + 1} vector {j + 1} angle", angle, lengths, scene.unit)
        for j, equation in enumerate(lp["equations"] or ()):
            _check_trig_arguments(r, f"[[mechanism.loops]] {k + 1} equation {j + 1}", equation, lengths, scene.unit)
    _check_quantity_kinds(r, scene, lengths)
    scene.dimensions = params
    scene.custom = {
        "input": input_name, "loops": loops, "points": points, "links": links, "ground": ground,
        "name": r.string(mech["name"], "[mechanism] name") if "name" in mech else None,
    }


def _bare_names(text) -> set:
    """Names that are whole additive terms of an expression string (``r1`` and ``2*r1`` in
    ``"theta2 + 2*r1"``; not inside a product of names or a function); none if it does not parse."""
    return _whole_terms(text)[0]


def _whole_terms(text) -> tuple[set, list]:
    """The names (see :func:`_bare_names`) and the numbers (``180`` in ``"theta2 + 180"``, ``-30`` in
    ``"theta2 - 30"``, ``30/57.3`` by its value; not a multiple of ``pi``) that are whole additive terms of
    an expression string; none if it does not parse."""
    try:
        node = ast.parse(str(text).replace("^", "**"), mode="eval").body
    except SyntaxError:
        return set(), []  # the expression's own parse reports it
    names, numbers, terms = set(), [], [(node, 1.0)]
    while terms:
        t, sign = terms.pop()
        value = _constant(t)
        if value is not None:
            if not any(isinstance(n, ast.Name) for n in ast.walk(t)):  # a multiple of pi is rad on purpose
                numbers.append(sign * value)
        elif isinstance(t, ast.BinOp) and isinstance(t.op, (ast.Add, ast.Sub)):
            terms += [(t.left, sign), (t.right, -sign if isinstance(t.op, ast.Sub) else sign)]
        elif isinstance(t, ast.UnaryOp) and isinstance(t.op, (ast.USub, ast.UAdd)):
            terms.append((t.operand, -sign if isinstance(t.op, ast.USub) else sign))
        elif isinstance(t, ast.BinOp) and isinstance(t.op, (ast.Mult, ast.Div)) and isinstance(t.right, ast.Constant):
            terms.append((t.left, sign))
        elif isinstance(t, ast.BinOp) and isinstance(t.op, ast.Mult) and isinstance(t.left, ast.Constant):
            terms.append((t.right, sign))
        elif isinstance(t, ast.Name):
            names.add(t.id)
    return names, numbers


def _constant(node) -> float | None:
    """The value of an expression made of numbers and ``pi`` alone (``30/57.3``, ``-2*pi``); None otherwise."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return float(node.value)
    if isinstance(node, ast.Name) and node.id == "pi":
        return math.pi
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        value = _constant(node.operand)
        return None if value is None else (-value if isinstance(node.op, ast.USub) else value)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)):
        a, b = _constant(node.left), _constant(node.right)
        if a is None or b is None:
            return None
        if isinstance(node.op, ast.Div):
            return a / b if b else None
        return a + b if isinstance(node.op, ast.Add) else a - b if isinstance(node.op, ast.Sub) else a * b
    return None


def _check_kinds(r: SceneReader, where: str, length, angle, angles: set, lengths: set, unit: str) -> None:
    """A vector's length holds no angle dimension as a whole term, and its angle no length dimension:
    a length and an angle are never added (``r1_deg = 4`` used as a length is 0.07 of a length unit)."""
    for name in sorted(_bare_names(length) & angles):
        r.fail(f"{where} length", f"'{name}' is an angle (given as {name}_deg in [mechanism.dimensions]) but is "
                                  f"used as a length; give it as {name} in {unit}")
    _check_angle_terms(r, f"{where} angle", angle, lengths, unit, "is added to an angle", "in an angle")


#: Functions whose argument is an angle (rad).
_TRIG = ("sin", "cos", "tan")
#: The largest number accepted in an angle (rad): a turn, written to a few figures (6.2832) too.
_MOST_IN_AN_ANGLE = 2.0 * math.pi + 1e-3


def _check_angle_terms(r: SceneReader, where: str, text, lengths: set, unit: str, doing: str, inside: str) -> None:
    """An angle expression (``text``, or a part of it) holds no length dimension as a whole term, and no number of
    more than a turn (a number in an angle is rad: 180 there is 28.6 turns, most likely meant as degrees).
    ``doing``: what a length there does, for the message; ``inside``: where the number is."""
    names, numbers = _whole_terms(text)
    for name in sorted(names & lengths):
        r.fail(where, f"'{name}' is a length (in {unit}, [mechanism.dimensions]) but {doing}; an angle dimension is "
                      f"given as {name}_deg")
    for number in numbers:
        if abs(number) > _MOST_IN_AN_ANGLE:
            r.fail(where, f"the number {number:g} {inside} is more than a turn: a number in an angle is rad "
                          f"({number:g} rad = {math.degrees(number):.4g}°); write pi for 180°, or give an angle "
                          "dimension as <name>_deg")


def _check_trig_arguments(r: SceneReader, where: str, text, lengths: set, unit: str) -> None:
    """The argument of every sin, cos and tan in ``text`` passes :func:`_check_angle_terms`."""
    sides = str(text).replace("^", "**").split("=") if str(text).count("=") == 1 else [str(text).replace("^", "**")]
    try:  # an equation "lhs = rhs": both sides
        trees = [ast.parse(side.strip(), mode="eval") for side in sides]
    except SyntaxError:
        return  # the expression's own parse reports it
    for node in (n for tree in trees for n in ast.walk(tree)):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in _TRIG and node.args:
            _check_angle_terms(r, where, ast.unparse(node.args[0]), lengths, unit,
                               f"is added to an angle (the argument of {node.func.id})",
                               f"in an angle (the argument of {node.func.id})")


def _check_quantity_kinds(r: SceneReader, scene: Scene, lengths: set) -> None:
    """A derived quantity's angle arguments hold no length dimension (nor a number of more than a turn); one of
    dimension "angle" holds none as a whole term either."""
    for name, (expression, dimension) in scene.derived.items():
        where = f"[mechanism.quantities] {name} expression"
        _check_trig_arguments(r, where, expression, lengths, scene.unit)
        if dimension == "angle":
            _check_angle_terms(r, where, expression, lengths, scene.unit,
                               "is a whole term of an angle (dimension = \"angle\")",
                               "in an angle (dimension = \"angle\")")



def _read_linkage(r: SceneReader, scene: Scene, mech: dict, dims: dict) -> None:
    """A ready-made linkage's dimensions, read as its :class:`~numkin.linkages.LinkageSpec` declares them."""
    from . import linkages

    name = r.string(mech["linkage"], "[mechanism] linkage")
    if name not in linkages.SPECS:
        r.fail(
            "[mechanism] linkage",
            f"unknown linkage '{name}'{nearest(name, linkages.SPECS)}; ready-made linkages: {', '.join(linkages.SPECS)}",
        )
    for key in ("input", "loops", "points", "links", "ground", "name"):
        if key in mech:
            r.fail(f"[mechanism] {key}", f"applies to loops, not to a ready-made linkage ('{name}')")
    spec = linkages.spec(name)
    scene.linkage = name
    valid = [d.scene_key for d in spec.dimensions]
    r.keys(dims, valid, f"[mechanism.dimensions] of {name}")
    out = {}
    for d in spec.dimensions:
        key, where = d.scene_key, f"[mechanism.dimensions] {d.scene_key}"
        if key not in dims:
            if d.required:
                r.fail("[mechanism.dimensions]", f"missing dimension '{key}' of {name}; it needs {', '.join(valid)}")
            out[d.name] = _default(d, spec.length_unit, scene.unit)
            continue
        value = dims[key]
        if d.kind == "length":
            out[d.name] = r.length(value, where, scene.unit)
        elif d.kind == "signed":
            out[d.name] = r.length(value, where, scene.unit, positive=False)
        elif d.kind == "pair":
            if not isinstance(value, list) or len(value) != 2:
                r.fail(where, f"must be a pair [x, y], got {value!r}")
            out[d.name] = tuple(r.length(v, f"{where}[{i}]", scene.unit, positive=False) for i, v in enumerate(value))
        else:
            out[d.name] = math.radians(r.number(value, where))
    scene.dimensions = out
    if "branch" in mech:
        if not spec.branches:
            with_branch = [s.name for s in linkages.SPECS.values() if s.branches]
            r.fail(
                "[mechanism] branch",
                f"applies to {', '.join(with_branch)} only; pick the branch of {name} with [guess]",
            )
        branch = r.string(mech["branch"], "[mechanism] branch")
        if branch not in spec.branches:
            r.fail("[mechanism] branch", f"must be {' or '.join(repr(b) for b in spec.branches)}, got {branch!r}")
        scene.branch = branch


def _read_quantities(r: SceneReader, scene: Scene, mech: dict) -> None:
    """``[mechanism.quantities]``: ``mu = { expression = "theta4 - theta3", dimension = "angle" }``."""
    where = "[mechanism.quantities]"
    for name, value in r.table(mech.get("quantities", {}), where).items():
        _identifier(r, name, f"{where} {name}")
        r.keys(r.table(value, f"{where} {name}"), ("expression", "dimension"), f"{where} {name}")
        for key in ("expression", "dimension"):
            if key not in value:
                r.fail(f"{where} {name}", f"missing key '{key}' (e.g. {name} = {{ expression = \"theta4 - theta3\", "
                                          'dimension = "angle" })')
        scene.derived[name] = (r.string(value["expression"], f"{where} {name} expression"),
                               r.string(value["dimension"], f"{where} {name} dimension"))


def _default(dimension, spec_unit: str, unit: str):
    """A dimension's default, its lengths converted from the spec's unit to the scene's."""
    value = dimension.default
    if dimension.kind == "angle":
        return value
    if dimension.kind == "pair":
        return tuple(float(convert_length(v, spec_unit, unit)) for v in value)
    return float(convert_length(value, spec_unit, unit))


def _identifier(r: SceneReader, name: str, where: str) -> None:
    if not name.isidentifier() or name.startswith("_") or name in FUNCTIONS or name == "pi":
        r.fail(where, f"'{name}' is not a usable symbol name (an identifier such as 'theta3', not a function name)")


# ---------------------------------------------------------------------- build
def build_mechanism(scene: Scene):
    """The scene's :class:`~numkin.Mechanism`; names in the scene are checked against it."""
    if scene.kind != "mechanism":
        raise SceneError(f"{scene.source}: a {scene.kind} scene has no mechanism")
    mech = _build_linkage(scene) if scene.linkage else _build_loops(scene)
    try:
        mech.add_quantities(scene.derived)
    except InputError as error:
        scene.fail("[mechanism.quantities]", str(error).replace(mech.name, mech.title))
    _check_names(scene, mech)
    return mech


def _build_linkage(scene: Scene):
    from . import linkages

    kwargs = dict(scene.dimensions)
    if scene.branch is not None:
        kwargs["branch"] = scene.branch
    try:
        return linkages.spec(scene.linkage).build(**kwargs, length_unit=scene.unit)
    except InputError as error:  # a dimension the builder refuses: said where the scene gives it
        scene.fail("[mechanism]", str(error))
    except NumkinError:  # cannot assemble, ...: already said in the linkage's terms
        raise
    except ValueError as error:
        scene.fail("[mechanism]", str(error))


def _build_loops(scene: Scene):
    """A mechanism written as loops, through the kernel cache: keyed by the scene's expressions as
    written, so a second run of the scene needs no sympy."""
    import json

    from . import kernel_cache
    from .mechanism import Mechanism

    spec = scene.custom
    written = {k: spec[k] for k in ("input", "loops", "points")}
    written["dimensions"] = list(scene.dimensions)
    key = kernel_cache.bundle_key("scene loops", json.dumps(written, sort_keys=True))
    try:
        return Mechanism.from_model(
            key, lambda: _loops_model(scene), list(scene.dimensions.values()),
            name=spec.get("name") or scene.title or scene.name, links=spec["links"], ground=spec["ground"],
            length_unit=scene.unit,
        )
    except SceneError:
        raise
    except ValueError as error:
        scene.fail("[mechanism]", str(error))


def _loops_model(scene: Scene):
    """The scene's loops, input, dimension symbols and points as sympy objects (see :meth:`numkin.cached_model.CachedModel.from_model`)."""
    import sympy as sp

    from .loops import Loop

    spec = scene.custom
    input_sym = sp.Symbol(spec["input"], real=True)
    names = {spec["input"]: input_sym}
    symbols = []
    for key in scene.dimensions:
        sym = sp.Symbol(key, real=True)
        names[key] = sym
        symbols.append(sym)
    loops = []
    for k, lp in enumerate(spec["loops"]):
        where = f"[[mechanism.loops]] {k + 1} ('{lp['name']}')"
        unknowns = []
        for u in lp["unknowns"]:
            if u in names:
                scene.fail(where, f"unknown '{u}' is already the input, a dimension or an earlier unknown")
            unknowns.append(sp.Symbol(u, real=True))
        local = dict(names)
        local.update({str(u): u for u in unknowns})
        try:
            if lp["vectors"] is not None:
                vectors = [
                    (
                        parse_expression(scene, length, local, f"{where} vector {j + 1} length"),
                        parse_expression(scene, angle, local, f"{where} vector {j + 1} angle"),
                    )
                    for j, (length, angle) in enumerate(lp["vectors"])
                ]
                loop = Loop.from_vectors(vectors, unknowns, name=lp["name"])
            else:
                eqs = [parse_equation(scene, e, local, f"{where} equation {j + 1}") for j, e in enumerate(lp["equations"])]
                loop = Loop(eqs, unknowns, name=lp["name"])
        except SceneError:
            raise
        except ValueError as error:
            scene.fail(where, str(error))
        loops.append(loop)
        names.update({str(u): u for u in unknowns})
    points = {
        p: tuple(parse_expression(scene, c, names, f"[mechanism.points] {p}") for c in xy) for p, xy in spec["points"].items()
    }
    return loops, input_sym, symbols, points


def _check_names(scene: Scene, mech) -> None:
    """Unknowns, points, guesses and check quantities named in the scene exist in ``mech``."""
    unknowns = list(mech.unknowns)
    for u in scene.unknowns or ():
        if u not in unknowns:
            scene.fail("[output] unknowns", f"'{u}' is not an unknown{nearest(u, unknowns)}; unknowns: {', '.join(unknowns)}")
    for p in scene.points:
        if p not in mech.points:
            points = ", ".join(mech.points) or "none"
            scene.fail("[output] points", f"'{p}' is not a point{nearest(p, mech.points)}; points: {points}")
    if scene.guess is not None:
        guess_values(scene, mech)
    valid = quantity_names(scene, mech, all_unknowns=True)
    for k, check in enumerate(scene.checks):
        for key in check["expected"]:
            if key not in valid:
                q = scene_quantity(scene, mech, key)
                if q is not None and q.is_point and q.of not in scene.points:
                    scene.fail(f"[[check]] {k + 1}", f"'{key}' needs '{q.of}' in [output] points")
                if q is not None and not scene.wants(q.kind):
                    scene.fail(f"[[check]] {k + 1}", f"'{key}' needs \"{q.kind}\" in [output] quantities")
                scene.fail(
                    f"[[check]] {k + 1}",
                    f"unknown key '{key}'{nearest(key, valid + ['at_deg', 'tolerance'])}; "
                    f"quantities: {', '.join(valid)}",
                )
    # the error tables study, and the figures draw, an unknown or a derived quantity
    named = unknowns + list(mech.derived)
    listed = f"unknowns: {', '.join(unknowns)}" + (
        f"; derived quantities ([mechanism.quantities]): {', '.join(mech.derived)}" if mech.derived else "")
    quantity = scene.report.get("quantity")
    if quantity is not None and quantity not in named:
        scene.fail("[report] quantity", f"'{quantity}' is neither an unknown nor a derived quantity"
                                        f"{nearest(quantity, named)}; {listed}")
    if scene.figures:
        from .figures.specs import parse_spec  # (not the modules that draw)

        for spec in scene.figures:
            kind, arg = parse_spec(spec)
            if arg is not None and kind != "mechanism" and arg not in named:
                scene.fail("[output] figures", f"{spec!r}: '{arg}' is not an unknown or derived quantity"
                                               f"{nearest(arg, named)}; {listed}")


def guess_values(scene: Scene, mech) -> dict | None:
    """The ``[guess]`` table as ``{unknown: value}`` (rad, working unit), or None."""
    if scene.guess is None:
        return None
    out = {}
    expect = {(f"{u}_deg" if u in mech.angles else u): u for u in mech.unknowns}
    for key, value in scene.guess.items():
        if key not in expect:
            hint = ""
            if key in mech.angles:
                hint = f" ('{key}' is an angle: write {key}_deg)"
            elif key.endswith("_deg") and key[:-4] in mech.unknowns:
                hint = f" ('{key[:-4]}' is a length in {scene.unit}: write {key[:-4]})"
            scene.fail(
                "[guess]", f"unknown key '{key}'{hint or nearest(key, expect)}; valid keys: {', '.join(expect)}"
            )
        u = expect[key]
        where = f"[guess] {key}"
        if u in mech.angles:
            out[u] = math.radians(SceneReader(scene.source).number(value, where))
        else:
            out[u] = SceneReader(scene.source).length(value, where, scene.unit, positive=False)
    missing = [k for k, u in expect.items() if u not in out]
    if missing:
        how = ("give every unknown: a mechanism written as loops has no default guess" if scene.custom is not None
               else "give every unknown, or leave out [guess] for the linkage's default")
        scene.fail("[guess]", f"lacks {', '.join(missing)} ({how})")
    return out

# -------------------------------------------------------------- expressions
_EXPR_CHARS = re.compile(r"[A-Za-z0-9_+\-*/^().,\s]*")
FUNCTIONS = ("sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "abs")


def parse_expression(scene: Scene, text, names: Mapping, where: str):
    """A scene's expression (a string, or a number) as a sympy expression in ``names`` (name -> symbol).

    Only names, numbers, ``+ - * / ^ ( )`` and the functions of
    :data:`FUNCTIONS` are read; anything else, a name not in ``names``, or an
    infinite or undefined value fails the scene at ``where``.

    Examples
    --------
    >>> import sympy as sp
    >>> from numkin.schema import Scene
    >>> t = sp.Symbol("theta2")
    >>> parse_expression(Scene(name="x", source="x.toml", description="", data={}), "2*cos(theta2)^2", {"theta2": t}, "[x] y")
    2*cos(theta2)**2
    """
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
            f"{text!r}: an expression may contain names, numbers, + - * / ^ ( ) and the functions {', '.join(FUNCTIONS)}",
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
        scene.fail(where, f"{text!r} calls unknown function '{undefined[0]}'; functions: {', '.join(FUNCTIONS)}")
    for sym in expr.free_symbols:
        if sym.name not in names:
            scene.fail(
                where,
                f"{text!r} uses '{sym.name}', which is not the input, a dimension or an unknown"
                f"{nearest(sym.name, names)}; known names: {', '.join(names)}",
            )
    if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
        scene.fail(where, f"{text!r} is infinite or undefined ({expr}): a division by zero?")
    return expr


def parse_equation(scene: Scene, text, names: Mapping, where: str):
    """A scene's equation as the expression that vanishes: ``"lhs = rhs"`` gives ``lhs - rhs``, an expression
    alone is taken ``= 0`` (:func:`parse_expression` reads each side).

    Examples
    --------
    >>> import sympy as sp
    >>> from numkin.schema import Scene
    >>> t5, t2 = sp.symbols("theta5 theta2")
    >>> parse_equation(Scene(name="x", source="x.toml", description="", data={}), "theta5 = theta2 + 0.6", {"theta5": t5, "theta2": t2}, "[x] y")
    -theta2 + theta5 - 0.6
    """
    if not isinstance(text, str):
        scene.fail(where, f"must be a string: an expression (= 0) or \"lhs = rhs\", got {text!r}")
    if text.count("=") > 1:
        scene.fail(where, f"{text!r} has {text.count('=')} '=' signs: an equation is an expression (= 0) or one \"lhs = rhs\"")
    if text.count("=") == 1:
        lhs, rhs = text.split("=")
        return parse_expression(scene, lhs, names, where) - parse_expression(scene, rhs, names, where)
    return parse_expression(scene, text, names, where)

"""Loops: the closure equations of a linkage, in their unknowns.

A loop is a closed chain of vectors whose sum is zero. Written as (length,
angle) pairs, ``sum_k L_k exp(i A_k) = 0`` gives two scalar equations, its
real and imaginary parts. Either member of a pair may be an unknown symbol, a
known value, a parameter or an expression of the input. A loop may also be
given directly as sympy residual expressions.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Callable, Iterable, Sequence

from .errors import InputError

__all__ = ["Loop", "as_symbol", "SymbolName", "LazyPoints", "describe", "check_lengths", "check_symbols",
           "read_parameters", "read_points", "check_point_names"]


def as_symbol(name, among=()):
    """A sympy symbol from a symbol or its name: the symbol of that name in `among` (the symbols of the
    equations, whatever their assumptions: a symbol made again with other assumptions means the
    equations' own), else a new real-valued one.

    Examples
    --------
    >>> import sympy as sp
    >>> plain = sp.Symbol("theta2")                     # as sp.symbols("theta2") makes it
    >>> as_symbol("theta2", [plain]) is plain, as_symbol("theta2").is_real
    (True, True)
    >>> as_symbol(sp.Symbol("theta2", real=True), [plain]) is plain
    True
    """
    import sympy as sp

    if isinstance(name, SymbolName):
        return name._sympy_()
    if isinstance(name, sp.Symbol):
        if name not in among:
            return next((sym for sym in among if getattr(sym, "name", None) == name.name), name)
        return name
    if isinstance(name, str) and name.isidentifier():
        for sym in among:
            if getattr(sym, "name", None) == name:
                return sym
        return sp.Symbol(name, real=True)
    raise InputError(f"{name!r} is not a symbol name (use an identifier such as 'theta3')")


def _angle_unknowns(residuals, unknowns) -> set:
    """Unknowns that appear inside a trigonometric function: those are angles (rad)."""
    import sympy as sp

    found = set()
    for expr in residuals:
        for fn in expr.atoms(sp.sin, sp.cos, sp.tan, sp.exp):
            found |= fn.free_symbols & set(unknowns)
    return found


class Loop:
    """Closure equations of one loop in its own unknowns.

    Parameters
    ----------
    residuals : sequence of sympy expressions
        Residuals that vanish when the loop is closed. Their unit is a length.
    unknowns : sequence of sympy symbols or names
        The unknowns this loop solves for; as many as residuals. A later loop
        of a :class:`~numkin.Mechanism` may use the unknowns of earlier ones
        as known values.
    name : str, optional
        Used in error messages ("loop 'O2-A-B-O4' did not converge ...").
    angles : sequence, optional
        Which unknowns are angles (rad). Default: those that appear inside a
        trigonometric function; the others are lengths. In a
        :class:`~numkin.Mechanism`, an unknown of such a loop is an angle
        too where another loop or a point takes its sine or cosine, or an
        equation sets it to a sum of angles
        (:func:`numkin.symbol_roles.angle_unknowns`).

    Notes
    -----
    Written with :meth:`from_vectors`, a loop knows its vectors: the
    mechanism checks that the lengths of those that turn are positive and
    that a loop of constant lengths can close at all. Written as residuals,
    it has no vectors, and those checks cannot be made.

    Examples
    --------
    A four-bar written as vectors, crank angle ``theta2`` as input:

    >>> import sympy as sp
    >>> t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    >>> loop = Loop.from_vectors([(1, t2), (3, t3), (-3, t4), (-4, 0)], [t3, t4], name="O2ABO4")
    >>> loop.residuals[0]
    cos(theta2) + 3*cos(theta3) - 3*cos(theta4) - 4
    >>> sorted(str(a) for a in loop.angles)
    ['theta3', 'theta4']
    """

    def __init__(self, residuals: Sequence, unknowns: Sequence, *, name: str | None = None, angles=None):
        where = f"loop '{name}'" if name else "a loop"
        for argument, value in (("residuals", residuals), ("unknowns", unknowns)):
            if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
                raise InputError(f"{where}: {argument} must be a list, got {type(value).__name__} {value!r:.60}")
        self.residuals = [_expression(r, f"{where}: equation {k + 1}") for k, r in enumerate(residuals)]
        free = set().union(*(r.free_symbols for r in self.residuals))
        self.unknowns = [as_symbol(u, free) for u in unknowns]
        self.name = name or "-".join(str(u) for u in self.unknowns)
        if not self.unknowns:
            raise InputError(f"loop '{self.name}' has no unknowns")
        if len(set(self.unknowns)) != len(self.unknowns):
            raise InputError(f"loop '{self.name}' lists an unknown twice: {self.unknowns}")
        if len(self.residuals) != len(self.unknowns):
            raise InputError(
                f"loop '{self.name}' has {len(self.residuals)} equations for "
                f"{len(self.unknowns)} unknowns; it must have as many of each"
            )
        missing = [str(u) for u in self.unknowns if u not in free]
        if missing:
            raise InputError(f"loop '{self.name}': unknown(s) {', '.join(missing)} appear in no equation")
        #: whether ``angles`` was given (or follows from vectors): a mechanism then takes it as it is
        self.angles_declared = angles is not None
        if angles is None:
            self.angles = _angle_unknowns(self.residuals, self.unknowns)
        else:
            self.angles = {as_symbol(a, self.unknowns) for a in angles}
            stray = self.angles - set(self.unknowns)
            if stray:
                raise InputError(f"loop '{self.name}': angles {sorted(map(str, stray))} are not unknowns of it")
        self.length_symbols: set = set()
        self.vector_symbols: list = []  # (length symbols, angle symbols) of every vector, where given as vectors
        self.vectors: list = []  # the (length, angle) pairs, where given as vectors

    @classmethod
    def from_vectors(cls, vectors: Iterable, unknowns: Sequence, *, name: str | None = None) -> "Loop":
        """A loop from vectors ``(length, angle)`` that sum to zero.

        A vector subtracted in the loop equation is written with a minus sign
        on its length (``(-r4, theta4)``) or pi added to its angle. Angles in
        rad, measured counter-clockwise from +x.
        """
        import sympy as sp

        if isinstance(vectors, (str, bytes)) or not isinstance(vectors, Iterable):
            where = f"loop {name!r}" if name else "a loop"
            raise InputError(f"{where}: vectors must be a list of (length, angle) pairs, got {type(vectors).__name__} "
                             f"{vectors!r:.60}")
        pairs = []
        for k, v in enumerate(vectors):
            try:
                length, angle = v
            except (TypeError, ValueError):
                raise InputError(f"vector {k} of loop '{name}' must be a (length, angle) pair, got {v!r}") from None
            pair = (_expression(length, f"vector {k} of loop '{name}': its length"),
                    _expression(angle, f"vector {k} of loop '{name}': its angle"))
            for what, expr in zip(("length", "angle"), pair):
                if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan) or expr.has(sp.I):
                    raise InputError(f"vector {k} of loop '{name}': its {what} {expr} is not a finite real "
                                     "expression")
            pairs.append(pair)
        if len(pairs) < 2:
            raise InputError(f"loop '{name}' needs at least two vectors")
        re = sum(length * sp.cos(angle) for length, angle in pairs)
        im = sum(length * sp.sin(angle) for length, angle in pairs)
        unknown_syms = [as_symbol(u, set().union(*(length.free_symbols | angle.free_symbols for length, angle in pairs)))
                        for u in unknowns]
        angle_syms = set().union(*(a.free_symbols for _, a in pairs)) & set(unknown_syms)
        loop = cls([re, im], unknown_syms, name=name, angles=angle_syms)
        loop.length_symbols = set().union(*(length.free_symbols for length, _ in pairs)) - set(unknown_syms)
        # per vector: the symbols of its length and of its angle (describe tells the turning ones)
        loop.vector_symbols = [(length.free_symbols, angle.free_symbols) for length, angle in pairs]
        loop.vectors = pairs
        return loop

    @classmethod
    def placeholder(cls, name: str, resolve: Callable) -> "Loop":
        """A loop known by its name only, whose equations ``resolve()`` fills in when first read.

        A mechanism loaded from the kernel cache holds such loops: solving
        needs only their names; their sympy expressions are derived on demand.
        """
        loop = cls.__new__(cls)
        loop.name = name
        loop._resolve = resolve
        return loop

    def __getattr__(self, attr):
        resolve = self.__dict__.get("_resolve")
        if resolve is None or attr.startswith("__"):
            raise AttributeError(f"'Loop' object has no attribute {attr!r}")
        resolve()
        self.__dict__.pop("_resolve", None)
        return getattr(self, attr)

    def __repr__(self) -> str:
        return f"Loop({self.name!r}, unknowns={[str(u) for u in self.unknowns]})"


def _expression(value, where: str, symbols: Mapping | None = None):
    """``value`` (a sympy expression, a number or an arithmetic string) as a sympy expression; an InputError
    naming ``where`` if it is none (a string is read with :func:`numkin.derived.names_in` first: never run).
    ``symbols``: name -> symbol, what a name in a string means."""
    import sympy as sp

    from .derived import names_in

    if isinstance(value, bool) or value is None:
        raise InputError(f"{where}: {value!r} is not an expression")
    if isinstance(value, str):
        names_in(value, where)
    try:
        expr = sp.sympify(value, locals=dict(symbols or {}), rational=False)
    except (sp.SympifyError, SyntaxError, TypeError, ValueError) as error:
        raise InputError(f"{where}: cannot read the expression {value!r:.60} ({type(error).__name__})") from None
    if not isinstance(expr, sp.Expr):
        raise InputError(f"{where}: {value!r:.60} is not a number-valued expression (an equation is written "
                         "as lhs - rhs, which is 0)")
    return expr


class SymbolName(str):
    """The name of a sympy symbol, standing in for it where sympy is not imported yet.

    It is the name wherever a string is wanted (printing, formatting,
    comparison with names); sympy reads it as the symbol itself
    (``sympify`` calls ``_sympy_``), and any attribute of a symbol
    (``.name``, ``.is_real``, ...) is the symbol's.

    Examples
    --------
    >>> import sympy as sp
    >>> t = sp.Symbol("theta", real=True)
    >>> s = SymbolName("theta", lambda: t)
    >>> f"{s} [deg]", sp.sympify(s) is t, s.is_real
    ('theta [deg]', True, True)
    """

    def __new__(cls, name: str, symbol: Callable):
        obj = super().__new__(cls, name)
        obj._symbol = symbol
        return obj

    def _sympy_(self):
        return self._symbol()

    def __getattr__(self, attr):
        if attr.startswith("__") or attr == "_symbol":
            raise AttributeError(attr)
        return getattr(self._symbol(), attr)


class LazyPoints(Mapping):
    """Named points ``name -> (x, y)`` whose expressions ``resolve()`` derives when one is first read.

    Names (iteration, ``in``, ``len``) are known without sympy.
    """

    def __init__(self, names, resolve: Callable):
        self._names = list(names)
        self._set = set(self._names)
        self._resolve = resolve
        self._exprs = None

    def resolved(self, exprs: dict) -> None:
        """Give the expressions (called by ``resolve``)."""
        self._exprs = dict(exprs)

    def __getitem__(self, key):
        if key not in self._set:
            raise KeyError(key)
        if self._exprs is None:
            self._resolve()
        return self._exprs[key]

    def __contains__(self, key) -> bool:
        return key in self._set

    def __iter__(self):
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __repr__(self) -> str:
        return repr(dict(self))


# --------------------------------------------------------- loops described by their names
def describe(loops, input_symbol, parameters, points) -> dict:
    """What numkin needs to know about loops besides their compiled kernels, by names only (JSON data).

    ``{"input", "input_assumptions", "parameters": [[name, non-negative, sign undeclared], ...], "loops": [{"name",
    "unknowns", "angles", "lengths", "links"}, ...], "points": [names], "point_symbols":
    {name: [names its coordinates use]}}``: the kernel cache keeps it so a
    mechanism can be checked and solved without sympy. ``lengths`` are the parameters in the loop's
    vector lengths, ``links`` those in the lengths of vectors that turn (whose angle holds the input or
    an unknown): a vector of fixed direction is an offset, which may have either sign. ``numbers`` is
    the largest vector length written as a number (0 if none), ``scales`` the parameters that scale
    the loop (in its vectors' lengths; in a loop written as equations, those outside every sine, cosine
    and tangent of an equation that has one), ``angle_parameters`` those in its angles: all three for
    :func:`numkin.symbol_roles.default_length_scale`.

    Examples
    --------
    >>> import sympy as sp
    >>> t, x = sp.symbols("t x", real=True)
    >>> r = sp.Symbol("r", positive=True)
    >>> loop = Loop([x - r * sp.cos(t)], [x], name="shadow")
    >>> describe([loop], t, {r: 1.0}, {"P": (x, 0)})["parameters"]
    [['r', True, False]]
    """
    moving = {input_symbol, *(u for lp in loops for u in lp.unknowns)}
    from .symbol_roles import angle_offsets, angle_unknowns, scale_names

    angles, input_angle = angle_unknowns(loops, input_symbol, points)
    return {
        "input": str(input_symbol),
        "input_is_angle": input_angle,
        "input_assumptions": {k: bool(v) for k, v in input_symbol.assumptions0.items()},
        "parameters": [[str(s), bool(s.is_positive or s.is_nonnegative), s.is_real is None] for s in parameters],
        "loops": [{"name": lp.name, "unknowns": [str(u) for u in lp.unknowns],
                   "angles": [str(u) for u in lp.unknowns if u in angles],
                   "lengths": sorted(str(s) for s in lp.length_symbols),
                   "links": sorted({str(s) for length, angle in lp.vector_symbols if angle & moving
                                    for s in length - set(lp.unknowns)}),
                   "numbers": max([abs(float(length)) for length, _ in lp.vectors if not length.free_symbols] + [0.0]),
                   "angle_offsets": angle_offsets(lp, moving),
                   **scale_names(lp, moving)} for lp in loops],
        "points": [str(k) for k in (points or {})],
        "point_symbols": {str(k): sorted({s.name for c in xy for s in getattr(c, "free_symbols", ())})
                          for k, xy in (points or {}).items()},
    }


def read_points(points, among, owner: str = "mechanism") -> dict:
    """Named points as ``{name: (x, y)}`` of sympy expressions in the mechanism's own symbols.

    A coordinate is a sympy expression, a number or a string; a name in it
    means the symbol of that name in ``among`` (the unknowns, the input and
    the parameters), whatever its assumptions. A name that is none of them
    is kept, for :func:`check_point_names` to refuse.

    Raises
    ------
    InputError
        If ``points`` is not a mapping of names to pairs, or a coordinate
        cannot be read or is not finite and real; the message names the point.

    Examples
    --------
    >>> import sympy as sp
    >>> t = sp.Symbol("t", real=True)
    >>> read_points({"P": ("2*cos(t)", 0)}, [t])["P"][0].free_symbols == {t}
    True
    >>> read_points({"P": "2*cos(t)"}, [t], "shadow")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: shadow: point 'P' must be a pair (x, y) of expressions, got '2*cos(t)'
    """
    import sympy as sp

    if points is None:
        return {}
    if not isinstance(points, Mapping):
        raise InputError(f"{owner}: points must be a mapping name -> (x, y), got {type(points).__name__} "
                         f"{points!r:.60}")
    symbols = {s.name: s for s in among}
    own = set(among)
    out = {}
    for name, xy in points.items():
        where = f"{owner}: point {name!r}"
        if not (isinstance(name, str) and name.isidentifier()):
            raise InputError(f"{where}: a point's name is an identifier such as 'B' or 'O2'")
        if isinstance(xy, (str, bytes)) or not hasattr(xy, "__len__") or len(xy) != 2:
            raise InputError(f"{where} must be a pair (x, y) of expressions, got {xy!r:.60}")
        coordinates = []
        for axis, c in zip("xy", xy):
            expr = _expression(c, f"{where} {axis}", symbols)  # arithmetic only: sympy evaluates what it reads
            strangers = expr.free_symbols - own
            if strangers:  # a name means the mechanism's symbol of that name
                expr = expr.xreplace({s: symbols[s.name] for s in strangers if s.name in symbols})
            if expr.has(sp.I, sp.zoo, sp.nan, sp.oo, -sp.oo):
                raise InputError(f"{where} {axis}: {c!r:.60} is not a finite real expression")
            coordinates.append(expr)
        out[name] = tuple(coordinates)
    return out


def check_point_names(model: dict, owner: str = "mechanism") -> None:
    """Every name a point's coordinates use is an unknown, the input or a parameter (:func:`describe`'s names).

    Checked where a mechanism is built, from the sympy model or from the
    kernel cache alike, so a misspelt name is refused there rather than
    when the points are first computed.

    Examples
    --------
    >>> model = {"input": "t", "parameters": [["r", True, False]], "loops": [{"unknowns": ["x"]}],
    ...          "point_symbols": {"P": ["r", "tt"]}}
    >>> check_point_names(model, "shadow")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: shadow: point 'P' names ['tt'], which the mechanism does not have: it may use the unknowns ['x'], the input t and the parameters ['r']
    """
    from .derived import refuse_unknown_names

    unknowns = [u for lp in model["loops"] for u in lp["unknowns"]]
    params = [p for p, _, _ in model["parameters"]]
    for name, used in model["point_symbols"].items():
        refuse_unknown_names(f"{owner}: point {name!r}", used, unknowns, model["input"], params)


def read_parameters(parameters, input_symbol, named=()) -> dict:
    """A mechanism's parameters as ``{symbol: float}``: keys are symbols or names (of the symbols in
    `named`, the loops' own), values finite numbers, non-negative where the symbol is declared so, and
    the input is none of them.

    Examples
    --------
    >>> import sympy as sp
    >>> r, t = sp.symbols("r t")
    >>> read_parameters({"r": 2}, t, {r, t})
    {r: 2.0}
    """
    from .units import finite

    if not hasattr(parameters or {}, "items"):
        raise InputError(f"parameters must map symbols (or names) to values, got {parameters!r:.80}")
    out = {}
    for key, value in (parameters or {}).items():
        sym = as_symbol(key, named)
        if sym == input_symbol:
            raise InputError(f"{sym} is the input; it cannot also be a parameter with a value")
        value = finite(f"parameter {sym}", value)
        if value < 0 and (sym.is_positive or sym.is_nonnegative):
            raise InputError(f"parameter {sym} = {value:g} is negative, but {sym} is declared non-negative")
        out[sym] = value
    return out


def check_lengths(model: dict, value_of: dict, every_link: bool = False) -> None:
    """A parameter that is the length of a link (a vector that turns) must be positive.

    A subtracted vector is written ``(-r4, theta4)``: the sign belongs in
    the loop, not in the value. The length of a vector of fixed direction
    (``(-e, pi/2)``) is an offset and may have either sign; so may a
    parameter declared real and no more (``sympy.Symbol("e", real=True)``), unless
    ``every_link`` (the dimensions of a scene written as loops, all declared
    real). ``model`` is :func:`describe`'s, ``value_of`` maps parameter
    names to values. The ``ValueError`` names the parameter, also as its
    attribute ``parameter``.

    Examples
    --------
    >>> model = {"parameters": [["r2", False, False]], "loops": [{"name": "O2-A", "lengths": ["r2"], "links": ["r2"]}]}
    >>> check_lengths(model, {"r2": -1.0})                  # declared real: a signed offset
    >>> check_lengths(model, {"r2": -1.0}, every_link=True)
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: loop 'O2-A': length r2 = -1 is negative (a negative length mirrors the linkage): lengths must be positive; write the vector as (-r2, angle) in the loop
    """
    given = every_link
    # a signed offset is declared real (and not non-negative); undeclared and non-negative ones are lengths
    lengths = {p for p, non_negative, real_unknown in model["parameters"] if real_unknown or non_negative}
    for lp in model["loops"]:
        for sym in lp.get("links", lp["lengths"]):
            if not (every_link or sym in lengths):
                continue
            value = value_of.get(sym)
            if value is not None and value <= 0:
                why = ("is zero (a link of no length: its angle is free, or its input moves nothing)" if value == 0
                       else f"= {value:g} is negative (a negative length mirrors the linkage)")
                error = InputError(
                    f"loop '{lp['name']}': length {sym} {why}: lengths must be positive"
                    + ("" if value == 0 else f"; write the vector as (-{sym}, angle) in the loop")
                    + ("" if given else f", or declare {sym} real (sympy.Symbol('{sym}', real=True)) if it is "
                       "a signed offset")
                )
                error.parameter = sym
                raise error


def check_symbols(loops, input_symbol, parameters) -> None:
    """Every symbol of every loop is the input, a parameter with a value, or an unknown of it or of an
    earlier loop; the input appears in some loop; no loop solves for a symbol already known.

    Examples
    --------
    >>> import sympy as sp
    >>> t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    >>> loop = Loop.from_vectors([(1, t2), (3, t3), (-3, t4), (-4, 0)], [t3, t4], name="O2ABO4")
    >>> check_symbols([loop], sp.Symbol("theta22"), {})
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: the input theta22 appears in no loop: the loops use theta2, which has no value; is it the input?
    """
    import sympy as sp

    writes = {}  # name -> {symbol: the first loop that writes it}
    for lp in loops:
        for sym in set().union(*(r.free_symbols for r in lp.residuals)):
            writes.setdefault(sym.name, {}).setdefault(sym, lp.name)
    for name, where in sorted(writes.items()):
        if len(where) > 1:
            (a, la), (b, lb) = sorted(where.items(), key=lambda item: sp.srepr(item[0]))[:2]
            whose = f"loop '{la}' writes {sp.srepr(a)} and loop '{lb}' {sp.srepr(b)}" if la != lb else (
                f"loop '{la}' writes both {sp.srepr(a)} and {sp.srepr(b)}")
            raise InputError(f"{whose}: two different sympy symbols named '{name}' (their assumptions differ), "
                             "which numkin cannot take for one; make each symbol once (sympy.symbols) and use it "
                             "in every loop")
    known = {input_symbol} | set(parameters)
    used = set().union(*(r.free_symbols for lp in loops for r in lp.residuals))
    if input_symbol not in used:
        unknowns = set().union(*(set(lp.unknowns) for lp in loops))
        others = sorted(map(str, used - known - unknowns))
        raise InputError(
            f"the input {input_symbol} appears in no loop"
            + (f": the loops use {', '.join(others)}, " + ("which has no value; is it the input?" if len(others) == 1
               else "which have no values; is one of them the input?") if others else "")
        )
    for lp in loops:
        clash = set(lp.unknowns) & known
        if clash:
            raise InputError(
                f"loop '{lp.name}': {sorted(map(str, clash))} already known "
                "(the input, a parameter or an unknown of an earlier loop)"
            )
        free = set().union(*(r.free_symbols for r in lp.residuals))
        stray = free - known - set(lp.unknowns)
        if stray:
            import difflib

            unused = [str(p) for p in parameters if p not in used]
            near = [f"parameter {m[0]} is given but used by no loop: a misspelling of {s}?" for s in sorted(map(str, stray))
                    for m in [difflib.get_close_matches(s, unused, n=1, cutoff=0.6)] if m]
            raise InputError(
                f"loop '{lp.name}' uses symbol(s) {', '.join(sorted(map(str, stray)))} that are neither "
                "its unknowns, earlier unknowns, the input nor a parameter with a value"
                + "".join(f"; {text}" for text in near)
            )
        known |= set(lp.unknowns)

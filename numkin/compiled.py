"""Sympy expressions compiled once into vectorised numpy functions.

Everything symbolic about a mechanism happens here, once, when it is built
(or, for what only sweeps need, at its first sweep); nothing symbolic runs
inside a loop over input angles. Compilation is cached by the expressions'
shape, so every four-bar (its dimensions are symbols with values) shares one
set of functions.

* :func:`vector_function` -- numpy functions of whole arrays (real or
  complex, for complex-step differentiation) returning stacked arrays;
* :func:`scalar_function` -- ``math``-module functions of single floats, for
  the sequential steps of a continuation;
* :class:`~numkin.blocks.BlockStructure` (in :mod:`numkin.blocks`, re-exported
  here) -- Newton steps, loop orientations and condition numbers that use
  the block lower-triangular shape of the loops' Jacobian;
* :class:`CompiledMechanism` -- all of a mechanism's functions.
"""

from __future__ import annotations

import math
from functools import cached_property, lru_cache

import numpy as np

from .blocks import BlockStructure, stack_rows

__all__ = [
    "vector_function", "scalar_function", "CompiledMechanism", "BlockStructure", "stack_rows", "MATH_ERRORS",
    "acceleration_rhs", "rates", "jacobian_rows", "KERNEL_ROLES", "compiled_once", "export_function",
    "import_function", "KernelNotKept", "underivable",
]

#: The numeric functions of a mechanism a bundle of the kernel cache keeps: role -> attribute of
#: :class:`CompiledMechanism`. The first three are compiled with the mechanism, the others on first use
#: (``"rates"``, the fused velocity and acceleration solve, is kept with the loops' blocks it was written for).
KERNEL_ROLES = {"F": "_F", "J": "_J", "F_t": "_Ft", "fast": "_fast", "scalar_F": "scalar_F", "scalar_FJT": "scalar_FJT",
                "second": "_second", "rates": "_rates"}

#: Errors the ``math`` module raises where numpy returns NaN or inf.
MATH_ERRORS = (ValueError, ZeroDivisionError, OverflowError)


@lru_cache(maxsize=512)
def _lambdify(exprs: tuple, args: tuple, modules: str, cse: bool):
    """``sympy.lambdify`` once per (expressions, arguments): mechanisms of one shape share code.

    Parameters enter as symbols, so e.g. every four-bar compiles to the same
    functions; building another one costs no new compilation. The generated
    code is also kept on disk between runs (:mod:`numkin.kernel_cache`).
    """
    from .kernel_cache import cached_lambdify

    return cached_lambdify(exprs, args, modules, cse)


def vector_function(exprs, args, varying=None):
    """Lambdify a list of expressions into ``f(*args) -> ndarray of shape (len(exprs), ...)``.

    ``varying`` are the arguments passed as arrays (default: all); entries
    that depend on none of them (a zero in a Jacobian, a parameter) are
    broadcast to the arrays' shape, so the result is always one stacked
    array. Its dtype follows the arguments (complex in, complex out).
    """
    import sympy as sp

    exprs = [sp.sympify(e) for e in exprs]
    args = tuple(args)
    varying = set(args if varying is None else varying)
    moving = [k for k, e in enumerate(exprs) if e.free_symbols & varying]
    fixed = [k for k in range(len(exprs)) if k not in set(moving)]
    f_moving = _lambdify(tuple(exprs[k] for k in moving), args, "numpy", True) if moving else None
    f_fixed = _lambdify(tuple(exprs[k] for k in fixed), args, "numpy", False) if fixed else None
    f = _stacked(moving, fixed, f_moving, f_fixed)
    f.expressions = exprs
    return f


def _stacked(moving: list, fixed: list, f_moving, f_fixed):
    """``f(*values)``: the rows of ``f_moving`` (arrays) and ``f_fixed`` (numbers) stacked in one array."""
    m = len(moving) + len(fixed)

    if not fixed:

        def f(*values):
            return np.array(f_moving(*values))

    else:

        def f(*values):
            shape = next((np.shape(v) for v in values if np.ndim(v)), ())
            arr = np.empty((m, *shape), dtype=np.result_type(*values, float))
            arr[fixed] = np.array(f_fixed(*values), dtype=arr.dtype).reshape((len(fixed),) + (1,) * len(shape))
            if moving:
                arr[moving] = f_moving(*values)
            return arr

    f.parts = ("stacked", list(moving), list(fixed), f_moving, f_fixed)
    return f


def hoist_fixed_terms(exprs, unknowns, inputs=()):
    """Rewrite expressions so that a Newton solve recomputes only what depends on the unknowns.

    Two rewrites, both exact up to rounding:

    * ``sin``/``cos`` of a sum ``a + c`` where ``a`` holds the unknowns and
      ``c`` does not (``cos(phi + offset)``) is expanded by the addition
      theorem when ``sin(a)`` or ``cos(a)`` occurs anyway, so no new
      transcendental function of the unknowns is evaluated;
    * every function call free of the unknowns (``cos(theta)``,
      ``cos(offset)``) is replaced by a symbol ``_numkin_fixed<k>``;
    * then, in every sum, the terms free of the unknowns are gathered into
      one symbol where they hold ``inputs`` or a replaced call and take an
      operation to form (``r2*cos(theta2) - r1``), and so is a whole
      expression free of the unknowns that holds them: formed once per
      sweep, not at every Newton iteration.

    Returns ``(new expressions, symbols, their expressions)``: evaluate the
    latter once per sweep and pass them as extra arguments.

    Examples
    --------
    >>> import sympy as sp
    >>> t, a, b, r1, r2 = sp.symbols("t a b r1 r2")
    >>> exprs, names, fixed = hoist_fixed_terms([r2 * sp.cos(t) + sp.cos(a) - r1, sp.sin(b)], [a, b], [t])
    >>> exprs, names, fixed
    ([_numkin_fixed1 + cos(a), sin(b)], [_numkin_fixed1], [-r1 + r2*cos(t)])
    """
    import sympy as sp

    unknowns = set(unknowns)
    exprs = [sp.sympify(e) for e in exprs]
    trig = set().union(*(e.atoms(sp.sin, sp.cos) for e in exprs))
    expand = {}
    for f in trig:
        arg = f.args[0]
        if not isinstance(arg, sp.Add):
            continue
        a = sp.Add(*[term for term in arg.args if term.free_symbols & unknowns])
        c = arg - a
        if a == 0 or c == 0 or not ({sp.sin(a), sp.cos(a)} & trig):
            continue
        if isinstance(f, sp.sin):
            expand[f] = sp.sin(a) * sp.cos(c) + sp.cos(a) * sp.sin(c)
        else:
            expand[f] = sp.cos(a) * sp.cos(c) - sp.sin(a) * sp.sin(c)
    if expand:
        exprs = [e.xreplace(expand) for e in exprs]
    fixed = sorted(
        {f for e in exprs for f in e.atoms(sp.Function) if f.free_symbols and not (f.free_symbols & unknowns)},
        key=sp.default_sort_key,
    )
    names = [sp.Symbol(f"_numkin_fixed{k}") for k in range(len(fixed))]
    if fixed:
        exprs = [e.xreplace(dict(zip(fixed, names))) for e in exprs]
    back = dict(zip(names, fixed))
    groups: dict = {}

    moving = set(inputs) | set(names)

    def varies(e) -> bool:
        """Free of the unknowns, holding the input or a replaced call, and an operation to form."""
        return not e.is_Atom and not (e.free_symbols & unknowns) and bool(e.free_symbols & moving)

    def gathered(e):
        if e.is_Atom:
            return e
        args = [gathered(a) for a in e.args]
        if isinstance(e, sp.Add):
            free = [a for a in args if not (a.free_symbols & unknowns)]
            rest = [a for a in args if a.free_symbols & unknowns]
            group = sp.Add(*free)
            if rest and varies(group):
                return sp.Add(symbol_of(group), *rest)
        return e.func(*args) if args != list(e.args) else e

    def symbol_of(group):
        if group not in groups:
            groups[group] = sp.Symbol(f"_numkin_fixed{len(names) + len(groups)}")
        return groups[group]

    exprs = [symbol_of(e) if varies(e) else gathered(e) for e in exprs]
    for group, name in groups.items():
        names.append(name)
        fixed.append(group.xreplace(back))
    used = set().union(*(e.free_symbols for e in exprs))
    kept = [k for k, name in enumerate(names) if name in used]  # a call now only inside a gathered sum goes
    return exprs, [names[k] for k in kept], [fixed[k] for k in kept]


def scalar_function(exprs, args):
    """Lambdify expressions for *scalar* (float) arguments: ``f(*args) -> list of floats``.

    Uses the ``math`` module, some ten times faster than numpy on single
    numbers (the sequential steps of a continuation). Where ``math`` lacks a
    function of the expressions it falls back to numpy. Domain errors
    (``math.sqrt(-1)``) are raised as ``ValueError`` etc. (:data:`MATH_ERRORS`);
    callers treat them as a non-finite result.
    """
    import sympy as sp

    exprs = tuple(sp.sympify(e) for e in exprs)
    args = tuple(args)
    f = _lambdify(exprs, args, "math", True)
    try:
        f(*([0.375] * len(args)))
    except MATH_ERRORS:
        pass
    except Exception:  # a function the math module does not have
        f = _floats(vector_function(exprs, args))
    return f


def _floats(g):
    """``f(*values) -> list of floats`` from a stacked-array function ``g`` (a scalar function through numpy)."""

    def f(*values):
        return [float(v) for v in g(*values)]

    f.parts = ("floats", g)
    return f


class KernelNotKept(Exception):
    """A generated function that the kernel cache cannot keep (its code uses more than numpy or math)."""


def export_function(f, kernels: list):
    """How to rebuild ``f`` from kept kernels (JSON data); the kernels it needs are appended to ``kernels``.

    Raises :class:`KernelNotKept` if a piece of ``f`` cannot be kept.
    """
    if f is None:
        return None
    parts = getattr(f, "parts", None)
    if parts is not None and parts[0] == "stacked":
        _, moving, fixed, f_moving, f_fixed = parts
        return {"moving": moving, "fixed": fixed, "f_moving": export_function(f_moving, kernels),
                "f_fixed": export_function(f_fixed, kernels)}
    if parts is not None and parts[0] == "floats":
        return {"floats": export_function(parts[1], kernels)}
    entry = getattr(f, "numkin_kernel", None)
    if entry is None:
        raise KernelNotKept(getattr(f, "__name__", repr(f)))
    kernels.append(entry)
    return {"kernel": len(kernels) - 1}


def import_function(spec, functions: list):
    """The function :func:`export_function` described, from the loaded kernels ``functions``."""
    if spec is None:
        return None
    if "kernel" in spec:
        return functions[spec["kernel"]]
    if "floats" in spec:
        return _floats(import_function(spec["floats"], functions))
    return _stacked(spec["moving"], spec["fixed"], import_function(spec["f_moving"], functions),
                    import_function(spec["f_fixed"], functions))



class compiled_once(cached_property):
    """A cached property whose value may come ready-made from ``instance._loaded`` (the kernel
    cache), else is computed and reported to ``instance._on_compile()`` if set (so the kernel
    cache keeps it)."""

    def __get__(self, instance, owner=None):
        if instance is None:
            return self
        known = instance.__dict__
        if self.attrname in known:
            return known[self.attrname]
        loaded = known.get("_loaded", {}).pop(self.attrname, None)
        if loaded is not None:  # from the kernel cache: installed on first use, like a compiled one
            known[self.attrname] = loaded
            return loaded
        value = super().__get__(instance, owner)
        hook = known.get("_on_compile")
        if hook is not None:
            hook()
        return value


#: Attributes of a :class:`CompiledMechanism` that are sympy objects (derived on first use when loaded from a bundle).
_SYMBOLIC = ("residuals", "unknowns", "input_symbol", "parameters", "args", "varying", "jacobian_matrix")


def underivable(loops, input_symbol) -> str:
    """Which loop's equation has a derivative sympy leaves unevaluated (``Derivative(im(z), z)`` of ``Abs`` of a
    ``z`` not declared real), which no printer writes as code, and what to do; ``""`` if none is found."""
    import sympy as sp

    for lp in loops:
        for k, r in enumerate(lp.residuals):
            for u in [*lp.unknowns, input_symbol]:
                left = r.diff(u).atoms(sp.Derivative)
                if left:
                    return (f"loop '{lp.name}': equation {k + 1} has no derivative sympy can write as code with respect "
                            f"to {u} ({sorted(map(str, left))[0]}): a function such as Abs or sign of symbols not "
                            "declared real; declare them real (sympy.symbols(..., real=True)) or write the equation "
                            "without it")
    return ""


class CompiledMechanism:
    """Numeric functions of a mechanism's stacked loop equations ``F(q, t) = 0``.

    ``q`` (n unknowns) are passed as rows of an (n, N) array, ``t`` as an (N,)
    array of inputs, parameter values are bound when called. The position
    functions (``F``, ``J`` and ``F_t``) are compiled on construction; the
    second-order function used for accelerations only on first use.
    :meth:`from_kernels` makes one from kept kernels without sympy: its
    symbolic attributes (``residuals``, ``jacobian_matrix``, ``unknowns``,
    ``args``, ...) are then derived when first read.

    Parameters
    ----------
    residuals : list of sympy expressions
        Stacked residuals of all loops, in loop order.
    unknowns : list of sympy symbols
    input_symbol : sympy symbol
    parameters : list of sympy symbols
    """

    def __init__(self, residuals, unknowns, input_symbol, parameters):
        self._symbolic(residuals, unknowns, input_symbol, parameters)
        self.n = len(self.unknowns)
        jac = self.jacobian_matrix
        self._F = vector_function(list(self.residuals), self.args, self.varying)
        self._J = vector_function(list(jac), self.args, self.varying)
        self._Ft = vector_function(list(self.residuals.diff(input_symbol)), self.args, self.varying)

    def _symbolic(self, residuals, unknowns, input_symbol, parameters) -> None:
        import sympy as sp

        self.residuals = sp.Matrix(residuals)
        self.unknowns = list(unknowns)
        self.input_symbol = input_symbol
        self.parameters = list(parameters)
        self.args = [*self.unknowns, input_symbol, *self.parameters]
        self.jacobian_matrix = self.residuals.jacobian(self.unknowns)
        self.varying = [*self.unknowns, input_symbol]

    @classmethod
    def from_kernels(cls, n: int, roles: dict, functions: list, symbolic) -> "CompiledMechanism":
        """A compiled mechanism of ``n`` unknowns from kept kernels, without sympy.

        ``roles`` maps each of :data:`KERNEL_ROLES` to what :func:`export_function`
        wrote; ``functions`` are the loaded kernels; ``symbolic()`` returns
        ``(residuals, unknowns, input_symbol, parameters)`` when a symbolic
        attribute is first read.
        """
        self = cls.__new__(cls)
        self.n = int(n)
        self._model = symbolic
        self._loaded = {}
        for role, spec in roles.items():
            if role == "fast":
                value = (import_function(spec["rows"], functions), import_function(spec["terms"], functions))
            elif role == "rates":
                value = (tuple((int(a), int(b)) for a, b in spec["blocks"]), import_function(spec["f"], functions))
            else:
                value = import_function(spec, functions)
            if role in ("F", "J", "F_t"):
                self.__dict__[KERNEL_ROLES[role]] = value
            else:
                self._loaded[KERNEL_ROLES[role]] = value
        for role in ("F", "J", "F_t"):
            if KERNEL_ROLES[role] not in self.__dict__:
                raise KeyError(role)
        return self

    def __getattr__(self, name):
        model = self.__dict__.get("_model")
        if name in _SYMBOLIC and model is not None:
            del self.__dict__["_model"]
            self._symbolic(*model())
            return getattr(self, name)
        raise AttributeError(f"'CompiledMechanism' object has no attribute {name!r}")

    def export_kernels(self, kernels: list) -> dict:
        """The numeric functions compiled so far, as :func:`export_function` describes them
        (role -> JSON data; the kernels are appended to ``kernels``)."""
        out = {}
        known = {**self.__dict__.get("_loaded", {}), **self.__dict__}
        for role, attr in KERNEL_ROLES.items():
            if attr not in known:
                continue
            value = known[attr]
            if role == "fast":
                out[role] = {"rows": export_function(value[0], kernels), "terms": export_function(value[1], kernels)}
            elif role == "rates":
                out[role] = {"blocks": [list(b) for b in value[0]], "f": export_function(value[1], kernels)}
            else:
                out[role] = export_function(value, kernels)
        return out

    @compiled_once
    def _fast(self):
        """Residual-and-Jacobian rows compiled for many points, with what does not change
        during a Newton solve taken out: see :func:`hoist_fixed_terms`."""
        exprs = list(self.residuals) + list(self.jacobian_matrix)
        exprs, names, fixed = hoist_fixed_terms(exprs, self.unknowns, [self.input_symbol])
        rows = _lambdify(tuple(exprs), (*self.unknowns, self.input_symbol, *names, *self.parameters), "numpy", True)
        terms = _lambdify(tuple(fixed), (self.input_symbol, *self.parameters), "numpy", True) if fixed else None
        return rows, terms

    def fixed_terms(self, t, p) -> list:
        """The functions of the input and parameters alone that :meth:`FJ_rows` uses (e.g.
        ``cos(theta)``), evaluated once for a sweep's inputs ``t``."""
        terms = self._fast[1]
        return [] if terms is None else terms(t, *p)

    @property
    def FJ_kernel(self):
        """The function behind :meth:`FJ_rows`: ``FJ_kernel(*q, t, *fixed, *p) -> rows``, for callers
        that evaluate it many times with the same ``fixed`` and ``p``."""
        return self._fast[0]

    def FJ_rows(self, q, t, p, fixed=None) -> list:
        """Residuals and Jacobian in one call, as a list of n + n*n rows: rows 0..n-1 the
        residuals, then the Jacobian's entries row by row (``n + i * n + j`` is entry (i, j)).

        Each row is an (N,) array, or a number where the entry is constant.
        ``fixed`` is :meth:`fixed_terms` at ``t`` (computed here if not given).
        """
        if fixed is None:
            fixed = self.fixed_terms(t, p)
        return self._fast[0](*q, t, *fixed, *p)

    @compiled_once
    def scalar_F(self):
        """Residuals at one point: ``scalar_F(*q, t, *p) -> list`` (``math`` module, floats)."""
        return scalar_function(list(self.residuals), self.args)

    @compiled_once
    def scalar_FJT(self):
        """Residuals, Jacobian rows and dF/dt at one point, one flat list of n + n*n + n floats."""
        exprs = list(self.residuals) + list(self.jacobian_matrix) + list(self.residuals.diff(self.input_symbol))
        return scalar_function(exprs, self.args)

    def F(self, q, t, p):
        """Residuals, shape (n, N)."""
        return self._F(*q, t, *p)

    def J(self, q, t, p):
        """Jacobians dF/dq, shape (N, n, n)."""
        n = self.n
        return np.moveaxis(self._J(*q, t, *p).reshape(n, n, -1), -1, 0)

    def F_t(self, q, t, p):
        """Partial derivative dF/dt, shape (n, N)."""
        return self._Ft(*q, t, *p)

    def tangent(self, q, t, p):
        """dq/dt along the solution (t is the input), shape (n, N): solves ``J q' = -F_t``."""
        rhs = -self.F_t(q, t, p).T[..., None]
        return np.linalg.solve(self.J(q, t, p), rhs)[..., 0].T

    @compiled_once
    def _second(self):
        """The acceleration right-hand side ``G_q q' + G_t`` (``G = J q' + F_t``) at many points:
        ``f(*q, *dq, t, *p) -> n rows`` ((N,) arrays, or numbers where constant). Derived on
        first use; generated code kept like every kernel's (in memory per shape, on disk)."""
        import sympy as sp

        n = self.n
        dq = [sp.Symbol(f"_numkin_dq{k}") for k in range(n)]
        t = self.input_symbol
        g = self.jacobian_matrix * sp.Matrix(dq) + self.residuals.diff(t)
        h = g.jacobian(self.unknowns) * sp.Matrix(dq) + g.diff(t)
        return _lambdify(tuple(h), (*self.unknowns, *dq, t, *self.parameters), "numpy", True)

    def rates_kernel(self, blocks):
        """The generated function of :func:`rates` for the loops' ``blocks`` ((start, stop) of each
        loop's unknowns): ``f(J, q, t, p, dq, d2q)`` (see :mod:`numkin.rates_kernel`), or None where
        it cannot be written out (a block larger than 2 x 2). Derived on first use, once per shape of
        loop equations; kept like every kernel (in memory, on disk, in the mechanism's bundle)."""
        blocks = tuple((int(a), int(b)) for a, b in blocks)
        known = self.__dict__
        kept = known.get("_rates")
        if kept is None:
            kept = known.get("_loaded", {}).pop("_rates", None)
            if kept is not None:
                known["_rates"] = kept
        if kept is not None and kept[0] == blocks:
            return kept[1]
        f = _rates_kernel(tuple(self.residuals), tuple(self.unknowns), self.input_symbol, tuple(self.parameters),
                          blocks)
        known["_rates"] = (blocks, f)
        hook = known.get("_on_compile")
        if hook is not None:
            hook()
        return f

    def second_derivative(self, q, dq, t, p):
        """d2q/dt2 along the solution, shape (n, N): solves ``J q'' = -(G_q q' + G_t)`` (dense LU)."""
        N = np.shape(t)[0] if np.ndim(t) else 1
        rhs = -stack_rows(self._second(*q, *dq, t, *p), N).T[..., None]
        return np.linalg.solve(self.J(q, t, p), rhs)[..., 0].T

    def point_function(self, exprs):
        """Compile expressions of (q, t, parameters), e.g. a point's coordinates."""
        return vector_function(exprs, self.args, self.varying)


def acceleration_rhs(compiled: CompiledMechanism, q, dq, t, p) -> list:
    """``G_q q' + G_t`` with ``G = J q' + dF/dt`` at every point, as n rows.

    The acceleration equations are ``J q'' = -(G_q q' + G_t)``. Derived
    once per shape of loop equations with sympy (on first use) and
    generated and kept like every other kernel. Rows are (N,) arrays, or
    numbers where an entry is constant; ``dq`` is ``q'`` (n, N).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> m = linkages.slider_crank(80, 200)
    >>> q = np.array([[np.pi], [280.0]])
    >>> rows = acceleration_rhs(m.compiled, q, np.zeros((2, 1)), np.zeros(1), m.parameter_values)
    >>> [float(np.round(r[0], 9)) for r in rows]   # x'' = -r cos(theta) when q' = 0: [x: -r, y: 0]
    [-80.0, -0.0]
    """
    return list(compiled._second(*q, *dq, t, *p))


@lru_cache(maxsize=128)
def _rates_kernel(residuals: tuple, unknowns: tuple, input_symbol, parameters: tuple, blocks: tuple):
    """The fused rates function for one shape of loop equations and blocks (see :meth:`CompiledMechanism.rates_kernel`)."""
    from .kernel_cache import cached_source
    from .rates_kernel import RATES_NARGS, rates_source

    def build():
        return rates_source(residuals, unknowns, input_symbol, parameters, blocks)

    return cached_source(residuals, (*unknowns, input_symbol, *parameters), f"rates {list(blocks)}", RATES_NARGS,
                         build)


def jacobian_rows(compiled: CompiledMechanism, q, t, p):
    """The Jacobian ``dF/dq`` at every point as n*n rows (entry (i, j) is row ``i * n + j``)."""
    n = compiled.n
    return compiled.J(q, t, p).reshape(-1, n * n).T


def rates(compiled: CompiledMechanism, blocks: BlockStructure, q, t, p, jac=None):
    """dq/dt and d2q/dt2 at every point by block-triangular solves: two (n, N) arrays.

    ``J q' = -dF/dt``, then ``J q'' = -(G_q q' + G_t)``, both solved loop by
    loop: the cost is linear in the number of loops and every operation runs
    on whole arrays. For real values and loops of one or two unknowns both
    solves are one generated function (:meth:`CompiledMechanism.rates_kernel`,
    :mod:`numkin.rates_kernel`) that shares the right-hand sides' terms and
    the blocks' determinants; otherwise :meth:`BlockStructure.solve_negated`
    solves each. ``jac``: the Jacobian rows at ``q`` if known (a sweep keeps
    its last), else computed. Columns where a diagonal block is singular or a
    value not finite are NaN (both arrays where ``dq`` is not finite).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> m = linkages.slider_crank(80, 200)
    >>> s = m.sweep(np.radians([0.0, 90.0]))
    >>> dq, d2q = rates(m.compiled, m.block_structure, s.values, s.inputs, m.parameter_values)
    >>> print(np.round(dq[1], 9) + 0.0, np.round(d2q[1, :1], 9))   # x' = -r at 90 deg; x'' = -r (1 + r/l) at 0
    [  0. -80.] [-112.]
    """
    N = np.size(t)
    with np.errstate(all="ignore"):
        if jac is None:
            jac = jacobian_rows(compiled, q, t, p)
        fused = None
        if getattr(q, "dtype", None) == float and getattr(t, "dtype", None) == float:
            fused = compiled.rates_kernel(blocks.blocks)
        if fused is not None:
            both = np.empty((2, compiled.n, N))
            dq, d2q = both
            try:
                fused(jac, q, t, p, dq, d2q)
                total = both.sum()
            except ZeroDivisionError:  # a block singular everywhere (constant entries): solved below
                fused = None
        if fused is None:
            dq, _ = blocks.solve_negated(jac, compiled.F_t(q, t, p), N)
            d2q, _ = blocks.solve_negated(jac, compiled._second(*q, *dq, t, *p), N)
            total = dq.sum() + d2q.sum()
        if not (np.isfinite(total) if isinstance(total, complex) else math.isfinite(total)):
            bad = ~np.isfinite(dq.sum(axis=0))  # a singular block or a value not finite
            dq[:, bad] = np.nan
            d2q[:, bad | ~np.isfinite(d2q.sum(axis=0))] = np.nan
    return dq, d2q

"""A mechanism built from the kernel cache: its compiled kernels and names without sympy.

:meth:`CachedModel.from_model` builds a :class:`~numkin.Mechanism` whose loops
``model()`` writes; when :mod:`numkin.kernel_cache` holds a bundle for its
key, the mechanism is made from the bundle's names and kernels, and sympy is
imported only when a symbolic attribute (the loops, the parameters' symbols,
a point's expressions) is first read. :class:`~numkin.Mechanism` inherits this.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from typing import Callable

from .compiled import CompiledMechanism, KernelNotKept, export_function, import_function
from .errors import InputError
from .loops import LazyPoints, Loop, SymbolName, as_symbol, describe, read_points

__all__ = ["CachedModel", "count_message"]

#: Keywords of :class:`~numkin.Mechanism` besides the loops, input, parameters, points, name and unit.
_OPTIONS = ("guess", "guess_input", "links", "ground", "length_scale", "assembly_check", "branch", "quantities")


def count_message(name, values, parameters) -> str:
    """What is wrong when ``values`` and ``parameters`` differ in number: the same words from the sympy model
    and from the kernel cache."""
    return f"{name}: {len(values)} parameter values for {len(parameters)} parameters {list(parameters)}"


class CachedModel:
    """The kernel-cache path of :class:`~numkin.Mechanism` (a mixin: ``from_model`` and the lazy sympy model)."""

    @classmethod
    def from_model(cls, key: str, model: Callable, values, **options) -> "CachedModel":
        """A mechanism whose loops ``model()`` writes, built from the kernel cache when it holds them.

        Parameters
        ----------
        key : str
            What the mechanism is built from, as :func:`numkin.kernel_cache.bundle_key` makes it:
            two models with one key must write the same loops and points.
        model : callable
            ``model() -> (loops, input, parameter symbols, points)``; called only when the cache
            misses or when a symbolic attribute (``loops``' expressions, ``parameters``,
            ``points``' expressions, ...) is first read.
        values : sequence of float
            The parameters' values, in the order ``model`` lists their symbols.
        **options
            The keywords of :class:`Mechanism` (``name``, ``guess``, ``links``, ...).

        Examples
        --------
        >>> import sympy as sp
        >>> from numkin import Loop, Mechanism
        >>> def model():
        ...     t, x = sp.symbols("t x", real=True)
        ...     r = sp.Symbol("r", real=True)
        ...     return [Loop([x - r * sp.cos(t)], [x])], t, [r], {"P": (x, 0)}
        >>> m = Mechanism.from_model("a point on a circle's shadow", model, [2.0], guess={"x": 1.0})
        >>> m.unknowns, float(m.solve(0.0).x[0])
        (('x',), 2.0)
        """
        from . import kernel_cache

        if not isinstance(key, str):
            raise InputError(f"key must be a string (what the mechanism is built from), got {key!r:.60}")
        if not callable(model):
            raise InputError(f"model must be a function () -> (loops, input, parameter symbols, points), got "
                             f"{model!r:.60}")
        if isinstance(values, (str, bytes)) or not isinstance(values, Iterable):
            raise InputError(f"values must be the parameters' values in the order model() lists them, got "
                             f"{type(values).__name__} {values!r:.60}")
        values = list(values)
        found = kernel_cache.load_bundle(key)
        if found is not None:
            try:
                return cls._from_bundle(key, found, model, values, options)
            except (KeyError, TypeError, IndexError, AttributeError):
                pass  # a bundle of another shape: built again below
        built = model()
        if not (isinstance(built, (tuple, list)) and len(built) == 4):
            raise InputError(f"model() must return (loops, input, parameter symbols, points), got {built!r:.80}")
        loops, input_symbol, symbols, points = built
        symbols = list(symbols)
        if len(values) != len(symbols):
            raise InputError(count_message(options.get("name", "mechanism"), values, [str(s) for s in symbols]))
        mech = cls(loops, input_symbol, dict(zip(symbols, values)), points=points, **options)
        mech._keep(key)
        return mech

    def _keep(self, key: str) -> None:
        """Store this mechanism's kernels compiled so far, and its names, as a bundle of the kernel cache;
        kernels compiled later are added as they come (:class:`~numkin.compiled.compiled_once`)."""
        from . import kernel_cache

        if kernel_cache.cache_dir() is None:
            return
        kernels: list = []
        try:
            model = describe(self.loops, self.input_symbol, self.parameters, self.points)
            model["kernels"] = self.compiled.export_kernels(kernels)
            if "point_function" in self.__dict__ or "point_function" in self.__dict__.get("_loaded", {}):
                model["point_kernel"] = export_function(self.point_function, kernels)
        except KernelNotKept:
            return
        model["zeros"] = [list(z) for z in self._zeros()]
        kernel_cache.store_bundle(key, model, kernels)
        self.__dict__["_on_compile"] = self.compiled.__dict__["_on_compile"] = lambda: self._keep(key)

    @classmethod
    def _from_bundle(cls, key: str, found, model: Callable, values: list, options: dict) -> "CachedModel":
        """The mechanism from a bundle of the kernel cache: no sympy until a symbolic attribute is read."""
        kept, functions = found
        options = dict(options)
        name, length_unit = options.pop("name", "mechanism"), options.pop("length_unit", "mm")
        setup = {k: options.pop(k, None) for k in _OPTIONS}
        if options:
            raise TypeError(f"Mechanism.from_model() got unexpected keyword(s) {sorted(options)}")
        self = cls.__new__(cls)
        self._setup(kept, values, name=name, length_unit=length_unit, **setup)
        self._model = model
        self._input_assumptions = dict(kept["input_assumptions"])
        self.loops = [Loop.placeholder(lp["name"], self._materialize) for lp in kept["loops"]]
        self.points = LazyPoints(kept["points"], self._materialize)
        self._jacobian_zeros = kept["zeros"]
        self.compiled = CompiledMechanism.from_kernels(len(self.unknowns), kept["kernels"], functions, self._symbolic)
        if "point_kernel" in kept:
            self._loaded = {"point_function": import_function(kept["point_kernel"], functions)}
        self.__dict__["_on_compile"] = self.compiled.__dict__["_on_compile"] = lambda: self._keep(key)
        self.add_quantities(self.__dict__.pop("_declared"))
        return self

    def _materialize(self) -> None:
        """Build the sympy model of a mechanism loaded from the kernel cache (on first use of a symbolic attribute)."""
        model = self.__dict__.pop("_model", None)
        if model is None:
            return
        loops, input_symbol, symbols, points = model()
        for stub, lp in zip(self.__dict__["loops"], loops):
            stub.__dict__.pop("_resolve", None)
            stub.__dict__.update(lp.__dict__)
        self.input_symbol = as_symbol(input_symbol)
        self.parameters = dict(zip((as_symbol(s) for s in symbols), self.parameter_values.tolist()))
        self.unknown_symbols = [u for lp in self.loops for u in lp.unknowns]
        self.points.resolved(read_points(points, [*self.unknown_symbols, self.input_symbol, *self.parameters],
                                         self.name))

    def _symbolic(self):
        """``(residuals, unknowns, input symbol, parameter symbols)`` for :class:`CompiledMechanism`."""
        self._materialize()
        return ([r for lp in self.loops for r in lp.residuals], self.unknown_symbols, self.input_symbol,
                list(self.parameters))

    def __getattr__(self, name):
        if name in ("parameters", "unknown_symbols", "_input_symbol") and "_model" in self.__dict__:
            self._materialize()
            return getattr(self, name)
        raise AttributeError(f"'Mechanism' object has no attribute {name!r}")

    @property
    def input_symbol(self):
        """The input as a sympy symbol.

        On a mechanism loaded from the kernel cache before sympy was imported,
        a :class:`~numkin.loops.SymbolName` (a ``str``, the symbol's name) that
        sympy reads as the symbol.
        """
        sym = self.__dict__.get("_input_symbol")
        if sym is not None:
            return sym
        if "_model" not in self.__dict__:
            return self._input_symbol
        if "sympy" in sys.modules:
            return self._sympy_input()
        return SymbolName(self.input_name, self._sympy_input)

    @input_symbol.setter
    def input_symbol(self, value) -> None:
        self.__dict__["_input_symbol"] = value

    def _sympy_input(self):
        """The input symbol, equal to the model's, made without deriving the model."""
        import sympy as sp

        self.input_symbol = sp.Symbol(self.input_name, **self._input_assumptions)
        return self.input_symbol

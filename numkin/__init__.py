"""numkin: numerical kinematics of planar linkages.

A linkage is written as vector-loop closure equations (:class:`Loop`,
:class:`Mechanism`, or a ready-made one from :mod:`numkin.linkages`); its
position is solved over a sweep of the input by Newton-Raphson
(:func:`newton`, :meth:`Mechanism.sweep`); angular velocity and acceleration
come from finite-difference schemes (:mod:`numkin.derivatives`) and from the
differentiated loop equations (:mod:`numkin.analytic`).

Radians inside; degrees only at the edges, always labelled.

Importing numkin is light: the submodules and the names below are loaded on
first use (sympy, pandas and matplotlib only by the stages that need them).

Examples
--------
>>> import numkin
>>> numkin.Mechanism.__name__
'Mechanism'
"""

from __future__ import annotations

import importlib
import sys
import types

from .errors import (AssemblyError, BranchError, ConvergenceError, ConvergenceWarning, DegreesWarning, GuessWarning,
                     InputError, NumkinError)

__version__ = "0.1.0"

#: Name -> module it is defined in (loaded on first use).
_NAMES = {
    "Loop": "loops",
    "LostDigitsWarning": "conditioning",
    "Mechanism": "mechanism",
    "NewtonResult": "newton",
    "newton": "newton",
    "SingularityWarning": "sweep",
    "Sweep": "sweep",
    "SweepEvent": "sweep",
}
#: Submodules reachable as attributes of the package without importing them first.
_SUBMODULES = (
    "analytic", "animate", "bench", "cli", "compare", "compiled", "derived", "derivatives", "expressions", "figures",
    "kinematics", "linkages", "loops", "mechanism", "newton", "outputs", "pipeline", "quantities", "report", "scene",
    "schema", "schemes", "stability", "sweep", "units",
)

__all__ = [
    "AssemblyError",
    "BranchError",
    "ConvergenceError",
    "ConvergenceWarning",
    "DegreesWarning",
    "GuessWarning",
    "Loop",
    "LostDigitsWarning",
    "Mechanism",
    "NewtonResult",
    "InputError",
    "NumkinError",
    "SingularityWarning",
    "Sweep",
    "SweepEvent",
    "analytic",
    "compare",
    "derivatives",
    "kinematics",
    "linkages",
    "newton",
    "units",
]


def __getattr__(name: str):
    """Load a submodule or a public name on first use (PEP 562)."""
    if name in _NAMES:
        value = getattr(importlib.import_module(f".{_NAMES[name]}", __name__), name)
    elif name in _SUBMODULES:
        value = importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module 'numkin' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list:
    return sorted(set(globals()) | set(_NAMES) | set(_SUBMODULES))


class _Package(types.ModuleType):
    """The package module: a public name (``numkin.newton``, the function) is not replaced by the
    submodule of the same name when that submodule is imported."""

    def __setattr__(self, name, value):
        if name in _NAMES and isinstance(value, types.ModuleType):
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package

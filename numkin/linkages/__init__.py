"""Ready-made linkages, built on the same loop API a user writes, and their registry.

Every builder returns a :class:`~numkin.Mechanism` whose unknowns carry the
source documents' names, with a default guess on its documented branch, so
``linkage.sweep(inputs)`` works without a guess. Lengths are in the unit the
dimensions are given in (default mm); angles in rad.

=======================  ===================================  ==========================
linkage                  unknowns                             input
=======================  ===================================  ==========================
``four_bar``             theta3, theta4                       theta2 (crank)
``slider_crank``         theta3, x                            theta (crank)
``quick_return``         r3, theta3, r4, r5                   theta2 (crank)
``six_bar``              theta3, theta4, theta5, x            theta2 (crank)
``chained_four_bars``    phi, psi, beta, gamma                theta (input of linkage 1)
=======================  ===================================  ==========================

Each linkage is one module of this package that defines its builder and a
:class:`~numkin.linkages.base.LinkageSpec` called ``SPEC``; the modules are
found when the package is imported, and :data:`SPECS` holds their specs.
Scenes, figures, the stability suite and the benchmark read a linkage's
dimensions, unknowns, drawing and defaults from its spec
(:func:`spec`, :func:`spec_of`), never from its name. Looking specs up
imports no sympy: the builders import it when called.

Examples
--------
>>> from numkin import linkages
>>> s = linkages.spec("slider_crank")
>>> [d.name for d in s.dimensions], s.unknown_names, s.links
(['crank', 'rod', 'offset'], ('theta3', 'x'), (('O', 'A'), ('A', 'P')))
>>> linkages.spec_of(linkages.four_bar(4, 1, 3, 3)).branches
('open', 'crossed')
"""

from __future__ import annotations

import difflib
import importlib
import pkgutil
import types

from ..errors import InputError
from .base import Dimension, LinkageSpec
from .chained_four_bars import chained_four_bars
from .four_bar import four_bar, grashof
from .quick_return import quick_return
from .six_bar import six_bar
from .slider_crank import slider_crank

__all__ = [
    "four_bar", "slider_crank", "quick_return", "six_bar", "chained_four_bars", "grashof",
    "SPECS", "spec", "spec_of", "register", "LinkageSpec", "Dimension",
]

#: Registry name -> :class:`LinkageSpec` of every ready-made linkage.
SPECS: dict[str, LinkageSpec] = {}

#: Modules of this package that are not linkages.
_NOT_LINKAGES = ("base",)


def register(linkage_spec: LinkageSpec, *, replace: bool = False) -> LinkageSpec:
    """Add a ready-made linkage to :data:`SPECS` (and so to scenes' ``linkage =``).

    Parameters
    ----------
    linkage_spec : LinkageSpec
    replace : bool
        Allow replacing a linkage of the same name.

    Raises
    ------
    ValueError
        If the name is taken (and ``replace`` is false) or the spec is inconsistent
        (a link or ground pivot that is not a named point, a dimension named twice).

    Examples
    --------
    >>> from numkin import linkages
    >>> linkages.register(linkages.spec("four_bar"), replace=True).name
    'four_bar'
    """
    if not isinstance(linkage_spec, LinkageSpec):
        raise TypeError(f"register() takes a LinkageSpec, got {type(linkage_spec).__name__}")
    name = linkage_spec.name
    if not name.isidentifier():
        raise InputError(f"linkage name {name!r} must be an identifier (it is the builder's name)")
    if name in SPECS and not replace and SPECS[name] is not linkage_spec:
        raise InputError(f"a linkage named {name!r} is already registered (pass replace=True)")
    names = [d.name for d in linkage_spec.dimensions]
    if len(set(names)) != len(names):
        raise InputError(f"{name}: a dimension is named twice in {names}")
    points = set(linkage_spec.points)
    used = [p for link in linkage_spec.links for p in link] + list(linkage_spec.ground)
    used += [p for line in linkage_spec.dimension_lines for p in line[:2]]
    for p in used:
        if p not in points:
            raise InputError(f"{name}: point {p!r} of a link, ground or dimension line is not in points {sorted(points)}")
    for kind in (kind for _, kind in linkage_spec.unknowns):
        if kind not in ("angle", "length"):
            raise InputError(f"{name}: an unknown is an 'angle' or a 'length', got {kind!r}")
    SPECS[name] = linkage_spec
    return linkage_spec


def spec(name: str) -> LinkageSpec:
    """The :class:`LinkageSpec` registered as ``name``.

    Raises
    ------
    ValueError
        For an unknown name, with the nearest one suggested.

    Examples
    --------
    >>> spec("quick_return").dimension_lines[0]
    ('O1', 'O2', 'r_1', 1.0)
    """
    try:
        return SPECS[name]
    except (KeyError, TypeError):
        match = difflib.get_close_matches(str(name), list(SPECS), n=1, cutoff=0.5)
        hint = f" (did you mean '{match[0]}'?)" if match else ""
        raise InputError(f"unknown linkage {name!r}{hint}; ready-made linkages: {', '.join(SPECS)}") from None


def spec_of(mechanism) -> LinkageSpec | None:
    """The spec a mechanism was built from, or None for a mechanism written as loops.

    Examples
    --------
    >>> spec_of(quick_return()).name
    'quick_return'
    """
    return SPECS.get(getattr(mechanism, "linkage", None))


def _discover() -> None:
    """Register the SPEC of every linkage module of this package, and its builder as
    ``numkin.linkages.<name>`` (where importing a module of that name bound the module itself)."""
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_") or info.name in _NOT_LINKAGES:
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        linkage_spec = getattr(module, "SPEC", None)
        if isinstance(linkage_spec, LinkageSpec):
            register(linkage_spec)
            if isinstance(globals().get(linkage_spec.name, module), types.ModuleType):
                globals()[linkage_spec.name] = linkage_spec.build


for _module in (four_bar, slider_crank, quick_return, six_bar, chained_four_bars):
    register(importlib.import_module(f"{__name__}.{_module.__name__}").SPEC)
_discover()

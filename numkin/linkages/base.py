"""What a ready-made linkage is: a builder and its :class:`LinkageSpec`.

A spec says everything other stages need to know about a linkage without
building it (and without sympy): the builder, the dimension names, kinds and
units, the input and the unknowns, the assembly branches and how the default
guess is made, the named points, links and ground pivots that a drawing
needs, dimension lines for dimensioned drawings, and the dimensions a scene
may leave out (with their default values).

Examples
--------
>>> from numkin.linkages.base import Dimension
>>> d = Dimension("offset", "angle", "alpha - phi", default=1.0)
>>> d.scene_key, d.unit("in")
('offset_deg', 'rad')
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Callable

from ..errors import InputError
from ..units import finite

__all__ = ["Dimension", "LinkageSpec", "DIMENSION_KINDS", "length", "pair", "finite", "finish", "build"]

#: Kinds of dimension: a positive length, a signed length (a coordinate), a point (x, y), an angle.
DIMENSION_KINDS = ("length", "signed", "pair", "angle")


@dataclass(frozen=True)
class Dimension:
    """One dimension of a ready-made linkage: a keyword of its builder.

    Parameters
    ----------
    name : str
        The builder's keyword (``"crank"``).
    kind : {"length", "signed", "pair", "angle"}
        A positive length, a signed length, a point ``(x, y)`` (lengths), or
        an angle (rad in Python, ``<name>_deg`` in degrees in a scene).
    description : str
        What it is, in words.
    default : float or tuple or None
        The builder's default (lengths in the spec's ``length_unit``, angles
        in rad); None if the dimension must be given.
    """

    name: str
    kind: str
    description: str = ""
    default: float | tuple | None = None

    def __post_init__(self):
        if self.kind not in DIMENSION_KINDS:
            raise InputError(f"dimension {self.name!r}: kind must be one of {DIMENSION_KINDS}, got {self.kind!r}")

    @property
    def required(self) -> bool:
        """Whether a scene must give it (no default)."""
        return self.default is None

    @property
    def scene_key(self) -> str:
        """The key in a scene's ``[mechanism.dimensions]`` (angles in degrees: ``<name>_deg``)."""
        return f"{self.name}_deg" if self.kind == "angle" else self.name

    def unit(self, length_unit: str) -> str:
        """Unit of the value passed to the builder: ``length_unit`` for lengths, ``"rad"`` for angles."""
        return "rad" if self.kind == "angle" else length_unit


@dataclass(frozen=True)
class LinkageSpec:
    """Everything numkin knows about one ready-made linkage.

    Parameters
    ----------
    name : str
        Registry key and builder name (``"four_bar"``).
    build : callable
        ``build(**dimensions, length_unit=...) -> Mechanism`` (plus ``branch=``
        if ``branches`` is not empty).
    summary : str
        One line: what the linkage is.
    dimensions : tuple of Dimension
        In the builder's order.
    input : str
        Name of the input angle (rad).
    unknowns : tuple of (str, {"angle", "length"})
        The unknowns in solving order.
    length_unit : str
        Unit of the default lengths (and the builder's default ``length_unit``).
    branches : tuple of str
        Assembly branches the builder's ``branch=`` accepts, the default
        first; empty if the branch is picked by the guess only.
    guess : str
        How the default guess is made (on which branch).
    points, links, ground : tuple
        Named points, links (tuples of point names, drawn as polylines) and
        ground pivots of the built mechanism.
    dimension_lines : tuple of (str, str, str, float)
        ``(from point, to point, label, side)`` dimension lines of a
        dimensioned drawing; empty: each link is labelled with its length.
    """

    name: str
    build: Callable
    summary: str
    dimensions: tuple
    input: str
    unknowns: tuple
    length_unit: str = "mm"
    branches: tuple = ()
    guess: str = ""
    points: tuple = ()
    links: tuple = ()
    ground: tuple = ()
    dimension_lines: tuple = field(default=())

    @property
    def unknown_names(self) -> tuple:
        """Names of the unknowns, in solving order."""
        return tuple(name for name, _ in self.unknowns)

    @property
    def angles(self) -> tuple:
        """Names of the unknowns that are angles (rad)."""
        return tuple(name for name, kind in self.unknowns if kind == "angle")

    def dimension(self, name: str) -> Dimension:
        """The :class:`Dimension` called ``name``."""
        for d in self.dimensions:
            if d.name == name:
                return d
        raise KeyError(f"{self.name} has no dimension {name!r}; dimensions: {', '.join(d.name for d in self.dimensions)}")

    def defaults(self) -> dict:
        """The default dimensions, name -> value (lengths in ``length_unit``, angles in rad)."""
        return {d.name: d.default for d in self.dimensions if d.default is not None}


# ------------------------------------------------------------------ helpers of the builders
def length(name: str, value) -> float:
    """A link length: a finite positive number, or a ValueError naming it.

    Examples
    --------
    >>> length("crank", "2")
    2.0
    """
    from ..mechanism import LENGTH_SCALE_RANGE

    v = finite(name, value)
    if v <= 0:
        raise InputError(f"{name} = {value!r} must be a positive, finite length")
    lo, hi = LENGTH_SCALE_RANGE
    if not lo <= v <= hi:
        raise InputError(
            f"{name} = {value!r} is outside the lengths numkin solves, {lo:.0e} to {hi:.0e}: "
            "give the lengths in another unit"
        )
    return v




def pair(name: str, value) -> tuple[float, float]:
    """A point ``(x, y)`` given as two finite numbers, or an InputError naming it.

    Examples
    --------
    >>> pair("o4", [3.7, -2])
    (3.7, -2.0)
    >>> pair("o4", (1,))
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: o4 must be a pair of numbers, got (1,)
    """
    try:
        x, y = value
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a pair of numbers, got {value!r}") from None
    return finite(f"{name}[0]", x), finite(f"{name}[1]", y)


def build(spec: LinkageSpec, model: Callable, values, **options):
    """The mechanism of a ready-made linkage, through the kernel cache.

    ``model()`` writes the linkage's loops with its dimensions as symbols
    (``(loops, input, parameter symbols, points)``, see
    :meth:`numkin.cached_model.CachedModel.from_model`); ``values`` are the dimensions in the
    order of those symbols. The cache key is the linkage's name and the
    source of the module that defines ``model``, so a second build of the
    linkage, in this run or a later one, needs no sympy.
    """
    import sys

    from .. import kernel_cache
    from ..mechanism import Mechanism

    key = kernel_cache.bundle_key(f"linkage {spec.name}", _module_digest(sys.modules[model.__module__].__file__))
    mech = Mechanism.from_model(key, model, values, links=spec.links, ground=spec.ground, **options)
    return finish(mech, spec)


@lru_cache(maxsize=None)
def _module_digest(path: str) -> str:
    import hashlib

    with open(path, "rb") as source:
        return hashlib.sha256(source.read()).hexdigest()


def finish(mechanism, spec: LinkageSpec):
    """Tag a built mechanism with its linkage's registry name (read by :func:`numkin.linkages.spec_of`)."""
    mechanism.linkage = spec.name
    return mechanism

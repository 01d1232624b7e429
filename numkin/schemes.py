"""The registry of finite-difference schemes: each declared by its stencil.

A stencil scheme is declared by its offsets (in steps h) and the derivative
it estimates; its weights and order of accuracy are computed exactly
(:mod:`numkin.stencils`). Each scheme also records

* its **partner**: the scheme for the other derivative used with it (the
  first-derivative scheme in ``alpha_in * q'`` beside a second-derivative
  scheme, and the second-derivative scheme of the same family beside a
  first-derivative one);
* its **family**: the first-derivative scheme it belongs with (figures give
  a family one colour); ``centred_of_centred`` is centred applied twice, so
  its family is ``centred``;
* its **ends**: how the samples of an open grid where the interior stencil
  does not fit are handled (``"one-sided"``: the smallest one-sided window
  of at least the interior's order; ``"mirror"``: the interior reflected);
* how it is **shown**: its ``label`` in tables, its name in a caption's
  prose, its line ``style`` and ``marker`` in figures (a second-derivative
  scheme that is its family's partner is drawn in the family's colours, see
  :func:`numkin.figures.style.source_style`), and whether it is among the
  schemes a study shows by ``default`` (:func:`default_schemes`).

Rule for partners (checked by the tests): a second-derivative scheme's
partner is a first-derivative scheme of the same family and the same order,
and a first-derivative scheme's partner has it as partner in turn.

Schemes that are not stencils -- ``richardson`` (an extrapolation of two
centred differences), the FFT schemes ``spectral`` and ``spectral_second``,
and ``complex_step`` (of a function, not of samples) -- are described in the
same registry with their ``kind``.

Examples
--------
Add a 7-point centred first derivative at run time; every function that
takes a scheme by name then accepts it:

>>> import numpy as np
>>> from numkin import derivatives, schemes
>>> s = schemes.register("seven_point", range(-3, 4), 1)
>>> s.order, [str(w) for w in s.weights]
(6, ['-1/60', '3/20', '-3/4', '3/4', '-3/20', '1/60'])
>>> x = np.linspace(0.0, 2 * np.pi, 60, endpoint=False)
>>> dy = derivatives.differentiate(np.sin(x), x[1], "seven_point", periodic=True)
>>> bool(np.max(np.abs(dy - np.cos(x))) < 1e-7)
True
>>> schemes.unregister("seven_point")
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Callable

from .errors import InputError
from .stencils import Rule, Stencil

__all__ = [
    "Scheme", "SCHEMES", "REGISTRY", "RegistryView", "NameList", "PARTNER", "FAMILY", "BUILT_IN", "ALIASES",
    "register", "unregister", "get_scheme", "lookup", "by_label", "default_schemes", "point_stencil",
    "own_stencil_points",
]


@dataclass(frozen=True)
class Scheme:
    """One scheme of the registry.

    Attributes
    ----------
    name : str
        Registry name (for the built-in schemes, also the name of the
        function in :mod:`numkin.derivatives`).
    derivative : int
        Which derivative the scheme estimates: 1 or 2.
    order : int
        Order p of the truncation error O(h**p) on uniform grids, ends
        included; derived from the stencil. 0 marks the spectral schemes,
        whose error on smooth periodic data falls faster than any power of h.
    stencil : str
        Interior formula, for tables and plot legends.
    function : callable
        ``function(y, h, periodic=..., period_offset=0.0)`` (``complex_step``:
        ``function(f, x, h)``).
    periodic_only : bool
        True if the scheme needs ``periodic=True``.
    description : str
        One-line description.
    kind : {"stencil", "richardson", "spectral", "complex_step"}
    offsets, weights : tuple
        Interior stencil (offsets in steps h, exact weights); empty for the
        FFT schemes.
    partner : str or None
        The scheme for the other derivative used with this one.
    family : str
        The first-derivative scheme this one belongs with.
    ends : str
        End handling on open grids.
    rule : numkin.stencils.Rule or None
        Interior and end stencils, for stencil schemes.
    label : str
        How tables name the scheme's rows: its name unless declared
        (``"complex step"``); :func:`by_label` finds the scheme again.
    prose : str
        How a caption's sentence names it (default: the label with spaces,
        ``"centred of centred"``; ``"the second difference"``).
    default : bool
        Among the schemes a study shows when none are named
        (:func:`default_schemes`, :data:`numkin.report.ROUNDOFF_SCHEMES`).
    style : tuple of (str, object)
        Matplotlib keywords of its curves (``color``, ``linestyle``,
        ``linewidth``, ...) as declared; empty or without a colour: drawn
        as :func:`numkin.figures.style.source_style` derives.
    marker : tuple
        ``(marker, size, filled)`` on the error figures as declared; empty:
        derived likewise (:func:`numkin.figures.style.marker_style`).

    Examples
    --------
    >>> from numkin.derivatives import SCHEMES
    >>> scheme = SCHEMES["centred"]
    >>> print(scheme.order, scheme.stencil)
    2 (y[i+1] - y[i-1])/(2h)
    >>> SCHEMES["centred_of_centred"].partner, SCHEMES["centred_of_centred"].family
    ('centred', 'centred')
    """

    name: str
    derivative: int
    order: int
    stencil: str
    function: Callable
    periodic_only: bool
    description: str
    kind: str = "stencil"
    offsets: tuple = ()
    weights: tuple = ()
    partner: str | None = None
    family: str = ""
    ends: str = ""
    rule: Rule | None = field(default=None, compare=False, repr=False)
    label: str = ""
    prose: str = ""
    default: bool = False
    style: tuple = field(default=(), repr=False)
    marker: tuple = field(default=(), repr=False)

    def __post_init__(self):
        if not self.label:
            object.__setattr__(self, "label", self.name)
        if not self.prose:
            object.__setattr__(self, "prose", self.label.replace("_", " "))

    @property
    def reach(self) -> tuple[int, int]:
        """Points at the start and at the end of an open grid where the interior stencil does not apply
        (they take the end stencils, ``ends``): ``(-min(offsets), max(offsets))``, (0, 0) for none.

        Examples
        --------
        >>> from numkin.derivatives import SCHEMES
        >>> SCHEMES["forward"].reach, SCHEMES["second_difference"].reach, SCHEMES["spectral"].reach
        ((0, 1), (1, 1), (0, 0))
        """
        if not self.offsets:
            return 0, 0
        return max(0, -min(self.offsets)), max(0, max(self.offsets))


#: Declarations of the built-in schemes: name -> keyword arguments of :func:`register`
#: (``offsets``/``derivative`` for stencils, ``kind`` and the rest for the others).
#: Figure styles: schemes that can give the same numbers (forward and backward on a
#: symmetric curve, five-point and Richardson) have dash patterns that interleave and
#: markers that stay visible one over the other (a large open one around a small
#: filled one). centred_of_centred, drawn beside the second difference (the centred
#: family's partner), has a colour of its own.
BUILT_IN = {
    "forward": dict(offsets=(0, 1), derivative=1, ends="mirror", partner="forward_of_forward",
                    description="forward difference", default=True,
                    style=dict(color="#D55E00", linestyle=(0, (5, 5)), linewidth=1.8), marker=("^", 8.5, False)),
    "backward": dict(offsets=(-1, 0), derivative=1, ends="mirror", description="backward difference",
                     style=dict(color="#CC79A7", linestyle=(5, (5, 5)), linewidth=1.8), marker=("v", 4.5, True)),
    "centred": dict(offsets=(-1, 0, 1), derivative=1, partner="second_difference",
                    description="centred difference", default=True,
                    style=dict(color="#0072B2", linestyle="-", linewidth=2.6, alpha=0.55, zorder=1.9),
                    marker=("o", 4.5, True)),
    "five_point": dict(offsets=(-2, -1, 0, 1, 2), derivative=1, partner="five_point_second",
                       description="five-point centred difference", default=True,
                       style=dict(color="#009E73", linestyle=(0, (1.2, 1.8)), linewidth=2.4),
                       marker=("D", 8.0, False)),
    "richardson": dict(kind="richardson", derivative=1, order=4, stencil="(4 D(h) - D(2h))/3",
                       offsets=(-2, -1, 0, 1, 2), ends="one-sided (five_point's)",
                       description="Richardson extrapolation of centred differences with steps h and 2h",
                       style=dict(color="#E69F00", linestyle=(0, (6, 4)), linewidth=1.4), marker=("o", 3.5, True)),
    "spectral": dict(kind="spectral", derivative=1, order=0, stencil="ik Y_k (FFT)", partner="spectral_second",
                     description="FFT differentiation of one full period", default=True,
                     style=dict(color="#56B4E9", linestyle="-.", linewidth=1.6), marker=("*", 7.0, True)),
    "second_difference": dict(offsets=(-1, 0, 1), derivative=2, partner="centred",
                              description="centred second difference", default=True,
                              prose="the second difference", style=dict(linestyle="-")),
    "forward_of_forward": dict(offsets=(0, 1, 2), derivative=2, ends="mirror", partner="forward",
                               description="forward difference applied twice (centred on sample i+1)",
                               marker=("^", 5.5, True)),
    "centred_of_centred": dict(offsets=(-2, 0, 2), derivative=2, partner="centred",
                               description="centred difference applied twice (2h-wide second difference)",
                               style=dict(color="#1B3A6B", linewidth=1.6), marker=("s", 8.0, False)),
    "five_point_second": dict(offsets=(-2, -1, 0, 1, 2), derivative=2, partner="five_point",
                              description="five-point centred second difference"),
    "spectral_second": dict(kind="spectral", derivative=2, order=0, stencil="-k^2 Y_k (FFT)",
                            partner="spectral", description="FFT second derivative of one full period"),
    "complex_step": dict(kind="complex_step", derivative=1, order=2, stencil="Im f(x + ih)/h",
                         description="complex step of a function: no subtractive cancellation",
                         label="complex step", default=True,
                         style=dict(color="0.45", linestyle="-", linewidth=1.2), marker=("s", 8.0, False)),
}

#: Other spellings accepted by :func:`get_scheme`.
ALIASES = {"central": "centred", "centered": "centred", "second": "second_difference", "five-point": "five_point"}

_REGISTRY: dict[str, Scheme] = {}
_LOADED = False


def _load() -> dict[str, Scheme]:
    """The registry, with the built-in schemes added on first use."""
    global _LOADED
    if not _LOADED:
        _LOADED = True
        from . import derivatives

        for name, decl in BUILT_IN.items():
            # a stencil scheme without its own documented function in numkin.derivatives gets the generated one
            _REGISTRY[name] = _build(name, function=getattr(derivatives, name, None), **decl)
    return _REGISTRY


class RegistryView(Mapping):
    """A read-only, always current view of the registry: ``value(scheme)`` of every scheme ``select`` keeps.

    The entries of `fixed` (sources that are no schemes, such as ``"analytic"``) come first.
    """

    def __init__(self, select, value, fixed: Mapping | None = None):
        self._select, self._value, self._fixed = select, value, dict(fixed or {})

    def _items(self):
        return {**self._fixed, **{k: self._value(s) for k, s in _load().items() if self._select(s)}}

    def __getitem__(self, key):
        return self._items()[key]

    def __iter__(self):
        return iter(self._items())

    def __len__(self):
        return len(self._items())

    def __repr__(self):
        return repr(self._items())


#: Every scheme, complex step included: name -> :class:`Scheme`.
REGISTRY: Mapping = RegistryView(lambda s: True, lambda s: s)
#: The schemes of sampled data (all but complex step): name -> :class:`Scheme`.
SCHEMES: Mapping = RegistryView(lambda s: s.kind != "complex_step", lambda s: s)
#: Second-derivative scheme -> the first-derivative scheme used with it.
PARTNER: Mapping = RegistryView(lambda s: s.derivative == 2 and s.partner is not None, lambda s: s.partner)
#: Scheme -> family (the first-derivative scheme it belongs with).
FAMILY: Mapping = RegistryView(lambda s: True, lambda s: s.family)


def _build(name, *, derivative, offsets=(), kind="stencil", ends="one-sided", partner=None, family=None,
           description=None, order=None, stencil=None, function=None, label="", prose="", default=False,
           style=None, marker=()) -> Scheme:
    rule = None
    weights: tuple = ()
    if kind == "stencil":
        rule = Rule.build(Stencil.from_offsets(offsets, derivative), ends)
        order, stencil = rule.order, rule.interior.formula()
        offsets, weights = rule.interior.offsets, rule.interior.weights
        if function is None:
            from .derivatives import scheme_function

            function = scheme_function(name, rule)
    elif kind == "richardson":  # the offsets and weights of the stencil it amounts to (a zero weight left out)
        combined = Stencil.from_offsets(offsets, derivative)
        offsets, weights = combined.offsets, combined.weights
    if family is None:
        family = name if derivative == 1 else (partner or name)
    return Scheme(
        name=name, derivative=int(derivative), order=int(order), stencil=stencil, function=function,
        periodic_only=kind == "spectral", description=description or f"{len(offsets)}-point stencil {stencil}",
        kind=kind, offsets=tuple(offsets), weights=tuple(weights), partner=partner, family=family,
        ends={"spectral": "periodic only", "complex_step": "none (it evaluates a function, not samples)"}.get(kind, ends),
        rule=rule, label=label, prose=prose, default=bool(default), style=tuple(dict(style or {}).items()),
        marker=tuple(marker),
    )


def _default_partner(derivative: int, rule: Rule) -> str | None:
    """A registered stencil scheme for the other derivative with the same span and order."""
    span = (min(rule.interior.offsets), max(rule.interior.offsets))
    for s in _load().values():
        if s.kind == "stencil" and s.derivative == 3 - derivative and s.order == rule.order and s.rule and (
            (min(s.rule.interior.offsets), max(s.rule.interior.offsets)) == span
        ):
            return s.name
    return None


def register(name: str, offsets, derivative: int, *, partner: str | None = None, family: str | None = None,
             ends: str = "one-sided", description: str | None = None, replace: bool = False, label: str = "",
             prose: str = "", default: bool = False, style=None, marker=()) -> Scheme:
    """Add a finite-difference scheme declared by its stencil offsets.

    After this call :func:`numkin.derivatives.differentiate`,
    :func:`numkin.kinematics.finite_difference`, :func:`numkin.compare.compare`
    and everything else that looks schemes up by name accept `name`.

    Parameters
    ----------
    name : str
        New scheme name (letters, digits and ``_``).
    offsets : sequence of int
        Sample offsets of the interior stencil, in steps h (``range(-3, 4)``
        for the 7-point centred stencil). The weights are solved exactly and
        the order of accuracy derived from them.
    derivative : {1, 2}
        The derivative estimated.
    partner : str, optional
        Scheme for the other derivative used with this one. Default: a
        registered stencil scheme for the other derivative with the same span
        and order. Required for a second-derivative scheme if there is none.
    family : str, optional
        Default: `name` for a first derivative, the partner for a second.
    ends : {"one-sided", "mirror"}, default "one-sided"
        End stencils on open grids (see the module notes).
    description : str, optional
    replace : bool, default False
        Allow replacing a scheme registered earlier at run time (never a built-in one).
    label, prose : str, optional
        Its name in tables and in captions' sentences (default: the name;
        the label with spaces). A label names one scheme only.
    default : bool, default False
        Whether studies show it when no schemes are named (:func:`default_schemes`).
    style : mapping, optional
        Matplotlib keywords of its curves; with a ``color`` they are its
        whole style, without one they amend the derived style
        (:func:`numkin.figures.style.source_style`).
    marker : tuple, optional
        ``(marker, size, filled)`` on the error figures.

    Returns
    -------
    Scheme
        The new scheme, now in :data:`REGISTRY` under `name`.

    Raises
    ------
    ValueError
        For a taken or malformed name or label, offsets that cannot give the
        derivative, an unknown partner, a partner of the wrong derivative
        or order, or a style that is not a mapping of keywords.

    Examples
    --------
    >>> from numkin import schemes
    >>> s = schemes.register("seven_point_second", range(-3, 4), 2, partner="five_point")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: partner='five_point' of seven_point_second has order 4; the scheme has order 6: give a partner of the same order
    """
    registry = _load()
    if not isinstance(name, str) or not name.isidentifier():
        raise InputError(f"a scheme name must be letters, digits and '_', got {name!r}")
    if name in BUILT_IN or name in ALIASES or (name in registry and not replace):
        raise InputError(f"scheme {name!r} is already registered" + ("" if name in BUILT_IN else "; pass replace=True"))
    if derivative not in (1, 2) or isinstance(derivative, bool):
        raise InputError(f"derivative must be 1 or 2, got {derivative!r}")
    shown = _shown(name, label, prose, default, style, marker)
    scheme = _build(name, derivative=derivative, offsets=tuple(offsets), ends=ends, family=family,
                    description=description)
    if partner is None:
        partner = _default_partner(derivative, scheme.rule)
    if partner is not None:
        other = get_scheme(partner)
        if other.derivative == derivative:
            raise InputError(f"partner={partner!r} of {name} estimates the same derivative; it must estimate the other")
        if other.order != scheme.order:
            raise InputError(f"partner={partner!r} of {name} has order {other.order}; the scheme has order "
                             f"{scheme.order}: give a partner of the same order")
        partner = other.name
    elif derivative == 2:
        raise InputError(f"{name}: no first-derivative scheme of order {scheme.order} on the same offsets is "
                         "registered; register one first or give partner=")
    scheme = _build(name, derivative=derivative, offsets=tuple(offsets), ends=ends, family=family,
                    description=description, partner=partner, **shown)
    registry[name] = scheme
    return scheme


def _shown(name, label, prose, default, style, marker) -> dict:
    """The checked arguments of :func:`register` on how a scheme is shown."""
    label = label or name
    if not isinstance(label, str) or not label.strip() or not isinstance(prose, str):
        raise InputError(f"{name}: label and prose must be text, got {label!r} and {prose!r}")
    taken = [s.name for s in _load().values() if s.name != name and label in (s.name, s.label)]
    if taken:
        raise InputError(f"{name}: label {label!r} names scheme {taken[0]!r} already; give another")
    if style is not None and not (isinstance(style, Mapping) and all(isinstance(k, str) for k in style)):
        raise InputError(f"{name}: style must be a mapping of matplotlib keywords, got {style!r}")
    marker = tuple(marker or ())
    if marker and not (len(marker) == 3 and isinstance(marker[0], str) and isinstance(marker[2], bool)):
        raise InputError(f"{name}: marker must be (marker, size, filled), got {marker!r}")
    return dict(label=label, prose=prose, default=bool(default), style=style, marker=marker)


def unregister(name: str) -> None:
    """Remove a scheme added with :func:`register` (built-in schemes stay)."""
    if name in BUILT_IN:
        raise InputError(f"{name!r} is a built-in scheme and cannot be removed")
    if _load().pop(name, None) is None:
        raise InputError(f"no scheme {name!r} was registered")


def own_stencil_points(schemes, n_points: int, periodic: bool) -> slice:
    """The points of a sweep where every one of `schemes` applies its own (interior) stencil.

    One period of a periodic grid (its last point repeats the first); on
    an open grid all but the first and last points the schemes' largest
    :attr:`Scheme.reach` leaves out, where one-sided end stencils stand in.
    The one rule of :mod:`numkin.compare`, :mod:`numkin.report` and the
    figures for telling end values apart.

    Examples
    --------
    >>> own_stencil_points([get_scheme("five_point")], 181, periodic=False)
    slice(2, 179, None)
    >>> own_stencil_points([get_scheme("forward"), get_scheme("second_difference")], 181, periodic=False)
    slice(1, 180, None)
    >>> own_stencil_points([get_scheme("centred")], 361, periodic=True)
    slice(0, 360, None)
    """
    if periodic:
        return slice(0, n_points - 1)
    before = max((s.reach[0] for s in schemes), default=0)
    after = max((s.reach[1] for s in schemes), default=0)
    return slice(before, n_points - after)


def lookup(name: str) -> Scheme:
    """Any scheme of :data:`REGISTRY` by name or alias, complex step included."""
    key = name.strip().lower() if isinstance(name, str) else name
    try:
        return _load()[ALIASES.get(key, key)]
    except (KeyError, TypeError):
        raise InputError(
            f"unknown finite-difference method {name!r}; valid names: "
            f"{', '.join(SCHEMES)} (aliases: {', '.join(ALIASES)})"
        ) from None


def by_label(text) -> Scheme | None:
    """The scheme a table's row or a figure's source names: by its label or registry name; None for none.

    Tables write a scheme's ``label`` (``"complex step"``); figures drawn
    from them, and from frames keyed by registry name, find the
    :class:`Scheme` again here. No aliases; ``"analytic"`` is no scheme.

    Examples
    --------
    >>> by_label("complex step").name, by_label("complex_step").label, by_label("analytic")
    ('complex_step', 'complex step', None)
    """
    registry = _load()
    key = str(text)
    if key in registry:
        return registry[key]
    return next((s for s in registry.values() if s.label == key), None)


def default_schemes(derivative: int, *, periodic: bool) -> tuple[str, ...]:
    """The schemes a comparison of one derivative shows when none are named.

    The ``default`` first-derivative schemes of sampled data, in registry
    order; for the second derivative their partners, in the same order, then
    the other ``default`` second-derivative schemes, each named once. The
    periodic-only ones (spectral) come last, and only if `periodic`.

    Examples
    --------
    >>> default_schemes(1, periodic=True)
    ('forward', 'centred', 'five_point', 'spectral')
    >>> default_schemes(2, periodic=False)
    ('forward_of_forward', 'second_difference', 'five_point_second')
    """
    if derivative not in (1, 2) or isinstance(derivative, bool):
        raise InputError(f"derivative must be 1 or 2, got {derivative!r}")
    shown = [s for s in SCHEMES.values() if s.default and (periodic or not s.periodic_only)]
    shown.sort(key=lambda s: s.periodic_only)  # stable: registry order within each
    if derivative == 1:
        return tuple(s.name for s in shown if s.derivative == 1)
    names = [s.partner for s in shown if s.derivative == 1 and s.partner is not None]
    names += [s.name for s in shown if s.derivative == 2]
    return tuple(dict.fromkeys(n for n in names if periodic or not SCHEMES[n].periodic_only))


class NameList(Sequence):
    """A read-only, always current sequence of scheme names: ``names()``, computed at each use.

    Examples
    --------
    >>> firsts = NameList(lambda: tuple(n for n, s in SCHEMES.items() if s.derivative == 1))
    >>> firsts[:2], "centred" in firsts
    (('forward', 'backward'), True)
    """

    def __init__(self, names: Callable[[], tuple]):
        self._names = names

    def __getitem__(self, index):
        return self._names()[index]

    def __len__(self):
        return len(self._names())

    def __eq__(self, other):
        return tuple(self) == (tuple(other) if isinstance(other, NameList) else other)

    def __add__(self, other):
        return tuple(self) + tuple(other)

    def __radd__(self, other):
        return tuple(other) + tuple(self)

    def __reduce__(self):  # (pickled as the names it holds now)
        return tuple, (tuple(self),)

    __hash__ = None

    def __repr__(self):
        return repr(self._names())


def get_scheme(name: str) -> Scheme:
    """Look up a scheme of sampled data by name or alias.

    Parameters
    ----------
    name : str
        A key of :data:`SCHEMES` or one of the aliases ``"central"`` and
        ``"centered"`` (centred), ``"second"`` (second_difference) and
        ``"five-point"`` (five_point). Case and surrounding spaces are ignored.

    Returns
    -------
    Scheme
        The registered scheme of that name.

    Raises
    ------
    ValueError
        For any other name; the message lists the valid names.

    Examples
    --------
    >>> from numkin.derivatives import get_scheme
    >>> get_scheme("central").name
    'centred'
    """
    scheme = lookup(name)
    if scheme.kind == "complex_step":
        raise InputError(f"{name!r} differentiates a function, not samples; valid names: {', '.join(SCHEMES)}")
    return scheme


def point_stencil(name: str) -> Stencil:
    """The stencil of a scheme for a derivative at one input, from values at ``x + k h``.

    ``estimate = stencil.apply(values, h)`` with ``values[..., j] = f(x + stencil.offsets[j] * h)``;
    ``stencil.offsets``, ``stencil.coefficients`` (floats), ``stencil.weights`` (exact),
    ``stencil.derivative`` and ``stencil.order`` describe it. Richardson's
    extrapolation is the five-point stencil written out.

    Raises
    ------
    ValueError
        For the spectral schemes and complex step, which have no real stencil.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin.schemes import point_stencil
    >>> s = point_stencil("five_point")
    >>> s.offsets, s.coefficients
    ((-2, -1, 1, 2), (0.08333333333333333, -0.6666666666666666, 0.6666666666666666, -0.08333333333333333))
    >>> h = 1e-3
    >>> print(f"{s.apply(np.sin(0.5 + h * np.array(s.offsets)), h):.12f}")   # cos(0.5)
    0.877582561890
    """
    scheme = lookup(name)
    if scheme.rule is not None:
        return scheme.rule.interior
    if scheme.kind == "richardson":
        return Stencil.from_offsets(scheme.offsets, scheme.derivative)
    raise InputError(f"{scheme.name} ({scheme.kind}) has no finite stencil at one input")


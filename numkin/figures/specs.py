"""The figures a scene may ask for, by name: what each draws, and a scene's figure name read.

:data:`FIGURES` names every figure :func:`numkin.figures.render` draws and
:data:`CAPTIONS` says what each draws; :func:`parse_spec` reads a scene's
figure name (``"kinematics:beta"``) and :func:`caption` a figure file's stem.
Nothing here imports matplotlib or the modules that draw: a scene is
checked against these names when it is read.

Examples
--------
>>> parse_spec("kinematics:beta"), "roundoff" in FIGURES
(('kinematics', 'beta'), True)
"""

from __future__ import annotations

import math

from ..errors import InputError

__all__ = ["CAPTIONS", "FIGURES", "WITH_QUANTITY", "FigureSkipped", "caption", "parse_spec"]

#: Figure names a scene may ask for -> one-line description.
FIGURES: dict[str, str] = {
    "position": "unknowns against the input angle",
    "derivative": "dq/dθ by forward and centred differences on one graph",
    "difference": "Δ between the forward and centred dq/dθ, twin axes with d²q/dθ²",
    "kinematics": "position, velocity and acceleration of one unknown: schemes, analytic, check points",
    "slider": "x, v and a of a slider",
    "acceleration": "numerical against analytic acceleration of one unknown, with the error",
    "mechanism": "the linkage drawn at one input angle with its dimensions",
    "convergence": "error against step h (log-log) with reference slopes 1, 2, 4",
    "work-precision": "error against work (evaluations; or against run time)",
    "roundoff": "error against h down to rounding: the V-curve",
    "newton": "Newton's residual per iteration for each Jacobian",
}

#: Gallery caption of each figure: what it draws, exactly (``{q}``: the unknown's symbol; ``{at}``: the angle).
#: Keys are those of :data:`FIGURES`; the second form, where given, is for a figure drawn without its argument.
CAPTIONS: dict[str, tuple[str, ...]] = {
    "position": ("{q} against the input angle",
                 "The unknowns against the input angle, angles and lengths on separate panels"),
    "derivative": ("First derivative of {q} with respect to the input angle by the forward and the centred "
                   "difference; the values of their one-sided end stencils are markers of their own",),
    "difference": ("The gap between the centred and the forward first derivatives of {q}, beside its second "
                   "derivative by the second difference (twin axes, interior points); dotted lines where the "
                   "second derivative is zero",),
    "kinematics": ("{q}, its velocity and its acceleration against the input angle: finite differences and the "
                   "analytic solution, with their values at the check angles; on an open grid the values of the "
                   "one-sided end stencils are markers of their own",),
    "slider": ("Slider position {q}, its velocity and its acceleration against the input angle: finite "
               "differences and the analytic solution, with their values at the check angles; on an open grid "
               "the values of the one-sided end stencils are markers of their own",),
    "acceleration": ("Acceleration of {q} by finite differences against the analytic one, and |numerical − "
                     "analytic| of each on a log scale; on an open grid the values of the one-sided end stencils "
                     "are markers of their own",),
    "mechanism": ("The linkage drawn at {at}, with its dimensions",
                  "The linkage drawn at the first check angle, with its dimensions"),
    "convergence": ("Largest error against grid step (log-log) of every scheme, each labelled with its formal "
                    "order, beside reference slopes 1, 2 and 4",),
    "work-precision": ("Largest error against work (evaluations of the loop equations and of the stencils) for "
                       "every method, the analytic solution and the complex step included, from coarse to fine "
                       "grid; the Pareto front ringed",),
    "roundoff": ("Relative error against step at one angle, down to the rounding floor: the V-curves, the "
                 "textbook optimal steps and the measured optimum",),
    "newton": ("Newton's scaled residual per iteration, one curve per Jacobian",),
}

#: Figures that take an unknown or a derived quantity (``"name:unknown"``).
WITH_QUANTITY = ("position", "derivative", "difference", "kinematics", "slider", "acceleration")


class FigureSkipped(UserWarning):
    """A figure a scene asked for could not be drawn from the data at hand."""



def parse_spec(spec: str) -> tuple[str, str | None]:
    """Split a figure name of a scene: ``"kinematics:beta"`` -> ``("kinematics", "beta")``.

    The name may be written with ``_`` for ``-`` (``work_precision``). The
    part after ``:`` is an unknown or a derived quantity of the mechanism
    (``kinematics:mu`` of a ``[mechanism.quantities]`` entry ``mu``) for
    ``position``, ``derivative``, ``difference``, ``kinematics``, ``slider``
    and ``acceleration``, or the input angle in degrees (``mechanism:30``);
    the table figures take none. Whether the mechanism has that unknown is
    checked when the figure is drawn. Does not import matplotlib.

    Raises
    ------
    ValueError
        For an unknown figure name or an argument a figure does not take.

    Examples
    --------
    >>> parse_spec("kinematics:beta")
    ('kinematics', 'beta')
    >>> parse_spec("work_precision")
    ('work-precision', None)
    >>> parse_spec("mechanism:30")
    ('mechanism', '30')
    """
    if not isinstance(spec, str) or not spec.strip():
        raise InputError(f"figure name must be a non-empty string, got {spec!r}")
    name, _, arg = spec.strip().partition(":")
    kind = name.strip().lower().replace("_", "-")
    arg = arg.strip() or None
    if kind not in FIGURES:
        import difflib

        near = difflib.get_close_matches(kind, list(FIGURES), n=1)
        hint = f" (did you mean '{near[0]}'?)" if near else ""
        raise InputError(f"unknown figure {spec!r}{hint}; figures are: {', '.join(FIGURES)}")
    if arg is not None and kind not in WITH_QUANTITY and kind != "mechanism":
        raise InputError(f"figure {spec!r}: '{kind}' takes no ':' argument")
    if arg is not None and kind == "mechanism":
        try:
            angle = float(arg)
        except ValueError:
            raise InputError(f"figure {spec!r}: 'mechanism:<angle in degrees>', got {arg!r}") from None
        if not math.isfinite(angle) or abs(angle) > 1e6:
            raise InputError(f"figure {spec!r}: the angle must be a finite number of degrees (at most 1e6), "
                             f"got {arg!r}")
    return kind, arg


def caption(stem: str) -> str:
    """What the figure of a file stem draws (``"derivative-phi"``, ``"mechanism-30deg"``), from :data:`CAPTIONS`.

    The stem is a figure name of :data:`FIGURES`, then ``-<unknown>`` or
    ``-<angle>deg`` as :func:`render` names its files. Symbols are written
    as TeX between dollars. Does not import matplotlib.

    Raises
    ------
    ValueError
        For a stem that starts with no figure name.

    Examples
    --------
    >>> print(caption("position-phi"))
    $\\phi$ against the input angle
    >>> caption("mechanism-30deg")
    'The linkage drawn at 30°, with its dimensions'
    >>> caption("newton")
    "Newton's scaled residual per iteration, one curve per Jacobian"
    """
    from .labels import sym

    for kind in sorted(CAPTIONS, key=len, reverse=True):
        if stem == kind or stem.startswith(kind + "-"):
            arg = stem[len(kind) + 1:]
            forms = CAPTIONS[kind]
            if not arg:
                return forms[-1]
            at = f"{arg.removesuffix('deg')}°" if kind == "mechanism" else ""
            return forms[0].format(q=sym(arg), at=at)
    raise InputError(f"figure file {stem!r}: no figure of that name; figures are: {', '.join(FIGURES)}")

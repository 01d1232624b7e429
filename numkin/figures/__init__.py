"""Figures of sweeps, velocities, accelerations and error tables.

One function per figure. Each takes plain data (a :class:`~numkin.Sweep`,
the DataFrames of :func:`numkin.analytic.kinematics` and
:func:`numkin.kinematics.finite_difference`, the tables of
:mod:`numkin.report`), draws only what it is given and returns a
:class:`matplotlib.figure.Figure` that is not registered with pyplot.
:func:`save` writes it (PNG and SVG by default) and closes it;
:func:`render` draws and saves the figures a scene asks for.

Figures use the package style (``numkin/numkin.mplstyle``: fixed size, dpi
and fonts, matplotlib's defaults underneath, the user's matplotlibrc
ignored), the Agg renderer and no dates or version strings in the files, so
regenerating a figure gives the same bytes. Input angles are drawn in
degrees, every axis is labelled with its unit.

Importing this package does not import matplotlib (the figure functions do),
so :data:`FIGURES` and :func:`parse_spec` can be used to check a scene's
figure list cheaply.

The package is split by job: :mod:`~numkin.figures.style` (style file,
colours, saving), :mod:`~numkin.figures.labels` (symbols, units, number
formats), :mod:`~numkin.figures.curves` (curves against the input),
:mod:`~numkin.figures.error_plots` (error-analysis tables),
:mod:`~numkin.figures.drawing` (the linkage itself, shared with
:mod:`numkin.animate`), :mod:`~numkin.figures.dispatch` (figures by name),
:mod:`~numkin.figures.ticks` (log axes labelled ``10⁻¹²`` in the tick font),
:mod:`~numkin.figures.fitting` (titles broken into lines, or set smaller, to fit the figure),
:mod:`~numkin.figures.ends` (which values of an open grid come from one-sided
end stencils, drawn and labelled apart), :mod:`~numkin.figures.series` (the
values and rates of a derived quantity, drawn as an unknown's),
:mod:`~numkin.figures.arguments` (the kind of each argument, checked at the
entry) and :mod:`~numkin.figures.registries` (scheme families and dimension lines).

=========================  ======================================================  ====================
name                       figure                                                  needs
=========================  ======================================================  ====================
``position``               unknowns and derived quantities against the input       sweep
``derivative``             dq/dθ by forward and centred differences                sweep (uniform step)
``difference``             Δ = ``|centred − forward|``, d²q/dθ² on twin axes       sweep (uniform step)
``kinematics``             q, q̇, q̈ against θ: schemes, analytic, check points      analytic and/or finite
``slider``                 x, v, a of a slider                                     analytic and/or finite
``acceleration``           numerical against analytic acceleration, and the error  analytic and finite
``mechanism``              the linkage drawn at one input, dimensions labelled     sweep with points
``convergence``            error against h (log-log), reference slopes 1, 2, 4     convergence table
``work-precision``         error against work (exact evaluation counts)            work-precision table
``roundoff``               error against h down to rounding: the V-curve           roundoff table
``newton``                 Newton's residual per iteration, per Jacobian           newton table
=========================  ======================================================  ====================

A scene names a figure as ``"name"`` or ``"name:unknown"`` (``"kinematics:beta"``),
see :func:`parse_spec`; :func:`caption` says what the file of one draws.

Derived quantities
------------------
A derived quantity of the mechanism (``mu = theta4 - theta3``, declared with
:meth:`numkin.Mechanism.add_quantities` or a scene's ``[mechanism.quantities]``)
is drawn wherever an unknown is: ``"kinematics:mu"``, ``"position:mu"``,
``"slider:s"`` of a length, or ``figures.kinematics(sweep, "mu", ...)``. Its
values come from its expression at the solved unknowns (an angle unwrapped
and drawn in degrees, labelled with its symbol and unit); its exact rates
from :func:`numkin.analytic.derived_kinematics` (a scene's, or at the
analytic frame's input speed); its finite-difference rates are the
schemes of each frame applied to its sampled values, as for an unknown
(:mod:`numkin.figures.series`).

Arguments
---------
Each figure function checks the kind of its arguments first: a string
where a Sweep belongs, a number for a list of names or a DataFrame for a
mapping of them raises :class:`numkin.InputError` naming the argument
(:mod:`numkin.figures.arguments`).

Examples
--------
>>> import numpy as np
>>> from numkin import linkages, figures
>>> sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0, 361)))
>>> fig = figures.position(sweep, ["theta4"])
>>> [p.suffix for p in figures.save(fig, "/tmp/numkin-doc-theta4")]
['.png', '.svg']
>>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
>>> fig = figures.position(mech.sweep(np.radians(np.arange(0, 361))), "mu")
>>> fig.axes[0].get_ylabel()
'$\\\\mu$ [deg]'
>>> figures.save(fig, "/tmp/numkin-doc-mu", ["png"])[0].name
'numkin-doc-mu.png'
"""

from __future__ import annotations

from .specs import CAPTIONS, FIGURES, FigureSkipped, caption, parse_spec
from .style import STYLE, save, style  # (the function style, not the module of that name: bound after it)

#: Where each function that draws lives: loaded on first use, so that reading a scene's figure names
#: (:mod:`~numkin.figures.specs`) loads none of the modules that draw.
_DRAWING = {
    "acceleration_comparison": "curves", "derivative": "curves", "difference": "curves", "kinematics": "curves",
    "position": "curves", "slider": "curves", "render": "dispatch", "mechanism": "drawing",
    "convergence": "error_plots", "newton_residuals": "error_plots", "roundoff": "error_plots",
    "work_precision": "error_plots",
}


def __getattr__(name):
    if name in _DRAWING:
        from importlib import import_module

        value = getattr(import_module(f".{_DRAWING[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_DRAWING))

__all__ = [
    "CAPTIONS",
    "FIGURES",
    "FigureSkipped",
    "STYLE",
    "acceleration_comparison",
    "caption",
    "convergence",
    "derivative",
    "difference",
    "kinematics",
    "mechanism",
    "newton_residuals",
    "parse_spec",
    "position",
    "render",
    "roundoff",
    "save",
    "slider",
    "style",
    "work_precision",
]

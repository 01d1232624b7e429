"""numkin: numerical kinematics of planar linkages.

A linkage is written as vector-loop closure equations (:class:`Loop`,
:class:`Mechanism`, or a ready-made one from :mod:`numkin.linkages`); its
position is solved over a sweep of the input by Newton-Raphson
(:func:`newton`, :meth:`Mechanism.sweep`); angular velocity and acceleration
come from finite-difference schemes (:mod:`numkin.derivatives`) and from the
differentiated loop equations (:mod:`numkin.analytic`).

Radians inside; degrees only at the edges, always labelled.
"""

from . import analytic, compare, derivatives, kinematics, linkages, units
from .errors import AssemblyError, BranchError, ConvergenceError, NumkinError
from .loops import Loop
from .mechanism import Mechanism
from .newton import NewtonResult, newton
from .sweep import SingularityWarning, Sweep, SweepEvent

__version__ = "0.1.0"

__all__ = [
    "AssemblyError",
    "BranchError",
    "ConvergenceError",
    "Loop",
    "Mechanism",
    "NewtonResult",
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

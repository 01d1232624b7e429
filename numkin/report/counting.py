"""Counting the work of a computation: point evaluations of a mechanism's compiled loop equations.

The work measure of :func:`numkin.report.work_precision_table`: exact counts,
the same in every run, where timings vary. They are numkin's own records:
a sweep keeps its ``nfev`` and ``njev``, and the derivatives of
:mod:`numkin.analytic` record theirs to any :func:`count_evaluations` open
for their mechanism.

Examples
--------
>>> import numpy as np
>>> from numkin import analytic, linkages
>>> mech = linkages.slider_crank(80, 200)
>>> sweep = mech.sweep(np.radians(np.arange(0, 91, 10)))      # 10 points
>>> with count_evaluations(mech) as count:
...     dq = analytic.tangent(sweep)                            # J q' = -dF/dtheta, J kept by the sweep
>>> count.total, count.points                                   # dF/dtheta at 10 points
(10, {'F_t': 10})
"""

from __future__ import annotations

import numpy as np

from .. import kinematics
from ..sweep import EvaluationCounter, Sweep, count_evaluations
from .study import silenced

__all__ = [
    "COUNTED_FUNCTIONS",
    "EvaluationCounter",
    "count_evaluations",
    "stencil_evaluations",
    "sweep_evaluations",
]

#: The kernels whose point evaluations numkin records (:func:`count_evaluations`), and what they
#: evaluate. A fused evaluation (residuals with the Jacobian) counts once under each.
COUNTED_FUNCTIONS = {
    "F": "the residuals of the loop equations (a sweep's nfev)",
    "J": "the Jacobian dF/dq (a sweep's njev)",
    "F_t": "dF/dtheta, the right-hand side of the velocity equations",
    "second": "the right-hand side of the acceleration equations",
}


def sweep_evaluations(sweep: Sweep) -> int:
    """Point evaluations of the compiled loop equations spent by a sweep: ``nfev + njev``.

    Read from the sweep's own record (``Sweep.nfev``,
    ``Sweep.njev``): exact, the same in every run.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> s = linkages.slider_crank(80, 200).sweep(np.radians([0.0]))
    >>> sweep_evaluations(s) == s.nfev + s.njev > 0
    True
    """
    return int(sweep.nfev) + int(sweep.njev)


def stencil_evaluations(sweep: Sweep) -> int:
    """Grid points at which a finite-difference scheme is evaluated on `sweep`.

    As :func:`numkin.kinematics.sweep_derivative` does it: every sample of
    an open grid; on a full turn differenced as periodic, the N distinct
    samples (the closing sample repeats the first and is copied).
    """
    mech = sweep.mechanism
    grid = kinematics.sweep_grid(sweep)
    angle = np.array([u in mech.angles for u in mech.unknowns], dtype=bool)
    rows = silenced(kinematics.prepare_rows, np.asarray(sweep.values), angle, mech.unknowns, sweep.inputs, grid,
                  mech.length_scale)
    return int(rows.y.shape[-1] - (1 if rows.periodic else 0))

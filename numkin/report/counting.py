"""Counting the work of a computation: point evaluations of a mechanism's compiled loop equations.

The work measure of :func:`numkin.report.work_precision_table`: exact counts,
the same in every run, where timings vary.
"""

from __future__ import annotations

from contextlib import contextmanager
from functools import cached_property
from typing import Iterator

import numpy as np

from .. import kinematics
from ..sweep import Sweep
from .study import silenced

__all__ = [
    "COUNTED_FUNCTIONS",
    "EvaluationCounter",
    "count_evaluations",
    "stencil_evaluations",
]

#: Functions of :class:`~numkin.compiled.CompiledMechanism` counted by :func:`count_evaluations`,
#: and where each call finds its input angles: ``"qt"`` ``f(q, t, ...)``, ``"t"`` ``f(t, ...)``,
#: ``"second"`` ``f(*q, *dq, t, *p)``, ``"scalar"`` one point per call. Methods built on these
#: (``tangent``, ``second_derivative``) are counted through them.
COUNTED_FUNCTIONS = {
    "F": "qt",
    "J": "qt",
    "F_t": "qt",
    "FJ_rows": "qt",
    "fixed_terms": "t",
    "_second": "second",
    "scalar_F": "scalar",
    "scalar_FJT": "scalar",
}


class EvaluationCounter:
    """Point evaluations of a mechanism's compiled functions, as counted by :func:`count_evaluations`.

    A *point evaluation* is one call of one compiled function of the loop
    equations (residuals, Jacobian, both together, dF/dtheta, the terms of
    the input alone, the acceleration right-hand side) at one input angle,
    real or complex: a call on N inputs counts N.

    Attributes
    ----------
    calls : dict
        Function name -> number of calls.
    points : dict
        Function name -> point evaluations.
    """

    def __init__(self) -> None:
        self.calls: dict = {}
        self.points: dict = {}

    @property
    def total(self) -> int:
        """All point evaluations counted."""
        return int(sum(self.points.values()))

    def add(self, name: str, points: int) -> None:
        self.calls[name] = self.calls.get(name, 0) + 1
        self.points[name] = self.points.get(name, 0) + int(points)

    def __repr__(self) -> str:
        return f"EvaluationCounter(total={self.total}, points={self.points})"


_ABSENT = object()


def _size(shape) -> int:
    return int(np.prod(shape, dtype=np.int64)) if shape else 1


def _points_of(kind: str, n: int, args, kwargs) -> int:
    """Number of input angles a call of a counted function evaluates at."""
    if kind == "scalar":
        return 1
    if kind == "t":
        t = args[0] if args else kwargs["t"]
        return _size(np.shape(t))
    if kind == "second":
        q0, t = args[0], args[2 * n]
    else:
        q = args[0] if args else kwargs["q"]
        t = args[1] if len(args) > 1 else kwargs["t"]
        q0 = q[0] if len(q) else 0.0
    return _size(np.broadcast_shapes(np.shape(t), np.shape(q0)))


@contextmanager
def count_evaluations(mechanism) -> Iterator[EvaluationCounter]:
    """Count the point evaluations of a mechanism's compiled functions inside a ``with`` block.

    The functions named in :data:`COUNTED_FUNCTIONS` of ``mechanism.compiled``
    are wrapped, for the duration of the block, by counters of calls and of
    input angles (a call on N inputs is N point evaluations; a call of a
    scalar function one). Everything that evaluates the loop equations --
    the sweep's sequential and batched Newton steps, the tangent and
    acceleration solves of :mod:`numkin.analytic`, the complex-step Newton
    -- goes through them, so the count is exact: it is what the code did,
    not an estimate, and it is the same in every run (it depends on the
    algorithm and the data, not on the machine's speed or load).

    The wrappers sit on this mechanism's ``compiled`` object only and are
    removed on leaving the block (functions compiled meanwhile are kept);
    calls from other threads during the block are counted too.

    Parameters
    ----------
    mechanism : Mechanism

    Yields
    ------
    EvaluationCounter

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> mech = linkages.slider_crank(80, 200)
    >>> sweep = mech.sweep(np.radians(np.arange(0, 91, 10)))      # 10 points
    >>> with count_evaluations(mech) as count:
    ...     dq = analytic.tangent(sweep)                            # J q' = -dF/dtheta
    >>> count.total, count.points                                   # J and dF/dtheta at 10 points
    (20, {'F_t': 10, 'J': 10})
    """
    comp = mechanism.compiled
    counter = EvaluationCounter()
    n = len(mechanism.unknowns)
    saved = []  # (name, value in the instance's __dict__ before, or _ABSENT; lazily compiled box)
    try:
        for name, kind in COUNTED_FUNCTIONS.items():
            attr = getattr(type(comp), name, None)
            box: dict = {}
            if name in vars(comp):  # a function stored on the instance, or a cached property already compiled
                box["f"] = vars(comp)[name]
                before = vars(comp)[name]
            elif isinstance(attr, cached_property):  # compiled on first use: not before (position-only work
                before = _ABSENT                      # must not compile the acceleration equations)

                def compile_now(_attr=attr):
                    return _attr.func(comp)

                box["compile"] = compile_now
            elif callable(attr):
                box["f"] = getattr(comp, name)  # a method, bound
                before = _ABSENT
            else:
                continue

            def counted(*args, _box=box, _name=name, _kind=kind, **kwargs):
                if "f" not in _box:
                    _box["f"] = _box["compile"]()
                counter.add(_name, _points_of(_kind, n, args, kwargs))
                return _box["f"](*args, **kwargs)

            saved.append((name, before, box, isinstance(attr, cached_property)))
            setattr(comp, name, counted)
        yield counter
    finally:
        for name, before, box, lazy in reversed(saved):
            if before is not _ABSENT:
                setattr(comp, name, before)
            elif lazy and "f" in box:  # compiled meanwhile: keep it, as the cached property would
                setattr(comp, name, box["f"])
            else:
                delattr(comp, name)


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

"""The result of a position sweep: :class:`Sweep`, and what it met on its way.

The algorithm that computes it, continuation on one assembly branch, is in
:mod:`numkin.continuation` (:func:`~numkin.continuation.run_sweep`).

Every sweep's angles are continuous along it (unwrapped): neighbouring
points never differ by a whole turn, whatever the grid, ``max_step`` or
length of the sweep. A point near or at a singular position is recorded as a
:class:`SweepEvent`; at a change point passed with ``on_singular="report"``
the event names the branch kept and carries its tangent, so that
derivatives at the singular input can be taken from that branch.
"""

from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Iterator

import numpy as np

from .errors import InputError
from .newton import COND_MAX, COND_WARN
from .units import deg_text, input_degrees

__all__ = ["Sweep", "SweepEvent", "SingularityWarning", "COND_MAX", "COND_WARN", "EvaluationCounter",
           "count_evaluations", "record_evaluations", "check_sweep"]


def check_sweep(sweep):
    """``(mechanism, inputs, values)`` of a sweep, or :class:`~numkin.errors.InputError` for anything else."""
    for attr in ("mechanism", "inputs", "values"):
        if not hasattr(sweep, attr):
            hint = ": give mechanism.sweep(inputs)" if hasattr(sweep, "unknowns") else ""
            raise InputError(f"sweep must be a numkin Sweep (from Mechanism.sweep), got {type(sweep).__name__}{hint}")
    return sweep.mechanism, np.asarray(sweep.inputs, dtype=float), np.asarray(sweep.values, dtype=float)


class SingularityWarning(UserWarning):
    """A sweep passed close to, or through, a singular position."""


@dataclass(frozen=True)
class SweepEvent:
    """Something a sweep met on its way: a near-singular point or a change point.

    Attributes
    ----------
    kind : str
        ``"near-singular"``, ``"change point"`` or ``"singular"``.
    input_value : float
        Input (rad) where it was met (a change point: located to about
        1e-9 of the sweep's span).
    loop : str
        Loop concerned.
    message : str
    branch : str
        At a change point: the branch the sweep kept, in words (e.g.
        ``"the crossed branch"``); empty otherwise.
    tangent : tuple of float
        At a change point: ``dq/d(input)`` of the kept branch at
        ``input_value``, in ``Sweep.unknowns`` order (the mean of the two
        one-sided tangents below, which agree when the tangent is
        continuous); empty otherwise.
    tangent_before, tangent_after : tuple of float
        The one-sided tangents just before and just after the change point
        (in the sweep's direction).
    tangent_continuous : bool or None
        Whether the two one-sided tangents agree (to 1e-3 relative): the
        branch kept is the one whose tangent is continuous.
    """

    kind: str
    input_value: float
    loop: str
    message: str
    branch: str = ""
    tangent: tuple = ()
    tangent_before: tuple = ()
    tangent_after: tuple = ()
    tangent_continuous: bool | None = None


@dataclass
class Sweep:
    """Positions of a mechanism over a sweep of its input.

    Attributes
    ----------
    mechanism : Mechanism
    inputs : ndarray (N,)
        Input values, rad.
    values : ndarray (n, N)
        Unknowns in ``mechanism.unknowns`` order. Angles in rad, continuous
        along the sweep (unwrapped: no 2 pi jumps); lengths in the
        mechanism's length unit.
    iterations : ndarray (N,)
        Newton iterations spent at each point (by its last corrector).
    residual : ndarray (N,)
        Scaled residual norm at each point.
    cond : ndarray (N,)
        Largest condition number of the loops' scaled Jacobian blocks.
    events : list of SweepEvent
        Singular and near-singular positions met; a change point passed
        with ``on_singular="report"`` carries the kept branch's tangent
        (``SweepEvent.tangent``).
    jacobian : str
        How Newton's Jacobian was computed.
    tol : float
        Stopping tolerance used.
    nfev : int
        Point evaluations of the compiled residuals spent by the sweep: an
        evaluation at N inputs counts N, one fused with the Jacobian counts
        here and in ``njev``, a finite-difference Jacobian's n (forward) or
        2n (central) residuals count here.
    njev : int
        Point evaluations of the Jacobian (symbolic, or one per
        finite-difference Jacobian at one input).
    jacobian_rows : list or None
        The Jacobian at ``values`` as the sweep left it, n*n rows ((N,)
        arrays or numbers; entry (i, j) is row ``i * n + j``), reused by the
        exact derivatives of :mod:`numkin.analytic`; None for a sweep put
        together otherwise or copied with ``dataclasses.replace`` (its
        Jacobian is then computed when needed). Set by
        :meth:`Mechanism.sweep`; change no value in place afterwards.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0, 361)))
    >>> sweep["theta4"].shape
    (361,)
    >>> list(sweep.to_frame().columns[:3])
    ['theta2 [deg]', 'theta3 [deg]', 'theta4 [deg]']
    """

    mechanism: object
    inputs: np.ndarray
    values: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    cond: np.ndarray
    events: list = field(default_factory=list)
    jacobian: str = "symbolic"
    tol: float = 1e-12
    nfev: int = 0
    njev: int = 0
    #: The Jacobian rows at ``values`` as the sweep left them (see the class docstring). A plain
    #: attribute, not a field: a copy with other values (``dataclasses.replace``) does not inherit it.
    jacobian_rows = None

    @property
    def unknowns(self) -> tuple:
        return self.mechanism.unknowns

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.values[self.unknowns.index(name)]
        except ValueError:
            if name == self.mechanism.input_name:
                return self.inputs
            raise KeyError(f"{name!r} is not an unknown of {self.mechanism.name}; unknowns are {list(self.unknowns)}") from None

    def __contains__(self, name) -> bool:
        return name in self.unknowns

    def __len__(self) -> int:
        return self.inputs.size

    def unit(self, name: str) -> str:
        """Unit of an unknown's values: ``"rad"`` or the length unit."""
        return "rad" if name in self.mechanism.angles else self.mechanism.length_unit

    @property
    def step(self) -> float | None:
        """The uniform input step (rad), or None if the grid is not uniform."""
        if self.inputs.size < 2:
            return None
        d = np.diff(self.inputs)
        return float(d.mean()) if np.allclose(d, d[0], rtol=1e-9, atol=1e-14) else None

    def index(self, input_value: float) -> int:
        """Index of the grid point nearest to ``input_value`` (rad)."""
        return int(np.argmin(np.abs(self.inputs - input_value)))

    def points(self) -> dict:
        """Coordinates of the mechanism's named points: name -> (2, N) array."""
        return self.mechanism.point_coordinates(self.values, self.inputs)

    def to_frame(self, degrees: bool = True):
        """A pandas DataFrame: one row per input, columns labelled with units.

        Angles are given in degrees (``"theta3 [deg]"``) when ``degrees`` is
        true, else in rad; lengths in the mechanism's unit; then the Newton
        diagnostics ``iterations``, ``residual`` and ``cond``. What each
        column holds is in ``attrs["kinds"]`` (:mod:`numkin.column_kinds`).
        """
        import pandas as pd

        from .column_kinds import set_kinds

        angle_unit = "deg" if degrees else "rad"
        conv = np.degrees if degrees else (lambda a: a)
        input_col = f"{self.mechanism.input_name} [{angle_unit}]"
        cols = {input_col: input_degrees(self.inputs) if degrees else self.inputs}
        for name, vals in zip(self.unknowns, self.values):
            if name in self.mechanism.angles:
                cols[f"{name} [{angle_unit}]"] = conv(vals)
            else:
                cols[f"{name} [{self.mechanism.length_unit}]"] = vals
        kinds = {input_col: "input", **{c: "value" for c in list(cols)[1:]}}
        cols["iterations"] = self.iterations
        cols["residual"] = self.residual
        cols["cond"] = self.cond
        return set_kinds(pd.DataFrame(cols), {**kinds, "iterations": "count", "residual": "error", "cond": "error"})

    def __repr__(self) -> str:
        lo, hi = (deg_text(self.inputs[0]), deg_text(self.inputs[-1])) if self.inputs.size else ("", "")
        return (
            f"Sweep({self.mechanism.name!r}, {self.inputs.size} points {lo}..{hi}, "
            f"unknowns={list(self.unknowns)}, max iterations={int(self.iterations.max(initial=0))}, "
            f"max cond={float(self.cond.max(initial=0)):.3g}, events={len(self.events)})"
        )



class EvaluationCounter:
    """Point evaluations of a mechanism's compiled functions, recorded by numkin as it works.

    A *point evaluation* is one evaluation of one compiled function of the
    loop equations at one input angle, real or complex: a call on N inputs
    counts N. Kernels: ``"F"`` the residuals and ``"J"`` the Jacobian (a
    sweep's ``nfev`` and ``njev``), ``"F_t"`` dF/dtheta and ``"second"``
    the acceleration right-hand side of :mod:`numkin.analytic`.

    Attributes
    ----------
    calls : dict
        Kernel name -> number of records.
    points : dict
        Kernel name -> point evaluations.

    Examples
    --------
    >>> c = EvaluationCounter()
    >>> c.add("F", 3); c.add("J", 3); c.add("F", 1)
    >>> c.total, c.points
    (7, {'F': 4, 'J': 3})
    """

    def __init__(self) -> None:
        self.calls: dict = {}
        self.points: dict = {}

    @property
    def total(self) -> int:
        """All point evaluations counted."""
        return int(sum(self.points.values()))

    def add(self, name: str, points: int) -> None:
        """Add ``points`` point evaluations of the kernel ``name`` (nothing if zero)."""
        if points:
            self.calls[name] = self.calls.get(name, 0) + 1
            self.points[name] = self.points.get(name, 0) + int(points)

    def __repr__(self) -> str:
        return f"EvaluationCounter(total={self.total}, points={self.points})"


_COUNTERS: ContextVar = ContextVar("numkin_evaluation_counters", default=())


def record_evaluations(mechanism, name: str, points: int) -> None:
    """Add ``points`` evaluations of kernel ``name`` to every counter open for ``mechanism``.

    Called by numkin's own sweeps and derivatives with the counts they keep
    (a few integer additions per kernel call); a no-op when nothing counts.
    """
    for mech, counter in _COUNTERS.get():
        if mech is mechanism:
            counter.add(name, points)


@contextmanager
def count_evaluations(mechanism) -> Iterator[EvaluationCounter]:
    """Collect, inside a ``with`` block, the evaluation counts numkin records for ``mechanism``.

    Sweeps (``Sweep.nfev``, ``Sweep.njev``, as kernels ``"F"`` and
    ``"J"``) and the exact and complex-step derivatives of
    :mod:`numkin.analytic` record the point evaluations of the compiled loop
    equations they spend; the counts are exact and the same in every run.
    Counters nest; other mechanisms' work is not counted.

    Yields
    ------
    EvaluationCounter

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> mech = linkages.four_bar(4, 1, 3, 3)
    >>> with count_evaluations(mech) as count:
    ...     s = mech.sweep(np.radians([0.0, 10.0]))
    >>> count.points == {"F": s.nfev, "J": s.njev}
    True
    """
    counter = EvaluationCounter()
    token = _COUNTERS.set(_COUNTERS.get() + ((mechanism, counter),))
    try:
        yield counter
    finally:
        _COUNTERS.reset(token)

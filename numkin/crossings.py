"""What a continuation meets on its way: change points passed, recorded, raised or described.

:class:`Crossings` is the part of :class:`numkin.march.Continuation` that
keeps the change points a sweep passes (where a loop's Jacobian changes
sign and two assembly branches meet): placed by the sign change of the
Jacobian's determinant, raised once the march has gone on past them
(``on_singular="raise"``), or described when the sweep is done, with the
branch kept and its tangent from each side (``on_singular="report"``). A
change point passed on the way from the default guess to the sweep's first
input is said to lie there, before the sweep.
"""

from __future__ import annotations

import math

import numpy as np

from .errors import BranchError, ConvergenceError, warn
from .sweep import SingularityWarning, SweepEvent
from .units import deg_text

__all__ = ["Crossings", "AT_END"]

#: A change point found within this (relative) distance of the input where a march stops is at that input:
#: its Jacobian's determinant, linear between the last two points, is round-off there (the sign's noise).
AT_END = 1e-10


class Crossings:
    """The change points of one sweep (a part of :class:`numkin.march.Continuation`, whose state it reads:
    ``crossings``, ``pending``, ``approach``, ``before_sweep``, ``passed_on_way``, ``events``, ``on_singular``, the
    mechanism and its one-point kernels)."""

    def record(self, kind, t, loop, message, *, raise_kind=None, cond=None, **extra):
        """Raise (``on_singular="raise"``) or record an event once and warn."""
        if raise_kind is not None and self.on_singular == "raise":
            raise BranchError(message, kind=raise_kind, input_value=float(t), loop=loop, cond=cond)
        for e in self.events:  # the same crossing met again (from a node, then from a grid point)
            if e.kind == kind and e.loop == loop and abs(e.input_value - t) <= 1e-6 * max(1.0, abs(t)):
                return
        self.events.append(SweepEvent(kind, float(t), loop, message, **extra))
        warn(message, SingularityWarning)

    def crossing(self, t, x, t_new, v_new, k):
        """Input where loop ``k``'s Jacobian determinant, linear between two solved points, is zero."""
        a, b = self.blocks.blocks[k]
        n = self.n

        def det(v):
            rows = v[n : n + n * n]
            return float(np.linalg.det(np.array([[rows[i * n + j] for j in range(a, b)] for i in range(a, b)])))

        v_old = self.eval1(x, t)
        d0, d1 = (det(v_old), det(v_new)) if v_old is not None else (math.nan, math.nan)
        if not (math.isfinite(d0) and math.isfinite(d1) and d0 != d1):
            return 0.5 * (t + t_new)
        return t + (t_new - t) * min(1.0, max(0.0, d0 / (d0 - d1)))

    def change_point(self, t, t_new, loop, tc=None):
        """Note a change point passed: raised (``on_singular="raise"``) once the march has gone on past it
        (:meth:`raise_pending`), so that a toggle, where no solution lies beyond, is said as one; or kept
        (once) to be described when the sweep is done."""
        tc = 0.5 * (t + t_new) if tc is None else tc
        if self.on_singular == "raise" and self.pending is None:  # (the first passed is the one raised)
            self.pending = (tc, loop)
        met = _same(self.crossings, tc, loop)
        if met is None:
            self.crossings.append((tc, loop))
        if self.approach is not None:
            self.before_sweep.append((tc, loop))
            self.passed_on_way.append((tc, loop))
        elif met is not None and met in self.before_sweep:
            # passed again by the sweep itself: the sweep's, where the sweep found it (the sweep's end, if it
            # stops there: then :meth:`unpassed_crossings` gives it back to the way from the guess)
            self.before_sweep.remove(met)
            self.crossings[self.crossings.index(met)] = (tc, loop)

    def where_passed(self, tc, loop) -> str:
        """``" on the way from the default guess at ... to the sweep's first input ..."`` for a change point
        passed before the sweep (marching from the default guess's input to the sweep's start), else ``""``."""
        if _same(self.before_sweep, tc, loop) is None:
            return ""
        tg, t0 = self.approach_inputs
        return (f" on the way from the default guess at {deg_text(tg, 3)} to the sweep's first input "
                f"{deg_text(t0, 3)}, before the sweep")

    def unpassed_crossings(self, t_end, o):
        """Forget the change points found at ``t_end``, where a march stops: no step went past them (a
        toggle reached there, or a singular position the march ends on, shows either sign of the Jacobian,
        and whether the linkage goes on there shows only in a step beyond). Returns the orientations ``o``
        with those loops' as before them."""
        if not self.crossings:
            return o
        o = list(o) if o is not None else None
        kept = []
        at_end = AT_END * max(1.0, abs(t_end))
        for tc, loop in self.crossings:
            if abs(tc - t_end) <= at_end:
                if o is not None:
                    k = self.loop_names.index(loop)
                    o[k] = -o[k]
                on_way = _same(self.passed_on_way, tc, loop)
                if self.approach is None and on_way is not None:
                    # passed on the way from the guess; the sweep only came back to it: passed, before the sweep
                    kept.append((tc, loop))
                    if _same(self.before_sweep, tc, loop) is None:
                        self.before_sweep.append(on_way)
                    continue
                for forgotten in (self.before_sweep, self.passed_on_way):
                    met = _same(forgotten, tc, loop)
                    if met is not None:
                        forgotten.remove(met)
            else:
                kept.append((tc, loop))
        self.crossings = kept
        if self.pending is not None and abs(self.pending[0] - t_end) <= at_end:
            self.pending = None
        return o

    def raise_pending(self):
        """Raise the change point the march has gone past (``on_singular="raise"``), if any."""
        if self.pending is None:
            return
        tc, loop = self.pending
        self.pending = None
        way = self.where_passed(tc, loop)
        advice = " (or pass sweep() a guess at its first input)" if way else ""
        self.record(
            "change point", tc, loop,
            f"{self.mech.name}: loop '{loop}' passes a singular position at input {deg_text(tc, 4)}{way} (its "
            "Jacobian changes sign): a change point, where the branches meet and the continuation is ambiguous; pass "
            f"on_singular='report' to go on along the branch whose tangent is continuous{advice}",
            raise_kind="change point",
        )

    def one_sided_tangent(self, t, X, O, cond, tc, side, h):
        """dq/d(input) at the change point ``tc`` from one side (``side`` -1 or +1), on the sweep's branch.

        Marches from the best-conditioned grid point on that side to
        ``tc + side h`` and ``tc + side 2h`` and extrapolates the tangents
        there linearly to ``tc`` (error of order h^2). None if there is no
        such grid point or the march fails.
        """
        on_side = np.flatnonzero((np.sign(t - tc) == side) & (cond < 1e6))
        state = (list(self.crossings), list(self.before_sweep), self.pending)  # (the tangent's marches pass nothing)
        if on_side.size == 0:
            return None
        j = int(on_side[np.argmin(np.abs(t[on_side] - tc))])
        xj = X[:, j].tolist()
        d, o = self.local1(self.eval1(xj, float(t[j])))
        if d is None:
            return None
        try:
            x1, d1, o1, _ = self.march(float(t[j]), xj, d, o, tc + 2 * side * h)
            _, d2, _, _ = self.march(tc + 2 * side * h, x1, d1, o1, tc + side * h)
        except (BranchError, ConvergenceError):
            return None
        finally:
            self.crossings, self.before_sweep, self.pending = state
        if d1 is None or d2 is None:
            return None
        return [2.0 * b - a for a, b in zip(d1, d2)]

    def describe_crossings(self, t, X, O, cond):
        """Record every change point passed (``on_singular="report"``): the branch kept and its tangent."""
        mech = self.mech
        inp = mech.input_name
        branch = getattr(mech, "branch", None)
        kept = f"the {branch} branch" if branch and self.started_on_default else "the branch the sweep was on"
        span = float(abs(t[-1] - t[0])) if t.size > 1 else 1.0
        h = min(1e-3, 0.25 * span)
        for tc, loop in list(self.crossings):
            sides = [self.one_sided_tangent(t, X, O, cond, tc, side, h) for side in (-1.0, 1.0)]
            if t.size > 1 and t[-1] < t[0]:
                sides.reverse()  # before and after in the sweep's direction
            before, after = (list(v) if v is not None else [math.nan] * self.n for v in sides)
            known = [v for v in (before, after) if not math.isnan(v[0])]
            tangent = [sum(c) / len(known) for c in zip(*known)] if known else [math.nan] * self.n
            scale = max([abs(a) * w for a, w in zip(tangent, self.inv_xs)] + [1.0])
            continuous = None
            if len(known) == 2:
                continuous = all(abs(a - b) * w <= 1e-3 * scale for a, b, w in zip(before, after, self.inv_xs))
            rates = ", ".join(f"d{u}/d{inp} = {v:.4f}" for u, v in zip(mech.unknowns, tangent))
            how = {True: "its tangent is continuous", False: "its tangent jumps here",
                   None: "its tangent from one side"}[continuous]
            way = self.where_passed(tc, loop)
            branch = "the branch the guess was on" if way else kept
            message = (
                f"{mech.name}: loop '{loop}' passes a singular position at input {deg_text(tc, 4)}{way} (its "
                f"Jacobian changes sign): a change point, where the branches meet; kept {branch} ({how}: {rates})"
            )
            self.record(
                "change point", tc, loop, message, branch=branch, tangent=tuple(tangent),
                tangent_before=tuple(before), tangent_after=tuple(after), tangent_continuous=continuous,
            )


def _same(points, tc, loop):
    """The entry ``(input, loop)`` of `points` that is the change point at `tc` of `loop` (to 1e-6), or None."""
    return next(((c, lp) for c, lp in points if lp == loop and abs(c - tc) <= 1e-6 * max(1.0, abs(tc))), None)

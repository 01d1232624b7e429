"""The grid points between a sweep's nodes, solved in one Newton batch, and the sweep's singular points.

A predictor from the nodes (on an even grid round a whole turn, the
trigonometric polynomial through their values and tangents where it is
trusted: :mod:`numkin.turn_predictor`; else Hermite polynomials through their
values, tangents and curvatures: quintic; cubic next to a node whose
curvature is unknown; with few points per node, curvatures from the
neighbouring nodes, used where they save an iteration), then Newton on all
points at once; points that fail the acceptance tests, and every
segment where batch points land on another turn, are marched point by point.
"""

from __future__ import annotations

import math

import numpy as np

from .errors import warn
from .march import COND_TANGENT, MAX_CORRECTION, Continuation
from .newton import COND_MAX, COND_WARN, is_singular, residual_floor
from .newton import colmax as _colmax
from .predictors import (
    QUINTIC_MIN_POINTS,
    free_quintic,
    hermite,
    hermite_uniform,
    node_curvatures,
    quintic_pays,
    quintic_terms,
)
from .sweep import SingularityWarning, SweepEvent
from .units import deg_text
from .turn_predictor import turn_predict

__all__ = ["nodes_of", "fill", "report_near_singular", "CHUNK"]


def nodes_of(t: np.ndarray, max_step: float, largest_step: float | None = None) -> np.ndarray:
    """Grid indices marched sequentially: at most ``max_step`` apart where the grid allows.

    ``largest_step``: the largest ``|t[i + 1] - t[i]|``, if known.

    Examples
    --------
    >>> nodes_of(np.linspace(0.0, 1.0, 11), 0.35).tolist()
    [0, 3, 6, 9, 10]
    """
    if t.size <= 2:
        return np.arange(t.size)
    h = float(np.abs(t[1:] - t[:-1]).max()) if largest_step is None else largest_step
    every = max(1, int(max_step / h * (1.0 + 1e-9))) if h > 0 else 1
    last = t.size - 1
    return np.arange(0, t.size, every) if last % every == 0 else np.array([*range(0, last, every), last])



#: Whether segments of fewer than QUINTIC_MIN_POINTS points are predicted by the quintic on
#: :func:`numkin.predictors.free_curvatures` (else by the cubic).
FREE_CURVATURES = True

#: Whether a sweep round a whole turn is predicted by :func:`numkin.turn_predictor.turn_predict` where
#: it is trusted (else the Hermite predictors everywhere).
TURN = True

#: Grid points solved together in one Newton batch: the batch's temporaries stay this
#: many columns wide however long the sweep.
CHUNK = 8192


def fill(ctx: Continuation, t, X, D, O, iters, nodes, every=None, even=False):
    """Solve the grid points between nodes by Newton batches (predicted from the nodes).

    The points are taken :data:`CHUNK` at a time. ``even``: the inputs are evenly spaced (on a
    grid round a whole turn, the nodes' trigonometric polynomial predicts them where it is
    trusted: :func:`numkin.turn_predictor.turn_predict`; else Hermite polynomials). ``every``:
    besides, the nodes are every ``every``-th input, the last included (one matrix product
    predicts them: :func:`numkin.predictors.hermite_uniform`). Returns the scaled
    residual norm (N,), the largest condition number of the loops' blocks
    (N,) and the Jacobian rows at every point of the sweep.
    """
    N = t.size
    if nodes.size == N:
        f, jac = ctx.eval_batch(X, t)
        return _colmax(np.abs(f)) / ctx.fscale, _colmax(ctx.blocks.cond(jac, N)), jac
    fine_mask = np.empty(N, dtype=bool)
    fine_mask.fill(True)
    fine_mask[nodes] = False
    uniform = every is not None and N <= CHUNK
    # every column's left node (a node is its own left node, at s = 0), made where first read: by the
    # Hermite predictor off an even grid, and by the rarer tests below
    k = None

    def left_nodes():
        nonlocal k
        if k is None:
            k = np.arange(N) // every if uniform else np.searchsorted(nodes, np.arange(N), side="right") - 1
        return k

    # the round-off floor of the residual: sines of the largest angles and inputs of the sweep
    big = float(np.maximum.reduce(np.abs(X.take(nodes, axis=1)), axis=None) * max(ctx.inv_xs))
    ctx.floor = residual_floor([big], max(abs(float(t[0])), abs(float(t[-1]))))
    On = O.take(nodes, axis=1)
    one_orientation = bool((On == On[:, :1]).all())
    scale = None if all(w == 1.0 for w in ctx.inv_xs) else np.asarray(ctx.inv_xs)[:, None]
    ok = np.empty(N, dtype=bool)
    residual = np.empty(N)
    cond = np.empty(N) if N <= CHUNK else None  # (a long sweep's after its batches: a lower peak of memory)
    jac = None
    # round a whole turn, the nodes' trigonometric polynomial where trusted; else Hermite: with many points
    # per segment, curvatures from the tangent field (a few kernel calls on the nodes); with fewer, from the
    # nodes' values and tangents alone
    terms = None  # the quintic predictor's terms over the cubic, once for every chunk
    x_turn = turn_predict(t, X, D, nodes, angle_rows=ctx.angle_idx, inv_xs=ctx.inv_xs, even=even) if TURN else None
    if x_turn is None and N >= QUINTIC_MIN_POINTS * nodes.size:
        terms = quintic_terms(t, X, D, node_curvatures(ctx, t, X, D, nodes), nodes)
    elif x_turn is None and FREE_CURVATURES and nodes.size >= 3:
        alpha, beta, gap = free_quintic(t, X, D, nodes)
        terms = (alpha, beta) if quintic_pays(gap, ctx.inv_xs) else None
    for c0 in range(0, N, CHUNK):
        c = slice(c0, min(N, c0 + CHUNK))
        fm, tc = fine_mask[c], t[c]
        if x_turn is not None:
            x_pred = x_turn[:, c]  # (its columns, kept for the correction: the batch iterates in a copy)
        elif uniform:
            x_pred = hermite_uniform(t.take(nodes), X, D, every, terms)
        else:
            x_pred = hermite(tc, t, X, D, None, nodes, left_nodes()[c], terms)
        x, converged, it, f, jac_c = ctx.newton_batch(x_pred.copy(), tc, fm, overwrite=True)
        # accept a point if Newton converged on the turn of its prediction, the correction is
        # small and no loop changed orientation
        x_pred -= x
        np.abs(x_pred, out=x_pred)
        if scale is not None:
            x_pred *= scale
        okc = converged & (_colmax(x_pred) <= MAX_CORRECTION)
        del x_pred
        if cond is not None:
            cond_c, o = ctx.blocks.cond_signs(jac_c, tc.size, quiet=False)  # (under the sweep's errstate)
            cond[c] = _colmax(cond_c)
            del cond_c
        else:
            o = ctx.blocks.signs(jac_c, tc.size)
        if one_orientation:
            for kk in range(O.shape[0]):
                okc &= o[kk] == On[kk, 0]
        else:
            kc = left_nodes()[c]
            a = nodes.take(kc)
            b = nodes.take(np.minimum(kc + 1, nodes.size - 1))
            Oa, Ob = O.take(a, axis=1), O.take(b, axis=1)
            for kk in range(O.shape[0]):
                okc &= (o[kk] == Oa[kk]) & (Oa[kk] == Ob[kk])
        ok[c] = okc | ~fm
        X[:, c] = x  # the nodes were not active: unchanged
        np.copyto(O[:, c], o, where=fm)
        np.copyto(iters[c], it, where=fm)
        residual[c] = _colmax(np.abs(f)) / ctx.fscale
        jac = jac_c if c.stop - c.start == N else _put_rows(jac, jac_c, c, N)
        del x, f, jac_c, o
    if ctx.angle_idx:
        # Both nodes of a segment are right (marched), so a run of batch points on another turn
        # shows as a neighbour step of half a turn or more: march that whole segment.
        rows = ctx.angle_idx
        angles = X[rows[0]] if len(rows) == 1 else X if len(rows) == X.shape[0] else X.take(rows, axis=0)
        steps = angles[..., 1:] - angles[..., :-1]
        np.abs(steps, out=steps)
        if not np.maximum.reduce(steps, axis=None) < math.pi:  # (a NaN is no jump: looked at as a jump would be)
            jump = np.flatnonzero((steps if len(rows) == 1 else steps.max(axis=0)) >= math.pi)
            if jump.size:
                k = left_nodes()
                ok &= ~(fine_mask & np.isin(k, k.take(jump)))
    if cond is None:
        cond = _conds(ctx, jac, N)
    n = X.shape[0]
    redone = set()

    def singular_at(i):
        """Whether grid point i sits on a singular position (its tangent and orientation are noise)."""
        if i not in redone:
            return not cond[i] <= COND_TANGENT
        v = ctx.eval1(X[:, i].tolist(), float(t[i]))
        return v is None or not max(ctx.blocks.cond1(v[n : n + n * n])) <= COND_TANGENT

    # A node on a singular position (a change point on the grid) gives the Hermite predictor
    # and the orientation test nothing to trust: its segments are marched.
    bad_nodes = (~(cond.take(nodes) <= COND_TANGENT)).nonzero()[0]
    if bad_nodes.size:
        k = left_nodes()
        ok &= ~(fine_mask & (np.isin(k, bad_nodes) | np.isin(k + 1, bad_nodes)))
    redo = (~ok).nonzero()[0]
    if redo.size:
        # Points the batch could not place safely are reached one by one from their left
        # neighbour, or from the nearest point before it that is not on a singular position:
        # the march then passes the singular one with its own tests of branch and tangent.
        for kk in redo.tolist():
            left = kk - 1
            while left > 0 and singular_at(left):
                left -= 1
            tl = float(t[left])
            xl = X[:, left].tolist()
            if np.all(np.isfinite(D[:, left])):
                dl = D[:, left].tolist()
            else:
                dl, _ = ctx.local1(ctx.eval1(xl, tl))
            previous = (float(t[left - 1]), X[:, left - 1].tolist()) if left >= 1 else None
            xk, dk, ok_, iters[kk] = ctx.march(tl, xl, dl, O[:, left].tolist(), float(t[kk]), previous)
            X[:, kk], D[:, kk], O[:, kk] = xk, dk, ok_
            redone.add(kk)
        f_redo, jac_redo = ctx.eval_batch(X[:, redo], t[redo])
        if N <= CHUNK:  # the batch's own rows, which may be arrays the kernel was given: not written into
            jac = [r.copy() if np.ndim(r) else r for r in jac]
        residual[redo] = _colmax(np.abs(f_redo)) / ctx.fscale
        jac = _put_rows(jac, jac_redo, redo, N)
        cond[redo] = _colmax(ctx.blocks.cond(jac_redo, redo.size))
    return residual, cond, jac


def _conds(ctx, jac, N):
    """The largest condition number of the loops' blocks at every point, CHUNK points at a time."""
    cond = np.empty(N)
    for c0 in range(0, N, CHUNK):
        c = slice(c0, min(N, c0 + CHUNK))
        cond[c] = _colmax(ctx.blocks.cond_signs([r[c] if np.ndim(r) else r for r in jac], c.stop - c.start,
                                                quiet=False)[0])
    return cond


def _put_rows(rows, sub, idx, N):
    """Jacobian rows of every point (arrays, or numbers where constant) with the columns ``idx``
    set from ``sub``; ``rows`` None: new rows."""
    if rows is None:
        rows = [np.empty(N) if np.ndim(r) else r for r in sub]
    for i, r in enumerate(sub):
        if np.ndim(rows[i]):
            rows[i][idx] = r
        elif np.ndim(r) or r != rows[i]:
            full = np.full(N, rows[i], dtype=float)
            full[idx] = r
            rows[i] = full
    return rows


def report_near_singular(ctx, t, X, cond):
    """Record (or raise, as ``ctx.on_singular`` says) the first singular point of a sweep, and warn
    of the points near a singular position (condition number above ``COND_WARN``)."""
    if not cond.size or np.maximum.reduce(cond) <= COND_WARN:  # (a NaN fails the test)
        return
    singular = np.flatnonzero(is_singular(cond))
    if singular.size:
        k = singular[0]
        loop, _ = ctx.worst1(X[:, k].tolist(), float(t[k]), which="cond")
        ctx.record(
            "singular", t[k], loop,
            f"{ctx.mech.name}: the Jacobian of loop '{loop}' is singular at input {deg_text(t[k], 3)} "
            f"(condition number {cond[k]:.3g}): a toggle or change point, where the branch cannot be told",
            raise_kind="singular", cond=float(cond[k]),
        )
    near = np.flatnonzero((cond > COND_WARN) & (cond <= COND_MAX))
    if near.size == 0:
        return
    k = near[np.argmax(cond[near])]
    loop, _ = ctx.worst1(X[:, k].tolist(), float(t[k]), which="cond")
    ctx.events.append(
        SweepEvent(
            "near-singular", float(t[k]), loop,
            f"{ctx.mech.name}: {near.size} point(s) near a singular position of loop '{loop}' "
            f"(condition number up to {cond[k]:.3g} at {deg_text(t[k], 3)}): expect lost digits there",
        )
    )
    warn(ctx.events[-1].message, SingularityWarning)

"""The grid points between a sweep's nodes, solved in one Newton batch, and the sweep's singular points.

A cubic Hermite predictor from the nodes' values and tangents, then Newton
on all points at once; points that fail the acceptance tests, and every
segment where batch points land on another turn, are marched point by point.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .compiled import stack_rows
from .march import MAX_CORRECTION, Continuation, deg_text
from .newton import COND_MAX, COND_WARN, colmax as _colmax, is_singular, residual_floor
from .sweep import SweepEvent, SingularityWarning

__all__ = ["nodes_of", "fill", "report_near_singular"]


def nodes_of(t: np.ndarray, max_step: float) -> np.ndarray:
    """Grid indices marched sequentially: at most ``max_step`` apart where the grid allows."""
    if t.size <= 2:
        return np.arange(t.size)
    h = np.abs(np.diff(t)).max()
    every = max(1, int(max_step / h * (1.0 + 1e-9))) if h > 0 else 1
    idx = np.arange(0, t.size, every)
    if idx[-1] != t.size - 1:
        idx = np.append(idx, t.size - 1)
    return idx


def fill(ctx: Continuation, t, X, D, O, iters, nodes):
    """Solve the grid points between nodes in one Newton batch (cubic Hermite predictor).

    Returns the residuals (n, N) and Jacobian rows at every point of the sweep.
    """
    N = t.size
    if nodes.size == N:
        return ctx.eval_batch(X, t)
    fine_mask = np.ones(N, dtype=bool)
    fine_mask[nodes] = False
    # every column's left and right node (a node is its own left node, at s = 0)
    k = np.searchsorted(nodes, np.arange(N), side="right") - 1
    x_pred = _hermite(t, X, D, nodes, k)
    # the round-off floor of the residual: sines of the largest angles and inputs of the sweep
    big = float(np.abs(X.take(nodes, axis=1)).max() * max(ctx.inv_xs))
    ctx.floor = residual_floor([big], max(abs(float(t[0])), abs(float(t[-1]))))
    x, converged, it, f, jac = ctx.newton_batch(x_pred.copy(), t, fine_mask, overwrite=True)
    # accept a point if Newton converged on the turn of its prediction, the correction is
    # small and no loop changed orientation
    corr = np.abs(x - x_pred)
    if not all(w == 1.0 for w in ctx.inv_xs):
        corr *= np.asarray(ctx.inv_xs)[:, None]
    ok = converged & (_colmax(corr) <= MAX_CORRECTION)
    del corr, x_pred
    o = ctx.blocks.signs(jac, N)
    On = O.take(nodes, axis=1)
    if (On == On[:, :1]).all():  # one orientation at all nodes: compare with it
        for kk in range(O.shape[0]):
            ok &= o[kk] == On[kk, 0]
    else:
        a = nodes.take(k)
        b = nodes.take(np.minimum(k + 1, nodes.size - 1))
        Oa, Ob = O.take(a, axis=1), O.take(b, axis=1)
        for kk in range(O.shape[0]):
            ok &= (o[kk] == Oa[kk]) & (Oa[kk] == Ob[kk])
    ok |= ~fine_mask
    X[...] = x  # the nodes were not active: unchanged
    if ctx.angle_idx:
        # Both nodes of a segment are right (marched), so a run of batch points on another turn
        # shows as a neighbour step of half a turn or more: march that whole segment.
        ang = X if len(ctx.angle_idx) == X.shape[0] else X[ctx.angle_idx]
        jump = np.flatnonzero(_colmax(np.abs(np.diff(ang, axis=1))) >= math.pi)
        if jump.size:
            ok &= ~(fine_mask & np.isin(k, k.take(jump)))
    O[...] = np.where(fine_mask, o, O)
    iters[...] = np.where(fine_mask, it, iters)
    redo = np.flatnonzero(~ok)
    if redo.size:
        # Points the batch could not place safely are reached one by one from their left neighbour.
        tl = t.tolist()
        for k in redo.tolist():
            left = k - 1
            xl = X[:, left].tolist()
            if np.all(np.isfinite(D[:, left])):
                dl = D[:, left].tolist()
            else:
                dl, _ = ctx.local1(ctx.eval1(xl, tl[left]))
            xk, dk, ok_, iters[k] = ctx.march(tl[left], xl, dl, O[:, left].tolist(), tl[k])
            X[:, k], D[:, k], O[:, k] = xk, dk, ok_
        f_redo, jac_redo = ctx.eval_batch(X[:, redo], t[redo])
        f[:, redo] = f_redo
        jac = stack_rows(jac, N)
        jac[:, redo] = stack_rows(jac_redo, redo.size)
    return f, jac

def _hermite(t, X, D, nodes, k):
    """The cubic Hermite predictor at every grid point from its nodes' values and tangents (n, N).

    ``k`` is every column's left node (its index in ``nodes``); built row by
    row, so that few (N,) temporaries are alive at once.
    """
    a = nodes.take(k)
    b = nodes.take(np.minimum(k + 1, nodes.size - 1))
    ta = t.take(a)
    delta = t.take(b) - ta
    delta[a == b] = 1.0
    s = t - ta
    s /= delta
    del ta
    s2 = s * s
    h01 = s2 * (3.0 - 2.0 * s)  # 3 s^2 - 2 s^3
    h11 = s2 * (s - 1.0)  # s^3 - s^2
    h10 = h11 - s2
    h10 += s  # s^3 - 2 s^2 + s
    del s, s2
    h10 *= delta
    h11 *= delta
    del delta
    out = np.empty_like(X)
    for i in range(X.shape[0]):
        xa = X[i].take(a)
        row = X[i].take(b)
        row -= xa
        row *= h01
        row += xa
        del xa
        dd = D[i].take(a)
        dd *= h10
        row += dd
        D[i].take(b, out=dd)
        dd *= h11
        row += dd
        out[i] = row
    return out


def report_near_singular(ctx, t, X, cond):
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
    warnings.warn(ctx.events[-1].message, SingularityWarning, stacklevel=3)

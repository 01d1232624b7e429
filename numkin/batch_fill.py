"""The grid points between a sweep's nodes, solved in one Newton batch, and the sweep's singular points.

A Hermite predictor from the nodes' values, tangents and curvatures (quintic;
cubic next to a node whose curvature is unknown), then Newton on all points
at once; points that fail the acceptance tests, and every
segment where batch points land on another turn, are marched point by point.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .march import COND_TANGENT, MAX_CORRECTION, Continuation, deg_text
from .newton import COND_MAX, COND_WARN, colmax as _colmax, is_singular, residual_floor
from .sweep import SweepEvent, SingularityWarning

__all__ = ["nodes_of", "fill", "node_curvatures", "report_near_singular", "CHUNK", "QUINTIC_MIN_POINTS"]


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


#: Grid points per node from which the batch is predicted by quintic Hermite polynomials (the nodes'
#: curvatures cost a few kernel calls on the nodes; a prediction error of order h^6 instead of h^4
#: saves a Newton iteration on every point once the segments hold this many).
QUINTIC_MIN_POINTS = 100

#: Grid points solved together in one Newton batch: the batch's temporaries stay this
#: many columns wide however long the sweep.
CHUNK = 8192


def fill(ctx: Continuation, t, X, D, O, iters, nodes):
    """Solve the grid points between nodes by Newton batches (a Hermite predictor from the nodes).

    The points are taken :data:`CHUNK` at a time. Returns the scaled
    residual norm (N,), the largest condition number of the loops' blocks
    (N,) and the Jacobian rows at every point of the sweep.
    """
    N = t.size
    if nodes.size == N:
        f, jac = ctx.eval_batch(X, t)
        return _colmax(np.abs(f)) / ctx.fscale, _colmax(ctx.blocks.cond(jac, N)), jac
    fine_mask = np.ones(N, dtype=bool)
    fine_mask[nodes] = False
    # every column's left and right node (a node is its own left node, at s = 0)
    k = np.searchsorted(nodes, np.arange(N), side="right") - 1
    # the round-off floor of the residual: sines of the largest angles and inputs of the sweep
    big = float(np.abs(X.take(nodes, axis=1)).max() * max(ctx.inv_xs))
    ctx.floor = residual_floor([big], max(abs(float(t[0])), abs(float(t[-1]))))
    On = O.take(nodes, axis=1)
    one_orientation = bool((On == On[:, :1]).all())
    scale = None if all(w == 1.0 for w in ctx.inv_xs) else np.asarray(ctx.inv_xs)[:, None]
    ok = np.empty(N, dtype=bool)
    residual = np.empty(N)
    jac = None
    if N >= QUINTIC_MIN_POINTS * nodes.size:
        D2n = node_curvatures(ctx, t, X, D, nodes)
    else:  # few points per segment: the curvatures would cost more than the iteration they save
        D2n = np.full((X.shape[0], nodes.size), np.nan)
    for c0 in range(0, N, CHUNK):
        c = slice(c0, min(N, c0 + CHUNK))
        fm, kc, tc = fine_mask[c], k[c], t[c]
        x_pred = _hermite(tc, t, X, D, D2n, nodes, kc)
        x, converged, it, f, jac_c = ctx.newton_batch(x_pred.copy(), tc, fm, overwrite=True)
        # accept a point if Newton converged on the turn of its prediction, the correction is
        # small and no loop changed orientation
        x_pred -= x
        np.abs(x_pred, out=x_pred)
        if scale is not None:
            x_pred *= scale
        okc = converged & (_colmax(x_pred) <= MAX_CORRECTION)
        del x_pred
        o = ctx.blocks.signs(jac_c, tc.size)
        if one_orientation:
            for kk in range(O.shape[0]):
                okc &= o[kk] == On[kk, 0]
        else:
            a = nodes.take(kc)
            b = nodes.take(np.minimum(kc + 1, nodes.size - 1))
            Oa, Ob = O.take(a, axis=1), O.take(b, axis=1)
            for kk in range(O.shape[0]):
                okc &= (o[kk] == Oa[kk]) & (Oa[kk] == Ob[kk])
        ok[c] = okc | ~fm
        X[:, c] = x  # the nodes were not active: unchanged
        O[:, c] = np.where(fm, o, O[:, c])
        iters[c] = np.where(fm, it, iters[c])
        residual[c] = _colmax(np.abs(f)) / ctx.fscale
        jac = jac_c if c.stop - c.start == N else _put_rows(jac, jac_c, c, N)
        del x, f, jac_c, o
    if ctx.angle_idx:
        # Both nodes of a segment are right (marched), so a run of batch points on another turn
        # shows as a neighbour step of half a turn or more: march that whole segment.
        jump = None
        for i in ctx.angle_idx:
            d = np.diff(X[i])
            np.abs(d, out=d)
            jump = d if jump is None else np.maximum(jump, d, out=jump)
        jump = np.flatnonzero(jump >= math.pi)
        if jump.size:
            ok &= ~(fine_mask & np.isin(k, k.take(jump)))
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
    bad_nodes = np.flatnonzero(~(cond.take(nodes) <= COND_TANGENT))
    if bad_nodes.size:
        ok &= ~(fine_mask & (np.isin(k, bad_nodes) | np.isin(k + 1, bad_nodes)))
    redo = np.flatnonzero(~ok)
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
    if N <= CHUNK:
        return _colmax(ctx.blocks.cond(jac, N))
    cond = np.empty(N)
    for c0 in range(0, N, CHUNK):
        c = slice(c0, min(N, c0 + CHUNK))
        cond[c] = _colmax(ctx.blocks.cond([r[c] if np.ndim(r) else r for r in jac], c.stop - c.start))
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


def node_curvatures(ctx: Continuation, t, X, D, nodes) -> np.ndarray:
    """d2q/dt2 at the nodes (n, nodes): the tangent's central difference along the curve.

    The tangent ``-J^-1 dF/dt`` (loop by loop) at ``(q + e q', t + e)`` and
    ``(q - e q', t - e)``, ``e`` a thousandth of the nodes' spacing: an error
    of order e^2 (the path's curvature from its tangent field; no second
    derivatives of the loop equations, which a sweep of positions never
    derives). NaN where a node's tangent is unknown or a block singular (its
    segments are then predicted by the cubic); a node on a singular position
    has its segments marched whatever the prediction (:func:`fill`).
    """
    tn = t.take(nodes)
    Xn, Dn = X.take(nodes, axis=1), D.take(nodes, axis=1)
    e = 1e-3 * float(np.abs(np.diff(tn)).min()) if nodes.size > 1 else 1e-3
    m = nodes.size
    comp, p = ctx.comp, ctx.p
    ts = np.concatenate([tn + e, tn - e])
    xs = np.concatenate([Xn + e * Dn, Xn - e * Dn], axis=1)
    jac = comp.FJ_rows(xs, ts, p)[ctx.n :]
    tangent, _ = ctx.blocks.solve_negated(jac, comp.F_t(xs, ts, p), 2 * m)
    return (tangent[:, :m] - tangent[:, m:]) / (2.0 * e)


def _hermite(tc, t, X, D, D2n, nodes, k):
    """The Hermite predictor at the inputs ``tc`` from their nodes' values, tangents and curvatures (n, M).

    Quintic (values, first and second derivatives at both nodes: error of
    order h^6) on a segment whose nodes both have a curvature in ``D2n``
    (n, nodes; NaN where unknown), cubic (values and tangents: order h^4)
    on the others. ``k`` is the left node of every input (its index in
    ``nodes``), ``t`` the sweep's inputs; built row by row, so that few
    temporaries are alive at once.
    """
    kb = np.minimum(k + 1, nodes.size - 1)
    a = nodes.take(k)
    b = nodes.take(kb)
    ta = t.take(a)
    delta = t.take(b) - ta
    delta[a == b] = 1.0
    s = tc - ta
    s /= delta
    del ta
    u = 1.0 - s
    s2 = s * s
    known = np.isfinite(D2n).all(axis=0)
    quintic = known.take(k) & known.take(kb)
    if quintic.all():
        h01, h10, h11 = _quintic_bases(s, u)
        c = 0.5 * delta * delta
        D2 = D2n
    else:
        h01, h10, h11 = _cubic_bases(s, u)
        c = None
        if quintic.any():
            q = quintic
            h01[q], h10[q], h11[q] = _quintic_bases(s[q], u[q])
            c = np.where(q, 0.5 * delta * delta, 0.0)
            D2 = np.nan_to_num(D2n, nan=0.0)
    h20 = h21 = None
    if c is not None:
        h20 = s2 * u * u * u * c  # s^2 (1 - s)^3 / 2, times delta^2
        h21 = s2 * s * u * u * c  # s^3 (1 - s)^2 / 2, times delta^2
    del s, u, s2
    h10 *= delta
    h11 *= delta
    del delta
    out = np.empty((X.shape[0], tc.size))
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
        if h20 is not None:
            D2[i].take(k, out=dd)
            dd *= h20
            row += dd
            D2[i].take(kb, out=dd)
            dd *= h21
            row += dd
        out[i] = row
    return out


def _cubic_bases(s, u):
    """Cubic Hermite bases of the right node's value and of both tangents at ``s`` (``u = 1 - s``)."""
    s2 = s * s
    return s2 * (3.0 - 2.0 * s), s * u * u, -s2 * u  # 3 s^2 - 2 s^3, s (1 - s)^2, s^2 (s - 1)


def _quintic_bases(s, u):
    """Quintic Hermite bases of the right node's value and of both tangents at ``s`` (``u = 1 - s``)."""
    s3 = s * s * s
    # s^3 (6 s^2 - 15 s + 10), s (1 - s)^3 (3 s + 1), s^3 (1 - s) (3 s - 4)
    return s3 * (s * (6.0 * s - 15.0) + 10.0), s * u * u * u * (3.0 * s + 1.0), s3 * u * (3.0 * s - 4.0)


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

"""The predictors of a continuation: where the next solution is expected, before Newton corrects it.

Sequential steps (:func:`predict`): the tangent line, plus the cubic through
the previous point and its tangent, bounded so that no prediction can blow
up. The batch between nodes (:func:`hermite`): Hermite polynomials through
the nodes' values and tangents (cubic), and their curvatures where known
(quintic, from :func:`node_curvatures`, or, with few points per node, from
the neighbouring nodes: :func:`free_curvatures`, :func:`free_quintic`, chosen
by :func:`quintic_pays`).
"""

from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np

from .unrolled import max_lines

if TYPE_CHECKING:  # pragma: no cover - for annotations only
    from .march import Continuation

__all__ = ["predict", "unrolled_predict", "hermite", "hermite_uniform", "node_curvatures", "free_curvatures", "cubic_bases", "MAX_PREDICTION",
           "SANE_DISTANCE", "QUINTIC_MIN_POINTS", "HERMITE_BLOCK", "QUINTIC_GAIN_FLOOR", "QUINTIC_GAIN_LIMIT", "quintic_pays", "quintic_terms", "free_quintic", "FREE_QUINTIC_NODES"]

#: Largest predicted change of an unknown in one step (scaled), 1.0: with the largest accepted
#: correction (:data:`numkin.march.MAX_CORRECTION`, 0.3) well below pi, an accepted point is never a
#: whole turn away from its predecessor.
MAX_PREDICTION = 1.0
#: The quadratic (or cubic) predictor uses the previous point only if it is at least this fraction
#: of the step away, 0.2 (closer points make the added terms blow up).
SANE_DISTANCE = 0.2
#: Grid points per node, 100, from which the batch is predicted by quintic Hermite polynomials (the
#: nodes' curvatures cost a few kernel calls on the nodes; a prediction error of order h^6 instead of
#: h^4 saves a Newton iteration on every point once the segments hold this many).
QUINTIC_MIN_POINTS = 100
#: The band of the largest scaled difference of the quintic and cubic predictions at the middle of a
#: segment (an estimate of the cubic's error, rad) in which the quintic on free curvatures is used:
#: below 2e-4 the cubic leaves Newton no third iteration either, above 1e-3 the quintic's own error
#: still leaves one (on the built-in linkages at 30 degree nodes: a slider-crank 1.5e-4 to 1.8e-4, the
#: four-bars and the six-bar 2.3e-4 to 3.5e-4, the chained homework and the quick-return 1.1e-3 and more).
QUINTIC_GAIN_FLOOR = 2e-4
QUINTIC_GAIN_LIMIT = 1e-3
#: Entries (unknowns times inputs) up to which :func:`hermite` builds all rows at once (fewer array
#: calls), above which row by row (fewer temporaries alive).
HERMITE_BLOCK = 8192


def predict(t, x, d, t_prev, x_prev, t_new, inv_xs, rate, d_prev=None):
    """Predictor of a continuation step that cannot blow up.

    Parameters
    ----------
    t, x, d : float, list of float, list of float or None
        The last accepted point: input (rad), unknowns (rad or length) and
        tangent dq/dt (None where unknown).
    t_prev, x_prev : float, list of float, or None
        The point before it (None at the first step).
    t_new : float
        The input to predict at (rad).
    inv_xs : list of float or None
        The unknowns' inverse scales (None: all one).
    rate : float
        The largest scaled entry of ``d``.
    d_prev : list of float, optional
        The previous point's tangent.

    Returns
    -------
    list of float
        The predicted unknowns at ``t_new``.

    Notes
    -----
    The tangent ``x + d s``; plus, through the previous point, the cubic
    term as well when its tangent ``d_prev`` is known (the cubic through
    both points and both tangents), else the quadratic one, only when that
    point is at least ``SANE_DISTANCE`` times the step away and the added
    terms (scaled) stay below the step times (1 + ``rate``), ``rate`` the
    largest scaled entry of the tangent (else the quadratic, else the
    tangent alone). Without a tangent: the secant through a sane previous
    point, or ``x`` itself.

    Examples
    --------
    The cubic through two points and their tangents is exact for
    ``q(t) = t^3`` (at t = 0 and 1, predicting t = 1.5):

    >>> predict(1.0, [1.0], [3.0], 0.0, [0.0], 1.5, None, 3.0, [0.0])
    [3.375]
    """
    s = t_new - t
    if d is None:
        if x_prev is None or abs(t - t_prev) < SANE_DISTANCE * abs(s):
            return list(x)
        r = s / (t - t_prev)
        lin = [a + (a - b) * r for a, b in zip(x, x_prev)]
        if max([abs(a - b) * w for a, b, w in zip(lin, x, inv_xs or [1.0] * len(x))]) <= MAX_PREDICTION:
            return lin
        return list(x)
    lin = [a + da * s for a, da in zip(x, d)]
    if x_prev is None:
        return lin
    h = t_prev - t
    if abs(h) < SANE_DISTANCE * abs(s):
        return lin
    bound = abs(s) * (1.0 + rate)
    r = s / h
    # p(u) = x + d u + A u^2 + B u^3 with p(h) = x_prev (and p'(h) = d_prev): e = A h^2 + B h^3
    e = [b - a - da * h for a, da, b in zip(x, d, x_prev)]
    if d_prev is not None:
        # A h^2 = 3 e - g h, B h^3 = g h - 2 e, g = d_prev - d
        gh = [(b - a) * h for a, b in zip(d, d_prev)]
        higher = [((3.0 * ei - gi) + (gi - 2.0 * ei) * r) * r * r for ei, gi in zip(e, gh)]
        if max([abs(q) * w for q, w in zip(higher, inv_xs)] if inv_xs else map(abs, higher)) <= bound:
            return [a + q for a, q in zip(lin, higher)]
    quad = [ei * r * r for ei in e]
    if not max([abs(q) * w for q, w in zip(quad, inv_xs)] if inv_xs else map(abs, quad)) <= bound:
        return lin
    return [a + q for a, q in zip(lin, quad)]


@lru_cache(maxsize=64)
def unrolled_predict(n, inv_xs=None):
    """Generate :func:`predict` written out for ``n`` unknowns and their inverse scales ``inv_xs``.

    ``inv_xs`` is a tuple (or None: all one); the function is generated
    once per argument pair. ``predict1(t, x, d, t_prev, x_prev, t_new, rate, d_prev)`` gives the
    same numbers as ``predict(t, x, d, t_prev, x_prev, t_new, inv_xs, rate,
    d_prev)`` where the tangent ``d`` is known (a step from a solved point);
    without it, it calls :func:`predict`.

    Examples
    --------
    >>> predict1 = unrolled_predict(1)
    >>> predict1(1.0, [1.0], [3.0], 0.0, [0.0], 1.5, 3.0, [0.0])
    [3.375]
    """
    w = [1.0] * n if inv_xs is None else list(inv_xs)

    def biggest(name):
        return [f"abs({name}{i})" if w[i] == 1.0 else f"abs({name}{i}) * {w[i]!r}" for i in range(n)]

    def listed(fmt):
        return "[" + ", ".join(fmt.format(i=i) for i in range(n)) + "]"

    unpack = ", ".join(f"{{0}}{i}" for i in range(n)) + ("," if n == 1 else "")
    lines = [
        "def predict1(t, x, d, t_prev, x_prev, t_new, rate, d_prev=None):",
        "    if d is None:",
        "        return PREDICT(t, x, d, t_prev, x_prev, t_new, INV_XS, rate, d_prev)",
        "    s = t_new - t",
        f"    {unpack.format('x')} = x",
        f"    {unpack.format('d')} = d",
        *[f"    lin{i} = x{i} + d{i} * s" for i in range(n)],
        "    if x_prev is None:",
        f"        return {listed('lin{i}')}",
        "    h = t_prev - t",
        "    if abs(h) < SANE * abs(s):",
        f"        return {listed('lin{i}')}",
        "    bound = abs(s) * (1.0 + rate)",
        "    r = s / h",
        *[f"    e{i} = x_prev[{i}] - x{i} - d{i} * h" for i in range(n)],
        "    if d_prev is not None:",
        *[f"        g{i} = (d_prev[{i}] - d{i}) * h" for i in range(n)],
        *[f"        q{i} = ((3.0 * e{i} - g{i}) + (g{i} - 2.0 * e{i}) * r) * r * r" for i in range(n)],
        *max_lines("qmax", biggest("q"), "        "),
        "        if qmax <= bound:",
        f"            return {listed('lin{i} + q{i}')}",
        *[f"    q{i} = e{i} * r * r" for i in range(n)],
        *max_lines("qmax", biggest("q"), "    "),
        "    if not qmax <= bound:",
        f"        return {listed('lin{i}')}",
        f"    return {listed('lin{i} + q{i}')}",
    ]
    namespace = {"PREDICT": predict, "INV_XS": inv_xs, "SANE": SANE_DISTANCE}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace["predict1"]


def node_curvatures(ctx: Continuation, t, X, D, nodes) -> np.ndarray:
    """d2q/dt2 at the nodes (n, nodes): the tangent's central difference along the curve.

    The tangent ``-J^-1 dF/dt`` (loop by loop) at ``(q + e q', t + e)`` and
    ``(q - e q', t - e)``, ``e`` a thousandth of the nodes' spacing: an error
    of order e^2 (the path's curvature from its tangent field; no second
    derivatives of the loop equations, which a sweep of positions never
    derives). NaN where a node's tangent is unknown or a block singular (its
    segments are then predicted by the cubic); a node on a singular position
    has its segments marched whatever the prediction (:func:`numkin.batch_fill.fill`).
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


def free_curvatures(t, X, D, nodes):
    """d2q/dt2 at the nodes (n, nodes) from the nodes' values and tangents alone: no kernel call.

    At every node, the second derivative of the quintic through the values
    and tangents of three neighbouring nodes (the node and its neighbours;
    at the first and last node, the two nodes next to it on one side): an
    error of order h^4 in the spacing h of the nodes, so that the quintic
    Hermite predictor built on these curvatures errs by order h^6 like the
    one on exact curvatures (:func:`node_curvatures`), with a larger
    constant. With uniform spacing h, the middle formula is
    ``2 (x[k+1] - 2 x[k] + x[k-1]) / h^2 - (d[k+1] - d[k-1]) / (2 h)``.
    NaN where a tangent used is unknown; None with fewer than three nodes.

    Examples
    --------
    A quintic is reproduced exactly: ``q(t) = t^5`` at t = 0, 1, 3, 4 (``q'' = 20 t^3``):

    >>> import numpy as np
    >>> t = np.array([0.0, 1.0, 3.0, 4.0]); nodes = np.arange(4)
    >>> d2 = free_curvatures(t, (t ** 5)[None, :], (5 * t ** 4)[None, :], nodes)
    >>> np.allclose(d2, 20 * t ** 3, rtol=1e-12, atol=1e-9)
    True
    """
    m = nodes.size
    if m < 3:
        return None
    dt = np.diff(t.take(nodes)).tolist()
    # weights of x(j-1), x(j), x(j+1), d(j-1), d(j), d(j+1) for node k, j = k clipped to [1, m - 2]
    w = np.empty((6, m))
    w[:, 0] = _curvature_weights(dt[0], dt[1], 0)
    inner = dt[:-1]
    h = inner[0]
    if m > 3 and max(inner) - min(inner) <= 1e-12 * abs(h):  # evenly spaced but for the last segment
        w[:, 1:-2] = np.array(_curvature_weights(h, h, 1))[:, None]
    else:
        for j in range(1, m - 2):
            w[:, j] = _curvature_weights(dt[j - 1], dt[j], 1)
    w[:, -2] = _curvature_weights(dt[-2], dt[-1], 1)
    w[:, -1] = _curvature_weights(dt[-2], dt[-1], 2)
    idx = nodes.take(_stencils(m))
    out = (X.take(idx, axis=1) * w[:3]).sum(axis=1)
    out += (D.take(idx, axis=1) * w[3:]).sum(axis=1)
    return out


def quintic_terms(t, X, D, D2n, nodes):
    """What the quintic Hermite predictor adds to the cubic on every segment: ``(alpha, beta)`` (n, nodes).

    On the segment from node j (``s = 0``) to node j + 1 (``s = 1``), of
    length h, the quintic through the nodes' values, tangents and
    curvatures ``D2n`` is the cubic through their values and tangents plus
    ``s^2 (1 - s)^2 (alpha_j + beta_j s)``, with ``alpha = C0 / 2 - 3 e + f``
    and ``beta = (C1 - C0) / 2 + 6 e - 3 f``: ``e = x1 - x0 - h d0``,
    ``f = h (d1 - d0)``, ``C = h^2 D2`` at either node. Zero (the cubic) on a
    segment where a curvature is unknown (NaN) and in the last column
    (the last node alone).

    Examples
    --------
    ``q(t) = t^5`` from nodes at t = 0 and 1: at s = 1/2 the cubic gives -1/8, the quintic 1/32 (exact), 5/32 more:

    >>> import numpy as np
    >>> t = np.array([0.0, 1.0]); nodes = np.array([0, 1])
    >>> alpha, beta = quintic_terms(t, (t ** 5)[None, :], (5 * t ** 4)[None, :], (20 * t ** 3)[None, :], nodes)
    >>> float((alpha[0, 0] + 0.5 * beta[0, 0]) / 16)
    0.15625
    """
    h = np.diff(t.take(nodes))
    Y, Dn = X.take(nodes, axis=1), D.take(nodes, axis=1)
    hh = h * h
    m0 = Dn[:, :-1] * h
    f = Dn[:, 1:] * h
    f -= m0
    e = np.diff(Y, axis=1)
    e -= m0
    e *= 3.0
    c0 = D2n[:, :-1] * (0.5 * hh)
    alpha = np.zeros(Y.shape)
    beta = np.zeros(Y.shape)
    a = alpha[:, :-1]
    np.subtract(c0, e, out=a)
    a += f
    bt = beta[:, :-1]
    np.multiply(D2n[:, 1:], 0.5 * hh, out=bt)
    bt -= c0
    bt += 2.0 * e
    f *= 3.0
    bt -= f
    if not np.isfinite(a.sum() + bt.sum()):  # a curvature unknown: the cubic on its segments
        bad = ~(np.isfinite(a) & np.isfinite(bt)).all(axis=0)
        a[:, bad] = 0.0
        bt[:, bad] = 0.0
    return alpha, beta


def quintic_pays(gap, inv_xs, floor=None, limit=None):
    """Whether the quintic predictor is expected to save the batch a Newton iteration over the cubic:
    where the two differ by more than ``floor`` and at most ``limit`` (scaled; defaults
    :data:`QUINTIC_GAIN_FLOOR`, :data:`QUINTIC_GAIN_LIMIT`) at the middle of the segments (the largest
    difference); ``gap`` (n, nodes) is 16 times that difference, ``alpha + beta / 2``
    (:func:`quintic_terms`, :func:`free_quintic`).

    The difference estimates the cubic's error: where it is small the cubic
    needs no more iterations than the quintic; in between, the quintic's
    error is small enough for the last iteration to go; where it is large
    the quintic's own error still leaves one (and the quintic costs more than
    it saves). NaN counts as nothing (a segment predicted by the cubic).

    Examples
    --------
    >>> import numpy as np
    >>> [quintic_pays(np.array([[g, -g / 2, np.nan]]), [1.0]) for g in (1e-3, 8e-3, 0.5)]
    [False, True, False]
    """
    gap = np.abs(gap)
    if any(w != 1.0 for w in inv_xs):
        gap *= np.asarray(inv_xs)[:, None]
    largest = float(np.maximum.reduce(gap, axis=None)) / 16.0
    if largest != largest:  # NaN somewhere: the largest of the others
        largest = float(np.nanmax(gap)) / 16.0 if np.isfinite(gap).any() else 0.0
    return (QUINTIC_GAIN_FLOOR if floor is None else floor) < largest <= (QUINTIC_GAIN_LIMIT if limit is None else limit)


def free_quintic(t, X, D, nodes):
    """:func:`quintic_terms` on :func:`free_curvatures`, and the quintic's change of the prediction at
    the middle of every segment, ``(alpha, beta, gap)`` (n, nodes each); None with fewer than three
    nodes.

    All three are linear in the nodes' values and tangents, with weights that depend on the nodes'
    inputs alone: for a few nodes (at most :data:`FREE_QUINTIC_NODES`, every value and tangent
    finite) the weights are kept for the grid and the terms are two small matrix products;
    otherwise they are computed as the two functions do.

    Examples
    --------
    A quintic is predicted exactly (its curvatures are found exactly):

    >>> import numpy as np
    >>> t = np.linspace(0.0, 3.0, 31); nodes = np.array([0, 10, 20, 30]); k = np.repeat([0, 1, 2, 3], [10, 10, 10, 1])
    >>> X, D = (t ** 5 - t ** 2)[None, :], (5 * t ** 4 - 2 * t)[None, :]
    >>> alpha, beta, gap = free_quintic(t, X, D, nodes)
    >>> bool(np.abs(hermite(t, t, X, D, None, nodes, k, (alpha, beta)) - X).max() < 1e-12)
    True
    """
    m = nodes.size
    if m < 3:
        return None
    Y, Dn = X.take(nodes, axis=1), D.take(nodes, axis=1)
    if m > FREE_QUINTIC_NODES or not np.isfinite(np.add.reduce(Dn, axis=None) + np.add.reduce(Y, axis=None)):
        alpha, beta = quintic_terms(t, X, D, free_curvatures(t, X, D, nodes), nodes)
        gap = 0.5 * beta
        gap += alpha
        return alpha, beta, gap
    tn = t.take(nodes)
    wy, wd = _free_quintic_weights(tuple((tn[1:] - tn[:-1]).tolist()))
    out = Y @ wy
    out += Dn @ wd
    return out[:, :m], out[:, m : 2 * m], out[:, 2 * m :]


#: Most nodes for which :func:`free_quintic` keeps its weights (three m x m matrices of each kind).
FREE_QUINTIC_NODES = 64


@lru_cache(maxsize=16)
def _free_quintic_weights(dt):
    """Weights (m, 3 m) of the nodes' values and of their tangents in ``[alpha | beta | gap]`` of
    :func:`free_quintic`, for nodes spaced ``dt`` (a tuple)."""
    m = len(dt) + 1
    # the curvature at node k, from nodes j - 1, j, j + 1 (j = k clipped to [1, m - 2])
    ay, ad = np.zeros((m, m)), np.zeros((m, m))
    for k in range(m):
        j = min(max(k, 1), m - 2)
        w = _curvature_weights(dt[j - 1], dt[j], 0 if k == 0 else 2 if k == m - 1 else 1)
        ay[j - 1 : j + 2, k] = w[:3]
        ad[j - 1 : j + 2, k] = w[3:]
    h = np.array(dt)
    seg = np.arange(m - 1)
    ey, ed, fd = np.zeros((m, m)), np.zeros((m, m)), np.zeros((m, m))
    s0, s1 = np.zeros((m, m)), np.zeros((m, m))
    ey[seg + 1, seg], ey[seg, seg] = 1.0, -1.0  # e = x1 - x0 - h d0
    ed[seg, seg] = -h
    fd[seg + 1, seg], fd[seg, seg] = h, -h  # f = h (d1 - d0)
    s0[seg, seg] = 0.5 * h * h  # C0 h^2 / 2 from the curvatures
    s1[seg + 1, seg] = 0.5 * h * h
    alpha_y, alpha_d = ay @ s0 - 3.0 * ey, ad @ s0 - 3.0 * ed + fd
    beta_y, beta_d = ay @ (s1 - s0) + 6.0 * ey, ad @ (s1 - s0) + 6.0 * ed - 3.0 * fd
    wy = np.hstack([alpha_y, beta_y, alpha_y + 0.5 * beta_y])
    wd = np.hstack([alpha_d, beta_d, alpha_d + 0.5 * beta_d])
    wy.flags.writeable = wd.flags.writeable = False
    return wy, wd


@lru_cache(maxsize=64)
def _stencils(m):
    """Node indices (3, m) of the three nodes whose quintic gives node k's curvature."""
    j = np.clip(np.arange(m), 1, m - 2)
    return np.vstack([j - 1, j, j + 1])


def _curvature_weights(a, b, at):
    """Weights of x0, x1, x2, d0, d1, d2 (values and tangents at -a, 0 and b) in the second derivative
    of the quintic through them, at -a (``at`` 0), 0 (1) or b (2)."""
    s = a + b
    if at == 1:
        c2 = 2.0 * a * a * (3.0 * a + 5.0 * b) / (b * b * s ** 3)
        c0 = 2.0 * b * b * (5.0 * a + 3.0 * b) / (a * a * s ** 3)
        return (c0, -c0 - c2, c2, 2.0 * b * b / (a * s * s), -4.0 * (a - b) / (a * b), -2.0 * a * a / (b * s * s))
    if at == 0:
        c2 = 2.0 * a * a * (2.0 * a + 5.0 * b) / (b ** 3 * s * s)
        c1 = -2.0 * s * s * (2.0 * a - 3.0 * b) / (a * a * b ** 3)
        return (-c1 - c2, c1, c2, -4.0 * (2.0 * a + b) / (a * s), -2.0 * s * s / (a * b * b), -2.0 * a * a / (b * b * s))
    c0 = 2.0 * b * b * (5.0 * a + 2.0 * b) / (a ** 3 * s * s)
    c1 = 2.0 * s * s * (3.0 * a - 2.0 * b) / (a ** 3 * b * b)
    return (c0, c1, -c0 - c1, 2.0 * b * b / (a * a * s), 2.0 * s * s / (a * a * b), 4.0 * (a + 2.0 * b) / (b * s))


def hermite(tc, t, X, D, D2n, nodes, k, terms=None):
    """The Hermite predictor at the inputs ``tc`` from their nodes' values, tangents and curvatures: an
    array (n, M), n unknowns by the M inputs of ``tc``.

    Quintic (values, first and second derivatives at both nodes: error of
    order h^6) on a segment whose nodes both have a curvature in ``D2n``
    (n, nodes; NaN where unknown), cubic (values and tangents: order h^4)
    on the others (on every segment where ``D2n`` is None): the quintic is
    the cubic plus :func:`quintic_terms` ``(alpha, beta)``, given as
    ``terms`` or computed from ``D2n``. ``k`` is the left node of every input (its index in
    ``nodes``), ``t`` the sweep's inputs. All rows at once where they are
    few (:data:`HERMITE_BLOCK`), else row by row, so that few temporaries
    are alive at once.

    Examples
    --------
    ``q(t) = t^3`` from nodes at t = 0 and 2 (values and tangents: the cubic is exact):

    >>> import numpy as np
    >>> t = np.array([0.0, 0.5, 1.0, 2.0]); nodes = np.array([0, 3])
    >>> X, D = (t**3)[None, :], (3 * t**2)[None, :]
    >>> hermite(t, t, X, D, np.full((1, 2), np.nan), nodes, np.array([0, 0, 0, 1])).tolist()
    [[0.0, 0.125, 1.0, 8.0]]
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
    if terms is None and D2n is not None and np.isfinite(D2n).any():
        terms = quintic_terms(t, X, D, D2n, nodes)  # zero (the cubic) where a curvature is unknown
    h01, h10, h11 = cubic_bases(s, u)
    w = None
    if terms is not None:
        w = s * u
        w *= w  # s^2 (1 - s)^2
    h10 *= delta
    h11 *= delta
    del delta, u
    n = X.shape[0]
    out = np.empty((n, tc.size))
    for rows in [slice(0, n)] if n * tc.size <= HERMITE_BLOCK else [slice(i, i + 1) for i in range(n)]:
        xa = X[rows].take(a, axis=1)
        row = out[rows]
        X[rows].take(b, axis=1, out=row)
        row -= xa
        row *= h01
        row += xa
        del xa
        dd = D[rows].take(a, axis=1)
        dd *= h10
        row += dd
        D[rows].take(b, axis=1, out=dd)
        dd *= h11
        row += dd
        if w is not None:  # s^2 (1 - s)^2 (alpha + beta s)
            terms[1][rows].take(k, axis=1, out=dd)
            dd *= s
            part = terms[0][rows].take(k, axis=1)
            part += dd
            part *= w
            row += part
    return out


def hermite_uniform(tn, X, D, every, terms=None):
    """:func:`hermite` at every input of an evenly spaced grid whose nodes are every ``every``-th input,
    first and last included (``(X.shape[1] - 1) % every == 0``): one matrix product.

    The inputs of a segment sit at ``s = j / every`` (j = 0 ... every - 1) of it, so the bases
    are the same on every segment: the prediction is the nodes' values, tangents (times the
    segment's length) and quintic terms ``(alpha, beta)`` (:func:`quintic_terms`; None: the
    cubic) times a (6, every) matrix of bases. ``tn``: the nodes' inputs. The same polynomials
    as :func:`hermite`, evaluated at these ``s`` (the grid's own to its unevenness: a sweep takes
    this path where its steps agree to ``numkin.continuation.EVEN_STEPS``).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 2.0, 9); nodes = np.arange(0, 9, 4); k = np.arange(9) // 4
    >>> X, D = np.vstack([np.sin(t), t ** 4]), np.vstack([np.cos(t), 4 * t ** 3])
    >>> bool(np.allclose(hermite_uniform(t[nodes], X, D, 4), hermite(t, t, X, D, None, nodes, k), rtol=0, atol=1e-14))
    True
    """
    n, N = X.shape
    m = tn.size
    basis = _uniform_bases(every, terms is not None)
    cols = basis.shape[0]
    h = tn[1:] - tn[:-1]
    Y, Dn = X[:, ::every], D[:, ::every]
    coef = np.empty((n, m - 1, cols))
    coef[:, :, 0] = Y[:, :-1]
    coef[:, :, 1] = Y[:, 1:]
    np.multiply(Dn[:, :-1], h, out=coef[:, :, 2])
    np.multiply(Dn[:, 1:], h, out=coef[:, :, 3])
    if terms is not None:
        coef[:, :, 4] = terms[0][:, :-1]
        coef[:, :, 5] = terms[1][:, :-1]
    out = np.empty((n, N))
    out[:, :-1] = (coef.reshape(n * (m - 1), cols) @ basis).reshape(n, N - 1)
    out[:, -1] = X[:, -1]  # the last node
    return out


@lru_cache(maxsize=16)
def _uniform_bases(every, quintic):
    """The bases of :func:`hermite_uniform` at ``s = j / every`` (read-only): the left and right
    node's value, tangent (per unit of the segment's length), and with ``quintic`` the terms
    ``s^2 (1 - s)^2`` and ``s^3 (1 - s)^2``."""
    s = np.arange(every) / every
    u = 1.0 - s
    h01, h10, h11 = cubic_bases(s, u)
    basis = np.empty((6 if quintic else 4, every))
    np.subtract(1.0, h01, out=basis[0])
    basis[1], basis[2], basis[3] = h01, h10, h11
    if quintic:
        w = s * u
        w *= w
        basis[4] = w
        np.multiply(w, s, out=basis[5])
    basis.flags.writeable = False
    return basis


def cubic_bases(s, u):
    """Cubic Hermite bases of the right node's value and of both tangents at ``s`` (``u = 1 - s``).

    Examples
    --------
    >>> cubic_bases(0.5, 0.5)
    (0.5, 0.125, -0.125)
    """
    s2 = s * s
    return s2 * (3.0 - 2.0 * s), s * u * u, -s2 * u  # 3 s^2 - 2 s^3, s (1 - s)^2, s^2 (s - 1)


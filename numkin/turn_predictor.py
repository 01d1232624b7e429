"""The batch predictor of a sweep over a whole turn: a trigonometric polynomial through the nodes.

Over one turn of the input angle, every unknown of a linkage is a periodic
function of the input, plus whole turns of an angle that goes round with it,
and away from singular positions an analytic one: its Fourier coefficients
fall off geometrically. The trigonometric polynomial through the nodes'
values and tangents (:func:`turn_predict`: K nodes evenly spaced round the turn,
2K coefficients) then predicts the grid points between them far better than
the Hermite polynomials of :mod:`numkin.predictors`, segment by segment: on
a 1° grid with 30° nodes, 5.7e-9 rad on the four-bar 4:1:3:3 and 5.7e-10
(scaled) on the slider-crank 80:200, against 4.3e-5 for the quintic on the
four-bar and 1.8e-4 for the cubic on the slider-crank, so that the batch's
Newton stops after one step instead of two (their sweeps of 361 points 3
to 11 % faster, of 3601 to 360 001 points a fifth to a third; where a
trusted fit still leaves some points a second step, as on the six-bar at
361 points, it costs the 20 µs of the fit).

The fit is taken only where it is expected to be that good: the amplitude
of its three highest harmonics and of its ``sin K tau`` term (scaled like the
unknowns) at most :data:`TURN_TRUST`, and between :data:`TURN_MIN_NODES` and
:data:`TURN_MAX_NODES` nodes round the turn. Where the coefficients fall off slowly (a linkage that
passes near a singular position, like the chained homework with 5e-4, or an
input that is not an angle, whose unknowns do not repeat after 2 pi) the
batch keeps the Hermite predictors. Either way the prediction is only where
Newton starts: the batch's acceptance tests are the same.

Examples
--------
A function with harmonics up to 4, from 8 nodes round the turn, predicted on a 1° grid:

>>> import numpy as np
>>> t = np.radians(np.arange(0.0, 361.0))
>>> X = np.vstack([np.cos(t) + 0.1 * np.sin(4 * t), t + 0.2 * np.sin(t)])
>>> D = np.vstack([-np.sin(t) + 0.4 * np.cos(4 * t), 1 + 0.2 * np.cos(t)])
>>> pred = turn_predict(t, X, D, np.arange(0, 361, 45), angle_rows=[1], inv_xs=[1.0, 1.0])
>>> bool(np.abs(pred - X).max() < 1e-13)
True
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

__all__ = ["turn_predict", "TURN_TRUST", "TURN_MIN_NODES", "TURN_MAX_NODES"]

#: Largest scaled amplitude of the fit's three highest harmonics (and of its ``sin K tau`` term), 1e-5, for
#: which the fit is used. On a motion whose harmonics fall off steadily it overestimates the fit's error
#: (the four-bar 4:1:3:3 at 30° nodes: 4.3e-7 against 5.7e-9; the six-bar 6.9e-7 against 1.1e-8), while
#: the cubic and quintic err by 1e-5 to 1e-3 on grids of 30° nodes. A motion whose harmonics are all
#: multiples of a divisor m of K (m = 4 with 12 nodes: harmonics 4, 8 and a ``cos 12 tau``, which is 1 at
#: every node; a crank geared 4 to 1) leaves the top of the fit empty and can deceive it (2.4e-2 off with
#: 12 nodes); Newton then starts further off, as it would from a Hermite prediction there, and the
#: batch's acceptance tests are the same.
TURN_TRUST = 1e-5
#: Fewest nodes round the turn, 6 (harmonics up to 5: three of them to judge the fit by).
TURN_MIN_NODES = 6
#: Most nodes round the turn, 24 (15° apart; the default ``max_step`` of 30° gives 12): the fit's matrices
#: grow as K^3 (440 KB at 24 nodes). Closer nodes come from a smaller ``max_step``, and they make the
#: Hermite predictors more accurate too (their error falls as the fourth power of the nodes' spacing).
TURN_MAX_NODES = 24
#: Most entries of one segment's bases (2K by the points per segment) kept between sweeps, in at most 8
#: kept matrices: 8 MB in all (a grid with more points per segment builds its own for each sweep).
_KEPT_BASES = 131072
_TWO_PI = 2.0 * math.pi


def turn_predict(t, X, D, nodes, *, angle_rows, inv_xs, even=True):
    """The fit's prediction (n, N) at every grid point (the nodes' own values at ``nodes``), or None
    where the grid is not one it applies to or the fit is not trusted.

    It applies where the grid ``t`` is evenly spaced (``even``, as the caller found), a whole
    number M of its steps make a turn (2 pi, to 1e-9 relative), the nodes are every e-th grid
    point from the first with e dividing M (and the last: :func:`numkin.batch_fill.nodes_of`),
    at least :data:`TURN_MIN_NODES` of them go once round, their values and tangents are
    finite. It is trusted where the scaled amplitude of its three highest harmonics and of its
    ``sin K tau`` term is at most :data:`TURN_TRUST` and it meets every node it was not fitted
    to (one turn on, or the last node of a grid that stops short of a turn) as closely. ``X``, ``D``
    (n, N): values and tangents, read at the nodes; ``angle_rows``: the rows of ``X`` that are
    angles (they may gain whole turns over a turn of the input: the gain is read at the node
    one turn on, or, on a grid that stops short of it, rounded from the last nodes' values and
    tangents); ``inv_xs``: the unknowns' inverse scales.
    """
    n, N = X.shape
    if not even or N < 3 or nodes.size < 3:
        return None
    h = (float(t[-1]) - float(t[0])) / (N - 1)
    if h == 0.0 or not math.isfinite(h):
        return None
    M = round(_TWO_PI / abs(h))
    e = int(nodes[1] - nodes[0])
    if M < 1 or abs(M * abs(h) - _TWO_PI) > 1e-9 * _TWO_PI or e < 1 or M % e:
        return None
    K = M // e
    if not TURN_MIN_NODES <= K <= TURN_MAX_NODES or nodes.size < K or int(nodes[K - 1]) != (K - 1) * e:
        return None
    last = (K - 1) * e + 1
    data = np.concatenate((X[:, 0:last:e], D[:, 0:last:e]), axis=1)  # (n, 2K): values, then tangents
    factor = M * h / _TWO_PI  # d/dtau = factor d/dt: +-1 to rounding (the grid may run backwards)
    if factor != 1.0:
        data[:, K:] *= factor
    shift = None  # whole turns gained over a turn of the input, by the angles
    if angle_rows:
        turns = [0] * n
        one_turn_on = M <= N - 1 and int(nodes[min(K, nodes.size - 1)]) == M
        for i in angle_rows:
            if one_turn_on:  # the node one turn on
                gain = float(X[i, M]) - float(X[i, 0])
            else:  # from the last node round to the first, by the trapezoid rule on their tangents
                gain = float(X[i, last - 1]) - float(X[i, 0]) + 0.5 * (e * h) * (float(D[i, last - 1]) + float(D[i, 0]))
            if not math.isfinite(gain):  # (a tangent unknown at a node: no fit)
                return None
            turns[i] = round(gain / _TWO_PI)
        if any(turns):
            shift = np.array(turns, dtype=float) * _TWO_PI
            data -= np.outer(shift, _trend(K))
    coef = data @ _inverse_t(K)  # (n, 2K) coefficients, one row per unknown
    # the squared amplitudes of harmonics K - 3, K - 2, K - 1 (cos and sin) and of sin K tau, scaled (a few
    # floats: plain arithmetic); NaN fails the tests
    for (c0, s0, c1, s1, c2, s2, sk), w in zip(coef[:, 2 * K - 7 :].tolist(), inv_xs):
        limit = (TURN_TRUST / w) ** 2
        if not (c0 * c0 + s0 * s0 <= limit and c1 * c1 + s1 * s1 <= limit and c2 * c2 + s2 * s2 <= limit
                and sk * sk <= limit):
            return None
    scale = None if max(inv_xs) == 1.0 == min(inv_xs) else np.asarray(inv_xs, dtype=float)[:, None]
    out = _one_turn(coef, K, e, N)
    if shift is not None:
        ramp = np.arange(N) * (1.0 / M)
        for i in np.flatnonzero(shift).tolist():
            out[i] += float(shift[i]) * ramp
    others = nodes[K:]
    if others.size:
        miss = np.abs(out.take(others, axis=1) - X.take(others, axis=1))
        if scale is not None:
            miss *= scale
        if not float(np.maximum.reduce(miss, axis=None)) <= TURN_TRUST:
            return None
    out[:, nodes] = X.take(nodes, axis=1)
    return out


def _basis_rows(tau, K):
    """The 2K basis functions and their derivatives at the angles ``tau``: (len(tau), 2K) each.

    Order: 1, cos tau, sin tau, ..., cos (K-1) tau, sin (K-1) tau, sin K tau (at K even nodes
    ``cos K tau`` is the constant again; ``sin K tau`` is zero there, fixed by the tangents).
    """
    k = np.arange(1, K)
    ang = np.outer(tau, k)
    c, s = np.cos(ang), np.sin(ang)
    B = np.empty((tau.size, 2 * K))
    dB = np.empty((tau.size, 2 * K))
    B[:, 0], dB[:, 0] = 1.0, 0.0
    B[:, 1 : 2 * K - 1 : 2], B[:, 2 : 2 * K - 1 : 2] = c, s
    dB[:, 1 : 2 * K - 1 : 2], dB[:, 2 : 2 * K - 1 : 2] = -s * k, c * k
    B[:, -1], dB[:, -1] = np.sin(K * tau), K * np.cos(K * tau)
    return B, dB


@lru_cache(maxsize=8)
def _inverse_t(K):
    """The transposed inverse of the interpolation matrix at K even nodes (values, then tangents): (2K, 2K),
    so that ``[values | tangents] @ _inverse_t(K)`` are the coefficients (read-only)."""
    B, dB = _basis_rows(_TWO_PI * np.arange(K) / K, K)
    inv = np.linalg.inv(np.vstack([B, dB])).T.copy()
    inv.flags.writeable = False
    return inv


@lru_cache(maxsize=8)
def _trend(K):
    """What an unknown gaining 1 over a turn, ``j / M`` at grid point j, has at the K nodes and as
    tangent (d/dtau: 1 / 2 pi), in the order of the fitted data: (2K,)."""
    r = np.concatenate((np.arange(K) / K, np.full(K, 1.0 / _TWO_PI)))
    r.flags.writeable = False
    return r


def _one_turn(coef, K, e, N):
    """The polynomials with coefficients ``coef`` (n, 2K) at the N grid points ``tau_j = 2 pi j / M``,
    M = K e (past a turn, the turn again): (n, N).

    Segment by segment: on the segment from node m (``tau_m = 2 pi m / K``), at ``tau_m + delta``, each
    harmonic is the node's rotation of it times ``cos k delta`` and ``sin k delta``, which are the same on
    every segment (``delta = 2 pi i / M``, i = 0 ... e - 1): two products, with matrices of K^3 and of 2K
    times the points per segment entries (as many as the grid's points of two unknowns).
    """
    n = coef.shape[0]
    per_node = _product(coef, _rotations(K)).reshape(n * K, 2 * K)  # each node's coefficients in delta
    at = _product(_segment_bases(K, e), per_node.T)  # (e, n K): point i of every segment, by row
    M = K * e
    out = np.empty((n, max(N, M)))
    out[:, :M].reshape(n, K, e)[...] = at.T.reshape(n, K, e)  # (one strided copy)
    if N > M:
        out[:, M:] = out[:, : N - M] if N <= 2 * M else out.take(np.arange(M, N) % M, axis=1)
    return out if N >= M else out[:, :N]


#: Most multiply-adds in one matrix product of the predictor, 131072: below this OpenBLAS computes a
#: product on one thread (a threaded product leaves its threads spinning on the other cores afterwards,
#: CPU time taken from the rest of the sweep).
_ONE_THREAD = 131072


def _product(a, b):
    """``a @ b`` in blocks of rows of ``a``, each product small enough for one thread (:data:`_ONE_THREAD`)."""
    rows = max(1, _ONE_THREAD // max(1, a.shape[1] * b.shape[1]))
    if a.shape[0] <= rows:
        return a @ b
    out = np.empty((a.shape[0], b.shape[1]))
    for r in range(0, a.shape[0], rows):
        np.matmul(a[r : r + rows], b, out=out[r : r + rows])
    return out


@lru_cache(maxsize=4)
def _rotations(K):
    """(2K, 2K K): the coefficients in ``tau`` to those in ``delta`` on the segment from each node
    (``a cos k(tau_m + delta) + b sin k(tau_m + delta)`` = ``(a cos k tau_m + b sin k tau_m) cos k delta``
    + ``(b cos k tau_m - a sin k tau_m) sin k delta``; ``sin K tau_m`` is 0 and ``cos K tau_m`` 1)."""
    R = np.zeros((2 * K, K, 2 * K))
    R[0, :, 0] = 1.0
    R[-1, :, -1] = 1.0
    for k in range(1, K):
        c, s = np.cos(k * _TWO_PI * np.arange(K) / K), np.sin(k * _TWO_PI * np.arange(K) / K)
        i, j = 2 * k - 1, 2 * k  # cos k, sin k
        R[i, :, i], R[j, :, i] = c, s
        R[j, :, j], R[i, :, j] = c, -s
    R = R.reshape(2 * K, K * 2 * K)
    R.flags.writeable = False
    return R


def _segment_bases(K, e):
    """(e, 2K): the basis functions at ``delta = 2 pi i / (K e)``, i = 0 ... e - 1 (read-only; kept
    between sweeps up to :data:`_KEPT_BASES` entries)."""
    return _kept_segment_bases(K, e) if 2 * K * e <= _KEPT_BASES else _new_segment_bases(K, e)


def _new_segment_bases(K, e):
    """The bases of :func:`_segment_bases`: ``exp(i k delta)`` by repeated products of ``exp(i delta)``
    (round-off of k ulps at harmonic k; a predictor's), ``sin K delta`` on its own."""
    delta = _TWO_PI * np.arange(e) / (K * e)
    B = np.empty((e, 2 * K))
    B[:, 0] = 1.0
    z = np.exp(1j * delta)
    zk = z.copy()
    for k in range(1, K):
        B[:, 2 * k - 1], B[:, 2 * k] = zk.real, zk.imag
        if k < K - 1:
            zk *= z
    B[:, -1] = np.sin(K * delta)
    B.flags.writeable = False
    return B


_kept_segment_bases = lru_cache(maxsize=8)(_new_segment_bases)

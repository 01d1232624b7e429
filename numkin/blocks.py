"""The block lower-triangular shape of a mechanism's Jacobian, and the solves that use it.

Loop ``k``'s residuals depend only on its own unknowns and those of earlier
loops, so a Newton step, a tangent or an acceleration is a forward
substitution through the loops, each a small solve. :class:`BlockStructure`
does it at one point (plain floats, generated code for blocks of size 1 and
2) or at many (numpy arrays); :func:`stack_rows` stacks Jacobian rows that
are arrays or numbers.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from .unrolled import cond2, unrolled_local, unrolled_newton, unrolled_newton_batch, unrolled_solve, unrolled_update

__all__ = ["BlockStructure", "stack_rows"]


class BlockStructure:
    """The block lower-triangular shape of a mechanism's Jacobian, and solves that use it.

    Loop ``k``'s residuals depend only on its own unknowns and those of
    earlier loops, so ``J`` is block lower-triangular with one square
    diagonal block per loop: a Newton step is a forward substitution through
    the loops, each a small solve (2 x 2 for a vector loop, by Cramer's rule).
    The orientation of a loop (the sign of its block's determinant) and the
    condition number of its scaled block come from the same numbers.

    Jacobians are passed as *rows*: ``J[i * n + j]`` is entry (i, j), a
    float (one point) or an (N,) array or a number (many points).

    Parameters
    ----------
    slices : list of slice
        The unknowns of every loop (``Mechanism.loop_slices``).
    fscale : float
        Residual scale (a length).
    xscale : array_like (n,)
        Unknown scales.
    zeros : iterable of (i, j), optional
        Jacobian entries that are identically zero besides the upper blocks
        (the unrolled solves skip them).

    Examples
    --------
    >>> bs = BlockStructure([slice(0, 2)], 1.0, [1.0, 1.0])
    >>> bs.solve1([2.0, 0.0, 0.0, 4.0], [1.0, 1.0])
    ([0.5, 0.25], [1.0])
    >>> [round(c, 12) for c in bs.cond1([2.0, 0.0, 0.0, 4.0])]
    [2.0]
    """

    def __init__(self, slices, fscale, xscale, zeros=()):
        self.xscale = np.asarray(xscale, dtype=float)
        self.n = n = self.xscale.size
        self.fscale = float(fscale)
        self.blocks = [(s.start, s.stop) for s in slices]
        self.inv_xscale = [1.0 / v for v in self.xscale.tolist()]
        # scale of entry (i, j) of a scaled block: xscale_j / fscale
        self._col = [v / self.fscale for v in self.xscale.tolist()]
        # squares of unscaled entries would leave the normal float64 range
        self._extreme = not all(1e-30 <= c <= 1e30 for c in self._col)
        self._rows = {(a, b): [i * n + j for i in range(a, b) for j in range(a, b)] for a, b in self.blocks}
        self._small = all(b - a <= 2 for a, b in self.blocks)
        self._step = None
        self.newton1 = None
        self.newton_batch = None
        self._local = None
        zeros = self._zeros = set(zeros)
        if self._small:
            self.solve1 = unrolled_solve(n, self.blocks, zeros, batch=False)
            self._step = unrolled_solve(n, self.blocks, zeros, batch=True)
            self.update1 = unrolled_update(n, self.blocks, zeros, self.inv_xscale)
            self._local = unrolled_local(n, self.blocks, zeros, self._col)
            self.local1 = self._local  # the method below, written out: called without the indirection
            #: Newton-Raphson at one point with every update written out for these blocks; called with
            #: the kernel, the point and the stopping rule (see :meth:`numkin.march.Continuation.newton1`).
            self.newton1 = unrolled_newton(n, self.blocks, zeros, self.inv_xscale, self._col)
            #: Newton-Raphson on whole arrays with every update written out (see
            #: :meth:`numkin.march.Continuation.newton_batch`).
            self.newton_batch = unrolled_newton_batch(n, self.blocks, zeros, self.inv_xscale)

    def loop_newton1(self, k):
        """:attr:`newton1` on the unknowns of block ``k`` alone, every other unknown held (generated when first
        asked for, once for every mechanism of the same structure); None unless every block is of size 1 or 2."""
        if not self._small:
            return None
        return _loop_newton1(self.n, tuple(self.blocks), frozenset(self._zeros), tuple(self.inv_xscale),
                             tuple(self._col), k)

    def newton_step(self, J, f):
        """The Newton step ``-J^-1 f`` at every point: J rows, f (n, N) -> (dx (n, N), bad (N,)).

        ``bad`` marks singular or non-finite solves (their dx is NaN). Call
        it under ``numpy.errstate(all="ignore")``: a zero determinant gives
        inf or NaN, which ``bad`` reports.
        """
        return self.solve_negated(J, f, f.shape[1])

    def solve_negated(self, J, rows, N):
        """``-J^-1 r`` at every point, block by block: J rows, ``r`` n rows -> (dx (n, N), bad (N,)).

        The rows of ``J`` and ``r`` are (N,) arrays or numbers (a constant
        entry). The cost is linear in the number of loops: one forward
        substitution through the diagonal blocks, Cramer's rule for blocks
        of size 1 and 2. ``bad`` marks singular or non-finite solves (their
        dx is NaN). Call it under ``numpy.errstate(all="ignore")``.

        Examples
        --------
        >>> import numpy as np
        >>> bs = BlockStructure([slice(0, 1), slice(1, 2)], 1.0, [1.0, 1.0])
        >>> dx, bad = bs.solve_negated([2.0, 0.0, 1.0, 4.0], [np.array([2.0, 4.0]), 0.0], 2)
        >>> dx.tolist(), bad.tolist()
        ([[-1.0, -2.0], [0.25, 0.5]], [False, False])
        """
        if self._step is None:
            dx, _, bad = self.solve(J, -stack_rows(rows, N))
            return dx, bad
        dx = np.empty((self.n, N), dtype=complex if _any_complex(rows) or _any_complex(J[:1]) else float)
        self._step(J, rows, dx)
        total = dx[0] if self.n == 1 else dx.sum(axis=0)
        bad = ~np.isfinite(total)
        if bad.any():
            dx[:, bad] = np.nan
        return dx, bad

    # ------------------------------------------------------------ one point
    def solve1(self, J, rhs):
        """Solve ``J dx = rhs`` at one point; returns ``(dx, signs)`` or ``(None, None)`` if singular.

        ``signs`` are the signs of the diagonal blocks' determinants. (For
        blocks of size 1 and 2 an unrolled version replaces this method.)
        """
        n = self.n
        dx = [0.0] * n
        signs = []
        for a, b in self.blocks:
            r = [rhs[i] - sum(J[i * n + j] * dx[j] for j in range(a)) for i in range(a, b)]
            k = b - a
            m = np.array([J[i] for i in self._rows[(a, b)]], dtype=float).reshape(k, k)
            det = float(np.linalg.det(m)) if np.all(np.isfinite(m)) else math.nan
            if not (det != 0.0 and math.isfinite(det)):
                return None, None
            sol = np.linalg.solve(m, np.asarray(r, dtype=float))
            if not np.all(np.isfinite(sol)):
                return None, None
            dx[a:b] = sol.tolist()
            signs.append(1.0 if det > 0 else -1.0)
        return dx, signs

    def update1(self, v, x):
        """One Newton update at one point from ``v = [F..., J rows..., ...]``.

        Returns ``(x - J^-1 F, scaled step norm)`` or ``(None, None)`` if J
        is singular. (For blocks of size 1 and 2 an unrolled version
        replaces this method.)
        """
        n = self.n
        dx, _ = self.solve1(v[n : n + n * n], [-a for a in v[:n]])
        if dx is None:
            return None, None
        return [a + b for a, b in zip(x, dx)], max([abs(a) * w for a, w in zip(dx, self.inv_xscale)])

    def update1_loop(self, v, x, k):
        """:meth:`update1` of block ``k``'s unknowns alone, every other unknown held: ``(x - J_kk^-1 F_k, scaled
        step norm)`` or ``(None, None)`` if the block is singular or the step not finite."""
        n = self.n
        a, b = self.blocks[k]
        m = np.array([v[n + i * n + j] for i in range(a, b) for j in range(a, b)], dtype=float).reshape(b - a, b - a)
        det = float(np.linalg.det(m)) if np.all(np.isfinite(m)) else math.nan
        dx = np.linalg.solve(m, [-f for f in v[a:b]]).tolist() if det != 0.0 and math.isfinite(det) else None
        if dx is None or not math.isfinite(sum(dx)):
            return None, None
        return [*x[:a], *(xi + di for xi, di in zip(x[a:b], dx)), *x[b:]], max(
            [abs(d) * w for d, w in zip(dx, self.inv_xscale[a:b])])

    def local1(self, v):
        """Tangent, orientations and largest condition number at one solved point.

        ``v`` holds the residuals, the Jacobian rows and dF/dt (one point,
        floats). Returns ``(dq/dt, signs, cond)``: the tangent ``-J^-1 dF/dt``
        and the signs of the blocks' determinants (None, None where a block
        is singular), and the largest condition number of the scaled blocks
        (:meth:`cond1`).

        Examples
        --------
        >>> bs = BlockStructure([slice(0, 2)], 1.0, [1.0, 1.0])
        >>> d, o, c = bs.local1([0.0, 0.0, 2.0, 0.0, 0.0, 4.0, -1.0, -1.0])
        >>> d, o, round(c, 12)
        ([0.5, 0.25], [1.0], 2.0)
        """
        if self._local is not None:
            return self._local(v)
        n, nn = self.n, self.n * self.n
        d, o = self.solve1(v[n : n + nn], [-a for a in v[n + nn :]])
        return d, o, max(self.cond1(v[n : n + nn]))

    def cond1(self, J):
        """Condition numbers of the scaled diagonal blocks at one point (list, one per loop)."""
        if not self._small:
            return self.cond(list(J), 1)[:, 0].tolist()
        n = self.n
        out = []
        for a, b in self.blocks:
            if b - a == 1:
                j = J[a * n + a]
                out.append(1.0 if (j != 0.0 and math.isfinite(j)) else math.inf)
                continue
            i0 = a * n + a
            ca, cb = self._col[a], self._col[a + 1]
            out.append(cond2(J[i0] * ca, J[i0 + 1] * cb, J[i0 + n] * ca, J[i0 + n + 1] * cb))
        return out

    # ------------------------------------------------------------ many points
    def solve(self, J, rhs):
        """Solve ``J dx = rhs`` at every point: J rows (n*n entries, arrays or numbers), rhs (n, N).

        Returns ``dx`` (n, N), ``signs`` (loops, N) and ``bad`` (N,): points
        whose solve is singular or not finite (their dx is NaN).
        """
        n = self.n
        N = rhs.shape[1]
        dx = [None] * n
        signs = np.empty((len(self.blocks), N))
        bad = np.zeros(N, dtype=bool)
        with np.errstate(all="ignore"):
            for k, (a, b) in enumerate(self.blocks):
                r = [rhs[i] for i in range(a, b)]
                if a:
                    for i in range(a, b):
                        for j in range(a):
                            e = J[i * n + j]
                            if np.ndim(e) or e != 0:
                                r[i - a] = r[i - a] - e * dx[j]
                size = b - a
                if size == 2:
                    i0 = a * n + a
                    j00, j01, j10, j11 = J[i0], J[i0 + 1], J[i0 + n], J[i0 + n + 1]
                    det = j00 * j11 - j01 * j10
                    inv = 1.0 / det
                    dx[a] = (r[0] * j11 - j01 * r[1]) * inv
                    dx[a + 1] = (j00 * r[1] - j10 * r[0]) * inv
                elif size == 1:
                    det = J[a * n + a]
                    dx[a] = r[0] / det
                else:
                    m = np.moveaxis(stack_rows([J[i] for i in self._rows[(a, b)]], N).reshape(size, size, N), -1, 0)
                    det = np.linalg.det(m)
                    ok = np.isfinite(det) & (det != 0)
                    sol = np.full((size, N), np.nan, dtype=np.result_type(m, rhs))
                    if ok.any():
                        sol[:, ok] = np.linalg.solve(m[ok], np.array(r)[:, ok].T[..., None])[..., 0].T
                    dx[a:b] = list(sol)
                det = np.real(det)
                signs[k] = np.sign(det)
                bad |= ~(det != 0)
            out = stack_rows(dx, N)
            bad |= ~np.isfinite(out.sum(axis=0))
        out[:, bad] = np.nan
        return out, signs, bad

    def signs(self, J, N):
        """Signs of the diagonal blocks' determinants (loops, N) from J rows; 0 where singular."""
        n = self.n
        out = np.empty((len(self.blocks), N))
        for k, (a, b) in enumerate(self.blocks):
            size = b - a
            if size == 2:
                i0 = a * n + a
                det = J[i0] * J[i0 + n + 1] - J[i0 + 1] * J[i0 + n]
            elif size == 1:
                det = J[a * n + a]
            else:
                det = np.linalg.det(np.moveaxis(stack_rows([J[i] for i in self._rows[(a, b)]], N).reshape(size, size, N), -1, 0))
            out[k] = np.sign(np.real(det))
        return out

    def cond(self, J, N):
        """2-norm condition numbers of the scaled diagonal blocks (loops, N), from J rows.

        Block rows are divided by ``fscale`` and columns multiplied by the
        unknowns' scales. A 2 x 2 block uses the closed form
        ``((A + B) / 2)^2 / |d|``, ``d`` the determinant and ``A``, ``B`` the
        sum and the difference of the singular values (``A^2 = s + 2|d|``,
        ``B^2 = s - 2|d|``, ``s`` the squared Frobenius norm), each computed
        as a sum of squares, so that well-conditioned blocks lose no digits.
        A singular or non-finite block gives ``inf``.
        """
        return self.cond_signs(J, N)[0]

    def cond_signs(self, J, N, quiet=True):
        """:meth:`cond` and :meth:`signs` from one pass over the blocks: ``(cond (loops, N), signs (loops, N))``.

        ``quiet``: numpy's floating-point warnings (a singular block divides by zero) silenced here;
        False where the caller runs under ``numpy.errstate(all="ignore")`` already.

        Examples
        --------
        >>> import numpy as np
        >>> bs = BlockStructure([slice(0, 2)], 1.0, [1.0, 1.0])
        >>> cond, signs = bs.cond_signs([np.array([2.0, 0.0]), 0.0, 0.0, np.array([4.0, -1.0])], 2)
        >>> cond.tolist(), signs.tolist()
        ([[2.0, inf]], [[1.0, 0.0]])
        """
        if quiet:
            with np.errstate(all="ignore"):
                return self.cond_signs(J, N, quiet=False)
        n = self.n
        out = np.empty((len(self.blocks), N))
        signs = np.empty((len(self.blocks), N))
        for k, (a, b) in enumerate(self.blocks):
            size = b - a
            if size == 2:
                i0 = a * n + a
                p, q, r, s = (J[i] if isinstance(J[i], np.ndarray) and J[i].dtype.kind == "f" else np.real(J[i])
                              for i in (i0, i0 + 1, i0 + n, i0 + n + 1))
                ca, cb = self._col[a], self._col[a + 1]
                det = p * s - q * r
                signs[k] = np.sign(det)
                if self._extreme:  # entries of order one whatever the length scale: no overflow in the squares
                    p, q, r, s = p * ca, q * cb, r * ca, s * cb
                    det = p * s - q * r
                elif ca != cb:  # scaling all entries alike leaves the condition number alone
                    p, r = p * (ca / cb), r * (ca / cb)
                    det = p * s - q * r
                if np.ndim(det) == 0:  # a block of constants
                    det = np.full(N, det, dtype=float)
                sg = np.copysign(1.0, det)
                ss, sr = sg * s, sg * r
                c = p + ss  # (sigma1 + sigma2)^2 = (p + sg s)^2 + (q - sg r)^2
                c *= c
                w = q - sr
                w *= w
                c += w
                u = p - ss  # (sigma1 - sigma2)^2 = (p - sg s)^2 + (q + sg r)^2
                u *= u
                np.add(q, sr, out=w)
                w *= w
                u += w
                np.sqrt(c, out=c)
                np.sqrt(u, out=u)
                c += u
                c *= c  # (2 sigma1)^2
                np.abs(det, out=u)
                u *= 4.0
                c /= u  # sigma1 / sigma2
                np.maximum(c, 1.0, out=out[k])  # c < 1 only by rounding at cond 1
                nan = np.isnan(out[k])  # a zero or non-finite block: singular
                if np.count_nonzero(nan):
                    out[k, nan] = np.inf
            elif size == 1:
                e = np.real(J[a * n + a])
                out[k] = np.where(np.isfinite(e) & (e != 0), 1.0, np.inf)
                signs[k] = np.sign(e)
            else:
                m = np.moveaxis(stack_rows([J[i] for i in self._rows[(a, b)]], N).reshape(size, size, N), -1, 0)
                signs[k] = np.sign(np.real(np.linalg.det(m)))
                m = np.real(m) * (np.asarray(self._col[a:b])[None, None, :])
                c = np.full(N, np.inf)
                ok = np.all(np.isfinite(m), axis=(1, 2))
                if ok.any():
                    c[ok] = np.linalg.cond(m[ok])
                out[k] = np.where(np.isfinite(c), c, np.inf)
        return out, signs


@lru_cache(maxsize=64)
def _loop_newton1(n, blocks, zeros, inv_xscale, col, k):
    """:func:`numkin.unrolled.unrolled_newton` of block ``k`` alone, kept for mechanisms of the same structure."""
    return unrolled_newton(n, list(blocks), set(zeros), list(inv_xscale), list(col), only=k)


def _any_complex(rows) -> bool:
    """Whether any of the rows (arrays or numbers) is complex."""
    for r in rows:
        if isinstance(r, np.ndarray):
            if r.dtype.kind == "c":
                return True
        elif isinstance(r, (complex, np.complexfloating)):
            return True
    return False


def stack_rows(rows, N):
    """Rows that are (N,) arrays or numbers, as one (len(rows), N) array."""
    if all(np.ndim(r) for r in rows):
        return np.array(rows)
    dtype = np.result_type(*rows, float)
    out = np.empty((len(rows), N), dtype=dtype)
    for i, r in enumerate(rows):
        out[i] = r
    return out

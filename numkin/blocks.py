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

import numpy as np

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
        if self._small:
            zeros = set(zeros)
            self.solve1 = _unrolled_solve(n, self.blocks, zeros, batch=False)
            self._step = _unrolled_solve(n, self.blocks, zeros, batch=True)
            self.update1 = _unrolled_update(n, self.blocks, zeros, self.inv_xscale)
            #: Newton-Raphson at one point with every update written out for these blocks; called with
            #: the kernel, the point and the stopping rule (see :meth:`numkin.march.Continuation.newton1`).
            self.newton1 = _unrolled_newton(n, self.blocks, zeros, self.inv_xscale, self._col)
            #: Newton-Raphson on whole arrays with every update written out (see
            #: :meth:`numkin.march.Continuation.newton_batch`).
            self.newton_batch = _unrolled_newton_batch(n, self.blocks, zeros, self.inv_xscale)

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
            out.append(_cond2(J[i0] * ca, J[i0 + 1] * cb, J[i0 + n] * ca, J[i0 + n + 1] * cb))
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
        ``(s + sqrt((s - 2|d|)(s + 2|d|))) / (2|d|)``, ``s`` the squared
        Frobenius norm and ``d`` the determinant, with ``s - 2|d|`` computed
        as a sum of squares, so that well-conditioned blocks lose no digits.
        A singular or non-finite block gives ``inf``.
        """
        n = self.n
        out = np.empty((len(self.blocks), N))
        with np.errstate(all="ignore"):
            for k, (a, b) in enumerate(self.blocks):
                size = b - a
                if size == 2:
                    i0 = a * n + a
                    p, q, r, s = (np.real(J[i]) for i in (i0, i0 + 1, i0 + n, i0 + n + 1))
                    ca, cb = self._col[a], self._col[a + 1]
                    if self._extreme:  # entries of order one whatever the length scale: no overflow in the squares
                        p, q, r, s = p * ca, q * cb, r * ca, s * cb
                    elif ca != cb:  # scaling all entries alike leaves the condition number alone
                        p, q, r, s = p * (ca / cb), q, r * (ca / cb), s
                    det = p * s - q * r
                    fro = p * p + q * q + r * r + s * s
                    sg = np.copysign(1.0, det)
                    u, w = p - sg * s, q + sg * r
                    ad = np.abs(det)
                    c = np.maximum((fro + np.sqrt((u * u + w * w) * (fro + 2 * ad))) / (2 * ad), 1.0)
                    out[k] = c  # c < 1 only by rounding at cond 1
                    nan = np.isnan(out[k])  # a zero or non-finite block: singular
                    if nan.any():
                        out[k, nan] = np.inf
                elif size == 1:
                    e = np.real(J[a * n + a])
                    out[k] = np.where(np.isfinite(e) & (e != 0), 1.0, np.inf)
                else:
                    m = np.moveaxis(stack_rows([J[i] for i in self._rows[(a, b)]], N).reshape(size, size, N), -1, 0)
                    m = np.real(m) * (np.asarray(self._col[a:b])[None, None, :])
                    c = np.full(N, np.inf)
                    ok = np.all(np.isfinite(m), axis=(1, 2))
                    if ok.any():
                        c[ok] = np.linalg.cond(m[ok])
                    out[k] = np.where(np.isfinite(c), c, np.inf)
        return out


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



def _cond2(p, q, r, s):
    """2-norm condition number of [[p, q], [r, s]] (closed form; see ``BlockStructure.cond``)."""
    det = p * s - q * r
    if not (det != 0.0 and math.isfinite(det)):
        return math.inf
    fro = p * p + q * q + r * r + s * s
    gap = (p - s) ** 2 + (q + r) ** 2 if det > 0 else (p + s) ** 2 + (q - r) ** 2
    ad = abs(det)
    c = (fro + math.sqrt(gap * (fro + 2.0 * ad))) / (2.0 * ad)
    return c if c >= 1.0 else (1.0 if math.isfinite(c) else math.inf)


def _step_lines(n, blocks, zeros, singular, indent="    "):
    """Lines computing the Newton step ``d0 .. d{n-1} = -J^-1 F`` from ``v = [F..., J rows...]``
    by forward substitution through the blocks (sizes 1 and 2); ``singular`` is the statement
    run where a block's determinant is zero or not finite. ``singular=None``: whole arrays, no
    test (the caller tests the result), each 2 x 2 block multiplied by ``1 / det``."""
    lines = []
    for a, b in blocks:
        for i in range(a, b):
            terms = "".join(f" + v[{n + i * n + j}] * d{j}" for j in range(a) if (i, j) not in zeros)
            lines.append(f"r{i} = v[{i}]{terms}")
        if b - a == 2:
            i0 = n + a * n + a
            lines.append(f"a00 = v[{i0}]; a01 = v[{i0 + 1}]; a10 = v[{i0 + n}]; a11 = v[{i0 + n + 1}]")
            if singular is None:
                lines += [
                    "inv = 1.0 / (a00 * a11 - a01 * a10)",
                    f"d{a} = (a01 * r{a + 1} - r{a} * a11) * inv",
                    f"d{a + 1} = (a10 * r{a} - a00 * r{a + 1}) * inv",
                ]
                continue
            lines += [
                "det = a00 * a11 - a01 * a10",
                f"if not (det != 0.0 and -INF < det < INF): {singular}",
                f"d{a} = (a01 * r{a + 1} - r{a} * a11) / det",
                f"d{a + 1} = (a10 * r{a} - a00 * r{a + 1}) / det",
            ]
        elif singular is None:
            lines.append(f"d{a} = -r{a} / v[{n + a * n + a}]")
        else:
            lines += [
                f"det = v[{n + a * n + a}]",
                f"if not (det != 0.0 and -INF < det < INF): {singular}",
                f"d{a} = -r{a} / det",
            ]
    if singular is not None:
        lines.append(f"if not -INF < {' + '.join(f'd{i}' for i in range(n))} < INF: {singular}")
    return [indent + line for line in lines]


def _scaled_max(names, weights):
    """Source of ``max(|name_i| * weight_i)`` (a weight of one left out)."""
    terms = [f"abs({a})" if w == 1.0 else f"abs({a}) * {w!r}" for a, w in zip(names, weights)]
    return terms[0] if len(terms) == 1 else f"max({', '.join(terms)})"


def _unrolled_update(n, blocks, zeros, inv_xscale):
    """Generate ``update1(v, x) -> (x_new, step)``: one Newton update at one point, written out.

    ``v`` holds the residuals then the Jacobian rows (from offset n).
    """
    lines = ["def update1(v, x):", *_step_lines(n, blocks, zeros, "return None, None")]
    step = _scaled_max([f"d{i}" for i in range(n)], inv_xscale)
    lines.append(f"    return [{', '.join(f'x[{i}] + d{i}' for i in range(n))}], {step}")
    namespace = {"INF": math.inf}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers only
    return namespace["update1"]


def _unrolled_newton(n, blocks, zeros, inv_xscale, col):
    """Generate ``newton1(K, x, t, pt, maxiter, fscale, tol, converged, floor, errors, cond_max=None)``:
    Newton-Raphson at one point with every update written out.

    ``K(*x, t, *pt)`` is the fused scalar kernel (residuals, Jacobian rows,
    ...), ``converged`` the stopping rule (:func:`numkin.newton_rules.has_converged`)
    and ``floor(x, t)`` the residual's round-off floor (consulted only when the
    steps stall above ``tol``). Returns ``(x, status, iterations, residual, v,
    evaluations)`` as :meth:`numkin.march.Continuation.newton1` does: a
    Jacobian singular where the residual is already within ``tol`` (a root
    on a singular position, predicted exactly) has converged; with
    ``cond_max``, a Jacobian whose scaled blocks (``col``: the unknowns'
    scales over the residuals') have a larger condition number is refused
    as singular.
    """
    xs = [f"x{i}" for i in range(n)]
    xl = "[" + ", ".join(xs) + "]"
    res = "max(" + ", ".join(f"abs(v[{i}])" for i in range(n)) + ")" if n > 1 else "abs(v[0])"
    # the conditioning rule on the scaled 2 x 2 blocks (a block of size 1 is refused only where it is
    # exactly singular, by the step itself, as in BlockStructure.cond1)
    conds = [f"COND2(v[{n + a * n + a}] * {col[a]!r}, v[{n + a * n + a + 1}] * {col[a + 1]!r}, "
             f"v[{n + (a + 1) * n + a}] * {col[a]!r}, v[{n + (a + 1) * n + a + 1}] * {col[a + 1]!r})"
             for a, b in blocks if b - a == 2]
    cond_check = []
    if conds:
        worst = conds[0] if len(conds) == 1 else f"max({', '.join(conds)})"
        cond_check = [f"        if cond_max is not None and not {worst} <= cond_max:",
                      "            status = 'singular'",
                      "            break"]
    lines = [
        "def newton1(K, x, t, pt, maxiter, fscale, tol, converged, floor, errors, cond_max=None):",
        f"    {', '.join(xs)}{',' if n == 1 else ''} = x",
        "    try:",
        f"        v = K({', '.join(xs)}, t, *pt)",
        "    except errors:",
        "        return x, 'diverged', 0, NAN, None, 1",
        "    if not -INF < sum(v) < INF:",
        "        return x, 'diverged', 0, NAN, None, 1",
        f"    res = {res} / fscale",
        "    prev = INF",
        "    it = 0",
        "    status = 'maxiter'",
        "    while it < maxiter:",
        *cond_check,
        *_step_lines(n, blocks, zeros, "status = 'converged' if res <= tol and cond_max is None else 'singular'; break",
                     indent="        "),
        *[f"        x{i} += d{i}" for i in range(n)],
        f"        step = {_scaled_max([f'd{i}' for i in range(n)], inv_xscale)}",
        "        it += 1",
        "        try:",
        f"            v = K({', '.join(xs)}, t, *pt)",
        "        except errors:",
        f"            return {xl}, 'diverged', it, NAN, None, it + 1",
        "        if not -INF < sum(v) < INF:",
        f"            return {xl}, 'diverged', it, NAN, None, it + 1",
        f"        res = {res} / fscale",
        f"        low = floor({xl}, t) if res > tol and step >= 0.9 * prev else 0.0",
        "        if converged(res, step, prev, tol, low):",
        "            status = 'converged'",
        "            break",
        "        prev = step",
        f"    return {xl}, status, it, res, v, it + 1",
    ]
    namespace = {"INF": math.inf, "NAN": math.nan, "COND2": _cond2}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace["newton1"]


def _unrolled_newton_batch(n, blocks, zeros, inv_xscale):
    """Generate ``newton_batch(K, x, t, kargs, active, maxiter, fscale, tol, floor, converged)``:
    Newton-Raphson on whole arrays with every update written out.

    The iteration of :func:`numkin.newton.solve_batch` without compaction
    (every column is computed at every iteration, the inactive ones are not
    moved) and without histories: ``K(*x, t, *kargs)`` is the fused kernel
    (residual rows, then Jacobian rows), ``x`` (n, N) is iterated in place,
    ``converged`` the stopping rule (:func:`numkin.newton_rules.has_converged`).
    Returns ``(converged, singular, iterations, rows, evaluations)``, ``rows``
    the kernel's rows at the returned ``x``, ``evaluations`` the kernel's
    calls; or None, before any step, if a residual row
    is not an (N,) array (a constant residual: the caller's general loop
    takes it).
    """
    xs = ", ".join(f"x{i}" for i in range(n))
    call = f"K({xs}, t, *kargs)"
    fmax = "ABS(v[0])" if n == 1 else "MAX(" * (n - 1) + "ABS(v[0])" + "".join(
        f", ABS(v[{i}]))" for i in range(1, n))
    step = f"ABS(d0) * {inv_xscale[0]!r}" if inv_xscale[0] != 1.0 else "ABS(d0)"
    for i in range(1, n):
        term = f"ABS(d{i})" if inv_xscale[i] == 1.0 else f"ABS(d{i}) * {inv_xscale[i]!r}"
        step = f"MAX({step}, {term})"
    temporaries = ", ".join(["v", *(f"r{i}" for i in range(n)), *(f"d{i}" for i in range(n))]
                            + (["a00", "a01", "a10", "a11", "inv"] if any(b - a == 2 for a, b in blocks) else []))
    lines = [
        "def newton_batch(K, x, t, kargs, active, maxiter, fscale, tol, floor, converged):",
        "    N = x.shape[1]",
        *[f"    x{i} = x[{i}]" for i in range(n)],
        f"    v = {call}",
        f"    if not all(type(v[i]) is NDARRAY and v[i].shape == (N,) for i in range({n})):",
        "        return None",
        f"    fmax = {fmax}",
        "    done_all = ZEROS(N, dtype=bool)",
        "    singular = ZEROS(N, dtype=bool)",
        "    iterations = ZEROS(N, dtype=int)",
        "    act = active & ISFINITE(fmax)",
        "    prev = FULL(N, INF)",
        "    evaluations = 1",
        "    for _ in range(maxiter):",
        "        if not act.any():",
        "            break",
        *_step_lines(n, blocks, zeros, None, indent="        "),
        f"        upd = ISFINITE({' + '.join(f'd{i}' for i in range(n))})",
        "        bad = act & ~upd",
        "        upd &= act",
        *[f"        ADD(x{i}, d{i}, out=x{i}, where=upd)" for i in range(n)],
        f"        step = {step}",
        f"        del {temporaries}  # freed before the next evaluation: one set of rows alive at a time",
        f"        v = {call}",
        "        evaluations += 1",
        f"        fmax = {fmax}",
        "        iterations += upd",
        "        singular |= bad",
        "        done = upd & converged(fmax / fscale, step, prev, tol, floor)",
        "        done_all |= done",
        "        act &= ~(done | bad) & ISFINITE(fmax)",
        "        prev = WHERE(upd, step, prev)",
        "    return done_all, singular, iterations, v, evaluations",
    ]
    namespace = {"INF": math.inf, "ABS": np.abs, "MAX": np.maximum, "ADD": np.add, "ISFINITE": np.isfinite,
                 "WHERE": np.where, "ZEROS": np.zeros, "FULL": np.full, "NDARRAY": np.ndarray}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace["newton_batch"]


def _unrolled_solve(n, blocks, zeros=frozenset(), batch=False):
    """Generate the block forward substitution written out (blocks of size 1 or 2).

    ``batch=False``: ``solve1(J, r) -> (dx, signs)`` for one point (floats),
    ``(None, None)`` if a block is singular or a result not finite: the
    fastest plain-Python form. ``batch=True``: ``step(J, f) -> rows of
    -J^-1 f`` for arrays (no checks: the caller tests the result). Entries
    in ``zeros`` are left out.
    """

    def term(i, j):
        return (i, j) not in zeros

    lines = ["def solve(J, r):"] if not batch else ["def solve(J, f, out):"]
    for k, (a, b) in enumerate(blocks):
        for i in range(a, b):
            # batch: g_i = f_i + sum J_ij d_j  (d = -J^-1 f is solved as J d = -f)
            if batch:
                terms = "".join(f" + J[{i * n + j}] * d{j}" for j in range(a) if term(i, j))
                lines.append(f"    r{i} = f[{i}]{terms}")
            else:
                terms = "".join(f" - J[{i * n + j}] * d{j}" for j in range(a) if term(i, j))
                lines.append(f"    r{i} = r[{i}]{terms}")
        if b - a == 2:
            i0 = a * n + a
            lines += [
                f"    a00 = J[{i0}]; a01 = J[{i0 + 1}]; a10 = J[{i0 + n}]; a11 = J[{i0 + n + 1}]",
                f"    det{k} = a00 * a11 - a01 * a10",
            ]
            if batch:
                lines += [
                    f"    inv = -1.0 / det{k}",
                    f"    out[{a}] = (r{a} * a11 - a01 * r{a + 1}) * inv",
                    f"    out[{a + 1}] = (a00 * r{a + 1} - a10 * r{a}) * inv",
                    f"    d{a} = out[{a}]; d{a + 1} = out[{a + 1}]",
                    f"    del inv, det{k}, r{a}, r{a + 1}",
                ]
            else:
                lines += [
                    f"    if not (det{k} != 0.0 and -INF < det{k} < INF): return None, None",
                    f"    d{a} = (r{a} * a11 - a01 * r{a + 1}) / det{k}",
                    f"    d{a + 1} = (a00 * r{a + 1} - a10 * r{a}) / det{k}",
                ]
        else:
            lines.append(f"    det{k} = J[{a * n + a}]")
            if batch:
                lines += [f"    out[{a}] = -r{a} / det{k}", f"    d{a} = out[{a}]", f"    del det{k}, r{a}"]
            else:
                lines += [
                    f"    if not (det{k} != 0.0 and -INF < det{k} < INF): return None, None",
                    f"    d{a} = r{a} / det{k}",
                ]
    d = ", ".join(f"d{i}" for i in range(n))
    if batch:
        lines.append("    return out")
    else:
        sg = ", ".join(f"(1.0 if det{k} > 0 else -1.0)" for k in range(len(blocks)))
        lines += [
            f"    if not -INF < {' + '.join(f'd{i}' for i in range(n))} < INF: return None, None",
            f"    return [{d}], [{sg}]",
        ]
    namespace = {"INF": math.inf}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers only
    return namespace["solve"]

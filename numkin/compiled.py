"""Sympy expressions compiled once into vectorised numpy functions.

Everything symbolic about a mechanism happens here, once, when it is built
(or, for what only sweeps need, at its first sweep); nothing symbolic runs
inside a loop over input angles. Compilation is cached by the expressions'
shape, so every four-bar (its dimensions are symbols with values) shares one
set of functions.

* :func:`vector_function` -- numpy functions of whole arrays (real or
  complex, for complex-step differentiation) returning stacked arrays;
* :func:`scalar_function` -- ``math``-module functions of single floats, for
  the sequential steps of a continuation;
* :class:`BlockStructure` -- Newton steps, loop orientations and condition
  numbers that use the block lower-triangular shape of the loops' Jacobian;
* :class:`CompiledMechanism` -- all of a mechanism's functions.
"""

from __future__ import annotations

import math
from functools import cached_property, lru_cache

import numpy as np
import sympy as sp

__all__ = [
    "vector_function", "scalar_function", "CompiledMechanism", "BlockStructure", "stack_rows", "MATH_ERRORS",
    "acceleration_rhs", "rates", "jacobian_rows",
]

#: Errors the ``math`` module raises where numpy returns NaN or inf.
MATH_ERRORS = (ValueError, ZeroDivisionError, OverflowError)


@lru_cache(maxsize=512)
def _lambdify(exprs: tuple, args: tuple, modules: str, cse: bool):
    """``sympy.lambdify`` once per (expressions, arguments): mechanisms of one shape share code.

    Parameters enter as symbols, so e.g. every four-bar compiles to the same
    functions; building another one costs no new compilation. The generated
    code is also kept on disk between runs (:mod:`numkin.kernel_cache`).
    """
    from .kernel_cache import cached_lambdify

    return cached_lambdify(exprs, args, modules, cse)


def vector_function(exprs, args, varying=None):
    """Lambdify a list of expressions into ``f(*args) -> ndarray of shape (len(exprs), ...)``.

    ``varying`` are the arguments passed as arrays (default: all); entries
    that depend on none of them (a zero in a Jacobian, a parameter) are
    broadcast to the arrays' shape, so the result is always one stacked
    array. Its dtype follows the arguments (complex in, complex out).
    """
    exprs = [sp.sympify(e) for e in exprs]
    args = tuple(args)
    varying = set(args if varying is None else varying)
    moving = [k for k, e in enumerate(exprs) if e.free_symbols & varying]
    fixed = [k for k in range(len(exprs)) if k not in set(moving)]
    f_moving = _lambdify(tuple(exprs[k] for k in moving), args, "numpy", True) if moving else None
    f_fixed = _lambdify(tuple(exprs[k] for k in fixed), args, "numpy", False) if fixed else None
    m = len(exprs)

    if not fixed:

        def f(*values):
            return np.array(f_moving(*values))

    else:

        def f(*values):
            shape = next((np.shape(v) for v in values if np.ndim(v)), ())
            arr = np.empty((m, *shape), dtype=np.result_type(*values, float))
            arr[fixed] = np.array(f_fixed(*values), dtype=arr.dtype).reshape((len(fixed),) + (1,) * len(shape))
            if moving:
                arr[moving] = f_moving(*values)
            return arr

    f.expressions = exprs
    return f


def hoist_fixed_terms(exprs, unknowns):
    """Rewrite expressions so that a Newton solve recomputes only what depends on the unknowns.

    Two rewrites, both exact up to rounding:

    * ``sin``/``cos`` of a sum ``a + c`` where ``a`` holds the unknowns and
      ``c`` does not (``cos(phi + offset)``) is expanded by the addition
      theorem when ``sin(a)`` or ``cos(a)`` occurs anyway, so no new
      transcendental function of the unknowns is evaluated;
    * every function call free of the unknowns (``cos(theta)``,
      ``cos(offset)``) is replaced by a symbol ``_numkin_fixed<k>``.

    Returns ``(new expressions, symbols, their expressions)``: evaluate the
    latter once per sweep and pass them as extra arguments.
    """
    unknowns = set(unknowns)
    exprs = [sp.sympify(e) for e in exprs]
    trig = set().union(*(e.atoms(sp.sin, sp.cos) for e in exprs))
    expand = {}
    for f in trig:
        arg = f.args[0]
        if not isinstance(arg, sp.Add):
            continue
        a = sp.Add(*[term for term in arg.args if term.free_symbols & unknowns])
        c = arg - a
        if a == 0 or c == 0 or not ({sp.sin(a), sp.cos(a)} & trig):
            continue
        if isinstance(f, sp.sin):
            expand[f] = sp.sin(a) * sp.cos(c) + sp.cos(a) * sp.sin(c)
        else:
            expand[f] = sp.cos(a) * sp.cos(c) - sp.sin(a) * sp.sin(c)
    if expand:
        exprs = [e.xreplace(expand) for e in exprs]
    fixed = sorted(
        {f for e in exprs for f in e.atoms(sp.Function) if f.free_symbols and not (f.free_symbols & unknowns)},
        key=sp.default_sort_key,
    )
    names = [sp.Symbol(f"_numkin_fixed{k}") for k in range(len(fixed))]
    if fixed:
        exprs = [e.xreplace(dict(zip(fixed, names))) for e in exprs]
    return exprs, names, fixed


def scalar_function(exprs, args):
    """Lambdify expressions for *scalar* (float) arguments: ``f(*args) -> list of floats``.

    Uses the ``math`` module, some ten times faster than numpy on single
    numbers (the sequential steps of a continuation). Where ``math`` lacks a
    function of the expressions it falls back to numpy. Domain errors
    (``math.sqrt(-1)``) are raised as ``ValueError`` etc. (:data:`MATH_ERRORS`);
    callers treat them as a non-finite result.
    """
    exprs = tuple(sp.sympify(e) for e in exprs)
    args = tuple(args)
    f = _lambdify(exprs, args, "math", True)
    try:
        f(*([0.375] * len(args)))
    except MATH_ERRORS:
        pass
    except Exception:  # a function the math module does not have
        g = vector_function(exprs, args)

        def f(*values):
            return [float(v) for v in g(*values)]

    return f


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
        if self._small:
            zeros = set(zeros)
            self.solve1 = _unrolled_solve(n, self.blocks, zeros, batch=False)
            self._step = _unrolled_solve(n, self.blocks, zeros, batch=True)
            self.update1 = _unrolled_update(n, self.blocks, zeros, self.inv_xscale)

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
        dx = np.empty((self.n, N), dtype=complex if any(map(np.iscomplexobj, rows)) or np.iscomplexobj(J[0]) else float)
        self._step(J, rows, dx)
        total = dx[0] if self.n == 1 else dx.sum(axis=0)
        bad = ~np.isfinite(total)
        if np.ndim(bad) == 0:
            bad = np.full(N, bool(bad))
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


def stack_rows(rows, N):
    """Rows that are (N,) arrays or numbers, as one (len(rows), N) array."""
    if all(np.ndim(r) for r in rows):
        return np.array(rows)
    dtype = np.result_type(*rows, float)
    out = np.empty((len(rows), N), dtype=dtype)
    for i, r in enumerate(rows):
        out[i] = r
    return out


_stack = stack_rows  # the former name


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


def _unrolled_update(n, blocks, zeros, inv_xscale):
    """Generate ``update1(v, x) -> (x_new, step)``: one Newton update at one point, written out.

    ``v`` holds the residuals then the Jacobian rows (from offset n).
    """
    lines = ["def update1(v, x):"]
    for k, (a, b) in enumerate(blocks):
        for i in range(a, b):
            terms = "".join(f" + v[{n + i * n + j}] * d{j}" for j in range(a) if (i, j) not in zeros)
            lines.append(f"    r{i} = v[{i}]{terms}")
        if b - a == 2:
            i0 = n + a * n + a
            lines += [
                f"    a00 = v[{i0}]; a01 = v[{i0 + 1}]; a10 = v[{i0 + n}]; a11 = v[{i0 + n + 1}]",
                "    det = a00 * a11 - a01 * a10",
                "    if not (det != 0.0 and -INF < det < INF): return None, None",
                f"    d{a} = (a01 * r{a + 1} - r{a} * a11) / det",
                f"    d{a + 1} = (a10 * r{a} - a00 * r{a + 1}) / det",
            ]
        else:
            lines += [
                f"    det = v[{n + a * n + a}]",
                "    if not (det != 0.0 and -INF < det < INF): return None, None",
                f"    d{a} = -r{a} / det",
            ]
    lines.append(f"    if not -INF < {' + '.join(f'd{i}' for i in range(n))} < INF: return None, None")
    steps = ", ".join(f"abs(d{i})" if inv_xscale[i] == 1.0 else f"abs(d{i}) * {inv_xscale[i]!r}" for i in range(n))
    lines.append(f"    return [{', '.join(f'x[{i}] + d{i}' for i in range(n))}], max({steps}{',' if n == 1 else ''})")
    if n == 1:
        lines[-1] = lines[-1].replace(f"max({steps},)", steps)
    namespace = {"INF": math.inf}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers only
    return namespace["update1"]


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


class CompiledMechanism:
    """Numeric functions of a mechanism's stacked loop equations ``F(q, t) = 0``.

    ``q`` (n unknowns) are passed as rows of an (n, N) array, ``t`` as an (N,)
    array of inputs, parameter values are bound when called. The position
    functions (``F``, ``J`` and ``F_t``) are compiled on construction; the
    second-order function used for accelerations only on first use.

    Parameters
    ----------
    residuals : list of sympy expressions
        Stacked residuals of all loops, in loop order.
    unknowns : list of sympy symbols
    input_symbol : sympy symbol
    parameters : list of sympy symbols
    """

    def __init__(self, residuals, unknowns, input_symbol, parameters):
        self.residuals = sp.Matrix(residuals)
        self.unknowns = list(unknowns)
        self.input_symbol = input_symbol
        self.parameters = list(parameters)
        self.n = len(self.unknowns)
        self.args = [*self.unknowns, input_symbol, *self.parameters]
        jac = self.residuals.jacobian(self.unknowns)
        self.jacobian_matrix = jac
        self.varying = [*self.unknowns, input_symbol]
        self._F = vector_function(list(self.residuals), self.args, self.varying)
        self._J = vector_function(list(jac), self.args, self.varying)
        self._Ft = vector_function(list(self.residuals.diff(input_symbol)), self.args, self.varying)

    @cached_property
    def _fast(self):
        """Residual-and-Jacobian rows compiled for many points, with what does not change
        during a Newton solve taken out: see :func:`hoist_fixed_terms`."""
        exprs = list(self.residuals) + list(self.jacobian_matrix)
        exprs, names, fixed = hoist_fixed_terms(exprs, self.unknowns)
        rows = _lambdify(tuple(exprs), (*self.unknowns, self.input_symbol, *names, *self.parameters), "numpy", True)
        terms = _lambdify(tuple(fixed), (self.input_symbol, *self.parameters), "numpy", True) if fixed else None
        return rows, terms

    def fixed_terms(self, t, p) -> list:
        """The functions of the input and parameters alone that :meth:`FJ_rows` uses (e.g.
        ``cos(theta)``), evaluated once for a sweep's inputs ``t``."""
        terms = self._fast[1]
        return [] if terms is None else terms(t, *p)

    def FJ_rows(self, q, t, p, fixed=None) -> list:
        """Residuals and Jacobian in one call, as a list of n + n*n rows: rows 0..n-1 the
        residuals, then the Jacobian's entries row by row (``n + i * n + j`` is entry (i, j)).

        Each row is an (N,) array, or a number where the entry is constant.
        ``fixed`` is :meth:`fixed_terms` at ``t`` (computed here if not given).
        """
        if fixed is None:
            fixed = self.fixed_terms(t, p)
        return self._fast[0](*q, t, *fixed, *p)

    @cached_property
    def scalar_F(self):
        """Residuals at one point: ``scalar_F(*q, t, *p) -> list`` (``math`` module, floats)."""
        return scalar_function(list(self.residuals), self.args)

    @cached_property
    def scalar_FJT(self):
        """Residuals, Jacobian rows and dF/dt at one point, one flat list of n + n*n + n floats."""
        exprs = list(self.residuals) + list(self.jacobian_matrix) + list(self.residuals.diff(self.input_symbol))
        return scalar_function(exprs, self.args)

    def F(self, q, t, p):
        """Residuals, shape (n, N)."""
        return self._F(*q, t, *p)

    def J(self, q, t, p):
        """Jacobians dF/dq, shape (N, n, n)."""
        n = self.n
        return np.moveaxis(self._J(*q, t, *p).reshape(n, n, -1), -1, 0)

    def F_t(self, q, t, p):
        """Partial derivative dF/dt, shape (n, N)."""
        return self._Ft(*q, t, *p)

    def tangent(self, q, t, p):
        """dq/dt along the solution (t is the input), shape (n, N): solves ``J q' = -F_t``."""
        rhs = -self.F_t(q, t, p).T[..., None]
        return np.linalg.solve(self.J(q, t, p), rhs)[..., 0].T

    @cached_property
    def _second(self):
        """The acceleration right-hand side ``G_q q' + G_t`` (``G = J q' + F_t``) at many points:
        ``f(*q, *dq, t, *p) -> n rows`` ((N,) arrays, or numbers where constant). Derived on
        first use; generated code kept like every kernel's (in memory per shape, on disk)."""
        n = self.n
        dq = [sp.Symbol(f"_numkin_dq{k}") for k in range(n)]
        t = self.input_symbol
        g = self.jacobian_matrix * sp.Matrix(dq) + self.residuals.diff(t)
        h = g.jacobian(self.unknowns) * sp.Matrix(dq) + g.diff(t)
        return _lambdify(tuple(h), (*self.unknowns, *dq, t, *self.parameters), "numpy", True)

    def second_derivative(self, q, dq, t, p):
        """d2q/dt2 along the solution, shape (n, N): solves ``J q'' = -(G_q q' + G_t)`` (dense LU)."""
        N = np.shape(t)[0] if np.ndim(t) else 1
        rhs = -stack_rows(self._second(*q, *dq, t, *p), N).T[..., None]
        return np.linalg.solve(self.J(q, t, p), rhs)[..., 0].T

    def point_function(self, exprs):
        """Compile expressions of (q, t, parameters), e.g. a point's coordinates."""
        return vector_function(exprs, self.args, self.varying)


def acceleration_rhs(compiled: CompiledMechanism, q, dq, t, p) -> list:
    """``G_q q' + G_t`` with ``G = J q' + dF/dt`` at every point, as n rows.

    The acceleration equations are ``J q'' = -(G_q q' + G_t)``. Derived
    once per shape of loop equations with sympy (on first use) and
    generated and kept like every other kernel. Rows are (N,) arrays, or
    numbers where an entry is constant; ``dq`` is ``q'`` (n, N).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> m = linkages.slider_crank(80, 200)
    >>> q = np.array([[np.pi], [280.0]])
    >>> rows = acceleration_rhs(m.compiled, q, np.zeros((2, 1)), np.zeros(1), m.parameter_values)
    >>> [float(np.round(r[0], 9)) for r in rows]   # x'' = -r cos(theta) when q' = 0: [x: -r, y: 0]
    [-80.0, -0.0]
    """
    return list(compiled._second(*q, *dq, t, *p))


def jacobian_rows(compiled: CompiledMechanism, q, t, p):
    """The Jacobian ``dF/dq`` at every point as n*n rows (entry (i, j) is row ``i * n + j``)."""
    n = compiled.n
    return compiled.J(q, t, p).reshape(-1, n * n).T


def rates(compiled: CompiledMechanism, blocks: BlockStructure, q, t, p, jac=None):
    """dq/dt and d2q/dt2 at every point by block-triangular solves: two (n, N) arrays.

    ``J q' = -dF/dt``, then ``J q'' = -(G_q q' + G_t)``, both solved loop by
    loop (:meth:`BlockStructure.solve_negated`): the cost is linear in the
    number of loops and every operation runs on whole arrays. ``jac``: the
    Jacobian rows at ``q`` if known (a sweep keeps its last), else computed.
    Columns where a diagonal block is singular or a value not finite are NaN.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> m = linkages.slider_crank(80, 200)
    >>> s = m.sweep(np.radians([0.0, 90.0]))
    >>> dq, d2q = rates(m.compiled, m.block_structure, s.values, s.inputs, m.parameter_values)
    >>> print(np.round(dq[1], 9) + 0.0, np.round(d2q[1, :1], 9))   # x' = -r at 90 deg; x'' = -r (1 + r/l) at 0
    [  0. -80.] [-112.]
    """
    N = np.size(t)
    with np.errstate(all="ignore"):
        if jac is None:
            jac = jacobian_rows(compiled, q, t, p)
        dq, _ = blocks.solve_negated(jac, compiled.F_t(q, t, p), N)
        d2q, _ = blocks.solve_negated(jac, compiled._second(*q, *dq, t, *p), N)
    return dq, d2q

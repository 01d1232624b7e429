"""Generated code for Jacobians whose loop blocks are of size 1 and 2: every operation written out.

A mechanism's Jacobian is block lower-triangular (:class:`numkin.blocks.BlockStructure`);
where every block is 1 x 1 or 2 x 2, the solves, the Newton iterations and
the one-point quantities of a continuation step are generated once per
mechanism as straight-line Python (plain floats at one point, whole numpy
arrays at many), with the identically zero entries left out.

* :func:`unrolled_solve` -- the forward substitution at one point or on arrays;
* :func:`unrolled_update`, :func:`unrolled_newton` -- one update and the whole
  Newton iteration at one point;
* :func:`unrolled_newton_batch` -- the Newton iteration on whole arrays;
* :func:`unrolled_local` -- at one solved point: tangent, orientations and the
  largest condition number, from one pass over the blocks;
* :func:`scaled_distance`, :func:`scaled_size` -- the largest scaled difference
  of two points, the largest scaled entry of one; :func:`max_lines` -- the
  largest of a few floats written out as comparisons (``max()``'s result, NaN
  included);
* :func:`unrolled_kink` -- whether the tangent turned faster than the march allows;
* :func:`cond2` -- the 2-norm condition number of a 2 x 2 matrix, closed form.

Examples
--------
>>> solve1 = unrolled_solve(2, [(0, 2)])
>>> solve1([2.0, 0.0, 0.0, 4.0], [1.0, 1.0])
([0.5, 0.25], [1.0])
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

__all__ = ["cond2", "step_lines", "scaled_max", "max_lines", "unrolled_update", "unrolled_newton", "unrolled_newton_batch",
           "unrolled_solve", "unrolled_local", "scaled_distance", "scaled_size", "unrolled_kink"]


def cond2(p, q, r, s):
    """2-norm condition number of [[p, q], [r, s]] (closed form; see ``BlockStructure.cond``)."""
    det = p * s - q * r
    if not (det != 0.0 and math.isfinite(det)):
        return math.inf
    fro = p * p + q * q + r * r + s * s
    gap = (p - s) ** 2 + (q + r) ** 2 if det > 0 else (p + s) ** 2 + (q - r) ** 2
    ad = abs(det)
    c = (fro + math.sqrt(gap * (fro + 2.0 * ad))) / (2.0 * ad)
    return c if c >= 1.0 else (1.0 if math.isfinite(c) else math.inf)


def step_lines(n, blocks, zeros, singular, indent="    ", rows=0):
    """Lines computing the Newton step, d = -J^-1 F in ``d0``, ``d1``, ..., from ``v = [F..., J rows...]``
    by forward substitution through the blocks (sizes 1 and 2); ``singular`` is the statement
    run where a block's determinant (``det<k>`` for block k) is zero or not finite, or the step not
    finite. ``singular=None``: whole arrays, no test (the caller tests the result), each 2 x 2 block
    multiplied by ``1 / det``. ``rows``: where in ``v`` the right-hand side F starts (0: the residuals)."""
    lines = []
    for k, (a, b) in enumerate(blocks):
        for i in range(a, b):
            terms = "".join(f" + v[{n + i * n + j}] * d{j}" for j in range(a) if (i, j) not in zeros)
            lines.append(f"r{i} = v[{rows + i}]{terms}")
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
                f"det{k} = a00 * a11 - a01 * a10",
                f"if not (det{k} != 0.0 and -INF < det{k} < INF): {singular}",
                f"d{a} = (a01 * r{a + 1} - r{a} * a11) / det{k}",
                f"d{a + 1} = (a10 * r{a} - a00 * r{a + 1}) / det{k}",
            ]
        elif singular is None:
            lines.append(f"d{a} = -r{a} / v[{n + a * n + a}]")
        else:
            lines += [
                f"det{k} = v[{n + a * n + a}]",
                f"if not (det{k} != 0.0 and -INF < det{k} < INF): {singular}",
                f"d{a} = -r{a} / det{k}",
            ]
    if singular is not None:
        steps = [f"d{i}" for a, b in blocks for i in range(a, b)]
        lines.append(f"if not -INF < {' + '.join(steps)} < INF: {singular}")
    return [indent + line for line in lines]


def scaled_max(names, weights):
    """Source of ``max(|name_i| * weight_i)`` (a weight of one left out)."""
    terms = [f"abs({a})" if w == 1.0 else f"abs({a}) * {w!r}" for a, w in zip(names, weights)]
    return terms[0] if len(terms) == 1 else f"max({', '.join(terms)})"


def max_lines(target, terms, indent):
    """Lines setting ``target`` to ``max(terms)`` (expressions) without the call: the same value as the
    built-in, which keeps the first term unless a later one is larger (a NaN stays where it is first)."""
    lines = [f"{indent}{target} = {terms[0]}"]
    for term in terms[1:]:
        lines += [f"{indent}_next = {term}", f"{indent}if _next > {target}: {target} = _next"]
    return lines


def unrolled_update(n, blocks, zeros, inv_xscale):
    """Generate ``update1(v, x) -> (x_new, step)``: one Newton update at one point, written out.

    ``v`` holds the residuals then the Jacobian rows (from offset n).
    """
    lines = ["def update1(v, x):", *step_lines(n, blocks, zeros, "return None, None")]
    step = scaled_max([f"d{i}" for i in range(n)], inv_xscale)
    lines.append(f"    return [{', '.join(f'x[{i}] + d{i}' for i in range(n))}], {step}")
    namespace = {"INF": math.inf}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers only
    return namespace["update1"]


def unrolled_newton(n, blocks, zeros, inv_xscale, col, only=None):
    """Generate ``newton1(K, x, t, pt, maxiter, fscale, tol, floor, errors, cond_max=None)``:
    Newton-Raphson at one point with every update written out.

    ``only``: the index of one block: Newton on its unknowns alone, every other
    unknown held (its residuals, step and conditioning are that block's).

    ``K(*x, t, *pt)`` is the fused scalar kernel (residuals, Jacobian rows,
    ...), the stopping rule is :func:`numkin.newton_rules.has_converged` written out,
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
    moved = range(n)
    if only is not None:  # the block alone: no coupling to the unknowns before it, which are held
        a0, b0 = blocks[only]
        blocks, moved = [(a0, b0)], range(a0, b0)
        zeros = set(zeros) | {(i, j) for i in moved for j in range(a0)}
    res = [f"abs(v[{i}])" for i in moved]
    steps = [f"abs(d{i})" if inv_xscale[i] == 1.0 else f"abs(d{i}) * {inv_xscale[i]!r}" for i in moved]
    # the conditioning rule on the scaled 2 x 2 blocks (a block of size 1 is refused only where it is
    # exactly singular, by the step itself, as in BlockStructure.cond1)
    # The condition number of a scaled 2 x 2 block is at most its squared Frobenius norm over |det|
    # (sigma1 / sigma2 <= (sigma1^2 + sigma2^2) / (sigma1 sigma2)): where that bound is below half of
    # cond_max the block passes without the closed form (the same decision, rounding included).
    cond_check = []
    for a, b in blocks:
        if b - a != 2:
            continue
        entries = [f"v[{n + a * n + a}] * {col[a]!r}", f"v[{n + a * n + a + 1}] * {col[a + 1]!r}",
                   f"v[{n + (a + 1) * n + a}] * {col[a]!r}", f"v[{n + (a + 1) * n + a + 1}] * {col[a + 1]!r}"]
        cond_check += [
            f"            p, q, r, s = {', '.join(entries)}",
            "            if not p * p + q * q + r * r + s * s <= half * abs(p * s - q * r) and not COND2(p, q, r, s) <= cond_max:",
            "                status = 'singular'",
            "                break",
        ]
    if cond_check:
        cond_check = ["        if cond_max is not None:", *cond_check]
    lines = [
        "def newton1(K, x, t, pt, maxiter, fscale, tol, floor, errors, cond_max=None):",
        "    tol23 = tol ** (2.0 / 3.0)",
        "    half = 0.5 * cond_max if cond_max is not None else 0.0",
        f"    {', '.join(xs)}{',' if n == 1 else ''} = x",
        "    try:",
        f"        v = K({', '.join(xs)}, t, *pt)",
        "    except errors:",
        "        return x, 'diverged', 0, NAN, None, 1",
        "    if not -INF < sum(v) < INF:",
        "        return x, 'diverged', 0, NAN, None, 1",
        *max_lines("res", res, "    "),
        "    res /= fscale",
        "    prev = INF",
        "    it = 0",
        "    status = 'maxiter'",
        "    while it < maxiter:",
        *cond_check,
        *step_lines(n, blocks, zeros, "status = 'converged' if res <= tol and cond_max is None else 'singular'; break",
                     indent="        "),
        *[f"        x{i} += d{i}" for i in moved],
        *max_lines("step", steps, "        "),
        "        it += 1",
        "        try:",
        f"            v = K({', '.join(xs)}, t, *pt)",
        "        except errors:",
        f"            return {xl}, 'diverged', it, NAN, None, it + 1",
        "        if not -INF < sum(v) < INF:",
        f"            return {xl}, 'diverged', it, NAN, None, it + 1",
        *max_lines("res", res, "        "),
        "        res /= fscale",
        "        if res <= tol:",  # numkin.newton_rules.has_converged at one point
        "            if step <= tol or (step <= tol23 and step <= 0.25 * prev) or step >= 0.9 * prev:",
        "                status = 'converged'",
        "                break",
        f"        elif step >= 0.9 * prev and res <= floor({xl}, t):",
        "            status = 'converged'",
        "            break",
        "        prev = step",
        f"    return {xl}, status, it, res, v, it + 1",
    ]
    namespace = {"INF": math.inf, "NAN": math.nan, "COND2": cond2}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace["newton1"]


def unrolled_newton_batch(n, blocks, zeros, inv_xscale):
    """Generate ``newton_batch(K, x, t, kargs, active, maxiter, fscale, tol, floor, converged)``:
    Newton-Raphson on whole arrays with every update written out.

    The iteration of ``numkin.newton.solve_batch`` without compaction and
    without histories: ``K(*x, t, *kargs)`` is the fused kernel (residual
    rows, then Jacobian rows), ``x`` (n, N) is iterated in place,
    ``converged`` the stopping rule (:func:`numkin.newton_rules.has_converged`,
    called with the columns just moved as ``where``). Every column is
    computed at every iteration (the inactive ones are not moved): below
    ``COMPACT_MIN`` columns every array operation costs about the same
    whatever its width, so gathering the last active columns would cost
    what it saves.

    Returns ``(converged, singular, iterations, rows, evaluations)``,
    ``rows`` the kernel's rows at the returned ``x`` and ``evaluations``
    the kernel's calls; or None, before any step, if a residual row is not
    an (N,) array (a constant residual: the caller's general loop takes it).
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
        f"    if not ({' and '.join(f'type(v[{i}]) is NDARRAY and v[{i}].shape == (N,)' for i in range(n))}):",
        "        return None",
        "    evaluations = 1",
        f"    fmax = {fmax}",
        "    done_all = ZEROS(N, dtype=bool)",
        "    singular = ZEROS(N, dtype=bool)",
        "    iterations = ZEROS(N, dtype=int)",
        "    act = active & ISFINITE(fmax)",
        "    prev = FULL(N, INF)",
        "    for _ in range(maxiter):",
        "        left = COUNT(act)",
        "        if not left:",
        "            break",
        *step_lines(n, blocks, zeros, None, indent="        "),
        f"        finite = ISFINITE({' + '.join(f'd{i}' for i in range(n))})",
        "        upd = act & finite",
        "        moved = COUNT(upd)",
        "        if moved != left:  # a singular or non-finite step: refused, the column not moved",
        "            bad = act & ~finite",
        "            singular |= bad",
        "            act &= ~bad",
        "        if COUNT(finite) == N:  # every step finite: the others times zero (x + 0 is x)",
        *[f"            ADD(x{i}, d{i} * upd, out=x{i})" for i in range(n)],
        "        else:",
        *[f"            ADD(x{i}, d{i}, out=x{i}, where=upd)" for i in range(n)],
        f"        step = {step}",
        f"        del {temporaries}  # freed before the next evaluation: one set of rows alive at a time",
        f"        v = {call}",
        "        evaluations += 1",
        f"        fmax = {fmax}",
        "        iterations += upd",
        "        done = converged(fmax / fscale if fscale != 1.0 else fmax, step, prev, tol, floor, upd)",
        "        done_all |= done",
        "        act &= ~done",
        "        act &= ISFINITE(fmax)",
        "        prev = step  # read only where a column goes on, that is, was moved",
        "    return done_all, singular, iterations, v, evaluations",
    ]
    namespace = {"INF": math.inf, "ABS": np.abs, "MAX": np.maximum, "ADD": np.add, "ISFINITE": np.isfinite,
                 "WHERE": np.where, "ZEROS": np.zeros, "FULL": np.full, "NDARRAY": np.ndarray,
                 "COUNT": np.count_nonzero}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace["newton_batch"]


def unrolled_solve(n, blocks, zeros=frozenset(), batch=False):
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


def unrolled_local(n, blocks, zeros, col):
    """Generate ``local1(v) -> (tangent, orientations, cond)`` at one solved point, written out.

    ``v`` holds the residuals, the Jacobian rows (from offset n) and dF/dt
    (from offset n + n*n). The tangent solves ``J d = -dF/dt`` block by
    block, the orientations are the signs of the blocks' determinants, and
    ``cond`` is the largest condition number of the scaled blocks (``col``:
    the unknowns' scales over the residuals'; a block of size one counts 1,
    or inf where it is zero). Tangent and orientations are None where a
    block is singular or the tangent not finite; ``cond`` is always given.
    The same numbers as ``BlockStructure.solve1`` and ``BlockStructure.cond1``.

    Examples
    --------
    >>> local1 = unrolled_local(2, [(0, 2)], set(), [1.0, 1.0])
    >>> d, o, c = local1([0.0, 0.0, 2.0, 0.0, 0.0, 4.0, -1.0, -1.0])
    >>> d, o, round(c, 12)
    ([0.5, 0.25], [1.0], 2.0)
    """
    nn = n * n
    lines = ["def local1(v):"]
    conds = []
    for k, (a, b) in enumerate(blocks):
        if b - a == 2:
            i0 = n + a * n + a
            ca, cb = col[a], col[a + 1]
            lines.append(f"    c{k} = COND2(v[{i0}] * {ca!r}, v[{i0 + 1}] * {cb!r}, v[{i0 + n}] * {ca!r}, "
                         f"v[{i0 + n + 1}] * {cb!r})")
        else:
            j = f"v[{n + a * n + a}]"
            lines.append(f"    c{k} = 1.0 if ({j} != 0.0 and -INF < {j} < INF) else INF")
        conds.append(f"c{k}")
    cmax = conds[0] if len(conds) == 1 else f"max({', '.join(conds)})"
    lines.append(f"    cmax = {cmax}")
    # the tangent is the Newton step of dF/dt: -J^-1 dF/dt, the same floats as solve1(J, -dF/dt)
    lines += step_lines(n, blocks, zeros, "return None, None, cmax", rows=n + nn)
    signs = ", ".join(f"(1.0 if det{k} > 0 else -1.0)" for k in range(len(blocks)))
    lines.append(f"    return [{', '.join(f'd{i}' for i in range(n))}], [{signs}], cmax")
    namespace = {"INF": math.inf, "COND2": cond2}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace["local1"]


@lru_cache(maxsize=64)
def scaled_distance(n, weights):
    """Generate ``distance(a, b) -> max |a_i - b_i| w_i`` for ``n`` values, written out.

    ``weights`` is a tuple; the function is generated once per argument
    pair. A weight of one is left out, so the result is the same float as the
    list form ``max([abs(a - b) * w for ...])``.

    Examples
    --------
    >>> scaled_distance(2, (1.0, 0.5))([1.0, 4.0], [0.0, 1.0])
    1.5
    """
    return _largest_scaled("distance(a, b)", [f"a[{i}] - b[{i}]" for i in range(n)], weights)


@lru_cache(maxsize=64)
def scaled_size(n, weights):
    """Generate ``size(a) -> max |a_i| w_i`` for ``n`` values, written out (the same float as
    ``max([abs(x) * w for ...])``, a weight of one left out).

    Examples
    --------
    >>> scaled_size(2, (1.0, 0.5))([-1.0, 4.0])
    2.0
    """
    return _largest_scaled("size(a)", [f"a[{i}]" for i in range(n)], weights)


def _largest_scaled(signature, values, weights):
    """Generate ``def <signature>`` returning ``max |value_i| w_i`` written out (a weight of one left out)."""
    terms = [f"abs({v})" + ("" if w == 1.0 else f" * {w!r}") for v, w in zip(values, weights)]
    lines = [f"def {signature}:", *max_lines("out", terms, "    "), "    return out"]
    namespace = {}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace[signature.split("(")[0]]


@lru_cache(maxsize=64)
def unrolled_kink(n, weights, turn, reach):
    """Generate ``kinked(t, d, t_prev, d_prev, t_new, d_new, rate) -> bool`` for ``n`` unknowns, written out:
    whether the tangent ``d_new`` at ``t_new`` differs from the one expected by more than ``turn`` (1 +
    ``rate``), scaled by ``weights`` (a tuple).

    The tangent expected is ``d`` extrapolated linearly through ``d_prev`` (the tangent at ``t_prev``)
    when ``t_prev`` is at most ``reach`` steps back, else ``d`` (the march's test of a tangent that turned
    too fast, :data:`numkin.march.MAX_TANGENT_TURN` and :data:`numkin.march.TREND_REACH`).

    Examples
    --------
    >>> kinked = unrolled_kink(1, (1.0,), 0.5, 2.0)
    >>> kinked(1.0, [1.0], 0.0, [0.0], 2.0, [2.0], 1.0), kinked(1.0, [1.0], 0.0, [0.0], 2.0, [3.5], 1.0)
    (False, True)
    """
    diffs = [f"abs(d_new[{i}] - e{i})" + ("" if weights[i] == 1.0 else f" * {weights[i]!r}") for i in range(n)]
    lines = [
        "def kinked(t, d, t_prev, d_prev, t_new, d_new, rate):",
        "    if d_new is None:",
        "        return False",
        f"    {', '.join(f'e{i}' for i in range(n))}{',' if n == 1 else ''} = d",
        "    if d_prev is not None and t_prev is not None:",
        "        r = (t_new - t) / (t - t_prev)",
        f"        if 0.0 < r <= {reach!r}:",
        *[f"            e{i} = e{i} + (e{i} - d_prev[{i}]) * r" for i in range(n)],
        *max_lines("out", diffs, "    "),
        f"    return out > {turn!r} * (1.0 + rate)",
    ]
    namespace = {}
    exec("\n".join(lines), namespace)  # noqa: S102 - generated from integers and floats only
    return namespace["kinked"]

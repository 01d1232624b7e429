"""One generated function for the exact rates: dq/dt and d2q/dt2 at many points in one call.

The velocity and acceleration equations of a mechanism share their matrix,
the Jacobian ``J``, and most of their trigonometry::

    J q'  = -F_t                                     (velocity)
    J q'' = -(G_q q' + G_t),   G = J q' + F_t        (acceleration)

:func:`rates_source` writes both solves as one Python function of whole
numpy arrays:

* the right-hand sides are derived with sympy and their common
  subexpressions eliminated together, so a term of the input alone
  (``sin(theta)``) is computed once for both;
* a term of the right-hand sides that equals an entry of the Jacobian (up
  to sign) is read from the Jacobian rows the caller passes (a sweep keeps
  them) instead of being computed again: for vector loops the second
  derivatives of ``r cos(phi)`` and ``r sin(phi)`` are entries of ``J``, so
  no sine or cosine of an unknown is evaluated;
* the forward substitution through the loops (blocks of size 1 and 2, by
  Cramer's rule, as :class:`numkin.blocks.BlockStructure` does it) is
  written out once, and each block's inverse determinant serves both
  right-hand sides;
* sums of several terms and the solutions are computed in place (into one
  new array, or into ``dq`` and ``d2q``), with the rounding of the plain
  expressions: fewer temporaries, which counts for long sweeps.

The function is ``rates(J, q, t, p, dq, d2q)``: ``J`` the n*n Jacobian rows
(entry (i, j) is row ``i * n + j``; (N,) arrays or numbers), ``q`` (n, N),
``t`` (N,), ``p`` the parameter values; it writes ``dq`` and ``d2q`` (both
(n, N), float) and returns nothing. It does not test its results: a singular
block gives inf or NaN, which the caller masks. Its code uses only numpy's
functions, so the kernel cache (:mod:`numkin.kernel_cache`) keeps it.

Examples
--------
>>> import numpy as np, sympy as sp
>>> from numkin.kernel_cache import kernel_from_source
>>> t, x = sp.symbols("t x")
>>> rates = kernel_from_source(rates_source([x - sp.cos(t)], [x], t, [], [(0, 1)]), RATES_NARGS)
>>> dq, d2q = np.empty((1, 1)), np.empty((1, 1))
>>> rates([1.0], np.zeros((1, 1)), np.array([0.5]), [], dq, d2q)
>>> bool(np.isclose(dq[0, 0], -np.sin(0.5))), bool(np.isclose(d2q[0, 0], -np.cos(0.5)))
(True, True)
"""

from __future__ import annotations

from collections import Counter

__all__ = ["rates_source", "RATES_NARGS"]

#: Number of arguments of the generated function: ``(J, q, t, p, dq, d2q)``.
RATES_NARGS = 6


def _printer():
    from sympy.printing.numpy import NumPyPrinter

    return NumPyPrinter({"fully_qualified_modules": False, "inline": True, "allow_unknown_functions": True,
                         "user_functions": {}})


def _right_hand_sides(residuals, unknowns, input_symbol, dq):
    """``J``, ``F_t`` and ``G_q q' + G_t`` (``G = J q' + F_t``) for the unknowns' derivatives ``dq``."""
    import sympy as sp

    F = sp.Matrix(list(residuals))
    jac = F.jacobian(list(unknowns))
    ft = F.diff(input_symbol)
    g = jac * sp.Matrix(dq) + ft
    h = g.jacobian(list(unknowns)) * sp.Matrix(dq) + g.diff(input_symbol)
    return jac, list(ft), list(h)


def rates_source(residuals, unknowns, input_symbol, parameters, blocks, name: str = "rates") -> str | None:
    """Source of ``name(J, q, t, p, dq, d2q)``, the rates of the loop equations ``residuals = 0``.

    Parameters
    ----------
    residuals : sequence of sympy expressions
        The stacked loop equations, loops in solving order.
    unknowns : sequence of sympy symbols
    input_symbol : sympy symbol
    parameters : sequence of sympy symbols
        In the order of the values ``p`` the function is called with.
    blocks : sequence of (start, stop)
        The unknowns of each loop: the diagonal blocks of the block
        lower-triangular Jacobian.

    Returns
    -------
    str or None
        The function's code, or None where a block is larger than 2 x 2 or
        the blocks do not cover the unknowns in order (then the caller solves
        with :class:`numkin.blocks.BlockStructure`).
    """
    import sympy as sp

    n = len(unknowns)
    blocks = [(int(a), int(b)) for a, b in blocks]
    if [a for a, _ in blocks] != [0] + [b for _, b in blocks[:-1]] or not blocks or blocks[-1][1] != n:
        return None
    if any(not 1 <= b - a <= 2 for a, b in blocks):
        return None
    # plain names for the code: q<i>, t, p<k>, w<i> (= dq), J<k>, x<k> (common subexpressions)
    qs = [sp.Symbol(f"q{i}", **u.assumptions0) for i, u in enumerate(unknowns)]
    ts = sp.Symbol("t", **input_symbol.assumptions0)
    ps = [sp.Symbol(f"p{k}", **s.assumptions0) for k, s in enumerate(parameters)]
    ws = [sp.Symbol(f"w{i}", real=True) for i in range(n)]
    rename = {**dict(zip(unknowns, qs)), input_symbol: ts, **dict(zip(parameters, ps))}
    # derived in the mechanism's own symbols (sympy's cache holds their first derivatives), then renamed
    jac, ft, h = _right_hand_sides([sp.sympify(r) for r in residuals], unknowns, input_symbol, ws)
    jac, ft, h = jac.xreplace(rename), [e.xreplace(rename) for e in ft], [e.xreplace(rename) for e in h]
    varying = set(qs) | {ts}
    entries = ([], [])  # varying Jacobian entries: (terms, symbol) of sums; (factors, coefficient, symbol) of products
    for k, e in enumerate(jac):
        if e.free_symbols & varying and not e.is_Symbol:
            symbol = sp.Symbol(f"J{k}", real=True)
            if e.is_Add:
                entries[0].append((e.args, symbol))
            else:
                coeff, factors = e.as_coeff_mul()
                if len(factors) > 1 or not factors[0].is_Symbol:  # (reading -x from J saves nothing)
                    entries[1].append((Counter(factors), coeff, symbol))
    entries[0].sort(key=lambda entry: -len(entry[0]))  # the largest first
    entries[1].sort(key=lambda entry: -sum(entry[0].values()))
    ft = [_read_entries(e, *entries) for e in ft]
    h = [_read_entries(e, *entries) for e in h]
    replacements, reduced = sp.cse(ft + h, symbols=sp.numbered_symbols("x"))
    after_first = set(ws)  # what depends on dq: computed after the first solve
    before, after = [], []
    for sym, e in replacements:
        if e.free_symbols & after_first:
            after_first.add(sym)
            after.append((sym, e))
        else:
            before.append((sym, e))
    zeros = {(i, j) for i in range(n) for j in range(n) if jac[i, j] == 0}
    constant = {(i, j) for i in range(n) for j in range(n) if not jac[i, j].free_symbols & varying}
    # symbols holding arrays (the others hold numbers): what varies, and the terms computed from it
    arrays = varying | set(ws) | {entry[-1] for entry in entries[0] + entries[1]}
    pr = _printer()
    body = []
    for sym, e in before:
        body += _assign(pr, sym, e, arrays)
    body += [f"f{i} = {pr.doprint(reduced[i])}" for i in range(n)]
    body += _solve_lines(n, blocks, zeros, constant, "f", "w", "dq", True, {i for i in range(n) if reduced[i] == 0})
    for sym, e in after:
        body += _assign(pr, sym, e, arrays)
    for i in range(n):
        body += _assign(pr, sp.Symbol(f"h{i}"), reduced[n + i], arrays)
    body += _solve_lines(n, blocks, zeros, constant, "h", "v", "d2q", False,
                         {i for i in range(n) if reduced[n + i] == 0})
    code = "\n".join(body)
    used = set(_names(code))
    head = [f"q{i} = q[{i}]" for i in range(n) if f"q{i}" in used]
    head += [f"p{k} = p[{k}]" for k in range(len(parameters)) if f"p{k}" in used]
    head += [f"J{k} = J[{k}]" for k in range(n * n) if f"J{k}" in used]
    return "\n".join([f"def {name}(J, q, t, p, dq, d2q):", *("    " + line for line in head + body), "    return None", ""])


def _read_entries(expr, sums, products):
    """``expr`` with each product that contains the factors of a Jacobian entry, and each sum that
    contains the terms of one (or their negatives), written with the entry's symbol instead
    (``r3 w0**2 cos(q0)`` is ``J2 w0**2`` where ``J2 = r3 cos(q0)``): exact, and those terms are
    then read from the Jacobian rows rather than computed. ``sums`` and ``products`` as
    :func:`rates_source` lists them."""
    import sympy as sp

    if expr.is_Add:
        terms = list(expr.args)
        found = []
        for core, symbol in sums:
            for sign in (1, -1):
                signed = [sign * term for term in core]
                while all(term in terms for term in signed):
                    for term in signed:
                        terms.remove(term)
                    found.append(sign * symbol)
        return sp.Add(*found, *[_read_entries(term, sums, products) for term in terms])
    coeff, factors = expr.as_coeff_mul()
    have = Counter(_read_entries(f, sums, products) if f.is_Add else f for f in factors)
    found = []
    for core, c, symbol in products:
        while all(have[f] >= m for f, m in core.items()):
            have -= core
            coeff = coeff / c
            found.append(symbol)
    if not found and have == Counter(factors):
        return expr
    return sp.Mul(coeff, *found, *have.elements())


def _assign(pr, sym, expr, arrays: set) -> list:
    """Lines setting the variable ``sym`` to ``expr``; ``arrays``: the symbols holding arrays (``sym``
    joins them if ``expr`` involves one).

    A sum of three or more terms that involves an array is accumulated in
    place in one new array (no temporary per term): the first two terms
    make it, the others are added to it, in the printed order. Negation is
    exact and rounding to nearest symmetric, so terms taken with the
    opposite sign, and a sum negated at the end, round as the printed
    expression does.
    """
    import sympy as sp

    name = str(sym)
    if not expr.free_symbols & arrays:
        return [f"{name} = {pr.doprint(expr)}"]
    arrays.add(sym)
    if not isinstance(expr, sp.Add) or len(expr.args) < 3:
        return [f"{name} = {pr.doprint(expr)}"]
    terms = [(-1, -t) if t.could_extract_minus_sign() else (1, t) for t in expr.as_ordered_terms()]
    (s0, m0), (s1, m1) = terms[:2]
    if s0 == s1:
        lines = [f"{name} = {pr.doprint(m0)} + {pr.doprint(m1)}"]
    elif s0 > 0:
        lines = [f"{name} = {pr.doprint(m0)} - {pr.doprint(m1)}"]
    else:
        lines = [f"{name} = {pr.doprint(m1)} - {pr.doprint(m0)}"]
    negated = s0 < 0 and s1 < 0  # the variable holds minus the partial sum
    for sign, m in terms[2:]:
        lines.append(f"{name} {'+' if (sign > 0) != negated else '-'}= {pr.doprint(m)}")
    if negated:
        lines.append(f"negative({name}, out={name})")
    return lines


def _names(code: str):
    import ast

    return (node.id for node in ast.walk(ast.parse(code)) if isinstance(node, ast.Name))


def _solve_lines(n, blocks, zeros, constant, rhs, sol, out, first, zero_rows):
    """Forward substitution ``J sol = -rhs`` block by block, each solution written into a row of ``out``.

    The operations are those of :meth:`numkin.blocks.BlockStructure.solve_negated`
    (the same rounding), done in place where the values are arrays; the first
    solve computes each 2 x 2 block's ``inv<k> = -1 / det`` and the second
    reuses it. Rows of ``rhs`` in ``zero_rows`` are identically zero (left
    out); entries in ``zeros`` are zero and those in ``constant`` numbers.
    """
    lines = []
    for k, (a, b) in enumerate(blocks):
        for i in range(a, b):
            terms = [f"J[{i * n + j}] * {sol}{j}" for j in range(a) if (i, j) not in zeros]
            if not terms:  # (sums are commutative: f + J w is J w + f to the last bit)
                lines.append(f"r{i} = {rhs}{i}")
                continue
            lines.append(f"r{i} = {terms[0]}")
            if i not in zero_rows:
                lines.append(f"r{i} += {rhs}{i}")
            lines += [f"r{i} += {term}" for term in terms[1:]]
        if b - a == 2:
            i0 = a * n + a
            if first:
                lines.append(f"a{k}, b{k}, c{k}, d{k} = J[{i0}], J[{i0 + 1}], J[{i0 + n}], J[{i0 + n + 1}]")
                if {(a, a), (a + 1, a + 1)} <= constant and {(a, a + 1), (a + 1, a)} <= constant:
                    lines.append(f"inv{k} = -1.0 / (a{k} * d{k} - b{k} * c{k})")
                else:
                    lines += [f"inv{k} = a{k} * d{k}", f"inv{k} -= b{k} * c{k}", f"divide(-1.0, inv{k}, out=inv{k})"]
            lines += [
                f"{sol}{a} = multiply(r{a}, d{k}, out={out}[{a}])",
                f"{sol}{a} -= b{k} * r{a + 1}",
                f"{sol}{a} *= inv{k}",
                f"{sol}{a + 1} = multiply(a{k}, r{a + 1}, out={out}[{a + 1}])",
                f"{sol}{a + 1} -= c{k} * r{a}",
                f"{sol}{a + 1} *= inv{k}",
            ]
        else:
            if first:
                lines.append(f"a{k} = J[{a * n + a}]")
            lines += [f"{sol}{a} = divide(r{a}, a{k}, out={out}[{a}])", f"negative({sol}{a}, out={sol}{a})"]
    return lines

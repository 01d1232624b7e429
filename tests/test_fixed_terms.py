"""The batch residual-and-Jacobian rows with the input's terms formed once agree with the plain kernels."""

import numpy as np
import pytest
import sympy as sp

from numkin import linkages
from numkin.compiled import hoist_fixed_terms

MECHANISMS = {
    "four_bar": lambda: linkages.four_bar(4, 1, 3, 3),
    "slider_crank": lambda: linkages.slider_crank(80, 200, 20),
    "chained_four_bars": linkages.chained_four_bars,
}


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_rows_equal_residuals_and_jacobian(name):
    mech = MECHANISMS[name]()
    comp, p = mech.compiled, mech.parameter_values
    rng = np.random.default_rng(7)
    n, N = len(mech.unknowns), 50
    q = rng.uniform(-4.0, 4.0, (n, N))
    t = rng.uniform(-4.0, 4.0, N)
    rows = [np.broadcast_to(r, (N,)) for r in comp.FJ_rows(q, t, p)]
    f, jac = np.array(rows[:n]), np.array(rows[n:]).reshape(n, n, N)
    scale = 10.0 * max(1.0, float(np.max(p)))
    np.testing.assert_allclose(f, comp.F(q, t, p), rtol=0, atol=1e-14 * scale)
    np.testing.assert_allclose(np.moveaxis(jac, -1, 0), comp.J(q, t, p), rtol=0, atol=1e-14 * scale)


def test_sums_of_the_input_alone_are_gathered():
    t, a, b, r1, r2, c = sp.symbols("t a b r1 r2 c")
    exprs = [r2 * sp.cos(t) + c * sp.cos(a) - r1, r2 * sp.sin(t) * sp.sin(b), r1 - c + sp.sin(b), r2 * sp.sin(t)]
    new, names, fixed = hoist_fixed_terms(exprs, [a, b], [t])
    # every expression, with the symbols put back, is the one it replaces
    back = dict(zip(names, fixed))
    assert all(sp.simplify(e.xreplace(back) - old) == 0 for e, old in zip(new, exprs))
    assert r2 * sp.cos(t) - r1 in fixed            # a sum of the input's terms
    assert new[2] == r1 - c + sp.sin(b)              # parameters alone: left as they are
    assert new[3] in names                           # a whole expression of the input
    assert not (new[0].free_symbols & {t})           # no term of the input left in the first residual

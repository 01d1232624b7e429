"""Sympy expressions compiled once into vectorised numpy functions.

Everything symbolic about a mechanism happens here, once, when it is built;
nothing symbolic runs inside a loop over input angles. The compiled functions
take whole numpy arrays (real or complex, for complex-step differentiation)
and return stacked arrays.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np
import sympy as sp

__all__ = ["vector_function", "CompiledMechanism"]


def vector_function(exprs, args, varying=None):
    """Lambdify a list of expressions into ``f(*args) -> ndarray of shape (len(exprs), ...)``.

    ``varying`` are the arguments passed as arrays (default: all); entries
    that depend on none of them (a zero in a Jacobian, a parameter) are
    broadcast to the arrays' shape, so the result is always one stacked
    array. Its dtype follows the arguments (complex in, complex out).
    """
    exprs = [sp.sympify(e) for e in exprs]
    varying = set(args if varying is None else varying)
    moving = [k for k, e in enumerate(exprs) if e.free_symbols & varying]
    fixed = [k for k in range(len(exprs)) if k not in set(moving)]
    f_moving = sp.lambdify(args, [exprs[k] for k in moving], modules="numpy", cse=True) if moving else None
    f_fixed = sp.lambdify(args, [exprs[k] for k in fixed], modules="numpy") if fixed else None
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
        """``d/dt (J q' + F_t)`` with ``q'' = 0``: the right-hand side of the acceleration equations."""
        dq = [sp.Dummy(f"d{u}") for u in self.unknowns]
        g = self.jacobian_matrix * sp.Matrix(dq) + self.residuals.diff(self.input_symbol)
        h = g.jacobian(self.unknowns) * sp.Matrix(dq) + g.diff(self.input_symbol)
        return vector_function(
            list(h), [*self.unknowns, *dq, self.input_symbol, *self.parameters], [*self.varying, *dq]
        )

    def second_derivative(self, q, dq, t, p):
        """d2q/dt2 along the solution, shape (n, N): solves ``J q'' = -(G_q q' + G_t)``."""
        rhs = -self._second(*q, *dq, t, *p).T[..., None]
        return np.linalg.solve(self.J(q, t, p), rhs)[..., 0].T

    def point_function(self, exprs):
        """Compile expressions of (q, t, parameters), e.g. a point's coordinates."""
        return vector_function(exprs, self.args, self.varying)

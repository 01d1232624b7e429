"""Checks of homework 5 (quadrature and an ODE), shipped next to the kincheck package.

Like kincheck, it holds no answers: the hidden tests pass in the reference values.
"""

from __future__ import annotations

import numpy as np

import kincheck as kc

__all__ = ["quadrature_rule", "initial_state", "state"]


def _not_set(x) -> bool:
    return x is None or x is Ellipsis


def quadrature_rule(rule, *, n: int, cases) -> None:
    """Check ``rule(f, n)`` on ``(f, degree, exact)`` cases a correct rule integrates exactly."""
    if _not_set(rule) or not callable(rule):
        raise AssertionError("`gauss_chebyshev` is not defined yet: run the cell that defines it")
    for f, degree, exact in cases:
        try:
            value = rule(f, n)
        except Exception as error:  # the student's function failed: say how, without a traceback
            raise AssertionError(f"`gauss_chebyshev(f, {n})` raised {type(error).__name__}: {error}") from None
        value = kc.returned(value, "gauss_chebyshev", f"gauss_chebyshev(f, {n})")
        try:
            got = float(value)
        except (TypeError, ValueError):
            raise AssertionError(f"`gauss_chebyshev(f, {n})` should return a number, got {type(value).__name__}") from None
        if abs(got - exact) <= 1e-12 * max(1.0, abs(exact)):
            continue
        message = (
            f"`gauss_chebyshev` with n = {n} gives {got:.12g} for f(t) = t^{degree}, expected "
            f"{exact:.12g}: the rule with n + 1 nodes is exact for polynomials up to degree {2 * n + 1}"
        )
        if degree == 0:
            ratio = got / exact
            if abs(ratio - n / (n + 1)) < 1e-9:
                message += ". It returns n/(n + 1) of π: the weights π/(n + 1) are summed over n nodes, not n + 1"
            elif abs(ratio - (n + 1) / n) < 1e-9 or abs(ratio - (n + 2) / (n + 1)) < 1e-9:
                message += ". The weights do not add up to π: the weight is π/(number of nodes)"
        raise AssertionError(message)


def _states(x, name: str, rows: int | None = None) -> np.ndarray:
    values = kc.floats(x, name)
    if values.ndim != 2 or (rows is not None and values.shape[0] != rows):
        want = f"{rows} rows" if rows is not None else "one row per time"
        raise AssertionError(f"`{name}` should have {want}, one state per row; got shape {np.shape(x)}")
    return values


def initial_state(name: str, x, want, *, rows: int, names) -> None:
    """The first row of a solution ``x`` is the initial state ``want``; a unit slip is named."""
    values = _states(x, name, rows)
    if values.shape[1] != len(want):
        raise AssertionError(f"`{name}` should have {len(want)} columns ({', '.join(names)}); got {values.shape[1]}")
    for j, (got, ref) in enumerate(zip(values[0], want)):
        if abs(got - ref) <= 1e-12 * max(1.0, abs(ref)):
            continue
        hint = kc.explain_factor(got / ref, ("deg", "mm")) if ref else None
        raise AssertionError(
            f"`{name}[0]` has {names[j]} = {got:.6g} at t = 0, expected {ref:.6g}"
            + (f": {hint}" if hint else "")
        )


def state(name: str, x, row: int, want, *, time: str, rtol: float) -> None:
    """Row ``row`` of a solution ``x`` matches the state ``want`` (each within rtol of the largest)."""
    values = _states(x, name)
    if values.shape[0] <= row or values.shape[1] != len(want):
        raise AssertionError(f"`{name}` has shape {values.shape}; row {row} ({time}) of {len(want)} values is asked")
    got, ref = values[row], np.asarray(want, dtype=float)
    scale = np.max(np.abs(ref))
    worst = int(np.argmax(np.abs(got - ref)))
    if np.abs(got - ref)[worst] <= rtol * scale:
        return
    if not np.all(np.isfinite(got)):
        raise AssertionError(f"`{name}` is not finite at {time}")
    raise AssertionError(
        f"`{name}` at {time}: component {worst} is {got[worst]:.10g}, expected {ref[worst]:.10g} "
        f"(within {rtol:g} of the state's size {scale:.3g}); the state has drifted from the reference"
    )

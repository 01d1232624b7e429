"""The first point of a sweep: Newton from the guess loop by loop, on the guess's turn, polished; and why it fails.

A singular Jacobian met on the way is told apart: dependent loop equations
(singular wherever tried), a poor guess (singular far from any solution),
or a singular position of the linkage at the input itself. A guess angle
more than a turn from zero was most likely given in degrees: a failure
names every such angle (:func:`degrees_hint`), and so does the
:class:`~numkin.errors.GuessWarning` of a first point far from such a guess
and the :class:`~numkin.errors.ConvergenceWarning` of a
:meth:`~numkin.Mechanism.solve` that did not converge (:func:`unsolved`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from .errors import AssemblyError, BranchError, ConvergenceWarning, GuessWarning, InputError, warn
from .march import FAR, TWO_PI, Continuation
from .newton import COND_MAX, is_singular
from .units import deg_text, number_array

__all__ = ["solve_start", "loop_by_loop", "guess_vector", "far_guesses", "still_far", "degrees_hint", "unsolved",
           "never_closes"]


def far_guesses(mech, guess) -> list:
    """``(name, value)`` of every angle of ``guess`` (in unknown order, rad) more than a turn from zero.

    Such a guess was most likely given in degrees.

    Examples
    --------
    >>> from numkin import linkages
    >>> far_guesses(linkages.four_bar(4, 1, 3, 3), [60.0, 2.0])
    [('theta3', 60.0)]
    """
    return [(u, float(g)) for u, g in zip(mech.unknowns, guess) if u in mech.angles and abs(g) > TWO_PI]


def still_far(mech, far, x) -> list:
    """The entries ``(name, guess)`` of ``far`` (:func:`far_guesses`) whose solution in ``x`` is more than
    1 rad from the guess: what a guess in degrees, which Newton still solved, is warned of.

    Examples
    --------
    >>> from numkin import linkages
    >>> still_far(linkages.four_bar(4, 1, 3, 3), [("theta3", 60.0)], [0.5, 2.0])
    [('theta3', 60.0)]
    """
    return [(name, value) for name, value in far if abs(x[mech.unknowns.index(name)] - value) > 1.0]


def degrees_hint(far) -> str:
    """Why ``far`` (:func:`far_guesses`) looks wrong, naming every such angle; ``""`` if there is none.

    Examples
    --------
    >>> degrees_hint([("phi", 45.0), ("psi", 60.0)])
    'the guess phi = 45, psi = 60 is more than a turn from zero: angles are in rad (was it given in degrees?)'
    """
    if not far:
        return ""
    values = ", ".join(f"{name} = {value:g}" for name, value in far)
    return f"the guess {values} is more than a turn from zero: angles are in rad (was it given in degrees?)"


def _hinted(error, far):
    """``error`` with the degrees hint of ``far`` added to its message (and kept as ``far_guess``)."""
    if far:
        error.args = (f"{error.args[0]}; {degrees_hint(far)}",)
    error.far_guess = far
    return error


def unsolved(mech, input_value: float, guess, out, cond: float):
    """The :class:`~numkin.NewtonResult` of a :meth:`Mechanism.solve` that did not converge, and a warning.

    The message and the :class:`~numkin.errors.ConvergenceWarning` name the
    input angle, the loop with the largest residual and that residual, a
    singular Jacobian if Newton met one, and every guess angle more than a
    turn from zero (:func:`degrees_hint`).
    """
    from .newton import NewtonResult

    t = np.array([input_value])
    it = int(out.iterations[0])
    residuals = mech.loop_residuals(out.x, t)
    loop = max(residuals, key=lambda k: np.nan_to_num(residuals[k][0], nan=np.inf))
    why = f"loop '{loop}' residual {float(residuals[loop][0]):.3g} after {it} iterations"
    if out.singular[0]:
        conds = mech.loop_conditions(out.x, t)
        worst = max(conds, key=lambda k: np.nan_to_num(conds[k][0], nan=np.inf))
        why += f" (singular Jacobian of loop '{worst}', condition number {cond:.3g}: not divided through)"
    hint = degrees_hint(far_guesses(mech, guess))
    warn(
        f"{mech.name}: Newton did not converge at input {deg_text(input_value, 3)}: {why}; the result is not a "
        f"position (converged=False)" + (f"; {hint}" if hint else ""), ConvergenceWarning,
    )
    return NewtonResult.from_batch(out, 0, cond, f"did not converge: {why}")


def guess_vector(mech, guess, at: float) -> np.ndarray:
    """A mechanism's guess as a vector in unknown order; ``guess`` may be a mapping, sequence or callable
    (called with the input ``at``, rad).

    Examples
    --------
    >>> from numkin import linkages
    >>> guess_vector(linkages.four_bar(4, 1, 3, 3), {"theta4": 2.0, "theta3": 0.5}, 0.0).tolist()
    [0.5, 2.0]
    """
    if guess is None:
        raise InputError(
            f"{mech.name}: no guess given and the mechanism has no default; pass guess= "
            f"with values for {list(mech.unknowns)}"
        )
    if callable(guess):
        guess = guess(at)
    if isinstance(guess, Mapping):
        values = {str(k): v for k, v in guess.items()}
        if values.keys() != set(mech.unknowns):
            unknown = sorted(set(values) - set(mech.unknowns))
            if unknown:
                raise InputError(f"guess names {unknown}, which are not unknowns of {mech.name} {list(mech.unknowns)}")
            raise InputError(f"guess lacks values for {[u for u in mech.unknowns if u not in values]}")
        vec = [values[u] for u in mech.unknowns]
    else:
        vec = guess
    vec = number_array(vec, lambda: f"guess must be numbers (rad for angles) for {list(mech.unknowns)}", shown=guess)
    vec = vec.reshape(-1)
    if vec.size != len(mech.unknowns):
        raise InputError(
            f"guess has {vec.size} values but {mech.name} has {len(mech.unknowns)} unknowns {list(mech.unknowns)}"
        )
    if not math.isfinite(vec.sum()) and not np.isfinite(vec).all():  # (a finite sum: all finite)
        bad = mech.unknowns[int(np.flatnonzero(~np.isfinite(vec))[0])]
        raise InputError(f"guess for {bad} is not finite")
    return vec


def solve_start(ctx: Continuation, t0: float, guess, maxiter: int):
    """Solve the first point from the guess (continuing from ``guess_input`` if needed).

    Returns ``(x, iterations, d, o)``: the point (list), its Newton
    iterations, and the tangent dq/dt and loop orientations the sweep goes on
    with. Where the point was reached from ``guess_input`` these are the
    march's (a point on or next to a singular position has no tangent or
    orientation of its own: the guess's branch carries them there).
    """
    mech = ctx.mech
    g = mech.default_guess if guess is None else guess
    ctx.started_on_default = guess is None
    if guess is None and g is not None and not callable(g) and mech.guess_input is not None and mech.guess_input != t0:
        tg = float(mech.guess_input)
        x_g, _, v = _solve_first(ctx, tg, guess_vector(mech, g, tg), maxiter, note=" (the default guess's input)")
        d, o = ctx.local1(v)
        ctx.approach = ctx.approach_inputs = (tg, t0)
        try:
            x, d_t0, o_t0, iters = ctx.march(tg, x_g, d, o, t0)
            o_t0 = ctx.unpassed_crossings(t0, o_t0)  # a singular position at t0: passed (or not) by the sweep
        finally:
            ctx.approach = None
        if d_t0 is None or o_t0 is None:
            d_t0, o_t0 = ctx.local1(ctx.eval1(x, t0))
        return x, iters, d_t0, o_t0
    x, iters, v = _solve_first(ctx, t0, guess_vector(mech, g, t0), maxiter)
    d, o = ctx.local1(v)
    return x, iters, d, o


def _dependent(ctx, x, t0) -> bool:
    """Whether the Jacobian is singular wherever it is tried near ``x``: dependent equations."""
    for delta in (0.0, 0.37, -0.61, 1.13):
        y = [a + delta * (1.0 + 0.71 * k) * s for k, (a, s) in enumerate(zip(x, ctx.xs))]
        v = ctx.eval1(y, t0)
        if v is None:
            continue
        if not is_singular(max(ctx.blocks.cond1(v[ctx.n : ctx.n + ctx.nn]))):
            return False
    return True


def never_closes(mech):
    """``(loop, message)`` for a loop of vectors of constant lengths whose longest vector is longer than
    all the others together: no angles close it, at any input. None if there is no such loop.

    Examples
    --------
    >>> import sympy as sp
    >>> from numkin import Loop, Mechanism
    >>> t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    >>> r1, r2, r3, r4 = sp.symbols("r1 r2 r3 r4")
    >>> loop = Loop.from_vectors([(r2, t2), (r3, t3), (-r4, t4), (-r1, 0)], [t3, t4], name="O2-A-B-O4")
    >>> never_closes(Mechanism([loop], t2, {r1: 100, r2: 10, r3: 30, r4: 30}))[1]
    "loop 'O2-A-B-O4' cannot close at any input: its vector of length r1 = 100 is longer than all the others together (70)"
    """
    values = {str(s): v for s, v in mech.parameters.items()}
    for lp in mech.loops:
        sizes = []
        for length, _ in lp.vectors:
            if not {str(s) for s in length.free_symbols} <= set(values):
                break  # a length that moves (a slider): the polygon has no fixed sides
            value = complex(length.subs({s: values[str(s)] for s in length.free_symbols}))
            if value.imag != 0 or not math.isfinite(value.real):  # e.g. sqrt of a negative dimension
                return lp.name, (f"loop '{lp.name}' cannot close: its vector length {length} = {value:g} is not a "
                                 "finite real number; check the dimensions in it")
            sizes.append((abs(value.real), length))
        else:
            if len(sizes) < 2:
                continue
            longest, expr = max(sizes, key=lambda p: p[0])
            rest = sum(a for a, _ in sizes) - longest
            if longest > rest * (1.0 + 1e-12):
                name = str(expr).lstrip("-")
                return lp.name, (f"loop '{lp.name}' cannot close at any input: its vector of length {name} = "
                                 f"{longest:g} is longer than all the others together ({rest:g})")
    return None


def _where(t0, note):
    """The input of a first point, for messages."""
    return f"input {deg_text(t0, 3)}{note}"


def _loop_numbers(ctx, x, t0, k):
    """Loop ``k``'s scaled residual and condition number at ``x`` (NaN and inf where undefined)."""
    v = ctx.eval1(x, t0)
    if v is None:
        return math.nan, math.inf
    a, b = ctx.blocks.blocks[k]
    return max([abs(f) for f in v[a:b]]) / ctx.fscale, ctx.blocks.cond1(v[ctx.n : ctx.n + ctx.nn])[k]


def loop_by_loop(ctx, x, t0, maxiter):
    """Newton at the input ``t0`` on one loop after another, each from its own guess with the loops before it
    solved: ``(x, status, iterations, residual, v, loop, loop_iterations)``: ``iterations`` of all loops,
    ``loop`` the index of the loop that failed (else the last), ``loop_iterations`` and ``residual`` its own
    Newton steps and scaled residual, ``v`` the evaluation at ``x`` of its last step (None if unknown).

    The loops' Jacobian is block lower-triangular: Newton on all of them at
    once moves the first loop as Newton on it alone would, and each later one
    along a linearisation in the earlier loops' steps, which far from the
    solution carries it off its own guess, onto another assembly branch
    even where its guess was exact. Solved one at a time, every loop's
    guess picks its own branch. ``maxiter`` Newton steps are allowed each loop.
    """
    last, total = len(ctx.blocks.blocks) - 1, 0
    for k in range(last + 1):
        x, status, it, res, v = ctx.newton1(x, t0, maxiter, cond_max=COND_MAX, loop=k if last else None)
        total += it
        if status != "converged":
            return x, status, total, res, v, k, it
    return x, "converged", total, res, v, last, it


def _solve_first(ctx, t0, x_guess, maxiter, note=""):
    """Newton from the guess at t0, loop by loop, the angles reduced to the guess's turn, then polished."""
    mech = ctx.mech
    guess = x_guess.tolist()
    x, status, it, res, v, failed, steps = loop_by_loop(ctx, guess, t0, maxiter)
    far = far_guesses(mech, guess)
    if status != "converged" and (status != "singular" or not res <= FAR):
        impossible = never_closes(mech)
        if impossible is not None:
            raise AssemblyError(f"{mech.name}: {impossible[1]}", input_value=float(t0), loop=impossible[0],
                                cause="cannot close", residual=res, iterations=it)
    if status == "singular":
        where = _where(t0, note)
        loop = ctx.loop_names[failed]  # (the loops after it are not solved yet: only its own numbers tell)
        res, cond = _loop_numbers(ctx, x, t0, failed)
        if _dependent(ctx, x, t0):
            raise AssemblyError(
                f"{mech.name}: the loop equations are dependent: their Jacobian (loop '{loop}') is singular "
                f"at {where} and at every nearby point tried, so they do not fix the unknowns; "
                "check that no equation repeats another",
                input_value=float(t0), loop=loop, cause="dependent equations", residual=res, iterations=steps,
            )
        if not res <= FAR:
            raise _hinted(AssemblyError(
                f"{mech.name}: cannot assemble at {where} from the guess: Newton met a singular Jacobian "
                f"of loop '{loop}' after {steps} iterations, far from any solution (scaled residual {res:.3g}); "
                "give a guess nearer the position (angles in rad)",
                input_value=float(t0), loop=loop, cause="bad guess", residual=res, iterations=steps,
            ), far)
        raise BranchError(
            f"{mech.name}: the Jacobian of loop '{loop}' is singular at {where} "
            f"(condition number {cond:.3g}): a toggle or change point, where the branch cannot be chosen; "
            "start the sweep at another input (and pass on_singular='report' if the sweep crosses "
            "such a position)",
            kind="singular", input_value=float(t0), loop=loop, cond=cond,
        )
    if status != "converged":
        where = _where(t0, note)
        loop = ctx.loop_names[failed]
        res, _ = _loop_numbers(ctx, x, t0, failed)
        more = f", or allow more than maxiter={maxiter} steps" if status == "maxiter" else ""
        raise _hinted(AssemblyError(
            f"{mech.name}: cannot assemble at {where}: Newton from the guess did not converge "
            f"(loop '{loop}' residual {res:.3g} after {steps} iterations); "
            f"check the dimensions or give a better guess (angles in rad){more}",
            input_value=float(t0), loop=loop, cause="bad guess", residual=res, iterations=steps,
        ), far)
    x, moved = ctx.nearest_turn(x, guess)
    if moved:  # reduced to the guess's turn, then polished there
        x, status, it2, _, v = ctx.newton1(x, t0, maxiter, cond_max=COND_MAX)
        it += it2
    far = still_far(mech, far, x)
    if far:
        where = _where(t0, note)
        starts = ", ".join(f"{name} at {math.degrees(x[mech.unknowns.index(name)]):.6g}°" for name, _ in far)
        warn(GuessWarning(
            f"{mech.name}: {degrees_hint(far)}; the solution at {where} is more than 1 rad from it, and the "
            f"sweep keeps the guess's turn (it starts with {starts})", far=far, starts=[
                x[mech.unknowns.index(name)] for name, _ in far]))
    return x, it, v

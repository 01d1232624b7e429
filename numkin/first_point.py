"""The first point of a sweep: Newton from the guess, on the guess's turn, polished; and why it fails.

A singular Jacobian met on the way is told apart: dependent loop equations
(singular wherever tried), a poor guess (singular far from any solution),
or a singular position of the linkage at the input itself.
"""

from __future__ import annotations

import math
import warnings


from .errors import AssemblyError, BranchError
from .march import FAR, TWO_PI, Continuation, deg_text
from .newton import COND_MAX, is_singular

__all__ = ["solve_start"]


def solve_start(ctx: Continuation, t0: float, guess, maxiter: int):
    """Solve the first point from the guess (continuing from ``guess_input`` if needed).

    Returns ``(x, iterations, v)``.
    """
    mech = ctx.mech
    g = mech.default_guess if guess is None else guess
    ctx.started_on_default = guess is None
    if guess is None and g is not None and not callable(g) and mech.guess_input is not None and mech.guess_input != t0:
        tg = float(mech.guess_input)
        x_g, _, v = _solve_first(ctx, tg, mech.guess_vector(g, tg), maxiter, note=" (the default guess's input)")
        d, o = ctx.local1(v)
        x, _, _, iters = ctx.march(tg, x_g, d, o, t0)
        return x, iters, ctx.eval1(x, t0)
    return _solve_first(ctx, t0, mech.guess_vector(g, t0), maxiter)


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


def _solve_first(ctx, t0, x_guess, maxiter, note=""):
    """Newton from the guess at t0, the angles reduced to the guess's turn, then polished."""
    mech = ctx.mech
    guess = x_guess.tolist()
    x, status, it, res, v = ctx.newton1(guess, t0, maxiter, cond_max=COND_MAX)
    where = f"input {deg_text(t0, 3)}{note}"
    if status == "singular":
        loop, cond = ctx.worst1(x, t0, which="cond")
        _, res = ctx.worst1(x, t0)
        if _dependent(ctx, x, t0):
            raise AssemblyError(
                f"{mech.name}: the loop equations are dependent: their Jacobian (loop '{loop}') is singular "
                f"at {where} and at every nearby point tried, so they do not fix the unknowns; "
                "check that no equation repeats another",
                input_value=float(t0), loop=loop, cause="dependent equations", residual=res, iterations=it,
            )
        if not res <= FAR:
            raise AssemblyError(
                f"{mech.name}: cannot assemble at {where} from the guess: Newton met a singular Jacobian "
                f"of loop '{loop}' after {it} iterations, far from any solution (scaled residual {res:.3g}); "
                "give a guess nearer the position (angles in rad)",
                input_value=float(t0), loop=loop, cause="bad guess", residual=res, iterations=it,
            )
        raise BranchError(
            f"{mech.name}: the Jacobian of loop '{loop}' is singular at {where} "
            f"(condition number {cond:.3g}): a toggle or change point, where the branch cannot be chosen; "
            "start the sweep at another input (and pass on_singular='report' if the sweep crosses "
            "such a position)",
            kind="singular", input_value=float(t0), loop=loop, cond=cond,
        )
    if status != "converged":
        loop, res = ctx.worst1(x, t0)
        raise AssemblyError(
            f"{mech.name}: cannot assemble at {where}: Newton from the guess did not converge "
            f"(loop '{loop}' residual {res:.3g} after {it} iterations); "
            "check the dimensions or give a better guess (angles in rad)",
            input_value=float(t0), loop=loop, cause="bad guess", residual=res, iterations=it,
        )
    x, moved = ctx.nearest_turn(x, guess)
    if moved:  # reduced to the guess's turn, then polished there
        x, status, it2, _, v = ctx.newton1(x, t0, maxiter, cond_max=COND_MAX)
        it += it2
    far = [k for k in ctx.angle_idx if abs(guess[k]) > TWO_PI and abs(x[k] - guess[k]) > 1.0]
    if far:
        k = far[0]
        name = mech.unknowns[k]
        warnings.warn(
            f"{mech.name}: the guess {name} = {guess[k]:g} is more than a turn from zero and the solution "
            f"at {where} is {abs(x[k] - guess[k]):.3g} rad away from it: angles are in rad (was the guess "
            f"in degrees?); the sweep keeps the guess's turn ({name} starts at {math.degrees(x[k]):.6g}°)",
            UserWarning, stacklevel=4,
        )
    return x, it, v

"""The checks of the homework's linkages: loop closure, assembly, continuity, input units.

Loop-closure residuals of the homework's four-bars (:func:`four_bar_gap`) and
six-bar (:func:`six_bar_gap`); the unit of angle arrays decided by those loops
(:func:`read_angles`, :func:`read_angle_group`, :func:`chained_four_bar_angles`);
and the checks that raise on them: :func:`closure` (the loop does not close, or a
Newton iteration stopped early), :func:`continuity` (a jump to the other branch),
:func:`chained_four_bar_assembly` (the mirror assembly),
:func:`quick_return_input_unit` (θ2 in degrees where radians are taken) and
:func:`inputs_in_degrees` (a sweep's input angles in degrees where radians are taken).
"""

from __future__ import annotations

import math

import numpy as np

from .reading import FULL_TURN, _grid_angles, _wrapped, array

__all__ = [
    "four_bar_gap",
    "four_bar_side",
    "chained_four_bar_angles",
    "chained_four_bar_assembly",
    "six_bar_gap",
    "quick_return_input_unit",
    "inputs_in_degrees",
    "read_angle_group",
    "read_angles",
    "closure",
    "continuity",
]


def four_bar_gap(out_rad, in_rad, r_fixed, r_in, r_coupler, r_out) -> np.ndarray:
    """Loop-closure residual of the homework's four-bar, one value per sample.

    The loop ``r_out e^{i out} + r_coupler e^{i coupler} + r_in e^{i(in + π)} = r_fixed``
    closes for some coupler angle exactly when the distance
    ``|r_fixed - r_out e^{i out} + r_in e^{i in}|`` equals ``r_coupler``; the
    difference is returned (same length unit as the links).
    """
    out_rad = np.asarray(out_rad, dtype=float)
    in_rad = np.asarray(in_rad, dtype=float)
    reach = np.abs(r_fixed - r_out * np.exp(1j * out_rad) + r_in * np.exp(1j * in_rad))
    return np.abs(reach - r_coupler)


def chained_four_bar_angles(phi, beta):
    """φ and β of the chained four-bars homework read in radians, each unit decided by its loop.

    Returns ``(phi_rad, beta_rad, beta_unit, beta_residual)``.
    """
    def gap1(a):
        return four_bar_gap(a, np.radians(np.arange(a.size)), 7.0, 1.94, 6.86, 2.36)

    _, phi_rad, _ = read_angles("phi", phi, gap1)

    def gap2(b):
        return four_bar_gap(b, phi_rad[: b.size] + np.radians(149.0), 1.25, 2.39, 1.87, 1.26)

    unit, beta_rad, residual = read_angles("beta", beta, gap2)
    return phi_rad, beta_rad, unit, residual


def four_bar_side(out_rad, in_rad, r_fixed, r_in, r_out) -> np.ndarray:
    """Which of the two assemblies of the homework's four-bar the angles are on, one value per sample.

    With the output pivot at the origin, the end of the input link is
    ``P = r_fixed + r_in e^{i in}`` and the output joint ``Q = r_out e^{i out}``;
    the coupler joins them.  For a given input the loop closes at the two
    intersections of the circles about the origin (radius ``r_out``) and about
    ``P`` (radius of the coupler), mirror images across the line from the origin
    to ``P``.  The sine of the angle from ``P`` to ``Q`` is returned: positive on
    one assembly, negative on the other, zero only at a toggle position.
    """
    p = r_fixed + r_in * np.exp(1j * np.asarray(in_rad, dtype=float))
    q = np.exp(1j * np.asarray(out_rad, dtype=float))
    return np.imag(np.conj(p) * q) / np.abs(p)


_CHAINED = {
    # name: (dimensions fixed, input, output, the side of the assembly asked, the question's guess at θ = 0)
    "phi": ((7.0, 1.94, 2.36), 1.0, "linkage 1", "(φ, ψ) = (45°, 60°)"),
    "beta": ((1.25, 2.39, 1.26), -1.0, "linkage 2", "(β, γ) = (30°, 270°)"),
}


def chained_four_bar_assembly(name: str, phi, beta=None) -> None:
    """Raise if φ (``name`` "phi") or β ("beta") closes its loop on the other assembly than the one asked.

    The question's guesses at θ = 0 lead, by continuation, to one assembly of each
    linkage; a guess near the other circle intersection leads to its mirror image,
    which closes the loop and turns without a jump, so that only its side
    (:func:`four_bar_side`) tells it apart.  Raises only on that evidence: angles
    that cannot be read or do not close the loop are left to the other checks.
    """
    try:
        if name == "phi":
            _, out, residual = read_angles(
                "phi", phi, lambda a: four_bar_gap(a, np.radians(np.arange(a.size)), 7.0, 1.94, 6.86, 2.36)
            )
            inputs = np.radians(np.arange(out.size))
        else:
            phi_rad, out, _, residual = chained_four_bar_angles(phi, beta)
            inputs = phi_rad[: out.size] + np.radians(149.0)
    except AssertionError:
        return
    (r_fixed, r_in, r_out), side, linkage, guess = _CHAINED[name]
    sides = four_bar_side(out, inputs, r_fixed, r_in, r_out)
    closes = np.isfinite(sides) & (np.nan_to_num(np.abs(residual), nan=1.0) < 1e-6)
    if not closes.any() or np.any(sides[closes] * side > 0):
        return
    first = int(np.flatnonzero(closes)[0])
    raise AssertionError(
        f"`{name}` is on the other assembly (the other circle intersection) of {linkage}: the loop closes "
        f"and turns without a jump, but from θ = {first}° on, the output link lies on the other side of the line "
        "from its pivot to the end of the input link, the mirror image of the asked assembly. Start at θ = 0 "
        f"from the question's guess {guess} and then from each previous solution."
    )


def six_bar_gap(crank_rad, t3, t4, t5, x, *, crank=1.0, coupler=4.0, o4=(3.7, -2.0), o4b=3.0, bc=3.2,
                o4c=6.0, rod=6.5, slider_y=3.0) -> np.ndarray:
    """Loop-closure residual of the six-bar homework, the larger of its two loops per sample.

    Loop 1 ``crank e^{i θ2} + coupler e^{i θ3} - o4b e^{i θ4} - O4`` and loop 2
    ``O4 + o4b e^{i θ4} + bc e^{i(θ4 + β)} - rod e^{i θ5} - (x + i slider_y)``,
    with ``β = π - angle(O4 B C)`` from the ternary link's sides; the defaults
    are the homework's dimensions (cm).
    """
    beta = np.pi - np.arccos((o4b**2 + bc**2 - o4c**2) / (2 * o4b * bc))
    pivot = complex(*o4)
    one = crank * np.exp(1j * crank_rad) + coupler * np.exp(1j * t3) - o4b * np.exp(1j * t4) - pivot
    two = (pivot + o4b * np.exp(1j * t4) + bc * np.exp(1j * (t4 + beta)) - rod * np.exp(1j * t5)
           - (np.asarray(x) + 1j * slider_y))
    return np.maximum(np.abs(one), np.abs(two))


def quick_return_input_unit(values, theta2_deg: float) -> None:
    """Raise if (r3, θ3, r4, r5) close the quick-return loop at θ2 = ``theta2_deg`` *radians*.

    That is the evidence of θ2 passed in degrees to functions that take radians; the
    message names it only when the loop closes there and not at the asked angle.
    """
    r3, t3, r4, r5 = (float(v) for v in values)

    def worst(t2, t3):
        return max(abs(40.0 * math.cos(t2) - r3 * math.cos(t3)),
                   abs(60.0 + 40.0 * math.sin(t2) - r3 * math.sin(t3)),
                   abs(120.0 - r4 * math.sin(t3)), abs(r5 - r4 * math.cos(t3)))

    for t3_rad in (t3, math.radians(t3)):
        if worst(math.radians(theta2_deg), t3_rad) < 1e-6:
            return  # closes at the asked angle
    for t3_rad in (t3, math.radians(t3)):
        if worst(theta2_deg, t3_rad) < 1e-6:
            raise AssertionError(
                f"your r3, θ3, r4, r5 close the loop at θ2 = {theta2_deg:g} rad "
                f"(= {math.degrees(theta2_deg) % 360:.1f}° after whole turns), not at {theta2_deg:g}°: "
                f"θ2 was given in degrees where F and J take radians; use np.radians({theta2_deg:g})"
            )


def inputs_in_degrees(name: str, arrays, gap, *, grid=FULL_TURN, tol: float = 1e-6, radians: str = "theta",
                      degrees: str = "theta_deg") -> None:
    """Raise if the angle ``arrays`` close their loop with the grid's input angles read as radians.

    Solved at θ = 0, 1, 2, … rad where 0°, 1°, 2°, … are asked, the angles close the loop at
    those inputs and at no asked one: the evidence of input angles in degrees (the variable
    ``degrees``) handed to functions that take radians (``radians``).  ``gap(inputs_rad,
    *angles_rad)`` is the loop-closure residual; the arrays are read in radians and in
    degrees.  Raises only on that evidence: arrays that cannot be read, that close the loop
    at the asked inputs, or at neither, are left to the other checks (:func:`closure`).
    """
    try:
        values = [array(a, name, grid) for a in arrays]
    except AssertionError:
        return
    asked = np.radians(_grid_angles(grid))
    read_as_radians = _grid_angles(grid)  # 0, 1, 2, ... where 0°, 1°, 2°, ... are asked

    def worst(inputs, angles):
        with np.errstate(all="ignore"):
            residual = np.asarray(gap(inputs, *angles), dtype=float)
        return float(np.nanmax(residual)) if np.isfinite(residual).any() else math.inf

    readings = [values, [np.radians(a) for a in values]]
    if any(worst(asked, angles) <= tol for angles in readings):
        return
    if any(worst(read_as_radians, angles) <= tol for angles in readings):
        start, _, step = grid
        first = ", ".join(f"{start + k * step:g}" for k in range(3))
        raise AssertionError(
            f"`{name}` closes the loop at θ = {first}, … rad, not at θ = {first.replace(', ', '°, ')}°, …: the input "
            f"angles were given in degrees where the equations take radians; use `{radians}`, not `{degrees}`"
        )


def read_angle_group(arrays, gap):
    """Read several angle arrays in one unit, deciding it by the loop equations.

    ``gap(*angles_rad)`` returns the loop-closure residual; the unit (radians
    or degrees) in which it is smaller wins.  Returns ``(unit, [angles in
    radians], residual)``.
    """
    best = None
    for unit in ("rad", "deg"):
        read = [a if unit == "rad" else np.radians(a) for a in arrays]
        residual = np.asarray(gap(*read), dtype=float)
        if best is None or np.max(residual) < np.max(best[2]):
            best = (unit, read, residual)
    return best


def read_angles(name: str, x, gap, *, grid=FULL_TURN):
    """Read the angle array ``x`` in radians, deciding its unit by the loop equations.

    ``gap(angles_rad)`` returns the loop-closure residual of the angles; the
    unit (radians or degrees) in which the residual is smaller wins.  Returns
    ``(unit, angles in radians, residual)``.
    """
    unit, (read,), residual = read_angle_group([array(x, name, grid)], gap)
    return unit, read, residual


def closure(
    name: str,
    gap,
    *,
    tol: float = 1e-9,
    grid=FULL_TURN,
    step_rad: float | None = None,
    broken: float = 1e-2,
):
    """Check that loop-closure residuals ``gap`` (one per grid angle) are all below ``tol``.

    A residual above ``broken`` means the equations or the data are wrong; one
    between ``tol`` and ``broken`` means the Newton iteration stopped before it
    converged, and the message says how finite differences magnify it.
    """
    gap = np.nan_to_num(np.abs(np.asarray(gap, dtype=float)), nan=0.0)  # NaN ends: not checked
    worst = int(np.argmax(gap))
    if gap[worst] <= tol:
        return
    where = _grid_angles(grid)[worst]
    if gap[worst] > broken:
        raise AssertionError(
            f"`{name}` does not satisfy the loop-closure equations (|F| up to {gap[worst]:.3g} "
            f"at θ = {where:g}°) in radians or in degrees: check the equations, the link "
            "lengths and the input angles"
        )
    h = step_rad if step_rad is not None else math.radians(grid[2])
    raise AssertionError(
        f"`{name}` satisfies the loop-closure equations only to |F| ≈ {gap[worst]:.1g} "
        f"(worst at θ = {where:g}°): the Newton iteration stops too early, e.g. at |F| < 1e-4. "
        f"Iterate until the step |Δx| < 1e-10. A first difference divides this error by "
        f"h = {h:.3g}, a second difference by h² = {h * h:.2g}."
    )


def continuity(name: str, angles_rad, *, grid=FULL_TURN, max_step_deg: float = 10.0):
    """Check that angles (radians) move by less than ``max_step_deg`` between grid points."""
    values = np.asarray(angles_rad, dtype=float)
    steps = np.nan_to_num(np.degrees(np.abs(_wrapped(np.diff(values)))), nan=0.0)
    worst = int(np.argmax(steps))
    if steps[worst] <= max_step_deg:
        return
    where = _grid_angles(grid)
    raise AssertionError(
        f"`{name}` jumps by {steps[worst]:.3g}° between θ = {where[worst]:g}° and "
        f"{where[worst + 1]:g}°: Newton has jumped to the other assembly branch. Start each "
        "solve from the previous solution (continuation), not from the same fixed guess."
    )

# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [raw]
# # ASSIGNMENT CONFIG
# name: hw2-quick-return
# files:
#   - kincheck
# requirements:
#   - numpy>=1.24,<3
#   - matplotlib>=3.7,<4
# tests:
#   ok_format: false
# generate: true
# export_cell:
#   pdf: false
#   instructions: "Upload the zip file this cell makes."
# check_all_cell: true

# %% [markdown]
# # Homework 2 — Position analysis of a quick-return mechanism
#
# The rocker pivot O₁ is at the origin and the crank pivot O₂ = (0, r₁) above it. The
# crank O₂A (length r₂, angle θ₂ from the horizontal) carries the slider A, which runs in
# the slotted rocker O₁B (angle θ₃); O₁A = r₃. The output slider B runs on the horizontal
# line through C = (0, r₁ + r₆), at CB = r₅ from C; O₁B = r₄. With the two loop-closure
# equations written in components,
#
# $$
# \begin{aligned}
# \text{(I)}\quad & r_1 + r_2 \sin\theta_2 = r_3 \sin\theta_3 &
# \text{(II)}\quad & r_2 \cos\theta_2 = r_3 \cos\theta_3 \\
# \text{(III)}\quad & r_1 + r_6 = r_4 \sin\theta_3 &
# \text{(IV)}\quad & r_5 = r_4 \cos\theta_3
# \end{aligned}
# $$
#
# with r₁ = 60 mm, r₂ = 40 mm and r₆ = 60 mm. The unknowns are
# **x = [r₃, θ₃, r₄, r₅]**, in that order (lengths in mm, θ₃ in rad inside your functions).
#
# Run `grader.check("q1")` (and so on) after each question.

# %%
import numpy as np
import matplotlib.pyplot as plt

R1, R2, R6 = 60.0, 40.0, 60.0  # mm: O2O1, crank O2A, O2C
THETA2_DEG = 30.0

# %% [raw]
# # BEGIN QUESTION
# name: q1
# points: [1, 1]

# %% [markdown]
# **Q1 — residual and Jacobian.** Write `F(x, theta2)`, returning the four residuals of
# equations (I)–(IV) (each written as left side minus right side, in any order), and
# `J(x, theta2)`, the 4 × 4 matrix of their partial derivatives with respect to
# x = [r₃, θ₃, r₄, r₅]. `theta2` is in radians.

# %% [raw]
# # BEGIN SOLUTION

# %%
def F(x, theta2):
    """Residuals of equations (I)-(IV) at x = [r3, theta3, r4, r5]."""
    # BEGIN SOLUTION
    r3, theta3, r4, r5 = x
    return np.array([
        R2 * np.cos(theta2) - r3 * np.cos(theta3),
        R1 + R2 * np.sin(theta2) - r3 * np.sin(theta3),
        r5 - r4 * np.cos(theta3),
        R1 + R6 - r4 * np.sin(theta3),
    ])
    # END SOLUTION


def J(x, theta2):
    """Partial derivatives of F with respect to r3, theta3, r4, r5."""
    # BEGIN SOLUTION
    r3, theta3, r4, r5 = x
    return np.array([
        [-np.cos(theta3), r3 * np.sin(theta3), 0.0, 0.0],
        [-np.sin(theta3), -r3 * np.cos(theta3), 0.0, 0.0],
        [0.0, r4 * np.sin(theta3), -np.cos(theta3), 1.0],
        [0.0, -r4 * np.cos(theta3), -np.sin(theta3), 0.0],
    ])
    # END SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_jacobian_matches_residual(F, J):
    import numpy as np
    import kincheck as kc

    assert callable(F) and callable(J), "define the functions `F(x, theta2)` and `J(x, theta2)`"
    x, t2 = np.array([80.0, 1.1, 125.0, 45.0]), 0.4
    f = np.asarray(kc.returned(F(x, t2), "F", "F(x, theta2)"), dtype=float)
    jac = np.asarray(kc.returned(J(x, t2), "J", "J(x, theta2)"), dtype=float)
    assert f.shape == (4,), f"`F` should return 4 residuals, got shape {f.shape}"
    assert jac.shape == (4, 4), f"`J` should return a 4 x 4 matrix, got shape {jac.shape}"
    names = ["r3", "theta3", "r4", "r5"]
    for k in range(4):
        step = 1e-6 * max(1.0, abs(x[k]))
        up, down = x.copy(), x.copy()
        up[k] += step
        down[k] -= step
        column = (np.asarray(F(up, t2)) - np.asarray(F(down, t2))) / (2 * step)
        assert np.allclose(jac[:, k], column, rtol=1e-5, atol=1e-6), (
            f"column {k} of `J` (derivatives with respect to {names[k]}) is {np.round(jac[:, k], 4)}, "
            f"but differencing your `F` gives {np.round(column, 4)}"
        )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_residual_vanishes_at_the_solution(F):
    import numpy as np
    import kincheck as kc

    assert callable(F), "define the function `F(x, theta2)` (not defined: did its cell raise an error?)"
    X30 = [87.1779788708, 1.1621584717, 130.766968306, 51.9615242271]  # reference: x_30
    x = np.array(X30)
    f = np.asarray(kc.returned(F(x, np.radians(30.0)), "F", "F(x, theta2)"), dtype=float)
    assert f.shape == (4,), f"`F` should return 4 residuals, got shape {f.shape}"
    if not np.all(np.abs(f) <= 1e-8 * 100):  # NaN is no residual that vanishes
        report_order = x[[0, 2, 3, 1]]
        g = np.asarray(F(report_order, np.radians(30.0)), dtype=float)
        assert np.max(np.abs(g)) > 1e-6, (
            "`F` takes the unknowns in the order [r3, r4, r5, theta3]; the question asks for "
            "x = [r3, theta3, r4, r5]"
        )
        g = np.asarray(F(x, 30.0), dtype=float)
        assert np.max(np.abs(g)) > 1e-6, "`F` takes theta2 in degrees; the question asks for radians"
        raise AssertionError(
            f"`F` does not vanish at the solution x = {np.round(x, 4)}, theta2 = 30°: "
            f"residuals {np.round(f, 6)}; check equations (I)-(IV)"
        )

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q2
# points: [1, 1]

# %% [markdown]
# **Q2 — Newton–Raphson at θ₂ = 30°.** Solve F(x) = 0 at θ₂ = 30° by Newton–Raphson from a
# guess read off a rough sketch of the linkage, iterating until the step is below 1e-10.
# Store the solution in `r3`, `theta3`, `r4`, `r5` (mm; θ₃ in radians or degrees, reduced
# to one turn [0, 2π) or [0°, 360°)).
#
# The hand calculation of the source report gave r₃ = 87.17 mm, θ₃ = 66.58°,
# r₄ = 130.75 mm and r₅ = 51.96 mm. Compare.

# %% [raw]
# # BEGIN SOLUTION

# %%
def newton(x0, theta2, tol=1e-10, maxiter=50):
    """Solve F(x, theta2) = 0 from x0; stop when the Newton step is below tol."""
    # BEGIN SOLUTION
    x = np.array(x0, dtype=float)
    for _ in range(maxiter):
        step = np.linalg.solve(J(x, theta2), -F(x, theta2))
        x = x + step
        if np.max(np.abs(step)) < tol:
            return x
    raise RuntimeError(f"Newton did not converge from {x0} at theta2 = {theta2}")
    # END SOLUTION


""" # BEGIN PROMPT
guess = ...  # [r3, theta3, r4, r5] read off a sketch
r3, theta3, r4, r5 = ..., ..., ..., ...  # replace each ... with the solution at theta2 = 30 degrees
""" # END PROMPT
# BEGIN SOLUTION NO PROMPT
guess = [80.0, np.radians(60.0), 130.0, 50.0]  # from a sketch of the linkage at 30 degrees
r3, theta3, r4, r5 = newton(guess, np.radians(THETA2_DEG))
theta3 = np.mod(theta3, 2 * np.pi)
# END SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_solution_satisfies_the_equations(r3, theta3, r4, r5):
    import numpy as np
    import kincheck as kc

    values = [kc.at(v, n, 30) for v, n in ((r3, "r3"), (theta3, "theta3"), (r4, "r4"), (r5, "r5"))]
    t2 = np.radians(30.0)
    best = None
    for unit in ("rad", "deg"):
        a, t3, b, c = values
        t3 = t3 if unit == "rad" else np.radians(t3)
        f = np.array([
            60.0 + 40.0 * np.sin(t2) - a * np.sin(t3),
            40.0 * np.cos(t2) - a * np.cos(t3),
            120.0 - b * np.sin(t3),
            c - b * np.cos(t3),
        ])
        if best is None or np.max(np.abs(f)) < np.max(np.abs(best[1])):
            best = (unit, f)
    unit, f = best
    print(f"`theta3` read as {'radians' if unit == 'rad' else 'degrees'}")
    kc.quick_return_input_unit(values, 30.0)
    labels = ["(I) r1 + r2 sin θ2 = r3 sin θ3", "(II) r2 cos θ2 = r3 cos θ3",
              "(III) r1 + r6 = r4 sin θ3", "(IV) r5 = r4 cos θ3"]
    worst = int(np.argmax(np.abs(f)))
    assert abs(f[worst]) < 1e-6, (
        f"equation {labels[worst]} is off by {f[worst]:.3g} mm at θ2 = 30° "
        f"(theta3 read as {'radians' if unit == 'rad' else 'degrees'})"
    )
    assert values[0] > 0, (
        f"`r3` = {values[0]:.6g} mm, a negative length: Newton found the mirror solution (r3 < 0, r4 < 0, "
        "θ3 turned by 180°), which satisfies (I)-(IV) as well; start it from a guess read off the sketch, with r3 > 0"
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_values_at_30_degrees(r3, theta3, r4, r5):
    import math
    import kincheck as kc

    R3 = 87.1779788708  # reference: r3_30
    THETA3 = 1.1621584717  # reference: theta3_30
    R4 = 130.766968306  # reference: r4_30
    R5 = 51.9615242271  # reference: r5_30
    kc.quick_return_input_unit([kc.at(v, n, 30) for v, n in ((r3, "r3"), (theta3, "theta3"), (r4, "r4"), (r5, "r5"))], 30.0)
    MIRROR = ("a negative length: Newton found the mirror solution (r3 < 0, r4 < 0, θ3 turned by 180°), which "
              "satisfies (I)-(IV) as well; start it from a guess read off the sketch, with r3 > 0")
    kc.value("r3", r3, R3, rtol=1e-6, unit="mm", suspects=("mm",), flipped=MIRROR)
    kc.value(
        "r4", r4, R4, rtol=1e-6, unit="mm", suspects=("mm",), flipped=MIRROR,
        alternatives=[(130.75, "130.75 mm is the hand value of the source report, an arithmetic slip: r4 = (r1 + r6) / sin θ3")],
    )
    kc.value("r5", r5, R5, rtol=1e-6, unit="mm", suspects=("mm",),
             flipped="the sign is flipped: check the signs of equation (IV), r5 = r4 cos θ3")
    t3 = kc.at(theta3, "theta3", 30)
    unit = kc.unit_of("theta3", [t3], {0: THETA3}, grid=(0, 0, 1), tol=1e-6)
    turn = 2 * math.pi if unit == "rad" else 360.0
    assert 0 <= t3 < turn, (
        f"`theta3` = {t3:.6g} {'rad' if unit == 'rad' else 'deg'} is {math.degrees(THETA3):.3f}° plus "
        f"{round((t3 - (THETA3 if unit == 'rad' else math.degrees(THETA3))) / turn)} whole turns: "
        "reduce it to one turn with np.mod"
    )

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q3
# points: [1, 1, 1]

# %% [markdown]
# **Q3 — a full turn.** Solve the position for θ₂ = 0°, 1°, …, 360°, starting the Newton
# iteration at each angle **from the solution at the previous angle** (continuation).
# Store θ₃ in `theta3_sweep` (radians or degrees) and r₅ in `r5_sweep` (mm), 361 values each.

# %% [raw]
# # BEGIN SOLUTION

# %%
theta2_deg = np.arange(0, 361)
""" # BEGIN PROMPT
theta3_sweep = ...
r5_sweep = ...
""" # END PROMPT
# BEGIN SOLUTION NO PROMPT
solutions = np.empty((theta2_deg.size, 4))
x = [70.0, 1.0, 140.0, 80.0]  # sketch at theta2 = 0: A = (40, 60)
for k, d in enumerate(theta2_deg):
    x = newton(x, np.radians(d))
    solutions[k] = x
theta3_sweep = np.mod(solutions[:, 1], 2 * np.pi)
r5_sweep = solutions[:, 3]
# END SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_sweep_stays_on_one_branch(theta3_sweep):
    import numpy as np
    import kincheck as kc

    t2 = np.radians(np.arange(361.0))
    toward_a = np.arctan2(60.0 + 40.0 * np.sin(t2), 40.0 * np.cos(t2))  # direction of O1A

    def gap(t3):
        return np.abs(np.sin(t3 - toward_a[: t3.size]))

    unit, angles, residual = kc.read_angles("theta3_sweep", theta3_sweep, gap)
    print(f"`theta3_sweep` read as {'radians' if unit == 'rad' else 'degrees'}")
    kc.closure("theta3_sweep", residual, tol=1e-6)
    flipped = np.flatnonzero(np.cos(angles - toward_a[: angles.size]) < 0)
    assert flipped.size == 0, (
        f"at θ2 = {flipped[0]}° (and {flipped.size - 1} more angles) θ3 points away from A: Newton "
        "found the mirror solution with r3 < 0. Start each solve from the previous solution "
        "(continuation), not from the same fixed guess."
    )
    kc.continuity("theta3_sweep", angles)

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_theta3_sweep(theta3_sweep):
    import kincheck as kc

    THETA3 = {0: 0.982793723247, 30: 1.1621584717, 60: 1.36253556467, 90: 1.57079632679, 120: 1.77905708892, 150: 1.97943418189, 180: 2.15879893034, 210: 2.28452070574, 240: 2.23859361527, 270: 1.57079632679, 300: 0.902999038323, 330: 0.85707194785}  # reference: theta3
    kc.angles("theta3_sweep", theta3_sweep, THETA3, tol=1e-6)

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_r5_sweep(r5_sweep):
    import kincheck as kc

    R5 = {0: 80.0, 30: 51.9615242271, 60: 25.3589838486, 90: 2.93915231796e-15, 120: -25.3589838486, 150: -51.9615242271, 180: -80.0, 210: -103.923048454, 240: -94.6410161514, 270: -4.40872856024e-14, 300: 94.6410161514, 330: 103.923048454}  # reference: r5
    kc.series("r5_sweep", r5_sweep, R5, rtol=1e-6, unit="mm", suspects=("mm",),
              flipped="the sign is flipped: check the signs of equation (IV), r5 = r4 cos θ3")

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if np.shape(r5_sweep) == theta2_deg.shape:  # once `r5_sweep` is computed
    fig, ax = plt.subplots()
    ax.plot(theta2_deg, r5_sweep)
    ax.set_xlabel("crank angle θ2 (deg)")
    ax.set_ylabel("r5 = CB (mm)")
    ax.set_title("Output slider of the quick-return mechanism")
    plt.show()

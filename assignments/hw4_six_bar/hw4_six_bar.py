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
# name: hw4-six-bar
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
# # Homework 4 — Position, velocity and acceleration of a six-bar with a slider
#
# The crank O₂A (length 1, angle θ₂) turns clockwise at ω₂ = −10 rad/s about O₂ = (0, 0).
# The coupler AB (length 4, angle θ₃) drives the ternary rocker O₄BC about O₄ = (3.7, −2),
# with O₄B = 3 (angle θ₄), BC = 3.2 and O₄C = 6; BC makes the fixed angle β with O₄B. The
# rod CD (length 6.5, angle θ₅ of the vector from D to C) drives the slider D along the
# line y = 3, at x from O₂. Lengths are in cm. Two loops:
#
# $$
# \begin{aligned}
# \text{loop 1:}\quad & L_2 e^{i\theta_2} + L_3 e^{i\theta_3} - O_4B\, e^{i\theta_4} - O_4 = 0 \\
# \text{loop 2:}\quad & O_4 + O_4B\, e^{i\theta_4} + BC\, e^{i(\theta_4 + \beta)} - L_5 e^{i\theta_5} - (x + 3i) = 0
# \end{aligned}
# $$
#
# Run `grader.check("q1")` (and so on) after each question.

# %%
import numpy as np
import matplotlib.pyplot as plt

L2, L3 = 1.0, 4.0  # crank O2A, coupler AB (cm)
O4B, BC, O4C = 3.0, 3.2, 6.0  # ternary rocker (cm)
L5 = 6.5  # rod CD (cm)
O4 = np.array([3.7, -2.0])  # rocker pivot (cm)
Y_D = 3.0  # slider line y = 3 (cm)
OMEGA2 = -10.0  # rad/s, clockwise
BETA = np.pi - np.arccos((O4B**2 + BC**2 - O4C**2) / (2 * O4B * BC))  # angle from O4B to BC

theta2_deg = np.arange(0, 361)  # 0, 1, ..., 360 degrees
theta2 = np.radians(theta2_deg)
h = np.radians(1.0)  # grid step, rad

# %% [raw]
# # BEGIN QUESTION
# name: q1
# points: [1, 1]

# %% [markdown]
# **Q1 — position.** Solve loop 1 for (θ₃, θ₄), then loop 2 for (θ₅, x), by Newton–Raphson
# at θ₂ = 0°, 1°, …, 360°. At θ₂ = 0 start from (θ₃, θ₄) = (0, 1) rad and (θ₅, x) = (1, 1);
# after that, start each solve **from the solution at the previous angle**. Iterate until
# the step is below 1e-10. Store `theta3`, `theta4`, `theta5` (radians or degrees) and
# `x_D` (cm), 361 values each.

# %% [raw]
# # BEGIN SOLUTION

# %%
def newton(F, J, x0, tol=1e-10, maxiter=50):
    """Solve F(x) = 0 from x0; stop when the Newton step is below tol."""
    # BEGIN SOLUTION
    x = np.array(x0, dtype=float)
    for _ in range(maxiter):
        step = np.linalg.solve(J(x), -F(x))
        x = x + step
        if np.max(np.abs(step)) < tol:
            return x
    raise RuntimeError(f"Newton did not converge from {x0}")
    # END SOLUTION


""" # BEGIN PROMPT
theta3, theta4, theta5, x_D = ..., ..., ..., ...  # replace each ... with an array over theta2
""" # END PROMPT
# BEGIN SOLUTION NO PROMPT
def loop1(t2):
    def F(v):
        t3, t4 = v
        return np.array([
            L2 * np.cos(t2) + L3 * np.cos(t3) - O4B * np.cos(t4) - O4[0],
            L2 * np.sin(t2) + L3 * np.sin(t3) - O4B * np.sin(t4) - O4[1],
        ])

    def J(v):
        t3, t4 = v
        return np.array([[-L3 * np.sin(t3), O4B * np.sin(t4)], [L3 * np.cos(t3), -O4B * np.cos(t4)]])

    return F, J


def loop2(t4):
    def F(v):
        t5, x = v
        return np.array([
            O4[0] + O4B * np.cos(t4) + BC * np.cos(t4 + BETA) - L5 * np.cos(t5) - x,
            O4[1] + O4B * np.sin(t4) + BC * np.sin(t4 + BETA) - L5 * np.sin(t5) - Y_D,
        ])

    def J(v):
        t5, x = v
        return np.array([[L5 * np.sin(t5), -1.0], [-L5 * np.cos(t5), 0.0]])

    return F, J


theta3, theta4, theta5, x_D = (np.empty(theta2.size) for _ in range(4))
first, second = [0.0, 1.0], [1.0, 1.0]  # guesses at theta2 = 0
for k, t2 in enumerate(theta2):
    first = newton(*loop1(t2), first)
    second = newton(*loop2(first[1]), second)
    theta3[k], theta4[k] = first
    theta5[k], x_D[k] = second
# END SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_loops_close_on_one_branch(theta3, theta4, theta5, x_D):
    import numpy as np
    import kincheck as kc

    x = kc.array(x_D, "x_D")
    t2 = np.radians(np.arange(x.size))
    raw = [kc.array(a, n)[: x.size] for a, n in ((theta3, "theta3"), (theta4, "theta4"), (theta5, "theta5"))]
    unit, angles, residual = kc.read_angle_group(raw, lambda t3, t4, t5: kc.six_bar_gap(t2, t3, t4, t5, x))
    print(f"angles read as {'radians' if unit == 'rad' else 'degrees'}")
    kc.inputs_in_degrees("theta3, theta4, theta5", raw, lambda t, t3, t4, t5: kc.six_bar_gap(t[: x.size], t3, t4, t5, x),
                         radians="theta2", degrees="theta2_deg")
    if np.nanmax(residual) > 1e-9:  # a length in another unit than cm: the loops close once it is converted
        for factor, unit_name, convert in ((10.0, "millimetres", "x_D / 10"), (0.01, "metres", "x_D × 100")):
            _, _, scaled = kc.read_angle_group(raw, lambda t3, t4, t5: kc.six_bar_gap(t2, t3, t4, t5, x / factor))
            assert np.nanmax(scaled) > 1e-9, (
                f"`x_D` looks like {unit_name}: the loops close with {convert}; the question asks for centimetres"
            )
    kc.closure("theta3, theta4, theta5, x_D", residual, tol=1e-9)
    for name, a in zip(("theta3", "theta4", "theta5"), angles):
        kc.continuity(name, a)

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_slider_position(x_D):
    import kincheck as kc

    X = {0: -1.7788130729, 30: -1.9366255824, 60: -2.68256474799, 90: -3.70858438599, 120: -4.7126162668, 150: -5.46016513355, 180: -5.84837875089, 210: -5.87334851638, 240: -5.52995995042, 270: -4.76902499792, 300: -3.6094989305, 330: -2.41094979384}  # reference: x
    FROM_O4 = {d: v - 3.7 for d, v in X.items()}
    kc.series(
        "x_D", x_D, X, rtol=1e-6, unit="cm", suspects=("cm", "mm"),
        alternatives=[(FROM_O4, "this is x measured from O4; the question measures x from O2")],
        small_hint="Positions this close to the reference come from a solve stopped before it converged: see the loop-closure check",
    )

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q2
# points: [1, 1, 1, 1]

# %% [markdown]
# **Q2 — velocity and acceleration of the slider.** The crank speed is constant, so
# v = ω₂ dx/dθ₂ and a = ω₂² d²x/dθ₂². Compute them with the centred difference and the
# centred second difference of `x_D` (at the two ends, any one-sided formula: the checks
# compare interior angles only), and store them in `v_D` (cm/s) and `a_D` (cm/s²), 361
# values each.

# %% [raw]
# # BEGIN SOLUTION

# %%
def centred_difference(y, h):
    """dy/dx by centred differences on a grid of step h."""
    # BEGIN SOLUTION
    d = np.empty_like(y)
    d[1:-1] = (y[2:] - y[:-2]) / (2 * h)
    d[0] = (-3 * y[0] + 4 * y[1] - y[2]) / (2 * h)
    d[-1] = (3 * y[-1] - 4 * y[-2] + y[-3]) / (2 * h)
    return d
    # END SOLUTION


def second_difference(y, h):
    """d²y/dx² by the centred second difference on a grid of step h."""
    # BEGIN SOLUTION
    d = np.empty_like(y)
    d[1:-1] = (y[2:] - 2 * y[1:-1] + y[:-2]) / h**2
    d[0] = (2 * y[0] - 5 * y[1] + 4 * y[2] - y[3]) / h**2
    d[-1] = (2 * y[-1] - 5 * y[-2] + 4 * y[-3] - y[-4]) / h**2
    return d
    # END SOLUTION


v_D = OMEGA2 * centred_difference(x_D, h)  # SOLUTION
a_D = OMEGA2**2 * second_difference(x_D, h)  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_rates_follow_from_position(x_D, v_D, a_D):
    import numpy as np
    import kincheck as kc

    x = kc.array(x_D, "x_D")
    h = np.radians(1.0)
    inside = range(30, 331, 30)
    own_v = kc.own_difference(x, inside, h, "centred", -10.0)
    own_a = kc.own_difference(x, inside, h, "second", 100.0)
    kc.series("v_D", v_D, own_v, rtol=1e-6, unit="cm/s", suspects=("deg",), small_hint=None, alternatives=[
        (kc.own_difference(x, inside, h, "forward", -10.0),
         "this matches the forward difference of your `x_D`; the question asks for centred"),
        (kc.own_difference(x, inside, h, "centred", 10.0), kc.ROTATION),
    ])
    kc.series("a_D", a_D, own_a, rtol=1e-6, unit="cm/s²", suspects=("deg",), small_hint=None, alternatives=[
        (kc.own_difference(x, inside, h, "forward_twice", 100.0),
         "this matches the forward difference of your `x_D` applied twice; the question asks for the centred second difference"),
        (kc.own_difference(x, inside, h, "gradient_twice", 100.0),
         "this matches np.gradient applied twice to your `x_D`; the question asks for the centred second difference"),
    ], flipped="the sign is flipped: a = ω2² d²x/dθ2², whose sign does not depend on the sense of rotation")

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_slider_velocity(v_D):
    import kincheck as kc

    V = {30: 9.57619107951, 60: 17.9177555236, 90: 20.2931974979, 120: 17.2834210237, 150: 10.9560918928, 180: 3.89930053432, 210: -2.944953495, 240: -10.3583120403, 270: -18.7580541703, 300: -24.3988785229, 330: -19.1450862035}  # reference: v
    kc.series("v_D", v_D, V, rtol=5e-3, unit="cm/s", suspects=("deg", "cm"), flipped=kc.ROTATION)

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_slider_acceleration(a_D):
    import kincheck as kc

    A = {30: -216.268322148, 60: -102.019821361, 90: 9.93661951135, 120: 98.0960436806, 150: 134.423977006, 180: 132.163347752, 210: 132.431990323, 240: 153.307831871, 270: 156.89460999, 300: 26.2653090339, 330: -223.06027955}  # reference: a
    kc.series("a_D", a_D, A, rtol=5e-3, unit="cm/s²", suspects=("deg", "cm"),
              flipped="the sign is flipped: a = ω2² d²x/dθ2², whose sign does not depend on the sense of rotation")

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_velocity_is_not_a_forward_difference(v_D, x_D):
    import numpy as np
    import kincheck as kc

    x = kc.array(x_D, "x_D")
    v = kc.array(v_D, "v_D")
    h = np.radians(1.0)
    inside = np.arange(30, 331, 30)
    centred = -10.0 * (x[inside + 1] - x[inside - 1]) / (2 * h)
    forward = -10.0 * (x[inside + 1] - x[inside]) / h
    scale = np.max(np.abs(centred))
    if np.max(np.abs(v[inside] - centred)) > 1e-6 * scale:
        assert np.max(np.abs(v[inside] - forward)) > 1e-6 * scale, (
            "`v_D` matches the forward difference of your `x_D`; the question asks for centred"
        )

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if all(np.shape(y) == theta2_deg.shape for y in (x_D, v_D, a_D)):  # once all three are computed
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7, 8))
    for ax, y, label in zip(axes, (x_D, v_D, a_D), ("x of D (cm)", "v of D (cm/s)", "a of D (cm/s²)")):
        ax.plot(theta2_deg, y)
        ax.set_ylabel(label)
    axes[-1].set_xlabel("crank angle θ2 (deg)")
    plt.show()

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
# name: hw1-chained-four-bar
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
# # Homework 1 — Newton with continuation and finite differences on two chained four-bars
#
# A gear drives **linkage 1** (input θ). Its output angle φ drives **linkage 2**, whose
# input angle is α = φ + 180° − 31° = φ + 149°; its output angle is β.
# Both linkages are written in the same loop form, with r₁ the fixed link, r₄ the
# input, r₃ the coupler and r₂ the output:
#
# $$ r_2 e^{i\,\text{out}} + r_3 e^{i\,\text{coupler}} + r_4 e^{i(\text{in} + \pi)} = r_1 $$
#
# | | fixed r₁ | input r₄ | coupler r₃ | output r₂ | input angle | unknowns | guess at θ = 0 |
# |---|---|---|---|---|---|---|---|
# | linkage 1 | 7.0 | 1.94 | 6.86 | 2.36 | θ | φ, ψ | (45°, 60°) |
# | linkage 2 | 1.25 | 2.39 | 1.87 | 1.26 | α = φ + 149° | β, γ | (30°, 270°) |
#
# Lengths are in inches. The driving gear turns at ω = 450 rad/min.
#
# Run `grader.check("q1a")` (and so on) after each question: it runs the public checks and
# tells you what looks off. Hidden checks compare your numbers with reference values when
# the homework is graded.

# %%
import numpy as np
import matplotlib.pyplot as plt

# linkage 1 (in): fixed, input, coupler, output
FIXED_1, INPUT_1, COUPLER_1, OUTPUT_1 = 7.0, 1.94, 6.86, 2.36
# linkage 2 (in)
FIXED_2, INPUT_2, COUPLER_2, OUTPUT_2 = 1.25, 2.39, 1.87, 1.26
OFFSET_DEG = 149.0  # alpha = phi + 149 degrees
OMEGA_RAD_PER_MIN = 450.0  # speed of the driving gear

theta_deg = np.arange(0, 361)  # 0, 1, ..., 360 degrees
theta = np.radians(theta_deg)
h = np.radians(1.0)  # grid step, rad

# %% [raw]
# # BEGIN QUESTION
# name: q1a
# points: [1, 1]

# %% [markdown]
# **Q1a — Newton with continuation.** Write a multivariable Newton–Raphson solver for the
# loop equations (real and imaginary parts) with their analytic Jacobian. Sweep θ from 0°
# to 360° in steps of 1°, starting from the guess (φ, ψ) = (45°, 60°) at θ = 0 and then
# **using the previous solution as the starting guess for the next θ**. Iterate until the
# Newton step is below 1e-10.
#
# Store the output angle in `phi` and the coupler angle in `psi`, one value per θ
# (361 values). Radians or degrees are both accepted; the check says which it read.

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


def four_bar_sweep(inputs, r_fixed, r_in, r_coupler, r_out, guess):
    """Output and coupler angles (rad) for each input angle (rad), by continuation."""
    # BEGIN SOLUTION
    start = np.array(guess, dtype=float)
    x = start
    result = np.empty((len(inputs), 2))
    for k, t in enumerate(inputs):

        def F(x):
            return np.array([
                r_out * np.cos(x[0]) + r_coupler * np.cos(x[1]) + r_in * np.cos(t + np.pi) - r_fixed,
                r_out * np.sin(x[0]) + r_coupler * np.sin(x[1]) + r_in * np.sin(t + np.pi),
            ])

        def J(x):
            return np.array([
                [-r_out * np.sin(x[0]), -r_coupler * np.sin(x[1])],
                [r_out * np.cos(x[0]), r_coupler * np.cos(x[1])],
            ])

        x = newton(F, J, x)  # the next solve starts here; not wrapped, so differences stay small
        if k == 0:  # Newton from a far guess may land whole turns away: back to the guess's turn
            x = start + (x - start + np.pi) % (2 * np.pi) - np.pi
        result[k] = x
    return result[:, 0], result[:, 1]
    # END SOLUTION


""" # BEGIN PROMPT
phi, psi = ..., ...  # replace each ... with an array of 361 angles: phi (output), psi (coupler)
""" # END PROMPT
phi, psi = four_bar_sweep(theta, FIXED_1, INPUT_1, COUPLER_1, OUTPUT_1, np.radians([45.0, 60.0]))  # SOLUTION NO PROMPT

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_phi_closes_loop_on_one_branch(phi):
    import numpy as np
    import kincheck as kc

    def gap(a):
        return kc.four_bar_gap(a, np.radians(np.arange(a.size)), 7.0, 1.94, 6.86, 2.36)

    unit, angles, residual = kc.read_angles("phi", phi, gap)
    print(f"`phi` read as {'radians' if unit == 'rad' else 'degrees'}")
    kc.inputs_in_degrees("phi", [phi], lambda t, a: kc.four_bar_gap(a, t, 7.0, 1.94, 6.86, 2.36))
    kc.closure("phi", residual, tol=1e-9)
    kc.continuity("phi", angles)
    kc.chained_four_bar_assembly("phi", phi)

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_phi_values(phi):
    import kincheck as kc

    kc.chained_four_bar_assembly("phi", phi)  # names the other assembly, where that is why the values differ
    kc.inputs_in_degrees("phi", [phi], lambda t, a: kc.four_bar_gap(a, t, 7.0, 1.94, 6.86, 2.36))  # and θ in degrees
    PHI = {10: 0.48101131173, 40: 0.801992851788, 70: 1.21832147982, 100: 1.64824558046, 130: 2.04593688727, 160: 2.31500391439, 190: 2.20276535076, 220: 1.71369175609, 250: 1.22685763437, 280: 0.852830800482, 310: 0.579419252725, 340: 0.417601762442}  # reference: phi
    kc.angles("phi", phi, PHI, tol=1e-6)

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if np.shape(phi) == theta.shape:  # once `phi` is computed
    fig, ax = plt.subplots()
    ax.plot(theta_deg, phi)
    ax.set_xlabel("θ (deg)")
    ax.set_ylabel("φ (rad, or deg if you kept degrees)")
    ax.set_title("Output angle of linkage 1")
    plt.show()

# %% [raw]
# # BEGIN QUESTION
# name: q1b
# points: [1, 1, 1]

# %% [markdown]
# **Q1b — dφ/dθ.** Compute dφ/dθ at every θ in two ways: the first **forward** difference
# (φᵢ₊₁ − φᵢ)/h and the **centred** difference (φᵢ₊₁ − φᵢ₋₁)/(2h). Store them in
# `dphi_fw` and `dphi_c` (361 values each; use any one-sided formula at the ends).
# Use the same angle unit for φ and for the step.

# %% [raw]
# # BEGIN SOLUTION

# %%
def forward_difference(y, h):
    """dy/dx by forward differences on a grid of step h."""
    # BEGIN SOLUTION
    d = np.empty_like(y)
    d[:-1] = (y[1:] - y[:-1]) / h
    d[-1] = (y[-1] - y[-2]) / h  # backward at the last point
    return d
    # END SOLUTION


def centred_difference(y, h):
    """dy/dx by centred differences on a grid of step h."""
    # BEGIN SOLUTION
    d = np.empty_like(y)
    d[1:-1] = (y[2:] - y[:-2]) / (2 * h)
    d[0] = (-3 * y[0] + 4 * y[1] - y[2]) / (2 * h)  # one-sided, second order
    d[-1] = (3 * y[-1] - 4 * y[-2] + y[-3]) / (2 * h)
    return d
    # END SOLUTION


dphi_fw = forward_difference(phi, h)  # SOLUTION
dphi_c = centred_difference(phi, h)  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_dphi_are_two_different_formulas(dphi_fw, dphi_c):
    import numpy as np
    import kincheck as kc

    fw = kc.array(dphi_fw, "dphi_fw")[1:-1]
    c = kc.array(dphi_c, "dphi_c")[1:-1]
    both = np.isfinite(fw) & np.isfinite(c)
    assert not np.allclose(fw[both], c[both], rtol=1e-9, atol=1e-12), (
        "`dphi_fw` and `dphi_c` are identical: one of them uses the other's formula"
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_dphi_centred(dphi_c):
    import kincheck as kc

    CENTRED = {10: 0.414283965924, 40: 0.745299788649, 70: 0.822866522745, 100: 0.806756122363, 130: 0.686503335805, 160: 0.25268110877, 190: -0.700963531508, 220: -1.01264948824, 250: -0.823267776406, 280: -0.612790094621, 310: -0.430894869195, 340: -0.148607150408}  # reference: dphi_centred
    FORWARD = {10: 0.423335776186, 40: 0.747933951388, 70: 0.823226771803, 100: 0.805832351818, 130: 0.682926280501, 160: 0.240248249112, 190: -0.714614613832, 220: -1.01139924675, 250: -0.819446899514, 280: -0.609655433751, 310: -0.427650811304, 340: -0.141470646941}  # reference: dphi_forward
    BACKWARD = {10: 0.405232155663, 40: 0.74266562591, 70: 0.822506273686, 100: 0.807679892908, 130: 0.690080391109, 160: 0.265113968429, 190: -0.687312449184, 220: -1.01389972974, 250: -0.827088653297, 280: -0.615924755492, 310: -0.434138927086, 340: -0.155743653875}  # reference: dphi_backward
    kc.series(
        "dphi_c", dphi_c, CENTRED, rtol=1e-5,
        alternatives=[
            (FORWARD, "this matches the forward difference; the question asks for centred"),
            (BACKWARD, "this matches the backward difference; the question asks for centred"),
        ],
        suspects=("deg",), step_rad=0.017453292519943295,  # h = 1° in radians
        flipped="the sign is flipped: check the order of the difference, (φᵢ₊₁ − φᵢ₋₁)/(2h)",
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_dphi_forward(dphi_fw):
    import kincheck as kc

    CENTRED = {10: 0.414283965924, 40: 0.745299788649, 70: 0.822866522745, 100: 0.806756122363, 130: 0.686503335805, 160: 0.25268110877, 190: -0.700963531508, 220: -1.01264948824, 250: -0.823267776406, 280: -0.612790094621, 310: -0.430894869195, 340: -0.148607150408}  # reference: dphi_centred
    FORWARD = {10: 0.423335776186, 40: 0.747933951388, 70: 0.823226771803, 100: 0.805832351818, 130: 0.682926280501, 160: 0.240248249112, 190: -0.714614613832, 220: -1.01139924675, 250: -0.819446899514, 280: -0.609655433751, 310: -0.427650811304, 340: -0.141470646941}  # reference: dphi_forward
    BACKWARD = {10: 0.405232155663, 40: 0.74266562591, 70: 0.822506273686, 100: 0.807679892908, 130: 0.690080391109, 160: 0.265113968429, 190: -0.687312449184, 220: -1.01389972974, 250: -0.827088653297, 280: -0.615924755492, 310: -0.434138927086, 340: -0.155743653875}  # reference: dphi_backward
    kc.series(
        "dphi_fw", dphi_fw, FORWARD, rtol=1e-5,
        alternatives=[
            (CENTRED, "this matches the centred difference; the question asks for forward"),
            (BACKWARD, "this matches the backward difference (φᵢ − φᵢ₋₁)/h; the question asks for forward (φᵢ₊₁ − φᵢ)/h"),
        ],
        suspects=("deg",), step_rad=0.017453292519943295,  # h = 1° in radians
        flipped="the sign is flipped: check the order of the difference, (φᵢ₊₁ − φᵢ)/h",
    )

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if np.shape(dphi_fw) == np.shape(dphi_c) == theta.shape:  # once both are computed
    fig, ax = plt.subplots()
    ax.plot(theta_deg, dphi_fw, label="forward")
    ax.plot(theta_deg, dphi_c, ":", label="centred")
    ax.set_xlabel("θ (deg)")
    ax.set_ylabel("dφ/dθ (rad/rad)")
    ax.legend()
    plt.show()

# %% [raw]
# # BEGIN QUESTION
# name: q1c
# points: [1, 1]

# %% [markdown]
# **Q1c — which is more accurate?** Set `order_forward` and `order_centred` to the order p
# of the truncation error O(hᵖ) of each formula, and `more_accurate` to `"forward"` or
# `"centred"`.

# %% [raw]
# # BEGIN SOLUTION

# %%
order_forward = 1  # SOLUTION
order_centred = 2  # SOLUTION
more_accurate = "centred"  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_answer_form(more_accurate, order_forward, order_centred):
    import kincheck as kc

    # read as the hidden check reads it: any case, any word that starts like "forward" or "centred"
    word = kc.text(more_accurate, "more_accurate")
    assert word.startswith(("forw", "cent")), (
        f'`more_accurate` should be "forward" or "centred", got {more_accurate!r}'
    )
    print(f'`more_accurate` read as "{"forward" if word.startswith("forw") else "centred"}"')
    for name, p in (("order_forward", order_forward), ("order_centred", order_centred)):
        value = kc.floats(p, name, "a number")
        assert value.size == 1 and not isinstance(p, bool), f"`{name}` should be a number, got {p!r}"

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_orders(more_accurate, order_forward, order_centred):
    import kincheck as kc

    forward = kc.floats(order_forward, "order_forward", "a number")
    centred = kc.floats(order_centred, "order_centred", "a number")
    assert forward.size == 1 and forward == 1, f"`order_forward` = {order_forward}: the forward difference has error h/2 f'', order 1"
    assert centred.size == 1 and centred == 2, f"`order_centred` = {order_centred}: the centred difference has error h²/6 f''', order 2"
    assert kc.text(more_accurate, "more_accurate").startswith("cent"), (
        "the centred difference is the more accurate one: its error falls like h², the forward one like h"
    )

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q2a
# points: [1, 1]

# %% [markdown]
# **Q2a — the second linkage.** Its input angle is α = φ + 149°. Solve linkage 2 with the
# same Newton continuation, starting from (β, γ) = (30°, 270°) at θ = 0. Store the output
# angle in `beta` and the coupler angle in `gamma` (361 values; radians or degrees).

# %% [raw]
# # BEGIN SOLUTION

# %%
alpha_in = phi + np.radians(OFFSET_DEG)  # SOLUTION
""" # BEGIN PROMPT
beta, gamma = ..., ...  # replace each ... with an array of 361 angles: beta (output), gamma (coupler)
""" # END PROMPT
beta, gamma = four_bar_sweep(alpha_in, FIXED_2, INPUT_2, COUPLER_2, OUTPUT_2, np.radians([30.0, 270.0]))  # SOLUTION NO PROMPT

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_beta_closes_loop_on_one_branch(phi, beta):
    import kincheck as kc

    _, angles, unit, residual = kc.chained_four_bar_angles(phi, beta)
    print(f"`beta` read as {'radians' if unit == 'rad' else 'degrees'}")
    kc.closure("beta", residual, tol=1e-9)
    kc.continuity("beta", angles)
    kc.chained_four_bar_assembly("beta", phi, beta)

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_beta_values(phi, beta):
    import kincheck as kc

    kc.chained_four_bar_assembly("beta", phi, beta)  # names the other assembly, where that is why the values differ
    BETA = {10: 1.23603736328, 40: 1.96570412988, 70: 2.92817258874, 100: 3.747693474, 130: 4.42245807272, 160: 4.88799096175, 190: 4.68846659713, 220: 3.86171648104, 250: 2.94604737807, 280: 2.0903207924, 310: 1.43923519488, 340: 1.11996147629}  # reference: beta
    kc.angles("beta", beta, BETA, tol=1e-6)

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q2b
# points: [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]

# %% [markdown]
# **Q2b — angular velocity and acceleration of the output.** With ω the speed of the
# driving gear,
#
# $$ \frac{d\beta}{dt} = \omega \frac{d\beta}{d\theta}, \qquad
#    \frac{d^2\beta}{dt^2} = \omega^2 \frac{d^2\beta}{d\theta^2}. $$
#
# Set `omega` to ω in rad/s. Compute, in rad/s and rad/s², at every θ:
#
# * `dbeta_dt_fw`: forward difference, `dbeta_dt_c`: centred difference;
# * `d2beta_dt2_fw`: the forward difference applied twice, (βᵢ₊₂ − 2βᵢ₊₁ + βᵢ)/h²,
#   `d2beta_dt2_c`: the centred second difference (βᵢ₊₁ − 2βᵢ + βᵢ₋₁)/h².
#
# Set `omega_100` and `alpha_100` to the **centred** angular velocity and acceleration at
# θ = 100° (a number, or your 0–360° array: the check picks θ = 100°). As a check, the
# assignment says the angular velocity is near 10 rad/s and the angular acceleration
# close to −25 rad/s² there.

# %% [raw]
# # BEGIN SOLUTION

# %%
def second_difference(y, h):
    """d²y/dx² by the centred second difference on a grid of step h."""
    # BEGIN SOLUTION
    d = np.empty_like(y)
    d[1:-1] = (y[2:] - 2 * y[1:-1] + y[:-2]) / h**2
    d[0] = (2 * y[0] - 5 * y[1] + 4 * y[2] - y[3]) / h**2  # one-sided, second order
    d[-1] = (2 * y[-1] - 5 * y[-2] + 4 * y[-3] - y[-4]) / h**2
    return d
    # END SOLUTION


omega = OMEGA_RAD_PER_MIN / 60.0  # SOLUTION
dbeta_dt_fw = omega * forward_difference(beta, h)  # SOLUTION
dbeta_dt_c = omega * centred_difference(beta, h)  # SOLUTION
d2beta_dt2_fw = omega**2 * forward_difference(forward_difference(beta, h), h)  # SOLUTION
d2beta_dt2_c = omega**2 * second_difference(beta, h)  # SOLUTION

# BEGIN SOLUTION NO PROMPT
i100 = np.flatnonzero(theta_deg == 100)[0]
# END SOLUTION
omega_100 = dbeta_dt_c[i100]  # SOLUTION
alpha_100 = d2beta_dt2_c[i100]  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_omega_in_rad_per_s(omega):
    import kincheck as kc

    kc.value("omega", omega, 7.5, rtol=1e-9, unit="rad/s", suspects=("rad/min", "rev"), flipped=kc.ROTATION)

# %%
def test_near_the_assignment_check(omega_100, alpha_100, omega, beta):
    import numpy as np
    import kincheck as kc

    # which unit slips fit is decided by what else was handed in, not by the size alone
    w = kc.at(omega, "omega", 0)
    slips = {7.5: ["deg"], 450.0: ["rad/min"], 7.5 / (2 * np.pi): ["rev"]}  # ω right, in rad/min, in rev/s
    suspects = next((s for w_is, s in slips.items() if abs(w - w_is) < 1e-6 * w_is), ["deg", "rad/min", "rev"])
    b = kc.array(beta, "beta")
    if suspects == ["deg"] and np.nanmax(np.abs(b)) <= 2 * np.pi + 0.5:
        suspects = []  # beta is in radians and omega is right: neither unit explains a miss
    h = np.radians(1.0)  # a missing division by h (or h²) is named first
    kc.band("omega_100", omega_100, 8.0, 12.0, about=10.0, deg=100, unit="rad/s", suspects=suspects, step_rad=h,
            flipped=kc.ROTATION)
    kc.band("alpha_100", alpha_100, -32.5, -17.5, about=-25.0, deg=100, unit="rad/s²", suspects=suspects, step_rad=h,
            flipped="the sign is flipped: ω² d²β/dθ² keeps its sign whichever way the gear turns; check the second difference (βᵢ₊₁ − 2βᵢ + βᵢ₋₁)/h²")

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_omega_100(omega_100):
    import kincheck as kc

    OMEGA_100 = 10.6328964886  # reference: omega_beta_100
    OMEGA_100_FW = 10.5999795275  # reference: omega_beta_fw_100
    OMEGA_100_BW = 10.6660146395  # reference: omega_beta_bw_100
    kc.value(
        "omega_100", omega_100, OMEGA_100, deg=100, rtol=5e-3, unit="rad/s", step_rad=0.017453292519943295,
        suspects=("deg", "rad/min", "rev"), alternatives=[
            (OMEGA_100_FW, "this matches the forward difference; the question asks for the centred difference"),
            (OMEGA_100_BW, "this matches the backward difference (np.diff one index early?); the question asks "
                           "for the centred difference"),
        ],
        flipped=kc.ROTATION,
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_alpha_100(alpha_100):
    import kincheck as kc

    ALPHA_100 = -28.3749666204  # reference: alpha_beta_100
    ALPHA_100_FW = -28.1265557975  # reference: alpha_beta_fw_100
    kc.value(
        "alpha_100", alpha_100, ALPHA_100, deg=100, rtol=5e-3, unit="rad/s²", step_rad=0.017453292519943295,
        suspects=("deg", "rad/min", "rev"),
        alternatives=[(ALPHA_100_FW, "this matches the forward difference applied twice; the question asks for the centred second difference")],
        flipped="the sign is flipped: ω² d²β/dθ² keeps its sign whichever way the gear turns; check the second difference (βᵢ₊₁ − 2βᵢ + βᵢ₋₁)/h²",
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_dbeta_dt_centred(dbeta_dt_c):
    import kincheck as kc

    CENTRED = {10: 5.98965846242, 40: 13.7121192715, 70: 12.9516698602, 100: 10.6329970835, 130: 8.62780841934, 160: 3.48986519077, 190: -9.09290899242, 220: -13.1258179125, 250: -12.9009693547, 280: -11.2400843708, 310: -7.0823888985, 340: -1.93099874476}  # reference: dbeta_dt_centred
    FORWARD = {10: 6.1539575112, 40: 13.7627006538, 70: 12.9095510357, 100: 10.5999795275, 130: 8.5867169372, 160: 3.32443065016, 190: -9.24976225005, 220: -13.1364439499, 250: -12.8885650637, 280: -11.1909207485, 310: -7.00095892645, 340: -1.83373672838}  # reference: dbeta_dt_forward
    BACKWARD = {10: 5.82535941365, 40: 13.6615378892, 70: 12.9937886847, 100: 10.6660146395, 130: 8.66889990148, 160: 3.65529973138, 190: -8.93605573479, 220: -13.1151918752, 250: -12.9133736458, 280: -11.289247993, 310: -7.16381887055, 340: -2.02826076113}  # reference: dbeta_dt_backward
    kc.series(
        "dbeta_dt_c", dbeta_dt_c, CENTRED, rtol=1e-5, unit="rad/s", step_rad=0.017453292519943295,
        suspects=("deg", "rad/min", "rev"),
        alternatives=[
            (FORWARD, "this matches the forward difference; the question asks for centred"),
            (BACKWARD, "this matches the backward difference; the question asks for centred"),
        ],
        flipped=kc.ROTATION,
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_dbeta_dt_forward(dbeta_dt_fw):
    import kincheck as kc

    CENTRED = {10: 5.98965846242, 40: 13.7121192715, 70: 12.9516698602, 100: 10.6329970835, 130: 8.62780841934, 160: 3.48986519077, 190: -9.09290899242, 220: -13.1258179125, 250: -12.9009693547, 280: -11.2400843708, 310: -7.0823888985, 340: -1.93099874476}  # reference: dbeta_dt_centred
    FORWARD = {10: 6.1539575112, 40: 13.7627006538, 70: 12.9095510357, 100: 10.5999795275, 130: 8.5867169372, 160: 3.32443065016, 190: -9.24976225005, 220: -13.1364439499, 250: -12.8885650637, 280: -11.1909207485, 310: -7.00095892645, 340: -1.83373672838}  # reference: dbeta_dt_forward
    kc.series(
        "dbeta_dt_fw", dbeta_dt_fw, FORWARD, rtol=1e-5, unit="rad/s", step_rad=0.017453292519943295,
        suspects=("deg", "rad/min", "rev"),
        alternatives=[(CENTRED, "this matches the centred difference; the question asks for forward")],
        flipped=kc.ROTATION,
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_d2beta_dt2_centred(d2beta_dt2_c):
    import kincheck as kc

    SECOND = {10: 141.204631092, 40: 43.47149589, 70: -36.1984632388, 100: -28.3764991377, 130: -35.3155275092, 160: -142.180514443, 190: -134.805444974, 220: -9.13240639217, 250: 10.6607028756, 280: 42.2530209027, 310: 69.9839058636, 340: 83.5905456819}  # reference: d2beta_dt2_second
    FORWARD_TWICE = {10: 141.834312181, 40: 38.0004175175, 70: -36.3696217271, 100: -28.1265557975, 130: -36.417933694, 160: -148.743488111, 190: -128.172584077, 220: -7.63602782686, 250: 11.1778128316, 280: 43.7021492814, 310: 70.1928583397, 340: 85.0328710984}  # reference: d2beta_dt2_forward_twice
    GRADIENT_TWICE = {10: 141.15020446, 40: 43.4968361987, 70: -36.1776377673, 100: -28.3810960095, 130: -35.3383400878, 160: -142.191413548, 190: -134.807188983, 220: -9.16255435504, 250: 10.667562033, 280: 42.252398488, 310: 69.9758272445, 340: 83.6149448045}  # reference: d2beta_dt2_gradient_twice
    kc.series(
        "d2beta_dt2_c", d2beta_dt2_c, SECOND, rtol=1e-4, unit="rad/s²", step_rad=0.017453292519943295,
        suspects=("deg", "rad/min", "rev"),
        alternatives=[
            (FORWARD_TWICE, "this matches the forward difference applied twice; the question asks for the centred second difference"),
            (GRADIENT_TWICE, "this matches np.gradient applied twice, a centred difference of step 2h; the question asks for the centred second difference (βᵢ₊₁ − 2βᵢ + βᵢ₋₁)/h²"),
        ],
        flipped="the sign is flipped: ω² d²β/dθ² keeps its sign whichever way the gear turns; check the second difference (βᵢ₊₁ − 2βᵢ + βᵢ₋₁)/h²",
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_d2beta_dt2_forward(d2beta_dt2_fw):
    import kincheck as kc

    SECOND = {10: 141.204631092, 40: 43.47149589, 70: -36.1984632388, 100: -28.3764991377, 130: -35.3155275092, 160: -142.180514443, 190: -134.805444974, 220: -9.13240639217, 250: 10.6607028756, 280: 42.2530209027, 310: 69.9839058636, 340: 83.5905456819}  # reference: d2beta_dt2_second
    FORWARD_TWICE = {10: 141.834312181, 40: 38.0004175175, 70: -36.3696217271, 100: -28.1265557975, 130: -36.417933694, 160: -148.743488111, 190: -128.172584077, 220: -7.63602782686, 250: 11.1778128316, 280: 43.7021492814, 310: 70.1928583397, 340: 85.0328710984}  # reference: d2beta_dt2_forward_twice
    kc.series(
        "d2beta_dt2_fw", d2beta_dt2_fw, FORWARD_TWICE, rtol=1e-4, unit="rad/s²", step_rad=0.017453292519943295,
        suspects=("deg", "rad/min", "rev"),
        forward=True, alternatives=[(SECOND, "this matches the centred second difference; the question asks for the forward difference applied twice")],
        flipped="the sign is flipped: ω² d²β/dθ² keeps its sign whichever way the gear turns; check the forward difference applied twice (βᵢ₊₂ − 2βᵢ₊₁ + βᵢ)/h²",
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_dbeta_dt_is_your_omega_times_the_centred_difference(dbeta_dt_c, omega, phi, beta):
    import numpy as np
    import kincheck as kc

    _, b, _, _ = kc.chained_four_bar_angles(phi, beta)
    b, w, h, degs = np.unwrap(b), kc.at(omega, "omega", 0), np.radians(1.0), range(10, 360, 30)
    kc.series(
        "dbeta_dt_c", dbeta_dt_c, kc.own_difference(b, degs, h, "centred", w), rtol=1e-6, unit="rad/s",
        alternatives=[(kc.own_difference(b, degs, h, "forward", w),
                       "this matches the forward difference of your `beta`; the question asks for centred")],
        suspects=("deg",), small_hint=None, step_rad=h,
        flipped="the sign is flipped against your own `omega` times the centred difference of your own `beta`: "
                "check the order of the difference, (βᵢ₊₁ − βᵢ₋₁)/(2h)",
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_d2beta_dt2_is_your_omega_squared_times_the_second_difference(d2beta_dt2_c, omega, phi, beta):
    import numpy as np
    import kincheck as kc

    _, b, _, _ = kc.chained_four_bar_angles(phi, beta)
    b, w, h, degs = np.unwrap(b), kc.at(omega, "omega", 0), np.radians(1.0), range(10, 340, 30)
    kc.series(
        "d2beta_dt2_c", d2beta_dt2_c, kc.own_difference(b, degs, h, "second", w**2), rtol=1e-6, unit="rad/s²",
        alternatives=[
            (kc.own_difference(b, degs, h, "forward_twice", w**2),
             "this matches the forward difference of your `beta` applied twice; the question asks for the centred second difference"),
            (kc.own_difference(b, degs, h, "gradient_twice", w**2),
             "this matches np.gradient applied twice to your `beta`, a centred difference of step 2h; the question asks for (βᵢ₊₁ − 2βᵢ + βᵢ₋₁)/h²"),
        ],
        suspects=("deg",), small_hint=None, step_rad=h,
        flipped="the sign is flipped against your own `omega` squared times the second difference of your own `beta`: "
                "check the second difference (βᵢ₊₁ − 2βᵢ + βᵢ₋₁)/h²",
    )

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if all(np.shape(y) == theta.shape for y in (dbeta_dt_fw, dbeta_dt_c, d2beta_dt2_fw, d2beta_dt2_c)):
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 7))
    ax1.plot(theta_deg, dbeta_dt_fw, label="forward")
    ax1.plot(theta_deg, dbeta_dt_c, ":", label="centred")
    ax1.set_ylabel("dβ/dt (rad/s)")
    ax1.legend()
    ax2.plot(theta_deg, d2beta_dt2_fw, label="forward of forward")
    ax2.plot(theta_deg, d2beta_dt2_c, ":", label="centred second difference")
    ax2.set_xlabel("θ (deg)")
    ax2.set_ylabel("d²β/dt² (rad/s²)")
    ax2.legend()
    plt.show()

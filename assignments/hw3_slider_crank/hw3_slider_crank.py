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
# name: hw3-slider-crank
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
# # Homework 3 — Piston acceleration by numerical differentiation
#
# The crank AB of a slider-crank, R = 80 mm long, turns counter-clockwise (ω > 0) at a constant 6000 rpm about A.
# The connecting rod BC is L = 200 mm long and the piston C moves along the horizontal
# axis through A. With θ the crank angle and θ₃ the rod angle, the loop is
#
# $$ R e^{i\theta} + L e^{i\theta_3} - x = 0 , $$
#
# where x = AC is the position of the piston. Find x(θ) and the piston acceleration ẍ for
# crank angles from 0° to 180° by numerical differentiation.
#
# Run `grader.check("q1")` (and so on) after each question.

# %%
import numpy as np
import matplotlib.pyplot as plt

R_MM, L_MM = 80.0, 200.0  # crank AB and rod BC, mm
SPEED_RPM = 6000.0  # crank speed

theta_deg = np.arange(0, 181)  # 0, 1, ..., 180 degrees
theta = np.radians(theta_deg)
h = np.radians(1.0)  # grid step, rad

# %% [raw]
# # BEGIN QUESTION
# name: q1
# points: [1, 1]

# %% [markdown]
# **Q1 — position.** Solve the loop for x at every θ of `theta` (the closed form, or
# Newton–Raphson on the real and imaginary parts) and store it in `x_piston`, in **mm**
# (181 values).

# %% [raw]
# # BEGIN SOLUTION

# %%
def piston_position(theta):
    """Piston position x (mm) at crank angles theta (rad)."""
    # BEGIN SOLUTION
    # R sin(theta) + L sin(theta3) = 0 and x = R cos(theta) + L cos(theta3)
    return R_MM * np.cos(theta) + np.sqrt(L_MM**2 - (R_MM * np.sin(theta)) ** 2)
    # END SOLUTION


x_piston = piston_position(theta)  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_position_in_stroke(x_piston):
    import numpy as np
    import kincheck as kc

    x = kc.array(x_piston, "x_piston", grid=(0, 180, 1))
    if np.all((x > 0.1) & (x < 0.3)):
        raise AssertionError("`x_piston` looks like metres; the question asks for millimetres")
    assert np.all((x >= 120 - 1e-6) & (x <= 280 + 1e-6)), (
        f"`x_piston` goes from {x.min():.4g} to {x.max():.4g} mm; the piston stays between "
        "L - R = 120 mm and L + R = 280 mm"
    )
    assert np.all(np.diff(x) <= 1e-9), (
        "`x_piston` should fall steadily from 0° to 180° (the piston moves from top to bottom dead centre)"
    )

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_position_values(x_piston):
    import kincheck as kc

    X = {0: 280.0, 20: 273.294924648, 40: 254.559715823, 60: 227.616630393, 80: 197.720534276, 100: 169.936825849, 120: 147.616630393, 140: 131.992604923, 160: 122.944105322, 180: 120.0}  # reference: x
    X_AT_RADIANS = {0: 280.0, 20: 218.834099981, 40: 137.555302665, 60: 122.314843289, 80: 174.684649797, 100: 264.840049072, 120: 259.665966553, 140: 168.159786676, 160: 121.177806497, 180: 141.575532828}  # reference: x_at_degrees_as_radians
    kc.series("x_piston", x_piston, X, grid=(0, 180, 1), rtol=1e-6, unit="mm", suspects=("mm",), alternatives=[
        (X_AT_RADIANS, "this is x at θ = 0, 1, 2, …, 180 rad, not at 0°, 1°, 2°, …, 180°: the angles were given in "
                       "degrees where `piston_position` takes radians; pass `theta`, not `theta_deg`"),
    ])

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q2
# points: [1]

# %% [markdown]
# **Q2 — crank speed.** Set `omega` to the crank speed in rad/s.

# %% [raw]
# # BEGIN SOLUTION

# %%
omega = SPEED_RPM * 2 * np.pi / 60  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_omega(omega):
    import math
    import kincheck as kc

    kc.value("omega", omega, 6000 * 2 * math.pi / 60, rtol=1e-9, unit="rad/s", suspects=("rpm", "rad/min", "rev", "deg"),
             flipped=kc.ROTATION)

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q3
# points: [1, 1, 1, 1, 1]

# %% [markdown]
# **Q3 — acceleration.** The crank speed is constant, so ẍ = ω² d²x/dθ². Compute it with the
# centred second difference
#
# $$ \frac{d^2x}{d\theta^2} \approx \frac{x(\theta + h) - 2x(\theta) + x(\theta - h)}{h^2}, \qquad h = 1° $$
#
# at every θ of `theta`. At 0° and 180° the formula needs x at −1° and 181°, outside
# `theta`: x is known at any angle, so compute it there too and use the same centred
# formula at the ends (a table of x alone would force a one-sided formula there, with a
# larger error). Store the acceleration in `a_piston`, in **m/s²** (181 values), and set `a_0` and
# `a_90` to the acceleration at θ = 0° and 90° (numbers, or your array: the check picks
# the angle). Check: at θ = 0 the exact acceleration is −Rω²(1 + R/L).

# %% [raw]
# # BEGIN SOLUTION

# %%
""" # BEGIN PROMPT
a_piston = ...
a_0 = ...
a_90 = ...
""" # END PROMPT
# BEGIN SOLUTION NO PROMPT
theta_ext = np.radians(np.arange(-1, 182))  # one more angle at each end
x_ext = piston_position(theta_ext) / 1000.0  # m
a_piston = omega**2 * (x_ext[2:] - 2 * x_ext[1:-1] + x_ext[:-2]) / h**2
a_0 = a_piston[0]
a_90 = a_piston[90]
# END SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_top_dead_centre(a_0):
    import math
    import kincheck as kc

    w = 6000 * 2 * math.pi / 60
    exact = -0.080 * w**2 * (1 + 80 / 200)
    kc.band("a_0", a_0, 1.01 * exact, 0.99 * exact, about=exact, deg=0, grid=(0, 180, 1),
            unit="m/s²", suspects=("deg", "rpm", "rad/min", "rev", "mm"), step_rad=math.radians(1.0),
            flipped="the sign is flipped: ẍ = ω² d²x/dθ², with no minus sign; reversing the crank does not change it (ω² > 0)")

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_a_0(a_0):
    import math
    import kincheck as kc

    A_0 = -44215.8277169  # reference: a_0
    kc.value("a_0", a_0, A_0, deg=0, grid=(0, 180, 1), rtol=5e-3, unit="m/s²", suspects=("deg", "rpm", "rad/min", "rev", "mm"),
             step_rad=math.radians(1.0),
             flipped="the sign is flipped: ẍ = ω² d²x/dθ², with no minus sign; reversing the crank does not change it (ω² > 0)")

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_a_90(a_90):
    import math
    import kincheck as kc

    A_90 = 13783.8351992  # reference: a_90
    kc.value("a_90", a_90, A_90, deg=90, grid=(0, 180, 1), rtol=5e-3, unit="m/s²", suspects=("deg", "rpm", "rad/min", "rev", "mm"),
             step_rad=math.radians(1.0),
             flipped="the sign is flipped: ẍ = ω² d²x/dθ², with no minus sign; reversing the crank does not change it (ω² > 0)")

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_acceleration_curve(a_piston):
    import math
    import kincheck as kc

    A = {0: -44215.8277169, 20: -39662.2185167, 40: -27006.8431306, 60: -9517.00516052, 80: 7355.12225638, 100: 18323.6906951, 120: 22065.728923, 140: 21380.7127557, 160: 19693.9058083, 180: 18949.6404501}  # reference: a
    kc.series("a_piston", a_piston, A, grid=(0, 180, 1), rtol=5e-3, unit="m/s²", suspects=("deg", "rpm", "rad/min", "rev", "mm"),
              step_rad=math.radians(1.0), flipped="the sign is flipped: ẍ = ω² d²x/dθ², with no minus sign; reversing the crank does not change it (ω² > 0)")

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_acceleration_is_your_omega_squared_times_the_second_difference(a_piston, x_piston, omega):
    import math
    import kincheck as kc

    # The centred second difference of x (m/rad², step 1°). `a_piston` comes from x computed beyond the grid, not
    # from `x_piston`: a slip in `x_piston` alone costs no check of it. An `a_piston` made from your own `x_piston`
    # (in mm) is yours too, and passes as well.
    D2X = {20: -0.10046119827, 40: -0.0684064701765, 60: -0.0241071723657, 80: 0.0186274238085, 100: 0.0464104269589, 120: 0.0558907968719, 140: 0.0541575294146, 160: 0.0498858044716}  # reference: d2x_second
    w = kc.at(omega, "omega", 0)
    h = math.radians(1.0)
    try:
        x = kc.array(x_piston, "x_piston", grid=(0, 180, 1)) / 1000.0  # m
        kc.series("a_piston", a_piston, kc.own_difference(x, D2X, h, "second", w**2), grid=(0, 180, 1), rtol=1e-6)
        return
    except AssertionError:
        pass  # not your own x_piston's: checked against x itself below
    kc.series("a_piston", a_piston, {d: w**2 * v for d, v in D2X.items()}, grid=(0, 180, 1), rtol=1e-6,
              unit="m/s²", suspects=("deg", "mm"), small_hint=None, step_rad=h,
              flipped="the sign is flipped: ẍ = ω² d²x/dθ², with no minus sign; reversing the crank does not change it (ω² > 0)")

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if np.shape(a_piston) == theta.shape:  # once `a_piston` is computed
    fig, ax = plt.subplots()
    ax.plot(theta_deg, np.asarray(a_piston) / 1000)
    ax.set_xlabel("crank angle θ (deg)")
    ax.set_ylabel("piston acceleration ẍ (km/s²)")
    plt.show()

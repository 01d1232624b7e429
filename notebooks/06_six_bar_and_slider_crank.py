# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Lesson 6 — Sliders: the six-bar and the slider-crank
#
# Two mechanisms whose output is a **slider**: the unknown is a length $x$, and we want its
# velocity $v = \dot x$ and acceleration $a = \ddot x$ for a crank turning at constant speed
# $\omega$ (so $\dot\theta = \omega$, $\ddot\theta = 0$):
#
# $$
# v = \omega\,\frac{dx}{d\theta}, \qquad a = \omega^2\,\frac{d^2x}{d\theta^2}.
# $$
#
# **The six-bar** (source document `001`): crank $O_2A = 1$ cm turning clockwise at
# $\omega_2 = -10$ rad/s, coupler $AB = 4$, ternary rocker about $O_4 = (3.7, -2)$ with
# $O_4B = 3$, $BC = 3.2$, $O_4C = 6$, rod $CD = 6.5$ to the slider $D$ on the line $y = 3$;
# $x$ is measured from $O_2$. Two loops:
#
# $$
# \begin{aligned}
# &l_2 e^{i\theta_2} + l_3 e^{i\theta_3} - l_{41} e^{i\theta_4} - (3.7 - 2i) = 0,\\
# &(3.7 - 2i) + l_{41} e^{i\theta_4} + l_{42} e^{i(\theta_4 + \beta)} - l_5 e^{i\theta_5} - (x + 3i) = 0,
# \end{aligned}
# $$
#
# with $\beta = \pi - \angle O_4BC$ fixed by the triangle $O_4BC$.
#
# **The slider-crank** (source document `004`, an exam): crank $R = 80$ mm, rod $L = 200$ mm,
# 6000 rpm; the piston position and its acceleration from 0° to 180° by a numerical second
# difference, against the analytic
# $x(\theta) = R\cos\theta + \sqrt{L^2 - R^2\sin^2\theta}$ differentiated twice.

# %%
# %matplotlib inline
import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import sympy as sp

from numkin import analytic, figures, kinematics, linkages, units
from numkin.compare import compare

# %% [markdown]
# ## 1. The six-bar: position
#
# numkin's `six_bar()` is the document's linkage on the document's assembly branch.

# %%
six = linkages.six_bar()
theta2 = np.radians(np.arange(0, 361, 1.0))
sweep6 = six.sweep(theta2)
print(sweep6)
figures.mechanism(sweep6, at=math.radians(30))

# %% [markdown]
# An independent reference: the same linkage built joint by joint from circle intersections
# in sympy — $A$ on the crank circle, $B$ where the circles about $A$ (radius 4) and $O_4$
# (radius 3) meet, $C$ from the rigid triangle, $D$ where the circle about $C$ (radius 6.5)
# meets the line $y = 3$ — gives $x_D(\theta_2)$ in closed form, and sympy differentiates it.

# %%
t = sp.Symbol("theta2", real=True)
l2, l3, l41, l42, l43, l5 = 1, 4, 3, sp.Rational(32, 10), 6, sp.Rational(13, 2)
o4x, o4y, y_d = sp.Rational(37, 10), -2, 3
Ax, Ay = l2 * sp.cos(t), l2 * sp.sin(t)
dist = sp.sqrt((o4x - Ax) ** 2 + (o4y - Ay) ** 2)
theta3_cf = sp.atan2(o4y - Ay, o4x - Ax) + sp.acos((l3**2 + dist**2 - l41**2) / (2 * l3 * dist))
Bx, By = Ax + l3 * sp.cos(theta3_cf), Ay + l3 * sp.sin(theta3_cf)
theta4_cf = sp.atan2(By - o4y, Bx - o4x)
beta = sp.pi - sp.acos((l41**2 + l42**2 - l43**2) / (2 * l41 * l42))
Cx, Cy = Bx + l42 * sp.cos(theta4_cf + beta), By + l42 * sp.sin(theta4_cf + beta)
xD = Cx - sp.sqrt(l5**2 - (Cy - y_d) ** 2)
closed_form = sp.lambdify(t, [xD, sp.diff(xD, t), sp.diff(xD, t, 2)], "numpy", cse=True)
x_cf, dx_cf, d2x_cf = (np.asarray(v, dtype=float) for v in closed_form(theta2))

print(f"max |x_numkin - x_closed_form| = {np.abs(sweep6['x'] - x_cf).max():.1e} cm")
assert np.abs(sweep6["x"] - x_cf).max() < 1e-10
for deg, ref in [(0, -1.77881), (90, -3.70858), (180, -5.84838)]:
    value = sweep6["x"][sweep6.index(math.radians(deg))]
    print(f"x_D({deg:3d} deg) = {value:.5f} cm   (reference {ref})")
    assert abs(value - ref) < 1e-5

# %% [markdown]
# ## 2. The six-bar: velocity and acceleration of the slider
#
# Three ways: numkin's analytic solution of the differentiated loop equations
# (`analytic.kinematics`), finite differences of the sampled $x$ (`kinematics.finite_difference`:
# centred difference and second difference, periodic over the full turn), and the sympy closed
# form. The crank turns clockwise: $\omega_2 = -10$ rad/s.

# %%
OMEGA6 = units.angular_speed("-10 rad/s")
exact6 = analytic.kinematics(sweep6, OMEGA6)
finite6 = kinematics.finite_difference(sweep6, OMEGA6, method="centred", second_method="second_difference")
print("finite differences:", finite6.attrs["method"], "/", finite6.attrs["second_method"],
      "periodic" if finite6.attrs["periodic"] else "open grid")

table6 = pd.DataFrame({
    "theta2 [deg]": [0, 90, 180, 270],
}).assign(
    **{
        "x [cm]": lambda d: [sweep6["x"][k] for k in d["theta2 [deg]"]],
        "v analytic [cm/s]": lambda d: exact6["v_x"].iloc[d["theta2 [deg]"]].to_numpy(),
        "v centred [cm/s]": lambda d: finite6["v_x"].iloc[d["theta2 [deg]"]].to_numpy(),
        "v closed form [cm/s]": lambda d: OMEGA6 * dx_cf[d["theta2 [deg]"]],
        "a analytic [cm/s^2]": lambda d: exact6["a_x"].iloc[d["theta2 [deg]"]].to_numpy(),
        "a second difference [cm/s^2]": lambda d: finite6["a_x"].iloc[d["theta2 [deg]"]].to_numpy(),
        "a closed form [cm/s^2]": lambda d: OMEGA6**2 * d2x_cf[d["theta2 [deg]"]],
    }
)
table6.round(4)

# %%
assert np.abs(exact6["v_x"] - OMEGA6 * dx_cf).max() < 1e-8
assert np.abs(exact6["a_x"] - OMEGA6**2 * d2x_cf).max() < 1e-7
err_v = np.abs(finite6["v_x"] - exact6["v_x"]).max()
err_a = np.abs(finite6["a_x"] - exact6["a_x"]).max()
print(f"max |v_centred - v_analytic|           = {err_v:.2e} cm/s  (max |v| = {np.abs(exact6['v_x']).max():.2f})")
print(f"max |a_second_diff - a_analytic|       = {err_a:.2e} cm/s^2 (max |a| = {np.abs(exact6['a_x']).max():.2f})")
assert err_v < 1e-3 * np.abs(exact6["v_x"]).max() and err_a < 1e-3 * np.abs(exact6["a_x"]).max()

# %%
deg = np.degrees(theta2)
fig, axes = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
axes[0].plot(deg, sweep6["x"], "k-")
axes[0].set_ylabel(r"$x_D$ [cm]")
for ax, col, label in [(axes[1], "v_x", r"$v_D$ [cm/s]"), (axes[2], "a_x", r"$a_D$ [cm/s$^2$]")]:
    ax.plot(deg, finite6[col], color="C1", lw=3, alpha=0.6, label="finite differences")
    ax.plot(deg, exact6[col], "k-", lw=1, label="analytic")
    ax.set_ylabel(label)
    ax.legend(loc="upper right", fontsize=8)
axes[2].set_xlabel(r"$\theta_2$ [deg]")
axes[2].set_xticks(range(0, 361, 60))
axes[0].set_title(r"six-bar: slider $D$, $\omega_2 = -10$ rad/s")
fig.tight_layout()
plt.show()

# %% [markdown]
# `compare` puts every second-derivative scheme beside the analytic acceleration:

# %%
cmp6 = compare(sweep6, OMEGA6, "a_x")
print(cmp6.summary.to_string(float_format="{:.2e}".format))

# %% [markdown]
# ## 3. The slider-crank at 6000 rpm
#
# The exam computed the piston acceleration at 500 points from 0° to 180° by the second
# difference and compared it with sympy's derivative. With $\omega = 6000$ rpm $= 200\pi$
# rad/s the exact values at the top dead centre ($\theta = 0$) and at $\theta = 90^\circ$ (crank
# perpendicular to the line of stroke; the dead centres are at 0° and 180°) follow from
# $x''(\theta)$ by hand:
#
# $$
# a(0) = -R\omega^2\Big(1 + \frac RL\Big), \qquad
# a(90^\circ) = \frac{R^2\omega^2}{\sqrt{L^2 - R^2}},
# $$
#
# from $x'' = -R\cos\theta - \dfrac{R^2\cos 2\theta}{S} - \dfrac{R^4\sin^2\theta\cos^2\theta}{S^3}$,
# $S = \sqrt{L^2 - R^2\sin^2\theta}$.

# %%
R, L = 80.0, 200.0  # mm
OMEGA = units.angular_speed("6000 rpm")
a0_hand = -R * OMEGA**2 * (1 + R / L) / 1000  # m/s^2
a90_hand = R**2 * OMEGA**2 / math.sqrt(L**2 - R**2) / 1000
print(f"omega = 6000 rpm = {OMEGA:.4f} rad/s")
print(f"by hand: a(0) = {a0_hand:.1f} m/s^2, a(90 deg) = {a90_hand:.1f} m/s^2")

crank = linkages.slider_crank(R, L)
theta = np.linspace(0.0, math.pi, 500)  # the exam's grid
h = theta[1] - theta[0]
sweep_sc = crank.sweep(theta)
exact_sc = analytic.kinematics(sweep_sc, "6000 rpm")
finite_sc = kinematics.finite_difference(sweep_sc, "6000 rpm")  # open grid: 0..180 deg
at = crank.sweep(np.radians([0.0, 90.0]))
a_at = analytic.kinematics(at, "6000 rpm")["a_x"].to_numpy() / 1000  # mm/s^2 -> m/s^2
print(f"numkin : a(0) = {a_at[0]:.1f} m/s^2, a(90 deg) = {a_at[1]:.1f} m/s^2")
assert abs(a_at[0] - (-44215.8)) < 0.1 and abs(a_at[1] - 13783.8) < 0.1
assert abs(a_at[0] - a0_hand) < 1e-6 and abs(a_at[1] - a90_hand) < 1e-6

# %% [markdown]
# The exam's own reference was sympy's second derivative of the closed form; so is ours:

# %%
th = sp.Symbol("theta", real=True)
x_exam = R * sp.cos(th) + sp.sqrt(L**2 - R**2 * sp.sin(th) ** 2)
a_exam = sp.lambdify(th, OMEGA**2 * sp.diff(x_exam, th, 2) / 1000, "numpy")(theta)
a_numkin = exact_sc["a_x"].to_numpy() / 1000
a_second = finite_sc["a_x"].to_numpy() / 1000
# on this open grid the centred formula (x[i+1] - 2x[i] + x[i-1])/h^2 needs a neighbour on each side:
# at 0 and 180 deg numkin uses the one-sided stencil (2x[0] - 5x[1] + 4x[2] - x[3])/h^2 instead
inner = np.s_[1:-1]
err_sc = np.abs(a_second - a_numkin)
print(f"max |a_numkin - a_sympy|                          = {np.abs(a_numkin - a_exam).max():.2e} m/s^2")
print(f"max |second difference - a_numkin|, interior      = {err_sc[inner].max():.2e} m/s^2 "
      f"(h = {math.degrees(h):.4f} deg; max |a| = {np.abs(a_numkin).max():.0f} m/s^2)")
print(f"|one-sided end stencil - a_numkin| at 0 and 180 deg = {err_sc[0]:.2e}, {err_sc[-1]:.2e} m/s^2")
assert np.abs(a_numkin - a_exam).max() < 1e-6
assert err_sc[inner].max() < 1e-3 * np.abs(a_numkin).max()

# %%
fig, (ax, ax_err) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=[3, 1])
deg = np.degrees(theta)
ax.plot(deg[inner], a_second[inner], color="C1", lw=3, alpha=0.6, label="second difference (interior points)")
ax.plot(deg[[0, -1]], a_second[[0, -1]], "s", color="C1", mfc="none", label="one-sided end stencil (0° and 180°)")
ax.plot(deg, a_numkin, "k-", lw=1, label="analytic")
ax.plot([0, 90], a_at, "ko")
for d, value in zip([0, 90], a_at):
    ax.annotate(f"{value:,.1f} m/s²", (d, value), textcoords="offset points", xytext=(10, 5))
ax.set_ylabel(r"piston acceleration [m/s$^2$]")
ax.set_title("slider-crank, R = 80 mm, L = 200 mm, 6000 rpm")
ax.legend(loc="lower right")
ax_err.semilogy(deg[inner], err_sc[inner], color="C1", label="second difference")
ax_err.semilogy(deg[[0, -1]], err_sc[[0, -1]], "s", color="C1", mfc="none", label="one-sided end stencil")
ax_err.legend(loc="upper center", fontsize=8)
ax_err.set_ylabel("|error| [m/s²]")
ax_err.set_xlabel(r"$\theta$ [deg]")
ax_err.set_xticks(range(0, 181, 30))
fig.tight_layout()
plt.show()

# %% [markdown]
# At the interior points the relative error of the second difference is about
# $\frac{h^2}{12}\,\max|x''''| / \max|x''|$ (both maxima fall at $\theta = 0$). The two end
# points have no neighbour outside the grid, so there numkin uses the one-sided stencil
# $(2x_0 - 5x_1 + 4x_2 - x_3)/h^2$, also of order $h^2$ but with error $\frac{11}{12}h^2 x''''$:
# eleven times the interior's at $\theta = 0$. (Computing $x$ at $-h$ and $\pi + h$, as homework 3
# does, keeps the centred formula at the ends.) The relative errors are the same at 6000 rpm as
# at 60 rpm: $\omega^2$ multiplies the numerical and the exact values alike. The large numbers
# ($4\times10^4$ m/s²) do not make the problem harder, as long as errors are judged relative to
# the quantity's scale.

# %%
d4x = sp.lambdify(th, sp.diff(x_exam, th, 4), "numpy")(theta)  # mm/rad^4, sympy's, from the closed form
d2x = sp.lambdify(th, sp.diff(x_exam, th, 2), "numpy")(theta)  # mm/rad^2
estimate = h**2 / 12 * np.abs(d4x).max() / np.abs(d2x).max()
rel = err_sc[inner].max() / np.abs(a_numkin).max()
rel_end = err_sc[0] / np.abs(a_numkin).max()
slow = crank.sweep(theta)
err_slow = np.abs(kinematics.finite_difference(slow, "60 rpm")["a_x"] - analytic.kinematics(slow, "60 rpm")["a_x"])
rel_slow = err_slow.to_numpy()[inner].max() / np.abs(analytic.kinematics(slow, "60 rpm")["a_x"]).max()
print(f"h^2/12 max|x''''| / max|x''|                  = {estimate:.3e}")
print(f"relative error, interior points               : {rel:.3e} at 6000 rpm, {rel_slow:.3e} at 60 rpm")
print(f"relative error, one-sided end stencil at 0 deg: {rel_end:.3e} ({rel_end / rel:.2f} x the interior's)")
assert abs(rel / estimate - 1) < 0.01
assert abs(rel_end / rel - 11) < 0.2
assert abs(rel / rel_slow - 1) < 1e-6

# %% [markdown]
# ## Questions
#
# 1. Engine books approximate $a \approx -R\omega^2(\cos\theta + \tfrac RL \cos 2\theta)$. Plot
#    its error against `exact_sc["a_x"]` over 0–180°. Where is it exact, and how large is the
#    error at 90°? (Expand $\sqrt{L^2 - R^2\sin^2\theta}$ to see where the formula comes from.)
# 2. The six-bar's crank turns clockwise. Which columns of `exact6` change sign if you pass
#    `+10` instead of `-10` rad/s, and which do not? Why?
# 3. `cmp6.summary` lists a spectral scheme. Why can it be used on the six-bar's full turn but
#    not on the slider-crank's half turn, and what does `finite_sc` use at 0° and 180° instead?

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
# # Lesson 3 — Differentiation schemes: forward, centred, second difference
#
# **The homework's questions** (source document `003`). With $\phi(\theta)$ and
# $\beta(\theta)$ known on a 1° grid (Lesson 2), estimate $d\phi/d\theta$ by a *forward* and a
# *centred* difference and say which is more accurate; then the angular velocity and
# acceleration of the output of linkage 2 for a driving speed $\omega = 450$ rad/min,
#
# $$
# \omega_\beta = \frac{d\beta}{dt} = \omega\,\frac{d\beta}{d\theta}, \qquad
# \alpha_\beta = \frac{d^2\beta}{dt^2} = \omega^2\,\frac{d^2\beta}{d\theta^2}
# \quad(\text{constant } \omega),
# $$
#
# with the check "at $\theta = 100^\circ$ the angular velocity is near 10 rad/s and the
# angular acceleration close to $-25$ rad/s²".
#
# Taylor expansion about $\theta_i$ with step $h$ gives the schemes and their leading errors:
#
# $$
# \begin{aligned}
# \text{forward:}\quad & \frac{y_{i+1} - y_i}{h} &&= y'_i + \tfrac{h}{2}\,y''_i + O(h^2),\\
# \text{centred:}\quad & \frac{y_{i+1} - y_{i-1}}{2h} &&= y'_i + \tfrac{h^2}{6}\,y'''_i + O(h^4),\\
# \text{second difference:}\quad & \frac{y_{i+1} - 2y_i + y_{i-1}}{h^2} &&= y''_i + \tfrac{h^2}{12}\,y''''_i + O(h^4),\\
# \text{forward of forward:}\quad & \frac{y_{i+2} - 2y_{i+1} + y_i}{h^2} &&= y''_i + h\,y'''_i + O(h^2).
# \end{aligned}
# $$
#
# The reference is exact: differentiating the loop equations $\mathbf F(\mathbf q(\theta),
# \theta) = 0$ gives linear systems for $\mathbf q'$ and $\mathbf q''$ with the position
# Jacobian, $J\mathbf q' = -\partial\mathbf F/\partial\theta$, solved by `numkin.analytic`.

# %%
# %matplotlib inline
import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from numkin import analytic, linkages, units
from numkin import derivatives as fd

OMEGA = units.angular_speed("450 rad/min")  # rad/s
print(f"omega = 450 rad/min = {OMEGA} rad/s")

mech = linkages.chained_four_bars()
theta = np.radians(np.arange(0, 361, 1.0))
h = theta[1] - theta[0]  # the step in rad: derivatives per rad
sweep = mech.sweep(theta)
k100 = sweep.index(math.radians(100))
theta_deg = np.degrees(theta)

dq, d2q = analytic.derivatives(sweep)  # d/dtheta and d2/dtheta2 of every unknown, per rad
row = {name: k for k, name in enumerate(sweep.unknowns)}

# %% [markdown]
# ## 1. $d\phi/d\theta$: forward against centred
#
# `numkin.derivatives` works on plain arrays. The sweep's angles are continuous (no `% 360`),
# so no $2\pi$ jump reaches a difference quotient. The grid 0°…360° is treated as open: the
# end points use one-sided stencils of the same order.

# %%
phi = sweep["phi"]
dphi_fw = fd.forward(phi, h)
dphi_c = fd.centred(phi, h)
dphi_exact = dq[row["phi"]]
d2phi_exact = d2q[row["phi"]]

fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(theta_deg, dphi_fw, label="forward", lw=2)
ax.plot(theta_deg, dphi_c, ":", label="centred", lw=2)
ax.plot(theta_deg, dphi_exact, "k-", lw=0.8, label="analytic")
ax.axhline(0, color="0.5", lw=0.5)
ax.set_xlabel(r"$\theta$ [deg]")
ax.set_ylabel(r"$d\phi/d\theta$ [rad/rad]")
ax.set_xticks(range(0, 361, 60))
ax.legend()
plt.show()
print(f"max |forward - analytic| = {np.abs(dphi_fw - dphi_exact).max():.2e}")
print(f"max |centred - analytic| = {np.abs(dphi_c - dphi_exact).max():.2e}")

# %% [markdown]
# To the eye the curves coincide (as the homework found). Their difference
# $\Delta = |(d\phi/d\theta)_C - (d\phi/d\theta)_{FW}|$ is mostly the forward scheme's error,
# $\Delta \approx \tfrac{h}{2}\,|\phi''|$, so it vanishes where $\phi'' = 0$ — where
# $d\phi/d\theta$ has its extrema:

# %%
delta = np.abs(dphi_c - dphi_fw)
predicted = h / 2 * np.abs(d2phi_exact)
zeros = theta_deg[np.flatnonzero(np.sign(d2phi_exact[:-1]) != np.sign(d2phi_exact[1:]))]
print(f"phi'' changes sign near theta = {zeros} deg")
print(f"max Delta = {delta.max():.3e};  max |Delta - h/2 |phi''|| = {np.abs(delta - predicted).max():.1e}")
assert np.abs(delta - predicted).max() < 0.01 * delta.max()
for z in zeros:  # Delta has a local minimum (near zero) at each sign change of phi''
    k = int(np.argmin(np.abs(theta_deg - z)))
    assert delta[k] < 0.05 * delta.max()

fig, ax1 = plt.subplots(figsize=(7, 4))
ax1.plot(theta_deg, delta, color="C4", label=r"$\Delta = |D_C - D_{FW}|$")
ax1.plot(theta_deg, predicted, "k:", lw=1, label=r"$\frac{h}{2}|\phi''|$")
ax1.set_xlabel(r"$\theta$ [deg]")
ax1.set_ylabel(r"$\Delta$ [rad/rad]", color="C4")
ax1.set_xticks(range(0, 361, 60))
ax2 = ax1.twinx()
ax2.plot(theta_deg, fd.second_difference(phi, h), color="C3", lw=0.8,
         label=r"$\phi''$ (second difference)")
ax2.axhline(0, color="C3", lw=0.4)
ax2.set_ylabel(r"$d^2\phi/d\theta^2$ [rad/rad$^2$]", color="C3")
for z in zeros:
    ax1.axvline(z, color="0.6", ls="--", lw=0.8)
ax1.set_title(r"$\Delta \to 0$ where $\phi'' = 0$")
fig.legend(loc="lower center", ncol=3)
fig.tight_layout(rect=(0, 0.08, 1, 1))
plt.show()

# %% [markdown]
# ## 2. $\omega_\beta$ and $\alpha_\beta$ at $\theta = 100^\circ$
#
# The exact values come from `analytic.kinematics`, which applies $\omega = \omega_{in} q'$ and
# $\alpha = \omega_{in}^2 q''$ to the analytic derivatives. The homework's own table (its
# "centred" acceleration is the second difference) is shown beside numkin's.

# %%
kin = analytic.kinematics(sweep, omega="450 rad/min")
beta = sweep["beta"]
omega_schemes = {
    "forward": OMEGA * fd.forward(beta, h),
    "centred": OMEGA * fd.centred(beta, h),
}
alpha_schemes = {
    "forward of forward": OMEGA**2 * fd.forward_of_forward(beta, h),
    "second difference": OMEGA**2 * fd.second_difference(beta, h),
}
homework = {"forward": 10.59897, "centred": 10.63198,
            "forward of forward": -28.11947, "second difference": -28.36941}
w_exact, a_exact = kin["omega_beta"].iloc[k100], kin["alpha_beta"].iloc[k100]
rows = [("omega_beta [rad/s]", "analytic", w_exact, np.nan, "≈ 10 (assignment)")]
rows += [("omega_beta [rad/s]", name, v[k100], homework[name], "") for name, v in omega_schemes.items()]
rows += [("alpha_beta [rad/s^2]", "analytic", a_exact, np.nan, "≈ -25 (assignment)")]
rows += [("alpha_beta [rad/s^2]", name, v[k100], homework[name], "") for name, v in alpha_schemes.items()]
check = pd.DataFrame(rows, columns=["quantity", "method", "numkin", "homework table", "note"])
check["numkin - analytic"] = [r[2] - (w_exact if r[0].startswith("omega") else a_exact) for r in rows]
check.round(5)

# %%
assert abs(w_exact - 10.6329) < 1e-4 and abs(a_exact - (-28.3750)) < 1e-4
assert abs(omega_schemes["centred"][k100] - 10.6330) < 1e-4
assert abs(omega_schemes["forward"][k100] - 10.59998) < 1e-5
assert abs(alpha_schemes["second difference"][k100] - (-28.3765)) < 1e-4
assert abs(alpha_schemes["forward of forward"][k100] - (-28.1266)) < 1e-4

# %% [markdown]
# The assignment's "near 10 rad/s" and "close to −25 rad/s²" are loose checks; the exact
# values are 10.6329 rad/s and −28.3750 rad/s². The homework's own table agrees with numkin's
# differences to three or four digits only: its Newton stopped when the relative step fell
# below $10^{-4}$, so its $\beta$ carried an error of its own. Lesson 4 re-runs that Newton and
# measures what a loose stopping rule costs.

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for ax, schemes, exact, label in [
    (axes[0], omega_schemes, kin["omega_beta"], r"$\omega_\beta$ [rad/s]"),
    (axes[1], alpha_schemes, kin["alpha_beta"], r"$\alpha_\beta$ [rad/s$^2$]"),
]:
    for (name, values), style in zip(schemes.items(), ["-", ":"]):
        ax.plot(theta_deg, values, style, lw=2, label=name)
    ax.plot(theta_deg, exact, "k-", lw=0.8, label="analytic")
    ax.plot(100, exact.iloc[k100], "ko")
    ax.annotate(f"{exact.iloc[k100]:.4f} at 100°", (100, exact.iloc[k100]), textcoords="offset points",
                xytext=(15, -15), arrowprops=dict(arrowstyle="->"))
    ax.set_xlabel(r"$\theta$ [deg]")
    ax.set_ylabel(label)
    ax.set_xticks(range(0, 361, 60))
    ax.legend(fontsize=8)
fig.tight_layout()
plt.show()

# %% [markdown]
# ## 3. Which is more accurate, and by how much?
#
# The leading error terms predict the errors from derivatives we already have:
# $e_{FW} \approx \omega\,\tfrac h2 \beta''$ and $e_C \approx \omega\,\tfrac{h^2}{6}\beta'''$
# ($\beta'''$ here by a centred difference of the exact $\beta''$). Predicted and measured:

# %%
d1b, d2b = dq[row["beta"]], d2q[row["beta"]]
d3b = fd.centred(d2b, h)
pred = pd.DataFrame({
    "measured error at 100° [rad/s]": [omega_schemes["forward"][k100] - w_exact,
                                       omega_schemes["centred"][k100] - w_exact],
    "predicted leading term [rad/s]": [OMEGA * h / 2 * d2b[k100], OMEGA * h**2 / 6 * d3b[k100]],
    "max |error| over the turn [rad/s]": [np.abs(omega_schemes["forward"] - kin["omega_beta"]).max(),
                                          np.abs(omega_schemes["centred"] - kin["omega_beta"]).max()],
}, index=["forward", "centred"])
print(pred.to_string(float_format="{:.3e}".format))
ratio_100 = abs(pred.iloc[0, 0] / pred.iloc[1, 0])
ratio_max = pred.iloc[0, 2] / pred.iloc[1, 2]
print(f"\ncentred is {ratio_100:.0f}x more accurate at 100 deg, {ratio_max:.0f}x in the worst-case error over the turn")
assert ratio_100 > 100 and ratio_max > 30
for k in range(2):
    assert abs(pred.iloc[k, 0] / pred.iloc[k, 1] - 1) < 0.05  # the leading term explains the error

# %% [markdown]
# The ratio of the two errors is roughly $\frac{3\,|\beta''|}{h\,|\beta'''|}$: with
# $h = 1^\circ = 0.0175$ rad the centred difference wins by two orders of magnitude. The gap
# grows as $h$ shrinks, because the errors scale as $h$ and $h^2$. Halving the step shows it:

# %%
fine = mech.sweep(np.radians(np.arange(0, 361, 0.5)))
h_fine = math.radians(0.5)
w_fine = analytic.kinematics(fine, OMEGA)["omega_beta"].to_numpy()
halving = {}
for name, fun in [("forward", fd.forward), ("centred", fd.centred)]:
    e_coarse = np.abs(OMEGA * fun(beta, h) - kin["omega_beta"].to_numpy())[1:-1].max()
    e_fine = np.abs(OMEGA * fun(fine["beta"], h_fine) - w_fine)[1:-1].max()
    halving[name] = e_coarse / e_fine
    print(f"{name:8s}: max error {e_coarse:.3e} (h = 1 deg) -> {e_fine:.3e} (h = 0.5 deg), ratio {e_coarse / e_fine:.2f}")
assert abs(halving["forward"] - 2) < 0.3 and abs(halving["centred"] - 4) < 0.6

# %% [markdown]
# ## 4. Where the weights come from
#
# Each scheme is declared by its offsets. Requiring the Taylor expansion of
# $\sum_k w_k\,y_{i+k}$ to give exactly $h\,y'_i$ (or $h^2 y''_i$) is a small linear system for
# the weights, solved here in exact fractions; the first Taylor term left over gives the order
# and the error constant. A new scheme is one call, and every function that takes a scheme by
# name accepts it:

# %%
from numkin import schemes

for name in ("forward", "centred", "second_difference", "five_point"):
    s = schemes.SCHEMES[name]
    print(f"{name:18s} offsets {s.offsets}, weights {[str(w) for w in s.weights]}, order {s.order}")
seven = schemes.register("seven_point", range(-3, 4), 1)
print("seven_point        weights", [str(w) for w in seven.weights], "order", seven.order,
      "error constant", seven.rule.interior.error_constant)
w7 = OMEGA * fd.differentiate(beta, h, "seven_point")
e7 = np.abs(w7 - kin["omega_beta"].to_numpy()).max()
print(f"seven_point: max error {e7:.2e} rad/s over the turn (centred: {pred.iloc[1, 2]:.2e} rad/s)")
assert seven.order == 6 and e7 < pred.iloc[1, 2] / 100
schemes.unregister("seven_point")

# %% [markdown]
# ## Questions
#
# 1. The forward-of-forward estimate is centred on $\theta_{i+1}$, not $\theta_i$. Shift it by
#    one sample (`np.roll`) and compare its error at 100° with the second difference's. What
#    order is the shifted estimate?
# 2. The ends of the open grid (0° and 360°) use one-sided stencils. Compare the error of
#    `fd.centred(beta, h)` at the first point with the interior error, then redo it with
#    `periodic=True` on the first 360 samples (`beta[:-1]`). What does `period_offset` mean for
#    $\beta$, and what is it here?
# 3. Predict, without computing, the error of the second difference at 100° for $h = 0.5^\circ$
#    from its value at $h = 1^\circ$. Then check it with the `fine` sweep.

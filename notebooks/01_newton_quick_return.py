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
# # Lesson 1 — Newton–Raphson on loop-closure equations
#
# **The quick-return mechanism** (source document `000`). A crank $O_2A$ of length $r_2$ turns
# about $O_2 = (0, r_1)$; the slider $A$ runs in a slotted rocker that pivots about
# $O_1 = (0, 0)$; the end $B$ of the rocker drives an output slider along the horizontal line
# $y = r_1 + r_6$, at a distance $r_5$ from $C = (0, r_1 + r_6)$. With $r_1 = 60$ mm,
# $r_2 = 40$ mm, $r_6 = 60$ mm and the crank at $\theta_2 = 30^\circ$, find $r_3 = O_1A$,
# $\theta_3$ (the rocker angle), $r_4 = O_1B$ and $r_5 = CB$.
#
# Two vector loops, $\vec r_1 + \vec r_2 - \vec r_3 = 0$ and
# $\vec r_1 + \vec r_6 + \vec r_5 - \vec r_4 = 0$ (with $\theta_4 = \theta_3$), give four
# scalar equations $\mathbf F(\mathbf q) = 0$ in $\mathbf q = (r_3, \theta_3, r_4, r_5)$:
#
# $$
# \begin{aligned}
# F_1 &= r_1 + r_2\sin\theta_2 - r_3\sin\theta_3 = 0, &
# F_2 &= r_2\cos\theta_2 - r_3\cos\theta_3 = 0,\\
# F_3 &= r_1 + r_6 - r_4\sin\theta_3 = 0, &
# F_4 &= r_5 - r_4\cos\theta_3 = 0.
# \end{aligned}
# $$
#
# Newton–Raphson linearises $\mathbf F$ at the current guess and solves for the correction:
#
# $$
# J(\mathbf q_k)\,\Delta\mathbf q = -\mathbf F(\mathbf q_k), \qquad
# \mathbf q_{k+1} = \mathbf q_k + \Delta\mathbf q, \qquad
# J_{ij} = \frac{\partial F_i}{\partial q_j}.
# $$
#
# Near a simple root the error is squared at every step,
# $\lVert \mathbf e_{k+1}\rVert \approx C \lVert \mathbf e_k\rVert^2$ (quadratic convergence),
# provided $J$ is the true Jacobian.

# %%
# %matplotlib inline
import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import sympy as sp

import numkin
from numkin import linkages

pd.set_option("display.precision", 6)
R1, R2, R6 = 60.0, 40.0, 60.0  # mm
THETA2 = math.radians(30.0)

# %% [markdown]
# ## 1. The hand solution
#
# Squaring and adding $F_1$ and $F_2$, and dividing $F_3$ by $F_4$, give the closed form
#
# $$
# r_3 = \sqrt{r_1^2 + r_2^2 + 2 r_1 r_2 \sin\theta_2},\quad
# \theta_3 = \operatorname{atan2}(r_1 + r_2\sin\theta_2,\; r_2\cos\theta_2),\quad
# r_4 = \frac{r_1 + r_6}{\sin\theta_3},\quad
# r_5 = \frac{r_2 (r_1 + r_6)\cos\theta_2}{r_1 + r_2\sin\theta_2}.
# $$

# %%
hand = {
    "r3 [mm]": math.sqrt(R1**2 + R2**2 + 2 * R1 * R2 * math.sin(THETA2)),
    "theta3 [deg]": math.degrees(math.atan2(R1 + R2 * math.sin(THETA2), R2 * math.cos(THETA2))),
}
hand["r4 [mm]"] = (R1 + R6) / math.sin(math.radians(hand["theta3 [deg]"]))
hand["r5 [mm]"] = R2 * (R1 + R6) * math.cos(THETA2) / (R1 + R2 * math.sin(THETA2))

# numkin: the ready-made mechanism, solved by Newton at theta2 = 30 deg
qr = linkages.quick_return(r1=R1, r2=R2, r6=R6)
sol = qr.solve(THETA2)
print(qr)
print(sol)
numkin_values = {
    "r3 [mm]": sol.x[0],
    "theta3 [deg]": math.degrees(sol.x[1]),
    "r4 [mm]": sol.x[2],
    "r5 [mm]": sol.x[3],
}
report_hand = {"r3 [mm]": 87.17, "theta3 [deg]": 66.58, "r4 [mm]": 130.75, "r5 [mm]": 51.96}
report_numerical = {"r3 [mm]": 87.17797887, "theta3 [deg]": math.degrees(13.72852909),
                    "r4 [mm]": 130.76696831, "r5 [mm]": 51.96152423}
table = pd.DataFrame(
    {
        "report, by hand": report_hand,
        "report, Newton (raw)": report_numerical,
        "closed form (this notebook)": hand,
        "numkin": numkin_values,
    }
)
table

# %%
for key in hand:
    assert abs(numkin_values[key] - hand[key]) < 1e-9, key
assert abs(numkin_values["r3 [mm]"] - 87.178) < 1e-3
assert abs(numkin_values["theta3 [deg]"] - 66.587) < 1e-3
assert abs(numkin_values["r4 [mm]"] - 130.767) < 1e-3
assert abs(numkin_values["r5 [mm]"] - 51.962) < 1e-3

# %% [markdown]
# Two entries of the report's table need a word.
#
# * Its **hand value of $r_4$ (130.75 mm) is an arithmetic slip.** The report writes
#   $r_4 = (r_1 + r_6)\,r_3 / (r_1 + r_2\sin\theta_2)$; evaluated with the *truncated*
#   $r_3 = 87.17$ instead of 87.178 it gives 130.755, written down as 130.75. With the
#   unrounded $r_3$ it is 130.767 mm — the value the report's own Newton code printed.
# * Its **Newton code printed $\theta_3 = 13.7285$**, in radians, which the report read as 66.58°.
#   That is not a conversion: see section 3.

# %%
r3_truncated = 87.17
print(f"(r1 + r6) r3 / (r1 + r2 sin θ2) with r3 = 87.17      : {(R1 + R6) * r3_truncated / (R1 + R2 * math.sin(THETA2)):.3f} mm")
print(f"(r1 + r6) r3 / (r1 + r2 sin θ2) with r3 = {hand['r3 [mm]']:.6f}: "
      f"{(R1 + R6) * hand['r3 [mm]'] / (R1 + R2 * math.sin(THETA2)):.3f} mm")

# %% [markdown]
# The mechanism at $\theta_2 = 30^\circ$, drawn from numkin's named points:

# %%
pts = qr.point_coordinates(sol.x[:, None], np.array([THETA2]))
P = {name: xy[:, 0] for name, xy in pts.items()}
fig, ax = plt.subplots(figsize=(6, 4))
ax.axhline(R1 + R6, color="0.6", ls="--", lw=1, label="slider line y = r1 + r6")
for a, b, style in [("O2", "A", "C0-"), ("O1", "B", "C1-"), ("C", "B", "C2:")]:
    ax.plot([P[a][0], P[b][0]], [P[a][1], P[b][1]], style, lw=3 if style.endswith("-") else 1.5)
for name, (x, y) in P.items():
    ax.plot(x, y, "ko", ms=4)
    ax.annotate(name, (x, y), textcoords="offset points", xytext=(5, 5))
ax.set_aspect("equal")
ax.set_xlim(-40, 110)
ax.set_xlabel("x [mm]")
ax.set_ylabel("y [mm]")
ax.set_title(r"quick-return mechanism at $\theta_2 = 30^\circ$")
ax.legend(loc="lower right")
plt.show()

# %% [markdown]
# ## 2. The Jacobian: symbolic or finite differences
#
# `numkin.newton` takes the residuals as sympy expressions (or as a Python function) and a
# choice of Jacobian: `"symbolic"` (differentiated once by sympy, then compiled),
# `"forward"` or `"central"` finite differences (steps scaled to $|x|$), or any callable.
# Here is the symbolic one:

# %%
r3, th3, r4, r5 = sp.symbols("r3 theta3 r4 r5", real=True)
q = [r3, th3, r4, r5]
eqs = [
    R1 + R2 * sp.sin(THETA2) - r3 * sp.sin(th3),
    R2 * sp.cos(THETA2) - r3 * sp.cos(th3),
    R1 + R6 - r4 * sp.sin(th3),
    r5 - r4 * sp.cos(th3),
]
sp.Matrix(eqs).jacobian(q)

# %% [markdown]
# We start every variant from the same rough guess — a sketch's reading,
# $r_3 = 80$, $\theta_3 = 60^\circ$, $r_4 = 120$, $r_5 = 60$ — and record the residual
# $\max_i |F_i| / r_1$ after every step (`NewtonResult.residual_norms`). For contrast, the
# *chord method* keeps the Jacobian of the first guess for all steps.

# %%
guess = np.array([80.0, math.radians(60.0), 120.0, 60.0])
scales = dict(fscale=R1, xscale=[R1, 1.0, R1, R1])  # residuals are lengths; theta3 is in rad

f_num = sp.lambdify([q], eqs, "numpy")
jac_num = sp.lambdify([q], sp.Matrix(eqs).jacobian(q), "numpy")
J_first = np.array(jac_num(guess), dtype=float)

runs = {
    "symbolic": numkin.newton(eqs, guess, unknowns=q, jacobian="symbolic", **scales),
    "forward FD": numkin.newton(eqs, guess, unknowns=q, jacobian="forward", **scales),
    "central FD": numkin.newton(eqs, guess, unknowns=q, jacobian="central", **scales),
    "chord (frozen J)": numkin.newton(lambda x: np.array(f_num(x)), guess,
                                      jacobian=lambda x: J_first, **scales),
}
history = pd.DataFrame({name: pd.Series(r.residual_norms) for name, r in runs.items()})
history.index.name = "iteration"
print(history.to_string(float_format="{:.2e}".format, na_rep=""))

# %%
for name, r in runs.items():
    assert r.converged, name
    assert abs(r.x[0] - hand["r3 [mm]"]) < 1e-8 and abs(math.degrees(r.x[1]) - hand["theta3 [deg]"]) < 1e-8
    orders = np.round(r.convergence_order(), 2) if "chord" not in name else "(not meaningful: see below)"
    print(f"{name:17s} iterations {r.iterations:2d}   order estimates {orders}")

assert np.allclose(runs["symbolic"].residual_norms[:4], [2.68e-1, 2.57e-2, 1.58e-4, 8.62e-9], rtol=0.01)
order = runs["symbolic"].convergence_order()
assert abs(order[-1] - 2) < 0.3  # quadratic
assert runs["chord (frozen J)"].iterations > 2 * runs["symbolic"].iterations

# %%
fig, ax = plt.subplots(figsize=(6, 4))
for (name, r), marker in zip(runs.items(), "osx^"):
    ax.semilogy(np.arange(r.residual_norms.size), np.maximum(r.residual_norms, 1e-17), marker=marker, label=name)
ax.axhline(np.finfo(float).eps, color="0.5", ls=":", label="machine epsilon")
ax.set_xlabel("Newton iteration k")
ax.set_ylabel(r"scaled residual $\max|F_i| / r_1$")
ax.set_title(r"quick-return, $\theta_2 = 30^\circ$")
ax.legend()
plt.show()

# %% [markdown]
# With the exact (symbolic) Jacobian the number of correct digits roughly doubles every step:
# $2.7\cdot10^{-1} \to 2.6\cdot10^{-2} \to 1.6\cdot10^{-4} \to 8.6\cdot10^{-9} \to 10^{-16}$.
# `convergence_order()` estimates the order $p$ from successive step sizes,
# $p_k = \log(s_{k+1}/s_k) / \log(s_k/s_{k-1})$; it approaches 2.
# The finite-difference curves lie on top of the symbolic one. How good is a difference
# Jacobian? Column $j$ of a forward difference is $(\mathbf F(\mathbf q + h_j\mathbf e_j) -
# \mathbf F(\mathbf q))/h_j$ with $h_j \approx \sqrt{\varepsilon}\,\max(|q_j|, s_j)$ (and
# $\varepsilon^{1/3}$ for central differences, $s_j$ the scale of unknown $j$), the rule
# `numkin.newton` documents. At the starting guess:

# %%
def fd_jacobian(x, central=False):
    eps = np.finfo(float).eps
    jac = np.empty((4, 4))
    for j, s_j in enumerate(scales["xscale"]):
        h = (eps ** (1 / 3) if central else math.sqrt(eps)) * max(abs(x[j]), s_j)
        e = np.zeros(4)
        e[j] = h
        if central:
            jac[:, j] = (np.array(f_num(x + e)) - np.array(f_num(x - e))) / (2 * h)
        else:
            jac[:, j] = (np.array(f_num(x + e)) - np.array(f_num(x))) / h
    return jac


J_exact = np.array(jac_num(guess), dtype=float)
for name, central in [("forward", False), ("central", True)]:
    rel = np.abs(fd_jacobian(guess, central) - J_exact).max() / np.abs(J_exact).max()
    print(f"{name} difference Jacobian: max relative deviation from the exact one {rel:.1e}")
    assert rel < 1e-6

# %% [markdown]
# Errors of $10^{-8}$ or less in $J$ change each Newton step only in its eighth digit or so,
# far below what matters until the very last iteration. The chord method's frozen Jacobian is
# a much cruder approximation of the true one, and the convergence drops to *linear*: the
# residual shrinks by a roughly constant factor per step.

# %%
ratios = history["chord (frozen J)"].dropna()
print("chord method, residual ratio per step:", np.round((ratios.values[1:] / ratios.values[:-1])[:8], 3))

# %% [markdown]
# ## 3. What the source code did: a fixed guess of ones
#
# The report's Newton started from $\mathbf q_0 = (1, 1, 1, 1)$ — 1 mm, 1 rad — **at every crank
# angle**, with a numerical Jacobian and the stopping rule $|\Delta q| < 10^{-6}$. numkin's
# `newton` reproduces its answer at 30°:

# %%
ones = numkin.newton(eqs, [1.0, 1.0, 1.0, 1.0], unknowns=q, jacobian="forward", **scales)
theta3_raw = ones.x[1]
print(ones)
print(f"theta3 = {theta3_raw:.8f} rad = {math.degrees(theta3_raw):.4f} deg")
turns = (theta3_raw - math.radians(hand['theta3 [deg]'])) / (2 * math.pi)
print(f"theta3 - 66.587 deg = {turns:.10f} full turns")
assert abs(theta3_raw - 13.72852909) < 1e-7  # the report's printed value
assert abs(turns - 2) < 1e-10  # 66.587 deg + 4 pi

# %% [markdown]
# $\theta_3 = 13.7285$ rad is $786.59^\circ = 66.587^\circ + 2\cdot 360^\circ$: the right
# configuration, but Newton's early steps from a poor guess threw the angle around and it
# converged two full turns away. The report printed the raw number and compared it, as if in
# degrees, with 66.58 — a coincidence that hid the problem. From another starting guess Newton
# finds the **other root** of the same equations: $r_3 < 0$ with $\theta_3$ turned by 180°,
# which satisfies $F = 0$ but is not the mechanism (a length cannot be negative).

# %%
other = numkin.newton(eqs, [-80.0, math.radians(-120.0), -130.0, 50.0], unknowns=q, **scales)
print(other)
print(f"r3 = {other.x[0]:.3f} mm, theta3 = {math.degrees(other.x[1]):.3f} deg "
      f"(= {hand['theta3 [deg]']:.3f} - 180), r4 = {other.x[2]:.3f} mm, r5 = {other.x[3]:.3f} mm")
assert other.converged and other.x[0] < 0
assert abs(math.degrees(other.x[1]) - (hand["theta3 [deg]"] - 180)) < 1e-8

# %% [markdown]
# ## 4. A fixed guess over a full turn
#
# Over a whole turn the fixed guess is worse: every angle is solved from scratch and Newton may
# land on either root, any number of turns away. numkin's `Mechanism.solve` does exactly one
# Newton solve from a given guess (no continuation), so it reproduces the report's loop;
# `Mechanism.sweep` instead starts each angle from the previous solution (Lesson 2).

# %%
theta2 = np.radians(np.arange(0, 360, 1.0))
fixed = np.array([qr.solve(t, guess=[1.0, 1.0, 1.0, 1.0]).x for t in theta2]).T
sweep = qr.sweep(theta2)
turns_off = np.round((fixed[1] - sweep["theta3"]) / (2 * np.pi), 6)
negative_r3 = fixed[0] < 0
print(f"{theta2.size} angles: {np.sum(turns_off == 0)} give theta3 on the right turn, "
      f"{np.sum(negative_r3)} land on the root with r3 < 0, "
      f"theta3 is off by up to {np.abs(turns_off).max():.1f} turns")
print(f"continuation sweep: r3 >= {sweep['r3'].min():.2f} mm everywhere, "
      f"theta3 from {np.degrees(sweep['theta3']).min():.2f} to {np.degrees(sweep['theta3']).max():.2f} deg")
assert np.all(sweep["r3"] > 0)
assert negative_r3.any()

# %%
fig, axes = plt.subplots(1, 2, figsize=(10, 4))
deg = np.degrees(theta2)
axes[0].plot(deg, np.degrees(fixed[1]), ".", ms=3, label="fixed guess (1, 1, 1, 1)")
axes[0].plot(deg, np.degrees(sweep["theta3"]), "k-", lw=2, label="numkin sweep (continuation)")
axes[0].set_xlabel(r"$\theta_2$ [deg]")
axes[0].set_ylabel(r"$\theta_3$ [deg]")
axes[0].set_title("the angle, as Newton returns it")
axes[0].legend()
axes[1].plot(deg, fixed[0], ".", ms=3, label="fixed guess (1, 1, 1, 1)")
axes[1].plot(deg, sweep["r3"], "k-", lw=2, label="numkin sweep")
axes[1].set_xlabel(r"$\theta_2$ [deg]")
axes[1].set_ylabel(r"$r_3$ [mm]")
axes[1].set_title("the slider position O1A")
axes[1].legend()
fig.tight_layout()
plt.show()

# %% [markdown]
# ## Questions
#
# 1. The hand solution needs the sign of $\cos\theta_2$ to pick $\theta_3$ (the report splits
#    $\theta_2 \in [-\pi/2, \pi/2]$ and $[\pi/2, 3\pi/2]$). Why does `atan2` make that split
#    unnecessary? What would Newton need instead to stay on the physical root?
# 2. The chord method's residual ratio is roughly constant. Estimate it from the spectral
#    radius of $I - J_0^{-1} J(\mathbf q^*)$, its largest eigenvalue in magnitude (compute both
#    matrices), and compare with the table. Why does a norm of the same matrix
#    (`np.linalg.norm`) give a much larger number, and which of the two governs the ratio after
#    many iterations?
# 3. Modify section 4 so that each angle starts from the previous angle's solution (still with
#    `qr.solve`). How many angles now land on the wrong root, and how many Newton iterations
#    does each angle take compared with the fixed guess?

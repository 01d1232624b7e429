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
# # Lesson 2 — Continuation over a full turn
#
# **The chained four-bars of the homework** (source document `003`). Linkage 1 (fixed link
# $r_1 = 7.0$, input $r_4 = 1.94$, coupler $r_3 = 6.86$, output $r_2 = 2.36$ in) is driven by
# the input angle $\theta$; its output angle $\phi$ drives linkage 2 (fixed 1.25, input 2.39,
# coupler 1.87, output 1.26 in) through the input angle $\alpha = \phi + 180^\circ - 31^\circ$.
# Written as the homework writes them, the loop equations are
#
# $$
# r_2 e^{i\phi} + r_3 e^{i\psi} + r_4 e^{i(\theta + \pi)} = r_1, \qquad
# r_2' e^{i\beta} + r_3' e^{i\gamma} + r_4' e^{i(\alpha + \pi)} = r_1',
# $$
#
# four real equations in $(\phi, \psi, \beta, \gamma)$. The assignment: increment $\theta$ from
# 0° to 360° in steps of 1°, solve by Newton at every step, and *use the previously found
# solution as the starting guess for the next value of* $\theta$. This lesson shows why.

# %%
# %matplotlib inline
import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import numkin
from numkin import linkages

theta = np.radians(np.arange(0, 361, 1.0))  # rad inside, degrees only on the axes
theta_deg = np.degrees(theta)

# %% [markdown]
# ## 1. numkin's sweep
#
# `linkages.chained_four_bars()` is the homework's linkage, with its starting guesses
# $(\phi, \psi) = (45^\circ, 60^\circ)$ and $(\beta, \gamma) = (30^\circ, 270^\circ)$ at
# $\theta = 0$. `Mechanism.sweep` continues from one angle to the next.

# %%
mech = linkages.chained_four_bars()
sweep = mech.sweep(theta)
print(sweep)
k100 = sweep.index(math.radians(100))
phi100, beta100 = math.degrees(sweep["phi"][k100]), math.degrees(sweep["beta"][k100])
print(f"phi(100 deg)  = {phi100:.4f} deg")
print(f"beta(100 deg) = {beta100:.4f} deg   (both checked against closed forms below)")
sweep.to_frame().iloc[[0, 1, 2, 100, 200, 360]]

# %% [markdown]
# An independent check of $\phi$: the joint $A = r_1 + r_4 e^{i\theta}$ is known, and $B$ lies at
# distance $r_2$ from the pivot $C$ (the origin) and $r_3$ from $A$ — the intersection of two
# circles,
# $\phi = \arg A \pm \arccos\dfrac{r_2^2 + |A|^2 - r_3^2}{2 r_2 |A|}$.
# Linkage 2 is the same construction with $A' = r_1' + r_4' e^{i\alpha}$, $\alpha = \phi + 149^\circ$:
# $\beta = \arg A' \pm \arccos\dfrac{r_2'^2 + |A'|^2 - r_3'^2}{2 r_2' |A'|}$, and
# $r_3' e^{i\gamma} = A' - r_2' e^{i\beta}$. Each sign is one assembly; the homework's is the one
# nearer its starting guesses at $\theta = 0$, and neither $\arccos$ argument reaches $\pm 1$ over
# the turn, so the sign stays the same all the way round.

# %%
r1, r4, r3, r2 = 7.0, 1.94, 6.86, 2.36
A = r1 + r4 * np.exp(1j * theta)
gap = np.arccos((r2**2 + np.abs(A) ** 2 - r3**2) / (2 * r2 * np.abs(A)))
phi_plus = np.angle(A) + gap  # the homework's branch (the '+' intersection)


def angle_gap(a, b):
    """|a - b| modulo 2 pi, in rad."""
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b)))))


print(f"max |phi_numkin - phi_circles| = {angle_gap(phi_plus, sweep['phi']).max():.2e} rad")
assert angle_gap(phi_plus, sweep["phi"]).max() < 1e-10

# linkage 2, driven by alpha = phi + 149 deg of the closed-form phi
q1, q4, q3, q2 = 1.25, 2.39, 1.87, 1.26
A2 = q1 + q4 * np.exp(1j * (phi_plus + math.radians(149)))
cos_gap2 = (q2**2 + np.abs(A2) ** 2 - q3**2) / (2 * q2 * np.abs(A2))
assert np.abs(cos_gap2).max() < 1  # never in line: one assembly all the way round
guess2 = np.radians([30.0, 270.0])  # the homework's (beta, gamma) at theta = 0
assemblies = []
for sign in (+1, -1):
    beta_s = np.angle(A2) + sign * np.arccos(cos_gap2)
    gamma_s = np.angle(A2 - q2 * np.exp(1j * beta_s))
    assemblies.append((angle_gap(beta_s[0], guess2[0]) + angle_gap(gamma_s[0], guess2[1]), beta_s, gamma_s))
_, beta_circles, gamma_circles = min(assemblies, key=lambda a: a[0])
print(f"phi(100 deg)  = {math.degrees(phi_plus[k100]):.4f} deg by the circles, {phi100:.4f} deg by numkin")
print(f"beta(100 deg) = {math.degrees(beta_circles[k100]) % 360:.4f} deg by the circles, {beta100:.4f} deg by numkin")
print(f"max |beta_numkin - beta_circles| = {angle_gap(beta_circles, sweep['beta']).max():.2e} rad, "
      f"max |gamma_numkin - gamma_circles| = {angle_gap(gamma_circles, sweep['gamma']).max():.2e} rad")
assert angle_gap(beta_circles, sweep["beta"]).max() < 1e-10
assert angle_gap(gamma_circles, sweep["gamma"]).max() < 1e-10

# %%
fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(theta_deg, np.degrees(sweep["phi"]), label=r"$\phi$ (output of linkage 1)")
ax.plot(theta_deg, np.degrees(sweep["beta"]), label=r"$\beta$ (output of linkage 2)")
ax.plot([100, 100], [phi100, beta100], "ko", ms=4)
ax.annotate(f"{phi100:.4f}°", (100, phi100), textcoords="offset points", xytext=(8, -12))
ax.annotate(f"{beta100:.4f}°", (100, beta100), textcoords="offset points", xytext=(8, 4))
ax.set_xlabel(r"$\theta$ [deg]")
ax.set_ylabel("angle [deg]")
ax.set_xticks(range(0, 361, 60))
ax.legend()
ax.set_title("chained four-bars over one turn")
plt.show()

# %% [markdown]
# ## 2. Continuation by hand, with `numkin.newton`
#
# Linkage 1 alone, written as a residual function with its exact Jacobian:
#
# $$
# \mathbf F(\phi, \psi) =
# \begin{pmatrix}
# r_2\cos\phi + r_3\cos\psi - r_4\cos\theta - r_1\\
# r_2\sin\phi + r_3\sin\psi - r_4\sin\theta
# \end{pmatrix},\qquad
# J = \begin{pmatrix} -r_2\sin\phi & -r_3\sin\psi\\ r_2\cos\phi & r_3\cos\psi\end{pmatrix}.
# $$

# %%
def F(x, th):
    phi, psi = x
    return np.array([
        r2 * np.cos(phi) + r3 * np.cos(psi) + r4 * np.cos(th + np.pi) - r1,
        r2 * np.sin(phi) + r3 * np.sin(psi) + r4 * np.sin(th + np.pi),
    ])


def J(x, th):
    phi, psi = x
    return np.array([[-r2 * np.sin(phi), -r3 * np.sin(psi)], [r2 * np.cos(phi), r3 * np.cos(psi)]])


def solve(th, guess):
    return numkin.newton(F, guess, args=(th,), jacobian=J, fscale=r1)


homework_guess = np.radians([45.0, 60.0])
print(f"at theta = 0: r2 + r3 = {r2 + r3:.2f} in, |A| = r1 + r4 = {abs(A[0]):.2f} in")
first = solve(0.0, homework_guess)
print(first)
whole_turns = math.floor(math.degrees(first.x[0]) / 360)
print(f"phi(0) = {first.x[0]:.4f} rad = {math.degrees(first.x[0]):.2f} deg "
      f"= {math.degrees(first.x[0]) % 360:.4f} deg {whole_turns:+d} turns")
assert whole_turns == -47
assert first.converged and abs(math.degrees(first.x[0]) % 360 - 24.3814) < 1e-4

# %% [markdown]
# Even the very first solve is instructive. At $\theta = 0$ the linkage is nearly stretched out
# ($r_2 + r_3 = 9.22$ against $|A| = 8.94$), the Jacobian is poorly conditioned along the
# way, and Newton's first steps from $(45^\circ, 60^\circ)$ are huge: it converges to the right
# configuration, $\phi = 24.38^\circ$, but **47 turns away**. The homework took every angle
# `% 360`, which hides this; numkin's sweep takes the solution nearest to the guess. We do the
# same here and then march, starting each angle from the previous solution:

# %%
start = homework_guess + np.remainder(first.x - homework_guess + np.pi, 2 * np.pi) - np.pi
continued, iters_continued = [], []
guess = start
for th in theta:
    r = solve(th, guess)
    assert r.converged
    continued.append(r.x)
    iters_continued.append(r.iterations)
    guess = r.x  # the previous solution is the next guess
continued = np.array(continued).T
print(f"max |phi_by_hand - phi_numkin| = {np.abs(continued[0] - sweep['phi']).max():.2e} rad")
assert np.abs(continued[0] - sweep["phi"]).max() < 1e-10

# %% [markdown]
# ## 3. A branch jump, provoked
#
# Now the mistake the assignment warns about: the same fixed guess $(45^\circ, 60^\circ)$ at
# every angle. A four-bar has two assemblies at each $\theta$ — the two intersections of the
# circles ($\pm$ above) — and Newton from a fixed, distant guess picks whichever basin the guess
# falls into.

# %%
fixed, iters_fixed, converged_fixed = [], [], []
for th in theta:
    r = solve(th, homework_guess)
    fixed.append(r.x)
    iters_fixed.append(r.iterations)
    converged_fixed.append(r.converged)
fixed, iters_fixed, ok = np.array(fixed).T, np.array(iters_fixed), np.array(converged_fixed)
# which circle intersection each converged solve found (the '-' one is the other assembly)
on_branch = ok & (angle_gap(fixed[0], phi_plus) < 1e-6)
other_branch = ok & (angle_gap(fixed[0], np.angle(A) - gap) < 1e-6)
assert np.array_equal(on_branch | other_branch, ok)  # every converged solve is one of the two
turns = np.round((fixed[0] - sweep["phi"]) / (2 * np.pi))
print(f"fixed guess: {ok.sum()} of {theta.size} angles converge; {other_branch.sum()} of them land on the "
      f"other assembly; of the {on_branch.sum()} on the homework's, {np.sum(on_branch & (turns != 0))} are "
      f"whole turns away")
for k in np.flatnonzero(~ok):
    print(f"theta = {theta_deg[k]:.0f} deg: no convergence, stopped after {iters_fixed[k]} iterations (maxiter)")
assert other_branch.sum() > 50 and 1 <= (~ok).sum() <= 3

iterations = pd.DataFrame({
    "fixed guess (45, 60) deg, converged solves": pd.Series(iters_fixed[ok]).describe(),
    "previous solution": pd.Series(iters_continued).describe(),
    "numkin sweep (predictor + Newton)": pd.Series(sweep.iterations[1:]).describe(),
}).loc[["mean", "min", "max"]]
assert iterations.loc["mean", "previous solution"] < iterations.loc["mean", "fixed guess (45, 60) deg, converged solves"]
assert abs(iterations.loc["mean", "numkin sweep (predictor + Newton)"] - iterations.loc["mean", "previous solution"]) < 1
iterations.round(2)

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
ax = axes[0]
ax.plot(theta_deg[ok], np.degrees(fixed[0][ok]) % 360, ".", ms=3, color="C3", label="fixed guess, % 360")
ax.plot(theta_deg, np.degrees(sweep["phi"]), "k-", lw=1.5, label="continuation")
ax.set_xlabel(r"$\theta$ [deg]")
ax.set_ylabel(r"$\phi$ [deg]")
ax.set_title("a fixed guess jumps between the two assemblies")
ax.legend(loc="center")

# the two assemblies at theta = 100 deg
ax = axes[1]
k = k100
Ak = A[k]
for phi_k, style, label in [
    (sweep["phi"][k], "k-", "continuation branch"),
    (np.angle(Ak) - gap[k], "C3--", "the other assembly"),
]:
    B = r2 * np.exp(1j * phi_k)
    xs = [0, B.real, Ak.real, r1]
    ys = [0, B.imag, Ak.imag, 0]
    ax.plot(xs, ys, style, marker="o", ms=4, label=label)
ax.plot([0, r1], [0, 0], color="0.6", lw=4, zorder=0)
ax.annotate("C", (0, 0), textcoords="offset points", xytext=(-12, -12))
ax.annotate("D", (r1, 0), textcoords="offset points", xytext=(4, -12))
ax.annotate("A", (Ak.real, Ak.imag), textcoords="offset points", xytext=(4, 4))
ax.set_aspect("equal")
ax.set_xlabel("x [in]")
ax.set_ylabel("y [in]")
ax.set_title(r"linkage 1 at $\theta = 100^\circ$")
ax.legend(loc="lower left", fontsize=8)
fig.tight_layout()
plt.show()

# %% [markdown]
# From the fixed guess, Newton lands on the other assembly at about half the angles, and at
# one angle (40°) it does not converge at all: it stops after its 50 allowed iterations, a
# failure the loop would have to check `converged` to notice. That solve is left out of the
# table's first column and of the plot. Which basin the guess falls into is decided in the last
# bits of the arithmetic: the same loop with $F$ written with $-r_4\cos\theta$ instead of
# $r_4\cos(\theta + \pi)$ puts two more angles on the homework's assembly.
#
# Starting from the previous solution keeps Newton inside the basin of the branch it is on,
# because a 1° step moves the solution by a little, and Newton converges from any guess close
# enough to a regular root. It is also much cheaper: compare the iteration counts in the table.
# numkin's sweep stays on the same branch and costs about as much per angle (a similar mean,
# one iteration more at its worst): it *predicts* the next solution with the tangent
# $\mathbf q' = -J^{-1}\,\partial\mathbf F/\partial\theta$ and corrects it with Newton, and
# it checks that the sign of $\det J$ — constant along a branch — never changes silently. What
# it adds is not speed but safety: a step that fails its checks (no convergence, a large
# correction, a changed sign of $\det J$) is halved and tried again (question 1).

# %% [markdown]
# ## 4. A branch jump, caught
#
# Continuation can still fail where the two branches **meet**: at a singular position,
# $\det J = 0$. numkin refuses to cross such a point silently.
#
# **A change point.** The parallelogram four-bar (ground 5, crank 2, coupler 5, rocker 2)
# satisfies $s + l = p + q$; at $\theta_2 = 0^\circ$ and $180^\circ$ all four links are
# collinear and the parallelogram and the crossed ("anti-parallelogram") assemblies meet.

# %%
para = linkages.four_bar(5, 2, 5, 2)
span = np.radians(np.arange(10, 371, 1.0))
try:
    para.sweep(span)
except numkin.BranchError as err:
    caught = err
print(type(caught).__name__, f"(kind={caught.kind!r}, input {math.degrees(caught.input_value):.3f} deg, "
      f"loop {caught.loop!r}):")
print(caught)
assert caught.kind == "change point" and abs(math.degrees(caught.input_value) - 180) < 0.01

# %% [markdown]
# With `on_singular="report"` the sweep records the event (and warns), and goes on along the
# smooth continuation — here the parallelogram, $\theta_4 = \theta_2$, $\theta_3 = 0$:

# %%
import warnings

with warnings.catch_warnings():
    warnings.simplefilter("ignore", numkin.SingularityWarning)
    reported = para.sweep(span, on_singular="report")
for event in reported.events:
    print(f"{event.kind:12s} at {math.degrees(event.input_value):8.3f} deg: {event.message}")
print(f"max |theta4 - theta2| = {np.abs(reported['theta4'] - span).max():.1e} rad, "
      f"max |theta3| = {np.abs(reported['theta3']).max():.1e} rad")
assert {e.kind for e in reported.events} >= {"change point"}

# %% [markdown]
# **A linkage that cannot go all the way round.** Ground 7, crank 4, coupler 3, rocker 5 is a
# non-Grashof triple rocker ($s + l = 10 > p + q = 9$): the "crank" only rocks. Asking for a
# full turn is an `AssemblyError` naming the reachable range; a sweep within that range works.

# %%
rocker = linkages.four_bar(7, 4, 3, 5)
print(linkages.grashof(7, 4, 3, 5))
try:
    rocker.sweep(theta)
except numkin.AssemblyError as err:
    print("AssemblyError:", err)
inside = rocker.sweep(np.radians(np.linspace(-88.9, 88.9, 179)))
print(inside)
try:
    linkages.four_bar(10, 6, 1, 1).sweep(theta)
except numkin.AssemblyError as err:
    print("AssemblyError:", err)

# %% [markdown]
# ## Questions
#
# 1. Repeat section 2 with steps of 10°, 30°, 60° and 120° (previous solution as the guess,
#    no predictor). Does the hand-made continuation stay on the homework's assembly at every
#    step? Check the sign that tells the two assemblies apart rather than the look of the
#    curve. Why is the previous solution so safe a guess for this linkage: how far is the
#    other assembly from it, compared with how far the solution moves in one step? What does
#    `mech.sweep` do between the points of a coarse grid? (Read the `max_step` argument of
#    `Mechanism.sweep`.)
# 2. The homework reduced every angle `% 360`. Give one reason that is harmless for a plot of
#    $\phi$ and one reason it is harmful for the finite differences of Lesson 3.
# 3. For the parallelogram linkage, which assembly would a sweep from $\theta_2 = 10^\circ$ to
#    $350^\circ$ be on after 180° if the machine were real? Why can no algorithm that sees only
#    the loop equations answer that?

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
# # Lesson 4 — Error against step, and error against run time
#
# Lesson 3 compared schemes on one grid. Here we vary the step $h$ and measure. A
# finite-difference estimate of an $n$-th derivative with truncation order $p$ has an error
#
# $$
# e(h) \;\approx\; \underbrace{C\,h^{p}}_{\text{truncation}} \;+\;
# \underbrace{\frac{\varepsilon\,|y|}{h^{n}}}_{\text{rounding}},
# $$
#
# where $\varepsilon \approx 2.2\times10^{-16}$ is the relative rounding error of the samples
# $y$ (or the solver's tolerance, if larger). For large $h$ the first term wins: on a log-log
# plot the error falls on a line of slope $p$. For small $h$ the second wins and the error
# *grows* again. The best step balances the two,
#
# $$
# h^\ast \sim \varepsilon^{1/(p+n)}, \qquad e(h^\ast) \sim \varepsilon^{p/(p+n)} .
# $$
#
# Everything here is measured on the homework's chained four-bars ($\omega_{in} = 450$
# rad/min, output angle $\beta$) with the tables of `numkin.report`.

# %%
# %matplotlib inline
import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from numkin import analytic, kinematics, linkages, report

pd.set_option("display.width", 160)
pd.set_option("display.max_columns", 20)
mech = linkages.chained_four_bars()
OMEGA = "450 rad/min"
CHECK = math.radians(100.0)
EPS = np.finfo(float).eps

# %% [markdown]
# ## 1. Convergence: error against $h$
#
# `report.convergence_table` solves a full turn on grids of 36 … 3600 points, differences
# $\beta$ with every scheme and compares with the analytic $\omega_\beta$ and $\alpha_\beta$.
# The observed order is $\log(e_{k-1}/e_k) / \log(h_{k-1}/h_k)$ between successive grids.

# %%
conv = report.convergence_table(mech, omega=OMEGA, quantity="beta", check_angle=CHECK)
print(conv.attrs["caption"])
max_err = conv.pivot_table(index="scheme", columns="points per turn", values="max rel error [-]", sort=False)
orders = conv.pivot_table(index="scheme", columns="points per turn", values="observed order [-]", sort=False)
print("max relative error over the turn")
print(max_err.to_string(float_format="{:.1e}".format))
print("\nobserved order")
print(orders.to_string(float_format="{:.2f}".format))

# %%
# formal orders 1, 2, 4 appear on the intermediate grids (before the rounding floor)
for scheme, p in [("forward", 1), ("centred", 2), ("five_point", 4),
                  ("second_difference", 2), ("forward_of_forward", 1), ("five_point_second", 4)]:
    measured = orders.loc[scheme, 360]
    print(f"{scheme:20s} formal order {p}, observed {measured:.3f} (180 -> 360 points)")
    assert abs(measured - p) < 0.15, scheme
# on the finest grid the five-point first derivative still converges, the five-point second does not:
# its error falls only about 3.4-fold from 1440 to 3600 points (order 4 would be 2.5**4 = 39-fold), an order
# near 1.3 that the table leaves blank, at the round-off floor
fall = max_err.loc["five_point_second", 1440] / max_err.loc["five_point_second", 3600]
print(f"five_point_second from 1440 to 3600 points: error / {fall:.1f} (order {np.log(fall) / np.log(2.5):.2f})")
assert orders.loc["five_point", 3600] > 3.5 and np.isnan(orders.loc["five_point_second", 3600]) and 3.0 < fall < 4.0
# the spectral schemes get worse beyond 180 points: tens of times (first), hundreds of times (second)
assert max_err.loc["spectral", 3600] > 10 * max_err.loc["spectral", 180]
assert max_err.loc["spectral_second", 3600] > 100 * max_err.loc["spectral_second", 180]

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
for ax, derivative, title in [(axes[0], 1, r"$\omega_\beta$ (first derivative)"),
                              (axes[1], 2, r"$\alpha_\beta$ (second derivative)")]:
    part = conv[conv["quantity"].str.startswith("omega" if derivative == 1 else "alpha")]
    for scheme, rows in part.groupby("scheme", sort=False):
        ax.loglog(np.radians(rows["h [deg]"]), rows["max rel error [-]"], "o-", ms=4, label=scheme)
    h_ref = np.radians(np.array([10.0, 0.1]))
    for p, y0 in [(1, 2e-1), (2, 2e-2), (4, 3e-3)]:
        ax.loglog(h_ref, y0 * (h_ref / h_ref[0]) ** p, "k:", lw=1)
        ax.annotate(f"slope {p}", (h_ref[1], y0 * (h_ref[1] / h_ref[0]) ** p), fontsize=8,
                    textcoords="offset points", xytext=(4, 0))
    ax.set_xlabel("h [rad]")
    ax.set_title(title)
    ax.legend(fontsize=7, loc="lower right")
axes[0].set_ylabel(r"max relative error over the turn")
fig.tight_layout()
plt.show()

# %% [markdown]
# Each scheme falls on its line — slope 1 for forward (and forward-of-forward), 2 for centred
# and the second difference, 4 for five-point and Richardson — until it meets a floor. Up to
# 3600 points only the five-point *second* derivative meets it among the difference schemes:
# from 1440 to 3600 points its error falls about 3.4-fold instead of 39-fold (an order near 1.3,
# which the table leaves blank: its caption names the schemes whose errors reached the
# round-off floor), while the five-point first derivative still converges at order 4 there.
# The spectral (FFT) schemes converge faster than any power of $h$ on this smooth periodic
# motion, reach the floor by 180 points, and then get clearly *worse* as the grid is refined —
# the first derivative tens of times worse from 180 to 3600 points, the second derivative
# hundreds of times (slopes near $-1$ and $-2$, blank in the table): the floor is set by the
# positions' own accuracy divided by $h$ (or $h^2$), not by the scheme.

# %% [markdown]
# ## 2. The rounding floor: the V-curve and the optimal step
#
# `report.roundoff_table` takes the position at $\theta = 100^\circ$ on the sweep's branch and
# its neighbours $\theta + k h$ (the offsets $k$ of each scheme's stencil), each solved by
# numkin's Newton, for $h$ from $10^{-1}$ down to $10^{-12}$ rad, and differences them. The
# complex step, $q'(\theta) = \operatorname{Im} q(\theta + ih)/h$, subtracts nothing and so
# has no floor. This is the table `numkin report homework` writes (`homework-roundoff.md`).
#
# Where is the best step? Taking the smallest error of the scan would pick a *lucky* step,
# where rounding errors happen to cancel, one or two decades below its neighbours, and a
# different one for every angle. The table fits the two lines of the error model instead —
# the truncation line $C_t h^p$ and the rounding line $C_r \varepsilon / h^n$, each by a median
# over the scan — and takes their intersection: the **measured optimal h**, with the fitted
# curve's error there, and, beside it, the error measured at that very step.

# %%
rnd = report.roundoff_table(mech, quantity="beta", check_angle=CHECK)
steps = [c for c in rnd.columns if c.startswith("rel error at h = ")]
h_values = np.array([float(c.split("= ")[1].split(" rad")[0]) for c in steps])
print(report.format_text(rnd))

# %%
scan = rnd.attrs["scan"]  # every step of the scan (8 per decade) and each scheme's error there
fig, ax = plt.subplots(figsize=(7.5, 4.8))
for k, (_, row) in enumerate(rnd.iterrows()):
    color = f"C{k}"
    ax.loglog(scan["h [rad]"], np.maximum(scan[row["scheme"]], 1e-17), "-", lw=0.8, color=color, alpha=0.6)
    ax.loglog(h_values, np.maximum(row[steps].to_numpy(dtype=float), 1e-17), "o", ms=4, color=color,
              label=row["scheme"])
    if np.isfinite(row["measured optimal h [rad]"]):
        ax.loglog(row["measured optimal h [rad]"], row["rel error at measured optimal h [-]"], "*", ms=12,
                  color=color, markeredgecolor="black", markeredgewidth=0.5)
    if row["scheme"] != "complex step":
        ax.loglog(row["textbook optimal h [rad]"], row["rel error on fitted curve at textbook h [-]"], "D", ms=6,
                  mfc="white", color=color)
ax.axhline(EPS, color="0.5", ls=":", lw=1)
ax.annotate("machine epsilon", (1e-12, EPS), textcoords="offset points", xytext=(0, 4), fontsize=8)
ax.set_xlabel("step h [rad]")
ax.set_ylabel(r"relative error at $\theta = 100^\circ$ [-]")
ax.set_title("the V-curve: rounding (left, small h) against truncation (right, large h)\n"
             "star: measured optimum, diamond: textbook step (both on the fitted lines)", fontsize=10)
ax.legend(fontsize=8, loc="upper center")
plt.show()

# %%
table = rnd.set_index("scheme")
second = table.loc["second_difference"]
e4, e8, e9 = (second[f"rel error at h = {h} rad [-]"] for h in ("1e-04", "1e-08", "1e-09"))
print(f"second difference, h = 1e-4 rad: relative error {e4:.2g}")
print(f"second difference, h = 1e-8 rad: relative error {e8:.2g}, that is {100 * e8:.0f} %")
print(f"second difference, h = 1e-9 rad: relative error {e9:.2g}")
assert e8 > 10 and e9 > 1e3  # wrong by more than 1000 % and more than 100 000 %
for scheme in ("forward", "centred", "five_point", "second_difference"):
    row = table.loc[scheme]
    ratio = row["measured optimal h [rad]"] / row["textbook optimal h [rad]"]
    print(f"{scheme:18s} measured h* = {row['measured optimal h [rad]']:.2g} rad "
          f"(error {row['rel error at measured optimal h [-]']:.2g}), textbook {row['textbook rule']} = "
          f"{row['textbook optimal h [rad]']:.2g} rad: ratio {ratio:.2f}")
    assert 1 < ratio < 5  # the same order of magnitude, a few times larger: C_t and C_r are not 1
cs = table.loc["complex step"]
print(f"complex step: {cs['rel error at h = 1e-01 rad [-]']:.2g} at h = 0.1, {cs['rel error at h = 1e-06 rad [-]']:.2g} "
      f"at 1e-6, at most {cs[steps[6:]].max():.2g} for h <= 1e-7 rad")

# %% [markdown]
# Reading the V-curves: a *smaller step is not always better*. The second difference divides
# by $h^2$: at $h = 10^{-8}$ rad its error is more than ten times the value itself (the
# numbers are printed above), and at $10^{-9}$ rad more than a thousand times, even though every
# position it uses is correct to about 16 digits. Its best step is near
# $\varepsilon^{1/4} \approx 10^{-4}$ rad; the centred difference does best near
# $\varepsilon^{1/3}$, the five-point formula near $\varepsilon^{1/5}$, the forward difference
# near $\sqrt\varepsilon$. The measured optima have the textbook's order of magnitude but are
# a few times larger here (the ratios are printed above): the textbook takes
# $C_t = C_r = 1$. The complex step has no rounding floor but does have a truncation error,
# $h^2 |\beta^{(3)}/(6\beta')|$; it reaches the level of machine epsilon (a few $10^{-16}$)
# only for $h \le 10^{-7}$ rad and stays there down to the smallest $h$.

# %% [markdown]
# ## 3. Work against precision
#
# Accuracy costs work: a finer grid has more points for Newton to solve and for a scheme to
# difference. `report.work_precision_table` counts that work (the evaluations of the loop
# equations a sweep and a derivative spend: the same in every run) and times both (medians of
# repeats — **times vary from run to run and machine to machine**), for every scheme and grid,
# beside the analytic solution and the complex step. The front below, and the figure, are by work.

# %%
wp = report.work_precision_table(mech, omega=OMEGA, quantity="beta", grids=(36, 72, 180, 360, 720, 1440), repeat=3)
work_col, front_col = "work [evaluations]", "Pareto front by work"
time_col = [c for c in wp.columns if c.startswith("sweep + derivative time")][0]
cost = wp[work_col]  # the sweep's evaluations plus the derivative's
print(wp.attrs["caption"])
print(wp[wp[front_col]][["method", "quantity", "points per turn", work_col, time_col, "max rel error [-]"]]
      .to_string(index=False, float_format="{:.3g}".format))

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
for ax, prefix in zip(axes, ("omega", "alpha")):
    part = wp[wp["quantity"].str.startswith(prefix)]
    for method, rows in part.groupby("method", sort=False):
        ax.loglog(cost[rows.index], np.maximum(rows["max rel error [-]"], 1e-16), "o-", ms=4, lw=0.8,
                  label=method)
    ax.set_xlabel("work [evaluations of the loop equations]")
    ax.set_title(part["quantity"].iloc[0])
    ax.legend(fontsize=7)
axes[0].set_ylabel("max relative error over the turn")
fig.tight_layout()
plt.show()

# %% [markdown]
# The cheapest method for a wanted accuracy, read off the front by work
# (`report.cheapest_table(wp, by="work")`):

# %%
print(report.cheapest_table(wp, by="work").to_string(index=False, float_format="{:.3g}".format))

# %% [markdown]
# By time (`report.cheapest_table(wp)`, the default) the choice is not so sharp: up to a few
# hundred points per turn a sweep takes about the same time whatever its grid (a dozen nodes
# solved one after another, then one batch of Newton steps on whole arrays), so which of the
# coarse grids is fastest changes from run to run. The shape does not: the analytic
# solution costs about as much as one sweep and is exact to rounding. Among the difference
# schemes, high order pays, because the number of points needed for a given error falls so
# fast with the order. From the convergence table (extrapolated with the observed order where
# the grids stop short):

# %%
target = 1e-4
for scheme in ("forward", "centred", "five_point", "spectral"):
    errs = max_err.loc[scheme]
    ok = errs[errs <= target]
    if len(ok):
        print(f"{scheme:11s}: max rel error <= {target:g} from {ok.index[0]} points per turn on")
    else:
        n_last, p = errs.index[-1], orders.loc[scheme].iloc[-1]
        needed = n_last * (errs.iloc[-1] / target) ** (1 / p)
        print(f"{scheme:11s}: about {needed:,.0f} points per turn (extrapolated, order {p:.2f})")

# %% [markdown]
# ## 4. The cost of a loose Newton tolerance
#
# Every sample of $\beta$ carries the error $\delta$ that Newton left. A first difference turns
# it into an error $\sim\delta/h$ of $\omega$, a second difference into $\sim 4\delta/h^2$ of
# $\alpha$: with $h = 1^\circ$, $1/h^2 \approx 3300$. `report.tolerance_table` solves the turn
# with three loose rules at $10^{-4}$ — the absolute step rule $\lVert\Delta x\rVert_2 < 10^{-4}$
# of report 001, the relative step rule $\lVert\Delta x\rVert_2 / \lVert x\rVert_2 < 10^{-4}$ of
# homework 003 (loop by loop, as the homework does it) and the residual rule $\max|F| < 10^{-4}$
# — and with numkin's own rule. On the homework the absolute step rule changes $\alpha_\beta$ by
# no more than numkin's tight sweep does (max error 0.033 % of $\max|\alpha_\beta|$ both); the
# residual rule spoils it by 12.7 % of $\max|\alpha_\beta|$ (26.1 rad/s² at 173°, 7.5 % of its
# range); the relative rule reproduces the homework's printed values at 100° but leaves its
# first point, reached from the far guess, loose: $\alpha_\beta$ is off by 126 rad/s² at 1° and
# 359° (61 % of $\max|\alpha_\beta|$), where that point is a neighbour in the stencil, and by
# 252 rad/s² (123 %) at 0°, where it is the centre, weighted $-2$ against 1
# (`numkin report homework`'s tolerance table; the turn is differenced as periodic).

# %%
tol = report.tolerance_table(mech, omega=OMEGA, quantity="beta", check_angle=CHECK)
cols = ["stopping rule", "Newton iterations per point (mean)", "max |F| [in]",
        "omega_beta max rel error [%]", "alpha_beta max rel error [%]"]
for number, rule in enumerate(tol["stopping rule"]):
    print(f"[{number}] {rule}")
print()
print(tol[cols[1:]].rename_axis("rule").to_string(float_format="{:.3g}".format))

# %% [markdown]
# The residual rule looks harmless in $\omega$, but the acceleration is visibly wrong. Where,
# and by how much? Difference the student-style sweep ourselves:

# %%
theta = np.radians(np.arange(0, 361, 1.0))
loose = report.student_sweep(mech, theta, rule="residual", tol=1e-4)
tight = mech.sweep(theta)
exact = analytic.kinematics(tight, OMEGA)
alpha_loose = kinematics.finite_difference(loose, OMEGA, periodic=False)["alpha_beta"]
alpha_tight = kinematics.finite_difference(tight, OMEGA, periodic=False)["alpha_beta"]
err_loose = np.abs(alpha_loose - exact["alpha_beta"]).to_numpy()
err_tight = np.abs(alpha_tight - exact["alpha_beta"]).to_numpy()
k = int(np.argmax(err_loose))
k100 = tight.index(CHECK)
print(f"residual rule |F| < 1e-4: largest alpha_beta error {err_loose[k]:.1f} rad/s^2 at theta = {np.degrees(theta[k]):.0f} deg")
print(f"  for comparison: |alpha_beta(100 deg)| = {abs(exact['alpha_beta'][k100]):.1f} rad/s^2, "
      f"max |alpha_beta| = {np.abs(exact['alpha_beta']).max():.1f} rad/s^2")
print(f"numkin's rule (1e-12):    largest alpha_beta error {err_tight.max():.3f} rad/s^2 (the second difference's own)")
assert err_loose.max() > 0.5 * abs(exact["alpha_beta"][k100])  # an error as large as alpha itself at 100 deg
assert err_tight.max() < 0.1

fig, ax = plt.subplots(figsize=(7, 4))
ax.semilogy(np.degrees(theta), np.maximum(err_loose, 1e-8), label=r"residual rule $|F| < 10^{-4}$")
ax.semilogy(np.degrees(theta), np.maximum(err_tight, 1e-8), label="numkin, tol = 1e-12")
ax.set_xlabel(r"$\theta$ [deg]")
ax.set_ylabel(r"$|\alpha_\beta$ error$|$ [rad/s$^2$]")
ax.set_xticks(range(0, 361, 60))
ax.set_title("second difference of a loosely solved sweep")
ax.legend()
plt.show()

# %% [markdown]
# The error is not smooth: the residual rule stops as soon as $|F|$ first drops below the
# tolerance, so the error left in $\beta$ changes irregularly from one point to the next, and
# the second difference multiplies those point-to-point jumps by $1/h^2$. A plot of $\beta$
# would never show it.
#
# **The homework's own table, explained.** The homework's Newton stopped when the *relative*
# step $\lVert\Delta x\rVert / \lVert x\rVert$ fell below $10^{-4}$ (angles in degrees in,
# radians inside). Re-running exactly that loop reproduces its reported numbers — and shows
# that the fourth-digit differences from numkin's values in Lesson 3 come from the stopping
# rule, not from the schemes:

# %%
def homework_newton(theta_deg, r_in, r_coupler, r_out, r_fixed, guess_deg, tol=1e-4):
    """The homework's loop: Newton from a guess in degrees, stop on |dx| / |x| < tol."""
    theta4 = np.deg2rad(180 + theta_deg)
    x = np.deg2rad(np.asarray(guess_deg, dtype=float))
    for _ in range(1000):
        f = np.array([r_out * np.cos(x[0]) + r_coupler * np.cos(x[1]) + r_in * np.cos(theta4) - r_fixed,
                      r_out * np.sin(x[0]) + r_coupler * np.sin(x[1]) + r_in * np.sin(theta4)])
        jac = np.array([[-r_out * np.sin(x[0]), -r_coupler * np.sin(x[1])],
                        [r_out * np.cos(x[0]), r_coupler * np.cos(x[1])]])
        dx = np.linalg.solve(jac, -f)
        x = x + dx
        if np.linalg.norm(dx) / np.linalg.norm(x) < tol:
            break
    return np.rad2deg(x)


theta_hw = np.linspace(0, 360, 361)
phi_hw, psi_hw = np.zeros(361), np.zeros(361)
phi_hw[0], psi_hw[0] = homework_newton(0, 1.94, 6.86, 2.36, 7.0, [45, 60])
for i in range(1, 361):
    phi_hw[i], psi_hw[i] = homework_newton(theta_hw[i], 1.94, 6.86, 2.36, 7.0, [phi_hw[i - 1], psi_hw[i - 1]])
phi_hw %= 360
beta_hw, gamma_hw = np.zeros(361), np.zeros(361)
b0, g0 = homework_newton(phi_hw[0] + 149, 2.39, 1.87, 1.26, 1.25, [30, 270])
beta_hw[0], gamma_hw[0] = b0 % 360, g0
for i in range(1, 361):
    b0, g0 = homework_newton(phi_hw[i] + 149, 2.39, 1.87, 1.26, 1.25, [beta_hw[i - 1], gamma_hw[i - 1]])
    beta_hw[i], gamma_hw[i] = b0 % 360, g0 % 360

b, h, w = np.deg2rad(beta_hw), math.radians(1.0), 7.5
hw_rerun = {
    "forward omega_beta [rad/s]": w * (b[101] - b[100]) / h,
    "centred omega_beta [rad/s]": w * (b[101] - b[99]) / (2 * h),
    "forward-of-forward alpha_beta [rad/s^2]": w**2 * (b[102] - 2 * b[101] + b[100]) / h**2,
    "second difference alpha_beta [rad/s^2]": w**2 * (b[101] - 2 * b[100] + b[99]) / h**2,
}
hw_reported = [10.59897, 10.63198, -28.11947, -28.36941]
numkin_tight = [
    w * (tight["beta"][101] - tight["beta"][100]) / h,
    w * (tight["beta"][101] - tight["beta"][99]) / (2 * h),
    w**2 * (tight["beta"][102] - 2 * tight["beta"][101] + tight["beta"][100]) / h**2,
    w**2 * (tight["beta"][101] - 2 * tight["beta"][100] + tight["beta"][99]) / h**2,
]
rerun = pd.DataFrame({"homework table": hw_reported, "homework loop re-run": list(hw_rerun.values()),
                      "same schemes, numkin sweep": numkin_tight}, index=list(hw_rerun))
print(rerun.to_string(float_format="{:.5f}".format))
print(f"\nbeta(100 deg): homework loop {beta_hw[100]:.4f} deg, numkin {np.degrees(tight['beta'][100]):.4f} deg")
assert np.allclose(rerun["homework loop re-run"], rerun["homework table"], atol=6e-6)

# %% [markdown]
# The homework's $\beta(100^\circ)$ is off by 0.0013°, invisible in any plot, yet enough
# to move its finite-difference $\omega_\beta$ and $\alpha_\beta$ in the fourth digit.

# %% [markdown]
# ## Questions
#
# 1. From the convergence table, estimate the constant $C$ of the centred difference
#    ($e \approx C h^2$) and predict the number of points per turn needed for a relative error
#    of $10^{-6}$ in $\omega_\beta$. Check your prediction with `report.convergence_table`.
# 2. In the convergence table the `five_point_second` row stops improving between 1440 and
#    3600 points (its error falls about 3.4-fold where order 4 would give 39-fold; the table leaves
#    that order blank, at the round-off floor), while the `five_point` row still
#    converges at order 4. Using the error model at the top of this notebook with
#    $\varepsilon = 10^{-12}$ (the sweep's tolerance, `tol = 1e-12 (default)` in the table of
#    section 4), predict at which $h$ the floor of the second derivative should appear. Does it
#    match? If not, estimate $\varepsilon$ from the error at 3600 points and compare it with the
#    sweep's `residual` column.
# 3. Re-run section 4 with `rule="step"` and with `tol=1e-8`. Which stopping rule would you
#    recommend to the homework's author, and why is a rule on $|\Delta x|$ alone not enough
#    near a toggle position?

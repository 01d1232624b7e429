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
# # Lesson 5 — Stiff and extreme cases: what breaks, and what numkin reports
#
# Everything so far ran on friendly linkages. Here we push on the places where the numbers can
# go wrong without anyone noticing, and check that numkin either gets them right or says why
# not. The common thread is the position Jacobian $J = \partial\mathbf F / \partial\mathbf q$:
#
# * Newton solves $J\,\Delta\mathbf q = -\mathbf F$, and a residual $\mathbf r$ left in the
#   loop equations means an error $\lVert\delta\mathbf q\rVert \lesssim \kappa(J)\,
#   \lVert\mathbf r\rVert / \lVert J \rVert$: a large condition number $\kappa(J)$ turns a
#   small residual into a large error;
# * velocities solve $J\mathbf q' = -\partial\mathbf F/\partial\theta$: where $J$ is singular
#   (a **toggle** or **change point**) $\mathbf q'$ is infinite or undefined, and finite
#   differences of $\mathbf q$ lose their accuracy nearby.
#
# The cases: a four-bar near a toggle, a four-bar whose coupler and rocker nearly align, a
# change point, high speed, extreme length scales and extreme grids.

# %%
# %matplotlib inline
import math
import warnings

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import sympy as sp

import numkin
from numkin import analytic, kinematics, linkages
from numkin.compare import compare

pd.set_option("display.width", 160)
turn = np.radians(np.arange(0, 361, 1.0))

# %% [markdown]
# ## 1. Near a toggle: ground 4, crank 2, coupler 4.0001, rocker 2
#
# $s + l = 6.0001 > p + q = 6$: a non-Grashof linkage, by $10^{-4}$. At $\theta_2 = 0$ the crank
# tip $A = (2, 0)$ is at distance 2 from $O_4$, less than $|r_3 - r_4| = 2.0001$: the linkage
# cannot close. It folds up (a toggle) at a small angle and cannot be driven through 0°.

# %%
toggle = linkages.four_bar(4, 2, 4.0001, 2)
print(linkages.grashof(4, 2, 4.0001, 2))
try:
    toggle.sweep(turn)
except numkin.AssemblyError as err:
    print("AssemblyError:", err)

# the limit, by hand: |A - O4| = r3 - r4  <=>  r1^2 + r2^2 - 2 r1 r2 cos(theta) = (r3 - r4)^2
limit = math.degrees(math.acos((4**2 + 2**2 - (4.0001 - 2) ** 2) / (2 * 4 * 2)))
print(f"limit position by hand: theta2 = {limit:.4f} deg")
assert abs(limit - 0.41) < 0.01

# %% [markdown]
# Inside the reachable range the sweep works; the condition number of $J$ and the angular
# velocity of the rocker grow as the input approaches the limit (per unit input speed,
# $\omega_{in} = 1$ rad/s):

# %%
dist = np.logspace(-5, 1.3, 120)  # degrees past the limit, down to 1e-5 deg
near = toggle.sweep(np.radians(limit + dist))
kin_near = analytic.kinematics(near, 1.0)
omega4 = np.abs(kin_near["omega_theta4"].to_numpy())
fig, ax = plt.subplots(figsize=(7, 4))
ax.loglog(dist, near.cond, label=r"condition number $\kappa(J)$")
ax.loglog(dist, omega4, label=r"$|\omega_4|$ [rad/s] for $\omega_{in}$ = 1 rad/s")
ax.loglog(dist, omega4[0] * (dist / dist[0]) ** -0.5, "k:", label=r"slope $-1/2$")
ax.set_xlabel(r"distance from the toggle, $\theta_2 - \theta_{lim}$ [deg]")
ax.legend()
ax.set_title("approaching the toggle of the 4, 2, 4.0001, 2 four-bar")
plt.show()
close = dist < 1e-2
slope = np.polyfit(np.log(dist[close]), np.log(omega4[close]), 1)[0]
print(f"log-log slope of |omega_4| within 0.01 deg of the limit: {slope:.3f}")
print(f"at {dist[0]:.0e} deg from the limit: cond(J) = {near.cond[0]:.3g}, |omega_4| = {omega4[0]:.3g} rad/s")
assert abs(slope + 0.5) < 0.05

# %% [markdown]
# The `LostDigitsWarning` the cell above prints is intended. Solving the velocity and acceleration
# equations with a Jacobian of condition number $\kappa$ costs digits: the positions are known to
# about $\varepsilon\kappa$ (relative, $\varepsilon \approx 2.2\times10^{-16}$) and the derivative
# equations amplify that by $\kappa$ again, so numkin estimates the relative error of an $n$-th
# derivative as $(2n - 1)\,\varepsilon\,\kappa^2$ (`numkin.conditioning.lost_digits`). At
# $10^{-5}$ degrees from the limit $\kappa \approx 5\times10^{4}$, and the estimate for the
# accelerations passes the tolerance $10^{-6}$: `analytic.kinematics` warns
# (`LostDigitsWarning`) naming the input angle, the condition number and the estimated errors,
# rather than returning numbers that look exact. The velocities plotted here are still good to
# about six digits:

# %%
from numkin.conditioning import lost_digits

print(f"cond(J) = {near.cond[0]:.3g} at {dist[0]:.0e} deg from the limit: estimated relative error "
      f"{lost_digits(near.cond[0], 1):.1e} (velocities), {lost_digits(near.cond[0], 2):.1e} (accelerations)")
assert lost_digits(near.cond[0], 1) < 1e-6 < lost_digits(near.cond[0], 2)

# %% [markdown]
# The velocity grows like $(\theta_2 - \theta_{lim})^{-1/2}$: a square-root singularity. A
# linkage written by hand, without the ready-made assembly check, and driven *past* the limit
# does not get a silently wrong answer either: the continuation stops at the toggle.

# %%
t2, t3, t4 = sp.symbols("theta2 theta3 theta4", real=True)
loop = numkin.Loop.from_vectors([(2, t2), (4.0001, t3), (-2, t4), (-4, 0)], [t3, t4], name="O2-A-B-O4")
by_hand = numkin.Mechanism([loop], t2, {}, name="near-toggle four-bar (by hand)", length_scale=4)
start = toggle.solve(math.radians(10)).x
try:
    by_hand.sweep(np.radians(np.arange(10.0, -1.0, -1.0)), guess=start)
except numkin.NumkinError as err:
    caught = err
print(f"{type(caught).__name__} at {math.degrees(caught.input_value):.3f} deg:\n{caught}")
assert isinstance(caught, (numkin.BranchError, numkin.ConvergenceError))
assert abs(math.degrees(caught.input_value) - limit) < 0.1

# %% [markdown]
# Over the reachable part of the turn, 1° to 359° on a 1° grid, where do finite differences of
# the sampled rocker angle err most? (Relative errors are divided by the largest $|\omega_4|$
# of the turn.)

# %%
reach = toggle.sweep(np.radians(np.arange(1.0, 360.0, 1.0)))
cmp_toggle = compare(reach, 1.0, "omega_theta4", schemes=("forward", "centred", "five_point"))
print(cmp_toggle.summary[["max abs error [rad/s]", "max at theta2 [deg]", "ends abs error [rad/s]"]]
      .to_string(float_format="{:.3g}".format))
pointwise = cmp_toggle.table.set_index("theta2 [deg]")
print(pointwise.loc[[1.0, 2.0, 178.0, 179.0, 180.0, 181.0, 182.0, 358.0, 359.0],
                    ["analytic [rad/s]", "forward rel error", "centred rel error", "five_point rel error"]]
      .to_string(float_format="{:.2e}".format))
# by hand: at theta2 = 180 deg the crank tip A = (-2, 0) is 6 from O4 = (4, 0), against r3 + r4 = 6.0001
print(f"theta2 = 180 deg: |A - O4| = {abs(-2.0 - 4.0):.4f}, r3 + r4 = {4.0001 + 2:.4f}: "
      "coupler and rocker nearly in line")
worst = cmp_toggle.summary["max at theta2 [deg]"]
assert all(178 <= worst[s] <= 182 for s in ("forward", "centred", "five_point"))
inner, ends = cmp_toggle.summary["max abs error [rad/s]"], cmp_toggle.summary["ends abs error [rad/s]"]
assert ends["five_point"] > 2 * inner["five_point"] and ends["centred"] > 0.9 * inner["centred"]

# %% [markdown]
# The errors peak in two places:
#
# * **Near 180°**, where coupler and rocker are almost stretched out in line: the crank tip is
#   6 from $O_4$ against $r_3 + r_4 = 6.0001$ (at the limit positions they fold instead,
#   $|A - O_4| = r_3 - r_4$). The rocker reverses within about 1.3° (the suite's row for this
#   case in section 7 says so), $\omega_4$ falls from about 0.9 to $-0.2$ rad/s between 179°
#   and 181°, and a 1° grid does not resolve that. The forward difference is worst at 180°
#   itself, whose forward stencil straddles the turn; the centred difference is worst at 179°
#   (and equally at 181°), while at 180° its symmetric stencil happens to be almost exact.
# * **At the ends of the sweep**, 1° and 359°, 0.6° from the limit positions at $\pm 0.405°$,
#   where $\omega_4$ grows like $(\theta_2 - \theta_{lim})^{-1/2}$ and the sweep is an open grid.
#   There a scheme's own stencil would reach past the data, so one-sided end stencils take over
#   (the summary gives their largest error apart, `ends abs error`: at the first and last point for
#   the centred difference, the first two and last two for the five-point formula). The five-point
#   formula's own stencil is worst at 181°; its end stencils err more than twice as much. The
#   centred end error is nearly as large as its peak at 179°.
#
# Section 2 takes the nearly-in-line case apart.

# %% [markdown]
# ## 2. Coupler and rocker nearly aligned: ground 4, crank 1, coupler 3, rocker $2 + \delta$
#
# At $\theta_2 = 180^\circ$ the crank tip is at distance 5 from $O_4$ and
# $r_3 + r_4 = 5 + \delta$: coupler and rocker are almost in line. The linkage is a Grashof
# crank-rocker for every $\delta > 0$, but it becomes stiff as $\delta \to 0$.

# %%
rows = []
for delta in (1e-2, 1e-4, 1e-6):
    fb = linkages.four_bar(4, 1, 3, 2 + delta)
    with warnings.catch_warnings(record=True) as caught_warnings:
        warnings.simplefilter("always", numkin.SingularityWarning)
        sw = fb.sweep(turn)
        velocity = compare(sw, 1.0, "omega_theta4", schemes=("centred",)).summary
        acceleration = compare(sw, 1.0, "alpha_theta4", schemes=("second_difference",)).summary
    rows.append({
        "delta": delta,
        "Grashof class": linkages.grashof(4, 1, 3, 2 + delta),
        "max cond(J)": sw.cond.max(),
        "max Newton iterations": int(sw.iterations.max()),
        "events": ", ".join(e.kind for e in sw.events) or "none",
        "warnings": len(caught_warnings),
        "centred omega_4: max rel error": velocity.loc["centred", "max rel error"],
        "second diff. alpha_4: max rel error": acceleration.loc["second_difference", "max rel error"],
    })
aligned = pd.DataFrame(rows).set_index("delta")
aligned

# %%
assert aligned["max cond(J)"].is_monotonic_increasing
ratio = aligned["max cond(J)"].iloc[-1] / aligned["max cond(J)"].iloc[0]
print(f"cond grows by {ratio:.0f}x when delta shrinks 10^4-fold: like delta^(-1/2)")
assert 50 < ratio < 200

# %% [markdown]
# The condition number grows like $\delta^{-1/2}$ but stays far from $10^{8}$, where numkin
# reports a point as near-singular (`SweepEvent` kind `"near-singular"`); positions stay
# accurate. The **derivatives** suffer first: the rocker's motion near 180° happens in an
# input interval of width about $\sqrt\delta$, which a 1° grid cannot resolve, so the
# finite-difference errors are large even though nothing is singular.
#
# The centred error is **not** monotone in $\delta$, though: it is largest at $\delta = 10^{-4}$
# and smaller again at $10^{-6}$. Measure how wide the turn is: the jump of
# $d\theta_4/d\theta_2$ across it divided by the largest $|d^2\theta_4/d\theta_2^2|$.

# %%
from numkin import stability

turns = stability.run_suite([f"nearly aligned, delta = {d:.0e}" for d in (1e-2, 1e-4, 1e-6)],
                            schemes=("centred", "second_difference")).set_index("case")
print(turns[["sharpest turn [deg]", "centred max rel error [-]", "second_difference max rel error [-]"]]
      .to_string(float_format="{:.3g}".format))
width = turns["sharpest turn [deg]"].to_numpy()
assert 0.5 < width[1] < 3 and width[2] < 0.5  # about one 1 deg step, then far less than one

# %% [markdown]
# At $\delta = 10^{-2}$ the turn spans several grid steps (NaN: wider than 3 steps) and is
# resolved. At $10^{-4}$ it is one to two steps wide: the centred difference at the neighbours
# of 180° straddles the turn and is worst. At $10^{-6}$ the turn is about a fifth of a step, a corner
# between grid points: the neighbours see straight lines on either side and only the point at
# the corner is wrong, so the first-derivative error falls again. The second difference
# divides by $h^2$ and feels the corner's sharpness: its error keeps growing.

# %% [markdown]
# ## 3. A change point: the parallelogram 5, 2, 5, 2
#
# Lesson 2 showed the sweep stopping at 180° with a `BranchError`. With
# `on_singular="report"` it goes on, and the analytic derivatives refuse to divide by the
# singular Jacobian: they are NaN at the change points, with a warning, rather than a number.

# %%
para = linkages.four_bar(5, 2, 5, 2)
with warnings.catch_warnings(record=True) as caught_warnings:
    warnings.simplefilter("always", numkin.SingularityWarning)
    sw_para = para.sweep(np.radians(np.arange(10.0, 371.0, 1.0)), on_singular="report")
    kin_para = analytic.kinematics(sw_para, 1.0)
for w in caught_warnings:
    print("warning:", str(w.message)[:160], "...")
nan_at = np.degrees(kin_para["theta2"][kin_para["omega_theta4"].isna()]).to_numpy()
print(f"omega_4 is NaN at theta2 = {nan_at} deg")
assert set(np.round(nan_at)) == {180.0, 360.0}

# %% [markdown]
# ## 4. High speed: the slider-crank at 60, 6000 and 60 000 rpm
#
# Accelerations scale with $\omega^2$: at 6000 rpm the piston reaches $4.4\times10^4$ m/s².
# Large numbers are not a numerical difficulty in themselves — the *relative* error of a scheme
# does not depend on the speed:

# %%
crank = linkages.slider_crank(80, 200)
sw_sc = crank.sweep(turn)
rows = []
for rpm in ("60 rpm", "6000 rpm", "60000 rpm"):
    c = compare(sw_sc, rpm, "a_x", schemes=("second_difference",))
    rows.append({
        "speed": rpm,
        "max |a| [m/s^2]": c.scale / 1000,
        "max abs error [m/s^2]": c.summary.loc["second_difference", "max abs error [mm/s^2]"] / 1000,
        "max rel error": c.summary.loc["second_difference", "max rel error"],
    })
speeds = pd.DataFrame(rows).set_index("speed")
print(speeds.to_string(float_format="{:.4g}".format))
assert np.allclose(speeds["max rel error"], speeds["max rel error"].iloc[0], rtol=1e-8)

# %% [markdown]
# ## 5. Extreme scales: the homework linkage scaled by $10^{-6}$ and $10^{3}$
#
# A MEMS linkage in micrometres and a crane in kilometres: the same angles, the same iteration
# counts and the same relative errors — because numkin's stopping rule scales residuals by the
# mechanism's characteristic length.

# %%
base = dict(fixed1=7.0, input1=1.94, coupler1=6.86, output1=2.36,
            fixed2=1.25, input2=2.39, coupler2=1.87, output2=1.26)
reference = linkages.chained_four_bars().sweep(turn)
rows = []
for k in (1e-6, 1.0, 1e3):
    sw_k = linkages.chained_four_bars(**{n: v * k for n, v in base.items()}).sweep(turn)
    c = compare(sw_k, "450 rad/min", "alpha_beta", schemes=("second_difference",))
    rows.append({
        "scale": k,
        "max |beta - beta_unscaled| [rad]": np.abs(sw_k["beta"] - reference["beta"]).max(),
        "max Newton iterations": int(sw_k.iterations.max()),
        "max scaled residual": sw_k.residual.max(),
        "alpha_beta: second diff. max rel error": c.summary.loc["second_difference", "max rel error"],
    })
scales = pd.DataFrame(rows).set_index("scale")
print(scales.to_string(float_format="{:.3e}".format))
assert scales["max |beta - beta_unscaled| [rad]"].max() < 1e-12

# %% [markdown]
# What breaks is an **absolute** stopping rule. `numkin.newton` measures the residual in
# units of `fscale` (default 1). At the micrometre scale the residual of a bad guess is already
# below $10^{-4}$, so the rule "$|F| < 10^{-4}$" accepts it:

# %%
k = 1e-6
r1, r4, r3, r2 = 7.0 * k, 1.94 * k, 6.86 * k, 2.36 * k


def F(x, th):
    phi, psi = x
    return np.array([r2 * np.cos(phi) + r3 * np.cos(psi) - r4 * np.cos(th) - r1,
                     r2 * np.sin(phi) + r3 * np.sin(psi) - r4 * np.sin(th)])


guess = np.radians([45.0, 60.0])
absolute = numkin.newton(F, guess, args=(0.0,), jacobian="forward", tol=1e-4)
relative = numkin.newton(F, guess, args=(0.0,), jacobian="forward", tol=1e-12, fscale=7.0 * k)
truth = math.degrees(reference["phi"][0])
for name, r in [("absolute |F| < 1e-4", absolute), ("relative |F|/r1 < 1e-12", relative)]:
    print(f"{name:24s}: converged={r.converged}, {r.iterations} iterations, "
          f"phi = {math.degrees(r.x[0]) % 360:8.4f} deg (true {truth:.4f})")
assert absolute.converged and abs(math.degrees(absolute.x[0]) % 360 - truth) > 1
assert abs(math.degrees(relative.x[0]) % 360 - truth) < 1e-8

# %% [markdown]
# ## 6. Extreme grids: 12 and 100 000 points per turn
#
# A coarse grid cannot resolve the motion; a very fine one divides the rounding error of the
# positions (they are converged to the last digits, about $10^{-16}$ relative) by $h^2$ in a
# second difference.

# %%
rows = []
for n in (12, 360, 100_000):
    sw_n = linkages.chained_four_bars().sweep(np.linspace(0.0, 2 * np.pi, n + 1))
    for quantity in ("omega_beta", "alpha_beta"):
        summary = compare(sw_n, "450 rad/min", quantity).summary
        for scheme, err in summary["max rel error"].items():
            rows.append({"points per turn": n, "quantity": quantity, "scheme": scheme, "max rel error": err})
grids = pd.DataFrame(rows).pivot_table(index=["quantity", "scheme"], columns="points per turn",
                                       values="max rel error", sort=False)
print(grids.to_string(float_format="{:.1e}".format))

# %%
assert grids.loc[("omega_beta", "centred"), 12] > 1e-2  # 30-degree steps: a poor estimate
assert grids.loc[("omega_beta", "centred"), 100_000] < 1e-7
# on the finest grid the accurate second derivatives all end near 1e-6, whatever their order: rounding / h^2
for scheme in ("second_difference", "five_point_second", "spectral_second"):
    assert 1e-7 < grids.loc[("alpha_beta", scheme), 100_000] < 1e-5
# the spectral one is worse than on 360 points; the five-point one gains nothing from 278x more points
assert grids.loc[("alpha_beta", "spectral_second"), 100_000] > 3 * grids.loc[("alpha_beta", "spectral_second"), 360]
assert grids.loc[("alpha_beta", "five_point_second"), 100_000] > 0.5 * grids.loc[("alpha_beta", "five_point_second"), 360]

# %% [markdown]
# On 12 points every scheme is poor: the step is 30°. On 100 000 points the first derivatives
# are good, but the second difference, the five-point and the spectral second derivatives all
# end near $10^{-6}$, whatever their order: the spectral one is about a hundred thousand times
# *worse* than on 360 points, and the five-point one is hardly better than on 360 points (with
# 278 times as many points), where its error was truncation. The grid is so fine that the
# rounding error of the computed positions, divided by $h^2 \approx 4\times10^{-9}$,
# dominates. Lesson 4 measures this floor.

# %% [markdown]
# ## 7. The whole suite in one table
#
# `numkin.stability.run_suite()` runs these cases (and a few more) through the solver, the
# analytic solution, a complex-step check of it, and every finite-difference scheme, and
# summarises each case in one row: what happened, whether that was the expected outcome, the
# conditioning, and the errors. Nothing in it may be a silently wrong number: a completed sweep
# whose checks fail would be marked `WRONG`.

# %%
suite = stability.run_suite()
columns = ["case", "expected", "outcome", "as expected", "max cond [-]", "Newton iterations (max)",
           "centred max rel error [-]", "second_difference max rel error [-]"]
shown = suite[columns].astype({"Newton iterations (max)": "Int64"})  # blank-able integers: NaN where unsolved
print(shown.to_string(index=False, float_format="{:.2e}".format))
assert suite["as expected"].all()
assert not suite["outcome"].astype(str).str.contains("WRONG").any()

# %%
for _, row in suite.iterrows():
    print(f"- {row['case']}: {row['what happened']}")

# %% [markdown]
# ## Questions
#
# 1. In section 1, the slope of $|\omega_4|$ against the distance from the limit is close to
#    $-1/2$. Derive it: near a toggle, how does $\theta_4$ depend on $\theta_2 - \theta_{lim}$?
# 2. For the nearly aligned linkage with $\delta = 10^{-6}$, how fine must the grid be near
#    180° for the centred difference to reach 1 % accuracy? Try a local sweep from 170° to 190°.
# 3. Section 6: estimate the noise of the positions from the second-difference error on
#    100 000 points ($e \approx 4\,\omega^2\varepsilon_q / h^2$). Is it consistent with the
#    sweep's `residual` column?

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
# # Lesson 7 — Gauss–Chebyshev quadrature and an elastic pendulum
#
# The last two problems of the exam in source document `004` are not linkage kinematics, but
# they use the same tools: a formula whose error we can predict, and a numerical solution that
# we check by its observed order. Nothing here needs numkin: numpy and matplotlib only.
#
# **Problem 2.** Evaluate
#
# $$ I = \int_0^{\pi/2} \frac{dx}{\sqrt{\sin x}} $$
#
# by Gauss–Chebyshev quadrature, compare it with the exact value and explain any difference.
#
# **Problem 3.** A mass $m$ hangs from an elastic cord of stiffness $k$ and unstretched length
# $L$. Released from rest at $\theta(0) = 45°$ with the cord unstretched, how long is the cord
# when the mass first crosses the vertical ($\theta = 0$)? With $g = 9.80665$ m/s²,
# $k = 30$ N/m, $L = 0.4$ m, $m = 0.2$ kg, the equations of motion are
#
# $$ \ddot r = r\dot\theta^2 + g\cos\theta - \frac km (r - L), \qquad
#    \ddot\theta = \frac{-2\dot r\dot\theta - g\sin\theta}{r}. $$

# %%
import math

import matplotlib.pyplot as plt
import mpmath
import numpy as np

# %% [markdown]
# ## 1. Gauss–Chebyshev quadrature
#
# The rule integrates against the weight $(1 - t^2)^{-1/2}$ on $[-1, 1]$ with $n + 1$ nodes:
#
# $$ \int_{-1}^{1} \frac{f(t)}{\sqrt{1 - t^2}}\,dt \approx \frac{\pi}{n + 1}\sum_{i=0}^{n} f(t_i),
#    \qquad t_i = \cos\frac{(2i + 1)\pi}{2n + 2}. $$
#
# It is exact when $f$ is a polynomial of degree up to $2n + 1$. To bring the integral to this
# form, substitute $\sin x = t^2$: then $\cos x\,dx = 2t\,dt$ and
# $\cos x = \sqrt{1 - t^4} = \sqrt{(1 - t^2)(1 + t^2)}$, so
#
# $$ I = \int_0^1 \frac{2\,dt}{\sqrt{(1 - t^2)(1 + t^2)}}
#      = \int_{-1}^{1} \frac{1}{\sqrt{1 - t^2}}\,\frac{dt}{\sqrt{1 + t^2}} $$
#
# (the integrand is even). The weight takes the square-root singularity at $t = \pm 1$, and
# $f(t) = 1/\sqrt{1 + t^2}$ is smooth. The singularity of the original integrand at $x = 0$
# is gone: $dx/\sqrt{\sin x} = 2\,dt/\cos x$.

# %%
def gauss_chebyshev(f, n):
    """Gauss–Chebyshev quadrature of ∫ f(t) / sqrt(1 - t²) dt over [-1, 1] with n + 1 nodes."""
    i = np.arange(n + 1)
    t = np.cos((2 * i + 1) * np.pi / (2 * n + 2))
    return np.pi / (n + 1) * np.sum(f(t))


def f(t):
    return 1.0 / np.sqrt(1.0 + t**2)


# The exact value: with sin x = s, I = B(1/4, 1/2) / 2 = Γ(1/4)² / (2 sqrt(2π)).
EXACT = math.gamma(0.25) ** 2 / (2 * math.sqrt(2 * math.pi))
I7 = gauss_chebyshev(f, 7)
print(f"exact            I = {EXACT:.15f}")
print(f"Gauss-Chebyshev n=7: {I7:.15f}   (the exam: 2.622056775816561)")
print(f"error {I7 - EXACT:.3e}, relative {abs(I7 - EXACT) / EXACT * 100:.3e} %")

# %%
assert abs(I7 - 2.622056775816561) < 1e-14  # the exam's value
assert abs(EXACT - 2.62205755429212) < 5e-15  # the exam's exact value (sympy)

# %% [markdown]
# ### Error against n
#
# Why is the error not zero? Because $f(t) = (1 + t^2)^{-1/2}$ is **not a polynomial**: the
# rule integrates exactly only the part of $f$ that a polynomial of degree $2n + 1$ can
# represent. The exam's answer also blames "a singularity at $x = 0$"; after the substitution
# there is none. How fast the error falls is set by how far from $[-1, 1]$ the function stops
# being analytic: $f$ has branch points at $t = \pm i$, on the Bernstein ellipse with
# $\rho = 1 + \sqrt 2$. The error falls like $n^{-1/2}\rho^{-2n}$ (the $n^{-1/2}$ comes from the
# square-root type of the branch points): the ratio of successive errors tends, from below, to
# $(1 + \sqrt 2)^{-2} \approx 0.1716$ per extra node.
#
# The table goes on until the error stops falling. Its errors are measured against $I$ to 40
# digits (mpmath): the double `EXACT` is itself off by about $7\times10^{-16}$, which would hide the
# last steps. The last column is the rule's own error, its sum also taken to 40 digits.

# %%
mpmath.mp.dps = 40
EXACT_40 = mpmath.gamma(mpmath.mpf(1) / 4) ** 2 / (2 * mpmath.sqrt(2 * mpmath.pi))


def gauss_chebyshev_40(n):
    # the same rule, nodes and sum to 40 digits: its error is the truncation error alone
    nodes = (mpmath.cos((2 * i + 1) * mpmath.pi / (2 * n + 2)) for i in range(n + 1))
    return mpmath.pi / (n + 1) * mpmath.fsum(1 / mpmath.sqrt(1 + t**2) for t in nodes)


rho2 = (1 + math.sqrt(2)) ** -2
ns = np.arange(1, 23)
values = np.array([gauss_chebyshev(f, n) for n in ns])
errors = np.array([float(abs(mpmath.mpf(v) - EXACT_40)) for v in values])
truncation = np.array([float(abs(gauss_chebyshev_40(n) - EXACT_40)) for n in ns])
print(f"EXACT - I = {float(mpmath.mpf(EXACT) - EXACT_40):.2e}")
print(" n   Gauss-Chebyshev       error       ratio to previous   error of the rule at 40 digits")
for k, (n, v, e, e40) in enumerate(zip(ns, values, errors, truncation)):
    ratio = "" if k == 0 else f"{e / errors[k - 1]:.4f}"
    print(f"{n:2d}   {v:.15f}   {e:.3e}   {ratio:17s}   {e40:.3e}")
print(f"predicted ratio (1 + √2)^-2 = {rho2:.4f}")

# %%
assert abs(EXACT_40 - mpmath.mpf("2.6220575542921198104648395898911194")) < 1e-30  # Γ(1/4)²/(2√(2π))
assert 1e-16 < abs(mpmath.mpf(EXACT) - EXACT_40) < 2e-15  # a few units in the last place of the double
first12 = slice(0, 12)
ratios = errors[first12][1:] / errors[first12][:-1]
assert np.all(np.diff(ratios) > 0) and np.all(ratios < rho2), ratios  # rises towards rho^-2
corrected = ratios * np.sqrt(ns[first12][1:] / ns[first12][:-1])  # the n^(-1/2) factor taken out
assert np.all(np.abs(corrected[4:] / rho2 - 1) < 0.03), corrected
# in double precision the error follows the rule's own down to n = 17, reaches 1e-15 at n = 19,
# and stays there: the double nearest to I is 1.9e-16 from it
assert np.allclose(errors[:17], truncation[:17], rtol=0.1)
assert ns[np.argmax(errors < 1e-15)] == 19 and ns[np.argmax(truncation < 1e-15)] == 19
assert np.all(errors[18:] < 3e-16)

fig, ax = plt.subplots()
ax.semilogy(ns, errors, "o-", label="|Gauss–Chebyshev − exact| (double)")
ax.semilogy(ns, truncation, ".:", color="0.4", label="the rule at 40 digits (mpmath)")
ref = errors[11] * np.sqrt(12 / ns) * rho2 ** (ns - 12)  # drawn through the error at n = 12
ax.semilogy(ns, ref, "--", label=r"$\propto n^{-1/2}(1+\sqrt{2})^{-2n}$ (through $n = 12$)")
ax.set_xlabel("n (n + 1 nodes)")
ax.set_ylabel("absolute error (dimensionless)")
ax.legend()
plt.show()

# %% [markdown]
# ## 2. The elastic pendulum with RK4
#
# With the state $y = (r, \theta, \dot r, \dot\theta)$ (m, rad, m/s, rad/s) the equations are
# first order, $\dot y = F(y)$, and the classical Runge–Kutta method advances one step $h$ by
#
# $$ k_1 = F(y_n),\; k_2 = F(y_n + \tfrac h2 k_1),\; k_3 = F(y_n + \tfrac h2 k_2),\;
#    k_4 = F(y_n + h k_3),\quad y_{n+1} = y_n + \tfrac h6 (k_1 + 2k_2 + 2k_3 + k_4). $$

# %%
G, K, L, M = 9.80665, 30.0, 0.4, 0.2  # m/s², N/m, m, kg
Y0 = np.array([L, math.radians(45.0), 0.0, 0.0])  # at rest at 45°, cord unstretched


def pendulum(t, y):
    r, th, rd, thd = y
    return np.array([
        rd,
        thd,
        r * thd**2 + G * math.cos(th) - K / M * (r - L),
        (-2 * rd * thd - G * math.sin(th)) / r,
    ])


def rk4(F, y0, t):
    """Classical fourth-order Runge–Kutta on the grid t; one row of the solution per time."""
    y = np.empty((len(t), len(y0)))
    y[0] = y0
    for n in range(len(t) - 1):
        h = t[n + 1] - t[n]
        k1 = F(t[n], y[n])
        k2 = F(t[n] + h / 2, y[n] + h / 2 * k1)
        k3 = F(t[n] + h / 2, y[n] + h / 2 * k2)
        k4 = F(t[n] + h, y[n] + h * k3)
        y[n + 1] = y[n] + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return y


t = np.linspace(0.0, 1.0, 500)  # the exam's grid
sol = rk4(pendulum, Y0, t)

# %% [markdown]
# ### Observed order
#
# Halve the step and the error should fall by $2^4 = 16$. Without an exact solution we compare
# each run at $t = 0.5$ s with a run on a much finer grid; the observed order between two steps
# is $p = \log_2(e_h / e_{h/2})$.

# %%
T = 0.5
fine = rk4(pendulum, Y0, np.linspace(0.0, T, 12801))[-1]
steps = [25, 50, 100, 200, 400]
errs = np.array([np.max(np.abs(rk4(pendulum, Y0, np.linspace(0.0, T, N + 1))[-1] - fine)) for N in steps])
orders = np.log2(errs[:-1] / errs[1:])
print(" steps   h (s)      max error at 0.5 s   observed order")
for k, (N, e) in enumerate(zip(steps, errs)):
    p = "" if k == 0 else f"{orders[k - 1]:.3f}"
    print(f"{N:5d}   {T / N:.5f}   {e:.3e}            {p}")

# %%
assert np.all(np.abs(orders[1:] - 4) < 0.15), orders

# %% [markdown]
# ### First crossing of the vertical
#
# θ changes sign between two grid times $t_k$ and $t_{k+1}$. On that step, the cubic Hermite
# interpolant built from $\theta$ and $\dot\theta$ (both in the RK4 state) is as accurate as
# the steps themselves; Newton's method finds its root $t^*$, and the same interpolation of
# $r$ and $\dot r$ gives the cord length there.

# %%
def hermite(t0, t1, y0, y1, d0, d1, s):
    """Cubic Hermite interpolant on [t0, t1] and its derivative, at time s."""
    h = t1 - t0
    u = (s - t0) / h
    h00, h10, h01, h11 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u, -2 * u**3 + 3 * u**2, u**3 - u**2
    value = h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1
    dh00, dh10, dh01, dh11 = 6 * u**2 - 6 * u, 3 * u**2 - 4 * u + 1, -6 * u**2 + 6 * u, 3 * u**2 - 2 * u
    slope = (dh00 * y0 + dh01 * y1) / h + dh10 * d0 + dh11 * d1
    return value, slope


k = int(np.flatnonzero(np.sign(sol[1:, 1]) != np.sign(sol[:-1, 1]))[0])
t0, t1 = t[k], t[k + 1]
s = t0 - sol[k, 1] * (t1 - t0) / (sol[k + 1, 1] - sol[k, 1])  # linear guess
for _ in range(20):
    value, slope = hermite(t0, t1, sol[k, 1], sol[k + 1, 1], sol[k, 3], sol[k + 1, 3], s)
    s_new = s - value / slope
    if abs(s_new - s) < 1e-15:
        break
    s = s_new
t_cross = s
r_cross = hermite(t0, t1, sol[k, 0], sol[k + 1, 0], sol[k, 2], sol[k + 1, 2], t_cross)[0]
print(f"first crossing of the vertical at t = {t_cross:.9f} s: r = {r_cross:.9f} m (the exam: 0.51 m)")

# %%
assert abs(r_cross - 0.51) < 0.005  # the exam's answer, to the digits it gives
assert t0 <= t_cross <= t1

fig, ax = plt.subplots()
ax2 = ax.twinx()
line_r = ax.plot(t, sol[:, 0], color="C0", label="cord length r (left axis)")
line_theta = ax2.plot(t, np.degrees(sol[:, 1]), color="black", linestyle="--", label="angle θ (right axis)")
mark = ax.plot([t_cross], [r_cross], "o", color="C3", label=f"first crossing of the vertical, r = {r_cross:.3f} m")
ax.set_xlabel("time t (s)")
ax.set_ylabel("cord length r (m)", color="C0")
ax.tick_params(axis="y", colors="C0")
ax2.set_ylabel("θ (deg)", color="black")
handles = line_r + line_theta + mark
ax.legend(handles, [h.get_label() for h in handles], loc="upper right", fontsize=8)
plt.show()

# %% [markdown]
# ## Questions
#
# 1. Apply the same rule to $\int_0^{\pi/2} dx/\sqrt{\sin x}$ without the substitution (map
#    $[0, \pi/2]$ to $[-1, 1]$ and divide by the weight). How does the error fall with $n$
#    now, and why?
# 2. The error ratio per node is $(1 + \sqrt 2)^{-2}$. From the error at $n = 12$, predict the
#    $n$ at which the error reaches $10^{-15}$, and check it in the table. What stops the
#    double-precision error from falling further, when the 40-digit column goes on?
# 3. Replace the Hermite interpolation by linear interpolation between $t_k$ and $t_{k+1}$.
#    How much does $r$ at the crossing change, and how does that compare with the RK4 error?
# 4. The exam's grid has 500 points on $[0, 1]$ s. From the error table, how many would you
#    need for the crossing length to be right to 1 µm?

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
# name: hw5-quadrature-pendulum
# files:
#   - kincheck
#   - odecheck.py
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
# # Homework 5 — Gauss–Chebyshev quadrature and an elastic pendulum
#
# **Part A.** Evaluate $I = \int_0^{\pi/2} dx/\sqrt{\sin x}$ by Gauss–Chebyshev quadrature,
#
# $$ \int_{-1}^{1} \frac{f(t)}{\sqrt{1 - t^2}}\,dt \approx \frac{\pi}{n + 1}\sum_{i=0}^{n} f(t_i),
#    \qquad t_i = \cos\frac{(2i + 1)\pi}{2n + 2}, $$
#
# after the substitution $\sin x = t^2$, which turns the integral into
# $\int_{-1}^{1} (1 - t^2)^{-1/2} (1 + t^2)^{-1/2}\,dt$, so $f(t) = 1/\sqrt{1 + t^2}$.
# The exact value is $I = 2.62205755429212$.
#
# **Part B.** A mass m = 0.2 kg hangs from an elastic cord (k = 30 N/m, unstretched length
# L = 0.4 m). Released from rest at θ = 45° with the cord unstretched, it moves by
#
# $$ \ddot r = r\dot\theta^2 + g\cos\theta - \frac km (r - L), \qquad
#    \ddot\theta = \frac{-2\dot r\dot\theta - g\sin\theta}{r}, \qquad g = 9.80665\ \text{m/s}^2. $$
#
# Find the cord length r when the mass first crosses the vertical (θ = 0).
#
# Run `grader.check("q1")` (and so on) after each question.

# %%
import numpy as np
import matplotlib.pyplot as plt

EXACT = 2.62205755429212  # the integral, exact
G, K, L, M = 9.80665, 30.0, 0.4, 0.2  # m/s², N/m, m, kg
t = np.linspace(0.0, 1.0, 501)  # time grid, s (step 0.002 s)

# %% [raw]
# # BEGIN QUESTION
# name: q1
# points: [1, 1]

# %% [markdown]
# **Q1 — the rule.** Write `gauss_chebyshev(f, n)`, the rule above with n + 1 nodes, and set
# `I7` to its value for f(t) = 1/√(1 + t²) and n = 7.

# %% [raw]
# # BEGIN SOLUTION

# %%
def gauss_chebyshev(f, n):
    """∫ f(t) / sqrt(1 - t²) dt over [-1, 1] by Gauss–Chebyshev with n + 1 nodes."""
    # BEGIN SOLUTION
    i = np.arange(n + 1)
    nodes = np.cos((2 * i + 1) * np.pi / (2 * n + 2))
    return np.pi / (n + 1) * np.sum(f(nodes))
    # END SOLUTION


def f(t):
    return 1.0 / np.sqrt(1.0 + t**2)


I7 = gauss_chebyshev(f, 7)  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_rule_is_exact_for_polynomials(gauss_chebyshev):
    import math
    import odecheck as oc

    oc.quadrature_rule(gauss_chebyshev, n=3, cases=[
        (lambda t: 1.0 + 0.0 * t, 0, math.pi),
        (lambda t: t**2, 2, math.pi / 2),
        (lambda t: t**6, 6, 5 * math.pi / 16),
    ])

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_I7(I7):
    import kincheck as kc

    # computed by mpmath (assignments/exam004.py)
    REF = 2.62205677582  # reference: I7
    kc.value("I7", I7, REF, rtol=1e-10, suspects=())

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q2
# points: [1, 1]

# %% [markdown]
# **Q2 — error against n.** Store |rule − EXACT| for n = 1, 2, …, 10 in `errors_gc`
# (10 numbers). The rule is exact for polynomials of degree up to 2n + 1: why is the error
# not zero here?

# %% [raw]
# # BEGIN SOLUTION

# %%
errors_gc = np.array([abs(gauss_chebyshev(f, n) - EXACT) for n in range(1, 11)])  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_errors_fall(errors_gc):
    import numpy as np
    import kincheck as kc

    e = kc.array(errors_gc, "errors_gc", grid=(1, 10, 1))
    assert np.all(e > 0), "`errors_gc` holds a zero or negative value: store the absolute error"
    assert np.all(np.diff(e) < 0), "`errors_gc` should fall as n grows"

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_errors_values(errors_gc):
    import kincheck as kc

    # computed by mpmath (assignments/exam004.py)
    ERRORS = [0.0569578939684, 0.00835387920278, 0.0012492495842, 0.000193092688489, 3.0370332993e-05, 4.8392849742e-06, 7.78475558716e-07, 1.26155646378e-07, 2.05640508865e-08, 3.36805176224e-09]  # reference: errors_gc
    kc.listed("errors_gc", errors_gc, ERRORS, rtol=1e-5)

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if isinstance(errors_gc, np.ndarray) and errors_gc.shape == (10,):
    fig, ax = plt.subplots()
    ax.semilogy(np.arange(1, 11), errors_gc, "o-")
    ax.set_xlabel("n (n + 1 nodes)")
    ax.set_ylabel("|rule − exact| (dimensionless)")
    plt.show()

# %% [raw]
# # BEGIN QUESTION
# name: q3
# points: [1, 1, 1]

# %% [markdown]
# **Q3 — RK4.** With the state y = (r, θ, ṙ, θ̇) in m, rad, m/s, rad/s, write the right-hand
# side `pendulum(t, y)` and the classical fourth-order Runge–Kutta method `rk4(F, y0, t)`
# (one row per time). Set `Y0` to the initial state and `sol` to the solution on `t`
# (501 × 4).

# %% [raw]
# # BEGIN SOLUTION

# %%
def pendulum(t, y):
    """dy/dt of the elastic pendulum, y = (r, theta, r_dot, theta_dot)."""
    # BEGIN SOLUTION
    r, th, rd, thd = y
    return np.array([
        rd,
        thd,
        r * thd**2 + G * np.cos(th) - K / M * (r - L),
        (-2 * rd * thd - G * np.sin(th)) / r,
    ])
    # END SOLUTION


def rk4(F, y0, t):
    """Classical Runge–Kutta on the grid t; returns one row of the state per time."""
    # BEGIN SOLUTION
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
    # END SOLUTION


Y0 = np.array([L, np.radians(45.0), 0.0, 0.0])  # SOLUTION
sol = rk4(pendulum, Y0, t)  # SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_initial_state(sol):
    import odecheck as oc

    oc.initial_state("sol", sol, [0.4, 0.7853981633974483, 0.0, 0.0], rows=501,
                     names=("r (m)", "θ (rad)", "ṙ (m/s)", "θ̇ (rad/s)"))

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_state_at_half_second(sol):
    import odecheck as oc

    # computed by mpmath (assignments/exam004.py)
    REF = [0.471409428657, -0.33923121466, -0.221242816746, -3.25718061843]  # reference: state_half
    oc.state("sol", sol, 250, REF, time="t = 0.5 s", rtol=1e-6)

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_state_at_one_second(sol):
    import odecheck as oc

    # computed by mpmath (assignments/exam004.py)
    REF = [0.460550966662, -0.396508462161, 0.5881987357, 2.98402279412]  # reference: state_end
    oc.state("sol", sol, 500, REF, time="t = 1 s", rtol=1e-5)

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q4
# points: [1]

# %% [markdown]
# **Q4 — observed order.** Solve up to t = 0.5 s with 50, 100 and 200 steps, compare the
# state at 0.5 s with a run of 3200 steps, and set `order_rk4` to log₂(e₁₀₀ / e₂₀₀), the
# observed order from the last two errors.

# %% [raw]
# # BEGIN SOLUTION

# %%
""" # BEGIN PROMPT
order_rk4 = ...
""" # END PROMPT
# BEGIN SOLUTION NO PROMPT
fine = rk4(pendulum, Y0, np.linspace(0.0, 0.5, 3201))[-1]
e = [np.max(np.abs(rk4(pendulum, Y0, np.linspace(0.0, 0.5, N + 1))[-1] - fine)) for N in (50, 100, 200)]
order_rk4 = np.log2(e[1] / e[2])
# END SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_order(order_rk4):
    import kincheck as kc

    kc.band("order_rk4", order_rk4, 3.8, 4.2, about=4.0, suspects=())

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %% [raw]
# # BEGIN QUESTION
# name: q5
# points: [1, 1, 1]

# %% [markdown]
# **Q5 — crossing the vertical.** Find the first time `t_cross` (s) at which θ = 0: take the
# step on which θ changes sign, interpolate θ there (a cubic through the step, using θ̇ too, is
# accurate enough) and solve for its root with Newton's method. Set `r_cross` to the cord
# length at that time (m).

# %% [raw]
# # BEGIN SOLUTION

# %%
""" # BEGIN PROMPT
t_cross = ...
r_cross = ...
""" # END PROMPT
# BEGIN SOLUTION NO PROMPT
def hermite(t0, t1, y0, y1, d0, d1, s):
    """Cubic Hermite interpolant on [t0, t1] and its derivative at s."""
    h = t1 - t0
    u = (s - t0) / h
    value = (2 * u**3 - 3 * u**2 + 1) * y0 + (u**3 - 2 * u**2 + u) * h * d0 \
        + (-2 * u**3 + 3 * u**2) * y1 + (u**3 - u**2) * h * d1
    slope = ((6 * u**2 - 6 * u) * y0 + (-6 * u**2 + 6 * u) * y1) / h \
        + (3 * u**2 - 4 * u + 1) * d0 + (3 * u**2 - 2 * u) * d1
    return value, slope


k = int(np.flatnonzero(np.sign(sol[1:, 1]) != np.sign(sol[:-1, 1]))[0])
s = t[k]
for _ in range(30):
    value, slope = hermite(t[k], t[k + 1], sol[k, 1], sol[k + 1, 1], sol[k, 3], sol[k + 1, 3], s)
    s -= value / slope
t_cross = s
r_cross = hermite(t[k], t[k + 1], sol[k, 0], sol[k + 1, 0], sol[k, 2], sol[k + 1, 2], s)[0]
# END SOLUTION

# %% [raw]
# # END SOLUTION

# %% [raw]
# # BEGIN TESTS

# %%
def test_crossing_is_plausible(t_cross, r_cross):
    import kincheck as kc

    kc.band("t_cross", t_cross, 0.2, 0.6, about=0.4, unit="s", suspects=())
    kc.band("r_cross", r_cross, 0.45, 0.6, about=0.51, unit="m", suspects=("mm",))

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_t_cross(t_cross):
    import kincheck as kc

    # computed by mpmath (assignments/exam004.py)
    REF = 0.396181280849  # reference: t_cross
    kc.value("t_cross", t_cross, REF, rtol=1e-5, unit="s", suspects=())

# %%
""" # BEGIN TEST CONFIG
hidden: true
""" # END TEST CONFIG
def test_r_cross(r_cross):
    import kincheck as kc

    # computed by mpmath (assignments/exam004.py)
    REF = 0.507745207652  # reference: r_cross
    kc.value("r_cross", r_cross, REF, rtol=1e-4, unit="m", suspects=("mm",))

# %% [raw]
# # END TESTS

# %% [raw]
# # END QUESTION

# %%
if isinstance(sol, np.ndarray) and sol.shape == (t.size, 4):
    fig, ax = plt.subplots()
    ax.plot(t, sol[:, 0])
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("cord length r (m)")
    plt.show()

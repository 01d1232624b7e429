"""Reference values of homework 5 (exam 004, problems 2 and 3), computed with mpmath.

These are independent of any Gauss–Chebyshev or Runge–Kutta code of the homework and
of lesson 7: the integral by mpmath's tanh-sinh quadrature (``mpmath.quad``), the rule's
values by its sum in 30-digit arithmetic, and the pendulum by mpmath's Taylor-series
ODE solver (``mpmath.odefun``) with the crossing of the vertical by ``mpmath.findroot``.
"""

from __future__ import annotations

__all__ = ["integral", "gauss_chebyshev", "pendulum", "expected"]

G, K, L, M = "9.80665", 30, "0.4", "0.2"  # m/s², N/m, m, kg


def _mp():
    import mpmath

    mpmath.mp.dps = 30
    return mpmath


def integral():
    """∫₀^{π/2} dx / sqrt(sin x) by mpmath.quad (the singularity at 0 is integrable)."""
    mp = _mp()
    return mp.quad(lambda x: 1 / mp.sqrt(mp.sin(x)), [0, mp.pi / 2])


def gauss_chebyshev(n: int):
    """The rule with n + 1 nodes applied to f(t) = 1/sqrt(1 + t²), in 30 digits."""
    mp = _mp()
    nodes = [mp.cos((2 * i + 1) * mp.pi / (2 * n + 2)) for i in range(n + 1)]
    return mp.pi / (n + 1) * mp.fsum(1 / mp.sqrt(1 + x**2) for x in nodes)


def pendulum():
    """(state(t) as a function, t_cross, r_cross): the elastic pendulum from rest at 45°."""
    mp = _mp()
    g, k, length, m = mp.mpf(G), mp.mpf(K), mp.mpf(L), mp.mpf(M)

    def rhs(t, y):
        r, th, rd, thd = y
        return [rd, thd, r * thd**2 + g * mp.cos(th) - k / m * (r - length), (-2 * rd * thd - g * mp.sin(th)) / r]

    state = mp.odefun(rhs, 0, [length, mp.pi / 4, 0, 0])
    t_cross = mp.findroot(lambda t: state(t)[1], mp.mpf("0.4"))
    return state, t_cross, state(t_cross)[0]


def expected() -> dict:
    exact = integral()
    state, t_cross, r_cross = pendulum()
    return {
        "I7": float(gauss_chebyshev(7)),
        "errors_gc": [float(abs(gauss_chebyshev(n) - exact)) for n in range(1, 11)],
        "state_half": [float(v) for v in state(0.5)],
        "state_end": [float(v) for v in state(1)],
        "t_cross": float(t_cross),
        "r_cross": float(r_cross),
    }

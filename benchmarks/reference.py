"""References the benchmarks time numkin against, written here independently of numkin.

Every linkage measured is a chain of *dyad loops*: loop ``k`` closes

    a e^{i phi} + b e^{i psi} + c e^{i (u + off)} + d = 0

in its two unknown angles ``phi`` and ``psi`` (rad), driven by ``u``: the
input angle for the first loop, the first unknown of the previous loop for
the others. ``a``, ``b``, ``c`` and ``d`` are real lengths (either sign).

* :func:`closed_form` -- positions by circle intersection, vectorised.
* :func:`closed_form_rates` -- closed form plus omega and alpha by 2x2
  Cramer rules on the differentiated loop equations, vectorised.
* :func:`ideal_sweep` -- a hand-written vectorised Newton: a scalar
  continuation at 13 nodes, a cubic Hermite predictor at every point, then
  Newton with 2x2 Cramer solves, loop after loop, on whole arrays.
* :func:`textbook_sweep` -- the way of the course's source documents: a
  sympy Jacobian built and lambdified inside every Newton call, one angle
  after another, each started from the previous solution.

Examples
--------
>>> import numpy as np
>>> chain = four_bar_chain(4.0, 1.0, 3.0, 3.0)
>>> q = closed_form(chain, np.radians([90.0]), signs=[1.0])
>>> np.round(np.degrees(q[:, 0]), 4)          # theta3, theta4 (numkin's open four-bar)
array([ 32.5561, 119.3714])
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "DyadLoop",
    "four_bar_chain",
    "homework_chain",
    "repeated_chain",
    "closed_form",
    "closed_form_rates",
    "ideal_sweep",
    "textbook_sweep",
    "pick_signs",
    "wrapped_max_diff",
    "HOMEWORK_1",
    "HOMEWORK_2",
    "HOMEWORK_OFFSET",
]

#: The homework's linkages (source document 003): fixed, input, coupler, output (in).
HOMEWORK_1 = (7.0, 1.94, 6.86, 2.36)
HOMEWORK_2 = (1.25, 2.39, 1.87, 1.26)
#: alpha = phi + 149 deg (rad).
HOMEWORK_OFFSET = math.radians(149.0)


@dataclass(frozen=True)
class DyadLoop:
    """``a e^{i phi} + b e^{i psi} + c e^{i(u + off)} + d = 0`` with driver ``u``.

    ``driver`` is -1 for the mechanism's input angle, else the index of the
    earlier loop whose first unknown drives this one.
    """

    a: float
    b: float
    c: float
    d: float
    off: float = 0.0
    driver: int = -1


def four_bar_chain(ground, crank, coupler, rocker):
    """numkin.linkages.four_bar's loop ``r2 e^{it2} + r3 e^{it3} - r4 e^{it4} - r1 = 0``; unknowns (theta3, theta4)."""
    return [DyadLoop(a=coupler, b=-rocker, c=crank, d=-ground)]


def _homework_loop(dims, off, driver):
    fixed, inp, coupler, out = dims
    return DyadLoop(a=out, b=coupler, c=inp, d=-fixed, off=off, driver=driver)


def homework_chain():
    """numkin.linkages.chained_four_bars' loops; unknowns (phi, psi, beta, gamma)."""
    return [_homework_loop(HOMEWORK_1, math.pi, -1), _homework_loop(HOMEWORK_2, HOMEWORK_OFFSET + math.pi, 0)]


def repeated_chain(loops: int, dims=HOMEWORK_1, offset=HOMEWORK_OFFSET):
    """``loops`` copies of the homework's first four-bar, each driven by the previous one's output plus ``offset``.

    Its input link is the shortest (a crank-rocker), so every loop assembles
    at every driving angle.
    """
    return [_homework_loop(dims, math.pi if k == 0 else offset + math.pi, k - 1) for k in range(loops)]


# ------------------------------------------------------------------ closed form
def _driver(loop, inputs, q):
    return inputs if loop.driver < 0 else q[2 * loop.driver]


def _intersect(loop, u, sign):
    """Circle intersection: the loop's (phi, psi) for driver angles u (rad), on branch ``sign``."""
    w = u + loop.off
    px = -loop.c * np.cos(w) - loop.d
    py = -loop.c * np.sin(w)
    a, b = abs(loop.a), abs(loop.b)
    dist = np.hypot(px, py)
    gamma = np.arccos(np.clip((a * a + dist * dist - b * b) / (2.0 * a * dist), -1.0, 1.0))
    phi = np.arctan2(py, px) + sign * gamma
    psi = np.arctan2(py - a * np.sin(phi), px - a * np.cos(phi))
    if loop.a < 0:
        phi = _opposite(phi)
    if loop.b < 0:
        psi = _opposite(psi)
    return phi, psi


def _opposite(angle):
    """angle + pi, kept in (-pi, pi] for angles from arctan2."""
    return np.where(angle > 0.0, angle - math.pi, angle + math.pi)


def closed_form(chain, inputs, signs) -> np.ndarray:
    """Positions (2 rows per loop, rad, wrapped) at every input, vectorised; shape (2K, N)."""
    inputs = np.asarray(inputs, dtype=float)
    q = np.empty((2 * len(chain), inputs.size))
    for k, (loop, sign) in enumerate(zip(chain, signs)):
        q[2 * k], q[2 * k + 1] = _intersect(loop, _driver(loop, inputs, q), sign)
    return q


def _cramer(loop, cp, sp_, cq, sq, rx, ry):
    """Solve ``a x e^{i phi} + b y e^{i psi} = rx + i ry`` for real x, y (whole arrays)."""
    s = sp_ * cq - cp * sq  # sin(phi - psi)
    x = (ry * cq - rx * sq) / (loop.a * s)
    y = (rx * sp_ - ry * cp) / (loop.b * s)
    return x, y


def closed_form_rates(chain, inputs, signs, omega, alpha=0.0):
    """Closed-form positions, angular velocities (rad/s) and accelerations (rad/s^2); each (2K, N).

    ``omega`` and ``alpha`` are the input's speed and acceleration.
    """
    inputs = np.asarray(inputs, dtype=float)
    q = closed_form(chain, inputs, signs)
    w = np.empty_like(q)
    acc = np.empty_like(q)
    for k, loop in enumerate(chain):
        if loop.driver < 0:
            u, du, ddu = inputs, omega, alpha
        else:
            u, du, ddu = q[2 * loop.driver], w[2 * loop.driver], acc[2 * loop.driver]
        phi, psi = q[2 * k], q[2 * k + 1]
        cp, sp_, cq, sq = np.cos(phi), np.sin(phi), np.cos(psi), np.sin(psi)
        cu, su = np.cos(u + loop.off), np.sin(u + loop.off)
        # a phi' e^{i phi} + b psi' e^{i psi} = -c u' e^{i(u+off)}
        dphi, dpsi = _cramer(loop, cp, sp_, cq, sq, -loop.c * du * cu, -loop.c * du * su)
        # ... = -c u'' e^{iu} - i (c u'^2 e^{iu} + a phi'^2 e^{i phi} + b psi'^2 e^{i psi})
        cx = loop.c * du * du * cu + loop.a * dphi * dphi * cp + loop.b * dpsi * dpsi * cq
        cy = loop.c * du * du * su + loop.a * dphi * dphi * sp_ + loop.b * dpsi * dpsi * sq
        ddphi, ddpsi = _cramer(loop, cp, sp_, cq, sq, -loop.c * ddu * cu + cy, -loop.c * ddu * su - cx)
        w[2 * k], w[2 * k + 1] = dphi, dpsi
        acc[2 * k], acc[2 * k + 1] = ddphi, ddpsi
    return q, w, acc


def wrapped_max_diff(a, b) -> float:
    """Largest difference of two angle arrays (rad), modulo 2 pi."""
    d = np.asarray(a, dtype=float) - np.asarray(b, dtype=float)
    return float(np.max(np.abs(np.remainder(d + math.pi, 2.0 * math.pi) - math.pi)))


def pick_signs(chain, inputs, values):
    """The circle-intersection branch of every loop that matches solved ``values`` (2K, N)."""
    signs = []
    inputs = np.asarray(inputs, dtype=float)[:1]
    values = np.asarray(values)[:, :1]
    for k in range(len(chain)):
        best = min((1.0, -1.0), key=lambda s: wrapped_max_diff(
            closed_form(chain, inputs, signs + [s])[2 * k: 2 * k + 2], values[2 * k: 2 * k + 2]))
        signs.append(best)
    return signs


# ------------------------------------------------------------------ hand-written Newton
def _residual(loop, u, phi, psi):
    cp, sp_, cq, sq = np.cos(phi), np.sin(phi), np.cos(psi), np.sin(psi)
    fx = loop.a * cp + loop.b * cq + loop.c * np.cos(u + loop.off) + loop.d
    fy = loop.a * sp_ + loop.b * sq + loop.c * np.sin(u + loop.off)
    return fx, fy, cp, sp_, cq, sq


def _newton_loop(loop, u, phi, psi, tol, maxiter=30):
    """Newton on one loop, all points at once: J delta = -F by the 2x2 Cramer rule."""
    for _ in range(maxiter):
        fx, fy, cp, sp_, cq, sq = _residual(loop, u, phi, psi)
        # i a e^{i phi} dphi + i b e^{i psi} dpsi = -F  <=>  a dphi e^{i phi} + b dpsi e^{i psi} = i F
        dphi, dpsi = _cramer(loop, cp, sp_, cq, sq, -fy, fx)
        phi = phi + dphi
        psi = psi + dpsi
        if np.max(np.abs(dphi)) < tol and np.max(np.abs(dpsi)) < tol:
            break
    return phi, psi


def _scalar_cramer(loop, phi, psi, rx, ry):
    cp, sp_, cq, sq = math.cos(phi), math.sin(phi), math.cos(psi), math.sin(psi)
    s = sp_ * cq - cp * sq
    return (ry * cq - rx * sq) / (loop.a * s), (rx * sp_ - ry * cp) / (loop.b * s)


def _scalar_newton(loop, u, phi, psi, tol, maxiter=30):
    """Newton on one loop at one input, in plain floats."""
    w = u + loop.off
    cw, sw = math.cos(w), math.sin(w)
    for _ in range(maxiter):
        fx = loop.a * math.cos(phi) + loop.b * math.cos(psi) + loop.c * cw + loop.d
        fy = loop.a * math.sin(phi) + loop.b * math.sin(psi) + loop.c * sw
        dphi, dpsi = _scalar_cramer(loop, phi, psi, -fy, fx)
        phi += dphi
        psi += dpsi
        if abs(dphi) < tol and abs(dpsi) < tol:
            break
    return phi, psi


def _scalar_tangent(loop, u, du, phi, psi):
    w = u + loop.off
    return _scalar_cramer(loop, phi, psi, -loop.c * du * math.cos(w), -loop.c * du * math.sin(w))


def ideal_sweep(chain, inputs, guess, nodes: int = 13, tol: float = 1e-12) -> np.ndarray:
    """Hand-written vectorised Newton over a sweep; returns (2K, N) positions (rad, continuous).

    A scalar continuation at ``nodes`` evenly spaced grid points (Euler
    predictor, Newton corrector, plain floats) from ``guess`` (2K values at
    ``inputs[0]``), a cubic Hermite predictor at every point from the nodes'
    values and tangents, then Newton loop after loop on the whole grid.
    """
    t = np.asarray(inputs, dtype=float)
    idx = np.unique(np.linspace(0, t.size - 1, min(nodes, t.size)).round().astype(int))
    tn = t[idx]
    K = len(chain)
    qn = np.empty((2 * K, idx.size))
    dn = np.empty((2 * K, idx.size))
    x = [float(v) for v in np.asarray(guess, dtype=float).ravel()]
    d = None
    prev_t = float(tn[0])
    for j, tj in enumerate(tn.tolist()):
        if d is not None:
            x = [xi + di * (tj - prev_t) for xi, di in zip(x, d)]
        d = [0.0] * (2 * K)
        for k, loop in enumerate(chain):
            u, du = (tj, 1.0) if loop.driver < 0 else (x[2 * loop.driver], d[2 * loop.driver])
            x[2 * k], x[2 * k + 1] = _scalar_newton(loop, u, x[2 * k], x[2 * k + 1], tol)
            d[2 * k], d[2 * k + 1] = _scalar_tangent(loop, u, du, x[2 * k], x[2 * k + 1])
        qn[:, j], dn[:, j] = x, d
        prev_t = tj
    # cubic Hermite predictor on every interval between nodes
    if idx.size > 1:
        seg = np.clip(np.searchsorted(tn, t, side="right") - 1, 0, idx.size - 2)
        t0, t1 = tn[seg], tn[seg + 1]
        h = t1 - t0
        s = (t - t0) / h
        s2, s3 = s * s, s * s * s
        h00, h10, h01, h11 = 2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2
        q = h00 * qn[:, seg] + (h10 * h) * dn[:, seg] + h01 * qn[:, seg + 1] + (h11 * h) * dn[:, seg + 1]
    else:
        q = np.repeat(qn, t.size, axis=1)
    for k, loop in enumerate(chain):
        u = t if loop.driver < 0 else q[2 * loop.driver]
        q[2 * k], q[2 * k + 1] = _newton_loop(loop, u, q[2 * k], q[2 * k + 1], tol)
    return q


# ------------------------------------------------------------------ textbook
def _textbook_newton(loop, u, guess, tol=1e-12, max_iter=100):
    """One solve as in the source documents: symbols, residuals, Jacobian and lambdify built per call."""
    import sympy as sp

    phi, psi = sp.symbols("phi psi")
    w = u + loop.off
    f1 = loop.a * sp.cos(phi) + loop.b * sp.cos(psi) + loop.c * math.cos(w) + loop.d
    f2 = loop.a * sp.sin(phi) + loop.b * sp.sin(psi) + loop.c * math.sin(w)
    F = sp.Matrix([f1, f2])
    J = F.jacobian([phi, psi])
    F_func = sp.lambdify((phi, psi), F, "numpy")
    J_func = sp.lambdify((phi, psi), J, "numpy")
    x = np.array(guess, dtype=float)
    for _ in range(max_iter):
        F_val = np.array(F_func(x[0], x[1]), dtype=np.float64).flatten()
        J_val = np.array(J_func(x[0], x[1]), dtype=np.float64)
        delta = np.linalg.solve(J_val, -F_val)
        x = x + delta
        if np.linalg.norm(delta) / np.linalg.norm(x) < tol:
            break
    return x


def textbook_sweep(chain, inputs, guess) -> np.ndarray:
    """The source documents' sequential sweep: (2K, N) positions, each angle started from the previous one."""
    t = np.asarray(inputs, dtype=float)
    q = np.empty((2 * len(chain), t.size))
    x = np.asarray(guess, dtype=float).copy()
    for j, tj in enumerate(t.tolist()):
        for k, loop in enumerate(chain):
            u = tj if loop.driver < 0 else x[2 * loop.driver]
            x[2 * k: 2 * k + 2] = _textbook_newton(loop, float(u), x[2 * k: 2 * k + 2])
        q[:, j] = x
    return q

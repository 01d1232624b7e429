"""Other planar-kinematics packages on numkin's linkages, when they are installed (none is required).

Each function returns ``None`` when its package cannot be imported, else a
dict of contenders ``label -> (callable, note)``; calling a contender solves
the linkage over ``n`` input angles spanning one turn. Position notes name
the largest difference of the package's output angle from the closed form
(rad, modulo 2 pi), so all contenders are seen to solve the same problem.

Examples
--------
>>> status("surely-not-a-package-name") is None
True
"""

from __future__ import annotations

import importlib
import importlib.metadata
import math

import numpy as np

from . import reference

__all__ = ["status", "pylinkage_four_bar", "pylinkage_chained", "mechanism_four_bar", "PACKAGES"]

#: Packages looked for, in the order they are reported.
PACKAGES = ("pylinkage", "mechanism", "pyslvs")


def status(name: str):
    """The installed version of ``name`` if it imports, else None."""
    try:
        importlib.import_module(name)
    except Exception:  # any failure to import means "not available here"
        return None
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return "?"


def _rocker_diff(chain, crank, rocker):
    """Largest closed-form difference of the rocker angle at the package's own crank angles."""
    ref = reference.closed_form(chain, crank, [1.0])[1]
    return reference.wrapped_max_diff(rocker, ref)


def _pylinkage_contenders(linkage, driver, n, omega, diff):
    """Contenders of a built pylinkage Linkage, compiled (or loaded from numba's cache) before any timing."""
    linkage.set_input_velocity(driver, omega, 0.0)

    def fast():
        return linkage.step_fast(iterations=n)

    def fast_kinematics():
        return linkage.step_fast_with_kinematics(iterations=n)

    def plain():
        return list(linkage.step(iterations=n))

    pos = fast()
    fast_kinematics()
    numba = status("numba")
    engine = f"numba {numba}" if numba else "pure Python (numba not installed)"
    return {
        "pylinkage step_fast (positions)": (fast, f"{engine}; max diff {diff(pos):.1e} rad"),
        "pylinkage step_fast_with_kinematics": (fast_kinematics, f"{engine}; positions, velocities, accelerations"),
        "pylinkage step (plain Python)": (plain, "positions"),
    }


def pylinkage_four_bar(ground, crank, coupler, rocker, n, omega=10.0):
    """pylinkage on the four-bar: ``step_fast`` (numba when installed), ``step_fast_with_kinematics``, plain ``step``."""
    if status("pylinkage") is None:
        return None
    import pylinkage as pl

    chain = reference.four_bar_chain(ground, crank, coupler, rocker)
    q0 = reference.closed_form(chain, np.array([0.0]), [1.0])[:, 0]
    o2, o4 = pl.Ground(0.0, 0.0, name="O2"), pl.Ground(ground, 0.0, name="O4")
    driver = pl.Crank(o2, crank, angular_velocity=2.0 * math.pi / n, initial_angle=0.0, name="A")
    b = pl.RRRDyad(driver.output, o4, coupler, rocker,
                   x=ground + rocker * math.cos(q0[1]), y=rocker * math.sin(q0[1]), name="B")

    def diff(pos):
        a, bb = pos[:, 2], pos[:, 3]
        return _rocker_diff(chain, np.arctan2(a[:, 1], a[:, 0]), np.arctan2(bb[:, 1], bb[:, 0] - ground))

    return _pylinkage_contenders(pl.Linkage([o2, o4, driver, b]), driver, n, omega, diff)


def pylinkage_chained(n, omega=10.0):
    """pylinkage on the homework's chained four-bars; linkage 2's input rigidly 149 deg from linkage 1's output."""
    if status("pylinkage") is None:
        return None
    import pylinkage as pl

    (f1, i1, c1, o1), (f2, i2, c2, o2) = reference.HOMEWORK_1, reference.HOMEWORK_2
    chain, signs = reference.homework_chain(), [1.0, -1.0]
    phi, _, beta, _ = reference.closed_form(chain, np.array([0.0]), signs)[:, 0]
    c, d, g = pl.Ground(0.0, 0.0, name="C"), pl.Ground(f1, 0.0, name="D"), pl.Ground(-f2, 0.0, name="G")
    a = pl.Crank(d, i1, angular_velocity=2.0 * math.pi / n, initial_angle=0.0, name="A")
    b = pl.RRRDyad(a.output, c, c1, o1, x=o1 * math.cos(phi), y=o1 * math.sin(phi), name="B")
    e = pl.FixedDyad(c, b, i2, reference.HOMEWORK_OFFSET, name="E")
    f = pl.RRRDyad(e, g, c2, o2, x=-f2 + o2 * math.cos(beta), y=o2 * math.sin(beta), name="F")

    def diff(pos):
        theta = np.arctan2(pos[:, 3, 1], pos[:, 3, 0] - f1)
        ref = reference.closed_form(chain, theta, signs)[2]
        return reference.wrapped_max_diff(np.arctan2(pos[:, 6, 1], pos[:, 6, 0] + f2), ref)

    return _pylinkage_contenders(pl.Linkage([c, d, g, a, b, e, f]), a, n, omega, diff)


def mechanism_four_bar(ground, crank, coupler, rocker, n, omega=10.0):
    """The ``mechanism`` package: fsolve at every angle for position, velocity and acceleration."""
    if status("mechanism") is None:
        return None
    from mechanism import Mechanism, Vector, get_joints

    chain = reference.four_bar_chain(ground, crank, coupler, rocker)
    theta = np.linspace(0.0, 2.0 * math.pi, n)
    guess = reference.closed_form(chain, theta[:1], [1.0])[:, 0]
    O, A, B, C = get_joints("O A B C")
    va, vb = Vector((O, A), r=crank), Vector((A, B), r=coupler)
    vc, vd = Vector((C, B), r=rocker), Vector((O, C), r=ground, theta=0, style="ground")

    def loops(x, i):
        out = np.zeros((1, 2))
        out[0] = va(i) + vb(x[0]) - vc(x[1]) - vd()
        return out.flatten()

    def run():
        m = Mechanism(vectors=[va, vb, vc, vd], origin=O, loops=loops, pos=theta,
                      vel=np.full(n, omega), acc=np.zeros(n), guess=(guess, np.zeros(2), np.zeros(2)))
        m.iterate()
        return vc.pos.thetas

    diff = _rocker_diff(chain, theta, run())
    return {"mechanism (fsolve per angle)": (run, f"positions, velocities, accelerations; max diff {diff:.1e} rad")}

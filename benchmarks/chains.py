"""numkin mechanisms of the benchmark's dyad-loop chains, built with :class:`numkin.Loop` and :class:`numkin.Mechanism`.

Examples
--------
>>> import numpy as np
>>> from benchmarks import reference
>>> chain = reference.repeated_chain(2)
>>> mech = build(chain)
>>> mech.unknowns
('phi1', 'psi1', 'phi2', 'psi2')
>>> sweep = mech.sweep(np.radians([0.0, 1.0]))
>>> signs = reference.pick_signs(chain, sweep.inputs, sweep.values)
>>> reference.wrapped_max_diff(reference.closed_form(chain, sweep.inputs, signs), sweep.values) < 1e-10
True
"""

from __future__ import annotations

import numpy as np

from . import reference

__all__ = ["build", "start_guess"]


def start_guess(chain, signs=None, at: float = 0.0) -> np.ndarray:
    """The closed-form position of every unknown (rad) at input ``at``, on branch ``signs`` (default +1 each)."""
    signs = signs or [1.0] * len(chain)
    return reference.closed_form(chain, np.array([at]), signs)[:, 0]


def build(chain, signs=None, scale: float = 1.0):
    """A numkin Mechanism for ``chain`` (lengths multiplied by ``scale``), input ``theta``.

    Loop ``k`` has unknowns ``phi<k>``, ``psi<k>`` (k from 1) and its own
    parameter symbols; the starting guess is the closed form at theta = 0.
    """
    import sympy as sp

    import numkin

    theta = sp.Symbol("theta")
    loops, params, unknowns = [], {}, []
    for k, lp in enumerate(chain, start=1):
        phi, psi = sp.symbols(f"phi{k} psi{k}")
        A, B, C, D, OFF = sp.symbols(f"a{k} b{k} c{k} d{k} off{k}", positive=True)
        u = theta if lp.driver < 0 else unknowns[2 * lp.driver]
        sgn = [1 if v >= 0 else -1 for v in (lp.a, lp.b, lp.c, lp.d)]
        vectors = [(sgn[0] * A, phi), (sgn[1] * B, psi), (sgn[2] * C, u + OFF), (sgn[3] * D, 0)]
        loops.append(numkin.Loop.from_vectors(vectors, [phi, psi], name=f"loop {k}"))
        params.update({A: abs(lp.a) * scale, B: abs(lp.b) * scale, C: abs(lp.c) * scale,
                       D: abs(lp.d) * scale, OFF: lp.off})
        unknowns += [phi, psi]
    guess = dict(zip((str(u) for u in unknowns), start_guess(chain, signs).tolist()))
    lengths = [abs(v) * scale for lp in chain for v in (lp.a, lp.b, lp.c, lp.d)]
    return numkin.Mechanism(loops, theta, params, name=f"chain of {len(chain)} four-bars",
                            guess=guess, guess_input=0.0, length_unit="in", length_scale=max(lengths))

"""The chained homework's first point: Newton starts from the circle-intersection position nearest the guess."""

import math

import numpy as np
import pytest

from numkin import linkages
from numkin.linkages.chained_four_bars import _nearest

DIMS = (7.0, 1.94, 6.86, 2.36, 1.25, 2.39, 1.87, 1.26, math.radians(149.0))
GUESS = {"phi": math.radians(45.0), "psi": math.radians(60.0), "beta": math.radians(30.0), "gamma": math.radians(270.0)}


def _closes(x, theta):
    """Both loops' residuals (complex), written out from the homework's loop form."""
    f1, i1, c1, o1, f2, i2, c2, o2, off = DIMS
    phi, psi, beta, gamma = x
    one = o1 * np.exp(1j * phi) + c1 * np.exp(1j * psi) - i1 * np.exp(1j * theta) - f1
    two = o2 * np.exp(1j * beta) + c2 * np.exp(1j * gamma) - i2 * np.exp(1j * (phi + off)) - f2
    return abs(one), abs(two)


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.0, 4.5])
def test_nearest_position_closes_both_loops(theta):
    x = _nearest(list(GUESS.values()), theta, DIMS)
    assert max(_closes(x, theta)) < 1e-13


def test_default_start_selects_the_assembly_newton_selects_from_the_homework_guess():
    mech = linkages.chained_four_bars()
    inputs = np.radians(np.arange(0.0, 361.0))
    default = mech.sweep(inputs)             # Newton from the closed-form position
    from_guess = mech.sweep(inputs, guess=GUESS)   # Newton from the homework's guesses themselves
    np.testing.assert_allclose(default.values, from_guess.values, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(default.iterations[1:], from_guess.iterations[1:])
    assert default.iterations[0] < from_guess.iterations[0]


def test_the_other_branch_is_chosen_by_a_guess_near_it():
    g = list(GUESS.values())
    x = _nearest(g, 0.0, DIMS)
    # at theta = 0 linkage 1 is symmetric about its base line: its other assembly is (-phi, -psi)
    other = _nearest([-x[0], -x[1], x[2], x[3]], 0.0, DIMS)
    assert other[:2] == pytest.approx([-x[0], -x[1]], abs=1e-12)
    assert max(_closes(other, 0.0)) < 1e-13


def test_a_loop_that_cannot_close_gives_no_start():
    assert _nearest(list(GUESS.values()), 0.0, (7.0, 1.94, 1.0, 1.0, *DIMS[4:])) is None


def test_other_dimensions_start_on_the_circle_intersection_nearest_the_guess():
    # fixed1 = 7.1: Newton from the homework's guesses themselves wanders to the assembly phi = -19.5 deg; the
    # default start is the one nearest the guesses (sum of angular distances), as the closed-form tests choose it
    f1, i1, c1, o1 = 7.1, 1.94, 6.86, 2.36
    sweep = linkages.chained_four_bars(fixed1=f1).sweep(np.radians([0.0, 1.0]))
    # at theta = 0 linkage 1 is a triangle on its base line: cos(phi) from the law of cosines, phi = +-acos
    phi = math.acos((o1**2 + (f1 + i1) ** 2 - c1**2) / (2 * o1 * (f1 + i1)))
    candidates = [(s * phi, math.atan2(-s * o1 * math.sin(phi), f1 + i1 - o1 * math.cos(phi))) for s in (1, -1)]
    miss = [abs(math.remainder(p - GUESS["phi"], 2 * math.pi)) + abs(math.remainder(q - GUESS["psi"], 2 * math.pi))
            for p, q in candidates]
    nearest = candidates[int(np.argmin(miss))]
    assert sweep.values[:2, 0] == pytest.approx(nearest, abs=1e-12)


def test_the_start_reads_the_dimensions_as_they_are_at_the_sweep():
    inputs = np.radians(np.arange(0.0, 91.0, 5.0))
    changed = linkages.chained_four_bars()
    changed.parameter_values[4] = 1.3  # fixed2, after the build
    fresh = linkages.chained_four_bars(fixed2=1.3)
    np.testing.assert_array_equal(changed.sweep(inputs).values, fresh.sweep(inputs).values)

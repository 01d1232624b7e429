"""Exam 004, problems 2 and 3: lesson 7's numbers and homework 5's references against mpmath.

The references are independent computations: the integral by mpmath's tanh-sinh
quadrature, the elastic pendulum by mpmath's Taylor-series ODE solver with
``findroot`` for the crossing of the vertical (``assignments/exam004.py``).  Lesson 7
(``notebooks/07_quadrature_and_elastic_pendulum.py``) is run as a script and its own
Gauss-Chebyshev values, RK4 solution and crossing are compared with them.
"""

from __future__ import annotations

import math
import runpy
from pathlib import Path

import numpy as np
import pytest
from conftest import load_module

ROOT = Path(__file__).resolve().parents[1]
LESSON = ROOT / "notebooks" / "07_quadrature_and_elastic_pendulum.py"


_load = load_module


exam004 = _load("numkin_assignments_exam004", ROOT / "assignments" / "exam004.py")
pytest.importorskip("mpmath")


@pytest.fixture(scope="module")
def reference():
    state, t_cross, r_cross = exam004.pendulum()
    return {"I": float(exam004.integral()), "state": state, "t_cross": float(t_cross), "r_cross": float(r_cross)}


@pytest.fixture(scope="module")
def lesson(tmp_path_factory):
    """The lesson's variables after running it top to bottom (figures to a non-interactive backend)."""
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path_factory.mktemp("lesson7"))
        mp.setattr(plt, "show", lambda *a, **k: None)
        values = runpy.run_path(str(LESSON))
    plt.close("all")
    return values


def test_exact_integral_is_the_documents(reference):
    assert reference["I"] == pytest.approx(2.62205755429212, abs=5e-15)
    # and the closed form Γ(1/4)² / (2 sqrt(2π))
    assert reference["I"] == pytest.approx(math.gamma(0.25) ** 2 / (2 * math.sqrt(2 * math.pi)), rel=1e-15)


def test_documents_n7_value_is_the_rule_with_eight_nodes():
    assert float(exam004.gauss_chebyshev(7)) == pytest.approx(2.622056775816561, abs=1e-15)


def test_lesson_quadrature_against_mpmath(lesson, reference):
    assert lesson["EXACT"] == pytest.approx(reference["I"], rel=1e-15)
    assert lesson["I7"] == pytest.approx(float(exam004.gauss_chebyshev(7)), abs=1e-15)
    want = [abs(float(exam004.gauss_chebyshev(int(n))) - reference["I"]) for n in lesson["ns"]]
    assert np.allclose(lesson["errors"], want, rtol=1e-4, atol=1e-15)


def test_lesson_rk4_against_mpmath(lesson, reference):
    t, sol = lesson["t"], lesson["sol"]
    for k in (100, 250, 499):
        want = np.array([float(v) for v in reference["state"](t[k])])
        assert np.max(np.abs(sol[k] - want)) < 1e-6 * np.max(np.abs(want)), (t[k], sol[k], want)


def test_lesson_observed_order_is_four(lesson):
    assert np.all(np.abs(lesson["orders"][1:] - 4.0) < 0.15)


def test_lesson_crossing_against_mpmath(lesson, reference):
    assert lesson["t_cross"] == pytest.approx(reference["t_cross"], abs=1e-7)
    assert lesson["r_cross"] == pytest.approx(reference["r_cross"], abs=1e-7)
    assert round(reference["r_cross"], 2) == 0.51  # the document's answer

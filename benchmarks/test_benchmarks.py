"""Smoke tests of the benchmarks: they run, and their references solve the same problem numkin does.

No timing is asserted anywhere: times depend on the machine and its load.
Run with ``python -m pytest -q -p no:cacheprovider benchmarks``; the whole
``--quick`` run is marked slow.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmarks import reference, run, suites

ANGLES = np.radians(np.arange(0.0, 361.0, 5.0))


@pytest.mark.parametrize("chain", [reference.four_bar_chain(4.0, 1.0, 3.0, 3.0), reference.homework_chain(),
                                   reference.repeated_chain(3)], ids=["four-bar", "homework", "chain of 3"])
def test_references_close_their_loops_and_agree(chain):
    signs = [1.0] * len(chain) if len(chain) != 2 else [1.0, -1.0]
    q = reference.closed_form(chain, ANGLES, signs)
    for k, loop in enumerate(chain):  # every loop equation holds at the closed form
        u = ANGLES if loop.driver < 0 else q[2 * loop.driver]
        z = (loop.a * np.exp(1j * q[2 * k]) + loop.b * np.exp(1j * q[2 * k + 1])
             + loop.c * np.exp(1j * (u + loop.off)) + loop.d)
        assert np.max(np.abs(z)) < 1e-12
    assert reference.wrapped_max_diff(reference.ideal_sweep(chain, ANGLES, q[:, 0]), q) < 1e-10
    assert reference.wrapped_max_diff(reference.textbook_sweep(chain, ANGLES[:3], q[:, 0]), q[:, :3]) < 1e-10


def test_closed_form_rates_match_centred_differences_of_the_positions():
    chain, signs, omega, alpha = reference.homework_chain(), [1.0, -1.0], 10.0, 3.0
    theta, h = np.radians(np.arange(10.0, 350.0, 20.0)), 1e-4
    q, w, a = reference.closed_form_rates(chain, theta, signs, omega, alpha)
    q_plus, q_minus = (reference.closed_form(chain, theta + s * h, signs) for s in (1.0, -1.0))
    dq = np.angle(np.exp(1j * (q_plus - q_minus))) / (2 * h)
    d2q = np.angle(np.exp(1j * (q_plus - q))) / h**2 - np.angle(np.exp(1j * (q - q_minus))) / h**2
    np.testing.assert_allclose(w, omega * dq, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(a, omega**2 * d2q + alpha * dq, rtol=1e-4, atol=1e-3)


def test_homework_reference_gives_the_documents_exact_values():
    """Source document 003: at theta = 100 deg, omega_beta = 10.633 rad/s and alpha_beta = -28.375 rad/s^2 at 450 rad/min."""
    _, w, a = reference.closed_form_rates(reference.homework_chain(), np.radians([100.0]), [1.0, -1.0], 450 / 60)
    assert round(float(w[2, 0]), 3) == 10.633
    assert round(float(a[2, 0]), 3) == -28.375


def test_one_table_as_markdown():
    text = run.main(["--quick", "--only", "sweep", "--sizes", "36"], echo=False)
    assert "| four-bar | 36 |" in text and "| chained homework | 36 |" in text
    assert "numkin / closed form" in text


def test_the_predictor_table_gives_both_sweeps_and_leaves_the_flag_as_it_was():
    from numkin import batch_fill

    table = suites.predictors(suites.Settings.quick(), sizes=(37,))
    rows = {row[0]: row for row in table.rows}
    assert set(rows) == set(suites.predictor_linkages()) and batch_fill.TURN is True
    assert rows["four-bar 4:1:3:3"][5] == "165 → 128"  # one batch step fewer per point with the fit
    before, after = rows["chained-four-bars"][5].split(" → ")
    assert before == after  # the fit refused: the same evaluations


def test_the_predictor_table_takes_every_registered_linkage_with_its_defaults(monkeypatch):
    import dataclasses

    from numkin import linkages

    built = suites.predictor_linkages()
    assert [name.split(" ")[0].replace("-", "_") for name in built] == list(linkages.SPECS)
    assert built["six-bar"]().title == linkages.six_bar().title
    # a linkage without defaults for its dimensions, and none given: the table says what it needs
    copy = dataclasses.replace(linkages.spec("slider_crank"), name="slider_copy")
    monkeypatch.setitem(linkages.SPECS, "slider_copy", copy)
    with pytest.raises(ValueError, match="needs slider_copy's crank, rod"):
        suites.predictor_linkages()
    monkeypatch.setitem(suites.GIVEN_DIMENSIONS, "slider_copy", (40.0, 100.0))
    assert list(suites.predictor_linkages())[-1] == "slider-copy 40:100"


def test_the_tables_say_no_verdict():
    table = suites.sweep_scaling(suites.Settings.quick(), sizes=(36,), linkages=("four-bar",))
    words = " ".join(map(str, table.rows + table.columns + table.notes)).lower()
    assert not any(w in words for w in ("pass", "fail", "target", "goal", " met"))


@pytest.mark.slow
def test_quick_mode_runs_every_table(tmp_path):
    out = tmp_path / "bench.md"
    text = run.main(["--quick", "--output", str(out)], echo=False)
    assert out.read_text(encoding="utf-8") == text
    for title in ("Start-up", "four-bar, N = 361", "chained homework, N = 361", "Sweep alone against N",
                  "Chains of K four-bars", "Rebuild of a same-shape chain"):
        assert f"## {title}" in text
    assert not math.isnan(float(text.split("| `numkin --help` | ")[1].split(" |")[0]))

"""Sweeps: continuation on one branch, singular positions, errors, grids, the Sweep object.

References are closed forms derived here (circle intersection for the
four-bar); angles are compared continuously (no 2 pi jumps).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import sympy as sp

from numkin import (
    AssemblyError,
    BranchError,
    ConvergenceError,
    Loop,
    Mechanism,
    SingularityWarning,
    Sweep,
    linkages,
)

TWO_PI = 2 * math.pi
FULL_TURN = np.radians(np.arange(0.0, 361.0))
CR = (4.0, 1.0, 3.0, 3.0)  # crank-rocker: ground, crank, coupler, rocker


def four_bar_reference(theta2, r1, r2, r3, r4, side=1.0):
    """Circle intersection: B at r3 from A = r2 e^{i theta2} and r4 from O4 = (r1, 0); side +1 left of A -> O4."""
    ax, ay = r2 * np.cos(theta2), r2 * np.sin(theta2)
    dx, dy = r1 - ax, -ay
    d = np.hypot(dx, dy)
    ux, uy = dx / d, dy / d
    along = (r3**2 - r4**2 + d**2) / (2 * d)
    h = np.sqrt(r3**2 - along**2)
    bx, by = ax + along * ux - side * h * uy, ay + along * uy + side * h * ux
    return np.arctan2(by - ay, bx - ax), np.arctan2(by, bx - r1)


def assert_angle_continuous(got, ref, atol=1e-10):
    ref = np.unwrap(ref)
    k = np.round((got[0] - ref[0]) / TWO_PI)
    np.testing.assert_allclose(got, ref + TWO_PI * k, rtol=0, atol=atol)
    if got.size > 1:
        assert np.max(np.abs(np.diff(got))) <= 1.5 * np.max(np.abs(np.diff(ref))) + 1e-9


def check_four_bar(sweep, dims=CR, side=1.0, atol=1e-10):
    t3, t4 = four_bar_reference(sweep.inputs, *dims, side)
    assert_angle_continuous(sweep["theta3"], t3, atol)
    assert_angle_continuous(sweep["theta4"], t4, atol)


# ------------------------------------------------------------ assembly errors
def test_triple_rocker_over_a_full_turn_names_class_and_range():
    with pytest.raises(AssemblyError) as err:
        linkages.four_bar(7, 4, 3, 5).sweep(FULL_TURN)
    msg = str(err.value)
    assert "non-Grashof" in msg
    assert "88.98" in msg
    # the closed form of that limit: cos(theta2) = (7^2 + 4^2 - (3 + 5)^2) / (2 * 7 * 4)
    assert f"{math.degrees(math.acos(1 / 56)):.2f}" == "88.98"
    assert isinstance(err.value, ValueError)


def test_linkage_that_assembles_nowhere():
    with pytest.raises(AssemblyError, match="cannot be assembled at any input angle"):
        linkages.four_bar(10, 6, 1, 1).sweep(FULL_TURN)


def test_slider_crank_rod_too_short():
    with pytest.raises(AssemblyError, match="rod"):
        linkages.slider_crank(3, 1).sweep(FULL_TURN)


# ------------------------------------------------------- singular positions
def test_change_point_raises_branch_error_at_180():
    inputs = np.radians(np.arange(10.0, 351.0))
    with pytest.raises(BranchError) as err:
        linkages.four_bar(5, 2, 5, 2).sweep(inputs)
    assert err.value.kind == "change point"
    assert math.degrees(err.value.input_value) == pytest.approx(180.0, abs=1e-3)
    assert err.value.loop == "O2-A-B-O4"
    assert "180.000" in str(err.value)


def test_change_point_at_the_start_is_singular():
    with pytest.raises(BranchError) as err:
        linkages.four_bar(5, 2, 5, 2).sweep(FULL_TURN)
    assert err.value.kind == "singular"
    assert err.value.input_value == 0.0


def test_change_point_reported_and_warned():
    inputs = np.radians(np.arange(10.0, 351.0))
    with pytest.warns(SingularityWarning) as record:
        sweep = linkages.four_bar(5, 2, 5, 2).sweep(inputs, on_singular="report")
    assert any("passes a singular position" in str(w.message) for w in record)
    kinds = [e.kind for e in sweep.events]
    assert len(record) == len(sweep.events)
    assert kinds.count("change point") == 1  # met from a node and again from grid points: recorded once
    event = sweep.events[kinds.index("change point")]
    assert math.degrees(event.input_value) == pytest.approx(180.0, abs=1e-3)
    assert event.loop == "O2-A-B-O4"
    # the smooth continuation through the change point is the parallelogram: theta3 = 0, theta4 = theta2
    np.testing.assert_allclose(sweep["theta3"], 0.0, atol=1e-10)
    np.testing.assert_allclose(sweep["theta4"], inputs, atol=1e-10)


def test_near_toggle_stays_on_one_branch_and_reports_condition():
    dims = (4.0, 2.0, 4.0001, 2.0)
    inputs = np.radians(np.arange(1.0, 360.0))
    sweep = linkages.four_bar(*dims).sweep(inputs)
    t3, t4 = sweep["theta3"], sweep["theta4"]
    sign = np.sign(np.sin(t4 - t3))
    assert np.all(sign == sign[0])
    check_four_bar(sweep, dims, 1.0, atol=1e-9)
    # condition numbers: those of the scaled 2 x 2 Jacobian, computed here
    r3, r4 = dims[2], dims[3]
    jac = np.array([[-r3 * np.sin(t3), r4 * np.sin(t4)], [r3 * np.cos(t3), -r4 * np.cos(t4)]]) / max(dims)
    cond = np.linalg.cond(np.moveaxis(jac, -1, 0))
    np.testing.assert_allclose(sweep.cond, cond, rtol=1e-8)
    k = int(np.argmax(sweep.cond))
    assert 170.0 <= math.degrees(inputs[k]) <= 190.0 or k in (0, inputs.size - 1)
    assert sweep.cond[178] > 100  # coupler and rocker almost in line at theta2 = 180
    assert "cond" in sweep.to_frame().columns


def test_toggle_of_a_hand_written_triple_rocker():
    """No assembly check: the continuation itself finds the limit position at 88.98 deg."""
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4", real=True)
    loop = Loop.from_vectors([(4, t2), (3, t3), (-5, t4), (-7, 0)], [t3, t4], name="rocker loop")
    ref = linkages.four_bar(7, 4, 3, 5).default_guess
    m = Mechanism([loop], t2, guess=ref, length_scale=7.0)
    limit = math.degrees(math.acos(1 / 56))
    for inputs in (np.radians(np.arange(0.0, 100.0, 1.0)), np.radians(np.arange(0.0, -100.0, -7.0))):
        with pytest.raises(BranchError) as err:
            m.sweep(inputs)
        assert err.value.kind == "toggle"
        assert abs(math.degrees(err.value.input_value)) == pytest.approx(limit, abs=1e-3)
        assert err.value.loop == "rocker loop"
        assert "toggle" in str(err.value)


def test_toggle_in_the_second_loop_of_a_chain():
    with pytest.raises(BranchError) as err:
        linkages.chained_four_bars(fixed1=7.1).sweep(np.radians(np.arange(0.0, 361.0, 5.0)))
    assert err.value.kind == "toggle"
    assert err.value.loop == "linkage 2"


def test_convergence_error_fields():
    """x = sqrt(2 - theta) stops existing at theta = 2 rad: Newton cannot converge past it."""
    x, th = sp.symbols("x theta", real=True)
    m = Mechanism([Loop([x - sp.sqrt(2 - th)], [x], name="root")], th, guess=[math.sqrt(2)], guess_input=0.0)
    with pytest.raises(ConvergenceError) as err:
        m.sweep(np.linspace(0.0, 3.0, 31))
    e = err.value
    assert e.input_value == pytest.approx(2.0, abs=1e-6)
    assert e.loop == "root"
    assert isinstance(e.iterations, int)
    assert e.residual is None or not e.residual < 1e-12
    assert "root" in str(e) and "114.59" in str(e)
    assert isinstance(e, RuntimeError)


# --------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "inputs, kwargs, fragment",
    [
        (FULL_TURN, dict(guess=[1.0]), "guess has 1 values"),
        (FULL_TURN, dict(guess={"theta3": 1.0, "theta5": 2.0}), "theta5"),
        (FULL_TURN, dict(guess={"theta3": 1.0}), "theta4"),
        (FULL_TURN, dict(guess={"theta3": math.nan, "theta4": 1.0}), "theta3"),
        (np.radians([0.0, 10.0, 5.0]), {}, "monotonic"),
        (np.radians([0.0, 10.0, 10.0]), {}, "monotonic"),
        (np.array([0.0, math.nan]), {}, "inputs"),
        (np.zeros((2, 2)), {}, "inputs"),
        (np.array([]), {}, "inputs"),
        (FULL_TURN, dict(jacobian="exact"), "jacobian"),
        (FULL_TURN, dict(on_singular="ignore"), "on_singular"),
        (FULL_TURN, dict(max_step=0.0), "max_step"),
        (FULL_TURN, dict(tol=-1.0), "tol"),
        (FULL_TURN, dict(maxiter=0), "maxiter"),
    ],
)
def test_bad_sweep_input(inputs, kwargs, fragment):
    with pytest.raises(ValueError, match=fragment):
        linkages.four_bar(*CR).sweep(inputs, **kwargs)


@pytest.mark.parametrize("value", [0.0, -2.0, math.nan])
def test_bad_length_names_the_parameter(value):
    with pytest.raises(ValueError, match="coupler"):
        linkages.four_bar(4, 1, value, 3)


# ------------------------------------------------------------------- grids
@pytest.mark.parametrize(
    "inputs",
    [
        pytest.param(np.radians(np.arange(137.0, 137.0 + 361.0)), id="start-137"),
        pytest.param(np.radians(np.arange(360.0, -1.0, -1.0)), id="backwards"),
        pytest.param(np.linspace(0.0, TWO_PI, 12), id="coarse-12"),
        pytest.param(np.radians(np.array([0.0, 170.0, 185.0, 359.0])), id="uneven-coarse"),
        pytest.param(np.linspace(-3 * math.pi, 3 * math.pi, 1001), id="three-turns"),
        pytest.param(np.array([2.0]), id="one-point"),
    ],
)
def test_grids_agree_with_closed_form(inputs):
    check_four_bar(linkages.four_bar(*CR).sweep(inputs))


def test_fine_grid_of_100000_points():
    inputs = np.linspace(0.0, TWO_PI, 100_000)
    sweep = linkages.four_bar(*CR).sweep(inputs)
    check_four_bar(sweep)
    assert sweep.residual.max() <= 1e-12


@pytest.mark.parametrize("jacobian", ["forward", "central"])
def test_finite_difference_jacobian_sweeps(jacobian):
    sweep = linkages.four_bar(*CR).sweep(FULL_TURN, jacobian=jacobian)
    assert sweep.jacobian == jacobian
    check_four_bar(sweep)
    chained = linkages.chained_four_bars().sweep(FULL_TURN, jacobian=jacobian)
    ref = linkages.chained_four_bars().sweep(FULL_TURN)
    np.testing.assert_allclose(chained.values, ref.values, rtol=0, atol=1e-10)


def test_other_branch_by_branch_or_guess():
    crossed = linkages.four_bar(*CR, branch="crossed").sweep(FULL_TURN)
    check_four_bar(crossed, side=-1.0)
    t3, t4 = four_bar_reference(FULL_TURN[:1], *CR, -1.0)
    by_guess = linkages.four_bar(*CR).sweep(FULL_TURN, guess={"theta3": float(t3[0]), "theta4": float(t4[0])})
    check_four_bar(by_guess, side=-1.0)
    # a callable guess is evaluated at the first input
    by_callable = linkages.four_bar(*CR).sweep(
        FULL_TURN[100:], guess=lambda th: [float(v[0]) for v in four_bar_reference(np.array([th]), *CR, -1.0)]
    )
    check_four_bar(by_callable, side=-1.0)


def test_max_step_does_not_change_the_answer():
    ref = linkages.chained_four_bars().sweep(FULL_TURN)
    for max_step in (math.radians(2.0), math.radians(90.0)):
        other = linkages.chained_four_bars().sweep(FULL_TURN, max_step=max_step)
        np.testing.assert_allclose(other.values, ref.values, rtol=0, atol=1e-10)


def test_chained_sweep_starting_away_from_the_guess_input():
    """The default guess holds at theta = 0: a sweep from 200 deg first continues there from 0."""
    ref = linkages.chained_four_bars().sweep(np.radians(np.arange(0.0, 721.0)))
    late = linkages.chained_four_bars().sweep(np.radians(np.arange(200.0, 561.0)))
    shift = np.round((late.values[:, 0] - ref.values[:, 200]) / TWO_PI)
    np.testing.assert_allclose(late.values, ref.values[:, 200:561] + TWO_PI * shift[:, None], atol=1e-10)
    backwards = linkages.chained_four_bars().sweep(np.radians(np.arange(360.0, -1.0, -1.0)))
    shift = np.round((backwards.values[:, -1] - ref.values[:, 0]) / TWO_PI)
    np.testing.assert_allclose(backwards.values[:, ::-1], ref.values[:, :361] + TWO_PI * shift[:, None], atol=1e-10)


# ------------------------------------------------------------ Sweep object
def test_sweep_object():
    m = linkages.quick_return()
    sweep = m.sweep(FULL_TURN)
    assert isinstance(sweep, Sweep)
    assert len(sweep) == 361
    assert sweep.unknowns == ("r3", "theta3", "r4", "r5")
    assert "r3" in sweep and "x" not in sweep
    np.testing.assert_array_equal(sweep["theta2"], FULL_TURN)
    with pytest.raises(KeyError, match="r3"):
        sweep["r9"]
    assert sweep.unit("r3") == "mm" and sweep.unit("theta3") == "rad"
    assert sweep.step == pytest.approx(math.radians(1.0))
    assert linkages.quick_return().sweep(np.radians([0.0, 1.0, 3.0])).step is None
    assert sweep.index(math.radians(30.2)) == 30
    frame = sweep.to_frame()
    assert list(frame.columns) == [
        "theta2 [deg]", "r3 [mm]", "theta3 [deg]", "r4 [mm]", "r5 [mm]", "iterations", "residual", "cond",
    ]
    assert frame["theta3 [deg]"].iloc[30] == pytest.approx(66.587, abs=5e-4)
    rad = sweep.to_frame(degrees=False)
    assert rad["theta3 [rad]"].iloc[30] == pytest.approx(math.radians(66.587), abs=1e-5)
    assert sweep.residual.max() <= 1e-12
    assert sweep.iterations.min() >= 1 and sweep.iterations.max() <= 12
    assert np.all(sweep.cond >= 1)
    assert sweep.events == []
    assert set(sweep.points()) == {"O1", "O2", "A", "B", "C"}
    assert "quick-return" in repr(sweep)


def test_condition_numbers_of_blocks_mixing_lengths_and_angles():
    """Quick-return: rows divided by the length scale, columns times 1 rad or the length scale."""
    m = linkages.quick_return()
    sweep = m.sweep(FULL_TURN)
    L = m.length_scale
    assert L == 60.0
    r3, t3, r4 = sweep["r3"], sweep["theta3"], sweep["r4"]
    c, s_ = np.cos(t3), np.sin(t3)
    loop1 = np.array([[-c * L, r3 * s_], [-s_ * L, -r3 * c]]) / L  # d/d(r3, theta3)
    loop2 = np.array([[-c * L, np.full_like(c, L)], [-s_ * L, np.zeros_like(c)]]) / L  # d/d(r4, r5)
    cond = np.maximum(np.linalg.cond(np.moveaxis(loop1, -1, 0)), np.linalg.cond(np.moveaxis(loop2, -1, 0)))
    np.testing.assert_allclose(sweep.cond, cond, rtol=1e-10)
    conds = m.loop_conditions(sweep.values, sweep.inputs)
    np.testing.assert_allclose(conds["O1-C-B"], np.linalg.cond(np.moveaxis(loop2, -1, 0)), rtol=1e-10)
    np.testing.assert_allclose(r4, (60.0 + 60.0) / s_, rtol=1e-12)


def test_regular_sweeps_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for m in (linkages.six_bar(), linkages.chained_four_bars(), linkages.slider_crank(80, 200, 10)):
            m.sweep(FULL_TURN)

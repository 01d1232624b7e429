"""Batched and shared computations of the reports and figures give what the one-at-a-time ones give.

References: the slider-crank piston in closed form, x = r cos(t) + sqrt(l^2 - r^2 sin^2(t)),
evaluated by mpmath at 30 digits at the complex input t + i h (so Im x(t + i h) / h is the
complex step of the closed form itself, for every h, truncation included); tabulate's own
rendering of every candidate part of a wide table.
"""

from __future__ import annotations

import copy
import math

import mpmath as mp
import numpy as np
import pandas as pd
import pytest

from numkin import analytic, linkages
from numkin.quantities import resolve
from numkin.report import format_text
from numkin.report.roundoff import complex_step_scan
from numkin.report.study import branch_point

R, L = 80.0, 200.0


def _piston_complex_step(t: float, h: float) -> float:
    """Im x(t + i h) / h of the closed-form piston position, at 30 digits."""
    with mp.workdps(30):
        z = mp.mpf(t) + 1j * mp.mpf(h)
        x = R * mp.cos(z) + mp.sqrt(L**2 - R**2 * mp.sin(z) ** 2)
        return float(mp.im(x) / h)


@pytest.mark.parametrize("deg", [37.0, 100.0, 250.0])
def test_complex_step_scan_is_the_closed_forms_complex_step_and_the_one_by_one_solve(deg):
    mech = linkages.slider_crank(R, L)
    theta = math.radians(deg)
    point = branch_point(mech, theta)
    steps = 10.0 ** -np.linspace(0.5, 30, 25)
    scan = complex_step_scan(mech, point, steps)
    j = mech.unknowns.index("x")
    reference = np.array([_piston_complex_step(theta, h) for h in steps])
    np.testing.assert_allclose(scan[j], reference, rtol=1e-12, atol=1e-12 * R)
    one_by_one = np.column_stack([analytic.complex_step(point, h=float(h))[:, 0] for h in steps])
    np.testing.assert_array_equal(scan, one_by_one)


def test_complex_step_scan_refuses_bad_steps():
    mech = linkages.slider_crank(R, L)
    with pytest.raises(ValueError, match="steps"):
        complex_step_scan(mech, branch_point(mech, 0.3), [1e-3, 0.0])


def _render(df, cols):
    """A part of `df` as tabulate draws it, numbers to 3 significant figures (the error columns' format)."""
    from tabulate import tabulate

    numeric = [df[c].dtype.kind in "iuf" for c in cols]
    rows = [[f"{v:.3g}" if isinstance(v, float) else str(v) for v in row] for row in df[cols].itertuples(index=False)]
    return tabulate(rows, headers=cols, disable_numparse=True, colalign=["right" if n else "left" for n in numeric],
                    maxcolwidths=[None if n else 40 for n in numeric],
                    maxheadercolwidths=[14 if n else 24 for n in numeric])


def _slow_parts(df, keys, max_width):
    """Parts of a wide table found by rendering every candidate with tabulate (the definition)."""

    def width(cols):
        return max(len(line) for line in _render(df, cols).splitlines())

    rest = [c for c in df.columns if c not in keys]
    if width(list(df.columns)) <= max_width:
        return [list(df.columns)]
    parts, current = [], []
    for c in rest:
        if current and width(keys + current + [c]) > max_width:
            parts.append(keys + current)
            current = []
        current.append(c)
    return parts + [keys + current]


def test_wide_table_parts_are_those_of_rendering_every_candidate():
    rng = np.random.default_rng(7)
    cols = {"case": ["first case", "a second, longer case name"]}
    for k in range(14):
        cols[f"error of scheme number {k} {'with a long name ' * (k % 3)}[-]"] = rng.random(2) * 10.0 ** -k
    df = pd.DataFrame(cols)
    df.attrs["row_keys"] = ["case"]
    for max_width in (60, 90, 130, 1000):
        blocks = format_text(df, max_width=max_width).split("\n\n")
        expected = _slow_parts(df, ["case"], max_width)
        assert len(blocks) == len(expected) and (max_width < 1000) == (len(expected) > 1)
        for n, (block, part) in enumerate(zip(blocks, expected)):
            head = f" ({n + 1} of {len(expected)})\n" if len(expected) > 1 else ""
            assert block == head + _render(df, part)


def test_format_text_leaves_the_tables_attrs_alone():
    df = pd.DataFrame({"scheme": ["centred"], "max abs error [rad/s]": [2.5e-4]})
    df.attrs.update(caption="A caption.", views=[["errors", ["scheme", "max abs error [rad/s]"]]], scan={"h": [0.1]})
    before = copy.deepcopy(df.attrs)
    first = format_text(df)
    assert df.attrs == before
    assert format_text(df) == first


def test_a_quantity_copies_as_itself():
    q = resolve(linkages.slider_crank(R, L), "a_x")
    assert copy.deepcopy(q) is q and copy.copy(q) is q
    holder = pd.DataFrame({"a": [1.0]})
    holder.attrs["quantities"] = {"a": q}
    assert holder["a"].attrs["quantities"]["a"] is q


def test_png_is_the_same_whatever_the_order_of_formats(tmp_path):
    from numkin import figures

    sweep = linkages.slider_crank(R, L).sweep(np.radians(np.arange(0, 361, 2)))
    paths = figures.save(figures.position(sweep, ["x"]), tmp_path / "a", ["svg", "png"])
    assert [p.name for p in paths] == ["a.svg", "a.png"]
    figures.save(figures.position(sweep, ["x"]), tmp_path / "b", ["png", "svg"])
    figures.save(figures.position(sweep, ["x"]), tmp_path / "c", ["png"])
    png = (tmp_path / "a.png").read_bytes()
    assert png == (tmp_path / "b.png").read_bytes() == (tmp_path / "c.png").read_bytes()
    assert (tmp_path / "a.svg").read_bytes() == (tmp_path / "b.svg").read_bytes()


def test_tables_of_one_report_equal_the_tables_computed_alone():
    from numkin import report

    mech = linkages.slider_crank(R, L)
    opts = dict(omega="6000 rpm", quantity="x", check_angle=math.radians(90.0))
    grids, schemes = (36, 72), ("centred", "forward", "second_difference")
    together = report.full_report(mech, grids=grids, schemes=schemes, points_per_turn=72, **opts)
    alone = {
        "convergence": report.convergence_table(mech, grids=grids, schemes=schemes, **opts),
        "work_precision": report.work_precision_table(mech, omega=opts["omega"], quantity="x", grids=grids,
                                                      schemes=schemes),
        "tolerance": report.tolerance_table(mech, points_per_turn=72, **opts),
        "roundoff": report.roundoff_table(mech, quantity="x", check_angle=opts["check_angle"]),
    }
    for name, table in alone.items():
        pd.testing.assert_frame_equal(together[name], table, check_exact=True)
    # the work counts are the evaluations each row spends, not what sharing saved: the analytic
    # velocity costs dF/dtheta at the 37 and 73 inputs of the two grids
    wp = together["work_precision"]
    analytic_v = wp[(wp["method"] == "analytic") & wp["quantity"].str.startswith("v_x")]
    assert analytic_v["derivative work [evaluations]"].tolist() == [37, 73]


def test_shared_sweeps_are_one_object_inside_the_block_and_fresh_outside():
    from numkin.report.grids import TURN, grid_inputs
    from numkin.report.study import shared_results, solve_sweep

    mech = linkages.slider_crank(R, L)
    inputs = grid_inputs(36, 0.0, TURN)
    with shared_results():
        a = solve_sweep(mech, inputs)
        assert solve_sweep(mech, inputs.copy()) is a
        assert solve_sweep(mech, inputs, tol=1e-6) is not a                  # other settings: another sweep
        assert solve_sweep(mech, inputs, shared=False) is not a
    b = solve_sweep(mech, inputs)
    assert b is not a
    np.testing.assert_array_equal(a.values, b.values)


def test_a_shared_sweep_still_warns_every_caller_that_asks():
    from numkin import SingularityWarning
    from numkin.report.study import shared_results, solve_sweep

    import warnings

    mech = linkages.four_bar(5, 2, 5, 2)                                        # a change point at 180 deg
    inputs = np.radians(np.arange(10.0, 351.0, 10.0))
    with pytest.warns(SingularityWarning, match="180"):
        mech.sweep(inputs, on_singular="report")
    with shared_results():
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            first = solve_sweep(mech, inputs, on_singular="report")             # quiet: nothing shown
        for _ in range(2):
            with pytest.warns(SingularityWarning, match="180"):
                assert solve_sweep(mech, inputs, quiet=False, on_singular="report") is first


def _student_reference(mech, inputs, rule, tol, maxiter=100):
    """The student loop written out with the array kernels, one Newton step after another."""
    comp, p = mech.compiled, mech.parameter_values
    x = mech.guess_vector(mech.default_guess, float(inputs[0])).copy()
    blocks = list(mech.loop_slices) if rule == "relative" else [slice(0, x.size)]
    values, iters = [], []
    for t in inputs:
        tk, steps = np.array([t]), 0
        for block in blocks:
            for it in range(maxiter + 1):
                f = comp.F(x[:, None], tk, p)[:, 0]
                if rule == "residual" and np.max(np.abs(f)) < tol:
                    break
                dx = np.linalg.solve(comp.J(x[:, None], tk, p)[0][block, block], -f[block])
                x[block] += dx
                size = np.linalg.norm(dx) / (np.linalg.norm(x[block]) if rule == "relative" else 1.0)
                if rule != "residual" and size < tol:
                    it += 1
                    break
            steps += it
        values.append(x.copy())
        iters.append(steps)
    return np.array(values).T, np.array(iters)


@pytest.mark.parametrize("rule", ["step", "relative", "residual"])
def test_student_sweep_on_the_one_point_kernel_takes_the_array_kernels_steps(rule, monkeypatch):
    from numkin.report import student_sweep

    mech = linkages.chained_four_bars()
    inputs = np.radians(np.arange(0.0, 361.0, 3.0))
    values, iters = _student_reference(mech, inputs, rule, 1e-4)
    s = student_sweep(mech, inputs, rule=rule, tol=1e-4)
    np.testing.assert_array_equal(s.iterations, iters)
    np.testing.assert_allclose(s.values, values, rtol=0, atol=1e-12)
    # where the one-point kernel cannot evaluate, the array kernels take over: the same steps
    comp = mech.compiled

    class Undefined:
        def __getattr__(self, name):
            return getattr(comp, name)

        @staticmethod
        def scalar_FJT(*args):
            raise ValueError("math domain error")

    monkeypatch.setattr(type(mech), "compiled", property(lambda self: Undefined()), raising=False)
    s2 = student_sweep(mech, inputs, rule=rule, tol=1e-4)
    np.testing.assert_array_equal(s2.iterations, iters)
    np.testing.assert_array_equal(s2.values, values)

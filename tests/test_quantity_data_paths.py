"""What a number is travels with it as data, never as a header parsed back.

The comparison's summary names each column's role and unit
(:class:`numkin.compare.SummaryColumn`), and JSON, the CLI and the scene's
summary table read them from there.
"""

from __future__ import annotations

import math

import pytest

from numkin import outputs
from numkin.cli_text import format_result
from numkin.scene import run_scene


@pytest.fixture(scope="module")
def slider_crank():
    """The slider-crank scene: an open grid (0 to 180 deg), so its summaries have the end stencils' column."""
    return run_scene("slider-crank")


def test_summary_columns_name_their_role_and_unit(slider_crank):
    for comparison in slider_crank.comparisons.values():
        columns = comparison.summary.attrs["columns"]
        assert [c.header for c in columns.values()] == list(comparison.summary.columns)
        assert list(columns) == ["order", "max_abs_error", "rms_abs_error", "max_rel_error", "rms_rel_error",
                                 "max_at_deg", "ends_abs_error"]
        units = {key: c.unit for key, c in columns.items()}
        unit = comparison.target.unit
        assert units == {"order": None, "max_abs_error": unit, "rms_abs_error": unit, "max_rel_error": None,
                         "rms_rel_error": None, "max_at_deg": "deg", "ends_abs_error": unit}
        assert {key for key, c in columns.items() if c.quantity_unit} == {"max_abs_error", "rms_abs_error",
                                                                          "ends_abs_error"}


def test_json_error_summary_is_the_comparisons_own_numbers(slider_crank):
    errors = slider_crank.to_dict()["errors"]
    assert list(errors) == list(slider_crank.comparisons) == ["v_x", "a_x"]
    for name, comparison in slider_crank.comparisons.items():
        unit, summary = comparison.unit, comparison.summary
        assert list(errors[name]) == ["unit", *summary.index]
        assert errors[name]["unit"] == unit
        for scheme, row in summary.iterrows():
            want = {
                "order": row["order"],
                "max_abs_error": float(row[f"max abs error [{unit}]"]),
                "rms_abs_error": float(row[f"rms abs error [{unit}]"]),
                "max_rel_error": float(row["max rel error"]),
                "rms_rel_error": float(row["rms rel error"]),
                "max_at_deg": float(row["max at theta [deg]"]),
                "ends_abs_error": float(row[f"ends abs error [{unit}]"]),
            }
            assert errors[name][scheme] == outputs.jsonable(want)
            record = comparison.summary_records()[scheme]
            assert list(record) == list(want)
            assert all(record[k] == v or (v != v and record[k] != record[k]) for k, v in want.items())


def test_cli_and_summary_table_read_the_roles(slider_crank):
    text = format_result(slider_crank).split("largest error over the sweep")[1]
    for name, comparison in slider_crank.comparisons.items():
        for scheme, record in comparison.summary_records().items():
            cells = next(ln.split() for ln in text.splitlines() if ln.split()[:3] == [name, f"[{comparison.unit}]", scheme])
            assert cells[3:] == [f"{record['max_abs_error']:.3g}", f"{100 * record['max_rel_error']:.3g}%",
                                 f"{record['max_at_deg']:g}", f"{record['ends_abs_error']:.3g}"]
    table = outputs.tables(slider_crank)["summary"]
    assert list(table.columns) == ["quantity", "unit", "scheme", "order", "max abs error", "rms abs error",
                                   "max rel error", "rms rel error", "max at theta [deg]", "ends abs error"]
    first = slider_crank.comparisons["v_x"].summary_records()["centred"]
    assert table.loc[0, "max abs error"] == first["max_abs_error"]
    assert math.isclose(table.loc[0, "max at theta [deg]"], first["max_at_deg"])


# ------------------------------------------------------------------ a check's values keep their Quantity
def test_in_degrees_is_an_angles_position():
    from numkin.quantities import Quantity

    assert Quantity("theta3", 0, "angle").in_degrees
    assert not Quantity("theta3", 1, "angle").in_degrees
    assert not Quantity("x", 0, "length").in_degrees
    assert not Quantity("P", 0, "length", axis="x").in_degrees


def _quick_return(tmp_path, **check):
    """The quick-return scene with its check values replaced by `check`."""
    from pathlib import Path

    import numkin

    text = (Path(numkin.__file__).parent / "scenes" / "quick-return.toml").read_text()
    head, _, rest = text.partition("[[check]]")
    lines = ["[[check]]", "at_deg = 30", *(f"{k} = {v!r}" for k, v in check.items())]
    path = tmp_path / "quick-return.toml"
    path.write_text(head + "\n".join(lines) + "\n\n[animation]" + rest.partition("[animation]")[2])
    return run_scene(str(path))


def test_a_check_keeps_the_quantity_of_each_value(tmp_path):
    result = _quick_return(tmp_path, theta3_deg=66.587 + 360, r3=87.178 + 360)
    check = result.checks[0]
    q = check.quantities["theta3_deg"]
    assert (q.name, q.dimension, q.order, q.in_degrees) == ("theta3", "angle", 0, True)
    assert check.units["theta3_deg"] == "deg" and check.quantities["r3"].unit == "mm"
    # an angle's position agrees a turn away (decided by its Quantity), a length does not
    assert check.ok == {"theta3_deg": True, "r3": False}
    lines = format_result(result).splitlines()
    assert any(ln.split()[:3] == ["theta3", "[deg]", "66.587"] for ln in lines)
    assert any(ln.split()[:2] == ["r3", "[mm]"] for ln in lines)
    assert "theta3_deg" in check.to_dict()["values"] and "quantities" not in check.to_dict()


# ------------------------------------------------------------------ figures: symbol and unit from the Quantity
def test_kinematics_figures_take_symbol_and_unit_from_the_quantity():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from numkin import figures, linkages
    from numkin.analytic import kinematics
    from numkin.figures.labels import axis_label, axis_unit, quantities_of
    from numkin.kinematics import finite_difference

    sweep = linkages.six_bar().sweep(np.radians(np.arange(0, 361)))  # lengths in cm
    exact, fd = kinematics(sweep, "-10 rad/s"), {"centred": finite_difference(sweep, "-10 rad/s")}
    position, velocity, acceleration = quantities_of(sweep, "x")
    assert [axis_unit(q) for q in (position, velocity, acceleration)] == ["cm", "cm/s", "cm/s²"]
    fig = figures.kinematics(sweep, "x", analytic=exact, finite=fd, check_angles=[np.radians(90)])
    assert [ax.get_ylabel() for ax in fig.axes[:3]] == [axis_label(q) for q in (position, velocity, acceleration)]
    text = "\n".join(t.get_text() for ax in fig.axes for t in ax.texts)
    assert f"${acceleration.symbol}$ at $\\theta_{{2}}$ = 90°" in text
    assert any(line.startswith("  analytic: ") and line.endswith(" cm/s²") for line in text.splitlines())
    plt.close(fig)

    fig = figures.acceleration_comparison(sweep, "x", exact, fd)
    assert fig.axes[0].get_ylabel() == axis_label(acceleration) == "$a_{x}$ [cm/s²]"
    assert fig.axes[1].get_ylabel() == "|numerical − analytic| [cm/s²]"
    assert fig.axes[0].get_title().endswith(f": ${acceleration.symbol}$, numerical against analytic")
    plt.close(fig)

    angle = quantities_of(linkages.chained_four_bars().sweep(np.radians([0.0, 1.0])), "beta")
    assert [axis_label(q) for q in angle] == ["$\\beta$ [deg]", "$\\omega_{\\beta}$ [rad/s]",
                                              "$\\alpha_{\\beta}$ [rad/s²]"]


# ------------------------------------------------------------------ report tables: the check angle and Jacobian as data
def test_report_tables_carry_their_check_angle_and_figures_write_it_from_there():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numkin import figures, linkages, report

    mech = linkages.four_bar(4, 1, 3, 3)
    tables = report.full_report(mech, omega=1.0, quantity="theta4", check_angle=math.radians(90), grids=(36, 72),
                                schemes=("centred",), points_per_turn=36)
    for name in ("convergence", "roundoff", "newton", "jacobian", "tolerance"):
        assert tables[name].attrs["check"] == ("theta2", 90.0), name
    roundoff = tables["roundoff"]
    assert "theta2 = 90 deg" in roundoff.attrs["caption"].split(";")[0]
    fig = figures.roundoff(roundoff)
    assert "at $\\theta_{2}$ = 90° on the sweep's branch" in fig.axes[0].get_title()
    plt.close(fig)
    # the caption is only typeset: what it names is the table's attrs["check"], never parsed out of it
    plain = roundoff.copy()
    plain.attrs = {k: v for k, v in roundoff.attrs.items() if k != "check"}
    fig = figures.roundoff(plain)
    assert "at theta2 = 90 deg on the sweep's branch" in fig.axes[0].get_title()
    plt.close(fig)


def test_newton_figure_takes_each_tables_jacobian_from_its_attrs():
    import types

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numkin import linkages, report
    from numkin.figures.dispatch import _build, _Data

    mech = linkages.four_bar(4, 1, 3, 3)
    forward = report.newton_table(mech, check_angle=math.radians(90), jacobian="forward")
    hand_made = forward.copy()
    hand_made.attrs = {}
    result = types.SimpleNamespace(tables={"first solve": forward, "newton_central": hand_made})
    fig, stem = _build("newton", None, _Data(result))
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert stem == "newton" and labels == ["forward Jacobian"]  # a table's key says nothing of its Jacobian
    assert fig.axes[0].get_title() == "Newton: residual per iteration at $\\theta_{2}$ = 90°"
    plt.close(fig)
    result = types.SimpleNamespace(tables={"newton": hand_made})
    fig, _ = _build("newton", None, _Data(result))
    assert [ln.get_label() for ln in fig.axes[0].get_lines()] == ["symbolic Jacobian"]  # numkin's default
    plt.close(fig)


# ------------------------------------------------------------------ number formats: by what a column holds
def _numeric(table):
    return [c for c in table.columns if table[c].dtype.kind in "iuf"]


def test_every_number_column_numkin_makes_says_what_it_holds(slider_crank):
    from numkin import linkages, report
    from numkin.column_kinds import FORMATS

    scene_tables = outputs.tables(run_scene("homework"))
    scene_tables.update({f"slider-crank {k}": t for k, t in outputs.tables(slider_crank).items()})
    mech = linkages.four_bar(4, 1, 3, 3)
    angle = math.radians(90)
    report_tables = {
        "convergence": report.convergence_table(mech, omega=1.0, quantity="theta4", check_angle=angle, grids=(36, 72),
                                                schemes=("centred",), span=math.radians(180)),
        "newton": report.newton_table(mech, check_angle=angle),
        "jacobian": report.jacobian_table(mech, check_angle=angle, points_per_turn=36),
        "tolerance": report.tolerance_table(mech, omega=1.0, quantity="theta4", check_angle=angle, points_per_turn=36),
    }
    for name, table in {**scene_tables, **report_tables}.items():
        kinds = table.attrs["kinds"]
        assert set(_numeric(table)) <= set(kinds), name
        assert set(kinds.values()) <= set(FORMATS), name
    checks, comparison = scene_tables["checks"], scene_tables["comparison-alpha_beta"]
    assert checks.attrs["kinds"]["second_difference"] == "value"  # an estimate, not a difference of two results
    assert comparison.attrs["kinds"]["second_difference [rad/s^2]"] == "value"
    assert comparison.attrs["kinds"]["second_difference abs error [rad/s^2]"] == "error"
    assert scene_tables["positions"].attrs["kinds"]["beta [deg]"] == "value"  # solved, not given
    assert scene_tables["positions"].attrs["kinds"]["theta [deg]"] == "input"
    assert scene_tables["summary"].attrs["kinds"]["max at theta [deg]"] == "input"
    assert report_tables["tolerance"].attrs["kinds"]["alpha_theta4 largest error at theta2 [deg]"] == "input"


def test_writers_format_by_the_kind_a_table_names(tmp_path):
    import pandas as pd

    from numkin.column_kinds import set_kinds
    from numkin.report import format_text, write_tables

    made = set_kinds(pd.DataFrame({"theta [deg]": [100.0], "second_difference [rad/s^2]": [-28.376497],
                                   "cond": [5.8712]}),
                     {"theta [deg]": "input", "second_difference [rad/s^2]": "value", "cond": "error"})
    by_hand = pd.DataFrame(made, copy=True)
    by_hand.attrs = {}
    write_tables({"made": made, "by_hand": by_hand}, tmp_path, formats=("md", "tex"))
    assert (tmp_path / "made.md").read_text().splitlines()[-1] == "| 100 | -28.37650 | 5.87 |"
    assert "100 & -28.37650 & 5.87" in (tmp_path / "made.tex").read_text()
    assert "-28.37650" in format_text(made)
    # a table built by hand: each column's format is guessed from its label, as before
    assert (tmp_path / "by_hand.md").read_text().splitlines()[-1] == "| 100 | -28.4 | 5.87 |"
    with pytest.raises(ValueError, match="unknown column kind"):
        set_kinds(made, {"cond": "condition"})

"""Every Markdown table that ``numkin report`` writes renders as a table in GitHub-flavoured Markdown.

The reference is an independent parser, markdown-it-py with its table
extension (the GFM pipe-table rules): each written ``.md`` must parse into
tables whose every row has as many cells as the header, and as many as the
view of the table it shows; no cell says "nan".
"""

from __future__ import annotations

import dataclasses
import math

import pandas as pd
import pytest

from numkin import cli, report
from numkin.scene import list_scenes, load_scene

markdown_it = pytest.importorskip("markdown_it")


def parsed_tables(text: str) -> list:
    """The tables of a Markdown text as lists of rows of cell texts (header first), by markdown-it-py."""
    md = markdown_it.MarkdownIt("commonmark").enable("table")
    tables, rows, row, cell = [], None, None, None
    for tok in md.parse(text):
        if tok.type == "table_open":
            rows = []
        elif tok.type == "table_close":
            tables.append(rows)
            rows = None
        elif tok.type == "tr_open":
            row = []
        elif tok.type == "tr_close":
            rows.append(row)
        elif tok.type in ("th_open", "td_open"):
            cell = ""
        elif tok.type == "inline" and cell is not None:
            cell = tok.content
        elif tok.type in ("th_close", "td_close"):
            row.append(cell)
            cell = None
    return tables


def check_markdown(path, table) -> int:
    """Assert the file at `path` shows each view of `table` as a parsed table; return the cells counted."""
    tables = parsed_tables(path.read_text(encoding="utf-8"))
    views = report.table_views(table)
    assert len(tables) == len(views), path.name
    cells = 0
    for rows, (title, view) in zip(tables, views):
        assert len(rows) == len(view) + 1, (path.name, title)
        for row in rows:
            assert len(row) == view.shape[1], (path.name, title, row)
            assert not any(c.strip().lower() == "nan" for c in row), (path.name, title, row)
            cells += len(row)
        assert [c.replace("\\|", "|") for c in rows[0]] == [str(c) for c in view.columns]
    return cells


def test_parser_sees_an_unescaped_bar_as_a_broken_table():
    assert parsed_tables("| a | b |\n|---|---|\n| 1 | 2 |\n") == [[["a", "b"], ["1", "2"]]]
    # a bar inside a cell must be escaped, or the row has a cell too many and GFM drops it
    assert parsed_tables("| max\\|F\\| | b |\n|---|---|\n| 1 | 2 |\n")[0][0] == ["max|F|", "b"]


def test_bars_in_cells_and_headers_are_escaped(tmp_path):
    df = pd.DataFrame({"max |F| [in]": [1e-9, math.nan], "rule": ["||dx||_2 < tol", "x"]})
    df.attrs["caption"] = "a | caption"
    path = report.write_tables({"bars": df}, tmp_path, formats=("md",))[0]
    assert check_markdown(path, df) == 6
    rows = parsed_tables(path.read_text())[0]
    assert rows[1] == ["1e-09", "||dx||_2 < tol"] and rows[2] == ["", "x"]


def _reported(name):
    scene = load_scene(name)
    return scene.kind == "mechanism" and bool(scene.speed)


def _scene_tables(name) -> dict:
    """The tables of a scene's report (the stability scene: its suite, a few cases of each kind here)."""
    scene = load_scene(name)
    if scene.kind == "stability":
        scene = dataclasses.replace(scene, stability_cases=(
            "near toggle (4, 2, 4.0001, 2)", "nearly aligned, delta = 1e-04", "change point (5, 2, 5, 2), through 180 deg",
            "non-Grashof (7, 4, 3, 5), full turn", "homework x 1e3"))
    return report.scene_report(scene)


@pytest.mark.parametrize("name", list_scenes())
def test_every_markdown_table_of_numkin_report_parses(name, tmp_path, capsys):
    tables = _scene_tables(name)
    if _reported(name):  # what the command writes
        assert cli.main(["report", name, "--out", str(tmp_path)]) == 0
        capsys.readouterr()
    else:
        report.write_tables({f"{name}-{k}": v for k, v in tables.items()}, tmp_path)
    written = sorted(tmp_path.glob("*.md"))
    assert [p.stem for p in written] == sorted(f"{name}-{k}" for k in tables)
    cells = sum(check_markdown(tmp_path / f"{name}-{k}.md", t) for k, t in tables.items())
    assert cells > 50
    for t in tables.values():  # the terminal shows the same parts, in lines a terminal can hold
        text = report.format_text(t)
        assert "nan" not in text.lower().split()
        if "what happened" not in t.columns and "error or warning raised" not in t.columns:
            assert max(len(line) for line in text.splitlines()) <= 200


def test_a_scene_without_input_speed_is_reported_per_rad_per_s():
    tables = report.scene_report(load_scene("quick-return"))
    assert list(tables) == ["convergence", "work_precision", "cheapest", "roundoff", "newton", "jacobian", "tolerance"]
    rates = {"convergence", "work_precision", "cheapest", "roundoff", "tolerance"}  # the tables holding rates
    assert all(("per rad/s of input speed" in t.attrs["caption"]) == (k in rates) for k, t in tables.items())


def test_a_scene_whose_input_accelerates_says_its_tables_leave_the_acceleration_out():
    """The report studies the schemes at constant input speed: where the scene's input accelerates, every table
    with accelerations says that they are omega^2 d2q/dtheta2 alone (the tolerance table's exact value at the
    check angle is that: 6000 rpm, crank r = 80 mm, rod l = 200 mm at 90°, x'' = r^2 / sqrt(l^2 - r^2) times
    omega^2, 13783.8 m/s^2; the scene's own adds alpha_in dx/dtheta = 5 (-r))."""
    import dataclasses
    import math

    scene = dataclasses.replace(load_scene("slider-crank"), acceleration=5.0)
    tables = report.scene_report(scene)
    said = {k for k, t in tables.items() if "alpha_in = 5 rad/s^2" in t.attrs["caption"]}
    assert said == {k for k, t in tables.items()
                    if any(q.order == 2 and q.wrt == "time" for q in (t.attrs.get("quantities") or {}).values())}
    assert {"convergence", "tolerance"} <= said and "newton" not in said
    tol = tables["tolerance"]
    w = 6000 * 2 * math.pi / 60
    assert tol["a_x at theta = 90 deg [m/s^2]"].iloc[0] == pytest.approx(0.08**2 / math.sqrt(0.2**2 - 0.08**2) * w**2,
                                                                        rel=1e-12)


def test_untimed_report_files_are_the_same_in_two_runs(tmp_path):
    """Without timing (the default) every table is exact: two runs write byte-identical files."""
    from numkin import linkages

    mech = linkages.slider_crank(80, 200)
    runs = []
    for k in range(2):
        tables = report.full_report(mech, omega="6000 rpm", quantity="x", check_angle=math.radians(60),
                                    grids=(36, 72), schemes=("centred", "second_difference"), points_per_turn=36)
        paths = report.write_tables(tables, tmp_path / str(k))
        runs.append({p.name: p.read_bytes() for p in paths})
    assert runs[0] == runs[1]
    assert not any("varies" in name for name in tables["work_precision"].columns)

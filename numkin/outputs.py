"""Scene outputs: the tables a scene asks for, written as CSV (and Markdown, LaTeX), and JSON.

Column labels and units come from :class:`numkin.quantities.Quantity`
(``omega_theta4 [rad/s]``, ``x_P [mm]``); an angle's position is written in
degrees (``theta3 [deg]``), as everywhere at the edges.

Examples
--------
>>> from numkin.pipeline import run_scene
>>> result = run_scene("slider-crank")
>>> sorted(result.tables)[:2]
['checks', 'comparison-a_x']
>>> list(result.tables["kinematics"].columns)[:3]
['theta [deg]', 'v_x [m/s]', 'a_x [m/s^2]']
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from .errors import InputError
from .folders import made_folder
from .units import input_degrees

__all__ = ["tables", "write_tables", "error_summary", "jsonable"]


def jsonable(obj):
    """``obj`` with numpy scalars as Python numbers and non-finite floats as None (for JSON)."""
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def error_summary(comparisons: dict) -> dict:
    """``{quantity: {"unit": unit, scheme: {key: value}}}`` from :class:`~numkin.compare.Comparison` objects.

    The keys are the roles of the summary's columns
    (:class:`~numkin.compare.SummaryColumn`: ``max_abs_error``,
    ``max_at_deg``, ...), read from :meth:`~numkin.compare.Comparison.summary_records`;
    the unit of the absolute errors is given once per quantity.

    Raises
    ------
    InputError
        If ``comparisons`` is not a mapping name -> Comparison (the message names the entry).
    """
    if not isinstance(comparisons, Mapping):
        raise InputError(f"comparisons must be a mapping name -> numkin.compare.Comparison, got "
                         f"{type(comparisons).__name__} {comparisons!r:.60}")
    if not comparisons:
        return {}  # a position-only scene's: numkin.compare is not even imported
    from .compare import Comparison

    for name, comparison in comparisons.items():
        if not isinstance(comparison, Comparison):
            raise InputError(f"comparisons[{name!r}] must be a numkin.compare.Comparison (from compare()), got "
                             f"{type(comparison).__name__} {comparison!r:.60}")
    out = {}
    for name, comparison in comparisons.items():
        rows = {"unit": comparison.unit}
        rows.update(comparison.summary_records())
        out[name] = rows
    return out


def _columns(result, quantities, values_of) -> dict:
    """Label -> array for each quantity, by :attr:`Quantity.label`; positions of angles in degrees."""
    from .scene_quantities import scene_unit

    cols = {}
    for q in quantities:
        values = values_of(q)
        if values is None:
            continue
        if q.in_degrees:
            cols[f"{q.name} [{scene_unit(q)}]"] = np.degrees(values)
        else:
            cols[q.label] = values
    return cols


def tables(result) -> dict:
    """The DataFrames a scene asks for (only those), from a :class:`~numkin.pipeline.SceneResult`.

    Raises
    ------
    InputError
        If ``result`` is not a scene's result with a mechanism (the stability suite's has none).
    """
    import pandas as pd

    from .scene_quantities import scene_quantities
    from .column_kinds import set_kinds
    from .pipeline import SceneResult

    if not isinstance(result, SceneResult) or result.sweep is None:
        what = "the stability suite's result" if isinstance(result, SceneResult) else \
            f"{type(result).__name__} {result!r:.60}"
        raise InputError(f"result must be the SceneResult of run_scene() on a scene with a mechanism, got {what}")

    scene, mech, sweep = result.scene, result.mechanism, result.sweep
    wanted = set(scene.tables)
    out = {}
    input_col = f"{mech.input_name} [deg]"
    quantities = scene_quantities(scene, mech).values()
    xy = sweep.points() if scene.points and wanted & {"positions", "points"} else {}

    def point_value(q):
        if q.order == 0:
            return xy[q.of][0 if q.axis == "x" else 1]
        pk = result.point_kinematics
        return pk[q.name].to_numpy() if pk is not None and q.name in pk else None

    def unknown_rate(q):
        if q.of in mech.derived:
            return result.derived_kinematics[q.name].to_numpy()
        return result.kinematics[q.name].to_numpy()

    def by_input(columns: dict):
        """A table of the input and `columns` (label -> values of a quantity)."""
        table = pd.DataFrame({input_col: input_degrees(sweep.inputs), **columns})
        return set_kinds(table, {input_col: "input", **{label: "value" for label in columns}})

    if "positions" in wanted:
        frame = sweep.to_frame()  # (the input, the unknowns, Newton's diagnostics: their kinds said)
        added = {}
        if mech.derived:
            derived = result.derived_positions()
            derived_positions = [q for q in quantities if q.of in derived and not q.is_point and q.order == 0]
            added.update(_columns(result, derived_positions, lambda q: derived[q.of]))
        added.update(_columns(result, [q for q in quantities if q.is_point and q.order == 0], point_value))
        for label, values in added.items():
            frame[label] = values
        out["positions"] = set_kinds(frame, {label: "value" for label in added})
    if "kinematics" in wanted and result.kinematics is not None:
        rates = [q for q in quantities if not q.is_point and q.order > 0]
        out["kinematics"] = by_input(_columns(result, rates, unknown_rate))
    if "points" in wanted and scene.points:
        points = [q for q in quantities if q.is_point]
        # per point: x, y, then its velocity and acceleration components
        points.sort(key=lambda q: scene.points.index(q.of))
        out["points"] = by_input(_columns(result, points, point_value))
    if "comparison" in wanted:
        for name, comparison in result.comparisons.items():
            out[f"comparison-{name}"] = comparison.table
    if "summary" in wanted and result.comparisons:
        frames, kinds = [], {}
        for name, comparison in result.comparisons.items():
            columns = comparison.summary.attrs["columns"].values()
            # the unit of the absolute errors is the row's own column: their labels go without it
            bare = {c.header: c.name for c in columns if c.quantity_unit}
            kinds.update({bare.get(c.header, c.header): c.kind for c in columns if c.kind})
            s = comparison.summary.reset_index().rename(columns=bare)
            s.insert(0, "unit", comparison.unit)
            s.insert(0, "quantity", name)
            frames.append(s)
        summary = pd.concat(frames, ignore_index=True)
        summary.attrs = {}  # (not one comparison's: every quantity's rows)
        out["summary"] = set_kinds(summary, kinds)
    if "checks" in wanted and result.checks:
        rows, kinds = [], {input_col: "input", "value": "value", "expected": "value"}
        for c in result.checks:
            kinds.update({scheme: "value" for scheme in c.schemes})
            for key, value in c.values.items():
                row = {input_col: c.at_deg, "quantity": key, "unit": c.units[key], "value": value}
                for scheme, vals in c.schemes.items():
                    row[scheme] = vals.get(key, np.nan)
                ends = sorted(s for s, keys in c.end_stencil.items() if key in keys)
                if ends:
                    row["one-sided end stencil"] = ", ".join(ends)
                row["expected"] = c.expected.get(key, np.nan)
                row["ok"] = c.ok.get(key, "")
                rows.append(row)
        out["checks"] = set_kinds(pd.DataFrame(rows), kinds)
    return out


def write_tables(scene, tables: dict, out: Path) -> list[Path]:
    """Write ``tables`` as ``<out>/<scene>-<name>.<format>`` in the scene's formats; the paths written.

    ``out`` is made, with its parents, if it is not there.

    Raises
    ------
    InputError
        Naming the argument: ``scene`` is not a :class:`~numkin.schema.Scene`,
        ``tables`` not a mapping name -> pandas DataFrame, ``out`` not a
        folder that is there or can be made (:func:`output_folder`).
    """
    import pandas as pd

    from .schema import Scene

    if not isinstance(scene, Scene):
        raise InputError(f"scene must be a numkin.scene.Scene (from load_scene()), got {type(scene).__name__} "
                         f"{scene!r:.60}")
    if not isinstance(tables, Mapping):
        raise InputError(f"tables must be a mapping name -> pandas.DataFrame, got {type(tables).__name__} "
                         f"{tables!r:.60}")
    for name, frame in tables.items():
        if not isinstance(name, str) or not isinstance(frame, pd.DataFrame):
            raise InputError(f"tables[{name!r}] must be a pandas.DataFrame named by a string, got "
                             f"{type(frame).__name__} {frame!r:.60}")
    out = made_folder(out)
    written = []
    if "csv" in scene.table_formats:
        for name, frame in tables.items():
            path = out / f"{scene.name}-{name}.csv"
            frame.to_csv(path, index=False)
            written.append(path)
    others = tuple(f for f in scene.table_formats if f != "csv")
    if others:
        from .report import write_tables as write_report_tables

        named = {f"{scene.name}-{k}": v for k, v in tables.items()}
        written += list(write_report_tables(named, out, formats=others))
    return written

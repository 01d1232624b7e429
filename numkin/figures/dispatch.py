"""Figures by name: drawing and saving the figures a scene asks for (:mod:`~numkin.figures.specs`) from a result."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Sequence

import numpy as np

from ..errors import InputError, warn
from .curves import acceleration_comparison, derivative, difference, kinematics, position, slider
from .drawing import mechanism
from .error_plots import convergence, jacobian_of, newton_residuals, roundoff, work_precision
from .arguments import need_names, need_result
from .labels import (check_points, check_unknown, derived_of, frame_input, input_name, is_angle, rate_columns,
                     table_column)
from .series import with_rates
from .specs import FigureSkipped, parse_spec
from .style import METADATA, gc_paused, save

__all__ = ["render"]

class _Missing(Exception):
    """Data a figure needs is absent (render skips the figure)."""



# ============================================================================ render
class _Data:
    """What a result holds for figures (duck-typed; see :func:`render`)."""

    def __init__(self, result):
        self.sweep = getattr(result, "sweep", None)
        self.analytic = getattr(result, "analytic", None)
        if self.analytic is None:
            k = getattr(result, "kinematics", None)
            self.analytic = k if hasattr(k, "columns") else None
        self.analytic = _joined(self.analytic, getattr(result, "derived_kinematics", None), self.sweep)
        finite = getattr(result, "finite", None)
        self.finite = dict(finite) if finite else _frames_from_comparisons(getattr(result, "comparisons", None),
                                                                            self.sweep)
        self.tables = dict(getattr(result, "tables", None) or {})
        checks = getattr(result, "check_angles", None)
        if checks is None:
            checks = [math.radians(float(c.at_deg)) for c in getattr(result, "checks", None) or ()
                      if getattr(c, "at_deg", None) is not None]
        self.check_angles = [float(a) for a in np.atleast_1d(checks)] if checks is not None else []
        scene = getattr(result, "scene", None)
        self.quantity = getattr(result, "quantity", None) or (getattr(scene, "report", None) or {}).get("quantity")
        self.unknowns = tuple(getattr(scene, "unknowns", None) or ())

    def need_sweep(self):
        if self.sweep is None:
            raise _Missing("no sweep in the result (a stability scene?)")
        return self.sweep

    def unknown(self, arg, kind="angle"):
        sweep = self.need_sweep()
        if arg is not None:
            return check_unknown(sweep, arg)
        wanted = (lambda n: is_angle(sweep, n)) if kind == "angle" else (lambda n: not is_angle(sweep, n))
        for cand in (self.quantity, *self.unknowns):
            if (cand in sweep.unknowns or cand in derived_of(sweep)) and wanted(cand):
                return cand
        pool = [n for n in sweep.unknowns if wanted(n)]
        if kind == "length" and "x" in pool:
            return "x"
        if not pool:
            raise _Missing(f"{sweep.mechanism.name} has no {kind} unknown")
        return pool[0]

    def table(self, *keys):
        for key in keys:
            if key in self.tables:
                return self.tables[key]
        raise _Missing(f"no '{keys[0]}' table in the result (numkin.report makes it)")


def _joined(analytic, derived, sweep):
    """The analytic kinematics with the columns of :func:`numkin.analytic.derived_kinematics` beside them.

    Either may be absent; the derived frame's columns are joined only when
    it lies on the same inputs, row by row (it always does in a scene's
    result); otherwise it is left out with a warning.
    """
    if not hasattr(derived, "columns"):
        return analytic
    if analytic is None:
        return derived
    new = [c for c in derived.columns if c not in analytic.columns]
    if not new:
        return analytic
    if sweep is None or len(derived) != len(analytic) or not np.allclose(
            frame_input(derived, sweep), frame_input(analytic, sweep), rtol=0.0, atol=1e-12):
        warn("derived_kinematics lies on other inputs than the analytic kinematics: its columns "
             f"{new} are not joined (compute both from the same sweep)", UserWarning)
        return analytic
    out = analytic.copy()
    for c in new:
        out[c] = derived[c].to_numpy()
    return out


def _scheme_columns(table, inp: str, unit) -> list:
    """``(column, scheme)`` of a comparison table's scheme estimates.

    From ``table.attrs["quantities"]`` (column -> Quantity, whose source is
    the scheme), as :func:`numkin.compare.compare` sets them; a table without
    them gives none (its headers are never parsed back into schemes).
    """
    from ..quantities import Quantity

    known = table.attrs.get("quantities") or {}
    return [(c, q.source) for c, q in known.items()
            if isinstance(q, Quantity) and c in table.columns and q.source not in (inp, "analytic", "solved")
            and (unit is None or q.unit == unit)]


def _frames_from_comparisons(comparisons, sweep) -> dict:
    """scheme -> frame (``<input>`` in rad and the compared quantities) from numkin.compare results.

    Each frame's ``attrs["periodic"]`` is its comparison's grid, so that the
    figures can name the values of the one-sided end stencils of an open grid.
    """
    if not comparisons or sweep is None:
        return {}
    import pandas as pd

    inp = input_name(sweep)
    cols: dict = {}
    periodic: dict = {}
    for quantity, comp in comparisons.items():
        table = getattr(comp, "table", None)
        if table is None:
            continue
        xcol = table_column(table, f"{inp} [deg]", "comparison table", required=False)
        if xcol is None:
            continue
        unit = getattr(comp, "unit", None)
        for c, scheme in _scheme_columns(table, inp, unit):
            frame = cols.setdefault(scheme, {inp: np.radians(np.asarray(table[xcol], dtype=float))})
            frame[getattr(comp, "quantity", quantity)] = np.asarray(table[c], dtype=float)
            if getattr(comp, "periodic", None) is not None:
                periodic[scheme] = bool(comp.periodic)
    frames = {k: pd.DataFrame(v) for k, v in cols.items()}
    for k, frame in frames.items():  # open or periodic grid: where the one-sided end stencils are (figures.ends)
        if k in periodic:
            frame.attrs["periodic"] = periodic[k]
    return frames


def _build(kind: str, arg, d: _Data):
    """(figure, file stem) for one figure, or raise _Missing."""
    if kind == "position":
        sweep = d.need_sweep()
        chosen = [n for n in d.unknowns if n in sweep.unknowns]
        names = [check_unknown(sweep, arg)] if arg else [*chosen, *derived_of(sweep)] if chosen else None
        return position(sweep, names), "position" + (f"-{arg}" if arg else "")
    if kind in ("derivative", "difference"):
        sweep = d.need_sweep()
        name = d.unknown(arg)
        if sweep.step is None:
            raise _Missing("finite differences need a sweep with a uniform step")
        fn = derivative if kind == "derivative" else difference
        return fn(sweep, name), f"{kind}-{name}"
    if kind in ("kinematics", "slider"):
        sweep = d.need_sweep()
        name = d.unknown(arg, "angle" if kind == "kinematics" else "length")
        vcol, acol = rate_columns(sweep, name)
        analytic, finite = with_rates(sweep, name, d.analytic, d.finite, where=f"figure '{kind}'", strict=False)
        frames = [f for f in [analytic, *finite.values()] if f is not None]
        if not any(vcol in f.columns or acol in f.columns for f in frames):
            raise _Missing(f"no velocity or acceleration of {name!r} in the result (ask for them in the scene)")
        fn = kinematics if kind == "kinematics" else slider
        checks = check_points(d.check_angles, sweep.inputs, strict=False)  # a scene's checks on the turn drawn
        return fn(sweep, name, analytic=analytic, finite=finite, check_angles=checks), f"{kind}-{name}"
    if kind == "acceleration":
        sweep = d.need_sweep()
        name = d.unknown(arg, "length")
        _, acol = rate_columns(sweep, name)
        analytic, finite = with_rates(sweep, name, d.analytic, d.finite, where="figure 'acceleration'",
                                      strict=False)
        if analytic is None or acol not in analytic.columns:
            raise _Missing(f"no analytic {acol} in the result (ask for accelerations in the scene)")
        finite = {k: f for k, f in finite.items() if acol in f.columns}
        if not finite:
            raise _Missing(f"no finite-difference {acol} in the result (give second-derivative schemes)")
        return acceleration_comparison(sweep, name, analytic, finite), f"acceleration-{name}"
    if kind == "mechanism":
        sweep = d.need_sweep()
        if not sweep.mechanism.points or not sweep.mechanism.links:
            raise _Missing(f"{sweep.mechanism.name} has no points and links to draw")
        at = math.radians(float(arg)) if arg is not None else (d.check_angles[0] if d.check_angles else None)
        return mechanism(sweep, at), "mechanism" + (f"-{arg}deg" if arg is not None else "")
    if kind == "convergence":
        return convergence(d.table("convergence")), "convergence"
    if kind == "work-precision":
        return work_precision(d.table("work_precision", "work-precision")), "work-precision"
    if kind == "roundoff":
        return roundoff(d.table("roundoff")), "roundoff"
    if kind == "newton":
        # the tables of numkin.report.newton_table, each naming its Jacobian (attrs["jacobian"]); or one named "newton"
        found = {jacobian_of(t): t for key, t in d.tables.items()
                 if getattr(t, "attrs", {}).get("jacobian") or key == "newton"}
        if not found:
            raise _Missing("no 'newton' table in the result (numkin.report.newton_table makes it)")
        return newton_residuals(found), "newton"
    raise InputError(f"unknown figure {kind!r}")  # pragma: no cover - parse_spec checked it


def render(result, names: Sequence[str] | None = None, out_dir=".", formats: Sequence[str] = ("png", "svg")) -> list[Path]:
    """Draw and save the figures a scene asks for; skip, with a warning, those whose data is absent.

    Parameters
    ----------
    result : object
        Duck-typed: ``sweep`` (Sweep), and as available ``analytic`` (or
        ``kinematics``: the DataFrame of :func:`numkin.analytic.kinematics`;
        the columns of ``derived_kinematics``, the DataFrame of
        :func:`numkin.analytic.derived_kinematics`, are joined to it),
        ``finite`` (scheme -> DataFrame of
        :func:`numkin.kinematics.finite_difference`; else taken from
        ``comparisons``, quantity -> :class:`numkin.compare.Comparison`),
        ``tables`` (name -> DataFrame, the names of
        :func:`numkin.report.full_report`; the Newton tables are those of
        :func:`numkin.report.newton_table`, each naming its Jacobian in
        ``attrs["jacobian"]``, or one named ``newton``), ``check_angles``
        (rad; else the ``at_deg`` of ``checks``), ``figures`` (else
        ``scene.figures``) and
        ``scene.report["quantity"]`` / ``scene.unknowns`` for the default
        unknown.
    names : sequence of str, optional
        Figure names (see :func:`parse_spec`); default the result's. An
        unknown named in them may be a derived quantity of the mechanism
        (``"kinematics:mu"``): drawn as an unknown is, see
        :func:`numkin.figures.kinematics`.
    out_dir : str or Path
        Folder of the files ``<figure>[-<unknown>].<format>``.
    formats : sequence of str

    Returns
    -------
    list of Path
        Files written.

    Warns
    -----
    FigureSkipped
        For each figure whose data the result does not hold.

    Raises
    ------
    ValueError
        For an unknown figure name or format, or an unknown that the
        mechanism does not have.

    Examples
    --------
    >>> import math, types
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.quick_return().sweep(np.radians(np.arange(0, 361)))
    >>> result = types.SimpleNamespace(sweep=sweep, check_angles=[math.radians(30)], figures=["mechanism"])
    >>> [p.name for p in figures.render(result, out_dir="/tmp/numkin-doc-render")]
    ['mechanism.png', 'mechanism.svg']
    """
    need_result(result, "render")
    names = need_names(names, "names", "render")
    if names is None:
        names = getattr(result, "figures", None)
        if names is None:
            names = getattr(getattr(result, "scene", None), "figures", None) or ()
    if isinstance(names, str):
        names = [names]
    specs = [(spec, *parse_spec(spec)) for spec in names]
    if isinstance(formats, str):
        formats = (formats,)
    formats = need_names(formats, "formats", "render")
    bad = [f for f in formats if str(f).lower().lstrip(".") not in METADATA]
    if bad or not formats:
        raise InputError(
            f"formats: {bad[0] if bad else 'nothing'!r} is not a figure format numkin writes; choose from {sorted(METADATA)}"
        )
    data = _Data(result)
    out = Path(out_dir)
    written: list[Path] = []
    for spec, kind, arg in specs:
        # one figure at a time, its objects alive until it is saved; then none is left referenced,
        # so the first collection after the pause frees them all at once
        with gc_paused():
            try:
                fig, stem = _build(kind, arg, data)
            except _Missing as why:
                warn(f"figure '{spec}' skipped: {why}", FigureSkipped)
                continue
            written += save(fig, out / stem, formats)
            del fig
    return written

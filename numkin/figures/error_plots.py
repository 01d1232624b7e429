"""Figures of the error-analysis tables: convergence, work-precision, round-off, Newton."""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..schemes import by_label
from .arguments import need_names, need_table, need_tables
from .labels import sym, table_column
from .registries import is_second_derivative
from .style import CYCLE, marker_style, new_figure, shared_doc, source_label, source_style, style

__all__ = ["convergence", "jacobian_of", "newton_residuals", "on_curve", "quantity_of", "roundoff", "table_caption",
           "work_precision"]


def quantity_of(table, value):
    """The :class:`~numkin.quantities.Quantity` a table's ``quantity`` value stands for, or None.

    The value itself if it is one, else ``table.attrs["quantities"][value]``
    when the table carries that mapping.

    Examples
    --------
    >>> import pandas as pd
    >>> from numkin import linkages
    >>> from numkin.quantities import resolve
    >>> t = pd.DataFrame({"quantity": ["omega_beta [rad/s]"]})
    >>> t.attrs["quantities"] = {"omega_beta [rad/s]": resolve(linkages.chained_four_bars(), "omega_beta")}
    >>> print(quantity_of(t, "omega_beta [rad/s]").unit, quantity_of(t, "other"))
    rad/s None
    """
    from ..quantities import Quantity

    if isinstance(value, Quantity):
        return value
    known = getattr(table, "attrs", {}).get("quantities") or {}
    q = known.get(value) if isinstance(known, dict) else None
    return q if isinstance(q, Quantity) else None


def _panel_text(quantity, error: str, table=None) -> tuple[str, str]:
    """Title text and error unit of one panel of a report figure (``"–"`` for a relative error).

    From the quantity's :class:`~numkin.quantities.Quantity` when the table
    carries it (every table of :mod:`numkin.report` does); else the table's
    text as it stands, without a unit: a label is never parsed back into a
    quantity.
    """
    q = quantity_of(table, quantity) if quantity is not None and table is not None else None
    if q is not None:
        qtext, unit = f"${q.symbol}$", q.unit.replace("^2", "²")
    else:
        qtext, unit = ("" if quantity is None else str(quantity)), ""
    if "rel" in error:
        unit = "–"
    return qtext, unit





def _order_label(scheme: str, order) -> str:
    """A scheme's legend label, with its formal order when known (a spectral scheme's label says it already)."""
    label = source_label(scheme)
    if order is None or order == "spectral" and "spectral" in label:
        return label
    return label + (" (spectral)" if order == "spectral" else f" (order {order})")


def table_caption(table) -> str:
    """The caption a report table carries in its ``attrs`` ("" if none)."""
    return table.attrs.get("caption", "") if hasattr(table, "attrs") else ""


def _groups(table, column: str = "quantity") -> list:
    """(value, sub-table) in order of first appearance; one group if the column is absent."""
    if column not in table.columns:
        return [(None, table)]
    out = []
    for value in dict.fromkeys(table[column]):
        out.append((value, table[table[column] == value]))
    return out


def _positive(values) -> np.ndarray:
    v = np.asarray(values, dtype=float)
    return np.where(v > 0, v, np.nan)


def _plain_log_ticks(axis, values) -> None:
    """Log-axis ticks at 1, 2, 5 x 10^k written as plain numbers, when the data span under 3 decades."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size and v.max() / v.min() < 1e3:
        axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
        axis.set_minor_formatter(NullFormatter())


def _title(table, default: str) -> str:
    """A table's ``attrs["title"]`` if it has one; else the first clause of its caption (:func:`_caption_title`);
    else `default`."""
    attrs = getattr(table, "attrs", {})
    if attrs.get("title"):
        return str(attrs["title"])
    caption = table_caption(table)
    return _caption_title(caption, attrs.get("check")) if caption else default


def _check_text(check, plain: bool = False) -> str:
    """A check angle, ``attrs["check"]`` (the input's name and the angle in degrees), as a report's caption writes
    it (`plain`: ``theta = 100 deg``, six significant digits) or as a figure does (``θ = 100°``)."""
    name, degrees = check
    return f"{name} = {degrees:.6g} deg" if plain else f"{sym(name)} = {degrees:.6g}°"


def _caption_title(caption: str, check=None) -> str:
    """The first clause of a report table's caption; the check angle it names, the table's ``attrs["check"]``
    (``theta = 100 deg``), written with the input's symbol and a degree sign (``θ = 100°``)."""
    head = caption.split(";")[0]
    return head.replace(_check_text(check, plain=True), _check_text(check)) if check else head


def _log_limits(values, pad: float = 3.0) -> tuple[float, float]:
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        return 1e-16, 1.0
    return float(v.min()) / pad, float(v.max()) * pad


@shared_doc
def convergence(table, *, error: str = "max abs error"):
    """Error against step h (log-log) for each scheme, with reference slopes 1, 2 and 4 (and the
    formal order of any other scheme drawn, e.g. 6).

    Parameters
    ----------
    table : DataFrame
        From :func:`numkin.report.convergence_table`: columns ``scheme``,
        ``formal order``, ``quantity``, ``h [deg]`` and the error column.
        One panel per quantity (velocity schemes, acceleration schemes).
    error : str
        Start of the error column's name: ``"max abs error"`` (default),
        ``"RMS abs error"`` or ``"max rel error"``.

    {{returns_figure}}

    {{example_tables}}
    >>> conv = report.convergence_table(linkages.chained_four_bars(), omega="450 rad/min", quantity="beta",
    ...                                 grids=(36, 72, 180), schemes=("forward", "centred"))
    >>> fig = figures.convergence(conv)
    >>> fig.axes[0].get_xscale(), fig.axes[0].get_yscale()
    ('log', 'log')
    >>> figures.save(fig, "/tmp/numkin-doc-convergence", ["png"])[0].suffix
    '.png'
    """
    need_table(table, "table", "convergence")
    need_names(error, "error", "convergence")
    what = "convergence table"
    hcol = table_column(table, "h [", what)
    ecol = table_column(table, error, what)
    scol = table_column(table, "scheme", what)
    h_unit = (table.attrs.get("units") or {}).get(hcol)
    groups = _groups(table)
    orders = {1, 2, 4}
    if "formal order" in table.columns:
        orders |= {int(o) for o in table["formal order"].astype(str) if o.isdigit() and int(o) > 0}
    dashes = [(0, (6, 2)), (0, (3, 2)), (0, (1, 1.5)), (0, (5, 1.5, 1, 1.5)), (0, (8, 2, 1, 2, 1, 2))]
    with style():
        from .ticks import log_scale

        fig, axes = new_figure(1, len(groups), size=(6.4 if len(groups) == 1 else 9.6, 5.4))
        for ax, (quantity, sub) in zip(axes[0], groups):
            qtext, unit = _panel_text(quantity, error, table)
            h_all = np.asarray(sub[hcol], dtype=float)
            e_all = _positive(sub[ecol])
            for k, scheme in enumerate(dict.fromkeys(sub[scol])):
                rows = sub[sub[scol] == scheme].sort_values(hcol)
                order = rows["formal order"].iloc[0] if "formal order" in rows.columns else None
                label = _order_label(scheme, order)
                st = source_style(scheme, k)
                st["linewidth"] = min(st.get("linewidth", 1.5), 1.6)
                st.pop("alpha", None)
                ax.plot(rows[hcol], _positive(rows[ecol]), label=label, **marker_style(scheme, st["color"]), **st)
            ylo, yhi = _log_limits(e_all)
            hmin, hmax = float(np.nanmin(h_all)), float(np.nanmax(h_all))
            # reference slopes, from the largest step, under the data
            at_max = e_all[np.isclose(h_all, hmax)]
            anchor = float(np.nanmin(at_max)) / 4 if np.isfinite(at_max).any() else yhi / 10
            hh = np.geomspace(hmin, hmax, 50)
            for p, ls in zip(sorted(orders), dashes * len(orders)):
                yy = anchor * (hh / hmax) ** p
                ax.plot(hh, yy, color="0.35", linestyle=ls, linewidth=0.9, scalex=False, scaley=False)
                inside = np.flatnonzero(yy >= ylo * 1.5)
                j = inside[0] if inside.size else hh.size - 1
                if j == 0:  # at the line's left end
                    ax.text(hh[0], yy[0], f"slope {p}", fontsize=7.5, color="0.25", ha="right", va="bottom")
                else:  # where it rises into view: beside it, to its right
                    ax.text(hh[j] * 1.15, yy[j], f"slope {p}", fontsize=7.5, color="0.25", ha="left", va="bottom")
            log_scale(ax, "xy")
            ax.set_ylim(ylo, yhi)
            ax.set_xlim(hmin / 1.6, hmax * 1.3)
            ax.set_xlabel(f"step $h$ [{h_unit}]" if h_unit else "step $h$")
            ax.set_ylabel(f"{error} [{unit}]")
            ax.set_title(f"{qtext}" if qtext else "error against step")
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.17), ncols=2, fontsize=7.5)
        title = _title(table, "")
        if title:
            fig.suptitle(title, fontsize=9)
    return fig


def _front(x, y) -> np.ndarray:
    """Pareto front of points (cost x, error y): no other point is no worse in both and better in one.

    Points with a non-finite or non-positive coordinate are not on it.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    out = np.zeros(x.size, dtype=bool)
    for k in np.flatnonzero(ok):
        dominated = ok & (x <= x[k]) & (y <= y[k]) & ((x < x[k]) | (y < y[k]))
        out[k] = not dominated.any()
    return out


@shared_doc
def work_precision(table, *, work: str = "work", time: str | None = None, error: str = "max abs error"):
    """Error against work (log-log) for each method, the Pareto front ringed; or against run time.

    By default the cost is the table's exact work count (``work
    [evaluations]``: point evaluations of the compiled loop equations plus
    stencil evaluations, see :func:`numkin.report.work_precision_table`),
    the same in every run, so the figure is reproducible byte for byte.
    With `time` the measured run time is drawn instead, and the axis says
    that it varies between runs. The Pareto front (no other point of the
    panel has less cost and no larger error) is computed from the points
    drawn, so it always matches the axes.

    Parameters
    ----------
    table : DataFrame
        From :func:`numkin.report.work_precision_table`: columns ``method``,
        ``quantity``, the work or time column and the error column. One
        panel per quantity.
    work : str
        Start of the work column's name: ``"work"`` (sweep + derivative,
        default), ``"sweep work"`` or ``"derivative work"``.
    time : str, optional
        Start of a time column's name (``"sweep + derivative time"``,
        ``"sweep time"``, ``"derivative time"``): draw the measured time
        (ms, varies between runs) instead of the work.
    error : str
        Start of the error column's name.

    {{returns_figure}}

    Examples
    --------
    >>> from numkin import linkages, report, figures
    >>> wp = report.work_precision_table(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                                  grids=(36, 72), schemes=("centred", "second_difference"), repeat=1)
    >>> fig = figures.work_precision(wp)
    >>> fig.axes[0].get_xlabel()
    'work [point evaluations + stencil evaluations]'
    >>> figures.save(fig, "/tmp/numkin-doc-wp", ["png"])[0].suffix
    '.png'
    >>> figures.work_precision(wp, time="sweep + derivative time").axes[0].get_xlabel()
    'sweep + derivative time [ms] (varies between runs)'
    """
    need_table(table, "table", "work_precision")
    need_names(work, "work", "work_precision")
    need_names(time, "time", "work_precision")
    need_names(error, "error", "work_precision")
    what = "work-precision table"
    if time is not None:
        xcol = table_column(table, time, what)
        unit = (table.attrs.get("units") or {}).get(xcol)  # as the table says it, never read from the header
        xlabel = f"{time}{f' [{unit}]' if unit else ''} (varies between runs)"
        title = "error against run time, each method from coarse to fine grid (times vary between runs)"
    else:
        xcol = table_column(table, work, what, required=False)
        if xcol is None:
            raise InputError(
                f"{what}: no column starting with {work!r} (a table from an older numkin?); columns are "
                f"{list(table.columns)}; pass time='sweep + derivative time' to draw the measured run time"
            )
        xlabel = f"{work} [point evaluations + stencil evaluations]"
        title = ("error against work: evaluations of the loop equations + stencil evaluations, "
                 "each method from coarse to fine grid")
    ecol = table_column(table, error, what)
    mcol = table_column(table, "method", what)
    groups = _groups(table)
    with style():
        from .ticks import log_scale

        fig, axes = new_figure(1, len(groups), size=(6.4 if len(groups) == 1 else 9.6, 5.0))
        for ax, (quantity, sub) in zip(axes[0], groups):
            qtext, unit = _panel_text(quantity, error, table)
            order_col = "points per turn" if "points per turn" in sub.columns else xcol
            for k, method in enumerate(dict.fromkeys(sub[mcol])):
                rows = sub[sub[mcol] == method].sort_values(order_col, kind="mergesort")
                st = source_style(method, k)
                st["linewidth"] = min(st.get("linewidth", 1.5), 1.4)
                st.pop("alpha", None)
                st.pop("zorder", None)
                ax.plot(np.asarray(rows[xcol], dtype=float), _positive(rows[ecol]), label=source_label(method),
                        **marker_style(method, st["color"]), **st)
            on_front = _front(sub[xcol], sub[ecol])
            front = sub[on_front]
            ax.plot(np.asarray(front[xcol], dtype=float), _positive(front[ecol]), linestyle="none", marker="o",
                    markersize=14, markerfacecolor="none", markeredgecolor="black", markeredgewidth=1.0,
                    label="Pareto front", zorder=5)
            log_scale(ax, "xy")
            _plain_log_ticks(ax.xaxis, sub[xcol])
            ax.set_xlabel(xlabel)
            ax.set_ylabel(f"{error} [{unit}]")
            ax.set_title(qtext or "work and precision")
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncols=3, fontsize=7.5)
        fig.suptitle(title, fontsize=9)
    return fig


def on_curve(h, errors, at: float) -> float:
    """The error of a curve drawn on log-log axes, at step `at` (straight between its points).

    NaN outside the curve's steps or where a neighbour is missing.

    Examples
    --------
    >>> f"{on_curve([1e-4, 1e-2], [1e-10, 1e-6], 1e-3):.3g}"
    '1e-08'
    """
    h = np.asarray(h, dtype=float)
    e = np.asarray(errors, dtype=float)
    ok = np.isfinite(h) & np.isfinite(e) & (h > 0) & (e > 0)
    h, e = h[ok], e[ok]
    order = np.argsort(h)
    h, e = h[order], e[order]
    if h.size == 0 or not (h[0] * (1 - 1e-12) <= at <= h[-1] * (1 + 1e-12)):
        return float("nan")
    return float(10.0 ** np.interp(math.log10(at), np.log10(h), np.log10(e)))


@shared_doc
def roundoff(table):
    """Relative error against the step h at one angle: truncation error above, rounding below.

    Each scheme's V-curve at the table's steps, the fine scan its optimum is
    measured on (``attrs["scan"]``, a thin line of the same colour), its
    measured optimal step (star: where the truncation line and the rounding
    line fitted to that scan meet) and the textbook estimate
    ``h* ~ eps**(1/(p+n))`` (open marker), each at the error the table
    measured at that step (its columns ``rel error measured at that h`` and
    ``rel error measured at textbook h``; an error measured as exactly 0, which
    a log axis cannot show, on the drawn curve there); machine epsilon dotted.

    Parameters
    ----------
    table : DataFrame
        From :func:`numkin.report.roundoff_table`: ``scheme``, columns
        ``rel error at h = 1e-01 rad [-]`` ..., ``measured optimal h [rad]``,
        ``rel error measured at that h [-]``, ``textbook optimal h [rad]``,
        ``rel error measured at textbook h [-]``.

    {{returns_figure}}

    {{example_tables}}
    >>> ro = report.roundoff_table(linkages.chained_four_bars(), quantity="beta", check_angle=math.radians(100),
    ...                            schemes=("forward", "centred"))
    >>> figures.save(figures.roundoff(ro), "/tmp/numkin-doc-roundoff", ["png"])[0].suffix
    '.png'
    """
    need_table(table, "table", "roundoff")
    what = "round-off table"
    scol = table_column(table, "scheme", what)
    steps = table.attrs.get("steps") or {}
    cols = [(float(h), c) for c, h in steps.items() if c in table.columns]
    if not cols:
        raise InputError(f"{what}: no columns of errors at a step h (attrs['steps'], which "
                         "numkin.report.roundoff_table sets); columns are " + str(list(table.columns)))
    cols.sort()
    hs = np.array([h for h, _ in cols])
    eps = float(np.finfo(float).eps)
    scan = dict(table.attrs.get("scan") or {})
    scan_h = np.asarray(scan.pop("h [rad]", []), dtype=float)
    scan_order = np.argsort(scan_h)
    scan_h = scan_h[scan_order]
    scan = {k: np.asarray(v, dtype=float) for k, v in scan.items() if len(v) == scan_h.size}
    with style():
        from .ticks import log_scale

        fig, axes = new_figure(size=(6.4, 5.2))
        ax = axes[0, 0]
        allv = []
        for k, (_, row) in enumerate(table.iterrows()):
            scheme = str(row[scol])
            st = source_style(scheme, k)
            st.pop("alpha", None)
            st.pop("zorder", None)
            st["linewidth"] = 1.4
            second = is_second_derivative(scheme)
            st["linestyle"] = "--" if second else "-"
            errs = _positive([row[c] for _, c in cols])
            allv.extend(errs)
            order = row.get("formal order")
            label = _order_label(scheme, order)
            mk = marker_style(scheme, st["color"])
            mk["markersize"] = 0.7 * mk["markersize"]
            ax.plot(hs, errs, label=label, **mk, **st)
            fine_h, fine_e = hs, errs
            if scheme in scan:  # the fine scan the optimum is measured on, as a thin line
                fine_h, fine_e = scan_h, _positive(scan[scheme])[scan_order]
                allv.extend(fine_e)
                ax.plot(fine_h, fine_e, color=st["color"], linestyle=st["linestyle"], linewidth=0.6, alpha=0.75,
                        label=f"_scan {scheme}", zorder=1.5)
            # the table's two steps at the errors it measured there (else, for a table without them, on the drawn
            # fine scan or the coarse curve)
            for h_col, e_col, kind in (("measured optimal h [rad]", "rel error measured at that h [-]", "*"),
                                       ("textbook optimal h [rad]", "rel error measured at textbook h [-]", "D")):
                if h_col not in row.index or (kind == "D" and getattr(by_label(scheme), "kind", "") == "complex_step"):
                    continue
                h_at = float(row[h_col])
                e_at = float(row[e_col]) if e_col in row.index else math.nan
                if not e_at > 0:  # no column, or an error measured as exactly 0 (no place on a log axis): the curve's
                    e_at = on_curve(fine_h, fine_e, h_at)
                look = (dict(markersize=11, color=st["color"], markeredgecolor="black", markeredgewidth=0.5)
                        if kind == "*" else dict(markersize=6, markerfacecolor="white", markeredgecolor=st["color"],
                                                 markeredgewidth=1.3))
                ax.plot(h_at, e_at, marker=kind, linestyle="none", zorder=5, **look)
        ax.axhline(eps, color="0.4", linestyle=":", linewidth=0.9)
        ax.text(hs.max(), eps * 1.6, "machine ε", ha="right", va="bottom", fontsize=7.5, color="0.3")
        # legend entries for the markers
        ax.plot([], [], marker="*", markersize=10, color="0.5", markeredgecolor="black", markeredgewidth=0.5,
                linestyle="none", label="measured optimum")
        ax.plot([], [], marker="D", markersize=6, markerfacecolor="white", markeredgecolor="0.3",
                linestyle="none", label=r"textbook $h^* \sim \varepsilon^{1/(p+n)}$")
        if scan:
            ax.plot([], [], color="0.4", linewidth=0.6, label=f"fine scan ({scan_h.size} steps)")
        log_scale(ax, "xy")
        lo, hi = _log_limits(allv + [eps])
        ax.set_ylim(lo, hi)
        ax.set_xlabel("step $h$ [rad]")
        ax.set_ylabel("relative error [–]")
        ax.set_title(_title(table, "round-off: error against step"), fontsize=9)
        fig.legend(loc="outside lower center", fontsize=7.5, ncols=3)
    return fig


@shared_doc
def newton_residuals(tables):
    """Newton's residual norm per iteration (log scale), one curve per Jacobian.

    Parameters
    ----------
    tables : DataFrame or mapping of str to DataFrame
        From :func:`numkin.report.newton_table` (columns ``iteration``,
        ``residual norm [-]``): Jacobian name -> table, or one table (a
        ``Jacobian`` column, if present, splits it into curves).

    {{returns_figure}}

    {{example_tables}}
    >>> mech = linkages.chained_four_bars()
    >>> tables = {j: report.newton_table(mech, check_angle=math.radians(100), jacobian=j)
    ...           for j in ("symbolic", "forward", "central")}
    >>> fig = figures.newton_residuals(tables)
    >>> fig.axes[0].get_yscale()
    'log'
    >>> figures.save(fig, "/tmp/numkin-doc-newton", ["png"])[0].suffix
    '.png'
    """
    need_tables(tables, "tables", "newton_residuals")
    if hasattr(tables, "columns"):
        if "Jacobian" in tables.columns:
            tables = {str(j): sub for j, sub in _groups(tables, "Jacobian")}
        else:
            tables = {jacobian_of(tables): tables}
    if not tables:
        raise InputError("newton_residuals: no Newton table given")
    # overlapping curves stay visible: large open, medium open, small filled markers
    styles = {"symbolic": ("black", "-", "o", 10, "none"), "forward": ("#D55E00", "--", "s", 6.5, "none"),
              "central": ("#0072B2", ":", "^", 4.5, "#0072B2")}
    with style():
        from .ticks import log_scale

        fig, axes = new_figure(size=(6.4, 4.2))
        ax = axes[0, 0]
        kmax = 0
        for k, (name, t) in enumerate(tables.items()):
            it = table_column(t, "iteration", "Newton table")
            rc = table_column(t, "residual norm", "Newton table")
            color, ls, marker, size, face = styles.get(str(name), (CYCLE[k % len(CYCLE)], "-.", "D", 5, "none"))
            ax.plot(t[it], _positive(t[rc]), color=color, linestyle=ls, marker=marker, markersize=size,
                    markerfacecolor=face, markeredgewidth=1.2, label=f"{name} Jacobian")
            kmax = max(kmax, int(np.max(t[it])))
        from matplotlib.ticker import MaxNLocator

        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        log_scale(ax, "y")
        ax.set_xlabel("iteration $k$ [–]")
        ax.set_ylabel("residual norm (scaled) [–]")
        first = next(iter(tables.values()))
        check = getattr(first, "attrs", {}).get("check")
        at = f" at {_check_text(check)}" if check else ""
        ax.set_title(f"Newton: residual per iteration{at}")
        ax.legend(loc="upper right")
    return fig


def jacobian_of(table) -> str:
    """Name of the Jacobian a Newton table was solved with: its ``attrs["jacobian"]``, set by
    :func:`numkin.report.newton_table`; ``"symbolic"`` (numkin's default) for a table that does not say."""
    return str(getattr(table, "attrs", {}).get("jacobian") or "symbolic")

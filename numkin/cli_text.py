"""What ``numkin run`` prints: a scene's result (check points, largest errors of the schemes, files
written) and the stability suite, as text.

Examples
--------
>>> fmt_value(10.63318, 10.633), fmt_value(0.000123456789), fmt_value(6.3701234, 6.371, mismatch=True)
('10.633', '0.000123457', '6.37012')
"""

from __future__ import annotations

import math
import textwrap

__all__ = ["format_result", "fmt_value"]


def fmt_value(value: float, expected: float | None = None, mismatch: bool = False, written: str | None = None) -> str:
    """A value to the decimals of its expected value, else to 6 significant digits; a ``mismatch`` (a value that
    misses its expected one) to 6 significant digits or two decimals more than the expected value, whichever
    shows more, so that it never reads as the expected value rounded. ``written``: the expected value as the
    scene file writes it (``"122.340"``), whose decimals count then."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if value == 0:
        value = 0.0  # no "-0"
    if expected is not None:
        text = written.replace("_", "") if written is not None else repr(float(expected))
        if written is not None and "e" in text.lower() and value == expected:
            return text  # (the expected value itself, as written: 1.50e2)
        if "e" not in text.lower():
            decimals = 0 if written is None and text.endswith(".0") else len((text.split(".") + [""])[1])
            if not mismatch:
                return f"{value:.{decimals}f}"
            shown = f"{expected:.{decimals}f}"
            for digits in range(decimals + 2, 16):  # two decimals more, and more until it differs from the expected
                text = f"{value:.{digits}f}"
                if text.rstrip("0") != shown.rstrip("0") and float(text) != float(shown):
                    break
            six = f"{value:#.6g}".rstrip(".")
            return six if "e" not in six and "." in six and len(six.split(".")[1]) > digits else text
    return f"{value:#.6g}".rstrip(".")


def _label(check, key: str) -> str:
    """A check value's label: its Quantity's name (``theta3``, whose scene key is ``theta3_deg``) and unit."""
    q = check.quantities.get(key)
    return f"{key if q is None else q.name} [{check.units[key]}]"


def _check_lines(check, input_name: str, title: str) -> list[str]:
    head = f"{title} {input_name} = {check.at_deg:g}°"
    if not check.on_grid:
        head += " (between grid points: no finite differences)"
    lines = [head]
    width = max((len(_label(check, k)) for k in check.values), default=10) + 2
    for key, value in check.values.items():
        expected = check.expected.get(key)
        missed = expected is not None and not check.ok[key]
        written = check.written.get(key)
        line = f"  {_label(check, key):<{width}}{fmt_value(value, expected, mismatch=missed, written=written):>12}"
        if expected is not None:
            mark = "ok" if check.ok[key] else f"MISMATCH (tolerance {check.tolerance[key]:.1g})"
            line += f"   expected {fmt_value(expected, expected, written=written)} {mark}"
        schemes = [f"{s}{' (one-sided end stencil)' if key in check.end_stencil.get(s, ()) else ''} {fmt_value(vals[key])}"
                   for s, vals in check.schemes.items() if key in vals]
        if schemes:
            line += "   " + "   ".join(schemes)
        lines.append(line.rstrip())
    return lines


def format_result(result) -> str:
    """The text summary printed by ``numkin run``: sweep, check points, largest errors, files."""
    from .units import deg_text  # (numpy, which --help does not load)

    scene = result.scene
    lines = [f"{scene.name}: {scene.title or scene.description}"]
    if scene.kind == "stability":
        lines += _suite_lines(result.suite)
    else:
        mech, sweep = result.mechanism, result.sweep
        name = mech.input_name
        motion = f"{name} {scene.start_deg:g}..{scene.stop_deg:g}° step {scene.step_deg:g}° ({scene.n_points} points)"
        if result.omega is not None:
            speed = f"{result.omega:.6g} rad/s"
            if scene.speed_text and scene.speed_text.strip() != speed:
                speed = f"{scene.speed_text} = {speed}"
            motion += f", speed {speed}"
            if result.alpha:
                motion += f", acceleration {result.alpha:.6g} rad/s^2"
        lines.append(f"  {mech.title}; {motion}")
        lines.append(
            f"  Newton: max {int(sweep.iterations.max())} iterations, max residual "
            f"{float(sweep.residual.max()):.1e}, largest condition number of a loop's block {float(sweep.cond.max()):.3g}"
        )
        for event in sweep.events:
            lines.append(f"  {event.kind} at {name} = {deg_text(event.input_value)}: {event.message}")
        for check in result.checks:
            lines += [""] + _check_lines(check, name, "check at")
        if result.at is not None:
            lines += [""] + _check_lines(result.at, name, "every quantity at")
        if result.comparisons:
            lines += ["", "largest error over the sweep, against the exact (analytic) solution"]
            rows = []
            open_grid = any(not c.periodic for c in result.comparisons.values())
            for quantity, comparison in result.comparisons.items():
                for scheme, row in comparison.summary_records().items():
                    ends = row.get("ends_abs_error", math.nan)
                    rows.append((
                        f"{quantity} [{comparison.unit}]", scheme, f"{row['max_abs_error']:.3g}",
                        f"{100 * row['max_rel_error']:.3g}%", f"{row['max_at_deg']:g}",
                        *([f"{ends:.3g}" if ends == ends else ""] if open_grid else []),
                    ))
            head = ("quantity", "scheme", "max abs error", "max rel error", f"at {name} [deg]",
                    *(["ends, one-sided"] if open_grid else []))
            widths = [max(len(r[k]) for r in [head, *rows]) for k in range(len(head))]
            for r in [head, *rows]:
                lines.append("  " + "  ".join(
                    (f"{c:<{w}}" if k < 2 else f"{c:>{w}}") for k, (c, w) in enumerate(zip(r, widths))
                ).rstrip())
            lines.append("  (max rel error: the largest error over the largest |exact value| of the sweep)")
            if open_grid:
                lines.append("  (an open grid: the first and last points take one-sided end stencils, whose largest "
                             "error is given apart)")
    if result.written:
        lines += ["", "written:"] + [f"  {p}" for p in result.written]
    return "\n".join(lines)


def _suite_lines(suite) -> list[str]:
    """The stability suite, one line per case plus what happened (the full table goes to --out / JSON)."""
    columns = [
        ("case", "case", str), ("outcome", "outcome", str),
        ("as expected", "as expected", lambda v: "yes" if v else "NO"),
        ("max cond [-]", "max cond", lambda v: fmt_value(float(v))),
        ("Newton iterations (max)", "iterations", lambda v: "-" if v != v else str(int(v))),
        ("centred max rel error [-]", "centred rel err", lambda v: "-" if v != v else f"{float(v):.2e}"),
        ("second_difference max rel error [-]", "2nd diff rel err", lambda v: "-" if v != v else f"{float(v):.2e}"),
    ]
    columns = [c for c in columns if c[0] in suite.columns]
    rows = [[head for _, head, _ in columns]]
    for _, record in suite.iterrows():
        rows.append([fmt(record[col]) for col, _, fmt in columns])
    widths = [max(len(r[k]) for r in rows) for k in range(len(columns))]
    lines = []
    for n, r in enumerate(rows):
        lines.append("  " + "  ".join(f"{c:<{w}}" for c, w in zip(r, widths)).rstrip())
    notes = []
    for _, record in suite.iterrows():
        what = " ".join(str(record.get("what happened", "") or "").split())
        raised = " ".join(str(record.get("error or warning raised", "") or "").split())
        text = "; ".join(t for t in (what, raised) if t)
        if text:
            notes += textwrap.wrap(f"{record['case']}: {text}", width=118, initial_indent="  ", subsequent_indent="    ")
    return lines + ([""] + notes if notes else [])

"""Writing tables: Markdown, CSV and LaTeX (booktabs rules, without jinja2).

Numbers are written by what their column holds, as the table says where it
is made (``attrs["kinds"]``, :mod:`numkin.column_kinds`); a column the table
does not name (a table built by hand) by its label (:func:`column_format`).
"""

from __future__ import annotations

import math
from typing import Mapping, Sequence

import numpy as np

from ..column_kinds import FORMATS
from ..errors import InputError
from ..folders import made_folder

__all__ = [
    "write_tables",
    "format_text",
    "format_cell",
    "column_format",
    "column_formats",
    "table_views",
]


def column_format(column: str) -> str:
    """The number format of a column a table does not name a kind for, guessed from its label (Python format
    spec, ``"int"`` or ``"exact"``; :func:`column_formats`).

    For a table built by hand, and for the tables whose functions do not
    yet say their columns' kinds (the round-off, work-precision,
    cheapest-method and stability tables).

    Errors, residuals, norms, condition numbers, differences (``a vs b``),
    measured widths (``sharpest turn``) and times: 3 significant figures; orders: 2 decimals; counts (iterations, points, evaluations):
    integers, a mean of them 1 decimal; estimated optimal steps 2
    significant figures; exact values and other quantities 7 significant
    figures (shown with their trailing zeros, so that a column's values
    read alike: 10.63300 beside 10.63198), exact values 6 decimals (7 significant figures outside
    1e-3 ... 1e4); inputs (steps, angles, tolerances) as given (up to 6
    significant figures).

    Examples
    --------
    >>> [column_format(c) for c in ("max abs error [rad/s]", "observed order [-]", "points per turn",
    ...                              "h [deg]", "exact value [unit of quantity]")]
    ['.3g', '.2f', 'int', '.6g', 'exact']
    """
    c = str(column).lower()
    if c.endswith("optimal h [rad]"):
        return ".2g"
    if c.startswith("exact value"):
        return "exact"
    if "order" in c and "formal" not in c:
        return ".2f"
    if "(mean)" in c or "mean" in c.split():
        return ".1f"
    if any(w in c for w in ("iteration", "points", "evaluations", "count")):
        return "int"
    if any(w in c for w in ("error", "residual", "norm", "cond", "difference", "|f|", "j^-1", "time", "[%]", " vs ",
                            "sharpest")):
        return ".3g"
    if c.startswith("h ") or c.startswith("tol") or "wanted" in c or "[deg]" in c or c.startswith("delta"):
        return ".6g"
    return ".7g"


def column_formats(df) -> dict:
    """The number format of each column of `df`: by its kind (``attrs["kinds"]``, :data:`numkin.column_kinds.FORMATS`)
    where the table names one, else by its label (:func:`column_format`).

    Examples
    --------
    >>> import pandas as pd
    >>> df = pd.DataFrame({"second_difference [rad/s^2]": [-28.37646], "h [deg]": [1.0]})
    >>> column_formats(df)                    # a table built by hand: guessed from the labels
    {'second_difference [rad/s^2]': '.3g', 'h [deg]': '.6g'}
    >>> df.attrs["kinds"] = {"second_difference [rad/s^2]": "value"}
    >>> column_formats(df)["second_difference [rad/s^2]"]
    '.7g'
    """
    kinds = df.attrs.get("kinds") or {}
    return {c: FORMATS[kinds[c]] if c in kinds else column_format(c) for c in df.columns}


def format_cell(value, column: str = "", *, fmt: str | None = None) -> str:
    """One cell as text, by its column's format: `fmt` (one of :data:`numkin.column_kinds.FORMATS`) if given,
    else guessed from the column's label (:func:`column_format`); NaN and None are blank.

    Examples
    --------
    >>> format_cell(2.85596, "Newton iterations per point (mean)"), format_cell(0.000942185, "rel error [%]")
    ('2.9', '0.000942')
    >>> format_cell(float("nan"), "max abs error"), format_cell(True, "Pareto front"), format_cell(-0.0, "x [mm]")
    ('', 'yes', '0')
    >>> format_cell(10.632996, "omega_beta [rad/s]"), format_cell(10.631984, "omega_beta [rad/s]"), format_cell(3.0, "x")
    ('10.63300', '10.63198', '3')
    >>> format_cell(1234567.5, "x [mm]"), format_cell(-0.5, "x [mm]"), format_cell(-28.37646, fmt=".7g")
    ('1234568', '-0.5000000', '-28.37646')
    """
    if value is None:
        return ""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer, float, np.floating)):
        v = float(value)
        if math.isnan(v):
            return ""
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        fmt = fmt or column_format(column)
        if fmt == "int":
            text = str(int(round(v)))
        elif fmt == "exact":
            text = f"{v:.6f}" if 1e-3 <= abs(v) < 1e4 else format(v, ".7g")
        elif fmt == ".7g" and v != round(v):  # a quantity: its 7 figures, trailing zeros kept (10.63300, not 10.633)
            text = format(v, "#.7g").rstrip(".")  # (1234568, not 1234568.)
        else:
            text = format(v, fmt)
        if text.lstrip("-").strip("0.e+") == "":  # a negative zero, or a value that rounds to zero
            text = text.lstrip("-")
        return text
    return str(value)


def table_views(df) -> list:
    """The parts a table is read in: ``[(title, DataFrame)]`` from ``attrs["views"]``, else the whole table.

    Columns that no view names are not lost: they make a last part, "other
    columns", after the row keys (``attrs["row_keys"]``).
    """
    return [(title, df[cols]) for title, cols in _view_columns(df)]


def _md_escape(text: str) -> str:
    """Text safe in a GitHub-flavoured Markdown table cell: ``|`` escaped, no line breaks."""
    return str(text).replace("\\", "\\\\").replace("|", "\\|").replace("\n", " ")


def _markdown_table(df, formats: dict) -> str:
    """A GitHub-flavoured Markdown table (pipe table), each column's numbers in its format of `formats`."""
    numeric = [df[c].dtype.kind in "iuf" for c in df.columns]
    header = "| " + " | ".join(_md_escape(c) for c in df.columns) + " |"
    rule = "|" + "|".join("---:" if isnum else ":---" for isnum in numeric) + "|"
    lines = [header, rule]
    fmts = [formats[c] for c in df.columns]
    for row in df.itertuples(index=False):
        lines.append("| " + " | ".join(_md_escape(format_cell(v, fmt=f)) for v, f in zip(row, fmts)) + " |")
    return "\n".join(lines) + "\n"


def format_text(df, *, width: int = 100, max_width: int = 120) -> str:
    """A table for the terminal: its caption wrapped to `width`, then each view as a plain text table.

    Numbers as in Markdown (:func:`format_cell`), NaN blank, one view per
    block, so that a wide table is read in parts no wider than its view;
    headers wrap at 14 characters over numbers, 24 over text, and text
    cells at 40. A view wider than `max_width` characters is shown in parts
    that each repeat the columns naming a row (``attrs["row_keys"]``, else
    the first column).

    Examples
    --------
    >>> import pandas as pd
    >>> print(format_text(pd.DataFrame({"scheme": ["centred"], "max abs error [rad/s]": [2.5e-4],
    ...                                  "observed order [-]": [1.998]})))
    scheme      max abs error    observed order
                      [rad/s]               [-]
    --------  ---------------  ----------------
    centred           0.00025              2.00
    >>> wide = pd.DataFrame({"case": ["a"], **{f"error of scheme {k} [-]": [0.5] for k in range(12)}})
    >>> text = format_text(wide, max_width=60)
    >>> max(len(line) for line in text.splitlines()) <= 60, text.count("case") > 1   # parts, each with its key
    (True, True)
    """
    import textwrap

    import pandas as pd

    blocks = []
    caption = df.attrs.get("caption")
    if caption:
        blocks.append(textwrap.fill(str(caption), width=width))
    keys = [c for c in df.attrs.get("row_keys") or [] if c in df.columns]
    formats = column_formats(df)
    plain = pd.DataFrame(df, copy=False)
    plain.attrs = {}  # columns read without copying the table's attrs each time
    formatted = {}  # column -> (cells as text, right-aligned): each column formatted once for all its views
    for title, columns in _view_columns(df):
        for c in columns:
            if c not in formatted:
                column = plain[c]
                formatted[c] = ([format_cell(v, fmt=formats[c]) for v in column.tolist()], column.dtype.kind in "iuf")
        whole = _text_table(columns, formatted)
        parts = _fitting_parts(columns, [k for k in keys if k in columns] or list(columns[:1]), max_width,
                               whole)
        for n, part in enumerate(parts):
            head = title + (f" ({n + 1} of {len(parts)})" if len(parts) > 1 else "")
            text = whole if len(parts) == 1 else _text_table(part, formatted)
            blocks.append((f"{head}\n" if head else "") + text)
    return "\n\n".join(blocks)


def _view_columns(df) -> list:
    """The column names of each view of :func:`table_views`, without slicing the DataFrame."""
    views = df.attrs.get("views") or []
    present = set(df.columns)
    out = [(str(title), [c for c in cols if c in present]) for title, cols in views]
    out = [(t, cols) for t, cols in out if cols]
    if not out:
        return [("", list(df.columns))]
    named = {c for _, cols in out for c in cols}
    rest = [c for c in df.columns if c not in named]
    if rest:
        keys = [c for c in df.attrs.get("row_keys") or () if c in present]
        out.append(("other columns", keys + rest))
    return out


def _text_table(columns: list, formatted: dict) -> str:
    """Columns (already formatted, :func:`format_cell`) as a plain text table (tabulate)."""
    from tabulate import tabulate

    cells = [list(row) for row in zip(*(formatted[c][0] for c in columns))]
    align = ["right" if formatted[c][1] else "left" for c in columns]
    return tabulate(
        cells, headers=list(columns), disable_numparse=True, colalign=align,
        maxcolwidths=[None if a == "right" else 40 for a in align],
        maxheadercolwidths=[14 if a == "right" else 24 for a in align],
    )


def _column_widths(columns: list, text: str) -> dict:
    """Width of each column of `text`, the :func:`_text_table` of `columns` (read off the rule under the headers).

    A column's width depends on its own header and cells only, so a table of
    some of the columns is as wide as theirs plus two spaces between each.
    """
    rule = next(line for line in text.splitlines() if line.strip() and not line.strip("- "))
    widths = [len(run) for run in rule.split()]
    return dict(zip(columns, widths))


def _fitting_parts(columns: list, keys: list, max_width: int, whole: str) -> list:
    """`columns` as they are if no wider than `max_width`, else in parts: the key columns, then as many more as fit.

    `whole` is the text table of all `columns` (:func:`_text_table`).
    """
    widths = _column_widths(columns, whole)

    def width(cols):
        return sum(widths[c] for c in cols) + 2 * (len(cols) - 1)

    if width(columns) <= max_width:
        return [columns]
    rest = [c for c in columns if c not in keys]
    parts, current = [], []
    for column in rest:
        if current and width(keys + current + [column]) > max_width:
            parts.append(keys + current)
            current = []
        current.append(column)
    if current:
        parts.append(keys + current)
    return parts


_TEX_SPECIAL = {
    "\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
    "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "|": r"\textbar{}", "<": r"\textless{}",
    ">": r"\textgreater{}", "°": r"\textdegree{}",
}


def _tex(text: str) -> str:
    """Escape text for LaTeX; ``^2`` and ``^(1/4)`` become superscripts."""
    import re

    out = []
    parts = re.split(r"(\^\([^)]*\)|\^-?\d+)", text)
    for part in parts:
        if part.startswith("^"):
            out.append(r"\textsuperscript{" + "".join(_TEX_SPECIAL.get(c, c) for c in part[1:].strip("()")) + "}")
        else:
            out.append("".join(_TEX_SPECIAL.get(c, c) for c in part))
    return "".join(out)


def _booktabs(df, name: str) -> str:
    """A LaTeX table with booktabs rules (needs \\usepackage{booktabs}); no jinja2.

    The cells carry the digits of the Markdown table (:func:`format_cell`), and a
    table read in parts (:func:`table_views`) is one tabular per part, each
    under its title, so that no part is wider than the Markdown one.
    """
    lines = ["% needs \\usepackage{booktabs}", "\\begin{table}[htbp]", "\\centering"]
    caption = df.attrs.get("caption")
    if caption:
        lines.append("\\caption{" + _tex(caption) + "}")
    lines.append("\\label{tab:" + name.replace("_", "-") + "}")
    formats = column_formats(df)
    for k, (title, view) in enumerate(table_views(df)):
        if k:
            lines.append("\\medskip")
        if title:
            lines.append("\\par\\textbf{" + _tex(title) + "}\\par\\smallskip")
        spec = "".join("r" if view[c].dtype.kind in "iuf" else "l" for c in view.columns)
        lines += ["\\begin{tabular}{" + spec + "}", "\\toprule",
                  " & ".join(_tex(str(c)) for c in view.columns) + " \\\\", "\\midrule"]
        for row in view.itertuples(index=False):
            lines.append(" & ".join(_tex(format_cell(v, fmt=formats[c])) for v, c in zip(row, view.columns)) + " \\\\")
        lines += ["\\bottomrule", "\\end{tabular}"]
    lines.append("\\end{table}")
    return "\n".join(lines) + "\n"


def _markdown(df) -> str:
    """A table as Markdown: its caption, then each view (:func:`table_views`) under a bold title."""
    parts = []
    caption = df.attrs.get("caption")
    if caption:
        parts.append(_md_escape(caption))
    formats = column_formats(df)
    for title, view in table_views(df):
        if title:
            parts.append(f"**{_md_escape(title)}**")
        parts.append(_markdown_table(view, formats))
    return "\n\n".join(p.rstrip("\n") for p in parts) + "\n"


def write_tables(tables: Mapping, out_dir, formats: Sequence[str] = ("md", "csv", "tex")) -> list:
    """Write tables as Markdown, CSV and LaTeX (booktabs) files, one file per table and format.

    Parameters
    ----------
    tables : mapping
        name -> DataFrame (e.g. from :func:`full_report`); the name is the file stem.
    out_dir : str or Path
        Directory, created if needed.
    formats : sequence of {"md", "csv", "tex"}
        Markdown (GitHub-flavoured pipe tables, ``|`` escaped, numbers with
        the significant figures of their column, :func:`format_cell`; a
        wide table in the parts named by ``attrs["views"]``, one idea
        each, and the columns no part names in a last one), CSV (every
        column, full precision, empty cells for NaN) and LaTeX with booktabs
        rules (the parts of the Markdown, the same digits). A table's
        ``attrs["caption"]`` heads the Markdown and becomes the LaTeX
        caption.

    Returns
    -------
    list of Path
        The files written, table by table in the mapping's order, formats
        in the given order.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> df = pd.DataFrame({"h [deg]": [1.0, 0.5], "max abs error [rad/s]": [2e-4, 5e-5]})
    >>> with tempfile.TemporaryDirectory() as d:
    ...     [p.name for p in write_tables({"demo": df}, d, formats=("csv", "tex"))]
    ['demo.csv', 'demo.tex']
    """
    allowed = ("md", "csv", "tex")
    formats = [formats] if isinstance(formats, str) else list(formats)
    bad = [f for f in formats if f not in allowed]
    if bad:
        raise InputError(f"unknown table format(s) {bad}; choose from {list(allowed)}")
    out = made_folder(out_dir, "out_dir")
    written = []
    for name, df in tables.items():
        for fmt in formats:
            path = out / f"{name}.{fmt}"
            if fmt == "md":
                text = _markdown(df)
            elif fmt == "csv":
                text = df.to_csv(index=False)
            else:
                text = _booktabs(df, str(name))
            path.write_text(text, encoding="utf-8")
            written.append(path)
    return written

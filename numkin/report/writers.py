"""Writing tables: Markdown, CSV and LaTeX (booktabs rules, without jinja2)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

__all__ = [
    "write_tables",
]


def _cell(value) -> str:
    """One table cell as text: 6 significant digits, blanks for NaN, yes/no for booleans."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        if math.isnan(value):
            return ""
        return f"{float(value):.6g}"
    return "" if value is None else str(value)


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
    """A LaTeX table with booktabs rules (needs \\usepackage{booktabs}); no jinja2."""
    numeric = [
        df[c].dtype.kind in "iuf" for c in df.columns
    ]
    spec = "".join("r" if isnum else "l" for isnum in numeric)
    lines = [
        "% needs \\usepackage{booktabs}",
        "\\begin{table}[htbp]",
        "\\centering",
    ]
    caption = df.attrs.get("caption")
    if caption:
        lines.append("\\caption{" + _tex(caption) + "}")
    lines.append("\\label{tab:" + name.replace("_", "-") + "}")
    lines.append("\\begin{tabular}{" + spec + "}")
    lines.append("\\toprule")
    lines.append(" & ".join(_tex(str(c)) for c in df.columns) + " \\\\")
    lines.append("\\midrule")
    for row in df.itertuples(index=False):
        lines.append(" & ".join(_tex(_cell(v)) for v in row) + " \\\\")
    lines.append("\\bottomrule")
    lines.append("\\end{tabular}")
    lines.append("\\end{table}")
    return "\n".join(lines) + "\n"


def _require_tabulate() -> None:
    try:
        import tabulate  # noqa: F401  (pandas.DataFrame.to_markdown needs it)
    except ImportError:
        raise ImportError(
            "writing Markdown tables needs the 'tabulate' package (pip install tabulate); "
            "or call write_tables(..., formats=('csv', 'tex'))"
        ) from None


def _markdown(df) -> str:
    _require_tabulate()
    align = ["right" if df[c].dtype.kind in "iuf" else "left" for c in df.columns]
    text = df.map(_cell).to_markdown(index=False, disable_numparse=True, colalign=align)
    caption = df.attrs.get("caption")
    return (f"{caption}\n\n" if caption else "") + text + "\n"


def write_tables(tables: Mapping, out_dir, formats: Sequence[str] = ("md", "csv", "tex")) -> list:
    """Write tables as Markdown, CSV and LaTeX (booktabs) files, one file per table and format.

    Parameters
    ----------
    tables : mapping
        name -> DataFrame (e.g. from :func:`full_report`); the name is the file stem.
    out_dir : str or Path
        Directory, created if needed.
    formats : sequence of {"md", "csv", "tex"}
        Markdown (``DataFrame.to_markdown``, needs ``tabulate``), CSV (full
        precision, empty cells for NaN) and LaTeX with booktabs rules. A
        table's ``attrs["caption"]`` heads the Markdown and becomes the
        LaTeX caption.

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
        raise ValueError(f"unknown table format(s) {bad}; choose from {list(allowed)}")
    if "md" in formats:
        _require_tabulate()  # fail before any file is written
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
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

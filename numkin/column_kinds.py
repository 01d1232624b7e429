"""What a table's columns hold, said where the table is made, and the number format of each kind.

A table made by numkin (the scene tables of :mod:`numkin.outputs`, a
comparison's of :func:`numkin.compare.compare`, the error tables of
:mod:`numkin.report`) names what each numeric column holds in
``DataFrame.attrs["kinds"]``, column -> kind; the writers of
:mod:`numkin.report.writers` (Markdown, LaTeX, the terminal) format every
cell by its column's kind (CSV keeps every digit):

================  =====================================================  =============================
kind              the column holds                                       written
================  =====================================================  =============================
``"error"``       errors, residuals, norms, condition numbers,           3 significant figures
                  differences between two results, measured times
``"order"``       orders of convergence, observed or estimated           2 decimals
``"mean"``        a mean of counts                                       1 decimal
``"count"``       iterations, points, evaluations                        an integer
``"step"``        estimated optimal steps                                2 significant figures
``"exact"``       exact values of a quantity                             6 decimals (7 significant
                                                                         figures outside 1e-3 ... 1e4)
``"input"``       what was given: input angles, steps, tolerances        up to 6 significant figures
``"value"``       a computed quantity                                    7 significant figures, trailing
                                                                         zeros kept (10.63300)
================  =====================================================  =============================

A column of text needs no kind. A column a table does not name (a table
built by hand) is formatted by its label
(:func:`numkin.report.writers.column_format`).

Examples
--------
>>> import pandas as pd
>>> df = set_kinds(pd.DataFrame({"theta [deg]": [0.0], "omega [rad/s]": [1.5]}),
...                {"theta [deg]": "input", "omega [rad/s]": "value", "absent": "error"})
>>> df.attrs["kinds"]
{'theta [deg]': 'input', 'omega [rad/s]': 'value'}
>>> FORMATS["value"], FORMATS["error"]
('.7g', '.3g')
"""

from __future__ import annotations

from collections.abc import Mapping

from .errors import InputError

__all__ = ["FORMATS", "set_kinds"]

#: The number format of each kind of column: a Python format spec, ``"int"`` or ``"exact"``.
FORMATS = {
    "error": ".3g",
    "order": ".2f",
    "mean": ".1f",
    "count": "int",
    "step": ".2g",
    "exact": "exact",
    "input": ".6g",
    "value": ".7g",
}


def set_kinds(df, kinds: Mapping):
    """Say what the columns of `df` hold: ``attrs["kinds"]`` updated with column -> kind; `df` is returned.

    Columns `df` does not have are left out (a column made only on an open
    grid, say).

    Raises
    ------
    InputError
        For a kind not in :data:`FORMATS`.
    """
    bad = sorted({str(k) for k in kinds.values() if k not in FORMATS})
    if bad:
        raise InputError(f"unknown column kind(s) {bad}; kinds are {list(FORMATS)}")
    present = set(df.columns)
    df.attrs["kinds"] = {**(df.attrs.get("kinds") or {}), **{c: k for c, k in kinds.items() if c in present}}
    return df

"""The tables typed into module docstrings agree with the registries they describe.

``numkin.derivatives`` lists the schemes, ``numkin.linkages`` and
``numkin.scene`` the ready-made linkages; the registries are what runs, so a
scheme or a linkage added there must be added to these pages too.
"""

from __future__ import annotations

import re

import numkin.derivatives
import numkin.linkages
import numkin.scene
from numkin.schemes import SCHEMES


def rst_rows(doc: str, first_column: str) -> list[list[str]]:
    """The rows of the simple rst table whose header starts with ``first_column``, split at the
    column boundaries of its ``=====`` rules (a row continued on the next line is kept apart)."""
    lines = doc.splitlines()
    start = next(k for k, line in enumerate(lines)
                 if k and lines[k - 1].startswith("===") and line.strip().strip("`").startswith(first_column))
    rule = lines[start - 1]
    spans = [m.span() for m in re.finditer(r"=+", rule)]
    rows = []
    for line in lines[start + 2:]:
        if line.startswith("="):
            break
        rows.append([line[a:b if k < len(spans) - 1 else None].strip() for k, (a, b) in enumerate(spans)])
    return rows


def test_the_scheme_table_of_numkin_derivatives_is_the_registry():
    rows = rst_rows(numkin.derivatives.__doc__, "name")
    listed = {name: (derivative, order) for name, derivative, order, _ in rows}
    finite_differences = {n: s for n, s in SCHEMES.items() if n != "complex_step"}
    assert set(listed) >= set(n for n in finite_differences if n in numkin.schemes.BUILT_IN)
    for name, (derivative, order) in listed.items():
        scheme = SCHEMES[name]
        assert derivative == ("1st" if scheme.derivative == 1 else "2nd"), name
        assert order == ("spectral" if scheme.order == 0 else str(scheme.order)), name


def test_the_linkage_tables_name_every_registered_linkage():
    rows = rst_rows(numkin.linkages.__doc__, "linkage")
    listed = {name.strip("`"): (unknowns, inp) for name, unknowns, inp in rows}
    assert set(listed) == set(numkin.linkages.SPECS)
    for name, (unknowns, inp) in listed.items():
        spec = numkin.linkages.SPECS[name]
        assert unknowns.split(", ") == list(spec.unknown_names), name
        assert inp.split()[0] == spec.input, name
    # the scene page's table: each linkage with every dimension (its scene key) and every unknown
    scene_rows = rst_rows(numkin.scene.__doc__, "linkage")
    text = {}
    name = None
    for row in scene_rows:
        if row[0]:
            name = row[0].strip("`")
        text[name] = text.get(name, "") + " " + " ".join(row[1:])
    assert set(text) == set(numkin.linkages.SPECS)
    for name, cells in text.items():
        words = set(re.findall(r"\w+", cells))
        spec = numkin.linkages.SPECS[name]
        assert {d.scene_key for d in spec.dimensions} <= words, name
        assert set(spec.unknown_names) <= words, name

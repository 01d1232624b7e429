"""Every pipe table of the project's Markdown pages keeps its columns.

A ``|`` inside a cell (``|Δx|``) must be written ``\\|``: unescaped, it splits
the cell and the row gets more cells than its header, which GitHub and the
documentation (MyST, built on markdown-it-py) render by dropping the excess.
Tables are found with markdown-it-py (so pipes in code blocks do not count);
each source row is split into cells by the rule of GitHub-flavoured Markdown.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

markdown_it = pytest.importorskip("markdown_it")

ROOT = Path(__file__).resolve().parents[1]


def _pages() -> list[Path]:
    """The project's Markdown pages: the files git tracks (outside a git checkout, every page but build
    outputs and environments)."""
    try:
        listed = subprocess.run(["git", "ls-files", "*.md"], cwd=ROOT, capture_output=True, text=True, check=True)
        return sorted(ROOT / name for name in listed.stdout.split())
    except (OSError, subprocess.CalledProcessError):
        return sorted(p for p in ROOT.rglob("*.md") if not {"_build", ".git"} & set(p.relative_to(ROOT).parts)
                      and not any(part.startswith(".") or part.endswith("venv") for part in p.relative_to(ROOT).parts))


PAGES = _pages()


def cells(line: str) -> list[str]:
    """The cells of one source row of a pipe table: split at every pipe not escaped with a backslash."""
    row = line.strip()
    row = row[1:] if row.startswith("|") else row
    row = row[:-1] if row.endswith("|") and not row.endswith("\\|") else row
    return re.split(r"(?<!\\)\|", row)


def tables(text: str):
    """``(first line number, source lines, rendered body rows)`` of each table markdown-it-py finds."""
    md = markdown_it.MarkdownIt("commonmark").enable("table")
    tokens = md.parse(text)
    lines = text.splitlines()
    found = []
    for k, token in enumerate(tokens):
        if token.type == "table_open":
            start, end = token.map
            rendered = 0
            for t in tokens[k:]:
                if t.type == "table_close":
                    break
                rendered += t.type == "tr_open"
            found.append((start + 1, [ln for ln in lines[start:end] if ln.strip()], rendered))
    return found


def test_the_guard_sees_an_unescaped_pipe():
    """The rule the test applies: an unescaped |x| adds two cells, an escaped \\|x\\| none."""
    bad = "| a | b |\n|---|---|\n| 1 | |x| < 2 |\n"
    good = "| a | b |\n|---|---|\n| 1 | \\|x\\| < 2 |\n"
    (_, bad_lines, _), = tables(bad)
    (_, good_lines, _), = tables(good)
    assert len(cells(bad_lines[2])) == 4 and len(cells(good_lines[2])) == 2


def test_readme_is_checked():
    assert ROOT / "README.md" in PAGES and tables((ROOT / "README.md").read_text(encoding="utf-8"))


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(ROOT)) for p in PAGES])
def test_every_row_has_as_many_cells_as_its_header(page):
    for first, lines, rendered in tables(page.read_text(encoding="utf-8")):
        header = len(cells(lines[0]))
        assert rendered == len(lines) - 1, f"{page.name}:{first}: markdown-it-py renders {rendered} rows"
        for n, line in enumerate(lines[2:], start=first + 2):
            assert len(cells(line)) == header, (
                f"{page.name}:{n}: {len(cells(line))} cells under a header of {header} "
                f"(escape a | inside a cell as \\|): {line.strip()[:80]}"
            )


def test_the_readme_names_every_module_in_how_numkin_is_built():
    """The stage table of README's "How numkin is built" is written by hand: every module of the
    package (and every subpackage) must be named there, so that the map stays whole."""
    import re

    import numkin

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## How numkin is built", 1)[1].split("\n## ", 1)[0]
    named = set(re.findall(r"`(?:numkin\.)?([a-z_]+)(?:/|\.py)?`", section))
    package = Path(numkin.__file__).parent
    modules = {p.stem for p in package.glob("*.py") if not p.stem.startswith("_")}
    modules |= {p.name for p in package.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert sorted(modules - named) == []

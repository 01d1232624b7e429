"""Every scene file printed in the documentation runs as written.

The TOML examples of the scene schema (the docstring of ``numkin.scene``, which
is the documentation's "Scene files" page) and of README.md are written to files
and run through ``numkin run`` (and ``numkin report`` where they have a
``[report]`` section): each must exit with 0 and pass its check points. The
expected values the examples check were derived independently below.
"""

from __future__ import annotations

import math
import re
import textwrap
from pathlib import Path

import pytest

import numkin.scene
from numkin.cli import main

README = Path(__file__).resolve().parents[1] / "README.md"


def literal_blocks(doc: str) -> list[str]:
    """The reStructuredText literal blocks (after a line ending in ``::``) of a docstring."""
    lines = doc.splitlines()
    blocks, i = [], 0
    while i < len(lines):
        if not lines[i].rstrip().endswith("::"):
            i += 1
            continue
        j = i + 1
        while j < len(lines) and not lines[j].strip():
            j += 1
        k = j
        while k < len(lines) and (not lines[k].strip() or lines[k].startswith(" ")):
            k += 1
        blocks.append(textwrap.dedent("\n".join(lines[j:k])).strip() + "\n")
        i = k
    return blocks


def fenced_blocks(text: str, language: str) -> list[str]:
    """The fenced code blocks of a Markdown text in one language."""
    return re.findall(rf"^```{language}\n(.*?)^```", text, flags=re.S | re.M)


SCENE_DOC = [b for b in literal_blocks(numkin.scene.__doc__) if "[mechanism]" in b]
README_SCENES = fenced_blocks(README.read_text(encoding="utf-8"), "toml")
EXAMPLES = [(f"numkin.scene example {k + 1}", b) for k, b in enumerate(SCENE_DOC)] + [
    (f"README.md scene {k + 1}", b) for k, b in enumerate(README_SCENES)
]


def test_the_examples_are_found():
    """The schema and the loops example of numkin.scene, and README.md's small scene."""
    assert len(SCENE_DOC) == 2 and any("[[mechanism.loops]]" in b for b in SCENE_DOC)
    assert len(README_SCENES) >= 1


@pytest.mark.parametrize("where, text", EXAMPLES, ids=[name for name, _ in EXAMPLES])
def test_scene_example_runs_as_written(where, text, tmp_path, capsys):
    path = tmp_path / "example.toml"
    path.write_text(text, encoding="utf-8")
    code = main(["run", str(path), "--out", str(tmp_path / "out")])
    out, err = capsys.readouterr()
    assert code == 0, f"{where}: {err}"
    result = numkin.scene.run_scene(str(path))
    for check in result.checks:
        assert all(check.ok.values()), f"{where}: check at {check.at_deg} deg: {check.ok}"
    if "[report]" in text:
        code = main(["report", str(path)])
        assert code == 0, f"{where}: {capsys.readouterr().err}"


def four_bar_closed_form(ground, crank, coupler, rocker, theta2, omega2):
    """theta3, theta4 and omega4 (rad, rad/s) of the open branch (B left of the line A -> O4), by circle intersection."""
    ax, ay = crank * math.cos(theta2), crank * math.sin(theta2)
    dx, dy = ground - ax, -ay
    d = math.hypot(dx, dy)
    a = (coupler**2 - rocker**2 + d * d) / (2 * d)
    h = math.sqrt(coupler**2 - a * a)
    bx, by = ax + a * dx / d - h * dy / d, ay + a * dy / d + h * dx / d
    theta3 = math.atan2(by - ay, bx - ax)
    theta4 = math.atan2(by, bx - ground)
    # velocity loop: crank w2 sin(t2 - t3) = rocker w4 sin(t4 - t3)
    omega4 = omega2 * crank * math.sin(theta2 - theta3) / (rocker * math.sin(theta4 - theta3))
    return theta3, theta4, omega4


def test_the_examples_check_the_closed_form():
    """The values both numkin.scene examples check: the four-bar (4, 1, 3, 3) at 100 deg, 450 rad/min."""
    _, theta4, omega4 = four_bar_closed_form(4, 1, 3, 3, math.radians(100), 450 / 60)
    assert round(math.degrees(theta4), 3) == 122.343
    assert round(omega4, 4) == 2.3329
    for block in SCENE_DOC:
        assert re.search(r"^theta4_deg = 122\.343\b", block, flags=re.M)
        assert re.search(r"^omega_theta4 = 2\.3329\b", block, flags=re.M)

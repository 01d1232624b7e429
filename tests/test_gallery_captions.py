"""The gallery's captions say what their figures draw.

Every figure of every built-in scene is drawn as `numkin figures --all` draws it, and each
claim its caption (:func:`numkin.figures.caption`) makes is read back from the Figure:
legend labels, axis labels and scales, titles and the text on the axes. A source the figure
draws (the analytic solution, a scheme) must be named by the caption, and a thing the
caption names must be drawn.
"""

from __future__ import annotations

import re

import pytest

pytest.importorskip("matplotlib")
import matplotlib  # noqa: E402

matplotlib.use("Agg")

from numkin.figures import CAPTIONS, FIGURES, caption, dispatch  # noqa: E402
from numkin.figures.ends import END_LABEL  # noqa: E402
from numkin.figures.labels import sym  # noqa: E402
from numkin.schema import list_scenes  # noqa: E402
from numkin.scene import load_scene, render_figures, run_scene  # noqa: E402


@pytest.fixture(scope="module")
def gallery(tmp_path_factory):
    """(scene, file stem) -> Figure, for every figure of every built-in scene."""
    kept = {}
    with pytest.MonkeyPatch.context() as mp:
        for scene in list_scenes():
            mp.setattr(dispatch, "save", lambda fig, path, formats, scene=scene: kept.__setitem__((scene, path.name), fig) or [])
            render_figures(run_scene(load_scene(scene), figures=False), tmp_path_factory.mktemp(scene))
    assert len(kept) >= 10
    return kept


def legend_labels(fig) -> list[str]:
    return [t for ax in fig.axes for t in ax.get_legend_handles_labels()[1]]


def texts(fig) -> str:
    """Titles, axis labels, legend labels and the text drawn on the figure."""
    parts = [fig._suptitle.get_text() if fig._suptitle else ""]
    for ax in fig.axes:
        parts += [ax.get_title(), ax.get_xlabel(), ax.get_ylabel()]
    parts += legend_labels(fig)
    parts += [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    return "\n".join(parts)


def broken_claims(stem: str, text: str, fig) -> list[str]:
    """The claims of caption `text` about the figure of `stem` that the figure contradicts."""
    wrong = []
    labels = legend_labels(fig)
    everything = texts(fig)
    axis_labels = " ".join(ax.get_xlabel() + " " + ax.get_ylabel() for ax in fig.axes).lower()
    low = text.lower()

    def claim(ok, what):
        if not ok:
            wrong.append(what)

    # sources: named by the caption if and only if drawn
    drawn_analytic = "analytic" in labels
    claim(drawn_analytic == ("analytic" in low or "exact" in low), "analytic solution drawn <-> named")
    for scheme in ("forward", "centred", "second difference", "complex step"):
        if scheme in low:
            claim(any(lab.lower().startswith(scheme) for lab in labels)
                  or scheme in everything.lower(), f"{scheme} named but not drawn")
    ends = any(lab.endswith(END_LABEL) for lab in labels)
    if "on an open grid" in low:  # drawn where the sweep is not one periodic turn
        span = max(float(max(ln.get_xdata(), default=0)) - float(min(ln.get_xdata(), default=0))
                   for ax in fig.axes for ln in ax.get_lines())
        claim(ends == (span < 360 - 1e-9), "end stencils drawn <-> open grid")
    else:
        claim(("end stencil" in low) == ends, "end stencils drawn <-> named")
    low = low.replace("complex step", "")
    # what the axes show
    for word in ("error", "step", "residual", "work", "iteration"):
        if word in low:
            claim(word in axis_labels, f"'{word}' on no axis")
    if "log scale" in low or "log-log" in low:
        claim(any(ax.get_yscale() == "log" for ax in fig.axes), "no log axis")
    if "log-log" in low:
        claim(any(ax.get_xscale() == "log" and ax.get_yscale() == "log" for ax in fig.axes), "no log-log axes")
    if "formal order" in low:
        claim(labels and all(re.search(r"\(order \w+\)|spectral", lab) for lab in labels if "slope" not in lab),
              "formal orders not in the legend")
    claim(("observed" in low) == ("observed" in everything.lower()), "observed orders drawn <-> named")
    if "reference slopes 1, 2 and 4" in low:
        claim(all(f"slope {p}" in everything for p in (1, 2, 4)), "reference slopes missing")
    if "jacobian" in low:
        claim(len([lab for lab in labels if "Jacobian" in lab]) >= 2, "no curve per Jacobian")
    if "pareto" in low:
        claim(any("Pareto" in lab for lab in labels), "Pareto front not marked")
    if "velocity" in low and "acceleration" in low:
        claim(len(fig.axes) >= 3, "position, velocity and acceleration need three panels")
    if "twin axes" in low:
        claim(len(fig.axes) == 2 and fig.axes[0].bbox.bounds == fig.axes[1].bbox.bounds, "no twin axes")
    # which unknown, which angle
    kind = next(k for k in sorted(FIGURES, key=len, reverse=True) if stem == k or stem.startswith(k + "-"))
    arg = stem[len(kind) + 1:]
    if arg and kind != "mechanism":
        claim(sym(arg) in text and sym(arg)[1:-1] in everything, f"unknown {arg} not named by both")
    if kind == "position":
        ys = " ".join(ax.get_ylabel() for ax in fig.axes)
        shown = sum(len(ax.get_lines()) for ax in fig.axes)
        if "the unknowns" in low:
            claim(shown >= 2, "one unknown drawn, the caption says the unknowns")
        else:
            claim(shown == 1 and sym(arg) in ys, "the caption's unknown is not the one drawn")
    if kind == "mechanism" and arg:
        claim(f"{arg.removesuffix('deg')}°" in fig.axes[0].get_title(), "drawn at another angle")
    return wrong


def test_every_figure_name_has_a_caption():
    assert set(CAPTIONS) == set(FIGURES)
    with pytest.raises(ValueError, match="no figure of that name"):
        caption("histogram")


def test_captions_say_what_the_figures_draw(gallery):
    problems = {f"{scene}/{stem}": broken_claims(stem, caption(stem), fig)
                for (scene, stem), fig in gallery.items()}
    assert not {k: v for k, v in problems.items() if v}


@pytest.mark.parametrize("stem, old", [
    ("derivative-phi", "First derivative by finite differences beside the exact one"),
    ("convergence", "Error against grid step for every scheme, with the observed orders"),
    ("newton", "Newton's residual and step per iteration, three Jacobians"),
    ("position-phi", "Position of each unknown over the sweep of the input"),
])
def test_a_caption_the_figure_contradicts_is_caught(gallery, stem, old):
    fig = next(f for (_, s), f in gallery.items() if s == stem)
    assert broken_claims(stem, old, fig)

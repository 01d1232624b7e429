"""The figure style, the colours of the derivative sources, and deterministic saving.

Every numkin figure is drawn inside :func:`style` (matplotlib's defaults plus
``numkin/numkin.mplstyle``), on a :class:`~matplotlib.figure.Figure` with an
Agg canvas that pyplot does not know (:func:`new_figure`), and written by
:func:`save` with no date or version in the files, so regenerating a figure
gives the same bytes. :func:`save` lays the figure out once, at the saving
resolution (again when a title had to be broken into lines to fit the
figure, :mod:`~numkin.figures.fitting`), and draws each format once from
that layout.

Examples
--------
>>> from numkin.figures.style import source_style
>>> source_style("forward", 0)["color"]
'#D55E00'
"""

from __future__ import annotations

import os
import re
import sys
from contextlib import contextmanager
from pathlib import Path
from typing import Sequence

from ..errors import InputError
from ..folders import made_folder
from .registries import family_of

__all__ = [
    "DOC_PARTS",
    "shared_doc",
    "CYCLE", "METADATA", "SAVE_OPTIONS", "SOURCE_CYCLE", "SOURCE_MARKERS", "SOURCE_STYLE", "STYLE", "close", "gc_paused", "new_figure", "save", "source_label",
    "marker_style", "source_style", "style",
]

#: The package style file.
STYLE = Path(__file__).resolve().parent.parent / "numkin.mplstyle"

#: Metadata written into each format: nothing that changes between runs or versions.
METADATA = {
    "png": {"Software": None},
    "svg": {"Date": None, "Creator": None},
    "pdf": {"CreationDate": None, "ModDate": None, "Producer": None, "Creator": None},
}

#: Fixed colours and line styles of the derivative sources (others take the colour cycle).
#: Schemes that can give the same numbers (forward and backward on a symmetric curve,
#: five-point and Richardson) have dash patterns that interleave, so both stay visible.
SOURCE_STYLE = {
    "analytic": {"color": "black", "linestyle": "-", "linewidth": 1.0, "zorder": 4},
    "forward": {"color": "#D55E00", "linestyle": (0, (5, 5)), "linewidth": 1.8},
    "backward": {"color": "#CC79A7", "linestyle": (5, (5, 5)), "linewidth": 1.8},
    "centred": {"color": "#0072B2", "linestyle": "-", "linewidth": 2.6, "alpha": 0.55, "zorder": 1.9},
    "five_point": {"color": "#009E73", "linestyle": (0, (1.2, 1.8)), "linewidth": 2.4},
    "richardson": {"color": "#E69F00", "linestyle": (0, (6, 4)), "linewidth": 1.4},
    "spectral": {"color": "#56B4E9", "linestyle": "-.", "linewidth": 1.6},
    # a second derivative of the centred family, drawn beside the second difference: a colour of its own
    "centred_of_centred": {"color": "#1B3A6B", "linestyle": (0, (7, 2, 1.5, 2)), "linewidth": 1.6},
}

#: Markers of the sources on the error figures: (marker, size, filled). Sources that give the
#: same points (forward and backward, five-point and Richardson: the same errors on the same
#: grids) stay visible one over the other: a large open marker around a small filled one.
SOURCE_MARKERS = {
    "analytic": ("o", 4.0, True), "complex step": ("s", 8.0, False), "complex_step": ("s", 8.0, False),
    "forward": ("^", 8.5, False), "backward": ("v", 4.5, True), "centred": ("o", 4.5, True),
    "five_point": ("D", 8.0, False), "richardson": ("o", 3.5, True), "spectral": ("*", 7.0, True),
    "second_difference": ("o", 4.5, True), "forward_of_forward": ("^", 5.5, True),
    "centred_of_centred": ("s", 8.0, False), "five_point_second": ("D", 8.0, False),
    "spectral_second": ("*", 7.0, True),
}

#: Colour cycle of curves without a fixed style (unknowns, links, Jacobians).
CYCLE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]

#: Colours of sources without a fixed style (a registered scheme): none of :data:`SOURCE_STYLE`'s, so
#: that a scheme is never drawn in the colour of another (Paul Tol's muted palette).
SOURCE_CYCLE = ["#882255", "#44AA99", "#999933", "#AA4499", "#332288", "#DDCC77"]

#: Further savefig arguments per format. PNG: zlib level 1 (lossless like every level; about a third
#: faster to write than the default 6, the files about a tenth larger).
SAVE_OPTIONS = {"png": {"pil_kwargs": {"compress_level": 1}}}


@contextmanager
def style():
    """Context in which numkin draws and saves: matplotlib's defaults plus :data:`STYLE`.

    Examples
    --------
    >>> import matplotlib
    >>> from numkin.figures import style
    >>> with style():
    ...     matplotlib.rcParams["svg.hashsalt"]
    'numkin'
    """
    import matplotlib.style

    with matplotlib.style.context(str(STYLE), after_reset=True):
        yield


@contextmanager
def gc_paused():
    """Context without automatic cyclic garbage collection (the state before it is restored after).

    A figure allocates some hundred thousand objects that all stay alive until it is saved and
    closed; meanwhile each collection triggered by those allocations scans them again and frees
    nothing. Reference counting still frees everything without cycles at once.

    Examples
    --------
    >>> import gc
    >>> with gc_paused():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True
    """
    import gc

    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()


def new_figure(nrows=1, ncols=1, *, size=None, sharex=False, height_ratios=None):
    """A Figure with an Agg canvas (not known to pyplot) and a grid of axes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    gridspec = {"height_ratios": height_ratios} if height_ratios else None
    axes = fig.subplots(nrows, ncols, sharex=sharex, squeeze=False, gridspec_kw=gridspec)
    return fig, axes


def close(fig) -> None:
    """Release a figure (only pyplot keeps figures; numkin's are not registered with it)."""
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close(fig)


#: rcParams under which a figure gets no layout engine (savefig gives a figure back the engine these
#: name when it puts back the "no engine" it found, and a figure with an engine is drawn twice).
_NO_LAYOUT = {"figure.autolayout": False, "figure.constrained_layout.use": False}


def _lay_out(fig, dpi: float) -> None:
    """Run the figure's layout engine at `dpi`, fit the titles (:func:`~numkin.figures.fitting.fit_titles`),
    then keep the axes there: no layout engine from now on.

    ``set_layout_engine("none")`` would leave a placeholder engine, and savefig draws a figure
    that has any engine once more before printing it (a pass that measures every text again).
    """
    import matplotlib

    from .fitting import fit_titles

    engine = fig.get_layout_engine()
    if fig.axes:
        before = fig.dpi
        fig.set_dpi(dpi)
        try:
            if engine is None:  # axes that stay where they are: a title too wide is only set smaller
                fit_titles(fig, relayout=False)
            else:
                engine.execute(fig)
                # the engine leaves titles' widths out: one that runs off the figure is fitted, then made room for
                for _ in range(2):
                    if not fit_titles(fig):
                        break
                    engine.execute(fig)
        finally:
            fig.set_dpi(before)
    if engine is None:
        return
    with matplotlib.rc_context(_NO_LAYOUT):
        fig.set_layout_engine(None)


def save(fig, path_stem, formats: Sequence[str] = ("png", "svg")) -> list[Path]:
    """Save a figure in each format, deterministically, and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path_stem : str or Path
        Path without the extension; ``".png"``, ``".svg"`` (or ``".pdf"``)
        is appended. Missing folders are created.
    formats : sequence of {"png", "svg", "pdf"}

    Returns
    -------
    list of Path
        The files written, in the order of `formats`.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages, figures
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    >>> [p.name for p in figures.save(figures.position(sweep, ["x"]), "/tmp/numkin-doc-x", ["png"])]
    ['numkin-doc-x.png']
    """
    import matplotlib

    from .arguments import got, need_figure, need_names

    need_figure(fig, "save")
    if not isinstance(path_stem, (str, os.PathLike)) or not str(os.fspath(path_stem)).strip():
        raise InputError(f"save: path_stem must be a file path without its extension (str or Path), "
                         f"got {got(path_stem)}")
    path_stem = os.fspath(path_stem)
    formats = need_names(formats, "formats", "save")
    if isinstance(formats, str):
        formats = (formats,)
    fmts = [str(f).lower().lstrip(".") for f in formats]
    try:
        bad = [f for f in fmts if f not in METADATA]
        if bad or not fmts:
            raise InputError(
                f"formats: {bad[0] if bad else 'nothing'!r} is not a figure format numkin writes; "
                f"choose from {sorted(METADATA)}"
            )
        stem = Path(path_stem)
        made_folder(stem.parent, "path_stem")
        # One layout for every format, computed once at the saving resolution, then frozen: savefig
        # draws a figure that has no layout engine once (a figure with one is drawn twice, once to lay
        # it out), and the PNG is drawn with the renderer the layout measured its text with.
        paths = []
        with style():
            _lay_out(fig, matplotlib.rcParams["savefig.dpi"])
            with matplotlib.rc_context(_NO_LAYOUT):
                for fmt in fmts:
                    path = stem.with_name(f"{stem.name}.{fmt}")
                    fig.savefig(path, format=fmt, metadata=METADATA[fmt], **SAVE_OPTIONS.get(fmt, {}))
                    paths.append(path)
        return paths
    finally:
        close(fig)



#: Docstring parts the figure functions share: a line ``{{name}}`` in a docstring
#: decorated with :func:`shared_doc` becomes the part, at that line's indentation.
DOC_PARTS = {
    "uniform_sweep_name": "sweep : Sweep\n    On a uniform grid.\nname : str\n    The unknown.",
    "returns_figure": "Returns\n-------\nmatplotlib.figure.Figure",
    "example_figures": "Examples\n--------\n>>> import numpy as np\n>>> from numkin import linkages, figures",
    "example_tables": "Examples\n--------\n>>> import math\n>>> from numkin import linkages, report, figures",
}
DOC_PARTS["example_homework"] = (
    DOC_PARTS["example_figures"] + "\n>>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))"
)


def shared_doc(fn):
    """Fill the shared parts (:data:`DOC_PARTS`) into `fn`'s docstring; returns `fn`.

    Examples
    --------
    >>> def f():
    ...     '''A figure.
    ...
    ...     {{returns_figure}}
    ...     '''
    >>> shared_doc(f).__doc__.split()[-3:]
    ['Returns', '-------', 'matplotlib.figure.Figure']
    """

    def part(m):
        indent, key = m.group(1), m.group(2)
        return "\n".join(indent + line if line else "" for line in DOC_PARTS[key].splitlines())

    if fn.__doc__:
        fn.__doc__ = re.sub(r"^([ \t]*)\{\{(\w+)\}\}$", part, fn.__doc__, flags=re.M)
    return fn


def source_label(key: str) -> str:
    """Legend text of a source: ``"five_point"`` -> ``"five point"``."""
    return str(key).replace("_", " ")


def source_style(key: str, k: int) -> dict:
    """Line style of a source (colour of its family for second-derivative schemes); else colour `k` of
    :data:`SOURCE_CYCLE`, none of the fixed ones.

    Examples
    --------
    >>> source_style("forward_of_forward", 0)["color"] == source_style("forward", 3)["color"]
    True
    >>> {source_style("seven_point", k)["color"] for k in range(6)} & {s["color"] for s in SOURCE_STYLE.values()}
    set()
    """
    key = str(key)
    style_ = SOURCE_STYLE.get(key) or SOURCE_STYLE.get(family_of(key))
    if key in ("complex_step", "complex step"):
        style_ = {"color": "0.45", "linestyle": "-", "linewidth": 1.2}
    if style_ is None:
        style_ = {"color": SOURCE_CYCLE[k % len(SOURCE_CYCLE)], "linestyle": "-.", "linewidth": 1.5}
    style_ = dict(style_)
    if key != family_of(key) and key not in ("complex_step", "complex step"):
        style_["linestyle"] = (0, (7, 2, 1.5, 2)) if key != "second_difference" else style_["linestyle"]
    return style_


def marker_style(key: str, color) -> dict:
    """Keyword arguments of ``plot`` that draw a source's marker (:data:`SOURCE_MARKERS`) in `color`."""
    marker, size, filled = SOURCE_MARKERS.get(str(key), ("o", 4.5, True))
    return {"marker": marker, "markersize": size, "markerfacecolor": color if filled else "none",
            "markeredgecolor": color, "markeredgewidth": 1.0}

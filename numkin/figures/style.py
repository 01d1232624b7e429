"""The figure style, the colours and markers of the derivative sources, and deterministic saving.

Every numkin figure is drawn inside :func:`style` (matplotlib's defaults plus
``numkin/numkin.mplstyle``), on a :class:`~matplotlib.figure.Figure` with an
Agg canvas that pyplot does not know (:func:`new_figure`), and written by
:func:`save` with no date or version in the files, so regenerating a figure
gives the same bytes. :func:`save` lays the figure out once, at the saving
resolution (again when a title had to be broken into lines to fit the
figure, :mod:`~numkin.figures.fitting`), and draws each format once from
that layout.

A scheme's colour, line style and marker are declared on the scheme
(:mod:`numkin.schemes`); :func:`source_style` and :func:`marker_style` derive
those of a scheme that declares none, so a scheme registered at run time is
drawn without a change here.

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
from ..schemes import REGISTRY, RegistryView, by_label

__all__ = [
    "DOC_PARTS",
    "shared_doc",
    "ANALYTIC_STYLE", "CYCLE", "METADATA", "SAVE_OPTIONS", "SECOND_DASH", "SOURCE_CYCLE", "SOURCE_MARKERS",
    "SOURCE_STYLE", "STYLE", "close", "gc_paused", "new_figure", "save", "source_label", "marker_style",
    "source_style", "style",
]

#: The package style file.
STYLE = Path(__file__).resolve().parent.parent / "numkin.mplstyle"

#: Metadata written into each format: nothing that changes between runs or versions.
METADATA = {
    "png": {"Software": None},
    "svg": {"Date": None, "Creator": None},
    "pdf": {"CreationDate": None, "ModDate": None, "Producer": None, "Creator": None},
}

#: Line style of the analytic solution, the reference every scheme is drawn against.
ANALYTIC_STYLE = {"color": "black", "linestyle": "-", "linewidth": 1.0, "zorder": 4}
#: Marker of the analytic solution, and of a source that declares none: (marker, size, filled).
_ANALYTIC_MARKER, _MARKER = ("o", 4.0, True), ("o", 4.5, True)
#: Dash pattern of the second-derivative schemes (unless a scheme's style names its own line style).
SECOND_DASH = (0, (7, 2, 1.5, 2))

#: Colour cycle of curves without a fixed style (unknowns, links, Jacobians).
CYCLE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]

#: Colours of sources without a fixed style (a registered scheme): none of :data:`SOURCE_STYLE`'s, so
#: that a scheme is never drawn in the colour of another (Paul Tol's muted palette); with the line
#: style ``"-."`` and width 1.5.
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


def _partner_of_family(scheme):
    """The scheme's family (a first-derivative scheme) if the scheme is that family's partner, else None."""
    family = REGISTRY.get(scheme.family)
    return family if family is not None and family is not scheme and family.partner == scheme.name else None


def _own_style(scheme, k: int) -> dict:
    """The style a scheme declares; on colour `k` of :data:`SOURCE_CYCLE` if it names no colour."""
    own = dict(scheme.style)
    if "color" in own:
        return own
    return {"color": SOURCE_CYCLE[k % len(SOURCE_CYCLE)], "linestyle": "-.", "linewidth": 1.5, **own}


def source_style(key: str, k: int) -> dict:
    """Line style of a source: a scheme (by name or table label), ``"analytic"`` or any other curve.

    A scheme whose style (``style`` of :class:`numkin.schemes.Scheme`) names a colour is drawn in it; a
    second-derivative scheme that is its family's partner (the second difference of the centred
    family) in its family's; any other in colour `k` of :data:`SOURCE_CYCLE`, none of the fixed
    ones. A second-derivative scheme takes the dash :data:`SECOND_DASH`; then the keys its style
    gives apply. Other sources than schemes also take colour `k` of the cycle.

    Examples
    --------
    >>> source_style("forward_of_forward", 0)["color"] == source_style("forward", 3)["color"]
    True
    >>> {source_style("seven_point", k)["color"] for k in range(6)} & {s["color"] for s in SOURCE_STYLE.values()}
    set()
    """
    key = str(key)
    scheme = by_label(key)
    if scheme is None:
        return dict(ANALYTIC_STYLE) if key == "analytic" else {
            "color": SOURCE_CYCLE[k % len(SOURCE_CYCLE)], "linestyle": "-.", "linewidth": 1.5}
    own = dict(scheme.style)
    family = None if "color" in own else _partner_of_family(scheme)
    style_ = _own_style(family or scheme, k)
    if scheme.derivative == 2:
        style_["linestyle"] = SECOND_DASH
    style_.update(own)
    return {**{name: style_[name] for name in ("color", "linestyle", "linewidth") if name in style_}, **style_}


def _marker(scheme) -> tuple:
    """(marker, size, filled) of a scheme: its own, else its family's if it is the family's partner."""
    family = _partner_of_family(scheme)
    return scheme.marker or (family.marker if family is not None else ()) or _MARKER


#: The fixed styles: the analytic solution's and each scheme's whose style names a colour, always current.
SOURCE_STYLE = RegistryView(lambda s: "color" in dict(s.style), lambda s: source_style(s.name, 0),
                            fixed={"analytic": ANALYTIC_STYLE})
#: Markers of the sources on the error figures, (marker, size, filled): the analytic solution's and each
#: scheme's (:func:`marker_style`), always current.
SOURCE_MARKERS = RegistryView(lambda s: True, _marker, fixed={"analytic": _ANALYTIC_MARKER})


def marker_style(key: str, color) -> dict:
    """Keyword arguments of ``plot`` that draw a source's marker (:data:`SOURCE_MARKERS`) in `color`.

    A scheme's marker is its own (``marker`` of :class:`numkin.schemes.Scheme`), else its family's if it is the
    family's partner; a source without one has a small filled circle.

    Examples
    --------
    >>> marker_style("complex step", "k")["marker"], marker_style("second_difference", "k")["marker"]
    ('s', 'o')
    """
    key = str(key)
    scheme = by_label(key)
    marker, size, filled = _ANALYTIC_MARKER if key == "analytic" else _marker(scheme) if scheme else _MARKER
    return {"marker": marker, "markersize": size, "markerfacecolor": color if filled else "none",
            "markeredgecolor": color, "markeredgewidth": 1.0}

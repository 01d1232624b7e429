"""Which plotted values of a finite difference come from its end stencils on an open grid.

On an open grid (0..180°, say) a scheme's interior stencil reaches past the
data at the first and last points; :mod:`numkin.derivatives` uses one-sided
stencils there. A figure that draws such an estimate names them apart: the
curve labelled with the scheme holds the interior points only, and the end
values are drawn as markers labelled :data:`END_LABEL`.
"""

from __future__ import annotations

from typing import Iterable

import numpy as np

__all__ = ["END_LABEL", "end_mask", "frame_ends", "scheme_reach"]

#: What a value at the ends of an open grid was computed with.
END_LABEL = "one-sided end stencil"


def scheme_reach(names: Iterable[str]) -> tuple[int, int]:
    """Points at the start and at the end of an open grid that the interior stencils cannot reach.

    The largest backward and forward offsets of the schemes' interior
    stencils (``centred``: one each side; ``forward``: none before, one after;
    ``richardson``: two each side); the FFT schemes (periodic grids only)
    reach none.

    Examples
    --------
    >>> scheme_reach(["second_difference"]), scheme_reach(["forward"]), scheme_reach(["richardson"])
    ((1, 1), (0, 1), (2, 2))
    """
    from ..schemes import get_scheme, own_stencil_points

    own = own_stencil_points([get_scheme(name) for name in names], 0, periodic=False)
    return own.start, -own.stop


def frame_ends(key: str, frame, derivative: int) -> tuple[int, int]:
    """:func:`scheme_reach` of the schemes behind one column of a finite-difference frame.

    Parameters
    ----------
    key : str
        The frame's name in a figure (a scheme name when the frame holds one
        scheme's estimates, as from :func:`numkin.compare.compare`).
    frame : DataFrame
        From :func:`numkin.kinematics.finite_difference` (its ``attrs`` give
        the schemes and whether the grid was periodic) or a scheme's
        compared values with ``attrs["periodic"]``.
    derivative : int
        1 for a velocity column, 2 for an acceleration column.

    Returns
    -------
    tuple of int
        ``(0, 0)`` on a periodic grid or when the frame does not say how it
        was computed; in the frame's row order (a descending sweep's first
        rows are the grid's last, ``attrs["descending"]``).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> from numkin.kinematics import finite_difference
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    >>> frame_ends("fd", finite_difference(sweep, "6000 rpm"), 2)
    (1, 1)
    >>> turn = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 361)))  # one turn: periodic
    >>> frame_ends("fd", finite_difference(turn, "6000 rpm"), 2)
    (0, 0)
    """
    attrs = dict(getattr(frame, "attrs", None) or {})
    periodic = attrs.get("periodic")
    if periodic is None or bool(periodic):
        return 0, 0
    if "method" in attrs and "second_method" in attrs:
        names = [attrs["method"]] if derivative == 1 else [attrs["second_method"]]
        if derivative == 2 and np.any(np.asarray(attrs.get("alpha", 0.0), dtype=float) != 0):
            names.append(attrs["method"])  # alpha_q = omega**2 D2(q) + alpha D1(q)
    else:
        names = [key]
    try:
        before, after = scheme_reach(names)
    except (KeyError, ValueError):
        return 0, 0
    return (after, before) if attrs.get("descending") else (before, after)


def end_mask(n: int, ends: tuple[int, int]) -> np.ndarray:
    """Boolean mask of the `n` points of a grid that lie within `ends` of its first and last point.

    Examples
    --------
    >>> end_mask(6, (1, 2)).tolist()
    [True, False, False, False, True, True]
    """
    mask = np.zeros(n, dtype=bool)
    before, after = ends
    mask[: min(before, n)] = True
    if after:
        mask[max(n - after, 0):] = True
    return mask

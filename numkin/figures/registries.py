"""What figures know about schemes and linkages.

:data:`SCHEME_FAMILY` maps a second-derivative scheme to the first-derivative
scheme it belongs with, read from :data:`numkin.schemes.FAMILY`; it agrees
with :data:`numkin.kinematics.PARTNER`. How a scheme is drawn is read from
the scheme itself (:func:`numkin.figures.style.source_style`). The dimension
lines drawn on a ready-made linkage are its spec's (:func:`dimensions_of`,
from :func:`numkin.linkages.spec_of`).

Examples
--------
>>> from numkin.kinematics import PARTNER
>>> all(SCHEME_FAMILY[second] == first for second, first in PARTNER.items())
True
"""

from __future__ import annotations

from collections.abc import Mapping

from ..schemes import RegistryView, by_label

__all__ = ["SCHEME_FAMILY", "dimensions_of", "family_of", "is_second_derivative"]


#: Second-derivative scheme -> its family (:data:`numkin.schemes.FAMILY`), always current.
SCHEME_FAMILY: Mapping = RegistryView(lambda s: s.derivative == 2, lambda s: s.family)


def is_second_derivative(source: str) -> bool:
    """Whether a source (a registry name or a table's label) is a second-derivative scheme.

    Examples
    --------
    >>> is_second_derivative("five_point_second"), is_second_derivative("centred"), is_second_derivative("analytic")
    (True, False, False)
    """
    scheme = by_label(source)
    return scheme is not None and scheme.derivative == 2


def family_of(source: str) -> str:
    """The family of a source (a registry name or a table's label): the first-derivative scheme it
    belongs with; the source itself if it is no scheme.

    Examples
    --------
    >>> family_of("forward_of_forward"), family_of("centred"), family_of("complex step"), family_of("analytic")
    ('forward', 'centred', 'complex_step', 'analytic')
    """
    scheme = by_label(source)
    return scheme.family if scheme is not None else str(source)


def dimensions_of(mechanism):
    """The dimension lines of a ready-made linkage, or None (then each link is labelled with its length).

    Read from the linkage's spec (``LinkageSpec.dimension_lines``:
    from point, to point, symbol, side and size of the offset); None for a
    mechanism written as loops, or a linkage whose spec has no dimension lines.

    Examples
    --------
    >>> from numkin import linkages
    >>> [d[2] for d in dimensions_of(linkages.quick_return())][:2]
    ['r_1', 'r_6']
    >>> dimensions_of(linkages.four_bar(4, 1, 3, 3)) is None
    True
    """
    from ..linkages import spec_of

    linkage_spec = spec_of(mechanism)
    lines = linkage_spec.dimension_lines if linkage_spec is not None else ()
    return [tuple(line) for line in lines] or None

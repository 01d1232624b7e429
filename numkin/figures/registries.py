"""What figures know about schemes and linkages: the two tables to read from registries later.

:data:`SCHEME_FAMILY` maps a second-derivative scheme to the first-derivative
scheme it is drawn like (same colour); it agrees with
:data:`numkin.kinematics.PARTNER`. :data:`LINKAGE_DIMENSIONS` holds the
dimension lines drawn on the ready-made linkages, by name prefix.

Examples
--------
>>> from numkin.kinematics import PARTNER
>>> all(SCHEME_FAMILY[second] == first for second, first in PARTNER.items())
True
"""

from __future__ import annotations

__all__ = ["LINKAGE_DIMENSIONS", "SCHEME_FAMILY", "dimensions_of", "family_of"]


#: Dimension lines drawn on the ready-made linkages, by the start of the mechanism's name:
#: (from point, to point, symbol, side and size of the offset).
LINKAGE_DIMENSIONS = {
    "quick-return": [
        ("O1", "O2", "r_1", 1.0), ("O2", "C", "r_6", 1.0), ("O2", "A", "r_2", 1.0),
        ("O1", "A", "r_3", -1.0), ("O1", "B", "r_4", -2.2), ("C", "B", "r_5", 1.0),
    ],
}

#: Second-derivative scheme (or complex step) -> the source it is coloured like: its partner
#: first-derivative scheme of :data:`numkin.kinematics.PARTNER`.
SCHEME_FAMILY = {
    "second_difference": "centred", "forward_of_forward": "forward", "centred_of_centred": "centred",
    "five_point_second": "five_point", "spectral_second": "spectral", "complex_step": "analytic",
    "complex step": "analytic",
}


def family_of(source: str) -> str:
    """The first-derivative scheme (or ``"analytic"``) a source is drawn like; itself if none.

    Examples
    --------
    >>> family_of("forward_of_forward"), family_of("centred")
    ('forward', 'centred')
    """
    return SCHEME_FAMILY.get(str(source), str(source))


def dimensions_of(mechanism_name: str):
    """The dimension lines of a ready-made linkage (see :data:`LINKAGE_DIMENSIONS`), or None.

    Examples
    --------
    >>> [d[2] for d in dimensions_of("quick-return (Example 2)")][:2]
    ['r_1', 'r_6']
    >>> dimensions_of("four-bar") is None
    True
    """
    return next((v for key, v in LINKAGE_DIMENSIONS.items() if str(mechanism_name).startswith(key)), None)

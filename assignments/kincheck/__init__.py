"""Feedback checks for the numkin homework.

Every homework folder ships this package (the folder ``kincheck/``) next to its
notebook, and the autograder tests (``grader.check("q2")`` in the notebook,
``otter run`` for grading) call it.  It holds no answers: the hidden tests pass
in the reference values, which ``python assignments/build.py expected`` computes
with numkin.

Each check either returns quietly or raises ``AssertionError`` with a message
that says what looks off: a unit (degrees where radians are asked, rad/min
where rad/s is asked, rpm, rev/s, mm), a sign, the forward difference where the
centred one is asked, a Newton iteration stopped too early, a branch jump.

Arrays are sampled on a grid of input angles in degrees, for example
``grid=(0, 360, 1)`` for θ = 0°, 1°, …, 360°.  Reference values are given as
``{angle in degrees: value}`` and compared at those angles only, so that the
end points (where students pick their own one-sided formulas) do not matter.

The checks are used as ``import kincheck as kc``; every name below is one of
its modules', re-exported here:

* ``reading`` — what the student handed in: names not set yet or not defined,
  functions not written yet, text, numbers, arrays on the grid, angles in radians or degrees;
* ``compare`` — one value, an angle, a series, a band, a list against the
  reference values, with feedback;
* ``diagnose`` — what makes a number wrong: a unit factor, a flipped sign, a
  missing division by the step, rounding, single precision;
* ``loops`` — the linkages' own checks: loop closure, assembly, continuity,
  angles whose unit the loop decides.
"""

from __future__ import annotations

from .compare import (
    ALTERNATIVE_CLOSER,
    NEWTON_HINT,
    angle_value,
    band,
    listed,
    matches_alternative,
    own_difference,
    series,
    value,
)
from .diagnose import (
    FLIPPED,
    ROTATION,
    SINGLE,
    SUSPECTS,
    agrees_as_written,
    as_written,
    explain_factor,
)
from .loops import (
    chained_four_bar_angles,
    chained_four_bar_assembly,
    closure,
    continuity,
    four_bar_gap,
    four_bar_side,
    inputs_in_degrees,
    quick_return_input_unit,
    read_angle_group,
    read_angles,
    six_bar_gap,
)
from .reading import FULL_TURN, angles, array, at, floats, returned, rows, text, unit_of

# FULL_TURN, NEWTON_HINT and SINGLE are kincheck's attributes too, as they always were, not in __all__
__all__ = [
    "ALTERNATIVE_CLOSER",
    "FLIPPED",
    "ROTATION",
    "SUSPECTS",
    "angles",
    "angle_value",
    "array",
    "floats",
    "text",
    "agrees_as_written",
    "as_written",
    "at",
    "band",
    "closure",
    "continuity",
    "chained_four_bar_angles",
    "chained_four_bar_assembly",
    "four_bar_side",
    "four_bar_gap",
    "own_difference",
    "inputs_in_degrees",
    "quick_return_input_unit",
    "listed",
    "read_angle_group",
    "returned",
    "rows",
    "read_angles",
    "six_bar_gap",
    "explain_factor",
    "matches_alternative",
    "series",
    "unit_of",
    "value",
]

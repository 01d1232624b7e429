"""Scenes: one kinematics problem declared in a TOML file.

This module is the scene's public face; the work is done by one module per
job: :mod:`numkin.schema` reads and validates a file into a :class:`Scene`,
:mod:`numkin.assemble` builds its mechanism, :mod:`numkin.pipeline` runs it
(:func:`run_scene`) and :mod:`numkin.outputs` builds and writes its tables.

A scene names the mechanism, the input motion, what to compute, which
finite-difference schemes to compare, the check points and the tables and
figures wanted. :func:`load_scene` reads and validates it (built-in name or
path), :func:`run_scene` computes exactly what it asks for and nothing more:
a position-only scene never differentiates (nothing of ``numkin.analytic``,
``numkin.kinematics`` or ``numkin.compare`` is called, and the acceleration
equations are never derived), and a scene that asks for no figure never
imports matplotlib.

Degrees appear only at the edge and are labelled in the key names
(``start_deg``, ``theta3_deg``); everything inside is in radians.

Scene file
----------
All sections but ``[scene]`` and one of ``[mechanism]`` / ``[stability]``
are optional. ::

    [scene]
    description = "one line, shown by `numkin scenes`"    # required
    title = "heading printed by `numkin run`"              # optional

    [mechanism]
    linkage = "four_bar"     # a ready-made linkage (table below) ...
    unit = "mm"              # working length unit: mm, cm, m, km, in, ft (default mm)
    # branch = "open"        # four_bar only: "open" or "crossed" (or a [guess], not both)
    [mechanism.dimensions]   # numbers in `unit`, or strings with their own unit
    ground = 4               # ("80 mm"); angles as <name>_deg
    crank = 1
    coupler = 3
    rocker = 3
    [mechanism.quantities]   # optional derived quantities, reported like the unknowns
    mu = { expression = "theta4 - theta3", dimension = "angle" }   # the transmission angle

    [input]
    speed = "450 rad/min"    # needed for velocity/acceleration: rad/s, rad/min, rpm,
                             # rev/s, deg/s (a bare number is rad/s); sign = direction
    acceleration = "0 rad/s^2"   # optional input angular acceleration (numkin run; the
                                 # report's tables study the schemes at constant speed)
    start_deg = 0            # sweep of the input, inclusive, uniform step
    stop_deg = 360
    step_deg = 1
    on_singular = "raise"    # at a change point: "raise" (default), or "report" it and go on
                             # along the branch whose tangent is continuous (a toggle always raises)

    [guess]                  # values at start_deg: picks the assembly branch;
    theta3_deg = 30          # all unknowns (angles as <name>_deg, lengths in `unit`);
    theta4_deg = 120         # optional for ready-made linkages

    [output]
    quantities = ["position", "velocity", "acceleration"]   # default ["position"]
    unknowns = ["theta4"]    # which unknowns to report (default all)
    points = ["B"]           # named points whose x, y (vx, vy, ax, ay) are wanted
    tables = ["positions", "kinematics", "points", "comparison", "summary", "checks"]
    table_formats = ["csv"]  # csv, md, tex
    figures = ["kinematics:theta4"]   # numkin.figures.FIGURES names, ":<unknown or derived quantity>" (default none)

    [compare]                # finite differences against the analytic solution, for the
                             # unknowns' rates (numkin.compare.compare takes a point's too)
    schemes = ["forward", "centred"]            # first derivative -> velocity
    second_schemes = ["second_difference"]      # second derivative -> acceleration

    [[check]]                # a check point; expected values are optional
    at_deg = 100
    theta4_deg = 122.343     # agrees to the last digit written (122.340: 5e-4; 1.50e2: 0.5), or give
    omega_theta4 = 2.3329    # [rad/s]
    tolerance = 1e-3         # an absolute tolerance

    [report]                 # settings of the error-analysis tables (numkin.report; without
                             # [input] speed they are per rad/s of input speed):
    quantity = "theta4"      # the unknown or derived quantity studied (default: the first reported)
    check_deg = 100          # check angle (default: the first [[check]])
    grids = [36, 72, 180, 360]   # points per turn of the convergence tables (distinct, <= 100000;
                                 # by default 36 ... 3600, those too coarse for a part of a turn left out)
    schemes = ["forward", "centred"]   # default: all
    points_per_turn = 360    # grid of the Jacobian and tolerance tables (<= 100000)
    repeat = 3               # timing repeats

    [animation]              # defaults of `numkin animate`'s options (all optional)
    frames = 72              # frame count
    fps = 24                 # frames per second
    dpi = 80                 # dots per inch, 10 to 600: the GIF is width * dpi pixels wide
    width = 5.6              # frame width in inches, 1 to 40
    turn = "full"            # "full": a full turn when the input can turn fully; "sweep": the sweep
    traces = ["B"]           # named points whose paths (coupler curves) are drawn
    arrows = "velocity"      # "velocity" or "acceleration" arrows (needs [input] speed)

The same four-bar written as loops (instead of ``linkage``); a mechanism of
loops needs its ``[guess]``::

    [scene]
    description = "the four-bar (4, 1, 3, 3) written as one vector loop"

    [mechanism]
    input = "theta2"         # the input symbol (an angle, rad)
    unit = "mm"
    links = [["O2", "A", "B", "O4"]]    # optional, for drawing: names of [mechanism.points]
    ground = ["O2", "O4"]
    [mechanism.dimensions]   # parameters: lengths in `unit`; <name>_deg an angle
    r1 = 4
    r2 = 1
    r3 = 3
    r4 = 3
    [[mechanism.loops]]
    name = "O2-A-B-O4"
    unknowns = ["theta3", "theta4"]
    vectors = [["r2", "theta2"], ["r3", "theta3"], ["-r4", "theta4"], ["-r1", "0"]]
    # or: equations = ["r2*cos(theta2) + ... ", "..."]   (each = 0, or "lhs = rhs")
    [mechanism.points]       # x, y of every point that links and ground name
    O2 = ["0", "0"]
    A = ["r2*cos(theta2)", "r2*sin(theta2)"]
    B = ["r2*cos(theta2) + r3*cos(theta3)", "r2*sin(theta2) + r3*sin(theta3)"]
    O4 = ["r1", "0"]

    [input]
    speed = "450 rad/min"

    [guess]
    theta3_deg = 30
    theta4_deg = 120

    [output]
    quantities = ["position", "velocity"]
    points = ["B"]

    [[check]]
    at_deg = 100
    theta4_deg = 122.343
    omega_theta4 = 2.3329

Expressions are sympy-parsable strings in the input, the dimensions, the
unknowns of this and earlier loops, ``pi`` and ``sin cos tan asin acos atan
atan2 sqrt exp abs``. A loop of vectors sums (length, angle) pairs to zero
(angles in rad from +x, counter-clockwise). Inside an expression every angle
is in rad: a dimension given as ``<name>_deg`` is converted, and a bare number
in an angle (``"theta2 + 0.5"``) is rad. A dimension is a length or an angle,
never both: an angle dimension as a whole term of a vector's length, or a
length dimension added to an angle (a vector's angle, the argument of sin,
cos or tan anywhere, a derived quantity of dimension "angle"), is refused (a
product or a function of them, ``"r*cos(tilt)"``, ``"atan2(h, d)"``, is
fine); so is a number of more than a turn in an angle (``"theta3 + 30"`` is
30 rad: write ``pi/6``, or a dimension ``gamma_deg = 30``). An angle (an angle
dimension, or a name that is a whole term of a vector's angle) as a whole term
of a point's coordinate, which is a length, is refused too. The lengths of vectors
that turn must be positive; a loop written as ``equations`` has no vector
lengths, so nothing checks their signs there.

Quantity names (for ``[[check]]``, ``--at``, JSON): an angle unknown's position
``<u>_deg``, a length unknown ``<u>`` [unit]; ``omega_<u>`` [rad/s] and
``alpha_<u>`` [rad/s^2]; ``v_<u>`` [unit/s] and ``a_<u>`` [unit/s^2]; points
``x_<P>``, ``y_<P>``, ``vx_<P>``, ``vy_<P>``, ``ax_<P>``, ``ay_<P>``.

A derived quantity of ``[mechanism.quantities]`` (:mod:`numkin.derived`) is
named like an unknown (``mu_deg``, ``omega_mu``, ``alpha_mu`` for an angle;
``s``, ``v_s``, ``a_s`` for a length), always reported in the tables,
compared by ``[compare]``, checked by ``[[check]]``, drawn by ``[output]
figures`` (``"kinematics:mu"``) and studied by the error tables
(``[report] quantity = "mu"``). Its expression uses the
mechanism's own symbols: the unknowns, the input and the dimensions of a
mechanism of loops; for a ready-made linkage its unknowns (table below), its
input and its parameters (a four-bar's ``r1`` to ``r4``; a misspelt name is
refused with the list of them).

The stability suite is a scene too: ``[stability] cases = [...]`` (default all
of :data:`numkin.stability.CASES`) instead of ``[mechanism]``.

=====================  ==================================================  ==================
``linkage``            dimensions (all required unless marked)             unknowns
=====================  ==================================================  ==================
``four_bar``           ground, crank, coupler, rocker (+ ``branch``)       theta3, theta4
``slider_crank``       crank, rod, offset (optional, 0)                    theta3, x
``quick_return``       r1, r2, r6 (optional: 60, 40, 60 mm)                r3, theta3, r4, r5
``six_bar``            crank, coupler, o4b, bc, o4c, rod, o4 = [x, y],     theta3, theta4,
                       slider_y (optional: the linkage's default, in cm)   theta5, x
``chained_four_bars``  fixed1, input1, coupler1, output1, fixed2, input2,  phi, psi,
                       coupler2, output2, offset_deg (optional: the        beta, gamma
                       homework's, in inches)
=====================  ==================================================  ==================

The table is :data:`numkin.linkages.SPECS` (a linkage's dimensions, their
kinds and defaults are read from its :class:`~numkin.linkages.LinkageSpec`);
a dimension left out takes the linkage's default, converted to ``unit``.

A mistake in a scene (an unknown key, with the nearest valid one suggested; a
missing dimension; a bad unit; malformed TOML; a point whose coordinates use
a name that is not the input, a dimension or an unknown) raises
:class:`SceneError`, a ``ValueError`` whose one-line message names the file,
the key and the value. An argument of the wrong kind (``load_scene(None)``,
``run_scene(..., out=<a file>)``) raises :class:`~numkin.errors.InputError`
naming the argument and what was given, before anything is computed.

Examples
--------
>>> from numkin.scene import load_scene, run_scene
>>> scene = load_scene("quick-return")
>>> result = run_scene(scene)
>>> check = result.checks[0]
>>> round(check.values["r3"], 3), round(check.values["theta3_deg"], 3)
(87.178, 66.587)
"""

from __future__ import annotations

from .pipeline import CheckResult, SceneResult, render_figures, run_scene
from .schema import SCENES_DIR, Scene, SceneError, check_scene_argument, list_scenes, load_scene, scene_path

__all__ = [
    "Scene",
    "SceneResult",
    "CheckResult",
    "SceneError",
    "LINKAGES",
    "SCENES_DIR",
    "load_scene",
    "check_scene_argument",
    "list_scenes",
    "scene_path",
    "run_scene",
    "render_figures",
]


def __getattr__(name: str):
    """``LINKAGES``: the registry of ready-made linkages, :data:`numkin.linkages.SPECS`."""
    if name == "LINKAGES":
        from .linkages import SPECS

        return SPECS
    raise AttributeError(f"module 'numkin.scene' has no attribute {name!r}")

"""Error-analysis reports: error against step, error against run time, solver settings.

Every table is a :class:`pandas.DataFrame` returned by one function, built
from a mechanism and plain settings (input speed, the quantity to study, a
check angle in rad, grids, schemes), so that a notebook can call each one
and :func:`full_report` can call them all for a scene:

============================  ===============================================================
function                      what the table shows
============================  ===============================================================
:func:`convergence_table`     max / RMS error of every scheme on every grid against the
                              analytic solution, the error at a check angle, observed order
:func:`work_precision_table`  work (exact counts of evaluations, the same in every run) and
                              run time (sweep, differencing, their sum) beside the error reached,
                              with the analytic solution and the complex step as rows, and
                              the Pareto fronts by work and by time
:func:`cheapest_table`        from a work-precision table: the cheapest method for each
                              wanted accuracy, by run time or by work
:func:`count_evaluations`     context manager counting the point evaluations of a
                              mechanism's compiled loop equations (the work measure)
:func:`roundoff_table`        error against the step h (1e-1 ... 1e-12 rad) at one angle;
                              the measured optimal h beside the textbook estimates
:func:`newton_table`          residual, step and error norms per Newton iteration of one
                              solve, with the estimated order of convergence
:func:`jacobian_table`        symbolic against forward / central finite-difference
                              Jacobians: iterations, time, final accuracy
:func:`tolerance_table`       loose stopping rules (the absolute step rule of report 001,
                              the relative step rule of homework 003, a residual rule)
                              against numkin's, and what they do to differenced omega, alpha
============================  ===============================================================

What is studied
---------------
The ``quantity`` of a table is an unknown of the mechanism (``"beta"``) or
one of its derived quantities (:mod:`numkin.derived`: an expression of the
unknowns, the input and the dimensions declared once, such as a four-bar's
transmission angle ``mu = theta4 - theta3``; a scene's ``[report] quantity``
names either). A derived quantity is studied as an unknown is: its values
over each sweep are differenced by the same schemes (an angle unwrapped, a
full turn as periodic, whole turns included) and compared with its exact
derivatives (the chain rule through the unknowns' analytic rates,
:func:`numkin.expressions.derived_derivatives`). Unlike an unknown, a derived
quantity need not return to its start after a turn (``theta2/2 + theta3``,
``r2*theta2``): decided on the tight sweep, such a quantity's full turn is an
open grid in every table, with end stencils, its own "ends" column and a
caption note; where its exact derivative is 0 over the sweep, relative
errors are blank. The round-off table
differences its values at the positions solved at ``theta + k h`` (steps
whose samples leave its domain blank); its complex step is the quantity's
own, ``Im(q(x(theta + i h), theta + i h)) / h`` (blank where its expression
is not analytic); the work-precision table's complex-step rows are the
unknowns' complex-step rates carried through its chain rule; the tolerance table differences its values on each loosely solved
sweep. The Newton and Jacobian tables study the solve of all the unknowns at
once and take no quantity: they are the same whichever quantity the report
studies. One object, :class:`~numkin.report.studied.StudiedQuantity`, gives
every table these values, derivatives and labels.

Conventions
-----------
* Angles are in rad inside; tables show degrees only in labelled columns
  (``"h [deg]"``) and in the text of column names such as
  ``"abs error at theta = 100 deg [unit of quantity]"``. A table computed at
  a check angle carries it as data, ``attrs["check"]``: the input's name and
  the angle in degrees (figures write it from there).
* A row's ``quantity`` names what was differentiated, with its unit:
  ``"omega_beta [rad/s]"`` (first-derivative schemes) or
  ``"alpha_beta [rad/s^2]"`` (second-derivative schemes); for a length
  unknown ``"v_x [mm/s]"`` / ``"a_x [mm/s^2]"``; a derived quantity's are
  named the same way (``"omega_mu [rad/s]"``, ``"v_gap [mm/s]"``), from its
  :class:`~numkin.quantities.Quantity`. Absolute errors are in
  that unit (column names say ``[unit of quantity]``); relative errors
  (``[-]``, or ``[%]`` in the tolerance table) are divided by the largest
  magnitude of the exact quantity over the sweep, except those taken at one
  angle (every error of the round-off table, the tolerance table's errors at
  the check angle), divided by the exact value there. Every caption names
  the denominator of each relative-error column
  (:func:`~numkin.report.captions.relative_text`).
* Grids are given in points per turn N; a full-turn grid is
  ``np.linspace(start, start + 2 pi, N + 1)`` (the last sample repeats the
  first), differenced as periodic by :mod:`numkin.kinematics`; errors
  are taken over the N distinct points.
* Row order is fixed by the arguments (scheme order, then grid order), so
  two runs give the same table. Timing is opt-in (``repeat``); **timings
  are the only entries that vary between runs**, and every column holding
  them (or chosen by them) says ``(varies)``. Work is measured by exact counts instead
  (``work [evaluations]``, see :func:`work_precision_table`): the same in
  every run, so figures drawn from it are reproducible byte for byte.
* Warnings of the main sweeps (a near-singular point, data that had to be
  differenced as an open grid) reach the caller; the repeated sweeps of
  the timings and of the loose-tolerance solves are quiet.

Tables computed inside :func:`shared_results` (as :func:`full_report` and
the scene figures compute theirs) share what they have in common: each sweep
of the same grid, its analytic derivatives and each scheme's differences are
computed once; counted and timed calls are computed anew.

:func:`write_tables` writes the tables as Markdown (GitHub-flavoured pipe
tables; a wide table in parts, ``attrs["views"]``, one idea each; numbers
with the significant figures of their column), CSV (every column, full
precision) and LaTeX (booktabs rules, written here without jinja2);
:func:`format_text` gives the same parts for the terminal.

Modules, one table family each, in the order :func:`full_report` runs them:
:mod:`~numkin.report.convergence`, :mod:`~numkin.report.workprecision`
(with :mod:`~numkin.report.counting`, the work measure),
:mod:`~numkin.report.roundoff`, :mod:`~numkin.report.newton_tables`,
:mod:`~numkin.report.tolerance`; what they share is :mod:`~numkin.report.study`
(the input speed, the quantity's labels, sweeps and points on the sweep's
branch), :mod:`~numkin.report.grids` (the grids in points per turn and the
schemes they hold) and :mod:`~numkin.report.captions` (captions, views,
relative errors), the quantity studied over a sweep :mod:`~numkin.report.studied`, and
:mod:`~numkin.report.writers` writes the tables. Every name above is
importable from :mod:`numkin.report` itself.

Examples
--------
>>> import math
>>> from numkin import linkages, report
>>> mech = linkages.chained_four_bars()
>>> conv = report.convergence_table(mech, omega="450 rad/min", quantity="beta",
...                                 check_angle=math.radians(100), grids=(180, 360),
...                                 schemes=("centred",))
>>> print(round(float(conv["observed order [-]"].iloc[1]), 2))
2.0
"""

from __future__ import annotations

import importlib
import pkgutil
from typing import Iterable, Sequence

from .convergence import convergence_table
from .counting import COUNTED_FUNCTIONS, EvaluationCounter, count_evaluations
from .newton_tables import jacobian_table, newton_table
from .roundoff import ROUNDOFF_SCHEMES, ROUNDOFF_STEPS, fitted_optimum, roundoff_table, stencil
from .grids import DEFAULT_GRIDS, TURN
from .study import input_speed, shared_results
from .tolerance import STUDENT_RULES, student_sweep, tolerance_table
from .workprecision import cheapest_table, work_precision_table
from .writers import format_cell, format_text, table_views, write_tables

__all__ = [
    "DEFAULT_GRIDS",
    "input_speed",
    "shared_results",
    "format_text",
    "format_cell",
    "table_views",
    "stencil",
    "fitted_optimum",
    "ROUNDOFF_SCHEMES",
    "ROUNDOFF_STEPS",
    "COUNTED_FUNCTIONS",
    "EvaluationCounter",
    "count_evaluations",
    "convergence_table",
    "work_precision_table",
    "cheapest_table",
    "roundoff_table",
    "newton_table",
    "jacobian_table",
    "tolerance_table",
    "student_sweep",
    "STUDENT_RULES",
    "full_report",
    "scene_report",
    "write_tables",
]


def full_report(
    mechanism,
    *,
    omega,
    quantity: str,
    check_angle: float,
    grids: Iterable[int] = DEFAULT_GRIDS,
    schemes: Sequence[str] | None = None,
    points_per_turn: int = 360,
    repeat: int | None = None,
    start: float = 0.0,
    guess=None,
    span: float = TURN,
) -> dict:
    """Every table of this module for one mechanism, in a fixed order.

    Parameters
    ----------
    mechanism : Mechanism
    omega : float or str
        Input speed of every table (rad/s or a string with units).
    quantity : str
        The unknown or derived quantity (:mod:`numkin.derived`) the
        convergence, work-precision, round-off and tolerance tables study
        (the Newton and Jacobian tables take none).
    check_angle : float
        Input angle (rad) of the point values, the round-off scan and the
        Newton solve; it should lie on every grid.
    grids : iterable of int
        Points per turn for the convergence and work-precision tables.
    schemes : sequence of str, optional
        Finite-difference schemes (default all).
    points_per_turn : int
        Points per turn of the Jacobian and tolerance sweeps.
    repeat : int, optional
        Timing repeats of the work-precision and Jacobian tables. Default
        None: no timing; every table is then the same in every run, and
        the cheapest method is chosen by work.
    start : float
        First input angle, rad.
    guess : optional
        Starting guess at `start` (default: the mechanism's); picks the branch of every table.
    span : float
        Input range of the sweeps, rad: a full turn (default) or less, for a
        linkage that cannot turn fully (open grids: no spectral schemes).

    Returns
    -------
    dict
        name -> DataFrame: ``convergence``, ``work_precision``,
        ``cheapest``, ``roundoff``, ``newton``, ``jacobian``, ``tolerance``.

    Examples
    --------
    >>> import math
    >>> from numkin import linkages
    >>> tables = full_report(linkages.slider_crank(80, 200), omega="6000 rpm", quantity="x",
    ...                      check_angle=0.0, grids=(36, 72), schemes=("centred",), points_per_turn=36)
    >>> list(tables)
    ['convergence', 'work_precision', 'cheapest', 'roundoff', 'newton', 'jacobian', 'tolerance']
    """
    with shared_results():  # the tables sweep the same grids: each sweep and its derivatives computed once
        return _full_report(mechanism, omega=omega, quantity=quantity, check_angle=check_angle, grids=grids,
                            schemes=schemes, points_per_turn=points_per_turn, repeat=repeat, start=start, guess=guess,
                            span=span)


def _full_report(mechanism, *, omega, quantity, check_angle, grids, schemes, points_per_turn, repeat, start,
                 guess, span) -> dict:
    wp = work_precision_table(
        mechanism, omega=omega, quantity=quantity, grids=grids, schemes=schemes, repeat=repeat, start=start,
        guess=guess, span=span,
    )
    return {
        "convergence": convergence_table(
            mechanism, omega=omega, quantity=quantity, check_angle=check_angle, grids=grids, schemes=schemes,
            start=start, guess=guess, span=span,
        ),
        "work_precision": wp,
        "cheapest": cheapest_table(wp, by="time" if repeat else "work"),
        "roundoff": roundoff_table(mechanism, quantity=quantity, check_angle=check_angle, guess=guess, start=start),
        "newton": newton_table(mechanism, check_angle=check_angle, guess=guess, start=start),
        "jacobian": jacobian_table(
            mechanism, check_angle=check_angle, points_per_turn=points_per_turn, repeat=repeat, start=start, guess=guess,
            span=span,
        ),
        "tolerance": tolerance_table(
            mechanism, omega=omega, quantity=quantity, check_angle=check_angle, points_per_turn=points_per_turn, start=start,
            guess=guess, span=span,
        ),
    }


def scene_report(scene, *, repeat: int | None = None) -> dict:
    """The report of any scene, as ``numkin report`` writes it: name -> DataFrame.

    * a mechanism scene: :func:`full_report` with the scene's ``[report]``
      settings (:meth:`numkin.scene.Scene.report_options`); a scene without
      an input speed (positions only) is reported per rad/s of input speed
      (derivatives with respect to time equal those with respect to the
      input angle, in /s), and every caption says so;
    * a scene whose input accelerates (``[input] acceleration``): the tables
      study the difference schemes at the constant input speed, and every
      caption of a table with accelerations says that they are
      ``omega**2 d2q/dtheta2`` alone, without the scene's ``alpha_in dq/dtheta``
      (which ``numkin run`` adds);
    * the stability scene: its suite (:func:`numkin.stability.report_tables`,
      the scene's ``cases``).

    Parameters
    ----------
    scene : Scene
        From :func:`numkin.scene.load_scene`.
    repeat : int, optional
        Timing repeats (default None: not timed; see :func:`full_report`).

    Returns
    -------
    dict

    Examples
    --------
    >>> import dataclasses
    >>> from numkin.scene import load_scene
    >>> scene = dataclasses.replace(load_scene("stability"), stability_cases=("cannot assemble (10, 6, 1, 1)",))
    >>> list(scene_report(scene))
    ['stability']
    """
    if scene.kind == "stability":
        from .. import stability

        return stability.report_tables(scene.stability_cases)
    mech = scene.build_mechanism()
    options = scene.report_options(mech)
    per_unit = not options.get("omega")
    if per_unit:
        options["omega"] = 1.0
    if repeat:
        options["repeat"] = repeat
    left_out = _coarse_defaults_left_out(scene, options)
    from ..errors import InputError, NumkinError
    from ..pipeline import in_scene_terms

    with in_scene_terms(scene, mech, tables=True):
        try:
            tables = full_report(mech, **options)
        except NumkinError as error:
            if getattr(error, "cause", None) == "too few samples" and error.args[0].startswith("grids: "):
                said = "" if "grids" in (scene.report or {}) else f" (by default {', '.join(map(str, DEFAULT_GRIDS))})"
                error.args = (f"[report] grids{said}: {error.args[0][len('grids: '):]}".replace(
                    "(or leave the scheme out)", "(or leave the scheme out of [report] schemes)"), *error.args[1:])
                raise
            solving = not isinstance(error, InputError)  # a solve that failed, not a value refused
            if solving and "span" in options and error.args and isinstance(error.args[0], str):  # less than a turn
                error.args = (f"{error.args[0]}; the round-off and Newton tables solve from 20° before to 11.5° "
                              "after the check angle ([report] check_deg), inside the linkage's range",
                              *error.args[1:])
            raise
    if left_out:
        for table in tables.values():
            if "points per turn" in table.columns:
                table.attrs["caption"] = f"{table.attrs.get('caption', '')} {left_out}".strip()
    if per_unit:
        _add_to_captions(tables, 1, "The scene gives no input speed: velocities and accelerations are per rad/s "
                                    "of input speed (d/dtheta and d2/dtheta2).")
    elif scene.acceleration:
        _add_to_captions(tables, 2, (
            f"The scene's input accelerates (alpha_in = {scene.acceleration:.6g} rad/s^2); these tables study the "
            f"difference schemes at the constant input speed omega = {options['omega']:.6g} rad/s, so an "
            "acceleration here is omega^2 d2q/dtheta2 alone: `numkin run` gives the scene's, which adds "
            "alpha_in dq/dtheta."))
    return tables


def _coarse_defaults_left_out(scene, options: dict) -> str:
    """On a scene's sweep of less than a turn, with the default grids, leave out of ``options`` the grids that hold
    fewer points over it than a scheme studied needs; what was left out, for the captions ("" if nothing)."""
    import math

    from .grids import scheme_list, too_coarse

    if "grids" in (scene.report or {}) or "span" not in options:
        return ""
    schemes = scheme_list(options.get("schemes"), periodic=False)
    short = too_coarse(schemes, DEFAULT_GRIDS, options["start"], options["span"], False)
    kept = [n for n in DEFAULT_GRIDS if n not in {s[0] for s in short}]
    if not short or len(kept) < 2:  # (too few left for an observed order: the grid check says why)
        return ""
    options["grids"] = tuple(kept)
    n, count, name, minimum, _ = short[-1]
    needs = f"fewer than {name} needs ({minimum})" if name else "fewer than 5"
    return (f"The default grids of {', '.join(str(s[0]) for s in short)} points per turn are left out: over the "
            f"scene's {math.degrees(options['span']):.4g} deg the finest of them holds {count if count else 'under 5'} "
            f"points, {needs}.")


def _add_to_captions(tables: dict, order: int, note: str) -> None:
    """Append `note` to the caption of every table holding a rate of `order` or higher with respect to time."""
    for table in tables.values():
        rates = (table.attrs.get("quantities") or {}).values()
        if any(q.order and q.order >= order and q.wrt == "time" for q in rates):
            table.attrs["caption"] = f"{table.attrs.get('caption', '')} {note}".strip()


def __getattr__(name: str):
    """A ``*_table`` function of any module of this package, found by its name.

    A new table family is one new module here: ``numkin.report.<name>_table``
    finds it without an import line in this file.
    """
    if name.endswith("_table") and not name.startswith("_"):
        for info in pkgutil.iter_modules(__path__):
            module = importlib.import_module(f"{__name__}.{info.name}")
            if name in getattr(module, "__all__", ()):
                return getattr(module, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

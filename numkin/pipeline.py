"""Running a scene: solve, differentiate, evaluate the check points, write what it asks for.

:func:`run_scene` computes exactly what a :class:`~numkin.schema.Scene` asks
for and nothing more: a position-only scene never differentiates (nothing of
``numkin.analytic``, ``numkin.kinematics`` or ``numkin.compare`` is called),
and a scene that asks for no figure never imports matplotlib. The tables are
built and written by :mod:`numkin.outputs`, the figures by
:mod:`numkin.figures`.

Examples
--------
>>> result = run_scene("quick-return", at=30)
>>> round(result.at.values["r4"], 3), result.at.units["theta3_deg"]
(130.767, 'deg')
"""

from __future__ import annotations

import copy
import json
import math
import warnings
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

from . import outputs
from .scene_quantities import scene_quantities, scene_unit
from .schema import Scene, SceneReader, check_scene_argument, in_range, load_scene, nearest
from .errors import InputError, warn
from .folders import output_folder
from .units import is_number

__all__ = ["CheckResult", "SceneResult", "run_scene", "render_figures", "written_tolerance", "in_scene_terms"]


# --------------------------------------------------------------------- results
@dataclass
class CheckResult:
    """Every quantity of a scene at one input angle.

    Attributes
    ----------
    at_deg : float
        Input angle (degrees).
    values : dict
        Quantity name -> value: the Newton solution for positions, the
        analytic solution for velocities and accelerations (units in ``units``).
    units : dict
        Quantity name -> unit label.
    schemes : dict
        Scheme name -> {quantity name -> value} for the compared schemes (only
        at grid points).
    end_stencil : dict
        Scheme name -> the quantities whose value there comes from the
        scheme's one-sided end stencil (the first or last points of an open grid).
    expected : dict
        Expected values from the scene file.
    written : dict
        Quantity name -> the expected value as the scene file writes it
        (``"122.340"``: TOML reads it as 122.34), where known.
    ok : dict
        Quantity name -> whether the value agrees with the expected one.
    on_grid : bool
        True if the angle is a point of the sweep.
    quantities : dict
        Quantity name -> its :class:`~numkin.quantities.Quantity` (what the
        value is: an angle's position is given in degrees, its name
        ``theta3_deg`` that of the Quantity ``theta3``).
    """

    at_deg: float
    values: dict
    units: dict
    schemes: dict = field(default_factory=dict)
    end_stencil: dict = field(default_factory=dict)
    expected: dict = field(default_factory=dict)
    written: dict = field(default_factory=dict)
    tolerance: dict = field(default_factory=dict)
    ok: dict = field(default_factory=dict)
    on_grid: bool = True
    quantities: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        """True if every expected value agrees."""
        return all(self.ok.values())

    def to_dict(self) -> dict:
        return {
            "at_deg": self.at_deg, "on_grid": self.on_grid, "values": self.values, "units": self.units,
            "schemes": self.schemes, "expected": self.expected, "tolerance": self.tolerance, "ok": self.ok,
            "passed": self.passed,
        }


@dataclass
class SceneResult:
    """What :func:`run_scene` computed: only what the scene asked for.

    Attributes
    ----------
    scene : Scene
    mechanism : Mechanism or None
    sweep : Sweep or None
        Positions over the input sweep.
    omega, alpha : float or None
        Input speed [rad/s] and acceleration [rad/s^2].
    kinematics : pandas.DataFrame or None
        ``numkin.analytic.kinematics`` (velocity/acceleration scenes only).
    point_kinematics : pandas.DataFrame or None
        ``numkin.analytic.point_kinematics`` of the wanted points.
    derived_kinematics : pandas.DataFrame or None
        ``numkin.analytic.derived_kinematics`` of the derived quantities
        (``[mechanism.quantities]``).
    comparisons : dict
        Quantity name (``omega_beta``, ``alpha_beta``, ``a_x``) -> ``numkin.compare.Comparison``.
    checks : list of CheckResult
        The scene's check points.
    at : CheckResult or None
        Every quantity at the angle asked for by ``run_scene(..., at=)``.
    tables : dict
        Table name -> DataFrame (the tables the scene asked for).
    suite : pandas.DataFrame or None
        The stability suite's table (stability scenes).
    report : dict
        Error-analysis tables of :mod:`numkin.report` computed for figures
        that are drawn from them (``convergence``, ``work_precision``,
        ``roundoff``, ``newton_<jacobian>``).
    written : list of Path
        Files written (tables, figures).
    """

    scene: Scene
    mechanism: Any = None
    sweep: Any = None
    omega: float | None = None
    alpha: float | None = None
    kinematics: Any = None
    point_kinematics: Any = None
    derived_kinematics: Any = None
    comparisons: dict = field(default_factory=dict)
    checks: list = field(default_factory=list)
    at: CheckResult | None = None
    tables: dict = field(default_factory=dict)
    suite: Any = None
    report: dict = field(default_factory=dict)
    written: list = field(default_factory=list)

    @property
    def passed(self) -> bool:
        """True if every check point agrees (and, for the stability suite, every case went as expected)."""
        if self.suite is not None and "as expected" in self.suite:
            return bool(self.suite["as expected"].all())
        return all(c.passed for c in self.checks)

    def derived_positions(self) -> dict:
        """Values of the derived quantities over the sweep, name -> (N,): from ``derived_kinematics``
        when the scene differentiated, else evaluated once (nothing differentiated)."""
        if self.derived_kinematics is not None:
            return {name: self.derived_kinematics[name].to_numpy() for name in self.mechanism.derived}
        if "_derived_values" not in self.__dict__:
            from .expressions import derived_values

            self.__dict__["_derived_values"] = derived_values(self.sweep)
        return self.__dict__["_derived_values"]

    def value(self, name: str, at_deg: float) -> float:
        """One quantity (see the module docstring for names) at an input angle (degrees)."""
        return _evaluate(self, at_deg).values[name]

    def to_dict(self) -> dict:
        """A JSON-ready summary: input, check points, per-scheme errors, files written."""
        s = self.scene
        out = {"scene": s.name, "description": s.description, "kind": s.kind}
        if s.kind == "stability":
            out["stability"] = json.loads(self.suite.to_json(orient="records")) if self.suite is not None else None
            out["passed"] = self.passed
        else:
            mech = self.mechanism
            out["mechanism"] = mech.name
            out["unit"] = s.unit
            out["input"] = {
                "name": mech.input_name, "start_deg": s.start_deg, "stop_deg": s.stop_deg,
                "step_deg": s.step_deg, "points": s.n_points,
                "speed_rad_s": self.omega, "acceleration_rad_s2": self.alpha if self.omega is not None else None,
            }
            sw = self.sweep
            out["newton"] = {
                "max_iterations": int(np.max(sw.iterations)), "max_residual": float(np.max(sw.residual)),
                "max_cond": float(np.max(sw.cond)), "events": [e.message for e in sw.events],
            }
            out["checks"] = [c.to_dict() for c in self.checks]
            if self.at is not None:
                out["at"] = self.at.to_dict()
            out["errors"] = outputs.error_summary(self.comparisons)
            out["passed"] = self.passed
        out["written"] = [str(p) for p in self.written]
        return outputs.jsonable(out)


# --------------------------------------------------------------------- running
def run_scene(
    scene,
    out=None,
    at: float | None = None,
    *,
    figures: bool = True,
    progress: Callable[[str], None] | None = None,
) -> SceneResult:
    """Compute what a scene asks for, and write its tables and figures to ``out``.

    Parameters
    ----------
    scene : Scene or str or path
        A scene, a built-in name or a .toml path.
    out : path, optional
        Folder for the tables (``<scene>-<table>.<format>``) and the figures
        the scene asks for; nothing is written without it.
    at : float, optional
        An input angle (degrees): ``result.at`` then holds every quantity there.
    figures : bool
        Render the scene's figures when ``out`` is given (default True).
    progress : callable, optional
        Called with the name of each stage as it starts (for progress bars).

    Returns
    -------
    SceneResult

    Raises
    ------
    InputError
        An argument of the wrong kind, before anything is computed: ``scene``
        neither a :class:`Scene`, a name nor a path; ``out`` a file or under
        one (:func:`numkin.folders.output_folder`); ``at`` not one finite
        number; ``figures`` not True or False; ``progress`` not callable.

    Examples
    --------
    >>> result = run_scene("quick-return", at=30)
    >>> round(result.at.values["r4"], 3)
    130.767
    >>> run_scene("quick-return", at="30")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: at must be an input angle in degrees (a finite number), got str '30'
    """
    if not isinstance(scene, Scene):
        check_scene_argument(scene, "scene")
    if out is not None:
        output_folder(out)
    if at is not None and not is_number(at, finite=True):
        raise InputError(f"at must be an input angle in degrees (a finite number), got {type(at).__name__} {at!r:.60}")
    if not isinstance(figures, bool):
        raise InputError(f"figures must be True or False, got {figures!r:.60}")
    if progress is not None and not callable(progress):
        raise InputError(f"progress must be a function of the stage's name, got {progress!r:.60}")
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    step = progress or (lambda stage: None)
    result = SceneResult(scene=scene)
    with ExitStack() as scope:
        _run(scene, result, scope, out, at, figures, step)
    return result


def _run(scene: Scene, result: SceneResult, scope: ExitStack, out, at, figures: bool, step) -> None:
    """The stages of :func:`run_scene`; from the mechanism on, inside :func:`in_scene_terms`."""
    if scene.kind == "stability":
        if at is not None:
            scene.fail("--at", "applies to a scene with a mechanism, not to the stability suite")
        step("stability suite")
        from . import stability

        cases = list(scene.stability_cases) if scene.stability_cases is not None else None
        if cases is not None:
            valid = list(stability.CASES)
            for c in cases:
                if c not in valid:
                    scene.fail("[stability] cases", f"unknown case '{c}'{nearest(c, valid)}; cases: {', '.join(valid)}")
        result.suite = stability.run_suite(cases)
        result.tables["stability"] = result.suite
    else:
        if at is not None:
            in_range(SceneReader(scene.source), scene, float(at), "--at")
        step("mechanism")
        mech = scene.build_mechanism()
        result.mechanism = mech
        scope.enter_context(in_scene_terms(scene, mech))
        step("positions")
        result.sweep = mech.sweep(scene.inputs(), guess=scene.guess_values(mech), on_singular=scene.on_singular)
        if scene.differentiates:
            result.omega, result.alpha = scene.speed, scene.acceleration
            step("velocity and acceleration")
            _differentiate(result)
        step("check points")
        result.checks = [_evaluate(result, c["at_deg"], c) for c in scene.checks]
        if at is not None:
            result.at = _evaluate(result, float(at), None, every=True)
        result.tables = outputs.tables(result)
    if out is not None:
        out = Path(out)
        if result.tables and scene.tables:
            step("tables")
            result.written += outputs.write_tables(scene, result.tables, out)
        if figures and scene.figures:
            result.written += render_figures(result, out, progress=step)


@contextmanager
def in_scene_terms(scene: Scene, mech, *, tables: bool = False):
    """Inside: errors and warnings said as a scene takes them, and each warning issued once, however
    many solves inside give it (a report sweeps many grids from the same guess).

    A ``[guess]`` angle more than a turn from zero is named as the scene writes it (``theta3_deg =
    1950``, in degrees) instead of in rad; advice on a guess speaks of ``[guess]`` in degrees; the way
    past a change point is the key ``[input] on_singular``, or, for the error-analysis tables
    (``tables``, which sweep the scene's range), none: they need the range free of change points. The
    warnings are issued again when the block ends, also when it fails.

    Examples
    --------
    >>> import warnings
    >>> from numkin.scene import load_scene
    >>> scene = load_scene("homework")
    >>> mech = scene.build_mechanism()
    >>> with warnings.catch_warnings(record=True) as caught, in_scene_terms(scene, mech):
    ...     warnings.simplefilter("always")
    ...     for _ in range(3):
    ...         warnings.warn("the same thing", UserWarning)
    >>> len(caught)
    1
    """
    from .errors import NumkinError
    from .first_point import degrees_hint, far_guesses

    guess = scene.guess_values(mech)
    every = far_guesses(mech, [guess[u] for u in mech.unknowns]) if guess else []

    def as_written(text: str, far=None) -> str:
        """``text`` with the hint about ``far`` (default: every far guess) said as the scene writes it, and the
        mechanism named with the unit of its dimensions, as ``numkin run`` heads its output."""
        if mech.title != mech.name and mech.name not in mech.title:
            text = text.replace(mech.name, mech.title)
        text = text.replace("guess nearer the position (angles in rad)", "[guess] nearer the position (angles as "
                            "<unknown>_deg, in degrees)").replace(
            "better guess (angles in rad)", "better [guess] (angles as <unknown>_deg, in degrees)").replace(
            ": pass at_change_point='continue' for these values", " (from Python, at_change_point='continue' "
            "returns these values)")
        if tables:
            text = text.replace(
                "pass on_singular='report' to go on along the branch whose tangent is continuous",
                "the error-analysis tables sweep the scene's range and need it free of change points "
                "([input] on_singular = \"report\" takes numkin run through them)")
        text = text.replace("pass on_singular='report'", 'set on_singular = "report" in [input]')
        far = every if far is None else far
        hint = degrees_hint(far)
        if not hint or hint not in text:
            return text
        values = ", ".join(f"{name}_deg = {scene.guess[f'{name}_deg']:g}" for name, _ in far)
        return text.replace(hint, f"[guess] {values} is more than a turn from zero (in degrees)")

    caught: list = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")  # every warning recorded; the caller's filters apply when issued again
            try:
                yield
            except NumkinError as error:
                if error.args and isinstance(error.args[0], str):
                    error.args = (as_written(error.args[0], getattr(error, "far_guess", None) or None),
                                  *error.args[1:])
                raise
    finally:  # issued again even when a later stage fails (the warnings came first)
        _issue_once(caught, as_written)


def _issue_once(caught, as_written) -> None:
    """Issue recorded warnings again, each distinct one once, their text rewritten by ``as_written``."""
    from .errors import GuessWarning

    seen = set()
    for w in caught:
        guess_warning = isinstance(w.message, GuessWarning)
        text = as_written(str(w.message), w.message.far if guess_warning else None)
        if (w.category, text) in seen:
            continue
        seen.add((w.category, text))
        if text == str(w.message):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        elif guess_warning:
            warn(GuessWarning(text, far=w.message.far, starts=w.message.starts))
        else:
            warn(text, w.category)


#: Figures drawn from the error-analysis tables of numkin.report, and the table each needs.
_REPORT_FIGURES = {
    "convergence": "convergence", "work-precision": "work_precision", "roundoff": "roundoff", "newton": "newton",
}


def render_figures(result: SceneResult, out_dir, *, formats=("png", "svg"), progress=None) -> list:
    """Draw and save the figures a scene asks for (:func:`numkin.figures.render`).

    The error-analysis tables that some figures are drawn from (convergence,
    work-precision, roundoff, Newton) are computed here, only those asked for,
    with the scene's ``[report]`` settings, and kept in ``result.report``;
    nothing is timed (the work-precision figure plots exact work counts), so
    the figures are the same bytes on every run. A figure of a derived
    quantity (``kinematics:mu``) is drawn from what the scene computed: its
    values, ``result.derived_kinematics`` and the comparisons of its rates.
    """
    from . import figures as fig

    step = progress or (lambda stage: None)
    scene = result.scene
    kinds = {fig.parse_spec(name)[0] for name in scene.figures}
    wanted = [kind for kind in _REPORT_FIGURES if kind in kinds and _REPORT_FIGURES[kind] not in result.report]
    if wanted and result.mechanism is not None and scene.speed:
        from . import report

        options = scene.report_options(result.mechanism)
        common = {k: options[k] for k in ("quantity", "guess")}
        sweep_opts = {k: options[k] for k in ("start", "span", "grids", "schemes") if k in options}
        # the convergence and work-precision tables sweep the same grids; a far guess is said once, as written
        with report.shared_results(), in_scene_terms(scene, result.mechanism, tables=True):
            for kind in wanted:
                step(f"{kind} table")
                if kind == "convergence":
                    table = report.convergence_table(
                        result.mechanism, omega=scene.speed, check_angle=options["check_angle"], **common, **sweep_opts,
                    )
                elif kind == "work-precision":  # the figure plots work counts: never timed
                    table = report.work_precision_table(
                        result.mechanism, omega=scene.speed, **common, **sweep_opts, repeat=None,
                    )
                elif kind == "roundoff":
                    table = report.roundoff_table(
                        result.mechanism, check_angle=options["check_angle"], start=options["start"], **common,
                    )
                else:
                    for jacobian in ("symbolic", "forward", "central"):
                        result.report[f"newton_{jacobian}"] = report.newton_table(
                            result.mechanism, check_angle=options["check_angle"], jacobian=jacobian, guess=options["guess"],
                            start=options["start"],
                        )
                    continue
                result.report[_REPORT_FIGURES[kind]] = table
    step("figures")
    view = copy.copy(result)
    view.tables = {**result.tables, **result.report}
    return list(fig.render(view, out_dir=Path(out_dir), formats=formats))


def _differentiate(result: SceneResult) -> None:
    """Analytic velocity/acceleration and the scheme comparisons (never for position-only scenes)."""
    from . import analytic

    scene, sweep = result.scene, result.sweep
    result.kinematics = analytic.kinematics(sweep, result.omega, result.alpha)
    if scene.points:
        result.point_kinematics = analytic.point_kinematics(sweep, result.omega, result.alpha, points=list(scene.points))
    if result.mechanism.derived:
        result.derived_kinematics = analytic.derived_kinematics(sweep, result.omega, result.alpha)
    if scene.schemes or scene.second_schemes:
        from .compare import compare

        schemes = {1: scene.schemes, 2: scene.second_schemes}
        rates = scene_quantities(scene, result.mechanism, orders=(1, 2)).values()
        for q in rates:
            if not q.is_point and schemes[q.order]:
                try:
                    result.comparisons[q.name] = compare(
                        sweep, result.omega, q.name, schemes=schemes[q.order], alpha=result.alpha,
                    )
                except InputError as error:
                    if error.cause != "too few samples":
                        raise
                    key = "schemes" if q.order == 1 else "second_schemes"
                    periodic = error.grid == "a periodic"  # (a full turn: only a smaller step gives more points)
                    raise InputError(
                        f"[compare] {key}: '{error.scheme}' needs at least {error.minimum} points on {error.grid} "
                        f"grid; the sweep ({scene.start_deg:g}° to {scene.stop_deg:g}° in steps of {scene.step_deg:g}°) "
                        f"has {error.points}{' per turn' if periodic else ''}: "
                        f"{'make its step smaller' if periodic else 'widen the sweep, make its step smaller'}, or "
                        "choose a scheme of fewer points", cause="too few samples") from None


def _evaluate(result: SceneResult, at_deg: float, check: dict | None = None, *, every: bool = False) -> CheckResult:
    """The quantities at one input angle; positions from Newton, the rest analytic."""
    scene, mech, sweep = result.scene, result.mechanism, result.sweep
    at = math.radians(at_deg)
    i = sweep.index(at)
    on_grid = bool(abs(sweep.inputs[i] - at) <= 1e-9 * max(1.0, abs(at)))
    if on_grid:
        sub, j, kin, pk, dk = sweep, i, result.kinematics, result.point_kinematics, result.derived_kinematics
    else:  # solve there by continuation from the nearest grid point
        sub = mech.sweep(np.array([sweep.inputs[i], at]), guess=sweep.values[:, i])
        j, kin, pk, dk = 1, None, None, None
        if result.kinematics is not None:
            from . import analytic

            kin = analytic.kinematics(sub, result.omega, result.alpha)
            if scene.points:
                pk = analytic.point_kinematics(sub, result.omega, result.alpha, points=list(scene.points))
            if mech.derived:
                dk = analytic.derived_kinematics(sub, result.omega, result.alpha)
    derived = {}
    if mech.derived and dk is None:  # a position-only scene: the values alone, nothing differentiated
        from .expressions import derived_values

        values_at = result.derived_positions() if on_grid else derived_values(sub)
        derived = {name: v[j] for name, v in values_at.items()}
    xy = mech.point_coordinates(sub.values[:, j : j + 1], sub.inputs[j : j + 1]) if scene.points else {}
    values, units, quantities = {}, {}, {}
    for key, q in scene_quantities(scene, mech, all_unknowns=every).items():
        if q.is_point:
            if q.order == 0:
                value = xy[q.of][0 if q.axis == "x" else 1, 0]
            elif pk is not None:
                value = pk[q.name].iloc[j]
            else:
                continue
        elif q.of in mech.derived:
            if dk is not None:
                value = dk[q.name].iloc[j]
            elif q.order == 0:
                value = derived[q.of]
            else:
                continue
            value = math.degrees(value) if q.order == 0 and q.dimension == "angle" else value
        elif q.order == 0:
            value = math.degrees(sub[q.of][j]) if q.dimension == "angle" else sub[q.of][j]
        elif kin is not None:
            value = kin[q.name].iloc[j]
        else:
            continue
        values[key], units[key], quantities[key] = float(value), scene_unit(q), q
    if check is not None:  # also the checked quantities of unknowns not reported
        missing = [key for key in check["expected"] if key not in values]
        if missing:
            every_value = _evaluate(result, at_deg, None, every=True)
            for key in missing:
                values[key], units[key] = every_value.values[key], every_value.units[key]
                quantities[key] = every_value.quantities[key]
    res = CheckResult(at_deg=at_deg, values=values, units=units, on_grid=on_grid, quantities=quantities)
    if on_grid:
        for name, comparison in result.comparisons.items():
            if name not in values:
                continue
            n = len(comparison.table)
            for scheme, value in _scheme_values(comparison, i).items():
                res.schemes.setdefault(scheme, {})[name] = value
                before, after = comparison.table.attrs.get("ends", {}).get(scheme, (0, 0))
                if i < before or i >= n - after:
                    res.end_stencil.setdefault(scheme, set()).add(name)
    if check is not None:
        written = check.get("written", {})
        for key, expected in check["expected"].items():
            text = written.get(key)
            tol = check["tolerance"] if check["tolerance"] is not None else written_tolerance(
                text if text is not None else expected)
            if text is not None:
                res.written[key] = text
            diff = values[key] - expected
            if quantities[key].in_degrees:  # an angle's position: the same angle a turn away agrees
                diff = math.remainder(diff, 360.0)
            res.expected[key] = expected
            res.tolerance[key] = tol
            res.ok[key] = bool(abs(diff) <= tol)
    return res


def written_tolerance(value) -> float:
    """Half a unit of the last decimal written (plus a rounding allowance).

    ``value`` is the number as the scene file writes it (a string: its
    trailing zeros count) or a float (the decimals of its shortest repr).

    Examples
    --------
    >>> [f"{written_tolerance(v):.1g}" for v in (10.633, "122.340", 122.340, "100", "1.50e2", "-44215.8")]
    ['0.0005', '0.0005', '0.005', '0.5', '0.5', '0.05']
    """
    text = (value.strip().replace("_", "") if isinstance(value, str) else repr(float(value))).lower()
    mantissa, _, exponent = text.partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    if not isinstance(value, str) and mantissa.endswith(".0"):
        decimals = 0  # (a float's repr: 100.0 is 100 written)
    return 0.5 * 10.0 ** (int(exponent or 0) - decimals) * (1 + 1e-9)


def _scheme_values(comparison, i: int) -> dict:
    """Each scheme's value at grid index ``i`` from a Comparison's table (its columns by their Quantity's source)."""
    table = comparison.table
    column_of = {q.source: column for column, q in table.attrs["quantities"].items()}
    return {str(s): float(table[column_of[s]].iloc[i]) for s in comparison.summary.index}

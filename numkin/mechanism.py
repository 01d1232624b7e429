"""Mechanism: an input (driver) symbol and an ordered list of loops.

On construction the loops are checked (every symbol is an unknown, a
parameter, the input or an unknown of an earlier loop), stacked, and their
residuals, Jacobian and input derivative compiled once
(:class:`~numkin.compiled.CompiledMechanism`).
"""

from __future__ import annotations

import math
from functools import cached_property
from typing import Callable, Iterable, Mapping, Sequence

import numpy as np

from .cached_model import CachedModel, count_message
from .compiled import BlockStructure, CompiledMechanism, compiled_once, underivable
from .derived import bind, names_of, read_quantities, taken_names, warn_not_finite
from .errors import AssemblyError, ConvergenceError, GuessWarning, InputError, warn
from .loops import (Loop, as_symbol, check_lengths, check_point_names, check_symbols, describe,
                    read_parameters, read_points)
from .symbol_roles import default_length_scale, warn_degrees
from .newton import JACOBIANS, TOL_MIN, NewtonResult, check_tol, iterate, residual_floor, scaled_cond
from .units import finite, number_array, with_length_unit

__all__ = ["Mechanism", "LENGTH_SCALE_RANGE"]


#: Length scales (in any unit) a mechanism may have: products of two lengths (a loop
#: Jacobian's determinant) stay normal float64 numbers, so every length scale in this
#: range solves alike, in the same iterations to the same relative accuracy.
LENGTH_SCALE_RANGE = (1e-150, 1e150)


def _names(value, argument: str) -> list:
    """``value``, a list of point names (None: none), as a list; an InputError naming ``argument`` otherwise."""
    if value is None:
        return []
    if not isinstance(value, (list, tuple)) or not all(isinstance(v, str) for v in value):
        raise InputError(f"{argument} must be a list of point names, got {value!r:.60}")
    return list(value)


class Mechanism(CachedModel):
    """A planar linkage as loop-closure equations in one input.

    Parameters
    ----------
    loops : sequence of Loop
        In solving order; a later loop may use the unknowns of earlier ones.
    input : sympy symbol or str
        The driver, usually the crank angle (rad).
    parameters : mapping, optional
        Values of the known dimensions that appear as symbols in the loops.
    name : str, optional
    guess : mapping, sequence or callable, optional
        Default starting guess: values of the unknowns at the input
        ``guess_input`` (a mapping name -> value, a sequence in unknown order,
        or a callable ``guess(input) -> mapping`` valid at any input).
    guess_input : float, optional
        The input value (rad) at which a fixed ``guess`` holds. A sweep that
        starts elsewhere first continues from there, so that it starts on the
        guessed branch.
    points : mapping, optional
        Named points ``name -> (x, y)`` as expressions of the unknowns, the
        input and the parameters (for drawing and point kinematics): sympy
        expressions, numbers or strings, whose names mean the loops' own
        symbols. A point that uses any other name is refused here, naming
        the point and the name (:func:`numkin.loops.read_points`).
    links : sequence of sequences, optional
        Rigid links as sequences of point names (drawn as polylines).
    quantities : mapping, optional
        Derived quantities ``name -> (expression, "angle" or "length")``, e.g.
        a transmission angle ``{"mu": ("theta4 - theta3", "angle")}``: listed,
        differentiated and compared like the unknowns (:mod:`numkin.derived`).
    ground : sequence, optional
        Names of the fixed pivots (drawn as ground symbols).
    length_unit : str
        Unit of the lengths (labels only; no conversion), default ``"mm"``.
    length_scale : float, optional
        Characteristic length for the stopping rule; default the largest
        vector length (:func:`numkin.symbol_roles.default_length_scale`: a
        parameter in a vector's length, or a length written as a number;
        a parameter in a vector's angle, a ground's tilt, is none). It must lie in
        :data:`LENGTH_SCALE_RANGE` (1e-150 to 1e150); within it, a linkage
        scaled by any factor solves in the same iterations to the same
        relative accuracy.
    assembly_check : callable, optional
        ``assembly_check(inputs) -> str | None`` returns why some of the
        requested inputs cannot be assembled (or None); used by the
        ready-made linkages to name the Grashof class and reachable range.
    branch : str, optional
        Name of the assembly branch the default guess picks (e.g.
        ``"crossed"``): a sweep from it that passes a change point says
        "kept the crossed branch".

    Examples
    --------
    >>> import numpy as np, sympy as sp
    >>> t2, t3, t4 = sp.symbols("theta2 theta3 theta4")
    >>> a, b, c, d = sp.symbols("a b c d", positive=True)
    >>> loop = Loop.from_vectors([(b, t2), (c, t3), (-d, t4), (-a, 0)], [t3, t4])
    >>> m = Mechanism([loop], t2, {a: 4, b: 1, c: 3, d: 3}, guess={"theta3": 0.5, "theta4": 1.5})
    >>> sweep = m.sweep(np.radians([0.0, 1.0, 2.0]))
    >>> np.round(np.degrees(sweep["theta4"]), 4)
    array([120.    , 119.6689, 119.3426])
    """

    def __init__(
        self,
        loops: Sequence[Loop],
        input,
        parameters: Mapping | None = None,
        *,
        name: str = "mechanism",
        guess=None,
        guess_input: float | None = None,
        points: Mapping | None = None,
        links: Sequence | None = None,
        ground: Sequence | None = None,
        length_unit: str = "mm",
        length_scale: float | None = None,
        assembly_check: Callable | None = None,
        branch: str | None = None,
        quantities: Mapping | None = None,
    ):
        if isinstance(loops, Loop):
            loops = [loops]
        self.loops = list(loops) if isinstance(loops, Iterable) and not isinstance(loops, str) else []
        if not self.loops or not all(isinstance(lp, Loop) for lp in self.loops):
            raise InputError(f"`loops` must be a non-empty sequence of numkin.Loop, got {loops!r:.80}")
        self.name = name
        named = set().union(*(r.free_symbols for lp in self.loops for r in lp.residuals))  # a name means these
        self.input_symbol = as_symbol(input, named)
        self.parameters = read_parameters(parameters, self.input_symbol, named)
        check_symbols(self.loops, self.input_symbol, self.parameters)
        self.unknown_symbols = [u for lp in self.loops for u in lp.unknowns]
        self.points = read_points(points, [*self.unknown_symbols, self.input_symbol, *self.parameters],
                                  name if isinstance(name, str) else "mechanism")
        self._setup(describe(self.loops, self.input_symbol, self.parameters, self.points),
                    list(self.parameters.values()), name=name, guess=guess, guess_input=guess_input, links=links,
                    ground=ground, length_unit=length_unit, length_scale=length_scale,
                    assembly_check=assembly_check, branch=branch, quantities=quantities)
        try:
            self.compiled = CompiledMechanism(
                [r for lp in self.loops for r in lp.residuals],
                self.unknown_symbols,
                self.input_symbol,
                list(self.parameters),
            )
        except NotImplementedError as error:  # sympy's printer: a derivative it cannot write as code
            raise InputError(underivable(self.loops, self.input_symbol) or f"{name}: {error}") from None
        self.add_quantities(self.__dict__.pop("_declared"))

    def _setup(self, model: dict, values: list, *, name, guess, guess_input, links, ground, length_unit,
               length_scale, assembly_check, branch, quantities=None) -> None:
        """Everything numeric about the mechanism, from the names in ``model`` and the parameter ``values``."""
        for key, value in (("name", name), ("branch", branch)):
            if not (isinstance(value, str) and value.strip() or value is None and key == "branch"):
                raise InputError(f"{key} must be a non-empty string, got {value!r:.60}")
        self.name = name
        self.input_name = model["input"]
        #: whether the input is an angle (:func:`numkin.symbol_roles.angle_unknowns`): else a length, warned of
        self.input_is_angle = bool(model.get("input_is_angle", True))
        if not self.input_is_angle:
            warn(
                f"{name}: the input {self.input_name} is a length: the loops take no sine or cosine of it and use it "
                "as a vector's length; numkin drives a linkage by an input angle (rad), and its tables and "
                "messages show the input in degrees: for a linkage driven by a length (a cylinder), make the input "
                "the angle of a link it moves and the length an unknown", UserWarning,
            )
        params = model["parameters"]
        check_point_names(model, name)  # from the sympy model or from the kernel cache alike
        if len(values) != len(params):
            raise InputError(count_message(name, values, [p for p, _, _ in params]))
        values = [finite(f"parameter {p}", v) for (p, _, _), v in zip(params, values)]
        for (p, nonnegative, _), v in zip(params, values):
            if v < 0 and nonnegative:
                raise InputError(f"parameter {p} = {v:g} is negative, but {p} is declared non-negative")
        value_of = {p: v for (p, _, _), v in zip(params, values)}
        check_lengths(model, value_of)
        self._description = model  # numkin.loops.describe's names: what check_lengths reads
        self.unknowns = tuple(u for lp in model["loops"] for u in lp["unknowns"])
        self.angles = tuple(u for lp in model["loops"] for u in lp["unknowns"] if u in lp["angles"])
        self.loop_slices = []
        start = 0
        for lp in model["loops"]:
            self.loop_slices.append(slice(start, start + len(lp["unknowns"])))
            start += len(lp["unknowns"])
        if not (isinstance(length_unit, str) and length_unit.strip() and length_unit.strip().isprintable()
                and not set(length_unit) & set("[]/ ")):
            raise InputError(f"length_unit must be a unit's name such as 'mm', 'in' or 'm', got {length_unit!r}")
        self.length_unit = length_unit
        if length_scale is None:
            length_scale = default_length_scale(model, value_of)
        self.length_scale = finite("length_scale", length_scale)
        if not self.length_scale > 0:
            raise InputError(f"length_scale must be a positive number, got {self.length_scale}")
        lo, hi = LENGTH_SCALE_RANGE
        if not lo <= self.length_scale <= hi:
            raise InputError(
                f"{name}: length scale {self.length_scale:.3g} is outside the range numkin solves, "
                f"{lo:.0e} to {hi:.0e} (products of two lengths must stay normal float64 numbers): "
                "give the lengths in another unit"
            )
        self.xscale = np.array([1.0 if u in self.angles else self.length_scale for u in self.unknowns])
        if not (links is None or isinstance(links, (list, tuple))):
            raise InputError(f"links must be a list of links, each a list of point names, got {links!r:.60}")
        self.links = [tuple(_names(link, "each of links")) for link in links or ()]
        self.ground = tuple(_names(ground, "ground"))
        unknown_points = {p for link in self.links for p in link} | set(self.ground)
        missing = sorted(unknown_points - set(model["points"]))
        if missing:
            raise InputError(f"links or ground name undefined point(s) {missing}")
        if assembly_check is not None and not callable(assembly_check):
            raise InputError(f"assembly_check must be a function of the inputs, got {assembly_check!r:.60}")
        self.assembly_check = assembly_check
        self.branch = branch
        if isinstance(guess, (str, bytes)):
            raise InputError(f"guess must be a mapping name -> value, a sequence in unknown order or a function "
                             f"of the input, got {guess!r:.60}")
        self._guess = guess
        self.guess_input = None if guess_input is None else finite("guess_input (rad)", guess_input)
        warn_degrees(name, model, value_of, self.guess_input)
        self.parameter_values = np.array(values, dtype=float)
        self.derived = {}
        self._declared = quantities  # declared by add_quantities once the model can be read

    def add_quantities(self, quantities) -> "Mechanism":
        """Declare derived quantities ``{name: (expression, "angle" or "length")}``; returns the mechanism.

        For a ready-made linkage, whose builder takes its dimensions only:
        ``linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})``.
        See :mod:`numkin.derived`.
        """
        model = self._description
        params = [p for p, _, _ in model["parameters"]]
        taken = taken_names(self.unknowns, self.angles, self.input_name, params, model["points"])
        taken.update({own: f"the quantity {d.name}" for d in self.derived.values() for own in names_of(d.name, d.dimension)})
        known = (self.unknowns, self.input_name, params)
        new = read_quantities(quantities, taken, self.name, known)
        for derived in new.values():
            bind(self, derived)  # what an expression names, and whether it moves, checked now, not at first use
        self.derived = {**self.derived, **new}
        return self

    # --------------------------------------------------------------- numerics
    def residual_function(self, inputs):
        """``F(x, idx)`` for the Newton batch: residuals at the inputs ``inputs[idx]``."""
        t = np.asarray(inputs)
        p = self.parameter_values

        def F(x, idx=slice(None)):
            return self.compiled.F(x, t[idx], p)

        return F

    def jacobian_function(self, inputs, jacobian="symbolic"):
        """``J(x, idx)`` for the Newton batch, or the name of a finite-difference rule."""
        if jacobian not in JACOBIANS:
            raise InputError(f"jacobian must be one of {JACOBIANS}, got {jacobian!r}")
        if jacobian != "symbolic":
            return jacobian
        t = np.asarray(inputs)
        p = self.parameter_values

        def J(x, idx=slice(None)):
            return self.compiled.J(x, t[idx], p)

        return J

    @cached_property
    def block_structure(self) -> BlockStructure:
        """The block lower-triangular shape of the Jacobian (one block per loop) and its solves."""
        return BlockStructure(self.loop_slices, self.length_scale, self.xscale, self._zeros())

    def _zeros(self) -> list:
        """Entries (i, j) of the Jacobian that are zero whatever the unknowns."""
        zeros = self.__dict__.get("_jacobian_zeros")
        if zeros is None:
            jac = self.compiled.jacobian_matrix
            zeros = [(i, j) for i in range(jac.rows) for j in range(jac.cols) if jac[i, j] == 0]
        return [tuple(z) for z in zeros]

    def _jacobian_rows(self, x, inputs):
        jac = self.compiled.J(np.asarray(x), np.asarray(inputs, dtype=float), self.parameter_values)
        return jac.reshape(jac.shape[0], -1).T

    def loop_residuals(self, x, inputs) -> dict:
        """Scaled residual norm of every loop, name -> (N,) array."""
        f = self.compiled.F(x, np.asarray(inputs), self.parameter_values)
        return {lp.name: np.max(np.abs(f[s]), axis=0) / self.length_scale for lp, s in zip(self.loops, self.loop_slices)}

    def loop_conditions(self, x, inputs) -> dict:
        """Condition number of every loop's own scaled Jacobian block, name -> (N,) array.

        Rows are divided by ``length_scale``, columns multiplied by ``xscale``;
        ``inf`` where the block is singular.
        """
        rows = self._jacobian_rows(x, inputs)
        conds = self.block_structure.cond(rows, rows.shape[1])
        return {lp.name: c for lp, c in zip(self.loops, conds)}

    def loop_orientations(self, x, inputs) -> np.ndarray:
        """Sign of the determinant of every loop's Jacobian block, shape (loops, N).

        It is constant along a branch and changes only through a singular
        (toggle or change-point) position.
        """
        rows = self._jacobian_rows(x, inputs)
        return self.block_structure.signs(rows, rows.shape[1])

    def guess_vector(self, guess, at: float) -> np.ndarray:
        """The guess as a vector in unknown order; ``guess`` may be a mapping, sequence or callable
        (:func:`numkin.first_point.guess_vector`)."""
        from .first_point import guess_vector

        return guess_vector(self, guess, at)

    def check_lengths(self, every_link: bool = False) -> None:
        """:func:`numkin.loops.check_lengths` here; ``every_link``: every link's length, whatever its declaration."""
        params = self._description["parameters"]
        check_lengths(self._description, {p: v for (p, _, _), v in zip(params, self.parameter_values.tolist())},
                      every_link)

    @property
    def default_guess(self):
        """The documented default guess (mapping, sequence, callable or None)."""
        return self._guess

    @property
    def title(self) -> str:
        """The name with the length unit after each dimension, for titles, captions and summaries.

        Examples
        --------
        >>> from numkin import linkages
        >>> linkages.slider_crank(0.08, 0.2, length_unit="m").title
        'slider-crank (crank 0.08 m, rod 0.2 m, offset 0 m)'
        """
        return with_length_unit(self.name, self.length_unit)

    # ---------------------------------------------------------------- solving
    def solve(self, input_value: float, guess=None, *, jacobian="symbolic", tol=1e-12, maxiter=50) -> NewtonResult:
        """Solve the position at one input by Newton-Raphson (no continuation).

        Newton on all loops at once, the textbook iteration: far from the
        solution a later loop moves with the earlier ones' steps, so a poor
        guess for one loop can take the next onto its other branch; a
        sweep's first point is solved loop by loop instead (:meth:`sweep`).

        Parameters
        ----------
        input_value : float
            Input (rad for an angle).
        guess : mapping, sequence or callable, optional
            Defaults to the mechanism's default guess.
        jacobian : {"symbolic", "forward", "central"}
            How Newton's Jacobian is computed (the step rule of the finite
            differences: :mod:`numkin.newton_rules`).
        tol : float
            Relative tolerance of the stopping rule (:mod:`numkin.newton_rules`).
        maxiter : int
            Newton steps allowed.

        Returns
        -------
        NewtonResult
            ``x`` in unknown order (``self.unknowns``). If ``converged`` is False a
            :class:`~numkin.ConvergenceWarning` says where and why.

        Examples
        --------
        >>> import warnings, numpy as np
        >>> from numkin import linkages
        >>> m = linkages.four_bar(4, 1, 3, 3)
        >>> res = m.solve(np.radians(90), guess=[0.5, 2.0])
        >>> res.converged, np.round(np.degrees(res.x), 4)
        (True, array([ 32.5561, 119.3714]))
        >>> with warnings.catch_warnings(record=True) as caught:
        ...     warnings.simplefilter("always")
        ...     res = m.solve(np.radians(90), guess=[30, 120])  # degrees by mistake: angles are in rad
        >>> res.converged, caught[0].category.__name__
        (False, 'ConvergenceWarning')

        A guess in degrees that still converges, turns away from the solution, is warned of:

        >>> with warnings.catch_warnings(record=True) as caught:
        ...     warnings.simplefilter("always")
        ...     res = m.solve(np.radians(30), guess={"theta3": 60, "theta4": 120})
        >>> res.converged, caught[0].category.__name__
        (True, 'GuessWarning')
        """
        input_value = finite("input_value (rad)", input_value)
        tol = check_tol(tol)
        if isinstance(maxiter, bool) or not isinstance(maxiter, (int, np.integer)) or maxiter < 1:
            raise InputError(f"maxiter must be a positive integer, got {maxiter!r}")
        t = np.array([input_value])
        x0 = self.guess_vector(self._guess if guess is None else guess, input_value)
        F = self.residual_function(t)
        J = self.jacobian_function(t, jacobian)
        out = iterate(F, J, x0[:, None], fscale=self.length_scale, xscale=self.xscale, tol=tol, maxiter=maxiter,
                      record=True)
        cond = float(scaled_cond(self.compiled.J(out.x, t, self.parameter_values), self.length_scale, self.xscale)[0])
        from .first_point import degrees_hint, far_guesses, still_far, unsolved

        if out.converged[0]:
            x = out.x[:, 0]
            far = still_far(self, far_guesses(self, x0), x)
            if far:
                found = ", ".join(f"{u} = {math.degrees(x[self.unknowns.index(u)]):.6g}°" for u, _ in far)
                warn(GuessWarning(f"{self.name}: {degrees_hint(far)}; Newton converged at input "
                                  f"{math.degrees(input_value):.6g}° to {found}, more than 1 rad from it",
                                  far=far, starts=[x[self.unknowns.index(u)] for u, _ in far]))
            return NewtonResult.from_batch(out, 0, cond, f"converged in {out.iterations[0]} iterations")

        return unsolved(self, float(input_value), x0, out, cond)  # says why, and warns

    def polish(self, x, inputs, *, maxiter: int = 30) -> np.ndarray:
        """Positions refined by Newton to the round-off floor, with numkin's one stopping and conditioning rule.

        Parameters
        ----------
        x : array_like (n, M)
            Solved (or nearly solved) positions, real or complex, at ``inputs``.
        inputs : array_like (M,)
            Input values (rad), real or complex.

        Returns
        -------
        ndarray (n, M)

        Raises
        ------
        ConvergenceError
            If a position does not reach the floor (names the input and the loop).

        Examples
        --------
        >>> import numpy as np
        >>> from numkin import linkages
        >>> m = linkages.four_bar(4, 1, 3, 3)
        >>> x = m.polish(np.array([[0.5682], [2.0834]]), np.radians([90.0]))
        >>> np.round(np.degrees(x[:, 0]), 8)
        array([ 32.5561258 , 119.37138726])
        """
        x, t = self._positions(x, inputs, "polish", complex_ok=True)
        scaled = np.abs(x).max(axis=1, initial=0.0) / self.xscale if x.size else np.zeros(0)
        floor = residual_floor(scaled, float(np.abs(t).max(initial=0.0)))
        out = iterate(self.residual_function(t), self.jacobian_function(t), x, fscale=self.length_scale,
                      xscale=self.xscale, tol=TOL_MIN, maxiter=maxiter, floor=floor)
        bad = np.flatnonzero(~out.converged)
        if bad.size:
            k = int(bad[0])
            worst = max(self.loop_residuals(out.x[:, k : k + 1].real, t[k : k + 1].real).items(),
                        key=lambda kv: np.nan_to_num(kv[1][0], nan=np.inf))
            raise ConvergenceError(
                f"{self.name}: position at input {math.degrees(float(np.real(t[k]))):.3f}° not refined to "
                f"round-off: loop '{worst[0]}' residual {worst[1][0]:.3g} after {int(out.iterations[k])} iterations"
                + (" (singular Jacobian)" if out.singular[k] else ""),
                input_value=float(np.real(t[k])), loop=worst[0], residual=float(worst[1][0]),
                iterations=int(out.iterations[k]), cause="singular" if out.singular[k] else "no convergence",
            )
        return out.x

    def sweep(
        self,
        inputs,
        guess=None,
        *,
        jacobian: str = "symbolic",
        tol: float = 1e-12,
        maxiter: int = 50,
        max_step: float = math.radians(30.0),
        on_singular: str = "raise",
        progress: bool = False,
    ):
        """Solve the position over a sweep of the input, by continuation.

        Parameters
        ----------
        inputs : array_like
            Strictly monotonic input values (rad for an angle).
        guess : mapping, sequence or callable, optional
            Starting guess at ``inputs[0]`` (or at ``guess_input`` for the
            mechanism's default guess). Picks the assembly branch: the first
            point is solved loop after loop, each loop from its own guess (so
            each loop's guess picks that loop's branch), where :meth:`solve`
            takes Newton on all loops at once.
        jacobian : {"symbolic", "forward", "central"}
            How Newton's Jacobian is computed.
        tol : float
            Relative tolerance of the stopping rule (see :mod:`numkin.newton`).
        maxiter : int
            Newton iterations allowed at the starting point, for each loop
            (``iterations[0]`` of the result counts those of all loops).
        max_step : float
            Largest input step (rad) between the points solved one after
            the other (each step is also shrunk as needed: it is accepted only
            when Newton converges, the correction is small and no loop changes
            orientation); the grid points between them are then solved in
            one batch.
        on_singular : {"raise", "report"}
            What to do at a change point (or a grid point on a singular
            position): raise :class:`~numkin.BranchError`, or record it in
            ``Sweep.events``, warn, and go on along the branch whose tangent
            is continuous. A toggle (limit position) cannot be driven past:
            it raises :class:`~numkin.BranchError` either way.
        progress : bool
            Show a progress bar (tqdm) over the sequentially solved steps.

        Returns
        -------
        Sweep

        Examples
        --------
        >>> import numpy as np
        >>> from numkin import linkages
        >>> sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0, 361)))
        >>> np.round(np.degrees(sweep["theta4"][[0, 90]]), 4)
        array([120.    , 119.3714])
        """
        from .continuation import run_sweep

        return run_sweep(
            self,
            inputs,
            guess,
            jacobian=jacobian,
            tol=tol,
            maxiter=maxiter,
            max_step=max_step,
            on_singular=on_singular,
            progress=progress,
        )

    # ----------------------------------------------------------------- points
    @compiled_once
    def point_function(self):
        """Compiled coordinates of all named points: ``f(q, t) -> (2 * points, N)``."""
        exprs = [c for xy in self.points.values() for c in xy]
        return self.compiled.point_function(exprs) if exprs else None

    def point_coordinates(self, x, inputs) -> dict:
        """Coordinates of the named points, name -> (2, N) array.

        A coordinate that is not finite where the unknowns are (its
        expression undefined there, ``sqrt`` of a negative number) is warned
        of, naming the point's coordinate and the input
        (:func:`numkin.derived.warn_not_finite`).
        """
        if not self.points:
            return {}
        x, t = self._positions(x, inputs, "point_coordinates")
        with np.errstate(all="ignore"):
            xy = self.point_function(*x, t, *self.parameter_values)
        if not np.all(np.isfinite(xy)):
            names = [f"{axis}_{name}" for name in self.points for axis in "xy"]
            rows = np.broadcast_to(np.asarray(xy).reshape(len(names), -1), (len(names), t.size))
            warn_not_finite(self, names, rows, np.asarray(x), t)
        return {name: xy[2 * k : 2 * k + 2] for k, name in enumerate(self.points)}

    def check_assembly(self, inputs) -> None:
        """Raise :class:`AssemblyError` if the linkage cannot be assembled at some input."""
        t = number_array(inputs, "check_assembly: inputs must be numbers (input values, rad)")
        if self.assembly_check is None:
            return
        reason = self.assembly_check(t)
        if reason:
            raise AssemblyError(f"{self.name}: {reason}", **self._assembly_failure(t))

    def _assembly_failure(self, t) -> dict:
        """The attributes of an assembly check's refusal of the inputs ``t``: the first input it refuses
        (by bisection of the prefixes it refuses), the loop, and the cause (``"cannot close"`` where a
        loop's longest side outreaches the others, else ``"not assemblable"``)."""
        from .first_point import never_closes

        lo, hi = 0, t.size  # t[:lo] is accepted, t[:hi] refused
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if self.assembly_check(t[:mid]):
                hi = mid
            else:
                lo = mid
        closes = never_closes(self)
        loop = closes[0] if closes else self.loops[0].name if len(self.loops) == 1 else None
        return {"input_value": float(t[lo]), "loop": loop, "cause": "cannot close" if closes else "not assemblable"}

    def _positions(self, x, inputs, where, complex_ok=False):
        """``x`` (n, M) and ``inputs`` (M,) as arrays of numbers of those shapes, or an InputError naming
        ``where`` and what is wrong (a single input and a vector of unknowns are one position)."""
        t = number_array(inputs, f"{where}: inputs must be numbers (input values, rad)", complex_ok=complex_ok)
        x = number_array(x, f"{where}: x must be numbers (the positions of {list(self.unknowns)})",
                         complex_ok=complex_ok)
        t = t.reshape(1) if t.ndim == 0 else t
        x = x.reshape(-1, 1) if x.ndim == 1 and t.size == 1 else x
        if t.ndim != 1 or x.shape != (len(self.unknowns), t.size):
            raise InputError(f"{where}: x must have shape (unknowns, inputs) = ({len(self.unknowns)}, {t.size}) for "
                             f"inputs of shape {t.shape}, got {x.shape}")
        return x, t

    def __repr__(self) -> str:
        return f"Mechanism({self.name!r}, input={self.input_symbol}, unknowns={list(self.unknowns)}, loops={[lp.name for lp in self.loops]})"

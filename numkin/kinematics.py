"""Velocity and acceleration by finite differences of a sampled sweep.

The position sweep gives every unknown ``q`` at the grid inputs
``theta_0, theta_0 + h, ...``; the schemes of :mod:`numkin.derivatives`
estimate ``q'`` and ``q''`` (d/dtheta) from those samples, and the input's
speed and acceleration turn them into time derivatives exactly as in
:mod:`numkin.analytic`::

    omega = omega_in * q'          alpha = omega_in**2 * q'' + alpha_in * q'

so that :func:`finite_difference` returns the same columns as
:func:`numkin.analytic.kinematics` and the two can be compared column by
column (:mod:`numkin.compare`).

Grids
-----
* The grid must be uniform (``sweep.step`` not None); a descending sweep is
  differenced as the same data in ascending order.
* A sweep spanning exactly one turn (``inputs[-1] == inputs[0] + 2*pi``;
  the last sample repeats the first configuration) is *periodic* under
  ``periodic="auto"``: the first N-1 samples are differenced with wrapping
  stencils and ``period_offset = value[-1] - value[0]`` (2*pi k for an
  angle that turns k times per turn of the input, 0 otherwise), and the
  first sample's result is copied to the last. If some unknown does not
  return to its starting value (e.g. the sweep changed branch), "auto"
  falls back to the open grid with a warning; ``periodic=True`` raises.
* Any other sweep is an open grid: one-sided end stencils of the same
  order (see :mod:`numkin.derivatives`).

Angles are differenced unwrapped. Where neighbouring samples of an angle
differ by more than pi, the step is compared with what the angle's tangent
(from the velocity equations) says it turned: whole turns between the two
are wrapped data (reduced modulo 2*pi), removed with a warning; a real turn
of more than pi between samples is kept, and warned of as a grid too coarse
for difference quotients. Samples without a tangent are unwrapped as
:func:`numpy.unwrap` does.

Conventions of the student schemes
----------------------------------
``forward`` at sample i is ``(q[i+1] - q[i]) / h`` and
``forward_of_forward`` at sample i is ``(q[i+2] - 2 q[i+1] + q[i]) / h**2``,
i.e. :func:`~numkin.derivatives.forward` applied twice, with the result
kept at the left sample i, as the homework computed it. On the homework's
1° grid this gives, at theta = 100°, 10.6000 rad/s and -28.1266 rad/s^2
for beta (the exact values are 10.6329 and -28.3750).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from . import derivatives as _d
from . import schemes as _schemes
from .analytic import check_sweep, input_rates, kinematics_frame
from .analytic import tangent as sweep_tangent
from .conditioning import DIGITS_RTOL, rounding_error, warn_rounding
from .errors import InputError, warn
from .units import deg_text, is_full_turn

__all__ = ["finite_difference", "rounding_error", "sweep_derivative", "sweep_grid", "SweepGrid", "prepare_rows", "Rows", "scheme_for", "apply_scheme", "unwrap_angles", "PARTNER",
           "CLOSURE_TOL", "closure_gap", "closes"]

#: First-derivative scheme used with each second-derivative scheme (for the
#: ``alpha_in * q'`` term of an accelerating input, and by :mod:`numkin.compare`):
#: a read-only view of :data:`numkin.schemes.PARTNER`.
PARTNER = _schemes.PARTNER

_TURN = 2.0 * math.pi


@dataclass(frozen=True)
class SweepGrid:
    """The grid of a sweep as seen by the finite-difference schemes.

    Attributes
    ----------
    h : float
        Step (rad), positive.
    periodic : bool
        True if the sweep is to be treated as periodic (it spans exactly one
        turn, and ``periodic`` was "auto" or True).
    reverse : bool
        True if the inputs descend (data are differenced reversed).
    full_turn : bool
        True if the inputs span exactly one turn.
    """

    h: float
    periodic: bool
    reverse: bool
    full_turn: bool


def sweep_grid(sweep, periodic="auto") -> SweepGrid:
    """Check that a sweep can be differenced and describe its grid.

    Parameters
    ----------
    sweep : Sweep
    periodic : {"auto", True, False}
        "auto": periodic if the sweep spans exactly one turn.

    Returns
    -------
    SweepGrid

    Raises
    ------
    ValueError
        For fewer than 2 points, a non-uniform grid, an invalid `periodic`,
        or ``periodic=True`` on a sweep that does not span exactly one turn.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.linspace(0, 2 * np.pi, 37))
    >>> g = sweep_grid(sweep)
    >>> round(float(np.degrees(g.h)), 6), g.periodic
    (10.0, True)
    """
    _, t, _ = check_sweep(sweep)
    if not (isinstance(periodic, (bool, np.bool_)) or (isinstance(periodic, str) and periodic == "auto")):
        raise InputError(f"periodic must be 'auto', True or False, got {periodic!r}")
    periodic = periodic if isinstance(periodic, str) else bool(periodic)
    if t.size < 2:
        raise InputError(f"finite differences need at least 2 points in the sweep, got {t.size}")
    d = np.diff(t)
    if not np.allclose(d, d[0], rtol=1e-9, atol=1e-14):
        raise InputError(
            "finite differences need a uniform grid: the steps of sweep.inputs vary from "
            f"{math.degrees(np.min(np.abs(d))):.6g}° to {math.degrees(np.max(np.abs(d))):.6g}°; "
            "sweep a uniform grid (np.linspace) or use numkin.analytic"
        )
    h = float(np.mean(d))
    span = float(t[-1] - t[0])
    full_turn = is_full_turn(t)
    if periodic is True and not full_turn:
        raise InputError(
            "periodic=True needs a sweep over exactly one turn, inputs[-1] = inputs[0] + 360° "
            f"(the last sample repeating the first); this sweep spans {math.degrees(span):.6g}°"
        )
    is_periodic = full_turn if periodic == "auto" else bool(periodic)
    return SweepGrid(h=abs(h), periodic=is_periodic, reverse=h < 0, full_turn=full_turn)


def unwrap_angles(y: np.ndarray, angle, names, inputs, tangent=None, purpose: str = "differencing") -> np.ndarray:
    """Angle rows of samples ``y`` (k, N) with the whole turns of wrapped data removed (warns).

    Only where neighbouring samples differ by more than pi is anything done. ``tangent``: the rows'
    derivatives with respect to the input (an array like ``y``, or a function returning it, called only
    then), e.g. a sweep's: a step is then compared with what the tangent says the angle turned
    (the trapezoid rule), and the whole turns between the two are removed: data reduced modulo 2 pi
    are unwrapped, while a real turn of more than pi between samples of a coarse grid is kept, and
    warned of as a grid too coarse to difference. Without a tangent (or where it is unknown) a jump
    of more than pi is taken for wrapping (:func:`numpy.unwrap`). ``angle``: which rows are angles;
    ``names``, ``inputs`` (rad): for the warnings, which say what the samples are unwrapped for (``purpose``).
    A step next to a NaN sample is left as it is.

    Examples
    --------
    >>> import warnings
    >>> t = np.radians([0.0, 90.0, 180.0, 270.0])
    >>> wrapped = np.array([[3.0, -3.0, -2.0, -1.0]])    # 3 rad, then -3 rad: a wrap, the tangent says +0.28 rad
    >>> with warnings.catch_warnings(record=True) as said:
    ...     out = unwrap_angles(wrapped, [True], ["q"], t, tangent=np.full((1, 4), 0.18))
    >>> out.round(4).tolist(), "wrapped data" in str(said[0].message)
    ([[3.0, 3.2832, 4.2832, 5.2832]], True)
    """
    y = np.array(y, dtype=float, copy=True)
    angle = np.broadcast_to(np.asarray(angle, dtype=bool), y.shape[:1])
    if not angle.any():
        return y
    rows = np.flatnonzero(angle)
    steps = np.diff(y[rows], axis=-1)
    big = np.abs(steps) > math.pi  # the steps read at all (NaN: a step next to a NaN sample, left as it is)
    if not big.any():
        return y
    turns = np.where(big, np.round(steps / _TURN), 0.0)  # numpy.unwrap's reading
    if tangent is not None:
        if callable(tangent):
            with warnings.catch_warnings():  # (what the tangent's own solve says is not about these samples)
                warnings.simplefilter("ignore")
                tangent = tangent()
        d = np.asarray(tangent, dtype=float)[rows]
        expected = 0.5 * np.diff(inputs) * (d[:, 1:] + d[:, :-1])
        known = big & np.isfinite(expected)
        turns[known] = np.round((steps[known] - expected[known]) / _TURN)
    wrapped = np.any(turns != 0, axis=-1)
    if wrapped.any():
        r = int(rows[wrapped][0])
        k = int(np.flatnonzero(turns[np.flatnonzero(wrapped)[0]] != 0)[0])
        warn(
            f"angle(s) {[names[i] for i in rows[wrapped]]} jump by more than 180° between neighbouring samples "
            f"(first {names[r]} between inputs {deg_text(inputs[k])} and "
            f"{deg_text(inputs[k + 1])}): wrapped data; unwrapped before {purpose}",
            UserWarning,
        )
        y[rows] -= _TURN * np.concatenate([np.zeros((rows.size, 1)), np.cumsum(turns, axis=-1)], axis=-1)
    real = big & (turns == 0)
    if real.any():
        i = int(np.flatnonzero(real.any(axis=-1))[0])
        r, k = int(rows[i]), int(np.flatnonzero(real[i])[0])
        warn(
            f"angle(s) {[names[j] for j in rows[real.any(axis=-1)]]} turn by more than 180° between neighbouring "
            f"samples (first {names[r]}, by {math.degrees(abs(steps[i, k])):.1f}° between inputs "
            f"{deg_text(inputs[k])} and {deg_text(inputs[k + 1])}): the grid is too coarse for "
            "difference quotients; sample the sweep more finely",
            UserWarning,
        )
    return y


#: A row closes after one turn of the input if its end is within this of its start (whole turns
#: aside for an angle): rad, or times the mechanism's length scale for a length. Far above a solved
#: sweep's error, far below what a quantity that does not close misses by.
CLOSURE_TOL = 1e-7


def closure_gap(offset, angle):
    """How far a quantity's end misses its start after one turn: ``offset`` (end - start), less the whole turns
    nearest to it where the quantity is an `angle` (arrays broadcast; floats give a float).

    Examples
    --------
    >>> closure_gap(4 * np.pi + 0.25, True), closure_gap(3.0, False)
    (0.25, 3.0)
    """
    gap = np.where(angle, offset - _TURN * np.round(np.divide(offset, _TURN)), offset)
    return float(gap) if np.ndim(gap) == 0 else gap


def closes(offset, angle, length_scale: float):
    """Whether a quantity returns to its start after one turn: its :func:`closure_gap` at most
    :data:`CLOSURE_TOL` (rad for an angle, times `length_scale` for a length).

    Examples
    --------
    >>> closes(np.array([2 * np.pi, 0.5, 1e-6]), np.array([True, True, False]), 100.0).tolist()
    [True, False, True]
    """
    ok = np.abs(closure_gap(offset, angle)) <= CLOSURE_TOL * np.where(angle, 1.0, length_scale)
    return bool(ok) if np.ndim(ok) == 0 else ok


def _closure(y: np.ndarray, angle: np.ndarray, length_scale: float) -> tuple[np.ndarray, np.ndarray]:
    """Period offsets ``y[:, -1] - y[:, 0]`` and whether each row closes after one turn."""
    offset = y[:, -1] - y[:, 0]
    return offset, closes(offset, angle, length_scale)


@dataclass
class Rows:
    """Sampled rows ready for differencing: unwrapped, ascending, periodicity settled.

    Made by :func:`prepare_rows`; :meth:`apply` runs one scheme on all rows.
    """

    y: np.ndarray  # (k, N), ascending input
    h: float
    periodic: bool
    reverse: bool
    offset: np.ndarray | None  # (k,) period offsets when periodic

    def apply(self, scheme) -> np.ndarray:
        """One scheme (a :class:`numkin.derivatives.Scheme`) on all rows: (k, N) in the sweep's order."""
        if scheme.periodic_only and not self.periodic:
            raise InputError(
                f"scheme {scheme.name!r} needs a periodic sweep over exactly one turn "
                "(inputs[-1] = inputs[0] + 360°, e.g. np.linspace(0, 2*np.pi, N + 1)); "
                "use five_point or five_point_second on a partial sweep"
            )
        if self.periodic:
            d = scheme.function(self.y[:, :-1], self.h, periodic=True, period_offset=self.offset)
            d = np.concatenate([d, d[:, :1]], axis=1)
        else:
            d = scheme.function(self.y, self.h, periodic=False)
        return d[:, ::-1] if self.reverse else d


def prepare_rows(y, angle, names, inputs, grid: SweepGrid, length_scale: float, periodic="auto", *,
                 close: bool = False, tangent=None) -> Rows:
    """Unwrap the angle rows of ``y`` (k, N), orient them ascending and settle periodicity.

    On a full-turn grid every row must return to its starting value (up to
    whole turns for angles); otherwise ``periodic=True`` raises and "auto"
    warns and falls back to the open grid. Used to difference quantities
    other than the unknowns (point coordinates) exactly as the unknowns are.

    Parameters
    ----------
    y : array_like, shape (k, N)
        Samples over the sweep's inputs.
    angle : bool or sequence of bool
        Which rows are angles (rad; unwrapped, may gain whole turns).
    names : sequence of str
        Row names, for messages.
    inputs : ndarray, shape (N,)
        The sweep's inputs (rad), for messages.
    grid : SweepGrid
        From :func:`sweep_grid`.
    length_scale : float
        Scale of the length rows, for the closure test.
    periodic : {"auto", True, False}
        As passed by the user (decides between raising and falling back).
    close : bool
        On a full-turn grid, difference as periodic a row whose last sample
        misses its first by solver error (a loosely solved sweep): the period
        offset is then the whole number of turns nearest to the rows' (0 for
        lengths), and the last sample is not used.
    tangent : array_like or callable, optional
        The rows' derivatives with respect to the input, shape (k, N) (or a
        function returning them, called only where neighbouring angle samples
        differ by more than pi): tells wrapped data from a real turn of more
        than pi between the samples of a coarse grid (:func:`unwrap_angles`).

    Returns
    -------
    Rows

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> from numkin.derivatives import get_scheme
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.linspace(0, 2 * np.pi, 361))
    >>> ax = sweep.points()["A"][0]                      # x of the crank pin, 80 cos(theta)
    >>> rows = prepare_rows(ax[None], False, ["x_A"], sweep.inputs, sweep_grid(sweep), 200.0)
    >>> print(np.round(rows.apply(get_scheme("spectral"))[0, 90], 9))   # -80 sin(90 deg)
    -80.0
    """
    y = np.atleast_2d(np.asarray(y, dtype=float))
    angle = np.broadcast_to(np.asarray(angle, dtype=bool), y.shape[:1])
    bad = ~np.all(np.isfinite(y), axis=0)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        row = names[int(np.flatnonzero(~np.isfinite(y[:, k]))[0])]
        raise InputError(f"{row} is not finite at input {deg_text(inputs[k])}: cannot difference it")
    y = unwrap_angles(y, angle, names, inputs, tangent)
    if grid.reverse:
        y = y[:, ::-1]
    is_periodic, offset = grid.periodic, None
    if is_periodic:
        offset, ok = _closure(y, angle, length_scale)
        if close:  # the mismatch is the solver's error: the period is whole turns (angles), none (lengths)
            offset, ok = np.where(angle, _TURN * np.round(offset / _TURN), 0.0), np.ones_like(ok)
        if not ok.all():
            bad_names = [names[i] for i in np.flatnonzero(~ok)]
            msg = (
                f"{bad_names} do not return to their starting value after one turn of the input "
                f"(value[-1] - value[0] = {offset[~ok][0]:.6g}, not a whole number of turns): "
                "they are not periodic in the input (an unknown that does not close has changed branch; a "
                "derived quantity such as theta2/2 may simply not be periodic)"
            )
            if periodic is True:
                raise InputError(msg)
            warn(msg + "; differenced as an open grid", UserWarning)
            is_periodic, offset = False, None
    return Rows(y, grid.h, is_periodic, grid.reverse, offset)


def _unknown_rows(sweep, periodic, close=False):
    """(mechanism, inputs, prepared rows of the unknowns)."""
    grid = sweep_grid(sweep, periodic)
    mech, t, q = check_sweep(sweep)
    angle = np.array([u in mech.angles for u in mech.unknowns], dtype=bool)
    return mech, t, prepare_rows(q, angle, mech.unknowns, t, grid, mech.length_scale, periodic, close=close,
                                 tangent=lambda: sweep_tangent(sweep))


def scheme_for(name, derivative: int, parameter: str):
    """The :class:`~numkin.derivatives.Scheme` called `name`, checked to estimate `derivative`.

    Raises a ValueError naming `parameter` and listing the valid schemes if
    the scheme estimates the other derivative.

    Examples
    --------
    >>> scheme_for("central", 1, "method").name
    'centred'
    >>> scheme_for("forward", 2, "second_method")
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: second_method='forward' estimates a first derivative; second_method must be one of ['second_difference', 'forward_of_forward', 'centred_of_centred', 'five_point_second', 'spectral_second']
    """
    scheme = _d.get_scheme(name)
    if scheme.derivative != derivative:
        valid = [s for s, v in _d.SCHEMES.items() if v.derivative == derivative]
        kind = "first" if scheme.derivative == 1 else "second"
        raise InputError(f"{parameter}={name!r} estimates a {kind} derivative; {parameter} must be one of {valid}")
    return scheme


def sweep_derivative(sweep, method="centred", periodic="auto", *, close: bool = False) -> np.ndarray:
    """dq/dtheta (or d2q/dtheta2) of all unknowns by one finite-difference scheme.

    Parameters
    ----------
    sweep : Sweep
        A sweep on a uniform grid.
    method : str
        Any scheme of :data:`numkin.derivatives.SCHEMES` (or alias); a
        second-derivative scheme returns d2q/dtheta2.
    periodic : {"auto", True, False}
        See the module notes.
    close : bool
        On a full-turn sweep, difference it as periodic even where its last
        point misses its first by the solver's error (see :func:`prepare_rows`):
        for a study of loosely solved sweeps, whose end mismatch is that
        error and not a change of branch.

    Returns
    -------
    ndarray, shape (n, N)
        Rows in ``sweep.unknowns`` order, per rad (per rad^2).

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import linkages
    >>> sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0, 181)))
    >>> dx = sweep_derivative(sweep, "centred")[1]
    >>> print(f"{dx[90]:.4f}")   # exact -80; error h**2/6 * 80
    -79.9959
    """
    scheme = _d.get_scheme(method)
    _, _, rows = _unknown_rows(sweep, periodic, close)
    return rows.apply(scheme)


#: The schemes :func:`finite_difference` uses unless told otherwise.
DEFAULT_METHOD, DEFAULT_SECOND_METHOD = "centred", "second_difference"


def apply_scheme(rows, scheme, argument, quantity, default=False):
    """``rows.apply(scheme)`` (:meth:`Rows.apply`); too short a sweep for it is an InputError in the words of the
    call: the argument that chose the scheme, whether its scheme is the default, the quantity it is for."""
    try:
        return rows.apply(scheme)
    except InputError as err:
        if err.cause != "too few samples":
            raise
        points = rows.y.shape[-1] - (1 if rows.periodic else 0)
        given = "the default " if default else ""
        error = InputError(
            f"{argument}={scheme.name!r} ({given}scheme for {quantity}) needs at least {err.minimum} points on "
            f"{err.grid} grid; the sweep has {points}{' per turn' if rows.periodic else ''}: sweep more points, "
            f"or choose a scheme of fewer points for {argument}",
            cause="too few samples")
        error.minimum, error.grid, error.scheme, error.points = err.minimum, err.grid, scheme.name, points
        raise error from None


def finite_difference(sweep, omega, alpha=0.0, method=DEFAULT_METHOD, second_method=DEFAULT_SECOND_METHOD,
                      periodic="auto", *, rtol=DIGITS_RTOL):
    """Angular velocities and accelerations from finite differences of a sweep.

    Parameters
    ----------
    sweep : Sweep
        A solved sweep on a uniform grid.
    omega : float, str or array_like
        Input angular speed: rad/s, a string with units (``"450 rad/min"``,
        ``"6000 rpm"``, ``"-10 rad/s"``) or one value per point.
    alpha : float, str or array_like, default 0
        Input angular acceleration: rad/s^2, a string, or one value per point.
    method : str, default "centred"
        First-derivative scheme for ``q'`` (``forward``, ``backward``,
        ``centred``, ``five_point``, ``richardson``, ``spectral``).
    second_method : str, default "second_difference"
        Second-derivative scheme for ``q''`` (``second_difference``,
        ``forward_of_forward``, ``centred_of_centred``,
        ``five_point_second``, ``spectral_second``).
    periodic : {"auto", True, False}, default "auto"
        "auto" treats a sweep over exactly one turn as periodic.
    rtol : float, default :data:`numkin.conditioning.DIGITS_RTOL`
        Relative error (to the largest value of each column) above which the
        estimated rounding error of a difference quotient warns, see
        :func:`rounding_error`.

    Returns
    -------
    pandas.DataFrame
        The columns of :func:`numkin.analytic.kinematics`: ``<input>``
        (rad), ``omega_<name>`` [rad/s] and ``alpha_<name>`` [rad/s^2] for
        angles, ``v_<name>`` [length unit/s] and ``a_<name>`` [length
        unit/s^2] for lengths. ``frame.attrs`` holds the units, the schemes,
        the step ``h`` (rad) and whether the grid was treated as periodic.

    Raises
    ------
    ValueError
        For a non-uniform grid, an unknown scheme or one of the wrong
        derivative order, a spectral scheme on a sweep that is not one full
        turn, or too few points for the scheme.
    numkin.units.UnitError
        If `omega` or `alpha` has the wrong dimension.

    Warns
    -----
    numkin.conditioning.LostDigitsWarning
        If the estimated rounding error of a scheme exceeds `rtol` somewhere.

    Notes
    -----
    ``alpha_q = omega_in**2 D2(q) + alpha_in D1(q)`` with D1 = `method` and
    D2 = `second_method`.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import kinematics, linkages
    >>> sweep = linkages.chained_four_bars().sweep(np.radians(np.arange(0, 361)))
    >>> fd = kinematics.finite_difference(sweep, "450 rad/min")
    >>> print(f"{fd['omega_beta'][100]:.4f} {fd['alpha_beta'][100]:.4f}")
    10.6330 -28.3765
    >>> fw = kinematics.finite_difference(sweep, "450 rad/min", method="forward",
    ...                                   second_method="forward_of_forward")
    >>> print(f"{fw['omega_beta'][100]:.5f} {fw['alpha_beta'][100]:.4f}")
    10.59998 -28.1266
    """
    s1 = scheme_for(method, 1, "method")
    s2 = scheme_for(second_method, 2, "second_method")
    mech, t, rows = _unknown_rows(sweep, periodic)
    w, a = input_rates(omega, alpha, t.size)
    d1 = apply_scheme(rows, s1, "method", "omega", method == DEFAULT_METHOD)
    d2 = apply_scheme(rows, s2, "second_method", "alpha", second_method == DEFAULT_SECOND_METHOD)
    for scheme, d in ((s1, d1), (s2, d2)):
        warn_rounding(sweep, mech, t, rows, scheme, d, rtol)
    attrs = {
        "omega": w, "alpha": a, "method": s1.name, "second_method": s2.name,
        "h": rows.h, "periodic": rows.periodic, "descending": rows.reverse,
    }
    return kinematics_frame(mech, t, w * d1, w**2 * d2 + a * d1, attrs, s1.name, s2.name)


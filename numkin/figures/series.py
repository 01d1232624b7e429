"""What a curve figure draws of a name: an unknown of the sweep, or a derived quantity of its mechanism.

A derived quantity (``mu = theta4 - theta3``, declared with
:meth:`numkin.Mechanism.add_quantities` or a scene's ``[mechanism.quantities]``)
is drawn wherever an unknown is. Its samples over the sweep are its
expression evaluated at the solved unknowns (:func:`numkin.analytic.derived_values`),
an angle unwrapped as the unknowns' angles are continuous (:func:`sampled`).
Its rates come from the frames a figure is given (:func:`with_rates`): the
analytic ones from :func:`numkin.analytic.derived_kinematics` at the frame's
input speed, the finite-difference ones by the frame's own schemes applied
to the samples, as :func:`numkin.kinematics.finite_difference` does for an
unknown (unwrapped, periodicity settled by :func:`numkin.kinematics.prepare_rows`,
as :func:`numkin.compare.compare` does for a derived quantity).

Examples
--------
>>> import numpy as np
>>> from numkin import linkages
>>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
>>> sweep = mech.sweep(np.radians([0.0, 90.0]))
>>> print(np.degrees(sampled(sweep, "mu")).round(4))
[60.     86.8153]
"""

from __future__ import annotations

import numpy as np

from .labels import derived_of, frame_input, is_angle, rate_columns

__all__ = ["sampled", "with_rates"]


def sampled(sweep, name: str) -> np.ndarray:
    """The values of an unknown or derived quantity over the sweep (rad or the length unit).

    An unknown's are the sweep's own. A derived angle is unwrapped where
    neighbouring samples jump by more than half a turn (an ``atan2``
    crossing ±180°), so that it is drawn and differenced like an angle
    unknown; samples where its expression is undefined stay NaN.
    """
    if name in sweep.unknowns:
        return sweep[name]
    from ..expressions import derived_values

    y = np.array(derived_values(sweep, [name])[name], dtype=float)
    finite = np.isfinite(y)
    if is_angle(sweep, name) and finite.sum() > 1:
        y[finite] = np.unwrap(y[finite])
    return y


def _on_sweep(frame, sweep) -> bool:
    """Whether a frame holds one row per input of the sweep, at the same inputs."""
    if frame is None or len(frame) != len(sweep):
        return False
    return bool(np.allclose(frame_input(frame, sweep), sweep.inputs, rtol=0.0, atol=1e-12))


def _analytic_rates(sweep, name: str, frame):
    """``frame`` with the exact rates of the derived quantity `name` added, at the frame's input speed."""
    from ..expressions import derived_kinematics

    attrs = frame.attrs
    kin = derived_kinematics(sweep, attrs["omega"], attrs.get("alpha", 0.0), names=[name])
    out = frame.copy()
    for col in rate_columns(sweep, name):
        out[col] = kin[col].to_numpy()
    return out


def _scheme_rates(sweep, name: str, frame, values: np.ndarray):
    """``frame`` with the rates of `name` by the frame's schemes (``attrs["method"]``, ``"second_method"``)."""
    from ..analytic import input_rates
    from ..kinematics import prepare_rows, scheme_for, sweep_grid

    attrs = frame.attrs
    s1 = scheme_for(attrs["method"], 1, "method")
    s2 = scheme_for(attrs["second_method"], 2, "second_method")
    periodic = "auto" if attrs.get("periodic") else False
    t = sweep.inputs
    rows = prepare_rows(values[None, :], [is_angle(sweep, name)], [name], t, sweep_grid(sweep, periodic),
                        sweep.mechanism.length_scale, periodic)
    w, a = input_rates(attrs["omega"], attrs.get("alpha", 0.0), t.size)
    d1, d2 = rows.apply(s1)[0], rows.apply(s2)[0]
    vcol, acol = rate_columns(sweep, name)
    out = frame.copy()
    out[vcol], out[acol] = w * d1, w**2 * d2 + a * d1
    out.attrs["periodic"] = rows.periodic  # a derived quantity that does not close is differenced as open
    return out


def with_rates(sweep, name: str, analytic=None, finite=None):
    """The frames a curve figure draws `name` from, with a derived quantity's rates added where missing.

    For an unknown, or a derived quantity whose columns a frame already
    holds (a scene's comparisons, :func:`numkin.analytic.derived_kinematics`
    joined to the kinematics), the frames are returned as given. A frame
    without them gains them when it says how it was made and lies on the
    sweep's inputs: the analytic frame of :func:`numkin.analytic.kinematics`
    (its ``attrs`` ``omega``, ``alpha``) the exact rates, a frame of
    :func:`numkin.kinematics.finite_difference` (its ``method``,
    ``second_method``, ``omega``, ``alpha``) the same schemes applied to
    the derived quantity's samples. Frames are copied, never changed.

    Parameters
    ----------
    sweep : Sweep
    name : str
        An unknown or a derived quantity of the sweep's mechanism.
    analytic : DataFrame, optional
    finite : mapping of str to DataFrame, optional

    Returns
    -------
    tuple
        ``(analytic, finite)``: the analytic frame (or None) and a dict.

    Examples
    --------
    >>> import numpy as np
    >>> from numkin import analytic, linkages
    >>> from numkin.kinematics import finite_difference
    >>> mech = linkages.four_bar(4, 1, 3, 3).add_quantities({"mu": ("theta4 - theta3", "angle")})
    >>> sweep = mech.sweep(np.radians(np.arange(0, 361)))
    >>> exact, fd = with_rates(sweep, "mu", analytic.kinematics(sweep, 10.0),
    ...                        {"centred": finite_difference(sweep, 10.0)})
    >>> print(f"{exact['omega_mu'][90]:.4f} rad/s exact, {fd['centred']['omega_mu'][90]:.4f} rad/s centred")
    4.4513 rad/s exact, 4.4511 rad/s centred
    """
    finite = dict(finite or {})
    if name not in derived_of(sweep):
        return analytic, finite
    cols = set(rate_columns(sweep, name))
    values = None
    if analytic is not None and not cols & set(analytic.columns) and "omega" in analytic.attrs \
            and _on_sweep(analytic, sweep):
        analytic = _analytic_rates(sweep, name, analytic)
    for key, frame in finite.items():
        attrs = frame.attrs
        if cols & set(frame.columns) or not {"method", "second_method", "omega"} <= set(attrs) \
                or not _on_sweep(frame, sweep):
            continue
        if values is None:
            values = sampled(sweep, name)
        finite[key] = _scheme_rates(sweep, name, frame, values)
    return analytic, finite

"""Checks of the arguments of the public figure functions, at their entry.

A figure function given a wrong kind of thing (a string where a
:class:`~numkin.Sweep` belongs, a number for a list of names, a lone
DataFrame for a mapping of them) raises :class:`~numkin.InputError`
naming the argument and what it should be, instead of failing somewhere
inside matplotlib or pandas. Only the kind of each argument is checked
here; what it holds (an unknown's name, a table's columns) is checked
where it is used.

Examples
--------
>>> need_names(3, "names", "position")
Traceback (most recent call last):
...
numkin.errors.InputError: position: names must be a name or a list of names (str), got int 3
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping

from ..errors import InputError
from ..units import is_number

__all__ = ["got", "need_angle", "need_angles", "need_figure", "need_frame", "need_frames", "need_names",
           "need_result", "need_sweep", "need_table", "need_tables"]


def _items(n: int) -> str:
    return f"{n} item" if n == 1 else f"{n} items"


def got(value) -> str:
    """``"str 'abc'"``: the type and a short repr of a wrong argument, for messages."""
    text = repr(value)
    if "\n" in text:  # a DataFrame, or a list of them: its type (and length) says enough
        size = f" of {_items(len(value))}" if isinstance(value, (list, tuple)) else ""
        return f"a {type(value).__name__}{size}" if size else type(value).__name__
    if len(text) > 60:
        text = text[:57] + "..."
    return f"{type(value).__name__} {text}"


def need_sweep(sweep, where: str) -> None:
    """`sweep` must be a :class:`~numkin.Sweep` (a Mechanism is named as such: sweep it first)."""
    from ..sweep import Sweep

    if isinstance(sweep, Sweep):
        return
    hint = ""
    if hasattr(sweep, "sweep") and hasattr(sweep, "unknowns"):
        hint = " (a Mechanism: give mechanism.sweep(inputs))"
    raise InputError(f"{where}: sweep must be a numkin Sweep (Mechanism.sweep(inputs)), got {got(sweep)}{hint}")


def _listed(values):
    """A non-string iterable as a list (a generator is read once), or None if `values` is not iterable."""
    if isinstance(values, (str, bytes)) or _is_frame(values) or not hasattr(values, "__iter__"):
        return None
    import numpy as np

    if isinstance(values, np.ndarray) and values.ndim == 0:
        return None
    return list(values)


def need_names(names, parameter: str, where: str):
    """`names` must be None, a string or an iterable of strings (a list, tuple, array, ``dict.keys()``...).

    Returns
    -------
    None, str or list of str
        `names` itself for None or a string; else its items as a list.
    """
    if names is None or isinstance(names, str):
        return names
    listed = _listed(names)
    if listed is not None and all(isinstance(n, str) for n in listed):
        return listed
    raise InputError(f"{where}: {parameter} must be a name or a list of names (str), got {got(names)}")


def _is_frame(frame) -> bool:
    return hasattr(frame, "columns") and hasattr(frame, "attrs") and hasattr(frame, "iloc")


def _each_frame(mapping: Mapping, parameter: str, where: str) -> None:
    """Every value of a mapping must be a DataFrame (named by its key)."""
    for key, frame in mapping.items():
        if not _is_frame(frame):
            raise InputError(f"{where}: {parameter}[{key!r}] must be a DataFrame, got {got(frame)}")


def need_frame(frame, parameter: str, where: str, *, optional: bool = True) -> None:
    """`frame` must be a pandas DataFrame (or None when `optional`)."""
    if frame is None and optional or _is_frame(frame):
        return
    raise InputError(f"{where}: {parameter} must be a DataFrame (numkin.analytic.kinematics), got {got(frame)}")


def need_frames(frames, parameter: str, where: str, *, optional: bool = True):
    """`frames` must be a mapping scheme name -> DataFrame, or pairs ``(name, DataFrame)`` (None when
    `optional`).

    Returns
    -------
    None or mapping
        `frames` itself, or the pairs as a dict.
    """
    if frames is None and optional:
        return None
    if _is_frame(frames):
        raise InputError(f"{where}: {parameter} must map scheme names to DataFrames, got one DataFrame; "
                         f"give {{'centred': frame}}")
    if not isinstance(frames, Mapping):
        listed = _listed(frames)
        if listed and all(isinstance(p, tuple) and len(p) == 2 and isinstance(p[0], str) for p in listed):
            frames = dict(listed)
        else:
            raise InputError(f"{where}: {parameter} must map scheme names to DataFrames "
                             f"({{'centred': numkin.kinematics.finite_difference(...)}}), got {got(frames)}")
    _each_frame(frames, parameter, where)
    return frames


def need_angle(angle, parameter: str, where: str) -> None:
    """`angle` must be None or a number (rad); a string is refused (it would be read as radians)."""
    if angle is None or is_number(angle):
        return
    raise InputError(f"{where}: {parameter} must be an input angle in rad (a number, e.g. np.radians(30)), "
                     f"got {got(angle)}")


def need_angles(angles, parameter: str, where: str):
    """`angles` must be None, a number or an iterable (or array) of numbers, in rad.

    Returns
    -------
    `angles` itself, or its items as a list (a generator is read once).
    """
    import numpy as np

    if angles is None or is_number(angles):
        return angles
    if isinstance(angles, np.ndarray) and angles.dtype.kind in "iuf":
        return angles
    if isinstance(angles, np.ndarray) and angles.dtype.kind != "O":
        raise InputError(f"{where}: {parameter} must be input angles in rad (numbers), got an array of {angles.dtype}")
    if isinstance(angles, (str, bytes, Mapping)) or not hasattr(angles, "__iter__"):
        raise InputError(f"{where}: {parameter} must be input angles in rad (numbers), got {got(angles)}")
    listed = list(np.ravel(angles)) if isinstance(angles, np.ndarray) else list(angles)
    bad = [a for a in listed if not is_number(a)]
    if bad:
        raise InputError(f"{where}: {parameter} must be input angles in rad (numbers), got {got(bad[0])} among them")
    return listed


def need_table(table, parameter: str, where: str) -> None:
    """`table` must be a DataFrame of :mod:`numkin.report`."""
    if not _is_frame(table):
        raise InputError(f"{where}: {parameter} must be a DataFrame from numkin.report, got {got(table)}")


def need_tables(tables, parameter: str, where: str) -> None:
    """`tables` must be a DataFrame or a mapping name -> DataFrame."""
    if _is_frame(tables):
        return
    if not isinstance(tables, Mapping):
        raise InputError(f"{where}: {parameter} must be a DataFrame or a mapping of names to DataFrames, "
                         f"got {got(tables)}")
    _each_frame(tables, parameter, where)


def need_figure(fig, where: str) -> None:
    """`fig` must be a matplotlib Figure."""
    if not (hasattr(fig, "savefig") and hasattr(fig, "get_layout_engine")):
        raise InputError(f"{where}: fig must be a matplotlib Figure (what a numkin.figures function returns), "
                         f"got {got(fig)}")


def need_result(result, where: str) -> None:
    """`result` must be an object with attributes (a SceneResult), not a plain value."""
    if result is None or isinstance(result, (str, bytes, numbers.Number, list, tuple, Mapping)):
        raise InputError(f"{where}: result must be a SceneResult (numkin.scene.run_scene) or an object with a "
                         f"sweep and the frames and tables to draw, got {got(result)}")

"""Exceptions raised by numkin.

Every error names what is wrong and where: the parameter, the loop, the input
angle. Nothing that failed is ever returned as if it were valid. The same
facts travel as attributes, so that a caller (the ``numkin`` command, a
notebook) can say them in its own words or prefix where the linkage came
from (a scene file) without parsing the message.
"""

from __future__ import annotations

import os
import sys
import warnings

__all__ = ["NumkinError", "InputError", "AssemblyError", "ConvergenceError", "BranchError", "ConvergenceWarning", "DegreesWarning",
           "GuessWarning", "warn"]

_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warn(message, category=None) -> None:
    """``warnings.warn``, attributed to the first caller outside numkin: the user's own line.

    A warning may arise several calls deep inside numkin (a sweep inside a
    scene inside the command); a fixed ``stacklevel`` would point at one of
    numkin's lines instead, and a notebook would show numkin's path.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn("a test", UserWarning)
    >>> "numkin" + os.sep in caught[0].filename
    False
    """
    frame, level = sys._getframe(1), 2
    while frame.f_back is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)


class NumkinError(Exception):
    """Base class of the errors numkin raises on purpose.

    Attributes
    ----------
    input_value : float or None
        Input (driver) value where it happened, rad for angular inputs.
    loop : str or None
        Name of the loop concerned.
    cause : str or None
        The cause in one word or phrase, e.g. ``"bad guess"``,
        ``"dependent equations"``, ``"change point"``, ``"toggle"``.
    """

    def __init__(self, message="", *, input_value=None, loop=None, cause=None):
        super().__init__(message)
        self.input_value = input_value
        self.loop = loop
        self.cause = cause

    @property
    def message(self) -> str:
        """The message alone (``str(error)``)."""
        return str(self.args[0]) if self.args else ""


class InputError(NumkinError, ValueError):
    """A value given to numkin is not one it can use: a parameter, an argument, a scene's key.

    The message names the value and where it was given. A ``ValueError``, so
    that ``except ValueError`` catches it as it catches Python's own; the
    ``numkin`` command says it in one line and exits with status 2, while a
    ``ValueError`` that is not a ``NumkinError`` is a check numkin lacks
    (exit status 3).

    Examples
    --------
    >>> from numkin import linkages
    >>> try:
    ...     linkages.four_bar(4.0, -1.0, 3.0, 3.0)
    ... except ValueError as error:
    ...     print(type(error).__name__)
    InputError
    """


class AssemblyError(NumkinError, ValueError):
    """The linkage cannot be assembled at a requested input.

    Raised before or at the first Newton solve of a sweep. For ready-made
    four-bars the message names the Grashof class and the reachable input
    range. ``cause`` is ``"bad guess"`` when Newton from the guess wandered
    off, ``"dependent equations"`` when the loop equations do not fix the
    unknowns, ``"cannot close"`` when a loop's longest vector is longer than
    all the others together, ``"not assemblable"`` otherwise (a ready-made
    linkage's assembly check refusing an input: ``input_value`` is the first
    input refused).

    Attributes
    ----------
    residual : float or None
        Scaled residual norm at the last iterate.
    iterations : int or None
        Newton iterations spent.
    far_guess : list of (str, float)
        The guess's angles more than a turn from zero (rad), named in the
        message as perhaps given in degrees; empty if none.
    """

    def __init__(self, message="", *, input_value=None, loop=None, cause=None, residual=None, iterations=None,
                 far_guess=()):
        super().__init__(message, input_value=input_value, loop=loop, cause=cause)
        self.residual = residual
        self.iterations = iterations
        self.far_guess = list(far_guess)


class ConvergenceError(NumkinError, RuntimeError):
    """Newton-Raphson did not converge at a point of a sweep.

    Attributes
    ----------
    input_value : float
        Input (driver) value where it failed, rad for angular inputs.
    loop : str
        Name of the loop whose residual is largest.
    residual : float
        Scaled residual norm at the last iterate.
    iterations : int
        Iterations spent.
    """

    def __init__(self, message="", *, input_value=None, loop=None, residual=None, iterations=None, cause=None):
        super().__init__(message, input_value=input_value, loop=loop, cause=cause)
        self.residual = residual
        self.iterations = iterations


class BranchError(NumkinError):
    """A sweep reached a singular position it cannot cross on one branch.

    ``kind`` is ``"toggle"`` (a limit position: the input cannot be driven
    further), ``"change point"`` (the Jacobian changes sign: the branches meet
    and the choice is ambiguous) or ``"singular"`` (the Jacobian is singular
    at the requested point itself).

    Attributes
    ----------
    kind : str
    input_value : float
        Input value (rad) where it happens.
    loop : str
        Name of the loop concerned.
    cond : float or None
        Condition number of the loop's scaled Jacobian block there.
    """

    def __init__(self, message="", *, kind, input_value=None, loop=None, cond=None, cause=None):
        super().__init__(message, input_value=input_value, loop=loop, cause=cause or kind)
        self.kind = kind
        self.cond = cond


class ConvergenceWarning(UserWarning):
    """Newton-Raphson did not converge, and the caller gets the result anyway.

    :meth:`numkin.Mechanism.solve` returns its :class:`~numkin.NewtonResult`
    (``converged`` False) and warns with this category, naming the input
    angle, the loop with the largest residual and that residual; a sweep
    raises :class:`ConvergenceError` instead.
    """


class DegreesWarning(UserWarning):
    """Angles given to numkin look like degrees where rad are expected.

    A sweep whose inputs step by 0.5 or more over 90 or more
    (``np.arange(0, 361)``, ``np.linspace(0, 360, 100)``), or by whole
    numbers over 30 or more (``np.arange(30, 61)``), is, in rad, turns in
    steps of 29° or more; a ``guess_input`` or a parameter added to an angle
    more than a turn from zero is most likely in degrees too. ``np.radians``
    converts. (The input may be a length, a slider's position: then the
    warning does not apply.)
    """


class GuessWarning(DegreesWarning):
    """A sweep's guess of an angle is more than a turn from zero and more than 1 rad from the solution.

    Angles are in rad: such a guess was most likely given in degrees. The
    sweep keeps the guess's turn.

    Attributes
    ----------
    far : list of (str, float)
        Every such unknown and its guess (rad).
    starts : list of float
        Where the sweep starts them (rad), in the same order.
    """

    def __init__(self, message="", *, far=(), starts=()):
        super().__init__(message)
        self.far = list(far)
        self.starts = list(starts)

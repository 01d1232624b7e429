"""Output folders: a folder given for numkin's outputs, checked before any work and made when written to.

Every writer of numkin (scene outputs, error tables, figures, animations)
makes its folder with :func:`made_folder`; the command line checks ``--out``
with :func:`output_folder` before it solves anything. Like :mod:`numkin.errors`
and :mod:`numkin.units`, this module serves every stage.
"""

from __future__ import annotations

import os
from pathlib import Path

from .errors import InputError

__all__ = ["output_folder", "made_folder"]


def output_folder(out, argument: str = "out") -> Path:
    """``out`` as the :class:`~pathlib.Path` of a folder that is there or can be made; nothing is made.

    Raises
    ------
    InputError
        Naming ``argument`` and the path: ``out`` is not a path (``str`` or
        :class:`pathlib.Path`), is a file, or lies under a file.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.NamedTemporaryFile() as f:
    ...     output_folder(f.name + "/tables")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: out: cannot make the folder '.../tables': '...' is a file, not a folder
    >>> output_folder(3)
    Traceback (most recent call last):
    ...
    numkin.errors.InputError: out must be a folder's path (str or pathlib.Path), got int 3
    """
    if isinstance(out, (str, os.PathLike)) and not str(out).strip():
        raise InputError(f"{argument} is empty: give a folder's path ('.' for the current folder)")
    if isinstance(out, bytes) or not isinstance(out, (str, os.PathLike)):
        raise InputError(f"{argument} must be a folder's path (str or pathlib.Path), got {type(out).__name__} "
                         f"{out!r:.60}")
    path = Path(out)
    if path.exists() and not path.is_dir():
        raise InputError(f"{argument}: '{path}' is a file, not a folder")
    above = path.parent
    while not above.exists() and above != above.parent:
        above = above.parent
    if above.exists() and not above.is_dir():
        raise InputError(f"{argument}: cannot make the folder '{path}': '{above}' is a file, not a folder")
    return path


def made_folder(out, argument: str = "out") -> Path:
    """:func:`output_folder`, made (with its parents); an OSError said as an InputError naming the folder.

    Every writer of numkin makes its folder with it (scene outputs, error tables, figures, animations).
    """
    path = output_folder(out, argument)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise InputError(f"{argument}: cannot make the folder '{path}': {error.strerror or error}") from None
    return path

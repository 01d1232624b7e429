"""A disk cache of generated kernels: the code ``sympy.lambdify`` writes, kept between runs.

A kernel is keyed by the expressions' structure (``sympy.srepr``), its
arguments, the target module (``numpy`` or ``math``), whether common
subexpressions were eliminated, and the versions of numkin, sympy, numpy and
Python; a new version of any of them misses the cache. Only code whose every
global name is a function or constant of numpy or math is kept. An entry is
a small JSON file written to a temporary file and renamed into place
(atomic: concurrent runs never see half an entry); on reading, its checksum,
its key and the shape of its code (one function, no imports, no attribute
access, only the recorded global names) are checked, and an entry that fails
any check is rebuilt, never trusted.

The folder is the user's cache folder (``platformdirs.user_cache_dir``, else
``$XDG_CACHE_HOME`` or ``~/.cache``) under ``numkin/kernels``; the
environment variable ``NUMKIN_CACHE_DIR`` names another one, and
``NUMKIN_CACHE_DIR=off`` turns the cache off. A folder that cannot be
written only costs the cache.
"""

from __future__ import annotations

import ast
import hashlib
import inspect
import json
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

__all__ = ["cache_dir", "cached_lambdify", "ENV_VAR"]

#: Environment variable naming the cache folder (``off`` disables the cache).
ENV_VAR = "NUMKIN_CACHE_DIR"
_FORMAT = 1


def cache_dir() -> Path | None:
    """The folder of the kernel cache, or None when it is turned off."""
    where = os.environ.get(ENV_VAR)
    if where is not None:
        return None if where.strip().lower() in ("", "off", "0", "none") else Path(where)
    try:
        from platformdirs import user_cache_dir

        base = Path(user_cache_dir("numkin"))
    except ImportError:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "numkin"
    return base / "kernels"


def _versions() -> str:
    import sympy

    from . import __version__

    return f"numkin {__version__}; sympy {sympy.__version__}; numpy {np.__version__}; python {sys.version_info[:3]}"


def _key(exprs, args, modules, cse) -> str:
    import sympy as sp

    text = "\n".join([f"format {_FORMAT}", _versions(), modules, str(bool(cse)), sp.srepr(tuple(args)),
                      sp.srepr(tuple(exprs))])
    return hashlib.sha256(text.encode()).hexdigest()


def _resolve(name, value, module):
    """Where a global of generated code comes from: ``[module, attribute]`` or ``["float", repr]``; None if unknown."""
    for mod, label in ((module, module.__name__), (math, "math"), (np, "numpy")):
        if getattr(mod, name, None) is value and value is not None:
            return [label, name]
    if isinstance(value, float):
        return ["float", repr(value)]
    return None


def _namespace(names: dict) -> dict | None:
    ns = {}
    for name, (where, what) in names.items():
        if where == "float":
            ns[name] = float(what)
        elif where in ("math", "numpy"):
            mod = math if where == "math" else np
            if not hasattr(mod, what):
                return None
            ns[name] = getattr(mod, what)
        else:
            return None
    return ns


def _safe(source: str, names: dict, nargs: int) -> bool:
    """One plain function: no imports, no attribute access, no dunder names, only the recorded globals."""
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return False
    if len(tree.body) != 1 or not isinstance(tree.body[0], ast.FunctionDef) or len(tree.body[0].args.args) != nargs:
        return False
    fn = tree.body[0]
    local = {a.arg for a in fn.args.args}
    for node in ast.walk(fn):
        if isinstance(node, (ast.Import, ast.ImportFrom, ast.Attribute, ast.Global, ast.Nonlocal, ast.Lambda,
                             ast.ClassDef, ast.AsyncFunctionDef)) or (isinstance(node, ast.FunctionDef) and node is not fn):
            return False
        if isinstance(node, ast.Name):
            if node.id.startswith("__"):
                return False
            if isinstance(node.ctx, ast.Store):
                local.add(node.id)
    used = {n.id for n in ast.walk(fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    return used <= local | set(names) | {"range", "len", "abs", "float", "complex", "int"}


def _load(path: Path, key: str, nargs: int):
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
        source, names = entry["source"], entry["names"]
        if entry.get("key") != key or entry.get("sha256") != hashlib.sha256(source.encode()).hexdigest():
            return None
        if not _safe(source, names, nargs):
            return None
        ns = _namespace(names)
        if ns is None:
            return None
        exec(compile(source, f"<numkin kernel {key[:12]}>", "exec"), ns)  # noqa: S102 - checked above
        return ns[entry["name"]]
    except (OSError, ValueError, KeyError, TypeError, SyntaxError, NameError):
        return None


def _store(path: Path, key: str, f, module) -> None:
    try:
        source = inspect.getsource(f)
    except (OSError, TypeError):
        return
    names = {}
    for name in f.__code__.co_names:
        value = f.__globals__.get(name)
        where = _resolve(name, value, module)
        if where is None:
            if name in ("range", "len", "abs", "float", "complex", "int"):
                continue
            return  # a helper numkin cannot rebuild without sympy: not cached
        names[name] = where
    if not _safe(source, names, f.__code__.co_argcount):
        return
    entry = {"key": key, "name": f.__name__, "source": source, "names": names,
             "sha256": hashlib.sha256(source.encode()).hexdigest(), "versions": _versions()}
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            json.dump(entry, out)
        os.replace(tmp, path)
    except OSError:
        try:
            os.unlink(tmp)
        except (OSError, UnboundLocalError):
            pass


def cached_lambdify(exprs: tuple, args: tuple, modules: str, cse: bool):
    """``sympy.lambdify(args, list(exprs), modules=modules, cse=cse)``, through the disk cache.

    Examples
    --------
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> f = cached_lambdify((sp.cos(x) ** 2 + sp.sin(x) ** 2,), (x,), "math", True)
    >>> round(f(0.3)[0], 12)
    1.0
    """
    import sympy as sp

    folder = cache_dir()
    symbols = set(args).union(*(sp.sympify(e).free_symbols for e in exprs))
    if folder is None or any(isinstance(s, sp.Dummy) for s in symbols):  # a Dummy's name differs every run
        return sp.lambdify(args, list(exprs), modules=modules, cse=cse)
    key = _key(exprs, args, modules, cse)
    path = folder / f"{key}.json"
    f = _load(path, key, len(args)) if path.exists() else None
    if f is None:
        f = sp.lambdify(args, list(exprs), modules=modules, cse=cse)
        _store(path, key, f, math if modules == "math" else np)
    return f

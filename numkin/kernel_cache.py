"""A disk cache of generated kernels: the code ``sympy.lambdify`` writes, kept between runs.

Three kinds of entry share one folder, each a small JSON file:

* a **kernel**: one generated function, keyed by the expressions' structure
  (``sympy.srepr``), its arguments, the target module (``numpy`` or
  ``math``) and whether common subexpressions were eliminated;
* a **generated source**: a function numkin writes itself from expressions
  (the fused rates of :mod:`numkin.rates_kernel`, :func:`cached_source`),
  keyed by the expressions, their arguments, what it is, and a digest of the
  modules that write code;
* a **bundle**: everything a mechanism compiles to, keyed without sympy by
  what it is built from (a ready-made linkage's name and the source of its
  module, or a scene's loop and point expressions as written), together with
  what a sweep, the derivatives and a drawing need to know about it (names of
  the unknowns, angles, loops and parameters, the Jacobian's zero pattern,
  the length symbols). A bundle that is found lets
  :meth:`numkin.cached_model.CachedModel.from_model` build the mechanism without importing
  sympy; its sympy expressions are derived only when someone asks for them.

Both keys also hold the versions of numkin, sympy, numpy and Python and a
digest of the modules that derive the code; a new version of any of them
misses the cache. Only code whose every global name is a function or
constant of numpy or math is kept. Entries are written to a temporary file
and renamed into place (atomic: concurrent runs never see half an entry); on
reading, the checksum, the key and the shape of the code (plain functions,
no imports, no attribute access, only the recorded global names) are
checked, and an entry that fails any check is rebuilt, never trusted. A
bundle's code is parsed and compiled once per process (one ``compile`` for
all of its functions).

The folder is the user's cache folder (``platformdirs.user_cache_dir``, else
``$XDG_CACHE_HOME`` or ``~/.cache``) under ``numkin/kernels``; the
environment variable ``NUMKIN_CACHE_DIR`` names another one, and
``NUMKIN_CACHE_DIR=off`` turns the cache off. A folder that cannot be
written only costs the cache.
"""

from __future__ import annotations

import ast
import hashlib
import json
import math
import os
import re
import sys
import tempfile
from pathlib import Path

import numpy as np

__all__ = ["cache_dir", "cached_lambdify", "cached_source", "kernel_from_source", "bundle_key", "load_bundle",
           "store_bundle", "ENV_VAR"]

#: Environment variable naming the cache folder (``off`` disables the cache).
ENV_VAR = "NUMKIN_CACHE_DIR"
_FORMAT = 4
#: Built-in names generated code may use.
_BUILTINS = frozenset({"range", "len", "abs", "float", "complex", "int"})
#: Modules of numkin whose code decides what a mechanism compiles to (their digest is part of a bundle's key).
_DERIVING = ("compiled.py", "loops.py", "mechanism.py", "kernel_cache.py", "assemble.py", "rates_kernel.py")
#: Bundles loaded in this process: path -> (model, functions).
_BUNDLES: dict = {}


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


def _sympy_version() -> str:
    """sympy's version, read from its release file when sympy is not imported (importing it costs 0.3 s)."""
    if "sympy" in sys.modules:
        return sys.modules["sympy"].__version__
    import importlib.util

    try:
        spec = importlib.util.find_spec("sympy")
        text = Path(spec.origin).with_name("release.py").read_text(encoding="utf-8")
    except (AttributeError, ImportError, OSError, TypeError, ValueError):
        return "unknown"
    found = re.search(r"__version__\s*=\s*['\"]([^'\"]+)", text)
    return found.group(1) if found else "unknown"


def _versions() -> str:
    from . import __version__

    return f"numkin {__version__}; sympy {_sympy_version()}; numpy {np.__version__}; python {sys.version_info[:3]}"


def _key(exprs, args, modules, cse) -> str:
    import sympy as sp

    text = "\n".join([f"format {_FORMAT}", _versions(), modules, str(bool(cse)), sp.srepr(tuple(args)),
                      sp.srepr(tuple(exprs))])
    return hashlib.sha256(text.encode()).hexdigest()


def bundle_key(kind: str, text: str) -> str:
    """The key of a bundle: ``kind`` and ``text`` (what the mechanism is built from), the versions and
    a digest of the modules that derive the code; no sympy needed.

    Examples
    --------
    >>> len(bundle_key("linkage four_bar", "source of the module"))
    64
    >>> bundle_key("a", "x") == bundle_key("a", "y")
    False
    """
    text = "\n".join([f"bundle format {_FORMAT}", _versions(), _deriving_digest(), kind, text])
    return hashlib.sha256(text.encode()).hexdigest()


def _deriving_digest() -> str:
    """sha256 of the modules that derive the code (:data:`_DERIVING`)."""
    digest = hashlib.sha256()
    here = Path(__file__).parent
    for name in _DERIVING:
        try:
            digest.update((here / name).read_bytes())
        except OSError:
            digest.update(name.encode())
    return digest.hexdigest()


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


def _safe_function(fn, names, nargs: int) -> bool:
    """One plain function: no imports, no attribute access, no dunder names, only the recorded globals."""
    if not isinstance(fn, ast.FunctionDef) or len(fn.args.args) != nargs or fn.decorator_list:
        return False
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
    return used <= local | set(names) | _BUILTINS


def _safe(source: str, names: dict, nargs: int) -> bool:
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return False
    return len(tree.body) == 1 and _safe_function(tree.body[0], names, nargs)


def _write(path: Path, entry: dict) -> None:
    """Write an entry atomically (a temporary file renamed into place); a failure only costs the cache."""
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            json.dump(entry, out)
        os.replace(tmp, path)
    except OSError:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass


def _read(path: Path, key: str) -> dict | None:
    """The entry at ``path`` if its key and checksum hold, else None."""
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
        source = entry["source"]
        if entry.get("key") != key or entry.get("sha256") != _checksum(entry):
            return None
        return entry if isinstance(source, str) else None
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _checksum(entry: dict) -> str:
    """sha256 of an entry's code and, for a bundle, of everything else it records."""
    extra = {k: entry.get(k) for k in ("names", "kernels", "model")} if "model" in entry else {}
    text = entry["source"] + (json.dumps(extra, sort_keys=True) if extra else "")
    return hashlib.sha256(text.encode()).hexdigest()


def _load(path: Path, key: str, nargs: int):
    entry = _read(path, key)
    if entry is None:
        return None
    try:
        return _checked_function(entry["source"], entry["names"], nargs, entry["name"], entry.get("module", "numpy"),
                                 f"<numkin kernel {key[:12]}>")
    except (ValueError, KeyError, TypeError, SyntaxError, NameError):
        return None


def _checked_function(source: str, names: dict, nargs: int, name: str, module: str, label: str):
    """The function ``name`` that ``source`` defines, its globals ``names``, carrying what keeps it as
    ``f.numkin_kernel``; None if the code's shape fails a check (see :func:`_safe`)."""
    if not _safe(source, names, nargs):
        return None
    ns = _namespace(names)
    if ns is None:
        return None
    exec(compile(source, label, "exec"), ns)  # noqa: S102 - checked above
    f = ns[name]
    f.numkin_kernel = {"name": name, "source": source, "names": names, "nargs": nargs, "module": module}
    return f


def _kernel_entry(f, module) -> dict | None:
    """What keeps a generated function: its source, global names and arity; None if it cannot be kept."""
    import inspect

    try:
        source = inspect.getsource(f)
    except (OSError, TypeError):
        return None
    names = {}
    for name in f.__code__.co_names:
        value = f.__globals__.get(name)
        where = _resolve(name, value, module)
        if where is None:
            if name in _BUILTINS:
                continue
            return None  # a helper numkin cannot rebuild without sympy: not kept
        names[name] = where
    if not _safe(source, names, f.__code__.co_argcount):
        return None
    return {"name": f.__name__, "source": source, "names": names, "nargs": f.__code__.co_argcount,
            "module": module.__name__}


def cached_lambdify(exprs: tuple, args: tuple, modules: str, cse: bool):
    """``sympy.lambdify(args, list(exprs), modules=modules, cse=cse)``, through the disk cache.

    A function that can be kept carries what keeps it as ``f.numkin_kernel``
    (for bundles).

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
        entry = _kernel_entry(f, math if modules == "math" else np)
        if entry is not None:
            f.numkin_kernel = entry
            _write(path, {"key": key, **{k: entry[k] for k in ("name", "source", "names", "module")},
                          "sha256": hashlib.sha256(entry["source"].encode()).hexdigest(), "versions": _versions()})
    return f


def kernel_from_source(source: str, nargs: int, module: str = "numpy"):
    r"""The one function generated code ``source`` defines, its global names taken from ``module``
    (``"numpy"`` or ``"math"``), carrying what keeps it as ``f.numkin_kernel``; None if the code is not
    of the shape the cache keeps (see the module's notes) or names something ``module`` lacks.

    Examples
    --------
    >>> f = kernel_from_source("def f(x):\n    return cos(x) ** 2 + sin(x) ** 2\n", 1)
    >>> round(float(f(0.3)), 12), sorted(f.numkin_kernel["names"])
    (1.0, ['cos', 'sin'])
    """
    mod = {"numpy": np, "math": math}.get(module)
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return None
    if mod is None or len(tree.body) != 1 or not isinstance(tree.body[0], ast.FunctionDef):
        return None
    fn = tree.body[0]
    local = {a.arg for a in fn.args.args}
    local |= {n.id for n in ast.walk(fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
    names = {}
    for node in ast.walk(fn):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in local | _BUILTINS:
            where = _resolve(node.id, getattr(mod, node.id, None), mod)
            if where is None:
                return None
            names[node.id] = where
    return _checked_function(source, names, nargs, fn.name, module, f"<numkin kernel {fn.name}>")


def cached_source(exprs: tuple, args: tuple, kind: str, nargs: int, build):
    """A function generated from ``exprs`` in ``args`` by ``build() -> source or None``, through the disk cache.

    ``kind`` names the generator and whatever else the code depends on (it is
    part of the key with ``exprs``, ``args`` and a digest of the modules that
    generate code, so a changed generator misses the cache). Returns
    :func:`kernel_from_source` of the source, or None if ``build`` gives none
    or the code cannot be kept. An entry is checked as every kernel's is; one
    that fails a check is rebuilt.
    """
    import sympy as sp

    folder = cache_dir()
    symbols = set(args).union(*(sp.sympify(e).free_symbols for e in exprs))
    if folder is None or any(isinstance(s, sp.Dummy) for s in symbols):
        source = build()
        return None if source is None else kernel_from_source(source, nargs)
    key = _key(exprs, args, f"source {kind} {_deriving_digest()}", False)  # a new generator: a new key
    path = folder / f"{key}.json"
    entry = _read(path, key) if path.exists() else None
    if entry is not None and entry.get("source") is not None:
        f = kernel_from_source(entry["source"], nargs)
        if f is not None and entry.get("names") == f.numkin_kernel["names"]:
            return f
    source = build()
    f = None if source is None else kernel_from_source(source, nargs)
    if f is not None:
        kernel = f.numkin_kernel
        _write(path, {"key": key, **{k: kernel[k] for k in ("name", "source", "names", "module")},
                      "sha256": hashlib.sha256(kernel["source"].encode()).hexdigest(), "versions": _versions()})
    return f


# ------------------------------------------------------------------------ bundles
def _bundle_path(key: str) -> Path | None:
    folder = cache_dir()
    return None if folder is None else folder / f"{key}.json"


def _hex(key: str) -> str:
    """A key as a file name: a key of :func:`bundle_key` as it is, any other text hashed."""
    return key if re.fullmatch(r"[0-9a-f]{64}", key) else hashlib.sha256(key.encode()).hexdigest()


def store_bundle(key: str, model: dict, kernels: list) -> None:
    """Keep a mechanism's description ``model`` (JSON data) and its generated functions ``kernels``
    (``f.numkin_kernel`` entries, referred to by position in ``model``) under ``key``.

    Their sources are written as one module, function ``k`` renamed ``_numkin_k<k>``.
    """
    key = _hex(key)
    path = _bundle_path(key)
    if path is None:
        return
    sources, table, names = [], [], {"numpy": {}, "math": {}}
    for k, kernel in enumerate(kernels):
        group = names.get(kernel["module"])
        head = f"def {kernel['name']}("
        if group is None or not kernel["source"].startswith(head):
            return
        for name, where in kernel["names"].items():
            if group.setdefault(name, where) != where:
                return
        sources.append(kernel["source"].replace(head, f"def _numkin_k{k}(", 1))
        table.append([kernel["module"], kernel["nargs"]])
    entry = {"key": key, "kind": "bundle", "model": model, "kernels": table, "names": names,
             "source": "\n".join(sources), "versions": _versions()}
    entry["sha256"] = _checksum(entry)
    _write(path, entry)
    _BUNDLES.pop(path, None)


def _bundle_functions(key: str, entry: dict) -> list | None:
    """The functions of a bundle entry, after checking the shape of its code; None if any check fails."""
    table, names = entry["kernels"], entry["names"]
    tree = ast.parse(entry["source"])
    if len(tree.body) != len(table):
        return None
    for k, (fn, (module, nargs)) in enumerate(zip(tree.body, table)):
        if module not in names or not isinstance(fn, ast.FunctionDef) or fn.name != f"_numkin_k{k}":
            return None
        if not _safe_function(fn, names[module], nargs):
            return None
    code = compile(tree, f"<numkin kernels {key[:12]}>", "exec")
    spaces = {}
    for module in {module for module, _ in table}:
        ns = _namespace(names[module])
        if ns is None:
            return None
        exec(code, ns)  # noqa: S102 - checked above
        spaces[module] = ns
    functions = []
    lines = entry["source"].splitlines(keepends=True)
    for k, (fn, (module, nargs)) in enumerate(zip(tree.body, table)):
        f = spaces[module][f"_numkin_k{k}"]
        used = {n.id for n in ast.walk(fn) if isinstance(n, ast.Name)}
        f.numkin_kernel = {"name": fn.name, "source": "".join(lines[fn.lineno - 1 : fn.end_lineno]), "nargs": nargs,
                           "names": {n: w for n, w in names[module].items() if n in used}, "module": module}
        functions.append(f)
    return functions


def load_bundle(key: str):
    """``(model, functions)`` kept under ``key`` (see :func:`store_bundle`), or None.

    An entry whose key, checksum or code shape is wrong is ignored (and so
    rebuilt by the caller). Loaded once per process.
    """
    key = _hex(key)
    path = _bundle_path(key)
    if path in _BUNDLES:
        return _BUNDLES[path]
    if path is None or not path.exists():
        return None
    entry = _read(path, key)
    try:
        if entry is None or entry.get("kind") != "bundle" or not isinstance(entry.get("model"), dict):
            return None
        functions = _bundle_functions(key, entry)
    except (ValueError, KeyError, TypeError, SyntaxError, NameError, RecursionError):
        return None
    if functions is None:
        return None
    _BUNDLES[path] = (entry["model"], functions)
    return _BUNDLES[path]

"""Build-time helpers of the numkin documentation (a local Sphinx extension).

* :func:`sync_lessons` copies the lessons ``notebooks/0*.py`` into the
  documentation tree, where myst-nb reads and executes them;
* :func:`build_gallery` draws every built-in figure with ``numkin figures --all``
  and writes the gallery page;
* :class:`ApiIndex` tells the autosummary templates where each public object is
  documented: once, under the shortest public module path that exports it;
* :func:`setup` makes a change of numkin's code re-read every page, and points
  the README's links at the pages that hold the same documents.
"""

from __future__ import annotations

import hashlib
import importlib
import inspect
import logging
import os
import pkgutil
import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

from docutils import nodes
from docutils.utils import get_source_line
from sphinx.util import logging as sphinx_logging

LESSON_SUFFIX = ".lesson.py"


# ------------------------------------------------------------------------ sources
def source_hash(package_dir: Path) -> str:
    """A digest of every file of the package (code, scenes, style)."""
    digest = hashlib.sha256()
    for path in sorted(p for p in Path(package_dir).rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        digest.update(str(path.relative_to(package_dir)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _write_if_changed(path: Path, data: bytes) -> None:
    """Write `data` unless the file already holds it (Sphinx then sees no change)."""
    if not path.exists() or path.read_bytes() != data:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)


# ------------------------------------------------------------------------ lessons
def sync_lessons(notebooks: Path, target: Path) -> list[Path]:
    """Copy every ``notebooks/0*.py`` lesson to ``target/<name>.lesson.py``; drop stale copies."""
    lessons = sorted(Path(notebooks).glob("0*.py"))
    wanted = {target / (p.stem + LESSON_SUFFIX): p for p in lessons}
    for path, source in wanted.items():
        _write_if_changed(path, source.read_bytes())
    for path in target.glob("*" + LESSON_SUFFIX):
        if path not in wanted:
            path.unlink()
    return list(wanted)


# ------------------------------------------------------------------------ gallery
def _figure_caption(stem: str) -> str:
    """The caption of a gallery figure: :func:`numkin.figures.caption` (what the figure draws) and its file."""
    from numkin.figures import caption

    try:
        return f"{caption(stem)} (``{stem}``)"
    except ValueError:
        return f"``{stem}``"


def _run(*args: str, cwd: Path | None = None) -> str:
    env = {**os.environ, "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, "-m", "numkin", *args], capture_output=True, text=True, env=env, cwd=cwd)
    if done.returncode != 0:
        raise RuntimeError(f"numkin {' '.join(args)} failed (exit {done.returncode}):\n{done.stderr}")
    return done.stdout


def build_gallery(target: Path, stamp: str) -> None:
    """Draw every figure of every built-in scene into ``target/figures`` and write ``target/index.md``.

    Skipped when ``target`` was made from the same numkin code (`stamp`), since
    the figures are deterministic.
    """
    target = Path(target)
    stamp += hashlib.sha256(Path(__file__).read_bytes()).hexdigest()[:16]  # and this page's layout
    stamp_file = target / ".numkin-source"
    if stamp_file.exists() and stamp_file.read_text() == stamp and (target / "index.md").exists():
        return
    scenes = {}
    for line in _run("scenes").splitlines():
        name, _, description = line.partition("  ")
        if name.strip():
            scenes[name.strip()] = description.strip()
    with tempfile.TemporaryDirectory() as tmp:
        written = [Path(line.strip()) for line in _run("figures", "--all", "--out", tmp, "--formats", "png").splitlines()
                   if line.strip().endswith(".png")]
        figures = target / "figures"
        if figures.exists():
            shutil.rmtree(figures)
        entries: dict[str, list[str]] = {}
        for path in written:
            rel = path.relative_to(tmp)
            (figures / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, figures / rel)
            entries.setdefault(rel.parts[0], []).append(rel.as_posix())
    lines = [
        "# Gallery",
        "",
        "Every figure of every built-in scene, as `numkin figures --all --out figures/` draws it",
        "(drawn anew for this page; the same command gives the same bytes on every run).",
        "Each scene's figures are the ones its `[output] figures` list asks for; the scene files",
        "are described on the [scene file](../scene.rst) page.",
        "",
    ]
    for scene, files in entries.items():
        lines += [f"## `{scene}`", "", scenes.get(scene, ""), "", f"`numkin figures {scene} --out figures/`", ""]
        lines += ["::::{container} numkin-gallery", ""]
        for rel in files:
            stem = Path(rel).stem
            lines += [
                f":::{{figure}} figures/{rel}",
                f":alt: {scene}: {stem}",
                ":width: 100%",
                "",
                _figure_caption(stem),
                ":::",
                "",
            ]
        lines += ["::::", ""]
    missing = [s for s in scenes if s not in entries]
    if missing:
        lines += ["## Scenes without figures", "",
                  ", ".join(f"`{s}`" for s in missing) + " (they ask for none; `numkin run` prints their results).", ""]
    _write_if_changed(target / "index.md", "\n".join(lines).encode())
    stamp_file.write_text(stamp)


# ------------------------------------------------------------------------ API
def _children(fullname: str, names) -> list[str]:
    """Those of the module names `names` directly below package `fullname`, sorted."""
    depth = fullname.count(".") + 1
    return sorted(m for m in names if m.startswith(fullname + ".") and m.count(".") == depth)


class ApiIndex:
    """Where each public object of a package is documented.

    Every public module (no part of its name starting with ``_``) is walked;
    a class or function listed in the ``__all__`` of several modules is
    documented once, under the shallowest of them (ties: the module that
    defines it), unless that name is also a module's (``numkin.newton``). The
    other modules list it with a link to that page. A module hidden by a
    function of its own name gets a page ``<module>-module``
    (:func:`write_shadowed_pages`). Passed to the autosummary templates as
    ``api``.
    """

    def __init__(self, package: str):
        self.package = package
        self._modules: dict[str, object] | None = None
        self._canonical: dict[int, str] = {}
        self.shadowed: list[str] = []

    def __getstate__(self):  # modules do not pickle; the index is rebuilt on demand
        return {"package": self.package, "_modules": None, "_canonical": {}, "shadowed": []}

    # Sphinx compares configuration values between builds: equal when of the same
    # package, so that a rebuild does not re-read every page for this value.
    def __eq__(self, other) -> bool:
        return isinstance(other, ApiIndex) and other.package == self.package

    def __hash__(self) -> int:
        return hash(("ApiIndex", self.package))

    def __repr__(self) -> str:
        return f"ApiIndex({self.package!r})"

    # -- index
    def _index(self) -> dict[str, object]:
        if self._modules is not None:
            return self._modules
        root = importlib.import_module(self.package)
        modules = {self.package: root}
        for info in pkgutil.walk_packages(root.__path__, self.package + ".", onerror=lambda name: None):
            if any(part.startswith("_") for part in info.name.split(".")):
                continue
            module = importlib.import_module(info.name)
            parent, _, last = info.name.rpartition(".")
            if getattr(modules.get(parent), last, module) is not module:
                # shadowed: the package exports a function of the same name
                # (numkin.newton), which is documented under that name instead
                self.shadowed.append(info.name)
                continue
            modules[info.name] = module
        exporters: dict[int, list[tuple[str, str]]] = {}
        objects: dict[int, object] = {}
        for modname, module in modules.items():
            for name in getattr(module, "__all__", ()):
                obj = getattr(module, name, None)
                if inspect.isclass(obj) or inspect.isfunction(obj):
                    exporters.setdefault(id(obj), []).append((modname, name))
                    objects[id(obj)] = obj
        for key, places in exporters.items():
            defining = getattr(objects[key], "__module__", "")

            def rank(place, defining=defining):
                modname, name = place
                full = f"{modname}.{name}"
                return (full in modules, modname.count("."), modname != defining, full)

            modname, name = min(places, key=rank)
            self._canonical[key] = f"{modname}.{name}"
        self._modules = modules
        return modules

    def canonical(self, obj) -> str | None:
        """The full name under which `obj` is documented (None: not a listed class or function)."""
        self._index()
        return self._canonical.get(id(obj))

    # -- for the templates
    def submodules(self, fullname: str) -> list[str]:
        """The public modules directly below package `fullname`."""
        return _children(fullname, self._index())

    def relative(self, fullname: str, names) -> list[str]:
        """`names` (full names) as autosummary wants them on the page of module `fullname`."""
        prefix = fullname + "."
        return [n[len(prefix):] if n.startswith(prefix) else n for n in names]

    def here(self, fullname: str, names) -> list[str]:
        """Those of `names` (members of module `fullname`) documented on its page."""
        module = self._index().get(fullname)
        out = []
        for name in names:
            canonical = self.canonical(getattr(module, name, None))
            if canonical is None or canonical == f"{fullname}.{name}":
                out.append(name)
        return out

    def elsewhere(self, fullname: str, names) -> list[str]:
        """Full names of those of `names` documented on another page."""
        module = self._index().get(fullname)
        out = []
        for name in names:
            canonical = self.canonical(getattr(module, name, None))
            if canonical is not None and canonical != f"{fullname}.{name}":
                out.append(canonical)
        return out

    def data(self, fullname: str) -> list[str]:
        """Names in the ``__all__`` of module `fullname` that are neither modules, classes nor functions."""
        module = self._index().get(fullname)
        out = []
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name, None)
            if not (inspect.ismodule(obj) or inspect.isclass(obj) or inspect.isfunction(obj) or callable(obj)):
                out.append(name)
        return out

    def documented_name(self, target: str) -> str | None:
        """The name under which the object a full dotted name reaches is documented (None: not one of ours)."""
        parts = target.split(".")
        if parts[0] != self.package:
            return None
        for k in range(len(parts) - 1, 0, -1):
            try:
                obj = importlib.import_module(".".join(parts[:k]))
            except ImportError:
                continue
            rest = parts[k:]
            for i, attr in enumerate(rest):
                obj = getattr(obj, attr, None)
                canonical = self.canonical(obj)
                if canonical:
                    return ".".join([canonical, *rest[i + 1:]])
                if obj is None:
                    return None
            return None
        return None

    def shadowed_below(self, fullname: str) -> list[str]:
        """The modules directly below package `fullname` that a function of the same name hides
        (``numkin.newton``): each has its own page, ``<module>-module`` (:func:`write_shadowed_pages`)."""
        self._index()
        return _children(fullname, self.shadowed)

    def filename_map(self) -> dict[str, str]:
        """Page names for objects whose name differs from a module's only in case (``numkin.Sweep``)."""
        modules = {m.lower() for m in self._index()}
        self._index()
        out = {}
        for full in self._canonical.values():
            if full.lower() in modules:
                out[full] = f"{full}-object"
        return out


def write_shadowed_pages(target: Path, api: ApiIndex) -> list[str]:
    """A page ``<module>-module.rst`` in `target` for every module a function of the same name hides.

    ``numkin.newton`` is both a function and a module; autosummary reaches the
    function by that name, so the module's docstring and its other public
    names are written here: the docstring, an autosummary of the classes and
    functions documented on no other page, links to those that are, and the
    data. Returns the modules.
    """
    import ast

    api._index()
    target = Path(target)
    for name in api.shadowed:
        module = sys.modules[name]
        assigned = {t.id for node in ast.parse(inspect.getsource(module)).body
                    if isinstance(node, (ast.Assign, ast.AnnAssign))
                    for t in (node.targets if isinstance(node, ast.Assign) else [node.target])
                    if isinstance(t, ast.Name)}
        own, other, data = [], [], []
        for member in getattr(module, "__all__", ()):
            obj = getattr(module, member, None)
            if not (inspect.isclass(obj) or inspect.isfunction(obj)):
                if member in assigned:  # (data imported from another module is documented there)
                    data.append(member)
                continue
            canonical = api.canonical(obj)
            if canonical is None:
                own.append(member)
            elif canonical not in api.shadowed:  # (the function of the module's own name has its page)
                other.append(canonical)
        title = f"{name} (module)"
        lines = [title, "=" * len(title), "", f".. automodule:: {name}", "   :no-members:", "   :no-index:", "",
                 f".. currentmodule:: {name}", ""]
        parent, _, last = name.rpartition(".")
        if api.canonical(getattr(sys.modules[parent], last, None)):
            lines += [f"The function of the same name is :func:`{name}`.", ""]
        if own:
            lines += [".. rubric:: Classes and functions", "", ".. autosummary::", "   :nosignatures:",
                      "   :toctree:", "", *[f"   {m}" for m in own], ""]
        if other:
            lines += [".. rubric:: Also exported here", "", ".. autosummary::", "   :nosignatures:", "",
                      *[f"   ~{m}" for m in other], ""]
        if data:
            lines += [".. rubric:: Data", ""]
            for member in data:
                lines += [f".. autodata:: {member}", "   :no-value:", ""]
        _write_if_changed(target / f"{name}-module.rst", "\n".join(lines).encode())
    return list(api.shadowed)


# ------------------------------------------------------------------------ CLI
def _rst_help(text: str | None) -> str | None:
    """argparse help laid out for a terminal, as reStructuredText.

    ``numkin``'s descriptions and epilogs are pre-formatted: a line ending with
    ``:`` followed by indented lines (``examples:``) becomes a literal block.
    """
    if not text:
        return text
    lines = text.split("\n")
    out = []
    for k, line in enumerate(lines):
        following = lines[k + 1] if k + 1 < len(lines) else ""
        if line.rstrip().endswith(":") and not line.startswith(" ") and following.startswith("  "):
            out += [line.rstrip() + ":", ""]
        else:
            out.append(line)
    return "\n".join(out)


def cli_parser():
    """``numkin.cli.build_parser()`` with its help texts as reStructuredText (for sphinx-argparse)."""
    import argparse

    from numkin.cli import build_parser

    parser = build_parser()
    todo = [parser]
    while todo:
        p = todo.pop()
        p.description, p.epilog = _rst_help(p.description), _rst_help(p.epilog)
        for action in p._actions:
            if isinstance(action, argparse._SubParsersAction):
                todo += list(action.choices.values())
    return parser


# ------------------------------------------------------------------------ Sphinx
_README_LINKS = {
    "](notebooks/README.md)": "](lessons/index.md)",
    "](assignments/README.md)": "](assignments.md)",
}


def _include_read(app, relative_path, parent_docname, content) -> None:
    """The README's links to other folders' READMEs point at the pages that include them."""
    text = content[0]
    for old, new in _README_LINKS.items():
        text = text.replace(old, new)
    content[0] = text


class _Links(HTMLParser):
    """The ids a page defines and the local links it makes."""

    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()
        self.links: list[str] = []
        self._last_tag = ""

    def handle_starttag(self, tag, attrs) -> None:
        attrs = dict(attrs)
        if "problematic" in (attrs.get("class") or "").split() and self._last_tag == "a" and self.links:
            # docutils' link from a markup error in a docstring to its message,
            # which is listed among the docstring defects instead
            self.links.pop()
        self._last_tag = tag
        for key in ("id", "name"):
            if attrs.get(key):
                self.ids.add(attrs[key])
        for key in ("href", "src"):
            value = attrs.get(key)
            if value and not urlsplit(value).scheme and not value.startswith("//"):
                self.links.append(value)


def broken_links(html_dir: Path) -> list[str]:
    """Every link between the built pages whose file or ``#anchor`` does not exist."""
    html_dir = Path(html_dir)
    pages: dict[Path, _Links] = {}
    for path in sorted(html_dir.rglob("*.html")):
        if "_static" in path.relative_to(html_dir).parts:
            continue
        parser = _Links()
        parser.feed(path.read_text(encoding="utf-8", errors="replace"))
        pages[path.resolve()] = parser
    broken = []
    for page, parser in pages.items():
        for link in parser.links:
            parts = urlsplit(link)
            target = (page.parent / unquote(parts.path)).resolve() if parts.path else page
            if target.is_dir():
                target = target / "index.html"
            where = page.relative_to(html_dir.resolve())
            if not target.exists():
                broken.append(f"{where}: {link} (no such file)")
            elif parts.fragment and target in pages and unquote(parts.fragment) not in pages[target].ids:
                broken.append(f"{where}: {link} (no such anchor)")
    return sorted(set(broken))


def _check_links(app, exception) -> None:
    """After an HTML build: a warning (an error under -W) for each broken internal link."""
    if exception is None and app.builder.format == "html":
        log = sphinx_logging.getLogger(__name__)
        for text in broken_links(Path(app.outdir)):
            log.warning(f"broken internal link: {text}", type="numkin", subtype="link")


def _resolve_short_name(app, env, node, contnode):
    """A Python reference written with a short name (``Mechanism.sweep``) resolves to the
    documented object of the role's kind whose full name ends with it, wherever the
    docstring is; among several, the one nearest the docstring's module."""
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "").lstrip("~.")
    if not target:
        return None
    domain = env.get_domain("py")
    api = app.config.autosummary_context.get("api")
    moved = api.documented_name(target) if isinstance(api, ApiIndex) else None
    if moved and moved in domain.objects and not domain.objects[moved].aliased:
        # a full name through a re-export (numkin.scene.load_scene): the page it is documented on
        entry = domain.objects[moved]
        from sphinx.util.nodes import make_refnode

        return make_refnode(app.builder, node.get("refdoc", ""), entry.docname, entry.node_id, contnode, moved)
    kinds = set(domain.objtypes_for_role(node.get("reftype", "")) or ())
    found = {}
    for name, entry in domain.objects.items():
        if (name == target or name.endswith("." + target)) and not entry.aliased and (not kinds or entry.objtype in kinds):
            found[entry.node_id] = name
    if not found:
        return None
    context = (node.get("py:module") or "").split(".")

    def shared(name: str) -> int:
        parts = name.split(".")
        n = 0
        while n < min(len(parts), len(context)) and parts[n] == context[n]:
            n += 1
        return n

    best = max(map(shared, found.values()))
    nearest = [name for name in found.values() if shared(name) == best]
    if len(nearest) != 1:
        return None
    full = nearest[0]
    entry = domain.objects[full]
    from sphinx.util.nodes import make_refnode

    return make_refnode(app.builder, node.get("refdoc", ""), entry.docname, entry.node_id, contnode, full)


class DocstringDefects(logging.Filter):
    """Markup errors inside numkin's docstrings, printed as notes instead of failing ``-W`` on request.

    A docstring whose reStructuredText does not parse (an undefined
    ``|substitution|`` from an absolute value written ``|x|``, a malformed
    table) or that refers to a name documented nowhere is listed, with its
    place, after the build, instead of failing it, only when
    ``NUMKIN_DOCS_STRICT_DOCSTRINGS=0`` (to see them all at once while
    mending them). By default they fail the build, like every other warning
    and any problem in the pages of docs/ and in the lessons.
    """

    def __init__(self) -> None:
        super().__init__()
        self.found: list[str] = []

    def filter(self, record: logging.LogRecord) -> bool:
        location = getattr(record, "location", "") or ""
        if isinstance(location, nodes.Node):
            source, line = get_source_line(location)
            location = f"{source}:{line}"
        location = str(location)
        kind = getattr(record, "type", "")
        if kind in ("docutils", "ref") and ("docstring of" in location or "<autosummary>" in location):
            location = location.replace(os.getcwd() + os.sep, "")
            text = f"{location}: {record.getMessage()}".splitlines()[0]
            if text not in self.found:
                self.found.append(text)
            return False
        return True


def _report_defects(app, exception) -> None:
    defects = app.numkin_docstring_defects.found
    if defects:
        log = sphinx_logging.getLogger(__name__)
        log.info(f"\ndocstring defects ({len(defects)}; errors unless NUMKIN_DOCS_STRICT_DOCSTRINGS=0):")
        for text in defects:
            log.info(f"  {text}")


def setup(app):
    app.add_config_value("numkin_source_hash", "", "env", types=frozenset({str}))
    app.connect("include-read", _include_read)
    app.connect("build-finished", _check_links)
    app.connect("missing-reference", _resolve_short_name)
    if os.environ.get("NUMKIN_DOCS_STRICT_DOCSTRINGS", "1") in ("0", "no", "false"):
        app.numkin_docstring_defects = DocstringDefects()
        for handler in logging.getLogger(sphinx_logging.NAMESPACE).handlers:
            if isinstance(handler, sphinx_logging.WarningStreamHandler):
                handler.filters.insert(0, app.numkin_docstring_defects)
        app.connect("build-finished", _report_defects)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}

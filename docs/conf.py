"""Sphinx configuration of the numkin documentation.

Build (from the repository root)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

Generated at build time, never committed (see .gitignore):

* ``docs/lessons/*.lesson.py``: copies of ``notebooks/0*.py`` (jupytext percent
  sources), read and executed by myst-nb, so every lesson appears with its outputs;
* ``docs/gallery/``: every figure of every built-in scene, drawn by
  ``numkin figures --all``, and the page that shows them;
* ``docs/api/generated/``: the API pages, written by autosummary from the
  docstrings of every public module of the ``numkin`` package.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))
sys.path.insert(0, str(ROOT))

import numkin  # noqa: E402
import numkin_docs  # noqa: E402  (docs/_ext/numkin_docs.py)

# -- project -------------------------------------------------------------------
project = "numkin"
author = "the numkin authors"
copyright = "the numkin authors, MIT licence"
release = numkin.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "myst_nb",
    "sphinxarg.ext",
    "numkin_docs",
]

root_doc = "index"
templates_path = ["_templates"]
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints", "jupyter_execute"]
html_static_path = ["_static"]
html_css_files = ["numkin.css"]

# Every source file below docs/ is generated or written here: a change in
# numkin's code (docstrings, figures, lesson outputs) re-reads every page.
numkin_source_hash = numkin_docs.source_hash(ROOT / "numkin")

# API pages are written anew by autosummary on every build: none left from a module that moved.
shutil.rmtree(DOCS / "api" / "generated", ignore_errors=True)

# Lessons and gallery are generated before Sphinx looks for source files.
numkin_docs.sync_lessons(ROOT / "notebooks", DOCS / "lessons")
numkin_docs.build_gallery(DOCS / "gallery", numkin_source_hash)

# -- HTML ------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"numkin {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 7,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_sidebars = {page: [] for page in ("index", "gallery/index", "scene", "cli", "assignments")}
smartquotes_action = "qe"  # quotes and ellipses; "--out" stays two hyphens
highlight_language = "none"  # literal blocks in docstrings are TOML, shell or plain text; doctests are highlighted anyway
html_last_updated_fmt = None

# -- MathJax ---------------------------------------------------------------------
# Equations are typeset by MathJax in the browser. Where Debian's libjs-mathjax
# (MathJax 2) is installed, the files its SVG output needs (about 3 MB) are
# copied into the site (_static/mathjax), so the pages typeset their equations
# wherever they are served or opened, offline too (SVG output needs no web
# fonts); otherwise Sphinx's default (a CDN). NUMKIN_DOCS_MATHJAX overrides: "cdn"
# for the default, or the URL of a MathJax script. The build itself never needs MathJax.
_mathjax = os.environ.get("NUMKIN_DOCS_MATHJAX", "")
_debian_mathjax = Path("/usr/share/javascript/mathjax/MathJax.js")
#: The parts of MathJax 2 that the TeX-AMS-MML_SVG configuration loads.
_MATHJAX_FILES = ("MathJax.js", "config/TeX-AMS-MML_SVG.js", "jax/input/TeX", "jax/input/MathML", "jax/element",
                  "jax/output/SVG/config.js", "jax/output/SVG/jax.js", "jax/output/SVG/autoload",
                  "jax/output/SVG/fonts/TeX", "extensions")
_copy_mathjax = not _mathjax and _debian_mathjax.exists()
if _mathjax != "cdn" and (_mathjax or _debian_mathjax.exists()):
    _url = _mathjax or "mathjax/MathJax.js"  # relative: in the site's _static folder
    if "MathJax.js" in _url:  # MathJax 2
        mathjax_path = _url if "?" in _url else _url + "?config=TeX-AMS-MML_SVG"
        myst_update_mathjax = False  # myst's setting is MathJax 3's
        mathjax2_config = {"tex2jax": {"inlineMath": [["\\(", "\\)"]], "displayMath": [["\\[", "\\]"]],
                                       "processEscapes": True, "processEnvironments": True}}
    else:
        mathjax_path = _url

# -- API reference: autosummary + autodoc + numpydoc --------------------------------
autosummary_generate = True
autosummary_ignore_module_all = False  # a module's __all__ is its public interface
autosummary_imported_members = False
autosummary_context = {"api": numkin_docs.ApiIndex("numkin")}
autosummary_filename_map = autosummary_context["api"].filename_map()
# modules a function of the same name hides from autosummary (numkin.newton): pages of their own
numkin_docs.write_shadowed_pages(DOCS / "api" / "generated", autosummary_context["api"])
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "none"  # numpydoc sections carry the types
autodoc_preserve_defaults = True  # signatures show defaults as written: max_step=math.radians(30.0)
autodoc_mock_imports: list[str] = []
numpydoc_show_class_members = False  # members are documented on the class page itself
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set[str] = set()
numpydoc_xref_param_type = False
add_module_names = False

# -- lessons: myst-nb reads the jupytext sources and runs them ---------------------
nb_custom_formats = {".lesson.py": ["jupytext.reads", {"fmt": "py:percent"}]}
# "force": run every lesson when it is read; Sphinx re-reads a lesson only when it
# or numkin's code changed (numkin_source_hash), so a rebuild reuses the outputs.
# NUMKIN_DOCS_EXECUTE=off builds the lessons without outputs (a quick look at the text).
nb_execution_mode = os.environ.get("NUMKIN_DOCS_EXECUTE", "force")
nb_execution_timeout = 180  # seconds per cell (a lesson takes 10-30 s in all)
nb_execution_in_temp = True  # files a lesson writes go to a temporary folder
nb_execution_raise_on_error = True  # a failing cell (or assert) fails the build
nb_execution_show_tb = True
nb_merge_streams = True
nb_kernel_rgx_aliases = {".*": "python3"}
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

# -- cross references -----------------------------------------------------------
# Every reference to numkin's own objects must resolve (-n): a broken one in
# docs/ fails the build; one in a docstring is listed among the docstring
# defects (docs/_ext/numkin_docs.py). No network at build time, so no
# intersphinx: names of other libraries stay plain text.
nitpicky = True
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|pandas|matplotlib|sympy|scipy|mpmath|PIL|tqdm|time|math|fractions|dataclasses|argparse|pathlib|typing|collections)(\..*)?"),
]


def _copy_mathjax_files(app) -> None:
    """Copy the MathJax 2 files the pages load into the site's _static/mathjax (HTML builds), before the
    pages are written (and their links checked)."""
    if not _copy_mathjax or app.builder.format != "html":
        return
    root, dest = _debian_mathjax.parent, Path(app.outdir) / "_static" / "mathjax"
    for name in _MATHJAX_FILES:
        src = root / name
        if src.is_dir():
            shutil.copytree(src, dest / name, dirs_exist_ok=True)
        else:
            (dest / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dest / name)


def setup(app):
    app.connect("builder-inited", _copy_mathjax_files)

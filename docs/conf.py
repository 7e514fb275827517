"""Sphinx configuration of the hertz documentation.

Build: ``pip install -e ".[docs]"`` then
``sphinx-build -W --keep-going -b html docs docs/_build/html``.

Prose is MyST markdown; pages with ``{code-cell}`` blocks are MyST markdown notebooks
that myst-nb executes at every build (``nb_execution_mode = "force"``), so every number
and figure they show comes from code that ran; an error in a cell fails the build. The
API reference is autosummary over the public names, with numpydoc docstrings.

Intersphinx without network: the build machine and CI reach package registries only, so
intersphinx cannot download the projects' objects.inv. The inventories are local files,
docs/_inventories/*.inv, written by ``python docs/_inventories/make_inventories.py`` from
the list of objects these pages refer to, with each project's real documentation URL as
the base: links go to the published pages, the build needs no network, and a reference
to an object not in the list is a warning (an error under -W), so the list cannot rot
silently. Chosen over downloading at build time (impossible here) and over committing
the full downloaded inventories (cannot be fetched here, several MB, and would hide
references that do not exist). meshio publishes no Sphinx documentation: its entries
point to its README and source.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
try:
    import hertz
except ImportError:  # not installed: the checkout's, built in place (setup.py build_ext -i)
    sys.path.insert(0, str(ROOT))
    import hertz

project = "hertz"
author = "the hertz developers"
copyright = "2026, the hertz developers"  # noqa: A001
release = hertz.__version__
version = release

extensions = [
    "myst_nb",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}  # rst first: autosummary writes .rst
exclude_patterns = ["_build", "_inventories", "**.ipynb_checkpoints", "fem/*.md",
                    "speed_vs_error.md"]
root_doc = "index"

# MyST
myst_enable_extensions = ["colon_fence", "dollarmath", "deflist"]
myst_heading_anchors = 3

# myst-nb: execute every notebook page at every build, fail on any error.
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 60
nb_execution_show_tb = True
nb_merge_streams = True

# autodoc / autosummary / numpydoc
autosummary_generate = True
autosummary_imported_members = True
autodoc_typehints = "none"
autodoc_default_options = {"members": True, "inherited-members": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# intersphinx from local inventories (see the module docstring).
_INV = DOCS / "_inventories"
intersphinx_mapping = {
    "python": ("https://docs.python.org/3/", str(_INV / "python.inv")),
    "numpy": ("https://numpy.org/doc/stable/", str(_INV / "numpy.inv")),
    "scipy": ("https://docs.scipy.org/doc/scipy/", str(_INV / "scipy.inv")),
    "dask": ("https://docs.dask.org/en/stable/", str(_INV / "dask.inv")),
    "meshio": ("https://github.com/nschloe/meshio/", str(_INV / "meshio.inv")),
}
intersphinx_disabled_reftypes = ["*"]  # only explicit project:target references leave the site
intersphinx_timeout = 1

# The CalculiX how-to (howto/calculix.md) comes from another branch: where it is missing,
# its toctree entry is dropped (_drop_missing_calculix) and the tutorial's link to it is
# left out (an ``only:: calculix`` block).
HAVE_CALCULIX = (DOCS / "howto" / "calculix.md").exists()
if HAVE_CALCULIX:
    tags.add("calculix")  # noqa: F821  (Sphinx injects ``tags`` into conf.py)

html_theme = "furo"
html_title = f"hertz {release}"
html_static_path = []
html_show_sourcelink = False


_ABSOLUTE = re.compile(r"(?<![\\\w`])\|(?=[^\s|])([^|`]*?[^\s|\\])\|(?![\w`])")


def _escape_plain_math(app, what, name, obj, options, lines):
    """Docstrings write their math as plain text: absolute values ``|tau_yz|`` (which
    docutils reads as a substitution) and powers ``k'**2`` (after a quote, ``**`` would
    start bold text). Escape both."""
    for i, line in enumerate(lines):
        line = _ABSOLUTE.sub(r"\\|\1\\|", line)
        lines[i] = line.replace("'**", "'\\**")


_ONLY_CALCULIX = re.compile(r"^```\{only\} calculix\n.*?^```\n", re.M | re.S)


def _drop_missing_calculix(app, docname, source):
    if not HAVE_CALCULIX:
        if docname == "howto/index":
            source[0] = source[0].replace("\ncalculix\n", "\n")
        source[0] = _ONLY_CALCULIX.sub("", source[0])


def setup(app):
    app.connect("autodoc-process-docstring", _escape_plain_math)
    app.connect("source-read", _drop_missing_calculix)
